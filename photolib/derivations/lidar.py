"""Laser-scanning models in sympy: Chapter 9, §9.1, §9.4, §9.7, §9.8, §9.11.

* :func:`triangulation_depth_model` — the triangulation scanner (9.4.4) derived from its
  geometry (camera at the origin, laser at (B, 0), beam X = B − Z·tan α, image p = f·X/Z) and
  its derivative ∂Z/∂p = −Z²/(fB), which is (9.4.5).
* :func:`ray_plane_model` — (9.4.8) solved for N: N = −(A·X_S + B·Y_S + C·Z_S + D)/(A·X′ +
  B·Y′ + C·Z′); the printed (9.4.9) lacks the minus sign.
* :func:`plane_model` — a plane with unit normal n = (cos a cos b, sin a cos b, sin b) and
  distance p (the parametrisation of (9.11.1)); the residual n·X − p of a point and its
  Jacobian by (a, b, p) drive the least-squares plane fit of (9.4.7) (laser plane P3).
* :func:`mobile_mapping_model` — the georeferencing (9.8.3) of a scanner point with the lever
  arm r_GNSS/S (IMU axes) and the boresight A_IMU/S(Δω, Δα, Δκ) as the six unknowns of the §9.8
  calibration; the residual is R_M(model) − R_M(known target).
* :func:`scanner_camera_rotation` — the built-in camera on a TLS head (§9.7): A = A_κ A_ω with
  κ = −φ_k, ω = 90° + ν_k (the κ–α–ω sequence (1.3.4), α = 0), whose viewing direction −z is the
  unit vector (cos ν sin φ, cos ν cos φ, sin ν) of (9.4.1)/(9.7.7) corrected.

The numeric functions (``*_functions``) are lambdified once (``functools.lru_cache``).
"""

from __future__ import annotations

from functools import lru_cache

import sympy as sp

from .model import _lambdified_parts
from .rotation import rotation_matrix_symbolic

__all__ = ["triangulation_depth_model", "ray_plane_model", "plane_model", "plane_functions",
           "mobile_mapping_model", "mobile_mapping_functions", "scanner_camera_rotation",
           "MOBILE_PARAMETERS"]

MOBILE_PARAMETERS = ("lever_x", "lever_y", "lever_z", "d_omega", "d_alpha", "d_kappa")
"""Names of the six unknowns of the §9.8 lever-arm/boresight calibration."""


def triangulation_depth_model():
    """Depth of a triangulation scanner solved from its geometry, (9.4.4), and ∂Z/∂p, (9.4.5).

    Returns
    -------
    dict
        ``symbols`` (p, f, B, alpha), ``Z`` (sympy solution of p = f·(B − Z tan α)/Z),
        ``dZ_dp`` and ``printed`` (B·f/(p + f tan α)).

    Raises
    ------
    None
        Builds a fixed model; takes no input.

    References
    ----------
    Chibunichev (2022), §9.4, eqs. (9.4.4), (9.4.5).

    Examples
    --------
    >>> m = triangulation_depth_model()
    >>> import sympy as sp
    >>> sp.simplify(m["Z"] - m["printed"])
    0
    """
    p, f, B, a, Z = sp.symbols("p f B alpha Z", positive=True)
    beam_X = B - Z * sp.tan(a)
    solution = sp.solve(sp.Eq(p, f * beam_X / Z), Z)[0]
    printed = B * f / (p + f * sp.tan(a))
    return {"symbols": (p, f, B, a), "Z": solution, "dZ_dp": sp.diff(solution, p), "printed": printed}


def ray_plane_model():
    """The ray–plane intersection (9.4.8) solved for the scale N (the corrected (9.4.9)).

    Returns
    -------
    dict
        ``symbols`` (A, B, C, D, X_S, Y_S, Z_S, X′, Y′, Z′), ``N`` (the solution) and
        ``printed`` (the book's (9.4.9), without the minus sign).

    Raises
    ------
    None
        Builds a fixed model; takes no input.

    References
    ----------
    Chibunichev (2022), §9.4, eqs. (9.4.8), (9.4.9).

    Examples
    --------
    >>> m = ray_plane_model()
    >>> import sympy as sp
    >>> sp.simplify(m["N"] + m["printed"])
    0
    """
    A, B, C, D = sp.symbols("A B C D", real=True)
    XS, YS, ZS, Xp, Yp, Zp, N = sp.symbols("X_S Y_S Z_S X' Y' Z' N", real=True)
    eq = A * (XS + N * Xp) + B * (YS + N * Yp) + C * (ZS + N * Zp) + D
    solution = sp.solve(eq, N)[0]
    printed = (A * XS + B * YS + C * ZS + D) / (A * Xp + B * Yp + C * Zp)
    return {"symbols": (A, B, C, D, XS, YS, ZS, Xp, Yp, Zp), "N": solution, "printed": printed,
            "equation": eq}


def plane_model():
    """Residual of a point from the plane n(a, b)·X − p = 0 with n = (cos a cos b, sin a cos b, sin b).

    Returns
    -------
    dict
        ``parameters`` (a, b, p), ``data`` (X, Y, Z), ``residual`` and ``jacobian`` (1×3).

    Raises
    ------
    None
        Builds a fixed model; takes no input.

    References
    ----------
    Chibunichev (2022), §9.4, eq. (9.4.7); §9.11, eq. (9.11.1).

    Examples
    --------
    >>> m = plane_model()
    >>> m["jacobian"].shape
    (1, 3)
    """
    a, b, p = sp.symbols("a b p", real=True)
    X, Y, Z = sp.symbols("X Y Z", real=True)
    residual = X * sp.cos(a) * sp.cos(b) + Y * sp.sin(a) * sp.cos(b) + Z * sp.sin(b) - p
    return {"parameters": (a, b, p), "data": (X, Y, Z), "residual": residual,
            "jacobian": sp.Matrix([residual]).jacobian([a, b, p])}


