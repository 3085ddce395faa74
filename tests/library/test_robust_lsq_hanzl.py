"""Robust adjustment of Hanzl §2.6 (seed 002 lines 313–342) in the one engine photolib.lsq.

Truth: Hanzl's identities (Σ r_i = m − n, v = −Q_vv P l, w_i ~ N(0, 1)), the Danish weight function
evaluated independently with numpy, and seeded synthetic space resections with planted blunders
(the true exterior orientation is known); scipy.optimize.least_squares as an independent check of
the final adjustment.
"""

import numpy as np
import pytest
from scipy.optimize import least_squares

from photolib import lsq
from photolib import resection as R
from photolib.camera import ExteriorOrientation, InteriorOrientation
from photolib.errors import DegenerateGeometryError
from photolib.single_image import project

IO = InteriorOrientation(100.0)
SIGMA = 0.005            # mm, image noise


def _linear_problem(seed, m=12, n=3):
    rng = np.random.default_rng(seed)
    A = rng.normal(size=(m, n))
    p = rng.uniform(0.5, 3.0, m)
    l = rng.normal(size=m)
    return A, p, l


def scene(seed, n=20, fraction=0.15, sigma=SIGMA):
    """A near-vertical image (f = 100 mm, H ≈ 1500 m) of n control points; a fraction of them get
    blunders of 0.1–0.5 mm in both coordinates."""
    rng = np.random.default_rng(seed)
    XYZ = np.column_stack([rng.uniform(0, 2000, n), rng.uniform(0, 2000, n), rng.uniform(0, 80, n)])
    eo = ExteriorOrientation.from_degrees(1000, 1000, 1500, *rng.uniform(-4, 4, 3))
    xy = project(XYZ, eo, IO) + rng.normal(0, sigma, (n, 2))
    nb = int(round(fraction * n))
    bad = np.sort(rng.choice(n, nb, replace=False))
    xy[bad] += rng.choice([-1, 1], (nb, 2)) * rng.uniform(0.1, 0.5, (nb, 2))
    return XYZ, xy, eo, bad


# --- Hanzl's identities ---------------------------------------------------------------------------
@pytest.mark.parametrize("seed", [0, 1, 2])
def test_sum_of_redundancy_numbers_is_m_minus_n(seed):
    A, p, l = _linear_problem(seed)
    adj = lsq.gauss_newton(lambda x: (A, A @ x - l), np.zeros(3), p)
    assert adj.redundancy.sum() == pytest.approx(12 - 3, abs=1e-10)
    assert np.all((adj.redundancy > 0) & (adj.redundancy < 1))


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_residuals_are_minus_qvv_p_l(seed):
    """Hanzl line 317: v = A(AᵀPA)⁻¹AᵀPl − l = −Q_vv P l with Q_vv = P⁻¹ − A N⁻¹ Aᵀ (guide S5)."""
    A, p, l = _linear_problem(seed)
    P = np.diag(p)
    N = A.T @ P @ A
    Qvv = np.linalg.inv(P) - A @ np.linalg.solve(N, A.T)
    adj = lsq.gauss_newton(lambda x: (A, A @ x - l), np.zeros(3), p)
    np.testing.assert_allclose(adj.residuals, -Qvv @ P @ l, atol=1e-12)
    # the printed middle step (−A N⁻¹ Aᵀ + P⁻¹) P l is +Q_vv P l: the sign slip of line 317
    printed_middle = (-A @ np.linalg.solve(N, A.T) + np.linalg.inv(P)) @ P @ l
    np.testing.assert_allclose(printed_middle, -adj.residuals, atol=1e-12)
    np.testing.assert_allclose(np.diag(Qvv @ P), adj.redundancy, atol=1e-12)


def test_normalized_residuals_equal_the_studentised_form():
    A, p, l = _linear_problem(5, m=15, n=4)
    adj = lsq.gauss_newton(lambda x: (A, A @ x - l), np.zeros(4), p)
    w = lsq.normalized_residuals(A, adj.residuals, adj.Q, p)
    P = np.diag(p)
    Qvv = np.linalg.inv(P) - A @ np.linalg.inv(A.T @ P @ A) @ A.T
    s0 = np.sqrt(adj.residuals @ P @ adj.residuals / (15 - 4))
    np.testing.assert_allclose(w, np.abs(adj.residuals) / (s0 * np.sqrt(np.diag(Qvv))), rtol=1e-10)
    # unit weights: the internally studentised residuals |e_i| / (s √(1 − h_ii)) of regression
    adj1 = lsq.gauss_newton(lambda x: (A, A @ x - l), np.zeros(4))
    H = A @ np.linalg.pinv(A)
    e = l - H @ l
    s = np.sqrt(e @ e / 11)
    np.testing.assert_allclose(lsq.normalized_residuals(A, adj1.residuals, adj1.Q),
                               np.abs(e) / (s * np.sqrt(1 - np.diag(H))), rtol=1e-9)


