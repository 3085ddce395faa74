"""The Errata appendix is generated from textbook/: photolib.book.errata on a synthetic chapter file."""

import sys
import types

import pytest

from photolib.book import errata as er
from photolib.book.textbook import load_chapter

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
    fixture.right = lambda inputs: {"good": 4.0, "wrong": 2 ** 0.5, "rounded": 0.3345, "missing": None, "sign": 5.0}
    fixture.as_printed = lambda inputs: {"wrong": 3 ** 0.5}
    fixture.formula_ok = lambda inputs: {"printed_equals_derived": True}
    fixture.formula_bad = lambda inputs: {"printed_equals_derived": False}
    monkeypatch.setitem(sys.modules, "errata_fixture", fixture)
    (tmp_path / "ch07.toml").write_text(CHAPTER, encoding="utf-8")
    monkeypatch.setenv("PHOTOLIB_TEXTBOOK", str(tmp_path))
    load_chapter.cache_clear()
    yield fixture
    load_chapter.cache_clear()


def test_every_erratum_is_listed_with_printed_and_correct(synthetic):
    records = er.errata()
    assert [(r.id, r.item) for r in records] == [
        ("7.1-early", "sign"), ("7.2-example", "wrong"), ("7.10-formula-bad", "(7.10.2)")]   # sorted by §
    sign, wrong, formula = records
    assert (sign.printed, sign.correct, sign.diagnosis, sign.lines) == ("-5", "5", "sign lost in the OCR", (3, 3))
    assert (wrong.printed, wrong.correct, wrong.unit, wrong.proof) == ("1,73", "1.41", "mm", "sympy sqrt(2)")
    assert wrong.as_printed is True and wrong.as_printed_value.startswith("1.73")
    assert sign.as_printed is None
    assert formula.kind == "formula" and formula.correct == "\\frac{1}{m} = \\frac{f}{H}"
    assert all(r.status == "erratum" and r.chapter == 7 for r in records)


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
                 "0,333", "±0.002", "inputs printed to two decimals", "9,9", "the book omits the image coordinates"):
        assert text in md, text
    assert md.index("§7.1") < md.index("§7.2") < md.index("§7.10")
    errata_part, rest = md.split("Differences caused by rounded inputs")
    rounding_part, missing_part = rest.split("Numbers that cannot be reproduced")
    assert "1,73" in errata_part and "0,333" not in errata_part and "9,9" not in errata_part
    assert "0,333" in rounding_part and "9,9" in missing_part
    assert "4,00" not in md and "(7.10.1)" not in md


def test_counts(synthetic):
    (row,) = er.status_counts()
    assert (row["chapter"], row["reproduced"], row["erratum"], row["input-rounding"], row["not-reproducible"],
            row["total"]) == (7, 2, 3, 1, 1, 7)


def test_no_errata(tmp_path, monkeypatch):
    text = CHAPTER.split("[[example]]")[0]
    (tmp_path / "ch07.toml").write_text(text, encoding="utf-8")
    monkeypatch.setenv("PHOTOLIB_TEXTBOOK", str(tmp_path))
    load_chapter.cache_clear()
    try:
        assert er.errata() == [] and "No erratum is recorded." in er.errata_markdown()
    finally:
        load_chapter.cache_clear()


def test_real_textbook_errata_are_consistent():
    """Every erratum of the real textbook/ carries its correction, diagnosis and proof."""
    load_chapter.cache_clear()
    for rec in er.errata(recompute=False):
        assert rec.correct and rec.diagnosis and rec.proof, rec.id
