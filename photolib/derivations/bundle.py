"""The bundle method and its extensions: Chapter 3, §3.5 (bundle adjustment), §3.6 (self-calibration),
§3.8 (camera rigs), §3.9 (rolling shutter). Used by :mod:`photolib.bundle` through the printed
code of ``photolib/_bundle_generated.py`` (see :func:`photolib.derivations.numpy_source`).
"""

from __future__ import annotations

from functools import lru_cache

import sympy as sp

from .collinearity import collinearity_terms
from .distortion import brown_correction_terms
from .model import Model
from .rotation import rotation_matrix_symbolic
from .symbols import (B_X, B_Y, B_Z, EO_SYMBOLS, IO_SYMBOLS, MOUNT_SYMBOLS, RATE_SYMBOLS, X, Xs, Y, Ys, Z, Zs,
                      alpha_2p, f, kappa_2p, omega_2p, x, x0, y, y0)

__all__ = ["bundle_collinearity_model", "self_calibration_model", "rig_collinearity_model",
           "printed_rig_3_8_13", "derived_rig_image_coordinates", "rolling_shutter_model"]


@lru_cache(maxsize=None)
def bundle_collinearity_model(order: str = "kaw") -> Model:
    """(3.5.1) with unknown exterior orientation **and** unknown object point — the bundle model.

    F_x = x₀ − f x*/z* − x,  F_y = y₀ − f y*/z* − y,  (x*, y*, z*)ᵀ = Aᵀ(X − X_S, Y − Y_S, Z − Z_S)ᵀ.
    Dropping the last three columns of the Jacobian gives (3.5.3) (fixed control point),
    dropping the first six gives (3.5.4).

    Parameters
    ----------
    order : {"kaw", "wak"}, optional
        Rotation sequence.

    Returns
    -------
    Model
        Parameters X_S, Y_S, Z_S, ω, α, κ, X, Y, Z; data x, y, f, x₀, y₀. The Jacobian rows are
        the coefficients a₁…a₉, b₁…b₉ of the correction equations (3.5.2).

    Raises
    ------
    InputError
        If ``order`` is unknown.

    References
    ----------
    Chibunichev (2022), §3.5, eqs. (3.5.1)–(3.5.4).

    Examples
    --------
    >>> m = bundle_collinearity_model("kaw")
    >>> len(m.parameters), m.jacobian().shape
    (9, (2, 9))
    """
    Xst, Yst, Zst = collinearity_terms(order)
    F_x = x0 - f * Xst / Zst - x
    F_y = y0 - f * Yst / Zst - y
    return Model(f"bundle-collinearity-{order}", EO_SYMBOLS + (X, Y, Z), (x, y, f, x0, y0), (F_x, F_y))


@lru_cache(maxsize=None)
def self_calibration_model(order: str = "kaw") -> Model:
    """(3.6.1) with (3.6.2): the bundle model with interior orientation and distortion unknown.

    F_x = x₀ − f x*/z* − x − Δ_x,  F_y = y₀ − f y*/z* − y − Δ_y,  Δ of (3.6.2)/(1.2.2) evaluated at
    the measured coordinates reduced to the principal point (x − x₀, y − y₀), so that x + Δ_x is the
    ideal coordinate exactly as in :func:`photolib.camera.correct_distortion`.

    Parameters
    ----------
    order : {"kaw", "wak"}, optional
        Rotation sequence.

    Returns
    -------
    Model
        Parameters: the 6 EO, X, Y, Z and the 8 block-wide f, x₀, y₀, k₁, k₂, k₃, p₁, p₂ — the 17
        columns a₁…a₁₇ of (3.6.3); data x, y.

    Raises
    ------
    InputError
        If ``order`` is unknown.

    References
    ----------
    Chibunichev (2022), §3.6, eqs. (3.6.1)–(3.6.3).

    Examples
    --------
    >>> len(self_calibration_model("kaw").parameters)
    17
    """
    Xst, Yst, Zst = collinearity_terms(order)
    d_x, d_y = brown_correction_terms(x - x0, y - y0)
    F_x = x0 - f * Xst / Zst - x - d_x
    F_y = y0 - f * Yst / Zst - y - d_y
    return Model(f"self-calibration-{order}", EO_SYMBOLS + (X, Y, Z) + IO_SYMBOLS, (x, y), (F_x, F_y))


def _rig_camera_terms(order: str = "kaw"):
    """(S₂, C₂) of a rig camera: S₂ = S₁ + A₁B (3.8.5), C₂ = A₁A₂′ (3.8.8)."""
    A1 = rotation_matrix_symbolic(order)
    A2p = rotation_matrix_symbolic(order, omega_2p, alpha_2p, kappa_2p)
    S2 = sp.Matrix([Xs, Ys, Zs]) + A1 * sp.Matrix([B_X, B_Y, B_Z])
    return S2, A1 * A2p


@lru_cache(maxsize=None)
def rig_collinearity_model(order: str = "kaw") -> Model:
    """(3.8.13): collinearity of a rig camera in the reference EO and the 6 mounting elements.

    (X*, Y*, Z*)ᵀ = C₂ᵀ(X − X_S2, Y − Y_S2, Z − Z_S2)ᵀ (3.8.12) with S₂ = S₁ + A₁B (3.8.5) and
    C₂ = A₁A₂′ (3.8.8).

    Parameters
    ----------
    order : {"kaw", "wak"}, optional
        Rotation sequence of A₁ and A₂′.

    Returns
    -------
    Model
        Parameters X_S1 … κ₁ (written X_S … κ), B_X, B_Y, B_Z, ω₂′, α₂′, κ₂′, X, Y, Z — the 15
        columns c₁…c₁₅ / d₁…d₁₅ of (3.8.15); data x, y, f, x₀, y₀.

    Raises
    ------
    InputError
        If ``order`` is unknown.

    References
    ----------
    Chibunichev (2022), §3.8, eqs. (3.8.5), (3.8.8), (3.8.12)–(3.8.15).

    Examples
    --------
    >>> len(rig_collinearity_model("kaw").parameters)
    15
    """
    S2, C2 = _rig_camera_terms(order)
    Xst, Yst, Zst = C2.T * (sp.Matrix([X, Y, Z]) - S2)
    F_x = x0 - f * Xst / Zst - x
    F_y = y0 - f * Yst / Zst - y
    return Model(f"rig-collinearity-{order}", EO_SYMBOLS + MOUNT_SYMBOLS + (X, Y, Z), (x, y, f, x0, y0), (F_x, F_y))


