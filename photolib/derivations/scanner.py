"""Scanner (pushbroom) models in sympy: Chapter 8, §8.2–8.5, §8.8.

* :func:`scanner_collinearity_model` — the unit-vector collinearity (8.5.2) of one scanner line,
  F_x = z·X*/Z* − x, F_y = z·Y*/Z* − y with (X*, Y*, Z*)ᵀ = Aᵀ(X − X_S, Y − Y_S, Z − Z_S)ᵀ and
  A = A_ω A_α A_κ of (1.3.2). Its Jacobian by the line's six elements (X_S, Y_S, Z_S, ω, α, κ)
  gives, by the chain rule, the columns of the time-polynomial resection (8.5.3)–(8.5.5): the
  column of k_j is Δt times that of element j, the column of d_j Δt² times it.
* :func:`pushbroom_polynomial_model` — the same equations with the EO written out as polynomials
  in Δt (8.5.3)/(8.5.5); used to check the chain rule (it is slow to lambdify, the library uses
  the line model).
* :func:`scanner_coplanarity_model` — the coplanarity condition (8.8.3)/(8.8.4) of case 3 of
  §8.8 with the twelve first-line elements of both images as unknowns (8.8.6). Its full sympy
  Jacobian takes seconds to derive, so the library assembles the coefficients a₁…a₁₂ of (8.8.6)
  from :func:`rotated_ray_model` (R = A·r and ∂R/∂(ω, α, κ)) by the product rule of the
  determinant: a₁…a₃ = −(R₁ × R₂), a₇…a₉ = R₁ × R₂, a₄…a₆ = B·(∂R₁/∂θ × R₂),
  a₁₀…a₁₂ = B·(R₁ × ∂R₂/∂θ); the tests check them against this model.

Parameter order everywhere: (X_S, Y_S, Z_S, ω, α, κ) — the order of (8.5.3); the book lists the
angles as (α, ω, κ) in (8.8.6), which is only the order of the list.
"""

from __future__ import annotations

from functools import lru_cache

import sympy as sp

from ..errors import InputError
from .model import Model
from .rotation import rotation_matrix_symbolic
from .symbols import EO_SYMBOLS, X, Xs, Y, Ys, Z, Zs, alpha, kappa, omega

__all__ = ["scanner_collinearity_model", "pushbroom_polynomial_model", "scanner_coplanarity_model",
           "rotated_ray_model", "POLY_SYMBOLS", "RAY_SYMBOLS"]

# unit ray (x, y, z) of (8.2.2)/(8.3.1)/(8.4.2)/(8.4.3) and the line time Δt of (8.5.4)
_rx, _ry, _rz = sp.symbols("r_x r_y r_z", real=True)
RAY_SYMBOLS = (_rx, _ry, _rz)
"""The unit ray (x, y, z) of (8.2.2) in the scanner frame (names r_x, r_y, r_z)."""

_dt = sp.Symbol("Delta_t", real=True)
_k = sp.symbols("k_1:7", real=True)
_d = sp.symbols("d_1:7", real=True)
POLY_SYMBOLS = EO_SYMBOLS + _k + _d
"""X_S0, Y_S0, Z_S0, ω0, α0, κ0, k₁…k₆, d₁…d₆ of (8.5.3)/(8.5.5) (the first six are the EO symbols)."""

_coplanar = sp.symbols("X_S10 Y_S10 Z_S10 omega_10 alpha_10 kappa_10 X_S20 Y_S20 Z_S20 omega_20 alpha_20 kappa_20",
                       real=True)
_increments = sp.symbols("dX_1 dY_1 dZ_1 dX_2 dY_2 dZ_2", real=True)
_rays2 = sp.symbols("x_1 y_1 z_1 x_2 y_2 z_2", real=True)


def _collinearity(S, angles):
    A = rotation_matrix_symbolic("wak", *angles)
    Xst, Yst, Zst = A.T * sp.Matrix([X - S[0], Y - S[1], Z - S[2]])
    return (_rz * Xst / Zst - _rx, _rz * Yst / Zst - _ry)


@lru_cache(maxsize=None)
def scanner_collinearity_model() -> Model:
    """F_x = z X*/Z* − x, F_y = z Y*/Z* − y — the inverse rigorous model (8.5.2) of one line.

    Returns
    -------
    Model
        Parameters X_S, Y_S, Z_S, ω, α, κ (the EO of the line, A = A_ω A_α A_κ of (1.3.2));
        data X, Y, Z (object point) and r_x, r_y, r_z (the unit ray (8.2.2) in the scanner frame).

    Raises
    ------
    InputError
        Never (no input).

    References
    ----------
    Chibunichev (2022), §8.5, eq. (8.5.2); §8.8, eqs. (8.8.5), (8.8.7); §1.3, eq. (1.3.2).

    Examples
    --------
    >>> m = scanner_collinearity_model()
    >>> [str(s) for s in m.parameters]
    ['X_S', 'Y_S', 'Z_S', 'omega', 'alpha', 'kappa']
    >>> res, jac = m.compile()
    >>> res(0, 0, 1000, 0, 0, 0, 0, 100, 0, 0, 0.0995037, -0.995037).round(6).ravel().tolist()
    [0.0, 0.0]
    """
    return Model("scanner-collinearity-wak", EO_SYMBOLS, (X, Y, Z) + RAY_SYMBOLS,
                 _collinearity((Xs, Ys, Zs), (omega, alpha, kappa)))


