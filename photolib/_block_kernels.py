"""Compiled loops of the block adjustment — Chapter 3, §3.5, eqs. (3.5.2), (3.5.8), (3.5.14), (3.5.16).

The per-observation work of a bundle block — the correction equations (3.5.2) of every image
observation, the normal-equation blocks (3.5.8), the reduction (3.5.16) of the points into the
band of the image unknowns and the back-substitution (3.5.14) — consists of loops over 10⁴–10⁶
observations doing a few hundred floating-point operations each. As numpy calls they cost many
small temporaries (and, for small blocks, mostly Python overhead); here they are loops compiled
by numba (``cache=True``: compiled once per machine and stored beside the source, later
processes only load them). The arithmetic is the one of :mod:`photolib.lsq`; the model
functions are the sympy-printed ``collinearity_<order>_point`` of
:mod:`photolib._bundle_generated`.

Private: used by :func:`photolib.lsq.block_gauss_newton` and
:func:`photolib.bundle.bundle_correction_equations`. The first use in a process loads the
compiled code (about 0.4 s, most of it numba's own start-up; the first compilation on a new
machine takes about 10 s): :func:`load` does it explicitly and reports the seconds.
"""

from __future__ import annotations

import time

import numba
import numpy as np

from . import _bundle_generated

__all__ = ["load", "collinearity", "normal_blocks", "invert_3x3", "reduce_to_band", "scale_band", "back_substitute",
           "image_components", "reverse_cuthill_mckee", "band_cholesky", "band_solve", "normal_step", "reduced_step"]

_jit = numba.njit(cache=True, nogil=True)
_point_kaw = _jit(_bundle_generated.collinearity_kaw_point)
_point_wak = _jit(_bundle_generated.collinearity_wak_point)


@_jit
def collinearity(wak, cams, pts, image, point, xy, f, x0, y0, B1, B2, L, zstar):   # pragma: no cover (compiled)
    """B1 (m, 2, 6), B2 (m, 2, 3), L (m, 2) of (3.5.2) and z* of every observation, in place."""
    for k in range(image.shape[0]):
        i, p = image[k], point[k]
        if wak:
            r = _point_wak(cams[i, 0], cams[i, 1], cams[i, 2], cams[i, 3], cams[i, 4], cams[i, 5],
                           pts[p, 0], pts[p, 1], pts[p, 2], xy[k, 0], xy[k, 1], f, x0, y0)
        else:
            r = _point_kaw(cams[i, 0], cams[i, 1], cams[i, 2], cams[i, 3], cams[i, 4], cams[i, 5],
                           pts[p, 0], pts[p, 1], pts[p, 2], xy[k, 0], xy[k, 1], f, x0, y0)
        L[k, 0] = r[0]
        L[k, 1] = r[1]
        for j in range(6):
            B1[k, 0, j] = r[2 + j]
            B1[k, 1, j] = r[11 + j]
        for j in range(3):
            B2[k, 0, j] = r[8 + j]
            B2[k, 1, j] = r[17 + j]
        zstar[k] = r[20]


@_jit
def normal_blocks(frame, point, B1, B2, L, P, slot, N11, L1, N22, L2, W):   # pragma: no cover (compiled)
    """Accumulate N₁₁, −Lᴺ₁ per image, N₂₂, −Lᴺ₂ per point and the q×3 blocks W of N₁₂, (3.5.8).

    Observation k adds p·B1ᵀB1 to N11[frame[k]], −p·B1ᵀL to L1, p·B2ᵀB2 and −p·B2ᵀL to its
    point, and p·B1ᵀB2 to W[slot[k]] when slot[k] ≥ 0 (a free point in a free image).
    """
    m, r, q = B1.shape
    for k in range(m):
        fr, pt, c = frame[k], point[k], slot[k]
        for a in range(r):
            w, el = P[k, a], L[k, a]
            for i in range(q):
                wb = w * B1[k, a, i]
                L1[fr, i] -= wb * el
                for j in range(q):
                    N11[fr, i, j] += wb * B1[k, a, j]
                if c >= 0:
                    for j in range(3):
                        W[c, i, j] += wb * B2[k, a, j]
            for i in range(3):
                wb = w * B2[k, a, i]
                L2[pt, i] -= wb * el
                for j in range(3):
                    N22[pt, i, j] += wb * B2[k, a, j]


