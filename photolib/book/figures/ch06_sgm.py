"""Figures for Chapter 6, §6.4–6.5 (semi-global matching in image and object space).

* :func:`downsample` — a Middlebury pair at 1/k resolution (block means; disparities / k), so
  that the notebook runs in seconds.
* :func:`cost_volume_slice` — Fig. 6.6 а: one image row of the cost cube C(x, p) (6.4.1) and of
  the aggregated S(x, p) (6.4.4), with the true disparity drawn over them.
* :func:`wta_vs_sgm` — Fig. 6.6 б against SGM: winner-takes-all on C, SGM on the same C, the
  ground truth and the error map (bad > 2 px, invalid) with the bad-2.0 figures.
* :func:`normal_case_pair`, :func:`point_cloud` — §6.4's last step: a rendered normal-case pair,
  SGM disparities → forward intersection → the dense point cloud against the true surface.
* :func:`voxel_scene`, :func:`voxel_dsm` — §6.5: DSM by SGM in object space from three vertical
  images: truth, voxel WTA, voxel SGM and the error of SGM.

Every figure function returns the matplotlib Figure (closed, so that a notebook shows it once)
together with the numbers it shows, rounded.
"""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np

from ... import sgm
from ...camera import ExteriorOrientation, InteriorOrientation
from ...datasets import StereoBenchmark


def _done(fig):
    plt.close(fig)
    return fig


def bad_percent(disparity, pair, threshold=2.0):
    """bad-2.0 (%) over ``pair.evaluate``, invalid (NaN) pixels counted as bad."""
    wrong = ~(np.abs(disparity - pair.disparity) <= threshold)
    return float(100.0 * wrong[pair.evaluate].mean())


