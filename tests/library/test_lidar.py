"""photolib.lidar: Chapter 9 geometry (ALS, TLS, laser-line scanner, built-in camera, mobile mapping)."""

import numpy as np
import pytest
import sympy as sp

from photolib import lidar
from photolib.camera import ExteriorOrientation, InteriorOrientation
from photolib.derivations import lidar as dlidar
from photolib.errors import DegenerateGeometryError, PointBehindCameraError
from photolib.pointcloud import PointCloud
from photolib.rotation import rotation_matrix
from photolib.single_image import project

RNG = np.random.default_rng(20221)


def test_als_vector_and_flat_terrain():
    phi = np.radians(np.linspace(-30, 30, 13))
    H = 1000.0
    v = lidar.als_scanner_vector(H / np.cos(phi), phi)
    np.testing.assert_allclose(np.linalg.norm(v, axis=1), H / np.cos(phi))
    np.testing.assert_allclose(v[6], [0, 0, -H])
    pts = lidar.als_georeference(H / np.cos(phi), phi, [10.0, 20.0, H], np.eye(3))
    np.testing.assert_allclose(pts[:, 2], 0, atol=1e-9)          # flat ground Z = 0
    np.testing.assert_allclose(pts[:, 1], 20 + H * np.tan(phi))  # across-track offsets


def test_als_georeference_rotated_per_pulse():
    n = 20
    angles = RNG.normal(0, 0.05, (n, 3))
    A = np.array([rotation_matrix(*a, order="wak") for a in angles])
    S = RNG.uniform(0, 100, (n, 3)) + [0, 0, 800]
    D, phi = RNG.uniform(700, 900, n), RNG.uniform(-0.5, 0.5, n)
    expected = S + np.einsum("nij,nj->ni", A, np.column_stack([0 * D, D * np.sin(phi), -D * np.cos(phi)]))
    np.testing.assert_allclose(lidar.als_georeference(D, phi, S, A), expected, atol=1e-9)


@pytest.mark.parametrize("H, fov_deg, printed", [(4700, 60, 5400), (5600, 60, 6500), (200, 46, 170)])
def test_swath_table_9_1(H, fov_deg, printed):
    # Table 9.1 (ALS): SW printed for the maximal range; rounded to the hundred / ten
    assert lidar.swath_width(H, np.radians(fov_deg)) == pytest.approx(printed, rel=0.011)


def test_footprint_table_9_1():
    assert lidar.footprint_diameter(1000.0, 0.25e-3) == pytest.approx(0.25, rel=1e-6)   # 25 cm at 1000 m


def test_ranging_round_trips():
    D = RNG.uniform(1, 5000, 50)
    v = lidar.SPEED_OF_LIGHT / 1.0003
    np.testing.assert_allclose(lidar.pulse_range(2 * D / v, v), D, rtol=1e-14)
    lam = 20.0                                    # modulation wavelength: unit length 10 m
    units = 2 * D / lam
    K = np.floor(units)
    np.testing.assert_allclose(lidar.phase_range(K, 2 * np.pi * (units - K), lam), D, rtol=1e-12)
    np.testing.assert_allclose(lidar.phase_range(K, 2 * np.pi * (units - K), lam / 2, round_trip=False), D,
                               rtol=1e-12)


def test_return_masks_on_a_cloud():
    cloud = PointCloud(np.arange(15.0).reshape(5, 3), return_number=[1, 1, 2, 3, 1],
                       number_of_returns=[1, 3, 3, 3, 2])
    m = lidar.return_masks(cloud.return_number, cloud.number_of_returns)
    assert m["first"].tolist() == [True, True, False, False, True]
    assert m["last"].tolist() == [True, False, False, True, False]
    assert m["intermediate"].tolist() == [False, False, True, False, False]


def test_polar_round_trip():
    P = RNG.normal(0, 30, (200, 3))
    D, phi, nu = lidar.xyz_to_polar(P)
    np.testing.assert_allclose(lidar.polar_to_xyz(D, phi, nu), P, atol=1e-10)
    assert np.all((phi >= 0) & (phi < 2 * np.pi))


def test_triangulation_against_sympy_and_monte_carlo():
    m = dlidar.triangulation_depth_model()
    p_, f_, B_, a_ = m["symbols"]
    vals = {p_: 1.3, f_: 16.0, B_: 150.0, a_: 0.2}
    Z = lidar.triangulation_depth(1.3, 16.0, 150.0, 0.2)
    assert Z == pytest.approx(float(m["Z"].subs(vals)), rel=1e-12)
    assert lidar.triangulation_sigma(Z, 16.0, 150.0, 0.002) == pytest.approx(abs(float(m["dZ_dp"].subs(vals))) * 0.002,
                                                                              rel=1e-12)
    rng = np.random.default_rng(3)
    sim = lidar.triangulation_depth(1.3 + rng.normal(0, 0.0005, 20000), 16.0, 150.0, 0.2)
    assert np.std(sim) == pytest.approx(lidar.triangulation_sigma(Z, 16.0, 150.0, 0.0005), rel=0.03)


