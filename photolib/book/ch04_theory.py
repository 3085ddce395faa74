"""Chapter 4, §4.1–§4.4 (projective transformations): formula checks and inline statements.

Adapters for the ``[[formula]]`` entries ``4.1.x-…`` … ``4.4.x-…`` and the inline numeric
statements ``4.0-…`` of ``textbook/ch04.toml`` (the worked examples of §4.3/§4.4 live elsewhere).

Every formula adapter takes the printed formula transcribed as sympy text (so a test can hand in
a deliberately wrong one) and returns ``{"printed_equals_derived": bool}``. The derivations are
independent of :mod:`photolib.projective`; they start from Chapter 1:

* the camera: A (camera → object) is the quaternion matrix (1.3.7) divided by its scale — a
  rational parametrisation of *all* rotations — and the image of a point follows the collinearity
  equations (1.4.12), generalised to two principal distances f_x, f_y:
  x = x₀ − f_x·X*/Z*, y = y₀ − f_y·Y*/Z*, (X*, Y*, Z*) = Aᵀ(X − X_S, Y − Y_S, Z − Z_S);
* the DLT coefficients come from (1.4.12) by dividing numerator and denominator by the constant
  term of the denominator, D = −(a₁₃X_S + a₂₃Y_S + a₃₃Z_S):
  L₉, L₁₀, L₁₁ = a_{j3}/D, L_{1,2,3} = (x₀a_{j3} − f_x a_{j1})/D, L_{5,6,7} = (y₀a_{j3} − f_y a_{j2})/D,
  L₄ = −(L₁X_S + L₂Y_S + L₃Z_S), L₈ = −(L₅X_S + L₆Y_S + L₇Z_S);
* a pair: the model frame is the camera-1 frame (A₁ = E, S₁ = 0, the "left image fixed" system of
  (4.4.7)), camera 2 at the base b with A₂ (camera → model).

Polynomial identities are decided by ``sympy.expand``. Identities that involve rotations, roots
or inverses are evaluated exactly, in rational arithmetic, at several random rational cameras
and points (``_samples``): the quaternion rotation makes every quantity rational, so a printed
formula either gives exactly the derived value or it does not; a wrong rational identity
survives a random rational point only with probability zero.

String symbols: ``X Y Z`` object point, ``Xs Ys Zs`` (``RS`` the vector) projection centre,
``x y`` image point, ``x0 y0 f fx fy`` interior orientation, ``a11 … a33`` (``A``) the rotation,
``L1 … L11``, ``L`` (4.2.4), ``M`` the 3×3 of L₁…L₃, L₅…L₇, L₉…L₁₁, ``K Kinv`` (4.1.2),
``D`` = diag(1, 1, −1), ``bx by bz`` (``b``, ``Sb``) the base, ``r1 r2`` rays, ``A2`` the
rotation of image 2, ``x1 y1 x2 y2``, ``f11 … f32`` (4.4.12), ``F``, ``E``, ``r1pp`` (r₁″).
"""

from __future__ import annotations

import numpy as np
import sympy as sp

from ..camera import ExteriorOrientation, InteriorOrientation
from ._exact import zero

D_MATRIX = sp.diag(1, 1, -1)

_SYM = {s.name: s for s in sp.symbols(
    "X Y Z Xs Ys Zs x y x0 y0 f fx fy bx by bz x1 y1 x2 y2 L "
    "L1 L2 L3 L4 L5 L6 L7 L8 L9 L10 L11 f11 f12 f13 f21 f22 f23 f31 f32 f33", real=True)}
_BASE_LOCALS = {"sqrt": sp.sqrt, "Matrix": sp.Matrix, "D": D_MATRIX, "I3": sp.eye(3)}


def _parse(text: str, values: dict):
    """Evaluate a transcribed formula with the given symbol values (sympy objects)."""
    return sp.parse_expr(str(text), local_dict={**_BASE_LOCALS, **values})


def _ok(flag) -> dict:
    return {"printed_equals_derived": bool(flag)}


def _is_zero(value) -> bool:
    value = sp.Matrix(value) if isinstance(value, (list, tuple)) else value
    return zero(value)          # exact canonical form where it applies, else sympy's simplify


