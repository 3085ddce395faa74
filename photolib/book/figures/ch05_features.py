"""Figures for Chapter 5, §5.5 and §5.7–5.10 (gradients, interest operators, descriptors, RANSAC).

* :func:`fig_5_12` — Fig. 5.12 redrawn: the 8×8 image, the printed Roberts image and the computed
  one, the 39 background cells that differ outlined.
* :func:`sobel_components` — Fig. 5.13-style: G, g_x, g_y of Sobel's operator on an image.
* :func:`detector_responses` — Figs. 5.19/5.22–5.26-style: the responses of Moravec, Harris,
  Förstner, FAST and LoG on one image with their strongest points.
* :func:`descriptor_grid` — Fig. 5.27-style: the 16×16 region turned to the dominant direction,
  its 4×4 cells and the 8-bin histograms drawn as arrows.
* :func:`matches_with_ransac` — Fig. 5.28-style: descriptor matches between an image and a turned
  and shifted copy, RANSAC inliers (a similarity) and outliers.
* :func:`textured_pair` — the synthetic scene of the last two figures (also used by the notebook).

Every figure function returns the matplotlib Figure (closed, so that a notebook shows it once).
"""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np
from scipy import ndimage as ndi

from ... import features as ft
from ...ransac import ransac


def _done(fig):
    plt.close(fig)
    return fig


def fig_5_12(image, printed, computed):
    """Input, printed and computed Roberts images with every cell's value; differing cells outlined."""
    image, printed, computed = (np.asarray(a, float) for a in (image, printed, computed))
    fig, axes = plt.subplots(1, 3, figsize=(11, 3.9))
    for ax, data, title in zip(axes, (image, printed, computed),
                               ("Fig. 5.12a: image", "Fig. 5.12b as printed", "computed |g_x| + |g_y|")):
        ax.imshow(data, cmap="gray", vmin=0, vmax=25)
        for r in range(8):
            for c in range(8):
                ax.text(c, r, f"{data[r, c]:g}", ha="center", va="center", fontsize=8,
                        color="black" if data[r, c] > 12 else "white")
                if ax is not axes[0] and printed[r, c] != computed[r, c]:
                    ax.add_patch(plt.Rectangle((c - 0.5, r - 0.5), 1, 1, fill=False, ec="red", lw=1.2))
        ax.set_title(title, fontsize=10)
        ax.set_xticks([]), ax.set_yticks([])
    fig.suptitle("Roberts gradient (5.5.11) with (5.5.3); red: printed 10, computed 0", fontsize=10)
    fig.tight_layout()
    return _done(fig)


def sobel_components(img):
    """G (5.5.2), g_x and g_y (5.5.6) of Sobel's operator (Fig. 5.13-style)."""
    gx, gy = ft.gradient_sobel(img, border="mirror", normalize=True)
    G = ft.gradient_magnitude(gx, gy)
    fig, axes = plt.subplots(1, 4, figsize=(13, 3.4))
    for ax, data, title, cmap in zip(axes, (img, G, gx, gy), ("image", "G (5.5.2)", "g_x", "g_y (upwards)"),
                                     ("gray", "gray", "RdBu_r", "RdBu_r")):
        lim = np.percentile(np.abs(data), 99)
        kw = {"vmin": -lim, "vmax": lim} if cmap == "RdBu_r" else {}
        ax.imshow(data, cmap=cmap, **kw)
        ax.set_title(title, fontsize=10)
        ax.set_xticks([]), ax.set_yticks([])
    fig.tight_layout()
    return _done(fig)


def detector_responses(img, max_points=60):
    """Responses of the five operators of §5.8 and their strongest points (red crosses)."""
    ops = [("Moravec (5.8.1)", "moravec", {}, ft.moravec(img)),
           ("Harris R (5.8.4)", "harris", {}, ft.harris(img)),
           ("Förstner w, q ≥ 0.5 (5.8.7)", "foerstner", {}, None),
           ("FAST-9 score (5.8.9)", "fast", {"threshold_fast": 20}, ft.fast(img, 20)),
           ("σ²|LoG|, σ = 2 (5.8.13)", "log", {"sigma": 2.0}, 4.0 * np.abs(ft.log_filter(img, 2.0)))]
    w, q = ft.foerstner(img)
    ops[2] = (ops[2][0], ops[2][1], ops[2][2], np.where(q >= 0.5, w, 0.0))
    fig, axes = plt.subplots(2, 5, figsize=(16, 6.5))
    for k, (title, name, opts, R) in enumerate(ops):
        pts = ft.interest_points(img, name, max_points=max_points, **opts)
        axes[0, k].imshow(np.sqrt(np.maximum(R, 0)), cmap="magma")
        axes[0, k].set_title(title, fontsize=9)
        axes[1, k].imshow(img, cmap="gray")
        axes[1, k].plot(pts[:, 0], pts[:, 1], "r+", ms=6, mew=1.2)
        axes[1, k].set_title(f"{len(pts)} strongest points", fontsize=9)
        for ax in axes[:, k]:
            ax.set_xticks([]), ax.set_yticks([])
    fig.tight_layout()
    return _done(fig)


