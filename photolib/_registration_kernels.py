"""numba kernels of photolib.registration (Chapter 9, §9.6): normals by local PCA.

Imported on first use so that ``import photolib.registration`` stays fast.
"""

import numpy as np
from numba import njit

__all__ = ["pca_normals"]


@njit(cache=True)
def _smallest_eigvec(c00, c01, c02, c11, c12, c22):
    """Smallest eigenpair of a symmetric 3×3 matrix (trigonometric method) and the middle value."""
    p1 = c01 * c01 + c02 * c02 + c12 * c12
    q = (c00 + c11 + c22) / 3.0
    p2 = (c00 - q) ** 2 + (c11 - q) ** 2 + (c22 - q) ** 2 + 2.0 * p1
    p = np.sqrt(p2 / 6.0)
    out = np.empty(3)
    if p == 0.0:
        out[:] = np.nan
        return out, 0.0, 0.0
    b00, b11, b22 = (c00 - q) / p, (c11 - q) / p, (c22 - q) / p
    b01, b02, b12 = c01 / p, c02 / p, c12 / p
    r = (b00 * (b11 * b22 - b12 * b12) - b01 * (b01 * b22 - b12 * b02) + b02 * (b01 * b12 - b11 * b02)) / 2.0
    r = min(1.0, max(-1.0, r))
    phi = np.arccos(r) / 3.0
    e_max = q + 2.0 * p * np.cos(phi)
    e_min = q + 2.0 * p * np.cos(phi + 2.0 * np.pi / 3.0)
    e_mid = 3.0 * q - e_max - e_min
    # eigenvector of e_min: the longest cross product of two rows of C − e_min·E
    a0 = np.array([c00 - e_min, c01, c02])
    a1 = np.array([c01, c11 - e_min, c12])
    a2 = np.array([c02, c12, c22 - e_min])
    best = -1.0
    for u, v in ((a0, a1), (a0, a2), (a1, a2)):
        w = np.array([u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]])
        nw = w[0] * w[0] + w[1] * w[1] + w[2] * w[2]
        if nw > best:
            best = nw
            out[:] = w
    out /= np.sqrt(best) if best > 0 else np.nan
    return out, e_mid, e_max


@njit(cache=True)
def pca_normals(points, idx):
    """Normals (n, 3) and eigenvalues (middle, largest) of the neighbourhoods ``idx`` (n, k)."""
    n, k = idx.shape
    normals = np.empty((n, 3))
    mid = np.empty(n)
    big = np.empty(n)
    for i in range(n):
        m0 = m1 = m2 = 0.0
        for a in range(k):
            j = idx[i, a]
            m0 += points[j, 0]
            m1 += points[j, 1]
            m2 += points[j, 2]
        m0 /= k
        m1 /= k
        m2 /= k
        c00 = c01 = c02 = c11 = c12 = c22 = 0.0
        for a in range(k):
            j = idx[i, a]
            d0, d1, d2 = points[j, 0] - m0, points[j, 1] - m1, points[j, 2] - m2
            c00 += d0 * d0
            c01 += d0 * d1
            c02 += d0 * d2
            c11 += d1 * d1
            c12 += d1 * d2
            c22 += d2 * d2
        v, e_mid, e_max = _smallest_eigvec(c00 / k, c01 / k, c02 / k, c11 / k, c12 / k, c22 / k)
        normals[i] = v
        mid[i] = e_mid
        big[i] = e_max
    return normals, mid, big
