"""photolib.mrf — the MRF terrain paper (Baikalova et al.) against independent ground truth.

Expected values come from numpy.corrcoef (Pearson's r), synthetic pairs with a known parallax
field, exact softmax probabilities (the sampler with b = 0), and synthetic cameras and points.
"""

import numpy as np
import pytest
from scipy.ndimage import gaussian_filter, map_coordinates

from photolib import mrf
from photolib.camera import ExteriorOrientation
from photolib.errors import InputError
from photolib.rotation import rot_x, rot_y, rot_z
from photolib.synthetic import stereo_pair


def _texture(shape, seed, sigma=1.0):
    return gaussian_filter(np.random.default_rng(seed).standard_normal(shape), sigma)


# --- correlation --------------------------------------------------------------------------------
def test_correlation_coefficient_is_pearson():
    rng = np.random.default_rng(0)
    for _ in range(20):
        w1 = rng.random((7, 7))
        w2 = 0.6 * w1 + 0.4 * rng.random((7, 7))
        expected = np.corrcoef(w1.ravel(), w2.ravel())[0, 1]
        assert mrf.correlation_coefficient(w1, w2) == pytest.approx(expected, abs=1e-14)
        # invariant to a linear brightness change of either window
        assert mrf.correlation_coefficient(3 * w1 + 50, 0.2 * w2 - 7) == pytest.approx(expected, abs=1e-12)


def test_correlation_volume_equals_corrcoef_of_the_windows():
    rng = np.random.default_rng(1)
    right = 100 + 40 * rng.random((30, 50))
    left = 100 + 40 * rng.random((24, 40))
    P = np.arange(-3, 6)
    shift = (4, 2)
    r = mrf.correlation_volume(left, right, P, window=5, shift=shift)
    checked = 0
    for _ in range(200):
        k, y, x = rng.integers(len(P)), rng.integers(24), rng.integers(40)
        x2, y2 = x + shift[0] + P[k], y + shift[1]
        inside = 2 <= y < 22 and 2 <= x < 38 and 2 <= y2 < 28 and 2 <= x2 < 48
        if not inside:
            assert np.isnan(r[k, y, x])
            continue
        w1 = left[y - 2:y + 3, x - 2:x + 3]
        w2 = right[y2 - 2:y2 + 3, x2 - 2:x2 + 3]
        assert r[k, y, x] == pytest.approx(np.corrcoef(w1.ravel(), w2.ravel())[0, 1], abs=1e-6)  # float32 storage
        checked += 1
    assert checked > 100


def test_textureless_windows_are_undefined():
    left = _texture((20, 30), 2)
    left[5:15, 5:15] = 0.7
    right = left.copy()
    r = mrf.correlation_volume(left, right, [0], window=5)
    assert np.isnan(r[0, 10, 10])
    assert r[0, 10, 20] == pytest.approx(1.0, abs=1e-6)


def test_known_parallax_field_is_recovered():
    """Piecewise-constant integer parallaxes on random texture: WTA exact away from the steps."""
    H, W = 60, 80
    right = _texture((H, W + 20), 3)
    p_true = np.full((H, W), 3)
    p_true[:, 40:] = 7
    p_true[20:40, 10:30] = 11
    yy, xx = np.mgrid[0:H, 0:W]
    left = right[yy, xx + p_true]
    P = np.arange(0, 15)
    r = mrf.correlation_volume(left, right, P, window=5)
    p, rmax = mrf.winner_takes_all(r, P)
    # pixels whose 5×5 window sees one parallax only
    from scipy.ndimage import maximum_filter, minimum_filter
    uniform = (maximum_filter(p_true, 5) == minimum_filter(p_true, 5))
    inner = np.zeros_like(uniform)
    inner[2:-2, 2:-2] = True
    sel = uniform & inner
    assert sel.sum() > 2500
    np.testing.assert_array_equal(p[sel], p_true[sel])
    assert np.all(rmax[sel] > 0.999)


def test_find_overlap_shift_recovers_a_known_shift():
    scene = _texture((300, 400), 4, sigma=2.0)
    left = scene[40:240, 10:290]
    right = scene[13:213, 93:373]                 # left (x, y) is right (x − 83, y + 27)
    x0, y0, r = mrf.find_overlap_shift(left, right, max_shift=(120, 60))
    assert (x0, y0) == (-83, 27)
    assert r == pytest.approx(1.0, abs=1e-9)


def test_parallax_count_matches_the_parallax_of_the_heights():
    """N·pixel = parallax difference of H_min and H_max: p(h) = f·B/(H − h), f = H/M (first order)."""
    B, dpi, H, M = 2160.0, 300, 2100.0, 30000
    N = mrf.parallax_count(100.0, -100.0, B, dpi, H, M)
    f = H / M
    dp = f * B * (1 / (H - 100.0) - 1 / (H + 100.0))          # m on the photo, exact for a vertical pair
    assert N == pytest.approx(dp / (0.0254 / dpi), rel=3e-3)   # second-order term (Δh/2H)² ≈ 2e-3
    assert mrf.parallax_count(100.0, -100.0, B, dpi, H, M, constant=0.245) == pytest.approx(N * 0.0254 / 0.245)


