"""Figures for Chapter 7, §7.2–7.4, §7.7 (rectification, orthophoto, tolerances, mosaics).

* :func:`forward_vs_inverse` — Figs. 7.2–7.3: a 2× enlargement by the forward method (holes)
  and by the inverse method, and the four output pixels a mapped pixel covers (151.3, 20.7).
* :func:`bilinear_cell` — Figs. 7.5–7.6: a DEM cell with nodes 1–4, ΔX, ΔY and the
  interpolated point (7.3.1).
* :func:`displacement_curves` — Figs. 7.7–7.8: orthophoto shift against r for a DEM error
  (r·ΔZ/f and the simulated shift on tilted photos) and against an attitude error Δω.
* :func:`mosaic_cutline` — Fig. 7.17: two orthophotos, the cutline and the mosaic by the row rule.
* :func:`monoplot_convergence` — Fig. 7.19: the iteration Z₁ → (X₁, Y₁) → Z₂ … on a profile.

Every figure function returns the matplotlib Figure (closed, so that a notebook shows it once)
together with the numbers it shows, rounded.
"""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.patches import Rectangle

from ... import rectify
from ...camera import ExteriorOrientation, InteriorOrientation


def _done(fig):
    plt.close(fig)
    return fig


def forward_vs_inverse(seed: int = 0, size: int = 12):
    """Figs. 7.2–7.3: forward (holes) against inverse rectification; the 4-pixel footprint."""
    image = np.random.default_rng(seed).random((size, size))
    rr, cc = np.mgrid[0:size, 0:size].astype(float)
    m = 2 * (size - 1) + 1
    forward, _ = rectify.rectify_forward(image, 2.0 * rr, 2.0 * cc, (m, m))
    R, C = np.mgrid[0:m, 0:m].astype(float)
    inverse = rectify.resample(image, R / 2.0, C / 2.0, "bilinear")
    _, weight = rectify.rectify_forward(np.ones((1, 1)), np.array([[20.7]]), np.array([[151.3]]), (23, 154))
    fig, ax = plt.subplots(1, 3, figsize=(12, 4))
    cmap = plt.get_cmap("gray").copy()
    cmap.set_bad("tab:red")
    ax[0].imshow(forward, cmap=cmap, vmin=0, vmax=1)
    ax[0].set_title(f"forward ×2: {100 * np.isnan(forward).mean():.0f} % holes (red)")
    ax[1].imshow(inverse, cmap="gray", vmin=0, vmax=1)
    ax[1].set_title("inverse ×2, bilinear: no holes")
    a = ax[2]
    for i in range(19, 23):
        for j in range(150, 154):
            a.add_patch(Rectangle((j - 0.5, i - 0.5), 1, 1, fill=False, color="0.6"))
            if weight[i, j] > 0:
                a.text(j, i, f"{weight[i, j]:.2f}", ha="center", va="center")
    a.add_patch(Rectangle((151.3 - 0.5, 20.7 - 0.5), 1, 1, fill=False, ls="--", color="tab:blue", lw=2))
    a.plot(151.3, 20.7, "o", color="tab:blue")
    a.set_xlim(149.5, 153.5)
    a.set_ylim(22.5, 18.5)
    a.set_aspect("equal")
    a.set_xlabel("column (x^T)")
    a.set_ylabel("row (y^T)")
    a.set_title("pixel mapped to (151.3, 20.7): area weights")
    fig.tight_layout()
    weights = {f"({j}, {i})": round(float(weight[i, j]), 2) for i, j in np.argwhere(weight > 0)}
    return _done(fig), {"forward_hole_percent": round(100 * float(np.isnan(forward).mean()), 1), "weights": weights}


