"""photolib.planning (Chapter 10, §10.3): flight planning, relief, GCP markers, IMU tolerances.

Expected values come from hand arithmetic, analytic geometry over planes, brute-force coverage
counting, an independent z-buffer projection of the terrain, rotation matrices of Chapter 1 and
pyproj's geodesic — never from the module's own output.
"""

import math

import numpy as np
import pytest

from photolib import planning
from photolib.errors import DegenerateGeometryError, InputError
from photolib.rotation import rotation_matrix
from photolib.synthetic import terrain_height


# ----------------------------------------------------------------------------- GSD and the block
def test_gsd_and_height_are_inverse():
    # 5.2 µm pixel, f = 100 mm, H = 1500 m: GSD = 0.0052 · 1500 / 100 = 0.078 m
    assert planning.ground_sample_distance(0.0052, 100.0, 1500.0) == pytest.approx(0.078, rel=1e-12)
    assert planning.flying_height_for_gsd(0.078, 0.0052, 100.0) == pytest.approx(1500.0, rel=1e-12)


def _coverage(centres, Lx, Ly, pts):
    """How many footprints (axis-aligned rectangles) contain each point."""
    dx = np.abs(pts[:, None, 0] - centres[None, :, 0]) <= Lx / 2 + 1e-9
    dy = np.abs(pts[:, None, 1] - centres[None, :, 1]) <= Ly / 2 + 1e-9
    return dx & dy


@pytest.mark.parametrize("length, width, p, q", [(5000.0, 3000.0, 0.6, 0.3), (7300.0, 1200.0, 0.8, 0.2),
                                                 (900.0, 500.0, 0.6, 0.3), (12000.0, 6100.0, 0.65, 0.4)])
def test_block_covers_in_stereo_with_the_fewest_images(length, width, p, q):
    plan = planning.plan_block(length, width, f=100.0, pixel_size=0.005, sensor=(10000, 14000), gsd=0.1,
                               forward_overlap=p, side_overlap=q)
    assert plan.flying_height == pytest.approx(2000.0)
    assert plan.footprint_along == pytest.approx(1000.0) and plan.footprint_across == pytest.approx(1400.0)
    assert plan.base == pytest.approx((1 - p) * 1000.0) and plan.strip_spacing == pytest.approx((1 - q) * 1400.0)
    g = np.stack(np.meshgrid(np.linspace(0, length, 241), np.linspace(0, width, 61)), -1).reshape(-1, 2)
    inside = _coverage(plan.exposure_centres(), plan.footprint_along, plan.footprint_across, g)
    strip = np.repeat(np.arange(plan.n_strips), plan.images_per_strip)
    per_strip = np.stack([inside[:, strip == j].sum(1) for j in range(plan.n_strips)], 1)
    assert (per_strip.max(1) >= 2).all(), "a block point outside every stereo model"

    # one exposure fewer per strip (re-centred) leaves stereo gaps; one strip fewer leaves gaps
    m, n = plan.images_per_strip - 1, plan.n_strips - 1
    if m >= 2:
        xs = length / 2 + (np.arange(m) - (m - 1) / 2) * plan.base
        fewer = np.column_stack([xs, np.full(m, width / 2)])
        line = np.column_stack([np.linspace(0, length, 2001), np.full(2001, width / 2)])
        assert (_coverage(fewer, plan.footprint_along, 1.0, line).sum(1) < 2).any()
    if n >= 1:
        ys = width / 2 + (np.arange(n) - (n - 1) / 2) * plan.strip_spacing
        column = np.linspace(0, width, 2001)
        assert (np.min(np.abs(column[:, None] - ys[None]), 1) > plan.footprint_across / 2 + 1e-9).any()


def test_single_coverage_and_interval():
    plan = planning.plan_block(4000.0, 900.0, f=50.0, pixel_size=0.004, sensor=(6000, 8000), flying_height=500.0,
                               forward_overlap=0.3, side_overlap=0.0, speed=25.0, stereo=False, mean_height=120.0)
    # GSD 0.04 m, L = 240 m along, 320 m across, b = 168 m: ceil(3760/168) + 1 = 24 images; 3 strips
    assert plan.gsd == pytest.approx(0.04) and plan.altitude == pytest.approx(620.0)
    assert plan.images_per_strip == 24 and plan.n_strips == 3 and plan.n_images == 72
    assert plan.exposure_interval == pytest.approx(168.0 / 25.0)


