"""Adapters for the theory and the published numbers of A.V. Sementsov's thesis (seed 004).

Each function takes the ``inputs`` table of an entry of ``textbook/ch11_sementsov.toml`` (ids
``sementsov-…``) and returns ``{quantity: value}`` (examples) or ``{"printed_equals_derived": bool}``
(formulas). Formula checks compare the transcribed printed forms of
:mod:`photolib.derivations.planar_target` with their derivations (exact zero tests); example
adapters recompute the numbers with :mod:`photolib.planar_target` and
:mod:`photolib.additional_parameters`. The Monte Carlo tables (Appendix A, Tables 1–3, 5, 6) are
another module's (``sementsov_simulation``).
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np
import sympy as sp

from .. import additional_parameters as ap
from .. import planar_target as pt
from ..derivations import planar_target as D
from ..derivations.distortion import brown_correction_terms
from ..derivations.gnss import gnss_rotation_symbolic
from ..derivations.symbols import Zs, alpha, f, kappa, omega, x, y
from ._exact import zero as _zero

__all__ = ["formula_check", "corrected_formula_check", "relief_rule", "gnss_pixels", "table4", "table4_as_printed",
           "offset_coefficients", "slope_ratio", "star_exposure", "pixel_sizes", "equivalent_focal",
           "locus_ends", "methodology_roots", "table_b1_parameters", "frame_lattice", "b1_bundle_comparison", "table7",
           "table7_text", "figures_c", "target_marks", "experiment_count", "CALIBRATIONS", "B1_PARAMETERS"]

CALIBRATIONS = ("stars", "spatial", "planar")
"""The three real calibrations of Table B.1 / Table 7: star field, spatial target, planar target."""
B1_PARAMETERS = ("mu", "f", "x0", "y0", "k1", "k2", "k3", "P1", "P2")
"""The rows of Table B.1."""


def _ok(flag) -> dict:
    return {"printed_equals_derived": bool(flag)}



def _sin_p_to_k(expr):
    """Apply (12): sin α′ → k sin α."""
    return sp.sympify(expr).xreplace({sp.sin(D.ALPHA_P): D.K * sp.sin(alpha)})


def _k_from_12(expr):
    """Apply (12) the other way: k → sin α′/sin α."""
    return sp.sympify(expr).xreplace({D.K: sp.sin(D.ALPHA_P) / sp.sin(alpha)})


def _solve(expr, symbol):
    sols = sp.solve(sp.sympify(expr), symbol)
    if len(sols) != 1:
        raise ValueError(f"expected one solution for {symbol}, got {sols}")
    return sols[0]


# --- formulas ----------------------------------------------------------------------------------------------
def formula_check(inputs: dict) -> dict:
    """Compare one printed formula of the thesis with its sympy derivation (``inputs["item"]``)."""
    item = inputs["item"]
    if item == "6":
        A = gnss_rotation_symbolic(alpha, omega, kappa)
        cosines = dict(zip(D.DIRECTION_COSINES, (A[0, 0], A[0, 1], A[0, 2], A[1, 0], A[1, 1], A[1, 2],
                                                 A[2, 0], A[2, 1], A[2, 2])))
        ok = _zero(D.printed_collinearity_6().xreplace(cosines) - D.derived_collinearity_6())
    elif item == "8":
        ok = _zero(D.printed_tilted_plane_8() - D.derived_tilted_plane_8())
    elif item == "9":
        ok = _zero(D.printed_transformed_bundle_9() - D.derived_transformed_bundle_9())
    elif item == "cross":
        ok = all(_zero(sp.expand(p) - d) for p, d in zip(D.printed_cross_multiplied(), D.derived_identity()))
    elif item == "10":
        ok = all(_zero(p - d) for p, d in zip(D.printed_expansion_10(), D.derived_identity()))
    elif item == "11":
        printed, derived = D.printed_coefficient_equations_11(), D.derived_coefficient_equations()
        ok = all(_zero(printed[key] - derived[key]) for key in printed) and \
            derived[("x", "other")] == 0 and derived[("y", "other")] == 0
    elif item in ("12", "13", "14", "15", "16", "17"):
        ok = _solution_step(item)
    elif item == "734":
        ok = sp.expand(D.printed_centre_shift_734() - D.derived_centre_shift()) == 0
    elif item == "18":
        ok = _zero(D.printed_centre_locus().subs(D.solution_substitution()))
    elif item == "2":
        sx_p, sy_p, _ = D.ebner12_symbolic(printed=True)
        sx_c, sy_c, _ = D.ebner12_symbolic(printed=False)
        ok = _zero(sx_p - sx_c) and _zero(sy_p - sy_c)
    elif item == "2-orthogonal":
        ok = D.ebner12_gram().is_diagonal()
    elif item == "3":
        sx, sy, params = D.brown_symbolic()
        keep = {p for p in params if p.name in ("k_1", "k_2", "k_3", "p_1", "p_2")}
        zero = {p: 0 for p in params if p not in keep}
        dx, dy = brown_correction_terms(x, y)
        ok = _zero(sx.subs(zero) - dx) and _zero(sy.subs(zero) - dy)
    elif item == "4":
        sx, sy, params = D.photomod_symbolic()
        k1, k2, k3, P1, P2, a1, a2, b1, b2 = params
        dx, dy = brown_correction_terms(x, y)
        to_p = {sp.Symbol("p_1", real=True): P1, sp.Symbol("p_2", real=True): P2}
        affine_x, affine_y = -b1 * x - b2 * y, -a1 * x - a2 * y
        ok = _zero(sx - (-dx.xreplace(to_p) + affine_x)) and _zero(sy - (-dy.xreplace(to_p) + affine_y))
    elif item == "5":
        t = sp.Symbol("theta", positive=True)
        chord2 = 2 - 2 * sp.cos(t)                      # ‖u − v‖² of two unit vectors at the angle θ
        ok = sp.series(chord2, t, 0, 4).removeO() == t**2
    elif item == "tau":
        tau, p, w, d = sp.symbols("tau alpha_p omega_s delta", positive=True)
        derived = _solve(w * tau * sp.cos(d) - p, tau)  # arc of the star's small circle in time τ = one pixel
        ok = _zero(derived - p / (w * sp.cos(d)))
    elif item == "star-vector":
        ra, d = sp.symbols("alpha delta", real=True)
        Rz = sp.Matrix([[sp.cos(ra), -sp.sin(ra), 0], [sp.sin(ra), sp.cos(ra), 0], [0, 0, 1]])
        Ry = sp.Matrix([[sp.cos(d), 0, -sp.sin(d)], [0, 1, 0], [sp.sin(d), 0, sp.cos(d)]])   # turns x up by δ
        derived = Rz * Ry * sp.Matrix([1, 0, 0])
        printed = sp.Matrix([sp.cos(d) * sp.cos(ra), sp.cos(d) * sp.sin(ra), sp.sin(d)])
        ok = _zero(derived - printed)
    else:
        raise KeyError(f"unknown formula item {item!r}")
    return _ok(ok)


def _solution_step(item) -> bool:
    """(12)–(17) each from its equation of (11), with the earlier results substituted (the thesis's order)."""
    de, pr = D.derived_coefficient_equations(), D.printed_solution()
    sa, ca, sp_, cp = sp.sin(alpha), sp.cos(alpha), sp.sin(D.ALPHA_P), sp.cos(D.ALPHA_P)
    if item == "12":                                    # the XY coefficient of the y-equation
        derived = _solve(de[("y", "XY")].xreplace({sp_: sp.Symbol("s")}), sp.Symbol("s"))
        printed = _solve(pr["12"].xreplace({sp_: sp.Symbol("s")}), sp.Symbol("s"))
        return _zero(derived - printed)
    if item == "13":                                    # the X² coefficient of the y-equation, with (12)
        return _zero(_sin_p_to_k(de[("y", "X^2")]) - pr["13"])
    dx0 = _solve(_k_from_12(de[("x", "X^2")]), D.DX0)  # (14) from the X² coefficient of the x-equation
    if item == "14":
        return _zero(dx0 - _solve(pr["14"], D.DX0))
    zsp = _solve(_k_from_12(de[("x", "X")].subs(D.DX0, dx0)), D.ZSP)       # (15) from the X coefficient
    if item == "15":
        return _zero(zsp - _k_from_12(_solve(pr["15"], D.ZSP)))
    if item == "16":                                    # the Y coefficient of the y-equation, with (12), (14), (15)
        dxs = _solve(_k_from_12(de[("y", "Y")].subs(D.ZSP, zsp)), D.DXS)
        printed = _solve(pr["16"], D.DXS).subs(D.DX0, dx0)
        return _zero(dxs - printed)
    # (17), α = 0: the constant term of the y-equation gives δY_S = δy₀ Z′_S/(k f) = δy₀ Z_S/f
    horizontal = de[("y", "1")].subs({alpha: 0, D.ALPHA_P: 0, D.ZSP: D.K * Zs})
    dys = _solve(horizontal, D.DYS)
    return _zero(dys - D.DY0 * Zs / f)


def corrected_formula_check(inputs: dict) -> dict:
    """The corrected forms recorded in the errata equal the derivation (used by the tests)."""
    item = inputs["item"]
    if item == "18":
        ok = _zero(D.corrected_centre_locus().subs(D.solution_substitution()))
    elif item == "2":
        ok = D.ebner12_gram(printed=False).is_diagonal() and len(D.ebner12_symbolic()[2]) == 12
    else:
        raise KeyError(item)
    return _ok(ok)


# --- inline numbers -----------------------------------------------------------------------------------------
def relief_rule(inputs: dict) -> dict:
    """Line 378: the relief 0.2 H of a calibration field for H = 500 m and 1 000 m."""
    share = inputs["relief_share"]
    return {f"relief at H = {H:g} m": share * H for H in inputs["heights_m"]}


def gnss_pixels(inputs: dict) -> dict:
    """Lines 1024/1035: the GNSS precision 0.1 m / 0.3 m in pixels of GSD = Z_S/f (22)."""
    g = pt.gsd(inputs["Z_S_m"], inputs["f_px"])
    return {"GSD": g, "σ_XY in pixels": inputs["sigma_XY_m"] / g, "σ_Z in pixels": inputs["sigma_Z_m"] / g}


def _table4(inputs, xy_coefficient=None):
    out = {}
    for H in inputs["distances_m"]:
        if xy_coefficient is None:
            o = pt.permissible_offsets(inputs["m_px"], H, inputs["f_px"])
            l_xy, l_z = o.l_xy, o.l_z
        else:                                           # the printed rounded coefficient of (24)
            o = pt.permissible_offsets(inputs["m_px"], H, inputs["f_px"])
            l_xy, l_z = xy_coefficient * inputs["m_px"] * o.gsd, o.l_z
        out[f"l_XY at {H:g} m"] = l_xy * 1000.0
        out[f"l_Z at {H:g} m"] = l_z * 1000.0
    out["l_XY at 20 m (text, line 1154)"] = out["l_XY at 20 m"]
    out["l_Z at 20 m (text, line 1160)"] = out["l_Z at 20 m"]
    return out


def table4(inputs: dict) -> dict:
    """Table 4 by (23)/(24) with the exact coefficients 1.7/0.4 and 0.4/0.6 = 2/3 (mm)."""
    return _table4(inputs)


def table4_as_printed(inputs: dict) -> dict:
    """Table 4 with the rounded coefficient 0.67 printed in (24)."""
    return _table4(inputs, xy_coefficient=inputs["printed_xy_coefficient"])


def offset_coefficients(inputs: dict) -> dict:
    """Lines 1123/1139: 1.7/0.4 = 4.25 and 0.4/0.6 ≈ 0.67 (from the printed slopes and random errors)."""
    o = pt.permissible_offsets(1.0, 1.0, 1.0, slope_xy=inputs["slope_xy"], xi_xy=inputs["xi_xy"],
                               slope_z=inputs["slope_z"], xi_z=inputs["xi_z"])
    return {"l_Z coefficient": o.l_z_px, "l_XY coefficient": o.l_xy_px}


def slope_ratio(inputs: dict) -> dict:
    """Line 1105: Δf is more than 15 times smaller than Δx₀ for an offset l_X (0.6 vs 0.035)."""
    ratio = inputs["slope_x0"] / inputs["slope_f"]
    return {"Δx₀/Δf": ratio, "Δf smaller than Δx₀ by more than 15 times": "yes" if ratio > 15 else "no"}


def star_exposure(inputs: dict) -> dict:
    """Line 1280: the longest exposure for a 60″ pixel at 15″/s (worst case δ = 0)."""
    return {"τ": pt.max_star_exposure(inputs["pixel_arcsec"], np.radians(inputs["declination_deg"]),
                                      inputs["rate_arcsec_s"])}


def pixel_sizes(inputs: dict) -> dict:
    """Lines 1280, 1330, 1336: angular and physical size of a pixel of the NEX-5R."""
    pixel_mm = inputs["sensor_width_mm"] / inputs["frame_px"][0]
    return {"angular pixel, nominal lens": pt.angular_pixel_size(inputs["lens_mm"], pixel_mm),
            "angular pixel, calibrated f": pt.angular_pixel_size(inputs["f_px"]),
            "pixel size": pixel_mm * 1000.0}


def equivalent_focal(inputs: dict) -> dict:
    """Line 1231: the 35 mm equivalent of the 16 mm lens from the printed sensor size (diagonal ratio)."""
    crop = np.hypot(*inputs["film_mm"]) / np.hypot(*inputs["sensor_mm"])
    return {"35 mm equivalent": inputs["lens_mm"] * crop}


def locus_ends(inputs: dict) -> dict:
    """Line 763: the ends of the quarter circle — α′ = 0° as k → 0, α′ = 90° at k = 1/sin α."""
    a = np.radians(inputs["alpha_deg"])
    locus = pt.centre_locus(a, inputs["Z_S"])
    low = pt.transformed_bundle(a, inputs["k_small"], inputs["f"], inputs["Z_S"])
    top = pt.transformed_bundle(a, locus.k_max, inputs["f"], inputs["Z_S"])
    return {"k at the top": locus.k_max, "α′ at the top": float(np.degrees(top.alpha_prime)),
            "α′ at the bottom": float(np.degrees(low.alpha_prime))}


def methodology_roots(inputs: dict) -> dict:
    """Lines 771–820: the roots in k of each methodology's conditions (Figs. 27–29)."""
    out = {}
    for label, spec in inputs["cases"].items():
        a2 = spec.get("alpha2_deg")
        r = pt.condition_roots(spec["method"], np.radians(spec["alpha1_deg"]),
                               None if a2 is None else np.radians(a2))
        out[f"number of roots [{label}]"] = len(r.roots)
        out[f"root [{label}]"] = r.roots[0] if len(r.roots) == 1 else None
    return out


# --- Table B.1 and the bundle comparison (Table 7, Figs. C.1–C.3) -------------------------------------------
@lru_cache(maxsize=None)
def table_b1_parameters() -> dict:
    """{calibration: {parameter: value}} as transcribed in the entry ``sementsov-table-b1``."""
    from .textbook import load_chapter
    ex = load_chapter(11).example("sementsov-table-b1")
    values = {q.name: q.value for q in ex.quantities}
    return {c: {p: values[f"{p} [{c}]"] for p in B1_PARAMETERS} for c in CALIBRATIONS}


def frame_lattice(frame=(4912, 3264), nodes=(25, 17), margin=50.0) -> np.ndarray:
    """A lattice of ``nodes`` points over a frame of ``frame`` pixels (origin at the centre), ``margin`` px in."""
    hx, hy = frame[0] / 2 - margin, frame[1] / 2 - margin
    gx, gy = np.meshgrid(np.linspace(-hx, hx, nodes[0]), np.linspace(-hy, hy, nodes[1]))
    return np.column_stack([gx.ravel(), gy.ravel()])


def _rays(cal, xy, reading):
    """Rays of a Table B.1 calibration at frame coordinates ``xy`` (from the frame centre).

    ``reading="correction"``: σ of (4) evaluated at x − x₀, y − y₀ is added (the corrected ray);
    ``"distortion"``: it is subtracted.
    """
    xb = xy - [cal["x0"], cal["y0"]]
    sigma = ap.photomod(xb, {k: cal[k] for k in ("k1", "k2", "k3", "P1", "P2")})
    sign = 1.0 if reading == "correction" else -1.0
    return pt.image_rays(xb + sign * sigma, cal["f"])


def b1_bundle_comparison(frame=(4912, 3264), nodes=(25, 17), margin=50.0, reading="correction") -> dict:
    """{calibration: BundleComparison} of the spatial- and planar-target bundles against the star-calibrated
    bundle, from the printed Table B.1 parameters on a lattice of frame points (not the thesis's stars)."""
    params = table_b1_parameters()
    xy = frame_lattice(frame, nodes, margin)
    ref = _rays(params["stars"], xy, reading)
    return {c: pt.compare_bundles(ref, _rays(params[c], xy, reading)) for c in ("spatial", "planar")}


@lru_cache(maxsize=None)
def _comparison(frame, nodes, margin, reading):
    return b1_bundle_comparison(frame, nodes, margin, reading)


def table7(inputs: dict) -> dict:
    """Table 7: μ from Table B.1; m_Δα only as the proxy against the star-calibrated bundle (see notes)."""
    params = table_b1_parameters()
    cmp_ = _comparison(tuple(inputs["frame_px"]), tuple(inputs["grid_nodes"]), float(inputs["margin_px"]),
                       inputs["reading"])
    out = {f"μ [{c}]": params[c]["mu"] for c in CALIBRATIONS}
    for c in ("spatial", "planar"):
        out[f"m_Δα [{c}]"] = cmp_[c].rms_arcsec
    return out


def table7_text(inputs: dict) -> dict:
    """Line 1332 restates Table 7's 75.8″ and 87.0″ (read from the entry ``sementsov-table-7``)."""
    from .textbook import load_chapter
    values = {q.name: q.value for q in load_chapter(11).example("sementsov-table-7").quantities}
    return {"m_Δα spatial (text)": values["m_Δα [spatial]"], "m_Δα planar (text)": values["m_Δα [planar]"]}


def figures_c(inputs: dict) -> dict:
    """Figs. C.1–C.3: maximum and RMS deviation — only the proxies against the star-calibrated bundle."""
    cmp_ = _comparison(tuple(inputs["frame_px"]), tuple(inputs["grid_nodes"]), float(inputs["margin_px"]),
                       inputs["reading"])
    out = {}
    for c in ("spatial", "planar"):
        out[f"maximum [{c}]"] = cmp_[c].max_arcsec
        out[f"RMS [{c}]"] = cmp_[c].rms_arcsec
    return out


def target_marks(inputs: dict) -> dict:
    """Lines 1212/1221: 40 A3 sheets of 35 marks, 5 of them special (line 988)."""
    return {"marks": inputs["sheets"] * inputs["marks_per_sheet"],
            "special marks": inputs["sheets"] * inputs["special_per_sheet"]}


def experiment_count(inputs: dict) -> dict:
    """Line 1356: the mock-up experiments the thesis describes, counted (at most)."""
    total = sum(n for n in inputs["counts"].values())
    return {"numerical experiments": total}
