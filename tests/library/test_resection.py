"""Space resection, Chapter 1 §1.8–§1.9: book examples, round trips, OpenCV cross-check, accuracy, bad input."""

import itertools

import cv2
import numpy as np
import pytest
from scipy.optimize import least_squares

from photolib.camera import ExteriorOrientation, InteriorOrientation
from photolib.conventions import camera_matrix, eo_to_opencv, image_to_opencv, opencv_to_eo
from photolib.errors import ConvergenceError, DegenerateGeometryError, InputError
from photolib.resection import (angle_equation_count, approximate_exterior_orientation, implied_noise,
                                independent_angle_equations, resection_by_angles, space_resection)
from photolib.single_image import project

# The §1.8 example as printed (seed lines 650–667); §1.9 uses the same data (lines 747–769).
IO = InteriorOrientation(100.0, 0.0, 0.0)
XYZ = np.array([[1000, 1000, 10], [500, 1500, 15], [1500, 1500, 20], [500, 500, 15], [1500, 500, 20]], float)
XY = np.array([[8.763, -3.503], [-33.520, 50.212], [67.940, 42.748], [-46.273, -46.459], [56.541, -64.224]])
EO_TRUE = ExteriorOrientation.from_degrees(1000, 1000, 1000, 2, 5, 7)
EO0 = ExteriorOrientation.from_degrees(1010, 1300, 900, 0, 0, 0)


def _reprojection(p, XYZ, xy, io, order="kaw"):
    return (project(XYZ, ExteriorOrientation.from_vector(p, order), io) - xy).ravel()


# --- §1.8 book example ----------------------------------------------------------------------------
def test_book_example_correct_solution():
    """Our adjustment equals an independent minimisation (scipy, finite-difference Jacobian)."""
    res = space_resection(XYZ, XY, IO, EO0)
    ref = least_squares(_reprojection, EO_TRUE.vector, args=(XYZ, XY, IO), x_scale=[1, 1, 1, 1e-3, 1e-3, 1e-3],
                        xtol=1e-15, ftol=1e-15, gtol=1e-15)
    np.testing.assert_allclose(res.eo.vector, ref.x, atol=1e-6)
    J = ref.jac
    mu = np.sqrt(ref.fun @ ref.fun / (10 - 6))
    std = mu * np.sqrt(np.diag(np.linalg.inv(J.T @ J)))
    np.testing.assert_allclose(res.std, std, rtol=1e-4)
    np.testing.assert_allclose(res.mu, mu, rtol=1e-8)
    # the physically required signs of the dominant correlations (near-vertical image, flat control)
    assert res.corr[0, 4] > 0.9 and res.corr[1, 3] < -0.9
    assert res.residuals.shape == (5, 2)
    np.testing.assert_allclose(res.residuals.ravel(), ref.fun, atol=1e-7)   # mm


def test_book_example_unit_free_weights():
    """P = 1/σ² changes μ into a unitless number (μ_mm/σ) but not the m_j (guide pitfall 10)."""
    a = space_resection(XYZ, XY, IO, EO0)
    b = space_resection(XYZ, XY, IO, EO0, weights=np.full(5, 1 / 0.016 ** 2))
    np.testing.assert_allclose(b.std, a.std, rtol=1e-9)
    assert b.mu == pytest.approx(a.mu / 0.016, rel=1e-9)


def test_printed_partials_diverge_on_book_example():
    """The coefficients of (1.8.3) as printed drive the book's own iteration away (the erratum)."""
    with pytest.raises(ConvergenceError, match="space resection .printed partials. diverged") as info:
        space_resection(XYZ, XY, IO, EO0, jacobian="printed")
    xs = [rec.x[0] for rec in info.value.history]
    assert xs[1] > xs[0] > 1000 and abs(xs[3] - 1000) > 500         # 1010 → 1186 → 1574 → 2178 …


def test_printed_partials_are_minus_the_truth_in_effect():
    """Diagnosis of §1.8: (Bpᵀ Bp)⁻¹ Bpᵀ J has all eigenvalues with negative real part near the solution."""
    from photolib.resection import _collinearity_linearizer
    p = space_resection(XYZ, XY, IO, EO0).eo.vector
    Bp, _ = _collinearity_linearizer(XYZ, XY, IO, "kaw", "printed")(p)
    J, _ = _collinearity_linearizer(XYZ, XY, IO, "kaw", "derived")(p)
    eig = np.linalg.eigvals(np.linalg.solve(Bp.T @ Bp, Bp.T @ J))
    assert np.all(eig.real < -0.5)


