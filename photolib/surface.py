"""Digital surface models by correlation — Chapter 6, §6.1–6.3.

* §6.1 — the segment cd of the epipolar line on image 2 that can hold the match of a point of
  image 1 when the heights lie in [Z_min, Z_max]: the ray of the point cut at Z_min and Z_max
  by (6.1.1), both points projected into image 2 by (6.1.2) (:func:`epipolar_segment`).
* §6.2 — a regular DSM from a pair by the vertical-line search ("vertical line locus"): for
  every grid node (X, Y) the heights Z_i = Z_min + i·ΔZ, i = 0…n, n = ⌈(Z_max − Z_min)/ΔZ⌉ (the
  book's i = 1…n misses Z_min), are projected into both images by (6.1.2); the correlation
  coefficient (5.1.2) of the two windows — here an object-space window of (2h + 1)² points
  around the node on the plane Z_i, projected into both images — is maximal at the surface;
  ΔZ is then reduced around the best Z, coarse to fine (:func:`dsm_vertical_line`).
* §6.3 — a regular DSM from many images: the same search for every pair of images that sees
  the node, keeping per node the pair with the highest correlation (:func:`dsm_multi_image`).

Conventions. Orientation as in Chapter 1 (:class:`photolib.camera.InteriorOrientation`,
:class:`photolib.camera.ExteriorOrientation`); digital images ``img[row, col]`` with the fiducial
centre at the centre of the frame (:func:`photolib.synthetic.pixel_to_image`), brightness read by
bilinear interpolation (1.10.7). A node is reported ``valid`` only when its correlation reaches
``min_correlation`` and its windows lie inside both images; otherwise Z is NaN (no confident
wrong heights).
"""

from __future__ import annotations

from dataclasses import dataclass
from itertools import combinations

import numpy as np

from . import _checks
from .camera import ExteriorOrientation, InteriorOrientation, _expect, as_points
from .errors import DegenerateGeometryError, InputError, PointBehindCameraError

__all__ = ["epipolar_segment", "DSMResult", "dsm_vertical_line", "dsm_multi_image"]


_number = _checks.number
_IMAGE_MESSAGES = {"type": "{name} must be an array of numbers", "numeric": "{name} must be an array of numbers",
                   "ndim": "{name} must be a 2-D image, got shape {shape}",
                   "small": "{name} must be a 2-D image, got shape {shape}"}


def _z_range(z_min, z_max):
    lo, hi = _number(z_min, "z_min"), _number(z_max, "z_max")
    if not lo < hi:
        raise InputError(f"z_min must be below z_max, got {lo} and {hi}")
    return lo, hi


