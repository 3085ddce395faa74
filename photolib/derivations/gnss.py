"""The GNSS-centres paper in sympy: a stereo pair whose projection centres are known (appendix to Chapter 2).

N.F. Dobrynin, T.M. Pimshina, «Использование космических средств позиционирования при обработке
аэро- и космической информации» (the appendix "GNSS centres" of the book; cf. Chapter 2, §2.7–§2.8
for the coplanarity condition): the α–ω–χ rotation (6), the coplanarity condition (1) with the base
(2) known, the collinearity equations (3)/(4), the derivatives (7), (8) and coefficients (5), (9)
as printed, as derived by sympy and as corrected.
"""

from __future__ import annotations

from functools import lru_cache

import sympy as sp

from ..errors import InputError
from .model import Model, _printed_function
from .symbols import (B_X, B_Y, B_Z, X, Xs, Y, Ys, Z, Zs, alpha, alpha1, alpha2, chi, chi1, chi2, f, omega,
                      omega1, omega2, x, x0, x1, x2, y, y0, y1, y2)

__all__ = ["GNSS_ANGLES", "GNSS_COEFFICIENTS", "GNSS_GROUND_COEFFICIENTS", "gnss_rotation_symbolic",
           "printed_gnss_direction_cosines", "gnss_coplanarity_model", "gnss_collinearity_model",
           "printed_gnss_cosine_partials", "derived_gnss_cosine_partials", "printed_gnss_vector_partials",
           "derived_gnss_vector_partials", "printed_gnss_coplanarity_coefficients",
           "derived_gnss_coplanarity_coefficients", "printed_gnss_ground_coefficients",
           "derived_gnss_ground_coefficients", "printed_gnss_jacobians", "printed_gnss_intersection_scale",
           "corrected_gnss_vector_partials", "corrected_gnss_coplanarity_coefficients",
           "corrected_gnss_ground_coefficients"]


def _sym(*values):
    try:
        return tuple(sp.sympify(v, strict=True) for v in values)
    except (sp.SympifyError, TypeError) as exc:
        raise InputError(f"symbolic arguments must be sympy expressions or numbers: {exc}") from exc


def _partials_dict(value, name):
    if not isinstance(value, dict) or not set("ABCDEF") <= set(value):
        raise InputError(f"{name} must be a dict with the keys A, B, C, D, E, F (as (8)), got {type(value).__name__}")
    return value


