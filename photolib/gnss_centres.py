"""Stereo model of an isolated pair whose projection centres were measured by GNSS — the GNSS
appendix of the book (after Chapter 2, §2.6–§2.11; ``chapters/appendix_gnss_centres.ipynb``).

Implements the method of N.F. Dobrynin and T.M. Pimshina, «Использование космических средств
позиционирования при обработке аэро- и космической информации» (seed
``001_723f59c162a2adba.txt``; the paper prints no year, no data set and no example). Equation
numbers (1)–(9) are the paper's:

* (6) the α–ω–χ direction cosines, A = R_Y(α)·R_X(ω)·R_Z(χ): :func:`rotation_aok`;
* (4) image-space vectors (X*, Y*, Z*): :func:`image_space_vectors`;
* (1), (2) the coplanarity condition with the base row (B_Y, B_X, B_Z): :func:`coplanarity_residuals`;
* (3) collinearity of one control point: :func:`ground_from_image`;
* (5) and (9) the correction equations, solved jointly by least squares:
  :func:`orient_pair` (the six angles α₁, ω₁, χ₁, α₂, ω₂, χ₂);
* lines 171–179 the initial χ from the direction angle of the base: :func:`initial_chi`;
* line 212 the space intersection with the three expressions of N: :func:`intersection_forms`,
  :func:`space_intersection`.

Frames. Geodetic coordinates X (north), Y (east), Z (up) form a left-handed frame. The
image-space frame S X* Y* Z* has X* ∥ Y, Y* ∥ X, Z* ∥ Z (right-handed), so a geodetic difference
(ΔX, ΔY, ΔZ) has image-frame components (ΔY, ΔX, ΔZ) (:func:`geodetic_to_image_frame`). Image
coordinates and f in mm, geodetic coordinates in m, angles in radians.

Derivatives. All partial derivatives come from the sympy models
:func:`photolib.derivations.gnss_coplanarity_model` and
:func:`photolib.derivations.gnss_collinearity_model`. The paper's printed derivatives contain
errors — ∂a₁/∂ω in (7), A = ∂X*/∂ω and B = ∂Z*/∂ω in (8), the coefficients d = ∂φ/∂α₂ and
e = ∂φ/∂ω₂ of (5) and the sign of d′, d″ in (9); they are available only through the explicit
option ``partials="printed"`` of :func:`orient_pair`
(:func:`photolib.derivations.printed_gnss_jacobians`). All iterations run on
:func:`photolib.lsq.gauss_newton`.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from . import derivations
from .camera import as_points
from .errors import ConvergenceError, DegenerateGeometryError, InputError, PointBehindCameraError
from .image_pair import intersection_scale
from .lsq import Adjustment, AdjustmentView, gauss_newton
from .rotation import rot_x, rot_y, rot_z

__all__ = ["ANGLE_NAMES", "PARTIALS", "rotation_aok", "geodetic_to_image_frame", "image_frame_to_geodetic",
           "image_space_vectors", "project", "ground_from_image", "base_components", "coplanarity_residuals",
           "base_direction_angle", "initial_chi", "correction_equations", "orient_pair", "iteration_history",
           "intersection_forms", "space_intersection", "build_model", "synthetic_pair"]

ANGLE_NAMES = ("alpha1", "omega1", "chi1", "alpha2", "omega2", "chi2")
"""The six unknowns of (5), in the paper's order."""

PARTIALS = ("derived", "printed")


# --- frames and direction cosines -------------------------------------------------------------------
def rotation_aok(alpha, omega, chi) -> np.ndarray:
    """The direction-cosine matrix (6) of the α–ω–χ system: A = R_Y(α)·R_X(ω)·R_Z(χ).

    R_Y(α) turns by −α in the right-handed sense (so that a₃ = −sin α cos ω as printed); A maps
    image (camera) coordinates to the image-space frame X* Y* Z*. Vectorised over the angles.

    Parameters
    ----------
    alpha, omega, chi : float or arrays
        The angles (rad).

    Returns
    -------
    (3, 3) or (..., 3, 3) ndarray
        A.

    Raises
    ------
    InputError
        NaN/inf angles.

    References
    ----------
    Dobrynin & Pimshina (n.d.), eq. (6); Chibunichev (2022), §1.3.

    Examples
    --------
    >>> rotation_aok(0.0, 0.0, 0.0)
    array([[1., 0., 0.],
           [0., 1., 0.],
           [0., 0., 1.]])
    """
    return rot_y(-np.asarray(alpha, dtype=float)) @ rot_x(omega) @ rot_z(chi)