def epipolar_segment(xy1, eo1: ExteriorOrientation, eo2: ExteriorOrientation, io: InteriorOrientation,
                     z_min: float, z_max: float, io2: InteriorOrientation | None = None):
    """End points c (at Z_min) and d (at Z_max) on image 2 of the epipolar segment of points of image 1.

    (6.1.1): X = X_S + (Z − Z_S)·(a₁₁(x − x₀) + a₁₂(y − y₀) − a₁₃f)/(a₃₁(x − x₀) + a₃₂(y − y₀) − a₃₃f),
    Y likewise with a₂ⱼ — the ray of image 1 cut by the planes Z_min and Z_max (1.4.7);
    (6.1.2): the two points projected into image 2 by the collinearity equations (1.4.12).

    Parameters
    ----------
    xy1 : (n, 2) array
        Points of image 1, mm.
    eo1, eo2 : ExteriorOrientation
        Orientation of images 1 and 2.
    io : InteriorOrientation
        Camera of image 1 (and 2 unless ``io2``).
    z_min, z_max : float
        Height range of the terrain, m (z_min < z_max).
    io2 : InteriorOrientation, optional

    Returns
    -------
    c, d : (n, 2) ndarrays
        The ends of the segment on image 2, mm.

    Raises
    ------
    InputError
        NaN, wrong shapes or types, z_min ≥ z_max.
    PointBehindCameraError
        A plane Z_min/Z_max at or above a projection centre (the ray never reaches it), or a
        point of the segment behind camera 2.
    DegenerateGeometryError
        A horizontal ray.

    References
    ----------
    Chibunichev (2022), §6.1, eqs. (6.1.1), (6.1.2), Fig. 6.2; §1.4, (1.4.7), (1.4.12).

    Examples
    --------
    >>> from photolib.camera import InteriorOrientation, ExteriorOrientation
    >>> from photolib.surface import epipolar_segment
    >>> io = InteriorOrientation(100.0)
    >>> c, d = epipolar_segment([[0.0, 0.0]], ExteriorOrientation(0, 0, 1000), ExteriorOrientation(400, 0, 1000),
    ...                         io, 0.0, 200.0)
    >>> c, d                                  # x-parallax b·f/(Z_S − Z): 40 mm at Z = 0, 50 mm at Z = 200
    (array([[-40.,   0.]]), array([[-50.,   0.]]))
    """
    from .single_image import image_to_ground, project
    io2 = io if io2 is None else io2
    for e, i, w in ((eo1, io, "image 1"), (eo2, io2, "image 2")):
        _expect(e, ExteriorOrientation, f"{w} exterior orientation")
        _expect(i, InteriorOrientation, f"{w} interior orientation")
    lo, hi = _z_range(z_min, z_max)
    xy = as_points(xy1, 2, "xy1")
    if hi >= eo1.Zs:
        raise PointBehindCameraError(f"z_max = {hi} is not below the projection centre of image 1 (Z_S = {eo1.Zs})")
    try:
        P = [image_to_ground(xy, z, eo1, io) for z in (lo, hi)]
    except PointBehindCameraError:
        raise
    except DegenerateGeometryError as exc:
        if "behind" in str(exc):
            raise PointBehindCameraError(f"the height range is behind camera 1 for some rays: {exc}") from None
        raise
    return project(P[0], eo2, io2), project(P[1], eo2, io2)


@dataclass(frozen=True, eq=False, repr=False)
class DSMResult:
    """A regular DSM found by correlation (§6.2–6.3).

    Attributes
    ----------
    X, Y : (ny, nx) arrays
        The grid nodes, m.
    Z : (ny, nx) array
        Heights, m (NaN where not ``valid``).
    correlation : (ny, nx) array
        R (5.1.2) at the chosen height (NaN where undefined).
    valid : (ny, nx) bool array
        R ≥ ``min_correlation`` and windows inside the images.
    pair : (ny, nx) int array
        Index into ``pairs`` of the pair that gave the height (−1: none).
    pairs : list of (int, int)
        The image pairs searched.

    References
    ----------
    Chibunichev (2022), §6.2–6.3, Figs. 6.4–6.5.

    Examples
    --------
    >>> from photolib.surface import DSMResult
    >>> r = DSMResult(np.zeros((1, 1)), np.zeros((1, 1)), np.ones((1, 1)), np.ones((1, 1)),
    ...               np.ones((1, 1), bool), np.zeros((1, 1), int), [(0, 1)])
    >>> r
    DSMResult(1 × 1 nodes, 1 valid, 1 pairs)
    """

    X: np.ndarray
    Y: np.ndarray
    Z: np.ndarray
    correlation: np.ndarray
    valid: np.ndarray
    pair: np.ndarray
    pairs: list

    def __repr__(self) -> str:
        return (f"DSMResult({self.Z.shape[0]} × {self.Z.shape[1]} nodes, {int(self.valid.sum())} valid, "
                f"{len(self.pairs)} pairs)")


