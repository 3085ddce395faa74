"""The geometric conditions of §11.6 (11.6.1)–(11.6.7) added to the bundle adjustment (§3.5).

A synthetic terrestrial block: a façade (a wall at Y = 20 m with a projecting bay) seen by four
horizontal cameras (ω = 90°, sequence ω–α–κ) from a line 20 m in front of it. Expected values
come from the synthetic ground truth and from an independent solution of the same least-squares
problem by ``scipy.optimize.least_squares`` with the collinearity equations and the conditions
written out here in numpy (no photolib code in the residuals).
"""

import numpy as np
import pytest
from scipy.optimize import least_squares

from photolib import terrestrial
from photolib.bundle import bundle_adjustment, self_calibrating_bundle_adjustment
from photolib.camera import InteriorOrientation
from photolib.errors import DegenerateGeometryError, InputError
from photolib.synthetic import Observations

F_MM = 35.0
SIGMA = 0.002                    # image noise, mm
IO = InteriorOrientation(F_MM)


def _rotation(omega, alpha, kappa):
    """A = A_ω A_α A_κ of (1.3.2), written out independently of photolib.rotation."""
    co, so, ca, sa, ck, sk = np.cos(omega), np.sin(omega), np.cos(alpha), np.sin(alpha), np.cos(kappa), np.sin(kappa)
    Aw = np.array([[1, 0, 0], [0, co, -so], [0, so, co]])
    Aa = np.array([[ca, 0, sa], [0, 1, 0], [-sa, 0, ca]])
    Ak = np.array([[ck, -sk, 0], [sk, ck, 0], [0, 0, 1]])
    return Aw @ Aa @ Ak


def _project(cam, X):
    """Collinearity (1.4.12): x = −f·(AᵀΔX)_x/(AᵀΔX)_z, y likewise (x₀ = y₀ = 0)."""
    p = (X - cam[:3]) @ _rotation(*cam[3:])          # rows: (AᵀΔX)ᵀ
    return -F_MM * p[:, :2] / p[:, 2:]


def facade_block(sigma=SIGMA, seed=0):
    """Cameras (4, 6), points (k, 3), observations; points 0–3 the bay's corners (a vertical edge
    0–1, a horizontal edge 0–2), 4–7 four coplanar wall points, the rest wall and bay points."""
    rng = np.random.default_rng(seed)
    special = np.array([[-1.0, 18.5, 1.0], [-1.0, 18.5, 7.0], [3.0, 18.5, 1.0], [3.0, 18.5, 7.0],
                        [-7.0, 20.0, 0.5], [7.0, 20.0, 0.5], [-6.0, 20.0, 9.0], [6.5, 20.0, 8.5]])
    wall = np.column_stack([rng.uniform(-8, 8, 24), np.full(24, 20.0), rng.uniform(0, 10, 24)])
    bay = np.column_stack([rng.uniform(-1, 3, 8), np.full(8, 18.5), rng.uniform(1, 7, 8)])
    points = np.vstack([special, wall, bay])
    xs = np.array([-6.0, -2.0, 2.0, 6.0])
    cams = np.column_stack([xs, np.zeros(4), np.full(4, 1.6), np.full(4, np.pi / 2 + 0.08),
                            np.arctan2(xs, 20.0) * 0.8, rng.normal(0, 0.01, 4)])
    image = np.repeat(np.arange(4), len(points))
    point = np.tile(np.arange(len(points)), 4)
    xy = np.vstack([_project(c, points) for c in cams]) + rng.normal(0, sigma, (image.size, 2))
    return cams, points, Observations(image, point, xy)


def start_values(cams, points, seed=1):
    rng = np.random.default_rng(seed)
    c0 = cams + np.concatenate([rng.normal(0, 0.1, (4, 3)), rng.normal(0, 0.01, (4, 3))], axis=1)
    return c0, points + rng.normal(0, 0.2, points.shape)


def first_camera_fixed(cams, sigma_c=1e-4, sigma_a=1e-6):
    """GNSS centre and INS angles of image 0 only: shifts and rotations, but no scale."""
    gnss, ins = np.full((4, 3), np.nan), np.full((4, 3), np.nan)
    gnss[0], ins[0] = cams[0, :3], cams[0, 3:]
    return dict(gnss=gnss, ins=ins, sigma_centre=sigma_c, sigma_angles=sigma_a)


