"""The §1.10–§1.11 formula-check adapters (photolib.book.ch01_digital)."""

import numpy as np
import pytest

from photolib.book import ch01_digital


def test_formula_checks_report_the_reconstruction():
    r = ch01_digital.formula_1_11_6({})
    assert r == {"printed_equals_derived": False, "reconstruction_equals_derived": True,
                 "exact_inverse_round_trip": True, "mark2_on_x_axis": True, "printed_mark2_on_x_axis": False}
    r = ch01_digital.formula_1_11_10({})
    assert not r["printed_equals_derived"] and r["equal_when_kx_eq_ky"] and r["difference_is_a2_dk"]


@pytest.mark.parametrize("phi_deg, vertical", [(0.5, False), (-1.3, False), (0.0, True)])
def test_book_slope_form_of_the_origin(phi_deg, vertical):
    """(1.11.7) as printed gives the synthetic origin, except when line 3–4 is vertical (c₂ = ∞)."""
    import numpy as np
    from photolib.book.ch01_digital import book_origin
    side = np.array([[-106.0, 0.0], [106.0, 0.0], [0.0, 106.0], [0.0, -106.0]])
    a0, b0, phi, kx, ky = 3.2, -2.7, np.radians(phi_deg), 0.9995, 1.0003
    u, v = side[:, 0] / kx, side[:, 1] / ky                       # exact inverse of (1.11.6)
    c, s = np.cos(phi), np.sin(phi)
    measured = np.column_stack([a0 + c * u - s * v, b0 + s * u + c * v])
    if vertical:
        assert measured[2, 0] == measured[3, 0]
        assert not np.isfinite(book_origin(measured)[0])
    else:
        assert book_origin(measured) == pytest.approx((a0, b0), abs=1e-9)
