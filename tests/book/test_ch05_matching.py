"""Book layer for Chapter 5, §5.1–5.4 and §5.11: the adapters of textbook/ch05_matching.toml."""

import pytest

from photolib.book import ch05_matching as C
from photolib.book import verify
from photolib.book.textbook import load_chapter

IDS = ("5.1", "5.2", "5.4", "5.11")


def mine(entries):
    return [e for e in entries if any(e.id.startswith(p + "-") or e.id.startswith(p + ".") for p in IDS)
            and "matching" in (getattr(e, "compute", "") or "")]


def test_every_entry_keeps_its_status():
    chapter = load_chapter(5)
    rows = [r for ex in mine(chapter.examples) for r in verify.check_example(ex)]
    rows += [verify.check_formula(fm) for fm in mine(chapter.formulas)]
    assert len(rows) >= 25
    bad = [r for r in rows if not r.ok]
    assert not bad, bad


def test_formula_adapters_reject_wrong_forms():
    assert not C.parabola_vertex_formula({"vertex": "a1/(2*a2)"})["printed_equals_derived"]
    assert not C.lsm_partials_formula({"coefficients": {"a1": "-g_x"}})["printed_equals_derived"]
    assert C.lsm_partials_formula({"coefficients": {"a3": "-g_x*u", "a6": "-g_y*v"}})["printed_equals_derived"]
    assert not C.lsm_solution_formula({"sign_of_update": 1})["printed_equals_derived"]
    assert C.gradient_weight_formula({"printed": "exp(-(G_max/G - 1))"})["printed_equals_derived"]
    assert not C.circle_linearisation_formula({"circle": "(x_i - x_c)**2 + (y_i - y_c)**2 - R"})[
        "printed_equals_derived"]
    assert not C.robust_weight_formula({"c": 0.05, "exp_early": 4, "exp_late": 3})["printed_equals_derived"]


def test_simulations_report_their_figures():
    out = C.circle_accuracy({"seed": 3, "centre_radius": [32.37, 30.81, 6.3], "blur": 0.8, "noise": 2.0})
    assert out["centroid_glare_px"] > 0.5 > out["circle_glare_px"]
    lsm = C.lsm_accuracy({"seed": 4, "texture_sigma": 2.0, "trials": 4, "half_window": 7, "noise": 0.0})
    assert lsm["rms_px"] < 0.05