def bilinear_cell(Z=(102.0, 106.0, 104.0, 111.0), dX=3.0, dY=6.5, D=10.0):
    """Figs. 7.5–7.6: a DEM cell, nodes 1 = (X₁, Y₁), 2 = (X₁, Y₁ + ΔD), 3 = (X₁ + ΔD, Y₁),
    4 = (X₁ + ΔD, Y₁ + ΔD), the auxiliary heights Z_K, Z_M and the point's Z_i by (7.3.1)."""
    Z1, Z2, Z3, Z4 = Z
    ZK = Z1 + (Z2 - Z1) / D * dY
    ZM = Z3 + (Z4 - Z3) / D * dY
    Zi = ZK + (ZM - ZK) / D * dX
    fig, ax = plt.subplots(figsize=(5, 5))
    nodes = {1: (0, 0, Z1), 2: (0, D, Z2), 3: (D, 0, Z3), 4: (D, D, Z4)}
    ax.add_patch(Rectangle((0, 0), D, D, fill=False))
    for k, (x, y, z) in nodes.items():
        ax.plot(x, y, "ks")
        ax.annotate(f"{k}: Z{k} = {z:g}", (x, y), textcoords="offset points", xytext=(5, 5))
    ax.plot([0, D], [dY, dY], "--", color="tab:blue")
    ax.plot(0, dY, "o", color="tab:blue")
    ax.plot(D, dY, "o", color="tab:blue")
    ax.annotate(f"K: {ZK:.2f}", (0, dY), textcoords="offset points", xytext=(5, -12), color="tab:blue")
    ax.annotate(f"M: {ZM:.2f}", (D, dY), textcoords="offset points", xytext=(-60, -12), color="tab:blue")
    ax.plot(dX, dY, "o", color="tab:red")
    ax.annotate(f"i: Z = {Zi:.2f}", (dX, dY), textcoords="offset points", xytext=(5, 6), color="tab:red")
    ax.annotate("", (dX, -0.6), (0, -0.6), arrowprops={"arrowstyle": "<->"})
    ax.text(dX / 2, -1.3, "ΔX", ha="center")
    ax.annotate("", (-0.6, dY), (-0.6, 0), arrowprops={"arrowstyle": "<->"})
    ax.text(-1.6, dY / 2, "ΔY", va="center")
    ax.set_xlim(-2.5, D + 2.5)
    ax.set_ylim(-2.5, D + 2.5)
    ax.set_aspect("equal")
    ax.set_title("(7.3.1): bilinear height in a DEM cell")
    grid = rectify.RasterGrid(-D / 2, D * 1.5, D, (2, 2))
    dem = np.array([[Z2, Z4], [Z1, Z3]])
    library = float(rectify.dem_height(dem, grid, dX, dY))
    return _done(fig), {"Z_K": round(ZK, 3), "Z_M": round(ZM, 3), "Z_i": round(Zi, 3),
                        "dem_height": round(library, 3)}


def displacement_curves(dZ: float = 2.0, f: float = 100.0, H: float = 1000.0):
    """Figs. 7.7–7.8: orthophoto shift of a DEM error against r (r·ΔZ/f and monoplotting on
    tilted photos, r from the principal point), and the shift of an attitude error Δω at the
    frame centre and edge (flat ground, vertical photo)."""
    grid = rectify.RasterGrid(-1500.0, 1500.0, 10.0, (300, 300))
    flat = np.zeros(grid.shape)
    io = InteriorOrientation(f)
    r = np.linspace(5.0, 100.0, 20)
    xy = np.column_stack([r / np.sqrt(2), r / np.sqrt(2)])
    fig, ax = plt.subplots(1, 2, figsize=(11, 4))
    ax[0].plot(r, rectify.relief_displacement(r, dZ, f), "k-", lw=2, label="r·ΔZ/f (7.4.2)")
    shifts = {}
    for tilt in (0.0, 3.0, 5.0):
        t = np.radians(tilt)
        eo = ExteriorOrientation(0.0, 0.0, H, t * 0.6, t * 0.8, 0.0)
        good = rectify.monoplot(xy, eo, io, flat, grid).XYZ
        bad = rectify.monoplot(xy, eo, io, flat + dZ, grid).XYZ
        shift = np.hypot(*(bad - good)[:, :2].T)
        shifts[tilt] = round(float(shift[-1]), 3)
        ax[0].plot(r, shift, "o", ms=4, label=f"simulated, tilt {tilt:g}°")
    ax[0].set_xlabel("r from the principal point, mm")
    ax[0].set_ylabel("shift on the orthophoto, m")
    ax[0].set_title(f"DEM error ΔZ = {dZ:g} m (Fig. 7.7)")
    ax[0].legend()
    dw = np.radians(np.linspace(0.0, 0.1, 11))
    edge = np.array([[0.0, 0.0], [100.0, 0.0], [0.0, 100.0]])
    truth = rectify.monoplot(edge, ExteriorOrientation(0.0, 0.0, H), io, flat, grid).XYZ
    curves = []
    for w in dw:
        moved = rectify.monoplot(edge, ExteriorOrientation(0.0, 0.0, H, w, 0.0, 0.0), io, flat, grid).XYZ
        curves.append(np.hypot(*(moved - truth)[:, :2].T))
    curves = np.array(curves)
    for k, label in enumerate(("centre", "x = 100 mm", "y = 100 mm")):
        ax[1].plot(np.degrees(dw), curves[:, k], "o-", ms=4, label=label)
    ax[1].set_xlabel("attitude error Δω, °")
    ax[1].set_ylabel("shift on the orthophoto, m")
    ax[1].set_title(f"tilt error, H = {H:g} m (Fig. 7.8)")
    ax[1].legend()
    fig.tight_layout()
    return _done(fig), {"shift_at_r100_m": shifts, "tilt_shift_centre_0.1deg_m": round(float(curves[-1, 0]), 3)}


