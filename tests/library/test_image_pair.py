"""Chapter 2 (theory of a pair of frame images): photolib.image_pair and the Chapter 2 sympy models.

Expected values come from synthetic ground truth, sympy, OpenCV (triangulatePoints,
findEssentialMat/recoverPose), scipy (least_squares, Rotation.align_vectors) and the book's
stated inline numbers — never from photolib's own output.
"""

import cv2
import numpy as np
import pytest
import sympy as sp
from scipy.optimize import least_squares
from scipy.spatial.transform import Rotation

from photolib import derivations as d
from photolib import image_pair as ip
from photolib.camera import ExteriorOrientation, InteriorOrientation
from photolib.conventions import camera_matrix, eo_to_opencv, image_to_opencv, opencv_projection_matrix
from photolib.errors import DegenerateGeometryError, InputError
from photolib.single_image import project

IO = InteriorOrientation(100.0, 0.02, -0.01)
D = np.diag([1.0, -1.0, -1.0])     # book camera frame ↔ OpenCV camera frame


def make_pair(seed=0, n=24, order="kaw"):
    """Aerial pair: f = 100 mm, H ≈ 1000 m, scale 1:10 000, base ≈ 400 m (60 % overlap of a 100 mm frame)."""
    rng = np.random.default_rng(seed)
    eo1 = ExteriorOrientation.from_degrees(1000, 1000, 1000, *rng.uniform(-2, 2, 3), order=order)
    eo2 = ExteriorOrientation.from_degrees(1400, 1000 + rng.uniform(-10, 10), 1000 + rng.uniform(-10, 10),
                                           *rng.uniform(-2, 2, 3), order=order)
    XYZ = np.column_stack([rng.uniform(920, 1480, n), rng.uniform(560, 1440, n), rng.uniform(-20, 20, n)])
    return eo1, eo2, XYZ, project(XYZ, eo1, IO), project(XYZ, eo2, IO)


def true_dependent_elements(eo1, eo2):
    """Relative orientation in the system b_y b_z ω'₂ α'₂ κ'₂ from the true EO: the model frame is camera 1's."""
    A2p = eo1.matrix.T @ eo2.matrix
    b = eo1.matrix.T @ (eo2.center - eo1.center)
    return A2p, b / b[0]


# --- §2.1, §2.3 ---------------------------------------------------------------------------------------
def test_stereo_vision_radius_book_statement():
    # §2.1: R = 65 mm × 200 000″ / 30″ "= 430 m" — the book rounds ρ″ and the result.
    R_book = ip.stereo_vision_radius(0.065, 30, rho=200_000)
    assert R_book == pytest.approx(65 * 200_000 / 30 / 1000)
    assert round(R_book, -1) == 430
    assert ip.stereo_vision_radius(0.065, 30) == pytest.approx(0.065 * 206264.806 / 30, rel=1e-8)   # 447 m
    assert ip.stereo_vision_radius(0.065, 30, B=0.13, V=8) == pytest.approx(16 * ip.stereo_vision_radius(0.065, 30))


def test_depth_change_is_the_derivative_of_the_convergence_angle():
    b, L, g = sp.symbols("b L gamma", positive=True)
    dL_dgamma = sp.diff(b / g, g).subs(g, b / L)                                    # L = b/γ (2.1.1)
    assert sp.simplify(dL_dgamma + L ** 2 / b) == 0                                # (2.1.3)
    assert ip.depth_change(0.065, 10.0, 1e-6) == pytest.approx(float(dL_dgamma.subs({b: 0.065, L: 10.0})) * 1e-6)
    assert ip.convergence_angle(0.065, 10.0) == pytest.approx(0.0065)


def test_parallaxes():
    p, q = ip.parallaxes([[5.229, -0.003], [57.529, -0.898]], [[-52.662, 0.034], [-1.741, -1.753]])
    np.testing.assert_allclose(p, [57.891, 59.270])
    np.testing.assert_allclose(q, [-0.037, 0.855])


