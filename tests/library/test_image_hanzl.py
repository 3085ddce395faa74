"""Hanzl §8–§10.1 through the library: filters (correlation, border, rounding), median, gradient
filters, 1-D edge enhancement, NCC, LS shift, quadratic correlation peak, Förstner size/roundness and
Hanzl's selection rule, pyramids, bilinear coefficients, normalised images.

Truth: scipy.ndimage (independent filters), numpy (corrcoef, eigenvalues), synthetic ground truth,
and photolib.epipolar.rectify_pair for the normalised image."""

import numpy as np
import pytest
from scipy import ndimage as ndi

from photolib import digital, features as ft, matching
from photolib.camera import ExteriorOrientation, InteriorOrientation
from photolib.epipolar import pyramid, rectify_pair
from photolib.errors import DegenerateGeometryError

_SCIPY_MODE = {"nearest": "nearest", "constant": "constant", "mirror": "mirror", "reflect": "reflect"}


@pytest.mark.parametrize("border", sorted(_SCIPY_MODE))
@pytest.mark.parametrize("name", sorted(ft.HANZL_KERNELS))
def test_filter_is_correlation_like_scipy(border, name):
    rng = np.random.default_rng(1)
    img = rng.integers(0, 255, size=(9, 11)).astype(float)
    K = ft.HANZL_KERNELS[name]
    origin = [-1 if n % 2 == 0 else 0 for n in K.shape]      # even kernels anchored at the top-left element
    expected = ndi.correlate(img, K, mode=_SCIPY_MODE[border], cval=7.0, origin=origin)
    got = ft.filter_image(img, K, border=border, cval=7.0)
    assert np.allclose(got, expected, atol=1e-9)


def test_filter_is_not_convolution_for_asymmetric_kernels():
    img = np.zeros((7, 7)); img[:, 4:] = 10.0
    corr = ft.filter_image(img, "sobel_1")
    conv = ndi.convolve(img, ft.HANZL_KERNELS["sobel_1"], mode="nearest")
    assert np.allclose(corr, -conv)
    assert corr[3, 3] == -40.0            # Hanzl's Sobel x kernel [1 0 −1] is negative on a rising edge


def test_rounding_rules():
    img = np.array([[0.0, 0.0, 0.0], [0.0, 4.5, 0.0], [0.0, 0.0, 0.0]])
    k = np.zeros((3, 3)); k[1, 1] = 1.0
    assert ft.filter_image(img, k, rounding="half-up")[1, 1] == 5.0
    assert ft.filter_image(img, k, rounding="half-even")[1, 1] == 4.0


def _e6():
    g = np.full((5, 5), 2.0)
    g[1, 1], g[1, 3], g[2, 3], g[3, 2], g[3, 3] = 1, 3, 9, 4, 1
    return g


def test_book_matrices_e5_to_e8():
    a = np.ones((5, 5)); np.fill_diagonal(a, 3.0)
    e5 = ft.filter_image(a, "sharpen", border="constant", cval=1.0)
    assert np.array_equal(e5, e5.T)                         # symmetric input and kernel: symmetric output
    assert e5[3, 4] == -3.0                                 # the book prints 1 (erratum)
    e6 = ft.filter_image(_e6(), "mean", border="nearest", rounding="half-up")
    book6 = np.array([[2] * 5, [2, 2, 3, 3, 3], [2, 2, 3, 3, 3], [2, 2, 3, 3, 3], [2] * 5])
    assert np.array_equal(e6, book6)
    c = np.ones((5, 5)); np.fill_diagonal(c, 4.0)
    e7 = ft.filter_image(c, "mean", border="constant", cval=1.0, rounding="half-up")
    assert np.array_equal(e7, np.floor(ndi.correlate(c, np.full((3, 3), 1 / 9), mode="constant", cval=1.0) + 0.5))
    assert e7[0, 0] == 2.0 and ft.filter_image(c, "mean", border="nearest", rounding="half-up")[0, 0] == 3.0
    e8 = ft.median_filter(_e6())
    assert np.all(e8 == 2.0)                                # the book prints 3 at (1, 4) (erratum)


@pytest.mark.parametrize("border", sorted(_SCIPY_MODE))
def test_median_like_scipy(border):
    img = np.random.default_rng(2).integers(0, 50, size=(8, 9)).astype(float)
    for size in (3, 5):
        assert np.array_equal(ft.median_filter(img, size, border, cval=3.0),
                              ndi.median_filter(img, size, mode=_SCIPY_MODE[border], cval=3.0))


