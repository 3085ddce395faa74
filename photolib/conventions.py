"""Conversions between rotation, camera and distortion conventions — Chapter 1, §1.2–§1.3.

The book (Chibunichev, §1.3) describes the attitude of a camera by the direction-cosine matrix
**A** (1.3.1), which maps camera axes to object axes, ``(X − X_S) ∝ A (x − x₀, y − y₀, −f)``, and
builds it from three angles in one of two sequences. Other texts and software use other
conventions for the same physical attitude. This module converts, exactly, between:

=================  ============================================================================
``"kaw"``          book κ–α–ω, A = A_κ A_α A_ω, (1.3.4)/(1.3.5), angles by (1.3.6) — the
                   sequence of every numeric example in the book
``"wak"``          book ω–α–κ, A = A_ω A_α A_κ, (1.3.2), angles by (1.3.3)
``"hanzl"``        V. Hanzl, *Fotogrammetrie, Modul 01*, §2.2: R = R_ω R_φ R_κ with the same
                   elementary matrices; X = R x (image → object). R is the book's ω–α–κ **A**
                   itself, with φ ≡ α.
``"western"``      Wolf/ASPRS ω–φ–κ: M = M_κ M_φ M_ω of *passive* elementary rotations maps
                   object → image, x ∝ M (X − X_L). M = Aᵀ of the book's ω–α–κ, with φ ≡ α.
OpenCV (R, t)      R maps object → OpenCV camera axes (x right, y down, z forward, the camera
                   looks along +z), t = −R S. The book's camera looks along −z with y up, so
                   R = diag(1, −1, −1) Aᵀ; the image point (x, y) in mm is (u, v) = (x, −y)
                   with the intrinsic matrix K = [[f, 0, x₀], [0, f, −y₀], [0, 0, 1]].
quaternions        (1.3.7) with vector part (a, b, c) and scalar d = scipy's ``as_quat()``
                   order [x, y, z, w].
=================  ============================================================================

Distortion. The book's model (1.2.2) is Brown's: corrections d_x, d_y **added to measured**
coordinates (measured → ideal), in mm, about (x₀, y₀). OpenCV's model goes the other way
(ideal normalised coordinates → distorted), is written in the y-down OpenCV frame and names the
decentering coefficients the other way round. The two models are inverses of each other, so no
exact coefficient mapping exists. To first order (derived with sympy in the tests and in the
Conventions appendix):

    k1_cv = −k1·f²,  k2_cv = −k2·f⁴,  k3_cv = −k3·f⁶,  p1_cv = +f·p2,  p2_cv = −f·p1

(the signs of the radial terms flip because one model corrects and the other distorts; the p's
swap because OpenCV names them the other way round, and one of them changes sign because the
OpenCV y axis points down). :func:`brown_to_opencv` and :func:`opencv_to_brown` fit the other
model's coefficients by linear least squares over a grid covering the image format and report
the largest residual in μm, so the user knows what the conversion costs.

All angles are radians; image coordinates, f and K in mm (use :func:`camera_matrix_pixels` for
a K in pixels); object coordinates in m.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from scipy.spatial.transform import Rotation

from . import lsq
from .camera import ExteriorOrientation, InteriorOrientation, _expect, _scalar, as_points, correct_distortion
from .errors import InputError
from .rotation import (DEFAULT_ORDER, _as_rotation, _numbers, _warn_degrees, check_order, is_rotation,
                       matrix_to_quaternion, quaternion_matrix, rot_x, rot_y, rot_z, rotation_angles,
                       rotation_matrix)

__all__ = ["CONVENTIONS", "BOOK_TO_OPENCV_CAMERA", "hanzl_matrix", "western_matrix", "western_angles",
           "camera_to_object_matrix", "angles_of_matrix", "convert_angles", "wak_to_kaw", "kaw_to_wak",
           "hanzl_to_book", "book_to_hanzl", "western_to_book", "book_to_western", "quaternion_product",
           "quaternion_from_angles", "angles_from_quaternion", "quaternion_of_matrix", "eo_to_opencv",
           "opencv_to_eo", "rvec_to_matrix", "matrix_to_rvec", "eo_to_rvec", "camera_matrix",
           "opencv_projection_matrix", "image_to_opencv", "opencv_to_image", "image_to_opencv_pixels",
           "opencv_pixels_to_image", "camera_matrix_pixels", "opencv_distort", "brown_to_opencv_first_order",
           "opencv_to_brown_first_order", "DistortionConversion", "brown_to_opencv", "opencv_to_brown"]

CONVENTIONS = ("kaw", "wak", "hanzl", "western")
"""Angle conventions understood by :func:`convert_angles`."""

ORDERS_BOOK = ("kaw", "wak")

BOOK_TO_OPENCV_CAMERA = np.diag([1.0, -1.0, -1.0])
"""Maps book camera axes (x right, y up, looking along −z) to OpenCV's (x right, y down, along +z)."""


def _check_convention(name: str) -> str:
    if not isinstance(name, str) or name not in CONVENTIONS:
        raise InputError(f"unknown angle convention {name!r}; use one of {CONVENTIONS}")
    return name


def _T(M):
    return np.swapaxes(M, -1, -2)


# --- Hanzl and Western (Wolf/ASPRS) ------------------------------------------------------------
def hanzl_matrix(omega, phi, kappa) -> np.ndarray:
    """Hanzl's R = R_ω R_φ R_κ (Modul 01, §2.2), image → object: X = R x.

    His elementary matrices are the counter-clockwise rotations about x, y, z — the book's A_ω,
    A_α, A_κ — so R is the book's ω–α–κ matrix (1.3.2) with φ ≡ α.

    Parameters
    ----------
    omega, phi, kappa : float or array
        Hanzl's angles in radians.

    Returns
    -------
    ndarray
        R (3×3, or a stack), image → object.

    Raises
    ------
    InputError
        NaN/inf or non-numbers.

    References
    ----------
    Chibunichev (2022), §1.3, eq. (1.3.2); Hanzl, Fotogrammetrie, Modul 01, §2.2.

    Examples
    --------
    >>> np.allclose(hanzl_matrix(0.1, 0.2, 0.3), rotation_matrix(0.1, 0.2, 0.3, "wak"))
    True
    """
    return rot_x(omega) @ rot_y(phi) @ rot_z(kappa)


def _passive(angle, axis: int) -> np.ndarray:
    return _T((rot_x, rot_y, rot_z)[axis](angle))