def geodetic_to_image_frame(v) -> np.ndarray:
    """(ΔX, ΔY, ΔZ) geodetic (X north, Y east) → (ΔY, ΔX, ΔZ) in the image-space frame (line 48).

    The swap is its own inverse, so it also converts back (``image_frame_to_geodetic`` is the same function).

    Parameters
    ----------
    v : (..., 3) array
        Vectors.

    Returns
    -------
    (..., 3) ndarray
        The swapped vectors.

    Raises
    ------
    InputError
        Not 3-vectors, NaN/inf.

    References
    ----------
    Dobrynin & Pimshina (n.d.), line 48.

    Examples
    --------
    >>> geodetic_to_image_frame([1.0, 2.0, 3.0])
    array([2., 1., 3.])
    """
    v = np.asarray(v, dtype=float)
    if v.shape[-1] != 3:
        raise InputError(f"expected 3-vectors, got shape {v.shape}")
    return v[..., [1, 0, 2]]


image_frame_to_geodetic = geodetic_to_image_frame


def _angles(values, n: int, what: str) -> np.ndarray:
    a = np.asarray(values, dtype=float)
    if a.shape != (n,):
        raise InputError(f"{what}: expected {n} angles, got shape {a.shape}")
    if not np.all(np.isfinite(a)):
        raise InputError(f"{what} contain NaN or inf")
    return a


def _centre(S, what) -> np.ndarray:
    S = np.asarray(S, dtype=float)
    if S.shape != (3,) or not np.all(np.isfinite(S)):
        raise InputError(f"{what}: expected finite (X_S, Y_S, Z_S), got {S!r}")
    return S


def _camera(f, x0, y0):
    if not (np.isfinite(f) and f > 0 and np.isfinite(x0) and np.isfinite(y0)):
        raise InputError(f"interior orientation: f must be positive and f, x0, y0 finite, got {f}, {x0}, {y0}")
    return float(f), float(x0), float(y0)


def image_space_vectors(xy, angles, f, x0=0.0, y0=0.0) -> np.ndarray:
    """(X*, Y*, Z*) = A(α, ω, χ)·(x − x₀, y − y₀, −f)ᵀ, equation (4), one row per point.

    Parameters
    ----------
    xy : (n, 2) array
        Image coordinates (mm).
    angles : 3 angles
        α, ω, χ (rad).
    f, x0, y0 : float
        Interior orientation (mm).

    Returns
    -------
    (n, 3) ndarray
        The vectors.

    Raises
    ------
    InputError
        Bad shapes, NaN/inf, f ≤ 0.

    References
    ----------
    Dobrynin & Pimshina (n.d.), eq. (4).

    Examples
    --------
    >>> image_space_vectors([[10.0, 5.0]], [0.0, 0.0, 0.0], 100.0)
    array([[  10.,    5., -100.]])
    """
    xy = as_points(xy, 2, "image coordinates")
    a = _angles(angles, 3, "image angles (α, ω, χ)")
    f, x0, y0 = _camera(f, x0, y0)
    r = np.column_stack([xy[:, 0] - x0, xy[:, 1] - y0, np.full(len(xy), -f)])
    return r @ rotation_aok(*a).T


def project(points, S, angles, f, x0=0.0, y0=0.0) -> np.ndarray:
    """Image coordinates of geodetic points: the inverse of (3)/(4) (for synthetic data and checks).

    x = x₀ − f q₁/q₃, y = y₀ − f q₂/q₃ with q = Aᵀ·(ΔY, ΔX, ΔZ).

    Parameters
    ----------
    points : (n, 3) array
        Geodetic X, Y, Z (m).
    S : 3-vector
        Projection centre.
    angles : 3 angles
        α, ω, χ (rad).
    f, x0, y0 : float
        Interior orientation (mm).

    Returns
    -------
    (n, 2) ndarray
        Image coordinates (mm).

    Raises
    ------
    InputError
        Bad shapes, NaN/inf.
    PointBehindCameraError
        Points behind the camera.

    References
    ----------
    Dobrynin & Pimshina (n.d.), eqs. (3), (4).

    Examples
    --------
    >>> project([[100.0, 50.0, 0.0]], [0.0, 0.0, 1000.0], [0.0, 0.0, 0.0], 100.0)
    array([[ 5., 10.]])
    """
    P = as_points(points, 3, "geodetic points")
    S = _centre(S, "projection centre")
    a = _angles(angles, 3, "image angles (α, ω, χ)")
    f, x0, y0 = _camera(f, x0, y0)
    q = geodetic_to_image_frame(P - S) @ rotation_aok(*a)
    if np.any(q[:, 2] >= 0):
        bad = np.flatnonzero(q[:, 2] >= 0)
        raise PointBehindCameraError(f"points {bad.tolist()} are not in front of the camera", points=bad)
    return np.column_stack([x0 - f * q[:, 0] / q[:, 2], y0 - f * q[:, 1] / q[:, 2]])


