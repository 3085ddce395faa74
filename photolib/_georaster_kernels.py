"""numba kernels of :mod:`photolib.georaster` (Chapter 7, §7.3): private.

* :func:`lattice_bilinear` — bilinear interpolation of values given on a coarse lattice at the
  points of a fine rectilinear grid (separable weights), for the approximate CRS transform.
"""

from __future__ import annotations

import numpy as np
from numba import njit

__all__ = []


@njit(cache=True)
def lattice_bilinear(nodes, iy, ty, ix, tx, out):
    """out[r, c] = bilinear of nodes at (iy[r] + ty[r], ix[c] + tx[c])."""
    for r in range(iy.size):
        i = iy[r]
        v = ty[r]
        for c in range(ix.size):
            j = ix[c]
            u = tx[c]
            top = nodes[i, j] * (1.0 - u) + nodes[i, j + 1] * u
            bottom = nodes[i + 1, j] * (1.0 - u) + nodes[i + 1, j + 1] * u
            out[r, c] = top * (1.0 - v) + bottom * v
