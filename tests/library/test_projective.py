"""Tests of photolib.projective (Chapter 4, §4.1–§4.4).

Expected values come from sympy (the printed formulas and their corrections), from synthetic
ground truth (photolib.single_image.project of a known camera) and from OpenCV on the same data,
converted with photolib.conventions (OpenCV camera = diag(1, −1, −1)·(Chapter-1 camera), image
(u, v) = (x, −y), K = [[f, 0, x₀], [0, f, −y₀], [0, 0, 1]]).
"""

import cv2
import numpy as np
import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st

from photolib import conventions
from photolib import projective as pj
from photolib.camera import ExteriorOrientation, InteriorOrientation
from photolib.errors import DegenerateGeometryError, InputError
from photolib.single_image import project

FLIP_Y = np.diag([1.0, -1.0, 1.0])            # homogeneous book image (x, y, 1) ↔ OpenCV (u, v, 1)
C_CV = np.diag([1.0, -1.0, -1.0])              # Chapter-1 camera axes ↔ OpenCV camera axes


# --- synthetic scene -------------------------------------------------------------------------------
def scene(n=40, seed=1, relief=(-100.0, 150.0)):
    rng = np.random.default_rng(seed)
    XYZ = np.column_stack([rng.uniform(0, 1000, n), rng.uniform(100, 900, n), rng.uniform(*relief, n)])
    io = InteriorOrientation(100.0, 0.12, -0.08)
    eo1 = ExteriorOrientation.from_degrees(250, 480, 1000, 2.0, -3.0, 5.0)
    eo2 = ExteriorOrientation.from_degrees(760, 530, 1020, -1.5, 2.5, 8.0)
    return XYZ, io, eo1, eo2


def noisy(xy, sigma, seed):
    return xy + np.random.default_rng(seed).normal(0, sigma, xy.shape)


# --- symbolic proofs of the errata of §4.2 and the layout of §4.4 ----------------------------------------
def _rational_rotation():
    a, b, c, d = sp.symbols("a b c d", real=True)
    q = a * a + b * b + c * c + d * d
    return sp.Matrix([[a * a - b * b - c * c + d * d, 2 * (a * b - c * d), 2 * (a * c + b * d)],
                      [2 * (a * b + c * d), -a * a + b * b - c * c + d * d, 2 * (b * c - a * d)],
                      [2 * (a * c - b * d), 2 * (b * c + a * d), -a * a - b * b + c * c + d * d]]) / q


def test_dlt_decomposition_formulas_symbolically():
    """(4.2.4) holds; (4.2.5) needs a minus sign; (4.2.6) row 3 as printed is wrong, corrected is A."""
    A = _rational_rotation()                           # any rotation (camera → object)
    fx, fy = sp.symbols("f_x f_y", positive=True)
    x0, y0, Xs, Ys, Zs = sp.symbols("x_0 y_0 X_S Y_S Z_S", real=True)
    S = sp.Matrix([Xs, Ys, Zs])
    K = sp.Matrix([[fx, 0, x0], [0, fy, y0], [0, 0, 1]])
    P = K * sp.diag(1, 1, -1) * A.T * sp.Matrix.hstack(sp.eye(3), -S)
    L1, L2, L3, L4, L5, L6, L7, L8, L9, L10, L11, _ = list(P / P[2, 3])
    M = sp.Matrix([[L1, L2, L3], [L5, L6, L7], [L9, L10, L11]])
    assert sp.simplify(M * S + sp.Matrix([L4, L8, 1])) == sp.zeros(3, 1)          # S = −M⁻¹(L4, L8, 1)
    assert sp.simplify(M * S - sp.Matrix([L4, L8, 1])) != sp.zeros(3, 1)          # (4.2.5) as printed fails
    Lf = -(A[:, 2].dot(S))                             # L of (4.2.4) with its correct sign
    assert sp.simplify(Lf ** 2 - 1 / (L9 ** 2 + L10 ** 2 + L11 ** 2)) == 0
    assert sp.simplify((L1 * L9 + L2 * L10 + L3 * L11) * Lf ** 2 - x0) == 0
    assert sp.simplify((L5 * L9 + L6 * L10 + L7 * L11) * Lf ** 2 - y0) == 0
    assert sp.simplify((L1 ** 2 + L2 ** 2 + L3 ** 2) * Lf ** 2 - x0 ** 2 - fx ** 2) == 0
    assert sp.simplify((L5 ** 2 + L6 ** 2 + L7 ** 2) * Lf ** 2 - y0 ** 2 - fy ** 2) == 0
    corrected = sp.Matrix([[Lf * (x0 * Lj - Li) / fx, Lf * (y0 * Lj - Lk) / fy, Lf * Lj]
                           for Li, Lk, Lj in ((L1, L5, L9), (L2, L6, L10), (L3, L7, L11))])
    assert sp.simplify(corrected - A) == sp.zeros(3, 3)
    printed_row3 = sp.Matrix([[Lf * (x0 * L9 - L1) / fx, Lf * (y0 * L9 - L5) / fy]])
    assert sp.simplify(printed_row3 - A[2, :2]) != sp.zeros(1, 2)


