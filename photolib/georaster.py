"""Georeferenced rasters, map projections and tiled orthorectification — Chapter 7, §7.3 (and §8.5).

§7.3 builds an orthophoto on a grid aligned with the axes of a map projection (or of a
topocentric frame). This module connects the array-only engine of :mod:`photolib.rectify` with
the geodata tools a user works with:

* GeoTIFF input and output with the CRS and the geotransform (:func:`write_geotiff`,
  :func:`read_geotiff`, through rasterio/GDAL);
* map projections through pyproj: pixel centres of a :class:`~photolib.rectify.RasterGrid` in
  another CRS (:func:`grid_centres_in`, e.g. UTM → longitude/latitude for an RPC), geoid and
  ellipsoidal heights (:class:`GeoidModel`, :func:`read_geoid`: ellipsoidal height = height above
  the geoid + undulation N, read from an EGM96 ``.gtx`` grid and interpolated bilinearly with
  :func:`photolib.rectify.dem_height`), a DEM in one CRS sampled at the centres of a grid in
  another (:func:`dem_on_grid`), SRTM ``.hgt`` tiles (:func:`read_dem`);
* the RPC sensor model as a ``project(X, Y, Z)`` callable for :func:`photolib.rectify.orthorectify`
  on a map grid (:func:`rpc_projector`, RPC eqs. (8.5.6)–(8.5.9));
* out-of-core orthorectification on Dask tiles (:func:`orthorectify_tiled`): each output tile with
  its DEM window (plus a halo) and the source-image window it needs, equal to the in-memory result;
* the real Pléiades scene of Mont Ventoux (:func:`ventoux_scene`).

rasterio, pyproj and dask (the ``geo`` extra) are imported lazily, inside the functions that need
them; without them those functions raise :class:`GeoDependencyError`.

Conventions: object X east, Y north, a grid's origin is the top-left corner of its top-left pixel;
image (row, col) have (0, 0) at the centre of the first pixel (GDAL's = ours + 0.5). Coordinates
given to pyproj are always in (x, y) = (east, north) = (longitude, latitude) order.
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass
from pathlib import Path
from typing import Callable

import numpy as np

from .errors import InputError, PhotolibError
from .rectify import RESAMPLING_METHODS, RasterGrid, dem_height, mosaic_grid, orthorectify

__all__ = ["GeoDependencyError", "write_geotiff", "read_geotiff", "read_dem", "transform_points",
           "grid_centres_in", "GeoidModel", "read_geoid", "dem_on_grid", "rpc_projector",
           "TilePlan", "plan_tiles", "orthorectify_tiled", "mosaic_tiled", "VentouxScene", "ventoux_scene"]

_LONLAT = "EPSG:4326"
_LATTICE_STEP = 16
_KERNEL_RADIUS = {"nearest": 1, "bilinear": 1, "bicubic": 2}


class GeoDependencyError(PhotolibError, ImportError):
    """A function of :mod:`photolib.georaster` needs rasterio, pyproj or dask (the ``geo`` extra).

    Attributes
    ----------
    package : str
        The missing package.

    References
    ----------
    Chibunichev (2022), §7.3 (orthophotos in a map projection).

    Examples
    --------
    >>> from photolib.georaster import GeoDependencyError
    >>> str(GeoDependencyError("pyproj"))
    "pyproj is needed here: install photolib's 'geo' extra (pip install 'photolib[geo]')"
    """

    def __init__(self, package: str):
        super().__init__(f"{package} is needed here: install photolib's 'geo' extra "
                         f"(pip install 'photolib[geo]')")
        self.package = package


def _import(name):
    import importlib
    try:
        return importlib.import_module(name)
    except ImportError:
        raise GeoDependencyError(name.split(".")[0]) from None


_CRS_CACHE: dict = {}


def _crs(crs, name="crs"):
    pyproj = _import("pyproj")
    if crs is None or isinstance(crs, (bool, float, np.floating)):
        raise InputError(f"{name} must be a CRS (e.g. 'EPSG:32631'), got {crs!r}")
    if isinstance(crs, pyproj.CRS):
        return crs
    if isinstance(crs, (str, int)) and crs in _CRS_CACHE:
        return _CRS_CACHE[crs]
    try:
        if isinstance(crs, (str, int)):
            _CRS_CACHE[crs] = pyproj.CRS.from_user_input(crs)
            return _CRS_CACHE[crs]
        return pyproj.CRS.from_user_input(crs if not hasattr(crs, "to_wkt") else crs.to_wkt())
    except Exception as exc:  # pyproj.exceptions.CRSError and friends
        raise InputError(f"{name} is not a coordinate reference system pyproj understands: {crs!r} "
                         f"({exc})") from None


def _grid(grid, name="grid"):
    if not isinstance(grid, RasterGrid):
        raise InputError(f"{name} must be a photolib.rectify.RasterGrid, got {type(grid).__name__}")
    return grid


def _path(path, name="path"):
    if not isinstance(path, (str, os.PathLike)) or not str(path):
        raise InputError(f"{name} must be a file path, got {type(path).__name__}")
    return Path(path)


# --------------------------------------------------------------------------------- GeoTIFF
def write_geotiff(path, array, grid: RasterGrid, crs, nodata=None, *, compress: str = "deflate",
                  block_size: int = 256):
    """Write a raster on a grid to a GeoTIFF with its CRS and geotransform (rasterio/GDAL).

    Parameters
    ----------
    path : str or os.PathLike
        The file to create (overwritten).
    array : (rows, cols) or (rows, cols, bands) array
        Values; NaN pixels of a float array are written as ``nodata`` when it is given.
    grid : RasterGrid
        The raster's grid (its shape must match the array).
    crs : str, int or pyproj.CRS
        The coordinate reference system of the grid (e.g. ``"EPSG:32631"``).
    nodata : float, optional
        The nodata value recorded in the file.
    compress : str
        GDAL compression (``"deflate"``, ``"lzw"``, ``"none"``).
    block_size : int
        Internal tile size (a multiple of 16), so that readers can fetch windows.

    Returns
    -------
    pathlib.Path
        The path written.

    Raises
    ------
    InputError
        A shape that does not match the grid, a bad CRS, a non-numeric array, a bad path.
    GeoDependencyError
        rasterio or pyproj missing.

    References
    ----------
    Chibunichev (2022), §7.3 (the orthophoto's grid in the map projection) and §7.7 (mosaic
    origin X₀M, Y₀M). GeoTIFF: OGC 19-008r4.

    Examples
    --------
    >>> import tempfile, numpy as np
    >>> from photolib.rectify import RasterGrid
    >>> from photolib.georaster import write_geotiff, read_geotiff
    >>> grid = RasterGrid(500000.0, 4900000.0, 0.5, (2, 3))
    >>> path = write_geotiff(tempfile.mkdtemp() + "/o.tif", np.arange(6.0).reshape(2, 3), grid, "EPSG:32631")
    >>> array, back, crs = read_geotiff(path)
    >>> back == grid, crs.to_epsg(), array[1].tolist()
    (True, 32631, [3.0, 4.0, 5.0])
    """
    path = _path(path)
    grid = _grid(grid)
    crs = _crs(crs)
    rasterio = _import("rasterio")
    try:
        data = np.asarray(array)
    except Exception:
        raise InputError("array must be a numeric array") from None
    if data.dtype.kind not in "biuf":
        raise InputError(f"array must be numeric, got dtype {data.dtype}")
    if data.ndim not in (2, 3) or data.shape[:2] != grid.shape:
        raise InputError(f"the array's shape {data.shape} does not match the grid {grid.shape} "
                         f"(expected (rows, cols) or (rows, cols, bands))")
    if data.dtype.kind == "b":
        data = data.astype(np.uint8)
    bands = data[:, :, None] if data.ndim == 2 else data
    if nodata is not None:
        try:
            nodata = float(nodata)
        except (TypeError, ValueError):
            raise InputError(f"nodata must be a number, got {nodata!r}") from None
        if data.dtype.kind == "f":
            bands = np.where(np.isnan(bands), nodata, bands)
    block = int(block_size)
    if block < 16 or block % 16:
        raise InputError(f"block_size must be a positive multiple of 16, got {block_size!r}")
    profile = dict(driver="GTiff", height=grid.shape[0], width=grid.shape[1], count=bands.shape[2],
                   dtype=bands.dtype, crs=rasterio.crs.CRS.from_wkt(crs.to_wkt()),
                   transform=rasterio.Affine.from_gdal(*grid.geotransform), nodata=nodata)
    if compress and compress.lower() != "none":
        profile["compress"] = compress
    if min(grid.shape) >= block:
        profile.update(tiled=True, blockxsize=block, blockysize=block)
    with rasterio.open(path, "w", **profile) as dst:
        dst.write(np.moveaxis(bands, 2, 0))
    return path


def read_geotiff(path, *, crs="required", band=None, nodata_to_nan: bool = False):
    """Read a georeferenced raster (GeoTIFF or any GDAL format): array, grid and CRS.

    Parameters
    ----------
    path : str or os.PathLike
        The file.
    crs : 'required', None or CRS
        What to do when the file has no CRS: ``'required'`` (default) raises; ``None`` accepts it
        and returns ``crs = None``; a CRS is assigned to it. A file that has a CRS keeps its own
        (a different one given here raises).
    band : int, optional
        Read one band (1-based); by default all bands ((rows, cols) for one band, else
        (rows, cols, bands)).
    nodata_to_nan : bool
        Return float64 with NaN where the file's nodata value is.

    Returns
    -------
    array : ndarray
    grid : RasterGrid
        From the file's geotransform (north-up only).
    crs : pyproj.CRS or None

    Raises
    ------
    InputError
        A missing CRS (unless allowed), a rotated or south-up geotransform, a file GDAL cannot
        open, a band out of range.
    GeoDependencyError
        rasterio or pyproj missing.

    References
    ----------
    Chibunichev (2022), §7.3 (grid and map projection of an orthophoto).

    Examples
    --------
    >>> import tempfile, numpy as np
    >>> from photolib.rectify import RasterGrid
    >>> from photolib.georaster import write_geotiff, read_geotiff
    >>> path = write_geotiff(tempfile.mkdtemp() + "/d.tif", np.full((2, 2), np.nan), RasterGrid(5, 45, 0.5, (2, 2)),
    ...                      "EPSG:4326", nodata=-9999)
    >>> array, grid, crs = read_geotiff(path, nodata_to_nan=True)
    >>> bool(np.isnan(array).all()), grid.extent
    (True, (5.0, 44.0, 6.0, 45.0))
    """
    path = _path(path)
    rasterio = _import("rasterio")
    pyproj = _import("pyproj")
    if not path.exists():
        raise InputError(f"no such raster file: {path}")
    try:
        src = rasterio.open(path)
    except Exception as exc:
        raise InputError(f"GDAL cannot open {path} as a raster: {exc}") from None
    with src:
        if src.crs is None:
            if isinstance(crs, str) and crs == "required":
                raise InputError(f"{path} has no coordinate reference system (not georeferenced); "
                                 f"pass crs=None to read it anyway, or crs='EPSG:…' to assign one")
            file_crs = None if crs is None else _crs(crs)
        else:
            file_crs = pyproj.CRS.from_wkt(src.crs.to_wkt())
            if not (crs is None or (isinstance(crs, str) and crs == "required")):
                if _crs(crs) != file_crs:
                    raise InputError(f"{path} has CRS {file_crs.name!r}, not the one given ({crs!r})")
        grid = RasterGrid.from_geotransform(src.transform.to_gdal(), src.shape)
        if band is None:
            data = src.read()
            data = data[0] if data.shape[0] == 1 else np.moveaxis(data, 0, 2)
        else:
            if not isinstance(band, (int, np.integer)) or not 1 <= band <= src.count:
                raise InputError(f"band must be an integer in 1..{src.count}, got {band!r}")
            data = src.read(int(band))
        nodata = src.nodata
    if nodata_to_nan:
        mask = (data == nodata) if nodata is not None and not math.isnan(nodata) else None
        data = data.astype(np.float64)
        if mask is not None:
            data[mask] = np.nan
    return data, grid, file_crs


def read_dem(path, *, crs="required"):
    """Read a DEM (SRTM ``.hgt``, GeoTIFF …) as float heights with NaN voids, its grid and CRS.

    Parameters
    ----------
    path : str or os.PathLike
        The DEM file; SRTM ``.hgt`` tiles are opened by GDAL's SRTMHGT driver (EPSG:4326,
        heights above the EGM96 geoid, voids −32768).
    crs : 'required', None or CRS
        As in :func:`read_geotiff`.

    Returns
    -------
    heights : (rows, cols) float64 ndarray
    grid : RasterGrid
    crs : pyproj.CRS or None

    Raises
    ------
    InputError
        A file with several bands, no CRS, or that GDAL cannot open.
    GeoDependencyError
        rasterio or pyproj missing.

    References
    ----------
    Chibunichev (2022), §7.3 (the DEM of the orthorectification, (7.3.1)); §8.13 (SRTM).

    Examples
    --------
    >>> import tempfile, numpy as np
    >>> from photolib.rectify import RasterGrid
    >>> from photolib.georaster import write_geotiff, read_dem
    >>> path = write_geotiff(tempfile.mkdtemp() + "/h.tif", np.array([[1, -32768]], np.int16),
    ...                      RasterGrid(5, 45, 1.0, (1, 2)), "EPSG:4326", nodata=-32768)
    >>> read_dem(path)[0].tolist()
    [[1.0, nan]]
    """
    heights, grid, dem_crs = read_geotiff(path, crs=crs, nodata_to_nan=True)
    if heights.ndim != 2:
        raise InputError(f"a DEM has one band, {path} has {heights.shape[2]}")
    return heights, grid, dem_crs


# --------------------------------------------------------------------------------- CRS work
def transform_points(x, y, src_crs, dst_crs):
    """Transform planimetric coordinates between two CRSs (pyproj, always east/longitude first).

    Parameters
    ----------
    x, y : array_like
        Easting and northing (or longitude and latitude in degrees), broadcast together.
    src_crs, dst_crs : str, int or pyproj.CRS
        Source and target CRS, e.g. ``"EPSG:32631"`` (UTM 31N) and ``"EPSG:4326"``; a
        Gauss–Krüger zone (§7.3's map-projection variant) is e.g. ``"EPSG:28405"``.

    Returns
    -------
    x, y : ndarray
        Float arrays of the broadcast shape (0-d for scalars).

    Raises
    ------
    InputError
        NaN or inf coordinates, a bad CRS, points the projection cannot transform.
    GeoDependencyError
        pyproj missing.

    References
    ----------
    Chibunichev (2022), §7.3 (geodetic B, L, H and a map projection of the orthophoto grid).

    Examples
    --------
    >>> from photolib.georaster import transform_points
    >>> x, y = transform_points(3.0, 0.0, "EPSG:4326", "EPSG:32631")   # UTM 31N central meridian
    >>> round(float(x), 6), round(float(y), 6)
    (500000.0, 0.0)
    """
    pyproj = _import("pyproj")
    src, dst = _crs(src_crs, "src_crs"), _crs(dst_crs, "dst_crs")
    try:
        x, y = np.broadcast_arrays(np.asarray(x, dtype=np.float64), np.asarray(y, dtype=np.float64))
    except (TypeError, ValueError):
        raise InputError("x and y must be numbers or arrays of one shape") from None
    if not (np.isfinite(x).all() and np.isfinite(y).all()):
        raise InputError("x, y contain NaN or inf")
    transformer = _transformer(src, dst)
    tx, ty = transformer.transform(x, y, errcheck=False)
    tx, ty = np.asarray(tx, dtype=np.float64), np.asarray(ty, dtype=np.float64)
    if not (np.isfinite(tx).all() and np.isfinite(ty).all()):
        raise InputError(f"{int((~np.isfinite(tx)).sum())} point(s) cannot be transformed from "
                         f"{src.name!r} to {dst.name!r} (outside the projection's domain)")
    del pyproj
    return tx, ty


_TRANSFORMERS: dict = {}


def _transformer(src, dst):
    key = (id(src), id(dst))
    entry = _TRANSFORMERS.get(key)
    if entry is None or entry[0] is not src or entry[1] is not dst:
        pyproj = _import("pyproj")
        if len(_TRANSFORMERS) > 64:
            _TRANSFORMERS.clear()
        entry = (src, dst, pyproj.Transformer.from_crs(src, dst, always_xy=True))
        _TRANSFORMERS[key] = entry
    return entry[2]


def _is_lattice(X, Y):
    return (X.ndim == 2 and X.shape == Y.shape and X.size >= 2
            and np.array_equal(X, np.broadcast_to(X[:1], X.shape))
            and np.array_equal(Y, np.broadcast_to(Y[:, :1], Y.shape)))


def _axis_weights(values, spacing):
    u = values / spacing
    index = np.floor(u)
    return index.astype(np.int64), u - index


def _fast_transform(X, Y, src, dst, tolerance):
    """Transform a rectilinear lattice of points through a coarse lattice and bilinear weights.

    Like GDAL's approximate transformer, but with its error checked in object units: the exact
    transform is evaluated on lattice nodes every ``_LATTICE_STEP`` pixels, anchored at
    multiples of that spacing in object coordinates (so that any tile of a grid interpolates
    from the same nodes), and at the centres of the lattice cells, where bilinear interpolation
    errs most; if that error exceeds ``tolerance`` (metres; degrees are converted with 111 320 m
    per degree) every point goes through pyproj. Anything that is not a lattice, or is small,
    goes through pyproj point by point.
    """
    X = np.asarray(X, dtype=np.float64)
    Y = np.asarray(Y, dtype=np.float64)
    if tolerance is None or not _is_lattice(X, Y):
        return transform_points(X, Y, src, dst)
    src_crs, dst_crs = _crs(src, "src_crs"), _crs(dst, "dst_crs")
    xs, ys = X[0], Y[:, 0]
    if not (np.isfinite(xs).all() and np.isfinite(ys).all()):
        raise InputError("x, y contain NaN or inf")
    # the lattice spacing from the pixel size, rounded so that every tile of a grid finds the
    # same one (and so the same nodes): tiles and the whole grid interpolate identically
    # (a single row or column borrows the other axis's spacing: identical for square pixels)
    px = float(f"{abs(xs[-1] - xs[0]) / (xs.size - 1):.10g}") if xs.size > 1 else None
    py = float(f"{abs(ys[-1] - ys[0]) / (ys.size - 1):.10g}") if ys.size > 1 else None
    px, py = (px or py), (py or px)
    if px == 0.0 or py == 0.0:
        return transform_points(X, Y, src, dst)
    to_metres = 111320.0 if dst_crs.is_geographic else 1.0
    kernels = _kernels()
    for step in (_LATTICE_STEP,):
        sx, sy = step * px, step * py
        ix, tx = _axis_weights(xs, sx)
        iy, ty = _axis_weights(ys, sy)
        kx0, ky0 = int(ix.min()), int(iy.min())
        node_x = (np.arange(kx0, int(ix.max()) + 2)) * sx
        node_y = (np.arange(ky0, int(iy.max()) + 2)) * sy
        NX, NY = np.meshgrid(node_x, node_y)
        lon, lat = transform_points(NX, NY, src_crs, dst_crs)
        mid_x, mid_y = np.meshgrid(node_x[:-1] + sx / 2, node_y[:-1] + sy / 2)
        exact_x, exact_y = transform_points(mid_x, mid_y, src_crs, dst_crs)
        mean_x = (lon[:-1, :-1] + lon[:-1, 1:] + lon[1:, :-1] + lon[1:, 1:]) / 4
        mean_y = (lat[:-1, :-1] + lat[:-1, 1:] + lat[1:, :-1] + lat[1:, 1:]) / 4
        error = max(float(np.max(np.abs(mean_x - exact_x))), float(np.max(np.abs(mean_y - exact_y))))
        if error * to_metres <= tolerance:
            out_x = np.empty(X.shape)
            out_y = np.empty(X.shape)
            args = (np.ascontiguousarray(iy - ky0), np.ascontiguousarray(ty),
                    np.ascontiguousarray(ix - kx0), np.ascontiguousarray(tx))
            kernels.lattice_bilinear(np.ascontiguousarray(lon), *args, out_x)
            kernels.lattice_bilinear(np.ascontiguousarray(lat), *args, out_y)
            return out_x, out_y
    return transform_points(X, Y, src, dst)


def _tolerance(value):
    if value is None:
        return None
    try:
        value = float(value)
    except (TypeError, ValueError):
        raise InputError(f"transform_tolerance must be a positive number of metres or None, got {value!r}") from None
    if not (math.isfinite(value) and value > 0):
        raise InputError(f"transform_tolerance must be a positive number of metres or None, got {value!r}")
    return value


def _kernels():
    from . import _georaster_kernels
    return _georaster_kernels


def grid_centres_in(grid: RasterGrid, grid_crs, dst_crs):
    """The pixel centres of a grid, transformed into another CRS.

    Parameters
    ----------
    grid : RasterGrid
        The grid (e.g. an orthophoto in UTM).
    grid_crs, dst_crs : CRS
        The grid's CRS and the target (e.g. ``"EPSG:4326"`` for the longitude and latitude an
        RPC wants).

    Returns
    -------
    x, y : ndarray
        Two arrays of the grid's shape (longitude, latitude for a geographic target).

    Raises
    ------
    InputError
        Not a grid, a bad CRS.
    GeoDependencyError
        pyproj missing.

    References
    ----------
    Chibunichev (2022), §7.3 (each orthophoto pixel centre, in the map projection, transformed
    to geodetic B, L).

    Examples
    --------
    >>> from photolib.rectify import RasterGrid
    >>> from photolib.georaster import grid_centres_in
    >>> lon, lat = grid_centres_in(RasterGrid(499999.0, 1.0, 2.0, (1, 1)), "EPSG:32631", "EPSG:4326")
    >>> lon.round(9).tolist(), lat.round(9).tolist()
    ([[3.0]], [[0.0]])
    """
    X, Y = _grid(grid).centres()
    return transform_points(X, Y, grid_crs, dst_crs)


@dataclass(frozen=True)
class GeoidModel:
    """Geoid undulations N on a longitude/latitude grid; ellipsoidal h = H (above the geoid) + N.

    Parameters
    ----------
    undulation : (rows, cols) array
        N in metres at the grid's pixel centres (NaN = unknown).
    grid : RasterGrid
        Longitude/latitude grid (degrees) of the nodes; a global grid wraps in longitude.

    Attributes
    ----------
    global_longitudes : bool
        True when the grid spans 360° of longitude (longitudes are then wrapped into it).

    References
    ----------
    Chibunichev (2022), §7.3 (heights of the DEM and the geodetic height H); the EGM96 model
    (Lemoine et al., 1998), whose 15′ grid PROJ distributes as ``egm96_15.gtx``.

    Examples
    --------
    >>> import numpy as np
    >>> from photolib.rectify import RasterGrid
    >>> from photolib.georaster import GeoidModel
    >>> geoid = GeoidModel(np.array([[50.0, 52.0], [48.0, 50.0]]), RasterGrid(4.5, 45.5, 1.0, (2, 2)))
    >>> float(geoid.undulation_at(5.5, 44.5)), float(geoid.ellipsoidal(100.0, 5.5, 44.5))
    (50.0, 150.0)
    """

    undulation: np.ndarray
    grid: RasterGrid

    def __post_init__(self):
        _grid(self.grid, "grid")
        try:
            values = np.asarray(self.undulation, dtype=np.float64)
        except (TypeError, ValueError):
            raise InputError("undulation must be a numeric array") from None
        if values.shape != self.grid.shape:
            raise InputError(f"undulation's shape {values.shape} does not match its grid {self.grid.shape}")
        if values.size and np.isinf(values).any():
            raise InputError("undulation contains inf")
        object.__setattr__(self, "undulation", values)
        if self.global_longitudes:   # add the wrap column once
            wrapped = np.concatenate([values, values[:, :1]], axis=1)
            object.__setattr__(self, "_wrapped", (wrapped, RasterGrid(self.grid.x0, self.grid.y0,
                                                                      self.grid.pixel_size, wrapped.shape)))

    @property
    def global_longitudes(self) -> bool:
        return abs(self.grid.shape[1] * self.grid.dx - 360.0) < 1e-9

    def undulation_at(self, lon, lat):
        """N (m) at longitudes/latitudes (degrees), bilinear (7.3.1) in the geoid grid.

        Parameters
        ----------
        lon, lat : array_like
            Degrees.

        Returns
        -------
        ndarray
            Undulations, the broadcast shape.

        Raises
        ------
        InputError
            NaN coordinates, points outside a regional grid.

        References
        ----------
        Chibunichev (2022), §7.3, eq. (7.3.1) (bilinear interpolation in a grid).

        Examples
        --------
        >>> import numpy as np
        >>> from photolib.rectify import RasterGrid
        >>> from photolib.georaster import GeoidModel
        >>> GeoidModel(np.full((2, 2), 49.0), RasterGrid(0, 2, 1.0, (2, 2))).undulation_at(1.0, 1.0)
        array(49.)
        """
        try:
            lon, lat = np.broadcast_arrays(np.asarray(lon, dtype=np.float64), np.asarray(lat, dtype=np.float64))
        except (TypeError, ValueError):
            raise InputError("lon and lat must be numbers or arrays of one shape") from None
        if not (np.isfinite(lon).all() and np.isfinite(lat).all()):
            raise InputError("lon, lat contain NaN or inf")
        values, grid = self.undulation, self.grid
        if self.global_longitudes:
            first = grid.x0 + grid.dx / 2
            lon = (lon - first) % 360.0 + first
            values, grid = self._wrapped
        return dem_height(values, grid, lon, lat)

    def ellipsoidal(self, height, lon, lat):
        """Ellipsoidal height h = H + N of heights H above the geoid.

        Parameters
        ----------
        height : array_like
            H, metres above the geoid (e.g. SRTM).
        lon, lat : array_like
            Degrees.

        Returns
        -------
        ndarray

        Raises
        ------
        InputError
            NaN coordinates, points outside a regional grid.

        References
        ----------
        Chibunichev (2022), §7.3; §8.5 (the RPC wants ellipsoidal heights).

        Examples
        --------
        >>> import numpy as np
        >>> from photolib.rectify import RasterGrid
        >>> from photolib.georaster import GeoidModel
        >>> GeoidModel(np.full((2, 2), 49.0), RasterGrid(0, 2, 1.0, (2, 2))).ellipsoidal([1.0], 1.0, 1.0)
        array([50.])
        """
        N = self.undulation_at(lon, lat)
        try:
            return np.asarray(height, dtype=np.float64) + N
        except (TypeError, ValueError):
            raise InputError("height must be numeric and broadcast with lon, lat") from None


def read_geoid(path) -> GeoidModel:
    """Read a geoid grid (e.g. EGM96 ``egm96_15.gtx``) with rasterio into a :class:`GeoidModel`.

    Parameters
    ----------
    path : str or os.PathLike
        A single-band longitude/latitude raster of undulations (``.gtx``, GeoTIFF).

    Returns
    -------
    GeoidModel

    Raises
    ------
    InputError
        A file that is not a single-band raster in a geographic CRS.
    GeoDependencyError
        rasterio or pyproj missing.

    References
    ----------
    Chibunichev (2022), §7.3 (heights above the geoid vs the ellipsoid).

    Examples
    --------
    >>> import tempfile, numpy as np
    >>> from photolib.rectify import RasterGrid
    >>> from photolib.georaster import write_geotiff, read_geoid
    >>> path = write_geotiff(tempfile.mkdtemp() + "/g.tif", np.full((3, 3), 50.0), RasterGrid(4, 46, 1.0, (3, 3)), 4326)
    >>> float(read_geoid(path).undulation_at(5.2, 44.1))
    50.0
    """
    values, grid, crs = read_geotiff(path, crs=None, nodata_to_nan=True)   # no CRS: taken as lon/lat
    if values.ndim != 2:
        raise InputError(f"a geoid grid has one band, {path} has {values.shape[2]}")
    if crs is not None and not crs.is_geographic:
        raise InputError(f"a geoid grid must be in longitude/latitude, {path} is in {crs.name!r}")
    return GeoidModel(values, grid)


def _geoid(geoid):
    if geoid is None or isinstance(geoid, GeoidModel):
        return geoid
    if isinstance(geoid, (str, os.PathLike)):
        return read_geoid(geoid)
    raise InputError(f"geoid must be a GeoidModel, a path to a geoid grid, or None, got {type(geoid).__name__}")


def dem_on_grid(dem, dem_grid: RasterGrid, dem_crs, grid: RasterGrid, grid_crs, geoid=None, *,
                transform_tolerance=1e-4):
    """Heights of a DEM in one CRS at the pixel centres of a grid in another (bilinear, (7.3.1)).

    Every centre of ``grid`` is transformed into the DEM's CRS and the DEM is interpolated
    bilinearly there, in its own grid (as GDAL's RPC transformer does with ``RPC_DEM``); with a
    geoid the undulation is added, giving ellipsoidal heights. The result, on ``grid`` itself,
    is a DEM for :func:`photolib.rectify.orthorectify` with ``dem_grid = grid`` (no second
    interpolation: bilinear interpolation at the grid's own centres returns these values).

    Parameters
    ----------
    dem : (R, C) array
        Heights (NaN = void).
    dem_grid : RasterGrid
        The DEM's grid.
    dem_crs, grid_crs : CRS
        CRSs of the DEM and of the target grid.
    grid : RasterGrid
        The target grid.
    geoid : GeoidModel, path or None
        Add the geoid undulation (DEM heights above the geoid → ellipsoidal heights).
    transform_tolerance : float or None
        The grid centres are transformed through a coarse lattice with bilinear weights whose
        error is checked to stay below this many metres (default 0.1 mm); None: pyproj on every
        centre.

    Returns
    -------
    ndarray
        ``grid.shape`` heights.

    Raises
    ------
    InputError
        A DEM that does not cover the grid (naming the missing area), bad CRSs, mismatched shapes.
    GeoDependencyError
        pyproj missing.

    References
    ----------
    Chibunichev (2022), §7.3, eq. (7.3.1).

    Examples
    --------
    >>> import numpy as np
    >>> from photolib.rectify import RasterGrid
    >>> from photolib.georaster import dem_on_grid
    >>> dem_grid = RasterGrid(2.5, 0.5, 0.5, (2, 2))           # lon 2.75..3.25, lat 0.25..-0.25
    >>> Z = dem_on_grid(np.array([[10.0, 20.0], [30.0, 40.0]]), dem_grid, "EPSG:4326",
    ...                 RasterGrid(499000.0, 1000.0, 2000.0, (1, 1)), "EPSG:32631")
    >>> Z.round(3).tolist()
    [[25.0]]
    """
    _grid(dem_grid, "dem_grid")
    _grid(grid)
    geoid = _geoid(geoid)
    X, Y = grid.centres()
    lon, lat = _fast_transform(X, Y, grid_crs, dem_crs, _tolerance(transform_tolerance))
    heights = dem_height(dem, dem_grid, lon, lat)
    if geoid is not None:
        if not _crs(dem_crs).is_geographic:
            lon, lat = transform_points(lon, lat, dem_crs, _LONLAT)
        heights = heights + geoid.undulation_at(lon, lat)
    return heights


# --------------------------------------------------------------------------------- RPC projector
def rpc_projector(rpc, grid_crs, geoid=None, *, extrapolation: float = 3.0,
                  transform_tolerance=1e-4) -> Callable:
    """An RPC as a sensor callable ``project(X, Y, Z) -> (rows, cols)`` on a map grid.

    Grid coordinates → longitude/latitude (pyproj) → ellipsoidal height (Z + N when a geoid is
    given, Z being above the geoid; Z as is otherwise) → :func:`photolib.rpc.project`.

    Parameters
    ----------
    rpc : photolib.rpc.RPC or BiasCorrectedRPC
        The model, already shifted to the image's pixel grid (``rpc.shifted(row0, col0)`` for a
        crop).
    grid_crs : CRS
        The CRS of X, Y (e.g. ``"EPSG:32631"``).
    geoid : GeoidModel, path or None
        Geoid for heights Z above the geoid; None when Z is already ellipsoidal.
    extrapolation : float
        Passed to :func:`photolib.rpc.project`.
    transform_tolerance : float or None
        For X, Y forming a rectilinear lattice (an orthophoto grid's centres) the CRS transform
        goes through a coarse lattice with bilinear weights, its error checked against this many
        metres (default 0.1 mm, ≈ 2·10⁻⁴ px at 0.5 m); None: pyproj on every point.

    Returns
    -------
    callable
        ``project(X, Y, Z)`` for :func:`photolib.rectify.orthorectify`.

    Raises
    ------
    InputError
        Not an RPC, a bad CRS, a bad geoid.
    GeoDependencyError
        pyproj missing.

    References
    ----------
    Chibunichev (2022), §8.5, eqs. (8.5.6)–(8.5.9) (RPC), §7.3, eq. (7.3.2) (the sensor model of
    the orthophoto, here the RPC instead of collinearity).

    Examples
    --------
    >>> from photolib.rpc import RPC
    >>> from photolib.georaster import rpc_projector
    >>> num = lambda k: [0.0] * k + [1.0] + [0.0] * (19 - k)
    >>> rpc = RPC(100, 200, 0, 3, 0, 50, 80, 0.01, 0.01, 500, num(2), num(0), num(1), num(0))
    >>> rows, cols = rpc_projector(rpc, "EPSG:32631")(500000.0, 0.0, 0.0)
    >>> round(float(rows), 6), round(float(cols), 6)
    (100.0, 200.0)
    """
    from . import rpc as rpc_module

    if not isinstance(rpc, (rpc_module.RPC, getattr(rpc_module, "BiasCorrectedRPC", rpc_module.RPC))):
        raise InputError(f"rpc must be a photolib.rpc.RPC, got {type(rpc).__name__}")
    crs = _crs(grid_crs, "grid_crs")
    geoid = _geoid(geoid)
    tolerance = _tolerance(transform_tolerance)
    geographic = crs.is_geographic and crs.to_epsg() == 4326

    def project(X, Y, Z):
        try:
            X, Y, Z = np.broadcast_arrays(np.asarray(X, dtype=np.float64), np.asarray(Y, dtype=np.float64),
                                          np.asarray(Z, dtype=np.float64))
        except (TypeError, ValueError):
            raise InputError("X, Y, Z must be numbers or arrays that broadcast together") from None
        if geographic:
            lon, lat = X, Y
        else:
            lon, lat = _fast_transform(X, Y, crs, _LONLAT, tolerance)
        height = Z
        if geoid is not None:
            height = height + geoid.undulation_at(lon, lat)
        return rpc_module.project(rpc, lon, lat, height, extrapolation=extrapolation)

    return project


# --------------------------------------------------------------------------------- tiling
def _source(image):
    """(shape, kind, handle): a numpy array, a dask array, or a raster path read by windows."""
    if isinstance(image, (str, os.PathLike)):
        rasterio = _import("rasterio")
        try:
            with rasterio.open(image) as src:
                shape = (src.height, src.width) + ((src.count,) if src.count > 1 else ())
        except Exception as exc:
            raise InputError(f"GDAL cannot open the source image {image}: {exc}") from None
        return shape, "path", Path(image)
    if type(image).__module__.startswith("dask"):
        if image.ndim not in (2, 3) or 0 in image.shape[:2]:
            raise InputError(f"image must be (rows, cols) or (rows, cols, bands), got shape {image.shape}")
        if image.dtype.kind not in "biuf":
            raise InputError(f"image must be numeric, got dtype {image.dtype}")
        return tuple(image.shape), "dask", image
    try:
        array = np.asarray(image)
    except Exception:
        raise InputError("image must be an array, a dask array or a raster path") from None
    if array.dtype.kind not in "biuf" or array.ndim not in (2, 3) or 0 in array.shape[:2]:
        raise InputError(f"image must be a numeric (rows, cols) or (rows, cols, bands) array, "
                         f"got {array.dtype} {array.shape}")
    return array.shape, "numpy", array


class _Opaque:
    """Hides a dask array from dask.delayed's argument traversal (no whole-image dependency)."""

    def __init__(self, value):
        self.value = value


def _read_window(kind, handle, r0, r1, c0, c1):
    if isinstance(handle, _Opaque):
        handle = handle.value
    if kind == "numpy":
        return handle[r0:r1, c0:c1]
    if kind == "dask":
        return handle[r0:r1, c0:c1].compute(scheduler="synchronous")
    rasterio = _import("rasterio")
    with rasterio.open(handle) as src:
        data = src.read(window=((r0, r1), (c0, c1)))
    return data[0] if data.shape[0] == 1 else np.moveaxis(data, 0, 2)


def _tile_plan(project, dem, dem_grid, tile_grid, image_shape, halo, margin, height_range):
    """DEM window (with halo) and the planned source-image window of one output tile."""
    xmin, ymin, xmax, ymax = tile_grid.extent
    rows_a, cols_a = dem_grid.rowcol(np.array([xmin, xmax]), np.array([ymax, ymin]))
    dr0 = max(0, int(math.floor(rows_a.min())) - halo)
    dr1 = min(dem_grid.shape[0], int(math.ceil(rows_a.max())) + 1 + halo)
    dc0 = max(0, int(math.floor(cols_a.min())) - halo)
    dc1 = min(dem_grid.shape[1], int(math.ceil(cols_a.max())) + 1 + halo)
    if dr1 <= dr0 or dc1 <= dc0:
        raise InputError(f"the DEM does not cover the output tile X {xmin:.6g}..{xmax:.6g}, "
                         f"Y {ymin:.6g}..{ymax:.6g} (DEM extent {dem_grid.extent})")
    dem_window = dem[dr0:dr1, dc0:dc1]
    if height_range is None:
        block = np.asarray(dem_window.compute() if hasattr(dem_window, "compute") else dem_window, dtype=np.float64)
        finite = block[np.isfinite(block)]
        if finite.size == 0:
            return (dr0, dr1, dc0, dc1), None
        zlo, zhi = float(finite.min()), float(finite.max())
    else:
        zlo, zhi = height_range
    # the tile's border centres (every pixel) and a coarse interior lattice, at both heights
    n_r, n_c = tile_grid.shape
    step = 16
    rr = np.unique(np.concatenate([np.arange(0, n_r, step), [n_r - 1]]))
    cc = np.unique(np.concatenate([np.arange(0, n_c, step), [n_c - 1]]))
    border_r = np.concatenate([np.zeros(n_c), np.full(n_c, n_r - 1), np.arange(n_r), np.arange(n_r)])
    border_c = np.concatenate([np.arange(n_c), np.arange(n_c), np.zeros(n_r), np.full(n_r, n_c - 1)])
    lattice_r, lattice_c = (a.ravel() for a in np.meshgrid(rr, cc, indexing="ij"))
    pr = np.concatenate([border_r, lattice_r])
    pc = np.concatenate([border_c, lattice_c])
    X, Y = tile_grid.xy(pr, pc)
    rows, cols = [], []
    for z in (zlo, zhi):
        r, c = project(X, Y, np.full(X.shape, z))
        rows.append(np.asarray(r, dtype=np.float64))
        cols.append(np.asarray(c, dtype=np.float64))
    rows, cols = np.concatenate(rows), np.concatenate(cols)
    ok = np.isfinite(rows) & np.isfinite(cols) & (np.abs(rows) < 1e8) & (np.abs(cols) < 1e8)
    if not ok.any():
        return (dr0, dr1, dc0, dc1), None
    R, C = image_shape[:2]
    r0 = max(0, int(math.floor(rows[ok].min())) - margin)
    r1 = min(R, int(math.ceil(rows[ok].max())) + 1 + margin)
    c0 = max(0, int(math.floor(cols[ok].min())) - margin)
    c1 = min(C, int(math.ceil(cols[ok].max())) + 1 + margin)
    if r1 <= r0 or c1 <= c0:
        return (dr0, dr1, dc0, dc1), None
    return (dr0, dr1, dc0, dc1), (r0, r1, c0, c1)


def _window_covers(rows, cols, window, image_shape, radius):
    """True if every position that can touch the image lies inside the window's safe span."""
    r0, r1, c0, c1 = window
    R, C = image_shape[:2]
    near = (rows > -1.5) & (rows < R + 0.5) & (cols > -1.5) & (cols < C + 0.5)
    if not near.any():
        return True
    rr, cc = rows[near], cols[near]
    lo_r = -np.inf if r0 == 0 else r0 + radius
    hi_r = np.inf if r1 == R else r1 - 1 - radius
    lo_c = -np.inf if c0 == 0 else c0 + radius
    hi_c = np.inf if c1 == C else c1 - 1 - radius
    return bool(((rr >= lo_r) & (rr <= hi_r) & (cc >= lo_c) & (cc <= hi_c)).all())


def _ortho_tile(window_data, kind, handle, image_shape, bands, project, dem_window, dem_window_grid,
                tile_grid, window, method, fill, radius):
    """Orthorectify one tile with photolib.rectify.orthorectify on its image window."""
    out_shape = tile_grid.shape + ((bands,) if bands else ())
    if window is None:
        # the tile sees no image: every position is outside (resample to fill through a 1-pixel image)
        window = (0, 1, 0, 1)
        window_data = _read_window(kind, handle, 0, 1, 0, 1)
    seen = {}

    def shifted(X, Y, Z):
        rows, cols = project(X, Y, Z)
        rows, cols = np.asarray(rows, dtype=np.float64), np.asarray(cols, dtype=np.float64)
        seen["rows"], seen["cols"] = rows, cols
        return rows - window[0], cols - window[2]

    dem_array = np.asarray(dem_window, dtype=np.float64)
    data = np.asarray(window_data)
    result = orthorectify(data, shifted, dem_array, dem_window_grid, tile_grid, method, fill)
    rows, cols = seen["rows"], seen["cols"]
    valid = np.isfinite(rows) & np.isfinite(cols)
    if not _window_covers(rows[valid], cols[valid], window, image_shape, radius):
        # the planned window was too small (a sensor model bending beyond the margin): read the
        # exact window the positions need and redo the tile
        near = valid & (rows > -1.5) & (rows < image_shape[0] + 0.5) & (cols > -1.5) & (cols < image_shape[1] + 0.5)
        R, C = image_shape[:2]
        window = (max(0, int(math.floor(rows[near].min())) - radius - 1),
                  min(R, int(math.ceil(rows[near].max())) + radius + 2),
                  max(0, int(math.floor(cols[near].min())) - radius - 1),
                  min(C, int(math.ceil(cols[near].max())) + radius + 2))
        data = np.asarray(_read_window(kind, handle, *window))
        result = orthorectify(data, shifted, dem_array, dem_window_grid, tile_grid, method, fill)
    return result.reshape(out_shape)


@dataclass(frozen=True)
class TilePlan:
    """One output tile of :func:`orthorectify_tiled`: its grid, DEM window and image window.

    Attributes
    ----------
    row0, col0 : int
        The tile's first pixel in the output grid.
    grid : RasterGrid
        The tile's grid (``grid.window(row0, col0, …)``).
    dem_window : (int, int, int, int)
        DEM rows r0:r1 and columns c0:c1 under the tile plus the halo.
    image_window : (int, int, int, int) or None
        Source-image rows r0:r1 and columns c0:c1 the tile is planned to need (None: the tile
        sees no image).

    References
    ----------
    Chibunichev (2022), §7.3 (the inverse method, one output pixel at a time).

    Examples
    --------
    >>> from photolib.rectify import RasterGrid
    >>> from photolib.georaster import TilePlan
    >>> TilePlan(0, 0, RasterGrid(0, 8, 1, (8, 8)), (0, 4, 0, 4), None).image_window is None
    True
    """

    row0: int
    col0: int
    grid: RasterGrid
    dem_window: tuple
    image_window: object


def plan_tiles(project: Callable, dem, dem_grid: RasterGrid, grid: RasterGrid, image_shape, *,
               tile: int = 512, halo: int = 2, margin: int = 2, method: str = "bilinear",
               height_range=None):
    """The tiles of :func:`orthorectify_tiled` with the DEM and image windows each one needs.

    Each tile's DEM window is the DEM cells under it plus ``halo``; its image window is the
    bounding box of its border pixels (all of them) and a 16-pixel interior lattice projected at
    the DEM window's lowest and highest heights (or ``height_range``), widened by ``margin``
    plus the resampling kernel's reach, clipped to the image.

    Parameters
    ----------
    project : callable
        ``project(X, Y, Z) -> (rows, cols)``.
    dem : (R, C) array or dask array
        Heights on ``dem_grid``.
    dem_grid, grid : RasterGrid
        The DEM's and the orthophoto's grids.
    image_shape : (int, int)
        Rows and columns of the source image.
    tile, halo, margin : int
        Tile size (output pixels), DEM halo (cells), extra image margin (pixels).
    method : {'nearest', 'bilinear', 'bicubic'}
        Resampling (sets the kernel's reach: 1, 1, 2 pixels).
    height_range : (float, float), optional
        Heights to project at instead of each DEM window's extremes.

    Returns
    -------
    list of TilePlan
        Row-major.

    Raises
    ------
    InputError
        Bad grids or sizes, a DEM not covering a tile.

    References
    ----------
    Chibunichev (2022), §7.3, eqs. (7.3.1)–(7.3.2).

    Examples
    --------
    >>> import numpy as np
    >>> from photolib.rectify import RasterGrid
    >>> from photolib.georaster import plan_tiles
    >>> plans = plan_tiles(lambda X, Y, Z: (-Y, X), np.zeros((12, 12)), RasterGrid(-1, 1, 1, (12, 12)),
    ...                    RasterGrid(-0.5, 0.5, 1.0, (10, 10)), (10, 10), tile=8)
    >>> [(p.row0, p.col0, p.image_window) for p in plans]
    [(0, 0, (0, 10, 0, 10)), (0, 8, (0, 10, 5, 10)), (8, 0, (5, 10, 0, 10)), (8, 8, (5, 10, 5, 10))]
    """
    _grid(grid)
    _grid(dem_grid, "dem_grid")
    if not callable(project):
        raise InputError("project must be a callable project(X, Y, Z) -> (rows, cols)")
    if method not in RESAMPLING_METHODS:
        raise InputError(f"method must be one of {RESAMPLING_METHODS}, got {method!r}")
    if isinstance(tile, bool) or not isinstance(tile, (int, np.integer)) or tile < 8:
        raise InputError(f"tile must be an integer ≥ 8, got {tile!r}")
    for value, name in ((halo, "halo"), (margin, "margin")):
        if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < 0:
            raise InputError(f"{name} must be a non-negative integer, got {value!r}")
    try:
        shape = tuple(int(v) for v in image_shape)
    except (TypeError, ValueError):
        raise InputError(f"image_shape must be (rows, cols), got {image_shape!r}") from None
    if len(shape) < 2 or min(shape[:2]) < 1:
        raise InputError(f"image_shape must be (rows, cols), got {image_shape!r}")
    if height_range is not None:
        try:
            zlo, zhi = (float(v) for v in height_range)
        except (TypeError, ValueError):
            raise InputError(f"height_range must be (min, max), got {height_range!r}") from None
        if not (math.isfinite(zlo) and math.isfinite(zhi) and zlo <= zhi):
            raise InputError(f"height_range must be finite (min ≤ max), got {height_range!r}")
        height_range = (zlo, zhi)
    if not type(dem).__module__.startswith("dask"):
        try:
            dem = np.asarray(dem, dtype=np.float64)
        except (TypeError, ValueError):
            raise InputError("dem must be a numeric array") from None
    if dem.ndim != 2 or tuple(dem.shape) != dem_grid.shape:
        raise InputError(f"the DEM's shape {tuple(dem.shape)} does not match its grid {dem_grid.shape}")
    plans = []
    rows_total, cols_total = grid.shape
    for r in range(0, rows_total, tile):
        for c in range(0, cols_total, tile):
            tile_grid = grid.window(r, c, min(tile, rows_total - r), min(tile, cols_total - c))
            dem_window, window = _tile_plan(project, dem, dem_grid, tile_grid, shape, halo,
                                            margin + _KERNEL_RADIUS[method], height_range)
            plans.append(TilePlan(r, c, tile_grid, dem_window, window))
    return plans


class _GeoTIFFTarget:
    """A ``__setitem__`` target for ``dask.array.store`` writing windows of an open GeoTIFF."""

    def __init__(self, dataset):
        self.dataset = dataset

    def __setitem__(self, key, value):
        rows, cols = key[0], key[1]
        window = ((rows.start, rows.stop), (cols.start, cols.stop))
        bands = value[:, :, None] if value.ndim == 2 else value
        self.dataset.write(np.moveaxis(bands, 2, 0).astype(self.dataset.dtypes[0]), window=window)


def orthorectify_tiled(image, project: Callable, dem, dem_grid: RasterGrid, grid: RasterGrid,
                       method: str = "bilinear", fill: float = np.nan, *, tile: int = 512,
                       halo: int = 2, margin: int = 2, height_range=None, compute: bool = True,
                       progress=False, out_path=None, crs=None, nodata=None):
    """Orthophoto by the inverse method of §7.3, tile by tile on Dask (out of core).

    The output grid is cut into ``tile`` × ``tile`` blocks. For each block, with its own
    :class:`RasterGrid` (``grid.window``): the DEM window under it plus ``halo`` DEM cells, the
    image window it needs — the block's border (every pixel) and a 16-pixel interior lattice
    projected at the DEM window's minimum and maximum heights, plus ``margin`` pixels and the
    resampling kernel — and :func:`photolib.rectify.orthorectify` on those windows. Each block
    checks that all of its image positions fell inside the planned window (else it reads the
    exact window it needs), so the tiles equal the in-memory result (to rounding: the tile
    grids' centres are recomputed from shifted origins, ≲ 1e-12 relative).

    Parameters
    ----------
    image : (R, C[, bands]) array, dask array, or path of a raster
        The source image; a dask array is sliced lazily; a raster path is read window by window
        with rasterio (an image larger than memory).
    project : callable
        ``project(X, Y, Z) -> (rows, cols)``, the sensor model (e.g. :func:`rpc_projector`).
    dem : (R, C) array or dask array
        Heights on ``dem_grid`` in the grid's coordinates (e.g. :func:`dem_on_grid` on ``grid``).
    dem_grid : RasterGrid
        The DEM's grid.
    grid : RasterGrid
        The orthophoto's grid.
    method : {'nearest', 'bilinear', 'bicubic'}
        Resampling.
    fill : float
        Value outside the image.
    tile : int
        Block size in output pixels.
    halo : int
        Extra DEM cells around each block's DEM window.
    margin : int
        Extra image pixels around each block's planned image window.
    height_range : (float, float), optional
        Heights to project the block corners at; by default each DEM window's min and max.
    compute : bool
        Return a numpy array (default) or the lazy dask array.
    progress : bool or callable
        True: dask's text progress bar; a callable ``progress(done, total)`` is called after
        every finished block; False (default): silent.
    out_path : str or os.PathLike, optional
        Write the blocks straight into this GeoTIFF (needs ``crs``) and return its path.
    crs : CRS, optional
        The grid's CRS, for ``out_path``.
    nodata : float, optional
        The nodata value written to ``out_path`` (NaN pixels become it).

    Returns
    -------
    ndarray, dask.array.Array or pathlib.Path
        The orthophoto (``grid.shape`` (+ bands)), its lazy form, or the GeoTIFF written.

    Raises
    ------
    InputError
        Bad grids, a DEM not covering a block (naming the area), a bad tile size or method, a
        missing ``crs`` with ``out_path``.
    GeoDependencyError
        dask (or rasterio for paths) missing.

    References
    ----------
    Chibunichev (2022), §7.3, eqs. (7.3.1)–(7.3.2) (the inverse method, pixel by pixel — so any
    partition of the output grid gives the same orthophoto).

    Examples
    --------
    >>> import numpy as np
    >>> from photolib.rectify import RasterGrid, orthorectify
    >>> from photolib.georaster import orthorectify_tiled
    >>> image = np.random.default_rng(0).random((40, 50))
    >>> vertical = lambda X, Y, Z: (-Y + 0.01 * Z, X)
    >>> dem_grid, grid = RasterGrid(-2.0, 2.0, 1.0, (45, 55)), RasterGrid(0.0, 0.0, 0.5, (70, 90))
    >>> dem = np.random.default_rng(1).random((45, 55)) * 50
    >>> tiled = orthorectify_tiled(image, vertical, dem, dem_grid, grid, tile=32)
    >>> whole = orthorectify(image, vertical, dem, dem_grid, grid)
    >>> bool(np.allclose(tiled, whole, rtol=0, atol=1e-12, equal_nan=True))
    True
    """
    da = _import("dask.array")
    dask = _import("dask")
    _grid(grid)
    _grid(dem_grid, "dem_grid")
    if not callable(project):
        raise InputError("project must be a callable project(X, Y, Z) -> (rows, cols)")
    if method not in RESAMPLING_METHODS:
        raise InputError(f"method must be one of {RESAMPLING_METHODS}, got {method!r}")
    if isinstance(tile, bool) or not isinstance(tile, (int, np.integer)) or tile < 8:
        raise InputError(f"tile must be an integer ≥ 8, got {tile!r}")
    if type(dem).__module__.startswith("dask"):
        dem_array = dem
    else:
        try:
            dem_array = np.asarray(dem, dtype=np.float64)
        except (TypeError, ValueError):
            raise InputError("dem must be a numeric array") from None
    if dem_array.ndim != 2 or tuple(dem_array.shape) != dem_grid.shape:
        raise InputError(f"the DEM's shape {tuple(dem_array.shape)} does not match its grid {dem_grid.shape}")
    if out_path is not None and crs is None:
        raise InputError("out_path needs the grid's crs")
    shape, kind, handle = _source(image)
    bands = shape[2] if len(shape) == 3 else 0
    radius = _KERNEL_RADIUS[method]
    fill = float(fill)
    rows_total, cols_total = grid.shape
    plans = plan_tiles(project, dem_array, dem_grid, grid, shape, tile=tile, halo=halo, margin=margin,
                       method=method, height_range=height_range)
    blocks = []
    for plan in plans:
        if plan.col0 == 0:
            line = []
            blocks.append(line)
        tile_grid, window = plan.grid, plan.image_window
        dr0, dr1, dc0, dc1 = plan.dem_window
        dem_window = dem_array[dr0:dr1, dc0:dc1]
        dem_window_grid = dem_grid.window(dr0, dc0, dr1 - dr0, dc1 - dc0)
        if window is None:
            data = None
        elif kind == "numpy":
            data = handle[window[0]:window[1], window[2]:window[3]]
        elif kind == "dask":
            data = handle[window[0]:window[1], window[2]:window[3]]
        else:
            data = dask.delayed(_read_window)(kind, _Opaque(handle), *window)
        block = dask.delayed(_ortho_tile)(data, kind, _Opaque(handle),
                                          shape, bands, project, dem_window, dem_window_grid,
                                          tile_grid, window, method, fill, radius)
        piece = da.from_delayed(block, tile_grid.shape + ((bands,) if bands else ()), dtype=np.float64)
        line.append([piece] if bands else piece)      # da.block nests one list per axis
    ortho = da.block(blocks)
    if not compute and out_path is None:
        return ortho
    with _progress(progress, dask):
        if out_path is None:
            return ortho.compute(scheduler="threads")
        rasterio = _import("rasterio")
        path = _path(out_path, "out_path")
        grid_crs = _crs(crs)
        profile = dict(driver="GTiff", height=rows_total, width=cols_total, count=max(1, bands),
                       dtype="float64", crs=rasterio.crs.CRS.from_wkt(grid_crs.to_wkt()),
                       transform=rasterio.Affine.from_gdal(*grid.geotransform),
                       nodata=None if nodata is None else float(nodata), compress="deflate")
        if min(grid.shape) >= 256:
            profile.update(tiled=True, blockxsize=256, blockysize=256)
        if nodata is not None:
            ortho = da.where(da.isnan(ortho), float(nodata), ortho)
        with rasterio.open(path, "w", **profile) as dst:
            da.store(ortho, _GeoTIFFTarget(dst), lock=True, scheduler="threads")
        return path


def _mosaic_tile(crops_meta, tile_grid, cutline, fill_gaps, bands):
    """One tile of a mosaic: each orthophoto's part of the tile (NaN elsewhere) → rectify.mosaic."""
    from .rectify import mosaic

    crops = []
    for kind, handle, window, offset in crops_meta:
        crop = np.full(tile_grid.shape + ((bands,) if bands else ()), np.nan)
        if window is not None:
            r0, r1, c0, c1 = window
            data = np.asarray(_read_window(kind, handle, r0, r1, c0, c1), dtype=np.float64)
            nodata = getattr(handle.value if isinstance(handle, _Opaque) else handle, "nodata", None)
            if kind == "path" and nodata is not None:
                data = np.where(data == nodata, np.nan, data)
            tr, tc = offset
            crop[tr:tr + (r1 - r0), tc:tc + (c1 - c0)] = data
        crops.append(crop)
    image, _ = mosaic(crops, [tile_grid] * len(crops), cutline, fill_gaps=fill_gaps)
    return image


class _RasterPath(type(Path())):
    """A raster path remembering its nodata value."""

    nodata = None


def mosaic_tiled(orthos, grids, cutline, *, tile: int = 512, fill_gaps: bool = True,
                 compute: bool = True, progress=False):
    """A mosaic of orthophotos by the row rule of §7.7, tile by tile on Dask (out of core).

    The mosaic grid (X₀M = min X₀ᵢ, Y₀M = max Y₀ᵢ, covering all orthophotos) is cut into tiles;
    each tile reads only the parts of the orthophotos that fall on it (NaN elsewhere) and calls
    :func:`photolib.rectify.mosaic` on them with the tile's grid. The row rule and the gap
    filling decide pixel by pixel from object coordinates, so the tiles equal the in-memory
    mosaic.

    Parameters
    ----------
    orthos : sequence of arrays, dask arrays or raster paths
        The orthophotos, west to east (paths are read window by window; their nodata → NaN).
    grids : sequence of RasterGrid or None
        Their grids (one lattice); None reads them from the raster files.
    cutline : (k, 2) array or sequence of them
        As :func:`photolib.rectify.mosaic`.
    tile : int
        Tile size in mosaic pixels.
    fill_gaps : bool
        As :func:`photolib.rectify.mosaic`.
    compute : bool
        Return (ndarray, grid) (default) or (dask array, grid).
    progress : bool or callable
        As :func:`orthorectify_tiled`.

    Returns
    -------
    image : ndarray or dask.array.Array
    grid : RasterGrid

    Raises
    ------
    InputError
        Fewer than two orthophotos, grids of different lattices, bad cutlines, a bad tile size.
    GeoDependencyError
        dask (or rasterio for paths) missing.

    References
    ----------
    Chibunichev (2022), §7.7, Fig. 7.17 (the row rule; mosaic origin X₀M = min, Y₀M = max).

    Examples
    --------
    >>> import numpy as np
    >>> from photolib.rectify import RasterGrid, mosaic
    >>> from photolib.georaster import mosaic_tiled
    >>> west, east = np.zeros((20, 30)), np.ones((20, 30))
    >>> grids = [RasterGrid(0, 20, 1, (20, 30)), RasterGrid(15, 22, 1, (20, 30))]
    >>> cut = [[22.3, -5.0], [20.1, 30.0]]
    >>> tiled, grid = mosaic_tiled([west, east], grids, cut, tile=8)
    >>> whole, _ = mosaic([west, east], grids, cut)
    >>> bool(np.array_equal(tiled, whole, equal_nan=True)), grid.shape
    (True, (22, 45))
    """
    da = _import("dask.array")
    dask = _import("dask")
    if isinstance(orthos, np.ndarray) or not isinstance(orthos, (list, tuple)) or len(orthos) < 2:
        raise InputError("orthos must be a list of at least two orthophotos")
    if isinstance(tile, bool) or not isinstance(tile, (int, np.integer)) or tile < 8:
        raise InputError(f"tile must be an integer ≥ 8, got {tile!r}")
    sources = []
    for k, ortho in enumerate(orthos):
        shape, kind, handle = _source(ortho)
        if kind == "path":
            rasterio = _import("rasterio")
            with rasterio.open(handle) as src:
                file_grid = RasterGrid.from_geotransform(src.transform.to_gdal(), src.shape)
                handle = _RasterPath(handle)
                handle.nodata = src.nodata
            if grids is None:
                sources.append((shape, kind, handle, file_grid))
                continue
        elif grids is None:
            raise InputError("grids may be None only when every orthophoto is a raster path")
        sources.append((shape, kind, handle, None))
    if grids is not None:
        if isinstance(grids, RasterGrid) or not isinstance(grids, (list, tuple)) or len(grids) != len(orthos):
            raise InputError(f"grids must be a list of {len(orthos)} RasterGrid")
        sources = [(s, k, h, _grid(g, f"grids[{i}]")) for i, ((s, k, h, _), g) in enumerate(zip(sources, grids))]
    band_counts = {len(s[0]) == 3 and s[0][2] for s in sources}
    if len(band_counts) != 1:
        raise InputError("the orthophotos have different numbers of bands")
    bands = band_counts.pop() or 0
    for i, (shape, _, _, g) in enumerate(sources):
        if tuple(shape[:2]) != g.shape:
            raise InputError(f"orthos[{i}] has shape {tuple(shape[:2])}, its grid {g.shape}")
    all_grids = [s[3] for s in sources]
    # the mosaic grid of rectify.mosaic (which checks the cutlines in each tile); one lattice
    out_grid = mosaic_grid(all_grids)
    dx, dy = out_grid.dx, out_grid.dy
    rows_total, cols_total = out_grid.shape
    blocks = []
    for r in range(0, rows_total, tile):
        line = []
        for c in range(0, cols_total, tile):
            tile_grid = out_grid.window(r, c, min(tile, rows_total - r), min(tile, cols_total - c))
            metas = []
            for shape, kind, handle, g in sources:
                gr0 = int(round((g.y0 - tile_grid.y0) / dy))      # tile's first row in the ortho
                gc0 = int(round((tile_grid.x0 - g.x0) / dx))
                r0, c0 = max(0, gr0), max(0, gc0)
                r1 = min(g.shape[0], gr0 + tile_grid.shape[0])
                c1 = min(g.shape[1], gc0 + tile_grid.shape[1])
                window = (r0, r1, c0, c1) if r1 > r0 and c1 > c0 else None
                metas.append((kind, _Opaque(handle), window, (r0 - gr0, c0 - gc0)))
            block = dask.delayed(_mosaic_tile)(metas, tile_grid, cutline, fill_gaps, bands)
            piece = da.from_delayed(block, tile_grid.shape + ((bands,) if bands else ()), dtype=np.float64)
            line.append([piece] if bands else piece)
        blocks.append(line)
    image = da.block(blocks)
    if not compute:
        return image, out_grid
    with _progress(progress, dask):
        return image.compute(scheduler="threads"), out_grid


class _NoProgress:
    def __enter__(self):
        return self

    def __exit__(self, *exc):
        return False


def _progress(progress, dask):
    if progress is False or progress is None:
        return _NoProgress()
    diagnostics = _import("dask.diagnostics")
    if progress is True:
        return diagnostics.ProgressBar()
    if not callable(progress):
        raise InputError(f"progress must be True, False or a callable progress(done, total), got {progress!r}")
    callbacks = _import("dask.callbacks")

    class _Report(callbacks.Callback):
        def _start_state(self, dsk, state):
            self._total = sum(len(state[k]) for k in ("ready", "waiting", "running")) + len(state["finished"])
            self._done = 0

        def _posttask(self, key, result, dsk, state, worker_id):
            self._done += 1
            progress(self._done, self._total)

    return _Report()


# --------------------------------------------------------------------------------- real data
@dataclass(frozen=True)
class VentouxScene:
    """One Pléiades crop of Mont Ventoux with everything needed to orthorectify it.

    Attributes
    ----------
    image : (rows, cols) float64 ndarray
        The panchromatic crop.
    rpc : photolib.rpc.RPC
        The full scene's RPC shifted by the crop offset (crop pixel coordinates).
    crop_offset : (float, float)
        (row, col) of the crop's first pixel in the full scene (from the GeoTIFF transform).
    dem, dem_grid, dem_crs
        The SRTM 3″ tile (heights above the EGM96 geoid, NaN voids), its grid and CRS.
    geoid : GeoidModel
        EGM96 undulations.
    image_path : pathlib.Path
        The crop's file.

    References
    ----------
    Chibunichev (2022), §7.3 (orthophoto over a DEM) and §8.5 (RPC). Data: CNES shareloc test
    data (Pléiades 1B, © CNES, Etalab 2.0); SRTM; EGM96.

    Examples
    --------
    >>> from photolib.datasets import DataUnavailableError
    >>> from photolib.georaster import ventoux_scene
    >>> try:
    ...     scene = ventoux_scene("left")
    ... except DataUnavailableError:
    ...     scene = None
    >>> scene is None or scene.image.shape == (500, 500)
    True
    """

    image: np.ndarray
    rpc: object
    crop_offset: tuple
    dem: np.ndarray
    dem_grid: RasterGrid
    dem_crs: object
    geoid: GeoidModel
    image_path: Path

    def __post_init__(self):
        from .rpc import RPC
        image = np.asarray(self.image)
        if image.ndim != 2 or image.dtype.kind not in "iuf" or 0 in image.shape:
            raise InputError(f"image must be a numeric (rows, cols) array, got {image.dtype} {image.shape}")
        if not isinstance(self.rpc, RPC):
            raise InputError(f"rpc must be a photolib.rpc.RPC, got {type(self.rpc).__name__}")
        if not isinstance(self.geoid, GeoidModel):
            raise InputError(f"geoid must be a GeoidModel, got {type(self.geoid).__name__}")
        _grid(self.dem_grid, "dem_grid")
        if np.shape(self.dem) != self.dem_grid.shape:
            raise InputError(f"the DEM's shape {np.shape(self.dem)} does not match its grid {self.dem_grid.shape}")


def ventoux_scene(side: str = "left") -> VentouxScene:
    """The Pléiades Mont Ventoux crop (left or right) with its shifted RPC, SRTM and EGM96.

    Parameters
    ----------
    side : {'left', 'right'}
        Which image of the stereo pair.

    Returns
    -------
    VentouxScene

    Raises
    ------
    photolib.datasets.DataUnavailableError
        The real data is absent (``../shared/data`` or ``PHOTOLIB_DATA``).
    InputError
        An unknown side.
    GeoDependencyError
        rasterio or pyproj missing.

    References
    ----------
    Chibunichev (2022), §7.3 and §8.5.

    Examples
    --------
    >>> from photolib.datasets import DataUnavailableError
    >>> from photolib.georaster import ventoux_scene
    >>> try:
    ...     offset = ventoux_scene("left").crop_offset
    ... except DataUnavailableError:
    ...     offset = (5000.0, 5000.0)
    >>> offset
    (5000.0, 5000.0)
    """
    from .datasets import data_path
    from .rpc import RPC

    if side not in ("left", "right"):
        raise InputError(f"side must be 'left' or 'right', got {side!r}")
    folder = ("satellite", "pleiades_ventoux")
    image_path = data_path(*folder, f"{side}_image.tif")
    geom_path = data_path(*folder, f"{side}_image.geom")
    srtm_path = data_path(*folder, "N44E005.hgt")
    geoid_path = data_path(*folder, "egm96_15.gtx")
    rasterio = _import("rasterio")
    with rasterio.open(image_path) as src:
        image = src.read(1).astype(np.float64)
        transform = src.transform
    # the crop is not georeferenced: its transform holds the offset in full-scene pixels
    offset = (float(transform.f), float(transform.c))
    rpc = RPC.from_ossim_geom(geom_path).shifted(*offset)
    dem, dem_grid, dem_crs = read_dem(srtm_path)
    return VentouxScene(image=image, rpc=rpc, crop_offset=offset, dem=dem, dem_grid=dem_grid,
                        dem_crs=dem_crs, geoid=read_geoid(geoid_path), image_path=image_path)
