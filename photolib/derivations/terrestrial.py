"""Terrestrial photogrammetry in sympy: Chapter 11, §11.6–11.8.

The models behind :mod:`photolib.terrestrial`:

* the geometric condition equations of §11.6 — object distance (11.6.1), base length (11.6.2),
  centre-to-point distance (11.6.3), vertical line (11.6.4), horizontal plane (11.6.5, printed
  "Z_i − Z_i", read Z_i − Z_j) — as :class:`~photolib.derivations.model.Model` objects whose
  Jacobians are the coefficients of the correction equations (11.6.7);
* the book's plane condition (11.6.6), **identically zero** (its third row is the difference of
  the first two), and a correct replacement: four points i, j, k, l are coplanar when
  det[P_j − P_i; P_k − P_i; P_l − P_i] = 0;
* the collinearity equations in polar coordinates (11.6.9), with the bearing φ (from +Y toward
  +X) and the vertical angle ν, and their linearisation (11.6.10) in ω, α, κ (A = A_ω A_α A_κ
  of (1.3.2): the terrestrial sequence, ω ≈ 90°);
* the normal-case intersection (11.8.1) → (11.8.2) and the partial derivatives behind the
  accuracy formulas (11.8.4); the scale of the linear model linking (11.7.12).

Every function returns sympy objects; nothing is lambdified at import time.
"""

from __future__ import annotations

from functools import lru_cache

import sympy as sp

from ..errors import InputError
from .model import Model
from .rotation import rotation_matrix_symbolic
from .symbols import omega, alpha, kappa, f, x0, y0, x, y

__all__ = ["point_symbols", "distance_condition_model", "base_condition_model", "centre_distance_model",
           "vertical_line_model", "horizontal_plane_model", "book_plane_determinant", "coplanarity4_model",
           "polar_collinearity_model", "normal_case_relations", "linking_scale_symbolic"]

phi, nu, D = sp.symbols("varphi nu D", real=True)


def point_symbols(name: str) -> tuple:
    """The three coordinate symbols X_name, Y_name, Z_name of one point.

    Parameters
    ----------
    name : str
        The point's label, e.g. ``"i"`` or ``"Si"``.

    Returns
    -------
    tuple of sympy.Symbol
        (X_name, Y_name, Z_name).

    Raises
    ------
    InputError
        If ``name`` is not a non-empty string without spaces.

    References
    ----------
    Chibunichev (2022), §11.6, eqs. (11.6.1)–(11.6.6).

    Examples
    --------
    >>> point_symbols("i")
    (X_i, Y_i, Z_i)
    """
    if not isinstance(name, str) or not name or " " in name:
        raise InputError(f"a point label must be a non-empty string without spaces, got {name!r}")
    return sp.symbols(f"X_{name} Y_{name} Z_{name}", real=True)


def _dist(P, Q):
    return sp.sqrt(sum((p - q) ** 2 for p, q in zip(P, Q)))


@lru_cache(maxsize=None)
def distance_condition_model() -> Model:
    """(11.6.1): √((X_i − X_j)² + (Y_i − Y_j)² + (Z_i − Z_j)²) − D_ij = 0.

    Returns
    -------
    Model
        Parameters X_i, Y_i, Z_i, X_j, Y_j, Z_j; datum D (the measured distance).

    Raises
    ------
    InputError
        Never (the model is fixed).

    References
    ----------
    Chibunichev (2022), §11.6, eqs. (11.6.1), (11.6.7).

    Examples
    --------
    >>> m = distance_condition_model()
    >>> m.jacobian()[0, 0]
    (X_i - X_j)/sqrt((X_i - X_j)**2 + (Y_i - Y_j)**2 + (Z_i - Z_j)**2)
    """
    Pi, Pj = point_symbols("i"), point_symbols("j")
    return Model("terrestrial-distance", Pi + Pj, (D,), (_dist(Pi, Pj) - D,))


@lru_cache(maxsize=None)
def base_condition_model() -> Model:
    """(11.6.2): the distance between the projection centres S_i, S_j equals the measured base B.

    Returns
    -------
    Model
        Parameters X_Si, Y_Si, Z_Si, X_Sj, Y_Sj, Z_Sj; datum B.

    Raises
    ------
    InputError
        Never (the model is fixed).

    References
    ----------
    Chibunichev (2022), §11.6, eq. (11.6.2).

    Examples
    --------
    >>> base_condition_model().parameters[:3]
    (X_Si, Y_Si, Z_Si)
    """
    Si, Sj = point_symbols("Si"), point_symbols("Sj")
    B = sp.Symbol("B", real=True)
    return Model("terrestrial-base", Si + Sj, (B,), (_dist(Si, Sj) - B,))


