"""The one least-squares engine — Chapter 1, §1.8, eqs. (1.8.5)–(1.8.10); Chapter 3, §3.5–§3.9.

Every adjustment of the book is solved the same way. The model is linearised at the current
approximation into correction equations

    B·δ + L = V                                  (1.8.5)

(``B`` the partial derivatives, ``L`` the free terms = the model functions at the
approximation, ``V`` the residuals), turned into normal equations

    N·δ + Lᴺ = 0,   N = BᵀPB,   Lᴺ = BᵀPL        (1.8.6)

and solved as δ = −Q·Lᴺ with Q = N⁻¹ (1.8.7). The approximation is corrected by δ and the
process repeats until the corrections are negligible. At the end the engine reports the
a-posteriori accuracy

    μ = √(VᵀPV / (m − n))                         (1.8.9)
    m_j = μ·√Q_jj                                 (1.8.8)
    r_ij = Q_ij / √(Q_ii·Q_jj)                    (1.8.10)

and, where the design matrix is at hand, the redundancy numbers r_i = 1 − (B·Q·BᵀP)_ii
(:func:`redundancy_numbers`).

Robust adjustment (Hanzl, Fotogrammetrie, Modul 01, §2.6, seed 002 lines 313–342) is an option
of the same loop: :func:`robust_gauss_newton` repeats :func:`gauss_newton` with changed weights —
data snooping with the normalised residuals w_i = |v_i √p_i| / (σ₀ √r_i)
(:func:`normalized_residuals`) or the Danish method with the weight function exp(−0.05·t^d)
(:func:`danish_weight`) — and ends with the original weights of the observations kept.

There is **one** Gauss–Newton loop (``_iterate``) with two pluggable linear solvers:

* dense — :func:`solve_normal_equations`, for every problem of a handful of unknowns
  (:func:`gauss_newton`: resection, relative orientation, DLT, ...);
* block-sparse — :func:`solve_block_normal_equations`, for bundle blocks (§3.5): the points are
  eliminated by (3.5.16) with 3×3 block inverses, the reduced system of the image unknowns is
  factorised by a band Cholesky; block-wide ("global") unknowns — self-calibration (§3.6), rig
  mounting elements (§3.8) — join the reduced system (:func:`block_gauss_newton`).

Both give one result type, :class:`Adjustment`. Weights are spelled ``weights`` (a vector of
p_i = 1/m_i² or a matrix P); the sign convention is B·δ + L = V, δ = −Q·BᵀPL.
"""

from __future__ import annotations

import contextlib
import functools
import time
from dataclasses import dataclass, field
from typing import Callable, Sequence

import numpy as np
from threadpoolctl import ThreadpoolController

from .errors import ConvergenceError, DegenerateGeometryError, InputError

__all__ = ["Adjustment", "AdjustmentView", "IterationRecord", "BlockCorrectionEquations",
           "GlobalBlockCorrectionEquations", "BlockSolution", "gauss_newton", "block_gauss_newton",
           "solve_normal_equations", "solve_block_normal_equations", "solve_partitioned_normal_equations",
           "accuracy", "redundancy_numbers", "point_weights", "block_equations_dense",
           "global_block_equations_dense", "blas_on_one_thread", "RobustIterationRecord", "RobustAdjustment",
           "robust_gauss_newton", "normalized_residuals", "danish_weight", "DANISH_EXPONENTS", "DANISH_FACTOR",
           "SNOOPING_CRITICAL"]

_REF_18 = "Chibunichev (2022), §1.8, eqs. (1.8.5)–(1.8.10)"


@dataclass
class IterationRecord:
    """One step of the iteration: the approximation used, the correction found, and VᵀPV.

    Attributes
    ----------
    iteration : int
        1 for the first step.
    x : ndarray
        The approximation the step was linearised at (empty for block adjustments).
    delta : ndarray
        The corrections δ (block adjustments: max |δ| of the images, points[, globals]).
    vtpv : float
        VᵀPV of the free terms at ``x`` (1.8.9).

    References
    ----------
    Chibunichev (2022), §1.8, eqs. (1.8.5)–(1.8.7).

    Examples
    --------
    >>> import numpy as np
    >>> IterationRecord(1, np.zeros(2), np.array([0.5, -0.1]), 2.0).vtpv
    2.0
    """

    iteration: int
    x: np.ndarray
    delta: np.ndarray
    vtpv: float


@dataclass(repr=False)
class Adjustment:
    """Result of a least-squares adjustment with its a-posteriori accuracy (1.8.8)–(1.8.10).

    The one result type of the engine: :func:`gauss_newton` fills the dense fields (``Q``,
    ``std``, ``corr``, ``names``), :func:`block_gauss_newton` the block fields (``frames``,
    ``points``, ``globals``, cofactor blocks ``Q1``…``Q23``, ``timings``).

    Attributes
    ----------
    x : ndarray
        Adjusted unknowns (block adjustments: frames, free and fixed points, globals, flattened).
    residuals : ndarray
        V at the solution (block adjustments: (m, r) of the image observations).
    mu : float
        μ, r.m.s. error of unit weight (1.8.9) / (3.5.12).
    Q : ndarray or None
        Cofactor matrix N⁻¹ (dense adjustments).
    std : ndarray or None
        m_j = μ√Q_jj (1.8.8).
    corr : ndarray or None
        Correlation matrix r_ij (1.8.10).
    dof : int
        m − n, the number of redundant observations.
    iterations : int
        Steps taken.
    converged : bool
        Always True for a returned result (non-convergence raises).
    history : list of IterationRecord
        One record per step.
    names : tuple of str
        Names of the unknowns (dense adjustments).
    frames, points, globals : ndarray or None
        Block adjustments: (n, q) image unknowns, (k, 3) points, (g,) block-wide unknowns.
    frame_residuals, point_residuals, global_residuals : ndarray or None
        V of the direct observations of those unknowns ((3.5.17)–(3.5.19)); zeros where none.
    frames_std, points_std, globals_std : ndarray or None
        m_j (3.5.11) of each group (when the covariance was computed).
    Q1, Q2, Q3, Q13, Q23 : ndarray or None
        Cofactor blocks: per image (n, q, q), per point (k, 3, 3), globals (g, g), image × global
        (n, q, g), point × global (k, 3, g).
    timings : dict
        Seconds spent per stage (block adjustments).

    References
    ----------
    Chibunichev (2022), §1.8, eqs. (1.8.5)–(1.8.10); §3.5, eqs. (3.5.9)–(3.5.12).

    Examples
    --------
    >>> import numpy as np
    >>> t, y = np.array([0., 1., 2., 3.]), np.array([1.1, 2.9, 5.2, 6.8])
    >>> adj = gauss_newton(lambda x: (np.column_stack([np.ones(4), t]), x[0] + x[1] * t - y),
    ...                    [0., 0.], names=("a", "b"))
    >>> print(adj.summary())
    Least-squares adjustment (§1.8): 2 iterations, 4 observations, 2 unknowns, dof 2
      mu = 0.202485 (r.m.s. error of unit weight)
      a = 1.09 ± 0.169411
      b = 1.94 ± 0.0905539
    """

    x: np.ndarray
    residuals: np.ndarray
    mu: float
    Q: np.ndarray | None
    std: np.ndarray | None
    corr: np.ndarray | None
    dof: int
    iterations: int
    converged: bool = True
    history: list = field(default_factory=list)
    names: tuple = ()
    frames: np.ndarray | None = None
    points: np.ndarray | None = None
    globals: np.ndarray | None = None
    frame_residuals: np.ndarray | None = None
    point_residuals: np.ndarray | None = None
    global_residuals: np.ndarray | None = None
    frames_std: np.ndarray | None = None
    points_std: np.ndarray | None = None
    globals_std: np.ndarray | None = None
    Q1: np.ndarray | None = None
    Q2: np.ndarray | None = None
    Q3: np.ndarray | None = None
    Q13: np.ndarray | None = None
    Q23: np.ndarray | None = None
    timings: dict = field(default_factory=dict)
    design: tuple | None = None       # (B, weights) at the solution, dense adjustments only

    @property
    def covariance(self) -> np.ndarray:
        """μ²·Q, the estimated covariance matrix of the unknowns (dense adjustments)."""
        if self.Q is None:
            raise InputError("no full cofactor matrix Q: a block adjustment keeps only its blocks Q1…Q23")
        return self.mu ** 2 * self.Q

    @property
    def redundancy(self) -> np.ndarray:
        """Redundancy numbers r_i = 1 − (B·Q·BᵀP)_ii of the observations (:func:`redundancy_numbers`)."""
        if self.design is None or self.Q is None:
            raise InputError("redundancy numbers need the design matrix: only dense adjustments keep it")
        B, P = self.design
        return redundancy_numbers(B, self.Q, P)

    def as_dict(self) -> dict:
        """Unknowns by name (needs ``names``)."""
        return dict(zip(self.names, self.x))

    def summary(self) -> str:
        """A short readable text: iterations, μ, dof and every named unknown with ± m_j."""
        n_obs = int(np.size(self.residuals)) if self.frames is None else None
        if self.frames is None:
            head = (f"Least-squares adjustment (§1.8): {self.iterations} iterations, {n_obs} observations, "
                    f"{self.x.size} unknowns, dof {self.dof}")
        else:
            g = 0 if self.globals is None else self.globals.size
            head = (f"Block adjustment (§3.5): {self.iterations} iterations, {len(self.frames)} images, "
                    f"{len(self.points)} points, {g} block-wide unknowns, dof {self.dof}")
        lines = [head, f"  mu = {float(self.mu):.6g} (r.m.s. error of unit weight)"]
        if self.frames is None:
            names = self.names or tuple(f"x{i}" for i in range(self.x.size))
            std = self.std if self.std is not None else np.full(self.x.size, np.nan)
            lines += [f"  {nm} = {float(v):.6g} ± {float(s):.6g}" for nm, v, s in zip(names, self.x, std)]
        elif self.globals is not None and self.globals.size:
            names = self.names or tuple(f"global {i}" for i in range(self.globals.size))
            std = self.globals_std if self.globals_std is not None else np.full(self.globals.size, np.nan)
            lines += [f"  {nm} = {float(v):.6g} ± {float(s):.6g}" for nm, v, s in zip(names, self.globals, std)]
        return "\n".join(lines)

    def __repr__(self) -> str:
        kind = "dense" if self.frames is None else "block"
        return (f"<Adjustment ({kind}): {self.x.size} unknowns, mu={float(self.mu):.6g}, dof={self.dof}, "
                f"{self.iterations} iterations>")


class AdjustmentView:
    """Mixin for result objects that hold an :class:`Adjustment` as ``self.adjustment``.

    Gives them the a-posteriori accuracy of (1.8.8)–(1.8.10) and the iteration record under
    the same names as :class:`Adjustment`.

    Attributes
    ----------
    mu, std, corr, Q, iterations, history
        Those of ``self.adjustment``.

    References
    ----------
    Chibunichev (2022), §1.8, eqs. (1.8.8)–(1.8.10).

    Examples
    --------
    >>> import numpy as np
    >>> class Fit(AdjustmentView):
    ...     def __init__(self, adjustment):
    ...         self.adjustment = adjustment
    >>> t, y = np.array([0., 1., 2., 3.]), np.array([1.1, 2.9, 5.2, 6.8])
    >>> fit = Fit(gauss_newton(lambda x: (np.column_stack([np.ones(4), t]), x[0] + x[1] * t - y), [0., 0.]))
    >>> fit.iterations, round(fit.mu, 4)
    (2, 0.2025)
    """

    @property
    def mu(self) -> float:
        """μ, the r.m.s. error of unit weight (1.8.9)."""
        return self.adjustment.mu

    @property
    def std(self) -> np.ndarray:
        """m_j = μ√Q_jj (1.8.8), in the units of the unknowns."""
        return self.adjustment.std

    @property
    def corr(self) -> np.ndarray:
        """The correlation matrix r_ij (1.8.10)."""
        return self.adjustment.corr

    @property
    def Q(self) -> np.ndarray:
        """The cofactor matrix Q = N⁻¹ (1.8.7)."""
        return self.adjustment.Q

    @property
    def iterations(self) -> int:
        return self.adjustment.iterations

    @property
    def history(self) -> list:
        """One :class:`IterationRecord` per iteration (approximation used, δ, VᵀPV)."""
        return self.adjustment.history


def _as_weights(P, m: int):
    if P is None:
        return None
    try:
        P = np.asarray(P, dtype=float)
    except (TypeError, ValueError) as exc:
        raise InputError(f"weights must be numbers: {exc}") from None
    if P.ndim == 1:
        if P.shape != (m,):
            raise InputError(f"weights: expected {m} values, got {P.shape[0]}")
    elif P.shape != (m, m):
        raise InputError(f"weight matrix: expected shape ({m}, {m}), got {P.shape}")
    if not np.all(np.isfinite(P)):
        raise InputError("weights contain NaN or inf")
    if P.ndim == 1 and np.any(P <= 0):
        raise InputError("weights p_i = 1/m_i² must be positive (1.8.6)")
    if P.ndim == 2 and np.any(np.diag(P) <= 0):
        raise InputError("the weight matrix must have a positive diagonal (1.8.6)")
    return P


def _weighted(P, M):
    if P is None:
        return M
    if P.ndim == 1:
        return P[:, None] * M if M.ndim == 2 else P * M
    return P @ M


def point_weights(weights, n: int):
    """Weights of 2-D point observations as one value per coordinate, ordered x₁, y₁, x₂, …

    Parameters
    ----------
    weights : None or array_like
        None (unit weights), one per point (n,), one per coordinate (n, 2), or already flat (2n,).
        All must be finite and positive (p_i = 1/m_i², (1.8.6)).
    n : int
        Number of points.

    Returns
    -------
    ndarray (2n,) or None
        The weights per coordinate; None for unit weights.

    Raises
    ------
    InputError
        A wrong shape, NaN/inf, or a weight ≤ 0.

    References
    ----------
    Chibunichev (2022), §1.8, eq. (1.8.6) (P = diag(1/m_i²)).

    Examples
    --------
    >>> point_weights([1.0, 4.0], 2)
    array([1., 1., 4., 4.])
    """
    if weights is None:
        return None
    try:
        w = np.asarray(weights, dtype=float)
    except (TypeError, ValueError) as exc:
        raise InputError(f"weights must be numbers: {exc}") from None
    if w.shape == (n,):
        w = np.repeat(w, 2)
    elif w.shape == (n, 2):
        w = w.ravel()
    elif w.shape != (2 * n,):
        raise InputError(f"weights: expected shape ({n},), ({n}, 2) or ({2 * n},), got {w.shape}")
    if not np.all(np.isfinite(w)) or np.any(w <= 0):
        raise InputError("weights must be finite and positive (p_i = 1/m_i²)")
    return w


def _weighted_square_sum(V, P=None) -> float:
    """VᵀPV."""
    V = np.asarray(V, dtype=float)
    return float(V @ _weighted(P, V))



def _floats(value, what):
    try:
        return np.asarray(value, dtype=float)
    except (TypeError, ValueError) as exc:
        raise InputError(f"{what} must be numbers: {exc}") from None


def _as_matrix(value, what, ndim):
    a = _floats(value, what)
    if a.ndim != ndim:
        raise InputError(f"{what} must have {ndim} dimension(s), got shape {a.shape}")
    return a


