"""Figures for Chapter 6, §6.6–6.7 (DTM: TIN, grid, contours, DSM → DTM), drawn from library calls.

* :func:`spot_heights` — the synthetic spot heights the notebook and the figures share (a hill
  and a valley on a tilted plane, random X, Y).
* :func:`tin_figure` — Figs. 6.12–6.13: the Delaunay TIN of the spot heights, with the
  circumcircles of a few triangles (empty of other vertices).
* :func:`grid_figure` — Figs. 6.14–6.15: the grid from the TIN (plane of the enclosing triangle,
  (6.6.1)), a node inside its triangle, and the interpolation error against the true surface.
* :func:`contours_figure` — Figs. 6.16–6.17: contours by linear interpolation on the grid and on
  the TIN (our polylines, with matplotlib's contour/tricontour dashed beneath for comparison).
* :func:`dsm_dtm_figure` — §6.6 (1): DSM, filtered DTM, the removed object cells and the DTM
  error against the true ground on the renderer's synthetic scene.

Every function returns the matplotlib Figure (closed, so that a notebook shows it once).
"""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np

from ... import dtm


def _done(fig):
    plt.close(fig)
    return fig


def terrain(X, Y):
    """The analytic surface behind the spot heights: tilted plane + hill + valley, metres."""
    X, Y = np.asarray(X, float), np.asarray(Y, float)
    return (120 + 0.05 * X + 0.03 * Y + 12 * np.exp(-((X - 35) ** 2 + (Y - 60) ** 2) / 400)
            - 6 * np.exp(-((X - 75) ** 2 + (Y - 30) ** 2) / 250))


def spot_heights(n=120, seed=0):
    """n random spot heights over 100 × 100 m plus the four corners: (xy, z)."""
    rng = np.random.default_rng(seed)
    xy = np.vstack([rng.uniform(0, 100, (n, 2)), [[0, 0], [100, 0], [0, 100], [100, 100]]])
    return xy, terrain(xy[:, 0], xy[:, 1])


def tin_figure(n=120, seed=0, circles=4):
    """The TIN of the spot heights; a few circumcircles drawn to show the Delaunay rule."""
    xy, z = spot_heights(n, seed)
    tin = dtm.delaunay_tin(xy, z)
    fig, ax = plt.subplots(figsize=(6, 5.5))
    ax.triplot(xy[:, 0], xy[:, 1], tin.triangles, color="0.5", lw=0.6)
    sc = ax.scatter(xy[:, 0], xy[:, 1], c=z, s=14, cmap="terrain", zorder=3)
    fig.colorbar(sc, ax=ax, label="Z, m")
    rng = np.random.default_rng(seed + 1)
    for k in rng.choice(len(tin.triangles), circles, replace=False):
        p = xy[tin.triangles[k]]
        a, b, c = p
        b, c = b - a, c - a
        d = 2 * (b[0] * c[1] - b[1] * c[0])
        u = np.array([c[1] * (b @ b) - b[1] * (c @ c), b[0] * (c @ c) - c[0] * (b @ b)]) / d
        ax.add_patch(plt.Circle(a + u, np.hypot(*u), fill=False, color="C3", lw=1))
        ax.fill(p[:, 0], p[:, 1], color="C3", alpha=0.3)
    ax.set(xlim=(-5, 105), ylim=(-5, 105), aspect="equal", xlabel="X, m", ylabel="Y, m",
           title=f"Delaunay TIN: {len(tin.triangles)} triangles, empty circumcircles")
    return _done(fig)


def grid_figure(n=120, seed=0, step=5.0):
    """The grid from the TIN, (6.6.1), and its error against the analytic surface."""
    xy, z = spot_heights(n, seed)
    tin = dtm.delaunay_tin(xy, z)
    g = np.arange(0, 100 + step / 2, step)
    G = dtm.grid_from_tin(tin, g, g)
    Xg, Yg = np.meshgrid(g, g)
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.8))
    ext = (g[0] - step / 2, g[-1] + step / 2, g[0] - step / 2, g[-1] + step / 2)
    im = axes[0].imshow(G, origin="lower", extent=ext, cmap="terrain")
    axes[0].triplot(xy[:, 0], xy[:, 1], tin.triangles, color="k", lw=0.3, alpha=0.5)
    axes[0].plot(Xg, Yg, "k.", ms=2)
    node = np.array([[g[7], g[12]]])
    k = tin.delaunay.find_simplex(node)[0]
    tri = xy[tin.triangles[k]]
    axes[0].fill(tri[:, 0], tri[:, 1], fc="none", ec="C3", lw=2)
    axes[0].plot(*node[0], "o", color="C3")
    axes[0].set(title=f"height matrix, step {step:g} m (node i in its triangle, red)", xlabel="X, m", ylabel="Y, m")
    fig.colorbar(im, ax=axes[0], label="Z, m")
    err = G - terrain(Xg, Yg)
    lim = np.nanmax(np.abs(err))
    im = axes[1].imshow(err, origin="lower", extent=ext, cmap="RdBu_r", vmin=-lim, vmax=lim)
    axes[1].plot(xy[:, 0], xy[:, 1], "k.", ms=3)
    axes[1].set(title=f"grid − true surface (RMSE {np.sqrt(np.mean(err ** 2)):.2f} m)", xlabel="X, m")
    fig.colorbar(im, ax=axes[1], label="m")
    return _done(fig)


