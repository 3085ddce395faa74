"""Bad-input catalogue for photolib.rectify (Chapter 7): NaN/inf, wrong shapes and types, empty
input, grids that do not match, DEMs that do not cover, rays behind the camera, divergence."""

import numpy as np
import pytest

from catalogue import INF, NAN, Case, check_case
from photolib import rectify as R
from photolib.camera import ExteriorOrientation, InteriorOrientation
from photolib.errors import ConvergenceError, DegenerateGeometryError, InputError

IMG = np.arange(20.0).reshape(4, 5)
GRID = R.RasterGrid(0.0, 40.0, 10.0, (4, 4))            # centres X 5..35, Y 35..5
DEM = np.zeros((4, 4))
EO = ExteriorOrientation(20.0, 20.0, 1000.0)
IO = InteriorOrientation(100.0)
VERTICAL = lambda X, Y, Z: (-np.asarray(Y), np.asarray(X))   # noqa: E731
WRONG_SHAPE = lambda X, Y, Z: (np.zeros(3), np.zeros(3))     # noqa: E731
BIG = R.RasterGrid(-500.0, 500.0, 10.0, (100, 100))
STEEP = 2.2 * BIG.centres()[0] + 100.0
G1, G2 = R.RasterGrid(0.0, 4.0, 1.0, (4, 4)), R.RasterGrid(2.0, 4.0, 1.0, (4, 4))
LINE = [[3.0, 0.0], [3.0, 4.0]]
ORIGIN = (0.9, 0.6, 100.0)