# --- the camera of Chapter 1, exactly, at random rational values ---------------------------------
def quaternion_rotation(a, b, c, d) -> sp.Matrix:
    """(1.3.7) divided by a² + b² + c² + d²: orthogonal for any non-zero quaternion (vector a, b, c)."""
    Q = sp.Matrix([
        [d**2 + a**2 - b**2 - c**2, 2 * (a * b - c * d), 2 * (a * c + b * d)],
        [2 * (a * b + c * d), d**2 - a**2 + b**2 - c**2, 2 * (b * c - a * d)],
        [2 * (a * c - b * d), 2 * (b * c + a * d), d**2 - a**2 - b**2 + c**2],
    ])
    return Q / (a**2 + b**2 + c**2 + d**2)


def _rat(rng, lo, hi, den=8):
    return sp.Rational(int(rng.integers(int(lo * den), int(hi * den) + 1)), den)


def dlt_of_camera(A, S, fx, fy, x0, y0) -> list:
    """L₁…L₁₁ derived from (1.4.12) (module notes): division by D = −(a₁₃X_S + a₂₃Y_S + a₃₃Z_S)."""
    a1, a2, a3 = A[:, 0], A[:, 1], A[:, 2]
    Dn = -(a3.dot(S))
    m1 = (x0 * a3 - fx * a1) / Dn
    m2 = (y0 * a3 - fy * a2) / Dn
    m3 = a3 / Dn
    return [*m1, -m1.dot(S), *m2, -m2.dot(S), *m3]


def _samples(n=3, seed=4, equal_f=False, front=True):
    """Random exact cameras: dicts of symbol values, the rotation, the centre and derived images.

    ``front``: the object origin lies in front of the camera (a₁₃X_S + a₂₃Y_S + a₃₃Z_S > 0,
    i.e. D < 0), the situation of every aerial or terrestrial image whose object origin is in
    the field of view.
    """
    rng = np.random.default_rng(seed)
    out = []
    while len(out) < n:
        q = [_rat(rng, -1, 1), _rat(rng, -1, 1), _rat(rng, -1, 1), _rat(rng, 1, 3)]
        A = quaternion_rotation(*q)
        S = sp.Matrix([_rat(rng, -40, 40), _rat(rng, -40, 40), _rat(rng, 80, 200)])
        if front and A[:, 2].dot(S) <= 0:
            S = -S
        fx = _rat(rng, 50, 150)
        fy = fx if equal_f else _rat(rng, 50, 150)
        x0, y0 = _rat(rng, -2, 2), _rat(rng, -2, 2)
        P = sp.Matrix([_rat(rng, -30, 30), _rat(rng, -30, 30), _rat(rng, -10, 10)])
        u, v, w = A.T * (P - S)
        if w == 0 or A[:, 2].dot(S) == 0:
            continue
        x, y = x0 - fx * u / w, y0 - fy * v / w
        Ls = dlt_of_camera(A, S, fx, fy, x0, y0)
        values = {"X": P[0], "Y": P[1], "Z": P[2], "Xs": S[0], "Ys": S[1], "Zs": S[2], "RS": S, "A": A,
                  "x0": x0, "y0": y0, "fx": fx, "fy": fy, "f": fx, "x": x, "y": y,
                  "M": sp.Matrix([Ls[0:3], Ls[4:7], Ls[8:11]])}
        values.update({f"a{i + 1}{j + 1}": A[i, j] for i in range(3) for j in range(3)})
        values.update({f"L{i + 1}": Ls[i] for i in range(11)})
        out.append({"values": values, "A": A, "S": S, "P": P, "uvw": (u, v, w), "xy": (x, y), "L": Ls})
    return out


