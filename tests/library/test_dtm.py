"""photolib.dtm (Chapter 6, §6.6–6.7): TIN, grid from TIN, contours, DSM → DTM, texture choice.

Expected values come from analytic truth (planes, a cone), independent implementations
(scipy's LinearNDInterpolator, numpy's 3×3 solve of the book's system, a brute-force incircle
determinant, scikit-image's find_contours) and synthetic ground truth (the scene renderer's
ground and building masks, or a small scene built here) — never from photolib.dtm's own output.
"""

import numpy as np
import pytest
from scipy import ndimage
from scipy.interpolate import LinearNDInterpolator

from photolib import dtm
from photolib.camera import ExteriorOrientation


def cross2(a, b):
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


def random_tin(n=80, seed=0, offset=(0.0, 0.0), plane=None):
    rng = np.random.default_rng(seed)
    xy = rng.uniform(0, 100, (n, 2)) + np.asarray(offset)
    xy = np.vstack([xy, [[0, 0], [100, 0], [0, 100], [100, 100]] + np.asarray(offset)])
    if plane is None:
        z = 10 + 0.05 * xy[:, 0] + 3 * np.sin(xy[:, 1] / 15)
    else:
        a, b, c = plane
        z = a + b * xy[:, 0] + c * xy[:, 1]
    return xy, z


# --- (6.6.1): grid from the TIN --------------------------------------------------------------------
@pytest.mark.parametrize("seed", range(5))
def test_tin_grid_is_exact_on_any_plane(seed):
    rng = np.random.default_rng(100 + seed)
    a, b, c = rng.uniform(-50, 50), rng.uniform(-2, 2), rng.uniform(-2, 2)
    xy, z = random_tin(60, seed, plane=(a, b, c))
    tin = dtm.delaunay_tin(xy, z)
    x, y = np.linspace(0, 100, 41), np.linspace(100, 0, 37)          # y decreasing: north-up
    G = dtm.grid_from_tin(tin, x, y)
    X, Y = np.meshgrid(x, y)
    assert np.all(np.isfinite(G))                                      # the corners span the grid
    np.testing.assert_allclose(G, a + b * X + c * Y, rtol=0, atol=1e-12)


def test_tin_grid_is_exact_on_a_plane_with_map_coordinates():
    """Large coordinates (UTM-like): the centred form keeps the plane exact to 1e-12 relative."""
    a, b, c = 150.0, 0.01, -0.02
    off = (5.4e5, 6.1e6)
    xy, z = random_tin(50, 7, offset=off, plane=(a, b, c))
    tin = dtm.delaunay_tin(xy, z)
    x, y = off[0] + np.linspace(0, 100, 21), off[1] + np.linspace(0, 100, 21)
    X, Y = np.meshgrid(x, y)
    truth = a + b * (X - off[0]) + c * (Y - off[1]) + b * off[0] + c * off[1]
    np.testing.assert_allclose(dtm.grid_from_tin(tin, x, y), truth, rtol=1e-12, atol=0)


def test_triangle_planes_solve_the_books_three_equations():
    xy, z = random_tin(30, 1)
    tin = dtm.delaunay_tin(xy, z)
    ABC = dtm.triangle_planes(tin)
    for k, tri in enumerate(tin.triangles):
        M = np.column_stack([np.ones(3), xy[tri]])                     # A + B X_k + C Y_k = Z_k
        np.testing.assert_allclose(ABC[k], np.linalg.solve(M, z[tri]), rtol=1e-9, atol=1e-9)


def test_tin_heights_equal_scipy_linear_interpolation():
    xy, z = random_tin(80, 2)
    tin = dtm.delaunay_tin(xy, z)
    q = np.random.default_rng(5).uniform(-10, 110, (500, 2))
    ours = dtm.tin_heights(tin, q)
    ref = LinearNDInterpolator(xy, z)(q)
    np.testing.assert_array_equal(np.isnan(ours), np.isnan(ref))       # NaN exactly outside the hull
    ok = ~np.isnan(ref)
    assert ok.sum() > 300 and (~ok).sum() > 50
    np.testing.assert_allclose(ours[ok], ref[ok], rtol=0, atol=1e-10)


def test_tin_interpolates_its_vertices():
    xy, z = random_tin(40, 3)
    tin = dtm.delaunay_tin(xy, z)
    np.testing.assert_allclose(dtm.tin_heights(tin, xy), z, atol=1e-12)


def test_duplicate_points_with_equal_heights_are_merged():
    xy = [[0, 0], [1, 0], [0, 1], [1, 1], [1, 0]]
    tin = dtm.delaunay_tin(xy, [0, 1, 1, 2, 1])
    assert len(tin.points) == 4 and len(tin.triangles) == 2


