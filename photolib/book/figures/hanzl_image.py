"""Figures for Hanzl §6 and §8 (Appendix F.6): image motion, flight-plan footprints, Förstner points on a
synthetic image and the §8.2 filter examples as small heat maps.

Every function returns a matplotlib Figure, closed before it is returned (a notebook cell shows it once).
"""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np

from ...planning import PhotoFlightPlan, image_motion


def image_motion_figure(speeds_kmh=(150.0, 180.0, 250.0), scale_number: float = 10000.0,
                        book_point=(1 / 200, 25.0)):
    """Theoretical image motion s = v t / m_s (µm) against the exposure time, one line per speed;
    the effective (≈ half) smear dashed; the book's example marked."""
    t = np.linspace(1 / 1000, 1 / 50, 200)
    fig, ax = plt.subplots(figsize=(6.4, 3.6))
    for v in speeds_kmh:
        s = np.array([image_motion(v / 3.6, ti, scale_number) for ti in t]) * 1e6
        line, = ax.plot(t * 1000, s, label=f"v = {v:g} km/h")
        ax.plot(t * 1000, s / 2, "--", color=line.get_color(), lw=0.8)
    ax.plot(book_point[0] * 1000, book_point[1], "ko", label="Hanzl: 180 km/h, 1/200 s → 25 µm")
    ax.set_xlabel("exposure time t (ms)")
    ax.set_ylabel("image motion (µm)")
    ax.set_title(f"Image motion at 1 : {scale_number:,.0f} (dashed: effective ≈ half)")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    plt.close(fig)
    return fig


def flight_plan_figure(plan: PhotoFlightPlan, strips: int = 2, images: int = 4):
    """Footprints (s·m_s squares) of ``strips`` × ``images`` vertical images with base B and strip
    spacing A, in metres; the forward and side overlaps are visible as darker areas."""
    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    L = plan.footprint
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for j in range(strips):
        for i in range(images):
            x, y = i * plan.base, j * plan.strip_spacing
            ax.add_patch(plt.Rectangle((x - L / 2, y - L / 2), L, L, fc=colours[j % len(colours)], alpha=0.12,
                                       ec=colours[j % len(colours)], lw=1.0))
            ax.plot(x, y, "k+", ms=6)
    ax.annotate("", xy=(plan.base, -L / 2 - 150), xytext=(0, -L / 2 - 150), arrowprops=dict(arrowstyle="<->"))
    ax.text(plan.base / 2, -L / 2 - 120, f"B = {plan.base:.0f} m", ha="center", va="bottom", fontsize=8)
    xa = (images - 1) * plan.base + L / 2 + 150
    ax.annotate("", xy=(xa, plan.strip_spacing), xytext=(xa, 0), arrowprops=dict(arrowstyle="<->"))
    ax.text(xa + 60, plan.strip_spacing / 2, f"A = {plan.strip_spacing:.0f} m", rotation=90, va="center", fontsize=8)
    ax.set_xlim(-L / 2 - 300, xa + 400)
    ax.set_ylim(-L / 2 - 400, (strips - 1) * plan.strip_spacing + L / 2 + 200)
    ax.set_aspect("equal")
    ax.set_xlabel("X along the strips (m)")
    ax.set_ylabel("Y across (m)")
    ax.set_title(f"Footprints {L:.0f} m, h = {plan.flying_height:.0f} m, B/h = {plan.base_height_ratio:.2f}")
    plt.close(fig)
    return fig


def foerstner_figure(img, points, size_map=None):
    """A synthetic image with the points chosen by Hanzl's Förstner rule, and (optionally) the map of
    the size w = tr N/det N (log scale; white where det N = 0)."""
    panels = 2 if size_map is not None else 1
    fig, axes = plt.subplots(1, panels, figsize=(4.0 * panels, 4.0))
    axes = np.atleast_1d(axes)
    axes[0].imshow(img, cmap="gray")
    pts = np.asarray(points, float).reshape(-1, 2)
    axes[0].plot(pts[:, 0], pts[:, 1], "o", mfc="none", mec="red", ms=9, mew=1.5)
    axes[0].set_title(f"{len(pts)} points: w < 0.3·w_med, q > 0.75")
    if size_map is not None:
        m = np.where(np.isfinite(size_map), size_map, np.nan)
        im = axes[1].imshow(np.log10(m), cmap="viridis")
        fig.colorbar(im, ax=axes[1], fraction=0.046, label="log₁₀ w")
        axes[1].set_title("size of the error ellipse w = tr N / det N")
    for ax in axes:
        ax.set_xticks([])
        ax.set_yticks([])
    fig.tight_layout()
    plt.close(fig)
    return fig


def filter_examples_figure(examples):
    """Heat maps of small matrices with their values written in: ``examples`` is a list of
    (title, matrix) pairs, drawn in a grid of at most four columns; cells that differ from a
    printed matrix can be outlined by passing (title, matrix, mask)."""
    n = len(examples)
    cols = min(4, n)
    rows = int(np.ceil(n / cols))
    fig, axes = plt.subplots(rows, cols, figsize=(2.4 * cols, 2.5 * rows))
    axes = np.atleast_1d(axes).ravel()
    for ax, ex in zip(axes, examples):
        title, M = ex[0], np.asarray(ex[1], float)
        ax.imshow(M, cmap="coolwarm" if M.min() < 0 else "Greys", vmin=M.min(), vmax=M.max() if M.max() > M.min()
                  else M.min() + 1)
        for (r, c), v in np.ndenumerate(M):
            ax.text(c, r, f"{v:g}", ha="center", va="center", fontsize=8,
                    color="black" if M.max() == M.min() or (v - M.min()) / (M.max() - M.min()) < 0.6 or M.min() < 0
                    else "white")
        if len(ex) > 2:
            for r, c in zip(*np.nonzero(ex[2])):
                ax.add_patch(plt.Rectangle((c - 0.5, r - 0.5), 1, 1, fill=False, ec="red", lw=2))
        ax.set_title(title, fontsize=8)
        ax.set_xticks([])
        ax.set_yticks([])
    for ax in axes[n:]:
        ax.axis("off")
    fig.tight_layout()
    plt.close(fig)
    return fig
