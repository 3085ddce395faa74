"""Side-looking radar and InSAR in sympy: Chapter 8, §8.9–8.13.

The models behind :mod:`photolib.radar`:

* the range vector in the radar frame, (8.11.4) — **lost in the OCR of the book** and
  reconstructed here: the nadir direction (0, 0, −1) of the radar frame turned about its x axis
  (the flight direction, normal to the emission plane) by the look angle φ, times the slant range
  D, giving D·(0, s·sin φ, −cos φ) with s = +1 for the book's side (+y) and s = −1 for the other;
* the point (8.11.5), the Newton correction (8.11.6) and the vertical case (8.11.7);
* the radar stereo base condition (8.12.5) with its correction equations (8.12.6), and the
  range–Doppler form (range sphere + zero-Doppler plane) used for n ≥ 2 images;
* the InSAR relations (8.13.1)–(8.13.6) derived from the two-antenna geometry.

Every function returns sympy objects; nothing is lambdified at import time.
"""

from __future__ import annotations

from functools import lru_cache

import sympy as sp

from ..errors import InputError
from .model import Model

__all__ = ["look_sign", "radar_range_vector_symbolic", "radar_point_symbolic", "radar_height_model",
           "radar_stereo_model", "range_doppler_model", "insar_relations"]

phi, D = sp.symbols("phi D", real=True)
_A = sp.Matrix(3, 3, lambda i, j: sp.Symbol(f"a{i + 1}{j + 1}", real=True))
Xs, Ys, Zs, X, Y, Z = sp.symbols("X_S Y_S Z_S X Y Z", real=True)


def look_sign(side: str = "left") -> int:
    """The sign s of the radar frame's y axis toward the imaged side.

    Parameters
    ----------
    side : {"left", "right"}
        The imaged side of the flight path, with the radar frame's x axis along the flight
        direction and z up: then +y points to the left, so the book's (0, sin φ, −cos φ) is a
        left-looking radar (s = +1); a right-looking radar (Envisat ASAR, ERS, Sentinel-1) has
        s = −1.

    Returns
    -------
    int
        +1 or −1.

    Raises
    ------
    InputError
        If ``side`` is not "left" or "right".

    References
    ----------
    Chibunichev (2022), §8.9 (the radar frame Sxyz); §8.11, eq. (8.11.4).

    Examples
    --------
    >>> look_sign("left"), look_sign("right")
    (1, -1)
    """
    if side == "left":
        return 1
    if side == "right":
        return -1
    raise InputError(f"side must be 'left' or 'right', got {side!r}")


def radar_range_vector_symbolic(side: str = "left") -> sp.Matrix:
    """(8.11.4), lost in the OCR: the range vector (x, y, z) in the radar frame, derived.

    The point lies in the emission plane (zero-Doppler: x = 0) at slant range D; φ is measured
    from the nadir (0, 0, −1) toward the imaged side. Turning the nadir ray about the x axis by
    s·φ gives the vector.

    Parameters
    ----------
    side : {"left", "right"}
        See :func:`look_sign`.

    Returns
    -------
    sympy.Matrix
        D·R_x(s·φ)·(0, 0, −1)ᵀ = (0, s·D·sin φ, −D·cos φ)ᵀ.

    Raises
    ------
    InputError
        If ``side`` is unknown.

    References
    ----------
    Chibunichev (2022), §8.11, eq. (8.11.4) (reconstructed); (8.11.5) and (8.12.5) contain it.

    Examples
    --------
    >>> radar_range_vector_symbolic("left").T
    Matrix([[0, D*sin(phi), -D*cos(phi)]])
    """
    s = look_sign(side)
    a = s * phi
    R_x = sp.Matrix([[1, 0, 0], [0, sp.cos(a), -sp.sin(a)], [0, sp.sin(a), sp.cos(a)]])
    return sp.simplify(D * R_x * sp.Matrix([0, 0, -1]))


