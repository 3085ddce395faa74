"""Figures for the Chapter 2 worked example (after §2.12): correlation matrices as printed vs correct,
residual y-parallaxes and control-point residuals."""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np

from .ch01_resection import correlation_pair

RO_LABELS = (r"$\alpha'_1$", r"$\kappa'_1$", r"$\omega'_2$", r"$\alpha'_2$", r"$\kappa'_2$")
AO_LABELS = ("$X_0$", "$Y_0$", "$Z_0$", r"$\omega_M$", r"$\alpha_M$", r"$\kappa_M$", "$t$")


def correlation_heat_maps(correct, book, labels, titles=("correct partials", "printed in the book")):
    """Two correlation matrices side by side (−1 … 1), values in the cells (as in Chapter 1, §1.8)."""
    return correlation_pair(correct, book, labels=labels, titles=titles)


def y_parallaxes(q_computed, q_book, ax=None):
    """Residual y-parallaxes per point: computed (2.8.2) and printed, points with flipped sign marked."""
    q_computed, q_book = np.asarray(q_computed, float), np.asarray(q_book, float)
    if ax is None:
        _, ax = plt.subplots(figsize=(6, 3))
    n = np.arange(1, len(q_book) + 1)
    ax.bar(n - 0.2, q_computed * 1000, 0.4, label="computed (2.8.2)")
    ax.bar(n + 0.2, q_book * 1000, 0.4, label="printed")
    flipped = np.flatnonzero(np.sign(q_computed) != np.sign(q_book))
    ax.plot(n[flipped], np.maximum(q_computed, q_book)[flipped] * 1000 + 3, "rv", label="sign differs")
    ax.axhline(0, color="0.5", lw=0.5)
    ax.set(xticks=n, xlabel="point", ylabel="q, µm")
    ax.legend(fontsize=8)
    return ax


def control_residuals(XYZ, d, scale: float = 500.0, ax=None, title: str = ""):
    """Planimetric residuals dX, dY (arrows, magnified) and dZ (colour) at the control points."""
    XYZ, d = np.asarray(XYZ, float), np.asarray(d, float)
    if ax is None:
        _, ax = plt.subplots(figsize=(5, 5))
    sc = ax.scatter(XYZ[:, 0], XYZ[:, 1], c=d[:, 2], cmap="RdBu_r", vmin=-0.5, vmax=0.5, s=60, zorder=3)
    ax.quiver(XYZ[:, 0], XYZ[:, 1], scale * d[:, 0], scale * d[:, 1], angles="xy", scale_units="xy", scale=1,
              color="k", width=0.005)
    ax.figure.colorbar(sc, ax=ax, shrink=0.8, label="dZ, m")
    ax.set(xlabel="X, m", ylabel="Y, m", aspect="equal", title=title or f"dX, dY ×{scale:g}")
    return ax
