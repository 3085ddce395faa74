"""Bad-input catalogue for photolib.sgm (Chapter 6, §6.4–6.5): NaN pixels, mismatched sizes,
non-rectified pairs, empty or non-positive disparity ranges, bad penalties, grids and cameras."""

import numpy as np
import pytest
from scipy import ndimage as ndi

from catalogue import NAN, Case, check_case, finite
from photolib import sgm
from photolib.camera import ExteriorOrientation, InteriorOrientation
from photolib.errors import DegenerateGeometryError, InputError, PointBehindCameraError

rng = np.random.default_rng(5)
IMG = ndi.gaussian_filter(rng.uniform(0, 255, (40, 64)), 0.8)
LEFT = np.roll(IMG, 3, axis=1)
NANIMG = IMG.copy()
NANIMG[5, 5] = NAN
SHIFTED = ndi.shift(IMG, (3.0, 0.0), mode="nearest")           # 3 px vertical parallax
VOL = rng.uniform(0, 5, (6, 7, 4)).astype(np.float32)
NANVOL = VOL.copy()
NANVOL[1, 1, 1] = NAN
IO = InteriorOrientation(10.0)
EO1, EO2 = ExteriorOrientation(0, 0, 100), ExteriorOrientation(10, 0, 100)
AX = np.arange(-5, 6.0)
ZL = np.array([0.0, 1.0, 2.0])
SMALL = rng.uniform(0, 255, (50, 50))