def test_implied_noise_of_book_example():
    exact, noise = implied_noise(XYZ, XY, IO, EO_TRUE)
    np.testing.assert_allclose(exact, project(XYZ, EO_TRUE, IO))
    rms = np.sqrt(np.mean(noise ** 2))
    assert 0.008 < rms < 0.025          # consistent with the printed σ = 0.016 mm for 10 draws
    assert np.abs(noise).max() < 4 * 0.016


# --- round trips ---------------------------------------------------------------------------------
def _scene(rng, n=8, relief=80.0):
    eo = np.r_[rng.uniform(-100, 100, 2), rng.uniform(900, 1500), rng.uniform(-0.15, 0.15, 3)]
    eo[5] = rng.uniform(-np.pi, np.pi)
    XYZ = np.column_stack([rng.uniform(-500, 500, n), rng.uniform(-500, 500, n), rng.uniform(0, relief, n)])
    return eo, XYZ


@pytest.mark.parametrize("order", ["kaw", "wak"])
@pytest.mark.parametrize("seed", range(5))
def test_noise_free_round_trip(order, seed):
    rng = np.random.default_rng(seed)
    p, XYZ_ = _scene(rng)
    eo = ExteriorOrientation.from_vector(p, order)
    io = InteriorOrientation(rng.uniform(80, 160), rng.uniform(-0.1, 0.1), rng.uniform(-0.1, 0.1))
    xy = project(XYZ_, eo, io)
    start = p + np.r_[rng.normal(0, 30, 3), rng.normal(0, 0.05, 3)]
    res = space_resection(XYZ_, xy, io, start, order=order)
    np.testing.assert_allclose(res.eo.vector[:3], p[:3], atol=1e-6)
    np.testing.assert_allclose(res.eo.vector[3:], p[3:], atol=1e-8)
    assert res.eo.order == order
    assert res.mu < 1e-9


@pytest.mark.parametrize("seed", range(3))
def test_automatic_approximation_converges(seed):
    rng = np.random.default_rng(100 + seed)
    p, XYZ_ = _scene(rng)
    eo = ExteriorOrientation.from_vector(p)
    xy = project(XYZ_, eo, IO)
    approx = approximate_exterior_orientation(XYZ_, xy, IO)
    assert abs(approx.Zs - p[2]) < 0.2 * p[2]
    res = space_resection(XYZ_, xy, IO)
    np.testing.assert_allclose(res.eo.vector, p, atol=1e-6)


def test_distortion_is_corrected_before_the_adjustment():
    rng = np.random.default_rng(7)
    p, XYZ_ = _scene(rng)
    io = InteriorOrientation(100.0, 0.01, -0.02, k1=-2e-9 * 1e3, k2=2e-14, p1=1e-6, p2=-1e-6)
    xy = project(XYZ_, ExteriorOrientation.from_vector(p), io)       # what the distorting camera records
    res = space_resection(XYZ_, xy, io, p + 0.01)
    np.testing.assert_allclose(res.eo.vector, p, atol=1e-6)
    ideal = InteriorOrientation(100.0, 0.01, -0.02)
    off = space_resection(XYZ_, xy, ideal, p + 0.01)                # ignoring it biases the pose
    assert np.abs(off.eo.vector[:3] - p[:3]).max() > 1e-3


# --- OpenCV cross-check -------------------------------------------------------------------------
def test_opencv_solvepnp_agrees():
    """Same noisy data, OpenCV's iterative PnP (Levenberg–Marquardt on the reprojection error)."""
    rng = np.random.default_rng(42)
    p, XYZ_ = _scene(rng, n=10)
    eo = ExteriorOrientation.from_vector(p)
    io = InteriorOrientation(120.0, 0.05, -0.03)
    xy = project(XYZ_, eo, io) + rng.normal(0, 0.01, (10, 2))
    ours = space_resection(XYZ_, xy, io, p + np.r_[5, -5, 5, 0.01, -0.01, 0.01])
    R0, t0 = eo_to_opencv(ExteriorOrientation.from_vector(p + np.r_[5, -5, 5, 0.01, -0.01, 0.01]))
    rvec0, _ = cv2.Rodrigues(R0)
    ok, rvec, tvec = cv2.solvePnP(XYZ_, image_to_opencv(xy), camera_matrix(io), None, rvec0, t0.reshape(3, 1),
                                  useExtrinsicGuess=True, flags=cv2.SOLVEPNP_ITERATIVE)
    assert ok
    cv_eo = opencv_to_eo(cv2.Rodrigues(rvec)[0], tvec)
    np.testing.assert_allclose(ours.eo.vector[:3], cv_eo.vector[:3], atol=1e-4)
    np.testing.assert_allclose(ours.eo.vector[3:], cv_eo.vector[3:], atol=1e-7)