# =================================================================================================
# §4.1 the homogeneous camera and the DLT
# =================================================================================================
def homogeneous_camera(inputs: dict) -> dict:
    """(4.1.1)/(4.1.2) and (4.1.5): r ≃ K·[rotation | translation]·R reproduces (1.4.12)?

    ``inputs``: ``K`` (3×3 strings), ``rotation`` (a 3×3 expression in ``A``, ``D``),
    ``translation`` (a 3-vector expression in ``A``, ``RS``, ``D``) and ``frame``:
    ``"image"`` compares with (x, y) of (1.4.12) (f_x = f_y = f), ``"normalised"`` with
    r′ = K⁻¹r of (4.1.4), i.e. ((x − x₀)/f, (y − y₀)/f).
    """
    frame = inputs.get("frame", "image")
    flags = []
    for s in _samples(equal_f=True):
        val = s["values"]
        K = sp.Matrix([[_parse(e, val) for e in row] for row in inputs["K"]])
        R = sp.Matrix(_parse(inputs["rotation"], val))
        t = sp.Matrix(_parse(inputs["translation"], val)).reshape(3, 1)
        h = K * R.row_join(t) * sp.Matrix([*s["P"], 1])
        x, y = s["xy"]
        target = (x, y) if frame == "image" else ((x - val["x0"]) / val["f"], (y - val["y0"]) / val["f"])
        flags.append(h[2] != 0 and _is_zero([h[0] / h[2] - target[0], h[1] / h[2] - target[1]]))
    return _ok(all(flags))


def normalised_image_point(inputs: dict) -> dict:
    """(4.1.3)/(4.1.4): r′ = K⁻¹(x, y, 1)ᵀ with the K of (4.1.2) is ((x − x₀)/f_x, (y − y₀)/f_y, 1)ᵀ?

    With f_x = f_y = f this is the Chapter-1 ray (x − x₀, y − y₀, −f) divided by f and reflected
    by D = diag(1, 1, −1): the homogeneous frame of Chapter 4 has its z axis towards the object.
    """
    flags = []
    for s in _samples():
        val = s["values"]
        K = sp.Matrix([[_parse(e, val) for e in row] for row in inputs["K"]])
        x, y = s["xy"]
        r1 = K.inv() * sp.Matrix([x, y, 1])
        derived = sp.Matrix([(x - val["x0"]) / val["fx"], (y - val["y0"]) / val["fy"], 1])
        flags.append(_is_zero(r1 - derived))
    return _ok(all(flags))


def dehomogenised_camera(inputs: dict) -> dict:
    """(4.1.6): x′, y′ as printed against the normalised collinearity x′ = −X*/Z*, y′ = −Y*/Z*.

    x′ = (x − x₀)/f, y′ = (y − y₀)/f are the coordinates of r′ = K⁻¹r (4.1.4), from which (4.1.6)
    is obtained; ``inputs``: ``x``, ``y`` strings in a_ij, X, Y, Z, X_S, Y_S, Z_S.
    """
    flags = []
    for s in _samples():
        val = s["values"]
        u, v, w = s["uvw"]
        flags.append(_is_zero([_parse(inputs["x"], val) + u / w, _parse(inputs["y"], val) + v / w]))
    return _ok(all(flags))


def dlt_equations(inputs: dict) -> dict:
    """(4.1.7): the printed DLT with L₁…L₁₁ derived from (1.4.12) gives the collinearity image?"""
    flags = []
    for s in _samples():
        val = s["values"]
        x, y = s["xy"]
        flags.append(_is_zero([_parse(inputs["x"], val) - x, _parse(inputs["y"], val) - y]))
    return _ok(all(flags))


# =================================================================================================
# §4.2 projective resection, §4.3 projective intersection
# =================================================================================================
def _dlt_symbolic():
    S = _SYM
    den = S["L9"] * S["X"] + S["L10"] * S["Y"] + S["L11"] * S["Z"] + 1
    nx = S["L1"] * S["X"] + S["L2"] * S["Y"] + S["L3"] * S["Z"] + S["L4"]
    ny = S["L5"] * S["X"] + S["L6"] * S["Y"] + S["L7"] * S["Z"] + S["L8"]
    return nx, ny, den


