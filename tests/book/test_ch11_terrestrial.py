"""Chapter 11 §11.4–11.9 adapters (photolib/book/ch11_terrestrial.py) and their textbook entries.

Every formula adapter accepts the correct form and rejects a deliberately broken one (or the
book's erratum); the entries of textbook/ch11_terrestrial.toml hold their recorded statuses; the
worked example's 24 values are checked against the book's own arithmetic independently of the
library (plain formulas typed from the text).
"""

import pytest

from photolib.book import ch11_terrestrial as c
from photolib.book.textbook import load_chapter
from photolib.book.verify import check_example, check_formula

DIST = "sqrt((X_i-X_j)**2+(Y_i-Y_j)**2+(Z_i-Z_j)**2)"
POLAR_X = ("x_0 - f*(a11*cos(nu)*sin(phi)+a21*cos(nu)*cos(phi)+a31*sin(nu))"
           "/(a13*cos(nu)*sin(phi)+a23*cos(nu)*cos(phi)+a33*sin(nu))")
POLAR_Y = ("y_0 - f*(a12*cos(nu)*sin(phi)+a22*cos(nu)*cos(phi)+a32*sin(nu))"
           "/(a13*cos(nu)*sin(phi)+a23*cos(nu)*cos(phi)+a33*sin(nu))")


def ok(result):
    return result["printed_equals_derived"]


@pytest.mark.parametrize("adapter, good, bad", [
    (c.condition_formula, {"model": "distance", "F": f"{DIST} - D"}, {"model": "distance", "F": f"{DIST} + D"}),
    (c.condition_formula, {"model": "vertical", "F": ["X_i - X_j", "Y_i - Y_j"]},
     {"model": "vertical", "F": ["X_i - X_j", "Z_i - Z_j"]}),
    (c.condition_formula, {"model": "horizontal", "F": "Z_i - Z_j"}, {"model": "horizontal", "F": "Z_i - Z_i"}),
    (c.plane_formula, {"rows": [["X_j-X_i", "Y_j-Y_i", "Z_j-Z_i"], ["X_k-X_i", "Y_k-Y_i", "Z_k-Z_i"],
                                ["X_l-X_i", "Y_l-Y_i", "Z_l-Z_i"]]},
     {"rows": [["X_i-X_j", "Y_i-Y_j", "Z_i-Z_j"], ["X_i-X_k", "Y_i-Y_k", "Z_i-Z_k"], ["X_j-X_k", "Y_j-Y_k", "Z_j-Z_k"]]}),
    (c.distance_correction_formula,
     {"l_D": "D0 - D", "delta_D": "((X_i-X_j)*(dX_i-dX_j)+(Y_i-Y_j)*(dY_i-dY_j)+(Z_i-Z_j)*(dZ_i-dZ_j))/D0"},
     {"l_D": "D - D0", "delta_D": "((X_i-X_j)*(dX_i-dX_j)+(Y_i-Y_j)*(dY_i-dY_j)+(Z_i-Z_j)*(dZ_i-dZ_j))/D0"}),
    (c.polar_formula, {"xy": [POLAR_X, POLAR_Y]}, {"xy": [POLAR_X.replace("a21", "a12"), POLAR_Y]}),
    (c.polar_linearised_formula, {"unknowns": ["omega", "alpha", "kappa"]}, {"unknowns": ["omega", "alpha"]}),
    (c.linking_shift_formula, {"form": "A R_3M t"}, {"form": "zero"}),
    (c.linking_linear_formula, {"rows": ["c11*X+c12*Y+c13*Z", "c21*X+c22*Y+c23*Z", "c31*X+c32*Y+c33*Z"]},
     {"rows": ["c11*X+c21*Y+c31*Z", "c12*X+c22*Y+c32*Z", "c13*X+c23*Y+c33*Z"]}),
    (c.orthogonality_formula, {"equations": ["c31*c21+c32*c22+c33*c23"]}, {"equations": ["c31*c21+c32*c22+c33*c22"]}),
    (c.scale_formula, {"t": "sqrt(c11**2+c12**2+c13**2)"}, {"t": "c11+c12+c13"}),
    (c.chaining_formula, {"order": ["A0", "A", "A3p"]}, {"order": ["A3p", "A", "A0"]}),
    (c.intersection_scale_formula, {"N": "(B_X*Yp_2 - B_Y*Xp_2)/(Xp_1*Yp_2 - Xp_2*Yp_1)"},
     {"N": "(B_X*Xp_2 - B_Y*Yp_2)/(Xp_1*Yp_2 - Xp_2*Yp_1)"}),
    (c.normal_matrix_formula, {"A": [[1, 0, 0], [0, 0, -1], [0, 1, 0]], "ray": ["x", "f", "y"], "N": "B_X/p"},
     {"A": [[1, 0, 0], [0, 0, 1], [0, -1, 0]], "ray": ["x", "-f", "y"], "N": "B_X/p"}),
    (c.normal_point_formula, {"XYZ": ["Y/f*x_1", "B_X/p*f", "Y/f*y_1"]}, {"XYZ": ["Y/f*x_1", "B_X/p*f", "Y/f*x_1"]}),
    (c.accuracy_formula, {"m": ["Y/f*m_x", "Y/b*m_p", "Y/f*m_y"]}, {"m": ["Y/f*m_x", "Y/f*m_p", "Y/f*m_y"]}),
    (c.base_formula, {"b": "l_x*(100-P)/100"}, {"b": "l_x*P/100"}),
    (c.coverage_formula, {"delta": "Y/f", "H": ["l_x*Delta", "l_y*Delta"]}, {"delta": "f/Y", "H": ["l_x*Delta", "l_y*Delta"]}),
])
def test_formula_adapters_discriminate(adapter, good, bad):
    assert ok(adapter(good))
    assert not ok(adapter(bad))


