"""The least-squares DSM and true orthophoto in sympy: Chapter 7, §7.8, eqs. (7.8.1)–(7.8.4).

* (7.8.1) the photometric condition F(X, Y) − k_i·f_i(x_i, y_i) = 0 (printed "t_i" is an OCR slip
  for f_i) — :func:`photometric_condition`;
* (7.8.2) collinearity with the elements a_jk of image i — :func:`collinearity_782`, identical to
  (7.3.2) once a_jk are the elements of A (:func:`collinearity_732`, :func:`check_782_equals_732`);
* the coefficients a₁…a₃ of (7.8.3) and a₁…a₉ of (7.8.4), which the book does not print — derived
  here by the chain rule with the image brightness f_i kept as an unknown function of x, y
  (:func:`correction_coefficients`);
* ∂x/∂Z, ∂y/∂Z as numpy code for :func:`photolib.trueortho.lsq_dsm_ortho`
  (:func:`height_partials_function`, lambdified lazily);
* for (7.8.4), the partials of x_i, y_i by the six EO elements, which are those of the
  resection model of Chapter 1 (:func:`photolib.derivations.collinearity.collinearity_model`,
  reused, not re-derived): :func:`eo_partials_function` (numpy) and :func:`check_784_chain_rule`
  (sympy: a₄…a₉ of (7.8.4) = −k_i(∂f_i/∂x·∂x/∂p + ∂f_i/∂y·∂y/∂p) with ∂x/∂p, ∂y/∂p the
  Chapter 1 coefficients a₁…b₆ of (1.8.3)).
"""

from __future__ import annotations

from functools import lru_cache

import sympy as sp

from ..errors import InputError
from .rotation import rotation_matrix_symbolic
from .symbols import X, Xs, Y, Ys, Z, Zs, alpha, f, kappa, omega, x0, y0

__all__ = ["F_sym", "k_sym", "image_function", "photometric_condition", "collinearity_782",
           "collinearity_732", "check_782_equals_732", "height_partials", "correction_coefficients",
           "height_partials_function", "eo_partials_function", "check_784_chain_rule"]

F_sym, k_sym = sp.symbols("F k_i", real=True)
"""The orthophoto brightness F and the photometric gain k_i of image i (7.8.1)."""
_a = sp.Matrix(3, 3, lambda i, j: sp.Symbol(f"a{i + 1}{j + 1}", real=True))
_xs, _ys = sp.symbols("x_i y_i", real=True)
image_function = sp.Function("f_i")
"""The brightness f_i(x_i, y_i) of image i, an undefined sympy function."""


def _order(order):
    if order not in ("kaw", "wak"):
        raise InputError(f"order must be 'kaw' or 'wak', got {order!r}")
    return order


def photometric_condition() -> sp.Expr:
    """(7.8.1): F(X, Y) − k_i·f_i(x_i, y_i), zero at the solution.

    Returns
    -------
    sympy.Expr
        In the symbols F, k_i, x_i, y_i and the function f_i.

    Raises
    ------
    None
        Takes no input.

    References
    ----------
    Chibunichev (2022), §7.8, eq. (7.8.1) (printed "t_i(x_i, y_i)": an OCR/print slip for f_i).

    Examples
    --------
    >>> photometric_condition()
    F - k_i*f_i(x_i, y_i)
    """
    return F_sym - k_sym * image_function(_xs, _ys)


def collinearity_782() -> tuple:
    """(7.8.2) as printed: x_i, y_i in the elements a_jk of image i.

    Returns
    -------
    (sympy.Expr, sympy.Expr)
        x_i and y_i in X, Y, Z, X_S, Y_S, Z_S, f, x₀, y₀ and the symbols a11…a33.

    Raises
    ------
    None
        Takes no input.

    References
    ----------
    Chibunichev (2022), §7.8, eq. (7.8.2).

    Examples
    --------
    >>> x, y = collinearity_782()
    >>> sp.diff(x, sp.Symbol("a11", real=True)).has(f)
    True
    """
    d = sp.Matrix([X - Xs, Y - Ys, Z - Zs])
    U, V, W = (_a.T * d)
    return x0 - f * U / W, y0 - f * V / W


def collinearity_732(order: str = "wak") -> tuple:
    """(7.3.2): x = x₀ − f·x*/z*, y = y₀ − f·y*/z*, (x*, y*, z*)ᵀ = Aᵀ(X − X_S, Y − Y_S, Z − Z_S)ᵀ.

    Parameters
    ----------
    order : {"wak", "kaw"}
        A = A_ω A_α A_κ (1.3.2, ``"wak"``, the book's main definition) or A_κ A_α A_ω.

    Returns
    -------
    (sympy.Expr, sympy.Expr)

    Raises
    ------
    InputError
        An unknown order.

    References
    ----------
    Chibunichev (2022), §7.3, eq. (7.3.2); §1.3, eq. (1.3.2).

    Examples
    --------
    >>> x, y = collinearity_732()
    >>> sp.simplify(x.subs({omega: 0, alpha: 0, kappa: 0}) - (x0 - f * (X - Xs) / (Z - Zs)))
    0
    """
    A = rotation_matrix_symbolic(_order(order))
    U, V, W = A.T * sp.Matrix([X - Xs, Y - Ys, Z - Zs])
    return x0 - f * U / W, y0 - f * V / W


