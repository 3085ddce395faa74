"""Tests of photolib.georef — Chapter 8, §8.14–8.17 (direct georeferencing, scanner aerial
triangulation with fixed centres, scanner orthophotos, quasi-frame image, object-space SGM).

Expected values come from independent constructions (homogeneous 4×4 transforms, the frame
camera's collinearity in photolib.single_image, exhaustive enumeration of labellings, analytic
terrain and texture) or from the synthetic truth of the simulations.
"""

from __future__ import annotations

import itertools

import numpy as np
import pytest
import sympy as sp
from scipy.spatial.transform import Rotation

from photolib import georef, radar, sgm
from photolib.errors import PointBehindCameraError
from photolib.rectify import RasterGrid, orthorectify

RNG = np.random.default_rng(20261125)


def _random_rotation(rng, scale=0.1):
    return Rotation.from_rotvec(rng.normal(0, scale, 3)).as_matrix()


def _homogeneous(A, t):
    T = np.eye(4)
    T[:3, :3], T[:3, 3] = A, t
    return T


# --------------------------------------------------------------------------- §8.14
@pytest.fixture
def rig():
    rng = np.random.default_rng(3)
    return dict(gnss=np.array([1000.0, 2000.0, 1500.0]), A_imu=_random_rotation(rng, 0.05),
                lever_gnss=np.array([0.4, -0.1, 1.6]), lever_sensor=np.array([0.1, 0.2, -0.3]),
                boresight=_random_rotation(rng, 3e-3))


def test_direct_georeference_matches_homogeneous_chain(rig):
    # object ← IMU ← sensor as 4×4 transforms; the IMU origin from the antenna and its lever arm
    T_obj_imu = _homogeneous(rig["A_imu"], rig["gnss"] - rig["A_imu"] @ rig["lever_gnss"])
    T_imu_sen = _homogeneous(rig["boresight"], rig["lever_sensor"])
    R = RNG.normal(0, 50, (5, 3))
    expected = (T_obj_imu @ T_imu_sen @ np.c_[R, np.ones(5)].T).T[:, :3]
    got = georef.direct_georeference(R, **rig)
    np.testing.assert_allclose(got, expected, atol=1e-9)
    # the antenna itself: R_GNSS = R_IMU + A_imu·lever_gnss
    S, A = georef.sensor_pose(**rig)
    np.testing.assert_allclose(T_obj_imu @ np.r_[rig["lever_gnss"], 1], np.r_[rig["gnss"], 1], atol=1e-9)
    np.testing.assert_allclose(A[0], rig["A_imu"] @ rig["boresight"], atol=1e-15)


def test_round_trip_frame_scanner_lidar(rig):
    r = georef.frame_vector([[3.0, -4.0], [10.0, 2.0]], 100.0, 0.01, -0.02)
    P = georef.direct_georeference(r, **rig, Z=[120.0, 80.0])
    np.testing.assert_allclose(P[:, 2], [120.0, 80.0], atol=1e-9)
    back = georef.ground_to_sensor(P, **rig)
    np.testing.assert_allclose(back / -back[:, 2:] * 100.0, r / -r[:, 2:] * 100.0, atol=1e-9)
    u = georef.scanner_vector([-5.0, 0.0, 7.0], 100.0, x_line=12.0)
    np.testing.assert_allclose(np.linalg.norm(u, axis=1), 1.0)
    P = georef.direct_georeference(u, **rig, scale=[1500.0, 1600.0, 1700.0])
    np.testing.assert_allclose(georef.ground_to_sensor(P, **rig), u * [[1500.0], [1600.0], [1700.0]], atol=1e-8)
    D, phi = np.array([900.0, 1200.0]), np.array([-0.3, 0.4])
    P = georef.direct_georeference(radar.range_vector(D, phi), **rig)
    R = georef.ground_to_sensor(P, **rig)
    np.testing.assert_allclose(np.linalg.norm(R, axis=1), D)
    np.testing.assert_allclose(np.arctan2(R[:, 1], -R[:, 2]), phi)
    np.testing.assert_allclose(R[:, 0], 0.0, atol=1e-9)