@_jit
def invert_3x3(blocks, rcond, inverse, status):   # pragma: no cover (compiled)
    """Inverses of symmetric 3×3 blocks by the adjugate of the block scaled to unit diagonal.

    ``status[k]``: 0 done; 1 a diagonal element ≤ 0 (not determined); 2 4·det/9 < rcond (the
    smallest eigenvalue may be below rcond: to be decided by the caller).
    """
    for k in range(blocks.shape[0]):
        B = blocks[k]
        if not (B[0, 0] > 0 and B[1, 1] > 0 and B[2, 2] > 0):
            status[k] = 1
            continue
        d0, d1, d2 = np.sqrt(B[0, 0]), np.sqrt(B[1, 1]), np.sqrt(B[2, 2])
        a, b, c = B[0, 0] / (d0 * d0), B[0, 1] / (d0 * d1), B[0, 2] / (d0 * d2)
        e, f, i = B[1, 1] / (d1 * d1), B[1, 2] / (d1 * d2), B[2, 2] / (d2 * d2)
        A00, A01, A02 = e * i - f * f, c * f - b * i, b * f - c * e
        A11, A12, A22 = a * i - c * c, b * c - a * f, a * e - b * b
        det = a * A00 + b * A01 + c * A02
        if not (4.0 * det / 9.0 >= rcond):
            status[k] = 2
        out = inverse[k]
        out[0, 0] = A00 / (det * d0 * d0)
        out[0, 1] = out[1, 0] = A01 / (det * d0 * d1)
        out[0, 2] = out[2, 0] = A02 / (det * d0 * d2)
        out[1, 1] = A11 / (det * d1 * d1)
        out[1, 2] = out[2, 1] = A12 / (det * d1 * d2)
        out[2, 2] = A22 / (det * d2 * d2)


@_jit
def reduce_to_band(ptr, slot_frame, W, iN22, L2, position, N11, s, band):   # pragma: no cover (compiled)
    """S = N₁₁ − N₁₂N₂₂⁻¹N₁₂ᵀ into the lower band, s −= N₁₂N₂₂⁻¹L₂ᴺ, (3.5.16).

    ``W[ptr[p]:ptr[p + 1]]`` are the blocks of point p; image i is unknown block
    ``position[i]`` of the renumbered system (−1: held fixed). ``band[d, c]`` holds S[c + d, c]
    (LAPACK's lower band storage); ``s`` (n, q) starts as Lᴺ₁.
    """
    q = W.shape[1]
    most = 0
    for p in range(ptr.shape[0] - 1):
        most = max(most, ptr[p + 1] - ptr[p])
    Y = np.empty((most, q, 3))
    for p in range(ptr.shape[0] - 1):
        a0, a1 = ptr[p], ptr[p + 1]
        for c in range(a0, a1):
            y = Y[c - a0]
            for i in range(q):                                    # Y_a = W_a·N₂₂⁻¹
                for j in range(3):
                    y[i, j] = W[c, i, 0] * iN22[p, 0, j] + W[c, i, 1] * iN22[p, 1, j] + W[c, i, 2] * iN22[p, 2, j]
            fa = slot_frame[c]
            for i in range(q):
                s[fa, i] -= y[i, 0] * L2[p, 0] + y[i, 1] * L2[p, 1] + y[i, 2] * L2[p, 2]
        for ca in range(a0, a1):
            pa = position[slot_frame[ca]]
            if pa < 0:
                continue
            y = Y[ca - a0]
            for cb in range(a0, a1):
                pb = position[slot_frame[cb]]
                if pb < 0 or pb > pa:
                    continue
                for j in range(q):                            # column by column: the band is Fortran-ordered
                    col = q * pb + j
                    w0, w1, w2 = W[cb, j, 0], W[cb, j, 1], W[cb, j, 2]
                    for i in range(j if pa == pb else 0, q):
                        band[q * pa + i - col, col] -= y[i, 0] * w0 + y[i, 1] * w1 + y[i, 2] * w2
    for fr in range(N11.shape[0]):
        pf = position[fr]
        if pf < 0:
            continue
        for i in range(q):
            for j in range(i + 1):
                band[i - j, q * pf + j] += N11[fr, i, j]


@_jit
def scale_band(band, scale):   # pragma: no cover (compiled)
    """D·S·D in the lower band storage, D = diag(scale)."""
    b1, n = band.shape
    for c in range(n):
        for d in range(min(b1, n - c)):
            band[d, c] *= scale[c + d] * scale[c]


