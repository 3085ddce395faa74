"""photolib.mockup — the mock-up calibration experiments of the Sementsov appendix (§2.4, §3.1, §3.2).

Expected values come from an independent implementation (scipy.optimize.least_squares on residuals
written here from the printed direction cosines), from sympy, from numpy/scipy.stats, or from the
synthetic truth of the mock-ups.
"""

import numpy as np
import pytest
import scipy.stats
import sympy as sp
from scipy.optimize import least_squares

from photolib import mockup as M
from photolib.derivations import mockup as DM
from photolib.derivations.symbols import X, Xs, Y, Ys, Z, Zs, alpha, f, kappa, omega, x, x0, y, y0
from photolib.errors import ConvergenceError, DegenerateGeometryError, InputError


# --------------------------------------------------------------------------- an independent model
def printed_rotation(a, w, k):
    """The α–ω–κ direction cosines as the guide writes them out (a₃ = −sin α cos ω, c₁ = sin α cos κ + …)."""
    sa, ca, sw, cw, sk, ck = np.sin(a), np.cos(a), np.sin(w), np.cos(w), np.sin(k), np.cos(k)
    return np.array([[ca * ck - sa * sw * sk, -ca * sk - sa * sw * ck, -sa * cw],
                     [cw * sk, cw * ck, -sw],
                     [sa * ck + ca * sw * sk, -sa * sk + ca * sw * ck, ca * cw]])


def project(P, S, ang, io):
    d = (P - S) @ printed_rotation(*ang)
    return np.column_stack([io[1] - io[0] * d[:, 0] / d[:, 2], io[2] - io[0] * d[:, 1] / d[:, 2]])


def scipy_network(obs, gnss=(), mode="fixed", sigma=0.5):
    """The control-point network solved by scipy: IO per camera, free centre components, angles."""
    n_cam, n_cen = len(obs.cameras), len(obs.centres)
    cen = obs.centres.astype(float).copy()
    free = np.ones((n_cen, 3), bool)
    rows = []
    for g in gnss:
        if mode == "fixed":
            free[g.centre, g.mask] = False
            cen[g.centre, g.mask] = g.measured[g.mask]
        else:
            rows += [(g.centre, k, g.measured[k], g.sigma[k]) for k in np.flatnonzero(g.mask)]

    def unpack(p):
        io = p[:3 * n_cam].reshape(n_cam, 3)
        c = cen.copy()
        c[free] = p[3 * n_cam:3 * n_cam + free.sum()]
        return io, c, p[3 * n_cam + free.sum():].reshape(-1, 3)

    def res(p):
        io, c, ang = unpack(p)
        r = [(project(obs.points[im.point_ids], c[im.centre], ang[i], io[im.camera]) - im.xy).ravel()
             for i, im in enumerate(obs.images)]
        r += [np.array([(c[ci, k] - m) * sigma / s]) for ci, k, m, s in rows]
        return np.concatenate(r)

    p0 = np.concatenate([(np.array([c.io for c in obs.cameras]) * [1.01, 1, 1]).ravel(),
                         cen[free] + 1.0, np.array([s.angles for s in obs.stations]).ravel() + 0.01])
    sol = least_squares(res, p0, method="lm", xtol=1e-15, ftol=1e-15, gtol=1e-15, x_scale="jac")
    sol = least_squares(res, sol.x, method="lm", xtol=1e-15, ftol=1e-15, gtol=1e-15, x_scale="jac")  # polish
    J = sol.jac
    mu = np.sqrt(sol.fun @ sol.fun / (sol.fun.size - sol.x.size))
    std = mu * np.sqrt(np.diag(np.linalg.inv(J.T @ J)))
    io, c, ang = unpack(sol.x)
    return io, std[:3 * n_cam].reshape(n_cam, 3), c, mu


@pytest.mark.parametrize("variant,mode", [("1-2", "fixed"), ("1-1", "weighted"), ("2-3", "fixed"), ("3-2", "fixed"),
                                          ("1-3", "weighted")])
