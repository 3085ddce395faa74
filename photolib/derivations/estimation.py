"""Sympy derivations of the estimation formulas of Hanzl §7.3: least squares, sequential least
squares and the Kalman filter (seed 002, lines 1358–1500), and the inertial position integral of
§7.1 (lines 1306–1310).

Each function derives a result from first principles on small symbolic matrices (two unknowns,
a first block of two observations, a second block of one or two) and returns the derived
expression; :mod:`photolib.book.hanzl_dso` compares Hanzl's printed forms with them. The numeric
implementations are in :mod:`photolib.direct_orientation`.

* least squares: x̂ from ∂(vᵀPv)/∂x = 0 with v = Ax − l;
* sequential least squares: the batch solution of both blocks minus the solution of the first
  (Δx), (N₁ + N₂)⁻¹ − N₁⁻¹ (ΔQ), both forms of the gain K (matrix-inversion lemma);
* the Kalman update: the batch solution of the prior as a pseudo-observation x₀ + v₁ = x
  (weight Q_x⁻¹) with l + v_l = Ax (weight Q_l⁻¹);
* the transition matrix: e^{F(t − t₀)} and its Taylor series;
* the position integral: r(t) from r̈ = a(t), r(t₀) = r₀, ṙ(t₀) = v₀.
"""

from __future__ import annotations

from functools import lru_cache

import sympy as sp

from ..errors import InputError

__all__ = ["least_squares_solution", "sequential_blocks", "kalman_update_batch", "transition_series",
           "position_integral"]


def _symmetric(name: str, n: int) -> sp.Matrix:
    return sp.Matrix(n, n, lambda i, j: sp.Symbol(f"{name}{min(i, j) + 1}{max(i, j) + 1}", real=True))


def _general(name: str, rows: int, cols: int) -> sp.Matrix:
    return sp.Matrix(rows, cols, lambda i, j: sp.Symbol(f"{name}{i + 1}{j + 1}", real=True))


def _diagonal(name: str, n: int) -> sp.Matrix:
    return sp.diag(*[sp.Symbol(f"{name}{i + 1}", positive=True) for i in range(n)])


@lru_cache(maxsize=None)
def least_squares_solution():
    """x̂ of v = Ax − l, vᵀPv = min, derived from the gradient (Hanzl §7.3.1, §2.6).

    Returns
    -------
    dict
        ``A`` (3×2), ``P`` (diagonal), ``l`` (3×1) and ``x`` — the solution of
        ∂(vᵀPv)/∂x = 0, solved by sympy without using the normal-equation formula.

    Raises
    ------
    None
        Builds fixed symbolic matrices.

    References
    ----------
    Hanzl, Fotogrammetrie, Modul 01, §7.3.1 (seed 002 lines 1358–1368); §2.6 (line 317).

    Examples
    --------
    >>> d = least_squares_solution()
    >>> N = d["A"].T * d["P"] * d["A"]
    >>> sp.simplify(d["x"] - N.inv() * d["A"].T * d["P"] * d["l"]) == sp.zeros(2, 1)
    True
    """
    A, P, l = _general("a", 3, 2), _diagonal("p", 3), _general("l", 3, 1)
    x = sp.Matrix(sp.symbols("x1 x2", real=True))
    v = A * x - l
    objective = (v.T * P * v)[0, 0]
    solution = sp.solve([sp.diff(objective, xi) for xi in x], list(x), dict=True)[0]
    return {"A": A, "P": P, "l": l, "x": sp.Matrix([solution[xi] for xi in x])}


def sequential_blocks(m2: int = 1):
    """Sequential least squares derived as batch minus first-block solutions (Hanzl §7.3.2).

    Parameters
    ----------
    m2 : int
        Observations of the second block (1 or 2; two unknowns, two observations in the first).

    Returns
    -------
    dict
        The blocks ``N1`` (symmetric 2×2, standing for A₁ᵀP₁A₁), ``h1``, ``A2``, ``P2``, ``l2``,
        the first solution ``x0`` = N₁⁻¹h₁ and ``Q0`` = N₁⁻¹, and the derived ``dx`` (batch x of
        both blocks − x₀) and ``dQ`` ((N₁ + N₂)⁻¹ − N₁⁻¹).

    Raises
    ------
    InputError
        ``m2`` not 1 or 2.

    References
    ----------
    Hanzl, Fotogrammetrie, Modul 01, §7.3.2, eqs. "1)" and "2)" (seed 002 lines 1370–1430).

    Examples
    --------
    >>> d = sequential_blocks()
    >>> N = d["N1"] + d["A2"].T * d["P2"] * d["A2"]
    >>> sp.simplify(d["dQ"] - (N.inv() - d["N1"].inv())) == sp.zeros(2, 2)
    True
    """
    if isinstance(m2, bool) or not isinstance(m2, int) or m2 not in (1, 2):
        raise InputError(f"m2 must be the integer 1 or 2, got {m2!r}")
    return _sequential_blocks(m2)


@lru_cache(maxsize=None)            # validated above: the cache would take 1.0 or True for 1
def _sequential_blocks(m2: int) -> dict:
    N1, h1 = _symmetric("n", 2), _general("h", 2, 1)
    A2, P2, l2 = _general("b", m2, 2), _diagonal("w", m2), _general("k", m2, 1)
    N2, h2 = A2.T * P2 * A2, A2.T * P2 * l2
    Q0 = N1.inv()
    x0 = Q0 * h1
    batch = (N1 + N2).inv() * (h1 + h2)
    return {"N1": N1, "h1": h1, "A2": A2, "P2": P2, "l2": l2, "x0": x0, "Q0": Q0,
            "dx": (batch - x0).applyfunc(sp.simplify), "dQ": ((N1 + N2).inv() - Q0).applyfunc(sp.simplify)}


