"""Chapter 8, §8.9–8.13 (radar images, radar stereo, InSAR): formula checks and inline statements.

Adapters for the ``[[formula]]`` and ``[[example]]`` entries of ``textbook/ch08_radar.toml``.
Formula adapters take the printed formula (sympy text) in ``inputs`` and return
``{"printed_equals_derived": bool}``; the derivations come from
:mod:`photolib.derivations.radar` (the range vector as the nadir ray turned about the flight
axis, the two-antenna InSAR geometry), never from the numeric code of :mod:`photolib.radar`.
Statements are checked with :mod:`photolib.radar` on hand-placed points or seeded simulations
(conditions in the entries' notes).
"""

from __future__ import annotations

import numpy as np
import sympy as sp

from ..derivations import radar as dr

_NAMES = ["X", "Y", "Z", "X_S", "Y_S", "Z_S", "D", "phi", "D_0", "k", "y_c", "x", "y", "z",
          "H", "h", "B", "alpha", "D_1", "D_2", "Delta_D", "Delta_Phi", "lam", "delta_Phi", "delta_h",
          "B_0", "delta_D", "B_X", "B_Y", "B_Z", "D_X", "D_Y", "D_Z", "phi1", "phi2", "D1", "D2"]
_NAMES += [f"a{i}{j}" for i in (1, 2, 3) for j in (1, 2, 3)]
_NAMES += [f"{p}{i}{j}" for p in ("b", "c") for i in (1, 2, 3) for j in (1, 2, 3)]


def _syms():
    pos = {"D", "D_0", "k", "H", "B", "D_1", "D_2", "lam", "B_0", "delta_D", "D1", "D2"}
    out = {n: sp.Symbol(n, positive=True) if n in pos else sp.Symbol(n, real=True) for n in _NAMES}
    out.update({"sin": sp.sin, "cos": sp.cos, "tan": sp.tan, "tg": sp.tan, "pi": sp.pi, "sqrt": sp.sqrt,
                "acos": sp.acos, "asin": sp.asin})
    return out


def _parse(text):
    return sp.parse_expr(str(text), local_dict=_syms())


def _zero(expr) -> bool:
    expr = sp.expand(sp.expand_trig(sp.sympify(expr)))
    return sp.simplify(expr) == 0


def _ok(flag) -> dict:
    return {"printed_equals_derived": bool(flag)}


def _rename(expr):
    """Map the derivation module's symbols onto the printed names."""
    s = _syms()
    d = dr.insar_relations()["symbols"]
    table = {d["D1"]: s["D_1"], d["B"]: s["B"], d["H"]: s["H"], d["lambda"]: s["lam"],
             d["Delta_D"]: s["Delta_D"], d["delta_D"]: s["delta_D"], d["phi"]: s["phi"],
             d["alpha"]: s["alpha"], d["phi_0"]: s["phi"], d["B_perp"]: s["B_0"]}
    return sp.sympify(expr).xreplace(table)


# --------------------------------------------------------------------------- §8.9
def slant_range_formula(inputs: dict) -> dict:
    """(8.9.1): echoes sampled at equal time steps Δt give D = c·t/2 linear in the sample number.

    Derived: t = t₀ + y_c·Δt, D = c·t/2 = c·t₀/2 + (c·Δt/2)·y_c, i.e. D₀ = c·t₀/2, k = c·Δt/2.
    """
    s = _syms()
    c, t0, dt = sp.symbols("c t_0 Delta_t", positive=True)
    derived = c * (t0 + s["y_c"] * dt) / 2
    printed = _parse(inputs["D"]).subs({s["D_0"]: c * t0 / 2, s["k"]: c * dt / 2})
    return _ok(_zero(printed - derived))


# --------------------------------------------------------------------------- §8.11
def range_vector_formula(inputs: dict) -> dict:
    """(8.11.4): the printed (x, y, z) against the nadir ray turned about x by φ (sympy)."""
    vec = inputs.get("vector") or []
    if len(vec) != 3:
        return _ok(False)                        # nothing (or not a 3-vector) was printed
    s = _syms()
    derived = dr.radar_range_vector_symbolic(inputs.get("side", "left")).xreplace(
        {dr.D: s["D"], dr.phi: s["phi"]})
    return _ok(all(_zero(_parse(p) - d) for p, d in zip(vec, derived)))


