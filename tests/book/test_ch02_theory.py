"""Chapter 2 theory adapters (photolib/book/ch02_theory.py): formula checks must reject wrong
formulas, the inline computations and the simulation behind the "≈10 %" statement.

Expected values come from the book (printed numbers), sympy, or synthetic ground truth.
"""

import numpy as np
import pytest

from photolib import image_pair
from photolib.book import ch02_theory as c
from photolib.errors import DegenerateGeometryError


def ok(result):
    return result["printed_equals_derived"]


# --- formula checks accept the printed form and reject a wrong one ------------------------------
@pytest.mark.parametrize("fn, good, bad", [
    (c.convergence_angle_formula, {"printed": "b/L"}, {"printed": "b/(2*L)"}),
    (c.physiological_parallax_formula, {"printed": "arc1 - arc2"}, {"printed": "arc1 + arc2"}),
    (c.depth_change_formula, {"printed": ["-b*dgamma/gamma**2", "-L**2*dgamma/b"]},
     {"printed": ["-b*dgamma/gamma**2", "L**2*dgamma/b"]}),
    (c.ray_direction_formula, {"printed": ["x - x0", "y - y0", "-f"]}, {"printed": ["x - x0", "y - y0", "f"]}),
    (c.cross_product_components,
     {"printed_left": ["Y1*Z2 - Y2*Z1", "-(X1*Z2 - X2*Z1)", "X1*Y2 - X2*Y1"],
      "printed_right": ["BY*Z2 - BZ*Y2", "-(BX*Z2 - BZ*X2)", "BX*Y2 - BY*X2"]},
     {"printed_left": ["Y1*Z2 - Y2*Z1", "X1*Z2 - X2*Z1", "X1*Y2 - X2*Y1"],
      "printed_right": ["BY*Z2 - BZ*Y2", "-(BX*Z2 - BZ*X2)", "BX*Y2 - BY*X2"]}),
    (c.scale_norm_formula,
     {"printed": ["sqrt((BY*Z2 - BZ*Y2)**2 + (BX*Z2 - BZ*X2)**2 + (BX*Y2 - BY*X2)**2)",
                  "sqrt((Y1*Z2 - Y2*Z1)**2 + (X1*Z2 - X2*Z1)**2 + (X1*Y2 - X2*Y1)**2)"]},
     {"printed": ["sqrt((BY*Z2 - BZ*Y2)**2 + (BX*Z2 - BZ*X2)**2 + (BX*Y2 - BY*X2)**2)",
                  "sqrt((Y1*Z2 - Y2*Z1)**2 + (X1*Z2 + X2*Z1)**2 + (X1*Y2 - X2*Y1)**2)"]}),
    (c.scale_component_formulas,
     {"printed": ["(BY*Z2 - BZ*Y2)/(Y1*Z2 - Y2*Z1)", "(BX*Z2 - BZ*X2)/(X1*Z2 - X2*Z1)",
                  "(BX*Y2 - BY*X2)/(X1*Y2 - X2*Y1)"]},
     {"printed": ["(BY*Z2 - BZ*Y2)/(Y1*Z2 - Y2*Z1)", "(BX*Z2 - BZ*X2)/(X1*Z2 - X2*Z1)",
                  "(BX*Y2 - BY*X2)/(X2*Y1 - X1*Y2)"]}),
    (c.normal_case_scale, {"printed": ["(BX*Z2 - BZ*X2)/(X1*Z2 - X2*Z1)", "B/p"]},
     {"printed": ["(BX*Z2 - BZ*X2)/(X1*Z2 - X2*Z1)", "B/(x1 + x2)"]}),
    (c.normal_case_coordinates, {"printed": ["-Z/f*x1", "-Z/f*y1", "-B/p*f"]},
     {"printed": ["Z/f*x1", "-Z/f*y1", "-B/p*f"]}),
    (c.coplanarity_formula, {"printed_rows": [["BX", "BY", "BZ"], ["X1", "Y1", "Z1"], ["X2", "Y2", "Z2"]]},
     {"printed_rows": [["BX", "BY", "BZ"], ["X1", "Y1", "Z1"], ["X2", "Y2", "Z1"]]}),
    (c.coplanarity_system, {"system": "independent", "printed": "Y1*Z2 - Y2*Z1"},
     {"system": "independent", "printed": "Y1*Z2 + Y2*Z1"}),
    (c.coplanarity_system,
     {"system": "dependent", "printed_rows": [["1", "by", "bz"], ["x1 - x01", "y1 - y01", "-f1"], ["X2", "Y2", "Z2"]]},
     {"system": "dependent", "printed_rows": [["1", "by", "bz"], ["x1 - x01", "y1 - y01", "f1"], ["X2", "Y2", "Z2"]]}),
    (c.image_orientation_formula,
     {"printed_centre": ["X0 + (a11*XSM + a12*YSM + a13*ZSM)*t", "Y0 + (a21*XSM + a22*YSM + a23*ZSM)*t",
                         "Z0 + (a31*XSM + a32*YSM + a33*ZSM)*t"],
      "printed_angles": ["arctg(-a23/a33)", "arcsin(a13)", "arctg(-a12/a11)"]},
     {"printed_centre": ["X0 + (a11*XSM + a21*YSM + a31*ZSM)*t", "Y0 + (a12*XSM + a22*YSM + a32*ZSM)*t",
                         "Z0 + (a13*XSM + a23*YSM + a33*ZSM)*t"],
      "printed_angles": ["arctg(-a23/a33)", "arcsin(a13)", "arctg(-a12/a11)"]}),
    (c.accuracy_partials,
     {"printed": {"dX_dZ": "-x1/f", "dX_dx1": "-Z/f", "dY_dZ": "-y1/f", "dY_dy1": "-Z/f",
                  "dZ_dp": "B*f/p**2", "dZ_dp_2": "-Z/p", "dZ_dp_3": "-Z/b"}},
     {"printed": {"dX_dZ": "-x1/f", "dX_dx1": "-Z/f", "dY_dZ": "-y1/f", "dY_dy1": "-Z/f",
                  "dZ_dp": "-B*f/p**2", "dZ_dp_2": "-Z/p", "dZ_dp_3": "-Z/b"}}),
    (c.accuracy_formulas,
     {"printed": ["sqrt((x/f*mZ)**2 + (Z/f*mx)**2)", "sqrt((y/f*mZ)**2 + (Z/f*my)**2)", "sqrt((Z/b*mp)**2)"]},
     {"printed": ["sqrt((x/f*mZ)**2 + (Z/f*mx)**2)", "sqrt((y/f*mZ)**2 + (Z/f*my)**2)", "sqrt((Z/f*mp)**2)"]}),
    (c.photo_base_formula, {"printed": "l_x*(100 - P_x)/100"}, {"printed": "l_x*P_x/100"}),
])
def test_formula_checks_accept_printed_and_reject_wrong(fn, good, bad):
    assert ok(fn(good))
    assert not ok(fn(bad))


