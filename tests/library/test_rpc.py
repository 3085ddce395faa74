"""RPC sensor model, Chapter 8 §8.5 (8.5.6)–(8.5.9), and its Newton inverse (8.18.1).

Expected values come from sympy (term order, partial derivatives), synthetic ground truth (an
affine camera and a seeded nonlinear RPC), scipy's root finder, and GDAL's RPC transformer
through rasterio on the real Pléiades Ventoux model.
"""

import numpy as np
import pytest

from photolib import datasets
from photolib.rpc import RPC, RPC00B_TERMS, _terms, _terms_dH, _terms_dL, _terms_dP, locate, project

# The book's (8.5.8), transcribed: a1 + a2 X + a3 Y + a4 Z + a5 XY + a6 XZ + a7 YZ + a8 X² + a9 Y²
# + a10 Z² + a11 XYZ + a12 X³ + a13 XY² + a14 XZ² + a15 X²Y + a16 Y³ + a17 YZ² + a18 X²Z + a19 Y²Z + a20 Z³
BOOK_8_5_8 = ["1", "X", "Y", "Z", "X*Y", "X*Z", "Y*Z", "X**2", "Y**2", "Z**2", "X*Y*Z", "X**3",
              "X*Y**2", "X*Z**2", "X**2*Y", "Y**3", "Y*Z**2", "X**2*Z", "Y**2*Z", "Z**3"]


def unit(k):
    return [0.0] * k + [1.0] + [0.0] * (19 - k)


def random_rpc(seed=0, nonlinear=1e-3):
    """A seeded RPC: a dominant linear part plus small higher-order and denominator terms."""
    rng = np.random.default_rng(seed)
    line_num = np.r_[0.01, 0.05, -1.0, 0.03, nonlinear * rng.standard_normal(16)]
    samp_num = np.r_[-0.02, 1.0, 0.04, -0.02, nonlinear * rng.standard_normal(16)]
    line_den = np.r_[1.0, nonlinear * rng.standard_normal(19)]
    samp_den = np.r_[1.0, nonlinear * rng.standard_normal(19)]
    return RPC(line_off=5000.5, samp_off=4800.25, lat_off=44.1, long_off=5.3, height_off=1000.0,
               line_scale=5000.0, samp_scale=4800.0, lat_scale=0.05, long_scale=0.07, height_scale=900.0,
               line_num_coeff=line_num, line_den_coeff=line_den,
               samp_num_coeff=samp_num, samp_den_coeff=samp_den)


# ----------------------------------------------------------------------------- term order
def test_term_order_is_the_books_8_5_8_and_rpc00b():
    sympy = pytest.importorskip("sympy")
    L, P, H = sympy.symbols("L P H")
    book = [sympy.sympify(t).subs({"X": L, "Y": P, "Z": H}) for t in BOOK_8_5_8]
    ours = [sympy.sympify(t, locals={"L": L, "P": P, "H": H}) for t in RPC00B_TERMS]
    assert [sympy.expand(a - b) for a, b in zip(book, ours)] == [0] * 20
    rng = np.random.default_rng(1)
    vals = rng.uniform(-1.2, 1.2, (3, 7))
    for k, term in enumerate(book):
        f = sympy.lambdify((L, P, H), term, "numpy")
        fl = sympy.lambdify((L, P, H), sympy.diff(term, L), "numpy")
        fp = sympy.lambdify((L, P, H), sympy.diff(term, P), "numpy")
        fh = sympy.lambdify((L, P, H), sympy.diff(term, H), "numpy")
        np.testing.assert_allclose(_terms(*vals)[:, k], np.broadcast_to(f(*vals), (7,)), rtol=0, atol=1e-15)
        np.testing.assert_allclose(_terms_dL(*vals)[:, k], np.broadcast_to(fl(*vals), (7,)), rtol=0, atol=1e-15)
        np.testing.assert_allclose(_terms_dP(*vals)[:, k], np.broadcast_to(fp(*vals), (7,)), rtol=0, atol=1e-15)
        np.testing.assert_allclose(_terms_dH(*vals)[:, k], np.broadcast_to(fh(*vals), (7,)), rtol=0, atol=1e-15)


# ----------------------------------------------------------------------------- synthetic
def affine_camera(lon, lat, h):
    """A simple affine camera (pixels) — the synthetic ground truth."""
    row = 1200.0 - 9000.0 * (lat - 44.1) + 1500.0 * (lon - 5.3) + 0.12 * (h - 800.0)
    col = 900.0 + 8000.0 * (lon - 5.3) + 700.0 * (lat - 44.1) - 0.05 * (h - 800.0)
    return row, col