@lru_cache(maxsize=None)
def kalman_update_batch():
    """The Kalman update derived as least squares of the prior and one epoch's observations.

    The predicted state x with cofactors Q_x is an observation of the state (x + v_x = x̂,
    weight Q_x⁻¹) and the measurements l are observations of A x̂ (weight Q_l⁻¹); their joint
    least-squares solution and its cofactor matrix are returned (Hanzl §7.3.3.2).

    Returns
    -------
    dict
        ``x`` (2×1), ``Q`` (symmetric 2×2), ``A`` (2×2), ``Ql`` (diagonal 2×2), ``l`` (2×1),
        ``T`` (a general 2×2 transition matrix, for the printed gain), and the derived ``x_hat``,
        ``Q_hat``.

    Raises
    ------
    None
        Builds fixed symbolic matrices.

    References
    ----------
    Hanzl, Fotogrammetrie, Modul 01, §7.3.3.2 (seed 002 lines 1472–1500).

    Examples
    --------
    >>> d = kalman_update_batch()
    >>> K = d["Q"] * d["A"].T * (d["Ql"] + d["A"] * d["Q"] * d["A"].T).inv()
    >>> sp.simplify(d["Q_hat"] - (sp.eye(2) - K * d["A"]) * d["Q"]) == sp.zeros(2, 2)
    True
    """
    x, Q, A = _general("x", 2, 1), _symmetric("q", 2), _general("a", 2, 2)
    Ql, l, T = _diagonal("s", 2), _general("l", 2, 1), _general("t", 2, 2)
    N = Q.inv() + A.T * Ql.inv() * A
    Q_hat = N.inv()
    x_hat = Q_hat * (Q.inv() * x + A.T * Ql.inv() * l)
    return {"x": x, "Q": Q, "A": A, "Ql": Ql, "l": l, "T": T,
            "x_hat": x_hat, "Q_hat": Q_hat}


def transition_series(order: int = 2):
    """e^{FΔt} for a constant dynamic matrix F and its Taylor series to ``order`` (Hanzl §7.3.3.1).

    F is the position–velocity model with a first-order Gauss–Markov velocity,
    F = [[0, 1], [0, −β]] (β ≥ 0); e^{FΔt} solves ẋ = Fx with x(t₀) given.

    Parameters
    ----------
    order : int
        Highest power of Δt kept in the series (≥ 1).

    Returns
    -------
    dict
        ``F``, ``dt``, ``T`` (the exact e^{FΔt}) and ``series`` (the Taylor polynomial of T in Δt
        to ``order``, derived from T itself).

    Raises
    ------
    InputError
        ``order`` < 1.

    References
    ----------
    Hanzl, Fotogrammetrie, Modul 01, §7.3.3.1 (seed 002 lines 1446–1468).

    Examples
    --------
    >>> d = transition_series()
    >>> sp.simplify(d["T"].diff(d["dt"]) - d["F"] * d["T"]) == sp.zeros(2, 2)
    True
    """
    if isinstance(order, bool) or not isinstance(order, int) or order < 1:
        raise InputError(f"order must be an integer ≥ 1, got {order!r}")
    return _transition_series(order)


@lru_cache(maxsize=None)            # validated above: the cache would take 2.0 for 2
def _transition_series(order: int) -> dict:
    beta, dt = sp.symbols("beta dt", positive=True)
    F = sp.Matrix([[0, 1], [0, -beta]])
    T = (F * dt).exp().applyfunc(sp.simplify)
    series = T.applyfunc(lambda e: sp.series(e, dt, 0, order + 1).removeO())
    return {"F": F, "dt": dt, "T": T, "series": series}


@lru_cache(maxsize=None)
def position_integral():
    """r(t) from r̈ = a(t), r(t₀) = r₀, ṙ(t₀) = v₀ for a polynomial acceleration (Hanzl §7.1).

    Returns
    -------
    dict
        ``t``, ``t0``, ``r0``, ``v0``, ``a`` (a(t) = a₀ + a₁t + a₂t²) and ``r`` (the solution of
        the differential equation by sympy's ``dsolve``).

    Raises
    ------
    None
        Builds a fixed problem.

    References
    ----------
    Hanzl, Fotogrammetrie, Modul 01, §7.1 (seed 002 lines 1306–1310).

    Examples
    --------
    >>> d = position_integral()
    >>> sp.simplify(d["r"].diff(d["t"], 2) - d["a"])
    0
    """
    t, t0, r0, v0 = sp.symbols("t t0 r0 v0", real=True)
    a0, a1, a2 = sp.symbols("a0 a1 a2", real=True)
    a = a0 + a1 * t + a2 * t ** 2
    r = sp.Function("r")
    solution = sp.dsolve(sp.Eq(r(t).diff(t, 2), a), r(t), ics={r(t0): r0, r(t).diff(t).subs(t, t0): v0})
    return {"t": t, "t0": t0, "r0": r0, "v0": v0, "a": a, "r": sp.expand(solution.rhs)}
