"""Rotation matrices of the exterior orientation — Chapter 1, §1.3.

The book defines the direction-cosine matrix **A** (1.3.1): it maps vectors of the camera
system *Sxyz* into the object system *OXYZ*; object → camera uses **A**ᵀ. Two sequences of
elementary rotations are given and both are used:

* ``"wak"`` — ω–α–κ, ``A = A_ω A_α A_κ`` (1.3.2), angles back by (1.3.3). The text calls it the
  most widely used system and draws the angles for it.
* ``"kaw"`` — κ–α–ω, ``A = A_κ A_α A_ω`` (1.3.4)/(1.3.5), angles back by (1.3.6). **Every
  numeric example of Chapters 1, 2 and 4 was computed with this one**, so it is the default.

The elementary matrices are the right-handed (counter-clockwise) rotations about X, Y and Z
(the book's A_ω, A_α, A_κ). α is called φ in the Western literature.

Quaternions (1.3.7) use the vector part (a, b, c) and the scalar part d, the order of
``scipy.spatial.transform.Rotation.as_quat`` ([x, y, z, w]). The matrix of (1.3.7) carries the
scale m = a² + b² + c² + d²: AᵀA = m²E, so a unit quaternion gives a rotation.

All angles are in radians.
"""

from __future__ import annotations

import numpy as np

from .errors import DegenerateGeometryError, InputError

ORDERS = ("kaw", "wak")
"""Supported rotation sequences: ``"kaw"`` = (1.3.4)/(1.3.5), ``"wak"`` = (1.3.2)."""

DEFAULT_ORDER = "kaw"


def check_order(order: str) -> str:
    """Return ``order`` if it names a supported sequence, else raise :class:`InputError`."""
    if order not in ORDERS:
        raise InputError(f"unknown rotation order {order!r}; use 'kaw' (1.3.4)/(1.3.5) or 'wak' (1.3.2)")
    return order


def _elementary(angle, axis: int) -> np.ndarray:
    angle = np.asarray(angle, dtype=float)
    c, s = np.cos(angle), np.sin(angle)
    out = np.zeros(angle.shape + (3, 3))
    i, j = [(1, 2), (2, 0), (0, 1)][axis]
    out[..., axis, axis] = 1.0
    out[..., i, i] = c
    out[..., j, j] = c
    out[..., i, j] = -s
    out[..., j, i] = s
    return out


def rot_x(omega) -> np.ndarray:
    """A_ω: rotation by ω about the X axis (§1.3, the elementary matrices before (1.3.2))."""
    return _elementary(omega, 0)


def rot_y(alpha) -> np.ndarray:
    """A_α: rotation by α about the Y axis."""
    return _elementary(alpha, 1)


def rot_z(kappa) -> np.ndarray:
    """A_κ: rotation by κ about the Z axis."""
    return _elementary(kappa, 2)


def rotation_matrix(omega, alpha, kappa, order: str = DEFAULT_ORDER) -> np.ndarray:
    """Direction-cosine matrix A (camera → object) from the angles ω, α, κ.

    ``order="kaw"``: A = A_κ A_α A_ω, (1.3.4)/(1.3.5); ``order="wak"``: A = A_ω A_α A_κ, (1.3.2).
    Angles may be arrays of one shape; the result then has shape ``shape + (3, 3)``.
    """
    check_order(order)
    a_w, a_a, a_k = rot_x(omega), rot_y(alpha), rot_z(kappa)
    if order == "kaw":
        return a_k @ a_a @ a_w
    return a_w @ a_a @ a_k


def _check_matrix(A) -> np.ndarray:
    A = np.asarray(A, dtype=float)
    if A.shape[-2:] != (3, 3):
        raise InputError(f"a rotation matrix must be 3×3, got shape {A.shape}")
    if not np.all(np.isfinite(A)):
        raise InputError("the rotation matrix contains NaN or inf")
    return A


