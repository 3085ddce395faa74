"""Bad-input catalogue for the robust adjustment of Hanzl §2.6 (photolib.lsq.robust_gauss_newton and
friends, photolib.resection.robust_space_resection) and the sympy forms of Hanzl §2
(photolib.derivations.hanzl_foundations)."""

import numpy as np
import pytest

from catalogue import INF, NAN, Case, check_case
from photolib import lsq
from photolib import resection as R
from photolib.camera import ExteriorOrientation, InteriorOrientation
from photolib.derivations import hanzl_foundations as H
from photolib.errors import ConvergenceError, DegenerateGeometryError, InputError
from photolib.single_image import project

T = np.arange(10.0)
Y = 2.0 + 0.5 * T + 0.01 * np.sin(7 * T)
Y_BAD = Y.copy()
Y_BAD[6] -= 3.0
LINE = lambda p: (np.column_stack([np.ones(10), T]), p[0] + p[1] * T - Y_BAD)
NAN_LINE = lambda p: (np.column_stack([np.ones(10), T]), np.full(10, NAN))
TWO = lambda p: (np.column_stack([np.ones(2), T[:2]]), p[0] + p[1] * T[:2] - Y[:2])
# six points of which four are far off any common line: nothing consistent is left
WILD = np.array([0.0, 10.0, -7.0, 31.0, -2.0, 55.0])
WILD_LINE = lambda p: (np.column_stack([np.ones(6), T[:6]]), p[0] + p[1] * T[:6] - WILD)

IO = InteriorOrientation(100.0)
G = np.linspace(0.0, 2000.0, 4)
XYZ = np.column_stack([np.repeat(G, 4), np.tile(G, 4), 10.0 * np.arange(16) % 30])
XY = project(XYZ, ExteriorOrientation.from_degrees(1000, 1000, 1500, 2, 5, 7), IO)
XY_NAN = XY.copy()
XY_NAN[2, 0] = NAN

B5 = np.ones((5, 1))
V5 = np.array([0.0, 0.1, -0.1, 0.0, 2.0])
Q5 = np.array([[0.2]])
ADJ = lsq.gauss_newton(LINE, [0.0, 0.0])

