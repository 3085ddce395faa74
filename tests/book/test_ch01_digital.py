"""The §1.10–§1.11 formula-check adapters (photolib.book.ch01_digital)."""

from photolib.book import ch01_digital


def test_formula_checks_report_the_reconstruction():
    r = ch01_digital.formula_1_11_6({})
    assert r == {"printed_equals_derived": False, "reconstruction_equals_derived": True,
                 "exact_inverse_round_trip": True, "mark2_on_x_axis": True, "printed_mark2_on_x_axis": False}
    r = ch01_digital.formula_1_11_10({})
    assert not r["printed_equals_derived"] and r["equal_when_kx_eq_ky"] and r["difference_is_a2_dk"]