def test_normalized_residuals_are_standard_normal_without_blunders():
    rng = np.random.default_rng(11)
    A = rng.normal(size=(400, 3))
    l = A @ [1.0, 2.0, 3.0] + rng.normal(0, 0.1, 400)
    adj = lsq.gauss_newton(lambda x: (A, A @ x - l), np.zeros(3))
    w = lsq.normalized_residuals(A, adj.residuals, adj.Q)
    assert np.mean(w ** 2) == pytest.approx(1.0, abs=0.02)        # E w² = 1 exactly with σ₀ estimated
    assert np.mean(w > 1.96) == pytest.approx(0.05, abs=0.03)


def test_danish_weight_function_values():
    """exp(−0.05 t^d), evaluated independently (guide S5 table: t = 2 → 0.348 / 0.6703, t = 3 → 0.0019 / 0.2592)."""
    t = np.array([0.0, 1.0, 2.0, 3.0, 4.0])
    for d in (4.4, 3.0):
        np.testing.assert_allclose(lsq.danish_weight(t, d), [np.exp(-0.05 * v ** d) for v in t], rtol=1e-14)
    assert round(lsq.danish_weight(2.0, 4.4), 4) == 0.348 and round(lsq.danish_weight(3.0, 4.4), 4) == 0.0019
    assert round(lsq.danish_weight(2.0, 3.0), 4) == 0.6703 and round(lsq.danish_weight(3.0, 3.0), 4) == 0.2592
    assert lsq.DANISH_EXPONENTS == (4.4, 3.0) and lsq.DANISH_FACTOR == 0.05


# --- the robust engine ----------------------------------------------------------------------------
def test_danish_passes_follow_hanzl():
    XYZ, xy, eo, bad = scene(3, fraction=0.2)
    res = R.robust_space_resection(XYZ, xy, IO)
    hist = res.robust.robust_history
    assert hist[0].exponent is None and np.all(hist[0].factors == 1.0)        # 1st pass: plain LS
    assert hist[1].exponent == 4.4                                              # 2nd: d = 4.4
    assert all(h.exponent == 3.0 for h in hist[2:])                             # 3rd … : d = 3.0
    assert len(res.robust.weight_history) == len(hist)
    # plain = the first pass = ordinary least squares
    np.testing.assert_allclose(res.plain_eo.vector, R.space_resection(XYZ, xy, IO).eo.vector, atol=1e-9)


def test_final_adjustment_uses_the_original_weights_of_the_kept_points():
    XYZ, xy, eo, bad = scene(4, fraction=0.2)
    rng = np.random.default_rng(4)
    weights = rng.uniform(0.5, 2.0, len(XYZ))
    res = R.robust_space_resection(XYZ, xy, IO, weights=weights)
    kept = ~res.rejected_points
    ref = R.space_resection(XYZ[kept], xy[kept], IO, weights=weights[kept])
    np.testing.assert_allclose(res.eo.vector, ref.eo.vector, atol=1e-9)
    assert res.mu == pytest.approx(ref.mu, rel=1e-9)
    # independent: scipy least_squares on the kept points with the same weights
    sw = np.sqrt(np.repeat(weights[kept], 2))
    fun = lambda v: (project(XYZ[kept], ExteriorOrientation.from_vector(v, "kaw"), IO) - xy[kept]).ravel() * sw
    sol = least_squares(fun, res.plain_eo.vector, xtol=1e-15, ftol=1e-15, gtol=1e-15)
    np.testing.assert_allclose(res.eo.vector[:3], sol.x[:3], atol=1e-5)
    np.testing.assert_allclose(res.eo.vector[3:], sol.x[3:], atol=1e-9)


