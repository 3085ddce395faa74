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
* :func:`distortion_model` — the Brown correction (1.2.2)/(1.2.3) as a function of the measured x, y.
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


k1, k2, k3, p1, p2 = sp.symbols("k_1 k_2 k_3 p_1 p_2", real=True)


@lru_cache(maxsize=None)
def distortion_model() -> Model:
    """Measured → ideal coordinates x + d_x, y + d_y of (1.2.2)/(1.2.3); unknowns the measured x, y.

    Its Jacobian (the 2×2 matrix I + ∂d/∂x) drives the Newton inversion in
    :func:`photolib.camera.apply_distortion`.
    """
    xb, yb = x - x0, y - y0
    r2 = xb ** 2 + yb ** 2
    radial = k1 * r2 + k2 * r2 ** 2 + k3 * r2 ** 3
    d_x = xb * radial + (r2 + 2 * xb ** 2) * p1 + 2 * xb * yb * p2
    d_y = yb * radial + 2 * xb * yb * p1 + (r2 + 2 * yb ** 2) * p2
    return Model("brown-correction", (x, y), (x0, y0, k1, k2, k3, p1, p2), (x + d_x, y + d_y))


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


# --- Chapter 2 models --------------------------------------------------------------------------
# Symbols of a pair of images. Image coordinates of the pair models are *reduced* to the
# principal point (and corrected for distortion), so the ray vector of image i is (x_i, y_i, −f_i).
x1, y1, x2, y2 = sp.symbols("x_1 y_1 x_2 y_2", real=True)
f1, f2 = sp.symbols("f_1 f_2", positive=True)
b_y, b_z = sp.symbols("b_y b_z", real=True)
omega1, alpha1, kappa1 = sp.symbols("omega_1 alpha_1 kappa_1", real=True)
omega2, alpha2, kappa2 = sp.symbols("omega_2 alpha_2 kappa_2", real=True)
X0, Y0, Z0 = sp.symbols("X_0 Y_0 Z_0", real=True)
omegaM, alphaM, kappaM, t_M = sp.symbols("omega_M alpha_M kappa_M t", real=True)
XM, YM, ZM = sp.symbols("X_M Y_M Z_M", real=True)

RELATIVE_ORIENTATION_SYSTEMS = {
    # α'1 κ'1 ω'2 α'2 κ'2 with b_y = b_z = ω'1 = 0: condition (2.7.4)
    "independent": (alpha1, kappa1, omega2, alpha2, kappa2),
    # b_y b_z ω'2 α'2 κ'2 with ω'1 = α'1 = κ'1 = 0 (A'1 = E): condition (2.7.5)
    "dependent": (b_y, b_z, omega2, alpha2, kappa2),
}
"""The two systems of relative-orientation elements of §2.7 and their unknowns."""

RELATIVE_ORIENTATION_PARAMETERS = (b_y, b_z, omega1, alpha1, kappa1, omega2, alpha2, kappa2)
"""All eight parameters of the coplanarity condition (2.7.3); a system fixes three of them to 0."""


def coplanarity_expression(order: str = "kaw"):
    """φ of (2.7.3): det[[1, b_y, b_z], [X'₁, Y'₁, Z'₁], [X'₂, Y'₂, Z'₂]] with all eight parameters.

    (X'ᵢ, Y'ᵢ, Z'ᵢ)ᵀ = A'ᵢ (xᵢ, yᵢ, −fᵢ)ᵀ, A'ᵢ = A(ω'ᵢ, α'ᵢ, κ'ᵢ) of the rotation sequence ``order``.
    """
    r1 = rotation_matrix_symbolic(order, omega1, alpha1, kappa1) * sp.Matrix([x1, y1, -f1])
    r2 = rotation_matrix_symbolic(order, omega2, alpha2, kappa2) * sp.Matrix([x2, y2, -f2])
    return sp.Matrix([[1, b_y, b_z], [r1[0], r1[1], r1[2]], [r2[0], r2[1], r2[2]]]).det(method="berkowitz")