def point_formula(inputs: dict) -> dict:
    """(8.11.5): the printed X, Y, Z against R_S + A·(8.11.4) derived by sympy."""
    s = _syms()
    derived = dr.radar_point_symbolic("left")
    sub = {sym: s[str(sym)] for sym in derived.free_symbols if str(sym) in s}
    derived = derived.xreplace(sub)
    return _ok(all(_zero(_parse(p) - d) for p, d in zip(inputs["XYZ"], derived)))


def vector_sum_formula(inputs: dict) -> dict:
    """(8.11.1)–(8.11.3), (8.12.1)–(8.12.2): R_M = R_S + A·(x, y, z)ᵀ reproduces a point placed
    by hand (object → radar frame by Aᵀ, then back by the printed relations)."""
    from ..rotation import rotation_matrix
    rng = np.random.default_rng(int(inputs.get("seed", 0)))
    ok = True
    for _ in range(3):
        S = rng.normal(0, 1000, 3) + [0, 0, 8000]
        A = rotation_matrix(*rng.normal(0, 0.1, 3), "wak")
        M = rng.normal(0, 3000, 3)
        xyz = A.T @ (M - S)                         # the radar-frame coordinates of M
        DXYZ = A @ xyz                              # (8.11.3)
        ok &= bool(np.allclose(S + DXYZ, M, atol=1e-9))   # (8.11.1)/(8.11.2)
    return _ok(ok)


def newton_formula(inputs: dict) -> dict:
    """(8.11.6): a·δφ = l with a = ∂Z/∂φ (sympy) and l = Z − Z(φ⁰) converges to the φ of a point
    placed by hand (tilted radar, ω = 0.02, α = −0.01, κ = 0.3)."""
    from ..rotation import rotation_matrix
    model = dr.radar_height_model("left")
    a_expr = model.jacobian()[0]
    printed_a = _parse(inputs["a"]).xreplace({_syms()[str(v)]: v for v in a_expr.free_symbols})
    if not _zero(printed_a - a_expr):
        return _ok(False)
    S, A = np.array([1000.0, -2000.0, 8000.0]), rotation_matrix(0.02, -0.01, 0.3, "wak")
    D, phi_true = 12000.0, 0.75
    Z = S[2] + D * (A[2, 1] * np.sin(phi_true) - A[2, 2] * np.cos(phi_true))
    phi = 0.3
    for _ in range(20):
        l = Z - (S[2] + D * (A[2, 1] * np.sin(phi) - A[2, 2] * np.cos(phi)))
        a = D * (A[2, 1] * np.cos(phi) + A[2, 2] * np.sin(phi))
        phi += l / a
    return _ok(abs(phi - phi_true) < 1e-12)


def vertical_formula(inputs: dict) -> dict:
    """(8.11.7) cos φ = H/D: sympy with the third row of (8.11.5) for a vertical emission plane
    (a₃₂ = 0, a₃₃ = 1, the case of Fig. 8.25); ``inputs["plane"] = "tilted"`` checks the general
    case, where it does not hold."""
    s = _syms()
    Zp = dr.radar_point_symbolic("left")[2]
    sub = {sym: s[str(sym)] for sym in Zp.free_symbols if str(sym) in s}
    Zp = Zp.xreplace(sub)
    if inputs.get("plane", "vertical") == "vertical":
        Zp = Zp.subs({s["a32"]: 0, s["a33"]: 1})
    H = s["Z_S"] - Zp                                   # H = Z_S − Z
    printed = _parse(inputs["cos_phi"]).subs(s["H"], H)
    return _ok(_zero(printed - sp.cos(s["phi"])))


