"""Photogrammetric scanners — Chapter 1, §1.12 (Фотограмметрические сканеры), Figs. 1.27–1.28.

The library describes a scanner by its numbers (:class:`Scanner`: pixel size, scanning speed,
sensor) and derives from them what the book does **not** print: the number of pixels per side,
the raw file size and the scan time of a given frame format, and the swath/tile layout of
Figs. 1.27–1.28. The scan time assumes that the scanner's speed (MB/s) is the rate at which the
file of the requested bit depth and channel count is written; the manufacturers' conditions
are not printed. The radiometric resolution 2**b of a b-bit image is :func:`radiometric_levels`.

The book's Table 1.1 (four scanners) is data of the book and is read by the book layer
(``photolib.book.ch01_scanners``), which passes its rows to these functions.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Mapping

import numpy as np

from .errors import InputError

__all__ = ["Scanner", "radiometric_levels", "derived_figures", "scan_layout"]

_SENSOR_KINDS = ("lines", "array")


def _positive_integer(value, name: str) -> int:
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, np.integer, float, np.floating)):
        raise InputError(f"{name} must be a positive integer, got {value!r}")
    if not np.isfinite(value) or int(value) != value or value < 1:
        raise InputError(f"{name} must be a positive integer, got {value!r}")
    return int(value)


def _positive_number(value, name: str, allow_inf: bool = False) -> float:
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, np.integer, float, np.floating)):
        raise InputError(f"{name} must be a positive number, got {value!r}")
    value = float(value)
    if np.isnan(value) or (np.isinf(value) and not allow_inf) or value <= 0:
        raise InputError(f"{name} must be positive and finite, got {value!r}")
    return value


@dataclass(frozen=True)
class Scanner:
    """The numbers of a photogrammetric scanner that the derived figures need (§1.12).

    Parameters
    ----------
    name : str
        Name of the scanner (only used in the results).
    pixel_size_um : float
        Scanning pixel size Δ in μm (> 0).
    speed_MB_s : float
        Scanning speed in MB/s (10⁶ bytes per second, > 0).
    sensor_kind : {"lines", "array"}
        A line sensor (CCD lines, Fig. 1.27) or an area sensor (a matrix, Fig. 1.28).
    sensor_pixels : tuple of int
        ``(n,)`` pixels per line for a line sensor, ``(n_rows, n_cols)`` for an area sensor.
    format_mm : tuple of float, optional
        Largest frame format (width, height) in mm the scanner takes; unlimited if omitted.

    Raises
    ------
    InputError
        A non-positive or non-finite number, an unknown sensor kind, a wrong pixel count.

    References
    ----------
    Chibunichev (2022), §1.12, Table 1.1, Figs. 1.27–1.28.

    Examples
    --------
    >>> s = Scanner("line scanner", pixel_size_um=12, speed_MB_s=0.14, sensor_kind="lines",
    ...             sensor_pixels=(6000,))
    >>> s.pixel_size_um
    12.0
    """

    name: str
    pixel_size_um: float
    speed_MB_s: float
    sensor_kind: str
    sensor_pixels: tuple
    format_mm: tuple = (math.inf, math.inf)

    def __post_init__(self):
        object.__setattr__(self, "pixel_size_um", _positive_number(self.pixel_size_um, "pixel size (μm)"))
        object.__setattr__(self, "speed_MB_s", _positive_number(self.speed_MB_s, "scanning speed (MB/s)"))
        if self.sensor_kind not in _SENSOR_KINDS:
            raise InputError(f"sensor_kind must be 'lines' or 'array', got {self.sensor_kind!r}")
        pixels = tuple(np.atleast_1d(np.asarray(self.sensor_pixels, dtype=object)).tolist())
        need = 1 if self.sensor_kind == "lines" else 2
        if len(pixels) != need:
            raise InputError(f"a {self.sensor_kind} sensor needs {need} pixel count(s), got {self.sensor_pixels!r}")
        object.__setattr__(self, "sensor_pixels", tuple(_positive_integer(p, "sensor pixels") for p in pixels))
        fmt = tuple(np.broadcast_to(np.asarray(self.format_mm, dtype=object), (2,)).tolist())
        object.__setattr__(self, "format_mm", tuple(_positive_number(v, "scanner format (mm)", allow_inf=True) for v in fmt))

    @classmethod
    def from_row(cls, row: Mapping) -> "Scanner":
        """A scanner from a mapping with the keys of a Table 1.1 row.

        Parameters
        ----------
        row : mapping
            Keys ``name``, ``pixel_size_um``, ``speed_MB_s``, ``sensor_kind``,
            ``sensor_pixels`` and optionally ``format`` (mm).

        Returns
        -------
        Scanner

        Raises
        ------
        InputError
            A key is missing or a value is invalid.

        References
        ----------
        Chibunichev (2022), §1.12, Table 1.1.

        Examples
        --------
        >>> Scanner.from_row({"name": "S", "pixel_size_um": 9, "speed_MB_s": 1.0,
        ...                   "sensor_kind": "array", "sensor_pixels": (1032, 1536)}).sensor_pixels
        (1032, 1536)
        """
        if isinstance(row, Scanner):
            return row
        if not isinstance(row, Mapping):
            raise InputError(f"a scanner must be a Scanner or a mapping of its numbers, got {type(row).__name__}")
        missing = [k for k in ("name", "pixel_size_um", "speed_MB_s", "sensor_kind", "sensor_pixels") if k not in row]
        if missing:
            raise InputError(f"the scanner lacks {', '.join(missing)}")
        return cls(row["name"], row["pixel_size_um"], row["speed_MB_s"], row["sensor_kind"],
                   row["sensor_pixels"], row.get("format", row.get("format_mm", (math.inf, math.inf))))


def _as_scanner(scanner) -> Scanner:
    if isinstance(scanner, str):
        raise InputError(f"pass a Scanner (or a mapping of its numbers), not the name {scanner!r}; "
                         "the book's Table 1.1 scanners come from photolib.book.ch01_scanners")
    return Scanner.from_row(scanner)


def radiometric_levels(bits: int) -> int:
    """Number of grey levels of a b-bit image, 2**b (8 bit → 256 levels, 0…255).

    Parameters
    ----------
    bits : int
        Photometric resolution b in bits, a positive integer.

    Returns
    -------
    int
        2**b.

    Raises
    ------
    InputError
        ``bits`` is not a positive integer.

    References
    ----------
    Chibunichev (2022), §1.10 and §1.12 (photometric resolution, Table 1.1).

    Examples
    --------
    >>> radiometric_levels(8)
    256
    """
    return 2 ** _positive_integer(bits, "bits")


def _frame(frame_mm):
    try:
        fw, fh = (float(v) for v in np.broadcast_to(np.asarray(frame_mm, dtype=float), (2,)))
    except (TypeError, ValueError):
        raise InputError(f"frame size must be one or two positive numbers (mm), got {frame_mm!r}") from None
    if not (np.isfinite(fw) and np.isfinite(fh)) or fw <= 0 or fh <= 0:
        raise InputError(f"frame size must be positive, got {frame_mm!r}")
    return fw, fh


def derived_figures(scanner, frame_mm=(230.0, 230.0), bits: int = 8, channels: int = 1) -> dict:
    """OURS, not the book's: size and time of scanning one frame with a scanner.

    * pixels per side = ⌈frame side / pixel size⌉;
    * raw size = pixels_x·pixels_y·channels·bits/8 bytes, reported in MB = 10⁶ bytes;
    * scan time = raw size / speed (assumes the speed applies to this file);
    * swaths (line sensors, Fig. 1.27): ⌈frame width / (n·Δ)⌉ passes of width n·Δ;
      tiles (area sensors, Fig. 1.28): ⌈W/(n_x·Δ)⌉·⌈H/(n_y·Δ)⌉ (the longer sensor side along x).

    Parameters
    ----------
    scanner : Scanner or mapping
        The scanner's numbers (a mapping is read by :meth:`Scanner.from_row`).
    frame_mm : float or (float, float)
        Frame width and height in mm.
    bits : int
        Bits per channel.
    channels : int
        Number of channels (1 grey, 3 colour).

    Returns
    -------
    dict
        ``scanner``, ``pixel_size_um``, ``pixels_x``, ``pixels_y``, ``levels``, ``raw_MB``,
        ``scan_time_min``, ``fits_format`` and either ``swath_mm``, ``swaths`` (line sensor) or
        ``tile_mm``, ``tiles`` (area sensor).

    Raises
    ------
    InputError
        A non-positive frame, bits or channels, or an invalid scanner.

    References
    ----------
    Chibunichev (2022), §1.12, Table 1.1, Figs. 1.27–1.28.

    Examples
    --------
    >>> s = Scanner("S", 12, 0.14, "lines", (6000,))
    >>> f = derived_figures(s, (230, 230))
    >>> f["pixels_x"], f["swaths"]
    (19167, 4)
    """
    s = _as_scanner(scanner)
    fw, fh = _frame(frame_mm)
    channels = _positive_integer(channels, "channels")
    levels = radiometric_levels(bits)
    d_mm = s.pixel_size_um / 1000.0
    px, py = math.ceil(round(fw / d_mm, 9)), math.ceil(round(fh / d_mm, 9))
    size_mb = px * py * channels * bits / 8 / 1e6
    out = {"scanner": s.name, "pixel_size_um": s.pixel_size_um, "pixels_x": px, "pixels_y": py,
           "levels": levels, "raw_MB": size_mb, "scan_time_min": size_mb / s.speed_MB_s / 60.0,
           "fits_format": bool(max(fw, fh) <= max(s.format_mm) and min(fw, fh) <= min(s.format_mm))}
    if s.sensor_kind == "lines":
        width = s.sensor_pixels[0] * d_mm
        out.update(swath_mm=width, swaths=math.ceil(round(fw / width, 9)))
    else:
        nx, ny = max(s.sensor_pixels), min(s.sensor_pixels)
        tx, ty = nx * d_mm, ny * d_mm
        out.update(tile_mm=(tx, ty), tiles=math.ceil(round(fw / tx, 9)) * math.ceil(round(fh / ty, 9)))
    return out


def scan_layout(scanner, frame_mm=(230.0, 230.0)) -> list[tuple]:
    """OURS: rectangles (x, y, width, height) in mm covering the frame — swaths or tiles.

    Line sensors: vertical swaths of width n·Δ (the stage moves along y, then steps by n·Δ along
    x, Fig. 1.27). Area sensors: a grid of tiles of the projected sensor size (Fig. 1.28).

    Parameters
    ----------
    scanner : Scanner or mapping
        The scanner's numbers.
    frame_mm : float or (float, float)
        Frame width and height in mm.

    Returns
    -------
    list of tuple
        ``(x, y, width, height)`` in mm, together covering the frame exactly.

    Raises
    ------
    InputError
        A non-positive frame or an invalid scanner.

    References
    ----------
    Chibunichev (2022), §1.12, Figs. 1.27–1.28.

    Examples
    --------
    >>> rects = scan_layout(Scanner("S", 12, 0.14, "lines", (6000,)), (230, 230))
    >>> len(rects), rects[0]
    (4, (0.0, 0.0, 72.0, 230.0))
    """
    s = _as_scanner(scanner)
    fw, fh = _frame(frame_mm)
    fig = derived_figures(s, (fw, fh))
    if s.sensor_kind == "lines":
        w = fig["swath_mm"]
        return [(k * w, 0.0, min(w, fw - k * w), fh) for k in range(fig["swaths"])]
    tx, ty = fig["tile_mm"]
    nx, ny = math.ceil(round(fw / tx, 9)), math.ceil(round(fh / ty, 9))
    return [(a * tx, b * ty, min(tx, fw - a * tx), min(ty, fh - b * ty)) for b in range(ny) for a in range(nx)]
