"""The planar-target theory of A.V. Sementsov's thesis in sympy — appendix to Chapter 11 (§11.3).

Seed ``004_ae61db45a4af28ce.txt`` (PhD thesis, SGUGiT 2019); equation numbers are the thesis's.
Printed forms (``printed_*``) are transcribed from the seed; derived forms (``derived_*``) are built
from the collinearity equations (6) with the α–ω–κ matrix A = R_Y(α)·R_X(ω)·R_Z(κ)
(:func:`photolib.derivations.gnss.gnss_rotation_symbolic`, the same matrix as the GNSS appendix):

* (6) collinearity, (8) its tilted-plane case (7), (9) the transformed bundle;
* the cross-multiplied identities (lines 607–614) and their expansion (10), the coefficient
  equations (11) (matching the powers of X and Y);
* the solution (12)–(16) as a substitution, the centre shift of line 734;
* the locus of the centres (18): printed (centre +Z_S cot α) and corrected (−Z_S cot α);
* the AP models (2) (orthogonal 12-parameter set; printed with ``b_4``, corrected with c₄) and its
  Gram matrix on the 3 × 3 grid, (3) Brown's model and (4) the PHOTOMOD model.

The numeric code is :mod:`photolib.planar_target` and :mod:`photolib.additional_parameters`.
Every function returns sympy objects and caches them; nothing is lambdified at import time.
"""

from __future__ import annotations

from functools import lru_cache

import sympy as sp

from ..errors import InputError
from .gnss import gnss_rotation_symbolic
from .symbols import X, Y, Z, Xs, Ys, Zs, alpha, f, kappa, omega, x, y

__all__ = ["K", "ALPHA_P", "DX0", "DY0", "DXS", "DYS", "ZSP", "B_GRID", "DIRECTION_COSINES",
           "printed_collinearity_6", "derived_collinearity_6", "printed_tilted_plane_8", "derived_tilted_plane_8",
           "printed_transformed_bundle_9", "derived_transformed_bundle_9", "printed_cross_multiplied",
           "printed_expansion_10", "derived_identity", "printed_coefficient_equations_11",
           "derived_coefficient_equations", "printed_solution", "solution_substitution", "printed_centre_shift_734",
           "derived_centre_shift", "printed_centre_locus", "corrected_centre_locus", "ebner12_symbolic",
           "ebner12_gram", "brown_symbolic", "photomod_symbolic"]

K = sp.Symbol("k", positive=True)
"""k, the coefficient of the transformed bundle (f → k f)."""
ALPHA_P = sp.Symbol("alpha'", real=True)
"""α′, the tilt of the transformed bundle."""
DX0, DY0 = sp.symbols("delta_x0 delta_y0", real=True)
"""δx₀, δy₀: the decentration (shift of the principal point)."""
DXS, DYS = sp.symbols("delta_X_S delta_Y_S", real=True)
"""δX_S, δY_S: the shift of the projection centre."""
ZSP = sp.Symbol("Z'_S", real=True)
"""Z′_S: the height of the transformed centre."""
B_GRID = sp.Symbol("b", positive=True)
"""b: the spacing of the 3 × 3 grid of standard points of (2)."""
DIRECTION_COSINES = sp.symbols("a_1 a_2 a_3 b_1 b_2 b_3 c_1 c_2 c_3", real=True)
"""a₁, a₂, a₃, b₁, b₂, b₃, c₁, c₂, c₃ of (6), generic."""

_sa, _ca, _sp, _cp = sp.sin(alpha), sp.cos(alpha), sp.sin(ALPHA_P), sp.cos(ALPHA_P)


def _flag(value, name):
    if not isinstance(value, bool):
        raise InputError(f"{name} must be True or False, got {value!r}")
    return value