# --- the empty-circumcircle property (§6.6) --------------------------------------------------------
def incircle_brute_force(xy, triangles):
    """Independent check: the incircle determinant for every (triangle, other point) pair."""
    bad = 0
    for t in triangles:
        a, b, c = xy[t]
        if cross2(b - a, c - a) < 0:
            b, c = c, b
        for k, d in enumerate(xy):
            if k in t:
                continue
            M = np.array([[*(p - d), (p - d) @ (p - d)] for p in (a, b, c)])
            scale = max(np.abs(M[:, :2]).max(), 1.0) ** 4
            bad += np.linalg.det(M) > 1e-9 * scale
    return bad


@pytest.mark.parametrize("seed", range(3))
def test_delaunay_tin_has_empty_circumcircles(seed):
    xy, z = random_tin(50, seed)
    tin = dtm.delaunay_tin(xy, z)
    assert dtm.is_delaunay(tin.points, tin.triangles)
    assert incircle_brute_force(tin.points, tin.triangles) == 0
    # triangles are counter-clockwise
    p, t = tin.points, tin.triangles
    assert np.all(cross2(p[t[:, 1]] - p[t[:, 0]], p[t[:, 2]] - p[t[:, 0]]) > 0)


def test_a_flipped_edge_violates_the_rule():
    """Flip one interior edge of a Delaunay TIN: both new triangles hold a foreign vertex."""
    xy, z = random_tin(40, 4)
    tin = dtm.delaunay_tin(xy, z)
    tri = tin.triangles.copy()
    nb = tin.delaunay.neighbors
    for k in range(len(tri)):
        for j in range(3):
            m = nb[k, j]
            if m < 0:
                continue
            a = tri[k, j]                                              # vertex opposite the shared edge
            shared = [v for v in tri[k] if v != a]
            d = [v for v in tri[m] if v not in shared][0]
            # the flip is valid only for a convex quadrilateral a–s0–d–s1
            q = tin.points[[a, shared[0], d, shared[1]]]
            cr = [cross2(q[(i + 1) % 4] - q[i], q[(i + 2) % 4] - q[(i + 1) % 4]) for i in range(4)]
            if all(c > 0 for c in cr) or all(c < 0 for c in cr):
                tri[k] = [a, shared[0], d]
                tri[m] = [a, d, shared[1]]
                viol = dtm.empty_circumcircle_violations(tin.points, tri)
                assert not dtm.is_delaunay(tin.points, tri)
                assert incircle_brute_force(tin.points, tri[[k, m]]) > 0
                assert set(viol[:, 0]) == {k, m}
                return
    pytest.fail("no flippable edge found")


def test_cocircular_points_are_not_violations():
    """A square lattice: all four corners of each cell are co-circular (either diagonal is Delaunay)."""
    X, Y = np.meshgrid(np.arange(6.0), np.arange(5.0))
    xy = np.column_stack([X.ravel(), Y.ravel()])
    tin = dtm.delaunay_tin(xy, np.zeros(len(xy)))
    assert dtm.is_delaunay(tin.points, tin.triangles)
    assert len(tin.triangles) == 2 * 5 * 4


# --- contours (Fig. 6.17) -------------------------------------------------------------------------
PLANE = (3.0, 0.37, -0.21)


def test_grid_contours_of_a_plane_lie_on_their_lines():
    a, b, c = PLANE
    x, y = np.linspace(0, 50, 26), np.linspace(0, 40, 21)
    X, Y = np.meshgrid(x, y)
    Z = a + b * X + c * Y
    levels = np.arange(-4.0, 21.0, 2.5)
    cs = dtm.contours_from_grid(Z, levels, x, y)
    for level, lines in cs.items():
        inside = Z.min() < level < Z.max()
        assert len(lines) == (1 if inside else 0)
        for p in lines:
            np.testing.assert_allclose(a + b * p[:, 0] + c * p[:, 1], level, atol=1e-12)
            # an open line from border to border, vertices on the grid lines
            assert not np.allclose(p[0], p[-1])
            on_x = np.isclose(p[:, 0][:, None], x[None, :], atol=1e-9).any(axis=1)
            on_y = np.isclose(p[:, 1][:, None], y[None, :], atol=1e-9).any(axis=1)
            assert np.all(on_x | on_y)
            for end in (p[0], p[-1]):
                assert np.isclose(end[0], [0, 50]).any() or np.isclose(end[1], [0, 40]).any()


