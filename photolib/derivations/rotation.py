"""Rotation matrices in sympy: Chapter 1, §1.3, eqs. (1.3.1)–(1.3.5).

The elementary rotations A_ω, A_α, A_κ, their products for the two sequences of the book
(``"kaw"``: A = A_κ A_α A_ω of (1.3.4)/(1.3.5); ``"wak"``: A = A_ω A_α A_κ of (1.3.2)) and the
element lists exactly as printed, for comparison.
"""

from __future__ import annotations

import sympy as sp

from ..rotation import check_order
from .symbols import alpha, kappa, omega

__all__ = ["elementary_rotations", "rotation_matrix_symbolic", "book_rotation_elements_kaw",
           "book_rotation_elements_wak"]


def _angle(value, name):
    from ..errors import InputError
    try:
        return sp.sympify(value, strict=True)
    except (sp.SympifyError, TypeError) as exc:
        raise InputError(f"{name} must be a sympy expression or a number, got {value!r}") from exc


def elementary_rotations(w=omega, a=alpha, k=kappa):
    """The book's A_ω, A_α, A_κ as sympy matrices (right-handed rotations about X, Y, Z).

    Parameters
    ----------
    w, a, k : sympy.Expr or number, optional
        The angles ω, α, κ (default the symbols ``omega``, ``alpha``, ``kappa``).

    Returns
    -------
    tuple of sympy.Matrix
        ``(A_ω, A_α, A_κ)``, each 3×3.

    Raises
    ------
    InputError
        If an angle is not a sympy expression or a number.

    References
    ----------
    Chibunichev (2022), §1.3, eq. (1.3.1).

    Examples
    --------
    >>> A_w, A_a, A_k = elementary_rotations()
    >>> A_k
    Matrix([
    [cos(kappa), -sin(kappa), 0],
    [sin(kappa),  cos(kappa), 0],
    [         0,           0, 1]])
    """
    w, a, k = _angle(w, "w"), _angle(a, "a"), _angle(k, "k")
    c, s = sp.cos, sp.sin
    A_w = sp.Matrix([[1, 0, 0], [0, c(w), -s(w)], [0, s(w), c(w)]])
    A_a = sp.Matrix([[c(a), 0, s(a)], [0, 1, 0], [-s(a), 0, c(a)]])
    A_k = sp.Matrix([[c(k), -s(k), 0], [s(k), c(k), 0], [0, 0, 1]])
    return A_w, A_a, A_k


def rotation_matrix_symbolic(order: str = "kaw", w=omega, a=alpha, k=kappa) -> sp.Matrix:
    """A of (1.3.4)/(1.3.5) (``"kaw"``) or (1.3.2) (``"wak"``) in sympy.

    Parameters
    ----------
    order : {"kaw", "wak"}, optional
        The rotation sequence: A = A_κ A_α A_ω (``"kaw"``) or A_ω A_α A_κ (``"wak"``).
    w, a, k : sympy.Expr or number, optional
        The angles ω, α, κ (default the symbols ``omega``, ``alpha``, ``kappa``).

    Returns
    -------
    sympy.Matrix
        The 3×3 rotation matrix.

    Raises
    ------
    InputError
        If ``order`` is unknown or an angle is not a sympy expression or a number.

    References
    ----------
    Chibunichev (2022), §1.3, eqs. (1.3.2), (1.3.4), (1.3.5).

    Examples
    --------
    >>> rotation_matrix_symbolic("kaw")[2, 0]
    -sin(alpha)
    >>> rotation_matrix_symbolic("wak")[0, 2]
    sin(alpha)
    """
    check_order(order)
    A_w, A_a, A_k = elementary_rotations(w, a, k)
    return A_k * A_a * A_w if order == "kaw" else A_w * A_a * A_k


def book_rotation_elements_kaw() -> sp.Matrix:
    """The element list of (1.3.5) exactly as the book writes it (with the OCR's duplicate a21 dropped).

    Returns
    -------
    sympy.Matrix
        3×3 in the symbols ``omega``, ``alpha``, ``kappa``.

    Raises
    ------
    InputError
        Never (no input).

    References
    ----------
    Chibunichev (2022), §1.3, eq. (1.3.5).

    Examples
    --------
    >>> import sympy as sp
    >>> sp.simplify(book_rotation_elements_kaw() - rotation_matrix_symbolic("kaw")) == sp.zeros(3, 3)
    True
    """
    c, s = sp.cos, sp.sin
    w, a, k = omega, alpha, kappa
    return sp.Matrix([
        [c(k) * c(a), s(a) * s(w) * c(k) - s(k) * c(w), s(a) * c(w) * c(k) + s(w) * s(k)],
        [s(k) * c(a), s(k) * s(w) * s(a) + c(k) * c(w), s(a) * c(w) * s(k) - s(w) * c(k)],
        [-s(a), c(a) * s(w), c(a) * c(w)],
    ])


def book_rotation_elements_wak() -> sp.Matrix:
    """The element list of (1.3.2) as printed in §1.3.

    Returns
    -------
    sympy.Matrix
        3×3 in the symbols ``omega``, ``alpha``, ``kappa``.

    Raises
    ------
    InputError
        Never (no input).

    References
    ----------
    Chibunichev (2022), §1.3, eq. (1.3.2).

    Examples
    --------
    >>> import sympy as sp
    >>> sp.expand(book_rotation_elements_wak() - rotation_matrix_symbolic("wak")) == sp.zeros(3, 3)
    True
    """
    c, s = sp.cos, sp.sin
    w, a, k = omega, alpha, kappa
    return sp.Matrix([
        [c(a) * c(k), -c(a) * s(k), s(a)],
        [s(w) * s(a) * c(k) + c(w) * s(k), -s(w) * s(a) * s(k) + c(w) * c(k), -s(w) * c(a)],
        [-c(w) * s(a) * c(k) + s(w) * s(k), c(w) * s(a) * s(k) + s(w) * c(k), c(w) * c(a)],
    ])
