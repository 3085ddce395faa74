"""Tests of photolib.ransac (Chapter 5, §5.10): synthetic pairs with known orientation and 30 %
planted outliers, compared with OpenCV's findFundamentalMat / findEssentialMat on the same data.

OpenCV conventions: x₂ᵀFx₁ = 0 (our layout "x2Fx1"); findEssentialMat with focal = 1, pp = (0, 0)
takes normalised coordinates r″ = ((x − x₀)/f, (y − y₀)/f) and uses Nistér's closed-form five-point
solver (ours: the book's iterative five-point relative orientation); both thresholds are
Sampson/epipolar distances (OpenCV's in the units of the points it is given).
"""

import numpy as np
import pytest

from photolib import ransac as rs
from photolib.errors import ConvergenceError, DegenerateGeometryError, InputError
from photolib.projective import essential_from_orientation, fundamental_matrix, sampson_distance
from photolib.synthetic import stereo_pair

cv2 = pytest.importorskip("cv2")

SIGMA = 0.002          # mm image noise
THRESHOLD = 0.01       # mm


def pair_with_outliers(n=60, share=0.3, seed=0):
    p = stereo_pair(n, seed=seed, angle_spread_deg=3.0, sigma=SIGMA)
    rng = np.random.default_rng(100 + seed)
    bad = rng.choice(n, int(round(share * n)), replace=False)
    xy2 = p.xy2.copy()
    offs = rng.uniform(0.2, 3.0, (len(bad), 2)) * rng.choice([-1, 1], (len(bad), 2))
    xy2[bad] += offs
    truth = np.ones(n, bool); truth[bad] = False
    return p, xy2, truth


def same_up_to_sign(A, B):
    A, B = A / np.linalg.norm(A), B / np.linalg.norm(B)
    return min(np.linalg.norm(A - B), np.linalg.norm(A + B))


def test_iterations_needed_formula():
    assert rs.iterations_needed(0.7, 5, 0.99) == int(np.ceil(np.log(0.01) / np.log(1 - 0.7 ** 5)))
    assert rs.iterations_needed(1.0, 8) == 0


def test_relative_orientation_ransac_recovers_orientation_and_outliers():
    p, xy2, truth = pair_with_outliers()
    r = rs.ransac_relative_orientation(p.xy1, xy2, p.io, threshold=THRESHOLD, rng=3)
    assert np.array_equal(r.inliers, truth)
    assert r.iterations <= rs.iterations_needed(0.7 - 0.05, 5, 0.99) + 5
    ro = r.model
    A_true = p.eo1.matrix.T @ p.eo2.matrix
    assert np.allclose(ro.A1.T @ ro.A2, A_true, atol=2e-4)
    b_true = p.eo1.matrix.T @ (p.eo2.center - p.eo1.center)
    assert np.allclose(ro.base_direction, b_true / np.linalg.norm(b_true), atol=2e-3)


def test_essential_ransac_against_opencv_and_truth():
    p, xy2, truth = pair_with_outliers(seed=1)
    r = rs.ransac_essential(p.xy1, xy2, p.io, threshold=THRESHOLD, rng=0)
    E_true = essential_from_orientation(p.eo1, p.eo2)
    assert np.array_equal(r.inliers, truth)
    assert same_up_to_sign(r.model, E_true) < 2e-3
    n1 = (p.xy1 - [p.io.x0, p.io.y0]) / p.io.f
    n2 = (xy2 - [p.io.x0, p.io.y0]) / p.io.f
    E_cv, mask = cv2.findEssentialMat(n1, n2, focal=1.0, pp=(0.0, 0.0), method=cv2.RANSAC, prob=0.999,
                                      threshold=THRESHOLD / p.io.f)
    E_cv = E_cv[:3]
    assert np.mean(mask.ravel().astype(bool) == truth) >= 0.95
    assert same_up_to_sign(E_cv, E_true) < 5e-3
    assert same_up_to_sign(r.model, E_true) <= same_up_to_sign(E_cv, E_true) + 1e-3


def test_fundamental_ransac_against_opencv():
    p, xy2, truth = pair_with_outliers(seed=2)
    r = rs.ransac_fundamental_matrix(p.xy1, xy2, threshold=THRESHOLD, rng=0)
    assert np.array_equal(r.inliers, truth)
    F_cv, mask = cv2.findFundamentalMat(p.xy1, xy2, cv2.FM_RANSAC, THRESHOLD, 0.999)
    assert np.mean(mask.ravel().astype(bool) == truth) >= 0.95
    # both F explain the noise-free true correspondences to a fraction of the threshold
    for F in (r.model, F_cv):
        d = np.abs(sampson_distance(F, p.xy1_true[truth], p.xy2_true[truth]))
        assert np.median(d) < 3 * SIGMA
    # and agree with the eight-point solution on the true inliers
    F_ref = fundamental_matrix(p.xy1[truth], xy2[truth])
    assert same_up_to_sign(r.model, F_ref) < 1e-9


def test_seeded_and_deterministic():
    p, xy2, _ = pair_with_outliers(seed=3)
    a = rs.ransac_fundamental_matrix(p.xy1, xy2, THRESHOLD, rng=5)
    b = rs.ransac_fundamental_matrix(p.xy1, xy2, THRESHOLD, rng=5)
    assert a.iterations == b.iterations and np.array_equal(a.model, b.model)


def test_adaptive_iterations_without_outliers():
    x = np.arange(20.0)
    r = rs.ransac(np.c_[x, 3 * x - 1], lambda s: np.polyfit(s[:, 0], s[:, 1], 1),
                  lambda m, d: np.abs(np.polyval(m, d[:, 0]) - d[:, 1]), 2, 1e-6)
    assert r.iterations == 1 and r.n_inliers == 20


def test_errors_too_few_degenerate_no_consensus():
    fit = lambda s: np.polyfit(s[:, 0], s[:, 1], 1)          # noqa: E731
    res = lambda m, d: np.abs(np.polyval(m, d[:, 0]) - d[:, 1])  # noqa: E731
    with pytest.raises(InputError, match="fewer"):
        rs.ransac(np.zeros((1, 2)), fit, res, 2, 0.1)

    def degenerate(s):
        raise DegenerateGeometryError("collinear")
    with pytest.raises(DegenerateGeometryError, match="all"):
        rs.ransac(np.random.default_rng(0).normal(size=(10, 2)), degenerate, res, 2, 0.1, max_iterations=20)
    rnd = np.random.default_rng(1).uniform(0, 100, (30, 2))
    with pytest.raises(ConvergenceError, match="consensus") as info:
        rs.ransac(rnd, fit, res, 2, 1e-9, max_iterations=50)
    assert len(info.value.history) == 50
