"""Single-image geometry of Chapter 1 (§1.1, §1.4–§1.7): photolib.single_image.

Expected values come from sympy (the collinearity model of photolib.derivations, derivatives of
(1.5.4)), from an independent ray/plane intersection built on scipy's Rotation, or from synthetic
ground truth (round trips, the nadir point of a known tilt) — never from the code under test.
"""

import numpy as np
import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.spatial.transform import Rotation

from photolib import derivations
from photolib.camera import ExteriorOrientation, InteriorOrientation
from photolib.errors import DegenerateGeometryError, InputError
from photolib.rotation import rotation_matrix
from photolib.single_image import (
    camera_coordinates, horizontal_image_scale, horizontal_to_tilted, image_to_ground,
    planimetric_error_from_height_error, principal_to_nadir_distance, project, tilted_to_horizontal,
)

ORDERS = ["kaw", "wak"]
DISTORTING = InteriorOrientation(f=100.0, x0=0.12, y0=-0.08, k1=-2e-6, k2=3e-10, k3=-1e-14, p1=4e-7, p2=-3e-7)
IDEAL = InteriorOrientation(f=100.0, x0=0.12, y0=-0.08)

angle = st.floats(-0.35, 0.35)          # |angle| < 20°: a near-vertical aerial image
offset = st.floats(-200.0, 200.0)


def scipy_matrix(omega, alpha, kappa, order):
    """A from scipy's intrinsic Euler angles: 'kaw' = Rz(κ)Ry(α)Rx(ω), 'wak' = Rx(ω)Ry(α)Rz(κ)."""
    if order == "kaw":
        return Rotation.from_euler("ZYX", [kappa, alpha, omega]).as_matrix()
    return Rotation.from_euler("XYZ", [omega, alpha, kappa]).as_matrix()


def ground_points(rng, n=25, centre=(500.0, 300.0)):
    return np.column_stack([centre[0] + rng.uniform(-400, 400, n), centre[1] + rng.uniform(-400, 400, n),
                            rng.uniform(-20, 80, n)])


# --- project ↔ image_to_ground ----------------------------------------------------------------
@pytest.mark.parametrize("order", ORDERS)
@pytest.mark.parametrize("io", [IDEAL, DISTORTING], ids=["ideal", "distortion"])
@settings(max_examples=40, deadline=None)
@given(w=angle, a=angle, k=st.floats(-np.pi, np.pi), dx=offset, dy=offset, seed=st.integers(0, 2**16))
def test_project_and_image_to_ground_are_inverse(order, io, w, a, k, dx, dy, seed):
    rng = np.random.default_rng(seed)
    eo = ExteriorOrientation(500.0 + dx, 300.0 + dy, 1500.0, w, a, k, order)
    XYZ = ground_points(rng)
    xy = project(XYZ, eo, io)
    back = image_to_ground(xy, XYZ[:, 2], eo, io)
    np.testing.assert_allclose(back, XYZ, atol=1e-9, rtol=0)
    # and the other way round: image → ground → image
    again = project(back, eo, io)
    np.testing.assert_allclose(again, xy, atol=1e-9, rtol=0)


@pytest.mark.parametrize("order", ORDERS)
def test_project_satisfies_the_sympy_collinearity_model(order):
    """F_x = F_y = 0 of (1.8.2) (built from (1.4.12) in sympy) at the projected coordinates."""
    rng = np.random.default_rng(1)
    residual_fn, _ = derivations.collinearity_model(order).compile()
    io = IDEAL
    for _ in range(5):
        eo = ExteriorOrientation(*rng.uniform(-100, 100, 2), 900.0, *rng.uniform(-0.3, 0.3, 3), order=order)
        XYZ = ground_points(rng, 10, centre=(0.0, 0.0))
        xy = project(XYZ, eo, io)
        res = residual_fn(*eo.vector, XYZ[:, 0], XYZ[:, 1], XYZ[:, 2], xy[:, 0], xy[:, 1], io.f, io.x0, io.y0)
        np.testing.assert_allclose(res, 0.0, atol=1e-10)
        # and a wrong image point does not satisfy it
        res = residual_fn(*eo.vector, XYZ[:, 0], XYZ[:, 1], XYZ[:, 2], xy[:, 0] + 0.01, xy[:, 1], io.f, io.x0, io.y0)
        assert np.all(np.abs(res[0] + 0.01) < 1e-10)


@pytest.mark.parametrize("order", ORDERS)
def test_image_to_ground_equals_an_independent_ray_plane_intersection(order):
    rng = np.random.default_rng(2)
    for _ in range(5):
        w, a, k = rng.uniform(-0.3, 0.3, 3)
        S = np.array([rng.uniform(-50, 50), rng.uniform(-50, 50), 1200.0])
        eo = ExteriorOrientation(*S, w, a, k, order=order)
        xy = rng.uniform(-40, 40, (20, 2))
        Zplane = rng.uniform(-30, 60, 20)
        R = scipy_matrix(w, a, k, order)
        d = np.column_stack([xy[:, 0] - IDEAL.x0, xy[:, 1] - IDEAL.y0, np.full(20, -IDEAL.f)]) @ R.T
        normal = np.array([0.0, 0.0, 1.0])
        t = (Zplane - S @ normal) / (d @ normal)
        expected = S + t[:, None] * d
        np.testing.assert_allclose(image_to_ground(xy, Zplane, eo, IDEAL), expected, atol=1e-9)


