"""Tests of photolib.calibration (Chapter 11, §11.3): synthetic ground truth and OpenCV as peers."""

import numpy as np
import pytest

from photolib import calibration as cal
from photolib.camera import ExteriorOrientation, InteriorOrientation
from photolib.errors import DegenerateGeometryError
from photolib.single_image import project

TRUE = InteriorOrientation(50.0, 0.12, -0.08, k1=-4e-5, k2=2e-8, k3=0.0, p1=3e-6, p2=-2e-6)


def _test_field():
    """A 3-D test field: far wall at Z = −8 m and rings of targets at −7.2, −6.4, −6.0 m (§11.3)."""
    g = np.mgrid[-2:2.01:0.5, -1.5:1.51:0.5].reshape(2, -1).T
    wall = np.column_stack([g, np.full(len(g), -8.0)])
    rings = [np.column_stack([2.0 * np.cos(t), 1.5 * np.sin(t), np.full_like(t, z)])
             for z in (-7.2, -6.4, -6.0) for t in [np.linspace(0, 2 * np.pi, 16, endpoint=False)]]
    return np.vstack([wall] + rings)


def test_self_calibration_recovers_io_and_distortion_within_3_sigma():
    rng = np.random.default_rng(11)
    XYZ = _test_field()
    eo = ExteriorOrientation(0.05, -0.03, 0.1, 0.01, -0.02, 0.03)
    sigma = 0.0005                                      # 0.5 μm
    xy = project(XYZ, eo, TRUE) + rng.normal(0, sigma, (len(XYZ), 2))
    r = cal.self_calibration(XYZ, xy, InteriorOrientation(49.0), [0, 0, 0, 0, 0, 0], sigma_image=sigma)
    assert len(r.names) == 14
    for name in cal.IO_NAMES:
        err = abs(getattr(r.io, name) - getattr(TRUE, name))
        assert err <= 3 * r.io_std[name], (name, err, r.io_std[name])
    dof = 2 * len(XYZ) - 14
    assert abs(r.mu / sigma - 1) < 3 / np.sqrt(2 * dof)          # 3σ of μ/σ (χ² with dof)


def test_frontal_flat_target_is_singular_and_oblique_views_cure_it():
    g = np.mgrid[-2:2.01:0.25, -1.5:1.51:0.25].reshape(2, -1).T
    flat = np.column_stack([g, np.zeros(len(g))])
    io = InteriorOrientation(50.0, 0.1, -0.1)
    frontal = project(flat, ExteriorOrientation(0, 0, 8.0, 0, 0, 0), io)
    with pytest.raises(DegenerateGeometryError, match="Z_S"):
        cal.self_calibration(flat, frontal, InteriorOrientation(49.0), [0, 0, 8.0, 0, 0, 0],
                             calibrate=("f", "x0", "y0"))
    rng = np.random.default_rng(3)
    eos, views = [], []
    for w, a in [(0.5, 0.0), (-0.5, 0.0), (0.0, 0.5), (0.0, -0.5)]:
        eo = ExteriorOrientation(8 * np.sin(a), -8 * np.sin(w), 8 * np.cos(w) * np.cos(a), w, a, 0.0)
        eos.append(eo)
        views.append(project(flat, eo, io) + rng.normal(0, 0.001, (len(flat), 2)))
    start = [[e.Xs + 0.1, e.Ys, e.Zs - 0.2, e.omega, e.alpha, 0.01] for e in eos]
    r = cal.self_calibration(flat, views, InteriorOrientation(49.0), start, calibrate=("f", "x0", "y0"),
                             sigma_image=0.001)
    for name in ("f", "x0", "y0"):
        assert abs(getattr(r.io, name) - getattr(io, name)) <= 3 * r.io_std[name]
    assert abs(r.correlation("f", "Z_S[0]")) < 0.99


