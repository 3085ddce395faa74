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
* Hanzl §2.6 :func:`robust_space_resection` — the same adjustment resistant to blunders (data
  snooping or the Danish method of :func:`photolib.lsq.robust_gauss_newton`), points rejected whole.
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
from .camera import (ExteriorOrientation, InteriorOrientation, _expect, as_point_pairs, as_points,
                     correct_distortion)
from .errors import ConvergenceError, DegenerateGeometryError, InputError
from .lsq import Adjustment, AdjustmentView, IterationRecord, gauss_newton, point_weights, robust_gauss_newton
from .rotation import _numbers, check_order
from .single_image import camera_coordinates, project

__all__ = ["ResectionResult", "AngleResectionResult", "approximate_exterior_orientation", "space_resection",
           "angle_equation_count", "independent_angle_equations", "resection_by_angles", "implied_noise",
           "DEFAULT_TOL", "RobustResectionResult", "robust_space_resection"]

EO_NAMES = ExteriorOrientation.NAMES
CENTER_NAMES = ("Xs", "Ys", "Zs")

DEFAULT_TOL = (1e-7, 1e-7, 1e-7, 1e-10, 1e-10, 1e-10)
"""Convergence thresholds per unknown: 0.1 µm for X_S, Y_S, Z_S and 1e-10 rad for ω, α, κ."""


# --- results -----------------------------------------------------------------------------------
def _pm(value: float, sigma: float, digits: int, unit: str) -> str:
    """``value unit ± sigma unit`` with plain floats (σ omitted when not available)."""
    text = f"{value:.{digits}f}{unit}"
    if np.isfinite(sigma):
        text += f" ± {sigma:.{digits}f}{unit}" if abs(sigma) >= 10 ** -digits else f" ± {sigma:.2g}{unit}"
    return text


