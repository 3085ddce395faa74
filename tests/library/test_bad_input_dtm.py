"""Bad-input catalogue for photolib.dtm (Chapter 6, §6.6–6.7): too few / collinear / duplicate
points for a TIN, NaN/inf, wrong shapes, points outside the hull (NaN, documented), levels outside
the height range (no contour), bad filter parameters, degenerate faces, wrong camera types."""

import numpy as np
import pytest

from catalogue import INF, NAN, Case, check_case
from photolib import dtm
from photolib.camera import ExteriorOrientation
from photolib.errors import DegenerateGeometryError, InputError

SQ = [[0, 0], [2, 0], [0, 2], [2, 2]]
TIN = dtm.delaunay_tin(SQ, [0.0, 2.0, 2.0, 4.0])
RAMP = np.add.outer(np.arange(6.0), np.arange(7.0))
NADIR = ExteriorOrientation(0.0, 0.0, 100.0)
ROOF = [[[0, 0, 10], [1, 0, 10], [0, 1, 10]]]

CASES = [
    # delaunay_tin
    Case(dtm.delaunay_tin, ([[0, 0], [1, 1]], [0, 1]), raises=InputError, match="at least 3", why="two points"),
    Case(dtm.delaunay_tin, ([[0, 0], [1, 1], [2, 2], [3, 3]], [0, 1, 2, 3]), raises=DegenerateGeometryError,
         match="collinear", why="collinear points"),
    Case(dtm.delaunay_tin, ([[0, 0], [1, 0], [1, 0]], [0, 1, 1]), raises=InputError, match="at least 3",
         why="only two distinct points after merging a duplicate"),
    Case(dtm.delaunay_tin, (SQ + [[2, 2]], [0, 2, 2, 4, 5]), raises=InputError, match="different heights",
         why="duplicate point with another height"),
    Case(dtm.delaunay_tin, (SQ + [[2, 2]], [0, 2, 2, 4, 4]), raises=None, why="duplicate with the same height: merged",
         check=lambda t: len(t.points) == 4),
    Case(dtm.delaunay_tin, ([[0, 0], [1, 0], [0, NAN]], [0, 1, 2]), raises=InputError, why="NaN coordinate"),
    Case(dtm.delaunay_tin, (SQ, [0, 1, INF, 2]), raises=InputError, why="inf height"),
    Case(dtm.delaunay_tin, (SQ, [0, 1, 2]), raises=InputError, why="fewer heights than points"),
    Case(dtm.delaunay_tin, ([[0, 0, 0], [1, 0, 0], [0, 1, 0]], [0, 1, 2]), raises=InputError, why="3-D points"),
    Case(dtm.delaunay_tin, ([], []), raises=InputError, why="empty"),
    Case(dtm.delaunay_tin, ("points", [0]), raises=InputError, why="a string"),
    # TIN (the constructor trusts delaunay_tin; it stores what it is given)
    Case(dtm.TIN, (np.zeros((3, 2)), np.zeros(3), np.array([[0, 1, 2]]), None), raises=None,
         why="the constructor stores its fields", check=lambda t: repr(t) == "TIN(3 vertices, 1 triangles)"),
    # empty_circumcircle_violations / is_delaunay
    Case(dtm.empty_circumcircle_violations, (SQ, [[0, 1, 4]]), raises=InputError, match="0…3",
         why="index out of range"),
    Case(dtm.empty_circumcircle_violations, (SQ, [[0, 1]]), raises=InputError, why="two indices per triangle"),
    Case(dtm.empty_circumcircle_violations, (SQ, [[0.0, 1.0, 2.0]]), raises=InputError, match="integer",
         why="float indices"),
    Case(dtm.empty_circumcircle_violations, (SQ, np.zeros((0, 3), int)), raises=InputError, why="no triangles"),
    Case(dtm.empty_circumcircle_violations, ([[0, 0], [1, 1], [2, 2]], [[0, 1, 2]]),
         raises=DegenerateGeometryError, match="collinear", why="a flat triangle has no circumcircle"),
    Case(dtm.empty_circumcircle_violations, (SQ, [[0, 1, 2]], -1.0), raises=InputError, why="negative rtol"),
    Case(dtm.empty_circumcircle_violations, ([[0, 0], [1, NAN], [0, 1]], [[0, 1, 2]]), raises=InputError,
         why="NaN vertex"),
    Case(dtm.is_delaunay, (SQ, [[0, 1, 5]]), raises=InputError, why="index out of range"),
    Case(dtm.is_delaunay, ([[0, 0], [1, 1], [2, 2]], [[0, 1, 2]]), raises=DegenerateGeometryError,
         why="flat triangle"),
    Case(dtm.is_delaunay, (SQ, [[0, 1, 3], [0, 3, 2]]), raises=None, why="co-circular square: either diagonal",
         check=lambda ok: ok is True),
    # triangle_planes / tin_heights / grid_from_tin
    Case(dtm.triangle_planes, ("not a tin",), raises=InputError, match="TIN", why="not a TIN"),
    Case(dtm.triangle_planes, (TIN,), raises=None, why="plane z = x + y: A, B, C = 0, 1, 1 in both triangles",
         check=lambda p: np.allclose(p, [[0, 1, 1], [0, 1, 1]])),
    Case(dtm.tin_heights, (TIN, [[5.0, 5.0], [1.0, 1.0]]), raises=None, why="outside the hull → NaN (documented)",
         check=lambda z: np.isnan(z[0]) and z[1] == pytest.approx(2.0)),
    Case(dtm.tin_heights, (TIN, [[NAN, 1.0]]), raises=InputError, why="NaN query point"),
    Case(dtm.tin_heights, (TIN, [[1.0, 1.0, 1.0]]), raises=InputError, why="3-D query point"),
    Case(dtm.tin_heights, (np.zeros((3, 3)), [[1.0, 1.0]]), raises=InputError, why="an array instead of a TIN"),
    Case(dtm.grid_from_tin, (TIN, [0, 1, 2], [0, 0, 1]), raises=InputError, match="monotonic", why="repeated row"),
    Case(dtm.grid_from_tin, (TIN, [0], [0, 1]), raises=InputError, why="one column"),
    Case(dtm.grid_from_tin, (TIN, [[0, 1], [2, 3]], [0, 1]), raises=InputError, why="2-D axis"),
    Case(dtm.grid_from_tin, (TIN, [0, INF], [0, 1]), raises=InputError, why="inf coordinate"),
    Case(dtm.grid_from_tin, (TIN, [-1, 1, 3], [0, 2]), raises=None, why="nodes outside the hull are NaN",
         check=lambda G: np.isnan(G[:, [0, 2]]).all() and np.isfinite(G[:, 1]).all()),
    # contours
    Case(dtm.contours_from_grid, (RAMP, [100.0, -5.0]), raises=None, why="levels outside the range: no contour",
         check=lambda c: c == {100.0: [], -5.0: []}),
    Case(dtm.contours_from_grid, (RAMP, [NAN]), raises=InputError, why="NaN level"),
    Case(dtm.contours_from_grid, (RAMP, []), raises=InputError, why="no level"),
    Case(dtm.contours_from_grid, (np.arange(5.0), 1.0), raises=InputError, why="1-D grid"),
    Case(dtm.contours_from_grid, ([[1.0]], 1.0), raises=InputError, why="1×1 grid"),
    Case(dtm.contours_from_grid, (np.where(RAMP > 3, INF, RAMP), 2.5), raises=InputError, why="inf in the grid"),
    Case(dtm.contours_from_grid, (np.full((3, 3), NAN), 1.0), raises=None, why="all NaN: no data, no contour",
         check=lambda c: c == {1.0: []}),
    Case(dtm.contours_from_grid, (RAMP, 2.5, np.arange(6.0), np.arange(6.0)), raises=InputError,
         match="7 and 6", why="x of the wrong length"),
    Case(dtm.contours_from_grid, (RAMP, 2.5), dict(saddle="middle"), raises=InputError, why="unknown saddle rule"),
    Case(dtm.contours_from_grid, (np.zeros((3, 3)), 0.0), raises=None, why="flat grid at the level: no crossing",
         check=lambda c: c == {0.0: []}),
    Case(dtm.contours_from_tin, (TIN, [10.0]), raises=None, why="level above the TIN", check=lambda c: c == {10.0: []}),
    Case(dtm.contours_from_tin, (TIN, [NAN]), raises=InputError, why="NaN level"),
    Case(dtm.contours_from_tin, (TIN, [[1.0, 2.0]]), raises=InputError, why="2-D levels"),
    Case(dtm.contours_from_tin, (RAMP, 1.0), raises=InputError, match="TIN", why="a grid instead of a TIN"),
    # DSM → DTM
    Case(dtm.pmf_schedule, (0.0, 20.0), raises=InputError, why="zero cell size"),
    Case(dtm.pmf_schedule, (1.0, 2.0), raises=InputError, match="3 cells", why="window below 3 cells"),
    Case(dtm.pmf_schedule, (1.0, 20.0), dict(base=1.0), raises=InputError, why="windows that do not grow"),
    Case(dtm.pmf_schedule, (1.0, 20.0), dict(dh0=2.0, dh_max=1.0), raises=InputError, why="dh_max < dh0"),
    Case(dtm.pmf_schedule, (1.0, NAN), raises=InputError, why="NaN window"),
    Case(dtm.pmf_schedule, (1.0, 20.0), dict(slope=-0.1), raises=InputError, why="negative slope"),
    Case(dtm.filter_dsm, (np.where(RAMP > 3, NAN, RAMP), 1.0), dict(max_window=5.0), raises=InputError,
         why="NaN cells (fill gaps first)"),
    Case(dtm.filter_dsm, (np.zeros((2, 9)), 1.0), raises=InputError, why="grid smaller than 3×3"),
    Case(dtm.filter_dsm, (np.zeros(9), 1.0), raises=InputError, why="1-D DSM"),
    Case(dtm.filter_dsm, (RAMP, -1.0), raises=InputError, why="negative cell size"),
    Case(dtm.filter_dsm, (RAMP, 1.0), dict(max_window=5.0), raises=None, why="a tilted plane is all ground",
         check=lambda r: not r.objects.any() and np.array_equal(r.dtm, RAMP)),
    Case(dtm.GroundFilterResult, (np.zeros((2, 2)), np.zeros((2, 2), bool)), raises=None, why="a plain record",
         check=lambda r: r.dtm.shape == (2, 2)),
    # §6.7 texture choice
    Case(dtm.select_texture_images, (ROOF, [NADIR]), raises=None, why="nadir camera for a roof",
         check=lambda c: c.image.tolist() == [0]),
    Case(dtm.select_texture_images, (ROOF, []), raises=InputError, why="no camera"),
    Case(dtm.select_texture_images, (ROOF, [NADIR, "camera"]), raises=InputError, match=r"orientations\[1\]",
         why="not an ExteriorOrientation"),
    Case(dtm.select_texture_images, ([[[0, 0, 0], [1, 1, 1], [2, 2, 2]]], [NADIR]), raises=DegenerateGeometryError,
         why="collinear face vertices"),
    Case(dtm.select_texture_images, ([[[0, 0], [1, 0], [0, 1]]], [NADIR]), raises=InputError, why="2-D vertices"),
    Case(dtm.select_texture_images, ([[[0, 0, NAN], [1, 0, 0], [0, 1, 0]]], [NADIR]), raises=InputError,
         why="NaN vertex"),
    Case(dtm.select_texture_images, ([[[0, 0, 10], [0, 1, 10], [1, 0, 10]]], [NADIR]), raises=None,
         why="a face turned away from every camera: −1", check=lambda c: c.image.tolist() == [-1]),
    Case(dtm.TextureChoice, (np.array([0]), np.array([0.0])), raises=None, why="a plain record",
         check=lambda c: c.image[0] == 0),
]


@pytest.mark.parametrize("case", CASES, ids=lambda c: c.id)
def test_bad_input(case):
    check_case(case)
