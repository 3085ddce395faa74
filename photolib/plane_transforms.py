"""Plane (2-D) transformations — Hanzl, *Fotogrammetrie, Modul 01*, §2.5 (Rovinné transformace).

Hanzl lists six transformations between two planes (e.g. scanner coordinates x̄, ȳ → image
coordinates x, y, or image → object plane), with their number of parameters:

=========== ============ ====== ==============================================================
kind        Hanzl        params form (seed lines)
=========== ============ ====== ==============================================================
congruent   shodnostní   3      rotation α and shifts t_x, t_y (lines 265–269)
similarity  podobnostní  4      q·rotation and shifts; here a = q cos α, b = q sin α (271–273)
affine      afinní       6      a₁₁ … a₂₃; q_x, q_y, α, δα, t_x, t_y (275–285)
projective  kolineární   8      (2.5): a₁, a₂, a₃, b₁, b₂, b₃, c₁, c₂ (287–289)
bilinear    bilineární   8      a₁ … a₄, b₁ … b₄ with the term x̄ȳ (291–293)
polynomial  polynomická  12     2nd degree: a₁ … a₆, b₁ … b₆ (x̄², ȳ², x̄ȳ) (295–297)
=========== ============ ====== ==============================================================

The minimum number of identical points is the number of parameters divided by two (each point
gives two equations, line 301), rounded up: 2, 2, 3, 4, 4, 6 (:data:`MIN_POINTS`). With more
points the parameters are adjusted by least squares through the one engine :mod:`photolib.lsq`:
the linear kinds by :func:`photolib.lsq.solve_normal_equations` (the affine one through
:func:`photolib.interior.fit_affine`), the congruent one by :func:`photolib.lsq.gauss_newton`
with the sympy Jacobian of :func:`photolib.derivations.plane.congruent_model`, the projective one through
:func:`photolib.projective.homography_lsq`.

Related sections of the Russian textbook (Chibunichev 2022): §1.11 interior orientation (the
affine transformation (1.11.1) and the rotation-plus-two-scales form (1.11.6)), §1.7 eq. (1.7.5)
and §4.1 (the plane-to-plane projective transformation), §1.8 (the least-squares scheme).

Conventions
-----------
* Residuals are model minus observed, V = f(x̄, ȳ) − (x, y), one row per point, in the units of
  the destination coordinates; σ₀ is μ of (1.8.9), √(VᵀPV / (2n − u)), NaN without redundancy.
* The affine decomposition (Hanzl line 285) uses atan2 for the two angles, so it holds in every
  quadrant: α = atan2(a₂₁, a₁₁), α + δα = atan2(−a₁₂, a₂₂), δα wrapped to (−π, π]. Equivalently
  A = R(α)·[[1, −sin δα], [0, cos δα]]·diag(q_x, q_y) (rotation · shear · scales).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .camera import _scalar, as_point_pairs
from .derivations import plane as plane_models
from .errors import DegenerateGeometryError, InputError
from .lsq import accuracy, gauss_newton, point_weights, solve_normal_equations

__all__ = ["KINDS", "N_PARAMETERS", "MIN_POINTS", "PARAMETER_NAMES", "PlaneTransform", "AffineDecomposition",
           "fit_plane_transform", "affine_decomposition", "affine_from_decomposition"]

KINDS = ("congruent", "similarity", "affine", "projective", "bilinear", "polynomial")
PARAMETER_NAMES = {
    "congruent": ("alpha", "tx", "ty"),
    "similarity": ("a", "b", "tx", "ty"),
    "affine": ("a11", "a12", "a13", "a21", "a22", "a23"),
    "projective": ("a1", "a2", "a3", "b1", "b2", "b3", "c1", "c2"),
    "bilinear": ("a1", "a2", "a3", "a4", "b1", "b2", "b3", "b4"),
    "polynomial": ("a1", "a2", "a3", "a4", "a5", "a6", "b1", "b2", "b3", "b4", "b5", "b6"),
}
"""Names of the parameters of each kind, in the order of :attr:`PlaneTransform.parameters`."""
N_PARAMETERS = {k: len(v) for k, v in PARAMETER_NAMES.items()}
"""Number of parameters of each kind (Hanzl §2.5): 3, 4, 6, 8, 8, 12."""
MIN_POINTS = {k: -(-n // 2) for k, n in N_PARAMETERS.items()}
"""Minimum number of identical points, parameters / 2 rounded up (Hanzl §2.5, line 301)."""
_ALIASES = {"collinear": "projective", "kolinearni": "projective", "polynomial2": "polynomial"}
_AFFINE_LIKE = ("congruent", "similarity", "affine")


def _kind(kind) -> str:
    if not isinstance(kind, str):
        raise InputError(f"kind must be one of {', '.join(KINDS)}, got {kind!r}")
    k = _ALIASES.get(kind.strip().lower(), kind.strip().lower())
    if k not in KINDS:
        raise InputError(f"unknown plane transformation {kind!r}; choose one of {', '.join(KINDS)}")
    return k


def _points(xy, what: str) -> np.ndarray:
    try:
        a = np.asarray(xy, dtype=float)
    except (TypeError, ValueError) as exc:
        raise InputError(f"{what} must be numbers: {exc}") from None
    if a.ndim == 1:
        a = a.reshape(1, -1)
    if a.ndim != 2 or a.shape[1] != 2 or len(a) == 0:
        raise InputError(f"{what} must be (n, 2) coordinates, got shape {np.shape(xy)}")
    if not np.all(np.isfinite(a)):
        raise InputError(f"{what} contain NaN or inf")
    return a


def _matrix_2x3(p: np.ndarray, kind: str) -> np.ndarray:
    if kind == "congruent":
        c, s = math.cos(p[0]), math.sin(p[0])
        return np.array([[c, -s, p[1]], [s, c, p[2]]])
    if kind == "similarity":
        a, b = p[0], p[1]
        return np.array([[a, -b, p[2]], [b, a, p[3]]])
    return np.asarray(p, dtype=float).reshape(2, 3)


def _monomials(src: np.ndarray, kind: str) -> np.ndarray:
    x, y = src[:, 0], src[:, 1]
    one = np.ones_like(x)
    if kind == "bilinear":
        return np.column_stack([one, x, y, x * y])
    return np.column_stack([one, x, y, x * x, y * y, x * y])          # polynomial


def _evaluate(kind: str, p: np.ndarray, src: np.ndarray) -> np.ndarray:
    if kind in _AFFINE_LIKE:
        M = _matrix_2x3(p, kind)
        return src @ M[:, :2].T + M[:, 2]
    if kind == "projective":
        w = p[6] * src[:, 0] + p[7] * src[:, 1] + 1.0
        if np.any(np.abs(w) < 1e-15 * max(1.0, float(np.abs(src).max()))):
            raise DegenerateGeometryError("a point lies on the vanishing line c₁x + c₂y + 1 = 0 "
                                          "and is mapped to infinity")
        return np.column_stack([(p[0] * src[:, 0] + p[1] * src[:, 1] + p[2]) / w,
                                (p[3] * src[:, 0] + p[4] * src[:, 1] + p[5]) / w])
    m = _monomials(src, kind)
    h = len(p) // 2
    return np.column_stack([m @ p[:h], m @ p[h:]])


@dataclass(frozen=True, eq=False)
class AffineDecomposition:
    """The geometric parameters of an affine transformation (Hanzl §2.5, lines 277 and 285).

    A = [[q_x cos α, −q_y sin(α + δα)], [q_x sin α, q_y cos(α + δα)]], t = (t_x, t_y).

    Attributes
    ----------
    q_x, q_y : float
        Scales of the two axes (positive).
    alpha : float
        Rotation α of the x axis, radians, in (−π, π].
    delta_alpha : float
        Non-orthogonality (shear) δα of the axes, radians, in (−π, π]; 0 for a similarity.
    tx, ty : float
        Shifts (a₁₃, a₂₃).

    References
    ----------
    Hanzl, §2.5, lines 275–285.

    Examples
    --------
    >>> AffineDecomposition(1.0, 1.0, 0.0, 0.0, 0.0, 0.0).q_x
    1.0
    """

    q_x: float
    q_y: float
    alpha: float
    delta_alpha: float
    tx: float = 0.0
    ty: float = 0.0

    def __post_init__(self):
        for name in ("q_x", "q_y", "alpha", "delta_alpha", "tx", "ty"):
            object.__setattr__(self, name, _scalar(getattr(self, name), name))
        if self.q_x <= 0 or self.q_y <= 0:
            raise InputError(f"the scales q_x, q_y must be positive, got {self.q_x}, {self.q_y}")

    def __repr__(self) -> str:
        return (f"AffineDecomposition(q_x={self.q_x:.10g}, q_y={self.q_y:.10g}, α={self.alpha:.10g}, "
                f"δα={self.delta_alpha:.10g}, tx={self.tx:.10g}, ty={self.ty:.10g})")


@dataclass(frozen=True, eq=False)
class PlaneTransform:
    """One plane transformation of Hanzl §2.5: its kind, parameters and (when fitted) accuracy.

    Attributes
    ----------
    kind : str
        One of :data:`KINDS`.
    parameters : ndarray
        The parameters in the order of :data:`PARAMETER_NAMES` ``[kind]`` (read-only).
    residuals : ndarray or None
        V = f(src) − dst per identical point, (n, 2), destination units.
    sigma0 : float
        σ₀ = √(VᵀPV / dof) (μ of (1.8.9)); NaN without redundancy or when not fitted.
    dof : int
        Redundancy 2n − u.
    std : ndarray or None
        m_j = σ₀√Q_jj of the parameters.
    Q : ndarray or None
        Cofactor matrix of the parameters.

    References
    ----------
    Hanzl, §2.5, lines 261–311.

    Examples
    --------
    >>> t = PlaneTransform("similarity", [2.0, 0.0, 1.0, -1.0])
    >>> t.apply([[1.0, 1.0]])
    array([[3., 1.]])
    >>> t.decomposition.q_x
    2.0
    """

    kind: str
    parameters: np.ndarray
    residuals: np.ndarray | None = None
    sigma0: float = float("nan")
    dof: int = 0
    std: np.ndarray | None = None
    Q: np.ndarray | None = None

    def __post_init__(self):
        kind = _kind(self.kind)
        object.__setattr__(self, "kind", kind)
        try:
            p = np.array(self.parameters, dtype=float).ravel()
        except (TypeError, ValueError) as exc:
            raise InputError(f"parameters must be numbers: {exc}") from None
        if p.size != N_PARAMETERS[kind]:
            raise InputError(f"a {kind} transformation has {N_PARAMETERS[kind]} parameters "
                             f"({', '.join(PARAMETER_NAMES[kind])}), got {p.size}")
        if not np.all(np.isfinite(p)):
            raise InputError("the parameters contain NaN or inf")
        p.flags.writeable = False
        object.__setattr__(self, "parameters", p)
        for name in ("residuals", "std", "Q"):
            value = getattr(self, name)
            if value is not None:
                value = np.array(value, dtype=float)
                value.flags.writeable = False
                object.__setattr__(self, name, value)

    @property
    def names(self) -> tuple:
        """Names of the parameters."""
        return PARAMETER_NAMES[self.kind]

    @property
    def params(self) -> dict:
        """The parameters by name."""
        return dict(zip(self.names, map(float, self.parameters)))

    @property
    def matrix(self) -> np.ndarray:
        """The 3×3 homogeneous matrix (congruent, similarity, affine, projective kinds).

        Raises
        ------
        InputError
            For the bilinear and polynomial kinds, which are not linear in homogeneous coordinates.
        """
        if self.kind == "projective":
            return np.append(self.parameters, 1.0).reshape(3, 3)
        if self.kind in _AFFINE_LIKE:
            return np.vstack([_matrix_2x3(self.parameters, self.kind), [0.0, 0.0, 1.0]])
        raise InputError(f"a {self.kind} transformation has no 3×3 matrix")

    @property
    def decomposition(self) -> AffineDecomposition | None:
        """q_x, q_y, α, δα, t_x, t_y (Hanzl §2.5, line 285) for the congruent, similarity, affine kinds; else None."""
        if self.kind not in _AFFINE_LIKE:
            return None
        return affine_decomposition(_matrix_2x3(self.parameters, self.kind))

    def apply(self, xy) -> np.ndarray:
        """Transform points: (x, y) = f(x̄, ȳ).

        Parameters
        ----------
        xy : (2,) or (n, 2) array
            Source coordinates x̄, ȳ.

        Returns
        -------
        ndarray
            (2,) or (n, 2) destination coordinates.

        Raises
        ------
        InputError
            Wrong shape, NaN/inf.
        DegenerateGeometryError
            Projective kind: a point on the vanishing line.

        Examples
        --------
        >>> PlaneTransform("congruent", [0.0, 1.0, 2.0]).apply([0.0, 0.0])
        array([1., 2.])
        """
        pts = _points(xy, "points")
        out = _evaluate(self.kind, self.parameters, pts)
        return out[0] if np.ndim(xy) == 1 else out

    def __repr__(self) -> str:
        body = ", ".join(f"{k}={v:.10g}" for k, v in self.params.items())
        if self.dof > 0 and np.isfinite(self.sigma0):
            body += f", σ₀={self.sigma0:.3g}, {self.dof} redundant"
        return f"PlaneTransform({self.kind}: {body})"


def _check_geometry(src: np.ndarray, kind: str):
    need = MIN_POINTS[kind]
    if len(src) < need:
        raise DegenerateGeometryError(
            f"a {kind} transformation has {N_PARAMETERS[kind]} parameters and needs at least {need} identical "
            f"points (parameters / 2, two equations per point), got {len(src)}")
    centred = src - src.mean(axis=0)
    s = np.linalg.svd(centred, compute_uv=False)
    scale = max(float(np.abs(src).max()), 1.0)
    if s[0] <= 1e-12 * scale:
        raise DegenerateGeometryError(f"all source points coincide: the {kind} transformation is not determined")
    if kind not in ("congruent", "similarity") and s[1] <= 1e-9 * s[0]:
        raise DegenerateGeometryError(f"the source points are collinear: the {kind} transformation is not determined")


def _linear_design(src: np.ndarray, kind: str) -> np.ndarray:
    n = len(src)
    if kind == "similarity":
        B = np.zeros((2 * n, 4))
        B[0::2, 0], B[0::2, 1], B[0::2, 2] = src[:, 0], -src[:, 1], 1.0
        B[1::2, 0], B[1::2, 1], B[1::2, 3] = src[:, 1], src[:, 0], 1.0
        return B
    m = _monomials(src, kind)
    h = m.shape[1]
    B = np.zeros((2 * n, 2 * h))
    B[0::2, :h] = m
    B[1::2, h:] = m
    return B


def _result(kind, x, V, Q, P, n):
    dof = 2 * n - N_PARAMETERS[kind]
    if dof > 0:
        mu, std, _ = accuracy(V, Q, P, dof)
        mu, std = float(mu), np.asarray(std, dtype=float)
    else:
        mu, std = float("nan"), np.full(N_PARAMETERS[kind], np.nan)
    return PlaneTransform(kind, x, residuals=np.asarray(V, dtype=float).reshape(n, 2), sigma0=mu, dof=dof,
                          std=std, Q=Q)


def fit_plane_transform(src, dst, kind: str = "affine", weights=None) -> PlaneTransform:
    """Fit one of Hanzl's plane transformations to identical points (least squares if redundant).

    Parameters
    ----------
    src : (n, 2) array
        Source coordinates x̄, ȳ of the identical points (e.g. measured scanner coordinates).
    dst : (n, 2) array
        Destination coordinates x, y of the same points.
    kind : str
        "congruent" (3), "similarity" (4), "affine" (6), "projective" (alias "collinear", 8),
        "bilinear" (8) or "polynomial" (2nd degree, 12).
    weights : (n,) or (n, 2) array, optional
        Weights per point or per coordinate; unit weights if omitted.

    Returns
    -------
    PlaneTransform
        Parameters, residuals V = f(src) − dst, σ₀, dof, m_j and Q.

    Raises
    ------
    InputError
        Unknown kind, bad shapes, different counts, NaN/inf, bad weights.
    DegenerateGeometryError
        Fewer than :data:`MIN_POINTS` ``[kind]`` points (parameters / 2), coincident points,
        collinear points (all kinds but congruent and similarity), or any other configuration
        that leaves the parameters undetermined (e.g. six points on a conic for the polynomial).
    ConvergenceError
        Congruent or projective kind: the iteration does not converge.

    Notes
    -----
    Linear kinds: one step of :func:`photolib.lsq.solve_normal_equations` (the affine kind through
    :func:`photolib.interior.fit_affine`). Congruent: :func:`photolib.lsq.gauss_newton` with the
    Jacobian of :func:`photolib.derivations.plane.congruent_model`, started from the closed-form (Procrustes) rotation.
    Projective: :func:`photolib.projective.homography_lsq` (normalised DLT start, Gauss–Newton).

    References
    ----------
    Hanzl, §2.5, lines 261–311 (minimum points: line 301); Chibunichev (2022), §1.8, §1.11
    (1.11.1)–(1.11.2), §1.7 (1.7.5).

    Examples
    --------
    Affine transformation from three points (Hanzl, §2.5, lines 275–281):

    >>> t = fit_plane_transform([[0, 0], [10, 0], [0, 10]], [[1, 2], [21, 2], [1, 32]], "affine")
    >>> t.parameters.round(9) + 0.0
    array([2., 0., 1., 0., 3., 2.])
    >>> round(t.decomposition.q_y, 9), t.dof
    (3.0, 0)

    Minimum number of points is parameters / 2 (Hanzl, §2.5, line 301):

    >>> MIN_POINTS["projective"], MIN_POINTS["polynomial"]
    (4, 6)
    """
    kind = _kind(kind)
    src, dst = as_point_pairs(src, 2, dst, 2, ("source points", "destination points"), 1,
                              f"a {kind} transformation")
    n = len(src)
    _check_geometry(src, kind)
    P = point_weights(weights, n)
    if kind == "affine":
        from .interior import fit_affine

        t = fit_affine(src, dst, weights=P)
        # interior order a0, a1, a2, b0, b1, b2 -> Hanzl a11, a12, a13, a21, a22, a23
        order = [1, 2, 0, 4, 5, 3]
        x = np.array([t.a0, t.a1, t.a2, t.b0, t.b1, t.b2])[order]
        return _result(kind, x, t.residuals.ravel(), t.Q[np.ix_(order, order)], P, n)
    if kind == "projective":
        from .projective import homography_lsq

        r = homography_lsq(src, dst, weights=P)
        adj = r.adjustment
        return _result(kind, r.H.ravel()[:8], adj.residuals, adj.Q, P, n)
    if kind == "congruent":
        res_fn, jac_fn = plane_models.congruent_model().compile()
        ms, md = src.mean(axis=0), dst.mean(axis=0)
        cs, cd = src - ms, dst - md
        a0 = math.atan2(float(np.sum(cs[:, 0] * cd[:, 1] - cs[:, 1] * cd[:, 0])),
                        float(np.sum(cs[:, 0] * cd[:, 0] + cs[:, 1] * cd[:, 1])))
        c, s = math.cos(a0), math.sin(a0)
        x0 = [a0, md[0] - (c * ms[0] - s * ms[1]), md[1] - (s * ms[0] + c * ms[1])]
        data = (src[:, 0], src[:, 1], dst[:, 0], dst[:, 1])

        def linearize(p):
            F = res_fn(*p, *data)                      # (2, n)
            J = jac_fn(*p, *data)                      # (6, n)
            B = np.empty((2 * n, 3))
            B[0::2] = J[:3].T
            B[1::2] = J[3:].T
            return B, F.T.ravel()

        scale = max(1.0, float(np.abs(dst).max()))
        adj = gauss_newton(linearize, x0, P, tol=[1e-13, 1e-13 * scale, 1e-13 * scale],
                           names=PARAMETER_NAMES[kind])
        x = adj.x.copy()
        x[0] = math.atan2(math.sin(x[0]), math.cos(x[0]))
        return _result(kind, x, adj.residuals, adj.Q, P, n)
    B = _linear_design(src, kind)
    L = -dst.ravel()
    delta, Q = solve_normal_equations(B, L, P, PARAMETER_NAMES[kind])
    return _result(kind, delta, B @ delta + L, Q, P, n)


def _as_affine_matrix(a) -> np.ndarray:
    if isinstance(a, PlaneTransform):
        if a.kind not in _AFFINE_LIKE:
            raise InputError(f"a {a.kind} transformation has no affine decomposition")
        return _matrix_2x3(a.parameters, a.kind)
    try:
        M = np.asarray(a, dtype=float)
    except (TypeError, ValueError) as exc:
        raise InputError(f"the affine matrix must be numbers: {exc}") from None
    if M.shape == (6,):
        M = M.reshape(2, 3)
    if M.shape == (2, 2):
        M = np.column_stack([M, np.zeros(2)])
    if M.shape != (2, 3):
        raise InputError(f"expected a 2×2 matrix [a_ij], a 2×3 matrix [A | t] or a11…a23, got shape {M.shape}")
    if not np.all(np.isfinite(M)):
        raise InputError("the affine matrix contains NaN or inf")
    return M


def affine_decomposition(a) -> AffineDecomposition:
    """Scales, rotation and non-orthogonality of an affine matrix, Hanzl §2.5, line 285.

    q_x = √(a₁₁² + a₂₁²), q_y = √(a₁₂² + a₂₂²), tg α = a₂₁/a₁₁, tg(α + δα) = −a₁₂/a₂₂ (the
    angles with atan2, so that every quadrant is resolved; δα in (−π, π]).

    Parameters
    ----------
    a : (2, 2), (2, 3) or (6,) array, or PlaneTransform
        [a_ij], [A | (a₁₃, a₂₃)] or a₁₁, a₁₂, a₁₃, a₂₁, a₂₂, a₂₃; or a congruent, similarity or
        affine :class:`PlaneTransform`.

    Returns
    -------
    AffineDecomposition
        q_x, q_y, α, δα, t_x, t_y (t = 0 for a 2×2 input).

    Raises
    ------
    InputError
        Wrong shape, NaN/inf, a PlaneTransform of another kind.
    DegenerateGeometryError
        A zero column (q_x = 0 or q_y = 0): the angles are undefined.

    References
    ----------
    Hanzl, §2.5, lines 277 and 285.

    Examples
    --------
    >>> d = affine_decomposition([[2.0, 0.0], [0.0, 3.0]])
    >>> d.q_x, d.q_y, d.alpha, d.delta_alpha
    (2.0, 3.0, 0.0, 0.0)
    """
    M = _as_affine_matrix(a)
    q_x, q_y = math.hypot(M[0, 0], M[1, 0]), math.hypot(M[0, 1], M[1, 1])
    size = float(np.abs(M[:, :2]).max())
    if q_x <= 1e-14 * size or q_y <= 1e-14 * size or size == 0.0:
        raise DegenerateGeometryError("a column of the affine matrix is zero: q_x or q_y = 0, α and δα undefined")
    alpha = math.atan2(M[1, 0], M[0, 0])
    beta = math.atan2(-M[0, 1], M[1, 1])
    delta = math.remainder(beta - alpha, 2 * math.pi)
    if delta <= -math.pi:
        delta += 2 * math.pi
    return AffineDecomposition(q_x, q_y, alpha, delta, float(M[0, 2]), float(M[1, 2]))


def affine_from_decomposition(q_x, q_y, alpha, delta_alpha, tx=0.0, ty=0.0) -> np.ndarray:
    """The affine matrix [A | t] from scales, rotation and non-orthogonality, Hanzl §2.5, line 277.

    A = [[q_x cos α, −q_y sin(α + δα)], [q_x sin α, q_y cos(α + δα)]]
      = R(α)·[[1, −sin δα], [0, cos δα]]·diag(q_x, q_y).

    Parameters
    ----------
    q_x, q_y : float
        Positive scales of the axes.
    alpha, delta_alpha : float
        Rotation and non-orthogonality of the axes, radians.
    tx, ty : float, optional
        Shifts a₁₃, a₂₃.

    Returns
    -------
    (2, 3) ndarray
        [[a₁₁, a₁₂, a₁₃], [a₂₁, a₂₂, a₂₃]].

    Raises
    ------
    InputError
        Non-finite values, non-positive scales.

    References
    ----------
    Hanzl, §2.5, lines 275–277.

    Examples
    --------
    >>> affine_from_decomposition(2.0, 3.0, 0.0, 0.0, 1.0, -1.0)
    array([[ 2.,  0.,  1.],
           [ 0.,  3., -1.]])
    """
    d = AffineDecomposition(q_x, q_y, alpha, delta_alpha, tx, ty)
    b = d.alpha + d.delta_alpha
    return np.array([[d.q_x * math.cos(d.alpha), -d.q_y * math.sin(b), d.tx],
                     [d.q_x * math.sin(d.alpha), d.q_y * math.cos(b), d.ty]])
