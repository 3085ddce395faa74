"""Bad-input catalogue for photolib.planning (Chapter 10): impossible plans, bad DEMs, bad angles."""

import math

import numpy as np
import pytest

from catalogue import INF, NAN, Case, check_case
from photolib import planning as P
from photolib.errors import DegenerateGeometryError, InputError
from photolib.rectify import RasterGrid

_FLAT, _GRID = P.surface_dem(lambda X, Y: 0 * X + 100.0, (-1000, -1000, 3000, 1000), 50.0)
_STRIP = dict(altitude=1100.0, base=400.0, f=100.0, pixel_size=0.01, sensor=(10000, 10000), samples=10)
_BLOCK = dict(f=100.0, pixel_size=0.005, sensor=(10000, 10000), gsd=0.1)


def _strip(**kw):
    args = dict(_STRIP)
    args.update(kw)
    return args


def _block(**kw):
    args = dict(_BLOCK)
    args.update(kw)
    return args


CASES = [
    # GSD
    Case(P.ground_sample_distance, (0.0, 100.0, 1000.0), why="zero pixel", raises=InputError),
    Case(P.ground_sample_distance, (0.005, NAN, 1000.0), why="NaN focal length", raises=InputError),
    Case(P.ground_sample_distance, (0.005, 100.0, -10.0), why="negative height", raises=InputError),
    Case(P.ground_sample_distance, ("a", 100.0, 10.0), why="a string", raises=InputError),
    Case(P.flying_height_for_gsd, (INF, 0.005, 100.0), why="infinite GSD", raises=InputError),
    Case(P.flying_height_for_gsd, (0.1, 0.005, 0.0), why="zero focal length", raises=InputError),
    # block
    Case(P.plan_block, (1000.0, 1000.0), _block(forward_overlap=1.0), why="forward overlap 100 %",
         raises=InputError, match="100 %"),
    Case(P.plan_block, (1000.0, 1000.0), _block(side_overlap=1.5), why="side overlap above 100 %",
         raises=InputError, match="100 %"),
    Case(P.plan_block, (1000.0, 1000.0), _block(forward_overlap=-0.1), why="negative overlap", raises=InputError),
    Case(P.plan_block, (1000.0, 1000.0), _block(forward_overlap=0.3), why="stereo strip with p < 50 %",
         raises=InputError, match="50 %"),
    Case(P.plan_block, (0.0, 1000.0), _block(), why="zero length", raises=InputError),
    Case(P.plan_block, (1000.0, NAN), _block(), why="NaN width", raises=InputError),
    Case(P.plan_block, (1000.0, 1000.0), _block(sensor=(0, 100)), why="sensor without pixels", raises=InputError),
    Case(P.plan_block, (1000.0, 1000.0), _block(sensor=(100,)), why="sensor of one number", raises=InputError),
    Case(P.plan_block, (1000.0, 1000.0), _block(flying_height=500.0), why="both gsd and height", raises=InputError),
    Case(P.plan_block, (1000.0, 1000.0), _block(speed=0.0), why="zero speed", raises=InputError),
    Case(P.plan_block, (10.0, 10.0), _block(), why="block smaller than one footprint: one strip, one model",
         raises=None, check=lambda p: p.n_strips == 1 and p.images_per_strip == 2),
    Case(P.FlightPlan, (1000.0, 1000.0, 0.1, 1000.0, 1000.0, 0.6, 0.3, 400.0, 700.0, 1, 2, 2, NAN,
                        np.array([0.0]), np.array([0.0, 400.0])), why="a hand-made plan lists its centres",
         raises=None, check=lambda p: p.exposure_centres().tolist() == [[0.0, 0.0], [400.0, 0.0]]),
    # relief
    Case(P.strip_over_relief, (_FLAT, _GRID, (0, 0), (800, 0)), _strip(altitude=50.0),
         why="camera below the terrain", raises=DegenerateGeometryError),
    Case(P.strip_over_relief, (_FLAT, _GRID, (0, 0), (800, 0)), _strip(altitude=1e5),
         why="footprints leave the DEM", raises=InputError, match="leave the DEM"),
    Case(P.strip_over_relief, (_FLAT, _GRID, (0, 0), (0, 0)), _strip(), why="start equals end",
         raises=InputError),
    Case(P.strip_over_relief, (_FLAT, _GRID, (0, NAN), (800, 0)), _strip(), why="NaN start", raises=InputError),
    Case(P.strip_over_relief, (_FLAT[:, :-1], _GRID, (0, 0), (800, 0)), _strip(), why="DEM and grid differ",
         raises=InputError),
    Case(P.strip_over_relief, (_FLAT, "grid", (0, 0), (800, 0)), _strip(), why="not a grid", raises=InputError),
    Case(P.strip_over_relief, (np.where(np.arange(_FLAT.shape[1]) == 40, np.nan, _FLAT), _GRID, (0, 0), (800, 0)),
         _strip(), why="a void under the footprints", raises=InputError),
    Case(P.strip_over_relief, (_FLAT, _GRID, (0, 0), (800, 0)), _strip(base=0.0), why="zero base", raises=InputError),
    Case(P.strip_over_relief, (_FLAT, _GRID, (0, 0), (800, 0)), _strip(samples=2), why="too few rays",
         raises=InputError),
    Case(P.StripOverRelief, (np.zeros((1, 2)), 1.0, np.ones(1), np.ones(1), np.ones(1), np.zeros(0), NAN, -1,
                             np.zeros((1, 4, 2))), why="a single image has no overlap", raises=None,
         check=lambda s: math.isnan(s.min_overlap)),
    Case(P.surface_dem, (lambda X, Y: X, (0, 0, -1, 1), 1.0), why="empty bounds", raises=InputError),
    Case(P.surface_dem, (lambda X, Y: X * np.nan, (0, 0, 10, 10), 1.0), why="NaN heights", raises=InputError),
    Case(P.surface_dem, (lambda X, Y: X[:1], (0, 0, 10, 10), 1.0), why="wrong shape", raises=InputError),
    Case(P.surface_dem, (3.0, (0, 0, 10, 10), 1.0), why="not callable", raises=InputError),
    Case(P.surface_dem, (lambda X, Y: 5.0, (0, 0, 10, 10), 1.0), why="a constant surface broadcasts",
         raises=None, check=lambda r: r[0].shape == (10, 10) and bool(np.all(r[0] == 5.0))),
    Case(P.dem_to_local, (np.zeros((3, 3)), RasterGrid(40, 40, 0.01, (3, 3)), "EPSG:4326"),
         {"bounds": (-1e6, -1e6, 1e6, 1e6)}, why="bounds outside the DEM", raises=InputError, match="inside"),
    Case(P.dem_to_local, (np.zeros((3, 4)), RasterGrid(40, 40, 0.01, (3, 3)), "EPSG:4326"),
         why="DEM and grid differ", raises=InputError),
    Case(P.dem_to_local, (np.zeros((3, 3)), RasterGrid(40, 40, 0.01, (3, 3)), "EPSG:4326"),
         {"spacing": 5000.0}, why="spacing larger than the DEM", raises=InputError),
    # markers
    Case(P.gcp_marker, (0.0,), why="zero GSD", raises=InputError),
    Case(P.gcp_marker, (NAN,), why="NaN GSD", raises=InputError),
    Case(P.check_marker, (0.2, 0.5, 0.05), why="arm width wider than the cross", raises=InputError),
    Case(P.check_marker, (-0.2, 0.1, 0.05), why="negative arm", raises=InputError),
    Case(P.MarkerDesign, (0.1, 0.4, 2.0, 0.2, 0.3, 0.8), why="plain record", raises=None,
         check=lambda m: m.arm_min == 0.4),
    Case(P.MarkerCheck, (3.0, 2.0, 6.0, False, True, False, False), why="plain record", raises=None,
         check=lambda m: not m.ok),
    # IMU
    Case(P.imu_ground_error, (0.1, 0.1, 0.1, 1000.0, math.pi / 2), why="half field of 90°", raises=InputError),
    Case(P.imu_ground_error, (-1e-4, 0.0, 0.0, 1000.0), why="negative sigma", raises=InputError),
    Case(P.imu_ground_error, (0.005, 0.005, 0.01, 1000.0, 45.0), why="degrees given", raises=InputError,
         match="degrees"),
    Case(P.imu_ground_error, (0.0, 0.0, 0.0, 0.0), why="zero height", raises=InputError),
    Case(P.ImuGroundError, (0.0, 0.0, 0.0, 0.0, 0.0, 0.0), why="plain record", raises=None,
         check=lambda e: e.total_edge == 0.0),
    Case(P.skip_aerial_triangulation, (NAN, 0.0, 0.0), {"relief_from_lidar": True, "plan_scale": 2000},
         why="NaN sigma", raises=InputError),
    Case(P.skip_aerial_triangulation, (0.0, 0.0, 0.0), {"relief_from_lidar": "yes", "plan_scale": 2000},
         why="flag not a bool", raises=InputError),
    Case(P.skip_aerial_triangulation, (0.0, 0.0, 0.0), {"relief_from_lidar": True, "plan_scale": 0},
         why="zero scale", raises=InputError),
    Case(P.ATDecision, (False, ("x",)), why="plain record", raises=None, check=lambda d: not d.skip),
]


@pytest.mark.parametrize("case", CASES, ids=lambda c: c.id)
def test_bad_input(case):
    if case.function is P.dem_to_local:
        pytest.importorskip("pyproj")
    check_case(case)