# --- §2.4–§2.5 forward intersection -----------------------------------------------------------------------
def test_forward_intersection_matches_opencv_triangulate_points():
    eo1, eo2, XYZ, xy1, xy2 = make_pair(1)
    P1, P2 = opencv_projection_matrix(eo1, IO), opencv_projection_matrix(eo2, IO)
    np.testing.assert_allclose(P1, camera_matrix(IO) @ np.column_stack(eo_to_opencv(eo1)))
    Xh = cv2.triangulatePoints(P1, P2, image_to_opencv(xy1).T, image_to_opencv(xy2).T)
    X_cv = (Xh[:3] / Xh[3]).T
    np.testing.assert_allclose(X_cv, XYZ, atol=1e-5)
    for method in ("closest", "norm", "component"):
        np.testing.assert_allclose(ip.forward_intersection(xy1, xy2, eo1, eo2, IO, method=method), X_cv, atol=1e-5)
    np.testing.assert_allclose(ip.intersect_rays([xy1, xy2], [eo1, eo2], IO).points, XYZ, atol=1e-6)


def test_closed_forms_equal_least_squares_for_exact_data_and_all_formulas_agree():
    eo1, eo2, XYZ, xy1, xy2 = make_pair(2)
    lsq = ip.intersect_rays([xy1, xy2], [eo1, eo2], IO)
    assert np.all(lsq.mu < 1e-9)
    for method, formula in [("closest", None), ("norm", None), ("component", None), ("component", 2)]:
        np.testing.assert_allclose(ip.forward_intersection(xy1, xy2, eo1, eo2, IO, method=method, formula=formula),
                                   lsq.points, atol=1e-6)


def test_least_squares_intersection_matches_scipy_on_noisy_multi_image_data():
    eo1, eo2, XYZ, xy1, xy2 = make_pair(3, n=6)
    eo3 = ExteriorOrientation.from_degrees(1200, 1350, 1010, 1.0, -1.0, 30.0)
    rng = np.random.default_rng(33)
    xys = [xy + rng.normal(0, 0.005, xy.shape) for xy in (xy1, xy2, project(XYZ, eo3, IO))]
    eos = [eo1, eo2, eo3]
    res = ip.intersect_rays(xys, eos, IO)
    for j in range(len(XYZ)):
        fun = lambda P: np.concatenate([(project(P, eo, IO)[0] - xy[j]) for eo, xy in zip(eos, xys)])  # noqa: E731
        ref = least_squares(fun, XYZ[j] + 1.0, xtol=1e-14, ftol=1e-14, gtol=1e-14)
        np.testing.assert_allclose(res.points[j], ref.x, atol=1e-6)
        dof = 2 * len(eos) - 3
        s2 = 2 * ref.cost / dof
        cov = s2 * np.linalg.inv(ref.jac.T @ ref.jac)
        assert res.mu[j] == pytest.approx(np.sqrt(s2), rel=1e-5)
        np.testing.assert_allclose(res.std[j], np.sqrt(np.diag(cov)), rtol=1e-4)


def test_component_formulas_follow_the_well_conditioned_denominator():
    # Normal case: base along X and y1 = y2, so r1 × r2 has a zero first component. The
    # first formula of (2.4.12) is 0/0 and must be refused; the default picks the second.
    x1, y1, x2 = np.array([10.0, -20.0, 30.0]), np.array([5.0, 0.0, -40.0]), np.array([-30.0, -60.0, -12.0])
    eo1 = ExteriorOrientation(0, 0, 0)
    eo2 = ExteriorOrientation(400, 0, 0)
    io = InteriorOrientation(100.0)
    xy1, xy2 = np.column_stack([x1, y1]), np.column_stack([x2, y1])
    expected = ip.normal_case_intersection(x1, y1, x2, 100.0, 400.0)
    with pytest.raises(DegenerateGeometryError, match="formula 1"):
        ip.forward_intersection(xy1, xy2, eo1, eo2, io, method="component", formula=1)
    for formula in (None, 2):
        np.testing.assert_allclose(ip.forward_intersection(xy1, xy2, eo1, eo2, io, method="component", formula=formula),
                                   expected, rtol=1e-12)


