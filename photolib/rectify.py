"""Digital rectification and orthophotos of frame images — Chapter 7, §7.1–7.4, §7.7, §7.9.

The output of a rectification is a raster in object space. :class:`RasterGrid` describes it the
way §7.3 and §7.7 do: object X east, Y north, square or rectangular pixels of size Δ·m, and the
origin (X₀, Y₀) at the top-left corner of the top-left pixel (§7.7: X₀ = min X, Y₀ = max Y), so
that row i grows southwards. The same type describes a DEM grid.

Image positions are (row, col) pixel coordinates with (0, 0) at the centre of the first pixel
(as :mod:`photolib.rpc`; GDAL's pixel coordinates are ours + 0.5).

The inverse (indirect) method of §7.2–7.3 is :func:`orthorectify`: for every output pixel take
its centre (X, Y), interpolate the height Z in the DEM bilinearly (7.3.1), find the image position
through the sensor model — any callable ``project(X, Y, Z) -> (rows, cols)``, such as
:func:`frame_projector` for collinearity (7.3.2), a pushbroom sensor or an RPC — and resample the
image there (:func:`resample`: nearest neighbour, bilinear or bicubic). The forward (direct)
method, which accumulates each source pixel over the output pixels it covers, is
:func:`rectify_forward`.

Also here: central-projection targets of §7.2 (:func:`rectify_homography`,
:func:`rectify_to_horizontal`); the ortho pixel Δ·m and the geodetic ↔ geocentric ↔ topocentric
conversions of §7.3 (topocentric X north, Z along the ellipsoid normal, Y completing a
right-handed system, i.e. west; GSK-2011 and WGS-84 ellipsoids; plain numpy, no pyproj); the
tolerances (7.4.1)–(7.4.2) of §7.4; monoplotting by the iteration of Fig. 7.19 (7.7.1), cutlines
and mosaics of §7.7; the accuracy checks of §7.9.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable

import numpy as np

from .errors import InputError

__all__ = ["RasterGrid", "RESAMPLING_METHODS", "resample", "rectify_forward", "dem_height",
           "frame_projector", "orthorectify", "mosaic_grid", "rectify_homography", "rectify_to_horizontal",
           "ortho_pixel_size", "ELLIPSOIDS", "geodetic_to_geocentric", "geocentric_to_geodetic",
           "topocentric_matrix", "geocentric_to_topocentric", "topocentric_to_geocentric",
           "map_tolerance", "admissible_height", "relief_displacement", "MonoplotResult", "monoplot",
           "cutline_boundary", "mosaic", "AccuracyReport", "ortho_accuracy", "apriori_accuracy"]

RESAMPLING_METHODS = ("nearest", "bilinear", "bicubic")


def _kernels():
    from . import _rectify_kernels
    return _rectify_kernels


def _finite_float(value, name, positive=False):
    try:
        number = float(value)
    except (TypeError, ValueError):
        raise InputError(f"{name} must be a number, got {value!r}") from None
    if not math.isfinite(number):
        raise InputError(f"{name} must be finite, got {number}")
    if positive and number <= 0:
        raise InputError(f"{name} must be positive, got {number}")
    return number


@dataclass(frozen=True)
class RasterGrid:
    """A north-up raster grid in object space (an orthophoto, a mosaic or a DEM).

    Parameters
    ----------
    x0, y0 : float
        Object coordinates of the top-left corner of the top-left pixel (X₀ = min X, Y₀ = max Y).
    pixel_size : float or (float, float)
        Pixel size Δ·m along X and along Y (one number for square pixels); positive.
    shape : (int, int)
        Rows and columns.

    Attributes
    ----------
    dx, dy : float
        Pixel size along X (columns) and Y (rows).
    geotransform : tuple
        The GDAL geotransform (x0, dx, 0, y0, 0, −dy).
    extent : tuple
        (X min, Y min, X max, Y max) of the outer pixel edges.

    References
    ----------
    Chibunichev (2022), §7.3 (ortho grid aligned with the object axes, pixel Δ·m, origin on pixel
    multiples) and §7.7 (mosaic origin X₀M = min, Y₀M = max).

    Examples
    --------
    >>> from photolib.rectify import RasterGrid
    >>> grid = RasterGrid(1000.0, 2000.0, 0.5, (4, 6))
    >>> grid.xy(0, 0)
    (1000.25, 1999.75)
    >>> grid.rowcol(1000.25, 1999.75)
    (0.0, 0.0)
    """

    x0: float
    y0: float
    pixel_size: object
    shape: tuple

    def __post_init__(self):
        object.__setattr__(self, "x0", _finite_float(self.x0, "x0"))
        object.__setattr__(self, "y0", _finite_float(self.y0, "y0"))
        size = np.atleast_1d(np.asarray(self.pixel_size, dtype=object))
        if size.size not in (1, 2):
            raise InputError(f"pixel_size must be one number or (dx, dy), got {self.pixel_size!r}")
        dx = _finite_float(size[0], "pixel_size", positive=True)
        dy = _finite_float(size[-1], "pixel_size", positive=True)
        object.__setattr__(self, "pixel_size", (dx, dy))
        try:
            rows, cols = (int(v) for v in self.shape)
        except (TypeError, ValueError):
            raise InputError(f"shape must be (rows, cols), got {self.shape!r}") from None
        if rows < 1 or cols < 1 or (rows, cols) != tuple(self.shape):
            raise InputError(f"shape must be two positive integers, got {self.shape!r}")
        object.__setattr__(self, "shape", (rows, cols))

    @property
    def dx(self) -> float:
        return self.pixel_size[0]

    @property
    def dy(self) -> float:
        return self.pixel_size[1]

    @property
    def geotransform(self) -> tuple:
        return (self.x0, self.dx, 0.0, self.y0, 0.0, -self.dy)

    @property
    def extent(self) -> tuple:
        rows, cols = self.shape
        return (self.x0, self.y0 - rows * self.dy, self.x0 + cols * self.dx, self.y0)

    @classmethod
    def from_geotransform(cls, geotransform, shape) -> "RasterGrid":
        """The grid of a north-up GDAL geotransform (x0, dx, 0, y0, 0, −dy).

        Parameters
        ----------
        geotransform : sequence of 6 floats
            GDAL's (or ``rasterio``'s ``transform.to_gdal()``) geotransform.
        shape : (int, int)
            Rows and columns.

        Returns
        -------
        RasterGrid

        Raises
        ------
        InputError
            A rotated or south-up geotransform, or a wrong length.

        References
        ----------
        Chibunichev (2022), §7.3.

        Examples
        --------
        >>> from photolib.rectify import RasterGrid
        >>> RasterGrid.from_geotransform((10.0, 2.0, 0.0, 50.0, 0.0, -2.0), (3, 3)).extent
        (10.0, 44.0, 16.0, 50.0)
        """
        try:
            x0, dx, rx, y0, ry, dy = (float(v) for v in geotransform)
        except (TypeError, ValueError):
            raise InputError(f"a geotransform has six numbers, got {geotransform!r}") from None
        if rx != 0.0 or ry != 0.0 or dy >= 0.0:
            raise InputError(f"only north-up grids are supported (no rotation, negative row step); "
                             f"got {tuple(geotransform)}")
        return cls(x0, y0, (dx, -dy), shape)

    @classmethod
    def aligned(cls, xmin, ymin, xmax, ymax, pixel_size) -> "RasterGrid":
        """The smallest grid covering an area whose origin lies on multiples of the pixel size.

        Parameters
        ----------
        xmin, ymin, xmax, ymax : float
            The area to cover, object units.
        pixel_size : float
            Δ·m (§7.3).

        Returns
        -------
        RasterGrid

        Raises
        ------
        InputError
            An empty area, NaN, a non-positive pixel size.

        References
        ----------
        Chibunichev (2022), §7.3: the origin's coordinates are multiples of the pixel size, so that
        orthophotos of neighbouring images share one pixel lattice (§7.7).

        Examples
        --------
        >>> from photolib.rectify import RasterGrid
        >>> RasterGrid.aligned(101.3, 49.2, 104.9, 52.1, 1.0)
        RasterGrid(x0=101.0, y0=53.0, pixel_size=(1.0, 1.0), shape=(4, 4))
        """
        xmin, ymin = _finite_float(xmin, "xmin"), _finite_float(ymin, "ymin")
        xmax, ymax = _finite_float(xmax, "xmax"), _finite_float(ymax, "ymax")
        size = _finite_float(pixel_size, "pixel_size", positive=True)
        if xmax <= xmin or ymax <= ymin:
            raise InputError(f"the area is empty: x {xmin}..{xmax}, y {ymin}..{ymax}")
        x0 = math.floor(xmin / size) * size
        y0 = math.ceil(ymax / size) * size
        cols = max(1, math.ceil((xmax - x0) / size - 1e-9))
        rows = max(1, math.ceil((y0 - ymin) / size - 1e-9))
        return cls(x0, y0, size, (rows, cols))

    def xy(self, rows, cols):
        """Object X, Y of (fractional) pixel positions; integer positions are pixel centres.

        Parameters
        ----------
        rows, cols : float or array
            Pixel positions.

        Returns
        -------
        X, Y : float or ndarray

        Raises
        ------
        InputError
            Non-numeric positions.

        References
        ----------
        Chibunichev (2022), §7.3.

        Examples
        --------
        >>> from photolib.rectify import RasterGrid
        >>> RasterGrid(0.0, 10.0, 2.0, (5, 5)).xy(1, 2)
        (5.0, 7.0)
        """
        rows, cols = _as_arrays(rows, cols, "rows", "cols")
        X = self.x0 + (cols + 0.5) * self.dx
        Y = self.y0 - (rows + 0.5) * self.dy
        return (float(X), float(Y)) if X.ndim == 0 else (X, Y)

    def rowcol(self, X, Y):
        """Fractional pixel positions of object X, Y (the inverse of :meth:`xy`).

        Parameters
        ----------
        X, Y : float or array
            Object coordinates.

        Returns
        -------
        rows, cols : float or ndarray

        Raises
        ------
        InputError
            Non-numeric coordinates.

        References
        ----------
        Chibunichev (2022), §7.3.

        Examples
        --------
        >>> from photolib.rectify import RasterGrid
        >>> RasterGrid(0.0, 10.0, 2.0, (5, 5)).rowcol(5.0, 7.0)
        (1.0, 2.0)
        """
        X, Y = _as_arrays(X, Y, "X", "Y")
        rows = (self.y0 - Y) / self.dy - 0.5
        cols = (X - self.x0) / self.dx - 0.5
        return (float(rows), float(cols)) if rows.ndim == 0 else (rows, cols)

    def centres(self):
        """Object X, Y of every pixel centre, two arrays of the grid's shape.

        Returns
        -------
        X, Y : ndarray

        References
        ----------
        Chibunichev (2022), §7.3 (the centre of each orthophoto pixel is projected).

        Examples
        --------
        >>> from photolib.rectify import RasterGrid
        >>> X, Y = RasterGrid(0.0, 2.0, 1.0, (2, 3)).centres()
        >>> X[0].tolist(), Y[:, 0].tolist()
        ([0.5, 1.5, 2.5], [1.5, 0.5])
        """
        rows, cols = self.shape
        X = self.x0 + (np.arange(cols) + 0.5) * self.dx
        Y = self.y0 - (np.arange(rows) + 0.5) * self.dy
        return np.meshgrid(X, Y)

    def window(self, row0, col0, rows, cols) -> "RasterGrid":
        """The sub-grid of ``rows`` × ``cols`` pixels starting at pixel (row0, col0).

        Parameters
        ----------
        row0, col0 : int
            First pixel of the window (may lie outside the grid: tiles with a halo).
        rows, cols : int
            Window size.

        Returns
        -------
        RasterGrid

        Raises
        ------
        InputError
            A non-positive window size.

        References
        ----------
        Chibunichev (2022), §7.7 (orthophotos on one pixel lattice).

        Examples
        --------
        >>> from photolib.rectify import RasterGrid
        >>> RasterGrid(0.0, 10.0, 1.0, (10, 10)).window(2, 3, 4, 5)
        RasterGrid(x0=3.0, y0=8.0, pixel_size=(1.0, 1.0), shape=(4, 5))
        """
        return RasterGrid(self.x0 + int(col0) * self.dx, self.y0 - int(row0) * self.dy,
                          self.pixel_size, (rows, cols))


def _as_arrays(a, b, name_a, name_b):
    try:
        a = np.asarray(a, dtype=np.float64)
        b = np.asarray(b, dtype=np.float64)
        a, b = np.broadcast_arrays(a, b)
    except (TypeError, ValueError):
        raise InputError(f"{name_a} and {name_b} must be numbers or arrays of one shape") from None
    return a, b


def _image_bands(image, name="image"):
    try:
        array = np.asarray(image, dtype=np.float64)
    except (TypeError, ValueError):
        raise InputError(f"{name} must be a numeric array") from None
    if array.ndim not in (2, 3) or array.shape[0] < 1 or array.shape[1] < 1:
        raise InputError(f"{name} must be (rows, cols) or (rows, cols, bands), got shape {array.shape}")
    return array


def resample(image, rows, cols, method: str = "bilinear", fill: float = np.nan, *,
             cubic_a: float = -0.5):
    """Brightness of an image at fractional pixel positions (§7.2 resampling).

    Parameters
    ----------
    image : (R, C) or (R, C, bands) array
        The source image; NaN pixels propagate.
    rows, cols : arrays of one shape
        Positions, (0, 0) = centre of the first pixel.
    method : {'nearest', 'bilinear', 'bicubic'}
        Nearest neighbour (the pixel whose centre is closest, the book's 150.3, 21.7 → 150, 22),
        bilinear, or bicubic (Keys' cubic convolution with parameter ``cubic_a``).
    fill : float
        Value for positions outside the image (nearest: beyond half a pixel from the edge
        centres; bilinear and bicubic: outside the span of the pixel centres; bicubic replicates
        the edge pixels for the taps beyond the edge — OpenCV's BORDER_REPLICATE).
    cubic_a : float
        The cubic kernel's parameter: −0.5 (Keys; GDAL's and PIL's 'cubic'; exact on quadratic
        brightness) or −0.75 (OpenCV's INTER_CUBIC).

    Returns
    -------
    ndarray
        ``rows.shape`` (+ ``(bands,)`` for a 3-D image), float64.

    Raises
    ------
    InputError
        An unknown method, a non-image, positions of different shapes or NaN positions.

    References
    ----------
    Chibunichev (2022), §7.2 (nearest neighbour and bilinear interpolation) and §7.3 (bicubic).

    Examples
    --------
    >>> import numpy as np
    >>> from photolib.rectify import resample
    >>> image = np.arange(12.0).reshape(3, 4)
    >>> resample(image, [0.5], [1.5]).tolist(), resample(image, [0.6], [1.4], "nearest").tolist()
    ([3.5], [5.0])
    """
    if method not in RESAMPLING_METHODS:
        raise InputError(f"method must be one of {RESAMPLING_METHODS}, got {method!r}")
    array = _image_bands(image)
    rows, cols = _as_arrays(rows, cols, "rows", "cols")
    if np.isnan(rows).any() or np.isnan(cols).any():
        raise InputError("positions contain NaN (a sensor model that failed should give fill "
                         "positions outside the image, e.g. -1e9)")
    try:
        fill = float(fill)
    except (TypeError, ValueError):
        raise InputError(f"fill must be a number (NaN allowed), got {fill!r}") from None
    kernels = _kernels()
    bands = kernels.as_float_bands(array)
    out = np.empty((rows.size, bands.shape[2]))
    kernel = {"nearest": kernels.resample_nearest, "bilinear": kernels.resample_bilinear,
              "bicubic": kernels.resample_bicubic}[method]
    args = (bands, np.ascontiguousarray(rows.ravel()), np.ascontiguousarray(cols.ravel()), fill, out)
    if method == "bicubic":
        kernel(*args, _finite_float(cubic_a, "cubic_a"))
    else:
        kernel(*args)
    shape = rows.shape + ((bands.shape[2],) if array.ndim == 3 else ())
    return out.reshape(shape)


def rectify_forward(image, rows, cols, out_shape):
    """Forward (direct) rectification by accumulation (§7.2, (7.2.1)).

    Every source pixel is mapped to a fractional output position; its brightness is spread over
    the (up to) four output pixels around that position in proportion to the overlapped areas of
    a pixel-sized square centred there (the bilinear weights of the book's example), and each
    output pixel is the weighted mean of what it received. Output pixels that received nothing
    are the holes of the forward method.

    Parameters
    ----------
    image : (R, C) or (R, C, bands) array
        Source image.
    rows, cols : (R, C) arrays
        Output pixel positions of each source pixel's centre ((7.2.1) applied to the source grid).
    out_shape : (int, int)
        Output rows and columns.

    Returns
    -------
    rectified : ndarray
        The output image, NaN in the holes.
    weight : (rows, cols) ndarray
        The accumulated weight of each output pixel (0 in the holes).

    Raises
    ------
    InputError
        Positions that do not match the image, NaN, a bad output shape.

    References
    ----------
    Chibunichev (2022), §7.2, eq. (7.2.1) and the area-weighted accumulation of Fig. 7.3.

    Examples
    --------
    >>> import numpy as np
    >>> from photolib.rectify import rectify_forward
    >>> out, weight = rectify_forward(np.array([[100.0]]), np.array([[0.7]]), np.array([[0.3]]), (2, 2))
    >>> np.round(weight, 2).tolist()
    [[0.21, 0.09], [0.49, 0.21]]
    """
    array = _image_bands(image)
    rows, cols = _as_arrays(rows, cols, "rows", "cols")
    if rows.shape != array.shape[:2]:
        raise InputError(f"rows/cols must have the image's shape {array.shape[:2]}, got {rows.shape}")
    if not (np.isfinite(rows).all() and np.isfinite(cols).all()):
        raise InputError("output positions contain NaN or inf")
    try:
        n_rows, n_cols = (int(v) for v in out_shape)
    except (TypeError, ValueError):
        raise InputError(f"out_shape must be (rows, cols), got {out_shape!r}") from None
    if n_rows < 1 or n_cols < 1:
        raise InputError(f"out_shape must be positive, got {out_shape!r}")
    kernels = _kernels()
    bands = kernels.as_float_bands(array)
    values = bands.reshape(-1, bands.shape[2])
    total = np.zeros((n_rows, n_cols, bands.shape[2]))
    weight = np.zeros((n_rows, n_cols))
    kernels.accumulate_forward(values, np.ascontiguousarray(rows.ravel()),
                               np.ascontiguousarray(cols.ravel()), total, weight)
    with np.errstate(invalid="ignore", divide="ignore"):
        result = total / weight[:, :, None]
    result[weight == 0] = np.nan
    return (result if array.ndim == 3 else result[:, :, 0]), weight


def _coverage_message(dem_grid, X, Y, outside):
    xs, ys = X[outside], Y[outside]
    xmin, ymin, xmax, ymax = dem_grid.extent
    return (f"the DEM does not cover {outside.sum()} of {outside.size} requested points: the "
            f"missing area spans X {xs.min():.6g}..{xs.max():.6g}, Y {ys.min():.6g}..{ys.max():.6g} "
            f"(DEM centres span X {xmin + dem_grid.dx / 2:.6g}..{xmax - dem_grid.dx / 2:.6g}, "
            f"Y {ymin + dem_grid.dy / 2:.6g}..{ymax - dem_grid.dy / 2:.6g})")


def dem_height(dem, dem_grid: RasterGrid, X, Y, *, outside: str = "raise"):
    """Height at object points by bilinear interpolation in a DEM grid (7.3.1).

    The DEM's values are heights at its pixel centres.

    Parameters
    ----------
    dem : (R, C) array
        Heights; NaN marks voids (a point whose cell touches a void gets NaN).
    dem_grid : RasterGrid
        The DEM's grid.
    X, Y : arrays of one shape
        Object coordinates.
    outside : {'raise', 'nan'}
        Points outside the span of the DEM's pixel centres raise :class:`InputError` naming the
        missing area (default) or get NaN.

    Returns
    -------
    ndarray
        Heights, the shape of X.

    Raises
    ------
    InputError
        A DEM that does not match its grid, NaN coordinates, points outside the DEM.

    References
    ----------
    Chibunichev (2022), §7.3, eq. (7.3.1) and Fig. 7.6.

    Examples
    --------
    >>> import numpy as np
    >>> from photolib.rectify import RasterGrid, dem_height
    >>> grid = RasterGrid(0.0, 20.0, 10.0, (2, 2))      # centres at X 5, 15 and Y 15, 5
    >>> dem = np.array([[100.0, 110.0], [120.0, 130.0]])
    >>> float(dem_height(dem, grid, 10.0, 10.0))
    115.0
    """
    if not isinstance(dem_grid, RasterGrid):
        raise InputError(f"dem_grid must be a RasterGrid, got {type(dem_grid).__name__}")
    if outside not in ("raise", "nan"):
        raise InputError(f"outside must be 'raise' or 'nan', got {outside!r}")
    heights = _image_bands(dem, "dem")
    if heights.ndim != 2 or heights.shape != dem_grid.shape:
        raise InputError(f"the DEM's shape {heights.shape} does not match its grid {dem_grid.shape}")
    X, Y = _as_arrays(X, Y, "X", "Y")
    if not (np.isfinite(X).all() and np.isfinite(Y).all()):
        raise InputError("X, Y contain NaN or inf")
    rows, cols = dem_grid.rowcol(X, Y)
    rows, cols = np.asarray(rows), np.asarray(cols)
    eps = 1e-9
    miss = (rows < -eps) | (rows > dem_grid.shape[0] - 1 + eps) | (cols < -eps) | (cols > dem_grid.shape[1] - 1 + eps)
    if miss.any() and outside == "raise":
        raise InputError(_coverage_message(dem_grid, X, Y, miss))
    rows = np.clip(rows, 0.0, dem_grid.shape[0] - 1)
    cols = np.clip(cols, 0.0, dem_grid.shape[1] - 1)
    Z = resample(heights, rows, cols, "bilinear")
    Z[miss] = np.nan
    return Z


def frame_projector(eo, io, pixel_size: float, image_shape) -> Callable:
    """A sensor callable ``project(X, Y, Z) -> (rows, cols)`` for a frame image (7.3.2).

    Collinearity through :func:`photolib.single_image.project`, then photo coordinates (mm,
    origin at the frame centre, y up) to pixel positions.

    Parameters
    ----------
    eo : photolib.camera.ExteriorOrientation
        The image's exterior orientation.
    io : photolib.camera.InteriorOrientation
        The camera (f, x₀, y₀, distortion), mm.
    pixel_size : float
        Δ, mm.
    image_shape : (int, int)
        Rows and columns of the image.

    Returns
    -------
    callable
        ``project(X, Y, Z)`` on arrays of one shape, returning (rows, cols) of that shape; points
        behind the camera get positions far outside the image (so they resample to ``fill``).

    Raises
    ------
    InputError
        A non-positive pixel size or a bad image shape.

    References
    ----------
    Chibunichev (2022), §7.3, eq. (7.3.2).

    Examples
    --------
    >>> from photolib.camera import ExteriorOrientation, InteriorOrientation
    >>> from photolib.rectify import frame_projector
    >>> project = frame_projector(ExteriorOrientation(0.0, 0.0, 1000.0), InteriorOrientation(f=100.0),
    ...                           0.01, (1001, 1001))
    >>> rows, cols = project([0.0, 10.0], [0.0, 0.0], [0.0, 0.0])
    >>> rows.tolist(), cols.tolist()
    ([500.0, 500.0], [500.0, 600.0])
    """
    from .camera import ExteriorOrientation, InteriorOrientation
    from .single_image import camera_coordinates, project as collinearity
    from .synthetic import image_to_pixel

    if not isinstance(eo, ExteriorOrientation):
        raise InputError(f"eo must be an ExteriorOrientation, got {type(eo).__name__}")
    if not isinstance(io, InteriorOrientation):
        raise InputError(f"io must be an InteriorOrientation, got {type(io).__name__}")
    size = _finite_float(pixel_size, "pixel_size", positive=True)
    try:
        shape = tuple(int(v) for v in image_shape)
    except (TypeError, ValueError):
        raise InputError(f"image_shape must be (rows, cols), got {image_shape!r}") from None
    if len(shape) != 2 or min(shape) < 1:
        raise InputError(f"image_shape must be (rows, cols), got {image_shape!r}")

    def project(X, Y, Z):
        X, Y = _as_arrays(X, Y, "X", "Y")
        Z = np.broadcast_to(np.asarray(Z, dtype=np.float64), X.shape)
        points = np.column_stack([X.ravel(), Y.ravel(), Z.ravel()])
        rows = np.full(points.shape[0], -1e9)
        cols = np.full(points.shape[0], -1e9)
        in_front = camera_coordinates(points, eo)[:, 2] < 0
        if in_front.any():
            xy = collinearity(points[in_front], eo, io)
            colrow = image_to_pixel(xy, shape, size)
            cols[in_front], rows[in_front] = colrow[:, 0], colrow[:, 1]
        return rows.reshape(X.shape), cols.reshape(X.shape)

    return project


def orthorectify(image, project: Callable, dem, dem_grid: RasterGrid, grid: RasterGrid,
                 method: str = "bilinear", fill: float = np.nan):
    """Orthophoto by the inverse method over a DEM (§7.3).

    For every pixel of ``grid``: its centre (X, Y), the height Z from the DEM (7.3.1), the image
    position from the sensor model, and the brightness resampled there.

    Parameters
    ----------
    image : (R, C) or (R, C, bands) array
        The source image.
    project : callable
        ``project(X, Y, Z) -> (rows, cols)``: the sensor model in the grid's coordinates (e.g.
        :func:`frame_projector`; a pushbroom sensor; an RPC wrapped to the grid's CRS).
    dem : (R, C) array
        Heights on ``dem_grid``, in the grid's coordinates.
    dem_grid : RasterGrid
        The DEM's grid (same X, Y system as ``grid``).
    grid : RasterGrid
        The orthophoto's grid.
    method : {'nearest', 'bilinear', 'bicubic'}
        Resampling of the image.
    fill : float
        Value of orthophoto pixels whose image position falls outside the image.

    Returns
    -------
    ndarray
        The orthophoto, ``grid.shape`` (+ bands).

    Raises
    ------
    InputError
        A DEM that does not cover the grid (the message names the missing area), a sensor model
        returning arrays of the wrong shape, an unknown method.

    References
    ----------
    Chibunichev (2022), §7.3, eqs. (7.3.1)–(7.3.2), Figs. 7.5–7.6.

    Examples
    --------
    >>> import numpy as np
    >>> from photolib.rectify import RasterGrid, orthorectify
    >>> image = np.arange(16.0).reshape(4, 4)
    >>> dem_grid = RasterGrid(-10.0, 10.0, 5.0, (4, 4))
    >>> vertical = lambda X, Y, Z: (-Y, X)        # 1 m pixels: X = col, Y = −row
    >>> orthorectify(image, vertical, np.zeros((4, 4)), dem_grid, RasterGrid(-0.5, 0.5, 1.0, (2, 2)))
    array([[0., 1.],
           [4., 5.]])
    """
    if not isinstance(grid, RasterGrid):
        raise InputError(f"grid must be a RasterGrid, got {type(grid).__name__}")
    if not callable(project):
        raise InputError("project must be a callable project(X, Y, Z) -> (rows, cols)")
    X, Y = grid.centres()
    Z = dem_height(dem, dem_grid, X, Y)
    rows, cols = project(X, Y, Z)
    rows, cols = np.asarray(rows, dtype=np.float64), np.asarray(cols, dtype=np.float64)
    if rows.shape != X.shape or cols.shape != X.shape:
        raise InputError(f"the sensor model returned positions of shape {rows.shape}, "
                         f"expected {X.shape}")
    void = np.isnan(Z) | np.isnan(rows) | np.isnan(cols)
    rows = np.where(void, -1e9, rows)
    cols = np.where(void, -1e9, cols)
    return resample(image, rows, cols, method, fill)


# ============================================================================ §7.2 planar targets
def rectify_homography(image, H, out_shape, method: str = "bilinear", fill: float = np.nan):
    """Inverse rectification by a plane-to-plane (central) projection (§7.2, (7.2.2)).

    Every output pixel (row, col) is mapped to the source by the homography ``H`` acting on
    homogeneous (col, row, 1) — the column is x, the row is y, as in the book's nearest-neighbour
    example — and resampled there. The mapping is the inverse one of the book: output → source.

    Parameters
    ----------
    image : (R, C) or (R, C, bands) array
        The source image.
    H : (3, 3) array
        Output pixel (col, row, 1) → source pixel (col, row, 1), up to scale.
    out_shape : (int, int)
        Rows and columns of the output.
    method : {'nearest', 'bilinear', 'bicubic'}
        Resampling.
    fill : float
        Value of output pixels mapped outside the source or to infinity.

    Returns
    -------
    ndarray
        The rectified image, ``out_shape`` (+ bands).

    Raises
    ------
    InputError
        A non-finite or singular H, a bad output shape, an unknown method.

    References
    ----------
    Chibunichev (2022), §7.2, eqs. (7.2.1)–(7.2.2) (central projection as the target: normal-case
    stereo pairs, perspective views) and Fig. 7.4.

    Examples
    --------
    >>> import numpy as np
    >>> from photolib.rectify import rectify_homography
    >>> image = np.arange(12.0).reshape(3, 4)
    >>> shift = np.array([[1.0, 0.0, 1.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]])   # col + 1
    >>> rectify_homography(image, shift, (2, 2), "nearest")
    array([[1., 2.],
           [5., 6.]])
    """
    try:
        H = np.asarray(H, dtype=np.float64)
    except (TypeError, ValueError):
        raise InputError("H must be a 3 × 3 numeric matrix") from None
    if H.shape != (3, 3) or not np.isfinite(H).all():
        raise InputError(f"H must be a finite 3 × 3 matrix, got shape {H.shape}")
    if abs(np.linalg.det(H)) <= 1e-12 * max(np.abs(H).max(), 1e-300) ** 3:
        raise InputError("H is singular: it does not map a plane onto a plane")
    n_rows, n_cols = _shape2(out_shape, "out_shape")
    rows, cols = np.mgrid[0:n_rows, 0:n_cols].astype(np.float64)
    w = H[2, 0] * cols + H[2, 1] * rows + H[2, 2]
    ok = np.abs(w) > 1e-12
    safe = np.where(ok, w, 1.0)
    src_cols = np.where(ok, (H[0, 0] * cols + H[0, 1] * rows + H[0, 2]) / safe, -1e9)
    src_rows = np.where(ok, (H[1, 0] * cols + H[1, 1] * rows + H[1, 2]) / safe, -1e9)
    return resample(image, src_rows, src_cols, method, fill)


def rectify_to_horizontal(image, A, f: float, pixel_size: float, *, f0: float | None = None,
                          out_shape=None, out_pixel_size: float | None = None,
                          method: str = "bilinear", fill: float = np.nan):
    """A tilted frame image re-projected onto the horizontal image plane of the same centre (§7.2).

    The central-projection target of §7.2 (no DEM needed): for every pixel of the horizontal
    image, its photo coordinates (x⁰, y⁰), the tilted image's (x, y) by (1.7.10)
    (:func:`photolib.single_image.horizontal_to_tilted`) and the brightness resampled there. With
    the relative-orientation angles of a pair it gives the normal-case ("ideal") stereo pair.

    Parameters
    ----------
    image : (R, C) or (R, C, bands) array
        The tilted image; frame centre = principal point (the convention of
        :func:`photolib.synthetic.pixel_to_image`).
    A : (3, 3) array
        Rotation of the tilted camera relative to the horizontal one (e.g. ``eo.matrix``).
    f : float
        Focal length of the tilted image, mm.
    pixel_size : float
        Δ of the tilted image, mm.
    f0 : float, optional
        Focal length of the horizontal image (default ``f``).
    out_shape : (int, int), optional
        Output rows and columns (default: the input's).
    out_pixel_size : float, optional
        Δ of the output, mm (default ``pixel_size``).
    method : {'nearest', 'bilinear', 'bicubic'}
        Resampling.
    fill : float
        Value of output pixels whose ray misses the tilted frame (or its plane).

    Returns
    -------
    ndarray
        The horizontal image.

    Raises
    ------
    InputError
        A non-rotation ``A``, non-positive f, Δ, a bad shape.

    References
    ----------
    Chibunichev (2022), §7.2 (central projection as the target, "formulas linking the
    coordinates of a horizontal and a tilted image") and §1.7, eqs. (1.7.8)–(1.7.10).

    Examples
    --------
    >>> import numpy as np
    >>> from photolib.rectify import rectify_to_horizontal
    >>> image = np.arange(25.0).reshape(5, 5)
    >>> bool(np.allclose(rectify_to_horizontal(image, np.eye(3), 100.0, 0.01), image))
    True
    """
    from .rotation import _as_rotation
    from .single_image import horizontal_to_tilted
    from .synthetic import image_to_pixel, pixel_to_image

    array = _image_bands(image)
    A = _as_rotation(A, "A")
    f = _finite_float(f, "f", positive=True)
    size = _finite_float(pixel_size, "pixel_size", positive=True)
    f0 = f if f0 is None else _finite_float(f0, "f0", positive=True)
    out_size = size if out_pixel_size is None else _finite_float(out_pixel_size, "out_pixel_size", positive=True)
    shape = array.shape[:2] if out_shape is None else _shape2(out_shape, "out_shape")
    rows, cols = np.mgrid[0:shape[0], 0:shape[1]].astype(np.float64)
    x0, y0 = pixel_to_image(cols.ravel(), rows.ravel(), shape, out_size)
    xy0 = np.column_stack([x0, y0])
    # a horizontal ray (x⁰, y⁰, −f⁰) reaches the tilted image plane where Aᵀr has z < 0
    reach = (np.column_stack([xy0, np.full(len(xy0), -f0)]) @ A)[:, 2] < 0
    src = np.full((len(xy0), 2), -1e9)
    if reach.any():
        xy = horizontal_to_tilted(xy0[reach], A, f, f0)
        src[reach] = image_to_pixel(xy, array.shape[:2], size)
    return resample(array, src[:, 1].reshape(shape), src[:, 0].reshape(shape), method, fill)


def _shape2(value, name):
    try:
        n_rows, n_cols = (int(v) for v in value)
    except (TypeError, ValueError):
        raise InputError(f"{name} must be (rows, cols), got {value!r}") from None
    if n_rows < 1 or n_cols < 1:
        raise InputError(f"{name} must be two positive integers, got {value!r}")
    return n_rows, n_cols


# ============================================================================ §7.3 grids and frames
def ortho_pixel_size(pixel_size: float, scale_denominator: float) -> float:
    """Orthophoto pixel size Δ·m on the ground (§7.3).

    Parameters
    ----------
    pixel_size : float
        Δ, the source image's pixel size, mm.
    scale_denominator : float
        m, the denominator of the image's mean scale.

    Returns
    -------
    float
        Δ·m in metres.

    Raises
    ------
    InputError
        NaN, inf, non-positive values.

    References
    ----------
    Chibunichev (2022), §7.3 ("the element size is usually about Δ × m").

    Examples
    --------
    >>> from photolib.rectify import ortho_pixel_size
    >>> ortho_pixel_size(0.01, 14000)
    0.14
    """
    size = _finite_float(pixel_size, "pixel_size", positive=True)
    m = _finite_float(scale_denominator, "scale_denominator", positive=True)
    return size * m / 1000.0


ELLIPSOIDS = {
    # semi-major axis a (m), inverse flattening 1/f
    "GSK-2011": (6378136.5, 298.2564151),
    "WGS-84": (6378137.0, 298.257223563),
}


def _ellipsoid(name):
    if isinstance(name, str):
        if name not in ELLIPSOIDS:
            raise InputError(f"unknown ellipsoid {name!r}; known: {sorted(ELLIPSOIDS)} or (a, 1/f)")
        a, rf = ELLIPSOIDS[name]
    else:
        try:
            a, rf = (float(v) for v in name)
        except (TypeError, ValueError):
            raise InputError(f"an ellipsoid is a name or (a, 1/f), got {name!r}") from None
        if not (math.isfinite(a) and math.isfinite(rf) and a > 0 and rf > 1):
            raise InputError(f"an ellipsoid needs a > 0 and 1/f > 1, got {name!r}")
    flattening = 1.0 / rf
    return a, flattening * (2.0 - flattening)


def _finite_arrays(names, *values):
    try:
        arrays = np.broadcast_arrays(*(np.asarray(v, dtype=np.float64) for v in values))
    except (TypeError, ValueError):
        raise InputError(f"{', '.join(names)} must be numbers or arrays of one shape") from None
    for name, arr in zip(names, arrays):
        if not np.isfinite(arr).all():
            raise InputError(f"{name} contains NaN or inf")
    return arrays


def _check_latitude(B, stacklevel=4):
    import warnings
    from .errors import DegreesWarning
    if np.any(np.abs(B) > math.pi / 2 + 1e-12):
        if np.any(np.abs(B) > 2 * math.pi):
            warnings.warn("latitude above 2π in magnitude: angles are in radians — were degrees "
                          "passed?", DegreesWarning, stacklevel=stacklevel)
        raise InputError("latitude B must lie within ±π/2 (radians)")


def _scalarise(*arrays):
    return tuple(float(a) for a in arrays) if arrays[0].ndim == 0 else arrays


def geodetic_to_geocentric(B, L, H, ellipsoid="GSK-2011"):
    """Geodetic latitude, longitude, ellipsoidal height → geocentric X, Y, Z (§7.3).

    X = (N + H)cos B cos L, Y = (N + H)cos B sin L, Z = (N(1 − e²) + H)sin B with
    N = a/√(1 − e² sin² B).

    Parameters
    ----------
    B, L : float or array
        Latitude and longitude, radians.
    H : float or array
        Height above the ellipsoid, m (the book: DEM heights for map-projection orthophotos are
        geodetic heights above the reference ellipsoid).
    ellipsoid : str or (float, float)
        ``"GSK-2011"`` (a = 6 378 136.5 m, 1/f = 298.2564151), ``"WGS-84"`` or (a, 1/f).

    Returns
    -------
    X, Y, Z : float or ndarray
        Geocentric coordinates, m.

    Raises
    ------
    InputError
        NaN/inf, |B| > π/2, an unknown ellipsoid.

    References
    ----------
    Chibunichev (2022), §7.3 (nodes B, L, H → geocentric X, Y, Z; "the formulas are in courses
    of higher geodesy").

    Examples
    --------
    >>> import math
    >>> from photolib.rectify import geodetic_to_geocentric
    >>> geodetic_to_geocentric(0.0, 0.0, 0.0)
    (6378136.5, 0.0, 0.0)
    >>> round(geodetic_to_geocentric(math.pi / 2, 0.0, 0.0, "WGS-84")[2], 3)
    6356752.314
    """
    a, e2 = _ellipsoid(ellipsoid)
    B, L, H = _finite_arrays(("B", "L", "H"), B, L, H)
    _check_latitude(B)
    sinB, cosB = np.sin(B), np.cos(B)
    N = a / np.sqrt(1.0 - e2 * sinB ** 2)
    return _scalarise((N + H) * cosB * np.cos(L), (N + H) * cosB * np.sin(L), (N * (1.0 - e2) + H) * sinB)


def geocentric_to_geodetic(X, Y, Z, ellipsoid="GSK-2011"):
    """Geocentric X, Y, Z → geodetic latitude, longitude, ellipsoidal height (§7.3).

    Bowring's parametric-latitude iteration, repeated until the latitude changes by less than
    1e-14 rad (two or three steps on the Earth's surface and at satellite heights).

    Parameters
    ----------
    X, Y, Z : float or array
        Geocentric coordinates, m.
    ellipsoid : str or (float, float)
        ``"GSK-2011"``, ``"WGS-84"`` or (a, 1/f).

    Returns
    -------
    B, L, H : float or ndarray
        Latitude and longitude (radians), height above the ellipsoid (m).

    Raises
    ------
    InputError
        NaN/inf, a point near the centre of the ellipsoid (closer than 10 km), an unknown ellipsoid.

    References
    ----------
    Chibunichev (2022), §7.3.

    Examples
    --------
    >>> from photolib.rectify import geocentric_to_geodetic
    >>> B, L, H = geocentric_to_geodetic(6378136.5 + 100.0, 0.0, 0.0)
    >>> round(B, 12), round(L, 12), round(H, 6)
    (0.0, 0.0, 100.0)
    """
    a, e2 = _ellipsoid(ellipsoid)
    X, Y, Z = _finite_arrays(("X", "Y", "Z"), X, Y, Z)
    p = np.hypot(X, Y)
    if np.any(np.hypot(p, Z) < 1e4):
        raise InputError("a point lies within 10 km of the ellipsoid's centre: no geodetic position")
    b = a * math.sqrt(1.0 - e2)
    ep2 = e2 / (1.0 - e2)
    L = np.arctan2(Y, X)
    beta = np.arctan2(Z * a, p * b)
    B = np.arctan2(Z + ep2 * b * np.sin(beta) ** 3, p - e2 * a * np.cos(beta) ** 3)
    for _ in range(10):
        beta = np.arctan2(math.sqrt(1.0 - e2) * np.sin(B), np.cos(B))
        B_new = np.arctan2(Z + ep2 * b * np.sin(beta) ** 3, p - e2 * a * np.cos(beta) ** 3)
        done = np.all(np.abs(B_new - B) < 1e-14)
        B = B_new
        if done:
            break
    sinB, cosB = np.sin(B), np.cos(B)
    N = a / np.sqrt(1.0 - e2 * sinB ** 2)
    # the better-conditioned of the two height formulas
    H = np.where(np.abs(cosB) > 0.5, p / np.where(np.abs(cosB) > 0.5, cosB, 1.0) - N,
                 Z / np.where(np.abs(cosB) > 0.5, 1.0, sinB) - N * (1.0 - e2))
    return _scalarise(B, L, H)


def topocentric_matrix(B0, L0):
    """Rotation whose rows are the topocentric axes of §7.3 in geocentric components.

    X_tp north (in the meridian plane of the origin), Z_tp along the ellipsoid normal (up), Y_tp
    completing a right-handed system — hence pointing **west** (not east as in ENU, and not as
    Gauss–Krüger's left-handed x north, y east).

    Parameters
    ----------
    B0, L0 : float
        Geodetic latitude and longitude of the origin, radians.

    Returns
    -------
    (3, 3) ndarray
        R with topocentric = R · (geocentric − geocentric of the origin).

    Raises
    ------
    InputError
        NaN/inf, |B0| > π/2.

    References
    ----------
    Chibunichev (2022), §7.3 (the topocentric system O_tp X_tp Y_tp Z_tp).

    Examples
    --------
    >>> import numpy as np
    >>> from photolib.rectify import topocentric_matrix
    >>> np.round(topocentric_matrix(0.0, 0.0), 12) + 0.0
    array([[ 0.,  0.,  1.],
           [ 0., -1.,  0.],
           [ 1.,  0.,  0.]])
    """
    B0, L0 = _finite_arrays(("B0", "L0"), B0, L0)
    if B0.ndim or L0.ndim:
        raise InputError("B0 and L0 must be scalars (one origin)")
    _check_latitude(B0)
    sB, cB, sL, cL = math.sin(B0), math.cos(B0), math.sin(L0), math.cos(L0)
    north = [-sB * cL, -sB * sL, cB]
    west = [sL, -cL, 0.0]
    up = [cB * cL, cB * sL, sB]
    return np.array([north, west, up])


def geocentric_to_topocentric(X, Y, Z, origin, ellipsoid="GSK-2011"):
    """Geocentric → topocentric (X north, Y west, Z up) coordinates about an origin (§7.3).

    Parameters
    ----------
    X, Y, Z : float or array
        Geocentric coordinates, m.
    origin : (B0, L0, H0)
        The topocentric origin (radians, radians, m), usually the middle of the area.
    ellipsoid : str or (float, float)
        ``"GSK-2011"``, ``"WGS-84"`` or (a, 1/f).

    Returns
    -------
    x, y, z : float or ndarray
        Topocentric coordinates, m.

    Raises
    ------
    InputError
        NaN/inf, a bad origin, an unknown ellipsoid.

    References
    ----------
    Chibunichev (2022), §7.3.

    Examples
    --------
    >>> from photolib.rectify import geocentric_to_topocentric, geodetic_to_geocentric
    >>> XYZ = geodetic_to_geocentric(0.0, 0.0, 50.0)
    >>> tuple(round(v, 9) + 0.0 for v in geocentric_to_topocentric(*XYZ, origin=(0.0, 0.0, 0.0)))
    (0.0, 0.0, 50.0)
    """
    B0, L0, H0 = _origin(origin)
    X, Y, Z = _finite_arrays(("X", "Y", "Z"), X, Y, Z)
    R = topocentric_matrix(B0, L0)
    O = geodetic_to_geocentric(B0, L0, H0, ellipsoid)
    d = np.stack([X - O[0], Y - O[1], Z - O[2]])
    x, y, z = np.tensordot(R, d, axes=1)
    return _scalarise(x, y, z)


def topocentric_to_geocentric(x, y, z, origin, ellipsoid="GSK-2011"):
    """Topocentric (X north, Y west, Z up) → geocentric coordinates (§7.3).

    Parameters
    ----------
    x, y, z : float or array
        Topocentric coordinates, m.
    origin : (B0, L0, H0)
        The topocentric origin (radians, radians, m).
    ellipsoid : str or (float, float)
        ``"GSK-2011"``, ``"WGS-84"`` or (a, 1/f).

    Returns
    -------
    X, Y, Z : float or ndarray
        Geocentric coordinates, m.

    Raises
    ------
    InputError
        NaN/inf, a bad origin, an unknown ellipsoid.

    References
    ----------
    Chibunichev (2022), §7.3.

    Examples
    --------
    >>> from photolib.rectify import topocentric_to_geocentric
    >>> tuple(round(v, 6) for v in topocentric_to_geocentric(0.0, 0.0, 10.0, (0.0, 0.0, 0.0)))
    (6378146.5, 0.0, 0.0)
    """
    B0, L0, H0 = _origin(origin)
    x, y, z = _finite_arrays(("x", "y", "z"), x, y, z)
    R = topocentric_matrix(B0, L0)
    O = geodetic_to_geocentric(B0, L0, H0, ellipsoid)
    X, Y, Z = np.tensordot(R.T, np.stack([x, y, z]), axes=1)
    return _scalarise(X + O[0], Y + O[1], Z + O[2])


def _origin(origin):
    try:
        B0, L0, H0 = (float(v) for v in origin)
    except (TypeError, ValueError):
        raise InputError(f"origin must be (B0, L0, H0), got {origin!r}") from None
    if not all(math.isfinite(v) for v in (B0, L0, H0)):
        raise InputError(f"origin contains NaN or inf: {origin!r}")
    return B0, L0, H0


# ============================================================================ §7.4 tolerances
def map_tolerance(scale_denominator: float, mm: float = 0.3) -> float:
    """A tolerance of ``mm`` on the map expressed on the ground: mm·M (§7.4, §7.9).

    Parameters
    ----------
    scale_denominator : float
        M, the denominator of the map's scale.
    mm : float
        The tolerance on the map, mm (0.3 mm for ΔR_max of §7.4; 0.5 and 0.7 mm in §7.9).

    Returns
    -------
    float
        The tolerance on the ground, m.

    Raises
    ------
    InputError
        NaN, inf, non-positive values.

    References
    ----------
    Chibunichev (2022), §7.4 (ΔR_max = 0.3·M mm) and §7.9.

    Examples
    --------
    >>> from photolib.rectify import map_tolerance
    >>> map_tolerance(2000)
    0.6
    """
    M = _finite_float(scale_denominator, "scale_denominator", positive=True)
    return _finite_float(mm, "mm", positive=True) * M / 1000.0


def admissible_height(f: float, r: float, tolerance: float) -> float:
    """Admissible relief h_max (7.4.1) or DEM error ΔZ_max (7.4.2): (f / r)·ΔR_max.

    A point at height h above the plane the image is rectified onto (or a DEM error h) shifts
    on the rectified image by ΔR = r·h/f (vertical photo; r from the nadir point), so the
    displacement stays below ΔR_max while h ≤ f·ΔR_max/r. Valid for tilts up to 3–5°.

    Parameters
    ----------
    f : float
        Focal length, mm.
    r : float
        Radial distance on the image of the farthest point used, mm.
    tolerance : float
        ΔR_max on the ground, m (see :func:`map_tolerance`).

    Returns
    -------
    float
        h_max (= ΔZ_max), m.

    Raises
    ------
    InputError
        NaN, inf, non-positive values.

    References
    ----------
    Chibunichev (2022), §7.4, eqs. (7.4.1)–(7.4.2).

    Examples
    --------
    >>> from photolib.rectify import admissible_height
    >>> admissible_height(100.0, 100.0, 0.6)
    0.6
    """
    f = _finite_float(f, "f", positive=True)
    r = _finite_float(r, "r", positive=True)
    return f / r * _finite_float(tolerance, "tolerance", positive=True)


def relief_displacement(r, h, f: float):
    """Displacement ΔR = r·h/f on a rectified vertical photo of a height error h (§7.4).

    Parameters
    ----------
    r : float or array
        Radial distance of the image point from the nadir point, mm.
    h : float or array
        Height above the rectification plane, or the DEM error, m.
    f : float
        Focal length, mm.

    Returns
    -------
    float or ndarray
        ΔR on the ground, m (radially outward for h > 0).

    Raises
    ------
    InputError
        NaN, inf, negative r, non-positive f.

    References
    ----------
    Chibunichev (2022), §7.4, Fig. 7.7 and the relation behind (7.4.1)–(7.4.2).

    Examples
    --------
    >>> from photolib.rectify import relief_displacement
    >>> relief_displacement(100.0, 0.6, 100.0)
    0.6
    """
    f = _finite_float(f, "f", positive=True)
    r, h = _finite_arrays(("r", "h"), r, h)
    if np.any(r < 0):
        raise InputError("r is a distance: it must be non-negative")
    out = r * h / f
    return float(out) if out.ndim == 0 else out


# ============================================================================ §7.7 monoplotting
@dataclass(frozen=True)
class MonoplotResult:
    """Object points of image points found on a DEM by the iteration of Fig. 7.19.

    Attributes
    ----------
    XYZ : (n, 3) ndarray
        X, Y of the last iteration and the DEM height there, m.
    iterations : (n,) ndarray of int
        Evaluations of (7.7.1) each point needed (≥ 2: the second confirms the first).
    history : list of (n, 3) ndarray
        (X_k, Y_k, Z_k) of every iteration: Z_k is the height used to compute X_k, Y_k.

    References
    ----------
    Chibunichev (2022), §7.7, eq. (7.7.1) and Fig. 7.19; §7.9.

    Examples
    --------
    >>> import numpy as np
    >>> from photolib.camera import ExteriorOrientation, InteriorOrientation
    >>> from photolib.rectify import RasterGrid, monoplot
    >>> result = monoplot([[0.0, 0.0]], ExteriorOrientation(0.0, 0.0, 1000.0), InteriorOrientation(100.0),
    ...                   np.full((3, 3), 50.0), RasterGrid(-15.0, 15.0, 10.0, (3, 3)))
    >>> result.XYZ.tolist(), result.iterations.tolist()
    ([[0.0, 0.0, 50.0]], [2])
    """

    XYZ: np.ndarray
    iterations: np.ndarray
    history: list


def monoplot(xy, eo, io, dem, dem_grid: RasterGrid, *, z_start=None, tol: float = 1e-3,
             max_iter: int = 50) -> MonoplotResult:
    """Image points → object points on a DEM by successive approximations (7.7.1), Fig. 7.19.

    Start at Z₁ (the DEM's mean height, or ``z_start`` — §7.9 starts at a control point's known
    height), compute X₁, Y₁ by (7.7.1) (:func:`photolib.single_image.image_to_ground`), take
    Z₂ from the DEM by (7.3.1), and repeat until X and Y change by at most ``tol``. The iteration
    is a fixed point; it converges where the ray is steeper than the terrain (|slope · tan of
    the ray's nadir angle| < 1).

    Parameters
    ----------
    xy : (n, 2) array
        Photo coordinates, mm (distortion corrected by ``io``'s model if it has one).
    eo, io : ExteriorOrientation, InteriorOrientation
        The image's orientation.
    dem : (R, C) array
        Heights on ``dem_grid``.
    dem_grid : RasterGrid
        The DEM's grid.
    z_start : float or (n,) array, optional
        Starting heights (default: the mean of the DEM's finite heights).
    tol : float
        Convergence tolerance on X and Y, m.
    max_iter : int
        Most iterations.

    Returns
    -------
    MonoplotResult

    Raises
    ------
    InputError
        Bad shapes, NaN; a ray that leaves the DEM at the starting height (the DEM does not cover it).
    ConvergenceError
        The iteration did not settle within ``max_iter`` or left the DEM later (terrain steeper
        than the ray); ``history`` holds the iterations.
    DegenerateGeometryError
        A ray that does not reach the height (horizontal, or a height above the camera).

    References
    ----------
    Chibunichev (2022), §7.7, eq. (7.7.1) and Fig. 7.19 (the text's "(4.6.1)" means (7.7.1));
    §7.9 (a-priori accuracy check).

    Examples
    --------
    >>> import numpy as np
    >>> from photolib.camera import ExteriorOrientation, InteriorOrientation
    >>> from photolib.rectify import RasterGrid, monoplot
    >>> grid = RasterGrid(-500.0, 500.0, 10.0, (100, 100))
    >>> X, Y = grid.centres()
    >>> result = monoplot([[30.0, -20.0]], ExteriorOrientation(0.0, 0.0, 1000.0), InteriorOrientation(100.0),
    ...                   0.1 * X + 20.0, grid)
    >>> np.round(result.XYZ, 3).tolist()      # closed form: X = 0.3(1000 − Z), Z = 0.1X + 20
    [[285.437, -190.291, 48.544]]
    """
    from .camera import as_points
    from .errors import ConvergenceError, DegenerateGeometryError
    from .single_image import image_to_ground

    if not isinstance(dem_grid, RasterGrid):
        raise InputError(f"dem_grid must be a RasterGrid, got {type(dem_grid).__name__}")
    heights = _image_bands(dem, "dem")
    if heights.ndim != 2 or heights.shape != dem_grid.shape:
        raise InputError(f"the DEM's shape {heights.shape} does not match its grid {dem_grid.shape}")
    xy = as_points(xy, 2, "image coordinates")
    if len(xy) == 0:
        raise InputError("no image points given")
    tol = _finite_float(tol, "tol", positive=True)
    try:
        max_iter = int(max_iter)
    except (TypeError, ValueError):
        raise InputError(f"max_iter must be an integer, got {max_iter!r}") from None
    if max_iter < 1:
        raise InputError(f"max_iter must be ≥ 1, got {max_iter}")
    if z_start is None:
        finite = heights[np.isfinite(heights)]
        if finite.size == 0:
            raise InputError("the DEM has no finite heights")
        Z = np.full(len(xy), float(finite.mean()))
    else:
        Z = _finite_arrays(("z_start",), z_start)[0]
        try:
            Z = np.broadcast_to(Z, (len(xy),)).astype(np.float64)
        except ValueError:
            raise InputError(f"z_start: expected a scalar or {len(xy)} values") from None
    history = []
    iterations = np.zeros(len(xy), dtype=int)
    active = np.ones(len(xy), dtype=bool)
    previous = None
    for k in range(1, max_iter + 1):
        try:
            XY = image_to_ground(xy, Z, eo, io)[:, :2]
        except DegenerateGeometryError as exc:
            if k == 1:
                raise
            raise ConvergenceError(f"monoplotting reached a height the rays cannot meet at iteration "
                                   f"{k} ({exc}); terrain steeper than the ray?", history) from None
        if previous is not None:
            XY[~active] = previous[~active]
        history.append(np.column_stack([XY, Z]))
        if previous is not None:
            settled = active & (np.abs(XY - previous).max(axis=1) <= tol)
            iterations[settled] = k
            active &= ~settled
        Z_new = dem_height(heights, dem_grid, XY[:, 0], XY[:, 1], outside="nan")
        off = np.isnan(Z_new) & active
        if off.any():
            i = int(np.flatnonzero(off)[0])
            where = (f"image point {i} ({xy[i, 0]:.6g}, {xy[i, 1]:.6g} mm) reaches X {XY[i, 0]:.6g}, "
                     f"Y {XY[i, 1]:.6g} outside the DEM (or on a void)")
            if k == 1:
                raise InputError(f"the DEM does not cover the ray at the starting height: {where}")
            raise ConvergenceError(f"monoplotting left the DEM at iteration {k}: {where}; terrain "
                                   "steeper than the ray?", history)
        if not active.any():
            XYZ = np.column_stack([XY, np.where(np.isnan(Z_new), Z, Z_new)])
            return MonoplotResult(XYZ, iterations, history)
        Z = np.where(active, Z_new, Z)
        previous = XY
    raise ConvergenceError(f"monoplotting did not converge to {tol} m in {max_iter} iterations for "
                           f"{int(active.sum())} point(s) (first: {int(np.flatnonzero(active)[0])}); "
                           "terrain steeper than the ray?", history)


# ============================================================================ §7.7 mosaics
def _polyline(cutline, name="cutline"):
    try:
        line = np.asarray(cutline, dtype=np.float64)
    except (TypeError, ValueError):
        raise InputError(f"{name} must be a (k, 2) array of X, Y nodes") from None
    if line.ndim != 2 or line.shape[1] != 2 or len(line) < 2:
        raise InputError(f"{name} must be a (k ≥ 2, 2) array of X, Y nodes, got shape {line.shape}")
    if not np.isfinite(line).all():
        raise InputError(f"{name} contains NaN or inf")
    dY = np.diff(line[:, 1])
    if not (np.all(dY > 0) or np.all(dY < 0)):
        raise InputError(f"{name} must run monotonically in Y (north–south) so that it crosses "
                         "every row once")
    return line[np.argsort(line[:, 1])]


def cutline_boundary(grid: RasterGrid, cutline) -> np.ndarray:
    """The boundary pixel of every row of a grid: the column the cutline crosses at the row centre.

    §7.7: each row of the mosaic takes pixels from the first (western) orthophoto up to and
    including the boundary pixel, and from the second one after it.

    Parameters
    ----------
    grid : RasterGrid
        The mosaic's grid.
    cutline : (k, 2) array
        Nodes K_i (X, Y) of the cutline, monotonic in Y, spanning the grid's rows.

    Returns
    -------
    (rows,) ndarray of int
        The boundary column of each row (−1: the whole row comes from the second orthophoto;
        ``cols − 1``: from the first).

    Raises
    ------
    InputError
        A cutline that is not monotonic in Y or does not span every row, NaN.

    References
    ----------
    Chibunichev (2022), §7.7, Fig. 7.17.

    Examples
    --------
    >>> from photolib.rectify import RasterGrid, cutline_boundary
    >>> grid = RasterGrid(0.0, 4.0, 1.0, (4, 6))
    >>> cutline_boundary(grid, [[2.5, 0.0], [4.5, 4.0]]).tolist()
    [4, 3, 3, 2]
    """
    if not isinstance(grid, RasterGrid):
        raise InputError(f"grid must be a RasterGrid, got {type(grid).__name__}")
    line = _polyline(cutline)
    _, Yc = grid.xy(np.arange(grid.shape[0]), np.zeros(grid.shape[0]))
    if Yc.min() < line[0, 1] - 1e-9 or Yc.max() > line[-1, 1] + 1e-9:
        raise InputError(f"the cutline spans Y {line[0, 1]:.6g}..{line[-1, 1]:.6g} but the grid's row "
                         f"centres span Y {Yc.min():.6g}..{Yc.max():.6g}")
    X = np.interp(Yc, line[:, 1], line[:, 0])
    col = np.floor((X - grid.x0) / grid.dx).astype(int)
    return np.clip(col, -1, grid.shape[1] - 1)



def mosaic_grid(grids) -> RasterGrid:
    """The grid of a mosaic of orthophotos on one pixel lattice (§7.7).

    Parameters
    ----------
    grids : sequence of RasterGrid
        The orthophotos' grids: one pixel size, origins on multiples of it.

    Returns
    -------
    RasterGrid
        Origin X₀M = min X₀ᵢ, Y₀M = max Y₀ᵢ, covering every orthophoto.

    Raises
    ------
    InputError
        Not grids, different pixel sizes, an origin off the lattice of the first grid.

    References
    ----------
    Chibunichev (2022), §7.7 (mosaic origin X₀M = min(X₀₁, X₀₂), Y₀M = max(Y₀₁, Y₀₂)).

    Examples
    --------
    >>> from photolib.rectify import RasterGrid, mosaic_grid
    >>> mosaic_grid([RasterGrid(0.0, 10.0, 1.0, (5, 5)), RasterGrid(3.0, 12.0, 1.0, (5, 5))])
    RasterGrid(x0=0.0, y0=12.0, pixel_size=(1.0, 1.0), shape=(7, 8))
    """
    grids = list(grids) if isinstance(grids, (list, tuple)) else [grids]
    if not grids or not all(isinstance(g, RasterGrid) for g in grids):
        raise InputError("grids must be a non-empty sequence of RasterGrid")
    dx, dy = grids[0].dx, grids[0].dy
    for k, grid in enumerate(grids[1:], 1):
        if not (math.isclose(grid.dx, dx, rel_tol=1e-9) and math.isclose(grid.dy, dy, rel_tol=1e-9)):
            raise InputError(f"grids[{k}] has pixel size {grid.pixel_size}, grids[0] {grids[0].pixel_size}: "
                             "a mosaic needs one ground resolution")
        for shift, step in ((grid.x0 - grids[0].x0, dx), (grids[0].y0 - grid.y0, dy)):
            if abs(shift / step - round(shift / step)) > 1e-6:
                raise InputError(f"grids[{k}]'s origin is not on the pixel lattice of grids[0] "
                                 "(origins must be multiples of the pixel size, §7.7)")
    x0 = min(g.x0 for g in grids)
    y0 = max(g.y0 for g in grids)
    x1 = max(g.extent[2] for g in grids)
    y1 = min(g.extent[1] for g in grids)
    return RasterGrid(x0, y0, (dx, dy), (int(round((y0 - y1) / dy)), int(round((x1 - x0) / dx))))

def mosaic(orthos, grids, cutline, *, fill_gaps: bool = True, return_source: bool = False):
    """A digital photo mosaic of orthophotos joined along cutlines by the row rule of §7.7.

    The mosaic's origin is X₀M = min X₀ᵢ, Y₀M = max Y₀ᵢ; it covers all orthophotos. Orthophotos
    are ordered west to east and cutline i separates orthophoto i from i + 1: in every row,
    orthophoto i supplies the pixels up to and including the boundary pixel of cutline i and
    orthophoto i + 1 those after it. With ``fill_gaps`` a pixel whose assigned orthophoto has no
    value (NaN or outside it) takes the first other orthophoto that has one (not in the book).

    Parameters
    ----------
    orthos : sequence of (R, C) or (R, C, bands) arrays
        The orthophotos (NaN = no data).
    grids : sequence of RasterGrid
        Their grids: one pixel size and one pixel lattice (origins differ by whole pixels).
    cutline : (k, 2) array or sequence of them
        One cutline for two orthophotos, or ``len(orthos) − 1`` cutlines (X, Y nodes).
    fill_gaps : bool
        Fill pixels the assigned orthophoto does not cover from the others.
    return_source : bool
        Also return the index of the orthophoto each pixel came from (−1: none).

    Returns
    -------
    image : ndarray
        The mosaic (NaN where no orthophoto has data).
    grid : RasterGrid
        Its grid.
    source : (rows, cols) ndarray of int
        Only with ``return_source``.

    Raises
    ------
    InputError
        Fewer than two orthophotos, mismatched counts or shapes, grids of different pixel sizes
        or lattices, bad cutlines.

    References
    ----------
    Chibunichev (2022), §7.7, Fig. 7.17 (row rule, X₀M = min, Y₀M = max).

    Examples
    --------
    >>> import numpy as np
    >>> from photolib.rectify import RasterGrid, mosaic
    >>> west, east = np.zeros((2, 4)), np.ones((2, 4))
    >>> image, grid = mosaic([west, east], [RasterGrid(0, 2, 1, (2, 4)), RasterGrid(2, 3, 1, (2, 4))],
    ...                      [[3.2, 0.0], [3.2, 3.0]])
    >>> grid
    RasterGrid(x0=0.0, y0=3.0, pixel_size=(1.0, 1.0), shape=(3, 6))
    >>> image
    array([[nan, nan,  1.,  1.,  1.,  1.],
           [ 0.,  0.,  0.,  0.,  1.,  1.],
           [ 0.,  0.,  0.,  0.,  nan, nan]])
    """
    if isinstance(orthos, np.ndarray) or not isinstance(orthos, (list, tuple)):
        raise InputError("orthos must be a list of orthophoto arrays")
    if isinstance(grids, RasterGrid) or not isinstance(grids, (list, tuple)):
        raise InputError("grids must be a list of RasterGrid")
    n = len(orthos)
    if n < 2 or len(grids) != n:
        raise InputError(f"a mosaic needs ≥ 2 orthophotos and one grid each; got {n} and {len(grids)}")
    arrays = []
    for k, (image, grid) in enumerate(zip(orthos, grids)):
        if not isinstance(grid, RasterGrid):
            raise InputError(f"grids[{k}] must be a RasterGrid, got {type(grid).__name__}")
        array = _image_bands(image, f"orthos[{k}]")
        if array.shape[:2] != grid.shape:
            raise InputError(f"orthos[{k}] has shape {array.shape[:2]}, its grid {grid.shape}")
        arrays.append(array)
    if len({a.shape[2:] for a in arrays}) != 1:
        raise InputError("the orthophotos have different numbers of bands")
    out_grid = mosaic_grid(grids)
    dx, dy = out_grid.dx, out_grid.dy
    if n == 2 and np.ndim(cutline) == 2:
        cutlines = [cutline]
    else:
        cutlines = list(cutline) if isinstance(cutline, (list, tuple)) else [cutline]
        if len(cutlines) != n - 1:
            raise InputError(f"{n} orthophotos need {n - 1} cutlines, got {len(cutlines)}")
    x0, y0 = out_grid.x0, out_grid.y0
    rows, cols = out_grid.shape
    bands = arrays[0].shape[2:]
    stack = np.full((n, rows, cols) + bands, np.nan)
    for k, (array, grid) in enumerate(zip(arrays, grids)):
        r0 = int(round((y0 - grid.y0) / dy))
        c0 = int(round((grid.x0 - x0) / dx))
        stack[k, r0:r0 + grid.shape[0], c0:c0 + grid.shape[1]] = array
    # assignment by the row rule: pixel (i, j) belongs to the first orthophoto k with j ≤ boundary_k(i)
    assign = np.full((rows, cols), n - 1)
    jj = np.arange(cols)[None, :]
    for k in range(n - 2, -1, -1):
        boundary = cutline_boundary(out_grid, cutlines[k])
        assign = np.where(jj <= boundary[:, None], k, assign)
    have = ~np.isnan(stack.reshape(n, rows, cols, -1)).any(axis=3)
    source = np.where(np.take_along_axis(have, assign[None], 0)[0], assign, -1)
    if fill_gaps:
        for k in range(n):
            source = np.where((source < 0) & have[k], k, source)
    image = np.full((rows, cols) + bands, np.nan)
    for k in range(n):
        image[source == k] = stack[k][source == k]
    return (image, out_grid, source) if return_source else (image, out_grid)


# ============================================================================ §7.9 accuracy
@dataclass(frozen=True)
class AccuracyReport:
    """The accuracy figures of §7.9 and whether they meet the tolerances.

    Attributes
    ----------
    errors : (n,) ndarray
        Planimetric discrepancies at the control points, m.
    mean_error_mm, max_error_mm : float
        Mean and largest discrepancy at map scale, mm.
    tolerance_mm : float
        0.5 mm (mean discrepancy at control points).
    passes : bool
        mean_error_mm ≤ tolerance_mm.
    cutline_mean_mm, cutline_max_mm : float or None
        Mean and largest mismatch of the same contours across the cutline, mm at map scale.
    cutline_tolerance_mm : float
        0.7 mm.
    cutline_passes : bool or None
        cutline_mean_mm ≤ cutline_tolerance_mm (None without cutline points).

    References
    ----------
    Chibunichev (2022), §7.9.

    Examples
    --------
    >>> from photolib.rectify import ortho_accuracy
    >>> report = ortho_accuracy([[0.3, 0.4]], [[0.0, 0.0]], 2000)
    >>> report.mean_error_mm, report.passes
    (0.25, True)
    """

    errors: np.ndarray
    mean_error_mm: float
    max_error_mm: float
    tolerance_mm: float
    passes: bool
    cutline_mean_mm: float | None
    cutline_max_mm: float | None
    cutline_tolerance_mm: float
    cutline_passes: bool | None


def ortho_accuracy(measured_xy, true_xy, scale_denominator: float, *, cutline_xy=None,
                   tolerance_mm: float = 0.5, cutline_tolerance_mm: float = 0.7) -> AccuracyReport:
    """Accuracy check of an orthophoto or a mosaic against control points (§7.9).

    The mean planimetric discrepancy between control points measured on the orthophoto and
    their geodetic (or aerial-triangulation) X, Y must not exceed 0.5 mm at the map's scale;
    the same contour on both sides of a cutline must not mismatch by more than 0.7 mm (both read
    as mean values; the maxima are reported too). Use ground-level points only.

    Parameters
    ----------
    measured_xy, true_xy : (n, 2) arrays
        Control points measured on the orthophoto and their reference X, Y, m.
    scale_denominator : float
        M of the map being made.
    cutline_xy : ((m, 2), (m, 2)) arrays, optional
        The same contour points measured on the two orthophotos at the cutline, m.
    tolerance_mm, cutline_tolerance_mm : float
        The tolerances at map scale (the book's 0.5 and 0.7 mm).

    Returns
    -------
    AccuracyReport

    Raises
    ------
    InputError
        Mismatched or empty point sets, NaN, a non-positive scale.

    References
    ----------
    Chibunichev (2022), §7.9.

    Examples
    --------
    >>> from photolib.rectify import ortho_accuracy
    >>> report = ortho_accuracy([[1.0, 1.0], [0.0, 0.9]], [[0.0, 1.0], [0.0, 0.0]], 2000,
    ...                         cutline_xy=([[5.0, 5.0]], [[5.0, 6.5]]))
    >>> report.mean_error_mm, report.passes, report.cutline_mean_mm, report.cutline_passes
    (0.475, True, 0.75, False)
    """
    from .camera import as_point_pairs

    M = _finite_float(scale_denominator, "scale_denominator", positive=True)
    tol = _finite_float(tolerance_mm, "tolerance_mm", positive=True)
    cut_tol = _finite_float(cutline_tolerance_mm, "cutline_tolerance_mm", positive=True)
    measured, true = as_point_pairs(measured_xy, 2, true_xy, 2, names=("measured_xy", "true_xy"))
    if len(measured) == 0:
        raise InputError("no control points given")
    errors = np.hypot(*(measured - true).T)
    to_mm = 1000.0 / M
    mean_mm, max_mm = float(errors.mean() * to_mm), float(errors.max() * to_mm)
    cut_mean = cut_max = cut_pass = None
    if cutline_xy is not None:
        try:
            first, second = cutline_xy
        except (TypeError, ValueError):
            raise InputError("cutline_xy must be a pair (points on ortho 1, points on ortho 2)") from None
        first, second = as_point_pairs(first, 2, second, 2, names=("cutline points 1", "cutline points 2"))
        if len(first) == 0:
            raise InputError("no cutline points given")
        mismatch = np.hypot(*(first - second).T) * to_mm
        cut_mean, cut_max = float(mismatch.mean()), float(mismatch.max())
        cut_pass = cut_mean <= cut_tol
    return AccuracyReport(errors, mean_mm, max_mm, tol, mean_mm <= tol, cut_mean, cut_max, cut_tol,
                          cut_pass)


def apriori_accuracy(xy, control_XYZ, eo, io, dem, dem_grid: RasterGrid, scale_denominator: float,
                     *, tol: float = 1e-3, max_iter: int = 50) -> AccuracyReport:
    """A-priori accuracy check (§7.9): monoplot the control points' image measurements on the DEM.

    Each control point's image position is projected to the DEM by the iteration of §7.7
    (:func:`monoplot`), starting from its known height, and the computed X, Y are compared with
    the known ones (:func:`ortho_accuracy`), before any orthophoto is made. A failure points at
    the orientation or the DEM.

    Parameters
    ----------
    xy : (n, 2) array
        Image measurements of the control points, mm.
    control_XYZ : (n, 3) array
        Their known X, Y, Z, m.
    eo, io : ExteriorOrientation, InteriorOrientation
        The image's orientation.
    dem : (R, C) array
        Heights on ``dem_grid``.
    dem_grid : RasterGrid
        The DEM's grid.
    scale_denominator : float
        M of the map being made.
    tol, max_iter
        Passed to :func:`monoplot`.

    Returns
    -------
    AccuracyReport

    Raises
    ------
    InputError
        Mismatched point counts, NaN, a DEM not covering the points.
    ConvergenceError
        Monoplotting did not converge.

    References
    ----------
    Chibunichev (2022), §7.9 (a-priori estimate) and §7.7, eq. (7.7.1).

    Examples
    --------
    >>> import numpy as np
    >>> from photolib.camera import ExteriorOrientation, InteriorOrientation
    >>> from photolib.rectify import RasterGrid, apriori_accuracy
    >>> eo, io = ExteriorOrientation(0.0, 0.0, 1000.0), InteriorOrientation(100.0)
    >>> report = apriori_accuracy([[10.0, 5.0]], [[100.0, 50.0, 0.0]], eo, io, np.zeros((30, 30)),
    ...                           RasterGrid(-150.0, 150.0, 10.0, (30, 30)), 2000)
    >>> round(report.mean_error_mm, 9), report.passes
    (0.0, True)
    """
    from .camera import as_point_pairs

    xy, XYZ = as_point_pairs(xy, 2, control_XYZ, 3, names=("image points", "control points"))
    result = monoplot(xy, eo, io, dem, dem_grid, z_start=XYZ[:, 2], tol=tol, max_iter=max_iter)
    return ortho_accuracy(result.XYZ[:, :2], XYZ[:, :2], scale_denominator)