def radar_point_symbolic(side: str = "left") -> sp.Matrix:
    """(8.11.5): the object point R_M = R_S + A·(x, y, z)ᵀ of (8.11.1)–(8.11.4).

    Parameters
    ----------
    side : {"left", "right"}
        See :func:`look_sign`.

    Returns
    -------
    sympy.Matrix
        (X, Y, Z) in the symbols X_S, Y_S, Z_S, a11…a33, D, φ.

    Raises
    ------
    InputError
        If ``side`` is unknown.

    References
    ----------
    Chibunichev (2022), §8.11, eqs. (8.11.1)–(8.11.5).

    Examples
    --------
    >>> radar_point_symbolic()[2]
    D*(a32*sin(phi) - a33*cos(phi)) + Z_S
    """
    v = radar_range_vector_symbolic(side)
    return sp.Matrix([Xs, Ys, Zs]) + (_A * v).applyfunc(sp.factor)


@lru_cache(maxsize=None)
def radar_height_model(side: str = "left") -> Model:
    """(8.11.6): the third equation of (8.11.5) with φ unknown and Z known.

    Parameters
    ----------
    side : {"left", "right"}
        See :func:`look_sign`.

    Returns
    -------
    Model
        Parameter φ; data Z_S, a32, a33, D, Z; residual Z_S + D(s·a32 sin φ − a33 cos φ) − Z,
        whose derivative is the coefficient a of (8.11.6).

    Raises
    ------
    InputError
        If ``side`` is unknown.

    References
    ----------
    Chibunichev (2022), §8.11, eqs. (8.11.5)–(8.11.6).

    Examples
    --------
    >>> radar_height_model().jacobian()
    Matrix([[D*(a32*cos(phi) + a33*sin(phi))]])
    """
    Zp = radar_point_symbolic(side)[2]
    return Model(f"radar-height-{side}", (phi,), (Zs, _A[2, 1], _A[2, 2], D, Z), (Zp - Z,))


@lru_cache(maxsize=None)
def radar_stereo_model(side: str = "left") -> Model:
    """(8.12.5)–(8.12.6): the base condition D₁A₁u(φ₁) − D₂A₂u(φ₂) − B = 0 with φ₁, φ₂ unknown.

    Parameters
    ----------
    side : {"left", "right"}
        The imaged side (the same for both images). See :func:`look_sign`.

    Returns
    -------
    Model
        Parameters φ₁, φ₂; data: columns 2–3 of A₁ and A₂ (b12, b13, b22, b23, b32, b33 and
        c12 … c33), D₁, D₂, B_X, B_Y, B_Z; three residuals whose derivatives are the
        coefficients a₁, a₂, b₁, b₂, c₁, c₂ of (8.12.6).

    Raises
    ------
    InputError
        If ``side`` is unknown.

    References
    ----------
    Chibunichev (2022), §8.12, eqs. (8.12.4)–(8.12.6).

    Examples
    --------
    >>> m = radar_stereo_model()
    >>> [str(p) for p in m.parameters], len(m.residuals)
    (['phi1', 'phi2'], 3)
    """
    s = look_sign(side)
    p1, p2, D1, D2 = sp.symbols("phi1 phi2 D1 D2", real=True)
    b = {k: sp.Symbol(f"b{k}", real=True) for k in ("12", "13", "22", "23", "32", "33")}
    c = {k: sp.Symbol(f"c{k}", real=True) for k in ("12", "13", "22", "23", "32", "33")}
    B = sp.symbols("B_X B_Y B_Z", real=True)
    res = []
    for r in "123":
        u1 = b[r + "2"] * s * sp.sin(p1) - b[r + "3"] * sp.cos(p1)
        u2 = c[r + "2"] * s * sp.sin(p2) - c[r + "3"] * sp.cos(p2)
        res.append(D1 * u1 - D2 * u2 - B["123".index(r)])
    data = tuple(b.values()) + tuple(c.values()) + (D1, D2) + B
    return Model(f"radar-stereo-{side}", (p1, p2), data, tuple(res))


