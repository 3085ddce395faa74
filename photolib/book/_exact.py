"""An exact, fast zero test for the sympy checks of the printed formulas (book layer only).

``is_zero(expr)`` decides whether ``expr`` vanishes identically when it is a rational function of
symbols and of sines/cosines (tangents) of rational multiples of symbols, with rational
coefficients:

* every sin/cos of q·θ (q rational) is written as a polynomial in s = sin(θ/D), c = cos(θ/D), D the
  common denominator of the multiples of θ (``expand_trig`` of sin(nh), cos(nh));
* the expression is brought into sympy's sparse fraction field over ℚ (generators: the s, c of
  every angle first, then the other symbols, lex order), so it is p/q with p, q polynomials;
* p is reduced modulo s² + c² − 1 of every angle. These polynomials, with leading terms s², have
  pairwise coprime leading terms, so they are a Gröbner basis and the remainder is a canonical
  form: p vanishes on the circles (the expression is an identity) iff the remainder is 0.

Anything outside that class (floats, other functions, fractional powers, trigonometric functions
of non-linear arguments) gives ``None``: the caller then keeps its own sympy test (``simplify``,
``cancel``). So the answer is the exact one, without ``simplify``'s heuristics and in a fraction
of its time.
"""

from __future__ import annotations

import sympy as sp
from sympy.polys.rings import ring
from sympy.polys.orderings import lex

__all__: list = []


def _angle_terms(expr):
    """{θ: set of rational multiples q} of the sin/cos atoms, or None if one is not sin/cos(q·θ)."""
    per_angle = {}
    for t in expr.atoms(sp.sin, sp.cos):
        coeff, rest = t.args[0].as_coeff_Mul()
        if not (coeff.is_Rational and rest.is_Symbol):
            return None
        per_angle.setdefault(rest, set()).add(coeff)
    return per_angle


def is_zero(expr, size=600):
    """True/False if ``expr`` (an expression or a matrix) is/is not identically 0; None if undecided.

    ``size``: the largest number of terms (numerator + denominator) an intermediate fraction may have
    before the expression is left undecided.
    """
    if isinstance(expr, sp.MatrixBase):
        results = [is_zero(e, size) for e in expr]
        if any(r is False for r in results):
            return False
        return None if any(r is None for r in results) else True
    expr = sp.sympify(expr)
    if expr.is_Number:
        return None if expr.is_Float else bool(expr == 0)
    if expr.atoms(sp.Float):
        return None
    if expr.atoms(sp.tan, sp.cot):
        expr = expr.replace(sp.tan, lambda u: sp.sin(u) / sp.cos(u)).replace(sp.cot, lambda u: sp.cos(u) / sp.sin(u))
    trig = expr.atoms(sp.sin, sp.cos)
    if any(not (t.args[0].as_coeff_Mul()[1].is_Symbol) for t in trig):
        expr = expr.replace(lambda e: isinstance(e, (sp.sin, sp.cos)) and not e.args[0].as_coeff_Mul()[1].is_Symbol,
                            sp.expand_trig)
        trig = expr.atoms(sp.sin, sp.cos)
    if expr.is_Number:
        return bool(expr == 0)
    if expr.atoms(sp.Function) - trig:
        return None
    if any(not p.exp.is_Integer for p in expr.atoms(sp.Pow)):
        return None
    per_angle = _angle_terms(expr)
    if per_angle is None:
        return None
    subs, circles = {}, []
    for theta, coeffs in sorted(per_angle.items(), key=lambda kv: kv[0].name):
        den = sp.ilcm(1, 1, *[q.q for q in coeffs])
        h = sp.Dummy("h")
        s_, c_ = sp.Dummy(f"s_{theta.name}"), sp.Dummy(f"c_{theta.name}")
        for q in coeffs:
            n = int(q * den)
            for fn in (sp.sin, sp.cos):
                subs[fn(q * theta)] = sp.expand_trig(fn(n * h)).subs({sp.sin(h): s_, sp.cos(h): c_})
        circles.append((s_, c_))
    expr = expr.xreplace(subs)
    others = sorted(expr.free_symbols - {g for pair in circles for g in pair}, key=lambda s: s.name)
    gens = [s_ for s_, _ in circles] + [c_ for _, c_ in circles] + others
    if not gens:
        return None
    R, *elements = ring(gens, sp.QQ, lex)
    memo = _MEMO.setdefault(tuple(gens), {})
    if len(_MEMO) > 64:
        _MEMO.clear()
        memo = _MEMO.setdefault(tuple(gens), {})
    memo.update(zip(gens, ((g, R.one) for g in elements)))
    try:
        numer, denom = _fraction(expr, R, memo, size)
    except _Undecided:      # not a rational function of these generators: leave it to the caller
        return None
    if circles:
        n = len(circles)
        numer = numer.rem([elements[i] ** 2 + elements[n + i] ** 2 - 1 for i in range(n)])
    return not numer


def _reduced(p, q, size=600):
    """p/q as it is (no gcds: sympy's heuristic gcd of many-variable polynomials can take
    minutes); a form that grows beyond ``size`` terms is left to the caller's own test."""
    if len(p) + len(q) > size:
        raise _Undecided
    return p, q


class _Undecided(Exception):
    pass


_MEMO: dict = {}      # generators -> {sub-expression: (p, q)}: shared sub-trees are converted once


def _fraction(expr, R, memo, size=600):
    """(p, q) polynomials of ``R`` with expr = p/q, built bottom-up (q never 0)."""
    hit = memo.get(expr)
    if hit is None:
        hit = memo[expr] = _fraction_new(expr, R, memo, size)
    return hit


def _fraction_new(expr, R, gens, size):
    if expr.is_Rational:
        return R(expr), R.one
    if expr.is_Add:
        p, q = R.zero, R.one
        for arg in expr.args:
            a, b = _fraction(arg, R, gens, size)
            if b == q:
                p = p + a
            else:
                p, q = _reduced(p * b + a * q, q * b, size)
        return p, q
    if expr.is_Mul:
        p, q = R.one, R.one
        for arg in expr.args:
            a, b = _fraction(arg, R, gens, size)
            p, q = _reduced(p * a, q * b, size)
        return p, q
    if expr.is_Pow and expr.exp.is_Integer:
        a, b = _fraction(expr.base, R, gens, size)
        e = int(expr.exp)
        if e < 0:
            if not a:
                raise _Undecided
            a, b, e = b, a, -e
        return a ** e, b ** e
    raise _Undecided


def zero(expr, fallback=None, size=600) -> bool:
    """:func:`is_zero` where it decides, else ``fallback(entry)`` (default: ``simplify(entry) == 0``).

    A matrix is zero when every entry is; each undecided entry goes to the fallback alone.
    """
    if fallback is None:
        fallback = _simplify_zero
    entries = list(expr) if isinstance(expr, (sp.MatrixBase, list, tuple)) else [expr]
    for e in entries:
        exact = is_zero(e, size)
        if not (fallback(e) if exact is None else exact):
            return False
    return True


def _simplify_zero(e) -> bool:
    return sp.simplify(e) == 0


def lambdify(args, expr, modules="numpy"):
    """``sympy.lambdify`` without the generated docstring: the same code and numbers, but the
    docstring prints the whole expression, which for the large partials costs as much as the code."""
    try:
        return sp.lambdify(args, expr, modules, docstring_limit=0)
    except TypeError:       # sympy < 1.13 has no docstring_limit
        return sp.lambdify(args, expr, modules)
