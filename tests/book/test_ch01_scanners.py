"""§1.12 Table 1.1 read from textbook/ (photolib.book.ch01_scanners) and the derived table."""

import math

import pytest

from photolib import scanners
from photolib.book import ch01_scanners
from photolib.book.textbook import load_chapter
from photolib.errors import InputError


def test_table_1_1_has_4_scanners_by_8_rows():
    ex = load_chapter(1).example(ch01_scanners.TABLE_ID)
    assert len(ex.inputs["scanners"]) == 4 and len(ex.inputs["rows"]) == 8
    assert len(ex.quantities) == 32
    assert all(q.status == "transcribed" for q in ex.quantities)
    table = ch01_scanners.table_1_1()
    assert [s["name"] for s in table] == ex.inputs["scanners"]
    assert all(set(ch01_scanners.ROWS) <= set(s) for s in table)


def test_table_values_are_parsed_from_textbook():
    ex = load_chapter(1).example(ch01_scanners.TABLE_ID)
    printed = {q.name: q.printed for q in ex.quantities}
    for s in ch01_scanners.table_1_1():
        # numbers: the transcribed value is the printed one with a decimal point
        assert float(printed[f"speed_MB_s[{s['name']}]"].replace(",", ".")) == s["speed_MB_s"]
        assert str(s["pixel_size_um"]) == printed[f"pixel_size_um[{s['name']}]"]
        fw, fh = s["format"]
        assert printed[f"format_mm[{s['name']}]"] == f"{fw:g}×{fh:g}"
        n = s["sensor_pixels"]
        assert printed[f"sensor[{s['name']}]"].endswith("×".join(map(str, n)))
    kinds = [s["sensor_kind"] for s in ch01_scanners.table_1_1()]
    assert kinds == ["lines", "lines", "array", "lines"]


def test_derived_figures_of_table_1_1_by_hand():
    s = {x["name"]: x for x in ch01_scanners.table_1_1()}
    f = scanners.derived_figures(s["UltraScan 5000"], (230, 230), bits=8, channels=1)
    assert f["pixels_x"] == math.ceil(230 / 0.012) == 19167
    assert f["swaths"] == math.ceil(230 / (6000 * 0.012)) == 4
    assert scanners.derived_figures(s["PhotoScan PS2002 Z/I Imaging"])["pixels_x"] == 32858
    d = ch01_scanners.derived_figures("DSW 500 LH System")
    assert d["tiles"] == math.ceil(230 / (1536 * 0.009)) * math.ceil(230 / (1032 * 0.009))
    assert not ch01_scanners.derived_figures("UltraScan 5000", (300, 300))["fits_format"]
    assert ch01_scanners.scanner("UltraScan 5000").pixel_size_um == 12


def test_layout_covers_the_frame():
    for s in ch01_scanners.table_1_1():
        rects = scanners.scan_layout(s, (230, 230))
        assert sum(w * h for _, _, w, h in rects) == pytest.approx(230 * 230)


def test_derived_table_is_labelled():
    t = ch01_scanners.derived_table()
    assert "not in the book" in t.title
    assert len(t.rows) == 4


def test_unknown_scanner():
    with pytest.raises(InputError, match="no scanner"):
        ch01_scanners.derived_figures("Nikon Coolscan")
