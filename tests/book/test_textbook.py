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
