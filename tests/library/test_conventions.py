"""photolib.conventions: every conversion both ways, against published formulas, scipy and OpenCV."""

import cv2
import numpy as np
import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.spatial.transform import Rotation

from photolib import conventions as cv
from photolib import rotation as rot
from photolib.camera import ExteriorOrientation, InteriorOrientation, correct_distortion
from photolib.errors import DegenerateGeometryError, InputError
from photolib.single_image import project

angle = st.floats(-np.pi, np.pi, allow_nan=False)
tilt = st.floats(-np.radians(89.9), np.radians(89.9), allow_nan=False)
CONV = st.sampled_from(cv.CONVENTIONS)


def wrapped(a):
    return np.angle(np.exp(1j * np.asarray(a)))


# --- rotation conventions -----------------------------------------------------------------------
@settings(max_examples=300, deadline=None)
@given(angle, tilt, angle, CONV, CONV)
def test_convert_angles_both_ways(w, a, k, source, target):
    A = cv.camera_to_object_matrix(w, a, k, source)
    there = cv.convert_angles(w, a, k, source, target)
    np.testing.assert_allclose(cv.camera_to_object_matrix(*there, target), A, atol=1e-12)
    back = cv.convert_angles(*there, target, source)
    np.testing.assert_allclose(wrapped(np.array(back) - [w, a, k]), 0, atol=1e-9)


@settings(max_examples=200, deadline=None)
@given(angle, tilt, angle)
def test_named_conversions_are_inverse(w, a, k):
    pairs = [(cv.wak_to_kaw, cv.kaw_to_wak)]
    for order in ("kaw", "wak"):
        pairs += [(lambda *x, o=order: cv.hanzl_to_book(*x, order=o), lambda *x, o=order: cv.book_to_hanzl(*x, order=o)),
                  (lambda *x, o=order: cv.western_to_book(*x, order=o),
                   lambda *x, o=order: cv.book_to_western(*x, order=o))]
    for there, back in pairs:
        np.testing.assert_allclose(wrapped(np.array(back(*there(w, a, k))) - [w, a, k]), 0, atol=1e-9)
    # ω–α–κ, Hanzl and Wolf's ω–φ–κ are the same three numbers
    np.testing.assert_allclose(wrapped(np.array(cv.hanzl_to_book(w, a, k, "wak")) - [w, a, k]), 0, atol=1e-12)
    np.testing.assert_allclose(wrapped(np.array(cv.western_to_book(w, a, k, "wak")) - [w, a, k]), 0, atol=1e-12)


def test_vectorised_conversion():
    rng = np.random.default_rng(7)
    w, a, k = rng.uniform(-1.2, 1.2, (3, 50))
    out = np.array(cv.wak_to_kaw(w, a, k))
    assert out.shape == (3, 50)
    np.testing.assert_allclose(out[:, 17], cv.wak_to_kaw(w[17], a[17], k[17]))


def test_hanzl_matrix_is_his_printed_product():
    """Hanzl §2.2 writes R = R_ω R_φ R_κ with counter-clockwise elementary matrices and X = R x.
    Its elements (from his step equations) equal the book's (1.3.2) — except his printed r32,
    whose sign is a misprint: the product gives sin ω cos κ + cos ω sin φ sin κ."""
    w, p, k = 0.4, -0.3, 1.1
    c, s = np.cos, np.sin
    R = cv.hanzl_matrix(w, p, k)
    printed_r32 = s(w) * c(k) - c(w) * s(p) * s(k)
    product_r32 = s(w) * c(k) + c(w) * s(p) * s(k)
    assert R[2, 1] == pytest.approx(product_r32) and R[2, 1] != pytest.approx(printed_r32)
    np.testing.assert_allclose(R, rot.rotation_matrix(w, p, k, "wak"), atol=1e-15)


