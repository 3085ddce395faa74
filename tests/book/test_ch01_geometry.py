"""The §1.4–§1.7 formula-check adapters (photolib.book.ch01_geometry)."""


def test_scale_formula_check_accepts_only_f_over_H():
    """The formula check behind the §1.5 scale erratum: the printed 1/H fails, f/H passes."""
    from photolib.book.ch01_geometry import horizontal_image_scale as check
    assert check({"printed": "f/H", "f_mm": 153.0, "H_m": 1800.0})["printed_equals_derived"]
    assert not check({"printed": "1/H", "f_mm": 153.0, "H_m": 1800.0})["printed_equals_derived"]