def test_tin_contours_of_a_plane_lie_on_their_lines():
    a, b, c = PLANE
    xy, z = random_tin(70, 8, plane=PLANE)
    tin = dtm.delaunay_tin(xy, z)
    for level, lines in dtm.contours_from_tin(tin, [5.0, 10.0, 20.0]).items():
        assert len(lines) == 1
        np.testing.assert_allclose(a + b * lines[0][:, 0] + c * lines[0][:, 1], level, atol=1e-12)


def test_tin_contour_vertices_are_on_tin_edges_at_the_level():
    """Independent check on a curved surface: scipy's linear interpolation at every vertex = level."""
    xy, z = random_tin(120, 9)
    tin = dtm.delaunay_tin(xy, z)
    ref = LinearNDInterpolator(xy, z)
    for level, lines in dtm.contours_from_tin(tin, [8.0, 10.0, 12.5]).items():
        assert lines
        for p in lines:
            np.testing.assert_allclose(ref(p), level, atol=1e-9)


def test_grid_contours_of_a_cone_are_circles():
    """Cone Z = 20 − r with its apex on a node, 1 m grid: a closed polyline per level, all vertices
    within s²/(8(R − s)) of the circle of radius R = 20 − level (linear interpolation of r along a
    side of length s), and exact on the row and column through the apex (r is linear there)."""
    x = y = np.arange(-30.0, 31.0)
    X, Y = np.meshgrid(x, y)
    Z = 20 - np.hypot(X, Y)
    for level in (2.5, 7.0, 12.3):
        R = 20 - level
        lines = dtm.contours_from_grid(Z, level, x, y)[level]
        assert len(lines) == 1
        p = lines[0]
        np.testing.assert_array_equal(p[0], p[-1])                     # closed
        r = np.hypot(p[:, 0], p[:, 1])
        assert np.max(np.abs(r - R)) <= 1.0 / (8 * (R - 1))
        axis = np.isclose(p[:, 0], 0) | np.isclose(p[:, 1], 0)
        assert axis.sum() >= 4                                         # the 4 axis crossings
        np.testing.assert_allclose(r[axis], R, atol=1e-12)
        # the enclosed area (shoelace) approaches πR² (inscribed polygon: slightly less)
        area = 0.5 * abs(np.dot(p[:-1, 0], p[1:, 1]) - np.dot(p[1:, 0], p[:-1, 1]))
        assert 0.98 * np.pi * R ** 2 < area < np.pi * R ** 2


def _vertex_sets(lines, swap=False):
    out = []
    for p in lines:
        q = p[:, ::-1] if swap else p
        out.append(frozenset(map(tuple, np.round(q, 9))))
    return sorted(out, key=sorted)


@pytest.mark.parametrize("seed", range(3))
def test_grid_contours_agree_with_scikit_image(seed):
    measure = pytest.importorskip("skimage.measure")
    rng = np.random.default_rng(seed)
    Z = ndimage.gaussian_filter(rng.normal(size=(40, 55)), 2.5) * 10
    levels = np.quantile(Z, [0.1, 0.3, 0.5, 0.8])
    ours = dtm.contours_from_grid(Z, levels, saddle="low")             # skimage's default rule
    for level in levels:
        theirs = measure.find_contours(Z, level)                       # (row, col) vertices
        assert len(ours[float(level)]) == len(theirs)
        assert _vertex_sets(ours[float(level)]) == _vertex_sets(theirs, swap=True)
        closed_ours = sorted(np.allclose(p[0], p[-1]) for p in ours[float(level)])
        closed_theirs = sorted(np.allclose(p[0], p[-1]) for p in theirs)
        assert closed_ours == closed_theirs


def test_saddle_rule():
    Z = np.array([[1.0, 0.0], [0.0, 1.0]])
    low = dtm.contours_from_grid(Z, 0.5, saddle="low")[0.5]
    high = dtm.contours_from_grid(Z, 0.5, saddle="high")[0.5]
    # low connected: the two high corners (0,0) and (1,1) are cut off
    cut = lambda lines: sorted(tuple(np.round(p.mean(axis=0), 6)) for p in lines)  # noqa: E731
    assert cut(low) == [(0.25, 0.25), (0.75, 0.75)]
    assert cut(high) == [(0.25, 0.75), (0.75, 0.25)]
    # centre rule: the mean 0.5 is not above 0.5 → like "low"
    assert cut(dtm.contours_from_grid(Z, 0.5)[0.5]) == cut(low)