# --------------------------------------------------------------------------- §8.12
def _stereo_derived():
    s = _syms()
    out = []
    for i, (A, D, ph) in enumerate((("b", "D1", "phi1"), ("c", "D2", "phi2"))):
        u = sp.Matrix([0, sp.sin(s[ph]), -sp.cos(s[ph])])
        Am = sp.Matrix(3, 3, lambda r, c: s[f"{A}{r + 1}{c + 1}"])
        out.append(s[D] * Am * u)
    return out


def stereo_point_formula(inputs: dict) -> dict:
    """(8.12.3): the printed point of image i against R_Si + D_i·A_i·(8.11.4) (sympy).

    The printed right-hand side must be written in φ_i (the unknowns named after it); a
    vector (D_Xi, D_Yi, D_Zi) that is not expressed through φ_i is the unchanged (8.12.2).
    """
    derived = _stereo_derived()[0]
    printed = [_parse(p) for p in inputs["DXYZ1"]]
    return _ok(all(_zero(p - d) for p, d in zip(printed, derived)))


def base_formula(inputs: dict) -> dict:
    """(8.12.4)–(8.12.5): from R_M = R_S1 + D₁ = R_S2 + D₂ (8.12.1), B = R_S2 − R_S1 = D₁ − D₂;
    the printed components against D₁A₁u(φ₁) − D₂A₂u(φ₂) (sympy)."""
    d1, d2 = _stereo_derived()
    printed = [_parse(p) for p in inputs["B"]]
    return _ok(all(_zero(p - (a - b)) for p, a, b in zip(printed, d1, d2)))


def stereo_lsq_formula(inputs: dict) -> dict:
    """(8.12.6): three correction equations in δφ₁, δφ₂; the coefficients are the sympy Jacobian
    of (8.12.5); their least-squares iteration recovers a point placed by hand."""
    from .. import radar
    from ..rotation import rotation_matrix
    m = dr.radar_stereo_model("left")
    if m.jacobian().shape != (int(inputs["equations"]), int(inputs["unknowns"])):
        return _ok(False)
    S1, S2, M = np.array([0.0, 0.0, 8000.0]), np.array([0.0, 3000.0, 9500.0]), np.array([50.0, 6000.0, 300.0])
    A = []
    for S, A0 in ((S1, rotation_matrix(0.01, 0, 0, "wak")), (S2, rotation_matrix(-0.02, 0.01, 0, "wak"))):
        for _ in range(30):                       # turn about z until M is in the emission plane
            w = A0.T @ (M - S)
            A0 = A0 @ rotation_matrix(0.0, 0.0, -np.arctan2(w[0], w[1]), "wak")
        A.append(A0)
    res = radar.radar_stereo(S1, A[0], np.linalg.norm(M - S1), S2, A[1], np.linalg.norm(M - S2))
    return _ok(np.linalg.norm(res.point - M) < 1e-6)


# --------------------------------------------------------------------------- §8.13
def insar_angle_formula(inputs: dict) -> dict:
    """(8.13.1): the printed right side against the two-antenna geometry (sympy), baseline
    S₂ → S₁ = B(cos α, sin α) toward the imaged side."""
    s = _syms()
    rhs = _rename(dr.insar_relations("geometry")["sin_phi_minus_alpha"])
    if not _zero(rhs - sp.sin(s["phi"] - s["alpha"])):
        return _ok(False)
    D2 = _rename(dr.insar_relations("geometry")["D2"])
    printed = _parse(inputs["sin"]).subs(s["D_2"], D2)
    return _ok(_zero(printed - sp.sin(s["phi"] - s["alpha"])))


def insar_height_formula(inputs: dict) -> dict:
    """(8.13.2): the printed h against the vertical coordinate of M = S₁ + D₁(sin φ, −cos φ)."""
    derived = _rename(dr.insar_relations("geometry")["height"])
    return _ok(_zero(_parse(inputs["h"]) - derived))


