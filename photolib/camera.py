"""Interior and exterior orientation of a frame image — Chapter 1, §1.2–§1.3.

* :class:`InteriorOrientation` — f, x₀, y₀ and Brown's distortion coefficients (§1.2).
* :func:`distortion_correction` — (1.2.2): corrections d_x, d_y **added to measured**
  coordinates; :func:`correct_distortion`, :func:`apply_distortion` (its inverse);
  :func:`image_vector` — the ray vector (1.2.1)/(1.2.3).
* :class:`ExteriorOrientation` — X_S, Y_S, Z_S and the angles ω, α, κ of a named rotation
  sequence (§1.3); :class:`ExteriorOrientations` — many of them at once (a block of images).
* :func:`as_points`, :func:`as_point_pairs` — the input checks every library function uses
  for coordinate arrays (finite numbers, shapes, counts).

Units: image coordinates and f in millimetres, object coordinates in metres, angles in radians.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from .errors import ConvergenceError, DegenerateGeometryError, InputError
from .rotation import (DEFAULT_ORDER, _as_rotation, _numbers, _order, _rotation_matrix, _warn_degrees,
                       rotation_angles)

__all__ = ["as_points", "as_point_pairs", "InteriorOrientation", "distortion_correction", "correct_distortion",
           "apply_distortion", "image_vector", "ExteriorOrientation", "ExteriorOrientations"]


def _expect(value, cls, what: str):
    """Raise :class:`InputError` naming the expected type unless ``value`` is a ``cls``."""
    if not isinstance(value, cls):
        raise InputError(f"{what} must be a {cls.__name__}, got {type(value).__name__}")
    return value


def _scalar(value, what: str) -> float:
    """One finite number (not a string, not an array of several), as a float."""
    arr = _numbers(value, what)
    if arr.ndim != 0:
        raise InputError(f"{what} must be one number, got shape {arr.shape}")
    return float(arr)


def as_points(values, dim: int, what: str = "points") -> np.ndarray:
    """Validate an (n, dim) array of finite coordinates (a single point is promoted to (1, dim)).

    Parameters
    ----------
    values : array_like
        The coordinates, one row per point.
    dim : int
        Coordinates per point (2 for image points, 3 for object points).
    what : str
        Name of the argument, used in the error message.

    Returns
    -------
    ndarray
        Float array of shape (n, dim).

    Raises
    ------
    InputError
        A wrong shape, NaN/inf, or something that is not a number (e.g. a string).

    References
    ----------
    Chibunichev (2022), §1.2 and §1.4 (image and object coordinates).

    Examples
    --------
    >>> as_points([1.0, 2.0], 2)
    array([[1., 2.]])
    """
    arr = _numbers(values, what)
    if arr.ndim == 1 and arr.shape[0] == dim:
        arr = arr[None, :]
    if arr.ndim != 2 or arr.shape[1] != dim:
        raise InputError(f"{what}: expected an array of shape (n, {dim}), got {np.shape(values)}")
    return arr


def as_point_pairs(first, dim_first: int, second, dim_second: int, names=("points", "points"),
                   minimum: int = 1, task: str = "this problem"):
    """Validate two arrays of corresponding points (same count, finite) and a minimum count.

    Parameters
    ----------
    first, second : array_like
        The two point sets, (n, dim_first) and (n, dim_second).
    dim_first, dim_second : int
        Coordinates per point of each set.
    names : (str, str)
        Names of the two sets for the messages.
    minimum : int
        Least number of points ``task`` needs.
    task : str
        What the points are for, for the message.

    Returns
    -------
    (ndarray, ndarray)
        The two validated arrays.

    Raises
    ------
    InputError
        Wrong shapes, different counts, too few points, NaN/inf, non-numbers.

    References
    ----------
    Chibunichev (2022), §1.8 (control points and their image points).

    Examples
    --------
    >>> XYZ, xy = as_point_pairs([[0, 0, 0]], 3, [[1, 2]], 2)
    >>> XYZ.shape, xy.shape
    ((1, 3), (1, 2))
    """
    a = as_points(first, dim_first, names[0])
    b = as_points(second, dim_second, names[1])
    if len(a) != len(b):
        raise InputError(f"{len(a)} {names[0]} but {len(b)} {names[1]}: shapes must match")
    if len(a) < minimum:
        raise InputError(f"{task} needs at least {minimum} points, got {len(a)}")
    return a, b


@dataclass(frozen=True, repr=False)
class InteriorOrientation:
    """Interior orientation (§1.2): focal length f, principal point (x₀, y₀), Brown coefficients.

    Parameters
    ----------
    f : float
        Focal length (principal distance) in mm, > 0.
    x0, y0 : float
        Principal point in mm.
    k1, k2, k3 : float
        Radial distortion coefficients (mm⁻², mm⁻⁴, mm⁻⁶) of (1.2.2).
    p1, p2 : float
        Decentering coefficients (mm⁻¹) of (1.2.2); the corrections are added to measured
        coordinates.

    Raises
    ------
    InputError
        NaN/inf, a non-number, or f ≤ 0.

    References
    ----------
    Chibunichev (2022), §1.2, eqs. (1.2.1)–(1.2.3).

    Examples
    --------
    >>> InteriorOrientation(100.0, 0.02, -0.01)
    InteriorOrientation(f=100.000 mm, x0=0.020 mm, y0=-0.010 mm)
    """

    f: float
    x0: float = 0.0
    y0: float = 0.0
    k1: float = 0.0
    k2: float = 0.0
    k3: float = 0.0
    p1: float = 0.0
    p2: float = 0.0

    def __post_init__(self):
        for name in ("f", "x0", "y0", "k1", "k2", "k3", "p1", "p2"):
            _scalar(getattr(self, name), f"interior orientation {name}")
        if self.f <= 0:
            raise InputError(f"focal length must be positive, got f = {self.f}")

    @property
    def has_distortion(self) -> bool:
        """True if any distortion coefficient is non-zero."""
        return any((self.k1, self.k2, self.k3, self.p1, self.p2))

    def __repr__(self) -> str:
        parts = [f"f={float(self.f):.3f} mm", f"x0={float(self.x0):.3f} mm", f"y0={float(self.y0):.3f} mm"]
        units = {"k1": "mm⁻²", "k2": "mm⁻⁴", "k3": "mm⁻⁶", "p1": "mm⁻¹", "p2": "mm⁻¹"}
        parts += [f"{k}={float(getattr(self, k)):.4g} {u}" for k, u in units.items() if getattr(self, k)]
        return f"InteriorOrientation({', '.join(parts)})"


def distortion_correction(xy, io: InteriorOrientation):
    """Corrections (d_x, d_y) of (1.2.2) for measured image coordinates ``xy`` (mm).

    With x̄ = x − x₀, ȳ = y − y₀, r² = x̄² + ȳ²:
    d_x = x̄(k₁r² + k₂r⁴ + k₃r⁶) + (r² + 2x̄²)p₁ + 2x̄ȳ p₂,
    d_y = ȳ(k₁r² + k₂r⁴ + k₃r⁶) + 2x̄ȳ p₁ + (r² + 2ȳ²)p₂.

    Parameters
    ----------
    xy : (n, 2) array
        Measured image coordinates in mm.
    io : InteriorOrientation
        Principal point and distortion coefficients.

    Returns
    -------
    ndarray
        (n, 2) corrections d_x, d_y in mm, to be added to ``xy``.

    Raises
    ------
    InputError
        Wrong shape, NaN/inf, or ``io`` not an InteriorOrientation.

    References
    ----------
    Chibunichev (2022), §1.2, eq. (1.2.2).

    Examples
    --------
    >>> distortion_correction([[10.0, 0.0]], InteriorOrientation(100.0, k1=-1e-5))
    array([[-0.01,  0.  ]])
    """
    _expect(io, InteriorOrientation, "io")
    xy = as_points(xy, 2, "image coordinates")
    xb, yb = xy[:, 0] - io.x0, xy[:, 1] - io.y0
    r2 = xb * xb + yb * yb
    radial = io.k1 * r2 + io.k2 * r2 ** 2 + io.k3 * r2 ** 3
    dx = xb * radial + (r2 + 2 * xb * xb) * io.p1 + 2 * xb * yb * io.p2
    dy = yb * radial + 2 * xb * yb * io.p1 + (r2 + 2 * yb * yb) * io.p2
    return np.column_stack([dx, dy])


def correct_distortion(xy, io: InteriorOrientation) -> np.ndarray:
    """Measured → ideal image coordinates: x + d_x, y + d_y (1.2.3).

    Parameters
    ----------
    xy : (n, 2) array
        Measured image coordinates in mm.
    io : InteriorOrientation

    Returns
    -------
    ndarray
        (n, 2) ideal coordinates in mm.

    Raises
    ------
    InputError
        Wrong shape, NaN/inf, or ``io`` not an InteriorOrientation.

    References
    ----------
    Chibunichev (2022), §1.2, eqs. (1.2.2)–(1.2.3).

    Examples
    --------
    >>> correct_distortion([[10.0, 0.0]], InteriorOrientation(100.0, k1=-1e-5))
    array([[9.99, 0.  ]])
    """
    _expect(io, InteriorOrientation, "io")
    xy = as_points(xy, 2, "image coordinates")
    return xy + distortion_correction(xy, io)


def apply_distortion(xy_ideal, io: InteriorOrientation, tol: float = 1e-12, max_iter: int = 30) -> np.ndarray:
    """Ideal → measured coordinates: solve x + d_x(x, y) = x_ideal, y + d_y(x, y) = y_ideal.

    The inverse of :func:`correct_distortion`, needed to simulate what a distorting camera
    records. Newton's method with the 2×2 Jacobian of (1.2.2) derived by sympy
    (:func:`photolib.derivations.distortion_model`).

    Parameters
    ----------
    xy_ideal : (n, 2) array
        Ideal image coordinates in mm.
    io : InteriorOrientation
    tol : float
        Step threshold, relative to the largest coordinate.
    max_iter : int
        Newton iterations allowed.

    Returns
    -------
    ndarray
        (n, 2) measured coordinates in mm; ``correct_distortion`` of them gives ``xy_ideal``.

    Raises
    ------
    InputError
        Wrong shape, NaN/inf, or ``io`` not an InteriorOrientation.
    DegenerateGeometryError
        Where the correction folds the image over (its Jacobian determinant is not positive):
        no measured point maps to the ideal one.
    ConvergenceError
        Newton's method did not settle in ``max_iter`` steps.

    References
    ----------
    Chibunichev (2022), §1.2, eqs. (1.2.2)–(1.2.3).

    Examples
    --------
    >>> io = InteriorOrientation(100.0, k1=-1e-5)
    >>> measured = apply_distortion([[9.99, 0.0]], io)
    >>> correct_distortion(measured, io).round(12) + 0.0
    array([[9.99, 0.  ]])
    """
    from . import derivations

    _expect(io, InteriorOrientation, "io")
    ideal = as_points(xy_ideal, 2, "image coordinates")
    if not io.has_distortion:
        return ideal.copy()
    residual_fn, jacobian_fn = derivations.distortion_model().compile()
    coefficients = (io.x0, io.y0, io.k1, io.k2, io.k3, io.p1, io.p2)
    measured = ideal.copy()
    for _ in range(max_iter):
        F = residual_fn(measured[:, 0], measured[:, 1], *coefficients).T - ideal
        j11, j12, j21, j22 = jacobian_fn(measured[:, 0], measured[:, 1], *coefficients)
        det = j11 * j22 - j12 * j21
        if np.any(det <= 0):
            bad = np.flatnonzero(det <= 0)[:5].tolist()
            raise DegenerateGeometryError(
                f"points {bad} lie where the distortion correction (1.2.2) folds the image over; "
                "it has no inverse there")
        step = np.column_stack([(j22 * F[:, 0] - j12 * F[:, 1]) / det, (j11 * F[:, 1] - j21 * F[:, 0]) / det])
        measured = measured - step
        if np.max(np.abs(step)) < tol * max(1.0, float(np.max(np.abs(ideal)))):
            return measured
    raise ConvergenceError("inverting the distortion model did not converge; are the coefficients realistic?")


def image_vector(xy, io: InteriorOrientation, distortion: bool = True) -> np.ndarray:
    """Ray vectors r = (x − x₀ + d_x, y − y₀ + d_y, −f) of (1.2.3), (1.2.1) without distortion.

    Parameters
    ----------
    xy : (n, 2) array
        Measured image coordinates in mm.
    io : InteriorOrientation
    distortion : bool
        Apply the correction (1.2.2) first (if ``io`` has coefficients).

    Returns
    -------
    ndarray
        (n, 3) vectors in the image space system, mm.

    Raises
    ------
    InputError
        Wrong shape, NaN/inf, or ``io`` not an InteriorOrientation.

    References
    ----------
    Chibunichev (2022), §1.2, eqs. (1.2.1), (1.2.3).

    Examples
    --------
    >>> image_vector([[1.0, 2.0]], InteriorOrientation(100.0, 0.5, 0.5))
    array([[   0.5,    1.5, -100. ]])
    """
    _expect(io, InteriorOrientation, "io")
    xy = as_points(xy, 2, "image coordinates")
    if distortion and io.has_distortion:
        xy = correct_distortion(xy, io)
    return np.column_stack([xy[:, 0] - io.x0, xy[:, 1] - io.y0, np.full(len(xy), -io.f)])


_EO_UNITS = ("m", "m", "m")


@dataclass(frozen=True, repr=False)
class ExteriorOrientation:
    """Exterior orientation (§1.3): projection centre (X_S, Y_S, Z_S) in m, angles ω, α, κ in radians.

    The one exterior-orientation type of the library; it carries the rotation sequence its
    angles belong to. For many images at once use :class:`ExteriorOrientations`.

    Parameters
    ----------
    Xs, Ys, Zs : float
        Projection centre S in metres.
    omega, alpha, kappa : float
        Angles in radians (an angle above 2π in magnitude warns: degrees passed?).
    order : {"kaw", "wak"}
        Rotation sequence of the angles: ``"kaw"`` (1.3.5, the book's examples) or ``"wak"``
        (1.3.2).

    Attributes
    ----------
    vector : ndarray
        (X_S, Y_S, Z_S, ω, α, κ).
    center : ndarray
        (X_S, Y_S, Z_S).
    matrix : ndarray
        A (camera → object) of the named sequence.
    angles_degrees : ndarray
        (ω, α, κ) in degrees.

    Raises
    ------
    InputError
        NaN/inf, a non-number, an unknown order.

    References
    ----------
    Chibunichev (2022), §1.3, eqs. (1.3.1)–(1.3.6); §1.4, eq. (1.4.10).

    Examples
    --------
    >>> eo = ExteriorOrientation.from_degrees(1000, 1000, 1000, 2, 5, 7)
    >>> eo
    ExteriorOrientation(Xs=1000.000 m, Ys=1000.000 m, Zs=1000.000 m, omega=2.0000°, alpha=5.0000°, kappa=7.0000°, order='kaw')
    >>> eo.kappa
    0.1221...
    """

    Xs: float
    Ys: float
    Zs: float
    omega: float = 0.0
    alpha: float = 0.0
    kappa: float = 0.0
    order: str = DEFAULT_ORDER

    NAMES = ("Xs", "Ys", "Zs", "omega", "alpha", "kappa")

    def __post_init__(self):
        _order(self.order)
        values = [_scalar(getattr(self, name), f"exterior orientation {name}") for name in self.NAMES]
        _warn_degrees(values[3:], "exterior orientation angles omega, alpha, kappa", stacklevel=4)

    def __repr__(self) -> str:
        w, a, k = self.angles_degrees
        return (f"ExteriorOrientation(Xs={float(self.Xs):.3f} m, Ys={float(self.Ys):.3f} m, "
                f"Zs={float(self.Zs):.3f} m, omega={w:.4f}°, alpha={a:.4f}°, kappa={k:.4f}°, "
                f"order={self.order!r})")

    @classmethod
    def from_degrees(cls, Xs, Ys, Zs, omega=0.0, alpha=0.0, kappa=0.0, order=DEFAULT_ORDER):
        """Build from angles given in degrees (the centre in metres)."""
        w, a, k = np.radians(_numbers([omega, alpha, kappa], "angles in degrees"))
        return cls(Xs, Ys, Zs, float(w), float(a), float(k), order)

    @classmethod
    def from_vector(cls, vector, order=DEFAULT_ORDER):
        """Build from (X_S, Y_S, Z_S, ω, α, κ), angles in radians."""
        v = _numbers(vector, "exterior orientation vector")
        if v.shape != (6,):
            raise InputError(f"exterior orientation vector must have 6 elements, got {v.shape}")
        return cls(*map(float, v), order=order)

    @classmethod
    def from_matrix(cls, center, A, order=DEFAULT_ORDER):
        """Build from a projection centre and a rotation matrix A (camera → object).

        ``A`` must be a rotation (AᵀA = E, det A = +1); its angles are taken by (1.3.6) or
        (1.3.3) for ``order``.
        """
        c = _numbers(center, "projection centre")
        if c.shape != (3,):
            raise InputError(f"the projection centre must be (X_S, Y_S, Z_S), got shape {c.shape}")
        w, a, k = rotation_angles(A, order)
        return cls(float(c[0]), float(c[1]), float(c[2]), w, a, k, order)

    @property
    def vector(self) -> np.ndarray:
        """(X_S, Y_S, Z_S, ω, α, κ) as a float array."""
        return np.array([self.Xs, self.Ys, self.Zs, self.omega, self.alpha, self.kappa], dtype=float)

    @property
    def center(self) -> np.ndarray:
        """(X_S, Y_S, Z_S) in metres."""
        return np.array([self.Xs, self.Ys, self.Zs], dtype=float)

    @property
    def angles_degrees(self) -> np.ndarray:
        """(ω, α, κ) in degrees."""
        return np.degrees(np.array([self.omega, self.alpha, self.kappa], dtype=float))

    @property
    def matrix(self) -> np.ndarray:
        """A (camera → object) of the named sequence, (1.3.2) or (1.3.5)."""
        return _rotation_matrix(float(self.omega), float(self.alpha), float(self.kappa), self.order)

    def with_order(self, order: str) -> "ExteriorOrientation":
        """The same orientation with its angles expressed in another rotation sequence."""
        w, a, k = rotation_angles(self.matrix, order)
        return replace(self, omega=w, alpha=a, kappa=k, order=order)


class ExteriorOrientations:
    """The exterior orientations of many images at once (a block), vectorised (§1.3, §3.5).

    Holds the centres as an (n, 3) array and the angles as an (n, 3) array of one rotation
    sequence. Indexing with an integer gives an :class:`ExteriorOrientation`, with a slice or an
    index array another collection.

    Parameters
    ----------
    centres : (n, 3) array
        Projection centres (X_S, Y_S, Z_S) in metres.
    angles : (n, 3) array
        (ω, α, κ) per image in radians.
    order : {"kaw", "wak"}
        Rotation sequence of all the angles.

    Attributes
    ----------
    centres, angles : ndarray
        Read-only (n, 3) arrays.
    order : str
        The rotation sequence.

    Raises
    ------
    InputError
        Shapes that are not (n, 3) or differ, NaN/inf, non-numbers, an unknown order.

    References
    ----------
    Chibunichev (2022), §1.3, eqs. (1.3.2), (1.3.5); §3.5 (the bundle of many images).

    Examples
    --------
    >>> eos = ExteriorOrientations([[0, 0, 1000], [600, 0, 1000]], [[0, 0, 0], [0, 0, 0.1]])
    >>> len(eos), eos.matrices().shape
    (2, (2, 3, 3))
    >>> eos[1]
    ExteriorOrientation(Xs=600.000 m, Ys=0.000 m, Zs=1000.000 m, omega=0.0000°, alpha=0.0000°, kappa=5.7296°, order='kaw')
    """

    def __init__(self, centres, angles, order: str = DEFAULT_ORDER):
        self.order = _order(order)
        c = _numbers(centres, "centres")
        a = _numbers(angles, "angles")
        if c.ndim == 1 and c.size == 3:
            c = c[None]
        if a.ndim == 1 and a.size == 3:
            a = a[None]
        if c.ndim != 2 or c.shape[1] != 3:
            raise InputError(f"centres: expected shape (n, 3), got {c.shape}")
        if a.shape != c.shape:
            raise InputError(f"angles: expected shape {c.shape} like the centres, got {a.shape}")
        _warn_degrees(a, "angles omega, alpha, kappa")
        c, a = c.copy(), a.copy()
        c.flags.writeable = False
        a.flags.writeable = False
        self.centres, self.angles = c, a

    @classmethod
    def from_list(cls, orientations, order: str | None = None) -> "ExteriorOrientations":
        """Collect a sequence of :class:`ExteriorOrientation` (converted to ``order``, by default
        the order of the first)."""
        items = list(orientations)
        for k, eo in enumerate(items):
            _expect(eo, ExteriorOrientation, f"orientations[{k}]")
        if order is None:
            order = items[0].order if items else DEFAULT_ORDER
        _order(order)
        items = [eo if eo.order == order else eo.with_order(order) for eo in items]
        vectors = np.array([eo.vector for eo in items], dtype=float).reshape(-1, 6)
        return cls(vectors[:, :3], vectors[:, 3:], order)

    @classmethod
    def from_vectors(cls, vectors, order: str = DEFAULT_ORDER) -> "ExteriorOrientations":
        """From an (n, 6) array of (X_S, Y_S, Z_S, ω, α, κ)."""
        v = _numbers(vectors, "exterior orientation vectors")
        if v.ndim != 2 or v.shape[1] != 6:
            raise InputError(f"exterior orientation vectors: expected shape (n, 6), got {v.shape}")
        return cls(v[:, :3], v[:, 3:], order)

    def to_list(self) -> list:
        """The orientations as a list of :class:`ExteriorOrientation`."""
        return [self[k] for k in range(len(self))]

    @property
    def vectors(self) -> np.ndarray:
        """(n, 6) array of (X_S, Y_S, Z_S, ω, α, κ)."""
        return np.hstack([self.centres, self.angles])

    def matrices(self) -> np.ndarray:
        """(n, 3, 3) stack of A (camera → object), (1.3.2) or (1.3.5)."""
        return _rotation_matrix(self.angles[:, 0], self.angles[:, 1], self.angles[:, 2], self.order)

    def with_order(self, order: str) -> "ExteriorOrientations":
        """The same orientations with the angles in another rotation sequence."""
        _order(order)
        if order == self.order:
            return self
        w, a, k = rotation_angles(self.matrices(), order) if len(self) else (np.empty(0),) * 3
        return ExteriorOrientations(self.centres, np.column_stack([w, a, k]), order)

    def __len__(self) -> int:
        return len(self.centres)

    def __iter__(self):
        return iter(self.to_list())

    def __getitem__(self, index):
        if isinstance(index, (int, np.integer)):
            n = len(self)
            if not -n <= index < n:
                raise InputError(f"image {index} out of range: the collection holds {n} orientations")
            c, a = self.centres[index], self.angles[index]
            return ExteriorOrientation(*map(float, c), *map(float, a), order=self.order)
        try:
            return ExteriorOrientations(self.centres[index], self.angles[index], self.order)
        except IndexError as exc:
            raise InputError(f"bad image index {index!r}: {exc}") from None

    def __eq__(self, other):
        if not isinstance(other, ExteriorOrientations):
            return NotImplemented
        return (self.order == other.order and np.array_equal(self.centres, other.centres)
                and np.array_equal(self.angles, other.angles))

    __hash__ = None

    def __repr__(self) -> str:
        n = len(self)
        head = f"ExteriorOrientations({n} images, order={self.order!r}"
        if n == 0:
            return head + ")"
        lo, hi = self.centres.min(axis=0), self.centres.max(axis=0)
        return head + (f", centres X {lo[0]:.3f}…{hi[0]:.3f} m, Y {lo[1]:.3f}…{hi[1]:.3f} m, "
                       f"Z {lo[2]:.3f}…{hi[2]:.3f} m)")
