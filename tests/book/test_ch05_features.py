"""Chapter 5 §5.5, §5.7–5.10 adapters (photolib/book/ch05_features.py) and their TOML entries:
every entry verifies with its recorded status; every formula adapter accepts the derived form and
rejects the printed erratum or a deliberately broken version of a correct formula; Fig. 5.12."""

import pytest

from photolib.book import ch05_features as c
from photolib.book import verify
from photolib.book.textbook import load_chapter

OURS = ("5.12-", "5.5", "5.8", "5.9-", "5.10-")


def entries():
    ch = load_chapter(5)
    return ([e for e in ch.examples if e.id.startswith(OURS)],
            [f for f in ch.formulas if f.id.startswith(OURS)])


EXAMPLES, FORMULAS = entries()


@pytest.mark.parametrize("example", EXAMPLES, ids=[e.id for e in EXAMPLES])
def test_example_status_holds(example):
    rows = verify.check_example(example)
    bad = [r for r in rows if not r.ok]
    assert not bad, bad


@pytest.mark.parametrize("formula", FORMULAS, ids=[f.id for f in FORMULAS])
def test_formula_status_holds(formula):
    assert verify.check_formula(formula).ok


def test_fig_5_12_counts():
    ex = next(e for e in EXAMPLES if e.id == "5.12-roberts-image")
    statuses = [q.status for q in ex.quantities]
    assert len(statuses) == 64 and statuses.count("erratum") == 39 and statuses.count("reproduced") == 25


def ok(result):
    return result["printed_equals_derived"]


GAUSS = "exp(-(x**2 + y**2)/(2*sigma**2))"


