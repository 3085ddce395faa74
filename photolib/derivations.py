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


# --- GNSS-centres paper (seed 001) ---
# N.F. Dobrynin, T.M. Pimshina, «Использование космических средств позиционирования при обработке
# аэро- и космической информации» (seed 001_723f59c162a2adba.txt). A stereo pair whose projection
# centres are known from GNSS: the unknowns are the six angles α₁, ω₁, χ₁, α₂, ω₂, χ₂ of the α–ω–χ
# system (6). Frames: geodetic X north, Y east, Z up (left-handed); the image-space frame S X* Y* Z*
# has X* ∥ Y (east), Y* ∥ X (north), Z* ∥ Z, so a geodetic difference (ΔX, ΔY, ΔZ) has image-frame
# components (ΔY, ΔX, ΔZ) — hence the base row (B_Y, B_X, B_Z) of (1).
chi, chi1, chi2 = sp.symbols("chi chi_1 chi_2", real=True)
B_X, B_Y, B_Z = sp.symbols("B_X B_Y B_Z", real=True)
GNSS_ANGLES = (alpha1, omega1, chi1, alpha2, omega2, chi2)
"""The six unknowns of the paper, in its order (5): α₁, ω₁, χ₁, α₂, ω₂, χ₂."""
GNSS_COEFFICIENTS = ("a", "b", "c", "d", "e", "m")
"""Names of the coefficients of (5) (the paper relabels them a₁…a₆ at lines 135–145)."""
GNSS_GROUND_COEFFICIENTS = ("a'", "b'", "c'", "d'", "e'", "m'")
"""Names of the coefficients of (9) for image 1 (a′…m′; image 2 has a″…m″)."""


def gnss_rotation_symbolic(a=alpha, w=omega, k=chi) -> sp.Matrix:
    """A = R_Y(α)·R_X(ω)·R_Z(χ), the α–ω–χ system of the paper, built from elementary rotations.

    R_Y(α) = [[cos α, 0, −sin α], [0, 1, 0], [sin α, 0, cos α]] (the sense of α that gives the
    printed a₃ = −sin α cos ω), R_X(ω), R_Z(χ) right-handed as in §1.3. Compare with the element
    list (6) as printed, :func:`printed_gnss_direction_cosines`.
    """
    c, s = sp.cos, sp.sin
    R_Y = sp.Matrix([[c(a), 0, -s(a)], [0, 1, 0], [s(a), 0, c(a)]])
    R_X = sp.Matrix([[1, 0, 0], [0, c(w), -s(w)], [0, s(w), c(w)]])
    R_Z = sp.Matrix([[c(k), -s(k), 0], [s(k), c(k), 0], [0, 0, 1]])
    return R_Y * R_X * R_Z


def printed_gnss_direction_cosines(a=alpha, w=omega, k=chi) -> sp.Matrix:
    """The direction cosines (6) exactly as printed (seed lines 82–92), rows (a), (b), (c)."""
    c, s = sp.cos, sp.sin
    return sp.Matrix([
        [c(a) * c(k) - s(a) * s(w) * s(k), -c(a) * s(k) - s(a) * s(w) * c(k), -s(a) * c(w)],
        [c(w) * s(k), c(w) * c(k), -s(w)],
        [s(a) * c(k) + c(a) * s(w) * s(k), -s(a) * s(k) + c(a) * s(w) * c(k), c(a) * c(w)],
    ])


def gnss_image_space(xx=x, yy=y, a=alpha, w=omega, k=chi) -> sp.Matrix:
    """(X*, Y*, Z*) of (4): (x − x₀)a₁ + (y − y₀)a₂ − f a₃ etc., the direction cosines of (6)."""
    return printed_gnss_direction_cosines(a, w, k) * sp.Matrix([xx - x0, yy - y0, -f])


def gnss_coplanarity_expression() -> sp.Expr:
    """φ of (1): det[[B_Y, B_X, B_Z], [X₁*, Y₁*, Z₁*], [X₂*, Y₂*, Z₂*]], the vectors of (4)."""
    r1 = gnss_image_space(x1, y1, alpha1, omega1, chi1)
    r2 = gnss_image_space(x2, y2, alpha2, omega2, chi2)
    return sp.Matrix([[B_Y, B_X, B_Z], list(r1), list(r2)]).det(method="berkowitz")