# --- GNSS-centres paper (seed 001) ---
# N.F. Dobrynin, T.M. Pimshina, «Использование космических средств позиционирования при обработке
# аэро- и космической информации» (seed 001_723f59c162a2adba.txt). A stereo pair whose projection
# centres are known from GNSS: the unknowns are the six angles α₁, ω₁, χ₁, α₂, ω₂, χ₂ of the α–ω–χ
# system (6). Frames: geodetic X north, Y east, Z up (left-handed); the image-space frame S X* Y* Z*
# has X* ∥ Y (east), Y* ∥ X (north), Z* ∥ Z, so a geodetic difference (ΔX, ΔY, ΔZ) has image-frame
# components (ΔY, ΔX, ΔZ) — hence the base row (B_Y, B_X, B_Z) of (1).
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

    Parameters
    ----------
    a, w, k : sympy.Expr, optional
        The angles α, ω, χ (default the symbols alpha, omega, chi).

    Returns
    -------
    sympy.Matrix
        3×3 rotation matrix.

    Raises
    ------
    InputError
        If an argument is not a sympy expression or a number.

    References
    ----------
    Dobrynin & Pimshina, GNSS-centres paper (appendix of the book), eq. (6).

    Examples
    --------
    >>> import sympy as sp
    >>> sp.simplify(gnss_rotation_symbolic() - printed_gnss_direction_cosines()) == sp.zeros(3, 3)
    True
    """
    a, w, k = _sym(a, w, k)
    c, s = sp.cos, sp.sin
    R_Y = sp.Matrix([[c(a), 0, -s(a)], [0, 1, 0], [s(a), 0, c(a)]])
    R_X = sp.Matrix([[1, 0, 0], [0, c(w), -s(w)], [0, s(w), c(w)]])
    R_Z = sp.Matrix([[c(k), -s(k), 0], [s(k), c(k), 0], [0, 0, 1]])
    return R_Y * R_X * R_Z


def printed_gnss_direction_cosines(a=alpha, w=omega, k=chi) -> sp.Matrix:
    """The direction cosines (6) exactly as printed (seed lines 82–92), rows (a), (b), (c).

    Parameters
    ----------
    a, w, k : sympy.Expr, optional
        The angles α, ω, χ (default the symbols alpha, omega, chi).

    Returns
    -------
    sympy.Matrix
        3×3, rows (a₁ a₂ a₃), (b₁ b₂ b₃), (c₁ c₂ c₃).

    Raises
    ------
    InputError
        If an argument is not a sympy expression or a number.

    References
    ----------
    Dobrynin & Pimshina, GNSS-centres paper (appendix of the book), eq. (6).

    Examples
    --------
    >>> printed_gnss_direction_cosines()[1, 2]
    -sin(omega)
    """
    a, w, k = _sym(a, w, k)
    c, s = sp.cos, sp.sin
    return sp.Matrix([
        [c(a) * c(k) - s(a) * s(w) * s(k), -c(a) * s(k) - s(a) * s(w) * c(k), -s(a) * c(w)],
        [c(w) * s(k), c(w) * c(k), -s(w)],
        [s(a) * c(k) + c(a) * s(w) * s(k), -s(a) * s(k) + c(a) * s(w) * c(k), c(a) * c(w)],
    ])


def _gnss_image_space(xx=x, yy=y, a=alpha, w=omega, k=chi) -> sp.Matrix:
    """(X*, Y*, Z*) of (4): (x − x₀)a₁ + (y − y₀)a₂ − f a₃ etc., the direction cosines of (6)."""
    return printed_gnss_direction_cosines(a, w, k) * sp.Matrix([xx - x0, yy - y0, -f])


def _gnss_coplanarity_expression() -> sp.Expr:
    """φ of (1): det[[B_Y, B_X, B_Z], [X₁*, Y₁*, Z₁*], [X₂*, Y₂*, Z₂*]], the vectors of (4)."""
    r1 = _gnss_image_space(x1, y1, alpha1, omega1, chi1)
    r2 = _gnss_image_space(x2, y2, alpha2, omega2, chi2)
    # the determinant by its first row, not expanded: the same function as
    # Matrix(...).det() (checked in the tests), with printed numpy code a tenth as long
    return (B_Y * (r1[1] * r2[2] - r1[2] * r2[1]) - B_X * (r1[0] * r2[2] - r1[2] * r2[0])
            + B_Z * (r1[0] * r2[1] - r1[1] * r2[0]))


@lru_cache(maxsize=None)
def gnss_coplanarity_model() -> Model:
    """The coplanarity condition (1) with the six angles unknown and the base (2) known from GNSS.

    Data: x₁, y₁, x₂, y₂ (mm), f, x₀, y₀ (one camera), B_X, B_Y, B_Z (geodetic, (2)). The rows
    of the Jacobian are the coefficients a, b, c, d, e, m of the correction equation (5).

    Returns
    -------
    Model
        Parameters :data:`GNSS_ANGLES`; data x₁, y₁, x₂, y₂, f, x₀, y₀, B_X, B_Y, B_Z.

    Raises
    ------
    InputError
        Never (no input).

    References
    ----------
    Dobrynin & Pimshina, GNSS-centres paper (appendix of the book), eq. (1), (2), (5).

    Examples
    --------
    >>> [str(p) for p in gnss_coplanarity_model().parameters][:3]
    ['alpha_1', 'omega_1', 'chi_1']
    """
    return Model("gnss-coplanarity", GNSS_ANGLES, (x1, y1, x2, y2, f, x0, y0, B_X, B_Y, B_Z),
                 (_gnss_coplanarity_expression(),))


@lru_cache(maxsize=None)
def gnss_collinearity_model() -> Model:
    """The collinearity equations (3) of one image as free terms of (9): l_y = (Y) − Y, l_x = (X) − X.

    (Y) = (Z − Z_S)X*/Z* + Y_S and (X) = (Z − Z_S)Y*/Z* + X_S, with X*, Y*, Z* of (4). Unknowns
    α, ω, χ of the image; data x, y, f, x₀, y₀, the centre X_S, Y_S, Z_S (GNSS) and the control
    point X, Y, Z. The Jacobian rows are a′, b′, c′ (l_y) and d′, e′, m′ (l_x) of (9).

    Returns
    -------
    Model
        Parameters α, ω, χ; data x, y, f, x₀, y₀, X_S, Y_S, Z_S, X, Y, Z.

    Raises
    ------
    InputError
        Never (no input).

    References
    ----------
    Dobrynin & Pimshina, GNSS-centres paper (appendix of the book), eq. (3), (9).

    Examples
    --------
    >>> [str(p) for p in gnss_collinearity_model().parameters]
    ['alpha', 'omega', 'chi']
    """
    Xst, Yst, Zst = _gnss_image_space(x, y, alpha, omega, chi)
    l_y = (Z - Zs) * Xst / Zst + Ys - Y
    l_x = (Z - Zs) * Yst / Zst + Xs - X
    return Model("gnss-collinearity", (alpha, omega, chi), (x, y, f, x0, y0, Xs, Ys, Zs, X, Y, Z), (l_y, l_x))


def printed_gnss_cosine_partials() -> dict:
    """The derivatives of the direction cosines (7) as printed, keyed ``(cosine, angle)``.

    Line 96 gives ∂a₁/∂α = −c₁; lines 101–105 the rest. Values are written with the cosines of
    (6) substituted. ∂c₂/∂χ is not printed (it is absent from the key set).

    Returns
    -------
    dict
        Keys ``(cosine, angle)`` such as ``("a1", "alpha")``.

    Raises
    ------
    InputError
        Never (no input).

    References
    ----------
    Dobrynin & Pimshina, GNSS-centres paper (appendix of the book), eq. (7).

    Examples
    --------
    >>> printed_gnss_cosine_partials()[("b3", "omega")]
    -cos(omega)
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
    """All 27 derivatives of the direction cosines of (6) by sympy, keyed like (7).

    Returns
    -------
    dict
        27 entries keyed like :func:`printed_gnss_cosine_partials`.

    Raises
    ------
    InputError
        Never (no input).

    References
    ----------
    Dobrynin & Pimshina, GNSS-centres paper (appendix of the book), eq. (6), (7).

    Examples
    --------
    >>> derived_gnss_cosine_partials()[("b3", "omega")]
    -cos(omega)
    """
    A = printed_gnss_direction_cosines()
    names = ("a1", "a2", "a3", "b1", "b2", "b3", "c1", "c2", "c3")
    return {(n, an): sp.diff(A[i], th) for i, n in enumerate(names)
            for an, th in (("alpha", alpha), ("omega", omega), ("chi", chi))}