@dataclass(repr=False)
class ResectionResult(AdjustmentView):
    """Result of :func:`space_resection` (§1.8).

    Printing it gives a short summary: the centre in metres and the angles in degrees, each
    with its m_j, μ and the number of iterations.

    Attributes
    ----------
    eo : ExteriorOrientation
        The adjusted exterior orientation.
    adjustment : photolib.lsq.Adjustment
        The full least-squares result (order of the unknowns: X_S, Y_S, Z_S, ω, α, κ).
    jacobian : str
        ``"derived"`` or ``"printed"`` partials.
    mu, std, corr, Q, iterations, history
        From the adjustment: μ (1.8.9) in mm with unit weights (unitless with P = 1/σ²),
        m_j (1.8.8) in metres for X_S, Y_S, Z_S and radians for ω, α, κ, r_ij (1.8.10).

    References
    ----------
    Chibunichev (2022), §1.8, eqs. (1.8.2)–(1.8.10).

    Examples
    --------
    >>> io = InteriorOrientation(100.0)
    >>> XYZ = [[1000, 1000, 10], [500, 1500, 15], [1500, 1500, 20], [500, 500, 15], [1500, 500, 20]]
    >>> xy = project(XYZ, ExteriorOrientation.from_degrees(1000, 1000, 1000, 2, 5, 7), io)
    >>> space_resection(XYZ, xy, io)
    ResectionResult (§1.8, derived partials, ... iterations, μ = ...)
      X_S = 1000.000 m ...
      ω = 2.0000° ...
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

    def summary(self) -> str:
        """A few lines: X_S, Y_S, Z_S in m and ω, α, κ in degrees with their m_j; μ; iterations."""
        std = np.asarray(self.std, dtype=float)
        v = self.eo.vector
        lines = [f"ResectionResult (§1.8, {self.jacobian} partials, {self.iterations} iterations, "
                 f"μ = {float(self.mu):.4g}, order {self.eo.order!r})"]
        for k, name in enumerate(("X_S", "Y_S", "Z_S")):
            lines.append(f"  {name} = {_pm(v[k], std[k], 3, ' m')}")
        for k, name in enumerate(("ω", "α", "κ"), start=3):
            lines.append(f"  {name} = {_pm(np.degrees(v[k]), np.degrees(std[k]), 4, '°')}")
        return "\n".join(lines)

    __repr__ = summary


@dataclass(repr=False)
class AngleResectionResult(AdjustmentView):
    """Result of :func:`resection_by_angles` (§1.9): the projection centre and its accuracy.

    μ and m_j are *nominal*: of the n(n−1)/2 equations only 2n−3 are independent, but the
    degrees of freedom are counted as m − 3, as the book does. Printing it gives a short summary.

    Attributes
    ----------
    center : ndarray
        X_S, Y_S, Z_S in metres.
    adjustment : photolib.lsq.Adjustment
        The least-squares result.
    pairs : tuple
        The pairs of points (i, j) that gave equations (1.9.1).
    mu, std, corr, Q, iterations, history
        From the adjustment (nominal, see above); m_j in metres.

    References
    ----------
    Chibunichev (2022), §1.9, eqs. (1.9.1)–(1.9.2).

    Examples
    --------
    >>> io = InteriorOrientation(100.0)
    >>> XYZ = [[1000, 1000, 10], [500, 1500, 15], [1500, 1500, 20], [500, 500, 15], [1500, 500, 20]]
    >>> xy = project(XYZ, ExteriorOrientation.from_degrees(1000, 1000, 1000, 2, 5, 7), io)
    >>> resection_by_angles(XYZ, xy, io).center.round(3)
    array([1000., 1000., 1000.])
    """

    center: np.ndarray
    adjustment: Adjustment
    pairs: tuple

    @property
    def residuals(self) -> np.ndarray:
        """v_i, one per pair of points (cosine units)."""
        return self.adjustment.residuals

    def summary(self) -> str:
        """A few lines: X_S, Y_S, Z_S in m with their (nominal) m_j, μ, pairs and iterations."""
        std = np.asarray(self.std, dtype=float)
        lines = [f"AngleResectionResult (§1.9, {len(self.pairs)} pairs, {self.iterations} iterations, "
                 f"μ = {float(self.mu):.4g}, nominal)"]
        for k, name in enumerate(("X_S", "Y_S", "Z_S")):
            lines.append(f"  {name} = {_pm(float(self.center[k]), std[k], 3, ' m')}")
        return "\n".join(lines)

    __repr__ = summary


# --- input checks ------------------------------------------------------------------------------
def _tolerance(tol, n: int) -> np.ndarray:
    tol = _numbers(tol, "tol")
    try:
        tol = np.broadcast_to(tol, (n,))
    except ValueError:
        raise InputError(f"tol: expected one threshold or {n}, got shape {tol.shape}") from None
    if np.any(tol <= 0):
        raise InputError("tol: the thresholds must be positive")
    return tol


def _iterations(max_iter) -> int:
    if isinstance(max_iter, bool) or not isinstance(max_iter, (int, np.integer)) or max_iter < 1:
        raise InputError(f"max_iter must be a positive integer, got {max_iter!r}")
    return int(max_iter)


def _control_points(XYZ, xy, io):
    _expect(io, InteriorOrientation, "io")
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

    Parameters
    ----------
    XYZ : (n, 3) array
        Control points in metres, n ≥ 2, not all at one place in plan.
    xy : (n, 2) array
        Their image coordinates in mm, not all at one place.
    io : InteriorOrientation
    order : {"kaw", "wak"}
        Sequence of the returned angles (ω = α = 0, so κ is the same in both).

    Returns
    -------
    ExteriorOrientation

    Raises
    ------
    InputError
        Wrong shapes, different counts, fewer than 2 points, NaN/inf, ``io`` of the wrong type.
    DegenerateGeometryError
        All image points (or all control points in plan) coincide: no scale, no κ.

    References
    ----------
    Chibunichev (2022), §1.8 (approximate values of the unknowns for (1.8.3)).

    Examples
    --------
    >>> eo = approximate_exterior_orientation([[0, 0, 0], [100, 0, 0]], [[0, 0], [10, 0]], InteriorOrientation(100.0))
    >>> eo.Zs
    1000.0
    """
    _expect(io, InteriorOrientation, "io")
    check_order(order)
    XYZ, xy = as_point_pairs(XYZ, 3, xy, 2, ("control point coordinates XYZ", "image coordinates xy"), 2,
                             "an approximate exterior orientation")
    z = (xy[:, 0] - io.x0) + 1j * (xy[:, 1] - io.y0)
    w = XYZ[:, 0] + 1j * XYZ[:, 1]
    dz, dw = z - z.mean(), w - w.mean()
    denom = np.sum(np.abs(dz) ** 2)
    if denom <= (1e-9 * max(1.0, float(np.max(np.abs(z))))) ** 2 * len(z):
        raise DegenerateGeometryError("all image points coincide: no approximate orientation possible")
    if np.sum(np.abs(dw) ** 2) <= (1e-9 * max(1.0, float(np.max(np.abs(w))))) ** 2 * len(w):
        raise DegenerateGeometryError("all control points coincide in plan: no approximate orientation possible")
    m = np.sum(np.conj(dz) * dw) / denom                        # N·e^{iκ}
    c = w.mean() - m * z.mean()
    scale = abs(m)
    return ExteriorOrientation(float(c.real), float(c.imag), float(XYZ[:, 2].mean() + scale * io.f),
                               0.0, 0.0, float(np.angle(m)), order)


