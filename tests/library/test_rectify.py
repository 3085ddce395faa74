"""Tests of photolib.rectify (Chapter 7, §7.1–7.4, §7.7, §7.9) against independent references:
scipy.ndimage.map_coordinates and OpenCV (resampling), literal transcriptions of the book's
formulas, pyproj (geodesy), analytic geometry and ray-cast synthetic images (photolib.synthetic)."""

import math

import cv2
import numpy as np
import pytest
from scipy import ndimage

from photolib.camera import ExteriorOrientation, InteriorOrientation
from photolib.errors import ConvergenceError, InputError
from photolib.rectify import (RasterGrid, admissible_height, apriori_accuracy, cutline_boundary, dem_height,
                              frame_projector, geocentric_to_geodetic, geocentric_to_topocentric,
                              geodetic_to_geocentric, map_tolerance, monoplot, mosaic, ortho_accuracy,
                              ortho_pixel_size, orthorectify, rectify_forward, rectify_homography,
                              rectify_to_horizontal, relief_displacement, resample, topocentric_matrix,
                              topocentric_to_geocentric)
from photolib.single_image import image_to_ground, project
from photolib.synthetic import render_image, terrain_scene


# --------------------------------------------------------------------------- resampling (§7.2–7.3)
def _random_image(seed=0, shape=(24, 30)):
    return np.random.default_rng(seed).random(shape).astype(np.float32)


def _positions_on_32nd(rng, n, limit_r, limit_c):
    """OpenCV's remap quantises positions to 1/32 pixel (INTER_BITS = 5): test on that lattice."""
    rows = rng.integers(0, int(limit_r * 32) + 1, n) / 32.0
    cols = rng.integers(0, int(limit_c * 32) + 1, n) / 32.0
    return rows.astype(np.float32), cols.astype(np.float32)


def test_bilinear_matches_scipy_map_coordinates():
    image = _random_image(1).astype(float)
    rng = np.random.default_rng(2)
    rows = rng.uniform(0, image.shape[0] - 1, 500)
    cols = rng.uniform(0, image.shape[1] - 1, 500)
    expected = ndimage.map_coordinates(image, [rows, cols], order=1)
    assert np.allclose(resample(image, rows, cols, "bilinear"), expected, atol=1e-12)


@pytest.mark.parametrize("flag, method, kwargs", [(cv2.INTER_NEAREST, "nearest", {}),
                                                  (cv2.INTER_LINEAR, "bilinear", {}),
                                                  (cv2.INTER_CUBIC, "bicubic", {"cubic_a": -0.75})])
def test_resample_matches_opencv_remap_inside_the_span_of_centres(flag, method, kwargs):
    image = _random_image(3)
    rng = np.random.default_rng(4)
    rows, cols = _positions_on_32nd(rng, 800, image.shape[0] - 1, image.shape[1] - 1)
    if method == "nearest":          # avoid exact half-pixel ties (rounding rules differ)
        keep = (np.abs(rows % 1 - 0.5) > 0.01) & (np.abs(cols % 1 - 0.5) > 0.01)
        rows, cols = rows[keep], cols[keep]
    expected = cv2.remap(image, cols[None], rows[None], flag, borderMode=cv2.BORDER_REPLICATE)[0]
    ours = resample(image.astype(float), rows.astype(float), cols.astype(float), method, **kwargs)
    assert np.abs(ours - expected).max() < 1e-6      # float32 weights in OpenCV


def test_opencv_extrapolates_beyond_the_centres_where_we_fill():
    image = _random_image(5)
    rows = np.array([-0.25, 3.0, image.shape[0] - 0.75], dtype=np.float32)
    cols = np.array([2.0, -0.25, 4.0], dtype=np.float32)
    cv = cv2.remap(image, cols[None], rows[None], cv2.INTER_LINEAR, borderMode=cv2.BORDER_REPLICATE)[0]
    ours = resample(image.astype(float), rows, cols, "bilinear", fill=-1.0)
    assert np.all(np.isfinite(cv)) and np.all(ours == -1.0)
    # nearest neighbour serves positions up to half a pixel beyond the edge centres
    assert resample(image.astype(float), [-0.49], [0.0], "nearest")[0] == image[0, 0]
    assert np.isnan(resample(image.astype(float), [-0.51], [0.0], "nearest")[0])


