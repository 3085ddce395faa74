"""Bad-input catalogue for photolib.pushbroom and photolib.derivations.scanner (Chapter 8, §8.2–8.8)."""

import numpy as np
import pytest

from catalogue import INF, NAN, Case, check_case
from photolib import pushbroom as pb
from photolib.derivations import scanner as ds
from photolib.errors import (ConvergenceError, DegenerateGeometryError, InputError,
                             PointBehindCameraError)

EO = pb.EOPolynomial([0, 0, 1000, 0, 0, 0], [100, 0, 0, 0, 0, 0])
CAM = pb.Pushbroom(0.1, 1e-5, 1001, 0.01, EO, n_rows=500)
RNG = np.random.default_rng(0)
ROWS, COLS, Z = RNG.uniform(0, 500, 12), RNG.uniform(0, 1000, 12), RNG.uniform(0, 200, 12)
XG, YG = CAM.ground(ROWS, COLS, Z)
XYZ = np.column_stack([XG, YG, Z])
FLAT = np.column_stack([XG, YG, np.zeros(12)])
R_UP = np.array([[0.0, 0.0, -1.0]])
TABLE = EO.elements(np.arange(50) * 0.01)
TAB = pb.EOTable(TABLE, 0.01)
TCAM = pb.Pushbroom(0.1, 1e-5, 1001, 0.01, TAB)


def _affine_model():
    return pb.fit_affine(XYZ, ROWS, COLS)