# --- the MRF relaxation -----------------------------------------------------------------------
def _noisy_pair():
    rng = np.random.default_rng(3)
    H, W, PMAX = 64, 96, 12
    yy, xx = np.mgrid[0:H, 0:W].astype(float)
    p_true = 5 + 3 * np.sin(xx / 15.0) + 1.5 * np.cos(yy / 11.0)
    right = gaussian_filter(rng.standard_normal((H, W + PMAX + 10)), 1.0)
    right[40:52, 30:60] = 0.0                                     # a textureless patch (water)
    left = map_coordinates(right, [yy, xx + p_true], order=3)
    left = left + 0.15 * rng.standard_normal(left.shape)
    right = right + 0.15 * rng.standard_normal(right.shape)
    return left, right, p_true, np.arange(0, PMAX + 1)


def test_relaxation_lowers_the_energy_and_beats_winner_takes_all():
    left, right, p_true, P = _noisy_pair()
    r = mrf.correlation_volume(left, right, P, window=5)
    wta, _ = mrf.winner_takes_all(r, P)
    res = mrf.gibbs_relaxation(r, P, a=10.0, b=-0.5, sweeps=30, burn_in=10, seed=0)
    assert res.energy[-1] < res.energy[0]
    assert mrf.mrf_energy(res.parallax, r, P, 10.0, -0.5) < mrf.mrf_energy(res.initial, r, P, 10.0, -0.5)
    sl = np.s_[3:-3, 3:-3]
    bad = lambda est: float(np.mean(np.abs(est - p_true)[sl] > 1))              # noqa: E731
    rmse = lambda est: float(np.sqrt(np.mean((est - p_true)[sl] ** 2)))         # noqa: E731
    assert bad(res.parallax) <= 0.5 * bad(wta)          # measured 0.033 vs 0.14
    assert rmse(res.parallax) <= 0.6 * rmse(wta)        # measured 0.46 vs 1.59 px
    patch = np.s_[40:52, 30:60]
    assert np.mean(np.abs(res.parallax - p_true)[patch] > 1) <= 0.5 * np.mean(np.abs(wta - p_true)[patch] > 1)


def test_relaxation_is_deterministic():
    left, right, _, P = _noisy_pair()
    r = mrf.correlation_volume(left[:30, :40], right[:30, :60], P, window=5)
    one = mrf.gibbs_relaxation(r, P, sweeps=8, burn_in=2, seed=5)
    two = mrf.gibbs_relaxation(r, P, sweeps=8, burn_in=2, seed=5)
    np.testing.assert_array_equal(one.parallax, two.parallax)
    np.testing.assert_array_equal(one.energy, two.energy)


def test_without_smoothness_the_marginals_are_the_softmax_of_the_correlation():
    """b = 0: pixels are independent and P(x, y, p) = exp(a r)/Σ exp(a r) exactly."""
    rng = np.random.default_rng(6)
    r = rng.uniform(-1, 1, (4, 3, 3))
    a = 1.5
    res = mrf.gibbs_relaxation(r, [0, 1, 2, 3], a=a, b=0.0, sweeps=2100, burn_in=100, seed=2)
    expected = np.exp(a * r) / np.exp(a * r).sum(axis=0)
    sigma = np.sqrt(expected * (1 - expected) / 2000)
    assert np.all(np.abs(res.marginals - expected) < 4.5 * sigma + 1e-12)


def test_printed_sign_of_b_is_refused_and_roughens():
    left, right, p_true, P = _noisy_pair()
    r = mrf.correlation_volume(left, right, P, window=5)
    with pytest.raises(InputError, match="negative"):
        mrf.gibbs_relaxation(r, P, b=0.5)
    rough = mrf.gibbs_relaxation(r, P, a=10.0, b=0.5, sweeps=5, burn_in=1, as_printed=True)
    wta, _ = mrf.winner_takes_all(r, P)
    assert np.nanmean(np.abs(rough.parallax - p_true)) > 2 * np.nanmean(np.abs(wta - p_true))


# --- geometry -----------------------------------------------------------------------------------
def test_direction_cosines_are_the_alpha_omega_chi_product():
    rng = np.random.default_rng(7)
    for al, om, ch in rng.uniform(-1.2, 1.2, (10, 3)):
        A = mrf.direction_cosines(al, om, ch)
        np.testing.assert_allclose(A, rot_y(-al) @ rot_x(om) @ rot_z(ch), atol=1e-15)
        np.testing.assert_allclose(A.T @ A, np.eye(3), atol=1e-15)
        np.testing.assert_allclose(mrf.direction_cosine_angles(A), (al, om, ch), atol=1e-12)


