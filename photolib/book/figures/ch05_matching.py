"""Figures for Chapter 5, §5.1–5.4 and §5.11: correlation surfaces and peak sharpness, the
least-squares-matching iteration on its window, and target fits (centroid, robust circle fit,
Kadnichansky cross).

Every function takes already computed library results (:mod:`photolib.matching`,
:mod:`photolib.targets`) plus the images, and returns the matplotlib figure.
"""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np
from scipy import ndimage as ndi

__all__ = ["correlation_surfaces", "lsm_iterations", "lsm_window_residuals", "target_fits"]


def correlation_surfaces(cases, half_window: int):
    """One row per case: the search area with the template outline, the correlation surface R
    (5.1.2), and the profiles of R through the maximum along x and y (Fig. 5.5: sharp vs flat).

    ``cases``: list of ``(title, search_image, MatchResult)`` where the match was computed with
    :func:`photolib.matching.match_point` (``surface``, ``origin``, ``r_max``, ``sharpness``,
    ``confident`` and ``reason`` are shown).
    """
    n = len(cases)
    fig, axes = plt.subplots(n, 3, figsize=(11, 3.3 * n), constrained_layout=True, squeeze=False)
    h = half_window
    for row, (title, image, m) in zip(axes, cases):
        a0, a1, a2 = row
        R = m.surface
        x0, y0 = m.origin
        a0.imshow(image, cmap="gray")
        ix, iy = m.integer
        a0.add_patch(plt.Rectangle((ix - h - 0.5, iy - h - 0.5), 2 * h + 1, 2 * h + 1, fill=False, ec="C1", lw=1.5))
        a0.add_patch(plt.Rectangle((x0 - h - 0.5, y0 - h - 0.5), R.shape[1] + 2 * h, R.shape[0] + 2 * h,
                                   fill=False, ec="C0", lw=1, ls="--"))
        a0.set_title(f"{title}\nsearch area (dashed), best window (orange)", fontsize=9)
        a0.set_axis_off()
        im = a1.imshow(R, cmap="viridis", vmin=-1, vmax=1, extent=(x0 - 0.5, x0 + R.shape[1] - 0.5,
                                                                  y0 + R.shape[0] - 0.5, y0 - 0.5))
        a1.plot(m.x, m.y, "r+", ms=12, mew=2)
        a1.set_title(f"R (5.1.2): R_max = {m.r_max:.3f}", fontsize=9)
        fig.colorbar(im, ax=a1, shrink=0.8)
        i, j = iy - y0, ix - x0
        xs = np.arange(R.shape[1]) - j
        ys = np.arange(R.shape[0]) - i
        a2.plot(xs, R[i, :], "o-", ms=3, label="along x")
        a2.plot(ys, R[:, j], "s-", ms=3, label="along y")
        a2.axvline(0, color="0.7", lw=0.5)
        sharp = "nan" if not np.isfinite(m.sharpness) else f"{m.sharpness:.3f}"
        verdict = "confident" if m.confident else "NOT confident: " + m.reason.split(":")[0]
        a2.set_title(f"sharpness −d²R/dx² = {sharp} /px²\n{verdict}", fontsize=9)
        a2.set(xlabel="offset from the maximum, px", ylabel="R", ylim=(-1.05, 1.05))
        a2.legend(fontsize=8, loc="lower left")
    plt.close(fig)          # shown once, by the notebook cell that returns it
    return fig


def lsm_window_residuals(left, right, point, params, half_window: int):
    """The residual image k₀ + k₁f₁ − f₂(b₁u + b₂v − p, c₁u + c₂v − q) of (5.4.5) over the window
    for a parameter dict (missing unknowns take their identity values); bilinear resampling."""
    full = {"p": 0.0, "q": 0.0, "b1": 1.0, "b2": 0.0, "c1": 0.0, "c2": 1.0, "k0": 0.0, "k1": 1.0}
    full.update(params)
    x1, y1 = point
    h = half_window
    v, u = np.mgrid[-h:h + 1, -h:h + 1].astype(float)
    X = x1 + full["b1"] * u + full["b2"] * v - full["p"]
    Y = y1 + full["c1"] * u + full["c2"] * v - full["q"]
    f1 = np.asarray(left, float)[y1 - h:y1 + h + 1, x1 - h:x1 + h + 1]
    f2 = ndi.map_coordinates(np.asarray(right, float), [Y, X], order=1)
    return full["k0"] + full["k1"] * f1 - f2


