"""Chapter 4 theory adapters (photolib/book/ch04_theory.py): every formula check accepts the right
form and rejects a deliberately wrong one; the errata of §4.1–§4.4 are rejected as printed and
accepted once corrected; the inline point counts.

Expected values come from sympy / exact rational arithmetic on the Chapter-1 camera (1.4.12),
synthetic ground truth and OpenCV's five-point solver — never from photolib.projective itself.
"""

import numpy as np
import pytest
import sympy as sp

from photolib.book import ch04_theory as c


def ok(result):
    return result["printed_equals_derived"]


K = [["fx", "0", "x0"], ["0", "fy", "y0"], ["0", "0", "1"]]
I3 = [["1", "0", "0"], ["0", "1", "0"], ["0", "0", "1"]]
VX = "L1*X + L2*Y + L3*Z + L4 - x*X*L9 - x*Y*L10 - x*Z*L11 - x"
VY = "L5*X + L6*Y + L7*Z + L8 - y*X*L9 - y*Y*L10 - y*Z*L11 - y"
L_ALL = [f"L{i}" for i in range(1, 12)]
B_ROWS = [["X", "Y", "Z", "1", "0", "0", "0", "0", "-x*X", "-x*Y", "-x*Z"],
          ["0", "0", "0", "0", "X", "Y", "Z", "1", "-y*X", "-y*Y", "-y*Z"]]
IO = dict(L="-1/sqrt(L9**2 + L10**2 + L11**2)", x0="(L1*L9 + L2*L10 + L3*L11)*L**2",
          y0="(L5*L9 + L6*L10 + L7*L11)*L**2", fx="sqrt((L1**2 + L2**2 + L3**2)*L**2 - x0**2)",
          fy="sqrt((L5**2 + L6**2 + L7**2)*L**2 - y0**2)")
ROWS_12 = [["L*(x0*L9 - L1)/fx", "L*(y0*L9 - L5)/fy", "L*L9"], ["L*(x0*L10 - L2)/fx", "L*(y0*L10 - L6)/fy", "L*L10"]]
ROW3_PRINTED = ["L*(x0*L9 - L1)/fx", "L*(y0*L9 - L5)/fy", "L*L11"]
ROW3_CORRECT = ["L*(x0*L11 - L3)/fx", "L*(y0*L11 - L7)/fy", "L*L11"]
DLT_X = "(L1*X + L2*Y + L3*Z + L4)/(L9*X + L10*Y + L11*Z + 1)"
DLT_Y = "(L5*X + L6*Y + L7*Z + L8)/(L9*X + L10*Y + L11*Z + 1)"
SB = [["0", "-bz", "by"], ["bz", "0", "-bx"], ["-by", "bx", "0"]]
EIGHT = "x1*x2*f11 + y1*x2*f21 + x2*f31 + x1*y2*f12 + y1*y2*f22 + y2*f32 + x1*f13 + y1*f23 + 1"


