"""Bad-input catalogue for photolib.georaster: GeoTIFFs without CRS, bad CRSs, DEMs that do not
cover the grid, sensor models that are not callables, bad tile sizes, missing real data."""

import tempfile
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("rasterio")
pytest.importorskip("pyproj")
pytest.importorskip("dask")

from catalogue import INF, NAN, Case, check_case  # noqa: E402
from photolib import georaster as g  # noqa: E402
from photolib.datasets import DataUnavailableError  # noqa: E402
from photolib.errors import DegenerateGeometryError, InputError  # noqa: E402
from photolib.rectify import RasterGrid  # noqa: E402
from photolib.rpc import RPC  # noqa: E402

_DIR = Path(tempfile.mkdtemp(prefix="photolib_bad_georaster_"))


def _no_crs_file():
    import rasterio
    import warnings
    path = _DIR / "no_crs.tif"
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        with rasterio.open(path, "w", driver="GTiff", height=2, width=2, count=1, dtype="float32",
                           transform=rasterio.Affine(1, 0, 0, 0, -1, 2)) as dst:
            dst.write(np.ones((1, 2, 2), np.float32))
    return path


def _rotated_file():
    import rasterio
    path = _DIR / "rotated.tif"
    with rasterio.open(path, "w", driver="GTiff", height=2, width=2, count=1, dtype="float32", crs="EPSG:32631",
                       transform=rasterio.Affine(1, 0.2, 0, 0.1, -1, 2)) as dst:
        dst.write(np.ones((1, 2, 2), np.float32))
    return path


def _two_band_file():
    return g.write_geotiff(_DIR / "two.tif", np.ones((2, 2, 2)), RasterGrid(0, 2, 1, (2, 2)), 4326)


def _text_file():
    path = _DIR / "text.tif"
    path.write_text("not a raster")
    return path


def _unit(k):
    return [0.0] * k + [1.0] + [0.0] * (19 - k)


TOY_RPC = RPC(100, 200, 0, 3, 0, 50, 80, 0.01, 0.01, 500, _unit(2), _unit(0), _unit(1), _unit(0))
# a denominator 1 + L that vanishes at longitude 2.99
ZERO_DEN = RPC(100, 200, 0, 3, 0, 50, 80, 0.01, 0.01, 500, _unit(2), _unit(0) + np.r_[0, 1.0, [0] * 18],
               _unit(1), _unit(0))
GRID = RasterGrid(0.0, 10.0, 1.0, (10, 10))
UTM = RasterGrid(499000.0, 1000.0, 100.0, (3, 3))
GEOID = g.GeoidModel(np.full((3, 3), 50.0), RasterGrid(1.5, 1.5, 1.0, (3, 3)))
VERTICAL = (lambda X, Y, Z: (-Y, X))
SCENE_ARGS = dict(image=np.zeros((2, 2)), rpc=TOY_RPC, crop_offset=(0.0, 0.0), dem=np.zeros((3, 3)),
                  dem_grid=RasterGrid(0, 3, 1, (3, 3)), dem_crs=None, geoid=GEOID, image_path=Path("x"))


def _scene(**changes):
    return g.VentouxScene(**{**SCENE_ARGS, **changes})


