"""Chapter 11, §11.1–11.3 entries of textbook/ch11_calibration.toml: every status holds, quickly."""

import time

import numpy as np
import pytest

from photolib.book import verify
from photolib.book.textbook import load_chapter
from photolib.calibration import certificate_to_mm, certificate_to_pixels

CH = load_chapter(11)
FORMULAS = [f.id for f in CH.formulas if f.section in ("11.1", "11.2", "11.3")]
EXAMPLES = [e.id for e in CH.examples if e.section in ("11.1", "11.2", "11.3")]


def test_every_printed_formula_of_11_3_has_an_entry():
    equations = " ".join(f.equation for f in CH.formulas if f.id in FORMULAS)
    for n in range(1, 9):
        assert f"(11.3.{n})" in equations, n


@pytest.mark.parametrize("formula_id", FORMULAS)
def test_formula_status_holds_and_is_fast(formula_id):
    entry = next(f for f in CH.formulas if f.id == formula_id)
    verify.check_formula(entry)                      # warm the sympy caches
    t = time.perf_counter()
    row = verify.check_formula(entry)
    assert row.ok, row
    assert time.perf_counter() - t < 1.0             # photolib verify must stay quick


@pytest.mark.parametrize("example_id", EXAMPLES)
def test_example_statuses_hold(example_id):
    rows = verify.check_example(CH.example(example_id))
    assert rows and all(r.ok for r in rows), [r for r in rows if not r.ok]


def test_errata_of_11_3_are_recorded():
    errata = {f.id for f in CH.formulas if f.id in FORMULAS and f.status == "erratum"}
    assert {"11.3.1-distortion", "11.3.5-solution-Q", "11.3.8-chessboard"} <= errata


def test_printed_solution_sign_walks_away_from_the_minimum():
    # (11.3.5): one Newton step of B·δ + L = V from a wrong start; −Q·Lᴺ lands on the LSQ solution
    rng = np.random.default_rng(11)
    B = rng.normal(size=(8, 3))
    truth = np.array([1.0, -2.0, 0.5])
    obs = B @ truth
    start = np.zeros(3)
    L = B @ start - obs
    N, LN = B.T @ B, B.T @ L
    right = start - np.linalg.solve(N, LN)
    printed = start + np.linalg.solve(N, LN)
    assert np.allclose(right, truth)
    assert np.linalg.norm(printed - truth) > np.linalg.norm(start - truth)


def test_certificate_conversion_is_invertible_and_matches_independent_arithmetic():
    px = {"f": 8075.4, "k1": -2.1391e-9, "k2": 2.8649e-17}
    mm = certificate_to_mm(px, 0.0062)
    assert mm["f"] == pytest.approx(8075.4 * 0.0062, rel=1e-15)
    assert mm["k1"] == pytest.approx(-2.1391e-9 / 0.0062 ** 2, rel=1e-15)
    assert mm["k2"] == pytest.approx(2.8649e-17 / 0.0062 ** 4, rel=1e-15)
    back = certificate_to_pixels(mm, 0.0062)
    assert all(back[k] == pytest.approx(v, rel=1e-14) for k, v in px.items())
    # the radial correction in px and in mm describe the same displacement (r in px ↔ r·Δ in mm)
    r = 3000.0
    d_px = r * (px["k1"] * r ** 2 + px["k2"] * r ** 4)
    rm = r * 0.0062
    d_mm = rm * (mm["k1"] * rm ** 2 + mm["k2"] * rm ** 4)
    assert d_mm == pytest.approx(d_px * 0.0062, rel=1e-12)


