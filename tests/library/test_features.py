"""Tests of photolib.features (Chapter 5, §5.5, §5.7–5.9) against the book's Fig. 5.12, sympy-free
identities, synthetic ground truth and independent implementations (scikit-image, OpenCV, SciPy).

Conventions that differ between the peers and photolib (stated where the comparison is made):
* scikit-image ``corner_harris``/``corner_foerstner``: unnormalised Sobel gradients (ndi.sobel),
  Gaussian weight σ = 1 truncated at 4σ (9×9), zero padding → photolib with window=9, sigma=1,
  gradient="sobel" (Sobel/8), weight="gaussian", border="constant": R × 8⁴, w × 8², q equal.
* scikit-image ``corner_moravec(window_size=h)``: only the diagonal shifts 0 < |dr|, |dc| ≤ h
  → photolib ``moravec(variant="diagonal")``; the book's (5.8.1) is a different (normalised,
  in-window, 4-direction) measure, compared by its points only.
* OpenCV ``cornerHarris(blockSize=n, ksize=3)``: Sobel, *unweighted* window sums, BORDER_REFLECT_101,
  its own constant scale → photolib weight="box", border="mirror": R proportional.
* OpenCV ``FAST``: strict inequalities (brighter if > c + t) against the book's ≥ in (5.8.9) → on
  integer images cv2 with t equals photolib with t + 1.
"""

import numpy as np
import pytest
from scipy import ndimage as ndi
from scipy.spatial import cKDTree

from photolib import features as ft
from photolib.errors import InputError

cv2 = pytest.importorskip("cv2")
skf = pytest.importorskip("skimage.feature")


def texture(shape=(120, 140), seed=0, sigma=2.0):
    rng = np.random.default_rng(seed)
    img = ndi.gaussian_filter(rng.normal(size=shape), sigma)
    return (img - img.min()) / np.ptp(img) * 200 + 20


# --- §5.5 gradients ------------------------------------------------------------------------------------
FIG_5_12_INPUT = np.full((8, 8), 10.0)
FIG_5_12_INPUT[2:6, 2:6] = 20.0
FIG_5_12_PRINTED = np.array([[10] * 8, [10, 10, 20, 20, 20, 10, 10, 10]] + [[10, 20, 0, 0, 0, 20, 10, 10]] * 3
                            + [[10, 10, 20, 20, 20, 10, 10, 10], [10] * 8, [10] * 8], float)


def test_fig_5_12_roberts_cell_by_cell():
    gx, gy = ft.gradient_roberts(FIG_5_12_INPUT)
    G = ft.gradient_magnitude(gx, gy, "l1")
    ring = FIG_5_12_PRINTED != 10
    # the 21 printed object/edge cells (12 × "20", 9 × "0") are reproduced exactly
    assert ring.sum() == 21 and np.array_equal(G[ring], FIG_5_12_PRINTED[ring])
    # of the 43 cells printed "10", 4 (the ring's corners) are 10 and 39 are 0 (flat background)
    tens = FIG_5_12_PRINTED == 10
    assert tens.sum() == 43
    assert int(np.sum(G[tens] == 10)) == 4 and int(np.sum(G[tens] == 0)) == 39
    assert set(map(tuple, np.argwhere(tens & (G == 10)))) == {(1, 1), (1, 5), (5, 1), (5, 5)}


def test_fig_5_12_anchor_bottom_right_does_not_fit():
    gx, gy = ft.gradient_roberts(FIG_5_12_INPUT, anchor="bottom-right")
    G = ft.gradient_magnitude(gx, gy, "l1")
    ring = FIG_5_12_PRINTED != 10
    assert not np.array_equal(G[ring], FIG_5_12_PRINTED[ring])


