"""Figures for Chapter 1, §1.8–§1.9 (space resection): residual vectors, correlation matrices, convergence."""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np

EO_LABELS = ("$X_S$", "$Y_S$", "$Z_S$", r"$\omega$", r"$\alpha$", r"$\kappa$")


def residual_vectors(xy, residuals, scale: float = 1000.0, ax=None, title: str = "", frame_mm: float = 115.0):
    """Residual vectors v (mm) drawn at the image points, magnified ``scale`` times (cf. Fig. 1.17)."""
    xy, residuals = np.asarray(xy, float), np.asarray(residuals, float)
    if ax is None:
        _, ax = plt.subplots(figsize=(5, 5))
    ax.plot(*xy.T, "k^", ms=7, label="control point")
    ax.quiver(*xy.T, *(scale * residuals).T, angles="xy", scale_units="xy", scale=1, color="C3",
              width=0.006, label=f"residual ×{scale:g}")
    for k, (x, y) in enumerate(xy, 1):
        ax.annotate(str(k), (x, y), xytext=(4, 4), textcoords="offset points")
    ax.axhline(0, color="0.7", lw=0.5)
    ax.axvline(0, color="0.7", lw=0.5)
    ax.set(xlim=(-frame_mm, frame_mm), ylim=(-frame_mm, frame_mm), xlabel="x, mm", ylabel="y, mm", aspect="equal",
           title=title)
    ax.legend(loc="lower left", fontsize=8)
    return ax


def correlation_pair(computed, book, labels=EO_LABELS, titles=("computed", "book")):
    """Two correlation matrices side by side, same colour scale (−1 … 1), values written in the cells."""
    fig, axes = plt.subplots(1, 2, figsize=(9, 4.2), constrained_layout=True)
    for ax, R, title in zip(axes, (computed, book), titles):
        R = np.asarray(R, float)
        im = ax.imshow(R, cmap="RdBu_r", vmin=-1, vmax=1)
        n = len(R)
        for i in range(n):
            for j in range(n):
                ax.text(j, i, f"{R[i, j]:.2f}", ha="center", va="center", fontsize=7,
                        color="w" if abs(R[i, j]) > 0.6 else "k")
        ax.set_xticks(range(n), labels[:n])
        ax.set_yticks(range(n), labels[:n])
        ax.set_title(title)
    fig.colorbar(im, ax=axes, shrink=0.8, label="$r_{ij}$")
    return fig


def convergence(histories, labels, ax=None):
    """|δ| of the position unknowns per iteration for one or more runs (log scale)."""
    if ax is None:
        _, ax = plt.subplots(figsize=(5, 3.2))
    for history, label in zip(histories, labels):
        steps = [np.linalg.norm(rec.delta[:3]) for rec in history]
        ax.semilogy(range(1, len(steps) + 1), steps, "o-", label=label)
    ax.set(xlabel="iteration", ylabel=r"$|\delta X_S, \delta Y_S, \delta Z_S|$, m")
    ax.legend(fontsize=8)
    return ax
