"""Geometry of a single frame image — Chapter 1, §1.1 and §1.4–§1.7.

* §1.1 elements of central projection: :func:`principal_to_nadir_distance` (on = f·tan α₀).
* §1.4 image ↔ object: :func:`project` — collinearity equations (1.4.10)–(1.4.12)
  (:func:`project_to_images` for many images at once);
  :func:`image_to_ground` — ray to a known height, (1.4.4)–(1.4.7).
* §1.5 horizontal image: :func:`horizontal_image_scale` (1/m = f/H).
* §1.6 height error: :func:`planimetric_error_from_height_error` (1.6.1).
* §1.7 tilted ↔ horizontal image from one centre: :func:`tilted_to_horizontal` (1.7.5),
  :func:`horizontal_to_tilted` (1.7.10).

Image coordinates in mm, object coordinates in m. A (camera → object) comes from the
exterior orientation's rotation sequence.
"""

from __future__ import annotations

import numpy as np

from .camera import (ExteriorOrientation, ExteriorOrientations, InteriorOrientation, _expect, _scalar,
                     apply_distortion, as_points, correct_distortion)
from .errors import DegenerateGeometryError, InputError, PointBehindCameraError
from .rotation import _as_rotation, _numbers, _order, _rotation_matrix, _warn_degrees

__all__ = ["principal_to_nadir_distance", "camera_coordinates", "project", "project_to_images",
           "image_to_ground", "horizontal_image_scale", "planimetric_error_from_height_error",
           "tilted_to_horizontal", "horizontal_to_tilted"]


def _positive(value, name):
    """Validate a positive finite scalar (a focal length or a flying height)."""
    value = _scalar(value, name)
    if value <= 0:
        raise InputError(f"{name} must be positive and finite, got {value}")
    return value


def principal_to_nadir_distance(f, tilt):
    """on = f·tan α₀: distance in the image from the principal point o to the nadir point n (§1.1).

    Parameters
    ----------
    f : float
        Focal length in mm.
    tilt : float or array
        Tilt α₀ of the image in radians, |α₀| < π/2 (at 90° the nadir point is at infinity).

    Returns
    -------
    float or ndarray
        on in mm.

    Raises
    ------
    InputError
        f ≤ 0, NaN/inf, a non-number, or |α₀| ≥ 90°.

    References
    ----------
    Chibunichev (2022), §1.1 (elements of central projection, Fig. 1.3).

    Examples
    --------
    >>> round(float(principal_to_nadir_distance(100.0, np.radians(45.0))), 9)
    100.0
    """
    f = _positive(f, "focal length f")
    tilt = _numbers(tilt, "the tilt α₀")
    if np.any(np.abs(tilt) >= np.pi / 2):
        raise InputError("the tilt α₀ must be finite and |α₀| < 90°")
    return f * np.tan(tilt)


def camera_coordinates(XYZ, eo: ExteriorOrientation) -> np.ndarray:
    """(X*, Y*, Z*) = Aᵀ(X − X_S, Y − Y_S, Z − Z_S) of (1.4.10), one row per point.

    Parameters
    ----------
    XYZ : (n, 3) array
        Object points in metres.
    eo : ExteriorOrientation

    Returns
    -------
    ndarray
        (n, 3) coordinates in the camera-parallel system; a point in front of the camera has
        Z* < 0.

    Raises
    ------
    InputError
        A wrong shape, NaN/inf, or ``eo`` not an ExteriorOrientation.

    References
    ----------
    Chibunichev (2022), §1.4, eq. (1.4.10).

    Examples
    --------
    >>> camera_coordinates([[10.0, 0.0, 0.0]], ExteriorOrientation(0.0, 0.0, 1000.0))
    array([[   10.,     0., -1000.]])
    """
    _expect(eo, ExteriorOrientation, "eo")
    XYZ = as_points(XYZ, 3, "object points")
    return (XYZ - eo.center) @ eo.matrix


