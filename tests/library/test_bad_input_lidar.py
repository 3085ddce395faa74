"""Bad-input catalogue for photolib.lidar and photolib.derivations.lidar (Chapter 9 geometry)."""

import numpy as np
import pytest

from catalogue import INF, NAN, Case, check_case
from photolib import lidar
from photolib.camera import ExteriorOrientation, InteriorOrientation
from photolib.derivations import lidar as dlidar
from photolib.errors import DegenerateGeometryError, InputError, PointBehindCameraError

IO, EO = InteriorOrientation(50.0), ExteriorOrientation(0, 0, 10.0)
SCENE = lidar.simulate_laser_line_scanner(seed=4, n_marks=5, n_trace=5)
S_ARGS = (SCENE.marks_xyz, SCENE.marks_xy, SCENE.marks_plate, SCENE.trace_xy, SCENE.trace_label, SCENE.io)
PF = lidar.fit_plane([[0, 0, 0.0], [1, 0, 0], [0, 1, 0], [1, 1, 0.01]])
TARGETS = np.array([[5.0, 0, 0], [0, 5, 0], [0, 0, 5], [3, 3, 1]])

CASES = [
    Case(lidar.als_scanner_vector, (NAN, 0.1), raises=InputError, why="NaN range"),
    Case(lidar.als_scanner_vector, (-5.0, 0.1), raises=InputError, why="negative range"),
    Case(lidar.als_scanner_vector, ([1.0, 2.0], [0.1, 0.2, 0.3]), raises=InputError, why="sizes do not broadcast"),
    Case(lidar.als_georeference, (100.0, 0.0, [0, 0, 100.0], np.ones((3, 3))), raises=InputError,
         why="A not a rotation"),
    Case(lidar.als_georeference, ([100.0] * 3, [0.0] * 3, np.zeros((2, 3)), np.eye(3)), raises=InputError,
         why="2 positions for 3 pulses"),
    Case(lidar.swath_width, (1000.0, 2 * np.pi), raises=InputError, match="fov", why="360° scanner"),
    Case(lidar.swath_width, (-1.0, 0.5), raises=InputError, why="negative height"),
    Case(lidar.footprint_diameter, (1000.0, 0.0), raises=InputError, why="zero divergence"),
    Case(lidar.footprint_diameter, (1000.0, 250.0), raises=InputError, why="divergence in degrees/mrad"),
    Case(lidar.pulse_range, (-1e-6,), raises=InputError, why="negative time"),
    Case(lidar.pulse_range, (1e-6, 0.0), raises=InputError, why="zero speed"),
    Case(lidar.phase_range, (2.5, 1.0, 10.0), raises=InputError, why="non-integer K"),
    Case(lidar.phase_range, (2, 7.0, 10.0), raises=InputError, why="phase ≥ 2π"),
    Case(lidar.phase_range, (2, 1.0, INF), raises=InputError, why="inf wavelength"),
    Case(lidar.return_masks, ([1, 2], [1, 1]), raises=InputError, why="return number above number of returns"),
    Case(lidar.return_masks, ([1, 2], [2]), raises=InputError, why="mismatched lengths"),
    Case(lidar.polar_to_xyz, (10.0, NAN, 0.0), raises=InputError, why="NaN angle"),
    Case(lidar.xyz_to_polar, ([[0, 0, 0.0]],), raises=InputError, match="origin", why="point at the origin"),
    Case(lidar.xyz_to_polar, (np.zeros((3, 2)),), raises=InputError, why="two columns"),
    Case(lidar.triangulation_depth, (-5.0, 10.0, 100.0, 0.0), raises=DegenerateGeometryError,
         why="rays do not meet in front"),
    Case(lidar.triangulation_depth, (1.0, 10.0, 100.0, 2.0), raises=InputError, why="alpha ≥ π/2"),
    Case(lidar.triangulation_depth, (1.0, 0.0, 100.0, 0.1), raises=InputError, why="zero focal length"),
    Case(lidar.triangulation_sigma, (100.0, 10.0, 0.0, 0.001), raises=InputError, why="zero base"),
    Case(lidar.triangulation_sigma, (100.0, 10.0, 1.0, -0.001), raises=InputError, why="negative sigma"),
    Case(lidar.image_rays, ([[0.0, 0.0]], "eo", IO), raises=InputError, why="eo not an ExteriorOrientation"),
    Case(lidar.image_rays, ([[NAN, 0.0]], EO, IO), raises=InputError, why="NaN image point"),
    Case(lidar.intersect_ray_plane, ([[0.0, 0.0]], EO, IO, [0, 0, 0, 1.0]), raises=InputError, why="zero normal"),
    Case(lidar.intersect_ray_plane, ([[0.0, 0.0]], EO, IO, [1.0, 0, 0, 1.0]), raises=DegenerateGeometryError,
         why="ray parallel to the plane"),
    Case(lidar.intersect_ray_plane, ([[0.0, 0.0]], EO, IO, [0, 0, 1.0, -20.0]), raises=PointBehindCameraError,
         why="plane behind the camera"),
    Case(lidar.fit_plane, ([[0, 0, 0.0], [1, 1, 1]],), raises=InputError, why="two points"),
    Case(lidar.fit_plane, ([[0, 0, 0.0], [1, 1, 1], [2, 2, 2]],), raises=DegenerateGeometryError,
         why="collinear points"),
    Case(lidar.fit_plane, ([[0, 0, 0.0], [1, 0, 0], [0, 1, NAN]],), raises=InputError, why="NaN point"),
    Case(lidar.fit_plane, ([[0, 0, 0.0], [1, 0, 0], [0, 1, 0], [1, 1, 0]], [1.0, 1.0]), raises=InputError,
         why="weights of another length"),
    Case(lidar.PlaneFit, (PF.plane, PF.rms, PF.sigma_angles, PF.adjustment), raises=None,
         check=lambda p: abs(p.normal[2]) > 0.99, why="a result container"),
    Case(PF.distance, ([[0, 0]],), raises=InputError, why="two coordinates"),
    Case(lidar.colour_points, ([[0, 0, 0.0]], np.zeros((1, 1)), EO, IO, 0.01), raises=InputError,
         why="1×1 image"),
    Case(lidar.colour_points, ([[0, 0, 0.0]], np.zeros((5, 5)), EO, IO, 0.0), raises=InputError,
         why="zero pixel size"),
    Case(lidar.colour_points, ([[0, 0, 20.0]], np.zeros((5, 5)), EO, IO, 0.01), raises=PointBehindCameraError,
         why="point behind the camera"),
    Case(lidar.colour_points, ([[100, 0, 0.0]], np.ones((5, 5)), EO, IO, 0.01), raises=None,
         check=lambda r: np.isnan(r[0][0]) and not r[1][0], why="outside the image → NaN, flagged"),
    Case(lidar.simulate_laser_line_scanner, (), {"n_marks": 2}, raises=InputError, why="too few marks"),
    Case(lidar.simulate_laser_line_scanner, (), {"sigma_xy": -1.0}, raises=InputError, why="negative noise"),
    Case(lidar.simulate_laser_line_scanner, (), {"laser_tilt": 0.0}, raises=InputError, why="horizontal laser"),
    Case(lidar.LaserLineScene, tuple(SCENE.__dict__.values()), raises=None, check=lambda s: s.sigma_xy >= 0,
         why="a result container"),
    Case(lidar.laser_line_scan, (SCENE.marks_xyz[:-1],) + S_ARGS[1:], raises=InputError, why="mismatched marks"),
    Case(lidar.laser_line_scan, S_ARGS[:4] + (np.full(len(SCENE.trace_label), 7),) + S_ARGS[5:], raises=InputError,
         why="unknown trace label"),
    Case(lidar.laser_line_scan, S_ARGS[:3] + (SCENE.trace_xy[SCENE.trace_label == 0],
                                              SCENE.trace_label[SCENE.trace_label == 0], SCENE.io),
         raises=InputError, match="plates", why="no trace on the plates"),
    Case(lidar.laser_line_scan, S_ARGS, {"image": SCENE.image}, raises=InputError, why="image without pixel size"),
    Case(lidar.LaserLineResult, (EO, (PF, PF), np.zeros((0, 3)), PF, np.zeros((0, 3)), None, None), raises=None,
         check=lambda r: r.colours is None, why="a result container"),
    Case(lidar.scanner_camera_pose, (NAN, 0.0, [0, 0, 0], 0.1), raises=InputError, why="NaN angle"),
    Case(lidar.scanner_camera_pose, (0.0, 0.0, [0, 0], 0.1), raises=InputError, why="2-vector centre"),
    Case(lidar.scanner_camera_pose, (0.0, 0.0, [0, 0, 0], -0.1), raises=InputError, why="negative offset"),
    Case(lidar.scanner_camera_project, ([[0, -5, 0.0]], [0, 0, 0], lidar.scanner_camera_pose(0, 0, [0, 0, 0], 0)[1],
                                        10.0), raises=PointBehindCameraError, why="point behind"),
    Case(lidar.scanner_camera_project, ([[0, 5, 0.0]], [0, 0, 0], np.ones((3, 3)), 10.0), raises=InputError,
         why="A not a rotation"),
    Case(lidar.mobile_georeference, ([[1.0, 0, 0]], [[0, 0, 0.0]], np.eye(3), [0, 0], np.eye(3)), raises=InputError,
         why="2-vector lever arm"),
    Case(lidar.mobile_georeference, ([[NAN, 0, 0]], [[0, 0, 0.0]], np.eye(3), [0, 0, 0], np.eye(3)),
         raises=InputError, why="NaN point"),
    Case(lidar.calibrate_mobile_system, (TARGETS[:2], np.zeros((2, 3)), np.eye(3), TARGETS[:2]), raises=InputError,
         why="two targets"),
    Case(lidar.calibrate_mobile_system, (TARGETS, np.zeros((3, 3)), np.eye(3), TARGETS), raises=InputError,
         why="mismatched counts"),
    Case(lidar.calibrate_mobile_system, ([[1.0, 0, 0], [2, 0, 0], [3, 0, 0]], np.zeros((3, 3)), np.eye(3),
                                         [[1.0, 0, 0], [2, 0, 0], [3, 0, 0]]),
         raises=DegenerateGeometryError, match="collinear", why="collinear targets, one pose"),
    Case(lidar.calibrate_mobile_system, (TARGETS, np.zeros((4, 3)), np.eye(3), TARGETS), {"sigma_target": 0.0},
         raises=InputError, why="zero sigma"),
    Case(lidar.MobileCalibration, (np.zeros(3), np.zeros(3), np.eye(3), np.zeros(6), None), raises=None,
         check=lambda c: c.lever.shape == (3,), why="a result container"),
    Case(lidar.tls_max_range, (0.005, 5.0), raises=InputError, why="angular accuracy in degrees"),
    Case(lidar.tls_max_range, (0.0, 1e-4), raises=InputError, why="zero accuracy"),
    Case(lidar.tls_angular_step, (0.01, 0.0), raises=InputError, why="zero range"),
    Case(lidar.tls_angular_step, (NAN, 10.0), raises=InputError, why="NaN detail"),
    # the sympy models take no input: they must build
    Case(dlidar.triangulation_depth_model, (), raises=None, check=lambda m: "Z" in m, why="no input"),
    Case(dlidar.ray_plane_model, (), raises=None, check=lambda m: "N" in m, why="no input"),
    Case(dlidar.plane_model, (), raises=None, check=lambda m: m["jacobian"].shape == (1, 3), why="no input"),
    Case(dlidar.plane_functions, (), raises=None, check=lambda f: len(f) == 2, why="no input"),
    Case(dlidar.mobile_mapping_model, (), raises=None, check=lambda m: m["jacobian"].shape == (3, 6), why="no input"),
    Case(dlidar.mobile_mapping_functions, (), raises=None, check=lambda f: len(f) == 2, why="no input"),
    Case(dlidar.scanner_camera_rotation, (), raises=None, check=lambda m: m["A"].shape == (3, 3), why="no input"),
]


@pytest.mark.parametrize("case", CASES, ids=lambda c: c.id)
def test_bad_input(case):
    check_case(case)