@lru_cache(maxsize=None)
def gnss_coplanarity_model() -> Model:
    """The coplanarity condition (1) with the six angles unknown and the base (2) known from GNSS.

    Data: x₁, y₁, x₂, y₂ (mm), f, x₀, y₀ (one camera), B_X, B_Y, B_Z (geodetic, (2)). The rows
    of the Jacobian are the coefficients a, b, c, d, e, m of the correction equation (5).
    """
    return Model("gnss-coplanarity", GNSS_ANGLES, (x1, y1, x2, y2, f, x0, y0, B_X, B_Y, B_Z),
                 (gnss_coplanarity_expression(),))


@lru_cache(maxsize=None)
def gnss_collinearity_model() -> Model:
    """The collinearity equations (3) of one image as free terms of (9): l_y = (Y) − Y, l_x = (X) − X.

    (Y) = (Z − Z_S)X*/Z* + Y_S and (X) = (Z − Z_S)Y*/Z* + X_S, with X*, Y*, Z* of (4). Unknowns
    α, ω, χ of the image; data x, y, f, x₀, y₀, the centre X_S, Y_S, Z_S (GNSS) and the control
    point X, Y, Z. The Jacobian rows are a′, b′, c′ (l_y) and d′, e′, m′ (l_x) of (9).
    """
    Xst, Yst, Zst = gnss_image_space(x, y, alpha, omega, chi)
    l_y = (Z - Zs) * Xst / Zst + Ys - Y
    l_x = (Z - Zs) * Yst / Zst + Xs - X
    return Model("gnss-collinearity", (alpha, omega, chi), (x, y, f, x0, y0, Xs, Ys, Zs, X, Y, Z), (l_y, l_x))


def printed_gnss_cosine_partials() -> dict:
    """The derivatives of the direction cosines (7) as printed, keyed ``(cosine, angle)``.

    Line 96 gives ∂a₁/∂α = −c₁; lines 101–105 the rest. Values are written with the cosines of
    (6) substituted. ∂c₂/∂χ is not printed (it is absent from the key set).
    """
    A = printed_gnss_direction_cosines()
    a1, a2, a3, b1, b2, b3, c1, c2, c3 = A
    s, c = sp.sin, sp.cos
    zero = sp.Integer(0)
    return {
        ("a1", "alpha"): -c1, ("a1", "omega"): a3 * c(omega), ("a1", "chi"): a2,
        ("a2", "alpha"): -c2, ("a2", "omega"): a3 * c(chi), ("a2", "chi"): -a1,
        ("a3", "alpha"): -c3, ("a3", "omega"): -b3 * s(alpha), ("a3", "chi"): zero,
        ("b1", "alpha"): zero, ("b2", "alpha"): zero, ("b3", "alpha"): zero, ("b3", "chi"): zero,
        ("c3", "chi"): zero,
        ("b1", "omega"): b3 * s(chi), ("b1", "chi"): b2, ("b2", "omega"): b3 * c(chi), ("b2", "chi"): -b1,
        ("b3", "omega"): -c(omega),
        ("c1", "alpha"): a1, ("c1", "omega"): c3 * s(chi), ("c1", "chi"): c2, ("c2", "alpha"): a2,
        ("c2", "omega"): c3 * c(chi), ("c3", "alpha"): a3, ("c3", "omega"): b3 * c(alpha),
    }


def derived_gnss_cosine_partials() -> dict:
    """All 27 derivatives of the direction cosines of (6) by sympy, keyed like (7)."""
    A = printed_gnss_direction_cosines()
    names = ("a1", "a2", "a3", "b1", "b2", "b3", "c1", "c2", "c3")
    return {(n, an): sp.diff(A[i], th) for i, n in enumerate(names)
            for an, th in (("alpha", alpha), ("omega", omega), ("chi", chi))}


def printed_gnss_vector_partials(xx=x, yy=y, a=alpha, w=omega, k=chi) -> dict:
    """The derivatives (8) of X*, Y*, Z* as printed (lines 112–123; repeated for each image at
    lines 149–167): keys ``"X_alpha"`` (= −Z*), ``"A"``, ``"C"``, ``"Y_alpha"`` (= 0), ``"D"``,
    ``"E"``, ``"Z_alpha"`` (= X*), ``"B"``, ``"F"``."""
    A_ = printed_gnss_direction_cosines(a, w, k)
    a1, a2, a3, b1, b2, b3, c1, c2, c3 = A_
    u, v = xx - x0, yy - y0
    s, c = sp.sin, sp.cos
    Xst, Yst, Zst = gnss_image_space(xx, yy, a, w, k)
    return {
        "X_alpha": -Zst,
        "A": a3 * u * c(w) + a3 * v * c(k) + b3 * f * s(a),
        "C": a2 * u - a1 * v,
        "Y_alpha": sp.Integer(0),
        "D": b3 * u * s(k) + b3 * v * c(k) + f * c(w),
        "E": b2 * u - b1 * v,
        "Z_alpha": Xst,
        "B": c3 * u * s(k) + c2 * v * c(k) + c1 * f,
        "F": c2 * u - c1 * v,
    }


