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

import functools
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


class AdjustmentView:
    """Mixin for result objects that hold an :class:`Adjustment` as ``self.adjustment``.

    Gives them the a-posteriori accuracy of (1.8.8)–(1.8.10) and the iteration record under
    the same names as :class:`Adjustment`.
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
    P = np.asarray(P, dtype=float)
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
    """Weights of 2-D point observations as one value per coordinate, (2n,) ordered x₁, y₁, x₂, …

    ``weights`` may be None (unit weights), one per point (n,), one per coordinate (n, 2), or
    already flat (2n,). All must be finite and positive (p_i = 1/m_i², (1.8.6)).
    """
    if weights is None:
        return None
    w = np.asarray(weights, dtype=float)
    if w.shape == (n,):
        w = np.repeat(w, 2)
    elif w.shape == (n, 2):
        w = w.ravel()
    elif w.shape != (2 * n,):
        raise InputError(f"weights: expected shape ({n},), ({n}, 2) or ({2 * n},), got {w.shape}")
    if not np.all(np.isfinite(w)) or np.any(w <= 0):
        raise InputError("weights must be finite and positive (p_i = 1/m_i²)")
    return w


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
    """
    N11, N12, N22 = (np.atleast_2d(np.asarray(M, dtype=float)) for M in (N11, N12, N22))
    L1, L2 = np.asarray(L1, dtype=float), np.asarray(L2, dtype=float)
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
    """

    frame: np.ndarray
    point: np.ndarray
    B1: np.ndarray
    B2: np.ndarray
    L: np.ndarray
    P: np.ndarray | float = 1.0


@dataclass
class BlockSolution:
    """One solved linear step of a block: corrections and (optionally) cofactor blocks."""

    delta1: np.ndarray                  # (n_frames, q) corrections of the image unknowns
    delta2: np.ndarray                  # (n_points, 3) corrections of the points
    Q1: np.ndarray | None = None        # (n_frames, q, q) diagonal blocks of N⁻¹ for the images
    Q2: np.ndarray | None = None        # (n_points, 3, 3) diagonal blocks of N⁻¹ for the points
    timings: dict = field(default_factory=dict)


def _block_sum(index, blocks, n):
    """Σ of ``blocks[k]`` over k with ``index[k] == i``, for i in range(n) → (n, *block shape).

    One product with the n×m "summing matrix" (a 1 in row index[k], column k): faster and far
    lighter than a bincount over m·(block size) flat indices.
    """
    from scipy import sparse
    m = index.shape[0]
    summing = sparse.csr_matrix((np.ones(m), (index, np.arange(m))), shape=(n, m))
    return np.asarray(summing @ blocks.reshape(m, -1)).reshape((n,) + blocks.shape[1:])


def _normal_blocks(index, A, B, n, chunk: int = 16384):
    """Σ_k A[k]ᵀ·B[k] over the observations k of each group i = index[k] → (n, a, b), (3.5.8).

    With A = P·B₁, B = [B₁ | L] (the correction equations bordered by their free terms) and the
    image of each observation as index, the result is [N₁₁ | B₁ᵀPL]. Observations are taken in
    chunks, so the m per-observation products are never held at once.
    """
    out = np.zeros((n, A.shape[2], B.shape[2]))
    for start in range(0, index.shape[0], chunk):
        part = slice(start, start + chunk)
        out += _block_sum(index[part], np.einsum("kri,krj->kij", A[part], B[part]), n)
    return out


def _block_diagonal(blocks):
    """A scipy.sparse block-diagonal matrix (BSR) from an (n, b, b) stack."""
    from scipy import sparse
    n, b, _ = blocks.shape
    return sparse.bsr_matrix((blocks, np.arange(n), np.arange(n + 1)), shape=(n * b, n * b))


def _invert_3x3_blocks(blocks, rcond):
    """Vectorised inverses of the 3×3 diagonal blocks of N₂₂ (one per point).

    Each block is scaled to unit diagonal first; a block whose smallest eigenvalue is below
    ``rcond`` (rays intersecting at a grazing angle, a point not determined) raises
    :class:`DegenerateGeometryError` naming the points. With unit diagonal the other two
    eigenvalues have λ₂·λ₃ ≤ (3/2)², so λ_min ≥ 4·det/9: eigenvalues are computed only for the
    few blocks whose determinant does not already settle it.
    """
    d = np.sqrt(np.einsum("kii->ki", blocks))
    if np.any(~(d > 0)):
        bad = np.flatnonzero(~np.all(d > 0, axis=1))
        raise DegenerateGeometryError(f"points {bad[:10].tolist()} are not determined by any observation")
    scaled = blocks / (d[:, :, None] * d[:, None, :])
    suspect = np.flatnonzero(~(4.0 * np.linalg.det(scaled) / 9.0 >= rcond))
    low = np.linalg.eigvalsh(scaled[suspect])[:, 0] if suspect.size else np.zeros(0)
    if np.any(~(low >= rcond)):
        bad = suspect[~(low >= rcond)]
        raise DegenerateGeometryError(
            f"points {bad[:10].tolist()} are not determined: their rays are (nearly) parallel "
            f"(smallest scaled eigenvalue {np.nanmin(low):.1e})")
    return np.linalg.inv(scaled) / (d[:, :, None] * d[:, None, :])


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


def _blas_on_one_thread():
    """A context in which BLAS and LAPACK run on one thread — if threadpoolctl is installed, else a no-op.

    The band Cholesky of :class:`_Factorisation` works on panels a few hundred unknowns wide: a
    multithreaded BLAS gains nothing there, and when other processes hold the cores its threads
    wait for each other, which made the factorisation up to 40× slower on a busy machine
    (benchmarks/README.md). Setting OPENBLAS_NUM_THREADS=1 has the same effect without threadpoolctl.
    """
    import contextlib
    controller = _blas_controller()
    return contextlib.nullcontext() if controller is None else controller.limit(limits=1, user_api="blas")


@functools.lru_cache(maxsize=None)
def _blas_controller():
    """threadpoolctl's view of the loaded BLAS libraries (found once; None without threadpoolctl)."""
    try:
        from threadpoolctl import ThreadpoolController
    except ImportError:
        return None
    import scipy.linalg  # noqa: F401 — make sure scipy's BLAS is loaded before the libraries are listed
    return ThreadpoolController()