def rotation_angles(A, order: str = DEFAULT_ORDER, singular: str = "raise"):
    """Angles (ω, α, κ) of a rotation matrix: (1.3.6) for ``"kaw"``, (1.3.3) for ``"wak"``.

    The book writes ω and κ with arctan of a ratio and α with arcsin; here atan2 keeps every
    quadrant and α is taken as atan2(sin α, |cos α|) so that it stays accurate near ±90°;
    κ is read off the rotation left after removing ω and α, so that the angles reproduce the
    matrix to rounding error even within 1e-12 rad of the singularity. α is returned in
    [−90°, 90°], ω and κ in (−180°, 180°].

    At α = ±90° (cos α = 0, gimbal lock) only ω ∓ κ (kaw) or ω ± κ (wak) is defined. With
    ``singular="raise"`` (default) a :class:`DegenerateGeometryError` is raised; with
    ``singular="kappa-zero"`` the documented branch κ = 0 is taken and ω carries the whole
    rotation about the remaining axis.
    """
    check_order(order)
    A = _check_matrix(A)
    if order == "kaw":
        sin_a, cos_w_part, sin_w_part = -A[..., 2, 0], A[..., 2, 2], A[..., 2, 1]
    else:
        sin_a, cos_w_part, sin_w_part = A[..., 0, 2], A[..., 2, 2], -A[..., 1, 2]
    cos_a = np.hypot(cos_w_part, sin_w_part)
    alpha = np.arctan2(sin_a, cos_a)
    gimbal = cos_a < 1e-12
    if np.any(gimbal):
        if singular == "raise":
            raise DegenerateGeometryError(
                "alpha = ±90°: omega and kappa are not separable (gimbal lock, §1.3); "
                "pass singular='kappa-zero' to take the branch kappa = 0")
        if singular != "kappa-zero":
            raise InputError("singular must be 'raise' or 'kappa-zero'")
    omega = np.arctan2(sin_w_part, cos_w_part)
    # κ from what is left of A once the ω and α rotations are removed: A_κ = A (A_α A_ω)ᵀ (kaw)
    # or A_κ = (A_ω A_α)ᵀ A (wak). Reading κ off a₁₁, a₂₁ (or a₁₁, −a₁₂) directly would take
    # it from elements of size cos α, which near α = ±90° lose their relative accuracy; the
    # angles then no longer reproduce the matrix (error ≈ 1e-16 / cos α).
    if order == "kaw":
        rest = A @ np.swapaxes(rot_y(alpha) @ rot_x(omega), -1, -2)
    else:
        rest = np.swapaxes(rot_x(omega) @ rot_y(alpha), -1, -2) @ A
    kappa = np.arctan2(rest[..., 1, 0], rest[..., 0, 0])
    if np.any(gimbal):
        sign = np.sign(sin_a)
        if order == "kaw":   # A = A_κ A_±90 A_ω with κ = 0: a12 = ±sin ω, a22 = cos ω
            omega_g = np.arctan2(sign * A[..., 0, 1], A[..., 1, 1])
        else:                # A = A_ω A_±90 with κ = 0: a21 = ±sin ω, a22 = cos ω
            omega_g = np.arctan2(sign * A[..., 1, 0], A[..., 1, 1])
        omega = np.where(gimbal, omega_g, omega)
        kappa = np.where(gimbal, 0.0, kappa)
    if np.ndim(omega) == 0:
        return float(omega), float(alpha), float(kappa)
    return omega, alpha, kappa


def quaternion_matrix(a, b, c, d) -> np.ndarray:
    """Matrix (1.3.7) of the quaternion with vector part (a, b, c) and scalar part d.

    It is m·R with m = a² + b² + c² + d² and R a rotation; AᵀA = m²E. Use a unit quaternion
    (m = 1) for a rotation matrix.
    """
    a, b, c, d = (np.asarray(v, dtype=float) for v in (a, b, c, d))
    return np.stack([
        np.stack([d * d + a * a - b * b - c * c, 2 * (a * b - c * d), 2 * (a * c + b * d)], -1),
        np.stack([2 * (a * b + c * d), d * d - a * a + b * b - c * c, 2 * (b * c - a * d)], -1),
        np.stack([2 * (a * c - b * d), 2 * (b * c + a * d), d * d - a * a - b * b + c * c], -1),
    ], -2)


