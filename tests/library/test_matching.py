"""Area matching, Chapter 5, §5.1–5.4: correlation, sub-pixel vertex, least-squares matching.

Expected values come from synthetic ground truth (images shifted or warped by a known amount),
independent implementations (OpenCV ``matchTemplate``, scikit-image ``match_template``,
finite differences) and sympy — never from the code's own output.
"""

import numpy as np
import pytest
import sympy as sp
from scipy import ndimage as ndi

from photolib import matching as M
from photolib.derivations import matching as D
from photolib.errors import ConvergenceError, DegenerateGeometryError


def texture(n=120, sigma=2.0, seed=0):
    rng = np.random.default_rng(seed)
    img = ndi.gaussian_filter(rng.normal(size=(n, n)), sigma)
    return (img - img.min()) / (img.max() - img.min()) * 200 + 20


def shifted(img, p, q):
    """Image 2 with x₂ = x₁ − p, y₂ = y₁ − q (cubic spline shift)."""
    return ndi.shift(img, (-q, -p), order=3, mode="reflect")


# --- §5.1 -----------------------------------------------------------------------------------------

def test_coefficients_range_and_invariance():
    rng = np.random.default_rng(3)
    a = rng.uniform(0, 255, (5, 7))                    # the book's 5×7 matrix: n = 35
    assert a.size == 35
    assert M.correlation_coefficient(a, 3 * a + 40) == pytest.approx(1.0)
    assert M.correlation_coefficient(a, -a) == pytest.approx(-1.0)     # (5.1.2) lies in [−1, 1]
    inv = 255 - a
    assert 0 <= M.correlation_coefficient(a, inv, centred=False) <= 1  # (5.1.1) ≥ 0 for grey values
    # (5.1.2) is the cosine of the angle between the centred vectors
    u, v = (a - a.mean()).ravel(), (inv - inv.mean()).ravel()
    assert M.correlation_coefficient(a, inv) == pytest.approx(u @ v / np.linalg.norm(u) / np.linalg.norm(v))


def test_surface_equals_opencv_and_skimage():
    cv2 = pytest.importorskip("cv2")
    skf = pytest.importorskip("skimage.feature")
    img = texture(80, 1.5, seed=1)
    tmpl = img[30:45, 20:41]
    search = texture(80, 1.5, seed=2)[5:60, 3:70] + 0.3 * img[5:60, 3:70]
    R = M.correlation_surface(tmpl, search)
    ref_cv = cv2.matchTemplate(search.astype(np.float32), tmpl.astype(np.float32), cv2.TM_CCOEFF_NORMED)
    ref_sk = skf.match_template(search, tmpl)
    assert R.shape == ref_cv.shape == ref_sk.shape
    np.testing.assert_allclose(R, ref_sk, atol=1e-9)
    np.testing.assert_allclose(R, ref_cv, atol=2e-4)
    assert np.unravel_index(np.argmax(R), R.shape) == np.unravel_index(np.argmax(ref_cv), R.shape)
    R1 = M.correlation_surface(tmpl, search, centred=False)           # (5.1.1) = TM_CCORR_NORMED
    ref1 = cv2.matchTemplate(search.astype(np.float32), tmpl.astype(np.float32), cv2.TM_CCORR_NORMED)
    np.testing.assert_allclose(R1, ref1, atol=2e-4)


@pytest.mark.parametrize("p,q", [(7, -3), (-4, 5), (0, 0), (10, 10)])
def test_integer_shift_recovered_exactly(p, q):
    img = texture()
    m = M.match_point(img, shifted(img, p, q), (60, 60), search_radius=12, subpixel=None)
    assert (m.p, m.q) == (p, q)
    assert m.integer == (60 - p, 60 - q)
    assert m.r_max == pytest.approx(1.0) and m.confident


@pytest.mark.parametrize("frac", [0.0, 0.25, 0.5, 0.75])
def test_subpixel_parabola_1d_shift(frac):
    img = texture(120, 1.0, seed=0)
    p = 7 + frac
    m = M.match_point(img, shifted(img, p, 0.0), (60, 60), search_radius=10)
    assert abs(m.p - p) < 0.06
    # the separate y parabola through the x-integer column is biased at half-pixel x shifts
    # (the R profile is sampled off its ridge; guide pitfall 14): about 0.1 px on this texture
    assert abs(m.q) < 0.15