def derived_gnss_vector_partials(xx=x, yy=y, a=alpha, w=omega, k=chi) -> dict:
    """The derivatives of (4) by sympy, keyed like :func:`printed_gnss_vector_partials`."""
    r = gnss_image_space(xx, yy, a, w, k)
    keys = {"X_alpha": (0, a), "A": (0, w), "C": (0, k), "Y_alpha": (1, a), "D": (1, w), "E": (1, k),
            "Z_alpha": (2, a), "B": (2, w), "F": (2, k)}
    return {name: sp.diff(r[i], th) for name, (i, th) in keys.items()}


def printed_gnss_coplanarity_coefficients(A1=None, A2=None) -> dict:
    """The coefficients a, b, c, d, e, m of (5) as printed (lines 135–145).

    ``A1``, ``A2`` are dicts of the quantities A…F (image 1) and A*…F* (image 2) to insert;
    by default the printed (8) (lines 149–167), so the result is what the paper computes.
    Pass :func:`derived_gnss_vector_partials` to check the printed *structure* alone.
    """
    A1 = printed_gnss_vector_partials(x1, y1, alpha1, omega1, chi1) if A1 is None else A1
    A2 = printed_gnss_vector_partials(x2, y2, alpha2, omega2, chi2) if A2 is None else A2
    X1, Y1, Z1 = gnss_image_space(x1, y1, alpha1, omega1, chi1)
    X2, Y2, Z2 = gnss_image_space(x2, y2, alpha2, omega2, chi2)
    A, B, C, D, E, F = (A1[k] for k in "ABCDEF")
    As, Bs, Cs, Ds, Es, Fs = (A2[k] for k in "ABCDEF")
    return {
        "a": B_X * (X1 * X2 + Z1 * Z2) - B_Y * X1 * Y2 - B_Z * Z1 * Y2,
        "b": B_X * (B * X2 - A * Z2) + B_Y * (D * Z2 - B * Y2) + B_Z * (A * Y2 - D * X2),
        "c": B_X * (F * X2 - C * Z2) + B_Y * (E * Z2 - F * Y2) + B_Z * (C * Y2 - E * X2),
        "d": B_X * (Z1 * Z2 - X1 * X2) + B_Y * Y1 * X2 + B_Z * X1 * Z2,
        "e": -B_X * (Bs * X1 - Z1 * Z2) + B_Y * (Bs * Y1 - Ds * Z1) + B_Z * (Ds * X1 - As * Y1),
        "m": B_X * (Cs * Z1 - Fs * X1) + B_Y * (Fs * Y1 - Es * Z1) + B_Z * (Es * X1 - Cs * Y1),
    }


def derived_gnss_coplanarity_coefficients() -> dict:
    """∂φ/∂α₁ … ∂φ/∂χ₂ of (1) by sympy, keyed a, b, c, d, e, m like (5)."""
    J = gnss_coplanarity_model().jacobian()
    return dict(zip(GNSS_COEFFICIENTS, list(J)))


def printed_gnss_ground_coefficients(partials=None) -> dict:
    """The coefficients a′…m′ of (9) as printed (lines 190–194) for one image (symbols α, ω, χ, x, y).

    (Z_s − Z) multiplies each; Z_s is the centre of the image. ``partials`` = A…F to insert
    (default the printed (8)). Image 2's a″…m″ are the same expressions with starred quantities.
    """
    P = printed_gnss_vector_partials() if partials is None else partials
    Xst, Yst, Zst = gnss_image_space()
    A, B, C, D, E, F = (P[k] for k in "ABCDEF")
    k = (Zs - Z) / Zst ** 2
    return {
        "a'": k * (Xst ** 2 + Zst ** 2), "b'": k * (B * Xst - A * Zst), "c'": k * (F * Xst - C * Zst),
        "d'": -k * Xst * Yst, "e'": k * (B * Yst - D * Zst), "m'": k * (F * Yst - E * Zst),
    }


