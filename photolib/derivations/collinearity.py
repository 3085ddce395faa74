"""The collinearity equations and single-image resection: Chapter 1, §1.4, §1.8, §1.9.

* :func:`collinearity_model` — F_x, F_y of (1.8.1)/(1.8.2), unknowns X_S, Y_S, Z_S, ω, α, κ.
* :func:`printed_resection_partials` / :func:`derived_resection_partials` — the coefficients
  a₁…b₆ of (1.8.3) as printed and as derived by sympy (most printed ones are wrong, see the
  errata of Chapter 1); :func:`printed_resection_jacobian` — the printed ones as numpy code for
  the "as printed" mode of :func:`photolib.resection.space_resection`.
* :func:`angle_equality_model` — φ = cos ASB − cos aSb of (1.9.1), unknowns X_S, Y_S, Z_S, and the
  printed a₁, b₁, c₁ (:func:`printed_angle_equality_partials`).
"""

from __future__ import annotations

from functools import lru_cache

import sympy as sp

from .model import Model, _printed_function
from .rotation import rotation_matrix_symbolic
from .symbols import (EO_SYMBOLS, XA, XB, YA, YB, ZA, ZB, X, Xs, Y, Ys, Z, Zs, alpha, f, kappa, omega, x,
                      x0, xa, xb, y, y0, ya, yb)

__all__ = ["collinearity_terms", "collinearity_model", "angle_equality_model",
           "printed_angle_equality_partials", "RESECTION_COEFFICIENTS", "printed_resection_partials",
           "derived_resection_partials", "printed_resection_jacobian"]


def collinearity_terms(order: str = "kaw"):
    """(X*, Y*, Z*)ᵀ = Aᵀ(X − X_S, Y − Y_S, Z − Z_S)ᵀ of (1.4.10)/(1.8.1).

    Parameters
    ----------
    order : {"kaw", "wak"}, optional
        Rotation sequence of A (see :func:`rotation_matrix_symbolic`).

    Returns
    -------
    sympy.Matrix
        3×1: X*, Y*, Z* in the symbols X_S … κ, X, Y, Z.

    Raises
    ------
    InputError
        If ``order`` is unknown.

    References
    ----------
    Chibunichev (2022), §1.4, eq. (1.4.10); §1.8, eq. (1.8.1).

    Examples
    --------
    >>> from photolib.derivations import Xs, X, omega, alpha, kappa
    >>> collinearity_terms("kaw")[2].subs({omega: 0, alpha: 0, kappa: 0})
    Z - Z_S
    """
    A = rotation_matrix_symbolic(order)
    return A.T * sp.Matrix([X - Xs, Y - Ys, Z - Zs])


@lru_cache(maxsize=None)
def collinearity_model(order: str = "kaw") -> Model:
    """F_x = x₀ − f X*/Z* − x, F_y = y₀ − f Y*/Z* − y — the collinearity equations (1.8.2).

    Parameters
    ----------
    order : {"kaw", "wak"}, optional
        Rotation sequence.

    Returns
    -------
    Model
        Parameters X_S, Y_S, Z_S, ω, α, κ; data X, Y, Z, x, y, f, x₀, y₀; residuals F_x, F_y.
        Its Jacobian rows are a₁…a₆ and b₁…b₆ of (1.8.3).

    Raises
    ------
    InputError
        If ``order`` is unknown.

    References
    ----------
    Chibunichev (2022), §1.8, eqs. (1.8.1)–(1.8.3).

    Examples
    --------
    >>> m = collinearity_model("kaw")
    >>> m.name, len(m.parameters), len(m.residuals)
    ('collinearity-kaw', 6, 2)
    >>> residual_fn, jacobian_fn = m.compile()
    >>> residual_fn(0, 0, 1000, 0, 0, 0, 100, 0, 0, 10, 0, 100, 0, 0).ravel().tolist()
    [0.0, 0.0]
    """
    Xst, Yst, Zst = collinearity_terms(order)
    F_x = x0 - f * Xst / Zst - x
    F_y = y0 - f * Yst / Zst - y
    return Model(f"collinearity-{order}", EO_SYMBOLS, (X, Y, Z, x, y, f, x0, y0), (F_x, F_y))


