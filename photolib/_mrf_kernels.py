"""Compiled kernels of the Gibbs/MRF relaxation (private; used by :mod:`photolib.mrf`, the MRF terrain paper).

Loop-shaped code (a sequential raster-scan Gibbs sampler over every pixel and every candidate
parallax) compiled with numba. This module imports numba at import time; :mod:`photolib.mrf`
imports it only when the relaxation is first run, so that ``import photolib.mrf`` stays fast.
"""

from __future__ import annotations

import numpy as np
from numba import njit

__all__ = ["gibbs_sweeps", "energy"]


@njit(cache=True)
def energy(data, labels, values, a, b):
    """U = −a·Σ_x V_p(x, p_x) − b·Σ_{8-neighbour pairs, each once} (p_x − p_y)²."""
    H, W = labels.shape
    ud = 0.0
    us = 0.0
    for y in range(H):
        for x in range(W):
            k = labels[y, x]
            v = values[k]
            ud += data[k, y, x]
            # each unordered pair once: right, down-left, down, down-right
            if x + 1 < W:
                d = v - values[labels[y, x + 1]]
                us += d * d
            if y + 1 < H:
                d = v - values[labels[y + 1, x]]
                us += d * d
                if x + 1 < W:
                    d = v - values[labels[y + 1, x + 1]]
                    us += d * d
                if x - 1 >= 0:
                    d = v - values[labels[y + 1, x - 1]]
                    us += d * d
    return -a * ud - b * us


@njit(cache=True)
def gibbs_sweeps(data, labels, values, a, b, sweeps, burn_in, seed, counts, energies):
    """Sequential (raster-scan) Gibbs sampling of the conditional P(x, y, p) of the paper.

    ``data`` (P, H, W) is V_p, ``labels`` (H, W) the current indices into ``values`` (updated in
    place), ``counts`` (P, H, W) accumulates the samples after ``burn_in`` sweeps, ``energies``
    (sweeps,) receives U after every sweep. The random stream is numba's generator seeded with
    ``seed``, so a run is a deterministic function of its arguments.
    """
    np.random.seed(seed)
    P, H, W = data.shape
    logits = np.empty(P)
    for s in range(sweeps):
        for y in range(H):
            for x in range(W):
                s1 = 0.0
                n = 0
                for dy in range(-1, 2):
                    yy = y + dy
                    if yy < 0 or yy >= H:
                        continue
                    for dx in range(-1, 2):
                        if dy == 0 and dx == 0:
                            continue
                        xx = x + dx
                        if xx < 0 or xx >= W:
                            continue
                        s1 += values[labels[yy, xx]]
                        n += 1
                m = -np.inf
                for k in range(P):
                    v = values[k]
                    # a·V_p + b·V_s with V_s = Σ (v − p_j)² = n v² − 2 v Σp_j + Σp_j² (last term cancels)
                    lg = a * data[k, y, x] + b * (n * v * v - 2.0 * v * s1)
                    logits[k] = lg
                    if lg > m:
                        m = lg
                total = 0.0
                for k in range(P):
                    e = np.exp(logits[k] - m)
                    logits[k] = e
                    total += e
                u = np.random.random() * total
                acc = 0.0
                choice = P - 1
                for k in range(P):
                    acc += logits[k]
                    if u < acc:
                        choice = k
                        break
                labels[y, x] = choice
        if s >= burn_in:
            for y in range(H):
                for x in range(W):
                    counts[labels[y, x], y, x] += 1
        energies[s] = energy(data, labels, values, a, b)
    return labels
