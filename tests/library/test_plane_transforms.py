"""Tests of photolib.plane_transforms (Hanzl §2.5, seed lines 261–311).

Expected values come from synthetic ground truth, from sympy (the decomposition), and from
independent implementations: scikit-image's transform estimators, numpy.linalg.lstsq and
scipy.optimize.least_squares.
"""

import dataclasses
import math

import numpy as np
import pytest
import sympy as sp
from scipy.optimize import least_squares
from skimage import transform as skt

from photolib import interior, projective
from photolib import plane_transforms as pt
from photolib.errors import DegenerateGeometryError

RNG_SEED = 20260512

# synthetic ground truth per kind (parameters in PARAMETER_NAMES order)
TRUTH = {
    "congruent": [0.7, 12.5, -4.0],
    "similarity": [1.2 * math.cos(-0.4), 1.2 * math.sin(-0.4), 3.0, 7.0],
    "affine": [1.01, 0.03, 5.0, -0.02, 0.97, -3.0],
    "projective": [1.1, 0.05, 3.0, -0.04, 0.95, -2.0, 2e-4, -1e-4],
    "bilinear": [2.0, 1.01, 0.02, 1e-4, -1.0, -0.03, 0.99, -2e-4],
    "polynomial": [1.0, 1.02, 0.01, 1e-4, -2e-4, 3e-4, -2.0, -0.02, 0.98, 2e-4, 1e-4, -1e-4],
}


def _src(n, seed=RNG_SEED):
    rng = np.random.default_rng(seed)
    return rng.uniform(-100.0, 100.0, (n, 2))


def _sk(cls, src, dst, **kw):
    if hasattr(cls, "from_estimate"):
        return cls.from_estimate(src, dst, **kw)
    t = cls()
    assert t.estimate(src, dst, **kw)
    return t


# --- Hanzl's counts ---------------------------------------------------------------------------------
def test_parameter_counts_and_minimum_points_are_hanzls():
    # Hanzl §2.5: 3, 4, 6 parameters (lines 265, 271, 275), 8 for the collinear (287), 8 for the
    # bilinear and 12 for the 2nd-degree polynomial (counted from 293 and 297);
    # minimum identical points 2, 2, 3, 4, 4, 6 (line 301)
    assert pt.N_PARAMETERS == {"congruent": 3, "similarity": 4, "affine": 6, "projective": 8, "bilinear": 8,
                               "polynomial": 12}
    assert pt.MIN_POINTS == {"congruent": 2, "similarity": 2, "affine": 3, "projective": 4, "bilinear": 4,
                             "polynomial": 6}


# --- exact recovery of synthetic parameters ----------------------------------------------------------
@pytest.mark.parametrize("kind", pt.KINDS)
@pytest.mark.parametrize("extra", [0, 8])
def test_exact_recovery(kind, extra):
    n = pt.MIN_POINTS[kind] + extra
    src = _src(n)
    truth = pt.PlaneTransform(kind, TRUTH[kind])
    dst = truth.apply(src)
    fit = pt.fit_plane_transform(src, dst, kind)
    assert fit.kind == kind
    np.testing.assert_allclose(fit.parameters, TRUTH[kind], rtol=1e-8, atol=1e-10)
    assert fit.dof == 2 * n - pt.N_PARAMETERS[kind]
    assert np.abs(fit.residuals).max() < 1e-8
    if fit.dof == 0:
        assert math.isnan(fit.sigma0)


def test_collinear_alias():
    src = _src(5)
    dst = pt.PlaneTransform("projective", TRUTH["projective"]).apply(src)
    assert pt.fit_plane_transform(src, dst, "collinear").kind == "projective"


def test_apply_forms_are_hanzls():
    # the printed forms, written out independently of the module
    x, y = 3.0, -2.0
    a = 0.3
    assert np.allclose(pt.PlaneTransform("congruent", [a, 1.0, 2.0]).apply([x, y]),
                       [math.cos(a) * x - math.sin(a) * y + 1.0, math.sin(a) * x + math.cos(a) * y + 2.0])
    p = TRUTH["projective"]
    w = p[6] * x + p[7] * y + 1
    assert np.allclose(pt.PlaneTransform("projective", p).apply([x, y]),
                       [(p[0] * x + p[1] * y + p[2]) / w, (p[3] * x + p[4] * y + p[5]) / w])
    b = TRUTH["bilinear"]
    assert np.allclose(pt.PlaneTransform("bilinear", b).apply([x, y]),
                       [b[0] + b[1] * x + b[2] * y + b[3] * x * y, b[4] + b[5] * x + b[6] * y + b[7] * x * y])
    c = TRUTH["polynomial"]
    mono = [1, x, y, x * x, y * y, x * y]
    assert np.allclose(pt.PlaneTransform("polynomial", c).apply([x, y]),
                       [np.dot(c[:6], mono), np.dot(c[6:], mono)])