def test_book_nearest_neighbour_rounding():
    # §7.2: x = 150.3, y = 21.7 → j = 150, i = 22 (x ↔ column j, y ↔ row i)
    image = np.arange(300 * 200, dtype=float).reshape(300, 200)
    value = resample(image, [21.7], [150.3], "nearest")[0]
    assert value == image[22, 150]


def test_bicubic_keys_is_exact_on_quadratic_brightness():
    rr, cc = np.mgrid[0:15, 0:17].astype(float)
    image = 2.0 + 0.3 * rr - 0.2 * cc + 0.05 * rr ** 2 + 0.02 * rr * cc - 0.03 * cc ** 2
    rng = np.random.default_rng(6)
    r, c = rng.uniform(1, 13, 200), rng.uniform(1, 15, 200)
    truth = 2.0 + 0.3 * r - 0.2 * c + 0.05 * r ** 2 + 0.02 * r * c - 0.03 * c ** 2
    assert np.allclose(resample(image, r, c, "bicubic"), truth, atol=1e-12)


def test_resample_multiband_equals_bandwise():
    rgb = np.random.default_rng(7).random((10, 12, 3))
    r, c = np.array([[1.2, 4.7]]), np.array([[3.3, 8.9]])
    out = resample(rgb, r, c, "bicubic")
    assert out.shape == (1, 2, 3)
    for b in range(3):
        assert np.allclose(out[..., b], resample(rgb[..., b], r, c, "bicubic"))


# --------------------------------------------------------------------------- forward method (§7.2)
def test_forward_book_example_area_weights():
    # §7.2: x^T = 151.3, y^T = 20.7 covers four output pixels; overlapped areas of a unit square
    out, weight = rectify_forward(np.array([[80.0]]), np.array([[20.7]]), np.array([[151.3]]), (25, 155))
    expected = {(20, 151): 0.7 * 0.3, (20, 152): 0.3 * 0.3, (21, 151): 0.7 * 0.7, (21, 152): 0.3 * 0.7}
    for (i, j), w in expected.items():
        assert weight[i, j] == pytest.approx(w, abs=1e-12)
        assert out[i, j] == pytest.approx(80.0)
    assert weight.sum() == pytest.approx(1.0)
    assert np.isnan(out).sum() == out.size - 4


def test_forward_conserves_flux_and_averages():
    rng = np.random.default_rng(8)
    image = rng.random((20, 20))
    rr, cc = np.mgrid[0:20, 0:20].astype(float)
    theta = 0.3
    rows = 10 + 0.8 * ((rr - 10) * math.cos(theta) - (cc - 10) * math.sin(theta))
    cols = 12 + 0.8 * ((rr - 10) * math.sin(theta) + (cc - 10) * math.cos(theta))
    out, weight = rectify_forward(image, rows, cols, (30, 30))
    assert weight.sum() == pytest.approx(image.size)                  # every pixel fully inside
    assert np.nansum(out * weight) == pytest.approx(image.sum())      # brightness·area conserved
    flat, _ = rectify_forward(np.full((20, 20), 7.0), rows, cols, (30, 30))
    assert np.allclose(flat[weight > 0], 7.0)


def test_forward_leaves_holes_when_upsampling_and_inverse_does_not():
    image = np.random.default_rng(9).random((10, 10))
    rr, cc = np.mgrid[0:10, 0:10].astype(float)
    out, weight = rectify_forward(image, 2.0 * rr, 2.0 * cc, (19, 19))
    assert np.isnan(out).sum() == 19 * 19 - 100            # only the 100 hit pixels get a value
    R, C = np.mgrid[0:19, 0:19].astype(float)
    inverse = resample(image, R / 2.0, C / 2.0, "bilinear")
    assert not np.isnan(inverse).any()


# --------------------------------------------------------------------------- DEM heights (7.3.1)
def _formula_731(Z1, Z2, Z3, Z4, dX, dY, D):
    """(7.3.1) as printed; nodes 1 = (X1, Y1), 2 = (X1, Y1 + D), 3 = (X1 + D, Y1), 4 = (X1 + D, Y1 + D)."""
    ZK = Z1 + (Z2 - Z1) / D * dY
    ZM = Z3 + (Z4 - Z3) / D * dY
    return ZK + (ZM - ZK) / D * dX


