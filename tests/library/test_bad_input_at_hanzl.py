"""Bad-input catalogue for Hanzl §4–§5 (aerotriangulation, close range): the additional-parameter models
hanzl17, brown18, murai (photolib.additional_parameters), the AP option and tests of the self-calibrating
bundle (photolib.bundle), the accuracy rules (photolib.triangulation_layouts, photolib.terrestrial) and the
sympy forms (photolib.derivations.hanzl_at)."""

import numpy as np
import pytest

from catalogue import INF, NAN, Case, check_case
from photolib import additional_parameters as ap
from photolib import bundle, synthetic, terrestrial
from photolib import triangulation_layouts as tl
from photolib.camera import InteriorOrientation
from photolib.derivations import hanzl_at as D
from photolib.errors import InputError


def _small_result(with_ap=True):
    blk = synthetic.aerial_block(2, 3, points_per_image=15, sigma=0.002, seed=3)
    cams0, pts0 = blk.start_values(seed=2)
    kw = dict(additional_parameters="hanzl17", ap_names=("g1", "g2"), ap_base=40.0) if with_ap else {}
    return bundle.self_calibrating_bundle_adjustment(blk.observations, cams0, pts0, blk.io,
                                                     calibrate=() if with_ap else ("x0", "y0"),
                                                     control=blk.control_values(), order=blk.order, **kw)


_BLK = synthetic.aerial_block(2, 3, points_per_image=15, sigma=0.002, seed=3)
_C0, _P0 = _BLK.start_values(seed=2)
_ARGS = (_BLK.observations, _C0, _P0, _BLK.io)
_KW = dict(control=_BLK.control_values(), order=_BLK.order)
_IO = InteriorOrientation(f=100.0)

