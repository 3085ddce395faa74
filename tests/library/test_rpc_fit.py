"""RPC fitting by the terrain-independent grid (§8.6), bias compensation (8.6.1)–(8.6.4), RPC stereo
intersection (8.8.9) and the Kanopus-V conventional frame (§8.18).

Ground truth is synthetic: a small vectorised pushbroom written here (EO quadratic in time,
(8.5.3)/(8.5.5), linear CCD, rays (8.2.2), image → ground (8.5.1)) and a frame camera through
photolib.single_image; the derivatives of (8.8.9) are checked against sympy; the real Pléiades
Ventoux pair is used for the intersection when ../shared/data is present.
"""

import numpy as np
import pytest

from photolib import datasets
from photolib.camera import ExteriorOrientation, InteriorOrientation
from photolib.errors import DegenerateGeometryError
from photolib.rotation import rotation_matrix
from photolib.rpc import (RPC, BiasCorrectedRPC, _rpc_eval, _terms, conventional_frame_rpc, fit_bias, fit_rpc,
                          fit_rpc_points, intersect_rpc, locate, project, rpc_grid)
from photolib.single_image import image_to_ground
from photolib.single_image import project as collinearity
from photolib.synthetic import image_to_pixel, microframe_camera, pixel_to_image


class Pushbroom:
    """Linear-CCD pushbroom: EO quadratic in time, local metric ground frame (X east, Y north).

    The satellite flies along X (k₁ = v), the CCD line is the sensor's y axis (across track).

    Resurs-P-like defaults (H = 475 km, f = 3.8 m, 8 µm pixels, GSD 1 m, v = 7 km/s), the rotation
    A = A_ω A_α A_κ of (1.3.2) and the ray (0, y_c − y₀, −f) of (8.2.2) with y₀ the CCD centre.
    """

    def __init__(self, ncol=8000, eo0=(0, 0, 475e3, 0.08, 0.03, 0.02), k=(7000, 30, -5, 2e-5, -1e-5, 3e-5),
                 d=(0, 0, 0, 1e-7, 0, 0), f=3.8, pixel=8e-6, dt=1 / 7000):
        self.f, self.pixel, self.ncol, self.dt = f, pixel, ncol, dt
        self.eo0, self.k, self.d = (np.asarray(v, float) for v in (eo0, k, d))

    def ground(self, rows, cols, Z):
        rows, cols, Z = np.broadcast_arrays(*(np.asarray(a, float) for a in (rows, cols, Z)))
        t = rows[..., None] * self.dt
        e = self.eo0 + self.k * t + self.d * t * t
        A = rotation_matrix(e[..., 3], e[..., 4], e[..., 5], order="wak")
        ray = np.stack([np.zeros_like(cols), (cols - self.ncol / 2) * self.pixel, np.full(cols.shape, -self.f)], -1)
        Xp = np.einsum("...ij,...j->...i", A, ray)
        return (e[..., 0] + (Z - e[..., 2]) * Xp[..., 0] / Xp[..., 2],
                e[..., 1] + (Z - e[..., 2]) * Xp[..., 1] / Xp[..., 2])


SHAPE = (6000, 8000)


@pytest.fixture(scope="module")
def sensor():
    return Pushbroom(ncol=SHAPE[1])


@pytest.fixture(scope="module")
def five_planes(sensor):
    return fit_rpc(sensor.ground, SHAPE, (0.0, 1000.0), levels=5, step=200)


def random_points(n, seed, shape=SHAPE, heights=(0.0, 1000.0)):
    rng = np.random.default_rng(seed)
    return rng.uniform(0, shape[0] - 1, n), rng.uniform(0, shape[1] - 1, n), rng.uniform(*heights, n)


# ----------------------------------------------------------------------------- §8.6 grid fit
def test_fit_from_a_pushbroom_reproduces_it_at_random_heights(sensor, five_planes):
    fit = five_planes
    assert fit.unknowns == 39 and fit.rpc.line_den_coeff[0] == 1.0 and fit.rpc.samp_den_coeff[0] == 1.0
    r, c, h = random_points(500, 3)
    X, Y = sensor.ground(r, c, h)                         # the rigorous model, independent of the fit
    pr, pc = project(fit.rpc, X, Y, h)
    assert np.max(np.hypot(pr - r, pc - c)) < 1e-6
    assert fit.check_error < 1e-6 and fit.fit_error < 1e-6
    # and the inverse (8.18.1) lands on the sensor's own ground point
    lon, lat = locate(fit.rpc, r, c, h)
    assert np.max(np.hypot(lon - X, lat - Y)) < 1e-5      # metres (GSD 1 m)


