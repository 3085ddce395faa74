"""Photogrammetric scanners — Chapter 1, §1.12 (Фотограмметрические сканеры), Table 1.1.

Table 1.1 of the book is data and lives in ``textbook/ch01.toml`` (example ``"1.12-table-1.1"``);
:func:`table_1_1` reads it from there, so there is one source of truth.

Everything else in this module is **derived by us, not printed in the book**: the number of
pixels per side, the raw file size and the scan time of a given frame format from the table's
pixel size and scanning speed, and the swath/tile layout of Figs. 1.27–1.28. The scan time
assumes that the table's speed (MB/s) is the rate at which the file of the requested bit depth
and channel count is written; the manufacturers' conditions are not printed.
"""

from __future__ import annotations

import math
import re

import numpy as np

from .errors import InputError

TABLE_ID = "1.12-table-1.1"
ROWS = ("sensor", "format_mm", "pixel_size_um", "accuracy_um", "bits", "colour", "density_range", "speed_MB_s")


def radiometric_levels(bits: int) -> int:
    """Number of grey levels of a b-bit image, 2**b (8 bit → 256 levels, 0…255)."""
    if int(bits) != bits or bits < 1:
        raise InputError(f"bits must be a positive integer, got {bits!r}")
    return 2 ** int(bits)


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
    """
    from .textbook import load_chapter
    ex = load_chapter(1).example(TABLE_ID)
    by_name = {q.name: q.value for q in ex.quantities}
    scanners = []
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
        scanners.append(row)
    return scanners


def _scanner(scanner):
    if isinstance(scanner, dict):
        return scanner
    for s in table_1_1():
        if s["name"] == scanner:
            return s
    raise InputError(f"no scanner {scanner!r} in Table 1.1")


def derived_figures(scanner, frame_mm=(230.0, 230.0), bits: int = 8, channels: int = 1) -> dict:
    """OURS, not the book's: size and time of scanning one frame with a Table 1.1 scanner.

    * pixels per side = ⌈frame side / pixel size⌉;
    * raw size = pixels_x·pixels_y·channels·bits/8 bytes, reported in MB = 10⁶ bytes;
    * scan time = raw size / table speed (assumes the speed applies to this file);
    * swaths (line sensors, Fig. 1.27): ⌈frame width / (n·Δ)⌉ passes of width n·Δ;
      tiles (area sensors, Fig. 1.28): ⌈W/(n_x·Δ)⌉·⌈H/(n_y·Δ)⌉ (the longer sensor side along x).
    """
    s = _scanner(scanner)
    fw, fh = (float(v) for v in np.broadcast_to(np.asarray(frame_mm, dtype=float), (2,)))
    if not (np.isfinite(fw) and np.isfinite(fh)) or fw <= 0 or fh <= 0:
        raise InputError(f"frame size must be positive, got {frame_mm!r}")
    if int(channels) != channels or channels < 1:
        raise InputError(f"channels must be a positive integer, got {channels!r}")
    levels = radiometric_levels(bits)
    d_mm = s["pixel_size_um"] / 1000.0
    px, py = math.ceil(round(fw / d_mm, 9)), math.ceil(round(fh / d_mm, 9))
    size_mb = px * py * channels * bits / 8 / 1e6
    out = {"scanner": s["name"], "pixel_size_um": s["pixel_size_um"], "pixels_x": px, "pixels_y": py,
           "levels": levels, "raw_MB": size_mb, "scan_time_min": size_mb / s["speed_MB_s"] / 60.0,
           "fits_format": bool(max(fw, fh) <= max(s["format"]) and min(fw, fh) <= min(s["format"]))}
    if s["sensor_kind"] == "lines":
        width = s["sensor_pixels"][0] * d_mm
        out.update(swath_mm=width, swaths=math.ceil(round(fw / width, 9)))
    else:
        nx, ny = max(s["sensor_pixels"]), min(s["sensor_pixels"])
        tx, ty = nx * d_mm, ny * d_mm
        out.update(tile_mm=(tx, ty), tiles=math.ceil(round(fw / tx, 9)) * math.ceil(round(fh / ty, 9)))
    return out


def scan_layout(scanner, frame_mm=(230.0, 230.0)) -> list[tuple]:
    """OURS: rectangles (x, y, width, height) in mm covering the frame — swaths or tiles.

    Line sensors: vertical swaths of width n·Δ (the stage moves along y, then steps by n·Δ along
    x, Fig. 1.27). Area sensors: a grid of tiles of the projected sensor size (Fig. 1.28).
    """
    s = _scanner(scanner)
    fw, fh = (float(v) for v in np.broadcast_to(np.asarray(frame_mm, dtype=float), (2,)))
    fig = derived_figures(s, (fw, fh))
    if s["sensor_kind"] == "lines":
        w = fig["swath_mm"]
        return [(k * w, 0.0, min(w, fw - k * w), fh) for k in range(fig["swaths"])]
    tx, ty = fig["tile_mm"]
    nx, ny = math.ceil(round(fw / tx, 9)), math.ceil(round(fh / ty, 9))
    return [(a * tx, b * ty, min(tx, fw - a * tx), min(ty, fh - b * ty)) for b in range(ny) for a in range(nx)]


def derived_table(frame_mm=(230.0, 230.0), bits: int = 8, channels: int = 1):
    """OURS: a table of :func:`derived_figures` for every scanner, titled as not from the book."""
    from .verify import Table
    rows = []
    for s in table_1_1():
        f = derived_figures(s, frame_mm, bits, channels)
        layout = f"{f['swaths']} swaths of {f['swath_mm']:.1f} mm" if "swaths" in f else \
            f"{f['tiles']} tiles of {f['tile_mm'][0]:.2f}×{f['tile_mm'][1]:.2f} mm"
        rows.append([s["name"], f"{f['pixel_size_um']:g}", f"{f['pixels_x']}×{f['pixels_y']}",
                     f"{f['raw_MB']:.0f}", f"{f['scan_time_min']:.1f}", layout])
    fw, fh = np.broadcast_to(np.asarray(frame_mm, dtype=float), (2,))
    title = (f"Derived by us, not in the book: a {fw:g}×{fh:g} mm frame at {bits} bit, {channels} channel(s)")
    return Table(["scanner", "pixel μm", "pixels", "raw MB", "scan min", "layout"], rows, title)