class _Factorisation:
    """Cholesky factorisation S = L·Lᵀ of the reduced matrix (3.5.16), as a band matrix.

    S is scaled to unit diagonal, D·S·D with D = diag(S)^−½, so that its pivots are comparable;
    the unknowns are renumbered by :func:`_band_ordering`; LAPACK's band Cholesky (``dpbtrf``)
    then factorises the lower band in place — n·(b + 1) numbers for a half-bandwidth b, the only
    large array (a general sparse LU would keep both L and U). An aerial block keeps b at about
    one strip of images whatever the number of strips. Systems of up to ``dense_limit`` unknowns
    use the dense Cholesky (``dpotrf``).

    Every pivot of the scaled matrix is an L_ii² in (0, 1]; one ≤ ``rcond`` (or a failed
    factorisation) means S is singular — a datum defect — and raises DegenerateGeometryError.
    """

    def __init__(self, S, rcond, dense_limit=0, chunk: int = 1 << 17):
        from scipy import sparse
        from scipy.linalg import lapack
        n = S.shape[0]
        d = np.sqrt(S.diagonal())
        if np.any(~(d > 0)):
            raise DegenerateGeometryError(
                f"image unknowns {np.flatnonzero(~(d > 0))[:10].tolist()} are not determined by any observation")
        self.n = n
        self.scale = 1.0 / d
        self.dense = n <= dense_limit
        if self.dense:
            self.order, b = np.arange(n), n - 1
        else:
            self.order, b = _band_ordering(S)
        position = np.empty(n, np.intp)
        position[self.order] = np.arange(n)
        # lower band of the scaled, renumbered S in LAPACK storage: band[i − j, j] = S_ij, i ≥ j
        # (filled in chunks of the non-zeros, so no full-size index arrays are held)
        S = sparse.coo_matrix(S)
        band = np.zeros((b + 1, n), order="F")         # Fortran order: LAPACK works in it without a copy
        for start in range(0, S.nnz, chunk):
            part = slice(start, start + chunk)
            row, col = S.row[part], S.col[part]
            i, j = position[row], position[col]
            lower = i >= j
            np.add.at(band, (i[lower] - j[lower], j[lower]),
                      (S.data[part] * self.scale[row] * self.scale[col])[lower])
        del S
        with _blas_on_one_thread():
            if self.dense:       # the same numbers as a full lower triangle (row i − j, column j → i, j)
                full = np.zeros((n, n), order="F")
                ii, jj = np.tril_indices(n)
                full[ii, jj] = band[ii - jj, jj]
                self.factor, info = lapack.dpotrf(full, lower=1, clean=1, overwrite_a=1)
                pivots = np.diag(self.factor) ** 2
            else:
                self.factor, info = lapack.dpbtrf(band, lower=1, overwrite_ab=1)
                pivots = self.factor[0] ** 2
        # info > 0: the leading minor of that order is not positive definite
        self.min_pivot = 0.0 if info != 0 else float(pivots.min(initial=np.inf))
        if not self.min_pivot > rcond:
            raise DegenerateGeometryError(
                "the reduced normal matrix (3.5.16) is singular (smallest scaled pivot "
                f"{self.min_pivot:.1e}): the block has a datum defect — too little control "
                "(fixed or weighted control points, GNSS centres) to fix its position, rotation and scale")

    def solve(self, rhs):
        """S⁻¹·rhs for a vector or a matrix of right-hand sides."""
        from scipy.linalg import cho_solve, cho_solve_banded
        scale = self.scale if rhs.ndim == 1 else self.scale[:, None]
        b = (rhs * scale)[self.order]
        y = cho_solve((self.factor, True), b, check_finite=False) if self.dense else \
            cho_solve_banded((self.factor, True), b, check_finite=False)
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


