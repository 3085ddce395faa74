"""Projective transformations in photogrammetry — Chapter 4, §4.1–§4.4.

* §4.1 the homogeneous camera and the direct linear transformation (DLT):
  :func:`calibration_matrix` (K of (4.1.2)), :func:`projection_matrix` ((4.1.1)/(4.1.2) in a
  form consistent with Chapter 1), :func:`dlt_from_projection`, :func:`projection_from_dlt`,
  :func:`dlt_from_orientation`, :func:`dlt_project` (4.1.7), :func:`orientation_from_dlt`
  ((4.2.4)–(4.2.6) and (1.3.6)).
* §4.2 projective space resection: :func:`dlt_resection` — L₁…L₁₁ from ≥ 6 non-coplanar
  control points by linear least squares (4.2.1)–(4.2.3), as printed or with Hartley's
  normalisation, with μ and m_L from :mod:`photolib.lsq`.
* §4.3 projective forward intersection: :func:`dlt_intersection` (4.3.1), any number of images.
* §4.4 relative orientation through the fundamental and essential matrices:
  :func:`skew_matrix` (4.4.4), :func:`fundamental_matrix` (4.4.13)/(4.4.14),
  :func:`essential_matrix` (4.4.15)/(4.4.16), :func:`fundamental_from_orientation`,
  :func:`essential_from_orientation` (a corrected (4.4.10)), :func:`epipolar_lines`,
  :func:`epipolar_residuals`, :func:`sampson_distance`, :func:`decompose_essential` (rotation,
  base direction and the elements b_y, b_z, ω′₂, α′₂, κ′₂ of the system (2.7.5)),
  :func:`relative_orientation_projective` (both steps), :func:`essential_from_fundamental`,
  :func:`ransac_fundamental`.
* Plane-to-plane homography (8 parameters, cf. (1.7.5) and Hanzl's projective transformation):
  :func:`homography_dlt` (normalised linear) and :func:`homography_lsq` (iterated least squares
  with the sympy Jacobian of :func:`photolib.derivations.homography_model`), :func:`apply_homography`.

Conventions (see the chapter's notes for the proofs)
-----------------------------------------------------
Chapter 1 writes the image ray as r = (x − x₀, y − y₀, −f) with A mapping camera → object axes,
so a point in front of the camera has Z* < 0, Z* the third component of Aᵀ(X − S). The book's
homogeneous form (4.1.2), K·[A | R_S], is only valid if its "A" is read as an object → camera
rotation whose z axis points *towards* the object and R_S as a translation. In Chapter-1 terms::

    P = K · D · Aᵀ · [E | −S],   K = [[f_x, 0, x₀], [0, f_y, y₀], [0, 0, 1]],   D = diag(1, 1, −1)

(the same camera as (1.4.12) when f_x = f_y = f). Dividing P by P₃₄ gives L₁…L₁₁ of (4.1.7);
P₃₄ = a₁₃X_S + a₂₃Y_S + a₃₃Z_S, not Z_S as the text says.

Errata handled here (proved in ``tests/test_projective.py``):

* (4.2.5) lacks a minus sign: S = −M⁻¹(L₄, L₈, 1)ᵀ, M the 3×3 of L₁…L₃, L₅…L₇, L₉…L₁₁
  (``printed=True`` gives the printed, negated centre — the book's example table shows it).
* (4.2.6): the third row repeats the first; it must be a₃₁ = L(x₀L₁₁ − L₃)/f_x,
  a₃₂ = L(y₀L₁₁ − L₇)/f_y.
* The sign of L in (4.2.4) (−1/√(L₉² + L₁₀² + L₁₁²)) holds only when the object origin is in
  front of the camera; we pick the sign that makes det A = +1.
* (4.4.13)/(4.4.14) define F by r₁ᵀ F r₂ = 0, but the book's epipolar line l₂ = F r₁ and its
  printed numeric F and E satisfy r₂ᵀ F r₁ = 0. This module returns F and E in the layout
  ``"x2Fx1"`` (x₂ᵀ F x₁ = 0, l₂ = F x₁ — the book's numbers, Hartley & Zisserman, OpenCV);
  ``layout="x1Fx2"`` gives the transpose, the matrix of the equations (4.4.13)/(4.4.14).
* (4.4.10)/(4.4.16) write A₂⁻¹ where (4.4.7) gives A₂; the book's K⁻¹(x, y, 1) is the
  Chapter-1 ray reflected by D. Consistently: E = D A₂ᵀ S_b A₁ D (x2Fx1 layout), F = K₂⁻ᵀ E K₁⁻¹.

Units: image coordinates in mm, object coordinates in m, angles in radians.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .camera import ExteriorOrientation, InteriorOrientation, as_point_pairs, as_points
from .image_pair import _check_type
from .errors import DegenerateGeometryError, InputError, PointBehindCameraError
from .lsq import Adjustment, accuracy, gauss_newton, point_weights, solve_normal_equations
from .rotation import check_order, rotation_angles

__all__ = ["DLT_NAMES", "HOMOGRAPHY_NAMES", "LAYOUTS", "D_REFLECTION", "normalizing_transform",
           "nearest_rotation", "calibration_matrix", "projection_matrix", "dlt_from_projection",
           "projection_from_dlt", "dlt_from_orientation", "dlt_project", "orientation_from_dlt", "dlt_design",
           "dlt_resection", "dlt_intersection", "skew_matrix", "normalized_image_coordinates",
           "essential_from_orientation", "fundamental_from_orientation", "fundamental_matrix",
           "essential_matrix", "essential_from_fundamental", "epipolar_residuals", "sampson_distance",
           "epipolar_lines", "essential_candidates", "decompose_essential", "relative_orientation_projective",
           "ransac_fundamental", "apply_homography", "homography_dlt", "homography_lsq",
           "coplanarity_interior_matrix", "fundamental_coplanarity"]

DLT_NAMES = tuple(f"L{i}" for i in range(1, 12))
HOMOGRAPHY_NAMES = tuple(f"h{i}" for i in range(1, 9))
LAYOUTS = ("x2Fx1", "x1Fx2")
D_REFLECTION = np.diag([1.0, 1.0, -1.0])
"""D = diag(1, 1, −1): the Chapter-1 camera frame (image at z = −f) ↔ the homogeneous frame of §4.1."""


# --- helpers ------------------------------------------------------------------------------------
def _check_layout(layout: str) -> str:
    if layout not in LAYOUTS:
        raise InputError(f"layout must be 'x2Fx1' (x₂ᵀFx₁ = 0, l₂ = Fx₁) or 'x1Fx2' (4.4.13), got {layout!r}")
    return layout


def _check_method(method: str, allowed=("normalized", "book")) -> str:
    if method not in allowed:
        raise InputError(f"method must be one of {allowed}, got {method!r}")
    return method


def _dlt_vector(L) -> np.ndarray:
    L = np.asarray(L, dtype=float)
    if L.shape != (11,):
        raise InputError(f"DLT coefficients: expected 11 values L1…L11, got shape {L.shape}")
    if not np.all(np.isfinite(L)):
        raise InputError("DLT coefficients contain NaN or inf")
    return L


def _matrix3(M, what: str) -> np.ndarray:
    M = np.asarray(M, dtype=float)
    if M.shape != (3, 3) or not np.all(np.isfinite(M)):
        raise InputError(f"{what} must be a finite 3×3 matrix, got shape {M.shape}")
    return M


def _homogeneous(points) -> np.ndarray:
    return np.column_stack([points, np.ones(len(points))])


def _pair(xy1, xy2, minimum: int, what: str):
    xy1 = as_points(xy1, 2, f"{what}: image-1 coordinates")
    xy2 = as_points(xy2, 2, f"{what}: image-2 coordinates")
    if len(xy1) != len(xy2):
        raise InputError(f"{what}: {len(xy1)} points on image 1 but {len(xy2)} on image 2")
    if len(xy1) < minimum:
        raise InputError(f"{what} needs at least {minimum} correspondences, got {len(xy1)}")
    return xy1, xy2


def normalizing_transform(points) -> np.ndarray:
    """Hartley's conditioning: move the centroid to the origin, mean distance √dim.

    Parameters
    ----------
    points : (n, 2) or (n, 3) array
        Points to condition.

    Returns
    -------
    (dim+1, dim+1) ndarray
        The homogeneous matrix T with x̃ = T·x.

    Raises
    ------
    InputError
        Wrong shape, NaN/inf.
    DegenerateGeometryError
        All points coincide.

    References
    ----------
    Chibunichev (2022), §4.2; Hartley & Zisserman, Multiple View Geometry (2003), §4.4.4.

    Examples
    --------
    >>> normalizing_transform([[0.0, 0.0], [2.0, 0.0]])
    array([[ 1.41421356,  0.        , -1.41421356],
           [ 0.        ,  1.41421356, -0.        ],
           [ 0.        ,  0.        ,  1.        ]])
    """
    points = np.asarray(points, dtype=float)
    if points.ndim != 2 or points.shape[1] not in (2, 3) or len(points) == 0:
        raise InputError(f"normalizing_transform: expected an (n, 2) or (n, 3) array of points, got shape {points.shape}")
    if not np.all(np.isfinite(points)):
        raise InputError("normalizing_transform: the points contain NaN or inf")
    dim = points.shape[1]
    centroid = points.mean(axis=0)
    spread = np.mean(np.linalg.norm(points - centroid, axis=1))
    if not spread > 0:
        raise DegenerateGeometryError("all points coincide; no projective transformation is determined")
    s = np.sqrt(dim) / spread
    T = np.eye(dim + 1)
    T[:dim, :dim] *= s
    T[:dim, dim] = -s * centroid
    return T


def _null_vector(M):
    """Right singular vector of the smallest singular value and all singular values (padded)."""
    _, s, Vt = np.linalg.svd(M, full_matrices=True)
    s = np.concatenate([s, np.zeros(Vt.shape[0] - len(s))])
    return Vt[-1], s


def nearest_rotation(M) -> np.ndarray:
    """The rotation matrix closest to M in the Frobenius norm (SVD, det = +1).

    The result does not depend on the signs the SVD picks (U·Vᵀ is invariant).

    Parameters
    ----------
    M : (3, 3) array
        A nearly orthogonal matrix.

    Returns
    -------
    (3, 3) ndarray
        The nearest rotation.

    Raises
    ------
    InputError
        Not a finite 3×3 matrix.

    References
    ----------
    Chibunichev (2022), §4.2, eq. (4.2.6).

    Examples
    --------
    >>> nearest_rotation([[1.0, 0.01, 0], [0, 1, 0], [0, 0, 1]]).round(3)
    array([[ 1.   ,  0.005,  0.   ],
           [-0.005,  1.   ,  0.   ],
           [ 0.   ,  0.   ,  1.   ]])
    """
    U, _, Vt = np.linalg.svd(_matrix3(M, "matrix"))
    R = U @ Vt
    if np.linalg.det(R) < 0:
        R = U @ np.diag([1.0, 1.0, -1.0]) @ Vt
    return R


# --- §4.1 the homogeneous camera and the DLT ----------------------------------------------------------
def calibration_matrix(io: InteriorOrientation, fx=None, fy=None, skew: float = 0.0) -> np.ndarray:
    """K of (4.1.2): [[f_x, s, x₀], [0, f_y, y₀], [0, 0, 1]] (f_x = f_y = f unless given; the book has s = 0).

    Parameters
    ----------
    io : InteriorOrientation
        f, x₀, y₀ (mm).
    fx, fy : float, optional
        Separate focal lengths.
    skew : float
        s.

    Returns
    -------
    (3, 3) ndarray
        K.

    Raises
    ------
    InputError
        io of the wrong type; f_x, f_y not positive and finite.

    References
    ----------
    Chibunichev (2022), §4.1, eq. (4.1.2).

    Examples
    --------
    >>> from photolib.camera import InteriorOrientation
    >>> calibration_matrix(InteriorOrientation(100.0, 0.1, -0.2))
    array([[100. ,   0. ,   0.1],
           [  0. , 100. ,  -0.2],
           [  0. ,   0. ,   1. ]])
    """
    _check_type(io, InteriorOrientation, "io")
    fx = io.f if fx is None else float(fx)
    fy = io.f if fy is None else float(fy)
    if not (np.isfinite(fx) and np.isfinite(fy) and fx > 0 and fy > 0 and np.isfinite(skew)):
        raise InputError(f"f_x, f_y must be positive and finite and the skew finite, got {fx}, {fy}, {skew}")
    return np.array([[fx, skew, io.x0], [0.0, fy, io.y0], [0.0, 0.0, 1.0]])


def projection_matrix(io: InteriorOrientation, eo: ExteriorOrientation, fx=None, fy=None,
                      skew: float = 0.0) -> np.ndarray:
    """3×4 projection matrix P = K·D·Aᵀ·[E | −S] of (4.1.1)/(4.1.2) (corrected form, see module notes).

    (x, y, 1)ᵀ ∝ P·(X, Y, Z, 1)ᵀ reproduces the collinearity equations (1.4.12) for f_x = f_y = f.
    ``io`` distortion is ignored (the projective model has none).

    Parameters
    ----------
    io : InteriorOrientation
        Interior orientation.
    eo : ExteriorOrientation
        Exterior orientation.
    fx, fy, skew
        As in :func:`calibration_matrix`.

    Returns
    -------
    (3, 4) ndarray
        P.

    Raises
    ------
    InputError
        Orientations of the wrong type, bad f_x, f_y.

    References
    ----------
    Chibunichev (2022), §4.1, eqs. (4.1.1), (4.1.2); §1.4, eq. (1.4.12).

    Examples
    --------
    >>> import numpy as np
    >>> from photolib.camera import ExteriorOrientation, InteriorOrientation
    >>> io = InteriorOrientation(100.0)
    >>> eo = ExteriorOrientation(0.0, 0.0, 1000.0)
    >>> P = projection_matrix(io, eo)
    >>> h = P @ [100.0, 50.0, 0.0, 1.0]
    >>> h[:2] / h[2]
    array([10.,  5.])
    """
    K = calibration_matrix(io, fx, fy, skew)
    R = D_REFLECTION @ _check_type(eo, ExteriorOrientation, "eo").matrix.T
    return K @ R @ np.column_stack([np.eye(3), -eo.center])


def dlt_from_projection(P) -> np.ndarray:
    """L₁…L₁₁ of (4.1.7): the projection matrix divided by its element P₃₄ (4.1.6) → (4.1.7).

    Parameters
    ----------
    P : (3, 4) array
        A projection matrix.

    Returns
    -------
    (11,) ndarray
        L₁…L₁₁.

    Raises
    ------
    InputError
        Not a finite 3×4 array.
    DegenerateGeometryError
        P₃₄ = 0 (the object origin in the plane of the centre parallel to the image).

    References
    ----------
    Chibunichev (2022), §4.1, eqs. (4.1.6), (4.1.7).

    Examples
    --------
    >>> dlt_from_projection(np.arange(1.0, 13.0).reshape(3, 4))[:3].round(4)
    array([0.0833, 0.1667, 0.25  ])
    """
    P = np.asarray(P, dtype=float)
    if P.shape != (3, 4) or not np.all(np.isfinite(P)):
        raise InputError(f"a projection matrix must be a finite 3×4 array, got shape {P.shape}")
    if abs(P[2, 3]) <= 1e-12 * np.abs(P[2, :3]).max():
        raise DegenerateGeometryError(
            "P₃₄ = 0: the object origin lies in the plane through the projection centre parallel to the "
            "image, so (4.1.7) cannot be normalised; move the object origin")
    return (P / P[2, 3]).ravel()[:11]


def projection_from_dlt(L) -> np.ndarray:
    """The 3×4 matrix [[L₁ L₂ L₃ L₄], [L₅ L₆ L₇ L₈], [L₉ L₁₀ L₁₁ 1]] of (4.1.7).

    Parameters
    ----------
    L : (11,) array
        L₁…L₁₁.

    Returns
    -------
    (3, 4) ndarray
        The matrix.

    Raises
    ------
    InputError
        Not 11 finite numbers.

    References
    ----------
    Chibunichev (2022), §4.1, eq. (4.1.7).

    Examples
    --------
    >>> projection_from_dlt(np.arange(1.0, 12.0))[2]
    array([ 9., 10., 11.,  1.])
    """
    return np.append(_dlt_vector(L), 1.0).reshape(3, 4)


def dlt_from_orientation(io: InteriorOrientation, eo: ExteriorOrientation, fx=None, fy=None,
                         skew: float = 0.0) -> np.ndarray:
    """L₁…L₁₁ of (4.1.7) for a camera given by its interior and exterior orientation.

    Parameters
    ----------
    io : InteriorOrientation
        Interior orientation.
    eo : ExteriorOrientation
        Exterior orientation.
    fx, fy, skew
        As in :func:`calibration_matrix`.

    Returns
    -------
    (11,) ndarray
        L₁…L₁₁.

    Raises
    ------
    InputError
        Orientations of the wrong type.
    DegenerateGeometryError
        P₃₄ = 0.

    References
    ----------
    Chibunichev (2022), §4.1, eqs. (4.1.1)–(4.1.7).

    Examples
    --------
    >>> import numpy as np
    >>> from photolib.camera import ExteriorOrientation, InteriorOrientation
    >>> io = InteriorOrientation(100.0)
    >>> eo = ExteriorOrientation(0.0, 0.0, 1000.0)
    >>> dlt_project(dlt_from_orientation(io, eo), [[100.0, 50.0, 0.0]])
    array([[10.,  5.]])
    """
    return dlt_from_projection(projection_matrix(io, eo, fx, fy, skew))


def dlt_project(L, XYZ) -> np.ndarray:
    """Object → image by the DLT (4.1.7): x = (L₁X + L₂Y + L₃Z + L₄)/(L₉X + L₁₀Y + L₁₁Z + 1), likewise y.

    Parameters
    ----------
    L : (11,) array
        L₁…L₁₁.
    XYZ : (n, 3) array
        Object points.

    Returns
    -------
    (n, 2) ndarray
        Image coordinates.

    Raises
    ------
    InputError
        Bad shapes, NaN/inf.
    DegenerateGeometryError
        A point in the plane of the centre parallel to the image.

    References
    ----------
    Chibunichev (2022), §4.1, eq. (4.1.7).

    Examples
    --------
    >>> dlt_project([1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0], [[2.0, 3.0, 5.0]])
    array([[2., 3.]])
    """
    P = projection_from_dlt(L)
    XYZ = as_points(XYZ, 3, "object points")
    h = _homogeneous(XYZ) @ P.T
    if np.any(np.abs(h[:, 2]) < 1e-15):
        raise DegenerateGeometryError("a point lies in the plane of the projection centre parallel to the image")
    return h[:, :2] / h[:, 2:]


@dataclass(frozen=True, repr=False)
class DLTOrientation:
    """Interior and exterior orientation recovered from L₁…L₁₁, (4.2.4)–(4.2.6).

    ``fx`` and ``fy`` are those of (4.2.4); with a non-zero ``skew`` s (the non-orthogonality
    of the image axes the 11 coefficients can hold) the book's f_x equals √(f_x² + s²) of the
    general camera K = [[f_x, s, x₀], [0, f_y, y₀], [0, 0, 1]]. ``A_printed`` is the matrix of
    (4.2.6) (third row corrected); ``eo`` uses its nearest rotation ``A``.
    """

    x0: float
    y0: float
    fx: float
    fy: float
    skew: float
    L: float                     # the factor L of (4.2.4) with the sign that gives det A > 0
    center: np.ndarray           # (4.2.5) with the minus sign
    A_printed: np.ndarray        # (4.2.6) with row 3 corrected, not exactly orthogonal for noisy data
    A: np.ndarray                # nearest rotation to A_printed
    eo: ExteriorOrientation

    @property
    def book_angles(self) -> np.ndarray:
        """(ω, α, κ) read off ``A_printed`` literally by (1.3.6) (``"kaw"``) or (1.3.3) (``"wak"``).

        This is what the book's example tabulates; ``eo`` instead takes the angles of the
        nearest rotation, which differ by the non-orthogonality of ``A_printed`` (≈ 0.005°).
        """
        a = self.A_printed
        if self.eo.order == "kaw":
            return np.array([np.arctan2(a[2, 1], a[2, 2]), np.arcsin(-a[2, 0]), np.arctan2(a[1, 0], a[0, 0])])
        return np.array([np.arctan2(-a[1, 2], a[2, 2]), np.arcsin(a[0, 2]), np.arctan2(-a[0, 1], a[0, 0])])

    @property
    def orthogonality_error(self) -> float:
        """max |AᵀA − E| of the matrix (4.2.6) — how far the DLT camera is from a metric one."""
        return float(np.abs(self.A_printed.T @ self.A_printed - np.eye(3)).max())

    def __repr__(self) -> str:
        w, a, k = np.degrees(self.eo.vector[3:])
        X, Y, Z = self.center
        return (f"DLTOrientation (4.2.4)–(4.2.6)\n"
                f"  x₀ = {self.x0:.4f} mm, y₀ = {self.y0:.4f} mm, f_x = {self.fx:.4f} mm, f_y = {self.fy:.4f} mm, "
                f"skew = {self.skew:.2e} mm\n"
                f"  S = ({X:.3f}, {Y:.3f}, {Z:.3f}) m; ω, α, κ = {w:.4f}°, {a:.4f}°, {k:.4f}° ({self.eo.order})\n"
                f"  non-orthogonality of A: {self.orthogonality_error:.1e}")


def orientation_from_dlt(L, order: str = "kaw", printed: bool = False) -> DLTOrientation:
    """x₀, y₀, f_x, f_y (4.2.4), the centre (4.2.5), A (4.2.6) and ω, α, κ by (1.3.6)/(1.3.3).

    Parameters
    ----------
    L : (11,) array
        L₁…L₁₁ of (4.1.7).
    order : {"kaw", "wak"}
        Rotation sequence of the returned angles; the book uses (1.3.6), i.e. ``"kaw"``.
    printed : bool
        If True the centre is computed by (4.2.5) exactly as printed, M⁻¹(L₄, L₈, 1)ᵀ, which
        is the negative of the true centre (the book's example table prints these values);
        the returned ``eo`` then carries that wrong centre too.

    Returns
    -------
    DLTOrientation
        Interior and exterior orientation.

    Raises
    ------
    InputError
        Not 11 finite numbers, unknown order.
    DegenerateGeometryError
        Singular 3×3 part, f_x² ≤ 0 or f_y² ≤ 0.

    References
    ----------
    Chibunichev (2022), §4.2, eqs. (4.2.4)–(4.2.6); §1.3, eqs. (1.3.3), (1.3.6).

    Examples
    --------
    >>> import numpy as np
    >>> from photolib.camera import ExteriorOrientation, InteriorOrientation
    >>> io = InteriorOrientation(100.0)
    >>> eo = ExteriorOrientation(0.0, 0.0, 1000.0)
    >>> o = orientation_from_dlt(dlt_from_orientation(io, eo))
    >>> round(o.fx, 9), o.center.round(6)
    (100.0, array([   0.,    0., 1000.]))
    """
    check_order(order)
    L = _dlt_vector(L)
    m1, m2, m3 = L[0:3], L[4:7], L[8:11]
    n3 = np.linalg.norm(m3)
    M = np.vstack([m1, m2, m3])
    det = np.linalg.det(M)
    if n3 == 0 or abs(det) <= 1e-12 * np.linalg.norm(m1) * np.linalg.norm(m2) * n3:
        raise DegenerateGeometryError("the 3×3 part of the DLT matrix is singular: not a central projection")
    Lf = -1.0 / n3                                                   # (4.2.4)
    x0 = float(m1 @ m3) * Lf ** 2
    y0 = float(m2 @ m3) * Lf ** 2
    fx2 = float(m1 @ m1) * Lf ** 2 - x0 ** 2
    fy2 = float(m2 @ m2) * Lf ** 2 - y0 ** 2
    if fx2 <= 0 or fy2 <= 0:
        raise DegenerateGeometryError("(4.2.4) gives f_x² ≤ 0 or f_y² ≤ 0: the coefficients are not a camera")
    fx, fy = np.sqrt(fx2), np.sqrt(fy2)
    skew = (float(m1 @ m2) * Lf ** 2 - x0 * y0) / fy

    def a_matrix(Lf):                                                # (4.2.6), row 3 corrected
        return Lf * np.column_stack([(x0 * m3 - m1) / fx, (y0 * m3 - m2) / fy, m3])

    A_printed = a_matrix(Lf)
    if np.linalg.det(A_printed) < 0:          # the object origin is behind the camera: L > 0
        Lf = -Lf
        A_printed = a_matrix(Lf)
    center = np.linalg.solve(M, np.array([L[3], L[7], 1.0]))
    if not printed:
        center = -center                                              # (4.2.5) with the minus sign
    A = nearest_rotation(A_printed)
    w, a, k = rotation_angles(A, order)
    eo = ExteriorOrientation(float(center[0]), float(center[1]), float(center[2]), w, a, k, order)
    return DLTOrientation(x0, y0, float(fx), float(fy), float(skew), float(Lf), center, A_printed, A, eo)


# --- §4.2 projective space resection -----------------------------------------------------------------
@dataclass(repr=False)
class DLTResection:
    """Result of :func:`dlt_resection`: L₁…L₁₁ with the accuracy of the linear model (4.2.1).

    ``residuals`` are v_x, v_y of (4.2.1) (algebraic, mm scaled by the DLT denominator);
    ``image_residuals`` the reprojection errors DLT(X) − x in mm. μ, m_L and r_ij follow
    (1.8.8)–(1.8.10) with Q = (BᵀPB)⁻¹ of (4.2.2).
    """

    L: np.ndarray
    Q: np.ndarray
    mu: float
    std: np.ndarray
    corr: np.ndarray
    residuals: np.ndarray
    image_residuals: np.ndarray
    dof: int
    method: str

    def orientation(self, order: str = "kaw", printed: bool = False) -> DLTOrientation:
        """Interior and exterior orientation by (4.2.4)–(4.2.6), see :func:`orientation_from_dlt`."""
        return orientation_from_dlt(self.L, order, printed)

    def as_dict(self) -> dict:
        """{"L1": L₁, …, "L11": L₁₁}."""
        return dict(zip(DLT_NAMES, self.L))

    def __repr__(self) -> str:
        rms = float(np.sqrt(np.mean(self.image_residuals ** 2)))
        return (f"DLTResection ({self.method}), {len(self.image_residuals)} points, dof = {self.dof}\n"
                f"  μ = {self.mu:.3g}; r.m.s. reprojection error {1000 * rms:.1f} µm\n"
                f"  L = [{', '.join(f'{v:.6g}' for v in self.L)}]")


def _check_not_coplanar(XYZ, what: str):
    s = np.linalg.svd(XYZ - XYZ.mean(axis=0), compute_uv=False)
    if s[0] == 0 or s[2] <= 1e-9 * s[0]:
        raise DegenerateGeometryError(f"{what} are coplanar (or collinear): the 11 DLT coefficients are not determined")


def dlt_design(XYZ, xy):
    """B and the free terms of (4.2.1)/(4.2.2): rows [X Y Z 1 0 0 0 0 −xX −xY −xZ], free term −x, then y.

    Parameters
    ----------
    XYZ : (n, 3) array
        Control points.
    xy : (n, 2) array
        Their image coordinates.

    Returns
    -------
    B : (2n, 11) ndarray
        Coefficients.
    free : (2n,) ndarray
        Free terms.

    Raises
    ------
    InputError
        Bad shapes, different counts, NaN/inf.

    References
    ----------
    Chibunichev (2022), §4.2, eqs. (4.2.1), (4.2.2).

    Examples
    --------
    >>> B, free = dlt_design([[1.0, 2.0, 3.0]], [[0.5, -0.5]])
    >>> B.shape, free
    ((2, 11), array([-0.5,  0.5]))
    """
    XYZ, xy = as_point_pairs(XYZ, 3, xy, 2, ("object points XYZ", "image points xy"), 1, "the DLT design matrix")
    X, Y, Z = XYZ.T
    x, y = xy.T
    n = len(XYZ)
    one, zero = np.ones(n), np.zeros(n)
    B = np.empty((2 * n, 11))
    B[0::2] = np.column_stack([X, Y, Z, one, zero, zero, zero, zero, -x * X, -x * Y, -x * Z])
    B[1::2] = np.column_stack([zero, zero, zero, zero, X, Y, Z, one, -y * X, -y * Y, -y * Z])
    return B, -xy.ravel()


def dlt_resection(XYZ, xy, method: str = "normalized", weights=None) -> DLTResection:
    """Projective space resection: L₁…L₁₁ from ≥ 6 non-coplanar control points, (4.2.1)–(4.2.3).

    Parameters
    ----------
    XYZ : (n, 3) array
        Control point coordinates (m), n ≥ 6, not all in one plane.
    xy : (n, 2) array
        Their image coordinates (mm).
    method : {"normalized", "book"}
        ``"book"`` solves (4.2.1) as printed by least squares, M = −(BᵀPB)⁻¹BᵀPL (the lost
        (4.2.3)); ``"normalized"`` conditions both point sets by Hartley's transform, takes the
        homogeneous SVD solution and converts it back to L₁…L₁₁.
    weights : array, optional
        p_i per point (n,) or per coordinate (n, 2); unit weights if omitted.

    Returns
    -------
    DLTResection
        L, Q, μ, m_L, r_ij, residuals of (4.2.1), reprojection errors. For ``"normalized"``
        μ, m_L and the residuals are those of (4.2.1) evaluated at the normalised solution.

    Raises
    ------
    InputError
        Fewer than 6 points, mismatched shapes, NaN/inf, a bad option.
    DegenerateGeometryError
        Coplanar control points, or an object origin in the plane of the projection centre
        parallel to the image (no L₁₂ = 1 normalisation possible).

    References
    ----------
    Chibunichev (2022), §4.2, eqs. (4.2.1)–(4.2.3); §1.8, eqs. (1.8.8)–(1.8.10).

    Examples
    --------
    >>> from photolib.camera import ExteriorOrientation, InteriorOrientation
    >>> from photolib.single_image import project
    >>> io, eo = InteriorOrientation(100.0), ExteriorOrientation(0.0, 0.0, 1000.0, 0.01, 0.02, 0.03)
    >>> XYZ = np.random.default_rng(0).uniform([-300, -300, -50], [300, 300, 50], (8, 3))
    >>> res = dlt_resection(XYZ, project(XYZ, eo, io))
    >>> res.orientation().center.round(6)
    array([   0.,    0., 1000.])
    """
    _check_method(method)
    XYZ, xy = as_point_pairs(XYZ, 3, xy, 2, ("control points XYZ", "image points xy"), 6,
                             "the projective resection")
    _check_not_coplanar(XYZ, "the control points")
    n = len(XYZ)
    P = point_weights(weights, n)
    B, free = dlt_design(XYZ, xy)
    delta, Q = solve_normal_equations(B, free, P, DLT_NAMES)     # M = −Q·BᵀPL, (4.2.2)–(4.2.3)
    if method == "book":
        L = delta
    else:
        T = normalizing_transform(xy)
        U = normalizing_transform(XYZ)
        Xn = _homogeneous(XYZ) @ U.T
        xn = _homogeneous(xy) @ T.T
        A = np.zeros((2 * n, 12))
        A[0::2, 0:4] = Xn
        A[0::2, 8:12] = -xn[:, :1] * Xn
        A[1::2, 4:8] = Xn
        A[1::2, 8:12] = -xn[:, 1:2] * Xn
        if P is not None:
            A = np.sqrt(P)[:, None] * A
        p, _ = _null_vector(A)
        L = dlt_from_projection(np.linalg.solve(T, p.reshape(3, 4)) @ U)
    V = B @ L + free
    mu, std, corr = accuracy(V, Q, P)
    image_residuals = dlt_project(L, XYZ) - xy
    return DLTResection(L, Q, mu, std, corr, V.reshape(n, 2), image_residuals, 2 * n - 11, method)


# --- §4.3 projective forward intersection ------------------------------------------------------------
@dataclass(repr=False)
class DLTIntersection:
    """Object points by (4.3.1) with the precision of each: μ (1.8.9) and m_X, m_Y, m_Z (1.8.8)."""

    XYZ: np.ndarray             # (n, 3)
    std: np.ndarray             # (n, 3); NaN when there is no redundancy
    mu: np.ndarray              # (n,)
    residuals: np.ndarray       # (n, k, 2): v_x, v_y of (4.3.1) per image
    image_residuals: np.ndarray  # (n, k, 2): DLT(X) − x per image, mm
    dof: int

    def __repr__(self) -> str:
        n = len(self.XYZ)
        lines = [f"DLTIntersection (4.3.1): {n} points from {self.residuals.shape[1]} images, dof = {self.dof}"]
        for i in range(min(n, 5)):
            X, Y, Z = self.XYZ[i]
            lines.append(f"  point {i}: X = {X:.3f} m, Y = {Y:.3f} m, Z = {Z:.3f} m"
                         + ("" if np.all(np.isnan(self.std[i])) else
                            f" (m = {', '.join(f'{v:.3f}' for v in self.std[i])} m)"))
        if n > 5:
            lines.append(f"  … {n - 5} more")
        return "\n".join(lines)


def dlt_intersection(Ls, xys, weights=None) -> DLTIntersection:
    """Projective forward intersection (4.3.1) from two or more images.

    For every point and image: (L₁ − xL₉)X + (L₂ − xL₁₀)Y + (L₃ − xL₁₁)Z + L₄ − x = v_x and the
    same with L₅…L₈ and y; all images are solved together by least squares (one
    :func:`~photolib.lsq.solve_normal_equations` per point). Every point is checked to lie in
    front of every camera (image axes as in Chapter 1: x right, y up).

    Parameters
    ----------
    Ls : sequence of (11,) arrays
        The DLT coefficients of each image.
    xys : sequence of (n, 2) arrays
        Image coordinates of the same n points on each image.
    weights : sequence of (n,) or (n, 2) arrays, optional
        Weights of the coordinates.

    Returns
    -------
    DLTIntersection
        Points, m_X, m_Y, m_Z, μ, residuals.

    Raises
    ------
    InputError
        Fewer than two images, mismatched counts, bad weights, NaN.
    DegenerateGeometryError
        Rays that do not intersect in a point (parallel).
    PointBehindCameraError
        A point behind a camera; ``points`` lists them.

    References
    ----------
    Chibunichev (2022), §4.3, eq. (4.3.1); §1.8, eqs. (1.8.8), (1.8.9).

    Examples
    --------
    >>> import numpy as np
    >>> from photolib.camera import ExteriorOrientation, InteriorOrientation
    >>> io = InteriorOrientation(100.0)
    >>> eo = ExteriorOrientation(0.0, 0.0, 1000.0)
    >>> e2 = ExteriorOrientation(400.0, 0.0, 1000.0)
    >>> L1, L2 = dlt_from_orientation(io, eo), dlt_from_orientation(io, e2)
    >>> dlt_intersection([L1, L2], [[[20.0, 10.0]], [[-20.0, 10.0]]]).XYZ.round(6)
    array([[200., 100.,   0.]])
    """
    Ls = [_dlt_vector(L) for L in Ls]
    if len(Ls) < 2 or len(xys) != len(Ls):
        raise InputError(f"forward intersection needs ≥ 2 images with coefficients and coordinates each "
                         f"(got {len(Ls)} coefficient sets, {len(xys)} coordinate sets)")
    xys = [as_points(xy, 2, f"image {i + 1} coordinates") for i, xy in enumerate(xys)]
    n = len(xys[0])
    if any(len(xy) != n for xy in xys):
        raise InputError("every image must give coordinates for the same points")
    k = len(Ls)
    if weights is None:
        W = None
    else:
        W = []
        for w in weights:
            w = np.asarray(w, dtype=float)
            w = np.repeat(w[:, None], 2, axis=1) if w.shape == (n,) else w
            if w.shape != (n, 2) or not np.all(np.isfinite(w)) or np.any(w <= 0):
                raise InputError(f"weights: expected positive finite arrays of shape ({n},) or ({n}, 2)")
            W.append(w)
        W = np.stack(W, axis=1)                                       # (n, k, 2)
    xy = np.stack(xys, axis=1)                                        # (n, k, 2)
    Lm = np.stack(Ls)                                                 # (k, 11)
    # rows (L1 − xL9, L2 − xL10, L3 − xL11 | L4 − x), (L5 − yL9, … | L8 − y) for every image
    Bx = Lm[None, :, 0:3] - xy[:, :, 0:1] * Lm[None, :, 8:11]
    By = Lm[None, :, 4:7] - xy[:, :, 1:2] * Lm[None, :, 8:11]
    lx = Lm[None, :, 3] - xy[:, :, 0]
    ly = Lm[None, :, 7] - xy[:, :, 1]
    B = np.stack([Bx, By], axis=2).reshape(n, 2 * k, 3)
    free = np.stack([lx, ly], axis=2).reshape(n, 2 * k)
    XYZ = np.empty((n, 3))
    std = np.full((n, 3), np.nan)
    mu = np.full(n, np.nan)
    V = np.empty((n, 2 * k))
    dof = 2 * k - 3
    for i in range(n):
        p = None if W is None else W[i].ravel()
        try:
            XYZ[i], Q = solve_normal_equations(B[i], free[i], p, ("X", "Y", "Z"))
        except DegenerateGeometryError as err:
            raise DegenerateGeometryError(f"point {i}: the rays do not intersect in a point ({err})") from err
        V[i] = B[i] @ XYZ[i] + free[i]
        mu[i], std[i], _ = accuracy(V[i], Q, p)
    behind = np.zeros(n, bool)
    for L in Ls:
        behind |= ~_in_front_of_dlt(L, XYZ)
    if np.any(behind):
        bad = np.flatnonzero(behind)
        raise PointBehindCameraError(f"points {bad.tolist()} lie behind at least one of the cameras", points=bad)
    image_res = np.stack([dlt_project(L, XYZ) for L in Ls], axis=1) - xy
    return DLTIntersection(XYZ, std, mu, V.reshape(n, k, 2), image_res, dof)


def _in_front_of_dlt(L, XYZ) -> np.ndarray:
    """True for points in front of the DLT camera (image axes as in Chapter 1, x right, y up).

    With P = K·D·Aᵀ·[E | −S] (module notes) det M < 0 and the third homogeneous coordinate
    w = −Z* > 0 for a point in front; sign(det M)·w is invariant to the scale of L, so a point
    is in front when sign(det M)·w < 0.
    """
    P = projection_from_dlt(L)
    w = _homogeneous(XYZ) @ P[2]
    return np.sign(np.linalg.det(P[:, :3])) * w < 0


# --- §4.4 fundamental and essential matrices -----------------------------------------------------------
def skew_matrix(b) -> np.ndarray:
    """S_b of (4.4.4): [[0, −b_z, b_y], [b_z, 0, −b_x], [−b_y, b_x, 0]], so that S_b·r = b × r (4.4.3).

    Parameters
    ----------
    b : 3-vector
        The base.

    Returns
    -------
    (3, 3) ndarray
        S_b.

    Raises
    ------
    InputError
        Not a finite 3-vector.

    References
    ----------
    Chibunichev (2022), §4.4, eqs. (4.4.3), (4.4.4).

    Examples
    --------
    >>> skew_matrix([1.0, 2.0, 3.0]) @ [0.0, 0.0, 1.0]
    array([ 2., -1.,  0.])
    """
    b = np.asarray(b, dtype=float)
    if b.shape != (3,) or not np.all(np.isfinite(b)):
        raise InputError(f"b must be a finite 3-vector, got shape {b.shape}")
    return np.array([[0.0, -b[2], b[1]], [b[2], 0.0, -b[0]], [-b[1], b[0], 0.0]])


def normalized_image_coordinates(xy, io: InteriorOrientation) -> np.ndarray:
    """r″ = K⁻¹(x, y, 1)ᵀ of (4.4.15) = ((x − x₀)/f, (y − y₀)/f, 1), one row per point.

    This is the Chapter-1 ray (x − x₀, y − y₀, −f) divided by f and reflected by D = diag(1, 1, −1).

    Parameters
    ----------
    xy : (n, 2) array
        Image coordinates (mm).
    io : InteriorOrientation
        Interior orientation.

    Returns
    -------
    (n, 3) ndarray
        r″.

    Raises
    ------
    InputError
        Bad shapes, NaN/inf, io of the wrong type.

    References
    ----------
    Chibunichev (2022), §4.4, eq. (4.4.15).

    Examples
    --------
    >>> from photolib.camera import InteriorOrientation
    >>> normalized_image_coordinates([[10.0, -20.0]], InteriorOrientation(100.0))
    array([[ 0.1, -0.2,  1. ]])
    """
    xy = as_points(xy, 2, "image coordinates")
    return _homogeneous(xy) @ np.linalg.inv(calibration_matrix(_check_type(io, InteriorOrientation, "io"))).T


def _layout(M, layout):
    return M if _check_layout(layout) == "x2Fx1" else M.T.copy()


def essential_from_orientation(eo1: ExteriorOrientation, eo2: ExteriorOrientation,
                               layout: str = "x2Fx1") -> np.ndarray:
    """E for normalised coordinates r″ (4.4.15) of two oriented images (a corrected (4.4.16)).

    r₂″ᵀ E r₁″ = 0 with E = D·A₂ᵀ·S_b·A₁·D, b = (S₂ − S₁)/|S₂ − S₁| — the coplanarity (4.4.1) with
    r_i = A_i·D·r_i″ (not A₂⁻¹ as printed). Scaled to unit Frobenius norm.

    Parameters
    ----------
    eo1, eo2 : ExteriorOrientation
        The two images.
    layout : {"x2Fx1", "x1Fx2"}
        Layout of the result.

    Returns
    -------
    (3, 3) ndarray
        E.

    Raises
    ------
    InputError
        Orientations of the wrong type, unknown layout.
    DegenerateGeometryError
        Zero base.

    References
    ----------
    Chibunichev (2022), §4.4, eqs. (4.4.1), (4.4.7), (4.4.16).

    Examples
    --------
    >>> import numpy as np
    >>> from photolib.camera import ExteriorOrientation, InteriorOrientation
    >>> io = InteriorOrientation(100.0)
    >>> eo = ExteriorOrientation(0.0, 0.0, 1000.0)
    >>> E = essential_from_orientation(eo, ExteriorOrientation(400.0, 0.0, 1000.0))
    >>> float(np.array([0.2, 0.1, 1.0]) @ E @ [0.6, 0.1, 1.0])
    0.0
    """
    b = _check_type(eo2, ExteriorOrientation, "eo2").center - _check_type(eo1, ExteriorOrientation, "eo1").center
    nb = np.linalg.norm(b)
    if nb == 0:
        raise DegenerateGeometryError("the two projection centres coincide: the base is zero")
    E = D_REFLECTION @ eo2.matrix.T @ skew_matrix(b / nb) @ eo1.matrix @ D_REFLECTION
    return _layout(E / np.linalg.norm(E), layout)


def fundamental_from_orientation(io1: InteriorOrientation, eo1: ExteriorOrientation,
                                 io2: InteriorOrientation, eo2: ExteriorOrientation,
                                 layout: str = "x2Fx1") -> np.ndarray:
    """F = K₂⁻ᵀ·E·K₁⁻¹ of two oriented images (a corrected (4.4.10)), unit Frobenius norm.

    Parameters
    ----------
    io1, eo1, io2, eo2
        Interior and exterior orientation of the two images.
    layout : {"x2Fx1", "x1Fx2"}
        Layout of the result.

    Returns
    -------
    (3, 3) ndarray
        F.

    Raises
    ------
    InputError
        Wrong types, unknown layout.
    DegenerateGeometryError
        Zero base.

    References
    ----------
    Chibunichev (2022), §4.4, eqs. (4.4.10), (4.4.16).

    Examples
    --------
    >>> import numpy as np
    >>> from photolib.camera import ExteriorOrientation, InteriorOrientation
    >>> io = InteriorOrientation(100.0)
    >>> eo = ExteriorOrientation(0.0, 0.0, 1000.0)
    >>> F = fundamental_from_orientation(io, eo, io, ExteriorOrientation(400.0, 0.0, 1000.0))
    >>> float(np.abs(epipolar_residuals(F, [[60.0, 10.0]], [[20.0, 10.0]]))[0]) < 1e-12
    True
    """
    E = essential_from_orientation(eo1, eo2)
    F = np.linalg.inv(calibration_matrix(io2)).T @ E @ np.linalg.inv(calibration_matrix(io1))
    return _layout(F / np.linalg.norm(F), layout)


def coplanarity_interior_matrix(io: InteriorOrientation) -> np.ndarray:
    """Hanzl's interior-orientation matrix C = [[1, 0, −x₀], [0, 1, −y₀], [0, 0, −c]] (§3.2.5).

    C maps homogeneous image coordinates (x, y, 1) to the image vector (x − x₀, y − y₀, −c). The book
    prints +x₀, +y₀ (line 608), which maps to (x + x₀, y + y₀, −c): an erratum.

    Parameters
    ----------
    io : InteriorOrientation
        c (= f), x₀, y₀ (mm).

    Returns
    -------
    (3, 3) ndarray
        C.

    Raises
    ------
    InputError
        ``io`` not an InteriorOrientation.

    References
    ----------
    Hanzl, Fotogrammetrie, Modul 01, §3.2.5 (seed 002 lines 604–612); Chibunichev (2022), §4.4 (K⁻¹ of (4.4.10)).

    Examples
    --------
    >>> coplanarity_interior_matrix(InteriorOrientation(150.0, 0.01, -0.02)) @ [1.0, 2.0, 1.0]
    array([   0.99,    2.02, -150.  ])
    """
    _check_type(io, InteriorOrientation, "io")
    return np.array([[1.0, 0.0, -io.x0], [0.0, 1.0, -io.y0], [0.0, 0.0, -io.f]])


def fundamental_coplanarity(io1: InteriorOrientation, R1, io2: InteriorOrientation, R2, base) -> np.ndarray:
    """F = C₁ᵀR₁ᵀBR₂C₂ of Hanzl §3.2.5: [x₁ y₁ 1]·F·[x₂ y₂ 1]ᵀ = 0 (layout ``"x1Fx2"``).

    From the coplanarity condition p₁ᵀ(b × p₂) = 0 with p_j = R_jC_j(x_j, y_j, 1)ᵀ and B = [b]ₓ
    (:func:`skew_matrix`); C from :func:`coplanarity_interior_matrix` (with the corrected −x₀, −y₀).
    Not normalised: the scale is that of the formula (compare up to scale with
    :func:`fundamental_from_orientation` ``(…, layout="x1Fx2")``).

    Parameters
    ----------
    io1, io2 : InteriorOrientation
        Interior orientation of the images.
    R1, R2 : (3, 3) arrays
        Rotations image → model (object) frame.
    base : 3-vector
        b = S₂ − S₁ in the same frame (e.g. (1, 0, 0) for the independent pair).

    Returns
    -------
    (3, 3) ndarray
        F, rank 2.

    Raises
    ------
    InputError
        Wrong types or shapes, NaN/inf, a matrix that is not a rotation.
    DegenerateGeometryError
        Zero base.

    References
    ----------
    Hanzl, Fotogrammetrie, Modul 01, §3.2.5 (seed 002 lines 596–624); Chibunichev (2022), §4.4, eq. (4.4.10).

    Examples
    --------
    >>> io = InteriorOrientation(100.0)
    >>> F = fundamental_coplanarity(io, np.eye(3), io, np.eye(3), [1.0, 0.0, 0.0])
    >>> F
    array([[   0.,    0.,    0.],
           [   0.,    0.,  100.],
           [   0., -100.,    0.]])
    >>> float(np.array([60.0, 10.0, 1.0]) @ F @ [20.0, 10.0, 1.0])   # same y: on the epipolar line
    0.0
    """
    mats = []
    for R, name in ((R1, "R1"), (R2, "R2")):
        try:
            R = np.asarray(R, dtype=float)
        except (TypeError, ValueError):
            raise InputError(f"{name} must be a 3×3 matrix of numbers") from None
        if R.shape != (3, 3) or not np.all(np.isfinite(R)):
            raise InputError(f"{name} must be a finite 3×3 matrix, got shape {R.shape}")
        if not np.allclose(R.T @ R, np.eye(3), atol=1e-9) or np.linalg.det(R) < 0:
            raise InputError(f"{name} is not a rotation matrix (RᵀR ≠ I or det < 0)")
        mats.append(R)
    b = as_points(base, 3, "base").reshape(-1)
    if b.shape != (3,):
        raise InputError("base must be one 3-vector")
    if not np.linalg.norm(b) > 0:
        raise DegenerateGeometryError("the base is zero: both projection centres coincide")
    C1, C2 = coplanarity_interior_matrix(io1), coplanarity_interior_matrix(io2)
    return C1.T @ mats[0].T @ skew_matrix(b) @ mats[1] @ C2


def _eight_point(h1, h2, method: str, rank: str):
    """Linear solution of x₂ᵀ F x₁ = 0 from homogeneous rows h1, h2 (layout x2Fx1)."""
    T1 = normalizing_transform(h1[:, :2] / h1[:, 2:])
    T2 = normalizing_transform(h2[:, :2] / h2[:, 2:])
    conditioned = np.einsum("ni,nj->nij", h2 @ T2.T, h1 @ T1.T).reshape(len(h1), 9)
    if _null_vector(conditioned)[1][7] <= 1e-9 * np.linalg.norm(conditioned, 2):
        raise DegenerateGeometryError(
            "the correspondences fit a whole family of epipolar geometries (all object points in one plane, "
            "a pure rotation without base, or repeated points): F is not determined")
    if method == "normalized":
        design = conditioned
    else:                                                         # rows of (4.4.14), x2Fx1 order
        design = np.einsum("ni,nj->nij", h2, h1).reshape(len(h1), 9)
    F = _null_vector(design)[0].reshape(3, 3)
    if rank == "rank2":                        # Hartley: rank 2 in the conditioned frame
        U, sv, Vt = np.linalg.svd(F)
        F = U @ np.diag([sv[0], sv[1], 0.0]) @ Vt
    if method == "normalized":
        F = T2.T @ F @ T1
    if rank == "essential":                    # singular values (σ, σ, 0) in the frame of E itself
        U, sv, Vt = np.linalg.svd(F)
        F = U @ np.diag([1.0, 1.0, 0.0]) @ Vt * (sv[0] + sv[1]) / 2
    return F


def _scale(F, method):
    if method == "book":
        if abs(F[2, 2]) < 1e-12 * np.abs(F).max():
            raise DegenerateGeometryError("f₃₃ ≈ 0: the book's normalisation f₃₃ = 1 (4.4.13) is impossible here")
        return F / F[2, 2]
    F = F / np.linalg.norm(F)
    return F if F[2, 2] >= 0 else -F


def fundamental_matrix(xy1, xy2, method: str = "normalized", layout: str = "x2Fx1") -> np.ndarray:
    """Fundamental matrix from ≥ 8 correspondences, (4.4.11)–(4.4.14).

    The sign is fixed (f₃₃ ≥ 0 after scaling), so the result does not depend on the signs the SVD picks.

    Parameters
    ----------
    xy1, xy2 : (n, 2) arrays
        Image coordinates of the same points on images 1 and 2 (mm), n ≥ 8.
    method : {"normalized", "book"}
        ``"book"``: the SVD null vector of the coefficients of (4.4.14) from the raw coordinates,
        scaled to f₃₃ = 1, no rank-2 constraint (what the book prints). ``"normalized"``:
        Hartley's normalised 8-point algorithm, rank 2 enforced, unit Frobenius norm.
    layout : {"x2Fx1", "x1Fx2"}
        ``"x2Fx1"`` (default): x₂ᵀ F x₁ = 0 and l₂ = F x₁ — the layout of the book's numbers
        and of OpenCV; ``"x1Fx2"``: the transpose, the F of equations (4.4.13)/(4.4.14).

    Returns
    -------
    (3, 3) ndarray
        F.

    Raises
    ------
    InputError
        Fewer than 8 correspondences, mismatched shapes, NaN.
    DegenerateGeometryError
        Correspondences that leave a family of solutions (planar scene, pure rotation).

    References
    ----------
    Chibunichev (2022), §4.4, eqs. (4.4.11)–(4.4.14); Hartley & Zisserman, Multiple View Geometry (2003), §11.2.

    Examples
    --------
    >>> from photolib.synthetic import stereo_pair
    >>> p = stereo_pair(10, seed=0, angle_spread_deg=2.0)
    >>> F = fundamental_matrix(p.xy1, p.xy2)
    >>> float(np.abs(epipolar_residuals(F, p.xy1, p.xy2)).max()) < 1e-9
    True
    """
    _check_method(method)
    _check_layout(layout)
    xy1, xy2 = _pair(xy1, xy2, 8, "the fundamental matrix")
    F = _eight_point(_homogeneous(xy1), _homogeneous(xy2), method, "rank2" if method == "normalized" else "none")
    return _layout(_scale(F, method), layout)


def essential_matrix(xy1, xy2, io1: InteriorOrientation, io2: InteriorOrientation | None = None,
                     method: str = "normalized", layout: str = "x2Fx1") -> np.ndarray:
    """Essential matrix from ≥ 8 correspondences with known interior orientation, (4.4.15)/(4.4.16).

    The coordinates are first reduced to r″ = K⁻¹(x, y, 1)ᵀ (4.4.15); then the same linear
    solution as :func:`fundamental_matrix`. ``"book"``: unconstrained, e₃₃ = 1 (the book's
    example); ``"normalized"``: conditioned, singular values forced to (σ, σ, 0), unit norm.
    (The book's remark that five points suffice needs the non-linear five-point solver.)

    Parameters
    ----------
    xy1, xy2 : (n, 2) arrays
        Corresponding image coordinates (mm), n ≥ 8.
    io1, io2 : InteriorOrientation
        Interior orientation (``io2`` defaults to ``io1``).
    method : {"normalized", "book"}
        See above.
    layout : {"x2Fx1", "x1Fx2"}
        Layout of the result.

    Returns
    -------
    (3, 3) ndarray
        E.

    Raises
    ------
    InputError
        Fewer than 8 correspondences, NaN, bad options.
    DegenerateGeometryError
        Planar scene, pure rotation.

    References
    ----------
    Chibunichev (2022), §4.4, eqs. (4.4.15), (4.4.16).

    Examples
    --------
    >>> from photolib.synthetic import stereo_pair
    >>> p = stereo_pair(10, seed=0, angle_spread_deg=2.0)
    >>> E = essential_matrix(p.xy1, p.xy2, p.io)
    >>> np.linalg.svd(E, compute_uv=False).round(6)
    array([0.707107, 0.707107, 0.      ])
    """
    _check_method(method)
    _check_layout(layout)
    xy1, xy2 = _pair(xy1, xy2, 8, "the essential matrix")
    io2 = io1 if io2 is None else io2
    h1, h2 = normalized_image_coordinates(xy1, io1), normalized_image_coordinates(xy2, io2)
    E = _eight_point(h1, h2, method, "essential" if method == "normalized" else "none")
    return _layout(_scale(E, method), layout)


def essential_from_fundamental(F, io1: InteriorOrientation, io2: InteriorOrientation | None = None,
                               layout: str = "x2Fx1") -> np.ndarray:
    """E = K₂ᵀ·F·K₁ (layout x2Fx1; K₁ᵀ·F·K₂ for x1Fx2) — (4.4.10) with (4.4.16).

    Parameters
    ----------
    F : (3, 3) array
        Fundamental matrix.
    io1, io2 : InteriorOrientation
        Interior orientation (``io2`` defaults to ``io1``).
    layout : {"x2Fx1", "x1Fx2"}
        Layout of F (and of the result).

    Returns
    -------
    (3, 3) ndarray
        E.

    Raises
    ------
    InputError
        Not a finite 3×3 matrix, bad io, unknown layout.

    References
    ----------
    Chibunichev (2022), §4.4, eqs. (4.4.10), (4.4.16).

    Examples
    --------
    >>> from photolib.camera import InteriorOrientation
    >>> essential_from_fundamental(np.eye(3), InteriorOrientation(2.0)).diagonal()
    array([4., 4., 1.])
    """
    F = _matrix3(F, "F")
    io2 = io1 if io2 is None else io2
    K1, K2 = calibration_matrix(io1), calibration_matrix(io2)
    return K2.T @ F @ K1 if _check_layout(layout) == "x2Fx1" else K1.T @ F @ K2


def epipolar_residuals(F, xy1, xy2, layout: str = "x2Fx1") -> np.ndarray:
    """Algebraic residuals x₂ᵀ F x₁ (or x₁ᵀ F x₂ for layout x1Fx2) of (4.4.13), one per point.

    Parameters
    ----------
    F : (3, 3) array
        Fundamental matrix.
    xy1, xy2 : (n, 2) arrays
        Corresponding coordinates.
    layout : {"x2Fx1", "x1Fx2"}
        Layout of F.

    Returns
    -------
    (n,) ndarray
        The residuals.

    Raises
    ------
    InputError
        Bad shapes, NaN/inf, unknown layout.

    References
    ----------
    Chibunichev (2022), §4.4, eq. (4.4.13).

    Examples
    --------
    >>> epipolar_residuals(skew_matrix([1.0, 0, 0]), [[1.0, 2.0]], [[3.0, 2.0]])
    array([0.])
    """
    F = _layout(_matrix3(F, "F"), layout)                       # now always x2Fx1
    xy1, xy2 = _pair(xy1, xy2, 1, "epipolar residuals")
    return np.einsum("ni,ij,nj->n", _homogeneous(xy2), F, _homogeneous(xy1))


def sampson_distance(F, xy1, xy2, layout: str = "x2Fx1") -> np.ndarray:
    """First-order geometric distance of each correspondence from the epipolar geometry (image units).

    Parameters
    ----------
    F : (3, 3) array
        Fundamental matrix.
    xy1, xy2 : (n, 2) arrays
        Corresponding coordinates.
    layout : {"x2Fx1", "x1Fx2"}
        Layout of F.

    Returns
    -------
    (n,) ndarray
        Sampson distances.

    Raises
    ------
    InputError
        Bad shapes, NaN/inf, unknown layout.

    References
    ----------
    Chibunichev (2022), §4.4; Hartley & Zisserman, Multiple View Geometry (2003), §11.4.3.

    Examples
    --------
    >>> sampson_distance(skew_matrix([1.0, 0, 0]), [[1.0, 2.0]], [[3.0, 2.5]]).round(4)
    array([0.3536])
    """
    F = _layout(_matrix3(F, "F"), layout)
    xy1, xy2 = _pair(xy1, xy2, 1, "Sampson distance")
    h1, h2 = _homogeneous(xy1), _homogeneous(xy2)
    Fx1 = h1 @ F.T
    Ftx2 = h2 @ F
    r = np.einsum("ni,ni->n", h2, Fx1)
    return np.abs(r) / np.sqrt(Fx1[:, 0] ** 2 + Fx1[:, 1] ** 2 + Ftx2[:, 0] ** 2 + Ftx2[:, 1] ** 2)


def epipolar_lines(F, xy, image: int = 2, layout: str = "x2Fx1") -> np.ndarray:
    """Epipolar ("basis") lines (a, b, c), a·x + b·y + c = 0, scaled to a² + b² = 1.

    ``image=2``: lines on image 2 of points ``xy`` of image 1, l₂ = F r₁ (the formula after
    (4.4.16)); ``image=1``: lines on image 1 of points of image 2, l₁ = Fᵀ r₂.

    Parameters
    ----------
    F : (3, 3) array
        Fundamental matrix.
    xy : (n, 2) array
        Points.
    image : {1, 2}
        The image the lines lie on.
    layout : {"x2Fx1", "x1Fx2"}
        Layout of F.

    Returns
    -------
    (n, 3) ndarray
        The lines.

    Raises
    ------
    InputError
        Bad shapes, NaN/inf, image not 1 or 2.
    DegenerateGeometryError
        A point at the epipole.

    References
    ----------
    Chibunichev (2022), §4.4, eq. (4.4.16) and the line formula after it.

    Examples
    --------
    >>> epipolar_lines(skew_matrix([1.0, 0, 0]), [[1.0, 2.0]])
    array([[ 0., -1.,  2.]])
    """
    F = _layout(_matrix3(F, "F"), layout)
    if image not in (1, 2):
        raise InputError(f"image must be 1 or 2, got {image!r}")
    h = _homogeneous(as_points(xy, 2, "image coordinates"))
    lines = h @ F.T if image == 2 else h @ F
    norm = np.hypot(lines[:, 0], lines[:, 1])
    if np.any(norm == 0):
        raise DegenerateGeometryError("a point is the epipole: its epipolar line is undefined")
    return lines / norm[:, None]


@dataclass(frozen=True)
class EssentialCandidate:
    """One of the four (rotation, base) decompositions of an essential matrix.

    Attributes
    ----------
    A2 : (3, 3) array
        A′₂, camera-2 axes → model axes (the model frame is the camera-1 frame of Chapter 1).
    base : (3,) array
        Unit base vector S₁ → S₂ in the model frame.
    n_front : int
        Number of points with positive ray scales N₁ and N₂ (in front of both cameras).
    N1, N2 : (n,) arrays
        The ray scales of the vector forward intersection N₁r₁ − N₂A′₂r₂ ≈ b (§2.4).

    References
    ----------
    Chibunichev (2022), §4.4, eqs. (4.4.1)–(4.4.16); §2.4, eq. (2.4.7).

    Examples
    --------
    >>> import numpy as np
    >>> c = EssentialCandidate(np.eye(3), np.array([1.0, 0, 0]), 3, np.ones(3), np.ones(3))
    >>> c.n_front
    3
    """

    A2: np.ndarray
    base: np.ndarray
    n_front: int
    N1: np.ndarray
    N2: np.ndarray

    def __repr__(self) -> str:
        w, a, k = np.degrees(rotation_angles(self.A2, "kaw", singular="kappa-zero"))
        b = ", ".join(f"{v:+.4f}" for v in self.base)
        return (f"EssentialCandidate(ω′₂, α′₂, κ′₂ = {w:.3f}°, {a:.3f}°, {k:.3f}° (kaw); base ({b}); "
                f"{self.n_front}/{len(self.N1)} points in front)")


def _ray_scales(r1, r2m, b):
    """N₁, N₂ with N₁r₁ − N₂r₂ ≈ b (the vector forward intersection of §2.4), vectorised."""
    c = np.cross(r1, r2m)
    cc = np.einsum("ni,ni->n", c, c)
    with np.errstate(divide="ignore", invalid="ignore"):
        N1 = np.einsum("ni,ni->n", np.cross(b, r2m), c) / cc
        N2 = np.einsum("ni,ni->n", np.cross(b, r1), c) / cc
    return N1, N2


_W_TURN = np.array([[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])


def _candidate_key(A2, b):
    """Canonical order of the four candidates, independent of LAPACK's sign choices in the SVD.

    The two rotations are told apart by their rotation angle (largest first), the two bases by
    the sign of their largest component (positive first); the angle is rounded so that rounding
    noise cannot swap two candidates.
    """
    angle = np.arccos(np.clip((np.trace(A2) - 1.0) / 2.0, -1.0, 1.0))
    k = int(np.argmax(np.abs(np.round(b, 12))))
    return (-round(float(angle), 9), -float(np.sign(b[k])))


def essential_candidates(E, xy1, xy2, io1: InteriorOrientation, io2: InteriorOrientation | None = None,
                         layout: str = "x2Fx1") -> list:
    """The four (A′₂, b) decompositions of an essential matrix, in a canonical order.

    E (for r″ of (4.4.15)) is turned into the Chapter-1 frame, E₁ = D·E·D = A′₂ᵀ S_b (A′₁ = E).
    With E₁ = U diag(1, 1, 0) Vᵀ (U, V taken with det = +1) the rotations are A′₂ᵀ = U W Vᵀ and
    U Wᵀ Vᵀ and A′₂ᵀ b = ±u₃. The set of four candidates does not depend on the signs the SVD
    picks; their order here does not either: the rotation with the larger rotation angle comes
    first, and for each rotation the base whose largest component is positive.

    Parameters
    ----------
    E : (3, 3) array
        Essential matrix for normalised coordinates r″ (4.4.15).
    xy1, xy2 : (n, 2) arrays
        Corresponding image coordinates (mm) used for the cheirality count.
    io1, io2 : InteriorOrientation
        Interior orientation of the two images (``io2`` defaults to ``io1``).
    layout : {"x2Fx1", "x1Fx2"}
        Layout of ``E`` (see :func:`fundamental_matrix`).

    Returns
    -------
    list of EssentialCandidate
        Four candidates with A′₂, the unit base, the ray scales and the number of points in front.

    Raises
    ------
    InputError
        E not a finite 3×3 matrix, bad point arrays, unknown layout.
    DegenerateGeometryError
        E of rank < 2.

    References
    ----------
    Chibunichev (2022), §4.4, eqs. (4.4.1), (4.4.15), (4.4.16); Hartley & Zisserman (2003), §9.6.

    Examples
    --------
    >>> import numpy as np
    >>> from photolib.camera import InteriorOrientation
    >>> E = skew_matrix([1.0, 0.0, 0.0])
    >>> xy = np.array([[10.0, 5.0], [-20.0, 8.0], [5.0, -30.0]])
    >>> [c.n_front for c in essential_candidates(E, xy + [0, 0], xy - [30, 0], InteriorOrientation(100.0))]
    [0, 0, 3, 0]
    """
    E = _layout(_matrix3(E, "E"), layout)
    xy1, xy2 = _pair(xy1, xy2, 1, "the decomposition of E")
    io2 = io1 if io2 is None else io2
    r1 = normalized_image_coordinates(xy1, io1) @ D_REFLECTION       # Chapter-1 rays / f
    r2 = normalized_image_coordinates(xy2, io2) @ D_REFLECTION
    E1 = D_REFLECTION @ E @ D_REFLECTION
    U, s, Vt = np.linalg.svd(E1)
    if not s[0] > 0 or s[1] <= 1e-9 * s[0]:
        raise DegenerateGeometryError("E has rank < 2: no base direction can be recovered")
    if np.linalg.det(U) < 0:
        U = -U
    if np.linalg.det(Vt) < 0:
        Vt = -Vt
    out = []
    for R in (U @ _W_TURN @ Vt, U @ _W_TURN.T @ Vt):      # R = A′₂ᵀ (camera 1 → camera 2)
        for t in (U[:, 2], -U[:, 2]):                      # t = A′₂ᵀ b
            A2 = R.T
            b = A2 @ t
            N1, N2 = _ray_scales(r1, r2 @ A2.T, b)
            out.append(EssentialCandidate(A2, b, int(np.sum((N1 > 0) & (N2 > 0))), N1, N2))
    return sorted(out, key=lambda c: _candidate_key(c.A2, c.base))


def decompose_essential(E, xy1, xy2, io1: InteriorOrientation, io2: InteriorOrientation | None = None,
                        order: str = "kaw", layout: str = "x2Fx1", system: str = "dependent"):
    """Rotation and base direction from E, with the cheirality test, and the elements of §2.7.

    Of the four candidates of :func:`essential_candidates` the one that puts most points in
    front of both cameras (positive ray scales N₁, N₂ of §2.4) is kept; a tie (which only
    degenerate data produce) keeps the first in the canonical order. The result is converted to
    the elements of relative orientation of Chapter 2 in the system ``system``.

    Parameters
    ----------
    E : (3, 3) array
        Essential matrix for normalised coordinates r″ (4.4.15).
    xy1, xy2 : (n, 2) arrays
        Corresponding image coordinates (mm).
    io1, io2 : InteriorOrientation
        Interior orientation of the images (``io2`` defaults to ``io1``).
    order : {"kaw", "wak"}
        Rotation sequence of the returned angles.
    layout : {"x2Fx1", "x1Fx2"}
        Layout of ``E``.
    system : {"dependent", "independent"}
        ``"dependent"`` (2.7.5): b_y, b_z, ω′₂, α′₂, κ′₂ with A′₁ = E (the default);
        ``"independent"`` (2.7.4): α′₁, κ′₁, ω′₂, α′₂, κ′₂ with the model X axis along the base.

    Returns
    -------
    photolib.image_pair.RelativeOrientation
        The elements, ``in_front`` (points in front of both cameras) and ``n_points``; no
        adjustment (``adjustment`` is None).

    Raises
    ------
    InputError
        Bad matrix, points, order, layout or system.
    DegenerateGeometryError
        E of rank < 2; no candidate puts any point in front; B_X = 0 in the dependent system.

    References
    ----------
    Chibunichev (2022), §4.4, eqs. (4.4.1)–(4.4.16); §2.7, eqs. (2.7.3)–(2.7.5).

    Examples
    --------
    >>> import numpy as np
    >>> from photolib.camera import InteriorOrientation
    >>> xy = np.array([[10.0, 5.0], [-20.0, 8.0], [5.0, -30.0]])
    >>> ro = decompose_essential(skew_matrix([1.0, 0, 0]), xy, xy - [30, 0], InteriorOrientation(100.0))
    >>> round(ro.b_y, 6), ro.in_front
    (0.0, 3)
    """
    from .image_pair import _relative_from_rotation

    check_order(order)
    cands = essential_candidates(E, xy1, xy2, io1, io2, layout)
    best = max(cands, key=lambda c: c.n_front)          # max keeps the first of equal scores
    if best.n_front == 0:
        raise PointBehindCameraError("no decomposition of E puts the points in front of both cameras",
                                     points=range(len(best.N1)))
    xy1, xy2 = _pair(xy1, xy2, 1, "the decomposition of E")
    return _relative_from_rotation(best.A2, best.base, xy1, xy2, io1, io1 if io2 is None else io2,
                                   system, order, in_front=best.n_front)


def relative_orientation_projective(xy1, xy2, io1: InteriorOrientation, io2: InteriorOrientation | None = None,
                                    order: str = "kaw", system: str = "dependent"):
    """§4.4 end to end: E by the normalised 8-point method, then :func:`decompose_essential`.

    Parameters
    ----------
    xy1, xy2 : (n, 2) arrays
        Corresponding image coordinates (mm), n ≥ 8.
    io1, io2 : InteriorOrientation
        Interior orientation of the images (``io2`` defaults to ``io1``).
    order : {"kaw", "wak"}
        Rotation sequence of the returned angles.
    system : {"dependent", "independent"}
        System of the elements, see :func:`decompose_essential`.

    Returns
    -------
    photolib.image_pair.RelativeOrientation
        The closed-form elements (no adjustment), ``in_front`` and ``n_points``.

    Raises
    ------
    InputError
        Fewer than 8 correspondences, NaN/inf, bad options.
    DegenerateGeometryError
        Planar scene or pure rotation (no base); B_X = 0 in the dependent system.
    PointBehindCameraError
        No decomposition puts the points in front of both cameras.

    References
    ----------
    Chibunichev (2022), §4.4, eqs. (4.4.11)–(4.4.16); §2.7, eq. (2.7.5).

    Examples
    --------
    >>> import numpy as np
    >>> from photolib.camera import ExteriorOrientation, InteriorOrientation
    >>> from photolib.single_image import project
    >>> io = InteriorOrientation(100.0)
    >>> P = np.random.default_rng(0).uniform([-300, -300, -40], [300, 300, 40], (12, 3))
    >>> e1 = ExteriorOrientation(0, 0, 1000, 0.01, 0.02, 0.03)
    >>> e2 = ExteriorOrientation(400, 10, 1000, -0.02, 0.01, 0.05)
    >>> ro = relative_orientation_projective(project(P, e1, io), project(P, e2, io), io)
    >>> round(ro.b_y, 4), ro.in_front
    (0.0..., 12)
    """
    E = essential_matrix(xy1, xy2, io1, io2)
    return decompose_essential(E, xy1, xy2, io1, io2, order, system=system)


def ransac_fundamental(xy1, xy2, threshold: float, rng=0, max_trials: int = 2000,
                       confidence: float = 0.999, layout: str = "x2Fx1"):
    """F from correspondences with outliers: RANSAC over 8-point samples, Sampson distance < threshold.

    Chapter 4's name for :func:`photolib.ransac.ransac_fundamental_matrix` (the one RANSAC loop of
    the library, §5.10), with the layout of F chosen here.

    Parameters
    ----------
    xy1, xy2 : (n, 2) arrays
        Correspondences, n ≥ 9.
    threshold : float
        Sampson distance (image units) below which a match is an inlier.
    rng : int or numpy.random.Generator
        Seed or generator (deterministic by default).
    max_trials : int
        Maximum number of samples.
    confidence : float
        Probability of drawing one outlier-free sample, in (0, 1).
    layout : {"x2Fx1", "x1Fx2"}
        Layout of the result.

    Returns
    -------
    photolib.ransac.RansacResult
        ``model`` = F in the requested layout, the inlier mask, the number of samples drawn.

    Raises
    ------
    InputError
        Fewer than 9 points, a bad threshold or confidence, NaN.
    DegenerateGeometryError
        Every sample degenerate.
    ConvergenceError
        No consensus.

    References
    ----------
    Chibunichev (2022), §4.4; Hartley & Zisserman, Multiple View Geometry (2003), §11.6.

    Examples
    --------
    >>> from photolib.synthetic import stereo_pair
    >>> p = stereo_pair(30, seed=0, angle_spread_deg=2.0, sigma=0.002)
    >>> xy2 = p.xy2.copy(); xy2[:3] += 5.0
    >>> r = ransac_fundamental(p.xy1, xy2, threshold=0.02)
    >>> int(r.inliers.sum()), bool(r.inliers[:3].any())
    (27, False)
    """
    _check_layout(layout)
    from dataclasses import replace

    from .ransac import ransac_fundamental_matrix         # the one RANSAC loop (§5.10)
    result = ransac_fundamental_matrix(xy1, xy2, threshold, confidence=confidence, max_iterations=max_trials,
                                       rng=rng)
    return replace(result, model=_layout(result.model, layout))


# --- plane-to-plane homography -------------------------------------------------------------------------
def apply_homography(H, xy) -> np.ndarray:
    """x′ = (h₁x + h₂y + h₃)/(h₇x + h₈y + 1), y′ = (h₄x + h₅y + h₆)/(h₇x + h₈y + 1) (H 3×3 or h₁…h₈).

    Parameters
    ----------
    H : (3, 3) array or (8,) array
        The homography.
    xy : (n, 2) array
        Points of the source plane.

    Returns
    -------
    (n, 2) ndarray
        Points of the destination plane.

    Raises
    ------
    InputError
        Bad shapes, NaN/inf.
    DegenerateGeometryError
        A singular (zero, rank-deficient) H; a point mapped to infinity.

    References
    ----------
    Chibunichev (2022), §1.7, eq. (1.7.5); §4 (plane-to-plane projective transformation).

    Examples
    --------
    >>> apply_homography(np.diag([2.0, 3.0, 1.0]), [[1.0, 1.0]])
    array([[2., 3.]])
    """
    H = np.asarray(H, dtype=float)
    if H.shape == (8,):
        H = np.append(H, 1.0).reshape(3, 3)
    H = _matrix3(H, "H")
    if abs(np.linalg.det(H)) <= 1e-12 * max(np.abs(H).max(), np.finfo(float).tiny) ** 3:
        raise DegenerateGeometryError("H is singular (zero or rank-deficient): it is not a projective transformation")
    h = _homogeneous(as_points(xy, 2, "plane coordinates")) @ H.T
    if np.any(np.abs(h[:, 2]) < 1e-15 * np.abs(h).max()):
        raise DegenerateGeometryError("a point is mapped to infinity (on the vanishing line)")
    return h[:, :2] / h[:, 2:]


def _check_plane_points(src, dst):
    src, dst = as_point_pairs(src, 2, dst, 2, ("source points", "destination points"), 4,
                              "a projective (8-parameter) transformation")
    for pts, what in ((src, "source"), (dst, "destination")):
        c = pts - pts.mean(axis=0)
        s = np.linalg.svd(c, compute_uv=False)
        if s[1] <= 1e-9 * s[0]:
            raise DegenerateGeometryError(f"the {what} points are collinear: the homography is not determined")
    return src, dst


def homography_dlt(src, dst) -> np.ndarray:
    """Plane-to-plane homography (8 parameters, h₃₃ = 1) by the normalised linear DLT, ≥ 4 points.

    Parameters
    ----------
    src, dst : (n, 2) arrays
        Corresponding points, n ≥ 4, no three collinear.

    Returns
    -------
    (3, 3) ndarray
        H with h₃₃ = 1.

    Raises
    ------
    InputError
        Fewer than 4 points, bad shapes, NaN.
    DegenerateGeometryError
        Collinear points, h₃₃ = 0.

    References
    ----------
    Chibunichev (2022), §1.7, eq. (1.7.5); Hartley & Zisserman, Multiple View Geometry (2003), §4.1.

    Examples
    --------
    >>> src = np.array([[0.0, 0], [1, 0], [1, 1], [0, 1]])
    >>> homography_dlt(src, 2 * src + 1).round(9) + 0.0
    array([[2., 0., 1.],
           [0., 2., 1.],
           [0., 0., 1.]])
    """
    src, dst = _check_plane_points(src, dst)
    T1, T2 = normalizing_transform(src), normalizing_transform(dst)
    s = _homogeneous(src) @ T1.T
    d = _homogeneous(dst) @ T2.T
    n = len(src)
    A = np.zeros((2 * n, 9))
    A[0::2, 0:3] = s
    A[0::2, 6:9] = -d[:, :1] * s
    A[1::2, 3:6] = s
    A[1::2, 6:9] = -d[:, 1:2] * s
    h, sv = _null_vector(A)
    if sv[7] <= 1e-12 * sv[0]:
        raise DegenerateGeometryError("the points leave the homography undetermined (three of them collinear?)")
    H = np.linalg.solve(T2, h.reshape(3, 3)) @ T1
    if abs(H[2, 2]) < 1e-12 * np.abs(H).max():
        raise DegenerateGeometryError("h₃₃ = 0: the source origin maps to infinity; the 8-parameter form fails")
    return H / H[2, 2]


@dataclass(repr=False)
class HomographyResult:
    """Least-squares homography: H (h₃₃ = 1) and the adjustment (μ, m_h, r_ij, residuals in dst units)."""

    H: np.ndarray
    adjustment: Adjustment

    @property
    def residuals(self) -> np.ndarray:
        """Residuals (n, 2) in the units of the destination coordinates."""
        return self.adjustment.residuals.reshape(-1, 2)

    def __repr__(self) -> str:
        rms = float(np.sqrt(np.mean(self.residuals ** 2)))
        rows = "; ".join(" ".join(f"{v:.6g}" for v in row) for row in self.H)
        return (f"HomographyResult: H = [{rows}]\n"
                f"  μ = {self.adjustment.mu:.3g}, r.m.s. residual {rms:.3g}, {self.adjustment.iterations} iterations")


def homography_lsq(src, dst, H0=None, weights=None, tol: float = 1e-12, max_iter: int = 50) -> HomographyResult:
    """Homography by iterated least squares on the destination coordinates (Gauss–Newton of §1.8).

    The residuals F_x = (h₁x + h₂y + h₃)/(h₇x + h₈y + 1) − x′ (and F_y) and their partial
    derivatives come from :func:`photolib.derivations.homography_model`.

    Parameters
    ----------
    src, dst : (n, 2) arrays
        Corresponding points, n ≥ 4.
    H0 : (3, 3) or (8,) array, optional
        Start; :func:`homography_dlt` by default.
    weights : (n,) or (n, 2) array, optional
        Weights per point or per coordinate.
    tol, max_iter
        Convergence tolerance and iteration limit.

    Returns
    -------
    HomographyResult
        H (h₃₃ = 1) and the adjustment.

    Raises
    ------
    InputError
        Bad shapes, NaN in the points or in H0, bad weights.
    DegenerateGeometryError
        Collinear points, h₃₃ = 0 in H0.
    ConvergenceError
        No convergence within ``max_iter``.

    References
    ----------
    Chibunichev (2022), §1.7, eq. (1.7.5); §1.8, eqs. (1.8.5)–(1.8.10).

    Examples
    --------
    >>> src = np.array([[0.0, 0], [1, 0], [1, 1], [0, 1], [0.5, 0.2]])
    >>> homography_lsq(src, 2 * src + 1).H.round(9) + 0.0
    array([[2., 0., 1.],
           [0., 2., 1.],
           [0., 0., 1.]])
    """
    from . import derivations

    src, dst = _check_plane_points(src, dst)
    n = len(src)
    if H0 is None:
        H0 = homography_dlt(src, dst)
    H0 = np.asarray(H0, dtype=float)
    if H0.shape not in ((3, 3), (8,)):
        raise InputError(f"H0 must be a 3×3 matrix or h₁…h₈, got shape {H0.shape}")
    if not np.all(np.isfinite(H0)):
        raise InputError("H0 contains NaN or inf")
    if H0.shape == (3, 3) and abs(H0[2, 2]) < 1e-12 * np.abs(H0).max():
        raise DegenerateGeometryError("H0 has h₃₃ = 0: the 8-parameter form (h₃₃ = 1) cannot represent it")
    h0 = (H0 / H0[2, 2]).ravel()[:8] if H0.shape == (3, 3) else H0
    P = point_weights(weights, n)
    residual_fn, jacobian_fn = derivations.homography_model().compile()
    data = (src[:, 0], src[:, 1], dst[:, 0], dst[:, 1])

    def linearize(h):
        F = residual_fn(*h, *data)                       # (2, n)
        J = jacobian_fn(*h, *data)                       # (16, n)
        B = np.empty((2 * n, 8))
        B[0::2] = J[:8].T
        B[1::2] = J[8:].T
        return B, F.T.ravel()

    adj = gauss_newton(linearize, h0, P, tol=tol * np.maximum(1.0, np.abs(h0)), max_iter=max_iter,
                       names=HOMOGRAPHY_NAMES)
    return HomographyResult(np.append(adj.x, 1.0).reshape(3, 3), adj)
