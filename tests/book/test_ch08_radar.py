"""Chapter 8 §8.9–8.13 adapters (photolib/book/ch08_radar.py) and their textbook entries.

Every formula adapter accepts the correct form and rejects the book's erratum or a deliberately
broken form (expected values from sympy derivations, not from photolib.radar's numeric code);
the statements' simulations give the figures recorded in textbook/ch08_radar.toml.
"""

import pytest

from photolib.book import ch08_radar as c
from photolib.book.textbook import load_chapter
from photolib.book.verify import check_example, check_formula


def ok(result):
    return result["printed_equals_derived"]


@pytest.mark.parametrize("adapter, good, bad", [
    (c.slant_range_formula, {"D": "D_0 + k*y_c"}, {"D": "D_0 - k*y_c"}),
    (c.range_vector_formula, {"vector": ["0", "D*sin(phi)", "-D*cos(phi)"]}, {"vector": []}),
    (c.range_vector_formula, {"vector": ["0", "-D*sin(phi)", "-D*cos(phi)"], "side": "right"},
     {"vector": ["0", "D*cos(phi)", "-D*sin(phi)"]}),
    (c.point_formula, {"XYZ": ["X_S + (a12*sin(phi) - a13*cos(phi))*D", "Y_S + (a22*sin(phi) - a23*cos(phi))*D",
                               "Z_S + (a32*sin(phi) - a33*cos(phi))*D"]},
     {"XYZ": ["X_S + (a12*cos(phi) - a13*sin(phi))*D", "Y_S", "Z_S"]}),
    (c.newton_formula, {"a": "D*(a32*cos(phi) + a33*sin(phi))"}, {"a": "D*(a32*cos(phi) - a33*sin(phi))"}),
    (c.vertical_formula, {"cos_phi": "H/D", "plane": "vertical"}, {"cos_phi": "H/D", "plane": "tilted"}),
    (c.stereo_point_formula, {"DXYZ1": ["D1*(b12*sin(phi1) - b13*cos(phi1))", "D1*(b22*sin(phi1) - b23*cos(phi1))",
                                        "D1*(b32*sin(phi1) - b33*cos(phi1))"]}, {"DXYZ1": ["D_X", "D_Y", "D_Z"]}),
    (c.base_formula, {"B": ["D1*(b12*sin(phi1) - b13*cos(phi1)) - D2*(c12*sin(phi2) - c13*cos(phi2))",
                            "D1*(b22*sin(phi1) - b23*cos(phi1)) - D2*(c22*sin(phi2) - c23*cos(phi2))",
                            "D1*(b32*sin(phi1) - b33*cos(phi1)) - D2*(c32*sin(phi2) - c33*cos(phi2))"]},
     {"B": ["-D1*(b12*sin(phi1) - b13*cos(phi1)) + D2*(c12*sin(phi2) - c13*cos(phi2))", "0", "0"]}),
    (c.stereo_lsq_formula, {"equations": 3, "unknowns": 2}, {"equations": 2, "unknowns": 2}),
    (c.insar_angle_formula, {"sin": "(D_2**2 - D_1**2 - B**2)/(2*D_1*B)"},
     {"sin": "(D_1**2 - D_2**2 + B**2)/(2*D_1*B)"}),
    (c.insar_height_formula, {"h": "H - D_1*cos(phi)"}, {"h": "H - D_1*sin(phi)"}),
    (c.phase_formula, {"Delta_Phi": "4*pi/lam*Delta_D"}, {"Delta_Phi": "2*pi/lam*Delta_D"}),
    (c.phase_formula, {"Delta_Phi": "2*pi/lam*Delta_D", "passes": "bistatic"},
     {"Delta_Phi": "4*pi/lam*Delta_D", "passes": "bistatic"}),
    (c.insar_difference_formula, {"sin": "(Delta_D**2 + 2*D*Delta_D - B**2)/(2*D*B)"},
     {"sin": "(Delta_D**2 + D*Delta_D - B**2)/(2*D*B)"}),
    (c.height_precision_formula, {"delta_h": "D*lam*sin(phi)/(4*pi*B_0)*delta_Phi"},
     {"delta_h": "D*lam*cos(phi)/(4*pi*B_0)*delta_Phi"}),
    (c.critical_baseline_formula, {"B_crit": "D*lam*tg(phi)/(2*delta_D)"}, {"B_crit": "D*lam*tg(phi)/delta_D"}),
])
def test_adapters_accept_the_correct_form_and_reject_the_wrong_one(adapter, good, bad):
    assert ok(adapter(good))
    assert not ok(adapter(bad))


def test_statements():
    r = c.range_only_height({"sigma_D": 1.0, "trials": 500, "seed": 4})
    assert r["rms_height_m"] > 500                          # metre ranges → km heights
    assert c.phase_range_mm({"sigma_phase_deg": 10.0, "wavelength": 0.05624})["sigma_dD_mm"] == pytest.approx(
        0.05624 * 1e3 * (10 / 180) / 4, rel=1e-12)         # λ·δΦ/(4π) with δΦ = 10° = π/18
    assert c.dinsar_mm({"wavelength": 0.05624})["mm_per_tenth_fringe"] == pytest.approx(56.24 / 20)
    b = c.envisat_critical_baseline({"D": 850e3, "wavelength": 0.05624, "look_deg": 23.0, "bandwidth": 16e6})
    assert 1050 < b["B_crit"] < 1150


def _mine(entries):
    return [e for e in entries if e.id.startswith(("8.9", "8.10", "8.11", "8.12", "8.13"))]


def test_every_entry_of_the_fragment_verifies():
    chapter = load_chapter(8)
    formulas = _mine(chapter.formulas)
    examples = _mine(chapter.examples)
    assert len(formulas) == 16 and len(examples) == 9
    for f in formulas:
        row = check_formula(f)
        assert row.ok, row
    for e in examples:
        for row in check_example(e):
            assert row.ok, row
