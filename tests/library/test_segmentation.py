"""photolib.segmentation (Chapter 9, §9.11): Hough planes (9.11.1), RANSAC line/plane/sphere/
cylinder with least-squares refinement, region growing, ground classification.

Ground truth is synthetic (shapes sampled with Gaussian noise plus uniform outliers, seeded) and
independent least squares (scipy.optimize.least_squares) for the refined parameters. Stated
figures: recall = found true points / true points, precision = true points / found points.
"""

import math

import numpy as np
import pytest
from scipy.optimize import least_squares

from photolib import segmentation as sg
from photolib.errors import DegenerateGeometryError


def _unit(v):
    v = np.asarray(v, float)
    return v / np.linalg.norm(v)


def _plane_points(rng, n, normal, d, size=10.0, sigma=0.01):
    normal = _unit(normal)
    u = np.cross(normal, [1.0, 0, 0] if abs(normal[0]) < 0.9 else [0, 1.0, 0])
    u = _unit(u)
    v = np.cross(normal, u)
    st = rng.uniform(-size / 2, size / 2, (n, 2))
    return normal * d + st[:, :1] * u + st[:, 1:] * v + rng.normal(0, sigma, (n, 1)) * normal


def _sphere_points(rng, n, c, r, sigma=0.005):
    d = rng.normal(size=(n, 3))
    d /= np.linalg.norm(d, axis=1)[:, None]
    return c + d * (r + rng.normal(0, sigma, (n, 1))), d


def _cylinder_points(rng, n, p, a, r, length=4.0, sigma=0.005):
    a = _unit(a)
    u = _unit(np.cross(a, [1.0, 0, 0] if abs(a[0]) < 0.9 else [0, 1.0, 0]))
    v = np.cross(a, u)
    t = rng.uniform(0, 2 * np.pi, n)
    h = rng.uniform(-length / 2, length / 2, n)
    radial = np.cos(t)[:, None] * u + np.sin(t)[:, None] * v
    return p + h[:, None] * a + radial * (r + rng.normal(0, sigma, (n, 1))), radial


def _recall_precision(found, truth):
    found = np.asarray(found, bool)
    return found[truth].mean(), truth[found].mean()


# --- (9.11.1) ---------------------------------------------------------------------------------------
def test_plane_angles_round_trip_and_range():
    rng = np.random.default_rng(0)
    for _ in range(200):
        n = _unit(rng.normal(size=3))
        d = rng.uniform(-5, 5)
        a, b, p = sg.plane_angles(sg.Plane(n, d))
        assert 0 <= a < math.pi and -math.pi / 2 <= b <= math.pi / 2
        back = sg.plane_from_angles(a, b, p)
        s = np.sign(back.normal @ n)
        np.testing.assert_allclose(back.normal * s, n, atol=1e-12)
        assert back.d * s == pytest.approx(d, abs=1e-12)
        # every point of the plane satisfies (9.11.1) with the recovered α, β, p
        X = _plane_points(rng, 5, n, d, sigma=0)
        lhs = X[:, 0] * math.cos(a) * math.cos(b) + X[:, 1] * math.sin(a) * math.cos(b) + X[:, 2] * math.sin(b)
        np.testing.assert_allclose(lhs, p, atol=1e-9)


# --- least squares against scipy ------------------------------------------------------------------
def test_fit_plane_is_orthogonal_regression():
    rng = np.random.default_rng(1)
    P = _plane_points(rng, 100, [0.2, -0.3, 1.0], 4.0, sigma=0.05)
    pl = sg.fit_plane(P)
    res = least_squares(lambda x: P @ _unit(x[:3]) - x[3], np.r_[0, 0, 1.0, 0])
    n_ref = _unit(res.x[:3]) * np.sign(res.x[2])
    np.testing.assert_allclose(pl.normal * np.sign(pl.normal[2]), n_ref, atol=1e-6)
    assert abs(pl.d) == pytest.approx(abs(res.x[3]), abs=1e-5)


