"""Bad-input catalogue for the Hanzl §6 and §8–§10.1 additions: planning (§6), features filters (§8.2),
matching.quadratic_peak (§8.3), the Förstner options (§8.4), digital.normalized_image_coordinates (§10.1)."""

import numpy as np
import pytest

from catalogue import INF, NAN, Case, check_case
from photolib import digital, features as ft, matching, planning as P
from photolib.errors import DegenerateGeometryError, InputError

_IMG = np.arange(25.0).reshape(5, 5)
_X, _Y = np.meshgrid([-1.0, 0.0, 1.0], [-1.0, 0.0, 1.0])
_PEAK = 1.0 - _X ** 2 - _Y ** 2

CASES = [
    # §6 planning
    Case(P.diffraction_radius, (0.0,), why="zero f-number", raises=InputError),
    Case(P.diffraction_radius, (4.0, NAN), why="NaN wavelength", raises=InputError),
    Case(P.image_motion, (-1.0, 0.005, 10000), why="negative speed", raises=InputError),
    Case(P.image_motion, (50.0, 0.0, 10000), why="zero exposure time", raises=InputError),
    Case(P.image_motion, (50.0, 0.005, INF), why="infinite scale number", raises=InputError),
    Case(P.awar, ([1.0, 2.0], [50.0]), why="lengths differ", raises=InputError),
    Case(P.awar, ([0.0, 0.0], [50.0, 60.0]), why="no area", raises=InputError),
    Case(P.awar, ([1.0, -2.0], [50.0, 60.0]), why="negative area", raises=InputError),
    Case(P.photo_flight_plan, (153.0, 10000), {"forward_overlap": 100.0}, why="100 % overlap", raises=InputError),
    Case(P.photo_flight_plan, (153.0, 10000), {"side_overlap": 0.25 - 1}, why="negative overlap", raises=InputError),
    Case(P.photo_flight_plan, (0.0, 10000), why="zero camera constant", raises=InputError),
    Case(P.photo_flight_plan, (153.0, 10000), {"forward_overlap": 0.0}, why="no overlap is a valid plan",
         raises=None, check=lambda p: p.base == p.footprint),
    Case(P.PhotoFlightPlan, (1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 0.5), why="a hand-made plan", raises=None,
         check=lambda p: p.base == 4.0),
    Case(P.photo_scale_from_map, (-500,), why="negative map scale", raises=InputError),
    Case(P.photo_scale_from_map, ([500, NAN],), why="NaN map scale", raises=InputError),
    Case(P.photo_scale_from_map, (500,), {"constant": 0.0}, why="zero constant", raises=InputError),
    Case(P.target_sizes, (0,), why="zero scale number", raises=InputError),
    Case(P.TargetSizes, (1.0, 0.2, 0.3), why="a hand-made record", raises=None, check=lambda t: t.square_side == 0.3),
    Case(P.goniometer_distortion, ([1.0, 2.0], [0.1], 150.0), why="lengths differ", raises=InputError),
    Case(P.goniometer_distortion, ([0.0, 0.0], [0.0, 0.0], 150.0), why="all angles zero",
         raises=DegenerateGeometryError),
    Case(P.goniometer_distortion, ([1.0, 2.0], [0.1, 2.0], 150.0), why="angle beyond 90°", raises=InputError),
    Case(P.goniometer_distortion, ([1.0, 2.0], [0.01, 0.02], 150.0, "median"), why="unknown criterion",
         raises=InputError),
    Case(P.GoniometerCalibration, (0.0, 150.0, np.zeros(1), np.zeros(1), "lsq"), why="a hand-made record",
         raises=None, check=lambda g: g.c == 150.0),
    # §8.2 filters
    Case(ft.filter_image, (_IMG, "unknown"), why="unknown kernel name", raises=InputError, match="unknown kernel"),
    Case(ft.filter_image, (_IMG, [1.0, 2.0]), why="1-D kernel", raises=InputError),
    Case(ft.filter_image, (_IMG, [[NAN]]), why="NaN kernel", raises=InputError),
    Case(ft.filter_image, (_IMG, "mean"), {"border": "wrap"}, why="unknown border", raises=InputError),
    Case(ft.filter_image, (_IMG, "mean"), {"rounding": "up"}, why="unknown rounding", raises=InputError),
    Case(ft.filter_image, (_IMG, "mean"), {"border": "constant", "cval": NAN}, why="NaN cval", raises=InputError),
    Case(ft.filter_image, (np.ones((1, 1)), "mean"), why="a 1×1 image is padded", raises=None,
         check=lambda g: g.shape == (1, 1) and abs(g[0, 0] - 1.0) < 1e-12),
    Case(ft.median_filter, (_IMG, 4), why="even window", raises=InputError),
    Case(ft.median_filter, (np.array([[1.0, NAN]]),), why="NaN pixel", raises=InputError),
    Case(ft.edge_filter, (_IMG, "canny"), why="unknown operator", raises=InputError),
    Case(ft.second_difference_1d, ([1.0, 2.0],), why="too short a profile", raises=InputError),
    Case(ft.second_difference_1d, ([1.0, 2.0, 3.0],), {"ends": "wrap"}, why="unknown ends", raises=InputError),
    Case(ft.foerstner, (_IMG,), {"form": "area"}, why="unknown form", raises=InputError),
    Case(ft.interest_points, (_IMG, "foerstner"), {"selection": "best"}, why="unknown selection", raises=InputError),
    Case(ft.interest_points, (_IMG, "foerstner"), {"selection": "hanzl", "w_factor": -1.0},
         why="negative w factor", raises=InputError),
    # §8.3
    Case(matching.quadratic_peak, (np.ones((2, 3)),), why="grid smaller than 3×3", raises=InputError),
    Case(matching.quadratic_peak, (_X ** 2 - _Y ** 2,), why="saddle", raises=DegenerateGeometryError),
    Case(matching.quadratic_peak, (np.ones((3, 3)),), why="flat surface", raises=DegenerateGeometryError),
    Case(matching.quadratic_peak, (_PEAK,), {"offsets": ([0, 0, 1], [0, 1, 2])}, why="repeated offsets",
         raises=InputError),
    Case(matching.quadratic_peak, (1.0 - (_X - 5) ** 2 - _Y ** 2,), why="maximum outside the grid",
         raises=DegenerateGeometryError),
    # §10.1
    Case(digital.normalized_image_coordinates, ([1.0, 2.0], 100.0, np.eye(3), 2 * np.eye(3)),
         why="not a rotation", raises=InputError),
    Case(digital.normalized_image_coordinates, ([1.0, 2.0], 0.0, np.eye(3), np.eye(3)), why="zero c",
         raises=InputError),
    Case(digital.normalized_image_coordinates, ([1.0, 2.0, 3.0], 100.0, np.eye(3), np.eye(3)),
         why="three coordinates", raises=InputError),
    Case(digital.normalized_image_coordinates, ([100.0, 0.0], 100.0, np.eye(3),
                                                np.array([[0.0, 0.0, 1.0], [0.0, 1.0, 0.0], [-1.0, 0.0, 0.0]])),
         why="ray parallel to the normalised plane", raises=DegenerateGeometryError),
]


@pytest.mark.parametrize("case", CASES, ids=lambda c: c.id)
def test_bad_input(case):
    check_case(case)
