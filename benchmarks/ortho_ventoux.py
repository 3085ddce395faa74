"""RPC orthorectification of the Pléiades Ventoux crop (Chapter 7, §7.3; RPC §8.5): photolib vs GDAL.

One run, the same inputs and the same output grid for both tools:

* image: ``left_image.tif`` (500 × 500, uint16), RPC of the full scene shifted by the crop
  offset from the GeoTIFF transform (row 5000, col 5000);
* terrain: SRTM 3″ ``N44E005.hgt`` (heights above the EGM96 geoid) + the EGM96 undulation from
  ``egm96_15.gtx`` (≈ 50 m here) = ellipsoidal heights, as the RPC wants;
* output grid: UTM 31N (EPSG:32631), 0.5 m pixels, origin on multiples of 0.5 m, covering the
  crop's footprint on the terrain; bilinear resampling in both tools.

photolib: :func:`photolib.georaster.dem_on_grid` (SRTM bilinear in longitude/latitude at each
output centre + EGM96) → :func:`photolib.georaster.rpc_projector` → 
:func:`photolib.rectify.orthorectify`.

GDAL (through ``rasterio.warp.reproject(rpcs=…, RPC_DEM=…)``): GDAL's RPC transformer takes the
RPC_DEM values as heights in the RPC's own vertical reference (ellipsoidal), scaled by
RPC_HEIGHT_SCALE and offset by RPC_HEIGHT. ``RPC_DEM_APPLY_VDATUM_SHIFT`` (default TRUE) would
convert a DEM that *declares* a geoid vertical CRS (e.g. EPSG:4326+5773) through PROJ, which
needs PROJ's EGM96 grid (not installed offline here); the ``.hgt`` tile declares plain EPSG:4326,
so GDAL would use its heights as ellipsoidal ones — 50 m too low. So the benchmark writes an
ellipsoidal DEM (SRTM + N at the SRTM nodes, float64, EPSG:4326, the SRTM grid) to a temporary
GeoTIFF and points RPC_DEM at it (bilinear DEM interpolation, GDAL's default). GDAL is timed with
its default approximate transformer (0.125 px error threshold) and also run exactly
(``tolerance=0``) for the comparison.

Positions, not only brightness: both tools also orthorectify two index images (the row and the
column number of every source pixel); bilinear interpolation of a linear function is exact, so
each orthophoto pixel then holds the source position that the tool used. Statistics are over
pixels where both tools have data and the positions lie ≥ 1 px inside the image (GDAL treats the
outer half pixel differently). The forward maps are also compared without any resampling:
``RPCTransformer(RPC_DEM=…)`` vs the photolib projector at the output centres.

Times: median of ``--repeats`` runs each, wall clock, inputs in memory, after one warm-up run
(numba compilation, PROJ database). Run: ``python benchmarks/ortho_ventoux.py [--repeats 5]``.
"""

from __future__ import annotations

import argparse
import os
import platform
import statistics
import tempfile
import time
import warnings

import numpy as np


def footprint_grid(scene, pixel_size=0.5, pad=5.0):
    """The UTM 31N grid covering the crop's footprint on the terrain (monoplotting the border)."""
    from photolib import georaster as g
    from photolib.rectify import RasterGrid, dem_height
    from photolib.rpc import locate

    n = 50
    edge = np.linspace(0, 499, n)
    rows = np.r_[np.zeros(n), np.full(n, 499.0), edge, edge]
    cols = np.r_[edge, edge, np.zeros(n), np.full(n, 499.0)]
    h = np.full(rows.shape, scene.rpc.height_off)
    for _ in range(20):
        lon, lat = locate(scene.rpc, rows, cols, h)
        h = scene.geoid.ellipsoidal(dem_height(scene.dem, scene.dem_grid, lon, lat), lon, lat)
    x, y = g.transform_points(lon, lat, 4326, 32631)
    return RasterGrid.aligned(x.min() - pad, y.min() - pad, x.max() + pad, y.max() + pad, pixel_size)


def run_photolib(scene, grid, image, tolerance=1e-4):
    from photolib import georaster as g
    from photolib.rectify import orthorectify

    heights = g.dem_on_grid(scene.dem, scene.dem_grid, scene.dem_crs, grid, 32631, geoid=scene.geoid,
                            transform_tolerance=tolerance)
    project = g.rpc_projector(scene.rpc, 32631, transform_tolerance=tolerance)
    return orthorectify(image, project, heights, grid, grid, "bilinear")


def run_gdal(scene, grid, image, dem_path, tolerance=0.125):
    import rasterio
    from rasterio.rpc import RPC as RasterioRPC
    from rasterio.warp import Resampling, reproject

    out = np.full(grid.shape, np.nan)
    reproject(np.ascontiguousarray(image, dtype=np.float64), out,
              rpcs=RasterioRPC.from_gdal(scene.rpc.to_gdal_metadata()), src_crs="EPSG:4326",
              dst_crs="EPSG:32631", dst_transform=rasterio.Affine.from_gdal(*grid.geotransform),
              resampling=Resampling.bilinear, dst_nodata=np.nan, RPC_DEM=str(dem_path), tolerance=tolerance)
    return out


def timed(fn, repeats):
    fn()                                                   # warm-up
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - start)
    return statistics.median(times), out