def western_matrix(omega, phi, kappa) -> np.ndarray:
    """Wolf/ASPRS ω–φ–κ matrix M = M_κ M_φ M_ω (object → image), built from passive rotations.

    M_ω = [[1, 0, 0], [0, cos ω, sin ω], [0, −sin ω, cos ω]] and likewise M_φ, M_κ (each the
    transpose of the book's active matrix). Then m11 = cos φ cos κ, m12 = cos ω sin κ +
    sin ω sin φ cos κ, …, m33 = cos ω cos φ, and M = Aᵀ of the book's (1.3.2).

    Parameters
    ----------
    omega, phi, kappa : float or array
        Wolf/ASPRS angles in radians.

    Returns
    -------
    ndarray
        M (3×3, or a stack), object → image.

    Raises
    ------
    InputError
        NaN/inf or non-numbers.

    References
    ----------
    Chibunichev (2022), §1.3, eq. (1.3.2) (M = Aᵀ); Wolf, Dewitt & Wilkinson, Elements of Photogrammetry, §C-7.

    Examples
    --------
    >>> np.allclose(western_matrix(0.1, 0.2, 0.3), rotation_matrix(0.1, 0.2, 0.3, "wak").T)
    True
    """
    return _passive(kappa, 2) @ _passive(phi, 1) @ _passive(omega, 0)


def western_angles(M, singular: str = "raise"):
    """(ω, φ, κ) of a Wolf/ASPRS matrix M (object → image).

    φ = asin m31, ω = atan2(−m32, m33), κ = atan2(−m21, m11); since M = Aᵀ of the book's
    ω–α–κ these are the book's (1.3.3) applied to Mᵀ, which is how they are computed.

    Parameters
    ----------
    M : (3, 3) array
        A rotation matrix (object → image).
    singular : {"raise", "kappa-zero"}
        Behaviour at φ = ±90°, as in :func:`photolib.rotation.rotation_angles`.

    Returns
    -------
    (omega, phi, kappa)
        Radians.

    Raises
    ------
    InputError
        NaN/inf, a wrong shape, or M not a rotation.
    DegenerateGeometryError
        φ = ±90° with ``singular="raise"``.

    References
    ----------
    Chibunichev (2022), §1.3, eq. (1.3.3).

    Examples
    --------
    >>> [round(v, 12) for v in western_angles(western_matrix(0.1, 0.2, 0.3))]
    [0.1, 0.2, 0.3]
    """
    M = _as_rotation(M, "M")
    return rotation_angles(_T(M), "wak", singular=singular)


# --- generic angle conversion --------------------------------------------------------------------
def camera_to_object_matrix(omega, alpha, kappa, convention: str = DEFAULT_ORDER) -> np.ndarray:
    """The book's A (camera → object) for angles given in any of :data:`CONVENTIONS`.

    ``"kaw"`` (1.3.5), ``"wak"`` (1.3.2) and ``"hanzl"`` give A directly; for ``"western"``
    A = Mᵀ. Vectorised over arrays of angles.

    Parameters
    ----------
    omega, alpha, kappa : float or array
        Angles in radians, in ``convention``.
    convention : {"kaw", "wak", "hanzl", "western"}
        The angle convention.

    Returns
    -------
    ndarray
        A (3×3 or a stack), camera → object.

    Raises
    ------
    InputError
        NaN/inf, non-numbers, an unknown convention.

    References
    ----------
    Chibunichev (2022), §1.3, eqs. (1.3.1)–(1.3.6).

    Examples
    --------
    >>> np.allclose(camera_to_object_matrix(0.1, 0.2, 0.3, "western"), rotation_matrix(0.1, 0.2, 0.3, "wak"))
    True
    """
    _check_convention(convention)
    if convention in ORDERS_BOOK:
        return rotation_matrix(omega, alpha, kappa, convention)
    if convention == "hanzl":
        return hanzl_matrix(omega, alpha, kappa)
    return _T(western_matrix(omega, alpha, kappa))



def angles_of_matrix(A, convention: str = DEFAULT_ORDER, singular: str = "raise"):
    """Angles of the book's A (camera → object) in a given convention (inverse of
    :func:`camera_to_object_matrix`): (1.3.6) for ``"kaw"``, (1.3.3) for ``"wak"``/``"hanzl"``,
    :func:`western_angles` of Aᵀ for ``"western"``.

    Parameters
    ----------
    A : (3, 3) array
        A rotation, camera → object.
    convention : {"kaw", "wak", "hanzl", "western"}
        The angle convention wanted.
    singular : {"raise", "kappa-zero"}
        Behaviour at gimbal lock.

    Returns
    -------
    (omega, alpha, kappa)
        Radians.

    Raises
    ------
    InputError
        NaN/inf, a wrong shape, A not a rotation, an unknown convention.
    DegenerateGeometryError
        Gimbal lock with ``singular="raise"``.

    References
    ----------
    Chibunichev (2022), §1.3, eqs. (1.3.3), (1.3.6).

    Examples
    --------
    >>> [round(v, 12) for v in angles_of_matrix(rotation_matrix(0.1, 0.2, 0.3, "wak"), "hanzl")]
    [0.1, 0.2, 0.3]
    """
    _check_convention(convention)
    A = _as_rotation(A, "A")
    if convention == "kaw":
        return rotation_angles(A, "kaw", singular=singular)
    if convention in ("wak", "hanzl"):
        return rotation_angles(A, "wak", singular=singular)
    return western_angles(_T(A), singular=singular)


def convert_angles(omega, alpha, kappa, source: str, target: str, singular: str = "raise"):
    """Convert the angles of one attitude from convention ``source`` to ``target``.

    Goes through the matrix: A = camera_to_object_matrix(angles, source), then the angles of A
    in ``target``. Exact up to rounding; the ``target`` angles come back in the principal
    ranges of :func:`photolib.rotation.rotation_angles` (α in [−90°, 90°]). Vectorised.

    Parameters
    ----------
    omega, alpha, kappa : float or array
        Angles in radians, in ``source``.
    source, target : {"kaw", "wak", "hanzl", "western"}
        The two conventions.
    singular : {"raise", "kappa-zero"}
        Behaviour at gimbal lock.

    Returns
    -------
    (omega, alpha, kappa)
        Radians, in ``target``.

    Raises
    ------
    InputError
        NaN/inf, non-numbers, unknown conventions.
    DegenerateGeometryError
        Gimbal lock in ``target`` with ``singular="raise"``.

    References
    ----------
    Chibunichev (2022), §1.3, eqs. (1.3.1)–(1.3.6).

    Examples
    --------
    >>> [round(v, 12) for v in convert_angles(0.1, 0.2, 0.3, "wak", "western")]
    [0.1, 0.2, 0.3]
    """
    A = camera_to_object_matrix(omega, alpha, kappa, source)
    return angles_of_matrix(A, target, singular=singular)