@lru_cache(maxsize=None)
def coplanarity_model(system: str = "dependent", order: str = "kaw") -> Model:
    """The relative-orientation condition (2.7.3) in one of the two systems of §2.7.

    ``"independent"``: unknowns α'₁, κ'₁, ω'₂, α'₂, κ'₂, with b_y = b_z = ω'₁ = 0 — (2.7.4).
    ``"dependent"``: unknowns b_y, b_z, ω'₂, α'₂, κ'₂, with A'₁ = E — (2.7.5).
    Data: reduced image coordinates and focal lengths (x₁, y₁, f₁, x₂, y₂, f₂). The rows of B
    are the coefficients a₁…a₅ of the correction equation (2.8.1), derived by sympy.
    """
    check_order(order)
    if system not in RELATIVE_ORIENTATION_SYSTEMS:
        raise ValueError(f"unknown system {system!r}; use 'independent' or 'dependent'")
    unknowns = RELATIVE_ORIENTATION_SYSTEMS[system]
    fixed = {p: 0 for p in RELATIVE_ORIENTATION_PARAMETERS if p not in unknowns}
    phi = coplanarity_expression(order).subs(fixed)
    return Model(f"coplanarity-{system}-{order}", unknowns, (x1, y1, f1, x2, y2, f2), (phi,))


def printed_relative_orientation_partials() -> dict:
    """∂X'₂/∂θ, ∂Y'₂/∂θ, ∂Z'₂/∂θ (θ = ω'₂, α'₂, κ'₂) as printed in §2.8 (seed lines 1361–1368).

    The OCR repeats fragments such as "+ y₂ sin ω₂ sin ω₂ …"; these are dropped and the
    remaining terms kept as printed. Keys are ``("X", "omega")`` etc.; x, y, f carry the
    index 2 (symbols ``x_2, y_2, f_2``). They equal ∂A/∂θ·(x₂, y₂, **+f₂**)ᵀ for the κ–α–ω
    matrix (1.3.5), i.e. every f-term has the wrong sign for the book's ray (x₂, y₂, −f₂):
    compare :func:`derived_relative_orientation_partials`.
    """
    c, s = sp.cos, sp.sin
    w, a, k, xx, yy, ff = omega2, alpha2, kappa2, x2, y2, f2
    return {
        ("X", "omega"): yy * c(k) * s(a) * c(w) + yy * s(k) * s(w) + ff * c(w) * s(k) - ff * s(w) * s(a) * c(k),
        ("Y", "omega"): yy * c(w) * s(a) * s(k) - yy * c(k) * s(w) - ff * c(w) * c(k) - ff * s(w) * s(a) * s(k),
        ("Z", "omega"): yy * c(w) * c(a) - ff * s(w) * c(a),
        ("X", "alpha"): -xx * c(k) * s(a) + yy * c(k) * c(a) * s(w) + ff * c(w) * c(a) * c(k),
        ("Y", "alpha"): -xx * s(k) * s(a) + yy * s(w) * c(a) * s(k) + ff * c(w) * c(a) * s(k),
        ("Z", "alpha"): -xx * c(a) - yy * s(w) * s(a) - ff * c(w) * s(a),
        ("X", "kappa"): -xx * s(k) * c(a) - yy * s(k) * s(a) * s(w) - yy * c(k) * c(w)
                        + ff * s(w) * c(k) - ff * c(w) * s(a) * s(k),
        ("Y", "kappa"): xx * c(k) * c(a) + yy * s(w) * s(a) * c(k) - yy * s(k) * c(w)
                        + ff * s(w) * s(k) + ff * c(w) * s(a) * c(k),
        ("Z", "kappa"): sp.Integer(0),
    }


def derived_relative_orientation_partials(order: str = "kaw", z_sign: int = -1) -> dict:
    """∂(A'₂ r₂)/∂θ derived by sympy, r₂ = (x₂, y₂, z_sign·f₂); the book's ray has z_sign = −1 (2.7.3)."""
    A = rotation_matrix_symbolic(order, omega2, alpha2, kappa2)
    r = A * sp.Matrix([x2, y2, z_sign * f2])
    return {(C, name): sp.diff(r[i], th) for i, C in enumerate("XYZ")
            for name, th in (("omega", omega2), ("alpha", alpha2), ("kappa", kappa2))}


@lru_cache(maxsize=None)
def intersection_model(order: str = "kaw") -> Model:
    """Collinearity equations (1.8.2) with the object point (X, Y, Z) as the unknowns.

    The residuals are F_x, F_y of :func:`collinearity_model`; the data are the exterior
    orientation of the image and the measured (x, y) with f, x₀, y₀. Used for the
    least-squares forward intersection of two or more rays (§2.4).
    """
    F_x, F_y = collinearity_model(order).residuals
    return Model(f"intersection-{order}", (X, Y, Z), EO_SYMBOLS + (x, y, f, x0, y0), (F_x, F_y))