def test_normal_case_formulas_2_5_1_and_2_5_4():
    B, f, x1, x2, y1 = sp.symbols("B f x_1 x_2 y_1", real=True)
    r1, r2, base = sp.Matrix([x1, y1, -f]), sp.Matrix([x2, y1, -f]), sp.Matrix([B, 0, 0])
    N = base.cross(r2)[1] / r1.cross(r2)[1]                      # 2nd formula of (2.4.12)
    assert sp.simplify(N - B / (x1 - x2)) == 0                   # (2.5.1)
    Zs = -N * f
    assert sp.simplify(N * x1 - (-Zs / f * x1)) == 0             # (2.5.4)
    # numbers: a normal pair projected with the collinearity equations
    rng = np.random.default_rng(4)
    XYZ = np.column_stack([rng.uniform(-100, 500, 10), rng.uniform(-300, 300, 10), rng.uniform(-1020, -980, 10)])
    io = InteriorOrientation(100.0)
    xy1 = project(XYZ, ExteriorOrientation(0, 0, 0), io)
    xy2 = project(XYZ, ExteriorOrientation(400, 0, 0), io)
    np.testing.assert_allclose(xy1[:, 1], xy2[:, 1], atol=1e-12)
    np.testing.assert_allclose(ip.normal_case_intersection(xy1[:, 0], xy1[:, 1], xy2[:, 0], 100.0, 400.0),
                               XYZ, atol=1e-9)


def test_intersection_bad_input():
    eo1, eo2, XYZ, xy1, xy2 = make_pair(5, n=5)
    with pytest.raises(DegenerateGeometryError, match="parallel"):
        ip.intersection_scale([400, 0, 0], [[1, 2, -100]], [[2, 4, -200]])
    with pytest.raises(DegenerateGeometryError, match="parallel"):
        ip.forward_intersection(xy1, xy1, eo1, ExteriorOrientation(*eo2.center, *[eo1.omega, eo1.alpha, eo1.kappa]), IO)
    with pytest.raises(DegenerateGeometryError, match="coincide"):
        ip.forward_intersection(xy1, xy2, eo1, eo1, IO)
    with pytest.raises(DegenerateGeometryError, match="parallax"):
        ip.normal_case_intersection([1.0], [0.0], [1.0], 100.0, 400.0)
    bad = xy1.copy()
    bad[2, 0] = np.nan
    with pytest.raises(InputError, match="NaN"):
        ip.forward_intersection(bad, xy2, eo1, eo2, IO)
    with pytest.raises(InputError, match="NaN"):
        ip.intersect_rays([bad, xy2], [eo1, eo2], IO)
    with pytest.raises(InputError, match="at least two images"):
        ip.intersect_rays([xy1], [eo1], IO)
    with pytest.raises(InputError):
        ip.forward_intersection(xy1, xy2[:3], eo1, eo2, IO)


# --- §2.7–§2.8 relative orientation: symbolic checks ----------------------------------------------------------
def test_coplanarity_coefficients_a1_a2_are_the_printed_determinants():
    phi = d.coplanarity_model("dependent").residuals[0]
    X2, Y2, Z2 = d.rotation_matrix_symbolic("kaw", d.omega2, d.alpha2, d.kappa2) * sp.Matrix([d.x2, d.y2, -d.f2])
    a1 = -sp.Matrix([[d.x1, -d.f1], [X2, Z2]]).det()
    a2 = sp.Matrix([[d.x1, d.y1], [X2, Y2]]).det()
    assert sp.simplify(sp.diff(phi, d.b_y) - a1) == 0
    assert sp.simplify(sp.diff(phi, d.b_z) - a2) == 0
    # a3..a5: the determinant with the derivatives of (X'2, Y'2, Z'2) in its last row
    for th in (d.omega2, d.alpha2, d.kappa2):
        row = [sp.diff(v, th) for v in (X2, Y2, Z2)]
        a = sp.Matrix([[1, d.b_y, d.b_z], [d.x1, d.y1, -d.f1], row]).det()
        assert sp.simplify(sp.diff(phi, th) - a) == 0
    # (2.7.4): with b_y = b_z = ω'1 = 0 the condition is Y'1 Z'2 − Y'2 Z'1
    phi_i = d.coplanarity_model("independent").residuals[0]
    r1 = d.rotation_matrix_symbolic("kaw", 0, d.alpha1, d.kappa1) * sp.Matrix([d.x1, d.y1, -d.f1])
    assert sp.simplify(phi_i - (r1[1] * Z2 - Y2 * r1[2])) == 0


