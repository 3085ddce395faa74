"""The Errata appendix is generated from textbook/: photolib.book.errata on a synthetic chapter file,
and on the real textbook/ (kinds erratum / transcription, grouping, pages, Markdown for MyST)."""

import re
import sys
import types
from collections import Counter

import pytest

from photolib.book import errata as er
from photolib.book.textbook import load_chapter, load_pages

CHAPTER = '''
chapter = 7
title = "Synthetic chapter"
title_original = "Синтетическая глава"
seed = "seed.txt"
lines = [1, 100]

[[example]]
id = "7.2-example"
section = "7.2"
lines = [10, 14]
title = "A synthetic example"
compute = "errata_fixture:right"
as_printed_compute = "errata_fixture:as_printed"
inputs = { a = 2.0 }

[[example.quantity]]
name = "good"
printed = "4,00"
value = 4.0
decimals = 2
unit = "m"
status = "reproduced"

[[example.quantity]]
name = "wrong"
printed = "1,73"
value = 1.73
decimals = 2
unit = "mm"
status = "erratum"
correct = 1.41
diagnosis = "square root of 3 instead of 2"
proof = "sympy sqrt(2)"
as_printed = true

[[example.quantity]]
name = "lost"
printed = "7,5"
value = 7.5
decimals = 1
status = "transcription"
correct = 2.5
diagnosis = "The OCR read the 2 as 7 (Z* and x_0 of the text survive; it costs $5)."
proof = "the text two lines below repeats 2,5"

[[example.quantity]]
name = "rounded"
printed = "0,333"
value = 0.333
decimals = 3
status = "input-rounding"
bound = 0.002
reason = "inputs printed to two decimals"

[[example.quantity]]
name = "missing"
printed = "9,9"
value = 9.9
decimals = 1
status = "not-reproducible"
reason = "the book omits the image coordinates"

[[example]]
id = "7.1-early"
section = "7.1"
lines = [3, 3]
title = "An earlier statement"
compute = "errata_fixture:right"
inputs = { a = 2.0 }

[[example.quantity]]
name = "sign"
printed = "-5"
value = -5.0
decimals = 0
status = "erratum"
correct = 5.0
diagnosis = "sign lost in the OCR"
proof = "test"

[[example.quantity]]
name = "twin1"
printed = "1,0"
value = 1.0
decimals = 1
status = "erratum"
correct = 3.0
diagnosis = "The book's program used the transposed rotation for every correlation of this table. The first gives 1."
proof = "test_twins"

[[example.quantity]]
name = "twin2"
printed = "2,0"
value = 2.0
decimals = 1
status = "erratum"
correct = 4.0
diagnosis = "The book's program used the transposed rotation for every correlation of this table. The second gives 2."
proof = "test_twins"

[[formula]]
id = "7.10-formula-ok"
section = "7.10"
lines = [50, 52]
equation = "(7.10.1)"
printed = "x = y"
status = "reproduced"
compute = "errata_fixture:formula_ok"

[[formula]]
id = "7.10-formula-bad"
section = "7.10"
lines = [60, 61]
equation = "(7.10.2)"
printed = "\\\\frac{1}{m} = \\\\frac{1}{H}"
status = "erratum"
correct = "\\\\frac{1}{m} = \\\\frac{f}{H}"
diagnosis = "f lost"
proof = "sympy"
compute = "errata_fixture:formula_bad"
'''


@pytest.fixture
def synthetic(tmp_path, monkeypatch):
    fixture = types.ModuleType("errata_fixture")
    fixture.right = lambda inputs: {"good": 4.0, "wrong": 2 ** 0.5, "lost": 2.5, "rounded": 0.3345, "missing": None,
                                    "sign": 5.0, "twin1": 3.0, "twin2": 4.0}
    fixture.as_printed = lambda inputs: {"wrong": 3 ** 0.5}
    fixture.formula_ok = lambda inputs: {"printed_equals_derived": True}
    fixture.formula_bad = lambda inputs: {"printed_equals_derived": False}
    monkeypatch.setitem(sys.modules, "errata_fixture", fixture)
    (tmp_path / "ch07.toml").write_text(CHAPTER, encoding="utf-8")
    monkeypatch.setenv("PHOTOLIB_TEXTBOOK", str(tmp_path))
    load_chapter.cache_clear()
    load_pages.cache_clear()
    yield fixture
    load_chapter.cache_clear()
    load_pages.cache_clear()