def dlt_linear_equations(inputs: dict) -> dict:
    """(4.2.1) and (4.3.1): v = (denominator of (4.1.7))·(DLT image − measured), linear in the unknowns?

    ``inputs``: ``vx``, ``vy`` (strings) and ``unknowns`` (the names the equations must be linear
    in: L1…L11 for the resection, X, Y, Z for the intersection). Decided by ``sympy.expand``.
    """
    nx, ny, den = _dlt_symbolic()
    x, y = _SYM["x"], _SYM["y"]
    derived = (sp.expand(nx - x * den), sp.expand(ny - y * den))
    printed = [sp.expand(_parse(inputs[k], _SYM)) for k in ("vx", "vy")]
    same = all(sp.expand(p - d) == 0 for p, d in zip(printed, derived))
    unknowns = [_SYM[u] for u in inputs["unknowns"]]
    linear = all(sp.Poly(p, *unknowns).total_degree() <= 1 for p in printed)
    return _ok(same and linear)


def _synthetic_resection_data(n=8, seed=2):
    """An exact, non-coplanar control set seen by one of the random cameras (floats)."""
    s = _samples(1, seed=seed)[0]
    A = np.array(s["A"], dtype=float)
    S = np.array(s["S"], dtype=float).ravel()
    val = s["values"]
    fx, fy, x0, y0 = (float(val[k]) for k in ("fx", "fy", "x0", "y0"))
    rng = np.random.default_rng(seed)
    XYZ = np.column_stack([rng.uniform(-30, 30, n), rng.uniform(-30, 30, n), rng.uniform(-10, 10, n)])
    uvw = (XYZ - S) @ A
    xy = np.column_stack([x0 - fx * uvw[:, 0] / uvw[:, 2], y0 - fy * uvw[:, 1] / uvw[:, 2]])
    return XYZ, xy, np.array([float(v) for v in s["L"]])


def dlt_matrix_form(inputs: dict) -> dict:
    """(4.2.2) BM + L = v with the (lost) solution (4.2.3) M = −(BᵀB)⁻¹BᵀL.

    ``inputs``: ``B_rows`` (the two rows of B per point, strings of 11 entries in X, Y, Z, x, y),
    ``free`` (the two free terms) and ``solution`` (a matrix expression in ``B``, ``l``).
    Checks (a) symbolically that B·M + L is (4.2.1), (b) numerically that the solution formula
    returns the true L₁…L₁₁ from exact images of 8 non-coplanar control points.
    """
    nx, ny, den = _dlt_symbolic()
    x, y = _SYM["x"], _SYM["y"]
    Ms = sp.Matrix([_SYM[f"L{i}"] for i in range(1, 12)])
    rows = [sp.Matrix([[_parse(e, _SYM) for e in row]]) for row in inputs["B_rows"]]
    free = [_parse(e, _SYM) for e in inputs["free"]]
    symbolic = all(sp.expand((row * Ms)[0] + fr - d) == 0
                   for row, fr, d in zip(rows, free, (nx - x * den, ny - y * den)))
    XYZ, xy, L_true = _synthetic_resection_data()
    B, l = [], []
    for (X, Y, Z), (xi, yi) in zip(XYZ, xy):
        vals = {"X": X, "Y": Y, "Z": Z, "x": xi, "y": yi}
        for row_text, fr_text in zip(inputs["B_rows"], inputs["free"]):
            B.append([float(_parse(e, vals)) for e in row_text])
            l.append(float(_parse(fr_text, vals)))
    M = _parse(inputs["solution"], {"B": sp.Matrix(B), "l": sp.Matrix(l)})
    M = np.array(M, dtype=float).ravel()
    numeric = M.shape == (11,) and np.allclose(M, L_true, rtol=1e-7, atol=1e-10)
    return _ok(symbolic and numeric)


def interior_orientation_from_dlt(inputs: dict) -> dict:
    """(4.2.4): L, x₀, y₀, f_x, f_y as printed, evaluated in order from the derived L₁…L₁₁.

    L must equal the derived factor D = −(a₁₃X_S + a₂₃Y_S + a₃₃Z_S) (its sign matters for (4.2.6));
    the samples have the object origin in front of the camera (D < 0).
    """
    flags = []
    for s in _samples():
        val = dict(s["values"])
        truth = {k: val[k] for k in ("x0", "y0", "fx", "fy")}
        Dn = -(s["A"][:, 2].dot(s["S"]))
        val["L"] = _parse(inputs["L"], val)
        ok = _is_zero(val["L"] - Dn)
        for key in ("x0", "y0", "fx", "fy"):
            val[key] = _parse(inputs[key], val)
            ok = ok and _is_zero(val[key] - truth[key])
        flags.append(ok)
    return _ok(all(flags))