# --- §1.8 ---------------------------------------------------------------------------------------
def _start_vector(eo0, XYZ, xy, io, order: str) -> np.ndarray:
    """The start values of a resection in ``order``: the given orientation (an
    ExteriorOrientation in any order, or a 6-vector) or, when None, the approximation of §1.9."""
    if eo0 is None:
        eo0 = approximate_exterior_orientation(XYZ, xy, io, order)
    if isinstance(eo0, ExteriorOrientation):
        return (eo0 if eo0.order == order else eo0.with_order(order)).vector
    return ExteriorOrientation.from_vector(eo0, order).vector


def _collinearity_linearizer(XYZ, xy, io: InteriorOrientation, order: str = "kaw", jacobian: str = "derived"):
    """Internal: ``linearize(p) -> (B, L)`` of (1.8.5) for the EO vector p = (X_S, Y_S, Z_S, ω, α, κ).

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

    References
    ----------
    Chibunichev (2022), §1.8, eqs. (1.8.2)–(1.8.10).

    Examples
    --------
    >>> io = InteriorOrientation(100.0)
    >>> XYZ = [[1000, 1000, 10], [500, 1500, 15], [1500, 1500, 20], [500, 500, 15], [1500, 500, 20]]
    >>> xy = project(XYZ, ExteriorOrientation.from_degrees(1000, 1000, 1000, 2, 5, 7), io)
    >>> space_resection(XYZ, xy, io).eo.angles_degrees.round(6)
    array([2., 5., 7.])
    """
    check_order(order)
    if jacobian not in ("derived", "printed"):
        raise InputError(f"jacobian must be 'derived' or 'printed', got {jacobian!r}")
    if jacobian == "printed" and order != "kaw":
        raise InputError("the printed partials of (1.8.3) are written for the κ–α–ω matrix (1.3.5): use order='kaw'")
    XYZ, xy = _control_points(XYZ, xy, io)
    P = point_weights(weights, len(XYZ))
    x0 = _start_vector(eo0, XYZ, xy, io, order)
    tol = _tolerance(DEFAULT_TOL if tol is None else tol, 6)
    max_iter = _iterations(max_iter)
    linearize = _collinearity_linearizer(XYZ, xy, io, order, jacobian)
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


