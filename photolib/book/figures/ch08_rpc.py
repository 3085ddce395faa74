"""Figures for Chapter 8, §8.5–8.8 and §8.18 (RPC models).

* :func:`grid_on_planes` — Fig. 8.15 redrawn: the terrain-independent grid of §8.6, image grid
  nodes intersected with several height planes by a synthetic pushbroom.
* :func:`error_vs_planes` — the RPC fit against the number of height planes: the largest image
  error on the planes and between them (log scale), with the numerical rank of the fit.
* :func:`table_8_2_bars` — Table 8.2 (real Resurs-P data, as printed) beside the seeded
  simulation of :func:`photolib.book.ch08_rpc.table_8_2_simulation` (labelled as such).
* :func:`kanopus_layout` — Fig. 8.40/8.42 redrawn: six micro-frames in two staggered rows placed
  in the conventional frame.

Every figure function returns the matplotlib Figure (closed, so that a notebook shows it once)
together with the numbers it shows, rounded.
"""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np

from ... import rpc as rpcmod
from .. import ch08_rpc


def _done(fig):
    plt.close(fig)
    return fig


def grid_on_planes(lines=3000, columns=4000, step=500, heights=(0.0, 500.0, 1000.0, 1500.0, 2000.0)):
    """The §8.6 grid of a small tilted pushbroom on ``heights``: returns (fig, points per plane)."""
    from ...pushbroom import EOPolynomial, Pushbroom
    eo = EOPolynomial([0.0, 0.0, 475e3, 0.08, 0.03, 0.02], [7000.0, 30.0, -5.0, 2e-5, -1e-5, 3e-5])
    sensor = Pushbroom(3.8, 8e-6, columns, 1 / 7000, eo, n_rows=lines)
    r, c, X, Y, Z = rpcmod.rpc_grid(sensor.ground, (lines, columns), heights, step=step)
    fig = plt.figure(figsize=(7, 5))
    ax = fig.add_subplot(projection="3d")
    colours = plt.cm.viridis(np.linspace(0, 0.9, len(heights)))
    for h, col in zip(heights, colours):
        m = Z == h
        ax.scatter((X[m] - X.mean()) / 1000, (Y[m] - Y.mean()) / 1000, Z[m], s=6, color=col, label=f"Z = {h:.0f} m")
    corner = (r == 0) & (c == 0)
    ax.plot((X[corner] - X.mean()) / 1000, (Y[corner] - Y.mean()) / 1000, Z[corner], "k-", lw=1,
            label="one image node on all planes")
    ax.set_xlabel("X, km")
    ax.set_ylabel("Y, km")
    ax.set_zlabel("Z, m")
    ax.set_title("§8.6: image grid × height planes (synthetic pushbroom)")
    ax.legend(fontsize=7, loc="upper left")
    return _done(fig), int(np.sum(Z == heights[0]))


def error_vs_planes(levels=(2, 3, 4, 5, 6)):
    """Largest image error on and between the planes, and the rank, against the number of planes."""
    rows = []
    for n in levels:
        fit = ch08_rpc.height_plane_fit(n)
        rows.append((n, fit.fit_error, fit.check_error, fit.rank))
    fig, ax = plt.subplots(figsize=(6.5, 3.8))
    n = [r[0] for r in rows]
    ax.semilogy(n, [max(r[1], 1e-12) for r in rows], "o-", label="on the planes (fitting grid)")
    ax.semilogy(n, [max(r[2], 1e-12) for r in rows], "s-", label="between the planes (random heights)")
    ax.axhline(1.0, color="grey", lw=0.8, ls=":")
    for k, fit_err, chk, rank in rows:
        ax.annotate(f"rank {rank[0]}/{rank[1]}", (k, max(chk, 1e-12)), textcoords="offset points", xytext=(4, 6),
                    fontsize=7)
    ax.set_xticks(n)
    ax.set_xlabel("number of height planes")
    ax.set_ylabel("largest image error, px")
    ax.set_title("RPC fitted to a pushbroom (all 20 terms): three planes are not enough")
    ax.legend(fontsize=8)
    return _done(fig), [(k, float(f"{a:.1g}"), float(f"{b:.1g}"), rank) for k, a, b, rank in rows]


BOOK_TABLE_8_2 = {60: {"RPC": (None, 4.8), "shift": (None, 2.8), "affine": (0.7, 0.7), "poly2": (0.4, 0.5)},
                  30: {"RPC": (None, 4.1), "shift": (None, 2.7), "affine": (0.6, 0.7), "poly2": (0.6, 0.7)}}


def table_8_2_bars(layouts=20, seed=0):
    """Check-point RMS of Table 8.2 (book, real data) beside the seeded simulation."""
    models = ("RPC", "shift", "affine", "poly2")
    sims = {km: ch08_rpc.table_8_2_simulation(km, layouts=layouts, seed=seed) for km in (60, 30)}
    fig, axes = plt.subplots(1, 2, figsize=(9, 3.6), sharey=True)
    x = np.arange(len(models))
    for ax, km in zip(axes, (60, 30)):
        ax.bar(x - 0.2, [BOOK_TABLE_8_2[km][m][1] for m in models], 0.4, label="book (Resurs-P No. 3, real)")
        ax.bar(x + 0.2, [sims[km][m][1] for m in models], 0.4, label="simulation (synthetic, seeded)", hatch="//",
               alpha=0.7)
        ax.set_xticks(x, ["RPC\n0/21", "+ shift\n1/20", "+ affine\n14/7", "+ poly2\n14/7"])
        ax.set_title(f"{km} km fragment: RMS on check points")
    axes[0].set_ylabel("RMS, m")
    axes[0].legend(fontsize=8)
    rounded = {km: {m: tuple(None if v is None else round(v, 2) for v in sims[km][m]) for m in models} for km in sims}
    return _done(fig), rounded


def kanopus_layout():
    """The six micro-frames in the conventional frame (synthetic Kanopus-V-like layout)."""
    from ...synthetic import microframe_camera

    cam = microframe_camera()
    fig, ax = plt.subplots(figsize=(9, 2.8))
    h, w = cam.matrix_shape
    for i, (r0, c0) in enumerate(cam.offsets):
        ax.add_patch(plt.Rectangle((c0, r0), w, h, fill=True, alpha=0.35, color=f"C{i}"))
        ax.text(c0 + w / 2, r0 + h / 2, f"{i + 1}", ha="center", va="center")
    H, W = cam.frame_shape
    ax.add_patch(plt.Rectangle((0, 0), W, H, fill=False, ls="--", color="k"))
    ax.set_xlim(-200, W + 200)
    ax.set_ylim(H + 200, -200)
    ax.set_aspect("equal")
    ax.set_xlabel("column of the conventional frame, px")
    ax.set_ylabel("row, px")
    ax.set_title("§8.18: six micro-frames in two staggered rows (synthetic layout, not from the book)")
    return _done(fig), (H, W)