@lru_cache(maxsize=None)
def centre_distance_model() -> Model:
    """(11.6.3): the distance from the projection centre S_i to the object point i equals D_i.

    Returns
    -------
    Model
        Parameters X_i, Y_i, Z_i, X_Si, Y_Si, Z_Si; datum D.

    Raises
    ------
    InputError
        Never (the model is fixed).

    References
    ----------
    Chibunichev (2022), §11.6, eq. (11.6.3).

    Examples
    --------
    >>> len(centre_distance_model().parameters)
    6
    """
    Pi, Si = point_symbols("i"), point_symbols("Si")
    return Model("terrestrial-centre-distance", Pi + Si, (D,), (_dist(Pi, Si) - D,))


@lru_cache(maxsize=None)
def vertical_line_model() -> Model:
    """(11.6.4): two points on one vertical line, X_i − X_j = 0 and Y_i − Y_j = 0.

    Returns
    -------
    Model
        Parameters X_i, Y_i, Z_i, X_j, Y_j, Z_j; no data; two residuals.

    Raises
    ------
    InputError
        Never (the model is fixed).

    References
    ----------
    Chibunichev (2022), §11.6, eq. (11.6.4).

    Examples
    --------
    >>> vertical_line_model().jacobian().tolist()
    [[1, 0, 0, -1, 0, 0], [0, 1, 0, 0, -1, 0]]
    """
    Pi, Pj = point_symbols("i"), point_symbols("j")
    return Model("terrestrial-vertical", Pi + Pj, (), (Pi[0] - Pj[0], Pi[1] - Pj[1]))


@lru_cache(maxsize=None)
def horizontal_plane_model() -> Model:
    """(11.6.5), read Z_i − Z_j = 0 (the OCR prints Z_i − Z_i): two points at one height.

    Returns
    -------
    Model
        Parameters X_i, Y_i, Z_i, X_j, Y_j, Z_j; no data; one residual.

    Raises
    ------
    InputError
        Never (the model is fixed).

    References
    ----------
    Chibunichev (2022), §11.6, eq. (11.6.5).

    Examples
    --------
    >>> horizontal_plane_model().jacobian().tolist()
    [[0, 0, 1, 0, 0, -1]]
    """
    Pi, Pj = point_symbols("i"), point_symbols("j")
    return Model("terrestrial-horizontal", Pi + Pj, (), (Pi[2] - Pj[2],))


def book_plane_determinant() -> sp.Expr:
    """The determinant of (11.6.6) as printed, expanded: it is identically zero.

    Rows P_i − P_j, P_i − P_k, P_j − P_k: the third is the second minus the first, so the
    determinant vanishes for any three points — the printed condition constrains nothing.

    Returns
    -------
    sympy.Expr
        The expanded determinant (``0``).

    Raises
    ------
    InputError
        Never.

    References
    ----------
    Chibunichev (2022), §11.6, eq. (11.6.6).

    Examples
    --------
    >>> book_plane_determinant()
    0
    """
    Pi, Pj, Pk = (sp.Matrix(point_symbols(n)) for n in "ijk")
    M = sp.Matrix.vstack((Pi - Pj).T, (Pi - Pk).T, (Pj - Pk).T)
    return sp.expand(M.det())


@lru_cache(maxsize=None)
def coplanarity4_model() -> Model:
    """The corrected plane condition: det[P_j − P_i; P_k − P_i; P_l − P_i] = 0 for four points.

    Six times the signed volume of the tetrahedron i, j, k, l; zero exactly when the fourth
    point lies in the plane of the first three (write one equation per extra point l).

    Returns
    -------
    Model
        Parameters X_i … Z_l (12); no data; one residual.

    Raises
    ------
    InputError
        Never (the model is fixed).

    References
    ----------
    Chibunichev (2022), §11.6, eq. (11.6.6) (corrected).

    Examples
    --------
    >>> len(coplanarity4_model().parameters)
    12
    """
    P = [sp.Matrix(point_symbols(n)) for n in "ijkl"]
    M = sp.Matrix.vstack((P[1] - P[0]).T, (P[2] - P[0]).T, (P[3] - P[0]).T)
    params = tuple(s for n in "ijkl" for s in point_symbols(n))
    return Model("terrestrial-coplanarity4", params, (), (sp.expand(M.det()),))


def _polar_direction(distance=1):
    return sp.Matrix([distance * sp.cos(nu) * sp.sin(phi), distance * sp.cos(nu) * sp.cos(phi),
                      distance * sp.sin(nu)])