def test_dem_height_equals_the_book_formula():
    rng = np.random.default_rng(10)
    dem = rng.uniform(100, 200, (6, 7))
    grid = RasterGrid(500.0, 800.0, 5.0, dem.shape)
    X = rng.uniform(grid.x0 + 2.5, grid.x0 + 6.5 * 5 - 2.5, 100)
    Y = rng.uniform(grid.y0 - 5.5 * 5 + 2.5, grid.y0 - 2.5, 100)
    ours = dem_height(dem, grid, X, Y)
    for x, y, z in zip(X, Y, ours):
        r, c = grid.rowcol(x, y)
        i, j = int(math.ceil(r)), int(math.floor(c))            # node 1: lower-left (south-west)
        i = min(i, dem.shape[0] - 1)
        X1, Y1 = grid.xy(i, j)
        Z1, Z2, Z3, Z4 = dem[i, j], dem[i - 1, j], dem[i, j + 1], dem[i - 1, j + 1]
        assert z == pytest.approx(_formula_731(Z1, Z2, Z3, Z4, x - X1, y - Y1, 5.0), abs=1e-9)


def test_dem_height_exact_on_planes():
    grid = RasterGrid(0.0, 100.0, 4.0, (25, 25))
    X, Y = grid.centres()
    dem = 0.12 * X - 0.07 * Y + 150.0
    rng = np.random.default_rng(11)
    x, y = rng.uniform(2, 98, 300), rng.uniform(2, 98, 300)
    assert np.allclose(dem_height(dem, grid, x, y), 0.12 * x - 0.07 * y + 150.0, atol=1e-10)


def test_dem_height_outside_names_the_missing_area():
    grid = RasterGrid(0.0, 100.0, 10.0, (10, 10))
    with pytest.raises(InputError, match=r"missing area spans X 120\.\.130"):
        dem_height(np.zeros((10, 10)), grid, [50.0, 120.0, 130.0], [50.0, 50.0, 50.0])
    out = dem_height(np.zeros((10, 10)), grid, [50.0, 120.0], [50.0, 50.0], outside="nan")
    assert out[0] == 0.0 and np.isnan(out[1])


# --------------------------------------------------------------------------- grids (§7.3)
def test_aligned_grid_origin_is_a_multiple_of_the_pixel():
    size = ortho_pixel_size(0.01, 14000)              # Δ·m: 10 µm, 1:14 000 → 0.14 m
    assert size == pytest.approx(0.14)
    grid = RasterGrid.aligned(1003.31, 2001.07, 1043.9, 2040.2, size)
    assert grid.x0 / size == pytest.approx(round(grid.x0 / size), abs=1e-9)
    assert grid.y0 / size == pytest.approx(round(grid.y0 / size), abs=1e-9)
    xmin, ymin, xmax, ymax = grid.extent
    assert xmin <= 1003.31 < xmin + size and ymax - size < 2040.2 <= ymax
    assert xmax >= 1043.9 and ymin <= 2001.07


# --------------------------------------------------------------------------- ortho of a ray-cast image
@pytest.fixture(scope="module")
def scene_and_render():
    scene = terrain_scene(extent=120.0, spacing=1.0, n_buildings=0, relief=15.0, relief_scale=30.0,
                          texture_scale=2.0, seed=3)
    io = InteriorOrientation(50.0)
    eo = ExteriorOrientation(60.0, 60.0, 500.0, 0.03, -0.02, 0.1)
    render = render_image(scene, io, eo, (200, 200), pixel_size=0.05, supersample=1)
    dem = scene.ground[::-1]                 # the scene's row 0 is south; ours is north
    dem_grid = RasterGrid(scene.x[0] - 0.5, scene.y[-1] + 0.5, 1.0, dem.shape)
    return scene, render, dem, dem_grid


def test_frame_projector_inverts_the_renderer(scene_and_render):
    _, render, _, _ = scene_and_render
    project_ = frame_projector(render.eo, render.io, render.pixel_size, render.shape)
    rows, cols = project_(render.XYZ[..., 0], render.XYZ[..., 1], render.XYZ[..., 2])
    rr, cc = np.mgrid[0:200, 0:200]
    assert np.abs(rows - rr).max() < 1e-9 and np.abs(cols - cc).max() < 1e-9