def test_fit_from_the_library_pushbroom_reproduces_its_projection():
    """photolib.pushbroom.Pushbroom (EO quadratic in time, Newton line search (8.5.2)) → RPC → the
    same image positions at random heights between the planes."""
    from photolib.pushbroom import EOPolynomial, Pushbroom as LibraryPushbroom

    eo = EOPolynomial([0.0, 0.0, 475e3, 0.08, 0.03, 0.02], [7000.0, 30.0, -5.0, 2e-5, -1e-5, 3e-5],
                      [0.0, 0.0, 0.0, 1e-7, 0.0, 0.0])
    sensor = LibraryPushbroom(3.8, 8e-6, 4000, 1 / 7000, eo, n_rows=3000)
    fit = fit_rpc(sensor.ground, (3000, 4000), (0.0, 1000.0), levels=5, step=200)
    r, c, h = random_points(300, 11, shape=(3000, 4000))
    X, Y = sensor.ground(r, c, h)
    rows, cols = sensor.project(X, Y, h)                   # the rigorous inverse, not the fit
    np.testing.assert_allclose(rows, r, atol=1e-6)
    pr, pc = project(fit.rpc, X, Y, h)
    assert np.max(np.hypot(pr - rows, pc - cols)) < 1e-6


def test_normalisation_spans_minus_one_to_one(sensor, five_planes):
    r, c, lon, lat, h = rpc_grid(sensor.ground, SHAPE, np.linspace(0, 1000, 5), step=200)
    rpc = five_planes.rpc
    for values, off, scale in ((r, rpc.line_off, rpc.line_scale), (c, rpc.samp_off, rpc.samp_scale),
                               (lon, rpc.long_off, rpc.long_scale), (lat, rpc.lat_off, rpc.lat_scale),
                               (h, rpc.height_off, rpc.height_scale)):
        u = (values - off) / scale
        assert u.min() == pytest.approx(-1, abs=1e-12) and u.max() == pytest.approx(1, abs=1e-12)
    assert (rpc.line_off, rpc.line_scale, rpc.height_off, rpc.height_scale) == (2999.5, 2999.5, 500.0, 500.0)


def test_three_height_planes_leave_the_cubic_height_terms_undetermined(sensor):
    # On three distinct heights H³ is a combination of 1, H, H² (a Vandermonde identity) …
    Hn = np.array([-1.0, 0.0, 1.0])
    V = np.stack([np.ones(3), Hn, Hn ** 2], axis=1)
    coef, res, *_ = np.linalg.lstsq(V, Hn ** 3, rcond=None)
    np.testing.assert_allclose(V @ coef, Hn ** 3, atol=1e-15)
    Hn4 = np.linspace(-1, 1, 4)
    V4 = np.stack([np.ones(4), Hn4, Hn4 ** 2], axis=1)
    assert np.linalg.norm(V4 @ np.linalg.lstsq(V4, Hn4 ** 3, rcond=None)[0] - Hn4 ** 3) > 0.1
    # … so the book's literal three-plane fit loses rank and fails between the planes
    three = fit_rpc(sensor.ground, SHAPE, (0.0, 1000.0), levels=3, step=200, height_terms="all")
    four = fit_rpc(sensor.ground, SHAPE, (0.0, 1000.0), levels=4, step=200, height_terms="all")
    assert three.rank[0] < four.rank[0] and three.rank[1] < four.rank[1]
    assert min(three.condition) > 1e15                  # numerically singular (the 4-plane design is rank-
    # deficient too, by the benign over-parameterisation of a smooth sensor, but keeps H³ apart)
    assert three.fit_error < 1e-6                         # perfect on the planes …
    r, c, _ = random_points(300, 5)
    for h, bound in ((0.0, 1e-6), (500.0, 1e-6), (1000.0, 1e-6), (250.0, None), (750.0, None)):
        X, Y = sensor.ground(r, c, h)
        pr, pc = project(three.rpc, X, Y, h)
        err = np.max(np.hypot(pr - r, pc - c))
        if bound:
            assert err < bound
        else:
            assert err > 1.0                               # … pixels off between them
    assert three.check_error > 1.0 and four.check_error < 1e-6
    # "auto" drops H³ when only three heights are given; four or more keep all 20 terms
    auto = fit_rpc(sensor.ground, SHAPE, (0.0, 1000.0), levels=3, step=200)
    assert auto.dropped == ("H**3",) and auto.unknowns == 37 and auto.check_error < 1e-3
    assert four.dropped == ()