def test_ray_plane_sign():
    m = dlidar.ray_plane_model()
    assert sp.simplify(m["equation"].subs(dlidar.sp.Symbol("N", real=True), m["N"])) == 0
    assert sp.simplify(m["N"] + m["printed"]) == 0          # the printed (9.4.9) has the wrong sign
    io, eo = InteriorOrientation(50.0), ExteriorOrientation(5.0, -3.0, 20.0, 0.1, -0.05, 0.3, order="kaw")
    truth = np.column_stack([RNG.uniform(-5, 5, (10, 2)), np.zeros(10)])
    truth[:, 2] = 0.1 * truth[:, 0] - 0.2 * truth[:, 1] + 1.0
    plane = [0.1, -0.2, -1.0, 1.0]
    xy = project(truth, eo, io)
    np.testing.assert_allclose(lidar.intersect_ray_plane(xy, eo, io, plane), truth, atol=1e-9)
    plane_behind = [0, 0, 1.0, -30.0]                     # Z = 30 is above the camera (looking down)
    with pytest.raises(PointBehindCameraError):
        lidar.intersect_ray_plane(xy, eo, io, plane_behind)


def test_fit_plane_matches_svd_and_sigma():
    rng = np.random.default_rng(7)
    n_true = np.array([0.2, -0.3, 0.9]) / np.linalg.norm([0.2, -0.3, 0.9])
    uv = rng.uniform(-2, 2, (300, 2))
    basis = np.linalg.svd(n_true[None])[2][1:]
    P = uv @ basis + 5 * n_true + rng.normal(0, 0.01, (300, 1)) * n_true
    fit = lidar.fit_plane(P)
    c = P.mean(0)
    n_svd = np.linalg.svd(P - c)[2][-1]
    assert abs(fit.normal @ n_svd) == pytest.approx(1, abs=1e-12)
    assert fit.rms == pytest.approx(0.01, rel=0.15)
    np.testing.assert_allclose(fit.distance(P).std(), fit.rms, rtol=1e-3)
    assert abs(fit.plane[3] + 5 * np.sign(fit.normal @ n_true)) < 0.005


def test_fit_plane_collinear():
    with pytest.raises(DegenerateGeometryError, match="collinear"):
        lidar.fit_plane([[0, 0, 0], [1, 1, 1], [2, 2, 2.0], [3, 3, 3]])


@pytest.mark.parametrize("seed", [0, 1])
def test_laser_line_scanner_end_to_end(seed):
    s = lidar.simulate_laser_line_scanner(seed=seed, sigma_xy=0.001)
    r = lidar.laser_line_scan(s.marks_xyz, s.marks_xy, s.marks_plate, s.trace_xy, s.trace_label, s.io,
                              image=s.image, pixel_size=s.pixel_size)
    np.testing.assert_allclose(r.eo.center, s.eo.center, atol=0.005)
    assert abs(r.laser_plane.normal @ s.laser_plane[:3]) > 1 - 1e-5
    truth = s.trace_xyz[s.trace_label == 0]
    assert np.abs(r.points - truth).max() < 0.003            # 1 µm image noise → mm on the profile
    # the cylinder's radius from the profile: algebraic circle fit in XY (independent of the library)
    X, Y = r.points[:, 0], r.points[:, 1]
    sol = np.linalg.lstsq(np.column_stack([X, Y, np.ones_like(X)]), X ** 2 + Y ** 2, rcond=None)[0]
    radius = np.sqrt(sol[2] + (sol[0] / 2) ** 2 + (sol[1] / 2) ** 2)
    assert radius == pytest.approx(s.object_radius, abs=0.003)
    # colours (9.4.10): the image's brightness of the true surface at those points
    from photolib.lidar import _scene_brightness
    np.testing.assert_allclose(r.colours, _scene_brightness(truth), atol=0.02)


def test_laser_line_noiseless_exact():
    s = lidar.simulate_laser_line_scanner(seed=3, sigma_xy=0.0)
    r = lidar.laser_line_scan(s.marks_xyz, s.marks_xy, s.marks_plate, s.trace_xy, s.trace_label, s.io)
    np.testing.assert_allclose(r.points, s.trace_xyz[s.trace_label == 0], atol=1e-7)