def printed_gnss_vector_partials(xx=x, yy=y, a=alpha, w=omega, k=chi) -> dict:
    """The derivatives (8) of X*, Y*, Z* as printed (lines 112–123; repeated for each image at
    lines 149–167): keys ``"X_alpha"`` (= −Z*), ``"A"``, ``"C"``, ``"Y_alpha"`` (= 0), ``"D"``,
    ``"E"``, ``"Z_alpha"`` (= X*), ``"B"``, ``"F"``.

    Parameters
    ----------
    xx, yy : sympy.Expr, optional
        Image coordinates (default the symbols x, y).
    a, w, k : sympy.Expr, optional
        The angles α, ω, χ (default the symbols alpha, omega, chi).

    Returns
    -------
    dict
        Keys X_alpha, A, C, Y_alpha, D, E, Z_alpha, B, F.

    Raises
    ------
    InputError
        If an argument is not a sympy expression or a number.

    References
    ----------
    Dobrynin & Pimshina, GNSS-centres paper (appendix of the book), eq. (8).

    Examples
    --------
    >>> printed_gnss_vector_partials()["Y_alpha"]
    0
    """
    xx, yy, a, w, k = _sym(xx, yy, a, w, k)
    A_ = printed_gnss_direction_cosines(a, w, k)
    a1, a2, a3, b1, b2, b3, c1, c2, c3 = A_
    u, v = xx - x0, yy - y0
    s, c = sp.sin, sp.cos
    Xst, Yst, Zst = _gnss_image_space(xx, yy, a, w, k)
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
    """The derivatives of (4) by sympy, keyed like :func:`printed_gnss_vector_partials`.

    Parameters
    ----------
    xx, yy : sympy.Expr, optional
        Image coordinates (default the symbols x, y).
    a, w, k : sympy.Expr, optional
        The angles α, ω, χ (default the symbols alpha, omega, chi).

    Returns
    -------
    dict
        Keyed like :func:`printed_gnss_vector_partials`.

    Raises
    ------
    InputError
        If an argument is not a sympy expression or a number.

    References
    ----------
    Dobrynin & Pimshina, GNSS-centres paper (appendix of the book), eq. (4), (8).

    Examples
    --------
    >>> derived_gnss_vector_partials()["Y_alpha"]
    0
    """
    return dict(_derived_gnss_vector_partials(*_sym(xx, yy, a, w, k)))


