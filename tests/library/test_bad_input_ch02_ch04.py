"""Bad-input catalogue for Chapter 2 (image_pair), Chapter 4 (projective) and the GNSS appendix
(gnss_centres): every public callable, given NaN, inf, wrong shapes or types, too few points,
degenerate geometry (collinear, coplanar, parallel rays, zero base) or points behind a camera,
raises a named photolib error — or, for a tricky but valid input, returns the right result."""

import numpy as np
import pytest

from catalogue import INF, NAN, Case, check_case, finite
from photolib import gnss_centres as G
from photolib import image_pair as ip
from photolib import projective as pj
from photolib.camera import ExteriorOrientation, InteriorOrientation
from photolib.errors import DegenerateGeometryError, InputError, PointBehindCameraError
from photolib.synthetic import StereoPair, stereo_pair

IO = InteriorOrientation(100.0)
PAIR = stereo_pair(12, seed=3, centres=((0.0, 0.0, 1000.0), (400.0, 5.0, 1003.0)), angle_spread_deg=2.0)
XY1, XY2, EO1, EO2, XYZ = PAIR.xy1, PAIR.xy2, PAIR.eo1, PAIR.eo2, PAIR.points
NANXY = XY1.copy()
NANXY[2, 0] = NAN
INFXY = XY1.copy()
INFXY[0, 1] = INF
LINE = np.column_stack([np.linspace(-50, 50, 12), np.linspace(-30, 30, 12)])
SAME = np.tile([[1.0, 2.0]], (12, 1))
R1 = ip.image_rays(XY1, EO1, IO)
R2 = ip.image_rays(XY2, EO2, IO)
E = pj.essential_from_orientation(EO1, EO2)
F = pj.fundamental_from_orientation(IO, EO1, IO, EO2)
L1, L2 = pj.dlt_from_orientation(IO, EO1), pj.dlt_from_orientation(IO, EO2)
RO = ip.relative_orientation(XY1, XY2, IO)
MODEL = ip.build_model(XY1, XY2, RO, IO, base_length=400.0)
T = ip.absolute_orientation(MODEL.points[:5], XYZ[:5])
# the same scene seen by camera 2 flipped to look upwards: every point is behind it
EO2_UP = ExteriorOrientation(*EO2.center, np.pi, 0.0, 0.0)
# a plane (facade) for homographies
SRC = np.array([[0, 0], [10, 0], [10, 8], [0, 8], [5, 3], [2, 6]], float)
H_TRUE = np.array([[1.1, 0.1, 3.0], [-0.05, 0.9, 1.0], [0.001, 0.002, 1.0]])
DST = pj.apply_homography(H_TRUE, SRC)
# GNSS pair
GP = G.synthetic_pair(30.0, seed=3)
GA = GP.angles
CTRL = GP.control_args

ZERO_BASE = stereo_pair(12, seed=3, centres=((0.0, 0.0, 1000.0), (0.0, 0.0, 1000.0)), angle_spread_deg=2.0)
SHORT_BASE = stereo_pair(12, seed=3, centres=((0.0, 0.0, 1000.0), (0.02, 0.0, 1000.0)), angle_spread_deg=2.0,
                         sigma=0.003)


def _close(expected, atol=1e-6):
    return lambda result: np.allclose(result, expected, atol=atol)


