"""Figures for Chapter 5, §5.6 (narrowing the search): the image pyramid, coarse-to-fine matching
through it, the epipolar line of a point (with the book's (5.6.2) as printed against the corrected
form), a pair before and after resampling to the normal case, and the intersection of two epipolar
lines on a third image.

Every function takes already computed library results (:mod:`photolib.epipolar`) plus the images
and returns the matplotlib figure. Lines a·x + b·y + c = 0 are in image millimetres (x right, y up,
origin at the frame centre, :func:`photolib.synthetic.pixel_to_image`); the functions convert them
to pixels of ``img[row, col]`` for drawing.
"""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np

from ...synthetic import image_to_pixel

__all__ = ["pyramid_levels", "coarse_to_fine", "epipolar_geometry", "rectification", "three_images"]


def line_in_frame(line, shape, pixel_size: float, n: int = 200) -> np.ndarray:
    """Pixel positions (col, row) of the part of the line a·x + b·y + c = 0 (mm) inside the frame."""
    a, b, c = np.asarray(line, dtype=float)
    rows, cols = shape
    hx, hy = (cols - 1) / 2 * pixel_size, (rows - 1) / 2 * pixel_size
    if abs(b) >= abs(a):
        x = np.linspace(-hx, hx, n)
        y = -(a * x + c) / b
    else:
        y = np.linspace(-hy, hy, n)
        x = -(b * y + c) / a
    keep = (np.abs(x) <= hx + 1e-9) & (np.abs(y) <= hy + 1e-9)
    return image_to_pixel(np.column_stack([x[keep], y[keep]]), shape, pixel_size)


def _show(ax, img, title):
    ax.imshow(img, cmap="gray", vmin=0, vmax=1)
    ax.set_title(title, fontsize=9)
    ax.set_xlim(-0.5, img.shape[1] - 0.5)
    ax.set_ylim(img.shape[0] - 0.5, -0.5)
    ax.set_xticks([])
    ax.set_yticks([])


def pyramid_levels(levels, title: str = "Image pyramid (Fig. 5.15): each level averages 2×2 pixels"):
    """The levels of :func:`photolib.epipolar.pyramid` side by side, all drawn over the same frame
    (so that a coarse pixel covers 2^k original pixels), with their sizes."""
    n = len(levels)
    fig, axes = plt.subplots(1, n, figsize=(2.9 * n, 3.2), constrained_layout=True)
    rows, cols = levels[0].shape
    for k, (ax, img) in enumerate(zip(np.atleast_1d(axes), levels)):
        ax.imshow(img, cmap="gray", vmin=0, vmax=1, extent=(-0.5, cols - 0.5, rows - 0.5, -0.5),
                  interpolation="nearest")
        ax.set_title(f"level {k}: {img.shape[0]} × {img.shape[1]} px", fontsize=9)
        ax.set_xticks([])
        ax.set_yticks([])
    fig.suptitle(title, fontsize=10)
    plt.close(fig)          # shown once, by the notebook cell that returns it
    return fig


def coarse_to_fine(pyr_right, point, approx, match, search_radius: int, refine_radius: int,
                   half_window: int, truth=None):
    """Coarse-to-fine search (§5.6): on every level of image 2 (coarsest first) the predicted
    position, the search area (± ``search_radius`` px on the top level, ± ``refine_radius`` below)
    and the integer match found there (``match.trace`` of :func:`photolib.epipolar.match_coarse_to_fine`).

    The predictions follow the library's rule: a pixel c of level k has its centre at 2c + 0.5 of
    level k − 1; the top level starts from ``approx``, a lower level from the point of image 1 on
    that level moved by twice the parallax found above.
    """
    trace = match.trace
    levels = len(trace) - 1
    pt = np.asarray(point, dtype=float)
    fig, axes = plt.subplots(1, levels + 1, figsize=(3.1 * (levels + 1), 3.6), constrained_layout=True)
    s = 2 ** levels
    guess = np.rint((np.asarray(approx, dtype=float) - 0.5 * (s - 1)) / s)
    for ax, (lev, xi, yi, r) in zip(np.atleast_1d(axes), trace):
        img = pyr_right[lev]
        radius = search_radius if lev == levels else refine_radius
        _show(ax, img, f"level {lev} ({img.shape[0]}×{img.shape[1]}): ±{radius} px\nmatch ({xi:.1f}, {yi:.1f}), "
                       f"R = {r:.3f}")
        ax.add_patch(plt.Rectangle((guess[0] - radius - half_window - 0.5, guess[1] - radius - half_window - 0.5),
                                   2 * (radius + half_window) + 1, 2 * (radius + half_window) + 1,
                                   fill=False, ec="C0", lw=1.2, ls="--"))
        ax.plot(guess[0], guess[1], "o", mfc="none", mec="C0", ms=7)
        ax.plot(xi, yi, "+", color="C3", ms=11, mew=2)
        if truth is not None:
            t = (np.asarray(truth, dtype=float) - 0.5 * (2 ** lev - 1)) / 2 ** lev
            ax.plot(t[0], t[1], "x", color="C2", ms=7, mew=1.5)
        pad = max(3 * (radius + half_window), 12)
        ax.set_xlim(max(-0.5, guess[0] - pad), min(img.shape[1] - 0.5, guess[0] + pad))
        ax.set_ylim(min(img.shape[0] - 0.5, guess[1] + pad), max(-0.5, guess[1] - pad))
        if lev > 0:
            p_l = np.rint((pt - 0.5 * (2 ** lev - 1)) / 2 ** lev)
            p_next = np.rint((pt - 0.5 * (2 ** (lev - 1) - 1)) / 2 ** (lev - 1))
            guess = np.rint(p_next + 2.0 * (np.array([xi, yi]) - p_l))
    fig.suptitle("Coarse-to-fine: prediction (circle), search area with windows (dashed), match (+)"
                 + (", truth (x)" if truth is not None else ""), fontsize=10)
    plt.close(fig)          # shown once, by the notebook cell that returns it
    return fig


