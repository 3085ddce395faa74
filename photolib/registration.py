"""Scan orientation and registration — Chapter 9, §9.5–9.6, eq. (9.5.1).

A terrestrial scanner is neither levelled nor oriented, so each scan is a point cloud in its
own frame SX′Y′Z′. The book links it to the object frame OXYZ by the six-element rigid
transformation without scale (9.5.1)

    (X, Y, Z)ᵀ = (X₀, Y₀, Z₀)ᵀ + A(ω, α, κ)·(X′, Y′, Z′)ᵀ

* §9.5 — :func:`rigid_transform`: the six elements from ≥ 3 non-collinear targets by least
  squares (the engine :func:`photolib.lsq.gauss_newton`, the Jacobian of
  :func:`photolib.derivations.registration.rigid_model`) with the r.m.s. errors of the elements;
  :func:`rigid_closed_form` (SVD, Kabsch/Umeyama without scale) gives its start. Two targets,
  or targets on one line, leave the rotation about that line free:
  :class:`~photolib.errors.DegenerateGeometryError` says so.
* §9.6 — :func:`register_stations`: several scans with shared targets merged by one joint
  adjustment (the six elements of every station but a fixed one, and the tie targets' coordinates
  in the common frame), then optionally oriented on control targets as in §9.5.
* Targetless registration (the "natural contours" of §9.6): :func:`icp`, the iterative closest
  point method, point-to-point (Besl & McKay 1992) or point-to-plane (Chen & Medioni 1992) with
  the normals of :func:`estimate_normals` (local PCA), pairs from a scipy k-d tree, rejection of
  far pairs (distance and trimming) and convergence tests; the result :class:`ICPResult`.

Angles are in radians; the rotation sequence is the library's (:mod:`photolib.rotation`).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Callable, Sequence

import numpy as np

from .camera import as_points
from .errors import ConvergenceError, DegenerateGeometryError, InputError
from .lsq import Adjustment, gauss_newton, solve_normal_equations
from .rotation import DEFAULT_ORDER, check_order, rotation_angles, rotation_matrix

__all__ = ["RIGID_NAMES", "RigidTransform", "rigid_closed_form", "rigid_transform", "StationRegistration",
           "register_stations", "estimate_normals", "ICPIteration", "ICPResult", "icp"]

RIGID_NAMES = ("X0", "Y0", "Z0", "omega", "alpha", "kappa")
"""Names of the six elements of (9.5.1), in the order of the unknowns."""

_REF = "Chibunichev (2022), §9.5, eq. (9.5.1)"


# --- the transformation (9.5.1) -------------------------------------------------------------------
@dataclass(repr=False)
class RigidTransform:
    """The six elements of (9.5.1): X = X₀ + A(ω, α, κ)·X′ (scanner → object, no scale).

    Parameters
    ----------
    X0, Y0, Z0 : float
        Origin of the scanner frame in the object frame.
    omega, alpha, kappa : float
        Angles of A in radians.
    order : {"kaw", "wak"}
        Rotation sequence of A (:func:`photolib.rotation.rotation_matrix`).
    adjustment : Adjustment, optional
        The least-squares adjustment that produced the elements (μ, m_j, r_ij), if any.
    residuals : ndarray, optional
        "Transformed − given" at the targets used.

    Attributes
    ----------
    shift, matrix, vector, std, homogeneous
        (X₀, Y₀, Z₀); A; the six elements; their r.m.s. errors m_j (or None); the 4×4 matrix.

    References
    ----------
    Chibunichev (2022), §9.5, eq. (9.5.1).

    Examples
    --------
    >>> T = RigidTransform(1.0, 2.0, 3.0, 0.0, 0.0, np.pi / 2)
    >>> T.apply([[1.0, 0.0, 0.0]]).round(12)
    array([[1., 3., 3.]])
    >>> T.inverse().apply(T.apply([[0.5, 0.2, 0.1]])).round(12)
    array([[0.5, 0.2, 0.1]])
    """

    X0: float
    Y0: float
    Z0: float
    omega: float
    alpha: float
    kappa: float
    order: str = DEFAULT_ORDER
    adjustment: Adjustment | None = None
    residuals: np.ndarray | None = None

    def __post_init__(self):
        check_order(self.order)
        try:
            values = np.array([self.X0, self.Y0, self.Z0, self.omega, self.alpha, self.kappa], dtype=float)
        except (TypeError, ValueError):
            raise InputError("the six elements X0, Y0, Z0, omega, alpha, kappa must be numbers") from None
        if not np.all(np.isfinite(values)):
            raise InputError(f"the six elements must be finite, got {values.tolist()}")
        self.X0, self.Y0, self.Z0, self.omega, self.alpha, self.kappa = map(float, values)

    @property
    def shift(self) -> np.ndarray:
        return np.array([self.X0, self.Y0, self.Z0])

    @property
    def vector(self) -> np.ndarray:
        return np.array([self.X0, self.Y0, self.Z0, self.omega, self.alpha, self.kappa])

    @property
    def matrix(self) -> np.ndarray:
        return rotation_matrix(self.omega, self.alpha, self.kappa, self.order)

    @property
    def std(self):
        return None if self.adjustment is None else self.adjustment.std

    @property
    def homogeneous(self) -> np.ndarray:
        H = np.eye(4)
        H[:3, :3], H[:3, 3] = self.matrix, self.shift
        return H

    @property
    def rotation_angle(self) -> float:
        """The angle of the rotation A about its axis (radians)."""
        return _angle_of(self.matrix)

    def apply(self, points) -> np.ndarray:
        """(9.5.1) for an (n, 3) array of scanner coordinates."""
        P = as_points(points, 3, "scanner points")
        return P @ self.matrix.T + self.shift

    def inverse(self) -> "RigidTransform":
        """Object → scanner: X′ = Aᵀ(X − X₀)."""
        A = self.matrix
        return RigidTransform.from_matrix(-A.T @ self.shift, A.T, self.order)

    def compose(self, other: "RigidTransform") -> "RigidTransform":
        """``self ∘ other``: apply ``other`` first, then ``self``."""
        if not isinstance(other, RigidTransform):
            raise InputError(f"compose needs a RigidTransform, got {type(other).__name__}")
        A1, A2 = self.matrix, other.matrix
        return RigidTransform.from_matrix(A1 @ other.shift + self.shift, A1 @ A2, self.order)

    @classmethod
    def from_matrix(cls, shift, A, order: str = DEFAULT_ORDER, **kwargs) -> "RigidTransform":
        """The transform with shift (X₀, Y₀, Z₀) and rotation matrix A (angles in ``order``)."""
        s = np.asarray(shift, dtype=float).reshape(3)
        w, a, k = rotation_angles(np.asarray(A, dtype=float), check_order(order), singular="kappa-zero")
        return cls(float(s[0]), float(s[1]), float(s[2]), float(w), float(a), float(k), order, **kwargs)

    @classmethod
    def from_homogeneous(cls, H, order: str = DEFAULT_ORDER) -> "RigidTransform":
        """The transform of a 4×4 matrix [A X₀; 0 1]."""
        H = np.asarray(H, dtype=float)
        if H.shape != (4, 4) or not np.all(np.isfinite(H)):
            raise InputError(f"a homogeneous transform must be a finite 4×4 matrix, got shape {H.shape}")
        return cls.from_matrix(H[:3, 3], H[:3, :3], order)

    def __repr__(self):
        e = ", ".join(f"{n}={v:.6g}" for n, v in zip(RIGID_NAMES, self.vector))
        return f"RigidTransform({e}, order={self.order!r})"


def _angle_of(A) -> float:
    return float(np.arccos(np.clip((np.trace(A) - 1.0) / 2.0, -1.0, 1.0)))


def _check_geometry(P, what):
    """≥ 3 targets not on one line, or the rotation about the line through them is free (§9.5)."""
    if len(P) < 2:
        raise DegenerateGeometryError(f"{what}: {len(P)} target(s) cannot fix the six elements of (9.5.1); "
                                      "at least 3 non-collinear targets are needed")
    s = np.linalg.svd(P - P.mean(axis=0), compute_uv=False)
    if len(P) == 2:
        raise DegenerateGeometryError(f"{what}: 2 targets leave the rotation about the line joining them free; "
                                      "at least 3 non-collinear targets are needed (§9.5)")
    if s[0] == 0:
        raise DegenerateGeometryError(f"{what}: the targets coincide; at least 3 non-collinear targets are needed")
    if s[1] < 1e-9 * s[0]:
        raise DegenerateGeometryError(f"{what}: the targets lie on one line, which leaves the rotation about it "
                                      "free; at least 3 non-collinear targets are needed (§9.5)")


def _kabsch(P, Q, w=None):
    """(A, t) minimising Σ w‖Q − (A·P + t)‖² (no scale), with the reflection guard."""
    w = np.ones(len(P)) if w is None else w
    ws = w.sum()
    mp, mq = (w @ P) / ws, (w @ Q) / ws
    H = ((Q - mq) * w[:, None]).T @ (P - mp)                # Σ w (q − q̄)(p − p̄)ᵀ
    U, _, Vt = np.linalg.svd(H)
    D = np.diag([1.0, 1.0, np.sign(np.linalg.det(U @ Vt)) or 1.0])
    A = U @ D @ Vt                                           # independent of the SVD's signs
    return A, mq - A @ mp


def _pair_arrays(scanner_points, object_points):
    P = as_points(scanner_points, 3, "scanner points")
    Q = as_points(object_points, 3, "object points")
    if len(P) != len(Q):
        raise InputError(f"targets: {len(P)} scanner points but {len(Q)} object points")
    return P, Q


def _target_weights(weights, n):
    if weights is None:
        return None
    w = np.asarray(weights, dtype=float)
    if w.shape == (n,):
        w = np.repeat(w[:, None], 3, axis=1)
    if w.shape != (n, 3):
        raise InputError(f"weights: expected shape ({n},) or ({n}, 3), got {np.shape(weights)}")
    if not np.all(np.isfinite(w)) or np.any(w <= 0):
        raise InputError("weights must be finite and positive")
    return w


def rigid_closed_form(scanner_points, object_points, weights=None, order: str = DEFAULT_ORDER) -> RigidTransform:
    """Closed-form six elements of (9.5.1) from ≥ 3 non-collinear targets (SVD, no scale).

    The rotation from the SVD of the weighted cross-covariance of the centred point sets with
    the reflection guard (Kabsch; Umeyama's method with the scale fixed at 1), then X₀. It
    minimises the same sum of squares as the least-squares solution with isotropic weights, so
    it needs no approximate angles; :func:`rigid_transform` starts from it. The result does not
    depend on the signs the SVD picks.

    Parameters
    ----------
    scanner_points, object_points : (n, 3) arrays
        X′, Y′, Z′ and X, Y, Z of the same targets, n ≥ 3, not collinear.
    weights : (n,) array, optional
        Weights of the targets (isotropic); unit by default.
    order : {"kaw", "wak"}
        Rotation sequence of the returned angles.

    Returns
    -------
    RigidTransform
        The six elements (no adjustment).

    Raises
    ------
    InputError
        Wrong shapes, different counts, NaN/inf, bad weights.
    DegenerateGeometryError
        Fewer than 3 targets, or collinear ones (the rotation about their line is free).

    References
    ----------
    Chibunichev (2022), §9.5, eq. (9.5.1).
    W. Kabsch, Acta Cryst. A32 (1976) 922; S. Umeyama, IEEE TPAMI 13(4), 1991, 376–380.

    Examples
    --------
    >>> P = np.array([[0.0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]])
    >>> T = rigid_closed_form(P, P + [10, 20, 30])
    >>> T.shift.round(9), round(T.rotation_angle, 9)
    (array([10., 20., 30.]), 0.0)
    """
    check_order(order)
    P, Q = _pair_arrays(scanner_points, object_points)
    w = _target_weights(weights, len(P))
    _check_geometry(P, "scanner points")
    _check_geometry(Q, "object points")
    A, t = _kabsch(P, Q, None if w is None else w[:, 0])
    return RigidTransform.from_matrix(t, A, order)


def rigid_transform(scanner_points, object_points, weights=None, order: str = DEFAULT_ORDER,
                    initial: RigidTransform | None = None, tol: float = 1e-10,
                    max_iter: int = 30) -> RigidTransform:
    """Exterior orientation of a scan from ≥ 3 non-collinear targets by least squares, §9.5.

    Each coordinate of a target gives one equation of (9.5.1); linearised at the approximation
    they are the correction equations B·δ + L = V with B derived by sympy
    (:func:`photolib.derivations.registration.rigid_model`), solved by the engine of §1.8. The
    returned ``adjustment`` holds μ (1.8.9) and the r.m.s. errors m_j of X₀, Y₀, Z₀, ω, α, κ
    (1.8.8); with exactly 3 targets there are 9 − 6 = 3 redundant equations.

    Parameters
    ----------
    scanner_points, object_points : (n, 3) arrays
        X′, Y′, Z′ (scan) and X, Y, Z (object, e.g. by total station) of n ≥ 3 targets.
    weights : (n,) or (n, 3) array, optional
        Weights p = 1/m² of the targets or of each coordinate; unit weights by default.
    order : {"kaw", "wak"}
        Rotation sequence of A.
    initial : RigidTransform, optional
        Approximate values; by default :func:`rigid_closed_form`.
    tol, max_iter
        Convergence tolerance (on X₀ in the data's unit; the angles 100× tighter) and limit.

    Returns
    -------
    RigidTransform
        The six elements with ``adjustment`` (μ, m_j, r_ij in the order of :data:`RIGID_NAMES`)
        and ``residuals`` (n, 3), transformed − given.

    Raises
    ------
    InputError
        Wrong shapes, NaN/inf, different counts, bad weights.
    DegenerateGeometryError
        Fewer than 3 targets, or targets on one line (2 targets leave a rotation free).
    ConvergenceError
        No convergence within ``max_iter``.

    References
    ----------
    Chibunichev (2022), §9.5, eq. (9.5.1); §1.8, eqs. (1.8.5)–(1.8.10).

    Examples
    --------
    >>> P = np.array([[0.0, 0, 0], [10, 0, 0], [0, 10, 0], [0, 0, 10], [10, 10, 2]])
    >>> truth = RigidTransform(100.0, 200.0, 30.0, 0.1, -0.05, 0.3)
    >>> T = rigid_transform(P, truth.apply(P))
    >>> np.allclose(T.vector, truth.vector), T.adjustment.dof
    (True, 9)
    """
    check_order(order)
    P, Q = _pair_arrays(scanner_points, object_points)
    w = _target_weights(weights, len(P))
    _check_geometry(P, "scanner points")
    _check_geometry(Q, "object points")
    if initial is None:
        start = rigid_closed_form(P, Q, None if w is None else w.mean(axis=1), order)
    elif isinstance(initial, RigidTransform):
        start = initial
    else:
        raise InputError(f"initial must be a RigidTransform, got {type(initial).__name__}")
    if start.order != order:
        start = RigidTransform.from_matrix(start.shift, start.matrix, order)
    from .derivations.registration import rigid_model
    res_fn, jac_fn = rigid_model(order).compile()
    n = len(P)
    data = (P[:, 0], P[:, 1], P[:, 2], Q[:, 0], Q[:, 1], Q[:, 2])

    def linearize(x):
        L = res_fn(*x, *data).T.reshape(-1)                              # φ of (9.5.1), per target
        B = jac_fn(*x, *data).reshape(3, 6, n).transpose(2, 0, 1).reshape(-1, 6)
        return B, L

    tol_v = np.array([tol] * 3 + [tol * 1e-2] * 3)
    adj = gauss_newton(linearize, start.vector, None if w is None else w.reshape(-1), tol=tol_v,
                       max_iter=max_iter, names=RIGID_NAMES)
    result = RigidTransform(*map(float, adj.x), order=order, adjustment=adj)
    result.residuals = result.apply(P) - Q
    return result


# --- §9.6 several stations -------------------------------------------------------------------------
@dataclass(repr=False)
class StationRegistration:
    """Result of :func:`register_stations`: every station's six elements and the tie targets.

    Attributes
    ----------
    transforms : list of RigidTransform
        Scanner → common frame (the fixed station's frame, or the object frame with control).
    targets : dict
        Target name → (3,) coordinates in the common frame (tie targets adjusted, the others
        transformed from their one station).
    adjustment : Adjustment
        The joint adjustment (unknowns: six elements of every free station, then the tie targets).
    residuals : list of dict
        Per station, target name → (3,) residual "transformed − adjusted" of the tie targets.
    control : RigidTransform or None
        The §9.5 orientation of the merged model on control targets, if control was given.

    References
    ----------
    Chibunichev (2022), §9.6; eq. (9.5.1).

    Examples
    --------
    >>> StationRegistration([RigidTransform(0, 0, 0, 0, 0, 0)], {}, None, [{}]).transforms[0].shift
    array([0., 0., 0.])
    """

    transforms: list
    targets: dict
    adjustment: Adjustment | None
    residuals: list
    control: RigidTransform | None = None

    def merge(self, clouds: Sequence) -> np.ndarray:
        """All stations' (n_i, 3) clouds in the common frame, stacked."""
        if len(clouds) != len(self.transforms):
            raise InputError(f"merge: {len(clouds)} clouds for {len(self.transforms)} stations")
        return np.vstack([T.apply(c) for T, c in zip(self.transforms, clouds)])


def _station_dicts(stations):
    if not isinstance(stations, (list, tuple)) or len(stations) < 2:
        raise InputError("register_stations needs a list of at least 2 stations (dicts target → X′, Y′, Z′)")
    out = []
    for s, st in enumerate(stations):
        if not isinstance(st, dict) or not st:
            raise InputError(f"station {s}: expected a non-empty dict target name → (X′, Y′, Z′)")
        out.append({name: as_points(xyz, 3, f"station {s}, target {name!r}")[0] for name, xyz in st.items()})
    return out


def register_stations(stations, fixed: int = 0, control: dict | None = None, order: str = DEFAULT_ORDER,
                      weights=None, tol: float = 1e-10, max_iter: int = 30) -> StationRegistration:
    """Merge several scans by shared targets in one joint adjustment, then orient them (§9.6).

    The equations (9.5.1) of every (station, tie target) observation,
    φ = P_j − X₀ₛ − Aₛ·X′ₛⱼ, are adjusted together: the unknowns are the six elements of every
    station but ``fixed`` (whose frame is the common one) and the coordinates P_j of every target
    seen from two or more stations. Start values chain :func:`rigid_closed_form` from station to
    station. With ``control`` (target name → object X, Y, Z; ≥ 3 non-collinear) the merged model
    is then oriented on them by :func:`rigid_transform`, as the book prescribes, and every
    station's transform is composed with that orientation.

    Parameters
    ----------
    stations : list of dict
        Per station, target name → (X′, Y′, Z′) measured in that scan.
    fixed : int
        The station whose frame is the common frame.
    control : dict, optional
        Target name → object coordinates, for the final orientation of §9.5.
    order : {"kaw", "wak"}
        Rotation sequence.
    weights : list of dict, optional
        Per station, target name → weight p = 1/m² of that measurement; unit by default.
    tol, max_iter
        As in :func:`rigid_transform`.

    Returns
    -------
    StationRegistration
        Transforms, target coordinates, the joint adjustment, residuals, the control orientation.

    Raises
    ------
    InputError
        Not a list of ≥ 2 non-empty dicts, NaN/inf, ``fixed`` out of range, bad weights.
    DegenerateGeometryError
        A station that shares fewer than 3 non-collinear targets with the stations registered
        before it (the name of the station is given), or degenerate control.
    ConvergenceError
        No convergence.

    References
    ----------
    Chibunichev (2022), §9.6; §9.5, eq. (9.5.1).

    Examples
    --------
    >>> T = np.array([[0.0, 0, 0], [5, 0, 0], [0, 5, 0], [0, 0, 3], [5, 5, 1]])
    >>> s1 = RigidTransform(2.0, -1.0, 0.5, 0.0, 0.0, 0.4)
    >>> st0 = {i: p for i, p in enumerate(T)}
    >>> st1 = {i: p for i, p in enumerate(s1.inverse().apply(T))}
    >>> reg = register_stations([st0, st1])
    >>> np.allclose(reg.transforms[1].vector, s1.vector)
    True
    """
    check_order(order)
    st = _station_dicts(stations)
    S = len(st)
    if not isinstance(fixed, (int, np.integer)) or not 0 <= fixed < S:
        raise InputError(f"fixed must be a station index in 0..{S - 1}, got {fixed!r}")
    wts = None
    if weights is not None:
        if len(weights) != S:
            raise InputError(f"weights: {len(weights)} dicts for {S} stations")
        wts = [{k: float(v) for k, v in wd.items()} for wd in weights]
        if any((not np.isfinite(v)) or v <= 0 for wd in wts for v in wd.values()):
            raise InputError("weights must be finite and positive")
    # start values: chain the closed form through shared targets
    start: dict[int, RigidTransform] = {fixed: RigidTransform(0.0, 0.0, 0.0, 0.0, 0.0, 0.0, order)}
    known: dict = {}

    def _add_known(s):
        for name, p in st[s].items():
            known.setdefault(name, []).append(start[s].apply(p[None])[0])

    _add_known(fixed)
    while len(start) < S:
        progress = False
        for s in range(S):
            if s in start:
                continue
            shared = [n for n in st[s] if n in known]
            if len(shared) < 3:
                continue
            P = np.array([st[s][n] for n in shared])
            Q = np.array([np.mean(known[n], axis=0) for n in shared])
            try:
                start[s] = rigid_closed_form(P, Q, order=order)
            except DegenerateGeometryError:
                continue
            _add_known(s)
            progress = True
        if not progress:
            missing = sorted(set(range(S)) - set(start))
            raise DegenerateGeometryError(
                f"stations {missing} share fewer than 3 non-collinear targets with the registered stations; "
                "the rotation is not determined (§9.5–9.6)")
    counts: dict = {}
    for d in st:
        for n in d:
            counts[n] = counts.get(n, 0) + 1
    ties = sorted((n for n, c in counts.items() if c >= 2), key=str)
    tie_index = {n: j for j, n in enumerate(ties)}
    free = [s for s in range(S) if s != fixed]
    col = {s: 6 * i for i, s in enumerate(free)}
    n_st = 6 * len(free)
    obs = [(s, n) for s in range(S) for n in st[s] if n in tie_index]
    x0 = np.concatenate([np.concatenate([start[s].vector for s in free]),
                         np.concatenate([np.mean(known[n], axis=0) for n in ties])])
    m = 3 * len(obs)
    from .derivations.registration import rigid_model
    res_fn, jac_fn = rigid_model(order).compile()
    obs_s = np.array([s for s, _ in obs])
    obs_j = np.array([tie_index[n] for _, n in obs])
    Xp = np.array([st[s][n] for s, n in obs])
    p_obs = None if wts is None else np.repeat([wts[s].get(n, 1.0) for s, n in obs], 3)

    def linearize(x):
        B = np.zeros((m, len(x)))
        L = np.empty(m)
        Pt = x[n_st:].reshape(-1, 3)[obs_j]
        for s in range(S):
            rows = np.flatnonzero(obs_s == s)
            if not len(rows):
                continue
            e = np.zeros(6) if s == fixed else x[col[s]:col[s] + 6]
            d = (Xp[rows, 0], Xp[rows, 1], Xp[rows, 2], Pt[rows, 0], Pt[rows, 1], Pt[rows, 2])
            r3 = (3 * rows[:, None] + np.arange(3)).reshape(-1)
            L[r3] = res_fn(*e, *d).T.reshape(-1)
            if s != fixed:
                B[r3, col[s]:col[s] + 6] = jac_fn(*e, *d).reshape(3, 6, len(rows)).transpose(2, 0, 1).reshape(-1, 6)
        for k in range(3):
            B[3 * np.arange(len(obs)) + k, n_st + 3 * obs_j + k] = 1.0
        return B, L

    names = [f"{e}[{s}]" for s in free for e in RIGID_NAMES] + [f"{c}({n})" for n in ties for c in "XYZ"]
    tol_v = np.concatenate([np.tile([tol] * 3 + [tol * 1e-2] * 3, len(free)), np.full(3 * len(ties), tol)])
    if m <= len(x0):
        raise DegenerateGeometryError(f"{m} equations for {len(x0)} unknowns: too few shared targets for a "
                                      "joint adjustment (each station needs ≥ 3 non-collinear tie targets)")
    adj = gauss_newton(linearize, x0, p_obs, tol=tol_v, max_iter=max_iter, names=names)
    transforms = []
    for s in range(S):
        if s == fixed:
            transforms.append(RigidTransform(0.0, 0.0, 0.0, 0.0, 0.0, 0.0, order))
        else:
            transforms.append(RigidTransform(*map(float, adj.x[col[s]:col[s] + 6]), order=order))
    tie_xyz = adj.x[n_st:].reshape(-1, 3)
    targets = {n: tie_xyz[tie_index[n]].copy() for n in ties}
    for s in range(S):
        for n, p in st[s].items():
            if n not in targets:
                targets[n] = transforms[s].apply(p[None])[0]
    residuals = [{n: transforms[s].apply(p[None])[0] - targets[n] for n, p in st[s].items() if n in tie_index}
                 for s in range(S)]
    result = StationRegistration(transforms, targets, adj, residuals)
    if control is not None:
        if not isinstance(control, dict):
            raise InputError(f"control must be a dict target name → X, Y, Z, got {type(control).__name__}")
        names_c = [n for n in control if n in targets]
        if len(names_c) < 3:
            raise DegenerateGeometryError(f"only {len(names_c)} control targets are in the merged model; "
                                          "at least 3 non-collinear are needed (§9.5)")
        C = rigid_transform(np.array([targets[n] for n in names_c]),
                            np.array([as_points(control[n], 3, f"control {n!r}")[0] for n in names_c]),
                            order=order, tol=tol, max_iter=max_iter)
        result.control = C
        result.transforms = [C.compose(T) for T in transforms]
        result.targets = {n: C.apply(p[None])[0] for n, p in targets.items()}
    return result


# --- targetless registration: ICP ------------------------------------------------------------------
def _cloud(points, what, minimum):
    P = np.asarray(points, dtype=float) if not isinstance(points, str) else None
    if P is None or P.ndim != 2 or P.shape[1] != 3:
        raise InputError(f"{what}: expected an (n, 3) array of coordinates, got "
                         f"{type(points).__name__ if P is None else P.shape}")
    if not np.all(np.isfinite(P)):
        bad = int(np.count_nonzero(~np.isfinite(P).all(axis=1)))
        raise InputError(f"{what}: {bad} point(s) with NaN or inf coordinates; remove them first")
    if len(P) < minimum:
        raise DegenerateGeometryError(f"{what}: {len(P)} points are too few (at least {minimum} needed)")
    return P


def _pca_normals(P, tree, k, workers):
    """Unoriented unit normals and the mask of undefined ones (line or point neighbourhoods)."""
    _, idx = tree.query(P, k=k, workers=workers)
    from ._registration_kernels import pca_normals
    normals, mid, big = pca_normals(P, idx.astype(np.int64))
    scale = np.maximum(big, np.finfo(float).tiny)
    undefined = (mid <= 1e-6 * scale + np.finfo(float).tiny) | ~np.isfinite(normals).all(axis=1)
    normals[undefined] = 0.0
    return normals, undefined


def estimate_normals(points, k: int = 10, viewpoint=None, workers: int = 1) -> np.ndarray:
    """Unit surface normals by local PCA: the least eigenvector of the k-neighbour covariance.

    Neighbours come from a scipy k-d tree (:class:`scipy.spatial.cKDTree`). The sign is
    normalised: towards ``viewpoint`` if given, else with a non-negative Z component (then Y,
    then X on ties). Where the neighbourhood is not a surface (all neighbours on one line or one
    point) the normal is undefined and returned as NaN, never a guess.

    Parameters
    ----------
    points : (n, 3) array
        The cloud, n > k.
    k : int
        Neighbours per point (including the point itself), ≥ 3.
    viewpoint : (3,) array, optional
        The scanner position, to orient the normals towards it.
    workers : int
        Threads for the k-d tree queries (−1: all cores).

    Returns
    -------
    ndarray (n, 3)
        Unit normals (NaN rows where undefined).

    Raises
    ------
    InputError
        Wrong shape, NaN/inf, k < 3 or not an integer.
    DegenerateGeometryError
        Fewer than k points.

    References
    ----------
    Chibunichev (2022), §9.6 (natural surfaces as ties); Hoppe et al., SIGGRAPH 1992 (normals by PCA).

    Examples
    --------
    >>> g = np.stack(np.meshgrid(np.arange(5.0), np.arange(5.0)), -1).reshape(-1, 2)
    >>> estimate_normals(np.column_stack([g, np.zeros(25)]), k=6)[0].round(12) + 0.0
    array([0., 0., 1.])
    """
    if isinstance(k, bool) or not isinstance(k, (int, np.integer)) or k < 3:
        raise InputError(f"k must be an integer ≥ 3, got {k!r}")
    P = _cloud(points, "points", k)
    from scipy.spatial import cKDTree
    normals, undefined = _pca_normals(P, cKDTree(P), int(k), workers)
    if viewpoint is not None:
        v = as_points(viewpoint, 3, "viewpoint")[0]
        flip = np.einsum("ni,ni->n", normals, v - P) < 0
    else:
        key = normals[:, 2] + 1e-9 * normals[:, 1] + 1e-18 * normals[:, 0]
        flip = key < 0
    normals[flip] *= -1
    normals[undefined] = np.nan
    return normals


@dataclass
class ICPIteration:
    """One ICP step: pairs used, their r.m.s. distance before the step, and the step's size.

    Attributes
    ----------
    iteration : int
        1 for the first step.
    rms : float
        R.m.s. of the used pair distances (point-to-plane: of the normal distances) before the step.
    pairs : int
        Pairs kept after rejection.
    rotation_step : float
        Angle of the step's rotation (radians).
    translation_step : float
        Length of the step's translation.

    References
    ----------
    Chibunichev (2022), §9.6; Besl & McKay (1992).

    Examples
    --------
    >>> ICPIteration(1, 0.1, 500, 1e-3, 2e-3).pairs
    500
    """

    iteration: int
    rms: float
    pairs: int
    rotation_step: float
    translation_step: float


@dataclass(repr=False)
class ICPResult:
    """Result of :func:`icp`.

    Attributes
    ----------
    transform : RigidTransform
        Source → target, (9.5.1).
    rms : float
        R.m.s. pair distance at the solution (point-to-plane: normal distance).
    fitness : float
        Fraction of the source points paired (within the rejection distance) at the solution.
    iterations : int
        Steps taken.
    converged : bool
        Whether the step criteria were met.
    method : str
        ``"point-to-point"`` or ``"point-to-plane"``.
    history : list of ICPIteration
        One record per step.

    References
    ----------
    Chibunichev (2022), §9.6, eq. (9.5.1); Besl & McKay (1992); Chen & Medioni (1992).

    Examples
    --------
    >>> r = ICPResult(RigidTransform(0, 0, 0, 0, 0, 0), 0.0, 1.0, 1, True, "point-to-point")
    >>> r.matrix.shape
    (4, 4)
    """

    transform: RigidTransform
    rms: float
    fitness: float
    iterations: int
    converged: bool
    method: str
    history: list = field(default_factory=list)

    @property
    def matrix(self) -> np.ndarray:
        return self.transform.homogeneous

    def __repr__(self):
        return (f"ICPResult({self.method}, rms={self.rms:.4g}, fitness={self.fitness:.3f}, "
                f"iterations={self.iterations}, converged={self.converged})")


def _rodrigues(theta):
    a = float(np.linalg.norm(theta))
    if a < 1e-300:
        return np.eye(3)
    k = theta / a
    K = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    return np.eye(3) + np.sin(a) * K + (1 - np.cos(a)) * (K @ K)


def icp(source, target, method: str = "point-to-plane", initial=None, max_distance: float | None = None,
        trim: float = 1.0, max_iter: int = 50, tol_rotation: float = 1e-7, tol_translation: float = 1e-6,
        k_normals: int = 10, target_normals=None, order: str = DEFAULT_ORDER, workers: int = 1,
        raise_on_max_iter: bool = True, coarse_fraction: float | None = None,
        progress: Callable[[ICPIteration], None] | None = None) -> ICPResult:
    """Targetless registration of two overlapping scans by the iterative closest point method.

    Each step pairs every source point (transformed by the current estimate) with its nearest
    target point (scipy :class:`~scipy.spatial.cKDTree`, built once), rejects pairs farther than
    ``max_distance`` and keeps the ``trim`` fraction of the closest, and solves one least-squares
    step for the six elements of (9.5.1):

    * ``"point-to-point"`` — the closed form (SVD) minimising Σ‖q − (A·p + X₀)‖²;
    * ``"point-to-plane"`` — the linearised Σ(n·(A·p + X₀ − q))² with the target normals n
      (:func:`estimate_normals`), the rotation linearised about the pairs' centroid; one
      correction step of the engine (:func:`photolib.lsq.solve_normal_equations`).

    It stops when the step's rotation is below ``tol_rotation`` and its translation below
    ``tol_translation``. ICP converges to the nearest local minimum: the start must be within a
    few degrees and a fraction of the overlap (e.g. from targets or a coarse alignment).

    Parameters
    ----------
    source, target : (n, 3), (m, 3) arrays
        The scan to move and the fixed scan (finite coordinates).
    method : {"point-to-plane", "point-to-point"}
        The error metric.
    initial : RigidTransform or (4, 4) array, optional
        Start value of source → target; identity by default.
    max_distance : float, optional
        Pairs farther apart are rejected (in the data's unit); no limit by default.
    trim : float
        Fraction (0, 1] of the closest pairs kept each step (trimmed ICP).
    max_iter : int
        Steps allowed.
    tol_rotation, tol_translation : float
        Convergence thresholds on the step (radians, the data's unit).
    k_normals : int
        Neighbours for the target normals.
    target_normals : (m, 3) array, optional
        Precomputed target normals (rows with NaN are not used).
    order : {"kaw", "wak"}
        Rotation sequence of the returned angles.
    workers : int
        Threads for the k-d tree queries (−1: all cores).
    raise_on_max_iter : bool
        Raise :class:`ConvergenceError` when ``max_iter`` is reached (default); else return
        with ``converged = False``.
    coarse_fraction : float, optional
        Coarse-to-fine: iterate first on this fraction (0, 1) of the source points (a seeded
        random subset) until the steps fall below 10× the tolerances, then on all points. The
        far-off first steps are the expensive k-d tree queries; the result is that of the full
        cloud. None (default): all points from the start.
    progress : callable, optional
        Called with each :class:`ICPIteration`.

    Returns
    -------
    ICPResult
        Transform, r.m.s., fitness, iterations, convergence flag and history.

    Raises
    ------
    InputError
        Wrong shapes, NaN/inf, a bad method, trim, tolerances or initial transform.
    DegenerateGeometryError
        Too few points; too few pairs within ``max_distance``; a geometry that does not fix the
        six elements (e.g. one plane for point-to-plane).
    ConvergenceError
        No convergence within ``max_iter`` (the history is attached).

    References
    ----------
    Chibunichev (2022), §9.6, eq. (9.5.1). P. J. Besl, N. D. McKay, IEEE TPAMI 14(2), 1992;
    Y. Chen, G. Medioni, Image Vision Comput. 10(3), 1992.

    Examples
    --------
    >>> rng = np.random.default_rng(0)
    >>> g = rng.uniform(-1, 1, (2000, 2))
    >>> cloud = np.column_stack([g, 0.3 * np.sin(3 * g[:, 0]) * np.cos(2 * g[:, 1])])
    >>> truth = RigidTransform(0.05, -0.03, 0.02, 0.03, -0.02, 0.05)
    >>> r = icp(truth.inverse().apply(cloud), cloud, method="point-to-point", max_iter=200)
    >>> bool(np.allclose(r.transform.vector, truth.vector, atol=1e-4)), r.converged
    (True, True)
    """
    if method not in ("point-to-plane", "point-to-point"):
        raise InputError(f"method must be 'point-to-plane' or 'point-to-point', got {method!r}")
    check_order(order)
    if not (isinstance(trim, (int, float)) and 0 < trim <= 1):
        raise InputError(f"trim must be a fraction in (0, 1], got {trim!r}")
    if max_distance is not None and not (np.isfinite(max_distance) and max_distance > 0):
        raise InputError(f"max_distance must be a positive number, got {max_distance!r}")
    if not (tol_rotation > 0 and tol_translation > 0):
        raise InputError("tol_rotation and tol_translation must be positive")
    if coarse_fraction is not None and not (isinstance(coarse_fraction, (int, float)) and 0 < coarse_fraction < 1):
        raise InputError(f"coarse_fraction must be a fraction in (0, 1) or None, got {coarse_fraction!r}")
    if isinstance(max_iter, bool) or not isinstance(max_iter, (int, np.integer)) or max_iter < 1:
        raise InputError(f"max_iter must be a positive integer, got {max_iter!r}")
    if isinstance(k_normals, bool) or not isinstance(k_normals, (int, np.integer)) or k_normals < 3:
        raise InputError(f"k_normals must be an integer ≥ 3, got {k_normals!r}")
    need = 6 if method == "point-to-plane" else 3
    S = _cloud(source, "source", need)
    T = _cloud(target, "target", max(need, k_normals if method == "point-to-plane" else need))
    if initial is None:
        A, t = np.eye(3), np.zeros(3)
    elif isinstance(initial, RigidTransform):
        A, t = initial.matrix, initial.shift
    else:
        H = np.asarray(initial, dtype=float)
        if H.shape != (4, 4) or not np.all(np.isfinite(H)):
            raise InputError(f"initial must be a RigidTransform or a finite 4×4 matrix, got shape {H.shape}")
        A, t = H[:3, :3], H[:3, 3]
        if not np.allclose(A.T @ A, np.eye(3), atol=1e-6) or np.linalg.det(A) < 0:
            raise InputError("initial: the 3×3 block is not a rotation")
    from scipy.spatial import cKDTree
    # work about the target's centroid: coordinates of a georeferenced scan may be large
    c0 = T.mean(axis=0)
    Tc = T - c0
    Sc = S - c0
    t = t + A @ c0 - c0                        # the same transform in centred coordinates
    tree = cKDTree(Tc)
    normals = None
    if method == "point-to-plane":
        if target_normals is None:
            normals, undefined = _pca_normals(Tc, tree, int(k_normals), workers)
            normals[undefined] = np.nan
        else:
            normals = np.asarray(target_normals, dtype=float)
            if normals.shape != T.shape:
                raise InputError(f"target_normals: expected shape {T.shape}, got {normals.shape}")
    history: list[ICPIteration] = []
    dmax = np.inf if max_distance is None else float(max_distance)
    converged = False

    active = Sc
    coarse = False
    if coarse_fraction is not None and coarse_fraction * len(Sc) >= 50 * need:
        pick = np.random.default_rng(0).choice(len(Sc), int(coarse_fraction * len(Sc)), replace=False)
        active, coarse = Sc[np.sort(pick)], True

    def pairs_at(A, t, Sc):
        X = Sc @ A.T + t
        d, j = tree.query(X, k=1, distance_upper_bound=dmax, workers=workers)
        keep = np.isfinite(d)
        if normals is not None:
            keep &= np.isfinite(normals[np.minimum(j, len(T) - 1), 0])
        idx = np.flatnonzero(keep)
        if trim < 1.0 and len(idx):
            nk = max(need, int(np.ceil(trim * len(idx))))
            if nk < len(idx):
                idx = idx[np.argpartition(d[idx], nk - 1)[:nk]]
        return X, d, j, idx

    for it in range(1, max_iter + 1):
        X, d, j, idx = pairs_at(A, t, active)
        if len(idx) < need:
            raise DegenerateGeometryError(
                f"ICP step {it}: only {len(idx)} pairs within max_distance={max_distance} "
                f"(at least {need} needed); the start is too far or max_distance too small")
        p, q = X[idx], Tc[j[idx]]
        if normals is None:
            rms = float(np.sqrt(np.mean(d[idx] ** 2)))
            dA, dt = _kabsch(p, q)
        else:
            n = normals[j[idx]]
            c = p.mean(axis=0)
            L = np.einsum("ni,ni->n", n, p - q)                   # n·(p − q): the free terms
            B = np.column_stack([np.cross(p - c, n), n])          # ∂/∂(θ, X₀) at θ = 0
            rms = float(np.sqrt(np.mean(L ** 2)))
            delta, _ = solve_normal_equations(B, L, names=("theta_x", "theta_y", "theta_z", "dX0", "dY0", "dZ0"))
            dA = _rodrigues(delta[:3])
            dt = c + delta[3:] - dA @ c
        A, t = dA @ A, dA @ t + dt
        U, _, Vt = np.linalg.svd(A)                                  # keep A orthonormal
        A = U @ Vt
        rstep, tstep = _angle_of(dA), float(np.linalg.norm(dA @ p.mean(axis=0) + dt - p.mean(axis=0)))
        rec = ICPIteration(it, rms, int(len(idx)), rstep, tstep)
        history.append(rec)
        if progress is not None:
            progress(rec)
        if not (np.all(np.isfinite(A)) and np.all(np.isfinite(t))):
            raise ConvergenceError(f"ICP step {it}: the estimate became NaN/inf", history)
        if coarse and rstep < 10 * tol_rotation and tstep < 10 * tol_translation:
            active, coarse = Sc, False                                 # fine stage: all points
            continue
        if not coarse and rstep < tol_rotation and tstep < tol_translation:
            converged = True
            break
    if not converged and raise_on_max_iter:
        raise ConvergenceError(f"ICP did not converge in {max_iter} steps (last step {history[-1].rotation_step:.3g} "
                               f"rad, {history[-1].translation_step:.3g}); raise max_iter or start closer", history)
    X, d, j, idx = pairs_at(A, t, Sc)
    if normals is not None and len(idx):
        rms = float(np.sqrt(np.mean(np.einsum("ni,ni->n", normals[j[idx]], X[idx] - Tc[j[idx]]) ** 2)))
    else:
        rms = float(np.sqrt(np.mean(d[idx] ** 2))) if len(idx) else float("nan")
    shift = t + c0 - A @ c0
    transform = RigidTransform.from_matrix(shift, A, order)
    return ICPResult(transform, rms, float(np.isfinite(d).sum() / len(S)), len(history), converged, method, history)