def project(XYZ, eo: ExteriorOrientation, io: InteriorOrientation, distortion: bool = True) -> np.ndarray:
    """Object → image by the collinearity equations (1.4.12): x = x₀ − f·X*/Z*, y = y₀ − f·Y*/Z*.

    With ``distortion`` and non-zero coefficients the ideal coordinates are turned into the
    coordinates a distorting camera measures (the inverse of the correction (1.2.3)).

    Parameters
    ----------
    XYZ : (n, 3) array
        Object points in metres.
    eo : ExteriorOrientation
    io : InteriorOrientation
    distortion : bool
        Add the camera's distortion to the ideal coordinates.

    Returns
    -------
    ndarray
        (n, 2) image coordinates in mm.

    Raises
    ------
    InputError
        A wrong shape, NaN/inf, or ``eo``/``io`` of the wrong type.
    PointBehindCameraError
        Points behind the camera (Z* ≥ 0); ``points`` lists them.

    References
    ----------
    Chibunichev (2022), §1.4, eqs. (1.4.10)–(1.4.12).

    Examples
    --------
    >>> project([[100.0, 50.0, 0.0]], ExteriorOrientation(0.0, 0.0, 1000.0), InteriorOrientation(100.0))
    array([[10.,  5.]])
    """
    _expect(io, InteriorOrientation, "io")
    star = camera_coordinates(XYZ, eo)
    if np.any(star[:, 2] >= 0):
        bad = np.flatnonzero(star[:, 2] >= 0).tolist()
        raise PointBehindCameraError(f"points {bad} are not in front of the camera (Z* >= 0)", points=bad)
    xy = np.column_stack([io.x0 - io.f * star[:, 0] / star[:, 2], io.y0 - io.f * star[:, 1] / star[:, 2]])
    if distortion and io.has_distortion:
        xy = apply_distortion(xy, io)
    return xy


def project_to_images(cameras, image, XYZ, io: InteriorOrientation, order: str = "kaw"):
    """Collinearity (1.4.12) for many images at once: point ``XYZ[k]`` in image ``image[k]``.

    Vectorised over observations — the projection used by the bundle method's simulations (§3.5).
    Points behind their image have z* ≥ 0 and are left for the caller to judge.

    Parameters
    ----------
    cameras : (n, 6) array or ExteriorOrientations
        Exterior orientations (X_S, Y_S, Z_S, ω, α, κ) in the rotation sequence ``order``
        (an :class:`~photolib.camera.ExteriorOrientations` carries its own order).
    image : (k,) array of int
        Image index of each observation, 0 ≤ image < n.
    XYZ : (k, 3) array
        Object point of each observation in metres.
    io : InteriorOrientation
        Only f, x₀, y₀ are used (ideal coordinates).
    order : {"kaw", "wak"}
        Rotation sequence of the angles of an (n, 6) array.

    Returns
    -------
    xy : (k, 2) ndarray
        Ideal image coordinates in mm.
    z_star : (k,) ndarray
        Z* of (1.4.10); negative in front of the camera.

    Raises
    ------
    InputError
        Wrong shapes, NaN/inf, image indices out of range, ``io`` of the wrong type.

    References
    ----------
    Chibunichev (2022), §1.4, eqs. (1.4.10)–(1.4.12); §3.5.

    Examples
    --------
    >>> xy, z = project_to_images([[0, 0, 1000, 0, 0, 0]], [0], [[100.0, 50.0, 0.0]], InteriorOrientation(100.0))
    >>> xy, z
    (array([[10.,  5.]]), array([-1000.]))
    """
    _expect(io, InteriorOrientation, "io")
    _order(order)
    if isinstance(cameras, ExteriorOrientations):
        cameras = cameras.with_order(order).vectors
    else:
        cameras = _numbers(cameras, "cameras")
        if cameras.ndim != 2 or cameras.shape[1] != 6:
            raise InputError(f"cameras: expected an (n, 6) array of (X_S, Y_S, Z_S, ω, α, κ), got {cameras.shape}")
        _warn_degrees(cameras[:, 3:], "camera angles omega, alpha, kappa")
    idx = _numbers(image, "image indices")
    if idx.ndim != 1 or np.any(idx != np.round(idx)):
        raise InputError(f"image: expected a (k,) array of whole image indices, got shape {idx.shape}")
    idx = idx.astype(np.intp)
    if idx.size and (idx.min() < 0 or idx.max() >= len(cameras)):
        raise InputError(f"image indices must lie in 0..{len(cameras) - 1}")
    XYZ = _numbers(XYZ, "object points XYZ")
    if XYZ.shape != (len(idx), 3):
        raise InputError(f"XYZ: expected shape ({len(idx)}, 3), one point per image index, got {XYZ.shape}")
    A = _rotation_matrix(cameras[:, 3], cameras[:, 4], cameras[:, 5], order)[idx]
    star = np.einsum("kji,kj->ki", A, XYZ - cameras[idx, :3])                     # Aᵀ(X − X_S)
    xy = np.column_stack([io.x0 - io.f * star[:, 0] / star[:, 2], io.y0 - io.f * star[:, 1] / star[:, 2]])
    return xy, star[:, 2]


