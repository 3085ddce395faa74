"""Direct sensor orientation: least squares, sequential least squares, the Kalman filter, GNSS/IMU
and the boresight calibration — Hanzl, §7 (seed 002, lines 1290–1500).

Hanzl §7 (direct sensor orientation, GNSS/IMU). The sections implemented:

* §7.1 (H7.1-1): the inertial position r = r₀ + v₀(t − t₀) + ∬a dt dt — :func:`integrate_imu`
  (a bias b of the accelerometers drifts by ½bt²; the text quotes 0.5–1 m after 1 min).
* §7.2.1: the Earth rate of the ECEF frame in the inertial frame, :data:`EARTH_RATE`
  = 7.29211×10⁻⁵ rad/s as printed.
* §7.3.1: least squares v = Ax − l, N = AᵀPA, h = AᵀPl, x = N⁻¹h, Q_x = N⁻¹,
  σ₀² = vᵀPv/(m − n) — :func:`least_squares` (through the one engine,
  :func:`photolib.lsq.solve_normal_equations`).
* §7.3.2: sequential least squares, Δx = K(l₂ − A₂x₀) "1)", ΔQ = −KA₂Q_x0 "2)", the gain
  K = (N₁ + N₂)⁻¹A₂ᵀP₂ = N₁⁻¹A₂ᵀ(P₂⁻¹ + A₂N₁⁻¹A₂ᵀ)⁻¹ (matrix-inversion lemma) and the prior
  as a pseudo-observation x₀ + v₁ = x — :func:`gain_matrix`, :func:`sequential_update`.
* §7.3.3: the Kalman filter: ẋ = Fx + w, T(t, t₀) = I + F(t − t₀) + ½F²(t − t₀)² + … = e^{F(t−t₀)}
  (:func:`transition_matrix`), Q_x = TQ_x0Tᵀ + Q_e (:func:`kalman_predict`), x̂ = x + K(l − Ax),
  Q̂ = (I − KA)Q_x, K = Q_xAᵀ(Q_l + AQ_xAᵀ)⁻¹ (:func:`kalman_update`; the text prints
  "(Q₁ + AQ_xTᵀ)⁻¹", an OCR/typing slip for Q_l and Aᵀ); :func:`kalman_filter` runs a linear
  filter over a sequence of epochs, :func:`gnss_imu_filter` a loosely coupled GNSS/IMU filter
  (position/velocity state, IMU accelerations as the known input of the prediction, GNSS
  positions as updates) on a trajectory from :func:`simulate_gnss_imu`.
* §7.3: the boresight-misalignment calibration with the basic 6 unknowns (3 GNSS shifts + 3
  angles) from control points seen in images of a small block (2 strips × 7 images, 10 control
  points, as the text recommends) — :func:`simulate_boresight_block`, :func:`calibrate_boresight`
  (Jacobians from sympy, :mod:`photolib.derivations.direct_orientation`; solved by
  :func:`photolib.lsq.gauss_newton`).

Related sections of Chibunichev (2022): §3.5 (GNSS/INS observations in the bundle, boresight),
§8.14 (direct georeferencing, :mod:`photolib.georef`, whose :func:`photolib.georef.sensor_pose`
is used here for the camera pose) and §9.8 (mobile-mapping lever arm and boresight,
:func:`photolib.lidar.calibrate_mobile_system`; the camera projection used in the simulation is
:func:`photolib.lidar.scanner_camera_project`). Rotations: A = A_ω A_α A_κ (1.3.2),
:func:`photolib.rotation.rotation_matrix` with ``order="wak"``.

Angles in radians, lengths in metres (image coordinates and f in mm in the boresight block).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.linalg

from .errors import DegenerateGeometryError, InputError

__all__ = ["EARTH_RATE", "LeastSquaresResult", "least_squares", "gain_matrix", "sequential_update",
           "transition_matrix", "kalman_predict", "kalman_update", "kalman_filter", "integrate_imu",
           "GnssImuTrajectory", "simulate_gnss_imu", "gnss_imu_filter", "BoresightBlock",
           "simulate_boresight_block", "BoresightCalibration", "calibrate_boresight"]

EARTH_RATE = 7.29211e-5
"""Rotation rate of ECEF in the inertial frame, rad/s, as printed in Hanzl §7.2.1 (seed line 1322)."""


# ---------------------------------------------------------------------------------------------
# input checks

def _arr(value, name, ndim):
    try:
        a = np.array(value, dtype=float)
    except (TypeError, ValueError) as exc:
        raise InputError(f"{name} must be numeric, got {type(value).__name__}") from exc
    if a.ndim not in ((ndim,) if isinstance(ndim, int) else ndim):
        raise InputError(f"{name} must have {ndim} dimension(s), got shape {a.shape}")
    if not np.all(np.isfinite(a)):
        raise InputError(f"{name} contains NaN or inf")
    return a


def _num(value, name, positive=False):
    a = _arr(value, name, 0)
    v = float(a)
    if positive and v <= 0:
        raise InputError(f"{name} must be positive, got {v}")
    return v


def _square(value, name, n=None):
    a = _arr(value, name, 2)
    if a.shape[0] != a.shape[1] or (n is not None and a.shape[0] != n):
        raise InputError(f"{name} must be square" + (f" {n}×{n}" if n is not None else "") + f", got {a.shape}")
    return a


def _cofactor(value, name, n):
    """A symmetric positive-definite (n, n) cofactor/covariance matrix."""
    Q = _square(value, name, n)
    if not np.allclose(Q, Q.T, rtol=1e-10, atol=1e-12 * max(np.abs(Q).max(), 1e-300)):
        raise InputError(f"{name} must be symmetric")
    try:
        np.linalg.cholesky(Q)
    except np.linalg.LinAlgError as exc:
        raise InputError(f"{name} must be positive definite") from exc
    return Q


def _semidefinite(value, name, n):
    Q = _square(value, name, n)
    if not np.allclose(Q, Q.T, rtol=1e-10, atol=1e-12 * max(np.abs(Q).max(), 1e-300)):
        raise InputError(f"{name} must be symmetric")
    if np.linalg.eigvalsh((Q + Q.T) / 2)[0] < -1e-10 * max(np.abs(Q).max(), 1e-300):
        raise InputError(f"{name} must be positive semi-definite")
    return Q


def _weight_matrix(P, m, name="P"):
    """P as an (m, m) symmetric positive-definite matrix (None: I; a vector: diag)."""
    if P is None:
        return np.eye(m)
    a = _arr(P, name, (1, 2))
    if a.ndim == 1:
        if a.shape != (m,):
            raise InputError(f"{name} must have {m} weights, got {a.shape[0]}")
        if np.any(a <= 0):
            raise InputError(f"{name}: weights must be positive")
        return np.diag(a)
    return _cofactor(a, name, m)


def _design(A, name, n=None):
    a = _arr(A, name, 2)
    if a.shape[0] == 0 or a.shape[1] == 0 or (n is not None and a.shape[1] != n):
        raise InputError(f"{name} must be m×{n if n is not None else 'n'} with m ≥ 1, got {a.shape}")
    return a


def _vector(x, name, n=None):
    a = _arr(x, name, 1)
    if a.size == 0 or (n is not None and a.shape != (n,)):
        raise InputError(f"{name} must be a vector of length {n if n is not None else '≥ 1'}, got {a.shape}")
    return a


def _solve_spd(M, B, what):
    try:
        c = scipy.linalg.cho_factor(M)
    except np.linalg.LinAlgError as exc:
        raise DegenerateGeometryError(f"{what} is singular or not positive definite") from exc
    return scipy.linalg.cho_solve(c, B)


# ---------------------------------------------------------------------------------------------
# §7.3.1 least squares

@dataclass(frozen=True)
class LeastSquaresResult:
    """Estimate of §7.3.1: x = N⁻¹h, Q_x = N⁻¹, v = Ax − l, σ₀² = vᵀPv/(m − n).

    Attributes
    ----------
    x : numpy.ndarray
        The estimate (n,).
    Q : numpy.ndarray
        The cofactor matrix Q_x = N⁻¹ (n, n).
    v : numpy.ndarray
        Residuals v = Ax − l (m,).
    sigma0_sq : float
        σ₀² = vᵀPv/(m − n) (NaN when m = n).
    dof : int
        m − n.

    References
    ----------
    Hanzl, §7.3.1 (seed 002 lines 1358–1368).

    Examples
    --------
    >>> r = least_squares([[1.0], [1.0]], [1.0, 3.0])
    >>> float(r.x[0]), float(r.sigma0_sq), r.dof
    (2.0, 2.0, 1)
    """

    x: np.ndarray
    Q: np.ndarray
    v: np.ndarray
    sigma0_sq: float
    dof: int


def least_squares(A, l, P=None) -> LeastSquaresResult:
    """Least squares of §7.3.1 for v = Ax − l with weights P, through :mod:`photolib.lsq`.

    x = (AᵀPA)⁻¹AᵀPl, Q_x = N⁻¹, σ₀² = vᵀPv/(m − n). The normal equations are solved by
    :func:`photolib.lsq.solve_normal_equations` (the project's one engine) with B = A and L = −l.

    Parameters
    ----------
    A : array_like (m, n)
        Design matrix.
    l : array_like (m,)
        Observations.
    P : array_like (m,) or (m, m), optional
        Weights (a vector: diagonal P); identity if omitted.

    Returns
    -------
    LeastSquaresResult

    Raises
    ------
    InputError
        NaN/inf, wrong shapes, m < n, non-positive weights, a P that is not symmetric
        positive definite.
    DegenerateGeometryError
        AᵀPA singular (the unknowns are not determined).

    References
    ----------
    Hanzl, §7.3.1 (seed 002 lines 1358–1368); Chibunichev (2022), §1.8, eqs. (1.8.5)–(1.8.9).

    Examples
    --------
    >>> r = least_squares([[1.0, 0.0], [1.0, 1.0], [1.0, 2.0]], [1.0, 2.0, 3.0])
    >>> r.x.round(12) + 0.0
    array([1., 1.])
    """
    from .lsq import solve_normal_equations
    A = _design(A, "A")
    m, n = A.shape
    l = _vector(l, "l", m)
    if m < n:
        raise InputError(f"{m} observations cannot determine {n} unknowns")
    Pm = _weight_matrix(P, m)
    x, Q = solve_normal_equations(A, -l, Pm)
    v = A @ x - l
    dof = m - n
    s2 = float(v @ Pm @ v / dof) if dof > 0 else float("nan")
    return LeastSquaresResult(x, Q, v, s2, dof)


# ---------------------------------------------------------------------------------------------
# §7.3.2 sequential least squares

def gain_matrix(Q0, A2, P2=None, form: str = "lemma") -> np.ndarray:
    """The gain matrix K of sequential least squares in either of its two forms (§7.3.2).

    ``form="normal"``: K = (N₁ + N₂)⁻¹A₂ᵀP₂ with N₁ = Q_x0⁻¹, N₂ = A₂ᵀP₂A₂ (an n×n inverse);
    ``form="lemma"``: K = N₁⁻¹A₂ᵀ(P₂⁻¹ + A₂N₁⁻¹A₂ᵀ)⁻¹ (an m₂×m₂ inverse, cheaper when m₂ ≤ n;
    the two are equal by the matrix-inversion lemma). With P₂⁻¹ = Q_l this is the Kalman gain
    K = Q_xAᵀ(Q_l + AQ_xAᵀ)⁻¹ of §7.3.3.2.

    Parameters
    ----------
    Q0 : array_like (n, n)
        Q_x0 = N₁⁻¹, cofactor matrix of the preliminary solution (symmetric positive definite).
    A2 : array_like (m2, n)
        Design matrix of the added observations.
    P2 : array_like (m2,) or (m2, m2), optional
        Their weights (identity if omitted).
    form : {"lemma", "normal"}

    Returns
    -------
    numpy.ndarray
        K (n, m2).

    Raises
    ------
    InputError
        NaN/inf, wrong shapes, Q0 or P2 not symmetric positive definite, unknown ``form``.

    References
    ----------
    Hanzl, §7.3.2 (seed 002 lines 1420–1424), §7.3.3.2 (line 1500, corrected).

    Examples
    --------
    >>> K1 = gain_matrix(np.eye(2), [[1.0, 1.0]], [2.0], form="normal")
    >>> K2 = gain_matrix(np.eye(2), [[1.0, 1.0]], [2.0], form="lemma")
    >>> K1.round(12), bool(np.allclose(K1, K2))
    (array([[0.4],
           [0.4]]), True)
    """
    if form not in ("lemma", "normal"):
        raise InputError(f"form must be 'lemma' or 'normal', got {form!r}")
    A2 = _design(A2, "A2")
    m2, n = A2.shape
    Q0 = _cofactor(Q0, "Q0", n)
    P2 = _weight_matrix(P2, m2, "P2")
    if form == "normal":
        N1 = _solve_spd(Q0, np.eye(n), "Q0")
        N = N1 + A2.T @ P2 @ A2
        return _solve_spd((N + N.T) / 2, A2.T @ P2, "N1 + N2")
    Ql = _solve_spd(P2, np.eye(m2), "P2")
    S = Ql + A2 @ Q0 @ A2.T
    return _solve_spd((S + S.T) / 2, (Q0 @ A2.T).T, "P2⁻¹ + A2 Q0 A2ᵀ").T


def sequential_update(x0, Q0, A2, l2, P2=None, form: str = "lemma"):
    """Add observations l₂ to a preliminary solution x₀, Q_x0 (sequential least squares, §7.3.2).

    Δx = K(l₂ − A₂x₀) "1)", ΔQ = −KA₂Q_x0 "2)", x = x₀ + Δx, Q_x = Q_x0 + ΔQ. Equivalent to the
    prior as a pseudo-observation, x₀ + v₁ = x (weights Q_x0⁻¹) together with l₂ + v₂ = A₂x,
    and — when x₀, Q_x0 come from l₁ — to the batch solution of l₁ and l₂ together.

    Parameters
    ----------
    x0 : array_like (n,)
        Preliminary estimate x₀ = N₁⁻¹h₁.
    Q0 : array_like (n, n)
        Its cofactor matrix Q_x0 = N₁⁻¹.
    A2 : array_like (m2, n)
    l2 : array_like (m2,)
    P2 : array_like (m2,) or (m2, m2), optional
    form : {"lemma", "normal"}
        The form of K (:func:`gain_matrix`).

    Returns
    -------
    x : numpy.ndarray (n,)
    Q : numpy.ndarray (n, n)
    K : numpy.ndarray (n, m2)

    Raises
    ------
    InputError
        NaN/inf, wrong shapes, Q0 or P2 not symmetric positive definite.

    References
    ----------
    Hanzl, §7.3.2, eqs. "1)", "2)" (seed 002 lines 1370–1430).

    Examples
    --------
    >>> x, Q, K = sequential_update([1.0], [[1.0]], [[1.0]], [3.0])
    >>> float(x[0]), float(Q[0, 0])
    (2.0, 0.5)
    """
    A2 = _design(A2, "A2")
    m2, n = A2.shape
    x0 = _vector(x0, "x0", n)
    l2 = _vector(l2, "l2", m2)
    K = gain_matrix(Q0, A2, P2, form)
    Q0 = np.asarray(Q0, float)
    x = x0 + K @ (l2 - A2 @ x0)
    Q = Q0 - K @ A2 @ Q0
    return x, (Q + Q.T) / 2, K


# ---------------------------------------------------------------------------------------------
# §7.3.3 Kalman filter

def transition_matrix(F, dt, terms: int | None = None) -> np.ndarray:
    """The transition matrix T(t, t₀) = e^{F(t − t₀)} of ẋ = Fx + w with constant F (§7.3.3.1).

    T = I + FΔt + ½F²Δt² + …: the matrix exponential (:func:`scipy.linalg.expm`), or the Taylor
    series cut after ``terms`` terms (``terms=2``: I + FΔt).

    Parameters
    ----------
    F : array_like (n, n)
        The dynamic matrix.
    dt : float
        t − t₀ (may be negative: prediction backwards).
    terms : int, optional
        Number of series terms (≥ 1); the exact exponential if omitted.

    Returns
    -------
    numpy.ndarray
        T (n, n).

    Raises
    ------
    InputError
        NaN/inf, F not square, ``terms`` not a positive integer.

    References
    ----------
    Hanzl, §7.3.3.1 (seed 002 lines 1446–1468).

    Examples
    --------
    >>> transition_matrix([[0.0, 1.0], [0.0, 0.0]], 0.5)
    array([[1. , 0.5],
           [0. , 1. ]])
    """
    F = _square(F, "F")
    dt = _num(dt, "dt")
    if terms is None:
        return scipy.linalg.expm(F * dt)
    if isinstance(terms, bool) or not isinstance(terms, (int, np.integer)) or terms < 1:
        raise InputError(f"terms must be a positive integer, got {terms!r}")
    T = np.eye(len(F))
    term = np.eye(len(F))
    for k in range(1, int(terms)):
        term = term @ F * dt / k
        T = T + term
    return T


def kalman_predict(x, Q, T, Qe=None, u=None):
    """Prediction of the Kalman filter: x = Tx₀ (+ u), Q_x = TQ_x0Tᵀ + Q_e (§7.3.3.1).

    Parameters
    ----------
    x : array_like (n,)
        State at t₀.
    Q : array_like (n, n)
        Its covariance (cofactor) matrix Q_x0.
    T : array_like (n, n)
        Transition matrix T(t, t₀) (:func:`transition_matrix`).
    Qe : array_like (n, n), optional
        Covariance of the process noise e(t) (symmetric positive semi-definite; zero if omitted).
    u : array_like (n,), optional
        A known input added to the state (e.g. the effect of measured IMU accelerations).

    Returns
    -------
    x : numpy.ndarray (n,)
    Q : numpy.ndarray (n, n)

    Raises
    ------
    InputError
        NaN/inf, wrong shapes, Q or Qe not symmetric positive semi-definite.

    References
    ----------
    Hanzl, §7.3.3.1 (seed 002 lines 1446–1470).

    Examples
    --------
    >>> x, Q = kalman_predict([0.0, 1.0], np.eye(2), [[1.0, 2.0], [0.0, 1.0]])
    >>> x, Q
    (array([2., 1.]), array([[5., 2.],
           [2., 1.]]))
    """
    T = _square(T, "T")
    n = len(T)
    x = _vector(x, "x", n)
    Q = _semidefinite(Q, "Q", n)
    xp = T @ x
    if u is not None:
        xp = xp + _vector(u, "u", n)
    Qp = T @ Q @ T.T
    if Qe is not None:
        Qp = Qp + _semidefinite(Qe, "Qe", n)
    return xp, (Qp + Qp.T) / 2


def kalman_update(x, Q, A, l, Ql):
    """Update of the Kalman filter by observations l = Ax̂ (§7.3.3.2).

    x̂ = x + K(l − Ax), Q̂ = (I − KA)Q_x, K = Q_xAᵀ(Q_l + AQ_xAᵀ)⁻¹ — the sequential update of
    §7.3.2 with the prediction as the pseudo-observation.

    Parameters
    ----------
    x : array_like (n,)
        Predicted state.
    Q : array_like (n, n)
        Its covariance Q_x (symmetric positive semi-definite).
    A : array_like (m, n)
        Observation matrix.
    l : array_like (m,)
        Observations.
    Ql : array_like (m,) or (m, m)
        Their covariance (a vector: variances).

    Returns
    -------
    x : numpy.ndarray (n,)
    Q : numpy.ndarray (n, n)
    K : numpy.ndarray (n, m)

    Raises
    ------
    InputError
        NaN/inf, wrong shapes, Ql not symmetric positive definite.
    DegenerateGeometryError
        Q_l + AQ_xAᵀ singular.

    References
    ----------
    Hanzl, §7.3.3.2 (seed 002 lines 1472–1500; the printed gain "(Q₁ + AQ_xTᵀ)⁻¹" read as
    (Q_l + AQ_xAᵀ)⁻¹).

    Examples
    --------
    >>> x, Q, K = kalman_update([0.0], [[1.0]], [[1.0]], [2.0], [1.0])
    >>> float(x[0]), float(Q[0, 0])
    (1.0, 0.5)
    """
    A = _design(A, "A")
    m, n = A.shape
    x = _vector(x, "x", n)
    Q = _semidefinite(Q, "Q", n)
    l = _vector(l, "l", m)
    Ql = _arr(Ql, "Ql", (1, 2))
    if Ql.ndim == 1:
        if Ql.shape != (m,) or np.any(Ql <= 0):
            raise InputError(f"Ql must be {m} positive variances, got {Ql}")
        Ql = np.diag(Ql)
    else:
        Ql = _cofactor(Ql, "Ql", m)
    S = Ql + A @ Q @ A.T
    K = _solve_spd((S + S.T) / 2, A @ Q, "Q_l + A Q_x Aᵀ").T
    xh = x + K @ (l - A @ x)
    Qh = (np.eye(n) - K @ A) @ Q
    return xh, (Qh + Qh.T) / 2, K


def kalman_filter(x0, Q0, T, A, observations, Ql, Qe=None):
    """A linear Kalman filter with constant T, Q_e, A and Q_l over a sequence of epochs (§7.3.3).

    At every epoch the state is predicted (:func:`kalman_predict`, not before the first) and
    updated with that epoch's observations (:func:`kalman_update`). With T = I and Q_e = 0 (a
    static state without process noise) the final estimate is the batch least-squares solution
    of all observations with the prior x₀, Q0 as a pseudo-observation.

    Parameters
    ----------
    x0 : array_like (n,)
        State before the first epoch.
    Q0 : array_like (n, n)
        Its covariance.
    T : array_like (n, n)
        Transition matrix between consecutive epochs.
    A : array_like (m, n)
        Observation matrix.
    observations : array_like (k, m)
        One row of observations per epoch.
    Ql : array_like (m,) or (m, m)
        Covariance of one epoch's observations.
    Qe : array_like (n, n), optional
        Process-noise covariance per step.

    Returns
    -------
    x : numpy.ndarray (k, n)
        Filtered states.
    Q : numpy.ndarray (k, n, n)
        Their covariances.

    Raises
    ------
    InputError
        NaN/inf, wrong shapes, covariances that are not symmetric positive (semi-)definite.
    DegenerateGeometryError
        A singular Q_l + AQ_xAᵀ.

    References
    ----------
    Hanzl, §7.3.3 (seed 002 lines 1432–1500).

    Examples
    --------
    >>> xs, Qs = kalman_filter([0.0], [[1e6]], [[1.0]], [[1.0]], [[1.0], [3.0]], [1.0])
    >>> round(float(xs[-1, 0]), 4)
    2.0
    """
    A = _design(A, "A")
    m, n = A.shape
    L = _arr(observations, "observations", 2)
    if L.shape[1] != m or len(L) == 0:
        raise InputError(f"observations must be (k, {m}) with k ≥ 1, got {L.shape}")
    x, Q = _vector(x0, "x0", n), _semidefinite(Q0, "Q0", n)
    T = _square(T, "T", n)
    xs, Qs = [], []
    for k, l in enumerate(L):
        if k > 0:
            x, Q = kalman_predict(x, Q, T, Qe)
        x, Q, _ = kalman_update(x, Q, A, l, Ql)
        xs.append(x)
        Qs.append(Q)
    return np.array(xs), np.array(Qs)


# ---------------------------------------------------------------------------------------------
# §7.1 inertial navigation and a GNSS/IMU trajectory

def integrate_imu(acc, dt, p0, v0):
    """Double integration of accelerations: r = r₀ + v₀(t − t₀) + ∬a dt dt (§7.1, H7.1-1).

    The accelerations are taken as constant over each step (exact for such a signal):
    v_{k+1} = v_k + a_kΔt, r_{k+1} = r_k + v_kΔt + ½a_kΔt². A constant bias b of the
    accelerometers therefore moves the position by ½bt² (the free-inertial drift of §7).

    Parameters
    ----------
    acc : array_like (k, d)
        Accelerations (gravity already removed), one per step.
    dt : float
        Step (s), positive.
    p0, v0 : array_like (d,)
        Initial position and velocity.

    Returns
    -------
    position : numpy.ndarray (k + 1, d)
    velocity : numpy.ndarray (k + 1, d)

    Raises
    ------
    InputError
        NaN/inf, wrong shapes, dt ≤ 0.

    References
    ----------
    Hanzl, §7.1 (seed 002 lines 1306–1310) and §7 (drift, line 1296).

    Examples
    --------
    >>> p, v = integrate_imu(np.full((60, 1), 5e-4), 1.0, [0.0], [0.0])
    >>> float(p[-1, 0])
    0.9
    """
    a = _arr(acc, "acc", 2)
    if len(a) == 0:
        raise InputError("acc has no samples")
    d = a.shape[1]
    dt = _num(dt, "dt", positive=True)
    p0, v0 = _vector(p0, "p0", d), _vector(v0, "v0", d)
    v = np.vstack([v0, v0 + np.cumsum(a, axis=0) * dt])
    p = np.vstack([p0, p0 + np.cumsum(v[:-1] * dt + 0.5 * a * dt ** 2, axis=0)])
    return p, v


@dataclass(frozen=True)
class GnssImuTrajectory:
    """A simulated aircraft trajectory with IMU accelerations and GNSS positions (§7.1).

    Attributes
    ----------
    t : numpy.ndarray
        IMU epochs (k + 1,), s.
    position, velocity : numpy.ndarray
        True position and velocity at ``t`` (k + 1, 3).
    acc : numpy.ndarray
        Measured accelerations (k, 3): the mean true acceleration over [t_i, t_{i+1}] plus bias
        and noise.
    dt : float
        IMU step (s).
    gnss_index : numpy.ndarray
        Indices into ``t`` of the GNSS epochs.
    gnss : numpy.ndarray
        Measured GNSS positions at those epochs (g, 3).
    sigma_gnss, sigma_acc : float
        Noise levels used (m, m/s²).
    acc_bias : numpy.ndarray
        Accelerometer bias used (3,).

    References
    ----------
    Hanzl, §7, §7.1 (seed 002 lines 1290–1316).

    Examples
    --------
    >>> tr = simulate_gnss_imu(duration=2.0)
    >>> tr.position.shape, tr.gnss.shape
    ((201, 3), (3, 3))
    """

    t: np.ndarray
    position: np.ndarray
    velocity: np.ndarray
    acc: np.ndarray
    dt: float
    gnss_index: np.ndarray
    gnss: np.ndarray
    sigma_gnss: float
    sigma_acc: float
    acc_bias: np.ndarray


def simulate_gnss_imu(*, seed: int = 0, duration: float = 60.0, imu_rate: float = 100.0, gnss_rate: float = 1.0,
                      speed: float = 50.0, acceleration=(0.05, 0.1, 0.0), vertical_amplitude: float = 0.3,
                      vertical_period: float = 20.0, sigma_gnss: float = 0.1, sigma_acc: float = 0.02,
                      acc_bias=(0.0, 0.0, 0.0)) -> GnssImuTrajectory:
    """Simulate an aircraft at ``speed`` m/s along X with constant acceleration and a vertical sway.

    The true acceleration is a₀ + (0, 0, A sin 2πt/P); position and velocity are its exact
    integrals. IMU samples at ``imu_rate`` are the exact mean acceleration over each step plus
    ``acc_bias`` and white noise σ_acc; GNSS positions at ``gnss_rate`` have white noise σ_gnss
    per coordinate (Tab. 7.1: 0.05–0.30 m). Seeded (numpy ``default_rng(seed)``).

    Parameters
    ----------
    seed : int
    duration : float
        s, positive.
    imu_rate, gnss_rate : float
        Hz, positive; ``imu_rate / gnss_rate`` must be an integer.
    speed : float
        Initial speed along X, m/s (the text's 50 m/s).
    acceleration : array_like (3,)
        a₀, m/s².
    vertical_amplitude, vertical_period : float
        A (m/s²) and P (s, positive) of the vertical sway.
    sigma_gnss, sigma_acc : float
        Noise standard deviations (≥ 0).
    acc_bias : array_like (3,)
        Accelerometer bias, m/s².

    Returns
    -------
    GnssImuTrajectory

    Raises
    ------
    InputError
        NaN/inf, non-positive rates/duration/period, negative σ, a rate ratio that is not an
        integer.

    References
    ----------
    Hanzl, §7 (seed 002 line 1296: 50 m/s; Tab. 7.1 GNSS accuracy), §7.1.

    Examples
    --------
    >>> tr = simulate_gnss_imu(duration=1.0, sigma_gnss=0.0)
    >>> bool(np.allclose(tr.gnss, tr.position[tr.gnss_index]))
    True
    """
    duration = _num(duration, "duration", positive=True)
    imu_rate = _num(imu_rate, "imu_rate", positive=True)
    gnss_rate = _num(gnss_rate, "gnss_rate", positive=True)
    speed = _num(speed, "speed")
    a0 = _vector(acceleration, "acceleration", 3)
    amp = _num(vertical_amplitude, "vertical_amplitude")
    period = _num(vertical_period, "vertical_period", positive=True)
    sg, sa = _num(sigma_gnss, "sigma_gnss"), _num(sigma_acc, "sigma_acc")
    if sg < 0 or sa < 0:
        raise InputError(f"sigma_gnss and sigma_acc must be ≥ 0, got {sg}, {sa}")
    bias = _vector(acc_bias, "acc_bias", 3)
    ratio = imu_rate / gnss_rate
    if abs(ratio - round(ratio)) > 1e-9 or round(ratio) < 1:
        raise InputError(f"imu_rate / gnss_rate must be a positive integer, got {ratio}")
    ratio = int(round(ratio))
    k = int(round(duration * imu_rate))
    if k < 1:
        raise InputError("duration shorter than one IMU step")
    dt = 1.0 / imu_rate
    t = np.arange(k + 1) * dt
    w = 2 * np.pi / period
    v0 = np.array([speed, 0.0, 0.0])
    vel = v0 + np.outer(t, a0)
    pos = np.outer(t, v0) + 0.5 * np.outer(t ** 2, a0)
    vel[:, 2] += amp / w * (1 - np.cos(w * t))
    pos[:, 2] += amp / w * (t - np.sin(w * t) / w)
    mean_acc = np.diff(vel, axis=0) / dt
    rng = np.random.default_rng(seed)
    acc = mean_acc + bias + sa * rng.standard_normal(mean_acc.shape)
    idx = np.arange(0, k + 1, ratio)
    gnss = pos[idx] + sg * rng.standard_normal((len(idx), 3))
    return GnssImuTrajectory(t, pos, vel, acc, dt, idx, gnss, sg, sa, bias)


def gnss_imu_filter(acc, dt, gnss, gnss_index, x0, Q0, sigma_acc, sigma_gnss):
    """A loosely coupled GNSS/IMU Kalman filter: IMU-driven prediction, GNSS position updates (§7.1, §7.3.3).

    State x = (r, v) (6). Prediction over each IMU step with ẋ = Fx + (0, a), F = [[0, I], [0, 0]],
    T = e^{FΔt} (:func:`transition_matrix`), the measured acceleration as known input
    u = (½a Δt², a Δt) and the accelerometer noise as process noise Q_e = σ_acc²ΓΓᵀ,
    Γ = (½Δt² I, Δt I). Update at the GNSS epochs with l = r, A = [I 0], Q_l = σ_gnss²I.

    Parameters
    ----------
    acc : array_like (k, 3)
        Measured accelerations per step.
    dt : float
        IMU step, s.
    gnss : array_like (g, 3)
        GNSS positions.
    gnss_index : array_like (g,) of int
        IMU epoch (0…k) of each GNSS position.
    x0 : array_like (6,)
        Initial position and velocity.
    Q0 : array_like (6, 6)
        Their covariance.
    sigma_acc : float
        Accelerometer white noise per step, m/s² (≥ 0).
    sigma_gnss : float
        GNSS noise per coordinate, m (> 0).

    Returns
    -------
    x : numpy.ndarray (k + 1, 6)
        Filtered states at every IMU epoch.
    Q : numpy.ndarray (k + 1, 6, 6)
        Their covariances.

    Raises
    ------
    InputError
        NaN/inf, wrong shapes, indices outside 0…k, σ out of range.

    References
    ----------
    Hanzl, §7.1 (IMU smooths GNSS noise, GNSS bounds the IMU drift), §7.3.3 (seed 002 lines
    1312–1316, 1432–1500).

    Examples
    --------
    >>> tr = simulate_gnss_imu(duration=5.0)
    >>> x, Q = gnss_imu_filter(tr.acc, tr.dt, tr.gnss, tr.gnss_index,
    ...                        np.r_[tr.gnss[0], 50.0, 0, 0], np.diag([0.01] * 3 + [1.0] * 3), 0.02, 0.1)
    >>> x.shape, Q.shape
    ((501, 6), (501, 6, 6))
    """
    a = _arr(acc, "acc", 2)
    if a.shape[1:] != (3,) or len(a) == 0:
        raise InputError(f"acc must be (k, 3) with k ≥ 1, got {a.shape}")
    dt = _num(dt, "dt", positive=True)
    G = _arr(gnss, "gnss", 2)
    if G.shape[1:] != (3,):
        raise InputError(f"gnss must be (g, 3), got {G.shape}")
    idx = _arr(gnss_index, "gnss_index", 1)
    if idx.shape != (len(G),) or np.any(idx != np.round(idx)) or np.any(idx < 0) or np.any(idx > len(a)):
        raise InputError(f"gnss_index must hold {len(G)} integers in 0…{len(a)}")
    x = _vector(x0, "x0", 6)
    Q = _semidefinite(Q0, "Q0", 6)
    sa = _num(sigma_acc, "sigma_acc")
    if sa < 0:
        raise InputError(f"sigma_acc must be ≥ 0, got {sa}")
    sg = _num(sigma_gnss, "sigma_gnss", positive=True)
    F = np.zeros((6, 6))
    F[:3, 3:] = np.eye(3)
    T = transition_matrix(F, dt)
    Gam = np.vstack([0.5 * dt ** 2 * np.eye(3), dt * np.eye(3)])
    Qe = sa ** 2 * Gam @ Gam.T
    H = np.hstack([np.eye(3), np.zeros((3, 3))])
    Ql = np.full(3, sg ** 2)
    updates = {}
    for j, i in enumerate(idx.astype(int)):
        updates.setdefault(i, []).append(G[j])
    xs, Qs = np.empty((len(a) + 1, 6)), np.empty((len(a) + 1, 6, 6))
    for k in range(len(a) + 1):
        if k > 0:
            x, Q = kalman_predict(x, Q, T, Qe, Gam @ a[k - 1])
        for g in updates.get(k, ()):
            x, Q, _ = kalman_update(x, Q, H, g, Ql)
        xs[k], Qs[k] = x, Q
    return xs, Qs


# ---------------------------------------------------------------------------------------------
# §7.3 boresight-misalignment calibration

@dataclass(frozen=True)
class BoresightBlock:
    """A simulated calibration block: images with GNSS/IMU poses and control points (§7.3).

    Attributes
    ----------
    xy : numpy.ndarray
        Image coordinates (k, 2), mm.
    image : numpy.ndarray
        Image index of each observation (k,).
    points : numpy.ndarray
        Ground coordinates of the control point of each observation (k, 3), m.
    control : numpy.ndarray
        The control points (c, 3).
    gnss : numpy.ndarray
        GNSS positions per image (n, 3).
    A_imu : numpy.ndarray
        IMU attitudes per image (n, 3, 3), IMU → object.
    f : float
        Camera constant, mm.
    shift, angles : numpy.ndarray
        True GNSS shift (3,), m, and boresight angles Δω, Δα, Δκ (3,), rad.
    sigma_xy : float
        Image noise, mm.

    References
    ----------
    Hanzl, §7.3 (seed 002 lines 1348–1352).

    Examples
    --------
    >>> b = simulate_boresight_block()
    >>> b.gnss.shape, b.control.shape
    ((14, 3), (10, 3))
    """

    xy: np.ndarray
    image: np.ndarray
    points: np.ndarray
    control: np.ndarray
    gnss: np.ndarray
    A_imu: np.ndarray
    f: float
    shift: np.ndarray
    angles: np.ndarray
    sigma_xy: float


def simulate_boresight_block(*, seed: int = 0, n_strips: int = 2, n_images: int = 7, n_control: int = 10,
                             f: float = 153.0, height: float = 1530.0, frame: float = 230.0,
                             shift=(0.12, -0.08, 0.25), angles=(0.002, -0.0015, 0.003),
                             sigma_xy: float = 0.005, relief: float = 150.0) -> BoresightBlock:
    """Simulate the calibration block of Hanzl §7.3: strips × images, control points, GNSS/IMU poses.

    Image scale 1 : height/f (1 : 10 000 by default), 60 % forward and 25 % side overlap,
    consecutive strips flown in opposite directions (so that the boresight angles and the GNSS
    shifts separate), control points spread over the block at heights 0…``relief``. Each image's
    true pose is the GNSS/IMU one corrected by the six calibration parameters, S = R_GNSS + d and
    A = A_IMU·A_b (:func:`photolib.georef.sensor_pose`); images are projected with
    :func:`photolib.lidar.scanner_camera_project` and given white noise ``sigma_xy``. GNSS/IMU
    themselves are noise-free.

    Parameters
    ----------
    seed : int
    n_strips, n_images, n_control : int
        Strips (≥ 1), images per strip (≥ 2), control points (≥ 3).
    f, height, frame : float
        Camera constant (mm), flying height (m), square format (mm); positive.
    shift : array_like (3,)
        True GNSS shift d (m).
    angles : array_like (3,)
        True boresight angles Δω, Δα, Δκ (rad).
    sigma_xy : float
        Image noise (mm, ≥ 0).
    relief : float
        Height range of the control points (m, ≥ 0, below ``height``).

    Returns
    -------
    BoresightBlock

    Raises
    ------
    InputError
        NaN/inf, counts or sizes out of range.

    References
    ----------
    Hanzl, §7.3 (seed 002 lines 1348–1352); Chibunichev (2022), §8.14 (8.14.1).

    Examples
    --------
    >>> b = simulate_boresight_block(sigma_xy=0.0)
    >>> bool(np.all(np.abs(b.xy) < 115.0))
    True
    """
    from .georef import sensor_pose
    from .lidar import scanner_camera_project
    from .rotation import rotation_matrix
    for v, name, low in ((n_strips, "n_strips", 1), (n_images, "n_images", 2), (n_control, "n_control", 3)):
        if isinstance(v, bool) or not isinstance(v, (int, np.integer)) or v < low:
            raise InputError(f"{name} must be an integer ≥ {low}, got {v!r}")
    f, H, fr = (_num(v, n, positive=True) for v, n in ((f, "f"), (height, "height"), (frame, "frame")))
    d, ang = _vector(shift, "shift", 3), _vector(angles, "angles", 3)
    s, relief = _num(sigma_xy, "sigma_xy"), _num(relief, "relief")
    if s < 0 or relief < 0 or relief >= H:
        raise InputError(f"sigma_xy must be ≥ 0 and relief in [0, height), got {s}, {relief}")
    rng = np.random.default_rng(seed)
    side = fr * H / f                              # ground side of one image, m
    base, spacing = 0.4 * side, 0.75 * side
    Ab = rotation_matrix(*ang, order="wak")
    gnss, A_imu = [], []
    for j in range(n_strips):
        heading = 0.0 if j % 2 == 0 else np.pi
        xs = np.arange(n_images) * base
        for xi in (xs if j % 2 == 0 else xs[::-1]):
            S = np.array([xi, j * spacing, H]) + rng.normal(0, 5.0, 3)
            A_true = rotation_matrix(*rng.normal(0, 0.01, 2), heading + rng.normal(0, 0.01), order="wak")
            Ai = A_true @ Ab.T
            gnss.append(S - d)
            A_imu.append(Ai)
    gnss, A_imu = np.array(gnss), np.array(A_imu)
    S_all, A_all = sensor_pose(gnss + d, A_imu, np.zeros(3), np.zeros(3), Ab)
    lo = np.array([-0.3 * side, -0.3 * side])
    hi = np.array([(n_images - 1) * base + 0.3 * side, (n_strips - 1) * spacing + 0.3 * side])
    control = np.column_stack([rng.uniform(lo, hi, (n_control, 2)), rng.uniform(0, relief, n_control)])
    xy, image, points = [], [], []
    for i in range(len(gnss)):
        p = scanner_camera_project(control, S_all[i], A_all[i], f)
        inside = np.all(np.abs(p) < fr / 2, axis=1)
        xy.append(p[inside] + s * rng.standard_normal((int(inside.sum()), 2)))
        image.append(np.full(int(inside.sum()), i))
        points.append(control[inside])
    return BoresightBlock(np.vstack(xy), np.concatenate(image), np.vstack(points), control, gnss, A_imu, f,
                          d, ang, s)


@dataclass(frozen=True)
class BoresightCalibration:
    """The six calibration parameters of §7.3 with their accuracy.

    Attributes
    ----------
    shift : numpy.ndarray
        GNSS shift d = (dX, dY, dZ), m.
    angles : numpy.ndarray
        Boresight angles Δω, Δα, Δκ, rad (A_b = A_ω A_α A_κ, camera → IMU).
    boresight : numpy.ndarray
        A_b (3, 3).
    std : numpy.ndarray
        m_j of the six unknowns (m, rad).
    adjustment : photolib.lsq.Adjustment

    References
    ----------
    Hanzl, §7.3 (seed 002 lines 1350–1352).

    Examples
    --------
    >>> "angles" in BoresightCalibration.__dataclass_fields__
    True
    """

    shift: np.ndarray
    angles: np.ndarray
    boresight: np.ndarray
    std: np.ndarray
    adjustment: object


def calibrate_boresight(xy, image, points, gnss, A_imu, f, *, sigma_xy=None, x0=None,
                        max_iter: int = 30) -> BoresightCalibration:
    """GNSS shift and boresight misalignment (6 unknowns) from control points in images (§7.3).

    Each image point (x, y) of a control point X in image i must satisfy the collinearity
    equations with the pose S = R_GNSS,i + d, A = A_IMU,i·A_b(Δω, Δα, Δκ). The six unknowns are
    adjusted by :func:`photolib.lsq.gauss_newton` with the sympy Jacobian of
    :func:`photolib.derivations.direct_orientation.boresight_model`.

    Parameters
    ----------
    xy : array_like (k, 2)
        Image coordinates (principal point at the origin), unit of ``f``.
    image : array_like (k,) of int
        Image index of each observation (into ``gnss``/``A_imu``).
    points : array_like (k, 3)
        Ground coordinates of the observed control points.
    gnss : array_like (n, 3)
        GNSS positions of the images.
    A_imu : array_like (n, 3, 3)
        IMU attitudes (IMU → object).
    f : float
        Camera constant.
    sigma_xy : float, optional
        A-priori σ of an image coordinate: weights 1/σ².
    x0 : array_like (6,), optional
        Approximate values (default zeros).
    max_iter : int

    Returns
    -------
    BoresightCalibration

    Raises
    ------
    InputError
        NaN/inf, wrong shapes, indices out of range, non-rotation attitudes, fewer than 3
        observations.
    DegenerateGeometryError
        A geometry that does not determine the six unknowns (e.g. control points on one line in
        one image).
    ConvergenceError
        No convergence.

    References
    ----------
    Hanzl, §7.3 (seed 002 lines 1348–1352); Chibunichev (2022), §1.8 (the engine), §8.14.

    Examples
    --------
    >>> b = simulate_boresight_block(sigma_xy=0.0)
    >>> cal = calibrate_boresight(b.xy, b.image, b.points, b.gnss, b.A_imu, b.f)
    >>> bool(np.allclose(cal.shift, b.shift, atol=1e-6)), bool(np.allclose(cal.angles, b.angles, atol=1e-9))
    (True, True)
    """
    from .derivations.direct_orientation import BORESIGHT_PARAMETERS, boresight_functions
    from .lsq import gauss_newton
    from .rotation import is_rotation, rotation_matrix
    xy = _arr(xy, "xy", 2)
    k = len(xy)
    if xy.shape[1:] != (2,) or k < 3:
        raise InputError(f"xy must be (k, 2) with k ≥ 3 observations, got {xy.shape}")
    img = _arr(image, "image", 1)
    X = _arr(points, "points", 2)
    G = _arr(gnss, "gnss", 2)
    A = _arr(A_imu, "A_imu", 3)
    if G.shape[1:] != (3,) or A.shape[1:] != (3, 3) or len(A) != len(G):
        raise InputError(f"gnss must be (n, 3) and A_imu (n, 3, 3) with equal n, got {G.shape}, {A.shape}")
    if X.shape != (k, 3) or img.shape != (k,):
        raise InputError(f"points must be ({k}, 3) and image ({k},), got {X.shape}, {img.shape}")
    if np.any(img != np.round(img)) or np.any(img < 0) or np.any(img >= len(G)):
        raise InputError(f"image indices must be integers in 0…{len(G) - 1}")
    bad = [i for i in range(len(A)) if not is_rotation(A[i], 1e-6)]
    if bad:
        raise InputError(f"A_imu[{bad[0]}] is not a rotation matrix")
    f = _num(f, "f", positive=True)
    start = np.zeros(6) if x0 is None else _vector(x0, "x0", 6)
    weights = None
    if sigma_xy is not None:
        weights = np.full(2 * k, 1 / _num(sigma_xy, "sigma_xy", positive=True) ** 2)
    i = img.astype(int)
    residual, jacobian = boresight_functions()
    data = (*G[i].T, *A[i].reshape(k, 9).T, *X.T, np.full(k, f), *xy.T)

    def linearize(x):
        L = np.concatenate([np.broadcast_to(np.asarray(v, float), (k,)) for v in residual(*x, *data)])
        J = np.array([np.broadcast_to(np.asarray(v, float), (k,)) for v in jacobian(*x, *data)])  # (12, k)
        B = J.reshape(2, 6, k).transpose(0, 2, 1).reshape(2 * k, 6)
        return B, L

    tol = np.array([1e-7] * 3 + [1e-10] * 3)
    adj = gauss_newton(linearize, start, weights, names=BORESIGHT_PARAMETERS, tol=tol, max_iter=max_iter)
    ang = adj.x[3:].copy()
    return BoresightCalibration(adj.x[:3].copy(), ang, rotation_matrix(*ang, order="wak"),
                                np.asarray(adj.std, float), adj)
