"""Space resection of a single image — Chapter 1, §1.8–§1.9.

* §1.8 :func:`space_resection` — the six exterior-orientation elements X_S, Y_S, Z_S, ω, α, κ
  from ≥ 3 control points by iterated least squares on the collinearity equations (1.8.2):
  correction equations (1.8.3)/(1.8.4), matrix form B·δ + L = V (1.8.5), normal equations
  (1.8.6)–(1.8.7) and the a-posteriori accuracy (1.8.8)–(1.8.10). The partial derivatives are
  derived by sympy (:func:`photolib.derivations.collinearity_model`); ``jacobian="printed"``
  runs the same iteration with the coefficients a₁…b₆ exactly as the book prints them (most
  of them are wrong — the "as printed" mode of the errata).
* §1.9 :func:`resection_by_angles` — only the projection centre, from the equality of the angle
  between two rays in object space and in image space, φ = cos ASB − cos aSb = 0 (1.9.1),
  linearised as (1.9.2). :func:`angle_equation_count` and :func:`independent_angle_equations`
  give the counts n(n−1)/2 and 2n−3 the book states.
* :func:`implied_noise` — the noise-free image coordinates of a known pose and the noise a
  data set contains (how the book's §1.8 example can be regenerated).

Units: image coordinates in mm, object coordinates in m, angles in radians.
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass
from typing import Callable, Sequence

import numpy as np

from . import derivations
from .camera import ExteriorOrientation, InteriorOrientation, as_point_pairs, as_points, correct_distortion
from .errors import ConvergenceError, DegenerateGeometryError, InputError
from .lsq import Adjustment, AdjustmentView, IterationRecord, gauss_newton, point_weights
from .rotation import check_order
from .single_image import camera_coordinates, project

EO_NAMES = ExteriorOrientation.NAMES
CENTER_NAMES = ("Xs", "Ys", "Zs")

DEFAULT_TOL = (1e-7, 1e-7, 1e-7, 1e-10, 1e-10, 1e-10)
"""Convergence thresholds per unknown: 0.1 µm for X_S, Y_S, Z_S and 1e-10 rad for ω, α, κ."""


# --- results -----------------------------------------------------------------------------------
@dataclass
class ResectionResult(AdjustmentView):
    """Result of :func:`space_resection` (§1.8).

    ``eo`` is the adjusted exterior orientation, ``adjustment`` the full least-squares result
    of :func:`photolib.lsq.gauss_newton` (order of the unknowns: X_S, Y_S, Z_S, ω, α, κ).
    ``mu``, ``std`` (metres for X_S, Y_S, Z_S, radians for ω, α, κ), ``corr``, ``Q``,
    ``iterations`` and ``history`` come from the adjustment; μ is in mm with unit weights
    (unitless with P = 1/σ²).
    """

    eo: ExteriorOrientation
    adjustment: Adjustment
    jacobian: str = "derived"

    @property
    def std_degrees(self) -> np.ndarray:
        """m_j with the angular ones in degrees."""
        return np.concatenate([self.std[:3], np.degrees(self.std[3:])])

    @property
    def residuals(self) -> np.ndarray:
        """V of (1.8.4) as (n, 2): v_x, v_y per point (corrections to the measured coordinates)."""
        return self.adjustment.residuals.reshape(-1, 2)


@dataclass
class AngleResectionResult(AdjustmentView):
    """Result of :func:`resection_by_angles` (§1.9): the projection centre and its accuracy.

    μ and m_j are *nominal*: of the n(n−1)/2 equations only 2n−3 are independent, but the
    degrees of freedom are counted as m − 3, as the book does.
    """

    center: np.ndarray
    adjustment: Adjustment
    pairs: tuple

    @property
    def residuals(self) -> np.ndarray:
        """v_i, one per pair of points (cosine units)."""
        return self.adjustment.residuals


# --- input checks ------------------------------------------------------------------------------
def _control_points(XYZ, xy, io):
    if not isinstance(io, InteriorOrientation):
        raise InputError(f"io must be an InteriorOrientation, got {type(io).__name__}")
    XYZ, xy = as_point_pairs(XYZ, 3, xy, 2, ("control points XYZ", "image points xy"), 3, "a resection")
    centred = XYZ - XYZ.mean(axis=0)
    sv = np.linalg.svd(centred, compute_uv=False)
    if sv[0] == 0 or sv[1] < 1e-9 * sv[0]:
        raise DegenerateGeometryError("the control points are collinear (or coincide): the resection is undetermined")
    if io.has_distortion:
        xy = correct_distortion(xy, io)                          # (1.2.3)
    return XYZ, xy


def approximate_exterior_orientation(XYZ, xy, io: InteriorOrientation, order: str = "kaw") -> ExteriorOrientation:
    """Approximate EO for a near-vertical image (start values for :func:`space_resection`).

    Assumes ω = α = 0. Then (X − X_S, Y − Y_S) = N·R(κ)(x − x₀, y − y₀) with N = (Z_S − Z)/f,
    a plane similarity transform. Its least-squares fit over all points gives the image scale N
    (m per mm), κ (the direction of the image axes on the ground), and X_S, Y_S; the height is
    Z_S = mean(Z) + N·f. Fails for strongly tilted or oblique images — give ``eo0`` there.
    """
    XYZ = as_points(XYZ, 3, "control point coordinates XYZ")
    xy = as_points(xy, 2, "image coordinates xy")
    z = (xy[:, 0] - io.x0) + 1j * (xy[:, 1] - io.y0)
    w = XYZ[:, 0] + 1j * XYZ[:, 1]
    dz, dw = z - z.mean(), w - w.mean()
    denom = np.sum(np.abs(dz) ** 2)
    if denom == 0:
        raise DegenerateGeometryError("all image points coincide: no approximation possible")
    m = np.sum(np.conj(dz) * dw) / denom                        # N·e^{iκ}
    c = w.mean() - m * z.mean()
    scale = abs(m)
    return ExteriorOrientation(float(c.real), float(c.imag), float(XYZ[:, 2].mean() + scale * io.f),
                               0.0, 0.0, float(np.angle(m)), order)


# --- §1.8 ---------------------------------------------------------------------------------------
def collinearity_linearizer(XYZ, xy, io: InteriorOrientation, order: str = "kaw", jacobian: str = "derived"):
    """``linearize(p) -> (B, L)`` of (1.8.5) for the EO vector p = (X_S, Y_S, Z_S, ω, α, κ).

    Rows alternate x, y per point; L = F_x, F_y of (1.8.2) (computed − measured); B holds
    a₁…a₆ / b₁…b₆ of (1.8.3), derived by sympy (``"derived"``) or as printed (``"printed"``).
    ``xy`` must already be corrected for distortion.
    """
    residual_fn, jacobian_fn = derivations.collinearity_model(order).compile()
    if jacobian == "printed":
        jacobian_fn = derivations.printed_resection_jacobian()
    data = (XYZ[:, 0], XYZ[:, 1], XYZ[:, 2], xy[:, 0], xy[:, 1], io.f, io.x0, io.y0)
    n = len(XYZ)

    def linearize(p):
        F = residual_fn(*p, *data)                       # (2, n)
        J = jacobian_fn(*p, *data)                       # (12, n): a1..a6, b1..b6
        B = np.empty((2 * n, 6))
        B[0::2] = J[:6].T
        B[1::2] = J[6:].T
        return B, F.T.ravel()

    return linearize


def space_resection(XYZ, xy, io: InteriorOrientation, eo0=None, order: str = "kaw", weights=None,
                    jacobian: str = "derived", tol=None, max_iter: int = 50,
                    progress: Callable[[IterationRecord], None] | None = None) -> ResectionResult:
    """Exterior orientation of one image from control points, (1.8.2)–(1.8.10).

    Parameters
    ----------
    XYZ : (n, 3) array
        Object coordinates of the control points (m), n ≥ 3, not collinear.
    xy : (n, 2) array
        Their measured image coordinates (mm); corrected for distortion by (1.2.3) first.
    io : InteriorOrientation
    eo0 : ExteriorOrientation or 6-vector, optional
        Approximate values X_S⁰ … κ⁰ (angles in radians). If omitted,
        :func:`approximate_exterior_orientation` supplies them (near-vertical assumption).
    order : {"kaw", "wak"}
        Rotation sequence of the angles: (1.3.5) — the book's examples — or (1.3.2).
    weights : array, optional
        p_i = 1/m_i² per point (n,), per coordinate (n, 2) or (2n,); unit weights if omitted.
    jacobian : {"derived", "printed"}
        ``"derived"`` uses the sympy derivatives of (1.8.2). ``"printed"`` uses a₁…b₆ exactly as
        printed in §1.8 (only for ``order="kaw"``); it reproduces what the book's formulas do and
        generally diverges.
    tol : float or 6-array, optional
        |δ_j| thresholds (m for the centre, rad for the angles); default :data:`DEFAULT_TOL`.
    max_iter : int
    progress : callable, optional
        Called with every :class:`~photolib.lsq.IterationRecord`.

    Returns
    -------
    ResectionResult
        ``eo``, μ (1.8.9), m_j (1.8.8), r_ij (1.8.10), Q, residuals V (n, 2), iteration history.

    Raises
    ------
    InputError
        Fewer than 3 points, shapes that do not match, NaN/inf, a bad option.
    DegenerateGeometryError
        Collinear control points or a singular normal matrix.
    ConvergenceError
        The iteration diverged or did not settle in ``max_iter`` steps.
    """
    check_order(order)
    if jacobian not in ("derived", "printed"):
        raise InputError(f"jacobian must be 'derived' or 'printed', got {jacobian!r}")
    if jacobian == "printed" and order != "kaw":
        raise InputError("the printed partials of (1.8.3) are written for the κ–α–ω matrix (1.3.5): use order='kaw'")
    XYZ, xy = _control_points(XYZ, xy, io)
    P = point_weights(weights, len(XYZ))
    if eo0 is None:
        eo0 = approximate_exterior_orientation(XYZ, xy, io, order)
    if isinstance(eo0, ExteriorOrientation):
        x0 = (eo0 if eo0.order == order else eo0.with_order(order)).vector
    else:
        x0 = ExteriorOrientation.from_vector(eo0, order).vector
    tol = np.asarray(DEFAULT_TOL if tol is None else tol, dtype=float)
    linearize = collinearity_linearizer(XYZ, xy, io, order, jacobian)
    history = []

    def record(rec):
        history.append(rec)
        if progress is not None:
            progress(rec)

    def checked(p):
        if not history and np.any(camera_coordinates(XYZ, ExteriorOrientation.from_vector(p, order))[:, 2] >= 0):
            raise InputError("the approximate exterior orientation puts control points behind the camera (Z* >= 0)")
        # A diverging iteration ends up with control points behind the camera: stop there.
        if np.any(camera_coordinates(XYZ, ExteriorOrientation.from_vector(p, order))[:, 2] >= 0):
            raise ConvergenceError(
                f"space resection ({jacobian} partials) diverged: after {len(history)} iterations "
                f"the approximation X_S, Y_S, Z_S = {np.array2string(p[:3], precision=1)} puts control points "
                "behind the camera", list(history))
        return linearize(p)

    try:
        adj = gauss_newton(checked, x0, P, tol=tol, max_iter=max_iter, names=EO_NAMES, progress=record)
    except ConvergenceError as err:
        if str(err).startswith("space resection"):
            raise
        raise ConvergenceError(f"space resection ({jacobian} partials) did not converge: {err}", history) from err
    except DegenerateGeometryError as err:
        if len(history) > 1:     # the start was fine; the iteration ran away into a singular pose
            raise ConvergenceError(f"space resection ({jacobian} partials) diverged: after {len(history)} "
                                   f"iterations {err}", history) from err
        raise DegenerateGeometryError(f"space resection: {err}") from err
    eo = ExteriorOrientation.from_vector(adj.x, order)
    if np.any(camera_coordinates(XYZ, eo)[:, 2] >= 0):
        raise ConvergenceError("space resection converged to a pose with control points behind the camera "
                               "(Z* ≥ 0); give better approximate values", adj.history)
    return ResectionResult(eo, adj, jacobian)


# --- §1.9 ---------------------------------------------------------------------------------------
def angle_equation_count(n_points: int) -> int:
    """Number of equations (1.9.1) that n points give: one per pair, n(n−1)/2 (§1.9)."""
    if n_points < 0:
        raise InputError("the number of points cannot be negative")
    return n_points * (n_points - 1) // 2


def independent_angle_equations(n_points: int) -> int:
    """How many of them are independent: 2n − 3 (§1.9).

    n rays from S are n unit vectors (2n numbers); the angles between them do not change when
    the whole bundle is rotated (3 numbers), so they carry at most 2n − 3 independent values.
    """
    if n_points < 2:
        raise InputError("angles need at least 2 points")
    return 2 * n_points - 3


def _pairs(pairs, n: int) -> tuple:
    if isinstance(pairs, str):
        if pairs != "all":
            raise InputError(f"pairs must be 'all' or a list of (i, j), got {pairs!r}")
        return tuple(itertools.combinations(range(n), 2))
    out = tuple((int(i), int(j)) for i, j in pairs)
    for i, j in out:
        if not (0 <= i < n and 0 <= j < n) or i == j:
            raise InputError(f"pair ({i}, {j}) does not name two different points of {n}")
    if len(out) < 3:
        raise InputError(f"three unknowns need at least 3 pairs, got {len(out)}")
    return out


def resection_by_angles(XYZ, xy, io: InteriorOrientation, center0=None, pairs="all", weights=None,
                        tol=1e-7, max_iter: int = 50,
                        progress: Callable[[IterationRecord], None] | None = None) -> AngleResectionResult:
    """Projection centre from the equality of angles, §1.9, (1.9.1)–(1.9.2).

    For each pair of control points A, B: φ = cos ASB − cos aSb = 0 (1.9.1), the angle at S
    between the object rays equals the angle between the image rays (x − x₀, y − y₀, −f).
    The unknowns are X_S, Y_S, Z_S only; the correction equations
    a_i δX_S + b_i δY_S + c_i δZ_S + l_i = v_i (1.9.2) are iterated by least squares.

    Parameters
    ----------
    XYZ, xy, io
        As for :func:`space_resection` (n ≥ 3 non-collinear points).
    center0 : 3-vector, optional
        Approximate X_S, Y_S, Z_S; if omitted, from :func:`approximate_exterior_orientation`.
    pairs : "all" or sequence of (i, j)
        The pairs of points giving equations; "all" = the n(n−1)/2 pairs, as in the book.
    weights : array, optional
        One weight per pair.
    tol : float
        |δ| threshold in metres.

    Notes
    -----
    Only 2n − 3 of the n(n−1)/2 equations are independent (:func:`independent_angle_equations`).
    The degrees of freedom are nevertheless counted as m − 3, as the book does, so μ and the
    m_j are nominal: they are not the statistically rigorous precisions.
    """
    XYZ, xy = _control_points(XYZ, xy, io)
    pair_list = _pairs(pairs, len(XYZ))
    if center0 is None:
        center0 = approximate_exterior_orientation(XYZ, xy, io).center
    center0 = np.asarray(center0, dtype=float)
    if center0.shape != (3,):
        raise InputError(f"center0 must be (X_S, Y_S, Z_S), got shape {center0.shape}")
    P = None
    if weights is not None:
        P = np.asarray(weights, dtype=float)
        if P.shape != (len(pair_list),):
            raise InputError(f"weights: one per pair expected ({len(pair_list)}), got {P.shape}")
    i, j = np.array(pair_list).T
    residual_fn, jacobian_fn = derivations.angle_equality_model().compile()
    data = (XYZ[i, 0], XYZ[i, 1], XYZ[i, 2], XYZ[j, 0], XYZ[j, 1], XYZ[j, 2],
            xy[i, 0], xy[i, 1], xy[j, 0], xy[j, 1], io.f, io.x0, io.y0)

    def linearize(S):
        return jacobian_fn(*S, *data).T, residual_fn(*S, *data)[0]

    try:
        adj = gauss_newton(linearize, center0, P, tol=tol, max_iter=max_iter, names=CENTER_NAMES,
                           dof=len(pair_list) - 3, progress=progress)
    except ConvergenceError as err:
        raise ConvergenceError(f"resection by equality of angles did not converge: {err}", err.history) from err
    return AngleResectionResult(adj.x, adj, pair_list)


# --- regenerating the example -------------------------------------------------------------------
def implied_noise(XYZ, xy, io: InteriorOrientation, eo: ExteriorOrientation):
    """Noise-free image coordinates of ``eo`` by (1.4.12) and the noise ``xy − exact`` in the data.

    With the §1.8 example's true EO this recovers the random errors the book added (σ = 0.016 mm,
    rounded to 0.001 mm in print), so the example can be regenerated with other noise.
    Returns ``(exact, noise)``, both (n, 2) in mm.
    """
    XYZ = as_points(XYZ, 3, "control point coordinates XYZ")
    xy = as_points(xy, 2, "image coordinates xy")
    if len(XYZ) != len(xy):
        raise InputError(f"{len(XYZ)} control points but {len(xy)} image points: shapes must match")
    exact = project(XYZ, eo, io)
    return exact, xy - exact