CASES = [
    # danish_weight
    Case(lsq.danish_weight, (2.0, 0.0), raises=InputError, match="exponent", why="d = 0"),
    Case(lsq.danish_weight, (2.0, -3.0), raises=InputError, match="exponent", why="d < 0"),
    Case(lsq.danish_weight, (2.0, NAN), raises=InputError, why="NaN exponent"),
    Case(lsq.danish_weight, (NAN, 3.0), raises=InputError, match="NaN", why="NaN residual"),
    Case(lsq.danish_weight, ("a", 3.0), raises=InputError, why="text residual"),
    Case(lsq.danish_weight, (2.0, 3.0, 0.0), raises=InputError, match="factor", why="k = 0"),
    Case(lsq.danish_weight, (-2.0, 3.0), raises=None, why="a negative residual: |t| is used",
         check=lambda w: np.isclose(w, np.exp(-0.05 * 8.0))),
    Case(lsq.danish_weight, (1e6, 4.4), raises=None, why="huge residual underflows to 0, no error",
         check=lambda w: w == 0.0),
    # normalized_residuals
    Case(lsq.normalized_residuals, (B5, V5[:4], Q5), raises=InputError, match="one residual", why="short V"),
    Case(lsq.normalized_residuals, (B5, np.full(5, NAN), Q5), raises=InputError, match="NaN", why="NaN residuals"),
    Case(lsq.normalized_residuals, (B5, V5, Q5, np.eye(5)), raises=InputError, match="vector", why="weight matrix"),
    Case(lsq.normalized_residuals, (B5, V5, Q5, -np.ones(5)), raises=InputError, why="negative weights"),
    Case(lsq.normalized_residuals, (B5, V5, Q5, None, 0.0), raises=InputError, match="sigma0", why="σ₀ = 0"),
    Case(lsq.normalized_residuals, (np.ones((1, 1)), np.zeros(1), np.eye(1)), raises=InputError,
         match="redundancy", why="no redundancy for σ₀"),
    Case(lsq.normalized_residuals, (B5, np.zeros(5), Q5), raises=None, why="a perfect fit gives w = 0",
         check=lambda w: np.all(w == 0)),
    # robust_gauss_newton
    Case(lsq.robust_gauss_newton, (LINE, [0.0, 0.0]), {"method": "huber"}, raises=InputError, match="method",
         why="unknown method"),
    Case(lsq.robust_gauss_newton, (LINE, [0.0, 0.0]), {"exponents": (0.0, 3.0)}, raises=InputError,
         match="exponent", why="d = 0 in the 2nd pass"),
    Case(lsq.robust_gauss_newton, (LINE, [0.0, 0.0]), {"exponents": (4.4, -1.0)}, raises=InputError,
         match="exponent", why="d < 0 in later passes"),
    Case(lsq.robust_gauss_newton, (LINE, [0.0, 0.0]), {"exponents": (4.4,)}, raises=InputError,
         match="two", why="one exponent"),
    Case(lsq.robust_gauss_newton, (LINE, [0.0, 0.0]), {"exponents": 3.0}, raises=InputError, match="two",
         why="exponents not a pair"),
    Case(lsq.robust_gauss_newton, (LINE, [NAN, 0.0]), raises=InputError, match="NaN", why="NaN start"),
    Case(lsq.robust_gauss_newton, (NAN_LINE, [0.0, 0.0]), raises=InputError, match="NaN", why="NaN equations"),
    Case(lsq.robust_gauss_newton, (LINE, [0.0, 0.0], [1.0] * 9 + [NAN]), raises=InputError, why="NaN weight"),
    Case(lsq.robust_gauss_newton, (LINE, [0.0, 0.0], np.eye(10)), raises=InputError, match="vector",
         why="weight matrix"),
    Case(lsq.robust_gauss_newton, (TWO, [0.0, 0.0]), raises=InputError, match="redundant",
         why="too few observations (m = n)"),
    Case(lsq.robust_gauss_newton, (LINE, [0.0, 0.0]), {"group": 3}, raises=InputError, match="groups",
         why="m not a multiple of the group"),
    Case(lsq.robust_gauss_newton, (LINE, [0.0, 0.0]), {"reject_below": 1.5}, raises=InputError,
         match="reject_below", why="threshold ≥ 1"),
    Case(lsq.robust_gauss_newton, (LINE, [0.0, 0.0]), {"critical": -1.0}, raises=InputError, why="critical < 0"),
    Case(lsq.robust_gauss_newton, (LINE, [0.0, 0.0]), {"sigma0": INF}, raises=InputError, why="σ₀ inf"),
    Case(lsq.robust_gauss_newton, (LINE, [0.0, 0.0]), {"max_passes": 1}, raises=InputError, why="one pass"),
    Case(lsq.robust_gauss_newton, ("not callable", [0.0, 0.0]), raises=InputError, why="linearize not callable"),
    Case(lsq.robust_gauss_newton, (WILD_LINE, [0.0, 0.0]), {"method": "snooping", "sigma0": 1e-3},
         raises=DegenerateGeometryError, match="cannot determine", why="all observations rejected (snooping)"),
    Case(lsq.robust_gauss_newton, (WILD_LINE, [0.0, 0.0]), {"sigma0": 1e-3, "exponents": (4.4, 3.0)},
         raises=DegenerateGeometryError, match="cannot determine", why="all observations rejected (Danish)"),
    Case(lsq.robust_gauss_newton, (LINE, [0.0, 0.0]), {"method": "snooping", "sigma0": 0.01}, raises=None,
         why="one blunder (a-priori σ₀)", check=lambda r: np.flatnonzero(r.rejected).tolist() == [6]),
    # records
    Case(lsq.RobustIterationRecord, (1, "danish", 0.5, np.ones(3)), raises=None, why="a plain record",
         check=lambda r: r.exponent is None and r.rejected == ()),
    Case(lsq.RobustAdjustment, (ADJ, "danish", np.zeros(10, bool), np.zeros(10), ADJ, [], [], np.zeros(10)),
         raises=None, why="a plain record", check=lambda r: np.allclose(r.x, ADJ.x) and r.kept.all()),
    # robust_space_resection
    Case(R.robust_space_resection, (XYZ[[0, 5, 10]], XY[[0, 5, 10]], IO), raises=InputError, match="at least 4",
         why="too few points (no redundancy)"),
    Case(R.robust_space_resection, (XYZ, XY_NAN, IO), raises=InputError, why="NaN image coordinate"),
    Case(R.robust_space_resection, (XYZ, XY[:5], IO), raises=InputError, why="different counts"),
    Case(R.robust_space_resection, (XYZ, XY, IO), {"method": "lmeds"}, raises=InputError, match="method",
         why="unknown method"),
    Case(R.robust_space_resection, (XYZ, XY, IO), {"exponents": (4.4, 0.0)}, raises=InputError,
         match="exponent", why="d = 0"),
    Case(R.robust_space_resection, (XYZ, XY, IO), {"bogus": 1}, raises=InputError, match="bogus",
         why="unknown option"),
    Case(R.robust_space_resection, (XYZ, XY, "io"), raises=InputError, why="io of the wrong type"),
    Case(R.robust_space_resection, (XYZ, XY, IO), {"order": "xyz"}, raises=InputError, why="unknown order"),
    Case(R.robust_space_resection, (XYZ, XY, IO), raises=None, why="no blunders: nothing rejected",
         check=lambda r: not r.rejected_points.any() and np.allclose(r.eo.vector[:3], [1000, 1000, 1500])),
    Case(R.RobustResectionResult, (None, None, None, None, np.zeros(3, bool)), raises=None, why="a plain record",
         check=lambda r: r.rejected_points.shape == (3,)),
    # derivations.hanzl_foundations
    Case(H.hanzl_rotation, ("not an angle",), raises=InputError, why="text angle"),
    Case(H.hanzl_rotation, (0, 0, 0), raises=None, why="zero angles", check=lambda M: M == M.eye(3)),
    Case(H.printed_rotation_table, (), raises=None, why="no input", check=lambda M: M.shape == (3, 3)),
    Case(H.rotation_from_steps, (), raises=None, why="no input", check=lambda M: M.shape == (3, 3)),
    Case(H.plane_rotation, ("not an angle",), raises=InputError, why="text angle"),
    Case(H.plane_rotation, (0,), raises=None, why="α = 0", check=lambda out: out["printed"] == out["printed"].eye(2)),
    Case(H.collinearity_forms, (), raises=None, why="no input", check=lambda out: len(out["printed"]) == 2),
    Case(H.inverse_forms, (), raises=None, why="no input", check=lambda out: len(out["printed"]) == 2),
    Case(H.dlt_coefficients, (), raises=None, why="no input", check=lambda out: len(out["L"]) == 11),
    Case(H.plane_projective_coefficients, (), raises=None, why="no input",
         check=lambda out: len(out["coefficients"]) == 8),
    Case(H.affine_forms, (), raises=None, why="no input", check=lambda out: len(out["printed_decomposition"]) == 4),
    Case(H.least_squares_forms, (2, 2), raises=InputError, match="n < m", why="no redundancy"),
    Case(H.least_squares_forms, (9, 2), raises=InputError, why="too large a symbolic problem"),
    Case(H.least_squares_forms, (3.0, 2), raises=InputError, match="integers", why="float m"),
    Case(H.least_squares_forms, (True, 2), raises=InputError, why="bool m"),
    Case(H.danish_weight_forms, (), raises=None, why="no input", check=lambda out: len(out["symbols"]) == 2),
]


@pytest.mark.parametrize("case", CASES, ids=lambda c: c.id)
def test_bad_input(case):
    check_case(case)