# --- (6), (8), (9) ---------------------------------------------------------------------------------------
@lru_cache(maxsize=None)
def printed_collinearity_6() -> sp.Matrix:
    """(6) as printed (lines 577–579): x − x₀ and y − y₀ with generic direction cosines a₁ … c₃.

    Returns
    -------
    sympy.Matrix
        2 × 1: (x − x₀, y − y₀) = (−f)·((X−X_S)a₁ + (Y−Y_S)b₁ + (Z−Z_S)c₁)/(…a₃ + …b₃ + …c₃), …

    Raises
    ------
    InputError
        Never (no input).

    References
    ----------
    Sementsov (2019), eq. (6), lines 577–587.

    Examples
    --------
    >>> printed_collinearity_6().shape
    (2, 1)
    """
    a1, a2, a3, b1, b2, b3, c1, c2, c3 = DIRECTION_COSINES
    dX, dY, dZ = X - Xs, Y - Ys, Z - Zs
    den = dX * a3 + dY * b3 + dZ * c3
    return sp.Matrix([(-f) * (dX * a1 + dY * b1 + dZ * c1) / den, (-f) * (dX * a2 + dY * b2 + dZ * c2) / den])


def derived_collinearity_6(a=alpha, w=omega, k=kappa) -> sp.Matrix:
    """(6) derived: (x − x₀, y − y₀, −f) ∥ Aᵀ(P − S) with A = R_Y(α)·R_X(ω)·R_Z(κ).

    Parameters
    ----------
    a, w, k : sympy.Expr, optional
        The angles α, ω, κ (default the symbols alpha, omega, kappa).

    Returns
    -------
    sympy.Matrix
        2 × 1: x − x₀, y − y₀.

    Raises
    ------
    InputError
        An angle that is not a sympy expression or number.

    References
    ----------
    Sementsov (2019), eq. (6), lines 577–587; the matrix of :func:`photolib.derivations.gnss.gnss_rotation_symbolic`.

    Examples
    --------
    >>> derived_collinearity_6(0, 0, 0)[0]
    -f*(X - X_S)/(Z - Z_S)
    """
    A = gnss_rotation_symbolic(a, w, k)
    q = A.T * sp.Matrix([X - Xs, Y - Ys, Z - Zs])
    return sp.Matrix([-f * q[0] / q[2], -f * q[1] / q[2]])


@lru_cache(maxsize=None)
def printed_tilted_plane_8() -> sp.Matrix:
    """(8) as printed (lines 593–595): (6) for X_S = Y_S = 0, Z = 0, ω = κ = 0, α ≠ 0 (7).

    Returns
    -------
    sympy.Matrix
        2 × 1: x − x₀ = (−f)(X cos α − Z_S sin α)/(−X sin α − Z_S cos α), y − y₀ = (−f) Y/(…).

    Raises
    ------
    InputError
        Never (no input).

    References
    ----------
    Sementsov (2019), eqs. (7)–(8), lines 589–595.

    Examples
    --------
    A horizontal image (α = 0) is the plain central projection x − x₀ = f X/Z_S:

    >>> sp.simplify(printed_tilted_plane_8().subs(alpha, 0)[0])
    X*f/Z_S
    """
    den = -X * _sa - Zs * _ca
    return sp.Matrix([(-f) * (X * _ca - Zs * _sa) / den, (-f) * Y / den])


@lru_cache(maxsize=None)
def derived_tilted_plane_8() -> sp.Matrix:
    """(8) derived: :func:`derived_collinearity_6` with the configuration (7).

    Returns
    -------
    sympy.Matrix
        2 × 1: x − x₀, y − y₀.

    Raises
    ------
    InputError
        Never (no input).

    References
    ----------
    Sementsov (2019), eqs. (6)–(8), lines 577–595.

    Examples
    --------
    >>> import sympy as sp
    >>> sp.simplify(derived_tilted_plane_8() - printed_tilted_plane_8()) == sp.zeros(2, 1)
    True
    """
    return derived_collinearity_6(alpha, 0, 0).subs({Xs: 0, Ys: 0, Z: 0})


