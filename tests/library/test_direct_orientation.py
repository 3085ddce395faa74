"""Tests of photolib.direct_orientation (Hanzl §7: least squares, sequential LS, Kalman filter,
GNSS/IMU, boresight calibration) against batch least squares, numpy.linalg.lstsq, scipy and
synthetic ground truth."""

import numpy as np
import pytest
import scipy.linalg
from scipy import stats

from photolib import direct_orientation as do
from photolib.derivations import direct_orientation as ddo
from photolib.errors import DegenerateGeometryError
from photolib.rotation import rotation_matrix


def _problem(seed=0, m1=10, m2=3, n=4):
    rng = np.random.default_rng(seed)
    A1, A2 = rng.normal(size=(m1, n)), rng.normal(size=(m2, n))
    p1, p2 = rng.uniform(0.5, 2.0, m1), rng.uniform(0.5, 2.0, m2)
    l1, l2 = rng.normal(size=m1), rng.normal(size=m2)
    return A1, A2, p1, p2, l1, l2


def test_least_squares_equals_numpy_lstsq():
    A1, _, p1, _, l1, _ = _problem()
    r = do.least_squares(A1, l1, p1)
    w = np.sqrt(p1)
    x_np, *_ = np.linalg.lstsq(A1 * w[:, None], l1 * w, rcond=None)
    np.testing.assert_allclose(r.x, x_np, rtol=0, atol=1e-12)
    np.testing.assert_allclose(r.Q, np.linalg.inv(A1.T @ np.diag(p1) @ A1), atol=1e-12)
    v = A1 @ x_np - l1
    assert r.dof == 6
    assert r.sigma0_sq == pytest.approx(v @ (p1 * v) / 6, rel=1e-12)


def test_least_squares_full_weight_matrix_equals_diagonal_vector():
    A1, _, p1, _, l1, _ = _problem(1)
    a, b = do.least_squares(A1, l1, p1), do.least_squares(A1, l1, np.diag(p1))
    np.testing.assert_allclose(a.x, b.x, atol=1e-13)


@pytest.mark.parametrize("form", ["lemma", "normal"])
def test_sequential_equals_batch(form):
    A1, A2, p1, p2, l1, l2 = _problem(2)
    first = do.least_squares(A1, l1, p1)
    x, Q, K = do.sequential_update(first.x, first.Q, A2, l2, p2, form=form)
    A, l, p = np.vstack([A1, A2]), np.r_[l1, l2], np.r_[p1, p2]
    w = np.sqrt(p)
    x_batch, *_ = np.linalg.lstsq(A * w[:, None], l * w, rcond=None)      # independent
    np.testing.assert_allclose(x, x_batch, rtol=0, atol=1e-10)
    np.testing.assert_allclose(Q, np.linalg.inv(A.T @ np.diag(p) @ A), rtol=0, atol=1e-10)


def test_sequential_in_several_steps_equals_batch():
    rng = np.random.default_rng(3)
    A, l = rng.normal(size=(20, 3)), rng.normal(size=20)
    r = do.least_squares(A[:5], l[:5])
    x, Q = r.x, r.Q
    for i in range(5, 20, 3):
        x, Q, _ = do.sequential_update(x, Q, A[i:i + 3], l[i:i + 3])
    x_batch, *_ = np.linalg.lstsq(A, l, rcond=None)
    np.testing.assert_allclose(x, x_batch, rtol=0, atol=1e-10)


def test_both_gain_forms_agree():
    A1, A2, p1, p2, _, _ = _problem(4, n=5, m2=2)
    Q0 = np.linalg.inv(A1.T @ np.diag(p1) @ A1)
    K1 = do.gain_matrix(Q0, A2, p2, form="normal")
    K2 = do.gain_matrix(Q0, A2, p2, form="lemma")
    np.testing.assert_allclose(K1, K2, rtol=0, atol=1e-12)
    # the explicit printed formulas, computed with plain inverses
    N1, N2, P2 = np.linalg.inv(Q0), A2.T @ np.diag(p2) @ A2, np.diag(p2)
    np.testing.assert_allclose(K1, np.linalg.inv(N1 + N2) @ A2.T @ P2, atol=1e-12)
    np.testing.assert_allclose(K2, Q0 @ A2.T @ np.linalg.inv(np.linalg.inv(P2) + A2 @ Q0 @ A2.T), atol=1e-12)