def ground_from_image(xy, S, angles, Z, f, x0=0.0, y0=0.0) -> np.ndarray:
    """(X, Y) of points of known height Z by the collinearity equations (3).

    Y = (Z − Z_S)X*/Z* + Y_S, X = (Z − Z_S)Y*/Z* + X_S, with X*, Y*, Z* of (4).

    Parameters
    ----------
    xy : (n, 2) array
        Image coordinates (mm).
    S : 3-vector
        Projection centre.
    angles : 3 angles
        α, ω, χ (rad).
    Z : float or (n,) array
        Heights (m).
    f, x0, y0 : float
        Interior orientation (mm).

    Returns
    -------
    (n, 2) ndarray
        Geodetic X, Y (m).

    Raises
    ------
    InputError
        Bad shapes, NaN/inf.
    DegenerateGeometryError
        A horizontal ray.

    References
    ----------
    Dobrynin & Pimshina (n.d.), eqs. (3), (4).

    Examples
    --------
    >>> ground_from_image([[5.0, 10.0]], [0.0, 0.0, 1000.0], [0.0, 0.0, 0.0], 0.0, 100.0)
    array([[100.,  50.]])
    """
    r = image_space_vectors(xy, angles, f, x0, y0)
    S = _centre(S, "projection centre")
    try:
        Z = np.broadcast_to(np.asarray(Z, dtype=float), (len(r),))
    except (TypeError, ValueError):
        raise InputError(f"Z: expected one height or {len(r)} heights, got {np.shape(Z)}") from None
    if not np.all(np.isfinite(Z)):
        raise InputError("the heights Z contain NaN or inf")
    if np.any(r[:, 2] == 0):
        raise DegenerateGeometryError("a ray is horizontal (Z* = 0): it does not meet a level of known height")
    k = (Z - S[2]) / r[:, 2]
    return np.column_stack([k * r[:, 1] + S[0], k * r[:, 0] + S[1]])


def base_components(S1, S2) -> np.ndarray:
    """(B_X, B_Y, B_Z) = S₂ − S₁ of (2) (geodetic).

    Parameters
    ----------
    S1, S2 : 3-vectors
        Projection centres.

    Returns
    -------
    (3,) ndarray
        The base.

    Raises
    ------
    InputError
        NaN/inf, wrong shapes.
    DegenerateGeometryError
        Zero base.

    References
    ----------
    Dobrynin & Pimshina (n.d.), eq. (2).

    Examples
    --------
    >>> base_components([0.0, 0, 0], [10.0, 20, 1])
    array([10., 20.,  1.])
    """
    B = _centre(S2, "centre S2") - _centre(S1, "centre S1")
    if not np.any(B):
        raise DegenerateGeometryError("the base is zero: both projection centres coincide")
    return B


def coplanarity_residuals(angles, xy1, xy2, S1, S2, f, x0=0.0, y0=0.0) -> np.ndarray:
    """φ of (1) for each pair of corresponding points (m·mm²): det[[B_Y, B_X, B_Z], r₁*, r₂*].

    Parameters
    ----------
    angles : 6 angles
        α₁, ω₁, χ₁, α₂, ω₂, χ₂ (rad).
    xy1, xy2 : (n, 2) arrays
        Corresponding image points (mm).
    S1, S2 : 3-vectors
        Projection centres.
    f, x0, y0 : float
        Interior orientation (mm).

    Returns
    -------
    (n,) ndarray
        φ.

    Raises
    ------
    InputError
        Bad shapes, different counts, NaN/inf.
    DegenerateGeometryError
        Zero base.

    References
    ----------
    Dobrynin & Pimshina (n.d.), eqs. (1), (2).

    Examples
    --------
    >>> pair = synthetic_pair(30.0, seed=3)
    >>> float(abs(coplanarity_residuals(pair.angles, pair.xy1, pair.xy2, pair.S1, pair.S2, pair.f)).max()) < 1e-6
    True
    """
    a = _angles(angles, 6, "angles (α₁, ω₁, χ₁, α₂, ω₂, χ₂)")
    r1 = image_space_vectors(xy1, a[:3], f, x0, y0)
    r2 = image_space_vectors(xy2, a[3:], f, x0, y0)
    if len(r1) != len(r2):
        raise InputError(f"corresponding points: image 1 has {len(r1)}, image 2 has {len(r2)}")
    return np.cross(r1, r2) @ geodetic_to_image_frame(base_components(S1, S2))


