"""GeoTIFF, CRS work and tiled orthorectification — Chapter 7, §7.3 (photolib.georaster).

Expected values come from independent implementations (rasterio/GDAL reading the files back;
PROJ's own vgridshift on the EGM96 grid; GDAL's RPC transformer through rasterio), known
geodetic facts (UTM 31N's central meridian maps to easting 500 000 m), synthetic ground truth
(a DEM linear in longitude and latitude, which bilinear interpolation reproduces exactly) and the
in-memory :func:`photolib.rectify.orthorectify` for the tiled version.
"""

import numpy as np
import pytest

rasterio = pytest.importorskip("rasterio")
pyproj = pytest.importorskip("pyproj")
da = pytest.importorskip("dask.array")

from photolib import datasets, georaster as g  # noqa: E402
from photolib.camera import ExteriorOrientation, InteriorOrientation  # noqa: E402
from photolib.errors import InputError  # noqa: E402
from photolib.rectify import RasterGrid, dem_height, frame_projector, orthorectify  # noqa: E402
from photolib.rpc import locate, project as rpc_project  # noqa: E402


def ventoux(side="left"):
    try:
        return g.ventoux_scene(side)
    except datasets.DataUnavailableError as missing:
        pytest.skip(f"real data absent (../shared/data or PHOTOLIB_DATA): {missing}")


# ----------------------------------------------------------------------------- GeoTIFF
def test_geotiff_round_trip_read_back_by_rasterio(tmp_path):
    grid = RasterGrid(675000.0, 4897500.0, (0.5, 0.75), (33, 47))
    values = np.random.default_rng(0).random((33, 47))
    values[3, 4] = np.nan
    path = g.write_geotiff(tmp_path / "o.tif", values, grid, "EPSG:32631", nodata=-9999.0)
    with rasterio.open(path) as src:               # an independent (QGIS-compatible) reader
        assert src.crs.to_epsg() == 32631
        assert src.transform.to_gdal() == (675000.0, 0.5, 0.0, 4897500.0, 0.0, -0.75)
        assert src.nodata == -9999.0 and src.count == 1
        back = src.read(1)
    assert back[3, 4] == -9999.0
    np.testing.assert_array_equal(back[~np.isnan(values)], values[~np.isnan(values)])
    array, grid_back, crs = g.read_geotiff(path, nodata_to_nan=True)
    assert grid_back == grid and crs.to_epsg() == 32631
    np.testing.assert_array_equal(np.isnan(array), np.isnan(values))


def test_geotiff_bands_and_integer_types(tmp_path):
    grid = RasterGrid(10.0, 20.0, 1.0, (300, 260))          # ≥ one 256 block: tiled file
    rgb = np.random.default_rng(1).integers(0, 65535, (300, 260, 3)).astype(np.uint16)
    path = g.write_geotiff(tmp_path / "rgb.tif", rgb, grid, 3857)
    with rasterio.open(path) as src:
        assert src.count == 3 and src.dtypes[0] == "uint16" and src.block_shapes[0] == (256, 256)
        np.testing.assert_array_equal(np.moveaxis(src.read(), 0, 2), rgb)
    array, _, _ = g.read_geotiff(path)
    assert array.dtype == np.uint16 and np.array_equal(array, rgb)
    np.testing.assert_array_equal(g.read_geotiff(path, band=2)[0], rgb[:, :, 1])


def test_geotiff_without_crs_is_refused_unless_allowed(tmp_path):
    path = tmp_path / "plain.tif"
    with rasterio.open(path, "w", driver="GTiff", height=2, width=2, count=1, dtype="float32",
                       transform=rasterio.Affine(1, 0, 0, 0, -1, 2)) as dst:
        dst.write(np.ones((1, 2, 2), np.float32))
    with pytest.raises(InputError, match="no coordinate reference system"):
        g.read_geotiff(path)
    assert g.read_geotiff(path, crs=None)[2] is None
    assert g.read_geotiff(path, crs="EPSG:32631")[2].to_epsg() == 32631


