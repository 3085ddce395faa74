"""numba kernels of :mod:`photolib.segmentation` (Chapter 9, §9.11): Hough voting and the
lowest-point raster. Private; imported on first use so that ``import photolib.segmentation``
stays fast."""

from __future__ import annotations

import numpy as np
from numba import njit

__all__ = ["hough_vote", "lowest_per_cell"]


@njit(cache=True)
def hough_vote(xyz, normals, p_min, p_step, n_p):
    """Accumulator votes[a·b, k]: for each normal direction j (one (α, β) cell) and each point,
    the cell k of p = n_j·X (9.11.1). Points outside the p range are ignored."""
    n_dir = normals.shape[0]
    acc = np.zeros((n_dir, n_p), dtype=np.int32)
    for j in range(n_dir):
        nx, ny, nz = normals[j, 0], normals[j, 1], normals[j, 2]
        for i in range(xyz.shape[0]):
            p = xyz[i, 0] * nx + xyz[i, 1] * ny + xyz[i, 2] * nz
            k = int(np.floor((p - p_min) / p_step))
            if 0 <= k < n_p:
                acc[j, k] += 1
    return acc


@njit(cache=True)
def lowest_per_cell(rows, cols, z, ny, nx):
    """The lowest z per raster cell (+inf where the cell holds no point)."""
    grid = np.full((ny, nx), np.inf)
    for i in range(z.shape[0]):
        r, c = rows[i], cols[i]
        if z[i] < grid[r, c]:
            grid[r, c] = z[i]
    return grid
