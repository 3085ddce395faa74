"""Side-looking radar images and radar interferometry: Chapter 8, §8.9–8.13.

* §8.9 — the slant range from the image coordinate, D = D₀ + k·y_c (8.9.1); the radar frame
  Sxyz: origin at the emission point, y and z in the emission plane, x normal to it (along the
  flight). The model is **zero-Doppler**: a point is imaged when it lies in the emission plane.
* §8.11 — a point from one image: R_M = R_S + A·D·(0, s·sin φ, −cos φ)ᵀ, (8.11.1)–(8.11.5).
  (8.11.4) is lost in the OCR of the book; :mod:`photolib.derivations.radar` derives it. The look
  angle φ follows from a known height Z — in closed form (the circle of radius D in the
  emission plane cut by the plane Z = const) or by Newton's iteration (8.11.6) — or, for a
  vertical emission plane only (A = I up to a rotation about z), from cos φ = H/D (8.11.7).
  ``side`` chooses the imaged side (s = +1: the book's +y, "left"; s = −1: "right").
  Equal-range points (layover, Fig. 8.18) share one image pixel: :func:`layover_mask`.
* §8.12 — two images: the base condition B = D₁ − D₂ (8.12.4)–(8.12.5) solved for φ₁, φ₂ by
  least squares (8.12.6) (:func:`radar_stereo`); n ≥ 2 images by range spheres and
  zero-Doppler planes (:func:`radar_intersection`). Both go through :func:`photolib.lsq.gauss_newton`.
* §8.13 — InSAR: the look angle from D₁, D₂ (8.13.1) or from the range difference ΔD (8.13.4),
  the height (8.13.2), phase ↔ range difference (8.13.3) (4π/λ for repeat-pass or monostatic
  acquisition, 2π/λ for a bistatic single pass), the height precision (8.13.5) and the critical
  baseline (8.13.6). Phase unwrapping — not in the book, but required — by unweighted least
  squares with the discrete cosine transform (Ghiglia & Romero 1994): :func:`unwrap_phase_ls`;
  a simulated interferogram over a DEM: :func:`simulate_interferogram`, :func:`insar_heights`.

Baseline convention of §8.13 (Fig. 8.27 is lost): in the cross-track plane (u toward the imaged
side, w up) S₁ = (0, H), M = S₁ + D₁(sin φ, −cos φ) and the baseline S₂ → S₁ is B(cos α, sin α);
then (8.13.1) holds exactly (sympy: :func:`photolib.derivations.radar.insar_relations`). The
geometry is flat-Earth, as the book's h = H − D₁ cos φ.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from . import _checks
from .errors import ConvergenceError, DegenerateGeometryError, InputError

__all__ = ["slant_range", "range_coordinate", "range_vector", "radar_point", "radar_project",
           "look_angle_from_height", "look_angle_vertical", "layover_mask", "RadarStereo",
           "radar_stereo", "radar_intersection", "insar_look_angle", "insar_look_angle_from_difference",
           "insar_height", "range_difference_to_phase", "phase_to_range_difference",
           "perpendicular_baseline", "height_precision", "height_of_ambiguity", "critical_baseline",
           "range_resolution", "wrap_phase", "unwrap_phase_ls", "InsarGeometry", "Interferogram",
           "simulate_interferogram", "insar_heights", "load_dem_local"]

SPEED_OF_LIGHT = 299_792_458.0
_PASSES = {"repeat": 2, "monostatic": 2, "bistatic": 1}


# --------------------------------------------------------------------------- input helpers
def _array(value, name, *, positive=False, allow_zero=False):
    if isinstance(value, (str, bytes)) or value is None:
        raise InputError(f"{name} must be a number or an array of numbers, got {value!r}")
    try:
        a = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise InputError(f"{name} must be a number or an array of numbers, got {value!r}") from None
    if a.size == 0:
        raise InputError(f"{name} is empty")
    if not np.all(np.isfinite(a)):
        raise InputError(f"{name} contains NaN or inf")
    if positive and (np.any(a < 0) or (not allow_zero and np.any(a == 0))):
        raise InputError(f"{name} must be positive, got {value!r}")
    return a


def _vec3(value, name):
    a = _array(value, name)
    if a.shape != (3,):
        raise InputError(f"{name} must be a 3-vector, got shape {a.shape}")
    return a


def _rot(value, name):
    a = _array(value, name)
    if a.shape != (3, 3):
        raise InputError(f"{name} must be a 3×3 rotation matrix, got shape {a.shape}")
    if not np.allclose(a @ a.T, np.eye(3), atol=1e-6) or np.linalg.det(a) < 0:
        raise InputError(f"{name} is not a rotation matrix (AᵀA ≠ I or det A < 0)")
    return a


def _sign(side):
    """+1 for "left" (the book's +y), −1 for "right" (as photolib.derivations.radar.look_sign,
    without importing sympy)."""
    if side == "left":
        return 1
    if side == "right":
        return -1
    raise InputError(f"side must be 'left' or 'right', got {side!r}")


def _factor(passes):
    if passes not in _PASSES:
        raise InputError(f"passes must be one of {sorted(_PASSES)}, got {passes!r}")
    return _PASSES[passes]


def _out(a):
    return float(a) if np.ndim(a) == 0 else a


def _angle(value, name):
    a = _array(value, name)
    if np.any(np.abs(a) > 2 * np.pi):
        raise InputError(f"{name} must be in radians (|{name}| ≤ 2π), got {value!r}")
    return a


# --------------------------------------------------------------------------- §8.9
def slant_range(y_c, D0, k):
    """Slant range of an image point from its coordinate along the image line, (8.9.1).

    Parameters
    ----------
    y_c : float or array_like
        Coordinate along the image line from the near-range origin (pixels or mm).
    D0 : float
        Near (initial) slant range D₀, m (> 0).
    k : float
        Range scale, m per unit of y_c (> 0, from calibration).

    Returns
    -------
    float or ndarray
        D = D₀ + k·y_c, m.

    Raises
    ------
    InputError
        NaN/inf, a non-positive D₀ or k, or a coordinate giving D ≤ 0.

    References
    ----------
    Chibunichev (2022), §8.9, eq. (8.9.1).

    Examples
    --------
    >>> slant_range([0, 100, 1000], 850000.0, 7.8)
    array([850000., 850780., 857800.])
    """
    y = _array(y_c, "y_c")
    D0 = _checks.number(D0, "D0", positive=True)
    k = _checks.number(k, "k", positive=True)
    D = D0 + k * y
    if np.any(D <= 0):
        raise InputError("y_c gives a non-positive slant range")
    return _out(D)


def range_coordinate(D, D0, k):
    """Image coordinate y_c of a slant range: the inverse of (8.9.1).

    Parameters
    ----------
    D : float or array_like
        Slant range, m (> 0).
    D0, k : float
        Near range and range scale, as in :func:`slant_range`.

    Returns
    -------
    float or ndarray
        y_c = (D − D₀)/k.

    Raises
    ------
    InputError
        NaN/inf, a non-positive D, D₀ or k.

    References
    ----------
    Chibunichev (2022), §8.9, eq. (8.9.1).

    Examples
    --------
    >>> range_coordinate(850780.0, 850000.0, 7.8)
    100.0
    """
    D = _array(D, "D", positive=True)
    D0 = _checks.number(D0, "D0", positive=True)
    k = _checks.number(k, "k", positive=True)
    return _out((D - D0) / k)


# --------------------------------------------------------------------------- §8.11
def range_vector(D, phi, side: str = "left"):
    """The range vector in the radar frame, (8.11.4) (lost in the OCR; derived with sympy).

    Parameters
    ----------
    D : float or array_like
        Slant range, m (> 0).
    phi : float or array_like
        Look angle from the nadir toward the imaged side, rad (broadcast with D).
    side : {"left", "right"}
        Imaged side: +y of the radar frame ("left", the book's form) or −y ("right").

    Returns
    -------
    ndarray
        (…, 3): D·(0, s·sin φ, −cos φ).

    Raises
    ------
    InputError
        NaN/inf, D ≤ 0, |φ| > 2π, shapes that do not broadcast, an unknown side.

    References
    ----------
    Chibunichev (2022), §8.11, eq. (8.11.4); :func:`photolib.derivations.radar.radar_range_vector_symbolic`.

    Examples
    --------
    >>> range_vector(1000.0, 0.0)
    array([    0.,     0., -1000.])
    >>> range_vector(2.0, np.pi / 6, side="right").round(6)
    array([ 0.      , -1.      , -1.732051])
    """
    D = _array(D, "D", positive=True)
    phi = _angle(phi, "phi")
    s = _sign(side)
    try:
        D, phi = np.broadcast_arrays(D, phi)
    except ValueError:
        raise InputError(f"D {D.shape} and phi {phi.shape} do not broadcast") from None
    return np.stack([np.zeros_like(D), s * D * np.sin(phi), -D * np.cos(phi)], axis=-1)


def radar_point(S, A, D, phi, side: str = "left"):
    """The object point from the emission point, attitude, slant range and look angle, (8.11.5).

    Parameters
    ----------
    S : array_like (3,)
        Emission point R_S = (X_S, Y_S, Z_S), m.
    A : array_like (3, 3)
        Rotation radar frame → object frame (:func:`photolib.rotation.rotation_matrix`).
    D : float or array_like
        Slant range(s), m.
    phi : float or array_like
        Look angle(s), rad.
    side : {"left", "right"}
        Imaged side (see :func:`range_vector`).

    Returns
    -------
    ndarray
        (3,) or (…, 3): R_M = R_S + A·D·(0, s·sin φ, −cos φ)ᵀ.

    Raises
    ------
    InputError
        NaN/inf, wrong shapes, A not a rotation, D ≤ 0, an unknown side.

    References
    ----------
    Chibunichev (2022), §8.11, eqs. (8.11.1)–(8.11.5).

    Examples
    --------
    >>> radar_point([0, 0, 8000.0], np.eye(3), 10000.0, np.arccos(0.8)).round(6)
    array([   0., 6000.,    0.])
    """
    S, A = _vec3(S, "S"), _rot(A, "A")
    return S + range_vector(D, phi, side) @ A.T


def radar_project(S, A, M, side: str = "left"):
    """Slant range, look angle and along-track offset of object points: the inverse of (8.11.5).

    Parameters
    ----------
    S : array_like (3,)
        Emission point, m.
    A : array_like (3, 3)
        Rotation radar frame → object frame.
    M : array_like (3,) or (n, 3)
        Object point(s), m.
    side : {"left", "right"}
        Imaged side.

    Returns
    -------
    tuple of ndarray
        (D, φ, x): slant range, look angle and the coordinate x normal to the emission plane
        (0 for a point imaged at this emission, the zero-Doppler condition).

    Raises
    ------
    InputError
        NaN/inf, wrong shapes, A not a rotation, an unknown side.
    DegenerateGeometryError
        A point at the emission point (D = 0).

    References
    ----------
    Chibunichev (2022), §8.9 (the radar frame), §8.11, eqs. (8.11.3)–(8.11.5).

    Examples
    --------
    >>> D, phi, x = radar_project([0, 0, 8000.0], np.eye(3), [0, 6000.0, 0])
    >>> float(D), round(float(np.cos(phi)), 6), float(x)
    (10000.0, 0.8, 0.0)
    """
    S, A = _vec3(S, "S"), _rot(A, "A")
    M = _array(M, "M")
    if M.shape[-1:] != (3,) or M.ndim > 2:
        raise InputError(f"M must be (3,) or (n, 3), got shape {M.shape}")
    s = _sign(side)
    v = (M - S) @ A                      # Aᵀ(M − S), radar-frame coordinates
    D = np.linalg.norm(v, axis=-1)
    if np.any(D == 0):
        raise DegenerateGeometryError("a point coincides with the emission point (D = 0)")
    phi = np.arctan2(s * v[..., 1], -v[..., 2])
    return _out(D), _out(phi), _out(v[..., 0])


def _height_terms(S, A, s):
    R = np.hypot(A[2, 1], A[2, 2])
    if R < 1e-12:
        raise DegenerateGeometryError("the emission plane is horizontal (a32 = a33 = 0): Z does not fix φ")
    return R, np.arctan2(A[2, 2], s * A[2, 1])


def look_angle_from_height(S, A, D, Z, side: str = "left", *, method: str = "closed", phi0=None,
                           root: str = "look", tol: float = 1e-12, max_iter: int = 30):
    """The look angle φ of a point of known height Z: the third equation of (8.11.5).

    In the emission plane, the circle of radius D about S meets the plane Z = const in two
    points, symmetric about the nadir: the one on the imaged side (``root="look"``) and its
    mirror. Closed form: with R sin ψ = a₃₃, R cos ψ = s·a₃₂,
    Z − Z_S = D·R·sin(φ − ψ), so φ = ψ + arcsin((Z − Z_S)/(D·R)). Newton (``method="newton"``)
    iterates the correction equation (8.11.6) a·δφ = l with a = D(s·a₃₂ cos φ + a₃₃ sin φ).

    Parameters
    ----------
    S : array_like (3,)
        Emission point, m.
    A : array_like (3, 3)
        Rotation radar frame → object frame.
    D : float or array_like
        Slant range(s), m.
    Z : float or array_like
        Known height(s) of the point(s), m (broadcast with D).
    side : {"left", "right"}
        Imaged side.
    method : {"closed", "newton"}
        Closed form or the iteration (8.11.6).
    phi0 : float or array_like, optional
        Start of the Newton iteration (default: (8.11.7) with H = Z_S − Z).
    root : {"look", "mirror"}
        Which of the two intersections (closed form only).
    tol : float
        Newton: stop when every |δφ| < tol, rad.
    max_iter : int
        Newton: iterations allowed.

    Returns
    -------
    float or ndarray
        φ, rad, in (−π, π].

    Raises
    ------
    InputError
        NaN/inf, wrong shapes, unknown ``side``/``method``/``root``.
    DegenerateGeometryError
        The range does not reach the plane Z (|Z − Z_S| > D·R), the emission plane is
        horizontal, or Newton ended on the mirror root.
    ConvergenceError
        Newton did not converge.

    References
    ----------
    Chibunichev (2022), §8.11, eqs. (8.11.5)–(8.11.6).

    Examples
    --------
    >>> S, A = [0, 0, 8000.0], np.eye(3)
    >>> round(float(look_angle_from_height(S, A, 10000.0, 0.0)), 6), round(float(np.arccos(0.8)), 6)
    (0.643501, 0.643501)
    >>> round(float(look_angle_from_height(S, A, 10000.0, 0.0, method="newton")), 6)
    0.643501
    """
    S, A = _vec3(S, "S"), _rot(A, "A")
    D = _array(D, "D", positive=True)
    Z = _array(Z, "Z")
    s = _sign(side)
    if method not in ("closed", "newton"):
        raise InputError(f"method must be 'closed' or 'newton', got {method!r}")
    if root not in ("look", "mirror"):
        raise InputError(f"root must be 'look' or 'mirror', got {root!r}")
    try:
        D, Z = np.broadcast_arrays(D, Z)
    except ValueError:
        raise InputError(f"D {D.shape} and Z {Z.shape} do not broadcast") from None
    R, psi = _height_terms(S, A, s)
    c = (Z - S[2]) / (D * R)
    if np.any(np.abs(c) > 1 + 1e-12):
        bad = np.flatnonzero(np.abs(c) > 1)
        raise DegenerateGeometryError(
            f"the slant range does not reach the plane Z (|Z − Z_S| > D·√(a32² + a33²)) at {bad.size} "
            f"point(s), e.g. D = {D.flat[bad[0]]:.3f} m, Z − Z_S = {(Z - S[2]).flat[bad[0]]:.3f} m")
    c = np.clip(c, -1.0, 1.0)
    look = psi + np.arcsin(c)
    nadir = psi - np.pi / 2
    if method == "closed":
        phi = look if root == "look" else 2 * nadir - look
        return _out(np.angle(np.exp(1j * phi)))
    from .derivations.radar import radar_height_model
    residual, jacobian = radar_height_model(side).compile()
    if phi0 is None:
        H = np.clip((S[2] - Z) / D, -1.0, 1.0)
        phi = np.arccos(H)
    else:
        phi = np.broadcast_to(_angle(phi0, "phi0"), D.shape).astype(float)
    max_iter = _checks.integer(max_iter, "max_iter")
    tol = _checks.number(tol, "tol", positive=True)
    for _ in range(max_iter):
        l = residual(phi, S[2], A[2, 1], A[2, 2], D, Z)[0]
        a = jacobian(phi, S[2], A[2, 1], A[2, 2], D, Z)[0]
        if np.any(np.abs(a) < 1e-12 * D):
            raise ConvergenceError("(8.11.6): the coefficient a vanished (φ at the nadir or zenith of the plane)")
        delta = -l / a
        phi = phi + delta
        if np.all(np.abs(delta) < tol):
            break
    else:
        raise ConvergenceError(f"(8.11.6) did not converge in {max_iter} iterations")
    off = np.angle(np.exp(1j * (phi - nadir)))
    if np.any(off < 0):
        raise DegenerateGeometryError("Newton's iteration converged to the mirror root (the other side "
                                      "of the nadir): give phi0 on the imaged side")
    return _out(np.angle(np.exp(1j * phi)))


def look_angle_vertical(H, D):
    """The look angle from cos φ = H/D, (8.11.7) — exact only for a vertical emission plane.

    (8.11.7) assumes the radar z axis vertical in the emission plane (a₃₂ = 0, a₃₃ = 1, e.g.
    A = I or a rotation about z only); with roll or pitch use :func:`look_angle_from_height`.

    Parameters
    ----------
    H : float or array_like
        Height of the emission point above the point, H = Z_S − Z, m (> 0).
    D : float or array_like
        Slant range, m.

    Returns
    -------
    float or ndarray
        φ = arccos(H/D), rad.

    Raises
    ------
    InputError
        NaN/inf, H ≤ 0 or D ≤ 0.
    DegenerateGeometryError
        H > D: the range does not reach the point's height.

    References
    ----------
    Chibunichev (2022), §8.11, eq. (8.11.7).

    Examples
    --------
    >>> round(float(look_angle_vertical(8000.0, 10000.0)), 6)
    0.643501
    """
    H = _array(H, "H", positive=True)
    D = _array(D, "D", positive=True)
    if np.any(H > D):
        raise DegenerateGeometryError("H > D: the slant range does not reach the point's height")
    return _out(np.arccos(H / D))


def layover_mask(slant_ranges, axis: int = -1):
    """Points that share their slant range with another point of the same profile (layover).

    Along a ground-range profile (increasing away from the track) a point is imaged unambiguously
    only while the slant range increases strictly; where the terrain faces the radar more steeply
    than the look angle, several ground points have equal ranges and fall into one image pixel
    (Fig. 8.18).

    Parameters
    ----------
    slant_ranges : array_like
        Slant ranges of ground points ordered by increasing ground range along ``axis``.
    axis : int
        The ground-range axis.

    Returns
    -------
    ndarray of bool
        True where a point's range is ≤ that of a nearer point or ≥ that of a farther one.

    Raises
    ------
    InputError
        NaN/inf, an empty array or a bad axis.

    References
    ----------
    Chibunichev (2022), §8.9, Fig. 8.18.

    Examples
    --------
    >>> layover_mask([10.0, 11.0, 13.0, 12.5, 14.0]).tolist()
    [False, False, True, True, False]
    """
    D = _array(slant_ranges, "slant_ranges")
    if isinstance(axis, bool) or not isinstance(axis, (int, np.integer)) or not -D.ndim <= axis < D.ndim:
        raise InputError(f"axis must be an integer axis of a {D.ndim}-D array, got {axis!r}")
    D = np.moveaxis(np.atleast_1d(D), axis, -1)
    prev = np.maximum.accumulate(D, axis=-1)
    prev = np.concatenate([np.full(D.shape[:-1] + (1,), -np.inf), prev[..., :-1]], axis=-1)
    nxt = np.minimum.accumulate(D[..., ::-1], axis=-1)[..., ::-1]
    nxt = np.concatenate([nxt[..., 1:], np.full(D.shape[:-1] + (1,), np.inf)], axis=-1)
    return np.moveaxis((D <= prev) | (D >= nxt), -1, axis)


# --------------------------------------------------------------------------- §8.12
@dataclass
class RadarStereo:
    """A point intersected from a radar stereo pair by (8.12.5)–(8.12.6).

    Attributes
    ----------
    point : ndarray (3,)
        The object point: mean of the two evaluations of (8.12.3).
    phi : ndarray (2,)
        The look angles φ₁, φ₂, rad.
    misclosure : float
        |R_S1 + D₁A₁u₁ − (R_S2 + D₂A₂u₂)|, m (0 for consistent data).
    adjustment : object
        The :class:`photolib.lsq.Adjustment` of (8.12.6).

    References
    ----------
    Chibunichev (2022), §8.12, eqs. (8.12.1)–(8.12.6).

    Examples
    --------
    >>> r = RadarStereo(np.zeros(3), np.zeros(2), 0.0, None)
    >>> r.misclosure
    0.0
    """

    point: np.ndarray
    phi: np.ndarray
    misclosure: float
    adjustment: object


def radar_stereo(S1, A1, D1, S2, A2, D2, side: str = "left", *, phi0=None, Z0: float = 0.0):
    """A point from its slant ranges on two radar images: (8.12.5) solved by least squares (8.12.6).

    The base condition B = R_S2 − R_S1 = D₁A₁u(φ₁) − D₂A₂u(φ₂) gives three equations for the
    two look angles; they are iterated by :func:`photolib.lsq.gauss_newton` with the coefficients
    derived in :func:`photolib.derivations.radar.radar_stereo_model`, then the point follows
    from (8.12.3) (the book prints (8.12.3) as a copy of (8.12.2); the intended form is
    R_M = R_Si + D_i·A_i·(0, s·sin φ_i, −cos φ_i)ᵀ).

    Parameters
    ----------
    S1, S2 : array_like (3,)
        Emission points, m.
    A1, A2 : array_like (3, 3)
        Rotations radar frame → object frame.
    D1, D2 : float
        Slant ranges, m.
    side : {"left", "right"}
        Imaged side of both images.
    phi0 : array_like (2,), optional
        Approximate look angles; by default from the height ``Z0`` (closed form of
        :func:`look_angle_from_height`).
    Z0 : float
        Approximate height of the point for the default start, m.

    Returns
    -------
    RadarStereo
        Point, look angles, misclosure and the adjustment.

    Raises
    ------
    InputError
        NaN/inf, wrong shapes, D ≤ 0, A not a rotation, an unknown side.
    DegenerateGeometryError
        A zero base or a geometry that leaves φ₁, φ₂ undetermined; a range that does not reach
        ``Z0`` (give ``phi0``).
    ConvergenceError
        The iteration did not converge.

    References
    ----------
    Chibunichev (2022), §8.12, eqs. (8.12.1)–(8.12.6).

    Examples
    --------
    >>> M = np.array([0.0, 6000.0, 100.0])
    >>> S1, S2 = np.array([0, 0, 8000.0]), np.array([0, 0, 9500.0])        # vertical base (Fig. 8.22)
    >>> r = radar_stereo(S1, np.eye(3), np.linalg.norm(M - S1), S2, np.eye(3), np.linalg.norm(M - S2))
    >>> r.point.round(6)
    array([   0., 6000.,  100.])
    """
    from .derivations.radar import radar_stereo_model
    from .lsq import gauss_newton
    S1, S2 = _vec3(S1, "S1"), _vec3(S2, "S2")
    A1, A2 = _rot(A1, "A1"), _rot(A2, "A2")
    D1 = _checks.number(D1, "D1", positive=True)
    D2 = _checks.number(D2, "D2", positive=True)
    _sign(side)
    B = S2 - S1
    if np.linalg.norm(B) < 1e-9 * max(D1, D2):
        raise DegenerateGeometryError("the base S2 − S1 is zero: one emission point gives no intersection")
    if phi0 is None:
        phi0 = [look_angle_from_height(S1, A1, D1, Z0, side), look_angle_from_height(S2, A2, D2, Z0, side)]
    phi0 = _angle(phi0, "phi0")
    if phi0.shape != (2,):
        raise InputError(f"phi0 must hold two angles, got shape {phi0.shape}")
    residual, jacobian = radar_stereo_model(side).compile()
    cols = [(0, 1), (0, 2), (1, 1), (1, 2), (2, 1), (2, 2)]
    data = [A1[i, j] for i, j in cols] + [A2[i, j] for i, j in cols] + [D1, D2, *B]

    def linearize(p):
        return jacobian(p[0], p[1], *data).reshape(3, 2), residual(p[0], p[1], *data)

    adj = gauss_newton(linearize, phi0, tol=1e-12, names=("phi1", "phi2"))
    phi = np.asarray(adj.x, dtype=float)
    M1 = S1 + A1 @ range_vector(D1, phi[0], side)
    M2 = S2 + A2 @ range_vector(D2, phi[1], side)
    return RadarStereo(point=(M1 + M2) / 2, phi=phi, misclosure=float(np.linalg.norm(M1 - M2)), adjustment=adj)


def radar_intersection(S, A, D, *, X0=None, weights=None, side: str = "left", Z0: float = 0.0):
    """A point from n ≥ 2 radar images: range spheres and zero-Doppler planes by least squares.

    Each image gives |M − S_i| = D_i (the range, (8.9.1)) and a₁ᵢ·(M − S_i) = 0 (the point in
    the emission plane, x = 0 of the radar frame); 2n equations in X, Y, Z solved by
    :func:`photolib.lsq.gauss_newton` (model :func:`photolib.derivations.radar.range_doppler_model`).

    Parameters
    ----------
    S : array_like (n, 3)
        Emission points, m.
    A : array_like (n, 3, 3)
        Rotations radar frame → object frame.
    D : array_like (n,)
        Slant ranges, m.
    X0 : array_like (3,), optional
        Approximate point; by default from image 0 and the height ``Z0`` on the imaged ``side``.
    weights : array_like (2n,), optional
        Weights of the equations (range₀, Doppler₀, range₁, …); unit weights by default.
    side : {"left", "right"}
        Imaged side (for the default start only).
    Z0 : float
        Approximate height for the default start, m.

    Returns
    -------
    photolib.lsq.Adjustment
        ``x`` is the point (X, Y, Z); residuals, μ and m_X, m_Y, m_Z as usual.

    Raises
    ------
    InputError
        NaN/inf, wrong or mismatched shapes, fewer than 2 images, D ≤ 0.
    DegenerateGeometryError
        A geometry that does not fix the point (e.g. all emission points equal).
    ConvergenceError
        The iteration did not converge.

    References
    ----------
    Chibunichev (2022), §8.9, §8.12, eqs. (8.12.1)–(8.12.3).

    Examples
    --------
    >>> M = np.array([0.0, 6000.0, 100.0])
    >>> S = np.array([[0, 0, 8000.0], [0, 0, 9500.0]])
    >>> A = np.stack([np.eye(3)] * 2)
    >>> adj = radar_intersection(S, A, np.linalg.norm(M - S, axis=1))
    >>> np.asarray(adj.x).round(6)
    array([   0., 6000.,  100.])
    """
    from .derivations.radar import range_doppler_model
    from .lsq import gauss_newton
    S = _array(S, "S")
    A = _array(A, "A")
    D = _array(D, "D", positive=True)
    if S.ndim != 2 or S.shape[1] != 3:
        raise InputError(f"S must be (n, 3), got shape {S.shape}")
    n = S.shape[0]
    if n < 2:
        raise InputError(f"at least 2 images are needed, got {n}")
    if A.shape != (n, 3, 3) or D.shape != (n,):
        raise InputError(f"A must be ({n}, 3, 3) and D ({n},), got {A.shape} and {D.shape}")
    for i in range(n):
        _rot(A[i], f"A[{i}]")
    if X0 is None:
        phi = look_angle_from_height(S[0], A[0], D[0], Z0, side)
        X0 = radar_point(S[0], A[0], D[0], phi, side)
    X0 = _vec3(X0, "X0")
    residual, jacobian = range_doppler_model().compile()
    data = (S[:, 0], S[:, 1], S[:, 2], A[:, 0, 0], A[:, 1, 0], A[:, 2, 0], D)

    def linearize(x):
        L = residual(*x, *data).T.reshape(-1)
        J = jacobian(*x, *data).reshape(2, 3, n).transpose(2, 0, 1).reshape(2 * n, 3)
        return J, L

    return gauss_newton(linearize, X0, weights, tol=1e-9, names=("X", "Y", "Z"))


# --------------------------------------------------------------------------- §8.13
def insar_look_angle(D1, D2, B, alpha):
    """The look angle from the two slant ranges and the baseline, (8.13.1).

    Parameters
    ----------
    D1, D2 : float or array_like
        Slant ranges from S₁ and S₂, m.
    B : float
        Baseline length, m (> 0).
    alpha : float
        Baseline tilt from the horizontal, rad (S₂ → S₁ = B(cos α, sin α), u toward the imaged side).

    Returns
    -------
    float or ndarray
        φ = α + arcsin((D₂² − D₁² − B²)/(2D₁B)), rad.

    Raises
    ------
    InputError
        NaN/inf, non-positive ranges or baseline.
    DegenerateGeometryError
        Inconsistent ranges (|sin(φ − α)| > 1).

    References
    ----------
    Chibunichev (2022), §8.13, eq. (8.13.1).

    Examples
    --------
    >>> round(float(insar_look_angle(1000.0, np.sqrt(1000.0**2 + 100.0**2), 100.0, 0.0)), 12)
    0.0
    """
    D1 = _array(D1, "D1", positive=True)
    D2 = _array(D2, "D2", positive=True)
    B = _checks.number(B, "B", positive=True)
    alpha = float(_angle(alpha, "alpha"))
    return _asin_phi((D2 ** 2 - D1 ** 2 - B ** 2) / (2 * D1 * B), alpha)


def _asin_phi(s, alpha):
    if np.any(np.abs(s) > 1):
        raise DegenerateGeometryError("|sin(φ − α)| > 1: the ranges and the baseline are inconsistent")
    return _out(alpha + np.arcsin(s))


def insar_look_angle_from_difference(D, dD, B, alpha):
    """The look angle from the slant range and the interferometric range difference, (8.13.4).

    Parameters
    ----------
    D : float or array_like
        Slant range D = D₁ from S₁, m.
    dD : float or array_like
        Range difference ΔD = D₂ − D₁, m.
    B, alpha : float
        Baseline length (m) and tilt (rad), as in :func:`insar_look_angle`.

    Returns
    -------
    float or ndarray
        φ = α + arcsin((ΔD² + 2DΔD − B²)/(2DB)), rad.

    Raises
    ------
    InputError
        NaN/inf, non-positive D or B.
    DegenerateGeometryError
        |sin(φ − α)| > 1 (e.g. |ΔD| > B).

    References
    ----------
    Chibunichev (2022), §8.13, eq. (8.13.4).

    Examples
    --------
    >>> round(float(insar_look_angle_from_difference(1000.0, np.sqrt(1000.0**2 + 100.0**2) - 1000.0, 100.0, 0.0)), 12)
    0.0
    """
    D = _array(D, "D", positive=True)
    dD = _array(dD, "dD")
    B = _checks.number(B, "B", positive=True)
    alpha = float(_angle(alpha, "alpha"))
    return _asin_phi((dD ** 2 + 2 * D * dD - B ** 2) / (2 * D * B), alpha)


def insar_height(H, D1, phi):
    """The height of the point, h = H − D₁ cos φ, (8.13.2).

    Parameters
    ----------
    H : float
        Height of S₁ above the datum, m.
    D1 : float or array_like
        Slant range from S₁, m.
    phi : float or array_like
        Look angle, rad.

    Returns
    -------
    float or ndarray
        h, m.

    Raises
    ------
    InputError
        NaN/inf, non-positive H or D₁.

    References
    ----------
    Chibunichev (2022), §8.13, eq. (8.13.2).

    Examples
    --------
    >>> insar_height(8000.0, 10000.0, np.arccos(0.79))
    100.0...
    """
    H = _checks.number(H, "H", positive=True)
    D1 = _array(D1, "D1", positive=True)
    phi = _angle(phi, "phi")
    return _out(H - D1 * np.cos(phi))


def range_difference_to_phase(dD, wavelength, passes: str = "repeat"):
    """The interferometric phase of a range difference, (8.13.3).

    Parameters
    ----------
    dD : float or array_like
        Range difference ΔD, m.
    wavelength : float
        λ, m.
    passes : {"repeat", "monostatic", "bistatic"}
        "repeat"/"monostatic": each antenna transmits and receives, ΔΦ = 4πΔD/λ (the book's
        (8.13.3)); "bistatic": one transmitter, two receivers (a single-pass pair such as
        TanDEM-X in bistatic mode), ΔΦ = 2πΔD/λ.

    Returns
    -------
    float or ndarray
        ΔΦ, rad (unwrapped).

    Raises
    ------
    InputError
        NaN/inf, a non-positive wavelength, an unknown ``passes``.

    References
    ----------
    Chibunichev (2022), §8.13, eq. (8.13.3).

    Examples
    --------
    >>> round(float(range_difference_to_phase(0.05624 / 2, 0.05624)), 6)     # half a wavelength: one cycle
    6.283185
    """
    dD = _array(dD, "dD")
    lam = _checks.number(wavelength, "wavelength", positive=True)
    return _out(2 * np.pi * _factor(passes) * dD / lam)


def phase_to_range_difference(phase, wavelength, passes: str = "repeat"):
    """The range difference of an (unwrapped) interferometric phase: the inverse of (8.13.3).

    Parameters
    ----------
    phase : float or array_like
        ΔΦ, rad.
    wavelength : float
        λ, m.
    passes : {"repeat", "monostatic", "bistatic"}
        See :func:`range_difference_to_phase`.

    Returns
    -------
    float or ndarray
        ΔD = λΔΦ/(4π) (repeat) or λΔΦ/(2π) (bistatic), m.

    Raises
    ------
    InputError
        NaN/inf, a non-positive wavelength, an unknown ``passes``.

    References
    ----------
    Chibunichev (2022), §8.13, eq. (8.13.3).

    Examples
    --------
    >>> round(float(phase_to_range_difference(np.pi / 18, 0.05624)) * 1000, 3)   # 10° of phase noise, mm
    0.781
    """
    ph = _array(phase, "phase")
    lam = _checks.number(wavelength, "wavelength", positive=True)
    return _out(lam * ph / (2 * np.pi * _factor(passes)))


def perpendicular_baseline(B, alpha, phi):
    """The baseline component normal to the line of sight, B⊥ = B cos(φ − α).

    Parameters
    ----------
    B : float
        Baseline length, m.
    alpha : float
        Baseline tilt, rad.
    phi : float or array_like
        Look angle, rad.

    Returns
    -------
    float or ndarray
        B⊥ (the B₀ of (8.13.5)–(8.13.6)), m.

    Raises
    ------
    InputError
        NaN/inf, a non-positive B.

    References
    ----------
    Chibunichev (2022), §8.13, eqs. (8.13.5)–(8.13.6) (B₀).

    Examples
    --------
    >>> round(float(perpendicular_baseline(250.0, np.radians(23), np.radians(23))), 6)
    250.0
    """
    B = _checks.number(B, "B", positive=True)
    alpha = float(_angle(alpha, "alpha"))
    return _out(B * np.cos(_angle(phi, "phi") - alpha))


def height_precision(D, wavelength, phi, B_perp, sigma_phase, passes: str = "repeat"):
    """The height error caused by interferometric phase noise, (8.13.5).

    Parameters
    ----------
    D : float or array_like
        Slant range, m.
    wavelength : float
        λ, m.
    phi : float or array_like
        Look angle, rad.
    B_perp : float or array_like
        Perpendicular baseline B₀, m (> 0).
    sigma_phase : float or array_like
        Phase noise δΦ, rad (≥ 0).
    passes : {"repeat", "monostatic", "bistatic"}
        4π (the book) or 2π in the denominator.

    Returns
    -------
    float or ndarray
        δh = Dλ sin φ/(4πB₀)·δΦ (repeat), m. Exact to first order in B/D (sympy:
        :func:`photolib.derivations.radar.insar_relations`, ``dh_ratio_limit``).

    Raises
    ------
    InputError
        NaN/inf, non-positive D, λ or B₀, a negative δΦ, an unknown ``passes``.

    References
    ----------
    Chibunichev (2022), §8.13, eq. (8.13.5).

    Examples
    --------
    >>> round(float(height_precision(858000.0, 0.05624, np.radians(23), 250.0, 0.3)), 3)
    1.801
    """
    D = _array(D, "D", positive=True)
    lam = _checks.number(wavelength, "wavelength", positive=True)
    Bp = _array(B_perp, "B_perp", positive=True)
    sig = _array(sigma_phase, "sigma_phase", positive=True, allow_zero=True)
    phi = _angle(phi, "phi")
    return _out(D * lam * np.sin(phi) / (2 * np.pi * _factor(passes) * Bp) * sig)


def height_of_ambiguity(D, wavelength, phi, B_perp, passes: str = "repeat"):
    """The height change that turns the phase by one cycle (2π): (8.13.5) with δΦ = 2π.

    Parameters
    ----------
    D, wavelength, phi, B_perp, passes
        As in :func:`height_precision`.

    Returns
    -------
    float or ndarray
        h₂π = λD sin φ/(2B₀) (repeat) or λD sin φ/B₀ (bistatic), m.

    Raises
    ------
    InputError
        As :func:`height_precision`.

    References
    ----------
    Chibunichev (2022), §8.13, eq. (8.13.5).

    Examples
    --------
    >>> round(float(height_of_ambiguity(780e3 / np.cos(np.radians(23)), 0.05624, np.radians(23), 200.0)), 1)
    46.6
    """
    return height_precision(D, wavelength, phi, B_perp, 2 * np.pi, passes)


def critical_baseline(D, wavelength, phi, range_resolution, passes: str = "repeat"):
    """The perpendicular baseline at which the interferogram decorrelates, (8.13.6).

    On flat ground the phase changes by 2π across one slant-range resolution cell δ_D when
    B₀ = λD tan φ/(2δ_D) (repeat pass; λD tan φ/δ_D for a bistatic pair): derived with sympy in
    :func:`photolib.derivations.radar.insar_relations`.

    Parameters
    ----------
    D : float or array_like
        Slant range, m.
    wavelength : float
        λ, m.
    phi : float or array_like
        Look angle (incidence on flat ground), rad, 0 < φ < π/2.
    range_resolution : float
        Slant-range resolution δ_D, m (:func:`range_resolution`).
    passes : {"repeat", "monostatic", "bistatic"}
        See :func:`range_difference_to_phase`.

    Returns
    -------
    float or ndarray
        B₀ crit, m.

    Raises
    ------
    InputError
        NaN/inf, non-positive values, φ outside (0, π/2), an unknown ``passes``.

    References
    ----------
    Chibunichev (2022), §8.13, eq. (8.13.6).

    Examples
    --------
    Envisat ASAR (λ = 5.624 cm, D = 850 km, φ = 23°, 16 MHz bandwidth): the book's ≈ 1100 m.

    >>> round(float(critical_baseline(850e3, 0.05624, np.radians(23), range_resolution(16e6))))
    1083
    """
    D = _array(D, "D", positive=True)
    lam = _checks.number(wavelength, "wavelength", positive=True)
    dr = _checks.number(range_resolution, "range_resolution", positive=True)
    phi = _angle(phi, "phi")
    if np.any((phi <= 0) | (phi >= np.pi / 2)):
        raise InputError("phi must lie in (0, π/2)")
    return _out(lam * D * np.tan(phi) / (_factor(passes) * dr))


def range_resolution(bandwidth):
    """Slant-range resolution of a chirp of the given bandwidth, δ_D = c/(2W).

    Parameters
    ----------
    bandwidth : float
        Range (chirp) bandwidth W, Hz.

    Returns
    -------
    float
        δ_D, m.

    Raises
    ------
    InputError
        NaN/inf or a non-positive bandwidth.

    References
    ----------
    Chibunichev (2022), §8.13, eq. (8.13.6) (δ_D; the book gives no formula for it).

    Examples
    --------
    >>> round(range_resolution(16e6), 2)
    9.37
    """
    return SPEED_OF_LIGHT / (2 * _checks.number(bandwidth, "bandwidth", positive=True))


# --------------------------------------------------------------------------- phase unwrapping
def wrap_phase(phase):
    """Wrap a phase into (−π, π].

    Parameters
    ----------
    phase : float or array_like
        Phase, rad.

    Returns
    -------
    float or ndarray
        The wrapped phase.

    Raises
    ------
    InputError
        NaN/inf or non-numeric input.

    References
    ----------
    Chibunichev (2022), §8.13, eq. (8.13.3) (the recorded phase is known modulo 2π).

    Examples
    --------
    >>> wrap_phase([0.0, 3 * np.pi, -np.pi]).round(6)
    array([0.      , 3.141593, 3.141593])
    """
    p = _array(phase, "phase")
    w = p - 2 * np.pi * np.floor((p + np.pi) / (2 * np.pi))
    w = np.where(w == -np.pi, np.pi, w)
    return _out(w)


def unwrap_phase_ls(wrapped):
    """Unweighted least-squares phase unwrapping by the discrete cosine transform.

    Finds φ whose differences between neighbouring pixels best fit (least squares) the wrapped
    differences of the data: the discrete Poisson equation with Neumann boundary conditions,
    solved exactly by a 2-D DCT (Ghiglia & Romero 1994). Where the true phase differences are
    all below π in magnitude the result equals the true phase up to a constant; where they are
    not (aliasing, residues from noise or layover) the solution is smoothed there, not
    congruent to the data.

    Parameters
    ----------
    wrapped : array_like (M, N)
        Wrapped phase, rad; M, N ≥ 2.

    Returns
    -------
    ndarray (M, N)
        The unwrapped phase, with zero mean (the constant is unknown: fix it with a reference
        point, as :func:`insar_heights` does).

    Raises
    ------
    InputError
        NaN/inf, not a 2-D array, fewer than 2 pixels along an axis.

    References
    ----------
    Chibunichev (2022), §8.13 (phase unwrapping is implied by (8.13.3)–(8.13.4)); D.C. Ghiglia,
    L.A. Romero (1994), J. Opt. Soc. Am. A 11(1), 107–117.

    Examples
    --------
    >>> true = np.add.outer(np.linspace(0, 12, 20), np.linspace(0, 9, 30))
    >>> u = unwrap_phase_ls(wrap_phase(true))
    >>> bool(np.allclose(u - u.mean(), true - true.mean()))
    True
    """
    from scipy.fft import dctn, idctn
    psi = _array(wrapped, "wrapped")
    if psi.ndim != 2 or min(psi.shape) < 2:
        raise InputError(f"wrapped must be a 2-D array of at least 2×2 pixels, got shape {psi.shape}")
    M, N = psi.shape
    dx = wrap_phase(np.diff(psi, axis=1))
    dy = wrap_phase(np.diff(psi, axis=0))
    rho = np.zeros_like(psi)
    rho[:, :-1] += dx
    rho[:, 1:] -= dx
    rho[:-1, :] += dy
    rho[1:, :] -= dy
    rho_hat = dctn(rho, type=2, norm="ortho")
    denom = (2 * np.cos(np.pi * np.arange(M) / M)[:, None] + 2 * np.cos(np.pi * np.arange(N) / N)[None, :] - 4)
    denom[0, 0] = 1.0
    phi_hat = rho_hat / denom
    phi_hat[0, 0] = 0.0
    return idctn(phi_hat, type=2, norm="ortho")


# --------------------------------------------------------------------------- simulation
@dataclass(frozen=True)
class InsarGeometry:
    """A flat-Earth, straight-track InSAR pair over a ground grid (Envisat-like by default).

    Rows of the grid run along the track, columns away from it (ground range u increasing
    toward the imaged side); the scene centre is seen at ``look_angle``. S₁ = (0, H) in every
    row's cross-track plane, S₂ = S₁ − B(cos α, sin α) (the §8.13 convention).

    Attributes
    ----------
    wavelength : float
        λ, m (Envisat ASAR C band: 0.05624).
    H : float
        Height of S₁, m.
    look_angle : float
        Look angle at the scene centre on the datum, rad.
    B : float
        Baseline length, m.
    alpha : float
        Baseline tilt, rad.
    passes : str
        "repeat" (4π) or "bistatic" (2π), as :func:`range_difference_to_phase`.

    References
    ----------
    Chibunichev (2022), §8.13, eqs. (8.13.1)–(8.13.4), Fig. 8.27.

    Examples
    --------
    >>> g = InsarGeometry()
    >>> round(float(perpendicular_baseline(g.B, g.alpha, g.look_angle)), 1)
    249.6
    """

    wavelength: float = 0.05624
    H: float = 790e3
    look_angle: float = float(np.radians(23.0))
    B: float = 250.0
    alpha: float = float(np.radians(20.0))
    passes: str = "repeat"

    def __post_init__(self):
        for name in ("wavelength", "H", "B"):
            _checks.number(getattr(self, name), name, positive=True)
        a = _checks.number(self.look_angle, "look_angle")
        if not 0 < a < np.pi / 2:
            raise InputError("look_angle must lie in (0, π/2) rad")
        _angle(self.alpha, "alpha")
        _factor(self.passes)


@dataclass
class Interferogram:
    """A simulated interferogram over a height grid (see :func:`simulate_interferogram`).

    Attributes
    ----------
    D1 : ndarray
        Slant range from S₁ of every ground cell, m.
    phase : ndarray
        True (unwrapped) interferometric phase (8.13.3), rad.
    flat_phase : ndarray
        Phase of the datum h = 0 at the same slant range D₁ (the "flat-Earth" phase), rad.
    wrapped : ndarray
        The recorded interferogram: wrap(phase − flat_phase + noise), rad.
    geometry : InsarGeometry
        The acquisition.
    layover : ndarray of bool
        Cells in layover (:func:`layover_mask` along the columns).

    References
    ----------
    Chibunichev (2022), §8.13, Fig. 8.28.

    Examples
    --------
    >>> ifg = simulate_interferogram(np.zeros((4, 5)), 25.0)
    >>> ifg.wrapped.shape, float(np.abs(ifg.wrapped).max()) < 1e-9
    ((4, 5), True)
    """

    D1: np.ndarray
    phase: np.ndarray
    flat_phase: np.ndarray
    wrapped: np.ndarray
    geometry: InsarGeometry
    layover: np.ndarray


def _ground_u(shape, pixel_size, geometry):
    n = shape[1]
    return geometry.H * np.tan(geometry.look_angle) + (np.arange(n) - (n - 1) / 2) * pixel_size


def _delta_range(u, w, D1, g):
    """D₂ − D₁ for M − S₁ = (u, w), without the cancellation of two 800-km ranges."""
    D2 = np.hypot(u + g.B * np.cos(g.alpha), w + g.B * np.sin(g.alpha))
    return (g.B ** 2 + 2 * g.B * (u * np.cos(g.alpha) + w * np.sin(g.alpha))) / (D1 + D2)


def _flat_phase(D1, g):
    """The phase of the datum h = 0 seen at slant range D₁ (u = √(D₁² − H²), w = −H)."""
    u = np.sqrt(np.maximum((D1 - g.H) * (D1 + g.H), 0.0))
    return 2 * np.pi * _factor(g.passes) * _delta_range(u, -g.H, D1, g) / g.wavelength


def simulate_interferogram(heights, pixel_size, geometry: InsarGeometry | None = None, *,
                           sigma_phase: float = 0.0, seed: int = 0):
    """The interferogram of a height grid for a flat-Earth InSAR pair, (8.13.1)–(8.13.3).

    For each cell (row along the track, column along ground range u) the exact ranges
    D₁ = |M − S₁|, D₂ = |M − S₂| give ΔΦ = (4π/λ)(D₂ − D₁) (2π for bistatic). The phase of the
    datum at the same D₁ is subtracted (flattening), seeded Gaussian noise of σ = ``sigma_phase``
    is added, and the result is wrapped into (−π, π]. The grid is in ground geometry (a
    geocoded interferogram); cells in layover are flagged.

    Parameters
    ----------
    heights : array_like (M, N)
        Heights h of the grid, m.
    pixel_size : float
        Cell size, m.
    geometry : InsarGeometry, optional
        The acquisition (Envisat-like by default).
    sigma_phase : float
        Phase noise σ, rad (≥ 0).
    seed : int
        Seed of the noise.

    Returns
    -------
    Interferogram
        Ranges, true and flat-Earth phase, the wrapped noisy interferogram, the layover mask.

    Raises
    ------
    InputError
        NaN/inf, not a 2-D grid, a non-positive pixel size, a negative σ, a bad seed, a height
        at or above the sensor.

    References
    ----------
    Chibunichev (2022), §8.13, eqs. (8.13.1)–(8.13.3), Fig. 8.28.

    Examples
    --------
    >>> ifg = simulate_interferogram(np.full((3, 3), 100.0), 25.0)
    >>> float(np.ptp(ifg.phase - ifg.flat_phase)) < 0.01   # a constant height: almost no fringes
    True
    """
    h = _array(heights, "heights")
    if h.ndim != 2 or min(h.shape) < 1:
        raise InputError(f"heights must be a 2-D grid, got shape {h.shape}")
    px = _checks.number(pixel_size, "pixel_size", positive=True)
    g = InsarGeometry() if geometry is None else geometry
    if not isinstance(g, InsarGeometry):
        raise InputError(f"geometry must be an InsarGeometry, got {type(g).__name__}")
    sig = _checks.number(sigma_phase, "sigma_phase", positive=True, allow_zero=True)
    seed = _checks.integer(seed, "seed", minimum=0)
    if np.any(h >= g.H):
        raise InputError("a height is at or above the sensor height H")
    u = _ground_u(h.shape, px, g)[None, :]
    w = h - g.H
    D1 = np.hypot(u, w)
    k = 2 * np.pi * _factor(g.passes) / g.wavelength
    phase = k * _delta_range(u, w, D1, g)
    flat = _flat_phase(D1, g)
    noise = np.random.default_rng(seed).normal(0.0, sig, h.shape) if sig > 0 else 0.0
    return Interferogram(D1=D1, phase=phase, flat_phase=flat, wrapped=wrap_phase(phase - flat + noise),
                         geometry=g, layover=layover_mask(D1, axis=1))


def insar_heights(unwrapped, D1, geometry: InsarGeometry, reference, *, congruent: bool = False):
    """Heights from an unwrapped, flattened interferogram: (8.13.3) → (8.13.4) → (8.13.2).

    The unwrapped phase is known up to a constant; it is fixed with reference cells of known
    height (their mean offset; with ``congruent`` rounded to a multiple of 2π, for unwrappers
    whose result is congruent to the data). Then ΔD = λΔΦ/(4π) (8.13.3), φ from (8.13.4) and
    h = H − D₁ cos φ (8.13.2).

    Parameters
    ----------
    unwrapped : array_like (M, N)
        Unwrapped phase of the flattened interferogram, rad.
    D1 : array_like (M, N)
        Slant ranges from S₁, m.
    geometry : InsarGeometry
        The acquisition.
    reference : tuple (rows, cols, heights)
        Reference cells and their known heights (one or more).
    congruent : bool
        Round the constant to a multiple of 2π.

    Returns
    -------
    ndarray (M, N)
        Heights, m.

    Raises
    ------
    InputError
        NaN/inf, mismatched shapes, references outside the grid or malformed.
    DegenerateGeometryError
        A phase inconsistent with the geometry (|sin(φ − α)| > 1).

    References
    ----------
    Chibunichev (2022), §8.13, eqs. (8.13.2)–(8.13.4), Fig. 8.28.

    Examples
    --------
    >>> h = np.add.outer(np.zeros(8), np.linspace(100, 160, 10))
    >>> ifg = simulate_interferogram(h, 25.0)
    >>> u = unwrap_phase_ls(ifg.wrapped)
    >>> hh = insar_heights(u, ifg.D1, ifg.geometry, ([0], [0], [100.0]))
    >>> float(np.abs(hh - h).max()) < 1e-3
    True
    """
    U = _array(unwrapped, "unwrapped")
    D1 = _array(D1, "D1", positive=True)
    if U.shape != D1.shape or U.ndim != 2:
        raise InputError(f"unwrapped {U.shape} and D1 {D1.shape} must be 2-D grids of one shape")
    if not isinstance(geometry, InsarGeometry):
        raise InputError(f"geometry must be an InsarGeometry, got {type(geometry).__name__}")
    g = geometry
    try:
        rows, cols, href = reference
        rows = np.atleast_1d(np.asarray(rows))
        cols = np.atleast_1d(np.asarray(cols))
        href = _array(href, "reference heights").reshape(-1)
    except (TypeError, ValueError):
        raise InputError("reference must be (rows, cols, heights)") from None
    if not (rows.shape == cols.shape == href.shape and rows.size) or rows.dtype.kind not in "iu" \
            or cols.dtype.kind not in "iu":
        raise InputError("reference rows, cols (integers) and heights must have one length ≥ 1")
    if np.any((rows < 0) | (rows >= U.shape[0]) | (cols < 0) | (cols >= U.shape[1])):
        raise InputError("a reference cell lies outside the grid")
    Dr = D1[rows, cols]
    w = href - g.H
    u = np.sqrt(np.maximum((Dr - w) * (Dr + w), 0.0))
    k = 2 * np.pi * _factor(g.passes) / g.wavelength
    expected = k * _delta_range(u, w, Dr, g) - _flat_phase(Dr, g)
    offset = float(np.mean(expected - U[rows, cols]))
    if congruent:
        offset = 2 * np.pi * np.round(offset / (2 * np.pi))
    total = U + offset + _flat_phase(D1, g)
    dD = total / k
    phi = insar_look_angle_from_difference(D1, dD, g.B, g.alpha)
    return insar_height(g.H, D1, phi)


def load_dem_local(path=None, *, window=(0, 0, 100, 100), pixel_size: float = 25.0):
    """Read a geographic (EPSG:4326) DEM window and resample it to a local metric grid.

    The window's longitudes and latitudes are mapped to metres by an equirectangular projection
    about its centre (x = R cos φ₀ Δλ east, y = R Δφ north, R = 6 371 000 m; the error over
    10 km is below 10⁻⁵ relative) and the heights are interpolated bilinearly ((7.3.1)) at the
    centres of a grid of ``pixel_size`` whose rows run southward (the raster convention of
    Chapters 7–8). Needs rasterio (the ``geo`` extra), imported here only.

    Parameters
    ----------
    path : str or Path, optional
        The GeoTIFF; default ``photolib.datasets.data_path("dem", "srtm_ref.tif")``.
    window : tuple (row0, col0, rows, cols)
        The window in DEM pixels.
    pixel_size : float
        Output cell size, m.

    Returns
    -------
    ndarray (M, N)
        Heights on the local grid, m (as stored: SRTM heights are above the EGM96 geoid).

    Raises
    ------
    InputError
        A bad window or pixel size, a file that is not a (geographic) raster, no-data cells in
        the window.
    photolib.datasets.DataUnavailableError
        The data are absent.

    References
    ----------
    Chibunichev (2022), §8.13 (Fig. 8.28: the DEM); §7.3, eq. (7.3.1) (bilinear interpolation).

    Examples
    --------
    >>> from photolib.datasets import DataUnavailableError
    >>> try:
    ...     h = load_dem_local(window=(0, 0, 20, 20), pixel_size=90.0)
    ... except DataUnavailableError:
    ...     h = np.zeros((20, 15))
    >>> h.ndim
    2
    """
    from scipy.ndimage import map_coordinates
    from .datasets import data_path
    px = _checks.number(pixel_size, "pixel_size", positive=True)
    try:
        r0, c0, nr, nc = (int(v) for v in window)
    except (TypeError, ValueError):
        raise InputError(f"window must be (row0, col0, rows, cols), got {window!r}") from None
    if r0 < 0 or c0 < 0 or nr < 2 or nc < 2:
        raise InputError(f"window must start at ≥ 0 and span ≥ 2×2 pixels, got {window!r}")
    from pathlib import Path
    from .datasets import DataUnavailableError
    path = data_path("dem", "srtm_ref.tif") if path is None else path
    if isinstance(path, (str, Path)) and not Path(path).exists():
        raise DataUnavailableError(f"the DEM {path} does not exist (set PHOTOLIB_DATA for the shared data)",
                                   Path(path))
    import rasterio
    from rasterio.windows import Window
    try:
        ds = rasterio.open(path)
    except (rasterio.errors.RasterioIOError, TypeError) as exc:
        raise InputError(f"cannot read the DEM {path!r} as a raster: {exc}") from None
    with ds:
        if ds.crs is None or not ds.crs.is_geographic:
            raise InputError(f"{path} is not a geographic (longitude/latitude) raster")
        if r0 + nr > ds.height or c0 + nc > ds.width:
            raise InputError(f"window {window!r} exceeds the raster ({ds.height}×{ds.width})")
        z = ds.read(1, window=Window(c0, r0, nc, nr)).astype(float)
        nodata = ds.nodata
        t = ds.transform
    if (nodata is not None and np.any(z == nodata)) or not np.all(np.isfinite(z)):
        raise InputError("the window contains no-data cells")
    R = 6_371_000.0
    lat0 = t.f + t.e * (r0 + nr / 2)
    dx = R * np.cos(np.radians(lat0)) * np.radians(abs(t.a))     # metres per DEM column
    dy = R * np.radians(abs(t.e))                                 # metres per DEM row
    width, height = (nc - 1) * dx, (nr - 1) * dy
    n_c, n_r = int(width // px) + 1, int(height // px) + 1
    cc = np.arange(n_c) * px / dx
    rr = np.arange(n_r) * px / dy
    return map_coordinates(z, np.meshgrid(rr, cc, indexing="ij"), order=1, mode="nearest")
