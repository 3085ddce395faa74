"""Bad-input catalogue for photolib.matching, photolib.targets and photolib.derivations.matching."""

import numpy as np
import pytest

from catalogue import INF, NAN, Case, check_case, finite
from photolib import matching as M
from photolib import targets as T
from photolib.derivations import matching as D
from photolib.errors import ConvergenceError, DegenerateGeometryError, InputError

RNG = np.random.default_rng(0)
IMG = RNG.uniform(0, 255, (40, 40))
NANIMG = IMG.copy()
NANIMG[20, 20] = NAN
FLAT = np.full((40, 40), 80.0)
W = IMG[:5, :7]

CASES = [
    # correlation_coefficient
    Case(M.correlation_coefficient, (W, W[:, :6]), raises=InputError, why="mismatched sizes"),
    Case(M.correlation_coefficient, (W, np.where(W > 100, NAN, W)), raises=InputError, why="NaN pixels"),
    Case(M.correlation_coefficient, ([1.0], [2.0]), raises=InputError, why="one pixel"),
    Case(M.correlation_coefficient, (W, np.full_like(W, 3.0)), raises=DegenerateGeometryError, why="textureless"),
    Case(M.correlation_coefficient, ("ab", W), raises=InputError, why="a string"),
    # correlation_surface
    Case(M.correlation_surface, (IMG, W), raises=InputError, why="template larger than the search area"),
    Case(M.correlation_surface, (np.full((5, 5), 2.0), IMG), raises=DegenerateGeometryError, why="textureless template"),
    Case(M.correlation_surface, (W, NANIMG), raises=InputError, why="NaN in the search area"),
    Case(M.correlation_surface, (W.ravel(), IMG), raises=InputError, why="1-D template"),
    Case(M.correlation_surface, (W, FLAT), raises=None, why="flat search area: R undefined (NaN), not invented",
         check=lambda R: bool(np.all(np.isnan(R)))),
    # parabola_vertex
    Case(M.parabola_vertex, ([0.1, 0.2],), raises=InputError, why="two values"),
    Case(M.parabola_vertex, ([0.5, 0.5, 0.5],), raises=DegenerateGeometryError, why="flat profile"),
    Case(M.parabola_vertex, ([0.9, 0.5, 0.9],), raises=DegenerateGeometryError, why="a valley"),
    Case(M.parabola_vertex, ([0.1, NAN, 0.3],), raises=InputError, why="NaN"),
    Case(M.parabola_vertex, ([0.1, 0.5, 0.3], [0, 1]), raises=InputError, why="lengths differ"),
    Case(M.parabola_vertex, ([0.1, 0.5, 0.3], [1, 1, 1]), raises=InputError, why="repeated offsets"),
    # peak_sharpness
    Case(M.peak_sharpness, ([0.9, 0.5, 0.2],), raises=DegenerateGeometryError, why="peak on the border"),
    Case(M.peak_sharpness, ([],), raises=InputError, why="empty"),
    Case(M.peak_sharpness, ([NAN, NAN, NAN],), raises=InputError, why="all NaN"),
    Case(M.peak_sharpness, ([0.1, 0.5, 0.3], 7), raises=InputError, why="peak outside"),
    Case(M.peak_sharpness, (np.zeros((2, 2, 2)),), raises=InputError, why="3-D"),
    # MatchResult (a plain record)
    Case(M.MatchResult, (1.0, 2.0, 0.0, 0.0, (1, 2), 0.9, 0.1, True, ""), raises=None, why="plain record",
         check=lambda r: r.x == 1.0),
    # match_point
    Case(M.match_point, (IMG, IMG, (2, 20)), raises=InputError, match="border", why="template at the border"),
    Case(M.match_point, (IMG, IMG, (20, 20), (35, 20)), raises=InputError, match="border",
         why="search area beyond the border"),
    Case(M.match_point, (IMG, IMG[:, :30], (20, 20)), kwargs={"search_radius": 3, "half_window": 3}, raises=None,
         why="images of different sizes are allowed when the windows fit", check=lambda m: m.integer == (20, 20)),
    Case(M.match_point, (NANIMG, IMG, (20, 20)), kwargs={"search_radius": 3}, raises=InputError, why="NaN pixels"),
    Case(M.match_point, (FLAT, IMG, (20, 20)), kwargs={"search_radius": 3}, raises=DegenerateGeometryError,
         why="textureless template"),
    Case(M.match_point, (IMG, FLAT, (20, 20)), kwargs={"search_radius": 3}, raises=DegenerateGeometryError,
         why="textureless search area"),
    Case(M.match_point, (IMG, IMG, (20.5, 20)), raises=InputError, why="non-integer centre"),
    Case(M.match_point, (IMG, IMG, (20, 20)), kwargs={"subpixel": "cubic"}, raises=InputError, why="unknown method"),
    Case(M.match_point, (IMG, IMG, (20, 20)), kwargs={"half_window": 0}, raises=InputError, why="zero window"),
    Case(M.match_point, (IMG, IMG, (NAN, 20)), raises=InputError, why="NaN point"),
    # LSMResult
    Case(M.LSMResult, (1.0, 2.0, 0.0, 0.0, {}, 0.1, 0.1, 1.0, 1, [], True), raises=None, why="plain record",
         check=lambda r: r.y == 2.0),
    # lsm_shift
    Case(M.lsm_shift, (IMG, IMG, (3, 20)), raises=InputError, match="border", why="window at the border"),
    Case(M.lsm_shift, (IMG, IMG, (20, 20), (37.5, 20)), raises=InputError, match="border",
         why="approximation at the border"),
    Case(M.lsm_shift, (NANIMG, IMG, (20, 20)), raises=InputError, why="NaN pixels"),
    Case(M.lsm_shift, (IMG, np.where(IMG > 250, INF, IMG), (20, 20)), raises=InputError, why="inf pixels"),
    Case(M.lsm_shift, (FLAT, IMG, (20, 20)), raises=DegenerateGeometryError, why="textureless template"),
    Case(M.lsm_shift, (IMG, FLAT, (20, 20)), raises=DegenerateGeometryError, why="textureless image 2"),
    Case(M.lsm_shift, (IMG, IMG, (20, 20)), kwargs={"interpolation": "nearest"}, raises=InputError,
         why="unknown interpolation"),
    Case(M.lsm_shift, (IMG, IMG, (20, 20)), kwargs={"max_iter": 0}, raises=InputError, why="zero iterations"),
    Case(M.lsm_shift, (IMG, IMG, (20, 20)), raises=None, why="identical images: zero shift",
         check=lambda r: abs(r.p) < 1e-6 and abs(r.q) < 1e-6),
    Case(M.lsm_shift, (np.zeros((3, 3)), IMG, (1, 1)), raises=InputError, why="image smaller than the window"),
    # lsm_affine
    Case(M.lsm_affine, (IMG, IMG, (5, 20)), raises=InputError, why="window at the border"),
    Case(M.lsm_affine, (IMG, IMG, (20, 20)), kwargs={"half_window": 1}, raises=InputError, why="window too small"),
    Case(M.lsm_affine, (NANIMG, IMG, (20, 20)), raises=InputError, why="NaN pixels"),
    Case(M.lsm_affine, (FLAT, IMG, (20, 20)), raises=DegenerateGeometryError, why="textureless"),
    Case(M.lsm_affine, (IMG, IMG[::-1], (20, 20)), kwargs={"half_window": 8},
         raises=(ConvergenceError, DegenerateGeometryError), why="unrelated images: no convergence, no false match"),
    # derivations
    Case(D.lsm_residual, (), raises=None, why="no input", check=lambda r: len(r[1]) == 8),
    Case(D.lsm_partials, ("guessed",), raises=InputError, why="unknown variant"),
    Case(D.lsm_jacobian, (False, "projective"), raises=InputError, why="unknown model"),
    Case(D.parabola_vertex_symbolic, (), raises=None, why="no input", check=lambda r: "vertex" in r),
    Case(D.circle_partials, (), raises=None, why="no input", check=lambda r: callable(r["numpy"])),
    # targets
    Case(T.threshold_target, (IMG, -1, 10), raises=InputError, why="negative T1"),
    Case(T.threshold_target, (NANIMG, 1, 10), raises=InputError, why="NaN"),
    Case(T.threshold_target, (IMG, "a", 10), raises=InputError, why="non-numeric threshold"),
    Case(T.centroid, (np.zeros((4, 4)),), raises=DegenerateGeometryError, why="all zero"),
    Case(T.centroid, (IMG - 100,), raises=InputError, why="negative weights"),
    Case(T.centroid, (NANIMG,), raises=InputError, why="NaN"),
    Case(T.centroid, (np.array([]).reshape(0, 3),), raises=InputError, why="empty"),
    Case(T.gradient_weight, ([-1.0, 2.0],), raises=InputError, why="negative gradient"),
    Case(T.gradient_weight, ([0.0, 0.0],), raises=InputError, why="no edge"),
    Case(T.gradient_weight, ([NAN],), raises=InputError, why="NaN"),
    Case(T.robust_weight, ([1.0], 0.0, 1), raises=InputError, why="mu = 0"),
    Case(T.robust_weight, ([1.0], 1.0, 0), raises=InputError, why="iteration 0"),
    Case(T.robust_weight, ([INF], 1.0, 1), raises=InputError, why="inf residual"),
    Case(T.CircleFit, (1.0, 2.0, 3.0, 0.1, 0.1, 0.1, 1.0, 3), raises=None, why="plain record",
         check=lambda c: c.radius == 3.0),
    Case(T.circle_fit, (FLAT,), raises=DegenerateGeometryError, why="no gradient"),
    Case(T.circle_fit, (NANIMG,), raises=InputError, why="NaN"),
    Case(T.circle_fit, (np.tile(np.r_[np.full(20, 40.0), np.full(20, 200.0)], (40, 1)),),
         raises=DegenerateGeometryError, why="a straight edge is no circle"),
    Case(T.circle_fit, (IMG,), kwargs={"edge_fraction": 1.5}, raises=InputError, why="bad edge fraction"),
    Case(T.kadnichansky_detect, (IMG, -5), raises=InputError, why="negative threshold"),
    Case(T.kadnichansky_detect, (IMG[:5, :5], 40), raises=InputError, why="image smaller than the mask"),
    Case(T.kadnichansky_detect, (IMG, 40), kwargs={"mask": 6}, raises=InputError, why="even mask"),
    Case(T.kadnichansky_detect, (FLAT, 40), raises=DegenerateGeometryError, why="no target"),
    Case(T.kadnichansky_detect, (NANIMG, 40), raises=InputError, why="NaN"),
    Case(T.CrossFit, (1.0, 2.0, (0, 2), (0, 1)), raises=None, why="plain record", check=lambda c: c.y == 2.0),
    Case(T.kadnichansky_center, (IMG, (3, 20)), raises=InputError, match="border", why="at the border"),
    Case(T.kadnichansky_center, (FLAT, (20, 20)), raises=DegenerateGeometryError, why="no edges"),
    Case(T.kadnichansky_center, (IMG, (20, 20)), kwargs={"inner": 9}, raises=InputError, why="inner > reach − 2"),
    Case(T.kadnichansky_center, (NANIMG, (20, 20)), raises=InputError, why="NaN"),
    Case(T.find_targets, (IMG, np.full((5, 5), 3.0)), raises=DegenerateGeometryError, why="textureless template"),
    Case(T.find_targets, (W, IMG), raises=InputError, why="template larger than the image"),
    Case(T.find_targets, (IMG, W, 1.5), raises=InputError, why="threshold above 1"),
    Case(T.find_targets, (NANIMG, W), raises=InputError, why="NaN"),
    Case(T.find_targets, (FLAT, W, 0.5), raises=None, why="flat image: no targets",
         check=lambda r: r.shape == (0, 3)),
]


@pytest.mark.parametrize("case", CASES, ids=lambda c: c.id)
def test_bad_input(case):
    check_case(case)
