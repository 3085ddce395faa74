"""Bundle block adjustment (§3.5): the reduction (3.5.13)–(3.5.16), the block solver and the errors.

Expected values come from independent computations: the dense engine
(:func:`photolib.lsq.solve_normal_equations`), sympy, and synthetic ground truth.
"""

import numpy as np
import pytest
import sympy as sp

from photolib import synthetic
from photolib.bundle import bundle_adjustment, bundle_correction_equations, check_point_statistics
from photolib.derivations import bundle_collinearity_model, collinearity_model, compile_fused
from photolib.errors import PointBehindCameraError, ConvergenceError, DegenerateGeometryError, InputError
from photolib.lsq import (block_equations_dense, solve_block_normal_equations, solve_normal_equations,
                          solve_partitioned_normal_equations)


@pytest.fixture(scope="module")
def small_block():
    return synthetic.aerial_block(2, 4, points_per_image=12, sigma=0.005, n_check=4, seed=3)


def _free(blk):
    free = np.ones(len(blk.points), bool)
    free[blk.control] = False                 # control held fixed (3.5.3): the datum
    return free


def _linear_system(blk, perturbed=True):
    cams, pts = blk.start_values(seed=7) if perturbed else (blk.cameras, blk.points)
    o = blk.observations
    return bundle_correction_equations(o.image, o.point, o.xy, cams, pts, blk.io, blk.order)


# --- the reduction (3.5.13)–(3.5.16) --------------------------------------------------------------
def test_printed_3515_has_the_wrong_sign_and_3516_is_right():
    """(3.5.13) N·δ = Lᴺ eliminated both ways, exactly (sympy).

    Symbolic with scalar blocks, then exact rationals with a 3 + 2 partition (matrix blocks).
    """
    a, b, c, l1, l2 = sp.symbols("a b c l1 l2")
    d1, d2 = sp.Matrix([[a, b], [b, c]]).LUsolve(sp.Matrix([l1, l2]))
    printed_3515 = (l2 - b / a * l1) / (b / a * b - c)          # (N12ᵀN11⁻¹N12 − N22)δ2 = L2 − N12ᵀN11⁻¹L1
    corrected_3515 = (l2 - b / a * l1) / (c - b / a * b)
    eq_3516 = (l1 - b / c * l2) / (a - b / c * b)                 # (N11 − N12N22⁻¹N12ᵀ)δ1 = L1 − N12N22⁻¹L2
    assert sp.simplify(printed_3515 + d2) == 0
    assert sp.simplify(corrected_3515 - d2) == 0
    assert sp.simplify(eq_3516 - d1) == 0

    rng = np.random.default_rng(0)
    G = sp.Matrix(5, 5, [sp.Rational(int(v), 7) for v in rng.integers(-20, 20, 25)])
    N = G * G.T + sp.eye(5)
    LN = sp.Matrix([sp.Rational(k + 1, 3) for k in range(5)])
    full = N.LUsolve(LN)
    n11, n12, n22, L1, L2 = N[:3, :3], N[:3, 3:], N[3:, 3:], LN[:3, :], LN[3:, :]
    printed = (n12.T * n11.inv() * n12 - n22).LUsolve(L2 - n12.T * n11.inv() * L1)
    corrected = (n22 - n12.T * n11.inv() * n12).LUsolve(L2 - n12.T * n11.inv() * L1)
    delta1 = (n11 - n12 * n22.inv() * n12.T).LUsolve(L1 - n12 * n22.inv() * L2)
    assert corrected == full[3:, :]
    assert printed == -full[3:, :]
    assert delta1 == full[:3, :]


def test_reduced_equals_unreduced_normal_equations(small_block):
    eq = _linear_system(small_block)
    n, k = small_block.n_images, len(small_block.points)
    free = _free(small_block)
    B, L, P = block_equations_dense(eq, n, k, free_points=free)
    delta, Q = solve_normal_equations(B, L, P)                      # (3.5.8)–(3.5.9), dense
    sol = solve_block_normal_equations(eq, n, k, free_points=free, covariance=True, dense_limit=10_000)
    np.testing.assert_allclose(sol.delta1.ravel(), delta[:6 * n], rtol=1e-7, atol=1e-9)
    np.testing.assert_allclose(sol.delta2[free].ravel(), delta[6 * n:], rtol=1e-7, atol=1e-7)
    # cofactor blocks of the reduced path = diagonal blocks of the dense N⁻¹
    Q1 = np.array([Q[6 * i:6 * i + 6, 6 * i:6 * i + 6] for i in range(n)])
    Q2 = np.array([Q[6 * n + 3 * j:6 * n + 3 * j + 3, 6 * n + 3 * j:6 * n + 3 * j + 3] for j in range(free.sum())])
    np.testing.assert_allclose(sol.Q1, Q1, rtol=1e-6, atol=1e-14)
    np.testing.assert_allclose(sol.Q2[free], Q2, rtol=1e-6, atol=1e-12)