@lru_cache(maxsize=None)
def similarity_model(order: str = "kaw") -> Model:
    """φ_X, φ_Y, φ_Z of (2.11.1): (X, Y, Z)ᵀ − (X₀, Y₀, Z₀)ᵀ − t·A_M(X_M, Y_M, Z_M)ᵀ.

    Unknowns: the seven elements of exterior orientation of the model X₀, Y₀, Z₀, ω_M, α_M,
    κ_M, t (2.10.4); data: model and object coordinates of a control point. (2.10.5) as printed
    lacks the factor t; it is included here as in (2.10.4) and (2.11.1).
    """
    A = rotation_matrix_symbolic(order, omegaM, alphaM, kappaM)
    phi = sp.Matrix([X, Y, Z]) - sp.Matrix([X0, Y0, Z0]) - t_M * A * sp.Matrix([XM, YM, ZM])
    return Model(f"similarity-{order}", (X0, Y0, Z0, omegaM, alphaM, kappaM, t_M), (XM, YM, ZM, X, Y, Z),
                 tuple(phi))


# --- Chapter 3: the bundle method (§3.5) -------------------------------------------------------
@lru_cache(maxsize=None)
def bundle_collinearity_model(order: str = "kaw") -> Model:
    """(3.5.1) with unknown exterior orientation **and** unknown object point — the bundle model.

    F_x = x₀ − f x*/z* − x,  F_y = y₀ − f y*/z* − y,  (x*, y*, z*)ᵀ = Aᵀ(X − X_S, Y − Y_S, Z − Z_S)ᵀ.
    Parameters X_S, Y_S, Z_S, ω, α, κ, X, Y, Z; data x, y, f, x₀, y₀. The rows of the Jacobian
    are the coefficients a₁…a₉, b₁…b₉ of the correction equations (3.5.2); dropping the last
    three columns gives (3.5.3) (fixed control point), dropping the first six gives (3.5.4).
    """
    Xst, Yst, Zst = collinearity_terms(order)
    F_x = x0 - f * Xst / Zst - x
    F_y = y0 - f * Yst / Zst - y
    return Model(f"bundle-collinearity-{order}", EO_SYMBOLS + (X, Y, Z), (x, y, f, x0, y0), (F_x, F_y))


def numpy_source(model: Model, function_name: str = "residuals_and_jacobian") -> str:
    """Python/numpy source of one function computing residuals and Jacobian of ``model`` together.

    :meth:`Model.compile` lambdifies residuals and Jacobian separately; for large problems (a
    bundle block has 10⁵–10⁶ image observations) it pays to run sympy's common-subexpression
    elimination over *both* at once, so that x*, y*, z*, the trigonometric terms and 1/z* are
    evaluated once per observation. The sympy expressions stay the single source of truth: this
    is only printed code. The generated function takes ``(*parameters, *data)`` (arrays that
    broadcast) and returns ``(F, J)`` with shapes (n_res, n) and (n_res·n_par, n), row-major.
    """
    from sympy.printing.numpy import NumPyPrinter

    exprs = list(model.residuals) + list(model.jacobian())
    replacements, reduced = sp.cse(exprs, symbols=sp.numbered_symbols("_t"), optimizations="basic")
    printer = NumPyPrinter({"fully_qualified_modules": True, "inline": True})
    args = [printer.doprint(s) for s in list(model.parameters) + list(model.data)]
    lines = [f"def {function_name}({', '.join(args)}):",
             f'    """Generated by photolib.derivations.numpy_source from the sympy model {model.name!r}."""']
    lines += [f"    {printer.doprint(sym)} = {printer.doprint(expr)}" for sym, expr in replacements]
    n_res = len(model.residuals)
    lines.append(f"    _out = [{', '.join(printer.doprint(e) for e in reduced)}]")
    lines.append("    _out = numpy.broadcast_arrays(*[numpy.asarray(o, dtype=float) for o in _out])")
    lines.append(f"    return numpy.stack(_out[:{n_res}]), numpy.stack(_out[{n_res}:])")
    return "\n".join(lines) + "\n"


@lru_cache(maxsize=None)
def compile_fused(model: Model):
    """Execute :func:`numpy_source` and return the function ``(*parameters, *data) -> (F, J)``."""
    source = numpy_source(model)
    namespace = {"numpy": np}
    exec(compile(source, f"<photolib generated: {model.name}>", "exec"), namespace)
    fn = namespace["residuals_and_jacobian"]
    fn.source = source
    return fn
