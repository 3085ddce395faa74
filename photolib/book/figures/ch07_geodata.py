"""Figures for Chapter 7, §7.3 in a map projection: the Ventoux RPC orthophoto against GDAL's,
and the tiles of the out-of-core orthorectification.

* :func:`footprint_grid` — the UTM 31N grid covering the Ventoux crop on the terrain;
* :func:`gdal_orthophoto` — GDAL's RPC orthorectification (``rasterio.warp.reproject`` with
  ``RPC_DEM`` pointing at SRTM + EGM96 written as ellipsoidal heights);
* :func:`ventoux_vs_gdal` — photolib's orthophoto beside GDAL's and the map of their position
  difference (index images: each orthophoto pixel holds the source row/column it used);
* :func:`tile_layout` — output tiles with their DEM windows (halo) and the image windows they read.

Every figure function returns the matplotlib Figure (closed, so that a notebook shows it once)
together with the numbers it shows, rounded.
"""

from __future__ import annotations

import os
import tempfile

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.patches import Rectangle

from ... import georaster as g
from ...rectify import RasterGrid, dem_height, orthorectify
from ...rpc import locate

UTM31N = "EPSG:32631"


def _done(fig):
    plt.close(fig)
    return fig


def footprint_grid(scene, pixel_size=0.5, pad=5.0):
    """The UTM 31N grid (origin on pixel multiples) covering the crop's border monoplotted on SRTM + EGM96."""
    n = 50
    edge = np.linspace(0, scene.image.shape[0] - 1, n)
    last = scene.image.shape[0] - 1
    rows = np.r_[np.zeros(n), np.full(n, last), edge, edge]
    cols = np.r_[edge, edge, np.zeros(n), np.full(n, last)]
    h = np.full(rows.shape, scene.rpc.height_off)
    for _ in range(20):
        lon, lat = locate(scene.rpc, rows, cols, h)
        h = scene.geoid.ellipsoidal(dem_height(scene.dem, scene.dem_grid, lon, lat), lon, lat)
    x, y = g.transform_points(lon, lat, 4326, UTM31N)
    return RasterGrid.aligned(x.min() - pad, y.min() - pad, x.max() + pad, y.max() + pad, pixel_size)


def photolib_orthophoto(scene, grid, image=None):
    """photolib: SRTM + EGM96 at the output centres → RPC projector → orthorectify (bilinear)."""
    heights = g.dem_on_grid(scene.dem, scene.dem_grid, scene.dem_crs, grid, UTM31N, geoid=scene.geoid)
    return orthorectify(scene.image if image is None else image, g.rpc_projector(scene.rpc, UTM31N),
                        heights, grid, grid, "bilinear")


def ellipsoidal_dem_file(scene, folder=None):
    """SRTM + EGM96 undulation at the SRTM nodes, as a GeoTIFF for GDAL's RPC_DEM."""
    folder = folder or tempfile.mkdtemp(prefix="ventoux_dem_")
    lon, lat = scene.dem_grid.centres()
    return g.write_geotiff(os.path.join(folder, "srtm_ellipsoidal.tif"), scene.geoid.ellipsoidal(scene.dem, lon, lat),
                           scene.dem_grid, "EPSG:4326", nodata=-32768.0)


def gdal_orthophoto(scene, grid, dem_path, image=None, tolerance=0.125):
    """GDAL's RPC orthorectification on the same grid (bilinear; RPC_DEM = ellipsoidal heights)."""
    import rasterio
    from rasterio.rpc import RPC as RasterioRPC
    from rasterio.warp import Resampling, reproject

    source = scene.image if image is None else image
    out = np.full(grid.shape, np.nan)
    reproject(np.ascontiguousarray(source, dtype=np.float64), out,
              rpcs=RasterioRPC.from_gdal(scene.rpc.to_gdal_metadata()), src_crs="EPSG:4326", dst_crs=UTM31N,
              dst_transform=rasterio.Affine.from_gdal(*grid.geotransform), resampling=Resampling.bilinear,
              dst_nodata=np.nan, RPC_DEM=str(dem_path), tolerance=tolerance)
    return out


