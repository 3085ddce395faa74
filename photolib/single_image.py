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

from .camera import ExteriorOrientation, InteriorOrientation, apply_distortion, as_points, correct_distortion
from .errors import DegenerateGeometryError, InputError
from .rotation import rotation_matrix


def _positive(value, name):
    """Validate a positive finite scalar (a focal length or a flying height)."""
    value = float(value)
    if not np.isfinite(value) or value <= 0:
        raise InputError(f"{name} must be positive and finite, got {value}")
    return value


def _rotation(A) -> np.ndarray:
    """Validate a finite 3×3 matrix."""
    A = np.asarray(A, dtype=float)
    if A.shape != (3, 3) or not np.all(np.isfinite(A)):
        raise InputError(f"A must be a finite 3×3 matrix, got shape {A.shape}")
    return A


def principal_to_nadir_distance(f, tilt):
    """on = f·tan α₀: distance in the image from the principal point o to the nadir point n (§1.1).

    ``tilt`` (radians) must satisfy |α₀| < π/2: at 90° the nadir point is at infinity.
    """
    f = _positive(f, "focal length f")
    tilt = np.asarray(tilt, dtype=float)
    if not np.all(np.isfinite(tilt)) or np.any(np.abs(tilt) >= np.pi / 2):
        raise InputError("the tilt α₀ must be finite and |α₀| < 90°")
    return f * np.tan(tilt)


def camera_coordinates(XYZ, eo: ExteriorOrientation) -> np.ndarray:
    """(X*, Y*, Z*) = Aᵀ(X − X_S, Y − Y_S, Z − Z_S) of (1.4.10), one row per point."""
    XYZ = as_points(XYZ, 3, "object points")
    return (XYZ - eo.center) @ eo.matrix


def project(XYZ, eo: ExteriorOrientation, io: InteriorOrientation, distortion: bool = True) -> np.ndarray:
    """Object → image by the collinearity equations (1.4.12): x = x₀ − f·X*/Z*, y = y₀ − f·Y*/Z*.

    With ``distortion`` and non-zero coefficients the ideal coordinates are turned into the
    coordinates a distorting camera measures (the inverse of the correction (1.2.3)).
    Points behind the camera (Z* ≥ 0) raise :class:`DegenerateGeometryError`.
    """
    star = camera_coordinates(XYZ, eo)
    if np.any(star[:, 2] >= 0):
        bad = np.flatnonzero(star[:, 2] >= 0).tolist()
        raise DegenerateGeometryError(f"points {bad} are not in front of the camera (Z* >= 0)")
    xy = np.column_stack([io.x0 - io.f * star[:, 0] / star[:, 2], io.y0 - io.f * star[:, 1] / star[:, 2]])
    if distortion and io.has_distortion:
        xy = apply_distortion(xy, io)
    return xy


def project_to_images(cameras, image, XYZ, io: InteriorOrientation, order: str = "kaw"):
    """Collinearity (1.4.12) for many images at once: point ``XYZ[k]`` in image ``image[k]``.

    ``cameras`` is an (n, 6) array of exterior orientations (X_S, Y_S, Z_S, ω, α, κ) in the
    rotation sequence ``order``. Returns the ideal image coordinates (k, 2) and z* (k,) of
    (1.4.10); points behind their image have z* ≥ 0 and are left for the caller to judge.
    Vectorised over observations — the projection used by the bundle method's simulations (§3.5).
    """
    cameras = np.asarray(cameras, dtype=float)
    image = np.asarray(image, dtype=np.intp)
    XYZ = np.asarray(XYZ, dtype=float)
    A = rotation_matrix(cameras[:, 3], cameras[:, 4], cameras[:, 5], order)[image]
    star = np.einsum("kji,kj->ki", A, XYZ - cameras[image, :3])                   # Aᵀ(X − X_S)
    xy = np.column_stack([io.x0 - io.f * star[:, 0] / star[:, 2], io.y0 - io.f * star[:, 1] / star[:, 2]])
    return xy, star[:, 2]


