"""Chapter 5, §5.6: pyramids, coarse-to-fine matching, epipolar lines, normal-case resampling."""

import numpy as np
import pytest
from scipy.ndimage import gaussian_filter

from photolib.camera import ExteriorOrientation, InteriorOrientation
from photolib.epipolar import (epipolar_intersection, epipolar_line, epipolar_ordinate, match_coarse_to_fine,
                               pyramid, rectify_pair)
from photolib.errors import DegenerateGeometryError
from photolib.rotation import rotation_matrix
from photolib.single_image import image_to_ground, project
from photolib.synthetic import image_to_pixel, pixel_to_image, render_image, terrain_scene


def test_pyramid_mean_is_block_mean():
    skt = pytest.importorskip("skimage.transform")
    img = np.random.default_rng(0).random((64, 48))
    levels = pyramid(img, 3)
    assert [lv.shape for lv in levels] == [(64, 48), (32, 24), (16, 12), (8, 6)]
    np.testing.assert_allclose(levels[1], skt.downscale_local_mean(img, (2, 2)), atol=1e-14)
    np.testing.assert_allclose(levels[3], skt.downscale_local_mean(img, (8, 8)), atol=1e-14)
    g = pyramid(img, 2, "gauss")
    assert g[2].shape == (16, 12) and g[2].std() < levels[2].std()


def test_pyramid_odd_sizes_drop_the_last_row():
    lv = pyramid(np.arange(35.0).reshape(5, 7), 1)[1]
    np.testing.assert_array_equal(lv, [[4.0, 6.0, 8.0], [18.0, 20.0, 22.0]])


@pytest.mark.parametrize("p, q", [(37, -11), (-21, 6), (3, 0)])
def test_coarse_to_fine_recovers_large_shifts(p, q):
    """The guide's set-up (sift_pyr.py): 4 levels, ±8 px on top, ±2 px below; f1(x, y) = f2(x − p, y − q)."""
    rng = np.random.default_rng(4)
    base = gaussian_filter(rng.normal(size=(300, 300)), 3.0)
    img2 = np.roll(base, (-q, -p), axis=(0, 1))
    m = match_coarse_to_fine(base, img2, (150, 150), levels=3, half_window=5, search_radius=8, refine_radius=2)
    assert (round(m.p), round(m.q)) == (p, q)
    assert abs(m.p - p) < 0.2 and abs(m.q - q) < 0.2 and m.confident
    assert [t[0] for t in m.trace] == [3, 2, 1, 0]


def test_single_level_search_would_miss_the_shift():
    rng = np.random.default_rng(4)
    base = gaussian_filter(rng.normal(size=(300, 300)), 3.0)
    img2 = np.roll(base, (11, -37), axis=(0, 1))
    m = match_coarse_to_fine(base, img2, (150, 150), levels=0, half_window=5, search_radius=8)
    assert round(m.p) != 37 or not m.confident


def _ro_pair():
    """The guide's epi.py pair: f = 0.1, B = (1, 0, 0), α′1 = 1.2°, κ′1 = −0.8°, ω′2 = 0.7°, α′2 = −1.5°, κ′2 = 2°."""
    A1 = rotation_matrix(0.0, np.radians(1.2), np.radians(-0.8), "wak")
    A2 = rotation_matrix(np.radians(0.7), np.radians(-1.5), np.radians(2.0), "wak")
    io = InteriorOrientation(0.1)
    e1 = ExteriorOrientation.from_matrix([0, 0, 0], A1, "wak")
    e2 = ExteriorOrientation.from_matrix([1, 0, 0], A2, "wak")
    return io, e1, e2, A1, A2


def test_epipolar_ordinate_is_the_projection():
    io, e1, e2, A1, A2 = _ro_pair()
    M = np.array([[0.3, 0.4, -3.0]])
    m1, m2 = project(M, e1, io), project(M, e2, io)
    y = epipolar_ordinate(m1[0], m2[0, 0], A1, A2, 0.1)
    assert abs(y - m2[0, 1]) < 1e-15 and round(m2[0, 1], 9) == 0.013072817
    assert abs(epipolar_ordinate(m1[0], m2[0, 0], A1, A2, 0.1, as_printed=True) + m2[0, 1]) < 1e-15


def test_epipolar_ordinate_agrees_with_the_general_line():
    io, e1, e2, A1, A2 = _ro_pair()
    xy1 = np.array([[0.004, -0.007]])
    a, b, c = epipolar_line(xy1, e1, e2, io)[0]
    xc = np.linspace(-0.01, 0.01, 7)
    np.testing.assert_allclose(epipolar_ordinate(xy1[0], xc, A1, A2, 0.1), -(a * xc + c) / b, atol=1e-15)


def test_points_of_the_ray_lie_on_the_epipolar_line():
    io = InteriorOrientation(100.0, 0.02, -0.01)
    e1 = ExteriorOrientation(1000, 2000, 1500, 0.010, -0.020, 0.30)
    e2 = ExteriorOrientation(1600, 2010, 1495, -0.015, 0.012, 0.31)
    xy1 = np.array([[12.0, -31.0], [-40.0, 5.0]])
    lines = epipolar_line(xy1, e1, e2, io)
    for k in range(2):
        P = image_to_ground(np.repeat(xy1[k:k + 1], 5, 0), np.linspace(0, 400, 5), e1, io)
        xy2 = project(P, e2, io)
        assert np.max(np.abs(xy2 @ lines[k, :2] + lines[k, 2])) < 1e-10