def descriptor_grid(img, point):
    """The turned 16×16 region of a point, its 4×4 cells and the 8-bin histograms (Fig. 5.27-style)."""
    d = ft.sift_descriptors(img, [point])
    th = float(d.orientation[0])
    hist = d.vectors[0].reshape(4, 4, 8)
    x0, y0 = point
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(10, 4.8))
    half = 14
    ax1.imshow(img, cmap="gray")
    ax1.set_xlim(x0 - half, x0 + half)
    ax1.set_ylim(y0 + half, y0 - half)
    c, s = np.cos(th), np.sin(th)
    for t in np.arange(-8, 9, 4):
        for a, b in (((t, -8), (t, 8)), ((-8, t), (8, t))):
            P = np.array([[x0 + c * u - s * v, y0 + s * u + c * v] for u, v in (a, b)])
            ax1.plot(P[:, 0], P[:, 1], "y-", lw=1)
    ax1.arrow(x0, y0, 7 * c, 7 * s, color="r", width=0.25)
    ax1.set_title(f"16×16 region turned to θ = {np.degrees(th):.1f}°", fontsize=10)
    ang = (np.arange(8) + 0.5) * 2 * np.pi / 8
    for i in range(4):
        for j in range(4):
            cx, cy = j + 0.5, i + 0.5
            for b in range(8):
                L = 0.45 * hist[i, j, b] / max(hist.max(), 1e-12)
                ax2.plot([cx, cx + L * np.cos(ang[b])], [cy, cy + L * np.sin(ang[b])], "b-", lw=1.5)
    ax2.set_xlim(0, 4), ax2.set_ylim(4, 0)
    ax2.set_xticks(range(5)), ax2.set_yticks(range(5)), ax2.grid(True)
    ax2.set_aspect("equal")
    ax2.set_title("4×4 cells × 8 directions = 128 features", fontsize=10)
    fig.tight_layout()
    return _done(fig)


def textured_pair(N=240, angle_deg=30.0, shift=(7.3, -4.1), seed=4):
    """A smooth random texture and a copy turned by ``angle_deg`` about the centre and shifted.

    Returns img1, img2 and the true map x₂ = R·x₁ + t as (R, t) in (x, y) = (col, row) coordinates.
    """
    rng = np.random.default_rng(seed)
    base = ndi.gaussian_filter(rng.normal(size=(N, N)), 3.0)
    base = (base - base.min()) / np.ptp(base) * 200 + 20
    a = np.radians(angle_deg)
    R = np.array([[np.cos(a), -np.sin(a)], [np.sin(a), np.cos(a)]])
    c0 = np.full(2, (N - 1) / 2)
    t = np.asarray(shift, dtype=float)
    Y2, X2 = np.mgrid[0:N, 0:N].astype(float)
    P1 = (np.c_[X2.ravel(), Y2.ravel()] - c0 - t) @ R + c0
    img2 = ndi.map_coordinates(base, [P1[:, 1], P1[:, 0]], order=3, mode="reflect").reshape(N, N)
    return base, img2, R, c0 + t - R @ c0


def similarity_fit(sample):
    """x₂ = [[a, −b], [b, a]]·x₁ + (t_x, t_y) by linear least squares from ≥ 2 pairs."""
    p, q = sample
    A = np.zeros((2 * len(p), 4))
    A[0::2] = np.c_[p[:, 0], -p[:, 1], np.ones(len(p)), np.zeros(len(p))]
    A[1::2] = np.c_[p[:, 1], p[:, 0], np.zeros(len(p)), np.ones(len(p))]
    return np.linalg.lstsq(A, q.ravel(), rcond=None)[0]


def similarity_residual(m, d):
    """Distance of each x₂ from the mapped x₁."""
    a, b, tx, ty = m
    p, q = d
    return np.hypot(a * p[:, 0] - b * p[:, 1] + tx - q[:, 0], b * p[:, 0] + a * p[:, 1] + ty - q[:, 1])


def match_pair(img1, img2, max_points=150, threshold=1.5, seed=1):
    """Harris points, descriptors, ratio-test matches and a RANSAC similarity: (p1, p2, matches, result)."""
    p1 = ft.interest_points(img1, "harris", border=20, max_points=max_points)
    p2 = ft.interest_points(img2, "harris", border=20, max_points=max_points)
    m = ft.match_descriptors(ft.sift_descriptors(img1, p1), ft.sift_descriptors(img2, p2))
    res = ransac((p1[m[:, 0]], p2[m[:, 1]]), similarity_fit, similarity_residual, 2, threshold, rng=seed)
    return p1, p2, m, res


def matches_with_ransac(img1, img2, p1, p2, matches, result):
    """Both images side by side, matches as lines: RANSAC inliers green, outliers red (Fig. 5.28-style)."""
    W = img1.shape[1]
    fig, ax = plt.subplots(figsize=(11, 5.2))
    ax.imshow(np.hstack([img1, img2]), cmap="gray")
    for (i, j), good in zip(matches, result.inliers):
        ax.plot([p1[i, 0], p2[j, 0] + W], [p1[i, 1], p2[j, 1]], "-", color="lime" if good else "red",
                lw=0.8 if good else 1.4)
    ax.plot(p1[:, 0], p1[:, 1], "y.", ms=3)
    ax.plot(p2[:, 0] + W, p2[:, 1], "y.", ms=3)
    ax.set_title(f"{len(matches)} ratio-test matches; RANSAC: {result.n_inliers} inliers (green), "
                 f"{len(matches) - result.n_inliers} outliers (red)", fontsize=10)
    ax.set_xticks([]), ax.set_yticks([])
    fig.tight_layout()
    return _done(fig)