@lru_cache(maxsize=None)
def plane_functions():
    """Lambdified residual and Jacobian of :func:`plane_model`: ``f(a, b, p, X, Y, Z)``.

    Returns
    -------
    tuple of callables
        ``(residual, jacobian)``; the Jacobian returns a list of three arrays (∂/∂a, ∂/∂b, ∂/∂p).

    Raises
    ------
    None
        Builds a fixed model; takes no input.

    References
    ----------
    Chibunichev (2022), §9.4, eq. (9.4.7).

    Examples
    --------
    >>> r, J = plane_functions()
    >>> float(r(0.0, 0.0, 1.0, 3.0, 0.0, 0.0))
    2.0
    """
    m = plane_model()
    args = (*m["parameters"], *m["data"])
    return (sp.lambdify(args, m["residual"], "numpy"),
            sp.lambdify(args, list(m["jacobian"]), "numpy"))


def mobile_mapping_model():
    """(9.8.3) with the lever arm and the boresight angles as unknowns (the §9.8 calibration).

    R_M = R_GNSS + A_IMU·[r_GNSS/S + A_IMU/S(Δω, Δα, Δκ)·R′], A_IMU/S = A_ω A_α A_κ (1.3.2).

    Returns
    -------
    dict
        ``parameters`` (lever x, y, z, Δω, Δα, Δκ), ``data`` (R_GNSS 3, A_IMU 9 row-major,
        R′ 3, target 3), ``residual`` (3×1: model − target) and ``jacobian`` (3×6).

    Raises
    ------
    None
        Builds a fixed model; takes no input.

    References
    ----------
    Chibunichev (2022), §9.8, eqs. (9.8.1)–(9.8.3).

    Examples
    --------
    >>> mobile_mapping_model()["jacobian"].shape
    (3, 6)
    """
    lever = sp.Matrix(sp.symbols("l_x l_y l_z", real=True))
    dw, da, dk = sp.symbols("d_omega d_alpha d_kappa", real=True)
    gnss = sp.Matrix(sp.symbols("G_X G_Y G_Z", real=True))
    a = sp.symbols("a11 a12 a13 a21 a22 a23 a31 a32 a33", real=True)
    A_imu = sp.Matrix(3, 3, a)
    R = sp.Matrix(sp.symbols("R_x R_y R_z", real=True))
    target = sp.Matrix(sp.symbols("T_X T_Y T_Z", real=True))
    boresight = rotation_matrix_symbolic("wak", dw, da, dk)
    residual = gnss + A_imu * (lever + boresight * R) - target
    params = (*lever, dw, da, dk)
    return {"parameters": params, "data": (*gnss, *a, *R, *target), "residual": residual,
            "jacobian": residual.jacobian(params)}


@lru_cache(maxsize=None)
def mobile_mapping_functions():
    """Lambdified residual (3 arrays) and Jacobian (18 arrays, row-major 3×6) of (9.8.3).

    Returns
    -------
    tuple of callables
        ``(residual, jacobian)`` of ``(*parameters, *data)``.

    Raises
    ------
    None
        Builds a fixed model; takes no input.

    References
    ----------
    Chibunichev (2022), §9.8, eq. (9.8.3).

    Examples
    --------
    >>> r, J = mobile_mapping_functions()
    >>> len(J(*([0.0] * 6), *([0.0] * 3), *[1, 0, 0, 0, 1, 0, 0, 0, 1], *([1.0] * 3), *([0.0] * 3)))
    18
    """
    return _lambdified_parts(mobile_mapping_model())


def scanner_camera_rotation():
    """The built-in camera's rotation on a TLS head and the printed (9.7.7) direction.

    Returns
    -------
    dict
        ``symbols`` (φ, ν), ``A`` = A_κ(−φ)·A_ω(90° + ν), ``view`` (−third column of A),
        ``direction`` (cos ν sin φ, cos ν cos φ, sin ν), ``printed`` (… , sin φ) and
        ``literal`` (−third column of A_ω(ν)A_α(φ), the book's "substitute φ, ν for α, ω").

    Raises
    ------
    None
        Builds a fixed model; takes no input.

    References
    ----------
    Chibunichev (2022), §9.7, eqs. (9.7.6), (9.7.7); §9.4, eq. (9.4.1).

    Examples
    --------
    >>> m = scanner_camera_rotation()
    >>> import sympy as sp
    >>> sp.simplify(m["view"] - m["direction"]) == sp.zeros(3, 1)
    True
    """
    phi, nu = sp.symbols("varphi nu", real=True)
    A = rotation_matrix_symbolic("kaw", sp.pi / 2 + nu, 0, -phi)
    direction = sp.Matrix([sp.cos(nu) * sp.sin(phi), sp.cos(nu) * sp.cos(phi), sp.sin(nu)])
    printed = sp.Matrix([sp.cos(nu) * sp.sin(phi), sp.cos(nu) * sp.cos(phi), sp.sin(phi)])
    literal = -rotation_matrix_symbolic("wak", nu, phi, 0)[:, 2]
    return {"symbols": (phi, nu), "A": A, "view": sp.simplify(-A[:, 2]), "direction": direction,
            "printed": printed, "literal": sp.simplify(literal)}
