"""The MRF terrain paper's entries (textbook/ch06_mrf.toml): adapters accept the right forms, reject wrong ones."""

import pytest

from photolib.book import ch06_mrf as B
from photolib.book.textbook import load_chapter
from photolib.book.verify import check_example, check_formula

CH = load_chapter(6)
FORMULAS = [f for f in CH.formulas if f.id.startswith("mrf-")]
EXAMPLES = [e for e in CH.examples if e.id.startswith("mrf-")]


def test_fragment_refers_to_the_paper():
    assert FORMULAS and EXAMPLES
    assert all(e.seed == "003_82b4f0b2dd43dc56.txt" for e in FORMULAS + EXAMPLES)


@pytest.mark.parametrize("formula", FORMULAS, ids=lambda f: f.id)
def test_formula_status(formula):
    assert check_formula(formula).ok


@pytest.mark.parametrize("example", EXAMPLES, ids=lambda e: e.id)
def test_example_status(example):
    assert all(r.ok for r in check_example(example))


def test_correlation_literal_reading_differs():
    sums = {"a": "Sum(S1)", "b": "Sum(S2)", "e": "Dot(S1, S2)"}
    restored = {**sums, "c": "Sum(Sq(S1))", "d": "Sum(Sq(S2))", "r": "(e - a*b/n)/sqrt((c - a**2/n)*(d - b**2/n))"}
    assert B.correlation_formula(restored)["printed_equals_derived"]
    literal = {**sums, "c": "Sum(S1)*2", "d": "Sum(S2)*2", "r": "(e - a*b/n)/((c - a*2/n)*(d - b*2/n))*1/2"}
    assert not B.correlation_formula(literal)["printed_equals_derived"]
    swapped = {**restored, "r": "(e - a*b/n)/sqrt((c - a**2/n)*(d - b**2))"}
    assert not B.correlation_formula(swapped)["printed_equals_derived"]


def test_parallax_count_constants():
    assert B.parallax_count_formula({"N": "(H_max - H_min)*B*DPI/(H*M*0.0254)"})["printed_equals_derived"]
    for k in ("0.245", "0.254"):
        assert not B.parallax_count_formula({"N": f"(H_max - H_min)*B*DPI/(H*M*{k})"})["printed_equals_derived"]


def test_relative_elements_rank():
    printed = B.relative_elements_rank({"elements": ["alpha1", "omega1", "alpha2", "omega2", "chi2"]})
    base = B.relative_elements_rank({"elements": ["alpha1", "chi1", "alpha2", "omega2", "chi2"]})
    assert printed["rank_at_start"] == 4 and base["rank_at_start"] == 5
    assert printed["condition_at_solution"] > 10 * base["condition_at_solution"]


def test_intersection_without_p():
    good = {"N": "(Bx + x20*Bz/f)/(x10 - x20)", "X": "Xs1 + N*x10", "Y": "Ys1 + N*y10", "Z": "Zs1 - f*N"}
    assert B.intersection_formula(good)["printed_equals_derived"]
    assert not B.intersection_formula({**good, "Z": "Zs1 + p - f*N"})["printed_equals_derived"]
    assert not B.intersection_formula({**good, "N": "(Bx - x20*Bz/f)/(x10 - x20)"})["printed_equals_derived"]


def test_similarity_angle_map():
    assert B.similarity_angle_map({"alpha": "zeta", "omega": "xi", "chi": "nu"})["printed_equals_derived"]
    assert not B.similarity_angle_map({"alpha": "zeta", "omega": "nu", "chi": "xi"})["printed_equals_derived"]


def test_smoothness_sign_and_gibbs_conditional():
    assert not B.smoothness_sign({"b_sign": 1, "Delta": "(p - q)**2"})["printed_equals_derived"]
    assert B.smoothness_sign({"b_sign": -1, "Delta": "(p - q)**2"})["printed_equals_derived"]
    good = {"numerator": "exp(a*Vp(p) + b*Vs(p))", "summand": "exp(a*Vp(q) + b*Vs(q))"}
    assert B.gibbs_conditional(good)["printed_equals_derived"]
    assert not B.gibbs_conditional({**good, "numerator": "exp(a*Vp(p) + 2*b*Vs(p))"})["printed_equals_derived"]


def test_geometry_adapters_reject_wrong_forms():
    assert not B.horizontal_reduction_formula({"x0": "f*Xp/Zp", "y0": "-f*Yp/Zp"})["printed_equals_derived"]
    assert not B.convergence_rotation_formula({"X": "Xp*cos(G0) + Yp*sin(G0)", "Y": "Yp*cos(G0) + Xp*sin(G0)",
                                               "Z": "Zp"})["printed_equals_derived"]
    assert not B.base_direction_formula({"A_tau": "A1*Ab.T", "A2": "A_tau*A2p",
                                         "base": ["cos(v)*cos(tau)", "cos(v)*sin(tau)", "sin(v)"]})["printed_equals_derived"]
