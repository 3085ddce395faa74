"""Figures for Chapter 6, §6.1–6.3 (DSM by correlation): the rendered synthetic town (texture and
true DSM), the epipolar segment cd of a point between Z_min and Z_max, the correlation coefficient
against Z on the vertical line of one node (coarse to fine), and the DSM from one pair against the
best of several pairs, with their error maps.

Every function takes already computed results (:mod:`photolib.synthetic`, :mod:`photolib.surface`)
and returns the matplotlib figure.
"""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np

__all__ = ["town", "epipolar_segment", "vertical_line_search", "dsm_comparison"]


def _img(ax, img, title):
    ax.imshow(img, cmap="gray", vmin=0, vmax=1)
    ax.set_title(title, fontsize=9)
    ax.set_xticks([])
    ax.set_yticks([])


def town(scene, images, centres=None, frames=None):
    """The scene of :func:`photolib.synthetic.terrain_scene`: its texture, its DSM (with the
    projection centres, and optionally the ground footprints of the images as (k, 4, 2) X, Y
    corners), and the rendered images."""
    n = len(images)
    fig, axes = plt.subplots(1, 2 + n, figsize=(3.3 * (2 + n), 3.6), constrained_layout=True)
    ext = scene.extent
    axes[0].imshow(scene.albedo, cmap="gray", origin="lower", extent=ext, vmin=0, vmax=1)
    axes[0].set_title("texture (albedo)", fontsize=9)
    im = axes[1].imshow(scene.surface, cmap="terrain", origin="lower", extent=ext)
    fig.colorbar(im, ax=axes[1], shrink=0.75, label="Z, m")
    axes[1].set_title("true DSM: ground + buildings + trees", fontsize=9)
    for k in range(n):
        if centres is not None:
            axes[1].plot(*centres[k][:2], "o", color=f"C{k}", mec="k", ms=6)
            axes[1].annotate(f"S{k + 1}", centres[k][:2], xytext=(4, 4), textcoords="offset points", fontsize=8)
        if frames is not None:
            c = np.vstack([frames[k], frames[k][:1]])
            axes[1].plot(c[:, 0], c[:, 1], "-", color=f"C{k}", lw=1)
        _img(axes[2 + k], images[k], f"image {k + 1}")
    for ax in axes[:2]:
        ax.set(xlabel="X, m", ylabel="Y, m")
    plt.close(fig)          # shown once, by the notebook cell that returns it
    return fig


def epipolar_segment(left, right, point1, c, d, match, line=None, z_range=None):
    """§6.1, Fig. 6.2: the point m₁ on image 1; on image 2 the segment cd (ends at Z_min, Z_max),
    optionally the whole epipolar line ((n, 2) pixel positions), and the true match m₂ (pixels)."""
    fig, axes = plt.subplots(1, 3, figsize=(13.5, 4.6), constrained_layout=True)
    _img(axes[0], left, "image 1: point m₁")
    axes[0].plot(*point1, "o", color="C3", mec="w", ms=8)
    lab = f" (Z = {z_range[0]:g} … {z_range[1]:g} m)" if z_range is not None else ""
    _img(axes[1], right, "image 2: segment cd" + lab)
    _img(axes[2], right, "zoom on cd")
    c, d, match = (np.asarray(v, dtype=float) for v in (c, d, match))
    for ax in axes[1:]:
        if line is not None:
            ax.plot(line[:, 0], line[:, 1], "--", color="C0", lw=1, label="epipolar line")
        ax.plot([c[0], d[0]], [c[1], d[1]], "-", color="C1", lw=3, label="cd")
        ax.plot(*c, "s", color="C1", mec="k", ms=7, label="c (Z_min)")
        ax.plot(*d, "^", color="C1", mec="k", ms=8, label="d (Z_max)")
        ax.plot(*match, "o", color="C3", mec="w", ms=8, label="true m₂")
    mid, half = 0.5 * (c + d), max(0.5 * np.hypot(*(d - c)) + 6, 10)
    axes[2].set_xlim(mid[0] - half, mid[0] + half)
    axes[2].set_ylim(mid[1] + half, mid[1] - half)
    axes[2].legend(fontsize=8, loc="lower right")
    plt.close(fig)          # shown once, by the notebook cell that returns it
    return fig


