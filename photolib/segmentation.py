"""Point-cloud segmentation and classification — Chapter 9, §9.11, eq. (9.11.1).

§9.11 lists three segmentation methods and one classification task; all four are here:

* :func:`hough_planes` — the Hough transform for planes: each point X votes for the cells
  (α, β, p) of p = X cos α cos β + Y sin α cos β + Z sin β (9.11.1); the cloud is first moved to
  its centroid (the book's advice: it keeps the range of p small), the strongest cell gives a
  plane, its points are taken within a distance threshold, the plane is refined by least squares
  (:func:`fit_plane`), its points removed and the voting repeated. (α, β) are the azimuth and
  elevation of the unit normal (:func:`plane_from_angles`, :func:`plane_angles`); α ∈ [0, π),
  β ∈ [−π/2, π/2], p signed covers every plane once.
* :func:`ransac_shape`, :func:`detect_shapes` — RANSAC for a line, plane, sphere or cylinder
  through the one RANSAC loop :func:`photolib.ransac.ransac` (minimal samples: 2 points for a
  line, 3 for a plane, 4 for a sphere; the cylinder, five parameters, is sampled as 2 points with
  their normals — 6 conditions for 5 unknowns, the usual practice (Schnabel et al. 2007) instead
  of the book's 5 bare points, whose solution needs a degree-6 polynomial), each consensus set
  refitted by least squares: :func:`fit_line`, :func:`fit_plane` (orthogonal regression, closed
  form), :func:`fit_sphere`, :func:`fit_cylinder` (geometric distances by Gauss–Newton through
  :func:`photolib.lsq.gauss_newton`, the Jacobians from the sympy models of
  :mod:`photolib.derivations.shapes`). :func:`detect_shapes` extracts several shapes in turn.
* :func:`estimate_normals`, :func:`region_growing` — normals and curvature by local PCA of the k
  nearest neighbours (``scipy.spatial.cKDTree``); regions grown from the flattest seeds, a
  neighbour joining when its normal is within an angle of the region's least-squares plane and its
  orthogonal distance to that plane is below a threshold (the book's test).
* :func:`lowest_point_raster`, :func:`classify_ground` — ground classification and a DTM: the
  lowest point per cell, the progressive morphological filter of Chapter 6
  (:func:`photolib.dtm.filter_dsm`), and a band test |Z − DTM| ≤ band per point.

Units: everything is in the units of the cloud (metres, or feet for a cloud in feet — pass the
distances in the same unit; slopes and angles are unitless / radians).

References: Chibunichev (2022), §9.11; Schnabel R., Wahl R., Klein R. (2007), "Efficient RANSAC
for point-cloud shape detection", Computer Graphics Forum 26(2), 214–226; Zhang K. et al. (2003),
IEEE TGRS 41(4), 872–882 (progressive morphological filter).
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from .errors import ConvergenceError, DegenerateGeometryError, InputError

__all__ = ["Line", "Plane", "Sphere", "Cylinder", "Segment", "Normals", "GroundClassification",
           "plane_from_angles", "plane_angles", "fit_line", "fit_plane", "fit_sphere", "fit_cylinder",
           "distances", "estimate_normals", "ransac_shape", "detect_shapes", "hough_planes",
           "region_growing", "lowest_point_raster", "classify_ground"]

_MIN_POINTS = {"line": 2, "plane": 3, "sphere": 4, "cylinder": 2}


# --- models ---------------------------------------------------------------------------------------
class Line(NamedTuple):
    """A 3-D line X = point + t·direction.

    Attributes
    ----------
    point : (3,) ndarray
        A point of the line (the centroid of the fitted points).
    direction : (3,) ndarray
        Unit direction.

    References
    ----------
    Chibunichev (2022), §9.11 (RANSAC primitives: line from 2 points).

    Examples
    --------
    >>> Line(np.zeros(3), np.array([1.0, 0, 0])).direction
    array([1., 0., 0.])
    """

    point: np.ndarray
    direction: np.ndarray


class Plane(NamedTuple):
    """A plane n·X = d with a unit normal n (so d is the signed distance of the origin).

    Attributes
    ----------
    normal : (3,) ndarray
        Unit normal (cos α cos β, sin α cos β, sin β) of (9.11.1).
    d : float
        p of (9.11.1) in the frame of the coordinates.

    References
    ----------
    Chibunichev (2022), §9.11, eq. (9.11.1).

    Examples
    --------
    >>> Plane(np.array([0, 0, 1.0]), 5.0).d
    5.0
    """

    normal: np.ndarray
    d: float


class Sphere(NamedTuple):
    """A sphere |X − centre| = radius.

    Attributes
    ----------
    center : (3,) ndarray
        Centre.
    radius : float
        Radius.

    References
    ----------
    Chibunichev (2022), §9.11 (RANSAC primitives).

    Examples
    --------
    >>> Sphere(np.zeros(3), 2.0).radius
    2.0
    """

    center: np.ndarray
    radius: float


class Cylinder(NamedTuple):
    """A circular cylinder: points at distance ``radius`` from the axis through ``point``.

    Attributes
    ----------
    point : (3,) ndarray
        The point of the axis nearest to the centroid of the fitted points.
    axis : (3,) ndarray
        Unit axis direction (sign normalised: the largest component positive).
    radius : float
        Radius.

    References
    ----------
    Chibunichev (2022), §9.11 (a cylinder has five parameters: two for the axis direction,
    three for the circle).

    Examples
    --------
    >>> Cylinder(np.zeros(3), np.array([0, 0, 1.0]), 0.5).radius
    0.5
    """

    point: np.ndarray
    axis: np.ndarray
    radius: float


class Segment(NamedTuple):
    """One found shape: its model and the indices of its points in the input cloud.

    Attributes
    ----------
    model : Line, Plane, Sphere or Cylinder
        The least-squares model of the points.
    indices : (m,) ndarray of int
        Indices of the points (into the cloud given to the detector).
    score : int
        Votes of the Hough cell (:func:`hough_planes`) or the consensus size (:func:`detect_shapes`).

    References
    ----------
    Chibunichev (2022), §9.11.

    Examples
    --------
    >>> s = Segment(Plane(np.array([0, 0, 1.0]), 0.0), np.arange(3), 3)
    >>> len(s.indices)
    3
    """

    model: object
    indices: np.ndarray
    score: int


class Normals(NamedTuple):
    """Normals and surface variation of a cloud by local PCA (:func:`estimate_normals`).

    Attributes
    ----------
    normals : (n, 3) ndarray
        Unit normals (sign: towards +Z, or +X/+Y for vertical ones).
    curvature : (n,) ndarray
        Surface variation λ₀/(λ₀+λ₁+λ₂) of the neighbourhood (0 on a plane, ≤ 1/3).

    References
    ----------
    Chibunichev (2022), §9.11 (region growing: a least-squares plane through the neighbours).

    Examples
    --------
    >>> Normals(np.zeros((1, 3)), np.zeros(1)).curvature
    array([0.])
    """

    normals: np.ndarray
    curvature: np.ndarray


class GroundClassification(NamedTuple):
    """Result of :func:`classify_ground`.

    Attributes
    ----------
    ground : (n,) ndarray of bool
        True for ground points (|Z − DTM| ≤ band).
    dtm : (ny, nx) ndarray
        The terrain model on ``grid`` (cells; row 0 northmost).
    grid : photolib.rectify.RasterGrid
        Geometry of the raster (top-left corner at (min X, max Y)).
    objects : (ny, nx) ndarray of bool
        Cells flagged as objects by the morphological filter.

    References
    ----------
    Chibunichev (2022), §9.11 (DTM from ALS by morphological filters); §6.6.

    Examples
    --------
    >>> r = GroundClassification(np.ones(2, bool), np.zeros((1, 1)), None, np.zeros((1, 1), bool))
    >>> int(r.ground.sum())
    2
    """

    ground: np.ndarray
    dtm: np.ndarray
    grid: object
    objects: np.ndarray


# --- checks ---------------------------------------------------------------------------------------
def _points(points, what="points", minimum=1) -> np.ndarray:
    if isinstance(points, (str, bytes)) or points is None:
        raise InputError(f"{what}: expected an (n, 3) array of numbers, got {type(points).__name__}")
    try:
        arr = np.asarray(points, dtype=float)
    except (TypeError, ValueError):
        raise InputError(f"{what}: expected an (n, 3) array of numbers") from None
    if arr.ndim != 2 or arr.shape[1] != 3:
        raise InputError(f"{what}: expected an (n, 3) array, got shape {arr.shape}")
    if not np.all(np.isfinite(arr)):
        raise InputError(f"{what} contain NaN or inf ({int((~np.isfinite(arr)).any(axis=1).sum())} points)")
    if len(arr) < minimum:
        raise InputError(f"{what}: at least {minimum} points are needed, got {len(arr)}")
    return arr


def _number(value, what, positive=True, allow_zero=False) -> float:
    if isinstance(value, (bool, np.bool_, str, bytes)) or value is None:
        raise InputError(f"{what} must be a number, got {value!r}")
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise InputError(f"{what} must be a number, got {value!r}") from None
    if not math.isfinite(v):
        raise InputError(f"{what} must be finite, got {value!r}")
    if positive and (v < 0 or (v == 0 and not allow_zero)):
        raise InputError(f"{what} must be {'≥ 0' if allow_zero else 'positive'}, got {value!r}")
    return v


def _int(value, what, minimum=1) -> int:
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, np.integer)):
        raise InputError(f"{what} must be an integer, got {value!r}")
    if value < minimum:
        raise InputError(f"{what} must be at least {minimum}, got {value}")
    return int(value)


def _unit(v):
    v = np.asarray(v, dtype=float)
    n = np.linalg.norm(v)
    if not n > 0:
        raise DegenerateGeometryError("a zero direction vector")
    return v / n


def _sign(v):
    """Normalise the sign of a direction: the largest |component| positive."""
    return v if v[np.argmax(np.abs(v))] >= 0 else -v


# --- (9.11.1) -------------------------------------------------------------------------------------
def plane_from_angles(alpha, beta, p) -> Plane:
    """The plane of (9.11.1): p = X cos α cos β + Y sin α cos β + Z sin β.

    Parameters
    ----------
    alpha, beta : float
        Azimuth and elevation of the normal, radians.
    p : float
        Signed distance of the plane from the origin.

    Returns
    -------
    Plane
        Unit normal (cos α cos β, sin α cos β, sin β) and d = p.

    Raises
    ------
    InputError
        Non-numeric or non-finite arguments.

    References
    ----------
    Chibunichev (2022), §9.11, eq. (9.11.1).

    Examples
    --------
    >>> pl = plane_from_angles(0.0, np.pi / 2, 3.0)
    >>> np.round(pl.normal, 12) + 0.0, pl.d
    (array([0., 0., 1.]), 3.0)
    """
    a = _number(alpha, "alpha", positive=False)
    b = _number(beta, "beta", positive=False)
    d = _number(p, "p", positive=False)
    return Plane(np.array([math.cos(a) * math.cos(b), math.sin(a) * math.cos(b), math.sin(b)]), d)


def plane_angles(plane) -> tuple:
    """(α, β, p) of (9.11.1) for a plane, with α ∈ [0, π), β ∈ [−π/2, π/2], p signed.

    Parameters
    ----------
    plane : Plane
        Any plane (the normal need not be unit).

    Returns
    -------
    (float, float, float)
        α, β (radians) and p (the sign of the normal chosen so that α ∈ [0, π)).

    Raises
    ------
    InputError
        Not a plane, or a zero/NaN normal.

    References
    ----------
    Chibunichev (2022), §9.11, eq. (9.11.1).

    Examples
    --------
    >>> a, b, p = plane_angles(Plane(np.array([0.0, -1.0, 0.0]), 2.0))
    >>> round(a, 6), round(b, 6), p
    (1.570796, 0.0, -2.0)
    """
    if not isinstance(plane, Plane):
        raise InputError(f"expected a Plane, got {type(plane).__name__}")
    n = np.asarray(plane.normal, dtype=float)
    d = _number(plane.d, "plane.d", positive=False)
    if n.shape != (3,) or not np.all(np.isfinite(n)) or not np.linalg.norm(n) > 0:
        raise InputError(f"the plane's normal must be a finite non-zero 3-vector, got {plane.normal!r}")
    s = np.linalg.norm(n)
    n, d = n / s, d / s
    alpha = math.atan2(n[1], n[0])
    if alpha < 0 or alpha >= math.pi:             # n → −n: (α + π, −β, −p)
        n, d = -n, -d
        alpha = math.atan2(n[1], n[0])
        if alpha >= math.pi or alpha < 0:         # n = (−1, 0, z) gives atan2(0, ·) = π
            alpha = 0.0 if abs(n[0]) + abs(n[1]) < 1e-15 else alpha % math.pi
    beta = math.asin(max(-1.0, min(1.0, n[2])))
    return alpha, beta, float(d)


# --- least-squares fits ---------------------------------------------------------------------------
def fit_line(points) -> Line:
    """Least-squares 3-D line (orthogonal regression): centroid and principal direction.

    Parameters
    ----------
    points : (n, 3) array_like
        n ≥ 2 points.

    Returns
    -------
    Line
        Minimises the sum of squared orthogonal distances.

    Raises
    ------
    InputError
        Fewer than 2 points, NaN/inf, wrong shape.
    DegenerateGeometryError
        All points coincide.

    References
    ----------
    Chibunichev (2022), §9.11 (line from 2 points; parameters refined by least squares).

    Examples
    --------
    >>> ln = fit_line([[0, 0, 0], [1, 1, 1], [2, 2, 2]])
    >>> np.round(ln.direction * np.sqrt(3), 6)
    array([1., 1., 1.])
    """
    P = _points(points, "line points", 2)
    c = P.mean(axis=0)
    _, s, vt = np.linalg.svd(P - c, full_matrices=False)
    if s[0] <= 1e-12 * max(1.0, np.abs(P).max()):
        raise DegenerateGeometryError("the line points coincide: no direction")
    return Line(c, _sign(vt[0]))


def fit_plane(points) -> Plane:
    """Least-squares plane (orthogonal regression): the normal is the direction of least spread.

    Parameters
    ----------
    points : (n, 3) array_like
        n ≥ 3 non-collinear points.

    Returns
    -------
    Plane
        Unit normal and d minimising Σ (n·X_i − d)².

    Raises
    ------
    InputError
        Fewer than 3 points, NaN/inf, wrong shape.
    DegenerateGeometryError
        Collinear or coincident points.

    References
    ----------
    Chibunichev (2022), §9.11 (plane parameters refined by least squares after the Hough
    transform / RANSAC; region growing).

    Examples
    --------
    >>> pl = fit_plane([[0, 0, 1], [1, 0, 1], [0, 1, 1], [1, 1, 1]])
    >>> np.round(pl.normal, 12) + 0.0, round(pl.d, 12)
    (array([0., 0., 1.]), 1.0)
    """
    P = _points(points, "plane points", 3)
    c = P.mean(axis=0)
    _, s, vt = np.linalg.svd(P - c, full_matrices=False)
    scale = max(s[0], 1e-300)
    if s[0] <= 1e-12 * max(1.0, np.abs(P).max()) or s[1] <= 1e-9 * scale:
        raise DegenerateGeometryError("the plane points are collinear or coincide: no unique plane")
    n = _sign(vt[2])
    return Plane(n, float(n @ c))


def _gauss_newton(linearize, x0, what):
    from .lsq import gauss_newton
    try:
        return gauss_newton(linearize, x0, tol=1e-10, max_iter=50)
    except ConvergenceError as exc:
        raise ConvergenceError(f"{what}: the least-squares fit did not converge: {exc}") from exc


def fit_sphere(points) -> Sphere:
    """Sphere by least squares: algebraic start, then geometric distances by Gauss–Newton.

    Four points give the sphere through them; more are adjusted with the residuals
    v_i = |X_i − C| − R through :func:`photolib.lsq.gauss_newton`, the derivatives from the sympy
    model :func:`photolib.derivations.shapes.sphere_distance_model`.

    Parameters
    ----------
    points : (n, 3) array_like
        n ≥ 4 points, not coplanar.

    Returns
    -------
    Sphere

    Raises
    ------
    InputError
        Fewer than 4 points, NaN/inf, wrong shape.
    DegenerateGeometryError
        Coplanar points (no unique sphere).
    ConvergenceError
        The adjustment does not converge.

    References
    ----------
    Chibunichev (2022), §9.11 (RANSAC primitives; least-squares refinement); §1.8 (the engine).

    Examples
    --------
    >>> s = fit_sphere([[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, 0, 1], [0, 0, -1]])
    >>> np.round(s.center, 9) + 0.0, round(s.radius, 9)
    (array([0., 0., 0.]), 1.0)
    """
    P = _points(points, "sphere points", 4)
    c0 = P.mean(axis=0)
    Q = P - c0
    scale = np.abs(Q).max()
    if not scale > 0:
        raise DegenerateGeometryError("the sphere points coincide")
    Qs = Q / scale
    A = np.column_stack([2 * Qs, np.ones(len(Qs))])
    b = (Qs ** 2).sum(axis=1)
    sv = np.linalg.svd(A, compute_uv=False)
    if sv[-1] <= 1e-9 * sv[0]:
        raise DegenerateGeometryError("the sphere points are coplanar (or collinear): no unique sphere")
    sol = np.linalg.lstsq(A, b, rcond=None)[0]
    centre = sol[:3]
    r2 = sol[3] + centre @ centre
    if not r2 > 0:
        raise DegenerateGeometryError("the algebraic sphere has no real radius")
    x0 = np.r_[centre, math.sqrt(r2)]
    if len(P) > 4:
        from .derivations.shapes import sphere_distance_model
        residual_fn, jacobian_fn = sphere_distance_model().compile()
        data = tuple(Qs.T)

        def lin(x):
            args = (*x, *data)
            v = residual_fn(*args)[0]
            if np.any(v + x[3] == 0):                      # ρ = 0: the derivatives are undefined
                raise DegenerateGeometryError("a point lies at the sphere's centre")
            return jacobian_fn(*args).T, v
        x0 = _gauss_newton(lin, x0, "sphere").x
    return Sphere(c0 + x0[:3] * scale, float(abs(x0[3]) * scale))


def _frame(a):
    """Two unit vectors u, v completing a to a right-handed orthonormal frame."""
    t = np.array([1.0, 0, 0]) if abs(a[0]) < 0.9 else np.array([0, 1.0, 0])
    u = np.cross(a, t)
    u /= np.linalg.norm(u)
    return u, np.cross(a, u)


def _circle2d(xy):
    """Algebraic (Kåsa) circle: centre, radius."""
    A = np.column_stack([2 * xy, np.ones(len(xy))])
    sv = np.linalg.svd(A, compute_uv=False)
    if sv[-1] <= 1e-9 * sv[0]:
        raise DegenerateGeometryError("the cylinder's cross-section points are collinear: no circle")
    sol = np.linalg.lstsq(A, (xy ** 2).sum(axis=1), rcond=None)[0]
    r2 = sol[2] + sol[:2] @ sol[:2]
    if not r2 > 0:
        raise DegenerateGeometryError("the cross-section circle has no real radius")
    return sol[:2], math.sqrt(r2)


def _cylinder_from_two(P, N):
    """Minimal cylinder: 2 points with normals (axis ⟂ both normals; centre where the normal lines meet)."""
    a = np.cross(N[0], N[1])
    if np.linalg.norm(a) < math.sin(math.radians(0.5)):
        raise DegenerateGeometryError("parallel normals: the sample does not fix a cylinder axis")
    a = _unit(a)
    u, v = _frame(a)
    B = np.column_stack([u, v])
    p = P @ B
    n = N @ B
    n /= np.linalg.norm(n, axis=1)[:, None]
    # p0 + s n0 = p1 + t n1
    M = np.column_stack([n[0], -n[1]])
    if abs(np.linalg.det(M)) < 1e-9:
        raise DegenerateGeometryError("the projected normals are parallel")
    s, t = np.linalg.solve(M, p[1] - p[0])
    centre = p[0] + s * n[0]
    r = 0.5 * (abs(s) + abs(t))
    point = centre @ B.T + a * (P.mean(axis=0) @ a)
    return Cylinder(point, _sign(a), float(r))


def fit_cylinder(points, normals=None) -> Cylinder:
    """Cylinder by least squares: start from the normals, then Gauss–Newton on geometric distances.

    Start: the axis is the direction least represented in the normals (smallest eigenvector of
    Σ n nᵀ), the circle an algebraic fit in the plane across the axis. Then the residuals
    v_i = |(X_i − C) × a| − R are adjusted through :func:`photolib.lsq.gauss_newton` with the
    five unknowns (two tilts of the axis, two shifts of the axis point across it, R), the
    derivatives from the sympy model :func:`photolib.derivations.shapes.cylinder_distance_model`.
    With two points the normals are required and the minimal solution is returned.

    Parameters
    ----------
    points : (n, 3) array_like
        n ≥ 2 points with normals, or n ≥ 6 points (normals then estimated by :func:`estimate_normals`).
    normals : (n, 3) array_like, optional
        Surface normals at the points.

    Returns
    -------
    Cylinder

    Raises
    ------
    InputError
        Too few points, NaN/inf, mismatched normals.
    DegenerateGeometryError
        Parallel normals, a flat or collinear cross-section.
    ConvergenceError
        The adjustment does not converge.

    References
    ----------
    Chibunichev (2022), §9.11 (five parameters: axis direction, then the circle);
    Schnabel et al. (2007) (two points with normals).

    Examples
    --------
    >>> t = np.linspace(0, 2 * np.pi, 12, endpoint=False)
    >>> P = np.column_stack([2 * np.cos(t), 2 * np.sin(t), np.tile([0.0, 1, 2], 4)])
    >>> c = fit_cylinder(P, np.column_stack([np.cos(t), np.sin(t), 0 * t]))
    >>> np.round(c.axis, 6) + 0.0, round(c.radius, 6)
    (array([0., 0., 1.]), 2.0)
    """
    P = _points(points, "cylinder points", 2)
    if normals is None:
        if len(P) < 6:
            raise InputError(f"a cylinder from {len(P)} points needs their normals (or at least 6 points)")
        N = estimate_normals(P, k=min(10, len(P))).normals
    else:
        N = _points(normals, "normals")
        if N.shape != P.shape:
            raise InputError(f"normals {N.shape} do not match the points {P.shape}")
        norm = np.linalg.norm(N, axis=1)
        if np.any(norm == 0):
            raise InputError("normals contain a zero vector")
        N = N / norm[:, None]
    if len(P) == 2:
        return _cylinder_from_two(P, N)
    if len(P) < 5:
        raise InputError(f"a least-squares cylinder needs at least 5 points (5 unknowns), got {len(P)}")
    w, V = np.linalg.eigh(N.T @ N)
    a0 = _sign(V[:, 0])
    if w[1] <= 1e-3 * w[2]:
        raise DegenerateGeometryError("the normals are (nearly) parallel: the points are planar, not a cylinder")
    c0m = P.mean(axis=0)
    scale = max(np.abs(P - c0m).max(), 1e-300)
    Q = (P - c0m) / scale
    u, v = _frame(a0)
    centre2, r0 = _circle2d(Q @ np.column_stack([u, v]))
    c0 = centre2[0] * u + centre2[1] * v

    def unpack(x):
        m = a0 + x[0] * u + x[1] * v
        return m, c0 + x[2] * u + x[3] * v

    from .derivations.shapes import cylinder_distance_model
    residual_fn, jacobian_fn = cylinder_distance_model().compile()
    data = (*Q.T, *a0, *u, *v, *c0)

    def lin(x):
        args = (*x, *data)
        res = residual_fn(*args)[0]
        if np.any(res + x[4] == 0):                        # ρ = 0: the derivatives are undefined
            raise DegenerateGeometryError("a point lies on the cylinder's axis")
        return jacobian_fn(*args).T, res

    try:
        x = _gauss_newton(lin, np.array([0, 0, 0, 0, r0]), "cylinder").x
    except DegenerateGeometryError as exc:
        raise DegenerateGeometryError(f"the points do not determine a cylinder (planar or too short an arc?): "
                                      f"{exc}") from exc
    m, c = unpack(x)
    a = _unit(m)
    c = c + a * ((Q.mean(axis=0) - c) @ a)
    return Cylinder(c0m + c * scale, _sign(a), float(abs(x[4]) * scale))


def distances(model, points) -> np.ndarray:
    """Orthogonal distances of points to a line, plane, sphere or cylinder (non-negative).

    Parameters
    ----------
    model : Line, Plane, Sphere or Cylinder
        The shape.
    points : (n, 3) array_like
        Points.

    Returns
    -------
    (n,) ndarray
        |distance| in the cloud's units.

    Raises
    ------
    InputError
        Unknown model type, NaN/inf, wrong shapes.

    References
    ----------
    Chibunichev (2022), §9.11 (points checked against the shape's equation with a threshold;
    orthogonal distances in region growing).

    Examples
    --------
    >>> distances(Sphere(np.zeros(3), 1.0), [[0, 0, 3.0], [0.5, 0, 0]])
    array([2. , 0.5])
    """
    P = _points(points, "points", 0)
    if isinstance(model, Plane):
        return np.abs(P @ np.asarray(model.normal, float) - float(model.d))
    if isinstance(model, Sphere):
        return np.abs(np.linalg.norm(P - np.asarray(model.center, float), axis=1) - float(model.radius))
    if isinstance(model, Line):
        w = P - np.asarray(model.point, float)
        return np.linalg.norm(np.cross(w, _unit(model.direction)), axis=1)
    if isinstance(model, Cylinder):
        w = P - np.asarray(model.point, float)
        return np.abs(np.linalg.norm(np.cross(w, _unit(model.axis)), axis=1) - float(model.radius))
    raise InputError(f"unknown model type {type(model).__name__}: expected Line, Plane, Sphere or Cylinder")


# --- normals --------------------------------------------------------------------------------------
def estimate_normals(points, k: int = 10) -> Normals:
    """Normals and surface variation by PCA of the k nearest neighbours (scipy cKDTree).

    Parameters
    ----------
    points : (n, 3) array_like
        The cloud, n ≥ 3.
    k : int
        Neighbours per point including itself, 3 ≤ k ≤ n.

    Returns
    -------
    Normals
        Unit normals (sign towards +Z; vertical ones towards the largest component positive)
        and surface variation λ₀/Σλ.

    Raises
    ------
    InputError
        k < 3 or k > n, NaN/inf, wrong shape.

    References
    ----------
    Chibunichev (2022), §9.11 (a least-squares plane through a point's neighbours).

    Examples
    --------
    >>> g = np.stack(np.meshgrid(np.arange(5.0), np.arange(5.0)), -1).reshape(-1, 2)
    >>> nr = estimate_normals(np.column_stack([g, np.ones(25)]), k=5)
    >>> float(np.abs(nr.normals[:, 2]).min()), float(nr.curvature.max())
    (1.0, 0.0)
    """
    from scipy.spatial import cKDTree
    P = _points(points, "points", 3)
    k = _int(k, "k", 3)
    if k > len(P):
        raise InputError(f"k = {k} neighbours exceed the {len(P)} points")
    _, idx = cKDTree(P).query(P, k=k)
    nb = P[idx]                                        # (n, k, 3)
    d = nb - nb.mean(axis=1, keepdims=True)
    C = np.einsum("nki,nkj->nij", d, d)
    w, V = np.linalg.eigh(C)
    N = V[:, :, 0]
    flip = N[:, 2] < 0
    vertical = np.abs(N[:, 2]) < 1e-9
    big = np.take_along_axis(N, np.argmax(np.abs(N), axis=1)[:, None], 1)[:, 0]
    flip = np.where(vertical, big < 0, flip)
    N[flip] *= -1
    tot = w.sum(axis=1)
    curv = np.where(tot > 0, w[:, 0] / np.where(tot > 0, tot, 1), 0.0)
    return Normals(N, np.clip(curv, 0, None))


# --- RANSAC ---------------------------------------------------------------------------------------
def _minimal_fit(shape):
    fits = {"line": fit_line, "plane": fit_plane, "sphere": fit_sphere}

    def fit(sample):
        try:
            if shape == "cylinder":
                return fit_cylinder(sample[0], sample[1])
            return fits[shape](sample[0])
        except InputError as exc:                     # e.g. a consensus set too small for the refit
            raise DegenerateGeometryError(str(exc)) from exc
    return fit


def _normal_angle(model, P, N):
    """Angle between each point's normal and the shape's normal at that point (radians, 0…π/2)."""
    if isinstance(model, Plane):
        g = np.broadcast_to(model.normal, P.shape)
    elif isinstance(model, Sphere):
        g = P - model.center
    elif isinstance(model, Cylinder):
        w = P - model.point
        g = w - (w @ model.axis)[:, None] * model.axis
    else:
        return np.zeros(len(P))
    gn = np.linalg.norm(g, axis=1)
    cos = np.abs(np.einsum("ij,ij->i", g, N)) / np.where(gn > 0, gn, 1)
    return np.arccos(np.clip(cos, 0, 1))


def ransac_shape(points, shape: str, threshold, normals=None, angle_threshold=None, confidence=0.99,
                 max_iterations: int = 1000, min_inliers=None, rng=0):
    """RANSAC for a line, plane, sphere or cylinder (§9.11) with least-squares refinement.

    The one RANSAC loop :func:`photolib.ransac.ransac` with minimal samples of 2 (line), 3 (plane),
    4 (sphere) points or 2 points with normals (cylinder); the residual is the orthogonal distance
    (:func:`distances`); the consensus set is refitted by least squares (:func:`fit_line`,
    :func:`fit_plane`, :func:`fit_sphere`, :func:`fit_cylinder`). With ``angle_threshold`` (needs
    normals) a point also needs its normal within that angle of the shape's normal.

    Parameters
    ----------
    points : (n, 3) array_like
        The cloud.
    shape : {"line", "plane", "sphere", "cylinder"}
        The primitive.
    threshold : float
        Largest orthogonal distance of an inlier, cloud units.
    normals : (n, 3) array_like, optional
        Point normals (required for a cylinder: estimated with :func:`estimate_normals`, k = 10,
        when omitted).
    angle_threshold : float, optional
        Largest angle (radians) between a point's normal and the shape's.
    confidence, max_iterations, rng
        As in :func:`photolib.ransac.ransac`.
    min_inliers : int, optional
        Smallest acceptable consensus set (default: sample size + 1).

    Returns
    -------
    photolib.ransac.RansacResult
        ``model`` a Line/Plane/Sphere/Cylinder fitted to the inliers; ``inliers``; residuals.

    Raises
    ------
    InputError
        Unknown shape, too few points, NaN/inf, bad thresholds, mismatched normals.
    DegenerateGeometryError
        Every sample degenerate (e.g. a cloud of collinear points for a plane), or, for a
        cylinder, a consensus set with parallel normals (a plane).
    ConvergenceError
        No consensus set of ``min_inliers``.

    References
    ----------
    Chibunichev (2022), §9.11 (RANSAC: minimal samples, threshold test); §5.10;
    Fischler & Bolles (1981); Schnabel et al. (2007).

    Examples
    --------
    >>> rng = np.random.default_rng(0)
    >>> P = np.column_stack([rng.uniform(0, 10, (200, 2)), np.full(200, 5.0)])
    >>> P[:50] = rng.uniform(0, 10, (50, 3))                  # 25 % outliers
    >>> r = ransac_shape(P, "plane", 0.05)
    >>> r.n_inliers >= 150, np.round(np.abs(r.model.normal), 6), round(abs(r.model.d), 6)
    (True, array([0., 0., 1.]), 5.0)
    """
    from .ransac import ransac
    if shape not in _MIN_POINTS:
        raise InputError(f"unknown shape {shape!r}: use 'line', 'plane', 'sphere' or 'cylinder'")
    s = _MIN_POINTS[shape]
    P = _points(points, "points", s + 1)
    thr = _number(threshold, "threshold")
    if thr == 0:
        raise InputError("threshold must be positive, got 0")
    N = None
    if normals is not None:
        N = _points(normals, "normals")
        if N.shape != P.shape:
            raise InputError(f"normals {N.shape} do not match the points {P.shape}")
        nn = np.linalg.norm(N, axis=1)
        if np.any(nn == 0):
            raise InputError("normals contain a zero vector")
        N = N / nn[:, None]
    elif shape == "cylinder" or angle_threshold is not None:
        N = estimate_normals(P, k=min(10, len(P))).normals
    ang = None if angle_threshold is None else _number(angle_threshold, "angle_threshold")
    fit = _minimal_fit(shape)

    def residual(model, data):
        Pd = data[0]
        r = distances(model, Pd)
        if ang is not None:
            r = np.where(_normal_angle(model, Pd, data[1]) <= ang, r, np.inf)
        return r

    data = (P, N) if N is not None else (P,)
    result = ransac(data, fit, residual, s, thr, confidence, max_iterations, rng, min_inliers)
    if shape == "cylinder" and result.n_inliers >= 5:
        # a plane is the limit of cylinders of growing radius: a consensus set whose normals are all
        # parallel is a plane, not a cylinder (fit_cylinder refuses it) — never a silent huge cylinder
        try:
            fit_cylinder(P[result.inliers], N[result.inliers])
        except DegenerateGeometryError as exc:
            raise DegenerateGeometryError(f"RANSAC found no cylinder: its best consensus set is not one ({exc})") from exc
    return result


def detect_shapes(points, shape: str, threshold, min_inliers: int, max_shapes: int = 10, normals=None,
                  angle_threshold=None, max_iterations: int = 1000, rng=0) -> list:
    """Several shapes one after another: RANSAC, remove the consensus set, repeat (§9.11).

    Parameters
    ----------
    points : (n, 3) array_like
        The cloud.
    shape : {"line", "plane", "sphere", "cylinder"}
        The primitive.
    threshold : float
        Inlier distance, cloud units.
    min_inliers : int
        Stop when the best remaining shape has fewer points.
    max_shapes : int
        Upper limit of shapes.
    normals, angle_threshold, max_iterations
        As in :func:`ransac_shape`.
    rng : int or numpy.random.Generator
        Seed.

    Returns
    -------
    list of Segment
        Models with the indices of their points in ``points``, in order of extraction.

    Raises
    ------
    InputError
        Bad arguments (see :func:`ransac_shape`).

    References
    ----------
    Chibunichev (2022), §9.11 (Fig. 9.41: roof and road planes found by RANSAC).

    Examples
    --------
    >>> rng = np.random.default_rng(1)
    >>> a = np.column_stack([rng.uniform(0, 10, (100, 2)), np.zeros(100)])
    >>> b = np.column_stack([rng.uniform(0, 10, (80, 2)), np.full(80, 4.0)])
    >>> segs = detect_shapes(np.vstack([a, b]), "plane", 0.05, min_inliers=30)
    >>> [len(s.indices) for s in segs]
    [100, 80]
    """
    P = _points(points, "points", _MIN_POINTS.get(shape, 1) + 1)
    m_in = _int(min_inliers, "min_inliers", 1)
    k = _int(max_shapes, "max_shapes", 1)
    N = None if normals is None else _points(normals, "normals")
    if N is not None and N.shape != P.shape:
        raise InputError(f"normals {N.shape} do not match the points {P.shape}")
    if N is None and (shape == "cylinder" or angle_threshold is not None):
        N = estimate_normals(P, k=min(10, len(P))).normals
    rng = rng if isinstance(rng, np.random.Generator) else np.random.default_rng(rng)
    left = np.arange(len(P))
    out = []
    while len(out) < k and len(left) > max(m_in, _MIN_POINTS.get(shape, 1)):
        try:
            r = ransac_shape(P[left], shape, threshold, None if N is None else N[left], angle_threshold,
                             max_iterations=max_iterations, min_inliers=m_in, rng=rng)
        except (ConvergenceError, DegenerateGeometryError):
            break
        out.append(Segment(r.model, left[r.inliers], r.n_inliers))
        left = left[~r.inliers]
    return out


# --- Hough (9.11.1) -------------------------------------------------------------------------------
def hough_planes(points, angle_step=math.radians(2.0), p_step=None, threshold=None, min_votes: int = 50,
                 max_planes: int = 10) -> list:
    """Planes by the Hough transform of (9.11.1), with centring and least-squares refinement.

    The cloud is moved to its centroid; each point votes, for every normal direction (α, β) on a
    grid of ``angle_step`` (α ∈ [0, π), β ∈ [−π/2, π/2]), for the cell of
    p = X cos α cos β + Y sin α cos β + Z sin β. The strongest cell gives a plane; its points are
    those within ``threshold``; the plane is refitted by least squares (:func:`fit_plane`) and the
    points re-selected (until stable, at most 5 times); they are removed and the voting repeated.

    Parameters
    ----------
    points : (n, 3) array_like
        The cloud.
    angle_step : float
        Cell size of α and β, radians (default 2°).
    p_step : float, optional
        Cell size of p, cloud units (default: 1/50 of the largest distance from the centroid).
    threshold : float, optional
        Inlier distance for the refinement, cloud units (default: ``p_step``).
    min_votes : int
        Stop when the strongest cell (or the refined plane) holds fewer points.
    max_planes : int
        Upper limit of planes.

    Returns
    -------
    list of Segment
        Planes (in the original coordinates), the indices of their points, the cell's votes.

    Raises
    ------
    InputError
        NaN/inf, wrong shape, fewer than 3 points, bad steps.

    References
    ----------
    Chibunichev (2022), §9.11, eq. (9.11.1) (centring, least-squares refinement).

    Examples
    --------
    >>> rng = np.random.default_rng(0)
    >>> xy = rng.uniform(0, 10, (300, 2))
    >>> P = np.vstack([np.column_stack([xy, 2 + 0.1 * xy[:, 0]]),
    ...                np.column_stack([xy[:200, 0], np.full(200, 3.0), xy[:200, 1]])])
    >>> segs = hough_planes(P, p_step=0.05, threshold=0.02)
    >>> [len(s.indices) for s in segs]
    [300, 200]
    """
    from ._segmentation_kernels import hough_vote
    P = _points(points, "points", 3)
    da = _number(angle_step, "angle_step")
    if da == 0 or da > math.pi / 4:
        raise InputError(f"angle_step must lie in (0, π/4], got {angle_step}")
    centre = P.mean(axis=0)
    Q = P - centre
    radius = float(np.linalg.norm(Q, axis=1).max())
    if radius == 0:
        raise DegenerateGeometryError("all points coincide: no plane")
    dp = radius / 50 if p_step is None else _number(p_step, "p_step")
    if dp == 0:
        raise InputError("p_step must be positive, got 0")
    thr = dp if threshold is None else _number(threshold, "threshold")
    if thr == 0:
        raise InputError("threshold must be positive, got 0")
    mv = _int(min_votes, "min_votes", 3)
    kmax = _int(max_planes, "max_planes", 1)
    n_a = max(1, int(round(math.pi / da)))
    n_b = int(round(math.pi / da)) + 1
    alphas = (np.arange(n_a) + 0.0) * (math.pi / n_a)
    betas = np.linspace(-math.pi / 2, math.pi / 2, n_b)
    A, B = np.meshgrid(alphas, betas, indexing="ij")
    dirs = np.column_stack([(np.cos(A) * np.cos(B)).ravel(), (np.sin(A) * np.cos(B)).ravel(),
                            np.sin(B).ravel()])
    n_p = int(math.ceil(2 * radius / dp)) + 2
    p_min = -radius - dp
    left = np.arange(len(P))
    out = []
    while len(out) < kmax and len(left) >= mv:
        acc = hough_vote(Q[left], dirs, p_min, dp, n_p)
        j, kk = np.unravel_index(int(np.argmax(acc)), acc.shape)
        votes = int(acc[j, kk])
        if votes < mv:
            break
        plane = Plane(dirs[j], p_min + (kk + 0.5) * dp)
        sel = distances(plane, Q[left]) < max(thr, dp / 2)
        for _ in range(5):
            if sel.sum() < 3:
                break
            try:
                plane = fit_plane(Q[left][sel])
            except DegenerateGeometryError:
                break
            new = distances(plane, Q[left]) < thr
            if np.array_equal(new, sel):
                break
            sel = new
        if sel.sum() < mv:
            break
        out.append(Segment(Plane(plane.normal, float(plane.d + plane.normal @ centre)), left[sel], votes))
        left = left[~sel]
    return out


# --- region growing -------------------------------------------------------------------------------
def region_growing(points, distance_threshold, angle_threshold=math.radians(10.0), k: int = 12,
                   min_size: int = 10, max_curvature=0.05) -> np.ndarray:
    """Planar regions grown from seeds (§9.11): neighbours join while they fit the region's plane.

    Normals by local PCA (:func:`estimate_normals`, k neighbours, scipy cKDTree). Seeds are taken
    in order of increasing surface variation (flattest first, only below ``max_curvature``); a
    region grows through the k-neighbour graph: a neighbour joins when its normal lies within
    ``angle_threshold`` of the region's least-squares plane and its orthogonal distance to that
    plane is below ``distance_threshold``. The plane is refitted (:func:`fit_plane`) whenever the
    region has grown by a quarter since the last fit. A point whose own neighbourhood is not flat
    (surface variation above ``max_curvature``: edges, ridges) is judged by the distance alone,
    its normal being unreliable. Regions smaller than ``min_size`` are dissolved (label −1).

    Parameters
    ----------
    points : (n, 3) array_like
        The cloud.
    distance_threshold : float
        Largest orthogonal distance to the region's plane, cloud units.
    angle_threshold : float
        Largest angle between a point's normal and the plane's, radians.
    k : int
        Neighbours per point (normals and growth).
    min_size : int
        Smallest region kept.
    max_curvature : float
        Largest surface variation of a seed point.

    Returns
    -------
    (n,) ndarray of int
        Region label per point (0, 1, … in order of size, largest first); −1 unassigned.

    Raises
    ------
    InputError
        NaN/inf, wrong shape, k out of range, bad thresholds.

    References
    ----------
    Chibunichev (2022), §9.11 (region growing: seed, neighbours, least-squares plane,
    orthogonal-distance test).

    Examples
    --------
    >>> g = np.stack(np.meshgrid(np.arange(10.0), np.arange(10.0)), -1).reshape(-1, 2)
    >>> roof = np.vstack([np.column_stack([g[g[:, 0] < 5], 0.5 * g[g[:, 0] < 5, 0]]),
    ...                   np.column_stack([g[g[:, 0] >= 5], 4.5 - 0.5 * g[g[:, 0] >= 5, 0]])])
    >>> lab = region_growing(roof, 0.05, angle_threshold=np.radians(30), k=8)
    >>> np.bincount(lab[lab >= 0]).tolist()
    [50, 50]
    """
    from scipy.spatial import cKDTree
    P = _points(points, "points", 3)
    dt = _number(distance_threshold, "distance_threshold")
    at = _number(angle_threshold, "angle_threshold")
    if dt == 0 or at == 0:
        raise InputError("distance_threshold and angle_threshold must be positive")
    k = _int(k, "k", 3)
    if k > len(P):
        raise InputError(f"k = {k} neighbours exceed the {len(P)} points")
    ms = _int(min_size, "min_size", 1)
    mc = _number(max_curvature, "max_curvature", allow_zero=True)
    nr = estimate_normals(P, k)
    _, nbrs = cKDTree(P).query(P, k=k)
    cos_t = math.cos(at)
    labels = np.full(len(P), -1)
    order = np.argsort(nr.curvature, kind="stable")
    regions = []
    for seed in order:
        if labels[seed] != -1 or nr.curvature[seed] > mc:
            continue
        lab = len(regions)
        members = [seed]
        labels[seed] = lab
        normal, d = nr.normals[seed], float(nr.normals[seed] @ P[seed])
        fitted = 1
        front = [seed]
        while front:
            nxt = []
            for i in front:
                for j in nbrs[i]:
                    if labels[j] != -1:
                        continue
                    if abs(P[j] @ normal - d) > dt or (nr.curvature[j] <= mc and abs(nr.normals[j] @ normal) < cos_t):
                        continue
                    labels[j] = lab
                    members.append(j)
                    nxt.append(j)
                if len(members) >= max(3, 1.25 * fitted):
                    try:
                        pl = fit_plane(P[members])
                        normal, d, fitted = pl.normal, pl.d, len(members)
                    except DegenerateGeometryError:
                        pass
            front = nxt
        regions.append(np.array(members))
    keep = sorted((r for r in regions if len(r) >= ms), key=lambda r: (-len(r), int(r.min())))
    out = np.full(len(P), -1)
    for lab, r in enumerate(keep):
        out[r] = lab
    return out


# --- ground classification ------------------------------------------------------------------------
def lowest_point_raster(points, cell_size):
    """The lowest Z per raster cell (a DSM of last returns for ground filtering).

    The grid's top-left corner is (min X, max Y); row i grows southwards (the library's raster
    convention, :class:`photolib.rectify.RasterGrid`). Empty cells take the value of the
    nearest filled cell.

    Parameters
    ----------
    points : (n, 3) array_like
        The cloud.
    cell_size : float
        Cell size, cloud units.

    Returns
    -------
    (ndarray, RasterGrid, ndarray)
        Heights (ny, nx), the grid, the mask of cells that held no point.

    Raises
    ------
    InputError
        NaN/inf, wrong shape, no points, bad cell size, a raster over 10⁸ cells.

    References
    ----------
    Chibunichev (2022), §9.11 (DTM from ALS); §7.7 (grid origin X₀ = min, Y₀ = max).

    Examples
    --------
    >>> z, grid, empty = lowest_point_raster([[0, 0, 5], [0.5, 0.5, 3], [1.5, 0.2, 7]], 1.0)
    >>> z.tolist(), grid.shape, empty.tolist()
    ([[3.0, 7.0]], (1, 2), [[False, False]])
    """
    from scipy import ndimage
    from ._segmentation_kernels import lowest_per_cell
    from .rectify import RasterGrid
    P = _points(points, "points", 1)
    c = _number(cell_size, "cell_size")
    if c == 0:
        raise InputError("cell_size must be positive, got 0")
    x0, y0 = float(P[:, 0].min()), float(P[:, 1].max())
    col = np.floor((P[:, 0] - x0) / c).astype(np.int64)
    row = np.floor((y0 - P[:, 1]) / c).astype(np.int64)
    ny, nx = int(row.max()) + 1, int(col.max()) + 1
    if ny * nx > 10 ** 8:
        raise InputError(f"a raster of {ny} × {nx} cells: cell_size {c} is too small for the cloud")
    grid = lowest_per_cell(row, col, P[:, 2].copy(), ny, nx)
    empty = ~np.isfinite(grid)
    if empty.any():
        idx = ndimage.distance_transform_edt(empty, return_distances=False, return_indices=True)
        grid = grid[tuple(idx)]
    return grid, RasterGrid(x0, y0, c, (ny, nx)), empty


def classify_ground(points, cell_size, max_window, slope=0.3, dh0=0.3, dh_max=3.0, band=0.3,
                    base=2.0) -> GroundClassification:
    """Ground points and a DTM: lowest point per cell, progressive morphological filter, band test.

    The lowest-point raster (:func:`lowest_point_raster`) is filtered by
    :func:`photolib.dtm.filter_dsm` (Zhang et al. 2003, removed cells refilled from the TIN of
    the ground cells); a point is ground when |Z − DTM(X, Y)| ≤ ``band``, the DTM interpolated
    bilinearly between cell centres. All lengths in the cloud's units (give feet for a cloud in
    feet); ``slope`` is unitless.

    Parameters
    ----------
    points : (n, 3) array_like
        The cloud (last returns preferably).
    cell_size : float
        Raster cell, cloud units.
    max_window : float
        Largest filter window (≥ the largest building), cloud units.
    slope : float
        Steepest terrain slope kept (tan).
    dh0, dh_max : float
        Initial and largest height thresholds, cloud units.
    band : float
        Largest |Z − DTM| of a ground point, cloud units.
    base : float
        Window growth of the filter.

    Returns
    -------
    GroundClassification
        Ground mask, DTM, grid, object cells.

    Raises
    ------
    InputError
        NaN/inf, wrong shape, bad parameters, a raster smaller than 3 × 3 cells.
    DegenerateGeometryError
        Fewer than 3 ground cells remain.

    References
    ----------
    Chibunichev (2022), §9.11 (classification for a DTM: morphological filters); §6.6;
    Zhang et al. (2003), IEEE TGRS 41(4), 872–882.

    Examples
    --------
    >>> g = np.stack(np.meshgrid(np.arange(0, 30, 0.5), np.arange(0, 30, 0.5)), -1).reshape(-1, 2)
    >>> z = 0.05 * g[:, 0] + np.where((abs(g[:, 0] - 15) < 3) & (abs(g[:, 1] - 15) < 3), 6.0, 0.0)
    >>> r = classify_ground(np.column_stack([g, z]), 1.0, max_window=15.0)
    >>> int((~r.ground).sum()), int(((~r.ground) == (z > 3)).all())
    (121, 1)
    """
    from scipy import ndimage
    from .dtm import filter_dsm
    P = _points(points, "points", 3)
    b = _number(band, "band")
    z, grid, _ = lowest_point_raster(P, cell_size)
    if min(z.shape) < 3:
        raise InputError(f"the raster has {z.shape} cells: at least 3 × 3 are needed (smaller cell_size)")
    dtm, objects = filter_dsm(z, float(cell_size), max_window=max_window, slope=slope, dh0=dh0,
                              dh_max=dh_max, base=base)
    c = float(cell_size)
    rows = (grid.y0 - P[:, 1]) / c - 0.5
    cols = (P[:, 0] - grid.x0) / c - 0.5
    zg = ndimage.map_coordinates(dtm, [rows, cols], order=1, mode="nearest")
    return GroundClassification(np.abs(P[:, 2] - zg) <= b, dtm, grid, objects)
