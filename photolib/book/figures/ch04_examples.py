"""Figures for the Chapter 4 worked examples: the correlation matrix of L₁…L₁₁ as printed vs computed
(§4.3), and epipolar lines of the §4.4 pair drawn on the book's image points."""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np

L_LABELS = tuple(f"$L_{{{i}}}$" for i in range(1, 12))


def correlation_book_vs_computed(computed, book, labels=L_LABELS, tolerance: float = 0.005,
                                 titles=("computed (1.8.10), image 2", "printed in the book")):
    """Two correlation matrices side by side (−1 … 1); cells where the printed value differs from the
    computed one by more than ``tolerance`` (the printed rounding) are framed in both panels."""
    computed, book = np.asarray(computed, float), np.asarray(book, float)
    n = len(book)
    off = np.abs(book - computed) > tolerance + 1e-9
    fig, axes = plt.subplots(1, 2, figsize=(11, 5), constrained_layout=True)
    for ax, R, title in zip(axes, (computed, book), titles):
        im = ax.imshow(R, cmap="RdBu_r", vmin=-1, vmax=1)
        for i in range(n):
            for j in range(n):
                ax.text(j, i, f"{R[i, j]:.2f}".replace("-0.00", "0.00") if i != j else "1", ha="center",
                        va="center", fontsize=6, color="w" if abs(R[i, j]) > 0.6 else "k")
                if off[i, j]:
                    ax.add_patch(plt.Rectangle((j - 0.5, i - 0.5), 1, 1, fill=False, ec="k", lw=1.6))
        ax.set_xticks(range(n), labels[:n], fontsize=8)
        ax.set_yticks(range(n), labels[:n], fontsize=8)
        ax.set_title(title)
    fig.colorbar(im, ax=axes, shrink=0.75, label="$r_{ij}$")
    return fig


def epipolar_lines(lines, xy1, xy2, solved: int = 8, half_width: float = 90.0, title: str = ""):
    """Points of image 1 (left) and their epipolar lines a·x + b·y + c = 0 on image 2 (right) with
    the corresponding points; points 1…``solved`` were used to find F, the others are checks."""
    xy1, xy2, lines = np.asarray(xy1, float), np.asarray(xy2, float), np.asarray(lines, float)
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(10, 5), constrained_layout=True)
    x = np.array([-half_width, half_width])
    for k, ((px, py), (qx, qy), (a, b, c)) in enumerate(zip(xy1, xy2, lines)):
        colour = plt.cm.tab20(k % 20)
        style = "-" if k < solved else "--"
        a1.plot(px, py, "o" if k < solved else "s", color=colour)
        a1.annotate(str(k + 1), (px, py), xytext=(4, 4), textcoords="offset points", fontsize=8)
        a2.plot(x, -(a * x + c) / b, style, color=colour, lw=0.9)
        a2.plot(qx, qy, "o" if k < solved else "s", color=colour)
        a2.annotate(str(k + 1), (qx, qy), xytext=(4, 4), textcoords="offset points", fontsize=8)
    for ax, name in ((a1, "image 1: points $r_1$"), (a2, "image 2: lines $l_2 = F r_1$ and points $r_2$")):
        ax.set(xlim=(-half_width, half_width), ylim=(-half_width, half_width), aspect="equal",
               xlabel="x, mm", ylabel="y, mm", title=name)
        ax.axhline(0, color="0.8", lw=0.5)
        ax.axvline(0, color="0.8", lw=0.5)
    a2.plot([], [], "k-", label=f"points 1–{solved} (solve F)")
    a2.plot([], [], "k--", label="check points")
    a2.legend(loc="lower left", fontsize=8)
    if title:
        fig.suptitle(title)
    return fig


def point_differences(diff, std, labels=("X", "Y", "Z"), ax=None):
    """Book − computed object coordinates (mm) per point beside ±m (the a-posteriori precision)."""
    diff, std = np.asarray(diff, float) * 1000, np.asarray(std, float) * 1000
    if ax is None:
        _, ax = plt.subplots(figsize=(7, 3))
    n = np.arange(1, len(diff) + 1)
    for j, lab in enumerate(labels):
        ax.plot(n + (j - 1) * 0.2, diff[:, j], "o", color=f"C{j}", label=f"book − ours, {lab}")
        ax.errorbar(n + (j - 1) * 0.2, np.zeros(len(n)), yerr=std[:, j], fmt="none", ecolor=f"C{j}", alpha=0.35,
                    elinewidth=4)
    ax.axhline(0, color="0.5", lw=0.5)
    ax.set(xticks=n, xlabel="point", ylabel="mm")
    ax.legend(fontsize=8, ncol=3)
    return ax