# --- initial approximations (lines 171–179) ---------------------------------------------------------
def base_direction_angle(S1, S2) -> float:
    """Direction angle (azimuth from north, clockwise, radians in [0, 2π)) of the base S₁S₂.

    Parameters
    ----------
    S1, S2 : 3-vectors
        Projection centres.

    Returns
    -------
    float
        The direction angle (rad).

    Raises
    ------
    InputError
        NaN/inf.
    DegenerateGeometryError
        Zero or vertical base.

    References
    ----------
    Dobrynin & Pimshina (n.d.), lines 171–179.

    Examples
    --------
    >>> round(float(np.degrees(base_direction_angle([0.0, 0, 0], [1.0, 1.0, 0]))), 6)
    45.0
    """
    B = base_components(S1, S2)
    if np.hypot(B[0], B[1]) == 0:
        raise DegenerateGeometryError("the base is vertical: its direction angle (and χ) is undefined")
    return float(np.arctan2(B[1], B[0]) % (2 * np.pi))


def initial_chi(S1, S2) -> float:
    """(χ₁) = (χ₂) from the direction angle α of the base (lines 177–179), radians.

    χ = 90° − α for α < 90°, χ = 450° − α for 90° < α < 180°. The paper orders the pair "left
    to right" (the right image has the larger Y_S), so α ∈ [0°, 180°]; for other bases the same
    rule, (90° − α) mod 360°, is applied. With α = ω = 0 it makes the image x axis point along
    the base.

    Parameters
    ----------
    S1, S2 : 3-vectors
        Projection centres.

    Returns
    -------
    float
        χ (rad).

    Raises
    ------
    InputError
        NaN/inf.
    DegenerateGeometryError
        Zero or vertical base.

    References
    ----------
    Dobrynin & Pimshina (n.d.), lines 171–179.

    Examples
    --------
    >>> round(float(np.degrees(initial_chi([0.0, 0, 0], [1.0, 1.0, 0]))), 6)
    45.0
    """
    az = np.degrees(base_direction_angle(S1, S2))
    chi = 90.0 - az if az < 90.0 else 450.0 - az
    return float(np.radians(chi % 360.0))


# --- the joint adjustment (5) + (9) -------------------------------------------------------------------
@dataclass(repr=False)
class GnssOrientation(AdjustmentView):
    """The six angles of the pair from (5) and (9), with the adjustment of the engine of §1.8."""

    angles: np.ndarray             # α₁, ω₁, χ₁, α₂, ω₂, χ₂ (rad)
    partials: str                  # "derived" or "printed"
    adjustment: Adjustment = field(repr=False)
    coplanarity: np.ndarray = field(repr=False, default=None)    # residual φ of the tie points (m·mm²)
    ground: np.ndarray = field(repr=False, default=None)         # (k, 2, 2) (Y) − Y, (X) − X per control & image (m)

    def as_dict(self) -> dict:
        """{"alpha1": α₁, …, "chi2": χ₂} in radians."""
        return dict(zip(ANGLE_NAMES, map(float, self.angles)))

    def __repr__(self) -> str:
        labels = ("α₁", "ω₁", "χ₁", "α₂", "ω₂", "χ₂")
        std = self.adjustment.std
        parts = [f"{lab} = {np.degrees(v):+.4f}° ± {np.degrees(s):.4f}°" for lab, v, s in zip(labels, self.angles, std)]
        return (f"GnssOrientation ({self.partials} partials), {self.adjustment.iterations} iterations, "
                f"μ = {self.adjustment.mu:.3g}\n  " + "\n  ".join(parts))


def _check_pair(xy1, xy2, what):
    xy1 = as_points(xy1, 2, f"{what}, image 1")
    xy2 = as_points(xy2, 2, f"{what}, image 2")
    if len(xy1) != len(xy2):
        raise InputError(f"{what}: image 1 has {len(xy1)} points, image 2 has {len(xy2)}")
    return xy1, xy2