def test_every_erratum_is_listed_with_printed_and_correct(synthetic):
    records = er.errata()
    assert [(r.id, r.item) for r in records] == [
        ("7.1-early", "sign"), ("7.1-early", "twin1"), ("7.1-early", "twin2"), ("7.2-example", "wrong"),
        ("7.2-example", "lost"), ("7.10-formula-bad", "(7.10.2)")]   # sorted by §
    sign, _, _, wrong, lost, formula = records
    assert (sign.printed, sign.correct, sign.diagnosis, sign.lines) == ("-5", "5", "sign lost in the OCR", (3, 3))
    assert (wrong.printed, wrong.correct, wrong.unit, wrong.proof) == ("1,73", "1.41", "mm", "sympy sqrt(2)")
    assert wrong.as_printed is True and wrong.as_printed_value.startswith("1.73")
    assert sign.as_printed is None
    assert formula.kind == "formula" and formula.correct == "\\frac{1}{m} = \\frac{f}{H}"
    assert [r.status for r in records] == ["erratum"] * 4 + ["transcription", "erratum"]
    assert (lost.correct, lost.proof) == ("2.5", "the text two lines below repeats 2,5")
    assert all(r.chapter == 7 and r.where == f"§{r.section}" for r in records)   # no page anchors here
    assert [r.item for r in er.errata(statuses=("transcription",))] == ["lost"]
    with pytest.raises(er.InputError, match="statuses"):
        er.errata(statuses=("input-rounding",))


def test_as_printed_claim_is_recomputed(synthetic):
    synthetic.as_printed = lambda inputs: {"wrong": 1.9}        # no longer reproduces 1,73
    wrong = [r for r in er.errata() if r.item == "wrong"][0]
    assert wrong.as_printed is False
    assert [r for r in er.errata(recompute=False) if r.item == "wrong"][0].as_printed is True


def test_non_errata_are_not_listed(synthetic):
    items = {r.item for r in er.errata()}
    assert not items & {"good", "rounded", "missing", "(7.10.1)"}
    other = er.discrepancies()
    assert [(r.item, r.status) for r in other] == [("rounded", "input-rounding"), ("missing", "not-reproducible")]
    assert other[0].bound == 0.002 and "two decimals" in other[0].reason
    assert "omits" in other[1].reason


def test_markdown_contains_every_entry(synthetic):
    md = er.errata_markdown()
    assert "Chapter 7. Synthetic chapter (Синтетическая глава)" in md
    for text in ("§7.1", "§7.2", "§7.10", "1,73", "1.41 mm", "square root of 3 instead of 2", "-5",
                 "$\\frac{1}{m} = \\frac{f}{H}$", "f lost", "lines 60–61", "reproduces the book's number",
                 "0,333", "±0.002", "inputs printed to two decimals", "9,9", "the book omits the image coordinates",
                 "7,5", "2.5", "**transcription**", "1 defects of the OCR transcription"):
        assert text in md, text
    assert md.index("§7.1") < md.index("§7.2") < md.index("§7.10")
    errata_part, rest = md.split("Differences caused by rounded inputs")
    rounding_part, missing_part = rest.split("Numbers that cannot be reproduced")
    assert "1,73" in errata_part and "0,333" not in errata_part and "9,9" not in errata_part
    assert "0,333" in rounding_part and "9,9" in missing_part
    assert "4,00" not in md and "(7.10.1)" not in md


def test_one_table_per_chapter_with_the_kind_marked(synthetic):
    md = er.errata_markdown()
    header = "| § · page | equation / quantity | printed | correct | kind |"
    assert md.count(header) == 1
    rows = md.split(header)[1].split("\n\n")[0].splitlines()[2:]
    assert len(rows) == 5                       # sign, twin1+twin2, wrong, lost, (7.10.2)
    kinds = [row.rstrip(" |").rsplit("|", 1)[1].strip() for row in rows]
    assert kinds == ["erratum", "erratum", "erratum", "**transcription**", "erratum"]
    assert md.count("<details>") == md.count("</details>") == 5


def test_a_shared_diagnosis_is_written_once(synthetic):
    groups = er.group_records(er.errata(recompute=False))
    twins = next(g for g in groups if len(g.records) > 1)
    assert [r.item for r in twins.records] == ["twin1", "twin2"] and twins.label == "twin1, twin2"
    assert twins.common == "The book's program used the transposed rotation for every correlation of this table."
    assert twins.notes == ["The first gives 1.", "The second gives 2."]
    assert twins.common_proof == "test_twins" and twins.proof_notes == ["", ""]
    md = er.errata_markdown(recompute=False)
    assert md.count("transposed rotation for every correlation") == 1
    assert md.count("test\\_twins") == 1
    assert "The first gives 1." in md and "The second gives 2." in md
    # different statuses or sections never share a row, however similar the text
    assert all(len({(r.status, r.section) for r in g.records}) == 1 for g in groups)


def test_clauses_and_factoring():
    assert er._clauses("A sign (i.e. the minus; see (1.2)). Lost: here; there. Fig. 3 shows it") == [
        "A sign (i.e. the minus; see (1.2)).", "Lost:", "here;", "there.", "Fig. 3 shows it"]
    common, own = er._factor(["For the matrix (1.3.5): sign of f wrong. The general form is g.",
                              "For the matrix (1.3.5): sign of x wrong. The general form is g."])
    assert common == "For the matrix (1.3.5): … The general form is g."
    assert own == ["sign of f wrong.", "sign of x wrong."]
    with pytest.raises(er.InputError, match="by must be"):
        er.group_records([], by="section")