def lsm_iterations(left, right, point, result, half_window: int, truth=None, title: str = ""):
    """The LSM iteration on its window: the unknowns per step (with the true values dashed), the
    r.m.s. grey residual per step, and the residual image before the first and after the last step.

    ``result`` is an :class:`~photolib.matching.LSMResult` (``history`` of IterationRecord,
    ``params``); ``truth`` an optional dict of true values by name.
    """
    names = list(result.params)
    steps = [np.asarray(r.x, float) for r in result.history] + [np.array([result.params[n] for n in names])]
    steps = np.array(steps)
    k = np.arange(len(steps))
    groups = [("shift", [n for n in names if n in ("p", "q")]),
              ("affine", [n for n in names if n[0] in "bc"]),
              ("radiometry", [n for n in names if n[0] == "k"])]
    groups = [g for g in groups if g[1]]
    fig = plt.figure(figsize=(13, 6.4), constrained_layout=True)
    top, bottom = fig.subfigures(2, 1)
    tops = top.subplots(1, len(groups) + 2)
    for ax, (label, group) in zip(tops, groups):
        handles = []
        for idx, n in enumerate(group):
            j = names.index(n)
            # k0 and k1 differ in scale by orders of magnitude: k1 on its own (right) axis
            a = ax.twinx() if (label == "radiometry" and idx == 1) else ax
            handles += a.plot(k, steps[:, j], "o-", color=f"C{idx}", ms=4, label=n)
            if truth and n in truth:
                a.axhline(truth[n], color=f"C{idx}", ls="--", lw=0.8)
        ax.set_xlabel("iteration")
        ax.set_title(label + (" (dashed: true)" if truth else ""), fontsize=9)
        ax.legend(handles=handles, fontsize=8)
    ax = tops[len(groups)]
    m = (2 * half_window + 1) ** 2
    rms = [np.sqrt(r.vtpv / m) for r in result.history]
    ax.semilogy(k[:-1] + 1, rms, "o-", ms=4)
    ax.set_xlabel("iteration")
    ax.set_title("r.m.s. grey residual √(VᵀV/n)", fontsize=9)
    ax = tops[len(groups) + 1]
    shift_idx = [names.index(n) for n in ("p", "q")]
    step = [max(float(np.max(np.abs(np.asarray(r.delta, float)[shift_idx]))), 1e-12) for r in result.history]
    ax.semilogy(k[:-1] + 1, step, "o-", ms=4, color="C3")
    ax.set_xlabel("iteration")
    ax.set_title("max(|δp|, |δq|), px", fontsize=9)
    axs = bottom.subplots(1, 4)
    before = lsm_window_residuals(left, right, point, dict(zip(names, steps[0])), half_window)
    after = lsm_window_residuals(left, right, point, result.params, half_window)
    lim = float(np.max(np.abs(before)))
    h = half_window
    f1 = np.asarray(left, float)[point[1] - h:point[1] + h + 1, point[0] - h:point[0] + h + 1]
    for ax, (img, ttl, kw) in zip(axs, ((f1, "template f₁", {"cmap": "gray"}),
                                          (before, f"residual at the start (r.m.s. {np.sqrt(np.mean(before**2)):.2f})",
                                           {"cmap": "RdBu_r", "vmin": -lim, "vmax": lim}),
                                          (after, f"residual after step {result.iterations} "
                                           f"(r.m.s. {np.sqrt(np.mean(after**2)):.2f})",
                                           {"cmap": "RdBu_r", "vmin": -lim, "vmax": lim}))):
        im = ax.imshow(img, **kw)
        ax.set_title(ttl, fontsize=9)
        ax.set_axis_off()
        if ax is not axs[0]:
            bottom.colorbar(im, ax=ax, shrink=0.8)
    ax = axs[3]
    ax.axis("off")
    lines = [f"{n} = {result.params[n]:+.4f}" for n in names]
    lines += [f"m_p = {result.sigma_p:.4f} px", f"m_q = {result.sigma_q:.4f} px", f"μ = {result.sigma0:.3f}"]
    ax.text(0, 1, "\n".join(lines), va="top", family="monospace", fontsize=9)
    if title:
        fig.suptitle(title)
    plt.close(fig)          # shown once, by the notebook cell that returns it
    return fig


