"""photolib.rotation (§1.3) against scipy's Rotation, sympy and the book's own statements."""

import numpy as np
import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.spatial.transform import Rotation

from photolib import rotation as rot
from photolib.errors import DegenerateGeometryError, InputError

HALF_PI = np.pi / 2
angle = st.floats(-np.pi, np.pi, allow_nan=False)
tilt = st.floats(-HALF_PI + 1e-9, HALF_PI - 1e-9, allow_nan=False)
near_pole = st.floats(1e-15, 1e-6)   # distance of α from ±90°
sign = st.sampled_from([-1.0, 1.0])
ORDER = st.sampled_from(["kaw", "wak"])


def scipy_matrix(w, a, k, order):
    """Independent construction: intrinsic Euler sequences of scipy."""
    if order == "kaw":        # A_κ A_α A_ω = R_z(κ) R_y(α) R_x(ω)
        return Rotation.from_euler("ZYX", [k, a, w]).as_matrix()
    return Rotation.from_euler("XYZ", [w, a, k]).as_matrix()


@settings(max_examples=200, deadline=None)
@given(angle, tilt, angle, ORDER)
def test_matrix_equals_scipy_intrinsic_euler(w, a, k, order):
    np.testing.assert_allclose(rot.rotation_matrix(w, a, k, order), scipy_matrix(w, a, k, order), atol=1e-15)


def test_elementary_matrices_are_the_books():
    """A_ω, A_α, A_κ as printed (lines 209–217), counter-clockwise, compared with sympy's."""
    t = 0.3
    c, s = np.cos(t), np.sin(t)
    np.testing.assert_allclose(rot.rot_x(t), [[1, 0, 0], [0, c, -s], [0, s, c]])
    np.testing.assert_allclose(rot.rot_y(t), [[c, 0, s], [0, 1, 0], [-s, 0, c]])
    np.testing.assert_allclose(rot.rot_z(t), [[c, -s, 0], [s, c, 0], [0, 0, 1]])
    th = sp.Symbol("t")
    for M, R3 in ((rot.rot_x, sp.rot_axis1), (rot.rot_y, sp.rot_axis2), (rot.rot_z, sp.rot_axis3)):
        # sympy's rot_axisN is the passive (transposed) rotation
        np.testing.assert_allclose(M(t), np.array(R3(th).T.subs(th, t), dtype=float), atol=1e-15)


def test_vectorised_matrix_matches_loop():
    rng = np.random.default_rng(3)
    w, a, k = rng.uniform(-1, 1, (3, 4, 5))
    for order in ("kaw", "wak"):
        A = rot.rotation_matrix(w, a, k, order)
        assert A.shape == (4, 5, 3, 3)
        np.testing.assert_allclose(A[2, 3], rot.rotation_matrix(w[2, 3], a[2, 3], k[2, 3], order))
        back = np.array(rot.rotation_angles(A, order))
        np.testing.assert_allclose(back, [w, a, k], atol=1e-13)


@settings(max_examples=200, deadline=None)
@given(angle, tilt, angle, ORDER)
def test_orthogonal_with_unit_determinant(w, a, k, order):
    A = rot.rotation_matrix(w, a, k, order)
    np.testing.assert_allclose(A.T @ A, np.eye(3), atol=1e-14)
    assert np.linalg.det(A) == pytest.approx(1.0, abs=1e-14)
    assert rot.is_rotation(A)


@settings(max_examples=300, deadline=None)
@given(angle, st.floats(-np.radians(89.0), np.radians(89.0)), angle, ORDER)
def test_angles_round_trip(w, a, k, order):
    back = rot.rotation_angles(rot.rotation_matrix(w, a, k, order), order)
    diff = np.angle(np.exp(1j * (np.array(back) - [w, a, k])))   # modulo 2π
    np.testing.assert_allclose(diff, 0, atol=1e-12)


@settings(max_examples=300, deadline=None)
@given(angle, near_pole, sign, angle, ORDER)
def test_near_gimbal_lock_the_angles_reproduce_the_matrix(w, eps, s, k, order):
    """Within 1e-6 rad of α = ±90° ω and κ are ill-conditioned: compare matrices. The matrix is
    built by scipy and passed through a product with a rotation and its inverse, so that its
    small elements carry ordinary rounding errors."""
    a = s * (HALF_PI - eps)
    A = scipy_matrix(w, a, k, order)
    B = Rotation.from_rotvec([0.3, -0.2, 0.5]).as_matrix()
    A = B @ (B.T @ A)
    try:
        back = rot.rotation_angles(A, order)
    except DegenerateGeometryError:
        assert eps < 1e-11          # only that close may it be declared singular
        back = rot.rotation_angles(A, order, singular="kappa-zero")
    np.testing.assert_allclose(rot.rotation_matrix(*back, order), A, atol=1e-12)
    assert abs(abs(back[1]) - HALF_PI) < 2e-6


@settings(max_examples=100, deadline=None)
@given(angle, sign, angle, ORDER)
def test_exact_gimbal_lock(w, s, k, order):
    A = rot.rotation_matrix(w, s * HALF_PI, k, order)
    with pytest.raises(DegenerateGeometryError, match="gimbal"):
        rot.rotation_angles(A, order)
    back = rot.rotation_angles(A, order, singular="kappa-zero")
    assert back[2] == 0.0
    assert back[1] == pytest.approx(s * HALF_PI, abs=1e-8)
    np.testing.assert_allclose(rot.rotation_matrix(*back, order), A, atol=1e-12)


