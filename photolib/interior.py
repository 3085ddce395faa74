"""Interior orientation of scanned images — Chapter 1, §1.11 (Внутреннее ориентирование снимка).

A film photograph digitised on a scanner is measured in the scanner ("measuring") system
o_c x̄ ȳ. The image system of the camera, fixed by the fiducial marks, differs from it by a
shift, a rotation, film shrinkage (different along x and y) and a slight non-orthogonality.
Interior orientation finds the transformation from the fiducials, in one of two ways:

* **calibrated fiducial coordinates known** — the 2-D affine transformation (1.11.1), fitted by
  least squares from ≥ 3 non-collinear fiducials (1.11.2): :func:`fit_affine`,
  :func:`apply_affine`, :func:`invert_affine` (1.11.3)–(1.11.4); pixel coordinates by (1.11.5)
  (:func:`photolib.digital.pixel_to_physical`);
* **only the calibrated distances L_x, L_y known** — a rotation plus one scale per axis (1.11.6),
  its parameters from four side fiducials (1.11.7)–(1.11.9): :func:`fiducial_similarity`,
  :func:`similarity_forward`, :func:`similarity_inverse` (1.11.10).

Notes on the printed formulas
-----------------------------
* (1.11.6) lost the coefficients a₂ and a₁ of the (ȳ − b₀) terms in the OCR; the form used here
  is x = k_x[a₁(x̄ − a₀) + a₂(ȳ − b₀)], y = k_y[−a₂(x̄ − a₀) + a₁(ȳ − b₀)], a₁ = cos φ, a₂ = sin φ.
* (1.11.10) as printed is the inverse of (1.11.6) only when k_x = k_y; the exact inverse divides
  the x term by k_x and the y term by k_y before rotating back. ``similarity_inverse(exact=False)``
  gives the printed form.
* (1.11.7) uses slopes; the line through marks 3–4 is nearly vertical in the scanner system
  (c₂ → ∞), so the intersection is computed with a 2×2 solve instead.

Marks are numbered as in Fig. 1.25: 1 and 2 on the x axis (2 in the +x direction), 3 and 4 on the
y axis (3 in the +y direction).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .camera import _scalar, as_points
from .errors import DegenerateGeometryError, InputError
from .lsq import accuracy, solve_normal_equations
from .rotation import _numbers

__all__ = ["AffineTransform", "fit_affine", "apply_affine", "invert_affine", "FiducialSimilarity",
           "fiducial_similarity", "similarity_forward", "similarity_inverse", "AFFINE_NAMES"]

AFFINE_NAMES = ("a0", "a1", "a2", "b0", "b1", "b2")


@dataclass(repr=False)
class AffineTransform:
    """Parameters of (1.11.1), x = a0 + a1·x̄ + a2·ȳ, y = b0 + b1·x̄ + b2·ȳ, with their accuracy.

    Attributes
    ----------
    a0, a1, a2, b0, b1, b2 : float
        The six parameters (a0, b0 in the unit of the calibrated coordinates).
    mu : float
        μ of (1.8.9) in the unit of the calibrated coordinates (NaN with no redundancy).
    std : dict
        m_j of (1.8.8) per parameter.
    residuals : ndarray or None
        ϑ_x, ϑ_y of (1.11.2) per fiducial, (n, 2).
    dof : int
        Redundancy 2n − 6.
    Q : ndarray or None
        The cofactor matrix of the parameters.

    References
    ----------
    Chibunichev (2022), §1.11, eqs. (1.11.1)–(1.11.4).

    Examples
    --------
    >>> AffineTransform(1.0, 1.0, 0.0, 2.0, 0.0, 1.0)
    AffineTransform(a0=1, a1=1, a2=0, b0=2, b1=0, b2=1)
    """

    a0: float
    a1: float
    a2: float
    b0: float
    b1: float
    b2: float
    mu: float = float("nan")
    std: dict = field(default_factory=dict)
    residuals: np.ndarray | None = None
    dof: int = 0
    Q: np.ndarray | None = None

    def __post_init__(self):
        for k in AFFINE_NAMES:
            _scalar(getattr(self, k), f"affine parameter {k}")

    def __repr__(self) -> str:
        body = ", ".join(f"{k}={float(getattr(self, k)):.10g}" for k in AFFINE_NAMES)
        if self.dof > 0 and np.isfinite(self.mu):
            body += f", μ={float(self.mu):.3g}, {self.dof} redundant"
        return f"AffineTransform({body})"

    @property
    def params(self) -> dict:
        """The six parameters by name."""
        return {k: getattr(self, k) for k in AFFINE_NAMES}

    @property
    def P(self) -> np.ndarray:
        """The matrix P = [[a1, a2], [b1, b2]] of (1.11.1)."""
        return np.array([[self.a1, self.a2], [self.b1, self.b2]])

    @property
    def P_inv(self) -> np.ndarray:
        """P⁻¹ = [[A1, A2], [B1, B2]] of (1.11.3)."""
        det = np.linalg.det(self.P)
        if abs(det) < 1e-15 * max(1.0, np.abs(self.P).max() ** 2):
            raise DegenerateGeometryError("the affine matrix P is singular and has no inverse")
        return np.linalg.inv(self.P)


def _as_affine(params) -> AffineTransform:
    if isinstance(params, AffineTransform):
        return params
    if isinstance(params, dict):
        missing = [k for k in AFFINE_NAMES if k not in params]
        if missing:
            raise InputError(f"affine parameters lack {', '.join(missing)}")
        values = [params[k] for k in AFFINE_NAMES]
    else:
        values = list(_numbers(params, "affine parameters").ravel())
        if len(values) != 6:
            raise InputError(f"expected 6 affine parameters a0, a1, a2, b0, b1, b2, got {len(values)}")
    values = [_scalar(v, f"affine parameter {k}") for k, v in zip(AFFINE_NAMES, values)]
    return AffineTransform(*values)


def _check_spread(pts: np.ndarray, what: str, need: int):
    """Raise if the points are fewer than ``need`` or (nearly) collinear / coincident."""
    if len(pts) < need:
        raise InputError(f"{what}: at least {need} fiducials are needed, got {len(pts)}")
    centred = pts - pts.mean(axis=0)
    s = np.linalg.svd(centred, compute_uv=False)
    scale = max(np.abs(pts).max(), 1.0)
    if s[0] <= 1e-12 * scale:
        raise DegenerateGeometryError(f"{what}: all fiducials coincide")
    if s[1] <= 1e-9 * s[0]:
        raise DegenerateGeometryError(f"{what}: the fiducials are collinear; the affine transformation is not determined")


def fit_affine(measured, calibrated, weights=None) -> AffineTransform:
    """Affine interior orientation by least squares, (1.11.1)–(1.11.2).

    Each fiducial gives the two correction equations (1.11.2)

        a0 + a1·x̄ + a2·ȳ − x = ϑ_x,   b0 + b1·x̄ + b2·ȳ − y = ϑ_y,

    linear in the six parameters, solved by :func:`photolib.lsq.solve_normal_equations` with
    μ and m_j by :func:`photolib.lsq.accuracy` (1.8.8)–(1.8.9).

    Parameters
    ----------
    measured : (n, 2) array
        x̄, ȳ of the fiducials in the scanner (measuring) system, n ≥ 3, not collinear.
    calibrated : (n, 2) array
        x, y of the same fiducials in the camera system, from the calibration certificate.
    weights : (2n,) array, optional
        Weights of the equations in the order x₁, y₁, x₂, y₂, …; unit weights if omitted.

    Returns
    -------
    AffineTransform

    Raises
    ------
    InputError
        Fewer than 3 fiducials, different counts, NaN/inf, bad weights.
    DegenerateGeometryError
        Coincident or collinear fiducials.

    References
    ----------
    Chibunichev (2022), §1.11, eqs. (1.11.1)–(1.11.2); §1.8, eqs. (1.8.8)–(1.8.9).

    Examples
    --------
    >>> t = fit_affine([[0, 0], [10, 0], [0, 10]], [[1, 2], [11, 2], [1, 12]])
    >>> round(t.a0, 9), round(t.a1, 9), round(t.b2, 9)
    (1.0, 1.0, 1.0)
    """
    meas = as_points(measured, 2, "measured fiducials")
    cal = as_points(calibrated, 2, "calibrated fiducials")
    if meas.shape != cal.shape:
        raise InputError(f"measured and calibrated fiducials differ in number: {len(meas)} vs {len(cal)}")
    _check_spread(meas, "measured fiducials", 3)
    n = len(meas)
    if weights is not None:
        w = _numbers(weights, "weights")
        if w.shape != (2 * n,):
            raise InputError(f"weights: one per equation expected, shape ({2 * n},), got {w.shape}")
        if np.any(w <= 0):
            raise InputError("weights must be positive")
    # B·δ + L = V with the approximation 0: L = model(0) − observed = −(x, y)
    B = np.zeros((2 * n, 6))
    B[0::2, 0], B[0::2, 1], B[0::2, 2] = 1.0, meas[:, 0], meas[:, 1]
    B[1::2, 3], B[1::2, 4], B[1::2, 5] = 1.0, meas[:, 0], meas[:, 1]
    L = -cal.ravel()
    delta, Q = solve_normal_equations(B, L, weights, AFFINE_NAMES)
    V = B @ delta + L
    P = None if weights is None else np.asarray(weights, dtype=float)
    dof = 2 * n - 6
    if dof > 0:
        mu, std, _ = accuracy(V, Q, P, dof)
    else:
        mu, std = float("nan"), np.full(6, np.nan)
    return AffineTransform(*map(float, delta), mu=float(mu), std=dict(zip(AFFINE_NAMES, map(float, std))),
                           residuals=V.reshape(n, 2), dof=dof, Q=Q)


def apply_affine(params, measured):
    """Camera coordinates from scanner coordinates, (1.11.1): (x, y) = (a0, b0) + P·(x̄, ȳ).

    Parameters
    ----------
    params : AffineTransform, dict or 6 numbers
        a0, a1, a2, b0, b1, b2.
    measured : (2,) or (n, 2) array
        Scanner coordinates x̄, ȳ.

    Returns
    -------
    ndarray
        (2,) or (n, 2) camera coordinates x, y.

    Raises
    ------
    InputError
        Missing or non-finite parameters, wrong shapes, NaN/inf.

    References
    ----------
    Chibunichev (2022), §1.11, eq. (1.11.1).

    Examples
    --------
    >>> apply_affine([1, 1, 0, 2, 0, 1], [3.0, 4.0])
    array([4., 6.])
    """
    t = _as_affine(params)
    pts = as_points(measured, 2, "measured points")
    out = np.array([t.a0, t.b0]) + pts @ t.P.T
    return out[0] if np.ndim(measured) == 1 else out


def invert_affine(params, image_xy):
    """Scanner coordinates from camera coordinates, (1.11.3)–(1.11.4).

    x̄ = A1(x − a0) + A2(y − b0), ȳ = B1(x − a0) + B2(y − b0), with [[A1, A2], [B1, B2]] = P⁻¹.

    Parameters
    ----------
    params : AffineTransform, dict or 6 numbers
        a0, a1, a2, b0, b1, b2.
    image_xy : (2,) or (n, 2) array
        Camera coordinates x, y.

    Returns
    -------
    ndarray
        (2,) or (n, 2) scanner coordinates x̄, ȳ.

    Raises
    ------
    InputError
        Missing or non-finite parameters, wrong shapes, NaN/inf.
    DegenerateGeometryError
        P is singular.

    References
    ----------
    Chibunichev (2022), §1.11, eqs. (1.11.3)–(1.11.4).

    Examples
    --------
    >>> invert_affine([1, 1, 0, 2, 0, 1], [4.0, 6.0])
    array([3., 4.])
    """
    t = _as_affine(params)
    pts = as_points(image_xy, 2, "image points")
    out = (pts - np.array([t.a0, t.b0])) @ t.P_inv.T
    return out[0] if np.ndim(image_xy) == 1 else out


@dataclass(repr=False)
class FiducialSimilarity:
    """Parameters of (1.11.6): origin (a0, b0) in the scanner system, angle φ, scales k_x, k_y.

    Parameters
    ----------
    a0, b0 : float
        Origin of the fiducial system in scanner coordinates.
    phi : float
        Rotation angle φ in radians.
    kx, ky : float
        Scales along x and y (> 0).

    References
    ----------
    Chibunichev (2022), §1.11, eqs. (1.11.6)–(1.11.10).

    Examples
    --------
    >>> FiducialSimilarity(100.0, 50.0, 0.01, 1.0, 1.0)
    FiducialSimilarity(a0=100, b0=50, phi=0.57295780°, kx=1, ky=1)
    """

    a0: float
    b0: float
    phi: float
    kx: float
    ky: float

    def __post_init__(self):
        for k in ("a0", "b0", "phi", "kx", "ky"):
            _scalar(getattr(self, k), f"similarity parameter {k}")
        if self.kx <= 0 or self.ky <= 0:
            raise InputError(f"the scales kx, ky must be positive, got {self.kx}, {self.ky}")

    def __repr__(self) -> str:
        return (f"FiducialSimilarity(a0={float(self.a0):.10g}, b0={float(self.b0):.10g}, "
                f"phi={np.degrees(float(self.phi)):.8f}°, kx={float(self.kx):.10g}, ky={float(self.ky):.10g})")

    @property
    def a1(self) -> float:
        """a1 = cos φ."""
        return float(np.cos(self.phi))

    @property
    def a2(self) -> float:
        """a2 = sin φ."""
        return float(np.sin(self.phi))


def _line_intersection(p1, p2, p3, p4):
    """Intersection of the lines p1–p2 and p4–p3 by a 2×2 solve (robust form of (1.11.7))."""
    d1, d2 = p2 - p1, p3 - p4
    M = np.column_stack([d1, -d2])                  # p1 + s·d1 = p4 + t·d2
    det = np.linalg.det(M)
    if abs(det) <= 1e-12 * np.linalg.norm(d1) * np.linalg.norm(d2):
        raise DegenerateGeometryError("the lines through fiducials 1–2 and 3–4 are parallel")
    s, _ = np.linalg.solve(M, p4 - p1)
    return p1 + s * d1


def fiducial_similarity(measured, Lx, Ly) -> FiducialSimilarity:
    """Interior orientation from four side fiducials and calibrated distances, (1.11.7)–(1.11.9).

    * origin a0, b0: intersection of the lines through marks 1–2 and 3–4 (1.11.7), computed by
      a 2×2 solve so that a vertical line 3–4 (the book's c₂ → ∞) is no problem;
    * φ: direction of 1 → 2, tan φ = (ȳ2 − ȳ1)/(x̄2 − x̄1) (1.11.8), evaluated with atan2;
    * k_x = L_x / |12|, k_y = L_y / |43| (1.11.9).

    Parameters
    ----------
    measured : (4, 2) array
        x̄, ȳ of marks 1, 2, 3, 4 in the scanner system (1, 2 on the x axis with 2 towards +x;
        3, 4 on the y axis with 3 towards +y).
    Lx, Ly : float
        Calibrated distances 1–2 and 4–3, in the unit wanted for x, y.

    Returns
    -------
    FiducialSimilarity

    Raises
    ------
    InputError
        Not 4 marks, NaN/inf, non-positive distances.
    DegenerateGeometryError
        Coincident marks or parallel lines 1–2 and 3–4.

    References
    ----------
    Chibunichev (2022), §1.11, eqs. (1.11.6)–(1.11.9).

    Examples
    --------
    >>> t = fiducial_similarity([[-106, 0], [106, 0], [0, 106], [0, -106]], 212.0, 212.0)
    >>> t.a0, t.b0, t.phi, t.kx
    (0.0, 0.0, 0.0, 1.0)
    """
    pts = as_points(measured, 2, "measured fiducials")
    if pts.shape != (4, 2):
        raise InputError(f"fiducial_similarity needs exactly 4 marks (4×2), got {pts.shape}")
    Lx, Ly = _scalar(Lx, "Lx"), _scalar(Ly, "Ly")
    if Lx <= 0 or Ly <= 0:
        raise InputError(f"calibrated distances must be positive numbers, got Lx={Lx}, Ly={Ly}")
    p1, p2, p3, p4 = pts
    len12, len43 = np.hypot(*(p2 - p1)), np.hypot(*(p3 - p4))
    scale = max(np.abs(pts).max(), 1.0)
    if len12 <= 1e-12 * scale or len43 <= 1e-12 * scale:
        raise DegenerateGeometryError("coincident fiducials: marks 1 and 2 (or 3 and 4) are at the same place")
    a0, b0 = _line_intersection(p1, p2, p3, p4)
    phi = float(np.arctan2(p2[1] - p1[1], p2[0] - p1[0]))
    return FiducialSimilarity(float(a0), float(b0), phi, float(Lx / len12), float(Ly / len43))


def _as_similarity(params) -> FiducialSimilarity:
    if isinstance(params, FiducialSimilarity):
        return params
    if isinstance(params, dict):
        missing = [k for k in ("a0", "b0", "phi", "kx", "ky") if k not in params]
        if missing:
            raise InputError(f"similarity parameters lack {', '.join(missing)}")
        return FiducialSimilarity(**{k: _scalar(params[k], f"similarity parameter {k}")
                                     for k in ("a0", "b0", "phi", "kx", "ky")})
    raise InputError("similarity parameters must be a FiducialSimilarity or a dict with a0, b0, phi, kx, ky")


def similarity_forward(params, measured):
    """Camera coordinates from scanner coordinates, (1.11.6) as reconstructed.

        x = k_x[a1(x̄ − a0) + a2(ȳ − b0)],   y = k_y[−a2(x̄ − a0) + a1(ȳ − b0)],
        a1 = cos φ, a2 = sin φ.

    (The OCR of (1.11.6) dropped the a2 and a1 in front of (ȳ − b0).)

    Parameters
    ----------
    params : FiducialSimilarity or dict
        a0, b0, phi, kx, ky.
    measured : (2,) or (n, 2) array
        Scanner coordinates x̄, ȳ.

    Returns
    -------
    ndarray
        (2,) or (n, 2) camera coordinates x, y.

    Raises
    ------
    InputError
        Bad parameters, wrong shapes, NaN/inf.

    References
    ----------
    Chibunichev (2022), §1.11, eq. (1.11.6) (reconstructed; see the module notes).

    Examples
    --------
    >>> similarity_forward(FiducialSimilarity(1.0, 2.0, 0.0, 2.0, 3.0), [2.0, 3.0])
    array([2., 3.])
    """
    t = _as_similarity(params)
    pts = as_points(measured, 2, "measured points")
    dx, dy = pts[:, 0] - t.a0, pts[:, 1] - t.b0
    out = np.column_stack([t.kx * (t.a1 * dx + t.a2 * dy), t.ky * (-t.a2 * dx + t.a1 * dy)])
    return out[0] if np.ndim(measured) == 1 else out


def similarity_inverse(params, image_xy, exact: bool = True):
    """Scanner coordinates from camera coordinates, the inverse of (1.11.6).

    ``exact=True``: x̄ = a0 + a1·x/k_x − a2·y/k_y, ȳ = b0 + a2·x/k_x + a1·y/k_y (the exact inverse).
    ``exact=False``: (1.11.10) as printed, x̄ = a0 + (a1·x − a2·y)/k_x, ȳ = b0 + (a2·x + a1·y)/k_y,
    which equals the exact inverse only when k_x = k_y; its error is
    (Δx̄, Δȳ) = a2·(1/k_y − 1/k_x)·(y, x).

    Parameters
    ----------
    params : FiducialSimilarity or dict
        a0, b0, phi, kx, ky.
    image_xy : (2,) or (n, 2) array
        Camera coordinates x, y.
    exact : bool
        The exact inverse (True) or (1.11.10) as printed (False).

    Returns
    -------
    ndarray
        (2,) or (n, 2) scanner coordinates x̄, ȳ.

    Raises
    ------
    InputError
        Bad parameters, wrong shapes, NaN/inf.

    References
    ----------
    Chibunichev (2022), §1.11, eqs. (1.11.6), (1.11.10).

    Examples
    --------
    >>> similarity_inverse(FiducialSimilarity(1.0, 2.0, 0.0, 2.0, 3.0), [2.0, 3.0])
    array([2., 3.])
    """
    t = _as_similarity(params)
    pts = as_points(image_xy, 2, "image points")
    x, y = pts[:, 0], pts[:, 1]
    if exact:
        u, v = x / t.kx, y / t.ky
        out = np.column_stack([t.a0 + t.a1 * u - t.a2 * v, t.b0 + t.a2 * u + t.a1 * v])
    else:
        out = np.column_stack([t.a0 + (t.a1 * x - t.a2 * y) / t.kx, t.b0 + (t.a2 * x + t.a1 * y) / t.ky])
    return out[0] if np.ndim(image_xy) == 1 else out