def test_orthorectify_recovers_the_ground_positions_and_texture(scene_and_render):
    scene, render, dem, dem_grid = scene_and_render
    project_ = frame_projector(render.eo, render.io, render.pixel_size, render.shape)
    grid = RasterGrid.aligned(35.0, 35.0, 85.0, 85.0, 0.5)
    X, Y = grid.centres()
    gsd = render.pixel_size * (render.eo.Zs - dem.mean()) / render.io.f
    # "images" whose brightness is the X (Y) of the ground point each pixel sees (ray-cast truth)
    for method, bound in (("bilinear", 0.01 * gsd), ("bicubic", 0.01 * gsd), ("nearest", 0.75 * gsd)):
        oX = orthorectify(render.XYZ[..., 0], project_, dem, dem_grid, grid, method)
        oY = orthorectify(render.XYZ[..., 1], project_, dem, dem_grid, grid, method)
        assert np.abs(oX - X).max() < bound and np.abs(oY - Y).max() < bound, method
    truth = scene.albedo_at(X, Y)
    rms = {m: np.sqrt(np.mean((orthorectify(render.image, project_, dem, dem_grid, grid, m) - truth) ** 2))
           for m in ("nearest", "bilinear")}
    assert rms["bilinear"] < 0.1 * scene.albedo.std()
    assert rms["nearest"] > rms["bilinear"]            # §7.3: nearest neighbour is worse


def test_orthorectify_dem_not_covering_the_grid(scene_and_render):
    _, render, dem, dem_grid = scene_and_render
    project_ = frame_projector(render.eo, render.io, render.pixel_size, render.shape)
    with pytest.raises(InputError, match="missing area spans X"):
        orthorectify(render.image, project_, dem, dem_grid, RasterGrid(100.0, 60.0, 1.0, (10, 40)))


def test_points_behind_the_camera_get_the_fill():
    eo = ExteriorOrientation(0.0, 0.0, 100.0)
    project_ = frame_projector(eo, InteriorOrientation(100.0), 0.01, (101, 101))
    rows, cols = project_([0.0, 0.0], [0.0, 0.0], [0.0, 150.0])        # second point above S
    assert (rows[0], cols[0]) == (50.0, 50.0) and rows[1] < -1e8
    grid = RasterGrid(-0.5, 0.5, 1.0, (1, 1))
    out = orthorectify(np.ones((101, 101)), project_, np.full((3, 3), 150.0),
                       RasterGrid(-1.5, 1.5, 1.0, (3, 3)), grid, fill=-5.0)
    assert out[0, 0] == -5.0


# --------------------------------------------------------------------------- central projection (§7.2)
def test_rectify_homography_matches_opencv_warp():
    rr, cc = np.mgrid[0:60, 0:80].astype(float)
    image = np.sin(rr / 7.0) + np.cos(cc / 9.0)                        # smooth: |∇| ≤ 1/7 + 1/9
    H = np.array([[0.95, 0.04, 3.0], [-0.03, 1.02, 2.0], [2e-4, -1e-4, 1.0]])
    ours = rectify_homography(image, H, (50, 60))
    cv = cv2.warpPerspective(image.astype(np.float32), H, (60, 50),
                             flags=cv2.INTER_LINEAR | cv2.WARP_INVERSE_MAP)
    inside = ~np.isnan(ours)
    inside[:2] = inside[-2:] = False
    inside[:, :2] = inside[:, -2:] = False
    bound = (1 / 7 + 1 / 9) * math.sqrt(2) / 32          # OpenCV's 1/32-pixel position lattice
    assert inside.sum() > 2000 and np.abs(ours - cv)[inside].max() < bound