def test_three_image_intersection():
    io = InteriorOrientation(100.0)
    eos = [ExteriorOrientation(0, 0, 1000, 0.01, 0.0, 0.0), ExteriorOrientation(400, 10, 1000, 0.0, 0.02, 0.1),
           ExteriorOrientation(200, 350, 990, -0.02, 0.0, 0.0)]
    P = np.random.default_rng(2).uniform([50, 50, -20], [350, 250, 40], (10, 3))
    xy = [project(P, e, io) for e in eos]
    np.testing.assert_allclose(epipolar_intersection(xy[0], xy[1], *eos, io), xy[2], atol=1e-9)
    collinear = [ExteriorOrientation(0, 0, 1000), ExteriorOrientation(400, 0, 1000), ExteriorOrientation(200, 0, 1000)]
    with pytest.raises(DegenerateGeometryError, match="parallel"):
        epipolar_intersection(project(P, collinear[0], io), project(P, collinear[1], io), *collinear, io)


def _cv_setup(io, e1, e2, shape, d):
    """The same pair for OpenCV: K in pixels, cameras with y down and z forward (D = diag(1, −1, −1))."""
    h, w = shape
    K = np.array([[io.f / d, 0, (w - 1) / 2 + io.x0 / d], [0, io.f / d, (h - 1) / 2 - io.y0 / d], [0, 0, 1.0]])
    D = np.diag([1.0, -1.0, -1.0])
    R1, R2 = D @ e1.matrix.T, D @ e2.matrix.T
    return K, R2 @ R1.T, R2 @ (e1.center - e2.center)


def test_rectification_rows_agree_with_opencv():
    cv2 = pytest.importorskip("cv2")
    io = InteriorOrientation(35.0, 0.05, -0.03)
    e1 = ExteriorOrientation(0, 0, 500, 0.03, -0.04, 0.05)
    e2 = ExteriorOrientation(120, 8, 497, -0.02, 0.03, -0.04)
    shape, d = (300, 400), 0.02
    rp = rectify_pair(np.zeros(shape), np.zeros(shape), io, e1, e2, d)
    P = np.random.default_rng(3).uniform([0, -60, -30], [120, 60, 30], (40, 3))
    pix = [image_to_pixel(project(P, e, io), shape, d) for e in (e1, e2)]
    mine = [rp.to_rectified(pix[i], i) for i in range(2)]
    assert np.max(np.abs(mine[0][:, 1] - mine[1][:, 1])) < 1e-8           # equal rows: the normal case
    K, R, T = _cv_setup(io, e1, e2, shape, d)
    Rc1, Rc2, Pc1, Pc2, *_ = cv2.stereoRectify(K, np.zeros(5), K, np.zeros(5), shape[::-1], R, T.reshape(3, 1), alpha=-1)
    cvp = [cv2.undistortPoints(pix[i].reshape(-1, 1, 2), K, np.zeros(5), R=Rc, P=Pc).reshape(-1, 2)
           for i, Rc, Pc in ((0, Rc1, Pc1), (1, Rc2, Pc2))]
    assert np.max(np.abs(cvp[0][:, 1] - cvp[1][:, 1])) < 1e-3
    # the same rows in the same pixel units: normalised ordinate times f/Δ (OpenCV's y points down)
    f_px = io.f / d
    ours = -(pixel_to_image(0, mine[0][:, 1], shape, d)[1] + rp.y_offset) / io.f * f_px
    theirs = (cvp[0][:, 1] - Pc1[1, 2]) / Pc1[1, 1] * f_px
    assert np.max(np.abs(ours - theirs)) < 0.1
    assert np.max(np.abs(ours - theirs)) < 1e-4                           # in fact the same construction


def test_rectified_images_share_rows():
    scene = terrain_scene(extent=100.0, spacing=0.5, n_buildings=0, relief=6.0, seed=5)
    io = InteriorOrientation(35.0)
    e1 = ExteriorOrientation(35.0, 50.0, 330.0, 0.02, -0.01, 0.04)
    e2 = ExteriorOrientation(47.0, 51.0, 331.0, -0.01, 0.015, -0.02)
    shape, d = (160, 160), 0.03
    r1 = render_image(scene, io, e1, shape, pixel_size=d)
    r2 = render_image(scene, io, e2, shape, pixel_size=d)
    rp = rectify_pair(r1.image, r2.image, io, e1, e2, d)
    # object points seen by image 1 → both rectified images: same row, same brightness
    P = r1.XYZ[20:140:6, 20:140:6].reshape(-1, 3)
    q = [image_to_pixel(project(P, rp.eo[i], rp.interior(i)), shape, d) for i in range(2)]
    assert np.max(np.abs(q[0][:, 1] - q[1][:, 1])) < 1e-8
    inside = np.all((q[0] > 2) & (q[0] < 157) & (q[1] > 2) & (q[1] < 157), axis=1)
    for i, valid in enumerate((rp.valid_left, rp.valid_right)):
        r, c = np.clip(np.rint(q[i][:, 1]).astype(int), 0, 159), np.clip(np.rint(q[i][:, 0]).astype(int), 0, 159)
        inside &= valid[r, c]
    from scipy.ndimage import map_coordinates
    v = [map_coordinates(rp.left if i == 0 else rp.right, [q[i][inside, 1], q[i][inside, 0]], order=1)
         for i in range(2)]
    assert inside.sum() > 100
    assert np.corrcoef(v[0], v[1])[0, 1] > 0.95
    np.testing.assert_allclose(rp.from_rectified(rp.to_rectified([[10.0, 20.0]], 1), 1), [[10.0, 20.0]], atol=1e-9)