def test_network_adjustment_matches_scipy_least_squares(variant, mode):
    obs = M.variant_mockup(variant, seed=11)
    v = M.TABLE1_VARIANTS[variant]
    gnss = [M.simulate_gnss(obs, v.gnss, seed=12)] if v.gnss else []
    res = M.calibrate_network(obs, gnss=gnss, gnss_mode=mode,
                              cameras0=np.array([c.io for c in obs.cameras]) * [0.98, 1, 1])
    io, io_std, centres, mu = scipy_network(obs, gnss, mode)
    # the same minimum: equal VᵀPV (μ) to 1e-9; in the flat f–x₀–Z_S valley of one tilted image a
    # relative change of VᵀPV of 1e-13 (rounding) moves the minimiser by a few 1e-6 px
    assert res.mu == pytest.approx(mu, rel=1e-9)
    np.testing.assert_allclose(res.cameras, io, atol=2e-5)
    np.testing.assert_allclose(res.cameras_std, io_std, rtol=1e-5)
    np.testing.assert_allclose(res.centres, centres, atol=2e-5)


def test_plane_network_with_tripod_model_matches_scipy():
    """Control-free §3.2 network with eq. (20), same datum (plane, S₀, first image's rotation), solved by scipy."""
    obs = M.tripod_mockup([0.005, 0.065, -0.04], sigma=0.5, seed=5, half_size=1.6, step=0.4)
    res = M.calibrate_network(obs, targets="plane", tripod=True)
    used = res.point_used
    ids = np.flatnonzero(used)
    index = -np.ones(len(obs.points), int)
    index[ids] = np.arange(ids.size)
    ang_true = np.array([s.angles for s in obs.stations])
    z = obs.points[0, 2]

    def res_fn(p):
        io, l, ang = p[:3], p[3:6], np.vstack([ang_true[0], p[6:18].reshape(4, 3)])
        xy = p[18:].reshape(-1, 2)
        out = []
        for i, im in enumerate(obs.images):
            k = used[im.point_ids]
            P = np.column_stack([xy[index[im.point_ids[k]]], np.full(k.sum(), z)])
            S = printed_rotation(*ang[i]) @ l                 # S₀ = 0
            out.append((project(P, S, ang[i], io) - im.xy[k]).ravel())
        return np.concatenate(out)

    p0 = np.concatenate([[3050.0, 0, 0], [0, 0, 0], ang_true[1:].ravel(), obs.points[ids, :2].ravel()])
    sol = least_squares(res_fn, p0, method="trf", xtol=1e-15, ftol=1e-15, gtol=1e-15, x_scale="jac")
    np.testing.assert_allclose(res.cameras[0], sol.x[:3], atol=1e-5)
    np.testing.assert_allclose(res.l, sol.x[3:6], atol=1e-8)


# --------------------------------------------------------------------------- noise-free truth
@pytest.mark.parametrize("variant", list(M.TABLE1_VARIANTS))
def test_noise_free_mockup_recovers_the_true_interior_orientation(variant):
    obs = M.variant_mockup(variant, sigma=0.0)
    v = M.TABLE1_VARIANTS[variant]
    gnss = [M.GnssCentre(0, obs.centres[0], [0.1, 0.1, 0.3], v.gnss)] if v.gnss else []
    res = M.calibrate_network(obs, gnss=gnss, cameras0=np.tile([3000.0, 0.0, 0.0], (v.n_cameras, 1)),
                              angles0=np.radians(v.angles_deg) + 0.02)
    np.testing.assert_allclose(res.io_errors(obs), 0.0, atol=1e-6)
    assert res.mu < 1e-7


def test_tripod_offset_recovered_exactly_noise_free():
    l = np.array([0.005, 0.065, -0.04])
    obs = M.tripod_mockup(l, sigma=0.0)
    for datum, l0 in (("first-image", None), ("minimal", l / 2)):
        res = M.calibrate_network(obs, targets="plane", tripod=True, datum=datum, l0=l0,
                                  cameras0=[[3000.0, 0.0, 0.0]])
        np.testing.assert_allclose(res.l, l, atol=1e-10)
        np.testing.assert_allclose(res.io_errors(obs), 0.0, atol=1e-6)
    # with known targets: S₀ and l unknown together
    res = M.calibrate_network(obs, tripod=True, centres0=[[0.3, -0.2, 0.1]])
    np.testing.assert_allclose(res.centres[0], 0.0, atol=1e-10)
    np.testing.assert_allclose(res.l, l, atol=1e-10)
    np.testing.assert_allclose(np.linalg.norm(res.image_centres - res.centres[0], axis=1), np.linalg.norm(l))