def test_fit_reproduces_a_frame_camera_exactly():
    io = InteriorOrientation(f=100.0)
    eo = ExteriorOrientation(500.0, -300.0, 1500.0, 0.03, -0.02, 0.4, order="wak")
    shape, pixel = (800, 1000), 0.01

    def ground_of(rows, cols, heights):
        xy = np.stack(pixel_to_image(cols, rows, shape, pixel), axis=-1)
        XYZ = image_to_ground(xy.reshape(-1, 2), np.ravel(heights), eo, io)
        return XYZ[:, 0].reshape(np.shape(rows)), XYZ[:, 1].reshape(np.shape(rows))

    fit = fit_rpc(ground_of, shape, (0.0, 300.0), step=100)
    rng = np.random.default_rng(2)
    rpc = fit.rpc                                          # sample the footprint, project rigorously
    XYZ = np.column_stack([rpc.long_off + rpc.long_scale * rng.uniform(-0.8, 0.8, 300),
                           rpc.lat_off + rpc.lat_scale * rng.uniform(-0.8, 0.8, 300), rng.uniform(0, 300, 300)])
    col_row = image_to_pixel(collinearity(XYZ, eo, io), shape, pixel)
    inside = (col_row[:, 0] > 0) & (col_row[:, 0] < 999) & (col_row[:, 1] > 0) & (col_row[:, 1] < 799)
    assert inside.sum() > 50
    pr, pc = project(fit.rpc, XYZ[inside, 0], XYZ[inside, 1], XYZ[inside, 2])
    assert np.max(np.hypot(pr - col_row[inside, 1], pc - col_row[inside, 0])) < 1e-6


def test_fit_points_needs_39_points_and_two_heights(sensor):
    r, c, lon, lat, h = rpc_grid(sensor.ground, SHAPE, [0.0, 1000.0], step=1500)
    assert r.size == 70                                   # 5 rows × 7 columns × 2 planes
    with pytest.raises(DegenerateGeometryError, match="39 unknowns"):
        fit_rpc_points(r[:38], c[:38], lon[:38], lat[:38], h[:38])
    with pytest.raises(DegenerateGeometryError, match="height"):
        fit_rpc_points(r, c, lon, lat, np.zeros_like(h))


def test_rpc_grid_includes_the_last_row_and_column(sensor):
    r, c, *_ = rpc_grid(sensor.ground, (250, 301), [0.0], step=100)
    assert sorted(set(r)) == [0.0, 100.0, 200.0, 249.0] and sorted(set(c)) == [0.0, 100.0, 200.0, 300.0]


# ----------------------------------------------------------------------------- (8.6.1)–(8.6.4)
def synthetic_gcps(rpc, model, coeff_r, coeff_c, n, seed):
    """Measured points whose RPC coordinates are measured + δ(measured) (the sign of (8.6.1))."""
    rng = np.random.default_rng(seed)
    row, col, h = rng.uniform(100, 5900, n), rng.uniform(100, 7900, n), rng.uniform(0, 1000, n)
    x, y = (row - rpc.line_off) / rpc.line_scale, (col - rpc.samp_off) / rpc.samp_scale
    t = np.stack([np.ones(n), x, y, x * y, x * x, y * y], axis=1)[:, :len(coeff_r)]
    lon, lat = locate(rpc, row + t @ coeff_r, col + t @ coeff_c, h)
    return row, col, lon, lat, h


