"""Chapter 7 §7.5, §7.6, §7.8 adapters (photolib/book/ch07_trueortho.py) and their textbook entries.

Every formula adapter accepts the correct form and rejects a wrong one; Fig. 7.12 is compared with
its transcription; the statements' simulations give the figures recorded in
textbook/ch07_trueortho.toml.
"""

import pytest

from photolib.book import ch07_trueortho as c
from photolib.book.textbook import load_chapter
from photolib.book.verify import check_example, check_formula

IDS = ("7.5", "7.6", "7.8")


def ok(result):
    return result["printed_equals_derived"]


@pytest.mark.parametrize("adapter, good, bad", [
    (c.photometric_formula, {"condition": "F - k_i*f_i(x_i, y_i)"}, {"condition": "F - k_i*t_i(x_i, y_i)"}),
    (c.nadir_angle_criterion, {"reading": "alpha<beta"}, {"reading": "alpha>beta"}),
    (c.correction_structure, {"unknowns": ["F", "Z", "k_i"]}, {"unknowns": ["F", "Z"]}),
    (c.counts_formula, {"N": "2*P + (S - 1) + 6*S", "M": "P*S"}, {"N": "2*P + S + 6*S", "M": "P*S"}),
])
def test_adapters_accept_the_correct_form_and_reject_the_wrong_one(adapter, good, bad):
    assert ok(adapter(good))
    assert not ok(adapter(bad))


def test_collinearity_782_is_732_for_both_orders():
    assert ok(c.collinearity_formula({"order": "wak"})) and ok(c.collinearity_formula({"order": "kaw"}))


def test_fig_7_12_model_gives_both_printed_grids():
    entry = next(e for e in load_chapter(7).examples if e.id == "7.5-fig-7.12-index-matrix")
    out = c.fig_7_12(entry.inputs)
    assert tuple(out[f"left row {i}"] for i in range(10)) == c.FIG_7_12_LEFT
    assert tuple(out[f"right row {i}"] for i in range(10)) == c.FIG_7_12_RIGHT
    # a lower building (h/H = 0.05) does not give the printed pattern: the walls would be too thin
    low = dict(entry.inputs, box=entry.inputs["box"][:5] + [10.0])
    assert tuple(c.fig_7_12(low)[f"left row {i}"] for i in range(10)) != c.FIG_7_12_LEFT


def test_counts_and_two_images():
    assert c.counts_example({"P": 100}) == {"N (S = 2)": 201, "M (S = 2)": 200, "S = 2 solvable": "no",
                                            "M (S = 3)": 300, "S = 3 solvable": "yes"}
    assert c.two_images_refused({"side": 10}) == {"S = 2 solvable": "no"}


def test_neighbour_test_misses_group_occlusion():
    r = c.neighbour_only_test({"height": 20.0, "Zs": 60.0})
    assert r["hidden_cells"] > 40 and r["missed_by_neighbour_test"] > 20


def test_every_entry_of_the_fragment_verifies():
    chapter = load_chapter(7)
    formulas = [f for f in chapter.formulas if f.section in IDS]
    examples = [e for e in chapter.examples if e.section in IDS]
    assert len(formulas) == 6 and len(examples) >= 7
    for f in formulas:
        assert check_formula(f).ok, f.id
    for e in examples:
        assert all(row.ok for row in check_example(e)), e.id


def test_datum_defect_of_784_is_seven_and_three_gcps_remove_it():
    for images in (3, 4):
        r = c.datum_defect({"side": 6, "images": images, "height": 200.0})
        assert r["unknowns N"] == 2 * 36 + (images - 1) + 6 * images           # the book's count
        assert (r["datum defect"], r["defect with 2 GCPs"], r["defect with 3 GCPs"]) == (7, 1, 0)
        assert r["GCP equations needed"] == "yes"