def test_fundamental_equation_layout_symbolically():
    """(4.4.14) is the expansion of (x1 y1 1) F (x2 y2 1)ᵀ with f33 = 1 (4.4.13): the layout x1Fx2;
    and r1ᵀ S_b r2 of (4.4.5) is −b·(r1 × r2)."""
    x1, y1, x2, y2 = sp.symbols("x1 y1 x2 y2")
    F = sp.Matrix(3, 3, sp.symbols("f11 f12 f13 f21 f22 f23 f31 f32 f33"))
    F = F.subs(F[2, 2], 1)
    f = {str(s): s for s in F.free_symbols}
    lhs = (sp.Matrix([[x1, y1, 1]]) * F * sp.Matrix([x2, y2, 1]))[0]
    printed = (x1 * x2 * f["f11"] + y1 * x2 * f["f21"] + x2 * f["f31"] + x1 * y2 * f["f12"] + y1 * y2 * f["f22"]
               + y2 * f["f32"] + x1 * f["f13"] + y1 * f["f23"] + 1)
    assert sp.expand(lhs - printed) == 0
    b, u, v = (sp.Matrix(sp.symbols(f"{p}1:4")) for p in "buv")
    Sb = sp.Matrix([[0, -b[2], b[1]], [b[2], 0, -b[0]], [-b[1], b[0], 0]])
    assert sp.expand((u.T * Sb * v)[0] + b.dot(u.cross(v))) == 0
    assert np.allclose(pj.skew_matrix([1.0, 2.0, 3.0]) @ [4.0, 5.0, 6.0], np.cross([1, 2, 3], [4, 5, 6]))


# book §4.4 example (seed lines 2941–2962): points 1–12 and the printed F
BOOK_44 = np.array([[5.246, -1.742, -57.794, 8.397], [55.186, -3.495, -1.738, 3.496], [7.081, 52.197, -52.726, 64.207],
                    [3.423, -54.883, -58.390, -44.076], [53.175, 42.918, 2.253, 49.522],
                    [61.163, -61.596, -6.460, -50.928], [5.036, 52.469, -51.936, 64.462],
                    [8.573, -51.002, -50.051, -40.724], [63.066, 53.184, 6.308, 59.767],
                    [66.347, -65.855, -4.508, -54.688], [7.601, 3.618, -53.942, 13.603], [57.311, 0.354, 1.429, 7.053]])
BOOK_F = np.array([[4.3e-5, -3.3e-5, -0.0154], [-1.0e-4, 9.8e-5, -0.1870], [0.0056, 0.1876, 1.0]])


def test_book_printed_F_is_transpose_of_its_equation():
    """The printed F satisfies x2ᵀFx1 ≈ 0 (our default layout, l2 = F r1) and not (4.4.13) x1ᵀFx2 = 0."""
    xy1, xy2 = BOOK_44[:8, :2], BOOK_44[:8, 2:]
    as_x2Fx1 = np.abs(pj.epipolar_residuals(BOOK_F, xy1, xy2)).max()
    as_x1Fx2 = np.abs(pj.epipolar_residuals(BOOK_F, xy1, xy2, layout="x1Fx2")).max()
    assert as_x2Fx1 < 0.05 and as_x1Fx2 > 1.0
    F = pj.fundamental_matrix(xy1, xy2, method="book")
    assert np.allclose(F, BOOK_F, rtol=0.03, atol=3e-4)      # the printed 2–4 significant digits
    assert np.allclose(pj.fundamental_matrix(xy1, xy2, method="book", layout="x1Fx2"), F.T)


