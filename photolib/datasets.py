"""Real public data for Chapters 5–11: where it is, and readers for the stereo benchmarks.

The real data (Middlebury stereo pairs, OpenCV's chessboards, Pléiades crops with RPCs, SRTM,
LAS/LAZ point clouds) is never part of the package or the repository. It is found through
:func:`data_dir` only: the environment variable ``PHOTOLIB_DATA`` if set, otherwise the folder
``../shared/data`` beside the project's checkout (or beside the current directory). Code that
needs a file asks :func:`data_path`, which raises :class:`DataUnavailableError` (a
``FileNotFoundError``) naming the variable to set; tests and notebooks turn that into a skip.

scikit-image ships its own Middlebury pair ("Motorcycle"); :func:`motorcycle` reads it where
scikit-image is installed, with no download.

Disparity convention (both Middlebury sets): the left pixel at column ``x`` is seen in the
right image at column ``x − d``; unknown ground truth is ``NaN`` here (the files use 0, and
scikit-image uses ``inf``).
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .errors import InputError, PhotolibError

__all__ = ["DataUnavailableError", "StereoBenchmark", "data_dir", "data_path", "read_image",
           "middlebury_cones", "motorcycle"]

ENVIRONMENT_VARIABLE = "PHOTOLIB_DATA"


class DataUnavailableError(PhotolibError, FileNotFoundError):
    """The real data (or one file of it) is not on this machine.

    Raised by :func:`data_path`; the message names the missing file and the environment
    variable ``PHOTOLIB_DATA`` that points to the data folder.

    Attributes
    ----------
    path : pathlib.Path
        The file or folder that was looked for.

    References
    ----------
    The data's provenance and licences: ``../shared/data/README.md`` (not shipped).

    Examples
    --------
    >>> issubclass(DataUnavailableError, FileNotFoundError) and issubclass(DataUnavailableError, PhotolibError)
    True
    """

    def __init__(self, message: str, path: Path):
        super().__init__(message)
        self.path = path


def data_dir() -> Path:
    """The folder of the real data (it may not exist).

    Returns
    -------
    pathlib.Path
        ``$PHOTOLIB_DATA`` if the variable is set; otherwise ``../shared/data`` next to the
        source checkout this module belongs to, if that exists; otherwise ``../shared/data``
        relative to the current directory.

    Raises
    ------
    InputError
        If ``PHOTOLIB_DATA`` is set but empty.

    References
    ----------
    Used by the real-data parts of Chapters 5–11 (Chibunichev, 2022).

    Examples
    --------
    >>> isinstance(data_dir(), Path)
    True
    """
    env = os.environ.get(ENVIRONMENT_VARIABLE)
    if env is not None:
        if not env.strip():
            raise InputError(f"{ENVIRONMENT_VARIABLE} is set but empty; unset it or give the data folder")
        return Path(env).expanduser()
    beside_checkout = Path(__file__).resolve().parents[2] / "shared" / "data"
    if beside_checkout.is_dir():
        return beside_checkout
    return Path.cwd().parent / "shared" / "data"


def data_path(*parts: str) -> Path:
    """The path of one file (or folder) of the real data, checked to exist.

    Parameters
    ----------
    *parts : str
        Path components below the data folder, e.g. ``"stereo", "cones", "left.png"``.

    Returns
    -------
    pathlib.Path
        The existing path.

    Raises
    ------
    DataUnavailableError
        If the path does not exist (the message says how to point ``PHOTOLIB_DATA`` at the data).
    InputError
        If no component is given or a component is not a string.

    References
    ----------
    Used by the real-data parts of Chapters 5–11 (Chibunichev, 2022).

    Examples
    --------
    >>> try:
    ...     path = data_path("stereo", "cones", "left.png")
    ... except DataUnavailableError as missing:
    ...     path = None
    >>> path is None or path.name == "left.png"
    True
    """
    if not parts:
        raise InputError("data_path needs at least one path component")
    if not all(isinstance(p, str) and p for p in parts):
        raise InputError(f"data_path components must be non-empty strings, got {parts!r}")
    path = data_dir().joinpath(*parts)
    if not path.exists():
        raise DataUnavailableError(
            f"real data not available: {path} does not exist (set {ENVIRONMENT_VARIABLE} to the folder "
            f"holding the project's shared data, e.g. ../shared/data)", path)
    return path


def read_image(path, gray: bool = True) -> np.ndarray:
    """Read an image file into a float64 array (Pillow, imported on first use).

    Parameters
    ----------
    path : str or pathlib.Path
        A PNG, JPEG or single-band TIFF file (float TIFFs keep their values).
    gray : bool, optional
        Convert colour images to one band (ITU-R 601 luma, as Pillow's ``"L"`` mode).

    Returns
    -------
    numpy.ndarray
        ``(rows, columns)`` if ``gray`` or single-band, else ``(rows, columns, bands)``; float64.

    Raises
    ------
    DataUnavailableError
        If the file does not exist (a ``FileNotFoundError``).
    InputError
        If Pillow is missing or the file is not an image it can read.

    References
    ----------
    Chibunichev (2022), §5.1: an image is a matrix of brightness values.

    Examples
    --------
    >>> try:
    ...     left = read_image(data_path("stereo", "cones", "left.png"))
    ... except DataUnavailableError:
    ...     left = np.zeros((375, 450))
    >>> left.shape, left.dtype
    ((375, 450), dtype('float64'))
    """
    try:
        from PIL import Image, UnidentifiedImageError
    except ImportError as exc:     # pragma: no cover - Pillow comes with matplotlib / scikit-image
        raise InputError("reading image files needs Pillow (pip install pillow)") from exc
    if not isinstance(path, (str, os.PathLike)):
        raise InputError(f"read_image needs a file path, got {type(path).__name__}")
    path = Path(path)
    if not path.is_file():
        raise DataUnavailableError(f"no such image file: {path}", path)
    try:
        with Image.open(path) as image:
            if image.mode == "P":
                image = image.convert("L")
            if gray and image.mode in ("RGB", "RGBA", "CMYK", "LA"):
                image = image.convert("L")
            return np.asarray(image, dtype=np.float64)
    except UnidentifiedImageError as exc:
        raise InputError(f"{path} is not an image file Pillow can read") from exc


@dataclass(frozen=True)
class StereoBenchmark:
    """A rectified stereo pair with ground-truth disparities.

    Attributes
    ----------
    name : str
        Which pair.
    left, right : numpy.ndarray
        Grey images, float64, equal shapes.
    disparity : numpy.ndarray
        Ground-truth disparity of the left image in pixels (left column ``x`` ↔ right ``x − d``);
        ``NaN`` where unknown.
    evaluate : numpy.ndarray
        Boolean mask of the pixels scored (known and, where the set provides it, not occluded).
    max_disparity : int
        The largest ground-truth disparity, rounded up: a search range for matchers.

    References
    ----------
    Chibunichev (2022), §6.4 (semi-global matching); Scharstein & Szeliski (2003).

    Examples
    --------
    >>> pair = motorcycle()
    >>> pair.left.shape == pair.disparity.shape == pair.evaluate.shape
    True
    """

    name: str
    left: np.ndarray
    right: np.ndarray
    disparity: np.ndarray
    evaluate: np.ndarray
    max_disparity: int

    def __post_init__(self):
        shapes = {np.shape(a) for a in (self.left, self.right, self.disparity, self.evaluate)}
        if len(shapes) != 1 or len(shapes.pop()) != 2:
            raise InputError("a stereo benchmark needs 2-D left, right, disparity and mask of one shape")
        if not (np.all(np.isfinite(self.left)) and np.all(np.isfinite(self.right))):
            raise InputError("a stereo benchmark's images must be finite (NaN or inf pixels found)")


def _benchmark(name, left, right, disparity, evaluate):
    known = np.isfinite(disparity)
    evaluate = evaluate & known
    return StereoBenchmark(name, left, right, disparity, evaluate, int(np.ceil(np.nanmax(disparity))))


def _luma(rgb) -> np.ndarray:
    """ITU-R 601 luma, element by element (a matrix product would round differently on different
    BLAS kernels, and census costs compare grey values exactly)."""
    rgb = np.asarray(rgb, dtype=np.float64)
    return 0.299 * rgb[..., 0] + 0.587 * rgb[..., 1] + 0.114 * rgb[..., 2]


def middlebury_cones() -> StereoBenchmark:
    """The Middlebury 2003 "Cones" pair (450×375) with its quarter-pixel ground truth.

    Returns
    -------
    StereoBenchmark
        ``evaluate`` marks the non-occluded pixels with known disparity (the usual "nonocc"
        score region).

    Raises
    ------
    DataUnavailableError
        If the real data is not on this machine.

    References
    ----------
    Chibunichev (2022), §6.4; D. Scharstein and R. Szeliski, "High-accuracy stereo depth maps
    using structured light", CVPR 2003.

    Examples
    --------
    >>> try:
    ...     cones = middlebury_cones()
    ... except DataUnavailableError:
    ...     cones = None
    >>> cones is None or (cones.left.shape == (375, 450) and cones.max_disparity == 55)
    True
    """
    folder = data_path("stereo", "cones")
    left = read_image(folder / "left.png")
    right = read_image(folder / "right.png")
    disparity = read_image(folder / "disp_left.tif")
    disparity[disparity <= 0] = np.nan
    not_occluded = read_image(folder / "occlusion.png") > 127
    return _benchmark("Middlebury 2003 Cones", left, right, disparity, not_occluded)


def motorcycle() -> StereoBenchmark:
    """scikit-image's bundled Middlebury 2014 "Motorcycle" pair (741×500), grey.

    Returns
    -------
    StereoBenchmark
        ``evaluate`` marks the pixels with known disparity (scikit-image ships no occlusion mask).

    Raises
    ------
    InputError
        If scikit-image is not installed.

    References
    ----------
    Chibunichev (2022), §6.4; D. Scharstein et al., "High-resolution stereo datasets with
    subpixel-accurate ground truth", GCPR 2014.

    Examples
    --------
    >>> pair = motorcycle()
    >>> pair.left.shape, pair.max_disparity
    ((500, 741), 60)
    """
    try:
        from skimage import data as skimage_data
    except ImportError as exc:
        raise InputError("the Motorcycle pair comes with scikit-image (pip install scikit-image)") from exc
    left, right, disparity = skimage_data.stereo_motorcycle()
    left, right = _luma(left), _luma(right)
    disparity = np.asarray(disparity, dtype=np.float64)
    disparity[~np.isfinite(disparity)] = np.nan
    return _benchmark("Middlebury 2014 Motorcycle (scikit-image)", left, right, disparity, np.ones(left.shape, bool))
