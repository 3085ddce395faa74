"""photolib.additional_parameters: the AP models (2)–(4) of Sementsov's thesis against their sympy forms,
orthogonality of (2), the fixed-point inverse, and OpenCV's distortion model as a peer for (4)."""

import numpy as np
import pytest
import sympy as sp

from photolib import additional_parameters as ap
from photolib.derivations import planar_target as D
from photolib.derivations.symbols import f, x, y
from photolib.errors import ConvergenceError

# Table B.1, star calibration (pixel units), as printed (lines 2029–2036)
STARS = {"k1": -7.221e-9, "k2": 1.079e-15, "k3": -1.943e-23, "P1": -1.751e-7, "P2": -1.988e-7}
F_STARS = 3324.848


def _frame_points(n=400, seed=0):
    rng = np.random.default_rng(seed)
    return np.column_stack([rng.uniform(-2456, 2456, n), rng.uniform(-1632, 1632, n)])


def _sympy_fn(model):
    if model == "ebner12":
        sx, sy, params = D.ebner12_symbolic()
        args = (x, y, D.B_GRID) + tuple(params)
    elif model == "brown":
        sx, sy, params = D.brown_symbolic()
        args = (x, y, f) + tuple(params)
    else:
        sx, sy, params = D.photomod_symbolic()
        args = (x, y) + tuple(params)
    return sp.lambdify(args, [sx, sy], "numpy"), sp.Matrix([sx, sy]).jacobian(sp.Matrix(params)), args


@pytest.mark.parametrize("model", ap.MODELS)
def test_models_equal_their_sympy_forms(model):
    rng = np.random.default_rng(1)
    xy = rng.uniform(-2, 2, (30, 2))
    p = rng.normal(0, 0.1, len(ap.parameter_names(model)))
    extra = {"ebner12": {"b": 1.3}, "brown": {"f": 3.0}, "photomod": {}}[model]
    fn, _, _ = _sympy_fn(model)
    ref = np.column_stack(fn(xy[:, 0], xy[:, 1], *extra.values(), *p))
    assert np.allclose(ap.ap_corrections(model, xy, p, **extra), ref, atol=1e-13)
    named = dict(zip(ap.parameter_names(model), p))
    assert np.allclose(ap.ap_corrections(model, xy, named, **extra), ref, atol=1e-13)


@pytest.mark.parametrize("model", ap.MODELS)
def test_basis_equals_the_sympy_jacobian(model):
    rng = np.random.default_rng(2)
    xy = rng.uniform(-2, 2, (10, 2))
    extra = {"ebner12": {"b": 0.7}, "brown": {"f": 2.5}, "photomod": {}}[model]
    _, J, args = _sympy_fn(model)
    jf = sp.lambdify(args[: 2 + len(extra)], J, "numpy")
    B = ap.ap_basis(model, xy, **extra)
    assert B.shape == (10, 2, len(ap.parameter_names(model)))
    for i, (xi, yi) in enumerate(xy):
        assert np.allclose(B[i], np.array(jf(xi, yi, *extra.values()), dtype=float), atol=1e-13)


def test_ebner12_fields_are_orthogonal_on_the_grid():
    b = 1.7
    grid = np.array([(i * b, j * b) for i in (-1, 0, 1) for j in (-1, 0, 1)])
    B = ap.ap_basis("ebner12", grid, b=b)                   # (9, 2, 12)
    G = np.einsum("nci,ncj->ij", B, B)
    off = G - np.diag(np.diag(G))
    assert np.max(np.abs(off)) < 1e-12 * np.max(np.abs(G))
    assert np.all(np.diag(G) > 0)
    # the same from sympy (exact), the corrected and the printed (b_4) set
    assert D.ebner12_gram().is_diagonal() and D.ebner12_gram(printed=True).is_diagonal()


