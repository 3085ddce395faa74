"""Chapter 1, §1.3: the printed rotation formulas checked against sympy derivations.

Each function takes the ``inputs`` of a ``[[formula]]`` entry of ``textbook/ch01.toml`` — the
formula as printed, written as sympy strings in the symbols ω, α, κ (``omega``, ``alpha``,
``kappa``), a_ij (``a11`` …) or the quaternion a, b, c, d — and returns
``{"printed_equals_derived": bool}``. The derivations start from the elementary matrices
A_ω, A_α, A_κ printed before (1.3.2) (:func:`photolib.derivations.elementary_rotations`).
"""

from __future__ import annotations

import sympy as sp

from ..derivations import alpha, elementary_rotations, kappa, omega, rotation_matrix_symbolic

a, b, c, d = sp.symbols("a b c d", real=True)
A_SYMBOLS = sp.Matrix(3, 3, lambda i, j: sp.Symbol(f"a{i + 1}{j + 1}", real=True))
_NAMES = {"omega": omega, "alpha": alpha, "kappa": kappa, "a": a, "b": b, "c": c, "d": d,
          **{str(s): s for s in A_SYMBOLS}}


def _parse(text: str) -> sp.Expr:
    return sp.sympify(text, locals=_NAMES)


def product(order: str) -> sp.Matrix:
    """A_ω A_α A_κ (``"wak"``, (1.3.2)) or A_κ A_α A_ω (``"kaw"``, (1.3.4)), from the library's sympy rotation."""
    if order not in ("wak", "kaw"):
        raise ValueError(f"unknown order {order!r}")
    return rotation_matrix_symbolic(order)


