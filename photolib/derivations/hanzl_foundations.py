"""Sympy forms of Hanzl's mathematical foundations — Hanzl, *Fotogrammetrie, Modul 01*, §2.1–§2.6.

Seed 002 lines 131–342. Each printed formula is transcribed here ("printed") next to its derivation
from first principles ("derived"), so that the book layer (``photolib.book.hanzl_foundations``) can
compare them by exact zero tests:

* §2.1 plane rotation from the direction cosines, the orthonormality conditions (1.2)
  (:func:`plane_rotation`);
* §2.2 R = R_ω R_φ R_κ, the printed element table (line 191) and the step equations of lines
  175–179 (:func:`hanzl_rotation`, :func:`printed_rotation_table`, :func:`rotation_from_steps`);
* §2.3 the collinearity equations (2.2), the inverse (2.3) and the DLT form (2.4)
  (:func:`collinearity_forms`, :func:`inverse_forms`, :func:`dlt_coefficients`);
* §2.4 the plane projective transformation (2.5) (:func:`plane_projective_coefficients`);
* §2.5 the affine transformation and its decomposition (line 285) (:func:`affine_forms`);
* §2.6 the least-squares residuals and redundancy (line 317–325) and the Danish weight function
  (line 336) (:func:`least_squares_forms`, :func:`danish_weight_forms`).

Hanzl's R = R_ω R_φ R_κ is the Russian textbook's A = A_ω A_α A_κ (1.3.2) with φ ≡ α
(:func:`photolib.derivations.rotation.rotation_matrix_symbolic` with ``order="wak"``); his camera
constant c is the book's f, his X₀, Y₀, Z₀ the book's X_S, Y_S, Z_S.
"""

from __future__ import annotations

from functools import lru_cache

import sympy as sp

from ..errors import InputError
from .rotation import elementary_rotations
from .symbols import X, Y, Z, kappa, omega, x, x0, y, y0

__all__ = ["PHI", "C", "R_SYMBOLS", "hanzl_rotation", "printed_rotation_table", "rotation_from_steps",
           "plane_rotation", "collinearity_forms", "inverse_forms", "dlt_coefficients",
           "plane_projective_coefficients", "affine_forms", "least_squares_forms", "danish_weight_forms"]

PHI = sp.Symbol("phi", real=True)
"""Hanzl's φ (rotation about y), the book's α."""
C = sp.Symbol("c", positive=True)
"""Hanzl's camera constant c (the book's f)."""
R_SYMBOLS = sp.Matrix(3, 3, lambda i, j: sp.Symbol(f"r{i + 1}{j + 1}", real=True))
"""The elements r_ij of R as plain symbols, for the forms (2.2)–(2.5)."""
XC, YC, ZC = sp.symbols("X_0 Y_0 Z_0", real=True)          # projection centre (Hanzl's X₀, Y₀, Z₀)


def hanzl_rotation(w=omega, p=PHI, k=kappa) -> sp.Matrix:
    """R = R_ω R_φ R_κ of Hanzl §2.2 (lines 181–187), the product of the elementary rotations.

    Parameters
    ----------
    w, p, k : sympy.Expr or number, optional
        ω, φ, κ (default the symbols ``omega``, :data:`PHI`, ``kappa``).

    Returns
    -------
    sympy.Matrix
        3×3; it maps image-axis components to object-axis components, (X, Y, Z)ᵀ = R (x, y, z)ᵀ.

    Raises
    ------
    InputError
        An angle that is not a sympy expression or a number.

    References
    ----------
    Hanzl, Fotogrammetrie, Modul 01, §2.2 (seed 002 lines 171–199); Chibunichev (2022), §1.3, eq. (1.3.2).

    Examples
    --------
    >>> hanzl_rotation()[0, 2]
    sin(phi)
    """
    Rw, Rp, Rk = elementary_rotations(w, p, k)
    return Rw * Rp * Rk


