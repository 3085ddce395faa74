"""Collinearity of a mock-up calibration network in sympy: the Sementsov appendix (Appendix E), §2.2–§3.2.

A.V. Sementsov, PhD dissertation (SGUGiT, Novosibirsk 2019; seed ``004_ae61db45a4af28ce.txt``)
calibrates a non-metric camera on a planar target with simulated ("mock-up") images. The
adjustment behind those experiments (:func:`photolib.mockup.calibrate_network`) needs the
collinearity equations (6) (seed lines 577–579) with the interior orientation f, x₀, y₀ (in
pixels) among the unknowns, the α–ω–κ direction cosines A = R_Y(α)·R_X(ω)·R_Z(κ) (the matrix that
eq. (8) implies; the same as the GNSS-centres appendix, :func:`~photolib.derivations.gnss_rotation_symbolic`)
and, for the tripod head, the centre written by eq. (20) (lines 883–885), S_i = S₀ + A_i·l:

* :func:`mockup_collinearity_model` — F_x = x₀ − f·X*/Z* − x, F_y = y₀ − f·Y*/Z* − y with
  (X*, Y*, Z*)ᵀ = Aᵀ(P − S); unknowns f, x₀, y₀, X_S, Y_S, Z_S, α, ω, κ and the point X, Y, Z.
* :func:`mockup_tripod_model` — the same with S = S₀ + A·l; unknowns f, x₀, y₀, S₀ (3), l (3),
  α, ω, κ, X, Y, Z.

The rows of the coefficient matrix B of the correction equations are derived here by sympy
(:meth:`~photolib.derivations.model.Model.compile`); nothing is differentiated by hand.
"""

from __future__ import annotations

from functools import lru_cache

import sympy as sp

from .gnss import gnss_rotation_symbolic
from .model import Model
from .symbols import X, Xs, Y, Ys, Z, Zs, alpha, f, kappa, omega, x, x0, y, y0

__all__ = ["MOCKUP_PARAMETERS", "TRIPOD_PARAMETERS", "mockup_collinearity_terms", "mockup_collinearity_model",
           "mockup_tripod_model"]

S0_X, S0_Y, S0_Z = sp.symbols("S0_X S0_Y S0_Z", real=True)
l_X, l_Y, l_Z = sp.symbols("l_X l_Y l_Z", real=True)

MOCKUP_PARAMETERS = (f, x0, y0, Xs, Ys, Zs, alpha, omega, kappa, X, Y, Z)
"""Unknowns of :func:`mockup_collinearity_model`, in the order of the columns of B."""
TRIPOD_PARAMETERS = (f, x0, y0, S0_X, S0_Y, S0_Z, l_X, l_Y, l_Z, alpha, omega, kappa, X, Y, Z)
"""Unknowns of :func:`mockup_tripod_model`, in the order of the columns of B."""


def mockup_collinearity_terms(centre=None) -> sp.Matrix:
    """(X*, Y*, Z*)ᵀ = Aᵀ(P − S) with A = R_Y(α)·R_X(ω)·R_Z(κ), the terms of eq. (6).

    Parameters
    ----------
    centre : sequence of 3 sympy expressions, optional
        The projection centre S; default the symbols X_S, Y_S, Z_S.

    Returns
    -------
    sympy.Matrix
        3×1: X*, Y*, Z* in α, ω, κ, the centre and the point X, Y, Z.

    Raises
    ------
    InputError
        If ``centre`` is not three sympy expressions or numbers.

    References
    ----------
    Sementsov (2019), §2.2, eqs. (6)–(8), seed lines 577–595.

    Examples
    --------
    >>> from photolib.derivations import alpha, omega, kappa
    >>> t = mockup_collinearity_terms()
    >>> t[2].subs({omega: 0, kappa: 0})       # the denominator of eq. (8) with X_S = Y_S = 0, Z = 0
    -(X - X_S)*sin(alpha) + (Z - Z_S)*cos(alpha)
    """
    from ..errors import InputError
    if centre is None:
        centre = (Xs, Ys, Zs)
    try:
        S = sp.Matrix([sp.sympify(c, strict=True) for c in centre])
    except (sp.SympifyError, TypeError) as exc:
        raise InputError(f"centre must be three sympy expressions or numbers, got {centre!r}") from exc
    if S.shape != (3, 1):
        raise InputError(f"centre must have three components, got {S.shape[0]}")
    A = gnss_rotation_symbolic(alpha, omega, kappa)
    return A.T * (sp.Matrix([X, Y, Z]) - S)


