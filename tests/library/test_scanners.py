"""§1.12 scanners (photolib.scanners): Table 1.1 from textbook/, derived figures (ours)."""

import math

import pytest

from photolib import scanners
from photolib.errors import InputError
from photolib.book.textbook import load_chapter


def test_table_1_1_has_4_scanners_by_8_rows():
    ex = load_chapter(1).example(scanners.TABLE_ID)
    assert len(ex.inputs["scanners"]) == 4 and len(ex.inputs["rows"]) == 8
    assert len(ex.quantities) == 32
    assert all(q.status == "transcribed" for q in ex.quantities)
    table = scanners.table_1_1()
    assert [s["name"] for s in table] == ex.inputs["scanners"]
    assert all(set(scanners.ROWS) <= set(s) for s in table)


def test_table_values_are_parsed_from_textbook():
    ex = load_chapter(1).example(scanners.TABLE_ID)
    printed = {q.name: q.printed for q in ex.quantities}
    for s in scanners.table_1_1():
        # numbers: the transcribed value is the printed one with a decimal point
        assert float(printed[f"speed_MB_s[{s['name']}]"].replace(",", ".")) == s["speed_MB_s"]
        assert str(s["pixel_size_um"]) == printed[f"pixel_size_um[{s['name']}]"]
        fw, fh = s["format"]
        assert printed[f"format_mm[{s['name']}]"] == f"{fw:g}×{fh:g}"
        n = s["sensor_pixels"]
        assert printed[f"sensor[{s['name']}]"].endswith("×".join(map(str, n)))
    kinds = [s["sensor_kind"] for s in scanners.table_1_1()]
    assert kinds == ["lines", "lines", "array", "lines"]


def test_radiometric_levels():
    assert scanners.radiometric_levels(8) == 256
    assert [scanners.radiometric_levels(b) for b in (10, 12, 16)] == [1024, 4096, 65536]
    with pytest.raises(InputError):
        scanners.radiometric_levels(0)


def test_derived_figures_by_hand():
    s = {x["name"]: x for x in scanners.table_1_1()}
    f = scanners.derived_figures(s["UltraScan 5000"], (230, 230), bits=8, channels=1)
    assert f["pixels_x"] == math.ceil(230 / 0.012) == 19167
    assert f["raw_MB"] == pytest.approx(19167 ** 2 / 1e6)
    assert f["scan_time_min"] == pytest.approx(19167 ** 2 / 1e6 / 0.14 / 60)
    assert f["swaths"] == math.ceil(230 / (6000 * 0.012)) == 4
    # 7 μm divides 230 mm into 32857.14 → 32858 pixels (a partial pixel still has to be scanned)
    assert scanners.derived_figures(s["PhotoScan PS2002 Z/I Imaging"])["pixels_x"] == 32858
    # 16 bit RGB is 6× the bytes of 8 bit grey
    g = scanners.derived_figures(s["UltraScan 5000"], 230, bits=16, channels=3)
    assert g["raw_MB"] == pytest.approx(6 * f["raw_MB"])
    d = scanners.derived_figures("DSW 500 LH System")
    assert d["tiles"] == math.ceil(230 / (1536 * 0.009)) * math.ceil(230 / (1032 * 0.009))
    assert not scanners.derived_figures("UltraScan 5000", (300, 300))["fits_format"]


def test_layout_covers_the_frame():
    for s in scanners.table_1_1():
        rects = scanners.scan_layout(s, (230, 230))
        area = sum(w * h for _, _, w, h in rects)
        assert area == pytest.approx(230 * 230)
        assert all(w > 0 and h > 0 for _, _, w, h in rects)


def test_derived_table_is_labelled():
    t = scanners.derived_table()
    assert "not in the book" in t.title
    assert len(t.rows) == 4


def test_bad_input():
    with pytest.raises(InputError, match="no scanner"):
        scanners.derived_figures("Nikon Coolscan")
    with pytest.raises(InputError, match="positive"):
        scanners.derived_figures("UltraScan 5000", (0, 230))
    with pytest.raises(InputError, match="channels"):
        scanners.derived_figures("UltraScan 5000", channels=0)