def solve_normal_equations(B, L, weights=None, names: Sequence[str] = (), rcond: float = 1e-12):
    """One linear least-squares step: δ = −(BᵀPB)⁻¹BᵀPL, (1.8.6)–(1.8.7).

    Parameters
    ----------
    B : array_like (m, n)
        Partial derivatives of the correction equations B·δ + L = V (1.8.5).
    L : array_like (m,)
        Free terms (model value at the approximation minus the measurement).
    weights : array_like (m,) or (m, m), optional
        Weights p_i = 1/m_i² (a diagonal P) or a full matrix P; None means unit weights.
        (Positional use as the third argument is kept from the former name ``P``.)
    names : sequence of str, optional
        Names of the unknowns, used in the message of a singular N.
    rcond : float
        Smallest acceptable eigenvalue ratio of N scaled to unit diagonal.

    Returns
    -------
    delta : ndarray (n,)
        The corrections δ = −Q·BᵀPL.
    Q : ndarray (n, n)
        The cofactor matrix N⁻¹.

    Raises
    ------
    InputError
        Wrong shapes, NaN/inf, fewer equations than unknowns, non-positive weights.
    DegenerateGeometryError
        N singular or numerically rank-deficient; the message names the unknowns involved.

    References
    ----------
    Chibunichev (2022), §1.8, eqs. (1.8.5)–(1.8.7).

    Examples
    --------
    >>> import numpy as np
    >>> B = np.array([[1.0, 0.0], [1.0, 1.0], [1.0, 2.0]])
    >>> delta, Q = solve_normal_equations(B, np.array([-1.0, -2.0, -3.0]))
    >>> delta.round(6)
    array([1., 1.])
    """
    B, L = _floats(B, "B"), _floats(L, "L")
    if B.ndim != 2 or L.ndim != 1 or B.shape[0] != L.shape[0]:
        raise InputError(f"correction equations: B must be m×n and L of length m, got {B.shape} and {L.shape}")
    m, n = B.shape
    if m < n:
        raise InputError(f"{m} correction equations cannot determine {n} unknowns")
    if not (np.all(np.isfinite(B)) and np.all(np.isfinite(L))):
        raise InputError("the correction equations contain NaN or inf")
    if n == 0:
        raise InputError("no unknowns: B has no columns")
    P = _as_weights(weights, m)
    PB = _weighted(P, B)
    N = B.T @ PB
    LN = PB.T @ L
    # Scale N to unit diagonal before judging its rank: unknowns of different units
    # (metres, radians) must not look singular only because of their scale.
    d = np.sqrt(np.diag(N))
    if np.any(d == 0):
        missing = [names[i] if i < len(names) else f"unknown {i}" for i in np.flatnonzero(d == 0)]
        raise DegenerateGeometryError(f"the observations do not depend on {', '.join(missing)}")
    Ns = N / np.outer(d, d)
    eigval, eigvec = np.linalg.eigh(Ns)
    if eigval[0] < rcond * eigval[-1]:
        weak = np.argsort(-np.abs(eigvec[:, 0]))[:3]
        label = ", ".join(names[i] if i < len(names) else f"unknown {i}" for i in weak)
        raise DegenerateGeometryError(
            f"normal matrix is singular (condition {eigval[-1] / max(eigval[0], 1e-300):.1e}); "
            f"the geometry does not determine a combination of {label}")
    Qs = (eigvec / eigval) @ eigvec.T
    Q = Qs / np.outer(d, d)
    delta = -Q @ LN
    return delta, Q


def accuracy(V, Q, weights=None, dof: int | None = None):
    """μ, m_j and r_ij of (1.8.8)–(1.8.10) from the residuals ``V`` and cofactors ``Q``.

    Parameters
    ----------
    V : array_like (m,)
        Residuals of the observations.
    Q : array_like (n, n)
        Cofactor matrix N⁻¹.
    weights : array_like (m,) or (m, m), optional
        Weights (unit if omitted).
    dof : int, optional
        Redundancy m − n if not given.

    Returns
    -------
    mu : float
        μ = √(VᵀPV/dof) (1.8.9); NaN when dof ≤ 0.
    std : ndarray (n,)
        m_j = μ√Q_jj (1.8.8).
    corr : ndarray (n, n)
        r_ij = Q_ij/√(Q_ii Q_jj) (1.8.10).

    Raises
    ------
    InputError
        Shapes that do not match, NaN/inf.

    References
    ----------
    Chibunichev (2022), §1.8, eqs. (1.8.8)–(1.8.10).

    Examples
    --------
    >>> import numpy as np
    >>> mu, std, corr = accuracy(np.array([0.1, -0.1, 0.1, -0.1]), np.diag([1.0, 4.0]))
    >>> round(mu, 4), std.round(4)
    (0.1414, array([0.1414, 0.2828]))
    """
    V = _as_matrix(V, "V", 1)
    Q = _as_matrix(Q, "Q", 2)
    n = Q.shape[0]
    if Q.shape != (n, n):
        raise InputError(f"Q must be square, got {Q.shape}")
    if not (np.all(np.isfinite(V)) and np.all(np.isfinite(Q))):
        raise InputError("residuals or cofactors contain NaN or inf")
    dof = V.shape[0] - n if dof is None else dof
    vtpv = _weighted_square_sum(V, _as_weights(weights, V.shape[0]))
    mu = float(np.sqrt(vtpv / dof)) if dof > 0 else float("nan")
    q = np.sqrt(np.diag(Q))
    return mu, mu * q, Q / np.outer(q, q)


def redundancy_numbers(B, Q, weights=None):
    """Redundancy numbers r_i = 1 − (B·Q·BᵀP)_ii of the observations.

    r_i is the share of observation i in the redundancy: Σ r_i = m − n, 0 ≤ r_i ≤ 1; an
    observation with r_i ≈ 0 is not checked by the others (a blunder in it cannot show in its
    residual), and the standardised residual of data snooping is w_i = v_i / (μ·√(r_i / p_i))
    (unit weights: v_i / (μ√r_i)). With a full weight matrix (B Q Bᵀ P)_ii = Σ_j (BQBᵀ)_ij P_ji.

    Parameters
    ----------
    B : array_like (m, n)
        Design matrix of the correction equations (1.8.5) at the solution.
    Q : array_like (n, n)
        Cofactor matrix N⁻¹ = (BᵀPB)⁻¹.
    weights : array_like (m,) or (m, m), optional
        Weights P (unit if omitted).

    Returns
    -------
    ndarray (m,)
        r_i for every observation.

    Raises
    ------
    InputError
        Shapes that do not match, NaN/inf, non-positive weights.

    References
    ----------
    Chibunichev (2022), §1.8, eqs. (1.8.6)–(1.8.7) (Q = N⁻¹); §2.7 (blunder detection by the
    residuals of relative orientation).

    Examples
    --------
    >>> import numpy as np
    >>> B = np.ones((4, 1))                  # four direct measurements of one quantity
    >>> redundancy_numbers(B, np.array([[0.25]]))
    array([0.75, 0.75, 0.75, 0.75])
    """
    B = _as_matrix(B, "B", 2)
    Q = _as_matrix(Q, "Q", 2)
    m, n = B.shape
    if Q.shape != (n, n):
        raise InputError(f"Q must be {n}×{n} for a B of {n} columns, got {Q.shape}")
    if not (np.all(np.isfinite(B)) and np.all(np.isfinite(Q))):
        raise InputError("B or Q contain NaN or inf")
    P = _as_weights(weights, m)
    BQ = B @ Q
    if P is None:
        h = np.einsum("ij,ij->i", BQ, B)
    elif P.ndim == 1:
        h = np.einsum("ij,ij->i", BQ, B) * P
    else:
        h = np.einsum("ij,jk,ki->i", BQ, B.T, P)
    return 1.0 - h


# --- the one Gauss–Newton loop ------------------------------------------------------------------
def _iterate(solver, state, max_iter: int, progress):
    """Gauss–Newton: linearise, solve the normal equations, correct, until δ is negligible (§1.8).

    ``solver`` supplies the problem-specific parts: ``linearize(state) -> eq``,
    ``step(eq, state, iteration, history) -> (delta, vtpv)`` (the linear solver),
    ``record(iteration, state, delta, vtpv) -> IterationRecord``, ``update(state, delta)``,
    ``finite(state)``, ``converged(delta)``, ``no_convergence(max_iter, delta) -> str``,
    ``finish(state, history) -> Adjustment`` and ``watch_divergence`` (four growths of VᵀPV in a
    row raise :class:`ConvergenceError`).
    """
    history, growth = [], 0
    delta = None
    for iteration in range(1, max_iter + 1):
        eq = solver.linearize(state)
        delta, vtpv = solver.step(eq, state, iteration, history)
        record = solver.record(iteration, state, delta, vtpv)
        history.append(record)
        if progress is not None:
            progress(record)
        if solver.watch_divergence:
            if len(history) > 1 and vtpv > history[-2].vtpv * (1 + 1e-9):
                growth += 1
                if growth >= 4:
                    raise ConvergenceError(f"diverging: VᵀPV grew in {growth} consecutive iterations", history)
            else:
                growth = 0
        state = solver.update(state, delta)
        if not solver.finite(state):
            raise ConvergenceError(f"the iteration produced NaN/inf at step {iteration}", history)
        if solver.converged(delta):
            break
    else:
        raise ConvergenceError(solver.no_convergence(max_iter, delta), history)
    return solver.finish(state, history)


class _DenseSolver:
    """The dense linear solver of :func:`gauss_newton`: x is one vector, δ from (1.8.7)."""

    watch_divergence = False

    def __init__(self, linearize, weights, names, dof, tol):
        self._linearize, self.P, self.names, self.dof, self.tol = linearize, weights, tuple(names), dof, tol

    def linearize(self, x):
        return self._linearize(x)

    def step(self, eq, x, iteration, history):
        B, L = eq
        delta, _ = solve_normal_equations(B, L, self.P, self.names)
        return delta, _weighted_square_sum(L, _as_weights(self.P, len(L)))

    @staticmethod
    def record(iteration, x, delta, vtpv):
        return IterationRecord(iteration, x.copy(), delta, vtpv)

    @staticmethod
    def update(x, delta):
        return x + delta

    @staticmethod
    def finite(x):
        return bool(np.all(np.isfinite(x)))

    def converged(self, delta):
        return bool(np.all(np.abs(delta) < self.tol))

    @staticmethod
    def no_convergence(max_iter, delta):
        return f"no convergence in {max_iter} iterations: last corrections {np.array2string(delta, precision=3)}"

    def finish(self, x, history):
        B, L = self.linearize(x)
        delta, Q = solve_normal_equations(B, L, self.P, self.names)
        V = B @ delta + L
        P = _as_weights(self.P, len(L))
        mu, std, corr = accuracy(V, Q, P, self.dof)
        return Adjustment(x=x + delta, residuals=V, mu=mu, Q=Q, std=std, corr=corr,
                          dof=V.shape[0] - x.shape[0] if self.dof is None else self.dof,
                          iterations=len(history), converged=True, history=history, names=self.names,
                          design=(np.asarray(B, dtype=float), P))


def gauss_newton(linearize: Callable[[np.ndarray], tuple], x0, weights=None, *, tol=1e-10,
                 max_iter: int = 50, names: Sequence[str] = (), dof: int | None = None,
                 progress: Callable[[IterationRecord], None] | None = None, **legacy) -> Adjustment:
    """Iterate the correction equations of a nonlinear problem to convergence (§1.8).

    The dense solver of the one Gauss–Newton loop: each step solves (1.8.6)–(1.8.7) by
    :func:`solve_normal_equations`; after convergence the problem is linearised once more and
    the last (negligible) correction is applied, so that the residuals V = B·δ + L, μ (1.8.9),
    m_j (1.8.8) and r_ij (1.8.10) belong to the returned estimate.

    Parameters
    ----------
    linearize : callable
        ``linearize(x) -> (B, L)``: the partial derivatives and free terms at ``x``, (1.8.5).
    x0 : array_like (n,)
        Approximate values of the unknowns.
    weights : array_like (m,) or (m, m), optional
        Weights of the observations (vector p_i = 1/m_i² or matrix P); unit weights if omitted.
        May be given positionally (third argument); ``P=`` is accepted as the former keyword.
    tol : float or array_like (n,)
        Convergence when every |δ_j| < tol_j (give an array for unknowns of different units).
    max_iter : int
        Iterations allowed before :class:`ConvergenceError` is raised.
    names : sequence of str, optional
        Names of the unknowns (messages, :meth:`Adjustment.summary`).
    dof : int, optional
        Degrees of freedom for μ if not m − n (e.g. when equations are dependent).
    progress : callable, optional
        Called with each :class:`IterationRecord` (for long adjustments).

    Returns
    -------
    Adjustment
        Estimate, residuals, μ, Q, m_j, r_ij, iteration history, dof, redundancy numbers.

    Raises
    ------
    InputError
        NaN/inf or a wrong shape in the start values, equations or weights; m < n.
    DegenerateGeometryError
        A singular normal matrix (the unknowns of the weak combination are named).
    ConvergenceError
        NaN/inf during the iteration or no convergence in ``max_iter`` steps (with the history).

    References
    ----------
    Chibunichev (2022), §1.8, eqs. (1.8.5)–(1.8.10).

    Examples
    --------
    A straight line y = a + b·t through four points:

    >>> import numpy as np
    >>> t, y = np.array([0., 1., 2., 3.]), np.array([1.1, 2.9, 5.2, 6.8])
    >>> adj = gauss_newton(lambda x: (np.column_stack([np.ones(4), t]), x[0] + x[1] * t - y),
    ...                    [0., 0.], names=("a", "b"))
    >>> print(f"a = {adj.x[0]:.3f}, b = {adj.x[1]:.3f}, dof = {adj.dof}")
    a = 1.090, b = 1.940, dof = 2
    >>> round(float(adj.redundancy.sum()), 6)        # Σ r_i = m − n
    2.0
    """
    if legacy:
        if set(legacy) != {"P"} or weights is not None:
            raise InputError(f"gauss_newton: unexpected arguments {sorted(legacy)}")
        weights = legacy["P"]
    if not callable(linearize):
        raise InputError("linearize must be a callable x -> (B, L)")
    try:
        x = np.array(x0, dtype=float)
    except (TypeError, ValueError) as exc:
        raise InputError(f"the approximate values must be numbers: {exc}") from None
    if x.ndim != 1:
        raise InputError("the unknowns must be a 1-D vector")
    if not np.all(np.isfinite(x)):
        raise InputError("the approximate values contain NaN or inf")
    if not (isinstance(max_iter, (int, np.integer)) and max_iter >= 1):
        raise InputError(f"max_iter must be a positive integer, got {max_iter!r}")
    try:
        tol = np.broadcast_to(np.asarray(tol, dtype=float), x.shape)
    except ValueError:
        raise InputError(f"tol: one value or one per unknown ({x.size}), got shape {np.shape(tol)}") from None
    return _iterate(_DenseSolver(linearize, weights, names, dof, tol), x, max_iter, progress)


# --- Hanzl §2.6: robust adjustment (data snooping, the Danish method) ---------------------------
#
# Hanzl, Fotogrammetrie, Modul 01, §2.6 "Robustní vyrovnání" (seed 002 lines 313–342). In Hanzl's
# notation v = A·x − l with l = observed − computed; this engine writes B·δ + L = V with
# L = computed − observed, so L = −l, B = A and V = v: his v = −Q_vv·P·l is V = Q_vv·P·L here,
# Q_vv = P⁻¹ − B·Q·Bᵀ, and his r_i = (Q_vv P)_ii are :func:`redundancy_numbers`.

DANISH_EXPONENTS = (4.4, 3.0)
"""Exponents d of the Danish weight function: 4.4 in the 2nd iteration, 3.0 from the 3rd on (Hanzl §2.6, line 336)."""
DANISH_FACTOR = 0.05
"""The constant 0.05 of the Danish weight function exp(−0.05·t^d) (Hanzl §2.6, line 336)."""
SNOOPING_CRITICAL = 3.29
"""Default critical value of the normalised residual (two-sided N(0, 1) at α₀ = 0.1 %, Baarda's usual choice; Hanzl gives none)."""
_WEIGHT_FLOOR = 1e-12


def _positive_number(value, what: str) -> float:
    if isinstance(value, bool):
        raise InputError(f"{what} must be a positive number, got {value!r}")
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise InputError(f"{what} must be a positive number, got {value!r}") from None
    if not (np.isfinite(v) and v > 0):
        raise InputError(f"{what} must be a positive finite number, got {value!r}")
    return v