# --- the affine decomposition ------------------------------------------------------------------------
def test_decomposition_symbolic():
    qx, qy = sp.symbols("q_x q_y", positive=True)
    al, da = sp.symbols("alpha delta_alpha", real=True)
    A = sp.Matrix([[qx * sp.cos(al), -qy * sp.sin(al + da)], [qx * sp.sin(al), qy * sp.cos(al + da)]])
    # rotation · shear · scales
    R = sp.Matrix([[sp.cos(al), -sp.sin(al)], [sp.sin(al), sp.cos(al)]])
    S = sp.Matrix([[1, -sp.sin(da)], [0, sp.cos(da)]])
    assert sp.simplify(R * S * sp.diag(qx, qy) - A) == sp.zeros(2, 2)
    # Hanzl line 285
    assert sp.simplify(sp.sqrt(A[0, 0] ** 2 + A[1, 0] ** 2) - qx) == 0
    assert sp.simplify(sp.sqrt(A[0, 1] ** 2 + A[1, 1] ** 2) - qy) == 0
    assert sp.simplify(A[1, 0] / A[0, 0] - sp.tan(al)) == 0
    assert sp.simplify(-A[0, 1] / A[1, 1] - sp.tan(al + da)) == 0


@pytest.mark.parametrize("qx,qy,alpha,dalpha", [(1.002, 0.998, 0.01, 1e-4), (2.0, 0.5, 2.8, -0.3),
                                                  (0.7, 1.3, -2.5, 0.9), (1.0, 1.0, math.pi, 0.0)])
def test_decomposition_round_trip(qx, qy, alpha, dalpha):
    M = pt.affine_from_decomposition(qx, qy, alpha, dalpha, 4.0, -5.0)
    d = pt.affine_decomposition(M)
    got = [d.q_x, d.q_y, d.alpha, d.delta_alpha, d.tx, d.ty]
    np.testing.assert_allclose(got, [qx, qy, alpha, dalpha, 4.0, -5.0], atol=1e-12)
    np.testing.assert_allclose(pt.affine_from_decomposition(*got), M, atol=1e-12)


def test_decomposition_of_fitted_affine():
    M = pt.affine_from_decomposition(1.003, 0.996, 0.2, 0.001, 10.0, -20.0)
    src = _src(4)
    dst = src @ M[:, :2].T + M[:, 2]
    d = pt.fit_plane_transform(src, dst, "affine").decomposition
    np.testing.assert_allclose([d.q_x, d.q_y, d.alpha, d.delta_alpha, d.tx, d.ty],
                               [1.003, 0.996, 0.2, 0.001, 10.0, -20.0], atol=1e-10)
    s = pt.PlaneTransform("similarity", TRUTH["similarity"]).decomposition
    np.testing.assert_allclose([s.q_x, s.q_y, s.alpha, s.delta_alpha], [1.2, 1.2, -0.4, 0.0], atol=1e-12)
    assert pt.PlaneTransform("bilinear", TRUTH["bilinear"]).decomposition is None


# --- independent implementations --------------------------------------------------------------------
SK = {"congruent": skt.EuclideanTransform, "similarity": skt.SimilarityTransform, "affine": skt.AffineTransform,
      "projective": skt.ProjectiveTransform}


@pytest.mark.parametrize("kind", list(SK))
def test_against_skimage_exact(kind):
    src = _src(12)
    dst = pt.PlaneTransform(kind, TRUTH[kind]).apply(src)
    sk = _sk(SK[kind], src, dst)
    fit = pt.fit_plane_transform(src, dst, kind)
    np.testing.assert_allclose(fit.matrix / fit.matrix[2, 2], sk.params / sk.params[2, 2], rtol=1e-7, atol=1e-9)


def test_polynomial_against_skimage_exact():
    src = _src(12)
    dst = pt.PlaneTransform("polynomial", TRUTH["polynomial"]).apply(src)
    sk = _sk(skt.PolynomialTransform, src, dst, order=2)
    # skimage order per row: 1, x, y, x², xy, y²; Hanzl: 1, x, y, x², y², xy
    fit = pt.fit_plane_transform(src, dst, "polynomial")
    mine = fit.parameters.reshape(2, 6)[:, [0, 1, 2, 3, 5, 4]]
    np.testing.assert_allclose(mine, sk.params, rtol=1e-6, atol=1e-10)