@lru_cache(maxsize=None)
def printed_transformed_bundle_9() -> sp.Matrix:
    """(9) as printed (lines 597–599): x − x₀ − δx₀ and y − y₀ − δy₀ of the transformed bundle.

    Returns
    -------
    sympy.Matrix
        2 × 1: k(−f)(X cos α′ − δX_S cos α′ − Z′_S sin α′)/(−X sin α′ + δX_S sin α′ − Z′_S cos α′),
        k(−f)(Y − δY_S)/(…).

    Raises
    ------
    InputError
        Never (no input).

    References
    ----------
    Sementsov (2019), eq. (9), lines 597–599.

    Examples
    --------
    With k = 1 and nothing shifted it is (8):

    >>> printed_transformed_bundle_9().subs({K: 1, ALPHA_P: alpha, DXS: 0, DYS: 0, ZSP: Zs}) == printed_tilted_plane_8()
    True
    """
    den = -X * _sp + DXS * _sp - ZSP * _cp
    return sp.Matrix([K * (-f) * (X * _cp - DXS * _cp - ZSP * _sp) / den, K * (-f) * (Y - DYS) / den])


@lru_cache(maxsize=None)
def derived_transformed_bundle_9() -> sp.Matrix:
    """(9) derived: (6) with f → k f, α → α′, ω = κ = 0, centre (δX_S, δY_S, Z′_S), plane Z = 0.

    Returns
    -------
    sympy.Matrix
        2 × 1: x − x₀ − δx₀, y − y₀ − δy₀.

    Raises
    ------
    InputError
        Never (no input).

    References
    ----------
    Sementsov (2019), eqs. (6), (9), lines 577–599.

    Examples
    --------
    >>> import sympy as sp
    >>> sp.simplify(derived_transformed_bundle_9() - printed_transformed_bundle_9()) == sp.zeros(2, 1)
    True
    """
    return (K * derived_collinearity_6(ALPHA_P, 0, 0)).subs({Xs: DXS, Ys: DYS, Zs: ZSP, Z: 0}, simultaneous=True)


# --- the identities (10) and the coefficient equations (11) ---------------------------------------------------
def _parts():
    N = X * _ca - Zs * _sa
    D = -X * _sa - Zs * _ca
    Np = X * _cp - DXS * _cp - ZSP * _sp
    Dp = -X * _sp + DXS * _sp - ZSP * _cp
    return N, D, Np, Dp


@lru_cache(maxsize=None)
def printed_cross_multiplied() -> tuple:
    """The cross-multiplied equalities of lines 607–614, as printed (each "left − right").

    Returns
    -------
    tuple of sympy.Expr
        (x-equation, y-equation).

    Raises
    ------
    InputError
        Never (no input).

    References
    ----------
    Sementsov (2019), lines 601–614.

    Examples
    --------
    >>> len(printed_cross_multiplied())
    2
    """
    N, D, Np, Dp = _parts()
    ex = N * Dp - DX0 / (-f) * D * Dp - K * D * Np
    ey = Y * Dp - DY0 / (-f) * D * Dp - K * D * (Y - DYS)
    return ex, ey


@lru_cache(maxsize=None)
def printed_expansion_10() -> tuple:
    """The expanded identities (10) as printed, term by term (lines 618–629), each "left − right".

    Returns
    -------
    tuple of sympy.Expr
        (x-equation, y-equation).

    Raises
    ------
    InputError
        Never (no input).

    References
    ----------
    Sementsov (2019), eq. (10), lines 616–629.

    Examples
    --------
    >>> import sympy as sp
    >>> [sp.expand(p - d) for p, d in zip(printed_expansion_10(), derived_identity())]
    [0, 0]
    """
    sa, ca, sp_, cp = _sa, _ca, _sp, _cp
    q, qy = DX0 / f, DY0 / f
    left_x = (-X**2 * ca * sp_ + X * DXS * ca * sp_ - X * ZSP * ca * cp + X * Zs * sa * sp_
              - Zs * DXS * sa * sp_ + Zs * ZSP * sa * cp + q * X**2 * sa * sp_
              - q * X * DXS * sa * sp_ + q * X * ZSP * sa * cp + q * X * Zs * ca * sp_
              - q * Zs * DXS * ca * sp_ + q * Zs * ZSP * ca * cp)
    right_x = (-K * X**2 * sa * cp + K * X * DXS * sa * cp + K * X * ZSP * sa * sp_
               - K * X * Zs * ca * cp + K * Zs * DXS * ca * cp + K * Zs * ZSP * ca * sp_)
    left_y = (-X * Y * sp_ + Y * DXS * sp_ - Y * ZSP * cp + qy * X**2 * sa * sp_
              - qy * X * DXS * sa * sp_ + qy * X * ZSP * sa * cp + qy * X * Zs * ca * sp_
              - qy * Zs * DXS * ca * sp_ + qy * Zs * ZSP * ca * cp)
    right_y = -K * X * Y * sa + K * X * DYS * sa - K * Zs * Y * ca + K * Zs * DYS * ca
    return left_x - right_x, left_y - right_y