def fit_affine_rpc():
    """Fit the RPC numerators (denominators 1) to the affine camera on a 9 × 9 × 5 grid."""
    off = dict(lat_off=44.1, long_off=5.3, height_off=800.0, lat_scale=0.1, long_scale=0.1, height_scale=600.0,
               line_off=1200.0, samp_off=900.0, line_scale=1000.0, samp_scale=900.0)
    g = np.linspace(-1, 1, 9)
    L, P, H = np.meshgrid(g, g, np.linspace(-1, 1, 5), indexing="ij")
    lon, lat, h = (L * off["long_scale"] + off["long_off"], P * off["lat_scale"] + off["lat_off"],
                   H * off["height_scale"] + off["height_off"])
    row, col = affine_camera(lon, lat, h)
    A = _terms(L.ravel(), P.ravel(), H.ravel())
    line_num = np.linalg.lstsq(A, (row.ravel() - off["line_off"]) / off["line_scale"], rcond=None)[0]
    samp_num = np.linalg.lstsq(A, (col.ravel() - off["samp_off"]) / off["samp_scale"], rcond=None)[0]
    return RPC(**off, line_num_coeff=line_num, line_den_coeff=unit(0),
               samp_num_coeff=samp_num, samp_den_coeff=unit(0))


def test_affine_camera_fitted_rpc_reproduces_it_and_round_trips():
    rpc = fit_affine_rpc()
    rng = np.random.default_rng(7)
    lon = rng.uniform(5.21, 5.39, 200)
    lat = rng.uniform(44.01, 44.19, 200)
    h = rng.uniform(250.0, 1350.0, 200)                  # between and beyond the grid's planes
    row, col = project(rpc, lon, lat, h)
    true_row, true_col = affine_camera(lon, lat, h)
    assert np.max(np.hypot(row - true_row, col - true_col)) < 1e-6
    lon2, lat2 = locate(rpc, row, col, h)
    row2, col2 = project(rpc, lon2, lat2, h)
    assert np.max(np.hypot(row2 - row, col2 - col)) < 1e-6
    # the affine camera's own inverse at the same heights
    t_row, t_col = affine_camera(lon2, lat2, h)
    assert np.max(np.hypot(t_row - row, t_col - col)) < 1e-6


def test_nonlinear_rpc_inverse_matches_scipy_root():
    optimize = pytest.importorskip("scipy.optimize")
    rpc = random_rpc(3, nonlinear=2e-2)
    rng = np.random.default_rng(11)
    rows = rng.uniform(0, 10000, 25)
    cols = rng.uniform(0, 9600, 25)
    hs = rng.uniform(100, 1900, 25)
    lon, lat = locate(rpc, rows, cols, hs)
    back = np.hypot(*(np.subtract(project(rpc, lon, lat, hs), (rows, cols))))
    assert back.max() < 1e-6
    for i in range(5):
        def f(x):
            r, c = project(rpc, x[0], x[1], hs[i])
            return [float(r) - rows[i], float(c) - cols[i]]
        sol = optimize.root(f, [rpc.long_off, rpc.lat_off], method="lm", options={"xtol": 1e-15, "ftol": 1e-15})
        assert np.hypot(*f(sol.x)) < 1e-6                # scipy's own solution is a true root
        # 1e-9 degrees ≈ 0.1 mm on the ground
        np.testing.assert_allclose([lon[i], lat[i]], sol.x, rtol=0, atol=1e-9)


def test_shapes_broadcast_and_scalars():
    rpc = random_rpc()
    row, col = project(rpc, 5.3, 44.1, 1000.0)
    assert row.shape == () and col.shape == ()
    row, col = project(rpc, np.full((2, 3), 5.3), np.full((2, 3), 44.1), [0.0, 500.0, 1000.0])
    assert row.shape == (2, 3)
    lon, lat = locate(rpc, row, col, [0.0, 500.0, 1000.0])
    np.testing.assert_allclose(lon, 5.3, atol=1e-12)
    np.testing.assert_allclose(lat, 44.1, atol=1e-12)
    empty = project(rpc, [], [], [])
    assert empty[0].shape == (0,)
    assert locate(rpc, [], [], [])[0].shape == (0,)


def test_shifted_moves_image_coordinates_by_the_crop_offset():
    rpc = random_rpc()
    crop = rpc.shifted(5000, 4000)
    lon, lat, h = np.array([5.31, 5.28]), np.array([44.12, 44.09]), np.array([300.0, 1500.0])
    r, c = project(rpc, lon, lat, h)
    rc, cc = project(crop, lon, lat, h)
    np.testing.assert_allclose(rc, r - 5000, atol=1e-9)
    np.testing.assert_allclose(cc, c - 4000, atol=1e-9)
    assert crop.shifted(-5000, -4000) == rpc
    assert rpc.line_off == 5000.5                         # frozen: the original is unchanged


