"""The one least-squares engine — Chapter 1, §1.8, equations (1.8.5)–(1.8.10).

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

:func:`solve_normal_equations` is one linear step; :func:`gauss_newton` iterates it over a
``linearize(x) -> (B, L)`` callable supplied by each photogrammetric problem.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Callable, Sequence

import numpy as np

from .errors import ConvergenceError, DegenerateGeometryError, InputError


@dataclass
class IterationRecord:
    """One step of the iteration: the approximation used, the correction found, and VᵀPV."""

    iteration: int
    x: np.ndarray
    delta: np.ndarray
    vtpv: float


@dataclass
class Adjustment:
    """Result of a least-squares adjustment with its a-posteriori accuracy (1.8.8)–(1.8.10)."""

    x: np.ndarray                 # adjusted unknowns
    residuals: np.ndarray         # V = B·δ + L at the solution
    mu: float                     # μ, r.m.s. error of unit weight (1.8.9)
    Q: np.ndarray                 # cofactor matrix N⁻¹
    std: np.ndarray               # m_j = μ√Q_jj (1.8.8)
    corr: np.ndarray              # r_ij (1.8.10)
    dof: int                      # m − n, the number of redundant observations
    iterations: int
    converged: bool
    history: list = field(default_factory=list)
    names: tuple = ()

    @property
    def covariance(self) -> np.ndarray:
        """μ²·Q, the estimated covariance matrix of the unknowns."""
        return self.mu ** 2 * self.Q

    def as_dict(self) -> dict:
        """Unknowns by name (needs ``names``)."""
        return dict(zip(self.names, self.x))


def _as_weights(P, m: int):
    if P is None:
        return None
    P = np.asarray(P, dtype=float)
    if P.ndim == 1:
        if P.shape != (m,):
            raise InputError(f"weights: expected {m} values, got {P.shape[0]}")
    elif P.shape != (m, m):
        raise InputError(f"weight matrix: expected shape ({m}, {m}), got {P.shape}")
    if not np.all(np.isfinite(P)):
        raise InputError("weights contain NaN or inf")
    return P


def _weighted(P, M):
    if P is None:
        return M
    if P.ndim == 1:
        return P[:, None] * M if M.ndim == 2 else P * M
    return P @ M


def weighted_square_sum(V, P=None) -> float:
    """VᵀPV."""
    V = np.asarray(V, dtype=float)
    return float(V @ _weighted(P, V))


def solve_normal_equations(B, L, P=None, names: Sequence[str] = (), rcond: float = 1e-12):
    """One linear least-squares step: δ = −(BᵀPB)⁻¹BᵀPL, (1.8.6)–(1.8.7).

    ``P`` is a vector of weights p_i = 1/m_i² (a diagonal P) or a full matrix; ``None`` means
    unit weights. Returns ``(delta, Q)``. A singular or numerically rank-deficient N raises
    :class:`DegenerateGeometryError` naming the unknowns that are not determined.
    """
    B = np.asarray(B, dtype=float)
    L = np.asarray(L, dtype=float)
    if B.ndim != 2 or L.ndim != 1 or B.shape[0] != L.shape[0]:
        raise InputError(f"correction equations: B must be m×n and L of length m, got {B.shape} and {L.shape}")
    m, n = B.shape
    if m < n:
        raise InputError(f"{m} correction equations cannot determine {n} unknowns")
    if not (np.all(np.isfinite(B)) and np.all(np.isfinite(L))):
        raise InputError("the correction equations contain NaN or inf")
    P = _as_weights(P, m)
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


def accuracy(V, Q, P=None, dof: int | None = None):
    """μ, m_j and r_ij of (1.8.8)–(1.8.10) from the residuals ``V`` and cofactors ``Q``."""
    V = np.asarray(V, dtype=float)
    n = Q.shape[0]
    dof = V.shape[0] - n if dof is None else dof
    vtpv = weighted_square_sum(V, None if P is None else np.asarray(P, dtype=float))
    mu = float(np.sqrt(vtpv / dof)) if dof > 0 else float("nan")
    q = np.sqrt(np.diag(Q))
    return mu, mu * q, Q / np.outer(q, q)


def gauss_newton(linearize: Callable[[np.ndarray], tuple], x0, P=None, *, tol=1e-10,
                 max_iter: int = 50, names: Sequence[str] = (), dof: int | None = None,
                 progress: Callable[[IterationRecord], None] | None = None) -> Adjustment:
    """Iterate the correction equations of a nonlinear problem to convergence (§1.8).

    Parameters
    ----------
    linearize : callable
        ``linearize(x) -> (B, L)``: the partial derivatives and free terms at ``x``, (1.8.5).
    x0 : array
        Approximate values of the unknowns.
    P : array, optional
        Weights of the observations (vector or matrix); unit weights if omitted.
    tol : float or array
        Convergence when every |δ_j| < tol_j (give an array for unknowns of different units).
    max_iter : int
        Iterations allowed before :class:`ConvergenceError` is raised.
    dof : int, optional
        Degrees of freedom for μ if not m − n (e.g. when equations are dependent).
    progress : callable, optional
        Called with each :class:`IterationRecord` (for long adjustments).

    Returns
    -------
    Adjustment
        Estimate, residuals, μ, Q, m_j, r_ij, iteration history.
    """
    x = np.array(x0, dtype=float)
    if x.ndim != 1:
        raise InputError("the unknowns must be a 1-D vector")
    if not np.all(np.isfinite(x)):
        raise InputError("the approximate values contain NaN or inf")
    tol = np.broadcast_to(np.asarray(tol, dtype=float), x.shape)
    history = []
    for iteration in range(1, max_iter + 1):
        B, L = linearize(x)
        delta, Q = solve_normal_equations(B, L, P, names)
        record = IterationRecord(iteration, x.copy(), delta, weighted_square_sum(L, _as_weights(P, len(L))))
        history.append(record)
        if progress is not None:
            progress(record)
        x = x + delta
        if not np.all(np.isfinite(x)):
            raise ConvergenceError(f"the iteration produced NaN/inf at step {iteration}", history)
        if np.all(np.abs(delta) < tol):
            break
    else:
        raise ConvergenceError(
            f"no convergence in {max_iter} iterations: last corrections {np.array2string(delta, precision=3)}",
            history)
    B, L = linearize(x)
    delta, Q = solve_normal_equations(B, L, P, names)
    V = B @ delta + L
    mu, std, corr = accuracy(V, Q, _as_weights(P, len(L)), dof)
    return Adjustment(x=x + delta, residuals=V, mu=mu, Q=Q, std=std, corr=corr,
                      dof=V.shape[0] - x.shape[0] if dof is None else dof,
                      iterations=len(history), converged=True, history=history, names=tuple(names))