# ----------------------------------------------------------------------------- CRS work
def test_utm_central_meridian_and_gauss_krueger_round_trip():
    x, y = g.transform_points(3.0, 0.0, "EPSG:4326", "EPSG:32631")
    assert abs(x - 500000.0) < 1e-6 and abs(y) < 1e-6
    # §7.3's map-projection variant: Gauss–Krüger (Pulkovo 1942 zone 6, central meridian 33°E)
    x, y = g.transform_points(33.0, 55.0, "EPSG:4284", "EPSG:28406")
    assert abs(x - 6500000.0) < 1e-6                     # zone number · 10⁶ + 500 km false easting
    lon, lat = g.transform_points(x, y, "EPSG:28406", "EPSG:4284")
    assert abs(lon - 33.0) < 1e-10 and abs(lat - 55.0) < 1e-10


def test_lattice_transform_is_within_its_tolerance_and_tile_invariant():
    grid = RasterGrid(675000.5, 4897500.0, 0.5, (150, 170))
    X, Y = grid.centres()
    exact = g.grid_centres_in(grid, 32631, 4326)
    approx = g._fast_transform(X, Y, 32631, 4326, 1e-4)
    err = np.hypot((approx[0] - exact[0]) * 111320 * np.cos(np.radians(44.2)), (approx[1] - exact[1]) * 111320)
    assert err.max() < 1e-4
    tile = grid.window(40, 70, 50, 60)
    part = g._fast_transform(*tile.centres(), 32631, 4326, 1e-4)
    np.testing.assert_array_equal(part[0], approx[0][40:90, 70:130])
    np.testing.assert_array_equal(part[1], approx[1][40:90, 70:130])


def test_dem_on_grid_reproduces_a_dem_linear_in_lon_lat():
    dem_grid = RasterGrid(5.0, 44.5, 0.001, (500, 500))
    lon, lat = dem_grid.centres()
    dem = 300.0 + 2000.0 * (lon - 5.2) - 3000.0 * (lat - 44.2)
    grid = RasterGrid(675000.0, 4897500.0, 2.0, (60, 70))
    heights = g.dem_on_grid(dem, dem_grid, 4326, grid, 32631, transform_tolerance=None)
    glon, glat = g.grid_centres_in(grid, 32631, 4326)
    np.testing.assert_allclose(heights, 300.0 + 2000.0 * (glon - 5.2) - 3000.0 * (glat - 44.2), atol=1e-9)
    geoid = g.GeoidModel(np.full((4, 4), 50.0), RasterGrid(4.5, 45.0, 0.5, (4, 4)))
    np.testing.assert_allclose(g.dem_on_grid(dem, dem_grid, 4326, grid, 32631, geoid), heights + 50.0, atol=1e-6)


def test_dem_not_covering_the_grid_names_the_area():
    dem_grid = RasterGrid(5.0, 44.5, 0.001, (10, 10))
    with pytest.raises(InputError, match="does not cover"):
        g.dem_on_grid(np.zeros((10, 10)), dem_grid, 4326, RasterGrid(675000.0, 4897500.0, 2.0, (5, 5)), 32631)


def test_geoid_wraps_around_the_antimeridian():
    values = np.arange(4 * 8, dtype=float).reshape(4, 8)
    geoid = g.GeoidModel(values, RasterGrid(-180.0 - 22.5, 90.0 + 30, 45.0, (4, 8)))
    assert geoid.global_longitudes
    # node longitudes −180, −135, …, 135: between the last column and the first, across ±180°
    mid = geoid.undulation_at(157.5, 52.5)
    assert float(mid) == pytest.approx((values[1, 7] + values[1, 0]) / 2)
    assert float(geoid.undulation_at(-202.5, 52.5)) == pytest.approx(float(mid))
    assert float(geoid.undulation_at(180.0, 52.5)) == values[1, 0]