def test_prior_as_pseudo_observation():
    """x0 + v1 = x with weights Q0⁻¹ and l2 + v2 = A2 x, solved as one batch (§7.3.2)."""
    rng = np.random.default_rng(5)
    n = 3
    x0 = rng.normal(size=n)
    M = rng.normal(size=(n, n))
    Q0 = M @ M.T + np.eye(n)
    A2, l2, p2 = rng.normal(size=(4, n)), rng.normal(size=4), rng.uniform(1, 2, 4)
    x, Q, _ = do.sequential_update(x0, Q0, A2, l2, p2)
    P = scipy.linalg.block_diag(np.linalg.inv(Q0), np.diag(p2))
    batch = do.least_squares(np.vstack([np.eye(n), A2]), np.r_[x0, l2], P)
    np.testing.assert_allclose(x, batch.x, atol=1e-10)
    np.testing.assert_allclose(Q, batch.Q, atol=1e-10)


def test_transition_matrix_series_and_expm():
    F = np.zeros((6, 6))
    F[:3, 3:] = np.eye(3)
    T = do.transition_matrix(F, 0.5)
    expected = np.eye(6)
    expected[:3, 3:] = 0.5 * np.eye(3)                # constant velocity: exact T = I + FΔt
    np.testing.assert_allclose(T, expected, atol=1e-15)
    G = np.array([[0.0, 1.0], [-4.0, -0.3]])          # a damped oscillator: series → expm
    np.testing.assert_allclose(do.transition_matrix(G, 0.1, terms=25), scipy.linalg.expm(0.1 * G), atol=1e-14)
    np.testing.assert_allclose(do.transition_matrix(G, 0.1, terms=2), np.eye(2) + 0.1 * G, atol=1e-15)


def test_kalman_static_without_process_noise_equals_batch():
    """The issue's check: the Kalman filter and batch least squares give the same final estimate."""
    rng = np.random.default_rng(6)
    n, m, k = 3, 2, 15
    A = rng.normal(size=(m, n))
    x0, Q0 = rng.normal(size=n), np.diag([4.0, 9.0, 1.0])
    L = rng.normal(size=(k, m))
    Ql = np.diag([0.5, 2.0])
    xs, Qs = do.kalman_filter(x0, Q0, np.eye(n), A, L, Ql)
    P = scipy.linalg.block_diag(np.linalg.inv(Q0), *[np.linalg.inv(Ql)] * k)
    Abig = np.vstack([np.eye(n)] + [A] * k)
    lbig = np.concatenate([x0, L.ravel()])
    W = np.linalg.cholesky(P)                               # independent: whitened numpy lstsq
    x_batch, *_ = np.linalg.lstsq(W.T @ Abig, W.T @ lbig, rcond=None)
    np.testing.assert_allclose(xs[-1], x_batch, rtol=0, atol=1e-10)
    np.testing.assert_allclose(Qs[-1], np.linalg.inv(Abig.T @ P @ Abig), rtol=0, atol=1e-10)


def test_kalman_dynamic_without_process_noise_equals_batch_at_last_epoch():
    """Constant velocity, no process noise: the filter's last state is batch LS of all epochs."""
    rng = np.random.default_rng(7)
    dt, k = 0.5, 12
    T = do.transition_matrix([[0.0, 1.0], [0.0, 0.0]], dt)
    A = np.array([[1.0, 0.0]])
    L = (3.0 + 2.0 * dt * np.arange(k) + rng.normal(0, 0.1, k))[:, None]
    xs, _ = do.kalman_filter([0.0, 0.0], np.diag([1e8, 1e8]), T, A, L, [0.01])
    t_last = dt * (k - 1)
    design = np.column_stack([np.ones(k), dt * np.arange(k) - t_last])   # state at the last epoch
    x_batch, *_ = np.linalg.lstsq(design, L[:, 0], rcond=None)
    np.testing.assert_allclose(xs[-1], x_batch, atol=1e-5)             # the 1e8 prior: ~1e-7 effect


def test_integrate_imu_bias_drift_is_half_b_t_squared():
    # Hanzl §7: 0.5–1 m after 1 min ↔ a bias b = 2·d/t², i.e. 2.78e-4…5.56e-4 m/s²
    for d in (0.5, 1.0):
        b = 2 * d / 60.0 ** 2
        p, v = do.integrate_imu(np.full((6000, 3), [b, 0.0, 0.0]), 0.01, np.zeros(3), np.zeros(3))
        assert p[-1, 0] == pytest.approx(d, rel=1e-10)
        assert v[-1, 0] == pytest.approx(b * 60.0, rel=1e-10)


