"""Figures for Chapter 7, §7.5, §7.6, §7.8 (true orthophotos, point clouds, the least-squares DSM).

* :func:`lean_section` — Figs. 7.9–7.11: a vertical section through a building, the rays from S,
  the roof's displacement on an ortho over the DTM, the dead zone and the nadir angles α, β.
* :func:`index_matrices` — Fig. 7.12: the index matrix and the re-projected matrix as heat maps.
* :func:`town` / :func:`town_orthos` — Fig. 7.13 and 7.16: a synthetic town, one image's ortho
  over the DTM and over the DSM against the true orthophoto from five images.
* :func:`point_cloud_walls` — Figs. 7.14–7.15: the cloud an oblique view gives (wall points),
  the radius mean against the maximum-Z rule.
* :func:`lsq_demo` — Fig. 7.20 / §7.8: convergence of the least-squares DSM from three images.
* :func:`lsq_eo_demo` — (7.8.4): the same with the EO unknown and five GCPs.

Every figure function returns the matplotlib Figure (closed, so that a notebook shows it once)
together with the numbers it shows, rounded.
"""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np

from ...camera import ExteriorOrientation, InteriorOrientation
from ...rectify import RasterGrid, dem_height, frame_projector, orthorectify
from ...synthetic import render_image, terrain_scene
from ... import trueortho


def _done(fig):
    plt.close(fig)
    return fig


def scene_grid(sc):
    """The RasterGrid of a TerrainScene's nodes (north-up: use ``array[::-1]``)."""
    s = sc.spacing
    return RasterGrid(sc.x[0] - s / 2, sc.y[-1] + s / 2, s, sc.surface.shape)


def lean_section(H=100.0, Xs=0.0, building=(30.0, 42.0), h=20.0):
    """Figs. 7.9–7.11 in a vertical section: roof edge C, its false position C'₀ over the DTM,
    the dead zone 1–2 behind the building, and the nadir angles of two elements."""
    x0, x1 = building
    fig, ax = plt.subplots(figsize=(8, 4))
    ax.fill_between([x0, x1], 0, h, color="0.75", label="building")
    ax.plot([-5, 75], [0, 0], "k-", lw=1)
    ax.plot(Xs, H, "k^", ms=9)
    ax.annotate("S", (Xs, H), xytext=(4, 0), textcoords="offset points")
    # ray through the far roof edge C = (x1, h) reaches the ground at C'0
    c0 = Xs + (x1 - Xs) * H / (H - h)
    ax.plot([Xs, c0], [H, 0], "r-", lw=1)
    ax.plot(x1, h, "ro")
    ax.plot(c0, 0, "rx", ms=9)
    ax.annotate("C", (x1, h), xytext=(4, 4), textcoords="offset points")
    ax.annotate("C'₀", (c0, 0), xytext=(0, -14), textcoords="offset points")
    ax.annotate("C₀", (x1, 0), xytext=(-6, -14), textcoords="offset points")
    ax.plot([x1, c0], [0, 0], color="tab:orange", lw=6, alpha=0.7, label="dead zone 1–2")
    # a ground point M in the dead zone: its ray is blocked by the roof edge
    M = 0.5 * (x1 + c0)
    ax.plot([M, Xs], [0, H], "b--", lw=0.8)
    ax.plot(M, 0, "bs")
    ax.annotate("M", (M, 0), xytext=(0, 6), textcoords="offset points")
    ax.set_xlabel("X, m")
    ax.set_ylabel("Z, m")
    ax.set_title("A building on an ortho over the DTM: the roof edge C moves to C'₀; M is hidden")
    ax.legend(loc="upper right")
    ax.set_aspect("equal")
    tan_c, tan_m = (x1 - Xs) / (H - h), (M - Xs) / H
    return _done(fig), {"lean_m": round(c0 - x1, 2), "dead_zone_m": round(c0 - x1, 2),
                        "tan_alpha_roof_edge": round(tan_c, 3), "tan_beta_M": round(tan_m, 3)}


def index_matrices(left, right):
    """Fig. 7.12: two 10 × 11 grids of strings ('0', '1', '2', '.') as heat maps with the codes."""
    fig, axes = plt.subplots(1, 2, figsize=(9, 3.8))
    cmap = plt.get_cmap("viridis", 4)
    for ax, grid, title in zip(axes, (left, right), ("index matrix (image)", "orthophoto (re-projected)")):
        codes = np.array([[{"0": 0, "1": 1, "2": 2, ".": 3}[ch] for ch in row] for row in grid])
        ax.imshow(codes, cmap=cmap, vmin=-0.5, vmax=3.5)
        for (i, j), v in np.ndenumerate(codes):
            ax.text(j, i, "" if v == 3 else str(v), ha="center", va="center", color="w" if v < 2 else "k",
                    fontsize=8)
        ax.set_title(title)
        ax.set_xticks(range(11))
        ax.set_yticks(range(10))
    axes[1].text(11.5, 5, "blank: dead zone", fontsize=8, rotation=90, va="center")
    return _done(fig), {}