def test_gdal_metadata_and_ossim_round_trip_exactly(tmp_path):
    rpc = random_rpc(5)
    md = rpc.to_gdal_metadata()
    assert set(md) == {"LINE_OFF", "SAMP_OFF", "LAT_OFF", "LONG_OFF", "HEIGHT_OFF", "LINE_SCALE", "SAMP_SCALE",
                       "LAT_SCALE", "LONG_SCALE", "HEIGHT_SCALE", "LINE_NUM_COEFF", "LINE_DEN_COEFF",
                       "SAMP_NUM_COEFF", "SAMP_DEN_COEFF"}
    assert all(isinstance(v, str) for v in md.values())
    assert len(md["SAMP_DEN_COEFF"].split()) == 20
    assert RPC.from_gdal_metadata(md) == rpc
    assert RPC.from_gdal_metadata({k.lower(): v for k, v in md.items()}) == rpc
    # OSSIM keyword list, with a prefix as in a multi-image .geom
    lines = ["image0.type:  ossimRpcModel", "image0.polynomial_format:  B"]
    lines += [f"image0.{k.lower()}:  {v}" for k, v in md.items() if "COEFF" not in k]
    for key in ("LINE_NUM_COEFF", "LINE_DEN_COEFF", "SAMP_NUM_COEFF", "SAMP_DEN_COEFF"):
        lines += [f"image0.{key.lower()}_{i:02d}:  {v}" for i, v in enumerate(md[key].split())]
    path = tmp_path / "x.geom"
    path.write_text("\n".join(lines))
    assert RPC.from_ossim_geom(path) == rpc


# ----------------------------------------------------------------------------- real data
@pytest.fixture(scope="module")
def ventoux():
    try:
        geom = datasets.data_path("satellite", "pleiades_ventoux", "left_image.geom")
        tif = datasets.data_path("satellite", "pleiades_ventoux", "left_image.tif")
    except datasets.DataUnavailableError as exc:
        pytest.skip(f"real data absent (../shared/data or PHOTOLIB_DATA): {exc}")
    return RPC.from_ossim_geom(geom), tif


def ventoux_grid(rpc):
    g = np.linspace(-0.9, 0.9, 9)
    L, P, H = np.meshgrid(g, g, np.linspace(-0.8, 0.9, 4), indexing="ij")   # heights ≈ 370–1870 m
    return (L.ravel() * rpc.long_scale + rpc.long_off, P.ravel() * rpc.lat_scale + rpc.lat_off,
            H.ravel() * rpc.height_scale + rpc.height_off)


def test_ventoux_geom_is_read(ventoux):
    rpc, _ = ventoux
    assert (rpc.line_off, rpc.samp_off, rpc.height_off, rpc.height_scale) == (21109.5, 19207.5, 1075.0, 885.0)
    assert rpc.line_num_coeff[2] == pytest.approx(-1.03205102244059, abs=0)
    assert rpc.samp_den_coeff[0] == 1.0


def test_ventoux_project_agrees_with_gdal(ventoux):
    rasterio_rpc = pytest.importorskip("rasterio.rpc")
    transform = pytest.importorskip("rasterio.transform")
    rpc, _ = ventoux
    gdal_rpc = rasterio_rpc.RPC.from_gdal(rpc.to_gdal_metadata())
    assert RPC.from_gdal_metadata(gdal_rpc.to_gdal()) == rpc            # rasterio reads what we write
    lon, lat, h = ventoux_grid(rpc)
    row, col = project(rpc, lon, lat, h)
    with transform.RPCTransformer(gdal_rpc) as t:
        g_row, g_col = t.rowcol(lon, lat, h, op=lambda x: x)
    # GDAL reports pixel-corner coordinates (the RPC's (0, 0) is a pixel centre): ours + 0.5
    err = np.hypot(np.asarray(g_row) - 0.5 - row, np.asarray(g_col) - 0.5 - col)
    assert err.max() < 1e-6, err.max()


