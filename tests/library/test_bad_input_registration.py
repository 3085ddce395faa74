"""Bad-input catalogue for photolib.registration and photolib.derivations.registration (§9.5–9.6)."""

import numpy as np
import pytest

from catalogue import NAN, Case, check_case
from photolib.derivations import registration as dreg
from photolib.errors import ConvergenceError, DegenerateGeometryError, InputError
from photolib.registration import (ICPIteration, ICPResult, RigidTransform, StationRegistration, estimate_normals,
                                   icp, register_stations, rigid_closed_form, rigid_transform)

P4 = np.array([[0.0, 0, 0], [5, 0, 0], [0, 4, 0], [1, 1, 3]])
T = RigidTransform(1.0, 2.0, 3.0, 0.1, 0.2, 0.3)
Q4 = T.apply(P4)
COLLINEAR = np.array([[0.0, 0, 0], [1, 1, 1], [2, 2, 2], [3, 3, 3]])
_rng = np.random.default_rng(0)
CLOUD = _rng.uniform(0, 1, (300, 3)) * [5, 4, 0.0] + [0, 0, 0]
CLOUD[:, 2] = 0.3 * np.sin(CLOUD[:, 0]) * np.cos(CLOUD[:, 1])
WITH_NAN = CLOUD.copy()
WITH_NAN[3, 1] = NAN
ST0 = {i: p for i, p in enumerate(P4)}
ST1 = {i: p for i, p in enumerate(T.inverse().apply(P4))}