def test_photomod_inverse_round_trip_on_table_b1():
    xy = _frame_points()
    u = ap.invert_ap("photomod", xy, STARS, tol=1e-13)
    assert np.max(np.abs(ap.apply_ap("photomod", u, STARS) - xy)) < 1e-8
    back = ap.invert_ap("photomod", ap.apply_ap("photomod", xy, STARS), STARS, tol=1e-13)
    assert np.max(np.abs(back - xy)) < 1e-8


def test_photomod_against_opencv_distortion():
    """apply_ap of (4) is OpenCV's Brown–Conrady distortion with k_cv = −k·fⁿ, p1_cv = −P2·f, p2_cv = −P1·f
    (normalised coordinates); invert_ap is then cv2.undistortPoints."""
    cv2 = pytest.importorskip("cv2")
    xy = _frame_points(200, seed=3)
    fpx = F_STARS
    dist = np.array([-STARS["k1"] * fpx**2, -STARS["k2"] * fpx**4, -STARS["P2"] * fpx, -STARS["P1"] * fpx,
                     -STARS["k3"] * fpx**6])
    K = np.array([[fpx, 0, 0], [0, fpx, 0], [0, 0, 1.0]])
    obj = np.column_stack([xy / fpx, np.ones(len(xy))])
    projected, _ = cv2.projectPoints(obj, np.zeros(3), np.zeros(3), K, dist)
    assert np.allclose(projected.reshape(-1, 2), ap.apply_ap("photomod", xy, STARS), atol=1e-6)
    measured = ap.apply_ap("photomod", xy, STARS)
    und = cv2.undistortPoints(measured.reshape(-1, 1, 2), K, dist, P=K,
                              criteria=(cv2.TERM_CRITERIA_COUNT | cv2.TERM_CRITERIA_EPS, 100, 1e-14))
    assert np.allclose(und.reshape(-1, 2), ap.invert_ap("photomod", measured, STARS), atol=1e-4)


def test_photomod_radial_curve_of_table_b1():
    """The radial correction along +x with the printed star parameters equals −r(k1r² + k2r⁴ + k3r⁶)."""
    r = np.array([500.0, 1000.0, 2000.0, 2950.0])
    s = ap.photomod(np.column_stack([r, np.zeros(4)]), {k: STARS[k] for k in ("k1", "k2", "k3")})
    expected = -r * (STARS["k1"] * r**2 + STARS["k2"] * r**4 + STARS["k3"] * r**6)
    assert np.allclose(s[:, 0], expected) and np.allclose(s[:, 1], 0)


def test_brown_decentring_is_brown_conrady():
    xy = np.array([[3.0, -2.0]])
    s = ap.brown(xy, {"p1": 0.1, "p2": -0.2}, f=100.0)
    xx, yy = xy[0]
    r2 = xx * xx + yy * yy
    p1, p2 = 0.1, -0.2
    assert np.allclose(s[0], [p1 * (r2 + 2 * xx * xx) + 2 * p2 * xx * yy, 2 * p1 * xx * yy + p2 * (r2 + 2 * yy * yy)])


def test_invert_reports_non_convergence():
    with pytest.raises(ConvergenceError) as err:
        ap.invert_ap("photomod", [[1000.0, 0.0]], {"k1": -3e-6}, max_iter=50)
    assert err.value.history and len(err.value.history) <= 50
    with pytest.raises(ConvergenceError, match="did not converge"):
        ap.invert_ap("photomod", [[1000.0, 0.0]], {"b1": -1.0}, max_iter=20)   # σ = x: u + u = v oscillates


def test_parameter_names_and_zero_parameters():
    assert ap.parameter_names("ebner12") == tuple(f"c{i}" for i in range(1, 13))
    assert len(ap.parameter_names("brown")) == 26
    xy = _frame_points(5)
    for model, extra in (("ebner12", {"b": 1.0}), ("brown", {"f": 10.0}), ("photomod", {})):
        assert np.all(ap.ap_corrections(model, xy, {}, **extra) == 0)
        assert np.allclose(ap.invert_ap(model, xy, {}, **extra), xy)