def test_opencv_solvepnp_on_book_example():
    R0, t0 = eo_to_opencv(EO_TRUE)
    ok, rvec, tvec = cv2.solvePnP(XYZ, image_to_opencv(XY), camera_matrix(IO), None, cv2.Rodrigues(R0)[0],
                                  t0.reshape(3, 1), useExtrinsicGuess=True, flags=cv2.SOLVEPNP_ITERATIVE)
    cv_eo = opencv_to_eo(cv2.Rodrigues(rvec)[0], tvec)
    ours = space_resection(XYZ, XY, IO, EO0)
    np.testing.assert_allclose(ours.eo.vector[:3], cv_eo.vector[:3], atol=1e-3)    # 1000.20, 999.79, 999.97
    np.testing.assert_allclose(ours.eo.vector[3:], cv_eo.vector[3:], atol=1e-6)


# --- accuracy honesty ---------------------------------------------------------------------------
def test_monte_carlo_precision_matches_prediction():
    """300 seeded runs: empirical std of the estimates vs m_j = σ√Q_jj; mean μ² vs σ²."""
    rng = np.random.default_rng(2024)
    p, XYZ_ = _scene(rng, n=6)
    eo = ExteriorOrientation.from_vector(p)
    exact = project(XYZ_, eo, IO)
    sigma, runs = 0.01, 300
    est, mu2 = [], []
    for _ in range(runs):
        res = space_resection(XYZ_, exact + rng.normal(0, sigma, exact.shape), IO, p)
        est.append(res.eo.vector)
        mu2.append(res.mu ** 2)
    predicted = sigma * np.sqrt(np.diag(res.Q))
    empirical = np.std(est, axis=0, ddof=1)
    # relative s.e. of a sample std from 300 runs is 1/√598 ≈ 4 %: allow 4 s.e.
    np.testing.assert_allclose(empirical, predicted, rtol=0.17)
    # μ²/σ² has mean 1 and variance 2/dof (dof = 6): s.e. of the mean √(2/6/300) ≈ 3.3 %
    assert np.mean(mu2) / sigma ** 2 == pytest.approx(1.0, abs=0.14)
    assert np.all(np.abs(np.mean(est, axis=0) - p) < 4 * predicted / np.sqrt(runs))    # unbiased


# --- §1.9 -----------------------------------------------------------------------------------------
def _cos_residuals(S, XYZ, xy, io, pairs):
    out = []
    for i, j in pairs:
        a, b = XYZ[i] - S, XYZ[j] - S
        ra, rb = np.r_[xy[i] - [io.x0, io.y0], -io.f], np.r_[xy[j] - [io.x0, io.y0], -io.f]
        out.append(a @ b / np.linalg.norm(a) / np.linalg.norm(b) - ra @ rb / np.linalg.norm(ra) / np.linalg.norm(rb))
    return np.array(out)


def test_book_angles_example():
    """All 10 pairs, dof = m − n = 7: equals an independent scipy minimisation."""
    pairs = list(itertools.combinations(range(5), 2))
    res = resection_by_angles(XYZ, XY, IO, [1010, 1300, 900])
    ref = least_squares(_cos_residuals, [1000, 1000, 1000], args=(XYZ, XY, IO, pairs), xtol=1e-15, ftol=1e-15,
                        gtol=1e-15)
    np.testing.assert_allclose(res.center, ref.x, atol=1e-6)
    mu = np.sqrt(ref.fun @ ref.fun / 7)
    np.testing.assert_allclose(res.std, mu * np.sqrt(np.diag(np.linalg.inv(ref.jac.T @ ref.jac))), rtol=1e-4)
    assert res.adjustment.dof == 7 and len(res.pairs) == angle_equation_count(5)