def projection_centre_from_dlt(inputs: dict) -> dict:
    """(4.2.5): the printed expression (in ``M``, ``L4``, ``L8``) gives the projection centre?"""
    flags = []
    for s in _samples():
        flags.append(_is_zero(sp.Matrix(_parse(inputs["centre"], s["values"])) - s["S"]))
    return _ok(all(flags))


def rotation_from_dlt(inputs: dict) -> dict:
    """(4.2.6): the printed a_ij (3×3 strings in L, x₀, y₀, f_x, f_y, L₁…L₁₁) give A (camera → object)?

    L is taken from (4.2.4), −1/√(L₉² + L₁₀² + L₁₁²), with the object origin in front of the camera.
    """
    flags = []
    for s in _samples():
        val = dict(s["values"])
        val["L"] = -1 / sp.sqrt(val["L9"] ** 2 + val["L10"] ** 2 + val["L11"] ** 2)
        A = sp.Matrix([[_parse(e, val) for e in row] for row in inputs["rows"]])
        flags.append(_is_zero(A - s["A"]))
    return _ok(all(flags))


# =================================================================================================
# §4.4 coplanarity in matrix form, the fundamental and essential matrices
# =================================================================================================
def _vectors():
    b = sp.Matrix(sp.symbols("bx by bz", real=True))
    r1 = sp.Matrix(sp.symbols("X1 Y1 Z1", real=True))
    r2 = sp.Matrix(sp.symbols("X2 Y2 Z2", real=True))
    return b, r1, r2


def _skew_from(rows, b):
    return sp.Matrix([[_parse(e, {"bx": b[0], "by": b[1], "bz": b[2]}) for e in row] for row in rows])


PRINTED_SKEW = [["0", "-bz", "by"], ["bz", "0", "-bx"], ["-by", "bx", "0"]]


def triple_product_forms(inputs: dict) -> dict:
    """(4.4.2): every printed form (strings in ``b``, ``r1``, ``r2``) equals b·(r₁ × r₂) = det[b; r₁; r₂]?"""
    b, r1, r2 = _vectors()
    derived = sp.Matrix.vstack(b.T, r1.T, r2.T).det()
    forms = [_parse(t, {"b": b, "r1": r1, "r2": r2}) for t in inputs["printed"]]
    forms = [f[0] if isinstance(f, sp.MatrixBase) else f for f in forms]
    return _ok(all(sp.expand(f - derived) == 0 for f in forms))


def skew_matrix_formula(inputs: dict) -> dict:
    """(4.4.3)/(4.4.4): S_b·r = b × r for the printed S_b?"""
    b, r, _ = _vectors()
    Sb = _skew_from(inputs["Sb"], b)
    return _ok(all(sp.expand(e) == 0 for e in Sb * r - b.cross(r)))


def coplanarity_matrix_form(inputs: dict) -> dict:
    """(4.4.5): b·(r₁ × r₂) equals the printed matrix form (a string in ``r1``, ``r2``, ``Sb``)?

    ``mode``: ``"identity"`` — equal as expressions (what (4.4.5) writes); ``"condition"`` — the
    same condition "= 0", i.e. equal up to a non-zero constant factor (what (4.4.6) needs).
    S_b is the printed (4.4.4) unless ``Sb`` is given.
    """
    b, r1, r2 = _vectors()
    Sb = _skew_from(inputs.get("Sb", PRINTED_SKEW), b)
    printed = _parse(inputs["printed"], {"r1": r1, "r2": r2, "Sb": Sb})
    printed = sp.expand(printed[0] if isinstance(printed, sp.MatrixBase) else printed)
    derived = sp.expand(sp.Matrix.vstack(b.T, r1.T, r2.T).det())
    if inputs.get("mode", "identity") == "identity":
        return _ok(sp.expand(printed - derived) == 0)
    ratio = sp.cancel(printed / derived)
    return _ok(ratio != 0 and ratio.is_number)