def test_printed_relative_orientation_partials_have_the_wrong_sign_on_every_f_term():
    printed = d.printed_relative_orientation_partials()
    plus_f = d.derived_relative_orientation_partials("kaw", z_sign=+1)
    correct = d.derived_relative_orientation_partials("kaw", z_sign=-1)
    assert all(sp.simplify(printed[k] - plus_f[k]) == 0 for k in printed)       # = ∂A/∂θ·(x, y, +f)
    wrong = [k for k in printed if sp.simplify(printed[k] - correct[k]) != 0]
    assert len(wrong) == 8 and ("Z", "kappa") not in wrong                      # all but ∂Z'/∂κ = 0
    for k in wrong:   # the difference is exactly the f-terms: it vanishes for f = 0
        assert sp.simplify((printed[k] - correct[k]).subs(d.f2, 0)) == 0


def test_y_parallax_2_8_2_is_the_difference_of_normal_case_ordinates():
    X1, Y1, Z1, X2, Y2, Z2, f = sp.symbols("X1 Y1 Z1 X2 Y2 Z2 f")
    q = -f / (Z1 * Z2) * sp.Matrix([[1, 0, 0], [X1, Y1, Z1], [X2, Y2, Z2]]).det()
    assert sp.simplify(q - (-f * Y1 / Z1 + f * Y2 / Z2)) == 0
    r1, r2 = np.array([[10.0, 20.0, -100.0]]), np.array([[-30.0, 19.0, -101.0]])
    assert ip.y_parallax([1, 0, 0], r1, r2, 100.0)[0] == pytest.approx(-100 * 20 / -100 + 100 * 19 / -101)


# --- §2.7–§2.8 relative orientation: numbers ---------------------------------------------------------------
@pytest.mark.parametrize("order", ["kaw", "wak"])
def test_relative_orientation_recovers_the_true_elements(order):
    eo1, eo2, XYZ, xy1, xy2 = make_pair(6, order=order)
    A2p, b = true_dependent_elements(eo1, eo2)
    dep = ip.relative_orientation(xy1, xy2, IO, system="dependent", order=order)
    np.testing.assert_allclose(dep.A2, A2p, atol=1e-10)
    np.testing.assert_allclose(dep.base, b, atol=1e-10)
    np.testing.assert_allclose(dep.q, 0, atol=1e-9)
    ind = ip.relative_orientation(xy1, xy2, IO, system="independent", order=order)
    assert ind.omega1 == ind.b_y == ind.b_z == 0
    np.testing.assert_allclose(ind.A1.T @ ind.A2, A2p, atol=1e-10)                  # same relative rotation
    np.testing.assert_allclose(ind.A1.T @ [1, 0, 0], b / np.linalg.norm(b), atol=1e-10)   # base along X_M
    np.testing.assert_allclose(ind.q, 0, atol=1e-9)


def test_relative_orientation_agrees_with_opencv_essential_matrix():
    eo1, eo2, XYZ, xy1, xy2 = make_pair(7, n=30)
    ro = ip.relative_orientation(xy1, xy2, IO)
    K = camera_matrix(IO)
    u1, u2 = image_to_opencv(xy1), image_to_opencv(xy2)
    E, _ = cv2.findEssentialMat(u1, u2, K, method=cv2.RANSAC, prob=0.999999, threshold=1e-4)
    _, R_cv, t_cv, _ = cv2.recoverPose(E[:3], u1, u2, K)
    # OpenCV: x_cv2 = R x_cv1 + t with x_cv = D·(camera frame of the book) ⇒ R = D A'₂ᵀ D, t ∝ −R D b
    np.testing.assert_allclose(D @ R_cv.T @ D, ro.A2, atol=1e-7)
    t_expected = -R_cv @ D @ ro.base
    np.testing.assert_allclose(t_cv.ravel(), t_expected / np.linalg.norm(t_expected), atol=1e-7)


def test_relative_orientation_accuracy_matches_monte_carlo():
    # m_j = μ√Q_jj (1.8.8) from the correct (sympy) Jacobian must describe the actual scatter of
    # the elements. 400 seeded noisy copies of one pair, σ = 5 µm: the sample standard deviation
    # has a relative standard error of 1/√800 ≈ 3.5 %; 15 % is > 4 of those.
    eo1, eo2, XYZ, xy1, xy2 = make_pair(8, n=18)
    rng = np.random.default_rng(88)
    est, pred = [], []
    for _ in range(400):
        ro = ip.relative_orientation(xy1 + rng.normal(0, 0.005, xy1.shape), xy2 + rng.normal(0, 0.005, xy2.shape),
                                     IO, tol=1e-11)
        est.append(ro.adjustment.x)
        pred.append(ro.adjustment.std)
    ratio = np.std(est, axis=0, ddof=1) / np.sqrt(np.mean(np.square(pred), axis=0))
    np.testing.assert_allclose(ratio, 1.0, atol=0.15)


