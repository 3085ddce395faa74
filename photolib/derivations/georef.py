"""Scanner aerial triangulation with fixed projection centres in sympy — Chapter 8, §8.15.

The collinearity equations (8.15.1) of a scanner line whose exterior orientation is interpolated
between two fixed projection centres S_k, S_{k+1} by (8.15.2):

    E = c·E_k + (1 − c)·E_{k+1} − δE,   c = (t_{k+1} − t)/(t_{k+1} − t_k),
    δE = c·E_k^meas + (1 − c)·E_{k+1}^meas − E^meas(t),

for E ∈ {X_S, Y_S, Z_S, ω, α, κ}. The unknowns are the twelve elements of the two fixed centres
and the point X, Y, Z; the data are c, the six δE, f and the observed x, y. The Jacobian is
derived here by sympy (never typed by hand) and lambdified lazily, once per rotation order.
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np
import sympy as sp

from ..errors import InputError
from .rotation import rotation_matrix_symbolic
from .symbols import X, Xs, Y, Ys, Z, Zs, alpha, f, kappa, omega

__all__ = ["FIXED_CENTRE_PARAMETERS", "FIXED_CENTRE_DATA", "fixed_centre_collinearity", "line_collinearity",
           "fixed_centre_functions"]

_EO = ("X_S", "Y_S", "Z_S", "omega", "alpha", "kappa")
_Ek = sp.symbols(" ".join(f"{n}_k" for n in _EO), real=True)
_Ek1 = sp.symbols(" ".join(f"{n}_k1" for n in _EO), real=True)
_dE = sp.symbols(" ".join(f"delta_{n}" for n in _EO), real=True)
_c, _xo, _yo = sp.symbols("c x_obs y_obs", real=True)

FIXED_CENTRE_PARAMETERS = tuple(_Ek) + tuple(_Ek1) + (X, Y, Z)
"""The 15 unknowns of one observation: E_k (6), E_{k+1} (6) and the point X, Y, Z."""
FIXED_CENTRE_DATA = (_c,) + tuple(_dE) + (f, _xo, _yo)
"""The data of one observation: c, δX_S … δκ, f, the observed x and y."""


def _order(order):
    if order not in ("wak", "kaw"):
        raise InputError(f"order must be 'wak' (1.3.2) or 'kaw' (1.3.4), got {order!r}")
    return order


def fixed_centre_collinearity(order: str = "wak") -> sp.Matrix:
    """Residuals (x_model − x_obs, y_model − y_obs) of (8.15.1) with the line EO of (8.15.2).

    Parameters
    ----------
    order : {"wak", "kaw"}
        Rotation sequence of A (default (1.3.2), A = A_ω A_α A_κ).

    Returns
    -------
    sympy.Matrix
        2×1, in :data:`FIXED_CENTRE_PARAMETERS` and :data:`FIXED_CENTRE_DATA`.

    Raises
    ------
    InputError
        An unknown rotation order.

    References
    ----------
    Chibunichev (2022), §8.15, eq. (8.15.1) and the interpolation formulas after it ((8.15.2)).

    Examples
    --------
    >>> expr = fixed_centre_collinearity()
    >>> expr.shape
    (2, 1)
    >>> sorted(str(s) for s in expr.free_symbols)[:3]
    ['X', 'X_S_k', 'X_S_k1']
    """
    _order(order)
    E = [_c * a + (1 - _c) * b - d for a, b, d in zip(_Ek, _Ek1, _dE)]
    A = rotation_matrix_symbolic(order, E[3], E[4], E[5])
    d = sp.Matrix([X - E[0], Y - E[1], Z - E[2]])
    u = A.T * d                                 # (a11ΔX + a21ΔY + a31ΔZ, …): the columns of A
    return sp.Matrix([-f * u[0] / u[2] - _xo, -f * u[1] / u[2] - _yo])


def line_collinearity(order: str = "wak") -> sp.Matrix:
    """The collinearity equations (8.15.1) of one scanner line, as residuals x − x_obs, y − y_obs.

    x = −f·(a₁₁ΔX + a₂₁ΔY + a₃₁ΔZ)/(a₁₃ΔX + a₂₃ΔY + a₃₃ΔZ), y likewise with a₁₂, a₂₂, a₃₂;
    the line EO symbols are X_S, Y_S, Z_S, ω, α, κ.

    Parameters
    ----------
    order : {"wak", "kaw"}
        Rotation sequence of A.

    Returns
    -------
    sympy.Matrix
        2×1.

    Raises
    ------
    InputError
        An unknown rotation order.

    References
    ----------
    Chibunichev (2022), §8.15, eq. (8.15.1).

    Examples
    --------
    >>> line_collinearity().shape
    (2, 1)
    """
    _order(order)
    A = rotation_matrix_symbolic(order, omega, alpha, kappa)
    u = A.T * sp.Matrix([X - Xs, Y - Ys, Z - Zs])
    return sp.Matrix([-f * u[0] / u[2] - _xo, -f * u[1] / u[2] - _yo])


@lru_cache(maxsize=None)
def _line_functions(order):
    expr = line_collinearity(order)
    params = (Xs, Ys, Zs, omega, alpha, kappa, X, Y, Z)
    J = expr.jacobian(sp.Matrix(params))
    fn = sp.lambdify(list(params) + [f, _xo, _yo], list(expr) + list(J), modules="numpy", cse=True)
    # ∂E/∂E_k and ∂E/∂E_{k+1} of (8.15.2), by sympy
    E = _c * _Ek[0] + (1 - _c) * _Ek1[0] - _dE[0]
    dk = sp.lambdify([_c], sp.diff(E, _Ek[0]), modules="numpy")
    dk1 = sp.lambdify([_c], sp.diff(E, _Ek1[0]), modules="numpy")
    return fn, dk, dk1


@lru_cache(maxsize=None)
def fixed_centre_functions(order: str = "wak"):
    """Vectorised residual and Jacobian functions of :func:`fixed_centre_collinearity`.

    The Jacobian of the line collinearity (8.15.1) with respect to the line EO and the point is
    derived by sympy (:func:`line_collinearity`) and chained with ∂E/∂E_k = c,
    ∂E/∂E_{k+1} = 1 − c of (8.15.2) (also by sympy); the tests check the result against the
    direct sympy Jacobian of :func:`fixed_centre_collinearity`.

    Parameters
    ----------
    order : {"wak", "kaw"}
        Rotation sequence.

    Returns
    -------
    residual : callable
        ``residual(params (m, 15), data (m, 10)) -> (m, 2)``.
    jacobian : callable
        ``jacobian(params, data) -> (m, 2, 15)``: ∂residual/∂params.

    Raises
    ------
    InputError
        An unknown rotation order.

    References
    ----------
    Chibunichev (2022), §8.15, eq. (8.15.1), (8.15.2).

    Examples
    --------
    >>> import numpy as np
    >>> res, jac = fixed_centre_functions()
    >>> p = np.array([[0, 0, 1000, 0, 0, 0, 10, 0, 1000, 0, 0, 0, 5, 0, 0.0]])
    >>> d = np.array([[0.5, 0, 0, 0, 0, 0, 0, 100.0, 0, 0]])
    >>> res(p, d).round(9) + 0.0, jac(p, d).shape
    (array([[0., 0.]]), (1, 2, 15))
    """
    _order(order)
    fn, dk, dk1 = _line_functions(order)

    def _evaluate(params, data):
        params = np.asarray(params, dtype=float)
        data = np.asarray(data, dtype=float)
        m = params.shape[0]
        c = data[:, 0]
        E = c[:, None] * params[:, :6] + (1 - c[:, None]) * params[:, 6:12] - data[:, 1:7]
        cols = [E[:, i] for i in range(6)] + [params[:, 12 + i] for i in range(3)] + \
               [data[:, 7], data[:, 8], data[:, 9]]
        out = np.stack([np.broadcast_to(v, (m,)) for v in fn(*cols)], axis=1)
        return out[:, :2], out[:, 2:].reshape(m, 2, 9), np.broadcast_to(dk(c), (m,)), np.broadcast_to(dk1(c), (m,))

    def residual(params, data):
        return _evaluate(params, data)[0]

    def jacobian(params, data):
        _, J, a, b = _evaluate(params, data)
        return np.concatenate([J[:, :, :6] * a[:, None, None], J[:, :, :6] * b[:, None, None], J[:, :, 6:]], axis=2)

    return residual, jacobian