# ----------------------------------------------------------------------------- real data
def test_egm96_bilinear_matches_proj_vgridshift():
    scene = ventoux()
    gtx = datasets.data_path("satellite", "pleiades_ventoux", "egm96_15.gtx")
    proj = pyproj.Transformer.from_pipeline(
        f"+proj=pipeline +step +proj=unitconvert +xy_in=deg +xy_out=rad "
        f"+step +proj=vgridshift +grids={gtx} +multiplier=1 +step +proj=unitconvert +xy_in=rad +xy_out=deg")
    rng = np.random.default_rng(3)
    lon = np.r_[rng.uniform(5.0, 5.5, 50), rng.uniform(-179.9, 179.9, 50)]
    lat = np.r_[rng.uniform(44.0, 44.4, 50), rng.uniform(-80, 80, 50)]
    expected = proj.transform(lon, lat, np.zeros_like(lon))[2]
    np.testing.assert_allclose(scene.geoid.undulation_at(lon, lat), expected, atol=1e-4)
    n = float(scene.geoid.undulation_at(5.2, 44.2))
    assert 45.0 < n < 55.0                               # "about 50 m here" (data README)


def test_srtm_tile_reads_with_its_grid():
    scene = ventoux()
    assert scene.dem.shape == (1201, 1201) and scene.dem_crs.to_epsg() == 4326
    assert scene.dem_grid.xy(0, 0) == pytest.approx((5.0, 45.0))
    assert scene.crop_offset == (5000.0, 5000.0)


def test_rpc_projector_against_gdal_rpc_transformer():
    scene = ventoux()
    from rasterio.rpc import RPC as RasterioRPC
    from rasterio.transform import RPCTransformer
    rpc = scene.rpc
    rng = np.random.default_rng(4)
    rows, cols = rng.uniform(0, 499, 40), rng.uniform(0, 499, 40)
    h = rng.uniform(400, 1200, 40)
    lon, lat = locate(rpc, rows, cols, h)
    # GDAL's pixel → ground iteration stops at 0.1 px by default: ask it for full precision
    with RPCTransformer(RasterioRPC.from_gdal(rpc.to_gdal_metadata()), RPC_PIXEL_ERROR_THRESHOLD=1e-8,
                        RPC_MAX_ITERATIONS=100) as gdal:
        g_rows, g_cols = gdal.rowcol(lon, lat, zs=h, op=lambda v: v)            # ground → image
        g_lon, g_lat = gdal.xy(rows + 0.5, cols + 0.5, zs=h, offset="ul")       # image → ground
    # GDAL's pixel coordinates are ours + 0.5; round trips through both < 1e-6 px
    assert np.max(np.abs(np.asarray(g_rows) - 0.5 - rows)) < 1e-6
    assert np.max(np.abs(np.asarray(g_cols) - 0.5 - cols)) < 1e-6
    back_rows, back_cols = rpc_project(rpc, np.asarray(g_lon), np.asarray(g_lat), h)
    assert np.max(np.hypot(back_rows - rows, back_cols - cols)) < 1e-6
    # the projector on a UTM grid = pyproj + photolib.rpc.project (+ the geoid)
    X, Y = g.transform_points(lon, lat, 4326, 32631)
    for tolerance in (None, 1e-4):
        pr, pc = g.rpc_projector(rpc, 32631, scene.geoid, transform_tolerance=tolerance)(X, Y, h - 50.0)
        er, ec = rpc_project(rpc, lon, lat, h - 50.0 + scene.geoid.undulation_at(lon, lat))
        assert np.max(np.hypot(pr - er, pc - ec)) < 1e-6