CASES = [
    # rays
    Case(pb.ray_linear_ccd, (NAN, 1.0), why="NaN y_c", raises=InputError),
    Case(pb.ray_linear_ccd, (0.1, 0.0), why="zero focal length", raises=InputError),
    Case(pb.ray_linear_ccd, (np.zeros(3), 1.0, np.zeros(2)), why="shapes do not broadcast", raises=InputError),
    Case(pb.ray_linear_ccd, ("a", 1.0), why="a string", raises=InputError),
    Case(pb.staggered_offsets, ([2, 2], [0.1]), why="different lengths", raises=InputError),
    Case(pb.staggered_offsets, ([], []), why="empty", raises=InputError),
    Case(pb.staggered_offsets, ([2.5, 2], [0.1, 0.2]), why="non-integer columns", raises=InputError),
    Case(pb.ray_whiskbroom, (600.0, 1.0, 1000), why="pixel outside the line", raises=InputError),
    Case(pb.ray_whiskbroom, (0.0, 4.0, 1000), why="field of view ≥ π", raises=InputError),
    Case(pb.ray_whiskbroom, (INF, 1.0, 1000), why="inf", raises=InputError),
    Case(pb.line_field_of_view, (0, 0.0065, 62.5), why="no pixels", raises=InputError),
    Case(pb.line_field_of_view, (12000, NAN, 62.5), why="NaN pixel size", raises=InputError),
    Case(pb.line_field_of_view, (12000, 0.0065, [62.5, 60.0]), why="two focal lengths", raises=InputError),
    Case(pb.ray_three_line, (0.0, 1.0, "sideways", 0.1, -0.1), why="unknown line", raises=InputError),
    Case(pb.ray_three_line, (0.0, 1.0, "forward", NAN, -0.1), why="NaN offset", raises=InputError),
    Case(pb.tilted_focal_length, (1.0, np.pi / 2), why="tilt of 90°", raises=InputError),
    Case(pb.tilted_focal_length, (-1.0, 0.1), why="negative f0", raises=InputError),
    # EO and sensor
    Case(pb.EOPolynomial, ([0, 0, 0], [0] * 6), why="3 elements", raises=InputError),
    Case(pb.EOPolynomial, ([0] * 6, [NAN] * 6), why="NaN rates", raises=InputError),
    Case(pb.EOPolynomial.from_vector, (np.zeros(13),), why="13 parameters", raises=InputError),
    Case(pb.EOTable, (TABLE[:1], 0.01), why="one line", raises=InputError, match="at least 2"),
    Case(pb.EOTable, (TABLE[:, :5], 0.01), why="5 elements per line", raises=InputError),
    Case(pb.EOTable, (TABLE[0], 0.01), why="1-D table", raises=InputError),
    Case(pb.EOTable, (np.where(TABLE == 0, NAN, TABLE), 0.01), why="NaN in the table", raises=InputError),
    Case(pb.EOTable, (TABLE, 0.0), why="zero line period", raises=InputError),
    Case(pb.EOTable, (TABLE, 0.01, "xyz"), why="unknown rotation order", raises=InputError),
    Case(pb.EOTable(TABLE, 0.01, extrapolate=False).elements, ([0.6],), why="time after the table",
         raises=InputError, match="outside"),
    Case(TAB.at, ([NAN],), why="NaN time", raises=InputError),
    Case(pb.Pushbroom, (0.1, 1e-5, 100, 0.01, TAB), {"n_rows": 60}, why="more rows than table lines",
         raises=InputError),
    Case(TCAM.project, (1e5, 0.0, 0.0), {"bracket": True}, why="a point no line sees gives NaN", raises=None,
         check=lambda rc: bool(np.isnan(rc[0]) and np.isnan(rc[1]))),
    Case(CAM.project, (0.0, 0.0, 0.0), {"bracket": True, "max_iter": 1, "tol": 1e-30},
         why="bracketed search without convergence", raises=ConvergenceError),
    Case(pb.resect_pushbroom, (TCAM, ROWS[:8] / 10, COLS[:8], XYZ[:8]), why="a table cannot be resected",
         raises=InputError, match="EOPolynomial"),
    Case(pb.Pushbroom, (0.1, 1e-5, 100.5, 0.01, EO), why="non-integer columns", raises=InputError),
    Case(pb.Pushbroom, (0.1, 1e-5, 100, 0.01, "eo"), why="eo not an EOPolynomial", raises=InputError),
    Case(pb.Pushbroom, (0.1, 1e-5, 100, 0.01, EO), {"x_offsets": np.zeros(7)}, why="offsets of the wrong length",
         raises=InputError),
    Case(pb.Pushbroom, (0.0, 1e-5, 100, 0.01, EO), why="zero focal length", raises=InputError),
    Case(CAM.ground, (0.0, 10.0, 2000.0), why="plane above the sensor", raises=PointBehindCameraError),
    Case(CAM.ground, (np.zeros(3), np.zeros(2), 0.0), why="mismatched sizes", raises=InputError),
    Case(CAM.project, (NAN, 0.0, 0.0), why="NaN ground point", raises=InputError),
    Case(CAM.project, (0.0, 0.0, 5000.0), why="point above the sensor", raises=PointBehindCameraError),
    Case(CAM.project, (30.0, 0.0, 0.0), {"max_iter": 1, "tol": 1e-30}, why="no convergence in one step",
         raises=ConvergenceError),
    Case(CAM.monoplot, (10.0, 10.0, "dem"), why="dem not callable", raises=InputError),
    Case(CAM.monoplot, (10.0, 10.0, lambda X, Y: np.full(X.shape, np.nan)), why="DEM does not cover the footprint",
         raises=DegenerateGeometryError, match="DEM"),
    Case(CAM.monoplot, (10.0, 10.0, lambda X, Y: 0.0), why="dem returns a scalar", raises=InputError),
    Case(CAM.monoplot, (10.0, 1000.0, lambda X, Y: 500 + 50 * Y), why="slope steeper than the rays",
         raises=ConvergenceError),
    Case(CAM.projector, (), why="callable returned", raises=None,
         check=lambda f: np.allclose(f(XG[:2], YG[:2], Z[:2]), (ROWS[:2], COLS[:2]))),
    # resection
    Case(pb.resect_pushbroom, (CAM, ROWS[:5], COLS[:5], XYZ[:5]), why="5 GCPs for 12 unknowns", raises=InputError,
         match="at least 6"),
    Case(pb.resect_pushbroom, (CAM, ROWS, COLS, XYZ[:11]), why="mismatched sizes", raises=InputError),
    Case(pb.resect_pushbroom, (CAM, ROWS, COLS, XYZ), {"fixed": ("Q_S0",)}, why="unknown fixed name", raises=InputError),
    Case(pb.resect_pushbroom, (CAM, ROWS, COLS, XYZ), {"degree": 3}, why="degree 3", raises=InputError),
    Case(pb.resect_pushbroom, ("cam", ROWS, COLS, XYZ), why="not a Pushbroom", raises=InputError),
    Case(pb.resect_pushbroom, (CAM, ROWS, COLS, np.where(np.eye(12, 3) > 0, NAN, XYZ)), why="NaN GCP",
         raises=InputError),
    Case(pb.resect_pushbroom, (CAM, ROWS, COLS, XYZ), {"sigma_eo": [1.0] * 5}, why="sigma_eo of wrong length",
         raises=InputError),
    Case(pb.resection_condition, (CAM, ROWS, COLS, XYZ[:, :2]), why="2-D points", raises=InputError),
    Case(pb.resection_condition, (CAM, ROWS[:3], COLS[:3], XYZ[:3]), why="too few GCPs", raises=InputError),
    Case(pb.PushbroomResection, (CAM, None, (), (), 1.0), why="plain record", raises=None,
         check=lambda r: r.condition == 1.0),
    # approximating models
    Case(pb.fit_approximate_model, ("rpc", XYZ, ROWS, COLS), why="unknown kind", raises=InputError),
    Case(pb.fit_approximate_model, ("affine", XYZ, ROWS, COLS), {"perspective": "cols"},
         why="perspective option for the affine model", raises=InputError),
    Case(pb.fit_dlt, (XYZ[:5], ROWS[:5], COLS[:5]), why="5 GCPs", raises=InputError, match="at least 6"),
    Case(pb.fit_dlt, (FLAT, ROWS, COLS), why="GCPs at one height", raises=DegenerateGeometryError),
    Case(pb.fit_affine, (XYZ[:3], ROWS[:3], COLS[:3]), why="3 GCPs", raises=InputError, match="at least 4"),
    Case(pb.fit_affine, (XYZ, ROWS[:4], COLS), why="mismatched sizes", raises=InputError),
    Case(pb.fit_parallel_perspective, (XYZ[:6], ROWS[:6], COLS[:6]), why="6 GCPs (row equation needs 7)",
         raises=InputError, match="at least 7"),
    Case(pb.fit_parallel_perspective, (np.full((8, 3), INF), ROWS[:8], COLS[:8]), why="inf", raises=InputError),
    Case(pb.ApproximateModel, ("dlt", np.zeros(8), np.zeros(5), np.ones(5)), why="8 coefficients for a DLT",
         raises=InputError),
    Case(pb.ApproximateModel, ("affine", np.full(8, NAN), np.zeros(5), np.ones(5)), why="NaN coefficients",
         raises=InputError),
    Case(_affine_model().project, (NAN, 0.0, 0.0), why="NaN point", raises=InputError),
    # stereo
    Case(pb.intersect_scanner_rays, ([[0, 0, 100.0]], R_UP, [[0, 0, 100.0]], R_UP), why="zero base",
         raises=DegenerateGeometryError),
    Case(pb.intersect_scanner_rays, ([[0, 0, 100.0]], R_UP, [[10, 0, 100.0]], R_UP), why="parallel rays",
         raises=DegenerateGeometryError),
    Case(pb.intersect_scanner_rays, ([[0, 0, 100.0]], [[-0.1, 0, -1]], [[20, 0, 100.0]], [[0.1, 0, -1]]),
         why="rays meet behind the sensor", raises=PointBehindCameraError),
    Case(pb.intersect_scanner_rays, (np.zeros((2, 3)), R_UP, np.zeros((2, 3)), R_UP), why="mismatched sizes",
         raises=InputError),
    Case(pb.intersect_pushbroom, (CAM, [1.0], [2.0], "cam", [1.0], [2.0]), why="not a Pushbroom", raises=InputError),
    Case(pb.intersect_pushbroom, (CAM, [1.0, 2.0], [2.0], CAM, [1.0], [2.0]), why="mismatched sizes",
         raises=InputError),
    Case(pb.first_line_rays, (R_UP, np.zeros((2, 3))), why="mismatched sizes", raises=InputError),
    Case(pb.first_line_rays, (R_UP, [[NAN, 0, 0]]), why="NaN increments", raises=InputError),
    Case(pb.orient_pushbroom_pair, ((R_UP, R_UP, R_UP), (R_UP, R_UP, XYZ[:1]), (R_UP, R_UP, XYZ[:1]),
                                    np.zeros(6), np.zeros(6)), why="ties without increments", raises=InputError),
    Case(pb.orient_pushbroom_pair, ((R_UP, R_UP, R_UP, R_UP), (R_UP, R_UP, XYZ[:1]), (R_UP, R_UP, XYZ[:1]),
                                    np.zeros(6), np.zeros(6)), why="5 equations for 12 unknowns", raises=InputError),
    Case(pb.orient_pushbroom_pair, ((R_UP, R_UP, R_UP, R_UP), (R_UP, R_UP, XYZ[:1]), (R_UP, R_UP, XYZ[:1]),
                                    np.zeros(5), np.zeros(6)), why="5 EO elements", raises=InputError),
    Case(pb.PairOrientation, (np.zeros(6), np.zeros(6), None), why="plain record", raises=None,
         check=lambda r: len(r.names) == 12),
    # derivations
    Case(ds.pushbroom_polynomial_model, (3,), why="degree 3", raises=InputError),
    Case(ds.pushbroom_polynomial_model, (True,), why="a bool degree", raises=InputError),
    Case(ds.scanner_collinearity_model, (), why="no input", raises=None, check=lambda m: len(m.parameters) == 6),
    Case(ds.scanner_coplanarity_model, (), why="no input", raises=None, check=lambda m: len(m.parameters) == 12),
    Case(ds.rotated_ray_model, (), why="no input", raises=None, check=lambda m: len(m.residuals) == 3),
]


@pytest.mark.parametrize("case", CASES, ids=lambda c: c.id)
def test_bad_input(case):
    check_case(case)