@lru_cache(maxsize=None)
def angle_equality_model() -> Model:
    """φ = cos ASB − cos aSb (1.9.1) for one pair of control points A, B; unknowns X_S, Y_S, Z_S.

    The equation itself is lost in the OCR of §1.9; this form is the one whose derivatives
    are the printed a₁, b₁, c₁ (checked in the tests). Image coordinates are reduced to the
    principal point: the ray vectors are (x − x₀, y − y₀, −f).

    Returns
    -------
    Model
        Parameters X_S, Y_S, Z_S; data X_A, Y_A, Z_A, X_B, Y_B, Z_B, x_a, y_a, x_b, y_b, f, x₀, y₀.

    Raises
    ------
    InputError
        Never (no input).

    References
    ----------
    Chibunichev (2022), §1.9, eqs. (1.9.1)–(1.9.2).

    Examples
    --------
    >>> m = angle_equality_model()
    >>> [str(s) for s in m.parameters]
    ['X_S', 'Y_S', 'Z_S']
    """
    dA = sp.Matrix([XA - Xs, YA - Ys, ZA - Zs])
    dB = sp.Matrix([XB - Xs, YB - Ys, ZB - Zs])
    ra = sp.Matrix([xa - x0, ya - y0, -f])
    rb = sp.Matrix([xb - x0, yb - y0, -f])
    cos_object = dA.dot(dB) / (dA.norm() * dB.norm())
    cos_image = ra.dot(rb) / (ra.norm() * rb.norm())
    return Model("angle-equality", (Xs, Ys, Zs), (XA, YA, ZA, XB, YB, ZB, xa, ya, xb, yb, f, x0, y0),
                 (cos_object - cos_image,))


def printed_angle_equality_partials():
    """a₁, b₁, c₁ of §1.9 (lines 713–723) as printed.

    Returns
    -------
    dict
        ``{"a1": ∂φ/∂X_S, "b1": ∂φ/∂Y_S, "c1": ∂φ/∂Z_S}`` as sympy expressions.

    Raises
    ------
    InputError
        Never (no input).

    References
    ----------
    Chibunichev (2022), §1.9, the coefficients of (1.9.2).

    Examples
    --------
    >>> import sympy as sp
    >>> printed = printed_angle_equality_partials()
    >>> derived = sp.diff(angle_equality_model().residuals[0], Xs)
    >>> sp.simplify(printed["a1"] - derived)
    0
    """
    AS = sp.sqrt((XA - Xs) ** 2 + (YA - Ys) ** 2 + (ZA - Zs) ** 2)
    BS = sp.sqrt((XB - Xs) ** 2 + (YB - Ys) ** 2 + (ZB - Zs) ** 2)
    cos_ASB = ((XA - Xs) * (XB - Xs) + (YA - Ys) * (YB - Ys) + (ZA - Zs) * (ZB - Zs)) / (AS * BS)

    def partial(PA, PB, PS):
        return -((PA - PS) + (PB - PS)) / (AS * BS) + cos_ASB * ((PA - PS) / AS ** 2 + (PB - PS) / BS ** 2)

    return {"a1": partial(XA, XB, Xs), "b1": partial(YA, YB, Ys), "c1": partial(ZA, ZB, Zs)}


RESECTION_COEFFICIENTS = ("a1", "a2", "a3", "a4", "a5", "a6", "b1", "b2", "b3", "b4", "b5", "b6")
"""Names of the coefficients of (1.8.3), row-major: a₁…a₆ (F_x), b₁…b₆ (F_y)."""