def test_model_base_erratum():
    """§2.9 first listing B_Z = B_X b_y is wrong; B_Z = B_X b_z (second listing) is right."""
    assert not ok(c.model_base_components({"printed": ["BX*by", "BX*by"]}))
    assert ok(c.model_base_components({"printed": ["BX*by", "BX*bz"]}))


def test_similarity_component_erratum():
    """(2.10.5) as printed lacks t; with t it equals (2.10.4)."""
    rows = ["X0 + (a11*XM + a12*YM + a13*ZM)", "Y0 + (a21*XM + a22*YM + a23*ZM)", "Z0 + (a31*XM + a32*YM + a33*ZM)"]
    assert not ok(c.similarity_formula({"printed": rows}))
    assert ok(c.similarity_formula({"printed": [r + "*t" for r in rows]}))


# --- inline computations -----------------------------------------------------------------------
def test_stereo_radius_book_and_exact_rho():
    r = c.stereo_radius_example({"b_mm": 65.0, "gamma_min_arcsec": 30.0, "rho_arcsec": 200000.0})
    assert r["R_m"] == pytest.approx(65.0 * 200000.0 / 30.0 / 1000.0)   # 433.3 m: the book's "430"
    assert round(r["R_m"], -1) == 430
    assert r["R_exact_rho_m"] == pytest.approx(0.065 * (180 * 3600 / np.pi) / 30.0)   # 446.9 m