CASES = [
    # models
    Case(ap.hanzl17, ([[1.0, 1.0]], {"g1": 1.0}, 0.0), raises=InputError, why="b = 0"),
    Case(ap.hanzl17, ([[1.0, 1.0]], {"g1": 1.0}, 92.0, -1.0), raises=InputError, why="negative r0"),
    Case(ap.hanzl17, ([[1.0, 1.0]], {"g18": 1.0}, 92.0), raises=InputError, match="g18", why="unknown parameter"),
    Case(ap.hanzl17, ([[1.0, 1.0]], [0.0] * 12, 92.0), raises=InputError, match="17", why="12 numbers for 17"),
    Case(ap.hanzl17, ([[NAN, 1.0]], {"g1": 1.0}, 92.0), raises=InputError, why="NaN coordinate"),
    Case(ap.hanzl17, ([[2.0, 0.0]], {"g13": 1.0}, 92.0, 2.0), raises=None, why="radial zero at r = r0",
         check=lambda d: np.allclose(d, 0.0)),
    Case(ap.brown18, ([[1.0, 1.0]], {"a1": 1.0}, 0.0), raises=InputError, why="c = 0"),
    Case(ap.brown18, ([[1.0, 1.0]], "a1"), {"c": 50.0}, raises=InputError, why="string parameters"),
    Case(ap.brown18, ([[1.0, 1.0, 1.0]], {"a1": 1.0}, 50.0), raises=InputError, why="3 coordinates"),
    Case(ap.murai, ([[1.0, 1.0]], {"K3": 1.0}), raises=InputError, match="K3", why="Murai has no K3"),
    Case(ap.murai, ([[INF, 1.0]], {"K1": 1.0}), raises=InputError, why="inf coordinate"),
    Case(ap.ap_basis, ("hanzl17", [[1.0, 1.0]]), {"b": 92.0}, raises=InputError, match="r0", why="no r0"),
    Case(ap.ap_basis, ("brown18", [[1.0, 1.0]]), raises=InputError, match="f", why="no c"),
    Case(ap.ap_corrections, ("orient", [[1.0, 1.0]], {}), raises=InputError, match="unknown", why="ORIENT not implemented"),
    # bundle AP option
    Case(bundle.self_calibrating_bundle_adjustment, _ARGS, dict(_KW, calibrate=(), additional_parameters="hanzl17"),
         raises=InputError, match="ap_base", why="Ebner without b"),
    Case(bundle.self_calibrating_bundle_adjustment, _ARGS, dict(_KW, additional_parameters="hanzl17", ap_base=40.0,
                                                                 ap_names=("g1", "g1")),
         raises=InputError, match="ap_names", why="duplicate names"),
    Case(bundle.self_calibrating_bundle_adjustment, _ARGS, dict(_KW, additional_parameters="hanzl17", ap_base=40.0,
                                                                 ap_names=("k1",)),
         raises=InputError, match="ap_names", why="an IO name as AP"),
    Case(bundle.self_calibrating_bundle_adjustment, _ARGS, dict(_KW, ap_base=40.0), raises=InputError,
         match="additional_parameters", why="ap_base without a model"),
    Case(bundle.self_calibrating_bundle_adjustment, _ARGS, dict(_KW, calibrate=(), additional_parameters="nonsense"),
         raises=InputError, match="unknown", why="unknown model"),
    Case(bundle.self_calibrating_bundle_adjustment, _ARGS, dict(_KW, calibrate=()), raises=InputError,
         why="nothing to calibrate"),
    Case(bundle.additional_parameter_tests, (None,), raises=InputError, why="not a result"),
    Case(bundle.additional_parameter_tests, (_small_result(False),), raises=InputError,
         match="additional_parameters", why="result without APs"),
    Case(bundle.additional_parameter_tests, (_small_result(),), {"alpha": 1.5}, raises=InputError, why="alpha > 1"),
    Case(bundle.select_additional_parameters, _ARGS, dict(_KW, calibrate=(), additional_parameters="hanzl17"),
         raises=InputError, match="ap_base", why="Ebner without b"),
    Case(bundle.select_additional_parameters, _ARGS, dict(_KW, calibrate=(), additional_parameters="hanzl17",
                                                           ap_base=40.0, ap_names=()),
         raises=InputError, match="ap_names", why="no candidates"),
    Case(bundle.APTestReport, (("g1",), np.array([0.1]), np.array([1.0]), np.array([0.1]), 1.96, np.array([False]), []),
         raises=None, why="plain record", check=lambda r: r.insignificant() == ("g1",)),
    # rules
    Case(tl.at_accuracy_rule, (0.0, 1500.0), raises=InputError, why="m_s = 0"),
    Case(tl.at_accuracy_rule, (10000.0, NAN), raises=InputError, why="NaN height"),
    Case(tl.at_accuracy_rule, (10000.0, 1500.0), {"image_sigma_um": -5.0}, raises=InputError, why="negative µm"),
    Case(tl.gnss_at_accuracy, (10000.0, 0.0), raises=InputError, why="σ₀ = 0"),
    Case(tl.gnss_at_accuracy, ("ten thousand", 5.0), raises=InputError, why="text scale"),
    Case(terrestrial.close_range_point_sigma, (0.7, 0.005, 400.0, 0.5), raises=InputError, match="k", why="k < 1"),
    Case(terrestrial.close_range_point_sigma, (-0.7, 0.005, 400.0), raises=InputError, why="negative q"),
    Case(terrestrial.close_range_point_sigma, (0.7, INF, 400.0), raises=InputError, why="inf σ_x"),
    Case(terrestrial.relative_redundancy, ([],), raises=InputError, why="empty"),
    Case(terrestrial.relative_redundancy, ([0.5, 1.5],), raises=InputError, why="r_i > 1"),
    Case(terrestrial.relative_redundancy, ("0.5",), raises=InputError, why="text"),
    Case(terrestrial.relative_redundancy, ([[0.2, 0.4], [0.6, 0.8]],), raises=None, why="2-D array is flattened",
         check=lambda r: np.isclose(r, 0.5)),
    # sympy forms (no input)
    Case(D.hanzl17_symbolic, (), raises=None, why="no input", check=lambda t: len(t[2]) == 17),
    Case(D.brown18_symbolic, (), raises=None, why="no input", check=lambda t: len(t[2]) == 18),
    Case(D.murai_symbolic, (), raises=None, why="no input", check=lambda t: len(t[2]) == 8),
    Case(D.ebner_gram, (), raises=None, why="no input", check=lambda G: G.is_diagonal()),
    Case(D.eo_effects_symbolic, (), raises=None, why="no input", check=lambda e: len(e) == 6),
    Case(D.ebner_eo_products, (), raises=None, why="no input", check=lambda M: M.is_zero_matrix),
]


@pytest.mark.parametrize("case", CASES, ids=lambda c: c.id)
def test_bad_input(case):
    check_case(case)