def test_fit_sphere_matches_scipy_geometric_fit():
    rng = np.random.default_rng(2)
    P, _ = _sphere_points(rng, 80, np.array([3.0, -2.0, 10.0]), 1.5, sigma=0.02)
    s = sg.fit_sphere(P)
    ref = least_squares(lambda x: np.linalg.norm(P - x[:3], axis=1) - x[3], np.r_[P.mean(0), 1.0],
                        xtol=1e-14, ftol=1e-14).x
    np.testing.assert_allclose(s.center, ref[:3], atol=1e-7)
    assert s.radius == pytest.approx(ref[3], abs=1e-7)


def test_fit_cylinder_matches_scipy_geometric_fit():
    rng = np.random.default_rng(3)
    a_true = _unit([0.3, 0.2, 1.0])
    P, _ = _cylinder_points(rng, 150, np.array([5.0, 1.0, 2.0]), a_true, 0.8, sigma=0.01)
    c = sg.fit_cylinder(P)

    def resid(x):
        a = _unit([x[0], x[1], 1.0])
        w = P - np.array([x[2], x[3], 0.0])
        return np.linalg.norm(np.cross(w, a), axis=1) - x[4]
    ref = least_squares(resid, [0.25, 0.25, 5.0, 1.0, 1.0], xtol=1e-14, ftol=1e-14).x
    a_ref = _unit([ref[0], ref[1], 1.0])
    assert np.degrees(np.arccos(min(1.0, abs(c.axis @ a_ref)))) < 1e-4
    assert c.radius == pytest.approx(ref[4], abs=1e-6)
    assert sg.distances(sg.Cylinder(np.array([ref[2], ref[3], 0.0]), a_ref, ref[4]), c.point[None])[0] \
        == pytest.approx(ref[4], abs=1e-5)


def test_minimal_cylinder_from_two_points_with_normals():
    rng = np.random.default_rng(4)
    a = _unit([1.0, 0.5, 0.2])
    P, R = _cylinder_points(rng, 2, np.array([1.0, 2.0, 3.0]), a, 2.0, sigma=0.0)
    c = sg.fit_cylinder(P, R)
    assert abs(abs(c.axis @ a) - 1) < 1e-12
    assert c.radius == pytest.approx(2.0, abs=1e-9)
    np.testing.assert_allclose(sg.distances(c, P), 0, atol=1e-9)



# --- the sympy models behind fit_sphere / fit_cylinder (photolib.derivations.shapes) ------------
def _central_differences(fn, x, data, h=1e-6):
    cols = []
    for j in range(len(x)):
        e = np.zeros(len(x))
        e[j] = h
        cols.append((fn(*(x + e), *data)[0] - fn(*(x - e), *data)[0]) / (2 * h))
    return np.column_stack(cols)


def test_sphere_distance_jacobian_equals_finite_differences():
    from photolib.derivations import sphere_distance_model
    res, jac = sphere_distance_model().compile()
    rng = np.random.default_rng(11)
    P = rng.normal(0, 2.0, (20, 3))
    x = np.array([0.3, -0.2, 0.1, 1.7])
    data = tuple(P.T)
    np.testing.assert_allclose(res(*x, *data)[0], np.linalg.norm(P - x[:3], axis=1) - x[3], rtol=0, atol=1e-14)
    np.testing.assert_allclose(jac(*x, *data).T, _central_differences(res, x, data), rtol=0, atol=1e-8)


def test_cylinder_distance_jacobian_equals_finite_differences():
    from photolib.derivations import cylinder_distance_model
    res, jac = cylinder_distance_model().compile()
    rng = np.random.default_rng(12)
    a0 = _unit([0.2, -0.4, 1.0])
    u = _unit(np.cross(a0, [1.0, 0, 0]))
    v = np.cross(a0, u)
    c0 = np.array([0.5, -1.0, 0.3])
    P = rng.normal(0, 2.0, (25, 3))
    data = (*P.T, *a0, *u, *v, *c0)
    for x in (np.array([0.0, 0.0, 0.0, 0.0, 1.0]), np.array([0.15, -0.1, 0.3, -0.2, 0.9])):
        # the residual is the orthogonal distance of (X − c) × a, written independently
        a = _unit(a0 + x[0] * u + x[1] * v)
        c = c0 + x[2] * u + x[3] * v
        np.testing.assert_allclose(res(*x, *data)[0], np.linalg.norm(np.cross(P - c, a), axis=1) - x[4],
                                   rtol=0, atol=1e-13)
        np.testing.assert_allclose(jac(*x, *data).T, _central_differences(res, x, data), rtol=0, atol=1e-8)