@lru_cache(maxsize=None)
def polar_collinearity_model(with_distance: bool = False) -> Model:
    """(11.6.9): F_x = x₀ − f·U/W − x, F_y = y₀ − f·V/W − y with (U, V, W) = Aᵀ(cos ν sin φ, cos ν cos φ, sin ν).

    The collinearity equations (11.6.8) with X − X_S = D cos ν sin φ, Y − Y_S = D cos ν cos φ,
    Z − Z_S = D sin ν; D cancels (``with_distance=True`` keeps it, to show that it does).
    The Jacobian by (ω, α, κ) gives the coefficients a₁…a₃, b₁…b₃ of (11.6.10).

    Parameters
    ----------
    with_distance : bool
        Keep the distance D in the direction vector (it cancels).

    Returns
    -------
    Model
        Parameters ω, α, κ (A = A_ω A_α A_κ, (1.3.2)); data φ, ν, x, y, f, x₀, y₀
        (and D with ``with_distance``).

    Raises
    ------
    InputError
        If ``with_distance`` is not a bool.

    References
    ----------
    Chibunichev (2022), §11.6, eqs. (11.6.8)–(11.6.10); §1.3, eq. (1.3.2).

    Examples
    --------
    >>> m = polar_collinearity_model(with_distance=True)
    >>> import sympy as sp
    >>> sp.simplify(sp.diff(m.residuals[0], D))
    0
    """
    if not isinstance(with_distance, bool):
        raise InputError(f"with_distance must be True or False, got {with_distance!r}")
    A = rotation_matrix_symbolic("wak")
    d = A.T * _polar_direction(D if with_distance else 1)
    Fx = x0 - f * d[0] / d[2] - x
    Fy = y0 - f * d[1] / d[2] - y
    data = (phi, nu, x, y, f, x0, y0) + ((D,) if with_distance else ())
    return Model("terrestrial-polar-collinearity", (omega, alpha, kappa), data, (Fx, Fy))


def normal_case_relations() -> dict:
    """(11.8.1) in the normal case and the derivatives behind (11.8.4), derived with sympy.

    N = (B_X Y′₂ − B_Y X′₂)/(X′₁Y′₂ − X′₂Y′₁) is solved from N₁X′₁ = B + N₂X′₂ (X and Y
    rows); with ω = 90°, α = κ = 0 the ray is A(x, y, −f)ᵀ = (x, f, y)ᵀ and N = B_X/p (11.8.2).

    Returns
    -------
    dict
        ``"N_general"`` (solved N), ``"A_normal"`` (the matrix), ``"ray_normal"`` (A(x, y, −f)ᵀ),
        ``"N_normal"`` (B_X/p), ``"XYZ"`` ((11.8.2) in x₁, y₁, p), ``"dY_dp"``, ``"dX_dx1"``,
        ``"dX_dp"``, ``"dZ_dy1"`` and ``"symbols"``.

    Raises
    ------
    InputError
        Never.

    References
    ----------
    Chibunichev (2022), §11.8, eqs. (11.8.1)–(11.8.4); §2.4, eq. (2.4.12).

    Examples
    --------
    >>> r = normal_case_relations()
    >>> r["N_normal"]
    B_X/p
    >>> r["dY_dp"]
    -B_X*f/p**2
    """
    N1, N2, BX, BY = sp.symbols("N_1 N_2 B_X B_Y", real=True)
    X1, Y1, X2, Y2 = sp.symbols("Xp_1 Yp_1 Xp_2 Yp_2", real=True)      # X′₁, Y′₁, X′₂, Y′₂
    sol = sp.solve([N1 * X1 - (BX + N2 * X2), N1 * Y1 - (BY + N2 * Y2)], [N1, N2], dict=True)[0]
    A = rotation_matrix_symbolic("wak", sp.pi / 2, 0, 0)
    x1, y1, x2, p = sp.symbols("x_1 y_1 x_2 p", real=True)
    ray = A * sp.Matrix([x, y, -f])
    Nn = sp.simplify(sol[N1].subs({X1: x1, Y1: f, X2: x2, Y2: f, BY: 0}).subs(x1, x2 + p))
    XYZ = sp.Matrix([Nn * x1, Nn * f, Nn * y1])
    return {"N_general": sol[N1], "A_normal": A, "ray_normal": ray, "N_normal": Nn, "XYZ": XYZ,
            "dY_dp": sp.diff(XYZ[1], p), "dX_dx1": sp.diff(XYZ[0], x1), "dX_dp": sp.diff(XYZ[0], p),
            "dZ_dy1": sp.diff(XYZ[2], y1),
            "symbols": {"B_X": BX, "B_Y": BY, "x_1": x1, "y_1": y1, "x_2": x2, "p": p, "f": f,
                        "Xp_1": X1, "Yp_1": Y1, "Xp_2": X2, "Yp_2": Y2}}


def linking_scale_symbolic() -> sp.Expr:
    """(11.7.12): √(c₁₁² + c₁₂² + c₁₃²) for C = t·A (11.7.3), simplified — equals t.

    Returns
    -------
    sympy.Expr
        ``t``.

    Raises
    ------
    InputError
        Never.

    References
    ----------
    Chibunichev (2022), §11.7, eqs. (11.7.3), (11.7.11)–(11.7.12).

    Examples
    --------
    >>> linking_scale_symbolic()
    t
    """
    t = sp.Symbol("t", positive=True)
    C = t * rotation_matrix_symbolic("wak")
    return sp.simplify(sp.sqrt(C[0, 0] ** 2 + C[0, 1] ** 2 + C[0, 2] ** 2))
