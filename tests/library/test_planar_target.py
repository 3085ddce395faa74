"""photolib.planar_target: the planar-target theory of Sementsov's thesis (seed 004), checked against sympy,
scipy and synthetic ground truth."""

import numpy as np
import pytest
import sympy as sp
from scipy.optimize import brentq
from scipy.spatial.transform import Rotation

from photolib import planar_target as pt
from photolib.derivations import planar_target as D
from photolib.derivations.symbols import Zs, alpha, f
from photolib.gnss_centres import rotation_aok

F, ZS = 3100.0, 300.0


def _scipy_A(a, w, k):
    """R_Y(α)R_X(ω)R_Z(κ) with the thesis's sense of α (a₃ = −sin α): scipy's intrinsic Y-X-Z with −α."""
    return Rotation.from_euler("YXZ", [-a, w, k]).as_matrix()


def _plane_grid(a, n=15):
    half = 0.5 * ZS / np.tan(abs(a)) if a else ZS
    g = np.linspace(-half, half, n)
    X, Y = np.meshgrid(g, g)
    return np.column_stack([X.ravel(), Y.ravel(), np.zeros(X.size)])


def test_rotation_is_the_matrix_of_8():
    a = 0.4
    A = rotation_aok(a, 0.0, 0.0)
    assert np.allclose([A[0, 0], A[0, 2], A[2, 0], A[2, 2]], [np.cos(a), -np.sin(a), np.sin(a), np.cos(a)])
    rng = np.random.default_rng(1)
    for w in rng.uniform(-1, 1, (5, 3)):
        assert np.allclose(rotation_aok(*w), _scipy_A(*w), atol=1e-14)


def test_project_agrees_with_an_independent_collinearity():
    rng = np.random.default_rng(2)
    P = np.column_stack([rng.uniform(-50, 50, 20), rng.uniform(-50, 50, 20), rng.uniform(0, 5, 20)])
    S = np.array([3.0, -2.0, 120.0])
    a, w, k = 0.2, -0.1, 0.7
    q = (P - S) @ _scipy_A(a, w, k)
    expected = np.column_stack([10.0 - F * q[:, 0] / q[:, 2], -5.0 - F * q[:, 1] / q[:, 2]])
    assert np.allclose(pt.project(P, S, a, w, k, F, 10.0, -5.0), expected, atol=1e-9)


@pytest.mark.parametrize("alpha_deg", [30.0, -30.0, 60.0, 10.0])
@pytest.mark.parametrize("k", [0.5, 0.9, 1.0, 1.1])
def test_transformed_bundle_images_the_plane_identically(alpha_deg, k):
    a = np.radians(alpha_deg)
    P = _plane_grid(a)
    x0, y0 = 10.0, 10.0
    original = pt.project(P, [0.0, 0.0, ZS], a, 0.0, 0.0, F, x0, y0)
    b = pt.transformed_bundle(a, k, F, ZS)
    transformed = pt.project(P, [b.dX_S, b.dY_S, b.Z_S_prime], b.alpha_prime, 0.0, 0.0, b.f_prime,
                             x0 + b.dx0, y0 + b.dy0)
    assert np.max(np.abs(transformed - original)) < 1e-9
    if k != 1.0:                                   # a genuinely different camera
        assert abs(b.f_prime - F) > 1 and abs(b.dx0) > 1


def test_transformed_bundle_matches_the_sympy_solution():
    a = np.radians(30.0)
    ks = np.array([0.25, 0.5, 1.0, 1.5, 2.0])
    b = pt.transformed_bundle(a, ks, F, ZS)
    sub = D.solution_substitution()
    fn = {s: sp.lambdify((D.ALPHA_P, alpha, f, Zs), sub[s]) for s in (D.DX0, D.DXS, D.ZSP, D.K)}
    ap_ = np.arcsin(ks * np.sin(a))
    assert np.allclose(fn[D.K](ap_, a, F, ZS), ks)
    assert np.allclose(b.dx0, fn[D.DX0](ap_, a, F, ZS), atol=1e-9)
    assert np.allclose(b.dX_S, fn[D.DXS](ap_, a, F, ZS), atol=1e-9)
    assert np.allclose(b.Z_S_prime, fn[D.ZSP](ap_, a, F, ZS), atol=1e-9)
    assert np.allclose(b.alpha_prime, ap_) and np.all(b.dy0 == 0) and np.all(b.dY_S == 0)