def test_rectify_to_horizontal_equals_a_vertical_image_of_flat_ground():
    scene = terrain_scene(extent=300.0, spacing=2.0, n_buildings=0, relief=0.0, seed=4)
    io = InteriorOrientation(50.0)
    tilted = ExteriorOrientation(150.0, 150.0, 600.0, 0.04, -0.03, 0.2)
    vertical = ExteriorOrientation(150.0, 150.0, 600.0)
    r_t = render_image(scene, io, tilted, (120, 120), pixel_size=0.05, supersample=1)
    r_v = render_image(scene, io, vertical, (120, 120), pixel_size=0.05, supersample=1)
    # brightness = the X seen: bilinear interpolation of a nearly linear function of the pixel
    out = rectify_to_horizontal(r_t.XYZ[..., 0], tilted.matrix, io.f, 0.05)
    valid = ~np.isnan(out)
    assert valid.sum() > 0.4 * out.size              # the tilt shifts the footprint by ~40 px
    assert np.abs(out - r_v.XYZ[..., 0])[valid].max() < 1e-3


# --------------------------------------------------------------------------- geodesy (§7.3)
pyproj = pytest.importorskip("pyproj")
GSK = "+a=6378136.5 +rf=298.2564151"


def _points():
    rng = np.random.default_rng(12)
    B = np.radians(rng.uniform(-89, 89, 200))
    L = np.radians(rng.uniform(-180, 180, 200))
    H = rng.uniform(-500, 900e3, 200)
    return B, L, H


@pytest.mark.parametrize("name, crs", [("WGS-84", ("EPSG:4979", "EPSG:4978")),
                                       ("GSK-2011", (f"+proj=longlat {GSK} +no_defs", f"+proj=geocent {GSK} +no_defs"))])
def test_geodetic_geocentric_against_pyproj(name, crs):
    B, L, H = _points()
    t = pyproj.Transformer.from_crs(*crs, always_xy=True)
    X, Y, Z = t.transform(np.degrees(L), np.degrees(B), H)
    ours = geodetic_to_geocentric(B, L, H, name)
    assert np.allclose(ours, (X, Y, Z), atol=1e-6, rtol=0)
    back = geocentric_to_geodetic(X, Y, Z, name)
    assert np.allclose(back[0], B, atol=1e-12) and np.allclose(back[1], L, atol=1e-12)
    assert np.allclose(back[2], H, atol=1e-6)


def test_gsk2011_constants_are_not_wgs84():
    a = geodetic_to_geocentric(0.0, 0.0, 0.0, "GSK-2011")[0]
    assert a == 6378136.5 and geodetic_to_geocentric(0.0, 0.0, 0.0, "WGS-84")[0] == 6378137.0


def test_topocentric_frame_is_north_west_up_against_pyproj():
    B0, L0, H0 = math.radians(55.75), math.radians(37.62), 180.0
    R = topocentric_matrix(B0, L0)
    assert np.allclose(R @ R.T, np.eye(3)) and np.linalg.det(R) == pytest.approx(1.0)
    rng = np.random.default_rng(13)
    XYZ0 = geodetic_to_geocentric(B0, L0, H0, "WGS-84")
    X, Y, Z = (XYZ0[k] + rng.uniform(-5e3, 5e3, 50) for k in range(3))
    pipe = pyproj.Transformer.from_pipeline(
        f"+proj=topocentric +ellps=WGS84 +lat_0={math.degrees(B0)} +lon_0={math.degrees(L0)} +h_0={H0}")
    E, N, U = pipe.transform(X, Y, Z)
    x, y, z = geocentric_to_topocentric(X, Y, Z, (B0, L0, H0), "WGS-84")
    assert np.allclose(x, N, atol=1e-6) and np.allclose(y, -E, atol=1e-6) and np.allclose(z, U, atol=1e-6)
    assert np.allclose(topocentric_to_geocentric(x, y, z, (B0, L0, H0), "WGS-84"), (X, Y, Z), atol=1e-6)


# --------------------------------------------------------------------------- §7.4
def test_relief_displacement_is_exact_for_a_vertical_photo():
    f, H = 100.0, 1000.0
    eo, io = ExteriorOrientation(0.0, 0.0, H), InteriorOrientation(f)
    rng = np.random.default_rng(14)
    XYZ = np.column_stack([rng.uniform(-400, 400, 30), rng.uniform(-400, 400, 30), rng.uniform(-50, 80, 30)])
    xy = project(XYZ, eo, io)
    on_datum = image_to_ground(xy, 0.0, eo, io)             # rectified onto the plane Z = 0
    shift = np.hypot(*(on_datum[:, :2] - XYZ[:, :2]).T)
    r = np.hypot(*xy.T)
    assert np.allclose(shift, np.abs(relief_displacement(r, XYZ[:, 2], f)), rtol=1e-12)


