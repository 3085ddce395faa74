"""Tests of photolib.gnss_centres — the GNSS-centres paper (Dobrynin & Pimshina, seed 001).

Truth comes from synthetic pairs (known angles and ground points), from sympy, and from the
independent Chapter 2 route of photolib.image_pair (relative orientation + model + similarity).
"""

import numpy as np
import pytest

from photolib import derivations as D
from photolib import gnss_centres as G
from photolib import image_pair as IP
from photolib.camera import InteriorOrientation
from photolib.errors import ConvergenceError, DegenerateGeometryError, InputError

ARCSEC = np.radians(1 / 3600)


@pytest.mark.parametrize("az", [0.0, 90.0, 30.0, 135.0, 170.0])
def test_noise_free_recovery(az):
    pair = G.synthetic_pair(az, seed=7)
    model = G.build_model(*pair.args)
    assert model.orientation.adjustment.converged
    assert np.max(np.abs(model.orientation.angles - pair.angles)) < 1e-6 * ARCSEC
    assert np.max(np.abs(model.points - pair.ground)) < 1e-6
    assert model.orientation.iterations <= 8


def test_rotation_matches_printed_6_and_is_orthonormal():
    rng = np.random.default_rng(1)
    for a, w, k in rng.uniform(-1, 1, (5, 3)):
        A = G.rotation_aok(a, w, k)
        P = np.array(D.printed_gnss_direction_cosines().subs({D.alpha: a, D.omega: w, D.chi: k}), dtype=float)
        assert np.allclose(A, P, atol=1e-14)
        assert np.allclose(A @ A.T, np.eye(3), atol=1e-14) and np.isclose(np.linalg.det(A), 1.0)


@pytest.mark.parametrize("az", [0.0, 60.0])
def test_jacobian_matches_finite_differences(az):
    pair = G.synthetic_pair(az, seed=3)
    p = pair.angles + 0.01
    args = pair.args
    B, L = G.correction_equations(p, *args)
    h = 1e-6
    for j in range(6):
        e = np.zeros(6)
        e[j] = h
        Lp = G.correction_equations(p + e, *args)[1]
        Lm = G.correction_equations(p - e, *args)[1]
        fd = (Lp - Lm) / (2 * h)
        assert np.allclose(B[:, j], fd, rtol=1e-6, atol=1e-6 * np.abs(fd).max())


def test_printed_jacobian_differs_where_the_paper_errs():
    pair = G.synthetic_pair(10.0, seed=3)
    Bd, _ = G.correction_equations(pair.angles, *pair.args)
    Bp, _ = G.correction_equations(pair.angles, *pair.args, partials="printed")
    n = len(pair.xy1)
    cop_d, cop_p = Bd[:n], Bp[:n]
    same = np.isclose(cop_d, cop_p, rtol=1e-9, atol=0).all(axis=0)
    # a, c, m as printed are right; b (via printed A, B), d, e are wrong
    assert same.tolist() == [True, False, True, False, False, True]
    # (9): d' (row l_x of image 1, column alpha1) has the opposite sign
    assert np.allclose(Bp[n + 1, 0], -Bd[n + 1, 0])


@pytest.mark.parametrize("az", [0.0, 5.0, 175.0])
def test_printed_partials_fail_north_south(az):
    pair = G.synthetic_pair(az, seed=0)
    with pytest.raises(ConvergenceError):
        G.orient_pair(*pair.args, partials="printed", tol=1e-9, max_iter=30)
    h = G.iteration_history(*pair.args, partials="printed", tol=1e-9, max_iter=30)
    assert not h.converged and h.iterations == 30
    # the common α about the north-south base stays wrong by more than a degree
    assert np.max(np.abs(h.angles - pair.angles)) > np.radians(0.5)


def test_printed_option_is_explicit_and_validated():
    pair = G.synthetic_pair(45.0, seed=0)
    assert G.orient_pair(*pair.args).partials == "derived"
    with pytest.raises(InputError, match="partials"):
        G.orient_pair(*pair.args, partials="book")