def test_ventoux_locate_round_trip_and_gdal_inverse(ventoux):
    transform = pytest.importorskip("rasterio.transform")
    rasterio_rpc = pytest.importorskip("rasterio.rpc")
    rpc, _ = ventoux
    lon, lat, h = ventoux_grid(rpc)
    row, col = project(rpc, lon, lat, h)
    lon2, lat2 = locate(rpc, row, col, h)
    row2, col2 = project(rpc, lon2, lat2, h)
    assert np.max(np.hypot(row2 - row, col2 - col)) < 1e-6
    assert np.max(np.abs(lon2 - lon)) < 1e-10 and np.max(np.abs(lat2 - lat)) < 1e-10
    # GDAL's own iterative inverse stops once its last step is below its default threshold of
    # 0.1 px per axis (RPC_PIXEL_ERROR_THRESHOLD); its residual is of that order, ours 1e-6 px
    with transform.RPCTransformer(rasterio_rpc.RPC.from_gdal(rpc.to_gdal_metadata())) as t:
        g_lon, g_lat = t.xy(row + 0.5, col + 0.5, h, offset="ul")
    g_row, g_col = project(rpc, np.asarray(g_lon), np.asarray(g_lat), h)
    assert max(np.max(np.abs(g_row - row)), np.max(np.abs(g_col - col))) < 0.1


def test_ventoux_crop_rpc_from_the_geotiff_transform(ventoux):
    rasterio = pytest.importorskip("rasterio")
    rpc, tif = ventoux
    with rasterio.open(tif) as src:
        col0, row0, shape = src.transform.c, src.transform.f, src.shape
    assert (row0, col0) == (5000.0, 5000.0)
    crop = rpc.shifted(row0, col0)
    # the crop's centre pixel seen at the RPC's mean height lies at the centre of the crop
    lon, lat = locate(rpc, row0 + shape[0] / 2, col0 + shape[1] / 2, rpc.height_off)
    r, c = project(crop, lon, lat, rpc.height_off)
    np.testing.assert_allclose([r, c], [shape[0] / 2, shape[1] / 2], atol=1e-6)


def test_project_and_locate_dispatch_bias_corrected_models():
    from photolib.rpc import BiasCorrectedRPC
    rpc = random_rpc(2)
    fixed = BiasCorrectedRPC(rpc, "affine", (1.0, 0.2, -0.1), (-2.0, 0.05, 0.3))
    lon, lat, h = np.array([5.31, 5.28]), np.array([44.12, 44.09]), np.array([300.0, 1500.0])
    r, c = project(fixed, lon, lat, h)
    r0, c0 = project(rpc, lon, lat, h)
    dr, dc = fixed.correction(r, c)
    np.testing.assert_allclose(r + dr, r0, atol=1e-9)     # (8.6.1): x + δx = P1/P2
    np.testing.assert_allclose(c + dc, c0, atol=1e-9)
    lon2, lat2 = locate(fixed, r, c, h)
    np.testing.assert_allclose([lon2, lat2], [lon, lat], atol=1e-10)


def test_numba_kernel_matches_the_numpy_iteration():
    import photolib.rpc as rpcmod
    rpc = random_rpc(3, nonlinear=2e-2)
    rng = np.random.default_rng(21)
    rows, cols, hs = rng.uniform(0, 10000, 3000), rng.uniform(0, 9600, 3000), rng.uniform(100, 1900, 3000)
    assert rows.size >= rpcmod._KERNEL_FROM
    lon, lat = locate(rpc, rows, cols, hs)                        # the kernel
    r = (rows - rpc.line_off) / rpc.line_scale
    c = (cols - rpc.samp_off) / rpc.samp_scale
    H = (hs - rpc.height_off) / rpc.height_scale
    L, P = rpcmod._locate_numpy(rpc, r, c, H, 1e-9, 30, 3.0)     # the vectorised loop
    np.testing.assert_allclose(lon, L * rpc.long_scale + rpc.long_off, rtol=0, atol=1e-11)
    np.testing.assert_allclose(lat, P * rpc.lat_scale + rpc.lat_off, rtol=0, atol=1e-11)
    back = np.hypot(*(np.subtract(project(rpc, lon, lat, hs), (rows, cols))))
    assert back.max() < 1e-6


def test_numba_kernel_reports_the_same_errors():
    from photolib.errors import ConvergenceError, DegenerateGeometryError
    from test_bad_input_rpc import CUBIC, DIVERGE, NO_LAT
    many = np.full(1500, 1.0)
    with pytest.raises(DegenerateGeometryError, match="singular"):
        locate(NO_LAT, 100.0 * many, 200.0 * many, 0.0 * many)
    with pytest.raises(ConvergenceError, match="did not reach") as info:
        locate(CUBIC, 200.0 * many, 200.0 * many, 0.0 * many, max_iterations=2)
    assert len(info.value.history) == 3 and info.value.history[-1] > 1e-9
    with pytest.raises((ConvergenceError, DegenerateGeometryError)):
        locate(DIVERGE, 140.0 * many, 200.0 * many, 0.0 * many)