def wak_to_kaw(omega, alpha, kappa, singular: str = "raise"):
    """Book ω–α–κ angles (1.3.2) → book κ–α–ω angles (1.3.5) of the same matrix A.

    Parameters
    ----------
    omega, alpha, kappa : float or array
        Angles in radians.
    singular : {"raise", "kappa-zero"}
        Behaviour at gimbal lock.

    Returns
    -------
    (omega, alpha, kappa)
        Radians.

    Raises
    ------
    InputError
        NaN/inf or non-numbers.
    DegenerateGeometryError
        Gimbal lock with ``singular="raise"``.

    References
    ----------
    Chibunichev (2022), §1.3, eqs. (1.3.2), (1.3.5).

    Examples
    --------
    >>> [round(v, 12) for v in wak_to_kaw(0.0, 0.0, 0.3)]
    [0.0, 0.0, 0.3]
    """
    return convert_angles(omega, alpha, kappa, "wak", "kaw", singular)


def kaw_to_wak(omega, alpha, kappa, singular: str = "raise"):
    """Book κ–α–ω angles (1.3.5) → book ω–α–κ angles (1.3.2) of the same matrix A.

    Parameters
    ----------
    omega, alpha, kappa : float or array
        Angles in radians.
    singular : {"raise", "kappa-zero"}
        Behaviour at gimbal lock.

    Returns
    -------
    (omega, alpha, kappa)
        Radians.

    Raises
    ------
    InputError
        NaN/inf or non-numbers.
    DegenerateGeometryError
        Gimbal lock with ``singular="raise"``.

    References
    ----------
    Chibunichev (2022), §1.3, eqs. (1.3.5), (1.3.2).

    Examples
    --------
    >>> [round(v, 12) for v in kaw_to_wak(0.0, 0.0, 0.3)]
    [0.0, 0.0, 0.3]
    """
    return convert_angles(omega, alpha, kappa, "kaw", "wak", singular)


def hanzl_to_book(omega, phi, kappa, order: str = DEFAULT_ORDER, singular: str = "raise"):
    """Hanzl's (ω, φ, κ) → the book's (ω, α, κ) in ``order`` (identity for ``order="wak"``).

    Parameters
    ----------
    omega, alpha, kappa : float or array
        Angles in radians (φ ≡ α).
    order : {"kaw", "wak"}
        The book's sequence.
    singular : {"raise", "kappa-zero"}
        Behaviour at gimbal lock.

    Returns
    -------
    (omega, alpha, kappa)
        Radians.

    Raises
    ------
    InputError
        NaN/inf, non-numbers, an unknown order.
    DegenerateGeometryError
        Gimbal lock with ``singular="raise"``.

    References
    ----------
    Chibunichev (2022), §1.3, eqs. (1.3.1)–(1.3.6).

    Examples
    --------
    >>> [round(v, 12) for v in hanzl_to_book(0.1, 0.2, 0.3, order="wak")]
    [0.1, 0.2, 0.3]
    """
    return convert_angles(omega, phi, kappa, "hanzl", check_order(order), singular)


def book_to_hanzl(omega, alpha, kappa, order: str = DEFAULT_ORDER, singular: str = "raise"):
    """The book's (ω, α, κ) in ``order`` → Hanzl's (ω, φ, κ).

    Parameters
    ----------
    omega, alpha, kappa : float or array
        Angles in radians (φ ≡ α).
    order : {"kaw", "wak"}
        The book's sequence.
    singular : {"raise", "kappa-zero"}
        Behaviour at gimbal lock.

    Returns
    -------
    (omega, alpha, kappa)
        Radians.

    Raises
    ------
    InputError
        NaN/inf, non-numbers, an unknown order.
    DegenerateGeometryError
        Gimbal lock with ``singular="raise"``.

    References
    ----------
    Chibunichev (2022), §1.3, eqs. (1.3.1)–(1.3.6).

    Examples
    --------
    >>> [round(v, 12) for v in book_to_hanzl(0.1, 0.2, 0.3, order="wak")]
    [0.1, 0.2, 0.3]
    """
    return convert_angles(omega, alpha, kappa, check_order(order), "hanzl", singular)


def western_to_book(omega, phi, kappa, order: str = DEFAULT_ORDER, singular: str = "raise"):
    """Wolf/ASPRS (ω, φ, κ) of M → the book's (ω, α, κ) in ``order`` (A = Mᵀ).

    Parameters
    ----------
    omega, alpha, kappa : float or array
        Angles in radians (φ ≡ α).
    order : {"kaw", "wak"}
        The book's sequence.
    singular : {"raise", "kappa-zero"}
        Behaviour at gimbal lock.

    Returns
    -------
    (omega, alpha, kappa)
        Radians.

    Raises
    ------
    InputError
        NaN/inf, non-numbers, an unknown order.
    DegenerateGeometryError
        Gimbal lock with ``singular="raise"``.

    References
    ----------
    Chibunichev (2022), §1.3, eqs. (1.3.1)–(1.3.6).

    Examples
    --------
    >>> [round(v, 12) for v in western_to_book(0.1, 0.2, 0.3, order="wak")]
    [0.1, 0.2, 0.3]
    """
    return convert_angles(omega, phi, kappa, "western", check_order(order), singular)


def book_to_western(omega, alpha, kappa, order: str = DEFAULT_ORDER, singular: str = "raise"):
    """The book's (ω, α, κ) in ``order`` → Wolf/ASPRS (ω, φ, κ) of M = Aᵀ.

    Parameters
    ----------
    omega, alpha, kappa : float or array
        Angles in radians (φ ≡ α).
    order : {"kaw", "wak"}
        The book's sequence.
    singular : {"raise", "kappa-zero"}
        Behaviour at gimbal lock.

    Returns
    -------
    (omega, alpha, kappa)
        Radians.

    Raises
    ------
    InputError
        NaN/inf, non-numbers, an unknown order.
    DegenerateGeometryError
        Gimbal lock with ``singular="raise"``.

    References
    ----------
    Chibunichev (2022), §1.3, eqs. (1.3.1)–(1.3.6).

    Examples
    --------
    >>> [round(v, 12) for v in book_to_western(0.1, 0.2, 0.3, order="wak")]
    [0.1, 0.2, 0.3]
    """
    return convert_angles(omega, alpha, kappa, check_order(order), "western", singular)


# --- quaternions (1.3.7) -------------------------------------------------------------------------
def _axis_quaternion(angle, axis: int) -> np.ndarray:
    angle = np.asarray(angle, dtype=float)
    q = np.zeros(angle.shape + (4,))
    q[..., axis] = np.sin(angle / 2)
    q[..., 3] = np.cos(angle / 2)
    return q