def test_relative_orientation_bad_input():
    eo1, eo2, XYZ, xy1, xy2 = make_pair(9, n=8)
    with pytest.raises(InputError, match="at least 5"):
        ip.relative_orientation(xy1[:4], xy2[:4], IO)
    line = np.column_stack([np.linspace(950, 1450, 8), np.linspace(600, 1400, 8), np.zeros(8)])
    with pytest.raises(DegenerateGeometryError, match="one line"):
        ip.relative_orientation(project(line, eo1, IO), project(line, eo2, IO), IO)
    bad = xy2.copy()
    bad[0, 1] = np.nan
    with pytest.raises(InputError, match="NaN"):
        ip.relative_orientation(xy1, bad, IO)
    with pytest.raises(InputError, match="system"):
        ip.relative_orientation(xy1, xy2, IO, system="mixed")


# --- §2.9–§2.12 the double-resection chain ------------------------------------------------------------------
@pytest.mark.parametrize("system", ["dependent", "independent"])
def test_noise_free_chain_recovers_the_exterior_orientation(system):
    eo1, eo2, XYZ, xy1, xy2 = make_pair(10)
    ro = ip.relative_orientation(xy1, xy2, IO, system=system)
    model = ip.build_model(xy1, xy2, ro, IO, base_length=100.0)
    assert model.eo2.Xs == 100.0
    T = ip.absolute_orientation(model.points[:6], XYZ[:6], order="wak")
    np.testing.assert_allclose(T.apply(model.points), XYZ, atol=1e-6)
    np.testing.assert_allclose(T.inverse(XYZ), model.points, atol=1e-8)
    e1, e2 = ip.image_orientation_from_model(model, T, order="kaw")
    for est, true in ((e1, eo1), (e2, eo2)):
        np.testing.assert_allclose(est.center, true.center, atol=1e-6)
        np.testing.assert_allclose([est.omega, est.alpha, est.kappa], [true.omega, true.alpha, true.kappa], atol=1e-9)


def test_noisy_chain_is_within_the_predicted_accuracy():
    eo1, eo2, XYZ, xy1, xy2 = make_pair(11, n=40)
    rng = np.random.default_rng(111)
    sigma = 0.005
    n1, n2 = xy1 + rng.normal(0, sigma, xy1.shape), xy2 + rng.normal(0, sigma, xy2.shape)
    ro = ip.relative_orientation(n1, n2, IO)
    A2p, b = true_dependent_elements(eo1, eo2)
    true = np.r_[b[1:], Rotation.from_matrix(A2p).as_euler("xyz")]   # kaw = A_κ A_α A_ω: extrinsic x, y, z
    assert np.all(np.abs(ro.adjustment.x - true) < 4 * ro.adjustment.std)
    model = ip.build_model(n1, n2, ro, IO, base_length=100.0)
    control, check = slice(0, 10), slice(10, None)
    T = ip.absolute_orientation(model.points[control], XYZ[control])
    # check points against (2.13.3), H = 1000 m, b = B/m = 400 m / 10 000 = 40 mm, m_p = √2·σ
    H, base = 1000.0, 40.0
    m = np.array(ip.normal_case_accuracy(H, IO.f, base, sigma, sigma, np.sqrt(2) * sigma, approximate=True))
    # (2.13.3) ignores the errors of relative and absolute orientation and of the tilts, and the
    # r.m.s. of 30 check points has a sampling error of ≈ 13 %: accept 0.5–1.5 times the prediction.
    err = T.apply(model.points[check]) - XYZ[check]
    rms = np.sqrt(np.mean(err ** 2, axis=0))
    assert np.all(rms < 1.5 * m) and np.all(rms > 0.5 * m)


# --- §2.10–§2.11 similarity transform -----------------------------------------------------------------------
def _random_similarity(rng, order="kaw"):
    return ip.SimilarityTransform(*rng.uniform(-500, 500, 3), *np.radians(rng.uniform(-30, 30, 3)),
                                  rng.uniform(2, 8), order=order)