@pytest.mark.parametrize("kind", ["congruent", "similarity"])
def test_against_skimage_noisy(kind):
    # Umeyama's closed form (skimage) is the least-squares optimum of these two models
    src = _src(30)
    dst = pt.PlaneTransform(kind, TRUTH[kind]).apply(src) + np.random.default_rng(3).normal(0, 0.05, (30, 2))
    sk = _sk(SK[kind], src, dst)
    fit = pt.fit_plane_transform(src, dst, kind)
    np.testing.assert_allclose(fit.matrix, sk.params, rtol=1e-9, atol=1e-9)


@pytest.mark.parametrize("kind", ["affine", "bilinear", "polynomial"])
def test_linear_kinds_against_lstsq(kind):
    src = _src(40)
    rng = np.random.default_rng(5)
    dst = pt.PlaneTransform(kind, TRUTH[kind]).apply(src) + rng.normal(0, 0.02, (40, 2))
    x, y = src[:, 0], src[:, 1]
    one = np.ones_like(x)
    cols = {"affine": [x, y, one], "bilinear": [one, x, y, x * y],
            "polynomial": [one, x, y, x * x, y * y, x * y]}[kind]
    M = np.column_stack(cols)
    cx = np.linalg.lstsq(M, dst[:, 0], rcond=None)[0]
    cy = np.linalg.lstsq(M, dst[:, 1], rcond=None)[0]
    fit = pt.fit_plane_transform(src, dst, kind)
    np.testing.assert_allclose(fit.parameters, np.concatenate([cx, cy]), rtol=1e-7, atol=1e-11)
    V = np.column_stack([M @ cx, M @ cy]) - dst
    np.testing.assert_allclose(fit.residuals, V, atol=1e-9)
    np.testing.assert_allclose(fit.sigma0, math.sqrt((V ** 2).sum() / (80 - pt.N_PARAMETERS[kind])), rtol=1e-9)


@pytest.mark.parametrize("kind", ["congruent", "projective"])
def test_nonlinear_kinds_against_scipy(kind):
    src = _src(25)
    dst = pt.PlaneTransform(kind, TRUTH[kind]).apply(src) + np.random.default_rng(7).normal(0, 0.03, (25, 2))

    def f(p):
        return (pt.PlaneTransform(kind, p).apply(src) - dst).ravel()

    ref = least_squares(f, TRUTH[kind], xtol=1e-15, ftol=1e-15, gtol=1e-15, x_scale="jac")
    fit = pt.fit_plane_transform(src, dst, kind)
    np.testing.assert_allclose(fit.apply(src), pt.PlaneTransform(kind, ref.x).apply(src), atol=1e-8)
    np.testing.assert_allclose(fit.residuals.ravel(), ref.fun, atol=1e-8)


def test_reuses_existing_fits():
    src = _src(9)
    dst = pt.PlaneTransform("affine", TRUTH["affine"]).apply(src) + np.random.default_rng(2).normal(0, 0.01, (9, 2))
    a = interior.fit_affine(src, dst)
    fit = pt.fit_plane_transform(src, dst, "affine")
    np.testing.assert_allclose(fit.parameters, [a.a1, a.a2, a.a0, a.b1, a.b2, a.b0], rtol=1e-12)
    assert fit.sigma0 == pytest.approx(a.mu, rel=1e-12)
    h = projective.homography_lsq(src, dst)
    fit = pt.fit_plane_transform(src, dst, "projective")
    np.testing.assert_allclose(fit.parameters, h.H.ravel()[:8], rtol=1e-12)


# --- minimum counts and degenerate geometry ---------------------------------------------------------
@pytest.mark.parametrize("kind", pt.KINDS)
def test_too_few_points(kind):
    n = pt.MIN_POINTS[kind] - 1
    src = _src(n)
    with pytest.raises(DegenerateGeometryError, match=f"at least {pt.MIN_POINTS[kind]} identical points"):
        pt.fit_plane_transform(src, src + 1.0, kind)


@pytest.mark.parametrize("kind", ["affine", "projective", "bilinear", "polynomial"])
def test_collinear_points(kind):
    t = np.linspace(0.0, 10.0, 8)
    src = np.column_stack([t, 2 * t + 1])
    with pytest.raises(DegenerateGeometryError, match="collinear"):
        pt.fit_plane_transform(src, src + 1.0, kind)