def quaternion_product(p, q) -> np.ndarray:
    """Hamilton product p ⊗ q of quaternions stored (a, b, c, d) = (vector, scalar).

    The matrix (1.3.7) of p ⊗ q is the matrix of p times the matrix of q.

    Parameters
    ----------
    p, q : (..., 4) array
        Quaternions (a, b, c, d) = (vector, scalar).

    Returns
    -------
    ndarray
        p ⊗ q, (..., 4).

    Raises
    ------
    InputError
        NaN/inf, non-numbers, not 4 components.

    References
    ----------
    Chibunichev (2022), §1.3, eq. (1.3.7).

    Examples
    --------
    >>> quaternion_product([0, 0, 0, 1], [1, 0, 0, 0])
    array([1., 0., 0., 0.])
    """
    p, q = _numbers(p, "quaternion p"), _numbers(q, "quaternion q")
    if p.shape[-1:] != (4,) or q.shape[-1:] != (4,):
        raise InputError(f"quaternions have 4 components (a, b, c, d), got shapes {p.shape}, {q.shape}")
    pv, pw, qv, qw = p[..., :3], p[..., 3:], q[..., :3], q[..., 3:]
    vec = pw * qv + qw * pv + np.cross(pv, qv)
    sca = pw * qw - np.sum(pv * qv, axis=-1, keepdims=True)
    return np.concatenate([vec, sca], axis=-1)


def quaternion_from_angles(omega, alpha, kappa, order: str = DEFAULT_ORDER) -> np.ndarray:
    """Unit quaternion (a, b, c, d), d ≥ 0, whose matrix (1.3.7) is A of ``order``.

    Built as the product of the half-angle quaternions of the elementary rotations,
    q_κ ⊗ q_α ⊗ q_ω for ``"kaw"`` and q_ω ⊗ q_α ⊗ q_κ for ``"wak"``. Same as scipy's
    ``Rotation.from_euler(...).as_quat()`` up to the overall sign. Vectorised: the result has
    shape ``shape + (4,)``.

    Parameters
    ----------
    omega, alpha, kappa : float or array
        Angles in radians.
    order : {"kaw", "wak"}
        The sequence.

    Returns
    -------
    ndarray
        (a, b, c, d), shape ``shape + (4,)``.

    Raises
    ------
    InputError
        NaN/inf, non-numbers, an unknown order.

    References
    ----------
    Chibunichev (2022), §1.3, eqs. (1.3.2), (1.3.5), (1.3.7).

    Examples
    --------
    >>> quaternion_from_angles(0.0, 0.0, 0.3).round(6)
    array([0.      , 0.      , 0.149438, 0.988771])
    """
    check_order(order)
    omega, alpha, kappa = _numbers(omega, "omega"), _numbers(alpha, "alpha"), _numbers(kappa, "kappa")
    try:
        omega, alpha, kappa = np.broadcast_arrays(omega, alpha, kappa)
    except ValueError:
        raise InputError("omega, alpha, kappa do not broadcast to one shape") from None
    _warn_degrees(np.stack([omega, alpha, kappa]), "omega, alpha, kappa")
    qw, qa, qk = _axis_quaternion(omega, 0), _axis_quaternion(alpha, 1), _axis_quaternion(kappa, 2)
    q = quaternion_product(quaternion_product(qk, qa), qw) if order == "kaw" else \
        quaternion_product(quaternion_product(qw, qa), qk)
    return np.where(q[..., 3:] < 0, -q, q)


def angles_from_quaternion(q, order: str = DEFAULT_ORDER, singular: str = "raise"):
    """Angles (ω, α, κ) in ``order`` of the rotation of quaternion ``q`` = (a, b, c, d).

    The quaternion is normalised first (its scale m of (1.3.7) does not matter), then the angles
    are read from its matrix by (1.3.6)/(1.3.3). For ``"kaw"`` this is what the book's relations
    after (1.3.7) compute (:func:`photolib.rotation.quaternion_to_angles`).

    Parameters
    ----------
    q : (..., 4) array
        Quaternion(s) (a, b, c, d), any non-zero scale.
    order : {"kaw", "wak"}
        The sequence wanted.
    singular : {"raise", "kappa-zero"}
        Behaviour at gimbal lock.

    Returns
    -------
    (omega, alpha, kappa)
        Radians.

    Raises
    ------
    InputError
        NaN/inf, a zero quaternion, not 4 components.
    DegenerateGeometryError
        Gimbal lock with ``singular="raise"``.

    References
    ----------
    Chibunichev (2022), §1.3, eqs. (1.3.3), (1.3.6), (1.3.7).

    Examples
    --------
    >>> [round(v, 12) for v in angles_from_quaternion([0.0, 0.0, np.sin(0.15), np.cos(0.15)])]
    [0.0, 0.0, 0.3]
    """
    q = _numbers(q, "quaternion")
    if q.shape[-1:] != (4,):
        raise InputError(f"a quaternion has 4 components (a, b, c, d), got shape {q.shape}")
    norm = np.linalg.norm(q, axis=-1, keepdims=True)
    if not np.all(np.isfinite(norm)) or np.any(norm == 0):
        raise InputError("the quaternion must be finite and non-zero")
    q = q / norm
    return rotation_angles(quaternion_matrix(*np.moveaxis(q, -1, 0)), check_order(order), singular=singular)


def quaternion_of_matrix(A) -> np.ndarray:
    """Unit quaternion (a, b, c, d), d ≥ 0, of a rotation matrix A (camera → object); one matrix
    or a stack. (:func:`photolib.rotation.matrix_to_quaternion` applied to each.)

    Parameters
    ----------
    A : (..., 3, 3) array
        Rotation matrices (camera → object).

    Returns
    -------
    ndarray
        (..., 4) unit quaternions with d ≥ 0.

    Raises
    ------
    InputError
        NaN/inf, a wrong shape, a matrix that is not a rotation.

    References
    ----------
    Chibunichev (2022), §1.3, eq. (1.3.7).

    Examples
    --------
    >>> quaternion_of_matrix(np.eye(3))
    array([0., 0., 0., 1.])
    """
    A = _as_rotation(A, "A")
    flat = A.reshape(-1, 3, 3)
    out = np.array([matrix_to_quaternion(M) for M in flat]).reshape(-1, 4)
    return out.reshape(A.shape[:-2] + (4,))


# --- OpenCV --------------------------------------------------------------------------------------
def eo_to_opencv(eo: ExteriorOrientation):
    """Book exterior orientation → OpenCV extrinsics (R, t).

    R = diag(1, −1, −1)·Aᵀ maps object coordinates into OpenCV camera coordinates (x right,
    y down, z forward); t = −R·S. A point X is seen at X_cv = R X + t, which equals
    diag(1, −1, −1)·(X*, Y*, Z*) of (1.4.10).

    Parameters
    ----------
    eo : ExteriorOrientation
        The book's exterior orientation.

    Returns
    -------
    (R, t)
        R (3, 3) object → OpenCV camera axes, t (3,) = −R·S.

    Raises
    ------
    InputError
        ``eo`` is not an ExteriorOrientation.

    References
    ----------
    Chibunichev (2022), §1.3, eq. (1.3.1); §1.4, eq. (1.4.10).

    Examples
    --------
    >>> R, t = eo_to_opencv(ExteriorOrientation(0.0, 0.0, 1000.0))
    >>> R.diagonal(), t
    (array([ 1., -1., -1.]), array([  0.,   0., 1000.]))
    """
    _expect(eo, ExteriorOrientation, "eo")
    R = BOOK_TO_OPENCV_CAMERA @ eo.matrix.T
    return R, -R @ eo.center