def contours_figure(n=120, seed=0, step=5.0, interval=2.0):
    """Contours by linear interpolation on the grid and on the TIN (Fig. 6.17)."""
    xy, z = spot_heights(n, seed)
    tin = dtm.delaunay_tin(xy, z)
    g = np.arange(0, 100 + step / 2, step)
    G = dtm.grid_from_tin(tin, g, g)
    levels = np.arange(np.ceil(z.min() / interval) * interval, z.max(), interval)
    fig, axes = plt.subplots(1, 2, figsize=(11, 5))
    axes[0].contour(g, g, G, levels=levels, colors="0.6", linestyles="--", linewidths=2.5)
    for lines in dtm.contours_from_grid(G, levels, g, g).values():
        for p in lines:
            axes[0].plot(p[:, 0], p[:, 1], "C0", lw=1)
    axes[0].plot(*np.meshgrid(g, g), "k.", ms=1.5)
    axes[0].set(title=f"grid ({step:g} m): contours every {interval:g} m", xlabel="X, m", ylabel="Y, m")
    axes[1].tricontour(xy[:, 0], xy[:, 1], tin.triangles, z, levels=levels, colors="0.6",
                       linestyles="--", linewidths=2.5)
    axes[1].triplot(xy[:, 0], xy[:, 1], tin.triangles, color="0.85", lw=0.5)
    for lines in dtm.contours_from_tin(tin, levels).values():
        for p in lines:
            axes[1].plot(p[:, 0], p[:, 1], "C1", lw=1)
    axes[1].set(title="TIN: contours by linear interpolation on the edges", xlabel="X, m")
    for ax in axes:
        ax.set(aspect="equal", xlim=(0, 100), ylim=(0, 100))
    fig.suptitle("solid: photolib.dtm; grey dashed: matplotlib contour / tricontour")
    return _done(fig)


def dsm_dtm_scene(seed=3, extent=150.0, spacing=1.0, noise=0.05):
    """The renderer's scene (ground, buildings, trees) and its noisy DSM: (scene, dsm)."""
    from ...synthetic import terrain_scene
    scene = terrain_scene(extent=extent, spacing=spacing, n_buildings=6, n_trees=10, seed=seed)
    dsm = scene.surface + np.random.default_rng(seed).normal(0, noise, scene.surface.shape)
    return scene, dsm


def dsm_dtm_figure(seed=3, max_window=40.0, slope=0.1):
    """DSM, filtered DTM, removed cells and DTM error on the synthetic scene."""
    scene, dsm = dsm_dtm_scene(seed)
    result = dtm.filter_dsm(dsm, scene.spacing, max_window=max_window, slope=slope)
    ext = scene.extent
    fig, axes = plt.subplots(2, 2, figsize=(10, 9))
    vmin, vmax = scene.ground.min(), dsm.max()
    for ax, Z, title in ((axes[0, 0], dsm, "DSM (ground + buildings + trees, 5 cm noise)"),
                         (axes[0, 1], result.dtm, "DTM after the progressive morphological filter")):
        im = ax.imshow(Z, origin="lower", extent=ext, cmap="terrain", vmin=vmin, vmax=vmax)
        ax.set_title(title, fontsize=10)
    fig.colorbar(im, ax=axes[0, :], label="Z, m", shrink=0.8)
    truth = scene.buildings | scene.trees
    code = np.zeros(truth.shape)
    code[result.objects & truth] = 1
    code[result.objects & ~truth] = 2
    code[~result.objects & truth] = 3
    axes[1, 0].imshow(code, origin="lower", extent=ext, cmap=plt.matplotlib.colors.ListedColormap(
        ["white", "0.4", "C3", "C1"]), vmin=-0.5, vmax=3.5, interpolation="nearest")
    axes[1, 0].set_title("removed (grey), wrongly removed (red), missed (orange)", fontsize=10)
    err = result.dtm - scene.ground
    im = axes[1, 1].imshow(err, origin="lower", extent=ext, cmap="RdBu_r", vmin=-0.5, vmax=0.5)
    axes[1, 1].set_title(f"DTM − true ground: RMSE {np.sqrt(np.mean(err ** 2)):.2f} m", fontsize=10)
    fig.colorbar(im, ax=axes[1, :], label="m", shrink=0.8)
    return _done(fig)