def test_markdown_escapes_markup_outside_mathematics(synthetic):
    """Z* and x_0 are not emphasis, $5 does not open mathematics; LaTeX stays mathematics (MyST)."""
    from markdown_it import MarkdownIt
    from mdit_py_plugins.dollarmath import dollarmath_plugin
    md = er.errata_markdown(recompute=False)
    assert "Z\\* and x\\_0" in md and "costs \\$5" in md
    html = MarkdownIt("commonmark", {"html": True}).enable("table").use(dollarmath_plugin).render(md)
    assert "<strong>Diagnosis.</strong> The OCR read the 2 as 7 (Z* and x_0 of the text survive; it costs $5).</p>" \
        in html
    assert html.count('class="math inline"') == 2 and "\\frac{1}{m} = \\frac{f}{H}" in html
    assert "<details>" in html and "<strong>Diagnosis.</strong>" in html


def test_math_in_a_table_cell_keeps_its_bars():
    assert er._math_cell(r"\left| d^i - d^j \right| + \|v\|") == r"$\left\vert  d^i - d^j \right\vert  + \Vert v\Vert $"
    assert er._math_cell("(lost in the OCR: nothing is printed)") == "(lost in the OCR: nothing is printed)"


def test_counts(synthetic):
    (row,) = er.status_counts()
    assert (row["chapter"], row["reproduced"], row["erratum"], row["transcription"], row["input-rounding"],
            row["not-reproducible"], row["total"]) == (7, 2, 5, 1, 1, 1, 10)


def test_no_errata(tmp_path, monkeypatch):
    text = CHAPTER.split("[[example]]")[0]
    (tmp_path / "ch07.toml").write_text(text, encoding="utf-8")
    monkeypatch.setenv("PHOTOLIB_TEXTBOOK", str(tmp_path))
    load_chapter.cache_clear()
    try:
        assert er.errata() == [] and "No erratum is recorded." in er.errata_markdown()
    finally:
        load_chapter.cache_clear()


# --- the real textbook/ ------------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def real():
    load_chapter.cache_clear()
    load_pages.cache_clear()
    return er.errata(recompute=False)


def test_real_textbook_errata_are_consistent(real):
    """Every erratum and transcription of the real textbook/ carries its correction, diagnosis and proof."""
    assert {r.status for r in real} == {"erratum", "transcription"}
    for rec in real:
        assert rec.correct and rec.diagnosis and rec.proof, rec.id


def test_every_transcription_says_what_the_ocr_lost(real):
    """A transcription is a defect of the OCR text: its diagnosis says so."""
    lost = [r for r in real if r.status == "transcription"]
    assert len(lost) >= 9
    for rec in lost:
        assert re.search(r"\bOCR\b|transcription", rec.diagnosis), rec.id


def test_undecidable_errata_say_they_may_be_transcription_defects(real):
    """A diagnosis that cannot tell the book from the OCR keeps the erratum and says so."""
    undecided = [r for r in real if r.status == "erratum"
                 and re.search(r"book or OCR|\bor (the |an |in the )?OCR|OCR/print|thesis.s or the OCR.s", r.diagnosis)]
    assert len(undecided) >= 10
    for rec in undecided:
        assert "transcription defect" in rec.diagnosis or "cannot be excluded" in rec.diagnosis, rec.id


def test_real_citations_lead_with_the_page(real):
    book = [r for r in real if r.seed == load_pages().seed]
    assert all(re.fullmatch(r"§[\d.]+, pp?\. ≈?\d+(–\d+)?", r.where) for r in book), \
        [r.where for r in book if not re.fullmatch(r"§[\d.]+, pp?\. ≈?\d+(–\d+)?", r.where)]
    a1 = next(r for r in real if r.id == "1.8.3-a1")
    assert a1.where.startswith("§1.8, p")
    others = {r.id.split("-")[0]: r.where for r in real if r.seed != load_pages().seed}
    assert others["gnss"] == "Dobrynin & Pimshina, GNSS-centres paper"
    assert others["mrf"] == "Baikalova et al., MRF terrain paper"
    assert others["sementsov"].startswith("Sementsov, PhD thesis (2019), §")


def test_real_markdown_writes_each_diagnosis_once(real):
    groups = er.group_records(real)
    assert len(groups) < len(real) / 1.5
    a1 = next(g for g in groups if g.first.id == "1.8.3-a1")
    assert len(a1.records) == 11 and a1.label == "(1.8.3) a1 … b6 (11 formulas)"
    md = er.errata_markdown(recompute=False)
    paragraphs = [p for p in md.split("\n\n") if p.startswith("**Diagnosis.**")]
    repeated = [p[:80] for p, n in Counter(paragraphs).items() if n > 1]
    assert not repeated
    bullets = [line.split(".** ", 1)[1].split(" *Values")[0] for line in md.splitlines() if line.startswith("- **")]
    assert not [b[:80] for b, n in Counter(bullets).items() if n > 1]
    assert "lines 572–576" not in md.split("<details>")[0]       # OCR lines only inside the blocks
    assert md.count("<details>") == md.count("</details>") == len(groups)