def image_to_ground(xy, Z, eo: ExteriorOrientation, io: InteriorOrientation, distortion: bool = True) -> np.ndarray:
    """Image → object for points of known height Z, (1.4.4)–(1.4.7) ("monoplotting").

    (X′, Y′, Z′)ᵀ = A(x − x₀, y − y₀, −f)ᵀ (1.4.5), then X = X_S + (Z − Z_S)X′/Z′ and
    Y = Y_S + (Z − Z_S)Y′/Z′ (1.4.6). ``Z`` is a scalar or one height per point. Returns (n, 3).
    """
    xy = as_points(xy, 2, "image coordinates")
    if distortion and io.has_distortion:
        xy = correct_distortion(xy, io)
    try:
        Z = np.broadcast_to(np.asarray(Z, dtype=float), (len(xy),))
    except ValueError:
        raise InputError(f"heights: expected a scalar or {len(xy)} values, got shape {np.shape(Z)}") from None
    if not np.all(np.isfinite(Z)):
        raise InputError("heights contain NaN or inf")
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

    ``f`` in mm and ``H`` in m; returns the scale denominator m = H/f (dimensionless).
    """
    f, H = _positive(f, "focal length f"), _positive(H, "flying height H")
    return H / (f / 1000.0)


def planimetric_error_from_height_error(x, y, f, dZ):
    """ΔX = x·ΔZ/f, ΔY = y·ΔZ/f, ΔR = √(ΔX² + ΔY²) of (1.6.1) for a horizontal image.

    The book gives magnitudes: the displacement points away from the nadir for a point
    assumed too low. Returns (ΔX, ΔY, ΔR) in the units of ΔZ.
    """
    f = _positive(f, "focal length f")
    x, y, dZ = (np.asarray(v, dtype=float) for v in (x, y, dZ))
    if not all(np.all(np.isfinite(v)) for v in (x, y, dZ)):
        raise InputError("x, y and ΔZ must be finite")
    dX = np.asarray(x, dtype=float) / f * dZ
    dY = np.asarray(y, dtype=float) / f * dZ
    return dX, dY, np.hypot(dX, dY)


def tilted_to_horizontal(xy, A, f, f0, x0=0.0, y0=0.0) -> np.ndarray:
    """Tilted image → horizontal image from the same centre (1.7.5).

    x⁰ = −f⁰(a₁₁(x − x₀) + a₁₂(y − y₀) − a₁₃f)/(a₃₁(x − x₀) + a₃₂(y − y₀) − a₃₃f), likewise y⁰
    with the second row. ``A`` orients the tilted camera relative to the horizontal one.
    """
    xy = as_points(xy, 2, "image coordinates")
    A, f, f0 = _rotation(A), _positive(f, "focal length f"), _positive(f0, "focal length f0")
    r = np.column_stack([xy[:, 0] - x0, xy[:, 1] - y0, np.full(len(xy), -float(f))])
    v = r @ A.T                                             # (1.7.3)
    if np.any(v[:, 2] >= 0):
        raise DegenerateGeometryError("a ray of the tilted image does not reach the horizontal image plane")
    return np.column_stack([-f0 * v[:, 0] / v[:, 2], -f0 * v[:, 1] / v[:, 2]])


def horizontal_to_tilted(xy0, A, f, f0, x0=0.0, y0=0.0) -> np.ndarray:
    """Horizontal image → tilted image from the same centre (1.7.10).

    x = x₀ − f(a₁₁x⁰ + a₂₁y⁰ − a₃₁f⁰)/(a₁₃x⁰ + a₂₃y⁰ − a₃₃f⁰), likewise y with the second column.
    """
    xy0 = as_points(xy0, 2, "image coordinates")
    A, f, f0 = _rotation(A), _positive(f, "focal length f"), _positive(f0, "focal length f0")
    r0 = np.column_stack([xy0[:, 0], xy0[:, 1], np.full(len(xy0), -float(f0))])
    v = r0 @ A                                              # (1.7.8): Aᵀ r⁰
    if np.any(v[:, 2] >= 0):
        raise DegenerateGeometryError("a ray of the horizontal image does not reach the tilted image plane")
    return np.column_stack([x0 - f * v[:, 0] / v[:, 2], y0 - f * v[:, 1] / v[:, 2]])