def solve_block_normal_equations(eq: BlockCorrectionEquations, n_frames: int, n_points: int, *,
                                 frame_prior=None, point_prior=None, free_frames=None, free_points=None,
                                 covariance: bool = False, rcond: float = 1e-12,
                                 dense_limit: int = 0) -> BlockSolution:
    """One linear step of a block adjustment by the reduction (3.5.13)–(3.5.16).

    Builds N₁₁ (6×6 blocks), N₂₂ (3×3 blocks) and the block-sparse N₁₂ from the correction
    equations, eliminates the points (3.5.16) with vectorised 3×3 block inverses, factorises the
    reduced matrix of the image unknowns by a band Cholesky (:class:`_Factorisation`: the images
    renumbered for a narrow band, LAPACK ``dpbtrf``) and recovers the points by back-substitution
    δ₂ = N₂₂⁻¹(L₂ᴺ − N₁₂ᵀδ₁) (second row of (3.5.14)). ``timings`` of the result holds the seconds
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
    """
    import time
    from scipy import sparse

    t0 = time.perf_counter()
    timings = {}
    m, r, q = eq.B1.shape
    P = np.broadcast_to(np.asarray(eq.P, dtype=float), (m, r))
    free_frames = np.ones(n_frames, bool) if free_frames is None else np.asarray(free_frames, bool)
    free_points = np.ones(n_points, bool) if free_points is None else np.asarray(free_points, bool)

    # normal-equation blocks (3.5.8) in the convention N·δ = Lᴺ of (3.5.13). The correction
    # equations are bordered by their free terms, [B | L], so that one pass gives N and −Lᴺ.
    # (The blocks of fixed points and images are computed too and replaced below.)
    PB1, PB2 = P[:, :, None] * eq.B1, P[:, :, None] * eq.B2
    NL1 = _normal_blocks(eq.frame, PB1, np.concatenate([eq.B1, eq.L[:, :, None]], axis=2), n_frames)
    NL2 = _normal_blocks(eq.point, PB2, np.concatenate([eq.B2, eq.L[:, :, None]], axis=2), n_points)
    N11, L1 = NL1[:, :, :q], -NL1[:, :, q]
    N22, L2 = NL2[:, :, :3], -NL2[:, :, 3]
    # N₁₂: one q×3 block per observation of a free point in a free image (3.5.3), sorted by image
    coupled = np.flatnonzero(free_points[eq.point] & free_frames[eq.frame])
    coupled = coupled[np.argsort(eq.frame[coupled], kind="stable")]
    pts, frm = eq.point[coupled], eq.frame[coupled]
    W = np.einsum("kri,krj->kij", PB1, eq.B2)[coupled]
    del PB1, PB2
    _add_priors(frame_prior, N11, L1)
    _add_priors(point_prior, N22, L2)
    # fixed points/images: identity placeholders, their corrections are forced to zero below
    N22[~free_points] = np.eye(3)
    L2[~free_points] = 0.0
    N11[~free_frames] = np.eye(q)
    L1[~free_frames] = 0.0
    timings["normal equations"] = time.perf_counter() - t0

    # reduction (3.5.16): S = N₁₁ − N₁₂N₂₂⁻¹N₁₂ᵀ, s = L₁ᴺ − N₁₂N₂₂⁻¹L₂ᴺ. N₁₂ is block-sparse (BSR):
    # block row = image, block column = point, one q×3 block W per observation; N₁₂N₂₂⁻¹ has the
    # same blocks multiplied by the point's N₂₂⁻¹, and the product with N₁₂ᵀ leaves one q×q block
    # per pair of images with a common point (fig. 3.12).
    t = time.perf_counter()
    iN22 = _invert_3x3_blocks(N22, rcond)
    first = np.searchsorted(frm, np.arange(n_frames + 1))                 # block-row pointers
    N12 = sparse.bsr_matrix((W, pts, first), shape=(n_frames * q, n_points * 3))
    Y = sparse.bsr_matrix((W @ iN22[pts], pts, first), shape=N12.shape)  # N₁₂N₂₂⁻¹
    S = _block_diagonal(N11) - Y @ N12.T
    s = L1.ravel() - Y @ L2.ravel()
    del Y
    keep = np.repeat(free_frames, q)
    if not keep.all():
        S = S.tocsr()[keep][:, keep]
    timings["reduction"] = time.perf_counter() - t

    t = time.perf_counter()
    fac = _Factorisation(S, rcond, dense_limit)
    del S
    timings["factorisation"] = time.perf_counter() - t

    t = time.perf_counter()
    d1 = np.zeros(n_frames * q)
    d1[keep] = fac.solve(s[keep])
    N21d1 = _block_sum(pts, np.einsum("kij,ki->kj", W, d1.reshape(n_frames, q)[frm]), n_points)   # N₁₂ᵀδ₁
    d2 = np.einsum("kij,kj->ki", iN22, L2 - N21d1)                        # (3.5.14), row 2
    d2[~free_points] = 0.0
    timings["back-substitution"] = time.perf_counter() - t

    Q1 = Q2 = None
    if covariance:
        t = time.perf_counter()
        Q11 = np.zeros((n_frames * q, n_frames * q))
        Q11[np.ix_(keep, keep)] = fac.inverse()
        Q1 = Q11.reshape(n_frames, q, n_frames, q)[np.arange(n_frames), :, np.arange(n_frames), :]
        # Q₂₂ per point: N₂₂⁻¹ + N₂₂⁻¹ (Σ_a,b W_aᵀ Q₁₁[c_a, c_b] W_b) N₂₂⁻¹ over observation pairs
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
    return BlockSolution(d1.reshape(n_frames, q), d2, Q1, Q2, timings)


