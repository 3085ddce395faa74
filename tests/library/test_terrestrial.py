"""Terrestrial stereophotogrammetry (Chapter 11, §11.4–11.9): photolib.terrestrial.

Expected values come from sympy (photolib.derivations.terrestrial), synthetic ground truth
(points projected with photolib.single_image.project), independent formulas (full error
propagation, footprint geometry) and seeded simulations.
"""

import numpy as np
import pytest
import sympy as sp

from photolib import terrestrial as ter
from photolib.camera import ExteriorOrientation, InteriorOrientation
from photolib.derivations import terrestrial as dt
from photolib.image_pair import intersect_rays
from photolib.projective import fundamental_from_orientation, nearest_rotation
from photolib.rotation import rotation_angles, rotation_matrix
from photolib.single_image import project

IO = InteriorOrientation(50.0)


# --- §11.4–11.5 ------------------------------------------------------------------------------------
def test_base_system_axes():
    S1, S2 = np.array([10.0, 20.0, 5.0]), np.array([13.0, 24.0, 6.5])
    s = ter.base_system(S1, S2)
    assert np.allclose(s.axes @ s.axes.T, np.eye(3)) and np.isclose(np.linalg.det(s.axes), 1)
    assert np.allclose(s.to_base([S2]), [[5.0, 0.0, 1.5]])          # horizontal base 5 m, dZ 1.5 m
    assert np.allclose(s.axes[2], [0, 0, 1])
    P = np.random.default_rng(0).normal(size=(5, 3))
    assert np.allclose(s.to_object(s.to_base(P)), P)


def test_normal_case_matrix_is_the_sympy_one():
    A = np.array(dt.normal_case_relations()["A_normal"].tolist(), dtype=float)
    assert np.allclose(ter.case_rotation("normal"), A)
    x, y, f = 3.0, -2.0, 50.0
    assert np.allclose(A @ [x, y, -f], [x, f, y])                    # camera x, y, z ∥ X, Z, −Y


@pytest.mark.parametrize("case,kw", [("deviated", {"deviation": 0.3}), ("tilted", {"tilt": 0.25}),
                                     ("convergent", {"convergence": 0.4})])
def test_case_axes(case, kw):
    a1 = ter.case_rotation(case, 1, **kw) @ [0, 0, -1]
    a2 = ter.case_rotation(case, 2, **kw) @ [0, 0, -1]
    if case == "deviated":                    # both axes horizontal, turned by α from Y
        assert np.allclose(a1, a2) and np.isclose(a1[2], 0) and np.isclose(np.arccos(a1[1]), 0.3)
    elif case == "tilted":                    # parallel, raised by the tilt
        assert np.allclose(a1, a2) and np.isclose(np.arcsin(a1[2]), 0.25)
    else:                                     # axes turned toward each other, angle γ between them
        assert np.isclose(np.arccos(a1 @ a2), 0.4) and a1[0] > 0 > a2[0]
    e1, e2 = ter.case_orientations(case, 5.0, **kw)
    assert np.allclose(e1.matrix, ter.case_rotation(case, 1, **kw))
    assert np.allclose(e2.matrix, ter.case_rotation(case, 2, **kw))


# --- §11.8 ------------------------------------------------------------------------------------------
def test_general_intersection_equals_normal_case_and_truth():
    io = InteriorOrientation(17400.0)                 # pixels, the worked example's PhaseOne
    e1, e2 = ter.case_orientations("normal", 8.0)
    P = np.array([[2.0, 30.0, 1.5], [-4.0, 25.0, -2.0], [7.0, 40.0, 3.0]])
    xy1, xy2 = project(P, e1, io), project(P, e2, io)
    assert np.allclose(ter.base_intersection(xy1, xy2, e1, e2, io), P)                 # (11.8.1)
    assert np.allclose(ter.normal_case_point(xy1[:, 0], xy1[:, 1], xy2[:, 0], 17400.0, 8.0), P)  # (11.8.2)
    assert np.allclose(intersect_rays([xy1, xy2], [e1, e2], io).points, P)