# --- RANSAC with noise and outliers -------------------------------------------------------------
@pytest.mark.parametrize("shape", ["line", "plane", "sphere", "cylinder"])
def test_ransac_shapes_recall_precision_and_parameters(shape):
    """50 % uniform outliers in a 10 m box; σ = 5 mm; threshold 3σ: recall ≥ 0.98, precision ≥ 0.97."""
    rng = np.random.default_rng(10)
    n_in, sigma = 400, 0.005
    normals = None
    if shape == "line":
        p0, d0 = np.array([1.0, 2.0, 3.0]), _unit([1, 2, 0.5])
        t = rng.uniform(-4, 4, n_in)
        perp = rng.normal(0, sigma, (n_in, 3))
        P = p0 + t[:, None] * d0 + perp - (perp @ d0)[:, None] * d0
    elif shape == "plane":
        P = _plane_points(rng, n_in, [0.1, 0.2, 1.0], 3.0, sigma=sigma)
    elif shape == "sphere":
        P, _ = _sphere_points(rng, n_in, np.array([0.5, -0.5, 1.0]), 2.0, sigma=sigma)
    else:
        P, normals = _cylinder_points(rng, n_in, np.array([0.0, 0.0, 0.0]), [0.2, 0.1, 1.0], 1.0, sigma=sigma)
    out = rng.uniform(-5, 5, (n_in, 3))
    X = np.vstack([P, out])
    truth = np.r_[np.ones(n_in, bool), np.zeros(n_in, bool)]
    N = None
    if normals is not None:
        N = np.vstack([normals, _unit_rows(rng.normal(size=(n_in, 3)))])
    r = sg.ransac_shape(X, shape, 3 * sigma, normals=N, max_iterations=3000, rng=0)
    recall, precision = _recall_precision(r.inliers, truth)
    assert recall >= 0.98 and precision >= 0.97, (recall, precision)
    m = r.model
    if shape == "line":
        assert np.degrees(np.arccos(abs(m.direction @ d0))) < 0.05
        assert sg.distances(m, p0[None])[0] < 2e-3
    elif shape == "plane":
        assert np.degrees(np.arccos(abs(m.normal @ _unit([0.1, 0.2, 1.0])))) < 0.05
        assert abs(abs(m.d) - 3.0) < 2e-3
    elif shape == "sphere":
        assert np.linalg.norm(m.center - [0.5, -0.5, 1.0]) < 2e-3 and abs(m.radius - 2.0) < 2e-3
    else:
        assert np.degrees(np.arccos(abs(m.axis @ _unit([0.2, 0.1, 1.0])))) < 0.2
        assert abs(m.radius - 1.0) < 3e-3 and sg.distances(sg.Line(np.zeros(3), _unit([0.2, 0.1, 1])),
                                                           m.point[None])[0] < 5e-3


def _unit_rows(v):
    return v / np.linalg.norm(v, axis=1)[:, None]


def test_cylinder_ransac_with_estimated_normals():
    rng = np.random.default_rng(11)
    P, _ = _cylinder_points(rng, 600, np.zeros(3), [0, 1.0, 0.1], 0.5, sigma=0.002)
    X = np.vstack([P, rng.uniform(-2, 2, (200, 3))])
    r = sg.ransac_shape(X, "cylinder", 0.01, rng=1)
    recall, precision = _recall_precision(r.inliers, np.r_[np.ones(600, bool), np.zeros(200, bool)])
    assert recall >= 0.97 and precision >= 0.97
    assert abs(r.model.radius - 0.5) < 3e-3


