"""Digital terrain models — Chapter 6, §6.6–6.7: TIN, grid, contours, DSM → DTM, texture choice.

* :func:`delaunay_tin` — the Delaunay triangulated irregular network (TIN) of spot heights
  (§6.6): triangles whose circumcircles hold no other point; :class:`TIN` holds it.
* :func:`empty_circumcircle_violations`, :func:`is_delaunay` — the book's defining property,
  checked for any triangulation.
* :func:`triangle_planes` — the plane Z = A + B·X + C·Y through each triangle, (6.6.1).
  The equation itself is lost in the OCR (the text calls it "(6.7.1)"); only its description
  survives: A, B, C solve A + B·X_k + C·Y_k − Z_k = 0 for the three vertices k. Solved with
  sympy (Cramer's rule, ``photolib.book.ch06_dtm``), with D = (X₂−X₁)(Y₃−Y₁) − (X₃−X₁)(Y₂−Y₁):

      B = [(Z₂−Z₁)(Y₃−Y₁) − (Z₃−Z₁)(Y₂−Y₁)] / D,
      C = [(X₂−X₁)(Z₃−Z₁) − (X₃−X₁)(Z₂−Z₁)] / D,
      A = Z₁ − B·X₁ − C·Y₁.

  It is linear (barycentric) interpolation inside the triangle; the library evaluates it in
  the equivalent centred form Z = Z₁ + B(X − X₁) + C(Y − Y₁), which keeps full precision with
  large map coordinates.
* :func:`tin_heights`, :func:`grid_from_tin` — heights at arbitrary points / the nodes of a
  regular grid (the "height matrix" of §6.6); NaN outside the TIN's convex hull.
* :func:`contours_from_grid`, :func:`contours_from_tin` — contours by linear interpolation
  along the edges of grid squares (marching squares) or of triangles (Fig. 6.17), the segments
  chained into polylines (closed ones repeat their first vertex at the end).
* :func:`pmf_schedule`, :func:`filter_dsm` — DSM → DTM: remove buildings and vegetation
  ("editing the DSM", §6.6) with the progressive morphological filter of Zhang et al. (2003),
  then fill the removed cells by TIN interpolation of the ground cells.
* :func:`select_texture_images` — §6.7: for each face, the image whose optical axis is closest
  to the face's normal (the camera looks against the normal, from the face's front side).

Units: metres for X, Y, Z; grids are indexed Z[row, column] with the node coordinates given by
the vectors ``y`` (rows) and ``x`` (columns).

References: Zhang K., Chen S.-C., Whitman D., Shyu M.-L., Yan J., Zhang C. (2003), "A progressive
morphological filter for removing nonground measurements from airborne LIDAR data", IEEE TGRS
41(4), 872–882.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from . import _checks
from .camera import ExteriorOrientation
from .errors import DegenerateGeometryError, InputError

__all__ = ["TIN", "delaunay_tin", "empty_circumcircle_violations", "is_delaunay", "triangle_planes",
           "tin_heights", "grid_from_tin", "contours_from_grid", "contours_from_tin", "pmf_schedule",
           "GroundFilterResult", "filter_dsm", "TextureChoice", "select_texture_images"]


# --- input checks ---------------------------------------------------------------------------------
def _float_array(values, what: str, allow_nan: bool = False) -> np.ndarray:
    if isinstance(values, (str, bytes)):
        raise InputError(f"{what}: expected numbers, got the string {values!r}")
    try:
        raw = np.asarray(values)
        if raw.dtype.kind in "USV":
            raise InputError(f"{what}: expected numbers, got text")
        arr = np.asarray(values, dtype=float)
    except InputError:
        raise
    except (TypeError, ValueError):
        raise InputError(f"{what}: expected numbers") from None
    bad = np.isinf(arr) if allow_nan else ~np.isfinite(arr)
    if np.any(bad):
        raise InputError(f"{what} contain(s) {'inf' if allow_nan else 'NaN or inf'}")
    return arr


def _positive(value, what: str) -> float:
    return _checks.positive_scalar(_float_array(value, what), value, what,
                                   message="{name} must be one positive number, got {value!r}")


def _nonnegative(value, what: str) -> float:
    return _checks.positive_scalar(_float_array(value, what), value, what, allow_zero=True,
                                   message="{name} must be one number ≥ 0, got {value!r}")


def _xy(values, what: str) -> np.ndarray:
    arr = _float_array(values, what)
    if arr.ndim == 1 and arr.shape[0] == 2:
        arr = arr[None, :]
    if arr.ndim != 2 or arr.shape[1] != 2:
        raise InputError(f"{what}: expected an array of shape (n, 2), got {np.shape(values)}")
    return arr


def _axis(values, what: str) -> np.ndarray:
    arr = _float_array(values, what)
    if arr.ndim != 1 or arr.size < 2:
        raise InputError(f"{what}: expected a 1-D vector of at least 2 node coordinates, got shape {arr.shape}")
    d = np.diff(arr)
    if not (np.all(d > 0) or np.all(d < 0)):
        raise InputError(f"{what}: node coordinates must be strictly monotonic")
    return arr


# --- the TIN -------------------------------------------------------------------------------------
@dataclass(frozen=True, eq=False)
class TIN:
    """A triangulated irregular network: spot heights and their Delaunay triangles (§6.6).

    Build it with :func:`delaunay_tin`, which checks the input; the constructor trusts it.

    Attributes
    ----------
    points : ndarray
        (n, 2) planimetric coordinates X, Y of the vertices, m.
    z : ndarray
        (n,) heights Z of the vertices, m.
    triangles : ndarray
        (m, 3) vertex indices, counter-clockwise.
    delaunay : scipy.spatial.Delaunay
        The triangulation (point location for :func:`tin_heights`).

    References
    ----------
    Chibunichev (2022), §6.6 (Delaunay triangulation, Figs. 6.12–6.13).

    Examples
    --------
    >>> t = delaunay_tin([[0, 0], [1, 0], [0, 1], [1, 1]], [0, 1, 2, 3])
    >>> t.triangles.shape
    (2, 3)
    """

    points: np.ndarray
    z: np.ndarray
    triangles: np.ndarray
    delaunay: object

    def __repr__(self) -> str:
        return f"TIN({len(self.points)} vertices, {len(self.triangles)} triangles)"


def delaunay_tin(points_xy, z) -> TIN:
    """The Delaunay TIN of spot heights (scipy.spatial.Delaunay, i.e. Qhull).

    Parameters
    ----------
    points_xy : (n, 2) array_like
        Planimetric coordinates X, Y of the spot heights, m.
    z : (n,) array_like
        Their heights Z, m.

    Returns
    -------
    TIN
        Vertices (duplicates of the same point with the same height merged), heights and
        counter-clockwise triangles.

    Raises
    ------
    InputError
        NaN/inf, wrong shapes, different counts, fewer than 3 points, or one X, Y given two
        different heights (a DTM holds one Z per X, Y — the "2.5D" model of Chapter 6).
    DegenerateGeometryError
        All points on one line (no triangle exists).

    References
    ----------
    Chibunichev (2022), §6.6: the circle through a triangle's vertices holds no other vertex.

    Examples
    --------
    >>> t = delaunay_tin([[0, 0], [2, 0], [0, 2], [2, 2], [1, 1.2]], [0, 2, 2, 4, 2.2])
    >>> t
    TIN(5 vertices, 4 triangles)
    """
    from scipy.spatial import Delaunay, QhullError

    xy = _xy(points_xy, "points_xy")
    zz = _float_array(z, "z")
    if zz.ndim != 1 or zz.shape[0] != xy.shape[0]:
        raise InputError(f"z must be a vector of {xy.shape[0]} heights (one per point), got shape {zz.shape}")
    unique, first, inverse = np.unique(xy, axis=0, return_index=True, return_inverse=True)
    inverse = inverse.ravel()
    if len(unique) < len(xy):
        if np.any(zz != zz[first][inverse]):
            raise InputError("duplicate points with different heights: a DTM holds one Z per X, Y")
        order = np.sort(first)                          # keep the first occurrence, in input order
        xy, zz = xy[order], zz[order]
    if len(xy) < 3:
        raise InputError(f"a TIN needs at least 3 distinct points, got {len(xy)}")
    centred = xy - xy.mean(axis=0)
    scale = np.abs(centred).max()
    if scale == 0 or np.linalg.matrix_rank(centred / scale, tol=1e-12) < 2:
        raise DegenerateGeometryError("the points are collinear: no triangle can be formed")
    try:
        tri = Delaunay(xy)
    except QhullError as exc:                           # pragma: no cover - nearly collinear sets
        raise DegenerateGeometryError(f"Qhull could not triangulate the points: {exc}") from None
    simplices = tri.simplices.copy()
    a, b, c = (xy[simplices[:, k]] for k in range(3))
    cross = (b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (c[:, 0] - a[:, 0]) * (b[:, 1] - a[:, 1])
    flip = cross < 0
    simplices[flip] = simplices[flip][:, [0, 2, 1]]
    return TIN(xy, zz, simplices, tri)


def _as_tin(tin) -> TIN:
    if not isinstance(tin, TIN):
        raise InputError(f"tin must be a TIN (from delaunay_tin), got {type(tin).__name__}")
    return tin


def empty_circumcircle_violations(points_xy, triangles, rtol: float = 1e-9) -> np.ndarray:
    """Pairs (triangle, point) where a point lies strictly inside a triangle's circumcircle.

    Parameters
    ----------
    points_xy : (n, 2) array_like
        Vertex coordinates.
    triangles : (m, 3) array_like of int
        Vertex indices of the triangles (any orientation).
    rtol : float
        A point counts as inside when its distance from the centre is below R·(1 − rtol), so
        that co-circular points (e.g. the four corners of a square) are not violations.

    Returns
    -------
    ndarray
        (k, 2) int array of (triangle index, point index); empty for a Delaunay triangulation.

    Raises
    ------
    InputError
        NaN/inf, wrong shapes, indices out of range or not integers, negative ``rtol``.
    DegenerateGeometryError
        A triangle with collinear vertices (no circumcircle).

    References
    ----------
    Chibunichev (2022), §6.6 (the empty-circumcircle rule of Delaunay triangulation).

    Examples
    --------
    >>> square = [[0, 0], [1, 0], [1, 1], [0, 0.9]]
    >>> empty_circumcircle_violations(square, [[0, 1, 2], [0, 2, 3]]).tolist()   # bad diagonal
    [[0, 3], [1, 1]]
    >>> empty_circumcircle_violations(square, [[0, 1, 3], [1, 2, 3]]).tolist()
    []
    """
    from scipy.spatial import cKDTree

    xy = _xy(points_xy, "points_xy")
    tri = np.asarray(triangles)
    if tri.ndim != 2 or tri.shape[1] != 3 or tri.shape[0] == 0:
        raise InputError(f"triangles: expected an (m, 3) array of vertex indices, got shape {tri.shape}")
    if tri.dtype.kind not in "iu":
        raise InputError("triangles: vertex indices must be integers")
    if tri.min() < 0 or tri.max() >= len(xy):
        raise InputError(f"triangles: vertex indices must lie in 0…{len(xy) - 1}")
    tol = _nonnegative(rtol, "rtol")
    centres, radii = _circumcircles(xy, tri)
    tree = cKDTree(xy)
    out = []
    for k, near in enumerate(tree.query_ball_point(centres, radii * (1 - tol))):
        for p in near:
            if p not in tri[k]:
                out.append((k, p))
    return np.array(sorted(out), dtype=int).reshape(-1, 2)


def _circumcircles(xy, tri):
    a, b, c = (xy[tri[:, k]] for k in range(3))
    b, c = b - a, c - a                                 # relative to the first vertex
    d = 2.0 * (b[:, 0] * c[:, 1] - b[:, 1] * c[:, 0])
    size = np.maximum(np.abs(b).max(axis=1), np.abs(c).max(axis=1))
    if np.any(np.abs(d) <= 1e-12 * np.maximum(size, 1e-300) ** 2):
        raise DegenerateGeometryError("a triangle has collinear vertices: it has no circumcircle")
    bb, cc = (b ** 2).sum(axis=1), (c ** 2).sum(axis=1)
    ux = (c[:, 1] * bb - b[:, 1] * cc) / d
    uy = (b[:, 0] * cc - c[:, 0] * bb) / d
    return a + np.column_stack([ux, uy]), np.hypot(ux, uy)


def is_delaunay(points_xy, triangles, rtol: float = 1e-9) -> bool:
    """True if no vertex lies strictly inside any triangle's circumcircle (§6.6).

    Parameters
    ----------
    points_xy : (n, 2) array_like
        Vertex coordinates.
    triangles : (m, 3) array_like of int
        Vertex indices.
    rtol : float
        Relative tolerance on the radius (see :func:`empty_circumcircle_violations`).

    Returns
    -------
    bool

    Raises
    ------
    InputError
        As :func:`empty_circumcircle_violations`.
    DegenerateGeometryError
        A triangle with collinear vertices.

    References
    ----------
    Chibunichev (2022), §6.6.

    Examples
    --------
    >>> t = delaunay_tin(np.random.default_rng(0).uniform(0, 10, (30, 2)), np.zeros(30))
    >>> is_delaunay(t.points, t.triangles)
    True
    """
    return len(empty_circumcircle_violations(points_xy, triangles, rtol)) == 0


# --- (6.6.1): the plane through a triangle ------------------------------------------------------------
def _plane_parts(tin: TIN):
    """Per triangle: the first vertex (X₁, Y₁, Z₁) and the slopes B, C of (6.6.1)."""
    p, z, t = tin.points, tin.z, tin.triangles
    x1, y1, z1 = p[t[:, 0], 0], p[t[:, 0], 1], z[t[:, 0]]
    dx2, dy2, dz2 = p[t[:, 1], 0] - x1, p[t[:, 1], 1] - y1, z[t[:, 1]] - z1
    dx3, dy3, dz3 = p[t[:, 2], 0] - x1, p[t[:, 2], 1] - y1, z[t[:, 2]] - z1
    d = dx2 * dy3 - dx3 * dy2
    B = (dz2 * dy3 - dz3 * dy2) / d
    C = (dx2 * dz3 - dx3 * dz2) / d
    return x1, y1, z1, B, C


def triangle_planes(tin) -> np.ndarray:
    """Coefficients A, B, C of the plane Z = A + B·X + C·Y through each triangle, (6.6.1).

    Parameters
    ----------
    tin : TIN
        From :func:`delaunay_tin`.

    Returns
    -------
    ndarray
        (m, 3): A, B, C per triangle (B = ∂Z/∂X, C = ∂Z/∂Y).

    Raises
    ------
    InputError
        ``tin`` is not a :class:`TIN`.

    References
    ----------
    Chibunichev (2022), §6.6, eq. (6.6.1) (lost in the OCR; cited there as "(6.7.1)"); the
    closed form is derived with sympy in ``photolib.book.ch06_dtm``.

    Examples
    --------
    >>> t = delaunay_tin([[0, 0], [4, 0], [0, 2]], [1.0, 3.0, 0.0])
    >>> triangle_planes(t)
    array([[ 1. ,  0.5, -0.5]])
    """
    x1, y1, z1, B, C = _plane_parts(_as_tin(tin))
    return np.column_stack([z1 - B * x1 - C * y1, B, C])


def tin_heights(tin, points_xy) -> np.ndarray:
    """Heights of arbitrary points on the TIN: the plane (6.6.1) of the enclosing triangle.

    Parameters
    ----------
    tin : TIN
        From :func:`delaunay_tin`.
    points_xy : (k, 2) array_like
        Planimetric coordinates, m.

    Returns
    -------
    ndarray
        (k,) heights; NaN for points outside the TIN's convex hull (no enclosing triangle).

    Raises
    ------
    InputError
        ``tin`` not a TIN, NaN/inf or wrong shape of ``points_xy``.

    References
    ----------
    Chibunichev (2022), §6.6, eq. (6.6.1), Fig. 6.15 (node i inside a triangle).

    Examples
    --------
    >>> t = delaunay_tin([[0, 0], [4, 0], [0, 2], [4, 2]], [1.0, 3.0, 0.0, 2.0])
    >>> tin_heights(t, [[2.0, 1.0], [5.0, 1.0]])
    array([1.5, nan])
    """
    tin = _as_tin(tin)
    xy = _xy(points_xy, "points_xy")
    # a barycentric tolerance of 1e-12 (scipy's default is 100·eps) keeps Qhull's walk from falling
    # back to brute force for points exactly on edges (e.g. grid nodes in a grid of spot heights)
    k = tin.delaunay.find_simplex(xy, tol=1e-12)
    out = np.full(len(xy), np.nan)
    inside = k >= 0
    if np.any(inside):
        # scipy's simplex order is the TIN's row order (orientation fixed per row only)
        x1, y1, z1, B, C = (v[k[inside]] for v in _plane_parts(tin))
        out[inside] = z1 + B * (xy[inside, 0] - x1) + C * (xy[inside, 1] - y1)
    return out


def grid_from_tin(tin, x, y) -> np.ndarray:
    """The regular grid ("height matrix") of a TIN: each node from the plane of its triangle.

    Parameters
    ----------
    tin : TIN
        From :func:`delaunay_tin`.
    x : (nx,) array_like
        X of the grid columns (strictly monotonic).
    y : (ny,) array_like
        Y of the grid rows (strictly monotonic; decreasing for a north-up raster).

    Returns
    -------
    ndarray
        (ny, nx) heights, ``Z[i, j]`` at (x[j], y[i]); NaN outside the convex hull.

    Raises
    ------
    InputError
        ``tin`` not a TIN; ``x`` or ``y`` not a monotonic vector of ≥ 2 finite values.

    References
    ----------
    Chibunichev (2022), §6.6, eq. (6.6.1), Figs. 6.14–6.15.

    Examples
    --------
    >>> t = delaunay_tin([[0, 0], [4, 0], [0, 2], [4, 2]], [1.0, 3.0, 0.0, 2.0])
    >>> grid_from_tin(t, [0, 2, 4], [0, 2])
    array([[1., 2., 3.],
           [0., 1., 2.]])
    """
    tin = _as_tin(tin)
    gx, gy = _axis(x, "x"), _axis(y, "y")
    X, Y = np.meshgrid(gx, gy)
    return tin_heights(tin, np.column_stack([X.ravel(), Y.ravel()])).reshape(X.shape)


# --- contours -----------------------------------------------------------------------------------
def _levels(levels) -> np.ndarray:
    lv = _float_array(levels, "levels")
    lv = np.atleast_1d(lv)
    if lv.ndim != 1 or lv.size == 0:
        raise InputError("levels: expected one number or a non-empty vector of numbers")
    return lv


def _chain(seg: np.ndarray) -> list:
    """Chain segments (pairs of edge ids) into polylines of edge ids; loops end where they began."""
    if len(seg) == 0:
        return []
    ends = {}
    for s, (a, b) in enumerate(seg):
        ends.setdefault(a, []).append(s)
        ends.setdefault(b, []).append(s)
    used = np.zeros(len(seg), bool)
    lines = []

    def walk(start_edge, s):
        line = [start_edge]
        edge = start_edge
        while s is not None:
            used[s] = True
            a, b = seg[s]
            edge = b if a == edge else a
            line.append(edge)
            s = next((t for t in ends[edge] if not used[t]), None)
        return line

    for e in sorted(ends):                              # open lines start at an end (degree 1)
        if len(ends[e]) == 1 and not used[ends[e][0]]:
            lines.append(walk(e, ends[e][0]))
    for s in range(len(seg)):                           # the rest are loops
        if not used[s]:
            lines.append(walk(seg[s][0], s))
    return lines


def contours_from_grid(Z, levels, x=None, y=None, saddle: str = "centre") -> dict:
    """Contours of a grid by linear interpolation along the sides of the grid squares (Fig. 6.17).

    Marching squares: on each side whose end heights straddle the level (a node counts as
    above when Z > level) the crossing is put by linear interpolation; each square gives 0, 1
    or 2 segments, which are chained into polylines.

    Parameters
    ----------
    Z : (ny, nx) array_like
        Heights; NaN marks nodes without data (squares touching them are skipped).
    levels : float or sequence of float
        Contour heights.
    x, y : array_like, optional
        Node coordinates of the columns / rows (default: column and row indices).
    saddle : {"centre", "low", "high"}
        A square with diagonally opposite corners above (a saddle) is ambiguous. ``"centre"``
        decides by the mean of its four corners; ``"low"`` always joins the low corners
        (scikit-image's ``find_contours`` default, ``fully_connected="low"``); ``"high"`` the high.

    Returns
    -------
    dict
        level → list of (k, 2) arrays of (X, Y) vertices; a closed contour repeats its first
        vertex at the end. A level outside the range of ``Z`` has an empty list.

    Raises
    ------
    InputError
        ``Z`` not 2-D with at least 2×2 nodes, inf in ``Z``; NaN/inf in ``levels``;
        ``x``/``y`` of the wrong length or not monotonic; an unknown ``saddle``.

    References
    ----------
    Chibunichev (2022), §6.6, Figs. 6.16–6.17 (contours by linear interpolation in squares).

    Examples
    --------
    >>> Z = [[0.0, 1.0, 2.0], [1.0, 2.0, 3.0]]
    >>> contours_from_grid(Z, 1.5)[1.5][0]
    array([[1.5, 0. ],
           [1. , 0.5],
           [0.5, 1. ]])
    """
    G = _float_array(Z, "Z", allow_nan=True)
    if G.ndim != 2 or G.shape[0] < 2 or G.shape[1] < 2:
        raise InputError(f"Z must be a 2-D grid of at least 2×2 nodes, got shape {G.shape}")
    ny, nx = G.shape
    gx = np.arange(nx, dtype=float) if x is None else _axis(x, "x")
    gy = np.arange(ny, dtype=float) if y is None else _axis(y, "y")
    if gx.size != nx or gy.size != ny:
        raise InputError(f"x and y must have {nx} and {ny} node coordinates, got {gx.size} and {gy.size}")
    if saddle not in ("centre", "low", "high"):
        raise InputError(f"saddle must be 'centre', 'low' or 'high', got {saddle!r}")
    lv = _levels(levels)
    nh = ny * (nx - 1)
    # edge ids: horizontal side (i, j)–(i, j+1) → i(nx−1)+j; vertical (i, j)–(i+1, j) → nh + i·nx + j
    ih, jh = np.divmod(np.arange(nh), nx - 1)
    iv, jv = np.divmod(np.arange((ny - 1) * nx), nx)
    valid = np.all(np.isfinite(np.stack([G[:-1, :-1], G[:-1, 1:], G[1:, 1:], G[1:, :-1]])), axis=0)
    r, c = np.nonzero(valid)
    top = r * (nx - 1) + c
    bottom = (r + 1) * (nx - 1) + c
    left = nh + r * nx + c
    right = nh + r * nx + c + 1
    z0, z1, z2, z3 = G[r, c], G[r, c + 1], G[r + 1, c + 1], G[r + 1, c]
    out = {}
    for level in lv:
        a0, a1, a2, a3 = z0 > level, z1 > level, z2 > level, z3 > level
        segs = []
        crossings = [(top, a0 != a1), (right, a1 != a2), (bottom, a2 != a3), (left, a3 != a0)]
        n = sum(m.astype(int) for _, m in crossings)
        two = n == 2
        ids = np.stack([e for e, _ in crossings], axis=1)[two]
        mask = np.stack([m for _, m in crossings], axis=1)[two]
        if len(ids):
            segs.append(ids[mask].reshape(-1, 2))
        four = n == 4
        if np.any(four):
            t, rg, b, lf = top[four], right[four], bottom[four], left[four]
            centre = (z0[four] + z1[four] + z2[four] + z3[four]) / 4 > level
            if saddle == "low":
                centre = np.zeros_like(centre)
            elif saddle == "high":
                centre = np.ones_like(centre)
            # corner 0 and 2 above, centre below → cut corners 0 (left–top) and 2 (right–bottom);
            # centre above → cut the low corners 1 (top–right) and 3 (bottom–left)
            # (the same pairs serve corners 1, 3 above with the roles exchanged)
            diag02 = a0[four]
            cut02 = diag02 != centre
            s1 = np.where(cut02[:, None], np.column_stack([lf, t]), np.column_stack([t, rg]))
            s2 = np.where(cut02[:, None], np.column_stack([rg, b]), np.column_stack([b, lf]))
            segs += [s1, s2]
        seg = np.concatenate(segs) if segs else np.zeros((0, 2), int)
        polylines = []
        for chain in _chain(seg):
            e = np.asarray(chain)
            hor = e < nh
            pts = np.empty((len(e), 2))
            i, j = ih[e[hor]], jh[e[hor]]
            f = (level - G[i, j]) / (G[i, j + 1] - G[i, j])
            pts[hor] = np.column_stack([gx[j] + f * (gx[j + 1] - gx[j]), gy[i]])
            i, j = iv[e[~hor] - nh], jv[e[~hor] - nh]
            f = (level - G[i, j]) / (G[i + 1, j] - G[i, j])
            pts[~hor] = np.column_stack([gx[j], gy[i] + f * (gy[i + 1] - gy[i])])
            polylines.append(pts)
        out[float(level)] = polylines
    return out


def contours_from_tin(tin, levels) -> dict:
    """Contours of a TIN by linear interpolation along the triangle edges (Fig. 6.17).

    A vertex counts as above when Z > level; a triangle whose vertices straddle the level is
    crossed on exactly two edges, giving one segment; segments are chained into polylines.

    Parameters
    ----------
    tin : TIN
        From :func:`delaunay_tin`.
    levels : float or sequence of float
        Contour heights.

    Returns
    -------
    dict
        level → list of (k, 2) arrays of (X, Y) vertices; closed contours repeat their first
        vertex; a level outside the height range has an empty list.

    Raises
    ------
    InputError
        ``tin`` not a TIN; NaN/inf or an empty ``levels``.

    References
    ----------
    Chibunichev (2022), §6.6, Figs. 6.16–6.17 (contours from a TIN).

    Examples
    --------
    >>> t = delaunay_tin([[0, 0], [2, 0], [0, 2], [2, 2]], [0.0, 2.0, 2.0, 4.0])
    >>> contours_from_tin(t, 1.0)[1.0][0]
    array([[1. , 0. ],
           [0.5, 0.5],
           [0. , 1. ]])
    """
    tin = _as_tin(tin)
    lv = _levels(levels)
    t = tin.triangles
    pairs = np.concatenate([t[:, [0, 1]], t[:, [1, 2]], t[:, [2, 0]]])
    pairs.sort(axis=1)
    edges, inv = np.unique(pairs, axis=0, return_inverse=True)
    inv = inv.ravel().reshape(3, -1).T                  # (m, 3) edge id of each triangle side
    za, zb = tin.z[edges[:, 0]], tin.z[edges[:, 1]]
    pa, pb = tin.points[edges[:, 0]], tin.points[edges[:, 1]]
    out = {}
    for level in lv:
        above = tin.z > level
        crossed = above[edges[:, 0]] != above[edges[:, 1]]
        m = crossed[inv]                                # (m, 3)
        hit = m.sum(axis=1) == 2
        seg = inv[hit][m[hit]].reshape(-1, 2)
        polylines = []
        for chain in _chain(seg):
            e = np.asarray(chain)
            f = (level - za[e]) / (zb[e] - za[e])
            polylines.append(pa[e] + f[:, None] * (pb[e] - pa[e]))
        out[float(level)] = polylines
    return out


# --- DSM → DTM -------------------------------------------------------------------------------------
def pmf_schedule(cell_size, max_window, slope=0.3, dh0=0.3, dh_max=3.0, base=2.0):
    """Window sizes and height thresholds of the progressive morphological filter.

    Zhang et al. (2003), eqs. (3) and (5): windows w_k = 2·base^k + 1 cells (k = 1, 2, …; the
    last is clipped to ``max_window``), thresholds dh_1 = dh0 and
    dh_k = slope·(w_k − w_{k−1})·cell_size + dh0, capped at dh_max.

    Parameters
    ----------
    cell_size : float
        Grid spacing, m.
    max_window : float
        The largest window, m: at least the size of the largest building.
    slope : float
        Terrain slope (tan of the steepest ground slope kept), dimensionless.
    dh0 : float
        Initial height threshold, m (about the height noise plus a margin).
    dh_max : float
        Largest height threshold, m (below the lowest building).
    base : float
        Growth of the window, > 1.

    Returns
    -------
    (ndarray, ndarray)
        Window sizes in cells (odd integers, increasing) and thresholds in metres.

    Raises
    ------
    InputError
        Non-positive or non-finite parameters, ``base`` ≤ 1, ``dh_max`` < ``dh0``, or a
        ``max_window`` smaller than 3 cells.

    References
    ----------
    Chibunichev (2022), §6.6 (DTM by editing the DSM); Zhang et al. (2003), IEEE TGRS 41(4).

    Examples
    --------
    >>> w, dh = pmf_schedule(1.0, 20.0)
    >>> w.tolist(), dh.round(2).tolist()
    ([5, 9, 17, 19], [0.3, 1.5, 2.7, 0.9])
    """
    c = _positive(cell_size, "cell_size")
    wmax = _positive(max_window, "max_window")
    s, d0, dmax = _nonnegative(slope, "slope"), _nonnegative(dh0, "dh0"), _positive(dh_max, "dh_max")
    b = _positive(base, "base")
    if b <= 1:
        raise InputError(f"base must be > 1 (the windows must grow), got {base}")
    if dmax < d0:
        raise InputError(f"dh_max ({dmax}) must be at least dh0 ({d0})")
    cells = int(np.floor(wmax / c))
    cells -= 1 - cells % 2                              # odd, ≤ max_window
    if cells < 3:
        raise InputError(f"max_window = {wmax} m is less than 3 cells of {c} m")
    windows, k = [], 1
    while True:
        w = int(2 * round(b ** k) + 1)
        if w >= cells:
            windows.append(cells)
            break
        windows.append(w)
        k += 1
    windows = np.array(sorted(set(windows)))
    dh = np.empty(len(windows))
    dh[0] = d0
    dh[1:] = np.minimum(s * np.diff(windows) * c + d0, dmax)
    return windows, dh


class GroundFilterResult(NamedTuple):
    """The result of :func:`filter_dsm`: the DTM and the mask of removed object cells.

    Attributes
    ----------
    dtm : ndarray
        The terrain heights on the DSM's grid, m.
    objects : ndarray
        True where the DSM cell was classified as an object (building, vegetation) and its
        height replaced by interpolation.

    References
    ----------
    Chibunichev (2022), §6.6 (DTM from the DSM by removing buildings and vegetation).

    Examples
    --------
    >>> r = GroundFilterResult(np.zeros((2, 2)), np.zeros((2, 2), bool))
    >>> dtm, objects = r
    >>> bool(objects.any())
    False
    """

    dtm: np.ndarray
    objects: np.ndarray


def filter_dsm(dsm, cell_size, max_window=40.0, slope=0.3, dh0=0.3, dh_max=3.0, base=2.0) -> GroundFilterResult:
    """DSM → DTM: flag buildings and vegetation with the progressive morphological filter.

    The surface is opened (grey erosion then dilation, ``scipy.ndimage.grey_opening``, square
    windows) with growing windows w_k (:func:`pmf_schedule`); a cell whose height drops by more
    than dh_k from the previous surface is an object (Zhang et al., 2003). The grid is padded by
    point reflection at its borders (a plane continues as the same plane), so sloping ground at
    the border is not mistaken for a peak. The object cells are
    then filled by linear interpolation in the Delaunay TIN of the ground cells
    (:func:`delaunay_tin`, (6.6.1)); cells outside its hull take the nearest ground height.

    Parameters
    ----------
    dsm : (ny, nx) array_like
        The digital surface model on a regular grid, m (no NaN: fill gaps first).
    cell_size : float
        Grid spacing, m.
    max_window, slope, dh0, dh_max, base
        Filter parameters, see :func:`pmf_schedule` (defaults: 40 m, 0.3, 0.3 m, 3 m, 2).

    Returns
    -------
    GroundFilterResult
        ``(dtm, objects)``.

    Raises
    ------
    InputError
        ``dsm`` not 2-D, smaller than 3×3, NaN/inf; bad filter parameters.
    DegenerateGeometryError
        Fewer than 3 non-collinear ground cells remain (nothing to interpolate from).

    References
    ----------
    Chibunichev (2022), §6.6 (DTM by editing the DSM); Zhang et al. (2003), IEEE TGRS 41(4),
    872–882.

    Examples
    --------
    >>> ground = np.add.outer(np.arange(30.0), np.arange(30.0)) * 0.1
    >>> dsm = ground.copy(); dsm[10:16, 10:16] += 8.0          # a 6 m × 6 m building
    >>> dtm, objects = filter_dsm(dsm, 1.0, max_window=15.0)
    >>> int(objects.sum()), float(np.abs(dtm - ground).max()) < 1e-9
    (36, True)
    """
    from scipy import ndimage

    S = _float_array(dsm, "dsm")
    if S.ndim != 2 or min(S.shape) < 3:
        raise InputError(f"dsm must be a 2-D grid of at least 3×3 cells, got shape {S.shape}")
    windows, dh = pmf_schedule(cell_size, max_window, slope, dh0, dh_max, base)
    surface = S.copy()
    objects = np.zeros(S.shape, bool)
    for w, t in zip(windows, dh):
        h = int(w) // 2                                 # point-symmetric padding continues a plane
        padded = np.pad(surface, h, mode="reflect", reflect_type="odd")
        opened = ndimage.grey_opening(padded, size=(int(w), int(w)), mode="nearest")[h:-h, h:-h]
        objects |= (surface - opened) > t
        surface = opened
    ground = ~objects
    if ground.sum() < 3:
        raise DegenerateGeometryError(f"only {int(ground.sum())} ground cells remain: nothing to interpolate from")
    c = float(cell_size)
    dtm = S.copy()
    if objects.any():
        # the TIN of the ground cells that border removed cells: inside each removed region its
        # triangles are those of the TIN of all ground cells (their circumcircles hold no ground cell)
        rim = ground & ndimage.binary_dilation(objects, structure=np.ones((3, 3), bool))
        rows, cols = np.nonzero(rim)
        xy = np.column_stack([cols * c, rows * c])
        orow, ocol = np.nonzero(objects)
        try:
            filled = tin_heights(delaunay_tin(xy, S[rim]), np.column_stack([ocol * c, orow * c]))
        except DegenerateGeometryError:                  # a rim of fewer than 3 or collinear cells
            filled = np.full(len(orow), np.nan)
        gap = np.isnan(filled)
        if gap.any():
            from scipy.spatial import cKDTree
            grow, gcol = np.nonzero(ground)
            _, nearest = cKDTree(np.column_stack([gcol, grow]) * c).query(np.column_stack([ocol[gap], orow[gap]]) * c)
            filled[gap] = S[grow[nearest], gcol[nearest]]
        dtm[orow, ocol] = filled
    return GroundFilterResult(dtm, objects)


# --- §6.7: the texture image of a face ------------------------------------------------------------------
class TextureChoice(NamedTuple):
    """The result of :func:`select_texture_images`.

    Attributes
    ----------
    image : ndarray
        (m,) index of the chosen orientation per face; −1 where no camera sees the face's front.
    angle : ndarray
        (m,) angle between the chosen optical axis and the inward face normal, radians (NaN for −1).

    References
    ----------
    Chibunichev (2022), §6.7.

    Examples
    --------
    >>> TextureChoice(np.array([0]), np.array([0.0])).image
    array([0])
    """

    image: np.ndarray
    angle: np.ndarray


def select_texture_images(faces, orientations) -> TextureChoice:
    """For each face, the image whose optical axis is closest to the face's normal (§6.7).

    The face normal n = (P₂ − P₁) × (P₃ − P₁) points to the front (vertices counter-clockwise
    seen from outside). Camera j's optical axis in object space is d_j = A_j·(0, 0, −1) (the image
    ray of the principal point, (1.2.1)). Camera j is eligible when its projection centre lies in
    front of the face ((S_j − centroid)·n > 0) and the face centroid lies in front of the camera
    ((centroid − S_j)·d_j > 0); among the eligible, the one with the smallest angle between d_j
    and −n is chosen. Occlusion and the image frame are not checked.

    Parameters
    ----------
    faces : (m, 3, 3) array_like
        Vertices (X, Y, Z) of triangular faces, counter-clockwise seen from the front, m.
    orientations : sequence of ExteriorOrientation
        The candidate images (Chapter 1, :class:`photolib.camera.ExteriorOrientation`).

    Returns
    -------
    TextureChoice
        ``(image, angle)`` per face.

    Raises
    ------
    InputError
        Wrong shape or NaN/inf in ``faces``; an empty list or an element that is not an
        ExteriorOrientation.
    DegenerateGeometryError
        A face with collinear vertices (no normal).

    References
    ----------
    Chibunichev (2022), §6.7 (natural textures: the image whose optical axis is closest to the
    perpendicular to the face); §1.2–1.3 for the camera axis.

    Examples
    --------
    >>> nadir = ExteriorOrientation(0.0, 0.0, 100.0)
    >>> roof = [[[0, 0, 10], [1, 0, 10], [0, 1, 10]]]
    >>> select_texture_images(roof, [nadir]).image
    array([0])
    """
    F = _float_array(faces, "faces")
    if F.ndim == 2 and F.shape == (3, 3):
        F = F[None]
    if F.ndim != 3 or F.shape[1:] != (3, 3) or F.shape[0] == 0:
        raise InputError(f"faces: expected an (m, 3, 3) array of triangle vertices, got shape {F.shape}")
    cams = list(orientations) if not isinstance(orientations, ExteriorOrientation) else [orientations]
    if not cams:
        raise InputError("orientations: at least one ExteriorOrientation is needed")
    for k, eo in enumerate(cams):
        if not isinstance(eo, ExteriorOrientation):
            raise InputError(f"orientations[{k}] must be an ExteriorOrientation, got {type(eo).__name__}")
    n = np.cross(F[:, 1] - F[:, 0], F[:, 2] - F[:, 0])
    size = np.linalg.norm(n, axis=1)
    scale = np.max(np.abs(F - F[:, :1]), axis=(1, 2)) ** 2
    if np.any(size <= 1e-12 * np.maximum(scale, 1e-300)):
        raise DegenerateGeometryError("a face has collinear vertices: it has no normal")
    n /= size[:, None]
    centroid = F.mean(axis=1)
    S = np.array([eo.center for eo in cams])                          # (k, 3)
    d = np.array([eo.matrix @ np.array([0.0, 0.0, -1.0]) for eo in cams])
    to_cam = S[None, :, :] - centroid[:, None, :]                     # (m, k, 3)
    front = np.einsum("mkc,mc->mk", to_cam, n) > 0
    ahead = np.einsum("mkc,kc->mk", -to_cam, d) > 0
    cosine = np.clip(-(n @ d.T), -1.0, 1.0)                           # cos angle(d_j, −n)
    cosine = np.where(front & ahead, cosine, -np.inf)
    best = np.argmax(cosine, axis=1)
    ok = np.isfinite(cosine[np.arange(len(F)), best])
    image = np.where(ok, best, -1)
    angle = np.where(ok, np.arccos(np.where(ok, cosine[np.arange(len(F)), best], 1.0)), np.nan)
    return TextureChoice(image, angle)