def test_paraboloid_is_no_worse_off_both_grid_lines():
    img = texture(120, 2.0, seed=0)
    p, q = 7.3, -2.6
    right = shifted(img, p, q)
    sep = M.match_point(img, right, (60, 60), search_radius=10)
    two = M.match_point(img, right, (60, 60), search_radius=10, subpixel="paraboloid")
    assert (sep.integer, two.integer) == ((60 - 7, 63), (60 - 7, 63))
    assert np.hypot(two.p - p, two.q - q) <= np.hypot(sep.p - p, sep.q - q) + 1e-9
    assert np.hypot(two.p - p, two.q - q) < 0.25


def test_parabola_vertex_exact_and_equals_sympy_closed_form():
    x = np.arange(-2, 3, dtype=float)
    vertex, a = M.parabola_vertex(0.9 - 0.05 * (x - 0.37) ** 2, x)
    assert vertex == pytest.approx(0.37)
    closed = D.parabola_vertex_symbolic()["three_point"]
    rm, r0, rp = 0.61, 0.93, 0.80
    num = float(closed.subs({sp.Symbol("R_m"): rm, sp.Symbol("R_0"): r0, sp.Symbol("R_p"): rp}))
    assert M.parabola_vertex([rm, r0, rp])[0] == pytest.approx(num)


def test_peak_sharpness_ranks_low_and_high_contrast_texture():
    img = texture(100, 1.0, seed=5)
    smooth = texture(100, 4.0, seed=5)                 # the same kind of texture, far smoother
    sharp_hi = M.match_point(img, img, (50, 50), search_radius=5).sharpness
    sharp_lo = M.match_point(smooth, smooth, (50, 50), search_radius=5).sharpness
    assert sharp_hi > 3 * sharp_lo > 0


def test_textureless_template_raises_and_flat_search_raises():
    img = texture()
    flat = img.copy()
    flat[40:80, 40:80] = 100.0
    with pytest.raises(DegenerateGeometryError, match="textureless"):
        M.match_point(flat, img, (60, 60), half_window=5)
    with pytest.raises(DegenerateGeometryError):
        M.match_point(img, np.full_like(img, 7.0), (60, 60), half_window=5)


def test_no_confident_wrong_match_on_unrelated_or_repetitive_images():
    img = texture(seed=1)
    other = texture(seed=2)
    m = M.match_point(img, other, (60, 60), half_window=7, search_radius=8)
    assert not m.confident                              # unrelated texture: weak peak, flagged
    stripes = np.tile(np.sin(np.arange(120) * 2 * np.pi / 6.0) * 50 + 100, (120, 1))
    m = M.match_point(stripes, stripes, (60, 60), half_window=5, search_radius=8)
    assert not m.confident and "ambiguous" in m.reason


# --- §5.2 and §5.4 --------------------------------------------------------------------------------

def test_derived_jacobian_equals_finite_differences_of_the_residual():
    """a₁…a₈ against central differences of k₀ + k₁f₁ − f₂(warp) with an analytic f₂."""
    f2 = lambda x, y: np.sin(0.3 * x) * np.cos(0.2 * y) + 0.1 * x * y          # noqa: E731
    gx = lambda x, y: 0.3 * np.cos(0.3 * x) * np.cos(0.2 * y) + 0.1 * y       # noqa: E731
    gy = lambda x, y: -0.2 * np.sin(0.3 * x) * np.sin(0.2 * y) + 0.1 * x      # noqa: E731
    u, v, f1 = np.array([1.5, -2.0, 3.0]), np.array([0.5, 2.0, -1.0]), np.array([3.0, 1.0, 2.0])
    x0 = np.array([0.4, -0.3, 1.05, 0.08, -0.06, 0.97, 2.0, 0.9])

    def r(x):
        p, q, b1, b2, c1, c2, k0, k1 = x
        return k0 + k1 * f1 - f2(b1 * u + b2 * v - p, c1 * u + c2 * v - q)
    num = np.column_stack([(r(x0 + e) - r(x0 - e)) / 2e-6 for e in np.eye(8) * 1e-6])
    p, q, b1, b2, c1, c2 = x0[:6]
    X, Y = b1 * u + b2 * v - p, c1 * u + c2 * v - q
    B = D.lsm_jacobian()(u, v, gx(X, Y), gy(X, Y), f1)
    np.testing.assert_allclose(B, num, atol=1e-6)
    Bp = D.lsm_jacobian(as_printed=True)(u, v, gx(X, Y), gy(X, Y), f1)
    np.testing.assert_allclose(Bp[:, 2:6], -num[:, 2:6], atol=1e-6)      # the printed a₃…a₆: wrong sign
    np.testing.assert_allclose(Bp[:, [0, 1, 6, 7]], num[:, [0, 1, 6, 7]], atol=1e-6)