def correction_equations(angles, xy1, xy2, S1, S2, control_xyz, control_xy1, control_xy2, f, x0=0.0, y0=0.0,
                         partials: str = "derived"):
    """B and L of the joint correction equations at ``angles``: (5) for every tie point, then (9).

    Rows: one per tie point (coefficients a…m, free term l = φ), then for every control point
    l_y₁, l_x₁ (image 1: a′, b′, c′ / d′, e′, m′) and l_y₂, l_x₂ (image 2: a″…m″), each with zeros
    for the other image's angles.

    Parameters
    ----------
    angles : 6 angles
        The approximation (rad).
    xy1, xy2 : (n, 2) arrays
        Tie points (mm).
    S1, S2 : 3-vectors
        Projection centres.
    control_xyz, control_xy1, control_xy2 : arrays
        Control points and their image coordinates.
    f, x0, y0 : float
        Interior orientation (mm).
    partials : {"derived", "printed"}
        ``"derived"`` takes the coefficients from the sympy models; ``"printed"`` evaluates the
        paper's printed (5), (8), (9) instead (the free terms are the same).

    Returns
    -------
    B : (n + 4k, 6) ndarray
        Coefficients.
    L : (n + 4k,) ndarray
        Free terms.

    Raises
    ------
    InputError
        Unknown partials, NaN/inf, bad shapes.
    DegenerateGeometryError
        Zero base.

    References
    ----------
    Dobrynin & Pimshina (n.d.), eqs. (5), (8), (9).

    Examples
    --------
    >>> pair = synthetic_pair(30.0, seed=3)
    >>> B, L = correction_equations(pair.angles, pair.xy1, pair.xy2, pair.S1, pair.S2, *pair.control_args, pair.f)
    >>> B.shape
    (13, 6)
    """
    if partials not in PARTIALS:
        raise InputError(f"partials must be 'derived' or 'printed', got {partials!r}")
    p = _angles(angles, 6, "angles (α₁, ω₁, χ₁, α₂, ω₂, χ₂)")
    f, x0, y0 = _camera(f, x0, y0)
    BX, BY, BZ = base_components(S1, S2)
    S1, S2 = np.asarray(S1, float), np.asarray(S2, float)
    cop_res, cop_jac = derivations.gnss_coplanarity_model().compile()
    col_res, col_jac = derivations.gnss_collinearity_model().compile()
    pr_cop, pr_col = derivations.printed_gnss_jacobians()
    data = (xy1[:, 0], xy1[:, 1], xy2[:, 0], xy2[:, 1], f, x0, y0, BX, BY, BZ)
    L_cop = cop_res(*p, *data)[0]
    B_cop = (cop_jac if partials == "derived" else pr_cop)(*p, *data).T
    rows, frees = [B_cop], [L_cop]
    for img, (S, xy, cols) in enumerate(((S1, control_xy1, slice(0, 3)), (S2, control_xy2, slice(3, 6)))):
        if len(control_xyz) == 0:
            break
        d = (xy[:, 0], xy[:, 1], f, x0, y0, *S, control_xyz[:, 0], control_xyz[:, 1], control_xyz[:, 2])
        L = col_res(*p[cols], *d).T                                              # (k, 2): l_y, l_x
        J = (col_jac if partials == "derived" else pr_col)(*p[cols], *d).reshape(2, 3, -1).transpose(2, 0, 1)
        Bk = np.zeros((len(control_xyz), 2, 6))
        Bk[:, :, cols] = J
        rows.append(Bk.reshape(-1, 6))
        frees.append(L.reshape(-1))
    return np.vstack(rows), np.concatenate(frees)


def orient_pair(xy1, xy2, S1, S2, control_xyz, control_xy1, control_xy2, f, x0=0.0, y0=0.0, *,
                partials: str = "derived", initial=None, weights=None, tol: float = 1e-10,
                max_iter: int = 30) -> GnssOrientation:
    """The six angles of a pair with GNSS centres: (5) and (9) solved jointly, iterated.

    Parameters
    ----------
    xy1, xy2 : (n, 2) arrays
        Corresponding image points (mm), n ≥ 5 (each gives one coplanarity equation (5)).
    S1, S2 : 3-vectors
        The projection centres X_S, Y_S, Z_S (geodetic, m) measured by GNSS.
    control_xyz : (k, 3) array, k ≥ 1
        Geodetic X, Y, Z of the control points; ``control_xy1``, ``control_xy2`` their image
        coordinates. Each gives the four equations (9).
    f, x0, y0 : float
        Interior orientation (mm), the same for both images.
    partials : {"derived", "printed"}
        ``"derived"`` (default): coefficients from the sympy models. ``"printed"``: the paper's
        printed (5), (8), (9) — including its errors — to reproduce what they compute.
    initial : array of 6, optional
        Approximations; by default α = ω = 0 and χ of :func:`initial_chi` (lines 171–179).
    weights : array, optional
        Weights of the n + 4k equations; unit weights (the paper) by default. Note that φ is in
        m·mm² and the ground equations in m.
    tol, max_iter
        Convergence when every |δ| < ``tol`` rad; :class:`ConvergenceError` after ``max_iter``.

    Returns
    -------
    GnssOrientation
        The six angles (rad) with μ, m_j, r_ij and the residuals of (5) and (9).

    Raises
    ------
    InputError
        Fewer than 5 tie points, no control point, mismatched counts, NaN/inf, bad options.
    DegenerateGeometryError
        Zero or vertical base, a singular system.
    ConvergenceError
        No convergence within ``max_iter``.

    References
    ----------
    Dobrynin & Pimshina (n.d.), eqs. (5), (9), lines 171–179, 200; Chibunichev (2022), §1.8.

    Examples
    --------
    >>> pair = synthetic_pair(30.0, seed=3)
    >>> ori = orient_pair(*pair.args)
    >>> bool(np.allclose(ori.angles, pair.angles, atol=1e-9))
    True
    """
    xy1, xy2 = _check_pair(xy1, xy2, "tie points")
    if len(xy1) < 5:
        raise InputError(f"at least five coplanarity equations are needed (line 200), got {len(xy1)} tie points")
    C = np.asarray(control_xyz, dtype=float)
    C = C.reshape(-1, 3) if C.size else np.zeros((0, 3))
    if len(C) < 1:
        raise InputError("at least one control point (X, Y, Z) is needed: coplanarity fixes only five angles")
    C = as_points(C, 3, "control points")
    cxy1, cxy2 = _check_pair(control_xy1, control_xy2, "control points")
    if len(cxy1) != len(C):
        raise InputError(f"{len(C)} control points but {len(cxy1)} image coordinates")
    S1 = _centre(S1, "centre S1")
    S2 = _centre(S2, "centre S2")
    f, x0, y0 = _camera(f, x0, y0)
    if initial is None:
        chi0 = initial_chi(S1, S2)
        start = np.array([0.0, 0.0, chi0, 0.0, 0.0, chi0])
    else:
        start = _angles(initial, 6, "initial angles")

    def linearize(p):
        return correction_equations(p, xy1, xy2, S1, S2, C, cxy1, cxy2, f, x0, y0, partials)

    adj = gauss_newton(linearize, start, weights, tol=tol, max_iter=max_iter, names=ANGLE_NAMES)
    B, L = linearize(adj.x)
    n = len(xy1)
    return GnssOrientation(adj.x, partials, adj, L[:n], L[n:].reshape(2, len(C), 2).transpose(1, 0, 2))