def derived_gnss_ground_coefficients() -> dict:
    """∂(Y)/∂(α, ω, χ) and ∂(X)/∂(α, ω, χ) of (3) by sympy, keyed a′…m′ like (9)."""
    J = gnss_collinearity_model().jacobian()
    return dict(zip(GNSS_GROUND_COEFFICIENTS, list(J)))


@lru_cache(maxsize=None)
def printed_gnss_jacobians():
    """Numpy functions of the printed coefficients, for the "as printed" solution.

    Returns ``(coplanarity_fn, ground_fn)``: ``coplanarity_fn(*GNSS_ANGLES, *coplanarity data)``
    gives the printed a, b, c, d, e, m of (5) with the printed A…F of (8), shape (6, n);
    ``ground_fn(α, ω, χ, *collinearity data)`` the printed a′, b′, c′, d′, e′, m′ of (9), shape
    (6, n) (rows l_y: a′ b′ c′, then l_x: d′ e′ m′). Data orders are those of
    :func:`gnss_coplanarity_model` and :func:`gnss_collinearity_model`.
    """
    cop = printed_gnss_coplanarity_coefficients()
    cm = gnss_coplanarity_model()
    f_cop = sp.lambdify(list(cm.parameters) + list(cm.data), [cop[k] for k in GNSS_COEFFICIENTS],
                        modules="numpy", cse=True)
    gr = printed_gnss_ground_coefficients()
    gm = gnss_collinearity_model()
    f_gr = sp.lambdify(list(gm.parameters) + list(gm.data), [gr[k] for k in GNSS_GROUND_COEFFICIENTS],
                       modules="numpy", cse=True)
    return _broadcasting(f_cop, 6), _broadcasting(f_gr, 6)


def printed_gnss_intersection_scale() -> tuple:
    """The three expressions of N printed at line 212, as (numerator, denominator) pairs.

    Symbols: the image-space vectors are written with x₁… replaced by the components
    X₁*, Y₁*, Z₁*, X₂*, Y₂*, Z₂* (returned as the second element, a tuple of symbols).
    """
    X1s, Y1s, Z1s, X2s, Y2s, Z2s = sp.symbols("X_1^* Y_1^* Z_1^* X_2^* Y_2^* Z_2^*", real=True)
    forms = ((B_X * Z2s - B_Z * Y2s, Y1s * Z2s - Z1s * Y2s),
             (B_Z * X2s - B_Y * Z2s, Z1s * X2s - X1s * Z2s),
             (B_Y * Y2s - B_X * X2s, X1s * Y2s - Y1s * X2s))
    return forms, (X1s, Y1s, Z1s, X2s, Y2s, Z2s)


def corrected_gnss_vector_partials(xx=x, yy=y, a=alpha, w=omega, k=chi) -> dict:
    """(8) with the two corrections: A = a₃(x − x₀)sin χ + a₃(y − y₀)cos χ + b₃ f sin α and
    B = c₃(x − x₀)sin χ + c₃(y − y₀)cos χ − b₃ f cos α; the other seven as printed."""
    P = printed_gnss_vector_partials(xx, yy, a, w, k)
    a1, a2, a3, b1, b2, b3, c1, c2, c3 = printed_gnss_direction_cosines(a, w, k)
    u, v = xx - x0, yy - y0
    P["A"] = a3 * u * sp.sin(k) + a3 * v * sp.cos(k) + b3 * f * sp.sin(a)
    P["B"] = c3 * u * sp.sin(k) + c3 * v * sp.cos(k) - b3 * f * sp.cos(a)
    return P


def corrected_gnss_coplanarity_coefficients() -> dict:
    """a…m of (5) in the paper's notation with d and e corrected and the corrected A, B, A*, B*:
    d = −B_X(X₁*X₂* + Z₁*Z₂*) + B_Y Y₁*X₂* + B_Z Y₁*Z₂*,
    e = −B_X(B*X₁* − A*Z₁*) + B_Y(B*Y₁* − D*Z₁*) + B_Z(D*X₁* − A*Y₁*)."""
    A1 = corrected_gnss_vector_partials(x1, y1, alpha1, omega1, chi1)
    A2 = corrected_gnss_vector_partials(x2, y2, alpha2, omega2, chi2)
    out = printed_gnss_coplanarity_coefficients(A1, A2)
    X1, Y1, Z1 = gnss_image_space(x1, y1, alpha1, omega1, chi1)
    X2, Y2, Z2 = gnss_image_space(x2, y2, alpha2, omega2, chi2)
    As, Bs, Ds = A2["A"], A2["B"], A2["D"]
    out["d"] = -B_X * (X1 * X2 + Z1 * Z2) + B_Y * Y1 * X2 + B_Z * Y1 * Z2
    out["e"] = -B_X * (Bs * X1 - As * Z1) + B_Y * (Bs * Y1 - Ds * Z1) + B_Z * (Ds * X1 - As * Y1)
    return out