@settings(max_examples=200, deadline=None)
@given(angle, tilt, angle)
def test_western_matrix_against_published_elements(w, p, k):
    """The element formulas of M as published by Wolf & Dewitt, *Elements of Photogrammetry*
    (appendix on rotation matrices) and the ASPRS *Manual of Photogrammetry*."""
    c, s = np.cos, np.sin
    M = np.array([
        [c(p) * c(k), s(w) * s(p) * c(k) + c(w) * s(k), -c(w) * s(p) * c(k) + s(w) * s(k)],
        [-c(p) * s(k), -s(w) * s(p) * s(k) + c(w) * c(k), c(w) * s(p) * s(k) + s(w) * c(k)],
        [s(p), -s(w) * c(p), c(w) * c(p)],
    ])
    np.testing.assert_allclose(cv.western_matrix(w, p, k), M, atol=1e-15)
    np.testing.assert_allclose(M, rot.rotation_matrix(w, p, k, "wak").T, atol=1e-15)   # M = Aᵀ
    np.testing.assert_allclose(wrapped(np.array(cv.western_angles(M)) - [w, p, k]), 0, atol=1e-9)


def test_western_collinearity_equals_book_projection():
    """Wolf's x = x₀ − f (m11 ΔX + m12 ΔY + m13 ΔZ)/(m31 ΔX + m32 ΔY + m33 ΔZ) is (1.4.12)."""
    eo = ExteriorOrientation.from_degrees(500, 800, 1200, 4, -3, 70, order="wak")
    io = InteriorOrientation(153.0, 0.02, -0.01)
    XYZ = np.array([[450.0, 760, 30], [560, 850, 5], [520, 790, 60]])
    M = cv.western_matrix(eo.omega, eo.alpha, eo.kappa)
    d = (XYZ - eo.center) @ M.T
    xy = np.column_stack([io.x0 - io.f * d[:, 0] / d[:, 2], io.y0 - io.f * d[:, 1] / d[:, 2]])
    np.testing.assert_allclose(project(XYZ, eo, io), xy, atol=1e-12)


# --- quaternions ---------------------------------------------------------------------------------
@settings(max_examples=200, deadline=None)
@given(angle, tilt, angle, st.sampled_from(["kaw", "wak"]))
def test_quaternion_from_angles_is_scipy(w, a, k, order):
    q = cv.quaternion_from_angles(w, a, k, order)
    seq, ang = ("ZYX", [k, a, w]) if order == "kaw" else ("XYZ", [w, a, k])
    ref = Rotation.from_euler(seq, ang).as_quat()          # scipy order [x, y, z, w] = (a, b, c, d)
    assert min(np.abs(q - ref).max(), np.abs(q + ref).max()) < 1e-12
    np.testing.assert_allclose(rot.quaternion_matrix(*q), rot.rotation_matrix(w, a, k, order), atol=1e-14)
    back = cv.angles_from_quaternion(5.0 * q, order)
    np.testing.assert_allclose(wrapped(np.array(back) - [w, a, k]), 0, atol=1e-9)
    if q[3] > 1e-6:       # at d = 0 the sign of q is not fixed by d ≥ 0
        np.testing.assert_allclose(cv.quaternion_of_matrix(rot.rotation_matrix(w, a, k, order)), q, atol=1e-12)


def test_quaternion_product_composes_matrices():
    rng = np.random.default_rng(1)
    p, q = Rotation.random(2, random_state=rng).as_quat()
    np.testing.assert_allclose(rot.quaternion_matrix(*cv.quaternion_product(p, q)),
                               rot.quaternion_matrix(*p) @ rot.quaternion_matrix(*q), atol=1e-14)
    ref = (Rotation.from_quat(p) * Rotation.from_quat(q)).as_quat(canonical=False)
    pq = cv.quaternion_product(p, q)
    assert min(np.abs(pq - ref).max(), np.abs(pq + ref).max()) < 1e-14


# --- OpenCV --------------------------------------------------------------------------------------
eo_strategy = st.builds(
    lambda X, Y, Z, w, a, k, o: ExteriorOrientation(X, Y, Z, w, a, k, o),
    st.floats(-1e4, 1e4), st.floats(-1e4, 1e4), st.floats(500, 3000),
    st.floats(-0.3, 0.3), st.floats(-0.3, 0.3), angle, st.sampled_from(["kaw", "wak"]))


