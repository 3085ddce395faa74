"""Sympy forms of Hanzl's additional-parameter models, Modul 01 §4.4 and §5.4.1 (seed 002 lines 759–982).

Hanzl, Fotogrammetrie, Modul 01 (seed ``002_d5f7929691601478.txt``):

* :func:`hanzl17_symbolic` — Ebner's 12 orthogonal parameters g₁…g₁₂ (lines 764–770), the radial
  g₁₃…g₁₅ with the powers read as (r² − r₀²), (r⁴ − r₀⁴), (r⁶ − r₀⁶) (lines 776–778; the OCR prints
  (r² − r₀²) three times) and the tangential g₁₆, g₁₇ (lines 782–784).
* :func:`brown18_symbolic` — Brown's 18 parameters a₁…a₁₈ (lines 966–968).
* :func:`murai_symbolic` — Murai's model K₁, K₂, P₁…P₆ (lines 970–972).
* :func:`ebner_gram` / :func:`ebner_eo_products` — the orthogonality over the 3 × 3 Gruber grid
  x, y ∈ {−b, 0, b} among the twelve fields and against the six first-order effects of the exterior
  orientation of a vertical image (line 762). Related: Chibunichev §3.6 (self-calibration).
"""

from __future__ import annotations

from functools import lru_cache

import sympy as sp

from .symbols import f, x, y

__all__ = ["B_EBNER", "R0", "hanzl17_symbolic", "brown18_symbolic", "murai_symbolic", "ebner_gram",
           "eo_effects_symbolic", "ebner_eo_products"]

B_EBNER = sp.Symbol("b", positive=True)
"""The image base b of Ebner's set (spacing of the 3 × 3 grid)."""

R0 = sp.Symbol("r_0", nonnegative=True)
"""Radius of zero radial distortion r₀."""


@lru_cache(maxsize=None)
def hanzl17_symbolic() -> tuple:
    """Hanzl's dx, dy with g₁ … g₁₇ (Ebner 12 + radial 3 + tangential 2): (dx, dy, parameters).

    Returns
    -------
    tuple
        (dx, dy, (g₁ … g₁₇)) in x, y, :data:`B_EBNER` and :data:`R0`.

    Raises
    ------
    InputError
        Never (no input).

    References
    ----------
    Hanzl, Fotogrammetrie, Modul 01, §4.4 (seed 002 lines 764–784).

    Examples
    --------
    >>> len(hanzl17_symbolic()[2])
    17
    """
    g = sp.symbols("g_1:18", real=True)
    b = B_EBNER
    q = sp.Rational(2, 3) * b**2
    X2, Y2 = x**2 - q, y**2 - q
    r2 = x**2 + y**2
    dx = (g[0] * x + g[1] * y - g[2] * (2 * x**2 - sp.Rational(4, 3) * b**2) + g[3] * x * y + g[4] * Y2
          + g[6] * x * Y2 + g[8] * y * X2 + g[10] * X2 * Y2)
    dy = (-g[0] * y + g[1] * x + g[2] * x * y - g[3] * (2 * y**2 - sp.Rational(4, 3) * b**2) + g[5] * X2
          + g[7] * y * X2 + g[9] * x * Y2 + g[11] * X2 * Y2)
    rad = g[12] * (r2 - R0**2) + g[13] * (r2**2 - R0**4) + g[14] * (r2**3 - R0**6)
    dx += x * rad + g[15] * (r2 + 2 * x**2) + g[16] * 2 * x * y
    dy += y * rad + g[15] * 2 * x * y + g[16] * (r2 + 2 * y**2)
    return dx, dy, g


@lru_cache(maxsize=None)
def brown18_symbolic() -> tuple:
    """Brown's 18-parameter model as printed by Hanzl: (dx, dy, (a₁ … a₁₈)) in x, y and c (= :data:`f`).

    Returns
    -------
    tuple
        (dx, dy, parameters).

    Raises
    ------
    InputError
        Never (no input).

    References
    ----------
    Hanzl, Fotogrammetrie, Modul 01, §5.4.1 (seed 002 lines 966–968).

    Examples
    --------
    >>> len(brown18_symbolic()[2])
    18
    """
    a = (None,) + sp.symbols("a_1:19", real=True)
    r2 = x**2 + y**2
    common = a[13] * (x**2 - y**2) + a[14] * x**2 * y**2 + a[15] * (x**4 - y**4)
    rad = a[16] * r2 + a[17] * r2**2 + a[18] * r2**3
    dx = (a[1] * x + a[2] * y + a[3] * x * y + a[4] * y**2 + a[5] * x**2 * y + a[6] * x * y**2
          + a[7] * x**2 * y**2 + x / f * common + x * rad)
    dy = (a[8] * x * y + a[9] * x**2 + a[10] * x**2 * y + a[11] * x * y**2 + a[12] * x**2 * y**2
          + y / f * common + y * rad)
    return dx, dy, a[1:]