def test_sobel_equals_printed_nine_pixel_formula_and_scipy():
    f = texture((9, 11))
    gx, gy = ft.gradient_sobel(f)
    r, c = 4, 5
    f1, f2, f3, f4, f5, f6, f7, f8, f9 = f[r - 1:r + 2, c - 1:c + 2].ravel()
    assert gx[r, c] == pytest.approx((f3 + 2 * f6 + f9) - (f1 + 2 * f4 + f7))            # (5.5.9)
    assert gy[r, c] == pytest.approx((f1 + 2 * f2 + f3) - (f7 + 2 * f8 + f9))
    # scipy: ndi.sobel(axis=1) is the same x mask; its axis-0 derivative points down (−g_y)
    inner = (slice(1, -1), slice(1, -1))
    assert np.allclose(gx[inner], ndi.sobel(f, axis=1)[inner])
    assert np.allclose(gy[inner], -ndi.sobel(f, axis=0)[inner])
    assert np.all(gx[0] == 0) and np.all(gx[:, -1] == 0)       # border="zero"


def test_prewitt_and_backward_against_independent_forms():
    f = texture((9, 11))
    gx, gy = ft.gradient_prewitt(f, border="nearest")
    assert np.allclose(gx, ndi.prewitt(f, axis=1, mode="nearest"))
    assert np.allclose(gy, -ndi.prewitt(f, axis=0, mode="nearest"))
    bx, by = ft.gradient_backward(f)
    assert np.allclose(bx[:, 1:], np.diff(f, axis=1)) and np.all(bx[:, 0] == 0)
    assert np.allclose(by[:-1], -np.diff(f, axis=0)) and np.all(by[-1] == 0)


def test_normalised_gradients_are_derivatives_on_a_ramp():
    y, x = np.mgrid[0:10, 0:12].astype(float)
    f = 3.0 * x - 2.0 * y                     # rows grow downwards: ∂f/∂(y up) = +2
    for fn in (lambda a: ft.gradient_sobel(a, normalize=True), lambda a: ft.gradient_prewitt(a, normalize=True),
               ft.gradient_backward):
        gx, gy = fn(f)
        assert np.allclose(gx[2:-2, 2:-2], 3.0) and np.allclose(gy[2:-2, 2:-2], 2.0)
    assert ft.gradient_magnitude(3.0 * np.ones(2), 4.0 * np.ones(2)).tolist() == [5.0, 5.0]
    assert ft.gradient_magnitude(3.0 * np.ones(2), -4.0 * np.ones(2), "l1").tolist() == [7.0, 7.0]


# --- §5.8 detectors: peers -------------------------------------------------------------------------------
def test_harris_equals_skimage_up_to_sobel_scale():
    img = texture()
    Rs = skf.corner_harris(img, k=0.05, sigma=1)
    Rm = ft.harris(img, window=9, sigma=1.0, k=0.05, weight="gaussian", gradient="sobel", border="constant")
    assert np.allclose(Rm * 8.0 ** 4, Rs, rtol=1e-9, atol=1e-9 * np.abs(Rs).max())
    ps = skf.corner_peaks(Rs, min_distance=4, threshold_rel=0.01, exclude_border=5)
    pm = ft.nonmax_suppression(Rm, size=9, relative=0.01, border=5)
    assert set(map(tuple, ps[:, ::-1])) == set(map(tuple, pm.astype(int)))


def test_foerstner_equals_skimage():
    img = texture()
    w, q = skf.corner_foerstner(img, sigma=1)
    wm, qm = ft.foerstner(img, window=9, sigma=1.0, weight="gaussian", gradient="sobel", border="constant")
    assert np.allclose(qm, q, atol=1e-12)
    assert np.allclose(wm * 64.0, w, rtol=1e-9, atol=1e-12 * w.max())


@pytest.mark.parametrize("window_size", [1, 2])
def test_moravec_diagonal_variant_equals_skimage(window_size):
    img = texture()
    Ms = skf.corner_moravec(img, window_size=window_size)
    Mm = ft.moravec(img, 2 * window_size + 1, variant="diagonal")
    assert np.allclose(Mm, Ms, rtol=1e-10, atol=1e-9)


