"""Bad-input catalogue for photolib.georef and photolib.derivations.georef (Chapter 8, §8.14–8.17)."""

import numpy as np
import pytest

from catalogue import INF, NAN, Case, check_case
from photolib import georef
from photolib.derivations import georef as dgeoref
from photolib.errors import ConvergenceError, DegenerateGeometryError, InputError, PointBehindCameraError
from photolib.rectify import RasterGrid

E3 = np.eye(3)
Z3 = np.zeros(3)
G = np.array([0.0, 0.0, 1000.0])
POSE = (G, E3, Z3, Z3, E3)
EO2 = np.array([[0, 0, 1000, 0, 0, 0], [10.0, 0, 1000, 0, 0, 0]])
LINE_EO = np.column_stack([np.arange(20.0), np.zeros(20), np.full(20, 1000.0), np.zeros((20, 3))])
SCANNER = georef.TabulatedLineScanner(LINE_EO, 100.0, 0.01, 21)
GRID = RasterGrid(-0.5, 0.5, 1.0, (4, 4))
FLAT = lambda r, c, Z: (np.asarray(c, float), -np.asarray(r, float))       # noqa: E731
PROJ = lambda X, Y, Z: (1.5 - np.asarray(Y), np.asarray(X) + 1.5)         # noqa: E731
IMG = np.arange(16.0).reshape(4, 4)
AX = np.arange(-1.0, 2.0)
BLOCK = georef.three_line_block(n_points=6, n_control=3)
TF = BLOCK.t[BLOCK.fixed]
TRI = (BLOCK.at_rows(BLOCK.t), BLOCK.xy, BLOCK.point, TF, BLOCK.points)
TRI_KW = dict(f=BLOCK.f, control=BLOCK.control, measured=BLOCK.at_rows(BLOCK.eo_measured),
              measured_fixed=BLOCK.eo_measured[BLOCK.fixed])
NOT_ROTATION = np.diag([1.0, 1.0, 2.0])
V0 = BLOCK.view == 0