# --- Hanzl §2.6: robust resection ---------------------------------------------------------------
@dataclass(repr=False)
class RobustResectionResult(AdjustmentView):
    """Result of :func:`robust_space_resection`: the EO from the points kept, and the rejected points.

    Attributes
    ----------
    eo : ExteriorOrientation
        From the final adjustment (original weights, outliers removed).
    plain_eo : ExteriorOrientation
        Ordinary least squares with every point (the first pass), for comparison.
    robust : photolib.lsq.RobustAdjustment
        The robust adjustment (pass records, weight history, normalised residuals).
    adjustment : photolib.lsq.Adjustment
        The final adjustment (of the kept points).
    rejected_points : ndarray of bool (n,)
        True for the control points found to be outliers (both coordinates are removed).
    mu, std, corr, Q, iterations, history
        Those of the final adjustment.

    References
    ----------
    Hanzl, Fotogrammetrie, Modul 01, §2.6 (seed 002 lines 313–342); Chibunichev (2022), §1.8.

    Examples
    --------
    >>> io = InteriorOrientation(100.0)
    >>> g = np.linspace(0.0, 2000.0, 4)
    >>> XYZ = np.column_stack([np.repeat(g, 4), np.tile(g, 4), 10.0 * np.arange(16) % 30])
    >>> xy = project(XYZ, ExteriorOrientation.from_degrees(1000, 1000, 1500, 2, 5, 7), io)
    >>> xy = xy + 0.002 * np.sin(np.arange(32.0)).reshape(16, 2); xy[5, 0] += 0.3
    >>> res = robust_space_resection(XYZ, xy, io)
    >>> np.flatnonzero(res.rejected_points).tolist()
    [5]
    """

    eo: ExteriorOrientation
    plain_eo: ExteriorOrientation
    robust: object
    adjustment: Adjustment
    rejected_points: np.ndarray

    @property
    def residuals(self) -> np.ndarray:
        """v_x, v_y of every point (the rejected ones included) at the final EO, (n, 2), mm."""
        return self.robust.residuals.reshape(-1, 2)

    def summary(self) -> str:
        """The robust summary and the final EO."""
        head = self.robust.summary().replace("Robust adjustment", "Robust space resection")
        bad = np.flatnonzero(self.rejected_points).tolist()
        v = self.eo.vector
        return "\n".join([head, f"  rejected points: {bad}",
                          f"  X_S, Y_S, Z_S = {v[0]:.3f}, {v[1]:.3f}, {v[2]:.3f} m",
                          "  ω, α, κ = " + ", ".join(f"{np.degrees(a):.4f}°" for a in v[3:])])

    __repr__ = summary