def danish_weight(t, d: float, k: float = DANISH_FACTOR):
    """The Danish weight function p(v) = exp(−k·t^d) of a standardised residual t = |v√p|/σ₀.

    Hanzl (§2.6, line 336) prints the function without the exponential ("p(v_i) = −0,05 (…)^d",
    which would give negative weights); the text calls the weight functions exponential (Fig. 2.5)
    and the Danish method of Krarup and Kubik (as in Kraus's *Photogrammetrie*) uses exp(−0.05·t^d).
    The new weight of an observation is its original weight times this factor.

    Parameters
    ----------
    t : float or array_like
        Standardised residuals |v_i √p_i| / σ₀ (≥ 0; the absolute value is taken).
    d : float
        The exponent, > 0: 4.4 in the 2nd iteration, 3.0 from the 3rd on (:data:`DANISH_EXPONENTS`).
    k : float
        The constant, > 0 (0.05).

    Returns
    -------
    float or ndarray
        The weight factor in (0, 1], 1 at t = 0.

    Raises
    ------
    InputError
        NaN/inf residuals, d ≤ 0 or k ≤ 0.

    References
    ----------
    Hanzl, Fotogrammetrie, Modul 01, §2.6, Obr. 2.5 (seed 002 lines 334–340).

    Examples
    --------
    >>> round(float(danish_weight(2.0, 4.4)), 4), round(float(danish_weight(2.0, 3.0)), 4)
    (0.348, 0.6703)
    """
    d = _positive_number(d, "the exponent d")
    k = _positive_number(k, "the factor k")
    t = _floats(t, "standardised residuals")
    if not np.all(np.isfinite(t)):
        raise InputError("standardised residuals contain NaN or inf")
    out = np.exp(-k * np.abs(t) ** d)
    return float(out) if out.ndim == 0 else out


def normalized_residuals(B, V, Q, weights=None, sigma0: float | None = None):
    """Normalised residuals of data snooping, w_i = |v_i √p_i| / (σ₀ √r_i) (Hanzl §2.6).

    r_i = (Q_vv P)_ii are the redundancy numbers (:func:`redundancy_numbers`) and
    σ₀² = VᵀPV / (m − n) unless σ₀ is given (an a-priori value). Under the hypothesis of no gross
    error each w_i is N(0, 1); equivalently w_i = |v_i| / (σ₀ √q_vv,ii). An observation that the
    others do not check (r_i ≈ 0) gets w_i = NaN: no blunder in it can be seen.

    Parameters
    ----------
    B : array_like (m, n)
        Design matrix at the solution.
    V : array_like (m,)
        Residuals.
    Q : array_like (n, n)
        Cofactor matrix N⁻¹.
    weights : array_like (m,), optional
        Weights p_i (unit if omitted); a full matrix is not supported (correlated observations).
    sigma0 : float, optional
        σ₀; estimated from the residuals if omitted (needs m > n).

    Returns
    -------
    ndarray (m,)

    Raises
    ------
    InputError
        Shapes that do not match, NaN/inf, non-positive weights or σ₀, a weight matrix, no redundancy.

    References
    ----------
    Hanzl, Fotogrammetrie, Modul 01, §2.6 (seed 002 lines 317–325); Chibunichev (2022), §1.8,
    eq. (1.8.9) (σ₀ = μ).

    Examples
    --------
    >>> import numpy as np
    >>> B = np.ones((5, 1)); obs = np.array([1.0, 1.1, 0.9, 1.0, 3.0])
    >>> Q = np.array([[0.2]]); V = B[:, 0] * obs.mean() - obs
    >>> w = normalized_residuals(B, V, Q)
    >>> s0 = np.sqrt(V @ V / 4); bool(np.allclose(w, np.abs(V) / (s0 * np.sqrt(0.8))))   # r_i = 1 − 1/5
    True
    >>> int(np.argmax(w))
    4
    """
    B = _as_matrix(B, "B", 2)
    V = _as_matrix(V, "V", 1)
    m, n = B.shape
    if V.shape != (m,):
        raise InputError(f"V must have one residual per row of B ({m}), got {V.shape}")
    if not np.all(np.isfinite(V)):
        raise InputError("residuals contain NaN or inf")
    if weights is not None and np.ndim(weights) == 2:
        raise InputError("normalised residuals need uncorrelated observations: give the weights as a vector")
    P = _as_weights(weights, m)
    r = redundancy_numbers(B, Q, P)
    p = np.ones(m) if P is None else P
    if sigma0 is None:
        if m <= n:
            raise InputError(f"σ₀ cannot be estimated without redundancy ({m} observations, {n} unknowns)")
        sigma0 = float(np.sqrt(np.sum(p * V * V) / (m - n)))
        if sigma0 == 0:
            return np.zeros(m)
    else:
        sigma0 = _positive_number(sigma0, "sigma0")
    controlled = r > 1e-10
    w = np.full(m, np.nan)
    w[controlled] = np.abs(V[controlled] * np.sqrt(p[controlled])) / (sigma0 * np.sqrt(r[controlled]))
    return w


@dataclass
class RobustIterationRecord:
    """One pass of a robust adjustment (Hanzl §2.6).

    Attributes
    ----------
    iteration : int
        1 for the first (plain least squares) pass.
    method : str
        ``"danish"`` or ``"snooping"``.
    sigma0 : float
        σ₀ of the adjustment of this pass.
    factors : ndarray (m,)
        Danish: the weight factors p(v) used in this pass (1 in the first); snooping: 1 for the
        observations in the adjustment, 0 for the rejected ones.
    exponent : float or None
        Danish: the d used (None in the first pass).
    max_w : float or None
        Snooping: the largest normalised residual of this pass.
    rejected : tuple of int
        Observations rejected after this pass (snooping) / so far (Danish: weight factor below the threshold).

    References
    ----------
    Hanzl, Fotogrammetrie, Modul 01, §2.6 (seed 002 lines 313–342).

    Examples
    --------
    >>> import numpy as np
    >>> RobustIterationRecord(1, "danish", 0.5, np.ones(3)).exponent is None
    True
    """

    iteration: int
    method: str
    sigma0: float
    factors: np.ndarray
    exponent: float | None = None
    max_w: float | None = None
    rejected: tuple = ()
    x: np.ndarray | None = None


@dataclass(repr=False)
class RobustAdjustment(AdjustmentView):
    """Result of :func:`robust_gauss_newton`: the final adjustment and what was rejected.

    The final adjustment uses the ORIGINAL weights of the observations that were kept (Hanzl
    §2.6, last sentence); ``plain`` is the ordinary least-squares adjustment of all observations
    (the first pass), for comparison.

    Attributes
    ----------
    adjustment : Adjustment
        The final least-squares adjustment of the kept observations (its residuals, design,
        redundancy, … refer to the kept rows only).
    method : str
        ``"danish"`` or ``"snooping"``.
    rejected : ndarray of bool (m,)
        True for every observation found to be an outlier.
    residuals : ndarray (m,)
        Residuals of ALL observations at the final estimate (the rejected ones included).
    plain : Adjustment
        Ordinary least squares with every observation.
    robust_history : list of RobustIterationRecord
        One record per pass.
    weight_history : list of ndarray
        The weights of every pass (original weights × factors; 0 for rejected observations in snooping).
    normalized : ndarray (m,)
        Normalised residuals w_i of the final adjustment (NaN for the rejected observations and
        for observations with r_i ≈ 0).
    x, mu, std, corr, Q, iterations, history
        Those of the final adjustment.

    References
    ----------
    Hanzl, Fotogrammetrie, Modul 01, §2.6 (seed 002 lines 313–342).

    Examples
    --------
    >>> import numpy as np
    >>> t = np.arange(10.0); y = 2.0 + 0.5 * t + 0.01 * np.sin(7 * t); y[4] += 5.0
    >>> res = robust_gauss_newton(lambda p: (np.column_stack([np.ones(10), t]), p[0] + p[1] * t - y), [0.0, 0.0])
    >>> np.flatnonzero(res.rejected).tolist()
    [4]
    >>> bool(np.allclose(res.x, np.polyfit(np.delete(t, 4), np.delete(y, 4), 1)[::-1]))   # LS without it
    True
    """

    adjustment: Adjustment
    method: str
    rejected: np.ndarray
    residuals: np.ndarray
    plain: Adjustment
    robust_history: list
    weight_history: list
    normalized: np.ndarray

    @property
    def x(self) -> np.ndarray:
        """The adjusted unknowns of the final adjustment."""
        return self.adjustment.x

    @property
    def kept(self) -> np.ndarray:
        """True for the observations in the final adjustment."""
        return ~self.rejected

    def summary(self) -> str:
        """A few lines: method, passes, rejected observations, σ₀ of plain LS and of the final adjustment."""
        bad = np.flatnonzero(self.rejected)
        shown = ", ".join(str(i) for i in bad[:20]) + (" …" if bad.size > 20 else "")
        lines = [f"Robust adjustment (Hanzl §2.6, {self.method}): {len(self.robust_history)} passes, "
                 f"{bad.size} of {self.rejected.size} observations rejected" + (f" ({shown})" if bad.size else ""),
                 f"  sigma0: plain LS {float(self.plain.mu):.6g}, final {float(self.adjustment.mu):.6g}"]
        return "\n".join(lines)

    __repr__ = summary


def _grouped(mask_or_values, group: int, reduce):
    return reduce(np.asarray(mask_or_values).reshape(-1, group), axis=1)


def robust_gauss_newton(linearize: Callable[[np.ndarray], tuple], x0, weights=None, *, method: str = "danish",
                        sigma0: float | None = None, exponents=DANISH_EXPONENTS, k: float = DANISH_FACTOR,
                        reject_below: float = 0.01, critical: float = SNOOPING_CRITICAL, group: int = 1,
                        max_passes: int = 30, pass_tol: float = 1e-4, tol=1e-10, max_iter: int = 50,
                        names: Sequence[str] = (),
                        progress: Callable[[RobustIterationRecord], None] | None = None) -> RobustAdjustment:
    """Least squares resistant to gross errors: data snooping or the Danish method (Hanzl §2.6).

    Every pass is an ordinary :func:`gauss_newton` adjustment; only the weights change.

    * ``method="snooping"`` — adjust, compute the normalised residuals
      w_i = |v_i √p_i| / (σ₀ √r_i) (:func:`normalized_residuals`), reject the observation (or the
      group, e.g. both coordinates of a point) with the largest w if it exceeds ``critical``, and
      repeat ("the computation has to be repeated", drawback 4) until no w exceeds it. With σ₀
      estimated from the same residuals (Hanzl's σ₀² = vᵀPv/(m − n)) no w_i can exceed √(m − n)
      (drawback 1: σ₀ is inflated by the outliers); give an a-priori ``sigma0`` when the
      redundancy is small.
    * ``method="danish"`` — pass 1 is plain least squares; in pass ν ≥ 2 every observation gets
      the weight p_i·exp(−k·(|v_i √p_i| / σ₀)^d) from the residuals and σ₀ of pass ν − 1
      (σ₀² = Σ p_i f_i v_i² / Σ f_i r_i with the factors f_i and redundancy numbers r_i of that pass:
      a down-weighted observation leaves the redundancy as it leaves the sum), with
      d = ``exponents[0]`` (4.4) in pass 2 and ``exponents[1]`` (3.0) from pass 3 on; the passes
      stop when no weight factor changes by more than ``pass_tol``, or when neither the estimate
      (by ``tol``) nor the set of flagged observations changes any more (a noise-free fit, whose
      factors only follow rounding noise). Observations whose factor is
      below ``reject_below`` (of a group: any of them) are the outliers.

    Either way the outliers are removed and the final adjustment uses the original weights
    ("po vyloučení identifikovaných měření se vyrovnání provede s původními vahami").

    Parameters
    ----------
    linearize : callable
        ``linearize(x) -> (B, L)`` as for :func:`gauss_newton` (B·δ + L = V, L computed − observed).
    x0 : array_like (n,)
        Approximate values.
    weights : array_like (m,), optional
        Original weights p_i (unit if omitted). A full weight matrix is refused: robust
        re-weighting needs uncorrelated observations.
    method : {"danish", "snooping"}
    sigma0 : float, optional
        A-priori σ₀ (e.g. 1 with p_i = 1/σ_i²); estimated in every pass as √(VᵀPV/(m − n)) if omitted.
    exponents : (float, float)
        Danish exponents d for pass 2 and passes ≥ 3, both > 0.
    k : float
        Danish constant (0.05).
    reject_below : float
        Danish: weight factor below which an observation counts as an outlier, in (0, 1).
    critical : float
        Snooping: critical normalised residual (default 3.29).
    group : int
        Observations are rejected in groups of this many consecutive rows (2 for the x, y of an
        image point); m must be a multiple of it.
    max_passes : int
        Passes allowed before :class:`ConvergenceError`.
    pass_tol : float
        Danish: the passes stop when max |Δfactor| < pass_tol.
    tol, max_iter, names
        Passed to every :func:`gauss_newton`.
    progress : callable, optional
        Called with a :class:`RobustIterationRecord` after every pass.

    Returns
    -------
    RobustAdjustment
        The final adjustment (``adjustment``, ``x``, ``mu`` …), the ``rejected`` mask, the
        residuals of all observations, ``plain`` LS, the pass records and weight history.

    Raises
    ------
    InputError
        Bad options (unknown method, d ≤ 0, …), a weight matrix, NaN/inf, no redundancy (m ≤ n),
        m not a multiple of ``group``.
    DegenerateGeometryError
        So many observations rejected that the rest cannot determine the unknowns (or a singular
        normal matrix in a pass).
    ConvergenceError
        A pass did not converge, or the Danish weights did not settle in ``max_passes``.

    References
    ----------
    Hanzl, Fotogrammetrie, Modul 01, §2.6 (seed 002 lines 313–342); Chibunichev (2022), §1.8,
    eqs. (1.8.5)–(1.8.10) (each pass).

    Examples
    --------
    A straight line with one blunder (σ = 0.01 known a priori for data snooping: with σ₀
    estimated from the same 10 residuals no w_i can exceed √(m − n) = √8 < 3.29):

    >>> import numpy as np
    >>> t = np.arange(10.0); y = 2.0 + 0.5 * t + 0.01 * np.sin(7 * t); y[6] -= 3.0
    >>> lin = lambda p: (np.column_stack([np.ones(10), t]), p[0] + p[1] * t - y)
    >>> for method, s0 in (("danish", None), ("snooping", 0.01)):
    ...     res = robust_gauss_newton(lin, [0.0, 0.0], method=method, sigma0=s0)
    ...     print(method, np.flatnonzero(res.rejected).tolist(), res.x.round(2))
    danish [6] [2.01 0.5 ]
    snooping [6] [2.01 0.5 ]
    """
    if method not in ("danish", "snooping"):
        raise InputError(f"method must be 'danish' or 'snooping', got {method!r}")
    if not callable(linearize):
        raise InputError("linearize must be a callable x -> (B, L)")
    if isinstance(exponents, (str, bytes)) or not hasattr(exponents, "__len__") or len(exponents) != 2:
        raise InputError(f"exponents must be two positive numbers (d of the 2nd and of later passes), "
                         f"got {exponents!r}")
    d2, d3 = (_positive_number(d, "the Danish exponent d") for d in exponents)
    k = _positive_number(k, "the Danish factor k")
    reject_below = _positive_number(reject_below, "reject_below")
    if reject_below >= 1:
        raise InputError(f"reject_below must lie in (0, 1), got {reject_below}")
    critical = _positive_number(critical, "the critical value")
    if sigma0 is not None:
        sigma0 = _positive_number(sigma0, "sigma0")
    if isinstance(group, bool) or not isinstance(group, (int, np.integer)) or group < 1:
        raise InputError(f"group must be a positive integer, got {group!r}")
    if isinstance(max_passes, bool) or not isinstance(max_passes, (int, np.integer)) or max_passes < 2:
        raise InputError(f"max_passes must be an integer ≥ 2, got {max_passes!r}")
    pass_tol = _positive_number(pass_tol, "pass_tol")
    try:
        x = np.array(x0, dtype=float)
    except (TypeError, ValueError) as exc:
        raise InputError(f"the approximate values must be numbers: {exc}") from None
    if x.ndim != 1 or not np.all(np.isfinite(x)):
        raise InputError("the approximate values must be a 1-D vector without NaN or inf")
    B0, L0 = linearize(x)
    B0, L0 = _floats(B0, "B"), _floats(L0, "L")
    if B0.ndim != 2 or L0.ndim != 1 or B0.shape[0] != L0.shape[0] or B0.shape[1] != x.size:
        raise InputError(f"linearize must return B (m×{x.size}) and L (m,), got {B0.shape} and {L0.shape}")
    m, n = B0.shape
    if not (np.all(np.isfinite(B0)) and np.all(np.isfinite(L0))):
        raise InputError("the correction equations contain NaN or inf")
    if weights is not None and np.ndim(weights) == 2:
        raise InputError("a robust adjustment re-weights single observations: give the weights as a vector "
                         "(uncorrelated observations), not a matrix")
    P = _as_weights(weights, m)
    p = np.ones(m) if P is None else P
    if m % group:
        raise InputError(f"{m} observations cannot be split into groups of {group}")
    if m <= n:
        raise InputError(f"a robust adjustment needs redundant observations: {m} observations, {n} unknowns")

    def run(factors, start):
        keep = factors > 0
        if int(keep.sum()) < n or (int(keep.sum()) <= n and method == "snooping"):
            raise DegenerateGeometryError(
                f"the robust adjustment rejected {m - int(keep.sum())} of {m} observations: the remaining "
                f"{int(keep.sum())} cannot determine {n} unknowns with redundancy")

        def lin(xx):
            B, L = linearize(xx)
            B, L = np.asarray(B, dtype=float), np.asarray(L, dtype=float)
            return B[keep], L[keep]

        return gauss_newton(lin, start, p[keep] * factors[keep], tol=tol, max_iter=max_iter, names=names), keep

    def all_residuals(adj):
        B, L = linearize(adj.x)
        return np.asarray(L, dtype=float) + 0.0        # V at the estimate (the last δ is negligible)

    def sigma_of(adj, keep, factors):
        # σ₀² = Σ p_i f_i v_i² / Σ f_i r_i: each observation counts in the redundancy with its
        # weight factor f_i. (Counting a down-weighted observation fully in m − n would shrink σ₀
        # pass by pass until good observations are down-weighted too; ignoring the partly
        # down-weighted ones keeps σ₀ inflated by the outliers.) Plain LS: VᵀPV/(m − n).
        if sigma0 is not None:
            return sigma0
        f = factors[keep]
        r = adj.redundancy
        dof = float(np.sum(f * r))
        V = adj.residuals
        return float(np.sqrt(np.sum(p[keep] * f * V * V) / dof)) if dof > 1e-12 else float("nan")

    try:
        tol_x = np.broadcast_to(np.asarray(tol, dtype=float), x.shape)
    except ValueError:
        raise InputError(f"tol: one value or one per unknown ({x.size}), got shape {np.shape(tol)}") from None
    history, weight_history = [], []
    factors = np.ones(m)
    plain, keep = run(factors, x)
    current = plain
    s0 = sigma_of(plain, keep, factors)

    def emit(record):
        history.append(record)
        weight_history.append(p * factors)
        if progress is not None:
            progress(record)

    if method == "danish":
        emit(RobustIterationRecord(1, method, s0, factors.copy(), None, x=plain.x.copy()))
        for it in range(2, max_passes + 1):
            d = d2 if it == 2 else d3
            if not (np.isfinite(s0) and s0 > 0):
                break                                           # a perfect fit: nothing to re-weight
            t = np.abs(all_residuals(current) * np.sqrt(p)) / s0
            new = np.maximum(np.exp(-k * t ** d), _WEIGHT_FLOOR)
            change = float(np.max(np.abs(new - factors)))
            factors = new
            if int(np.sum(factors >= reject_below)) <= n:
                raise DegenerateGeometryError(
                    f"the Danish method down-weighted {int(np.sum(factors < reject_below))} of {m} observations "
                    f"below {reject_below}: the remaining ones cannot determine {n} unknowns with redundancy")
            current, keep = run(factors, current.x)
            s0 = sigma_of(current, keep, factors)
            flagged = np.flatnonzero(np.repeat(_grouped(factors < reject_below, group, np.any), group))
            emit(RobustIterationRecord(it, method, s0, factors.copy(), d, rejected=tuple(flagged.tolist()),
                                       x=current.x.copy()))
            settled_x = bool(np.all(np.abs(current.x - history[-2].x) < tol_x))
            if it >= 3 and (change < pass_tol or (settled_x and history[-1].rejected == history[-2].rejected)):
                break
        else:
            raise ConvergenceError(f"the Danish weights did not settle in {max_passes} passes", history)
        rejected = np.repeat(_grouped(factors < reject_below, group, np.any), group)
    else:
        rejected = np.zeros(m, bool)
        for it in range(1, max_passes + 1):
            kept = ~rejected
            B, _ = current.design
            w_kept = normalized_residuals(B, current.residuals, current.Q, p[kept], sigma0)
            w = np.full(m, np.nan)
            w[kept] = w_kept
            wg = _grouped(np.where(np.isnan(w), -np.inf, w), group, np.max)
            worst = int(np.argmax(wg))
            max_w = float(wg[worst])
            done = not (max_w > critical)
            if not done:
                rejected[worst * group:(worst + 1) * group] = True
            emit(RobustIterationRecord(it, method, s0, (~rejected).astype(float), max_w=max_w,
                                       rejected=tuple(np.flatnonzero(rejected).tolist()), x=current.x.copy()))
            if done:
                break
            factors = (~rejected).astype(float)
            current, keep = run(factors, current.x)
            s0 = sigma_of(current, keep, factors)
        else:
            raise ConvergenceError(f"data snooping still rejects after {max_passes} passes", history)
    final, keep = run((~rejected).astype(float), current.x)
    B, _ = final.design
    w = np.full(m, np.nan)
    if int(keep.sum()) > n:
        w[keep] = normalized_residuals(B, final.residuals, final.Q, p[keep], sigma0)
    return RobustAdjustment(final, method, rejected, all_residuals(final), plain, history, weight_history, w)