# --- §4.1 the camera model -------------------------------------------------------------------------------
def test_projection_matrix_and_dlt_reproduce_collinearity():
    XYZ, io, eo1, _ = scene()
    xy = project(XYZ, eo1, io)
    h = np.column_stack([XYZ, np.ones(len(XYZ))]) @ pj.projection_matrix(io, eo1).T
    assert np.allclose(h[:, :2] / h[:, 2:], xy, atol=1e-10)
    L = pj.dlt_from_orientation(io, eo1)
    assert np.allclose(pj.dlt_project(L, XYZ), xy, atol=1e-10)
    assert np.allclose(pj.dlt_from_projection(pj.projection_from_dlt(L)), L)
    # same camera as OpenCV's: P_cv = diag(1, −1, 1)·P
    P_cv = conventions.camera_matrix(io) @ np.column_stack(conventions.eo_to_opencv(eo1))
    assert np.allclose(FLIP_Y @ pj.projection_matrix(io, eo1), P_cv)


angles = st.floats(-np.radians(35), np.radians(35))


@settings(max_examples=60, deadline=None)
@given(f=st.floats(20, 300), x0=st.floats(-5, 5), y0=st.floats(-5, 5), w=angles, a=angles, k=st.floats(-3.1, 3.1),
       Xs=st.floats(-2000, 2000), Ys=st.floats(-2000, 2000), Zs=st.floats(-1500, 3000),
       order=st.sampled_from(["kaw", "wak"]))
def test_orientation_dlt_round_trip(f, x0, y0, w, a, k, Xs, Ys, Zs, order):
    """IO/EO → L₁…L₁₁ → IO/EO, also when the object origin is behind the camera (L > 0)."""
    io = InteriorOrientation(f, x0, y0)
    eo = ExteriorOrientation(Xs, Ys, Zs, w, a, k, order)
    P = pj.projection_matrix(io, eo)
    if abs(P[2, 3]) < 1e-3 * np.linalg.norm(P[2, :3]) * max(1.0, np.linalg.norm(eo.center)):
        return                                       # origin (almost) in the principal plane: no L12 = 1
    o = pj.orientation_from_dlt(pj.dlt_from_orientation(io, eo), order)
    assert np.allclose([o.x0, o.y0, o.fx, o.fy, o.skew], [x0, y0, f, f, 0.0], atol=1e-6 * f)
    assert np.allclose(o.center, eo.center, atol=1e-6 * max(1.0, np.abs(eo.center).max()))
    assert np.allclose(o.A, eo.matrix, atol=1e-9) and np.allclose(o.A_printed, eo.matrix, atol=1e-9)
    assert np.allclose(pj.orientation_from_dlt(pj.dlt_from_orientation(io, eo), order, printed=True).center,
                       -eo.center, atol=1e-6 * max(1.0, np.abs(eo.center).max()))


def test_affine_camera_parameters_recovered():
    XYZ, io, eo1, _ = scene()
    L = pj.dlt_from_orientation(io, eo1, fx=101.0, fy=99.5, skew=0.3)
    o = pj.orientation_from_dlt(L)
    assert np.isclose(o.fx, np.hypot(101.0, 0.3)) and np.isclose(o.fy, 99.5) and np.isclose(o.skew, 0.3)
    assert np.allclose(o.A_printed[:, 1:], eo1.matrix[:, 1:])           # columns 2, 3 of (4.2.6) stay exact


# --- §4.2 projective resection ---------------------------------------------------------------------------
@pytest.mark.parametrize("method", ["book", "normalized"])
def test_dlt_resection_exact_data(method):
    XYZ, io, eo1, _ = scene(n=12)
    r = pj.dlt_resection(XYZ, project(XYZ, eo1, io), method=method)
    assert np.allclose(r.L, pj.dlt_from_orientation(io, eo1), rtol=1e-7, atol=1e-12)
    assert r.mu < 1e-8 and r.dof == 2 * 12 - 11
    o = r.orientation()
    assert np.allclose(o.eo.vector, eo1.vector, atol=1e-6)


