"""True orthophotos: buildings, point clouds and the least-squares DSM — Chapter 7, §7.5, §7.6, §7.8.

Built on the Chapter 7 engine of :mod:`photolib.rectify` (:class:`~photolib.rectify.RasterGrid`,
:func:`~photolib.rectify.dem_height` (7.3.1), :func:`~photolib.rectify.resample`,
:func:`~photolib.rectify.frame_projector` (7.3.2)):

* §7.5 — :func:`visibility_mask`: the 0/1 "restriction matrix" of a DSM seen from the
  projection centre S, by the book's nadir-angle criterion (element A hides B when its nadir
  angle is larger, α_A > α_B) applied as a running maximum along the radial profile from the
  nadir point to each element (comparing only neighbouring elements, as the text suggests, misses
  occlusion by a group of elements); a brute-force ray march for comparison.
  :func:`index_matrix`: the 0/1/2 index matrix (ground, roof, visible wall) of a frame image from
  box buildings (Fig. 7.12). :func:`true_ortho_multi`: the orthophoto from all images at once
  (Fig. 7.13): per ortho pixel, drop the images whose ray is occluded by the DSM and take the
  unoccluded ray closest to nadir.
* §7.6 — :func:`ortho_from_points`: the orthophoto from a dense point cloud: forward
  accumulation over the four neighbouring pixels, or for each ortho pixel the mean /
  distance-weighted mean of the points within radius Δ, with the maximum-Z rule for walls.
* §7.8 — :func:`lsq_dsm_ortho`: the DSM and the true orthophoto by least squares, (7.8.1)–(7.8.3):
  unknowns F and Z per ortho pixel and the photometric gains k_i (one fixed to 1), each step solved
  by the block solver of :mod:`photolib.lsq` (the pixel blocks eliminated, a Schur complement for
  the gains); with ``estimate_eo=True`` the six EO elements of every image join the unknowns
  (7.8.4) together with the collinearity equations of ground control points, which fix the datum;
  :func:`lsq_unknown_count` the book's counts N = 2P + (S − 1) [+ 6S], M = PS.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable, Sequence

import numpy as np

from .errors import DegenerateGeometryError, InputError
from .rectify import RasterGrid, dem_height, rectify_forward, resample

__all__ = ["visibility_mask", "index_matrix", "TrueOrtho", "true_ortho_multi", "POINT_METHODS",
           "ortho_from_points", "lsq_unknown_count", "LsqOrtho", "lsq_dsm_ortho"]

POINT_METHODS = ("accumulate", "radius_mean", "idw", "max_z")



def _kernels():
    from . import _trueortho_kernels
    return _trueortho_kernels


def _grid(grid, name="grid"):
    if not isinstance(grid, RasterGrid):
        raise InputError(f"{name} must be a RasterGrid, got {type(grid).__name__}")
    return grid


def _raster(array, grid, name):
    try:
        a = np.asarray(array, dtype=np.float64)
    except (TypeError, ValueError):
        raise InputError(f"{name} must be a numeric array") from None
    if a.ndim != 2 or a.shape != grid.shape:
        raise InputError(f"{name} has shape {a.shape}, its grid {grid.shape}")
    if not np.all(np.isfinite(a)):
        raise InputError(f"{name} contains NaN or inf (fill the voids first)")
    return np.ascontiguousarray(a)


def _centre(centre):
    try:
        S = np.asarray(centre, dtype=np.float64).reshape(-1)
    except (TypeError, ValueError):
        raise InputError(f"the projection centre must be (X_S, Y_S, Z_S), got {centre!r}") from None
    if S.shape != (3,) or not np.all(np.isfinite(S)):
        raise InputError(f"the projection centre must be three finite numbers, got {centre!r}")
    return S


def visibility_mask(dsm, dsm_grid: RasterGrid, centre, *, method: str = "radial", step: float = 0.5):
    """The 0/1 restriction matrix of §7.5: which DSM elements the projection centre S sees.

    ``"radial"`` (the book's criterion): for every element B walk the horizontal profile from B
    towards the nadir point of S, sampling the DSM bilinearly (7.3.1) every ``step`` pixels; B
    is hidden when some element A on the profile has a larger nadir angle, tan α_A =
    r_A/(Z_S − Z_A) > tan α_B — i.e. the running maximum of tan α along the profile from the
    nadir outwards exceeds α_B (pitfall 19: comparing only the neighbouring element is not
    enough). ``"raymarch"`` (brute force, for checks): march along the 3-D ray from B to S in
    steps of ``step`` pixels of ray length and test whether the DSM rises above it.

    Parameters
    ----------
    dsm : (R, C) array
        Surface heights on ``dsm_grid`` (finite), with the pixel spacing of the orthophoto.
    dsm_grid : RasterGrid
        The DSM's grid.
    centre : (3,) array
        Projection centre (X_S, Y_S, Z_S), above the surface.
    method : {"radial", "raymarch"}
    step : float
        Sampling step in pixels (0 < step ≤ 1).

    Returns
    -------
    (R, C) uint8 array
        1 where the element is seen from S, 0 where it is hidden (multiply the orthophoto by it).

    Raises
    ------
    InputError
        NaN/inf, a DSM that does not match its grid, S below the highest DSM element, a bad step
        or method.

    References
    ----------
    Chibunichev (2022), §7.5, Fig. 7.11 (nadir angles α, β; the restriction matrix).

    Examples
    --------
    >>> import numpy as np
    >>> from photolib.rectify import RasterGrid
    >>> from photolib.trueortho import visibility_mask
    >>> dsm = np.zeros((1, 7)); dsm[0, 3] = 12.0              # a 12 m wall at X = 3.5
    >>> visibility_mask(dsm, RasterGrid(0.0, 1.0, 1.0, (1, 7)), (0.5, 0.5, 20.0)).tolist()
    [[1, 1, 1, 1, 0, 0, 0]]
    """
    grid = _grid(dsm_grid, "dsm_grid")
    z = _raster(dsm, grid, "dsm")
    S = _centre(centre)
    if method not in ("radial", "raymarch"):
        raise InputError(f"method must be 'radial' or 'raymarch', got {method!r}")
    try:
        step = float(step)
    except (TypeError, ValueError):
        raise InputError(f"step must be a number, got {step!r}") from None
    if not (0 < step <= 1):
        raise InputError(f"step must be in (0, 1] pixels, got {step}")
    if S[2] <= z.max():
        raise InputError(f"the projection centre (Z = {S[2]:.3f}) must be above the highest DSM element "
                         f"({z.max():.3f})")
    h = step * min(grid.dx, grid.dy)
    if method == "radial":
        out = np.empty(z.shape, np.uint8)
        _kernels().visibility_grid(z, grid.x0, grid.y0, grid.dx, grid.dy, S[0], S[1], S[2], h, 1e-9, out)
        return out
    return _raymarch(z, grid, S, h)


def _raymarch(z, grid, S, h):
    """Brute-force ray marching from every element to S (numpy, vectorised over the elements)."""
    X, Y = grid.centres()
    P = np.stack([X.ravel(), Y.ravel(), z.ravel()], axis=1)
    d = S - P
    length = np.linalg.norm(d, axis=1)
    with np.errstate(divide="ignore"):
        t_top = np.where(d[:, 2] > 0, (z.max() - P[:, 2]) / d[:, 2], 0.0)      # ray above the DSM
    dt = h / length
    seen = np.ones(P.shape[0], bool)
    k = 1
    active = np.flatnonzero(k * dt < t_top)
    while active.size:
        t = k * dt[active]
        Q = P[active] + t[:, None] * d[active]
        zq = dem_height(z, grid, Q[:, 0], Q[:, 1], outside="nan")
        seen[active[np.nan_to_num(zq, nan=-np.inf) > Q[:, 2] + 1e-9]] = False
        k += 1
        active = active[(k * dt[active] < t_top[active]) & seen[active]]
    return seen.reshape(z.shape).astype(np.uint8)


def _buildings(buildings):
    try:
        b = np.asarray(buildings, dtype=np.float64)
    except (TypeError, ValueError):
        raise InputError("buildings must be an (n, 6) array X_min, X_max, Y_min, Y_max, Z_base, Z_top") from None
    if b.ndim == 1 and b.size == 6:
        b = b[None]
    if b.ndim != 2 or b.shape[1] != 6:
        raise InputError(f"buildings must be (n, 6): X_min, X_max, Y_min, Y_max, Z_base, Z_top; got {b.shape}")
    if not np.all(np.isfinite(b)):
        raise InputError("buildings contain NaN or inf")
    if np.any(b[:, 1] <= b[:, 0]) or np.any(b[:, 3] <= b[:, 2]) or np.any(b[:, 5] <= b[:, 4]):
        raise InputError("every building needs X_min < X_max, Y_min < Y_max, Z_base < Z_top")
    return b


def _inside_convex(rows, cols, poly):
    """Pixel centres (rows, cols) inside a convex polygon given as (k, 2) (row, col) vertices."""
    inside_pos = np.ones(rows.shape, bool)
    inside_neg = np.ones(rows.shape, bool)
    k = len(poly)
    for i in range(k):
        r1, c1 = poly[i]
        r2, c2 = poly[(i + 1) % k]
        cross = (c2 - c1) * (rows - r1) - (r2 - r1) * (cols - c1)
        inside_pos &= cross >= 0
        inside_neg &= cross <= 0
    return inside_pos | inside_neg


def index_matrix(image_shape, project: Callable, buildings, centre):
    """The index matrix of §7.5 (Fig. 7.12): 0 ground, 1 roof, 2 visible wall, per image pixel.

    The book's steps 1–3: fill the matrix with 0; project the roof and wall polygons of the
    building model into the image; fill them with 1 (roofs) and 2 (walls), keeping only the
    walls that face the projection centre (their outer normal points towards S). Buildings are
    painted farthest first, so a nearer building covers a farther one. A pixel belongs to a
    polygon when its centre lies inside the projected polygon.

    Parameters
    ----------
    image_shape : (int, int)
        Rows and columns of the image.
    project : callable
        ``project(X, Y, Z) -> (rows, cols)``, e.g. :func:`photolib.rectify.frame_projector`.
    buildings : (n, 6) array
        Box buildings X_min, X_max, Y_min, Y_max, Z_base, Z_top (object units).
    centre : (3,) array
        The projection centre S (decides which walls are seen).

    Returns
    -------
    (rows, cols) uint8 array

    Raises
    ------
    InputError
        A bad shape, NaN, a degenerate box, a sensor model returning wrong shapes, S inside a
        building.

    References
    ----------
    Chibunichev (2022), §7.5, Fig. 7.12 and steps 1–3 of the index-matrix method.

    Examples
    --------
    >>> from photolib.trueortho import index_matrix
    >>> vertical = lambda X, Y, Z: (3.5 - (Y - 5) * 10 / (10 - Z), 3.5 + (X - 5) * 10 / (10 - Z))
    >>> m = index_matrix((8, 8), vertical, [[6.0, 8.0, 6.0, 8.0, 0.0, 5.0]], (5.0, 5.0, 10.0))
    >>> m[:4, 4:].tolist()                    # roof (1) and the west and south walls (2)
    [[0, 2, 1, 1], [0, 2, 1, 1], [0, 2, 2, 2], [0, 0, 0, 0]]
    """
    try:
        shape = tuple(int(v) for v in image_shape)
    except (TypeError, ValueError):
        raise InputError(f"image_shape must be (rows, cols), got {image_shape!r}") from None
    if len(shape) != 2 or min(shape) < 1:
        raise InputError(f"image_shape must be two positive integers, got {image_shape!r}")
    if not callable(project):
        raise InputError("project must be a callable project(X, Y, Z) -> (rows, cols)")
    b = _buildings(buildings)
    S = _centre(centre)
    rows, cols = np.meshgrid(np.arange(shape[0], dtype=float), np.arange(shape[1], dtype=float), indexing="ij")
    out = np.zeros(shape, np.uint8)
    mid = np.column_stack([(b[:, 0] + b[:, 1]) / 2, (b[:, 2] + b[:, 3]) / 2, (b[:, 4] + b[:, 5]) / 2])
    for n in np.argsort(-np.linalg.norm(mid - S, axis=1), kind="stable"):
        x0, x1, y0, y1, zb, zt = b[n]
        if x0 < S[0] < x1 and y0 < S[1] < y1 and zb < S[2] < zt:
            raise InputError(f"the projection centre is inside building {n}")
        corners = np.array([[x0, y0], [x1, y0], [x1, y1], [x0, y1]])
        walls = []
        for i in range(4):                            # wall from corner i to i+1, outward normal
            (xa, ya), (xb, yb) = corners[i], corners[(i + 1) % 4]
            normal = np.array([yb - ya, xa - xb])     # corners run anticlockwise: normal points out
            if normal @ (S[:2] - (corners[i] + corners[(i + 1) % 4]) / 2) > 0:
                walls.append(np.array([[xa, ya, zb], [xb, yb, zb], [xb, yb, zt], [xa, ya, zt]]))
        for poly3, code in [(w, 2) for w in walls] + ([(np.column_stack([corners, np.full(4, zt)]), 1)]
                                                      if S[2] > zt else []):
            r, c = project(poly3[:, 0], poly3[:, 1], poly3[:, 2])
            r, c = np.asarray(r, dtype=float), np.asarray(c, dtype=float)
            if r.shape != (len(poly3),) or c.shape != r.shape:
                raise InputError(f"the sensor model returned positions of shape {r.shape}, expected {(len(poly3),)}")
            if not (np.all(np.isfinite(r)) and np.all(np.isfinite(c))) or np.any(np.abs(r) > 1e8):
                continue                              # behind the camera
            out[_inside_convex(rows, cols, np.column_stack([r, c]))] = code
    return out


@dataclass(frozen=True)
class TrueOrtho:
    """A true orthophoto from several images (Fig. 7.13) with its bookkeeping.

    Attributes
    ----------
    image : ndarray
        The orthophoto (``fill`` in dead zones seen by no image).
    source : (R, C) int array
        Index of the image each pixel came from, −1 in the dead zones.
    nadir_tangent : (R, C) array
        tan of the nadir angle of the chosen ray (NaN in the dead zones).
    visible : (S, R, C) uint8 array
        The restriction matrix of every image (1: the ray to S_i is not occluded and inside the image).

    References
    ----------
    Chibunichev (2022), §7.5, Fig. 7.13.

    Examples
    --------
    >>> import numpy as np
    >>> t = TrueOrtho(np.zeros((1, 1)), np.zeros((1, 1), int), np.zeros((1, 1)), np.ones((1, 1, 1), np.uint8))
    >>> int(t.source[0, 0])
    0
    """

    image: np.ndarray
    source: np.ndarray
    nadir_tangent: np.ndarray
    visible: np.ndarray


def true_ortho_multi(images: Sequence, projectors: Sequence[Callable], centres, dsm, dsm_grid: RasterGrid,
                     grid: RasterGrid, *, method: str = "bilinear", fill: float = np.nan,
                     step: float = 0.5) -> TrueOrtho:
    """The orthophoto from all images at once (§7.5, Fig. 7.13): the unoccluded ray closest to nadir.

    For each ortho pixel: its centre (X, Y) and the surface height Z from the DSM (DTM plus the
    building height h), then for every image the ray from the point to S_i — images whose ray is
    occluded by the DSM (the §7.5 nadir-angle criterion, :func:`visibility_mask`) or whose image
    position falls outside the frame are dropped, and the brightness is taken from the remaining
    image with the smallest nadir angle of the ray. Pixels no image sees stay dead (``fill``).

    Parameters
    ----------
    images : sequence of 2-D arrays
        The source images.
    projectors : sequence of callables
        ``project(X, Y, Z) -> (rows, cols)`` per image (e.g. :func:`photolib.rectify.frame_projector`).
    centres : (S, 3) array
        Projection centres of the images.
    dsm : (R, C) array
        Surface heights (with the buildings) on ``dsm_grid``.
    dsm_grid, grid : RasterGrid
        The DSM's and the orthophoto's grids (one X, Y system).
    method : {'nearest', 'bilinear', 'bicubic'}
        Resampling.
    fill : float
        Value of dead pixels.
    step : float
        Profile sampling step of the occlusion test, DSM pixels.

    Returns
    -------
    TrueOrtho

    Raises
    ------
    InputError
        Mismatched numbers of images, projectors and centres; NaN; a DSM not covering the grid.

    References
    ----------
    Chibunichev (2022), §7.5, Fig. 7.13; §7.3, eqs. (7.3.1)–(7.3.2).

    Examples
    --------
    >>> import numpy as np
    >>> from photolib.rectify import RasterGrid
    >>> from photolib.trueortho import true_ortho_multi
    >>> dsm_grid = RasterGrid(0.0, 1.0, 1.0, (1, 7)); dsm = np.zeros((1, 7)); dsm[0, 3] = 10.0
    >>> def camera(xs):                       # a 1-D "image": column = ground X where the ray meets Z = 0
    ...     return lambda X, Y, Z: (np.zeros_like(X), xs + (X - xs) * 20.0 / (20.0 - Z) - 0.5)
    >>> images = [np.arange(7.0)[None] + 10 * i for i in range(2)]
    >>> t = true_ortho_multi(images, [camera(0.5), camera(6.5)], [(0.5, 0.5, 20), (6.5, 0.5, 20)], dsm,
    ...                      dsm_grid, RasterGrid(1.0, 1.0, 1.0, (1, 5)))
    >>> t.source.tolist()
    [[0, 0, 0, 1, 1]]
    """
    grid = _grid(grid)
    dgrid = _grid(dsm_grid, "dsm_grid")
    z = _raster(dsm, dgrid, "dsm")
    images = list(images)
    projectors = list(projectors)
    try:
        C = np.asarray(centres, dtype=np.float64).reshape(-1, 3)
    except (TypeError, ValueError):
        raise InputError("centres must be an (S, 3) array") from None
    if not (len(images) == len(projectors) == C.shape[0]) or not images:
        raise InputError(f"got {len(images)} images, {len(projectors)} projectors and {C.shape[0]} centres: "
                         "one of each per image, at least one")
    if not np.all(np.isfinite(C)):
        raise InputError("centres contain NaN or inf")
    X, Y = grid.centres()
    Z = dem_height(z, dgrid, X, Y)
    h = float(step) * min(dgrid.dx, dgrid.dy)
    if not h > 0:
        raise InputError(f"step must be positive, got {step!r}")
    n_img = len(images)
    best = np.full(X.shape, np.inf)
    source = np.full(X.shape, -1, int)
    first = np.asarray(images[0], dtype=float)
    out = np.full(X.shape + first.shape[2:], float(fill))
    visible = np.zeros((n_img,) + X.shape, np.uint8)
    kern = _kernels()
    Xr, Yr, Zr = (np.ascontiguousarray(a.ravel()) for a in (X, Y, Z))
    for i, (image, project, S) in enumerate(zip(images, projectors, C)):
        if not callable(project):
            raise InputError(f"projector {i} is not callable")
        image = np.asarray(image, dtype=float)
        if image.ndim not in (2, 3) or image.shape[2:] != first.shape[2:]:
            raise InputError(f"image {i} has shape {image.shape}; all images need one number of bands")
        rows, cols = (np.asarray(a, dtype=float) for a in project(X, Y, Z))
        if rows.shape != X.shape or cols.shape != X.shape:
            raise InputError(f"projector {i} returned positions of shape {rows.shape}, expected {X.shape}")
        inside = (rows >= 0) & (rows <= image.shape[0] - 1) & (cols >= 0) & (cols <= image.shape[1] - 1)
        hid = np.zeros(Xr.size, np.bool_)
        kern.hidden_points(z, dgrid.x0, dgrid.y0, dgrid.dx, dgrid.dy, S[0], S[1], S[2], Xr, Yr, Zr, h, 1e-9, hid)
        ok = inside & ~hid.reshape(X.shape) & (S[2] > Z)
        visible[i] = ok
        with np.errstate(divide="ignore", invalid="ignore"):
            tan = np.hypot(X - S[0], Y - S[1]) / (S[2] - Z)
        take = ok & (tan < best)
        if take.any():
            values = resample(image, np.where(take, rows, -1e9), np.where(take, cols, -1e9), method)
            out[take] = values[take]
            best[take] = tan[take]
            source[take] = i
    return TrueOrtho(out, source, np.where(source >= 0, best, np.nan), visible)


def ortho_from_points(points, values, grid: RasterGrid, method: str = "radius_mean", *,
                      radius: float | None = None, z_tol: float = 0.5, max_points: int = 64):
    """Orthophoto from a dense point cloud (§7.6, Fig. 7.14).

    * ``"accumulate"`` — the forward method: each point's brightness d is spread over the four
      ortho pixels around its X, Y in proportion to the coordinate differences (bilinear weights,
      the accumulation of §7.2 through :func:`photolib.rectify.rectify_forward`);
    * ``"radius_mean"`` — the inverse method: mean brightness of the points within ``radius``
      (default Δ, the ortho pixel) of the pixel centre (a k-d tree, :class:`scipy.spatial.cKDTree`);
    * ``"idw"`` — the distance-weighted mean (weights 1/distance);
    * ``"max_z"`` — the rule for walls: when the points within the radius have different Z, take
      the point(s) with the maximum Z (mean of those within ``z_tol`` of it) — the roof, not the wall.

    Parameters
    ----------
    points : (n, 3) array
        X, Y, Z of the cloud.
    values : (n,) array
        Brightness d of each point.
    grid : RasterGrid
        The orthophoto grid.
    method : {"accumulate", "radius_mean", "idw", "max_z"}
    radius : float, optional
        Search radius (default the pixel size Δ).
    z_tol : float
        Points within ``z_tol`` below the highest one count as the top surface (``"max_z"``).
    max_points : int
        Nearest points examined per pixel (the k of the k-d tree query).

    Returns
    -------
    ndarray
        ``grid.shape``, NaN where no point contributes (holes).

    Raises
    ------
    InputError
        Wrong shapes, NaN/inf, an empty cloud, an unknown method, a non-positive radius.

    References
    ----------
    Chibunichev (2022), §7.6, Figs. 7.14–7.15; §7.2 (accumulation).

    Examples
    --------
    >>> import numpy as np
    >>> from photolib.rectify import RasterGrid
    >>> from photolib.trueortho import ortho_from_points
    >>> pts = np.array([[0.5, 0.5, 0.0], [0.55, 0.5, 5.0], [1.5, 0.5, 0.0]])   # a wall point in pixel 0
    >>> grid = RasterGrid(0.0, 1.0, 1.0, (1, 2))
    >>> ortho_from_points(pts, [10.0, 50.0, 20.0], grid, "max_z", radius=0.5).tolist()
    [[50.0, 20.0]]
    """
    grid = _grid(grid)
    try:
        P = np.asarray(points, dtype=np.float64)
        d = np.asarray(values, dtype=np.float64).reshape(-1)
    except (TypeError, ValueError):
        raise InputError("points and values must be numeric arrays") from None
    if P.ndim != 2 or P.shape[1] != 3 or P.shape[0] == 0:
        raise InputError(f"points must be a non-empty (n, 3) array, got shape {P.shape}")
    if d.shape != (P.shape[0],):
        raise InputError(f"values must have one brightness per point: {d.shape} for {P.shape[0]} points")
    if not (np.all(np.isfinite(P)) and np.all(np.isfinite(d))):
        raise InputError("points or values contain NaN or inf")
    if method not in POINT_METHODS:
        raise InputError(f"method must be one of {POINT_METHODS}, got {method!r}")
    r = min(grid.dx, grid.dy) if radius is None else float(radius)
    if not (math.isfinite(r) and r > 0):
        raise InputError(f"radius must be positive, got {radius!r}")
    if method == "accumulate":
        rows, cols = grid.rowcol(P[:, 0], P[:, 1])
        out, weight = rectify_forward(d[:, None], np.asarray(rows)[:, None], np.asarray(cols)[:, None], grid.shape)
        return out
    from scipy.spatial import cKDTree
    k = int(min(max(int(max_points), 1), P.shape[0]))
    X, Y = grid.centres()
    dist, idx = cKDTree(P[:, :2]).query(np.column_stack([X.ravel(), Y.ravel()]), k=k, distance_upper_bound=r)
    dist, idx = dist.reshape(-1, k), idx.reshape(-1, k)
    found = np.isfinite(dist)
    safe = np.where(found, idx, 0)
    if method == "radius_mean":
        w = found.astype(float)
    elif method == "idw":
        w = np.where(found, 1.0 / np.maximum(dist, 1e-6 * r), 0.0)
    else:
        zz = np.where(found, P[safe, 2], -np.inf)
        w = (found & (zz >= zz.max(axis=1, keepdims=True) - float(z_tol))).astype(float)
    total = w.sum(axis=1)
    with np.errstate(invalid="ignore", divide="ignore"):
        value = (w * d[safe]).sum(axis=1) / total
    value[total == 0] = np.nan
    return value.reshape(grid.shape)


def lsq_unknown_count(P: int, S: int, eo_known: bool = True):
    """The counts of §7.8: N = 2P + (S − 1) [+ 6S] unknowns, M = P·S equations.

    Parameters
    ----------
    P : int
        Number of DSM points (ortho pixels), ≥ 1.
    S : int
        Number of images, ≥ 1.
    eo_known : bool
        True: EO known (the book's example, no 6S term); False: six EO elements per image too.

    Returns
    -------
    (int, int)
        (N, M); the problem can be solved only when N ≤ M (and in practice N < M).

    Raises
    ------
    InputError
        Non-integer or non-positive counts.

    References
    ----------
    Chibunichev (2022), §7.8 (counts after (7.8.4) and the example P = 100, S = 2: N = 201 > M = 200).

    Examples
    --------
    >>> lsq_unknown_count(100, 2), lsq_unknown_count(100, 3)
    ((201, 200), (202, 300))
    """
    out = []
    for name, v in (("P", P), ("S", S)):
        if isinstance(v, bool) or not isinstance(v, (int, np.integer)) or v < 1:
            raise InputError(f"{name} must be a positive integer, got {v!r}")
        out.append(int(v))
    P, S = out
    return 2 * P + (S - 1) + (0 if eo_known else 6 * S), P * S


@dataclass
class LsqOrtho:
    """Result of :func:`lsq_dsm_ortho`.

    Attributes
    ----------
    ortho : (R, C) array
        F, the orthophoto brightness (in the reference image's radiometry).
    dsm : (R, C) array
        Z, the surface heights.
    gains : (S,) array
        k_i (k = 1 for the reference image); k_i = 1/gain_i of image i relative to the reference.
    adjustment : photolib.lsq.Adjustment
        The engine's result (iterations, history, μ; ``dof`` = equations (photometric and GCP)
        minus the unknowns the solver actually carried).
    counts : (int, int)
        (N, M) of :func:`lsq_unknown_count`.
    eos : tuple of photolib.camera.ExteriorOrientation
        The exterior orientations: adjusted with ``estimate_eo=True`` (7.8.4), else the given ones.

    References
    ----------
    Chibunichev (2022), §7.8, eqs. (7.8.1)–(7.8.4).

    Examples
    --------
    >>> import numpy as np
    >>> LsqOrtho(np.zeros((1, 1)), np.zeros((1, 1)), np.ones(3), None, (202, 300)).counts
    (202, 300)
    """

    ortho: np.ndarray
    dsm: np.ndarray
    gains: np.ndarray
    adjustment: object
    counts: tuple
    eos: tuple = ()


def _gcps(gcp_xyz, gcp_xy, S):
    """Checked GCP arrays: (n, 3) ground coordinates, (S, n, 2) image measurements (NaN: not measured)."""
    if gcp_xyz is None and gcp_xy is None:
        return np.zeros((0, 3)), np.zeros((S, 0, 2))
    if gcp_xyz is None or gcp_xy is None:
        raise InputError("give both gcp_xyz (n, 3) and gcp_xy (S, n, 2), or neither")
    try:
        G = np.asarray(gcp_xyz, dtype=np.float64)
        g = np.asarray(gcp_xy, dtype=np.float64)
    except (TypeError, ValueError):
        raise InputError("gcp_xyz and gcp_xy must be numeric arrays") from None
    if G.ndim != 2 or G.shape[1] != 3:
        raise InputError(f"gcp_xyz must be (n, 3) ground coordinates, got shape {G.shape}")
    if g.shape != (S, G.shape[0], 2):
        raise InputError(f"gcp_xy must be (S, n, 2) = {(S, G.shape[0], 2)} image coordinates in mm "
                         f"(NaN where not measured), got shape {g.shape}")
    if not np.all(np.isfinite(G)):
        raise InputError("gcp_xyz contains NaN or inf")
    if np.any(np.isinf(g)) or np.any(np.isnan(g[..., 0]) != np.isnan(g[..., 1])):
        raise InputError("gcp_xy contains inf, or a measurement with only one coordinate NaN")
    return G, g


def _datum_check(G, g):
    """§7.8.4: the GCPs must fix the 7 datum parameters (3 shifts, 3 rotations, scale)."""
    seen = ~np.isnan(g[..., 0]).all(axis=0)
    pts = G[seen]
    n = pts.shape[0]
    spread = 0.0
    if n >= 3:
        sv = np.linalg.svd(pts - pts.mean(axis=0), compute_uv=False)
        spread = sv[1] / max(sv[0], 1e-300)
    if n < 3 or spread < 1e-6:
        what = f"{n} measured GCP{'s' if n != 1 else ''}" + (" (collinear)" if n >= 3 else "")
        raise DegenerateGeometryError(
            f"§7.8, (7.8.4): with unknown EO the photometric equations only tie the images to each other, "
            f"leaving a datum defect of 7 (three shifts, three rotations and the scale of a 3-D similarity "
            f"of the cameras and the surface); got {what} — add the collinearity equations (7.8.2) of at "
            "least 3 non-collinear ground control points")


def lsq_dsm_ortho(images: Sequence, eos: Sequence, io, pixel_size: float, grid: RasterGrid, z0, *,
                  reference: int = 0, sigma_z0: float = 2.0, sigma_f: float = 0.02, max_step: float = 0.25,
                  max_iter: int = 20, tol_z: float = 1e-3, progress=None, estimate_eo: bool = False,
                  gcp_xyz=None, gcp_xy=None, sigma_gcp: float = 0.5) -> LsqOrtho:
    """DSM and true orthophoto by least squares from all images (§7.8, (7.8.1)–(7.8.4)).

    Unknowns: the brightness F and the height Z of every ortho pixel, and the photometric gain
    k_i of every image but the ``reference`` one (k = 1). Each pixel and image gives (7.8.1),
    F − k_i f_i(x_i, y_i) = 0, with x_i, y_i from (7.8.2) and f_i bilinear in image i; the
    correction equations (7.8.3) have a₁ = 1, a₂ = −k_i(∂f_i/∂x·∂x/∂Z + ∂f_i/∂y·∂y/∂Z) (sympy:
    :mod:`photolib.derivations.orthophoto`; image gradients by central differences), a₃ = −f_i.
    The normal matrix is 2 × 2 block-diagonal per pixel plus the gain columns (pitfall 20), so
    each Gauss–Newton step is solved by :func:`photolib.lsq.solve_block_normal_equations`: the
    images are its "frames" (unknown k_i, the reference image held fixed), the pixels its
    "points" (F, Z and a third coordinate held at 0 by a direct observation); the pixel blocks
    are eliminated and the gains solved from their Schur complement (3.5.16). Two safeguards
    make the per-pixel Newton steps robust: the initial DSM enters as a weak direct observation
    of Z (``sigma_z0``), and each pixel's δZ is bounded by ``max_step``, the bound halved
    whenever the pixel's step changes sign (an oscillating pixel). Iterations stop when the RMS
    of δZ is below ``tol_z``.

    With ``estimate_eo=True`` (7.8.4) each frame carries k_i and X_S, Y_S, Z_S, ω, α, κ (``eos``
    are then the initial values): a₄…a₉ = −k_i(∂f_i/∂x·∂x/∂p + ∂f_i/∂y·∂y/∂p) with ∂x/∂p, ∂y/∂p
    the collinearity partials of §1.8 (:func:`photolib.derivations.orthophoto.eo_partials_function`).
    The reference gain is held by a zero column and a direct observation δk = 0, so the solver
    carries exactly N = 2P + (S − 1) + 6S unknowns. The photometric equations alone leave a datum
    defect of 7 (a 3-D similarity of cameras and surface changes none of them), so the
    collinearity equations of ground control points join as further rows (weight
    (σ_f/σ_gcp)², σ_gcp in pixels); at least 3 non-collinear measured GCPs are required.
    Convergence then also needs the EO steps below ``tol_z`` (centres, m) and ``tol_z``/H
    (angles, rad).

    Parameters
    ----------
    images : sequence of 2-D arrays
        S ≥ 3 images (one camera, distortion-free).
    eos : sequence of photolib.camera.ExteriorOrientation
        Their exterior orientations: known, or initial values with ``estimate_eo``.
    io : photolib.camera.InteriorOrientation
        The camera.
    pixel_size : float
        Δ of the images, mm (pixel centres as :func:`photolib.synthetic.image_to_pixel`).
    grid : RasterGrid
        The ortho grid (P = rows × cols pixels); every pixel must project inside every image.
    z0 : (R, C) array
        Initial DSM on ``grid`` (good to a fraction of the texture's correlation length).
    reference : int
        Image whose gain is fixed to 1.
    sigma_z0 : float
        A-priori σ of the initial DSM (m): z0 enters as a direct observation of Z with weight
        (sigma_f/sigma_z0)², which keeps pixels with little texture along the parallax direction
        from running away (``np.inf``: no prior, the book's pure form). With ``estimate_eo`` use a
        weak prior (e.g. 20 m): a DSM prior with an error of its own tilts the whole block.
    sigma_f : float
        σ of the image brightness (the photometric equations get weight 1, the prior is scaled to it).
    max_step : float
        Largest |δZ| per iteration and pixel, m (halved for a pixel whose step changes sign).
    max_iter : int
        Iterations before :class:`ConvergenceError`.
    tol_z : float
        Convergence when the RMS of δZ over the pixels is below ``tol_z`` (m).
    progress : callable, optional
        Called with each :class:`photolib.lsq.IterationRecord` (``delta`` = max |δk|, RMS δZ
        [, max |δ centre|, max |δ angle|]).
    estimate_eo : bool
        False: EO known, (7.8.3). True: EO unknown, (7.8.4) with the GCP collinearity equations.
    gcp_xyz : (n, 3) array, optional
        Ground control points X, Y, Z (needed with ``estimate_eo``; ignored without it).
    gcp_xy : (S, n, 2) array, optional
        Their measured image coordinates x, y (mm, distortion-free), NaN where not measured.
    sigma_gcp : float
        σ of a GCP image measurement, pixels.

    Returns
    -------
    LsqOrtho

    Raises
    ------
    InputError
        Mismatched lists, wrong shapes, NaN, a pixel outside an image, a bad reference, bad GCP arrays.
    DegenerateGeometryError
        N > M (S ≤ 2: the book's example), a textureless pixel (Z not determined), unknown EO
        with fewer than 3 non-collinear GCPs (the datum defect of 7).
    ConvergenceError
        No convergence in ``max_iter`` iterations.

    References
    ----------
    Chibunichev (2022), §7.8, eqs. (7.8.1)–(7.8.4) and the counts N = 2P + (S − 1) [+ 6S], M = PS;
    §3.5, eq. (3.5.16) (the reduction); §1.8, eq. (1.8.3) (the EO partials).

    Examples
    --------
    >>> import numpy as np
    >>> from photolib.camera import ExteriorOrientation, InteriorOrientation
    >>> from photolib.rectify import RasterGrid
    >>> from photolib.trueortho import lsq_dsm_ortho
    >>> eos = [ExteriorOrientation(0.0, 0.0, 100.0)] * 2
    >>> lsq_dsm_ortho([np.ones((9, 9))] * 2, eos, InteriorOrientation(50.0), 0.1,
    ...               RasterGrid(-1.0, 1.0, 1.0, (2, 2)), np.zeros((2, 2)))
    Traceback (most recent call last):
    ...
    photolib.errors.DegenerateGeometryError: §7.8: 2 images give M = 8 equations for N = 9 unknowns ...
    >>> rng = np.random.default_rng(0)
    >>> lsq_dsm_ortho([rng.uniform(size=(30, 30)) for _ in range(3)], eos + eos[:1], InteriorOrientation(50.0),
    ...               0.1, RasterGrid(-1.0, 1.0, 1.0, (2, 2)), np.zeros((2, 2)), estimate_eo=True)
    Traceback (most recent call last):
    ...
    photolib.errors.DegenerateGeometryError: §7.8, (7.8.4): with unknown EO ... datum defect of 7 ...
    """
    from .camera import ExteriorOrientation, InteriorOrientation
    from .derivations.orthophoto import eo_partials_function, height_partials_function
    from .errors import ConvergenceError
    from .lsq import Adjustment, BlockCorrectionEquations, IterationRecord, solve_block_normal_equations
    from .single_image import project as collinearity
    from .synthetic import image_to_pixel

    grid = _grid(grid)
    images = [np.asarray(im, dtype=np.float64) for im in images]
    eos = list(eos)
    if len(images) != len(eos) or not images:
        raise InputError(f"got {len(images)} images and {len(eos)} orientations: one per image")
    if not isinstance(io, InteriorOrientation):
        raise InputError(f"io must be an InteriorOrientation, got {type(io).__name__}")
    for i, (im, eo) in enumerate(zip(images, eos)):
        if not isinstance(eo, ExteriorOrientation):
            raise InputError(f"orientation {i} must be an ExteriorOrientation, got {type(eo).__name__}")
        if im.ndim != 2 or min(im.shape) < 3 or not np.all(np.isfinite(im)):
            raise InputError(f"image {i} must be a finite 2-D array of at least 3 × 3 pixels, got {im.shape}")
    Z0 = _raster(z0, grid, "z0")
    d = float(pixel_size)
    if not (math.isfinite(d) and d > 0):
        raise InputError(f"pixel_size must be positive, got {pixel_size!r}")
    S = len(images)
    if isinstance(reference, bool) or not isinstance(reference, (int, np.integer)) or not 0 <= reference < S:
        raise InputError(f"reference must be an image index 0…{S - 1}, got {reference!r}")
    estimate_eo = bool(estimate_eo)
    P = grid.shape[0] * grid.shape[1]
    N, M = lsq_unknown_count(P, S, eo_known=not estimate_eo)
    if estimate_eo:
        G, g = _gcps(gcp_xyz, gcp_xy, S)
        try:
            sg = float(sigma_gcp)
        except (TypeError, ValueError):
            raise InputError(f"sigma_gcp must be a number, got {sigma_gcp!r}") from None
        if not (math.isfinite(sg) and sg > 0):
            raise InputError(f"sigma_gcp must be positive (pixels), got {sigma_gcp!r}")
        _datum_check(G, g)
        m_gcp = 2 * int((~np.isnan(g[..., 0])).sum())
        if S < 3 or N > M + m_gcp:                      # S = 2: per pixel, F and Z absorb both equations
            raise DegenerateGeometryError(
                f"§7.8, (7.8.4): {S} images give M = {M} photometric and {m_gcp} GCP equations for N = {N} "
                f"unknowns (2P + S − 1 + 6S with P = {P}): "
                + ("two images never determine the gains and the relative orientation — add a third image"
                   if S < 3 else "enlarge the grid, add images or GCPs"))
    else:
        G, g = np.zeros((0, 3)), np.zeros((S, 0, 2))
        if N > M:
            raise DegenerateGeometryError(
                f"§7.8: {S} images give M = {M} equations for N = {N} unknowns (2P + S − 1 with P = {P}): "
                "the DSM, the orthophoto and the gains are not determined — add a third image")
    X, Y = (a.ravel() for a in grid.centres())
    grads = [np.gradient(im) for im in images]
    orders = [eo.order for eo in eos]
    dxy = [height_partials_function(o) for o in orders]
    deo = [eo_partials_function(o) for o in orders] if estimate_eo else None
    q = 7 if estimate_eo else 1
    obs_img = np.repeat(np.arange(S), P)
    obs_pix = np.tile(np.arange(P), S)
    # GCP rows: one observation (r = 1) per coordinate of every measurement, on fixed "points" P + j
    gi, gj = np.nonzero(~np.isnan(g[..., 0]))
    n_gcp_rows = 2 * gi.size
    if n_gcp_rows:
        obs_img = np.concatenate([obs_img, np.repeat(gi, 2)])
        obs_pix = np.concatenate([obs_pix, P + np.repeat(gj, 2)])
    n_points = P + G.shape[0]

    def current(frames):
        if not estimate_eo:
            return eos
        return [ExteriorOrientation(*frames[i, 1:], order=orders[i]) for i in range(S)]

    def positions(Z, eo_now, check=False):
        rc, dZ, dE = [], [], []
        for i, eo in enumerate(eo_now):
            pts = np.column_stack([X, Y, Z])
            cr = image_to_pixel(collinearity(pts, eo, io, distortion=False), images[i].shape, d)
            rows, cols = cr[:, 1], cr[:, 0]
            out = (rows < 0) | (rows > images[i].shape[0] - 1) | (cols < 0) | (cols > images[i].shape[1] - 1)
            if check and out.any():
                raise InputError(f"{int(out.sum())} ortho pixels project outside image {i}: crop the grid")
            rows = np.clip(rows, 0, images[i].shape[0] - 1)
            cols = np.clip(cols, 0, images[i].shape[1] - 1)
            v = eo.vector
            pz = dxy[i](X, Y, Z, *v, io.f, io.x0, io.y0)
            rc.append((rows, cols))
            dZ.append((-pz[1] / d, pz[0] / d))                  # d(row)/dZ, d(col)/dZ
            if estimate_eo:
                pe = deo[i](X, Y, Z, *v, io.f, io.x0, io.y0)    # (2, 6, P)
                dE.append((-pe[1] / d, pe[0] / d))              # d(row)/dEO, d(col)/dEO: (6, P) each
        return rc, dZ, dE

    def linearize(frames, points):
        F, Z = points[:P, 0], points[:P, 1]
        eo_now = current(frames)
        rc, dZ, dE = positions(Z, eo_now)
        m = S * P + n_gcp_rows
        B1 = np.zeros((m, 1, q))
        B2 = np.zeros((m, 1, 3))
        L = np.empty((m, 1))
        W = np.ones((m, 1))
        for i in range(S):
            rows, cols = rc[i]
            fi = resample(images[i], rows, cols)
            g_r = resample(grads[i][0], rows, cols)
            g_c = resample(grads[i][1], rows, cols)
            k = frames[i, 0]
            s = slice(i * P, (i + 1) * P)
            B1[s, 0, 0] = 0.0 if (estimate_eo and i == reference) else -fi
            if estimate_eo:
                B1[s, 0, 1:] = (-k * (g_r * dE[i][0] + g_c * dE[i][1])).T
            B2[s, 0, 0] = 1.0
            B2[s, 0, 1] = -k * (g_r * dZ[i][0] + g_c * dZ[i][1])
            L[s, 0] = F - k * fi
        if n_gcp_rows:
            p_gcp = (sigma_f_ / (sg * d)) ** 2
            for i in range(S):
                sel = np.flatnonzero(gi == i)
                if not sel.size:
                    continue
                j = gj[sel]
                xy = collinearity(G[j], eo_now[i], io, distortion=False)
                pe = deo[i](G[j, 0], G[j, 1], G[j, 2], *eo_now[i].vector, io.f, io.x0, io.y0)   # (2, 6, n)
                rows_x = S * P + 2 * sel
                B1[rows_x, 0, 1:] = pe[0].T
                B1[rows_x + 1, 0, 1:] = pe[1].T
                L[rows_x, 0] = xy[:, 0] - g[i, j, 0]
                L[rows_x + 1, 0] = xy[:, 1] - g[i, j, 1]
                W[rows_x, 0] = W[rows_x + 1, 0] = p_gcp
        return BlockCorrectionEquations(obs_img, obs_pix, B1, B2, L, W)

    rc, _, _ = positions(Z0.ravel(), eos, check=True)
    F0 = np.mean([resample(images[i], *rc[i]) for i in range(S)], axis=0)
    points0 = np.zeros((n_points, 3))
    points0[:P] = np.column_stack([F0, Z0.ravel(), np.zeros(P)])
    points0[P:] = G
    try:
        sz, sigma_f_ = float(sigma_z0), float(sigma_f)
    except (TypeError, ValueError):
        raise InputError("sigma_z0 and sigma_f must be numbers") from None
    if not (sz > 0 and sigma_f_ > 0 and math.isfinite(sigma_f_)):
        raise InputError(f"sigma_z0 and sigma_f must be positive, got {sigma_z0!r}, {sigma_f!r}")
    p_z = (sigma_f_ / sz) ** 2
    p_prior = np.zeros((n_points, 3))
    p_prior[:P] = [0.0, p_z, 1.0]                       # Z ≈ z0 (weak), third coordinate = 0
    free_points = np.arange(n_points) < P               # the GCPs are fixed points
    frames = np.ones((S, q))
    if estimate_eo:
        frames[:, 1:] = [eo.vector for eo in eos]
        free, frame_prior = None, (np.zeros((S, q)), np.zeros((S, q)))
        frame_prior[1][reference, 0] = 1.0             # δk_ref = 0: a zero column and a direct observation
    else:
        free, frame_prior = np.ones(S, bool), None
        free[reference] = False
    n_unknowns = 2 * P + q * S - 1                      # the free columns the solver carries
    height = max(float(np.mean([eo.Zs for eo in eos]) - Z0.mean()), 1e-9)
    points = points0.copy()
    history = []
    bound, last = np.full(P, float(max_step)), np.zeros(P)
    try:
        for iteration in range(1, int(max_iter) + 1):
            eq = linearize(frames, points)
            l_prior = np.zeros((n_points, 3))
            l_prior[:P] = np.column_stack([np.zeros(P), points[:P, 1] - Z0.ravel(), points[:P, 2]])
            sol = solve_block_normal_equations(eq, S, n_points, point_prior=(l_prior, p_prior), free_frames=free,
                                               frame_prior=frame_prior, free_points=free_points, dense_limit=64)
            raw = sol.delta2[:P, 1]
            flip = (np.sign(raw) * np.sign(last) < 0) & (np.abs(raw) > tol_z)
            bound = np.where(flip, bound / 2, bound)          # a pixel oscillating: halve its step
            dZ = np.clip(raw, -bound, bound)
            last = dZ
            frames = frames + sol.delta1
            points[:P, 0] += sol.delta2[:P, 0]
            points[:P, 1] += dZ
            vtpv = float(np.sum(eq.P * eq.L ** 2))
            rms_dz = float(np.sqrt(np.mean(dZ ** 2)))
            deltas = [np.abs(sol.delta1[:, 0]).max(), rms_dz]
            done = rms_dz < tol_z
            if estimate_eo:
                d_centre, d_angle = np.abs(sol.delta1[:, 1:4]).max(), np.abs(sol.delta1[:, 4:]).max()
                deltas += [d_centre, d_angle]
                done = done and d_centre < tol_z and d_angle < tol_z / height
            record = IterationRecord(iteration, np.concatenate([frames.ravel(), points[:P, :2].ravel()]),
                                     np.array(deltas), vtpv)
            history.append(record)
            if progress is not None:
                progress(record)
            if not (np.all(np.isfinite(points)) and np.all(np.isfinite(frames))):
                raise ConvergenceError(f"§7.8: NaN/inf at iteration {iteration}", history)
            if done:
                break
        else:
            raise ConvergenceError(f"§7.8: no convergence in {max_iter} iterations (RMS δZ = {rms_dz:.3g})", history)
    except DegenerateGeometryError as exc:
        raise DegenerateGeometryError(f"§7.8: the least-squares DSM is not determined ({exc}); "
                                      "textureless pixels or too few images") from None
    eq = linearize(frames, points)
    m_total = S * P + n_gcp_rows
    dof = m_total - n_unknowns
    adj = Adjustment(np.concatenate([frames.ravel(), points[:P, :2].ravel()]), eq.L.copy(),
                     float(np.sqrt(np.sum(eq.P * eq.L ** 2) / max(dof, 1))), None, None, None, dof, len(history),
                     history=history, frames=frames.copy(), points=points.copy())
    return LsqOrtho(points[:P, 0].reshape(grid.shape), points[:P, 1].reshape(grid.shape), frames[:, 0].copy(),
                    adj, (N, M), tuple(current(frames)))