# --- the datum: a free network gets its scale from a measured length ----------------------------
def test_without_a_length_the_scale_is_a_datum_defect():
    cams, pts, obs = facade_block(sigma=0.0)
    c0, p0 = start_values(cams, pts)
    with pytest.raises(DegenerateGeometryError, match="6 of the 7"):
        bundle_adjustment(obs, c0, p0, IO, order="wak", **first_camera_fixed(cams))
    # conditions that do not fix the scale leave the defect
    with pytest.raises(DegenerateGeometryError, match="6 of the 7"):
        bundle_adjustment(obs, c0, p0, IO, order="wak", **first_camera_fixed(cams),
                          conditions=[("vertical", (0, 1), None, 0.001), ("coplanar", (4, 5, 6, 7), None, 0.01)])


@pytest.mark.parametrize("kind, idx", [("distance", (4, 7)), ("base", (0, 3)), ("centre_distance", (5, 2))])
def test_a_measured_length_fixes_the_scale(kind, idx):
    """Noise-free images, one length measured 1 % too long: the whole block is scaled by 1.01 about
    the fixed projection centre S₀ (rotations and shifts come from image 0, the scale from the length)."""
    cams, pts, obs = facade_block(sigma=0.0)
    c0, p0 = start_values(cams, pts)
    X = lambda what, i: cams[i, :3] if what == "image" else pts[i]          # noqa: E731
    items = {"distance": ("point", "point"), "base": ("image", "image"), "centre_distance": ("point", "image")}[kind]
    true_length = float(np.linalg.norm(X(items[0], idx[0]) - X(items[1], idx[1])))
    for factor in (1.0, 1.01):
        res = bundle_adjustment(obs, c0, p0, IO, order="wak", **first_camera_fixed(cams, 1e-7, 1e-9),
                                conditions=[(kind, idx, factor * true_length, 0.001)])
        S0 = cams[0, :3]
        np.testing.assert_allclose(res.points, S0 + factor * (pts - S0), atol=2e-5)
        np.testing.assert_allclose(res.cameras[:, :3], S0 + factor * (cams[:, :3] - S0), atol=2e-5)
        np.testing.assert_allclose(res.cameras[:, 3:], cams[:, 3:], atol=1e-7)
        assert res.dof == 2 * obs.image.size + 6 + 1 - (6 * 4 + 3 * len(pts))
        assert abs(res.condition_residuals[0]) < 1e-6


# --- conditions pull the points onto the truth -----------------------------------------------------
def _control(pts):
    return {i: pts[i] for i in (8, 9, 10, 11, 12)}


def test_vertical_and_horizontal_conditions_pull_the_points_onto_the_truth():
    """Noisy images, full control: the vertical edge 0–1 and the horizontal edge 0–2 (tight σ)
    are met by the adjusted points; the coordinates they tie (X, Y of points 0 and 1, Z of points 0
    and 2) get smaller a-posteriori errors m_j, and smaller true errors over eight seeded blocks."""
    conditions = [("vertical", (0, 1), None, 1e-5), ("horizontal", (0, 2), None, 1e-5)]

    def tied(P):
        return np.array([P[0, 0], P[0, 1], P[1, 0], P[1, 1], P[0, 2], P[2, 2]])

    err_free, err_cond = [], []
    for seed in range(8):
        cams, pts, obs = facade_block(seed=seed)
        c0, p0 = start_values(cams, pts, seed=seed + 10)
        plain = bundle_adjustment(obs, c0, p0, IO, order="wak", control=_control(pts))
        cond = bundle_adjustment(obs, c0, p0, IO, order="wak", control=_control(pts), conditions=conditions)
        P = cond.points
        assert abs(P[0, 0] - P[1, 0]) < 1e-4 and abs(P[0, 1] - P[1, 1]) < 1e-4 and abs(P[0, 2] - P[2, 2]) < 1e-4
        assert cond.condition_residuals.shape == (3,)
        assert np.all(tied(cond.points_std) < tied(plain.points_std))
        err_free.append(tied(plain.points - pts))
        err_cond.append(tied(cond.points - pts))
    assert np.sqrt(np.mean(np.square(err_cond))) < np.sqrt(np.mean(np.square(err_free)))