CASES = [
    # RasterGrid
    Case(R.RasterGrid, (NAN, 0.0, 1.0, (2, 2)), raises=InputError, why="NaN origin"),
    Case(R.RasterGrid, (0.0, 0.0, 0.0, (2, 2)), raises=InputError, match="positive", why="zero pixel"),
    Case(R.RasterGrid, (0.0, 0.0, (1.0, 2.0, 3.0), (2, 2)), raises=InputError, why="three pixel sizes"),
    Case(R.RasterGrid, (0.0, 0.0, 1.0, (0, 2)), raises=InputError, why="empty grid"),
    Case(R.RasterGrid, (0.0, 0.0, 1.0, (2.5, 2)), raises=InputError, why="fractional rows"),
    Case(R.RasterGrid, (0.0, 0.0, 1.0, "ab"), raises=InputError, why="text shape"),
    Case(R.RasterGrid.from_geotransform, ((0, 1, 0.1, 0, 0, -1), (2, 2)), raises=InputError,
         match="north-up", why="rotated geotransform"),
    Case(R.RasterGrid.from_geotransform, ((0, 1, 0, 0, 0, 1), (2, 2)), raises=InputError, why="south-up"),
    Case(R.RasterGrid.from_geotransform, ((0, 1, 0), (2, 2)), raises=InputError, why="3 numbers"),
    Case(R.RasterGrid.aligned, (5.0, 0.0, 5.0, 1.0, 1.0), raises=InputError, match="empty", why="empty area"),
    Case(R.RasterGrid.aligned, (0.0, 0.0, INF, 1.0, 1.0), raises=InputError, why="infinite area"),
    Case(R.RasterGrid.aligned, (0.0, 0.0, 1.0, 1.0, -1.0), raises=InputError, why="negative pixel"),
    # resample
    Case(R.resample, (IMG, [1.0], [1.0], "lanczos"), raises=InputError, match="method", why="unknown method"),
    Case(R.resample, (IMG, [NAN], [1.0]), raises=InputError, match="NaN", why="NaN position"),
    Case(R.resample, (IMG, [1.0, 2.0], [1.0, 2.0, 3.0]), raises=InputError, why="mismatched positions"),
    Case(R.resample, (np.zeros(5), [0.0], [0.0]), raises=InputError, why="1-D image"),
    Case(R.resample, (np.zeros((0, 5)), [0.0], [0.0]), raises=InputError, why="empty image"),
    Case(R.resample, ("image", [0.0], [0.0]), raises=InputError, why="text image"),
    Case(R.resample, (IMG, [1.0], [1.0]), {"fill": "none"}, raises=InputError, why="text fill"),
    Case(R.resample, (IMG, [1.0], [1.0], "bicubic"), {"cubic_a": NAN}, raises=InputError, why="NaN cubic_a"),
    Case(R.resample, (IMG, [99.0], [1.0]), raises=None, why="outside: the fill",
         check=lambda v: bool(np.isnan(v[0]))),
    Case(R.resample, (np.ones((1, 1)), [0.0], [0.0]), raises=None, why="a one-pixel image",
         check=lambda v: v[0] == 1.0),
    Case(R.resample, (IMG, [], []), raises=None, why="no positions", check=lambda v: v.shape == (0,)),
    # rectify_forward
    Case(R.rectify_forward, (IMG, np.zeros((2, 2)), np.zeros((2, 2)), (3, 3)), raises=InputError,
         match="shape", why="positions not of the image's shape"),
    Case(R.rectify_forward, (IMG, np.full((4, 5), NAN), np.zeros((4, 5)), (3, 3)), raises=InputError,
         why="NaN positions"),
    Case(R.rectify_forward, (IMG, np.zeros((4, 5)), np.zeros((4, 5)), (0, 3)), raises=InputError,
         why="empty output"),
    Case(R.rectify_forward, (IMG, np.zeros((4, 5)), np.zeros((4, 5)), "3x3"), raises=InputError,
         why="text output shape"),
    Case(R.rectify_forward, (IMG, np.full((4, 5), 50.0), np.zeros((4, 5)), (3, 3)), raises=None,
         why="everything outside: all holes", check=lambda r: bool(np.isnan(r[0]).all() and (r[1] == 0).all())),
    # dem_height
    Case(R.dem_height, (DEM, GRID, [50.0], [20.0]), raises=InputError, match="missing area",
         why="outside the DEM"),
    Case(R.dem_height, (np.zeros((3, 3)), GRID, [20.0], [20.0]), raises=InputError, match="match",
         why="DEM and grid shapes differ"),
    Case(R.dem_height, (DEM, (0, 0, 1), [20.0], [20.0]), raises=InputError, match="RasterGrid",
         why="a tuple for the grid"),
    Case(R.dem_height, (DEM, GRID, [NAN], [20.0]), raises=InputError, why="NaN X"),
    Case(R.dem_height, (DEM, GRID, [20.0], [20.0]), {"outside": "clip"}, raises=InputError,
         why="unknown outside rule"),
    Case(R.dem_height, (np.where(np.eye(4) > 0, NAN, 0.0), GRID, [5.0], [35.0]), raises=None,
         why="a void propagates", check=lambda z: bool(np.isnan(z[0]))),
    # frame_projector
    Case(R.frame_projector, (EO, IO, 0.0, (10, 10)), raises=InputError, why="zero pixel size"),
    Case(R.frame_projector, (EO, IO, 0.01, (10,)), raises=InputError, why="1-D image shape"),
    Case(R.frame_projector, ("eo", IO, 0.01, (10, 10)), raises=InputError, why="text EO"),
    Case(R.frame_projector, (EO, None, 0.01, (10, 10)), raises=InputError, why="no IO"),
    Case(lambda: R.frame_projector(EO, IO, 0.01, (11, 11))([20.0], [20.0], [2000.0]), raises=None,
         why="a point above (behind) the camera gets a far position",
         check=lambda rc: rc[0][0] < -1e8 and rc[1][0] < -1e8),
    # orthorectify
    Case(R.orthorectify, (IMG, VERTICAL, DEM, GRID, R.RasterGrid(100.0, 40.0, 1.0, (2, 2))),
         raises=InputError, match="missing area", why="DEM not covering the ortho grid"),
    Case(R.orthorectify, (IMG, WRONG_SHAPE, DEM, GRID, R.RasterGrid(5.0, 35.0, 1.0, (2, 2))),
         raises=InputError, match="shape", why="a sensor model returning the wrong shape"),
    Case(R.orthorectify, (IMG, "not callable", DEM, GRID, GRID), raises=InputError, why="no sensor model"),
    Case(R.orthorectify, (IMG, VERTICAL, DEM, GRID, (0, 0)), raises=InputError, why="a tuple for the grid"),
    Case(R.orthorectify, (IMG, VERTICAL, DEM, GRID, R.RasterGrid(5.0, 35.0, 1.0, (2, 2)), "area"),
         raises=InputError, why="unknown method"),
    # §7.2 central projection
    Case(R.rectify_homography, (IMG, np.zeros((3, 3)), (2, 2)), raises=InputError, match="singular",
         why="zero homography"),
    Case(R.rectify_homography, (IMG, np.eye(2), (2, 2)), raises=InputError, why="2 × 2 matrix"),
    Case(R.rectify_homography, (IMG, np.full((3, 3), NAN), (2, 2)), raises=InputError, why="NaN H"),
    Case(R.rectify_homography, (IMG, np.eye(3), (0, 2)), raises=InputError, why="empty output"),
    Case(R.rectify_homography, (IMG, [[0, 0, 1], [0, 1, 0], [1, 0, 0]], (2, 2)), raises=None,
         why="the line at infinity crosses the output", check=lambda out: bool(np.isnan(out[:, 0]).all())),
    Case(R.rectify_to_horizontal, (IMG, np.ones((3, 3)), 100.0, 0.01), raises=InputError,
         why="A is not a rotation"),
    Case(R.rectify_to_horizontal, (IMG, np.eye(3), -100.0, 0.01), raises=InputError, why="negative f"),
    Case(R.rectify_to_horizontal, (IMG, np.eye(3), 100.0, NAN), raises=InputError, why="NaN pixel size"),
    Case(R.rectify_to_horizontal, (IMG, np.diag([1.0, -1.0, -1.0]), 100.0, 0.01), raises=None,
         why="a camera looking up: no ray reaches, all fill", check=lambda out: bool(np.isnan(out).all())),
    # §7.3
    Case(R.ortho_pixel_size, (0.0, 10000), raises=InputError, why="zero pixel"),
    Case(R.ortho_pixel_size, (0.01, NAN), raises=InputError, why="NaN scale"),
    Case(R.geodetic_to_geocentric, (2.0, 0.0, 0.0), raises=InputError, match="π/2", why="latitude > π/2"),
    Case(R.geodetic_to_geocentric, (55.0, 37.0, 0.0), raises=InputError, why="degrees passed"),
    Case(R.geodetic_to_geocentric, (0.5, 0.5, NAN), raises=InputError, why="NaN height"),
    Case(R.geodetic_to_geocentric, (0.5, 0.5, 0.0, "Krassowsky"), raises=InputError, match="unknown",
         why="unknown ellipsoid"),
    Case(R.geodetic_to_geocentric, (0.5, 0.5, 0.0, (6378245.0, 0.5)), raises=InputError, why="1/f < 1"),
    Case(R.geodetic_to_geocentric, ([0.1, 0.2], [0.1, 0.2, 0.3], 0.0), raises=InputError,
         why="mismatched arrays"),
    Case(R.geocentric_to_geodetic, (0.0, 0.0, 0.0), raises=InputError, match="centre", why="the centre"),
    Case(R.geocentric_to_geodetic, (INF, 0.0, 0.0), raises=InputError, why="inf X"),
    Case(R.geocentric_to_geodetic, (0.0, 0.0, 6356751.9), raises=None, why="the pole (p = 0)",
         check=lambda blh: abs(blh[0] - np.pi / 2) < 1e-12
         and abs(blh[2] - (6356751.9 - 6378136.5 * (1 - 1 / 298.2564151))) < 1e-6),
    Case(R.topocentric_matrix, (NAN, 0.0), raises=InputError, why="NaN latitude"),
    Case(R.topocentric_matrix, ([0.1, 0.2], 0.0), raises=InputError, why="two origins"),
    Case(R.geocentric_to_topocentric, (0.0, 0.0, 0.0, (0.1, 0.2)), raises=InputError, why="origin without H"),
    Case(R.geocentric_to_topocentric, (1e6, 1e6, 6e6, (NAN, 0.2, 0.0)), raises=InputError, why="NaN origin"),
    Case(R.topocentric_to_geocentric, (NAN, 0.0, 0.0, ORIGIN), raises=InputError, why="NaN x"),
    Case(R.topocentric_to_geocentric, (0.0, 0.0, 0.0, "origin"), raises=InputError, why="text origin"),
    # §7.4
    Case(R.map_tolerance, (0,), raises=InputError, why="zero scale"),
    Case(R.map_tolerance, (2000, -0.3), raises=InputError, why="negative tolerance"),
    Case(R.admissible_height, (100.0, 0.0, 0.6), raises=InputError, why="r = 0 (the principal point)"),
    Case(R.admissible_height, (100.0, 50.0, NAN), raises=InputError, why="NaN tolerance"),
    Case(R.relief_displacement, (-5.0, 1.0, 100.0), raises=InputError, why="negative r"),
    Case(R.relief_displacement, ([1.0, 2.0], [1.0, 2.0, 3.0], 100.0), raises=InputError, why="mismatched r, h"),
    Case(R.relief_displacement, (5.0, 1.0, 0.0), raises=InputError, why="zero f"),
    # §7.7
    Case(R.MonoplotResult, (np.zeros((1, 3)), np.array([2]), []), raises=None, why="a plain record",
         check=lambda r: r.XYZ.shape == (1, 3)),
    Case(R.monoplot, ([[0.0, 0.0]], EO, IO, DEM, GRID), {"z_start": NAN}, raises=InputError, why="NaN start"),
    Case(R.monoplot, ([[NAN, 0.0]], EO, IO, DEM, GRID), raises=InputError, why="NaN image point"),
    Case(R.monoplot, (np.zeros((0, 2)), EO, IO, DEM, GRID), raises=InputError, why="no points"),
    Case(R.monoplot, ([[0.0, 0.0]], EO, IO, np.zeros((3, 3)), GRID), raises=InputError, why="DEM ≠ grid"),
    Case(R.monoplot, ([[0.0, 0.0]], EO, IO, np.full((4, 4), NAN), GRID), raises=InputError,
         why="an all-void DEM"),
    Case(R.monoplot, ([[50.0, 0.0]], EO, IO, DEM, GRID), raises=InputError, match="does not cover",
         why="ray outside the DEM"),
    Case(R.monoplot, ([[0.0, 0.0]], EO, IO, DEM, GRID), {"max_iter": 0}, raises=InputError, why="no iterations"),
    Case(R.monoplot, ([[0.0, 0.0]], EO, IO, DEM, GRID), {"tol": -1.0}, raises=InputError, why="negative tol"),
    Case(R.monoplot, ([[0.0, 0.0]], EO, IO, DEM, GRID), {"z_start": 2000.0}, raises=DegenerateGeometryError,
         why="start height above the camera"),
    Case(R.monoplot, ([[50.0, 0.0]], ExteriorOrientation(0.0, 0.0, 2000.0), IO, STEEP, BIG),
         {"z_start": 1100.0, "max_iter": 20}, raises=ConvergenceError, why="terrain steeper than the ray"),
    # mosaics
    Case(R.cutline_boundary, (G1, [[1.0, 0.0], [1.0, 2.0]]), raises=InputError, match="span",
         why="cutline shorter than the grid"),
    Case(R.cutline_boundary, (G1, [[1.0, 0.0], [2.0, 5.0], [1.0, 3.0]]), raises=InputError,
         match="monoton", why="cutline turning back in Y"),
    Case(R.cutline_boundary, (G1, [[1.0, 0.0]]), raises=InputError, why="one node"),
    Case(R.cutline_boundary, (G1, [[NAN, 0.0], [1.0, 4.0]]), raises=InputError, why="NaN node"),
    Case(R.cutline_boundary, ((0, 0), LINE), raises=InputError, why="a tuple for the grid"),
    Case(R.mosaic, ([np.zeros((4, 4))], [G1], LINE), raises=InputError, why="one orthophoto"),
    Case(R.mosaic_grid, ([],), raises=InputError, why="no grids"),
    Case(R.mosaic_grid, ([G1, "grid"],), raises=InputError, why="not a grid"),
    Case(R.mosaic_grid, ([G1, R.RasterGrid(2.0, 4.0, 2.0, (4, 4))],), raises=InputError, why="two pixel sizes"),
    Case(R.mosaic_grid, ([G1, R.RasterGrid(G1.x0 + 0.3 * G1.dx, G1.y0, G1.pixel_size, G1.shape)],),
         raises=InputError, match="lattice", why="origin off the lattice"),
    Case(R.mosaic, (np.zeros((2, 4, 4)), [G1, G2], LINE), raises=InputError, why="a 3-D array"),
    Case(R.mosaic, ([np.zeros((4, 4)), np.zeros((3, 4))], [G1, G2], LINE), raises=InputError,
         why="ortho ≠ its grid"),
    Case(R.mosaic, ([np.zeros((4, 4)), np.zeros((4, 4))], [G1, R.RasterGrid(2.0, 4.0, 2.0, (4, 4))], LINE),
         raises=InputError, match="resolution", why="different pixel sizes"),
    Case(R.mosaic, ([np.zeros((4, 4)), np.zeros((4, 4))], [G1, R.RasterGrid(2.5, 4.0, 1.0, (4, 4))], LINE),
         raises=InputError, match="lattice", why="origins off the lattice"),
    Case(R.mosaic, ([np.zeros((4, 4))] * 3, [G1, G2, G2], LINE), raises=InputError, why="3 orthos, 1 cutline"),
    Case(R.mosaic, ([np.zeros((4, 4)), np.zeros((4, 4, 3))], [G1, G2], LINE), raises=InputError,
         why="different band counts"),
    Case(R.mosaic, ([np.zeros((4, 4)), np.ones((4, 4))], [G1, G2], [[-10.0, 0.0], [-10.0, 4.0]]), raises=None,
         why="cutline west of everything: all from the second where it covers",
         check=lambda r: bool((r[0][:, 2:] == 1).all() and (r[0][:, :2] == 0).all())),
    # accuracy
    Case(R.AccuracyReport, (np.zeros(1), 0.0, 0.0, 0.5, True, None, None, 0.7, None), raises=None,
         why="a plain record", check=lambda r: r.passes),
    Case(R.ortho_accuracy, ([[0.0, 0.0]], [[0.0, 0.0], [1.0, 1.0]], 2000), raises=InputError,
         why="mismatched point counts"),
    Case(R.ortho_accuracy, (np.zeros((0, 2)), np.zeros((0, 2)), 2000), raises=InputError, why="no points"),
    Case(R.ortho_accuracy, ([[NAN, 0.0]], [[0.0, 0.0]], 2000), raises=InputError, why="NaN point"),
    Case(R.ortho_accuracy, ([[0.0, 0.0]], [[0.0, 0.0]], -2000), raises=InputError, why="negative scale"),
    Case(R.ortho_accuracy, ([[0.0, 0.0]], [[0.0, 0.0]], 2000), {"cutline_xy": [[0.0, 0.0]]}, raises=InputError,
         why="cutline points not a pair"),
    Case(R.apriori_accuracy, ([[0.0, 0.0]], [[20.0, 20.0]], EO, IO, DEM, GRID, 2000), raises=InputError,
         why="control points without Z"),
    Case(R.apriori_accuracy, ([[0.0, 0.0]], [[20.0, 20.0, NAN]], EO, IO, DEM, GRID, 2000), raises=InputError,
         why="NaN control height"),
]


@pytest.mark.parametrize("case", CASES, ids=lambda c: c.id)
def test_bad_input(case):
    check_case(case)