def test_moravec_book_points_near_skimage_points():
    """Different measures (module notes): the strongest corners of a rotated square agree to 2 px."""
    img = square_image()
    pb = ft.nonmax_suppression(ft.moravec(img, 5), 9, relative=0.3, border=3, max_points=4)
    ps = skf.corner_peaks(skf.corner_moravec(img, 2), min_distance=4, threshold_rel=0.3, num_peaks=4)[:, ::-1]
    assert len(pb) == len(ps) == 4
    d, _ = cKDTree(ps).query(pb)
    assert d.max() <= 2.0


@pytest.mark.parametrize("block", [3, 5])
def test_harris_proportional_to_opencv(block):
    img = texture().astype(np.float32).astype(float)
    Rc = cv2.cornerHarris(img.astype(np.float32), block, 3, 0.04).astype(float)
    Rm = ft.harris(img, window=block, k=0.04, weight="box", gradient="sobel", border="mirror")
    big = np.abs(Rc) > 1e-3 * np.abs(Rc).max()
    ratio = Rm[big] / Rc[big]
    assert np.ptp(ratio) < 1e-3 * np.median(ratio)          # float32 precision of OpenCV
    pc = ft.nonmax_suppression(Rc, 9, relative=0.01, border=4)
    pm = ft.nonmax_suppression(Rm, 9, relative=0.01, border=4)
    assert set(map(tuple, pc)) == set(map(tuple, pm))


@pytest.mark.parametrize("t", [10, 25])
def test_fast_equals_opencv_segment_test(t):
    u8 = texture().astype(np.uint8)
    kp = cv2.FastFeatureDetector_create(t, False, cv2.FAST_FEATURE_DETECTOR_TYPE_9_16).detect(u8)
    theirs = {(int(k.pt[0]), int(k.pt[1])) for k in kp}
    s = ft.fast(u8.astype(float), t + 1, n=9)
    ours = {(int(c), int(r)) for r, c in np.argwhere(s > 0)}
    assert len(theirs) > 50 and ours == theirs