@lru_cache(maxsize=None)
def derived_identity() -> tuple:
    """(8) = (9) brought to polynomials in X, Y: ((8) − (9))·D·D′/(−f), with D, D′ the denominators.

    Returns
    -------
    tuple of sympy.Expr
        (x-equation, y-equation), expanded.

    Raises
    ------
    InputError
        Never (no input).

    References
    ----------
    Sementsov (2019), eqs. (8)–(10), lines 593–629.

    Examples
    --------
    >>> import sympy as sp
    >>> sp.Poly(derived_identity()[0], X, Y).degree()
    2
    """
    N, D, Np, Dp = _parts()
    e8, e9 = derived_tilted_plane_8(), derived_transformed_bundle_9()
    out = []
    for i, shift in enumerate((DX0, DY0)):
        diff = e8[i] - (e9[i] + shift)                      # (x − x₀) of (8) minus (x − x₀) of (9)
        out.append(sp.expand(sp.cancel(sp.together(diff * D * Dp / (-f)))))
    return tuple(out)


_MONOMIALS = {"x": ("X^2", "X", "1"), "y": ("X^2", "XY", "X", "Y", "1")}


def _monomial(name):
    return {"X^2": X**2, "XY": X * Y, "X": X, "Y": Y, "1": sp.Integer(1)}[name]


@lru_cache(maxsize=None)
def printed_coefficient_equations_11() -> dict:
    """The coefficient equations (11) as printed (lines 651–667), each "left − right".

    Returns
    -------
    dict
        ``{("x", "X^2"): …, ("x", "X"): …, ("x", "1"): …, ("y", "X^2"): …, ("y", "XY"): …,
        ("y", "X"): …, ("y", "Y"): …, ("y", "1"): …}``.

    Raises
    ------
    InputError
        Never (no input).

    References
    ----------
    Sementsov (2019), eq. (11), lines 631–667.

    Examples
    --------
    >>> printed_coefficient_equations_11()[("y", "XY")]
    k*sin(alpha) - sin(alpha')
    """
    sa, ca, sp_, cp = _sa, _ca, _sp, _cp
    q, qy = DX0 / f, DY0 / f
    return {
        ("x", "X^2"): (-ca * sp_ + q * sa * sp_) - (-K * sa * cp),
        ("x", "X"): (DXS * ca * sp_ - ZSP * ca * cp + Zs * sa * sp_ - q * DXS * sa * sp_ + q * ZSP * sa * cp
                     + q * Zs * ca * sp_) - (K * DXS * sa * cp + K * ZSP * sa * sp_ - K * Zs * ca * cp),
        ("x", "1"): (-Zs * DXS * sa * sp_ + Zs * ZSP * sa * cp - q * Zs * DXS * ca * sp_ + q * Zs * ZSP * ca * cp)
        - (K * Zs * DXS * ca * cp + K * Zs * ZSP * ca * sp_),
        ("y", "X^2"): qy * sa * sp_,
        ("y", "XY"): -sp_ - (-K * sa),
        ("y", "X"): (-qy * DXS * sa * sp_ + qy * ZSP * sa * cp + qy * Zs * ca * sp_) - K * DYS * sa,
        ("y", "Y"): (DXS * sp_ - ZSP * cp) - (-K * Zs * ca),
        ("y", "1"): (-qy * Zs * DXS * ca * sp_ + qy * Zs * ZSP * ca * cp) - K * Zs * DYS * ca,
    }