def printed_rotation_table() -> sp.Matrix:
    """The element table of R exactly as the seed prints it (line 191), r₃₂ with its minus sign.

    Returns
    -------
    sympy.Matrix
        3×3 in ω, φ (:data:`PHI`), κ.

    Raises
    ------
    InputError
        Never (no input).

    References
    ----------
    Hanzl, Fotogrammetrie, Modul 01, §2.2 (seed 002 line 191).

    Examples
    --------
    >>> sp.simplify(printed_rotation_table()[2, 1] - hanzl_rotation()[2, 1]) != 0     # the r32 sign slip
    True
    """
    c, s, w, p, k = sp.cos, sp.sin, omega, PHI, kappa
    return sp.Matrix([
        [c(p) * c(k), -c(p) * s(k), s(p)],
        [c(w) * s(k) + s(w) * s(p) * c(k), c(w) * c(k) - s(w) * s(p) * s(k), -s(w) * c(p)],
        [s(w) * s(k) - c(w) * s(p) * c(k), s(w) * c(k) - c(w) * s(p) * s(k), c(w) * c(p)]])


def rotation_from_steps() -> sp.Matrix:
    """The matrix of the three printed step equations (lines 175–179): κ first, then φ, then ω.

    ẋ = x cos κ − y sin κ, ẏ = x sin κ + y cos κ, ż = z; ẍ = ẋ cos φ + ż sin φ, ÿ = ẏ,
    z̈ = −ẋ sin φ + ż cos φ; X = ẍ, Y = ÿ cos ω − z̈ sin ω, Z = ÿ sin ω + z̈ cos ω.

    Returns
    -------
    sympy.Matrix
        M with (X, Y, Z)ᵀ = M (x, y, z)ᵀ.

    Raises
    ------
    InputError
        Never (no input).

    References
    ----------
    Hanzl, Fotogrammetrie, Modul 01, §2.2 (seed 002 lines 175–179).

    Examples
    --------
    >>> sp.simplify(rotation_from_steps() - hanzl_rotation()) == sp.zeros(3, 3)
    True
    """
    xs, ys, zs = sp.symbols("x_s y_s z_s", real=True)
    c, s = sp.cos, sp.sin
    xd, yd, zd = xs * c(kappa) - ys * s(kappa), xs * s(kappa) + ys * c(kappa), zs
    xdd, ydd, zdd = xd * c(PHI) + zd * s(PHI), yd, -xd * s(PHI) + zd * c(PHI)
    out = [xdd, ydd * c(omega) - zdd * s(omega), ydd * s(omega) + zdd * c(omega)]
    return sp.Matrix([[sp.expand(e).coeff(v) for v in (xs, ys, zs)] for e in out])


def plane_rotation(alpha=sp.Symbol("alpha", real=True)) -> dict:
    """§2.1: the plane rotation from the direction cosines and as printed, and the conditions (1.2).

    Parameters
    ----------
    alpha : sympy.Expr, optional
        The rotation angle α.

    Returns
    -------
    dict
        ``"from_cosines"``: [[cos(xX), cos(yX)], [cos(xY), cos(yY)]] with cos(xX) = cos α,
        cos(xY) = cos(270° + α), cos(yX) = cos(90° + α), cos(yY) = cos α (lines 143–147);
        ``"printed"``: [[cos α, −sin α], [sin α, cos α]] (line 149); ``"conditions_printed"``:
        the three right-hand sides of (1.2) minus (1, 1, 0), r₁₁² + r₁₂² − 1, r₂₁² + r₂₂² − 1,
        r₁₁r₁₂ + r₂₁r₂₂ (lines 155–163), with r_ij of the printed matrix; ``"conditions_vectors"``:
        iᵀi − 1, jᵀj − 1, iᵀj for the unit vectors of line 151.

    Raises
    ------
    InputError
        ``alpha`` not a sympy expression or number.

    References
    ----------
    Hanzl, Fotogrammetrie, Modul 01, §2.1 (seed 002 lines 137–169).

    Examples
    --------
    >>> out = plane_rotation()
    >>> sp.simplify(out["from_cosines"] - out["printed"]) == sp.zeros(2, 2)
    True
    """
    try:
        a = sp.sympify(alpha, strict=True)
    except (sp.SympifyError, TypeError) as exc:
        raise InputError(f"alpha must be a sympy expression or a number, got {alpha!r}") from exc
    c = sp.cos
    deg = sp.pi / 180
    from_cosines = sp.Matrix([[c(a), c(90 * deg + a)], [c(270 * deg + a), c(a)]])
    R = sp.Matrix([[sp.cos(a), -sp.sin(a)], [sp.sin(a), sp.cos(a)]])
    i, j = sp.Matrix([sp.cos(a), sp.sin(a)]), sp.Matrix([-sp.sin(a), sp.cos(a)])
    printed = (R[0, 0] ** 2 + R[0, 1] ** 2 - 1, R[1, 0] ** 2 + R[1, 1] ** 2 - 1, R[0, 0] * R[0, 1] + R[1, 0] * R[1, 1])
    vectors = ((i.T * i)[0] - 1, (j.T * j)[0] - 1, (i.T * j)[0])
    return {"from_cosines": from_cosines, "printed": R, "conditions_printed": printed,
            "conditions_vectors": vectors}