def town(seed=5):
    """A synthetic town: 3 box buildings, 5 vertical images (four corners and the centre)."""
    sc = terrain_scene(extent=60.0, spacing=0.5, n_buildings=3, building_size=(8, 14), building_height=(8, 14),
                       relief=2.0, seed=seed)
    io = InteriorOrientation(35.0)
    H = float(sc.surface.max() + 100.0)
    eos = [ExteriorOrientation(30 + dx, 30 + dy, H) for dx, dy in [(-12, -12), (12, -12), (-12, 12), (12, 12), (0, 0)]]
    shape, pix = (160, 160), 0.15
    images = [render_image(sc, io, eo, shape, pixel_size=pix, supersample=1).image for eo in eos]
    return sc, io, eos, images, shape, pix


def town_orthos(data, image=0):
    """Ortho over the DTM, over the DSM (one image), the true ortho (five images), the truth."""
    sc, io, eos, images, shape, pix = data
    dgrid = scene_grid(sc)
    dsm, dtm = sc.surface[::-1].copy(), sc.ground[::-1].copy()
    grid = RasterGrid(5.0, 55.0, 0.5, (100, 100))
    X, Y = grid.centres()
    truth = dem_height(sc.albedo[::-1], dgrid, X, Y)
    proj = [frame_projector(eo, io, pix, shape) for eo in eos]
    over_dtm = orthorectify(images[image], proj[image], dtm, dgrid, grid)
    over_dsm = orthorectify(images[image], proj[image], dsm, dgrid, grid)
    true = trueortho.true_ortho_multi(images, proj, [eo.center for eo in eos], dsm, dgrid, grid)
    fig, axes = plt.subplots(2, 3, figsize=(11, 7.4))
    ext = grid.extent
    extent = (ext[0], ext[2], ext[1], ext[3])
    panels = ((over_dtm, f"image {image} over the DTM"), (over_dsm, f"image {image} over the DSM"),
              (true.image, "true ortho, 5 images (Fig. 7.13)"))
    for k, (a, title) in enumerate(panels):
        axes[0, k].imshow(a, cmap="gray", vmin=0, vmax=1, extent=extent)
        axes[0, k].set_title(title, fontsize=9)
        axes[1, k].imshow(np.abs(a - truth), cmap="magma", vmin=0, vmax=0.3, extent=extent)
        axes[1, k].set_title("|ortho − texture| (NaN white)", fontsize=9)
    for b in sc.footprints:
        for ax in axes.ravel():
            ax.plot([b[0], b[1], b[1], b[0], b[0]], [b[2], b[2], b[3], b[3], b[2]], "r-", lw=0.6)
    roof = dem_height(sc.buildings[::-1].astype(float), dgrid, X, Y) > 0.99

    def bad(a):
        return round(100 * float(np.nanmean(np.abs(a - truth) > 0.1)), 1)
    numbers = {"bad_pct_dtm": bad(over_dtm), "bad_pct_dsm": bad(over_dsm), "bad_pct_true": bad(true.image),
               "roof_err_dtm": round(float(np.nanmean(np.abs(over_dtm - truth)[roof])), 3),
               "roof_err_true": round(float(np.nanmean(np.abs(true.image - truth)[roof])), 3),
               "hidden_pct_image": round(100 * float((true.visible[image] == 0).mean()), 1),
               "dead_pct_true": round(100 * float((true.source < 0).mean()), 2),
               "images_used": np.bincount(true.source[true.source >= 0], minlength=len(images)).tolist()}
    return _done(fig), numbers