def check_782_equals_732(order: str = "wak") -> bool:
    """True when (7.8.2) with a_jk = A_jk is identically (7.3.2) (sympy ``simplify`` of the difference).

    Parameters
    ----------
    order : {"wak", "kaw"}
        Rotation sequence of A.

    Returns
    -------
    bool

    Raises
    ------
    InputError
        An unknown order.

    References
    ----------
    Chibunichev (2022), §7.3, eq. (7.3.2); §7.8, eq. (7.8.2).

    Examples
    --------
    >>> check_782_equals_732("wak")
    True
    """
    A = rotation_matrix_symbolic(_order(order))
    sub = {_a[i, j]: A[i, j] for i in range(3) for j in range(3)}
    return all(sp.simplify(p.subs(sub) - q) == 0 for p, q in zip(collinearity_782(), collinearity_732(order)))


def height_partials() -> dict:
    """∂x_i/∂Z and ∂y_i/∂Z of (7.8.2): derived, and the closed forms used by the library.

    Returns
    -------
    dict
        ``"dx_dZ"``, ``"dy_dZ"`` (sympy derivatives) and ``"dx_dZ_closed"``, ``"dy_dZ_closed"`` =
        −(f·a31 + a33·(x − x₀))/W and −(f·a32 + a33·(y − y₀))/W with W = a13ΔX + a23ΔY + a33ΔZ.

    Raises
    ------
    None
        Takes no input.

    References
    ----------
    Chibunichev (2022), §7.8, eqs. (7.8.2)–(7.8.3).

    Examples
    --------
    >>> d = height_partials()
    >>> sp.simplify(d["dx_dZ"] - d["dx_dZ_closed"]) == 0
    True
    """
    x, y = collinearity_782()
    W = _a[0, 2] * (X - Xs) + _a[1, 2] * (Y - Ys) + _a[2, 2] * (Z - Zs)
    return {"dx_dZ": sp.diff(x, Z), "dy_dZ": sp.diff(y, Z),
            "dx_dZ_closed": -(f * _a[2, 0] + _a[2, 2] * (x - x0)) / W,
            "dy_dZ_closed": -(f * _a[2, 1] + _a[2, 2] * (y - y0)) / W}


def correction_coefficients(eo_unknown: bool = False, order: str = "wak") -> dict:
    """The coefficients of (7.8.3) (EO known) or (7.8.4) (EO unknown), derived by sympy.

    (7.8.1) with x_i, y_i from (7.3.2) is differentiated by F, Z, k_i (and X_S, Y_S, Z_S, α, ω, κ
    in the book's order of (7.8.4)); the image brightness stays an undefined function, so its
    derivatives appear as ``Subs(Derivative(f_i(...)))`` (in practice the image gradient).

    Parameters
    ----------
    eo_unknown : bool
        False: a₁, a₂, a₃ of (7.8.3); True: a₁…a₉ of (7.8.4).
    order : {"wak", "kaw"}
        Rotation sequence of A.

    Returns
    -------
    dict
        ``"a1"``… and the free term ``"l"`` (the condition at the approximation).

    Raises
    ------
    InputError
        An unknown order.

    References
    ----------
    Chibunichev (2022), §7.8, eqs. (7.8.1)–(7.8.4).

    Examples
    --------
    >>> c = correction_coefficients()
    >>> c["a1"], c["a3"]
    (1, -f_i(x_i, y_i))
    """
    xe, ye = collinearity_732(_order(order))
    cond = F_sym - k_sym * image_function(xe, ye)
    unknowns = [F_sym, Z, k_sym] + ([Xs, Ys, Zs, alpha, omega, kappa] if eo_unknown else [])
    back = {xe: _xs, ye: _ys}
    out = {}
    for n, u in enumerate(unknowns, start=1):
        out[f"a{n}"] = sp.diff(cond, u).subs(back)
    out["l"] = cond.subs(back)
    return out


