"""Digital rectification and orthophotos of frame images — Chapter 7, §7.2–7.3 (the engine).

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
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable

import numpy as np

from .errors import InputError

__all__ = ["RasterGrid", "RESAMPLING_METHODS", "resample", "rectify_forward", "dem_height",
           "frame_projector", "orthorectify"]

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


def resample(image, rows, cols, method: str = "bilinear", fill: float = np.nan):
    """Brightness of an image at fractional pixel positions (§7.2 resampling).

    Parameters
    ----------
    image : (R, C) or (R, C, bands) array
        The source image; NaN pixels propagate.
    rows, cols : arrays of one shape
        Positions, (0, 0) = centre of the first pixel.
    method : {'nearest', 'bilinear', 'bicubic'}
        Nearest neighbour (the pixel whose centre is closest, the book's 150.3, 21.7 → 150, 22),
        bilinear, or bicubic (Keys' cubic convolution, a = −0.5, as GDAL's and OpenCV's 'cubic').
    fill : float
        Value for positions outside the image (nearest: beyond half a pixel from the edge
        centres; bilinear and bicubic: outside the span of the pixel centres).

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
    fill = float(fill)
    kernels = _kernels()
    bands = kernels.as_float_bands(array)
    out = np.empty((rows.size, bands.shape[2]))
    kernel = {"nearest": kernels.resample_nearest, "bilinear": kernels.resample_bilinear,
              "bicubic": kernels.resample_bicubic}[method]
    kernel(bands, np.ascontiguousarray(rows.ravel()), np.ascontiguousarray(cols.ravel()), fill, out)
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
    from .single_image import camera_coordinates, project as collinearity
    from .synthetic import image_to_pixel

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