def printed_resection_partials() -> dict:
    """The coefficients a₁…a₆, b₁…b₆ of (1.8.3) exactly as printed (seed lines 572–576).

    They are written for the κ–α–ω matrix (1.3.5); x′, y′ are "the image coordinates computed
    from the collinearity equations", i.e. x′ = x₀ − f X*/Z*. Most of them are wrong; see
    :func:`derived_resection_partials` and the errata of Chapter 1.

    Returns
    -------
    dict
        Keys :data:`RESECTION_COEFFICIENTS`, values sympy expressions.

    Raises
    ------
    InputError
        Never (no input).

    References
    ----------
    Chibunichev (2022), §1.8, eq. (1.8.3).

    Examples
    --------
    >>> sorted(printed_resection_partials()) == sorted(RESECTION_COEFFICIENTS)
    True
    """
    A = rotation_matrix_symbolic("kaw")
    a = lambda i, j: A[i - 1, j - 1]  # noqa: E731 — the book's a_ij
    Xst, Yst, Zst = collinearity_terms("kaw")
    x_c = x0 - f * Xst / Zst
    y_c = y0 - f * Yst / Zst
    dX, dY, dZ = X - Xs, Y - Ys, Z - Zs
    h = dX * sp.cos(kappa) + dY * sp.sin(kappa)
    c, s = sp.cos, sp.sin
    return {
        "a1": -(f * a(1, 1) - a(1, 3) * x_c) / Zst,
        "a2": -(f * a(2, 1) - a(2, 3) * x_c) / Zst,
        "a3": (f * a(3, 1) - a(3, 3) * x_c) / Zst,
        "a4": -x_c / Zst * (a(1, 2) * dX + a(2, 2) * dY + a(3, 2) * dZ),
        "a5": -f / Zst * (a(3, 1) * h - c(alpha) * dZ) + x_c / Zst * (a(3, 3) * h - s(alpha) * c(omega) * dZ),
        "a6": f / Zst * (a(1, 1) * dY - a(2, 1) * dX) - x_c / Zst * (a(1, 3) * dY + a(2, 3) * dX),
        "b1": -(f * a(1, 2) - a(1, 3) * y_c) / Zst,
        "b2": -(f * a(2, 2) - a(2, 3) * y_c) / Zst,
        "b3": (f * a(3, 2) - a(3, 3) * y_c) / Zst,
        "b4": -f / Zst * (a(1, 3) * dX + a(2, 3) * dY + a(3, 3) * dZ)
              + y_c / Zst * (a(1, 2) * dX + a(2, 2) * dY + a(3, 2) * dZ),
        "b5": -f / Zst * (a(3, 2) * h - s(alpha) * s(omega) * dZ) + y_c / Zst * (a(3, 3) * h - s(alpha) * c(omega) * dZ),
        "b6": f / Zst * (a(1, 2) * dY - a(2, 2) * dX) - y_c / Zst * (a(1, 3) * dY + a(2, 3) * dX),
    }


def derived_resection_partials(order: str = "kaw") -> dict:
    """a₁…a₆, b₁…b₆ of (1.8.3) derived by sympy from (1.8.2).

    Parameters
    ----------
    order : {"kaw", "wak"}, optional
        Rotation sequence.

    Returns
    -------
    dict
        Keys :data:`RESECTION_COEFFICIENTS`, values the sympy derivatives.

    Raises
    ------
    InputError
        If ``order`` is unknown.

    References
    ----------
    Chibunichev (2022), §1.8, eqs. (1.8.2)–(1.8.3).

    Examples
    --------
    >>> from photolib.derivations import X, Xs, Z, Zs, f, omega, alpha, kappa
    >>> a1 = derived_resection_partials("kaw")["a1"]
    >>> a1.subs({omega: 0, alpha: 0, kappa: 0})
    f/(Z - Z_S)
    """
    J = collinearity_model(order).jacobian()
    return {f"{row}{j + 1}": J[i, j] for i, row in enumerate("ab") for j in range(6)}


def _printed_resection_build():
    printed = printed_resection_partials()
    args = list(EO_SYMBOLS) + [X, Y, Z, x, y, f, x0, y0]
    return args, [printed[k] for k in RESECTION_COEFFICIENTS], 12


@lru_cache(maxsize=None)
def printed_resection_jacobian():
    """Numpy function of ``(*EO, X, Y, Z, x, y, f, x0, y0)`` giving the printed a₁…b₆ (row-major 2×6).

    Returns
    -------
    callable
        Returns an array of shape (12, n).

    Raises
    ------
    InputError
        Never (no input).

    References
    ----------
    Chibunichev (2022), §1.8, eq. (1.8.3).

    Examples
    --------
    >>> jac = printed_resection_jacobian()
    >>> jac(0, 0, 1000, 0, 0, 0, 100, 0, 0, 10, 0, 100, 0, 0).shape
    (12,)
    """
    return _printed_function("printed-resection", _printed_resection_build)