class _View:
    """One oriented digital image: projection (1.4.12) and bilinear sampling (NaN outside)."""

    def __init__(self, image, io, eo, pixel_size, name):
        _expect(io, InteriorOrientation, f"{name} interior orientation")
        _expect(eo, ExteriorOrientation, f"{name} exterior orientation")
        if io.has_distortion:
            raise InputError(f"{name}: distortion-free cameras only (correct the images first)")
        img = _checks.image(image, name, 2, messages=_IMAGE_MESSAGES, reject=(str, bytes))
        self.img, self.io, self.eo, self.d = img, io, eo, pixel_size
        self.A, self.S = eo.matrix, eo.center

    def sample(self, P):
        """Brightness at the projections of object points P (..., 3); NaN outside or behind."""
        star = (P - self.S) @ self.A
        zs = star[..., 2]
        with np.errstate(divide="ignore", invalid="ignore"):
            x = self.io.x0 - self.io.f * star[..., 0] / zs
            y = self.io.y0 - self.io.f * star[..., 1] / zs
        h, w = self.img.shape
        col = x / self.d + (w - 1) / 2
        row = (h - 1) / 2 - y / self.d
        ok = (zs < 0) & (col >= 0) & (col <= w - 1) & (row >= 0) & (row <= h - 1)
        c0 = np.clip(np.floor(np.where(ok, col, 0)).astype(int), 0, w - 2)
        r0 = np.clip(np.floor(np.where(ok, row, 0)).astype(int), 0, h - 2)
        dc, dr = np.where(ok, col, 0) - c0, np.where(ok, row, 0) - r0
        im = self.img
        v = (im[r0, c0] * (1 - dc) * (1 - dr) + im[r0, c0 + 1] * dc * (1 - dr)
             + im[r0 + 1, c0] * (1 - dc) * dr + im[r0 + 1, c0 + 1] * dc * dr)
        return np.where(ok, v, np.nan)


def _ncc(a, b):
    """(5.1.2) along the last axis; NaN where a window is incomplete or flat."""
    am = a - a.mean(-1, keepdims=True)
    bm = b - b.mean(-1, keepdims=True)
    den = np.sqrt((am * am).sum(-1) * (bm * bm).sum(-1))
    with np.errstate(divide="ignore", invalid="ignore"):
        r = (am * bm).sum(-1) / den
    return np.where(den > 1e-12, r, np.nan)


def _grid(X, Y):
    X = np.asarray(X, dtype=float) if not isinstance(X, (str, bytes)) else np.array(np.nan)
    Y = np.asarray(Y, dtype=float) if not isinstance(Y, (str, bytes)) else np.array(np.nan)
    if X.shape != Y.shape or X.ndim != 2 or X.size == 0:
        raise InputError(f"X and Y must be 2-D grids of one shape, got {X.shape} and {Y.shape}")
    if not (np.all(np.isfinite(X)) and np.all(np.isfinite(Y))):
        raise InputError("the grid X, Y contains NaN or inf")
    return X, Y


def _steps(steps):
    try:
        s = np.asarray(steps, dtype=float).ravel()
    except (TypeError, ValueError):
        raise InputError(f"steps must be numbers, got {steps!r}") from None
    if s.size == 0 or not np.all(np.isfinite(s)) or np.any(s <= 0) or np.any(np.diff(s) >= 0):
        raise InputError(f"steps must be positive and strictly decreasing (coarse to fine), got {steps!r}")
    return s