@pytest.mark.parametrize("p,q", [(0.3, -0.7), (-1.6, 0.45), (1.25, 1.9)])
def test_lsm_shift_recovers_subpixel_shift(p, q):
    img = texture(120, 2.0, seed=4)
    r = M.lsm_shift(img, shifted(img, p, q), (60, 60), approx=(60 - round(p), 60 - round(q)), half_window=7)
    assert abs(r.p - p) < 0.02 and abs(r.q - q) < 0.02
    assert r.confident and 0 < r.sigma_p < 0.05 and r.iterations <= 10
    assert r.history and r.history[0].x[0] == pytest.approx(round(p))


def test_lsm_shift_sigma_matches_monte_carlo():
    img = texture(100, 2.0, seed=6)
    rng = np.random.default_rng(7)
    right0 = shifted(img, 0.4, -0.2)
    est, sig = [], []
    for _ in range(30):
        right = right0 + rng.normal(0, 4.0, img.shape)
        r = M.lsm_shift(img, right, (50, 50), half_window=7, interpolation="cubic")
        est.append(r.p)
        sig.append(r.sigma_p)
    assert 0.6 < np.std(est) / np.mean(sig) < 1.6


def affine_pair(seed=1, n=160, interp=3):
    img = texture(n, 2.0, seed=seed)
    c = n / 2
    truth = dict(p=3.4, q=-1.7, b1=1.05, b2=0.08, c1=-0.06, c2=0.97, k0=12.0, k1=0.85)
    A = np.array([[truth["b1"], truth["b2"]], [truth["c1"], truth["c2"]]])
    Y2, X2 = np.mgrid[0:n, 0:n].astype(float)
    uv = np.linalg.solve(A, np.vstack([(X2 - c + truth["p"]).ravel(), (Y2 - c + truth["q"]).ravel()]))
    right = truth["k0"] + truth["k1"] * ndi.map_coordinates(img, [c + uv[1], c + uv[0]], order=interp,
                                                               mode="reflect").reshape(n, n)
    return img, right, int(c), truth


def test_lsm_affine_recovers_geometry_and_radiometry():
    img, right, c, truth = affine_pair()
    r = M.lsm_affine(img, right, (c, c), approx=(c - 3, c + 2), half_window=12, interpolation="cubic")
    for name, value in truth.items():
        tol = {"k0": 0.5, "k1": 0.005}.get(name, 0.003)
        assert r.params[name] == pytest.approx(value, abs=tol), name
    assert r.sigma_p < 0.01 and r.confident
    rb = M.lsm_affine(img, right, (c, c), approx=(c - 3, c + 2), half_window=12)      # bilinear, the book's
    assert abs(rb.p - truth["p"]) < 0.01 and abs(rb.q - truth["q"]) < 0.01


def test_lsm_affine_as_printed_diverges():
    img, right, c, truth = affine_pair()
    with pytest.raises(ConvergenceError) as info:
        M.lsm_affine(img, right, (c, c), approx=(c - 3, c + 2), half_window=12, as_printed=True)
    hist = info.value.history
    assert len(hist) >= 3
    err = [abs(h.x[0] - truth["p"]) + abs(h.x[1] - truth["q"]) for h in hist]
    assert err[-1] > err[0]


def test_lsm_textureless_and_one_directional_texture():
    img = texture()
    flat = img.copy()
    flat[40:80, 40:80] = 50.0
    with pytest.raises(DegenerateGeometryError):
        M.lsm_shift(flat, img, (60, 60), half_window=7)
    stripes = np.tile(np.sin(np.arange(120) * 0.5) * 50 + 100, (120, 1))   # no y gradient at all
    with pytest.raises(DegenerateGeometryError):
        M.lsm_shift(stripes, stripes, (60, 60), approx=(60.3, 60), half_window=7)


@pytest.mark.parametrize("search, template", [((40, 50), (7, 9)), ((300, 280), (31, 25))])
def test_valid_correlation_equals_scipy_signal_in_both_branches(search, template):
    """The direct (small) and FFT (large) branches of the correlation sums = scipy.signal.correlate."""
    from scipy.signal import correlate

    from photolib.matching import _correlate_valid
    rng = np.random.default_rng(7)
    s, t = rng.normal(size=search), rng.normal(size=template)
    np.testing.assert_allclose(_correlate_valid(s, t), correlate(s, t, mode="valid", method="direct"),
                               rtol=1e-10, atol=1e-10)