def test_mean_height_instead_of_terrain_moves_the_ground_point_about_90_m():
    scene = ventoux()
    row, col = 250.0, 250.0
    lon, lat = locate(scene.rpc, row, col, scene.rpc.height_off)
    mean_xy = g.transform_points(lon, lat, 4326, 32631)
    h = scene.rpc.height_off
    for _ in range(20):                                   # monoplotting on SRTM + EGM96
        lon, lat = locate(scene.rpc, row, col, h)
        h = float(scene.geoid.ellipsoidal(dem_height(scene.dem, scene.dem_grid, lon, lat), lon, lat))
    terrain_xy = g.transform_points(lon, lat, 4326, 32631)
    shift = float(np.hypot(mean_xy[0] - terrain_xy[0], mean_xy[1] - terrain_xy[1]))
    assert 400.0 < h < 700.0 and 70.0 < shift < 110.0


def test_ventoux_tiled_equals_in_memory():
    scene = ventoux()
    grid = RasterGrid(675240.0, 4897430.0, 0.5, (300, 330))
    Z = g.dem_on_grid(scene.dem, scene.dem_grid, scene.dem_crs, grid, 32631, geoid=scene.geoid)
    project = g.rpc_projector(scene.rpc, 32631)
    whole = orthorectify(scene.image, project, Z, grid, grid)
    tiled = g.orthorectify_tiled(scene.image_path, project, Z, grid, grid, tile=128)
    np.testing.assert_array_equal(tiled, whole)
    assert 0.2 < np.isfinite(whole).mean() < 1.0


# ----------------------------------------------------------------------------- tiling
def frame_scene(bands=False):
    rng = np.random.default_rng(5)
    image = rng.random((180, 200) + ((3,) if bands else ()))
    io = InteriorOrientation(f=50.0)
    eo = ExteriorOrientation(100.0, 90.0, 600.0, 0.05, -0.03, 0.2)
    project = frame_projector(eo, io, 0.05, image.shape[:2])
    dem_grid = RasterGrid(-80.0, 300.0, 5.0, (80, 80))
    dX, dY = dem_grid.centres()
    dem = 40.0 * np.sin(dX / 50.0) * np.cos(dY / 70.0) + 0.1 * dX
    grid = RasterGrid(-10.0, 200.0, 0.7, (201, 259))
    return image, project, dem, dem_grid, grid


@pytest.mark.parametrize("method", ["nearest", "bilinear", "bicubic"])
@pytest.mark.parametrize("tile", [37, 64])
def test_tiled_equals_in_memory_on_a_frame_image(method, tile):
    image, project, dem, dem_grid, grid = frame_scene()
    whole = orthorectify(image, project, dem, dem_grid, grid, method)
    tiled = g.orthorectify_tiled(image, project, dem, dem_grid, grid, method, tile=tile)
    assert np.isfinite(whole).mean() > 0.2 and np.isnan(whole).any()      # edges of the image inside
    np.testing.assert_allclose(tiled, whole, rtol=0, atol=1e-12)
    np.testing.assert_array_equal(np.isnan(tiled), np.isnan(whole))


def test_tiled_sources_bands_progress_and_geotiff(tmp_path):
    image, project, dem, dem_grid, grid = frame_scene(bands=True)
    whole = orthorectify(image, project, dem, dem_grid, grid)
    calls = []
    lazy = da.from_array(image, chunks=(50, 60, 3))
    tiled = g.orthorectify_tiled(lazy, project, da.from_array(dem, chunks=30), dem_grid, grid, tile=70,
                                 progress=lambda done, total: calls.append((done, total)))
    np.testing.assert_allclose(tiled, whole, rtol=0, atol=1e-12)
    assert calls and calls[-1][0] == calls[-1][1]
    src = g.write_geotiff(tmp_path / "src.tif", image, RasterGrid(0, 0, 1, image.shape[:2]), 3857)
    from_file = g.orthorectify_tiled(src, project, dem, dem_grid, grid, tile=70, compute=False)
    assert isinstance(from_file, da.Array) and from_file.numblocks == (3, 4, 1)
    np.testing.assert_allclose(from_file.compute(), whole, rtol=0, atol=1e-12)
    out = g.orthorectify_tiled(image, project, dem, dem_grid, grid, tile=70, out_path=tmp_path / "o.tif",
                               crs="EPSG:32631", nodata=-1.0)
    with rasterio.open(out) as written:
        assert written.crs.to_epsg() == 32631 and written.transform.to_gdal() == grid.geotransform
        back = np.moveaxis(written.read(), 0, 2)
    np.testing.assert_allclose(back, np.where(np.isnan(whole), -1.0, whole), rtol=0, atol=1e-12)