@pytest.mark.parametrize("fn,right,wrong", [
    (c.gradient_definition, {"printed": ["diff(f, x)", "diff(f, y)"]}, {"printed": ["diff(f, x)", "-diff(f, y)"]}),
    (c.gradient_magnitude_formula, {"printed": "sqrt(gx**2 + gy**2)", "norm": "l2"},
     {"printed": "gx**2 + gy**2", "norm": "l2"}),
    (c.gradient_magnitude_formula, {"printed": "abs(gx) + abs(gy)", "norm": "l1"},
     {"printed": "abs(gx) + 2*abs(gy)", "norm": "l1"}),
    (c.backward_differences, {"printed": ["f(x, y) - f(x - 1, y)", "f(x, y) - f(x, y - 1)"]},
     {"printed": ["f(x - 1, y) - f(x, y)", "f(x, y) - f(x, y - 1)"]}),
    (c.derivative_masks, {"operator": "sobel", "Hx": [["-1", "0", "1"], ["-2", "0", "2"], ["-1", "0", "1"]],
                          "Hy": [["1", "2", "1"], ["0", "0", "0"], ["-1", "-2", "-1"]]},
     {"operator": "sobel", "Hx": [["-1", "0", "1"], ["-1", "0", "1"], ["-1", "0", "1"]],
      "Hy": [["1", "2", "1"], ["0", "0", "0"], ["-1", "-2", "-1"]]}),
    (c.derivative_masks, {"operator": "roberts", "Hx": [["0", "1"], ["-1", "0"]], "Hy": [["1", "0"], ["0", "-1"]]},
     {"operator": "roberts", "Hx": [["1", "0"], ["0", "-1"]], "Hy": [["0", "1"], ["-1", "0"]]}),
    (c.sobel_nine_pixels, {"printed": ["(f3 + 2*f6 + f9) - (f1 + 2*f4 + f7)", "(f1 + 2*f2 + f3) - (f7 + 2*f8 + f9)"]},
     {"printed": ["(f1 + 2*f4 + f7) - (f3 + 2*f6 + f9)", "(f1 + 2*f2 + f3) - (f7 + 2*f8 + f9)"]}),
    (c.moravec_terms, {"i_lower": "-n/2", "i_upper": "n/2"}, {"i_lower": "n/2", "i_upper": "n/2"}),
    (c.harris_quadratic_form, {"printed_square": "(gx*u + gy*v)**2", "printed_vector": ["u", "v"]},
     {"printed_square": "(gx*u - gy*v)**2", "printed_vector": ["x", "y"]}),
    (c.autocorrelation_matrix, {"printed": [["gx**2", "gx*gy"], ["gx*gy", "gy**2"]]},
     {"printed": [["gx**2", "-gx*gy"], ["gx*gy", "gy**2"]]}),
    (c.harris_det_trace_response, {"quantity": "det", "printed": "A*D - B**2"}, {"quantity": "det", "printed": "C - B**2"}),
    (c.harris_det_trace_response, {"quantity": "trace", "printed": "A + D"}, {"quantity": "trace", "printed": "A + C"}),
    (c.harris_det_trace_response, {"quantity": "response", "printed": "l1*l2 - k*(l1 + l2)**2"},
     {"quantity": "response", "printed": "l1*l2 - k*(l1 + l2)"}),
    (c.foerstner_inverse, {"printed_adjugate": [["Syy", "-Sxy"], ["-Sxy", "Sxx"]]},
     {"printed_adjugate": [["Sxx", "-Sxy"], ["-Sxy", "Syy"]]}),
    (c.foerstner_w, {"printed": "(Sxx*Syy - Sxy**2)/(Sxx + Syy)"}, {"printed": "(Sxx*Syy - Sxy**2)/(Sxx + Syy)**2"}),
    (c.foerstner_q, {"printed": "4*(Sxx*Syy - Sxy**2)/(Sxx + Syy)**2"}, {"printed": "2*(Sxx*Syy - Sxy**2)/(Sxx + Syy)**2"}),
    (c.fast_classification, {"printed": ["f_u <= f_c - t", "(f_c - t < f_u) & (f_u < f_c + t)", "f_c + t <= f_u"]},
     {"printed": ["f_u <= f_c - t", "(f_c - t <= f_u) & (f_u < f_c + t)", "f_c + t <= f_u"]}),
    (c.gaussian_formula, {"printed": f"{GAUSS}/(2*pi*sigma**2)"}, {"printed": f"{GAUSS}/(2*pi*sigma)"}),
    (c.gaussian_derivative, {"printed": {"Wx": f"-x/(2*pi*sigma**4)*{GAUSS}"}},
     {"printed": {"Wx": f"x/(2*pi*sigma**4)*{GAUSS}"}}),
    (c.gaussian_derivative, {"printed": {"Wxx": f"(x**2 - sigma**2)/(2*pi*sigma**6)*{GAUSS}"}},
     {"printed": {"Wxx": f"-(x**2 - sigma**2)/(2*pi*sigma**6)*{GAUSS}"}}),
    (c.gaussian_derivative, {"printed": {"LoG": f"(x**2 + y**2 - 2*sigma**2)/(2*pi*sigma**6)*{GAUSS}"}},
     {"printed": {"LoG": "(x**2 + y**2 - 2*sigma**2)/(2*pi*sigma**6)*exp((x**2 + y**2)/(2*sigma**2))"}}),
])
def test_formula_adapters_accept_right_and_reject_wrong(fn, right, wrong):
    assert ok(fn(right)) and not ok(fn(wrong))


def test_inline_adapters():
    assert c.foerstner_q_bounds({}) == {"q_min": 0.0, "q_max": 1.0}
    assert c.foerstner_w_meaning({}) == {"w_at_good_points": "large"}
    assert c.descriptor_size({"cells": 4, "cell_size": 4, "bins": 8}) == {"region_side": 16.0, "n_features": 128.0}
    assert c.descriptor_size({"cells": 2, "cell_size": 4, "bins": 8})["n_features"] == 32.0
    assert c.ransac_minimal_sample({}) == {"min_points": 5.0}