def test_integrate_imu_reproduces_simulated_truth():
    tr = do.simulate_gnss_imu(duration=10.0, sigma_acc=0.0)
    p, v = do.integrate_imu(tr.acc, tr.dt, tr.position[0], tr.velocity[0])
    np.testing.assert_allclose(v, tr.velocity, atol=1e-9)
    np.testing.assert_allclose(p, tr.position, atol=1e-4)      # midpoint-of-step discretisation of the sway


def _run_filter(tr):
    x0 = np.r_[tr.gnss[0], tr.velocity[0]]
    return do.gnss_imu_filter(tr.acc, tr.dt, tr.gnss, tr.gnss_index, x0,
                              np.diag([tr.sigma_gnss ** 2] * 3 + [0.01] * 3), tr.sigma_acc, tr.sigma_gnss)


def test_filter_beats_raw_gnss():
    tr = do.simulate_gnss_imu(seed=11, duration=60.0, imu_rate=50.0, gnss_rate=2.0)
    x, _ = _run_filter(tr)
    i = tr.gnss_index[10:]
    rms_filter = np.sqrt(np.mean((x[i, :3] - tr.position[i]) ** 2))
    rms_gnss = np.sqrt(np.mean((tr.gnss[10:] - tr.position[i]) ** 2))
    assert rms_filter < 0.7 * rms_gnss


def test_free_inertial_drift_vs_filter():
    """A 40 µg-class bias drifts ~0.7 m in 60 s without GNSS (Hanzl: 0.5–1 m); the filter stays near σ_GNSS."""
    b = 2 * 0.75 / 60.0 ** 2
    tr = do.simulate_gnss_imu(seed=12, duration=60.0, imu_rate=50.0, acc_bias=(b, b, 0.0), sigma_acc=0.0)
    p, _ = do.integrate_imu(tr.acc, tr.dt, tr.position[0], tr.velocity[0])
    drift = np.linalg.norm(p[-1, :2] - tr.position[-1, :2])
    assert drift == pytest.approx(np.hypot(0.75, 0.75), rel=1e-3)


def test_filter_covariance_is_consistent():
    """Final-epoch normalised errors eᵀQ⁻¹e over independent runs follow χ²(6)."""
    nees = []
    for seed in range(40):
        tr = do.simulate_gnss_imu(seed=100 + seed, duration=10.0, imu_rate=20.0, gnss_rate=2.0)
        x, Q = _run_filter(tr)
        e = x[-1] - np.r_[tr.position[-1], tr.velocity[-1]]
        nees.append(e @ np.linalg.solve(Q[-1], e))
    total, dof = float(np.sum(nees)), 6 * len(nees)
    assert stats.chi2.ppf(0.0005, dof) < total < stats.chi2.ppf(0.9995, dof)


def test_boresight_model_matches_projection_used_in_simulation():
    b = do.simulate_boresight_block(sigma_xy=0.0)
    r, _ = ddo.boresight_functions()
    k = len(b.xy)
    res = r(*b.shift, *b.angles, *b.gnss[b.image].T, *b.A_imu[b.image].reshape(k, 9).T, *b.points.T,
            np.full(k, b.f), *b.xy.T)
    assert np.max(np.abs(res)) < 1e-9


def test_boresight_jacobian_against_finite_differences():
    b = do.simulate_boresight_block(sigma_xy=0.0)
    r, J = ddo.boresight_functions()
    k = len(b.xy)
    data = (*b.gnss[b.image].T, *b.A_imu[b.image].reshape(k, 9).T, *b.points.T, np.full(k, b.f), *b.xy.T)
    x = np.r_[b.shift, b.angles]
    jac = np.array([np.broadcast_to(np.asarray(v, float), (k,)) for v in J(*x, *data)]).reshape(2, 6, k)
    for j, h in enumerate([1e-3] * 3 + [1e-7] * 3):
        dx = np.zeros(6)
        dx[j] = h
        num = (np.array(r(*(x + dx), *data)) - np.array(r(*(x - dx), *data))) / (2 * h)
        np.testing.assert_allclose(jac[:, j], num, rtol=1e-5, atol=1e-9)