def corrected_gnss_ground_coefficients() -> dict:
    """a′…m′ of (9) with d′ = +(Z_s − Z)X*Y*/Z*² and the corrected A, B."""
    out = printed_gnss_ground_coefficients(corrected_gnss_vector_partials())
    Xst, Yst, Zst = gnss_image_space()
    out["d'"] = (Zs - Z) * Xst * Yst / Zst ** 2
    return out


# --- Chapter 2: as-printed derivatives -----------------------------------------------------------
# The book's own partial derivatives of §2.8 (relative orientation) and §2.11 (exterior
# orientation of the model), used by the explicit "as printed" modes of
# photolib.image_pair.relative_orientation / absolute_orientation and compared with sympy in
# textbook/ch02.toml ([[formula]] 2.8-…, 2.11-…). Never used by default.

_IMAGE1_SUBS = {omega2: omega1, alpha2: alpha1, kappa2: kappa1, x2: x1, y2: y1, f2: f1}
_RO_ANGLE_OF = {omega1: (1, "omega"), alpha1: (1, "alpha"), kappa1: (1, "kappa"),
                omega2: (2, "omega"), alpha2: (2, "alpha"), kappa2: (2, "kappa")}


def printed_ray_partials(image: int = 2) -> dict:
    """The printed ∂X'ᵢ/∂θ, ∂Y'ᵢ/∂θ, ∂Z'ᵢ/∂θ of §2.8 for image 1 or 2.

    The book prints them for image 2 only (seed lines 1361–1368); its worked example also
    solves for α'₁, κ'₁, and its program evidently used the same expressions with the index 1
    (which is what reproduces the published accuracy). Keys as in
    :func:`printed_relative_orientation_partials`.
    """
    printed = printed_relative_orientation_partials()
    if image == 2:
        return printed
    if image != 1:
        raise ValueError("image must be 1 or 2")
    return {k: sp.sympify(v).xreplace(_IMAGE1_SUBS) for k, v in printed.items()}


def printed_coplanarity_partials(system: str = "independent") -> tuple:
    """The coefficients a₁…a₅ of (2.8.1) as the book computes them, for a system of §2.7.

    a for b_y, b_z: the printed determinants (they equal the sympy derivatives); a for an angle θ
    of image i: the determinant (2.7.3) with the row of image i replaced by the printed
    (∂X'ᵢ/∂θ, ∂Y'ᵢ/∂θ, ∂Z'ᵢ/∂θ) of :func:`printed_ray_partials`. κ–α–ω matrix (1.3.5) only.
    The fixed parameters of the system are substituted by 0.
    """
    if system not in RELATIVE_ORIENTATION_SYSTEMS:
        raise ValueError(f"unknown system {system!r}; use 'independent' or 'dependent'")
    unknowns = RELATIVE_ORIENTATION_SYSTEMS[system]
    fixed = {p: 0 for p in RELATIVE_ORIENTATION_PARAMETERS if p not in unknowns}
    r1 = rotation_matrix_symbolic("kaw", omega1, alpha1, kappa1) * sp.Matrix([x1, y1, -f1])
    r2 = rotation_matrix_symbolic("kaw", omega2, alpha2, kappa2) * sp.Matrix([x2, y2, -f2])
    rows = [sp.Matrix([[1, b_y, b_z]]), r1.T, r2.T]
    phi = sp.Matrix.vstack(*rows).det(method="berkowitz")
    coefficients = []
    for p in unknowns:
        if p in (b_y, b_z):
            coefficients.append(sp.diff(phi, p))
            continue
        image, name = _RO_ANGLE_OF[p]
        partial = printed_ray_partials(image)
        drow = sp.Matrix([[partial[(C, name)] for C in "XYZ"]])
        M = list(rows)
        M[image] = drow
        coefficients.append(sp.Matrix.vstack(*M).det(method="berkowitz"))
    return tuple(sp.sympify(c).subs(fixed) for c in coefficients)