@_jit
def back_substitute(slot_frame, slot_point, W, d1, iN22, L2, free_points, d2):   # pragma: no cover (compiled)
    """δ₂ = N₂₂⁻¹(Lᴺ₂ − N₁₂ᵀδ₁), second row of (3.5.14); 0 for fixed points."""
    t = L2.copy()
    q = W.shape[1]
    for c in range(W.shape[0]):
        fr, p = slot_frame[c], slot_point[c]
        for j in range(3):
            acc = 0.0
            for i in range(q):
                acc += W[c, i, j] * d1[fr, i]
            t[p, j] -= acc
    for p in range(d2.shape[0]):
        for i in range(3):
            d2[p, i] = (iN22[p, i, 0] * t[p, 0] + iN22[p, i, 1] * t[p, 1] + iN22[p, i, 2] * t[p, 2]) \
                if free_points[p] else 0.0


@_jit
def image_components(image, point, n, k, labels):   # pragma: no cover (compiled)
    """Groups of images linked through common points: ``labels[j]`` = group of image j, in place.

    The connected components of the undirected graph of images and points (an edge image →
    point for every observation), by union–find; the groups are numbered 0, 1, … in the order
    of their lowest image index. Returns the number of groups.
    """
    parent = np.arange(n + k)
    for o in range(image.shape[0]):
        a, b = image[o], n + point[o]
        while parent[a] != a:                    # roots, halving the paths on the way
            parent[a] = parent[parent[a]]
            a = parent[a]
        while parent[b] != b:
            parent[b] = parent[parent[b]]
            b = parent[b]
        if a != b:
            if a < b:
                parent[b] = a
            else:
                parent[a] = b
    group = np.full(n + k, -1, np.intp)
    count = 0
    for j in range(n):
        r = j
        while parent[r] != r:
            r = parent[r]
        if group[r] < 0:
            group[r] = count
            count += 1
        labels[j] = group[r]
    return count


@_jit
def reverse_cuthill_mckee(indices, indptr, seeds, degree, order):   # pragma: no cover (compiled)
    """Reverse Cuthill–McKee numbering of a symmetric graph in CSR form (``indices``, ``indptr``), in place.

    The algorithm of ``scipy.sparse.csgraph.reverse_cuthill_mckee`` (symmetric mode), step for
    step, so the numbering is the same: breadth-first from the unvisited node of lowest degree
    (``seeds`` = ``np.argsort(degree)``, computed by numpy as scipy does; ``degree`` counts the
    diagonal twice), the new neighbours of each node sorted by degree (insertion sort), the
    result reversed into ``order``.
    """
    n = indptr.shape[0] - 1
    inds = seeds.copy()
    rev = np.empty(n, np.intp)
    for k in range(n):
        rev[inds[k]] = k
    cm = np.empty(n, np.intp)
    temp = np.empty(max(n, 1), np.intp)
    N = 0
    for zz in range(n):
        if inds[zz] != -1:
            seed = inds[zz]
            cm[N] = seed
            N += 1
            inds[rev[seed]] = -1
            level_start, level_end = N - 1, N
            while level_start < level_end:
                for ii in range(level_start, level_end):
                    i = cm[ii]
                    n_old = N
                    for jj in range(indptr[i], indptr[i + 1]):
                        j = indices[jj]
                        if inds[rev[j]] != -1:
                            inds[rev[j]] = -1
                            cm[N] = j
                            N += 1
                    level_len = 0
                    for kk in range(n_old, N):
                        temp[level_len] = degree[cm[kk]]
                        level_len += 1
                    for kk in range(1, level_len):
                        t, t2, ll = temp[kk], cm[n_old + kk], kk
                        while ll > 0 and t < temp[ll - 1]:
                            temp[ll] = temp[ll - 1]
                            cm[n_old + ll] = cm[n_old + ll - 1]
                            ll -= 1
                        temp[ll] = t
                        cm[n_old + ll] = t2
                level_start, level_end = level_end, N
        if N == n:
            break
    for k in range(n):
        order[k] = cm[n - 1 - k]