def test_grid_contours_skip_no_data_squares():
    x = np.arange(10.0)
    X, Y = np.meshgrid(x, x)
    Z = X.copy()
    Z[4, :] = np.nan                                                   # a row without data
    lines = dtm.contours_from_grid(Z, 5.5)[5.5]
    assert len(lines) == 2                                             # the line is cut in two
    assert all(np.allclose(p[:, 0], 5.5) for p in lines)


# --- DSM → DTM (progressive morphological filter) ----------------------------------------------------
def test_pmf_schedule_follows_zhang():
    w, dh = dtm.pmf_schedule(0.5, 30.0, slope=0.2, dh0=0.25, dh_max=2.0, base=2.0)
    # w_k = 2·2^k + 1 cells while below 30 m / 0.5 m = 60 cells → 59 (odd)
    assert w.tolist() == [5, 9, 17, 33, 59]
    expected = [0.25] + [min(0.2 * (b - a) * 0.5 + 0.25, 2.0) for a, b in zip(w[:-1], w[1:])]
    np.testing.assert_allclose(dh, expected)


def small_scene(seed=0):
    """Own synthetic scene (used if the renderer is absent): smooth ground, boxes, round trees."""
    rng = np.random.default_rng(seed)
    n, cell = 120, 1.0
    X, Y = np.meshgrid(np.arange(n) * cell, np.arange(n) * cell)
    ground = 100 + 4 * np.sin(X / 25) + 3 * np.cos(Y / 30) + 0.02 * X
    surface = ground.copy()
    buildings = np.zeros_like(ground, bool)
    for _ in range(6):
        w, h = rng.integers(8, 25, 2)
        r, c = rng.integers(5, n - 30, 2)
        buildings[r:r + h, c:c + w] = True
        surface[r:r + h, c:c + w] = ground[r:r + h, c:c + w].max() + rng.uniform(6, 15)
    trees = np.zeros_like(buildings)
    for _ in range(10):
        cx, cy, rad, ht = *rng.uniform(5, 115, 2), rng.uniform(2, 4), rng.uniform(4, 10)
        d = np.hypot(X - cx, Y - cy)
        canopy = ht * np.sqrt(np.clip(1 - (d / rad) ** 2, 0, None))
        m = (canopy > 0.3) & ~buildings
        surface[m] = np.maximum(surface[m], ground[m] + canopy[m])
        trees |= m
    return ground, surface, buildings, trees, cell


def scene_grids():
    try:
        from photolib.synthetic import terrain_scene
    except ImportError:
        return small_scene()
    s = terrain_scene(extent=150.0, spacing=1.0, n_buildings=6, n_trees=10, seed=3)
    return s.ground, s.surface, s.buildings, s.trees, s.spacing


def test_filter_dsm_removes_buildings_and_trees():
    """The slope parameter s is set from the terrain as a user would (its steepest slope, rounded
    up to 0.05); dh0 = 0.3 m for 5 cm height noise. Targets set before the run: ≥ 98 % of building
    cells and of tree cells higher than dh0 + 4σ = 0.5 m flagged (lower canopy rims cannot be told
    from noise by construction), ≥ 95 % of all tree cells, ≤ 2 % of bare ground cells flagged,
    DTM RMSE vs true ground ≤ 0.3 m over all cells and ≤ 0.06 m on bare ground."""
    ground, surface, buildings, trees, cell = scene_grids()
    gy, gx = np.gradient(ground, cell)
    slope = np.ceil(np.hypot(gx, gy).max() / 0.05) * 0.05
    rng = np.random.default_rng(11)
    noisy = surface + rng.normal(0, 0.05, surface.shape)                # 5 cm height noise
    dtm_grid, objects = dtm.filter_dsm(noisy, cell, max_window=40.0, slope=slope, dh0=0.3, dh_max=3.0)
    bare = ~(buildings | trees)
    assert objects[buildings].mean() >= 0.98
    assert objects[trees & (surface - ground > 0.5)].mean() >= 0.98
    assert objects[trees].mean() >= 0.95
    assert objects[bare].mean() <= 0.02
    rmse = np.sqrt(np.mean((dtm_grid - ground) ** 2))
    assert rmse <= 0.3
    assert np.sqrt(np.mean((dtm_grid - ground)[bare] ** 2)) <= 0.06
    assert np.sqrt(np.mean((surface - ground) ** 2)) > 3                 # the DSM itself was far off