@lru_cache(maxsize=None)
def derived_coefficient_equations() -> dict:
    """The coefficients of the monomials of :func:`derived_identity` (the method of undetermined coefficients).

    Returns
    -------
    dict
        Same keys as :func:`printed_coefficient_equations_11`, plus ``("x", "other")`` and
        ``("y", "other")``: what is left of the polynomial outside those monomials (0).

    Raises
    ------
    InputError
        Never (no input).

    References
    ----------
    Sementsov (2019), eqs. (10)–(11), lines 616–667.

    Examples
    --------
    >>> derived_coefficient_equations()[("y", "other")]
    0
    """
    out = {}
    for eq, expr in zip(("x", "y"), derived_identity()):
        poly = sp.Poly(expr, X, Y)
        rest = expr
        for m in _MONOMIALS[eq]:
            c = poly.coeff_monomial(_monomial(m))
            out[(eq, m)] = sp.expand(c)
            rest = rest - c * _monomial(m)
        out[(eq, "other")] = sp.expand(rest)
    return out


# --- the solution (12)–(17) ----------------------------------------------------------------------------------
@lru_cache(maxsize=None)
def printed_solution() -> dict:
    """(12)–(16) as printed (lines 675–701), each "left − right".

    Returns
    -------
    dict
        ``{"12": sin α′ − k sin α, "13": k δy₀/f sin²α, "14": δx₀/f − (cos α − cos α′)/sin α,
        "15": Z′_S − k Z_S, "16": δX_S + δx₀ Z_S/f}``.

    Raises
    ------
    InputError
        Never (no input).

    References
    ----------
    Sementsov (2019), eqs. (12)–(16), lines 669–703.

    Examples
    --------
    >>> printed_solution()["15"]
    Z'_S - Z_S*k
    """
    return {"12": _sp - K * _sa, "13": K * DY0 / f * _sa**2, "14": DX0 / f - (_ca - _cp) / _sa,
            "15": ZSP - K * Zs, "16": DXS + DX0 * Zs / f}


def solution_substitution(sign_16: int = -1) -> dict:
    """(12)–(16) with δy₀ = δY_S = 0 as a substitution {symbol: value}, k eliminated by (12).

    k = sin α′/sin α (12), δx₀ = f(cos α − cos α′)/sin α (14), Z′_S = k Z_S (15),
    δX_S = sign_16·δx₀·Z_S/f (16; the printed sign is −1), δy₀ = δY_S = 0 ((13), (17)).

    Parameters
    ----------
    sign_16 : {-1, 1}
        The sign of (16): −1 as printed, +1 the horizontal-case relation (for the check that it fails).

    Returns
    -------
    dict
        Substitution for K, DX0, DY0, DXS, DYS, ZSP.

    Raises
    ------
    InputError
        ``sign_16`` not ±1.

    References
    ----------
    Sementsov (2019), eqs. (12)–(17), lines 669–721.

    Examples
    --------
    >>> solution_substitution()[DY0]
    0
    """
    if isinstance(sign_16, bool) or sign_16 not in (-1, 1):
        raise InputError(f"sign_16 must be -1 or 1, got {sign_16!r}")
    k = _sp / _sa
    dx0 = f * (_ca - _cp) / _sa
    return {K: k, DX0: dx0, DY0: sp.Integer(0), DYS: sp.Integer(0), ZSP: k * Zs, DXS: sign_16 * dx0 * Zs / f}


@lru_cache(maxsize=None)
def printed_centre_shift_734() -> sp.Expr:
    """δX_S as a function of k, as printed at line 734: Z_S(√(1 − k² sin²α) − cos α)/sin α.

    Returns
    -------
    sympy.Expr

    Raises
    ------
    InputError
        Never (no input).

    References
    ----------
    Sementsov (2019), line 734.

    Examples
    --------
    >>> printed_centre_shift_734().subs(K, 1).simplify()
    Z_S*(-cos(alpha) + Abs(cos(alpha)))/sin(alpha)
    """
    return (sp.sqrt(1 - K**2 * _sa**2) - _ca) / _sa * Zs


@lru_cache(maxsize=None)
def derived_centre_shift() -> sp.Expr:
    """δX_S(k) derived from (14) and (16) with cos α′ = +√(1 − sin²α′) = √(1 − k² sin²α) (|α′| ≤ 90°).

    Returns
    -------
    sympy.Expr

    Raises
    ------
    InputError
        Never (no input).

    References
    ----------
    Sementsov (2019), eqs. (12), (14), (16), line 734.

    Examples
    --------
    >>> import sympy as sp
    >>> sp.simplify(derived_centre_shift() - printed_centre_shift_734())
    0
    """
    dx0 = f * (_ca - sp.sqrt(1 - (K * _sa)**2)) / _sa
    return sp.expand(-dx0 * Zs / f)


