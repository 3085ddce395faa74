"""Chapter 6, §6.6–6.7 adapters (photolib/book/ch06_dtm.py) and the fragment textbook/ch06_dtm.toml.

The lost plane (6.6.1) is reconstructed with sympy and checked independently here (numpy's
solve of the book's 3×3 system, barycentric weights); a deliberately wrong reconstruction is
rejected; every entry of the fragment keeps its recorded status.
"""

import numpy as np
import pytest
import sympy as sp

from photolib.book import ch06_dtm as c
from photolib.book.textbook import load_chapter
from photolib.book.verify import check_example, check_formula


def test_derived_plane_matches_numpy_solve():
    rng = np.random.default_rng(0)
    for _ in range(5):
        v = rng.uniform(-100, 100, (3, 3))
        sol = c.derive_plane()
        subs = dict(zip(sp.symbols("X1 Y1 Z1 X2 Y2 Z2 X3 Y3 Z3", real=True), v.ravel()))
        ours = [float(sol[k].subs(subs)) for k in "ABC"]
        M = np.column_stack([np.ones(3), v[:, :2]])
        np.testing.assert_allclose(ours, np.linalg.solve(M, v[:, 2]), rtol=1e-10, atol=1e-10)


def test_plane_formula_reconstruction():
    # the printed equation is empty: it cannot equal the derivation (status erratum)
    assert c.plane_formula({"printed": "", "reconstructed": "A + B*X + C*Y"}) == {"printed_equals_derived": False}
    # had the book printed the right plane, it would be reproduced
    assert c.plane_formula({"printed": "A + B*X + C*Y", "reconstructed": "A + B*X + C*Y"})["printed_equals_derived"]
    # a wrong printed plane (swapped slopes) is rejected
    assert not c.plane_formula({"printed": "A + C*X + B*Y", "reconstructed": "A + B*X + C*Y"})["printed_equals_derived"]
    # a wrong reconstruction does not pass through the vertices: the adapter refuses it
    with pytest.raises(AssertionError):
        c.plane_formula({"printed": "", "reconstructed": "A - B*X + C*Y"})


def test_plane_system_rejects_a_wrong_sign():
    assert c.plane_system({"equation": "A + B*X + C*Y - Z"})["printed_equals_derived"]
    assert not c.plane_system({"equation": "A + B*X - C*Y - Z"})["printed_equals_derived"]


def test_closed_form_is_barycentric_interpolation():
    X1, Y1, Z1, X2, Y2, Z2, X3, Y3, Z3 = (3.0, 1.0, 12.0, 11.0, 2.5, 15.0, 6.0, 9.0, 10.5)
    cf = c.closed_form()
    subs = dict(zip(sp.symbols("X1 Y1 Z1 X2 Y2 Z2 X3 Y3 Z3", real=True), (X1, Y1, Z1, X2, Y2, Z2, X3, Y3, Z3)))
    A, B, C = (float(cf[k].subs(subs)) for k in "ABC")
    P = np.array([6.5, 4.0])
    T = np.array([[X1, Y1], [X2, Y2], [X3, Y3]])
    lam = np.linalg.solve(np.vstack([T.T, np.ones(3)]), [*P, 1.0])      # barycentric weights
    assert A + B * P[0] + C * P[1] == pytest.approx(lam @ [Z1, Z2, Z3], abs=1e-12)


def test_inline_adapters():
    assert c.delaunay_rule({"seed": 1, "n_points": 200})["violations"] == 0
    assert c.grid_from_tin_exact({"seed": 2, "n_planes": 2})["max_error"] < 1e-12
    assert c.contours_linear({"seed": 3})["max_level_error"] < 1e-12
    d = c.density_vs_relief({"seed": 5, "tolerance": 0.1, "wavelength": 15.0, "amplitude": 2.0})
    assert d["spacing_high_relief_m"] < d["spacing_low_relief_m"]
    t = c.texture_choice({})
    assert (t["roof"], t["south_wall"], t["north_wall"]) == ("nadir", "south, 30° down", "north, 45° down")
    assert t["south_wall_angle_deg"] == pytest.approx(30.0, abs=1e-9)


def test_dsm_editing_meets_its_stated_targets():
    r = c.dsm_editing({"seed": 4, "noise": 0.05, "max_window": 30.0, "slope": 0.2})
    assert r["objects"] == "removed"
    assert r["objects_found_percent"] >= 98 and r["ground_flagged_percent"] <= 2 and r["rmse_m"] <= 0.3
    assert r["dsm_rmse_m"] > 3


def fragment_entries():
    chapter = load_chapter(6)
    examples = [e for e in chapter.examples if e.compute and e.compute.startswith("photolib.book.ch06_dtm:")]
    formulas = [f for f in chapter.formulas if f.compute.startswith("photolib.book.ch06_dtm:")]
    return examples, formulas


def test_fragment_entries_keep_their_status():
    examples, formulas = fragment_entries()
    assert len(examples) >= 6 and len(formulas) == 2
    for e in examples:
        assert e.id.startswith(("6.6-", "6.7-"))
        for row in check_example(e):
            assert row.ok, f"{e.id}/{row.quantity}: {row.computed} vs {row.book} ({row.status})"
    for f in formulas:
        assert check_formula(f).ok, f.id
    lost = next(f for f in formulas if f.id == "6.6.1-plane-lost")
    assert lost.status == "transcription" and "OCR" in lost.diagnosis and "(6.7.1)" in lost.diagnosis