@dataclass
class BlockAdjustment:
    """Result of :func:`block_gauss_newton`: a bundle-type adjustment with its accuracy."""

    frames: np.ndarray            # (n_frames, q) adjusted image unknowns
    points: np.ndarray            # (n_points, 3) adjusted points
    residuals: np.ndarray         # (m, r) V of the image observations at the solution
    frame_residuals: np.ndarray   # (n_frames, q) V of the direct image-unknown observations (0 if none)
    point_residuals: np.ndarray   # (n_points, 3) V of the direct point observations (0 if none)
    mu: float                     # (3.5.12)
    dof: int                      # M − N
    frames_std: np.ndarray | None  # m_j (3.5.11) of the image unknowns
    points_std: np.ndarray | None  # m_j of the point coordinates
    Q1: np.ndarray | None
    Q2: np.ndarray | None
    iterations: int
    converged: bool
    history: list = field(default_factory=list)
    timings: dict = field(default_factory=dict)


def _add_priors(prior, N, L):
    """Add direct observations (values l, weights p) of block unknowns to their diagonal blocks
    of N and to Lᴺ, in place: N_ii += p, Lᴺ_i −= p·l (the (3.5.17)–(3.5.19) rows folded in)."""
    if prior is None:
        return
    l, p = (np.asarray(a, dtype=float) for a in prior)
    idx = np.arange(p.shape[1])
    N[:, idx, idx] += p
    L -= p * l


