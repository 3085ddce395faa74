"""Compiled per-pixel loops of :mod:`photolib.rectify` (resampling and DEM interpolation).

Private: the public functions validate their inputs and call these kernels. numba compiles them
on first use (``cache=True`` keeps the machine code between sessions).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit, prange


@njit(cache=True)
def _keys_weight(t, a):
    """Keys' cubic convolution kernel with parameter a (−0.5: Keys/GDAL/PIL; −0.75: OpenCV)."""
    t = abs(t)
    if t <= 1.0:
        return ((a + 2.0) * t - (a + 3.0)) * t * t + 1.0
    if t < 2.0:
        return ((a * t - 5.0 * a) * t + 8.0 * a) * t - 4.0 * a
    return 0.0


@njit(cache=True, parallel=True)
def resample_nearest(image, rows, cols, fill, out):
    n_rows, n_cols = image.shape[0], image.shape[1]
    for k in prange(rows.size):
        r, c = rows[k], cols[k]
        if not (r >= -0.5 and r < n_rows - 0.5 and c >= -0.5 and c < n_cols - 0.5):
            out[k, :] = fill
            continue
        i = int(math.floor(r + 0.5))
        j = int(math.floor(c + 0.5))
        for b in range(image.shape[2]):
            out[k, b] = image[i, j, b]


@njit(cache=True, parallel=True)
def resample_bilinear(image, rows, cols, fill, out):
    n_rows, n_cols = image.shape[0], image.shape[1]
    for k in prange(rows.size):
        r, c = rows[k], cols[k]
        if not (r >= 0.0 and r <= n_rows - 1 and c >= 0.0 and c <= n_cols - 1):
            out[k, :] = fill
            continue
        i = min(int(r), n_rows - 2) if n_rows > 1 else 0
        j = min(int(c), n_cols - 2) if n_cols > 1 else 0
        dr, dc = r - i, c - j
        i1 = min(i + 1, n_rows - 1)
        j1 = min(j + 1, n_cols - 1)
        for b in range(image.shape[2]):
            top = image[i, j, b] * (1.0 - dc) + image[i, j1, b] * dc
            bottom = image[i1, j, b] * (1.0 - dc) + image[i1, j1, b] * dc
            out[k, b] = top * (1.0 - dr) + bottom * dr


@njit(cache=True, parallel=True)
def resample_bicubic(image, rows, cols, fill, out, a=-0.5):
    n_rows, n_cols = image.shape[0], image.shape[1]
    for k in prange(rows.size):
        r, c = rows[k], cols[k]
        if not (r >= 0.0 and r <= n_rows - 1 and c >= 0.0 and c <= n_cols - 1):
            out[k, :] = fill
            continue
        i0 = int(math.floor(r))
        j0 = int(math.floor(c))
        for b in range(image.shape[2]):
            total = 0.0
            for di in range(-1, 3):
                wi = _keys_weight(r - (i0 + di), a)
                if wi == 0.0:
                    continue
                ii = min(max(i0 + di, 0), n_rows - 1)
                row_sum = 0.0
                for dj in range(-1, 3):
                    wj = _keys_weight(c - (j0 + dj), a)
                    if wj == 0.0:
                        continue
                    jj = min(max(j0 + dj, 0), n_cols - 1)
                    row_sum += wj * image[ii, jj, b]
                total += wi * row_sum
            out[k, b] = total


@njit(cache=True, parallel=True)
def accumulate_forward(values, rows, cols, total, weight):
    """Spread each value over the (up to) four output pixels its centre falls between, with the
    bilinear area weights; the caller divides ``total`` by ``weight``. Serial over points within
    a thread would race, so the bands are the parallel axis."""
    n_rows, n_cols = total.shape[0], total.shape[1]
    for b in prange(values.shape[1]):
        for k in range(rows.size):
            r, c = rows[k], cols[k]
            if not (r > -1.0 and r < n_rows and c > -1.0 and c < n_cols):
                continue
            i = int(math.floor(r))
            j = int(math.floor(c))
            dr, dc = r - i, c - j
            for di in range(2):
                ii = i + di
                if ii < 0 or ii >= n_rows:
                    continue
                wr = dr if di == 1 else 1.0 - dr
                for dj in range(2):
                    jj = j + dj
                    if jj < 0 or jj >= n_cols:
                        continue
                    w = wr * (dc if dj == 1 else 1.0 - dc)
                    if w == 0.0:
                        continue
                    total[ii, jj, b] += w * values[k, b]
                    if b == 0:
                        weight[ii, jj] += w


def as_float_bands(image):
    """(rows, cols) or (rows, cols, bands) → contiguous float64 (rows, cols, bands)."""
    array = np.asarray(image, dtype=np.float64)
    if array.ndim == 2:
        array = array[:, :, None]
    return np.ascontiguousarray(array)