@pytest.mark.parametrize("kind", ["congruent", "similarity"])
def test_collinear_points_suffice_for_rigid_kinds(kind):
    t = np.linspace(0.0, 10.0, 5)
    src = np.column_stack([t, 2 * t + 1])
    dst = pt.PlaneTransform(kind, TRUTH[kind]).apply(src)
    np.testing.assert_allclose(pt.fit_plane_transform(src, dst, kind).parameters, TRUTH[kind], atol=1e-9)


def test_polynomial_points_on_a_conic_are_degenerate():
    ang = np.linspace(0, 2 * np.pi, 7)[:-1]
    src = 50 * np.column_stack([np.cos(ang), np.sin(ang)])
    with pytest.raises(DegenerateGeometryError):
        pt.fit_plane_transform(src, src + 1.0, "polynomial")


def test_projective_three_of_four_collinear():
    src = np.array([[0.0, 0.0], [1.0, 0.0], [2.0, 0.0], [0.0, 1.0]])
    with pytest.raises(DegenerateGeometryError):
        pt.fit_plane_transform(src, src * 2.0, "projective")


# --- noise: σ₀ estimates the noise -------------------------------------------------------------------
@pytest.mark.parametrize("kind", pt.KINDS)
def test_sigma0_estimates_noise(kind):
    n, sigma = 300, 0.01
    src = _src(n, seed=11)
    dst = pt.PlaneTransform(kind, TRUTH[kind]).apply(src) + np.random.default_rng(13).normal(0, sigma, (n, 2))
    fit = pt.fit_plane_transform(src, dst, kind)
    # the relative s.d. of σ̂ is about 1/√(2·dof) ≈ 2.9 %; 12 % is four of them
    assert fit.sigma0 == pytest.approx(sigma, rel=0.12)
    assert np.all(np.isfinite(fit.std)) and fit.Q.shape == (pt.N_PARAMETERS[kind],) * 2


def test_weights_scale_sigma0():
    src = _src(20)
    dst = pt.PlaneTransform("similarity", TRUTH["similarity"]).apply(src)
    dst = dst + np.random.default_rng(1).normal(0, 0.01, dst.shape)
    a = pt.fit_plane_transform(src, dst, "similarity")
    b = pt.fit_plane_transform(src, dst, "similarity", weights=np.full(20, 4.0))
    np.testing.assert_allclose(a.parameters, b.parameters, rtol=1e-12)
    assert b.sigma0 == pytest.approx(2 * a.sigma0, rel=1e-12)


def test_frozen():
    t = pt.PlaneTransform("affine", TRUTH["affine"])
    with pytest.raises(dataclasses.FrozenInstanceError):
        t.kind = "similarity"
    with pytest.raises(ValueError):
        t.parameters[0] = 5.0


# --- Hanzl's claims (lines 287, 301) -------------------------------------------------------------------
def _cross_ratio(p):
    d = lambda i, j: np.linalg.norm(p[i] - p[j])  # noqa: E731
    return d(0, 2) * d(1, 3) / (d(1, 2) * d(0, 3))


def test_projective_keeps_the_cross_ratio_only():
    # line 287: the collinear transformation keeps the cross-ratio, not the division ratio
    t = np.array([0.0, 1.0, 3.0, 7.0])
    line = np.column_stack([10 + 5 * t, -4 + 3 * t])
    proj = pt.PlaneTransform("projective", [1.0, 0.1, 2.0, 0.05, 0.9, -1.0, 0.02, -0.01])
    img = proj.apply(line)
    assert _cross_ratio(img) == pytest.approx(_cross_ratio(line), rel=1e-12)
    ratio = lambda p: np.linalg.norm(p[1] - p[0]) / np.linalg.norm(p[2] - p[1])  # noqa: E731
    assert abs(ratio(img) - ratio(line)) > 1e-2
    aff = pt.PlaneTransform("affine", TRUTH["affine"]).apply(line)
    assert ratio(aff) == pytest.approx(ratio(line), rel=1e-12)


def test_error_in_one_point_hidden_without_redundancy():
    # line 301: with three points the affine transformation absorbs an error of one point
    # (no redundancy), the similarity transformation shows it in the residuals
    src = np.array([[-100.0, -100.0], [100.0, -100.0], [100.0, 100.0]])
    dst = pt.PlaneTransform("similarity", TRUTH["similarity"]).apply(src)
    dst[2] += [0.05, 0.03]
    aff = pt.fit_plane_transform(src, dst, "affine")
    sim = pt.fit_plane_transform(src, dst, "similarity")
    assert aff.dof == 0 and np.abs(aff.residuals).max() < 1e-10
    assert sim.dof == 2 and np.abs(sim.residuals).max() > 0.01