@pytest.mark.parametrize("model, coeff_r, coeff_c", [
    ("shift", [2.5], [-1.75]),
    ("affine", [2.5, 0.8, -0.3], [-1.75, 0.2, 0.6]),
    ("poly2", [2.5, 0.8, -0.3, 0.15, -0.2, 0.1], [-1.75, 0.2, 0.6, -0.1, 0.05, 0.3]),
])
def test_bias_compensation_recovers_a_known_correction_from_the_minimum_gcps(five_planes, model, coeff_r, coeff_c):
    rpc = five_planes.rpc
    need = {"shift": 1, "affine": 3, "poly2": 6}[model]
    row, col, lon, lat, h = synthetic_gcps(rpc, model, np.array(coeff_r), np.array(coeff_c), need + 20, 4)
    fixed = fit_bias(rpc, row[:need], col[:need], lon[:need], lat[:need], h[:need], model)
    np.testing.assert_allclose(fixed.line_coeff, coeff_r, atol=1e-7)
    np.testing.assert_allclose(fixed.samp_coeff, coeff_c, atol=1e-7)
    assert fixed.rms < 1e-7
    # at the other 20 points: projection and inverse with the correction hit the measurements
    pr, pc = project(fixed, lon[need:], lat[need:], h[need:])
    assert np.max(np.hypot(pr - row[need:], pc - col[need:])) < 1e-6
    lon2, lat2 = fixed.locate(row[need:], col[need:], h[need:])
    assert np.max(np.hypot(lon2 - lon[need:], lat2 - lat[need:])) < 1e-5
    # the uncorrected RPC misses them by about the bias
    ur, uc = project(rpc, lon[need:], lat[need:], h[need:])
    assert np.min(np.hypot(ur - row[need:], uc - col[need:])) > 0.5
    with pytest.raises(DegenerateGeometryError, match=f"at least {need} GCP"):
        fit_bias(rpc, row[:need - 1], col[:need - 1], lon[:need - 1], lat[:need - 1], h[:need - 1], model)


def test_bias_sign_is_rpc_minus_measured(five_planes):
    rpc = five_planes.rpc
    lon, lat = locate(rpc, 1000.0, 2000.0, 300.0)
    fixed = fit_bias(rpc, [997.0], [2004.0], [lon], [lat], [300.0], "shift")
    assert fixed.line_coeff == pytest.approx((3.0,), abs=1e-8)        # 1000 − 997
    assert fixed.samp_coeff == pytest.approx((-4.0,), abs=1e-8)       # 2000 − 2004


def test_bias_least_squares_with_redundant_noisy_gcps(five_planes):
    rpc = five_planes.rpc
    coeff_r, coeff_c = np.array([2.0, 0.5, -0.4]), np.array([-1.0, 0.3, 0.2])
    row, col, lon, lat, h = synthetic_gcps(rpc, "affine", coeff_r, coeff_c, 400, 8)
    rng = np.random.default_rng(9)
    noisy_r, noisy_c = row + rng.normal(0, 0.3, 400), col + rng.normal(0, 0.3, 400)
    fixed = fit_bias(rpc, noisy_r, noisy_c, lon, lat, h, "affine")
    # the residual RMS is the noise (√2 · 0.3 px total), the coefficients within a few σ/√n
    assert fixed.rms == pytest.approx(0.3 * np.sqrt(2), rel=0.1)
    np.testing.assert_allclose(fixed.line_coeff, coeff_r, atol=0.1)
    np.testing.assert_allclose(fixed.samp_coeff, coeff_c, atol=0.1)


def test_affine_bias_from_collinear_gcps_is_degenerate(five_planes):
    rpc = five_planes.rpc
    row = np.array([1000.0, 2000.0, 3000.0])
    col = 2 * row
    lon, lat = locate(rpc, row, col, 0.0)
    with pytest.raises(DegenerateGeometryError):
        fit_bias(rpc, row, col, lon, lat, np.zeros(3), "affine")