def test_edge_filter_sum_and_max():
    img = np.random.default_rng(3).random((6, 7))
    s = ft.edge_filter(img, "sobel")
    g1 = ndi.correlate(img, ft.HANZL_KERNELS["sobel_1"], mode="nearest")
    g2 = ndi.correlate(img, ft.HANZL_KERNELS["sobel_2"], mode="nearest")
    assert np.allclose(s, np.abs(g1) + np.abs(g2))
    r = ft.edge_filter(img, "roberts")
    r1 = ndi.correlate(img, ft.HANZL_KERNELS["roberts_1"], mode="nearest", origin=-1)
    r2 = ndi.correlate(img, ft.HANZL_KERNELS["roberts_2"], mode="nearest", origin=-1)
    assert np.allclose(r, np.maximum(np.abs(r1), np.abs(r2)))


def test_second_difference_equals_sharpening_in_2d():
    g = np.array([5, 5, 5, 6, 8, 10, 12, 14, 15, 14], float)
    d2, e = ft.second_difference_1d(g)
    assert np.allclose(d2[1:-1], np.convolve(g, [1, -2, 1], mode="valid"))
    assert e[-1] == g[-1] and e[0] == g[0]
    assert e.max() - e.min() == 13 and g.max() - g.min() == 10       # the contrast 10 → 13 of the text
    img = np.random.default_rng(4).random((6, 6))
    assert np.allclose(ft.filter_image(img, "sharpen"), img - ft.filter_image(img, "laplace"))


def test_ncc_equals_numpy_corrcoef():
    rng = np.random.default_rng(5)
    a, b = rng.random((9, 9)), rng.random((9, 9))
    b = 0.6 * a + 0.4 * b
    assert matching.correlation_coefficient(a, b) == pytest.approx(np.corrcoef(a.ravel(), b.ravel())[0, 1], abs=1e-12)


def _texture(x, y):
    return (100 + 30 * np.sin(0.45 * x + 0.2 * y) + 25 * np.cos(0.31 * y - 0.15 * x)
            + 15 * np.sin(0.23 * x) * np.cos(0.37 * y))


def test_ls_shift_recovers_synthetic_subpixel_shift():
    dx, dy = 0.37, -0.22                                     # g_s(x, y) = g_r(x + dx, y + dy)
    yy, xx = np.mgrid[0:64, 0:64].astype(float)
    g_r, g_s = _texture(xx, yy), _texture(xx + dx, yy + dy)
    r = matching.lsm_shift(g_r, g_s, (32, 32), half_window=10)
    assert r.p == pytest.approx(dx, abs=0.01) and r.q == pytest.approx(dy, abs=0.01)
    assert r.sigma_p < 0.05 and r.sigma_q < 0.05


def test_quadratic_peak_exact_on_quadratics():
    rng = np.random.default_rng(6)
    X, Y = np.meshgrid([-1.0, 0.0, 1.0], [-1.0, 0.0, 1.0])
    for _ in range(20):
        x0, y0 = rng.uniform(-0.5, 0.5, 2)
        L = rng.normal(size=(2, 2))
        H = -(L @ L.T + 0.2 * np.eye(2))                     # negative definite
        d = np.stack([X - x0, Y - y0])
        r = 0.8 + 0.5 * np.einsum("i...,ij,j...->...", d, H, d)
        peak, _ = matching.quadratic_peak(r)
        assert np.allclose(peak, [x0, y0], atol=1e-10)


def test_quadratic_peak_on_correlation_surface_of_shifted_texture():
    yy, xx = np.mgrid[0:40, 0:40].astype(float)
    left, right = _texture(xx, yy), _texture(xx - 0.3, yy + 0.2)          # content moved by (+0.3, −0.2)
    R = matching.correlation_surface(left[15:26, 15:26], right[10:31, 10:31])
    i, j = np.unravel_index(np.argmax(R), R.shape)
    peak, _ = matching.quadratic_peak(R[i - 1:i + 2, j - 1:j + 2])
    # the correlation surface is only approximately quadratic over 3×3: sub-pixel to ~0.1 px (the integer
    # match is off by 0.3 / 0.2 px)
    assert j + peak[0] - 5 == pytest.approx(0.3, abs=0.1) and i + peak[1] - 5 == pytest.approx(-0.2, abs=0.1)


def test_quadratic_peak_rejects_saddle():
    X, Y = np.meshgrid([-1.0, 0.0, 1.0], [-1.0, 0.0, 1.0])
    with pytest.raises(DegenerateGeometryError):
        matching.quadratic_peak(X ** 2 - Y ** 2)