def ventoux_vs_gdal(scene, pixel_size=0.5):
    """photolib's orthophoto, GDAL's, and the position difference map; returns (fig, numbers)."""
    grid = footprint_grid(scene, pixel_size)
    dem_path = ellipsoidal_dem_file(scene)
    ours, theirs = photolib_orthophoto(scene, grid), gdal_orthophoto(scene, grid, dem_path)
    R, C = np.indices(scene.image.shape, dtype=np.float64)
    pr, pc = photolib_orthophoto(scene, grid, R), photolib_orthophoto(scene, grid, C)
    gr, gc = gdal_orthophoto(scene, grid, dem_path, R), gdal_orthophoto(scene, grid, dem_path, C)
    last = scene.image.shape[0] - 2
    inside = (pr >= 1) & (pr <= last) & (pc >= 1) & (pc <= last) & np.isfinite(gr) & np.isfinite(gc)
    diff = np.where(inside, np.hypot(pr - gr, pc - gc), np.nan)
    d = diff[inside]
    numbers = {"grid": f"{grid.shape[0]} × {grid.shape[1]} px of {grid.dx} m",
               "max_px": float(d.max()), "p99_px": float(np.percentile(d, 99)),
               "rms_px": float(np.sqrt(np.mean(d ** 2))), "pixels": int(d.size)}
    extent = (grid.extent[0], grid.extent[2], grid.extent[1], grid.extent[3])
    fig, axes = plt.subplots(1, 3, figsize=(13, 4.4))
    lo, hi = np.nanpercentile(ours, [1, 99])
    for ax, img, title in ((axes[0], ours, "photolib (RPC + SRTM + EGM96)"), (axes[1], theirs, "GDAL (RPC_DEM)")):
        ax.imshow(img, cmap="gray", vmin=lo, vmax=hi, extent=extent)
        ax.set_title(title)
        ax.set_xlabel("E, m (UTM 31N)")
    axes[0].set_ylabel("N, m")
    im = axes[2].imshow(diff, cmap="magma", extent=extent, vmin=0)
    axes[2].set_title("position difference, px")
    fig.colorbar(im, ax=axes[2], shrink=0.8, format="%.1e")
    for ax in axes:
        ax.ticklabel_format(useOffset=False, style="plain")
        ax.tick_params(labelsize=7)
    fig.tight_layout()
    return _done(fig), numbers


def tile_layout(image_shape, project, dem, dem_grid, grid, tile=64, halo=2):
    """Output tiles (object space) with their DEM windows, and the image windows they read."""
    plans = g.plan_tiles(project, dem, dem_grid, grid, image_shape, tile=tile, halo=halo)
    fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4.8))
    colours = plt.cm.tab20(np.linspace(0, 1, len(plans)))
    for plan, colour in zip(plans, colours):
        x0, y0, x1, y1 = plan.grid.extent
        left.add_patch(Rectangle((x0, y0), x1 - x0, y1 - y0, fill=True, alpha=0.35, color=colour, lw=0))
        dr0, dr1, dc0, dc1 = plan.dem_window
        dx0, dy0, dx1, dy1 = dem_grid.window(dr0, dc0, dr1 - dr0, dc1 - dc0).extent
        left.add_patch(Rectangle((dx0, dy0), dx1 - dx0, dy1 - dy0, fill=False, color=colour, lw=0.8, ls="--"))
        if plan.image_window is not None:
            r0, r1, c0, c1 = plan.image_window
            right.add_patch(Rectangle((c0 - 0.5, r0 - 0.5), c1 - c0, r1 - r0, fill=True, alpha=0.25, color=colour))
            right.add_patch(Rectangle((c0 - 0.5, r0 - 0.5), c1 - c0, r1 - r0, fill=False, color=colour, lw=0.8))
    ex = grid.extent
    left.set_xlim(ex[0] - 3 * dem_grid.dx, ex[2] + 3 * dem_grid.dx)
    left.set_ylim(ex[1] - 3 * dem_grid.dy, ex[3] + 3 * dem_grid.dy)
    left.set_aspect("equal")
    left.set_title(f"{len(plans)} output tiles (filled) and their DEM windows\n(dashed: + {halo} DEM cells of halo)")
    left.set_xlabel("X, m")
    left.set_ylabel("Y, m")
    right.set_xlim(-0.5, image_shape[1] - 0.5)
    right.set_ylim(image_shape[0] - 0.5, -0.5)
    right.set_aspect("equal")
    right.set_title("image windows read by the tiles\n(border + lattice at min/max DEM height, + margin)")
    right.set_xlabel("col")
    right.set_ylabel("row")
    fig.tight_layout()
    areas = [(p.image_window[1] - p.image_window[0]) * (p.image_window[3] - p.image_window[2])
             for p in plans if p.image_window is not None]
    numbers = {"tiles": len(plans), "tiles_reading_the_image": len(areas),
               "pixels_read_over_image": round(sum(areas) / (image_shape[0] * image_shape[1]), 2)}
    return _done(fig), numbers
