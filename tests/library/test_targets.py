"""Monocular target measurement, Chapter 5, §5.11: centroid, circle fit, cross target, templates.

Targets are rendered anti-aliased (8×8 supersampling) at known sub-pixel centres, blurred and
given noise with a fixed seed; the known centres are the ground truth.
"""

import numpy as np
import pytest
from scipy import ndimage as ndi

from photolib import targets as T
from photolib.errors import DegenerateGeometryError

N, SS = 64, 8
XC, YC, R = 32.37, 30.81, 6.3


def render(fun, n=N):
    y, x = (np.mgrid[0:n * SS, 0:n * SS] + 0.5) / SS - 0.5
    return fun(x, y).reshape(n, SS, n, SS).mean(axis=(1, 3))


def disc(glare=False, seed=3):
    img = render(lambda x, y: 40 + 160 * ((x - XC) ** 2 + (y - YC) ** 2 <= R ** 2))
    if glare:                                           # a local disturbance (Fig. 5.30)
        img = img + render(lambda x, y: 120 * ((x - 44.0) ** 2 + (y - 36.0) ** 2 <= 2.5 ** 2))
    rng = np.random.default_rng(seed)
    return ndi.gaussian_filter(img, 0.8) + rng.normal(0, 2, img.shape)


def test_threshold_piecewise():
    f = np.array([[0.0, 25.0, 90.0, 100.0]])
    np.testing.assert_array_equal(T.threshold_target(f, 15, 30), [[0.0, 0.0, 85.0, 85.0]])
    np.testing.assert_array_equal(T.threshold_target(f, 0, 0), f)


def test_centroid_of_symmetric_blob_is_exact_and_glare_biases_it():
    y, x = np.mgrid[0:21, 0:25]
    blob = np.exp(-((x - 12) ** 2 + (y - 10) ** 2) / 8.0)
    assert T.centroid(blob) == pytest.approx((12.0, 10.0))
    assert T.centroid(1 - blob, dark=True) == pytest.approx((12.0, 10.0))
    clean = T.centroid(T.threshold_target(disc(), 20, 80))
    glare = T.centroid(T.threshold_target(disc(glare=True), 20, 80))
    assert np.hypot(clean[0] - XC, clean[1] - YC) < 0.1          # the book: ≈ 0.1 px
    assert np.hypot(glare[0] - XC, glare[1] - YC) > 0.5          # Fig. 5.30: disturbed


def test_weights():
    assert T.gradient_weight([4.0, 2.0, 1.0]).tolist() == pytest.approx([1.0, np.exp(-1), np.exp(-3)])
    w = T.robust_weight([0.0, 2.0, 2.5], 1.0, 2)
    assert w.tolist() == pytest.approx([1.0, 1.0, np.exp(-0.1 * 2.5 ** 4)])
    assert T.robust_weight([2.5], 1.0, 4)[0] == pytest.approx(np.exp(-0.1 * 2.5 ** 3))


def test_circle_fit_clean_and_with_glare():
    c = T.circle_fit(disc())
    assert np.hypot(c.x - XC, c.y - YC) < 0.05 and abs(c.radius - R) < 0.3
    assert 0 < c.sigma_x < 0.5 and 0 < c.sigma_radius < 0.5     # conservative (docstring), never zero
    g = T.circle_fit(disc(glare=True))
    assert np.hypot(g.x - XC, g.y - YC) < 0.05                   # robust weights (5.11.6)
    plain = T.circle_fit(disc(glare=True), robust=False)
    assert np.hypot(plain.x - XC, plain.y - YC) > 0.5            # without P'' the glare pulls it away


def test_circle_fit_on_a_straight_edge_is_degenerate_or_flagged():
    edge = np.tile(np.r_[np.full(20, 40.0), np.full(20, 200.0)], (40, 1))
    with pytest.raises(DegenerateGeometryError):
        T.circle_fit(edge)


def cross_target(xc=30.4, yc=27.7, theta=5.0, seed=5, n=60):
    th = np.radians(theta)

    def f(x, y):
        u = (x - xc) * np.cos(th) + (y - yc) * np.sin(th)
        v = -(x - xc) * np.sin(th) + (y - yc) * np.cos(th)
        hi = ((u > 0) & (v < 0)) | ((u < 0) & (v > 0))
        return 40 + 160 * hi * (u ** 2 + v ** 2 < 15 ** 2) + 40 * (u ** 2 + v ** 2 >= 15 ** 2)
    img = render(f, n)
    return ndi.gaussian_filter(img, 0.7) + np.random.default_rng(seed).normal(0, 2, img.shape)


@pytest.mark.parametrize("xc,yc,theta", [(30.4, 27.7, 5.0), (29.85, 31.2, -3.0), (31.0, 30.0, 0.0)])
def test_kadnichansky_target(xc, yc, theta):
    img = cross_target(xc, yc, theta)
    (x0, y0), S = T.kadnichansky_detect(img, 40)
    assert abs(x0 - xc) <= 1.0 and abs(y0 - yc) <= 1.0 and S > 4 * 40
    c = T.kadnichansky_center(img, (x0, y0))
    assert np.hypot(c.x - xc, c.y - yc) < 0.05                     # the book: ≈ 0.04 px
    assert c.rms_a < 0.2 and c.rms_b < 0.2


def test_kadnichansky_no_target():
    with pytest.raises(DegenerateGeometryError):
        T.kadnichansky_detect(np.random.default_rng(0).normal(100, 2, (30, 30)), 40)


def test_find_targets_grid_of_crosses():
    centres = [(12.0 + 20 * i + 0.3 * j, 10.0 + 18 * j + 0.2 * i) for i in range(3) for j in range(3)]

    def f(x, y):
        out = np.zeros_like(x)
        for cx, cy in centres:
            out += ((np.abs(x - cx) < 0.8) & (np.abs(y - cy) < 5)) | ((np.abs(y - cy) < 0.8) & (np.abs(x - cx) < 5))
        return 30 + 150 * np.clip(out, 0, 1)
    img = ndi.gaussian_filter(render(f, 70), 0.6) + np.random.default_rng(1).normal(0, 2, (70, 70))
    tmpl = img[10 - 6:10 + 7, 12 - 6:12 + 7]                      # the first cross as template
    found = T.find_targets(img, tmpl, 0.7)
    assert len(found) == len(centres)
    for cx, cy in centres:
        d = np.hypot(found[:, 0] - cx, found[:, 1] - cy).min()
        assert d < 0.35
    assert T.find_targets(np.random.default_rng(2).normal(0, 1, (40, 40)), tmpl, 0.9).shape == (0, 3)
