"""Every entry of textbook/ is recomputed through the same code as ``photolib verify``."""

import pytest

from photolib.book.textbook import available_chapters, load_chapter
from photolib.book.verify import check_example, check_formula, summary, verify

EXAMPLES = [ex for n in available_chapters() for ex in load_chapter(n).examples]
FORMULAS = [fm for n in available_chapters() for fm in load_chapter(n).formulas]


@pytest.mark.parametrize("example", EXAMPLES, ids=[f"ch{e.chapter}:{e.id}" for e in EXAMPLES])
def test_example_keeps_its_recorded_status(example):
    rows = check_example(example)
    assert rows, f"{example.id} has no published quantities"
    changed = [f"{r.quantity}: book {r.book}, computed {r.computed}, recorded {r.status}" for r in rows if not r.ok]
    assert not changed, "\n".join(changed)


@pytest.mark.parametrize("formula", FORMULAS, ids=[f"ch{f.chapter}:{f.id}" for f in FORMULAS])
def test_formula_keeps_its_recorded_status(formula):
    assert check_formula(formula).ok


def test_status_rules_are_strict():
    """A recorded status that no longer holds is reported, in both directions."""
    import copy
    example = copy.deepcopy(load_chapter(1).example("1.6-height-error"))
    q = example.quantities[-1]            # ΔR = 7.8 m, reproduced
    q.status, q.correct, q.diagnosis, q.proof = "erratum", 7.9, "test", "test"
    assert not check_example(example)[-1].ok
    q.status, q.bound, q.reason = "input-rounding", 1.0, "test"
    assert not check_example(example)[-1].ok      # it reproduces, so it is not input-rounding
    q.status, q.value = "reproduced", 7.7
    assert not check_example(example)[-1].ok


def test_cli_exit_code_and_summary(capsys):
    from photolib.book.cli import main
    assert main(["verify", "--chapter", "1"]) == 0
    out = capsys.readouterr().out
    assert "status no longer holds: 0" in out
    assert summary(verify([1]))["changed"] == 0


def test_transcription_is_checked_like_an_erratum():
    """The computed value must round to the recorded correct value, not to the printed (OCR) one."""
    import copy
    example = copy.deepcopy(load_chapter(1).example("1.6-height-error"))
    q = example.quantities[-1]            # ΔR = 7.8 m, reproduced
    q.status, q.value, q.correct, q.diagnosis, q.proof = "transcription", 1.8, 7.8, "the OCR read 7 as 1", "test"
    row = check_example(example)[-1]
    assert row.ok and row.status == "transcription" and row.expected == 7.8
    q.correct = 7.9                       # the computed value does not round to the recorded correct one
    row = check_example(example)[-1]
    assert not row.ok and row.observed_status == "differs (unclassified)"
    assert "recorded correct value 7.9" in row.explain()
    q.value, q.correct = 7.8, 7.8         # reproduces the printed value: not a transcription defect
    row = check_example(example)[-1]
    assert not row.ok and row.detail == "now reproduces" and row.observed_status == "reproduced"


def test_transcription_formula_is_checked_like_an_erratum():
    import copy
    formula = copy.deepcopy(next(f for f in load_chapter(1).formulas if f.id == "1.11.6-dropped-coefficients"))
    assert formula.status == "transcription"
    row = check_formula(formula)
    assert row.ok and row.observed_status == "transcription" and row.computed == "differs from derivation"
    formula.status = "reproduced"
    assert not check_formula(formula).ok


def test_transcription_needs_correct_diagnosis_and_proof(tmp_path, monkeypatch):
    from photolib.errors import InputError
    head = 'chapter = 7\ntitle = "T"\nseed = "s.txt"\nlines = [1, 9]\n'
    quantity = ('[[example]]\nid = "e"\nsection = "7.1"\nlines = [1, 2]\ntitle = "t"\ncompute = "m:f"\n'
                '[[example.quantity]]\nname = "q"\nprinted = "1"\nvalue = 1.0\ndecimals = 0\n'
                'status = "transcription"\ndiagnosis = "lost in the OCR"\nproof = "p"\n')
    formula = ('[[formula]]\nid = "f"\nsection = "7.1"\nlines = [1, 2]\nequation = "(7.1.1)"\nprinted = "x"\n'
               'status = "transcription"\ncorrect = "y"\ndiagnosis = "lost in the OCR"\ncompute = "m:f"\n')
    monkeypatch.setenv("PHOTOLIB_TEXTBOOK", str(tmp_path))
    for body, message in ((quantity, "a transcription needs 'correct'"), (formula, "a transcription needs")):
        (tmp_path / "ch07.toml").write_text(head + body, encoding="utf-8")
        load_chapter.cache_clear()
        try:
            with pytest.raises(InputError, match=message):
                load_chapter(7)
        finally:
            load_chapter.cache_clear()


