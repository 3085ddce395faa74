"""Rotation matrices of the exterior orientation — Chapter 1, §1.3.

The book defines the direction-cosine matrix **A** (1.3.1): it maps vectors of the camera
system *Sxyz* into the object system *OXYZ*; object → camera uses its transpose, Aᵀ. Two sequences of
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

import warnings

import numpy as np

from .errors import DegenerateGeometryError, DegreesWarning, InputError

__all__ = ["ORDERS", "DEFAULT_ORDER", "check_order", "rot_x", "rot_y", "rot_z", "rotation_matrix",
           "rotation_angles", "quaternion_matrix", "quaternion_scale", "matrix_to_quaternion",
           "quaternion_to_angles", "is_rotation"]

ORDERS = ("kaw", "wak")
"""Supported rotation sequences: ``"kaw"`` = (1.3.4)/(1.3.5), ``"wak"`` = (1.3.2)."""

DEFAULT_ORDER = "kaw"

_TWO_PI = 2 * np.pi
_ROTATION_TOL = 1e-6
"""How far AᵀA may deviate from E (largest element) and det A from +1 for A to count as a rotation."""


# --- input validation shared by the library (camera.as_points builds on these) -------------------
def _numbers(values, what: str) -> np.ndarray:
    """``values`` as a float array of finite numbers, or :class:`InputError` naming ``what``.

    Strings, objects that are not numbers, NaN and inf are refused with a message that names
    the argument (instead of numpy's "could not convert string to float").
    """
    if isinstance(values, (str, bytes)):
        raise InputError(f"{what}: expected numbers, got the string {values!r}")
    try:
        raw = np.asarray(values)
        if raw.dtype.kind in "USV":
            raise InputError(f"{what}: expected numbers, got text {_shorten(values)}")
        arr = raw.astype(float, copy=False) if raw.dtype.kind != "O" else np.asarray(values, dtype=float)
    except InputError:
        raise
    except (TypeError, ValueError):
        raise InputError(f"{what}: expected numbers, got {_shorten(values)}") from None
    if not np.all(np.isfinite(arr)):
        raise InputError(f"{what} contain(s) NaN or inf")
    return arr


def _shorten(value) -> str:
    text = repr(value)
    return text if len(text) <= 60 else text[:57] + "..."


def _warn_degrees(angles, what: str = "angles", stacklevel: int = 3):
    """Warn with :class:`DegreesWarning` if any angle exceeds 2π in magnitude (degrees passed?)."""
    if np.any(np.abs(angles) > _TWO_PI):
        warnings.warn(f"{what}: an angle of magnitude {float(np.max(np.abs(angles))):.4g} > 2π rad; "
                      "angles are in radians — were degrees passed?", DegreesWarning, stacklevel=stacklevel)


def _as_rotation(A, what: str = "A", tol: float = _ROTATION_TOL) -> np.ndarray:
    """A finite (…, 3, 3) array of proper rotations (AᵀA = E, det A = +1, §1.3) or :class:`InputError`."""
    A = _numbers(A, what)
    if A.ndim < 2 or A.shape[-2:] != (3, 3):
        raise InputError(f"{what}: a rotation matrix must be 3×3, got shape {A.shape}")
    gram = np.swapaxes(A, -1, -2) @ A
    off = float(np.max(np.abs(gram - np.eye(3)))) if A.size else 0.0
    det = np.linalg.det(A)
    if off > tol or np.any(np.abs(det - 1.0) > tol):
        raise InputError(f"{what} is not a rotation matrix: AᵀA differs from E by {off:.3g} and "
                         f"det A = {float(np.ravel(det)[np.argmax(np.abs(np.ravel(det) - 1))]):.6g} "
                         "(a rotation needs AᵀA = E and det A = +1, §1.3)")
    return A


def _order(order) -> str:
    if not isinstance(order, str) or order not in ORDERS:
        raise InputError(f"unknown rotation order {order!r}; use 'kaw' (1.3.4)/(1.3.5) or 'wak' (1.3.2)")
    return order


def check_order(order: str) -> str:
    """Return ``order`` if it names a supported rotation sequence.

    Parameters
    ----------
    order : {"kaw", "wak"}
        ``"kaw"``: A = A_κ A_α A_ω (1.3.4)/(1.3.5); ``"wak"``: A = A_ω A_α A_κ (1.3.2).

    Returns
    -------
    str
        ``order`` unchanged.

    Raises
    ------
    InputError
        Any other value.

    References
    ----------
    Chibunichev (2022), §1.3, eqs. (1.3.2), (1.3.4)–(1.3.5).

    Examples
    --------
    >>> check_order("wak")
    'wak'
    """
    return _order(order)


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


def _elementary_checked(angle, axis: int, what: str) -> np.ndarray:
    angle = _numbers(angle, what)
    _warn_degrees(angle, what, stacklevel=4)
    return _elementary(angle, axis)


def rot_x(omega) -> np.ndarray:
    """A_ω: rotation by ω about the X axis (counter-clockwise, right-handed).

    Parameters
    ----------
    omega : float or array
        Angle ω in radians; an array gives a stack of matrices of shape ``shape + (3, 3)``.

    Returns
    -------
    ndarray
        [[1, 0, 0], [0, cos ω, −sin ω], [0, sin ω, cos ω]].

    Raises
    ------
    InputError
        NaN, inf or something that is not a number.

    Warns
    -----
    DegreesWarning
        |ω| > 2π (degrees passed?).

    References
    ----------
    Chibunichev (2022), §1.3, the elementary matrices before eq. (1.3.2).

    Examples
    --------
    >>> rot_x(np.pi / 2).round(12) + 0.0
    array([[ 1.,  0.,  0.],
           [ 0.,  0., -1.],
           [ 0.,  1.,  0.]])
    """
    return _elementary_checked(omega, 0, "omega")


def rot_y(alpha) -> np.ndarray:
    """A_α: rotation by α about the Y axis (counter-clockwise, right-handed).

    Parameters
    ----------
    alpha : float or array
        Angle α in radians (φ in the Western literature).

    Returns
    -------
    ndarray
        [[cos α, 0, sin α], [0, 1, 0], [−sin α, 0, cos α]].

    Raises
    ------
    InputError
        NaN, inf or something that is not a number.

    References
    ----------
    Chibunichev (2022), §1.3, the elementary matrices before eq. (1.3.2).

    Examples
    --------
    >>> rot_y(np.pi / 2).round(12) + 0.0
    array([[ 0.,  0.,  1.],
           [ 0.,  1.,  0.],
           [-1.,  0.,  0.]])
    """
    return _elementary_checked(alpha, 1, "alpha")


def rot_z(kappa) -> np.ndarray:
    """A_κ: rotation by κ about the Z axis (counter-clockwise, right-handed).

    Parameters
    ----------
    kappa : float or array
        Angle κ in radians.

    Returns
    -------
    ndarray
        [[cos κ, −sin κ, 0], [sin κ, cos κ, 0], [0, 0, 1]].

    Raises
    ------
    InputError
        NaN, inf or something that is not a number.

    References
    ----------
    Chibunichev (2022), §1.3, the elementary matrices before eq. (1.3.2).

    Examples
    --------
    >>> rot_z(np.pi / 2).round(12) + 0.0
    array([[ 0., -1.,  0.],
           [ 1.,  0.,  0.],
           [ 0.,  0.,  1.]])
    """
    return _elementary_checked(kappa, 2, "kappa")


def _rotation_matrix(omega, alpha, kappa, order: str = DEFAULT_ORDER) -> np.ndarray:
    """:func:`rotation_matrix` without the input checks (for inputs already validated)."""
    a_w, a_a, a_k = _elementary(omega, 0), _elementary(alpha, 1), _elementary(kappa, 2)
    if order == "kaw":
        return a_k @ a_a @ a_w
    return a_w @ a_a @ a_k


def rotation_matrix(omega, alpha, kappa, order: str = DEFAULT_ORDER) -> np.ndarray:
    """Direction-cosine matrix A (camera → object) from the angles ω, α, κ.

    Parameters
    ----------
    omega, alpha, kappa : float or array
        The angles in radians; arrays of one shape (or broadcastable) give a stack of matrices
        of shape ``shape + (3, 3)``.
    order : {"kaw", "wak"}
        ``"kaw"``: A = A_κ A_α A_ω, (1.3.4)/(1.3.5) — every numeric example of the book;
        ``"wak"``: A = A_ω A_α A_κ, (1.3.2).

    Returns
    -------
    ndarray
        A, shape (3, 3) or ``shape + (3, 3)``.

    Raises
    ------
    InputError
        NaN, inf, a string, angles that do not broadcast, or an unknown ``order``.

    Warns
    -----
    DegreesWarning
        An angle of magnitude above 2π (were degrees passed?).

    References
    ----------
    Chibunichev (2022), §1.3, eqs. (1.3.1), (1.3.2), (1.3.4)–(1.3.5).

    Examples
    --------
    >>> A = rotation_matrix(0.0, 0.0, np.pi / 2)
    >>> A.round(12) + 0.0
    array([[ 0., -1.,  0.],
           [ 1.,  0.,  0.],
           [ 0.,  0.,  1.]])
    """
    _order(order)
    w, a, k = _numbers(omega, "omega"), _numbers(alpha, "alpha"), _numbers(kappa, "kappa")
    try:
        w, a, k = np.broadcast_arrays(w, a, k)
    except ValueError:
        raise InputError(f"omega, alpha, kappa have shapes {np.shape(w)}, {np.shape(a)}, {np.shape(k)} "
                         "that do not broadcast") from None
    _warn_degrees(np.stack([w, a, k]), "omega, alpha, kappa")
    return _rotation_matrix(w, a, k, order)


def _check_matrix(A) -> np.ndarray:
    A = _numbers(A, "the rotation matrix")
    if A.ndim < 2 or A.shape[-2:] != (3, 3):
        raise InputError(f"a rotation matrix must be 3×3, got shape {A.shape}")
    return A


def rotation_angles(A, order: str = DEFAULT_ORDER, singular: str = "raise"):
    """Angles (ω, α, κ) of a rotation matrix: (1.3.6) for ``"kaw"``, (1.3.3) for ``"wak"``.

    The book writes ω and κ with arctan of a ratio and α with arcsin; here atan2 keeps every
    quadrant and α is taken as atan2(sin α, |cos α|) so that it stays accurate near ±90°;
    κ is read off the rotation left after removing ω and α, so that the angles reproduce the
    matrix to rounding error even within 1e-12 rad of the singularity. α is returned in
    [−90°, 90°], ω and κ in (−180°, 180°].

    Parameters
    ----------
    A : (3, 3) or (..., 3, 3) array
        A proper rotation (AᵀA = E, det A = +1 to 1e-6), camera → object.
    order : {"kaw", "wak"}
        The sequence the angles belong to.
    singular : {"raise", "kappa-zero"}
        At α = ±90° (gimbal lock) only ω ∓ κ (kaw) or ω ± κ (wak) is defined: ``"raise"``
        raises, ``"kappa-zero"`` takes the branch κ = 0 and lets ω carry the whole rotation.

    Returns
    -------
    (omega, alpha, kappa)
        Floats for one matrix, arrays for a stack; radians.

    Raises
    ------
    InputError
        NaN/inf, a wrong shape, a matrix that is not a rotation, a bad option.
    DegenerateGeometryError
        α = ±90° with ``singular="raise"``.

    References
    ----------
    Chibunichev (2022), §1.3, eqs. (1.3.3), (1.3.6).

    Examples
    --------
    >>> A = rotation_matrix(0.1, 0.2, 0.3, "kaw")
    >>> [round(v, 12) for v in rotation_angles(A, "kaw")]
    [0.1, 0.2, 0.3]
    """
    if singular not in ("raise", "kappa-zero"):
        raise InputError(f"singular must be 'raise' or 'kappa-zero', got {singular!r}")
    _order(order)
    A = _as_rotation(A)
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
    omega = np.arctan2(sin_w_part, cos_w_part)
    # κ from what is left of A once the ω and α rotations are removed: A_κ = A (A_α A_ω)ᵀ (kaw)
    # or A_κ = (A_ω A_α)ᵀ A (wak). Reading κ off a₁₁, a₂₁ (or a₁₁, −a₁₂) directly would take
    # it from elements of size cos α, which near α = ±90° lose their relative accuracy; the
    # angles then no longer reproduce the matrix (error ≈ 1e-16 / cos α).
    if order == "kaw":
        rest = A @ np.swapaxes(_elementary(alpha, 1) @ _elementary(omega, 0), -1, -2)
    else:
        rest = np.swapaxes(_elementary(omega, 0) @ _elementary(alpha, 1), -1, -2) @ A
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

    Parameters
    ----------
    a, b, c, d : float or array
        Vector part (a, b, c) and scalar part d (scipy's ``as_quat()`` order [x, y, z, w]).

    Returns
    -------
    ndarray
        The 3×3 matrix (1.3.7), or a stack for array input.

    Raises
    ------
    InputError
        NaN, inf or something that is not a number.

    References
    ----------
    Chibunichev (2022), §1.3, eq. (1.3.7).

    Examples
    --------
    >>> quaternion_matrix(0, 0, 0, 1)
    array([[1., 0., 0.],
           [0., 1., 0.],
           [0., 0., 1.]])
    """
    a, b, c, d = (_numbers(v, name) for v, name in zip((a, b, c, d), "abcd"))
    try:
        a, b, c, d = np.broadcast_arrays(a, b, c, d)
    except ValueError:
        raise InputError("the quaternion components a, b, c, d do not broadcast") from None
    return np.stack([
        np.stack([d * d + a * a - b * b - c * c, 2 * (a * b - c * d), 2 * (a * c + b * d)], -1),
        np.stack([2 * (a * b + c * d), d * d - a * a + b * b - c * c, 2 * (b * c - a * d)], -1),
        np.stack([2 * (a * c - b * d), 2 * (b * c + a * d), d * d - a * a - b * b + c * c], -1),
    ], -2)


def quaternion_scale(a, b, c, d):
    """The implicit scale m = a² + b² + c² + d² of the matrix (1.3.7).

    Parameters
    ----------
    a, b, c, d : float or array
        The quaternion's components.

    Returns
    -------
    float or ndarray
        m; AᵀA = m²E for the matrix A of (1.3.7).

    Raises
    ------
    InputError
        NaN, inf or something that is not a number.

    References
    ----------
    Chibunichev (2022), §1.3, eq. (1.3.7).

    Examples
    --------
    >>> quaternion_scale(1, 2, 2, 0)
    9.0
    """
    a, b, c, d = (_numbers(v, name) for v, name in zip((a, b, c, d), "abcd"))
    m = a * a + b * b + c * c + d * d
    return float(m) if np.ndim(m) == 0 else m


def matrix_to_quaternion(A) -> np.ndarray:
    """Unit quaternion (a, b, c, d), d ≥ 0, whose matrix (1.3.7) is the rotation ``A``.

    Uses the largest of the four diagonal combinations (Shepperd's method) so that no
    division is by a small number.

    Parameters
    ----------
    A : (3, 3) array
        A proper rotation matrix (AᵀA = E, det A = +1).

    Returns
    -------
    ndarray
        (a, b, c, d) with a² + b² + c² + d² = 1 and d ≥ 0.

    Raises
    ------
    InputError
        NaN/inf, not one 3×3 matrix, or not a rotation.

    References
    ----------
    Chibunichev (2022), §1.3, eq. (1.3.7).

    Examples
    --------
    >>> matrix_to_quaternion(rotation_matrix(0.0, 0.0, np.pi / 2)).round(6)
    array([0.      , 0.      , 0.707107, 0.707107])
    """
    A = _as_rotation(A)
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

    Parameters
    ----------
    a, b, c, d : float
        The quaternion (vector part a, b, c; scalar part d); any non-zero scale.
    singular : {"raise", "kappa-zero"}
        Behaviour at α = ±90°, as in :func:`rotation_angles`.

    Returns
    -------
    (omega, alpha, kappa)
        Radians, in the sequence ``"kaw"``.

    Raises
    ------
    InputError
        NaN/inf, a zero quaternion, something that is not a number.
    DegenerateGeometryError
        α = ±90° with ``singular="raise"``.

    References
    ----------
    Chibunichev (2022), §1.3, eqs. (1.3.5), (1.3.7) and the relations after them.

    Examples
    --------
    >>> [round(v, 12) for v in quaternion_to_angles(0.0, 0.0, np.sin(0.15), np.cos(0.15))]
    [0.0, 0.0, 0.3]
    """
    q = np.array([_numbers(v, name) for v, name in zip((a, b, c, d), "abcd")], dtype=float)
    if q.shape != (4,):
        raise InputError(f"a quaternion is four numbers a, b, c, d, got shape {q.shape}")
    norm = np.linalg.norm(q)
    if norm == 0:
        raise InputError("the quaternion must be non-zero")
    a, b, c, d = q / norm
    sin_a = -2 * (a * c - b * d)
    cos_k_cos_a, sin_k_cos_a = d * d + a * a - b * b - c * c, 2 * (a * b + c * d)
    sin_w_cos_a, cos_w_cos_a = 2 * (b * c + a * d), d * d - a * a - b * b + c * c
    if np.hypot(sin_w_cos_a, cos_w_cos_a) < 1e-12:
        return rotation_angles(quaternion_matrix(a, b, c, d), "kaw", singular=singular)
    alpha = np.arctan2(sin_a, np.hypot(sin_w_cos_a, cos_w_cos_a))
    return float(np.arctan2(sin_w_cos_a, cos_w_cos_a)), float(alpha), float(np.arctan2(sin_k_cos_a, cos_k_cos_a))


def is_rotation(A, tol: float = 1e-9) -> bool:
    """True if AᵀA = E and det A = +1 within ``tol`` (the conditions after (1.3.1)).

    Parameters
    ----------
    A : (3, 3) array
        Any finite 3×3 matrix.
    tol : float
        Tolerance on the elements of AᵀA − E and on det A − 1.

    Returns
    -------
    bool

    Raises
    ------
    InputError
        NaN/inf, something that is not a number, or not 3×3.

    References
    ----------
    Chibunichev (2022), §1.3, the orthogonality conditions after eq. (1.3.1).

    Examples
    --------
    >>> is_rotation(rotation_matrix(0.1, 0.2, 0.3)), is_rotation(np.diag([1.0, 1.0, -1.0]))
    (True, False)
    """
    A = _check_matrix(A)
    if A.shape != (3, 3):
        raise InputError(f"is_rotation takes one 3×3 matrix, got shape {A.shape}")
    return bool(np.allclose(A.T @ A, np.eye(3), atol=tol) and abs(np.linalg.det(A) - 1) < tol)