@lru_cache(maxsize=None)
def height_partials_function(order: str = "kaw"):
    """numpy function (X, Y, Z, X_S, Y_S, Z_S, ω, α, κ, f, x₀, y₀) → (∂x/∂Z, ∂y/∂Z) of (7.3.2)/(7.8.2).

    Parameters
    ----------
    order : {"kaw", "wak"}
        Rotation sequence of the angles.

    Returns
    -------
    callable
        Returns a (2, …) array; lambdified on first use and cached.

    Raises
    ------
    InputError
        An unknown order.

    References
    ----------
    Chibunichev (2022), §7.8, eqs. (7.8.2)–(7.8.3).

    Examples
    --------
    >>> fn = height_partials_function("kaw")
    >>> [round(float(v), 6) for v in fn(10.0, 0.0, 0.0, 0.0, 0.0, 100.0, 0.0, 0.0, 0.0, 50.0, 0.0, 0.0)]
    [0.05, 0.0]
    """
    import numpy as np
    xe, ye = collinearity_732(_order(order))
    args = (X, Y, Z, Xs, Ys, Zs, omega, alpha, kappa, f, x0, y0)
    fn = sp.lambdify(args, [sp.diff(xe, Z), sp.diff(ye, Z)], "numpy")

    def partials(*values):
        return np.stack(np.broadcast_arrays(*[np.asarray(v, dtype=float) for v in fn(*values)]))
    return partials


def check_784_chain_rule(order: str = "kaw") -> bool:
    """True when a₄…a₉ of (7.8.4) are −k_i(∂f_i/∂x·∂x/∂p + ∂f_i/∂y·∂y/∂p) with the Chapter 1 partials.

    The coefficients of :func:`correction_coefficients` (``eo_unknown=True``) by X_S, Y_S, Z_S,
    α, ω, κ are compared, with the image brightness replaced by a linear function of gradient
    (g_x, g_y), against the Jacobian of the collinearity model of §1.8
    (:func:`photolib.derivations.collinearity.collinearity_model`, the coefficients a₁…b₆ of
    (1.8.3)); so the photometric equations and the GCP equations share one derivation.

    Parameters
    ----------
    order : {"kaw", "wak"}
        Rotation sequence of A.

    Returns
    -------
    bool

    Raises
    ------
    InputError
        An unknown order.

    References
    ----------
    Chibunichev (2022), §7.8, eq. (7.8.4); §1.8, eqs. (1.8.2)–(1.8.3).

    Examples
    --------
    >>> check_784_chain_rule("kaw")
    True
    """
    from .collinearity import collinearity_model
    order = _order(order)
    c = correction_coefficients(eo_unknown=True, order=order)
    gx, gy, u, v = sp.symbols("g_x g_y u v", real=True)
    linear = sp.Lambda((u, v), gx * u + gy * v)
    model = collinearity_model(order)
    J = model.jacobian()                                  # rows F_x, F_y; columns X_S, Y_S, Z_S, ω, α, κ
    column = {s: j for j, s in enumerate(model.parameters)}
    xe, ye = collinearity_732(order)
    back = {_xs: xe, _ys: ye}
    for name, p in zip(("a4", "a5", "a6", "a7", "a8", "a9"), (Xs, Ys, Zs, alpha, omega, kappa)):
        got = c[name].subs(back).subs(image_function, linear).doit()
        want = -k_sym * (gx * J[0, column[p]] + gy * J[1, column[p]])
        if sp.expand(got - want) != 0 and sp.simplify(got - want) != 0:
            return False
    return True


@lru_cache(maxsize=None)
def eo_partials_function(order: str = "kaw"):
    """numpy function (X, Y, Z, X_S, Y_S, Z_S, ω, α, κ, f, x₀, y₀) → ∂(x, y)/∂(X_S, Y_S, Z_S, ω, α, κ).

    The compiled Jacobian of the collinearity model of §1.8
    (:func:`photolib.derivations.collinearity.collinearity_model`) — the same code the resection
    and the bundle adjustment use; here for the columns a₄…a₉ of (7.8.4) (times −k_i and the image
    gradient) and for the GCP collinearity equations that (7.8.4) needs.

    Parameters
    ----------
    order : {"kaw", "wak"}
        Rotation sequence of the angles.

    Returns
    -------
    callable
        Returns a (2, 6, …) array: [∂x/∂p, ∂y/∂p] for p = X_S, Y_S, Z_S, ω, α, κ.

    Raises
    ------
    InputError
        An unknown order.

    References
    ----------
    Chibunichev (2022), §7.8, eq. (7.8.4); §1.8, eq. (1.8.3).

    Examples
    --------
    >>> fn = eo_partials_function("kaw")
    >>> [round(float(v), 6) for v in fn(10.0, 0.0, 0.0, 0.0, 0.0, 100.0, 0.0, 0.0, 0.0, 50.0, 0.0, 0.0)[0, :3]]
    [-0.5, 0.0, -0.05]
    """
    import numpy as np
    from .collinearity import collinearity_model
    _, jacobian = collinearity_model(_order(order)).compile()

    def partials(X, Y, Z, Xs_, Ys_, Zs_, om, al, ka, f_, x0_, y0_):
        J = jacobian(Xs_, Ys_, Zs_, om, al, ka, X, Y, Z, 0.0, 0.0, f_, x0_, y0_)
        J = np.asarray(J, dtype=float)
        return J.reshape((2, 6) + J.shape[1:])
    return partials