def test_common_centre_long_focus():
    XYZ = _test_field()
    io = InteriorOrientation(200.0, 0.05, 0.02)
    views, start = [], []
    for k in (-0.1, 0.0, 0.1):
        for w in (-0.05, 0.05):
            eo = ExteriorOrientation(0.2, 0.1, 12.0, w, k, 0.0)
            sel = [i for i, p in enumerate(project(XYZ, eo, io)) if abs(p[0]) < 20 and abs(p[1]) < 15]
            views.append((XYZ[sel], project(XYZ[sel], eo, io)))
            start.append([0.0, 0.0, 11.5, w, k, 0.0])
    r = cal.self_calibration([v[0] for v in views], [v[1] for v in views], InteriorOrientation(190.0), start,
                             calibrate=("f", "x0", "y0"), common_centre=True, sigma_image=0.001)
    assert r.io.f == pytest.approx(200.0, abs=1e-6)
    assert r.eo[0].Zs == pytest.approx(12.0, abs=1e-8) and r.eo[3].Zs == r.eo[0].Zs


def _homography(omega, alpha, f=600.0, dist=10.0, shape=(480, 640)):
    from photolib.rotation import rotation_matrix
    A = rotation_matrix(omega, alpha, 0.0, "kaw")
    R = np.diag([1.0, -1.0, -1.0]) @ A.T
    centre = np.array([3.0, 2.0, 0.0]) + A @ np.array([0.0, 0.0, dist])
    t = -R @ centre
    K = np.array([[f, 0, (shape[1] - 1) / 2], [0, f, (shape[0] - 1) / 2], [0, 0, 1]])
    return K @ np.column_stack([R[:, 0], R[:, 1], t])


def test_chessboard_detection_on_a_rendered_board():
    H = _homography(0.35, -0.25)
    img = cal.render_chessboard((7, 5), 1.0, H, (480, 640))
    found = cal.find_chessboard(img, (6, 4), name="rendered")
    truth = np.array([(i, j) for j in range(1, 5) for i in range(1, 7)], dtype=float)
    t = (H @ np.column_stack([truth, np.ones(len(truth))]).T).T
    t = t[:, :2] / t[:, 2:]
    from scipy.spatial import cKDTree
    d, idx = cKDTree(t).query(found)
    assert len(set(idx)) == 24
    cv2 = pytest.importorskip("cv2")                    # the peer: cv2.cornerSubPix from the same start
    ref = cv2.cornerSubPix(np.clip(img, 0, 255).astype(np.float32), np.ascontiguousarray(np.round(t).reshape(-1, 1, 2), dtype=np.float32), (5, 5),
                           (-1, -1), (cv2.TERM_CRITERIA_EPS + cv2.TERM_CRITERIA_MAX_ITER, 50, 1e-4))
    d_cv = np.hypot(*(ref.reshape(-1, 2) - t).T)
    assert np.sqrt(np.mean(d ** 2)) <= max(np.sqrt(np.mean(d_cv ** 2)), 0.03)


def test_chessboard_calibration_on_rendered_views_matches_truth():
    corners = []
    for w, a in [(0.4, 0.0), (-0.4, 0.1), (0.1, 0.4), (0.0, -0.4), (0.3, 0.3)]:
        img = cal.render_chessboard((7, 5), 1.0, _homography(w, a), (480, 640))
        corners.append(cal.find_chessboard(img, (6, 4)))
    r = cal.calibrate_chessboard(corners, (6, 4), 1.0, (480, 640), calibrate=("f", "x0", "y0"))
    assert r.io.f == pytest.approx(600.0, rel=2e-3)
    assert abs(r.io.x0) < 1.0 and abs(r.io.y0) < 1.0
    assert r.rms < 0.05


def test_certificates_round_trip():
    c = {"f": 8075.4, "k1": -2.1391e-9, "k2": 2.8649e-17, "f_sigma": 0.4}
    back = cal.certificate_to_pixels(cal.certificate_to_mm(c, 0.0062), 0.0062)
    assert all(back[k] == pytest.approx(v, rel=1e-12) for k, v in c.items())