def test_transcription_has_its_own_colour_and_legend():
    from photolib.book.textbook import STATUSES
    from photolib.book.verify import _LEGEND, STATUS_COLOURS, Table
    assert "transcription" in STATUSES and STATUSES.index("transcription") == STATUSES.index("erratum") + 1
    colours = [c for s, c in STATUS_COLOURS.items()]
    assert STATUS_COLOURS["transcription"] not in colours[:list(STATUS_COLOURS).index("transcription")]
    assert len(set(colours)) == len(colours) and "OCR" in _LEGEND["transcription"]
    html = Table(["q", "status"], [["a", "transcription (correct 2.5)"]])._repr_html_()
    assert STATUS_COLOURS["transcription"] in html and _LEGEND["transcription"] in html


# --- printed pages (textbook/pages.toml) ------------------------------------------------------------------
def test_page_anchors_are_monotonic_and_book_page_is_exact_on_them():
    from photolib.book.textbook import book_page, load_pages
    load_pages.cache_clear()
    pages = load_pages()
    assert pages.seed == "000_0363cf98558e0ca3.txt" and len(pages.anchors) >= 100
    lines = [a.line for a in pages.anchors]
    assert lines == sorted(set(lines))
    assert [a.page for a in pages.anchors] == sorted(a.page for a in pages.anchors)
    for a in pages.anchors:
        assert book_page(a.line) == (a.page, True), a
        if a.kind in ("number", "glued"):         # the page ends there: the next line is on a later page
            assert book_page(a.line + 1)[0] > a.page
    previous = 0
    for line in range(lines[0], lines[-1] + 1):
        page, exact = book_page(line)
        assert page >= previous
        previous = page
    assert book_page(429) == (19, True) and book_page(601) == (25, True) and book_page(1222) == (51, True)
    assert book_page(153) == (10, True) and book_page(154) == (11, True)       # "… дисторсии. 10 При …"


def test_book_page_between_anchors_is_interpolated_within_its_bounds():
    from photolib.book.textbook import book_page, page_citation
    assert book_page(420) == (19, True)        # §1.5 (p. 19) at 410, the printed "19" at 429
    assert book_page(440) == (20, True)        # after the "19", before §1.6 (p. 20) at 448
    page, exact = book_page(500)               # §1.7 (p. 21) at 466, §1.8 (p. 23) at 530
    assert 21 <= page <= 23 and not exact
    assert page_citation([444, 446]) == "p. 20" and page_citation(500) == f"p. ≈{page}"
    assert page_citation([410, 448]) == "pp. 19–20"


def test_book_page_rejects_bad_lines():
    from photolib.book.textbook import book_page
    from photolib.errors import InputError
    for bad in (0, -3, 2.5, "429", True, 10 ** 6, 1):
        with pytest.raises(InputError, match="line"):
            book_page(bad)


def test_page_anchors_must_not_go_back(tmp_path, monkeypatch):
    from photolib.book.textbook import load_pages
    from photolib.errors import InputError
    monkeypatch.setenv("PHOTOLIB_TEXTBOOK", str(tmp_path))
    cases = {'[[anchor]]\nline = 10\npage = 5\nkind = "heading"\n[[anchor]]\nline = 20\npage = 4\nkind = "heading"\n':
             "pages must not go back",
             '[[anchor]]\nline = 10\npage = 5\nkind = "number"\n[[anchor]]\nline = 20\npage = 5\nkind = "heading"\n':
             "pages must not go back",
             '[[anchor]]\nline = 10\npage = 5\nkind = "footer"\n': "unknown kind",
             '[[anchor]]\nline = 10\nkind = "heading"\n': "lacks"}
    for text, message in cases.items():
        (tmp_path / "pages.toml").write_text('seed = "s.txt"\n' + text, encoding="utf-8")
        load_pages.cache_clear()
        try:
            with pytest.raises(InputError, match=message):
                load_pages()
        finally:
            load_pages.cache_clear()


def test_formula_table_selects_by_prefix_set_or_list():
    """A prefix and a set keep the chapter's order, a list its own; the rows are check_formula's."""
    from photolib.book.verify import formula_table
    ids = [fm.id for fm in load_chapter(8).formulas if fm.id.startswith("hanzl-7.3.2")]
    assert len(ids) >= 3
    by_prefix = formula_table(8, "hanzl-7.3.2", "t")
    assert [row[0] for row in by_prefix.rows] == [
        fm.equation for fm in load_chapter(8).formulas if fm.id in ids]
    assert formula_table(8, set(ids), "t").rows == by_prefix.rows
    assert formula_table(8, ids[::-1], "t").rows == by_prefix.rows[::-1]
    first = next(fm for fm in load_chapter(8).formulas if fm.id == ids[0])
    assert by_prefix.rows[0][2:4] == [check_formula(first).computed, first.status]
    with pytest.raises(KeyError):
        formula_table(8, ["no-such-formula"], "t")
