"""Bad-input catalogue for photolib.mockup and photolib.derivations.mockup (the Sementsov appendix)."""

import numpy as np
import pytest

from catalogue import INF, NAN, Case, check_case
from photolib import mockup as M
from photolib.derivations import mockup as DM
from photolib.errors import ConvergenceError, DegenerateGeometryError, InputError

GRID = M.planar_grid(1000, 50)
ST = M.MockupStation(np.radians([30.0, 0.0, 0.0]))
OBS = M.variant_mockup("2-1", seed=0)
OBS_01 = M.variant_mockup("0-1", seed=0)
GNSS = M.GnssCentre(0, [0.0, 0.0, 300.0], [0.1, 0.1, 0.3], "XYZ")
TRIPOD = M.tripod_mockup([0.005, 0.065, -0.04], sigma=0.0, half_size=1.6, step=0.4)


def _stats_ok(s):
    return np.allclose(s.mean, [2.0]) and np.allclose(s.sko, [1.0])


CASES = [
    # cameras, stations, images, observations
    Case(M.MockupCamera, (0.0,), raises=InputError, why="f = 0"),
    Case(M.MockupCamera, (3100.0, NAN), raises=InputError, why="NaN x0"),
    Case(M.MockupCamera, (3100.0, 0.0, 0.0, -10.0), raises=InputError, why="negative frame width"),
    Case(M.MockupCamera, ("3100",), raises=None, why="a numeric string is a number", check=lambda c: c.f == 3100.0),
    Case(M.MockupStation, ([0.1, 0.2],), raises=InputError, why="two angles"),
    Case(M.MockupStation, ([0.1, INF, 0.0],), raises=InputError, why="inf angle"),
    Case(M.MockupStation, ([0.0, 0.0, 0.0], -1), raises=InputError, why="negative camera index"),
    Case(M.MockupStation, ([0.0, 0.0, 0.0], 0, 1.5), raises=InputError, why="fractional centre index"),
    Case(M.MockupImage, (0, 0, [0, 1], np.zeros((3, 2))), raises=InputError, why="xy rows differ from ids"),
    Case(M.MockupImage, (0, 0, [0, 0], np.zeros((2, 2))), raises=InputError, why="repeated point id"),
    Case(M.MockupImage, (0, 0, [0.5, 1.0], np.zeros((2, 2))), raises=InputError, why="fractional ids"),
    Case(M.MockupImage, (0, 0, [0, 1], [[0, 0], [NAN, 1]]), raises=InputError, why="NaN coordinate"),
    Case(M.MockupImage, (0, 0, np.array([3, 1]), np.ones((2, 2))), raises=None, why="plain record",
         check=lambda im: im.point_ids.tolist() == [3, 1]),
    Case(M.MockupObservations, (GRID, OBS.cameras, OBS.centres, OBS.stations, OBS.images[:1], 0.5),
         raises=InputError, match="images but", why="fewer images than stations"),
    Case(M.MockupObservations, (GRID[:5], OBS.cameras, OBS.centres, OBS.stations, OBS.images, 0.5),
         raises=InputError, match="refers to point", why="point index outside the target"),
    Case(M.MockupObservations, (GRID, OBS.cameras, OBS.centres, OBS.stations, OBS.images, -1.0),
         raises=InputError, why="negative sigma"),
    Case(M.MockupObservations, (GRID, [], OBS.centres, OBS.stations, OBS.images, 0.5), raises=InputError,
         why="no cameras"),
    Case(M.MockupObservations, (GRID, OBS.cameras, OBS.centres, OBS.stations, OBS.images, 0.5), raises=None,
         why="the fields of a mock-up", check=lambda o: len(o.images) == 2),
    Case(M.GnssCentre, (0, [0, 0, 300.0], [0.1, 0.1, 0.3], "XW"), raises=InputError, why="unknown component"),
    Case(M.GnssCentre, (0, [0, 0, 300.0], [0.1, 0.1, 0.3], ""), raises=InputError, why="no component"),
    Case(M.GnssCentre, (0, [0, 0, 300.0], [0.1, 0.1, 0.0], "Z"), raises=InputError, why="σ = 0 for a known one"),
    Case(M.GnssCentre, (0, [0, NAN, 300.0], [0.1, 0.1, 0.3], "Z"), raises=InputError, why="NaN measurement"),
    Case(M.GnssCentre, (0, [0, 0, 300.0], [0.1, 0.1, 0.3], "ZX"), raises=None, why="components in any order",
         check=lambda g: g.known == "XZ"),
    # the §2.4 recipe
    Case(M.planar_grid, (0.0, 50.0), raises=InputError, why="zero size"),
    Case(M.planar_grid, (1000.0, -50.0), raises=InputError, why="negative step"),
    Case(M.planar_grid, (1000.0, 0.5), raises=InputError, match="10⁶", why="too many points"),
    Case(M.planar_grid, (1000.0, NAN), raises=InputError, why="NaN step"),
    Case(M.planar_grid, (1.0, 5.0), raises=None, why="step larger than the target: one point",
         check=lambda g: g.tolist() == [[0.0, 0.0, 0.0]]),
    Case(M.project_points, ([[0, 0]], [0, 0, 300.0], [0, 0, 0], M.NEX5), raises=InputError, why="2-D points"),
    Case(M.project_points, ([[0, 0, 0]], [0, 0], [0, 0, 0], M.NEX5), raises=InputError, why="2-vector centre"),
    Case(M.project_points, ([[0, 0, 0]], [0, 0, 300.0], [0, 0, 0], [-1.0, 0, 0]), raises=InputError, why="f < 0"),
    Case(M.project_points, ([[0, 0, 300.0]], [0, 0, 300.0], [0, 0, 0], M.NEX5), raises=None,
         why="a point at the centre projects to NaN", check=lambda r: bool(np.isnan(r[0]).all())),
    Case(M.tripod_centres, ([0, 0, 0], [[0, 0]], [0, 0, 0.1]), raises=InputError, why="two angles per image"),
    Case(M.tripod_centres, ([0, 0, 0], [[0, 0, 0]], [0, NAN, 0.1]), raises=InputError, why="NaN offset"),
    Case(M.tripod_centres, ([0, 0, 0], np.zeros((0, 3)), [0, 0, 0.1]), raises=None, why="no images",
         check=lambda S: S.shape == (0, 3)),
    Case(M.simulate_mockup, (GRID, [M.NEX5], [[0, 0, 300.0]], [ST]), {"sigma": -0.5}, raises=InputError,
         why="negative sigma"),
    Case(M.simulate_mockup, (GRID, [M.NEX5], [[0, 0, 300.0]], [M.MockupStation([0, 0, 0], camera=1)]),
         raises=InputError, match="camera 1", why="camera index outside the list"),
    Case(M.simulate_mockup, (GRID, [M.NEX5], [[0, 0, 300.0]], [M.MockupStation([np.pi, 0, 0])]),
         raises=InputError, match="sees 0", why="camera looking away from the target"),
    Case(M.simulate_mockup, (GRID, [M.NEX5], [[0, 0, 300.0]], [ST]), {"seed": -1}, raises=InputError,
         why="negative seed"),
    Case(M.simulate_mockup, (GRID, ["camera"], [[0, 0, 300.0]], [ST]), raises=InputError, why="not a camera"),
    Case(M.simulate_gnss, (OBS, "XYZ"), {"centre": 3}, raises=InputError, why="centre outside the mock-up"),
    Case(M.simulate_gnss, (OBS, "Q"), raises=InputError, why="unknown component"),
    Case(M.simulate_gnss, ("mock-up", "Z"), raises=InputError, why="not a mock-up"),
    Case(M.simulate_gnss, (OBS, "Z", [0.1, 0.1, -0.3]), raises=InputError, why="negative σ"),
    # the adjustment
    Case(M.calibrate_network, ("obs",), raises=InputError, why="not a mock-up"),
    Case(M.calibrate_network, (OBS,), {"targets": "free"}, raises=InputError, why="unknown targets"),
    Case(M.calibrate_network, (OBS,), {"gnss_mode": "soft"}, raises=InputError, why="unknown GNSS mode"),
    Case(M.calibrate_network, (OBS,), {"datum": "none"}, raises=InputError, why="unknown datum"),
    Case(M.calibrate_network, (OBS,), {"tripod": "yes"}, raises=InputError, why="tripod not a bool"),
    Case(M.calibrate_network, (OBS,), {"gnss": [GNSS], "targets": "plane"}, raises=InputError,
         why="GNSS with the plane mode"),
    Case(M.calibrate_network, (OBS,), {"gnss": [GNSS, GNSS]}, raises=InputError, match="twice",
         why="one centre measured twice"),
    Case(M.calibrate_network, (OBS,), {"gnss": [M.GnssCentre(5, [0, 0, 300.0], [1, 1, 1])]}, raises=InputError,
         why="GNSS of a centre that is not there"),
    Case(M.calibrate_network, (OBS,), {"cameras0": [[3100.0, 0.0]]}, raises=InputError, why="bad IO start"),
    Case(M.calibrate_network, (OBS,), {"cameras0": [[-3100.0, 0.0, 0.0]]}, raises=InputError, why="negative f start"),
    Case(M.calibrate_network, (OBS,), {"angles0": [[NAN, 0, 0], [0, 0, 0]]}, raises=InputError, why="NaN angle start"),
    Case(M.calibrate_network, (OBS,), {"max_iter": 0}, raises=InputError, why="no iterations allowed"),
    Case(M.calibrate_network, (OBS,), {"sigma_image": 0.0}, raises=InputError, why="zero a-priori σ"),
    Case(M.calibrate_network, (TRIPOD,), {"targets": "plane", "tripod": True, "datum": "minimal"},
         raises=DegenerateGeometryError, match="l0", why="minimal gauge with coinciding start centres"),
    Case(M.calibrate_network, (OBS_01,), raises=DegenerateGeometryError, match="f/Z_S",
         why="one horizontal image with Z_S free"),
    Case(M.calibrate_network, (OBS,), {"max_iter": 1, "angles0": np.radians([[25.0, 3, 2], [-35.0, -2, 1]])},
         raises=ConvergenceError, why="one iteration from a poor start"),
    Case(M.calibrate_network, (OBS,), raises=None, why="variant 2-1 needs no GNSS",
         check=lambda r: np.all(np.abs(r.io_errors(OBS)) < 3.0)),
    Case(M.NetworkCalibration, tuple([None] * 15), raises=None, why="plain result record",
         check=lambda r: r.targets is None),
    # statistics
    Case(M.error_statistics, ([[1.0, 2.0, 3.0]],), raises=InputError, why="one row"),
    Case(M.error_statistics, ([[1.0, NAN], [2.0, 3.0]],), raises=InputError, why="NaN error"),
    Case(M.error_statistics, ("errors",), raises=InputError, why="a string"),
    Case(M.error_statistics, (np.zeros((2, 2, 2)),), raises=InputError, why="3-D array"),
    Case(M.error_statistics, ([1.0, 2.0, 3.0],), raises=None, why="one column as a vector", check=_stats_ok),
    Case(M.ErrorStatistics, (3, *([np.zeros(1)] * 6), np.eye(1)), raises=None, why="plain result record",
         check=lambda s: s.n == 3),
    # variants
    Case(M.variant_mockup, ("4-1",), raises=InputError, match="unknown Table 1 variant", why="no such variant"),
    Case(M.variant_mockup, ("1-1",), {"camera": (3100, 10, 10)}, raises=InputError, why="camera not a MockupCamera"),
    Case(M.variant_mockup, ("1-1",), {"height": -300.0}, raises=InputError, why="negative height"),
    Case(M.simulate_variant, ("1-1", 1), raises=InputError, why="one run"),
    Case(M.simulate_variant, ("1-1", 2), {"gnss_mode": "soft"}, raises=InputError, why="unknown GNSS mode"),
    Case(M.simulate_variant, ("1-1", 2), {"gnss_sigma": [0.1, 0.1]}, raises=InputError, why="two GNSS σ"),
    Case(M.simulate_variant, ("0-1", 2), {"sigma": 0.0}, raises=InputError, why="σ = 0: nothing to simulate"),
    Case(M.variant_precision, ("5-5",), raises=InputError, why="no such variant"),
    Case(M.variant_precision, ("1-1",), {"gnss_mode": "free"}, raises=InputError, why="unknown GNSS mode"),
    Case(M.variant_precision, ("1-1",), {"gnss_sigma": [0.1, 0.0, 0.3]}, raises=InputError, why="σ = 0"),
    Case(M.variant_precision, ("1-1",), {"sigma": NAN}, raises=InputError, why="NaN σ"),
    Case(M.MockupVariant, ("x", "1", (), (), (), "", "", (1, 1)), raises=None, why="plain record",
         check=lambda v: v.name == "x"),
    Case(M.VariantRuns, ("1-1", "fixed", np.zeros((2, 3)), np.zeros(2)), raises=None, why="plain record",
         check=lambda r: r.statistics.n == 2),
    Case(M.tripod_mockup, ([0.0, 0.0],), raises=InputError, why="2-vector offset"),
    Case(M.tripod_mockup, (), {"distance": 0.0}, raises=InputError, why="zero distance"),
    Case(M.tripod_mockup, (), {"camera": "NEX-5"}, raises=InputError, why="camera not a MockupCamera"),
    Case(M.tripod_mockup, (), {"step": 5.0}, raises=InputError, match="sees", why="too coarse a target"),
    # derivations
    Case(DM.mockup_collinearity_terms, (("X_S", "Y_S"),), raises=InputError, why="two centre components"),
    Case(DM.mockup_collinearity_terms, ((object(), 0, 0),), raises=InputError, why="not a sympy expression"),
    Case(DM.mockup_collinearity_terms, ((0, 0, 300),), raises=None, why="a numeric centre",
         check=lambda t: t.shape == (3, 1)),
    Case(DM.mockup_collinearity_model, (), raises=None, why="no input", check=lambda m: len(m.parameters) == 12),
    Case(DM.mockup_tripod_model, (), raises=None, why="no input", check=lambda m: len(m.parameters) == 15),
]


@pytest.mark.parametrize("case", CASES, ids=lambda c: c.id)
def test_bad_input(case):
    check_case(case)
