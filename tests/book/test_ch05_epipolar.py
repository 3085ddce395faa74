"""Book layer for Chapter 5, §5.6: the entries of textbook/ch05_epipolar.toml keep their statuses."""

from photolib.book import ch05_epipolar as C
from photolib.book import verify
from photolib.book.textbook import load_chapter


def mine(entries):
    return [e for e in entries if e.id.startswith("5.6")]


def test_every_entry_keeps_its_status():
    chapter = load_chapter(5)
    rows = [r for ex in mine(chapter.examples) for r in verify.check_example(ex)]
    rows += [verify.check_formula(fm) for fm in mine(chapter.formulas)]
    assert len(rows) >= 12
    bad = [r for r in rows if not r.ok]
    assert not bad, bad


def test_formula_adapters_tell_right_from_wrong():
    correct = "(Z_1*(a21*x_c - a23*f) - Y_1*(a31*x_c - a33*f))/(Y_1*a32 - Z_1*a22)"
    assert C.epipolar_ordinate_formula({"printed": correct})["printed_equals_derived"]
    assert not C.coplanarity_formula({"printed": "Y_1*Z_c + Y_c*Z_1"})["printed_equals_derived"]
    assert not C.unnumbered_formula({"printed": "Y_1*(a31*x_c + a32*y_c + a33*f) - Z_1*(a21*x_c + a22*y_c - a23*f)"})[
        "printed_equals_derived"]


def test_printed_ordinate_is_the_negative():
    out = C.epipolar_ordinate_numeric({"model_point": [0.3, 0.4, -3.0]})
    assert round(out["y_true"], 9) == 0.013072817 and out["difference"] < 1e-15
    assert abs(C.epipolar_ordinate_printed({"model_point": [0.3, 0.4, -3.0]})["y_c"] + out["y_true"]) < 1e-15


def test_normal_case_removes_large_y_parallaxes():
    out = C.normal_case({"seed": 3})
    assert out["max_q_before_px"] > 10 and out["max_q_px"] < 1e-9
