"""Laser scanning geometry — Chapter 9, §9.1–9.4, §9.7, §9.8, §9.10.

Airborne scanning (§9.1–9.3). A pulse leaves the mirror at the deflection angle φ (from nadir
toward +y of the scanner frame: x along the flight, z up) and returns after t; the range is
D = v·t/2 (9.4.2) and the point in the scanner frame is D·(0, sin φ, −cos φ) (9.1.1)
(:func:`als_scanner_vector`); with the scanner's position and attitude from GNSS/IMU at the
pulse's epoch it is georeferenced by (9.1.2) (:func:`als_georeference`, through
:func:`photolib.georef.direct_georeference`). The swath is SW = 2H·tan(Θ/2) and the footprint
2H·tan(g/2) (§9.2; :func:`swath_width`, :func:`footprint_diameter`, Table 9.1). A pulse may
return several echoes (multiple returns): :func:`return_masks` splits a cloud's returns into
first / last / intermediate / single.

Terrestrial scanning (§9.4). Polar ↔ Cartesian (9.4.1) (:func:`polar_to_xyz`,
:func:`xyz_to_polar`: φ from +Y′ toward +X′, ν the elevation); phase ranging (9.4.3)
(:func:`phase_range`: the printed D = Kλ + λΔφ/2π holds for λ the *unit length*, half the
modulation wavelength — a round trip); the triangulation scanner (9.4.4)/(9.4.5)
(:func:`triangulation_depth`, :func:`triangulation_sigma`). The laser-line scanner: a camera
oriented on a test object of two plates (:func:`photolib.resection.space_resection` on the
plates' marks), the plates as least-squares planes (9.4.7) (:func:`fit_plane`, through
:func:`photolib.lsq.gauss_newton`), the laser line's traces on the plates intersected with them
(9.4.6)–(9.4.9) (:func:`intersect_ray_plane` — with the minus sign the printed (9.4.9) lacks),
the laser plane fitted to those points, the object profile as ray ∩ laser plane and its colour
from the image by (9.4.10) (:func:`colour_points`); :func:`laser_line_scan` does it all,
:func:`simulate_laser_line_scanner` makes a scene with known truth.

Built-in camera (§9.7): camera centre R_S0 + c·(cos ν sin φ, cos ν cos φ, sin ν) (9.7.6)/(9.7.7)
— the printed third component sin φ is a typo — and attitude A = A_κ(−φ)·A_ω(90° + ν) in the
κ–α–ω sequence (1.3.4) (:func:`scanner_camera_pose`); projection (9.7.5)
(:func:`scanner_camera_project`).

Mobile mapping (§9.8): R_M = R_GNSS + A_IMU·[r_GNSS/S + A_IMU/S·R′] (9.8.3)
(:func:`mobile_georeference`), and the calibration of the lever arm r_GNSS/S and boresight
A_IMU/S(Δω, Δα, Δκ) (sequence (1.3.2)) from known targets by least squares
(:func:`calibrate_mobile_system`; Jacobian from :mod:`photolib.derivations.lidar`).

Station design (§9.10): D_max = Δ/tan(dφ) (9.10.1) and Δφ = arctan(d/D) (9.10.2; the printed
form is garbled) — :func:`tls_max_range`, :func:`tls_angular_step`.

Angles in radians; lengths in metres unless stated (image coordinates in mm).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .camera import ExteriorOrientation, InteriorOrientation, image_vector
from .errors import DegenerateGeometryError, InputError, PointBehindCameraError

__all__ = ["SPEED_OF_LIGHT", "als_scanner_vector", "als_georeference", "swath_width", "footprint_diameter",
           "pulse_range", "phase_range", "return_masks", "polar_to_xyz", "xyz_to_polar",
           "triangulation_depth", "triangulation_sigma", "image_rays", "intersect_ray_plane", "PlaneFit",
           "fit_plane", "colour_points", "LaserLineScene", "simulate_laser_line_scanner", "LaserLineResult",
           "laser_line_scan", "scanner_camera_pose", "scanner_camera_project", "mobile_georeference",
           "MobileCalibration", "calibrate_mobile_system", "tls_max_range", "tls_angular_step"]

SPEED_OF_LIGHT = 299_792_458.0
"""Speed of light in vacuum, m/s (divide by the refractive index of air, ≈ 1.0003, for v)."""


# ---------------------------------------------------------------------------------------------
# validation helpers

def _floats(value, name, *, ndim=None, tail=None, positive=False, allow_zero=False):
    if isinstance(value, (str, bytes)) or value is None:
        raise InputError(f"{name} must be numbers, got {type(value).__name__}")
    try:
        arr = np.asarray(value, dtype=float)
    except (TypeError, ValueError) as exc:
        raise InputError(f"{name} must be numbers: {exc}") from exc
    if ndim is not None and arr.ndim not in (ndim if isinstance(ndim, tuple) else (ndim,)):
        raise InputError(f"{name} must be {ndim}-dimensional, got shape {arr.shape}")
    if tail is not None and arr.shape[-len(tail):] != tail:
        raise InputError(f"{name} must have shape (..., {', '.join(map(str, tail))}), got {arr.shape}")
    if arr.size == 0 and ndim not in (None, 0):
        raise InputError(f"{name} is empty")
    if not np.all(np.isfinite(arr)):
        raise InputError(f"{name} contains NaN or inf")
    if positive and (np.any(arr < 0) or (not allow_zero and np.any(arr == 0))):
        raise InputError(f"{name} must be {'non-negative' if allow_zero else 'positive'}")
    return arr


def _broadcast(*arrays, names):
    try:
        return np.broadcast_arrays(*arrays)
    except ValueError as exc:
        raise InputError(f"{', '.join(names)} have shapes that do not broadcast: "
                         f"{[a.shape for a in arrays]}") from exc


def _rotation(A, name="A"):
    A = _floats(A, name, tail=(3, 3))
    if A.ndim not in (2, 3):
        raise InputError(f"{name} must be a (3, 3) matrix or an (n, 3, 3) stack, got {A.shape}")
    err = np.abs(np.einsum("...ji,...jk->...ik", A, A) - np.eye(3)).max()
    if err > 1e-6:
        raise InputError(f"{name} is not a rotation matrix (|AᵀA − I| = {err:.2g})")
    return A


def _io_eo(io, eo):
    if not isinstance(io, InteriorOrientation):
        raise InputError(f"io must be an InteriorOrientation, got {type(io).__name__}")
    if not isinstance(eo, ExteriorOrientation):
        raise InputError(f"eo must be an ExteriorOrientation, got {type(eo).__name__}")


def _plane(plane, name="plane"):
    arr = _floats(plane, name, ndim=1, tail=(4,))
    norm = np.linalg.norm(arr[:3])
    if norm < 1e-12:
        raise InputError(f"{name} has a zero normal (A = B = C = 0)")
    return arr / norm


# ---------------------------------------------------------------------------------------------
# §9.1–9.2 airborne scanning

def als_scanner_vector(D, phi) -> np.ndarray:
    """The vector SM of a laser point in the ALS scanner frame, (9.1.1): D·(0, sin φ, −cos φ).

    Parameters
    ----------
    D : float or array_like
        Slant ranges, m (≥ 0).
    phi : float or array_like
        Mirror deflection angles from nadir toward +y, radians.

    Returns
    -------
    numpy.ndarray
        (n, 3) vectors (x along the flight, z up).

    Raises
    ------
    InputError
        NaN/inf, negative ranges, shapes that do not broadcast.

    References
    ----------
    Chibunichev (2022), §9.1, eq. (9.1.1).

    Examples
    --------
    >>> als_scanner_vector(1000.0, 0.0)
    array([[    0.,     0., -1000.]])
    """
    D = _floats(D, "D", ndim=(0, 1), positive=True, allow_zero=True)
    phi = _floats(phi, "phi", ndim=(0, 1))
    D, phi = _broadcast(np.atleast_1d(D), np.atleast_1d(phi), names=("D", "phi"))
    return np.column_stack([np.zeros_like(D), D * np.sin(phi), -D * np.cos(phi)])


def als_georeference(D, phi, positions, A) -> np.ndarray:
    """Object coordinates of ALS points, (9.1.2): R = R_S,i + A_i·D·(0, sin φ, −cos φ).

    The scanner's position R_S,i and attitude A_i (scanner → object, e.g.
    :func:`photolib.rotation.rotation_matrix` of the IMU angles) at each pulse's epoch;
    computed by :func:`photolib.georef.direct_georeference` with zero lever arms and an identity
    boresight (give the full mounting with :func:`mobile_georeference`).

    Parameters
    ----------
    D, phi : array_like (n,)
        Ranges (m) and mirror angles (rad), as :func:`als_scanner_vector`.
    positions : array_like (3,) or (n, 3)
        Scanner positions X_S, Y_S, Z_S per pulse (or one for all).
    A : array_like (3, 3) or (n, 3, 3)
        Attitudes per pulse (or one).

    Returns
    -------
    numpy.ndarray
        (n, 3) object coordinates.

    Raises
    ------
    InputError
        NaN/inf, wrong shapes, mismatched counts, a non-rotation A.

    References
    ----------
    Chibunichev (2022), §9.1, eqs. (9.1.1), (9.1.2); §8.14, eq. (8.14.1).

    Examples
    --------
    >>> als_georeference(1000.0 / np.cos(0.3), 0.3, [0, 0, 1000.0], np.eye(3)).round(6)
    array([[  0.      , 309.336250,   0.      ]])
    """
    from .georef import direct_georeference
    vectors = als_scanner_vector(D, phi)
    A = _rotation(A)
    zero = np.zeros(3)
    return direct_georeference(vectors, _floats(positions, "positions", tail=(3,)), A, zero, zero, np.eye(3))


def swath_width(H, fov):
    """Swath width of an airborne scanner, SW = 2H·tan(Θ/2) (§9.2).

    Parameters
    ----------
    H : float or array_like
        Height above the ground, m (> 0).
    fov : float or array_like
        Full field of view Θ, radians, in (0, π).

    Returns
    -------
    float or numpy.ndarray
        SW, m.

    Raises
    ------
    InputError
        NaN/inf, H ≤ 0, Θ outside (0, π) (a 360° scanner has no swath by this formula).

    References
    ----------
    Chibunichev (2022), §9.2 (unnumbered formula); Table 9.1.

    Examples
    --------
    >>> round(float(swath_width(4700.0, np.radians(60))), 1)
    5427.1
    """
    H = _floats(H, "H", positive=True)
    fov = _floats(fov, "fov")
    if np.any(fov <= 0) or np.any(fov >= np.pi):
        raise InputError("fov must lie in (0, π) radians; a 360° scanner has no swath by SW = 2H·tan(Θ/2)")
    out = 2 * H * np.tan(fov / 2)
    return float(out) if out.ndim == 0 else out


def footprint_diameter(H, divergence):
    """Laser footprint diameter D = 2H·tan(g/2) for beam divergence g (§9.2).

    Parameters
    ----------
    H : float or array_like
        Range (height), m (> 0).
    divergence : float or array_like
        Full beam divergence g, radians (> 0, small).

    Returns
    -------
    float or numpy.ndarray
        Footprint diameter, m.

    Raises
    ------
    InputError
        NaN/inf or non-positive values, g ≥ π.

    References
    ----------
    Chibunichev (2022), §9.2; Table 9.1 (0.25 mrad → 25 cm at 1000 m).

    Examples
    --------
    >>> round(footprint_diameter(1000.0, 0.25e-3), 4)
    0.25
    """
    H = _floats(H, "H", positive=True)
    g = _floats(divergence, "divergence", positive=True)
    if np.any(g >= np.pi):
        raise InputError("divergence must be below π radians (give it in radians, e.g. 0.25e-3)")
    out = 2 * H * np.tan(g / 2)
    return float(out) if out.ndim == 0 else out


def pulse_range(t, v=SPEED_OF_LIGHT):
    """Range of a pulse scanner from the round-trip time, D = v·t/2 (9.4.2).

    Parameters
    ----------
    t : float or array_like
        Round-trip times, s (≥ 0).
    v : float
        Propagation speed, m/s (default c in vacuum).

    Returns
    -------
    float or numpy.ndarray
        D, m.

    Raises
    ------
    InputError
        NaN/inf, negative times, v ≤ 0.

    References
    ----------
    Chibunichev (2022), §9.1 (D = vt/2), §9.4, eq. (9.4.2).

    Examples
    --------
    >>> round(pulse_range(6.671281903963041e-6), 6)
    1000.0
    """
    t = _floats(t, "t", positive=True, allow_zero=True)
    v = float(_floats(v, "v", ndim=0, positive=True))
    out = v * t / 2
    return float(out) if out.ndim == 0 else out


def phase_range(K, phase, wavelength, *, round_trip: bool = True):
    """Range of a phase scanner, (9.4.3): D = (K + Δφ/2π)·λ_u.

    The printed D = Kλ + λΔφ/2π holds when λ is the *unit length* λ_u = λ_mod/2 — the wave
    travels the range twice (compare D = vt/2 of (9.4.2)). With ``round_trip=True`` (default)
    ``wavelength`` is the modulation wavelength and λ_u = λ/2; ``round_trip=False`` applies the
    printed formula literally (``wavelength`` is then the unit length).

    Parameters
    ----------
    K : int or array_like of int
        Whole number of unit lengths (≥ 0), resolved e.g. by several modulation frequencies.
    phase : float or array_like
        Phase difference Δφ in [0, 2π), radians.
    wavelength : float
        Modulation wavelength (or the unit length with ``round_trip=False``), m.
    round_trip : bool
        See above.

    Returns
    -------
    float or numpy.ndarray
        D, m.

    Raises
    ------
    InputError
        NaN/inf, negative or non-integer K, Δφ outside [0, 2π), wavelength ≤ 0.

    References
    ----------
    Chibunichev (2022), §9.4, eq. (9.4.3).

    Examples
    --------
    >>> phase_range(3, np.pi, 10.0)          # unit length 5 m: 3.5 units
    17.5
    """
    K = _floats(K, "K", positive=True, allow_zero=True)
    if np.any(K != np.round(K)):
        raise InputError("K must be a whole number of unit lengths")
    phase = _floats(phase, "phase")
    if np.any(phase < 0) or np.any(phase >= 2 * np.pi):
        raise InputError("phase must lie in [0, 2π) radians")
    lam = float(_floats(wavelength, "wavelength", ndim=0, positive=True))
    unit = lam / 2 if round_trip else lam
    out = (K + phase / (2 * np.pi)) * unit
    return float(out) if out.ndim == 0 else out


def return_masks(return_number, number_of_returns) -> dict:
    """Split laser returns into first, last, intermediate and single (multiple returns, §9.1).

    Parameters
    ----------
    return_number, number_of_returns : array_like of int (n,)
        The LAS attributes (e.g. of a :class:`photolib.pointcloud.PointCloud`), 1 ≤ r ≤ R.

    Returns
    -------
    dict of numpy.ndarray of bool
        ``first`` (r = 1), ``last`` (r = R), ``intermediate`` (1 < r < R), ``single`` (R = 1).

    Raises
    ------
    InputError
        Mismatched lengths, values < 1, r > R, non-integers, NaN.

    References
    ----------
    Chibunichev (2022), §9.1 (several reflections of one pulse: canopy and ground).

    Examples
    --------
    >>> m = return_masks([1, 1, 2, 3], [1, 3, 3, 3])
    >>> m["single"].tolist(), m["last"].tolist(), m["intermediate"].tolist()
    ([True, False, False, False], [True, False, False, True], [False, False, True, False])
    """
    r = _floats(return_number, "return_number", ndim=1)
    R = _floats(number_of_returns, "number_of_returns", ndim=1)
    if r.shape != R.shape:
        raise InputError(f"return_number has {len(r)} values but number_of_returns {len(R)}")
    if np.any(r != np.round(r)) or np.any(R != np.round(R)) or np.any(r < 1) or np.any(r > R):
        raise InputError("returns must be integers with 1 ≤ return_number ≤ number_of_returns")
    return {"first": r == 1, "last": r == R, "intermediate": (r > 1) & (r < R), "single": R == 1}


# ---------------------------------------------------------------------------------------------
# §9.4 terrestrial scanning

def polar_to_xyz(D, phi, nu) -> np.ndarray:
    """Scanner-frame coordinates from range and angles, (9.4.1).

    X′ = D cos ν sin φ, Y′ = D cos ν cos φ, Z′ = D sin ν: φ is the horizontal angle from +Y′
    toward +X′, ν the elevation above the X′Y′ plane.

    Parameters
    ----------
    D, phi, nu : float or array_like
        Ranges (m, ≥ 0), horizontal and vertical angles (rad); broadcast together.

    Returns
    -------
    numpy.ndarray
        (n, 3) points X′, Y′, Z′.

    Raises
    ------
    InputError
        NaN/inf, negative ranges, shapes that do not broadcast.

    References
    ----------
    Chibunichev (2022), §9.4, eq. (9.4.1).

    Examples
    --------
    >>> polar_to_xyz(10.0, np.pi / 2, 0.0).round(12)
    array([[10.,  0.,  0.]])
    """
    D = _floats(D, "D", ndim=(0, 1), positive=True, allow_zero=True)
    phi = _floats(phi, "phi", ndim=(0, 1))
    nu = _floats(nu, "nu", ndim=(0, 1))
    D, phi, nu = _broadcast(np.atleast_1d(D), np.atleast_1d(phi), np.atleast_1d(nu), names=("D", "phi", "nu"))
    return np.column_stack([D * np.cos(nu) * np.sin(phi), D * np.cos(nu) * np.cos(phi), D * np.sin(nu)])


def xyz_to_polar(xyz):
    """Range and angles of scanner-frame points, the inverse of (9.4.1).

    Parameters
    ----------
    xyz : array_like (n, 3)
        Points X′, Y′, Z′ (not at the origin).

    Returns
    -------
    tuple of numpy.ndarray
        D (m), φ in [0, 2π) (from +Y′ toward +X′), ν in [−π/2, π/2].

    Raises
    ------
    InputError
        NaN/inf, wrong shape, a point at the scanner's origin (no direction).

    References
    ----------
    Chibunichev (2022), §9.4, eq. (9.4.1).

    Examples
    --------
    >>> D, phi, nu = xyz_to_polar([[10.0, 0.0, 0.0]])
    >>> float(D[0]), float(np.degrees(phi[0])), float(nu[0])
    (10.0, 90.0, 0.0)
    """
    P = _floats(xyz, "xyz", ndim=2, tail=(3,))
    D = np.linalg.norm(P, axis=1)
    if np.any(D == 0):
        raise InputError("a point lies at the scanner's origin: its angles are undefined")
    phi = np.mod(np.arctan2(P[:, 0], P[:, 1]), 2 * np.pi)
    nu = np.arcsin(np.clip(P[:, 2] / D, -1, 1))
    return D, phi, nu


def triangulation_depth(p, f, B, alpha):
    """Depth of a triangulation scanner, Z = B·f/(p + f·tan α) (9.4.4).

    Camera at the origin looking along Z, the laser at distance B along the camera's x axis,
    the beam tilted by α toward the camera's axis; p is the image coordinate of the spot on the
    CCD line (same unit as f).

    Parameters
    ----------
    p : float or array_like
        Image coordinates of the laser spot.
    f : float
        Focal length (unit of p), > 0.
    B : float
        Base camera–laser, > 0 (unit of Z).
    alpha : float
        Beam angle to the camera axis, radians, in (−π/2, π/2).

    Returns
    -------
    float or numpy.ndarray
        Z (unit of B).

    Raises
    ------
    InputError
        NaN/inf, f or B ≤ 0, |α| ≥ π/2.
    DegenerateGeometryError
        p + f·tan α ≤ 0: the ray and the beam do not meet in front of the camera.

    References
    ----------
    Chibunichev (2022), §9.4, eq. (9.4.4).

    Examples
    --------
    >>> round(triangulation_depth(2.0, 20.0, 100.0, 0.0), 6)
    1000.0
    """
    p = _floats(p, "p")
    f = float(_floats(f, "f", ndim=0, positive=True))
    B = float(_floats(B, "B", ndim=0, positive=True))
    a = float(_floats(alpha, "alpha", ndim=0))
    if abs(a) >= np.pi / 2:
        raise InputError("alpha must lie in (−π/2, π/2) radians")
    denom = p + f * np.tan(a)
    if np.any(denom <= 0):
        raise DegenerateGeometryError("p + f·tan α ≤ 0: the camera ray and the laser beam do not meet in front "
                                      "of the camera")
    out = B * f / denom
    return float(out) if out.ndim == 0 else out


def triangulation_sigma(Z, f, B, sigma_p):
    """Depth precision of a triangulation scanner, m_Z = Z²·m_p/(f·B) (9.4.5).

    Exactly |∂Z/∂p|·m_p of (9.4.4) (a first-order propagation).

    Parameters
    ----------
    Z : float or array_like
        Depth (> 0), unit of B.
    f : float
        Focal length (unit of sigma_p), > 0.
    B : float
        Base, > 0.
    sigma_p : float
        m_p, the image-measurement error, ≥ 0.

    Returns
    -------
    float or numpy.ndarray
        m_Z (unit of B).

    Raises
    ------
    InputError
        NaN/inf, non-positive Z, f or B, negative sigma_p.

    References
    ----------
    Chibunichev (2022), §9.4, eq. (9.4.5).

    Examples
    --------
    >>> round(triangulation_sigma(1000.0, 20.0, 100.0, 0.001), 6)
    0.5
    """
    Z = _floats(Z, "Z", positive=True)
    f = float(_floats(f, "f", ndim=0, positive=True))
    B = float(_floats(B, "B", ndim=0, positive=True))
    s = float(_floats(sigma_p, "sigma_p", ndim=0, positive=True, allow_zero=True))
    out = Z ** 2 * s / (f * B)
    return float(out) if out.ndim == 0 else out


def image_rays(xy, eo: ExteriorOrientation, io: InteriorOrientation) -> np.ndarray:
    """Object-space directions of image rays, (9.4.6): X′ = A·(x − x₀ + d_x, y − y₀ + d_y, −f).

    The printed (9.4.6) omits d_x, d_y though it names them; they are applied here (1.2.3).

    Parameters
    ----------
    xy : array_like (n, 2)
        Measured image coordinates, mm.
    eo : ExteriorOrientation
    io : InteriorOrientation

    Returns
    -------
    numpy.ndarray
        (n, 3) directions (not normalised; mm scale).

    Raises
    ------
    InputError
        Wrong shapes, NaN/inf, wrong types.

    References
    ----------
    Chibunichev (2022), §9.4, eq. (9.4.6); §1.2, eq. (1.2.3).

    Examples
    --------
    >>> image_rays([[0.0, 0.0]], ExteriorOrientation(0, 0, 10), InteriorOrientation(50.0))
    array([[  0.,   0., -50.]])
    """
    _io_eo(io, eo)
    return image_vector(xy, io) @ eo.matrix.T


def intersect_ray_plane(xy, eo: ExteriorOrientation, io: InteriorOrientation, plane) -> np.ndarray:
    """Points where image rays meet a plane, (9.4.8) with N of the corrected (9.4.9).

    N = −(A·X_S + B·Y_S + C·Z_S + D)/(A·X′ + B·Y′ + C·Z′); the printed (9.4.9) has no minus sign
    and would put every point behind the camera (mirrored through S).

    Parameters
    ----------
    xy : array_like (n, 2)
        Image coordinates, mm.
    eo : ExteriorOrientation
    io : InteriorOrientation
    plane : array_like (4,)
        (A, B, C, D) of A·X + B·Y + C·Z + D = 0 (9.4.7).

    Returns
    -------
    numpy.ndarray
        (n, 3) points.

    Raises
    ------
    InputError
        Wrong shapes, NaN/inf, a zero normal.
    DegenerateGeometryError
        A ray parallel to the plane.
    PointBehindCameraError
        A ray that meets the plane behind the camera (N ≤ 0); ``points`` lists them.

    References
    ----------
    Chibunichev (2022), §9.4, eqs. (9.4.6)–(9.4.9).

    Examples
    --------
    >>> intersect_ray_plane([[1.0, 0.0]], ExteriorOrientation(0, 0, 10), InteriorOrientation(50.0),
    ...                     [0, 0, 1, 0]).round(6)
    array([[0.2, 0. , 0. ]])
    """
    plane = _plane(plane)
    rays = image_rays(xy, eo, io)
    S = eo.center
    denom = rays @ plane[:3]
    scale = np.linalg.norm(rays, axis=1)
    if np.any(np.abs(denom) <= 1e-12 * scale):
        raise DegenerateGeometryError("an image ray is parallel to the plane")
    N = -(plane[:3] @ S + plane[3]) / denom
    bad = N <= 0
    if np.any(bad):
        raise PointBehindCameraError(f"{int(bad.sum())} ray(s) meet the plane behind the camera", np.flatnonzero(bad))
    return S + N[:, None] * rays


@dataclass(frozen=True)
class PlaneFit:
    """A least-squares plane A·X + B·Y + C·Z + D = 0 with a unit normal (9.4.7).

    Attributes
    ----------
    plane : numpy.ndarray
        (A, B, C, D), (A, B, C) a unit vector, D = −p.
    normal : numpy.ndarray
        (A, B, C).
    rms : float
        R.m.s. orthogonal distance of the points.
    sigma_angles : numpy.ndarray
        m of the normal's azimuth and elevation (rad) and of p (m), from the adjustment.
    adjustment : photolib.lsq.Adjustment
        The engine's result (unknowns a, b, p of (9.11.1)).

    References
    ----------
    Chibunichev (2022), §9.4, eq. (9.4.7); §9.11, eq. (9.11.1).

    Examples
    --------
    >>> fit = fit_plane([[0, 0, 1.0], [1, 0, 1], [0, 1, 1], [1, 1, 1]])
    >>> fit.plane.round(6) + 0.0
    array([ 0.,  0.,  1., -1.])
    """

    plane: np.ndarray
    rms: float
    sigma_angles: np.ndarray
    adjustment: object

    @property
    def normal(self) -> np.ndarray:
        return self.plane[:3]

    def distance(self, points) -> np.ndarray:
        """Signed orthogonal distances of points from the plane.

        Parameters
        ----------
        points : array_like (n, 3)

        Returns
        -------
        numpy.ndarray
            (n,) distances.

        Raises
        ------
        InputError
            Wrong shape, NaN/inf.

        References
        ----------
        Chibunichev (2022), §9.4, eq. (9.4.7).

        Examples
        --------
        >>> fit_plane([[0, 0, 1.0], [1, 0, 1], [0, 1, 1]]).distance([[5, 5, 3.0]]).round(6)
        array([2.])
        """
        P = _floats(points, "points", ndim=2, tail=(3,))
        return P @ self.plane[:3] + self.plane[3]


def fit_plane(points, weights=None) -> PlaneFit:
    """Least-squares plane through points (9.4.7), by the one engine (:func:`photolib.lsq.gauss_newton`).

    The unknowns are the normal's azimuth a, elevation b and distance p of (9.11.1):
    n = (cos a cos b, sin a cos b, sin b), residual n·X − p (orthogonal distance); initial values
    from the SVD of the centred points. Points are centred before the adjustment (better
    conditioning), p is shifted back afterwards.

    Parameters
    ----------
    points : array_like (n, 3)
        n ≥ 3 points, not collinear.
    weights : array_like (n,), optional
        Weights of the points (1/σ²).

    Returns
    -------
    PlaneFit

    Raises
    ------
    InputError
        Wrong shape, NaN/inf, fewer than 3 points, bad weights.
    DegenerateGeometryError
        Collinear (or coincident) points: the plane is not determined.

    References
    ----------
    Chibunichev (2022), §9.4, eq. (9.4.7); §9.11, eq. (9.11.1); §1.8 (the engine).

    Examples
    --------
    >>> fit_plane([[0, 0, 0.0], [1, 0, 1], [0, 1, 0], [1, 1, 1]]).plane.round(6)
    array([-0.707107,  0.      ,  0.707107,  0.      ])
    """
    from .derivations.lidar import plane_functions
    from .lsq import gauss_newton
    P = _floats(points, "points", ndim=2, tail=(3,))
    if len(P) < 3:
        raise InputError(f"a plane needs at least 3 points, got {len(P)}")
    w = None
    if weights is not None:
        w = _floats(weights, "weights", ndim=1, positive=True)
        if len(w) != len(P):
            raise InputError(f"{len(w)} weights for {len(P)} points")
    centre = P.mean(axis=0) if w is None else (w[:, None] * P).sum(0) / w.sum()
    Q = P - centre
    s = np.linalg.svd(Q, compute_uv=False)
    scale = max(s[0], 1e-300)
    if len(P) < 3 or s[1] <= 1e-9 * scale:
        raise DegenerateGeometryError("the points are collinear (or coincide): the plane is not determined")
    n = np.linalg.svd(Q)[2][-1]
    if n[2] < 0:
        n = -n
    a0, b0 = np.arctan2(n[1], n[0]), np.arcsin(np.clip(n[2], -1, 1))
    residual, jacobian = plane_functions()

    def linearize(x):
        a, b, p = x
        L = np.asarray(residual(a, b, p, Q[:, 0], Q[:, 1], Q[:, 2]), float)
        J = np.column_stack([np.broadcast_to(np.asarray(c, float), (len(Q),))
                             for c in jacobian(a, b, p, Q[:, 0], Q[:, 1], Q[:, 2])])
        return J, L

    if len(P) == 3:
        adj_std = np.full(3, np.nan)
        x = np.array([a0, b0, 0.0])
        adj = None
    else:
        adj = gauss_newton(linearize, np.array([a0, b0, 0.0]), w, names=("a", "b", "p"))
        x, adj_std = adj.x, adj.std
    a, b, p = x
    normal = np.array([np.cos(a) * np.cos(b), np.sin(a) * np.cos(b), np.sin(b)])
    plane = np.append(normal, -(p + normal @ centre))
    rms = float(np.sqrt(np.mean((P @ normal + plane[3]) ** 2)))
    return PlaneFit(plane, rms, np.asarray(adj_std, float), adj)


def colour_points(points, image, eo: ExteriorOrientation, io: InteriorOrientation, pixel_size: float):
    """Colours of object points from an image by the collinearity equations (9.4.10).

    Points are projected by :func:`photolib.single_image.project`, converted to pixel positions
    (frame centre = principal-point origin, :func:`photolib.synthetic.image_to_pixel`) and the
    image is sampled bilinearly.

    Parameters
    ----------
    points : array_like (n, 3)
    image : array_like (rows, cols) or (rows, cols, channels)
    eo : ExteriorOrientation
    io : InteriorOrientation
    pixel_size : float
        mm per pixel.

    Returns
    -------
    tuple of numpy.ndarray
        ``colours`` (n,) or (n, channels) (NaN outside the image) and ``inside`` (n,) bool.

    Raises
    ------
    InputError
        Wrong shapes, NaN/inf, pixel_size ≤ 0.
    PointBehindCameraError
        A point behind the camera.

    References
    ----------
    Chibunichev (2022), §9.4, eq. (9.4.10); §9.7.

    Examples
    --------
    >>> img = np.arange(9.0).reshape(3, 3)
    >>> c, inside = colour_points([[0, 0, 0.0]], img, ExteriorOrientation(0, 0, 10), InteriorOrientation(50.0), 0.01)
    >>> c.tolist(), inside.tolist()
    ([4.0], [True])
    """
    from scipy.ndimage import map_coordinates

    from .single_image import camera_coordinates, project
    from .synthetic import image_to_pixel
    _io_eo(io, eo)
    P = _floats(points, "points", ndim=2, tail=(3,))
    img = _floats(image, "image", ndim=(2, 3))
    if min(img.shape[:2]) < 2:
        raise InputError("the image must have at least 2 rows and columns")
    ps = float(_floats(pixel_size, "pixel_size", ndim=0, positive=True))
    cam = camera_coordinates(P, eo)
    if np.any(cam[:, 2] >= 0):
        raise PointBehindCameraError("a point lies behind (or in the plane of) the camera",
                                     np.flatnonzero(cam[:, 2] >= 0))
    xy = project(P, eo, io)
    colrow = image_to_pixel(xy, img.shape[:2], ps)
    rows, cols = img.shape[:2]
    inside = (colrow[:, 0] >= 0) & (colrow[:, 0] <= cols - 1) & (colrow[:, 1] >= 0) & (colrow[:, 1] <= rows - 1)
    coords = [colrow[:, 1], colrow[:, 0]]
    if img.ndim == 2:
        out = map_coordinates(img, coords, order=1, mode="nearest")
        out[~inside] = np.nan
    else:
        out = np.column_stack([map_coordinates(img[..., c], coords, order=1, mode="nearest")
                               for c in range(img.shape[2])])
        out[~inside] = np.nan
    return out, inside


# ---------------------------------------------------------------------------------------------
# §9.4 the laser-line scanner, simulated and solved

@dataclass(frozen=True)
class LaserLineScene:
    """A simulated laser-line scanner (§9.4): test object of two plates, a camera and a laser plane.

    Attributes
    ----------
    io : InteriorOrientation
    eo : ExteriorOrientation
        The true camera EO (``order="kaw"``).
    marks_xyz, marks_xy : numpy.ndarray
        Marks on the plates P1 (Y = 0) and P2 (X = 0): object (m) and measured image (mm).
    marks_plate : numpy.ndarray
        1 or 2: the plate of each mark.
    trace_xy : numpy.ndarray
        Measured image points of the laser line (mm).
    trace_label : numpy.ndarray
        0 = on the object, 1 = on P1, 2 = on P2.
    trace_xyz : numpy.ndarray
        The true points of the trace.
    laser_plane : numpy.ndarray
        True (A, B, C, D), unit normal.
    object_centre, object_radius : numpy.ndarray, float
        The scanned object, a vertical cylinder.
    image : numpy.ndarray
        An image of the scene (brightness from the true surface) for colouring.
    pixel_size : float
        mm per pixel of ``image``.
    sigma_xy : float
        Measurement noise, mm.

    References
    ----------
    Chibunichev (2022), §9.4, eqs. (9.4.6)–(9.4.10), Fig. 9.12–9.14.

    Examples
    --------
    >>> scene = simulate_laser_line_scanner(seed=1)
    >>> sorted(set(scene.trace_label.tolist()))
    [0, 1, 2]
    """

    io: InteriorOrientation
    eo: ExteriorOrientation
    marks_xyz: np.ndarray
    marks_xy: np.ndarray
    marks_plate: np.ndarray
    trace_xy: np.ndarray
    trace_label: np.ndarray
    trace_xyz: np.ndarray
    laser_plane: np.ndarray
    object_centre: np.ndarray
    object_radius: float
    image: np.ndarray
    pixel_size: float
    sigma_xy: float


def _scene_brightness(P):
    """Albedo of the simulated scene at points P (a smooth pattern in X, Y, Z)."""
    return 0.5 + 0.4 * np.sin(7 * P[:, 0] + 3 * P[:, 2]) * np.cos(5 * P[:, 1] - 2 * P[:, 2])


def simulate_laser_line_scanner(*, seed: int = 0, sigma_xy: float = 0.001, n_marks: int = 12,
                                n_trace: int = 40, laser_tilt: float = 0.35) -> LaserLineScene:
    """Simulate the laser-line scanner of §9.4 with known truth.

    Test object: plate P1 in the plane Y = 0 (X ∈ [0, 1] m) and plate P2 in X = 0 (Y ∈ [0, 1] m),
    Z ∈ [0, 1] m, with marks; a vertical cylinder (r = 0.15 m) stands in the corner; the camera
    (f = 20 mm; a 240×240 image of 0.05 mm pixels for colour) looks into the corner from
    (1.6, 1.6, 1.1), 15° down;
    a laser plane tilted by ``laser_tilt`` about the horizontal cuts the plates and the
    cylinder. Image measurements get Gaussian noise ``sigma_xy`` (mm).

    Parameters
    ----------
    seed : int
        RNG seed.
    sigma_xy : float
        Image noise, mm (≥ 0).
    n_marks : int
        Marks per plate (≥ 4).
    n_trace : int
        Trace points per part (plate 1, plate 2, object), ≥ 3.
    laser_tilt : float
        Tilt of the laser plane from horizontal, radians, in (0, 1.2).

    Returns
    -------
    LaserLineScene

    Raises
    ------
    InputError
        Bad counts, negative noise, tilt out of range.

    References
    ----------
    Chibunichev (2022), §9.4 (the laser-line scanner with a camera), eqs. (9.4.6)–(9.4.10).

    Examples
    --------
    >>> simulate_laser_line_scanner().marks_xyz.shape
    (24, 3)
    """
    from ._checks import integer
    from .single_image import project
    from .synthetic import pixel_to_image
    n_marks = integer(n_marks, "n_marks", 4)
    n_trace = integer(n_trace, "n_trace", 3)
    sigma = float(_floats(sigma_xy, "sigma_xy", ndim=0, positive=True, allow_zero=True))
    tilt = float(_floats(laser_tilt, "laser_tilt", ndim=0))
    if not 0 < tilt < 1.2:
        raise InputError("laser_tilt must lie in (0, 1.2) radians")
    rng = np.random.default_rng(seed)
    io = InteriorOrientation(20.0)
    # camera at (1.6, 1.6, 1.1) looking toward (−1, −1) and 15° down: ω = 75°, κ = 135° about Z;
    # it must lie off the laser plane (the triangulation base), here 0.6·cos(tilt) m from it
    eo = ExteriorOrientation(1.6, 1.6, 1.1, np.radians(75.0), 0.0, 3 * np.pi / 4, order="kaw")
    u = rng.uniform(0.1, 0.95, (n_marks, 2))
    m1 = np.column_stack([u[:, 0], np.zeros(n_marks), u[:, 1]])
    u = rng.uniform(0.1, 0.95, (n_marks, 2))
    m2 = np.column_stack([np.zeros(n_marks), u[:, 0], u[:, 1]])
    marks = np.vstack([m1, m2])
    plate = np.repeat([1, 2], n_marks)
    normal = np.array([np.sin(tilt) / np.sqrt(2), -np.sin(tilt) / np.sqrt(2), np.cos(tilt)])
    laser = np.append(normal, -normal @ np.array([0.5, 0.5, 0.5]))
    centre, radius = np.array([0.35, 0.35]), 0.15

    def on_plate1(x):   # Y = 0: n·(x, 0, z) + d = 0 → z
        return np.column_stack([x, np.zeros_like(x), -(laser[0] * x + laser[3]) / laser[2]])

    def on_plate2(y):
        return np.column_stack([np.zeros_like(y), y, -(laser[1] * y + laser[3]) / laser[2]])

    t1 = on_plate1(np.linspace(0.6, 0.95, n_trace))
    t2 = on_plate2(np.linspace(0.6, 0.95, n_trace))
    # the cylinder's visible half (facing the camera at azimuth 45°): angles 45° ± 70°
    th = np.radians(45 + np.linspace(-70, 70, n_trace))
    cx, cy = centre[0] + radius * np.cos(th), centre[1] + radius * np.sin(th)
    t0 = np.column_stack([cx, cy, -(laser[0] * cx + laser[1] * cy + laser[3]) / laser[2]])
    truth = np.vstack([t0, t1, t2])
    label = np.repeat([0, 1, 2], n_trace)
    marks_xy = project(marks, eo, io) + rng.normal(0, sigma, (len(marks), 2)) if sigma else project(marks, eo, io)
    trace_xy = project(truth, eo, io) + (rng.normal(0, sigma, (len(truth), 2)) if sigma else 0.0)
    # an image of the scene: brightness of the surface each pixel ray hits (plates or cylinder)
    shape, ps = (240, 240), 0.05
    rows, cols = np.mgrid[0:shape[0], 0:shape[1]]
    xy = np.column_stack(pixel_to_image(cols.ravel(), rows.ravel(), shape, ps))
    rays = image_rays(xy, eo, io)
    S = eo.center
    best = np.full(len(rays), np.inf)
    hit = np.zeros((len(rays), 3))
    for k, (ax, lo_axis) in enumerate([(1, 0), (0, 1)]):      # planes Y = 0 and X = 0
        with np.errstate(divide="ignore", invalid="ignore"):
            N = -S[ax] / rays[:, ax]
        P = S + N[:, None] * rays
        ok = (N > 0) & (P[:, lo_axis] >= 0) & (P[:, lo_axis] <= 1.2) & (N < best)
        best[ok], hit[ok] = N[ok], P[ok]
    # cylinder: |(S + N r)_xy − c| = radius
    d = rays[:, :2]
    s0 = S[:2] - centre
    qa, qb, qc = (d ** 2).sum(1), 2 * d @ s0, s0 @ s0 - radius ** 2
    disc = qb ** 2 - 4 * qa * qc
    with np.errstate(invalid="ignore"):
        N = (-qb - np.sqrt(disc)) / (2 * qa)
    ok = (disc > 0) & (N > 0) & (N < best)
    best[ok], hit[ok] = N[ok], S + N[ok, None] * rays[ok]
    image = np.where(np.isfinite(best), _scene_brightness(hit), 0.0).reshape(shape)
    return LaserLineScene(io, eo, marks, marks_xy, plate, trace_xy, label, truth, laser, centre, radius,
                          image, ps, sigma)


@dataclass(frozen=True)
class LaserLineResult:
    """Result of :func:`laser_line_scan`.

    Attributes
    ----------
    eo : ExteriorOrientation
        The camera EO from the marks (space resection).
    plates : tuple of PlaneFit
        P1 and P2 from their marks (9.4.7).
    plate_points : numpy.ndarray
        R₁, R₂: the laser trace on the plates, ray ∩ plate (9.4.8)/(9.4.9).
    laser_plane : PlaneFit
        P3 fitted to the plate points.
    points : numpy.ndarray
        The object profile: rays of the object's trace ∩ P3.
    colours : numpy.ndarray or None
        Colours of ``points`` (9.4.10), if an image was given.
    resection : photolib.resection.ResectionResult

    References
    ----------
    Chibunichev (2022), §9.4, eqs. (9.4.6)–(9.4.10).

    Examples
    --------
    >>> s = simulate_laser_line_scanner(sigma_xy=0.0)
    >>> r = laser_line_scan(s.marks_xyz, s.marks_xy, s.marks_plate, s.trace_xy, s.trace_label, s.io)
    >>> bool(np.abs(r.points - s.trace_xyz[s.trace_label == 0]).max() < 1e-6)
    True
    """

    eo: ExteriorOrientation
    plates: tuple
    plate_points: np.ndarray
    laser_plane: PlaneFit
    points: np.ndarray
    colours: np.ndarray | None
    resection: object


def laser_line_scan(marks_xyz, marks_xy, marks_plate, trace_xy, trace_label, io: InteriorOrientation, *,
                    eo0=None, image=None, pixel_size=None) -> LaserLineResult:
    """The laser-line scanner of §9.4 end to end: EO, plates, laser plane, object profile, colour.

    1. Camera EO from the plates' marks by space resection (§1.8, through the engine);
    2. plates P1, P2 as least-squares planes through their marks (9.4.7);
    3. the laser trace on each plate: ray (9.4.6) ∩ plate, N of the corrected (9.4.9);
    4. the laser plane P3 through those points (9.4.7);
    5. the object's trace: ray ∩ P3; colours from ``image`` by (9.4.10).

    Parameters
    ----------
    marks_xyz : array_like (n, 3)
        Marks on the plates, object coordinates.
    marks_xy : array_like (n, 2)
        Their image coordinates, mm.
    marks_plate : array_like of int (n,)
        1 or 2: the plate of each mark (≥ 3 non-collinear marks per plate).
    trace_xy : array_like (m, 2)
        Image points of the laser line, mm.
    trace_label : array_like of int (m,)
        0 = object, 1 = on P1, 2 = on P2 (≥ 3 points on the plates together, not collinear).
    io : InteriorOrientation
    eo0 : ExteriorOrientation or 6-vector, optional
        Approximate EO for the resection (``order="kaw"``); default: from the marks.
    image : array_like, optional
        An image for colouring (with ``pixel_size``, mm).
    pixel_size : float, optional

    Returns
    -------
    LaserLineResult

    Raises
    ------
    InputError
        Wrong shapes, NaN, labels other than 0/1/2 or plates 1/2, mismatched sizes, an image
        without pixel size.
    DegenerateGeometryError
        Collinear marks on a plate, a laser trace on the plates that does not define a plane.
    PointBehindCameraError
        A trace ray meeting a plane behind the camera.

    References
    ----------
    Chibunichev (2022), §9.4, eqs. (9.4.6)–(9.4.10); §1.8 (resection).

    Examples
    --------
    >>> s = simulate_laser_line_scanner(seed=2)
    >>> r = laser_line_scan(s.marks_xyz, s.marks_xy, s.marks_plate, s.trace_xy, s.trace_label, s.io)
    >>> bool(abs(r.laser_plane.normal @ s.laser_plane[:3]) > 0.9999)
    True
    """
    from .resection import space_resection
    M = _floats(marks_xyz, "marks_xyz", ndim=2, tail=(3,))
    m = _floats(marks_xy, "marks_xy", ndim=2, tail=(2,))
    plate = _floats(marks_plate, "marks_plate", ndim=1)
    T = _floats(trace_xy, "trace_xy", ndim=2, tail=(2,))
    lab = _floats(trace_label, "trace_label", ndim=1)
    if not isinstance(io, InteriorOrientation):
        raise InputError(f"io must be an InteriorOrientation, got {type(io).__name__}")
    if len(M) != len(m) or len(plate) != len(M):
        raise InputError(f"{len(M)} marks, {len(m)} image marks and {len(plate)} plate labels: sizes differ")
    if len(T) != len(lab):
        raise InputError(f"{len(T)} trace points but {len(lab)} labels")
    if not set(np.unique(plate)) <= {1, 2} or not set(np.unique(lab)) <= {0, 1, 2}:
        raise InputError("marks_plate must be 1 or 2 and trace_label 0, 1 or 2")
    if image is not None and pixel_size is None:
        raise InputError("give pixel_size (mm) with the image")
    res = space_resection(M, m, io, eo0=eo0 if eo0 is not None else _initial_eo(M, m, io), order="kaw")
    eo = res.eo
    plates = []
    for k in (1, 2):
        pts = M[plate == k]
        if len(pts) < 3:
            raise InputError(f"plate {k} has {len(pts)} marks; at least 3 are needed")
        plates.append(fit_plane(pts))
    R = [intersect_ray_plane(T[lab == k], eo, io, plates[k - 1].plane) for k in (1, 2) if np.any(lab == k)]
    if not R:
        raise InputError("no trace points on the plates: the laser plane cannot be found")
    R = np.vstack(R)
    if len(R) < 3:
        raise InputError(f"{len(R)} trace points on the plates; at least 3 are needed for the laser plane")
    laser = fit_plane(R)
    obj = T[lab == 0]
    points = intersect_ray_plane(obj, eo, io, laser.plane) if len(obj) else np.zeros((0, 3))
    colours = None
    if image is not None and len(points):
        colours, _ = colour_points(points, image, eo, io, pixel_size)
    return LaserLineResult(eo, tuple(plates), R, laser, points, colours, res)


def _initial_eo(M, m, io):
    """Approximate EO for a horizontal-looking camera: a few resections from a ring of starts."""
    import warnings

    from .errors import ConvergenceError, DegreesWarning
    from .single_image import camera_coordinates
    from .resection import space_resection
    c = M.mean(axis=0)
    spread = np.linalg.norm(M - c, axis=1).max()
    best = None
    for az in np.radians(np.arange(0, 360, 45)):
        d = np.array([np.sin(az), np.cos(az), 0.0])
        S = c + 3 * spread * d
        # horizontal camera (ω = 90°) whose −z points back at the centroid: κ = π − azimuth
        eo = ExteriorOrientation(*S, np.pi / 2, 0.0, np.pi - az, order="kaw")
        try:
            with warnings.catch_warnings():     # a diverging start may pass through huge angles
                warnings.simplefilter("ignore", DegreesWarning)
                res = space_resection(M, m, io, eo0=eo, order="kaw", max_iter=30)
        except (ConvergenceError, DegenerateGeometryError, InputError):
            continue
        if np.any(camera_coordinates(M, res.eo)[:, 2] >= 0):
            continue            # the mirror solution: marks behind the camera
        if best is None or res.mu < best.mu:
            best = res
    if best is None:
        raise DegenerateGeometryError("no approximate camera EO found from the marks; give eo0")
    return best.eo


# ---------------------------------------------------------------------------------------------
# §9.7 the built-in camera of a TLS

def scanner_camera_pose(phi, nu, centre0, c):
    """Centre and attitude of a TLS's built-in camera at head angles φ_k, ν_k, (9.7.6)/(9.7.7).

    R_S = R_S0 + c·(cos ν sin φ, cos ν cos φ, sin ν) — the printed (9.7.7) has sin φ_k in the
    third component (not a unit vector: a typo) — and A = A_κ(−φ)·A_α(0)·A_ω(90° + ν) (the
    κ–α–ω sequence (1.3.4)), whose viewing direction −z is that same unit vector (the book's
    "put φ, ν for α, ω with κ = 0" in the ω–α–κ sequence gives a nadir-looking camera).

    Parameters
    ----------
    phi, nu : float
        Horizontal and vertical angles of the head, radians.
    centre0 : array_like (3,)
        R_S0, the camera centre's origin (scanner frame, from calibration).
    c : float
        The offset along the viewing direction (≥ 0).

    Returns
    -------
    tuple
        ``(centre, A)``: (3,) centre and (3, 3) camera → scanner rotation.

    Raises
    ------
    InputError
        NaN/inf, wrong shapes, c < 0.

    References
    ----------
    Chibunichev (2022), §9.7, eqs. (9.7.6), (9.7.7); §1.3, eq. (1.3.4); §9.4, eq. (9.4.1).

    Examples
    --------
    >>> S, A = scanner_camera_pose(0.0, 0.0, [0, 0, 0.2], 0.1)
    >>> S.round(12) + 0.0, (-A[:, 2]).round(12) + 0.0
    (array([0. , 0.1, 0.2]), array([0., 1., 0.]))
    """
    from .rotation import rotation_matrix
    phi = float(_floats(phi, "phi", ndim=0))
    nu = float(_floats(nu, "nu", ndim=0))
    S0 = _floats(centre0, "centre0", ndim=1, tail=(3,))
    c = float(_floats(c, "c", ndim=0, positive=True, allow_zero=True))
    direction = np.array([np.cos(nu) * np.sin(phi), np.cos(nu) * np.cos(phi), np.sin(nu)])
    A = rotation_matrix(np.pi / 2 + nu, 0.0, -phi, order="kaw")
    return S0 + c * direction, A


def scanner_camera_project(points, centre, A, f):
    """Image coordinates of scanner-frame points in the built-in camera, (9.7.5).

    x = −f·(a₁₁ΔX + a₂₁ΔY + a₃₁ΔZ)/(a₁₃ΔX + a₂₃ΔY + a₃₃ΔZ), y likewise with a₁₂, a₂₂, a₃₂
    (principal point at the origin, as printed).

    Parameters
    ----------
    points : array_like (n, 3)
        Points X′, Y′, Z′ in the scanner frame.
    centre : array_like (3,)
    A : array_like (3, 3)
        Camera → scanner (:func:`scanner_camera_pose`).
    f : float
        Focal length (unit of the result).

    Returns
    -------
    numpy.ndarray
        (n, 2) x, y.

    Raises
    ------
    InputError
        NaN/inf, wrong shapes, f ≤ 0, A not a rotation.
    PointBehindCameraError
        A point behind the camera.

    References
    ----------
    Chibunichev (2022), §9.7, eqs. (9.7.1)–(9.7.5).

    Examples
    --------
    >>> S, A = scanner_camera_pose(0.0, 0.0, [0, 0, 0], 0.0)
    >>> scanner_camera_project([[0.1, 10.0, 0.2]], S, A, 10.0).round(6)
    array([[0.1, 0.2]])
    """
    P = _floats(points, "points", ndim=2, tail=(3,))
    S = _floats(centre, "centre", ndim=1, tail=(3,))
    A = _rotation(A)
    if A.ndim != 2:
        raise InputError("A must be one (3, 3) matrix")
    f = float(_floats(f, "f", ndim=0, positive=True))
    cam = (P - S) @ A
    if np.any(cam[:, 2] >= 0):
        raise PointBehindCameraError("a point lies behind the camera", np.flatnonzero(cam[:, 2] >= 0))
    return np.column_stack([-f * cam[:, 0] / cam[:, 2], -f * cam[:, 1] / cam[:, 2]])


# ---------------------------------------------------------------------------------------------
# §9.8 mobile mapping

def mobile_georeference(R, gnss, A_imu, lever, boresight) -> np.ndarray:
    """Object coordinates of mobile-scanner points, (9.8.3).

    R_M = R_GNSS + A_IMU·[r_GNSS/S + A_IMU/S·R′]: ``lever`` is r_GNSS/S, the scanner origin
    from the GNSS antenna in IMU axes (= r_IMU/S − r_GNSS/IMU of (9.8.2)); computed by
    :func:`photolib.georef.direct_georeference`.

    Parameters
    ----------
    R : array_like (3,) or (n, 3)
        Points in the scanner frame (e.g. :func:`polar_to_xyz`).
    gnss : array_like (3,) or (n, 3)
        Antenna positions per point (or one).
    A_imu : array_like (3, 3) or (n, 3, 3)
        IMU attitudes (IMU → object).
    lever : array_like (3,)
        r_GNSS/S in IMU axes, m.
    boresight : array_like (3, 3)
        A_IMU/S, scanner → IMU.

    Returns
    -------
    numpy.ndarray
        (n, 3) object points.

    Raises
    ------
    InputError
        NaN/inf, wrong shapes, mismatched counts, non-rotation matrices.

    References
    ----------
    Chibunichev (2022), §9.8, eqs. (9.8.1)–(9.8.3).

    Examples
    --------
    >>> mobile_georeference([1.0, 0, 0], [100, 200, 10.0], np.eye(3), [0, 0, -1.0], np.eye(3))
    array([[101., 200.,   9.]])
    """
    from .georef import direct_georeference
    return direct_georeference(R, gnss, A_imu, np.zeros(3), lever, boresight)


@dataclass(frozen=True)
class MobileCalibration:
    """The lever arm and boresight of a mobile scanner from known targets (§9.8).

    Attributes
    ----------
    lever : numpy.ndarray
        r_GNSS/S in IMU axes, m.
    angles : numpy.ndarray
        Boresight Δω, Δα, Δκ (rad) of A_IMU/S = A_ω A_α A_κ (1.3.2).
    boresight : numpy.ndarray
        A_IMU/S (3, 3).
    std : numpy.ndarray
        m_j of the six unknowns (m, rad).
    adjustment : photolib.lsq.Adjustment

    References
    ----------
    Chibunichev (2022), §9.8, eqs. (9.8.1)–(9.8.3).

    Examples
    --------
    >>> MobileCalibration.__dataclass_fields__.keys() >= {"lever", "angles"}
    True
    """

    lever: np.ndarray
    angles: np.ndarray
    boresight: np.ndarray
    std: np.ndarray
    adjustment: object


def calibrate_mobile_system(R, gnss, A_imu, targets, *, lever0=None, angles0=None, sigma_target=None,
                            max_iter: int = 30) -> MobileCalibration:
    """Lever arm r_GNSS/S and boresight (Δω, Δα, Δκ) from scanned targets of known coordinates (§9.8).

    Each observation is a target seen in the scanner frame at R′ with the GNSS/IMU pose of that
    moment; (9.8.3) must give the target's known coordinates. The six unknowns are adjusted by
    :func:`photolib.lsq.gauss_newton` with the sympy Jacobian of
    :func:`photolib.derivations.lidar.mobile_mapping_model`.

    Parameters
    ----------
    R : array_like (n, 3)
        Targets in the scanner frame.
    gnss : array_like (n, 3)
        Antenna positions at each observation.
    A_imu : array_like (3, 3) or (n, 3, 3)
        IMU attitudes.
    targets : array_like (n, 3)
        Known object coordinates.
    lever0, angles0 : array_like (3,), optional
        Approximate values (default zero).
    sigma_target : float, optional
        A-priori σ of a coordinate (m): weights 1/σ² (μ then unitless).
    max_iter : int

    Returns
    -------
    MobileCalibration

    Raises
    ------
    InputError
        NaN/inf, wrong shapes, mismatched counts, fewer than 3 targets.
    DegenerateGeometryError
        Collinear targets seen from one pose (a rotation about their line is free).

    References
    ----------
    Chibunichev (2022), §9.8, eqs. (9.8.1)–(9.8.3); §1.8 (the engine).

    Examples
    --------
    >>> Rp = np.array([[5.0, 0, 0], [0, 5, 0], [0, 0, 5], [3, 3, 1]])
    >>> cal = calibrate_mobile_system(Rp, np.zeros((4, 3)), np.eye(3), Rp + [0.1, 0.2, 1.5])
    >>> cal.lever.round(6) + 0.0, cal.angles.round(6) + 0.0
    (array([0.1, 0.2, 1.5]), array([0., 0., 0.]))
    """
    from .derivations.lidar import MOBILE_PARAMETERS, mobile_mapping_functions
    from .lsq import gauss_newton
    from .rotation import rotation_matrix
    Rp = _floats(R, "R", ndim=2, tail=(3,))
    G = _floats(gnss, "gnss", ndim=2, tail=(3,))
    T = _floats(targets, "targets", ndim=2, tail=(3,))
    A = _rotation(A_imu, "A_imu")
    n = len(Rp)
    if A.ndim == 2:
        A = np.broadcast_to(A, (n, 3, 3))
    if not (len(G) == len(T) == len(A) == n):
        raise InputError(f"R, gnss, A_imu and targets must have one row per observation: "
                         f"{n}, {len(G)}, {len(A)}, {len(T)}")
    if n < 3:
        raise InputError(f"the calibration needs at least 3 targets, got {n}")
    # collinear targets in the scanner frame from a single pose leave a rotation free
    poses = np.unique(np.column_stack([G, A.reshape(n, 9)]).round(9), axis=0)
    if len(poses) == 1:
        s = np.linalg.svd(Rp - Rp.mean(0), compute_uv=False)
        if s[1] <= 1e-9 * max(s[0], 1e-300):
            raise DegenerateGeometryError("the targets are collinear and seen from one pose: a rotation about "
                                          "their line is not determined (use ≥ 3 non-collinear targets)")
    x0 = np.concatenate([np.zeros(3) if lever0 is None else _floats(lever0, "lever0", ndim=1, tail=(3,)),
                         np.zeros(3) if angles0 is None else _floats(angles0, "angles0", ndim=1, tail=(3,))])
    weights = None
    if sigma_target is not None:
        s = float(_floats(sigma_target, "sigma_target", ndim=0, positive=True))
        weights = np.full(3 * n, 1 / s ** 2)
    residual, jacobian = mobile_mapping_functions()
    data = (*G.T, *A.reshape(n, 9).T, *Rp.T, *T.T)

    def linearize(x):
        L = np.concatenate([np.broadcast_to(np.asarray(v, float), (n,)) for v in residual(*x, *data)])
        J = np.array([np.broadcast_to(np.asarray(v, float), (n,)) for v in jacobian(*x, *data)])  # (18, n)
        B = J.reshape(3, 6, n).transpose(0, 2, 1).reshape(3 * n, 6)
        return B, L

    adj = gauss_newton(linearize, x0, weights, names=MOBILE_PARAMETERS, max_iter=max_iter)
    angles = adj.x[3:]
    return MobileCalibration(adj.x[:3].copy(), angles.copy(), rotation_matrix(*angles, order="wak"),
                             np.asarray(adj.std, float), adj)


# ---------------------------------------------------------------------------------------------
# §9.10 station design

def tls_max_range(accuracy, angular_accuracy):
    """Largest station-to-object range for a required accuracy, D = Δ/tan(dφ) (9.10.1).

    Parameters
    ----------
    accuracy : float or array_like
        Δ, the required accuracy of the model, m (> 0).
    angular_accuracy : float or array_like
        dφ, the scanner's angular accuracy, radians, in (0, π/2).

    Returns
    -------
    float or numpy.ndarray
        D, m.

    Raises
    ------
    InputError
        NaN/inf, non-positive values, dφ ≥ π/2 (degrees passed?).

    References
    ----------
    Chibunichev (2022), §9.10, eq. (9.10.1).

    Examples
    --------
    >>> round(tls_max_range(0.005, np.radians(0.005)), 2)
    57.3
    """
    d = _floats(accuracy, "accuracy", positive=True)
    a = _floats(angular_accuracy, "angular_accuracy", positive=True)
    if np.any(a >= np.pi / 2):
        raise InputError("angular_accuracy must be below π/2 radians (give radians)")
    out = d / np.tan(a)
    return float(out) if out.ndim == 0 else out


def tls_angular_step(detail, D):
    """Angular scan step that resolves a detail d at range D, Δφ = arctan(d/D) (9.10.2).

    The printed "arctg(Δφ) = d/D" is garbled; tan Δφ = d/D is meant.

    Parameters
    ----------
    detail : float or array_like
        d, the smallest detail to resolve, m (> 0).
    D : float or array_like
        The (largest) range of the station, m (> 0).

    Returns
    -------
    float or numpy.ndarray
        Δφ, radians.

    Raises
    ------
    InputError
        NaN/inf, non-positive values.

    References
    ----------
    Chibunichev (2022), §9.10, eq. (9.10.2).

    Examples
    --------
    >>> round(float(np.degrees(tls_angular_step(0.01, 50.0))), 4)
    0.0115
    """
    d = _floats(detail, "detail", positive=True)
    D = _floats(D, "D", positive=True)
    out = np.arctan(d / D)
    return float(out) if out.ndim == 0 else out