@lru_cache(maxsize=64)
def _derived_gnss_vector_partials(xx, yy, a, w, k) -> dict:
    """The partials of :func:`derived_gnss_vector_partials`, derived once per argument tuple
    (sympy expressions are immutable; callers get a copy of the dict)."""
    r = _gnss_image_space(xx, yy, a, w, k)
    keys = {"X_alpha": (0, a), "A": (0, w), "C": (0, k), "Y_alpha": (1, a), "D": (1, w), "E": (1, k),
            "Z_alpha": (2, a), "B": (2, w), "F": (2, k)}
    return {name: sp.diff(r[i], th) for name, (i, th) in keys.items()}


def printed_gnss_coplanarity_coefficients(A1=None, A2=None) -> dict:
    """The coefficients a, b, c, d, e, m of (5) as printed (lines 135–145).

    ``A1``, ``A2`` are dicts of the quantities A…F (image 1) and A*…F* (image 2) to insert;
    by default the printed (8) (lines 149–167), so the result is what the paper computes.
    Pass :func:`derived_gnss_vector_partials` to check the printed *structure* alone.

    Parameters
    ----------
    A1, A2 : dict, optional
        The quantities A…F of images 1 and 2 (default the printed (8)).

    Returns
    -------
    dict
        Keys :data:`GNSS_COEFFICIENTS`.

    Raises
    ------
    InputError
        If ``A1`` or ``A2`` is not a dict with the keys A…F.

    References
    ----------
    Dobrynin & Pimshina, GNSS-centres paper (appendix of the book), eq. (5), (8).

    Examples
    --------
    >>> sorted(printed_gnss_coplanarity_coefficients())
    ['a', 'b', 'c', 'd', 'e', 'm']
    """
    A1 = printed_gnss_vector_partials(x1, y1, alpha1, omega1, chi1) if A1 is None else _partials_dict(A1, "A1")
    A2 = printed_gnss_vector_partials(x2, y2, alpha2, omega2, chi2) if A2 is None else _partials_dict(A2, "A2")
    X1, Y1, Z1 = _gnss_image_space(x1, y1, alpha1, omega1, chi1)
    X2, Y2, Z2 = _gnss_image_space(x2, y2, alpha2, omega2, chi2)
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
    """∂φ/∂α₁ … ∂φ/∂χ₂ of (1) by sympy, keyed a, b, c, d, e, m like (5).

    Derived by the product rule for determinants, as the paper does: ∂φ/∂θ is the determinant
    (1) with the row of the image that θ belongs to replaced by its sympy derivative
    ∂(X*, Y*, Z*)/∂θ of (4). (Differentiating the expanded determinant gives the same functions —
    the rows of ``gnss_coplanarity_model().jacobian()``, checked in the tests — but takes seconds.)

    Returns
    -------
    dict
        Keys :data:`GNSS_COEFFICIENTS`.

    Raises
    ------
    InputError
        Never (no input).

    References
    ----------
    Dobrynin & Pimshina, GNSS-centres paper (appendix of the book), eq. (1), (5).

    Examples
    --------
    >>> sorted(derived_gnss_coplanarity_coefficients())
    ['a', 'b', 'c', 'd', 'e', 'm']
    """
    return dict(_derived_gnss_coplanarity_coefficients())