def mosaic_cutline(seed: int = 0):
    """Fig. 7.17: two overlapping orthophotos (the second a little brighter), a polyline
    cutline and the mosaic by the row rule; the mosaic origin is (min X₀, max Y₀)."""
    rng = np.random.default_rng(seed)
    big = rectify.RasterGrid(0.0, 60.0, 1.0, (60, 80))
    X, Y = big.centres()
    scene = 0.5 + 0.2 * np.sin(X / 4.0) * np.cos(Y / 6.0) + 0.05 * rng.standard_normal(big.shape)
    g1, g2 = big.window(0, 0, 55, 50), big.window(6, 30, 54, 50)
    o1, o2 = scene[:55, :50], np.clip(scene[6:60, 30:80] + 0.15, 0, 1)
    cutline = np.array([[38.0, -1.0], [42.0, 20.0], [36.0, 40.0], [40.0, 61.0]])
    image, grid, source = rectify.mosaic([o1, o2], [g1, g2], cutline, return_source=True)
    fig, ax = plt.subplots(1, 3, figsize=(13, 4))
    for a, (img, g, title) in zip(ax, ((o1, g1, "orthophoto P1"), (o2, g2, "orthophoto P2"),
                                        (image, grid, "mosaic (row rule)"))):
        x0, y0, x1, y1 = g.extent
        a.imshow(img, cmap="gray", vmin=0, vmax=1, extent=(x0, x1, y0, y1))
        a.plot(cutline[:, 0], cutline[:, 1], "r-", lw=1.5)
        a.set_xlim(0, 80)
        a.set_ylim(0, 60)
        a.set_title(title)
    ax[2].plot(grid.x0, grid.y0, "bs")
    ax[2].annotate("(X0M, Y0M)", (grid.x0, grid.y0), textcoords="offset points", xytext=(4, -12), color="b")
    fig.tight_layout()
    return _done(fig), {"origin": (grid.x0, grid.y0), "shape": grid.shape,
                        "from_P1": int((source == 0).sum()), "from_P2": int((source == 1).sum()),
                        "empty": int((source < 0).sum())}


def monoplot_convergence(x_mm: float = 60.0, tilt_deg: float = 3.0):
    """Fig. 7.19: the iteration along a profile of a hilly DEM — Z₁ (mean height) → X₁ → Z₂ → …"""
    grid = rectify.RasterGrid(-2000.0, 2000.0, 10.0, (400, 400))
    X, Y = grid.centres()
    dem = 150.0 + 60.0 * np.sin(X / 300.0) + 0.25 * X
    io = InteriorOrientation(100.0)
    eo = ExteriorOrientation(0.0, 0.0, 1200.0, 0.0, np.radians(tilt_deg), 0.0)
    result = rectify.monoplot([[x_mm, 0.0]], eo, io, dem, grid, tol=1e-3)
    hist = np.array([h[0] for h in result.history])
    xs = np.linspace(hist[:, 0].min() - 150, hist[:, 0].max() + 150, 200)
    profile = rectify.dem_height(dem, grid, xs, np.zeros_like(xs))
    fig, ax = plt.subplots(1, 2, figsize=(11, 4))
    ax[0].plot(xs, profile, "k-", label="DEM profile (Y = 0)")
    ray_x = np.array([0.0, result.XYZ[0, 0] * 1.3])
    ray_z = eo.Zs + (ray_x - eo.Xs) * (result.XYZ[0, 2] - eo.Zs) / (result.XYZ[0, 0] - eo.Xs)
    ax[0].plot(ray_x, ray_z, "b-", lw=0.8, label="the ray of the image point")
    for k, (x, _, z) in enumerate(hist, 1):
        ax[0].plot([x], [z], "ro", ms=4)
        ax[0].annotate(f"{k}", (x, z), textcoords="offset points", xytext=(3, 3), fontsize=8)
        z_next = float(rectify.dem_height(dem, grid, x, 0.0))
        ax[0].plot([x, x], [z, z_next], "r:", lw=0.8)
    ax[0].set_xlim(xs[0], xs[-1])
    ax[0].set_ylim(profile.min() - 30, profile.max() + 60)
    ax[0].set_xlabel("X, m")
    ax[0].set_ylabel("Z, m")
    ax[0].legend(loc="upper left")
    ax[0].set_title("(7.7.1) on the height Z_k, then Z_{k+1} from the DEM")
    steps = np.abs(np.diff(hist[:, 0]))
    ax[1].semilogy(np.arange(2, len(hist) + 1), np.maximum(steps, 1e-9), "o-")
    ax[1].axhline(1e-3, color="0.5", ls="--", label="tolerance 1 mm")
    ax[1].set_xlabel("iteration k")
    ax[1].set_ylabel("|X_k − X_{k−1}|, m")
    ax[1].legend()
    fig.tight_layout()
    return _done(fig), {"iterations": int(result.iterations[0]),
                        "X": round(float(result.XYZ[0, 0]), 3), "Z": round(float(result.XYZ[0, 2]), 3)}