def point_cloud_walls(seed=6):
    """A point cloud from an oblique render (its XYZ per pixel), side view and orthos by two rules."""
    sc = terrain_scene(extent=40.0, spacing=0.25, n_buildings=1, building_size=(12, 16), building_height=(10, 12),
                       relief=1.0, seed=seed)
    io = InteriorOrientation(35.0)
    b = sc.footprints[0]
    eo = ExteriorOrientation(b[0] - 40.0, 0.5 * (b[2] + b[3]), float(sc.ground.mean()) + 70.0, 0.0, -np.arctan(45 / 70), 0.0)
    r = render_image(sc, io, eo, (200, 200), pixel_size=0.12, supersample=1)
    ok = r.visible
    pts, d = r.XYZ[ok], r.image[ok]
    grid = RasterGrid(b[0] - 4, b[3] + 4, 0.5, (int((b[3] - b[2] + 8) / 0.5), int((b[1] - b[0] + 8) / 0.5)))
    mean = trueortho.ortho_from_points(pts, d, grid, "radius_mean")
    top = trueortho.ortho_from_points(pts, d, grid, "max_z", z_tol=0.3)
    X, Y = grid.centres()
    truth = dem_height(sc.albedo[::-1], scene_grid(sc), X, Y)
    wall = np.abs(pts[:, 0] - b[0]) < 0.3
    fig, axes = plt.subplots(1, 3, figsize=(13, 3.8))
    sel = np.abs(pts[:, 1] - 0.5 * (b[2] + b[3])) < 1.0
    axes[0].scatter(pts[sel, 0], pts[sel, 2], c=np.where(wall[sel], "tab:red", "tab:blue"), s=2)
    axes[0].set_title("cloud, 2 m strip: wall points red")
    axes[0].set_xlabel("X, m")
    axes[0].set_ylabel("Z, m")
    ext = grid.extent
    for ax, a, title in ((axes[1], mean, "radius mean"), (axes[2], top, "maximum-Z rule")):
        ax.imshow(a, cmap="gray", vmin=0, vmax=1, extent=(ext[0], ext[2], ext[1], ext[3]))
        ax.axvline(b[0], color="r", lw=0.6)
        ax.set_title(title)
    inner = (X > b[0]) & (X < b[0] + 0.6) & (Y > b[2]) & (Y < b[3])      # roof pixels along the wall
    outer = (X < b[0]) & (X > b[0] - 0.6) & (Y > b[2]) & (Y < b[3])      # ground pixels along the wall

    def err(a, m):
        return round(float(np.nanmean(np.abs(a - truth)[m])), 3)
    return _done(fig), {"points": int(len(pts)), "wall_points": int(wall.sum()),
                        "roof_edge_err_mean": err(mean, inner), "roof_edge_err_max_z": err(top, inner),
                        "ground_edge_err_mean": err(mean, outer), "ground_edge_err_max_z": err(top, outer)}


def _lsq_scene(seed, noise):
    """The §7.8 hill scene: three convergent images with gains 1, 1.15, 0.9, the 32 × 32 ortho grid,
    the true DSM on it and an initial DSM off by a smooth error of ``noise`` m RMS."""
    from scipy.ndimage import gaussian_filter
    sc = terrain_scene(extent=40.0, spacing=0.5, n_buildings=0, relief=6.0, relief_scale=15.0, texture_scale=1.5,
                       seed=seed)
    io = InteriorOrientation(50.0)
    eos = []
    for a in np.radians([90.0, 210.0, 330.0]):
        dx, dy = 40 * np.cos(a), 40 * np.sin(a)
        eos.append(ExteriorOrientation(20 + dx, 20 + dy, 250.0, -np.arctan(dy / 150), np.arctan(dx / 150), 0.0))
    gains = [1.0, 1.15, 0.9]
    images = [g * render_image(sc, io, eo, (240, 240), pixel_size=0.04).image for eo, g in zip(eos, gains)]
    grid = RasterGrid(16.0, 24.0, 0.25, (32, 32))
    X, Y = grid.centres()
    Zt = dem_height(sc.surface[::-1], scene_grid(sc), X, Y)
    e = gaussian_filter(np.random.default_rng(1).normal(size=Zt.shape), 2)
    return sc, io, eos, images, grid, Zt, Zt + noise * e / e.std()


