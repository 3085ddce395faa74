"""Chapter 6 §6.4–6.5 adapters (photolib/book/ch06_sgm.py) and their textbook entries.

Every formula adapter accepts the correct form and rejects the book's erratum or a deliberately
broken form; the statements' simulations give the figures recorded in textbook/ch06_sgm.toml.
Expected values come from sympy, exhaustive enumeration, or synthetic ground truth.
"""

import pytest

from photolib.book import ch06_sgm as c
from photolib.book.textbook import load_chapter
from photolib.book.verify import check_example, check_formula


def ok(result):
    return result["printed_equals_derived"]


@pytest.mark.parametrize("adapter, good, bad", [
    (c.cost_formula, {"cost": "Abs(D1 - D2)"}, {"cost": "D1 - D2"}),
    (c.cost_formula, {"cost": "Abs(D2 - D1)"}, {"cost": "(D1 - D2)**2"}),
    (c.energy_formula, {"penalty": "iverson"}, {"penalty": "text"}),
    (c.previous_pixel_formula, {"reading": "vector"}, {"reading": "scalar"}),
    (c.voxel_energy_formula, {"threshold": "dZ"}, {"threshold": "1"}),
    (c.voxel_recursion_formula, {"last_min_index": "k"}, {"last_min_index": "i"}),
])
def test_adapters_accept_the_correct_form_and_reject_the_wrong_one(adapter, good, bad):
    assert ok(adapter(good))
    assert not ok(adapter(bad))


def test_recursion_sum_and_ncc_reproduce():
    assert ok(c.recursion_formula({"seed": 2, "trials": 3}))
    assert ok(c.sum_formula({"seed": 3}))
    assert ok(c.ncc_cost_formula({"n": 4}))


def test_signed_cost_is_useless_for_wta():
    r = c.signed_cost_wta({"seed": 7, "max_disparity": 20})
    assert r["wta_correct_signed"] < 0.2 < 0.7 < r["wta_correct_absolute"]


def test_penalties_must_be_scaled_to_the_cost():
    r = c.wta_vs_sgm({"seed": 7, "penalties": [8.0, 64.0]})
    assert r["wta_correct"] < r["sgm_unit_penalties_correct"] < r["sgm_correct"]
    assert r["sgm_correct"] > 0.99 and r["sgm_better"] == "yes"


def test_eight_paths_and_third_term():
    assert c.printed_directions({})["n_paths"] == 8
    assert c.third_term_no_effect({"seed": 6})["argmin_unchanged"] == "yes"


def _mine(entries):
    return [e for e in entries if e.id.startswith(("6.4", "6.5"))]


def test_every_entry_of_the_fragment_verifies():
    chapter = load_chapter(6)
    formulas = _mine(chapter.formulas)
    examples = _mine(chapter.examples)
    assert len(formulas) == 11 and len(examples) == 8
    for f in formulas:
        row = check_formula(f)
        assert row.ok, row
    for e in examples:
        for row in check_example(e):
            assert row.ok, row
