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

Conventions are those of Chapter 1: image coordinates and f in mm, object (and model)
coordinates in m, angles in radians; the ray of an image point is (x − x₀, y − y₀, −f) (1.2.1)
and A maps camera → object. Every rotation is built with an explicit sequence ``order``
(``"kaw"`` = (1.3.5), the book's examples; ``"wak"`` = (1.3.2)). All partial derivatives come from
the sympy models in :mod:`photolib.derivations`; all adjustments are solved by :mod:`photolib.lsq`.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from . import derivations
from .camera import ExteriorOrientation, InteriorOrientation, as_points, correct_distortion, image_vector
from .errors import DegenerateGeometryError, InputError
from .lsq import Adjustment, gauss_newton
from .rotation import DEFAULT_ORDER, check_order, rotation_angles, rotation_matrix

RHO_SECONDS = 180 * 3600 / np.pi
"""ρ″ = 206 264.8″ per radian (the book rounds it to 200 000″ in §2.1)."""

_PARALLEL = 1e-10   # sin of the angle between two rays below which they count as parallel


# --- §2.1 stereoscopic vision --------------------------------------------------------------------
def convergence_angle(b, L):
    """γ_F = b/L (2.1.1): convergence angle (rad) of the eye base b at distance L (same units)."""
    return np.asarray(b, dtype=float) / np.asarray(L, dtype=float)


def depth_change(b, L, d_gamma):
    """ΔL = −L²Δγ/b (2.1.3): change of distance for a change Δγ (rad) of the parallactic angle."""
    return -np.asarray(L, dtype=float) ** 2 * np.asarray(d_gamma, dtype=float) / b


def stereo_vision_radius(b, gamma_min_arcsec=30.0, rho=RHO_SECONDS, B=None, V=1.0):
    """Radius of stereo vision R = b·ρ″/γ_min (from (2.1.1) with γ = γ_min), §2.1.

    ``b`` eye base (result in the same unit), ``gamma_min_arcsec`` the stereo acuity in
    arcseconds (30″ of the first kind). With an instrument of base ``B`` and magnification
    ``V`` the radius grows by the plasticity coefficient ω = BV/b. The book evaluates
    R = 65 mm × 200 000″/30″ and prints 430 m: it rounds ρ″ to 200 000″ (pass ``rho=2e5``);
    with ρ″ = 206 264.8″ the radius is 447 m.
    """
    R = b * rho / gamma_min_arcsec
    if B is not None:
        R = R * plasticity_coefficient(b, B, V)
    return R


def plasticity_coefficient(b, B, V=1.0):
    """ω = BV/b (§2.1): factor by which an instrument of base B and magnification V extends R."""
    return B * V / b


# --- §2.3 parallaxes -------------------------------------------------------------------------------
def parallaxes(xy1, xy2):
    """x-parallax p = x₁ − x₂ and y-parallax q = y₁ − y₂ of corresponding points (§2.3)."""
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
    """(X', Y', Z')ᵀ = A(x − x₀, y − y₀, −f)ᵀ of (2.4.4): image rays in the object frame, one row per point."""
    return image_vector(xy, io, distortion) @ eo.matrix.T


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

    ``B`` is the base (2.4.9), a 3-vector or one per point; ``r1``, ``r2`` are (n, 3) rays.
    Parallel rays raise :class:`DegenerateGeometryError`.
    """
    r1 = as_points(r1, 3, "rays of image 1")
    r2 = as_points(r2, 3, "rays of image 2")
    _same_length(r1, r2, "rays")
    B = np.broadcast_to(np.asarray(B, dtype=float), r1.shape)
    if not np.all(np.isfinite(B)):
        raise InputError("the base contains NaN or inf")
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

    X = X_S1 + N·X'₁ etc. (2.4.4), with the rays of (2.4.4), the base (2.4.9) and N from
    :func:`intersection_scale` (``method``/``formula`` as there). The point lies on ray 1, as
    in the book; with noisy data use :func:`intersect_rays` for the least-squares point.
    A point behind camera 1 (N ≤ 0) raises :class:`DegenerateGeometryError`.
    """
    io2 = io1 if io2 is None else io2
    xy1 = as_points(xy1, 2, "image-1 coordinates")
    xy2 = as_points(xy2, 2, "image-2 coordinates")
    _same_length(xy1, xy2)
    r1, r2 = image_rays(xy1, eo1, io1), image_rays(xy2, eo2, io2)
    B = eo2.center - eo1.center                                               # (2.4.9)
    N = intersection_scale(B, r1, r2, method=method, formula=formula)
    if np.any(N <= 0):
        raise DegenerateGeometryError(
            f"the rays of points {np.flatnonzero(N <= 0).tolist()} meet behind camera 1 (N ≤ 0)")
    return eo1.center + N[:, None] * r1                                       # (2.4.4)


@dataclass
class RayIntersection:
    """Least-squares intersection of rays: points and their a-posteriori accuracy (1.8.8)–(1.8.9)."""

    points: np.ndarray        # (n, 3) X, Y, Z
    mu: np.ndarray            # (n,) μ of each point (mm, the unit of the image residuals)
    std: np.ndarray           # (n, 3) m_X, m_Y, m_Z
    residuals: np.ndarray     # (n, n_images, 2) image residuals v_x, v_y (mm)
    iterations: np.ndarray    # (n,)


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

    Returns
    -------
    RayIntersection
        Points, μ (dof = 2·n_images − 3; NaN with dof = 0), m_X, m_Y, m_Z, image residuals.
    """
    k = len(xy_list)
    if k < 2 or len(eo_list) != k:
        raise InputError(f"intersection needs the coordinates and orientation of at least two images, "
                         f"got {k} coordinate sets and {len(eo_list)} orientations")
    if isinstance(io_list, InteriorOrientation):
        io_list = [io_list] * k
    if len(io_list) != k:
        raise InputError(f"{k} images but {len(io_list)} interior orientations")
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
    return RayIntersection(np.array(points), np.array(mus), np.array(stds), np.array(resid), np.array(iters))


# --- §2.5 the normal case ----------------------------------------------------------------------------
def normal_case_intersection(x1, y1, x2, f, B) -> np.ndarray:
    """Object coordinates in the normal case (2.5.3): X = (B/p)x₁, Y = (B/p)y₁, Z = −(B/p)f.

    All angles zero, base B along X, S₁ at the origin, x₀ = y₀ = 0; N = B/p with the
    x-parallax p = x₁ − x₂ (2.5.1). Equivalent form (2.5.4): X = −(Z/f)x₁, Y = −(Z/f)y₁.
    Returns (n, 3) in the unit of B. Zero parallax (a point at infinity) raises
    :class:`DegenerateGeometryError`.
    """
    x1, y1, x2 = np.broadcast_arrays(*(np.atleast_1d(np.asarray(v, dtype=float)) for v in (x1, y1, x2)))
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
    """φ = det[[b_x, b_y, b_z], [X'₁, Y'₁, Z'₁], [X'₂, Y'₂, Z'₂]] = b·(r₁ × r₂), (2.7.1)–(2.7.3).

    Zero when the base and both rays are coplanar. ``base`` a 3-vector, ``r1``, ``r2`` (n, 3).
    """
    r1 = as_points(r1, 3, "rays of image 1")
    r2 = as_points(r2, 3, "rays of image 2")
    return np.cross(r1, r2) @ np.asarray(base, dtype=float)


def y_parallax(base, r1, r2, f) -> np.ndarray:
    """Residual y-parallax q = −f/(b Z'₁ Z'₂)·det[[1, b_y, b_z], r₁', r₂'] (2.8.2), b = √(1 + b_y² + b_z²).

    ``base`` = (1, b_y, b_z). For b_y = b_z = 0 this is exactly y₁ⁿ − y₂ⁿ, the difference of the
    ordinates of the two points in the normal case (yⁿ = −f Y'/Z'); for a tilted base it is an
    approximation.
    """
    base = np.asarray(base, dtype=float)
    r1 = as_points(r1, 3, "rays of image 1")
    r2 = as_points(r2, 3, "rays of image 2")
    b = np.linalg.norm(base) / abs(base[0])
    return -f / (b * r1[:, 2] * r2[:, 2]) * coplanarity(base / base[0], r1, r2)


@dataclass
class RelativeOrientation:
    """Elements of relative orientation of a pair (§2.7) and the accuracy of their adjustment (§2.8).

    All eight parameters of (2.7.3) are given; the three that the system fixes are 0. Angles
    in radians, of the rotation sequence ``order``. ``adjustment`` holds μ (in mm², the unit of
    φ), Q, m_j and the correlations r_ij of the five elements, in the order of :data:`RO_NAMES`.
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
    adjustment: Adjustment = field(repr=False)

    @property
    def names(self) -> tuple:
        return RO_NAMES[self.system]

    @property
    def elements(self) -> dict:
        """The five elements of the system by name."""
        return {name: getattr(self, name) for name in self.names}

    @property
    def base(self) -> np.ndarray:
        """Direction (1, b_y, b_z) of the base in the model frame."""
        return np.array([1.0, self.b_y, self.b_z])

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
        """m_j (1.8.8) of the five elements by name."""
        return dict(zip(self.names, self.adjustment.std))


def _check_spread(xy, what):
    """Raise if the points are (numerically) on one line."""
    centred = xy - xy.mean(axis=0)
    s = np.linalg.svd(centred, compute_uv=False)
    if s[0] == 0 or s[-1] < 1e-9 * s[0]:
        raise DegenerateGeometryError(f"{what} lie on one line; the problem is singular")


def relative_orientation(xy1, xy2, io1: InteriorOrientation, io2: InteriorOrientation | None = None,
                         system: str = "dependent", order: str = DEFAULT_ORDER, initial=None,
                         weights=None, tol: float = 1e-12, max_iter: int = 50,
                         jacobian: str = "derived") -> RelativeOrientation:
    """Relative orientation of a pair by the coplanarity condition, §2.7–§2.8.

    Each pair of corresponding points gives one condition φ = 0 (2.7.3); linearised, it is the
    correction equation (2.8.1) a₁δ₁ + … + a₅δ₅ + l = v with l = φ at the approximation and the
    coefficients derived by sympy (:func:`photolib.derivations.coplanarity_model`). The system
    is iterated by least squares (§1.8) until the corrections vanish.

    Parameters
    ----------
    xy1, xy2 : (n, 2) arrays
        Measured coordinates of n ≥ 5 corresponding points (mm).
    io1, io2 : InteriorOrientation
        Interior orientation of the two images (``io2`` defaults to ``io1``).
    system : {"dependent", "independent"}
        ``"dependent"``: b_y, b_z, ω'₂, α'₂, κ'₂ with A'₁ = E (2.7.5); the model frame is parallel
        to the camera frame of image 1. ``"independent"``: α'₁, κ'₁, ω'₂, α'₂, κ'₂ with
        b_y = b_z = ω'₁ = 0 (2.7.4); the model X axis is along the base.
    order : {"kaw", "wak"}
        Rotation sequence of the primed angles.
    initial : array of 5, optional
        Approximate values of the elements (zeros, as in the book, by default).
    weights : array (n,), optional
        Weights of the conditions; unit weights (the book) by default.
    jacobian : {"derived", "printed"}
        ``"derived"`` (default): a₁…a₅ derived by sympy. ``"printed"``: the book's §2.8
        partials (:func:`photolib.derivations.printed_coplanarity_partials`; κ–α–ω only), which
        equal ∂A/∂θ·(x, y, **+f**): a sign error on every f-term. The iteration still converges
        (slowly, to nearly the same elements) but m_j and r_ij are wrong — this mode exists only
        to reproduce the published accuracy of the worked example that closes §2.12.

    Returns
    -------
    RelativeOrientation
        The elements, residual y-parallaxes q (2.8.2) (computed with f₁) and the adjustment
        (μ, m_j, r_ij). With the correct (derived) Jacobian m_j and r_ij differ from the book's
        §2.8 tables, which were computed with the printed partials (sign error on the f-terms, see
        :func:`photolib.derivations.printed_relative_orientation_partials`).
    """
    check_order(order)
    if system not in RO_NAMES:
        raise InputError(f"unknown system {system!r}; use 'dependent' (2.7.5) or 'independent' (2.7.4)")
    io2 = io1 if io2 is None else io2
    xy1 = as_points(xy1, 2, "image-1 coordinates")
    xy2 = as_points(xy2, 2, "image-2 coordinates")
    _same_length(xy1, xy2)
    if len(xy1) < 5:
        raise InputError(f"relative orientation needs at least 5 corresponding points, got {len(xy1)}")
    _check_spread(xy1, "the points of image 1")
    _check_spread(xy2, "the points of image 2")
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

    x0 = np.zeros(5) if initial is None else np.asarray(initial, dtype=float)
    if x0.shape != (5,):
        raise InputError(f"initial values: expected 5 elements, got shape {x0.shape}")
    adj = gauss_newton(linearize, x0, weights, tol=tol, max_iter=max_iter, names=RO_NAMES[system])
    values = dict.fromkeys(_ALL_RO, 0.0)
    values.update(zip(RO_NAMES[system], map(float, adj.x)))
    A1 = rotation_matrix(values["omega1"], values["alpha1"], values["kappa1"], order)
    A2 = rotation_matrix(values["omega2"], values["alpha2"], values["kappa2"], order)
    q = y_parallax([1.0, values["b_y"], values["b_z"]], r1 @ A1.T, r2 @ A2.T, io1.f)   # (2.8.2)
    return RelativeOrientation(system, order, **values, q=q, adjustment=adj)


# --- §2.9 model construction --------------------------------------------------------------------------
@dataclass
class StereoModel:
    """A photogrammetric model (§2.9): model coordinates of the points and the orientation of both images in it."""

    points: np.ndarray                  # (n, 3) X_M, Y_M, Z_M
    eo1: ExteriorOrientation            # image 1 in the model frame (S₁ at the origin)
    eo2: ExteriorOrientation            # image 2: S₂ = (B_X, B_X b_y, B_X b_z)
    relative: RelativeOrientation = field(repr=False)


def build_model(xy1, xy2, ro: RelativeOrientation, io1: InteriorOrientation,
                io2: InteriorOrientation | None = None, *, base_length: float = 1.0,
                method: str = "closest", formula: int | None = None) -> StereoModel:
    """Model coordinates by forward intersection in the model frame, §2.9.

    S₁ = (0, 0, 0); the base component B_X (``base_length``, arbitrary and non-zero, often
    b·m) fixes the model scale; B_Y = B_X b_y, B_Z = B_X b_z; the image angles are the angles
    of relative orientation (ωᵢ = ω'ᵢ, αᵢ = α'ᵢ, κᵢ = κ'ᵢ). The points follow from (2.4.4) with
    N of :func:`intersection_scale` (``method``, ``formula``).
    """
    if not np.isfinite(base_length) or base_length == 0:
        raise InputError("the base component B_X must be finite and non-zero")
    io2 = io1 if io2 is None else io2
    eo1 = ExteriorOrientation(0.0, 0.0, 0.0, ro.omega1, ro.alpha1, ro.kappa1, ro.order)
    S2 = base_length * ro.base
    eo2 = ExteriorOrientation(*map(float, S2), ro.omega2, ro.alpha2, ro.kappa2, ro.order)
    points = forward_intersection(xy1, xy2, eo1, eo2, io1, io2, method=method, formula=formula)
    return StereoModel(points, eo1, eo2, ro)


# --- §2.10–§2.11 exterior orientation of the model -------------------------------------------------------
SIMILARITY_NAMES = ("X0", "Y0", "Z0", "omega", "alpha", "kappa", "t")


@dataclass
class SimilarityTransform:
    """Seven elements of exterior orientation of a model (§2.10): R = R₀ + t·A_M·R_M (2.10.4)."""

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

    @property
    def vector(self) -> np.ndarray:
        return np.array([self.X0, self.Y0, self.Z0, self.omega, self.alpha, self.kappa, self.t])

    @property
    def shift(self) -> np.ndarray:
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

    @classmethod
    def from_matrix(cls, shift, A, t, order=DEFAULT_ORDER):
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
    uses it as its start.

    References
    ----------
    S. Umeyama, "Least-squares estimation of transformation parameters between two point
    patterns", IEEE TPAMI 13(4), 1991, 376–380.
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

    tol_v = np.array([tol, tol, tol, tol * 1e-2, tol * 1e-2, tol * 1e-2, tol * 1e-2])
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

    S_i = R₀ + t·A_M·S_Mi (2.12.1) and A_i = A_M·A'_i (2.12.2); the angles are extracted in
    ``order`` (default: the transform's; the book's text uses (1.3.3), i.e. ``"wak"``). The chain
    works on matrices, so the model's and the images' rotation sequences need not agree.
    ``product="image-first"`` computes A_i = A'_i·A_M instead — wrong (A'_i maps image → model
    and A_M model → object, so A_M must be applied last), but it is what the book's program
    evidently did in the worked example after §2.12; it exists only to reproduce that table.
    Returns (eo1, eo2).
    """
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
@dataclass
class DoubleResection:
    """Every intermediate result of the double resection of §2.6 (steps 2–5; step 1, interior
    orientation, is done by the caller, e.g. with :mod:`photolib.interior`)."""

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


def double_resection(xy1, xy2, io1: InteriorOrientation, control_points, io2: InteriorOrientation | None = None,
                     *, components=None, system: str = "dependent", order: str = DEFAULT_ORDER,
                     base_length: float = 1.0, ro_weights=None, control_weights=None) -> DoubleResection:
    """Object coordinates from a stereo pair by double resection, §2.6, in one call.

    Chains relative orientation (:func:`relative_orientation`), model construction
    (:func:`build_model`), exterior orientation of the model from control points
    (:func:`absolute_orientation`), the transformation of every model point into the object
    system (2.10.4) and the exterior orientation of both images (:func:`image_orientation_from_model`).

    ``control_points`` is an (n, 3) array aligned with the image points, NaN for points that are
    not control (or for the unknown components of planimetric or height control; ``components``
    may give the mask explicitly). At least five points for step 2 and control enough for the
    seven elements of step 4 (three non-collinear full points, or the §2.11 alternatives).
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
    """Photo base at image scale b = l_x(100% − P_x)/100% (§2.13), l_x the frame side along the flight."""
    if not 0 <= overlap_percent < 100:
        raise InputError(f"forward overlap must be in [0, 100) %, got {overlap_percent}")
    return frame_length * (100.0 - overlap_percent) / 100.0


def normal_case_accuracy(H, f, b, m_x, m_y, m_p, x=0.0, y=0.0, approximate: bool = False):
    """m_X, m_Y, m_Z of a point from a normal-case pair (2.13.1)–(2.13.3).

    m_Z = (H/b)m_p; m_X = √((x/f·m_Z)² + (H/f·m_x)²) ≈ (H/f)m_x; m_Y likewise with y, m_y.
    H is the flying height (the |Z| of (2.5.4)); f, b, x, y, m_x, m_y, m_p in one image unit
    (mm); the result is in the unit of H. ``approximate=True`` drops the x, y terms as the
    book's numerical example does.
    """
    H, f, b = (np.asarray(v, dtype=float) for v in (H, f, b))
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