def phase_formula(inputs: dict) -> dict:
    """(8.13.3): each echo travels 2D_i, its phase is 2π·2D_i/λ (repeat pass / monostatic), so
    ΔΦ = 2π·2(D₂ − D₁)/λ; ``inputs["passes"] = "bistatic"`` (one transmitter): the paths are
    D₁ + D₁ and D₁ + D₂, ΔΦ = 2πΔD/λ."""
    s = _syms()
    D1, dD, lam = s["D_1"], s["Delta_D"], s["lam"]
    if inputs.get("passes", "repeat") == "bistatic":
        derived = 2 * sp.pi * ((D1 + D1 + dD) - 2 * D1) / lam
    else:
        derived = 2 * sp.pi * (2 * (D1 + dD) - 2 * D1) / lam
    return _ok(_zero(_parse(inputs["Delta_Phi"]) - derived))


def insar_difference_formula(inputs: dict) -> dict:
    """(8.13.4): (8.13.1) with D₂ = D + ΔD, D = D₁, against the geometry (sympy)."""
    s = _syms()
    printed = _parse(inputs["sin"]).subs(s["D"], s["D_1"])
    derived = _rename(dr.insar_relations("geometry")["sin_from_Delta_D"])
    return _ok(_zero(printed - derived))


def height_precision_formula(inputs: dict) -> dict:
    """(8.13.5): δh/δΦ printed against dh/dΦ from (8.13.2)–(8.13.4) (sympy): equal as B/D → 0
    (the exact ratio is D₂/D₁), with B₀ = B cos(φ − α) the perpendicular baseline."""
    s = _syms()
    prec = dr.insar_relations("precision")
    exact = _rename(prec["dh_dPhi_exact"])
    printed = (_parse(inputs["delta_h"]) / s["delta_Phi"]).subs(
        {s["B_0"]: s["B"] * sp.cos(s["phi"] - s["alpha"]), s["D"]: s["D_1"]})
    ratio = sp.cancel(exact / printed)
    return _ok(sp.simplify(sp.Abs(ratio.subs(s["B"], 0)) - 1) == 0)


def critical_baseline_formula(inputs: dict) -> dict:
    """(8.13.6): the printed B₀crit against the baseline at which the flat-ground phase turns by
    2π per slant-range resolution cell (sympy, first order in B/D)."""
    s = _syms()
    derived = _rename(dr.insar_relations("critical")["critical_baseline"])
    printed = _parse(inputs["B_crit"]).subs(s["D"], s["D_1"])
    return _ok(_zero(printed - derived))


# --------------------------------------------------------------------------- statements
def transcribed(inputs: dict) -> dict:
    """Pure specifications: nothing to compute."""
    return {}


def equal_range_one_pixel(inputs: dict) -> dict:
    """Fig. 8.18: two points of different heights at one slant range have one image coordinate."""
    from .. import radar
    S, A, D = np.array([0.0, 0.0, float(inputs["H"])]), np.eye(3), float(inputs["D"])
    pts = [radar.radar_point(S, A, D, radar.look_angle_from_height(S, A, D, z)) for z in inputs["heights"]]
    y = [radar.range_coordinate(np.linalg.norm(p - S), inputs["D0"], inputs["k"]) for p in pts]
    distinct = np.linalg.norm(pts[0] - pts[1]) > 100.0
    return {"same_pixel": "yes" if distinct and abs(y[0] - y[1]) < 1e-6 else "no"}


def vertical_base_stereo(inputs: dict) -> dict:
    """§8.10, Fig. 8.22: a vertical base (two flight heights) intersects a point by (8.12.6)."""
    from .. import radar
    M = np.array(inputs["M"], dtype=float)
    S1, S2 = np.array([0.0, 0.0, inputs["H1"]]), np.array([0.0, 0.0, inputs["H2"]])
    res = radar.radar_stereo(S1, np.eye(3), np.linalg.norm(M - S1), S2, np.eye(3), np.linalg.norm(M - S2))
    return {"vertical_base_works": "yes" if np.linalg.norm(res.point - M) < 1e-6 else "no"}


def short_base(inputs: dict) -> dict:
    """§8.13: 200–300 m at about 780 km is far below the critical baseline (8.13.6)."""
    from .. import radar
    phi = np.radians(inputs["look_deg"])
    D = inputs["H"] / np.cos(phi)
    bc = radar.critical_baseline(D, inputs["wavelength"], phi, radar.range_resolution(inputs["bandwidth"]))
    return {"short_base": "yes" if max(inputs["bases"]) < bc / 3 else "no",
            "B_crit_at_780km": bc}


