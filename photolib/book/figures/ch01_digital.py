"""Figures for Chapter 1, §1.10–§1.12: pixel systems, magnified pixel, sub-pixel shift, fiducials, scanning."""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.patches import Rectangle

from ... import digital, scanners
from .. import ch01_scanners


def pixel_systems(n_rows: int = 6, n_cols: int = 7, pixel=(4, 3)):
    """Fig. 1.19 redrawn: the raster (left-handed) and photogrammetric (right-handed) pixel systems.

    ``pixel = (i, j)`` is highlighted in both, with i counted in each system's own direction.
    """
    fig, axes = plt.subplots(1, 2, figsize=(10, 4.6))
    i, j = pixel
    for ax, system in zip(axes, ("raster", "photo")):
        for r in range(n_rows):
            for c in range(n_cols):
                ax.add_patch(Rectangle((c, r), 1, 1, fill=False, lw=0.6, color="0.6"))
        jj, ii = np.meshgrid(np.arange(n_cols), np.arange(n_rows))
        x, y = digital.pixel_center(ii.ravel(), jj.ravel())
        ax.plot(x, y, ".", color="C0", ms=4)
        ax.add_patch(Rectangle((j, i), 1, 1, color="C1", alpha=0.35))
        xc, yc = digital.pixel_center(i, j)
        ax.plot(xc, yc, "o", color="C3")
        ax.annotate(f"({xc:g}, {yc:g})", (xc, yc), xytext=(6, 6), textcoords="offset points", color="C3")
        ax.set_xlim(-0.3, n_cols + 0.8)
        ax.set_ylim(-0.3, n_rows + 0.8)
        ax.set_aspect("equal")
        ax.set_xticks(np.arange(n_cols) + 0.5, [str(k) for k in range(n_cols)])
        ax.set_yticks(np.arange(n_rows) + 0.5, [str(k) for k in range(n_rows)])
        ax.set_xlabel("column j  →  x_p")
        ax.set_ylabel("row i  →  y_p")
        if system == "raster":
            ax.invert_yaxis()
            ax.set_title("left-handed (raster): origin top-left, rows from the top")
        else:
            ax.set_title("right-handed (photogrammetric): origin bottom-left")
        ax.plot(0, 0, "ks")
        ax.annotate("$o_c$", (0, 0), xytext=(-14, -14 if system == "photo" else 4), textcoords="offset points")
    fig.suptitle(f"Pixel centres (1.10.1); the pixel i = {i}, j = {j} in both systems")
    fig.tight_layout()
    return fig


def magnified_pixel(i=2, j=1, i_sub=2, j_sub=3, n=5, n_rows=4, n_cols=3):
    """Figs. 1.20/1.21 redrawn: pixel (i, j) shown n× magnified, element a'_{i'j'} marked."""
    fig, ax = plt.subplots(figsize=(5.5, 6.5))
    for r in range(n_rows):
        for c in range(n_cols):
            ax.add_patch(Rectangle((c, r), 1, 1, fill=False, lw=1.4, color="k"))
    for k in range(1, n):
        ax.plot([j + k / n] * 2, [i, i + 1], color="0.6", lw=0.6)
        ax.plot([j, j + 1], [i + k / n] * 2, color="0.6", lw=0.6)
    x, y = digital.subpixel_coordinates(i, j, i_sub, j_sub, n, "corner")
    xc, yc = digital.subpixel_coordinates(i, j, i_sub, j_sub, n, "center")
    ax.add_patch(Rectangle((x - 0.5 / n, y - 0.5 / n), 1 / n, 1 / n, color="C1", alpha=0.6))
    ax.plot(x, y, "o", color="C3")
    ax.annotate(f"a'$_{{{i_sub}{j_sub}}}$\ncorner origin (1.10.2): ({x:g}, {y:g})\n"
                f"centre origin (1.10.5): ({xc:g}, {yc:g})", (x, y), xytext=(0.05, n_rows + 0.15),
                textcoords="data", arrowprops=dict(arrowstyle="->", color="C3"), fontsize=9)
    ax.plot(0, 0, "ks")
    ax.plot(0.5, 0.5, "k^")
    ax.annotate("corner origin", (0, 0), xytext=(4, -14), textcoords="offset points", fontsize=8)
    ax.annotate("centre origin", (0.5, 0.5), xytext=(4, -12), textcoords="offset points", fontsize=8)
    ax.set_xlim(-0.2, n_cols + 0.2)
    ax.set_ylim(-0.4, n_rows + 1.0)
    ax.set_aspect("equal")
    ax.set_xlabel("x_p (pixels of the original image)")
    ax.set_ylabel("y_p")
    ax.set_title(f"pixel i = {i}, j = {j} magnified n = {n}×")
    fig.tight_layout()
    return fig