def stats(values):
    a = np.abs(values[np.isfinite(values)])
    return dict(max=float(a.max()), p99=float(np.percentile(a, 99)), rms=float(np.sqrt(np.mean(a ** 2))), n=int(a.size))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--repeats", type=int, default=5)
    args = parser.parse_args()
    warnings.simplefilter("ignore")

    import rasterio
    from rasterio.rpc import RPC as RasterioRPC
    from rasterio.transform import RPCTransformer

    from photolib import datasets, georaster as g

    try:
        scene = g.ventoux_scene("left")
    except datasets.DataUnavailableError as missing:
        print(f"real data absent, nothing measured: {missing}")
        return
    grid = footprint_grid(scene)
    tmp = tempfile.mkdtemp(prefix="ortho_ventoux_")
    lon, lat = scene.dem_grid.centres()
    ellipsoidal = scene.geoid.ellipsoidal(scene.dem, lon, lat)
    dem_path = g.write_geotiff(os.path.join(tmp, "srtm_ellipsoidal.tif"), ellipsoidal, scene.dem_grid,
                               "EPSG:4326", nodata=-32768.0)

    t_ours, ours = timed(lambda: run_photolib(scene, grid, scene.image), args.repeats)
    t_ours_exact, ours_exact = timed(lambda: run_photolib(scene, grid, scene.image, None), args.repeats)
    t_gdal, gdal = timed(lambda: run_gdal(scene, grid, scene.image, dem_path), args.repeats)
    t_exact, _ = timed(lambda: run_gdal(scene, grid, scene.image, dem_path, 0.0), args.repeats)

    R, C = np.indices(scene.image.shape, dtype=np.float64)
    pos = {}
    for name, tol in (("gdal", 0.125), ("gdal_exact", 0.0)):
        pos[name] = (run_gdal(scene, grid, R, dem_path, tol), run_gdal(scene, grid, C, dem_path, tol))
    pos["photolib"] = (run_photolib(scene, grid, R), run_photolib(scene, grid, C))
    pr, pc = pos["photolib"]
    inside = (pr >= 1) & (pr <= 498) & (pc >= 1) & (pc <= 498)

    table = []
    for name in ("gdal", "gdal_exact"):
        gr, gc = pos[name]
        both = inside & np.isfinite(gr) & np.isfinite(gc)
        d = np.where(both, np.hypot(pr - gr, pc - gc), np.nan)
        table.append((f"position vs GDAL ({'approx. 0.125 px' if name == 'gdal' else 'exact'})", stats(d)))
    both = inside & np.isfinite(ours) & np.isfinite(gdal)
    brightness = np.where(both, ours - gdal, np.nan)
    nodata_mismatch = int((np.isfinite(ours) != np.isfinite(gdal)).sum())

    # forward maps without resampling: GDAL's RPC transformer with the same DEM at the output centres
    X, Y = grid.centres()
    glon, glat = g.transform_points(X, Y, 32631, 4326)
    with RPCTransformer(RasterioRPC.from_gdal(scene.rpc.to_gdal_metadata()), RPC_DEM=str(dem_path)) as t:
        fr, fc = t.rowcol(glon.ravel(), glat.ravel(), op=lambda v: v)
    fr = np.asarray(fr).reshape(X.shape) - 0.5
    fc = np.asarray(fc).reshape(X.shape) - 0.5
    heights = g.dem_on_grid(scene.dem, scene.dem_grid, scene.dem_crs, grid, 32631, geoid=scene.geoid)
    mr, mc = g.rpc_projector(scene.rpc, 32631)(X, Y, heights)
    forward = stats(np.hypot(mr - fr, mc - fc))

    print(f"# Ventoux RPC orthorectification, photolib vs GDAL {rasterio.__gdal_version__} "
          f"(rasterio {rasterio.__version__})\n")
    print(f"grid: UTM 31N, {grid.dx} m, {grid.shape[0]} × {grid.shape[1]} pixels, origin "
          f"({grid.x0:.1f}, {grid.y0:.1f}); {platform.machine()}, {os.cpu_count()} cores; "
          f"median of {args.repeats}\n")
    print("| compared | max | p99 | RMS | pixels |")
    print("|---|---|---|---|---|")
    for label, s in table:
        print(f"| {label}, px | {s['max']:.2e} | {s['p99']:.2e} | {s['rms']:.2e} | {s['n']} |")
    print(f"| forward maps at the output centres (no resampling), px | {forward['max']:.2e} | "
          f"{forward['p99']:.2e} | {forward['rms']:.2e} | {forward['n']} |")
    s = stats(brightness)
    print(f"| brightness vs GDAL (approx.), DN of {np.nanmax(scene.image):.0f} | {s['max']:.2e} | "
          f"{s['p99']:.2e} | {s['rms']:.2e} | {s['n']} |")
    print(f"\nnodata differs at {nodata_mismatch} of {grid.shape[0] * grid.shape[1]} pixels (image edge)\n")
    print("| tool | time (s) | ratio to GDAL |")
    print("|---|---|---|")
    print(f"| GDAL reproject, RPC_DEM, approx. transformer (default) | {t_gdal:.3f} | 1.00 |")
    print(f"| GDAL reproject, RPC_DEM, exact transformer | {t_exact:.3f} | {t_exact / t_gdal:.2f} |")
    print(f"| photolib dem_on_grid + rpc_projector + orthorectify | {t_ours:.3f} | {t_ours / t_gdal:.2f} |")
    print(f"| photolib, pyproj on every pixel (transform_tolerance=None) | {t_ours_exact:.3f} | "
          f"{t_ours_exact / t_gdal:.2f} |")
    print(f"\nphotolib approximate vs exact CRS transform: max |Δ brightness| "
          f"{np.nanmax(np.abs(ours - ours_exact)):.2e} DN")


if __name__ == "__main__":
    main()