def test_admissible_relief_meets_the_map_tolerance():
    dR = map_tolerance(2000)                                   # 0.3 mm · 2000 = 0.6 m
    assert dR == pytest.approx(0.6)
    h = admissible_height(100.0, 80.0, dR)
    assert relief_displacement(80.0, h, 100.0) == pytest.approx(dR)


# --------------------------------------------------------------------------- monoplotting (§7.7)
def _bisect_ray(xy, eo, io, dem, grid):
    """Independent truth: the first crossing of the ray with the bilinear DEM by bisection on Z."""
    def gap(Z):
        X, Y, _ = image_to_ground([xy], Z, eo, io)[0]
        return Z - dem_height(dem, grid, X, Y)
    lo, hi = dem.min() - 1.0, dem.max() + 1.0
    for _ in range(100):
        mid = 0.5 * (lo + hi)
        lo, hi = (lo, mid) if gap(lo) * gap(mid) <= 0 else (mid, hi)
    return image_to_ground([xy], 0.5 * (lo + hi), eo, io)[0]


def test_monoplot_converges_to_the_ray_dem_intersection(scene_and_render):
    scene, render, dem, dem_grid = scene_and_render
    rows, cols = np.array([20, 100, 180, 50]), np.array([30, 100, 170, 160])
    xy = np.column_stack(render.pixel_to_image(cols.astype(float), rows.astype(float)))
    result = monoplot(xy, render.eo, render.io, dem, dem_grid, tol=1e-6)
    for k in range(len(xy)):
        truth = _bisect_ray(xy[k], render.eo, render.io, dem, dem_grid)
        assert np.allclose(result.XYZ[k], truth, atol=1e-5)
    # the renderer's ray-cast truth lies on the triangulated surface, within the bilinear/TIN
    # difference of the DEM (centimetres on this relief)
    assert np.abs(result.XYZ - render.XYZ[rows, cols]).max() < 0.05
    assert result.iterations.min() >= 2 and result.iterations.max() <= 10
    assert len(result.history) == result.iterations.max()


def test_monoplot_diverges_on_terrain_steeper_than_the_ray():
    grid = RasterGrid(-5000.0, 5000.0, 50.0, (200, 200))
    X, _ = grid.centres()
    dem = 2.2 * X + 100.0            # slope 2.2 × the ray's tan(nadir angle) 0.5 = 1.1 > 1
    eo, io = ExteriorOrientation(0.0, 0.0, 2000.0), InteriorOrientation(100.0)
    # the fixed point is X* = 950/2.1 = 452.4, Z* = 1095.2; start 4.8 m above it
    with pytest.raises(ConvergenceError) as info:
        monoplot([[50.0, 0.0]], eo, io, dem, grid, z_start=1100.0, max_iter=30)
    steps = np.abs(np.diff([h[0, 0] for h in info.value.history]))
    assert len(steps) == 29 and np.allclose(steps[1:] / steps[:-1], 1.1)
    # the same start on terrain of slope 1.8 (factor 0.9) converges to the fixed point
    result = monoplot([[50.0, 0.0]], eo, io, 1.8 * X + 100.0, grid, z_start=1100.0, tol=1e-6, max_iter=300)
    assert result.XYZ[0, 0] == pytest.approx(950.0 / 1.9)


def test_monoplot_dem_height_error_gives_r_dz_over_f():
    grid = RasterGrid(-1000.0, 1000.0, 20.0, (100, 100))
    eo, io = ExteriorOrientation(0.0, 0.0, 1500.0), InteriorOrientation(100.0)
    xy = np.array([[30.0, 40.0]])
    good = monoplot(xy, eo, io, np.full((100, 100), 200.0), grid).XYZ
    bad = monoplot(xy, eo, io, np.full((100, 100), 202.0), grid).XYZ
    assert np.hypot(*(bad - good)[0, :2]) == pytest.approx(relief_displacement(50.0, 2.0, 100.0))