def test_tripod_centres_lie_on_the_sphere_and_rotate_l():
    ang = np.radians(M.TABLE2_ANGLES)
    S = M.tripod_centres([1.0, 2.0, 3.0], ang, [0.005, 0.065, -0.04])
    np.testing.assert_allclose(np.linalg.norm(S - [1, 2, 3], axis=1), np.linalg.norm([0.005, 0.065, -0.04]))
    np.testing.assert_allclose(S[1] - [1, 2, 3], printed_rotation(*ang[1]) @ [0.005, 0.065, -0.04])


# --------------------------------------------------------------------------- fixed vs weighted GNSS
def test_fixed_gnss_holds_the_measured_components_weighted_adjusts_them():
    obs = M.variant_mockup("1-1", seed=3)
    g = M.simulate_gnss(obs, "XYZ", seed=4)
    fixed = M.calibrate_network(obs, gnss=[g], gnss_mode="fixed")
    weighted = M.calibrate_network(obs, gnss=[g], gnss_mode="weighted")
    np.testing.assert_array_equal(fixed.centres[0], g.measured)
    np.testing.assert_array_equal(fixed.centres_std[0], 0.0)
    assert np.all(weighted.centres_std[0] > 0) and np.all(weighted.centres_std[0] < g.sigma)
    assert np.abs(weighted.centres[0] - g.measured).max() > 1e-3
    # a tiny σ is the same as fixing; without any GNSS one tilted image leaves the k-ambiguity of
    # §2.2 (methodology 1 needs one independently known element): singular
    tight = M.GnssCentre(0, g.measured, [1e-7] * 3, "XYZ")
    np.testing.assert_allclose(M.calibrate_network(obs, gnss=[tight], gnss_mode="weighted").cameras, fixed.cameras,
                               atol=1e-4)
    with pytest.raises(DegenerateGeometryError):
        M.calibrate_network(obs)


def test_horizontal_reference_variant_is_almost_the_same_fixed_or_weighted():
    """Variant 0-1: three GNSS components against the three combinations a horizontal image leaves open
    (f/Z_S, x₀ − f·X_S/Z_S, y₀ − f·Y_S/Z_S): hardly any redundancy, so weighting changes little. Not exactly
    nothing — the invariance is exact only at α = ω = 0, and the estimated tilt is not exactly 0."""
    obs = M.variant_mockup("0-1", seed=8)
    g = M.simulate_gnss(obs, "XYZ", seed=9)
    a = M.calibrate_network(obs, gnss=[g], gnss_mode="fixed")
    b = M.calibrate_network(obs, gnss=[g], gnss_mode="weighted")
    assert np.abs(a.cameras - b.cameras).max() < 0.01            # the SKO of the variant is ≈ 1–3 px
    assert np.abs(b.centres[0] - g.measured).max() < 0.01         # against σ = 0.1–0.3 m


def test_small_monte_carlo_variant_1_1_matches_the_book_only_with_fixed_gnss():
    """Book (Table A.4): SKO of x₀ = 2.597 px. Fixed GNSS reproduces that level, weighting halves it."""
    fixed = M.simulate_variant("1-1", runs=80, seed=2024, gnss_mode="fixed").statistics
    weighted = M.simulate_variant("1-1", runs=80, seed=2024, gnss_mode="weighted").statistics
    book = 2.597322127
    se = book / np.sqrt(2 * 79)                      # standard error of a sample SD of 80 values
    assert abs(fixed.sko[1] - book) < 4 * se
    assert weighted.sko[1] < 0.6 * book
    assert weighted.sko[1] < fixed.sko[1] - 6 * se


# --------------------------------------------------------------------------- §3.2 slopes
@pytest.mark.parametrize("step,half", [(0.2, 3.0), (0.25, 1.5), (0.25, 3.0), (0.25, 5.0), (0.3, 3.0)])
def test_tripod_slopes_are_robust_to_the_target_layout(step, half):
    """Δx₀/l_X and Δf/l_Z (pixels, l = 1 mm, noise-free) round to the book's −0.6 and −0.4 for any sensible layout."""
    slopes = []
    for axis, k in ((0, 1), (2, 0)):
        l = np.zeros(3)
        l[axis] = 0.001
        obs = M.tripod_mockup(l, sigma=0.0, step=step, half_size=half)
        err = M.calibrate_network(obs, targets="plane").io_errors(obs)[0]
        slopes.append(err[k] / (0.001 * 3100 / 2))
    assert round(slopes[0], 1) == -0.6 and -0.65 < slopes[0] < -0.62
    assert round(slopes[1], 1) == -0.4 and -0.42 < slopes[1] < -0.36