def _residuals(terms):
    Xst, Yst, Zst = terms
    return (x0 - f * Xst / Zst - x, y0 - f * Yst / Zst - y)


@lru_cache(maxsize=None)
def mockup_collinearity_model() -> Model:
    """F_x = x₀ − f·X*/Z* − x, F_y = y₀ − f·Y*/Z* − y: eq. (6) with the interior orientation unknown.

    Image coordinates, f, x₀ and y₀ in pixels (x₀, y₀ from the frame centre); the target point
    and the centre in metres; A = R_Y(α)·R_X(ω)·R_Z(κ).

    Returns
    -------
    Model
        Parameters :data:`MOCKUP_PARAMETERS` (f, x₀, y₀, X_S, Y_S, Z_S, α, ω, κ, X, Y, Z);
        data x, y (the measured image point); residuals F_x, F_y.

    Raises
    ------
    InputError
        Never (no input).

    References
    ----------
    Sementsov (2019), §2.2, eq. (6), seed lines 577–579; §2.4 (mock-up images), lines 916–935.

    Examples
    --------
    >>> m = mockup_collinearity_model()
    >>> len(m.parameters), [str(d) for d in m.data]
    (12, ['x', 'y'])
    >>> res, jac = m.compile()
    >>> res(3100.0, 10.0, 10.0, 0, 0, 300.0, 0, 0, 0, 30.0, 0, 0, 320.0, 10.0).ravel().round(9).tolist()
    [0.0, 0.0]
    """
    return Model("mockup-collinearity", MOCKUP_PARAMETERS, (x, y), _residuals(mockup_collinearity_terms()))


@lru_cache(maxsize=None)
def mockup_tripod_model() -> Model:
    """Eq. (6) with the tripod-head centre of eq. (20), S = S₀ + A·l, and the interior orientation unknown.

    S₀ is the rotation point of the tripod head, l the offset of the projection centre from it in
    the image-space (camera) frame — constant for one camera–tripod system — and A the image's
    rotation, so that the centres of images turned about S₀ lie on a sphere of radius |l|.

    Returns
    -------
    Model
        Parameters :data:`TRIPOD_PARAMETERS` (f, x₀, y₀, S₀_X, S₀_Y, S₀_Z, l_X, l_Y, l_Z, α, ω,
        κ, X, Y, Z); data x, y; residuals F_x, F_y.

    Raises
    ------
    InputError
        Never (no input).

    References
    ----------
    Sementsov (2019), §2.3, eq. (20), seed lines 883–895; eq. (6), lines 577–579.

    Examples
    --------
    >>> m = mockup_tripod_model()
    >>> [str(p) for p in m.parameters[3:9]]
    ['S0_X', 'S0_Y', 'S0_Z', 'l_X', 'l_Y', 'l_Z']
    >>> res, jac = m.compile()
    >>> # l along the optical axis of a horizontal image is a shift of the centre in Z
    >>> res(3100.0, 0, 0, 0, 0, 300.0, 0, 0, 10.0, 0, 0, 0, 31.0, 0, 0, 310.0, 0.0).ravel().round(9).tolist()
    [0.0, 0.0]
    """
    A = gnss_rotation_symbolic(alpha, omega, kappa)
    S = sp.Matrix([S0_X, S0_Y, S0_Z]) + A * sp.Matrix([l_X, l_Y, l_Z])
    return Model("mockup-tripod", TRIPOD_PARAMETERS, (x, y), _residuals(mockup_collinearity_terms(S)))