def test_general_intersection_other_cases():
    for case, kw in (("deviated", {"deviation": 0.2}), ("tilted", {"tilt": 0.15}), ("convergent", {"convergence": 0.3})):
        e1, e2 = ter.case_orientations(case, 4.0, **kw)
        P = np.array([[1.0, 20.0, 2.0], [3.0, 22.0, 4.0]])
        assert np.allclose(ter.base_intersection(project(P, e1, IO), project(P, e2, IO), e1, e2, IO), P)


def test_accuracy_corrections():
    base = ter.normal_case_accuracy(30.0, 17400.0, 4640.0, 0.5, 0.5, 0.5)
    tilted = ter.normal_case_accuracy(30.0, 17400.0, 4640.0, 0.5, 0.5, 0.5, tilt=np.pi / 3)
    dev = ter.normal_case_accuracy(30.0, 17400.0, 4640.0, 0.5, 0.5, 0.5, deviation=np.pi / 3)
    assert np.allclose(tilted, np.array(base) * 2)                  # Y/cos 60° = 2Y
    assert np.isclose(dev[1], base[1] * 2) and np.isclose(dev[0], base[0])   # b cos 60° = b/2


def test_monte_carlo_confirms_11_8_4_at_the_centre():
    f, Y, b = 17400.0, 30.0, 4640.0
    B = Y * b / f
    mc = ter.normal_case_monte_carlo(Y, f, B, n=100000, rng=3)
    book = ter.normal_case_accuracy(Y, f, b, 0.5, 0.5, 0.5)
    assert np.allclose(mc, book, rtol=0.02)


def test_monte_carlo_off_centre_shows_the_dropped_term():
    f, Y, b = 17400.0, 30.0, 4640.0
    B = Y * b / f
    X, Z = 6.0, 4.0
    mc = ter.normal_case_monte_carlo(Y, f, B, X=X, Z=Z, n=100000, rng=4)
    book = ter.normal_case_accuracy(Y, f, b, 0.5, 0.5, 0.5)
    p = f * B / Y
    full_X = np.hypot(Y / f * 0.5, X / p * 0.5)                     # first-order, ∂X/∂p = −X/p kept
    assert mc[0] > 1.2 * book[0]
    assert np.isclose(mc[0], full_X, rtol=0.03)


def test_stereo_design_coverage_geometry():
    d = ter.stereo_design(17400.0, (11600, 8700), 30.0)
    # footprints at depth Y of the two normal-case images: [−H_X/2, H_X/2] and [B − H_X/2, B + H_X/2]
    overlap = (d.H_X / 2) - (d.B - d.H_X / 2)
    assert np.isclose(d.stereo_width, overlap) and np.isclose(overlap / d.H_X, 0.6)
    assert np.isclose(d.B / d.H_X, 0.4)
    assert np.isclose(d.H_X, 20.0) and np.isclose(d.H_Z, 15.0)


def test_sympy_normal_case():
    r = dt.normal_case_relations()
    s = r["symbols"]
    assert sp.simplify(r["N_normal"] - s["B_X"] / s["p"]) == 0
    Y = r["XYZ"][1]
    assert sp.simplify(r["dY_dp"] + Y / s["p"]) == 0
    assert sp.simplify(r["dX_dx1"] - Y / s["f"]) == 0


# --- §11.6 ------------------------------------------------------------------------------------------
@pytest.mark.parametrize("kind,k,data", [("distance", 2, True), ("base", 2, True), ("centre_distance", 2, True),
                                         ("vertical", 2, False), ("horizontal", 2, False), ("coplanar", 4, False)])
