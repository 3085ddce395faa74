"""Model equations in sympy and the Jacobians derived from them — the one place for derivatives.

Each photogrammetric problem is written once as sympy expressions of its unknowns
(*parameters*) and its known quantities (*data*). The library never types a partial derivative
by hand: :meth:`Model.compile` differentiates the expressions with sympy and turns residuals
and Jacobian into vectorised numpy functions (``sympy.lambdify`` with common subexpressions).

The book's own printed derivatives are transcribed here too (:func:`printed_resection_partials`),
so that tests and notebooks can compare them with the derived ones term by term and the
"as printed" mode can reproduce what the book computed with them.

Models so far (Chapter 1):

* :func:`collinearity_model` — F_x, F_y of (1.8.1)/(1.8.2), unknowns X_S, Y_S, Z_S, ω, α, κ.
* :func:`angle_equality_model` — φ = cos ASB − cos aSb of (1.9.1), unknowns X_S, Y_S, Z_S.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import numpy as np
import sympy as sp

from .rotation import check_order

# --- symbols -------------------------------------------------------------------------------
Xs, Ys, Zs = sp.symbols("X_S Y_S Z_S", real=True)
omega, alpha, kappa = sp.symbols("omega alpha kappa", real=True)
X, Y, Z = sp.symbols("X Y Z", real=True)
x, y = sp.symbols("x y", real=True)
f, x0, y0 = sp.symbols("f x_0 y_0", positive=True)

EO_SYMBOLS = (Xs, Ys, Zs, omega, alpha, kappa)


def elementary_rotations(w=omega, a=alpha, k=kappa):
    """The book's A_ω, A_α, A_κ as sympy matrices (right-handed rotations about X, Y, Z)."""
    c, s = sp.cos, sp.sin
    A_w = sp.Matrix([[1, 0, 0], [0, c(w), -s(w)], [0, s(w), c(w)]])
    A_a = sp.Matrix([[c(a), 0, s(a)], [0, 1, 0], [-s(a), 0, c(a)]])
    A_k = sp.Matrix([[c(k), -s(k), 0], [s(k), c(k), 0], [0, 0, 1]])
    return A_w, A_a, A_k


def rotation_matrix_symbolic(order: str = "kaw", w=omega, a=alpha, k=kappa) -> sp.Matrix:
    """A of (1.3.4)/(1.3.5) (``"kaw"``) or (1.3.2) (``"wak"``) in sympy."""
    check_order(order)
    A_w, A_a, A_k = elementary_rotations(w, a, k)
    return A_k * A_a * A_w if order == "kaw" else A_w * A_a * A_k


def book_rotation_elements_kaw() -> sp.Matrix:
    """The element list of (1.3.5) exactly as the book writes it (with the OCR's duplicate a21 dropped)."""
    c, s = sp.cos, sp.sin
    w, a, k = omega, alpha, kappa
    return sp.Matrix([
        [c(k) * c(a), s(a) * s(w) * c(k) - s(k) * c(w), s(a) * c(w) * c(k) + s(w) * s(k)],
        [s(k) * c(a), s(k) * s(w) * s(a) + c(k) * c(w), s(a) * c(w) * s(k) - s(w) * c(k)],
        [-s(a), c(a) * s(w), c(a) * c(w)],
    ])


def book_rotation_elements_wak() -> sp.Matrix:
    """The element list of (1.3.2) as printed in §1.3."""
    c, s = sp.cos, sp.sin
    w, a, k = omega, alpha, kappa
    return sp.Matrix([
        [c(a) * c(k), -c(a) * s(k), s(a)],
        [s(w) * s(a) * c(k) + c(w) * s(k), -s(w) * s(a) * s(k) + c(w) * c(k), -s(w) * c(a)],
        [-c(w) * s(a) * c(k) + s(w) * s(k), c(w) * s(a) * s(k) + s(w) * c(k), c(w) * c(a)],
    ])


# --- generic model -----------------------------------------------------------------------------
def _broadcasting(fn, count):
    """Wrap a lambdified function so every output is an array of the common broadcast shape."""
    def wrapped(*args):
        out = fn(*args)
        return np.stack(np.broadcast_arrays(*[np.asarray(o, dtype=float) for o in out]))
    wrapped.count = count
    return wrapped


@dataclass(frozen=True)
class Model:
    """Residual functions of a least-squares problem, written in sympy.

    ``residuals`` are the functions whose values at the approximation are the free terms L of
    the correction equations (1.8.5); the rows of B are their derivatives by ``parameters``.
    """

    name: str
    parameters: tuple
    data: tuple
    residuals: tuple

    def jacobian(self) -> sp.Matrix:
        """∂F/∂p derived with sympy (rows: residuals, columns: parameters)."""
        return sp.Matrix(self.residuals).jacobian(sp.Matrix(self.parameters))

    def compile(self):
        """(residual_fn, jacobian_fn): numpy functions of ``(*parameters, *data)``.

        ``residual_fn`` returns an array (n_residuals, ...) and ``jacobian_fn`` an array
        (n_residuals · n_parameters, ...) in row-major order; the trailing axes broadcast over
        the data (e.g. one entry per control point).
        """
        return _compiled(self)