def scene(eo, n=25, seed=0):
    """Object points on the ground around the nadir of a near-vertical camera."""
    rng = np.random.default_rng(seed)
    H = eo.Zs
    XYZ = np.column_stack([eo.Xs + rng.uniform(-0.3, 0.3, n) * H, eo.Ys + rng.uniform(-0.3, 0.3, n) * H,
                           rng.uniform(0, 0.05, n) * H])
    return XYZ


@settings(max_examples=60, deadline=None)
@given(eo_strategy, st.floats(50, 300), st.floats(-1, 1), st.floats(-1, 1))
def test_cv2_project_points_equals_book_projection(eo, f, x0, y0):
    io = InteriorOrientation(f, x0, y0)
    XYZ = scene(eo)
    rvec, tvec = cv.eo_to_rvec(eo)
    uv, _ = cv2.projectPoints(XYZ, rvec, tvec, cv.camera_matrix(io), None)
    np.testing.assert_allclose(cv.image_to_opencv(project(XYZ, eo, io)), uv.reshape(-1, 2), atol=1e-9)
    # the same with (R, t) through cv2.Rodrigues, and back
    R, t = cv.eo_to_opencv(eo)
    np.testing.assert_allclose(cv2.Rodrigues(rvec)[0], R, atol=1e-12)
    np.testing.assert_allclose(cv.opencv_to_image(uv.reshape(-1, 2)), project(XYZ, eo, io), atol=1e-9)


@settings(max_examples=200, deadline=None)
@given(eo_strategy, st.sampled_from(["kaw", "wak"]))
def test_opencv_round_trip(eo, order):
    R, t = cv.eo_to_opencv(eo)
    back = cv.opencv_to_eo(R, t, order=order)
    assert back.order == order
    np.testing.assert_allclose(back.center, eo.center, atol=1e-8)
    np.testing.assert_allclose(back.matrix, eo.matrix, atol=1e-12)
    if order == eo.order:
        np.testing.assert_allclose(wrapped(back.vector[3:] - eo.vector[3:]), 0, atol=1e-9)
    back2 = cv.opencv_to_eo(cv.matrix_to_rvec(R), t, order=eo.order)
    np.testing.assert_allclose(back2.matrix, eo.matrix, atol=1e-12)


def test_rvec_against_cv2_rodrigues():
    """matrix_to_rvec equals cv2.Rodrigues away from 180°. A near-vertical book camera is a
    rotation by ≈180° about x in OpenCV terms (diag(1, −1, −1)); there cv2.Rodrigues(R) loses
    about half the digits (√eps ≈ 1e-8), so the round trip through it is checked loosely."""
    rng = np.random.default_rng(5)
    for R in Rotation.random(20, random_state=rng).as_matrix():
        if np.linalg.norm(Rotation.from_matrix(R).as_rotvec()) < 3.0:
            np.testing.assert_allclose(cv.matrix_to_rvec(R), cv2.Rodrigues(R)[0].ravel(), atol=1e-12)
        np.testing.assert_allclose(cv.rvec_to_matrix(cv.matrix_to_rvec(R)), R, atol=1e-14)
    R, _ = cv.eo_to_opencv(ExteriorOrientation(0.0, 0.0, 500.0, 6e-8, 0.0, 0.0))
    assert np.abs(cv2.Rodrigues(cv2.Rodrigues(R)[0])[0] - R).max() > 1e-9           # OpenCV's loss
    assert np.abs(cv.rvec_to_matrix(cv.matrix_to_rvec(R)) - R).max() < 1e-15       # scipy keeps it


def test_decompose_projection_matrix_agrees():
    eo = ExteriorOrientation.from_degrees(1200.0, -300.0, 1500.0, 3.0, -5.0, 40.0)
    io = InteriorOrientation(120.0, 0.4, -0.25)
    P = cv.opencv_projection_matrix(eo, io)
    K, R, C, *_ = cv2.decomposeProjectionMatrix(P)
    K = K / K[2, 2]
    np.testing.assert_allclose(K, cv.camera_matrix(io), atol=1e-9)
    np.testing.assert_allclose(R, cv.eo_to_opencv(eo)[0], atol=1e-12)
    np.testing.assert_allclose((C[:3] / C[3]).ravel(), eo.center, atol=1e-6)
    back = cv.opencv_to_eo(R, -R @ (C[:3] / C[3]).ravel())
    np.testing.assert_allclose(back.vector, eo.vector, atol=1e-9)