def test_dlt_resection_against_opencv_decomposition():
    """cv2.decomposeProjectionMatrix of the same (noisy) DLT gives the same x0, y0, f, skew, centre, rotation."""
    XYZ, io, eo1, _ = scene(n=30)
    r = pj.dlt_resection(XYZ, noisy(project(XYZ, eo1, io), 0.005, 3))
    o = r.orientation()
    K, R, C = cv2.decomposeProjectionMatrix(FLIP_Y @ pj.projection_from_dlt(r.L))[:3]
    K = K / K[2, 2]
    assert np.allclose([o.x0, o.y0, o.fy], [K[0, 2], -K[1, 2], K[1, 1]], rtol=1e-9, atol=1e-9)
    assert np.isclose(o.fx, np.hypot(K[0, 0], K[0, 1])) and np.isclose(o.skew, -K[0, 1], atol=1e-9)
    assert np.allclose(o.center, (C[:3] / C[3]).ravel(), atol=1e-6)
    A_cv = (C_CV @ R).T
    assert np.allclose(o.A_printed[:, 1:], A_cv[:, 1:], atol=1e-9)
    assert np.allclose(o.A, A_cv, atol=2 * abs(o.skew) / o.fy)          # differ only by the skew


def test_dlt_precision_and_weights():
    XYZ, io, eo1, _ = scene(n=30)
    xy = noisy(project(XYZ, eo1, io), 0.01, 5)
    r = pj.dlt_resection(XYZ, xy, method="book")
    B, free = pj.dlt_design(XYZ, xy)
    V = B @ r.L + free
    assert np.isclose(r.mu, np.sqrt(V @ V / (60 - 11)))
    assert np.allclose(r.std, r.mu * np.sqrt(np.diag(np.linalg.inv(B.T @ B))))
    assert np.allclose(r.L, np.linalg.lstsq(B, -free, rcond=None)[0], rtol=1e-8)
    assert np.allclose(np.diag(r.corr), 1.0)
    rw = pj.dlt_resection(XYZ, xy, method="book", weights=np.full(30, 4.0))
    assert np.allclose(rw.L, r.L) and np.isclose(rw.mu, 2 * r.mu)
    rn = pj.dlt_resection(XYZ, xy)                  # normalised: nearly the same solution
    assert np.allclose(rn.orientation().eo.vector, r.orientation().eo.vector, atol=0.05)


def test_dlt_agrees_with_collinearity_resection():
    """The linear DLT and the iterative resection of §1.8 find the same pose within the DLT's scatter."""
    resection = pytest.importorskip("photolib.resection")
    XYZ, io, eo1, _ = scene(n=30)
    exact = project(XYZ, eo1, io)
    xy = noisy(exact, 0.005, 11)
    dlt = pj.dlt_resection(XYZ, xy).orientation().eo
    col = resection.space_resection(XYZ, xy, io).eo
    scatter = np.std([pj.dlt_resection(XYZ, noisy(exact, 0.005, 100 + i)).orientation().eo.vector
                      for i in range(40)], axis=0)
    assert np.all(np.abs(dlt.vector - col.vector) < 4 * scatter)
    assert np.allclose(col.vector, eo1.vector, atol=0.5)


def test_dlt_resection_bad_input():
    XYZ, io, eo1, _ = scene(n=12)
    xy = project(XYZ, eo1, io)
    with pytest.raises(InputError, match="at least 6"):
        pj.dlt_resection(XYZ[:5], xy[:5])
    flat = XYZ.copy()
    flat[:, 2] = 50.0
    with pytest.raises(DegenerateGeometryError, match="coplanar"):
        pj.dlt_resection(flat, project(flat, eo1, io))
    bad = xy.copy()
    bad[0, 0] = np.nan
    with pytest.raises(InputError, match="NaN"):
        pj.dlt_resection(XYZ, bad)
    with pytest.raises(InputError):
        pj.dlt_resection(XYZ, xy[:-1])
    with pytest.raises(InputError):
        pj.dlt_resection(XYZ, xy, method="iterative")


