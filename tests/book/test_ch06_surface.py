"""Book layer for Chapter 6, §6.1–6.3: the entries of textbook/ch06_surface.toml keep their statuses."""

from photolib.book import ch06_surface as C
from photolib.book import verify
from photolib.book.textbook import load_chapter

PREFIXES = ("6.1", "6.2", "6.3")


def mine(entries):
    return [e for e in entries if e.id.startswith(PREFIXES) and "ch06_surface" in (e.compute or "")]


def test_every_entry_keeps_its_status():
    chapter = load_chapter(6)
    rows = [r for ex in mine(chapter.examples) for r in verify.check_example(ex)]
    rows += [verify.check_formula(fm) for fm in mine(chapter.formulas)]
    assert len(rows) == 6
    bad = [r for r in rows if not r.ok]
    assert not bad, bad


def test_formula_adapters_tell_right_from_wrong():
    wrong_x = "x_0 - f*(a11*(X - X_s) + a12*(Y - Y_s) + a13*(Z - Z_s))/(a31*(X - X_s) + a32*(Y - Y_s) + a33*(Z - Z_s))"
    ok_y = "y_0 - f*(a12*(X - X_s) + a22*(Y - Y_s) + a32*(Z - Z_s))/(a13*(X - X_s) + a23*(Y - Y_s) + a33*(Z - Z_s))"
    assert not C.image_formula({"x": wrong_x, "y": ok_y})["printed_equals_derived"]   # A instead of Aᵀ
    assert C.height_steps_formula({"i_first": 0, "n_rounding": "ceil"})["printed_equals_derived"]
    assert not C.height_steps_formula({"i_first": 0, "n_rounding": "none"})["printed_equals_derived"]


def test_segment_numbers():
    out = C.segment_contains_match({"point": [1290.0, 2140.0, 137.0], "z_min": 100.0, "z_max": 200.0})
    assert round(out["t"], 3) == 0.353 and out["distance_mm"] < 1e-9