def downsample(pair: StereoBenchmark, factor: int = 2) -> StereoBenchmark:
    """The pair at 1/``factor`` resolution: block means of the images, disparities divided by
    ``factor`` (NaN where any pixel of the block is unknown), a block scored if all its pixels are."""
    k = int(factor)
    H, W = (np.array(pair.left.shape) // k) * k

    def blocks(a, how):
        b = a[:H, :W].reshape(H // k, k, W // k, k)
        return how(b, axis=(1, 3))

    left, right = blocks(pair.left, np.mean), blocks(pair.right, np.mean)
    disp = blocks(pair.disparity, np.mean) / k
    evaluate = blocks(pair.evaluate, np.all) & np.isfinite(disp)
    return StereoBenchmark(pair.name + f" (1/{k})", left, right, disp, evaluate,
                           int(np.ceil(np.nanmax(disp))))


def cost_volume_slice(pair: StereoBenchmark, row: int, *, method="census", window=(7, 9), P1=8.0, P2=100.0):
    """Row ``row`` of C(x, p) and of S(x, p) with the true disparity; returns (fig, C_row, S_row)."""
    dmax = pair.max_disparity
    C = sgm.cost_volume(pair.left, pair.right, dmax, method=method, window=window)
    S = sgm.aggregate_costs(C, P1, P2)
    fig, axes = plt.subplots(2, 1, figsize=(9, 5.5), sharex=True)
    x = np.arange(pair.left.shape[1])
    for ax, V, title in ((axes[0], C, "cost C(x, p) (6.4.1), one image row"),
                         (axes[1], S, "aggregated S(x, p) = Σ_r L_r (6.4.4)")):
        im = ax.imshow(V[row].T, origin="lower", aspect="auto", cmap="viridis",
                       extent=(-0.5, x[-1] + 0.5, -0.5, dmax + 0.5))
        ax.plot(x, pair.disparity[row], "w.", ms=2, label="true p")
        ax.plot(x, np.argmin(V[row], axis=1), "r.", ms=2, label="argmin")
        ax.set_ylabel("p (px)")
        ax.set_title(title)
        fig.colorbar(im, ax=ax)
    axes[0].legend(loc="upper right", fontsize=8)
    axes[1].set_xlabel("x (px)")
    fig.tight_layout()
    return _done(fig), C[row], S[row]


def wta_vs_sgm(pair: StereoBenchmark, **options):
    """WTA on C, SGM on the same C, truth and the SGM error map; returns (fig, scores).

    ``options`` go to :func:`photolib.sgm.semi_global_matching` (default: census 7×9, P1 = 8,
    P2 = 100, P2 adapted with γ = 20, filling of invalid pixels).
    """
    kw = dict(cost="census", window=(7, 9), P1=8.0, P2=100.0, p2_gamma=20.0, fill=True)
    kw.update(options)
    r = sgm.semi_global_matching(pair.left, pair.right, pair.max_disparity, return_wta=True, **kw)
    scores = {"WTA": round(bad_percent(r.wta, pair), 1), "SGM": round(bad_percent(r.disparity, pair), 1)}
    err = np.abs(r.disparity - pair.disparity)
    status = np.full(pair.left.shape, 0.0)
    status[~pair.evaluate] = np.nan
    status[pair.evaluate & (err > 2)] = 1.0
    status[pair.evaluate & np.isnan(r.disparity)] = 2.0
    fig, axes = plt.subplots(2, 2, figsize=(10, 8))
    vmax = pair.max_disparity
    panels = ((axes[0, 0], pair.disparity, "ground truth"),
              (axes[0, 1], r.wta, f"winner-takes-all on C: bad-2.0 {scores['WTA']} %"),
              (axes[1, 0], r.disparity, f"SGM, 8 paths: bad-2.0 {scores['SGM']} %"))
    for ax, d, title in panels:
        ax.imshow(d, cmap="magma", vmin=0, vmax=vmax)
        ax.set_title(title, fontsize=10)
        ax.axis("off")
    axes[1, 1].imshow(pair.left, cmap="gray")
    axes[1, 1].imshow(np.ma.masked_where(~(status > 0), status), cmap="autumn", vmin=1, vmax=2, alpha=0.8)
    axes[1, 1].set_title("SGM errors > 2 px (scored pixels)", fontsize=10)
    axes[1, 1].axis("off")
    fig.suptitle(pair.name)
    fig.tight_layout()
    return _done(fig), scores


def normal_case_pair(shape=(300, 300), base=40.0, seed=1):
    """A rendered normal-case pair over the synthetic town: vertical images, base along X.

    Returns ``(scene, io, eo1, eo2, left, right, pixel_size, (dmin, dmax))``; f = 35 mm,
    Δ = 0.04 mm, flying height 250 m above the 100 m datum (GSD ≈ 0.29 m).
    """
    from ...synthetic import render_image, terrain_scene
    scene = terrain_scene(extent=120.0, spacing=0.5, n_buildings=4, n_trees=3, seed=seed)
    io = InteriorOrientation(35.0)
    pixel = 0.04
    eo1 = ExteriorOrientation(60.0 - base / 2, 60.0, 350.0)
    eo2 = ExteriorOrientation(60.0 + base / 2, 60.0, 350.0)
    left = render_image(scene, io, eo1, shape, pixel_size=pixel, noise=0.01, seed=1).image
    right = render_image(scene, io, eo2, shape, pixel_size=pixel, noise=0.01, seed=2).image
    zlo, zhi = float(scene.surface.min()), float(scene.surface.max())
    p = [io.f * base / (350.0 - z) / pixel for z in (zlo, zhi)]
    return scene, io, eo1, eo2, left, right, pixel, (int(np.floor(p[0])) - 2, int(np.ceil(p[1])) + 2)


def point_cloud(data=None, step=2):
    """SGM on the rendered pair → :func:`photolib.sgm.disparity_to_points`; returns
    (fig, stats) with the median |Z error| and the share of points within 0.5 m of the surface."""
    scene, io, eo1, eo2, left, right, pixel, (dmin, dmax) = data or normal_case_pair()
    r = sgm.semi_global_matching(left * 255, right * 255, dmax, min_disparity=dmin, cost="census",
                                 window=(5, 5), P1=8.0, P2=64.0)
    P = sgm.disparity_to_points(r.disparity, eo1, eo2, io, pixel)
    ok = np.isfinite(P[..., 2])
    pts = P[ok]
    truth = scene.surface_at(pts[:, 0], pts[:, 1])
    err = pts[:, 2] - truth
    good = np.isfinite(err)
    stats = {"points": int(ok.sum()), "median_abs_dz_m": round(float(np.median(np.abs(err[good]))), 2),
             "within_0.5m_percent": round(float(100 * np.mean(np.abs(err[good]) < 0.5)), 1)}
    fig = plt.figure(figsize=(11, 4.5))
    ax = fig.add_subplot(1, 2, 1, projection="3d")
    sel = pts[::step]
    ax.scatter(sel[:, 0], sel[:, 1], sel[:, 2], c=sel[:, 2], s=0.5, cmap="terrain")
    ax.set_xlabel("X (m)")
    ax.set_ylabel("Y (m)")
    ax.set_zlabel("Z (m)")
    ax.set_title(f"dense cloud: {stats['points']} points")
    ax2 = fig.add_subplot(1, 2, 2)
    sc = ax2.scatter(pts[good, 0], pts[good, 1], c=np.clip(err[good], -2, 2), s=0.5, cmap="coolwarm")
    fig.colorbar(sc, ax=ax2, label="Z − true surface (m)")
    ax2.set_aspect("equal")
    ax2.set_title(f"median |ΔZ| {stats['median_abs_dz_m']} m")
    fig.tight_layout()
    return _done(fig), stats


def voxel_scene(shape=(300, 300), seed=1):
    """Three vertical images over the synthetic town (bases 25 m, f = 35 mm, Δ = 0.025 mm,
    H = 250 m) and a voxel grid over a building: returns
    ``(images, eos, io, pixel, X, Y, Z, truth, far)``; ``far`` marks nodes > 2 m from walls."""
    from ...synthetic import render_image, terrain_scene
    scene = terrain_scene(extent=120.0, spacing=0.5, n_buildings=4, n_trees=0, seed=seed)
    io = InteriorOrientation(35.0)
    pixel = 0.025
    eos = [ExteriorOrientation(60.0 + dx, 45.0, 350.0) for dx in (-25.0, 0.0, 25.0)]
    images = [render_image(scene, io, e, shape, pixel_size=pixel, noise=0.01, seed=i).image
              for i, e in enumerate(eos)]
    X = np.arange(40.0, 80.0, 0.5)                 # around the building at X 45–73, Y 28–43
    Y = np.arange(24.0, 62.0, 0.5)
    GX, GY = np.meshgrid(X, Y)
    truth = scene.surface_at(GX, GY)
    dist = scene.discontinuity_distance()
    idx_r = np.rint((GY - scene.y[0]) / scene.spacing).astype(int)
    idx_c = np.rint((GX - scene.x[0]) / scene.spacing).astype(int)
    far = dist[idx_r, idx_c] > 2.0
    Z = np.arange(np.floor(truth.min()) - 2, np.ceil(truth.max()) + 2, 0.25)
    return images, eos, io, pixel, X, Y, Z, truth, far


def voxel_dsm(data=None, cost="ad"):
    """§6.5: truth, voxel WTA, voxel SGM and the SGM error; returns (fig, stats)."""
    images, eos, io, pixel, X, Y, Z, truth, far = data or voxel_scene()
    r = sgm.voxel_sgm(images, eos, io, pixel, X, Y, Z, cost=cost)
    stats = {}
    for name, z in (("WTA", r.Z_wta), ("SGM", r.Z)):
        e = np.abs(z - truth)[far]
        stats[name] = {"median_abs_dz_m": round(float(np.median(e)), 2),
                       "within_0.5m_percent": round(float(100 * np.mean(e < 0.5)), 1)}
    fig, axes = plt.subplots(1, 4, figsize=(15, 3.8))
    ext = (X[0], X[-1], Y[0], Y[-1])
    lo, hi = float(np.nanmin(truth)), float(np.nanmax(truth))
    for ax, z, title in ((axes[0], truth, "true DSM"), (axes[1], r.Z_wta, "voxel WTA"),
                         (axes[2], r.Z, f"voxel SGM ({cost})")):
        im = ax.imshow(z, origin="lower", extent=ext, cmap="terrain", vmin=lo, vmax=hi)
        ax.set_title(title)
    fig.colorbar(im, ax=axes[2], label="Z (m)")
    im = axes[3].imshow(np.clip(r.Z - truth, -2, 2), origin="lower", extent=ext, cmap="coolwarm")
    axes[3].set_title("SGM − truth (m)")
    fig.colorbar(im, ax=axes[3])
    fig.tight_layout()
    return _done(fig), stats
