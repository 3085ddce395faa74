"""Bad-input catalogue for Hanzl §3 (two images): photolib.image_pair, photolib.projective additions and
photolib.derivations.parallax."""

import numpy as np
import pytest

from catalogue import INF, NAN, Case, check_case
from photolib import image_pair as ip
from photolib import projective as pj
from photolib.camera import ExteriorOrientation, InteriorOrientation
from photolib.derivations import parallax as D
from photolib.errors import DegenerateGeometryError, InputError

IO = InteriorOrientation(100.0)
E1, E2 = ExteriorOrientation(0, 0, 1000), ExteriorOrientation(400, 0, 1000)
GRUBER = np.array([[0, 0], [90, 0], [0, 90], [90, 90], [0, -90], [90, -90]], float)
LINE = np.array([[0, 0], [10, 0], [20, 0], [30, 0], [40, 0], [50, 0]], float)

CASES = [
    # intersection_known_eo
    Case(ip.intersection_known_eo, ([[20.0, 10.0]], [[-20.0, 10.0]], E1, E2, IO), raises=None, why="normal case",
         check=lambda P: np.allclose(P, [[200, 100, 0]])),
    Case(ip.intersection_known_eo, ([[20.0, 10.0]], [[20.0, -30.0]], E1, ExteriorOrientation(0, 400, 1000), IO),
         raises=DegenerateGeometryError, match="k_x1 = k_x2", why="base along Y"),
    Case(ip.intersection_known_eo, ([[NAN, 10.0]], [[-20.0, 10.0]], E1, E2, IO), raises=InputError, why="NaN"),
    Case(ip.intersection_known_eo, ([[20.0, 10.0]], [[-20.0, 10.0], [1.0, 1.0]], E1, E2, IO), raises=InputError,
         why="different counts"),
    Case(ip.intersection_known_eo, ([[20.0, 10.0]], [[-20.0, 10.0]], "eo", E2, IO), raises=InputError,
         why="eo1 not an ExteriorOrientation"),
    Case(ip.intersection_known_eo, ([[20.0, 10.0]], [[-20.0, 10.0]], E1, E2, IO), kwargs={"warn_ratio": -1.0},
         raises=InputError, why="negative warn_ratio"),
    Case(ip.intersection_known_eo, ([[20.0, 10.0]], [[20.0, 10.0]], E1, E2, IO), raises=DegenerateGeometryError,
         why="parallel rays"),
    # orientation_counts
    Case(ip.orientation_counts, (1, 2, 2, 5), raises=None, why="Hanzl's example",
         check=lambda d: d["unknowns"] == 33 and d["redundancy"] == 7),
    Case(ip.orientation_counts, (-1, 2, 2, 5), raises=InputError, why="negative count"),
    Case(ip.orientation_counts, (1.5, 2, 2, 5), raises=InputError, why="non-integer count"),
    Case(ip.orientation_counts, (1, 2, 2, 5), kwargs={"images": 1}, raises=InputError, why="one image"),
    Case(ip.orientation_counts, (True, 2, 2, 5), raises=InputError, why="bool count"),
    # relative_orientation_parallax
    Case(ip.relative_orientation_parallax, (GRUBER, GRUBER - [90.0, 0.0], IO), raises=None, why="normal-case pair",
         check=lambda r: np.allclose([r.b_y, r.b_z, r.omega2, r.alpha2, r.kappa2], 0, atol=1e-12)),
    Case(ip.relative_orientation_parallax, (GRUBER[:4], GRUBER[:4] - [90.0, 0.0], IO), raises=InputError,
         match="at least 5", why="four points"),
    Case(ip.relative_orientation_parallax, (GRUBER, GRUBER - [90.0, 0.0], IO), kwargs={"system": "free"},
         raises=InputError, why="unknown system"),
    Case(ip.relative_orientation_parallax, (GRUBER, GRUBER - [90.0, 0.0], IO), kwargs={"iterate": "yes"},
         raises=InputError, why="iterate not a bool"),
    Case(ip.relative_orientation_parallax, (LINE, LINE - [90.0, 0.0], IO), raises=DegenerateGeometryError,
         why="collinear points"),
    Case(ip.relative_orientation_parallax, (GRUBER, GRUBER + [90.0, 0.0], IO), raises=DegenerateGeometryError,
         why="negative x-parallax: rays meet above the cameras"),
    Case(ip.relative_orientation_parallax, (np.where(GRUBER == 90, NAN, GRUBER), GRUBER, IO), raises=InputError,
         why="NaN coordinates"),
    Case(ip.relative_orientation_parallax, (GRUBER, GRUBER - [90.0, 0.0], 150.0), raises=InputError,
         why="io not an InteriorOrientation"),
    # model_deformation
    Case(ip.model_deformation, (300.0, 200.0, 1500.0, 900.0, {"domega1": 1e-3, "domega2": 1e-3}), raises=None,
         why="equal dω: rigid tilt", check=lambda dz: abs(dz - 0.2) < 1e-12),
    Case(ip.model_deformation, (300.0, 200.0, 1500.0, 900.0, {"dkappa": 1e-3}), raises=InputError,
         match="unknown elements", why="unknown element"),
    Case(ip.model_deformation, (300.0, 200.0, -1500.0, 900.0, {}), raises=InputError, why="negative h"),
    Case(ip.model_deformation, (300.0, 200.0, 1500.0, 0.0, {}), raises=InputError, why="zero base"),
    Case(ip.model_deformation, (INF, 200.0, 1500.0, 900.0, {}), raises=InputError, why="inf coordinate"),
    Case(ip.model_deformation, (300.0, 200.0, 1500.0, 900.0, [1e-3]), raises=InputError, why="elements not a dict"),
    Case(ip.model_deformation, (300.0, 200.0, 1500.0, 900.0, {"dphi1": NAN}), raises=InputError, why="NaN element"),
    # projective: Hanzl's C and F
    Case(pj.coplanarity_interior_matrix, (IO,), raises=None, why="plain",
         check=lambda C: np.allclose(C, [[1, 0, 0], [0, 1, 0], [0, 0, -100]])),
    Case(pj.coplanarity_interior_matrix, (100.0,), raises=InputError, why="not an InteriorOrientation"),
    Case(pj.fundamental_coplanarity, (IO, np.eye(3), IO, np.eye(3), [1.0, 0.0, 0.0]), raises=None, why="normal case",
         check=lambda F: np.allclose(F, [[0, 0, 0], [0, 0, 100], [0, -100, 0]])),
    Case(pj.fundamental_coplanarity, (IO, np.eye(3), IO, np.eye(3), [0.0, 0.0, 0.0]), raises=DegenerateGeometryError,
         why="zero base"),
    Case(pj.fundamental_coplanarity, (IO, 2 * np.eye(3), IO, np.eye(3), [1.0, 0.0, 0.0]), raises=InputError,
         why="not a rotation"),
    Case(pj.fundamental_coplanarity, (IO, np.eye(2), IO, np.eye(3), [1.0, 0.0, 0.0]), raises=InputError,
         why="2×2 matrix"),
    Case(pj.fundamental_coplanarity, (IO, np.eye(3), IO, np.eye(3), [1.0, NAN, 0.0]), raises=InputError,
         why="NaN base"),
    Case(pj.fundamental_coplanarity, (IO, "R", IO, np.eye(3), [1.0, 0.0, 0.0]), raises=InputError, why="text matrix"),
    Case(pj.fundamental_coplanarity, ("io", np.eye(3), IO, np.eye(3), [1.0, 0.0, 0.0]), raises=InputError,
         why="io not an InteriorOrientation"),
    # derivations.parallax
    Case(D.y_parallax_model, ("both",), raises=InputError, why="unknown system"),
    Case(D.y_parallax_model, ("independent",), raises=None, why="independent pair",
         check=lambda m: [str(s) for s in m.parameters] == ["dkappa1", "dkappa2", "dphi1", "dphi2", "domega2"]),
    Case(D.y_parallax_coefficients, (), raises=None, why="no input", check=lambda d: set(d) == set(D.ELEMENTS)),
    Case(D.deformation_coefficients, (), raises=None, why="no input",
         check=lambda d: set(d) == set(D.DEFORMATION_ELEMENTS)),
    Case(D.deformation_model, (), raises=None, why="no input", check=lambda m: len(m.parameters) == 8),
    Case(D.printed_formulas, (), raises=None, why="no input", check=lambda d: set(d) == set(D.derived_formulas())),
    Case(D.derived_formulas, (), raises=None, why="no input", check=lambda d: "510-py" in d),
]


@pytest.mark.parametrize("case", CASES, ids=lambda c: c.id)
def test_bad_input(case):
    check_case(case)