# --- Chapter 3, §3.5: block-structured normal equations and their reduction ---------------------
#
# A bundle block has two kinds of unknowns: the exterior orientation of each image ("frames",
# δ₁, six per image) and the coordinates of each point (δ₂, three per point). Every image
# observation involves one image and one point, so with the book's partition (3.5.13)
#
#     ⎡N₁₁  N₁₂⎤ ⎡δ₁⎤   ⎡L₁ᴺ⎤
#     ⎣N₁₂ᵀ N₂₂⎦ ⎣δ₂⎦ = ⎣L₂ᴺ⎦                                           (3.5.13)
#
# N₁₁ is block diagonal with 6×6 blocks, N₂₂ block diagonal with 3×3 blocks and N₁₂ sparse
# (figs. 3.11/3.12). NOTE the sign convention: (3.5.8) writes N·δ + Lᴺ = 0 with Lᴺ = AᵀPL, but
# (3.5.13)–(3.5.16) write N·δ = Lᴺ; there Lᴺ stands for −AᵀPL, and so it does below.
# Eliminating the points from the second row of (3.5.14), δ₂ = N₂₂⁻¹(L₂ᴺ − N₁₂ᵀδ₁), gives the
# reduced ("Schur complement") system of the image unknowns only
#
#     (N₁₁ − N₁₂N₂₂⁻¹N₁₂ᵀ)·δ₁ = L₁ᴺ − N₁₂N₂₂⁻¹L₂ᴺ                        (3.5.16)
#
# whose size is 6·(number of images) whatever the number of points, and N₂₂⁻¹ is a batch of
# independent 3×3 inverses. Eliminating the images instead gives
#
#     (N₂₂ − N₁₂ᵀN₁₁⁻¹N₁₂)·δ₂ = L₂ᴺ − N₁₂ᵀN₁₁⁻¹L₁ᴺ                        (3.5.15, corrected)
#
# — the book prints the left-hand matrix with the opposite sign, (N₁₂ᵀN₁₁⁻¹N₁₂ − N₂₂), which
# returns −δ₂ (the line before it in the book is right; the sign is lost in the last step).


def solve_partitioned_normal_equations(N11, N12, N22, L1, L2, eliminate: str = "points"):
    """Solve (3.5.13) by eliminating one group of unknowns — dense, for small systems and teaching.

    Parameters
    ----------
    N11, N12, N22 : arrays
        Blocks of the normal matrix, (n₁×n₁), (n₁×n₂), (n₂×n₂).
    L1, L2 : arrays
        Right-hand sides **in the convention of (3.5.13)**: N·δ = Lᴺ, i.e. Lᴺ = −AᵀPL.
    eliminate : {"points", "eo"}
        ``"points"``: reduce onto δ₁ by (3.5.16), then δ₂ = N₂₂⁻¹(L₂ᴺ − N₁₂ᵀδ₁);
        ``"eo"``: reduce onto δ₂ by the sign-corrected (3.5.15), then δ₁ = N₁₁⁻¹(L₁ᴺ − N₁₂δ₂).

    Returns
    -------
    delta1, delta2 : arrays

    Raises
    ------
    InputError
        An unknown ``eliminate``; blocks whose shapes do not fit together; NaN/inf.
    DegenerateGeometryError
        A singular block.

    References
    ----------
    Chibunichev (2022), §3.5, eqs. (3.5.13)–(3.5.16) (the sign of (3.5.15) corrected, see above).

    Examples
    --------
    >>> import numpy as np
    >>> N = np.array([[4.0, 1.0, 0.5], [1.0, 3.0, 0.2], [0.5, 0.2, 2.0]])
    >>> L = np.array([1.0, 2.0, 3.0])
    >>> d1, d2 = solve_partitioned_normal_equations(N[:1, :1], N[:1, 1:], N[1:, 1:], L[:1], L[1:])
    >>> bool(np.allclose(np.concatenate([d1, d2]), np.linalg.solve(N, L)))
    True
    """
    N11, N12, N22 = (np.atleast_2d(_floats(M, "N blocks")) for M in (N11, N12, N22))
    L1, L2 = np.atleast_1d(_floats(L1, "L1")), np.atleast_1d(_floats(L2, "L2"))
    n1, n2 = N11.shape[0], N22.shape[0]
    if N11.shape != (n1, n1) or N22.shape != (n2, n2) or N12.shape != (n1, n2) or L1.shape != (n1,) \
            or L2.shape != (n2,):
        raise InputError(f"partitioned normal equations: N11 {N11.shape}, N12 {N12.shape}, N22 {N22.shape}, "
                         f"L1 {L1.shape}, L2 {L2.shape} do not fit together")
    if not all(np.all(np.isfinite(a)) for a in (N11, N12, N22, L1, L2)):
        raise InputError("the partitioned normal equations contain NaN or inf")
    if eliminate not in ("points", "eo"):
        raise InputError(f"eliminate must be 'points' or 'eo', got {eliminate!r}")
    try:
        return _solve_partitioned(N11, N12, N22, L1, L2, eliminate)
    except np.linalg.LinAlgError as exc:
        raise DegenerateGeometryError(f"a block of the partitioned normal matrix is singular: {exc}") from None


def _solve_partitioned(N11, N12, N22, L1, L2, eliminate):
    if eliminate == "points":
        iN22 = np.linalg.inv(N22)
        d1 = np.linalg.solve(N11 - N12 @ iN22 @ N12.T, L1 - N12 @ iN22 @ L2)      # (3.5.16)
        d2 = iN22 @ (L2 - N12.T @ d1)                                              # (3.5.14), row 2
    elif eliminate == "eo":
        iN11 = np.linalg.inv(N11)
        d2 = np.linalg.solve(N22 - N12.T @ iN11 @ N12, L2 - N12.T @ iN11 @ L1)    # (3.5.15) corrected
        d1 = iN11 @ (L1 - N12 @ d2)                                                # (3.5.14), row 1
    else:
        raise InputError(f"eliminate must be 'points' or 'eo', got {eliminate!r}")
    return d1, d2


@dataclass
class BlockCorrectionEquations:
    """The correction equations (3.5.2)–(3.5.4) of a block, grouped by image observation.

    Observation k (r rows, r = 2 for x and y) involves image ``frame[k]`` and point ``point[k]``:

        B1[k]·δ₁[frame[k]] + B2[k]·δ₂[point[k]] + L[k] = V[k]

    Attributes
    ----------
    frame, point : int arrays (m,)
    B1 : array (m, r, q)
        Derivatives by the q unknowns of the image (q = 6: X_S, Y_S, Z_S, ω, α, κ).
    B2 : array (m, r, 3)
        Derivatives by the point coordinates (ignored for points held fixed, (3.5.3)).
    L : array (m, r)
        Free terms: model value at the approximation (computed − measured).
    P : array (m, r) or float
        Weights p = 1/m² of the measurements (3.5.7).

    References
    ----------
    Chibunichev (2022), §3.5, eqs. (3.5.2)–(3.5.4), (3.5.7).

    Examples
    --------
    >>> import numpy as np
    >>> rng = np.random.default_rng(0)
    >>> frame, point = np.repeat([0, 1], 5), np.tile(np.arange(5), 2)
    >>> eq = BlockCorrectionEquations(frame, point, rng.normal(size=(10, 2, 6)), rng.normal(size=(10, 2, 3)),
    ...                               rng.normal(size=(10, 2)))
    >>> eq.B1.shape, eq.P
    ((10, 2, 6), 1.0)
    """

    frame: np.ndarray
    point: np.ndarray
    B1: np.ndarray
    B2: np.ndarray
    L: np.ndarray
    P: np.ndarray | float = 1.0


@dataclass
class BlockSolution:
    """One solved linear step of a block: corrections and (optionally) cofactor blocks.

    Attributes
    ----------
    delta1 : ndarray (n_frames, q)
        Corrections of the image unknowns.
    delta2 : ndarray (n_points, 3)
        Corrections of the points (0 for fixed points).
    Q1, Q2 : ndarray or None
        Diagonal blocks of N⁻¹ for the images (n_frames, q, q) and the points (n_points, 3, 3).
    timings : dict
        Seconds per stage (normal equations, reduction, factorisation, back-substitution).
    delta3 : ndarray (g,) or None
        Corrections of the block-wide unknowns (with :class:`GlobalBlockCorrectionEquations`).
    Q3, Q13, Q23 : ndarray or None
        Cofactors of the globals (g, g), image × global (n_frames, q, g), point × global (n_points, 3, g).

    References
    ----------
    Chibunichev (2022), §3.5, eqs. (3.5.13)–(3.5.16); §3.6, eq. (3.6.3).

    Examples
    --------
    >>> import numpy as np
    >>> BlockSolution(np.zeros((2, 6)), np.zeros((5, 3))).delta1.shape
    (2, 6)
    """

    delta1: np.ndarray
    delta2: np.ndarray
    Q1: np.ndarray | None = None
    Q2: np.ndarray | None = None
    timings: dict = field(default_factory=dict)
    delta3: np.ndarray | None = None
    Q3: np.ndarray | None = None
    Q13: np.ndarray | None = None
    Q23: np.ndarray | None = None



def _block_sum(index, blocks, n):
    """Σ of ``blocks[k]`` over k with ``index[k] == i``, for i in range(n) → (n, *block shape).

    One product with the n×m "summing matrix" (a 1 in row index[k], column k): faster and far
    lighter than a bincount over m·(block size) flat indices.
    """
    from scipy import sparse
    m = index.shape[0]
    summing = sparse.csr_matrix((np.ones(m), (index, np.arange(m))), shape=(n, m))
    flat = np.ascontiguousarray(blocks).reshape(m, -1)       # (einsum may return another memory order)
    return np.asarray(summing @ flat).reshape((n,) + blocks.shape[1:])


def _block_diagonal(blocks):
    """A scipy.sparse block-diagonal matrix (BSR) from an (n, b, b) stack."""
    from scipy import sparse
    n, b, _ = blocks.shape
    return sparse.bsr_matrix((blocks, np.arange(n), np.arange(n + 1)), shape=(n * b, n * b))