def _search(v1, v2, X, Y, lo, hi, steps, offsets):
    """Vertical-line search for all nodes at once; returns Z (nodes,) and R (nodes,)."""
    Xf, Yf = X.ravel(), Y.ravel()
    WX, WY = Xf[:, None] + offsets[:, 0], Yf[:, None] + offsets[:, 1]

    def corr(Z):
        P = np.stack([WX, WY, np.broadcast_to(Z[:, None], WX.shape)], axis=-1)
        return _ncc(v1.sample(P), v2.sample(P))

    best_z = np.full(Xf.size, np.nan)
    best_r = np.full(Xf.size, -np.inf)
    n = int(np.ceil((hi - lo) / steps[0] - 1e-9))
    for i in range(n + 1):                                  # Z_i = Z_min + i·ΔZ, i = 0 … n
        Z = np.full(Xf.size, min(lo + i * steps[0], hi))
        r = corr(Z)
        better = np.nan_to_num(r, nan=-np.inf) > best_r
        best_z[better], best_r[better] = Z[better], r[better]
    prev = steps[0]
    for dz in steps[1:]:                                    # shrink ΔZ around the best Z
        k = int(np.ceil(prev / dz - 1e-9))
        centre = best_z.copy()
        for j in range(-k, k + 1):
            Z = np.clip(centre + j * dz, lo, hi)
            r = corr(np.nan_to_num(Z, nan=lo))
            better = np.isfinite(centre) & (np.nan_to_num(r, nan=-np.inf) > best_r)
            best_z[better], best_r[better] = Z[better], r[better]
        prev = dz
    best_r[~np.isfinite(best_r)] = np.nan
    return best_z, best_r


def _offsets(half_window, window_spacing):
    h = int(half_window)
    g = np.arange(-h, h + 1) * window_spacing
    WX, WY = np.meshgrid(g, g)
    return np.column_stack([WX.ravel(), WY.ravel()])


def _views(images, io, eos, pixel_size):
    if isinstance(images, np.ndarray) and images.ndim == 2:
        raise InputError("images must be a sequence of 2-D images, got one image")
    try:
        images = list(images)
        eos = list(eos)
    except TypeError:
        raise InputError("images and eos must be sequences") from None
    if len(images) != len(eos):
        raise InputError(f"{len(images)} images but {len(eos)} exterior orientations")
    if len(images) < 2:
        raise InputError("a DSM by correlation needs at least two images")
    ios = list(io) if isinstance(io, (list, tuple)) else [io] * len(images)
    if len(ios) != len(images):
        raise InputError(f"{len(images)} images but {len(ios)} interior orientations")
    d = _number(pixel_size, "pixel_size", positive=True)
    return [_View(im, i, e, d, f"image {k}") for k, (im, i, e) in enumerate(zip(images, ios, eos))]


def _check(X, Y, z_min, z_max, steps, half_window, window_spacing, min_correlation, views):
    X, Y = _grid(X, Y)
    lo, hi = _z_range(z_min, z_max)
    s = _steps(steps)
    _checks.integer(half_window, "half_window")
    if window_spacing is None:
        ws = abs(X[0, 1] - X[0, 0]) if X.shape[1] > 1 else (abs(Y[1, 0] - Y[0, 0]) if X.shape[0] > 1 else 0.0)
        if ws <= 0:
            raise InputError("give window_spacing for a grid of one node")
    else:
        ws = _number(window_spacing, "window_spacing", positive=True)
    mc = _number(min_correlation, "min_correlation")
    for v in views:
        if hi >= v.S[2]:
            raise PointBehindCameraError(f"z_max = {hi} m is not below a projection centre (Z_S = {v.S[2]} m)")
    return X, Y, lo, hi, s, ws, mc