@lru_cache(maxsize=None)
def collinearity_forms() -> dict:
    """§2.3: the collinearity equations (2.2) as printed and as derived from (2.1).

    Derivation: (X′ − X′₀, Y′ − Y′₀, Z′ − Z′₀)ᵀ = Rᵀ(X − X₀, Y − Y₀, Z − Z₀)ᵀ (2.1 multiplied by
    Rᵀ, lines 219–225) put into the collinearity condition (x − x₀)/(z − z₀) = (X′ − X′₀)/(Z′ − Z′₀)
    with z = 0, z₀ = c (line 227).

    Returns
    -------
    dict
        ``"printed"`` and ``"derived"``: (x, y) tuples in the symbols r_ij (:data:`R_SYMBOLS`),
        X, Y, Z, X₀, Y₀, Z₀, x₀, y₀, c; ``"rotated"``: the three printed lines of 2.1 × Rᵀ
        (left-hand sides) and ``"rotated_derived"``: Rᵀ(X − X₀).

    Raises
    ------
    InputError
        Never (no input).

    References
    ----------
    Hanzl, Fotogrammetrie, Modul 01, §2.3, eqs. (2.1)–(2.2) (seed 002 lines 201–231);
    Chibunichev (2022), §1.4, eq. (1.4.12).

    Examples
    --------
    >>> f = collinearity_forms()
    >>> [sp.simplify(p - d) for p, d in zip(f["printed"], f["derived"])]
    [0, 0]
    """
    r = R_SYMBOLS
    d = sp.Matrix([X - XC, Y - YC, Z - ZC])
    u = r.T * d                                                       # (X' − X'0, Y' − Y'0, Z' − Z'0)
    zz = 0 - C                                                        # z − z0 with z = 0, z0 = c
    derived = (x0 + zz * u[0] / u[2], y0 + zz * u[1] / u[2])
    den = r[0, 2] * (X - XC) + r[1, 2] * (Y - YC) + r[2, 2] * (Z - ZC)
    printed = (x0 - C * (r[0, 0] * (X - XC) + r[1, 0] * (Y - YC) + r[2, 0] * (Z - ZC)) / den,
               y0 - C * (r[0, 1] * (X - XC) + r[1, 1] * (Y - YC) + r[2, 1] * (Z - ZC)) / den)
    rotated = sp.Matrix([r[0, 0] * (X - XC) + r[1, 0] * (Y - YC) + r[2, 0] * (Z - ZC),
                         r[0, 1] * (X - XC) + r[1, 1] * (Y - YC) + r[2, 1] * (Z - ZC),
                         r[0, 2] * (X - XC) + r[1, 2] * (Y - YC) + r[2, 2] * (Z - ZC)])
    return {"printed": printed, "derived": derived, "rotated": rotated, "rotated_derived": u}