def test_detect_shapes_finds_three_planes():
    rng = np.random.default_rng(12)
    planes = [([0, 0, 1.0], 0.0), ([1.0, 0, 0.2], 2.0), ([0, 1.0, -0.3], -3.0)]
    parts = [_plane_points(rng, 300, n, d, sigma=0.01) for n, d in planes]
    X = np.vstack(parts + [rng.uniform(-5, 5, (150, 3))])
    label = np.repeat([0, 1, 2, -1], [300, 300, 300, 150])
    segs = sg.detect_shapes(X, "plane", 0.03, min_inliers=100, rng=0)
    assert len(segs) == 3
    for s in segs:
        true_lab = np.bincount(label[s.indices][label[s.indices] >= 0]).argmax()
        recall, precision = _recall_precision(np.isin(np.arange(len(X)), s.indices), label == true_lab)
        assert recall >= 0.97 and precision >= 0.97
        n_true = _unit(planes[true_lab][0])
        assert np.degrees(np.arccos(min(1, abs(s.model.normal @ n_true)))) < 0.2


# --- Hough ------------------------------------------------------------------------------------------
def test_hough_planes_two_planes_with_outliers():
    """Two planes + 20 % outliers, σ = 1 cm, 2° / 5 cm cells: both found; after LS refinement the
    normals are within 0.1° and p within 1 cm of the truth; recall, precision ≥ 0.97."""
    rng = np.random.default_rng(20)
    A = _plane_points(rng, 500, [0.3, 0.1, 1.0], 12.0, sigma=0.01) + [100, 200, 0]
    B = _plane_points(rng, 400, [1.0, -0.5, 0.0], 2.0, sigma=0.01) + [100, 200, 0]
    out = rng.uniform(-5, 5, (225, 3)) + [100, 200, 10]
    X = np.vstack([A, B, out])
    segs = sg.hough_planes(X, angle_step=np.radians(2), p_step=0.05, threshold=0.03, min_votes=100)
    assert len(segs) == 2
    truth = {0: (_unit([0.3, 0.1, 1.0]), np.arange(500)), 1: (_unit([1.0, -0.5, 0]), np.arange(500, 900))}
    for s, (n_true, idx) in zip(segs, truth.values()):
        assert np.degrees(np.arccos(min(1, abs(s.model.normal @ n_true)))) < 0.1
        on = X[idx] @ s.model.normal - s.model.d
        assert abs(np.mean(on)) < 0.01
        recall, precision = _recall_precision(np.isin(np.arange(len(X)), s.indices), np.isin(np.arange(len(X)), idx))
        assert recall >= 0.97 and precision >= 0.97


def test_hough_centring_matters_for_far_away_clouds():
    # map coordinates (10⁶ m away): centring keeps the p range to the cloud's size
    rng = np.random.default_rng(21)
    X = _plane_points(rng, 300, [0, 0.2, 1.0], 0.0, sigma=0.005) + [5e5, 6e6, 150.0]
    segs = sg.hough_planes(X, p_step=0.05, threshold=0.02)
    assert len(segs) == 1 and len(segs[0].indices) >= 295
    np.testing.assert_allclose(sg.distances(segs[0].model, X).mean(), 0.004, atol=0.003)


# --- normals and region growing ---------------------------------------------------------------------
def test_normals_of_a_sphere_are_radial():
    # a Fibonacci sphere (near-uniform spacing, symmetric neighbourhoods): PCA of a symmetric cap
    # of a sphere has the radial direction as its least-spread axis, so the error is small
    i = np.arange(2000) + 0.5
    phi, th = np.arccos(1 - 2 * i / 2000), np.pi * (1 + 5 ** 0.5) * i
    d = np.column_stack([np.cos(th) * np.sin(phi), np.sin(th) * np.sin(phi), np.cos(phi)])
    nr = sg.estimate_normals(5.0 * d, k=10)
    assert np.degrees(np.arccos(np.clip(np.abs(np.sum(nr.normals * d, axis=1)), 0, 1))).max() < 3.0