def test_boresight_recovered_exactly_without_noise():
    b = do.simulate_boresight_block(seed=1, sigma_xy=0.0)
    cal = do.calibrate_boresight(b.xy, b.image, b.points, b.gnss, b.A_imu, b.f)
    np.testing.assert_allclose(cal.shift, b.shift, atol=1e-6)
    np.testing.assert_allclose(cal.angles, b.angles, atol=1e-10)
    np.testing.assert_allclose(cal.boresight, rotation_matrix(*b.angles, order="wak"), atol=1e-10)


def test_boresight_recovered_within_3_sigma():
    b = do.simulate_boresight_block(seed=0)
    cal = do.calibrate_boresight(b.xy, b.image, b.points, b.gnss, b.A_imu, b.f, sigma_xy=b.sigma_xy)
    z = (np.r_[cal.shift, cal.angles] - np.r_[b.shift, b.angles]) / cal.std
    assert np.all(np.abs(z) < 3)


def test_boresight_errors_follow_their_covariance():
    """Over many simulated blocks, Σ z² with z = error/σ_apriori·√Q_jj is χ²(6·runs)."""
    z2 = 0.0
    runs = 15
    for seed in range(runs):
        b = do.simulate_boresight_block(seed=200 + seed)
        cal = do.calibrate_boresight(b.xy, b.image, b.points, b.gnss, b.A_imu, b.f, sigma_xy=b.sigma_xy)
        e = np.r_[cal.shift, cal.angles] - np.r_[b.shift, b.angles]
        z2 += float(e @ np.linalg.solve(cal.adjustment.Q, e))
    assert stats.chi2.ppf(0.0005, 6 * runs) < z2 < stats.chi2.ppf(0.9995, 6 * runs)


def test_boresight_one_image_collinear_points_is_degenerate():
    """Control points on one line in one image leave a rotation about that line free."""
    b = do.simulate_boresight_block(seed=3, sigma_xy=0.0)
    from photolib.lidar import scanner_camera_project
    from photolib.georef import sensor_pose
    S, A = sensor_pose(b.gnss[0] + b.shift, b.A_imu[0], np.zeros(3), np.zeros(3),
                       rotation_matrix(*b.angles, order="wak"))
    line = b.gnss[0] + [0.0, 0.0, -1530.0] + np.outer(np.linspace(-500, 500, 6), [1.0, 0.3, 0.05])
    xy = scanner_camera_project(line, S[0], A[0], b.f)
    with pytest.raises(DegenerateGeometryError):
        do.calibrate_boresight(xy, np.zeros(6, int), line, b.gnss, b.A_imu, b.f)


def test_earth_rate_is_the_printed_value_and_close_to_sidereal():
    assert do.EARTH_RATE == 7.29211e-5
    assert do.EARTH_RATE == pytest.approx(2 * np.pi / 86164.0905, abs=1e-10)


def test_estimation_derivations_agree_with_the_numeric_sequential_update():
    """The sympy blocks of photolib.derivations.estimation, evaluated at numbers, give the same Δx
    and ΔQ as photolib.direct_orientation.sequential_update (two independent routes)."""
    import sympy as sp
    from photolib.derivations import estimation as E
    d = E.sequential_blocks(1)
    N1 = np.array([[5.0, 1.0], [1.0, 3.0]])
    h1, A2, P2, l2 = np.array([1.0, -2.0]), np.array([[0.5, 2.0]]), np.array([4.0]), np.array([0.7])
    values = {sp.Symbol("n11", real=True): 5, sp.Symbol("n12", real=True): 1, sp.Symbol("n22", real=True): 3,
              sp.Symbol("h11", real=True): 1, sp.Symbol("h21", real=True): -2,
              sp.Symbol("b11", real=True): sp.Rational(1, 2), sp.Symbol("b12", real=True): 2,
              sp.Symbol("w1", positive=True): 4, sp.Symbol("k11", real=True): sp.Rational(7, 10)}
    dx = np.array(d["dx"].subs(values), dtype=float).ravel()
    dQ = np.array(d["dQ"].subs(values), dtype=float)
    Q0 = np.linalg.inv(N1)
    x, Q, _ = do.sequential_update(Q0 @ h1, Q0, A2, l2, np.diag(P2))
    assert np.allclose(x - Q0 @ h1, dx, atol=1e-12) and np.allclose(Q - Q0, dQ, atol=1e-12)