def robust_space_resection(XYZ, xy, io: InteriorOrientation, eo0=None, order: str = "kaw", weights=None,
                           method: str = "danish", sigma0: float | None = None, tol=None, max_iter: int = 50,
                           **robust_options) -> RobustResectionResult:
    """Space resection resistant to blunders: data snooping or the Danish method (Hanzl §2.6).

    The same correction equations as :func:`space_resection` (the sympy Jacobian of (1.8.2)),
    adjusted by :func:`photolib.lsq.robust_gauss_newton` with the two coordinates of a point as one
    group: a point is rejected as a whole. The final EO is adjusted with the original weights of
    the points kept.

    Parameters
    ----------
    XYZ, xy, io, eo0, order, weights, tol, max_iter
        As for :func:`space_resection` (the derived partials are used).
    method : {"danish", "snooping"}
    sigma0 : float, optional
        A-priori σ₀ in the units of √p·xy (mm with unit weights); estimated if omitted.
    **robust_options
        Passed to :func:`photolib.lsq.robust_gauss_newton` (``exponents``, ``k``,
        ``reject_below``, ``critical``, ``max_passes``, ``progress`` …).

    Returns
    -------
    RobustResectionResult

    Raises
    ------
    InputError
        As :func:`space_resection`; fewer than 4 points (no redundancy); bad robust options.
    DegenerateGeometryError
        Collinear control points; too many points rejected to determine the EO.
    ConvergenceError
        A pass or the re-weighting did not converge.

    References
    ----------
    Hanzl, Fotogrammetrie, Modul 01, §2.6 (seed 002 lines 313–342) and §3.2.1 (resection);
    Chibunichev (2022), §1.8, eqs. (1.8.2)–(1.8.10).

    Examples
    --------
    >>> io = InteriorOrientation(100.0)
    >>> g = np.linspace(0.0, 2000.0, 4)
    >>> XYZ = np.column_stack([np.repeat(g, 4), np.tile(g, 4), 10.0 * np.arange(16) % 30])
    >>> xy = project(XYZ, ExteriorOrientation.from_degrees(1000, 1000, 1500, 2, 5, 7), io)
    >>> xy[[3, 9], 1] -= 0.4
    >>> res = robust_space_resection(XYZ, xy, io, method="snooping", sigma0=0.005)
    >>> np.flatnonzero(res.rejected_points).tolist(), res.eo.vector[:3].round(3)
    ([3, 9], array([1000., 1000., 1500.]))
    """
    check_order(order)
    XYZ, xy = _control_points(XYZ, xy, io)
    if len(XYZ) < 4:
        raise InputError(f"a robust resection needs redundancy: at least 4 control points, got {len(XYZ)}")
    P = point_weights(weights, len(XYZ))
    x0 = _start_vector(eo0, XYZ, xy, io, order)
    if np.any(camera_coordinates(XYZ, ExteriorOrientation.from_vector(x0, order))[:, 2] >= 0):
        raise InputError("the approximate exterior orientation puts control points behind the camera (Z* >= 0)")
    tol = _tolerance(DEFAULT_TOL if tol is None else tol, 6)
    max_iter = _iterations(max_iter)
    linearize = _collinearity_linearizer(XYZ, xy, io, order, "derived")
    try:
        rob = robust_gauss_newton(linearize, x0, P, method=method, sigma0=sigma0, group=2, tol=tol,
                                  max_iter=max_iter, names=EO_NAMES, **robust_options)
    except TypeError as err:
        raise InputError(f"robust_space_resection: {err}") from None
    eo = ExteriorOrientation.from_vector(rob.x, order)
    kept = ~rob.rejected[0::2]
    if np.any(camera_coordinates(XYZ[kept], eo)[:, 2] >= 0):
        raise ConvergenceError("the robust resection converged to a pose with control points behind the camera "
                               "(Z* ≥ 0); give better approximate values", rob.adjustment.history)
    return RobustResectionResult(eo, ExteriorOrientation.from_vector(rob.plain.x, order), rob, rob.adjustment,
                                 rob.rejected[0::2].copy())


# --- §1.9 ---------------------------------------------------------------------------------------
def _count(n_points, least: int) -> int:
    if isinstance(n_points, bool) or not isinstance(n_points, (int, np.integer)):
        raise InputError(f"the number of points must be an integer, got {n_points!r}")
    if n_points < least:
        raise InputError(f"the number of points must be at least {least}, got {n_points}")
    return int(n_points)


def angle_equation_count(n_points: int) -> int:
    """Number of equations (1.9.1) that n points give: one per pair, n(n−1)/2 (§1.9).

    Parameters
    ----------
    n_points : int
        Number of control points, ≥ 0.

    Returns
    -------
    int
        n(n−1)/2.

    Raises
    ------
    InputError
        A negative number or not an integer.

    References
    ----------
    Chibunichev (2022), §1.9, eq. (1.9.1).

    Examples
    --------
    >>> angle_equation_count(5)
    10
    """
    n_points = _count(n_points, 0)
    return n_points * (n_points - 1) // 2