def test_tripod_model_removes_the_offset_bias():
    """Tables 5/6: l = (0.005, 0.065, −0.04) m biases the single-centre calibration; model (20) removes it."""
    l = np.array([0.005, 0.065, -0.04])
    rng = np.random.default_rng(46)
    single, model, ls = [], [], []
    for _ in range(4):
        obs = M.tripod_mockup(l, sigma=0.5, seed=rng)
        single.append(M.calibrate_network(obs, targets="plane").io_errors(obs)[0])
        res = M.calibrate_network(obs, targets="plane", tripod=True)
        model.append(res.io_errors(obs)[0])
        ls.append(res.l)
        assert np.all(np.abs(res.l - l) < 4 * res.l_std)
    single, model = np.array(single), np.array(model)
    assert single[:, 0].mean() > 15 and single[:, 2].mean() < -50      # Δf ≈ +28 px, Δy₀ ≈ −78 px
    assert np.all(np.abs(model.mean(axis=0)) < 2.0)


# --------------------------------------------------------------------------- errors
def test_one_horizontal_image_with_free_height_is_degenerate():
    obs = M.variant_mockup("0-1", seed=1)
    with pytest.raises(DegenerateGeometryError, match="f/Z_S"):
        M.calibrate_network(obs)
    g = M.simulate_gnss(obs, "XY", seed=1)
    with pytest.raises(DegenerateGeometryError, match="f/Z_S"):
        M.calibrate_network(obs, gnss=[g])
    # Z_S known but X_S free: x₀ and X_S are not separable — the engine finds it
    with pytest.raises(DegenerateGeometryError, match="singular"):
        M.calibrate_network(obs, gnss=[M.simulate_gnss(obs, "Z", seed=1)])


def test_non_convergence_is_reported():
    obs = M.variant_mockup("2-1", seed=1)
    with pytest.raises(ConvergenceError, match="did not converge"):
        M.calibrate_network(obs, max_iter=1, angles0=np.radians([[25.0, 3, 2], [-35.0, -2, 1]]))


def test_too_few_points_are_refused():
    obs = M.simulate_mockup(M.planar_grid(1000, 50), [M.NEX5], [[0, 0, 300.0]], [M.MockupStation([0.5, 0, 0])],
                            seed=1)
    small = M.MockupObservations(obs.points, obs.cameras, obs.centres, obs.stations,
                                 (M.MockupImage(0, 0, obs.images[0].point_ids[:3], obs.images[0].xy[:3]),), 0.5)
    with pytest.raises(InputError, match="cannot determine"):
        M.calibrate_network(small)


# --------------------------------------------------------------------------- simulation
def test_simulation_filters_the_frame_and_the_points_behind():
    P = np.array([[0.0, 0, 0], [10, 0, 0], [2000, 0, 0], [0, 0, 400.0], [50, 30, 0], [60, 0, 0]])
    obs = M.simulate_mockup(P, [M.NEX5], [[0, 0, 300.0]], [M.MockupStation([0, 0, 0])], sigma=0.0)
    # (2000, 0) is outside the frame (x = 20 677 px), (0, 0, 400) is behind the camera
    assert obs.images[0].point_ids.tolist() == [0, 1, 4, 5]
    np.testing.assert_allclose(obs.images[0].xy, project(P[[0, 1, 4, 5]], [0, 0, 300.0], [0, 0, 0], M.NEX5.io))


def test_simulated_noise_has_the_requested_sigma():
    obs = M.simulate_mockup(M.planar_grid(1000, 50), [M.NEX5], [[0, 0, 300.0]],
                            [M.MockupStation(np.radians([30.0, 0, 0]))] * 20, sigma=0.5, seed=7)
    exact = M.simulate_mockup(obs.points, [M.NEX5], obs.centres, obs.stations, sigma=0.0)
    d = np.concatenate([a.xy - b.xy for a, b in zip(obs.images, exact.images)])
    assert d.std() == pytest.approx(0.5, rel=0.05)
    assert abs(d.mean()) < 0.02