@_jit
def band_cholesky(band):   # pragma: no cover (compiled)
    """Cholesky factor L of a symmetric matrix in LAPACK's lower band storage, in place; the smallest pivot.

    ``band[d, c]`` = A[c + d, c] on entry and L[c + d, c] on return (the layout of LAPACK's
    ``dpbtrf`` with ``lower=1``, so LAPACK's ``dpbtrs`` can use the factor). Column-oriented
    (left-looking) Cholesky–Banachiewicz: L_jj² = a_jj − Σ L_jk², L_ij = (a_ij − Σ L_ik L_jk)/L_jj
    over the band. Returns (min L_jj², the column where it occurs) — the pivots — or (0.0, j) at
    the first column j whose pivot is not positive (the factorisation stops there: the matrix is
    not positive definite).
    """
    kd = band.shape[0] - 1
    n = band.shape[1]
    smallest, where = np.inf, -1
    for j in range(n):
        first = max(0, j - kd)
        pivot = band[0, j]
        for k in range(first, j):
            pivot -= band[j - k, k] * band[j - k, k]
        if not pivot > 0.0:
            return 0.0, j
        if pivot < smallest:
            smallest, where = pivot, j
        diagonal = np.sqrt(pivot)
        band[0, j] = diagonal
        for i in range(j + 1, min(n, j + kd + 1)):
            value = band[i - j, j]
            for k in range(max(0, i - kd), j):
                value -= band[i - k, k] * band[j - k, k]
            band[i - j, j] = value / diagonal
    return smallest, where


@_jit
def band_solve(factor, rhs):   # pragma: no cover (compiled)
    """Solve L·Lᵀ·x = rhs in place with the band factor of :func:`band_cholesky` (forward, then back)."""
    kd = factor.shape[0] - 1
    n = factor.shape[1]
    for i in range(n):
        value = rhs[i]
        for k in range(max(0, i - kd), i):
            value -= factor[i - k, k] * rhs[k]
        rhs[i] = value / factor[0, i]
    for i in range(n - 1, -1, -1):
        value = rhs[i]
        for k in range(i + 1, min(n, i + kd + 1)):
            value -= factor[k - i, i] * rhs[k]
        rhs[i] = value / factor[0, i]


@_jit
def normal_step(frame, point, B1, B2, L, P, slot, N11, L1, N22, L2, W, frame_l, frame_p, point_l, point_p,
                fixed_frames, fixed_points, rcond, iN22, status):   # pragma: no cover (compiled)
    """First half of one linear step, (3.5.8) and the N₂₂⁻¹ of (3.5.16), in one call.

    :func:`normal_blocks`; the direct observations of unknowns folded into the diagonal blocks
    (N_ii += p, Lᴺ_i −= p·l; ``frame_p``/``point_p`` with 0 rows when there are none); identity
    blocks and zero right-hand sides for fixed images and points; :func:`invert_3x3` of N₂₂.
    """
    normal_blocks(frame, point, B1, B2, L, P, slot, N11, L1, N22, L2, W)
    for f in range(frame_p.shape[0]):
        for i in range(frame_p.shape[1]):
            N11[f, i, i] += frame_p[f, i]
            L1[f, i] -= frame_p[f, i] * frame_l[f, i]
    for p in range(point_p.shape[0]):
        for i in range(3):
            N22[p, i, i] += point_p[p, i]
            L2[p, i] -= point_p[p, i] * point_l[p, i]
    q = N11.shape[1]
    for f in fixed_frames:
        for i in range(q):
            L1[f, i] = 0.0
            for j in range(q):
                N11[f, i, j] = 1.0 if i == j else 0.0
    for p in fixed_points:
        for i in range(3):
            L2[p, i] = 0.0
            for j in range(3):
                N22[p, i, j] = 1.0 if i == j else 0.0
    invert_3x3(N22, rcond, iN22, status)