@lru_cache(maxsize=None)
def inverse_forms() -> dict:
    """§2.3: the inverse (2.3), X and Y from x, y and a known Z, as printed and as derived.

    Derivation from (X − X₀, Y − Y₀, Z − Z₀)ᵀ = m R (x − x₀, y − y₀, −c)ᵀ (line 235): the third
    row gives m, the first two X and Y.

    Returns
    -------
    dict
        ``"printed"`` and ``"derived"``: (X, Y) in r_ij, x, y, x₀, y₀, c, X₀, Y₀, Z₀, Z.

    Raises
    ------
    InputError
        Never (no input).

    References
    ----------
    Hanzl, Fotogrammetrie, Modul 01, §2.3, eq. (2.3) (seed 002 lines 233–243); Chibunichev (2022),
    §1.4, eq. (1.4.7).

    Examples
    --------
    >>> f = inverse_forms()
    >>> [sp.simplify(p - d) for p, d in zip(f["printed"], f["derived"])]
    [0, 0]
    """
    r = R_SYMBOLS
    v = r * sp.Matrix([x - x0, y - y0, -C])
    m = (Z - ZC) / v[2]
    derived = (XC + m * v[0], YC + m * v[1])
    den = r[2, 0] * (x - x0) + r[2, 1] * (y - y0) - r[2, 2] * C
    printed = (XC + (Z - ZC) * (r[0, 0] * (x - x0) + r[0, 1] * (y - y0) - r[0, 2] * C) / den,
               YC + (Z - ZC) * (r[1, 0] * (x - x0) + r[1, 1] * (y - y0) - r[1, 2] * C) / den)
    return {"printed": printed, "derived": derived}


@lru_cache(maxsize=None)
def dlt_coefficients() -> dict:
    """§2.3: the eleven L of the DLT form (2.4) in terms of the orientation, and (2.4) itself.

    Writing (2.2) as one fraction, x = (x₀u₃ − c u₁)/u₃ with u = Rᵀ(X − X₀), and dividing
    numerator and denominator by the constant term D = −(r₁₃X₀ + r₂₃Y₀ + r₃₃Z₀) of u₃ gives
    ratios of linear forms in X, Y, Z whose denominators end in + 1 — eleven coefficients.

    Returns
    -------
    dict
        ``"L"``: tuple of the 11 expressions L₁ … L₁₁; ``"printed"``: (x, y) of (2.4) in symbols
        L1 … L11; ``"substituted"``: (2.4) with the L's replaced by their expressions;
        ``"collinearity"``: (2.2) as derived; ``"symbols"``: the L symbols.

    Raises
    ------
    InputError
        Never (no input).

    References
    ----------
    Hanzl, Fotogrammetrie, Modul 01, §2.3, eq. (2.4) (seed 002 line 245); Chibunichev (2022),
    §4.3 (DLT).

    Examples
    --------
    >>> out = dlt_coefficients()
    >>> len(out["L"]), sp.simplify(out["substituted"][0] - out["collinearity"][0])
    (11, 0)
    """
    r = R_SYMBOLS
    u = r.T * sp.Matrix([X - XC, Y - YC, Z - ZC])
    D = -(r[0, 2] * XC + r[1, 2] * YC + r[2, 2] * ZC)
    nums = [sp.expand(x0 * u[2] - C * u[0]), sp.expand(y0 * u[2] - C * u[1])]
    L = []
    for num in nums:
        L += [sp.simplify(num.coeff(v) / D) for v in (X, Y, Z)]
        L.append(sp.simplify(num.subs({X: 0, Y: 0, Z: 0}) / D))
    L += [r[0, 2] / D, r[1, 2] / D, r[2, 2] / D]
    Ls = sp.symbols("L1:12", real=True)
    den = Ls[8] * X + Ls[9] * Y + Ls[10] * Z + 1
    printed = ((Ls[0] * X + Ls[1] * Y + Ls[2] * Z + Ls[3]) / den, (Ls[4] * X + Ls[5] * Y + Ls[6] * Z + Ls[7]) / den)
    sub = dict(zip(Ls, L))
    return {"L": tuple(L), "printed": printed, "substituted": tuple(e.xreplace(sub) for e in printed),
            "collinearity": collinearity_forms()["derived"], "symbols": Ls}