@pytest.mark.parametrize("order", ["kaw", "wak"])
def test_similarity_exact_recovery_from_full_and_height_only_control(order):
    rng = np.random.default_rng(12)
    truth = _random_similarity(rng, order)
    XM = rng.uniform(-100, 100, (6, 3))
    XYZ = truth.apply(XM)
    full = ip.absolute_orientation(XM, XYZ, order=order)
    np.testing.assert_allclose(full.vector, truth.vector, atol=1e-9)
    assert full.adjustment.mu < 1e-8
    np.testing.assert_allclose(ip.similarity_closed_form(XM, XYZ, order).vector, truth.vector, atol=1e-9)
    # near-vertical model (the height-only start assumes ω, α small)
    vertical = ip.SimilarityTransform(1000, 2000, 900, 0.02, -0.03, 0.7, 5.0, order)
    XYZ_v = vertical.apply(XM)
    for mask_rows in ([(1, 1, 1), (1, 1, 1), (0, 0, 1)],                         # 2 full + 1 height
                      [(1, 1, 0), (1, 1, 0), (0, 0, 1), (0, 0, 1), (0, 0, 1)]):  # 2 planimetric + 3 height
        mask = np.zeros(XM.shape, bool)
        mask[:len(mask_rows)] = np.array(mask_rows, bool)
        ctrl = np.where(mask, XYZ_v, np.nan)
        res = ip.absolute_orientation(XM, ctrl, components=mask, order=order)
        np.testing.assert_allclose(res.vector, vertical.vector, atol=1e-8)
        assert np.all(np.isnan(res.residuals[~mask]))


def test_similarity_matches_umeyama_reference_on_noisy_data():
    # Reference: scipy's Kabsch rotation (Rotation.align_vectors) of the centred sets, then the
    # least-squares scale t = Σ c_Oᵀ R c_M / Σ|c_M|² and shift — the same criterion as (2.11.1).
    rng = np.random.default_rng(13)
    truth = _random_similarity(rng)
    XM = rng.uniform(-100, 100, (15, 3))
    XYZ = truth.apply(XM) + rng.normal(0, 0.05, (15, 3))
    cM, cO = XM - XM.mean(0), XYZ - XYZ.mean(0)
    R = Rotation.align_vectors(cO, cM)[0].as_matrix()
    t = np.sum(cO * (cM @ R.T)) / np.sum(cM ** 2)
    shift = XYZ.mean(0) - t * R @ XM.mean(0)
    res = ip.absolute_orientation(XM, XYZ)
    np.testing.assert_allclose(res.matrix, R, atol=1e-10)
    assert res.t == pytest.approx(t, rel=1e-10)
    np.testing.assert_allclose(res.shift, shift, atol=1e-7)
    v = res.residuals.ravel()
    assert res.adjustment.mu == pytest.approx(np.sqrt(v @ v / (45 - 7)), rel=1e-8)


def test_printed_2_11_partials_omega_kappa_t_agree_with_sympy_for_wak():
    # Not used by the library (it derives its own); documents the book's partials for the "as printed" mode.
    J = d.similarity_model("wak").jacobian()
    A = d.rotation_matrix_symbolic("wak", d.omegaM, d.alphaM, d.kappaM)
    a = lambda i, j: A[i - 1, j - 1]  # noqa: E731
    XM, YM, ZM, t = d.XM, d.YM, d.ZM, d.t_M
    omega_col = [0, (a(3, 1) * XM + a(3, 2) * YM + a(3, 3) * ZM) * t, -(a(2, 1) * XM + a(2, 2) * YM + a(2, 3) * ZM) * t]
    for i in range(3):
        r = i + 1
        assert sp.simplify(J[i, 3] - omega_col[i]) == 0
        assert sp.simplify(J[i, 5] - (-a(r, 2) * XM + a(r, 1) * YM) * t) == 0
        assert sp.simplify(J[i, 6] + (a(r, 1) * XM + a(r, 2) * YM + a(r, 3) * ZM)) == 0
        printed_alpha = (a(r, 3) * sp.cos(d.kappaM) * XM + a(r, 3) * sp.sin(d.kappaM) * YM
                         - (a(r, 1) * sp.cos(d.kappaM) + a(r, 2) * sp.sin(d.kappaM)) * ZM) * t
        assert sp.simplify(J[i, 4] - printed_alpha) != 0                        # wrong sin κ signs …
        assert sp.simplify((J[i, 4] - printed_alpha).subs(d.kappaM, 0)) == 0      # … invisible at κ_M = 0