def test_base_direction_reads_the_first_column():
    for al, ch in [(0.1, 0.2), (-0.3, 0.05), (0.0, -0.4)]:
        tau, v = mrf.base_direction(np.eye(3), al, ch)
        u = np.array([np.cos(v) * np.cos(tau), np.cos(v) * np.sin(tau), np.sin(v)])
        np.testing.assert_allclose(u, [np.cos(al) * np.cos(ch), np.sin(ch), np.sin(al) * np.cos(ch)], atol=1e-15)


def test_relative_orientation_and_intersection_round_trip():
    """Steps 1–6 on a synthetic tilted pair: the free model is the truth in the left camera's axes."""
    pair = stereo_pair(30, seed=2, angle_spread_deg=3.0, relief=60.0)
    S1, S2 = pair.centres
    A1 = pair.eo1.matrix
    B = np.linalg.norm(S2 - S1)
    po = mrf.orient_pair(pair.xy1, pair.xy2, pair.io, base_length=B)
    np.testing.assert_allclose(po.A1.T @ po.A2, A1.T @ pair.eo2.matrix, atol=1e-9)
    np.testing.assert_allclose(po.base, A1.T @ (S2 - S1), atol=1e-6)
    h1 = mrf.reduce_to_horizontal(pair.xy1 - [pair.io.x0, pair.io.y0], pair.io.f, po.A1)
    h2 = mrf.reduce_to_horizontal(pair.xy2 - [pair.io.x0, pair.io.y0], pair.io.f, po.A2)
    model = mrf.intersect_horizontal(h1, h2, po.base, pair.io.f, po.S1)
    truth = (pair.points - S1) @ A1          # A1ᵀ(P − S1) row-wise
    np.testing.assert_allclose(model, truth, atol=1e-6)


def test_parallax_to_model_on_a_normal_case_scan():
    """Vertical cameras, base along x: the right scan column of a point is column + parallax."""
    f, s, c = 100.0, 0.05, np.array([200.0, 150.0])
    S1, S2 = np.array([0.0, 0.0, 1000.0]), np.array([300.0, 0.0, 1000.0])
    rng = np.random.default_rng(8)
    P = np.column_stack([rng.uniform(100, 200, 20), rng.uniform(-100, 100, 20), rng.uniform(-50, 50, 20)])
    eo1, eo2 = ExteriorOrientation(*S1, 0, 0, 0), ExteriorOrientation(*S2, 0, 0, 0)

    def pixels(eo):
        d = (P - eo.center) @ eo.matrix
        xy = -f * d[:, :2] / d[:, 2:3]
        return np.column_stack([xy[:, 0] / s + c[0], -xy[:, 1] / s + c[1]])

    px1, px2 = pixels(eo1), pixels(eo2)
    np.testing.assert_allclose(px1[:, 1], px2[:, 1], atol=1e-9)
    E = np.eye(3)
    po = mrf.PairOrientation(0, 0, 0, 0, 0, 0, 0, E, E, S1, S2, f)
    out = mrf.parallax_to_model(px1, px2[:, 0] - px1[:, 0], po, s, c)
    np.testing.assert_allclose(out, P, atol=1e-9)


def test_absolute_orientation_from_two_full_and_one_height_point():
    rng = np.random.default_rng(5)
    model = np.column_stack([rng.uniform(-60, 60, (8, 2)), rng.uniform(-5, 5, 8)])
    zeta, xi, nu, t, X0 = 0.03, -0.02, 0.6, 8.5, np.array([1000.0, 2000.0, 150.0])
    geo = X0 + t * model @ mrf.direction_cosines(zeta, xi, nu).T
    mask = np.zeros((8, 3), bool)
    mask[0] = mask[1] = True
    mask[2, 2] = True
    mo = mrf.orient_model(model, np.where(mask, geo, np.nan), mask)
    np.testing.assert_allclose([mo.zeta, mo.xi, mo.nu, mo.t], [zeta, xi, nu, t], atol=1e-9)
    np.testing.assert_allclose([mo.X0, mo.Y0, mo.Z0], X0, atol=1e-6)
    np.testing.assert_allclose(mo.apply(model[3:]), geo[3:], atol=1e-6)      # check points


def test_convergence_rotation_is_a_rotation_about_z():
    pts = np.random.default_rng(9).normal(size=(5, 3))
    np.testing.assert_allclose(mrf.convergence_rotation(pts, 0.0), pts)
    out = mrf.convergence_rotation(pts, 0.3)
    np.testing.assert_allclose(out, pts @ rot_z(0.3).T, atol=1e-15)