@lru_cache(maxsize=None)
def range_doppler_model() -> Model:
    """Range sphere and zero-Doppler plane of one radar image, with the point (X, Y, Z) unknown.

    |M − S| − D = 0 (the point lies on the sphere of radius D, (8.9.1)) and
    a₁·(M − S) = 0 (it lies in the emission plane x = 0 of the radar frame, a₁ = first column
    of A). Two equations per image; two or more images intersect the point by least squares
    (the n-image generalisation of (8.12.1)–(8.12.3)).

    Returns
    -------
    Model
        Parameters X, Y, Z; data X_S, Y_S, Z_S, a11, a21, a31, D.

    Raises
    ------
    InputError
        Never.

    References
    ----------
    Chibunichev (2022), §8.9, §8.12, eqs. (8.12.1)–(8.12.3).

    Examples
    --------
    >>> [str(p) for p in range_doppler_model().parameters]
    ['X', 'Y', 'Z']
    """
    d = sp.Matrix([X - Xs, Y - Ys, Z - Zs])
    rng = sp.sqrt(d.dot(d)) - D
    dop = _A[0, 0] * d[0] + _A[1, 0] * d[1] + _A[2, 0] * d[2]
    return Model("radar-range-doppler", (X, Y, Z), (Xs, Ys, Zs, _A[0, 0], _A[1, 0], _A[2, 0], D), (rng, dop))


_INSAR_SYMBOLS = None


def _insar_symbols():
    global _INSAR_SYMBOLS
    if _INSAR_SYMBOLS is None:
        D1, B, H, lam, dD, dB = sp.symbols("D_1 B H lambda Delta_D delta_D", positive=True)
        ph, al = sp.symbols("phi alpha", real=True)
        _INSAR_SYMBOLS = {"D1": D1, "B": B, "H": H, "lambda": lam, "Delta_D": dD, "delta_D": dB,
                          "phi": ph, "alpha": al, "phi_0": sp.Symbol("phi_0", positive=True),
                          "B_perp": sp.Symbol("B_perp", positive=True)}
    return _INSAR_SYMBOLS


def _exact_D2(s):
    return sp.sqrt(s["D1"] ** 2 + s["B"] ** 2 + 2 * s["D1"] * s["B"] * sp.sin(s["phi"] - s["alpha"]))


@lru_cache(maxsize=None)
def _insar_geometry():
    s = _insar_symbols()
    D1, B, H, ph, al, dD = s["D1"], s["B"], s["H"], s["phi"], s["alpha"], s["Delta_D"]
    # the cross-track plane: u toward the imaged side, w up; S1 at (0, H); M = S1 + D1(sin φ, −cos φ)
    S1 = sp.Matrix([0, H])
    M = S1 + D1 * sp.Matrix([sp.sin(ph), -sp.cos(ph)])
    S2 = S1 - B * sp.Matrix([sp.cos(al), sp.sin(al)])           # baseline S2 → S1 = B(cos α, sin α)
    D2sq = sp.expand((M - S2).dot(M - S2)).subs({sp.sin(ph) ** 2: 1 - sp.cos(ph) ** 2,
                                                 sp.sin(al) ** 2: 1 - sp.cos(al) ** 2})
    sin_rhs = sp.cancel(sp.expand(D2sq - D1 ** 2 - B ** 2) / (2 * D1 * B))      # (8.13.1)
    D2 = _exact_D2(s)
    return {"sin_phi_minus_alpha": sin_rhs, "D2": D2, "Delta_D_of_phi": D2 - D1,
            "height": H - D1 * sp.cos(ph),                                        # (8.13.2) = M_w
            "sin_from_Delta_D": sp.cancel(((D1 + dD) ** 2 - D1 ** 2 - B ** 2) / (2 * D1 * B))}  # (8.13.4)


@lru_cache(maxsize=None)
def _insar_precision():
    s = _insar_symbols()
    D1, B, H, lam, ph, al = s["D1"], s["B"], s["H"], s["lambda"], s["phi"], s["alpha"]
    # (8.13.5): dh/dΦ at fixed D1 (repeat pass, Φ = 4πΔD/λ), exact, and its small-baseline limit
    Phi = 4 * sp.pi / lam * (_exact_D2(s) - D1)
    dh_dPhi = sp.diff(H - D1 * sp.cos(ph), ph) / sp.diff(Phi, ph)
    printed_dh = D1 * lam * sp.sin(ph) / (4 * sp.pi * B * sp.cos(ph - al))
    ratio = sp.cancel(dh_dPhi / printed_dh)
    return {"dh_dPhi_exact": dh_dPhi, "dh_dPhi_printed": printed_dh, "dh_ratio": ratio,
            "dh_ratio_limit": ratio.subs(B, 0)}                                   # continuous at B = 0