def test_intersection_zero_over_zero_cases():
    for az, bad_all, good in ((0.0, 1, 0), (90.0, 0, 1)):         # (0-based form index)
        pair = G.synthetic_pair(az, seed=4, level=True)
        r1 = G.image_space_vectors(pair.xy1, pair.angles[:3], pair.f)
        r2 = G.image_space_vectors(pair.xy2, pair.angles[3:], pair.f)
        num, den = G.intersection_forms(r1, r2, pair.S2 - pair.S1)
        size = np.linalg.norm(r1, axis=1) * np.linalg.norm(r2, axis=1)
        assert np.all(np.abs(den[:, bad_all]) < 1e-12 * size)
        assert np.all(np.abs(num[:, bad_all]) < 1e-9 * np.abs(num).max())
        assert np.all(np.abs(den[:, 2][[1, 4, 7]]) < 1e-12 * size[[1, 4, 7]])     # points under the flight line
        N_true = (pair.ground[:, 2] - pair.S1[2]) / r1[:, 2]
        assert np.allclose(num[:, good] / den[:, good], N_true, rtol=1e-12)
        with pytest.raises(DegenerateGeometryError, match="divides by ~0"):
            G.space_intersection(pair.xy1, pair.xy2, pair.S1, pair.S2, pair.angles, pair.f, form=bad_all + 1)
        with pytest.raises(DegenerateGeometryError):
            G.space_intersection(pair.xy1, pair.xy2, pair.S1, pair.S2, pair.angles, pair.f, form=3)
        P = G.space_intersection(pair.xy1, pair.xy2, pair.S1, pair.S2, pair.angles, pair.f)
        assert np.allclose(P, pair.ground, atol=1e-8)


def test_cross_check_with_image_pair_relative_orientation():
    """Chapter 2 route: relative orientation + model + 7-parameter similarity on the same pair.

    The geodetic frame is left-handed, so the model is compared with the points in the
    right-handed image-space frame (ΔY, ΔX, ΔZ)."""
    pair = G.synthetic_pair(30.0, seed=3)
    io = InteriorOrientation(f=pair.f)
    ro = IP.relative_orientation(pair.xy1, pair.xy2, io, system="dependent")
    model = IP.build_model(pair.xy1, pair.xy2, ro, io)
    T = IP.absolute_orientation(model.points, G.geodetic_to_image_frame(pair.ground))
    assert np.nanmax(np.abs(T.residuals)) < 1e-6
    assert np.isclose(T.t * np.linalg.norm(ro.base), np.linalg.norm(pair.S2 - pair.S1), rtol=1e-9)
    ours = G.orient_pair(*pair.args)
    A1, A2 = G.rotation_aok(*ours.angles[:3]), G.rotation_aok(*ours.angles[3:])
    assert np.allclose(A1.T @ A2, ro.A1.T @ ro.A2, atol=1e-12)         # the same relative rotation
    P = G.space_intersection(pair.xy1, pair.xy2, pair.S1, pair.S2, ours.angles, pair.f)
    assert np.allclose(G.geodetic_to_image_frame(P), T.apply(model.points), atol=1e-6)


def test_initial_chi_rule_and_degenerate_base():
    S1 = np.array([0.0, 0.0, 1000.0])
    for az, chi in ((30.0, 60.0), (120.0, 330.0), (0.0, 90.0), (90.0, 0.0)):
        S2 = S1 + [np.cos(np.radians(az)), np.sin(np.radians(az)), 0.0]
        assert np.isclose(np.degrees(G.initial_chi(S1, S2)), chi)
    with pytest.raises(DegenerateGeometryError, match="vertical"):
        G.initial_chi(S1, S1 + [0, 0, 10.0])
    with pytest.raises(DegenerateGeometryError, match="coincide"):
        G.initial_chi(S1, S1)


def test_bad_input():
    pair = G.synthetic_pair(45.0, seed=0)
    xy1, xy2, S1, S2, C, c1, c2, f, x0, y0 = pair.args
    with pytest.raises(InputError, match="five"):
        G.orient_pair(xy1[:4], xy2[:4], S1, S2, C, c1, c2, f)
    with pytest.raises(InputError, match="control point"):
        G.orient_pair(xy1, xy2, S1, S2, np.zeros((0, 3)), np.zeros((0, 2)), np.zeros((0, 2)), f)
    bad = xy1.copy()
    bad[2, 0] = np.nan
    with pytest.raises(InputError):
        G.orient_pair(bad, xy2, S1, S2, C, c1, c2, f)
    with pytest.raises(InputError, match="image 2"):
        G.orient_pair(xy1, xy2[:-1], S1, S2, C, c1, c2, f)
    with pytest.raises(InputError, match="f must be positive"):
        G.orient_pair(xy1, xy2, S1, S2, C, c1, c2, -100.0)
    with pytest.raises(InputError, match="centre S2"):
        G.orient_pair(xy1, xy2, S1, [1.0, np.inf, 2.0], C, c1, c2, f)
    with pytest.raises(DegenerateGeometryError, match="coincide"):
        G.orient_pair(xy1, xy2, S1, S1, C, c1, c2, f)
    with pytest.raises(InputError, match="6 angles"):
        G.coplanarity_residuals(pair.angles[:5], xy1, xy2, S1, S2, f)


def test_coplanarity_zero_for_true_angles_and_one_control_point_fixes_sixth_angle():
    pair = G.synthetic_pair(75.0, seed=2)
    phi = G.coplanarity_residuals(pair.angles, pair.xy1, pair.xy2, pair.S1, pair.S2, pair.f)
    assert np.max(np.abs(phi)) < 1e-6