def test_region_growing_separates_roof_facets_and_a_wall():
    rng = np.random.default_rng(31)
    xy = rng.uniform(0, 10, (1500, 2))
    z = np.where(xy[:, 0] < 5, 3 + 0.6 * xy[:, 0], 9 - 0.6 * xy[:, 0])        # gable roof, ridge at x = 5
    roof = np.column_stack([xy, z + rng.normal(0, 0.01, len(z))])
    wall = np.column_stack([rng.uniform(0, 10, 500), np.full(500, -0.3), rng.uniform(0, 3, 500)])
    X = np.vstack([roof, wall])
    truth = np.r_[np.where(xy[:, 0] < 5, 0, 1), np.full(500, 2)]
    lab = sg.region_growing(X, 0.05, angle_threshold=np.radians(15), k=12, min_size=50)
    assert lab.max() == 2
    for t in range(3):
        found = lab == np.bincount(lab[truth == t][lab[truth == t] >= 0]).argmax()
        recall, precision = _recall_precision(found, truth == t)
        assert recall >= 0.95 and precision >= 0.99, (t, recall, precision)


# --- ground classification ---------------------------------------------------------------------------
def test_classify_ground_synthetic_terrain_with_buildings_and_trees():
    """Rolling ground, 2 buildings, 30 trees, σ = 3 cm: type I ≤ 1 %, type II ≤ 2 %, DTM RMSE ≤ 0.15 m."""
    rng = np.random.default_rng(40)
    n = 40000
    xy = rng.uniform(0, 100, (n, 2))
    ground_z = lambda x, y: 50 + 3 * np.sin(x / 15) + 2 * np.cos(y / 20)  # noqa: E731
    z = ground_z(xy[:, 0], xy[:, 1]) + rng.normal(0, 0.03, n)
    obj = np.zeros(n, bool)
    for x0, y0, w, h in ((20, 20, 15, 10), (60, 55, 12, 20)):
        inb = (xy[:, 0] > x0) & (xy[:, 0] < x0 + w) & (xy[:, 1] > y0) & (xy[:, 1] < y0 + h)
        z[inb] += 8.0
        obj |= inb
    for cx, cy in rng.uniform(5, 95, (30, 2)):
        r = np.hypot(xy[:, 0] - cx, xy[:, 1] - cy)
        crown = (r < 3) & ~obj & (rng.random(n) < 0.7)             # 30 % of the points reach the ground
        z[crown] += rng.uniform(2, 10, crown.sum())
        obj |= crown
    res = sg.classify_ground(np.column_stack([xy, z]), 1.0, max_window=25.0, slope=0.3, dh0=0.3, dh_max=3.0,
                             band=0.3)
    t1 = np.mean(~res.ground[~obj])
    t2 = np.mean(res.ground[obj])
    assert t1 <= 0.01 and t2 <= 0.02, (t1, t2)
    rows, cols = np.mgrid[0:res.dtm.shape[0], 0:res.dtm.shape[1]]
    X, Y = res.grid.x0 + (cols + 0.5), res.grid.y0 - (rows + 0.5)
    assert np.sqrt(np.mean((res.dtm - ground_z(X, Y)) ** 2)) <= 0.15


def test_lowest_point_raster_convention():
    P = np.array([[10.0, 20.0, 5.0], [10.2, 19.9, 4.0], [12.5, 18.5, 7.0], [11.5, 20.0, 1.0]])
    z, grid, empty = sg.lowest_point_raster(P, 1.0)
    assert (grid.x0, grid.y0, grid.shape) == (10.0, 20.0, (2, 3))
    assert z[0, 0] == 4.0 and z[0, 1] == 1.0 and z[1, 2] == 7.0        # row 0 = northmost
    assert empty.sum() == 3


def test_degenerate_samples_are_skipped():
    # 3 planar points for a sphere: degenerate → named error, not a wrong sphere
    with pytest.raises(DegenerateGeometryError):
        sg.fit_sphere([[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0]])
