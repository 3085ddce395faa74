"""Chapter 1, §1.12: the book's Table 1.1 (four photogrammetric scanners) and our derived table.

Table 1.1 is data of the book and lives in ``textbook/ch01.toml`` (example ``"1.12-table-1.1"``);
:func:`table_1_1` reads it from there, so there is one source of truth. The derived figures
(pixels, file size, scan time, swaths/tiles) are computed by the library,
:mod:`photolib.scanners`, from each row's numbers; :func:`derived_table` is the book's display
of them, titled as not from the book.
"""

from __future__ import annotations

import re

import numpy as np

from .. import scanners as _scanners
from ..errors import InputError
from .textbook import load_chapter
from .verify import Table

TABLE_ID = "1.12-table-1.1"
ROWS = ("sensor", "format_mm", "pixel_size_um", "accuracy_um", "bits", "colour", "density_range", "speed_MB_s")


def _parse_sensor(text: str):
    """'3 lines, 6000' → ('lines', 3, (6000,)); 'array, 1032×1536' → ('array', 1, (1032, 1536))."""
    m = re.fullmatch(r"\s*(\d+) lines, (\d+)\s*", text)
    if m:
        return "lines", int(m.group(1)), (int(m.group(2)),)
    m = re.fullmatch(r"\s*array, (\d+)×(\d+)\s*", text)
    if m:
        return "array", 1, (int(m.group(1)), int(m.group(2)))
    raise InputError(f"cannot read the sensor cell {text!r}")


def _parse_format(text: str):
    a, b = text.split("×")
    return float(a), float(b)


def table_1_1() -> list[dict]:
    """Table 1.1 as one dict per scanner, read from ``textbook/`` (values as transcribed).

    Keys: ``name``, the eight rows of :data:`ROWS` as transcribed, and parsed helpers
    ``sensor_kind`` ("lines"/"array"), ``sensor_lines``, ``sensor_pixels`` (tuple),
    ``format`` (tuple, mm). The pixel size has no unit in the book; μm is implied.
    Each dict can be passed to :func:`photolib.scanners.derived_figures`.
    """
    ex = load_chapter(1).example(TABLE_ID)
    by_name = {q.name: q.value for q in ex.quantities}
    rows = []
    for name in ex.inputs["scanners"]:
        row = {"name": name}
        for key in ex.inputs["rows"]:
            qname = f"{key}[{name}]"
            if qname not in by_name:
                raise InputError(f"textbook entry {TABLE_ID} lacks {qname}")
            row[key] = by_name[qname]
        kind, lines, pixels = _parse_sensor(row["sensor"])
        row.update(sensor_kind=kind, sensor_lines=lines, sensor_pixels=pixels,
                   format=_parse_format(row["format_mm"]))
        rows.append(row)
    return rows


def scanner(name: str) -> _scanners.Scanner:
    """The library's :class:`photolib.scanners.Scanner` of a Table 1.1 scanner, by name."""
    for row in table_1_1():
        if row["name"] == name:
            return _scanners.Scanner.from_row(row)
    raise InputError(f"no scanner {name!r} in Table 1.1")


def derived_figures(name_or_row, frame_mm=(230.0, 230.0), bits: int = 8, channels: int = 1) -> dict:
    """:func:`photolib.scanners.derived_figures` for a Table 1.1 scanner given by name (or row)."""
    s = scanner(name_or_row) if isinstance(name_or_row, str) else name_or_row
    return _scanners.derived_figures(s, frame_mm, bits, channels)


def derived_table(frame_mm=(230.0, 230.0), bits: int = 8, channels: int = 1):
    """OURS: a table of the derived figures for every Table 1.1 scanner, titled as not from the book."""
    rows = []
    for s in table_1_1():
        f = _scanners.derived_figures(s, frame_mm, bits, channels)
        layout = f"{f['swaths']} swaths of {f['swath_mm']:.1f} mm" if "swaths" in f else \
            f"{f['tiles']} tiles of {f['tile_mm'][0]:.2f}×{f['tile_mm'][1]:.2f} mm"
        rows.append([s["name"], f"{f['pixel_size_um']:g}", f"{f['pixels_x']}×{f['pixels_y']}",
                     f"{f['raw_MB']:.0f}", f"{f['scan_time_min']:.1f}", layout])
    fw, fh = np.broadcast_to(np.asarray(frame_mm, dtype=float), (2,))
    title = (f"Derived by us, not in the book: a {fw:g}×{fh:g} mm frame at {bits} bit, {channels} channel(s)")
    return Table(["scanner", "pixel μm", "pixels", "raw MB", "scan min", "layout"], rows, title)
