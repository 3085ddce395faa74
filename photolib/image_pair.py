"""Theory of a pair of frame images — Chapter 2, §2.1–§2.13.

The module follows the chapter's order:

* §2.1 stereoscopic vision: :func:`convergence_angle` (2.1.1), :func:`depth_change` (2.1.3),
  :func:`stereo_vision_radius` (the inline radius of unaided stereo vision) and
  :func:`plasticity_coefficient` (ω = BV/b).
* §2.3 parallaxes of corresponding points: :func:`parallaxes` (p = x₁ − x₂, q = y₁ − y₂).
* §2.4 space forward intersection: :func:`image_rays` (2.4.4), :func:`intersection_scale`
  (2.4.7), (2.4.11), (2.4.12), :func:`forward_intersection` (2.4.4), and the least-squares
  intersection of two or more rays :func:`intersect_rays` (collinearity (1.8.2) with X, Y, Z unknown).
* §2.5 the normal ("ideal") case: :func:`normal_case_intersection` (2.5.1), (2.5.3)/(2.5.4).
* §2.7–§2.8 relative orientation: :func:`coplanarity` (2.7.3), :func:`y_parallax` (2.8.2),
  :func:`relative_orientation` ((2.7.4)/(2.7.5) by the correction equations (2.8.1)).
* §2.9 model construction: :func:`build_model`.
* §2.10–§2.11 exterior orientation of the model (7-element spatial similarity):
  :class:`SimilarityTransform` (2.10.4), :func:`similarity_closed_form` (a closed-form start,
  Umeyama's method), :func:`absolute_orientation` ((2.11.1)/(2.11.2) by least squares).
* §2.12 exterior orientation of the images: :func:`image_orientation_from_model` (2.12.1), (2.12.2).
* §2.13 a-priori accuracy of a normal-case pair: :func:`photo_base`, :func:`normal_case_accuracy`
  (2.13.1)–(2.13.3).

Hanzl, Fotogrammetrie, Modul 01, §3 "Orientation and point determination from two images" (seed 002
lines 344–674) adds his formulations: the closed-form intersection with known orientation
:func:`intersection_known_eo` (§3.1), the counts of the joint orientation :func:`orientation_counts`
(§3.2.2), the first-order y-parallax relative orientation :func:`relative_orientation_parallax`
(§3.2.3.1) and the model deformation :func:`model_deformation` (§3.2.3.2).

Conventions are those of Chapter 1: image coordinates and f in mm, object (and model)
coordinates in m, angles in radians; the ray of an image point is (x − x₀, y − y₀, −f) (1.2.1)
and A maps camera → object. Every rotation is built with an explicit sequence ``order``
(``"kaw"`` = (1.3.5), the book's examples; ``"wak"`` = (1.3.2)). All partial derivatives come from
the sympy models in :mod:`photolib.derivations`; all adjustments are solved by :mod:`photolib.lsq`.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass, field

import numpy as np

from . import derivations
from .camera import ExteriorOrientation, InteriorOrientation, as_points, correct_distortion, image_vector
from .derivations import parallax as _parallax
from .errors import ConvergenceError, DegenerateGeometryError, InputError, PointBehindCameraError
from .lsq import Adjustment, gauss_newton
from .rotation import DEFAULT_ORDER, check_order, rotation_angles, rotation_matrix

__all__ = ["RHO_SECONDS", "RO_NAMES", "SIMILARITY_NAMES", "convergence_angle", "depth_change",
           "stereo_vision_radius", "plasticity_coefficient", "parallaxes", "image_rays", "intersection_scale",
           "forward_intersection", "intersect_rays", "normal_case_intersection", "coplanarity", "y_parallax",
           "RelativeOrientation", "relative_orientation", "build_model", "SimilarityTransform",
           "similarity_closed_form", "absolute_orientation", "image_orientation_from_model",
           "double_resection", "photo_base", "normal_case_accuracy", "intersection_known_eo", "orientation_counts",
           "relative_orientation_parallax", "model_deformation"]

RHO_SECONDS = 180 * 3600 / np.pi
"""ρ″ = 206 264.8″ per radian (the book rounds it to 200 000″ in §2.1)."""

_PARALLEL = 1e-10   # sin of the angle between two rays below which they count as parallel


def _check_type(value, cls, what: str):
    """Raise :class:`InputError` naming the expected type unless ``value`` is a ``cls``."""
    if not isinstance(value, cls):
        raise InputError(f"{what} must be a {cls.__name__}, got {type(value).__name__}")
    return value


def _numbers(value, what: str, positive: bool = False) -> np.ndarray:
    """Finite numbers (a scalar or an array) as floats; ``positive`` also refuses values ≤ 0."""
    if isinstance(value, (str, bytes)):
        raise InputError(f"{what} must be a number, got a string")
    try:
        arr = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise InputError(f"{what} must be a number or an array of numbers, got {type(value).__name__}") from None
    if not np.all(np.isfinite(arr)):
        raise InputError(f"{what} contains NaN or inf")
    if positive and np.any(arr <= 0):
        raise InputError(f"{what} must be positive")
    return arr


# --- §2.1 stereoscopic vision --------------------------------------------------------------------
def convergence_angle(b, L):
    """γ_F = b/L (2.1.1): convergence angle (rad) of the eye base b at distance L.

    Parameters
    ----------
    b : float or array
        Eye (or instrument) base, positive.
    L : float or array
        Distance to the object, positive, in the unit of ``b``.

    Returns
    -------
    float or ndarray
        The convergence angle in radians.

    Raises
    ------
    InputError
        NaN, inf, non-positive values or non-numbers.

    References
    ----------
    Chibunichev (2022), §2.1, eq. (2.1.1).

    Examples
    --------
    >>> float(convergence_angle(0.065, 10.0))
    0.0065
    """
    return _numbers(b, "the eye base b", positive=True) / _numbers(L, "the distance L", positive=True)


def depth_change(b, L, d_gamma):
    """ΔL = −L²Δγ/b (2.1.3): change of distance for a change Δγ (rad) of the parallactic angle.

    Parameters
    ----------
    b : float
        Eye base (positive).
    L : float or array
        Distance (positive), in the unit of ``b``.
    d_gamma : float or array
        Change Δγ of the parallactic angle (rad).

    Returns
    -------
    float or ndarray
        ΔL in the unit of ``b``.

    Raises
    ------
    InputError
        NaN, inf, a non-positive base or distance.

    References
    ----------
    Chibunichev (2022), §2.1, eqs. (2.1.2), (2.1.3).

    Examples
    --------
    >>> round(float(depth_change(0.065, 10.0, 1e-4)), 4)
    -0.1538
    """
    b = _numbers(b, "the eye base b", positive=True)
    return -_numbers(L, "the distance L", positive=True) ** 2 * _numbers(d_gamma, "Δγ") / b


def stereo_vision_radius(b, gamma_min_arcsec=30.0, rho=RHO_SECONDS, B=None, V=1.0):
    """Radius of stereo vision R = b·ρ″/γ_min (from (2.1.1) with γ = γ_min), §2.1.

    ``b`` eye base (result in the same unit), ``gamma_min_arcsec`` the stereo acuity in
    arcseconds (30″ of the first kind). With an instrument of base ``B`` and magnification
    ``V`` the radius grows by the plasticity coefficient ω = BV/b. The book evaluates
    R = 65 mm × 200 000″/30″ and prints 430 m: it rounds ρ″ to 200 000″ (pass ``rho=2e5``);
    with ρ″ = 206 264.8″ the radius is 447 m.

    Parameters
    ----------
    b : float
        Eye base.
    gamma_min_arcsec : float
        Stereo acuity γ_min (″).
    rho : float
        ρ″, arcseconds per radian.
    B, V : float, optional
        Base and magnification of an instrument.

    Returns
    -------
    float
        R in the unit of ``b``.

    Raises
    ------
    InputError
        NaN, inf or non-positive values.

    References
    ----------
    Chibunichev (2022), §2.1, eq. (2.1.1).

    Examples
    --------
    >>> round(float(stereo_vision_radius(0.065, rho=2e5)))
    433
    """
    R = (_numbers(b, "the eye base b", positive=True) * _numbers(rho, "ρ″", positive=True)
         / _numbers(gamma_min_arcsec, "γ_min", positive=True))
    if B is not None:
        R = R * plasticity_coefficient(b, B, V)
    return R


def plasticity_coefficient(b, B, V=1.0):
    """ω = BV/b (§2.1): factor by which an instrument of base B and magnification V extends R.

    Parameters
    ----------
    b : float
        Eye base.
    B : float
        Base of the instrument, in the unit of ``b``.
    V : float
        Magnification.

    Returns
    -------
    float
        The plasticity coefficient ω.

    Raises
    ------
    InputError
        NaN, inf or non-positive values.

    References
    ----------
    Chibunichev (2022), §2.1.

    Examples
    --------
    >>> float(plasticity_coefficient(0.065, 0.13, 8.0))
    16.0
    """
    return (_numbers(B, "the instrument base B", positive=True) * _numbers(V, "the magnification V", positive=True)
            / _numbers(b, "the eye base b", positive=True))


# --- §2.3 parallaxes -------------------------------------------------------------------------------
def parallaxes(xy1, xy2):
    """x-parallax p = x₁ − x₂ and y-parallax q = y₁ − y₂ of corresponding points (§2.3).

    Parameters
    ----------
    xy1, xy2 : (n, 2) arrays
        Coordinates of the same points on images 1 and 2 (mm).

    Returns
    -------
    p, q : (n,) arrays
        The parallaxes (mm).

    Raises
    ------
    InputError
        Wrong shapes, different point counts, NaN/inf.

    References
    ----------
    Chibunichev (2022), §2.3.

    Examples
    --------
    >>> p, q = parallaxes([[10.0, 5.0]], [[-30.0, 4.5]])
    >>> float(p[0]), float(q[0])
    (40.0, 0.5)
    """
    xy1 = as_points(xy1, 2, "image-1 coordinates")
    xy2 = as_points(xy2, 2, "image-2 coordinates")
    _same_length(xy1, xy2)
    d = xy1 - xy2
    return d[:, 0], d[:, 1]


def _same_length(a, b, what="corresponding points"):
    if len(a) != len(b):
        raise InputError(f"{what}: image 1 has {len(a)} points, image 2 has {len(b)}")


# --- §2.4 forward intersection ---------------------------------------------------------------------
def image_rays(xy, eo: ExteriorOrientation, io: InteriorOrientation, distortion: bool = True) -> np.ndarray:
    """(X′, Y′, Z′)ᵀ = A(x − x₀, y − y₀, −f)ᵀ of (2.4.4): image rays in the object frame, one row per point.

    Parameters
    ----------
    xy : (n, 2) array
        Image coordinates (mm).
    eo : ExteriorOrientation
        Exterior orientation of the image (A maps camera → object axes).
    io : InteriorOrientation
        Interior orientation.
    distortion : bool
        Correct the distortion (1.2.2) first, if ``io`` has coefficients.

    Returns
    -------
    (n, 3) ndarray
        The rays (mm).

    Raises
    ------
    InputError
        Wrong shapes, NaN/inf, orientations of the wrong type.

    References
    ----------
    Chibunichev (2022), §2.4, eq. (2.4.4); §1.2, eq. (1.2.1).

    Examples
    --------
    >>> from photolib.camera import ExteriorOrientation, InteriorOrientation
    >>> image_rays([[10.0, 5.0]], ExteriorOrientation(0, 0, 1000), InteriorOrientation(100.0))
    array([[  10.,    5., -100.]])
    """
    _check_type(io, InteriorOrientation, "io")
    return image_vector(xy, io, distortion) @ _check_type(eo, ExteriorOrientation, "eo").matrix.T


def intersection_scale(B, r1, r2, *, method: str = "closest", formula: int | None = None) -> np.ndarray:
    """The scalar N of (2.4.3) that puts the object point on ray 1: R_M = R_S1 + N·r₁.

    It follows from N(r₁ × r₂) = B × r₂ (2.4.7). ``method``:

    * ``"norm"`` — (2.4.11), the ratio of the norms |B × r₂|/|r₁ × r₂| (2.4.10); the book's
      formula gives |N| only, the sign is taken from (B × r₂)·(r₁ × r₂).
    * ``"component"`` — (2.4.12), a ratio of components of the two cross products. By default
      each point uses the component of r₁ × r₂ of largest magnitude, so no division is by a
      near-zero number; ``formula=1, 2, 3`` forces the first, second or third formula of (2.4.12)
      (for a base along X the first has 0/0 form and the third fails for y ≈ 0; the second is (2.5.1)).
    * ``"closest"`` (default) — N = (B × r₂)·(r₁ × r₂)/|r₁ × r₂|², the least-squares solution of
      (2.4.7): the point of ray 1 nearest to ray 2. All three agree when the rays intersect.

    Parameters
    ----------
    B : 3-vector or (n, 3) array
        The base (2.4.9), one for all points or one per point.
    r1, r2 : (n, 3) arrays
        Rays of images 1 and 2 in the object frame.
    method : {"closest", "norm", "component"}
        See above.
    formula : {None, 1, 2, 3}
        The formula of (2.4.12) for ``method="component"``.

    Returns
    -------
    (n,) ndarray
        N for every point.

    Raises
    ------
    InputError
        Wrong shapes, NaN/inf, an unknown method or formula.
    DegenerateGeometryError
        Zero base, parallel rays, a forced formula that divides by ≈ 0.

    References
    ----------
    Chibunichev (2022), §2.4, eqs. (2.4.3), (2.4.7)–(2.4.12); §2.5, eq. (2.5.1).

    Examples
    --------
    >>> float(intersection_scale([400.0, 0, 0], [[0.0, 0, -100]], [[-40.0, 0, -100]])[0])
    10.0
    """
    r1 = as_points(r1, 3, "rays of image 1")
    r2 = as_points(r2, 3, "rays of image 2")
    _same_length(r1, r2, "rays")
    B = _numbers(B, "the base")
    if B.shape not in ((3,), r1.shape):
        raise InputError(f"the base: expected a 3-vector or one per point {r1.shape}, got shape {B.shape}")
    B = np.broadcast_to(B, r1.shape)
    if np.any(np.linalg.norm(B, axis=1) == 0):
        raise DegenerateGeometryError("the base is zero: both projection centres coincide")
    c = np.cross(r1, r2)          # left side of (2.4.8)
    d = np.cross(B, r2)           # right side of (2.4.8)
    c_norm = np.linalg.norm(c, axis=1)
    sin_angle = c_norm / (np.linalg.norm(r1, axis=1) * np.linalg.norm(r2, axis=1))
    if np.any(sin_angle < _PARALLEL):
        bad = np.flatnonzero(sin_angle < _PARALLEL).tolist()
        raise DegenerateGeometryError(f"the rays of points {bad} are parallel; they do not intersect")
    if method == "closest":
        return np.einsum("ij,ij->i", d, c) / c_norm ** 2
    if method == "norm":                                                   # (2.4.11)
        return np.sign(np.einsum("ij,ij->i", d, c)) * np.linalg.norm(d, axis=1) / c_norm
    if method == "component":                                              # (2.4.12)
        if formula is None:
            k = np.argmax(np.abs(c), axis=1)
        elif formula in (1, 2, 3):
            k = np.full(len(c), formula - 1)
            small = np.abs(c[np.arange(len(c)), k]) < _PARALLEL * c_norm
            if np.any(small):
                raise DegenerateGeometryError(
                    f"formula {formula} of (2.4.12) divides by ~0 for points {np.flatnonzero(small).tolist()}; "
                    "use formula=None to pick the well-conditioned component")
        else:
            raise InputError("formula must be None, 1, 2 or 3 (the three ratios of (2.4.12))")
        rows = np.arange(len(c))
        return d[rows, k] / c[rows, k]
    raise InputError(f"unknown method {method!r}; use 'closest', 'norm' or 'component'")


def forward_intersection(xy1, xy2, eo1: ExteriorOrientation, eo2: ExteriorOrientation,
                         io1: InteriorOrientation, io2: InteriorOrientation | None = None, *,
                         method: str = "closest", formula: int | None = None) -> np.ndarray:
    """Object points from a pair with known orientation, closed form (2.4.4), (2.4.9)–(2.4.12).

    X = X_S1 + N·X′₁ etc. (2.4.4), with the rays of (2.4.4), the base (2.4.9) and N from
    :func:`intersection_scale` (``method``/``formula`` as there). The point lies on ray 1, as
    in the book; with noisy data use :func:`intersect_rays` for the least-squares point.

    Parameters
    ----------
    xy1, xy2 : (n, 2) arrays
        Corresponding image coordinates (mm).
    eo1, eo2 : ExteriorOrientation
        Exterior orientation of the images.
    io1, io2 : InteriorOrientation
        Interior orientation (``io2`` defaults to ``io1``).
    method, formula
        As in :func:`intersection_scale`.

    Returns
    -------
    (n, 3) ndarray
        Object coordinates X, Y, Z (m).

    Raises
    ------
    InputError
        Wrong shapes or types, NaN/inf.
    DegenerateGeometryError
        Zero base, parallel rays.
    PointBehindCameraError
        A point behind camera 1 (N ≤ 0) or behind camera 2; ``points`` lists them.

    References
    ----------
    Chibunichev (2022), §2.4, eqs. (2.4.4), (2.4.9)–(2.4.12).

    Examples
    --------
    >>> from photolib.camera import ExteriorOrientation, InteriorOrientation
    >>> io = InteriorOrientation(100.0)
    >>> e1, e2 = ExteriorOrientation(0, 0, 1000), ExteriorOrientation(400, 0, 1000)
    >>> forward_intersection([[20.0, 10.0]], [[-20.0, 10.0]], e1, e2, io)
    array([[ 200.,  100.,    0.]])
    """
    io2 = io1 if io2 is None else io2
    _check_type(eo1, ExteriorOrientation, "eo1")
    _check_type(eo2, ExteriorOrientation, "eo2")
    xy1 = as_points(xy1, 2, "image-1 coordinates")
    xy2 = as_points(xy2, 2, "image-2 coordinates")
    _same_length(xy1, xy2)
    r1, r2 = image_rays(xy1, eo1, io1), image_rays(xy2, eo2, io2)
    B = eo2.center - eo1.center                                               # (2.4.9)
    N = intersection_scale(B, r1, r2, method=method, formula=formula)
    if np.any(N <= 0):
        bad = np.flatnonzero(N <= 0)
        raise PointBehindCameraError(f"the rays of points {bad.tolist()} meet behind camera 1 (N ≤ 0)", points=bad)
    points = eo1.center + N[:, None] * r1                                     # (2.4.4)
    behind2 = np.einsum("ij,ij->i", points - eo2.center, r2) <= 0
    if np.any(behind2):
        bad = np.flatnonzero(behind2)
        raise PointBehindCameraError(f"points {bad.tolist()} lie behind camera 2: the rays meet on the wrong side "
                                     "of the second projection centre", points=bad)
    return points


@dataclass(repr=False)
class RayIntersection:
    """Least-squares intersection of rays: points and their a-posteriori accuracy (1.8.8)–(1.8.9).

    Attributes
    ----------
    points : (n, 3) array
        X, Y, Z (m).
    mu : (n,) array
        μ of each point (mm, the unit of the image residuals); NaN without redundancy.
    std : (n, 3) array
        m_X, m_Y, m_Z (m).
    residuals : (n, n_images, 2) array
        Image residuals v_x, v_y (mm).
    iterations : (n,) array
        Iterations made for each point.

    References
    ----------
    Chibunichev (2022), §2.4; §1.8, eqs. (1.8.2), (1.8.8), (1.8.9).

    Examples
    --------
    >>> import numpy as np
    >>> r = RayIntersection(np.zeros((1, 3)), np.array([0.002]), np.full((1, 3), 0.05), np.zeros((1, 2, 2)), np.array([3]))
    >>> print(r)
    RayIntersection of 1 point from 2 images
      point 0: X = 0.000 m, Y = 0.000 m, Z = 0.000 m (m_X, m_Y, m_Z = 0.050, 0.050, 0.050 m; μ = 2.0 µm)
    """

    points: np.ndarray        # (n, 3) X, Y, Z
    mu: np.ndarray            # (n,) μ of each point (mm, the unit of the image residuals)
    std: np.ndarray           # (n, 3) m_X, m_Y, m_Z
    residuals: np.ndarray     # (n, n_images, 2) image residuals v_x, v_y (mm)
    iterations: np.ndarray    # (n,)

    def __repr__(self) -> str:
        n, k = len(self.points), self.residuals.shape[1] if self.residuals.ndim == 3 else 0
        lines = [f"RayIntersection of {n} point{'s' if n != 1 else ''} from {k} images"]
        for i in range(min(n, 5)):
            X, Y, Z = self.points[i]
            sx, sy, sz = self.std[i]
            lines.append(f"  point {i}: X = {X:.3f} m, Y = {Y:.3f} m, Z = {Z:.3f} m "
                         f"(m_X, m_Y, m_Z = {sx:.3f}, {sy:.3f}, {sz:.3f} m; μ = {1000 * self.mu[i]:.1f} µm)")
        if n > 5:
            lines.append(f"  … {n - 5} more")
        return "\n".join(lines)


def intersect_rays(xy_list, eo_list, io_list, weights=None, tol: float = 1e-9,
                   max_iter: int = 20) -> RayIntersection:
    """Least-squares forward intersection of two or more rays per point (§2.4, (1.8.2)).

    The unknowns are the object coordinates X, Y, Z of each point; every image contributes the
    two collinearity equations F_x, F_y of (1.8.2) (sympy model
    :func:`photolib.derivations.intersection_model`). Each point is adjusted on its own by the
    engine of §1.8, starting from the closed form (2.4.4) of the first two images.

    Parameters
    ----------
    xy_list : sequence of (n, 2) arrays
        Measured coordinates of the same n points on each image (mm), at least two images.
    eo_list, io_list : sequences
        Exterior and interior orientation of each image (``io_list`` may be a single
        :class:`InteriorOrientation` shared by all images).
    weights : array (n_images,), optional
        Weight of each image's coordinates (p = 1/m²); unit weights by default.
    tol, max_iter
        Convergence tolerance (m) and iteration limit.

    Returns
    -------
    RayIntersection
        Points, μ (dof = 2·n_images − 3; NaN with dof = 0), m_X, m_Y, m_Z, image residuals.

    Raises
    ------
    InputError
        Fewer than two images, mismatched counts, wrong types, NaN/inf, bad weights.
    DegenerateGeometryError
        Parallel rays, zero base of the first two images.
    PointBehindCameraError
        A point behind (or in the plane of) any camera; ``points`` lists them.
    ConvergenceError
        No convergence within ``max_iter``.

    References
    ----------
    Chibunichev (2022), §2.4; §1.8, eqs. (1.8.2), (1.8.8), (1.8.9).

    Examples
    --------
    >>> from photolib.camera import ExteriorOrientation, InteriorOrientation
    >>> io = InteriorOrientation(100.0)
    >>> e1, e2 = ExteriorOrientation(0, 0, 1000), ExteriorOrientation(400, 0, 1000)
    >>> r = intersect_rays([[[20.0, 10.0]], [[-20.0, 10.0]]], [e1, e2], io)
    >>> r.points.round(6)
    array([[200., 100.,   0.]])
    """
    k = len(xy_list)
    if k < 2 or len(eo_list) != k:
        raise InputError(f"intersection needs the coordinates and orientation of at least two images, "
                         f"got {k} coordinate sets and {len(eo_list)} orientations")
    if isinstance(io_list, InteriorOrientation):
        io_list = [io_list] * k
    if len(io_list) != k:
        raise InputError(f"{k} images but {len(io_list)} interior orientations")
    for i in range(k):
        _check_type(eo_list[i], ExteriorOrientation, f"eo_list[{i}]")
        _check_type(io_list[i], InteriorOrientation, f"io_list[{i}]")
    if weights is not None:
        w = _numbers(weights, "weights", positive=True)
        if w.shape != (k,):
            raise InputError(f"weights: expected one weight per image, shape ({k},), got {w.shape}")
    xys = [as_points(xy, 2, f"image-{i + 1} coordinates") for i, xy in enumerate(xy_list)]
    n = len(xys[0])
    if any(len(xy) != n for xy in xys):
        raise InputError("every image must give the coordinates of the same points")
    order_set = {eo.order for eo in eo_list}
    if len(order_set) != 1:   # the model has one rotation sequence; convert all to the first's
        eo_list = [eo.with_order(eo_list[0].order) for eo in eo_list]
    order = eo_list[0].order
    ideal = np.stack([correct_distortion(xy, io) if io.has_distortion else xy for xy, io in zip(xys, io_list)])
    eo_data = np.array([eo.vector for eo in eo_list]).T                          # (6, k)
    io_data = np.array([[io.f, io.x0, io.y0] for io in io_list]).T               # (3, k)
    res_fn, jac_fn = derivations.intersection_model(order).compile()
    P = None if weights is None else np.repeat(np.asarray(weights, dtype=float), 2)
    start = forward_intersection(xys[0], xys[1], eo_list[0], eo_list[1], io_list[0], io_list[1])

    points, mus, stds, resid, iters = [], [], [], [], []
    for j in range(n):
        data = (*eo_data, ideal[:, j, 0], ideal[:, j, 1], *io_data)

        def linearize(p, data=data):
            L = res_fn(*p, *data).T.reshape(-1)                                 # (F_x, F_y) per image
            B = jac_fn(*p, *data).reshape(2, 3, k).transpose(2, 0, 1).reshape(2 * k, 3)
            return B, L

        adj = gauss_newton(linearize, start[j], P, tol=tol, max_iter=max_iter, names=("X", "Y", "Z"))
        points.append(adj.x)
        mus.append(adj.mu)
        stds.append(adj.std)
        resid.append(adj.residuals.reshape(k, 2))
        iters.append(adj.iterations)
    points = np.array(points)
    behind = np.zeros(n, bool)
    for eo in eo_list:
        behind |= ((points - eo.center) @ eo.matrix)[:, 2] >= 0       # Z* = (Aᵀ(X − S))_z < 0 in front
    if np.any(behind):
        bad = np.flatnonzero(behind)
        raise PointBehindCameraError(f"the least-squares points {bad.tolist()} lie behind (or in the plane of) "
                                     "at least one camera", points=bad)
    return RayIntersection(points, np.array(mus), np.array(stds), np.array(resid), np.array(iters))


# --- §2.5 the normal case ----------------------------------------------------------------------------
def normal_case_intersection(x1, y1, x2, f, B) -> np.ndarray:
    """Object coordinates in the normal case (2.5.3): X = (B/p)x₁, Y = (B/p)y₁, Z = −(B/p)f.

    All angles zero, base B along X, S₁ at the origin, x₀ = y₀ = 0; N = B/p with the
    x-parallax p = x₁ − x₂ (2.5.1). Equivalent form (2.5.4): X = −(Z/f)x₁, Y = −(Z/f)y₁.

    Parameters
    ----------
    x1, y1, x2 : float or arrays
        Coordinates on image 1 and abscissa on image 2 (mm).
    f : float
        Focal length (mm).
    B : float
        Base (its unit is that of the result).

    Returns
    -------
    (n, 3) ndarray
        X, Y, Z in the unit of B.

    Raises
    ------
    InputError
        NaN/inf, incompatible shapes, f ≤ 0.
    DegenerateGeometryError
        Zero x-parallax (a point at infinity, parallel rays).

    References
    ----------
    Chibunichev (2022), §2.5, eqs. (2.5.1), (2.5.3), (2.5.4).

    Examples
    --------
    >>> normal_case_intersection(20.0, 10.0, -20.0, 100.0, 400.0)
    array([[ 200.,  100., -1000.]])
    """
    x1, y1, x2 = (np.atleast_1d(_numbers(v, name)) for v, name in ((x1, "x1"), (y1, "y1"), (x2, "x2")))
    _numbers(f, "f", positive=True)
    _numbers(B, "B")
    try:
        x1, y1, x2 = np.broadcast_arrays(x1, y1, x2)
    except ValueError:
        raise InputError(f"x1, y1, x2 have incompatible shapes {x1.shape}, {y1.shape}, {x2.shape}") from None
    if not (np.all(np.isfinite(x1)) and np.all(np.isfinite(y1)) and np.all(np.isfinite(x2))
            and np.isfinite(f) and np.isfinite(B)):
        raise InputError("normal-case coordinates contain NaN or inf")
    p = x1 - x2
    if np.any(p == 0):
        raise DegenerateGeometryError(f"zero x-parallax for points {np.flatnonzero(p == 0).tolist()}: parallel rays")
    N = B / p                                                                   # (2.5.1)
    return np.column_stack([N * x1, N * y1, -N * f])                            # (2.5.3)


# --- §2.7–§2.8 relative orientation ---------------------------------------------------------------------
RO_NAMES = {"independent": ("alpha1", "kappa1", "omega2", "alpha2", "kappa2"),
            "dependent": ("b_y", "b_z", "omega2", "alpha2", "kappa2")}
"""Names of the five elements of each system of §2.7 (angles of the primed model-frame rotations)."""

_ALL_RO = ("b_y", "b_z", "omega1", "alpha1", "kappa1", "omega2", "alpha2", "kappa2")


def coplanarity(base, r1, r2) -> np.ndarray:
    """φ = det[[b_x, b_y, b_z], [X′₁, Y′₁, Z′₁], [X′₂, Y′₂, Z′₂]] = b·(r₁ × r₂), (2.7.1)–(2.7.3).

    Zero when the base and both rays are coplanar.

    Parameters
    ----------
    base : 3-vector
        The base (b_x, b_y, b_z).
    r1, r2 : (n, 3) arrays
        Rays of the two images in the model frame.

    Returns
    -------
    (n,) ndarray
        φ for each pair of rays.

    Raises
    ------
    InputError
        Wrong shapes, different ray counts, NaN/inf.

    References
    ----------
    Chibunichev (2022), §2.7, eqs. (2.7.1)–(2.7.3).

    Examples
    --------
    >>> coplanarity([1.0, 0, 0], [[0.1, 0.05, -1]], [[-0.3, 0.05, -1]])
    array([0.])
    """
    r1 = as_points(r1, 3, "rays of image 1")
    r2 = as_points(r2, 3, "rays of image 2")
    _same_length(r1, r2, "rays")
    return np.cross(r1, r2) @ _base_vector(base)


def _base_vector(base) -> np.ndarray:
    b = np.asarray(base, dtype=float)
    if b.shape != (3,):
        raise InputError(f"the base must be a 3-vector, got shape {b.shape}")
    if not np.all(np.isfinite(b)):
        raise InputError("the base contains NaN or inf")
    return b


def y_parallax(base, r1, r2, f) -> np.ndarray:
    """Residual y-parallax q = −f/(b Z′₁ Z′₂)·det[[1, b_y, b_z], r₁′, r₂′] (2.8.2), b = √(1 + b_y² + b_z²).

    For b_y = b_z = 0 this is exactly y₁ⁿ − y₂ⁿ, the difference of the ordinates of the two
    points in the normal case (yⁿ = −f Y′/Z′); for a tilted base it is an approximation.

    Parameters
    ----------
    base : 3-vector
        (1, b_y, b_z) (any multiple with b_x ≠ 0).
    r1, r2 : (n, 3) arrays
        Rays in the model frame.
    f : float
        Focal length (mm).

    Returns
    -------
    (n,) ndarray
        q (mm).

    Raises
    ------
    InputError
        Wrong shapes, NaN/inf, f ≤ 0.
    DegenerateGeometryError
        b_x = 0 or a ray with Z′ = 0.

    References
    ----------
    Chibunichev (2022), §2.8, eq. (2.8.2).

    Examples
    --------
    >>> y_parallax([1.0, 0, 0], [[10.0, 5.0, -100]], [[-30.0, 4.0, -100]], 100.0)
    array([1.])
    """
    base = _base_vector(base)
    r1 = as_points(r1, 3, "rays of image 1")
    r2 = as_points(r2, 3, "rays of image 2")
    if not (np.isscalar(f) or np.ndim(f) == 0) or not np.isfinite(f) or f <= 0:
        raise InputError(f"f must be a positive finite number, got {f!r}")
    if base[0] == 0:
        raise DegenerateGeometryError("b_x = 0: the y-parallax (2.8.2) is defined for a base (1, b_y, b_z)")
    if np.any(r1[:, 2] == 0) or np.any(r2[:, 2] == 0):
        raise DegenerateGeometryError("a ray is parallel to the model XY plane (Z' = 0): (2.8.2) divides by Z'")
    b = np.linalg.norm(base) / abs(base[0])
    return -f / (b * r1[:, 2] * r2[:, 2]) * coplanarity(base / base[0], r1, r2)


@dataclass(repr=False)
class RelativeOrientation:
    """Elements of relative orientation of a pair (§2.7) and the accuracy of their adjustment (§2.8).

    The one relative-orientation result of photolib: :func:`relative_orientation` (the
    coplanarity adjustment of §2.8) and :func:`photolib.projective.decompose_essential` (the
    closed form from E, §4.4) both return it.

    Attributes
    ----------
    system : {"dependent", "independent"}
        The system of §2.7 the five elements belong to, (2.7.5) or (2.7.4).
    order : {"kaw", "wak"}
        Rotation sequence of the primed angles.
    b_y, b_z : float
        B_Y/B_X and B_Z/B_X of the base (0 in the independent system).
    omega1, alpha1, kappa1, omega2, alpha2, kappa2 : float
        Angles (rad) of A′₁ and A′₂ (image → model frame); the three the system fixes are 0.
    q : (n,) array
        Residual y-parallaxes (2.8.2), mm.
    adjustment : Adjustment or None
        μ (mm², the unit of φ), Q, m_j and r_ij of the five elements in the order of
        :data:`RO_NAMES`; None for a closed-form result (§4.4).
    base_sign : float
        Sign of B_X: +1 when image 2 lies along +X_M (the book's case), −1 otherwise.
    in_front : int or None
        Number of points in front of both cameras (cheirality test), where counted.
    n_points : int or None
        Number of corresponding points used.

    References
    ----------
    Chibunichev (2022), §2.7, eqs. (2.7.3)–(2.7.5); §2.8, eqs. (2.8.1), (2.8.2); §4.4.

    Examples
    --------
    >>> import numpy as np
    >>> ro = RelativeOrientation("dependent", "kaw", 0.01, -0.02, 0, 0, 0, 0.001, 0.002, 0.003, q=np.zeros(6))
    >>> ro.base
    array([ 1.  ,  0.01, -0.02])
    >>> print(ro)
    RelativeOrientation (dependent system (2.7.5), order kaw, 6 points)
      b_y    = +0.010000
      b_z    = -0.020000
      ω′₂    = +0.0573°
      α′₂    = +0.1146°
      κ′₂    = +0.1719°
    """

    system: str
    order: str
    b_y: float
    b_z: float
    omega1: float
    alpha1: float
    kappa1: float
    omega2: float
    alpha2: float
    kappa2: float
    q: np.ndarray                 # residual y-parallaxes (2.8.2), mm
    adjustment: Adjustment | None = None
    base_sign: float = 1.0
    in_front: int | None = None
    n_points: int | None = None

    def __post_init__(self):
        if self.system not in RO_NAMES:
            raise InputError(f"unknown system {self.system!r}; use 'dependent' (2.7.5) or 'independent' (2.7.4)")
        check_order(self.order)
        values = [getattr(self, name) for name in _ALL_RO]
        try:
            finite = bool(np.all(np.isfinite(np.asarray(values, dtype=float))))
        except (TypeError, ValueError):
            finite = False
        if not finite:
            raise InputError("the elements of relative orientation must be finite numbers")
        if self.base_sign not in (1.0, -1.0):
            raise InputError(f"base_sign must be +1 or −1, got {self.base_sign!r}")

    @property
    def names(self) -> tuple:
        """Names of the five elements of the system, :data:`RO_NAMES`."""
        return RO_NAMES[self.system]

    @property
    def elements(self) -> dict:
        """The five elements of the system by name."""
        return {name: getattr(self, name) for name in self.names}

    @property
    def base(self) -> np.ndarray:
        """Base B_X·(1, b_y, b_z)/|B_X| in the model frame: (1, b_y, b_z) times the sign of B_X."""
        return self.base_sign * np.array([1.0, self.b_y, self.b_z])

    @property
    def base_direction(self) -> np.ndarray:
        """Unit vector S₁ → S₂ in the model frame."""
        b = self.base
        return b / np.linalg.norm(b)

    @property
    def by(self) -> float:
        """Alias of :attr:`b_y` (the spelling of the former §4.4 result)."""
        return self.b_y

    @property
    def bz(self) -> float:
        """Alias of :attr:`b_z` (the spelling of the former §4.4 result)."""
        return self.b_z

    @property
    def A1(self) -> np.ndarray:
        """A'₁ = A(ω'₁, α'₁, κ'₁): image 1 → model frame."""
        return rotation_matrix(self.omega1, self.alpha1, self.kappa1, self.order)

    @property
    def A2(self) -> np.ndarray:
        """A'₂ = A(ω'₂, α'₂, κ'₂): image 2 → model frame."""
        return rotation_matrix(self.omega2, self.alpha2, self.kappa2, self.order)

    @property
    def std(self) -> dict:
        """m_j (1.8.8) of the five elements by name (empty for a closed-form result)."""
        if self.adjustment is None:
            return {}
        return dict(zip(self.names, self.adjustment.std))

    def summary(self) -> str:
        """A short readable summary: the five elements (angles in degrees) with ±m_j, μ, points."""
        labels = {"b_y": "b_y", "b_z": "b_z", "omega1": "ω′₁", "alpha1": "α′₁", "kappa1": "κ′₁",
                  "omega2": "ω′₂", "alpha2": "α′₂", "kappa2": "κ′₂"}
        kind = "dependent system (2.7.5)" if self.system == "dependent" else "independent system (2.7.4)"
        n = self.n_points if self.n_points is not None else len(self.q)
        lines = [f"RelativeOrientation ({kind}, order {self.order}, {n} points)"]
        std = self.std
        for name in self.names:
            value = getattr(self, name)
            if name.startswith("b_"):
                text = f"{value:+.6f}" + (f" ± {std[name]:.6f}" if name in std else "")
            else:
                text = f"{np.degrees(value):+.4f}°" + (f" ± {np.degrees(std[name]):.4f}°" if name in std else "")
            lines.append(f"  {labels[name]:6s} = {text}")
        if self.base_sign < 0:
            lines.append("  base along −X_M (B_X < 0)")
        if self.adjustment is not None:
            lines.append(f"  μ = {self.adjustment.mu:.3g} mm², {self.adjustment.iterations} iterations")
        if self.in_front is not None:
            lines.append(f"  {self.in_front}/{n} points in front of both cameras")
        return "\n".join(lines)

    def __repr__(self) -> str:
        return self.summary()


def _first_row_rotation(v, order):
    """(α, κ) with rotation_matrix(0, α, κ, order)[0] = v (unit): the start of (2.7.4) from a base.

    With ω = 0 the first row is (cos α cos κ, −sin κ, sin α cos κ) for ``"kaw"`` and
    (cos α cos κ, −cos α sin κ, sin α) for ``"wak"`` (sympy, :func:`photolib.derivations.
    rotation_matrix_symbolic`); of the two solutions the one with cos κ ≥ 0 (kaw) or cos α ≥ 0
    (wak) is returned. When the free angle is undefined (v along the axis of the other) it is 0.
    """
    x, y, z = np.asarray(v, dtype=float) / np.linalg.norm(v)
    if order == "kaw":
        kappa = np.arctan2(-y, np.hypot(x, z))
        alpha = np.arctan2(z, x) if np.hypot(x, z) > 1e-15 else 0.0
    else:
        alpha = np.arctan2(z, np.hypot(x, y))
        kappa = np.arctan2(-y, x) if np.hypot(x, y) > 1e-15 else 0.0
    if not np.allclose(rotation_matrix(0.0, alpha, kappa, order)[0], (x, y, z), atol=1e-12):
        raise DegenerateGeometryError("the base direction cannot be reached with ω′₁ = 0 in this rotation order")
    return float(alpha), float(kappa)


def _relative_from_rotation(A2, base, xy1, xy2, io1, io2, system, order, in_front=None):
    """The RelativeOrientation of a pair given A′₂ and the base in the camera-1 frame (closed form).

    ``A2`` maps camera-2 axes to camera-1 axes, ``base`` is S₁ → S₂ in camera-1 axes. The
    dependent system (2.7.5) takes the camera-1 frame as the model frame; the independent one
    (2.7.4) turns it so that X_M runs along the base with ω′₁ = 0.
    """
    check_order(order)
    if system not in RO_NAMES:
        raise InputError(f"unknown system {system!r}; use 'dependent' (2.7.5) or 'independent' (2.7.4)")
    b = np.asarray(base, dtype=float)
    nb = np.linalg.norm(b)
    if not nb > 0:
        raise DegenerateGeometryError("the base is zero: both projection centres coincide")
    b = b / nb
    if system == "dependent":
        if abs(b[0]) < 1e-9:
            raise DegenerateGeometryError("B_X = 0: b_y = B_Y/B_X and b_z = B_Z/B_X of (2.7.5) are undefined; "
                                          "use the independent system (2.7.4)")
        values = dict(b_y=float(b[1] / b[0]), b_z=float(b[2] / b[0]), omega1=0.0, alpha1=0.0, kappa1=0.0)
        A1 = np.eye(3)
        sign = float(np.sign(b[0]))
    else:
        a1, k1 = _first_row_rotation(b, order)
        A1 = rotation_matrix(0.0, a1, k1, order)
        values = dict(b_y=0.0, b_z=0.0, omega1=0.0, alpha1=a1, kappa1=k1)
        sign = 1.0
    A2m = A1 @ A2
    w2, a2, k2 = rotation_angles(A2m, order)
    values.update(omega2=w2, alpha2=a2, kappa2=k2)
    r1, r2 = image_vector(xy1, io1), image_vector(xy2, io2)
    q = y_parallax([1.0, values["b_y"], values["b_z"]], r1 @ A1.T, r2 @ A2m.T, io1.f)
    return RelativeOrientation(system, order, **values, q=q, adjustment=None, base_sign=sign,
                               in_front=in_front, n_points=len(xy1))


def _check_spread(xy, what):
    """Raise if the points are (numerically) on one line."""
    centred = xy - xy.mean(axis=0)
    s = np.linalg.svd(centred, compute_uv=False)
    if s[0] == 0 or s[-1] < 1e-9 * s[0]:
        raise DegenerateGeometryError(f"{what} lie on one line; the problem is singular")


def _relative_orientation_inputs(xy1, xy2, io1, io2, system):
    """Checked inputs of a relative orientation: the system, the interior orientations (io2 = io1
    when None) and at least five corresponding points spread over both images."""
    if system not in RO_NAMES:
        raise InputError(f"unknown system {system!r}; use 'dependent' (2.7.5) or 'independent' (2.7.4)")
    io2 = io1 if io2 is None else io2
    _check_type(io1, InteriorOrientation, "io1")
    _check_type(io2, InteriorOrientation, "io2")
    xy1 = as_points(xy1, 2, "image-1 coordinates")
    xy2 = as_points(xy2, 2, "image-2 coordinates")
    _same_length(xy1, xy2)
    if len(xy1) < 5:
        raise InputError(f"relative orientation needs at least 5 corresponding points, got {len(xy1)}")
    _check_spread(xy1, "the points of image 1")
    _check_spread(xy2, "the points of image 2")
    return xy1, xy2, io2


def relative_orientation(xy1, xy2, io1: InteriorOrientation, io2: InteriorOrientation | None = None,
                         system: str = "dependent", order: str = DEFAULT_ORDER, initial=None,
                         weights=None, tol: float = 1e-12, max_iter: int = 50,
                         jacobian: str = "derived") -> RelativeOrientation:
    """Relative orientation of a pair by the coplanarity condition, §2.7–§2.8.

    Each pair of corresponding points gives one condition φ = 0 (2.7.3); linearised, it is the
    correction equation (2.8.1) a₁δ₁ + … + a₅δ₅ + l = v with l = φ at the approximation and the
    coefficients derived by sympy (:func:`photolib.derivations.coplanarity_model`). The system
    is iterated by least squares (§1.8) until the corrections vanish.

    Without ``initial`` the iteration starts from the closed-form solution of §4.4: the
    essential matrix by the normalised 8-point method, its decomposition with the cheirality
    test, converted to the elements of ``system`` (:func:`photolib.projective.decompose_essential`).
    So strongly convergent (terrestrial) pairs converge to the right solution. With fewer than 8
    points, or when E is undetermined (all points in one plane), the start is zero, as in the book
    (right for near-vertical pairs). After convergence the solution is checked: a zero or too short
    base, and a solution that puts most points behind a camera (a false minimum or the mirrored
    solution), raise named errors instead of returning wrong elements.

    Parameters
    ----------
    xy1, xy2 : (n, 2) arrays
        Measured coordinates of n ≥ 5 corresponding points (mm).
    io1, io2 : InteriorOrientation
        Interior orientation of the two images (``io2`` defaults to ``io1``).
    system : {"dependent", "independent"}
        ``"dependent"``: b_y, b_z, ω′₂, α′₂, κ′₂ with A′₁ = E (2.7.5); the model frame is parallel
        to the camera frame of image 1. ``"independent"``: α′₁, κ′₁, ω′₂, α′₂, κ′₂ with
        b_y = b_z = ω′₁ = 0 (2.7.4); the model X axis is along the base.
    order : {"kaw", "wak"}
        Rotation sequence of the primed angles.
    initial : array of 5, optional
        Approximate values of the elements (the closed form from E by default, see above).
    weights : array (n,), optional
        Weights of the conditions; unit weights (the book) by default.
    tol, max_iter
        Convergence tolerance and iteration limit of the engine.
    jacobian : {"derived", "printed"}
        ``"derived"`` (default): a₁…a₅ derived by sympy. ``"printed"``: the book's §2.8
        partials (:func:`photolib.derivations.printed_coplanarity_partials`; κ–α–ω only), which
        equal ∂A/∂θ·(x, y, **+f**): a sign error on every f-term. The iteration still converges
        (slowly, to nearly the same elements) but m_j and r_ij are wrong — this mode exists only
        to reproduce the published accuracy of the worked example that closes §2.12.

    Returns
    -------
    RelativeOrientation
        The elements, residual y-parallaxes q (2.8.2) (computed with f₁), the adjustment
        (μ, m_j, r_ij), the sign of B_X and the number of points in front of both cameras.

    Raises
    ------
    InputError
        Fewer than 5 points, wrong shapes or types, NaN/inf, an unknown system or jacobian.
    DegenerateGeometryError
        Collinear points; a zero or too short base (a rotation alone explains the rays).
    PointBehindCameraError
        The converged solution puts most points behind a camera.
    ConvergenceError
        No convergence within ``max_iter``.

    References
    ----------
    Chibunichev (2022), §2.7, eqs. (2.7.3)–(2.7.5); §2.8, eqs. (2.8.1), (2.8.2); §4.4.

    Examples
    --------
    >>> import numpy as np
    >>> from photolib.synthetic import stereo_pair
    >>> pair = stereo_pair(12, seed=0, angle_spread_deg=3.0)
    >>> ro = relative_orientation(pair.xy1, pair.xy2, pair.io, system="independent")
    >>> truth = pair.eo1.matrix.T @ pair.eo2.matrix
    >>> bool(np.allclose(ro.A1.T @ ro.A2, truth, atol=1e-9)), ro.in_front
    (True, 12)
    """
    check_order(order)
    xy1, xy2, io2 = _relative_orientation_inputs(xy1, xy2, io1, io2, system)
    r1, r2 = image_vector(xy1, io1), image_vector(xy2, io2)
    data = (r1[:, 0], r1[:, 1], io1.f, r2[:, 0], r2[:, 1], io2.f)
    res_fn, jac_fn = derivations.coplanarity_model(system, order).compile()
    if jacobian == "printed":
        if order != "kaw":
            raise InputError("the printed §2.8 partials are for the κ–α–ω matrix (1.3.5): use order='kaw'")
        jac_fn = derivations.printed_coplanarity_jacobian(system)
    elif jacobian != "derived":
        raise InputError(f"jacobian must be 'derived' or 'printed', got {jacobian!r}")

    def linearize(p):
        return jac_fn(*p, *data).T, res_fn(*p, *data)[0]        # (2.8.1): B rows a1..a5, L = φ

    rot_rms = _rotation_only_rms(r1, r2)
    if rot_rms < 1e-9:
        raise DegenerateGeometryError(
            "the base is zero: the rays of image 2 are those of image 1 turned by a rotation alone "
            "(both projection centres coincide), so relative orientation is not determined")
    if initial is None:
        x0, sign = _closed_form_start(xy1, xy2, io1, io2, system, order)
    else:
        x0, sign = np.asarray(initial, dtype=float), None
        if x0.shape != (5,):
            raise InputError(f"initial values: expected 5 elements, got shape {x0.shape}")
        if not np.all(np.isfinite(x0)):
            raise InputError("initial values contain NaN or inf")
    try:
        adj = gauss_newton(linearize, x0, weights, tol=tol, max_iter=max_iter, names=RO_NAMES[system])
    except ConvergenceError as exc:
        _short_base_check(rot_rms, exc)
        raise
    values = dict.fromkeys(_ALL_RO, 0.0)
    values.update(zip(RO_NAMES[system], map(float, adj.x)))
    for name in RO_NAMES[system][2 if system == "dependent" else 0:]:     # angles into (−π, π]
        if abs(values[name]) > np.pi:
            values[name] = float(np.pi - (np.pi - values[name]) % (2 * np.pi))
    A1 = rotation_matrix(values["omega1"], values["alpha1"], values["kappa1"], order)
    A2 = rotation_matrix(values["omega2"], values["alpha2"], values["kappa2"], order)
    m1, m2 = r1 @ A1.T, r2 @ A2.T
    q = y_parallax([1.0, values["b_y"], values["b_z"]], m1, m2, io1.f)   # (2.8.2)
    ro_rms = _epipolar_rms(m1, m2, np.array([1.0, values["b_y"], values["b_z"]]))
    if rot_rms <= _SHORT_BASE_RATIO * ro_rms:
        raise DegenerateGeometryError(
            f"the base is zero or too short to be determined: a rotation alone explains the rays "
            f"(r.m.s. {rot_rms:.2e} rad) about as well as relative orientation does ({ro_rms:.2e} rad)")
    front, sign = _cheirality(m1, m2, np.array([1.0, values["b_y"], values["b_z"]]), sign)
    if 2 * front <= len(xy1):
        _short_base_check(rot_rms)
        raise PointBehindCameraError(
            f"the solution puts {len(xy1) - front} of {len(xy1)} points behind a camera: the iteration ended "
            "in a false minimum or the mirrored (twisted-pair) solution; give approximate values (initial=)",
            points=np.flatnonzero(~_in_front_mask(m1, m2, sign * np.array([1.0, values["b_y"], values["b_z"]]))))
    return RelativeOrientation(system, order, **values, q=q, adjustment=adj, base_sign=sign, in_front=front,
                               n_points=len(xy1))


_SHORT_BASE_RATIO = 5.0   # rotation-only fit / coplanarity fit below which the base counts as undetermined
_SHORT_BASE_ANGLE = 1e-3  # rad: a failed iteration on rays that a rotation fits this well had no usable base


def _short_base_check(rot_rms: float, cause: Exception | None = None):
    """After a failed iteration: blame a zero or too short base when a rotation alone fits the rays."""
    if rot_rms < _SHORT_BASE_ANGLE:
        raise DegenerateGeometryError(
            f"the base is zero or too short to be determined: a rotation alone fits the rays of the two "
            f"images to {rot_rms:.2e} rad r.m.s., and the iteration of relative orientation failed") from cause


def _epipolar_rms(m1, m2, base) -> float:
    """R.m.s. angle (rad) of the rays of image 2 out of the epipolar planes (base, ray 1)."""
    b = base / np.linalg.norm(base)
    n = np.cross(b, m1)
    sin = np.einsum("ij,ij->i", n, m2) / (np.linalg.norm(n, axis=1) * np.linalg.norm(m2, axis=1))
    return float(np.sqrt(np.mean(sin ** 2)))


def _rotation_only_rms(r1, r2) -> float:
    """R.m.s. distance (rad) of the unit rays of image 1 from those of image 2 under the best rotation.

    Zero (to noise) when the two projection centres coincide: then a rotation alone maps the
    bundles onto each other and the base is not determined.
    """
    u1 = r1 / np.linalg.norm(r1, axis=1, keepdims=True)
    u2 = r2 / np.linalg.norm(r2, axis=1, keepdims=True)
    U, _, Vt = np.linalg.svd(u1.T @ u2)
    R = U @ np.diag([1.0, 1.0, np.sign(np.linalg.det(U @ Vt))]) @ Vt      # u1 ≈ R u2 (Kabsch)
    return float(np.sqrt(np.mean(np.sum((u1 - u2 @ R.T) ** 2, axis=1))))


def _in_front_mask(m1, m2, base):
    c = np.cross(m1, m2)
    cc = np.einsum("ij,ij->i", c, c)
    with np.errstate(divide="ignore", invalid="ignore"):
        N1 = np.einsum("ij,ij->i", np.cross(base, m2), c) / cc
        N2 = np.einsum("ij,ij->i", np.cross(base, m1), c) / cc
    return (N1 > 0) & (N2 > 0)


def _cheirality(m1, m2, base, sign=None):
    """Points in front of both cameras for the base ±(1, b_y, b_z) (both signs tried unless given)."""
    signs = (1.0, -1.0) if sign is None else (sign,)
    counts = [(int(np.sum(_in_front_mask(m1, m2, s * base))), s) for s in signs]
    front, s = max(counts, key=lambda c: c[0])
    return front, s


def _closed_form_start(xy1, xy2, io1, io2, system, order):
    """Approximate elements from the essential matrix with the cheirality test (§4.4).

    Falls back to zeros (the book's start, right for near-vertical pairs) when E is not
    determined: fewer than 8 points, or all object points in one plane.
    """
    from .projective import relative_orientation_projective

    if len(xy1) < 8:
        return np.zeros(5), None
    try:
        ro = relative_orientation_projective(xy1, xy2, io1, io2, order=order, system=system)
    except DegenerateGeometryError:
        return np.zeros(5), None
    return np.array([getattr(ro, name) for name in RO_NAMES[system]]), ro.base_sign


# --- §2.9 model construction --------------------------------------------------------------------------
@dataclass(repr=False)
class StereoModel:
    """A photogrammetric model (§2.9): model coordinates of the points and the orientation of both images in it.

    Attributes
    ----------
    points : (n, 3) array
        Model coordinates X_M, Y_M, Z_M.
    eo1, eo2 : ExteriorOrientation
        The images in the model frame: S₁ = 0, S₂ = B_X·(1, b_y, b_z).
    relative : RelativeOrientation
        The relative orientation the model was built from.

    References
    ----------
    Chibunichev (2022), §2.9; eq. (2.4.4).

    Examples
    --------
    >>> import numpy as np
    >>> from photolib.camera import ExteriorOrientation
    >>> m = StereoModel(np.zeros((4, 3)), ExteriorOrientation(0, 0, 0), ExteriorOrientation(1, 0, 0), None)
    >>> print(m)
    StereoModel: 4 points, base B = (1.000, 0.000, 0.000)
    """

    points: np.ndarray                  # (n, 3) X_M, Y_M, Z_M
    eo1: ExteriorOrientation            # image 1 in the model frame (S₁ at the origin)
    eo2: ExteriorOrientation            # image 2: S₂ = (B_X, B_X b_y, B_X b_z)
    relative: RelativeOrientation = field(repr=False)

    def __repr__(self) -> str:
        B = ", ".join(f"{v:.3f}" for v in self.eo2.center - self.eo1.center)
        return f"StereoModel: {len(self.points)} points, base B = ({B})"


def build_model(xy1, xy2, ro: RelativeOrientation, io1: InteriorOrientation,
                io2: InteriorOrientation | None = None, *, base_length: float = 1.0,
                method: str = "closest", formula: int | None = None) -> StereoModel:
    """Model coordinates by forward intersection in the model frame, §2.9.

    S₁ = (0, 0, 0); the base component B_X (``base_length``, arbitrary and non-zero, often
    b·m) fixes the model scale; B_Y = B_X b_y, B_Z = B_X b_z (with the sign of B_X of the
    relative orientation); the image angles are the angles of relative orientation
    (ωᵢ = ω′ᵢ, αᵢ = α′ᵢ, κᵢ = κ′ᵢ). The points follow from (2.4.4) with N of
    :func:`intersection_scale` (``method``, ``formula``).

    Parameters
    ----------
    xy1, xy2 : (n, 2) arrays
        Corresponding image coordinates (mm).
    ro : RelativeOrientation
        The relative orientation.
    io1, io2 : InteriorOrientation
        Interior orientation (``io2`` defaults to ``io1``).
    base_length : float
        B_X, non-zero.
    method, formula
        As in :func:`intersection_scale`.

    Returns
    -------
    StereoModel
        Model points and the images' orientation in the model frame.

    Raises
    ------
    InputError
        Zero or NaN B_X, wrong types or shapes.
    DegenerateGeometryError
        Parallel rays.
    PointBehindCameraError
        Points behind a camera of the model.

    References
    ----------
    Chibunichev (2022), §2.9; §2.4, eq. (2.4.4).

    Examples
    --------
    >>> from photolib.synthetic import stereo_pair
    >>> pair = stereo_pair(8, seed=1)
    >>> ro = relative_orientation(pair.xy1, pair.xy2, pair.io)
    >>> build_model(pair.xy1, pair.xy2, ro, pair.io, base_length=400.0)
    StereoModel: 8 points, base B = (400.000, 0.000, 0.000)
    """
    _check_type(ro, RelativeOrientation, "ro")
    if np.ndim(base_length) != 0 or not np.isfinite(_numbers(base_length, "base_length")) or base_length == 0:
        raise InputError("the base component B_X must be finite and non-zero")
    io2 = io1 if io2 is None else io2
    eo1 = ExteriorOrientation(0.0, 0.0, 0.0, ro.omega1, ro.alpha1, ro.kappa1, ro.order)
    S2 = base_length * ro.base
    eo2 = ExteriorOrientation(*map(float, S2), ro.omega2, ro.alpha2, ro.kappa2, ro.order)
    points = forward_intersection(xy1, xy2, eo1, eo2, io1, io2, method=method, formula=formula)
    return StereoModel(points, eo1, eo2, ro)


# --- §2.10–§2.11 exterior orientation of the model -------------------------------------------------------
SIMILARITY_NAMES = ("X0", "Y0", "Z0", "omega", "alpha", "kappa", "t")


@dataclass(repr=False)
class SimilarityTransform:
    """Seven elements of exterior orientation of a model (§2.10): R = R₀ + t·A_M·R_M (2.10.4).

    Attributes
    ----------
    X0, Y0, Z0 : float
        The shift R₀ (m).
    omega, alpha, kappa : float
        Angles of A_M (rad) in the sequence ``order``.
    t : float
        Scale.
    order : {"kaw", "wak"}
        Rotation sequence.
    adjustment : Adjustment or None
        μ, m_j, r_ij of the least-squares solution (:func:`absolute_orientation`).
    residuals : (n, 3) array or None
        Transformed − given coordinates at the control points (NaN where not used).

    References
    ----------
    Chibunichev (2022), §2.10, eqs. (2.10.3)–(2.10.5); §2.11, eqs. (2.11.1), (2.11.2).

    Examples
    --------
    >>> T = SimilarityTransform(100.0, 200.0, 50.0, 0.0, 0.0, 0.0, 2.0)
    >>> T.apply([[1.0, 1.0, 1.0]])
    array([[102., 202.,  52.]])
    >>> print(T)
    SimilarityTransform (2.10.4), order kaw
      X₀ = 100.000 m, Y₀ = 200.000 m, Z₀ = 50.000 m
      ω = +0.0000°, α = +0.0000°, κ = +0.0000°
      t = 2
    """

    X0: float
    Y0: float
    Z0: float
    omega: float
    alpha: float
    kappa: float
    t: float
    order: str = DEFAULT_ORDER
    adjustment: Adjustment | None = field(default=None, repr=False)
    residuals: np.ndarray | None = field(default=None, repr=False)   # transformed − given at the control points

    def __post_init__(self):
        check_order(self.order)
        try:
            values = np.asarray([self.X0, self.Y0, self.Z0, self.omega, self.alpha, self.kappa, self.t], dtype=float)
        except (TypeError, ValueError):
            raise InputError("the seven elements of the similarity transform must be numbers") from None
        if not np.all(np.isfinite(values)):
            raise InputError("the seven elements of the similarity transform contain NaN or inf")
        if self.t == 0:
            raise DegenerateGeometryError("the scale t of the similarity transform is zero")

    @property
    def vector(self) -> np.ndarray:
        """(X₀, Y₀, Z₀, ω, α, κ, t)."""
        return np.array([self.X0, self.Y0, self.Z0, self.omega, self.alpha, self.kappa, self.t])

    @property
    def shift(self) -> np.ndarray:
        """R₀ = (X₀, Y₀, Z₀)."""
        return np.array([self.X0, self.Y0, self.Z0])

    @property
    def matrix(self) -> np.ndarray:
        """A_M (model → object)."""
        return rotation_matrix(self.omega, self.alpha, self.kappa, self.order)

    def apply(self, model_points) -> np.ndarray:
        """Object coordinates of model points by (2.10.4)."""
        XM = as_points(model_points, 3, "model points")
        return self.shift + self.t * XM @ self.matrix.T

    def inverse(self, object_points) -> np.ndarray:
        """Model coordinates of object points: R_M = A_Mᵀ(R − R₀)/t."""
        XYZ = as_points(object_points, 3, "object points")
        return (XYZ - self.shift) @ self.matrix / self.t

    def __repr__(self) -> str:
        adj = self.adjustment
        sd = dict(zip(SIMILARITY_NAMES, adj.std)) if adj is not None else {}
        pm = lambda name, scale=1.0, unit="": (f" ± {scale * sd[name]:.3f}{unit}" if name in sd else "")  # noqa: E731
        ang = lambda name: (f"{np.degrees(getattr(self, name)):+.4f}°"                                  # noqa: E731
                            + (f" ± {np.degrees(sd[name]):.4f}°" if name in sd else ""))
        lines = [f"SimilarityTransform (2.10.4), order {self.order}",
                 f"  X₀ = {self.X0:.3f} m{pm('X0', unit=' m')}, Y₀ = {self.Y0:.3f} m{pm('Y0', unit=' m')}, "
                 f"Z₀ = {self.Z0:.3f} m{pm('Z0', unit=' m')}",
                 f"  ω = {ang('omega')}, α = {ang('alpha')}, κ = {ang('kappa')}",
                 f"  t = {self.t:.6g}" + (f" ± {sd['t']:.3g}" if "t" in sd else "")]
        if adj is not None:
            lines.append(f"  μ = {adj.mu:.3g} m, {adj.iterations} iterations")
        return "\n".join(lines)

    @classmethod
    def from_matrix(cls, shift, A, t, order=DEFAULT_ORDER):
        """The transform with shift R₀, rotation matrix A_M (angles extracted in ``order``) and scale t."""
        w, a, k = rotation_angles(A, order)
        s = np.asarray(shift, dtype=float)
        return cls(float(s[0]), float(s[1]), float(s[2]), w, a, k, float(t), order)


def _check_not_collinear(P, what):
    if len(P) < 3:
        raise DegenerateGeometryError(f"{what}: at least 3 points are needed, got {len(P)}")
    s = np.linalg.svd(P - P.mean(axis=0), compute_uv=False)
    if s[0] == 0 or s[1] < 1e-9 * s[0]:
        raise DegenerateGeometryError(f"{what} lie on one line; the rotation about it is not determined")


def similarity_closed_form(model_points, object_points, order: str = DEFAULT_ORDER) -> SimilarityTransform:
    """Closed-form 3-D similarity R = R₀ + t·A·R_M from ≥ 3 non-collinear full control points.

    Umeyama's method (1991): the rotation from the SVD of the cross-covariance of the centred
    point sets (with the reflection guard), then t and R₀. It minimises the same sum of squares
    as (2.11.1) with unit weights, so it needs no approximate angles; :func:`absolute_orientation`
    uses it as its start. The result does not depend on the signs the SVD picks.

    Parameters
    ----------
    model_points, object_points : (n, 3) arrays
        Corresponding model and object coordinates, n ≥ 3, not collinear.
    order : {"kaw", "wak"}
        Rotation sequence of the returned angles.

    Returns
    -------
    SimilarityTransform
        The seven elements (no adjustment).

    Raises
    ------
    InputError
        Wrong shapes, different counts, NaN/inf.
    DegenerateGeometryError
        Fewer than 3 points or collinear points.

    References
    ----------
    Chibunichev (2022), §2.10, eq. (2.10.4); §2.11, eq. (2.11.1).
    S. Umeyama, "Least-squares estimation of transformation parameters between two point
    patterns", IEEE TPAMI 13(4), 1991, 376–380.

    Examples
    --------
    >>> import numpy as np
    >>> M = np.array([[0.0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]])
    >>> T = similarity_closed_form(M, 2 * M + [10, 20, 30])
    >>> round(T.t, 9), T.shift.round(9)
    (2.0, array([10., 20., 30.]))
    """
    check_order(order)
    XM = as_points(model_points, 3, "model points")
    XYZ = as_points(object_points, 3, "object points")
    _same_length(XM, XYZ, "control points")
    _check_not_collinear(XM, "the model points")
    _check_not_collinear(XYZ, "the object points")
    mM, mO = XM.mean(axis=0), XYZ.mean(axis=0)
    cM, cO = XM - mM, XYZ - mO
    U, S, Vt = np.linalg.svd(cO.T @ cM)            # Σ_i (object_i)(model_i)ᵀ
    D = np.diag([1.0, 1.0, np.sign(np.linalg.det(U @ Vt))])
    A = U @ D @ Vt
    t = np.trace(np.diag(S) @ D) / np.sum(cM ** 2)
    return SimilarityTransform.from_matrix(mO - t * A @ mM, A, t, order)


def level_similarity_start(XM, XYZ, mask, order):
    """Start values of the 7-element transform (2.10.4) for a near-vertical model: ω = α = 0.

    Scale, κ and the shifts come from a 2-D similarity fitted to ≥ 2 planimetric control points,
    Z₀ from the height points. Used when there are not 3 non-collinear full control points.
    """
    xy = mask[:, 0] & mask[:, 1]
    zm = XM[xy, 0] + 1j * XM[xy, 1]
    zo = XYZ[xy, 0] + 1j * XYZ[xy, 1]
    zm_c, zo_c = zm - zm.mean(), zo - zo.mean()
    c = np.vdot(zm_c, zo_c) / np.vdot(zm_c, zm_c).real       # 2-D similarity: zo = z0 + c·zm
    if c == 0:
        raise DegenerateGeometryError("the planimetric control points coincide in the model")
    z0 = zo.mean() - c * zm.mean()
    t, kappa = abs(c), float(np.angle(c))
    h = mask[:, 2]
    Z0 = float(np.mean(XYZ[h, 2] - t * XM[h, 2]))
    return SimilarityTransform(float(z0.real), float(z0.imag), Z0, 0.0, 0.0, kappa, float(t), order)


def absolute_orientation(model_points, control_points, components=None, order: str = DEFAULT_ORDER,
                         initial: SimilarityTransform | None = None, weights=None, tol: float = 1e-10,
                         max_iter: int = 50, jacobian: str = "derived") -> SimilarityTransform:
    """Exterior orientation of a model from control points, §2.11, by least squares.

    Every used coordinate of a control point gives one equation of (2.11.1); linearised they are
    the correction equations (2.11.2) with coefficients derived by sympy
    (:func:`photolib.derivations.similarity_model`), solved by the engine of §1.8.

    Parameters
    ----------
    model_points, control_points : (n, 3) arrays
        Model coordinates X_M, Y_M, Z_M and object coordinates X, Y, Z of the control points.
    components : (n, 3) bool array, optional
        Which object coordinates are known: all three for a full (planimetric-height) point,
        X and Y for a planimetric one, Z only for a height point. Unknown coordinates may be NaN.
        At least 7 equations are needed (e.g. 2 full + 1 height point, or 2 planimetric + 3 height).
    order : {"kaw", "wak"}
        Rotation sequence of ω_M, α_M, κ_M (the printed partials of §2.11 are for "wak").
    initial : SimilarityTransform, optional
        Approximate values. By default the closed form of :func:`similarity_closed_form` on the
        full control points (≥ 3 non-collinear); otherwise a near-vertical start (ω = α = 0) from
        the planimetric and height points.
    weights : (n, 3) array, optional
        Weights of the coordinates (unused entries ignored); unit weights by default.
    tol, max_iter
        Convergence tolerance and iteration limit.
    jacobian : {"derived", "printed", "book-program"}
        ``"derived"`` (default): coefficients of (2.11.2) derived by sympy. ``"printed"``: the
        §2.11 coefficients as printed (ω–α–κ only; ∂φ/∂α_M has the wrong sign on both sin κ_M
        terms). ``"book-program"``: the printed ones with a₅ = ∂φ_X/∂α_M set to 0, which is what
        the book's program evidently computed in the worked example after §2.12 (it reproduces X₀, m_X₀
        and the X₀ row of its correlation matrix). The last two exist only to reproduce the book.

    Returns
    -------
    SimilarityTransform
        The seven elements, the adjustment (μ, m_j, r_ij in the order X₀, Y₀, Z₀, ω, α, κ, t)
        and the residuals "transformed − given" at the control points (NaN where not used).

    Raises
    ------
    InputError
        Wrong shapes, NaN in known coordinates, fewer than 7 equations, bad options.
    DegenerateGeometryError
        Collinear control, not enough control of the right kinds.
    ConvergenceError
        No convergence within ``max_iter``.

    References
    ----------
    Chibunichev (2022), §2.11, eqs. (2.11.1), (2.11.2); §2.10, eq. (2.10.4).

    Examples
    --------
    >>> import numpy as np
    >>> M = np.array([[0.0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1], [1, 1, 0.2]])
    >>> T = absolute_orientation(M, 500 * M + [1000, 2000, 300])
    >>> round(T.t, 6), T.shift.round(6)
    (500.0, array([1000., 2000.,  300.]))
    """
    check_order(order)
    XM = as_points(model_points, 3, "model points")
    XYZ = np.asarray(control_points, dtype=float)
    if XYZ.shape != XM.shape:
        raise InputError(f"control points: expected shape {XM.shape}, got {XYZ.shape}")
    mask = np.ones(XM.shape, bool) if components is None else np.asarray(components, dtype=bool)
    if mask.shape != XM.shape:
        raise InputError(f"components: expected a boolean array of shape {XM.shape}, got {mask.shape}")
    if not np.all(np.isfinite(XYZ[mask])):
        raise InputError("control points contain NaN or inf in coordinates marked as known")
    if np.any(mask[:, 0] != mask[:, 1]):
        raise InputError("a control point must give X and Y together (planimetric) or neither")
    m = int(mask.sum())
    if m < 7:
        raise InputError(f"the seven elements of the model need at least 7 control equations, got {m}")
    used = mask.any(axis=1)
    _check_not_collinear(XM[used], "the model points of the control")
    obs = np.where(mask, XYZ, 0.0)
    full = mask.all(axis=1)
    if initial is None:
        try:
            start = similarity_closed_form(XM[full], obs[full], order)
        except DegenerateGeometryError:
            if (mask[:, 0].sum() < 2) or (mask[:, 2].sum() < 1):
                raise DegenerateGeometryError(
                    "control: no 3 non-collinear full points and not 2 planimetric + height points") from None
            start = level_similarity_start(XM, obs, mask, order)
    else:
        start = initial
    if weights is not None and np.shape(weights) != XM.shape:
        raise InputError(f"weights: expected shape {XM.shape}, got {np.shape(weights)}")
    P = None if weights is None else np.asarray(weights, dtype=float)[mask]
    res_fn, jac_fn = derivations.similarity_model(order).compile()
    if jacobian in ("printed", "book-program"):
        if order != "wak":
            raise InputError("the printed §2.11 partials are for the ω–α–κ matrix (1.3.2): use order='wak'")
        jac_fn = derivations.printed_similarity_jacobian(zero_a5=jacobian == "book-program")
    elif jacobian != "derived":
        raise InputError(f"jacobian must be 'derived', 'printed' or 'book-program', got {jacobian!r}")
    data = (XM[:, 0], XM[:, 1], XM[:, 2], obs[:, 0], obs[:, 1], obs[:, 2])
    n = len(XM)

    def linearize(p):
        L = res_fn(*p, *data).T[mask]                                       # (2.11.1): l = φ
        B = jac_fn(*p, *data).reshape(3, 7, n).transpose(2, 0, 1)[mask]       # (2.11.2)
        return B, L

    # t is relative: a correction of t below t·10⁻¹² (a few units of rounding of t) counts as zero
    tol_v = np.array([tol, tol, tol, tol * 1e-2, tol * 1e-2, tol * 1e-2, tol * 1e-2 * max(1.0, abs(start.t))])
    adj = gauss_newton(linearize, start.vector, P, tol=tol_v, max_iter=max_iter, names=SIMILARITY_NAMES)
    result = SimilarityTransform(*map(float, adj.x), order=order, adjustment=adj)
    residuals = np.full(XM.shape, np.nan)
    residuals[mask] = (result.apply(XM) - obs)[mask]
    result.residuals = residuals
    return result


# --- §2.12 exterior orientation of the images -------------------------------------------------------------
def image_orientation_from_model(model: StereoModel, transform: SimilarityTransform, order: str | None = None,
                                 product: str = "model-first"):
    """Exterior orientation of both images from the model's (§2.12).

    S_i = R₀ + t·A_M·S_Mi (2.12.1) and A_i = A_M·A′_i (2.12.2); the angles are extracted in
    ``order`` (default: the transform's; the book's text uses (1.3.3), i.e. ``"wak"``). The chain
    works on matrices, so the model's and the images' rotation sequences need not agree.

    Parameters
    ----------
    model : StereoModel
        The model (its images' orientation in the model frame).
    transform : SimilarityTransform
        The seven elements of the model's exterior orientation.
    order : {"kaw", "wak"}, optional
        Rotation sequence of the returned angles.
    product : {"model-first", "image-first"}
        ``"image-first"`` computes A_i = A′_i·A_M instead — wrong (A′_i maps image → model and
        A_M model → object, so A_M must be applied last), but it is what the book's program
        evidently did in the worked example after §2.12; it exists only to reproduce that table.

    Returns
    -------
    (ExteriorOrientation, ExteriorOrientation)
        eo1, eo2 in the object system.

    Raises
    ------
    InputError
        Wrong types, unknown order or product.

    References
    ----------
    Chibunichev (2022), §2.12, eqs. (2.12.1), (2.12.2).

    Examples
    --------
    >>> from photolib.camera import ExteriorOrientation
    >>> import numpy as np
    >>> from photolib.image_pair import StereoModel
    >>> model = StereoModel(np.zeros((1, 3)), ExteriorOrientation(0, 0, 0), ExteriorOrientation(1, 0, 0), None)
    >>> e1, e2 = image_orientation_from_model(model, SimilarityTransform(10.0, 0, 0, 0, 0, 0, 400.0))
    >>> e2.center
    array([410.,   0.,   0.])
    """
    _check_type(model, StereoModel, "model")
    _check_type(transform, SimilarityTransform, "transform")
    order = transform.order if order is None else check_order(order)
    if product not in ("model-first", "image-first"):
        raise InputError(f"product must be 'model-first' (2.12.2) or 'image-first', got {product!r}")
    A_M = transform.matrix
    result = []
    for eo in (model.eo1, model.eo2):
        S = transform.shift + transform.t * A_M @ eo.center                      # (2.12.1)
        A = A_M @ eo.matrix if product == "model-first" else eo.matrix @ A_M      # (2.12.2)
        result.append(ExteriorOrientation.from_matrix(S, A, order))
    return tuple(result)


# --- §2.6 the whole double-resection workflow ----------------------------------------------------------------
@dataclass(repr=False)
class DoubleResection:
    """Every intermediate result of the double resection of §2.6 (steps 2–5; step 1, interior
    orientation, is done by the caller, e.g. with :mod:`photolib.interior`).

    Attributes
    ----------
    relative : RelativeOrientation
        Step 2, the five elements of relative orientation (§2.7–§2.8).
    model : StereoModel
        Step 3, the model (§2.9).
    transform : SimilarityTransform
        Step 4, the seven elements of the model's exterior orientation (§2.11).
    object_points : (n, 3) array
        Step 5, all points in the object system (2.10.4).
    eo1, eo2 : ExteriorOrientation
        Exterior orientation of the images (§2.12).

    References
    ----------
    Chibunichev (2022), §2.6; §2.12, eqs. (2.12.1), (2.12.2).

    Examples
    --------
    >>> DoubleResection.__name__
    'DoubleResection'
    """

    relative: RelativeOrientation          # step 2: the five elements of relative orientation (§2.7–§2.8)
    model: StereoModel                     # step 3: the model by intersection in the model frame (§2.9)
    transform: SimilarityTransform         # step 4: the seven elements of the model's exterior orientation (§2.11)
    object_points: np.ndarray              # step 5: all points in the object system (2.10.4)
    eo1: ExteriorOrientation               # and the images' exterior orientation (§2.12)
    eo2: ExteriorOrientation

    @property
    def control_residuals(self) -> np.ndarray:
        """Transformed model − given object coordinates at the control points (NaN where not given)."""
        return self.transform.residuals

    def __repr__(self) -> str:
        return "\n".join([f"DoubleResection: {len(self.object_points)} object points", "  " + repr(self.relative)
                          .replace("\n", "\n  "), "  " + repr(self.transform).replace("\n", "\n  "),
                          f"  S₁ = ({', '.join(f'{v:.3f}' for v in self.eo1.center)}) m, "
                          f"S₂ = ({', '.join(f'{v:.3f}' for v in self.eo2.center)}) m"])


def double_resection(xy1, xy2, io1: InteriorOrientation, control_points, io2: InteriorOrientation | None = None,
                     *, components=None, system: str = "dependent", order: str = DEFAULT_ORDER,
                     base_length: float = 1.0, ro_weights=None, control_weights=None) -> DoubleResection:
    """Object coordinates from a stereo pair by double resection, §2.6, in one call.

    Chains relative orientation (:func:`relative_orientation`), model construction
    (:func:`build_model`), exterior orientation of the model from control points
    (:func:`absolute_orientation`), the transformation of every model point into the object
    system (2.10.4) and the exterior orientation of both images (:func:`image_orientation_from_model`).

    Parameters
    ----------
    xy1, xy2 : (n, 2) arrays
        Corresponding image coordinates (mm), n ≥ 5.
    io1, io2 : InteriorOrientation
        Interior orientation (``io2`` defaults to ``io1``).
    control_points : (n, 3) array
        Aligned with the image points, NaN for points that are not control (or for the unknown
        components of planimetric or height control).
    components : (n, 3) bool array, optional
        The mask of known control coordinates (default: the finite entries).
    system, order
        As in :func:`relative_orientation`.
    base_length : float
        B_X of the model.
    ro_weights, control_weights : arrays, optional
        Weights of the coplanarity conditions and of the control coordinates.

    Returns
    -------
    DoubleResection
        Every intermediate result and the object coordinates of all points.

    Raises
    ------
    InputError
        No control point, misaligned control, bad shapes or NaN image coordinates.
    DegenerateGeometryError
        Degenerate pair or control (see the steps).
    PointBehindCameraError
        Points behind a camera.
    ConvergenceError
        A step did not converge.

    References
    ----------
    Chibunichev (2022), §2.6; §2.7–§2.12.

    Examples
    --------
    >>> import numpy as np
    >>> from photolib.synthetic import stereo_pair
    >>> pair = stereo_pair(10, seed=2, angle_spread_deg=2.0)
    >>> control = np.full((10, 3), np.nan)
    >>> control[:4] = pair.points[:4]
    >>> dr = double_resection(pair.xy1, pair.xy2, pair.io, control)
    >>> bool(np.allclose(dr.object_points, pair.points, atol=1e-6))
    True
    """
    control = np.asarray(control_points, dtype=float)
    xy1 = as_points(xy1, 2, "image points of image 1")
    if control.shape != (len(xy1), 3):
        raise InputError(f"control_points must have shape ({len(xy1)}, 3) aligned with the image points, got {control.shape}")
    mask = np.isfinite(control) if components is None else np.asarray(components, dtype=bool)
    rows = mask.any(axis=1)
    if not rows.any():
        raise InputError("no control point is given: the model cannot be oriented (§2.11)")
    ro = relative_orientation(xy1, xy2, io1, io2, system=system, order=order, weights=ro_weights)
    model = build_model(xy1, xy2, ro, io1, io2, base_length=base_length)
    transform = absolute_orientation(model.points[rows], np.where(mask[rows], control[rows], 0.0),
                                     components=mask[rows], order=order, weights=control_weights)
    eo1, eo2 = image_orientation_from_model(model, transform, order)
    return DoubleResection(ro, model, transform, transform.apply(model.points), eo1, eo2)


# --- §2.13 a-priori accuracy -------------------------------------------------------------------------------
def photo_base(frame_length, overlap_percent):
    """Photo base at image scale b = l_x(100% − P_x)/100% (§2.13), l_x the frame side along the flight.

    Parameters
    ----------
    frame_length : float
        l_x (mm), positive.
    overlap_percent : float
        Forward overlap P_x in [0, 100) %.

    Returns
    -------
    float
        b (mm).

    Raises
    ------
    InputError
        NaN, a non-positive frame, an overlap outside [0, 100) %.

    References
    ----------
    Chibunichev (2022), §2.13.

    Examples
    --------
    >>> round(photo_base(230.0, 60.0), 6)
    92.0
    """
    _numbers(frame_length, "the frame length l_x", positive=True)
    if not 0 <= _numbers(overlap_percent, "the overlap") < 100:
        raise InputError(f"forward overlap must be in [0, 100) %, got {overlap_percent}")
    return frame_length * (100.0 - overlap_percent) / 100.0


def normal_case_accuracy(H, f, b, m_x, m_y, m_p, x=0.0, y=0.0, approximate: bool = False):
    """m_X, m_Y, m_Z of a point from a normal-case pair (2.13.1)–(2.13.3).

    m_Z = (H/b)m_p; m_X = √((x/f·m_Z)² + (H/f·m_x)²) ≈ (H/f)m_x; m_Y likewise with y, m_y.

    Parameters
    ----------
    H : float
        Flying height (the |Z| of (2.5.4)), in the unit of the result.
    f, b : float
        Focal length and photo base (mm).
    m_x, m_y, m_p : float
        Errors of x, y and of the x-parallax (mm).
    x, y : float
        Image position of the point (mm).
    approximate : bool
        Drop the x, y terms as the book's numerical example does.

    Returns
    -------
    (m_X, m_Y, m_Z)
        Floats (or arrays), in the unit of H.

    Raises
    ------
    InputError
        NaN/inf, non-positive H, f or b.

    References
    ----------
    Chibunichev (2022), §2.13, eqs. (2.13.1)–(2.13.3).

    Examples
    --------
    >>> [round(v, 4) for v in normal_case_accuracy(2000.0, 100.0, 40.0, 0.002, 0.002, 0.002, approximate=True)]
    [0.04, 0.04, 0.1]
    """
    H, f, b = (_numbers(v, name) for v, name in ((H, "H"), (f, "f"), (b, "b")))
    for v, name in ((m_x, "m_x"), (m_y, "m_y"), (m_p, "m_p"), (x, "x"), (y, "y")):
        _numbers(v, name)
    if np.any(f <= 0) or np.any(b <= 0) or np.any(H <= 0) or not np.all(np.isfinite([*np.ravel(H), *np.ravel(f), *np.ravel(b)])):
        raise InputError("H, f and b must be positive and finite")
    m_Z = H / b * m_p                                                            # (2.13.3)
    if approximate:
        m_X, m_Y = H / f * m_x, H / f * m_y
    else:
        m_X = np.hypot(np.asarray(x) / f * m_Z, H / f * m_x)
        m_Y = np.hypot(np.asarray(y) / f * m_Z, H / f * m_y)
    if np.ndim(m_X) == np.ndim(m_Y) == np.ndim(m_Z) == 0:
        return float(m_X), float(m_Y), float(m_Z)
    return m_X, m_Y, m_Z


# --- Hanzl, Fotogrammetrie, Modul 01, §3: orientation and points from two images ---------------------
def intersection_known_eo(xy1, xy2, eo1: ExteriorOrientation, eo2: ExteriorOrientation,
                          io1: InteriorOrientation, io2: InteriorOrientation | None = None,
                          warn_ratio: float = 0.1) -> np.ndarray:
    """Object points of a pair with known exterior orientation by Hanzl's closed form [§3.1].

    For image j, X = X₀ⱼ + (Z − Z₀ⱼ)k_xj and Y = Y₀ⱼ + (Z − Z₀ⱼ)k_yj with
    k_xj = (r₁₁x̄ + r₁₂ȳ − r₁₃c)/(r₃₁x̄ + r₃₂ȳ − r₃₃c), k_yj likewise with row 2 (x̄ = x − x₀,
    ȳ = y − y₀; the ratios of the ray R(x̄, ȳ, −c), i.e. (2.3)). Equating the two X equations gives
    Z = (X₀₂ − X₀₁ + Z₀₁k_x1 − Z₀₂k_x2)/(k_x1 − k_x2); X, Y follow from image 1. The book prints
    "+r₁₃c", "+r₃₃c" and calls the Y ratio k_z (errata, lines 352–360).

    Only the X equations are used: the form breaks down when k_x1 ≈ k_x2 (a base along Y, or a
    point whose rays differ only in Y). It raises when k_x1 − k_x2 vanishes and warns
    (``RuntimeWarning``) when |k_x1 − k_x2| < ``warn_ratio``·|(k_x1 − k_x2, k_y1 − k_y2)|; the
    general method is the least-squares intersection of all four equations,
    :func:`intersect_rays`.

    Parameters
    ----------
    xy1, xy2 : (n, 2) arrays
        Corresponding image coordinates (mm).
    eo1, eo2 : ExteriorOrientation
        Known exterior orientation (any rotation order; Hanzl's R is ``order="wak"``).
    io1, io2 : InteriorOrientation
        Interior orientation (``io2`` defaults to ``io1``).
    warn_ratio : float
        Threshold of the ill-conditioning warning (0 switches it off).

    Returns
    -------
    (n, 3) ndarray
        X, Y, Z (m).

    Raises
    ------
    InputError
        Wrong shapes or types, NaN/inf, a negative ``warn_ratio``.
    DegenerateGeometryError
        k_x1 = k_x2 for a point (the X equations do not fix Z), or a ray parallel to the XY plane.

    References
    ----------
    Hanzl, Fotogrammetrie, Modul 01, §3.1, [H3.1-1/2] (seed 002 lines 348–370);
    Chibunichev (2022), §2.4 (forward intersection).

    Examples
    --------
    >>> from photolib.camera import ExteriorOrientation, InteriorOrientation
    >>> io = InteriorOrientation(100.0)
    >>> e1, e2 = ExteriorOrientation(0, 0, 1000), ExteriorOrientation(400, 0, 1000)
    >>> intersection_known_eo([[20.0, 10.0]], [[-20.0, 10.0]], e1, e2, io).round(9) + 0.0
    array([[200., 100.,   0.]])
    """
    io2 = io1 if io2 is None else io2
    _check_type(eo1, ExteriorOrientation, "eo1")
    _check_type(eo2, ExteriorOrientation, "eo2")
    warn_ratio = float(_numbers(warn_ratio, "warn_ratio"))
    if warn_ratio < 0:
        raise InputError(f"warn_ratio must be ≥ 0, got {warn_ratio}")
    xy1 = as_points(xy1, 2, "image-1 coordinates")
    xy2 = as_points(xy2, 2, "image-2 coordinates")
    _same_length(xy1, xy2)
    r1, r2 = image_rays(xy1, eo1, io1), image_rays(xy2, eo2, io2)
    if np.any(r1[:, 2] == 0) or np.any(r2[:, 2] == 0):
        raise DegenerateGeometryError("a ray is parallel to the XY plane: k_x, k_y of §3.1 divide by its Z component")
    kx1, ky1 = r1[:, 0] / r1[:, 2], r1[:, 1] / r1[:, 2]
    kx2, ky2 = r2[:, 0] / r2[:, 2], r2[:, 1] / r2[:, 2]
    dkx, dky = kx1 - kx2, ky1 - ky2
    scale = 1.0 + np.abs(kx1) + np.abs(kx2)
    bad = np.abs(dkx) <= 1e-12 * scale
    if np.any(bad):
        raise DegenerateGeometryError(
            f"k_x1 = k_x2 for points {np.flatnonzero(bad).tolist()}: the X equations of §3.1 do not determine Z "
            "(base along Y or parallel rays); use intersect_rays (least squares over all four equations)")
    weak = np.abs(dkx) < warn_ratio * np.hypot(dkx, dky)
    if np.any(weak):
        warnings.warn(f"k_x1 ≈ k_x2 for points {np.flatnonzero(weak).tolist()}: the closed form of §3.1 uses only the "
                      "X equations and is ill-conditioned here (base not along X); prefer intersect_rays",
                      RuntimeWarning, stacklevel=2)
    X01, Y01, Z01 = eo1.center
    X02, Z02 = eo2.center[0], eo2.center[2]
    Z = (X02 - X01 + Z01 * kx1 - Z02 * kx2) / dkx                          # [H3.1-2]
    return np.column_stack([X01 + (Z - Z01) * kx1, Y01 + (Z - Z01) * ky1, Z])


def orientation_counts(full: int, planimetric: int, height: int, new: int = 0, images: int = 2) -> dict:
    """Observations, unknowns and redundancy of the joint orientation of a pair [Hanzl §3.2.2].

    Each point measured in every image gives 2·images equations (four for a pair); the unknowns
    are 6·images elements of exterior orientation, 3 coordinates per new point and the unknown
    coordinates of incomplete control (Z of a planimetric, X and Y of a height point). Also
    returns the equations a set of control gives to the absolute orientation of a model (3 per
    full, 2 per planimetric, 1 per height point; at least 7 are needed, §3.2.3).

    Parameters
    ----------
    full, planimetric, height, new : int
        Full (X, Y, Z), planimetric (X, Y), height (Z) control points and new points.
    images : int
        Number of images (2 in §3.2.2).

    Returns
    -------
    dict
        ``observations``, ``unknowns``, ``redundancy``, ``absolute_equations``.

    Raises
    ------
    InputError
        A negative or non-integer count, fewer than 2 images.

    References
    ----------
    Hanzl, Fotogrammetrie, Modul 01, §3.2.2 (seed 002 lines 412–438), §3.2.3 (lines 446–452);
    Chibunichev (2022), §3.5, eqs. (3.5.20)–(3.5.21) (the same counting for a bundle block).

    Examples
    --------
    >>> orientation_counts(1, 2, 2, 5)      # Hanzl line 436: he prints 31 unknowns
    {'observations': 40, 'unknowns': 33, 'redundancy': 7, 'absolute_equations': 9}
    """
    counts = {}
    for name, value in (("full", full), ("planimetric", planimetric), ("height", height), ("new", new),
                        ("images", images)):
        if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < 0:
            raise InputError(f"{name} must be a non-negative integer, got {value!r}")
        counts[name] = int(value)
    if counts["images"] < 2:
        raise InputError(f"a joint orientation needs at least 2 images, got {counts['images']}")
    n = counts["images"]
    points = counts["full"] + counts["planimetric"] + counts["height"] + counts["new"]
    observations = 2 * n * points
    unknowns = 6 * n + 3 * counts["new"] + counts["planimetric"] + 2 * counts["height"]
    return {"observations": observations, "unknowns": unknowns, "redundancy": observations - unknowns,
            "absolute_equations": 3 * counts["full"] + 2 * counts["planimetric"] + counts["height"]}


_HANZL_TO_RO = {"domega1": "omega1", "dphi1": "alpha1", "dkappa1": "kappa1", "domega2": "omega2",
                "dphi2": "alpha2", "dkappa2": "kappa2", "db_y": "b_y", "db_z": "b_z"}


def _parallax_state(p, system, r1, r2, c):
    """Rectified image coordinates, depths h and the exact residual y-parallax at the elements ``p``.

    The rays are turned into the model frame by R(ω, φ, κ) ("wak"); the two rays of a point are
    intersected in the XZ plane of the model (base (1, b_y, b_z)), which gives h (depth below centre
    1) and the Y of both rays at that depth; q = c·(Y₁ − Y₂)/h (zero when the rays meet).
    """
    v = dict.fromkeys(_ALL_RO, 0.0)
    v.update(zip(RO_NAMES[system], p))
    m1 = r1 @ rotation_matrix(v["omega1"], v["alpha1"], v["kappa1"], "wak").T
    m2 = r2 @ rotation_matrix(v["omega2"], v["alpha2"], v["kappa2"], "wak").T
    det = -m1[:, 0] * m2[:, 2] + m2[:, 0] * m1[:, 2]
    if np.any(np.abs(det) <= 1e-12 * np.linalg.norm(m1, axis=1) * np.linalg.norm(m2, axis=1)):
        raise DegenerateGeometryError("a pair of rays is parallel in the XZ plane of the model: no depth h")
    lam1 = (-m2[:, 2] * 1.0 + m2[:, 0] * v["b_z"]) / det
    lam2 = (-m1[:, 2] * 1.0 + m1[:, 0] * v["b_z"]) / det
    h = -lam1 * m1[:, 2]
    if np.any(h <= 0) or np.any(lam2 <= 0):
        raise DegenerateGeometryError("the rays of some points meet above or behind the cameras (h ≤ 0): "
                                      "the pair is not a near-vertical pair with the base along +x")
    q = c * (lam1 * m1[:, 1] - v["b_y"] - lam2 * m2[:, 1]) / h
    rect = (-c * m1[:, 0] / m1[:, 2], -c * m1[:, 1] / m1[:, 2], -c * m2[:, 0] / m2[:, 2], -c * m2[:, 1] / m2[:, 2])
    return rect, h, q


def relative_orientation_parallax(xy1, xy2, io1: InteriorOrientation, io2: InteriorOrientation | None = None,
                                  system: str = "dependent", iterate: bool = True, weights=None,
                                  tol: float = 1e-12, max_iter: int = 30) -> RelativeOrientation:
    """Relative orientation of a near-vertical pair from y-parallaxes, Hanzl §3.2.3.1 (Kraus's first-order form).

    The y-parallax q = y₁ − y₂ of a point is, to first order in the orientation elements,
    q = x₂dκ₂ − x₁dκ₁ + (c + y₂²/c)dω₂ − (c + y₁²/c)dω₁ − (x₂y₂/c)dφ₂ + (x₁y₁/c)dφ₁ + (c/h)db_y + (y₂/h)db_z
    (line 510; the coefficients are derived by sympy, :func:`photolib.derivations.parallax.y_parallax_model`).
    Five of the eight elements are solved by least squares (:func:`photolib.lsq.gauss_newton`):

    * ``"independent"`` pair (line 516): dκ₁, dκ₂, dφ₁, dφ₂, dω₂ (rotations only; b_y = b_z = ω₁ = 0);
    * ``"dependent"`` pair (line 520): dκ₂, dω₂, dφ₂, db_y, db_z (image 1 fixed).

    With ``iterate=False`` the result is the book's single linear solution (first order, coefficients at
    the measured coordinates). With ``iterate=True`` (default) the images are re-rectified with the current
    elements after every step — the rays turned by R(ω, φ, κ), the exact remaining parallax
    q = c(Y₁ − Y₂)/h measured where the rays meet in the model's XZ plane — and the first-order equations
    solved again for the increments, until they vanish: the classical iteration of the optical-mechanical
    instruments, which converges to the coplanar (rigorous) solution of :func:`relative_orientation`.

    The text defines p_y = y₂ − y₁ (line 508) but its formula holds for y₁ − y₂ (erratum); here q = y₁ − y₂
    throughout, as in Chibunichev §2.8. h, the depth of a point below centre 1 in units of b_x = 1, is taken
    from the intersection of the rays in the XZ plane.

    Parameters
    ----------
    xy1, xy2 : (n, 2) arrays
        Corresponding image coordinates of n ≥ 5 points (mm), e.g. the six Gruber points (Fig. 3.3).
    io1, io2 : InteriorOrientation
        Interior orientation (``io2`` defaults to ``io1``); both images are rectified to c = f₁.
    system : {"dependent", "independent"}
        The five-element system (see above).
    iterate : bool
        Iterate to convergence (default) or return the first-order solution.
    weights : array (n,), optional
        Weights of the parallaxes (unit by default).
    tol, max_iter
        Convergence tolerance (rad and units of b_x) and iteration limit.

    Returns
    -------
    RelativeOrientation
        ``order="wak"`` (Hanzl's R = R_ω R_φ R_κ, φ ≡ α); b_y, b_z are db_y/b_x, db_z/b_x; ``q`` the exact
        residual y-parallaxes (mm); ``adjustment`` μ (mm), m_j of the five elements in the order of
        :data:`RO_NAMES`.

    Raises
    ------
    InputError
        Fewer than 5 points, wrong shapes or types, NaN/inf, an unknown system.
    DegenerateGeometryError
        Collinear points, rays that do not meet below the cameras (not a near-vertical pair with the base
        along +x), a singular normal matrix (e.g. all points on one line of the model).
    ConvergenceError
        No convergence within ``max_iter`` (elements too large for the first-order equations).

    References
    ----------
    Hanzl, Fotogrammetrie, Modul 01, §3.2.3.1 (seed 002 lines 458–524); Kraus, Photogrammetry, vol. 1
    (y-parallax form); Chibunichev (2022), §2.7–§2.8 (the rigorous coplanarity form).

    Examples
    --------
    >>> import numpy as np
    >>> from photolib.camera import InteriorOrientation
    >>> xy1 = np.array([[0, 0], [90, 0], [0, 90], [90, 90], [0, -90], [90, -90]], float)
    >>> xy2 = xy1 - [90.0, 0.0]                       # a normal-case pair of a flat model
    >>> ro = relative_orientation_parallax(xy1, xy2, InteriorOrientation(150.0))
    >>> bool(np.allclose([ro.b_y, ro.b_z, ro.omega2, ro.alpha2, ro.kappa2], 0, atol=1e-12))
    True
    """
    if not isinstance(iterate, (bool, np.bool_)):
        raise InputError(f"iterate must be True or False, got {iterate!r}")
    xy1, xy2, io2 = _relative_orientation_inputs(xy1, xy2, io1, io2, system)
    c = float(io1.f)
    r1, r2 = image_vector(xy1, io1), image_vector(xy2, io2)
    model = _parallax.y_parallax_model(system)
    _, jac_fn = model.compile()
    hanzl = [str(s) for s in model.parameters]
    perm = [hanzl.index(next(k for k, v in _HANZL_TO_RO.items() if v == name)) for name in RO_NAMES[system]]

    def jacobian(rect, h):
        J = np.asarray(jac_fn(*np.zeros(5), *rect, c, h, 0.0), dtype=float).reshape(5, -1).T
        return J[:, perm]                                             # columns in the order of RO_NAMES

    rect0, h0, q0 = _parallax_state(np.zeros(5), system, r1, r2, c)
    if iterate:
        def linearize(p):
            rect, h, q = _parallax_state(p, system, r1, r2, c)
            return jacobian(rect, h), -q
    else:
        J0 = jacobian(rect0, h0)

        def linearize(p):
            return J0, J0 @ p - q0                                     # v = Σ a·d − q (first order)
    adj = gauss_newton(linearize, np.zeros(5), weights, tol=tol, max_iter=max_iter, names=RO_NAMES[system])
    values = dict.fromkeys(_ALL_RO, 0.0)
    values.update(zip(RO_NAMES[system], map(float, adj.x)))
    _, h, q = _parallax_state(adj.x, system, r1, r2, c)
    return RelativeOrientation(system, "wak", **values, q=q, adjustment=adj, base_sign=1.0,
                               in_front=int(np.sum(h > 0)), n_points=len(xy1))


def model_deformation(xm, ym, h, b, elements) -> np.ndarray:
    """Height deformation dz of a model caused by errors of its relative orientation, Hanzl §3.2.3.2.

    dz = (h/b)·p_x (corrected form of lines 544–548, derived by sympy in
    :func:`photolib.derivations.parallax.deformation_coefficients`):
    dz = −(h/b)db_x − ((x_m − b)/b)db_z − ((h² + x_m²)/b)dφ₁ + (x_m y_m/b)dω₁ − (h y_m/b)dκ₁
    + ((h² + (x_m − b)²)/b)dφ₂ − ((x_m − b)y_m/b)dω₂ + (h y_m/b)dκ₂.
    The book prints x_m²/b², (x_m − b)²/b² and the opposite signs of the dω₁, dκ₁ terms (errata).
    Rigid motions do not deform the model: equal dκ₁ = dκ₂ give dz = 0, equal dω₁ = dω₂ give the tilt
    dz = y_m·dω.

    Parameters
    ----------
    xm, ym : float or array
        Model coordinates of the points (origin at centre 1, x along the base), units of h and b.
    h : float or array
        Depth of the model below the projection centres (> 0).
    b : float
        Base (> 0).
    elements : dict
        Errors of the elements by name: ``db_x``, ``db_z`` (units of b), ``dphi1``, ``domega1``,
        ``dkappa1``, ``dphi2``, ``domega2``, ``dkappa2`` (rad); missing ones are 0.

    Returns
    -------
    ndarray or float
        dz (units of h), broadcast over xm, ym, h.

    Raises
    ------
    InputError
        Unknown element names, NaN/inf, h or b ≤ 0, elements not a dict.

    References
    ----------
    Hanzl, Fotogrammetrie, Modul 01, §3.2.3.2 (seed 002 lines 526–568), Fig. 3.4.

    Examples
    --------
    >>> round(float(model_deformation(300.0, 200.0, 1500.0, 900.0, {"domega1": 1e-3, "domega2": 1e-3})), 12)
    0.2
    >>> float(model_deformation(300.0, 200.0, 1500.0, 900.0, {"dkappa1": 1e-3, "dkappa2": 1e-3}))
    0.0
    """
    names = _parallax.DEFORMATION_ELEMENTS
    if not isinstance(elements, dict):
        raise InputError(f"elements must be a dict of element errors by name, got {type(elements).__name__}")
    unknown = sorted(set(elements) - set(names))
    if unknown:
        raise InputError(f"unknown elements {unknown}; use {', '.join(names)}")
    values = [float(_numbers(elements.get(n, 0.0), n)) for n in names]
    xm, ym = _numbers(xm, "xm"), _numbers(ym, "ym")
    h, b = _numbers(h, "h", positive=True), _numbers(b, "b", positive=True)
    if b.ndim != 0:
        raise InputError("b must be one number (the base)")
    res, _ = _parallax.deformation_model().compile()
    dz = np.asarray(res(*values, xm, ym, h, b), dtype=float)[0]
    return float(dz) if dz.ndim == 0 else dz