# --------------------------------------------------------------------------- mosaics (§7.7)
def test_mosaic_row_rule_and_origin():
    g1 = RasterGrid(100.0, 520.0, 2.0, (10, 12))
    g2 = RasterGrid(112.0, 524.0, 2.0, (12, 14))
    o1, o2 = np.full(g1.shape, 1.0), np.full(g2.shape, 2.0)
    cutline = np.array([[117.0, 490.0], [121.5, 530.0]])
    image, grid, source = mosaic([o1, o2], [g1, g2], cutline, return_source=True)
    assert (grid.x0, grid.y0) == (100.0, 524.0)                # X0M = min, Y0M = max
    assert grid.extent == (100.0, 500.0, 140.0, 524.0)
    for i in range(grid.shape[0]):
        _, Yc = grid.xy(i, 0)
        Xcut = np.interp(Yc, cutline[:, 1], cutline[:, 0])
        for j in range(grid.shape[1]):
            left_edge = grid.x0 + j * grid.dx
            Xc, Yc = grid.xy(i, j)
            in1 = g1.extent[0] < Xc < g1.extent[2] and g1.extent[1] < Yc < g1.extent[3]
            in2 = g2.extent[0] < Xc < g2.extent[2] and g2.extent[1] < Yc < g2.extent[3]
            want = 0 if left_edge <= Xcut else 1                # P1 up to and including the boundary pixel
            if not (in1, in2)[want]:
                want = 0 if in1 else (1 if in2 else -1)          # fill_gaps
            assert source[i, j] == want, (i, j)
    assert np.all(image[source == 0] == 1.0) and np.all(image[source == 1] == 2.0)
    assert np.all(np.isnan(image[source == -1]))


def test_mosaic_of_two_orthos_of_one_texture_is_seamless():
    big = RasterGrid(0.0, 60.0, 1.0, (60, 60))
    X, Y = big.centres()
    texture = np.sin(X / 3.0) * np.cos(Y / 5.0)
    g1, g2 = big.window(0, 0, 60, 40), big.window(5, 25, 50, 35)
    image, grid = mosaic([texture[:, :40], texture[5:55, 25:]], [g1, g2], [[30.0, 0.0], [33.0, 60.0]])
    assert grid == big
    covered = np.zeros(big.shape, bool)
    covered[:, :40] = covered[5:55, 25:] = True
    assert np.array_equal(~np.isnan(image), covered)
    assert np.array_equal(image[covered], texture[covered])


def test_cutline_boundary_example():
    grid = RasterGrid(0.0, 4.0, 1.0, (4, 6))
    # row centres Y = 3.5 … 0.5 → X = 4.25, 3.75, 3.25, 2.75 → columns 4, 3, 3, 2
    assert cutline_boundary(grid, [[2.5, 0.0], [4.5, 4.0]]).tolist() == [4, 3, 3, 2]


# --------------------------------------------------------------------------- accuracy (§7.9)
def test_ortho_accuracy_figures():
    measured = np.array([[10.3, 20.4], [30.0, 40.0], [50.0, 59.0]])
    true = np.array([[10.0, 20.0], [30.0, 40.6], [50.0, 60.0]])
    report = ortho_accuracy(measured, true, 2000, cutline_xy=([[0, 0], [1, 1]], [[0, 1.2], [1, 2.6]]))
    assert report.mean_error_mm == pytest.approx((0.5 + 0.6 + 1.0) / 3 / 2000 * 1000)
    assert report.max_error_mm == pytest.approx(0.5) and report.passes
    assert report.cutline_mean_mm == pytest.approx(0.7) and report.cutline_passes
    assert not ortho_accuracy(measured * 1.0, true, 1000).passes


def test_apriori_accuracy_by_monoplotting_control_points(scene_and_render):
    _, render, dem, dem_grid = scene_and_render
    rows, cols = np.array([30, 90, 150]), np.array([40, 120, 60])
    control = render.XYZ[rows, cols]
    xy = np.column_stack(render.pixel_to_image(cols.astype(float), rows.astype(float)))
    report = apriori_accuracy(xy, control, render.eo, render.io, dem, dem_grid, 500)
    assert report.passes and report.max_error_mm < 0.1        # < 5 cm on the ground at 1:500
    biased = ExteriorOrientation(*render.eo.vector[:3], render.eo.omega + 0.003, render.eo.alpha,
                                 render.eo.kappa)
    assert not apriori_accuracy(xy, control, biased, render.io, dem, dem_grid, 500).passes