def independent_angle_equations(n_points: int) -> int:
    """How many of them are independent: 2n − 3 (§1.9).

    n rays from S are n unit vectors (2n numbers); the angles between them do not change when
    the whole bundle is rotated (3 numbers), so they carry at most 2n − 3 independent values.

    Parameters
    ----------
    n_points : int
        Number of control points, ≥ 2.

    Returns
    -------
    int
        2n − 3.

    Raises
    ------
    InputError
        Fewer than 2 points or not an integer.

    References
    ----------
    Chibunichev (2022), §1.9.

    Examples
    --------
    >>> independent_angle_equations(5)
    7
    """
    n_points = _count(n_points, 2)
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
    max_iter : int
    progress : callable, optional
        Called with every :class:`~photolib.lsq.IterationRecord`.

    Returns
    -------
    AngleResectionResult
        ``center``, nominal μ and m_j, residuals per pair, iteration history.

    Raises
    ------
    InputError
        Fewer than 3 points or pairs, bad pairs, wrong shapes, NaN/inf, weights ≤ 0.
    DegenerateGeometryError
        Collinear control points or a singular normal matrix.
    ConvergenceError
        The iteration did not settle in ``max_iter`` steps.

    Notes
    -----
    Only 2n − 3 of the n(n−1)/2 equations are independent (:func:`independent_angle_equations`).
    The degrees of freedom are nevertheless counted as m − 3, as the book does, so μ and the
    m_j are nominal: they are not the statistically rigorous precisions.

    References
    ----------
    Chibunichev (2022), §1.9, eqs. (1.9.1)–(1.9.2).

    Examples
    --------
    >>> io = InteriorOrientation(100.0)
    >>> XYZ = [[1000, 1000, 10], [500, 1500, 15], [1500, 1500, 20], [500, 500, 15], [1500, 500, 20]]
    >>> xy = project(XYZ, ExteriorOrientation.from_degrees(1000, 1000, 1000, 2, 5, 7), io)
    >>> resection_by_angles(XYZ, xy, io).center.round(3)
    array([1000., 1000., 1000.])
    """
    XYZ, xy = _control_points(XYZ, xy, io)
    pair_list = _pairs(pairs, len(XYZ))
    if center0 is None:
        center0 = approximate_exterior_orientation(XYZ, xy, io).center
    center0 = _numbers(center0, "center0")
    if center0.shape != (3,):
        raise InputError(f"center0 must be (X_S, Y_S, Z_S), got shape {center0.shape}")
    tol = _tolerance(tol, 3)
    max_iter = _iterations(max_iter)
    P = None
    if weights is not None:
        P = _numbers(weights, "weights")
        if P.shape != (len(pair_list),):
            raise InputError(f"weights: one per pair expected ({len(pair_list)}), got {P.shape}")
        if np.any(P <= 0):
            raise InputError("weights must be positive")
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

    Parameters
    ----------
    XYZ : (n, 3) array
        Control points in metres.
    xy : (n, 2) array
        Their measured image coordinates in mm.
    io : InteriorOrientation
    eo : ExteriorOrientation
        The true pose.

    Returns
    -------
    (exact, noise)
        Both (n, 2) in mm.

    Raises
    ------
    InputError
        Wrong shapes, different counts, NaN/inf, ``io``/``eo`` of the wrong type.
    PointBehindCameraError
        A control point behind the camera of ``eo``.

    References
    ----------
    Chibunichev (2022), §1.8 (the example's data), eq. (1.4.12).

    Examples
    --------
    >>> io, eo = InteriorOrientation(100.0), ExteriorOrientation(0.0, 0.0, 1000.0)
    >>> exact, noise = implied_noise([[100.0, 50.0, 0.0]], [[10.001, 5.0]], io, eo)
    >>> noise.round(6)
    array([[0.001, 0.   ]])
    """
    _expect(io, InteriorOrientation, "io")
    _expect(eo, ExteriorOrientation, "eo")
    XYZ, xy = as_point_pairs(XYZ, 3, xy, 2, ("control points XYZ", "image points xy"), 1, "implied_noise")
    exact = project(XYZ, eo, io)
    return exact, xy - exact