def vertical_line_search(stages, z_true=None, title: str = ""):
    """§6.2, Fig. 6.4: R (5.1.2) against the trial height Z at one node.

    ``stages``: list of ``(label, Z, R)`` — e.g. the coarse pass over [Z_min, Z_max] and the finer
    passes around the best Z; the best Z of each stage is marked. Left: the whole range; right: a
    zoom on the last stages.
    """
    fig, axes = plt.subplots(1, 2, figsize=(11, 3.8), constrained_layout=True)
    markers = "os^dv"
    for ax, first in ((axes[0], 0), (axes[1], 1 if len(stages) > 1 else 0)):
        for k in range(first, len(stages)):
            label, Z, R = stages[k]
            Z, R = np.asarray(Z, dtype=float), np.asarray(R, dtype=float)
            ax.plot(Z, R, "-" + markers[k % 5], color=f"C{k}", ms=4, lw=1, label=label)
            if np.any(np.isfinite(R)):
                j = int(np.nanargmax(R))
                ax.plot(Z[j], R[j], markers[k % 5], color=f"C{k}", ms=10, mfc="none", mew=2)
        if z_true is not None:
            ax.axvline(z_true, color="k", lw=1, ls=":", label=f"true Z = {z_true:.2f} m")
        ax.set(xlabel="Z, m", ylabel="R (5.1.2)")
        ax.grid(alpha=0.3)
    axes[0].set_title("all trial heights", fontsize=9)
    axes[1].set_title("zoom: the finer steps", fontsize=9)
    axes[0].legend(fontsize=8)
    if title:
        fig.suptitle(title, fontsize=10)
    plt.close(fig)          # shown once, by the notebook cell that returns it
    return fig


def dsm_comparison(X, Y, truth, results, labels, vmax_error: float = 2.0, choice=None, pair_labels=None):
    """§6.2–6.3: the true DSM and each computed DSM on the grid, and below them the error maps
    Z − Z_true (clipped at ± ``vmax_error``; NaN = no confident height, grey). ``choice``: optional
    (ny, nx) int map of the pair chosen per node (−1: none), drawn in the lower-left panel."""
    n = len(results)
    fig, axes = plt.subplots(2, n + 1, figsize=(3.6 * (n + 1), 6.8), constrained_layout=True)
    ext = (X.min(), X.max(), Y.min(), Y.max())
    kw = dict(origin="lower", extent=ext, interpolation="nearest")
    lo, hi = np.nanmin(truth), np.nanmax(truth)
    im = axes[0, 0].imshow(truth, cmap="terrain", vmin=lo, vmax=hi, **kw)
    axes[0, 0].set_title("truth (scene.surface_at)", fontsize=9)
    for k, (Z, lab) in enumerate(zip(results, labels)):
        axes[0, k + 1].imshow(Z, cmap="terrain", vmin=lo, vmax=hi, **kw)
        axes[0, k + 1].set_title(lab, fontsize=9)
    fig.colorbar(im, ax=axes[0, :], shrink=0.8, label="Z, m")
    cmap = plt.get_cmap("RdBu_r").copy()
    cmap.set_bad("0.6")
    for k, (Z, lab) in enumerate(zip(results, labels)):
        err = Z - truth
        gross = np.mean(~(np.abs(err) < 1.0))
        em = axes[1, k + 1].imshow(np.ma.masked_invalid(err), cmap=cmap, vmin=-vmax_error, vmax=vmax_error, **kw)
        axes[1, k + 1].set_title(f"error of {lab}\n|err| > 1 m or none: {100 * gross:.1f} %", fontsize=9)
    fig.colorbar(em, ax=axes[1, 1:], shrink=0.8, label="Z − Z_true, m")
    ax = axes[1, 0]
    if choice is not None:
        m = np.ma.masked_less(choice, 0)
        cm = ax.imshow(m, cmap=plt.get_cmap("tab10", max(int(choice.max()) + 1, 1)), vmin=-0.5,
                       vmax=max(int(choice.max()), 0) + 0.5, **kw)
        cb = fig.colorbar(cm, ax=ax, shrink=0.8, ticks=range(int(choice.max()) + 1))
        if pair_labels is not None:
            cb.ax.set_yticklabels(pair_labels[:int(choice.max()) + 1], fontsize=7)
        ax.set_title("pair chosen per node (best R)", fontsize=9)
    else:
        ax.set_axis_off()
    for a in axes.ravel():
        if a.has_data():
            a.set(xlabel="X, m", ylabel="Y, m")
    plt.close(fig)          # shown once, by the notebook cell that returns it
    return fig