def _as_rotation_cv(R) -> np.ndarray:
    R = _numbers(R, "R")
    if R.shape in ((3,), (3, 1), (1, 3)):
        R = rvec_to_matrix(R)
    if R.shape != (3, 3) or not np.all(np.isfinite(R)):
        raise InputError(f"R must be a finite 3×3 matrix or a Rodrigues vector, got shape {R.shape}")
    if not is_rotation(R, tol=1e-6):
        raise InputError("R is not a rotation matrix (RᵀR ≠ E or det R ≠ +1)")
    return R


def opencv_to_eo(R, t, order: str = DEFAULT_ORDER, singular: str = "raise") -> ExteriorOrientation:
    """OpenCV extrinsics (R, t) → book :class:`ExteriorOrientation` with angles in ``order``.

    A = (diag(1, −1, −1) R)ᵀ, S = −Rᵀ t. ``R`` may also be a Rodrigues vector (rvec).

    Parameters
    ----------
    R : (3, 3) array or (3,) Rodrigues vector
        OpenCV rotation (object → OpenCV camera).
    t : (3,) array
        OpenCV translation.
    order : {"kaw", "wak"}
        Sequence of the returned angles.
    singular : {"raise", "kappa-zero"}
        Behaviour at gimbal lock.

    Returns
    -------
    ExteriorOrientation

    Raises
    ------
    InputError
        NaN/inf, wrong shapes, R not a rotation.
    DegenerateGeometryError
        Gimbal lock with ``singular="raise"``.

    References
    ----------
    Chibunichev (2022), §1.3, eqs. (1.3.1), (1.3.6).

    Examples
    --------
    >>> opencv_to_eo(np.diag([1.0, -1.0, -1.0]), [0.0, 0.0, 1000.0]).center
    array([   0.,    0., 1000.])
    """
    R = _as_rotation_cv(R)
    t = _numbers(t, "t").reshape(-1)
    if t.shape != (3,):
        raise InputError(f"t must be a finite 3-vector, got shape {np.shape(t)}")
    A = (BOOK_TO_OPENCV_CAMERA @ R).T
    w, a, k = rotation_angles(A, check_order(order), singular=singular)
    S = -R.T @ t
    return ExteriorOrientation(float(S[0]), float(S[1]), float(S[2]), w, a, k, order)


def rvec_to_matrix(rvec) -> np.ndarray:
    """Rodrigues vector → rotation matrix (what ``cv2.Rodrigues`` does), via scipy's rotvec.

    Parameters
    ----------
    rvec : (3,) array
        Rodrigues vector (axis × angle, radians).

    Returns
    -------
    ndarray
        The 3×3 rotation matrix.

    Raises
    ------
    InputError
        NaN/inf, not 3 components.

    References
    ----------
    Chibunichev (2022), §1.3 (rotation matrices, eq. (1.3.1)).

    Examples
    --------
    >>> rvec_to_matrix([0.0, 0.0, np.pi / 2]).round(12) + 0.0
    array([[ 0., -1.,  0.],
           [ 1.,  0.,  0.],
           [ 0.,  0.,  1.]])
    """
    rvec = _numbers(rvec, "rvec").reshape(-1)
    if rvec.shape != (3,):
        raise InputError(f"a Rodrigues vector has 3 finite components, got shape {np.shape(rvec)}")
    return Rotation.from_rotvec(rvec).as_matrix()


def matrix_to_rvec(R) -> np.ndarray:
    """Rotation matrix → Rodrigues vector (axis × angle, angle in [0, π]).

    Parameters
    ----------
    R : (3, 3) array
        A rotation matrix.

    Returns
    -------
    ndarray
        (3,) Rodrigues vector, angle in [0, π].

    Raises
    ------
    InputError
        NaN/inf, a wrong shape, R not a rotation.

    References
    ----------
    Chibunichev (2022), §1.3 (rotation matrices, eq. (1.3.1)).

    Examples
    --------
    >>> matrix_to_rvec(rvec_to_matrix([0.0, 0.0, 0.5])).round(12) + 0.0
    array([0. , 0. , 0.5])
    """
    R = _numbers(R, "R")
    if R.shape != (3, 3) or not is_rotation(R, tol=1e-6):
        raise InputError("matrix_to_rvec needs a 3×3 rotation matrix")
    return Rotation.from_matrix(R).as_rotvec()


def eo_to_rvec(eo: ExteriorOrientation):
    """Book exterior orientation → OpenCV (rvec, tvec), as ``cv2.projectPoints`` takes them.

    Parameters
    ----------
    eo : ExteriorOrientation

    Returns
    -------
    (rvec, tvec)
        As ``cv2.projectPoints`` takes them.

    Raises
    ------
    InputError
        ``eo`` is not an ExteriorOrientation.

    References
    ----------
    Chibunichev (2022), §1.3, eq. (1.3.1).

    Examples
    --------
    >>> rvec, tvec = eo_to_rvec(ExteriorOrientation(0.0, 0.0, 1000.0))
    >>> rvec.round(6), tvec
    (array([3.141593, 0.      , 0.      ]), array([   0.,    0., 1000.]))
    """
    R, t = eo_to_opencv(eo)
    return matrix_to_rvec(R), t


def camera_matrix(io: InteriorOrientation) -> np.ndarray:
    """OpenCV intrinsic matrix K in mm for the book's interior orientation.

    K = [[f, 0, x₀], [0, f, −y₀], [0, 0, 1]]: with (u, v) = (x, −y) the principal point
    (x₀, y₀) sits at (x₀, −y₀). Distortion is not part of K (see :func:`brown_to_opencv`).

    Parameters
    ----------
    io : InteriorOrientation

    Returns
    -------
    ndarray
        K (3×3) in mm.

    Raises
    ------
    InputError
        ``io`` is not an InteriorOrientation.

    References
    ----------
    Chibunichev (2022), §1.2, eq. (1.2.1).

    Examples
    --------
    >>> camera_matrix(InteriorOrientation(100.0, 0.1, 0.2))
    array([[100. ,   0. ,   0.1],
           [  0. , 100. ,  -0.2],
           [  0. ,   0. ,   1. ]])
    """
    _expect(io, InteriorOrientation, "io")
    return np.array([[io.f, 0.0, io.x0], [0.0, io.f, -io.y0], [0.0, 0.0, 1.0]])