def test_the_plane_condition_puts_a_fourth_point_into_the_plane():
    cams, pts, obs = facade_block(seed=3)
    c0, p0 = start_values(cams, pts, seed=4)
    # σ of the determinant (m³) ≈ σ of the distance from the plane × |∂F/∂P_l| (twice a triangle's
    # area, ≈ 120 m² here): 1e-3 m³ holds the point to about 10 µm
    res = bundle_adjustment(obs, c0, p0, IO, order="wak", control=_control(pts),
                            conditions=[("coplanar", (4, 5, 6, 7), None, 1e-3)])
    F, _ = terrestrial.condition_equations("coplanar", [res.points[i][None] for i in (4, 5, 6, 7)])
    free = bundle_adjustment(obs, c0, p0, IO, order="wak", control=_control(pts))
    F0, _ = terrestrial.condition_equations("coplanar", [free.points[i][None] for i in (4, 5, 6, 7)])
    assert abs(F[0, 0]) < 0.01 * abs(F0[0, 0])
    assert abs(res.condition_residuals[0] - F[0, 0]) < 1e-6          # v of the condition = its misclosure


# --- an independent solution of the same problem ---------------------------------------------------
def _scipy_solution(obs, c0, p0, prior, conditions):
    """The same weighted least squares, residuals written out in numpy, solved by scipy.

    Returns the cameras, the points and the residual function (residuals / σ)."""
    n, k = len(c0), len(p0)

    def residuals(x):
        cams, pts = x[:6 * n].reshape(n, 6), x[6 * n:].reshape(k, 3)
        r = [np.concatenate([(_project(cams[i], pts[obs.point[obs.image == i]]) - obs.xy[obs.image == i]).ravel()
                             for i in range(n)]) / SIGMA]
        for i, values, sig in prior:
            r.append((cams[0, i] - values) / sig)
        for kind, idx, measured, sig in conditions:
            P = [cams[j, :3] if kind == "base" or (kind == "centre_distance" and s == 1) else pts[j]
                 for s, j in enumerate(idx)]
            if kind in ("distance", "base", "centre_distance"):
                F = [np.linalg.norm(P[0] - P[1]) - measured]
            elif kind == "vertical":
                F = [P[0][0] - P[1][0], P[0][1] - P[1][1]]
            elif kind == "horizontal":
                F = [P[0][2] - P[1][2]]
            else:
                F = [np.linalg.det(np.array([P[1] - P[0], P[2] - P[0], P[3] - P[0]]))]
            r.append(np.array(F) / sig)
        return np.concatenate([np.atleast_1d(v) for v in r])

    sol = least_squares(residuals, np.concatenate([c0.ravel(), p0.ravel()]), method="lm", xtol=1e-15, ftol=1e-15,
                        gtol=1e-15, max_nfev=20000)
    return sol.x[:6 * n].reshape(n, 6), sol.x[6 * n:].reshape(k, 3), residuals


def test_agrees_with_an_independent_scipy_solution():
    cams, pts, obs = facade_block(seed=5)
    c0, p0 = start_values(cams, pts, seed=6)
    d = float(np.linalg.norm(pts[4] - pts[7])) + 0.003
    B = float(np.linalg.norm(cams[0, :3] - cams[3, :3])) - 0.002
    D = float(np.linalg.norm(pts[5] - cams[2, :3])) + 0.004
    conditions = [("distance", (4, 7), d, 0.002), ("base", (0, 3), B, 0.001), ("centre_distance", (5, 2), D, 0.003),
                  ("vertical", (0, 1), None, 0.001), ("horizontal", (0, 2), None, 0.002),
                  ("coplanar", (4, 5, 6, 7), None, 0.05)]
    sig_c, sig_a = 0.01, 1e-4
    ours = bundle_adjustment(obs, c0, p0, IO, order="wak", **first_camera_fixed(cams, sig_c, sig_a),
                             conditions=conditions, sigma_image=SIGMA, tol_centre=1e-9, tol_angle=1e-12,
                             tol_point=1e-9)
    prior = [(slice(0, 3), cams[0, :3], sig_c), (slice(3, 6), cams[0, 3:], sig_a)]
    c_ref, p_ref, residuals = _scipy_solution(obs, c0, p0, prior, conditions)
    np.testing.assert_allclose(ours.points, p_ref, atol=1e-7)
    np.testing.assert_allclose(ours.cameras[:, :3], c_ref[:, :3], atol=1e-7)
    np.testing.assert_allclose(ours.cameras[:, 3:], c_ref[:, 3:], atol=1e-9)
    # μ (3.5.12) from the independent weighted residuals: VᵀPV/(m − n), unit weight σ_image
    vtpv = float(np.sum(residuals(np.concatenate([c_ref.ravel(), p_ref.ravel()])) ** 2)) * SIGMA ** 2
    assert ours.dof == 2 * obs.image.size + 6 + 7 - (6 * 4 + 3 * len(pts))
    assert abs(ours.mu - np.sqrt(vtpv / ours.dof)) < 1e-6 * ours.mu
    assert ours.condition_residuals.shape == (7,)