def _invert_3x3_blocks(blocks, rcond):
    """Inverses of the 3×3 diagonal blocks of N₂₂ (one per point), in a compiled loop.

    Each block is scaled to unit diagonal first and inverted by its adjugate (closed form); a
    block whose smallest eigenvalue is below ``rcond`` (rays intersecting at a grazing angle, a
    point not determined) raises :class:`DegenerateGeometryError` naming the points. With unit
    diagonal the other two eigenvalues have λ₂·λ₃ ≤ (3/2)², so λ_min ≥ 4·det/9: eigenvalues are
    computed only for the few blocks whose determinant does not already settle it.
    """
    from . import _block_kernels as kernels
    blocks = np.ascontiguousarray(blocks, dtype=float)
    inverse = np.empty_like(blocks)
    status = np.zeros(blocks.shape[0], np.int8)
    kernels.invert_3x3(blocks, rcond, inverse, status)
    if status.any():
        _check_inverse_status(blocks, status, rcond)
    return inverse


def _check_inverse_status(blocks, status, rcond):
    """Raise for the blocks :func:`photolib._block_kernels.invert_3x3` could not invert or doubted
    (status 1: a diagonal element ≤ 0; status 2: decided here by the smallest eigenvalue)."""
    if status.any():
        bad = np.flatnonzero(status == 1)
        if bad.size:
            raise DegenerateGeometryError(f"points {bad[:10].tolist()} are not determined by any observation")
        suspect = np.flatnonzero(status == 2)
        d = np.sqrt(np.einsum("kii->ki", blocks[suspect]))
        low = np.linalg.eigvalsh(blocks[suspect] / (d[:, :, None] * d[:, None, :]))[:, 0]
        if np.any(~(low >= rcond)):
            raise DegenerateGeometryError(
                f"points {suspect[~(low >= rcond)][:10].tolist()} are not determined: their rays are (nearly) "
                f"parallel (smallest scaled eigenvalue {np.nanmin(low):.1e})")