@lru_cache(maxsize=None)
def printed_coplanarity_jacobian(system: str = "independent"):
    """Numpy function of ``(*unknowns, x₁, y₁, f₁, x₂, y₂, f₂)`` giving the printed a₁…a₅, shape (5, n)."""
    unknowns = RELATIVE_ORIENTATION_SYSTEMS[system]
    args = list(unknowns) + [x1, y1, f1, x2, y2, f2]
    fn = sp.lambdify(args, list(printed_coplanarity_partials(system)), modules="numpy", cse=True)
    return _broadcasting(fn, 5)


SIMILARITY_COEFFICIENTS = tuple(f"{row}{j}" for row in "abc" for j in range(1, 8))
"""Names of the coefficients of (2.11.2): a₁…a₇ (φ_X), b₁…b₇ (φ_Y), c₁…c₇ (φ_Z)."""


def printed_similarity_partials() -> dict:
    """a₁…a₇, b₁…b₇, c₁…c₇ of (2.11.2) exactly as printed (seed lines 1463–1481).

    The aᵢⱼ in them are the elements of A_M; the printed ∂/∂ω_M and ∂/∂κ_M agree with the ω–α–κ
    matrix (1.3.2) only. ∂φ/∂α_M (a₅, b₅, c₅) has the wrong sign on both sin κ_M terms: see
    :func:`derived_similarity_partials`.
    """
    A = rotation_matrix_symbolic("wak", omegaM, alphaM, kappaM)
    a = lambda i, j: A[i - 1, j - 1]  # noqa: E731 — the book's a_ij
    ck, sk = sp.cos(kappaM), sp.sin(kappaM)
    t = t_M
    out = {}
    for r, row in enumerate("abc", start=1):
        out.update({f"{row}{j}": sp.Integer(-1 if j == r else 0) for j in (1, 2, 3)})
        out[f"{row}5"] = (a(r, 3) * ck * XM + a(r, 3) * sk * YM - (a(r, 1) * ck + a(r, 2) * sk) * ZM) * t
        out[f"{row}6"] = (-a(r, 2) * XM + a(r, 1) * YM) * t
        out[f"{row}7"] = -(a(r, 1) * XM + a(r, 2) * YM + a(r, 3) * ZM)
    out["a4"] = sp.Integer(0)
    out["b4"] = (a(3, 1) * XM + a(3, 2) * YM + a(3, 3) * ZM) * t
    out["c4"] = -(a(2, 1) * XM + a(2, 2) * YM + a(2, 3) * ZM) * t
    return {k: out[k] for k in SIMILARITY_COEFFICIENTS}


def derived_similarity_partials(order: str = "wak") -> dict:
    """a₁…c₇ of (2.11.2) derived by sympy from (2.11.1) (:func:`similarity_model`)."""
    J = similarity_model(order).jacobian()
    return {f"{row}{j + 1}": J[i, j] for i, row in enumerate("abc") for j in range(7)}


@lru_cache(maxsize=None)
def printed_similarity_jacobian(zero_a5: bool = False):
    """Numpy function of ``(*elements, X_M, Y_M, Z_M, X, Y, Z)`` giving the printed a₁…c₇, shape (21, n).

    ``zero_a5=True`` sets a₅ = ∂φ_X/∂α_M to 0: what the book's program evidently did in the §2.11
    worked example (only then do its X₀, m_X₀ and the X₀ row of the correlation matrix come out).
    """
    printed = printed_similarity_partials()
    if zero_a5:
        printed["a5"] = sp.Integer(0)
    args = [X0, Y0, Z0, omegaM, alphaM, kappaM, t_M, XM, YM, ZM, X, Y, Z]
    fn = sp.lambdify(args, [printed[k] for k in SIMILARITY_COEFFICIENTS], modules="numpy", cse=True)
    return _broadcasting(fn, 21)


