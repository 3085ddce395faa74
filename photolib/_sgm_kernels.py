"""Numba kernels of semi-global matching (Chapter 6, §6.4–6.5) — private, imported on first use.

The loops here run over pixels (or X–Y nodes) in path order: the recursion (6.4.3) needs the
previous pixel of each path, so it cannot be vectorised over a whole image. Everything is
compiled with ``@njit(cache=True)``; :mod:`photolib.sgm` imports this module lazily.
"""

from __future__ import annotations

import numpy as np
from numba import njit

__all__ = []


@njit(cache=True, fastmath=True)
def _one_path(C, S, dy, dx, P1, P2, guide, gamma, out, keep):
    """Add the path costs L_r (6.4.3) of direction r = (dx, dy) to S (6.4.4).

    The previous pixel of (x, y) on the path is (x − dx, y − dy). Rows are visited in the
    order of dy, columns in the order of dx, so the predecessor is always computed first.
    Row buffers carry one +inf guard on each side of the disparity axis, so that the
    p ± 1 neighbours need no branch. With ``gamma > 0`` the penalty P2 is adapted to the
    intensity step of ``guide`` between the pixel and its predecessor:
    P2' = max(P1, P2·γ/(γ + |ΔI|)). ``keep`` stores L_r in ``out``. Costs must be finite.
    """
    H, W, D = C.shape
    big = np.float32(3.0e38)
    prev = np.full((W, D + 2), big, np.float32)
    cur = np.full((W, D + 2), big, np.float32)
    mprev = np.empty(W, np.float32)
    mcur = np.empty(W, np.float32)
    for iy in range(H):
        y = iy if dy >= 0 else H - 1 - iy
        yp = y - dy
        for ix in range(W):
            x = ix if dx >= 0 else W - 1 - ix
            xp = x - dx
            Cx = C[y, x]
            Lc = cur[x]
            Sx = S[y, x]
            mn = big
            if yp < 0 or yp >= H or xp < 0 or xp >= W:
                for d in range(D):
                    v = Cx[d]
                    Lc[d + 1] = v
                    Sx[d] += v
                    mn = min(mn, v)
            else:
                if dy != 0:
                    Lp = prev[xp]
                    m = mprev[xp]
                else:
                    Lp = cur[xp]
                    m = mcur[xp]
                p2 = P2
                if gamma > 0.0:
                    step = abs(guide[y, x] - guide[yp, xp])
                    p2 = np.float32(P2 * gamma / (gamma + step))
                    if p2 < P1:
                        p2 = P1
                jump = m + p2
                for d in range(D):
                    v = min(min(Lp[d + 1], jump), min(Lp[d], Lp[d + 2]) + P1)
                    v = Cx[d] + v - m
                    Lc[d + 1] = v
                    Sx[d] += v
                    mn = min(mn, v)
            mcur[x] = mn
            if keep:
                for d in range(D):
                    out[y, x, d] = Lc[d + 1]
        if dy != 0:
            tmp = prev
            prev = cur
            cur = tmp
            tm = mprev
            mprev = mcur
            mcur = tm


@njit(cache=True)
def aggregate(C, directions, P1, P2, guide, gamma):
    """S(x, y, p) = Σ_r L_r(x, y, p) over the given directions (6.4.3)/(6.4.4)."""
    H, W, D = C.shape
    S = np.zeros((H, W, D), np.float32)
    dummy = np.empty((1, 1, 1), np.float32)
    for k in range(directions.shape[0]):
        _one_path(C, S, directions[k, 0], directions[k, 1], np.float32(P1), np.float32(P2),
                  guide, gamma, dummy, False)
    return S


@njit(cache=True, fastmath=True, boundscheck=False)
def _step(Lp, m, Cx, Lc, acc, P1, p2, D):
    """One recursion step (6.4.3) from the predecessor's L (guarded buffer) into Lc; adds to acc.

    Written as two simple loops so that LLVM vectorises them.
    """
    jump = m + p2
    for d in range(D):
        a = min(Lp[d + 1], jump)
        b = min(Lp[d], Lp[d + 2]) + P1
        Lc[d + 1] = Cx[d] + min(a, b) - m
    mn = np.float32(3.0e38)
    for d in range(D):
        v = Lc[d + 1]
        acc[d] += v
        mn = min(mn, v)
    return mn