@pytest.mark.parametrize("kwargs, match", [({"forward_overlap": 1.0}, "100 %"), ({"forward_overlap": 1.2}, "100 %"),
                                           ({"side_overlap": 1.0}, "fraction"), ({"forward_overlap": 0.4}, "50 %"),
                                           ({"gsd": None}, "exactly one"), ({"flying_height": 900.0}, "exactly one")])
def test_impossible_plans(kwargs, match):
    args = dict(f=100.0, pixel_size=0.005, sensor=(10000, 10000), gsd=0.1)
    args.update(kwargs)
    with pytest.raises(InputError, match=match):
        planning.plan_block(1000.0, 1000.0, **args)


# ----------------------------------------------------------------------------- relief
def _plane_overlap(Zs, s, a, f, Xi, b):
    """Analytic forward overlap over the plane Z = s·X (vertical images at altitude Zs)."""
    Xe = (Xi + b - Zs * a / f) / (1 - s * a / f)          # ground of image i+1's rear edge
    xs = f * (Xe - Xi) / (Zs - s * Xe)                      # its coordinate in image i
    return (a - xs) / (2 * a)


def test_flat_terrain_gives_nominal_overlap_and_gsd():
    dem, grid = planning.surface_dem(lambda X, Y: np.full_like(X, 250.0), (-3000, -2000, 5000, 2000), 50.0)
    s = planning.strip_over_relief(dem, grid, (0, 0), (2400, 0), altitude=1250.0, base=400.0, f=100.0,
                                   pixel_size=0.01, sensor=(10000, 8000), samples=40)
    np.testing.assert_allclose(s.forward_overlap, 0.6, atol=1e-12)        # 1 − 400/1000
    np.testing.assert_allclose(s.gsd_mean, 0.1, rtol=1e-9)
    fp = s.footprints[0]
    np.testing.assert_allclose([fp[:, 0].min(), fp[:, 0].max(), fp[:, 1].min(), fp[:, 1].max()],
                               [-500, 500, -400, 400], atol=1e-3)


@pytest.mark.parametrize("slope", [0.1, -0.15])
def test_tilted_plane_matches_analytic_overlap_and_gsd(slope):
    k = 200
    dem, grid = planning.surface_dem(lambda X, Y: slope * X + 0 * Y, (-2000, -1000, 4000, 1000), 25.0)
    s = planning.strip_over_relief(dem, grid, (0, 0), (1200, 0), altitude=1200.0, base=400.0, f=100.0,
                                   pixel_size=0.01, sensor=(10000, 10000), samples=k)
    expected = [_plane_overlap(1200.0, slope, 50.0, 100.0, 400.0 * i, 400.0) for i in range(3)]
    np.testing.assert_allclose(s.forward_overlap, expected, atol=1.0 / k)
    assert s.min_pair == int(np.argmin(expected))
    # mean GSD over the cells: ground of the cell centres on the plane, analytically
    x = ((np.arange(k) + 0.5) / k * 2 - 1) * 50.0
    for i, Xi in enumerate(400.0 * np.arange(4)):
        X = (Xi + 1200.0 * x / 100.0) / (1 + slope * x / 100.0)
        assert s.gsd_mean[i] == pytest.approx(np.mean(0.01 * (1200.0 - slope * X) / 100.0), rel=1e-6)


def _zbuffer_overlap(surface, ci, cn, Zs, f, a, c, k, spacing=4.0):
    """Independent overlap: project a dense terrain cloud into image i, keep the highest point per
    cell (the visible one for a nadir camera, to within a cell), test whether it lies in image i+1."""
    half_x, half_y = (Zs - 0.0) * a / f * 1.2, (Zs - 0.0) * c / f * 1.2
    X, Y = np.meshgrid(np.arange(ci[0] - half_x, ci[0] + half_x, spacing),
                       np.arange(ci[1] - half_y, ci[1] + half_y, spacing))
    X, Y = X.ravel(), Y.ravel()
    Z = surface(X, Y)
    u = f * (X - ci[0]) / (Zs - Z)
    v = f * (Y - ci[1]) / (Zs - Z)
    ok = (np.abs(u) < a) & (np.abs(v) < c)
    col = np.floor((u[ok] + a) / (2 * a) * k).astype(int)
    row = np.floor((v[ok] + c) / (2 * c) * k).astype(int)
    cell = row * k + col
    order = np.lexsort((Z[ok], cell))
    last = np.r_[cell[order][1:] != cell[order][:-1], True]
    pick = np.flatnonzero(ok)[order[last]]
    assert len(pick) == k * k, "empty image cells: densify the cloud"
    un = f * (X[pick] - cn[0]) / (Zs - Z[pick])
    vn = f * (Y[pick] - cn[1]) / (Zs - Z[pick])
    return float(np.mean((np.abs(un) <= a) & (np.abs(vn) <= c)))


