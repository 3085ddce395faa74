"""Narrowing the search for corresponding points — Chapter 5, §5.6 (pyramids, epipolar lines, normal case).

* Image pyramids (Fig. 5.15): every level halves the rows and columns, a pixel being the mean
  of a 2×2 block of the level below (the book's rule) or a Gaussian-smoothed sample
  (:func:`pyramid`); coarse-to-fine correlation matching through the levels
  (:func:`match_coarse_to_fine`, using :func:`photolib.matching.match_point` on each level).
* Epipolar ("basis") lines (Figs. 5.16–5.17): the book's ordinate y_c of the line for a given
  x_c, (5.6.1)/(5.6.2), in the relative-orientation system with the base along X
  (:func:`epipolar_ordinate`; the printed (5.6.2) is negated, ``as_printed=True`` evaluates it);
  the line in general form a·x + b·y + c = 0 for any two oriented frame images
  (:func:`epipolar_line`).
* Resampling a pair to the normal ("ideal") case, where corresponding points share a row
  (:func:`rectify_pair` → :class:`EpipolarPair`): a common rotation whose x axis is the base —
  the mid rotation of the two images turned by the smallest rotation that brings its x axis onto
  the base (the construction of Bouguet's rectification, OpenCV's ``stereoRectify``).
* Three images (Fig. 5.18): the point of image 3 as the intersection of the epipolar lines of
  its homologues on images 1 and 2 (:func:`epipolar_intersection`).

Conventions. Orientation as in Chapter 1 (:class:`photolib.camera.InteriorOrientation`,
:class:`photolib.camera.ExteriorOrientation`), image coordinates in mm (x right, y up). Digital
images are arrays ``img[row, col]`` whose fiducial centre is the centre of the frame:
x = (col − (cols − 1)/2)·Δ, y = ((rows − 1)/2 − row)·Δ (:func:`photolib.synthetic.pixel_to_image`).
Points on images for the matcher are (x, y) = (col, row) as in :mod:`photolib.matching`.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from . import _checks
from .camera import ExteriorOrientation, InteriorOrientation, _expect, as_points
from .errors import DegenerateGeometryError, InputError, PointBehindCameraError

__all__ = ["pyramid", "PyramidMatch", "match_coarse_to_fine", "epipolar_ordinate", "epipolar_line",
           "EpipolarPair", "rectify_pair", "epipolar_intersection"]


_IMAGE_MESSAGES = {"type": "{name} must be an array of numbers, got {type}",
                   "numeric": "{name} must be an array of numbers",
                   "ndim": "{name} must be a 2-D (rows, cols) image, got shape {shape}",
                   "small": "{name} is too small: {shape}"}


def _image(value, name, min_size=2):
    return _checks.image(value, name, min_size, messages=_IMAGE_MESSAGES, reject=(str, bytes))


def _int(value, name, minimum):
    return _checks.integer(value, name, minimum, message="{name} must be an integer, got {value!r}",
                           too_small="{name} must be at least {minimum}, got {value}")


_number = _checks.number


# --- §5.6: image pyramid and coarse-to-fine matching --------------------------------------------------
def pyramid(image, levels: int, method: str = "mean") -> list:
    """An image pyramid: level 0 is the image, level k + 1 halves the rows and columns of level k.

    ``"mean"`` — the book's rule (Fig. 5.15): a pixel of level k + 1 is the arithmetic mean of a
    2×2 block of level k (an odd last row or column is dropped). ``"gauss"`` — the level is
    smoothed by a Gaussian (σ = 1 px) before the 2×2 mean (less aliasing). The centre of pixel
    (c, r) of level k + 1 lies at (2c + 0.5, 2r + 0.5) of level k.

    Parameters
    ----------
    image : (rows, cols) array
        The image.
    levels : int
        Number of levels above the image (≥ 0).
    method : {"mean", "gauss"}
        Reduction rule.

    Returns
    -------
    list of ndarray
        ``levels + 1`` images, finest first.

    Raises
    ------
    InputError
        Not a 2-D finite image, a negative level count, a level that would have fewer than
        2 × 2 pixels, an unknown method.

    References
    ----------
    Chibunichev (2022), §5.6, Fig. 5.15 (2×2 averaging, a four-level pyramid).

    Examples
    --------
    >>> from photolib.epipolar import pyramid
    >>> levels = pyramid(np.arange(16.0).reshape(4, 4), 1)
    >>> levels[1]
    array([[ 2.5,  4.5],
           [10.5, 12.5]])
    """
    img = _image(image, "image")
    levels = _int(levels, "levels", 0)
    if method not in ("mean", "gauss"):
        raise InputError(f"method must be 'mean' or 'gauss', got {method!r}")
    if min(img.shape) // 2 ** levels < 2:
        raise InputError(f"a {img.shape} image has fewer than 2 × 2 pixels on level {levels}")
    out = [img]
    for _ in range(levels):
        cur = out[-1]
        if method == "gauss":
            from scipy.ndimage import gaussian_filter
            cur = gaussian_filter(cur, 1.0, mode="nearest")
        h, w = cur.shape[0] // 2 * 2, cur.shape[1] // 2 * 2
        out.append(cur[:h, :w].reshape(h // 2, 2, w // 2, 2).mean(axis=(1, 3)))
    return out


@dataclass(frozen=True)
class PyramidMatch:
    """Result of :func:`match_coarse_to_fine`.

    Attributes
    ----------
    x, y : float
        The match on image 2 (col, row), sub-pixel on level 0.
    p, q : float
        Parallaxes x₁ − x₂, y₁ − y₂ (px), as in :mod:`photolib.matching`.
    correlation : float
        R (5.1.2) at the match on level 0.
    confident : bool
        The level-0 match passed the thresholds of :func:`photolib.matching.match_point`.
    trace : list of (level, x, y, R)
        The integer match found on every level, coarsest first (coordinates of that level).

    References
    ----------
    Chibunichev (2022), §5.6, Fig. 5.15.

    Examples
    --------
    >>> from photolib.epipolar import PyramidMatch
    >>> PyramidMatch(10.0, 5.0, 2.0, 0.0, 0.95, True).p
    2.0
    """

    x: float
    y: float
    p: float
    q: float
    correlation: float
    confident: bool
    trace: list = field(default_factory=list)


def match_coarse_to_fine(left, right, point, approx=None, *, levels: int = 3, half_window: int = 5,
                         search_radius: int = 8, refine_radius: int = 2, method: str = "mean",
                         min_correlation: float = 0.7) -> PyramidMatch:
    """Coarse-to-fine correlation matching through image pyramids (§5.6).

    The point of image 1 is carried to the top level of both pyramids and matched there by
    correlation (5.1.2) within ± ``search_radius`` px of the approximation; on every lower level
    the match found above, doubled, is refined within ± ``refine_radius`` px; level 0 adds the
    sub-pixel parabola vertex (5.1.3)–(5.1.5). A search of ± s px on level L covers ± s·2^L px
    of the original images at a fraction of the cost.

    Parameters
    ----------
    left, right : (rows, cols) arrays
        Images 1 and 2 (same size).
    point : (x, y) of int
        Point of image 1 (col, row).
    approx : (x, y) of int, optional
        Approximate match on image 2 (default: ``point``).
    levels : int
        Pyramid levels above the images.
    half_window : int
        Template half-size on every level.
    search_radius, refine_radius : int
        Search half-widths on the top level and on the lower levels, px.
    method : {"mean", "gauss"}
        Pyramid rule (:func:`pyramid`).
    min_correlation : float
        Confidence threshold on R of level 0.

    Returns
    -------
    PyramidMatch

    Raises
    ------
    InputError
        Images of different sizes, NaN pixels, a template or search area reaching beyond the
        border of some level, bad parameters.
    DegenerateGeometryError
        A textureless template on some level.

    References
    ----------
    Chibunichev (2022), §5.6, Fig. 5.15; §5.1, eqs. (5.1.2)–(5.1.5).

    Examples
    --------
    >>> from scipy.ndimage import gaussian_filter
    >>> from photolib.epipolar import match_coarse_to_fine
    >>> rng = np.random.default_rng(4)
    >>> a = gaussian_filter(rng.normal(size=(160, 160)), 2.0)
    >>> b = np.roll(a, (5, -23), axis=(0, 1))          # x₂ = x₁ − 23, y₂ = y₁ + 5
    >>> m = match_coarse_to_fine(a, b, (80, 80), levels=2, search_radius=8)
    >>> round(m.p), round(m.q), m.confident, [t[:3] for t in m.trace[:2]]
    (23, -5, True, [(2, 14.0, 21.0), (1, 28.0, 43.0)])
    """
    from .matching import match_point
    L = _image(left, "left")
    R = _image(right, "right")
    if L.shape != R.shape:
        raise InputError(f"left and right images differ in size: {L.shape} and {R.shape}")
    levels = _int(levels, "levels", 0)
    half_window = _int(half_window, "half_window", 1)
    search_radius = _int(search_radius, "search_radius", 1)
    refine_radius = _int(refine_radius, "refine_radius", 1)
    pt = np.asarray(point, dtype=float).ravel() if not isinstance(point, (str, bytes)) else np.zeros(0)
    if pt.shape != (2,) or not np.all(np.isfinite(pt)):
        raise InputError(f"point must be (x, y), got {point!r}")
    ap = pt if approx is None else np.asarray(approx, dtype=float).ravel()
    if ap.shape != (2,) or not np.all(np.isfinite(ap)):
        raise InputError(f"approx must be (x, y), got {approx!r}")
    pyr1, pyr2 = pyramid(L, levels, method), pyramid(R, levels, method)
    trace = []
    s = 2 ** levels
    guess = np.rint((ap - 0.5 * (s - 1)) / s).astype(int)      # level-k centre: (2c + 0.5) rule
    for lev in range(levels, -1, -1):
        s = 2 ** lev
        p_l = np.rint((pt - 0.5 * (s - 1)) / s).astype(int)
        radius = search_radius if lev == levels else refine_radius
        last = lev == 0
        res = match_point(pyr1[lev], pyr2[lev], tuple(int(v) for v in p_l), tuple(int(v) for v in guess),
                          half_window=half_window, search_radius=radius,
                          subpixel="parabola" if last else None, min_correlation=min_correlation if last else -1.0,
                          min_sharpness=0.0 if not last else 0.02)
        xi, yi = (float(res.x), float(res.y)) if last else (float(res.integer[0]), float(res.integer[1]))
        trace.append((lev, xi, yi, float(res.r_max)))
        if not last:
            # centre of level-(lev) pixel c at 2c + 0.5 of level lev − 1: shift the match by the
            # parallax found so far, applied to the point's own position on the finer level
            p_next = np.rint((pt - 0.5 * (2 ** (lev - 1) - 1)) / 2 ** (lev - 1)).astype(int)
            shift = 2.0 * (np.array([xi, yi]) - p_l)
            guess = np.rint(p_next + shift).astype(int)
    x2, y2 = xi, yi
    return PyramidMatch(float(x2), float(y2), float(pt[0] - x2), float(pt[1] - y2), float(res.r_max),
                        bool(res.confident), trace)


# --- §5.6: epipolar lines ---------------------------------------------------------------------------
def epipolar_ordinate(xy1, x_c, rotation1, rotation2, f: float, *, as_printed: bool = False):
    """Ordinate y_c of the epipolar line on image 2 for abscissae x_c, (5.6.1)/(5.6.2).

    In the relative-orientation system of the pair (base B = (1, 0, 0), b_y = b_z = ω′₁ = 0,
    principal points at the origin, one f): (X′₁, Y′₁, Z′₁)ᵀ = A′₁(x₁, y₁, −f)ᵀ, and the
    coplanarity of B, r₁, r_c (5.6.1), Y′₁Z′_c − Y′_cZ′₁ = 0, solved for y_c gives

        y_c = [Z′₁(a₂₁x_c − a₂₃f) − Y′₁(a₃₁x_c − a₃₃f)] / (Y′₁a₃₂ − Z′₁a₂₂),   a_ij of A′₂.

    The book prints the numerator with the opposite sign (an erratum, checked with sympy in
    :mod:`photolib.book.ch05_epipolar`); ``as_printed=True`` evaluates the printed form.

    Parameters
    ----------
    xy1 : (x₁, y₁)
        The point on image 1, mm (reduced to the principal point).
    x_c : float or array
        Abscissae on image 2, mm.
    rotation1, rotation2 : (3, 3) arrays
        A′₁ and A′₂ (camera → model) of the relative orientation.
    f : float
        Focal length, mm.
    as_printed : bool
        Evaluate the printed (5.6.2).

    Returns
    -------
    float or ndarray
        y_c, mm.

    Raises
    ------
    InputError
        NaN/inf, wrong shapes, f ≤ 0, matrices that are not rotations.
    DegenerateGeometryError
        Y′₁a₃₂ − Z′₁a₂₂ = 0: the epipolar line is parallel to the y axis of image 2.

    References
    ----------
    Chibunichev (2022), §5.6, eqs. (5.6.1), (5.6.2), Fig. 5.17.

    Examples
    --------
    >>> from photolib.epipolar import epipolar_ordinate
    >>> E = np.eye(3)
    >>> float(epipolar_ordinate((1.0, 2.0), 5.0, E, E, 100.0))   # normal case: same ordinate
    2.0
    """
    p = as_points(xy1, 2, "xy1")
    if p.shape[0] != 1:
        raise InputError(f"xy1 must be one point (x, y), got {p.shape[0]}")
    x1, y1 = p[0]
    f = _number(f, "f", positive=True)
    A1, A2 = _rotation(rotation1, "rotation1"), _rotation(rotation2, "rotation2")
    xc = np.asarray(x_c, dtype=float) if not isinstance(x_c, (str, bytes)) else np.array(np.nan)
    if not np.all(np.isfinite(xc)):
        raise InputError("x_c contains NaN or inf")
    _, Y1, Z1 = A1 @ np.array([x1, y1, -f])
    a = A2
    den = Y1 * a[2, 1] - Z1 * a[1, 1]
    if abs(den) < 1e-12 * (abs(Y1) + abs(Z1)):
        raise DegenerateGeometryError("the epipolar line is parallel to the y axis of image 2 (Y'1 a32 = Z'1 a22)")
    num = Z1 * (a[1, 0] * xc - a[1, 2] * f) - Y1 * (a[2, 0] * xc - a[2, 2] * f)
    y = (-num if as_printed else num) / den
    return float(y) if np.ndim(y) == 0 else y


def _rotation(value, name):
    try:
        A = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise InputError(f"{name} must be a 3×3 matrix of numbers") from None
    if A.shape != (3, 3) or not np.all(np.isfinite(A)):
        raise InputError(f"{name} must be a finite 3×3 matrix, got shape {A.shape}")
    if not (np.allclose(A.T @ A, np.eye(3), atol=1e-8) and np.linalg.det(A) > 0):
        raise InputError(f"{name} is not a rotation matrix (AᵀA ≠ E or det ≠ +1)")
    return A


def _io_eo(io, eo, what):
    _expect(io, InteriorOrientation, f"{what} interior orientation")
    _expect(eo, ExteriorOrientation, f"{what} exterior orientation")
    if io.has_distortion:
        raise InputError(f"{what}: the epipolar geometry here is that of distortion-free images; "
                         "correct the coordinates (photolib.camera.correct_distortion) and pass an ideal camera")


def epipolar_line(xy1, eo1: ExteriorOrientation, eo2: ExteriorOrientation, io1: InteriorOrientation,
                  io2: InteriorOrientation | None = None) -> np.ndarray:
    """Epipolar lines on image 2 of points of image 1: a·x + b·y + c = 0 (mm), a² + b² = 1.

    The plane through the base B = S₂ − S₁ and the ray r₁ = A₁(x₁ − x₀, y₁ − y₀, −f)ᵀ has the
    normal n = B × r₁ (the coplanarity (5.6.1) in object space); a point of image 2 lies on it
    when n · A₂(x − x₀, y − y₀, −f)ᵀ = 0. With m = A₂ᵀn: a = m₁, b = m₂,
    c = −m₁x₀ − m₂y₀ − m₃f, then normalised (the overall sign is arbitrary: only the line matters).

    Parameters
    ----------
    xy1 : (n, 2) array
        Points of image 1, mm.
    eo1, eo2 : ExteriorOrientation
        Orientation of images 1 and 2.
    io1 : InteriorOrientation
        Camera of image 1 (and of image 2 unless ``io2`` is given); distortion-free.
    io2 : InteriorOrientation, optional

    Returns
    -------
    (n, 3) ndarray
        Line coefficients (a, b, c) on image 2.

    Raises
    ------
    InputError
        Wrong types or shapes, NaN, a camera with distortion.
    DegenerateGeometryError
        Zero base, or a ray along the base (the epipole itself: no line).

    References
    ----------
    Chibunichev (2022), §5.6, eq. (5.6.1), Figs. 5.16–5.17; §1.4, eq. (1.4.5).

    Examples
    --------
    >>> from photolib.camera import InteriorOrientation, ExteriorOrientation
    >>> from photolib.epipolar import epipolar_line
    >>> io = InteriorOrientation(100.0)
    >>> line = epipolar_line([[3.0, 7.0]], ExteriorOrientation(0, 0, 1000), ExteriorOrientation(400, 0, 1000), io)
    >>> np.round(np.abs(line), 6)            # the normal case: the row y = 7
    array([[0., 1., 7.]])
    """
    io2 = io1 if io2 is None else io2
    _io_eo(io1, eo1, "image 1")
    _io_eo(io2, eo2, "image 2")
    xy = as_points(xy1, 2, "xy1")
    B = eo2.center - eo1.center
    nb = np.linalg.norm(B)
    if nb < 1e-12:
        raise DegenerateGeometryError("the two projection centres coincide: no base, no epipolar lines")
    r1 = np.column_stack([xy[:, 0] - io1.x0, xy[:, 1] - io1.y0, np.full(len(xy), -io1.f)]) @ eo1.matrix.T
    n = np.cross(B / nb, r1 / np.linalg.norm(r1, axis=1, keepdims=True))
    m = n @ eo2.matrix
    a, b = m[:, 0], m[:, 1]
    c = -m[:, 0] * io2.x0 - m[:, 1] * io2.y0 - m[:, 2] * io2.f
    norm = np.hypot(a, b)
    if np.any(norm < 1e-12):
        raise DegenerateGeometryError("a ray of image 1 runs along the base (or the plane is parallel to image 2): "
                                      "no epipolar line")
    return np.column_stack([a, b, c]) / norm[:, None]


def epipolar_intersection(xy1, xy2, eo1: ExteriorOrientation, eo2: ExteriorOrientation, eo3: ExteriorOrientation,
                          io: InteriorOrientation, *, min_angle: float = 1e-3) -> np.ndarray:
    """The point of image 3 as the intersection of the epipolar lines of xy1 and xy2 (Fig. 5.18).

    Parameters
    ----------
    xy1, xy2 : (n, 2) arrays
        Homologous points on images 1 and 2, mm.
    eo1, eo2, eo3 : ExteriorOrientation
        Orientation of the three images.
    io : InteriorOrientation
        The camera (distortion-free).
    min_angle : float
        Smallest angle between the two lines (radians) accepted as an intersection.

    Returns
    -------
    (n, 2) ndarray
        x, y on image 3, mm.

    Raises
    ------
    InputError
        Wrong shapes or types, NaN, a different number of points on images 1 and 2.
    DegenerateGeometryError
        The two lines are (nearly) parallel — e.g. three collinear projection centres — or a
        centre pair without base.

    References
    ----------
    Chibunichev (2022), §5.6, Fig. 5.18 (three overlapping images, the CDW system).

    Examples
    --------
    >>> from photolib.camera import InteriorOrientation, ExteriorOrientation
    >>> from photolib.single_image import project
    >>> from photolib.epipolar import epipolar_intersection
    >>> io = InteriorOrientation(100.0)
    >>> eos = [ExteriorOrientation(0, 0, 1000), ExteriorOrientation(400, 0, 1000), ExteriorOrientation(200, 300, 1000)]
    >>> P = [[150.0, 120.0, 30.0]]
    >>> xy3 = epipolar_intersection(project(P, eos[0], io), project(P, eos[1], io), *eos, io)
    >>> bool(np.allclose(xy3, project(P, eos[2], io)))
    True
    """
    p1, p2 = as_points(xy1, 2, "xy1"), as_points(xy2, 2, "xy2")
    if len(p1) != len(p2):
        raise InputError(f"xy1 has {len(p1)} points, xy2 {len(p2)}")
    _io_eo(io, eo3, "image 3")
    l13 = epipolar_line(p1, eo1, eo3, io)
    l23 = epipolar_line(p2, eo2, eo3, io)
    h = np.cross(l13, l23)
    sin_angle = np.abs(h[:, 2])                 # lines normalised: |a1 b2 − a2 b1| = sin of the angle
    if np.any(sin_angle < np.sin(_number(min_angle, "min_angle", positive=True))):
        raise DegenerateGeometryError("the two epipolar lines on image 3 are (nearly) parallel: no intersection "
                                      "(collinear projection centres or a point in their plane)")
    return h[:, :2] / h[:, 2:3]


# --- §5.6: resampling to the normal case -----------------------------------------------------------------
def _rotvec(R):
    from scipy.spatial.transform import Rotation
    return Rotation.from_matrix(R).as_rotvec()


def _exp(v):
    from scipy.spatial.transform import Rotation
    return Rotation.from_rotvec(v).as_matrix()


def _min_rotation(u, v):
    """The smallest rotation taking unit vector u to unit vector v."""
    axis = np.cross(u, v)
    s, c = np.linalg.norm(axis), float(np.dot(u, v))
    if s < 1e-15:
        if c > 0:
            return np.eye(3)
        raise DegenerateGeometryError("the base points against the mean x axis of the images: swap the images")
    return _exp(axis / s * np.arctan2(s, c))


@dataclass(frozen=True, eq=False, repr=False)
class EpipolarPair:
    """A pair resampled to the normal case by :func:`rectify_pair`.

    Both images share the rotation ``rotation`` (camera → object), whose x axis is the base
    S₂ − S₁, and the focal length f; corresponding points have equal y. In the rectified frames
    (same pixel size Δ), the image coordinates are x = x_n − ``x_offset[i]``, y = y_n − ``y_offset``
    where (x_n, y_n) = −f·(X̄/Z̄, Ȳ/Z̄) of the ray in the common system; the x-parallax of a point
    is p = x_n1 − x_n2 (mm) and the row of a point is the same on both images.

    Attributes
    ----------
    left, right : (rows, cols) arrays
        The resampled images (``fill`` outside the originals).
    valid_left, valid_right : (rows, cols) bool arrays
        Pixels that come from inside the original images.
    rotation : (3, 3) array
        The common rotation A_n (camera → object).
    f, pixel_size : float
        Focal length and pixel size, mm.
    x_offset : (2,) array
        x_n of the centre of each rectified frame, mm.
    y_offset : float
        y_n of the centre of both rectified frames, mm.
    homographies : (2, 3, 3) array
        Original pixel (col, row, 1) → rectified pixel, per image.
    eo : tuple of ExteriorOrientation
        The rectified images' orientation (centres S₁, S₂ and the rotation A_n, order of eo1).

    References
    ----------
    Chibunichev (2022), §5.6 (the "ideal case" pair), §6.1, Fig. 6.3.

    Examples
    --------
    >>> from photolib.epipolar import EpipolarPair
    >>> EpipolarPair.__name__
    'EpipolarPair'
    """

    left: np.ndarray
    right: np.ndarray
    valid_left: np.ndarray
    valid_right: np.ndarray
    rotation: np.ndarray
    f: float
    pixel_size: float
    x_offset: np.ndarray
    y_offset: float
    homographies: np.ndarray
    eo: tuple

    def interior(self, which: int) -> InteriorOrientation:
        """The interior orientation of rectified image ``which`` (0 or 1) in the frame convention of
        :func:`photolib.synthetic.pixel_to_image`: principal point (−x_offset, −y_offset)."""
        return InteriorOrientation(self.f, -float(self.x_offset[which]), -float(self.y_offset))

    def to_rectified(self, xy_pixels, which: int) -> np.ndarray:
        """Original pixel positions (col, row) of image ``which`` → rectified pixel positions."""
        return _apply_h(self.homographies[which], as_points(xy_pixels, 2, "pixel positions"))

    def from_rectified(self, xy_pixels, which: int) -> np.ndarray:
        """Rectified pixel positions (col, row) of image ``which`` → original pixel positions."""
        return _apply_h(np.linalg.inv(self.homographies[which]), as_points(xy_pixels, 2, "pixel positions"))

    def __repr__(self) -> str:
        return f"EpipolarPair({self.left.shape[0]} × {self.left.shape[1]} pixels, f = {self.f:.3f} mm)"


def _apply_h(H, pts):
    q = np.column_stack([pts, np.ones(len(pts))]) @ H.T
    if np.any(q[:, 2] <= 0):
        raise PointBehindCameraError("a point maps behind the rectified camera", points=np.flatnonzero(q[:, 2] <= 0))
    return q[:, :2] / q[:, 2:3]


def rectify_pair(left, right, io: InteriorOrientation, eo1: ExteriorOrientation, eo2: ExteriorOrientation,
                 pixel_size: float, *, shape=None, fill: float = 0.0) -> EpipolarPair:
    """Resample a pair to the normal ("ideal") case: epipolar lines become the rows of the images.

    The common rotation A_n is the mid rotation of the two images, A₁·exp(½·log(A₁ᵀA₂)), turned
    by the smallest rotation that brings its x axis onto the base B = S₂ − S₁ (Bouguet's
    construction, used by OpenCV's ``stereoRectify``). A pixel of rectified image i looks along
    r = A_n(x_n, y_n, −f)ᵀ; its brightness is read from the original image at the projection
    of r through A_i (a homography, (1.4.12)), by bilinear interpolation (1.10.7). The rectified
    frames keep the size and pixel size; each is centred on the image of the original frame
    centre in x, both on their mean in y.

    Parameters
    ----------
    left, right : (rows, cols) arrays
        Images 1 and 2 (frame convention of :func:`photolib.synthetic.pixel_to_image`).
    io : InteriorOrientation
        The camera of both images (distortion-free).
    eo1, eo2 : ExteriorOrientation
        Their orientation (e.g. from relative orientation, Chapter 2, or a block, Chapter 3).
    pixel_size : float
        Δ, mm.
    shape : (rows, cols), optional
        Size of the rectified frames (default: that of the originals).
    fill : float
        Brightness outside the original images.

    Returns
    -------
    EpipolarPair

    Raises
    ------
    InputError
        Non-2-D or NaN images, images of different sizes, wrong types, Δ ≤ 0, a camera with
        distortion.
    DegenerateGeometryError
        No base, or a base along the viewing direction (rectification undefined); a base
        pointing against the images' x axis (swap left and right).

    References
    ----------
    Chibunichev (2022), §5.6 (the normal case; epipolar images), §6.1, Fig. 6.3; §1.4, (1.4.12).

    Examples
    --------
    >>> from photolib.camera import InteriorOrientation, ExteriorOrientation
    >>> from photolib.epipolar import rectify_pair
    >>> io = InteriorOrientation(50.0)
    >>> e1 = ExteriorOrientation(0, 0, 500, 0.01, -0.02, 0.03)
    >>> e2 = ExteriorOrientation(100, 5, 502, -0.02, 0.01, 0.0)
    >>> img = np.random.default_rng(0).random((40, 60))
    >>> rp = rectify_pair(img, img, io, e1, e2, 0.1)
    >>> round(float(rp.rotation[:, 0] @ [100, 5, 2] / np.linalg.norm([100, 5, 2])), 12)   # x axis on the base
    1.0
    """
    from scipy.ndimage import map_coordinates
    L, R = _image(left, "left"), _image(right, "right")
    if L.shape != R.shape:
        raise InputError(f"left and right images differ in size: {L.shape} and {R.shape}")
    _io_eo(io, eo1, "image 1")
    _io_eo(io, eo2, "image 2")
    d = _number(pixel_size, "pixel_size", positive=True)
    fill = _number(fill, "fill")
    from .synthetic import _frame_shape
    out_shape = L.shape if shape is None else _frame_shape(shape)
    B = eo2.center - eo1.center
    nb = np.linalg.norm(B)
    if nb < 1e-12:
        raise DegenerateGeometryError("the two projection centres coincide: a pair without base cannot be rectified")
    A1, A2 = eo1.matrix, eo2.matrix
    A_mid = A1 @ _exp(0.5 * _rotvec(A1.T @ A2))
    b_mid = A_mid.T @ (B / nb)
    if abs(b_mid[2]) > 0.9:
        raise DegenerateGeometryError("the base runs along the viewing direction: no normal case")
    An = A_mid @ _min_rotation(np.array([1.0, 0.0, 0.0]), b_mid)
    f = float(io.f)

    def mm_h(A):      # original (x, y, 1) mm → rectified (x_n, y_n, 1) mm (projective)
        K = np.array([[1.0, 0.0, -io.x0], [0.0, 1.0, -io.y0], [0.0, 0.0, -f]])
        return np.diag([f, f, -1.0]) @ An.T @ A @ K

    h_in, w_in = L.shape
    h_out, w_out = out_shape
    P_in = np.array([[d, 0, -(w_in - 1) / 2 * d], [0, -d, (h_in - 1) / 2 * d], [0, 0, 1.0]])
    Hm = [mm_h(A1), mm_h(A2)]
    centres = []
    for H in Hm:
        c = H @ np.array([0.0, 0.0, 1.0])
        if c[2] <= 0:
            raise DegenerateGeometryError("the frame centre maps behind the rectified camera (rotation > 90°)")
        centres.append(c[:2] / c[2])
    x_off = np.array([centres[0][0], centres[1][0]])
    y_off = 0.5 * (centres[0][1] + centres[1][1])
    homs, images, valid = [], [], []
    cc, rr = np.meshgrid(np.arange(w_out, dtype=float), np.arange(h_out, dtype=float))
    for i, (H, img) in enumerate(zip(Hm, (L, R))):
        P_out = np.array([[d, 0, -(w_out - 1) / 2 * d + x_off[i]], [0, -d, (h_out - 1) / 2 * d + y_off],
                          [0, 0, 1.0]])
        Hp = np.linalg.inv(P_out) @ H @ P_in
        Hp = Hp / Hp[2, 2]
        homs.append(Hp)
        inv = np.linalg.inv(Hp)
        q = np.stack([cc.ravel(), rr.ravel(), np.ones(cc.size)]) .T @ inv.T
        ok = q[:, 2] > 0
        with np.errstate(divide="ignore", invalid="ignore"):
            src_c = np.where(ok, q[:, 0] / q[:, 2], -1e9)
            src_r = np.where(ok, q[:, 1] / q[:, 2], -1e9)
        inside = ok & (src_c >= 0) & (src_c <= w_in - 1) & (src_r >= 0) & (src_r <= h_in - 1)
        vals = map_coordinates(img, [np.clip(src_r, 0, h_in - 1), np.clip(src_c, 0, w_in - 1)], order=1)
        images.append(np.where(inside, vals, fill).reshape(out_shape))
        valid.append(inside.reshape(out_shape))
    eo_n = (ExteriorOrientation.from_matrix(eo1.center, An, eo1.order),
            ExteriorOrientation.from_matrix(eo2.center, An, eo1.order))
    return EpipolarPair(images[0], images[1], valid[0], valid[1], An, f, d, x_off, float(y_off), np.array(homs), eo_n)
