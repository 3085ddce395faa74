"""Bad-input catalogue for photolib.terrestrial (Chapter 11, §11.4–11.9)."""

import numpy as np
import pytest

from catalogue import INF, NAN, Case, check_case
from photolib import terrestrial as ter
from photolib.derivations import terrestrial as dt
from photolib.camera import ExteriorOrientation, InteriorOrientation
from photolib.errors import DegenerateGeometryError, InputError, PointBehindCameraError

IO = InteriorOrientation(50.0)
E1, E2 = ter.case_orientations("normal", 2.0)
F = np.eye(3)
P4 = np.array([[0.0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1], [1, 1, 1]])
MARKS = np.array([[0.0, 0, 0], [0.1, 0, 0], [0, 0.1, 0]])

CASES = [
    # §11.4–11.5
    Case(ter.base_system, ([0, 0, 0], [0, 0, 5]), raises=DegenerateGeometryError, why="vertical base"),
    Case(ter.base_system, ([0, 0, NAN], [1, 0, 0]), raises=InputError, why="NaN centre"),
    Case(ter.base_system, ([0, 0], [1, 0, 0]), raises=InputError, why="2-vector"),
    Case(ter.BaseSystem(np.zeros(3), np.eye(3)).to_base, ([[1.0, 2.0]],), raises=InputError, why="2-D points"),
    Case(ter.BaseSystem, (np.zeros(3), np.eye(3)), raises=None, why="identity system",
         check=lambda s: np.allclose(s.to_object([[1.0, 2, 3]]), [[1, 2, 3]])),
    Case(ter.case_rotation, ("oblique",), raises=InputError, why="unknown case"),
    Case(ter.case_rotation, ("normal", 3), raises=InputError, why="image 3"),
    Case(ter.case_rotation, ("convergent",), {"convergence": 4.0}, raises=InputError, why="γ ≥ π"),
    Case(ter.case_rotation, ("tilted",), {"tilt": NAN}, raises=InputError, why="NaN tilt"),
    Case(ter.case_orientations, ("normal", 0.0), raises=InputError, why="zero base"),
    Case(ter.case_orientations, ("normal", -1.0), raises=InputError, why="negative base"),
    # §11.8
    Case(ter.normal_case_point, (1.0, 1.0, 1.0, 50.0, 2.0), raises=DegenerateGeometryError, why="zero parallax"),
    Case(ter.normal_case_point, (NAN, 1.0, 0.0, 50.0, 2.0), raises=InputError, why="NaN coordinate"),
    Case(ter.normal_case_point, (1.0, 1.0, 0.0, 0.0, 2.0), raises=InputError, why="f = 0"),
    Case(ter.base_intersection, ([[1.0, 1.0]], [[1.0, 1.0]], E1, E2, IO), raises=DegenerateGeometryError,
         why="parallel rays"),
    Case(ter.base_intersection, ([[1.0, 1.0]], [[1.0, 1.0], [2, 2]], E1, E2, IO), raises=InputError,
         why="mismatched sizes"),
    Case(ter.base_intersection, ([[-1.0, 1.0]], [[1.0, 1.0]], E1, E2, IO), raises=PointBehindCameraError,
         why="rays meet behind the cameras"),
    Case(ter.base_intersection, ([[1.0, 1.0]], [[0.0, 1.0]], E1, E2, "camera"), raises=InputError, why="io not a camera"),
    Case(ter.normal_case_accuracy, (0.0, 100.0, 40.0, 0.5, 0.5, 0.5), raises=InputError, why="Y = 0"),
    Case(ter.normal_case_accuracy, (30.0, 100.0, INF, 0.5, 0.5, 0.5), raises=InputError, why="inf base"),
    Case(ter.normal_case_accuracy, (30.0, 100.0, 40.0, 0.5, 0.5, 0.5), {"tilt": 2.0}, raises=InputError,
         why="tilt beyond 90°"),
    Case(ter.normal_case_monte_carlo, (30.0, 100.0, 2.0), {"n": 1}, raises=InputError, why="one draw"),
    Case(ter.normal_case_monte_carlo, (30.0, 100.0, 0.0), raises=InputError, why="zero base"),
    Case(ter.normal_case_monte_carlo, (30.0, 100.0, 2.0), {"m_x": NAN}, raises=InputError, why="NaN sigma"),
    Case(ter.stereo_design, (17400.0, (11600, 8700), 30.0), {"overlap": 100.0}, raises=InputError, why="overlap 100 %"),
    Case(ter.stereo_design, (17400.0, (11600,), 30.0), raises=InputError, why="one frame side"),
    Case(ter.stereo_design, (17400.0, (11600, 8700), 30.0), {"orientation": "diagonal"}, raises=InputError,
         why="unknown frame orientation"),
    Case(ter.stereo_design, (17400.0, (11600, 8700), NAN), raises=InputError, why="NaN distance"),
    Case(ter.StereoDesign, (1.0, 1, 1, 1, 1, 1, 1, 1, 1), raises=None, why="plain record", check=lambda d: d.b == 1.0),
    # §11.6
    Case(ter.condition_equations, ("parallel", [P4[:1], P4[1:2]]), raises=InputError, why="unknown condition"),
    Case(ter.condition_equations, ("distance", [P4[:1], P4[1:2]]), raises=InputError, why="no measured distance"),
    Case(ter.condition_equations, ("distance", [P4[:1], P4[:1]], [1.0]), raises=DegenerateGeometryError,
         why="coincident points"),
    Case(ter.condition_equations, ("coplanar", [P4[:1], P4[1:2]]), raises=InputError, why="two points for coplanarity"),
    Case(ter.condition_equations, ("vertical", [P4[:1], P4[1:3]]), raises=InputError, why="mismatched sizes"),
    Case(ter.condition_equations, ("horizontal", [P4[:1], P4[1:2]], [1.0]), raises=InputError,
         why="surplus measured values"),
    Case(ter.condition_equations, ("base", [[[NAN, 0, 0]], P4[1:2]], [1.0]), raises=InputError, why="NaN centre"),
    Case(ter.polar_project, ([NAN], [0.0], np.pi / 2, 0, 0, IO), raises=InputError, why="NaN bearing"),
    Case(ter.polar_project, ([0.0, 1.0], [0.0, 0.0, 0.0], np.pi / 2, 0, 0, IO), raises=InputError,
         why="mismatched sizes"),
    Case(ter.polar_project, ([np.pi], [0.0], np.pi / 2, 0, 0, IO), raises=PointBehindCameraError,
         why="direction behind the camera"),
    Case(ter.orientation_from_directions, ([[0.0, 0.0]], [0.0], [0.0], IO), raises=DegenerateGeometryError,
         why="one direction"),
    Case(ter.orientation_from_directions, ([[0.0, 0.0], [1, 1]], [0.1, 0.1], [0.0, 0.0], IO),
         raises=DegenerateGeometryError, why="two identical directions"),
    Case(ter.orientation_from_directions, ([[0.0, 0.0], [1, 1]], [0.1], [0.0], IO), raises=InputError,
         why="fewer directions than points"),
    # §11.7
    Case(ter.link_models_linear, (P4[:3], P4[:3]), raises=DegenerateGeometryError, why="three points"),
    Case(ter.link_models_linear, (P4 * [1, 1, 0], P4 * [1, 1, 0]), raises=DegenerateGeometryError, why="coplanar points"),
    Case(ter.link_models_linear, (P4, P4[:4]), raises=InputError, why="mismatched sizes"),
    Case(ter.link_models_linear, (P4, P4), {"common": 7}, raises=InputError, why="common index out of range"),
    Case(ter.link_models_linear, (np.where(P4 == 1, NAN, P4), P4), raises=InputError, why="NaN"),
    Case(ter.link_models_svd, (P4[:2], P4[:2]), raises=DegenerateGeometryError, why="two points"),
    Case(ter.link_models_svd, (P4[:3] * 0 + [[0, 0, 0], [1, 1, 1], [2, 2, 2]], P4[:3] * 0 + [[0, 0, 0], [1, 1, 1], [2, 2, 2]]),
         raises=DegenerateGeometryError, why="collinear points"),
    Case(ter.ModelLink(np.zeros(3), np.eye(3), 1.0).apply, ([1.0, 2.0],), raises=InputError, why="2-vector"),
    Case(ter.ModelLink, (np.zeros(3), np.eye(3), 1.0), raises=None, why="identity link",
         check=lambda L: np.allclose(L.apply([[1.0, 2, 3]]), [[1, 2, 3]])),
    Case(ter.chain_rotation, (np.eye(2), np.eye(3), np.eye(3)), raises=InputError, why="2×2 matrix"),
    Case(ter.chain_rotation, (np.full((3, 3), NAN), np.eye(3), np.eye(3)), raises=InputError, why="NaN matrix"),
    Case(ter.centre_in_object, ([0, 0, 0], np.eye(3), [[1.0, 0, 0]], 0.0), raises=InputError, why="zero scale"),
    Case(ter.centre_in_object, ([0, 0, 0], np.eye(3), [[1.0, 0]], 1.0), raises=InputError, why="2-D centre"),
    # §11.9
    Case(ter.match_three_views, (P4[:, :2], P4[:, :2], P4[:, :2], F, F, F, 0.0), raises=InputError, why="zero threshold"),
    Case(ter.match_three_views, (P4[:, :2], P4[:, :2], P4[:, :2], np.eye(2), F, F, 0.1), raises=InputError,
         why="2×2 fundamental matrix"),
    Case(ter.match_three_views, ([[NAN, 0.0]], P4[:, :2], P4[:, :2], F, F, F, 0.1), raises=InputError, why="NaN point"),
    Case(ter.probe_tip, ([MARKS[:, :2], MARKS[:, :2]], [E1, E2], IO, MARKS[:2], [0, 0, 0]),
         raises=DegenerateGeometryError, why="two marks"),
    Case(ter.probe_tip, ([MARKS[:, :2]], [E1], IO, MARKS, [0, 0, 0]), raises=InputError, why="one image"),
    Case(ter.probe_tip, ([MARKS[:2, :2], MARKS[:, :2]], [E1, E2], IO, MARKS, [0, 0, 0]), raises=InputError,
         why="a mark missing on one image"),
    Case(ter.probe_tip, ([MARKS[:, :2], MARKS[:, :2]], [E1, E2], IO, MARKS, [0, 0]), raises=InputError,
         why="2-D tip"),
    # photolib.derivations.terrestrial (sympy models; only the labels and flags can be bad)
    Case(dt.point_symbols, (3,), raises=InputError, why="a number as label"),
    Case(dt.point_symbols, ("",), raises=InputError, why="empty label"),
    Case(dt.polar_collinearity_model, ("yes",), raises=InputError, why="flag not a bool"),
    Case(dt.distance_condition_model, (), raises=None, why="no input", check=lambda m: len(m.parameters) == 6),
    Case(dt.base_condition_model, (), raises=None, why="no input", check=lambda m: len(m.parameters) == 6),
    Case(dt.centre_distance_model, (), raises=None, why="no input", check=lambda m: len(m.parameters) == 6),
    Case(dt.vertical_line_model, (), raises=None, why="no input", check=lambda m: len(m.residuals) == 2),
    Case(dt.horizontal_plane_model, (), raises=None, why="no input", check=lambda m: len(m.residuals) == 1),
    Case(dt.coplanarity4_model, (), raises=None, why="no input", check=lambda m: len(m.parameters) == 12),
    Case(dt.book_plane_determinant, (), raises=None, why="no input: the printed (11.6.6) is 0", check=lambda e: e == 0),
    Case(dt.normal_case_relations, (), raises=None, why="no input", check=lambda r: "N_normal" in r),
    Case(dt.linking_scale_symbolic, (), raises=None, why="no input", check=lambda e: str(e) == "t"),
]


@pytest.mark.parametrize("case", CASES, ids=lambda c: c.id)
def test_bad_input(case):
    check_case(case)


def test_constants():
    assert ter.CASES == ("normal", "deviated", "tilted", "convergent")
    assert isinstance(ExteriorOrientation, type)