@lru_cache(maxsize=None)
def printed_centre_locus() -> sp.Expr:
    """(18) as printed (line 754), "left − 1": (δX_S − Z_S cot α)²/(Z_S/sin α)² + Z′_S²/(Z_S/sin α)² − 1.

    Returns
    -------
    sympy.Expr

    Raises
    ------
    InputError
        Never (no input).

    References
    ----------
    Sementsov (2019), eq. (18), lines 744–756 (the sign slip enters at line 738).

    Examples
    --------
    >>> import sympy as sp
    >>> sp.simplify(printed_centre_locus().subs(solution_substitution())) == 0
    False
    """
    r = Zs / _sa
    return (DXS - Zs * _ca / _sa) ** 2 / r**2 + ZSP**2 / r**2 - 1


@lru_cache(maxsize=None)
def corrected_centre_locus() -> sp.Expr:
    """(18) corrected, "left − 1": (δX_S + Z_S cot α)²/(Z_S/sin α)² + Z′_S²/(Z_S/sin α)² − 1.

    Returns
    -------
    sympy.Expr

    Raises
    ------
    InputError
        Never (no input).

    References
    ----------
    Sementsov (2019), eq. (18), lines 730–763, corrected.

    Examples
    --------
    >>> import sympy as sp
    >>> sp.simplify(corrected_centre_locus().subs(solution_substitution()))
    0
    """
    r = Zs / _sa
    return (DXS + Zs * _ca / _sa) ** 2 / r**2 + ZSP**2 / r**2 - 1


# --- the AP models (2)–(4) ---------------------------------------------------------------------------------
def ebner12_symbolic(printed: bool = False) -> tuple:
    """The 12-parameter set (2): (σx, σy, parameters), as printed (``b_4``) or corrected (c₄).

    Parameters
    ----------
    printed : bool
        True: σy carries the printed symbol b₄ (so the set has 13 symbols); False: c₄.

    Returns
    -------
    tuple
        (σx, σy, tuple of the parameter symbols); the grid spacing is :data:`B_GRID`.

    Raises
    ------
    InputError
        ``printed`` not a bool.

    References
    ----------
    Sementsov (2019), eq. (2), lines 476–480.

    Examples
    --------
    >>> len(ebner12_symbolic()[2]), len(ebner12_symbolic(printed=True)[2])
    (12, 13)
    """
    _flag(printed, "printed")
    c = sp.symbols("c_1:13", real=True)
    b4 = sp.Symbol("b_4", real=True) if printed else c[3]
    b = B_GRID
    q = sp.Rational(2, 3) * b**2
    sx = (c[0] * x + c[1] * y - c[2] * (2 * x**2 - sp.Rational(4, 3) * b**2) + c[3] * x * y - c[4] * (y**2 - q)
          + c[6] * x * (y**2 - q) + c[8] * (x**2 - q) * y + c[10] * (x**2 - q) * (y**2 - q))
    sy = (-c[0] * y + c[1] * x + c[2] * x * y + b4 * (2 * y**2 - sp.Rational(4, 3) * b**2) + c[5] * (x**2 - q)
          + c[7] * (x**2 - q) * y + c[9] * x * (y**2 - q) + c[11] * (x**2 - q) * (y**2 - q))
    params = c + ((b4,) if printed else ())
    return sx, sy, params