@dataclass
class IterationHistory:
    """Outcome of an iteration that may fail: used to compare printed and derived partials."""

    converged: bool
    iterations: int
    max_correction: np.ndarray     # max |δ| (rad) of each iteration
    angles: np.ndarray             # the last approximation (rad)
    reason: str = ""


def iteration_history(*args, **kwargs) -> IterationHistory:
    """Run :func:`orient_pair` (same arguments) and report the iterations whether or not it converges.

    Non-convergence within ``max_iter`` (:class:`ConvergenceError`) and a singular system on the
    way (:class:`DegenerateGeometryError`) are recorded, not raised.

    Parameters
    ----------
    *args, **kwargs
        The arguments of :func:`orient_pair`.

    Returns
    -------
    IterationHistory
        Converged or not, iterations, max |δ| per iteration, the last angles.

    Raises
    ------
    InputError
        Bad input (raised, not recorded).

    References
    ----------
    Dobrynin & Pimshina (n.d.), eqs. (5), (9).

    Examples
    --------
    >>> pair = synthetic_pair(30.0, seed=3)
    >>> h = iteration_history(*pair.args)
    >>> h.converged
    True
    """
    try:
        result = orient_pair(*args, **kwargs)
    except (ConvergenceError, DegenerateGeometryError) as exc:
        hist = getattr(exc, "history", None) or []
        steps = np.array([np.max(np.abs(r.delta)) for r in hist])
        last = hist[-1].x + hist[-1].delta if hist else np.full(6, np.nan)
        return IterationHistory(False, len(hist), steps, last, f"{type(exc).__name__}: {exc}")
    steps = np.array([np.max(np.abs(r.delta)) for r in result.history])
    return IterationHistory(True, result.iterations, steps, result.angles)


# --- space intersection (line 212) ---------------------------------------------------------------------
def intersection_forms(r1, r2, B) -> tuple:
    """The three expressions of N at line 212, as printed: (numerators, denominators), each (n, 3).

    ::

        N = (B_X Z₂* − B_Z Y₂*)/(Y₁*Z₂* − Z₁*Y₂*) = (B_Z X₂* − B_Y Z₂*)/(Z₁*X₂* − X₁*Z₂*)
          = (B_Y Y₂* − B_X X₂*)/(X₁*Y₂* − Y₁*X₂*).

    They are the components of N(r₁ × r₂) = b × r₂ with b = (B_Y, B_X, B_Z): form k is 0/0 when
    the k-th component of r₁ × r₂ vanishes.

    Parameters
    ----------
    r1, r2 : (n, 3) arrays
        Image-space vectors (4).
    B : 3-vector
        (B_X, B_Y, B_Z) geodetic (2).

    Returns
    -------
    (numerators, denominators)
        Two (n, 3) arrays.

    Raises
    ------
    InputError
        Bad shapes, NaN/inf.

    References
    ----------
    Dobrynin & Pimshina (n.d.), line 212.

    Examples
    --------
    >>> num, den = intersection_forms([[0.0, 0, -1]], [[-0.4, 0, -1]], [0.0, 400.0, 0])
    >>> float(num[0, 1] / den[0, 1])
    1000.0
    """
    r1 = as_points(r1, 3, "image-space vectors of image 1")
    r2 = as_points(r2, 3, "image-space vectors of image 2")
    BX, BY, BZ = np.asarray(B, dtype=float)
    X1, Y1, Z1 = r1.T
    X2, Y2, Z2 = r2.T
    num = np.column_stack([BX * Z2 - BZ * Y2, BZ * X2 - BY * Z2, BY * Y2 - BX * X2])
    den = np.column_stack([Y1 * Z2 - Z1 * Y2, Z1 * X2 - X1 * Z2, X1 * Y2 - Y1 * X2])
    return num, den