def opencv_projection_matrix(eo: ExteriorOrientation, io: InteriorOrientation) -> np.ndarray:
    """3×4 OpenCV projection matrix P = K [R | t] (mm): (u, v, 1) ∝ P (X, Y, Z, 1).

    The book's own camera matrix (image y up) is :func:`photolib.projective.projection_matrix`;
    the two differ by the flip of the y axis, diag(1, −1, 1).

    Parameters
    ----------
    eo : ExteriorOrientation
    io : InteriorOrientation

    Returns
    -------
    ndarray
        P (3×4), mm.

    Raises
    ------
    InputError
        ``eo`` or ``io`` of the wrong type.

    References
    ----------
    Chibunichev (2022), §1.4, eqs. (1.4.10)–(1.4.12).

    Examples
    --------
    >>> P = opencv_projection_matrix(ExteriorOrientation(0.0, 0.0, 1000.0), InteriorOrientation(100.0))
    >>> u = P @ [100.0, 50.0, 0.0, 1.0]
    >>> u[:2] / u[2]
    array([10., -5.])
    """
    _expect(io, InteriorOrientation, "io")
    R, t = eo_to_opencv(eo)
    return camera_matrix(io) @ np.column_stack([R, t])


def image_to_opencv(xy) -> np.ndarray:
    """Book image coordinates (x, y) in mm (y up) → OpenCV image coordinates (u, v) = (x, −y) in mm.

    Parameters
    ----------
    xy : (n, 2) array
        Book image coordinates in mm (y up).

    Returns
    -------
    ndarray
        (n, 2) OpenCV image coordinates (u, v) in mm.

    Raises
    ------
    InputError
        A wrong shape, NaN/inf.

    References
    ----------
    Chibunichev (2022), §1.2 (the image coordinate system).

    Examples
    --------
    >>> image_to_opencv([[1.0, 2.0]])
    array([[ 1., -2.]])
    """
    xy = as_points(xy, 2, "image coordinates")
    return xy * np.array([1.0, -1.0])


def opencv_to_image(uv) -> np.ndarray:
    """OpenCV image coordinates (u, v) in mm (v down) → book image coordinates (x, y) = (u, −v).

    Parameters
    ----------
    uv : (n, 2) array
        OpenCV image coordinates in mm (v down).

    Returns
    -------
    ndarray
        (n, 2) book image coordinates in mm.

    Raises
    ------
    InputError
        A wrong shape, NaN/inf.

    References
    ----------
    Chibunichev (2022), §1.2 (the image coordinate system).

    Examples
    --------
    >>> opencv_to_image([[1.0, -2.0]])
    array([[1., 2.]])
    """
    uv = as_points(uv, 2, "OpenCV image coordinates")
    return uv * np.array([1.0, -1.0])


def _pixel_origin(pixel_size_mm, shape, origin):
    pixel_size_mm = _scalar(pixel_size_mm, "pixel size")
    if pixel_size_mm <= 0:
        raise InputError(f"pixel size must be positive, got {pixel_size_mm}")
    dims = _numbers(shape, "shape")
    if dims.shape != (2,) or np.any(dims < 1) or np.any(dims != np.round(dims)):
        raise InputError(f"shape must be (n_rows, n_cols), two whole numbers ≥ 1, got {shape!r}")
    n_rows, n_cols = (int(v) for v in dims)
    if origin == "center":          # o' at the centre of the sensor
        return (n_cols - 1) / 2, (n_rows - 1) / 2
    if origin == "lower-left":      # o' at the outer lower-left corner of the sensor
        return -0.5, n_rows - 0.5
    raise InputError("origin of the image system must be 'center' or 'lower-left' (§1.2, Fig. 1.9 б)")


def image_to_opencv_pixels(xy, pixel_size_mm, shape, origin: str = "center") -> np.ndarray:
    """Book image coordinates in mm → OpenCV pixel coordinates (u, v).

    OpenCV puts pixel centres at integers with (0, 0) the centre of the top-left pixel, u to the
    right and v down. The book's o'xy of a digital camera has its origin at the centre or at the
    lower-left corner of the sensor (§1.2) and y up. ``shape`` = (n_rows, n_cols).

    Parameters
    ----------
    xy : (n, 2) array
        Book image coordinates in mm.
    pixel_size_mm : float
        Pixel side in mm, > 0.
    shape : (int, int)
        (n_rows, n_cols) of the sensor.
    origin : {"center", "lower-left"}
        Origin of the book's image system.

    Returns
    -------
    ndarray
        (n, 2) OpenCV pixel coordinates (u, v).

    Raises
    ------
    InputError
        NaN/inf, wrong shapes, a non-positive pixel size, an unknown origin.

    References
    ----------
    Chibunichev (2022), §1.2, Fig. 1.9; §1.10, eq. (1.10.4).

    Examples
    --------
    >>> image_to_opencv_pixels([[0.0, 0.0]], 0.01, (1000, 1500))
    array([[749.5, 499.5]])
    """
    u0, v0 = _pixel_origin(pixel_size_mm, shape, origin)
    xy = as_points(xy, 2, "image coordinates")
    pixel_size_mm = float(pixel_size_mm)
    return np.column_stack([u0 + xy[:, 0] / pixel_size_mm, v0 - xy[:, 1] / pixel_size_mm])


def opencv_pixels_to_image(uv, pixel_size_mm, shape, origin: str = "center") -> np.ndarray:
    """OpenCV pixel coordinates (u, v) → book image coordinates in mm (inverse of
    :func:`image_to_opencv_pixels`).

    Parameters
    ----------
    uv : (n, 2) array
        OpenCV pixel coordinates.
    pixel_size_mm : float
        Pixel side in mm, > 0.
    shape : (int, int)
        (n_rows, n_cols).
    origin : {"center", "lower-left"}
        Origin of the book's image system.

    Returns
    -------
    ndarray
        (n, 2) book image coordinates in mm.

    Raises
    ------
    InputError
        NaN/inf, wrong shapes, a non-positive pixel size, an unknown origin.

    References
    ----------
    Chibunichev (2022), §1.2, Fig. 1.9; §1.10, eq. (1.10.4).

    Examples
    --------
    >>> opencv_pixels_to_image([[749.5, 499.5]], 0.01, (1000, 1500))
    array([[0., 0.]])
    """
    u0, v0 = _pixel_origin(pixel_size_mm, shape, origin)
    uv = as_points(uv, 2, "pixel coordinates")
    pixel_size_mm = float(pixel_size_mm)
    return np.column_stack([(uv[:, 0] - u0) * pixel_size_mm, (v0 - uv[:, 1]) * pixel_size_mm])