# ----------------------------------------------------------------------------- (8.8.9)
def test_intersection_jacobian_matches_sympy():
    sympy = pytest.importorskip("sympy")
    from test_rpc import random_rpc
    rpc = random_rpc(4, nonlinear=3e-2)
    lon, lat, h = sympy.symbols("lon lat h")
    L = (lon - rpc.long_off) / rpc.long_scale
    P = (lat - rpc.lat_off) / rpc.lat_scale
    H = (h - rpc.height_off) / rpc.height_scale
    t = [L ** 0, L, P, H, L * P, L * H, P * H, L ** 2, P ** 2, H ** 2, P * L * H, L ** 3, L * P ** 2, L * H ** 2,
         L ** 2 * P, P ** 3, P * H ** 2, L ** 2 * H, P ** 2 * H, H ** 3]       # (8.5.9) with X = L, Y = P, Z = H
    poly = lambda a: sum(sympy.Float(c) * m for c, m in zip(a, t))
    row = poly(rpc.line_num_coeff) / poly(rpc.line_den_coeff) * rpc.line_scale + rpc.line_off
    col = poly(rpc.samp_num_coeff) / poly(rpc.samp_den_coeff) * rpc.samp_scale + rpc.samp_off
    J = sympy.lambdify((lon, lat, h), sympy.Matrix([row, col]).jacobian([lon, lat, h]), "numpy")
    rng = np.random.default_rng(1)
    pts = np.column_stack([rng.uniform(5.25, 5.35, 6), rng.uniform(44.06, 44.14, 6), rng.uniform(300, 1700, 6)])
    _, _, ours = _rpc_eval(rpc, pts[:, 0], pts[:, 1], pts[:, 2])
    for k, p in enumerate(pts):
        np.testing.assert_allclose(ours[k], np.array(J(*p), dtype=float), rtol=1e-10, atol=1e-9)


def stereo_pair():
    """Fore- and aft-looking pushbrooms (pitch α = ±0.25 rad) over the same area, RPCs fitted on 5 planes."""
    x0 = 475e3 * np.tan(0.25)                              # both look at X ≈ 0 at the first line
    fore = Pushbroom(ncol=4000, eo0=(x0, 0, 475e3, 0.0, 0.25, 0.0), k=(7000, 0, 0, 1e-6, 0, 0))
    aft = Pushbroom(ncol=4000, eo0=(-x0, 0, 475e3, 0.0, -0.25, 0.0), k=(7000, 0, 0, -1e-6, 0, 0))
    return [fit_rpc(s.ground, (3000, 4000), (0.0, 1500.0), step=200).rpc for s in (fore, aft)]


def test_intersection_recovers_ground_points_from_a_synthetic_pair():
    left, right = stereo_pair()
    rng = np.random.default_rng(6)
    lon_l, lat_l = locate(left, rng.uniform(200, 2800, 40), rng.uniform(200, 3800, 40), 700.0)
    X, Y, Z = lon_l, lat_l, rng.uniform(0, 1500, 40)
    rows = np.stack([project(m, X, Y, Z)[0] for m in (left, right)])
    cols = np.stack([project(m, X, Y, Z)[1] for m in (left, right)])
    res = intersect_rpc([left, right], rows, cols)
    err = np.sqrt((res.lon - X) ** 2 + (res.lat - Y) ** 2 + (res.height - Z) ** 2)
    assert err.max() < 1e-6                               # metres: the pair's ground frame is metric
    assert res.rms.max() < 1e-8 and res.residuals.shape == (40, 2, 2)
    # with bias-corrected models: measured = RPC − δ; the same points are recovered
    fl = BiasCorrectedRPC(left, "shift", (1.5,), (-0.5,))
    fr = BiasCorrectedRPC(right, "affine", (0.5, 0.2, -0.1), (2.0, 0.0, 0.3))
    rows_b = np.stack([project(m, X, Y, Z)[0] for m in (fl, fr)])
    cols_b = np.stack([project(m, X, Y, Z)[1] for m in (fl, fr)])
    assert np.max(np.abs(rows_b - rows)) > 0.4
    res_b = intersect_rpc([fl, fr], rows_b, cols_b)
    assert np.max(np.sqrt((res_b.lon - X) ** 2 + (res_b.lat - Y) ** 2 + (res_b.height - Z) ** 2)) < 1e-6
    # along-track stereo: a 1 px line (x-parallax) error changes the height by about
    # GSD / (B/H) (B/H = 2 tan 0.25 ≈ 0.51 here) and leaves no residual; a 1 px sample error
    # (y-parallax) cannot be absorbed and shows in the residuals
    bad = rows.copy()
    bad[1, 0] += 1.0
    res_bad = intersect_rpc([left, right], bad, cols)
    assert 1.0 < abs(res_bad.height[0] - Z[0]) < 5.0 and res_bad.rms[0] < 1e-3
    bad = cols.copy()
    bad[1, 0] += 1.0
    res_bad = intersect_rpc([left, right], rows, bad)
    # least squares splits it ±0.5 px between the two images: RMS over 4 equations √(2·0.25/4)
    assert res_bad.rms[0] == pytest.approx(np.sqrt(0.125), abs=1e-3)