def test_projection_reproduces_equation_8():
    """Eq. (8): X_S = Y_S = 0, Z = 0, tilt α only."""
    a, ZS, fv = np.radians(30.0), 300.0, 3100.0
    P = np.array([[120.0, -40.0, 0.0]])
    xy, _ = M.project_points(P, [0, 0, ZS], [a, 0, 0], [fv, 0, 0])
    D = -P[0, 0] * np.sin(a) - ZS * np.cos(a)
    np.testing.assert_allclose(xy[0], [-fv * (P[0, 0] * np.cos(a) - ZS * np.sin(a)) / D, -fv * P[0, 1] / D])


# --------------------------------------------------------------------------- the sympy models
def test_mockup_model_reduces_to_equation_8():
    F = DM.mockup_collinearity_model().residuals
    sub = {Xs: 0, Ys: 0, Z: 0, omega: 0, kappa: 0}
    D = -X * sp.sin(alpha) - Zs * sp.cos(alpha)
    assert sp.simplify(F[0].subs(sub) - (x0 - f * (X * sp.cos(alpha) - Zs * sp.sin(alpha)) / D - x)) == 0
    assert sp.simplify(F[1].subs(sub) - (y0 - f * Y / D - y)) == 0


def test_tripod_model_with_zero_offset_is_the_collinearity_model():
    T, C = DM.mockup_tripod_model(), DM.mockup_collinearity_model()
    S0 = sp.symbols("S0_X S0_Y S0_Z", real=True)
    lx = sp.symbols("l_X l_Y l_Z", real=True)
    for t, c in zip(T.residuals, C.residuals):
        expected = c.subs({Xs: S0[0], Ys: S0[1], Zs: S0[2]})
        assert sp.simplify(t.subs({lx[0]: 0, lx[1]: 0, lx[2]: 0}) - expected) == 0


def test_model_jacobian_matches_finite_differences():
    res, jac = DM.mockup_collinearity_model().compile()
    p = np.array([3100.0, 10.0, -5.0, 12.0, -7.0, 300.0, 0.4, -0.2, 0.1, 150.0, -80.0, 3.0])
    data = (400.0, -300.0)
    J = jac(*p, *data).reshape(2, 12)
    for j in range(12):
        h = 1e-6 * max(1.0, abs(p[j]))
        dp = np.zeros(12)
        dp[j] = h
        num = (res(*(p + dp), *data) - res(*(p - dp), *data)).ravel() / (2 * h)
        np.testing.assert_allclose(J[:, j], num, rtol=1e-6, atol=1e-6)


# --------------------------------------------------------------------------- Appendix A statistics
def test_error_statistics_against_numpy_and_scipy():
    E = np.random.default_rng(3).normal(size=(30, 3)) @ [[1, 0.5, 0], [0, 1, 0.2], [0, 0, 1]]
    s = M.error_statistics(E)
    np.testing.assert_allclose(s.mean, E.mean(0))
    np.testing.assert_allclose(s.sko, np.std(E, axis=0, ddof=1))
    np.testing.assert_allclose(s.sko, scipy.stats.tstd(E, axis=0))
    np.testing.assert_array_equal(s.max, E.max(0))
    np.testing.assert_array_equal(s.min, E.min(0))
    np.testing.assert_allclose(s.m_minus_sigma, E.mean(0) - np.std(E, axis=0, ddof=1))
    np.testing.assert_allclose(s.m_plus_sigma, E.mean(0) + np.std(E, axis=0, ddof=1))
    expected = [scipy.stats.pearsonr(E[:, i], E[:, j]).statistic for i, j in ((0, 1), (0, 2), (1, 2))]
    np.testing.assert_allclose(s.pairs, expected, rtol=1e-12)
    np.testing.assert_allclose(s.corr, np.corrcoef(E.T), rtol=1e-12)


def test_error_statistics_of_a_constant_column_has_no_correlation():
    s = M.error_statistics([[1.0, 2.0], [1.0, 3.0], [1.0, 5.0]])
    assert s.sko[0] == 0.0 and np.isnan(s.pairs[0])


def test_variant_precision_predicts_the_monte_carlo():
    """The first-order SDs of variant_precision against the SKO of 100 simulated mock-ups (4 standard errors)."""
    for variant, mode in (("1-1", "fixed"), ("1-2", "weighted")):
        expected = M.variant_precision(variant, gnss_mode=mode)[0]
        sko = M.simulate_variant(variant, 100, seed=31, gnss_mode=mode).statistics.sko
        se = expected / np.sqrt(2 * 99)
        assert np.all(np.abs(sko - expected) < 4 * se), (variant, mode, sko, expected)