def test_solution_makes_9_identical_to_8():
    e8, e9 = D.derived_tilted_plane_8(), D.derived_transformed_bundle_9()
    for sign, expected in ((-1, True), (1, False)):
        sub = D.solution_substitution(sign)
        same = all(sp.simplify((e9[i] + (D.DX0, D.DY0)[i] - e8[i]).subs(sub)) == 0 for i in range(2))
        assert same is expected


def test_family_lies_on_the_corrected_circle():
    for a_deg in (30.0, -45.0, 70.0):
        a = np.radians(a_deg)
        c = pt.centre_locus(a, ZS)
        ks = np.linspace(1e-6, c.k_max, 101)
        b = pt.transformed_bundle(a, ks, F, ZS)
        d = np.hypot(b.dX_S - c.centre[0], b.Z_S_prime - c.centre[1])
        assert np.allclose(d, c.radius, rtol=1e-12)
        assert np.isclose(c.radius, ZS / abs(np.sin(a))) and np.isclose(c.centre[0], -ZS / np.tan(a))
    # the ends named at line 763: (Z_S tan(α/2), 0) for k → 0, the top at k = 1/sin α
    a = np.radians(30.0)
    low = pt.transformed_bundle(a, 1e-12, F, ZS)
    top = pt.transformed_bundle(a, 2.0, F, ZS)
    assert np.isclose(low.dX_S, ZS * np.tan(a / 2)) and abs(low.Z_S_prime) < 1e-9
    assert np.isclose(top.alpha_prime, np.pi / 2) and np.isclose(top.Z_S_prime, ZS / np.sin(a))


def test_printed_circle_misses_the_family():
    a = np.radians(30.0)
    ks = np.array([0.5, 1.0, 1.5])
    b = pt.transformed_bundle(a, ks, F, ZS)
    printed_centre = +ZS / np.tan(a)                      # (18) as printed
    d = np.hypot(b.dX_S - printed_centre, b.Z_S_prime)
    on = np.isclose(d, ZS / np.sin(a))
    assert on.tolist() == [False, True, False]            # only the true centre (k = 1)


@pytest.mark.parametrize("method,a1,a2", [
    ("2.1", 30.0, -30.0), ("2.1", 30.0, 60.0), ("2.1", 20.0, 45.0), ("2.1", -20.0, 45.0),
    ("2.2", 30.0, -30.0), ("2.2", 30.0, 60.0), ("2.2", 20.0, 45.0),
    ("3", 30.0, 30.0), ("3", 20.0, -50.0),
    ("1-f", 30.0, None), ("1-Z_S", 30.0, None), ("1-x0", 30.0, None), ("1-X_S", -40.0, None),
    ("1-alpha", 30.0, None)])
def test_only_root_is_one(method, a1, a2):
    r = pt.condition_roots(method, np.radians(a1), None if a2 is None else np.radians(a2))
    assert len(r.roots) == 1 and abs(r.roots[0] - 1.0) < 1e-12
    # independent: a dense grid (10× finer, offset) and scipy's brentq on each sign change of each row
    grid = np.linspace(1e-7, r.k_max, 40001)
    rows = pt.condition_residual(method, grid, np.radians(a1), None if a2 is None else np.radians(a2))
    args = (np.radians(a1), None if a2 is None else np.radians(a2))
    for j, row in enumerate(rows):
        idx = np.flatnonzero(row[:-1] * row[1:] <= 0)
        roots = {round(brentq(lambda k: float(pt.condition_residual(method, k, *args)[j, 0]), grid[i], grid[i + 1]), 9)
                 for i in idx if row[i] != row[i + 1]}
        assert roots <= {1.0}