def test_synthetic_terrain_against_zbuffer():
    def surface(X, Y):
        return terrain_height(X, Y, mean=300.0, relief=160.0, wavelength=2500.0)
    dem, grid = planning.surface_dem(surface, (-1500, -1500, 4500, 1500), 10.0)
    k = 30
    s = planning.strip_over_relief(dem, grid, (0, 0), (2800, 0), altitude=1300.0, base=350.0, f=100.0,
                                   pixel_size=0.01, sensor=(10000, 10000), samples=k)
    ref = [_zbuffer_overlap(surface, s.centres[i], s.centres[i + 1], 1300.0, 100.0, 50.0, 50.0, k)
           for i in range(len(s.centres) - 1)]
    np.testing.assert_allclose(s.forward_overlap, ref, atol=2.0 / k)
    assert s.forward_overlap.min() < 1 - 350.0 / 1000.0 < s.forward_overlap.max()   # relief makes p vary
    assert s.min_overlap == pytest.approx(s.forward_overlap.min())


def test_strip_errors():
    dem, grid = planning.surface_dem(lambda X, Y: 0 * X + 100.0, (-500, -500, 500, 500), 50.0)
    common = dict(base=100.0, f=100.0, pixel_size=0.01, sensor=(1000, 1000))
    with pytest.raises(DegenerateGeometryError, match="not above"):
        planning.strip_over_relief(dem, grid, (0, 0), (200, 0), altitude=50.0, **common)
    with pytest.raises(InputError, match="leave the DEM"):
        planning.strip_over_relief(dem, grid, (0, 0), (200, 0), altitude=20000.0, **common)
    with pytest.raises(InputError, match="shorter than one base"):
        planning.strip_over_relief(dem, grid, (0, 0), (50, 0), altitude=300.0, **common)


def test_real_dem_strip_and_local_frame():
    from photolib.datasets import DataUnavailableError, data_path
    pytest.importorskip("rasterio")
    pyproj = pytest.importorskip("pyproj")
    from photolib.georaster import read_dem
    try:
        heights, grid, crs = read_dem(data_path("dem", "srtm_ref.tif"))
    except DataUnavailableError as exc:
        pytest.skip(f"real data absent: {exc}")
    Z, lg, local = planning.dem_to_local(heights, grid, crs, bounds=(-12000, -6000, 12000, 6000))
    # distances in the local frame agree with the geodesic on the ellipsoid
    to_ll = pyproj.Transformer.from_crs(local, "EPSG:4326", always_xy=True)
    lon, lat = to_ll.transform([-10000.0, 10000.0], [-5000.0, 5000.0])
    dist = pyproj.Geod(ellps="WGS84").inv(lon[0], lat[0], lon[1], lat[1])[2]
    assert dist == pytest.approx(math.hypot(20000.0, 10000.0), rel=2e-5)
    # SRTM heights in the local grid equal the DEM's at the same geographic point
    from photolib.rectify import dem_height
    lo, la = to_ll.transform(3000.0, -2000.0)
    assert dem_height(Z, lg, np.array([3000.0]), np.array([-2000.0]))[0] == pytest.approx(
        dem_height(heights, grid, np.array([lo]), np.array([la]))[0], abs=15.0)
    plan = planning.plan_block(18000.0, 4000.0, f=100.0, pixel_size=0.006, sensor=(11000, 17000), gsd=0.3,
                               mean_height=float(Z.mean()))
    s = planning.strip_over_relief(Z, lg, (-9000, 0), (9000, 0), altitude=plan.altitude, base=plan.base,
                                   f=100.0, pixel_size=0.006, sensor=(11000, 17000), samples=30)
    assert len(s.centres) == 14
    i = s.min_pair

    def surface(X, Y):
        return dem_height(Z, lg, X, Y)
    ref = _zbuffer_overlap(surface, s.centres[i], s.centres[i + 1], plan.altitude, 100.0, 33.0, 51.0, 30,
                           spacing=15.0)
    assert s.min_overlap == pytest.approx(ref, abs=2.0 / 30)
    assert s.min_overlap < plan.forward_overlap        # relief above the mean plane eats overlap
    np.testing.assert_array_less(s.gsd_min, s.gsd_max)