@lru_cache(maxsize=None)
def _insar_critical():
    s = _insar_symbols()
    D1, B, lam, al, dB, p, Bp = s["D1"], s["B"], s["lambda"], s["alpha"], s["delta_D"], s["phi_0"], s["B_perp"]
    # (8.13.6): on flat ground (h = 0) a cell at look angle φ₀ has D1 = H/cos φ₀. To first order
    # in B, ΔD = B·c₁(φ₀) with c₁ = ∂ΔD/∂B at B = 0 (independent of D1); the fringe rate along the
    # ground is dΔD/dD1 = B·(dc₁/dφ₀)/(dD1/dφ₀)
    Dp, Hf = sp.Symbol("D", positive=True), sp.Symbol("H", positive=True)
    c1 = sp.diff(sp.sqrt(Dp ** 2 + B ** 2 + 2 * Dp * B * sp.sin(p - al)) - Dp, B).subs(B, 0)
    rate1 = B * sp.diff(c1, p) / sp.diff(Hf / sp.cos(p), p)
    rate_perp = sp.cancel(rate1.subs(B, Bp / sp.cos(p - al)).subs(Hf, D1 * sp.cos(p))).subs(sp.sin(p), sp.tan(p) * sp.cos(p))
    # critical: the phase (4π/λ)ΔD turns by 2π across one slant-range resolution cell δ_D
    per_metre = sp.cancel(rate_perp / Bp)                                    # the rate is linear in B⊥
    Bcrit = sp.cancel(2 * sp.pi / (4 * sp.pi / lam * per_metre * dB))
    return {"fringe_rate_flat": rate_perp, "critical_baseline": Bcrit}


def insar_relations(part: str | None = None) -> dict:
    """The InSAR relations (8.13.1)–(8.13.6) derived from the two-antenna geometry.

    Geometry (Fig. 8.27 is lost; this fixes it): in the cross-track plane with u toward the
    imaged side and w up, S₁ = (0, H), the point M = S₁ + D₁(sin φ, −cos φ) and the baseline
    S₂ → S₁ = B(cos α, sin α). With the opposite baseline orientation the sign of (8.13.1)
    flips.

    Parameters
    ----------
    part : {None, "geometry", "precision", "critical"}
        Derive only (8.13.1)–(8.13.4), (8.13.5) or (8.13.6) (each is cached); all by default.

    Returns
    -------
    dict
        ``sin_phi_minus_alpha`` (the right side of (8.13.1) after substituting the geometry;
        simplifies to sin(φ − α)), ``D2``, ``Delta_D_of_phi``, ``height`` (8.13.2),
        ``sin_from_Delta_D`` (8.13.4), ``dh_dPhi_exact`` and ``dh_dPhi_printed`` (8.13.5) with
        ``dh_ratio`` (their ratio, D₂/D₁) and ``dh_ratio_limit`` (its value as B → 0), ``fringe_rate_flat`` (dΔD/dD₁ on flat ground
        to first order in B, in terms of B⊥) and ``critical_baseline`` (8.13.6), plus ``symbols``.

    Raises
    ------
    InputError
        An unknown ``part``.

    References
    ----------
    Chibunichev (2022), §8.13, eqs. (8.13.1)–(8.13.6).

    Examples
    --------
    >>> r = insar_relations()
    >>> s = r["symbols"]
    >>> import sympy as sp
    >>> sp.expand(sp.expand_trig(r["sin_phi_minus_alpha"] - sp.sin(s["phi"] - s["alpha"])))
    0
    >>> r["dh_ratio_limit"]
    1
    >>> r["critical_baseline"]
    D_1*lambda*tan(phi_0)/(2*delta_D)
    """
    parts = {"geometry": _insar_geometry, "precision": _insar_precision, "critical": _insar_critical}
    if part is not None and part not in parts:
        raise InputError(f"part must be one of {sorted(parts)} or None, got {part!r}")
    out = {"symbols": dict(_insar_symbols())}
    for name, fn in parts.items():
        if part in (None, name):
            out.update(fn())
    return out
