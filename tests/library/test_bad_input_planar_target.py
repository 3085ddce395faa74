"""Bad-input catalogue for photolib.planar_target, photolib.additional_parameters and
photolib.derivations.planar_target (Sementsov's thesis, appendix to Chapter 11)."""

import numpy as np
import pytest
import sympy as sp

from catalogue import INF, NAN, Case, check_case
from photolib import additional_parameters as ap
from photolib import planar_target as pt
from photolib.derivations import planar_target as D
from photolib.errors import ConvergenceError, DegenerateGeometryError, InputError, PointBehindCameraError

A30 = np.radians(30.0)
U3 = pt.image_rays([[0.0, 0.0], [100.0, 0.0], [0.0, 100.0]], 1000.0)

CASES = [
    # (6)
    Case(pt.project, ([[0.0, 0.0, 400.0]], [0, 0, 300.0], 0.0, 0.0, 0.0, 3100.0), raises=PointBehindCameraError,
         why="point above the camera (behind it)"),
    Case(pt.project, ([[0.0, 0.0, 0.0]], [0, 0, 300.0], 0.0, 0.0, 0.0, 0.0), raises=InputError, why="f = 0"),
    Case(pt.project, ([[0.0, 0.0]], [0, 0, 300.0], 0.0, 0.0, 0.0, 3100.0), raises=InputError, why="2-D points"),
    Case(pt.project, ([[0.0, 0.0, 0.0]], [[0, 0, 300.0], [1, 0, 300.0]], 0.0, 0.0, 0.0, 3100.0), raises=InputError,
         why="two centres"),
    Case(pt.project, ([[0.0, 0.0, 0.0]], [0, 0, 300.0], NAN, 0.0, 0.0, 3100.0), raises=InputError, why="NaN angle"),
    # (12)–(16)
    Case(pt.transformed_bundle, (0.0, 1.0, 3100.0, 300.0), raises=DegenerateGeometryError, match="horizontal",
         why="α = 0"),
    Case(pt.transformed_bundle, (30.0, 1.0, 3100.0, 300.0), raises=InputError, match="degrees", why="α in degrees"),
    Case(pt.transformed_bundle, (A30, 2.5, 3100.0, 300.0), raises=InputError, match="1/", why="k > 1/sin α"),
    Case(pt.transformed_bundle, (A30, 0.0, 3100.0, 300.0), raises=InputError, why="k = 0"),
    Case(pt.transformed_bundle, (A30, [0.5, NAN], 3100.0, 300.0), raises=InputError, why="NaN k"),
    Case(pt.transformed_bundle, (A30, 1.0, 3100.0, -300.0), raises=InputError, why="negative Z_S"),
    Case(pt.transformed_bundle, (A30, 2.0, 3100.0, 300.0), raises=None, why="k = 1/sin α exactly (α′ = 90°)",
         check=lambda b: np.isclose(b.alpha_prime, np.pi / 2)),
    Case(pt.TransformedBundle, (1.0, 0.5, 0.5, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0), raises=None, why="plain record",
         check=lambda b: b.k == 1.0),
    # (18)
    Case(pt.centre_locus, (0.0, 300.0), raises=DegenerateGeometryError, why="α = 0"),
    Case(pt.centre_locus, (A30, 0.0), raises=InputError, why="Z_S = 0"),
    Case(pt.centre_locus, (INF, 300.0), raises=InputError, why="inf angle"),
    Case(pt.CentreLocus, (A30, 300.0, (0.0, 0.0), 600.0, 2.0), raises=None, why="plain record",
         check=lambda c: c.radius == 600.0),
    # methodologies
    Case(pt.condition_residual, ("4", 1.0, A30, -A30), raises=InputError, match="methodology", why="unknown method"),
    Case(pt.condition_residual, ("2.1", 1.0, A30), raises=InputError, match="alpha2", why="missing α₂"),
    Case(pt.condition_residual, ("1-x0", 1.0, A30, A30), raises=InputError, match="alpha2", why="extra α₂"),
    Case(pt.condition_residual, ("2.2", 1.0, A30, A30), raises=DegenerateGeometryError, why="α₁ = α₂"),
    Case(pt.condition_residual, ("2.1", 3.0, A30, -A30), raises=InputError, why="k beyond 1/sin α"),
    Case(pt.condition_residual, ("2.1", [[1.0]], A30, -A30), raises=InputError, why="2-D k"),
    Case(pt.condition_residual, ("2.1", 1.0, A30, 0.0), raises=DegenerateGeometryError, why="horizontal image 2"),
    Case(pt.condition_roots, ("2.1", A30, -A30), {"samples": 3}, raises=InputError, why="too few samples"),
    Case(pt.condition_roots, ("2.2", A30, A30), raises=DegenerateGeometryError, why="equal tilts"),
    Case(pt.condition_roots, (None, A30), raises=InputError, why="method None"),
    Case(pt.ConditionRoots, ("2.1", A30, -A30, 2.0, (1.0,)), raises=None, why="plain record",
         check=lambda r: r.roots == (1.0,)),
    # (22)–(24)
    Case(pt.gsd, (0.0, 3100.0), raises=InputError, why="H = 0"),
    Case(pt.gsd, (300.0, "3100"), raises=None, why="f as numeric text is read",
         check=lambda g: np.isclose(g, 300 / 3100)),
    Case(pt.gsd, (300.0, NAN), raises=InputError, why="NaN f"),
    Case(pt.permissible_offsets, (0.0, 2.0, 3100.0), raises=InputError, why="m = 0"),
    Case(pt.permissible_offsets, (0.5, 2.0, 3100.0), {"slope_z": 0.0}, raises=InputError, why="zero slope"),
    Case(pt.PermissibleOffsets, (1.0, 2.0, 0.1, 0.2, 0.1), raises=None, why="plain record",
         check=lambda o: o.l_z == 0.2),
    # star field
    Case(pt.max_star_exposure, (60.0, 2.0), raises=InputError, match="declination", why="|δ| > π/2"),
    Case(pt.max_star_exposure, (-60.0, 0.0), raises=InputError, why="negative pixel size"),
    Case(pt.max_star_exposure, (60.0, np.pi / 2), raises=None, why="pole: infinite exposure",
         check=lambda t: np.isinf(t)),
    Case(pt.star_unit_vector, ([0.0, 1.0], [0.0, 0.1, 0.2]), raises=InputError, why="shapes do not broadcast"),
    Case(pt.star_unit_vector, (0.0, 100.0), raises=InputError, why="declination in degrees"),
    Case(pt.angular_pixel_size, (0.0,), raises=InputError, why="f = 0"),
    Case(pt.angular_pixel_size, (3300.0, -1.0), raises=InputError, why="negative pixel"),
    # (5)
    Case(pt.image_rays, ([[0.0, 0.0, 1.0]], 100.0), raises=InputError, why="3-D image points"),
    Case(pt.image_rays, ([[0.0, 0.0]], -100.0), raises=InputError, why="negative f"),
    Case(pt.compare_bundles, (U3, U3[:2]), raises=InputError, why="different counts"),
    Case(pt.compare_bundles, (U3[:1], U3[:1]), raises=DegenerateGeometryError, why="one ray"),
    Case(pt.compare_bundles, (np.tile(U3[:1], (3, 1)), np.tile(U3[:1], (3, 1))), raises=DegenerateGeometryError,
         why="parallel rays"),
    Case(pt.compare_bundles, (U3, np.zeros((3, 3))), raises=InputError, match="zero", why="zero vectors"),
    Case(pt.compare_bundles, (U3, U3 * np.array([1, 1, NAN])), raises=InputError, why="NaN rays"),
    Case(pt.BundleComparison, (0.0, 0.0, np.eye(3), np.zeros((1, 3)), 1), raises=None, why="plain record",
         check=lambda c: c.n == 1),
    # additional parameters
    Case(ap.parameter_names, ("opencv",), raises=InputError, match="unknown AP model", why="unknown model"),
    Case(ap.parameter_names, (3,), raises=InputError, why="model not a string"),
    Case(ap.ebner12, ([[1.0, 1.0]], np.zeros(12), 0.0), raises=InputError, why="b = 0"),
    Case(ap.ebner12, ([[1.0, 1.0]], np.zeros(11), 1.0), raises=InputError, match="12", why="11 parameters"),
    Case(ap.ebner12, ([[1.0, 1.0]], {"b4": 1.0}, 1.0), raises=InputError, match="unknown parameter", why="b4 name"),
    Case(ap.brown, ([[1.0, 1.0]], np.zeros(26), 0.0), raises=InputError, why="f = 0"),
    Case(ap.brown, ([[1.0, 1.0]], "k1", 100.0), raises=InputError, why="parameters a string"),
    Case(ap.photomod, ([[1.0, NAN]], {}), raises=InputError, why="NaN coordinate"),
    Case(ap.photomod, ([[1.0, 1.0]], {"k1": INF}), raises=InputError, why="inf coefficient"),
    Case(ap.photomod, ([[1.0, 1.0]], {"p1": 1e-7}), raises=InputError, match="P1", why="lower-case p1"),
    Case(ap.ap_corrections, ("ebner12", [[1.0, 1.0]], {}), raises=InputError, match="needs b", why="no b"),
    Case(ap.ap_corrections, ("brown", [[1.0, 1.0]], {}), raises=InputError, match="needs f", why="no f"),
    Case(ap.ap_corrections, ("photomod", np.zeros((0, 2)), {}), raises=None, why="no points",
         check=lambda r: r.shape == (0, 2)),
    Case(ap.ap_basis, ("brown", [[1.0, 1.0]]), raises=InputError, why="no f"),
    Case(ap.ap_basis, ("photomod", [1.0, 1.0, 1.0]), raises=InputError, why="3 coordinates"),
    Case(ap.apply_ap, ("photomod", [[1.0, 1.0]], [1.0]), raises=InputError, why="one parameter"),
    Case(ap.invert_ap, ("photomod", [[1000.0, 0.0]], {"k1": -3e-6}), raises=ConvergenceError, why="diverges"),
    Case(ap.invert_ap, ("photomod", [[1.0, 0.0]], {}), {"tol": 0.0}, raises=InputError, why="tol = 0"),
    Case(ap.invert_ap, ("photomod", [[1.0, 0.0]], {}), {"max_iter": 0}, raises=InputError, why="max_iter = 0"),
    Case(ap.invert_ap, ("photomod", np.zeros((0, 2)), {"k1": 1e-9}), raises=None, why="no points",
         check=lambda r: r.shape == (0, 2)),
    # derivations
    Case(D.derived_collinearity_6, ("a+",), raises=InputError, why="angle not an expression"),
    Case(D.derived_collinearity_6, (0, 0, 0), raises=None, why="zero angles", check=lambda m: m.shape == (2, 1)),
    Case(D.printed_collinearity_6, (), raises=None, why="no input", check=lambda m: m.shape == (2, 1)),
    Case(D.printed_tilted_plane_8, (), raises=None, why="no input",
         check=lambda m: sp.simplify(m - D.derived_tilted_plane_8()) == sp.zeros(2, 1)),
    Case(D.derived_tilted_plane_8, (), raises=None, why="no input", check=lambda m: m.shape == (2, 1)),
    Case(D.printed_transformed_bundle_9, (), raises=None, why="no input", check=lambda m: m.has(D.K)),
    Case(D.derived_transformed_bundle_9, (), raises=None, why="no input", check=lambda m: m.has(D.ZSP)),
    Case(D.printed_cross_multiplied, (), raises=None, why="no input", check=lambda t: len(t) == 2),
    Case(D.printed_expansion_10, (), raises=None, why="no input", check=lambda t: len(t) == 2),
    Case(D.derived_identity, (), raises=None, why="no input",
         check=lambda t: sp.expand(t[0] - D.printed_expansion_10()[0]) == 0),
    Case(D.printed_coefficient_equations_11, (), raises=None, why="no input", check=lambda d: len(d) == 8),
    Case(D.derived_coefficient_equations, (), raises=None, why="no input", check=lambda d: d[("x", "other")] == 0),
    Case(D.printed_solution, (), raises=None, why="no input", check=lambda d: set(d) == {"12", "13", "14", "15", "16"}),
    Case(D.solution_substitution, (0,), raises=InputError, match="sign_16", why="sign 0"),
    Case(D.solution_substitution, (True,), raises=InputError, why="a bool for the sign"),
    Case(D.printed_centre_shift_734, (), raises=None, why="no input", check=lambda e: e.has(D.K)),
    Case(D.derived_centre_shift, (), raises=None, why="no input",
         check=lambda e: sp.expand(e - D.printed_centre_shift_734()) == 0),
    Case(D.printed_centre_locus, (), raises=None, why="no input", check=lambda e: e.has(D.DXS)),
    Case(D.corrected_centre_locus, (), raises=None, why="no input",
         check=lambda e: sp.simplify(e.subs(D.solution_substitution())) == 0),
    Case(D.ebner12_symbolic, ("yes",), raises=InputError, match="printed", why="printed not a bool"),
    Case(D.ebner12_gram, (1,), raises=InputError, why="printed an int"),
    Case(D.brown_symbolic, (), raises=None, why="no input", check=lambda t: len(t[2]) == 26),
    Case(D.photomod_symbolic, (), raises=None, why="no input", check=lambda t: len(t[2]) == 9),
]


@pytest.mark.parametrize("case", CASES, ids=lambda c: c.id)
def test_bad_input(case):
    check_case(case)
