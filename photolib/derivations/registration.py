"""Scan registration in sympy: Chapter 9, §9.5–9.6, eq. (9.5.1).

* :func:`rigid_model` — the six-element transformation (9.5.1) scanner → object *without scale*
  written as the residuals φ = (X, Y, Z)ᵀ − (X₀, Y₀, Z₀)ᵀ − A(ω, α, κ)(X′, Y′, Z′)ᵀ of one target;
  its Jacobian by (X₀, Y₀, Z₀, ω, α, κ) gives the correction equations of §9.5 and, for the
  joint adjustment of several stations (§9.6), the columns of each station; the columns of the
  target's object coordinates there are +E (∂φ/∂X = E).
* :func:`rigid_transform_symbolic` — the right-hand side of (9.5.1) itself, for the book checks.

The model is the similarity transformation of §2.11 (:func:`photolib.derivations.similarity_model`)
with the scale fixed at t = 1: a terrestrial scanner measures ranges, so the model already has
metric scale. Parameter order: (X₀, Y₀, Z₀, ω, α, κ).
"""

from __future__ import annotations

from functools import lru_cache

import sympy as sp

from .model import Model
from .rotation import rotation_matrix_symbolic
from .symbols import X, X0, Y, Y0, Z, Z0, alpha, kappa, omega

__all__ = ["SCANNER_SYMBOLS", "rigid_transform_symbolic", "rigid_model"]

Xp, Yp, Zp = sp.symbols("X' Y' Z'", real=True)
SCANNER_SYMBOLS = (Xp, Yp, Zp)
"""Scanner (model) coordinates X′, Y′, Z′ of a point in the frame SX′Y′Z′ of (9.5.1)."""


def rigid_transform_symbolic(order: str = "kaw") -> sp.Matrix:
    """(X, Y, Z)ᵀ of (9.5.1): (X₀, Y₀, Z₀)ᵀ + A(ω, α, κ)·(X′, Y′, Z′)ᵀ in sympy.

    Parameters
    ----------
    order : {"kaw", "wak"}, optional
        Rotation sequence of A.

    Returns
    -------
    sympy.Matrix
        3×1, the object coordinates of the point.

    Raises
    ------
    InputError
        If ``order`` is unknown.

    References
    ----------
    Chibunichev (2022), §9.5, eq. (9.5.1).

    Examples
    --------
    >>> import sympy as sp
    >>> from photolib.derivations.symbols import omega, alpha, kappa
    >>> R = rigid_transform_symbolic("wak").subs({omega: 0, alpha: 0, kappa: 0})
    >>> list(R)
    [X' + X_0, Y' + Y_0, Z' + Z_0]
    """
    A = rotation_matrix_symbolic(order, omega, alpha, kappa)
    return sp.Matrix([X0, Y0, Z0]) + A * sp.Matrix(SCANNER_SYMBOLS)


@lru_cache(maxsize=None)
def rigid_model(order: str = "kaw") -> Model:
    """φ = (X, Y, Z)ᵀ − (9.5.1): the residuals of one target for the six elements of a scan.

    Parameters
    ----------
    order : {"kaw", "wak"}, optional
        Rotation sequence of A.

    Returns
    -------
    Model
        Parameters X₀, Y₀, Z₀, ω, α, κ; data X′, Y′, Z′ (scanner) and X, Y, Z (object) of a
        target.

    Raises
    ------
    InputError
        If ``order`` is unknown.

    References
    ----------
    Chibunichev (2022), §9.5, eq. (9.5.1); §9.6 (the same equations for tie targets).

    Examples
    --------
    >>> res, jac = rigid_model("kaw").compile()
    >>> res(1.0, 2.0, 3.0, 0, 0, 0, 1.0, 1.0, 1.0, 2.0, 3.0, 4.0).ravel().tolist()
    [0.0, 0.0, 0.0]
    """
    phi = sp.Matrix([X, Y, Z]) - rigid_transform_symbolic(order)
    return Model(f"rigid-{order}", (X0, Y0, Z0, omega, alpha, kappa), (Xp, Yp, Zp, X, Y, Z), tuple(phi))