def test_condition_jacobians_match_finite_differences(kind, k, data):
    rng = np.random.default_rng(5)
    pts = [rng.normal(size=(3, 3)) for _ in range(k)]
    meas = np.array([1.0, 2.0, 3.0]) if data else None
    F, J = ter.condition_equations(kind, pts, meas)
    h = 1e-6
    for c in range(3 * k):
        p_plus = [p.copy() for p in pts]
        p_minus = [p.copy() for p in pts]
        p_plus[c // 3][:, c % 3] += h
        p_minus[c // 3][:, c % 3] -= h
        num = (ter.condition_equations(kind, p_plus, meas)[0] - ter.condition_equations(kind, p_minus, meas)[0]) / (2 * h)
        assert np.allclose(J[:, :, c], num, atol=1e-6)


def test_distance_residual_and_11_6_7():
    Pi, Pj = np.array([[1.0, 2.0, 3.0]]), np.array([[4.0, 6.0, 3.0]])
    F, J = ter.condition_equations("distance", [Pi, Pj], [5.2])
    assert np.isclose(F[0, 0], -0.2)                                 # l_D = D⁰ − D
    assert np.allclose(J[0, 0], np.r_[(Pi - Pj)[0], (Pj - Pi)[0]] / 5.0)


def test_book_plane_condition_is_vacuous_and_the_four_point_one_is_not():
    assert dt.book_plane_determinant() == 0
    rng = np.random.default_rng(1)
    P = rng.normal(size=(4, 3))
    F, _ = ter.condition_equations("coplanar", [P[[0]], P[[1]], P[[2]], P[[3]]])
    assert abs(F[0, 0]) > 1e-3
    n = np.array([0.3, -0.2, 0.9])
    Q = rng.normal(size=(4, 3))
    Q -= np.outer(Q @ n / (n @ n), n)                                # project onto the plane n·x = 0
    F, _ = ter.condition_equations("coplanar", [Q[[0]], Q[[1]], Q[[2]], Q[[3]]])
    assert abs(F[0, 0]) < 1e-12


def test_polar_collinearity_is_collinearity_and_independent_of_distance():
    rng = np.random.default_rng(2)
    w, a, k = np.pi / 2 + 0.05, 0.1, -0.03
    S = np.array([1.0, 2.0, 0.5])
    phi, nu = rng.uniform(-0.3, 0.4, 6), rng.uniform(-0.2, 0.2, 6)
    D = rng.uniform(5, 50, 6)
    P = S + D[:, None] * np.column_stack([np.cos(nu) * np.sin(phi + a), np.cos(nu) * np.cos(phi + a), np.sin(nu)])
    phi2 = phi + a
    eo = ExteriorOrientation(*S, w, a, k, order="wak")
    assert np.allclose(ter.polar_project(phi2, nu, w, a, k, IO), project(P, eo, IO))
    m = dt.polar_collinearity_model(with_distance=True)
    assert sp.simplify(sp.diff(m.residuals[1], dt.D)) == 0


def test_orientation_from_directions_with_noise():
    rng = np.random.default_rng(7)
    true = np.array([np.pi / 2 + 0.08, -0.2, 0.05])
    phi, nu = rng.uniform(-0.6, 0.2, 8), rng.uniform(-0.3, 0.3, 8)
    xy = ter.polar_project(phi, nu, *true, IO) + rng.normal(0, 0.002, (8, 2))
    adj = ter.orientation_from_directions(xy, phi, nu, IO, start=(np.pi / 2, 0.0, 0.0))
    assert np.all(np.abs(adj.x - true) < 4 * adj.std + 1e-9)
    assert np.max(np.abs(adj.x - true)) < 2e-4


# --- §11.7 ------------------------------------------------------------------------------------------
def _two_models(noise, seed=1):
    rng = np.random.default_rng(seed)
    A = rotation_matrix(0.7, -0.4, 2.3, "wak")
    t, shift = 1.7, np.array([3.0, -2.0, 5.0])
    P3 = rng.uniform(-5, 5, (10, 3))
    P1 = shift + t * P3 @ A.T + rng.normal(0, noise, (10, 3))
    return P1, P3, A, t, shift


def test_linear_linking_exact():
    P1, P3, A, t, shift = _two_models(0.0)
    L = ter.link_models_linear(P1, P3)
    assert np.isclose(L.t, t) and np.allclose(L.A, A) and np.allclose(L.shift, shift)
    assert np.allclose(L.apply(P3), P1)
    assert np.allclose(L.C, t * A)


def test_linear_linking_vs_svd_with_noise():
    P1, P3, A, t, shift = _two_models(0.01)
    lin, svd = ter.link_models_linear(P1, P3), ter.link_models_svd(P1, P3)
    # the book's method: start values (t within 0.5 %, A within 5e-3, not exactly orthogonal)
    assert abs(lin.t / t - 1) < 5e-3 and np.abs(lin.A - A).max() < 5e-3
    assert np.abs(lin.A.T @ lin.A - np.eye(3)).max() > 1e-6
    # Umeyama: orthogonal and at least as close
    assert np.allclose(svd.A.T @ svd.A, np.eye(3)) and np.abs(svd.A - A).max() < np.abs(lin.A - A).max()
    assert np.abs(nearest_rotation(lin.A) - A).max() < 5e-3


def test_chaining_reproduces_the_images():
    """(11.7.14)/(11.7.15): image 3 oriented in model 2 → object frame gives the same image points."""
    rng = np.random.default_rng(3)
    link_A, link_t, link_shift = rotation_matrix(0.3, 0.2, -0.5, "wak"), 1.3, np.array([2.0, 1.0, -1.0])
    A0, t0, XS1 = rotation_matrix(1.5, 0.1, 0.2, "wak"), 25.0, np.array([100.0, 200.0, 50.0])
    A3p, S3 = rotation_matrix(1.4, 0.2, 0.1, "wak"), np.array([0.5, -0.3, 0.2])
    eo_m2 = ExteriorOrientation(*S3, *rotation_angles(A3p, "wak"), order="wak")
    P_m2 = S3 + (A3p @ np.column_stack([rng.uniform(-0.3, 0.3, (5, 2)), -np.ones(5)]).T).T * rng.uniform(2, 4, (5, 1))
    xy = project(P_m2, eo_m2, IO)
    A3 = ter.chain_rotation(A0, link_A, A3p)
    XS_model = link_shift + link_t * link_A @ S3                        # centre in the common model
    XS = ter.centre_in_object(XS1, A0, [XS_model], t0)[0]
    P_obj = XS1 + t0 * (link_shift + link_t * P_m2 @ link_A.T) @ A0.T
    eo_obj = ExteriorOrientation(*XS, *rotation_angles(A3, "wak"), order="wak")
    assert np.allclose(project(P_obj, eo_obj, IO), xy)


# --- §11.9 ------------------------------------------------------------------------------------------
def _three_cameras():
    return [ExteriorOrientation(x, 0.0, z, np.pi / 2, a, 0.0, order="wak")
            for x, z, a in ((0.0, 0.0, -0.15), (3.0, 0.0, 0.15), (1.5, 2.5, 0.0))]


def test_three_view_matching_all_correct():
    rng = np.random.default_rng(11)
    eos = _three_cameras()
    P = np.column_stack([rng.uniform(-1, 4, 60), rng.uniform(9, 12, 60), rng.uniform(-1.5, 3, 60)])
    xy = [project(P, e, IO) for e in eos]
    perm2, perm3 = rng.permutation(60), rng.permutation(60)
    xy2, xy3 = xy[1][perm2], xy[2][perm3]
    F = lambda a, b: fundamental_from_orientation(IO, eos[a], IO, eos[b])   # noqa: E731
    m = ter.match_three_views(xy[0] + rng.normal(0, 1e-4, (60, 2)), xy2, xy3, F(0, 1), F(0, 2), F(1, 2), 0.002)
    inv2, inv3 = np.argsort(perm2), np.argsort(perm3)
    assert len(m) >= 58                                              # at most a couple of ambiguous drops
    assert np.all(inv2[m[:, 0]] == m[:, 1]) and np.all(inv3[m[:, 0]] == m[:, 2])


def test_probe_tip_with_noise():
    rng = np.random.default_rng(4)
    eos = _three_cameras()
    marks = np.array([[0.0, 0, 0], [0.15, 0, 0], [0, 0.12, 0], [0.05, 0.05, 0.1], [0.1, -0.05, 0.08]])
    tip = np.array([0.02, 0.03, -0.25])
    R, s = rotation_matrix(0.4, -0.3, 1.1, "wak"), np.array([1.5, 10.0, 0.5])
    obj = s + marks @ R.T
    xy = [project(obj, e, IO) + rng.normal(0, 0.0005, (5, 2)) for e in eos]
    got, pts = ter.probe_tip(xy, eos, IO, marks, tip)
    assert np.linalg.norm(got - (s + R @ tip)) < 2e-3
    assert np.allclose(pts, obj, atol=2e-3)