# ----------------------------------------------------------------------------- markers and the IMU
def test_marker_sizes_from_gsd():
    m = planning.gcp_marker(0.05)
    assert (m.arm_min, m.arm_max, m.width_min, m.width_max, m.square_min) == pytest.approx((0.2, 1.0, 0.1, 0.15, 0.4))
    assert planning.check_marker(m.arm_min, m.width_min, 0.05).ok          # the smallest design conforms
    assert planning.check_marker(m.arm_min, m.width_max, 0.05).ok
    c = planning.check_marker(0.15, 0.1, 0.05)                               # 3-GSD arms: too short, span 6 px
    assert not c.arm_ok and not c.square_ok and c.width_ok and not c.ok
    assert not planning.check_marker(0.5, 0.05, 0.05).width_ok               # 1 GSD wide


def _ground_shift(H, theta, A):
    """Where a ray at off-nadir angle θ (in the XZ plane) meets the plane Z = 0, turned by A."""
    ray = A @ np.array([math.tan(theta), 0.0, -1.0])
    return np.array([ray[0], ray[1]]) * H / -ray[2]


def test_imu_ground_error_against_rotated_rays():
    H, th = 1000.0, math.atan(0.5)
    sr, sh = math.radians(0.005), math.radians(0.01)
    e = planning.imu_ground_error(sr, sr, sh, H, th)
    base = _ground_shift(H, th, np.eye(3))
    # α turns about Y, in the XZ plane; the error is the larger of the two signs (away from the nadir)
    tilt = max((_ground_shift(H, th, rotation_matrix(0.0, sg * sr, 0.0, order="wak")) for sg in (1, -1)),
               key=lambda g: np.linalg.norm(g - _ground_shift(H, th, np.eye(3))))
    head = _ground_shift(H, th, rotation_matrix(0.0, 0.0, sh, order="wak"))
    assert e.pitch_edge == pytest.approx(np.linalg.norm(tilt - base), rel=1e-6)
    assert e.heading_edge == pytest.approx(np.linalg.norm(head - base), rel=1e-6)
    assert e.roll_nadir == pytest.approx(np.linalg.norm(_ground_shift(H, 0.0, rotation_matrix(sr, 0, 0, order="wak"))),
                                         rel=1e-6)
    assert e.roll_nadir == pytest.approx(0.0873, abs=1e-4)                  # H·tan 0.005° at 1000 m


def test_skip_triangulation_at_the_book_limits():
    lim_rp, lim_h = math.radians(0.005), math.radians(0.01)
    ok = planning.skip_aerial_triangulation(lim_rp, lim_rp, lim_h, relief_from_lidar=True, plan_scale=2000)
    assert ok.skip and ok.reasons == ()
    for args in [(lim_rp * 1.01, lim_rp, lim_h), (lim_rp, lim_rp * 1.01, lim_h), (lim_rp, lim_rp, lim_h * 1.01)]:
        assert not planning.skip_aerial_triangulation(*args, relief_from_lidar=True, plan_scale=2000).skip
    assert not planning.skip_aerial_triangulation(0, 0, 0, relief_from_lidar=False, plan_scale=10000).skip
    assert not planning.skip_aerial_triangulation(0, 0, 0, relief_from_lidar=True, plan_scale=1000).skip
    assert not planning.skip_aerial_triangulation(0, 0, 0, relief_from_lidar=True, plan_scale=5000,
                                                  cadastral_points=True).skip


def test_peak_above_the_altitude_inside_a_footprint_is_refused():
    # a 2000-m spike 300 m to the side of the strip: below the centres, above the altitude
    def surface(X, Y):
        return np.where(np.hypot(X - 400.0, Y - 300.0) < 100.0, 2000.0, 100.0)
    dem, grid = planning.surface_dem(surface, (-3000, -3000, 4000, 3000), 25.0)
    with pytest.raises(DegenerateGeometryError, match="reaches the flying altitude"):
        planning.strip_over_relief(dem, grid, (0, 0), (800, 0), altitude=1100.0, base=400.0, f=100.0,
                                   pixel_size=0.01, sensor=(10000, 10000), samples=20)