def test_similarity_bad_input():
    rng = np.random.default_rng(14)
    truth = _random_similarity(rng)
    XM = rng.uniform(-100, 100, (5, 3))
    XYZ = truth.apply(XM)
    line = np.outer(np.arange(5.0), [1.0, 2.0, 0.5])
    with pytest.raises(DegenerateGeometryError, match="one line"):
        ip.absolute_orientation(line, truth.apply(line))
    # 2 full points and a height point on their line: the rotation about the line is free
    XM3 = np.array([[0.0, 0, 0], [10, 5, 2], [5, 2.5, 1], [20, 10, 4]])
    mask = np.array([[1, 1, 1], [1, 1, 1], [0, 0, 1], [0, 0, 0]], bool)
    with pytest.raises(DegenerateGeometryError):
        ip.absolute_orientation(XM3, np.where(mask, truth.apply(XM3), np.nan), components=mask)
    mask = np.zeros((5, 3), bool)
    mask[0] = mask[1] = True
    with pytest.raises(InputError, match="at least 7"):
        ip.absolute_orientation(XM, XYZ, components=mask)
    bad = XYZ.copy()
    bad[1, 2] = np.nan
    with pytest.raises(InputError, match="NaN"):
        ip.absolute_orientation(XM, bad)


# --- §2.13 a-priori accuracy --------------------------------------------------------------------------------
def test_normal_case_accuracy_matches_monte_carlo_of_2_5_3():
    H, f, B, mx, mp = 1000.0, 100.0, 400.0, 0.005, 0.007
    b = B / H * f                                          # photo base at image scale, 40 mm
    x1, y1 = 30.0, -45.0
    x2 = x1 - b                                            # flat terrain: p = b (Fig. 2.18)
    rng = np.random.default_rng(15)
    n = 40_000
    X = ip.normal_case_intersection(x1 + rng.normal(0, mx, n), y1 + rng.normal(0, mx, n),
                                    x2 + rng.normal(0, np.sqrt(mp ** 2 - mx ** 2), n), f, B)
    # x1 and x2 noise give m_p; X and Z then correlate through x1, which (2.13.1) ignores — so
    # compare m_Y and m_Z (sample s.d. error ≈ 0.35 %, tolerance 2 %)
    m_X, m_Y, m_Z = ip.normal_case_accuracy(H, f, b, mx, mx, mp, x=x1, y=y1)
    assert np.std(X[:, 2]) == pytest.approx(m_Z, rel=0.02)
    assert np.std(X[:, 1]) == pytest.approx(m_Y, rel=0.02)
    assert m_Z == pytest.approx(H / b * mp)
    assert m_X >= H / f * mx
    assert ip.photo_base(56.9, 60) == pytest.approx(22.76)


def test_non_convergence_is_reported_clearly():
    """Too few iterations, or the slowly converging as-printed Jacobian, raise ConvergenceError with a history."""
    from photolib.errors import ConvergenceError
    eo1, eo2, XYZ, xy1, xy2 = make_pair(3)
    xy2 = xy2 + np.random.default_rng(3).normal(0, 0.005, xy2.shape)
    io = InteriorOrientation(100.0)
    with pytest.raises(ConvergenceError) as info:
        ip.relative_orientation(xy1, xy2, io, max_iter=2)
    assert len(info.value.history) == 2
    with pytest.raises(ConvergenceError):
        ip.relative_orientation(xy1, xy2, io, system="independent", jacobian="printed", max_iter=6)
    model = ip.build_model(xy1, xy2, ip.relative_orientation(xy1, xy2, io), io, base_length=400.0)
    far = ip.SimilarityTransform(0.0, 0.0, 0.0, 0.3, -0.2, 1.0, 1.0)     # a poor start instead of the closed form
    with pytest.raises(ConvergenceError):
        ip.absolute_orientation(model.points, XYZ, initial=far, max_iter=3)