def space_intersection(xy1, xy2, S1, S2, angles, f, x0=0.0, y0=0.0, *, form: int | None = None) -> np.ndarray:
    """Geodetic X, Y, Z of points from the oriented pair (line 212): Y = N X₁* + Y_S1,
    X = N Y₁* + X_S1, Z = N Z₁* + Z_S1.

    The division is done by :func:`photolib.image_pair.intersection_scale` (``method="component"``),
    whose components are exactly the three printed forms when the base is written in the image-space frame.

    Parameters
    ----------
    xy1, xy2 : (n, 2) arrays
        Corresponding image points (mm).
    S1, S2 : 3-vectors
        Projection centres.
    angles : 6 angles
        α₁, ω₁, χ₁, α₂, ω₂, χ₂ (rad).
    f, x0, y0 : float
        Interior orientation (mm).
    form : {None, 1, 2, 3}
        Force one of the three printed expressions of N; ``None`` takes, point by point, the
        form with the largest |denominator|.

    Returns
    -------
    (n, 3) ndarray
        Geodetic X, Y, Z (m).

    Raises
    ------
    InputError
        Bad shapes, NaN/inf.
    DegenerateGeometryError
        Zero base, parallel rays, a forced 0/0 form.
    PointBehindCameraError
        Rays that meet behind camera 1.

    References
    ----------
    Dobrynin & Pimshina (n.d.), line 212; Chibunichev (2022), §2.4, eq. (2.4.12).

    Examples
    --------
    >>> pair = synthetic_pair(30.0, seed=3)
    >>> P = space_intersection(pair.xy1, pair.xy2, pair.S1, pair.S2, pair.angles, pair.f)
    >>> bool(np.allclose(P, pair.ground, atol=1e-6))
    True
    """
    a = _angles(angles, 6, "angles (α₁, ω₁, χ₁, α₂, ω₂, χ₂)")
    xy1, xy2 = _check_pair(xy1, xy2, "points")
    S1 = _centre(S1, "centre S1")
    r1 = image_space_vectors(xy1, a[:3], f, x0, y0)
    r2 = image_space_vectors(xy2, a[3:], f, x0, y0)
    b = geodetic_to_image_frame(base_components(S1, S2))
    N = intersection_scale(b, r1, r2, method="component", formula=form)
    if np.any(N <= 0):
        bad = np.flatnonzero(N <= 0)
        raise PointBehindCameraError(f"the rays of points {bad.tolist()} meet behind camera 1", points=bad)
    return S1 + N[:, None] * image_frame_to_geodetic(r1)


@dataclass(repr=False)
class GnssModel:
    """The stereo model: oriented pair and geodetic coordinates of all tie points."""

    orientation: GnssOrientation
    points: np.ndarray             # (n, 3) geodetic X, Y, Z of the tie points

    def __repr__(self) -> str:
        return f"GnssModel: {len(self.points)} tie points\n  " + repr(self.orientation).replace("\n", "\n  ")


def build_model(xy1, xy2, S1, S2, control_xyz, control_xy1, control_xy2, f, x0=0.0, y0=0.0, **kwargs) -> GnssModel:
    """:func:`orient_pair` followed by :func:`space_intersection` of the tie points (the paper's whole method).

    Parameters
    ----------
    xy1, xy2, S1, S2, control_xyz, control_xy1, control_xy2, f, x0, y0
        As in :func:`orient_pair`.
    **kwargs
        Options of :func:`orient_pair`.

    Returns
    -------
    GnssModel
        The orientation and the geodetic coordinates of the tie points.

    Raises
    ------
    InputError
        Bad input.
    DegenerateGeometryError
        Zero base, singular system.
    ConvergenceError
        No convergence.

    References
    ----------
    Dobrynin & Pimshina (n.d.), eqs. (1)–(9), line 212.

    Examples
    --------
    >>> pair = synthetic_pair(30.0, seed=3)
    >>> m = build_model(*pair.args)
    >>> bool(np.allclose(m.points, pair.ground, atol=1e-6))
    True
    """
    ori = orient_pair(xy1, xy2, S1, S2, control_xyz, control_xy1, control_xy2, f, x0, y0, **kwargs)
    return GnssModel(ori, space_intersection(xy1, xy2, S1, S2, ori.angles, f, x0, y0))


