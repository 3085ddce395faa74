"""Bad-input catalogue for photolib.features and photolib.ransac (Chapter 5, §5.5, §5.7–5.10):
NaN/inf pixels, wrong dimensions, empty and too small images, bad windows and options, points
at the border, mismatched sizes, too few correspondences, textureless images (no points, not
an error), degenerate samples and no consensus."""

import numpy as np
import pytest

from catalogue import INF, NAN, Case, check_case
from photolib import features as ft
from photolib import ransac as rs
from photolib.camera import InteriorOrientation
from photolib.errors import ConvergenceError, DegenerateGeometryError, InputError

rng = np.random.default_rng(0)
IMG = rng.uniform(0, 255, (32, 32))
NAN_IMG = IMG.copy(); NAN_IMG[3, 4] = NAN
INF_IMG = IMG.copy(); INF_IMG[5, 5] = INF
FLAT = np.full((32, 32), 50.0)
RGB = np.zeros((32, 32, 3))
IO = InteriorOrientation(100.0)
XY = rng.uniform(-50, 50, (12, 2))
XY_NAN = XY.copy(); XY_NAN[0, 0] = NAN


def empty_points(result):
    return np.asarray(result).shape == (0, 2)


def _line_fit(s):
    return np.polyfit(s[:, 0], s[:, 1], 1)


def _line_res(m, d):
    return np.abs(np.polyval(m, d[:, 0]) - d[:, 1])


def _always_degenerate(s):
    raise DegenerateGeometryError("degenerate sample")


IMAGE_FUNCTIONS = [ft.gradient_backward, ft.gradient_sobel, ft.gradient_prewitt, ft.gradient_roberts,
                   ft.moravec, ft.harris, ft.foerstner, ft.fast, ft.log_filter, ft.zero_crossings,
                   ft.nonmax_suppression, ft.interest_points]

CASES = []
for fn in IMAGE_FUNCTIONS:
    CASES += [
        Case(fn, (NAN_IMG,), raises=InputError, match="NaN", why="NaN pixel"),
        Case(fn, (INF_IMG,), raises=InputError, match="NaN or inf", why="inf pixel"),
        Case(fn, (RGB,), raises=InputError, match="2-D", why="colour (3-D) array"),
        Case(fn, (IMG[0],), raises=InputError, match="2-D", why="1-D array"),
        Case(fn, ("image.png",), raises=InputError, why="a file name instead of an array"),
    ]