def printed_rig_3_8_13(order: str = "kaw"):
    """(x₂, y₂) of (3.8.13) in the printed element form c₁₁…c₃₃ (C₂ = A₁A₂′), S₂ by (3.8.5).

    Parameters
    ----------
    order : {"kaw", "wak"}, optional
        Rotation sequence of A₁ and A₂′.

    Returns
    -------
    tuple of sympy.Expr
        ``(x₂, y₂)``.

    Raises
    ------
    InputError
        If ``order`` is unknown.

    References
    ----------
    Chibunichev (2022), §3.8, eqs. (3.8.5), (3.8.13).

    Examples
    --------
    >>> import sympy as sp
    >>> printed, derived = printed_rig_3_8_13("kaw"), derived_rig_image_coordinates("kaw")
    >>> sp.simplify(printed[0] - derived[0])
    0
    """
    S2, C2 = _rig_camera_terms(order)
    c = lambda i, j: C2[i - 1, j - 1]  # noqa: E731
    dX, dY, dZ = X - S2[0], Y - S2[1], Z - S2[2]
    den = c(1, 3) * dX + c(2, 3) * dY + c(3, 3) * dZ
    return (x0 - f * (c(1, 1) * dX + c(2, 1) * dY + c(3, 1) * dZ) / den,
            y0 - f * (c(1, 2) * dX + c(2, 2) * dY + c(3, 2) * dZ) / den)


def derived_rig_image_coordinates(order: str = "kaw"):
    """(x₂, y₂) derived from the vector equation (3.8.8): R_M = R_S1 + A₁B + N·C₂r₂, r₂ = (x₂ − x₀, y₂ − y₀, −f).

    Parameters
    ----------
    order : {"kaw", "wak"}, optional
        Rotation sequence of A₁ and A₂′.

    Returns
    -------
    tuple of sympy.Expr
        ``(x₂, y₂)``.

    Raises
    ------
    InputError
        If ``order`` is unknown.

    References
    ----------
    Chibunichev (2022), §3.8, eq. (3.8.8).

    Examples
    --------
    >>> from photolib.derivations import MOUNT_SYMBOLS, EO_SYMBOLS, X, Y, Z
    >>> x2, y2 = derived_rig_image_coordinates("kaw")
    >>> x2.subs({s: 0 for s in EO_SYMBOLS[:2] + EO_SYMBOLS[3:] + MOUNT_SYMBOLS}).subs({X: 0, Y: 0})
    x_0
    """
    S2, C2 = _rig_camera_terms(order)
    # (3.8.8) componentwise: X − S₂ = C₂·(N(x₂ − x₀), N(y₂ − y₀), −N f)ᵀ, and C₂⁻¹ = C₂ᵀ (a rotation)
    u, v, w = C2.T * (sp.Matrix([X, Y, Z]) - S2)
    N_val = -w / f                                   # third row: −N f = Z*  →  1/N = −f/Z*
    return x0 + u / N_val, y0 + v / N_val


@lru_cache(maxsize=None)
def rolling_shutter_model(order: str = "kaw") -> Model:
    """(3.9.1) with (3.9.2): collinearity of an image line whose EO moves linearly with x.

    EO of the line imaged at x: X_Si = X_S0 + k₁x, …, κ_i = κ₀ + k₆x (3.9.2), the measured image
    coordinate x standing for the time of the line; then F_x = x₀ − f x*/z* − x, F_y likewise
    with (x*, y*, z*)ᵀ = A_iᵀ(X − X_Si, …)ᵀ (3.9.1; the book omits x₀, y₀). Holding
    k₄ = k₅ = k₆ = 0 gives the simplified 9-unknown model.

    Parameters
    ----------
    order : {"kaw", "wak"}, optional
        Rotation sequence.

    Returns
    -------
    Model
        Parameters X_S0 … κ₀ (written X_S … κ), the rates k₁…k₆ (written k_XS … k_kappa), X, Y, Z;
        data x, y, f, x₀, y₀.

    Raises
    ------
    InputError
        If ``order`` is unknown.

    References
    ----------
    Chibunichev (2022), §3.9, eqs. (3.9.1)–(3.9.2).

    Examples
    --------
    >>> len(rolling_shutter_model("kaw").parameters)
    15
    """
    eo_i = [s + k * x for s, k in zip(EO_SYMBOLS, RATE_SYMBOLS)]
    A = rotation_matrix_symbolic(order, eo_i[3], eo_i[4], eo_i[5])
    Xst, Yst, Zst = A.T * sp.Matrix([X - eo_i[0], Y - eo_i[1], Z - eo_i[2]])
    F_x = x0 - f * Xst / Zst - x
    F_y = y0 - f * Yst / Zst - y
    return Model(f"rolling-shutter-{order}", EO_SYMBOLS + RATE_SYMBOLS + (X, Y, Z), (x, y, f, x0, y0), (F_x, F_y))