@_jit
def reduced_step(ptr, slot_frame, slot_point, W, iN22, L2, position, N11, L1, order, keep_index, free_points,
                 band, d1, d2):   # pragma: no cover (compiled)
    """Second half of one linear step: (3.5.16), its band Cholesky and solution, (3.5.14) row 2.

    :func:`reduce_to_band` into ``band`` (zeros on entry), scaled to unit diagonal
    (:func:`scale_band`), :func:`band_cholesky`, the renumbered and scaled right-hand side
    solved by :func:`band_solve` into ``d1`` (n_frames, q; zeros on entry), and
    :func:`back_substitute` into ``d2``. Returns (0, smallest pivot, its column) on success,
    (1, 0.0, column) for a diagonal element of S that is not positive (an unknown not
    determined), (2, 0.0, column) for a failed factorisation (columns of the renumbered system).
    """
    s = L1.copy()
    reduce_to_band(ptr, slot_frame, W, iN22, L2, position, N11, s, band)
    n = band.shape[1]
    scale = np.empty(n)
    for c in range(n):
        if not band[0, c] > 0.0:
            return 1, 0.0, c
        scale[c] = 1.0 / np.sqrt(band[0, c])
    scale_band(band, scale)
    smallest, where = band_cholesky(band)
    if smallest == 0.0:
        return 2, 0.0, where
    flat = s.ravel()
    rhs = np.empty(n)
    for c in range(n):
        rhs[c] = flat[keep_index[order[c]]] * scale[c]
    band_solve(band, rhs)
    out = d1.ravel()
    for c in range(n):
        out[keep_index[order[c]]] = rhs[c] * scale[c]
    back_substitute(slot_frame, slot_point, W, d1, iN22, L2, free_points, d2)
    return 0, smallest, where


def load() -> float:
    """Load (or, on a new machine, compile) every kernel now, and find the BLAS libraries; the seconds it took.

    Returns
    -------
    float
        Seconds spent (numba's start-up, loading the cached machine code, threadpoolctl's list of
        the BLAS libraries whose threads the factorisation limits).

    References
    ----------
    Chibunichev (2022), §3.5, eqs. (3.5.2), (3.5.8), (3.5.14), (3.5.16).

    Examples
    --------
    >>> load() >= 0.0
    True
    """
    t = time.perf_counter()
    _warm_up()
    from .lsq import _blas_libraries           # threadpoolctl's scan of the loaded BLAS libraries (≈ 10 ms, once)
    _blas_libraries()
    return time.perf_counter() - t


def _warm_up():
    """Call every kernel once on a tiny problem of the types used by the engine."""
    m, n, k, q = 2, 1, 2, 6
    image, point = np.zeros(m, np.intp), np.arange(m, dtype=np.intp)
    cams, pts = np.array([[0.0, 0.0, 100.0, 0.0, 0.0, 0.0]]), np.zeros((k, 3))
    xy = np.zeros((m, 2))
    B1, B2, L, z = np.empty((m, 2, q)), np.empty((m, 2, 3)), np.empty((m, 2)), np.empty(m)
    for wak in (False, True):
        collinearity(wak, cams, pts, image, point, xy, 100.0, 0.0, 0.0, B1, B2, L, z)
    N11, L1, N22, L2, W = np.zeros((n, q, q)), np.zeros((n, q)), np.zeros((k, 3, 3)), np.zeros((k, 3)), \
        np.zeros((m, q, 3))
    slot = np.arange(m, dtype=np.intp)
    normal_blocks(image, point, B1, B2, L, np.ones((m, 2)), slot, N11, L1, N22, L2, W)
    band = np.zeros((q, n * q), order="F")
    iN22 = np.empty((k, 3, 3))
    invert_3x3(np.broadcast_to(np.eye(3), (k, 3, 3)).copy(), 1e-12, iN22, np.zeros(k, np.int8))
    reduce_to_band(np.arange(k + 1, dtype=np.intp), image, W, iN22, L2, np.zeros(n, np.intp), N11,
                   L1.copy(), band)
    scale_band(band, np.ones(n * q))
    back_substitute(image, point, W, np.zeros((n, q)), iN22, L2, np.ones(k, bool), np.empty((k, 3)))
    image_components(image, point, n, k, np.empty(n, np.intp))
    empty = np.zeros((0, q))
    normal_step(image, point, B1, B2, L, np.ones((m, 2)), slot, N11, L1, N22, L2, W, empty, empty,
                np.zeros((0, 3)), np.zeros((0, 3)), np.zeros(0, np.intp), np.zeros(0, np.intp), 1e-12, iN22,
                np.zeros(k, np.int8))
    reduced_step(np.arange(k + 1, dtype=np.intp), image, point, W, iN22, L2, np.zeros(n, np.intp), N11, L1,
                 np.arange(n * q, dtype=np.intp), np.arange(n * q, dtype=np.intp), np.ones(k, bool),
                 np.zeros((q, n * q), order="F"), np.zeros((n, q)), np.empty((k, 3)))
    ptr2 = np.arange(n + 1, dtype=np.intp)
    reverse_cuthill_mckee(np.zeros(n, np.intp), ptr2, np.zeros(n, np.intp), np.full(n, 2, np.int32),
                          np.empty(n, np.intp))