def test_self_calibrating_bundle_takes_conditions_too():
    """f free, one image known in position and attitude: the distance fixes the scale and f comes
    out right (noise-free), as the same problem with the scale from full control."""
    cams, pts, obs = facade_block(sigma=0.0)
    c0, p0 = start_values(cams, pts)
    d = float(np.linalg.norm(pts[4] - pts[7]))
    res = self_calibrating_bundle_adjustment(obs, c0, p0, InteriorOrientation(F_MM - 0.5), calibrate=("f",),
                                             order="wak", **first_camera_fixed(cams, 1e-7, 1e-9),
                                             conditions=[("distance", (4, 7), d, 1e-4)])
    assert abs(res.io.f - F_MM) < 1e-5
    np.testing.assert_allclose(res.points, pts, atol=1e-4)
    assert res.correlations.names == ("f",) and res.condition_residuals.shape == (1,)


def test_bad_conditions_are_named():
    cams, pts, obs = facade_block(sigma=0.0)
    c0, p0 = start_values(cams, pts)
    for conditions, match in (([("distance", (0, 1), 5.0)], "expected"),
                              ("distance", "list of"),
                              ([("slope", (0, 1), None, 0.01)], "unknown condition"),
                              ([("distance", (0, 99), 5.0, 0.01)], "outside"),
                              ([("base", (0, 4), 5.0, 0.01)], "outside"),
                              ([("distance", (0, 1.5), 5.0, 0.01)], "integer"),
                              ([("distance", (0, 1), float("nan"), 0.01)], "measured"),
                              ([("distance", (0, 1), None, 0.01)], "measured"),
                              ([("vertical", (0, 1), 2.0, 0.01)], "no measured"),
                              ([("vertical", (0, 0), None, 0.01)], "twice"),
                              ([("coplanar", (0, 1, 2), None, 0.01)], "4 integer"),
                              ([("horizontal", (0, 1), None, 0.0)], "sigma")):
        with pytest.raises(InputError, match=match):
            bundle_adjustment(obs, c0, p0, IO, order="wak", control=_control(pts), conditions=conditions)


def test_a_condition_of_no_weight_leaves_the_block_solution():
    """The dense path with a condition of negligible weight gives the block solver's result:
    the same control (weighted, with a height-only point), GNSS and INS rows, the same m_j."""
    cams, pts, obs = facade_block(seed=2)
    c0, p0 = start_values(cams, pts, seed=3)
    control = {8: pts[8], 9: pts[9], 10: pts[10], 11: [np.nan, np.nan, pts[11, 2]]}
    gnss = cams[:, :3] + np.random.default_rng(4).normal(0, 0.02, (4, 3))
    ins = np.full((4, 3), np.nan)
    ins[1] = cams[1, 3:]
    kw = dict(order="wak", control=control, sigma_control=0.005, gnss=gnss, sigma_centre=0.02, ins=ins,
              sigma_angles=1e-3, sigma_image=SIGMA, tol_point=1e-9, tol_centre=1e-9, tol_angle=1e-12)
    block = bundle_adjustment(obs, c0, p0, IO, **kw)
    dense = bundle_adjustment(obs, c0, p0, IO, conditions=[("horizontal", (0, 3), None, 1e9)], **kw)
    np.testing.assert_allclose(dense.points, block.points, atol=1e-8)
    np.testing.assert_allclose(dense.cameras, block.cameras, atol=1e-8)
    assert dense.dof == block.dof + 1
    ratio = dense.mu / block.mu
    np.testing.assert_allclose(dense.points_std, ratio * block.points_std, rtol=1e-6)
    np.testing.assert_allclose(dense.cameras_std, ratio * block.cameras_std, rtol=1e-6)
    np.testing.assert_allclose(dense.control_residuals, block.control_residuals, atol=1e-8)
    np.testing.assert_allclose(dense.gnss_residuals, block.gnss_residuals, atol=1e-8)
    np.testing.assert_allclose(dense.ins_residuals, block.ins_residuals, atol=1e-10)
    np.testing.assert_allclose(dense.residuals, block.residuals, atol=1e-9)