@lru_cache(maxsize=None)
def _derived_gnss_coplanarity_coefficients():
    base = sp.Matrix([[B_Y, B_X, B_Z]])
    r1 = _gnss_image_space(x1, y1, alpha1, omega1, chi1)
    r2 = _gnss_image_space(x2, y2, alpha2, omega2, chi2)
    out = []
    for image, r, angles in ((1, r1, (alpha1, omega1, chi1)), (2, r2, (alpha2, omega2, chi2))):
        for theta in angles:
            rows = [list(base), list(r1), list(r2)]
            rows[image] = [sp.diff(e, theta) for e in r]
            out.append(_det3(rows))
    return tuple(zip(GNSS_COEFFICIENTS, out))


def _det3(m):
    """det of a 3×3 list of rows by the Laplace expansion along the first row (no simplification)."""
    return (m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
            + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]))


def printed_gnss_ground_coefficients(partials=None) -> dict:
    """The coefficients a′…m′ of (9) as printed (lines 190–194) for one image (symbols α, ω, χ, x, y).

    (Z_s − Z) multiplies each; Z_s is the centre of the image. ``partials`` = A…F to insert
    (default the printed (8)). Image 2's a″…m″ are the same expressions with starred quantities.

    Parameters
    ----------
    partials : dict, optional
        The quantities A…F to insert (default the printed (8)).

    Returns
    -------
    dict
        Keys :data:`GNSS_GROUND_COEFFICIENTS`.

    Raises
    ------
    InputError
        If ``partials`` is not a dict with the keys A…F.

    References
    ----------
    Dobrynin & Pimshina, GNSS-centres paper (appendix of the book), eq. (9).

    Examples
    --------
    >>> sorted(printed_gnss_ground_coefficients())
    ["a'", "b'", "c'", "d'", "e'", "m'"]
    """
    P = printed_gnss_vector_partials() if partials is None else _partials_dict(partials, "partials")
    Xst, Yst, Zst = _gnss_image_space()
    A, B, C, D, E, F = (P[k] for k in "ABCDEF")
    k = (Zs - Z) / Zst ** 2
    return {
        "a'": k * (Xst ** 2 + Zst ** 2), "b'": k * (B * Xst - A * Zst), "c'": k * (F * Xst - C * Zst),
        "d'": -k * Xst * Yst, "e'": k * (B * Yst - D * Zst), "m'": k * (F * Yst - E * Zst),
    }