@pytest.mark.parametrize("system", ["dependent", "independent"])
def test_double_resection_in_one_call_recovers_points_and_orientation(system):
    """§2.6: RO → model → model EO from 4 control points → all points and both images' EO, noise-free."""
    eo1, eo2, XYZ, xy1, xy2 = make_pair(5)
    control = np.full_like(XYZ, np.nan)
    control[[0, 5, 10, 15]] = XYZ[[0, 5, 10, 15]]
    result = ip.double_resection(xy1, xy2, IO, control, system=system, base_length=0.04)
    np.testing.assert_allclose(result.object_points, XYZ, atol=1e-6)
    for got, truth in ((result.eo1, eo1), (result.eo2, eo2)):
        np.testing.assert_allclose(got.center, truth.center, atol=1e-6)
        np.testing.assert_allclose(got.matrix, truth.matrix, atol=1e-10)
    assert result.relative.system == system and result.model.points.shape == XYZ.shape
    assert np.nanmax(np.abs(result.control_residuals)) < 1e-6


def test_double_resection_with_height_control_and_bad_input():
    eo1, eo2, XYZ, xy1, xy2 = make_pair(6)
    control = np.full_like(XYZ, np.nan)
    control[[0, 7]] = XYZ[[0, 7]]            # two full points
    control[12, 2] = XYZ[12, 2]              # and one height point (§2.11 minimal configuration)
    result = ip.double_resection(xy1, xy2, IO, control)
    np.testing.assert_allclose(result.object_points, XYZ, atol=1e-5)
    with pytest.raises(InputError, match="no control point"):
        ip.double_resection(xy1, xy2, IO, np.full_like(XYZ, np.nan))
    with pytest.raises(InputError, match="aligned"):
        ip.double_resection(xy1, xy2, IO, XYZ[:3])


# --- relative orientation without a start: convergent terrestrial pairs (issue 8) ---------------------
def _convergent_pair(seed):
    """Camera 1 looks horizontally at an object 30 m away; camera 2 on a circle about the object,
    turned by a convergence angle of 60°–150°, small random tilts. Ground truth by construction."""
    from photolib.rotation import rot_z
    from photolib.synthetic import stereo_pair

    rng = np.random.default_rng(seed)
    gamma = np.radians(rng.uniform(60.0, 150.0))
    heading = rng.uniform(-np.pi, np.pi)
    e1 = ExteriorOrientation.from_degrees(0, 0, 0, 90 + rng.uniform(-3, 3), rng.uniform(-3, 3),
                                          rng.uniform(-3, 3), order="wak")
    turn = rot_z(heading)
    e1 = ExteriorOrientation.from_matrix(np.zeros(3), turn @ e1.matrix, "wak")
    centre = turn @ np.array([0.0, 30.0, 0.0])
    R = rot_z(gamma * rng.choice([-1, 1]))
    e2 = ExteriorOrientation.from_matrix(centre + R @ (e1.center - centre), R @ e1.matrix, "wak")
    pts = rng.uniform(-7, 7, (15, 3)) + centre
    io = InteriorOrientation(50.0)
    return np.degrees(gamma), io, e1, e2, project(pts, e1, io), project(pts, e2, io)


@pytest.mark.parametrize("system", ["dependent", "independent"])
@pytest.mark.parametrize("order", ["kaw", "wak"])
def test_relative_orientation_of_convergent_pairs_without_a_start(system, order):
    """30 seeded pairs with 60°–150° convergence: the default start (closed form from E with the
    cheirality test) reaches the true relative rotation and base direction in every case."""
    wrong = []
    for seed in range(30):
        gamma, io, e1, e2, xy1, xy2 = _convergent_pair(seed)
        ro = ip.relative_orientation(xy1, xy2, io, system=system, order=order)
        rel_true = e1.matrix.T @ e2.matrix
        b_true = e1.matrix.T @ (e2.center - e1.center)
        ok = (np.allclose(ro.A1.T @ ro.A2, rel_true, atol=1e-8)
              and np.allclose(ro.A1.T @ ro.base_direction, b_true / np.linalg.norm(b_true), atol=1e-8)
              and ro.in_front == len(xy1))
        if not ok:
            wrong.append((seed, round(gamma, 1)))
    assert not wrong, f"wrong relative orientation for (seed, convergence°) {wrong}"


def test_relative_orientation_reports_a_zero_base():
    from photolib.synthetic import stereo_pair

    pair = stereo_pair(12, seed=1, centres=((0, 0, 1000.0), (0, 0, 1000.0)), angle_spread_deg=2.0, sigma=0.003)
    with pytest.raises(DegenerateGeometryError, match="base"):
        ip.relative_orientation(pair.xy1, pair.xy2, pair.io)