@pytest.mark.parametrize("seed", range(6))
@pytest.mark.parametrize("fraction", [0.1, 0.2])
def test_robust_recovers_the_true_orientation_where_least_squares_fails(seed, fraction):
    XYZ, xy, eo, bad = scene(seed, fraction=fraction)
    plain = R.space_resection(XYZ, xy, IO)
    clean = R.space_resection(np.delete(XYZ, bad, 0), np.delete(xy, bad, 0), IO)
    tol = 4 * clean.std[:3].max()                      # 4 σ of the blunder-free resection
    err = lambda e: np.abs(e.vector[:3] - eo.vector[:3]).max()
    # the Danish method finds exactly the blunders; the final EO is the blunder-free resection
    res = R.robust_space_resection(XYZ, xy, IO)
    assert np.flatnonzero(res.rejected_points).tolist() == bad.tolist()
    np.testing.assert_allclose(res.eo.vector, clean.eo.vector, atol=1e-9)
    # data snooping (a-priori σ₀) rejects one point per pass; with several blunders the least-squares
    # residuals smear them onto good points, which may be rejected too (swamping): every blunder
    # must be found and the EO must be as good
    sno = R.robust_space_resection(XYZ, xy, IO, method="snooping", sigma0=SIGMA)
    assert set(bad.tolist()) <= set(np.flatnonzero(sno.rejected_points).tolist())
    for r in (res, sno):
        assert err(r.eo) < tol
        assert np.abs(r.eo.vector[3:] - eo.vector[3:]).max() < 4 * clean.std[3:].max()
    if fraction == 0.2:
        assert err(plain.eo) > tol                    # least squares is pulled outside that bound


def test_snooping_with_estimated_sigma0_is_masked_by_many_blunders():
    """Hanzl's drawback 1: σ₀ from the residuals is inflated by the outliers. With 20 % blunders
    snooping with the estimated σ₀ misses them, with the a-priori σ₀ it finds them all."""
    missed = 0
    for seed in range(6):
        XYZ, xy, eo, bad = scene(seed, fraction=0.2)
        est = R.robust_space_resection(XYZ, xy, IO, method="snooping")
        missed += np.flatnonzero(est.rejected_points).tolist() != bad.tolist()
    assert missed >= 3


@pytest.mark.parametrize("seed", range(4))
def test_snooping_flags_a_single_planted_blunder(seed):
    rng = np.random.default_rng(100 + seed)
    XYZ, xy, eo, _ = scene(seed, fraction=0.0)
    i = int(rng.integers(len(XYZ)))
    xy[i, int(rng.integers(2))] += 0.08 * rng.choice([-1, 1])          # 16 σ
    for s0 in (None, SIGMA):
        res = R.robust_space_resection(XYZ, xy, IO, method="snooping", sigma0=s0)
        assert np.flatnonzero(res.rejected_points).tolist() == [i]
        assert res.robust.robust_history[0].max_w > lsq.SNOOPING_CRITICAL
        assert res.robust.robust_history[-1].max_w <= lsq.SNOOPING_CRITICAL


def test_no_blunders_no_rejection_and_plain_result():
    XYZ, xy, eo, _ = scene(9, fraction=0.0)
    plain = R.space_resection(XYZ, xy, IO)
    for method in ("danish", "snooping"):
        res = R.robust_space_resection(XYZ, xy, IO, method=method)
        assert not res.rejected_points.any()
        np.testing.assert_allclose(res.eo.vector, plain.eo.vector, atol=1e-9)


def test_single_observation_groups_on_a_line():
    t = np.arange(30.0)
    rng = np.random.default_rng(0)
    y = 1.0 + 0.2 * t + rng.normal(0, 0.01, 30)
    y[[3, 17, 25]] += [0.5, -0.8, 0.3]
    lin = lambda p: (np.column_stack([np.ones(30), t]), p[0] + p[1] * t - y)
    ref = np.polyfit(np.delete(t, [3, 17, 25]), np.delete(y, [3, 17, 25]), 1)[::-1]
    for method in ("danish", "snooping"):
        res = lsq.robust_gauss_newton(lin, [0.0, 0.0], method=method)
        assert np.flatnonzero(res.rejected).tolist() == [3, 17, 25]
        np.testing.assert_allclose(res.x, ref, atol=1e-10)
        assert res.residuals.shape == (30,) and np.isnan(res.normalized[res.rejected]).all()


def test_progress_is_called_per_pass():
    XYZ, xy, eo, bad = scene(2, fraction=0.1)
    seen = []
    res = R.robust_space_resection(XYZ, xy, IO, progress=seen.append)
    assert [r.iteration for r in seen] == list(range(1, len(seen) + 1))
    assert len(seen) == len(res.robust.robust_history)
    assert "rejected" in res.summary() and "Robust" in repr(res.robust)


def test_too_many_blunders_is_a_clear_error():
    t = np.arange(6.0)
    y = np.array([0.0, 10.0, -7.0, 31.0, -2.0, 55.0])
    lin = lambda p: (np.column_stack([np.ones(6), t]), p[0] + p[1] * t - y)
    with pytest.raises(DegenerateGeometryError, match="cannot determine"):
        lsq.robust_gauss_newton(lin, [0.0, 0.0], method="snooping", sigma0=1e-3)