def test_condition_residual_method_3_rows_vanish_together_only_at_one():
    k = np.array([0.8, 1.0, 1.2])
    r = pt.condition_residual("3", k, np.radians(30.0), np.radians(30.0))
    assert r.shape == (2, 3) and np.allclose(r[:, 1], 0) and np.all(np.abs(r[:, [0, 2]]) > 1e-3)


def test_gsd_and_permissible_offsets_scale_linearly():
    assert np.isclose(pt.gsd(300.0, 3100.0), 300.0 / 3100.0)
    o1, o2 = pt.permissible_offsets(0.5, 2.0, 3100.0), pt.permissible_offsets(1.0, 20.0, 3100.0)
    assert np.isclose(o2.l_xy / o1.l_xy, 20.0) and np.isclose(o2.l_z / o1.l_z, 20.0)
    assert np.isclose(o1.l_z_px / o1.l_xy_px, (1.7 / 0.4) / (0.4 / 0.6))
    assert np.allclose(pt.gsd([2.0, 20.0], 3100.0), [2 / 3100, 20 / 3100])


def test_star_helpers():
    taus = pt.max_star_exposure(60.0, np.radians([0.0, 60.0, -60.0, 90.0]))
    assert np.allclose(taus[:3], [4.0, 8.0, 8.0]) and np.isinf(taus[3])
    rng = np.random.default_rng(3)
    ra, dec = rng.uniform(0, 2 * np.pi, 50), rng.uniform(-1.5, 1.5, 50)
    e = pt.star_unit_vector(ra, dec)
    assert np.allclose(np.linalg.norm(e, axis=1), 1.0)
    assert np.allclose(np.arcsin(e[:, 2]), dec) and np.allclose(np.mod(np.arctan2(e[:, 1], e[:, 0]), 2 * np.pi), ra)
    assert np.isclose(pt.angular_pixel_size(16.0, 23.4 / 4912), np.degrees(23.4 / 4912 / 16.0) * 3600)


def test_compare_bundles_is_invariant_to_a_rotation_and_agrees_with_scipy():
    rng = np.random.default_rng(4)
    xy = rng.uniform(-2000, 2000, (60, 2))
    u = pt.image_rays(xy, 3300.0)
    R = Rotation.random(random_state=5).as_matrix()
    c = pt.compare_bundles(u, 7.0 * u @ R.T)              # lengths do not matter
    assert c.rms_arcsec < 1e-6 and np.allclose(c.rotation, R.T, atol=1e-12)
    # perturbed bundle: rotation and r.m.s. equal scipy's Wahba solution (Rotation.align_vectors)
    v = pt.image_rays(xy + rng.normal(0, 1.0, xy.shape), 3300.0) @ R.T
    c = pt.compare_bundles(u, v)
    ref, _ = Rotation.align_vectors(u, v)
    assert np.allclose(c.rotation, ref.as_matrix(), atol=1e-10)
    rms = np.sqrt(np.mean(np.sum((u - ref.apply(v)) ** 2, axis=1))) * 180 / np.pi * 3600
    assert np.isclose(c.rms_arcsec, rms, rtol=1e-9)
    # the chord of (5) against the true angle: equal to first order (1 px ≈ 62″)
    ang = np.arccos(np.clip(np.sum(u * (v @ c.rotation.T), axis=1), -1, 1)) * 180 / np.pi * 3600
    assert np.isclose(np.sqrt(np.mean(ang ** 2)), c.rms_arcsec, rtol=1e-7)


def test_image_rays_are_unit_vectors_along_the_image_vector():
    r = pt.image_rays([[30.0, -40.0]], 120.0, 10.0, 0.0)
    assert np.allclose(r, np.array([[20.0, -40.0, -120.0]]) / np.sqrt(20**2 + 40**2 + 120**2))