def test_intersection_of_identical_views_is_degenerate():
    left, _ = stereo_pair()
    with pytest.raises(DegenerateGeometryError, match="parallel"):
        intersect_rpc([left, left], [[1000.0], [1000.0]], [[2000.0], [2000.0]])


@pytest.fixture(scope="module")
def ventoux_pair():
    try:
        geoms = [datasets.data_path("satellite", "pleiades_ventoux", f"{s}_image.geom") for s in ("left", "right")]
    except datasets.DataUnavailableError as exc:
        pytest.skip(f"real data absent (../shared/data or PHOTOLIB_DATA): {exc}")
    # crop offsets (row, col) from the GeoTIFF transforms: left (5000, 5000), right (5162, 4915)
    return (RPC.from_ossim_geom(geoms[0]).shifted(5000, 5000), RPC.from_ossim_geom(geoms[1]).shifted(5162, 4915))


def test_intersection_on_the_real_ventoux_pair(ventoux_pair):
    left, right = ventoux_pair
    rng = np.random.default_rng(12)
    h = rng.uniform(400, 900, 200)
    lon, lat = locate(left, rng.uniform(0, 499, 200), rng.uniform(0, 499, 200), h)
    rows = np.stack([project(m, lon, lat, h)[0] for m in (left, right)])
    cols = np.stack([project(m, lon, lat, h)[1] for m in (left, right)])
    inside = np.all((rows > 0) & (rows < 494) & (cols > 0) & (cols < 497), axis=0)
    assert inside.sum() > 20                             # the crops overlap
    lon, lat, h, rows, cols = lon[inside], lat[inside], h[inside], rows[:, inside], cols[:, inside]
    res = intersect_rpc([left, right], rows, cols)
    metres = np.hypot((res.lon - lon) * 111320 * np.cos(np.radians(lat)), (res.lat - lat) * 110950)
    assert metres.max() < 1e-6 and np.max(np.abs(res.height - h)) < 1e-6
    # the pair's height sensitivity: a 1 px parallax error moves the height by the order of a GSD
    # divided by the base-to-height ratio (Pléiades ≈ 0.7 m GSD here)
    bad = rows.copy()
    bad[1] += 1.0
    dz = np.abs(intersect_rpc([left, right], bad, cols).height - h)
    assert 0.1 < np.median(dz) < 20


# ----------------------------------------------------------------------------- §8.18
# Kanopus-V-like focal plane (NOT from the book, which prints no parameters): f = 1797.5 mm,
# 1920 × 985-pixel matrices, 7.4 µm pixels (2.1 m GSD from 510 km); six matrices in two staggered
# rows 1500 px apart along track, 100 px across-track overlap.
def test_kanopus_micro_frames_combine_into_one_rpc():
    cam = microframe_camera()
    heights = (0.0, 2000.0)
    rpcs = [fit_rpc(cam.ground_of(i), cam.matrix_shape, heights, step=200).rpc for i in range(6)]
    combined = conventional_frame_rpc(rpcs, cam.offsets, [cam.matrix_shape] * 6, heights, step=200)
    assert combined.check_error < 0.01
    # against the rigorous micro-frame projection: ground points seen by each matrix
    rng = np.random.default_rng(3)
    for i, (r0, c0) in enumerate(cam.offsets):
        r, c, h = rng.uniform(0, 984, 50), rng.uniform(0, 1919, 50), rng.uniform(*heights, 50)
        X, Y = cam.ground_of(i)(r, c, h)
        row_col = cam.project(np.column_stack([X, Y, h]))
        np.testing.assert_allclose(row_col[:, 0] - r0, r, atol=1e-6)   # the rigorous model is consistent
        pr, pc = project(combined.rpc, X, Y, h)
        assert np.max(np.hypot(pr - row_col[:, 0], pc - row_col[:, 1])) < 0.01