def test_opencv_camera_axes():
    """OpenCV's camera looks along +z with y down: a point straight below a level camera has
    X_cv = (0, 0, H); the book's camera looks along −z with y up."""
    eo = ExteriorOrientation(0.0, 0.0, 1000.0)
    R, t = cv.eo_to_opencv(eo)
    np.testing.assert_allclose(R @ [0, 0, 0] + t, [0, 0, 1000])
    np.testing.assert_allclose(R @ [0, 10, 0] + t, [0, -10, 1000])   # north (book +y) is up in the image
    np.testing.assert_allclose(cv.image_to_opencv([[1.0, 2.0]]), [[1.0, -2.0]])
    np.testing.assert_allclose(cv.opencv_to_image(cv.image_to_opencv([[1.5, -2.5]])), [[1.5, -2.5]])


def test_pixel_helpers_round_trip_and_match_cv_pixels():
    io = InteriorOrientation(35.0, 0.05, -0.03)
    shape, pix = (3000, 4000), 0.006
    xy = np.array([[0.0, 0.0], [11.997, 8.997], [-5.0, 3.0]])
    for origin in ("center", "lower-left"):
        uv = cv.image_to_opencv_pixels(xy if origin == "center" else xy + [12, 9], pix, shape, origin)
        np.testing.assert_allclose(cv.opencv_pixels_to_image(uv, pix, shape, origin),
                                   xy if origin == "center" else xy + [12, 9], atol=1e-12)
    # the centre of the top-right pixel: x = +W/2 − Δ/2, y = +H/2 − Δ/2 → (u, v) = (n_cols − 1, 0)
    np.testing.assert_allclose(cv.image_to_opencv_pixels([[12 - 0.003, 9 - 0.003]], pix, shape), [[3999, 0]])
    eo = ExteriorOrientation.from_degrees(0, 0, 300, 2, 1, 10)
    XYZ = scene(eo, 10)
    rvec, tvec = cv.eo_to_rvec(eo)
    uv, _ = cv2.projectPoints(XYZ, rvec, tvec, cv.camera_matrix_pixels(io, pix, shape), None)
    np.testing.assert_allclose(cv.opencv_pixels_to_image(uv.reshape(-1, 2), pix, shape), project(XYZ, eo, io),
                               atol=1e-9)


def test_bad_opencv_input():
    with pytest.raises(InputError, match="rotation"):
        cv.opencv_to_eo(np.diag([1.0, 1.0, -1.0]), [0, 0, 0])
    with pytest.raises(InputError, match="3-vector"):
        cv.opencv_to_eo(np.eye(3), [0, 0])
    with pytest.raises(InputError, match="skew"):
        cv.opencv_to_brown_first_order([[100, 1, 0], [0, 100, 0], [0, 0, 1]], np.zeros(5))
    with pytest.raises(InputError, match="convention"):
        cv.convert_angles(0, 0, 0, "kaw", "zyx")
    with pytest.raises(InputError, match="distCoeffs"):
        cv.opencv_distort([[0.1, 0.1]], [0.1, 0.2])
    with pytest.raises(InputError, match="k1, k2, p1, p2, k3"):
        cv.opencv_distort([[0.1, 0.1]], [0.1, 0.2, 0, 0, 0, 0.3, 0, 0])
    with pytest.raises(InputError, match="half size"):
        cv.brown_to_opencv(InteriorOrientation(100.0, k1=1e-6), 0.0)
    # ω–α–κ (0, 90°, 0) has a31 = −1, i.e. α = 90° also in the κ–α–ω system, where it is singular
    with pytest.raises(DegenerateGeometryError):
        cv.wak_to_kaw(0.0, np.pi / 2, 0.0)
    w, a, k = cv.wak_to_kaw(0.0, np.pi / 2, 0.0, singular="kappa-zero")
    np.testing.assert_allclose(rot.rotation_matrix(w, a, k, "kaw"), rot.rotation_matrix(0, np.pi / 2, 0, "wak"),
                               atol=1e-15)