@lru_cache(maxsize=None)
def murai_symbolic() -> tuple:
    """Murai's model as printed by Hanzl: (dx, dy, (K₁, K₂, P₁ … P₆)).

    Returns
    -------
    tuple
        (dx, dy, parameters).

    Raises
    ------
    InputError
        Never (no input).

    References
    ----------
    Hanzl, Fotogrammetrie, Modul 01, §5.4.1 (seed 002 lines 970–972).

    Examples
    --------
    >>> len(murai_symbolic()[2])
    8
    """
    K1, K2 = sp.symbols("K_1 K_2", real=True)
    P = sp.symbols("P_1:7", real=True)
    r2 = x**2 + y**2
    dx = x * (K1 * r2 + K2 * r2**2) + (P[0] * x + P[1] * y + P[2] * x * y + P[3] * y**2)
    dy = y * (K1 * r2 + K2 * r2**2) + (P[4] * x * y + P[5] * x**2)
    return dx, dy, (K1, K2) + tuple(P)


def _grid():
    return [(i * B_EBNER, j * B_EBNER) for i in (-1, 0, 1) for j in (-1, 0, 1)]


def _fields(dx, dy, params):
    return [(sp.diff(dx, p), sp.diff(dy, p)) for p in params]


def _gram(fa, fb):
    G = sp.zeros(len(fa), len(fb))
    for i, (ax, ay) in enumerate(fa):
        for j, (bx, by) in enumerate(fb):
            G[i, j] = sp.expand(sum(((ax * bx + ay * by).subs({x: gx, y: gy}) for gx, gy in _grid()),
                                    sp.Integer(0)))
    return G


def ebner_gram() -> sp.Matrix:
    """Gram matrix of Ebner's twelve fields g₁ … g₁₂ (Hanzl's signs) over the 3 × 3 grid x, y ∈ {−b, 0, b}.

    Returns
    -------
    sympy.Matrix
        12 × 12; diagonal when the set is orthogonal.

    Raises
    ------
    InputError
        Never (no input).

    References
    ----------
    Hanzl, Fotogrammetrie, Modul 01, §4.4 (seed 002 lines 762–770).

    Examples
    --------
    >>> ebner_gram().is_diagonal()
    True
    """
    dx, dy, g = hanzl17_symbolic()
    f12 = _fields(dx, dy, g[:12])
    return _gram(f12, f12)


def eo_effects_symbolic() -> list:
    """First-order image displacements (dx, dy) of dX₀, dY₀, dZ₀, dω, dφ, dκ of a vertical image.

    Shifts of the centre move the image by −c/Z·(dX₀, dY₀) and scale it by x/Z, y/Z; the rotations
    give the familiar fields (c + x²/c, xy/c), (xy/c, c + y²/c) and (y, −x) (signs do not matter for
    orthogonality). Here c is :data:`photolib.derivations.symbols.f`.

    Returns
    -------
    list of (dx, dy)
        Six fields.

    Raises
    ------
    InputError
        Never (no input).

    References
    ----------
    Hanzl, Fotogrammetrie, Modul 01, §4.4 (line 762); Chibunichev §2.7 (the linearised collinearity).

    Examples
    --------
    >>> len(eo_effects_symbolic())
    6
    """
    return [(sp.Integer(1), sp.Integer(0)), (sp.Integer(0), sp.Integer(1)), (x, y),
            (x * y / f, f + y**2 / f), (f + x**2 / f, x * y / f), (y, -x)]


def ebner_eo_products() -> sp.Matrix:
    """Products of Ebner's twelve fields with the six EO fields summed over the 3 × 3 grid.

    Returns
    -------
    sympy.Matrix
        12 × 6; all zero when the set is orthogonal to the exterior orientation.

    Raises
    ------
    InputError
        Never (no input).

    References
    ----------
    Hanzl, Fotogrammetrie, Modul 01, §4.4 (seed 002 line 762).

    Examples
    --------
    >>> ebner_eo_products().is_zero_matrix
    True
    """
    dx, dy, g = hanzl17_symbolic()
    return _gram(_fields(dx, dy, g[:12]), eo_effects_symbolic())