@njit(cache=True, fastmath=True, inline="always")
def _start(Cx, Lc, acc, D):
    mn = np.float32(3.0e38)
    for d in range(D):
        v = Cx[d]
        Lc[d + 1] = v
        acc[d] += v
        mn = min(mn, v)
    return mn


@njit(cache=True, inline="always")
def _p2(P1, P2, guide, gamma, y, x, yp, xp):
    if gamma > 0.0:
        p2 = np.float32(P2 * gamma / (gamma + abs(guide[y, x] - guide[yp, xp])))
        if p2 < P1:
            p2 = P1
        return p2
    return P2


@njit(cache=True, fastmath=True)
def _sweep(C, S, s, diagonal, P1, P2, guide, gamma, first):
    """One sweep over the image adding 4 (or 2) path costs to S in a single pass.

    s = +1: rows top → bottom, columns left → right, directions r = (1, 0), (0, 1), (1, 1),
    (−1, 1) as (dx, dy); s = −1: the opposite four. The horizontal path's predecessor is the
    previous column of the same row; the others' predecessors are in the previous row.
    """
    H, W, D = C.shape
    big = np.float32(3.0e38)
    nrow = 3 if diagonal else 1
    prev = np.full((nrow, W, D + 2), big, np.float32)
    cur = np.full((nrow, W, D + 2), big, np.float32)
    mprev = np.zeros((nrow, W), np.float32)
    mcur = np.zeros((nrow, W), np.float32)
    hb = np.full((2, D + 2), big, np.float32)
    acc = np.empty(D, np.float32)
    for iy in range(H):
        y = iy if s > 0 else H - 1 - iy
        yp = y - s
        hm = np.float32(0.0)
        for ix in range(W):
            x = ix if s > 0 else W - 1 - ix
            Cx = C[y, x]
            for d in range(D):
                acc[d] = 0.0
            # horizontal path: predecessor (x − s, y)
            hcur = hb[ix % 2]
            if ix == 0:
                hm = _start(Cx, hcur, acc, D)
            else:
                hm = _step(hb[(ix + 1) % 2], hm, Cx, hcur, acc, P1,
                           _p2(P1, P2, guide, gamma, y, x, y, x - s), D)
            # row paths: vertical (x, y − s), diagonals (x − s, y − s) and (x + s, y − s)
            for k in range(nrow):
                xp = x if k == 0 else (x - s if k == 1 else x + s)
                if iy == 0 or xp < 0 or xp >= W:
                    mcur[k, x] = _start(Cx, cur[k, x], acc, D)
                else:
                    mcur[k, x] = _step(prev[k, xp], mprev[k, xp], Cx, cur[k, x], acc, P1,
                                       _p2(P1, P2, guide, gamma, y, x, yp, xp), D)
            Sx = S[y, x]
            if first:
                for d in range(D):
                    Sx[d] = acc[d]
            else:
                for d in range(D):
                    Sx[d] += acc[d]
        tmp = prev
        prev = cur
        cur = tmp
        tm = mprev
        mprev = mcur
        mcur = tm


@njit(cache=True)
def aggregate_sweeps(C, diagonal, P1, P2, guide, gamma):
    """S of (6.4.4) over 8 (diagonal) or 4 directions in two sweeps (forward and backward)."""
    H, W, D = C.shape
    S = np.empty((H, W, D), np.float32)
    _sweep(C, S, 1, diagonal, np.float32(P1), np.float32(P2), guide, gamma, True)
    _sweep(C, S, -1, diagonal, np.float32(P1), np.float32(P2), guide, gamma, False)
    return S


@njit(cache=True)
def single_path(C, dy, dx, P1, P2, guide, gamma):
    """L_r(x, y, p) of one direction (6.4.3)."""
    H, W, D = C.shape
    S = np.zeros((H, W, D), np.float32)
    out = np.empty((H, W, D), np.float32)
    _one_path(C, S, dy, dx, np.float32(P1), np.float32(P2), guide, gamma, out, True)
    return out


