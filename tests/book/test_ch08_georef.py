"""Chapter 8 §8.14–8.17 adapters (photolib/book/ch08_georef.py) and their textbook entries.

Every formula adapter accepts the correct form and rejects the book's erratum or a deliberately
broken form; the simulations give the figures recorded in textbook/ch08_georef.toml.
"""

import pytest

from photolib.book import ch08_georef as c
from photolib.book.textbook import load_chapter
from photolib.book.verify import check_example, check_formula

DENOM = "sqrt((x_i - x_0)**2 + (y_c - y_0)**2 + f**2)"


def ok(result):
    return result["printed_equals_derived"]


@pytest.mark.parametrize("adapter, good, bad", [
    (c.direct_georef_formula, {"R_M": "R_IMU + A*r_s + A*Ab*R", "R_IMU": "R_GNSS - A*r_g"},
     {"R_M": "R_IMU + A*r_s + Ab*A*R", "R_IMU": "R_GNSS - A*r_g"}),                # boresight on the wrong side
    (c.direct_georef_formula, {"R_M": "R_IMU + A*r_s + A*Ab*R", "R_IMU": "R_GNSS - A*r_g"},
     {"R_M": "R_IMU + A*r_s + A*Ab*R", "R_IMU": "R_GNSS + A*r_g"}),                # lever-arm sign
    (c.frame_vector_formula, {"r": ["x - x_0", "y - y_0", "-f"]}, {"r": ["x - x_0", "y - y_0", "f"]}),
    (c.scanner_vector_formula, {"r": [f"(x_i - x_0)/{DENOM}", f"(y_c - y_0)/{DENOM}", f"-f/{DENOM}"]},
     {"r": ["x_i - x_0", "y_c - y_0", "-f"]}),                                     # not a unit vector
    (c.range_vector_formula, {"R": ["0", "D*sin(phi)", "-D*cos(phi)"]}, {"R": ["0", "D*cos(phi)", "-D*sin(phi)"]}),
    (c.collinearity_formula,
     {"x": "-f*(a11*(X-X_s)+a21*(Y-Y_s)+a31*(Z-Z_s))/(a13*(X-X_s)+a23*(Y-Y_s)+a33*(Z-Z_s))",
      "y": "-f*(a12*(X-X_s)+a22*(Y-Y_s)+a32*(Z-Z_s))/(a13*(X-X_s)+a23*(Y-Y_s)+a33*(Z-Z_s))"},
     {"x": "-f*(a11*(X-X_s)+a12*(Y-Y_s)+a13*(Z-Z_s))/(a31*(X-X_s)+a32*(Y-Y_s)+a33*(Z-Z_s))",
      "y": "-f*(a12*(X-X_s)+a22*(Y-Y_s)+a32*(Z-Z_s))/(a13*(X-X_s)+a23*(Y-Y_s)+a33*(Z-Z_s))"}),  # rows for columns
    (c.interpolation_formula, {"c": "(t_k1 - t)/(t_k1 - t_k)", "delta": "c*M_k + (1 - c)*M_k1 - M_t",
                               "E": "c*E_k + (1 - c)*E_k1 - delta"},
     {"c": "(t_k1 - t)/(t_k1 - t_k)", "delta": "c*M_k + (1 - c)*M_k1 - M_t", "E": "c*E_k + (1 - c)*E_k1 + delta"}),
    (c.ray_ground_formula, {"vector": ["Xp", "Yp", "Zp"], "formulas": ["X_s + (Z - Z_s)*Xp/Zp",
                                                                      "Y_s + (Z - Z_s)*Yp/Zp"]},
     {"vector": ["Xp", "Yp", "Yp", "Zp"], "formulas": ["X_s + (Z - Z_s)*Xp/Zp"]}),
    (c.forward_rpc_formula, {"X": "R1(x, y, Z)/R2(x, y, Z)", "Y": "R3(x, y, Z)/R4(x, y, Z)"},
     {"X": "R1(x, y, Z)/R2(x, y, Z)", "Y": "R3(x, y, Z)/R2(x, y, Z)"}),
    (c.cost_formula, {"cost": "Abs(d1 - d2)"}, {"cost": "d1 - d2"}),
])
def test_adapters_accept_the_correct_form_and_reject_the_wrong_one(adapter, good, bad):
    assert ok(adapter(good))
    assert not ok(adapter(bad))


def test_sgm_formulas_reproduce():
    assert ok(c.energy_formula({"seed": 1, "trials": 4}))
    assert ok(c.recursion_formula({"seed": 2, "trials": 3}))
    assert ok(c.sum_formula({"seed": 3}))
    assert c.eight_directions({})["n_paths"] == 8


def test_coverage_counts():
    r = c.three_line_coverage({"strip_spacing": 400.0})
    assert (r["views_one_strip"], r["views_overlap"], r["stereo_pairs"]) == (3, 6, 3)


def test_imu_grade_and_interval():
    r = c.imu_quality_interval({"seed": 3, "tolerance_urad": 20.0, "grades_urad_per_sqrt_s": [1.0, 10.0]})
    assert r["interval_good_imu_s"] > r["interval_poor_imu_s"]
    assert r["better_imu_longer_interval"] == "yes"


def test_direct_holes_and_inverse_complete():
    r = c.direct_vs_inverse({"ortho_pixel": 0.5})
    assert r["holes_direct"] > 0.3 and r["holes_inverse"] == 0.0
    assert r["direct_has_holes"] == "yes" and r["inverse_without_rpc_problematic"] == "no"
    # with ortho pixels as coarse as the scanner's (0.8 m → 1.6 m) the direct method fills (nearly) all
    coarse = c.direct_vs_inverse({"ortho_pixel": 2.0})
    assert coarse["holes_direct"] < r["holes_direct"]


def _entries():
    chapter = load_chapter(8)
    ids = {e.id for e in chapter.examples} | {f.id for f in chapter.formulas}
    return chapter, sorted(i for i in ids if i.startswith(("8.14", "8.15", "8.16", "8.17")))


def test_every_entry_of_the_fragment_holds():
    chapter, ids = _entries()
    assert len(ids) >= 17
    for f in chapter.formulas:
        if f.id in ids:
            assert check_formula(f).ok, f.id
    for e in chapter.examples:
        if e.id in ids:
            assert all(r.ok for r in check_example(e)), e.id
