"""§1.10 digital image coordinates and bilinear resampling (photolib.digital).

Book numbers are checked through textbook/ by test_textbook.py; here: identities, independent
implementations (scipy.ndimage.map_coordinates, OpenCV remap) and bad input.
"""

import cv2
import numpy as np
import pytest
from hypothesis import given, settings, strategies as st
from scipy.ndimage import map_coordinates

from photolib import digital
from photolib.errors import InputError


def test_pixel_center_both_origins():
    # (1.10.1): half-integers; (1.10.4): integers — the two systems differ by half a pixel
    i, j = np.arange(6), np.arange(6)[::-1]
    xc, yc = digital.pixel_center(i, j, "corner")
    x0, y0 = digital.pixel_center(i, j, "center")
    np.testing.assert_array_equal(xc - x0, 0.5)
    np.testing.assert_array_equal(yc - y0, 0.5)
    np.testing.assert_array_equal(x0, j)
    assert digital.pixel_center(4, 3) == (3.5, 4.5)


@given(i=st.integers(0, 500), j=st.integers(0, 500), n=st.integers(1, 20), data=st.data())
@settings(max_examples=60, deadline=None)
def test_subpixel_identities(i, j, n, data):
    ii, jj = data.draw(st.integers(0, n - 1)), data.draw(st.integers(0, n - 1))
    x, y = digital.subpixel_coordinates(i, j, ii, jj, n, "corner")
    # the sub-element lies inside its pixel [j, j+1) × [i, i+1)
    assert j < x < j + 1 and i < y < i + 1
    # n = 1 (or the central element of an odd n) is the pixel centre
    xm, ym = digital.subpixel_coordinates(i, j, (n - 1) // 2, (n - 1) // 2, n)
    if n % 2 == 1:
        assert (xm, ym) == pytest.approx(digital.pixel_center(i, j))
    # (1.10.5) is (1.10.2) moved by half a pixel
    xc, yc = digital.subpixel_coordinates(i, j, ii, jj, n, "center")
    assert (x - xc, y - yc) == pytest.approx((0.5, 0.5), abs=1e-12)
    # a magnification of k·n with the block of k×k sub-elements averages to the n coordinate
    k = 3
    sub = [digital.subpixel_coordinates(i, j, ii * k + a, jj * k + b, n * k) for a in range(k) for b in range(k)]
    assert np.mean(sub, axis=0) == pytest.approx((x, y), abs=1e-12)


def test_pixel_to_physical_is_linear():
    rng = np.random.default_rng(1)
    x, y = rng.uniform(0, 1000, (2, 20))
    xc, yc = digital.pixel_to_physical(x, y, 12.5)
    np.testing.assert_allclose(xc, 12.5 * x)
    back = digital.pixel_to_physical(xc, yc, 1 / 12.5)
    np.testing.assert_allclose(back, (x, y))


@given(n=st.integers(1, 5000), data=st.data())
def test_flip_rows_involution(n, data):
    i = data.draw(st.integers(0, n - 1))
    assert digital.flip_rows(digital.flip_rows(i, n), n) == i
    assert digital.flip_rows(0, n) == n - 1


def test_flip_rows_and_flip_y_agree():
    n = 7
    i_top = np.arange(n)
    i_bottom = digital.flip_rows(i_top, n)
    for origin in ("corner", "center"):
        _, y_top = digital.pixel_center(i_top, 0, origin)
        _, y_bottom = digital.pixel_center(i_bottom, 0, origin)
        np.testing.assert_allclose(digital.flip_y(y_top, n, origin), y_bottom)
        np.testing.assert_allclose(digital.flip_y(digital.flip_y(y_top, n, origin), n, origin), y_top)


def _raster_positions(rng, h, w, m):
    return rng.uniform(0.5, w - 0.5, m), rng.uniform(0.5, h - 0.5, m)


def test_bilinear_reproduces_linear_ramp():
    rng = np.random.default_rng(2)
    h, w = 9, 13
    a, b, c = rng.normal(size=3)
    yy, xx = np.mgrid[0:h, 0:w] + 0.5                # pixel centres, raster system
    img = a + b * xx + c * yy
    x, y = _raster_positions(rng, h, w, 500)
    np.testing.assert_allclose(digital.bilinear(img, x, y), a + b * x + c * y, atol=1e-12)
    # the corners of the hull are reachable
    assert digital.bilinear(img, w - 0.5, h - 0.5) == pytest.approx(img[-1, -1])


def test_bilinear_at_pixel_centres_returns_pixels():
    rng = np.random.default_rng(3)
    img = rng.integers(0, 256, (6, 8)).astype(np.uint8)
    yy, xx = np.mgrid[0:6, 0:8] + 0.5
    np.testing.assert_array_equal(digital.bilinear(img, xx, yy), img)


def test_shift_by_zero_is_identity():
    img = np.random.default_rng(4).normal(size=(10, 12))
    np.testing.assert_array_equal(digital.shift_image(img, 0.0, 0.0), img)


def test_bilinear_matches_scipy_map_coordinates():
    # map_coordinates samples at array indices (row, col): centre of img[r, c] is at (r, c),
    # i.e. (row, col) = (y_p − 0.5, x_p − 0.5) in our raster system with the corner origin
    rng = np.random.default_rng(5)
    img = rng.normal(size=(20, 30))
    x, y = _raster_positions(rng, 20, 30, 1000)
    ref = map_coordinates(img, [y - 0.5, x - 0.5], order=1)
    np.testing.assert_allclose(digital.bilinear(img, x, y), ref, atol=1e-12)


def test_bilinear_matches_opencv_remap():
    # cv2.remap puts the centre of img[r, c] at (x, y) = (c, r): map = our coordinate − 0.5.
    # OpenCV quantises the fractional offsets to 1/32 (INTER_BITS = 5), so the positions are
    # chosen on that grid, where both must agree to float32 precision.
    rng = np.random.default_rng(6)
    img = rng.uniform(0, 255, (16, 24)).astype(np.float32)
    cols = rng.integers(0, 23 * 32, 400) / 32.0
    rows = rng.integers(0, 15 * 32, 400) / 32.0
    ref = cv2.remap(img, cols.astype(np.float32)[None, :], rows.astype(np.float32)[None, :],
                    interpolation=cv2.INTER_LINEAR)[0]
    np.testing.assert_allclose(digital.bilinear(img, cols + 0.5, rows + 0.5), ref, rtol=1e-5, atol=1e-3)


def test_rgb_is_per_channel_grey():
    rng = np.random.default_rng(7)
    rgb = rng.integers(0, 256, (8, 9, 3)).astype(np.uint8)
    x, y = _raster_positions(rng, 8, 9, 50)
    out = digital.bilinear(rgb, x, y)
    assert out.shape == (50, 3)
    for ch in range(3):
        np.testing.assert_array_equal(out[:, ch], digital.bilinear(rgb[..., ch], x, y))
    shifted = digital.shift_image(rgb, 0.3, -0.6)
    for ch in range(3):
        np.testing.assert_array_equal(shifted[..., ch], digital.shift_image(rgb[..., ch], 0.3, -0.6))


def test_shift_moves_a_blob_under_the_fixed_mark():
    # synthetic Gaussian blob at a known sub-pixel position; after shifting by its offset from
    # a fixed mark the blob's centroid sits on the mark (moving image, fixed mark, (1.10.6))
    h = w = 41
    yy, xx = np.mgrid[0:h, 0:w] + 0.5
    cx, cy = 20.3, 19.8
    img = np.exp(-((xx - cx) ** 2 + (yy - cy) ** 2) / (2 * 3.0 ** 2))
    mark = (20.5, 20.5)
    out = digital.shift_image(img, cx - mark[0], cy - mark[1], fill=0.0)
    wsum = out.sum()
    centroid = ((out * xx).sum() / wsum, (out * yy).sum() / wsum)
    assert centroid == pytest.approx(mark, abs=0.02)


def test_shift_image_is_a_translation_of_a_ramp():
    yy, xx = np.mgrid[0:10, 0:10] + 0.5
    img = 3 * xx - 2 * yy
    out = digital.shift_image(img, 0.4, 0.25)
    ok = np.isfinite(out)
    np.testing.assert_allclose(out[ok], (3 * (xx + 0.4) - 2 * (yy + 0.25))[ok])
    assert not np.isfinite(out[:, -1]).any() and not np.isfinite(out[-1, :]).any()


def test_bad_input():
    img = np.zeros((5, 5))
    with pytest.raises(InputError, match="outside"):
        digital.bilinear(img, 0.2, 2.0)
    with pytest.raises(InputError, match="outside"):
        digital.bilinear(img, 2.0, 4.6)
    with pytest.raises(InputError, match="NaN"):
        digital.bilinear(img, np.nan, 2.0)
    with pytest.raises(InputError, match="NaN"):
        digital.bilinear(np.full((3, 3), np.nan), 1.0, 1.0)
    with pytest.raises(InputError, match="shape"):
        digital.bilinear(np.zeros(5), 1.0, 1.0)
    with pytest.raises(InputError, match="2×2"):
        digital.bilinear(np.zeros((1, 5)), 1.0, 0.5)
    with pytest.raises(InputError, match="n must be ≥ 1"):
        digital.subpixel_coordinates(2, 1, 0, 0, 0)
    with pytest.raises(InputError, match="< n"):
        digital.subpixel_coordinates(2, 1, 5, 3, 5)
    with pytest.raises(InputError, match="integer"):
        digital.subpixel_coordinates(2, 1, 2, 3, 2.5)
    with pytest.raises(InputError, match="≥ 0"):
        digital.pixel_center(-1, 0)
    with pytest.raises(InputError, match="origin"):
        digital.pixel_center(1, 1, "middle")
    with pytest.raises(InputError, match="positive"):
        digital.pixel_to_physical(1.0, 1.0, 0.0)
    with pytest.raises(InputError, match="out of range"):
        digital.flip_rows(7, 7)
    with pytest.raises(InputError, match="outside"):
        digital.shift_image(img, 0.5, 0.0, fill=None)