def gaussian_blob(shape=(15, 15), center=(7.3, 7.9), sigma=1.6, amplitude=220.0, seed=0, noise=2.0):
    """A synthetic grey image: a Gaussian blob at a sub-pixel raster position plus seeded noise."""
    h, w = shape
    yy, xx = np.mgrid[0:h, 0:w] + 0.5
    img = amplitude * np.exp(-((xx - center[0]) ** 2 + (yy - center[1]) ** 2) / (2 * sigma ** 2)) + 20
    return np.clip(img + np.random.default_rng(seed).normal(0, noise, shape), 0, 255)


def subpixel_shift(image, mark, target, steps=(0.0, 1 / 3, 2 / 3, 1.0)):
    """Fig. 1.22 in action: the image moves under a fixed mark in fractions of the offset.

    ``mark`` and ``target`` are raster coordinates (x_p, y_p); panel k shows the fragment
    resampled by :func:`photolib.digital.shift_image` with the shift steps[k]·(target − mark).
    """
    mark, target = np.asarray(mark, float), np.asarray(target, float)
    fig, axes = plt.subplots(1, len(steps), figsize=(3.2 * len(steps), 3.5))
    h, w = image.shape[:2]
    for ax, t in zip(np.atleast_1d(axes), steps):
        d = t * (target - mark) + 0.0          # + 0.0: no "-0.00" in titles
        frag = digital.shift_image(image, d[0], d[1], fill=0.0)
        ax.imshow(frag, cmap="gray", vmin=0, vmax=255, extent=(0, w, h, 0), interpolation="nearest")
        ax.plot(*mark, "+", color="red", ms=16, mew=1.5)
        ax.plot(*(target - d), "x", color="C1", ms=8)
        ax.set_title(f"Δ = ({d[0]:+.2f}, {d[1]:+.2f}) px", fontsize=9)
        ax.set_xticks([])
        ax.set_yticks([])
    fig.suptitle("moving image, fixed mark (red +); orange x: the point m in the fragment")
    fig.tight_layout()
    return fig