def test_atan2_keeps_the_quadrant():
    """Plain arctan of (1.3.6)/(1.3.3) would return ω = −60°, κ = 30°; atan2 recovers them."""
    for order in ("kaw", "wak"):
        A = rot.rotation_matrix(np.radians(120), np.radians(20), np.radians(-150), order)
        np.testing.assert_allclose(np.degrees(rot.rotation_angles(A, order)), [120, 20, -150], atol=1e-12)
    A = rot.rotation_matrix(np.radians(120), np.radians(20), np.radians(-150), "kaw")
    naive = np.degrees([np.arctan(A[2, 1] / A[2, 2]), np.arctan(A[1, 0] / A[0, 0])])
    np.testing.assert_allclose(naive, [-60, 30], atol=1e-12)


def test_book_example_orders_differ():
    """ω = 5°, α = −10°, κ = 2°: the book's printed a21 = 0.03437 comes from (1.3.5), not (1.3.2)."""
    w, a, k = np.radians([5, -10, 2])
    assert round(rot.rotation_matrix(w, a, k, "kaw")[1, 0], 5) == 0.03437
    assert round(rot.rotation_matrix(w, a, k, "wak")[1, 0], 5) != 0.03437


quaternion = st.tuples(*[st.floats(-2, 2, allow_nan=False)] * 4).filter(lambda q: np.linalg.norm(q) > 1e-3)


@settings(max_examples=200, deadline=None)
@given(quaternion)
def test_quaternion_matrix_is_scipy_for_unit_quaternions(q):
    q = np.array(q) / np.linalg.norm(q)
    np.testing.assert_allclose(rot.quaternion_matrix(*q), Rotation.from_quat(q).as_matrix(), atol=1e-14)


@settings(max_examples=200, deadline=None)
@given(angle, tilt, angle, ORDER)
def test_matrix_to_quaternion_is_scipy(w, a, k, order):
    A = rot.rotation_matrix(w, a, k, order)
    q = rot.matrix_to_quaternion(A)
    ref = Rotation.from_matrix(A).as_quat()
    ref = -ref if ref[3] < 0 else ref
    assert q[3] >= 0
    # q and −q are the same rotation; at d = 0 the sign is not fixed by d ≥ 0
    assert min(np.abs(q - ref).max(), np.abs(q + ref).max()) < 1e-12
    np.testing.assert_allclose(rot.quaternion_matrix(*q), A, atol=1e-14)


@settings(max_examples=200, deadline=None)
@given(angle, st.floats(-np.radians(89.0), np.radians(89.0)), angle)
def test_quaternion_to_angles_agrees_with_rotation_angles(w, a, k):
    """The book's relations after (1.3.7) give the κ–α–ω angles (1.3.6) of the same matrix."""
    A = rot.rotation_matrix(w, a, k, "kaw")
    q = Rotation.from_matrix(A).as_quat() * 3.7          # any scale m: the relations are normalised
    diff = np.array(rot.quaternion_to_angles(*q)) - rot.rotation_angles(A, "kaw")
    np.testing.assert_allclose(np.angle(np.exp(1j * diff)), 0, atol=1e-12)      # ±180° are one angle


@settings(max_examples=100, deadline=None)
@given(quaternion)
def test_unnormalised_quaternion_scales_the_matrix(q):
    """(1.3.7) carries the scale m = a² + b² + c² + d²: AᵀA = m²E and det A = m³."""
    A = rot.quaternion_matrix(*q)
    m = rot.quaternion_scale(*q)
    np.testing.assert_allclose(A.T @ A, m ** 2 * np.eye(3), atol=1e-12 * max(1, m ** 2))
    assert np.linalg.det(A) == pytest.approx(m ** 3, rel=1e-10, abs=1e-12)


def test_quaternion_scale_symbolically():
    a, b, c, d = sp.symbols("a b c d", real=True)
    A = sp.Matrix([  # (1.3.7) as printed, lines 283–285
        [d**2 + a**2 - b**2 - c**2, 2 * (a*b - c*d), 2 * (a*c + b*d)],
        [2 * (a*b + c*d), d**2 - a**2 + b**2 - c**2, 2 * (b*c - a*d)],
        [2 * (a*c - b*d), 2 * (b*c + a*d), d**2 - a**2 - b**2 + c**2]])
    m = a**2 + b**2 + c**2 + d**2
    assert sp.expand(A.T * A - m**2 * sp.eye(3)) == sp.zeros(3, 3)
    assert sp.expand(A.det() - m**3) == 0
    # the numeric implementation is this matrix
    vals = (0.3, -0.5, 0.7, 1.1)
    np.testing.assert_allclose(rot.quaternion_matrix(*vals),
                               np.array(A.subs(dict(zip((a, b, c, d), vals))), dtype=float), atol=1e-15)


def test_bad_input_is_rejected():
    with pytest.raises(InputError, match="order"):
        rot.rotation_matrix(0, 0, 0, "xyz")
    with pytest.raises(InputError, match="3×3"):
        rot.rotation_angles(np.eye(2))
    with pytest.raises(InputError, match="NaN"):
        rot.rotation_angles(np.full((3, 3), np.nan))
    with pytest.raises(InputError, match="singular"):
        rot.rotation_angles(rot.rotation_matrix(0, HALF_PI, 0), singular="nonsense")
    with pytest.raises(InputError, match="non-zero"):
        rot.quaternion_to_angles(0, 0, 0, 0)
    with pytest.raises(InputError, match="one 3×3"):
        rot.matrix_to_quaternion(np.stack([np.eye(3)] * 2))
    assert not rot.is_rotation(np.diag([1.0, 1.0, -1.0]))