def test_frame_camera_agrees_with_single_image(rig):
    """The frame ray (8.14.1) with a height equals photolib.single_image.image_to_ground (§1.4)."""
    from photolib.camera import ExteriorOrientation, InteriorOrientation
    from photolib.rotation import rotation_angles
    from photolib.single_image import image_to_ground
    S, A = georef.sensor_pose(**rig)
    w, a, k = rotation_angles(A[0], order="wak")
    eo = ExteriorOrientation(*S[0], w, a, k, order="wak")
    xy = np.array([[3.0, -4.0], [-20.0, 15.0]])
    expected = image_to_ground(xy, 100.0, eo, InteriorOrientation(100.0))
    got = georef.direct_georeference(georef.frame_vector(xy, 100.0), **rig, Z=100.0)
    np.testing.assert_allclose(got[:, :2], np.asarray(expected)[:, :2], atol=1e-7)


def test_per_epoch_attitudes_and_behind(rig):
    A = np.stack([rig["A_imu"], np.eye(3)])
    P = georef.direct_georeference([0, 0, -1.0], [[0, 0, 1000.0], [5, 5, 1000.0]], A, [0, 0, 0], [0, 0, 0],
                                   np.eye(3), Z=0.0)
    assert P.shape == (2, 3) and np.allclose(P[1], [5, 5, 0])
    with pytest.raises(PointBehindCameraError):
        georef.direct_georeference([0, 0, 1.0], [0, 0, 1000.0], np.eye(3), [0, 0, 0], [0, 0, 0], np.eye(3), Z=0.0)


# --------------------------------------------------------------------------- §8.15
def test_interpolation_reproduces_truth_for_constant_offset():
    t = np.linspace(0, 10, 101)
    truth = np.column_stack([50 * t + 0.3 * np.sin(7 * t), np.cos(t), 1000 + t ** 2 / 10,
                             1e-3 * np.sin(9 * t), 2e-3 * t, 0.01 + 1e-4 * np.cos(11 * t)])
    offset = np.array([0.5, -0.2, 1.0, 1e-3, -2e-3, 5e-4])
    measured = truth - offset
    fixed = np.arange(0, 101, 25)
    E = georef.interpolate_fixed_centres(t, t[fixed], truth[fixed], measured, measured[fixed])
    np.testing.assert_allclose(E, truth, atol=1e-9)
    lin = georef.interpolate_fixed_centres(t, t[fixed], truth[fixed])      # δ = 0: linear
    np.testing.assert_allclose(lin[fixed], truth[fixed], atol=1e-12)
    assert np.abs(lin - truth).max() > 0.1


def test_chain_rule_jacobian_equals_sympy_jacobian():
    from photolib.derivations.georef import (FIXED_CENTRE_DATA, FIXED_CENTRE_PARAMETERS,
                                             fixed_centre_collinearity, fixed_centre_functions)
    p = np.array([10.0, 5, 1000, 0.01, -0.02, 0.03, 60, -3, 1002, 0.015, -0.01, 0.02, 40, 100, 30])
    d = np.array([0.3, 0.1, -0.2, 0.4, 1e-4, -2e-4, 3e-4, 62.5, 20.0, 1.5])
    # the data as exact rationals first, then the derivative of the whole model, then the point
    expr = fixed_centre_collinearity().subs({s: sp.Rational(str(v)) for s, v in zip(FIXED_CENTRE_DATA, d)})
    J = expr.jacobian(sp.Matrix(FIXED_CENTRE_PARAMETERS))
    at = {s: sp.Rational(str(v)) for s, v in zip(FIXED_CENTRE_PARAMETERS, p)}
    expected_J = np.array(J.evalf(subs=at), dtype=float)
    expected_r = np.array(expr.evalf(subs=at), dtype=float).ravel()
    res, jac = fixed_centre_functions()
    np.testing.assert_allclose(jac(p[None], d[None])[0], expected_J, rtol=1e-9, atol=1e-12)
    np.testing.assert_allclose(res(p[None], d[None])[0], expected_r, rtol=1e-9, atol=1e-12)


def test_line_scanner_round_trip():
    b = georef.three_line_block(n_points=4, n_control=2)
    for s in b.scanners():
        r, c = s.project(*b.points.T)
        X, Y = s.ground(r, c, b.points[:, 2])
        np.testing.assert_allclose(np.c_[X, Y], b.points[:, :2], atol=1e-6)


def _triangulate(b, P0, **kw):
    return georef.fixed_centre_triangulation(b.at_rows(b.t), b.xy, b.point, b.t[b.fixed], P0, f=b.f,
                                             control=b.control, measured=b.at_rows(b.eo_measured),
                                             measured_fixed=b.eo_measured[b.fixed], **kw)