def dsm_vertical_line(images, io, eos, X, Y, z_min: float, z_max: float, *, pixel_size: float,
                      steps=(1.0, 0.25, 0.05), half_window: int = 2, window_spacing: float | None = None,
                      min_correlation: float = 0.6) -> DSMResult:
    """Regular DSM from a pair by the vertical-line search with coarse-to-fine ΔZ (§6.2).

    For every node the heights Z_i = Z_min + i·ΔZ, i = 0…n, n = ⌈(Z_max − Z_min)/ΔZ⌉ are tried;
    at each, a (2h + 1)² window of points on the plane Z_i around the node (spacing
    ``window_spacing``) is projected into both images by (6.1.2) and the correlation coefficient
    (5.1.2) of the two sets of brightness values is computed; the Z of the maximum is kept. Each
    following step ΔZ′ of ``steps`` searches Z_best ± ΔZ (the previous step) in steps of ΔZ′.

    Parameters
    ----------
    images : sequence of two (rows, cols) arrays
        The pair.
    io : InteriorOrientation or sequence of them
        The camera(s), distortion-free.
    eos : sequence of two ExteriorOrientation
        Their orientation.
    X, Y : (ny, nx) arrays
        Grid nodes, m.
    z_min, z_max : float
        Height range, m.
    pixel_size : float
        Δ of the images, mm.
    steps : sequence of float
        ΔZ from coarse to fine, m (strictly decreasing).
    half_window : int
        h: the object-space window has (2h + 1)² points.
    window_spacing : float, optional
        Spacing of the window points, m (default: the grid spacing along X).
    min_correlation : float
        Nodes with a lower R are not valid (Z = NaN).

    Returns
    -------
    DSMResult

    Raises
    ------
    InputError
        Not exactly two images, mismatched lists, NaN pixels or nodes, grids of different shapes,
        z_min ≥ z_max, steps not decreasing.
    PointBehindCameraError
        z_max at or above a projection centre.

    References
    ----------
    Chibunichev (2022), §6.2, Fig. 6.4 (Z_i = Z_min + iΔZ, coarse-to-fine ΔZ); §6.1, (6.1.2); §5.1, (5.1.2).

    Examples
    --------
    >>> from photolib.camera import InteriorOrientation, ExteriorOrientation
    >>> from photolib.synthetic import terrain_scene, render_image
    >>> from photolib.surface import dsm_vertical_line
    >>> sc = terrain_scene(extent=60.0, spacing=0.25, n_buildings=0, relief=4.0, seed=1)
    >>> io, eos = InteriorOrientation(35.0), [ExteriorOrientation(25.0, 30.0, 250.0), ExteriorOrientation(35.0, 30.0, 250.0)]
    >>> imgs = [render_image(sc, io, e, (200, 200), pixel_size=0.02).image for e in eos]
    >>> X, Y = np.meshgrid(np.arange(26.0, 35.0, 2.0), np.arange(26.0, 35.0, 2.0))
    >>> r = dsm_vertical_line(imgs, io, eos, X, Y, 90.0, 110.0, pixel_size=0.02, window_spacing=0.3)
    >>> bool(np.nanmax(np.abs(r.Z - sc.surface_at(X, Y))) < 0.2), int(r.valid.sum())
    (True, 15)
    """
    views = _views(images, io, eos, pixel_size)
    if len(views) != 2:
        raise InputError(f"the vertical-line search of §6.2 takes a pair; got {len(views)} images "
                         "(use dsm_multi_image)")
    X, Y, lo, hi, s, ws, mc = _check(X, Y, z_min, z_max, steps, half_window, window_spacing, min_correlation, views)
    Z, R = _search(views[0], views[1], X, Y, lo, hi, s, _offsets(half_window, ws))
    Z, R = Z.reshape(X.shape), R.reshape(X.shape)
    valid = np.isfinite(R) & (np.nan_to_num(R, nan=-2) >= mc)
    return DSMResult(X, Y, np.where(valid, Z, np.nan), R, valid, np.where(valid, 0, -1), [(0, 1)])