def image_to_ground(xy, Z, eo: ExteriorOrientation, io: InteriorOrientation, distortion: bool = True) -> np.ndarray:
    """Image → object for points of known height Z, (1.4.4)–(1.4.7) ("monoplotting").

    (X′, Y′, Z′)ᵀ = A(x − x₀, y − y₀, −f)ᵀ (1.4.5), then X = X_S + (Z − Z_S)X′/Z′ and
    Y = Y_S + (Z − Z_S)Y′/Z′ (1.4.6).

    Parameters
    ----------
    xy : (n, 2) array
        Measured image coordinates in mm (corrected for distortion if ``distortion``).
    Z : float or (n,) array
        Height of each point in metres.
    eo : ExteriorOrientation
    io : InteriorOrientation
    distortion : bool
        Correct ``xy`` by (1.2.3) first.

    Returns
    -------
    ndarray
        (n, 3) object coordinates in metres.

    Raises
    ------
    InputError
        Wrong shapes, NaN/inf, ``eo``/``io`` of the wrong type.
    DegenerateGeometryError
        A ray parallel to the plane Z = const, or the plane behind the camera.

    References
    ----------
    Chibunichev (2022), §1.4, eqs. (1.4.4)–(1.4.7).

    Examples
    --------
    >>> image_to_ground([[10.0, 5.0]], 0.0, ExteriorOrientation(0.0, 0.0, 1000.0), InteriorOrientation(100.0))
    array([[100.,  50.,   0.]])
    """
    _expect(eo, ExteriorOrientation, "eo")
    _expect(io, InteriorOrientation, "io")
    xy = as_points(xy, 2, "image coordinates")
    if distortion and io.has_distortion:
        xy = correct_distortion(xy, io)
    Z = _numbers(Z, "heights Z")
    try:
        Z = np.broadcast_to(Z, (len(xy),))
    except ValueError:
        raise InputError(f"heights: expected a scalar or {len(xy)} values, got shape {np.shape(Z)}") from None
    r = np.column_stack([xy[:, 0] - io.x0, xy[:, 1] - io.y0, np.full(len(xy), -io.f)])
    ray = r @ eo.matrix.T                                   # (1.4.5)
    if np.any(np.abs(ray[:, 2]) < 1e-12 * np.linalg.norm(ray, axis=1)):
        raise DegenerateGeometryError("a ray is parallel to the horizontal plane Z = const")
    scale = (Z - eo.Zs) / ray[:, 2]                           # N of (1.4.4)
    if np.any(scale <= 0):
        raise DegenerateGeometryError("the plane Z lies behind the camera for some rays")
    return np.column_stack([eo.Xs + scale * ray[:, 0], eo.Ys + scale * ray[:, 1], Z])


def horizontal_image_scale(f, H):
    """Scale 1/m = f/H of a horizontal image of flat terrain (§1.5; the OCR prints 1/H).

    Parameters
    ----------
    f : float
        Focal length in mm.
    H : float
        Flying height above the terrain in m.

    Returns
    -------
    float
        The scale denominator m = H/f (dimensionless).

    Raises
    ------
    InputError
        f or H not positive, NaN/inf, a non-number.

    References
    ----------
    Chibunichev (2022), §1.5 (scale of a horizontal image).

    Examples
    --------
    >>> horizontal_image_scale(100.0, 1000.0)
    10000.0
    """
    f, H = _positive(f, "focal length f"), _positive(H, "flying height H")
    return H / (f / 1000.0)


def planimetric_error_from_height_error(x, y, f, dZ):
    """ΔX = x·ΔZ/f, ΔY = y·ΔZ/f, ΔR = √(ΔX² + ΔY²) of (1.6.1) for a horizontal image.

    The book gives magnitudes: the displacement points away from the nadir for a point
    assumed too low.

    Parameters
    ----------
    x, y : float or array
        Image coordinates in mm.
    f : float
        Focal length in mm.
    dZ : float or array
        Height error ΔZ (any length unit).

    Returns
    -------
    (ΔX, ΔY, ΔR)
        In the unit of ΔZ.

    Raises
    ------
    InputError
        f ≤ 0, NaN/inf, non-numbers, shapes that do not broadcast.

    References
    ----------
    Chibunichev (2022), §1.6, eq. (1.6.1).

    Examples
    --------
    >>> [float(v) for v in planimetric_error_from_height_error(30.0, 40.0, 100.0, 10.0)]
    [3.0, 4.0, 5.0]
    """
    f = _positive(f, "focal length f")
    x, y, dZ = _numbers(x, "x"), _numbers(y, "y"), _numbers(dZ, "ΔZ")
    try:
        np.broadcast_shapes(x.shape, y.shape, dZ.shape)
    except ValueError:
        raise InputError(f"x, y and ΔZ have shapes {x.shape}, {y.shape}, {dZ.shape} that do not broadcast") from None
    dX = x / f * dZ
    dY = y / f * dZ
    return dX, dY, np.hypot(dX, dY)