def test_triangulation_recovers_offsets_noise_free():
    b = georef.three_line_block(seed=2)
    rng = np.random.default_rng(1)
    P0 = b.points + np.where(b.control[:, None], 0.0, rng.normal(0, 3.0, b.points.shape))
    res = _triangulate(b, P0)
    np.testing.assert_allclose(res.offset, b.offset, atol=1e-6)
    np.testing.assert_allclose(res.points, b.points, atol=1e-4)
    np.testing.assert_allclose(res.eo_fixed, b.eo_true[b.fixed], atol=1e-5)
    # the refined EO of every line (8.15.2) equals the truth, wiggle included
    E = georef.interpolate_fixed_centres(b.t, b.t[b.fixed], res.eo_fixed, b.eo_measured, b.eo_measured[b.fixed])
    np.testing.assert_allclose(E, b.eo_true, atol=1e-5)


def test_triangulation_with_noise_within_its_precision():
    b = georef.three_line_block(seed=1, sigma_image=0.0025, sigma_gnss=0.02, sigma_imu=2e-5)
    rng = np.random.default_rng(5)
    P0 = b.points + np.where(b.control[:, None], 0.0, rng.normal(0, 3.0, b.points.shape))
    res = _triangulate(b, P0, sigma_image=0.0025, sigma_position=0.02, sigma_attitude=2e-5)
    std = res.adjustment.std[-6:]
    assert np.all(np.abs(res.offset - b.offset) < 4 * std)
    assert 0.6 < res.adjustment.mu < 1.5          # the a-priori σ were right


def test_ignoring_the_delta_terms_leaves_the_wiggle_in_the_residuals():
    """(8.15.2) without δ (linear interpolation of the fixed centres) cannot follow the
    high-frequency motion: μ grows far above 1 with the same σ."""
    b = georef.three_line_block(seed=2, sigma_image=0.0025)
    k, c = georef._fixed_weights(b.at_rows(b.t), b.t[b.fixed])
    Mf = b.eo_measured[b.fixed]
    linear = c[:, None] * Mf[k] + (1 - c[:, None]) * Mf[k + 1]
    res = georef.fixed_centre_triangulation(b.at_rows(b.t), b.xy, b.point, b.t[b.fixed], b.points, f=b.f,
                                            control=b.control, measured=linear, measured_fixed=Mf,
                                            sigma_image=0.0025, max_iter=50)
    good = _triangulate(b, b.points, sigma_image=0.0025)
    assert good.adjustment.mu < 1.5 and res.adjustment.mu > 10 * good.adjustment.mu


# --------------------------------------------------------------------------- §8.16
def _terrain(X, Y):
    return 20.0 * np.sin(X / 40.0) * np.cos(Y / 55.0) + 100.0


def _texture(X, Y):
    return 100 + 60 * np.sin(X / 6.0) * np.cos(Y / 9.0) + 40 * np.cos((X - Y) / 13.0)


def _render(scanner, shape):
    """Scanner image of the analytic terrain: every pixel's ray intersected by fixed-point iteration."""
    rows, cols = np.mgrid[0:shape[0], 0:shape[1]].astype(float)
    Z = np.full(rows.shape, 100.0)
    for _ in range(60):
        X, Y = scanner.ground(rows, cols, Z)
        Z = _terrain(X, Y)
    return _texture(X, Y)


def _nadir_scanner(n_lines=120, n_cols=121, step=0.8, x_line=0.0, y_shift=0.0, wiggle=True):
    i = np.arange(n_lines, dtype=float)
    eo = np.column_stack([step * i, y_shift + 0.5 * np.sin(i / 9.0), 1100.0 + 0 * i,
                          (2e-3 * np.sin(i / 5.0)) if wiggle else 0 * i, 1e-3 + 0 * i, 0.01 + 0 * i])
    return georef.TabulatedLineScanner(eo, 62.5, 0.05, n_cols, x_line)


@pytest.fixture(scope="module")
def ortho_case():
    s = _nadir_scanner()
    image = _render(s, s.shape)
    dem_grid = RasterGrid(-60.0, 100.0, 1.0, (220, 220))
    X, Y = dem_grid.centres()
    dem = _terrain(X, Y)
    grid = RasterGrid(10.0, 30.0, 0.5, (120, 140))
    return s, image, dem, dem_grid, grid


