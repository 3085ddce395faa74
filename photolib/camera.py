"""Interior and exterior orientation of a frame image — Chapter 1, §1.2–§1.3.

* :class:`InteriorOrientation` — f, x₀, y₀ and Brown's distortion coefficients (§1.2).
* :func:`distortion_correction` — (1.2.2): corrections d_x, d_y **added to measured**
  coordinates; :func:`image_vector` — the ray vector (1.2.1)/(1.2.3).
* :class:`ExteriorOrientation` — X_S, Y_S, Z_S and the angles ω, α, κ of a named rotation
  sequence (§1.3).

Units: image coordinates and f in millimetres, object coordinates in metres, angles in radians.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from .errors import ConvergenceError, DegenerateGeometryError, InputError
from .rotation import DEFAULT_ORDER, check_order, rotation_angles, rotation_matrix


def as_points(values, dim: int, what: str = "points") -> np.ndarray:
    """Validate an (n, dim) array of finite coordinates (a single point is promoted)."""
    arr = np.asarray(values, dtype=float)
    if arr.ndim == 1 and arr.shape[0] == dim:
        arr = arr[None, :]
    if arr.ndim != 2 or arr.shape[1] != dim:
        raise InputError(f"{what}: expected an array of shape (n, {dim}), got {np.shape(values)}")
    if not np.all(np.isfinite(arr)):
        raise InputError(f"{what} contain NaN or inf")
    return arr


def as_point_pairs(first, dim_first: int, second, dim_second: int, names=("points", "points"),
                   minimum: int = 1, task: str = "this problem"):
    """Validate two arrays of corresponding points (same count, finite) and a minimum count.

    Returns the two validated arrays; the messages name both point sets and the task.
    """
    a = as_points(first, dim_first, names[0])
    b = as_points(second, dim_second, names[1])
    if len(a) != len(b):
        raise InputError(f"{len(a)} {names[0]} but {len(b)} {names[1]}: shapes must match")
    if len(a) < minimum:
        raise InputError(f"{task} needs at least {minimum} points, got {len(a)}")
    return a, b


@dataclass(frozen=True)
class InteriorOrientation:
    """Interior orientation (§1.2): focal length f, principal point (x₀, y₀), Brown coefficients.

    k1, k2, k3 (mm⁻², mm⁻⁴, mm⁻⁶) are radial, p1, p2 (mm⁻¹) decentering, in the sense of (1.2.2):
    the corrections are added to measured coordinates.
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
        values = [self.f, self.x0, self.y0, self.k1, self.k2, self.k3, self.p1, self.p2]
        if not np.all(np.isfinite(values)):
            raise InputError("interior orientation contains NaN or inf")
        if self.f <= 0:
            raise InputError(f"focal length must be positive, got f = {self.f}")

    @property
    def has_distortion(self) -> bool:
        return any((self.k1, self.k2, self.k3, self.p1, self.p2))


def distortion_correction(xy, io: InteriorOrientation):
    """Corrections (d_x, d_y) of (1.2.2) for measured image coordinates ``xy`` (mm).

    With x̄ = x − x₀, ȳ = y − y₀, r² = x̄² + ȳ²:
    d_x = x̄(k₁r² + k₂r⁴ + k₃r⁶) + (r² + 2x̄²)p₁ + 2x̄ȳ p₂,
    d_y = ȳ(k₁r² + k₂r⁴ + k₃r⁶) + 2x̄ȳ p₁ + (r² + 2ȳ²)p₂.
    """
    xy = as_points(xy, 2, "image coordinates")
    xb, yb = xy[:, 0] - io.x0, xy[:, 1] - io.y0
    r2 = xb * xb + yb * yb
    radial = io.k1 * r2 + io.k2 * r2 ** 2 + io.k3 * r2 ** 3
    dx = xb * radial + (r2 + 2 * xb * xb) * io.p1 + 2 * xb * yb * io.p2
    dy = yb * radial + 2 * xb * yb * io.p1 + (r2 + 2 * yb * yb) * io.p2
    return np.column_stack([dx, dy])


