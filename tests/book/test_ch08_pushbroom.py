"""Chapter 8 §8.1–8.5, §8.7, §8.8 adapters (photolib/book/ch08_pushbroom.py), their textbook entries
and figures.

Every formula adapter accepts the correct form and rejects the book's erratum (or a deliberately
broken form); every entry of textbook/ch08_pushbroom.toml keeps its recorded status.
"""

import tomllib
from pathlib import Path

import matplotlib
import pytest

from photolib.book import ch08_pushbroom as c
from photolib.book.textbook import load_chapter
from photolib.book.verify import check_example, check_formula

matplotlib.use("Agg")
FRAGMENT = Path(__file__).resolve().parents[2] / "textbook" / "ch08_pushbroom.toml"
IDS = {e["id"] for kind in ("example", "formula") for e in tomllib.loads(FRAGMENT.read_text()).get(kind, [])}


def ok(result):
    return result["printed_equals_derived"]


@pytest.mark.parametrize("adapter, good, bad", [
    (c.ray_vector_formula, {"vector": ["x_i - x_0", "y_c - y_0", "-f"]}, {"vector": ["x_c - x_0", "y_c - y_0", "-f"]}),
    (c.unit_ray_formula, {"numerator": ["x_mu - x_0", "y_c - y_0", "-f"],
                          "norm": "sqrt((x_mu - x_0)**2 + (y_c - y_0)**2 + f**2)", "line_offset": "x_mu"},
     {"numerator": ["x_mu - x_0", "y_c - y_0", "-f"], "norm": "sqrt((x_n - x_0)**2 + (y_c - y_0)**2 + f**2)",
      "line_offset": "x_mu"}),
    (c.whiskbroom_formula, {"phi": "theta*y_m/l_y"}, {"phi": "2*theta*y_m/l_y"}),
    (c.tilted_focal_formula, {"f_tilted": "f_0/cos(alpha)"}, {"f_tilted": "f_0*cos(alpha)"}),
    (c.ground_formula, {"lines": ["X_S + (Z - Z_S)*Xp/Zp", "Y_S + (Z - Z_S)*Yp/Zp"]},
     {"lines": ["X_S + (Z - Z_S)*Xp/Zp", "Y_S + (Z - Z_S)*Yp/Zp", "Y_S + (Z"]}),
    (c.inverse_formula, {"left": ["x", "y"]}, {"left": ["y", "y"]}),
    (c.eo_polynomial_formula, {"degree": 2, "constant_terms": ["X_S0", "kappa_0"]},
     {"degree": 2, "constant_terms": ["X_S0", "kappa_S0"]}),
    (c.approximate_model_formula, {"kind": "dlt", "coefficients": 11}, {"kind": "dlt", "coefficients": 12}),
    (c.first_line_formula, {"composition": "A0*dA"}, {"composition": "dA*A0"}),
    (c.coplanarity_partials, {"unknowns": 12}, {"unknowns": 11}),
    (c.collinearity_partials, {"unknowns_per_image": 6}, {"unknowns_per_image": 12}),
])
def test_adapters_accept_the_correct_form_and_reject_the_wrong_one(adapter, good, bad):
    assert ok(adapter(good))
    assert not ok(adapter(bad))


def test_exact_checks_of_stereo_formulas():
    assert ok(c.intersection_formula({"seed": 1}))
    assert ok(c.coplanarity_formula({"seed": 2}))


def test_minimum_gcps_of_the_approximating_models():
    counts = c.approximate_model_counts({"seed": 0})
    assert (counts["dlt_min_gcp"], counts["affine_min_gcp"], counts["pp_min_gcp"]) == (6, 4, 7)


def test_flat_terrain_condition_numbers():
    r = c.flat_terrain({"seed": 0})
    assert r["cond_flat_free"] > 1e10 > 1e7 > max(r[f"cond_flat_fixed_{n}"] for n in ("Z_S0", "X_S0", "alpha0"))
    assert r["cond_hilly_free"] < 1e5


def test_time_polynomial_model_beats_the_approximations():
    r = c.approximation_errors({"seed": 10, "n_gcp": 20})
    assert r["err_time_polynomial"] < 1e-4 < 1 < r["err_dlt"] < r["err_affine"]
    assert r["err_parallel_perspective_cols"] < 0.2


def test_every_entry_keeps_its_status():
    chapter = load_chapter(8)
    mine = [e for e in list(chapter.examples) + list(chapter.formulas) if e.id in IDS]
    assert len(mine) == len(IDS)
    for entry in mine:
        rows = check_example(entry) if hasattr(entry, "quantities") else [check_formula(entry)]
        assert all(r.ok for r in rows), (entry.id, [(r.quantity, r.computed, r.detail) for r in rows if not r.ok])


def test_figures_draw():
    from photolib.book.figures import ch08_pushbroom as fig
    f1, foot = fig.pushbroom_geometry()
    assert foot[0][0] == 0.0 and foot[700][0] == pytest.approx(70.0)        # 50 m/s × 1.4 s
    f2, gap = fig.staggered_layout()
    assert gap == pytest.approx(40.0, abs=0.1)        # x_i = ±2 mm at f = 0.1 m, H = 1 km: ±20 m
    f3, conds, shift = fig.flat_terrain_ambiguity()
    assert conds["flat, free"] > 1e10 and shift["max_image_shift_px"] < 1e-3