def test_both_eliminations_of_the_partitioned_system_agree(small_block):
    eq = _linear_system(small_block)
    n, k = small_block.n_images, len(small_block.points)
    B, L, P = block_equations_dense(eq, n, k, free_points=_free(small_block))
    N = B.T @ (P[:, None] * B)
    LN = -B.T @ (P * L)                      # the right-hand side of (3.5.13)
    i = 6 * n
    full = np.linalg.solve(N, LN)
    for how in ("points", "eo"):
        d1, d2 = solve_partitioned_normal_equations(N[:i, :i], N[:i, i:], N[i:, i:], LN[:i], LN[i:], how)
        np.testing.assert_allclose(np.concatenate([d1, d2]), full, rtol=1e-6, atol=1e-8)


def test_sparse_and_dense_factorisation_agree(small_block):
    eq = _linear_system(small_block)
    n, k = small_block.n_images, len(small_block.points)
    ctrl = small_block.control
    free = _free(small_block)
    dense = solve_block_normal_equations(eq, n, k, free_points=free, dense_limit=10_000)
    sparse_ = solve_block_normal_equations(eq, n, k, free_points=free, dense_limit=0)
    np.testing.assert_allclose(sparse_.delta1, dense.delta1, rtol=1e-8, atol=1e-10)
    np.testing.assert_allclose(sparse_.delta2, dense.delta2, rtol=1e-8, atol=1e-8)
    assert np.all(dense.delta2[ctrl] == 0)


# --- the model ------------------------------------------------------------------------------------
def test_bundle_model_jacobian_matches_resection_model_and_point_partials_are_negated():
    bm = bundle_collinearity_model("kaw")
    J = bm.jacobian()
    Jr = collinearity_model("kaw").jacobian()
    assert sp.simplify(J[:, :6] - Jr) == sp.zeros(2, 6)
    assert sp.simplify(J[:, 6:] + J[:, :3]) == sp.zeros(2, 3)          # a₇…a₉ = −a₁…a₃