def test_scanner_camera_pose_direction_and_projection():
    for phi, nu in RNG.uniform([-3, -1], [3, 1], (10, 2)):
        S, A = lidar.scanner_camera_pose(phi, nu, [0.01, -0.02, 0.25], 0.08)
        d = np.array([np.cos(nu) * np.sin(phi), np.cos(nu) * np.cos(phi), np.sin(nu)])
        np.testing.assert_allclose(-A[:, 2], d, atol=1e-12)
        np.testing.assert_allclose(S, [0.01, -0.02, 0.25] + 0.08 * d, atol=1e-12)
        assert abs(A[2, 0]) < 1e-12                      # the image x axis stays horizontal
        P = S + 10 * d + RNG.normal(0, 0.5, (5, 3))
        eo = ExteriorOrientation(*S, np.pi / 2 + nu, 0.0, -phi, order="kaw")
        np.testing.assert_allclose(lidar.scanner_camera_project(P, S, A, 35.0),
                                   project(P, eo, InteriorOrientation(35.0)), atol=1e-9)


def test_printed_9_7_7_not_unit():
    m = dlidar.scanner_camera_rotation()
    phi, nu = m["symbols"]
    assert sp.simplify(m["printed"].dot(m["printed"]) - 1) != 0
    assert sp.simplify(m["direction"].dot(m["direction"]) - 1) == 0


def test_mobile_georeference_equals_9_8_1():
    A_imu = rotation_matrix(0.02, -0.01, 1.2, order="wak")
    bore = rotation_matrix(0.003, -0.002, 0.001, order="wak")
    r_gnss_imu, r_imu_s = np.array([0.2, -0.1, 1.4]), np.array([0.9, 0.3, -0.2])
    G, R = np.array([1000.0, 2000.0, 150.0]), RNG.normal(0, 10, (6, 3))
    expected = (G - A_imu @ r_gnss_imu) + A_imu @ r_imu_s + (A_imu @ bore @ R.T).T       # (9.8.1)
    np.testing.assert_allclose(lidar.mobile_georeference(R, G, A_imu, r_imu_s - r_gnss_imu, bore), expected,
                               atol=1e-9)


def _mobile_simulation(rng, sigma=0.003, n_poses=4, per_pose=6):
    lever, angles = np.array([0.35, -0.12, 1.65]), np.radians([0.4, -0.25, 0.9])
    bore = rotation_matrix(*angles, order="wak")
    targets = rng.uniform([-15, -15, 0], [15, 15, 6], (per_pose, 3))
    R, G, A, T = [], [], [], []
    for k in range(n_poses):
        A_imu = rotation_matrix(*rng.normal(0, 0.02, 2), 2 * np.pi * k / n_poses, order="wak")
        gnss = rng.uniform(-3, 3, 3) + [0, 0, 2.5]
        local = (A_imu.T @ (targets - gnss).T).T - lever          # = bore @ R
        R.append((bore.T @ local.T).T + rng.normal(0, sigma, (per_pose, 3)))
        G.append(np.tile(gnss, (per_pose, 1)))
        A.append(np.tile(A_imu, (per_pose, 1, 1)))
        T.append(targets)
    return np.vstack(R), np.vstack(G), np.concatenate(A), np.vstack(T), lever, angles


def test_mobile_calibration_recovers_lever_and_boresight():
    rng = np.random.default_rng(98)
    R, G, A, T, lever, angles = _mobile_simulation(rng)
    cal = lidar.calibrate_mobile_system(R, G, A, T, sigma_target=0.003)
    truth = np.concatenate([lever, angles])
    est = np.concatenate([cal.lever, cal.angles])
    assert np.all(np.abs(est - truth) < 3 * cal.std + 1e-12), (est - truth) / cal.std
    assert cal.adjustment.mu == pytest.approx(1.0, abs=0.35)
    np.testing.assert_allclose(cal.boresight, rotation_matrix(*cal.angles, order="wak"))


def test_mobile_calibration_collinear_targets():
    R = np.array([[1.0, 0, 0], [2, 0, 0], [3, 0, 0], [4, 0, 0]])
    with pytest.raises(DegenerateGeometryError, match="collinear"):
        lidar.calibrate_mobile_system(R, np.zeros((4, 3)), np.eye(3), R + 1.0)


def test_station_design_inverse():
    D = lidar.tls_max_range(0.005, np.radians(0.005))
    assert D * np.tan(np.radians(0.005)) == pytest.approx(0.005)
    step = lidar.tls_angular_step(0.01, D)
    assert D * np.tan(step) == pytest.approx(0.01)