def envisat_critical_baseline(inputs: dict) -> dict:
    """(8.13.6) with Envisat ASAR parameters (not printed in the book; see the notes)."""
    from .. import radar
    return {"B_crit": radar.critical_baseline(inputs["D"], inputs["wavelength"], np.radians(inputs["look_deg"]),
                                              radar.range_resolution(inputs["bandwidth"]))}


def range_only_height(inputs: dict) -> dict:
    """(8.13.1)–(8.13.2) from the ranges alone: metre-level range errors give a poor height
    (seeded Monte Carlo, σ_D on each range)."""
    from .. import radar
    g = radar.InsarGeometry()
    rng = np.random.default_rng(int(inputs["seed"]))
    phi = g.look_angle
    D1 = g.H / np.cos(phi)
    M = np.array([0.0, g.H]) + D1 * np.array([np.sin(phi), -np.cos(phi)])
    S2 = np.array([0.0, g.H]) - g.B * np.array([np.cos(g.alpha), np.sin(g.alpha)])
    D2 = np.linalg.norm(M - S2)
    n = int(inputs["trials"])
    d1 = D1 + rng.normal(0, inputs["sigma_D"], n)
    d2 = D2 + rng.normal(0, inputs["sigma_D"], n)
    ok = np.abs((d2 ** 2 - d1 ** 2 - g.B ** 2) / (2 * d1 * g.B)) <= 1
    h = radar.insar_height(g.H, d1[ok], radar.insar_look_angle(d1[ok], d2[ok], g.B, g.alpha))
    rms = float(np.sqrt(np.mean((h - M[1]) ** 2)))
    return {"height_precision_low": "yes" if rms > 100.0 else "no", "rms_height_m": rms}


def phase_range_mm(inputs: dict) -> dict:
    """(8.13.3) inverted: the range-difference error of a phase error δΦ."""
    from .. import radar
    dD = radar.phase_to_range_difference(np.radians(inputs["sigma_phase_deg"]), inputs["wavelength"])
    return {"millimetre_level": "yes" if dD < 1e-3 else "no", "sigma_dD_mm": dD * 1e3}


def dinsar_mm(inputs: dict) -> dict:
    """DInSAR: a tenth of a fringe of line-of-sight motion is λ/20 (repeat pass)."""
    from .. import radar
    cycle = radar.phase_to_range_difference(2 * np.pi, inputs["wavelength"])     # λ/2 per fringe
    tenth = cycle / 10 * 1e3
    return {"few_millimetres": "yes" if 1.0 <= tenth < 10.0 else "no", "mm_per_tenth_fringe": tenth}


def dense_dem_chain(inputs: dict) -> dict:
    """Fig. 8.28 on a synthetic DEM: wrapped, noisy interferogram → LS unwrapping → (8.13.3),
    (8.13.4), (8.13.2); the height RMS against (8.13.5)."""
    from .. import radar
    from ..synthetic import terrain_height
    Y, X = np.mgrid[0:inputs["rows"], 0:inputs["cols"]] * inputs["pixel"]
    h = terrain_height(X, Y, mean=500.0, relief=inputs["relief"], wavelength=3000.0)
    ifg = radar.simulate_interferogram(h, inputs["pixel"], sigma_phase=inputs["sigma_phase"], seed=inputs["seed"])
    u = radar.unwrap_phase_ls(ifg.wrapped)
    hh = radar.insar_heights(u, ifg.D1, ifg.geometry, ([0], [0], [h[0, 0]]))
    err = hh - h
    g = ifg.geometry
    pred = radar.height_precision(float(ifg.D1.mean()), g.wavelength, g.look_angle,
                                  radar.perpendicular_baseline(g.B, g.alpha, g.look_angle), inputs["sigma_phase"])
    ratio = float(np.std(err) / pred)
    return {"dense_dem": "yes" if 0.9 < ratio < 1.15 else "no", "rms_over_predicted": ratio}
