"""The least-squares engine (1.8.5)–(1.8.10) against numpy/scipy and textbook statistics."""

import numpy as np
import pytest

from photolib.errors import ConvergenceError, DegenerateGeometryError, InputError
from photolib.lsq import gauss_newton, solve_normal_equations


def test_linear_step_matches_numpy_lstsq():
    rng = np.random.default_rng(1)
    B = rng.normal(size=(20, 4))
    L = rng.normal(size=20)
    delta, Q = solve_normal_equations(B, L)
    expected = np.linalg.lstsq(B, -L, rcond=None)[0]
    np.testing.assert_allclose(delta, expected, rtol=1e-10)
    np.testing.assert_allclose(Q, np.linalg.inv(B.T @ B), rtol=1e-9)


def test_weights_equal_scaled_rows():
    rng = np.random.default_rng(2)
    B, L, p = rng.normal(size=(15, 3)), rng.normal(size=15), rng.uniform(0.5, 4, 15)
    d1, Q1 = solve_normal_equations(B, L, p)
    d2, Q2 = solve_normal_equations(B * np.sqrt(p)[:, None], L * np.sqrt(p))
    d3, _ = solve_normal_equations(B, L, np.diag(p))
    np.testing.assert_allclose(d1, d2, rtol=1e-10)
    np.testing.assert_allclose(d1, d3, rtol=1e-10)
    np.testing.assert_allclose(Q1, Q2, rtol=1e-10)


def test_accuracy_of_a_straight_line_fit_matches_scipy_linregress():
    from scipy.stats import linregress
    rng = np.random.default_rng(3)
    t = np.linspace(0, 10, 30)
    obs = 2.0 + 0.5 * t + rng.normal(0, 0.1, t.size)
    res = gauss_newton(lambda p: (np.column_stack([np.ones_like(t), t]), p[0] + p[1] * t - obs), [0.0, 0.0],
                       names=("a", "b"))
    ref = linregress(t, obs)
    np.testing.assert_allclose(res.x, [ref.intercept, ref.slope], rtol=1e-10)
    np.testing.assert_allclose(res.std, [ref.intercept_stderr, ref.stderr], rtol=1e-8)
    expected_r = -t.mean() / np.sqrt(np.mean(t ** 2))      # r(a, b) of a line fit
    assert res.corr[0, 1] == pytest.approx(expected_r, rel=1e-10)
    assert res.dof == 28 and res.converged


def test_nonlinear_fit_converges_and_records_history():
    t = np.linspace(0, 1, 12)
    truth = np.array([3.0, -1.5])
    obs = truth[0] * np.exp(truth[1] * t)

    def lin(p):
        e = np.exp(p[1] * t)
        return np.column_stack([e, p[0] * t * e]), p[0] * e - obs

    res = gauss_newton(lin, [2.0, -1.0], tol=1e-13)
    np.testing.assert_allclose(res.x, truth, rtol=1e-10)
    assert len(res.history) == res.iterations >= 3
    assert res.history[0].vtpv > res.history[-1].vtpv


def test_singular_geometry_is_named():
    B = np.column_stack([np.ones(5), 2 * np.ones(5)])
    with pytest.raises(DegenerateGeometryError, match="singular"):
        solve_normal_equations(B, np.zeros(5), names=("p", "q"))
    with pytest.raises(DegenerateGeometryError, match="q"):
        solve_normal_equations(np.column_stack([np.ones(5), np.zeros(5)]), np.zeros(5), names=("p", "q"))


def test_bad_input_and_divergence():
    with pytest.raises(InputError, match="NaN"):
        solve_normal_equations(np.array([[1.0], [np.nan]]), np.zeros(2))
    with pytest.raises(InputError, match="positive"):
        solve_normal_equations(np.eye(3), np.zeros(3), [1.0, -1.0, 1.0])
    with pytest.raises(InputError, match="cannot determine"):
        solve_normal_equations(np.ones((1, 2)), np.zeros(1))
    with pytest.raises(ConvergenceError) as info:      # a fixed point that Gauss-Newton never reaches
        gauss_newton(lambda p: (np.array([[1.0]]), np.array([1.0])), [0.0], max_iter=5)
    assert len(info.value.history) == 5


def test_point_weights_shapes_and_errors():
    from photolib.lsq import point_weights
    assert point_weights(None, 3) is None
    np.testing.assert_array_equal(point_weights([1.0, 2.0], 2), [1.0, 1.0, 2.0, 2.0])
    np.testing.assert_array_equal(point_weights([[1.0, 3.0], [2.0, 4.0]], 2), [1.0, 3.0, 2.0, 4.0])
    with pytest.raises(InputError, match="expected shape"):
        point_weights([1.0, 2.0, 3.0], 2)
    with pytest.raises(InputError, match="positive"):
        point_weights([1.0, 0.0], 2)