def _pair_samples(n_cameras=3, n_points=3, seed=7):
    """Exact random pairs: camera 1 = model frame (A₁ = E, S₁ = 0), camera 2 at b with A₂.

    Homogeneous images r′ = (x, y, 1) of (1.4.12) with f_x, f_y: r₁′ ≃ K·D·M and r₂′ ≃ K·D·A₂ᵀ(M − b).
    """
    rng = np.random.default_rng(seed)
    out = []
    for _ in range(n_cameras):
        A2 = quaternion_rotation(_rat(rng, -1, 1), _rat(rng, -1, 1), _rat(rng, -1, 1), _rat(rng, 1, 3))
        b = sp.Matrix([_rat(rng, 1, 3), _rat(rng, -1, 1), _rat(rng, -1, 1)])
        fx, fy, x0, y0 = _rat(rng, 50, 150), _rat(rng, 50, 150), _rat(rng, -2, 2), _rat(rng, -2, 2)
        K = sp.Matrix([[fx, 0, x0], [0, fy, y0], [0, 0, 1]])
        pts = []
        for _ in range(n_points):
            M = sp.Matrix([_rat(rng, -3, 3), _rat(rng, -3, 3), _rat(rng, -12, -6)])
            h1, h2 = K * D_MATRIX * M, K * D_MATRIX * A2.T * (M - b)
            pts.append((h1 / h1[2], h2 / h2[2]))
        Sb = sp.Matrix([[0, -b[2], b[1]], [b[2], 0, -b[0]], [-b[1], b[0], 0]])
        out.append({"A2": A2, "b": b, "K": K, "Sb": Sb, "points": pts})
    return out


def epipolar_matrix(inputs: dict) -> dict:
    """(4.4.9)/(4.4.10) and (4.4.16): does r₁ᵀ·F·r₂ = 0 (4.4.11) hold for the printed F (or E)?

    ``inputs``: ``matrix`` (a string in ``Kinv``, ``Sb``, ``A2``, ``D``) and ``calibrated``:
    False — r = r′ = (x, y, 1) with K of (4.1.2) (the fundamental matrix); True — r = r″ = K⁻¹r′
    of (4.4.15) (the essential matrix, K drops out). A₂ is the rotation of image 2 as defined
    by (4.4.7): camera → model, with A₁ = E. Rejects a zero matrix.
    """
    calibrated = bool(inputs.get("calibrated", False))
    flags = []
    for s in _pair_samples():
        Kinv = sp.eye(3) if calibrated else s["K"].inv()
        F = sp.Matrix(_parse(inputs["matrix"], {"Kinv": Kinv, "Sb": s["Sb"], "A2": s["A2"]}))
        ok = F.shape == (3, 3) and F != sp.zeros(3, 3)
        for r1, r2 in s["points"]:
            if calibrated:
                r1, r2 = s["K"].inv() * r1, s["K"].inv() * r2
            ok = ok and _is_zero((r1.T * F * r2)[0])
        flags.append(ok)
    return _ok(all(flags))


def eight_point_equation(inputs: dict) -> dict:
    """(4.4.13)/(4.4.14): the printed linear equation is (x₁ y₁ 1)·F·(x₂ y₂ 1)ᵀ with f₃₃ = 1?"""
    S = _SYM
    F = sp.Matrix(3, 3, [S[f"f{i}{j}"] for i in range(1, 4) for j in range(1, 4)]).subs(S["f33"], 1)
    derived = sp.expand((sp.Matrix([[S["x1"], S["y1"], 1]]) * F * sp.Matrix([S["x2"], S["y2"], 1]))[0])
    return _ok(sp.expand(_parse(inputs["printed"], S) - derived) == 0)