# --- distortion ----------------------------------------------------------------------------------
def test_first_order_mapping_derived_with_sympy():
    """Brown (measured → ideal, mm, y up) against OpenCV (ideal normalised → distorted, y down):
    to first order the OpenCV displacement equals −d of (1.2.2). Solve for OpenCV's coefficients."""
    xb, yb, f = sp.symbols("xbar ybar f", positive=True)
    k1, k2, k3, p1, p2 = sp.symbols("k1 k2 k3 p1 p2")
    K1, K2, K3, P1, P2 = sp.symbols("K1 K2 K3 P1 P2")
    r2 = xb**2 + yb**2
    radial = k1 * r2 + k2 * r2**2 + k3 * r2**3
    dx = xb * radial + (r2 + 2 * xb**2) * p1 + 2 * xb * yb * p2                 # (1.2.2)
    dy = yb * radial + 2 * xb * yb * p1 + (r2 + 2 * yb**2) * p2
    xn, yn = xb / f, -yb / f                                                      # OpenCV normalised, y down
    rn2 = xn**2 + yn**2
    radial_cv = K1 * rn2 + K2 * rn2**2 + K3 * rn2**3
    ddx = xn * radial_cv + 2 * P1 * xn * yn + P2 * (rn2 + 2 * xn**2)             # OpenCV documentation
    ddy = yn * radial_cv + P1 * (rn2 + 2 * yn**2) + 2 * P2 * xn * yn
    eqs = sp.Poly(sp.expand(f * ddx + dx), xb, yb).coeffs() + sp.Poly(sp.expand(-f * ddy + dy), xb, yb).coeffs()
    sol = sp.solve(eqs, [K1, K2, K3, P1, P2], dict=True)
    assert len(sol) == 1
    s = sol[0]
    values = {f: 120.0, k1: 3e-6, k2: -2e-10, k3: 5e-15, p1: 4e-6, p2: -7e-6}
    io = InteriorOrientation(120.0, k1=3e-6, k2=-2e-10, k3=5e-15, p1=4e-6, p2=-7e-6)
    expected = [float(s[K].subs(values)) for K in (K1, K2, P1, P2, K3)]
    np.testing.assert_allclose(cv.brown_to_opencv_first_order(io), expected, rtol=1e-12)
    back = cv.opencv_to_brown_first_order(cv.camera_matrix(io), expected)
    np.testing.assert_allclose([back.k1, back.k2, back.k3, back.p1, back.p2],
                               [io.k1, io.k2, io.k3, io.p1, io.p2], rtol=1e-12)


def test_opencv_distort_is_cv2():
    rng = np.random.default_rng(4)
    dist = np.array([-0.15, 0.04, 1.2e-3, -6e-4, -0.01])
    xy_n = rng.uniform(-0.35, 0.35, (100, 2))
    uv, _ = cv2.projectPoints(np.column_stack([xy_n, np.ones(100)]), np.zeros(3), np.zeros(3), np.eye(3), dist)
    np.testing.assert_allclose(cv.opencv_distort(xy_n, dist), uv.reshape(-1, 2), atol=1e-14)


FORMAT = (40.0, 30.0)


def cv_project_normalised(ideal_xy, io, dist):
    """OpenCV's forward model through cv2 itself: ideal book coordinates → distorted book coordinates."""
    K = cv.camera_matrix(io)
    n = (cv.image_to_opencv(ideal_xy) - K[:2, 2]) / io.f
    uv, _ = cv2.projectPoints(np.column_stack([n, np.ones(len(n))]), np.zeros(3), np.zeros(3), K, dist)
    return cv.opencv_to_image(uv.reshape(-1, 2))


@pytest.mark.parametrize("dist", [np.array([-0.12, 0.03, 1e-3, -5e-4, 0.0]),
                                  np.array([0.05, -0.01, -2e-4, 8e-4, 0.004]),
                                  np.array([-3e-3, 0.0, 0.0, 0.0, 0.0])])