# --- synthetic stand-in (the paper prints no data) -------------------------------------------------------
@dataclass
class SyntheticPair:
    """A synthetic stereo pair with known truth (our stand-in; nothing of it is from the paper)."""

    S1: np.ndarray
    S2: np.ndarray
    angles: np.ndarray             # true α₁, ω₁, χ₁, α₂, ω₂, χ₂
    ground: np.ndarray             # (n, 3) geodetic X, Y, Z of the tie points
    xy1: np.ndarray
    xy2: np.ndarray
    f: float
    x0: float = 0.0
    y0: float = 0.0
    control: tuple = (0,)          # indices of the tie points used as control points

    @property
    def control_args(self) -> tuple:
        c = list(self.control)
        return self.ground[c], self.xy1[c], self.xy2[c]

    @property
    def args(self) -> tuple:
        """Positional arguments of :func:`orient_pair` / :func:`build_model`."""
        return (self.xy1, self.xy2, self.S1, self.S2, *self.control_args, self.f, self.x0, self.y0)


def synthetic_pair(azimuth_deg: float, *, seed: int = 0, f: float = 100.0, H: float = 1500.0,
                   base: float = 1200.0, dZ_S: float = 5.0, tilt_deg: float = 2.0, chi_offset_deg: float = 3.0,
                   across: float = 1000.0, relief: float = 60.0, image_noise: float = 0.0,
                   control=(0,), level: bool = False) -> SyntheticPair:
    """A near-vertical pair flown along ``azimuth_deg`` (direction angle of S₁S₂, from north).

    S₁ = (5000, 3000, 150 + H); S₂ = S₁ + base·(cos az, sin az, 0) + (0, 0, dZ_S) (``level=True``
    sets dZ_S = 0). Nine tie points in the 3 × 3 (Gruber-like) layout: along the base at the
    nadirs and the midpoint, across at 0 and ±``across`` m, heights 150 m ± ``relief``
    (seeded). True α, ω uniform in ±``tilt_deg``, χ = initial χ ± ``chi_offset_deg``. Optional
    Gaussian ``image_noise`` (mm). Tie point ``control`` (default the first) doubles as the
    control point(s). Drawn by :func:`photolib.synthetic.stereo_pair` with the α–ω–χ projection
    :func:`project` (our stand-in: the paper prints no data).

    Parameters
    ----------
    azimuth_deg : float
        Direction angle of the base (°).
    seed : int
        Random seed.
    f, H, base, dZ_S : float
        Focal length (mm), flying height, base, height difference of the centres (m).
    tilt_deg, chi_offset_deg : float
        Spread of the true angles (°).
    across, relief : float
        Across-track offset and relief of the tie points (m).
    image_noise : float
        Gaussian image noise (mm).
    control : tuple of int
        Tie points used as control.
    level : bool
        Equal heights of the centres.

    Returns
    -------
    SyntheticPair
        Centres, true angles, ground points, image coordinates.

    Raises
    ------
    InputError
        Negative relief or noise, NaN.

    References
    ----------
    Dobrynin & Pimshina (n.d.), eqs. (3), (4), lines 171–179.

    Examples
    --------
    >>> pair = synthetic_pair(30.0, seed=3)
    >>> pair.xy1.shape, pair.control
    ((9, 2), (0,))
    """
    from .synthetic import stereo_pair

    az = np.radians(azimuth_deg)
    u = np.array([np.cos(az), np.sin(az), 0.0])            # along the base (geodetic)
    v = np.array([-np.sin(az), np.cos(az), 0.0])           # across
    S1 = np.array([5000.0, 3000.0, 150.0 + H])
    S2 = S1 + base * u + np.array([0.0, 0.0, 0.0 if level else dZ_S])
    chi0 = initial_chi(S1, S2)
    along = np.array([0.0, 0.5, 1.0]) * base
    grid = [S1[:2] + a * u[:2] + s * across * v[:2] for a in along for s in (-1.0, 0.0, 1.0)]
    pair = stereo_pair(seed=seed, centres=(S1, S2), angles=((0.0, 0.0, chi0), (0.0, 0.0, chi0)),
                       angle_spread=np.radians([tilt_deg, tilt_deg, chi_offset_deg]), ground_xy=np.array(grid),
                       mean_height=150.0, relief=relief, sigma=image_noise,
                       projector=lambda P, S, a: project(P, S, a, f))
    return SyntheticPair(S1, S2, pair.angles.ravel(), pair.points, pair.xy1, pair.xy2, f, control=tuple(control))