def test_foerstner_size_and_roundness_from_eigenvalues():
    img = np.zeros((21, 21)); img[6:15, 6:15] = 50.0
    img += np.random.default_rng(7).normal(0, 1, img.shape)
    size, q = ft.foerstner(img, window=7, form="size")
    w, q2 = ft.foerstner(img, window=7)
    assert np.allclose(q, q2)
    gx, gy = ft.gradient_backward(img, border="mirror")
    for r, c in [(6, 6), (10, 6), (10, 10)]:
        s = (slice(r - 3, r + 4), slice(c - 3, c + 4))
        N = np.array([[np.sum(gx[s] ** 2), np.sum(gx[s] * gy[s])], [np.sum(gx[s] * gy[s]), np.sum(gy[s] ** 2)]])
        lam = np.linalg.eigvalsh(np.linalg.inv(N))               # semi-axes² of the error ellipse
        assert size[r, c] == pytest.approx(lam.sum(), rel=1e-9)
        assert q[r, c] == pytest.approx(1 - ((lam[1] - lam[0]) / (lam[1] + lam[0])) ** 2, rel=1e-9)
        assert size[r, c] * w[r, c] == pytest.approx(1.0, rel=1e-12)


def test_hanzl_selection_picks_corners_not_edges():
    img = np.zeros((40, 40)); img[10:30, 10:30] = 100.0
    img = ndi.gaussian_filter(img, 1.0) + np.random.default_rng(8).normal(0, 0.5, img.shape)
    pts = ft.interest_points(img, "foerstner", size=7, relative=0.0, selection="hanzl", window=7)
    assert len(pts) >= 4
    corners = np.array([[10, 10], [10, 29], [29, 10], [29, 29]], float)
    d = np.linalg.norm(pts[:, None, :] - corners[None], axis=2).min(axis=1)
    assert np.all(d <= 3.0)                                      # every point at a corner, none on the edges
    assert np.all(np.linalg.norm(corners[:, None] - pts[None], axis=2).min(axis=1) <= 3.0)


def test_pyramid_sizes_and_mean():
    img = np.random.default_rng(9).random((256, 256))
    levels = pyramid(img, 5)
    assert [lv.shape[0] for lv in levels] == [256, 128, 64, 32, 16, 8]
    assert levels[-1].mean() == pytest.approx(img.mean(), rel=1e-12)


def test_bilinear_coefficients_of_hanzl():
    img = np.array([[3.0, 7.0], [2.0, 11.0]])                # g1 = (0,0), g2 = (d,0), g3 = (0,d), g4 = (d,d); d = 1 px
    g1, g2, g3, g4 = img[0, 0], img[0, 1], img[1, 0], img[1, 1]
    a0, a1, a2, a3 = g1, g2 - g1, g3 - g1, g1 - g2 - g3 + g4
    for X, Y in [(0.0, 0.0), (0.3, 0.8), (1.0, 1.0), (0.5, 0.25)]:
        assert digital.bilinear(img, 0.5 + X, 0.5 + Y) == pytest.approx(a0 + a1 * X + a2 * Y + a3 * X * Y)


def test_normalized_coordinates_match_rectify_pair():
    io = InteriorOrientation(50.0)
    e1 = ExteriorOrientation(0, 0, 500, 0.01, -0.02, 0.03)
    e2 = ExteriorOrientation(100, 5, 502, -0.02, 0.01, 0.0)
    img = np.random.default_rng(0).random((40, 60))
    d = 0.1
    rp = rectify_pair(img, img, io, e1, e2, d)
    h, w = img.shape
    pix = np.array([[5.0, 7.0], [30.0, 20.0], [50.0, 33.0]])
    for k, eo in enumerate((e1, e2)):
        mm = np.column_stack([d * pix[:, 0] - (w - 1) / 2 * d, -d * pix[:, 1] + (h - 1) / 2 * d])
        xn = digital.normalized_image_coordinates(mm, 50.0, eo.matrix, rp.rotation)
        rect = rp.to_rectified(pix, k)
        expect = np.column_stack([d * rect[:, 0] - (w - 1) / 2 * d + rp.x_offset[k],
                                  -d * rect[:, 1] + (h - 1) / 2 * d + rp.y_offset])
        assert np.allclose(xn, expect, atol=1e-9)


def test_normalized_coordinates_object_ray_preserved():
    rng = np.random.default_rng(10)
    from photolib.rotation import rotation_matrix
    R = rotation_matrix(0.05, -0.03, 0.2, order="wak")
    Rn = rotation_matrix(0.0, 0.0, 0.1, order="wak")
    xy = rng.uniform(-50, 50, (5, 2))
    xn = digital.normalized_image_coordinates(xy, 100.0, R, Rn, c_n=120.0)
    a = np.column_stack([xy, np.full(5, -100.0)]) @ R.T
    b = np.column_stack([xn, np.full(5, -120.0)]) @ Rn.T
    assert np.allclose(np.cross(a, b), 0.0, atol=1e-9) and np.all(np.sum(a * b, axis=1) > 0)