def _record_block_step(history, iteration, step, vtpv, progress, growth) -> int:
    """Append an :class:`IterationRecord`, report it, and watch for divergence.

    Returns the number of consecutive iterations in which VᵀPV grew; four in a row raise
    :class:`ConvergenceError` with the history.
    """
    record = IterationRecord(iteration, np.empty(0), step, vtpv)
    history.append(record)
    if progress is not None:
        progress(record)
    if len(history) > 1 and vtpv > history[-2].vtpv * (1 + 1e-9):
        growth += 1
        if growth >= 4:
            raise ConvergenceError(f"diverging: VᵀPV grew in {growth} consecutive iterations", history)
        return growth
    return 0


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


def block_gauss_newton(linearize, frames0, points0, *, frame_observations=None, point_observations=None,
                       free_frames=None, free_points=None, tol_frames=1e-8, tol_points=1e-6,
                       max_iter: int = 30, covariance: bool = False, rcond: float = 1e-12,
                       dense_limit: int = 0, progress=None) -> BlockAdjustment:
    """Gauss–Newton iterations of a block adjustment solved by the reduction (3.5.16).

    The same algorithm as :func:`gauss_newton` (δ = −N⁻¹Lᴺ (3.5.9), iterate until the corrections
    are negligible, then μ (3.5.12) and m_j (3.5.11)), with the linear step done by
    :func:`solve_block_normal_equations` so that a block of thousands of images stays sparse.

    Parameters
    ----------
    linearize : callable
        ``linearize(frames, points) -> BlockCorrectionEquations`` at the approximation.
    frames0, points0 : arrays (n_frames, q), (n_points, 3)
        Approximate values.
    frame_observations, point_observations : (values, weights) pairs, optional
        Direct observations of image unknowns / coordinates, same shapes as ``frames0`` /
        ``points0``; weight 0 (value NaN allowed) means "not observed". Their correction
        equations are δ + l = v with l = approximate − measured, (3.5.17)–(3.5.19).
    free_frames, free_points : bool arrays, optional
        False holds the unknowns fixed at their start values.
    tol_frames, tol_points : float or arrays (q,), (3,)
        Convergence when every |δ| is below them.
    max_iter : int
        Iterations before :class:`ConvergenceError`.
    covariance : bool
        Compute Q blocks and m_j at the end (see :func:`solve_block_normal_equations`).
    progress : callable, optional
        Called with each :class:`IterationRecord` (``delta`` holds max |δ₁|, max |δ₂|).
    """
    import time

    frames = np.array(frames0, dtype=float)
    points = np.array(points0, dtype=float)
    if frames.ndim != 2 or points.ndim != 2 or points.shape[1] != 3:
        raise InputError(f"approximations must be (n_frames, q) and (n_points, 3), got {frames.shape}, {points.shape}")
    if not (np.all(np.isfinite(frames)) and np.all(np.isfinite(points))):
        raise InputError("the approximate values contain NaN or inf")
    n_frames, q = frames.shape
    n_points = points.shape[0]
    free_frames = np.ones(n_frames, bool) if free_frames is None else np.asarray(free_frames, bool)
    free_points = np.ones(n_points, bool) if free_points is None else np.asarray(free_points, bool)

    fv, fw = _direct_observations(frame_observations, frames.shape)
    pv, pw = _direct_observations(point_observations, points.shape)
    tol1 = np.broadcast_to(np.asarray(tol_frames, dtype=float), (q,))
    tol2 = np.broadcast_to(np.asarray(tol_points, dtype=float), (3,))
    timings = {"jacobian": 0.0}
    history = []

    def priors():
        fp = None if fw is None else (np.where(fw > 0, frames - fv, 0.0), fw)       # l = x⁰ − x_measured
        pp = None if pw is None else (np.where(pw > 0, points - pv, 0.0), pw)
        return fp, pp

    def vtpv(eq, fp, pp):
        total = float(np.sum(np.broadcast_to(eq.P, eq.L.shape) * eq.L ** 2))
        for pr in (fp, pp):
            if pr is not None:
                total += float(np.sum(pr[1] * pr[0] ** 2))
        return total

    n_unknowns = q * int(free_frames.sum()) + 3 * int(free_points.sum())
    growth = 0
    for iteration in range(1, max_iter + 1):
        t = time.perf_counter()
        eq = linearize(frames, points)
        timings["jacobian"] += time.perf_counter() - t
        fp, pp = priors()
        value = vtpv(eq, fp, pp)
        if not np.isfinite(value):
            raise ConvergenceError(f"the correction equations became NaN/inf at iteration {iteration}", history)
        if iteration == 1:
            m_rows = eq.L.size + (0 if fw is None else int((fw > 0).sum())) + (0 if pw is None else int((pw > 0).sum()))
            if m_rows <= n_unknowns:
                raise InputError(f"{m_rows} correction equations cannot determine {n_unknowns} unknowns (M ≤ N)")
        sol = solve_block_normal_equations(eq, n_frames, n_points, frame_prior=fp, point_prior=pp,
                                           free_frames=free_frames, free_points=free_points,
                                           covariance=False, rcond=rcond, dense_limit=dense_limit)
        for key, val in sol.timings.items():
            timings[key] = timings.get(key, 0.0) + val
        step = np.array([np.abs(sol.delta1).max(initial=0.0), np.abs(sol.delta2).max(initial=0.0)])
        growth = _record_block_step(history, iteration, step, value, progress, growth)
        frames = frames + sol.delta1
        points = points + sol.delta2
        if not (np.all(np.isfinite(frames)) and np.all(np.isfinite(points))):
            raise ConvergenceError(f"the iteration produced NaN/inf at step {iteration}", history)
        if np.all(np.abs(sol.delta1) < tol1) and np.all(np.abs(sol.delta2) < tol2):
            break
    else:
        raise ConvergenceError(
            f"no convergence in {max_iter} iterations: last max |δ| = {step[0]:.3g} (images), "
            f"{step[1]:.3g} (points)", history)

    # residuals and accuracy at the solution (3.5.11)/(3.5.12)
    t = time.perf_counter()
    eq = linearize(frames, points)
    timings["jacobian"] += time.perf_counter() - t
    fp, pp = priors()
    m_rows = eq.L.size + (0 if fw is None else int((fw > 0).sum())) + (0 if pw is None else int((pw > 0).sum()))
    dof = m_rows - n_unknowns
    mu = float(np.sqrt(vtpv(eq, fp, pp) / dof))
    Q1 = Q2 = fstd = pstd = None
    if covariance:
        sol = solve_block_normal_equations(eq, n_frames, n_points, frame_prior=fp, point_prior=pp,
                                           free_frames=free_frames, free_points=free_points,
                                           covariance=True, rcond=rcond, dense_limit=dense_limit)
        timings["covariance"] = sol.timings["covariance"]
        Q1, Q2 = sol.Q1, sol.Q2
        fstd = mu * np.sqrt(np.einsum("kii->ki", Q1))
        pstd = mu * np.sqrt(np.einsum("kii->ki", Q2))
    zero_f = np.zeros_like(frames) if fp is None else fp[0]
    zero_p = np.zeros_like(points) if pp is None else pp[0]
    return BlockAdjustment(frames=frames, points=points, residuals=eq.L.copy(), frame_residuals=zero_f,
                           point_residuals=zero_p, mu=mu, dof=dof, frames_std=fstd, points_std=pstd,
                           Q1=Q1, Q2=Q2, iterations=len(history), converged=True, history=history,
                           timings=timings)