def derived_gnss_ground_coefficients() -> dict:
    """∂(Y)/∂(α, ω, χ) and ∂(X)/∂(α, ω, χ) of (3) by sympy, keyed a′…m′ like (9).

    Returns
    -------
    dict
        Keys :data:`GNSS_GROUND_COEFFICIENTS`.

    Raises
    ------
    InputError
        Never (no input).

    References
    ----------
    Dobrynin & Pimshina, GNSS-centres paper (appendix of the book), eq. (3), (9).

    Examples
    --------
    >>> sorted(derived_gnss_ground_coefficients())
    ["a'", "b'", "c'", "d'", "e'", "m'"]
    """
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

    Returns
    -------
    tuple of callable
        ``(coplanarity_fn, ground_fn)``.

    Raises
    ------
    InputError
        Never (no input).

    References
    ----------
    Dobrynin & Pimshina, GNSS-centres paper (appendix of the book), eq. (5), (8), (9).

    Examples
    --------
    >>> cop, ground = printed_gnss_jacobians()
    >>> cop(0, 0, 0, 0, 0, 0, 1.0, 2.0, -80.0, 2.0, 100.0, 0, 0, 0, 500.0, 10.0).shape
    (6,)
    """
    return (_printed_function("printed-gnss-coplanarity", _printed_gnss_coplanarity_build),
            _printed_function("printed-gnss-ground", _printed_gnss_ground_build))


def _printed_gnss_coplanarity_build():
    cop = printed_gnss_coplanarity_coefficients()
    cm = gnss_coplanarity_model()
    return list(cm.parameters) + list(cm.data), [cop[k] for k in GNSS_COEFFICIENTS], 6


def _printed_gnss_ground_build():
    gr = printed_gnss_ground_coefficients()
    gm = gnss_collinearity_model()
    return list(gm.parameters) + list(gm.data), [gr[k] for k in GNSS_GROUND_COEFFICIENTS], 6


def printed_gnss_intersection_scale() -> tuple:
    """The three expressions of N printed at line 212, as (numerator, denominator) pairs.

    Symbols: the image-space vectors are written with x₁… replaced by the components
    X₁*, Y₁*, Z₁*, X₂*, Y₂*, Z₂* (returned as the second element, a tuple of symbols).

    Returns
    -------
    tuple
        ``(forms, symbols)``: three (numerator, denominator) pairs and the six symbols.

    Raises
    ------
    InputError
        Never (no input).

    References
    ----------
    Dobrynin & Pimshina, GNSS-centres paper (appendix of the book), eq. (N after (9).

    Examples
    --------
    >>> forms, symbols = printed_gnss_intersection_scale()
    >>> len(forms), len(symbols)
    (3, 6)
    """
    X1s, Y1s, Z1s, X2s, Y2s, Z2s = sp.symbols("X_1^* Y_1^* Z_1^* X_2^* Y_2^* Z_2^*", real=True)
    forms = ((B_X * Z2s - B_Z * Y2s, Y1s * Z2s - Z1s * Y2s),
             (B_Z * X2s - B_Y * Z2s, Z1s * X2s - X1s * Z2s),
             (B_Y * Y2s - B_X * X2s, X1s * Y2s - Y1s * X2s))
    return forms, (X1s, Y1s, Z1s, X2s, Y2s, Z2s)


def corrected_gnss_vector_partials(xx=x, yy=y, a=alpha, w=omega, k=chi) -> dict:
    """(8) with the two corrections: A = a₃(x − x₀)sin χ + a₃(y − y₀)cos χ + b₃ f sin α and
    B = c₃(x − x₀)sin χ + c₃(y − y₀)cos χ − b₃ f cos α; the other seven as printed.

    Parameters
    ----------
    xx, yy : sympy.Expr, optional
        Image coordinates (default the symbols x, y).
    a, w, k : sympy.Expr, optional
        The angles α, ω, χ (default the symbols alpha, omega, chi).

    Returns
    -------
    dict
        Keyed like :func:`printed_gnss_vector_partials`.

    Raises
    ------
    InputError
        If an argument is not a sympy expression or a number.

    References
    ----------
    Dobrynin & Pimshina, GNSS-centres paper (appendix of the book), eq. (8).

    Examples
    --------
    >>> import sympy as sp
    >>> corr, der = corrected_gnss_vector_partials(), derived_gnss_vector_partials()
    >>> sp.simplify(corr["A"] - der["A"])
    0
    """
    xx, yy, a, w, k = _sym(xx, yy, a, w, k)
    P = printed_gnss_vector_partials(xx, yy, a, w, k)
    a1, a2, a3, b1, b2, b3, c1, c2, c3 = printed_gnss_direction_cosines(a, w, k)
    u, v = xx - x0, yy - y0
    P["A"] = a3 * u * sp.sin(k) + a3 * v * sp.cos(k) + b3 * f * sp.sin(a)
    P["B"] = c3 * u * sp.sin(k) + c3 * v * sp.cos(k) - b3 * f * sp.cos(a)
    return P


def corrected_gnss_coplanarity_coefficients() -> dict:
    """a…m of (5) in the paper's notation with d and e corrected and the corrected A, B, A*, B*:
    d = −B_X(X₁*X₂* + Z₁*Z₂*) + B_Y Y₁*X₂* + B_Z Y₁*Z₂*,
    e = −B_X(B*X₁* − A*Z₁*) + B_Y(B*Y₁* − D*Z₁*) + B_Z(D*X₁* − A*Y₁*).

    Returns
    -------
    dict
        Keys :data:`GNSS_COEFFICIENTS`.

    Raises
    ------
    InputError
        Never (no input).

    References
    ----------
    Dobrynin & Pimshina, GNSS-centres paper (appendix of the book), eq. (5).

    Examples
    --------
    >>> sorted(corrected_gnss_coplanarity_coefficients())
    ['a', 'b', 'c', 'd', 'e', 'm']
    """
    A1 = corrected_gnss_vector_partials(x1, y1, alpha1, omega1, chi1)
    A2 = corrected_gnss_vector_partials(x2, y2, alpha2, omega2, chi2)
    out = printed_gnss_coplanarity_coefficients(A1, A2)
    X1, Y1, Z1 = _gnss_image_space(x1, y1, alpha1, omega1, chi1)
    X2, Y2, Z2 = _gnss_image_space(x2, y2, alpha2, omega2, chi2)
    As, Bs, Ds = A2["A"], A2["B"], A2["D"]
    out["d"] = -B_X * (X1 * X2 + Z1 * Z2) + B_Y * Y1 * X2 + B_Z * Y1 * Z2
    out["e"] = -B_X * (Bs * X1 - As * Z1) + B_Y * (Bs * Y1 - Ds * Z1) + B_Z * (Ds * X1 - As * Y1)
    return out


def corrected_gnss_ground_coefficients() -> dict:
    """a′…m′ of (9) with d′ = +(Z_s − Z)X*Y*/Z*² and the corrected A, B.

    Returns
    -------
    dict
        Keys :data:`GNSS_GROUND_COEFFICIENTS`.

    Raises
    ------
    InputError
        Never (no input).

    References
    ----------
    Dobrynin & Pimshina, GNSS-centres paper (appendix of the book), eq. (9).

    Examples
    --------
    >>> import sympy as sp
    >>> corr, der = corrected_gnss_ground_coefficients(), derived_gnss_ground_coefficients()
    >>> sp.simplify(corr["d'"] - der["d'"])
    0
    """
    out = printed_gnss_ground_coefficients(corrected_gnss_vector_partials())
    Xst, Yst, Zst = _gnss_image_space()
    out["d'"] = (Zs - Z) * Xst * Yst / Zst ** 2
    return out


# --- Chapter 2: as-printed derivatives -----------------------------------------------------------
# The book's own partial derivatives of §2.8 (relative orientation) and §2.11 (exterior