# (adapter, accepted inputs, rejected inputs); the rejected one is either the book's erratum
# or a deliberately broken version of a formula the book prints correctly
CASES = [
    ("4.1.1", c.homogeneous_camera, dict(K=K, rotation="D*A.T", translation="-D*A.T*RS"),
     dict(K=K, rotation="A", translation="RS")),
    ("4.1.4", c.normalised_image_point, dict(K=K), dict(K=[["fx", "0", "x0"], ["0", "fy", "x0"], ["0", "0", "1"]])),
    ("4.1.5", c.homogeneous_camera,
     dict(K=I3, rotation="D*A.T", translation="-D*A.T*RS", frame="normalised"),
     dict(K=I3, rotation="A", translation="RS", frame="normalised")),
    ("4.1.6", c.dehomogenised_camera,
     dict(x="(a11*(X - Xs) + a21*(Y - Ys) + a31*(Z - Zs))/(-(a13*(X - Xs) + a23*(Y - Ys) + a33*(Z - Zs)))",
          y="(a12*(X - Xs) + a22*(Y - Ys) + a32*(Z - Zs))/(-(a13*(X - Xs) + a23*(Y - Ys) + a33*(Z - Zs)))"),
     dict(x="(a11*X + a12*Y + a13*Z + Xs)/(a31*X + a32*Y + a33*Z + Zs)",
          y="(a21*X + a22*Y + a23*Z + Ys)/(a31*X + a32*Y + a33*Z + Zs)")),
    ("4.1.7", c.dlt_equations, dict(x=DLT_X, y=DLT_Y), dict(x=DLT_X.replace("L4", "L8"), y=DLT_Y)),
    ("4.2.1", c.dlt_linear_equations, dict(vx=VX, vy=VY, unknowns=L_ALL),
     dict(vx=VX.replace("- x*Y*L10", "+ x*Y*L10"), vy=VY, unknowns=L_ALL)),
    ("4.2.1-linearity", c.dlt_linear_equations, dict(vx=VX, vy=VY, unknowns=L_ALL),
     dict(vx=VX, vy=VY, unknowns=["X", "Y", "Z", "x"])),           # not linear in the point: xX terms
    ("4.2.2", c.dlt_matrix_form, dict(B_rows=B_ROWS, free=["-x", "-y"], solution="-(B.T*B)**-1*B.T*l"),
     dict(B_rows=B_ROWS, free=["-x", "-y"], solution="(B.T*B)**-1*B.T*l")),
    ("4.2.2-rows", c.dlt_matrix_form, dict(B_rows=B_ROWS, free=["-x", "-y"], solution="-(B.T*B)**-1*B.T*l"),
     dict(B_rows=[B_ROWS[0], B_ROWS[1][:8] + ["-y*X", "-y*Z", "-y*Y"]], free=["-x", "-y"],
          solution="-(B.T*B)**-1*B.T*l")),
    ("4.2.4", c.interior_orientation_from_dlt, IO, {**IO, "L": "1/sqrt(L9**2 + L10**2 + L11**2)"}),
    ("4.2.4-f", c.interior_orientation_from_dlt, IO, {**IO, "fy": "sqrt((L5**2 + L6**2 + L7**2)*L**2 + y0**2)"}),
    ("4.2.5", c.projection_centre_from_dlt, dict(centre="-M**-1*Matrix([L4, L8, 1])"),
     dict(centre="M**-1*Matrix([L4, L8, 1])")),
    ("4.2.6", c.rotation_from_dlt, dict(rows=ROWS_12 + [ROW3_CORRECT]), dict(rows=ROWS_12 + [ROW3_PRINTED])),
    ("4.3.1", c.dlt_linear_equations,
     dict(vx="(L1 - x*L9)*X + (L2 - x*L10)*Y + (L3 - x*L11)*Z + L4 - x",
          vy="(L5 - y*L9)*X + (L6 - y*L10)*Y + (L7 - y*L11)*Z + L8 - y", unknowns=["X", "Y", "Z"]),
     dict(vx="(L1 - x*L9)*X + (L2 - x*L10)*Y + (L3 - x*L11)*Z + L4 + x",
          vy="(L5 - y*L9)*X + (L6 - y*L10)*Y + (L7 - y*L11)*Z + L8 - y", unknowns=["X", "Y", "Z"])),
    ("4.4.2", c.triple_product_forms,
     dict(printed=["b.dot(r1.cross(r2))", "-r1.dot(b.cross(r2))", "r2.dot(b.cross(r1))"]),
     dict(printed=["b.dot(r1.cross(r2))", "r1.dot(b.cross(r2))", "r2.dot(b.cross(r1))"])),
    ("4.4.4", c.skew_matrix_formula, dict(Sb=SB), dict(Sb=[["0", "bz", "by"], ["bz", "0", "-bx"], ["-by", "bx", "0"]])),
    ("4.4.5", c.coplanarity_matrix_form, dict(printed="-r1.T*Sb*r2"), dict(printed="r1.T*Sb*r2")),
    ("4.4.6", c.coplanarity_matrix_form, dict(printed="r1.T*Sb*r2", mode="condition", Sb=SB),
     dict(printed="r1.T*Sb*r2", mode="condition", Sb=[["0", "-bz", "by"], ["-bz", "0", "-bx"], ["-by", "bx", "0"]])),
    ("4.4.10", c.epipolar_matrix, dict(matrix="Kinv.T*D*Sb*A2*D*Kinv"), dict(matrix="Kinv.T*Sb*A2**-1*Kinv")),
    ("4.4.14", c.eight_point_equation, dict(printed=EIGHT), dict(printed=EIGHT.replace("y1*x2*f21", "y1*x2*f12"))),
    ("4.4.16", c.epipolar_matrix, dict(matrix="D*Sb*A2*D", calibrated=True),
     dict(matrix="Sb*A2**-1", calibrated=True)),
    ("line-F", c.epipolar_line, dict(printed="F.T*r1"), dict(printed="F*r1")),
    ("line-E", c.epipolar_line, dict(printed="E.T*r1", calibrated=True), dict(printed="E*r1", calibrated=True)),
]


@pytest.mark.parametrize("name, fn, good, bad", CASES, ids=[case[0] for case in CASES])
def test_formula_adapters_reject_wrong_forms(name, fn, good, bad):
    assert ok(fn(good)) is True
    assert ok(fn(bad)) is False