CASES = [
    # cost_volume
    Case(sgm.cost_volume, (LEFT, IMG[:, :-1], 5), why="images of different sizes", raises=InputError, match="same size"),
    Case(sgm.cost_volume, (NANIMG, IMG, 5), why="NaN pixels", raises=InputError, match="NaN"),
    Case(sgm.cost_volume, (LEFT, IMG, 0), why="disparity range ≤ 0", raises=InputError, match="range"),
    Case(sgm.cost_volume, (LEFT, IMG, 5), dict(min_disparity=5), why="max = min", raises=InputError),
    Case(sgm.cost_volume, (LEFT, IMG, 64), why="range as wide as the image", raises=InputError, match="width"),
    Case(sgm.cost_volume, (LEFT, IMG, 5), dict(min_disparity=-2), why="negative disparity", raises=InputError),
    Case(sgm.cost_volume, (LEFT, IMG, 5.5), why="fractional range", raises=InputError),
    Case(sgm.cost_volume, (LEFT, IMG, 5), dict(method="ssd"), why="unknown cost", raises=InputError),
    Case(sgm.cost_volume, (LEFT, IMG, 5), dict(method="census", window=4), why="even window", raises=InputError),
    Case(sgm.cost_volume, (LEFT[0], IMG[0], 5), why="1-D images", raises=InputError),
    Case(sgm.cost_volume, (np.zeros((0, 5)), np.zeros((0, 5)), 2), why="empty images", raises=InputError),
    Case(sgm.cost_volume, (np.full((10, 20), 7.0), np.full((10, 20), 7.0), 3), dict(method="ncc"),
         raises=None, why="textureless: NCC cost is the neutral 1, not a confident match",
         check=lambda C: np.allclose(C[:, 3:], 1.0)),
    # census
    Case(sgm.census_transform, (IMG, 9), why="81 bits do not fit", raises=InputError, match="bits"),
    Case(sgm.census_transform, (NANIMG,), why="NaN pixels", raises=InputError),
    # aggregation
    Case(sgm.aggregate_costs, (NANVOL, 1.0, 4.0), why="NaN costs", raises=InputError),
    Case(sgm.aggregate_costs, (VOL[0], 1.0, 4.0), why="2-D volume", raises=InputError),
    Case(sgm.aggregate_costs, (VOL, 5.0, 4.0), why="P2 < P1", raises=InputError, match="P2"),
    Case(sgm.aggregate_costs, (VOL, -1.0, 4.0), why="negative P1", raises=InputError),
    Case(sgm.aggregate_costs, (VOL, 1.0, 4.0), dict(paths=6), why="6 paths", raises=InputError),
    Case(sgm.aggregate_costs, (VOL, 1.0, 4.0), dict(p2_gamma=10.0), why="adaptive P2 without a guide",
         raises=InputError, match="guide"),
    Case(sgm.aggregate_costs, (VOL, 1.0, 4.0), dict(p2_gamma=10.0, guide=np.zeros((3, 3))),
         why="guide of another size", raises=InputError),
    Case(sgm.path_cost, (VOL, (0, 0), 1.0, 4.0), why="zero direction", raises=InputError),
    Case(sgm.path_cost, (VOL, (2, 0), 1.0, 4.0), why="step of 2", raises=InputError),
    Case(sgm.path_cost, (VOL, "x", 1.0, 4.0), why="direction not a pair", raises=InputError),
    Case(sgm.path_cost, (NANVOL, (1, 0), 1.0, 4.0), why="NaN costs", raises=InputError),
    # selection and checks
    Case(sgm.winner_takes_all, (NANVOL,), why="NaN costs", raises=InputError),
    Case(sgm.winner_takes_all, (VOL,), dict(subpixel="cubic"), why="unknown sub-pixel method", raises=InputError),
    Case(sgm.winner_takes_all, (np.zeros((2, 2, 1)),), raises=None, why="a single disparity: no refinement",
         check=lambda d: np.all(d == 0)),
    Case(sgm.right_disparity, (np.zeros((3, 3)),), why="2-D volume", raises=InputError),
    Case(sgm.left_right_check, (np.zeros((2, 3)), np.zeros((2, 4))), why="maps of different shapes", raises=InputError),
    Case(sgm.left_right_check, (np.full((2, 3), np.inf), np.zeros((2, 3))), why="inf disparity", raises=InputError),
    Case(sgm.left_right_check, (np.zeros((2, 3)), np.zeros((2, 3)), -1.0), why="negative tolerance", raises=InputError),
    Case(sgm.left_right_check, (np.full((2, 3), NAN), np.zeros((2, 3))), raises=None,
         why="all-NaN stays NaN", check=lambda d: np.isnan(d).all()),
    Case(sgm.fill_invalid, (np.zeros(3),), why="1-D map", raises=InputError),
    Case(sgm.fill_invalid, (np.array([[np.inf, 1.0]]),), why="inf", raises=InputError),
    Case(sgm.vertical_parallax, (IMG[:8, :8], IMG[:8, :8]), why="too small", raises=InputError),
    Case(sgm.vertical_parallax, (np.full((40, 64), 3.0), np.full((40, 64), 3.0)), why="textureless",
         raises=DegenerateGeometryError),
    Case(sgm.vertical_parallax, (LEFT, SHIFTED, 8), raises=None, why="3 px vertical shift measured",
         check=lambda dy: np.allclose(dy, 3.0, atol=0.5)),          # right(y + 3) = left(y)
    # the pipeline
    Case(sgm.semi_global_matching, (LEFT, SHIFTED, 8), why="non-rectified pair", raises=InputError,
         match="not rectified"),
    Case(sgm.semi_global_matching, (LEFT, IMG[:, :-2], 8), why="mismatched sizes", raises=InputError),
    Case(sgm.semi_global_matching, (NANIMG, IMG, 8), why="NaN pixels", raises=InputError),
    Case(sgm.semi_global_matching, (LEFT, IMG, -3), why="negative range", raises=InputError),
    Case(sgm.semi_global_matching, (LEFT, IMG, 8), dict(P1=10.0, P2=2.0), why="P2 < P1", raises=InputError),
    Case(sgm.semi_global_matching, (LEFT, IMG, 8), dict(median=2.5), why="fractional median size", raises=InputError),
    Case(sgm.semi_global_matching, (LEFT, IMG, 8), dict(subpixel="x"), why="unknown sub-pixel method", raises=InputError),
    Case(sgm.semi_global_matching, (LEFT, IMG, 8), raises=None, why="shifted pair: p = 3",
         check=lambda r: abs(np.nanmedian(r.disparity[:, 10:]) - 3) < 0.1),
    Case(sgm.SGMResult, (np.zeros((2, 2)), np.zeros((2, 2), bool), np.zeros((2, 2)), None, 0, 4), raises=None,
         why="a plain record", check=lambda r: r.max_disparity == 4),
    # points
    Case(sgm.disparity_to_points, (np.full((3, 3), NAN), EO1, EO2, IO, 0.01), why="no valid disparity",
         raises=DegenerateGeometryError),
    Case(sgm.disparity_to_points, (np.full((3, 3), np.inf), EO1, EO2, IO, 0.01), why="inf", raises=InputError),
    Case(sgm.disparity_to_points, (np.ones((3, 3)), EO1, EO2, IO, 0.0), why="zero pixel size", raises=InputError),
    Case(sgm.disparity_to_points, (np.ones((3, 3)), "eo", EO2, IO, 0.01), why="orientation of a wrong type",
         raises=InputError),
    Case(sgm.disparity_to_points, (np.ones((3, 3)), EO1, EO1, IO, 0.01), why="zero base",
         raises=DegenerateGeometryError),
    Case(sgm.disparity_to_points, (np.full((3, 3), -100.0), EO1, EO2, IO, 0.01), why="rays meet behind the cameras",
         raises=PointBehindCameraError),
    Case(sgm.disparity_to_points, (np.full((3, 3), 1000.0), EO1, EO2, IO, 0.01), raises=None,
         why="normal case", check=finite),
    # voxels
    Case(sgm.voxel_cost_volume, ([SMALL], [EO1], IO, 0.1, AX, AX, ZL), why="one image", raises=InputError, match="2"),
    Case(sgm.voxel_cost_volume, ([SMALL, SMALL], [EO1], IO, 0.1, AX, AX, ZL), why="fewer orientations", raises=InputError),
    Case(sgm.voxel_cost_volume, (SMALL, [EO1, EO2], IO, 0.1, AX, AX, ZL), why="a single array", raises=InputError),
    Case(sgm.voxel_cost_volume, ([SMALL, np.full((50, 50), NAN)], [EO1, EO2], IO, 0.1, AX, AX, ZL),
         why="NaN image", raises=InputError),
    Case(sgm.voxel_cost_volume, ([SMALL, SMALL], [EO1, EO2], IO, 0.1, AX, AX, np.array([0.0, 2.0, 3.0])),
         why="uneven Z step", raises=InputError, match="constant step"),
    Case(sgm.voxel_cost_volume, ([SMALL, SMALL], [EO1, EO2], IO, 0.1, AX, AX, np.array([1.0])),
         why="a single Z level", raises=InputError),
    Case(sgm.voxel_cost_volume, ([SMALL, SMALL], [EO1, EO2], IO, 0.1, AX, AX, ZL), dict(cost="census"),
         why="unknown voxel cost", raises=InputError),
    Case(sgm.voxel_cost_volume, ([SMALL, SMALL], [EO1, EO2], IO, 0.1, AX, AX, np.array([150.0, 151.0])),
         why="voxels above the cameras", raises=PointBehindCameraError),
    Case(sgm.voxel_cost_volume, ([SMALL, SMALL], [EO1, EO2], IO, 0.1, AX + 1e4, AX, ZL), raises=None,
         why="voxels outside every image get the largest cost",
         check=lambda C: np.allclose(C, np.ptp(SMALL))),
    Case(sgm.voxel_sgm, ([SMALL, SMALL], [EO1, EO2], IO, 0.1, AX, AX, ZL), dict(P1=3.0, P2=1.0),
         why="P2 < P1", raises=InputError),
    Case(sgm.voxel_sgm, ([SMALL, SMALL], [EO1, EO2], IO, -0.1, AX, AX, ZL), why="negative pixel size",
         raises=InputError),
    Case(sgm.VoxelSGMResult, (np.zeros((2, 2)), np.zeros((2, 2)), AX, AX, ZL), raises=None, why="a plain record",
         check=lambda r: r.Z.shape == (2, 2)),
]


@pytest.mark.parametrize("case", CASES, ids=lambda c: c.id)
def test_bad_input(case):
    check_case(case)