# --- Chapter 3: self-calibration, rigs, rolling shutter ---
# §3.6 (3.6.1)–(3.6.3), §3.8 (3.8.3)–(3.8.15), §3.9 (3.9.1)–(3.9.2). Used by photolib.bundle.
IO_SYMBOLS = (f, x0, y0, k1, k2, k3, p1, p2)
B_X, B_Y, B_Z = sp.symbols("B_X B_Y B_Z", real=True)
omega_2p, alpha_2p, kappa_2p = sp.symbols("omega_2p alpha_2p kappa_2p", real=True)
MOUNT_SYMBOLS = (B_X, B_Y, B_Z, omega_2p, alpha_2p, kappa_2p)
k_XS, k_YS, k_ZS, k_omega, k_alpha, k_kappa = sp.symbols("k_XS k_YS k_ZS k_omega k_alpha k_kappa", real=True)
RATE_SYMBOLS = (k_XS, k_YS, k_ZS, k_omega, k_alpha, k_kappa)


def brown_correction_terms(xb, yb):
    """Δ_x, Δ_y of (3.6.2) = (1.2.2) for coordinates xb, yb (reduced to the principal point)."""
    r2 = xb ** 2 + yb ** 2
    radial = k1 * r2 + k2 * r2 ** 2 + k3 * r2 ** 3
    return (xb * radial + (r2 + 2 * xb ** 2) * p1 + 2 * xb * yb * p2,
            yb * radial + 2 * xb * yb * p1 + (r2 + 2 * yb ** 2) * p2)


def printed_brown_3_6_2():
    """(Δ_x, Δ_y) of (3.6.2) exactly as printed: r = √(x² + y²), p₁(y² + 3x²), p₂(x² + 3y²)."""
    r = sp.sqrt(x ** 2 + y ** 2)
    radial = k1 * r ** 2 + k2 * r ** 4 + k3 * r ** 6
    return (x * radial + p1 * (y ** 2 + 3 * x ** 2) + 2 * p2 * x * y,
            y * radial + (2 * p1 * x * y + p2 * (x ** 2 + 3 * y ** 2)))


@lru_cache(maxsize=None)
def self_calibration_model(order: str = "kaw") -> Model:
    """(3.6.1) with (3.6.2): the bundle model with interior orientation and distortion unknown.

    F_x = x₀ − f x*/z* − x − Δ_x,  F_y = y₀ − f y*/z* − y − Δ_y,  Δ of (3.6.2)/(1.2.2) evaluated at
    the measured coordinates reduced to the principal point (x − x₀, y − y₀), so that x + Δ_x is the
    ideal coordinate exactly as in :func:`photolib.camera.correct_distortion`. Parameters: the 6
    EO, X, Y, Z and the 8 block-wide f, x₀, y₀, k₁, k₂, k₃, p₁, p₂ — the 17 columns a₁…a₁₇ of
    (3.6.3); data x, y.
    """
    Xst, Yst, Zst = collinearity_terms(order)
    d_x, d_y = brown_correction_terms(x - x0, y - y0)
    F_x = x0 - f * Xst / Zst - x - d_x
    F_y = y0 - f * Yst / Zst - y - d_y
    return Model(f"self-calibration-{order}", EO_SYMBOLS + (X, Y, Z) + IO_SYMBOLS, (x, y), (F_x, F_y))


def rig_camera_terms(order: str = "kaw"):
    """(S₂, C₂) of a rig camera: S₂ = S₁ + A₁B (3.8.5), C₂ = A₁A₂′ (3.8.8)."""
    A1 = rotation_matrix_symbolic(order)
    A2p = rotation_matrix_symbolic(order, omega_2p, alpha_2p, kappa_2p)
    S2 = sp.Matrix([Xs, Ys, Zs]) + A1 * sp.Matrix([B_X, B_Y, B_Z])
    return S2, A1 * A2p


@lru_cache(maxsize=None)
def rig_collinearity_model(order: str = "kaw") -> Model:
    """(3.8.13): collinearity of a rig camera in the reference EO and the 6 mounting elements.

    (X*, Y*, Z*)ᵀ = C₂ᵀ(X − X_S2, Y − Y_S2, Z − Z_S2)ᵀ (3.8.12) with S₂ and C₂ from
    :func:`rig_camera_terms`. Parameters X_S1 … κ₁ (written X_S … κ), B_X, B_Y, B_Z, ω₂′, α₂′, κ₂′,
    X, Y, Z — the 15 columns c₁…c₁₅ / d₁…d₁₅ of (3.8.15); data x, y, f, x₀, y₀.
    """
    S2, C2 = rig_camera_terms(order)
    Xst, Yst, Zst = C2.T * (sp.Matrix([X, Y, Z]) - S2)
    F_x = x0 - f * Xst / Zst - x
    F_y = y0 - f * Yst / Zst - y
    return Model(f"rig-collinearity-{order}", EO_SYMBOLS + MOUNT_SYMBOLS + (X, Y, Z), (x, y, f, x0, y0), (F_x, F_y))


