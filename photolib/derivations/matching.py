"""Area matching and target fitting in sympy — Chapter 5, §5.1–§5.4 and §5.11.

* :func:`lsm_partials` — the coefficients a₁…a₈ of the least-squares-matching correction
  equations (5.4.3)/(5.4.6): derived (the derivatives of the residual (5.4.5) by p, q, b₁, b₂,
  c₁, c₂, k₀, k₁) or as printed in (5.4.4)/(5.4.7). The printed a₃…a₆ carry the wrong sign:
  a₁ = g_x and a₂ = g_y are derivatives of the residual f₁ − f₂(b₁x₁ + b₂y₁ − p, …), while
  a₃ = g_x·x₁ … are derivatives of f₂ itself (the opposite convention).
* :func:`lsm_jacobian` — those coefficients as a vectorised numpy function (lambdified once),
  used by :func:`photolib.matching.lsm_affine` and, with ``as_printed=True``, by its "as printed"
  mode, which diverges.
* :func:`parabola_vertex_symbolic` — the vertex (5.1.5) of the parabola (5.1.3), and its
  closed form for three equally spaced values.
* :func:`circle_partials` — the coefficients of (5.11.4) (not printed in the book) derived from
  the circle equation (5.11.3), with the numpy function used by :func:`photolib.targets.circle_fit`.

Symbols: u, v are the template coordinates x₁, y₁ counted from the window centre; g_x, g_y the
gradient of image 2 at the warped position; f₁ the template grey value.
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np
import sympy as sp

from ..errors import InputError

__all__ = ["LSM_PARAMETERS", "lsm_residual", "lsm_partials", "lsm_jacobian", "parabola_vertex_symbolic",
           "circle_partials"]

LSM_PARAMETERS = ("p", "q", "b1", "b2", "c1", "c2", "k0", "k1")
"""Unknowns of (5.4.6), in the order of a₁…a₈."""

_p, _q, _b1, _b2, _c1, _c2, _k0, _k1 = sp.symbols("p q b1 b2 c1 c2 k0 k1", real=True)
_u, _v, _gx, _gy, _f1 = sp.symbols("u v g_x g_y f_1", real=True)
_PARAMS = (_p, _q, _b1, _b2, _c1, _c2, _k0, _k1)
_DATA = (_u, _v, _gx, _gy, _f1)
_F2 = sp.Function("f_2")


def _model(model):
    if model not in ("affine", "shift"):
        raise InputError(f"model must be 'affine' or 'shift', got {model!r}")
    return model


def lsm_residual():
    """The residual of (5.4.5): k₀ + k₁·f₁(x₁, y₁) − f₂(b₁x₁ + b₂y₁ − p, c₁x₁ + c₂y₁ − q).

    With b₁ = c₂ = 1, b₂ = c₁ = 0, k₀ = 0, k₁ = 1 it is the residual (5.2.1) of the shift-only
    matching; without k₀, k₁ it is (5.4.2).

    Returns
    -------
    tuple
        ``(expr, parameters, (u, v, f1), f2)``: the sympy residual, the eight unknown symbols
        p, q, b₁, b₂, c₁, c₂, k₀, k₁, the data symbols and the undefined function f₂.

    Raises
    ------
    InputError
        Never (no arguments).

    References
    ----------
    Chibunichev (2022), §5.2, eq. (5.2.1); §5.4, eqs. (5.4.1), (5.4.2), (5.4.5).

    Examples
    --------
    >>> expr, params, data, f2 = lsm_residual()
    >>> [str(s) for s in params]
    ['p', 'q', 'b1', 'b2', 'c1', 'c2', 'k0', 'k1']
    """
    x2 = _b1 * _u + _b2 * _v - _p
    y2 = _c1 * _u + _c2 * _v - _q
    return _k0 + _k1 * _f1 - _F2(x2, y2), _PARAMS, (_u, _v, _f1), _F2


def _gradient_symbol(sub):
    """g_x or g_y for Subs(Derivative(f₂(…, ξ, …), ξ), ξ, ·): the slot of f₂ that ξ occupies."""
    der = sub.expr
    (var, _count), = der.variable_count
    return (_gx, _gy)[der.expr.args.index(var)]


@lru_cache(maxsize=None)
def _derived():
    expr, params, _, _f2 = lsm_residual()
    out = {}
    for i, s in enumerate(params, start=1):
        # the chain rule leaves Subs(Derivative(f2(ξ, ·), ξ), ξ, x₂): that is g_x (slot 0) or g_y
        d = sp.diff(expr, s).replace(lambda e: isinstance(e, sp.Subs), _gradient_symbol)
        out[f"a{i}"] = sp.expand(d)
    return out


_PRINTED = {"a1": _gx, "a2": _gy, "a3": _gx * _u, "a4": _gx * _v, "a5": _gy * _u, "a6": _gy * _v,
            "a7": sp.Integer(1), "a8": _f1}


def lsm_partials(which: str = "derived") -> dict:
    """a₁…a₈ of (5.4.6): derived with sympy or as printed in (5.4.4)/(5.4.7).

    Parameters
    ----------
    which : {"derived", "printed"}
        ``"derived"``: the derivatives of the residual (5.4.5) by p, q, b₁, b₂, c₁, c₂, k₀, k₁
        (chain rule with ∂f₂/∂x₂ = g_x, ∂f₂/∂y₂ = g_y). ``"printed"``: the book's coefficients.

    Returns
    -------
    dict
        ``{"a1": expr, …, "a8": expr}`` in the symbols u (= x₁), v (= y₁), g_x, g_y, f_1.

    Raises
    ------
    InputError
        If ``which`` is neither "derived" nor "printed".

    References
    ----------
    Chibunichev (2022), §5.4, eqs. (5.4.3)–(5.4.7); §5.2, eq. (5.2.2).

    Examples
    --------
    >>> d, pr = lsm_partials("derived"), lsm_partials("printed")
    >>> d["a1"], d["a3"], pr["a3"]
    (g_x, -g_x*u, g_x*u)
    """
    if which == "derived":
        return dict(_derived())
    if which == "printed":
        return dict(_PRINTED)
    raise InputError(f"which must be 'derived' or 'printed', got {which!r}")


@lru_cache(maxsize=None)
def _jacobian_function(as_printed: bool, model: str):
    terms = lsm_partials("printed" if as_printed else "derived")
    keys = ["a1", "a2"] + (["a3", "a4", "a5", "a6"] if model == "affine" else []) + ["a7", "a8"]
    fn = sp.lambdify(_DATA, [terms[k] for k in keys], modules="numpy")

    def jac(u, v, gx, gy, f1, radiometric=True):
        u, v, gx, gy, f1 = np.broadcast_arrays(*(np.asarray(a, dtype=float) for a in (u, v, gx, gy, f1)))
        cols = [np.broadcast_to(np.asarray(c, dtype=float), u.shape) for c in fn(u, v, gx, gy, f1)]
        if not radiometric:
            cols = cols[:-2]
        return np.stack(cols, axis=-1)
    return jac


def lsm_jacobian(as_printed: bool = False, model: str = "affine"):
    """The coefficient matrix of (5.4.6) as a numpy function, lambdified once from sympy.

    Parameters
    ----------
    as_printed : bool
        Use the book's printed coefficients (5.4.4) instead of the derived ones.
    model : {"affine", "shift"}
        ``"affine"``: columns p, q, b₁, b₂, c₁, c₂ (+ k₀, k₁); ``"shift"``: p, q (+ k₀, k₁), (5.2.2).

    Returns
    -------
    callable
        ``jac(u, v, gx, gy, f1, radiometric=True) -> B`` of shape (m, n); with
        ``radiometric=False`` the columns of k₀, k₁ are dropped.

    Raises
    ------
    InputError
        If ``model`` is unknown.

    References
    ----------
    Chibunichev (2022), §5.2, eq. (5.2.2); §5.4, eqs. (5.4.3)–(5.4.7).

    Examples
    --------
    >>> jac = lsm_jacobian()
    >>> jac([2.0], [1.0], [3.0], [5.0], [7.0]).tolist()
    [[3.0, 5.0, -6.0, -3.0, -10.0, -5.0, 1.0, 7.0]]
    >>> float(lsm_jacobian(as_printed=True)([2.0], [1.0], [3.0], [5.0], [7.0])[0, 2])
    6.0
    """
    return _jacobian_function(bool(as_printed), _model(model))


def parabola_vertex_symbolic():
    """The vertex (5.1.5) of the parabola (5.1.3) and its three-point closed form.

    Returns
    -------
    dict
        ``"vertex"``: the solution of dR/dx = 0 for R = a₀ + a₁x + a₂x² (sympy, = −a₁/(2a₂));
        ``"three_point"``: the least-squares (here interpolating) vertex through R(−1) = R₋,
        R(0) = R₀, R(1) = R₊, expressed in R₋, R₀, R₊.

    Raises
    ------
    InputError
        Never (no arguments).

    References
    ----------
    Chibunichev (2022), §5.1, eqs. (5.1.3)–(5.1.5).

    Examples
    --------
    >>> parabola_vertex_symbolic()["vertex"]
    -a1/(2*a2)
    """
    a0, a1, a2, x = sp.symbols("a0 a1 a2 x")
    vertex = sp.solve(sp.diff(a0 + a1 * x + a2 * x ** 2, x), x)[0]
    rm, r0, rp = sp.symbols("R_m R_0 R_p")
    A = sp.Matrix([[1, -1, 1], [1, 0, 0], [1, 1, 1]])
    coef = (A.T * A).inv() * A.T * sp.Matrix([rm, r0, rp])
    three = sp.simplify(vertex.subs({a1: coef[1], a2: coef[2]}))
    return {"vertex": vertex, "three_point": three}


@lru_cache(maxsize=None)
def _circle():
    xi, yi, xc, yc, R = sp.symbols("x_i y_i x_c y_c R", real=True)
    expr = (xi - xc) ** 2 + (yi - yc) ** 2 - R ** 2
    partials = [sp.diff(expr, s) for s in (xc, yc, R)]
    fn = sp.lambdify((xc, yc, R, xi, yi), [expr] + partials, modules="numpy")
    return expr, partials, fn


def circle_partials():
    """Coefficients a₁, a₂, a₃ and free term l of (5.11.4), derived from the circle (5.11.3).

    Returns
    -------
    dict
        ``"residual"``: (x_i − x_c)² + (y_i − y_c)² − R²; ``"a1"``, ``"a2"``, ``"a3"``: its
        derivatives by x_c, y_c, R; ``"numpy"``: a function ``(xc, yc, R, x, y) -> [l, a1, a2, a3]``.

    Raises
    ------
    InputError
        Never (no arguments).

    References
    ----------
    Chibunichev (2022), §5.11, eqs. (5.11.3)–(5.11.4).

    Examples
    --------
    >>> c = circle_partials()
    >>> c["a1"], c["a3"]
    (2*x_c - 2*x_i, -2*R)
    """
    expr, partials, fn = _circle()
    return {"residual": expr, "a1": partials[0], "a2": partials[1], "a3": partials[2], "numpy": fn}