def test_direct_ortho_has_holes_inverse_has_none(ortho_case):
    s, image, dem, dem_grid, grid = ortho_case
    direct = georef.direct_orthorectify(image, s.ground, dem, dem_grid, grid)
    inverse = orthorectify(image, s.project, dem, dem_grid, grid)
    assert np.isfinite(inverse).all()                              # the grid lies inside the image
    assert direct.holes.mean() > 0.2                                # 0.5 m ortho pixels from ~0.8 m scans
    Xc, Yc = grid.centres()
    truth = _texture(Xc, Yc)
    assert np.sqrt(np.mean((inverse - truth) ** 2)) < 2.0          # texture std ≈ 45
    filled = ~direct.holes
    # direct values are the brightness of scanner pixels within half an ortho pixel
    assert np.sqrt(np.mean((direct.image[filled] - truth[filled]) ** 2)) < 12.0
    assert direct.iterations < 15


def test_line_scanner_project_is_inverse_of_ground(ortho_case):
    s = ortho_case[0]
    rows = RNG.uniform(0, s.shape[0] - 1, 50)
    cols = RNG.uniform(0, s.shape[1] - 1, 50)
    Z = RNG.uniform(80, 120, 50)
    X, Y = s.ground(rows, cols, Z)
    r, c = s.project(X, Y, Z)
    np.testing.assert_allclose(r, rows, atol=1e-6)
    np.testing.assert_allclose(c, cols, atol=1e-6)


# --------------------------------------------------------------------------- §8.17
def test_quasi_frame_reprojection_equals_scanner_projection(ortho_case):
    _, _, dem, dem_grid, _ = ortho_case
    # two overlapping scans of a staggered focal plane: different along-track offsets and across shifts
    s1 = _nadir_scanner(x_line=1.0, y_shift=-30.0, n_cols=101)
    s2 = _nadir_scanner(x_line=-1.0, y_shift=30.0, n_cols=101)
    scans = [_render(s, s.shape) for s in (s1, s2)]
    centre = np.r_[s1.eo[:, :3].mean(axis=0) * 0.5 + s2.eo[:, :3].mean(axis=0) * 0.5]
    q = georef.quasi_frame_image(scans, [s1.project, s2.project], dem, dem_grid, centre, 62.5, 0.05, (90, 140))
    inside = np.isfinite(q.image)
    assert inside.mean() > 0.8 and (q.count == 2).any()            # the scans overlap in the middle
    # ground points of random DEM positions: the quasi-image at their collinearity projection shows
    # the brightness the scans show at their scanner projection
    X = RNG.uniform(30, 70, 200)
    Y = RNG.uniform(-40, 40, 200)
    Z = _terrain(X, Y)
    from photolib.rectify import resample
    rq, cq = q.project(X, Y, Z)
    vq = resample(q.image, rq, cq, "bilinear")
    r1, c1 = s1.project(X, Y, Z)
    v1 = resample(scans[0], r1, c1, "bilinear")
    ok = np.isfinite(vq) & np.isfinite(v1)
    assert ok.sum() > 50
    assert np.sqrt(np.mean((vq[ok] - v1[ok]) ** 2)) < 4.0
    np.testing.assert_allclose(vq[ok], _texture(X, Y)[ok], atol=15.0)


def _chain_min(C, P1, P2):
    """Brute force: the least energy (8.17.2) of a chain over all labellings."""
    n, D = C.shape
    best = np.inf
    for lab in itertools.product(range(D), repeat=n):
        e = sum(C[i, l] for i, l in enumerate(lab))
        e += sum(P1 if abs(a - b) == 1 else (P2 if abs(a - b) > 1 else 0) for a, b in zip(lab[:-1], lab[1:]))
        best = min(best, e)
    return best


def test_one_path_equals_brute_force():
    rng = np.random.default_rng(11)
    for _ in range(3):
        C = rng.uniform(0, 5, (5, 5)).astype(np.float32)
        P1, P2 = 1.5, 4.0
        L = sgm.path_cost(C[None], (1, 0), P1, P2)[0].astype(float)
        subtracted = sum(L[i].min() for i in range(len(L) - 1))      # the − min_k L_r terms (8.17.3)
        assert L[-1].min() + subtracted == pytest.approx(_chain_min(C.astype(float), P1, P2), abs=1e-4)