def target_fits(disc, disc_truth, centroid_xy, circle, plain_circle, cross, cross_truth, cross_fit):
    """Three panels: (a) a round target with glare — truth, centroid (5.11.1), circle fitted without
    and with the robust weight (5.11.6); (b) its edge pixels coloured by their final weight P′·P″;
    (c) a Kadnichansky cross with its sub-pixel edge points, the two fitted lines and their
    intersection. Positions are (x, y) = (col, row)."""
    fig, axes = plt.subplots(1, 3, figsize=(14, 4.8), constrained_layout=True)
    a0, a1, a2 = axes
    t = np.linspace(0, 2 * np.pi, 200)
    a0.imshow(disc, cmap="gray")
    xc, yc, R = disc_truth
    a0.plot(xc + R * np.cos(t), yc + R * np.sin(t), "g-", lw=1, label="true circle")
    a0.plot(xc, yc, "g+", ms=14, mew=2, label="true centre")
    a0.plot(*centroid_xy, "yx", ms=10, mew=2,
            label=f"centroid (5.11.1): {np.hypot(centroid_xy[0] - xc, centroid_xy[1] - yc):.2f} px off")
    a0.plot(plain_circle.x + plain_circle.radius * np.cos(t), plain_circle.y + plain_circle.radius * np.sin(t),
            "C1--", lw=1, label=f"circle, P′ only: {np.hypot(plain_circle.x - xc, plain_circle.y - yc):.2f} px off")
    a0.plot(circle.x + circle.radius * np.cos(t), circle.y + circle.radius * np.sin(t), "C3-", lw=1,
            label=f"circle, P′·P″ (5.11.6): {np.hypot(circle.x - xc, circle.y - yc):.3f} px off")
    pad = R + 6
    a0.set(xlim=(xc - pad, xc + pad), ylim=(yc + pad, yc - pad), title="round target with glare")
    a0.legend(fontsize=7, loc="lower left")
    pts, w = circle.edge_points, circle.weights
    a1.imshow(disc, cmap="gray", alpha=0.35)
    sc = a1.scatter(pts[:, 0], pts[:, 1], c=w, cmap="plasma", s=14, vmin=0, vmax=1)
    a1.plot(circle.x + circle.radius * np.cos(t), circle.y + circle.radius * np.sin(t), "C3-", lw=1)
    fig.colorbar(sc, ax=a1, shrink=0.8, label="final weight P′·P″")
    a1.set(xlim=(xc - pad, xc + pad), ylim=(yc + pad, yc - pad),
           title=f"edge pixels and weights ({circle.iterations} iterations)")
    a2.imshow(cross, cmap="gray")
    cx, cy = cross_truth
    A, B = cross_fit.points_a, cross_fit.points_b
    a2.plot(A[:, 0], A[:, 1], "C0.", ms=6, label="edge points, line A")
    a2.plot(B[:, 0], B[:, 1], "C1.", ms=6, label="edge points, line B")
    s = np.linspace(-12, 12, 2)
    PA, QA = cross_fit.line_a
    PB, QB = cross_fit.line_b
    a2.plot(cx + s, PA * (cx + s) + QA, "C0-", lw=1)
    a2.plot(PB * (cy + s) + QB, cy + s, "C1-", lw=1)
    a2.plot(cx, cy, "g+", ms=14, mew=2, label="true centre")
    a2.plot(cross_fit.x, cross_fit.y, "rx", ms=10, mew=2,
            label=f"intersection: {np.hypot(cross_fit.x - cx, cross_fit.y - cy):.3f} px off")
    a2.set(xlim=(cx - 14, cx + 14), ylim=(cy + 14, cy - 14), title="Kadnichansky cross target")
    a2.legend(fontsize=7, loc="lower left")
    plt.close(fig)          # shown once, by the notebook cell that returns it
    return fig