def correct_distortion(xy, io: InteriorOrientation) -> np.ndarray:
    """Measured → ideal image coordinates: x + d_x, y + d_y (1.2.3)."""
    xy = as_points(xy, 2, "image coordinates")
    return xy + distortion_correction(xy, io)


def apply_distortion(xy_ideal, io: InteriorOrientation, tol: float = 1e-12, max_iter: int = 30) -> np.ndarray:
    """Ideal → measured coordinates: solve x + d_x(x, y) = x_ideal, y + d_y(x, y) = y_ideal.

    The inverse of :func:`correct_distortion`, needed to simulate what a distorting camera
    records. Newton's method with the 2×2 Jacobian of (1.2.2) derived by sympy
    (:func:`photolib.derivations.distortion_model`). Where the correction folds the image over
    (its Jacobian determinant is not positive) no measured point maps to the ideal one and
    :class:`DegenerateGeometryError` is raised.
    """
    from . import derivations

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
    """Ray vectors r = (x − x₀ + d_x, y − y₀ + d_y, −f) of (1.2.3), (1.2.1) without distortion."""
    xy = as_points(xy, 2, "image coordinates")
    if distortion and io.has_distortion:
        xy = correct_distortion(xy, io)
    return np.column_stack([xy[:, 0] - io.x0, xy[:, 1] - io.y0, np.full(len(xy), -io.f)])


@dataclass(frozen=True)
class ExteriorOrientation:
    """Exterior orientation (§1.3): projection centre (X_S, Y_S, Z_S) in m, angles ω, α, κ in radians.

    ``order`` names the rotation sequence the angles belong to: ``"kaw"`` (1.3.5, the book's
    examples) or ``"wak"`` (1.3.2).
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
        check_order(self.order)
        if not np.all(np.isfinite(self.vector)):
            raise InputError("exterior orientation contains NaN or inf")

    @classmethod
    def from_degrees(cls, Xs, Ys, Zs, omega=0.0, alpha=0.0, kappa=0.0, order=DEFAULT_ORDER):
        """Build from angles given in degrees."""
        w, a, k = np.radians([omega, alpha, kappa])
        return cls(Xs, Ys, Zs, float(w), float(a), float(k), order)

    @classmethod
    def from_vector(cls, vector, order=DEFAULT_ORDER):
        """Build from (X_S, Y_S, Z_S, ω, α, κ)."""
        v = np.asarray(vector, dtype=float)
        if v.shape != (6,):
            raise InputError(f"exterior orientation vector must have 6 elements, got {v.shape}")
        return cls(*map(float, v), order=order)

    @classmethod
    def from_matrix(cls, center, A, order=DEFAULT_ORDER):
        """Build from a projection centre and a rotation matrix A (camera → object)."""
        w, a, k = rotation_angles(A, order)
        c = np.asarray(center, dtype=float)
        return cls(float(c[0]), float(c[1]), float(c[2]), w, a, k, order)

    @property
    def vector(self) -> np.ndarray:
        return np.array([self.Xs, self.Ys, self.Zs, self.omega, self.alpha, self.kappa])

    @property
    def center(self) -> np.ndarray:
        return np.array([self.Xs, self.Ys, self.Zs])

    @property
    def angles_degrees(self) -> np.ndarray:
        return np.degrees([self.omega, self.alpha, self.kappa])

    @property
    def matrix(self) -> np.ndarray:
        """A (camera → object) of the named sequence."""
        return rotation_matrix(self.omega, self.alpha, self.kappa, self.order)

    def with_order(self, order: str) -> "ExteriorOrientation":
        """The same orientation with its angles expressed in another rotation sequence."""
        w, a, k = rotation_angles(self.matrix, order)
        return replace(self, omega=w, alpha=a, kappa=k, order=order)
