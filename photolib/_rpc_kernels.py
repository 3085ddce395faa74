"""numba kernel of photolib.rpc.locate: the Newton inverse (8.18.1) of an RPC, one point at a time.

Private module, imported on the first call of :func:`photolib.rpc.locate` so that
``import photolib.rpc`` stays fast. The numpy version in photolib.rpc evaluated the 20 terms and
their derivatives for every point at every step (≈ 6 Newton steps × 3 × 20 columns per point);
this kernel keeps everything in registers and stops each point when it has converged.

Status codes per point: 0 converged, 1 not converged in ``max_iterations``, 2 a denominator
vanished, 3 singular Jacobian, 4 left the valid range.
"""

from __future__ import annotations

import numpy as np
from numba import njit


@njit(cache=True)
def _terms_only(L, P, H, t):
    t[0] = 1.0
    t[1] = L
    t[2] = P
    t[3] = H
    t[4] = L * P
    t[5] = L * H
    t[6] = P * H
    t[7] = L * L
    t[8] = P * P
    t[9] = H * H
    t[10] = P * L * H
    t[11] = L * L * L
    t[12] = L * P * P
    t[13] = L * H * H
    t[14] = L * L * P
    t[15] = P * P * P
    t[16] = P * H * H
    t[17] = L * L * H
    t[18] = P * P * H
    t[19] = H * H * H


@njit(cache=True)
def _terms(L, P, H, t, tL, tP):
    """The 20 RPC00B terms and their derivatives by L and by P."""
    _terms_only(L, P, H, t)
    for k in range(20):
        tL[k] = 0.0
        tP[k] = 0.0
    tL[1] = 1.0
    tL[4] = P
    tL[5] = H
    tL[7] = 2 * L
    tL[10] = P * H
    tL[11] = 3 * L * L
    tL[12] = P * P
    tL[13] = H * H
    tL[14] = 2 * L * P
    tL[17] = 2 * L * H
    tP[2] = 1.0
    tP[4] = L
    tP[6] = H
    tP[8] = 2 * P
    tP[10] = L * H
    tP[12] = 2 * L * P
    tP[14] = L * L
    tP[15] = 3 * P * P
    tP[16] = H * H
    tP[18] = 2 * P * H


@njit(cache=True)
def _dot(c, t):
    s = 0.0
    for k in range(20):
        s += c[k] * t[k]
    return s


@njit(cache=True)
def _dot_L(c, t):
    """c · ∂terms/∂L without the zero entries (t holds the terms)."""
    L, P, H = t[1], t[2], t[3]
    return (c[1] + c[4] * P + c[5] * H + 2 * c[7] * L + c[10] * P * H + 3 * c[11] * L * L + c[12] * P * P
            + c[13] * H * H + 2 * c[14] * L * P + 2 * c[17] * L * H)


@njit(cache=True)
def _dot_P(c, t):
    """c · ∂terms/∂P without the zero entries."""
    L, P, H = t[1], t[2], t[3]
    return (c[2] + c[4] * L + c[6] * H + 2 * c[8] * P + c[10] * L * H + 2 * c[12] * L * P + c[14] * L * L
            + 3 * c[15] * P * P + c[16] * H * H + 2 * c[18] * P * H)


@njit(cache=True)
def _newton(r, c, H, L, P, ln, ld, sn, sd, line_scale, samp_scale, tol, max_iterations, limit, floor, t, history,
            record):
    """Newton (8.18.1) for one point from (L, P); returns (L, P, status, evaluations)."""
    tiny = np.finfo(np.float64).tiny
    for it in range(max_iterations + 1):
        _terms_only(L, P, H, t)
        dl = _dot(ld, t)
        ds = _dot(sd, t)
        if abs(dl) < floor or abs(ds) < floor:
            return L, P, 2, it + 1
        line = _dot(ln, t) / dl
        samp = _dot(sn, t) / ds
        fr = line - r
        fc = samp - c
        a = (_dot_L(ln, t) - line * _dot_L(ld, t)) / dl
        b = (_dot_P(ln, t) - line * _dot_P(ld, t)) / dl
        e = (_dot_L(sn, t) - samp * _dot_L(sd, t)) / ds
        f = (_dot_P(sn, t) - samp * _dot_P(sd, t)) / ds
        det = a * f - b * e
        scale = max(abs(a * f), abs(b * e)) + tiny
        if abs(det) <= 1e-12 * scale:
            return L, P, 3, it + 1
        res = np.hypot(fr * line_scale, fc * samp_scale)
        if record and res > history[it]:
            history[it] = res
        if res <= tol:
            return L, P, 0, it + 1
        if it == max_iterations:
            return L, P, 1, it + 1
        L = L - (f * fr - b * fc) / det
        P = P - (a * fc - e * fr) / det
        if abs(L) > limit or abs(P) > limit:
            return L, P, 4, it + 1
    return L, P, 1, max_iterations + 1


@njit(cache=True)
def locate_kernel(r, c, H, ln, ld, sn, sd, line_scale, samp_scale, tol, max_iterations, limit, floor):
    """Newton inverse of every point. Each point starts from its predecessor's solution (image
    points of a raster are neighbours: one or two steps instead of five); a point that does not
    converge from there is redone from the scene centre (0, 0), whose run alone decides its status
    and enters ``history`` (the largest residual after each step, as in the numpy loop)."""
    n = r.size
    L_out = np.zeros(n)
    P_out = np.zeros(n)
    status = np.zeros(n, dtype=np.int64)
    history = np.zeros(max_iterations + 1)
    scratch = np.zeros(max_iterations + 1)
    evaluations = 0
    t = np.empty(20)
    L0 = 0.0
    P0 = 0.0
    warm = False
    for i in range(n):
        code = 1
        if warm:
            L, P, code, used = _newton(r[i], c[i], H[i], L0, P0, ln, ld, sn, sd, line_scale, samp_scale, tol,
                                       max_iterations, limit, floor, t, scratch, False)
        if code != 0:
            L, P, code, used = _newton(r[i], c[i], H[i], 0.0, 0.0, ln, ld, sn, sd, line_scale, samp_scale, tol,
                                       max_iterations, limit, floor, t, history, True)
            if used > evaluations:
                evaluations = used
        L_out[i] = L
        P_out[i] = P
        status[i] = code
        warm = code == 0
        if warm:
            L0 = L
            P0 = P
    if evaluations == 0:
        evaluations = 1
    return L_out, P_out, status, history[:evaluations]


@njit(cache=True)
def project_kernel(L, P, H, ln, ld, sn, sd, rows, cols):
    """Normalised line and sample ratios (8.5.7) point by point, without the 20 × N term matrix.

    Returns the smallest |denominator| met, so that the caller can report a vanishing one.
    """
    t = np.empty(20)
    smallest = np.inf
    for k in range(L.size):
        _terms_only(L[k], P[k], H[k], t)
        dl = _dot(ld, t)
        ds = _dot(sd, t)
        smallest = min(smallest, abs(dl), abs(ds))
        rows[k] = _dot(ln, t) / dl
        cols[k] = _dot(sn, t) / ds
    return smallest