CASES += [
    # gradients
    Case(ft.gradient_sobel, (IMG,), {"border": "wrap"}, raises=InputError, match="border", why="unknown border"),
    Case(ft.gradient_roberts, (IMG,), {"anchor": "centre"}, raises=InputError, match="anchor", why="unknown anchor"),
    Case(ft.gradient_backward, (np.zeros((0, 3)),), raises=InputError, why="empty image"),
    Case(ft.gradient_sobel, (FLAT,), raises=None, check=lambda g: not np.any(g[0]) and not np.any(g[1]),
         why="textureless: zero gradient"),
    Case(ft.gradient_magnitude, (np.ones(3), np.ones(4)), raises=InputError, match="shape", why="mismatched sizes"),
    Case(ft.gradient_magnitude, (np.array([NAN]), np.ones(1)), raises=InputError, match="NaN", why="NaN"),
    Case(ft.gradient_magnitude, (np.ones(2), np.ones(2)), {"norm": "l3"}, raises=InputError, why="unknown norm"),
    Case(ft.gradient_magnitude, (np.ones(0), np.ones(0)), raises=InputError, match="empty", why="empty"),
    # detectors
    Case(ft.moravec, (IMG,), {"window": 4}, raises=InputError, match="odd", why="even window"),
    Case(ft.moravec, (IMG[:3, :3],), raises=InputError, match="smaller", why="image smaller than the window"),
    Case(ft.moravec, (IMG,), {"variant": "x"}, raises=InputError, match="variant", why="unknown variant"),
    Case(ft.moravec, (FLAT,), raises=None, check=lambda M: not np.any(M), why="textureless: M = 0"),
    Case(ft.harris, (IMG,), {"k": 0.3}, raises=InputError, match="k", why="k outside (0, 0.25)"),
    Case(ft.harris, (IMG,), {"weight": "cone"}, raises=InputError, match="weight", why="unknown weight"),
    Case(ft.harris, (IMG,), {"gradient": "canny"}, raises=InputError, match="gradient", why="unknown gradient"),
    Case(ft.harris, (IMG,), {"sigma": -1.0}, raises=InputError, match="sigma", why="negative sigma"),
    Case(ft.foerstner, (IMG,), {"window": 2}, raises=InputError, why="even window"),
    Case(ft.foerstner, (FLAT,), raises=None, check=lambda wq: not np.any(wq[0]) and not np.any(wq[1]),
         why="textureless: w = q = 0, no division by zero"),
    Case(ft.fast, (IMG,), {"threshold": 0}, raises=InputError, match="threshold", why="zero threshold"),
    Case(ft.fast, (IMG,), {"n": 17}, raises=InputError, match="n", why="arc longer than the circle"),
    Case(ft.fast, (IMG[:5, :5],), raises=InputError, match="smaller", why="image smaller than the circle"),
    Case(ft.log_kernel, (0.0,), raises=InputError, match="sigma", why="sigma = 0"),
    Case(ft.log_kernel, (NAN,), raises=InputError, match="sigma", why="NaN sigma"),
    Case(ft.log_kernel, (1.0,), {"radius": 0}, raises=InputError, match="radius", why="radius 0"),
    Case(ft.log_filter, (IMG,), {"sigma": -2.0}, raises=InputError, why="negative sigma"),
    Case(ft.zero_crossings, (IMG,), {"min_contrast": -1.0}, raises=InputError, why="negative contrast"),
    Case(ft.nonmax_suppression, (IMG,), {"size": 4}, raises=InputError, why="even size"),
    Case(ft.nonmax_suppression, (IMG,), {"relative": 1.5}, raises=InputError, why="relative ≥ 1"),
    Case(ft.nonmax_suppression, (IMG,), {"max_points": -1}, raises=InputError, why="negative max_points"),
    Case(ft.nonmax_suppression, (IMG,), {"threshold": NAN}, raises=InputError, why="NaN threshold"),
    Case(ft.nonmax_suppression, (FLAT,), raises=None, check=empty_points, why="flat response: no points"),
    Case(ft.interest_points, (IMG,), {"operator": "sift"}, raises=InputError, match="operator", why="unknown operator"),
    Case(ft.interest_points, (FLAT,), {"operator": "harris"}, raises=None, check=empty_points,
         why="textureless: no points, not an error"),
    Case(ft.interest_points, (FLAT,), {"operator": "log"}, raises=None, check=empty_points,
         why="textureless LoG: round-off is not a point"),
    Case(ft.interest_points, (IMG,), {"operator": "foerstner", "q_min": 2.0}, raises=InputError, why="q_min > 1"),
    # descriptors
    Case(ft.sift_descriptors, (IMG, [[2.0, 2.0]]), raises=InputError, match="border", why="region at the border"),
    Case(ft.sift_descriptors, (IMG, [[16.0, NAN]]), raises=InputError, match="NaN", why="NaN point"),
    Case(ft.sift_descriptors, (IMG, np.zeros((3, 3))), raises=InputError, match="shape", why="points not (n, 2)"),
    Case(ft.sift_descriptors, (NAN_IMG, [[16.0, 16.0]]), raises=InputError, match="NaN", why="NaN pixel"),
    Case(ft.sift_descriptors, (RGB, [[16.0, 16.0]]), raises=InputError, match="2-D", why="colour image"),
    Case(ft.sift_descriptors, (IMG, [[16.0, 16.0]]), {"cells": 0}, raises=InputError, why="zero cells"),
    Case(ft.sift_descriptors, (IMG, [[16.0, 16.0]]), {"clip": 0.0}, raises=InputError, why="clip 0"),
    Case(ft.sift_descriptors, (IMG, np.zeros((0, 2))), raises=None,
         check=lambda d: d.vectors.shape == (0, 128), why="no points: empty set"),
    Case(ft.sift_descriptors, (FLAT, [[16.0, 16.0]]), raises=None,
         check=lambda d: not d.valid[0] and not np.any(d.vectors), why="textureless region: flagged invalid"),
    Case(ft.DescriptorSet, (np.zeros((2, 2)), np.zeros(2), np.zeros((3, 128)), np.ones(2, bool)),
         raises=InputError, why="mismatched sizes"),
    Case(ft.DescriptorSet, (np.full((1, 2), NAN), np.zeros(1), np.zeros((1, 128)), np.ones(1, bool)),
         raises=InputError, match="NaN", why="NaN point"),
    Case(ft.match_descriptors, (np.zeros((2, 128)), np.zeros((2, 64))), raises=InputError, match="length",
         why="different descriptor lengths"),
    Case(ft.match_descriptors, (np.full((2, 4), NAN), np.ones((2, 4))), raises=InputError, match="NaN", why="NaN"),
    Case(ft.match_descriptors, (np.ones(4), np.ones((2, 4))), raises=InputError, why="1-D descriptors"),
    Case(ft.match_descriptors, (np.eye(3), np.eye(3)), {"ratio": 0.0}, raises=InputError, why="ratio 0"),
    Case(ft.match_descriptors, (np.eye(3), np.eye(3)[:1]), raises=None, check=lambda m: m.shape == (0, 2),
         why="one candidate: ratio undefined, no match"),
    Case(ft.match_descriptors, (np.zeros((3, 4)), np.zeros((3, 4))), raises=None, check=lambda m: m.shape == (0, 2),
         why="all-zero (textureless) descriptors are never matched"),
    # ransac
    Case(rs.iterations_needed, (1.5, 5), raises=InputError, why="inlier ratio > 1"),
    Case(rs.iterations_needed, (0.5, 0), raises=InputError, why="sample size 0"),
    Case(rs.iterations_needed, (0.5, 5, 1.0), raises=InputError, why="confidence 1"),
    Case(rs.iterations_needed, (NAN, 5), raises=InputError, why="NaN ratio"),
    Case(rs.ransac, (np.zeros((1, 2)), _line_fit, _line_res, 2, 0.1), raises=InputError, match="fewer",
         why="too few observations"),
    Case(rs.ransac, (np.zeros((5, 2)), _line_fit, _line_res, 2, -1.0), raises=InputError, why="negative threshold"),
    Case(rs.ransac, (np.zeros((5, 2)), "fit", _line_res, 2, 1.0), raises=InputError, why="fit not callable"),
    Case(rs.ransac, ((np.zeros(5), np.zeros(4)), _line_fit, _line_res, 2, 1.0), raises=InputError,
         match="length", why="mismatched data arrays"),
    Case(rs.ransac, (XY, _always_degenerate, _line_res, 2, 0.1), {"max_iterations": 10},
         raises=DegenerateGeometryError, match="degenerate", why="all samples degenerate"),
    Case(rs.ransac, (rng.uniform(0, 100, (20, 2)), _line_fit, _line_res, 2, 1e-9), {"max_iterations": 30},
         raises=ConvergenceError, match="consensus", why="no consensus"),
    Case(rs.ransac, (XY, _line_fit, lambda m, d: np.full(len(d), NAN), 2, 0.1), raises=InputError, match="NaN",
         why="residual function returns NaN"),
    Case(rs.RansacResult, (None, np.ones(3, bool), 1, np.zeros(2)), raises=InputError, why="mismatched sizes"),
    Case(rs.essential_from_relative_orientation, (np.eye(3),), raises=InputError, why="not a relative orientation"),
    Case(rs.ransac_relative_orientation, (XY[:5], XY[:5], IO), raises=InputError, match="at least",
         why="too few correspondences"),
    Case(rs.ransac_relative_orientation, (XY_NAN, XY, IO), raises=InputError, match="NaN", why="NaN"),
    Case(rs.ransac_relative_orientation, (XY, XY[:10], IO), raises=InputError, match="shape", why="mismatched sizes"),
    Case(rs.ransac_relative_orientation, (XY, XY, 100.0), raises=InputError, match="InteriorOrientation",
         why="focal length instead of an interior orientation"),
    Case(rs.ransac_relative_orientation, (XY, XY, IO), {"system": "x"}, raises=InputError, why="unknown system"),
    Case(rs.ransac_relative_orientation, (np.c_[np.arange(12.0), np.arange(12.0)],) * 2 + (IO,),
         {"max_iterations": 20}, raises=DegenerateGeometryError, why="collinear points: every sample degenerate"),
    Case(rs.ransac_essential, (XY[:5], XY[:5], IO), raises=InputError, why="too few correspondences"),
    Case(rs.ransac_essential, (XY, XY_NAN, IO), raises=InputError, match="NaN", why="NaN"),
    Case(rs.ransac_fundamental_matrix, (XY[:8], XY[:8], 0.01), raises=InputError, match="at least",
         why="8 points leave no redundancy"),
    Case(rs.ransac_fundamental_matrix, (XY, XY_NAN, 0.01), raises=InputError, match="NaN", why="NaN"),
    Case(rs.ransac_fundamental_matrix, (XY, XY, 0.0), raises=InputError, why="zero threshold"),
    Case(rs.ransac_fundamental_matrix, (XY, rng.uniform(-50, 50, (12, 2)), 1e-9), {"max_iterations": 30},
         raises=ConvergenceError, why="unrelated points: no consensus"),
]


@pytest.mark.parametrize("case", CASES, ids=[c.id for c in CASES])
def test_bad_input(case):
    check_case(case)
