"""Figures of Chapter 3, §3.5: the rebuilt block layouts (figs. 3.10, 3.13) and the structure of
the correction equations and normal equations (figs. 3.11, 3.12), drawn from built systems."""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.colors import ListedColormap
from matplotlib.patches import Rectangle

from ...synthetic import CONTROL, Block
from ...triangulation_layouts import BundleSystem, images_per_point

ROW_SHADE = {"tie": 0.45, "control": 0.9, "ground": 0.65, "gnss": 0.65, "ins": 0.65}


def plot_layout(block: Block, ax=None, counts: bool = False):
    """Footprints, projection centres and points of a rebuilt block (figs. 3.10/3.13).

    Control points are triangles, tie points circles; each point is labelled with its book number
    or (``counts=True``) with the number of images it appears on, as in fig. 3.13.
    """
    if ax is None:
        _, ax = plt.subplots(figsize=(6, 5))
    L = block.footprint
    colours = plt.cm.tab10(np.arange(block.n_images) % 10)
    for i, (X, Y) in enumerate(block.cameras[:, :2]):
        ax.add_patch(Rectangle((X - L / 2, Y - L / 2), L, L, fill=False, lw=1.0, ec=colours[i], alpha=0.8))
        ax.plot(X, Y, "+", color=colours[i], ms=10)
        ax.annotate(block.image_labels[i], (X, Y), textcoords="offset points", xytext=(4, -12), color=colours[i],
                    fontsize=8)
    ctrl = block.kind == CONTROL
    ax.plot(*block.points[ctrl, :2].T, "^", color="k", ms=8, label="XYZ control")
    ax.plot(*block.points[~ctrl, :2].T, "o", mfc="w", mec="k", ms=7, label="tie point")
    text = images_per_point(block) if counts else block.point_labels
    for (X, Y), t in zip(block.points[:, :2], text):
        ax.annotate(str(t), (X, Y), textcoords="offset points", xytext=(5, 4), fontsize=9)
    ax.set_aspect("equal")
    ax.set_xlabel("X, m")
    ax.set_ylabel("Y, m")
    ax.legend(loc="upper right", fontsize=8, framealpha=0.9)
    ax.set_title(f"{block.name}: footprints and points" + (" (images per point)" if counts else ""))
    return ax


def spy_design(system: BundleSystem, ax=None):
    """Structure of A (fig. 3.11): rows of (3.5.2) light, rows of (3.5.3) dark, direct observations mid grey."""
    if ax is None:
        _, ax = plt.subplots(figsize=(5, 6))
    shade = np.array([ROW_SHADE[k] for k in system.row_kind])
    img = np.where(system.A != 0, shade[:, None], 0.0)
    cmap = ListedColormap(plt.cm.Greys(np.linspace(0, 1, 256)))
    ax.imshow(img, cmap=cmap, vmin=0, vmax=1, interpolation="nearest", aspect="equal")
    ax.axvline(system.n_eo - 0.5, color="tab:red", lw=0.8)
    ax.set_xlabel(f"unknowns: {system.n_eo} EO | {system.A.shape[1] - system.n_eo} point coordinates")
    ax.set_ylabel("correction equations")
    ax.set_title(f"A  {system.A.shape[0]}×{system.A.shape[1]}, {system.nnz} non-zeros")
    return ax


def spy_normal(system: BundleSystem, ax=None):
    """Structure of N = AᵀPA (fig. 3.12) with the partition N₁₁ | N₁₂ / N₁₂ᵀ | N₂₂."""
    if ax is None:
        _, ax = plt.subplots(figsize=(5, 5))
    N, _ = system.normal()
    ax.spy(N, markersize=3, color="0.3")
    q = system.n_eo - 0.5
    ax.axvline(q, color="tab:red", lw=0.8)
    ax.axhline(q, color="tab:red", lw=0.8)
    n = N.shape[0]
    for text, x, y in (("N₁₁", q / 2, q / 2), ("N₁₂", (q + n) / 2, q / 2), ("N₁₂ᵀ", q / 2, (q + n) / 2),
                       ("N₂₂", (q + n) / 2, (q + n) / 2)):
        ax.text(x, y, text, color="tab:red", ha="center", va="center", fontsize=11, alpha=0.8)
    ax.set_title(f"N = AᵀPA  {n}×{n}")
    return ax
