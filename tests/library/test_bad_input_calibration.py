"""Bad-input catalogue for photolib.calibration (Chapter 11, §11.3)."""

import numpy as np
import pytest

from catalogue import INF, NAN, Case, check_case
from photolib import calibration as cal
from photolib.camera import InteriorOrientation
from photolib.errors import DegenerateGeometryError, InputError

IO = InteriorOrientation(50.0)
G = np.mgrid[-2:3, -2:3].reshape(2, -1).T.astype(float)
FLAT = np.column_stack([G, np.full(len(G), -10.0)])
XY = FLAT[:, :2] * 5.0
BOARD = render = cal.render_chessboard((5, 4), 20.0, np.array([[1.0, 0, 30], [0, 1, 25], [0, 0, 1]]), (140, 160))
CORNERS = [np.zeros((12, 2))] * 2

CASES = [
    Case(cal.target_field_tolerances, (50.0, 0.005, 6000.0, -1.0), raises=InputError, why="negative depth"),
    Case(cal.target_field_tolerances, (NAN, 0.005, 6000.0, 2000.0), raises=InputError, why="NaN focal length"),
    Case(cal.certificate_to_mm, ({"q": 1.0}, 0.0062), raises=InputError, why="unknown entry"),
    Case(cal.certificate_to_mm, ({"f": INF}, 0.0062), raises=InputError, why="inf value"),
    Case(cal.certificate_to_pixels, ({"f": 50.0}, 0.0), raises=InputError, why="zero pixel size"),
    Case(cal.certificate_to_pixels, ({}, 0.0062), raises=InputError, why="empty certificate"),
    Case(cal.pixels_to_image, ([[NAN, 0.0]], (480, 640)), raises=InputError, why="NaN coordinate"),
    Case(cal.image_to_pixels, ([[0.0, 0.0]], (0, 640)), raises=InputError, why="empty image shape"),
    Case(cal.calibration_residuals, (FLAT, XY[:3], IO, np.zeros(6)), raises=InputError, why="mismatched sizes"),
    Case(cal.calibration_residuals, (FLAT, XY, IO, np.zeros(5)), raises=InputError, why="5 EO elements"),
    Case(cal.self_calibration, (FLAT, XY, IO, np.zeros(6)), raises=DegenerateGeometryError, match="Z_S",
         why="flat frontal target: f and Z_S inseparable"),
    Case(cal.self_calibration, (FLAT[:3], XY[:3], IO, np.zeros(6)), raises=InputError, why="too few points"),
    Case(cal.self_calibration, (FLAT, XY, IO, np.zeros(6)), {"calibrate": ("f", "zz")}, raises=InputError,
         why="unknown name"),
    Case(cal.planar_start_values, (G[:3], [XY[:3]]), raises=InputError, why="fewer than 4 points"),
    Case(cal.planar_start_values, (G, [G * 100.0]), raises=DegenerateGeometryError, why="frontal view: f undetermined"),
    Case(cal.refine_corners, (BOARD, [[1.0, 1.0]]), raises=InputError, why="window at the border"),
    Case(cal.refine_corners, (np.full((50, 50), 7.0), [[25.0, 25.0]]), raises=DegenerateGeometryError,
         why="textureless window"),
    Case(cal.find_chessboard, (np.full((100, 100), 7.0), (4, 3)), {"name": "flat.png"},
         raises=DegenerateGeometryError, match="flat.png", why="no board: the error names the image"),
    Case(cal.find_chessboard, (BOARD, (9, 6)), {"name": "small.png"}, raises=DegenerateGeometryError,
         match="small.png.*not found", why="board of another size"),
    Case(cal.find_chessboard, (np.full((100, 100), NAN), (4, 3)), raises=InputError, why="NaN image"),
    Case(cal.find_chessboard, (BOARD, (1, 6)), raises=InputError, why="bad pattern size"),
    Case(cal.render_chessboard, ((2, 2), 1.0, np.zeros((3, 3)), (10, 10)), raises=InputError, why="singular H"),
    Case(cal.calibrate_chessboard, (CORNERS, (4, 3), 1.0, (100, 100)), raises=InputError, why="only 2 views"),
    Case(cal.calibrate_chessboard, ([np.zeros((11, 2))] * 3, (4, 3), 1.0, (100, 100)), raises=InputError,
         why="corners not matching the pattern"),
    Case(cal.CalibrationResult, (IO, {}, [], np.zeros((0, 6)), 0.0, [], 0.0, ("f",), np.eye(1), ("f",), 0),
         raises=None, check=lambda r: r.correlation("f", "f") == 1.0, why="a plain record"),
    Case(cal.CalibrationResult(IO, {}, [], np.zeros((0, 6)), 0.0, [], 0.0, ("f",), np.eye(1), ("f",), 0).correlation,
         ("f", "Z_S[9]"), raises=InputError, why="unknown unknown's name"),
]


@pytest.mark.parametrize("case", CASES, ids=lambda c: c.id)
def test_bad_input(case):
    check_case(case)