CASES = [
    Case(RigidTransform, (NAN, 0, 0, 0, 0, 0), raises=InputError, why="NaN element"),
    Case(RigidTransform, ("a", 0, 0, 0, 0, 0), raises=InputError, why="a string element"),
    Case(RigidTransform, (0, 0, 0, 0, 0, 0), {"order": "xyz"}, raises=InputError, why="unknown order"),
    Case(T.apply, (np.zeros((3, 2)),), raises=InputError, why="2-D points"),
    Case(T.compose, ("not a transform",), raises=InputError, why="compose with a string"),
    Case(RigidTransform.from_homogeneous, (np.eye(3),), raises=InputError, why="3×3 instead of 4×4"),
    Case(rigid_closed_form, (P4[:2], Q4[:2]), raises=DegenerateGeometryError, match="2 targets", why="two targets"),
    Case(rigid_closed_form, (COLLINEAR, COLLINEAR), raises=DegenerateGeometryError, match="one line",
         why="collinear targets"),
    Case(rigid_closed_form, (P4, Q4[:3]), raises=InputError, why="mismatched sizes"),
    Case(rigid_closed_form, (P4, np.where(P4 == 5, NAN, Q4)), raises=InputError, why="NaN object coordinate"),
    Case(rigid_closed_form, (np.empty((0, 3)), np.empty((0, 3))), raises=(InputError, DegenerateGeometryError),
         why="empty"),
    Case(rigid_transform, (P4[:2], Q4[:2]), raises=DegenerateGeometryError, match="rotation", why="two targets"),
    Case(rigid_transform, (COLLINEAR, COLLINEAR + 1), raises=DegenerateGeometryError, match="rotation",
         why="collinear targets"),
    Case(rigid_transform, (P4, Q4), {"weights": [1, 1, -1, 1]}, raises=InputError, why="negative weight"),
    Case(rigid_transform, (P4, Q4), {"weights": [1, 1]}, raises=InputError, why="weights of the wrong size"),
    Case(rigid_transform, (P4, Q4), {"initial": "start"}, raises=InputError, why="initial not a transform"),
    Case(rigid_transform, (P4, Q4), {"initial": RigidTransform(0, 0, 0, 0, 0, 0, "wak")}, raises=None,
         check=lambda r: np.allclose(r.vector, T.vector), why="start in another order"),
    Case(rigid_transform, (P4, np.full((4, 3), np.inf)), raises=InputError, why="inf coordinates"),
    Case(StationRegistration, ([T], {}, None, [{}]), raises=None, check=lambda r: len(r.transforms) == 1,
         why="one station, no ties"),
    Case(StationRegistration.merge, (StationRegistration([T], {}, None, [{}]), [P4, P4]), raises=InputError,
         why="more clouds than stations"),
    Case(register_stations, ([ST0],), raises=InputError, why="one station"),
    Case(register_stations, ("stations",), raises=InputError, why="not a list"),
    Case(register_stations, ([ST0, {}],), raises=InputError, why="an empty station"),
    Case(register_stations, ([ST0, {0: [NAN, 0, 0], 1: [1, 0, 0], 2: [0, 1, 0]}],), raises=InputError,
         why="NaN target"),
    Case(register_stations, ([ST0, ST1],), {"fixed": 5}, raises=InputError, why="fixed out of range"),
    Case(register_stations, ([ST0, {0: ST1[0], 1: ST1[1]}],), raises=DegenerateGeometryError, match="station",
         why="two shared targets"),
    Case(register_stations, ([ST0, ST1],), {"control": {0: [0, 0, 0], 1: [1, 0, 0]}},
         raises=DegenerateGeometryError, why="two control targets"),
    Case(register_stations, ([ST0, ST1],), {"weights": [{0: -1.0}, {}]}, raises=InputError, why="negative weight"),
    Case(estimate_normals, (WITH_NAN,), raises=InputError, match="NaN", why="NaN point"),
    Case(estimate_normals, (CLOUD[:5],), raises=DegenerateGeometryError, why="fewer points than neighbours"),
    Case(estimate_normals, (CLOUD,), {"k": 2}, raises=InputError, why="k too small"),
    Case(estimate_normals, (CLOUD[:, :2],), raises=InputError, why="2-D points"),
    Case(estimate_normals, (np.vstack([CLOUD, CLOUD]),), raises=None, why="duplicate points",
         check=lambda n: np.nanmedian(np.abs(n[:, 2])) > 0.7),
    Case(icp, (WITH_NAN, CLOUD), raises=InputError, match="NaN", why="NaN in the source"),
    Case(icp, (CLOUD, WITH_NAN), raises=InputError, match="NaN", why="NaN in the target"),
    Case(icp, (CLOUD[:4], CLOUD), raises=DegenerateGeometryError, match="too few", why="too few points"),
    Case(icp, (CLOUD, CLOUD), {"method": "point-to-line"}, raises=InputError, why="unknown method"),
    Case(icp, (CLOUD, CLOUD), {"trim": 0.0}, raises=InputError, why="trim of zero"),
    Case(icp, (CLOUD, CLOUD), {"max_distance": -1.0}, raises=InputError, why="negative max_distance"),
    Case(icp, (CLOUD, CLOUD), {"initial": np.eye(3)}, raises=InputError, why="3×3 initial"),
    Case(icp, (CLOUD, CLOUD), {"initial": np.diag([1.0, 1, -1, 1])}, raises=InputError, why="reflection"),
    Case(icp, (CLOUD, CLOUD), {"coarse_fraction": 1.5}, raises=InputError, why="coarse fraction above 1"),
    Case(icp, (CLOUD, CLOUD), {"k_normals": "ten"}, raises=InputError, why="k_normals a string"),
    Case(icp, (CLOUD, CLOUD), {"max_iter": 0}, raises=InputError, why="no iterations allowed"),
    Case(icp, (CLOUD + 100.0, CLOUD), {"max_distance": 1.0}, raises=DegenerateGeometryError, match="pairs",
         why="no pairs within max_distance"),
    Case(icp, (T.inverse().apply(CLOUD), CLOUD), {"max_iter": 1, "method": "point-to-point"},
         raises=ConvergenceError, why="not converged"),
    Case(icp, (np.vstack([CLOUD, CLOUD]), CLOUD), raises=None, why="duplicate source points",
         check=lambda r: r.transform.rotation_angle < 1e-9 and np.linalg.norm(r.transform.shift) < 1e-9),
    Case(ICPIteration, (1, 0.1, 10, 0.0, 0.0), raises=None, check=lambda r: r.pairs == 10, why="plain record"),
    Case(ICPResult, (T, 0.0, 1.0, 1, True, "point-to-point"), raises=None,
         check=lambda r: r.matrix.shape == (4, 4), why="plain record"),
    Case(dreg.rigid_model, ("xyz",), raises=InputError, why="unknown order"),
    Case(dreg.rigid_transform_symbolic, ("xyz",), raises=InputError, why="unknown order"),
]


@pytest.mark.parametrize("case", CASES, ids=lambda c: c.id)
def test_bad_input(case):
    check_case(case)