# --- §4.3 projective intersection ------------------------------------------------------------------------
def test_dlt_intersection_against_opencv_triangulation():
    XYZ, io, eo1, eo2 = scene(n=25)
    xy1, xy2 = project(XYZ, eo1, io), project(XYZ, eo2, io)
    L1, L2 = pj.dlt_from_orientation(io, eo1), pj.dlt_from_orientation(io, eo2)
    res = pj.dlt_intersection([L1, L2], [xy1, xy2])
    assert np.allclose(res.XYZ, XYZ, atol=1e-6)
    P1 = conventions.camera_matrix(io) @ np.column_stack(conventions.eo_to_opencv(eo1))
    P2 = conventions.camera_matrix(io) @ np.column_stack(conventions.eo_to_opencv(eo2))
    Xh = cv2.triangulatePoints(P1, P2, conventions.image_to_opencv(xy1).T, conventions.image_to_opencv(xy2).T)
    assert np.allclose(res.XYZ, (Xh[:3] / Xh[3]).T, atol=1e-5)
    assert res.dof == 1 and res.residuals.shape == (25, 2, 2)


def test_dlt_intersection_multi_image_precision():
    XYZ, io, eo1, eo2 = scene(n=20)
    eo3 = ExteriorOrientation.from_degrees(500, 900, 980, 6.0, 1.0, -3.0)
    Ls = [pj.dlt_from_orientation(io, e) for e in (eo1, eo2, eo3)]
    xys = [noisy(project(XYZ, e, io), 0.01, s) for s, e in enumerate((eo1, eo2, eo3))]
    res = pj.dlt_intersection(Ls, xys)
    assert res.dof == 3 and np.all(np.isfinite(res.std))
    # v of (4.3.1) is the image error times the DLT denominator w = Z*/Z*(origin) ∈ (0.8, 1.2) here,
    # so σ_v ≤ 1.2σ and each coordinate error must stay within 5·1.2σ·√Q_jj (√Q = m/μ)
    w = np.stack([np.column_stack([XYZ, np.ones(20)]) @ pj.projection_from_dlt(L)[2] for L in Ls])
    assert 0.8 < w.min() and w.max() < 1.2
    assert np.all(np.abs(res.XYZ - XYZ) < 5 * 1.2 * 0.01 * res.std / res.mu[:, None])
    with pytest.raises(InputError):
        pj.dlt_intersection(Ls[:1], xys[:1])


# --- §4.4 fundamental and essential matrices --------------------------------------------------------------
@pytest.mark.parametrize("method", ["book", "normalized"])
def test_fundamental_exact_data(method):
    XYZ, io, eo1, eo2 = scene(n=15)
    xy1, xy2 = project(XYZ, eo1, io), project(XYZ, eo2, io)
    F = pj.fundamental_matrix(xy1, xy2, method=method)
    truth = pj.fundamental_from_orientation(io, eo1, io, eo2)
    Fn = F / np.linalg.norm(F) * np.sign(F[2, 2] * truth[2, 2])
    assert np.allclose(Fn, truth, atol=1e-7)
    assert np.abs(pj.epipolar_residuals(truth, xy1, xy2)).max() < 1e-12
    s = np.linalg.svd(Fn, compute_uv=False)
    assert s[2] < 1e-8 * s[0]                          # rank 2
    # epipolar lines: the corresponding point lies on l2 = F r1 and on l1 = Fᵀ r2
    l2 = pj.epipolar_lines(F, xy1, image=2)
    assert np.abs(np.einsum("ni,ni->n", l2, np.column_stack([xy2, np.ones(15)]))).max() < 1e-6
    l1 = pj.epipolar_lines(F, xy2, image=1)
    assert np.abs(np.einsum("ni,ni->n", l1, np.column_stack([xy1, np.ones(15)]))).max() < 1e-6


