"""§1.12 scanners (photolib.scanners): derived figures (ours) from a scanner's numbers.

Table 1.1 of the book is read by the book layer: tests/book/test_ch01_scanners.py.
"""

import math

import pytest

from photolib import scanners
from photolib.errors import InputError

LINE = scanners.Scanner("line scanner", 12, 0.14, "lines", (6000,), (250, 250))
LINE_7 = scanners.Scanner("7 μm line scanner", 7, 2.0, "lines", (5632,))
AREA = scanners.Scanner("area scanner", 9, 1.0, "array", (1032, 1536))


def test_radiometric_levels():
    assert scanners.radiometric_levels(8) == 256
    assert [scanners.radiometric_levels(b) for b in (10, 12, 16)] == [1024, 4096, 65536]
    with pytest.raises(InputError):
        scanners.radiometric_levels(0)


def test_derived_figures_by_hand():
    f = scanners.derived_figures(LINE, (230, 230), bits=8, channels=1)
    assert f["pixels_x"] == math.ceil(230 / 0.012) == 19167
    assert f["raw_MB"] == pytest.approx(19167 ** 2 / 1e6)
    assert f["scan_time_min"] == pytest.approx(19167 ** 2 / 1e6 / 0.14 / 60)
    assert f["swaths"] == math.ceil(230 / (6000 * 0.012)) == 4
    # 7 μm divides 230 mm into 32857.14 → 32858 pixels (a partial pixel still has to be scanned)
    assert scanners.derived_figures(LINE_7)["pixels_x"] == 32858
    # 16 bit RGB is 6× the bytes of 8 bit grey
    g = scanners.derived_figures(LINE, 230, bits=16, channels=3)
    assert g["raw_MB"] == pytest.approx(6 * f["raw_MB"])
    d = scanners.derived_figures(AREA)
    assert d["tiles"] == math.ceil(230 / (1536 * 0.009)) * math.ceil(230 / (1032 * 0.009))
    assert not scanners.derived_figures(LINE, (300, 300))["fits_format"]
    assert scanners.derived_figures(LINE_7, (300, 300))["fits_format"]       # no format given: unlimited


def test_a_mapping_of_numbers_is_accepted():
    row = {"name": "area scanner", "pixel_size_um": 9, "speed_MB_s": 1.0, "sensor_kind": "array",
           "sensor_pixels": (1032, 1536), "format": (260, 260)}
    assert scanners.derived_figures(row) == scanners.derived_figures(
        scanners.Scanner("area scanner", 9, 1.0, "array", (1032, 1536), (260, 260)))


def test_layout_covers_the_frame():
    for s in (LINE, LINE_7, AREA):
        rects = scanners.scan_layout(s, (230, 230))
        area = sum(w * h for _, _, w, h in rects)
        assert area == pytest.approx(230 * 230)
        assert all(w > 0 and h > 0 for _, _, w, h in rects)


def test_bad_input():
    with pytest.raises(InputError, match="not the name"):
        scanners.derived_figures("Nikon Coolscan")
    with pytest.raises(InputError, match="positive"):
        scanners.derived_figures(LINE, (0, 230))
    with pytest.raises(InputError, match="channels"):
        scanners.derived_figures(LINE, channels=0)
    with pytest.raises(InputError, match="sensor_kind"):
        scanners.Scanner("x", 12, 1, "drum", (1,))
    with pytest.raises(InputError, match="pixel size"):
        scanners.Scanner("x", float("nan"), 1, "lines", (6000,))