def _fragment_entries():
    ch = load_chapter(11)
    return [e for e in list(ch.examples) + list(ch.formulas)
            if getattr(e, "compute", "") and "ch11_terrestrial" in (e.compute or "")
            or e.id.startswith(("11.4", "11.5", "11.6", "11.7", "11.8", "11.9"))]


@pytest.mark.parametrize("entry", _fragment_entries(), ids=lambda e: e.id)
def test_entry_holds_its_status(entry):
    rows = check_example(entry) if hasattr(entry, "quantities") else [check_formula(entry)]
    bad = [(r.quantity, r.computed, r.status, r.detail) for r in rows if not r.ok]
    assert not bad, bad


def test_worked_example_has_24_values_and_book_arithmetic():
    ex = next(e for e in load_chapter(11).examples if e.id == "11.8-accuracy-design")
    assert len(ex.quantities) == 24
    # the book's own arithmetic, typed from the text (lines 6786–6838)
    Y, m = 30.0, 0.5
    for f, lx, b, mY in ((17400, 11600, 4640, 0.003), (11670, 5470, 2188, 0.007),
                         (17400, 8700, 3480, 0.004), (11670, 3650, 1460, 0.010)):
        assert lx * (100 - 60) / 100 == b
        assert round(Y / b * m, 3) == mY and round(Y / f * m, 3) == 0.001
    assert [round(d * b, 1) for d, b in ((0.0017, 4640), (0.0026, 2188), (0.0017, 3480), (0.0026, 1460))] == \
        [7.9, 5.7, 5.9, 3.8]


def test_input_rounding_bounds_cover_the_exact_base():
    ex = next(e for e in load_chapter(11).examples if e.id == "11.8-accuracy-design")
    out = c.worked_example(ex.inputs)
    for q in ex.quantities:
        if q.status == "input-rounding":
            assert abs(out[q.name] - q.value) <= q.bound
            b = out["b_" + q.name[2:]]
            assert q.bound == pytest.approx(b * 0.00005 + 0.05, abs=1e-4)


def test_stereo_width_is_sixty_percent_of_coverage():
    ex = next(e for e in load_chapter(11).examples if e.id == "11.8-accuracy-design")
    out = c.worked_example(ex.inputs)
    for key in ("phaseone_horizontal", "sony_horizontal"):
        cam = key.split("_")[0]
        assert out[f"stereo_width_{key}"] == pytest.approx(0.6 * out[f"HX_{cam}"])
        assert out[f"B_{key}"] == pytest.approx(0.4 * out[f"HX_{cam}"])