def test_component_formula_degeneracy():
    r = c.component_formula_degeneracy({"denominators": ["Y1*Z2 - Y2*Z1", "X1*Z2 - X2*Z1", "X1*Y2 - X2*Y1"]})
    assert r["failing_formulas"] == "1, 3"
    # numerically: rays of points with y = 0 in the normal case
    r1 = np.array([[10.0, 0.0, -100.0], [5.0, 0.0, -100.0]])
    r2 = np.array([[-30.0, 0.0, -100.0], [-35.0, 0.0, -100.0]])
    B = np.array([400.0, 0.0, 0.0])
    assert np.allclose(image_pair.intersection_scale(B, r1, r2, method="component", formula=2), 400.0 / 40.0)
    for k in (1, 3):
        with pytest.raises(DegenerateGeometryError):
            image_pair.intersection_scale(B, r1, r2, method="component", formula=k)


def test_relative_orientation_counts():
    r = c.relative_orientation_counts({"order": "kaw", "n_points": 12, "seed": 0})
    assert (r["n_parameters"], r["n_elements"], r["n_fixed"], r["min_points"]) == (8, 5, 3, 5)
    assert r["admissible_systems"] == 2 * 3 * 3 and r["one_per_group"] == "yes"


def test_absolute_orientation_counts():
    r = c.absolute_orientation_counts({"seed": 0})
    assert (r["n_elements"], r["min_full_points"], r["rank_3_collinear"]) == (7, 3, 6)
    assert (r["min_full_with_height"], r["min_height_with_2_xy"]) == (2, 3)


def test_standard_zones_and_blunder_localisation():
    pts, zone = c.standard_zones(3)
    assert len(pts) == 18 and set(zone.tolist()) == set(range(1, 7))
    one = c.blunder_localisation(1)          # 6 points, 1 redundant: all |w| equal, no localisation
    assert one["dof"] == 1 and one["ratio"] == pytest.approx(1.0, abs=1e-6)
    two = c.blunder_localisation(2)          # pairs in the zones: the blunder stands out
    assert two["largest"] == 4 and two["ratio"] > 1.5


def test_dmc3_example():
    inputs = dict(H_m=2000.0, overlap_percent=60.0, f_mm=92.0, frame_px_x=14592, frame_px_y=25728, pixel_um=3.9,
                  m_xy_px=0.5, m_p_px=0.3, b_printed_mm=22.8, m_xy_printed_um=2.0, m_p_printed_um=1.2)
    r = c.dmc3_accuracy(inputs)
    b = 14592 * 3.9e-3 * 0.4
    assert r["b_mm"] == pytest.approx(b)
    assert r["m_Z"] == pytest.approx(2000.0 / b * 0.3 * 3.9e-3)           # 0.1028 → "0,10"
    assert round(r["m_Z"], 2) == 0.10 and round(r["m_X"], 2) == 0.04
    assert r["m_Z_printed_chain"] == pytest.approx(2000.0 / 22.8 * 0.0012)  # 0.1053 → would print 0.11
    assert round(r["m_Z_printed_chain"], 2) == 0.11


# --- the simulation behind the "≈10 %" statement --------------------------------------------------
def test_simulation_normal_case_matches_formula_exactly_in_z():
    """Sanity of the simulator: no tilt, no relief, no plan noise → Z errors follow m_Z = (H/b)m_p."""
    r = c.simulate_pair_accuracy(seed=3, n_points=20000, tilt_deg=0.0, relief_m=0.0, m_xy_px=0.01)
    assert r["rms"][2] == pytest.approx(r["full"][2], rel=0.03)
    assert np.all(r["rms"][:2] < 0.5 * r["full"][2])


def test_ten_percent_claim():
    r = c.ten_percent_claim({"seeds": [0, 1, 2], "limit_percent": 10.0})
    assert r["full_within_limit"] == "yes" and r["worst_full_percent"] < 10.0
    assert r["approx_within_limit"] == "no" and r["worst_approx_percent"] > 15.0
    sim = c.simulate_pair_accuracy(seed=0)
    assert sim["deviation_approx_percent"][1] > 15.0          # m_Y ≈ (Z/f)m_y is too small for the DMC III