def dsm_multi_image(images, io, eos, X, Y, z_min: float, z_max: float, *, pixel_size: float, pairs=None,
                    steps=(1.0, 0.25, 0.05), half_window: int = 2, window_spacing: float | None = None,
                    min_correlation: float = 0.6) -> DSMResult:
    """Regular DSM from many images: the vertical-line search on every pair, the best R per node (§6.3).

    Every pair (all combinations by default) is searched as in :func:`dsm_vertical_line`; each
    node takes the height of the pair whose correlation is highest (Fig. 6.5: the pair that sees
    the neighbourhood of the point alike — e.g. not across a roof edge that hides it on one image).
    The book recommends ≥ 60 % forward and side overlap so that every node has many pairs.

    Parameters
    ----------
    images : sequence of (rows, cols) arrays
        At least two images.
    io : InteriorOrientation or sequence of them
        The camera(s), distortion-free.
    eos : sequence of ExteriorOrientation
        Their orientation.
    X, Y : (ny, nx) arrays
        Grid nodes, m.
    z_min, z_max : float
        Height range, m.
    pixel_size : float
        Δ of the images, mm.
    pairs : sequence of (i, j), optional
        The pairs to search (default: all).
    steps, half_window, window_spacing, min_correlation
        As in :func:`dsm_vertical_line`.

    Returns
    -------
    DSMResult
        With ``pair`` the index into ``pairs`` chosen per node.

    Raises
    ------
    InputError
        Fewer than two images, mismatched lists, bad pair indices, NaN, z_min ≥ z_max.
    PointBehindCameraError
        z_max at or above a projection centre.

    References
    ----------
    Chibunichev (2022), §6.3, Fig. 6.5 (best pair per point; ≥ 60 % overlap).

    Examples
    --------
    >>> from photolib.camera import InteriorOrientation, ExteriorOrientation
    >>> from photolib.synthetic import terrain_scene, render_image
    >>> from photolib.surface import dsm_multi_image
    >>> sc = terrain_scene(extent=60.0, spacing=0.25, n_buildings=0, relief=4.0, seed=1)
    >>> io = InteriorOrientation(35.0)
    >>> eos = [ExteriorOrientation(x, 30.0, 250.0) for x in (25.0, 30.0, 35.0)]
    >>> imgs = [render_image(sc, io, e, (200, 200), pixel_size=0.02).image for e in eos]
    >>> X, Y = np.meshgrid(np.arange(27.0, 34.0, 2.0), np.arange(27.0, 34.0, 2.0))
    >>> r = dsm_multi_image(imgs, io, eos, X, Y, 90.0, 110.0, pixel_size=0.02, window_spacing=0.3)
    >>> r.pairs, bool(np.nanmax(np.abs(r.Z - sc.surface_at(X, Y))) < 0.2)
    ([(0, 1), (0, 2), (1, 2)], True)
    """
    views = _views(images, io, eos, pixel_size)
    X, Y, lo, hi, s, ws, mc = _check(X, Y, z_min, z_max, steps, half_window, window_spacing, min_correlation, views)
    if pairs is None:
        pairs = list(combinations(range(len(views)), 2))
    else:
        try:
            pairs = [tuple(int(v) for v in p) for p in pairs]
        except (TypeError, ValueError):
            raise InputError(f"pairs must be (i, j) index pairs, got {pairs!r}") from None
        if not pairs or any(len(p) != 2 or p[0] == p[1] or min(p) < 0 or max(p) >= len(views) for p in pairs):
            raise InputError(f"pairs must be pairs of distinct image indices below {len(views)}, got {pairs!r}")
    off = _offsets(half_window, ws)
    Zs, Rs = [], []
    for i, j in pairs:
        z, r = _search(views[i], views[j], X, Y, lo, hi, s, off)
        Zs.append(z)
        Rs.append(r)
    Rs = np.array(Rs)
    Zs = np.array(Zs)
    filled = np.nan_to_num(Rs, nan=-np.inf)
    k = np.argmax(filled, axis=0)
    idx = np.arange(Rs.shape[1])
    R, Z = Rs[k, idx], Zs[k, idx]
    valid = np.isfinite(R) & (np.nan_to_num(R, nan=-2) >= mc)
    shape = X.shape
    return DSMResult(X, Y, np.where(valid, Z, np.nan).reshape(shape), R.reshape(shape), valid.reshape(shape),
                     np.where(valid, k, -1).reshape(shape), pairs)