def test_opencv_to_brown_within_reported_residual(dist):
    """Distort with OpenCV (cv2.projectPoints), correct with (1.2.2) using the converted coefficients:
    the ideal points come back to within the reported residual."""
    K = np.array([[100.0, 0, 0.3], [0, 100.0, 0.2], [0, 0, 1]])
    io, max_um, rms_um = cv.opencv_to_brown(K, dist, FORMAT)
    assert (io.f, io.x0, io.y0) == (100.0, 0.3, -0.2)
    grid = cv._format_grid(FORMAT, 41)
    rng = np.random.default_rng(0)
    inside = rng.uniform(-1, 1, (500, 2)) * FORMAT
    for ideal, bound in ((grid, max_um + 1e-6), (inside, max_um)):   # the grid's max is the reported one
        measured = cv_project_normalised(ideal, io, dist)
        err_um = np.hypot(*(correct_distortion(measured, io) - ideal).T) * 1000
        assert err_um.max() <= bound
    assert err_um.max() > 0.2 * max_um if max_um > 1e-3 else True      # the residual is not a loose bound
    # with small distortion the fit is close to the first-order mapping
    if abs(dist[0]) < 1e-2:
        first = cv.opencv_to_brown_first_order(K, dist)
        assert io.k1 == pytest.approx(first.k1, rel=2e-2)


@pytest.mark.parametrize("io", [InteriorOrientation(100.0, 0.3, -0.2, k1=-2e-6, k2=1e-10, p1=3e-6, p2=-2e-6),
                                InteriorOrientation(50.0, -0.1, 0.05, k1=4e-5, k3=1e-12, p2=1e-5),
                                InteriorOrientation(150.0, k1=1e-8)])
def test_brown_to_opencv_within_reported_residual(io):
    """Book model gives the ideal position of each measured point exactly; OpenCV's model with the
    converted coefficients (cv2.projectPoints) sends it back to the measured point within the residual."""
    dist, max_um, rms_um = cv.brown_to_opencv(io, FORMAT)
    assert rms_um <= max_um
    grid = cv._format_grid(FORMAT, 41)
    rng = np.random.default_rng(1)
    inside = rng.uniform(-1, 1, (500, 2)) * FORMAT
    for measured, bound in ((grid, max_um + 1e-6), (inside, max_um)):
        err_um = np.hypot(*(cv_project_normalised(correct_distortion(measured, io), io, dist) - measured).T) * 1000
        assert err_um.max() <= bound
    if io.k1 == 1e-8:      # tiny distortion: the fit is the first-order mapping
        np.testing.assert_allclose(dist[0], cv.brown_to_opencv_first_order(io)[0], rtol=1e-3)
        assert max_um < 1e-3


def test_undistort_points_agrees_with_book_correction():
    """cv2.undistortPoints with tight criteria (OpenCV's own inverse) against the book correction with the
    coefficients from :func:`opencv_to_brown`: same points to within the reported residual."""
    K = np.array([[100.0, 0, 0.3], [0, 100.0, 0.2], [0, 0, 1]])
    dist = np.array([-0.12, 0.03, 1e-3, -5e-4, 0.0])
    io, max_um, _ = cv.opencv_to_brown(K, dist, FORMAT)
    rng = np.random.default_rng(2)
    ideal = rng.uniform(-1, 1, (300, 2)) * FORMAT
    measured = cv_project_normalised(ideal, io, dist)
    crit = (cv2.TERM_CRITERIA_COUNT | cv2.TERM_CRITERIA_EPS, 100, 1e-14)
    und = cv2.undistortPoints(cv.image_to_opencv(measured).reshape(-1, 1, 2), K, dist, None, None, K, crit)
    ideal_cv = cv.opencv_to_image(und.reshape(-1, 2))
    np.testing.assert_allclose(ideal_cv, ideal, atol=1e-9)     # OpenCV inverts its own model
    err_um = np.hypot(*(correct_distortion(measured, io) - ideal_cv).T) * 1000
    assert err_um.max() <= max_um
