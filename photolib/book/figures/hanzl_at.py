"""Figures for Hanzl §4–§5 (seed 002; ``chapters/appendix_hanzl_4_at_close_range.ipynb``).

* :func:`normal_structure` — Fig. 4.3 redrawn: non-zero patterns of the normal matrices of the bundle
  (left) and of independent models (right) for a small strip.
* :func:`ebner_fields` — Fig. 4.5 redrawn: the twelve Ebner deformation fields as quiver plots on the
  image (23 × 23 cm, b = 92 mm), with the 3 × 3 grid of standard points.
* :func:`ebner_recovery` — simulated and recovered g₁ … g₁₂ (with ±2σ bars) of the self-calibration.

Every function returns the matplotlib Figure, closed (a notebook cell shows it once).
"""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np

from ... import additional_parameters as ap

__all__ = ["normal_structure", "ebner_fields", "ebner_recovery"]


def _done(fig):
    plt.close(fig)
    return fig


def normal_structure(N_bundle, n_eo, N_models):
    """Spy plots of N = AᵀA: bundle (images then points) and independent models (7 per model)."""
    fig, axes = plt.subplots(1, 2, figsize=(9.5, 4.6), constrained_layout=True,
                             gridspec_kw={"width_ratios": [N_bundle.shape[0], max(N_models.shape[0], 30)]})
    ax = axes[0]
    ax.spy(N_bundle, markersize=1.6, color="C0")
    ax.axhline(n_eo - 0.5, color="C3", lw=0.8)
    ax.axvline(n_eo - 0.5, color="C3", lw=0.8)
    ax.set_title(f"bundle: {n_eo} EO unknowns | {N_bundle.shape[0] - n_eo} point coordinates", fontsize=9)
    ax = axes[1]
    ax.spy(N_models, markersize=4, color="C2")
    ax.set_title(f"independent models: 7 per model ({N_models.shape[0]})", fontsize=9)
    for a in axes:
        a.tick_params(labelsize=7)
    return _done(fig)


def ebner_fields(b: float = 92.0, half: float = 115.0, n: int = 7, scale: float = 0.9):
    """The 12 unit fields g_i of Ebner's set (Hanzl's signs), each normalised to its largest vector."""
    g = np.linspace(-half, half, n)
    X, Y = np.meshgrid(g, g)
    xy = np.column_stack([X.ravel(), Y.ravel()])
    B = ap.ap_basis("hanzl17", xy, b=b, r0=0.0)[:, :, :12]
    fig, axes = plt.subplots(3, 4, figsize=(9.5, 7.4), constrained_layout=True)
    grid = np.array([(i * b, j * b) for i in (-1, 0, 1) for j in (-1, 0, 1)])
    for k, ax in enumerate(axes.ravel()):
        u, v = B[:, 0, k], B[:, 1, k]
        m = np.hypot(u, v).max()
        ax.quiver(xy[:, 0], xy[:, 1], u / m, v / m, angles="xy", scale_units="xy", scale=1 / (scale * 2 * half / (n - 1)),
                  width=0.012, color="C0")
        ax.plot(grid[:, 0], grid[:, 1], "o", ms=3, color="C3")
        ax.set_xlim(-1.25 * half, 1.25 * half)
        ax.set_ylim(-1.25 * half, 1.25 * half)
        ax.set_aspect("equal")
        ax.set_xticks([])
        ax.set_yticks([])
        ax.set_title(f"g{k + 1}", fontsize=9)
    fig.suptitle("Ebner's 12 parameters (Hanzl fig. 4.5): image deformation fields, b = 92 mm, "
                 "red = 3 × 3 grid", fontsize=9)
    return _done(fig)


def ebner_recovery(names, values, std, truth):
    """Recovered g_i against the simulated ones, each divided by its σ (so all share one axis)."""
    names = list(names)
    v, s = np.asarray(values, float), np.asarray(std, float)
    t = np.array([truth.get(nm, 0.0) for nm in names])
    fig, ax = plt.subplots(figsize=(8.5, 3.4), constrained_layout=True)
    x = np.arange(len(names))
    ax.errorbar(x, v / s, yerr=2.0, fmt="o", color="C0", capsize=3, label="adjusted g / σ_g (±2)")
    ax.plot(x, t / s, "x", color="C3", ms=9, label="simulated g / σ_g")
    ax.axhline(0, color="0.5", lw=0.8)
    ax.set_xticks(x)
    ax.set_xticklabels(names)
    ax.set_ylabel("g / σ_g")
    ax.legend(fontsize=8)
    return _done(fig)