def test_filter_dsm_on_an_own_scene():
    """The same targets on a scene built here (steeper ground, up to 0.21)."""
    ground, surface, buildings, trees, cell = small_scene()
    noisy = surface + np.random.default_rng(12).normal(0, 0.05, surface.shape)
    dtm_grid, objects = dtm.filter_dsm(noisy, cell, max_window=40.0, slope=0.25)
    bare = ~(buildings | trees)
    assert objects[buildings].mean() >= 0.98
    assert objects[trees & (surface - ground > 0.5)].mean() >= 0.98
    assert objects[bare].mean() <= 0.02
    assert np.sqrt(np.mean((dtm_grid - ground) ** 2)) <= 0.3


def test_filter_dsm_keeps_a_tilted_plane():
    X, Y = np.meshgrid(np.arange(60.0), np.arange(50.0))
    ground = 50 + 0.25 * X - 0.1 * Y                                    # 14° slope, below `slope`
    dtm_grid, objects = dtm.filter_dsm(ground, 1.0, max_window=21.0, slope=0.3)
    assert not objects.any()
    np.testing.assert_array_equal(dtm_grid, ground)


# --- §6.7: texture images -----------------------------------------------------------------------------
def look_at(centre, target):
    """An ExteriorOrientation at ``centre`` whose optical axis (−z of the camera) points at target."""
    d = np.asarray(target, float) - np.asarray(centre, float)
    d /= np.linalg.norm(d)
    zc = -d
    up = np.array([0.0, 1.0, 0.0]) if abs(d[1]) < 0.9 else np.array([1.0, 0.0, 0.0])
    xc = np.cross(up, zc)
    xc /= np.linalg.norm(xc)
    yc = np.cross(zc, xc)
    return ExteriorOrientation.from_matrix(centre, np.column_stack([xc, yc, zc]))


def box_faces(x0=0, x1=10, y0=0, y1=10, z0=0, z1=8):
    """Roof and four walls of a box as triangles, counter-clockwise seen from outside."""
    P = lambda x, y, z: [x, y, z]  # noqa: E731
    roof = [[P(x0, y0, z1), P(x1, y0, z1), P(x1, y1, z1)]]
    south = [[P(x0, y0, z0), P(x1, y0, z0), P(x1, y0, z1)]]             # normal −Y
    north = [[P(x1, y1, z0), P(x0, y1, z0), P(x0, y1, z1)]]             # normal +Y
    east = [[P(x1, y0, z0), P(x1, y1, z0), P(x1, y1, z1)]]              # normal +X
    west = [[P(x0, y1, z0), P(x0, y0, z0), P(x0, y0, z1)]]              # normal −X
    return np.array(roof + south + north + east + west, float)


def test_texture_choice_picks_the_facing_camera():
    faces = box_faces()
    c = np.array([5.0, 5.0, 4.0])
    cams = [ExteriorOrientation(5.0, 5.0, 300.0),                      # 0 nadir
            look_at([5, -60, 70], c),                                  # 1 from the south, 45°-ish
            look_at([5, 70, 70], c),                                   # 2 from the north
            look_at([75, 5, 70], c),                                   # 3 from the east
            look_at([-60, 5, 70], c)]                                  # 4 from the west
    # check the face normals of the construction independently
    n = np.cross(faces[:, 1] - faces[:, 0], faces[:, 2] - faces[:, 0])
    np.testing.assert_allclose(n / np.linalg.norm(n, axis=1)[:, None],
                               [[0, 0, 1], [0, -1, 0], [0, 1, 0], [1, 0, 0], [-1, 0, 0]], atol=1e-12)
    choice = dtm.select_texture_images(faces, cams)
    assert choice.image.tolist() == [0, 1, 2, 3, 4]
    assert choice.angle[0] == pytest.approx(0, abs=1e-12)
    # the oblique cameras look down about 45–50°: angle to the wall normal ≈ their depression
    for k, cam in zip(range(1, 5), cams[1:]):
        d = cam.matrix @ [0, 0, -1]
        assert choice.angle[k] == pytest.approx(np.arcsin(-d[2]), abs=1e-9)


def test_texture_choice_ignores_cameras_behind_the_face():
    faces = box_faces()
    cams = [look_at([5, 70, 70], [5, 5, 4])]                           # only the north camera
    choice = dtm.select_texture_images(faces, cams)
    assert choice.image.tolist() == [0, -1, 0, -1, -1]                 # sees roof and north wall only
    assert np.isnan(choice.angle[1]) and np.isfinite(choice.angle[2])


def test_texture_choice_prefers_the_steeper_of_two_views():
    roof = box_faces()[:1]
    cams = [look_at([5, -200, 120], [5, 5, 8]), look_at([5, -40, 300], [5, 5, 8])]
    assert dtm.select_texture_images(roof, cams).image.tolist() == [1]
