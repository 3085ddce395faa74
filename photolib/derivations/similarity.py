"""The spatial similarity transformation (absolute orientation of a model): Chapter 2, §2.10–§2.11.

* :func:`similarity_model` — φ_X, φ_Y, φ_Z of (2.11.1) with the seven elements of (2.10.4).
* The coefficients of (2.11.2) as printed (:func:`printed_similarity_partials`) and derived
  (:func:`derived_similarity_partials`), and the printed ones as numpy code for the "as printed"
  modes of :func:`photolib.image_pair.absolute_orientation` (:func:`printed_similarity_jacobian`).
"""

from __future__ import annotations

from functools import lru_cache

import sympy as sp

from ..errors import InputError
from .model import Model, _printed_function
from .rotation import rotation_matrix_symbolic
from .symbols import X, X0, XM, Y, Y0, YM, Z, Z0, ZM, alphaM, kappaM, omegaM, t_M

__all__ = ["similarity_model", "SIMILARITY_COEFFICIENTS", "printed_similarity_partials",
           "derived_similarity_partials", "printed_similarity_jacobian"]


@lru_cache(maxsize=None)
def similarity_model(order: str = "kaw") -> Model:
    """φ_X, φ_Y, φ_Z of (2.11.1): (X, Y, Z)ᵀ − (X₀, Y₀, Z₀)ᵀ − t·A_M(X_M, Y_M, Z_M)ᵀ.

    (2.10.5) as printed lacks the factor t; it is included here as in (2.10.4) and (2.11.1).

    Parameters
    ----------
    order : {"kaw", "wak"}, optional
        Rotation sequence of A_M.

    Returns
    -------
    Model
        Parameters: the seven elements of exterior orientation of the model X₀, Y₀, Z₀, ω_M,
        α_M, κ_M, t (2.10.4); data: model and object coordinates X_M, Y_M, Z_M, X, Y, Z of a
        control point.

    Raises
    ------
    InputError
        If ``order`` is unknown.

    References
    ----------
    Chibunichev (2022), §2.10, eqs. (2.10.4)–(2.10.5); §2.11, eq. (2.11.1).

    Examples
    --------
    >>> res, jac = similarity_model("wak").compile()
    >>> res(0, 0, 0, 0, 0, 0, 2.0, 1.0, 2.0, 3.0, 2.0, 4.0, 6.0).ravel().tolist()
    [0.0, 0.0, 0.0]
    """
    A = rotation_matrix_symbolic(order, omegaM, alphaM, kappaM)
    phi = sp.Matrix([X, Y, Z]) - sp.Matrix([X0, Y0, Z0]) - t_M * A * sp.Matrix([XM, YM, ZM])
    return Model(f"similarity-{order}", (X0, Y0, Z0, omegaM, alphaM, kappaM, t_M), (XM, YM, ZM, X, Y, Z),
                 tuple(phi))


SIMILARITY_COEFFICIENTS = tuple(f"{row}{j}" for row in "abc" for j in range(1, 8))
"""Names of the coefficients of (2.11.2): a₁…a₇ (φ_X), b₁…b₇ (φ_Y), c₁…c₇ (φ_Z)."""


def printed_similarity_partials() -> dict:
    """a₁…a₇, b₁…b₇, c₁…c₇ of (2.11.2) exactly as printed (seed lines 1463–1481).

    The aᵢⱼ in them are the elements of A_M; the printed ∂/∂ω_M and ∂/∂κ_M agree with the ω–α–κ
    matrix (1.3.2) only. ∂φ/∂α_M (a₅, b₅, c₅) has the wrong sign on both sin κ_M terms: see
    :func:`derived_similarity_partials`.

    Returns
    -------
    dict
        Keys :data:`SIMILARITY_COEFFICIENTS`, values sympy expressions.

    Raises
    ------
    InputError
        Never (no input).

    References
    ----------
    Chibunichev (2022), §2.11, eq. (2.11.2).

    Examples
    --------
    >>> import sympy as sp
    >>> printed, derived = printed_similarity_partials(), derived_similarity_partials("wak")
    >>> sp.simplify(printed["a6"] - derived["a6"]), sp.simplify(printed["a5"] - derived["a5"]) == 0
    (0, False)
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
    """a₁…c₇ of (2.11.2) derived by sympy from (2.11.1) (:func:`similarity_model`).

    Parameters
    ----------
    order : {"wak", "kaw"}, optional
        Rotation sequence of A_M.

    Returns
    -------
    dict
        Keys :data:`SIMILARITY_COEFFICIENTS`, values the sympy derivatives.

    Raises
    ------
    InputError
        If ``order`` is unknown.

    References
    ----------
    Chibunichev (2022), §2.11, eqs. (2.11.1)–(2.11.2).

    Examples
    --------
    >>> derived_similarity_partials("wak")["a1"]
    -1
    """
    J = similarity_model(order).jacobian()
    return {f"{row}{j + 1}": J[i, j] for i, row in enumerate("abc") for j in range(7)}


def _printed_similarity_build(zero_a5):
    printed = printed_similarity_partials()
    if zero_a5:
        printed["a5"] = sp.Integer(0)
    args = [X0, Y0, Z0, omegaM, alphaM, kappaM, t_M, XM, YM, ZM, X, Y, Z]
    return args, [printed[k] for k in SIMILARITY_COEFFICIENTS], 21


@lru_cache(maxsize=None)
def printed_similarity_jacobian(zero_a5: bool = False):
    """Numpy function of ``(*elements, X_M, Y_M, Z_M, X, Y, Z)`` giving the printed a₁…c₇, shape (21, n).

    Parameters
    ----------
    zero_a5 : bool, optional
        Set a₅ = ∂φ_X/∂α_M to 0: what the book's program evidently did in the §2.11 worked
        example (only then do its X₀, m_X₀ and the X₀ row of the correlation matrix come out).

    Returns
    -------
    callable
        Returns an array of shape (21, n).

    Raises
    ------
    InputError
        If ``zero_a5`` is not a bool.

    References
    ----------
    Chibunichev (2022), §2.11, eq. (2.11.2).

    Examples
    --------
    >>> printed_similarity_jacobian()(0, 0, 0, 0, 0, 0, 1.0, 1.0, 2.0, 3.0, 1.0, 2.0, 3.0).shape
    (21,)
    """
    if not isinstance(zero_a5, bool):
        raise InputError(f"zero_a5 must be True or False, got {zero_a5!r}")
    key = "printed-similarity-zero-a5" if zero_a5 else "printed-similarity"
    return _printed_function(key, lambda: _printed_similarity_build(zero_a5))