def _is_zero(expr) -> bool:
    """Exact zero test of a trigonometric expression.

    Fast path (exact): every sin/cos of a rational multiple of an angle θ is written as a
    polynomial in s = sin(θ/D), c = cos(θ/D) (D the common denominator), the expression brought
    to one fraction, and its numerator reduced modulo s² + c² − 1 for each angle — a canonical
    form (degree ≤ 1 in every s), so the numerator is an identity on the circles iff it reduces
    to 0. Anything else (other functions, non-rational angle multiples) goes to sympy's simplify.
    """
    original = expr
    expr = sp.sympify(expr).replace(sp.tan, lambda u: sp.sin(u) / sp.cos(u))
    expr = sp.expand_trig(expr)
    if any(not p.exp.is_Integer for p in expr.atoms(sp.Pow)):
        return sp.simplify(sp.expand_trig(sp.expand(original))) == 0
    trig = expr.atoms(sp.sin, sp.cos)
    if expr.atoms(sp.Function) - trig:
        return sp.simplify(sp.expand_trig(sp.expand(original))) == 0
    per_angle = {}
    for t in trig:
        coeff, rest = t.args[0].as_coeff_Mul()
        if not (coeff.is_Rational and rest.is_Symbol):
            return sp.simplify(sp.expand_trig(sp.expand(original))) == 0
        per_angle.setdefault(rest, set()).add(coeff)
    subs, circles = {}, []
    for theta, coeffs in per_angle.items():
        den = sp.ilcm(1, 1, *[q.q for q in coeffs])
        h = sp.Dummy("h", real=True)
        s_, c_ = sp.Dummy("s", real=True), sp.Dummy("c", real=True)
        for q in coeffs:
            n = int(q * den)
            for fn in (sp.sin, sp.cos):
                poly = sp.expand_trig(fn(n * h))
                subs[fn(q * theta)] = poly.subs({sp.sin(h): s_, sp.cos(h): c_})
        circles.append((s_, c_))
    numerator = sp.numer(sp.together(expr.xreplace(subs)))
    gens = [g for pair in circles for g in pair]
    poly = sp.Poly(sp.expand(numerator), *gens) if gens else sp.Poly(sp.expand(numerator), sp.Dummy())
    reduced = sp.Integer(0)
    for monom, coeff in poly.terms():
        term = coeff
        for i, (s_, c_) in enumerate(circles):
            e_s, e_c = monom[2 * i], monom[2 * i + 1]
            term *= s_ ** (e_s % 2) * (1 - c_ ** 2) ** (e_s // 2) * c_ ** e_c
        reduced += term
    return sp.expand(reduced) == 0


def element_list(inputs: dict) -> dict:
    """(1.3.2) / (1.3.5): the nine printed a_ij equal the product of the elementary matrices."""
    printed = sp.Matrix(3, 3, [_parse(e) for e in inputs["elements"]])
    derived = product(inputs["order"])
    return {"printed_equals_derived": all(_is_zero(p - q) for p, q in zip(printed, derived))}


def angle_formulas(inputs: dict) -> dict:
    """(1.3.3) / (1.3.6): the printed arctan/arcsin formulas return the angles of the matrix.

    Each printed formula is ``arctg(ratio)`` or ``arcsin(value)`` of elements a_ij. With the
    elements of the order's matrix substituted, the ratio must equal tan of the angle and the
    value sin of the angle — then the formula gives the angle on the principal branch
    (|ω|, |κ| < 90°, |α| ≤ 90°); outside it atan2 is needed (the book notes the ambiguity).
    """
    A = product(inputs["order"])
    subs = {A_SYMBOLS[i, j]: A[i, j] for i in range(3) for j in range(3)}
    ok = True
    for name, symbol in (("omega", omega), ("alpha", alpha), ("kappa", kappa)):
        formula = _parse(inputs[name]).subs(subs)
        if isinstance(formula, sp.atan):
            ok &= _is_zero(formula.args[0] - sp.tan(symbol))
        elif isinstance(formula, sp.asin):
            ok &= _is_zero(formula.args[0] - sp.sin(symbol))
        else:
            return {"printed_equals_derived": False}
    return {"printed_equals_derived": bool(ok)}


def orthogonality(inputs: dict) -> dict:
    """The six relations after (1.3.1) (each printed as ``expression = value``) hold for the
    matrices of both sequences."""
    ok = True
    for order in ("wak", "kaw"):
        A = product(order)
        subs = {A_SYMBOLS[i, j]: A[i, j] for i in range(3) for j in range(3)}
        for lhs, rhs in inputs["relations"]:
            ok &= _is_zero(_parse(lhs).subs(subs) - _parse(rhs))
    return {"printed_equals_derived": bool(ok)}


def quaternion_rotation(a_=a, b_=b, c_=c, d_=d) -> sp.Matrix:
    """The Euler–Rodrigues matrix (d² − v·v)E + 2vvᵀ + 2d[v]× of q = (v, d), v = (a, b, c):
    |q|² times the counter-clockwise rotation by 2·atan2(|v|, d) about v (the library's model,
    :func:`photolib.derivations.quaternion_rotation_symbolic`)."""
    from ..derivations import quaternion_rotation_symbolic
    return quaternion_rotation_symbolic(a_, b_, c_, d_)


def quaternion_matrix(inputs: dict) -> dict:
    """(1.3.7): the printed matrix is the Euler–Rodrigues matrix of (a, b, c, d), so AᵀA = m²E
    and det A = m³ with m = a² + b² + c² + d² (orthogonal only up to scale; a rotation for m = 1),
    and its half-angle quaternions reproduce the elementary matrices A_ω, A_α, A_κ."""
    printed = sp.Matrix(3, 3, [_parse(e) for e in inputs["elements"]])
    m = _parse(inputs["scale"])
    ok = all(sp.expand(p - q) == 0 for p, q in zip(printed, quaternion_rotation()))
    ok &= sp.expand(printed.T * printed - m ** 2 * sp.eye(3)) == sp.zeros(3, 3)
    ok &= sp.expand(printed.det() - m ** 3) == 0
    t = sp.Symbol("t", real=True)
    h = (sp.sin(t / 2), sp.cos(t / 2))
    for axis, elementary in enumerate(elementary_rotations(t, t, t)):
        q = [0, 0, 0, h[1]]
        q[axis] = h[0]
        ok &= all(_is_zero(x - y) for x, y in zip(printed.subs(dict(zip((a, b, c, d), q))), elementary))
    return {"printed_equals_derived": bool(ok)}


def _hamilton(p, q):
    pv, pw, qv, qw = sp.Matrix(p[:3]), p[3], sp.Matrix(q[:3]), q[3]
    v = pw * qv + qw * pv + pv.cross(qv)
    return [v[0], v[1], v[2], pw * qw - (pv.T * qv)[0]]


def quaternion_angle_relations(inputs: dict) -> dict:
    """The relations after (1.3.7) between a unit quaternion and the κ–α–ω angles of (1.3.5).

    Derivation: the unit quaternion of A = A_κ A_α A_ω is q = q_κ ⊗ q_α ⊗ q_ω with the
    half-angle quaternions q_ω = (sin ω/2, 0, 0, cos ω/2), … Substituted into the right-hand
    sides, each must reduce to its printed left-hand side.
    """
    half = lambda ang, axis: [sp.sin(ang / 2) if i == axis else 0 for i in range(3)] + [sp.cos(ang / 2)]
    q = _hamilton(_hamilton(half(kappa, 2), half(alpha, 1)), half(omega, 0))
    subs = dict(zip((a, b, c, d), q))
    ok = True
    for lhs, rhs in inputs["relations"]:
        ok &= _is_zero(_parse(lhs) - _parse(rhs).subs(subs))
    return {"printed_equals_derived": bool(ok)}


def elementary_matrices(inputs: dict) -> dict:
    """The elementary matrices before (1.3.2): each is printed twice, as direction cosines
    (cos 90°, cos(90° + ω), …) and in sines and cosines; both forms must agree, and the second
    must be the matrix the library uses (counter-clockwise rotations about X, Y, Z)."""
    ok = True
    library = elementary_rotations()
    for name, ref in zip(("omega", "alpha", "kappa"), library):
        cosines = sp.Matrix(3, 3, [_parse(e) for e in inputs[name + "_cosines"]])
        trig = sp.Matrix(3, 3, [_parse(e) for e in inputs[name]])
        ok &= all(_is_zero(x - y) for x, y in zip(cosines, trig))
        ok &= all(_is_zero(x - y) for x, y in zip(trig, ref))
    return {"printed_equals_derived": bool(ok)}