def test_homogeneous_camera_forms():
    """(4.1.1): transposing A alone is not enough; the reflection D (or −f in K) is needed too."""
    assert not ok(c.homogeneous_camera(dict(K=K, rotation="A", translation="RS")))
    assert not ok(c.homogeneous_camera(dict(K=K, rotation="A.T", translation="-A.T*RS")))
    assert not ok(c.homogeneous_camera(dict(K=K, rotation="D*A.T", translation="D*A.T*RS")))
    assert ok(c.homogeneous_camera(dict(K=K, rotation="D*A.T", translation="-D*A.T*RS")))
    minus_f = [["-fx", "0", "x0"], ["0", "-fy", "y0"], ["0", "0", "1"]]
    assert ok(c.homogeneous_camera(dict(K=minus_f, rotation="A.T", translation="-A.T*RS")))


def test_epipolar_matrix_forms():
    """(4.4.10)/(4.4.16): A₂⁻¹ → A₂ alone does not repair F; with the reflection D it does.
    A zero matrix (which satisfies every epipolar equation) is rejected."""
    assert not ok(c.epipolar_matrix(dict(matrix="Kinv.T*Sb*A2**-1*Kinv")))
    assert not ok(c.epipolar_matrix(dict(matrix="Kinv.T*Sb*A2*Kinv")))
    assert ok(c.epipolar_matrix(dict(matrix="Kinv.T*D*Sb*A2*D*Kinv")))
    assert ok(c.epipolar_matrix(dict(matrix="-Kinv.T*D*Sb*A2*D*Kinv")))          # scale is free
    assert not ok(c.epipolar_matrix(dict(matrix="0*Sb")))
    # the printed form is right when A₂ means the model → image-2 rotation in the reflected frame
    assert ok(c.epipolar_matrix(dict(matrix="Kinv.T*(D*Sb*D)*(D*A2.T*D)**-1*Kinv")))
    assert not ok(c.epipolar_line(dict(printed="F*r1")))
    assert ok(c.epipolar_line(dict(printed="F.T*r1")))


def test_quaternion_rotation_is_orthogonal_and_samples_in_front():
    R = c.quaternion_rotation(*sp.symbols("a b c d", real=True))
    assert sp.simplify(R.T * R - sp.eye(3)) == sp.zeros(3, 3) and sp.simplify(R.det()) == 1
    for s in c._samples():
        assert s["A"][:, 2].dot(s["S"]) > 0                                 # origin in front: D < 0


def test_sign_of_L_depends_on_the_object_origin():
    """(4.2.4)'s L = −1/√(L₉² + L₁₀² + L₁₁²) equals D only when the object origin is in front."""
    for s in c._samples():
        v = s["values"]
        for S, front in ((s["S"], True), (-s["S"], False)):               # −S: the origin behind the camera
            L = c.dlt_of_camera(s["A"], S, v["fx"], v["fy"], v["x0"], v["y0"])
            L_printed = -1 / sp.sqrt(L[8] ** 2 + L[9] ** 2 + L[10] ** 2)
            D = -(s["A"][:, 2].dot(S))
            assert (L_printed == D) is front and L_printed ** 2 == D ** 2


def test_dlt_of_camera_matches_collinearity():
    for s in c._samples():
        L = s["L"]
        X, Y, Z = s["P"]
        den = L[8] * X + L[9] * Y + L[10] * Z + 1
        assert (L[0] * X + L[1] * Y + L[2] * Z + L[3]) / den == s["xy"][0]
        assert (L[4] * X + L[5] * Y + L[6] * Z + L[7]) / den == s["xy"][1]


def test_minimum_point_counts():
    counts = c.minimum_control_points({})
    assert counts["dlt_min_points"] == 6 and counts["classical_min_points"] == 3
    assert counts["coplanar_rank"] == 8                                      # < 11: coplanar control fails
    ep = c.epipolar_min_points({})
    assert ep["F_min_points"] == 8 and ep["E_linear_min_points"] == 8
    assert c.five_point_solver_recovers_E() is True


def test_dlt_parameter_count():
    r = c.dlt_parameter_count({})
    assert r == {"n_coefficients": 11, "n_without_affine": 9}


def test_parse_rejects_unknown_names():
    """A typo in a transcription becomes a free symbol, so the identity fails instead of passing."""
    assert not ok(c.dlt_equations(dict(x=DLT_X.replace("L4", "L44"), y=DLT_Y)))
    assert np.isfinite(float(c._parse("sqrt(4)", {})))