def camera_matrix_pixels(io: InteriorOrientation, pixel_size_mm, shape, origin: str = "center") -> np.ndarray:
    """OpenCV intrinsic matrix K in pixels: f/Δ on the diagonal and the principal point in
    OpenCV pixel coordinates (see :func:`image_to_opencv_pixels`).

    Parameters
    ----------
    io : InteriorOrientation
    pixel_size_mm : float
        Pixel side in mm, > 0.
    shape : (int, int)
        (n_rows, n_cols).
    origin : {"center", "lower-left"}
        Origin of the book's image system.

    Returns
    -------
    ndarray
        K (3×3) in pixels.

    Raises
    ------
    InputError
        ``io`` of the wrong type, a bad pixel size, shape or origin.

    References
    ----------
    Chibunichev (2022), §1.2, eq. (1.2.1); §1.10.

    Examples
    --------
    >>> camera_matrix_pixels(InteriorOrientation(35.0), 0.01, (1000, 1500))[0]
    array([3500. ,    0. ,  749.5])
    """
    _expect(io, InteriorOrientation, "io")
    c = image_to_opencv_pixels([io.x0, io.y0], pixel_size_mm, shape, origin)[0]
    fp = io.f / float(pixel_size_mm)
    return np.array([[fp, 0.0, c[0]], [0.0, fp, c[1]], [0.0, 0.0, 1.0]])


# --- distortion: Brown (1.2.2) ↔ OpenCV ----------------------------------------------------------
def _check_dist(dist) -> np.ndarray:
    d = _numbers(dist, "distCoeffs").reshape(-1)
    if d.size not in (4, 5, 8, 12, 14):
        raise InputError(f"OpenCV distCoeffs: 4, 5, 8, 12 or 14 finite values expected, got {d.size}")
    if d.size > 5 and np.any(d[5:] != 0):
        raise InputError("only the k1, k2, p1, p2, k3 terms of OpenCV's model have a Brown counterpart")
    out = np.zeros(5)
    out[:min(d.size, 5)] = d[:5]
    return out


def opencv_distort(xy_n, dist) -> np.ndarray:
    """OpenCV's distortion of ideal normalised coordinates (x', y') in the OpenCV frame (y down).

    x'' = x'(1 + k1 r² + k2 r⁴ + k3 r⁶) + 2 p1 x'y' + p2 (r² + 2x'²),
    y'' = y'(1 + k1 r² + k2 r⁴ + k3 r⁶) + p1 (r² + 2y'²) + 2 p2 x'y',
    with ``dist`` = (k1, k2, p1, p2[, k3]) in OpenCV's order.

    Parameters
    ----------
    xy_n : (n, 2) array
        Ideal normalised coordinates in the OpenCV frame.
    dist : array
        OpenCV ``distCoeffs`` (k1, k2, p1, p2[, k3]).

    Returns
    -------
    ndarray
        (n, 2) distorted normalised coordinates.

    Raises
    ------
    InputError
        NaN/inf, wrong shapes, unsupported coefficients.

    References
    ----------
    Chibunichev (2022), §1.2, eq. (1.2.2) (the book's model, the inverse direction).

    Examples
    --------
    >>> opencv_distort([[0.1, 0.0]], [-0.1, 0.0, 0.0, 0.0])
    array([[0.0999, 0.    ]])
    """
    k1, k2, p1, p2, k3 = _check_dist(dist)
    xy_n = as_points(xy_n, 2, "normalised coordinates")
    x, y = xy_n[:, 0], xy_n[:, 1]
    r2 = x * x + y * y
    radial = 1 + k1 * r2 + k2 * r2 ** 2 + k3 * r2 ** 3
    return np.column_stack([x * radial + 2 * p1 * x * y + p2 * (r2 + 2 * x * x),
                            y * radial + p1 * (r2 + 2 * y * y) + 2 * p2 * x * y])


def brown_to_opencv_first_order(io: InteriorOrientation) -> np.ndarray:
    """First-order OpenCV ``distCoeffs`` (k1, k2, p1, p2, k3) for the book's Brown coefficients:
    (−k1 f², −k2 f⁴, f p2, −f p1, −k3 f⁶). Neglects products of coefficients.

    Parameters
    ----------
    io : InteriorOrientation

    Returns
    -------
    ndarray
        (k1, k2, p1, p2, k3) in OpenCV's order.

    Raises
    ------
    InputError
        ``io`` is not an InteriorOrientation.

    References
    ----------
    Chibunichev (2022), §1.2, eq. (1.2.2).

    Examples
    --------
    >>> brown_to_opencv_first_order(InteriorOrientation(100.0, k1=-1e-6)) + 0.0
    array([0.01, 0.  , 0.  , 0.  , 0.  ])
    """
    _expect(io, InteriorOrientation, "io")
    f = io.f
    return np.array([-io.k1 * f ** 2, -io.k2 * f ** 4, f * io.p2, -f * io.p1, -io.k3 * f ** 6])


def opencv_to_brown_first_order(K, dist) -> InteriorOrientation:
    """First-order Brown coefficients (1.2.2) for OpenCV's K (mm) and ``distCoeffs``; inverse of
    :func:`brown_to_opencv_first_order`.

    Parameters
    ----------
    K : (3, 3) array
        OpenCV intrinsic matrix in mm (square pixels, no skew).
    dist : array
        OpenCV ``distCoeffs``.

    Returns
    -------
    InteriorOrientation

    Raises
    ------
    InputError
        NaN/inf, K not of the book's form, unsupported coefficients.

    References
    ----------
    Chibunichev (2022), §1.2, eq. (1.2.2).

    Examples
    --------
    >>> opencv_to_brown_first_order(camera_matrix(InteriorOrientation(100.0)), [0.01, 0, 0, 0]).k1
    -1e-06
    """
    f, x0, y0 = _intrinsics(K)
    k1, k2, p1, p2, k3 = _check_dist(dist)
    return InteriorOrientation(f, x0, y0, float(-k1 / f ** 2), float(-k2 / f ** 4), float(-k3 / f ** 6),
                               float(-p2 / f), float(p1 / f))


def _intrinsics(K):
    K = _numbers(K, "K")
    if K.shape != (3, 3):
        raise InputError(f"K must be a finite 3×3 matrix, got shape {K.shape}")
    if not (np.isclose(K[0, 0], K[1, 1], rtol=1e-12) and K[0, 1] == 0 and np.allclose(K[2], [0, 0, 1])
            and K[1, 0] == 0):
        raise InputError("the book's interior orientation needs K = [[f, 0, cx], [0, f, cy], [0, 0, 1]] "
                         "(square pixels, no skew)")
    return float(K[0, 0]), float(K[0, 2]), float(-K[1, 2])


def _format_grid(format_half_size_mm, n_grid):
    h = _numbers(format_half_size_mm, "format half size")
    try:
        h = np.broadcast_to(h, (2,))
    except ValueError:
        raise InputError(f"format half size: one or two numbers expected, got {format_half_size_mm!r}") from None
    if not np.all(h > 0):
        raise InputError(f"format half size must be positive, got {format_half_size_mm}")
    if isinstance(n_grid, bool) or not isinstance(n_grid, (int, np.integer)) or n_grid < 5:
        raise InputError("the fitting grid needs at least 5 nodes per side")
    gx, gy = np.meshgrid(np.linspace(-h[0], h[0], int(n_grid)), np.linspace(-h[1], h[1], int(n_grid)))
    return np.column_stack([gx.ravel(), gy.ravel()])