def test_camera_coordinates_use_the_transpose_of_A():
    eo = ExteriorOrientation(10.0, 20.0, 500.0, 0.1, -0.2, 0.3)
    R = scipy_matrix(0.1, -0.2, 0.3, "kaw")
    P = np.array([[40.0, -70.0, 12.0]])
    np.testing.assert_allclose(camera_coordinates(P, eo)[0], R.T @ (P[0] - eo.center), atol=1e-12)


# --- §1.5 horizontal image -------------------------------------------------------------------
def test_horizontal_image_reduces_to_1_5_5_and_scale_f_over_H():
    f, H = 153.0, 1800.0                               # mm, m
    eo = ExteriorOrientation(0.0, 0.0, 0.0)            # S at the origin, ω = α = κ = 0
    io = InteriorOrientation(f)
    XY = np.array([[120.0, -340.0], [-700.0, 55.0], [0.0, 0.0]])
    XYZ = np.column_stack([XY, np.full(3, -H)])        # H = −Z
    np.testing.assert_allclose(project(XYZ, eo, io), f / H * XY, rtol=1e-14, atol=1e-12)   # (1.5.5)
    np.testing.assert_allclose(image_to_ground(f / H * XY, -H, eo, io)[:, :2], XY, atol=1e-9)  # (1.5.4)
    # 1/m = f/H: a ground distance D shows as D·f/H on the image
    m = horizontal_image_scale(f, H)
    assert m == pytest.approx(H / (f / 1000.0))
    d_image = np.linalg.norm(np.diff(project(XYZ[:2], eo, io), axis=0)) / 1000.0   # m
    d_ground = np.linalg.norm(np.diff(XY[:2], axis=0))
    assert d_ground / d_image == pytest.approx(m, rel=1e-12)


def test_1_6_1_is_the_derivative_of_1_5_4_in_magnitude():
    x_, f_, Z_, dZ_ = sp.symbols("x f Z Delta_Z", real=True)
    X_154 = -Z_ / f_ * x_                              # (1.5.4), S at the origin
    dX = sp.diff(X_154, Z_) * dZ_                      # exact: (1.5.4) is linear in Z
    assert sp.simplify(sp.Abs(dX) - sp.Abs(x_ / f_ * dZ_)) == 0
    fn = sp.lambdify((x_, f_, dZ_), sp.Abs(dX))
    rng = np.random.default_rng(3)
    x, y = rng.uniform(-40, 40, (2, 30))
    gx, gy, gr = planimetric_error_from_height_error(x, y, 50.0, 10.0)
    np.testing.assert_allclose(np.abs(gx), fn(x, 50.0, 10.0), rtol=1e-14)
    np.testing.assert_allclose(np.abs(gy), fn(y, 50.0, 10.0), rtol=1e-14)
    np.testing.assert_allclose(gr, np.hypot(fn(x, 50.0, 10.0), fn(y, 50.0, 10.0)), rtol=1e-14)


def test_1_6_1_equals_the_shift_of_the_intersection_with_a_raised_plane():
    """Synthetic: intersect the same rays of a horizontal image with Z and Z + ΔZ."""
    eo, io = ExteriorOrientation(100.0, 200.0, 600.0), InteriorOrientation(50.0)
    xy = np.random.default_rng(4).uniform(-30, 30, (10, 2))
    shift = image_to_ground(xy, 10.0, eo, io) - image_to_ground(xy, 0.0, eo, io)
    _, _, dR = planimetric_error_from_height_error(xy[:, 0], xy[:, 1], 50.0, 10.0)
    np.testing.assert_allclose(np.hypot(shift[:, 0], shift[:, 1]), dR, rtol=1e-12)


# --- §1.1 nadir point --------------------------------------------------------------------------
@pytest.mark.parametrize("order", ORDERS)
def test_nadir_point_lies_f_tan_tilt_from_the_principal_point(order):
    rng = np.random.default_rng(5)
    io = InteriorOrientation(f=80.0, x0=0.3, y0=-0.2)
    for _ in range(10):
        w, a, k = rng.uniform(-0.4, 0.4, 3)
        eo = ExteriorOrientation(10.0, 20.0, 1000.0, w, a, k, order)
        below = np.array([eo.Xs, eo.Ys, 0.0])           # the ground point N vertically below S
        n = project(below, eo, io)[0]
        tilt = np.arccos(eo.matrix[2, 2])               # angle between the camera axis and the vertical
        assert np.hypot(n[0] - io.x0, n[1] - io.y0) == pytest.approx(
            float(principal_to_nadir_distance(io.f, tilt)), rel=1e-12)