CASES = [
    # §8.14 vectors
    Case(georef.frame_vector, ([NAN, 0.0], 100.0), raises=InputError, why="NaN image coordinate"),
    Case(georef.frame_vector, ([1.0, 2.0, 3.0], 100.0), raises=InputError, why="three coordinates"),
    Case(georef.frame_vector, ([1.0, 2.0], 0.0), raises=InputError, why="f = 0"),
    Case(georef.frame_vector, (np.zeros((0, 2)), 100.0), raises=InputError, why="empty"),
    Case(georef.scanner_vector, (INF, 100.0), raises=InputError, why="inf along-line coordinate"),
    Case(georef.scanner_vector, (1.0, -5.0), raises=InputError, why="negative f"),
    Case(georef.scanner_vector, (0.0, 100.0), raises=None, why="the centre pixel looks straight down",
         check=lambda r: np.allclose(r, [[0, 0, -1]])),
    # §8.14 poses and georeferencing
    Case(georef.sensor_pose, (G, NOT_ROTATION, Z3, Z3, E3), raises=InputError, why="IMU attitude not a rotation"),
    Case(georef.sensor_pose, (G, E3, [0, 0], Z3, E3), raises=InputError, why="2-D lever arm"),
    Case(georef.sensor_pose, (np.zeros((2, 3)), np.stack([E3] * 3), Z3, Z3, E3), raises=InputError,
         why="2 positions, 3 attitudes"),
    Case(georef.sensor_pose, (G, E3, Z3, [0, NAN, 0], E3), raises=InputError, why="NaN lever arm"),
    Case(georef.direct_georeference, ([0, 0, -1.0],) + POSE, dict(scale=1.0, Z=0.0), raises=InputError,
         why="both scale and Z"),
    Case(georef.direct_georeference, ([0, 0, 1.0],) + POSE, dict(Z=0.0), raises=PointBehindCameraError,
         why="ray pointing up cannot reach the ground"),
    Case(georef.direct_georeference, ([1.0, 0, 0],) + POSE, dict(Z=0.0), raises=PointBehindCameraError,
         why="horizontal ray"),
    Case(georef.direct_georeference, (np.zeros((3, 3)), np.zeros((2, 3)), E3, Z3, Z3, E3), raises=InputError,
         why="3 vectors, 2 positions"),
    Case(georef.direct_georeference, ([0, 0, -1.0], G, NOT_ROTATION, Z3, Z3, E3), raises=InputError,
         why="not a rotation"),
    Case(georef.ground_to_sensor, ([NAN, 0, 0],) + POSE, raises=InputError, why="NaN point"),
    Case(georef.ground_to_sensor, ([0, 0],) + POSE, raises=InputError, why="2-D point"),
    # §8.15
    Case(georef.interpolate_fixed_centres, (0.5, [0.0], EO2[:1]), raises=InputError, why="one fixed centre"),
    Case(georef.interpolate_fixed_centres, (0.5, [1.0, 0.0], EO2), raises=InputError, why="decreasing times"),
    Case(georef.interpolate_fixed_centres, (2.0, [0.0, 1.0], EO2), raises=InputError, why="extrapolation"),
    Case(georef.interpolate_fixed_centres, (0.5, [0.0, 1.0], EO2, np.zeros((1, 6))), raises=InputError,
         why="measured without measured_fixed"),
    Case(georef.interpolate_fixed_centres, (0.5, [0.0, 1.0], EO2[:, :5]), raises=InputError, why="5 EO elements"),
    Case(georef.interpolate_fixed_centres, (0.5, [0.0, 1.0], EO2, np.zeros((2, 6)), EO2), raises=InputError,
         why="2 measurements for 1 time"),
    Case(georef.TabulatedLineScanner, (LINE_EO[:1], 100.0, 0.01, 21), raises=InputError, why="one line"),
    Case(georef.TabulatedLineScanner, (LINE_EO, 100.0, 0.0, 21), raises=InputError, why="zero pixel size"),
    Case(georef.TabulatedLineScanner, (LINE_EO, 100.0, 0.01, 2.5), raises=InputError, why="fractional n_cols"),
    Case(georef.TabulatedLineScanner, (np.where(LINE_EO == 0, NAN, LINE_EO), 100.0, 0.01, 21), raises=InputError,
         why="NaN EO"),
    Case(SCANNER.project, (1e6, 0.0, 0.0), raises=None, why="a point no line sees gives NaN, not a guess",
         check=lambda rc: bool(np.isnan(rc[0]) and np.isnan(rc[1]))),
    Case(georef.ThreeLineBlock, tuple([np.zeros(1)] * 15), raises=None, why="a plain record",
         check=lambda b: isinstance(b, georef.ThreeLineBlock)),
    Case(georef.three_line_block, (), dict(n_points=3, n_control=5), raises=InputError, why="more control than points"),
    Case(georef.three_line_block, (), dict(sigma_image=-1.0), raises=InputError, why="negative noise"),
    Case(georef.three_line_block, (), dict(fixed_every=1000.0), raises=InputError, why="fixed spacing > strip"),
    Case(georef.three_line_block, (), dict(duration=NAN), raises=InputError, why="NaN duration"),
    Case(georef.FixedCentreAdjustment, (EO2, np.zeros((1, 3)), None, None), raises=None, why="a plain record",
         check=lambda r: r.offset is None),
    Case(georef.fixed_centre_triangulation, TRI[:3] + (TF[::-1], TRI[4]), TRI_KW, raises=InputError,
         why="decreasing fixed times"),
    Case(georef.fixed_centre_triangulation, (TRI[0][:-1],) + TRI[1:], TRI_KW, raises=InputError,
         why="mismatched observation counts"),
    Case(georef.fixed_centre_triangulation, TRI[:2] + (BLOCK.point + 100,) + TRI[3:], TRI_KW, raises=InputError,
         why="point index out of range"),
    Case(georef.fixed_centre_triangulation, TRI, dict(f=BLOCK.f, control=BLOCK.control), raises=InputError,
         why="no GNSS/IMU and no approximate EO"),
    Case(georef.fixed_centre_triangulation, TRI[:3] + (TF, np.where(BLOCK.points > 0, NAN, 0)), TRI_KW,
         raises=InputError, why="NaN points"),
    Case(georef.fixed_centre_triangulation, (TRI[0][V0], TRI[1][V0], TRI[2][V0]) + TRI[3:],
         dict(TRI_KW, measured=TRI_KW["measured"][V0]), raises=DegenerateGeometryError,
         why="tie points seen on one line only"),
    Case(georef.fixed_centre_triangulation, TRI, dict(TRI_KW, sigma_image=0.0), raises=InputError,
         why="zero sigma"),
    # §8.16
    Case(georef.DirectOrtho, (IMG, np.ones((4, 4), int), 1, 0), raises=None, why="a plain record",
         check=lambda o: not o.holes.any()),
    Case(georef.direct_orthorectify, (IMG, FLAT, np.zeros((3, 3)), GRID, GRID), raises=InputError,
         why="DEM of the wrong shape"),
    Case(georef.direct_orthorectify, (np.full((4, 4), NAN), FLAT, np.zeros((4, 4)), GRID, GRID),
         raises=InputError, why="NaN image"),
    Case(georef.direct_orthorectify, (IMG, "ground", np.zeros((4, 4)), GRID, GRID), raises=InputError,
         why="not a callable"),
    Case(georef.direct_orthorectify, (IMG, FLAT, np.zeros((4, 4)), GRID, (0, 0, 1, (4, 4))), raises=InputError,
         why="grid not a RasterGrid"),
    Case(georef.direct_orthorectify, (IMG, lambda r, c, Z: (np.asarray(c) + 1e4, np.asarray(r) * 0.0),
                                      np.zeros((4, 4)), GRID, GRID), raises=ConvergenceError,
         why="every pixel lands off the DEM"),
    Case(georef.direct_orthorectify, (IMG, lambda r, c, Z: (np.zeros(3), np.zeros(3)), np.zeros((4, 4)), GRID, GRID),
         raises=InputError, why="ground() returns the wrong shape"),
    # §8.17
    Case(georef.QuasiFrame, (IMG, np.ones((4, 4), int), Z3, Z3, 100.0, 1.0, "wak"), raises=None,
         why="a plain record", check=lambda q: q.image.shape == (4, 4)),
    Case(georef.quasi_frame_image, ([], [], np.zeros((4, 4)), GRID, G, 100.0, 1.0, (3, 3)), raises=InputError,
         why="no scans"),
    Case(georef.quasi_frame_image, ([IMG], [PROJ, PROJ], np.zeros((4, 4)), GRID, G, 100.0, 1.0, (3, 3)),
         raises=InputError, why="one scan, two projectors"),
    Case(georef.quasi_frame_image, ([IMG], [PROJ], np.zeros((4, 4)), GRID, G, -1.0, 1.0, (3, 3)),
         raises=InputError, why="negative f"),
    Case(georef.quasi_frame_image, ([IMG], [PROJ], np.zeros((4, 4)), GRID, [0, NAN, 0], 100.0, 1.0, (3, 3)),
         raises=InputError, why="NaN centre"),
    Case(georef.quasi_frame_image, ([IMG], [PROJ], np.full((4, 4), NAN), GRID, G, 100.0, 1.0, (3, 3)),
         raises=InputError, why="DEM without heights"),
    Case(georef.scan_voxel_cost, ([IMG], [PROJ], AX, AX, AX), raises=InputError, why="one scan"),
    Case(georef.scan_voxel_cost, (IMG, [PROJ], AX, AX, AX), raises=InputError, why="an array, not a list"),
    Case(georef.scan_voxel_cost, ([IMG, IMG], [PROJ, PROJ], AX, AX, [0.0, 0.0]), raises=InputError,
         why="Z not increasing"),
    Case(georef.scan_voxel_cost, ([IMG, IMG], [PROJ, 3], AX, AX, AX), raises=InputError, why="not a callable"),
    Case(georef.scan_voxel_cost, ([IMG, np.full((4, 4), INF)], [PROJ, PROJ], AX, AX, AX), raises=InputError,
         why="inf pixels"),
    Case(georef.scan_voxel_cost, ([IMG, IMG], [PROJ, lambda X, Y, Z: (np.full(X.shape, NAN),) * 2], AX, AX, AX),
         raises=None, why="a scan that sees nothing: worst cost everywhere",
         check=lambda C: bool(np.all(C == 15.0))),
    Case(georef.object_space_sgm, ([IMG, IMG], [PROJ, PROJ], AX, AX, AX), dict(P1=5.0, P2=1.0),
         raises=InputError, why="P2 < P1"),
    Case(georef.object_space_sgm, ([IMG, IMG], [PROJ, PROJ], AX, AX, AX), dict(paths=3), raises=InputError,
         why="3 paths"),
    # derivations
    Case(dgeoref.fixed_centre_collinearity, ("xyz",), raises=InputError, why="unknown order"),
    Case(dgeoref.line_collinearity, ("abc",), raises=InputError, why="unknown order"),
    Case(dgeoref.fixed_centre_functions, ("zz",), raises=InputError, why="unknown order"),
]


@pytest.mark.parametrize("case", CASES, ids=lambda c: c.id)
def test_bad_input(case):
    check_case(case)
