"""Chapter 9 §9.1–9.4, 9.7, 9.8, 9.10 adapters (photolib/book/ch09_lidar.py) and their textbook entries.

Every formula adapter accepts the correct form and rejects the book's erratum or a deliberately
broken form; the table and simulations give the figures recorded in textbook/ch09_lidar.toml.
"""

import pytest

from photolib.book import ch09_lidar as c
from photolib.book.textbook import load_chapter
from photolib.book.verify import check_example, check_formula

COLL = "(a13*(X - X_S) + a23*(Y - Y_S) + a33*(Z - Z_S))"


def ok(result):
    return result["printed_equals_derived"]


@pytest.mark.parametrize("adapter, good, bad", [
    (c.als_vector_formula, {"SM": ["0", "D*sin(phi)", "-D*cos(phi)"]}, {"SM": ["0", "D*cos(phi)", "-D*sin(phi)"]}),
    (c.als_georef_formula, {"R": "R_S + A*SM"}, {"R": "R_S + A.T*SM"}),
    (c.swath_footprint_formula, {"SW": "2*H*tan(theta/2)", "D": "2*H*tan(g/2)"},
     {"SW": "H*tan(theta/2)", "D": "2*H*tan(g/2)"}),
    (c.polar_formula, {"XYZ": ["D*cos(nu)*sin(phi)", "D*cos(nu)*cos(phi)", "D*sin(nu)"]},
     {"XYZ": ["D*cos(nu)*cos(phi)", "D*cos(nu)*sin(phi)", "D*sin(nu)"]}),
    (c.pulse_formula, {"D": "v*t/2"}, {"D": "v*t"}),
    (c.phase_formula, {"D": "(K + dphi/(2*pi))*lam/2"}, {"D": "K*lam + dphi/(2*pi)*lam"}),
    (c.triangulation_formula, {"Z": "B*f/(p + f*tan(alpha))"}, {"Z": "B*f/(p - f*tan(alpha))"}),
    (c.triangulation_sigma_formula, {"m_Z": "Z**2/(f*B)*m_p"}, {"m_Z": "Z/(f*B)*m_p"}),
    (c.image_ray_formula, {"r": ["x - x_0 + d_x", "y - y_0 + d_y", "-f"]}, {"r": ["x - x_0", "y - y_0", "-f"]}),
    (c.plane_formula, {"plane": "A*X + B*Y + C*Z + D"}, {"plane": "A*X + B*Y + C*Z - D"}),
    (c.ray_plane_substitution, {"equation": "A*(X_s + N*Xp) + B*(Y_s + N*Yp) + C*(Z_s + N*Zp) + D"},
     {"equation": "A*(X_s + N*Xp) + B*(Y_s + N*Yp) + C*(Z_s + N*Zp)"}),
    (c.ray_plane_scale, {"N": "-(A*X_s + B*Y_s + C*Z_s + D)/(A*Xp + B*Yp + C*Zp)"},
     {"N": "(A*X_s + B*Y_s + C*Z_s + D)/(A*Xp + B*Yp + C*Zp)"}),
    (c.collinearity_formula,
     {"x": f"x_0 - f*(a11*(X - X_S) + a21*(Y - Y_S) + a31*(Z - Z_S))/{COLL}",
      "y": f"y_0 - f*(a12*(X - X_S) + a22*(Y - Y_S) + a32*(Z - Z_S))/{COLL}"},
     {"x": f"x_0 - f*(a11*(X - X_S) + a12*(Y - Y_S) + a13*(Z - Z_S))/{COLL}",
      "y": f"y_0 - f*(a12*(X - X_S) + a22*(Y - Y_S) + a32*(Z - Z_S))/{COLL}"}),
    (c.camera_vector_formula, {"r": "A.T*(R_M - R_S)/N"}, {"r": "A*(R_M - R_S)/N"}),
    (c.camera_centre_formula, {"direction": "[cos(nu)*sin(phi), cos(nu)*cos(phi), sin(nu)]"},
     {"direction": "[cos(nu)*sin(phi), cos(nu)*cos(phi), sin(phi)]"}),
    (c.mobile_chain_formula, {"R_M": "R_IMU + A*r_s + A*Ab*R", "R_IMU": "R_GNSS - A*r_g"},
     {"R_M": "R_IMU + A*r_s + Ab*A*R", "R_IMU": "R_GNSS - A*r_g"}),
    (c.mobile_lever_formula, {"R_M": "R_GNSS + A*(r_gs + Ab*R)"}, {"R_M": "R_GNSS + A*r_gs + Ab*R"}),
    (c.max_range_formula, {"D": "Delta/tan(dphi)"}, {"D": "Delta*tan(dphi)"}),
    (c.angular_step_formula, {"equation": "tan(step) - d/D"}, {"equation": "atan(step) - d/D"}),
])
def test_adapter_accepts_correct_and_rejects_wrong(adapter, good, bad):
    assert ok(adapter(good))
    assert not ok(adapter(bad))


def test_camera_rotation_statement_is_wrong():
    assert not ok(c.camera_rotation_statement({}))


def test_table_9_1_als_values():
    units = {"X": {"range_max": 4700, "fov_deg": 60, "g_mrad": 0.25}, "Y": {"range_max": 200, "fov_deg": 360}}
    out = c.table_9_1_als({"units": units})
    assert out["SW_X"] == pytest.approx(9400 / 3 ** 0.5, rel=1e-12) and out["D1000_X"] == pytest.approx(25.0)
    assert "SW_Y" not in out


def test_simulations():
    assert c.laser_line_pipeline({"seed": 5, "sigma_xy": 0.001})["profile"] == "yes"
    assert c.mobile_calibration({"seed": 11, "lever": [0.35, -0.12, 1.65], "boresight_deg": [0.4, -0.25, 0.9],
                                 "sigma": 0.003, "targets": 6, "poses": 4})["calibrated"] == "yes"


def _entries():
    chapter = load_chapter(9)
    examples = [e for e in chapter.examples if (e.compute or "").startswith("photolib.book.ch09_lidar")
                or e.id in ("9.2-two-channels", "9.3-bathymetric", "9.4-triangulation-scanners", "9.9-coverage",
                            "9.9-table-9.1-tls", "9.9-table-9.2")]
    formulas = [f for f in chapter.formulas if f.compute.startswith("photolib.book.ch09_lidar")]
    return examples, formulas


@pytest.mark.parametrize("example", _entries()[0], ids=lambda e: e.id)
def test_example_status_holds(example):
    assert all(row.ok for row in check_example(example))


@pytest.mark.parametrize("formula", _entries()[1], ids=lambda f: f.id)
def test_formula_status_holds(formula):
    assert check_formula(formula).ok
