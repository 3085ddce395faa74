"""Bad-input catalogue of photolib.derivations: unknown orders and systems, wrong symbols and types.

Functions without input are listed with a success case whose result is checked independently.
"""

import pytest
import sympy as sp

from catalogue import Case, check_case
from photolib import derivations as D
from photolib.errors import InputError

_a, _t = sp.symbols("a t")


def _is_matrix(shape):
    return lambda r: isinstance(r, sp.MatrixBase) and r.shape == shape


def _keys(keys):
    return lambda r: isinstance(r, dict) and set(r) == set(keys)


ORDER_FUNCTIONS = [D.rotation_matrix_symbolic, D.collinearity_terms, D.collinearity_model, D.derived_resection_partials,
                   D.coplanarity_expression, D.intersection_model, D.similarity_model, D.derived_similarity_partials,
                   D.bundle_collinearity_model, D.self_calibration_model, D.rig_collinearity_model, D.printed_rig_3_8_13,
                   D.derived_rig_image_coordinates, D.rolling_shutter_model]

CASES = [Case(fn, ("xyz",), raises=InputError, match="order", why="unknown rotation order") for fn in ORDER_FUNCTIONS]
CASES += [Case(fn, (5,), raises=InputError, match="order", why="order not a string") for fn in ORDER_FUNCTIONS]
CASES += [
    Case(D.elementary_rotations, ("not an angle!",), raises=InputError, why="angle not an expression"),
    Case(D.quaternion_rotation_symbolic, ("a+",), raises=InputError, why="component not an expression"),
    Case(D.quaternion_rotation_symbolic, (0, 0, 0, 1), raises=None,
         check=lambda r: r == sp.eye(3), why="the unit quaternion gives E"),
    Case(D.brown_correction_terms, ([1, 2], 0), raises=InputError, why="coordinate is a list"),
    Case(D.coplanarity_model, ("mixed",), raises=InputError, match="system", why="unknown system"),
    Case(D.coplanarity_model, ("dependent", "kwa"), raises=InputError, match="order", why="unknown order"),
    Case(D.coplanarity_all_parameters_model, ("kwa",), raises=InputError, match="order", why="unknown order"),
    Case(D.coplanarity_all_parameters_model, (None,), raises=InputError, why="order None"),
    Case(D.printed_coplanarity_partials, ("mixed",), raises=InputError, match="system", why="unknown system"),
    Case(D.printed_coplanarity_jacobian, ("mixed",), raises=InputError, match="system", why="unknown system"),
    Case(D.printed_ray_partials, (3,), raises=InputError, match="image", why="no image 3"),
    Case(D.printed_ray_partials, (True,), raises=InputError, match="image", why="a bool for the image"),
    Case(D.derived_relative_orientation_partials, ("kaw", 0), raises=InputError, match="z_sign", why="z_sign 0"),
    Case(D.derived_relative_orientation_partials, ("abc",), raises=InputError, match="order", why="unknown order"),
    Case(D.printed_similarity_jacobian, ("yes",), raises=InputError, match="zero_a5", why="zero_a5 not a bool"),
    Case(D.gnss_rotation_symbolic, ("a+",), raises=InputError, why="angle not an expression"),
    Case(D.printed_gnss_direction_cosines, (None,), raises=InputError, why="angle None"),
    Case(D.printed_gnss_vector_partials, ("x+",), raises=InputError, why="coordinate not an expression"),
    Case(D.derived_gnss_vector_partials, (D.x, "y+"), raises=InputError, why="coordinate not an expression"),
    Case(D.corrected_gnss_vector_partials, ([1],), raises=InputError, why="coordinate is a list"),
    Case(D.printed_gnss_coplanarity_coefficients, ({"A": 1},), raises=InputError, match="A, B, C",
         why="A1 lacks B…F"),
    Case(D.printed_gnss_ground_coefficients, ([1, 2],), raises=InputError, match="partials", why="not a dict"),
    # the model core
    Case(D.Model, ("m", (_a,), (_t,), ()), raises=InputError, why="no residuals"),
    Case(D.Model, ("m", ("a",), (_t,), (_a * _t,)), raises=InputError, match="symbol", why="parameter a string"),
    Case(D.Model, ("m", (_a,), (_a,), (_a,)), raises=InputError, match="twice", why="symbol twice"),
    Case(D.Model, ("m", (_a,), (_t,), ("a*t",)), raises=InputError, match="expression", why="residual a string"),
    Case(D.Model, ("m", _a, (_t,), (_a,)), raises=InputError, match="tuple", why="parameters not a tuple"),
    Case(D.numpy_source, ("collinearity",), raises=InputError, match="Model", why="not a Model"),
    Case(D.numpy_source, (D.homography_model(), "not valid"), raises=InputError, match="identifier",
         why="function name not an identifier"),
    Case(D.compile_fused, ("collinearity",), raises=InputError, match="Model", why="not a Model"),
    # functions without input: checked results (independent of the code under test)
    Case(D.book_rotation_elements_kaw, raises=None, check=_is_matrix((3, 3)), why="no input"),
    Case(D.book_rotation_elements_wak, raises=None,
         check=lambda r: r[0, 2] == sp.sin(D.alpha) and r[2, 2] == sp.cos(D.omega) * sp.cos(D.alpha), why="no input"),
    Case(D.angle_equality_model, raises=None, check=lambda m: m.parameters == (D.Xs, D.Ys, D.Zs), why="no input"),
    Case(D.printed_angle_equality_partials, raises=None, check=_keys({"a1", "b1", "c1"}), why="no input"),
    Case(D.printed_resection_partials, raises=None, check=_keys(D.RESECTION_COEFFICIENTS), why="no input"),
    Case(D.printed_resection_jacobian, raises=None, check=callable, why="no input"),
    Case(D.distortion_model, raises=None, check=lambda m: m.parameters == (D.x, D.y), why="no input"),
    Case(D.printed_brown_3_6_2, raises=None, check=lambda r: len(r) == 2, why="no input"),
    Case(D.printed_relative_orientation_partials, raises=None,
         check=lambda r: len(r) == 9 and r[("Z", "kappa")] == 0, why="no input"),
    Case(D.printed_similarity_partials, raises=None,
         check=lambda r: r["a1"] == -1 and r["b2"] == -1 and r["a4"] == 0, why="no input"),
    Case(D.homography_model, raises=None, check=lambda m: len(m.parameters) == 8, why="no input"),
    Case(D.gnss_coplanarity_model, raises=None, check=lambda m: m.parameters == D.GNSS_ANGLES, why="no input"),
    Case(D.gnss_collinearity_model, raises=None, check=lambda m: len(m.residuals) == 2, why="no input"),
    Case(D.printed_gnss_cosine_partials, raises=None,
         check=lambda r: r[("b3", "omega")] == -sp.cos(D.omega), why="no input"),
    Case(D.derived_gnss_cosine_partials, raises=None, check=lambda r: len(r) == 27, why="no input"),
    Case(D.derived_gnss_coplanarity_coefficients, raises=None, check=_keys(D.GNSS_COEFFICIENTS), why="no input"),
    Case(D.derived_gnss_ground_coefficients, raises=None, check=_keys(D.GNSS_GROUND_COEFFICIENTS), why="no input"),
    Case(D.printed_gnss_jacobians, raises=None, check=lambda r: len(r) == 2 and all(map(callable, r)),
         why="no input"),
    Case(D.printed_gnss_intersection_scale, raises=None, check=lambda r: len(r[0]) == 3, why="no input"),
    Case(D.corrected_gnss_coplanarity_coefficients, raises=None, check=_keys(D.GNSS_COEFFICIENTS), why="no input"),
    Case(D.corrected_gnss_ground_coefficients, raises=None, check=_keys(D.GNSS_GROUND_COEFFICIENTS),
         why="no input"),
]


@pytest.mark.parametrize("case", CASES, ids=lambda c: c.id)
def test_bad_input(case):
    check_case(case)