def lsq_eo_demo(seed=3, noise=0.3, shift=0.5, tilt=1e-3, gcp_noise=0.0):
    """(7.8.4) on the scene of :func:`lsq_demo`: EO unknown, started ``shift`` m / ``tilt`` rad off,
    five GCPs (image coordinates exact, or with ``gcp_noise`` pixels of noise, σ_gcp = 0.1 px);
    the same run with the EO known beside it (both with σ_z0 = 20 m). Convergence of the EO and
    the final DSM error; the numbers: EO errors before and after, median |ΔZ| of both runs."""
    from ...single_image import project
    sc, io, eos, images, grid, Zt, z0 = _lsq_scene(seed, noise)
    xy = np.array([[8.0, 8.0], [32.0, 8.0], [8.0, 32.0], [32.0, 32.0], [20.0, 20.0]])
    G = np.column_stack([xy, dem_height(sc.surface[::-1], scene_grid(sc), xy[:, 0], xy[:, 1])])
    rng = np.random.default_rng(7)
    meas = np.stack([project(G, eo, io) for eo in eos])
    start = [ExteriorOrientation(*(eo.vector + np.r_[rng.choice([-1, 1], 3) * shift, rng.choice([-1, 1], 3) * tilt]))
             for eo in eos]
    meas = meas + gcp_noise * 0.04 * rng.normal(size=meas.shape)
    history = []
    known = trueortho.lsq_dsm_ortho(images, eos, io, 0.04, grid, z0, sigma_z0=20.0)
    res = trueortho.lsq_dsm_ortho(images, start, io, 0.04, grid, z0, sigma_z0=20.0, estimate_eo=True, gcp_xyz=G,
                                  gcp_xy=meas, sigma_gcp=0.1, progress=history.append)
    fig, axes = plt.subplots(1, 2, figsize=(9, 3.6))
    it = [h.iteration for h in history]
    axes[0].semilogy(it, [h.delta[1] for h in history], "o-", label="RMS δZ, m")
    axes[0].semilogy(it, [h.delta[2] for h in history], "s-", label="max |δ centre|, m")
    axes[0].semilogy(it, [h.delta[3] * 250 for h in history], "^-", label="max |δ angle| · H, m")
    axes[0].set_xlabel("iteration")
    axes[0].legend(fontsize=8)
    axes[0].set_title("(7.8.4): EO unknown")
    im = axes[1].imshow(res.dsm - Zt, cmap="RdBu", vmin=-0.05, vmax=0.05)
    axes[1].set_title("final DSM error, m")
    plt.colorbar(im, ax=axes[1], fraction=0.046)
    c_err = lambda es: round(float(np.max(np.abs([e.center - t.center for e, t in zip(es, eos)]))), 4)
    a_err = lambda es: round(float(np.max(np.abs([e.vector[3:] - t.vector[3:] for e, t in zip(es, eos)]))) * 1e3, 4)
    return _done(fig), {"iterations": len(history), "N": res.counts[0], "GCP rows": 2 * G.shape[0] * len(eos),
                        "centre_err_start_m": c_err(start), "centre_err_end_m": c_err(res.eos),
                        "angle_err_start_mrad": a_err(start), "angle_err_end_mrad": a_err(res.eos),
                        "median_dZ_known_eo": round(float(np.median(np.abs(known.dsm - Zt))), 4),
                        "median_dZ_unknown_eo": round(float(np.median(np.abs(res.dsm - Zt))), 4),
                        "gains": [round(float(k), 4) for k in res.gains]}


def lsq_demo(seed=3, noise=0.3):
    """§7.8 on a 40 m hill scene: three convergent images with gains 1, 1.15, 0.9, a 32 × 32 ortho
    grid, an initial DSM off by a smooth error of ``noise`` m RMS; iteration history and errors."""
    sc, io, eos, images, grid, Zt, z0 = _lsq_scene(seed, noise)
    X, Y = grid.centres()
    history = []
    res = trueortho.lsq_dsm_ortho(images, eos, io, 0.04, grid, z0, progress=history.append)
    fig, axes = plt.subplots(1, 3, figsize=(13, 3.6))
    axes[0].semilogy([h.iteration for h in history], [h.delta[1] for h in history], "o-")
    axes[0].set_xlabel("iteration")
    axes[0].set_ylabel("RMS δZ, m")
    axes[0].set_title("convergence")
    for ax, a, title in ((axes[1], z0 - Zt, "initial DSM error, m"), (axes[2], res.dsm - Zt, "final DSM error, m")):
        im = ax.imshow(a, cmap="RdBu", vmin=-0.6, vmax=0.6)
        ax.set_title(title)
        plt.colorbar(im, ax=ax, fraction=0.046)
    err0, err = np.abs(z0 - Zt), np.abs(res.dsm - Zt)
    return _done(fig), {"iterations": len(history), "N": res.counts[0], "M": res.counts[1],
                        "median_dZ_start": round(float(np.median(err0)), 3), "median_dZ_end": round(float(np.median(err)), 3),
                        "p90_dZ_end": round(float(np.percentile(err, 90)), 3),
                        "gains": [round(float(k), 4) for k in res.gains], "inverse_true_gains": [1.0, 0.8696, 1.1111],
                        "F_median_err": round(float(np.median(np.abs(res.ortho - dem_height(sc.albedo[::-1], scene_grid(sc), X, Y)))), 4)}