def ebner12_gram(printed: bool = False) -> sp.Matrix:
    """Gram matrix of the fields of (2) over the 3 × 3 grid x, y ∈ {−b, 0, b}.

    Entry (i, j) = Σ_grid (σx_i σx_j + σy_i σy_j), σ_i the field of parameter i alone. The set is
    orthogonal when every off-diagonal entry is 0.

    Parameters
    ----------
    printed : bool
        As :func:`ebner12_symbolic`.

    Returns
    -------
    sympy.Matrix
        12 × 12 (13 × 13 as printed).

    Raises
    ------
    InputError
        ``printed`` not a bool.

    References
    ----------
    Sementsov (2019), eq. (2), lines 472–480; H. Ebner (1976).

    Examples
    --------
    >>> G = ebner12_gram()
    >>> G.is_diagonal()
    True
    """
    sx, sy, params = ebner12_symbolic(printed)
    fields = [(sp.diff(sx, p), sp.diff(sy, p)) for p in params]
    grid = [(i * B_GRID, j * B_GRID) for i in (-1, 0, 1) for j in (-1, 0, 1)]
    n = len(fields)
    G = sp.zeros(n, n)
    for i in range(n):
        for j in range(i, n):
            val = sum(((fields[i][0] * fields[j][0] + fields[i][1] * fields[j][1]).subs({x: gx, y: gy})
                       for gx, gy in grid), sp.Integer(0))
            G[i, j] = G[j, i] = sp.expand(val)
    return G


@lru_cache(maxsize=None)
def brown_symbolic() -> tuple:
    """Brown's model (3) as printed: (σx, σy, parameters) in x, y (reduced) and f.

    Returns
    -------
    tuple
        (σx, σy, (a₁…a₇, b₁…b₇, c₁…c₇, k₁, k₂, k₃, p₁, p₂)).

    Raises
    ------
    InputError
        Never (no input).

    References
    ----------
    Sementsov (2019), eq. (3), lines 482–492.

    Examples
    --------
    >>> len(brown_symbolic()[2])
    26
    """
    a = sp.symbols("a_1:8", real=True)
    b = sp.symbols("b_1:8", real=True)
    c = sp.symbols("c_1:8", real=True)
    k1, k2, k3, p1, p2 = sp.symbols("k_1 k_2 k_3 p_1 p_2", real=True)
    r2 = x**2 + y**2
    cub = c[0] * x**2 + c[1] * x * y + c[2] * y**2 + c[3] * x**3 + c[4] * x**2 * y + c[5] * x * y**2 + c[6] * y**3
    rad = k1 * r2 + k2 * r2**2 + k3 * r2**3
    sx = (a[0] * x + a[1] * y + a[2] * x**2 + a[3] * x * y + a[4] * y**2 + a[5] * x**2 * y + a[6] * x * y**2
          + x / f * cub + x * rad + p1 * (y**2 + 3 * x**2) + 2 * p2 * x * y)
    sy = (b[0] * x + b[1] * y + b[2] * x**2 + b[3] * x * y + b[4] * y**2 + b[5] * x**2 * y + b[6] * x * y**2
          + y / f * cub + y * rad + 2 * p1 * x * y + p2 * (3 * y**2 + x**2))
    return sx, sy, a + b + c + (k1, k2, k3, p1, p2)


@lru_cache(maxsize=None)
def photomod_symbolic() -> tuple:
    """The PHOTOMOD model (4) as printed (b₁, b₂ in σx, a₁, a₂ in σy): (σx, σy, parameters).

    Returns
    -------
    tuple
        (σx, σy, (k₁, k₂, k₃, P₁, P₂, a₁, a₂, b₁, b₂)).

    Raises
    ------
    InputError
        Never (no input).

    References
    ----------
    Sementsov (2019), eq. (4), lines 494–504.

    Examples
    --------
    >>> photomod_symbolic()[2][:3]
    (k_1, k_2, k_3)
    """
    k1, k2, k3, P1, P2, a1, a2, b1, b2 = sp.symbols("k_1 k_2 k_3 P_1 P_2 a_1 a_2 b_1 b_2", real=True)
    r2 = x**2 + y**2
    sx = -k1 * x * r2 - k2 * x * r2**2 - k3 * x * r2**3 - P1 * (2 * x**2 + r2) - 2 * P2 * x * y - b1 * x - b2 * y
    sy = -k1 * y * r2 - k2 * y * r2**2 - k3 * y * r2**3 - P2 * (2 * y**2 + r2) - 2 * P1 * x * y - a1 * x - a2 * y
    return sx, sy, (k1, k2, k3, P1, P2, a1, a2, b1, b2)
