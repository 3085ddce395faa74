"""Book layer of the GNSS-centres appendix (Dobrynin & Pimshina): the adapters of
:mod:`photolib.book.gnss` that feed ``photolib verify`` (moved from tests/library, which must not
import the book layer)."""

from photolib.book import gnss as book


def test_printed_formula_statuses():
    verdicts = {item: book.formula_check({"item": item})["printed_equals_derived"] for item in
                ("cosines:a1/omega", "cosines:c2/chi", "vector:A", "vector:B", "coplanarity:d", "coplanarity:e",
                 "ground:d'", "coplanarity:a", "coplanarity:c", "coplanarity:m", "vector:C,Y_alpha,D,E,Z_alpha,F",
                 "intersection", "initial-chi", "rotation", "collinearity")}
    wrong = {k for k, v in verdicts.items() if not v}
    assert wrong == {"cosines:a1/omega", "cosines:c2/chi", "vector:A", "vector:B", "coplanarity:d",
                     "coplanarity:e", "ground:d'"}
    for item in ("cosines", "vector", "coplanarity", "ground"):
        assert book.corrected_formula_check({"item": item})["printed_equals_derived"]


def test_one_control_point_fixes_the_sixth_angle():
    r = book.equation_count({"azimuth_deg": 75.0, "seed": 2, "tie_points": 5})
    assert r["rank of the coplanarity equations alone"] == 5 and r["rank with one control point"] == 6