@pytest.mark.parametrize("adapter, good, bad", [
    ("distortion_formula",
     {"dx": "(x-x_0)*(r**2*k_1 + r**4*k_2 + r**6*k_3) + (r**2 + 2*(x-x_0)**2)*p_1 + 2*(x-x_0)*(y-y_0)*p_2",
      "dy": "(y-y_0)*(r**2*k_1 + r**4*k_2 + r**6*k_3) + 2*(x-x_0)*(y-y_0)*p_1 + (r**2 + 2*(y-y_0)**2)*p_2"},
     {"dx": "(x-x_0)*(r**2*k_1 + r**4*k_2 + r**6*k_3) + (r**2 + 2*(x-x_0)**2)*p_2 + 2*(x-x_0)*(y-y_0)*p_1",
      "dy": "(y-y_0)*(r**2*k_1 + r**4*k_2 + r**6*k_3) + 2*(x-x_0)*(y-y_0)*p_1 + (r**2 + 2*(y-y_0)**2)*p_2"}),
    ("condition_formula",
     {"Fx": "x_0 - f*(a11*(X-X_S)+a21*(Y-Y_S)+a31*(Z-Z_S))/(a13*(X-X_S)+a23*(Y-Y_S)+a33*(Z-Z_S)) - x - d_x",
      "Fy": "y_0 - f*(a12*(X-X_S)+a22*(Y-Y_S)+a32*(Z-Z_S))/(a13*(X-X_S)+a23*(Y-Y_S)+a33*(Z-Z_S)) - y - d_y"},
     {"Fx": "x_0 - f*(a11*(X-X_S)+a12*(Y-Y_S)+a13*(Z-Z_S))/(a31*(X-X_S)+a32*(Y-Y_S)+a33*(Z-Z_S)) - x - d_x",
      "Fy": "y_0 - f*(a12*(X-X_S)+a22*(Y-Y_S)+a32*(Z-Z_S))/(a13*(X-X_S)+a23*(Y-Y_S)+a33*(Z-Z_S)) - y - d_y"}),
    ("chessboard_formula", {"Fx": "x_0 - f*X/Z - x - d_x", "Fy": "y_0 - f*Y/Z - y - d_y"},
     {"Fx": "x_0 - f*X/Z - x + d_x", "Fy": "y_0 - f*Y/Z - y - d_y"}),
    ("solution_formula", {"sign": -1}, {"sign": 1}),
    ("precision_formula", {"m_j": "mu*sqrt(Q_jj)"}, {"m_j": "mu*Q_jj"}),
    ("unit_weight_formula", {"denominator": "m - n"}, {"denominator": "m"}),
    ("tolerance_formula", {"m_XY": "Z_min/f*Delta/10", "precision_px": "1/10"},
     {"m_XY": "f/Z_min*Delta/10", "precision_px": "1/10"}),
])
def test_adapters_accept_the_derivation_and_reject_a_broken_form(adapter, good, bad):
    from photolib.book import ch11_calibration as c
    assert getattr(c, adapter)(good)["printed_equals_derived"]
    assert not getattr(c, adapter)(bad)["printed_equals_derived"]


# --- Table 11.3: the trend on simulation (not the book's numbers) ------------------------------------
def test_long_focus_simulation_common_centre_narrows_f_and_the_depth_error():
    """photolib.book.ch11_calibration.long_focus_run: in every seeded run the common centre gives the
    smaller σ_f (11.3.6) — a property of the geometry — and each calibration's true f error lies within
    4 of its own σ_f (honest accuracy); pooled over the runs the depth error m_Z shrinks."""
    from photolib.book import ch11_calibration as c
    runs = [c.long_focus_run(seed) for seed in range(4)]
    for r in runs:
        assert r["common_centre"]["sigma_f"] < r["classical"]["sigma_f"]
        for label in ("classical", "common_centre"):
            assert abs(r[label]["f_error"]) < 4 * r[label]["sigma_f"], (label, r[label])
    mz = {label: np.sqrt(np.mean([r[label]["rms"][2] ** 2 for r in runs])) for label in ("classical", "common_centre")}
    assert mz["common_centre"] < mz["classical"]


def test_long_focus_trend_table_shows_the_book_values_beside_the_simulation():
    from photolib.book import ch11_calibration as c
    table, numbers = c.long_focus_trend(n_runs=2)
    book = {q.name: q.printed for q in CH.example("11.3-table-11.3").quantities}
    assert [row[:3] for row in table.rows[:3]] == [[f"m_{k}", book[f"m{k}_classical"], book[f"m{k}_common_centre"]]
                                                   for k in "XYZ"]
    assert set(numbers) == {"classical", "common_centre"}


# --- the chessboard method on real images: photolib's calibration against OpenCV's -------------------
def test_real_chessboard_calibration_agrees_with_opencv_on_the_same_corners():
    """OpenCV's sample left*.jpg (13 views), photolib's corners: photolib.calibration.calibrate_chessboard
    against cv2.calibrateCamera on the same corners. The models differ (OpenCV distorts ideal
    coordinates and has f_x ≠ f_y), so f agrees to 0.2 % (benchmarks/calibration_chessboard.py), the
    principal point to 0.5 px and the r.m.s. reprojection error to 10 %."""
    cv2 = pytest.importorskip("cv2")
    from photolib import calibration as cal
    from photolib import datasets
    try:
        folder = datasets.data_path("calibration", "opencv_chessboard")
    except datasets.DataUnavailableError:
        pytest.skip("real data absent")
    paths = sorted(folder.glob("left*.jpg"))
    corners = [np.asarray(cal.find_chessboard(datasets.read_image(p), (9, 6), name=p.name), float) for p in paths]
    ours = cal.calibrate_chessboard(corners, (9, 6), 25.0, (480, 640))
    obj = np.array([(j * 25.0, i * 25.0, 0) for i in range(6) for j in range(9)], np.float32)
    rms, K, *_ = cv2.calibrateCamera([obj] * len(corners), [c.astype(np.float32).reshape(-1, 1, 2) for c in corners],
                                     (640, 480), None, None)
    assert ours.io.f == pytest.approx((K[0, 0] + K[1, 1]) / 2, rel=2e-3)
    assert abs(ours.io.x0 + 319.5 - K[0, 2]) < 0.5 and abs(239.5 - ours.io.y0 - K[1, 2]) < 0.5
    assert 0.9 * rms < ours.rms < 1.1 * rms