CASES = [
    # write_geotiff
    Case(g.write_geotiff, (_DIR / "a.tif", np.zeros((3, 3)), GRID, 32631), why="array not of the grid's shape",
         raises=InputError, match="does not match"),
    Case(g.write_geotiff, (_DIR / "b.tif", np.zeros((10, 10)), GRID, "not a crs"), why="bad CRS",
         raises=InputError, match="coordinate reference system"),
    Case(g.write_geotiff, (_DIR / "c.tif", np.zeros((10, 10)), GRID, None), why="no CRS", raises=InputError),
    Case(g.write_geotiff, (_DIR / "d.tif", np.zeros((10, 10)), (0, 10, 1), 32631), why="not a RasterGrid",
         raises=InputError),
    Case(g.write_geotiff, (_DIR / "e.tif", np.full((10, 10), "x"), GRID, 32631), why="strings", raises=InputError),
    Case(g.write_geotiff, (3.5, np.zeros((10, 10)), GRID, 32631), why="path is a number", raises=InputError),
    Case(g.write_geotiff, (_DIR / "f.tif", np.zeros((10, 10)), GRID, 32631), dict(nodata="none"),
         why="nodata not a number", raises=InputError),
    Case(g.write_geotiff, (_DIR / "g.tif", np.full((10, 10), NAN), GRID, 32631), dict(nodata=-1),
         why="all NaN with nodata: written as nodata", raises=None, check=lambda p: Path(p).exists()),
    # read_geotiff / read_dem / read_geoid
    Case(g.read_geotiff, (_no_crs_file(),), why="GeoTIFF without CRS", raises=InputError,
         match="no coordinate reference system"),
    Case(g.read_geotiff, (_rotated_file(),), why="rotated geotransform", raises=InputError, match="north-up"),
    Case(g.read_geotiff, (_DIR / "missing.tif",), why="missing file", raises=InputError, match="no such"),
    Case(g.read_geotiff, (_text_file(),), why="not a raster", raises=InputError, match="cannot open"),
    Case(g.read_geotiff, (_two_band_file(),), dict(band=3), why="band out of range", raises=InputError),
    Case(g.read_geotiff, (_two_band_file(),), dict(crs=32631), why="a different CRS than the file's",
         raises=InputError),
    Case(g.read_dem, (_two_band_file(),), why="a DEM with two bands", raises=InputError, match="one band"),
    Case(g.read_dem, (_no_crs_file(),), why="DEM without CRS", raises=InputError),
    Case(g.read_geoid, (_two_band_file(),), why="a geoid with two bands", raises=InputError),
    Case(g.read_geoid, (g.write_geotiff(_DIR / "utm.tif", np.zeros((2, 2)), GRID.window(0, 0, 2, 2), 32631),),
         why="a geoid in a projected CRS", raises=InputError, match="longitude/latitude"),
    # transform_points / grid_centres_in
    Case(g.transform_points, (NAN, 0.0, 4326, 32631), why="NaN", raises=InputError, match="NaN"),
    Case(g.transform_points, ([1.0, INF], [0.0, 0.0], 4326, 32631), why="inf", raises=InputError),
    Case(g.transform_points, ([1.0, 2.0], [0.0, 0.0, 1.0], 4326, 32631), why="shapes", raises=InputError),
    Case(g.transform_points, (0.0, 0.0, "EPSG:999999", 32631), why="unknown EPSG", raises=InputError),
    Case(g.transform_points, (0.0, 0.0, 4326, 1.5), why="a float as CRS", raises=InputError),
    Case(g.transform_points, (0.0, 100.0, 4326, 32631), why="latitude 100°", raises=InputError),
    Case(g.transform_points, (np.zeros(0), np.zeros(0), 4326, 32631), why="empty",
         raises=None, check=lambda r: r[0].size == 0),
    Case(g.grid_centres_in, ("grid", 32631, 4326), why="not a grid", raises=InputError),
    Case(g.grid_centres_in, (UTM, None, 4326), why="no CRS", raises=InputError),
    # GeoidModel
    Case(g.GeoidModel, (np.zeros((2, 2)), RasterGrid(0, 3, 1, (3, 3))), why="shape vs grid", raises=InputError),
    Case(g.GeoidModel, (np.full((3, 3), INF), RasterGrid(0, 3, 1, (3, 3))), why="inf", raises=InputError),
    Case(g.GeoidModel, (np.zeros((3, 3)), "grid"), why="not a grid", raises=InputError),
    Case(GEOID.undulation_at, (NAN, 1.0), why="NaN longitude", raises=InputError),
    Case(GEOID.undulation_at, (40.0, 1.0), why="outside a regional geoid", raises=InputError, match="does not cover"),
    Case(GEOID.ellipsoidal, ("h", 2.0, 1.0), why="height is text", raises=InputError),
    # dem_on_grid
    Case(g.dem_on_grid, (np.zeros((3, 3)), RasterGrid(10.0, 10.0, 0.1, (3, 3)), 4326, UTM, 32631),
         why="DEM not covering the grid", raises=InputError, match="does not cover"),
    Case(g.dem_on_grid, (np.zeros((2, 2)), RasterGrid(2.9, 0.1, 0.1, (3, 3)), 4326, UTM, 32631),
         why="DEM shape vs grid", raises=InputError),
    Case(g.dem_on_grid, (np.zeros((3, 3)), RasterGrid(2.5, 0.5, 0.5, (2, 2)), 4326, UTM, 32631),
         dict(transform_tolerance=-1), why="negative tolerance", raises=InputError),
    Case(g.dem_on_grid, (np.zeros((2, 2)), RasterGrid(2.5, 0.5, 0.5, (2, 2)), 4326, UTM, 32631),
         dict(geoid=3), why="geoid of the wrong type", raises=InputError),
    # rpc_projector
    Case(g.rpc_projector, ("rpc", 32631), why="not an RPC", raises=InputError),
    Case(g.rpc_projector, (TOY_RPC, "nonsense"), why="bad CRS", raises=InputError),
    Case(g.rpc_projector(TOY_RPC, 32631), (500000.0, 0.0, NAN), why="NaN height", raises=InputError),
    Case(g.rpc_projector(TOY_RPC, 4326), (9.0, 0.0, 0.0), why="far outside the RPC's range",
         raises=InputError, match="valid range"),
    Case(g.rpc_projector(ZERO_DEN, 4326), (np.full((2, 2), 2.99), np.zeros((2, 2)), np.zeros((2, 2))),
         why="RPC denominator near zero", raises=DegenerateGeometryError, match="denominator"),
    Case(g.rpc_projector(TOY_RPC, 32631), ([1.0, 2.0], [1.0, 2.0, 3.0], 0.0), why="shapes", raises=InputError),
    # orthorectify_tiled
    Case(g.orthorectify_tiled, (np.zeros((10, 10)), VERTICAL, np.zeros((3, 3)), RasterGrid(100, 200, 1, (3, 3)),
                                RasterGrid(-0.5, 0.5, 1.0, (10, 10))),
         why="DEM not covering the grid", raises=InputError, match="cover"),
    Case(g.orthorectify_tiled, (np.zeros((10, 10)), "f", np.zeros((3, 3)), GRID, GRID),
         why="project not callable", raises=InputError),
    Case(g.orthorectify_tiled, (np.zeros((10, 10)), VERTICAL, np.zeros((10, 10)), GRID, GRID), dict(tile=2),
         why="tile too small", raises=InputError),
    Case(g.orthorectify_tiled, (np.zeros((10, 10)), VERTICAL, np.zeros((10, 10)), GRID, GRID),
         dict(method="lanczos"), why="unknown method", raises=InputError),
    Case(g.orthorectify_tiled, (np.zeros((0, 10)), VERTICAL, np.zeros((10, 10)), GRID, GRID),
         why="empty image", raises=InputError),
    Case(g.orthorectify_tiled, (np.zeros((10, 10)), VERTICAL, np.zeros((9, 10)), GRID, GRID),
         why="DEM shape vs grid", raises=InputError),
    Case(g.orthorectify_tiled, (np.zeros((10, 10)), VERTICAL, np.zeros((10, 10)), GRID, GRID),
         dict(height_range=(5.0, NAN)), why="NaN height range", raises=InputError),
    Case(g.orthorectify_tiled, (np.zeros((10, 10)), VERTICAL, np.zeros((10, 10)), GRID, GRID),
         dict(out_path=_DIR / "o.tif"), why="out_path without crs", raises=InputError),
    Case(g.orthorectify_tiled, (np.zeros((10, 10)), VERTICAL, np.zeros((10, 10)), GRID, GRID),
         dict(progress="yes"), why="progress neither bool nor callable", raises=InputError),
    Case(g.orthorectify_tiled, (_text_file(), VERTICAL, np.zeros((10, 10)), GRID, GRID),
         why="source path is not a raster", raises=InputError),
    Case(g.orthorectify_tiled, (np.zeros((10, 10)), VERTICAL, np.zeros((40, 40)),
                                RasterGrid(40, 70, 1, (40, 40)), RasterGrid(50, 50, 1, (10, 10))),
         why="grid far from the image: all fill", raises=None, check=lambda o: np.isnan(o).all()),
    # mosaic_tiled
    Case(g.mosaic_tiled, ([np.zeros((4, 4))], [GRID], [[0, 0], [0, 10]]), why="one orthophoto", raises=InputError),
    Case(g.mosaic_tiled, ([np.zeros((10, 10)), np.zeros((10, 10))], None, [[5, 0], [5, 10]]),
         why="grids None with arrays", raises=InputError),
    Case(g.mosaic_tiled, ([np.zeros((10, 10)), np.zeros((9, 10))], [GRID, GRID], [[5, 0], [5, 10]]),
         why="ortho shape vs grid", raises=InputError),
    Case(g.mosaic_tiled, ([np.zeros((10, 10)), np.zeros((10, 10))], [GRID, RasterGrid(0.3, 10, 1, (10, 10))],
                          [[5, 0], [5, 10]]), why="origins off the pixel lattice", raises=InputError),
    Case(g.mosaic_tiled, ([np.zeros((10, 10)), np.zeros((10, 10))], [GRID, GRID], [[5, 3], [5, 4]]),
         why="cutline not spanning the rows", raises=InputError, match="cutline"),
    Case(g.mosaic_tiled, ([np.zeros((10, 10)), np.zeros((10, 10))], [GRID, GRID], [[5, 0], [5, 10]]),
         dict(tile=0), why="tile 0", raises=InputError),
    # plan_tiles / TilePlan
    Case(g.plan_tiles, (VERTICAL, np.zeros((10, 10)), GRID, GRID, (10,)), why="image shape of one number",
         raises=InputError),
    Case(g.plan_tiles, (VERTICAL, np.zeros((10, 10)), GRID, GRID, (10, 10)), dict(halo=-1),
         why="negative halo", raises=InputError),
    Case(g.plan_tiles, (VERTICAL, np.zeros((10, 10)), GRID, GRID, (10, 10)), dict(margin=1.5),
         why="fractional margin", raises=InputError),
    Case(g.plan_tiles, (VERTICAL, np.zeros((10, 10)), GRID, "grid", (10, 10)), why="not a grid", raises=InputError),
    Case(g.plan_tiles, (VERTICAL, np.full((10, 10), NAN), GRID, GRID, (10, 10)),
         why="all-void DEM: tiles planned without an image window", raises=None,
         check=lambda plans: all(p.image_window is None for p in plans)),
    Case(g.TilePlan, (0, 0, GRID, (0, 10, 0, 10), None), why="a plain record", raises=None,
         check=lambda p: p.grid is GRID),
    # ventoux_scene / VentouxScene
    Case(g.ventoux_scene, ("middle",), why="unknown side", raises=InputError),
    Case(_scene, (), dict(rpc="rpc"), why="rpc not an RPC", raises=InputError),
    Case(g.VentouxScene, (), dict(SCENE_ARGS, image=np.zeros(3)), why="1-D image", raises=InputError),
    Case(g.VentouxScene, (), dict(SCENE_ARGS, dem=np.zeros((2, 2))), why="DEM shape", raises=InputError),
    Case(g.VentouxScene, (), dict(SCENE_ARGS, geoid=None), why="no geoid", raises=InputError),
]


@pytest.mark.parametrize("case", CASES, ids=lambda c: c.id)
def test_bad_input(case):
    check_case(case)


def test_missing_real_data_is_named(monkeypatch, tmp_path):
    monkeypatch.setenv("PHOTOLIB_DATA", str(tmp_path / "nowhere"))
    with pytest.raises(DataUnavailableError, match="PHOTOLIB_DATA"):
        g.ventoux_scene("left")


def test_missing_geo_extra_is_named(monkeypatch):
    import builtins
    real_import = builtins.__import__

    def fake_import(name, *args, **kwargs):
        if name == "pyproj" or name.startswith("pyproj."):
            raise ImportError("no pyproj")
        return real_import(name, *args, **kwargs)

    import sys
    monkeypatch.delitem(sys.modules, "pyproj", raising=False)
    monkeypatch.setattr(builtins, "__import__", fake_import)
    monkeypatch.setattr("importlib.import_module", lambda name: fake_import(name))
    with pytest.raises(g.GeoDependencyError, match="geo"):
        g.transform_points(0.0, 0.0, 4326, 32631)