class DistortionConversion(NamedTuple):
    """Result of :func:`brown_to_opencv` / :func:`opencv_to_brown`.

    Attributes
    ----------
    model : ndarray or InteriorOrientation
        OpenCV ``distCoeffs`` (k1, k2, p1, p2, k3), or the book's interior orientation.
    max_residual_um : float
        Largest position error of the fitted model over the grid, μm.
    rms_residual_um : float
        Its root mean square, μm.

    References
    ----------
    Chibunichev (2022), §1.2, eqs. (1.2.2)–(1.2.3).

    Examples
    --------
    >>> DistortionConversion(np.zeros(5), 0.0, 0.0).max_residual_um
    0.0
    """

    model: object             #: OpenCV distCoeffs (k1, k2, p1, p2, k3) or an InteriorOrientation
    max_residual_um: float    #: largest position error of the fitted model over the grid, μm
    rms_residual_um: float    #: its root mean square, μm


def brown_to_opencv(io: InteriorOrientation, format_half_size_mm, n_grid: int = 41) -> DistortionConversion:
    """Book Brown coefficients (1.2.2) → OpenCV ``distCoeffs`` fitted by least squares.

    A grid of measured points covers the format |x| ≤ h_x, |y| ≤ h_y (mm); the book model gives
    their ideal positions exactly (1.2.3). OpenCV's model must map the ideal normalised
    coordinates to the measured ones; it is linear in (k1, k2, p1, p2, k3), solved with
    :func:`photolib.lsq.solve_normal_equations`. Returns the coefficients and the residual
    position error (μm) of OpenCV's model with them.

    Parameters
    ----------
    io : InteriorOrientation
    format_half_size_mm : float or (float, float)
        Half the image format h_x, h_y in mm.
    n_grid : int
        Grid nodes per side, ≥ 5.

    Returns
    -------
    DistortionConversion
        OpenCV coefficients, largest and r.m.s. residual in μm.

    Raises
    ------
    InputError
        ``io`` of the wrong type, a bad format or grid.

    References
    ----------
    Chibunichev (2022), §1.2, eqs. (1.2.2)–(1.2.3).

    Examples
    --------
    >>> conv = brown_to_opencv(InteriorOrientation(100.0, k1=-1e-6), 50.0)
    >>> round(float(conv.model[0]), 4), conv.max_residual_um < 0.01
    (0.01, True)
    """
    _expect(io, InteriorOrientation, "io")
    measured = _format_grid(format_half_size_mm, n_grid)
    ideal = correct_distortion(measured, io)
    pp = np.array([io.x0, io.y0])
    flip = np.array([1.0, -1.0])
    ideal_n = (ideal - pp) * flip / io.f          # OpenCV normalised frame, y down
    target = (measured - pp) * flip / io.f - ideal_n
    x, y = ideal_n[:, 0], ideal_n[:, 1]
    r2 = x * x + y * y
    # columns: k1, k2, p1, p2, k3 (OpenCV order); rows: all Δx'' then all Δy''
    Bx = np.column_stack([x * r2, x * r2 ** 2, 2 * x * y, r2 + 2 * x * x, x * r2 ** 3])
    By = np.column_stack([y * r2, y * r2 ** 2, r2 + 2 * y * y, 2 * x * y, y * r2 ** 3])
    B = np.vstack([Bx, By])
    L = -np.concatenate([target[:, 0], target[:, 1]])
    delta, _ = lsq.solve_normal_equations(B, L, names=("k1", "k2", "p1", "p2", "k3"))
    error_mm = (B @ delta + L).reshape(2, -1).T * io.f
    return _result(delta, error_mm)


def opencv_to_brown(K, dist, format_half_size_mm, n_grid: int = 41) -> DistortionConversion:
    """OpenCV K (mm) and ``distCoeffs`` → book :class:`InteriorOrientation` fitted by least squares.

    A grid of ideal points covers the format; OpenCV's model gives the measured (distorted)
    positions exactly. The Brown correction (1.2.2) evaluated at the measured points must bring
    them back to the ideal ones; it is linear in (k1, k2, k3, p1, p2), solved with
    :func:`photolib.lsq.solve_normal_equations`. Returns the interior orientation and the
    residual position error (μm) of the corrected points.

    Parameters
    ----------
    K : (3, 3) array
        OpenCV intrinsic matrix in mm.
    dist : array
        OpenCV ``distCoeffs``.
    format_half_size_mm : float or (float, float)
        Half the image format in mm.
    n_grid : int
        Grid nodes per side, ≥ 5.

    Returns
    -------
    DistortionConversion
        The InteriorOrientation, largest and r.m.s. residual in μm.

    Raises
    ------
    InputError
        NaN/inf, K not of the book's form, a bad format or grid.

    References
    ----------
    Chibunichev (2022), §1.2, eqs. (1.2.2)–(1.2.3).

    Examples
    --------
    >>> conv = opencv_to_brown(camera_matrix(InteriorOrientation(100.0)), [0.01, 0, 0, 0], 50.0)
    >>> round(conv.model.k1 * 1e6, 3)
    -1.0
    """
    f, x0, y0 = _intrinsics(K)
    pp = np.array([x0, y0])
    flip = np.array([1.0, -1.0])
    ideal = _format_grid(format_half_size_mm, n_grid)
    measured = pp + opencv_distort((ideal - pp) * flip / f, dist) * flip * f
    xb, yb = (measured - pp).T
    r2 = xb * xb + yb * yb
    # columns: k1, k2, k3, p1, p2 (book order); d = ideal − measured
    Bx = np.column_stack([xb * r2, xb * r2 ** 2, xb * r2 ** 3, r2 + 2 * xb * xb, 2 * xb * yb])
    By = np.column_stack([yb * r2, yb * r2 ** 2, yb * r2 ** 3, 2 * xb * yb, r2 + 2 * yb * yb])
    B = np.vstack([Bx, By])
    target = ideal - measured
    L = -np.concatenate([target[:, 0], target[:, 1]])
    delta, _ = lsq.solve_normal_equations(B, L, names=("k1", "k2", "k3", "p1", "p2"))
    error_mm = (B @ delta + L).reshape(2, -1).T
    k1, k2, k3, p1, p2 = map(float, delta)
    io = InteriorOrientation(f, x0, y0, k1, k2, k3, p1, p2)
    res = _result(delta, error_mm)
    return DistortionConversion(io, res.max_residual_um, res.rms_residual_um)


def _result(delta, error_mm) -> DistortionConversion:
    norm_um = np.hypot(error_mm[:, 0], error_mm[:, 1]) * 1000.0
    return DistortionConversion(np.asarray(delta, dtype=float), float(norm_um.max()),
                                float(np.sqrt(np.mean(norm_um ** 2))))
