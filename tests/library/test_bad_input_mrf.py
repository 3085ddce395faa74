"""Bad-input catalogue for photolib.mrf (the MRF terrain paper): NaN, shapes, textureless windows, borders."""

import numpy as np
import pytest

from catalogue import INF, NAN, Case, check_case, finite
from photolib import mrf
from photolib.camera import InteriorOrientation
from photolib.errors import DegenerateGeometryError, InputError, PointBehindCameraError

RNG = np.random.default_rng(0)
IMG = RNG.random((20, 30))
FLAT = np.full((20, 30), 0.5)
WITH_NAN = IMG.copy()
WITH_NAN[3, 4] = NAN
VOL = RNG.uniform(-1, 1, (3, 4, 5))
E = np.eye(3)
IO = InteriorOrientation(100.0)
XY5 = RNG.uniform(-50, 50, (6, 2))
PO = mrf.PairOrientation(0, 0, 0, 0, 0, 0, 0, E, E, np.zeros(3), np.array([4.0, 0, 0]), 100.0)
M3 = np.array([[0.0, 0, 0], [10, 0, 1], [0, 10, -1]])

CASES = [
    # correlation_coefficient
    Case(mrf.correlation_coefficient, (np.ones((3, 3)), IMG[:3, :3]), raises=DegenerateGeometryError,
         why="textureless window"),
    Case(mrf.correlation_coefficient, (IMG[:3, :3], IMG[:3, :4]), raises=InputError, why="different shapes"),
    Case(mrf.correlation_coefficient, (np.full((3, 3), NAN), IMG[:3, :3]), raises=InputError, why="NaN"),
    Case(mrf.correlation_coefficient, ([1.0], [2.0]), raises=InputError, why="one pixel"),
    # correlation_volume
    Case(mrf.correlation_volume, (WITH_NAN, IMG, [0, 1]), raises=InputError, why="NaN pixel"),
    Case(mrf.correlation_volume, (IMG, IMG, [0, 1], 4), raises=InputError, why="even window"),
    Case(mrf.correlation_volume, (IMG, IMG, [0, 0.5]), raises=InputError, why="fractional parallax"),
    Case(mrf.correlation_volume, (IMG, IMG, []), raises=InputError, why="no parallaxes"),
    Case(mrf.correlation_volume, (IMG[:3, :3], IMG, [0], 5), raises=InputError, why="image smaller than the window"),
    Case(mrf.correlation_volume, (IMG[0], IMG, [0]), raises=InputError, why="1-D image"),
    Case(mrf.correlation_volume, (FLAT, IMG, [0, 1]), raises=None, why="textureless: NaN, never a confident r",
         check=lambda r: bool(np.all(np.isnan(r)))),
    Case(mrf.correlation_volume, (IMG, IMG, [100]), raises=None, why="every window off the right image: NaN",
         check=lambda r: bool(np.all(np.isnan(r)))),
    # find_overlap_shift
    Case(mrf.find_overlap_shift, (FLAT, FLAT), raises=DegenerateGeometryError, why="textureless images"),
    Case(mrf.find_overlap_shift, (IMG, WITH_NAN), raises=InputError, why="NaN pixel"),
    Case(mrf.find_overlap_shift, (IMG, IMG, -1), raises=InputError, why="negative max_shift"),
    Case(mrf.find_overlap_shift, (IMG, IMG, None, 0.0), raises=InputError, why="zero min_overlap"),
    Case(mrf.find_overlap_shift, (IMG, IMG), raises=None, why="identical images: zero shift",
         check=lambda s: s[:2] == (0, 0)),
    # parallax_count
    Case(mrf.parallax_count, (100.0, 200.0, 2000.0, 300, 2000.0, 30000), raises=InputError, why="h_max < h_min"),
    Case(mrf.parallax_count, (200.0, 100.0, 0.0, 300, 2000.0, 30000), raises=InputError, why="zero base"),
    Case(mrf.parallax_count, (NAN, 100.0, 2000.0, 300, 2000.0, 30000), raises=InputError, why="NaN height"),
    Case(mrf.parallax_count, (200.0, 100.0, 2000.0, -300, 2000.0, 30000), raises=InputError, why="negative dpi"),
    # winner_takes_all
    Case(mrf.winner_takes_all, (VOL, [0, 1]), raises=InputError, why="parallax list of another length"),
    Case(mrf.winner_takes_all, (VOL[0], [0, 1, 2]), raises=InputError, why="2-D volume"),
    Case(mrf.winner_takes_all, (np.full((3, 4, 5), INF), [0, 1, 2]), raises=InputError, why="inf"),
    Case(mrf.winner_takes_all, (np.full((3, 4, 5), NAN), [0, 1, 2]), raises=None,
         why="all undefined: NaN estimate, not a guess", check=lambda out: bool(np.all(np.isnan(out[0])))),
    # mrf_energy
    Case(mrf.mrf_energy, (np.full((4, 5), 0.5), VOL, [0, 1, 2]), raises=InputError, why="value not a candidate"),
    Case(mrf.mrf_energy, (np.zeros((3, 5)), VOL, [0, 1, 2]), raises=InputError, why="map of another shape"),
    Case(mrf.mrf_energy, (np.zeros((4, 5)), VOL, [0, 1, 2], 1.0, 1.0), raises=InputError, why="b > 0"),
    Case(mrf.mrf_energy, (np.zeros((4, 5)), VOL, [0, 1, 2], NAN), raises=InputError, why="NaN a"),
    # gibbs_relaxation
    Case(mrf.gibbs_relaxation, (VOL, [0, 1, 2]), {"b": 0.5}, raises=InputError, match="negative",
         why="the printed sign of b"),
    Case(mrf.gibbs_relaxation, (VOL, [0, 1, 2]), {"sweeps": 5, "burn_in": 5}, raises=InputError,
         why="burn-in not below sweeps"),
    Case(mrf.gibbs_relaxation, (VOL, [0, 1, 2]), {"seed": -1}, raises=InputError, why="negative seed"),
    Case(mrf.gibbs_relaxation, (VOL, [0, 1, 2]), {"a": -1.0}, raises=InputError, why="negative a"),
    Case(mrf.gibbs_relaxation, (VOL, [0, 1, 2]), {"initial": np.full((4, 5), 7.0)}, raises=InputError,
         why="start values not candidates"),
    Case(mrf.gibbs_relaxation, (np.full((3, 4, 5), NAN), [0, 1, 2]), {"sweeps": 3, "burn_in": 1}, raises=None,
         why="all undefined (textureless): a flat result of low confidence",
         check=lambda res: bool(np.all(res.confidence < 1.0 + 1e-12)) and finite(res.parallax)),
    # direction_cosines, direction_cosine_angles, base_direction
    Case(mrf.direction_cosines, (NAN, 0.0, 0.0), raises=InputError, why="NaN angle"),
    Case(mrf.direction_cosines, ("a", 0.0, 0.0), raises=InputError, why="text"),
    Case(mrf.direction_cosine_angles, (2 * E,), raises=InputError, why="not a rotation"),
    Case(mrf.direction_cosine_angles, (mrf.direction_cosines(0.2, np.pi / 2, 0.1),), raises=DegenerateGeometryError,
         why="ω = 90°"),
    Case(mrf.base_direction, (np.ones((3, 3)), 0.0, 0.0), raises=InputError, why="A_left not a rotation"),
    Case(mrf.base_direction, (E, NAN, 0.0), raises=InputError, why="NaN angle"),
    # orient_pair
    Case(mrf.orient_pair, (XY5[:4], XY5[:4], IO), raises=InputError, why="4 points"),
    Case(mrf.orient_pair, (XY5, XY5, "camera"), raises=InputError, why="io not an InteriorOrientation"),
    Case(mrf.orient_pair, (XY5, XY5, IO, 0.0), raises=InputError, why="zero base length"),
    Case(mrf.orient_pair, (XY5, XY5, IO), raises=DegenerateGeometryError, why="identical images: zero base"),
    # reduce_to_horizontal, intersect_horizontal, parallax_to_model
    Case(mrf.reduce_to_horizontal, ([[1.0, NAN]], 100.0, E), raises=InputError, why="NaN"),
    Case(mrf.reduce_to_horizontal, ([[1.0, 2.0]], 0.0, E), raises=InputError, why="f = 0"),
    Case(mrf.reduce_to_horizontal, ([[1.0, 2.0]], 100.0, mrf.direction_cosines(0.0, np.pi, 0.0)),
         raises=PointBehindCameraError, why="ray above the horizon"),
    Case(mrf.intersect_horizontal, ([[1.0, 2.0]], [[1.0, 2.0]], [4.0, 0, 0], 100.0), raises=DegenerateGeometryError,
         why="zero parallax"),
    Case(mrf.intersect_horizontal, ([[1.0, 2.0]], [[3.0, 2.0]], [4.0, 0, 0], 100.0), raises=PointBehindCameraError,
         why="intersection behind the cameras"),
    Case(mrf.intersect_horizontal, ([[1.0, 2.0]], [[3.0, 2.0], [1, 1]], [4.0, 0, 0], 100.0), raises=InputError,
         why="different counts"),
    Case(mrf.intersect_horizontal, ([[1.0, 2.0]], [[-3.0, 2.0]], [0.0, 4.0, 0], 100.0),
         raises=DegenerateGeometryError, why="base along y"),
    Case(mrf.parallax_to_model, ([[60.0, 50.0]], [-40.0], "pair", 0.1, (50.0, 50.0)), raises=InputError,
         why="pair of another type"),
    Case(mrf.parallax_to_model, ([[60.0, 50.0]], [-40.0, 1.0], PO, 0.1, (50.0, 50.0)), raises=InputError,
         why="parallax count differs"),
    Case(mrf.parallax_to_model, ([[60.0, 50.0]], [NAN], PO, 0.1, (50.0, 50.0)), raises=InputError, why="NaN parallax"),
    Case(mrf.parallax_to_model, ([[60.0, 50.0]], [0.0], PO, 0.1, (50.0, 50.0)), raises=DegenerateGeometryError,
         why="zero parallax"),
    # convergence_rotation, orient_model
    Case(mrf.convergence_rotation, ([[1.0, 2.0]], 0.1), raises=InputError, why="2-D points"),
    Case(mrf.convergence_rotation, ([[1.0, 2.0, 3.0]], NAN), raises=InputError, why="NaN angle"),
    Case(mrf.orient_model, (M3[:2], M3[:2]), raises=InputError, why="two points: 6 equations"),
    Case(mrf.orient_model, (M3, np.where([[1, 1, 1], [1, 1, 1], [0, 0, 0]], M3, NAN),
                            np.array([[1, 1, 1], [1, 1, 1], [0, 0, 0]], bool)), raises=InputError,
         why="2 full points only: 6 equations"),
    Case(mrf.orient_model, (np.array([[0.0, 0, 0], [1, 1, 1], [2, 2, 2]]), np.array([[0.0, 0, 0], [1, 1, 1], [2, 2, 2]])),
         raises=DegenerateGeometryError, why="collinear control"),
    Case(mrf.orient_model, (M3, np.full((3, 3), NAN)), raises=InputError, why="NaN control"),
]


@pytest.mark.parametrize("case", CASES, ids=lambda c: c.id)
def test_bad_input(case):
    check_case(case)