@lru_cache(maxsize=None)
def _compiled(model: Model):
    args = list(model.parameters) + list(model.data)
    res = sp.lambdify(args, list(model.residuals), modules="numpy", cse=True)
    jac_exprs = list(model.jacobian())
    jac = sp.lambdify(args, jac_exprs, modules="numpy", cse=True)
    return _broadcasting(res, len(model.residuals)), _broadcasting(jac, len(jac_exprs))


# --- Chapter 1 models --------------------------------------------------------------------------
def collinearity_terms(order: str = "kaw"):
    """(X*, Y*, Z*)ᵀ = Aᵀ(X − X_S, Y − Y_S, Z − Z_S)ᵀ of (1.4.10)/(1.8.1)."""
    A = rotation_matrix_symbolic(order)
    return A.T * sp.Matrix([X - Xs, Y - Ys, Z - Zs])


@lru_cache(maxsize=None)
def collinearity_model(order: str = "kaw") -> Model:
    """F_x = x₀ − f X*/Z* − x, F_y = y₀ − f Y*/Z* − y — the collinearity equations (1.8.2)."""
    Xst, Yst, Zst = collinearity_terms(order)
    F_x = x0 - f * Xst / Zst - x
    F_y = y0 - f * Yst / Zst - y
    return Model(f"collinearity-{order}", EO_SYMBOLS, (X, Y, Z, x, y, f, x0, y0), (F_x, F_y))


XA, YA, ZA, XB, YB, ZB = sp.symbols("X_A Y_A Z_A X_B Y_B Z_B", real=True)
xa, ya, xb, yb = sp.symbols("x_a y_a x_b y_b", real=True)


@lru_cache(maxsize=None)
def angle_equality_model() -> Model:
    """φ = cos ASB − cos aSb (1.9.1) for one pair of control points A, B; unknowns X_S, Y_S, Z_S.

    The equation itself is lost in the OCR of §1.9; this form is the one whose derivatives
    are the printed a₁, b₁, c₁ (checked in the tests). Image coordinates are reduced to the
    principal point: the ray vectors are (x − x₀, y − y₀, −f).
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
    """a₁, b₁, c₁ of §1.9 (lines 713–723) as printed."""
    AS = sp.sqrt((XA - Xs) ** 2 + (YA - Ys) ** 2 + (ZA - Zs) ** 2)
    BS = sp.sqrt((XB - Xs) ** 2 + (YB - Ys) ** 2 + (ZB - Zs) ** 2)
    cos_ASB = ((XA - Xs) * (XB - Xs) + (YA - Ys) * (YB - Ys) + (ZA - Zs) * (ZB - Zs)) / (AS * BS)

    def partial(PA, PB, PS):
        return -((PA - PS) + (PB - PS)) / (AS * BS) + cos_ASB * ((PA - PS) / AS ** 2 + (PB - PS) / BS ** 2)

    return {"a1": partial(XA, XB, Xs), "b1": partial(YA, YB, Ys), "c1": partial(ZA, ZB, Zs)}


RESECTION_COEFFICIENTS = ("a1", "a2", "a3", "a4", "a5", "a6", "b1", "b2", "b3", "b4", "b5", "b6")


def printed_resection_partials() -> dict:
    """The coefficients a₁…a₆, b₁…b₆ of (1.8.3) exactly as printed (seed lines 572–576).

    They are written for the κ–α–ω matrix (1.3.5); x′, y′ are "the image coordinates computed
    from the collinearity equations", i.e. x′ = x₀ − f X*/Z*. Most of them are wrong; see
    :func:`derived_resection_partials` and the errata of Chapter 1.
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
    """a₁…a₆, b₁…b₆ of (1.8.3) derived by sympy from (1.8.2)."""
    J = collinearity_model(order).jacobian()
    return {f"{row}{j + 1}": J[i, j] for i, row in enumerate("ab") for j in range(6)}


@lru_cache(maxsize=None)
def printed_resection_jacobian():
    """Numpy function of ``(*EO, X, Y, Z, x, y, f, x0, y0)`` giving the printed a₁…b₆ (row-major 2×6)."""
    printed = printed_resection_partials()
    args = list(EO_SYMBOLS) + [X, Y, Z, x, y, f, x0, y0]
    fn = sp.lambdify(args, [printed[k] for k in RESECTION_COEFFICIENTS], modules="numpy", cse=True)
    return _broadcasting(fn, 12)