@njit(cache=True)
def right_argmin(S):
    """Index disparity of the right image from the left volume: argmin_d S(y, x_r + d, d)."""
    H, W, D = S.shape
    out = np.full((H, W), -1, np.int64)
    for y in range(H):
        for xr in range(W):
            best = np.inf
            for d in range(D):
                x = xr + d
                if x >= W:
                    break
                if S[y, x, d] < best:
                    best = S[y, x, d]
                    out[y, xr] = d
    return out


@njit(cache=True, inline="always")
def _popcount(v):
    """Number of set bits of a uint64 (SWAR)."""
    v = v - ((v >> np.uint64(1)) & np.uint64(0x5555555555555555))
    v = (v & np.uint64(0x3333333333333333)) + ((v >> np.uint64(2)) & np.uint64(0x3333333333333333))
    v = (v + (v >> np.uint64(4))) & np.uint64(0x0F0F0F0F0F0F0F0F)
    return (v * np.uint64(0x0101010101010101)) >> np.uint64(56)


@njit(cache=True)
def hamming_volume(cl, cr, D, dmin, fill):
    """Census cost: popcount(cl(x, y) XOR cr(x − d, y)) for d = dmin … dmin + D − 1."""
    H, W = cl.shape
    C = np.empty((H, W, D), np.float32)
    for y in range(H):
        for x in range(W):
            a = cl[y, x]
            for k in range(D):
                xr = x - (dmin + k)
                if xr < 0 or xr >= W:
                    C[y, x, k] = fill
                else:
                    C[y, x, k] = _popcount(a ^ cr[y, xr])
    return C


@njit(cache=True)
def fill_rows(disp):
    """Replace NaN by the smaller of the nearest valid values to the left and right in its row."""
    H, W = disp.shape
    out = disp.copy()
    for y in range(H):
        left = np.empty(W)
        last = np.nan
        for x in range(W):
            if not np.isnan(disp[y, x]):
                last = disp[y, x]
            left[x] = last
        last = np.nan
        for x in range(W - 1, -1, -1):
            if not np.isnan(disp[y, x]):
                last = disp[y, x]
            elif np.isnan(left[x]):
                out[y, x] = last
            elif np.isnan(last):
                out[y, x] = left[x]
            else:
                out[y, x] = min(left[x], last)
    return out


@njit(cache=True)
def census(padded, H, W, rows, cols):
    """Census bit strings of the H×W image inside the edge-padded array (MSB = first neighbour)."""
    hr = rows // 2
    hc = cols // 2
    out = np.zeros((H, W), np.uint64)
    for y in range(H):
        for x in range(W):
            c = padded[y + hr, x + hc]
            bits = np.uint64(0)
            for i in range(rows):
                for j in range(cols):
                    if i == hr and j == hc:
                        continue
                    bits = bits << np.uint64(1)
                    if padded[y + i, x + j] < c:
                        bits = bits | np.uint64(1)
            out[y, x] = bits
    return out


@njit(cache=True)
def wta_subpixel(V, subpixel):
    """argmin over the last axis; subpixel 1: 3-point parabola vertex, 2: equiangular (V) fit."""
    H, W, D = V.shape
    out = np.empty((H, W), np.float64)
    for y in range(H):
        for x in range(W):
            v = V[y, x]
            best = 0
            for d in range(1, D):
                if v[d] < v[best]:
                    best = d
            r = float(best)
            if subpixel > 0 and best > 0 and best < D - 1:
                cm = float(v[best - 1])
                c0 = float(v[best])
                cp = float(v[best + 1])
                if subpixel == 1:
                    curv = 2.0 * (cm - 2.0 * c0 + cp)
                else:
                    curv = 2.0 * (max(cm, cp) - c0)
                if curv > 0:
                    delta = (cm - cp) / curv
                    if delta > 0.5:
                        delta = 0.5
                    elif delta < -0.5:
                        delta = -0.5
                    r += delta
            out[y, x] = r
    return out