def epipolar_line(inputs: dict) -> dict:
    """Line after (4.4.16): does l₂ (a string in ``F``/``E`` and ``r1``) pass through the corresponding r₂?

    F and E are the matrices of the book's equations (4.4.11)/(4.4.16), r₁ᵀFr₂ = 0, built from a
    pose with the corrected (4.4.10) (``epipolar_matrix`` proves that form).
    """
    calibrated = bool(inputs.get("calibrated", False))
    flags = []
    for s in _pair_samples(seed=11):
        Kinv = sp.eye(3) if calibrated else s["K"].inv()
        F = Kinv.T * D_MATRIX * s["Sb"] * s["A2"] * D_MATRIX * Kinv
        ok = True
        for r1, r2 in s["points"]:
            if calibrated:
                r1, r2 = s["K"].inv() * r1, s["K"].inv() * r2
            l2 = sp.Matrix(_parse(inputs["printed"], {"F": F, "E": F, "r1": r1}))
            ok = ok and l2[:2, 0] != sp.zeros(2, 1) and _is_zero((l2.T * r2)[0])
        flags.append(ok)
    return _ok(all(flags))


# =================================================================================================
# Inline numeric statements (ids 4.0-…)
# =================================================================================================
def _generic_camera(seed=0):
    rng = np.random.default_rng(seed)
    io = InteriorOrientation(100.0, 0.05, -0.03)
    eo = ExteriorOrientation(*rng.uniform(-50, 50, 2), 1000.0, *np.radians(rng.uniform(-4, 4, 3)))
    XYZ = np.column_stack([rng.uniform(-400, 400, 40), rng.uniform(-400, 400, 40), rng.uniform(-60, 60, 40)])
    return io, eo, XYZ


def dlt_parameter_count(inputs: dict) -> dict:
    """§4.2 line 2716, "all eleven coefficients": the 11 L's and the 11 camera parameters they hold.

    ``n_coefficients`` is the rank of ∂(L₁…L₁₁)/∂(X_S, Y_S, Z_S, ω, α, κ, x₀, y₀, f_x, f_y, skew)
    (central differences of :func:`photolib.projective.dlt_from_orientation`): 11 means the
    coefficients and the 6 + 5 camera parameters determine each other locally.
    ``n_without_affine``: the rank with only the 9 metric parameters (f_x = f_y, no skew).
    """
    from .. import projective

    io, eo, _ = _generic_camera()
    p0 = np.array([*eo.vector, io.x0, io.y0, io.f, io.f, 0.0])

    def L_of(p):
        return projective.dlt_from_orientation(InteriorOrientation(100.0, p[6], p[7]),
                                               ExteriorOrientation(*p[:6]), fx=p[8], fy=p[9], skew=p[10])

    steps = np.array([1e-2] * 3 + [1e-6] * 3 + [1e-4] * 5)
    J = np.column_stack([(L_of(p0 + h * e) - L_of(p0 - h * e)) / (2 * h) for h, e in zip(steps, np.eye(11))])
    Jn = J / np.linalg.norm(J, axis=0)
    rank = int(np.linalg.matrix_rank(Jn, tol=1e-7))
    J9 = np.column_stack([Jn[:, :8], J[:, 8] + J[:, 9]])          # f_x = f_y = f, skew = 0
    return {"n_coefficients": rank, "n_without_affine": int(np.linalg.matrix_rank(J9 / np.linalg.norm(J9, axis=0),
                                                                                   tol=1e-7))}


def _min_rank_count(rank_of_n, target, n_max=12):
    for n in range(1, n_max + 1):
        if rank_of_n(n) >= target:
            return n
    return None


def minimum_control_points(inputs: dict) -> dict:
    """§4.2 line 2719 / §4.3 line 2748: the fewest control points for the DLT and for (1.8) resection.

    ``dlt_min_points``: the smallest n for which the design matrix of (4.2.1) has rank 11 (points
    in general position, relief ±60 m). ``classical_min_points``: the smallest n for which the
    Jacobian of the collinearity equations (1.8.2) in the 6 exterior elements has rank 6.
    ``coplanar_rank``: the rank of (4.2.1) for 12 points on one plane (the DLT then fails).
    """
    from .. import derivations, projective
    from ..single_image import project

    io, eo, XYZ = _generic_camera()
    xy = project(XYZ, eo, io)

    def dlt_rank(n):
        B, _ = projective.dlt_design(XYZ[:n], xy[:n])
        return np.linalg.matrix_rank(B / np.linalg.norm(B, axis=0), tol=1e-9)

    _, jac = derivations.collinearity_model(eo.order).compile()

    def classical_rank(n):
        X, Y, Z = XYZ[:n].T
        J = np.asarray(jac(*eo.vector, X, Y, Z, *xy[:n].T, np.full(n, io.f), np.full(n, io.x0),
                           np.full(n, io.y0)), dtype=float).reshape(2, 6, n).transpose(2, 0, 1).reshape(2 * n, 6)
        return np.linalg.matrix_rank(J / np.linalg.norm(J, axis=0), tol=1e-9)

    plane = XYZ[:12].copy()
    plane[:, 2] = 0.1 * plane[:, 0] - 0.05 * plane[:, 1] + 20.0
    Bp, _ = projective.dlt_design(plane, project(plane, eo, io))
    return {"dlt_min_points": _min_rank_count(dlt_rank, 11),
            "classical_min_points": _min_rank_count(classical_rank, 6),
            "coplanar_rank": int(np.linalg.matrix_rank(Bp / np.linalg.norm(Bp, axis=0), tol=1e-9))}


