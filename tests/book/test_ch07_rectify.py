"""Chapter 7 §7.1–7.4, §7.7, §7.9 adapters (photolib/book/ch07_rectify.py) and their textbook entries.

Every formula adapter accepts the correct form and rejects the printed erratum or a deliberately
broken form; the simulations give the figures quoted in textbook/ch07_rectify.toml's notes.
Expected values come from sympy, the book's printed numbers, or synthetic ground truth.
"""

import numpy as np
import pytest

from photolib.book import ch07_rectify as c
from photolib.book.textbook import load_chapter
from photolib.book.verify import check_example, check_formula


def ok(result):
    return result["printed_equals_derived"]


BILINEAR = {"Z_K": "Z1 + (Z2 - Z1)/D*dY", "Z_M": "Z3 + (Z4 - Z3)/D*dY", "Z_i": "Z_K + (Z_M - Z_K)/D*dX"}


@pytest.mark.parametrize("adapter, good, bad", [
    (c.mapping_formula, {"reading": "two functions"}, {"reading": "one function"}),
    (c.accumulation_formula, {"printed": "dT - (s1*d1 + s2*d2)/(s1 + s2)"}, {"printed": "x - f(xT, yT)"}),
    (c.accumulation_formula, {"printed": "dT - (s1*d1 + s2*d2)/(s1 + s2)"}, {"printed": "dT - (d1 + d2)"}),
    (c.bilinear_dem_formula, BILINEAR, {**BILINEAR, "Z_K": "Z1 + (Z2 - Z1)/D*dX"}),
    (c.collinearity_formula, {"matrix": "A^T"}, {"matrix": "A"}),
    (c.ortho_pixel_formula, {"printed": "Delta*m"}, {"printed": "Delta/m"}),
    (c.admissible_relief_formula, {"printed": "f/r*Delta_R_max"}, {"printed": "r/f*Delta_R_max"}),
])
def test_adapters_accept_the_correct_form_and_reject_the_wrong_one(adapter, good, bad):
    assert ok(adapter(good))
    assert not ok(adapter(bad))


def test_monoplot_formula_reproduces():
    assert ok(c.monoplot_formula({}))


def test_forward_example_weights_are_the_overlapped_areas():
    r = c.forward_weights({"xT": 151.3, "yT": 20.7})
    assert r["pixels_covered"] == 4
    expected = {"w_151_20": 0.7 * 0.3, "w_152_20": 0.3 * 0.3, "w_151_21": 0.7 * 0.7, "w_152_21": 0.3 * 0.7}
    for key, value in expected.items():
        assert r[key] == pytest.approx(value, abs=1e-12)


def test_nearest_neighbour_example():
    assert c.nearest_neighbour({"x": 150.3, "y": 21.7}) == {"j": 150, "i": 22}


def test_forward_holes_figure_of_the_notes():
    r = c.forward_holes({"scale": 2.0, "size": 20, "seed": 0})
    assert r["forward_hole_fraction"] == pytest.approx(1 - 400 / 39 ** 2)      # 73.7 %


def test_resampling_figures_of_the_notes():
    r = c.resampling_quality({"size": 100, "tilt_deg": 2.0})
    assert round(r["rms_nearest"], 4) == 0.0111 and round(r["rms_bilinear"], 4) == 0.0010
    assert round(r["rms_bicubic"], 5) == 0.00045


@pytest.mark.parametrize("tilt, principal, nadir", [(0.0, 0.012, 0.012), (3.0, 0.27, 0.043), (5.0, 0.46, 0.083)])
def test_tilt_limit_figures_of_the_notes(tilt, principal, nadir):
    r = c.dem_error_displacement({"tilt_deg": tilt, "dZ": 2.0})
    assert r["max_relative_error_principal"] == pytest.approx(principal, abs=0.005)
    assert r["max_relative_error_nadir"] == pytest.approx(nadir, abs=0.0005)


def test_monoplot_iteration_and_apriori_figures():
    r = c.monoplot_iteration({"tol": 0.001, "tilt_deg": 2.0})
    assert r["converges"] == "yes" and r["max_iterations"] <= 4
    a = c.apriori_check({"M": 500, "d_omega": 0.002})
    assert a["mean_error_mm_wrong"] == pytest.approx(4.0, abs=0.05)


def _entries():
    chapter = load_chapter(7)
    return [e for e in list(chapter.examples) + list(chapter.formulas)
            if getattr(e, "compute", "") and "ch07_rectify" in e.compute]


@pytest.mark.parametrize("entry", _entries(), ids=lambda e: e.id)
def test_textbook_entry_holds(entry):
    if hasattr(entry, "quantities"):
        rows = check_example(entry)
        assert all(row.ok for row in rows), [row for row in rows if not row.ok]
    else:
        assert check_formula(entry).ok
