"""Lens distortion (Brown's model) in sympy: Chapter 1, §1.2, eqs. (1.2.2)–(1.2.3); Chapter 3, §3.6, eq. (3.6.2).

* :func:`distortion_model` — measured → ideal coordinates, whose Jacobian drives the Newton
  inversion in :func:`photolib.camera.apply_distortion`.
* :func:`brown_correction_terms` — Δ_x, Δ_y of (3.6.2) = (1.2.2) for the self-calibration model.
* :func:`printed_brown_3_6_2` — (3.6.2) exactly as printed.
"""

from __future__ import annotations

from functools import lru_cache

import sympy as sp

from ..errors import InputError
from .model import Model
from .symbols import k1, k2, k3, p1, p2, x, x0, y, y0

__all__ = ["distortion_model", "brown_correction_terms", "printed_brown_3_6_2"]


@lru_cache(maxsize=None)
def distortion_model() -> Model:
    """Measured → ideal coordinates x + d_x, y + d_y of (1.2.2)/(1.2.3); unknowns the measured x, y.

    Its Jacobian (the 2×2 matrix I + ∂d/∂x) drives the Newton inversion in
    :func:`photolib.camera.apply_distortion`.

    Returns
    -------
    Model
        Parameters x, y; data x₀, y₀, k₁, k₂, k₃, p₁, p₂.

    Raises
    ------
    InputError
        Never (no input).

    References
    ----------
    Chibunichev (2022), §1.2, eqs. (1.2.2)–(1.2.3).

    Examples
    --------
    >>> res, jac = distortion_model().compile()
    >>> res(1.0, 0.0, 0, 0, 0.1, 0, 0, 0, 0).ravel().tolist()   # x + k₁r²x
    [1.1, 0.0]
    """
    xb, yb = x - x0, y - y0
    r2 = xb ** 2 + yb ** 2
    radial = k1 * r2 + k2 * r2 ** 2 + k3 * r2 ** 3
    d_x = xb * radial + (r2 + 2 * xb ** 2) * p1 + 2 * xb * yb * p2
    d_y = yb * radial + 2 * xb * yb * p1 + (r2 + 2 * yb ** 2) * p2
    return Model("brown-correction", (x, y), (x0, y0, k1, k2, k3, p1, p2), (x + d_x, y + d_y))


def brown_correction_terms(xb, yb):
    """Δ_x, Δ_y of (3.6.2) = (1.2.2) for coordinates xb, yb (reduced to the principal point).

    Parameters
    ----------
    xb, yb : sympy.Expr or number
        Image coordinates reduced to the principal point.

    Returns
    -------
    tuple of sympy.Expr
        ``(Δ_x, Δ_y)`` in the symbols k₁, k₂, k₃, p₁, p₂.

    Raises
    ------
    InputError
        If a coordinate is not a sympy expression or a number.

    References
    ----------
    Chibunichev (2022), §3.6, eq. (3.6.2); §1.2, eq. (1.2.2).

    Examples
    --------
    >>> brown_correction_terms(1, 0)
    (k_1 + k_2 + k_3 + 3*p_1, p_2)
    """
    try:
        xb, yb = sp.sympify(xb, strict=True), sp.sympify(yb, strict=True)
    except (sp.SympifyError, TypeError) as exc:
        raise InputError(f"xb, yb must be sympy expressions or numbers: {exc}") from exc
    r2 = xb ** 2 + yb ** 2
    radial = k1 * r2 + k2 * r2 ** 2 + k3 * r2 ** 3
    return (xb * radial + (r2 + 2 * xb ** 2) * p1 + 2 * xb * yb * p2,
            yb * radial + 2 * xb * yb * p1 + (r2 + 2 * yb ** 2) * p2)


def printed_brown_3_6_2():
    """(Δ_x, Δ_y) of (3.6.2) exactly as printed: r = √(x² + y²), p₁(y² + 3x²), p₂(x² + 3y²).

    Returns
    -------
    tuple of sympy.Expr
        ``(Δ_x, Δ_y)`` in the symbols x, y, k₁, k₂, k₃, p₁, p₂.

    Raises
    ------
    InputError
        Never (no input).

    References
    ----------
    Chibunichev (2022), §3.6, eq. (3.6.2).

    Examples
    --------
    >>> import sympy as sp
    >>> dx, dy = printed_brown_3_6_2()
    >>> sp.expand(dx - brown_correction_terms(x, y)[0])
    0
    """
    r = sp.sqrt(x ** 2 + y ** 2)
    radial = k1 * r ** 2 + k2 * r ** 4 + k3 * r ** 6
    return (x * radial + p1 * (y ** 2 + 3 * x ** 2) + 2 * p2 * x * y,
            y * radial + (2 * p1 * x * y + p2 * (x ** 2 + 3 * y ** 2)))