@lru_cache(maxsize=None)
def plane_projective_coefficients() -> dict:
    """§2.4: the plane projective transformation (2.5) from the inverse (2.3) at a constant Z.

    (2.3) is X = (ā₁x + ā₂y + ā₃)/(c̄₁x + c̄₂y + c̄₃) (line 251); dividing by c̄₃ gives (2.5)
    with a_i = ā_i/c̄₃, b_i = b̄_i/c̄₃, c_i = c̄_i/c̄₃ — eight coefficients.

    Returns
    -------
    dict
        ``"coefficients"``: the 8 expressions a₁, a₂, a₃, b₁, b₂, b₃, c₁, c₂ (Z the plane's height);
        ``"printed"``: (X, Y) of (2.5) in symbols; ``"substituted"``: with the expressions put in;
        ``"inverse"``: (2.3) as derived.

    Raises
    ------
    InputError
        Never (no input).

    References
    ----------
    Hanzl, Fotogrammetrie, Modul 01, §2.4, eq. (2.5) (seed 002 lines 249–259); Chibunichev (2022),
    §1.7, eq. (1.7.5), §4.1.

    Examples
    --------
    >>> out = plane_projective_coefficients()
    >>> len(out["coefficients"]), sp.simplify(out["substituted"][1] - out["inverse"][1])
    (8, 0)
    """
    X_, Y_ = inverse_forms()["derived"]
    nX, dX = sp.fraction(sp.together(X_))
    nY, dY = sp.fraction(sp.together(Y_))
    if sp.simplify(dX - dY) != 0:                    # pragma: no cover - a property of (2.3)
        raise InputError("(2.3): the two denominators differ")
    nX, nY, dd = sp.expand(nX), sp.expand(nY), sp.expand(dX)
    lin = lambda e: (e.coeff(x), e.coeff(y), e.subs({x: 0, y: 0}))
    aa, bb, cc = lin(nX), lin(nY), lin(dd)
    coef = tuple(sp.simplify(v / cc[2]) for v in (*aa, *bb, cc[0], cc[1]))
    a1, a2, a3, b1, b2, b3, c1, c2 = syms = sp.symbols("a1 a2 a3 b1 b2 b3 c1 c2", real=True)
    den = c1 * x + c2 * y + 1
    printed = ((a1 * x + a2 * y + a3) / den, (b1 * x + b2 * y + b3) / den)
    sub = dict(zip(syms, coef))
    return {"coefficients": coef, "printed": printed, "substituted": tuple(e.xreplace(sub) for e in printed),
            "inverse": (X_, Y_), "symbols": syms}


def affine_forms() -> dict:
    """§2.5: the affine transformation in its geometric form (line 279) and the decomposition (line 285).

    Returns
    -------
    dict
        ``"geometric"``: [[q_x cos α, −q_y sin(α + δα)], [q_x sin α, q_y cos(α + δα)]];
        ``"printed_decomposition"``: the four printed relations as expressions that vanish when
        they hold, q_x − √(a₁₁² + a₂₁²), q_y − √(a₁₂² + a₂₂²), tg α − a₂₁/a₁₁,
        tg(α + δα) + a₁₂/a₂₂, with a_ij of the geometric form put in; ``"symbols"``.

    Raises
    ------
    InputError
        Never (no input).

    References
    ----------
    Hanzl, Fotogrammetrie, Modul 01, §2.5 (seed 002 lines 275–285); Chibunichev (2022), §1.11,
    eq. (1.11.6).

    Examples
    --------
    >>> [sp.simplify(e) for e in affine_forms()["printed_decomposition"]]
    [0, 0, 0, 0]
    """
    qx, qy = sp.symbols("q_x q_y", positive=True)
    a, da = sp.symbols("alpha delta_alpha", real=True)
    A = sp.Matrix([[qx * sp.cos(a), -qy * sp.sin(a + da)], [qx * sp.sin(a), qy * sp.cos(a + da)]])
    a11, a12, a21, a22 = A[0, 0], A[0, 1], A[1, 0], A[1, 1]
    rel = (qx - sp.sqrt(a11 ** 2 + a21 ** 2), qy - sp.sqrt(a12 ** 2 + a22 ** 2),
           sp.tan(a) - a21 / a11, sp.tan(a + da) + a12 / a22)
    return {"geometric": A, "printed_decomposition": rel, "symbols": (qx, qy, a, da)}