def block_equations_dense(eq: BlockCorrectionEquations, n_frames: int, n_points: int, free_points=None):
    """The same correction equations as one dense (B, L, P) for :func:`solve_normal_equations`.

    Columns: the q unknowns of every image, then X, Y, Z of every free point — the layout of
    fig. 3.11. Only for small blocks (checks, teaching): B has m·r rows and q·n + 3·k columns.
    """
    m, r, q = eq.B1.shape
    free_points = np.ones(n_points, bool) if free_points is None else np.asarray(free_points, bool)
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
    """

    B3: np.ndarray | None = None


@dataclass
class GlobalBlockSolution:
    """One solved linear step with global unknowns, and (optionally) cofactor blocks."""

    delta1: np.ndarray                  # (n_frames, q)
    delta2: np.ndarray                  # (n_points, 3)
    delta3: np.ndarray                  # (g,)
    Q1: np.ndarray | None = None        # (n_frames, q, q) diagonal blocks of N⁻¹ (images)
    Q2: np.ndarray | None = None        # (n_points, 3, 3) diagonal blocks of N⁻¹ (points)
    Q3: np.ndarray | None = None        # (g, g) cofactors of the global unknowns
    Q13: np.ndarray | None = None       # (n_frames, q, g) image × global cofactors
    Q23: np.ndarray | None = None       # (n_points, 3, g) point × global cofactors


def solve_block_normal_equations_global(eq: GlobalBlockCorrectionEquations, n_frames: int, n_points: int, *,
                                        frame_prior=None, point_prior=None, global_prior=None, free_points=None,
                                        covariance: bool = False, rcond: float = 1e-12, global_names=(),
                                        frame_names=()) -> GlobalBlockSolution:
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
                "different flying heights, convergent or rotated images, GNSS centres — or fix them")
        iG = np.linalg.inv(G)
    else:
        iG = np.zeros((0, 0))
    s1, s3 = s[:nq], s[nq:]
    d3 = iG @ (s3 - Zg.T @ s1) if g else np.zeros(0)
    d1 = fac.solve(s1 - S13 @ d3)
    dA = np.concatenate([d1, d3])
    d2 = np.einsum("kij,kj->ki", iN22, L2 - (C.T @ dA).reshape(n_points, 3))
    d2[~free_points] = 0.0
    sol = GlobalBlockSolution(d1.reshape(n_frames, q), d2, d3)
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


@dataclass
class GlobalBlockAdjustment(BlockAdjustment):
    """Result of :func:`block_gauss_newton_global`: :class:`BlockAdjustment` plus the global unknowns."""

    globals: np.ndarray | None = None          # (g,) adjusted block-wide unknowns
    globals_std: np.ndarray | None = None      # m_j (3.5.11)
    Q3: np.ndarray | None = None               # (g, g)
    Q13: np.ndarray | None = None              # (n_frames, q, g)
    Q23: np.ndarray | None = None              # (n_points, 3, g)
    global_residuals: np.ndarray | None = None  # V of direct observations of the globals


def block_gauss_newton_global(linearize, frames0, points0, globals0, *, frame_observations=None,
                              point_observations=None, global_observations=None, free_points=None,
                              tol_frames=1e-8, tol_points=1e-6, tol_globals=1e-10, max_iter: int = 30,
                              covariance: bool = False, rcond: float = 1e-12, global_names=(), frame_names=(),
                              progress=None) -> GlobalBlockAdjustment:
    """Gauss–Newton iterations of a block adjustment with block-wide unknowns (§3.6, §3.8).

    :func:`block_gauss_newton` with a third group of unknowns shared by all observations; each
    linear step is :func:`solve_block_normal_equations_global`. ``linearize(frames, points,
    globals) -> GlobalBlockCorrectionEquations``. Direct observations (values, weights) as in
    :func:`block_gauss_newton`, with ``global_observations`` of shape (g,).
    """
    frames = np.array(frames0, dtype=float)
    points = np.array(points0, dtype=float)
    glob = np.array(globals0, dtype=float).reshape(-1)
    if frames.ndim != 2 or points.ndim != 2 or points.shape[1] != 3:
        raise InputError(f"approximations must be (n_frames, q) and (n_points, 3), got {frames.shape}, {points.shape}")
    if not (np.all(np.isfinite(frames)) and np.all(np.isfinite(points)) and np.all(np.isfinite(glob))):
        raise InputError("the approximate values contain NaN or inf")
    n_frames, q = frames.shape
    n_points, g = points.shape[0], glob.size
    free_points = np.ones(n_points, bool) if free_points is None else np.asarray(free_points, bool)

    obs = [_direct_observations(frame_observations, frames.shape),
           _direct_observations(point_observations, points.shape),
           _direct_observations(global_observations, glob.shape)]
    tols = [np.broadcast_to(np.asarray(t, dtype=float), (s,)) for t, s in ((tol_frames, q), (tol_points, 3), (tol_globals, g))]

    def priors(values):
        return [None if w is None else (np.where(w > 0, x - v, 0.0), w) for x, (v, w) in zip(values, obs)]

    def vtpv(eq, pr):
        return float(np.sum(np.broadcast_to(eq.P, eq.L.shape) * eq.L ** 2)) + \
            sum(float(np.sum(p[1] * p[0] ** 2)) for p in pr if p is not None)

    n_unknowns = q * n_frames + 3 * int(free_points.sum()) + g
    m_rows = None
    history, growth = [], 0
    for iteration in range(1, max_iter + 1):
        eq = linearize(frames, points, glob)
        pr = priors((frames, points, glob))
        value = vtpv(eq, pr)
        if not np.isfinite(value):
            raise ConvergenceError(f"the correction equations became NaN/inf at iteration {iteration}", history)
        if m_rows is None:
            m_rows = eq.L.size + sum(int((w > 0).sum()) for _, w in obs if w is not None)
            if m_rows <= n_unknowns:
                raise InputError(f"{m_rows} correction equations cannot determine {n_unknowns} unknowns (M ≤ N)")
        sol = solve_block_normal_equations_global(eq, n_frames, n_points, frame_prior=pr[0], point_prior=pr[1],
                                                  global_prior=pr[2], free_points=free_points, rcond=rcond,
                                                  global_names=global_names, frame_names=frame_names)
        step = np.array([np.abs(sol.delta1).max(initial=0.0), np.abs(sol.delta2).max(initial=0.0),
                         np.abs(sol.delta3).max(initial=0.0)])
        growth = _record_block_step(history, iteration, step, value, progress, growth)
        frames, points, glob = frames + sol.delta1, points + sol.delta2, glob + sol.delta3
        if not (np.all(np.isfinite(frames)) and np.all(np.isfinite(points)) and np.all(np.isfinite(glob))):
            raise ConvergenceError(f"the iteration produced NaN/inf at step {iteration}", history)
        if all(np.all(np.abs(d) < t) for d, t in zip((sol.delta1, sol.delta2, sol.delta3), tols)):
            break
    else:
        raise ConvergenceError(f"no convergence in {max_iter} iterations: last max |δ| = {step.tolist()}", history)

    eq = linearize(frames, points, glob)
    pr = priors((frames, points, glob))
    dof = m_rows - n_unknowns
    mu = float(np.sqrt(vtpv(eq, pr) / dof))
    out = GlobalBlockAdjustment(frames=frames, points=points, residuals=eq.L.copy(),
                                frame_residuals=np.zeros_like(frames) if pr[0] is None else pr[0][0],
                                point_residuals=np.zeros_like(points) if pr[1] is None else pr[1][0],
                                mu=mu, dof=dof, frames_std=None, points_std=None, Q1=None, Q2=None,
                                iterations=len(history), converged=True, history=history, globals=glob,
                                global_residuals=np.zeros_like(glob) if pr[2] is None else pr[2][0])
    if covariance:
        sol = solve_block_normal_equations_global(eq, n_frames, n_points, frame_prior=pr[0], point_prior=pr[1],
                                                  global_prior=pr[2], free_points=free_points, covariance=True,
                                                  rcond=rcond, global_names=global_names, frame_names=frame_names)
        out.Q1, out.Q2, out.Q3, out.Q13, out.Q23 = sol.Q1, sol.Q2, sol.Q3, sol.Q13, sol.Q23
        out.frames_std = mu * np.sqrt(np.einsum("kii->ki", sol.Q1))
        out.points_std = mu * np.sqrt(np.einsum("kii->ki", sol.Q2))
        out.globals_std = mu * np.sqrt(np.diag(sol.Q3))
    return out


def global_block_equations_dense(eq: GlobalBlockCorrectionEquations, n_frames: int, n_points: int,
                                 free_points=None):
    """Dense (B, L, P) of :class:`GlobalBlockCorrectionEquations`: columns images | globals | free points.

    The column layout of fig. 3.18 (exterior orientation, mounting elements, tie points); for
    checks and figures of small blocks only.
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