@lru_cache(maxsize=None)
def pushbroom_polynomial_model(degree: int = 1) -> Model:
    """(8.5.2) with the EO as polynomials in Δt: linear (8.5.3) or quadratic (8.5.5).

    Parameters
    ----------
    degree : {1, 2}
        1: 12 unknowns X_S0 … κ0, k₁ … k₆; 2: 18 unknowns (also d₁ … d₆).

    Returns
    -------
    Model
        Parameters in the order X_S0, Y_S0, Z_S0, ω0, α0, κ0, k₁…k₆[, d₁…d₆]; data X, Y, Z,
        r_x, r_y, r_z, Δt.

    Raises
    ------
    InputError
        A degree other than 1 or 2.

    References
    ----------
    Chibunichev (2022), §8.5, eqs. (8.5.2)–(8.5.5).

    Examples
    --------
    >>> len(pushbroom_polynomial_model(1).parameters), len(pushbroom_polynomial_model(2).parameters)
    (12, 18)
    """
    if isinstance(degree, bool) or degree not in (1, 2):
        raise InputError(f"degree must be 1 (linear, (8.5.3)) or 2 (quadratic, (8.5.5)), got {degree!r}")
    e = [p + kk * _dt + (dd * _dt ** 2 if degree == 2 else 0)
         for p, kk, dd in zip(EO_SYMBOLS, _k, _d)]
    params = POLY_SYMBOLS[:12] if degree == 1 else POLY_SYMBOLS
    return Model(f"pushbroom-poly{degree}-wak", params, (X, Y, Z) + RAY_SYMBOLS + (_dt,),
                 _collinearity(e[:3], e[3:]))


@lru_cache(maxsize=None)
def scanner_coplanarity_model() -> Model:
    """The coplanarity determinant (8.8.3) with (8.8.4): B·(A₁r₁ × A₂r₂) = 0, B = S₂ⱼ − S₁ⱼ.

    S_ij = S_i0 + ΔS_ij; r_ij are the rays already turned into the first-line frame by (8.8.2).

    Returns
    -------
    Model
        Parameters X_S10, Y_S10, Z_S10, ω10, α10, κ10, X_S20, …, κ20 (the twelve unknowns of
        (8.8.6)); data ΔX₁, ΔY₁, ΔZ₁, ΔX₂, ΔY₂, ΔZ₂, x₁, y₁, z₁, x₂, y₂, z₂.

    Raises
    ------
    InputError
        Never (no input).

    References
    ----------
    Chibunichev (2022), §8.8, eqs. (8.8.2)–(8.8.4), (8.8.6).

    Examples
    --------
    >>> m = scanner_coplanarity_model()
    >>> len(m.parameters), len(m.data)
    (12, 12)
    """
    p = _coplanar
    S1 = sp.Matrix(p[0:3]) + sp.Matrix(_increments[0:3])
    S2 = sp.Matrix(p[6:9]) + sp.Matrix(_increments[3:6])
    R1 = rotation_matrix_symbolic("wak", *p[3:6]) * sp.Matrix(_rays2[0:3])
    R2 = rotation_matrix_symbolic("wak", *p[9:12]) * sp.Matrix(_rays2[3:6])
    det = sp.Matrix.hstack(S2 - S1, R1, R2).T.det(method="berkowitz")
    return Model("scanner-coplanarity-wak", p, _increments + _rays2, (det,))


@lru_cache(maxsize=None)
def rotated_ray_model() -> Model:
    """R = A·r — a scanner ray turned into the object frame, (X′, Y′, Z′) of (8.5.1)/(8.8.4).

    Returns
    -------
    Model
        Parameters ω, α, κ (A = A_ω A_α A_κ of (1.3.2)); data r_x, r_y, r_z; residuals X′, Y′, Z′.
        Its Jacobian (3 × 3) gives the angular coefficients of the coplanarity equations (8.8.6).

    Raises
    ------
    InputError
        Never (no input).

    References
    ----------
    Chibunichev (2022), §8.5, eq. (8.5.1); §8.8, eqs. (8.8.4), (8.8.6); §1.3, eq. (1.3.2).

    Examples
    --------
    >>> res, jac = rotated_ray_model().compile()
    >>> res(0.0, 0.0, 0.0, 0.0, 0.0, -1.0).ravel().tolist()
    [0.0, 0.0, -1.0]
    """
    R = rotation_matrix_symbolic("wak", omega, alpha, kappa) * sp.Matrix(RAY_SYMBOLS)
    return Model("scanner-rotated-ray-wak", (omega, alpha, kappa), RAY_SYMBOLS, tuple(R))
