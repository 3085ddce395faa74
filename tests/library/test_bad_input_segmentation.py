"""Bad-input catalogue for photolib.segmentation (Chapter 9, §9.11): NaN/inf and duplicate points,
wrong shapes, empty clouds, too few points for the model, degenerate samples (collinear points for
a plane, coplanar for a sphere, parallel normals for a cylinder), bad thresholds and steps."""

import numpy as np
import pytest

from catalogue import INF, NAN, Case, check_case
from photolib import segmentation as sg
from photolib.derivations import shapes as dsh
from photolib.errors import ConvergenceError, DegenerateGeometryError, InputError

SQ = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0], [0.5, 0.5, 0]], float)
LINE = np.column_stack([np.arange(10.0), 2 * np.arange(10.0), np.zeros(10)])
NANPTS = np.array([[0, 0, 0], [1, 0, NAN], [0, 1, 0], [1, 1, 1]], float)
INFPTS = np.array([[0, 0, 0], [1, 0, INF], [0, 1, 0], [1, 1, 1]], float)
DUP = np.repeat([[1.0, 2.0, 3.0]], 20, axis=0)
rng = np.random.default_rng(0)
GRID = np.column_stack([rng.uniform(0, 20, (400, 2)), rng.normal(0, 0.01, 400)])
PL = sg.Plane(np.array([0, 0, 1.0]), 0.0)