def test_fused_code_equals_lambdified_model():
    bm = bundle_collinearity_model("wak")
    res_fn, jac_fn = bm.compile()
    fused = compile_fused(bm)
    rng = np.random.default_rng(5)
    n = 50
    args = [rng.normal(0, 10, n), rng.normal(0, 10, n), 1000 + rng.normal(0, 5, n), *rng.normal(0, 0.05, (3, n)),
            rng.normal(0, 300, n), rng.normal(0, 300, n), rng.normal(0, 20, n), rng.normal(0, 30, n),
            rng.normal(0, 30, n), 100.0, 0.01, -0.02]
    F, J = fused(*args)
    np.testing.assert_allclose(F, res_fn(*args), rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(J, jac_fn(*args), rtol=1e-12, atol=1e-12)


def test_generated_module_is_up_to_date_with_the_sympy_model():
    """photolib/_bundle_generated.py is printed from sympy; regenerate with `python -m photolib.bundle`."""
    from pathlib import Path
    import photolib.bundle as bundle_module
    generated = Path(bundle_module.__file__).with_name("_bundle_generated.py").read_text()
    assert generated == bundle_module.generated_source()


# --- the adjustment ------------------------------------------------------------------------------
def test_noise_free_block_recovers_the_truth():
    blk = synthetic.aerial_block(2, 5, points_per_image=15, sigma=0.0, seed=11, order="wak")
    cams0, pts0 = blk.start_values(seed=2)
    res = bundle_adjustment(blk.observations, cams0, pts0, blk.io, order="wak",
                            control={i: blk.points[i] for i in blk.control})
    np.testing.assert_allclose(res.cameras, blk.cameras, atol=1e-6)
    np.testing.assert_allclose(res.points, blk.points, atol=1e-5)
    assert res.mu < 1e-8
    assert res.history[-1].vtpv < 1e-12


def test_statistical_honesty_on_a_simulated_block():
    """Monte-Carlo over noise: μ estimates σ, and point errors agree with the predicted m_j.

    Geometry fixed (18 images, 121 points, 6 fixed control points), 12 independent noise
    realisations. μ has dof = 203 per run, relative spread 1/√(2·203) ≈ 5 %, so the mean over 12
    runs has ≈ 1.4 %: it must be within 5 % of σ. For the normalised errors z = (X̂ − X)/m_j of
    all free points E[z²] = 1; pooled over 12 runs × 345 coordinates (correlated inside a run)
    we accept 0.8–1.25. The check-point r.m.s.² / predicted m_j² per axis (15 points × 12 runs,
    strongly correlated through the block deformation) must lie in 0.6–1.6.
    """
    blk = synthetic.aerial_block(3, 6, points_per_image=20, sigma=0.0, seed=21, n_check=15)
    sigma = 0.004
    control = {i: blk.points[i] for i in blk.control}
    free = np.ones(len(blk.points), bool)
    free[blk.control] = False
    cams0, pts0 = blk.start_values(seed=4)
    mus, z2, ratios = [], [], []
    for run in range(12):
        rng = np.random.default_rng(100 + run)
        obs = synthetic.Observations(blk.observations.image, blk.observations.point,
                                     blk.xy_true + rng.normal(0, sigma, blk.xy_true.shape))
        res = bundle_adjustment(obs, cams0, pts0, blk.io, control=control, sigma_image=sigma)
        mus.append(res.mu)
        z2.append(((res.points[free] - blk.points[free]) / res.points_std[free]) ** 2)
        st = check_point_statistics(res, blk.points, blk.check)
        ratios.append(st.rms ** 2 / st.predicted ** 2)
    assert np.mean(mus) == pytest.approx(sigma, rel=0.05)
    assert 0.8 < np.mean(np.concatenate(z2)) < 1.25
    ratio = np.mean(ratios, axis=0)
    assert np.all((0.6 < ratio) & (ratio < 1.6)), ratio


def test_gnss_centres_and_weighted_control():
    blk = synthetic.aerial_block(2, 6, points_per_image=15, sigma=0.003, seed=8)
    rng = np.random.default_rng(9)
    gnss_sigma = 0.05
    gnss = blk.cameras[:, :3] + rng.normal(0, gnss_sigma, (blk.n_images, 3))
    cams0, pts0 = blk.start_values(seed=5)
    # GNSS centres alone do not fix the roll about a single line of centres, but two strips do;
    # add one weighted control point to make it clearly determined
    one = blk.control[:1]
    res = bundle_adjustment(blk.observations, cams0, pts0, blk.io, gnss=gnss, gnss_sigma=gnss_sigma,
                            control={int(one[0]): blk.points[one[0]]}, control_sigma=0.05, sigma_image=0.003)
    centre_error = res.cameras[:, :3] - blk.cameras[:, :3]
    # errors are of the order of the GNSS accuracy, and within 4 m_j
    assert np.sqrt(np.mean(centre_error ** 2)) < 2 * gnss_sigma
    assert np.all(np.abs(centre_error) < 4 * res.cameras_std[:, :3] + 1e-3)
    np.testing.assert_allclose(res.gnss_residuals, res.cameras[:, :3] - gnss, atol=1e-6)
    assert res.mu == pytest.approx(0.003, rel=0.25)
    # without the control point the block is still determined by the GNSS centres of two strips
    res2 = bundle_adjustment(blk.observations, cams0, pts0, blk.io, gnss=gnss, gnss_sigma=gnss_sigma,
                             sigma_image=0.003)
    assert np.sqrt(np.mean((res2.cameras[:, :3] - blk.cameras[:, :3]) ** 2)) < 2 * gnss_sigma


# --- bad input -----------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def tiny_block():
    return synthetic.aerial_block(2, 3, points_per_image=12, sigma=0.003, seed=5)


def _run(blk, **kw):
    cams0, pts0 = blk.start_values(seed=1)
    args = dict(control={i: blk.points[i] for i in blk.control})
    args.update(kw)
    obs = args.pop("observations", blk.observations)
    return bundle_adjustment(obs, args.pop("cameras0", cams0), args.pop("points0", pts0), blk.io, **args)


def test_too_little_control_is_a_datum_defect(tiny_block):
    two = tiny_block.control[:2]
    with pytest.raises(DegenerateGeometryError, match="datum"):
        _run(tiny_block, control={i: tiny_block.points[i] for i in two})
    with pytest.raises(DegenerateGeometryError, match="datum"):
        _run(tiny_block, control=None)


def test_free_network_is_singular_in_the_solver_too(tiny_block):
    eq = _linear_system(tiny_block)
    with pytest.raises(DegenerateGeometryError, match="singular"):
        solve_block_normal_equations(eq, tiny_block.n_images, len(tiny_block.points))


def test_point_in_one_image_is_rejected(tiny_block):
    o = tiny_block.observations
    counts = np.bincount(o.point)
    p = int(np.flatnonzero((counts == 2) & (tiny_block.kind == synthetic.TIE))[0])
    drop = np.flatnonzero(o.point == p)[0]
    keep = np.arange(len(o)) != drop
    obs = synthetic.Observations(o.image[keep], o.point[keep], o.xy[keep])
    with pytest.raises(InputError, match=rf"points \[{p}\].*fewer than two"):
        _run(tiny_block, observations=obs)


def test_disconnected_block_is_rejected(tiny_block):
    o = tiny_block.observations
    # break every tie between image 0..2 (strip 1) and 3..5 (strip 2) by renaming strip-2 points
    k = len(tiny_block.points)
    second = o.image >= 3
    point = np.where(second, o.point + k, o.point)
    pts = np.vstack([tiny_block.points, tiny_block.points])
    ctrl_ids = np.concatenate([tiny_block.control, tiny_block.control + k])
    keep = np.bincount(point, minlength=2 * k)[point] >= 2          # both halves keep only multi-ray points
    used, point = np.unique(point[keep], return_inverse=True)
    obs = synthetic.Observations(o.image[keep], point, o.xy[keep])
    pts = pts[used]
    ctrl = {int(np.searchsorted(used, i)): pts[np.searchsorted(used, i)] for i in ctrl_ids if i in used}
    with pytest.raises(DegenerateGeometryError, match="falls apart into 2"):
        bundle_adjustment(obs, tiny_block.cameras, pts, tiny_block.io, control=ctrl)


def test_divergence_raises_convergence_error(tiny_block):
    # start values this far off put points behind cameras already: that is named as such before iterating
    cams0, pts0 = tiny_block.start_values(seed=1, angle_sigma=np.radians(40), centre_sigma=800)
    with pytest.raises(PointBehindCameraError) as info:
        _run(tiny_block, cameras0=cams0, points0=pts0, max_iter=8)
    assert info.value.points
    # from start values in front of every camera but too few iterations: ConvergenceError
    cams0, pts0 = tiny_block.start_values(seed=1)
    with pytest.raises(ConvergenceError):
        _run(tiny_block, cameras0=cams0, points0=pts0, max_iter=1)


@pytest.mark.parametrize("bad, match", [
    (dict(observations=np.zeros((5, 3))), "observations"),
    (dict(points0=np.full((3, 3), np.nan)), "points0"),
    (dict(cameras0=np.zeros((2, 5))), "cameras0"),
    (dict(control_sigma=-1.0), "σ must be positive"),
    (dict(gnss=np.zeros((2, 3))), "gnss"),
])
def test_bad_input_is_named(tiny_block, bad, match):
    with pytest.raises(InputError, match=match):
        _run(tiny_block, **bad)


def test_nan_observation_is_rejected(tiny_block):
    o = tiny_block.observations
    xy = o.xy.copy()
    xy[3, 1] = np.nan
    with pytest.raises(InputError, match="NaN"):
        _run(tiny_block, observations=synthetic.Observations(o.image, o.point, xy))


def test_synthetic_block_layout():
    blk = synthetic.aerial_block(3, 8, points_per_image=25, seed=2)
    per_image = np.bincount(blk.observations.image)
    assert 15 < per_image.mean() < 40
    assert np.all(np.bincount(blk.observations.point) >= 2)
    assert np.allclose(blk.base, 0.4 * 1000) and np.allclose(blk.strip_spacing, 0.7 * 1000)
    # noise-free projections reproduce the measurements up to the noise
    assert np.std(blk.observations.xy - blk.xy_true) == pytest.approx(blk.sigma, rel=0.1)
    again = synthetic.aerial_block(3, 8, points_per_image=25, seed=2)
    np.testing.assert_array_equal(again.observations.xy, blk.observations.xy)


def test_an_undetermined_image_is_named():
    """aerial_block(2, 3, points_per_image=10, seed=1): image 3 measures three points — control point
    17 (two equations for its orientation) and tie points 9 and 12, each seen by one other image
    only (four equations for its three coordinates: one left over for the orientation). Four
    equations for six unknowns: the error names image 3, in both linear solvers."""
    blk = synthetic.aerial_block(2, 3, points_per_image=10, seed=1)
    o = blk.observations
    assert sorted(o.point[o.image == 3]) == [9, 12, 17] and 17 in blk.control
    assert np.bincount(o.point)[[9, 12]].tolist() == [2, 2]
    cams0, pts0 = blk.start_values(seed=2)
    control = {int(i): blk.points[i] for i in blk.control}
    for covariance in (False, True):
        with pytest.raises(DegenerateGeometryError, match=r"image 3, which has 3 observations"):
            bundle_adjustment(o, cams0, pts0, blk.io, control=control, sigma_image=0.005, order=blk.order,
                              covariance=covariance)