def test_a_window_planned_too_small_is_enlarged():
    image, project, dem, dem_grid, grid = frame_scene()

    def wavy(X, Y, Z):          # bends strongly inside a tile: the corner/edge plan misses it
        rows, cols = project(X, Y, Z)
        bump = 25.0 * np.exp(-((X - 80.0) ** 2 + (Y - 120.0) ** 2) / 50.0)
        return rows + bump, cols - bump

    whole = orthorectify(image, wavy, dem, dem_grid, grid)
    tiled = g.orthorectify_tiled(image, wavy, dem, dem_grid, grid, tile=64, margin=0)
    np.testing.assert_allclose(tiled, whole, rtol=0, atol=1e-12)


def test_plan_tiles_windows_contain_every_position():
    image, project, dem, dem_grid, grid = frame_scene()
    plans = g.plan_tiles(project, dem, dem_grid, grid, image.shape, tile=64)
    assert len(plans) == 4 * 5 and plans[5].row0 == 64 and plans[5].col0 == 0
    for plan in plans:
        X, Y = plan.grid.centres()
        Z = dem_height(dem, dem_grid, X, Y)
        rows, cols = project(X, Y, Z)
        near = (rows > 0) & (rows < image.shape[0] - 1) & (cols > 0) & (cols < image.shape[1] - 1)
        if near.any():
            r0, r1, c0, c1 = plan.image_window
            assert r0 <= rows[near].min() - 1 or r0 == 0
            assert rows[near].max() + 1 <= r1 - 1 or r1 == image.shape[0]
            assert c0 <= cols[near].min() - 1 or c0 == 0
            assert cols[near].max() + 1 <= c1 - 1 or c1 == image.shape[1]
        dr0, dr1, dc0, dc1 = plan.dem_window
        window = dem_grid.window(dr0, dc0, dr1 - dr0, dc1 - dc0)
        dem_height(dem[dr0:dr1, dc0:dc1], window, X, Y)     # covers the tile: no error


@pytest.mark.parametrize("fill_gaps", [True, False])
def test_mosaic_tiled_equals_rectify_mosaic(tmp_path, fill_gaps):
    from photolib.rectify import mosaic
    rng = np.random.default_rng(8)
    grids = [RasterGrid(0.0, 60.0, 0.5, (100, 90)), RasterGrid(30.0, 62.0, 0.5, (110, 80)),
             RasterGrid(55.0, 58.0, 0.5, (90, 70))]
    orthos = [rng.random(g.shape) for g in grids]
    orthos[1][40:50, 10:30] = np.nan                              # a gap the others may fill
    cutlines = [[[38.3, 0.0], [41.7, 70.0]], [[62.2, 0.0], [60.9, 70.0]]]
    whole, grid = mosaic(orthos, grids, cutlines, fill_gaps=fill_gaps)
    tiled, tiled_grid = g.mosaic_tiled(orthos, grids, cutlines, tile=37, fill_gaps=fill_gaps)
    assert tiled_grid == grid
    np.testing.assert_array_equal(tiled, whole)
    paths = [g.write_geotiff(tmp_path / f"o{k}.tif", np.where(np.isnan(o), -9999.0, o), gr, 32631, nodata=-9999.0)
             for k, (o, gr) in enumerate(zip(orthos, grids))]
    from_files, file_grid = g.mosaic_tiled(paths, None, cutlines, tile=64, fill_gaps=fill_gaps)
    assert file_grid == grid
    np.testing.assert_array_equal(from_files, whole)