def test_nadir_for_a_pure_longitudinal_tilt_is_on_the_x_axis():
    io = InteriorOrientation(f=100.0)
    eo = ExteriorOrientation.from_degrees(0, 0, 2000.0, 0, 15.0, 0)
    n = project([0.0, 0.0, 0.0], eo, io)[0]
    np.testing.assert_allclose(n, [100.0 * np.tan(np.radians(15.0)), 0.0], atol=1e-12)


# --- §1.7 tilted ↔ horizontal ------------------------------------------------------------------
@pytest.mark.parametrize("order", ORDERS)
@settings(max_examples=40, deadline=None)
@given(w=angle, a=angle, k=st.floats(-np.pi, np.pi))
def test_1_7_5_and_1_7_10_are_mutually_inverse(order, w, a, k):
    A = rotation_matrix(w, a, k, order)
    xy = np.random.default_rng(6).uniform(-40, 40, (30, 2))
    h = tilted_to_horizontal(xy, A, 100.0, 120.0, 0.1, -0.1)
    np.testing.assert_allclose(horizontal_to_tilted(h, A, 100.0, 120.0, 0.1, -0.1), xy, atol=1e-9)


@pytest.mark.parametrize("order", ORDERS)
def test_rectification_equals_projection_of_a_flat_scene(order):
    """A tilted and a horizontal camera at the same S see the same ground point at m and m⁰."""
    rng = np.random.default_rng(7)
    w, a, k = rng.uniform(-0.3, 0.3, 3)
    io_t, io_h = InteriorOrientation(100.0, 0.2, -0.1), InteriorOrientation(150.0)
    tilted = ExteriorOrientation(50.0, -30.0, 1000.0, w, a, k, order)
    horizontal = ExteriorOrientation(50.0, -30.0, 1000.0, order=order)
    XYZ = np.column_stack([rng.uniform(-300, 300, (20, 2)), np.zeros(20)])
    m, m0 = project(XYZ, tilted, io_t), project(XYZ, horizontal, io_h)
    np.testing.assert_allclose(tilted_to_horizontal(m, tilted.matrix, 100.0, 150.0, 0.2, -0.1), m0, atol=1e-9)
    np.testing.assert_allclose(horizontal_to_tilted(m0, tilted.matrix, 100.0, 150.0, 0.2, -0.1), m, atol=1e-9)


# --- bad input --------------------------------------------------------------------------------
EO = ExteriorOrientation(0.0, 0.0, 1000.0)
IO = InteriorOrientation(100.0)


@pytest.mark.parametrize("call", [
    lambda: project([[1.0, np.nan, 0.0]], EO, IO),
    lambda: project([[1.0, 2.0]], EO, IO),
    lambda: project(np.zeros((2, 2, 3)), EO, IO),
    lambda: image_to_ground([[np.inf, 0.0]], 0.0, EO, IO),
    lambda: image_to_ground([[1.0, 2.0, 3.0]], 0.0, EO, IO),
    lambda: image_to_ground([[1.0, 2.0]], np.nan, EO, IO),
    lambda: image_to_ground([[1.0, 2.0], [3.0, 4.0]], [0.0, 1.0, 2.0], EO, IO),
    lambda: InteriorOrientation(0.0),
    lambda: InteriorOrientation(-50.0),
    lambda: ExteriorOrientation(0.0, np.nan, 1.0),
    lambda: horizontal_image_scale(0.0, 1000.0),
    lambda: horizontal_image_scale(100.0, -5.0),
    lambda: planimetric_error_from_height_error(1.0, 1.0, 0.0, 10.0),
    lambda: planimetric_error_from_height_error(np.nan, 1.0, 50.0, 10.0),
    lambda: principal_to_nadir_distance(-1.0, 0.1),
    lambda: principal_to_nadir_distance(100.0, np.pi / 2),
    lambda: tilted_to_horizontal([[1.0, 2.0]], np.eye(2), 100.0, 100.0),
    lambda: tilted_to_horizontal([[1.0, 2.0]], np.eye(3), 0.0, 100.0),
    lambda: horizontal_to_tilted([[1.0, 2.0]], np.eye(3), 100.0, -1.0),
    lambda: horizontal_to_tilted([[np.nan, 2.0]], np.eye(3), 100.0, 100.0),
], ids=lambda c: "")
def test_bad_input_raises_input_error(call):
    with pytest.raises(InputError):
        call()


def test_points_behind_the_camera_raise():
    with pytest.raises(DegenerateGeometryError, match="front"):
        project([[0.0, 0.0, 0.0], [0.0, 0.0, 1500.0]], EO, IO)    # the second is above S
    with pytest.raises(DegenerateGeometryError):
        image_to_ground([[1.0, 1.0]], 2000.0, EO, IO)             # plane above S: behind the camera
    with pytest.raises(DegenerateGeometryError):
        # a camera looking horizontally: the ray of the principal point never meets Z = 0
        image_to_ground([[0.0, 0.0]], 0.0, ExteriorOrientation(0.0, 0.0, 1000.0, 0.0, np.pi / 2, 0.0), IO)
    A = rotation_matrix(0.0, np.radians(80.0), 0.0)
    with pytest.raises(DegenerateGeometryError):
        tilted_to_horizontal([[-90.0, 0.0]], A, 100.0, 100.0)     # above the true horizon