def printed_rig_3_8_13(order: str = "kaw"):
    """(x₂, y₂) of (3.8.13) in the printed element form c₁₁…c₃₃ (C₂ = A₁A₂′), S₂ by (3.8.5)."""
    S2, C2 = rig_camera_terms(order)
    c = lambda i, j: C2[i - 1, j - 1]  # noqa: E731
    dX, dY, dZ = X - S2[0], Y - S2[1], Z - S2[2]
    den = c(1, 3) * dX + c(2, 3) * dY + c(3, 3) * dZ
    return (x0 - f * (c(1, 1) * dX + c(2, 1) * dY + c(3, 1) * dZ) / den,
            y0 - f * (c(1, 2) * dX + c(2, 2) * dY + c(3, 2) * dZ) / den)


def derived_rig_image_coordinates(order: str = "kaw"):
    """(x₂, y₂) derived from the vector equation (3.8.8): R_M = R_S1 + A₁B + N·C₂r₂, r₂ = (x₂ − x₀, y₂ − y₀, −f)."""
    S2, C2 = rig_camera_terms(order)
    # (3.8.8) componentwise: X − S₂ = C₂·(N(x₂ − x₀), N(y₂ − y₀), −N f)ᵀ, and C₂⁻¹ = C₂ᵀ (a rotation)
    u, v, w = C2.T * (sp.Matrix([X, Y, Z]) - S2)
    N_val = -w / f                                   # third row: −N f = Z*  →  1/N = −f/Z*
    return x0 + u / N_val, y0 + v / N_val


@lru_cache(maxsize=None)
def rolling_shutter_model(order: str = "kaw") -> Model:
    """(3.9.1) with (3.9.2): collinearity of an image line whose EO moves linearly with x.

    EO of the line imaged at x: X_Si = X_S0 + k₁x, …, κ_i = κ₀ + k₆x (3.9.2), the measured image
    coordinate x standing for the time of the line; then F_x = x₀ − f x*/z* − x, F_y likewise
    with (x*, y*, z*)ᵀ = A_iᵀ(X − X_Si, …)ᵀ (3.9.1; the book omits x₀, y₀). Parameters X_S0 …
    κ₀ (written X_S … κ), the rates k₁…k₆ (written k_XS … k_kappa), X, Y, Z; data x, y, f, x₀, y₀.
    Holding k₄ = k₅ = k₆ = 0 gives the simplified 9-unknown model.
    """
    eo_i = [s + k * x for s, k in zip(EO_SYMBOLS, RATE_SYMBOLS)]
    A = rotation_matrix_symbolic(order, eo_i[3], eo_i[4], eo_i[5])
    Xst, Yst, Zst = A.T * sp.Matrix([X - eo_i[0], Y - eo_i[1], Z - eo_i[2]])
    F_x = x0 - f * Xst / Zst - x
    F_y = y0 - f * Yst / Zst - y
    return Model(f"rolling-shutter-{order}", EO_SYMBOLS + RATE_SYMBOLS + (X, Y, Z), (x, y, f, x0, y0), (F_x, F_y))


# --- Chapter 4 models --------------------------------------------------------------------------
H_SYMBOLS = sp.symbols("h_1:9", real=True)
x_t, y_t = sp.symbols("x_t y_t", real=True)


@lru_cache(maxsize=None)
def homography_model() -> Model:
    """Plane-to-plane projective transformation with h₃₃ = 1 (8 parameters, cf. (1.7.5) and (4.1.7)).

    F_x = (h₁x + h₂y + h₃)/(h₇x + h₈y + 1) − x_t, F_y = (h₄x + h₅y + h₆)/(h₇x + h₈y + 1) − y_t;
    parameters h₁…h₈, data (x, y, x_t, y_t): source point and its measured image.
    Used by :func:`photolib.projective.homography_lsq`.
    """
    h1, h2, h3, h4, h5, h6, h7, h8 = H_SYMBOLS
    w = h7 * x + h8 * y + 1
    return Model("homography", tuple(H_SYMBOLS), (x, y, x_t, y_t),
                 ((h1 * x + h2 * y + h3) / w - x_t, (h4 * x + h5 * y + h6) / w - y_t))
