"""Bad-input catalogue for photolib.direct_orientation and photolib.derivations.direct_orientation (Hanzl §7)."""

import numpy as np
import pytest

from catalogue import INF, NAN, Case, check_case
from photolib import direct_orientation as do
from photolib.derivations import direct_orientation as ddo
from photolib.derivations import estimation as est
from photolib.errors import DegenerateGeometryError, InputError

A3 = np.array([[1.0, 0.0], [1.0, 1.0], [1.0, 2.0]])
L3 = np.array([1.0, 2.0, 3.0])
TR = do.simulate_gnss_imu(duration=1.0, imu_rate=10.0)
X0 = np.r_[TR.gnss[0], 50.0, 0, 0]
Q06 = np.eye(6)
BB = do.simulate_boresight_block(sigma_xy=0.0)
B_ARGS = (BB.xy, BB.image, BB.points, BB.gnss, BB.A_imu, BB.f)


def _with(args, i, value):
    a = list(args)
    a[i] = value
    return tuple(a)


CASES = [
    Case(do.least_squares, (A3, [1.0, NAN, 3.0]), raises=InputError, why="NaN observation"),
    Case(do.least_squares, (A3, L3[:2]), raises=InputError, why="l shorter than A"),
    Case(do.least_squares, (A3[:1], L3[:1]), raises=InputError, why="fewer observations than unknowns"),
    Case(do.least_squares, (A3, L3, [1.0, -1.0, 1.0]), raises=InputError, why="negative weight"),
    Case(do.least_squares, (A3, L3, [[1.0, 2.0, 0], [0, 1, 0], [0, 0, 1]]), raises=InputError,
         why="non-symmetric P"),
    Case(do.least_squares, (np.ones((3, 2)), L3), raises=DegenerateGeometryError, why="dependent columns"),
    Case(do.least_squares, ("abc", L3), raises=InputError, why="non-numeric A"),
    Case(do.least_squares, ([[1.0], [1.0]], [1.0, 3.0]), raises=None, check=lambda r: r.x[0] == pytest.approx(2.0),
         why="minimal redundant problem"),
    Case(do.LeastSquaresResult, (np.zeros(1), np.eye(1), np.zeros(1), 0.0, 0), raises=None,
         check=lambda r: r.dof == 0, why="plain container"),
    Case(do.gain_matrix, (np.eye(2), [[1.0, 1.0]], [2.0], "inverse"), raises=InputError, match="form",
         why="unknown form"),
    Case(do.gain_matrix, (-np.eye(2), [[1.0, 1.0]]), raises=InputError, match="positive definite",
         why="negative-definite Q0"),
    Case(do.gain_matrix, (np.eye(3), [[1.0, 1.0]]), raises=InputError, why="Q0 of the wrong size"),
    Case(do.gain_matrix, (np.eye(2), [[1.0, INF]]), raises=InputError, why="inf in A2"),
    Case(do.sequential_update, ([1.0, 2.0], np.eye(2), [[1.0, 1.0]], [1.0, 2.0]), raises=InputError,
         why="l2 longer than A2"),
    Case(do.sequential_update, ([1.0], np.eye(2), [[1.0, 1.0]], [1.0]), raises=InputError, why="x0 too short"),
    Case(do.sequential_update, ([0.0, 0.0], np.eye(2), [[1.0, 1.0]], [1.0], [0.0]), raises=InputError,
         why="zero weight"),
    Case(do.transition_matrix, ([[0.0, 1.0]], 1.0), raises=InputError, why="F not square"),
    Case(do.transition_matrix, (np.eye(2), NAN), raises=InputError, why="NaN dt"),
    Case(do.transition_matrix, (np.eye(2), 1.0, 0), raises=InputError, match="terms", why="zero terms"),
    Case(do.transition_matrix, (np.eye(2), 1.0, 2.5), raises=InputError, match="terms", why="fractional terms"),
    Case(do.kalman_predict, ([0.0, 1.0], np.eye(2), np.eye(3)), raises=InputError, why="T of the wrong size"),
    Case(do.kalman_predict, ([0.0, 1.0], np.eye(2), np.eye(2), -np.eye(2)), raises=InputError,
         match="semi-definite", why="negative process noise"),
    Case(do.kalman_predict, ([0.0, 1.0], np.eye(2), np.eye(2), None, [1.0]), raises=InputError,
         why="input of the wrong length"),
    Case(do.kalman_update, ([0.0], [[1.0]], [[1.0]], [2.0], [0.0]), raises=InputError, why="zero variance"),
    Case(do.kalman_update, ([0.0], [[0.0]], [[1.0]], [2.0], [[1.0]]), raises=None,
         check=lambda r: r[0][0] == 0.0, why="exact prior (zero covariance): observation ignored"),
    Case(do.kalman_update, ([0.0, 0.0], np.eye(2), [[1.0]], [2.0], [1.0]), raises=InputError,
         why="A with the wrong number of columns"),
    Case(do.kalman_filter, ([0.0], [[1.0]], [[1.0]], [[1.0]], [[1.0, 2.0]], [1.0]), raises=InputError,
         why="observation rows of the wrong width"),
    Case(do.kalman_filter, ([0.0], [[1.0]], [[1.0]], [[1.0]], np.zeros((0, 1)), [1.0]), raises=InputError,
         why="no epochs"),
    Case(do.kalman_filter, ([0.0], [[1.0]], [[1.0]], [[1.0]], [[NAN]], [1.0]), raises=InputError,
         why="NaN observation"),
    Case(do.integrate_imu, (np.zeros((3, 3)), 0.0, np.zeros(3), np.zeros(3)), raises=InputError, why="dt = 0"),
    Case(do.integrate_imu, (np.zeros((3, 3)), 0.1, np.zeros(2), np.zeros(3)), raises=InputError,
         why="p0 of the wrong length"),
    Case(do.integrate_imu, (np.zeros(3), 0.1, np.zeros(3), np.zeros(3)), raises=InputError, why="1-D acc"),
    Case(do.GnssImuTrajectory, (TR.t, TR.position, TR.velocity, TR.acc, TR.dt, TR.gnss_index, TR.gnss, 0.1, 0.02,
                                np.zeros(3)), raises=None, check=lambda t: t.dt == TR.dt, why="plain container"),
    Case(do.simulate_gnss_imu, (), {"imu_rate": 100.0, "gnss_rate": 3.0}, raises=InputError, match="integer",
         why="rates not commensurate"),
    Case(do.simulate_gnss_imu, (), {"duration": -1.0}, raises=InputError, why="negative duration"),
    Case(do.simulate_gnss_imu, (), {"sigma_gnss": -0.1}, raises=InputError, why="negative sigma"),
    Case(do.simulate_gnss_imu, (), {"acc_bias": (0.0, NAN, 0.0)}, raises=InputError, why="NaN bias"),
    Case(do.gnss_imu_filter, (TR.acc, TR.dt, TR.gnss, TR.gnss_index + 100, X0, Q06, 0.02, 0.1), raises=InputError,
         match="gnss_index", why="GNSS epoch after the last IMU epoch"),
    Case(do.gnss_imu_filter, (TR.acc, TR.dt, TR.gnss, TR.gnss_index + 0.5, X0, Q06, 0.02, 0.1), raises=InputError,
         match="gnss_index", why="fractional index"),
    Case(do.gnss_imu_filter, (TR.acc, TR.dt, TR.gnss, TR.gnss_index, X0, Q06, 0.02, 0.0), raises=InputError,
         why="zero GNSS sigma"),
    Case(do.gnss_imu_filter, (TR.acc[:, :2], TR.dt, TR.gnss, TR.gnss_index, X0, Q06, 0.02, 0.1), raises=InputError,
         why="2-D accelerations"),
    Case(do.gnss_imu_filter, (TR.acc, TR.dt, TR.gnss, TR.gnss_index, X0[:3], Q06, 0.02, 0.1), raises=InputError,
         why="state of length 3"),
    Case(do.BoresightBlock, (BB.xy, BB.image, BB.points, BB.control, BB.gnss, BB.A_imu, BB.f, BB.shift, BB.angles,
                             0.0), raises=None, check=lambda b: b.f == BB.f, why="plain container"),
    Case(do.simulate_boresight_block, (), {"n_control": 2}, raises=InputError, why="too few control points"),
    Case(do.simulate_boresight_block, (), {"n_images": 1.5}, raises=InputError, why="fractional image count"),
    Case(do.simulate_boresight_block, (), {"relief": 2000.0}, raises=InputError, why="relief above flying height"),
    Case(do.simulate_boresight_block, (), {"f": 0.0}, raises=InputError, why="zero camera constant"),
    Case(do.BoresightCalibration, (np.zeros(3), np.zeros(3), np.eye(3), np.zeros(6), None), raises=None,
         check=lambda c: c.boresight.shape == (3, 3), why="plain container"),
    Case(do.calibrate_boresight, _with(B_ARGS, 1, BB.image + 100), raises=InputError, match="image",
         why="image index out of range"),
    Case(do.calibrate_boresight, _with(B_ARGS, 4, 2 * BB.A_imu), raises=InputError, match="rotation",
         why="attitudes not rotations"),
    Case(do.calibrate_boresight, _with(B_ARGS, 0, BB.xy[:2]), raises=InputError, why="two observations"),
    Case(do.calibrate_boresight, _with(B_ARGS, 2, BB.points[:, :2]), raises=InputError, why="2-D points"),
    Case(do.calibrate_boresight, _with(B_ARGS, 5, -153.0), raises=InputError, why="negative f"),
    Case(do.calibrate_boresight, B_ARGS, {"sigma_xy": 0.0}, raises=InputError, why="zero sigma"),
    Case(ddo.boresight_model, (), raises=None, check=lambda m: m["jacobian"].shape == (2, 6), why="no input"),
    Case(ddo.boresight_functions, (), raises=None, check=lambda f: len(f) == 2, why="no input"),
    Case(est.least_squares_solution, (), raises=None, check=lambda d: d["x"].shape == (2, 1), why="no input"),
    Case(est.sequential_blocks, (3,), raises=InputError, why="second block of 3 observations"),
    Case(est.sequential_blocks, ("1",), raises=InputError, why="m2 not an integer"),
    Case(est.kalman_update_batch, (), raises=None, check=lambda d: d["Q_hat"].shape == (2, 2), why="no input"),
    Case(est.transition_series, (0,), raises=InputError, why="order 0"),
    Case(est.transition_series, (1.5,), raises=InputError, why="order not an integer"),
    Case(est.transition_series, (2.0,), raises=InputError, why="order a float equal to a cached integer"),
    Case(est.sequential_blocks, (True,), raises=InputError, why="m2 a bool equal to a cached 1"),
    Case(est.position_integral, (), raises=None, check=lambda d: "r" in d, why="no input"),
]


@pytest.mark.parametrize("case", CASES, ids=lambda c: c.id)
def test_bad_input(case):
    check_case(case)