def fiducial_systems(measured, params, Lx, Ly, exaggerate=20.0):
    """Figs. 1.24/1.25 redrawn: scanner system, fiducials 1–4, image axes at (a0, b0) turned by φ.

    The rotation is drawn ``exaggerate`` times larger than it is (a real φ of 0.5° is invisible).
    """
    p = params
    fig, ax = plt.subplots(figsize=(6.2, 6.2))
    pts = np.asarray(measured, float)
    lo = pts.min(axis=0) - 25
    ax.annotate("", xy=(lo[0] + 250, lo[1]), xytext=lo, arrowprops=dict(arrowstyle="->"))
    ax.annotate("", xy=(lo[0], lo[1] + 250), xytext=lo, arrowprops=dict(arrowstyle="->"))
    ax.text(lo[0] + 252, lo[1], "$\\bar x\\ (x_c)$")
    ax.text(lo[0], lo[1] + 253, "$\\bar y\\ (y_c)$")
    ax.text(lo[0] - 8, lo[1] - 10, "$o_c$")
    phi = p.phi * exaggerate
    o = np.array([p.a0, p.b0])
    ex, ey = np.array([np.cos(phi), np.sin(phi)]), np.array([-np.sin(phi), np.cos(phi)])
    # the marks are drawn on the (exaggerated) image axes at their measured distances from o'
    r = np.hypot(*(pts - o).T)
    show = np.array([o - r[0] * ex, o + r[1] * ex, o + r[2] * ey, o - r[3] * ey])
    for k, (x, y) in enumerate(show, 1):
        ax.plot(x, y, "k+", ms=12, mew=1.5)
        ax.annotate(str(k), (x, y), xytext=(6, 6), textcoords="offset points")
    ax.plot(*show[:2].T, "C0--", lw=0.8)
    ax.plot(*show[2:].T, "C0--", lw=0.8)
    for e, lab in ((ex, "x"), (ey, "y")):
        ax.annotate("", xy=o + 125 * e, xytext=o, arrowprops=dict(arrowstyle="->", color="C3"))
        ax.text(*(o + 130 * e), lab, color="C3")
    ax.plot(*o, "o", color="C3")
    ax.annotate(f"o' = (a0, b0) = ({p.a0:.3f}, {p.b0:.3f})", o, xytext=(8, -16), textcoords="offset points",
                color="C3", fontsize=8)
    arc = np.linspace(0, phi, 20)
    ax.plot(o[0] + 60 * np.cos(arc), o[1] + 60 * np.sin(arc), "C2")
    ax.text(o[0] + 64, o[1] + 2, f"φ = {np.degrees(p.phi):.3f}°", color="C2", fontsize=9)
    ax.annotate("", xy=show[1] + 12 * ey, xytext=show[0] + 12 * ey, arrowprops=dict(arrowstyle="<->", color="C4"))
    ax.text(*(o + 18 * ey - 40 * ex), f"$L_x$ = {Lx:g} mm", color="C4", fontsize=9)
    ax.annotate("", xy=show[2] - 12 * ex, xytext=show[3] - 12 * ex, arrowprops=dict(arrowstyle="<->", color="C4"))
    ax.text(*(o - 60 * ex - 50 * ey), f"$L_y$ = {Ly:g} mm", color="C4", fontsize=9, rotation=90)
    ax.set_aspect("equal")
    ax.set_xlim(lo[0] - 15, lo[0] + 275)
    ax.set_ylim(lo[1] - 15, lo[1] + 275)
    ax.set_title(f"fiducial and measuring systems (rotation drawn ×{exaggerate:g})", fontsize=10)
    fig.tight_layout()
    return fig


def scan_layouts(frame_mm=(230.0, 230.0)):
    """Figs. 1.27/1.28 redrawn for Table 1.1: swaths (line sensors) or tiles (area sensor)."""
    table = ch01_scanners.table_1_1()
    fig, axes = plt.subplots(1, len(table), figsize=(3.3 * len(table), 3.8))
    for ax, s in zip(axes, table):
        for k, (x, y, w, h) in enumerate(scanners.scan_layout(s, frame_mm)):
            ax.add_patch(Rectangle((x, y), w, h, facecolor=f"C{k % 2}", alpha=0.35, edgecolor="k", lw=0.4))
        if s["sensor_kind"] == "lines":
            ax.annotate("", xy=(10, frame_mm[1] - 10), xytext=(10, 10),
                        arrowprops=dict(arrowstyle="->", color="C3"))
        ax.set_xlim(0, frame_mm[0])
        ax.set_ylim(0, frame_mm[1])
        ax.set_aspect("equal")
        f = scanners.derived_figures(s, frame_mm)
        what = f"{f['swaths']} swaths" if "swaths" in f else f"{f['tiles']} tiles"
        ax.set_title(f"{s['name']}\n{what}", fontsize=9)
        ax.set_xlabel("x, mm")
    axes[0].set_ylabel("y, mm")
    fig.suptitle(f"covering a {frame_mm[0]:g}×{frame_mm[1]:g} mm frame (derived by us, not in the book)")
    fig.tight_layout()
    return fig