def epipolar_geometry(left, right, pixel_size: float, points1, lines, points2, xc, y_corrected, y_printed,
                      point2_mm, title: str = ""):
    """The epipolar geometry of a pair in three panels.

    * image 1 with its points (``points1``, pixels);
    * image 2 with the epipolar lines of those points (``lines`` (n, 3), mm, from
      :func:`photolib.epipolar.epipolar_line`) and the true matches (``points2``, pixels);
    * one point in the relative-orientation system: y_c(x_c) by the corrected (5.6.2) and as
      printed, against its true image on image 2 (``point2_mm``).
    """
    fig, axes = plt.subplots(1, 3, figsize=(13, 4.3), constrained_layout=True)
    _show(axes[0], left, "image 1: points m₁")
    _show(axes[1], right, "image 2: epipolar lines and true m₂")
    for k, (p1, line, p2) in enumerate(zip(points1, lines, points2)):
        col = f"C{k % 10}"
        axes[0].plot(*p1, "o", color=col, ms=6, mec="w")
        seg = line_in_frame(line, right.shape, pixel_size)
        axes[1].plot(seg[:, 0], seg[:, 1], "-", color=col, lw=1.3)
        axes[1].plot(*p2, "o", color=col, ms=6, mec="w")
    ax = axes[2]
    ax.plot(xc, y_corrected, "-", color="C0", lw=2, label="(5.6.2) corrected")
    ax.plot(xc, y_printed, "--", color="C3", lw=2, label="(5.6.2) as printed")
    ax.plot(*point2_mm, "ko", ms=7, label="true m₂ (projection)")
    ax.axhline(0, color="0.7", lw=0.5)
    ax.set(xlabel="x_c", ylabel="y_c", title="relative-orientation system: y_c(x_c)")
    ax.legend(fontsize=8)
    if title:
        fig.suptitle(title, fontsize=10)
    plt.close(fig)          # shown once, by the notebook cell that returns it
    return fig


def rectification(before, after, points_before, points_after, title: str = ""):
    """A pair before and after resampling to the normal case (:func:`photolib.epipolar.rectify_pair`).

    ``before``/``after`` are (image 1, image 2); ``points_before``/``points_after`` are the
    (n, 2) pixel positions (col, row) of the same object points on (image 1, image 2). A horizontal
    line through each point of image 1 is drawn on both images: after resampling it passes
    through the match on image 2 (zero y-parallax).
    """
    fig, axes = plt.subplots(2, 2, figsize=(9, 9), constrained_layout=True)
    for r, (imgs, pts, label) in enumerate(((before, points_before, "original"), (after, points_after, "rectified"))):
        q = np.abs(pts[0][:, 1] - pts[1][:, 1])
        for c in range(2):
            ax = axes[r, c]
            _show(ax, imgs[c], f"{label} image {c + 1}" + (f": |Δrow| up to {q.max():.1f} px" if c == 1 else ""))
            for k, (p, p_ref) in enumerate(zip(pts[c], pts[0])):
                col = f"C{k % 10}"
                ax.axhline(p_ref[1], color=col, lw=0.8, alpha=0.8)
                ax.plot(*p, "o", color=col, ms=5, mec="w")
    if title:
        fig.suptitle(title, fontsize=10)
    plt.close(fig)          # shown once, by the notebook cell that returns it
    return fig


def three_images(images, pixel_size: float, points, lines13, lines23, intersection):
    """Fig. 5.18: the point of image 3 as the intersection of the epipolar lines of m₁ and m₂.

    ``images``: three images; ``points``: (m₁, m₂, m₃) pixel positions, each (n, 2);
    ``lines13``/``lines23``: (n, 3) lines on image 3 (mm); ``intersection``: (n, 2) pixel positions
    from :func:`photolib.epipolar.epipolar_intersection`.
    """
    fig, axes = plt.subplots(1, 3, figsize=(12, 4.2), constrained_layout=True)
    for i, ax in enumerate(axes):
        _show(ax, images[i], f"image {i + 1}" + (": lines of m₁ (solid), m₂ (dashed)" if i == 2 else ""))
    for k in range(len(points[0])):
        col = f"C{k % 10}"
        for i in range(2):
            axes[i].plot(*points[i][k], "o", color=col, ms=6, mec="w")
        for line, ls in ((lines13[k], "-"), (lines23[k], "--")):
            seg = line_in_frame(line, images[2].shape, pixel_size)
            axes[2].plot(seg[:, 0], seg[:, 1], ls, color=col, lw=1.2)
        axes[2].plot(*intersection[k], "o", mfc="none", mec=col, ms=10, mew=1.5)
        axes[2].plot(*points[2][k], "+", color="k", ms=8)
    fig.suptitle("Three images (Fig. 5.18): intersection of two epipolar lines (circle) vs the true m₃ (+)",
                 fontsize=10)
    plt.close(fig)          # shown once, by the notebook cell that returns it
    return fig