CASES = [
    # models (plain containers)
    Case(sg.Line, (np.zeros(3), np.array([1.0, 0, 0])), raises=None, why="a container", check=lambda r: r.point.shape == (3,)),
    Case(sg.Plane, (np.array([0, 0, 1.0]), 1.0), raises=None, why="a container", check=lambda r: r.d == 1.0),
    Case(sg.Sphere, (np.zeros(3), 1.0), raises=None, why="a container", check=lambda r: r.radius == 1.0),
    Case(sg.Cylinder, (np.zeros(3), np.array([0, 0, 1.0]), 1.0), raises=None, why="a container",
         check=lambda r: r.radius == 1.0),
    Case(sg.Segment, (PL, np.arange(2), 2), raises=None, why="a container", check=lambda r: r.score == 2),
    Case(sg.Normals, (np.zeros((1, 3)), np.zeros(1)), raises=None, why="a container", check=lambda r: len(r) == 2),
    Case(sg.GroundClassification, (np.ones(1, bool), np.zeros((1, 1)), None, np.zeros((1, 1), bool)), raises=None,
         why="a container", check=lambda r: r.ground.all()),
    # (9.11.1)
    Case(sg.plane_from_angles, (NAN, 0.0, 1.0), raises=InputError, why="NaN alpha"),
    Case(sg.plane_from_angles, (0.0, INF, 1.0), raises=InputError, why="inf beta"),
    Case(sg.plane_from_angles, (0.0, 0.0, "p"), raises=InputError, why="a string"),
    Case(sg.plane_angles, ("plane",), raises=InputError, match="Plane", why="not a plane"),
    Case(sg.plane_angles, (sg.Plane(np.zeros(3), 1.0),), raises=InputError, match="non-zero", why="zero normal"),
    Case(sg.plane_angles, (sg.Plane(np.array([NAN, 0, 1]), 1.0),), raises=InputError, why="NaN normal"),
    Case(sg.plane_angles, (sg.Plane(np.array([-1.0, 0, 0]), 2.0),), raises=None, why="α = π folds to α = 0, p → −p",
         check=lambda r: r[0] == 0.0 and r[2] == -2.0),
    # fits
    Case(sg.fit_line, ([[0, 0, 0]],), raises=InputError, match="at least 2", why="one point"),
    Case(sg.fit_line, (DUP,), raises=DegenerateGeometryError, match="coincide", why="duplicate points only"),
    Case(sg.fit_line, (NANPTS,), raises=InputError, match="NaN", why="NaN point"),
    Case(sg.fit_plane, (LINE,), raises=DegenerateGeometryError, match="collinear", why="collinear points"),
    Case(sg.fit_plane, (SQ[:2],), raises=InputError, match="at least 3", why="two points"),
    Case(sg.fit_plane, (INFPTS,), raises=InputError, why="inf"),
    Case(sg.fit_plane, (np.zeros((4, 2)),), raises=InputError, match="shape", why="2-D points"),
    Case(sg.fit_plane, ([],), raises=InputError, why="empty"),
    Case(sg.fit_plane, ("cloud",), raises=InputError, why="a string"),
    Case(sg.fit_plane, (np.vstack([SQ, SQ]),), raises=None, why="duplicated points: the same plane",
         check=lambda p: abs(abs(p.normal[2]) - 1) < 1e-12),
    Case(sg.fit_sphere, (SQ,), raises=DegenerateGeometryError, match="coplanar", why="coplanar points"),
    Case(sg.fit_sphere, (SQ[:3],), raises=InputError, match="at least 4", why="three points"),
    Case(sg.fit_sphere, (NANPTS,), raises=InputError, why="NaN"),
    Case(sg.fit_cylinder, (SQ[:2],), raises=InputError, match="normals", why="two points without normals"),
    Case(sg.fit_cylinder, (SQ[:2], [[0, 0, 1.0], [0, 0, 1.0]]), raises=DegenerateGeometryError, match="parallel",
         why="parallel normals"),
    Case(sg.fit_cylinder, (SQ[:2], [[0, 0, 1.0]]), raises=InputError, match="match", why="mismatched normals"),
    Case(sg.fit_cylinder, (SQ[:2], [[0, 0, 0.0], [1, 0, 0]]), raises=InputError, match="zero", why="zero normal"),
    Case(sg.fit_cylinder, (SQ[:4], np.tile([0, 0, 1.0], (4, 1))), raises=InputError, match="at least 5",
         why="four points"),
    Case(sg.fit_cylinder, (GRID[:50],), raises=DegenerateGeometryError, match="planar", why="a plane, not a cylinder"),
    # distances
    Case(sg.distances, ("model", SQ), raises=InputError, match="unknown model", why="not a model"),
    Case(sg.distances, (PL, NANPTS), raises=InputError, why="NaN"),
    Case(sg.distances, (PL, np.zeros((0, 3))), raises=None, why="no points: no distances", check=lambda d: d.shape == (0,)),
    # normals
    Case(sg.estimate_normals, (SQ, 2), raises=InputError, match="at least 3", why="k = 2"),
    Case(sg.estimate_normals, (SQ, 6), raises=InputError, match="exceed", why="k > n"),
    Case(sg.estimate_normals, (SQ, 3.5), raises=InputError, match="integer", why="float k"),
    Case(sg.estimate_normals, (NANPTS, 3), raises=InputError, why="NaN"),
    # RANSAC
    Case(sg.ransac_shape, (GRID, "cone", 0.1), raises=InputError, match="unknown shape", why="unknown shape"),
    Case(sg.ransac_shape, (SQ[:3], "plane", 0.1), raises=InputError, match="at least 4", why="too few points"),
    Case(sg.ransac_shape, (GRID, "plane", 0.0), raises=InputError, why="zero threshold"),
    Case(sg.ransac_shape, (GRID, "plane", -1.0), raises=InputError, why="negative threshold"),
    Case(sg.ransac_shape, (NANPTS, "line", 0.1), raises=InputError, why="NaN"),
    Case(sg.ransac_shape, (LINE, "plane", 0.1), raises=DegenerateGeometryError, match="degenerate",
         why="collinear cloud: every plane sample degenerate"),
    Case(sg.ransac_shape, (DUP, "line", 0.1), raises=DegenerateGeometryError, why="duplicate points only"),
    Case(sg.ransac_shape, (GRID, "plane", 0.05), {"normals": np.zeros((3, 3))}, raises=InputError, match="match",
         why="mismatched normals"),
    Case(sg.ransac_shape, (GRID, "sphere", 0.001), {"min_inliers": 300, "max_iterations": 50},
         raises=ConvergenceError, why="no sphere in a plane: no consensus"),
    Case(sg.ransac_shape, (GRID, "cylinder", 0.05), raises=DegenerateGeometryError, why="a plane: parallel normals, no cylinder"),
    Case(sg.ransac_shape, (GRID, "plane", 0.05), raises=None, why="a noisy plane is found",
         check=lambda r: r.n_inliers >= 395),
    # detect_shapes
    Case(sg.detect_shapes, (GRID, "plane", 0.05, 0), raises=InputError, why="min_inliers 0"),
    Case(sg.detect_shapes, (GRID, "plane", 0.05, 10, 0), raises=InputError, why="max_shapes 0"),
    Case(sg.detect_shapes, (GRID, "plane", 0.05, 10), {"normals": np.zeros((2, 3))}, raises=InputError,
         why="mismatched normals"),
    Case(sg.detect_shapes, (NANPTS, "line", 0.1, 2), raises=InputError, why="NaN"),
    Case(sg.detect_shapes, (LINE, "plane", 0.1, 3), raises=None, why="collinear cloud: no plane, an empty list",
         check=lambda r: r == []),
    # the sympy models (photolib.derivations.shapes): no input that could be bad
    Case(dsh.sphere_distance_model, (), raises=None, why="no input",
         check=lambda m: len(m.parameters) == 4 and len(m.residuals) == 1),
    Case(dsh.cylinder_distance_model, (), raises=None, why="no input",
         check=lambda m: len(m.parameters) == 5 and len(m.data) == 15),
    # Hough
    Case(sg.hough_planes, (GRID,), {"angle_step": 0.0}, raises=InputError, why="zero angle step"),
    Case(sg.hough_planes, (GRID,), {"angle_step": 2.0}, raises=InputError, why="angle step too large"),
    Case(sg.hough_planes, (GRID,), {"p_step": -1.0}, raises=InputError, why="negative p step"),
    Case(sg.hough_planes, (GRID,), {"min_votes": 2}, raises=InputError, why="min_votes < 3"),
    Case(sg.hough_planes, (DUP,), raises=DegenerateGeometryError, match="coincide", why="duplicate points only"),
    Case(sg.hough_planes, (NANPTS,), raises=InputError, why="NaN"),
    Case(sg.hough_planes, (SQ[:2],), raises=InputError, why="two points"),
    # region growing
    Case(sg.region_growing, (GRID, 0.0), raises=InputError, why="zero distance threshold"),
    Case(sg.region_growing, (GRID, 0.1), {"k": 1000}, raises=InputError, match="exceed", why="k > n"),
    Case(sg.region_growing, (NANPTS, 0.1), {"k": 3}, raises=InputError, why="NaN"),
    Case(sg.region_growing, (GRID, 0.1), {"min_size": 0}, raises=InputError, why="min_size 0"),
    # ground
    Case(sg.lowest_point_raster, (GRID, 0.0), raises=InputError, why="zero cell"),
    Case(sg.lowest_point_raster, (GRID, 1e-6), raises=InputError, match="too small", why="a huge raster"),
    Case(sg.lowest_point_raster, (np.zeros((0, 3)), 1.0), raises=InputError, why="empty"),
    Case(sg.lowest_point_raster, (NANPTS, 1.0), raises=InputError, why="NaN"),
    Case(sg.classify_ground, (GRID, 10.0, 30.0), raises=InputError, match="3 × 3", why="raster of 2 × 2 cells"),
    Case(sg.classify_ground, (GRID, 1.0, 10.0), {"band": -1.0}, raises=InputError, why="negative band"),
    Case(sg.classify_ground, (GRID, 1.0, 10.0), {"slope": NAN}, raises=InputError, why="NaN slope"),
    Case(sg.classify_ground, (INFPTS, 1.0, 10.0), raises=InputError, why="inf"),
    Case(sg.classify_ground, (GRID, 1.0, 10.0), raises=None, why="flat noisy ground: all ground",
         check=lambda r: r.ground.mean() > 0.99),
]


@pytest.mark.parametrize("case", CASES, ids=lambda c: c.id)
def test_bad_input(case):
    check_case(case)