def quaternion_scale(a, b, c, d):
    """The implicit scale m = a² + b² + c² + d² of (1.3.7)."""
    return a * a + b * b + c * c + d * d


def matrix_to_quaternion(A) -> np.ndarray:
    """Unit quaternion (a, b, c, d), d ≥ 0, whose matrix (1.3.7) is the rotation ``A``.

    Uses the largest of the four diagonal combinations (Shepperd's method) so that no
    division is by a small number.
    """
    A = _check_matrix(A)
    if A.ndim != 2:
        raise InputError("matrix_to_quaternion takes one 3×3 matrix")
    trace = np.trace(A)
    candidates = [trace, A[0, 0], A[1, 1], A[2, 2]]
    k = int(np.argmax(candidates))
    if k == 0:
        d = 0.5 * np.sqrt(1.0 + trace)
        a, b, c = (A[2, 1] - A[1, 2]) / (4 * d), (A[0, 2] - A[2, 0]) / (4 * d), (A[1, 0] - A[0, 1]) / (4 * d)
    elif k == 1:
        a = 0.5 * np.sqrt(1.0 + A[0, 0] - A[1, 1] - A[2, 2])
        b, c, d = (A[0, 1] + A[1, 0]) / (4 * a), (A[0, 2] + A[2, 0]) / (4 * a), (A[2, 1] - A[1, 2]) / (4 * a)
    elif k == 2:
        b = 0.5 * np.sqrt(1.0 - A[0, 0] + A[1, 1] - A[2, 2])
        a, c, d = (A[0, 1] + A[1, 0]) / (4 * b), (A[1, 2] + A[2, 1]) / (4 * b), (A[0, 2] - A[2, 0]) / (4 * b)
    else:
        c = 0.5 * np.sqrt(1.0 - A[0, 0] - A[1, 1] + A[2, 2])
        a, b, d = (A[0, 2] + A[2, 0]) / (4 * c), (A[1, 2] + A[2, 1]) / (4 * c), (A[1, 0] - A[0, 1]) / (4 * c)
    q = np.array([a, b, c, d])
    q /= np.linalg.norm(q)
    return -q if q[3] < 0 else q


def quaternion_to_angles(a, b, c, d, singular: str = "raise"):
    """Angles (ω, α, κ) of the κ–α–ω system (1.3.5) from a quaternion.

    Implements the relations the book obtains by comparing (1.3.7) with (1.3.5):
    −sin α = 2(ac − bd), cos κ cos α = d² + a² − b² − c², sin κ cos α = 2(ab + cd),
    cos α sin ω = 2(bc + ad), cos α cos ω = d² − a² − b² + c². The quaternion is normalised
    first, so its scale m does not matter.
    """
    q = np.array([a, b, c, d], dtype=float)
    norm = np.linalg.norm(q)
    if not np.isfinite(norm) or norm == 0:
        raise InputError("the quaternion must be finite and non-zero")
    a, b, c, d = q / norm
    sin_a = -2 * (a * c - b * d)
    cos_k_cos_a, sin_k_cos_a = d * d + a * a - b * b - c * c, 2 * (a * b + c * d)
    sin_w_cos_a, cos_w_cos_a = 2 * (b * c + a * d), d * d - a * a - b * b + c * c
    if np.hypot(sin_w_cos_a, cos_w_cos_a) < 1e-12:
        return rotation_angles(quaternion_matrix(a, b, c, d), "kaw", singular=singular)
    alpha = np.arctan2(sin_a, np.hypot(sin_w_cos_a, cos_w_cos_a))
    return float(np.arctan2(sin_w_cos_a, cos_w_cos_a)), float(alpha), float(np.arctan2(sin_k_cos_a, cos_k_cos_a))


def is_rotation(A, tol: float = 1e-9) -> bool:
    """True if AᵀA = E and det A = +1 within ``tol`` (the conditions after (1.3.1))."""
    A = _check_matrix(A)
    return bool(np.allclose(A.T @ A, np.eye(3), atol=tol) and abs(np.linalg.det(A) - 1) < tol)