def test_angles_r13_sign_is_robust_to_print_rounding():
    """r(Xs, Zs) stays positive for any rounding of the printed coordinates (±0.0005 mm)."""
    rng = np.random.default_rng(19)
    r13 = [resection_by_angles(XYZ, XY + rng.uniform(-5e-4, 5e-4, XY.shape), IO, [1010, 1300, 900]).corr[0, 2]
           for _ in range(100)]
    assert min(r13) > 0


def test_angles_noise_free_recovers_center():
    xy = project(XYZ, EO_TRUE, IO)
    res = resection_by_angles(XYZ, xy, IO, [1010, 1300, 900])
    np.testing.assert_allclose(res.center, EO_TRUE.center, atol=1e-6)
    res2 = resection_by_angles(XYZ, xy, IO, pairs=[(0, 1), (0, 2), (1, 2), (3, 4)])
    np.testing.assert_allclose(res2.center, EO_TRUE.center, atol=1e-6)


def test_equation_counts():
    assert [angle_equation_count(n) for n in (3, 4, 5)] == [3, 6, 10]
    assert [independent_angle_equations(n) for n in (3, 4, 5)] == [3, 5, 7]
    # the independent count is the rank of the Jacobian of all pairwise angles w.r.t. the ray directions
    rng = np.random.default_rng(0)
    for n in (3, 4, 5, 6):
        rays = rng.normal(size=(n, 3))

        def cosines(v):
            r = v.reshape(n, 3)
            r = r / np.linalg.norm(r, axis=1, keepdims=True)
            return np.array([r[i] @ r[j] for i, j in itertools.combinations(range(n), 2)])
        h = 1e-6
        J = np.array([(cosines(rays.ravel() + h * e) - cosines(rays.ravel() - h * e)) / (2 * h) for e in np.eye(3 * n)]).T
        assert np.linalg.matrix_rank(J, tol=1e-6) == min(independent_angle_equations(n), angle_equation_count(n))


# --- bad input -----------------------------------------------------------------------------------
def test_bad_input():
    with pytest.raises(InputError, match="at least 3"):
        space_resection(XYZ[:2], XY[:2], IO, EO0)
    with pytest.raises(InputError, match="shapes must match"):
        space_resection(XYZ, XY[:4], IO, EO0)
    with pytest.raises(InputError, match="NaN"):
        space_resection(np.where(np.eye(5, 3) == 1, np.nan, XYZ), XY, IO, EO0)
    with pytest.raises(InputError, match="NaN"):
        space_resection(XYZ, XY * np.inf, IO, EO0)
    with pytest.raises(InputError, match="shape"):
        space_resection(XYZ[:, :2], XY, IO, EO0)
    line = np.column_stack([np.linspace(0, 1000, 5), np.linspace(0, 500, 5), np.linspace(0, 20, 5)])
    with pytest.raises(DegenerateGeometryError, match="collinear"):
        space_resection(line, XY, IO, EO0)
    with pytest.raises(DegenerateGeometryError, match="collinear"):
        resection_by_angles(line, XY, IO, [1010, 1300, 900])
    with pytest.raises(InputError, match="1.3.5"):
        space_resection(XYZ, XY, IO, EO0, order="wak", jacobian="printed")
    with pytest.raises(InputError, match="weights"):
        space_resection(XYZ, XY, IO, EO0, weights=np.ones(3))
    with pytest.raises(InputError, match="order"):
        space_resection(XYZ, XY, IO, EO0, order="xyz")
    with pytest.raises(InputError, match="behind the camera"):
        space_resection(XYZ, XY, IO, [1000, 1000, -500, 0, 0, 0])
    with pytest.raises(InputError, match="pair"):
        resection_by_angles(XYZ, XY, IO, pairs=[(0, 0), (1, 2), (2, 3)])


def test_too_few_iterations_is_a_convergence_error():
    with pytest.raises(ConvergenceError, match="space resection"):
        space_resection(XYZ, XY, IO, EO0, max_iter=2)
    with pytest.raises(ConvergenceError, match="equality of angles"):
        resection_by_angles(XYZ, XY, IO, [1010, 1300, 900], max_iter=2)