def test_log_kernel_against_scipy_gaussian_laplace():
    img = texture(sigma=3.0)
    L = ft.log_filter(img, 2.0)
    ref = ndi.gaussian_laplace(img, 2.0, mode="mirror")
    inner = (slice(10, -10), slice(10, -10))
    assert np.corrcoef(L[inner].ravel(), ref[inner].ravel())[0, 1] > 0.999
    K = ft.log_kernel(1.5)
    r = np.arange(-K.shape[0] // 2 + 1, K.shape[0] // 2 + 1)
    assert abs(K.sum()) < 1e-15 and K[r.size // 2, r.size // 2] < 0


def test_log_zero_crossing_on_a_step_edge():
    f = np.zeros((21, 40)); f[:, 20:] = 100.0
    zc = ft.zero_crossings(ft.log_filter(f, 2.0, border="nearest"), min_contrast=1.0)
    cols = np.unique(np.argwhere(zc)[:, 1])
    assert set(cols) <= {19, 20}


# --- §5.8 detectors: synthetic ground truth, rotation, textureless ----------------------------------
def square_image(N=101, angle=20.0, half=20, seed=0):
    yy, xx = np.mgrid[0:N, 0:N].astype(float)
    c, th = N // 2, np.radians(angle)
    u = (xx - c) * np.cos(th) + (yy - c) * np.sin(th)
    v = -(xx - c) * np.sin(th) + (yy - c) * np.cos(th)
    img = np.where((abs(u) <= half) & (abs(v) <= half), 200.0, 50.0)
    return ndi.gaussian_filter(img, 1.0) + np.random.default_rng(seed).normal(0, 1, img.shape)


def square_corners(N=101, angle=20.0, half=20):
    c, th = N // 2, np.radians(angle)
    return np.array([[c + s1 * half * np.cos(th) - s2 * half * np.sin(th),
                      c + s1 * half * np.sin(th) + s2 * half * np.cos(th)] for s1 in (-1, 1) for s2 in (-1, 1)])


@pytest.mark.parametrize("operator,opts,tol", [
    ("harris", {}, 2.5), ("foerstner", {}, 3.0), ("moravec", {}, 3.0), ("fast", {"threshold_fast": 20}, 3.0)])
def test_detectors_find_the_four_corners(operator, opts, tol):
    img = square_image()
    pts = ft.interest_points(img, operator, relative=0.3, max_points=4, **opts)
    assert len(pts) == 4
    d, _ = cKDTree(pts).query(square_corners())
    assert d.max() < tol                                   # blur pulls the corner inwards


@pytest.mark.parametrize("operator,opts", [
    ("harris", {}), ("moravec", {}), ("fast", {"threshold_fast": 10}), ("log", {}),
    ("foerstner", {"gradient": "sobel"})])
def test_detectors_invariant_to_90_degree_rotation(operator, opts):
    img = texture()
    p = ft.interest_points(img, operator, relative=0.05, **opts)
    pr = ft.interest_points(np.rot90(img), operator, relative=0.05, **opts)
    W = img.shape[1]
    mapped = np.c_[p[:, 1], W - 1 - p[:, 0]]           # (x, y) → (y, W − 1 − x) under np.rot90
    assert len(p) > 20
    assert set(map(tuple, mapped)) == set(map(tuple, pr))


def test_foerstner_backward_differences_rotation_within_a_pixel():
    """(5.5.4) lives on half-pixel positions: exact invariance is lost, the strongest points move ≤ 1.5 px."""
    img = texture()
    p = ft.interest_points(img, "foerstner", relative=0.05, max_points=20)
    pr = ft.interest_points(np.rot90(img), "foerstner", relative=0.05)
    mapped = np.c_[p[:, 1], img.shape[1] - 1 - p[:, 0]]
    d, _ = cKDTree(pr).query(mapped)
    assert d.max() <= 1.5


def test_harris_sign_pattern_and_foerstner_q_range():
    f = np.zeros((31, 31)); f[15:, 15:] = 100.0
    R = ft.harris(f)
    assert R[15, 15] > 0 and R[15, 25] < 0 and R[5, 5] == 0       # corner, edge, flat
    w, q = ft.foerstner(texture())
    assert np.all((q >= 0) & (q <= 1)) and np.all(w >= 0)
    w, q = ft.foerstner(f)
    assert q[15, 25] < 1e-12 and q[15, 15] > 0.9                  # straight edge vs corner


@pytest.mark.parametrize("operator", ["harris", "foerstner", "moravec", "fast", "log"])
def test_textureless_image_gives_no_points(operator):
    pts = ft.interest_points(np.full((40, 40), 77.0), operator)
    assert pts.shape == (0, 2)


def test_nonmax_plateau_keeps_one_point():
    R = np.zeros((9, 9)); R[3:5, 3:5] = 2.0
    assert ft.nonmax_suppression(R, 3).tolist() == [[3.0, 3.0]]


# --- §5.9 descriptors ------------------------------------------------------------------------------------------
def warped_pair(N=240, angle_deg=30.0, shift=(7.3, -4.1), seed=4):
    rng = np.random.default_rng(seed)
    base = ndi.gaussian_filter(rng.normal(size=(N, N)), 3.0)
    base = (base - base.min()) / np.ptp(base) * 200 + 20
    a = np.radians(angle_deg)
    R = np.array([[np.cos(a), -np.sin(a)], [np.sin(a), np.cos(a)]])
    c0 = np.full(2, (N - 1) / 2)
    t = np.asarray(shift)
    Y2, X2 = np.mgrid[0:N, 0:N].astype(float)
    P1 = (np.c_[X2.ravel(), Y2.ravel()] - c0 - t) @ R + c0        # x₁ = Rᵀ(x₂ − c₀ − t) + c₀
    img2 = ndi.map_coordinates(base, [P1[:, 1], P1[:, 0]], order=3, mode="reflect").reshape(N, N)
    return base, img2, R, c0 + t - R @ c0


def fit_similarity(sample):
    """Rotation + shift (+ scale) from ≥ 2 point pairs by linear least squares (independent of photolib)."""
    p, q = sample
    A = np.zeros((2 * len(p), 4)); A[0::2] = np.c_[p[:, 0], -p[:, 1], np.ones(len(p)), np.zeros(len(p))]
    A[1::2] = np.c_[p[:, 1], p[:, 0], np.zeros(len(p)), np.ones(len(p))]
    sol = np.linalg.lstsq(A, q.ravel(), rcond=None)[0]
    return sol


def similarity_residual(m, d):
    a, b, tx, ty = m
    p, q = d
    return np.hypot(a * p[:, 0] - b * p[:, 1] + tx - q[:, 0], b * p[:, 0] + a * p[:, 1] + ty - q[:, 1])


def test_descriptor_matching_recovers_rotation_and_shift():
    from photolib.ransac import ransac
    img1, img2, R, t = warped_pair()
    p1 = ft.interest_points(img1, "harris", border=20, max_points=150)
    p2 = ft.interest_points(img2, "harris", border=20, max_points=150)
    d1, d2 = ft.sift_descriptors(img1, p1), ft.sift_descriptors(img2, p2)
    assert d1.vectors.shape == (150, 128)                                   # 4 × 4 × 8
    m = ft.match_descriptors(d1, d2)
    pred = p1[m[:, 0]] @ R.T + t
    correct = np.hypot(*(p2[m[:, 1]] - pred).T) < 2.0
    assert len(m) >= 50 and correct.mean() > 0.9
    res = ransac((p1[m[:, 0]], p2[m[:, 1]]), fit_similarity, similarity_residual, 2, 1.5, rng=1)
    a, b, tx, ty = res.model
    assert np.degrees(np.arctan2(b, a)) == pytest.approx(30.0, abs=0.1)
    assert np.hypot(a, b) == pytest.approx(1.0, abs=2e-3)
    assert np.allclose([tx, ty], t, atol=0.3)
    # the dominant orientations differ by the rotation for correctly matched points
    dth = (d2.orientation[m[correct, 1]] - d1.orientation[m[correct, 0]] - np.radians(30)) % (2 * np.pi)
    dth = np.minimum(dth, 2 * np.pi - dth)
    assert np.median(dth) < np.radians(5)


def test_descriptor_invariant_to_linear_grey_change_and_textureless_invalid():
    img = texture((80, 80), sigma=2.0)
    pts = [[40.0, 40.0], [30.0, 45.0]]
    a, b = ft.sift_descriptors(img, pts), ft.sift_descriptors(3.0 * img + 40.0, pts)
    assert np.allclose(a.vectors, b.vectors, atol=1e-10)
    flat = ft.sift_descriptors(np.full((60, 60), 5.0), [[30.0, 30.0]])
    assert not flat.valid[0] and np.all(flat.vectors == 0)
    assert len(ft.match_descriptors(flat, flat)) == 0


def test_match_descriptors_ratio_and_cross_check():
    d1 = np.array([[1.0, 0.0], [0.0, 1.0]])
    d2 = np.array([[0.9, 0.1], [0.0, 1.0], [0.85, 0.0]])
    m = ft.match_descriptors(d1, d2, ratio=0.8)
    assert m.tolist() == [[1, 1]]                     # row 0 is ambiguous (0.14 vs 0.15): rejected
    assert ft.match_descriptors(d1, d2[:1]).shape == (0, 2)