CASES = [
    # --- §2.1 -----------------------------------------------------------------------------------
    Case(ip.convergence_angle, (0.065, NAN), raises=InputError, match="NaN", why="NaN distance"),
    Case(ip.convergence_angle, (0.065, 0.0), raises=InputError, why="zero distance"),
    Case(ip.convergence_angle, ("a", 10.0), raises=InputError, why="a string"),
    Case(ip.depth_change, (0.065, 10.0, INF), raises=InputError, why="inf Δγ"),
    Case(ip.depth_change, (0.0, 10.0, 1e-4), raises=InputError, why="zero eye base"),
    Case(ip.stereo_vision_radius, (NAN,), raises=InputError, why="NaN eye base"),
    Case(ip.stereo_vision_radius, (0.065, 0.0), raises=InputError, why="zero stereo acuity"),
    Case(ip.plasticity_coefficient, (0.065, -1.0), raises=InputError, why="negative instrument base"),
    # --- §2.3 / §2.4 / §2.5 -------------------------------------------------------------------------
    Case(ip.parallaxes, (NANXY, XY2), raises=InputError, match="NaN", why="NaN coordinate"),
    Case(ip.parallaxes, (XY1, XY2[:5]), raises=InputError, why="different point counts"),
    Case(ip.parallaxes, (XY1[:, :1], XY2), raises=InputError, why="one column"),
    Case(ip.image_rays, (XY1, "eo", IO), raises=InputError, match="ExteriorOrientation", why="wrong type of eo"),
    Case(ip.image_rays, (XY1, EO1, None), raises=InputError, why="no interior orientation"),
    Case(ip.image_rays, (INFXY, EO1, IO), raises=InputError, why="inf coordinate"),
    Case(ip.intersection_scale, ([1.0, 0, 0], R1, R1), raises=DegenerateGeometryError, match="parallel",
         why="parallel rays"),
    Case(ip.intersection_scale, ([0.0, 0, 0], R1, R2), raises=DegenerateGeometryError, match="base",
         why="zero base"),
    Case(ip.intersection_scale, ([NAN, 0, 0], R1, R2), raises=InputError, why="NaN base"),
    Case(ip.intersection_scale, ([1.0, 0], R1, R2), raises=InputError, why="2-vector base"),
    Case(ip.intersection_scale, (EO2.center - EO1.center, R1, R2), {"method": "magic"}, raises=InputError,
         why="unknown method"),
    Case(ip.forward_intersection, (XY1, XY2, EO1, EO2, IO), raises=None, check=_close(XYZ, 1e-6),
         why="valid pair: the true points"),
    Case(ip.forward_intersection, (XY1, XY2, EO1, EO2_UP, IO), raises=PointBehindCameraError,
         why="camera 2 looks away: points behind it"),
    Case(ip.forward_intersection, (XY1, XY2, EO2, EO1, IO), raises=PointBehindCameraError,
         why="orientations swapped: rays meet behind"),
    Case(ip.forward_intersection, (XY1, XY2, EO1, EO1, IO), raises=DegenerateGeometryError, match="base",
         why="zero base"),
    Case(ip.forward_intersection, (XY1, XY2, EO1, [1, 2, 3], IO), raises=InputError, why="eo2 not an orientation"),
    Case(ip.intersect_rays, ([XY1, XY2], [EO1, EO2], IO), raises=None,
         check=lambda r: np.allclose(r.points, XYZ, atol=1e-6), why="valid pair"),
    Case(ip.intersect_rays, ([XY1, XY2], [EO1, EO2_UP], IO), raises=PointBehindCameraError,
         why="points behind camera 2"),
    Case(ip.intersect_rays, ([XY1], [EO1], IO), raises=InputError, why="one image"),
    Case(ip.intersect_rays, ([XY1, XY2], [EO1, EO2], IO), {"weights": [1.0, NAN]}, raises=InputError,
         why="NaN weight"),
    Case(ip.intersect_rays, ([XY1, XY2], [EO1, "x"], IO), raises=InputError, why="wrong orientation type"),
    Case(ip.normal_case_intersection, ([10.0], [5.0], [10.0], 100.0, 400.0), raises=DegenerateGeometryError,
         why="zero x-parallax"),
    Case(ip.normal_case_intersection, ([10.0], [NAN], [2.0], 100.0, 400.0), raises=InputError, why="NaN y1"),
    Case(ip.normal_case_intersection, ([10.0, 2.0], [1.0, 1.0, 1.0], [2.0], 100.0, 400.0), raises=InputError,
         why="incompatible shapes"),
    # --- §2.7–§2.8 ----------------------------------------------------------------------------------
    Case(ip.coplanarity, ([1.0, NAN, 0.0], R1, R2), raises=InputError, match="NaN", why="NaN base"),
    Case(ip.coplanarity, ([1.0, 0.0, 0.0], R1, R2[:3]), raises=InputError, why="different ray counts"),
    Case(ip.y_parallax, ([1.0, 0.0, 0.0], R1, R2, NAN), raises=InputError, why="NaN f"),
    Case(ip.y_parallax, ([0.0, 1.0, 0.0], R1, R2, 100.0), raises=DegenerateGeometryError, why="b_x = 0"),
    Case(ip.y_parallax, ([1.0, INF, 0.0], R1, R2, 100.0), raises=InputError, why="inf b_y"),
    Case(ip.relative_orientation, (XY1[:4], XY2[:4], IO), raises=InputError, why="four points"),
    Case(ip.relative_orientation, (LINE, LINE + [3, 0], IO), raises=DegenerateGeometryError, why="collinear points"),
    Case(ip.relative_orientation, (NANXY, XY2, IO), raises=InputError, why="NaN coordinate"),
    Case(ip.relative_orientation, (XY1, XY2, "io"), raises=InputError, why="io of the wrong type"),
    Case(ip.relative_orientation, (XY1, XY2, IO), {"initial": [0, 0, NAN, 0, 0]}, raises=InputError,
         why="NaN start"),
    Case(ip.relative_orientation, (XY1, XY2, IO), {"system": "mixed"}, raises=InputError, why="unknown system"),
    Case(ip.relative_orientation, (ZERO_BASE.xy1, ZERO_BASE.xy2, IO), raises=DegenerateGeometryError,
         match="base", why="zero base (coinciding centres)"),
    Case(ip.relative_orientation, (SHORT_BASE.xy1, SHORT_BASE.xy2, IO), raises=DegenerateGeometryError,
         match="base", why="2 cm base from 1000 m with 3 µm noise"),
    Case(ip.RelativeOrientation, ("mixed", "kaw", 0, 0, 0, 0, 0, 0, 0, 0), {"q": np.zeros(3)}, raises=InputError,
         why="unknown system"),
    Case(ip.RelativeOrientation, ("dependent", "kaw", NAN, 0, 0, 0, 0, 0, 0, 0), {"q": np.zeros(3)},
         raises=InputError, why="NaN element"),
    # --- §2.9–§2.12 ----------------------------------------------------------------------------------
    Case(ip.build_model, (XY1, XY2, RO, IO), {"base_length": 0.0}, raises=InputError, why="zero B_X"),
    Case(ip.build_model, (XY1, XY2, "ro", IO), raises=InputError, why="ro of the wrong type"),
    Case(ip.build_model, (XY1, XY2, RO, IO), {"base_length": NAN}, raises=InputError, why="NaN B_X"),
    Case(ip.SimilarityTransform, (0, 0, 0, 0, 0, 0, 0.0), raises=DegenerateGeometryError, why="zero scale"),
    Case(ip.SimilarityTransform, (NAN, 0, 0, 0, 0, 0, 1.0), raises=InputError, why="NaN shift"),
    Case(ip.SimilarityTransform.from_matrix, ([0, 0, 0], np.diag([1.0, 1.0, -1.0]), 1.0), raises=InputError,
         why="a reflection, not a rotation"),
    Case(ip.similarity_closed_form, (XYZ[:2], XYZ[:2]), raises=DegenerateGeometryError, why="two points"),
    Case(ip.similarity_closed_form, (np.outer(np.arange(4), [1, 2, 3.0]),) * 2, raises=DegenerateGeometryError,
         why="collinear points"),
    Case(ip.similarity_closed_form, (XYZ[:4], XYZ[:3]), raises=InputError, why="different counts"),
    Case(ip.absolute_orientation, (MODEL.points[:2], XYZ[:2]), raises=InputError, why="6 equations"),
    Case(ip.absolute_orientation, (MODEL.points[:5], np.where(np.arange(5)[:, None] == 0, NAN, XYZ[:5])),
         raises=InputError, why="NaN in a known coordinate"),
    Case(ip.absolute_orientation, (MODEL.points[:5], XYZ[:5]), {"jacobian": "guess"}, raises=InputError,
         why="unknown jacobian"),
    Case(ip.image_orientation_from_model, (MODEL, "T"), raises=InputError, why="transform of the wrong type"),
    Case(ip.image_orientation_from_model, (MODEL, T), {"product": "sideways"}, raises=InputError,
         why="unknown product"),
    Case(ip.double_resection, (XY1, XY2, IO, np.full((12, 3), NAN)), raises=InputError, why="no control point"),
    Case(ip.double_resection, (XY1, XY2, IO, XYZ[:5]), raises=InputError, why="control not aligned"),
    Case(ip.photo_base, (56.9, 100.0), raises=InputError, why="100 % overlap"),
    Case(ip.photo_base, (NAN, 60.0), raises=InputError, why="NaN frame"),
    Case(ip.normal_case_accuracy, (2000.0, 92.0, 0.0, 0.002, 0.002, 0.001), raises=InputError, why="zero base"),
    Case(ip.normal_case_accuracy, (2000.0, 92.0, 22.8, NAN, 0.002, 0.001), raises=InputError, why="NaN m_x"),
    # --- §4.1–§4.3 -----------------------------------------------------------------------------------
    Case(pj.normalizing_transform, (NANXY,), raises=InputError, match="NaN", why="NaN point"),
    Case(pj.normalizing_transform, (SAME,), raises=DegenerateGeometryError, why="all points coincide"),
    Case(pj.normalizing_transform, (np.zeros(5),), raises=InputError, why="a 1-D array"),
    Case(pj.nearest_rotation, (np.full((3, 3), NAN),), raises=InputError, why="NaN matrix"),
    Case(pj.nearest_rotation, (np.eye(2),), raises=InputError, why="2×2"),
    Case(pj.calibration_matrix, (IO,), {"fx": -1.0}, raises=InputError, why="negative f_x"),
    Case(pj.calibration_matrix, ("io",), raises=InputError, why="io of the wrong type"),
    Case(pj.projection_matrix, (IO, "eo"), raises=InputError, why="eo of the wrong type"),
    Case(pj.dlt_from_projection, (np.zeros((3, 3)),), raises=InputError, why="3×3"),
    Case(pj.dlt_from_projection, (np.hstack([np.eye(3), np.zeros((3, 1))]),), raises=DegenerateGeometryError,
         why="P₃₄ = 0"),
    Case(pj.projection_from_dlt, (np.arange(10.0),), raises=InputError, why="10 coefficients"),
    Case(pj.dlt_from_orientation, (IO, None), raises=InputError, why="no orientation"),
    Case(pj.dlt_project, (L1, [[NAN, 0, 0]]), raises=InputError, why="NaN point"),
    Case(pj.dlt_project, (np.r_[L1[:10], NAN], XYZ), raises=InputError, why="NaN coefficient"),
    Case(pj.orientation_from_dlt, (np.zeros(11),), raises=DegenerateGeometryError, why="all zero"),
    Case(pj.orientation_from_dlt, (L1,), {"order": "xyz"}, raises=InputError, why="unknown order"),
    Case(pj.dlt_design, (XYZ, XY1[:3]), raises=InputError, why="different counts"),
    Case(pj.dlt_resection, (XYZ[:5], XY1[:5]), raises=InputError, why="five points"),
    Case(pj.dlt_resection, (np.column_stack([XYZ[:, :2], np.zeros(12)]), XY1), raises=DegenerateGeometryError,
         why="coplanar control"),
    Case(pj.dlt_resection, (XYZ, NANXY), raises=InputError, why="NaN image coordinate"),
    Case(pj.dlt_intersection, ([L1, L2], [XY1, XY2]), raises=None,
         check=lambda r: np.allclose(r.XYZ, XYZ, atol=1e-6), why="valid pair"),
    Case(pj.dlt_intersection, ([L1, pj.dlt_from_orientation(IO, EO2_UP)], [XY1, XY2]),
         raises=PointBehindCameraError, why="points behind camera 2"),
    Case(pj.dlt_intersection, ([L1], [XY1]), raises=InputError, why="one image"),
    Case(pj.dlt_intersection, ([L1, L1], [XY1, XY1]), raises=DegenerateGeometryError, why="parallel rays"),
    # --- §4.4 ----------------------------------------------------------------------------------------
    Case(pj.skew_matrix, ([1.0, NAN, 0.0],), raises=InputError, why="NaN"),
    Case(pj.normalized_image_coordinates, (XY1, "io"), raises=InputError, why="io of the wrong type"),
    Case(pj.essential_from_orientation, (EO1, EO1), raises=DegenerateGeometryError, match="base", why="zero base"),
    Case(pj.fundamental_from_orientation, (IO, EO1, IO, EO1), raises=DegenerateGeometryError, why="zero base"),
    Case(pj.fundamental_matrix, (XY1[:7], XY2[:7]), raises=InputError, why="seven points"),
    Case(pj.fundamental_matrix, (XY1, XY2), {"layout": "x1x2"}, raises=InputError, why="unknown layout"),
    Case(pj.fundamental_matrix, (ZERO_BASE.xy1, ZERO_BASE.xy2), raises=DegenerateGeometryError,
         why="pure rotation, no base"),
    Case(pj.essential_matrix, (NANXY, XY2, IO), raises=InputError, why="NaN"),
    Case(pj.essential_from_fundamental, (np.eye(2), IO), raises=InputError, why="2×2"),
    Case(pj.epipolar_residuals, (F, XY1, XY2[:3]), raises=InputError, why="different counts"),
    Case(pj.sampson_distance, (np.full((3, 3), INF), XY1, XY2), raises=InputError, why="inf F"),
    Case(pj.epipolar_lines, (F, XY1), {"image": 3}, raises=InputError, why="image 3"),
    Case(pj.essential_candidates, (np.zeros((3, 3)), XY1, XY2, IO), raises=DegenerateGeometryError,
         why="zero E"),
    Case(pj.essential_candidates, (E, XY1, XY2, IO), raises=None,
         check=lambda c: [x.n_front for x in c].count(12) == 1, why="exactly one candidate in front"),
    Case(pj.decompose_essential, (E, XY1, XY2, IO), {"system": "both"}, raises=InputError, why="unknown system"),
    Case(pj.decompose_essential, (np.zeros((3, 3)), XY1, XY2, IO), raises=DegenerateGeometryError, why="zero E"),
    Case(pj.relative_orientation_projective, (XY1[:7], XY2[:7], IO), raises=InputError, why="seven points"),
    Case(pj.relative_orientation_projective, (ZERO_BASE.xy1, ZERO_BASE.xy2, IO), raises=DegenerateGeometryError,
         why="zero base"),
    Case(pj.ransac_fundamental, (XY1, XY2, -1.0), raises=InputError, why="negative threshold"),
    Case(pj.ransac_fundamental, (XY1, XY2, NAN), raises=InputError, why="NaN threshold"),
    # --- homography ------------------------------------------------------------------------------------
    Case(pj.apply_homography, (np.zeros((3, 3)), SRC), raises=DegenerateGeometryError, why="zero matrix"),
    Case(pj.apply_homography, (np.ones((3, 3)), SRC), raises=DegenerateGeometryError, why="rank-1 matrix"),
    Case(pj.apply_homography, (H_TRUE, [[NAN, 0.0]]), raises=InputError, why="NaN point"),
    Case(pj.apply_homography, (np.eye(4), SRC), raises=InputError, why="4×4"),
    Case(pj.homography_dlt, (SRC[:3], DST[:3]), raises=InputError, why="three points"),
    Case(pj.homography_dlt, (LINE[:6], LINE[:6]), raises=DegenerateGeometryError, why="collinear points"),
    Case(pj.homography_lsq, (SRC, DST), {"H0": np.full((3, 3), NAN)}, raises=InputError, match="NaN",
         why="NaN start"),
    Case(pj.homography_lsq, (SRC, DST), {"H0": np.eye(2)}, raises=InputError, match="3×3", why="2×2 start"),
    Case(pj.homography_lsq, (SRC, DST), raises=None,
         check=lambda r: np.allclose(r.H, H_TRUE, atol=1e-8), why="exact data"),
    # --- GNSS appendix ----------------------------------------------------------------------------------
    Case(G.rotation_aok, (NAN, 0.0, 0.0), raises=InputError, why="NaN angle"),
    Case(G.geodetic_to_image_frame, ([1.0, 2.0],), raises=InputError, why="a 2-vector"),
    Case(G.image_frame_to_geodetic, ([[1.0, 2.0, 3.0, 4.0]],), raises=InputError, why="4-vectors"),
    Case(G.image_space_vectors, (GP.xy1, GA[:2], 100.0), raises=InputError, why="two angles"),
    Case(G.image_space_vectors, (GP.xy1, GA[:3], -100.0), raises=InputError, why="negative f"),
    Case(G.project, (GP.ground, GP.S1, GA[:3], 100.0), raises=None, check=_close(GP.xy1, 1e-9),
         why="valid: the synthetic image coordinates"),
    Case(G.project, (GP.ground + [0, 0, 5000.0], GP.S1, GA[:3], 100.0), raises=PointBehindCameraError,
         why="points above the camera"),
    Case(G.ground_from_image, (GP.xy1, GP.S1, GA[:3], NAN, 100.0), raises=InputError, why="NaN height"),
    Case(G.base_components, (GP.S1, GP.S1), raises=DegenerateGeometryError, match="base", why="zero base"),
    Case(G.coplanarity_residuals, (GA, GP.xy1, GP.xy2[:3], GP.S1, GP.S2, 100.0), raises=InputError,
         why="different counts"),
    Case(G.base_direction_angle, (GP.S1, GP.S1 + [0, 0, 10.0]), raises=DegenerateGeometryError, why="vertical base"),
    Case(G.initial_chi, ([NAN, 0, 0], GP.S2), raises=InputError, why="NaN centre"),
    Case(G.correction_equations, (GA, GP.xy1, GP.xy2, GP.S1, GP.S2, *CTRL, 100.0), {"partials": "guessed"},
         raises=InputError, why="unknown partials"),
    Case(G.orient_pair, (GP.xy1[:4], GP.xy2[:4], GP.S1, GP.S2, *CTRL, 100.0), raises=InputError, why="4 tie points"),
    Case(G.orient_pair, (GP.xy1, GP.xy2, GP.S1, GP.S2, np.zeros((0, 3)), np.zeros((0, 2)), np.zeros((0, 2)), 100.0),
         raises=InputError, why="no control point"),
    Case(G.orient_pair, (GP.xy1, GP.xy2, GP.S1, GP.S1, *CTRL, 100.0), raises=DegenerateGeometryError,
         why="zero base"),
    Case(G.iteration_history, (GP.xy1, GP.xy2, GP.S1, GP.S2, *CTRL, NAN), raises=InputError, why="NaN f"),
    Case(G.intersection_forms, (GP.xy1, GP.xy2, [1, 2, 3]), raises=InputError, why="2-D points for 3-D vectors"),
    Case(G.space_intersection, (GP.xy1, GP.xy2, GP.S1, GP.S2, GA, 100.0), raises=None,
         check=_close(GP.ground, 1e-6), why="valid: the true ground points"),
    Case(G.space_intersection, (GP.xy1, GP.xy2, GP.S2, GP.S1, GA, 100.0), raises=PointBehindCameraError,
         why="centres swapped: rays meet behind"),
    Case(G.build_model, (GP.xy1, GP.xy2, GP.S1, GP.S2, *CTRL, 100.0), {"partials": "x"}, raises=InputError,
         why="unknown partials"),
    Case(G.synthetic_pair, (30.0,), {"relief": -1.0}, raises=InputError, why="negative relief"),
    # --- the one synthetic-pair generator (photolib.synthetic) ------------------------------------------
    Case(stereo_pair, (8,), {"centres": ((0, 0, NAN), (400, 0, 1000))}, raises=InputError, why="NaN centre"),
    Case(stereo_pair, (8,), {"angles": np.zeros(3)}, raises=InputError, why="one row of angles"),
    Case(stereo_pair, (8,), {"sigma": -0.01}, raises=InputError, why="negative noise"),
    Case(stereo_pair, (8,), {"ground_xy": np.zeros((4, 3))}, raises=InputError, why="ground_xy with 3 columns"),
    Case(stereo_pair, (8,), {"centres": ((0, 0, 1000), (400, 0, 1000)), "mean_height": 2000.0, "relief": 1.0},
         raises=PointBehindCameraError, why="points above the cameras"),
    Case(StereoPair, (PAIR.io, "kaw", PAIR.centres, PAIR.angles, np.full((12, 3), NAN), PAIR.xy1, PAIR.xy2,
                      PAIR.xy1_true, PAIR.xy2_true, 0.0), raises=InputError, why="NaN object points"),
    Case(StereoPair, (PAIR.io, "kaw", PAIR.centres[:1], PAIR.angles, PAIR.points, PAIR.xy1, PAIR.xy2,
                      PAIR.xy1_true, PAIR.xy2_true, 0.0), raises=InputError, why="one centre"),
    Case(StereoPair, (PAIR.io, "kaw", PAIR.centres, PAIR.angles, PAIR.points, PAIR.xy1[:5], PAIR.xy2,
                      PAIR.xy1_true, PAIR.xy2_true, 0.0), raises=InputError, why="fewer image points than object points"),
]


@pytest.mark.parametrize("case", CASES, ids=[c.id for c in CASES])
def test_bad_input(case):
    check_case(case)
