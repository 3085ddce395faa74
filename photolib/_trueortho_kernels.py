"""Compiled per-pixel loops of :mod:`photolib.trueortho` (visibility along radial profiles).

Private: the public functions validate their inputs and call these kernels. numba compiles them
on first use (``cache=True`` keeps the machine code between sessions).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit, prange


@njit(cache=True)
def _height(dsm, x0, y0, dx, dy, X, Y):
    """Bilinear DSM height at (X, Y) (7.3.1); −inf outside the span of the pixel centres."""
    r = (y0 - Y) / dy - 0.5
    c = (X - x0) / dx - 0.5
    n_r, n_c = dsm.shape
    if not (r >= 0.0 and r <= n_r - 1 and c >= 0.0 and c <= n_c - 1):
        return -np.inf
    i = min(int(math.floor(r)), n_r - 2) if n_r > 1 else 0
    j = min(int(math.floor(c)), n_c - 2) if n_c > 1 else 0
    u = c - j
    v = r - i
    z00 = dsm[i, j]
    z01 = dsm[i, j + 1] if n_c > 1 else z00
    z10 = dsm[i + 1, j] if n_r > 1 else z00
    z11 = dsm[i + 1, j + 1] if (n_r > 1 and n_c > 1) else z00
    return (z00 * (1 - u) + z01 * u) * (1 - v) + (z10 * (1 - u) + z11 * u) * v


@njit(cache=True)
def hidden(dsm, x0, y0, dx, dy, zmax, Xs, Ys, Zs, X, Y, Z, step, eps):
    """The §7.5 criterion for one point B = (X, Y, Z) seen from S.

    Walk the horizontal profile from B towards the nadir point (X_S, Y_S); B is hidden when an
    element A on it has a larger nadir angle than B (tan α_A = r_A / (Z_S − Z_A) > tan α_B),
    i.e. when the running maximum of tan α over the profile exceeds tan α_B. The walk stops at
    the nadir or once the ray from B to S is above the highest DSM element.
    """
    ex = X - Xs
    ey = Y - Ys
    r_b = math.sqrt(ex * ex + ey * ey)
    if r_b <= 0.0:
        return False
    hb = Zs - Z
    if hb <= 0.0:
        return True
    tan_b = r_b / hb
    n = int(r_b / step)
    for k in range(1, n + 1):
        r_a = r_b - k * step
        if r_a <= 0.0:
            break
        # the ray's height above B at this distance: stop when it clears the whole DSM
        if Z + hb * (k * step) / r_b > zmax:
            break
        XA = Xs + ex * r_a / r_b
        YA = Ys + ey * r_a / r_b
        za = _height(dsm, x0, y0, dx, dy, XA, YA)
        if za == -np.inf:
            continue
        ha = Zs - za
        if ha <= 0.0:
            return True
        if r_a / ha > tan_b * (1.0 + eps):
            return True
    return False


@njit(cache=True, parallel=True)
def visibility_grid(dsm, x0, y0, dx, dy, Xs, Ys, Zs, step, eps, out):
    """The 0/1 restriction matrix of a DSM grid seen from S (§7.5)."""
    n_r, n_c = dsm.shape
    zmax = -np.inf
    for i in range(n_r):
        for j in range(n_c):
            if dsm[i, j] > zmax:
                zmax = dsm[i, j]
    for i in prange(n_r):
        Y = y0 - (i + 0.5) * dy
        for j in range(n_c):
            X = x0 + (j + 0.5) * dx
            out[i, j] = 0 if hidden(dsm, x0, y0, dx, dy, zmax, Xs, Ys, Zs, X, Y, dsm[i, j], step, eps) else 1


@njit(cache=True, parallel=True)
def hidden_points(dsm, x0, y0, dx, dy, Xs, Ys, Zs, X, Y, Z, step, eps, out):
    """:func:`hidden` for many points (true orthophoto, Fig. 7.13)."""
    zmax = -np.inf
    for i in range(dsm.shape[0]):
        for j in range(dsm.shape[1]):
            if dsm[i, j] > zmax:
                zmax = dsm[i, j]
    for k in prange(X.size):
        out[k] = hidden(dsm, x0, y0, dx, dy, zmax, Xs, Ys, Zs, X[k], Y[k], Z[k], step, eps)
