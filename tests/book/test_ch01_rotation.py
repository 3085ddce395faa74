"""The §1.3 formula-check adapters (photolib.book.ch01_rotation) against sympy and the derivations."""

import sympy as sp


def test_derivations_transcriptions_match_the_products():
    """derivations.book_rotation_elements_* (the printed (1.3.2), (1.3.5)) are the sympy products."""
    from photolib import derivations as dv
    from photolib.book.ch01_rotation import product
    for order, printed in (("wak", dv.book_rotation_elements_wak()), ("kaw", dv.book_rotation_elements_kaw())):
        assert sp.simplify(printed - product(order)) == sp.zeros(3, 3)


def test_formula_adapters_can_fail():
    """The §1.3 formula checks reject a wrong formula (so 'reproduced' means something)."""
    from photolib.book import ch01_rotation as ad
    wak = ["cos(alpha)*cos(kappa)", "-cos(alpha)*sin(kappa)", "sin(alpha)",
           "sin(omega)*sin(alpha)*cos(kappa) + cos(omega)*sin(kappa)",
           "-sin(omega)*sin(alpha)*sin(kappa) + cos(omega)*cos(kappa)", "-sin(omega)*cos(alpha)",
           "-cos(omega)*sin(alpha)*cos(kappa) + sin(omega)*sin(kappa)",
           "cos(omega)*sin(alpha)*sin(kappa) + sin(omega)*cos(kappa)", "cos(omega)*cos(alpha)"]
    assert ad.element_list({"order": "wak", "elements": wak})["printed_equals_derived"]
    assert not ad.element_list({"order": "kaw", "elements": wak})["printed_equals_derived"]
    hanzl_r32 = wak[:7] + ["-cos(omega)*sin(alpha)*sin(kappa) + sin(omega)*cos(kappa)"] + wak[8:]   # Hanzl's misprint
    assert not ad.element_list({"order": "wak", "elements": hanzl_r32})["printed_equals_derived"]
    good = {"order": "kaw", "omega": "atan(a32/a33)", "alpha": "asin(-a31)", "kappa": "atan(a21/a11)"}
    assert ad.angle_formulas(good)["printed_equals_derived"]
    assert not ad.angle_formulas({**good, "alpha": "asin(a31)"})["printed_equals_derived"]
    assert not ad.angle_formulas({**good, "order": "wak"})["printed_equals_derived"]
    ocr_literal = [["cos(a)*cos(omega)", "d**2 - a**2 - b**2 + c**2"]]   # the OCR's 'cos a' read as component a
    assert not ad.quaternion_angle_relations({"relations": ocr_literal})["printed_equals_derived"]
    assert ad.quaternion_angle_relations(
        {"relations": [["cos(alpha)*cos(omega)", "d**2 - a**2 - b**2 + c**2"]]})["printed_equals_derived"]
    assert not ad.orthogonality({"relations": [["a11*a12 + a21*a22 + a31*a32", "1"]]})["printed_equals_derived"]