def test_fundamental_against_opencv_8point():
    XYZ, io, eo1, eo2 = scene(n=30)
    xy1, xy2 = noisy(project(XYZ, eo1, io), 0.01, 1), noisy(project(XYZ, eo2, io), 0.01, 2)
    F = pj.fundamental_matrix(xy1, xy2)
    assert np.linalg.matrix_rank(F, tol=1e-10) == 2
    F_cv, _ = cv2.findFundamentalMat(conventions.image_to_opencv(xy1), conventions.image_to_opencv(xy2),
                                     cv2.FM_8POINT)
    ours = FLIP_Y @ F @ FLIP_Y
    # OpenCV solves the same normalised system through the eigenvectors of AᵀA (squared condition),
    # so agreement is judged relative to the size of F, not element by element
    assert np.abs(ours / ours[2, 2] - F_cv / F_cv[2, 2]).max() < 1e-6 * np.linalg.norm(F_cv / F_cv[2, 2])


def test_essential_and_relative_orientation_exact():
    XYZ, io, eo1, eo2 = scene(n=20)
    xy1, xy2 = project(XYZ, eo1, io), project(XYZ, eo2, io)
    E = pj.essential_matrix(xy1, xy2, io)
    truth = pj.essential_from_orientation(eo1, eo2)
    assert np.allclose(E * np.sign(E[2, 2] * truth[2, 2]), truth, atol=1e-8)
    s = np.linalg.svd(E, compute_uv=False)
    assert np.isclose(s[0], s[1]) and s[2] < 1e-12
    # E = K2ᵀ F K1 (the relation behind (4.4.16)), exact for 8 points with the book's method
    F8 = pj.fundamental_matrix(xy1[:8], xy2[:8], method="book")
    E8 = pj.essential_matrix(xy1[:8], xy2[:8], io, method="book")
    EK = pj.essential_from_fundamental(F8, io)
    assert np.allclose(EK / EK[2, 2], E8, rtol=1e-6)
    for order in ("kaw", "wak"):
        ro = pj.decompose_essential(E, xy1, xy2, io, order=order)
        A2 = eo1.matrix.T @ eo2.matrix                      # camera 2 in the camera-1 (model) frame
        b = eo1.matrix.T @ (eo2.center - eo1.center)
        assert np.allclose(ro.A2, A2, atol=1e-9)
        assert np.allclose(ro.base_direction, b / np.linalg.norm(b), atol=1e-9)
        assert np.allclose([ro.by, ro.bz], [b[1] / b[0], b[2] / b[0]], atol=1e-9)
        assert np.allclose([ro.omega2, ro.alpha2, ro.kappa2],
                           ExteriorOrientation.from_matrix([0, 0, 0], A2, order).vector[3:], atol=1e-9)
        assert ro.in_front == 20


def test_essential_and_pose_against_opencv():
    XYZ, io, eo1, eo2 = scene(n=30)
    xy1, xy2 = project(XYZ, eo1, io), project(XYZ, eo2, io)
    u1, u2 = conventions.image_to_opencv(xy1), conventions.image_to_opencv(xy2)
    K = conventions.camera_matrix(io)
    E_cv, _ = cv2.findEssentialMat(u1, u2, K, method=cv2.RANSAC, prob=0.999, threshold=1e-4)
    E_cv = E_cv[:3]
    E = FLIP_Y @ pj.essential_matrix(xy1, xy2, io) @ FLIP_Y      # OpenCV normalised = diag(1,−1,1)·r″
    assert np.allclose(E / np.linalg.norm(E) * np.sign(E[2, 2] * E_cv[2, 2]), E_cv / np.linalg.norm(E_cv),
                       atol=1e-6)
    _, R_cv, t_cv, _ = cv2.recoverPose(E_cv, u1, u2, K)
    ro = pj.relative_orientation_projective(xy1, xy2, io)
    assert np.allclose(ro.A2, C_CV @ R_cv.T @ C_CV, atol=1e-6)     # X_cv2 = R_cv X_cv1 + t
    assert np.allclose(ro.base_direction, -(ro.A2 @ C_CV @ t_cv).ravel(), atol=1e-6)