# --- Hanzl §2.2–§2.4 against the library (numbers from sympy and from the library's own functions) ---------
def test_printed_rotation_table_differs_only_in_r32():
    import sympy as sp
    from photolib.derivations import hanzl_foundations as H
    diff = (H.printed_rotation_table() - H.hanzl_rotation()).applyfunc(sp.simplify)
    nonzero = [(i, j) for i in range(3) for j in range(3) if diff[i, j] != 0]
    assert nonzero == [(2, 1)]
    assert sp.simplify(diff[2, 1] + 2 * sp.cos(H.omega) * sp.sin(H.PHI) * sp.sin(H.kappa)) == 0


def test_hanzl_matrix_equals_the_symbolic_product_and_the_wak_order():
    import sympy as sp
    from photolib import conventions, rotation
    from photolib.derivations import hanzl_foundations as H
    rng = np.random.default_rng(7)
    for w, p, k in rng.uniform(-1.5, 1.5, (5, 3)):
        sym = np.array(H.hanzl_rotation().subs({H.omega: w, H.PHI: p, H.kappa: k}), dtype=float)
        np.testing.assert_allclose(conventions.hanzl_matrix(w, p, k), sym, atol=1e-14)
        np.testing.assert_allclose(rotation.rotation_matrix(w, p, k, order="wak"), sym, atol=1e-14)


def _numeric_forms(eo, c=100.0, x0=0.01, y0=-0.02):
    import sympy as sp
    from photolib.derivations import hanzl_foundations as H
    R = eo.matrix
    sub = {H.R_SYMBOLS[i, j]: R[i, j] for i in range(3) for j in range(3)}
    sub.update({H.C: c, H.XC: eo.Xs, H.YC: eo.Ys, H.ZC: eo.Zs, H.x0: x0, H.y0: y0})
    return sub


def test_collinearity_inverse_and_dlt_agree_with_the_library():
    import sympy as sp
    from photolib import projective
    from photolib.derivations import hanzl_foundations as H
    from photolib.derivations.symbols import X, Y, Z, x, y
    from photolib.single_image import image_to_ground
    io = InteriorOrientation(100.0, 0.01, -0.02)
    eo = ExteriorOrientation.from_degrees(1000, 2000, 1500, 3, -5, 40, order="wak")
    sub = _numeric_forms(eo)
    P = np.array([[1100.0, 1950.0, 230.0], [800.0, 2300.0, 50.0], [1300.0, 1700.0, 120.0]])
    xy = project(P, eo, io)
    col = H.collinearity_forms()["printed"]
    inv = H.inverse_forms()["printed"]
    dlt = H.dlt_coefficients()
    L_lib = projective.dlt_from_orientation(io, eo)
    L_sym = np.array([float(e.xreplace(sub)) for e in dlt["L"]])
    np.testing.assert_allclose(L_sym, L_lib, rtol=1e-10)
    for (Xp, Yp, Zp), (xi, yi) in zip(P, xy):
        pt = {**sub, X: Xp, Y: Yp, Z: Zp, x: xi, y: yi}
        assert float(col[0].xreplace(pt)) == pytest.approx(xi, abs=1e-10)
        assert float(col[1].xreplace(pt)) == pytest.approx(yi, abs=1e-10)
        assert float(inv[0].xreplace(pt)) == pytest.approx(Xp, abs=1e-7)
        assert float(inv[1].xreplace(pt)) == pytest.approx(Yp, abs=1e-7)
    np.testing.assert_allclose(image_to_ground(xy, P[:, 2], eo, io)[:, :2], P[:, :2], atol=1e-7)
    np.testing.assert_allclose(projective.dlt_project(L_lib, P), xy, atol=1e-10)


def test_plane_projective_coefficients_agree_with_a_fitted_homography():
    from photolib import plane_transforms as pt
    from photolib.derivations import hanzl_foundations as H
    from photolib.derivations.symbols import Z
    io = InteriorOrientation(100.0, 0.01, -0.02)
    eo = ExteriorOrientation.from_degrees(1000, 2000, 1500, 3, -5, 40, order="wak")
    sub = {**_numeric_forms(eo), Z: 120.0}
    coef = np.array([float(e.xreplace(sub)) for e in H.plane_projective_coefficients()["coefficients"]])
    g = np.linspace(500.0, 1500.0, 5)
    P = np.column_stack([np.repeat(g, 5), np.tile(g + 1000.0, 5), np.full(25, 120.0)])
    xy = project(P, eo, io)
    fit = pt.fit_plane_transform(xy, P[:, :2], "projective")           # image → plane Z = 120 m
    np.testing.assert_allclose(fit.parameters, coef, rtol=1e-7)