def _band_ordering(S):
    """A numbering of the unknowns that keeps the non-zeros of a symmetric sparse S near the diagonal.

    Two candidates, the narrower band wins: the given numbering (images numbered strip by strip
    give a half-bandwidth of about one strip plus the forward overlap, fig. 3.12) and the reverse
    Cuthill–McKee numbering (breadth-first from a peripheral unknown, which repairs an arbitrary
    numbering). A block-sparse (BSR) S — q×q blocks, one per pair of images — is renumbered image
    by image, on the graph of its blocks.

    Returns
    -------
    order : int array (n,)
        ``S[order][:, order]`` is the renumbered matrix.
    bandwidth : int
        A half-bandwidth b of it (S_ij = 0 for |i − j| > b); exact for q = 1, at most q − 1 too
        wide for blocks.
    """
    from scipy import sparse
    from scipy.sparse.csgraph import reverse_cuthill_mckee
    if sparse.issparse(S) and S.format == "bsr":
        q = S.blocksize[0]
        graph = sparse.csr_matrix((np.ones(S.indices.size), S.indices, S.indptr), shape=(S.shape[0] // q,) * 2)
    else:
        q, graph = 1, sparse.csr_matrix(S)
    rcm = reverse_cuthill_mckee(graph, symmetric_mode=True)
    position = np.empty(rcm.size, np.intp)
    position[rcm] = np.arange(rcm.size)
    graph = graph.tocoo()
    natural = int(np.abs(graph.row - graph.col).max(initial=0))
    reordered = int(np.abs(position[graph.row] - position[graph.col]).max(initial=0))
    order, width = (rcm, reordered) if reordered < natural else (np.arange(rcm.size), natural)
    return (q * order[:, None] + np.arange(q)).ravel(), q * width + q - 1


@contextlib.contextmanager
def blas_on_one_thread():
    """A context in which BLAS and LAPACK run on one thread (threadpoolctl, a runtime dependency).

    For least-squares problems of a few hundred unknowns solved many times (Monte Carlo runs,
    RPC fitting, the factorisation below): a multithreaded BLAS gains nothing at that size, and
    on a machine whose cores are busy its threads wait for each other.

    The band Cholesky of :class:`_Factorisation` works on panels a few hundred unknowns wide: a
    multithreaded BLAS gains nothing there, and when other processes hold the cores its threads
    wait for each other, which made the factorisation up to 40× slower on a busy machine
    (benchmarks/README.md; at 100 images 0.24 s on two threads against 0.002 s on one). The
    switch sets the thread count of every BLAS library threadpoolctl found (once) and restores
    it on exit — what ``ThreadpoolController.limit`` does, at a few microseconds instead of ≈ 17.

    Returns
    -------
    context manager
        Use in a ``with`` statement; the thread counts are restored when it ends.

    Raises
    ------
    Nothing of its own; an error inside the ``with`` block propagates after the restore.

    References
    ----------
    benchmarks/README.md, "Bundle adjustment" (the timings behind the one-thread rule).

    Examples
    --------
    >>> import numpy as np
    >>> with blas_on_one_thread():
    ...     x = np.linalg.solve(np.eye(3) * 2.0, np.ones(3))
    >>> x.tolist()
    [0.5, 0.5, 0.5]
    """
    libraries = _blas_libraries()
    before = [lib.num_threads for lib in libraries]
    for lib in libraries:
        lib.set_num_threads(1)
    try:
        yield
    finally:
        for lib, n in zip(libraries, before):
            lib.set_num_threads(n)


# stored numbers of S from which the factorisation runs on one BLAS thread. Below it (a block of
# about 10 images) the factorisation takes a few microseconds, less than the switch (20–70 µs in a
# fresh process); above it two threads made the factorisation up to 100× slower under load
# (100 images: 0.24 s against 0.002 s), so the former limit of 200 000 was far too high.
_ONE_THREAD_FROM = 10_000


@functools.lru_cache(maxsize=None)
def _blas_libraries():
    """threadpoolctl's controllers of the BLAS libraries (found once)."""
    return tuple(lib for lib in _blas_controller().lib_controllers if lib.user_api == "blas")


@functools.lru_cache(maxsize=None)
def _blas_controller():
    """threadpoolctl's view of the loaded BLAS libraries (found once)."""
    import scipy.linalg  # noqa: F401 — make sure scipy's BLAS is loaded before the libraries are listed
    return ThreadpoolController()


class _Factorisation:
    """Cholesky factorisation S = L·Lᵀ of the reduced matrix (3.5.16), as a band matrix.

    S is scaled to unit diagonal, D·S·D with D = diag(S)^−½, so that its pivots are comparable;
    the unknowns are renumbered by :func:`_band_ordering`; LAPACK's band Cholesky (``dpbtrf``)
    then factorises the lower band in place — n·(b + 1) numbers for a half-bandwidth b, the only
    large array (a general sparse LU would keep both L and U). An aerial block keeps b at about
    one strip of images whatever the number of strips. Systems of up to ``dense_limit`` unknowns
    use the dense Cholesky (``dpotrf``). The block solver builds the scaled band directly
    (:meth:`from_band`); a sparse S is accepted for the other callers.

    Every pivot of the scaled matrix is an L_ii² in (0, 1]; one ≤ ``rcond`` (or a failed
    factorisation) means S is singular — a datum defect — and raises DegenerateGeometryError.
    """

    def __init__(self, S, rcond, dense_limit=0, chunk: int = 1 << 17):
        from scipy import sparse
        n = S.shape[0]
        d = np.sqrt(S.diagonal())
        _check_diagonal(d)
        order, b = (np.arange(n), n - 1) if n <= dense_limit else _band_ordering(S)
        position = np.empty(n, np.intp)
        position[order] = np.arange(n)
        scale = 1.0 / d
        band = np.zeros((b + 1, n), order="F")         # Fortran order: LAPACK works in it without a copy
        # lower band of the scaled, renumbered S in LAPACK storage: band[i − j, j] = S_ij, i ≥ j
        # (filled in chunks of the non-zeros, so no full-size index arrays are held)
        S = sparse.coo_matrix(S)
        for start in range(0, S.nnz, chunk):
            part = slice(start, start + chunk)
            row, col = S.row[part], S.col[part]
            i, j = position[row], position[col]
            lower = i >= j
            np.add.at(band, (i[lower] - j[lower], j[lower]), (S.data[part] * scale[row] * scale[col])[lower])
        self._factorise(band, order, scale, rcond, n <= dense_limit)

    @classmethod
    def from_band(cls, band, order, scale, rcond, dense=False):
        """The factorisation of a scaled, renumbered S given as its lower band (overwritten).

        ``band[d, c]`` = (D·S·D)[order[c + d], order[c]] (LAPACK storage, Fortran order), ``scale``
        the diagonal of D in the original numbering.
        """
        self = cls.__new__(cls)
        self._factorise(band, order, scale, rcond, dense)
        return self

    def _factorise(self, band, order, scale, rcond, dense):
        from scipy.linalg import lapack
        n = band.shape[1]
        self.n, self.order, self.scale, self.dense = n, order, scale, dense
        # one BLAS thread for every system larger than _ONE_THREAD_FROM stored numbers
        with blas_on_one_thread() if (n * n if dense else band.size) > _ONE_THREAD_FROM else contextlib.nullcontext():
            if dense:            # the same numbers as a full lower triangle (row i − j, column j → i, j)
                full = np.zeros((n, n), order="F")
                ii, jj = np.tril_indices(n)
                inside = ii - jj < band.shape[0]
                full[ii[inside], jj[inside]] = band[ii[inside] - jj[inside], jj[inside]]
                self.factor, info = lapack.dpotrf(full, lower=1, clean=1, overwrite_a=1)
                pivots = np.diag(self.factor) ** 2
            else:
                self.factor, info = lapack.dpbtrf(band, lower=1, overwrite_ab=1)
                pivots = self.factor[0] ** 2
        # info > 0: the leading minor of that order is not positive definite
        self.min_pivot = 0.0 if info != 0 else float(pivots.min(initial=np.inf))
        if not self.min_pivot > rcond:
            error = _datum_defect(self.min_pivot)
            error.min_pivot = self.min_pivot
            error.column = int(info) - 1 if info > 0 else int(np.argmin(pivots))   # in the renumbered system
            raise error

    def solve(self, rhs):
        """S⁻¹·rhs for a vector or a matrix of right-hand sides."""
        from scipy.linalg import lapack
        scale = self.scale if rhs.ndim == 1 else self.scale[:, None]
        b = (rhs * scale)[self.order]
        # LAPACK's triangular solves directly (what cho_solve / cho_solve_banded call, without their
        # per-call argument handling): dpotrs / dpbtrs with the lower factor
        if b.size == 0:
            y, info = b.copy(), 0
        else:
            y, info = lapack.dpotrs(self.factor, b, lower=1) if self.dense else \
                lapack.dpbtrs(self.factor, b, lower=1)
        if info != 0:
            raise ValueError(f"illegal value in argument {-info} of the LAPACK triangular solve")
        x = np.empty_like(y)
        x[self.order] = y
        return x * scale

    def inverse(self, chunk: int = 512):
        """S⁻¹ as a dense array (solved for column chunks of the identity)."""
        out = np.empty((self.n, self.n))
        for start in range(0, self.n, chunk):
            stop = min(start + chunk, self.n)
            e = np.zeros((self.n, stop - start))
            e[np.arange(start, stop), np.arange(stop - start)] = 1.0
            out[:, start:stop] = self.solve(e)
        return out


def _datum_defect(min_pivot):
    return DegenerateGeometryError(
        "the reduced normal matrix (3.5.16) is singular (smallest scaled pivot "
        f"{min_pivot:.1e}): the block has a datum defect — too little control "
        "(fixed or weighted control points, GNSS centres) to fix its position, rotation and scale")


def _singular_block(min_pivot, column, pattern, frame):
    """The error for a singular reduced matrix of a block, naming the image where the factorisation failed.

    ``column`` is the column of the renumbered reduced system whose pivot failed (or the smallest);
    the unknown there belongs to one image, whose observations are counted.
    """
    free_images = np.flatnonzero(pattern["free"][0])
    q = pattern["keep"].size // pattern["free"][0].size
    unknown = int(pattern["order"][column])
    image = int(free_images[unknown // q])
    seen = int(np.count_nonzero(frame == image))
    return DegenerateGeometryError(
        "the reduced normal matrix (3.5.16) is singular (smallest scaled pivot "
        f"{min_pivot:.1e}, first at unknown {unknown % q} of image {image}, which has {seen} observations): "
        "either the points of that image do not determine it (too few, on one line, or tie points "
        "seen by no other image) or the block has a datum defect — too little control (fixed or "
        "weighted control points, GNSS centres) to fix its position, rotation and scale")


def _check_diagonal(d):
    """Every diagonal element of S must be positive (an image unknown without observations is not)."""
    if not (d > 0).all():
        raise DegenerateGeometryError(
            f"image unknowns {np.flatnonzero(~(d > 0))[:10].tolist()} are not determined by any observation")


def _pairs_by_point(point, n_points):
    """All ordered pairs (a, b) of observations that see the same point (for N₂₂ cofactors)."""
    order = np.argsort(point, kind="stable")
    counts = np.bincount(point, minlength=n_points)
    starts = np.concatenate([[0], np.cumsum(counts)[:-1]])
    n_of = counts[point[order]]
    a = np.repeat(order, n_of)
    first = np.repeat(starts[point[order]], n_of)
    offset = np.arange(a.size) - np.repeat(np.cumsum(n_of) - n_of, n_of)
    b = order[first + offset]
    return a, b


def _block_pattern(frame, point, n_frames, n_points, q, free_frames, free_points):
    """Everything of a block step that depends only on which image sees which point (computed once).

    ``slot``: for every observation its q×3 block of N₁₂ (−1: a fixed point or image, (3.5.3)),
    numbered point by point so that ``ptr[p]:ptr[p + 1]`` are the blocks of point p; ``position``: the renumbered place of every
    free image in the reduced system (:func:`_band_ordering` on the graph of images with a common
    point: the given numbering or reverse Cuthill–McKee, whichever gives the narrower band);
    ``order``: the unknowns of the renumbered system as indices of the free image unknowns;
    ``bandwidth``: its half-bandwidth.
    """
    from . import _block_kernels as kernels
    coupled = np.flatnonzero(free_points[point] & free_frames[frame])
    coupled = coupled[np.argsort(point[coupled], kind="stable")]       # the blocks of one point side by side
    slot = np.full(frame.size, -1, np.intp)
    slot[coupled] = np.arange(coupled.size)
    slot_frame, slot_point = frame[coupled], point[coupled]
    ptr = np.searchsorted(slot_point, np.arange(n_points + 1)).astype(np.intp)
    free_idx = np.flatnonzero(free_frames)
    rank = np.cumsum(free_frames) - 1
    n_free = free_idx.size
    # the graph of the free images: an edge for every pair with a common free point (and each image itself)
    count = np.diff(ptr)
    pairs = count * count
    a = np.repeat(np.arange(slot_frame.size), np.repeat(count, count))       # every ordered pair of blocks
    within = np.arange(a.size) - np.repeat(np.cumsum(pairs) - pairs, pairs)  # of one point: (ptr + u, ptr + v)
    b = np.repeat(ptr[:-1], pairs) + within % np.repeat(count, pairs)
    edge = np.unique(np.concatenate([rank[slot_frame[a]] * n_free + rank[slot_frame[b]],
                                     np.arange(n_free) * (n_free + 1)]))
    row, col = edge // n_free, edge % n_free
    # the choice of _band_ordering (given numbering or reverse Cuthill–McKee, the narrower band),
    # made on the edge list at hand instead of a second sparse copy of the graph
    # (reverse Cuthill–McKee compiled, the same numbering as scipy.sparse.csgraph's: no sparse matrix needed;
    # every image has its diagonal entry, which scipy's degree counts twice)
    indptr = np.searchsorted(row, np.arange(n_free + 1))
    degree = np.diff(indptr).astype(np.int32) + 1
    rcm = np.empty(n_free, np.intp)
    kernels.reverse_cuthill_mckee(col, indptr, np.argsort(degree), degree, rcm)
    rcm_position = np.empty(rcm.size, np.intp)
    rcm_position[rcm] = np.arange(rcm.size)
    natural = int(np.abs(row - col).max(initial=0))
    reordered = int(np.abs(rcm_position[row] - rcm_position[col]).max(initial=0))
    image_order = rcm if reordered < natural else np.arange(n_free)
    position = np.full(n_frames, -1, np.intp)
    position[free_idx[image_order]] = np.arange(n_free)
    width = int(np.abs(position[free_idx[row]] - position[free_idx[col]]).max(initial=0))
    return {"frame": frame.copy(), "point": point.copy(), "slot": slot, "slot_frame": slot_frame,
            "slot_point": slot_point, "ptr": ptr, "position": position,
            "order": (q * image_order[:, None] + np.arange(q)).ravel(), "bandwidth": q * width + q - 1,
            "free": (free_frames.copy(), free_points.copy()),
            # the same in every iteration: fixed points / images and the free image unknowns
            "fixed_points": np.flatnonzero(~free_points), "fixed_frames": np.flatnonzero(~free_frames),
            "keep": np.repeat(free_frames, q)}


def _same(a, b):
    """``np.array_equal`` for two arrays (the block-pattern cache test), without its argument handling."""
    return a is b or (a.shape == b.shape and bool((a == b).all()))


def _solve_block(eq: BlockCorrectionEquations, n_frames: int, n_points: int, *,
                 frame_prior=None, point_prior=None, free_frames=None, free_points=None,
                 covariance: bool = False, rcond: float = 1e-12,
                 dense_limit: int = 0, cache: dict | None = None) -> BlockSolution:
    """One linear step of a block adjustment by the reduction (3.5.13)–(3.5.16).

    Builds N₁₁ (q×q blocks), N₂₂ (3×3 blocks) and the q×3 blocks of N₁₂ from the correction
    equations, eliminates the points (3.5.16) with vectorised 3×3 block inverses straight into
    the lower band of the renumbered reduced matrix, factorises it by a band Cholesky
    (:class:`_Factorisation`, LAPACK ``dpbtrf``) and recovers the points by back-substitution
    δ₂ = N₂₂⁻¹(L₂ᴺ − N₁₂ᵀδ₁) (second row of (3.5.14)). The loops over observations and points
    are compiled (:mod:`photolib._block_kernels`). ``timings`` of the result holds the seconds
    spent on the normal equations, the reduction, the factorisation and the back-substitution.

    Parameters
    ----------
    eq : BlockCorrectionEquations
        The image-observation rows (3.5.2)/(3.5.3).
    n_frames, n_points : int
        Number of images and points.
    frame_prior, point_prior : (l, p) pairs of arrays (n_frames, q) / (n_points, 3), optional
        Direct observations of single unknowns, δ + l = v with weight p (p = 0: none):
        control points (3.5.17), GNSS centres (3.5.18), INS angles (3.5.19).
    free_frames, free_points : bool arrays, optional
        False holds an image / a point fixed (its correction is 0, its columns drop out: (3.5.3),
        (3.5.4)). Default: all free.
    covariance : bool
        Also return the diagonal blocks of Q = N⁻¹ (for m_j = μ√Q_jj, (3.5.11)): Q₁₁ = S⁻¹ and
        Q₂₂ = N₂₂⁻¹ + N₂₂⁻¹N₁₂ᵀQ₁₁N₁₂N₂₂⁻¹ per point. Needs S⁻¹ dense: O((6n)²) memory.
    rcond : float
        Smallest acceptable pivot of the scaled reduced matrix; below it the block is declared
        singular (datum defect) with :class:`DegenerateGeometryError`.
    dense_limit : int
        Reduced systems of up to this many unknowns are factorised by the dense Cholesky
        (default 0: always the band Cholesky, which is as fast for small blocks).
    cache : dict, optional
        Keeps the block pattern (:func:`_block_pattern`) from one iteration to the next.
    """
    from . import _block_kernels as kernels

    t0 = time.perf_counter()
    timings = {}
    q = eq.B1.shape[2]
    free_frames = np.ones(n_frames, bool) if free_frames is None else np.asarray(free_frames, bool)
    free_points = np.ones(n_points, bool) if free_points is None else np.asarray(free_points, bool)
    frame, point = np.asarray(eq.frame, np.intp), np.asarray(eq.point, np.intp)
    pattern = None if cache is None else cache.get("pattern")
    if pattern is None or not (_same(pattern["frame"], frame) and _same(pattern["point"], point) and
                               _same(pattern["free"][0], free_frames) and _same(pattern["free"][1], free_points)):
        pattern = _block_pattern(frame, point, n_frames, n_points, q, free_frames, free_points)
        if cache is not None:
            cache["pattern"] = pattern
    slot_frame, slot_point = pattern["slot_frame"], pattern["slot_point"]
    if not covariance and (pattern["bandwidth"] + 1) * pattern["order"].size <= _ONE_THREAD_FROM and \
            pattern["order"].size > dense_limit:
        return _solve_block_compiled(eq, pattern, n_frames, n_points, frame_prior, point_prior, free_points,
                                     rcond, t0)

    # normal-equation blocks (3.5.8) in the convention N·δ = Lᴺ of (3.5.13): N₁₁, Lᴺ₁ per image,
    # N₂₂, Lᴺ₂ per point, one q×3 block W of N₁₂ per observation of a free point in a free image.
    # (The blocks of fixed points and images are computed too and replaced below.)
    P, N11, L1, N22, L2, W = _normal_arrays(eq, n_frames, n_points, slot_frame.size)
    kernels.normal_blocks(frame, point, np.ascontiguousarray(eq.B1, dtype=float),
                          np.ascontiguousarray(eq.B2, dtype=float), np.ascontiguousarray(eq.L, dtype=float), P,
                          pattern["slot"], N11, L1, N22, L2, W)
    _add_priors(frame_prior, N11, L1)
    _add_priors(point_prior, N22, L2)
    # fixed points/images: identity placeholders, their corrections are forced to zero below
    fixed_points, fixed_frames = pattern["fixed_points"], pattern["fixed_frames"]
    if fixed_points.size:
        N22[fixed_points] = np.eye(3)
        L2[fixed_points] = 0.0
    if fixed_frames.size:
        N11[fixed_frames] = np.eye(q)
        L1[fixed_frames] = 0.0
    timings["normal equations"] = time.perf_counter() - t0

    # reduction (3.5.16): S = N₁₁ − N₁₂N₂₂⁻¹N₁₂ᵀ, s = L₁ᴺ − N₁₂N₂₂⁻¹L₂ᴺ: one q×q block per pair of
    # images with a common point (fig. 3.12), written into the lower band of the renumbered S
    t = time.perf_counter()
    iN22 = _invert_3x3_blocks(N22, rcond)
    order, b = pattern["order"], pattern["bandwidth"]
    n_unknowns = order.size
    band = np.zeros((b + 1, n_unknowns), order="F")        # Fortran order: LAPACK works in it without a copy
    s = L1.copy()
    kernels.reduce_to_band(pattern["ptr"], slot_frame, W, iN22, L2, pattern["position"], N11,
                           s, band)
    timings["reduction"] = time.perf_counter() - t

    t = time.perf_counter()
    d = np.sqrt(band[0])
    _check_diagonal(d)
    kernels.scale_band(band, 1.0 / d)
    scale = np.empty(n_unknowns)
    scale[order] = 1.0 / d
    try:
        fac = _Factorisation.from_band(band, order, scale, rcond, dense=n_unknowns <= dense_limit)
    except DegenerateGeometryError as singular:
        raise _singular_block(singular.min_pivot, singular.column, pattern, frame) from None
    del band
    timings["factorisation"] = time.perf_counter() - t

    t = time.perf_counter()
    keep = pattern["keep"]
    d1 = np.zeros(n_frames * q)
    d1[keep] = fac.solve(s.ravel()[keep])
    d1 = d1.reshape(n_frames, q)
    d2 = np.empty((n_points, 3))
    kernels.back_substitute(slot_frame, slot_point, W, d1, iN22, L2, free_points, d2)   # (3.5.14), row 2
    timings["back-substitution"] = time.perf_counter() - t

    Q1 = Q2 = None
    if covariance:
        t = time.perf_counter()
        Q11 = np.zeros((n_frames * q, n_frames * q))
        Q11[np.ix_(keep, keep)] = fac.inverse()
        Q1 = Q11.reshape(n_frames, q, n_frames, q)[np.arange(n_frames), :, np.arange(n_frames), :]
        # Q₂₂ per point: N₂₂⁻¹ + N₂₂⁻¹ (Σ_a,b W_aᵀ Q₁₁[c_a, c_b] W_b) N₂₂⁻¹ over observation pairs
        pts, frm = slot_point, slot_frame
        a, b = _pairs_by_point(pts, n_points)
        T = np.zeros((n_points, 3, 3))
        Q11b = Q11.reshape(n_frames, q, n_frames, q)
        for start in range(0, a.size, 100_000):
            sa, sb = a[start:start + 100_000], b[start:start + 100_000]
            blocks = np.einsum("kia,kij,kjb->kab", W[sa], Q11b[frm[sa], :, frm[sb], :], W[sb])
            T += _block_sum(pts[sa], blocks, n_points)
        Q2 = iN22 + iN22 @ T @ iN22
        Q2[~free_points] = 0.0
        timings["covariance"] = time.perf_counter() - t
    return BlockSolution(d1, d2, Q1, Q2, timings)


def _solve_block_compiled(eq, pattern, n_frames, n_points, frame_prior, point_prior, free_points, rcond, t0):
    """The same linear step as :func:`_solve_block` for small reduced systems, as two compiled calls.

    For a band of up to ``_ONE_THREAD_FROM`` numbers (blocks of up to about ten images) the step
    costs little arithmetic and much per-call overhead, so the normal-equation blocks, the direct
    observations, the fixed unknowns and the N₂₂ inverses are one compiled call
    (:func:`photolib._block_kernels.normal_step`), and the reduction, the scaling, the band
    Cholesky (:func:`photolib._block_kernels.band_cholesky`, the algorithm of LAPACK's unblocked
    ``dpbtf2``), the solution and the back-substitution another (``reduced_step``). The errors
    are those of :func:`_solve_block`.
    """
    from . import _block_kernels as kernels
    q = eq.B1.shape[2]
    frame, point = np.asarray(eq.frame, np.intp), np.asarray(eq.point, np.intp)
    slot_frame = pattern["slot_frame"]
    P, N11, L1, N22, L2, W = _normal_arrays(eq, n_frames, n_points, slot_frame.size)
    fl, fp = _prior_arrays(frame_prior, (n_frames, q))
    pl, pp = _prior_arrays(point_prior, (n_points, 3))
    iN22, status = np.empty((n_points, 3, 3)), np.zeros(n_points, np.int8)
    kernels.normal_step(frame, point, np.ascontiguousarray(eq.B1, dtype=float), np.ascontiguousarray(eq.B2, dtype=float),
                        np.ascontiguousarray(eq.L, dtype=float), P, pattern["slot"], N11, L1, N22, L2, W, fl, fp, pl, pp,
                        pattern["fixed_frames"], pattern["fixed_points"], rcond, iN22, status)
    if status.any():
        _check_inverse_status(N22, status, rcond)
    order = pattern["order"]
    if "keep_index" not in pattern:
        pattern["keep_index"] = np.flatnonzero(pattern["keep"])
    band = np.zeros((pattern["bandwidth"] + 1, order.size), order="F")
    d1, d2 = np.zeros((n_frames, q)), np.empty((n_points, 3))
    code, value, column = kernels.reduced_step(pattern["ptr"], slot_frame, pattern["slot_point"], W, iN22, L2,
                                               pattern["position"], N11, L1, order, pattern["keep_index"],
                                               free_points, band, d1, d2)
    if code == 1:                      # the band is reduced but not yet scaled: the check of _solve_block
        _check_diagonal(np.sqrt(band[0]))
    if code == 2 or not value > rcond:
        raise _singular_block(value, column, pattern, frame)
    return BlockSolution(d1, d2, None, None, {"linear step (compiled)": time.perf_counter() - t0})


def _normal_arrays(eq, n_frames, n_points, n_slots):
    """The weights as an (m, r) array and zeroed N₁₁, Lᴺ₁, N₂₂, Lᴺ₂ and the q×3 blocks W of N₁₂."""
    m, r, q = eq.B1.shape
    P = np.asarray(eq.P, dtype=float)
    P = np.full((m, r), P) if P.ndim == 0 else np.ascontiguousarray(np.broadcast_to(P, (m, r)))
    return (P, np.zeros((n_frames, q, q)), np.zeros((n_frames, q)), np.zeros((n_points, 3, 3)),
            np.zeros((n_points, 3)), np.zeros((n_slots, q, 3)))


def _prior_arrays(prior, shape):
    """(l, p) of direct observations as contiguous arrays of ``shape`` ((0, k) arrays when there are none)."""
    if prior is None:
        empty = np.zeros((0, shape[1]))
        return empty, empty
    return tuple(np.ascontiguousarray(np.broadcast_to(np.asarray(a, dtype=float), shape)) for a in prior)


def _add_priors(prior, N, L):
    """Add direct observations (values l, weights p) of block unknowns to their diagonal blocks
    of N and to Lᴺ, in place: N_ii += p, Lᴺ_i −= p·l (the (3.5.17)–(3.5.19) rows folded in)."""
    if prior is None:
        return
    l, p = (np.asarray(a, dtype=float) for a in prior)
    idx = np.arange(p.shape[1])
    N[:, idx, idx] += p
    L -= p * l


def _direct_observations(obs, shape):
    """Validate direct observations of unknowns given as (values, weights); NaN values get weight 0.

    Returns (values, weights) broadcast to ``shape`` (or (None, None) when ``obs`` is None).
    """
    if obs is None:
        return None, None
    values, weights = (np.broadcast_to(np.asarray(a, dtype=float), shape) for a in obs)
    weights = np.where(np.isfinite(values), weights, 0.0)
    if np.any(~np.isfinite(weights)) or np.any(weights < 0):
        raise InputError("weights of the direct observations must be finite and non-negative")
    return np.where(weights > 0, values, 0.0), weights


def solve_block_normal_equations(eq: BlockCorrectionEquations, n_frames: int, n_points: int, *,
                                 frame_prior=None, point_prior=None, global_prior=None, free_frames=None,
                                 free_points=None, covariance: bool = False, rcond: float = 1e-12,
                                 dense_limit: int = 0, global_names=(), frame_names=()) -> BlockSolution:
    """One linear step of a block adjustment by the reduction (3.5.13)–(3.5.16) — the block-sparse solver.

    Builds N₁₁ (q×q blocks), N₂₂ (3×3 blocks) and the block-sparse N₁₂ from the correction
    equations, eliminates the points (3.5.16) with vectorised 3×3 block inverses, factorises the
    reduced matrix of the image unknowns by a band Cholesky (the images renumbered for a narrow
    band, LAPACK ``dpbtrf``) and recovers the points by back-substitution
    δ₂ = N₂₂⁻¹(L₂ᴺ − N₁₂ᵀδ₁) (second row of (3.5.14)). With
    :class:`GlobalBlockCorrectionEquations` the block-wide unknowns join the reduced system and are
    solved from their own g×g system after the images are eliminated in their turn
    (G = S₃₃ − S₃₁S₁₁⁻¹S₁₃); a (near-)singular G raises :class:`DegenerateGeometryError` naming
    the global unknowns and the image unknowns that absorb them.

    Parameters
    ----------
    eq : BlockCorrectionEquations or GlobalBlockCorrectionEquations
        The image-observation rows (3.5.2)/(3.5.3) (and (3.6.3) with globals).
    n_frames, n_points : int
        Number of images and points.
    frame_prior, point_prior : (l, p) pairs of arrays (n_frames, q) / (n_points, 3), optional
        Direct observations of single unknowns, δ + l = v with weight p (p = 0: none):
        control points (3.5.17), GNSS centres (3.5.18), INS angles (3.5.19).
    global_prior : (l, p) pair of arrays (g,), optional
        Direct observations of the global unknowns.
    free_frames, free_points : bool arrays, optional
        False holds an image / a point fixed (its correction is 0, its columns drop out: (3.5.3),
        (3.5.4)). Default: all free. (``free_frames`` only without global unknowns.)
    covariance : bool
        Also return the diagonal blocks of Q = N⁻¹ (for m_j = μ√Q_jj, (3.5.11)). Needs S⁻¹ dense:
        O((6n)²) memory.
    rcond : float
        Smallest acceptable pivot of the scaled reduced matrix; below it the block is declared
        singular (datum defect).
    dense_limit : int
        Reduced systems of up to this many unknowns are factorised by the dense Cholesky
        (default 0: always the band Cholesky).
    global_names, frame_names : sequences of str, optional
        Names used in the message of a singular global block.

    Returns
    -------
    BlockSolution
        δ₁, δ₂ (and δ₃), the cofactor blocks if asked, and the seconds spent per stage.

    Raises
    ------
    InputError
        Shapes that do not match, NaN/inf in the equations.
    DegenerateGeometryError
        A point not determined (parallel rays), a datum defect, inseparable global unknowns.

    References
    ----------
    Chibunichev (2022), §3.5, eqs. (3.5.8)–(3.5.16); §3.6, eq. (3.6.3); §3.8, eq. (3.8.15).

    Examples
    --------
    Two images, five points, correction equations of a made-up block (control: the direct
    observations of the image unknowns):

    >>> import numpy as np
    >>> rng = np.random.default_rng(0)
    >>> frame, point = np.repeat([0, 1], 5), np.tile(np.arange(5), 2)
    >>> eq = BlockCorrectionEquations(frame, point, rng.normal(size=(10, 2, 6)),
    ...                               rng.normal(size=(10, 2, 3)), np.zeros((10, 2)))
    >>> prior = (np.zeros((2, 6)), np.ones((2, 6)))
    >>> sol = solve_block_normal_equations(eq, 2, 5, frame_prior=prior)
    >>> float(np.abs(sol.delta1).max()), float(np.abs(sol.delta2).max())
    (0.0, 0.0)
    """
    _check_block_equations(eq, n_frames, n_points)
    if isinstance(eq, GlobalBlockCorrectionEquations):
        if free_frames is not None and not np.all(free_frames):
            raise InputError("fixed images are not supported together with global unknowns")
        t = time.perf_counter()
        sol = _solve_block_global(eq, n_frames, n_points, frame_prior=frame_prior, point_prior=point_prior,
                                  global_prior=global_prior, free_points=free_points, covariance=covariance,
                                  rcond=rcond, global_names=global_names, frame_names=frame_names)
        sol.timings["solve"] = time.perf_counter() - t
        return sol
    if global_prior is not None:
        raise InputError("global_prior needs GlobalBlockCorrectionEquations (with B3)")
    return _solve_block(eq, n_frames, n_points, frame_prior=frame_prior, point_prior=point_prior,
                        free_frames=free_frames, free_points=free_points, covariance=covariance, rcond=rcond,
                        dense_limit=dense_limit)


def _check_block_equations(eq, n_frames, n_points):
    """Shapes, index ranges and finiteness of block correction equations (at the public boundary)."""
    if not isinstance(eq, BlockCorrectionEquations):
        raise InputError(f"eq must be BlockCorrectionEquations, got {type(eq).__name__}")
    B1, B2, L = (np.asarray(a) for a in (eq.B1, eq.B2, eq.L))
    if B1.ndim != 3 or B2.ndim != 3 or L.ndim != 2 or B2.shape[2] != 3 or \
            not (B1.shape[:2] == B2.shape[:2] == L.shape) or np.shape(eq.frame) != (L.shape[0],) or \
            np.shape(eq.point) != (L.shape[0],):
        raise InputError(f"block correction equations: B1 (m, r, q), B2 (m, r, 3), L (m, r), frame and point (m,) "
                         f"expected, got {B1.shape}, {B2.shape}, {L.shape}, {np.shape(eq.frame)}, {np.shape(eq.point)}")
    frame, point = np.asarray(eq.frame), np.asarray(eq.point)
    if frame.size and (frame.min() < 0 or frame.max() >= n_frames or point.min() < 0 or point.max() >= n_points):
        raise InputError(f"image or point index outside 0…{n_frames - 1} / 0…{n_points - 1}")
    if not (np.all(np.isfinite(B1)) and np.all(np.isfinite(B2)) and np.all(np.isfinite(L))
            and np.all(np.isfinite(eq.P))):
        raise InputError("the block correction equations contain NaN or inf")


class _BlockSolver:
    """The block-sparse linear solver of the one Gauss–Newton loop (§3.5; §3.6/§3.8 with globals).

    The state is (frames, points, globals); δ is a :class:`BlockSolution`.
    """

    watch_divergence = True

    def __init__(self, linearize, shapes, with_globals, obs, free_frames, free_points, tols, covariance, rcond,
                 dense_limit, global_names, frame_names):
        self._linearize, self.with_globals = linearize, with_globals
        self.obs, self.free_frames, self.free_points, self.tols = obs, free_frames, free_points, tols
        self.covariance, self.rcond, self.dense_limit = covariance, rcond, dense_limit
        self.global_names, self.frame_names = tuple(global_names), tuple(frame_names)
        (n_frames, q), n_points, g = shapes
        self.n_frames, self.q, self.n_points, self.g = n_frames, q, n_points, g
        self.n_unknowns = q * int(free_frames.sum()) + 3 * int(free_points.sum()) + g
        self.m_rows = None
        self.timings = {"jacobian": 0.0}
        self.cache = {}           # the block pattern and band layout, the same in every iteration

    def linearize(self, state):
        t = time.perf_counter()
        eq = self._linearize(*state) if self.with_globals else self._linearize(*state[:2])
        self.timings["jacobian"] += time.perf_counter() - t
        return eq

    def priors(self, state):
        # l = x⁰ − x_measured for the directly observed unknowns, (3.5.17)–(3.5.19)
        return [None if w is None else (np.where(w > 0, x - v, 0.0), w) for x, (v, w) in zip(state, self.obs)]

    @staticmethod
    def vtpv(eq, pr):
        return float((eq.P * eq.L ** 2 if np.ndim(eq.P) == 0 else np.broadcast_to(eq.P, eq.L.shape) * eq.L ** 2).sum()) + \
            sum(float((p[1] * p[0] ** 2).sum()) for p in pr if p is not None)

    def solve(self, eq, pr, covariance):
        if self.with_globals:
            return _solve_block_global(eq, self.n_frames, self.n_points, frame_prior=pr[0], point_prior=pr[1],
                                       global_prior=pr[2], free_points=self.free_points, covariance=covariance,
                                       rcond=self.rcond, global_names=self.global_names,
                                       frame_names=self.frame_names)
        return _solve_block(eq, self.n_frames, self.n_points, frame_prior=pr[0], point_prior=pr[1],
                            free_frames=self.free_frames, free_points=self.free_points, covariance=covariance,
                            rcond=self.rcond, dense_limit=self.dense_limit, cache=self.cache)

    def step(self, eq, state, iteration, history):
        pr = self.priors(state)
        value = self.vtpv(eq, pr)
        if not np.isfinite(value):
            raise ConvergenceError(f"the correction equations became NaN/inf at iteration {iteration}", history)
        if self.m_rows is None:
            self.m_rows = eq.L.size + sum(int((w > 0).sum()) for _, w in self.obs if w is not None)
            if self.m_rows <= self.n_unknowns:
                raise InputError(f"{self.m_rows} correction equations cannot determine {self.n_unknowns} "
                                 "unknowns (M ≤ N)")
        sol = self.solve(eq, pr, False)
        for key, val in sol.timings.items():
            self.timings[key] = self.timings.get(key, 0.0) + val
        return sol, value

    def _deltas(self, sol):
        return (sol.delta1, sol.delta2) + ((sol.delta3,) if self.with_globals else ())

    def record(self, iteration, state, sol, vtpv):
        step = np.array([np.abs(d).max(initial=0.0) for d in self._deltas(sol)])
        return IterationRecord(iteration, np.empty(0), step, vtpv)

    def update(self, state, sol):
        frames, points, glob = state
        return (frames + sol.delta1, points + sol.delta2, glob + sol.delta3 if self.with_globals else glob)

    @staticmethod
    def finite(state):
        return all(bool(np.isfinite(s).all()) for s in state)

    def converged(self, sol):
        return all(bool((np.abs(d) < t).all()) for d, t in zip(self._deltas(sol), self.tols))

    def no_convergence(self, max_iter, sol):
        step = [float(np.abs(d).max(initial=0.0)) for d in self._deltas(sol)]
        what = ("images", "points", "globals")
        return (f"no convergence in {max_iter} iterations: last max |δ| = "
                + ", ".join(f"{v:.3g} ({w})" for v, w in zip(step, what)))

    def finish(self, state, history):
        frames, points, glob = state
        eq = self.linearize(state)
        pr = self.priors(state)
        dof = self.m_rows - self.n_unknowns
        mu = float(np.sqrt(self.vtpv(eq, pr) / dof))
        zeros = [np.zeros_like(s) if p is None else p[0] for s, p in zip(state, pr)]
        out = Adjustment(x=np.concatenate([frames.ravel(), points.ravel(), glob]), residuals=eq.L.copy(), mu=mu,
                         Q=None, std=None, corr=None, dof=dof, iterations=len(history), converged=True,
                         history=history, names=self.global_names, frames=frames, points=points,
                         globals=glob if self.with_globals else None, frame_residuals=zeros[0],
                         point_residuals=zeros[1], global_residuals=zeros[2] if self.with_globals else None,
                         timings=self.timings)
        if self.covariance:
            t = time.perf_counter()
            sol = self.solve(eq, pr, True)
            out.Q1, out.Q2, out.Q3, out.Q13, out.Q23 = sol.Q1, sol.Q2, sol.Q3, sol.Q13, sol.Q23
            out.frames_std = mu * np.sqrt(np.einsum("kii->ki", sol.Q1))
            out.points_std = mu * np.sqrt(np.einsum("kii->ki", sol.Q2))
            if self.with_globals:
                out.globals_std = mu * np.sqrt(np.diag(sol.Q3))
            self.timings["covariance"] = sol.timings.get("covariance", time.perf_counter() - t)
        return out


def block_gauss_newton(linearize, frames0, points0, globals0=None, *, frame_observations=None,
                       point_observations=None, global_observations=None, free_frames=None, free_points=None,
                       tol_frames=1e-8, tol_points=1e-6, tol_globals=1e-10, max_iter: int = 30,
                       covariance: bool = False, rcond: float = 1e-12, dense_limit: int = 0, global_names=(),
                       frame_names=(), progress=None) -> Adjustment:
    """Gauss–Newton iterations of a block adjustment solved by the reduction (3.5.16).

    The one Gauss–Newton loop of :func:`gauss_newton` (δ = −N⁻¹Lᴺ (3.5.9), iterate until the
    corrections are negligible, then μ (3.5.12) and m_j (3.5.11)) with the block-sparse linear
    solver :func:`solve_block_normal_equations`, so that a block of thousands of images stays
    sparse. With ``globals0`` a third group of unknowns shared by all observations
    (self-calibration (3.6.3), rig mounting elements (3.8.15)) joins the reduced system. VᵀPV
    growing in four consecutive iterations stops the iteration (divergence).

    Parameters
    ----------
    linearize : callable
        ``linearize(frames, points) -> BlockCorrectionEquations`` at the approximation, or with
        ``globals0``: ``linearize(frames, points, globals) -> GlobalBlockCorrectionEquations``.
    frames0, points0 : array_like (n_frames, q), (n_points, 3)
        Approximate values.
    globals0 : array_like (g,), optional
        Approximate values of the block-wide unknowns.
    frame_observations, point_observations, global_observations : (values, weights) pairs, optional
        Direct observations of image unknowns / coordinates / globals, same shapes as the
        approximations; weight 0 (value NaN allowed) means "not observed". Their correction
        equations are δ + l = v with l = approximate − measured, (3.5.17)–(3.5.19).
    free_frames, free_points : bool arrays, optional
        False holds the unknowns fixed at their start values (``free_frames`` only without globals).
    tol_frames, tol_points, tol_globals : float or arrays (q,), (3,), (g,)
        Convergence when every |δ| is below them.
    max_iter : int
        Iterations before :class:`ConvergenceError`.
    covariance : bool
        Compute the cofactor blocks and m_j at the end (see :func:`solve_block_normal_equations`).
    rcond : float
        Smallest acceptable scaled pivot (datum-defect test).
    dense_limit : int
        Reduced systems up to this size use the dense Cholesky.
    global_names, frame_names : sequences of str, optional
        Names of the global unknowns (messages, :meth:`Adjustment.summary`) and of the image unknowns.
    progress : callable, optional
        Called with each :class:`IterationRecord` (``delta`` holds max |δ₁|, max |δ₂| [, max |δ₃|]).

    Returns
    -------
    Adjustment
        With ``frames``, ``points`` (and ``globals``), residuals of the image and direct
        observations, μ, dof, the history, the cofactor blocks and m_j if asked, and ``timings``.

    Raises
    ------
    InputError
        Malformed approximations or observations; M ≤ N.
    DegenerateGeometryError
        Datum defect, undetermined points, inseparable global unknowns.
    ConvergenceError
        NaN/inf, divergence, or no convergence in ``max_iter`` steps (with the history).

    References
    ----------
    Chibunichev (2022), §3.5, eqs. (3.5.8)–(3.5.19); §3.6, eq. (3.6.3); §3.8, eq. (3.8.15).

    Examples
    --------
    Adjust a line of "images" that each see two "points" — a toy block with q = 1 whose
    image unknown is an offset a_i and whose point unknowns are (X, Y, Z) measured directly
    in the first two rows as X + a_i:

    >>> import numpy as np
    >>> truth = np.array([[1.0, 2.0, 3.0], [4.0, 5.0, 6.0]])
    >>> frame, point = np.array([0, 0, 1, 1]), np.array([0, 1, 0, 1])
    >>> def linearize(frames, points):
    ...     r = points[point] + frames[frame, :1] - truth[point]
    ...     B1 = np.ones((4, 3, 1))
    ...     return BlockCorrectionEquations(frame, point, B1, np.broadcast_to(np.eye(3), (4, 3, 3)).copy(), r)
    >>> adj = block_gauss_newton(linearize, np.zeros((2, 1)), truth + 0.1,
    ...                          frame_observations=(np.zeros((2, 1)), np.ones((2, 1))))
    >>> float(np.abs(adj.points - truth).max()) < 1e-9, adj.iterations
    (True, 2)
    """
    try:
        frames = np.array(frames0, dtype=float)
        points = np.array(points0, dtype=float)
        glob = np.zeros(0) if globals0 is None else np.array(globals0, dtype=float).reshape(-1)
    except (TypeError, ValueError) as exc:
        raise InputError(f"the approximate values must be numbers: {exc}") from None
    if not callable(linearize):
        raise InputError("linearize must be a callable")
    if frames.ndim != 2 or points.ndim != 2 or points.shape[1] != 3:
        raise InputError(f"approximations must be (n_frames, q) and (n_points, 3), got {frames.shape}, {points.shape}")
    if not (np.all(np.isfinite(frames)) and np.all(np.isfinite(points)) and np.all(np.isfinite(glob))):
        raise InputError("the approximate values contain NaN or inf")
    if not (isinstance(max_iter, (int, np.integer)) and max_iter >= 1):
        raise InputError(f"max_iter must be a positive integer, got {max_iter!r}")
    n_frames, q = frames.shape
    n_points, g = points.shape[0], glob.size
    with_globals = globals0 is not None
    if with_globals and free_frames is not None and not np.all(free_frames):
        raise InputError("fixed images are not supported together with global unknowns")
    free_frames = np.ones(n_frames, bool) if free_frames is None else np.asarray(free_frames, bool)
    free_points = np.ones(n_points, bool) if free_points is None else np.asarray(free_points, bool)
    if free_frames.shape != (n_frames,) or free_points.shape != (n_points,):
        raise InputError("free_frames / free_points: one flag per image / point")
    obs = [_direct_observations(frame_observations, frames.shape),
           _direct_observations(point_observations, points.shape),
           _direct_observations(global_observations, glob.shape)]
    try:
        tols = [np.broadcast_to(np.asarray(t, dtype=float), (s,))
                for t, s in ((tol_frames, q), (tol_points, 3), (tol_globals, g))]
    except ValueError:
        raise InputError("tolerances: one value or one per unknown of the group") from None
    solver = _BlockSolver(linearize, ((n_frames, q), n_points, g), with_globals, obs, free_frames, free_points,
                          tols, covariance, rcond, dense_limit, global_names, frame_names)
    return _iterate(solver, (frames, points, glob), max_iter, progress)


def block_equations_dense(eq: BlockCorrectionEquations, n_frames: int, n_points: int, free_points=None):
    """The same correction equations as one dense (B, L, P) for :func:`solve_normal_equations`.

    Columns: the q unknowns of every image, then X, Y, Z of every free point — the layout of
    fig. 3.11. Only for small blocks (checks, teaching): B has m·r rows and q·n + 3·k columns.

    Parameters
    ----------
    eq : BlockCorrectionEquations
    n_frames, n_points : int
    free_points : bool array, optional
        Points that are unknowns (default: all).

    Returns
    -------
    B : ndarray (m·r, q·n + 3·k_free)
    L : ndarray (m·r,)
    P : ndarray (m·r,)
        Weights per row.

    Raises
    ------
    InputError
        Shapes that do not match, indices outside the block, NaN/inf.

    References
    ----------
    Chibunichev (2022), §3.5, eqs. (3.5.2)–(3.5.8); fig. 3.11.

    Examples
    --------
    >>> import numpy as np
    >>> rng = np.random.default_rng(0)
    >>> frame, point = np.repeat([0, 1], 5), np.tile(np.arange(5), 2)
    >>> eq = BlockCorrectionEquations(frame, point, rng.normal(size=(10, 2, 6)), rng.normal(size=(10, 2, 3)),
    ...                               rng.normal(size=(10, 2)))
    >>> B, L, P = block_equations_dense(eq, 2, 5)
    >>> B.shape, L.shape
    ((20, 27), (20,))
    """
    _check_block_equations(eq, n_frames, n_points)
    m, r, q = eq.B1.shape
    free_points = np.ones(n_points, bool) if free_points is None else np.asarray(free_points, bool)
    if free_points.shape != (n_points,):
        raise InputError(f"free_points: one flag per point ({n_points}), got shape {free_points.shape}")
    column = np.cumsum(free_points) - 1
    n_cols = q * n_frames + 3 * int(free_points.sum())
    B = np.zeros((m * r, n_cols))
    rows = np.arange(m * r).reshape(m, r)
    for i in range(q):
        B[rows, (eq.frame * q + i)[:, None]] = eq.B1[:, :, i]
    on = free_points[eq.point]
    for i in range(3):
        B[rows[on], (q * n_frames + 3 * column[eq.point[on]] + i)[:, None]] = eq.B2[on, :, i]
    P = np.broadcast_to(np.asarray(eq.P, dtype=float), (m, r)).ravel()
    return B, eq.L.ravel(), P


# --- Chapter 3 (§3.6, §3.8): block adjustment with block-wide (global) unknowns -------------------
@dataclass
class GlobalBlockCorrectionEquations(BlockCorrectionEquations):
    """Block correction equations with a third group: unknowns shared by the whole block.

    Observation k (r rows):  B1[k]·δ₁[frame[k]] + B2[k]·δ₂[point[k]] + B3[k]·δ₃ + L[k] = V[k].
    δ₃ holds g block-wide unknowns: the interior orientation and distortion coefficients of a
    self-calibrating bundle (3.6.3), the mounting elements of a camera rig (3.8.15).

    Attributes
    ----------
    B3 : array (m, r, g)
        Derivatives by the global unknowns (zeros where an observation does not depend on them).

    References
    ----------
    Chibunichev (2022), §3.6, eq. (3.6.3); §3.8, eq. (3.8.15).

    Examples
    --------
    >>> import numpy as np
    >>> rng = np.random.default_rng(0)
    >>> frame, point = np.repeat([0, 1], 5), np.tile(np.arange(5), 2)
    >>> eq = BlockCorrectionEquations(frame, point, rng.normal(size=(10, 2, 6)), rng.normal(size=(10, 2, 3)),
    ...                               rng.normal(size=(10, 2)))
    >>> geq = GlobalBlockCorrectionEquations(eq.frame, eq.point, eq.B1, eq.B2, eq.L, B3=np.ones((10, 2, 1)))
    >>> geq.B3.shape
    (10, 2, 1)
    """

    B3: np.ndarray | None = None


def _solve_block_global(eq: GlobalBlockCorrectionEquations, n_frames: int, n_points: int, *,
                                        frame_prior=None, point_prior=None, global_prior=None, free_points=None,
                                        covariance: bool = False, rcond: float = 1e-12, global_names=(),
                                        frame_names=()) -> BlockSolution:
    """One linear step of a block adjustment with block-wide unknowns, by successive reduction.

    The points are eliminated exactly as in (3.5.16) (3×3 block inverses); the global unknowns
    join the reduced system, which is then solved in two stages: the image unknowns are
    eliminated in their turn, leaving the small g×g system of the global unknowns

        G = S₃₃ − S₃₁S₁₁⁻¹S₁₃,   G·δ₃ = s₃ − S₃₁S₁₁⁻¹s₁,   δ₁ = S₁₁⁻¹(s₁ − S₁₃δ₃),

    and δ₂ follows by back-substitution as in (3.5.14). G is the information the block
    geometry carries about the global unknowns once every exterior orientation and point is
    free to absorb what it can: a (near-)zero eigenvalue of G scaled to unit diagonal means the
    block cannot separate them from the other unknowns — :class:`DegenerateGeometryError`
    names the global unknowns of that combination and the image unknowns that absorb it.

    Parameters
    ----------
    eq : GlobalBlockCorrectionEquations
    n_frames, n_points : int
    frame_prior, point_prior, global_prior : (l, p) pairs, optional
        Direct observations δ + l = v with weights p (0: none), shapes (n_frames, q), (n_points, 3), (g,).
    free_points : bool array, optional
        False holds a point fixed (3.5.3).
    covariance : bool
        Also return cofactor blocks: Q₁ (image diagonal blocks), Q₂ (point blocks), Q₃ (g×g),
        Q₁₃ and Q₂₃ (cross-cofactors with the globals) for the correlations of §3.6.
    global_names, frame_names : sequences of str, optional
        Names used in the error message of a singular global block.
    """
    from scipy import sparse

    m, r, q = eq.B1.shape
    g = 0 if eq.B3 is None else eq.B3.shape[2]
    B3 = np.zeros((m, r, 0)) if eq.B3 is None else eq.B3
    P = np.broadcast_to(np.asarray(eq.P, dtype=float), (m, r))
    free_points = np.ones(n_points, bool) if free_points is None else np.asarray(free_points, bool)
    on_free = free_points[eq.point]
    pts, frm = eq.point[on_free], eq.frame[on_free]

    # normal-equation blocks, convention N·δ = Lᴺ of (3.5.13)
    PB1 = P[:, :, None] * eq.B1
    PB3 = P[:, :, None] * B3
    PB2 = P[on_free, :, None] * eq.B2[on_free]
    N11 = _block_sum(eq.frame, np.einsum("kri,krj->kij", PB1, eq.B1), n_frames)
    L1 = -_block_sum(eq.frame, np.einsum("kri,kr->ki", PB1, eq.L), n_frames)
    N22 = _block_sum(pts, np.einsum("kri,krj->kij", PB2, eq.B2[on_free]), n_points)
    L2 = -_block_sum(pts, np.einsum("kri,kr->ki", PB2, eq.L[on_free]), n_points)
    N33 = np.einsum("kri,krj->ij", PB3, B3)
    L3 = -np.einsum("kri,kr->i", PB3, eq.L)
    N13 = _block_sum(eq.frame, np.einsum("kri,krj->kij", PB1, B3), n_frames).reshape(n_frames * q, g)
    W1 = np.einsum("kri,krj->kij", PB1[on_free], eq.B2[on_free])          # q×3 blocks of N₁₂
    W3 = np.einsum("kri,krj->kij", PB3[on_free], eq.B2[on_free])          # g×3 blocks of N₃₂
    _add_priors(frame_prior, N11, L1)
    _add_priors(point_prior, N22, L2)
    if global_prior is not None and g:
        l, p = (np.asarray(a, dtype=float).reshape(g) for a in global_prior)
        N33[np.arange(g), np.arange(g)] += p
        L3 -= p * l
    N22[~free_points] = np.eye(3)
    L2[~free_points] = 0.0

    # eliminate the points (3.5.16): C = [N₁₂; N₃₂] (sparse, (q·n + g) × 3k)
    iN22 = _invert_3x3_blocks(N22, rcond)
    nq = n_frames * q
    rows1 = (frm[:, None, None] * q + np.arange(q)[None, :, None]) * np.ones((1, 1, 3), int)
    cols1 = (pts[:, None, None] * 3 + np.arange(3)[None, None, :]) * np.ones((1, q, 1), int)
    rows3 = (nq + np.arange(g)[None, :, None]) * np.ones((pts.size, 1, 3), int)
    cols3 = (pts[:, None, None] * 3 + np.arange(3)[None, None, :]) * np.ones((1, g, 1), int)
    C = sparse.csr_matrix((np.concatenate([W1.ravel(), W3.ravel()]),
                           (np.concatenate([rows1.ravel(), rows3.ravel()]),
                            np.concatenate([cols1.ravel(), cols3.ravel()]))), shape=(nq + g, n_points * 3))
    Y = C @ _block_diagonal(iN22)
    S = (Y @ C.T).tocsr()
    s = np.concatenate([L1.ravel(), L3]) - Y @ L2.ravel()
    S11 = _block_diagonal(N11) - S[:nq][:, :nq]
    S13 = N13 - S[:nq][:, nq:].toarray()
    S33 = N33 - S[nq:][:, nq:].toarray()

    # eliminate the images, leaving the g×g system of the globals
    fac = _Factorisation(S11.tocsr(), rcond, 0)
    Zg = fac.solve(S13) if g else np.zeros((nq, 0))                      # S₁₁⁻¹S₁₃
    G = S33 - S13.T @ Zg
    if g:
        d = np.sqrt(np.clip(np.diag(G), 0, None))
        d_ref = np.sqrt(np.diag(S33))
        weak = ~(d > 1e-7 * np.maximum(d_ref, 1e-300))
        Gs = G / np.outer(np.where(weak, 1, d), np.where(weak, 1, d))
        w, U = np.linalg.eigh(Gs)
        if weak.any() or w[0] < rcond ** 0.5:
            v = U[:, 0] if not weak.any() else weak.astype(float)
            names = list(global_names) or [f"global {i}" for i in range(g)]
            involved = [names[i] for i in np.argsort(-np.abs(v)) if abs(v[i]) > 0.2 * np.abs(v).max()]
            absorb = -(Zg @ (v / np.where(weak, 1, d)))                   # image corrections that absorb it
            msg = ""
            if absorb.size and np.abs(absorb).max() > 0:
                per = np.sqrt(np.sum(absorb.reshape(n_frames, q) ** 2, axis=0))
                fn = list(frame_names) or [f"image unknown {i}" for i in range(q)]
                top = [fn[i] for i in np.argsort(-per) if per[i] > 0.2 * per.max()]
                msg = f", absorbed by the image unknowns {', '.join(top)}"
            raise DegenerateGeometryError(
                f"the block geometry cannot separate the block-wide unknowns {', '.join(involved)} from the "
                f"other unknowns (smallest scaled eigenvalue of their reduced normal matrix "
                f"{max(w[0], 0.0):.1e}{msg}); add geometry that distinguishes them — terrain relief, "
                "convergent or rotated images, GNSS centres (over flat ground different flying heights "
                "alone do not: each image's Z_S absorbs a change of f) — or fix them")
        iG = np.linalg.inv(G)
    else:
        iG = np.zeros((0, 0))
    s1, s3 = s[:nq], s[nq:]
    d3 = iG @ (s3 - Zg.T @ s1) if g else np.zeros(0)
    d1 = fac.solve(s1 - S13 @ d3)
    dA = np.concatenate([d1, d3])
    d2 = np.einsum("kij,kj->ki", iN22, L2 - (C.T @ dA).reshape(n_points, 3))
    d2[~free_points] = 0.0
    sol = BlockSolution(d1.reshape(n_frames, q), d2, delta3=d3)
    if covariance:
        iS11 = fac.inverse()
        QA = np.empty((nq + g, nq + g))
        QA[:nq, :nq] = iS11 + Zg @ iG @ Zg.T
        QA[:nq, nq:] = -Zg @ iG
        QA[nq:, :nq] = QA[:nq, nq:].T
        QA[nq:, nq:] = iG
        sol.Q1 = QA[:nq, :nq].reshape(n_frames, q, n_frames, q)[np.arange(n_frames), :, np.arange(n_frames), :]
        sol.Q3 = iG
        sol.Q13 = QA[:nq, nq:].reshape(n_frames, q, g)
        # Q₂₂ per point = N₂₂⁻¹ + N₂₂⁻¹ CₚᵀQ_A Cₚ N₂₂⁻¹;  Q₂₃ = −N₂₂⁻¹ Cₚᵀ Q_A[:, globals]
        T = np.zeros((n_points, 3, 3))
        Csc = C.tocsc()
        chunk = max(1, int(2e6 // max(nq + g, 1)) // 3)
        for start in range(0, n_points, chunk):
            stop = min(start + chunk, n_points)
            Cd = Csc[:, 3 * start:3 * stop].toarray()
            Md = QA @ Cd
            T[start:stop] = np.einsum("ica,icb->cab", Cd.reshape(-1, stop - start, 3), Md.reshape(-1, stop - start, 3))
        Q2 = iN22 + iN22 @ T @ iN22
        Q2[~free_points] = 0.0
        sol.Q2 = Q2
        Q23 = -np.einsum("kij,kjg->kig", iN22, (C.T @ QA[:, nq:]).reshape(n_points, 3, g))
        Q23[~free_points] = 0.0
        sol.Q23 = Q23
    return sol


def global_block_equations_dense(eq: GlobalBlockCorrectionEquations, n_frames: int, n_points: int,
                                 free_points=None):
    """Dense (B, L, P) of :class:`GlobalBlockCorrectionEquations`: columns images | globals | free points.

    The column layout of fig. 3.18 (exterior orientation, mounting elements, tie points); for
    checks and figures of small blocks only.

    Parameters
    ----------
    eq : GlobalBlockCorrectionEquations
    n_frames, n_points : int
    free_points : bool array, optional

    Returns
    -------
    B, L, P : ndarray
        As :func:`block_equations_dense`, with the g global columns after the images.

    Raises
    ------
    InputError
        Shapes that do not match, NaN/inf.

    References
    ----------
    Chibunichev (2022), §3.6, eq. (3.6.3); §3.8, eq. (3.8.15); fig. 3.18.

    Examples
    --------
    >>> import numpy as np
    >>> rng = np.random.default_rng(0)
    >>> frame, point = np.repeat([0, 1], 5), np.tile(np.arange(5), 2)
    >>> eq = BlockCorrectionEquations(frame, point, rng.normal(size=(10, 2, 6)), rng.normal(size=(10, 2, 3)),
    ...                               rng.normal(size=(10, 2)))
    >>> geq = GlobalBlockCorrectionEquations(eq.frame, eq.point, eq.B1, eq.B2, eq.L, B3=np.ones((10, 2, 1)))
    >>> global_block_equations_dense(geq, 2, 5)[0].shape
    (20, 28)
    """
    B0, L, P = block_equations_dense(eq, n_frames, n_points, free_points)
    m, r, q = eq.B1.shape
    g = 0 if eq.B3 is None else eq.B3.shape[2]
    B = np.zeros((B0.shape[0], B0.shape[1] + g))
    B[:, :q * n_frames] = B0[:, :q * n_frames]
    if g:
        B[:, q * n_frames:q * n_frames + g] = eq.B3.reshape(m * r, g)
    B[:, q * n_frames + g:] = B0[:, q * n_frames:]
    return B, L, P
