"""Compiled z-buffer rasteriser of the synthetic scene renderer (ground truth for Chapters 5–6).

Private: used by :func:`photolib.synthetic.render_image`. The surface of a
:class:`photolib.synthetic.TerrainScene` is a regular grid of heights split into two triangles
per cell (along the diagonal from node (i, j) to node (i + 1, j + 1)). Every triangle whose three
vertices lie in front of the camera is projected by the collinearity equations (1.4.12) (done
by the caller, vectorised); the kernel visits the pixels of its bounding box, keeps those whose
centre lies inside the projected triangle, intersects the pixel's ray with the triangle's plane
in object space (an exact ray–plane intersection, not an interpolation in the image) and keeps
the nearest intersection (the z-buffer). Loops over triangles and pixels are compiled by numba
(``cache=True``).
"""

from __future__ import annotations

import numba
import numpy as np

__all__ = ["rasterise"]


@numba.njit(cache=True)
def rasterise(col, row, front, P, S, A, x0, y0, f, pixel, height, width):  # pragma: no cover - compiled
    """Z-buffer of a triangulated height grid.

    col, row : (ny, nx) projected node positions, pixel units, centre of pixel [r, c] at (c, r).
    front : (ny, nx) bool, node in front of the camera.
    P : (ny, nx, 3) node coordinates X, Y, Z.
    S : (3,) projection centre; A : (3, 3) rotation camera → object.
    x0, y0, f, pixel : interior orientation and pixel size, mm.
    Returns t (height, width) ray parameter of the nearest hit (inf: none; the ray is
    S + t·A·(x − x0, y − y0, −f)) and the index of the triangle hit (−1: none).
    """
    ny, nx = col.shape
    t_buf = np.full((height, width), np.inf)
    tri = np.full((height, width), -1, dtype=np.int64)
    cx = (width - 1) / 2.0
    cy = (height - 1) / 2.0
    eps = 1e-9
    for i in range(ny - 1):
        for j in range(nx - 1):
            for k in range(2):
                if k == 0:
                    ia, ja, ib, jb, ic, jc = i, j, i, j + 1, i + 1, j + 1
                else:
                    ia, ja, ib, jb, ic, jc = i, j, i + 1, j + 1, i + 1, j
                if not (front[ia, ja] and front[ib, jb] and front[ic, jc]):
                    continue
                ua, va = col[ia, ja], row[ia, ja]
                ub, vb = col[ib, jb], row[ib, jb]
                uc, vc = col[ic, jc], row[ic, jc]
                area = (ub - ua) * (vc - va) - (vb - va) * (uc - ua)
                if abs(area) < 1e-14:
                    continue
                c_lo = max(int(np.ceil(min(ua, ub, uc) - 1e-9)), 0)
                c_hi = min(int(np.floor(max(ua, ub, uc) + 1e-9)), width - 1)
                r_lo = max(int(np.ceil(min(va, vb, vc) - 1e-9)), 0)
                r_hi = min(int(np.floor(max(va, vb, vc) + 1e-9)), height - 1)
                if c_lo > c_hi or r_lo > r_hi:
                    continue
                # the triangle's plane in object space: n · (X − Pa) = 0
                e1x = P[ib, jb, 0] - P[ia, ja, 0]
                e1y = P[ib, jb, 1] - P[ia, ja, 1]
                e1z = P[ib, jb, 2] - P[ia, ja, 2]
                e2x = P[ic, jc, 0] - P[ia, ja, 0]
                e2y = P[ic, jc, 1] - P[ia, ja, 1]
                e2z = P[ic, jc, 2] - P[ia, ja, 2]
                nxx = e1y * e2z - e1z * e2y
                nyy = e1z * e2x - e1x * e2z
                nzz = e1x * e2y - e1y * e2x
                num = nxx * (P[ia, ja, 0] - S[0]) + nyy * (P[ia, ja, 1] - S[1]) + nzz * (P[ia, ja, 2] - S[2])
                tid = (i * (nx - 1) + j) * 2 + k
                for r in range(r_lo, r_hi + 1):
                    for c in range(c_lo, c_hi + 1):
                        w0 = ((ub - c) * (vc - r) - (vb - r) * (uc - c)) / area
                        w1 = ((uc - c) * (va - r) - (vc - r) * (ua - c)) / area
                        w2 = 1.0 - w0 - w1
                        if w0 < -eps or w1 < -eps or w2 < -eps:
                            continue
                        x = (c - cx) * pixel - x0
                        y = (cy - r) * pixel - y0
                        dx = A[0, 0] * x + A[0, 1] * y - A[0, 2] * f
                        dy = A[1, 0] * x + A[1, 1] * y - A[1, 2] * f
                        dz = A[2, 0] * x + A[2, 1] * y - A[2, 2] * f
                        den = nxx * dx + nyy * dy + nzz * dz
                        if den == 0.0:
                            continue
                        t = num / den
                        if t > 0.0 and t < t_buf[r, c]:
                            t_buf[r, c] = t
                            tri[r, c] = tid
    return t_buf, tri