def least_squares_forms(m: int = 3, n: int = 2) -> dict:
    """§2.6: the residuals of least squares as printed (line 317) and derived, and Σ r_i.

    A generic m × n design A (symbols a_ij), diagonal weights P (p_i), observations l:
    x̂ = (AᵀPA)⁻¹AᵀPl, v = A x̂ − l, Q_vv = P⁻¹ − A N⁻¹ Aᵀ.

    Parameters
    ----------
    m, n : int
        Size of the symbolic problem, 1 ≤ n < m ≤ 5.

    Returns
    -------
    dict
        ``"v"``: A x̂ − l; ``"printed_middle"``: (−A N⁻¹ Aᵀ + P⁻¹) P l as printed;
        ``"printed_final"``: −Q_vv P l; ``"redundancy"``: the diagonal of Q_vv P;
        ``"normalized_printed"`` / ``"normalized_qvv"``: w_i² σ₀² as |v_i √p_i|²/r_i and as v_i²/q_vv,ii;
        ``"A"``, ``"P"``, ``"l"``.

    Raises
    ------
    InputError
        m, n not integers with 1 ≤ n < m ≤ 5.

    References
    ----------
    Hanzl, Fotogrammetrie, Modul 01, §2.6 (seed 002 lines 317–325).

    Examples
    --------
    >>> out = least_squares_forms(3, 1)
    >>> sp.simplify(sum(out["redundancy"]))
    2
    """
    for value in (m, n):
        if isinstance(value, bool) or not isinstance(value, int):
            raise InputError(f"m and n must be integers, got {m!r}, {n!r}")
    if not 1 <= n < m <= 5:
        raise InputError(f"need 1 ≤ n < m ≤ 5 (a small symbolic problem), got m = {m}, n = {n}")
    return _least_squares_forms(m, n)


@lru_cache(maxsize=None)            # validated above: the cache would take 3.0 or True for 3 or 1
def _least_squares_forms(m: int, n: int) -> dict:
    A = sp.Matrix(m, n, lambda i, j: sp.Symbol(f"a{i + 1}{j + 1}", real=True))
    p = sp.symbols(f"p1:{m + 1}", positive=True)
    P = sp.diag(*p)
    l = sp.Matrix(sp.symbols(f"l1:{m + 1}", real=True))
    N = A.T * P * A
    Ninv = N.inv()
    xhat = Ninv * A.T * P * l
    v = A * xhat - l
    Qvv = P.inv() - A * Ninv * A.T
    middle = (-A * Ninv * A.T + P.inv()) * P * l
    final = -Qvv * P * l
    red = [(Qvv * P)[i, i] for i in range(m)]
    w_printed = [(v[i] * sp.sqrt(p[i])) ** 2 / red[i] for i in range(m)]
    w_qvv = [v[i] ** 2 / Qvv[i, i] for i in range(m)]
    return {"v": v, "printed_middle": middle, "printed_final": final, "redundancy": red,
            "normalized_printed": w_printed, "normalized_qvv": w_qvv, "A": A, "P": P, "l": l}


def danish_weight_forms() -> dict:
    """§2.6: the Danish weight function as the OCR gives it (line 336) and as reconstructed.

    Returns
    -------
    dict
        ``"printed"``: −0.05 t^d; ``"derived"``: exp(−0.05 t^d) (t = |v_i √p_i|/σ₀ ≥ 0, d > 0);
        ``"symbols"``: (t, d).

    Raises
    ------
    InputError
        Never (no input).

    References
    ----------
    Hanzl, Fotogrammetrie, Modul 01, §2.6, Obr. 2.5 (seed 002 lines 334–340).

    Examples
    --------
    >>> f = danish_weight_forms(); t, d = f["symbols"]
    >>> f["derived"].subs({t: 0, d: 3}), f["printed"].subs({t: 0, d: 3})
    (1, 0)
    """
    t, d = sp.symbols("t d", positive=True)
    k = sp.Rational(5, 100)
    return {"printed": -k * t ** d, "derived": sp.exp(-k * t ** d), "symbols": (t, d)}