def _tilt_inputs(xy, A, f, f0, x0, y0, what):
    xy = as_points(xy, 2, what)
    A = _as_rotation(A, "A")
    if A.shape != (3, 3):
        raise InputError(f"A must be one 3×3 rotation matrix, got shape {A.shape}")
    return xy, A, _positive(f, "focal length f"), _positive(f0, "focal length f0"), \
        _scalar(x0, "x0"), _scalar(y0, "y0")


def tilted_to_horizontal(xy, A, f, f0, x0=0.0, y0=0.0) -> np.ndarray:
    """Tilted image → horizontal image from the same centre (1.7.5).

    x⁰ = −f⁰(a₁₁(x − x₀) + a₁₂(y − y₀) − a₁₃f)/(a₃₁(x − x₀) + a₃₂(y − y₀) − a₃₃f), likewise y⁰
    with the second row.

    Parameters
    ----------
    xy : (n, 2) array
        Coordinates on the tilted image in mm.
    A : (3, 3) array
        Rotation orienting the tilted camera relative to the horizontal one.
    f, f0 : float
        Focal lengths of the tilted and the horizontal image in mm.
    x0, y0 : float
        Principal point of the tilted image in mm.

    Returns
    -------
    ndarray
        (n, 2) coordinates x⁰, y⁰ on the horizontal image in mm.

    Raises
    ------
    InputError
        NaN/inf, wrong shapes, ``A`` not a rotation, f or f0 not positive.
    DegenerateGeometryError
        A ray of the tilted image does not reach the horizontal image plane.

    References
    ----------
    Chibunichev (2022), §1.7, eqs. (1.7.3)–(1.7.5).

    Examples
    --------
    >>> tilted_to_horizontal([[10.0, 5.0]], np.eye(3), 100.0, 150.0)
    array([[15. ,  7.5]])
    """
    xy, A, f, f0, x0, y0 = _tilt_inputs(xy, A, f, f0, x0, y0, "image coordinates")
    r = np.column_stack([xy[:, 0] - x0, xy[:, 1] - y0, np.full(len(xy), -float(f))])
    v = r @ A.T                                             # (1.7.3)
    if np.any(v[:, 2] >= 0):
        raise DegenerateGeometryError("a ray of the tilted image does not reach the horizontal image plane")
    return np.column_stack([-f0 * v[:, 0] / v[:, 2], -f0 * v[:, 1] / v[:, 2]])


def horizontal_to_tilted(xy0, A, f, f0, x0=0.0, y0=0.0) -> np.ndarray:
    """Horizontal image → tilted image from the same centre (1.7.10).

    x = x₀ − f(a₁₁x⁰ + a₂₁y⁰ − a₃₁f⁰)/(a₁₃x⁰ + a₂₃y⁰ − a₃₃f⁰), likewise y with the second column.

    Parameters
    ----------
    xy0 : (n, 2) array
        Coordinates on the horizontal image in mm.
    A : (3, 3) array
        Rotation orienting the tilted camera relative to the horizontal one.
    f, f0 : float
        Focal lengths of the tilted and the horizontal image in mm.
    x0, y0 : float
        Principal point of the tilted image in mm.

    Returns
    -------
    ndarray
        (n, 2) coordinates on the tilted image in mm.

    Raises
    ------
    InputError
        NaN/inf, wrong shapes, ``A`` not a rotation, f or f0 not positive.
    DegenerateGeometryError
        A ray of the horizontal image does not reach the tilted image plane.

    References
    ----------
    Chibunichev (2022), §1.7, eqs. (1.7.8)–(1.7.10).

    Examples
    --------
    >>> horizontal_to_tilted([[15.0, 7.5]], np.eye(3), 100.0, 150.0)
    array([[10.,  5.]])
    """
    xy0, A, f, f0, x0, y0 = _tilt_inputs(xy0, A, f, f0, x0, y0, "horizontal image coordinates")
    r0 = np.column_stack([xy0[:, 0], xy0[:, 1], np.full(len(xy0), -float(f0))])
    v = r0 @ A                                              # (1.7.8): Aᵀ r⁰
    if np.any(v[:, 2] >= 0):
        raise DegenerateGeometryError("a ray of the horizontal image does not reach the tilted image plane")
    return np.column_stack([x0 - f * v[:, 0] / v[:, 2], y0 - f * v[:, 1] / v[:, 2]])