def _pair_images(seed=3, n=20):
    from ..single_image import project

    rng = np.random.default_rng(seed)
    io = InteriorOrientation(100.0)
    eo1 = ExteriorOrientation.from_degrees(0, 0, 1000, 1.0, 3.0, 2.0)
    eo2 = ExteriorOrientation.from_degrees(500, 0, 1000, -2.0, -1.0, 5.0)
    XYZ = np.column_stack([rng.uniform(-100, 600, n), rng.uniform(-500, 500, n), rng.uniform(-60, 60, n)])
    return io, eo1, eo2, XYZ, project(XYZ, eo1, io), project(XYZ, eo2, io)


def _eight_column_design(h1, h2):
    """Rows of (4.4.14): coefficients of f₁₁ … f₃₂ (f₃₃ = 1 moved to the right-hand side)."""
    return np.einsum("ni,nj->nij", h1, h2).reshape(len(h1), 9)[:, :8]


def epipolar_min_points(inputs: dict) -> dict:
    """§4.4 lines 2900 and 2921: the fewest points for F (eight) and for E ("five") by the linear method.

    ``F_min_points`` and ``E_linear_min_points``: the smallest n for which the linear system
    (4.4.14) — for E in normalised coordinates (4.4.15) — has rank 8, i.e. a unique solution.
    (That a non-linear five-point solver does recover E from five points is checked against
    OpenCV in the tests, :func:`five_point_solver_recovers_E`.)
    """
    from .. import projective

    io, eo1, eo2, XYZ, xy1, xy2 = _pair_images()
    h1 = np.column_stack([xy1, np.ones(len(xy1))])
    h2 = np.column_stack([xy2, np.ones(len(xy2))])
    n1 = projective.normalized_image_coordinates(xy1, io)
    n2 = projective.normalized_image_coordinates(xy2, io)

    def rank(a, b):
        return lambda n: np.linalg.matrix_rank(_eight_column_design(a[:n], b[:n]), tol=1e-9 * np.abs(a).max() ** 2)

    return {"F_min_points": _min_rank_count(rank(h1, h2), 8),
            "E_linear_min_points": _min_rank_count(rank(n1, n2), 8)}


def five_point_solver_recovers_E() -> bool:
    """OpenCV's non-linear five-point solver, fed exactly 5 correspondences of the same pair,
    returns the true E among its candidates — the sense in which five points do suffice.
    Needs OpenCV (the ``test`` extra); used by the tests, not by ``photolib verify``."""
    import cv2

    from .. import conventions, projective

    io, eo1, eo2, XYZ, xy1, xy2 = _pair_images()
    E_true = projective.essential_from_orientation(eo1, eo2)
    flip = np.diag([1.0, -1.0, 1.0])
    E_cv_true = flip @ E_true @ flip
    cands, _ = cv2.findEssentialMat(conventions.image_to_opencv(xy1[:5]), conventions.image_to_opencv(xy2[:5]),
                                    conventions.camera_matrix(io), method=cv2.LMEDS)
    found = False
    for k in range(0, len(cands), 3):
        C = cands[k:k + 3] / np.linalg.norm(cands[k:k + 3])
        found = found or min(np.abs(C - E_cv_true).max(), np.abs(C + E_cv_true).max()) < 1e-6
    return bool(found)