def test_object_space_sgm_recovers_dsm():
    """Forward and backward lines of a three-line camera (±20 mm, f = 62.5 mm, H = 300 m: base/height
    0.64), a random texture on a gentle terrain; 0.5 m voxels in Z."""
    from scipy.ndimage import gaussian_filter, map_coordinates

    def terrain(X, Y):
        return 100.0 + 4.0 * np.sin(X / 15.0) * np.cos(Y / 20.0)

    def scanner(x_line):
        i = np.arange(520, dtype=float)
        eo = np.column_stack([-110 + 0.48 * i, 0 * i, 400.0 + 0 * i, 0 * i, 0 * i, 0 * i])
        return georef.TabulatedLineScanner(eo, 62.5, 0.1, 101, x_line)

    rng = np.random.default_rng(4)
    tex = gaussian_filter(rng.uniform(0, 255, (300, 600)), 1.0)

    def render(s):
        rows, cols = np.mgrid[0:s.shape[0], 0:s.shape[1]].astype(float)
        Z = np.full(rows.shape, 100.0)
        for _ in range(30):
            X, Y = s.ground(rows, cols, Z)
            Z = terrain(X, Y)
        return map_coordinates(tex, [(Y + 75) * 2.0, (X + 150) * 2.0], order=1, mode="nearest")

    fwd, bwd = scanner(20.0), scanner(-20.0)
    imgs = [render(fwd), render(bwd)]
    X = np.arange(0.0, 30.0, 1.0)
    Y = np.arange(-15.0, 15.0, 1.0)
    Z = np.arange(94.0, 106.01, 0.5)
    res = georef.object_space_sgm(imgs, [fwd.project, bwd.project], X, Y, Z)
    GX, GY = np.meshgrid(X, Y)
    rms = np.sqrt(np.mean((res.Z - terrain(GX, GY)) ** 2))
    rms_wta = np.sqrt(np.mean((res.Z_wta - terrain(GX, GY)) ** 2))
    assert rms < 0.5                                                 # < one ΔZ
    assert rms <= rms_wta


def test_voxel_cost_is_min_over_pairs():
    a, b = np.full((10, 10), 10.0), np.full((10, 10), 13.0)
    c = np.full((10, 10), 30.0)
    p = lambda X, Y, Z: (5 - np.asarray(Y), np.asarray(X) + 5)   # noqa: E731
    C = georef.scan_voxel_cost([a, b, c], [p, p, p], np.arange(-2, 3.0), np.arange(-2, 3.0), [0.0, 1.0])
    np.testing.assert_allclose(C, 3.0)                              # min(|10−13|, |10−30|, |13−30|)


def test_tabulated_scanner_agrees_with_photolib_pushbroom():
    """An independent sensor model: photolib.pushbroom.Pushbroom with a linear EO in time (metres),
    sampled line by line into the table (exact for a linear EO)."""
    pushbroom = pytest.importorskip("photolib.pushbroom")
    eo = pushbroom.EOPolynomial([0.0, 2.0, 1100.0, 0.01, -0.02, 0.03], [40.0, 1.0, 0.5, 1e-3, 2e-3, -1e-3])
    pb = pushbroom.Pushbroom(0.0625, 5e-5, 81, 0.02, eo, x_offsets=0.004, n_rows=100)
    table = eo.elements(np.arange(100) * 0.02)
    tab = georef.TabulatedLineScanner(table, 62.5, 0.05, 81, x_line=4.0)
    assert isinstance(tab.sensor, pushbroom.Pushbroom) and isinstance(tab.sensor.eo, pushbroom.EOTable)
    rows, cols = RNG.uniform(0, 99, 20), RNG.uniform(0, 80, 20)
    X1, Y1 = pb.ground(rows, cols, 90.0)
    X2, Y2 = tab.ground(rows, cols, 90.0)
    np.testing.assert_allclose(np.c_[X1, Y1], np.c_[X2, Y2], atol=1e-6)
    r2, c2 = tab.project(X1, Y1, 90.0)
    np.testing.assert_allclose(np.c_[r2, c2], np.c_[rows, cols], atol=1e-6)
    # the direct method runs on the other module's sensor as well
    grid = RasterGrid(90.0, 40.0, 1.0, (40, 40))
    dem_grid = RasterGrid(-100.0, 150.0, 2.0, (150, 200))
    direct = georef.direct_orthorectify(np.ones((100, 81)), pb.ground, np.full((150, 200), 90.0), dem_grid, grid)
    assert direct.dropped == 0 and (~direct.holes).mean() > 0.9
    assert np.all(direct.image[~direct.holes] == 1.0)
