"""The quaternion rotation model in sympy: Chapter 1, §1.3, eq. (1.3.7).

A quaternion q = (v, d), v = (a, b, c), gives the Euler–Rodrigues matrix
``(d² − v·v)E + 2vvᵀ + 2d[v]×``: ``|q|²`` times the counter-clockwise rotation by ``2·atan2(|v|, d)``
about v — the matrix printed as (1.3.7). Divided by m = a² + b² + c² + d² it is a rotation for
every non-zero q (the rational parametrisation used in §1.7).
"""

from __future__ import annotations

import sympy as sp

from ..errors import InputError

__all__ = ["quaternion_rotation_symbolic"]

_a, _b, _c, _d = sp.symbols("a b c d", real=True)


def quaternion_rotation_symbolic(a=_a, b=_b, c=_c, d=_d) -> sp.Matrix:
    """The Euler–Rodrigues matrix of the quaternion (a, b, c, d) (not divided by its norm).

    Parameters
    ----------
    a, b, c : sympy.Expr or number, optional
        The vector part v of the quaternion (default real symbols ``a``, ``b``, ``c``).
    d : sympy.Expr or number, optional
        The scalar part (default the real symbol ``d``).

    Returns
    -------
    sympy.Matrix
        (d² − v·v)E + 2vvᵀ + 2d[v]×, 3×3; AᵀA = m²E and det A = m³ with m = a² + b² + c² + d².

    Raises
    ------
    InputError
        If a component is not a sympy expression or a number.

    References
    ----------
    Chibunichev (2022), §1.3, eq. (1.3.7).

    Examples
    --------
    >>> quaternion_rotation_symbolic()[0, 1]
    2*a*b - 2*c*d
    >>> quaternion_rotation_symbolic(0, 0, 1, 1)      # 90° about Z, times |q|² = 2
    Matrix([
    [0, -2, 0],
    [2,  0, 0],
    [0,  0, 2]])
    """
    try:
        a, b, c, d = (sp.sympify(v, strict=True) for v in (a, b, c, d))
    except (sp.SympifyError, TypeError) as exc:
        raise InputError(f"quaternion components must be sympy expressions or numbers: {exc}") from exc
    v = sp.Matrix([a, b, c])
    cross = sp.Matrix([[0, -c, b], [c, 0, -a], [-b, a, 0]])
    return (d ** 2 - (v.T * v)[0]) * sp.eye(3) + 2 * v * v.T + 2 * d * cross