def test_ransac_rejects_outliers():
    XYZ, io, eo1, eo2 = scene(n=80, seed=4)
    xy1, xy2 = noisy(project(XYZ, eo1, io), 0.005, 6), noisy(project(XYZ, eo2, io), 0.005, 7)
    rng = np.random.default_rng(8)
    outliers = rng.choice(80, 20, replace=False)
    xy2[outliers] += rng.uniform(2, 10, (20, 2)) * rng.choice([-1, 1], (20, 2))
    res = pj.ransac_fundamental(xy1, xy2, threshold=0.03, rng=0)
    truth = np.ones(80, bool)
    truth[outliers] = False
    assert not np.any(res.inliers[outliers]) and res.inliers[truth].mean() > 0.95
    again = pj.ransac_fundamental(xy1, xy2, threshold=0.03, rng=0)
    assert np.array_equal(again.model, res.model)
    assert np.median(pj.sampson_distance(res.model, xy1[truth], xy2[truth])) < 0.01


def test_fundamental_degenerate_and_bad_input():
    XYZ, io, eo1, eo2 = scene(n=20)
    flat = XYZ.copy()
    flat[:, 2] = 0.0
    with pytest.raises(DegenerateGeometryError, match="plane"):
        pj.fundamental_matrix(project(flat, eo1, io), project(flat, eo2, io))
    rotated = ExteriorOrientation(eo1.Xs, eo1.Ys, eo1.Zs, 0.1, -0.05, 0.3)     # same centre: no base
    with pytest.raises(DegenerateGeometryError):
        pj.fundamental_matrix(project(XYZ, eo1, io), project(XYZ, rotated, io))
    with pytest.raises(DegenerateGeometryError):
        pj.essential_matrix(project(XYZ, eo1, io), project(XYZ, rotated, io), io)
    xy1, xy2 = project(XYZ, eo1, io), project(XYZ, eo2, io)
    with pytest.raises(InputError, match="at least 8"):
        pj.fundamental_matrix(xy1[:7], xy2[:7])
    with pytest.raises(InputError):
        pj.fundamental_matrix(xy1, xy2[:-1])
    with pytest.raises(InputError):
        pj.fundamental_matrix(xy1, xy2, layout="rows")
    with pytest.raises(DegenerateGeometryError, match="rank"):
        pj.decompose_essential(np.zeros((3, 3)), xy1, xy2, io)
    bad = xy1.copy()
    bad[3, 1] = np.inf
    with pytest.raises(InputError):
        pj.essential_matrix(bad, xy2, io)


# --- plane-to-plane homography ---------------------------------------------------------------------------
def test_homography_plane_between_two_images():
    XYZ, io, eo1, eo2 = scene(n=25)
    flat = XYZ.copy()
    flat[:, 2] = 20.0
    xy1, xy2 = project(flat, eo1, io), project(flat, eo2, io)
    H = pj.homography_dlt(xy1, xy2)
    assert np.allclose(pj.apply_homography(H, xy1), xy2, atol=1e-9)
    res = pj.homography_lsq(xy1, xy2)
    assert np.allclose(res.H, H, rtol=1e-8, atol=1e-12) and res.adjustment.mu < 1e-9


def test_homography_lsq_against_opencv():
    XYZ, io, eo1, eo2 = scene(n=25)
    flat = XYZ.copy()
    flat[:, 2] = 20.0
    xy1 = project(flat, eo1, io)
    xy2 = noisy(project(flat, eo2, io), 0.01, 9)
    res = pj.homography_lsq(xy1, xy2)
    H_cv, _ = cv2.findHomography(xy1, xy2, 0)          # all points, reprojection error refined (LM)
    assert np.allclose(pj.apply_homography(res.H, xy1), pj.apply_homography(H_cv / H_cv[2, 2], xy1), atol=2e-5)
    r = res.residuals
    assert np.isclose(res.adjustment.mu, np.sqrt(np.sum(r ** 2) / (50 - 8)))
    assert np.sum(r ** 2) <= np.sum((pj.apply_homography(H_cv / H_cv[2, 2], xy1) - xy2) ** 2) + 1e-12
    with pytest.raises(InputError, match="at least 4"):
        pj.homography_dlt(xy1[:3], xy2[:3])
    line = np.column_stack([np.linspace(0, 1, 6), np.linspace(0, 2, 6)])
    with pytest.raises(DegenerateGeometryError, match="collinear"):
        pj.homography_lsq(line, xy2[:6])
