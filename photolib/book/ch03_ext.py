"""Chapter 3, §3.6, §3.8, §3.9: adapters for the ``textbook/`` entries (counts and printed formulas).

The book's numbers in these sections are counts of unknowns. Each adapter builds the actual
correction-equation system of :mod:`photolib.bundle` on a small synthetic block and counts its
columns, and evaluates the count functions only after checking them against such a build.
Formula checks return ``{"printed_equals_derived": bool}`` from sympy.
"""

from __future__ import annotations

import numpy as np
import sympy as sp

from .. import bundle, derivations as D, synthetic
from ._exact import zero
from .ch03_layouts import fig_3_10_block
from ..camera import InteriorOrientation


def _small_block():
    return synthetic.aerial_block(1, 3, points_per_image=8, sigma=0.0, n_check=0, seed=0)


# --- E6: §3.6 unknowns added by self-calibration -------------------------------------------------
def self_calibration_extra_unknowns(inputs: dict) -> dict:
    """Columns added to the bundle system (3.5.2) by the polynomial (3.6.2) and by (3.6.3) as written."""
    blk = _small_block()
    o = blk.observations
    io = np.zeros(8)
    io[0] = blk.io.f
    plain = bundle.bundle_correction_equations(o.image, o.point, o.xy, blk.cameras, blk.points, blk.io, blk.order)
    n_plain = plain.B1.shape[2] + plain.B2.shape[2]
    out = {}
    for key, names in (("extra_unknowns", bundle.DISTORTION_NAMES), ("extra_unknowns_3_6_3", bundle.IO_NAMES)):
        eq = bundle.self_calibration_correction_equations(o.image, o.point, o.xy, blk.cameras, blk.points, io,
                                                          names, blk.order)
        per_row = eq.B1.shape[2] + eq.B2.shape[2] + eq.B3.shape[2]
        out[key] = per_row - n_plain
        n_sys = bundle.count_self_calibration_unknowns(blk.n_images, len(blk.points), names)
        if n_sys != 6 * blk.n_images + 3 * len(blk.points) + eq.B3.shape[2]:
            raise AssertionError("count_self_calibration_unknowns disagrees with the built system")
    out["coefficients_in_3_6_3"] = 17
    return out


# --- E7: §3.8 Penta counts (3.8.1)/(3.8.2) -------------------------------------------------------
def _rig_system_columns(n_strips=1, exposures=3):
    rb = synthetic.rig_block(n_strips, exposures, n_points=200, n_control=4, sigma=0.0, seed=1)
    free = np.ones(len(rb.points), bool)
    cols = {}
    for par in ("rig", "free"):
        A, _ = bundle.rig_design_matrix(rb.observations, rb.exposure_of_image, rb.camera_of_image, rb.exposures,
                                        rb.mounts, rb.points, rb.ios, free_points=free, parameterisation=par,
                                        order=rb.order)
        cols[par] = A.shape[1]
    n_exp, n_cam = len(rb.exposures), rb.mounts.shape[0] + 1
    return cols, n_exp, n_cam, len(rb.points)


def penta_unknowns(inputs: dict) -> dict:
    """N₁ (3.8.1) and N₂ (3.8.2) for ``n`` exposures of an ``n_s``-camera rig, without points (k = 0).

    The count functions are first checked against the column count of real rig systems
    (:func:`photolib.bundle.rig_design_matrix`) of a small synthetic Penta-like block.
    """
    cols, n_exp, n_cam, k = _rig_system_columns()
    for par in ("rig", "free"):
        if cols[par] != bundle.count_rig_unknowns(n_exp, n_cam, k, par):
            raise AssertionError(f"count_rig_unknowns({par!r}) disagrees with the built system")
    n, ns, k = int(inputs["n_exposures"]), int(inputs["n_cameras"]), int(inputs.get("n_points", 0))
    return {"N1": bundle.count_rig_unknowns(n, ns, k, "free"), "N2": bundle.count_rig_unknowns(n, ns, k, "rig")}


# --- E8: fig. 3.18, the fig. 3.10 block shot with a stereo camera ---------------------------------
def fig318_systems(inputs: dict | None = None) -> dict:
    """Shapes of the correction-equation systems of fig. 3.11 (free EO) and fig. 3.18 (stereo rig)."""
    blk = fig_3_10_block(rig=True, sigma=0.0)
    free = blk.kind == synthetic.TIE
    shapes = {}
    for par in ("free", "rig"):
        A, _ = bundle.rig_design_matrix(blk.observations, blk.exposure_of_image, blk.camera_of_image, blk.exposures,
                                        blk.mounts, blk.points, blk.ios, free_points=free, parameterisation=par,
                                        order=blk.order)
        shapes[par] = A.shape
    return {"M_free": shapes["free"][0], "N_free": shapes["free"][1], "M_rig": shapes["rig"][0],
            "N_rig": shapes["rig"][1]}


def fig318_comparison(inputs: dict) -> dict:
    """The book's qualitative statement: the same number of equations, fewer unknowns."""
    s = fig318_systems()
    return {"equations": "same" if s["M_rig"] == s["M_free"] else "different",
            "unknowns": "fewer" if s["N_rig"] < s["N_free"] else "not fewer"}


# --- E10: §3.9 rolling-shutter unknowns per image -------------------------------------------------
def rolling_shutter_unknowns(inputs: dict) -> dict:
    """Image-unknown columns of the rolling-shutter correction equations, full (3.9.2) and simplified."""
    blk = _small_block()
    o = blk.observations
    out = {}
    for key, model in (("per_image_full", "full"), ("per_image_simplified", "linear")):
        q = 12 if model == "full" else 9
        frames = np.hstack([blk.cameras, np.zeros((blk.n_images, 6))])[:, :q]
        eq = bundle.rolling_shutter_correction_equations(o.image, o.point, o.xy, frames, blk.points, blk.io,
                                                         blk.order, model)
        out[key] = eq.B1.shape[2]
        if bundle.count_rolling_shutter_unknowns(1, 0, model) != out[key]:
            raise AssertionError("count_rolling_shutter_unknowns disagrees with the built system")
    return out


# --- [[formula]] checks ---------------------------------------------------------------------------
def _floats(subs: dict) -> dict:
    """{symbol: sympy Float}: numbers put in with ``xreplace`` (one pass, no ``subs`` pattern matching)."""
    return {k: sp.Float(v) for k, v in subs.items()}


def brown_3_6_2(inputs: dict) -> dict:
    """(3.6.2) as printed equals the library's distortion correction (1.2.2) with x₀ = y₀ = 0 (sympy)."""
    px, py = D.printed_brown_3_6_2()
    dx, dy = D.brown_correction_terms(D.x, D.y)
    model = D.distortion_model()
    mx, my = (e.subs({D.x0: 0, D.y0: 0}) - v for e, v in zip(model.residuals, (D.x, D.y)))
    ok = all(sp.expand(a - b) == 0 for a, b in ((px, dx), (py, dy), (px, mx), (py, my)))
    return {"printed_equals_derived": bool(ok)}


def correction_equation_3_6_3(inputs: dict) -> dict:
    """(3.6.3) as printed: a₁₀f + a₁₁x₀ + a₁₂y₀ (no δ) against the first-order expansion of (3.6.1).

    The linearisation of F(p) around p⁰ is F(p⁰) + Σ ∂F/∂p·δp: every unknown, f, x₀, y₀ included,
    enters through its correction. The printed terms multiply the partials by f, x₀, y₀ themselves.
    """
    model = D.self_calibration_model(inputs.get("order", "kaw"))
    deltas = {p: sp.Symbol(f"delta_{p.name}") for p in model.parameters}
    rng = np.random.default_rng(0)
    subs = {s: float(v) for s, v in zip(list(model.parameters) + list(deltas.values()) + [D.x, D.y],
                                        rng.uniform(0.1, 0.9, 2 * len(model.parameters) + 2))}
    subs[D.Z] = -500.0
    subs[D.f] = 100.0
    # row 0 of ∂F/∂p (the model's sympy Jacobian, evaluated by its printed numpy code) at that point
    J0 = model.compile()[1](*(subs[s] for s in model.parameters + model.data))[:len(model.parameters)]
    derived = sum(J0[j] * subs[deltas[p]] for j, p in enumerate(model.parameters))
    printed = sum(J0[j] * subs[p if p in (D.f, D.x0, D.y0) else deltas[p]] for j, p in enumerate(model.parameters))
    same = abs(float(derived - printed)) < 1e-9
    return {"printed_equals_derived": bool(same)}


def rig_collinearity_3_8_13(inputs: dict) -> dict:
    """(3.8.13) in the printed element form equals the solution of the vector equation (3.8.8) for r₂."""
    order = inputs.get("order", "kaw")
    px, py = D.printed_rig_3_8_13(order)
    dx, dy = D.derived_rig_image_coordinates(order)
    ok = zero(px - dx, size=10000) and zero(py - dy, size=10000)     # exact test decides at this size
    # and numerically: it is the ordinary collinearity (3.8.3) of image 2 with EO (S₂, angles of C₂)
    rng = np.random.default_rng(1)
    e1 = np.array([1000.0, 2000.0, 900.0, *np.radians(rng.uniform(-3, 3, 3))])
    mount = np.array([0.3, -0.1, 0.05, *np.radians([2.0, 38.0, -1.0])])
    P = np.array([1400.0, 2100.0, 40.0])
    subs = dict(zip(D.EO_SYMBOLS + D.MOUNT_SYMBOLS, np.concatenate([e1, mount])))
    subs.update({D.X: P[0], D.Y: P[1], D.Z: P[2], D.f: 100.0, D.x0: 0.0, D.y0: 0.0})
    xy_printed = np.array([float(px.xreplace(_floats(subs))), float(py.xreplace(_floats(subs)))])
    eo2 = bundle.rig_image_orientation(e1, mount, order)
    from ..single_image import project_to_images
    xy_frame, _ = project_to_images(eo2[None], np.zeros(1, int), P[None], InteriorOrientation(f=100.0), order)
    return {"printed_equals_derived": bool(ok and np.allclose(xy_printed, xy_frame[0], atol=1e-9))}


def rig_counts_3_8_1_2(inputs: dict) -> dict:
    """(3.8.1) N₁ = 6n_s n + 3k and (3.8.2) N₂ = 6(n + n_s − 1) + 3k against built rig systems."""
    ok = True
    for strips, exposures in ((1, 2), (1, 3), (2, 2)):
        cols, n, ns, k = _rig_system_columns(strips, exposures)
        ok &= cols["free"] == 6 * ns * n + 3 * k and cols["rig"] == 6 * (n + ns - 1) + 3 * k
    return {"printed_equals_derived": bool(ok)}


def rolling_shutter_3_9_1(inputs: dict) -> dict:
    """(3.9.1)–(3.9.2) reduce to the frame collinearity (3.5.1) (x₀ = y₀ = 0) when all rates vanish,
    and each EO element of a line is its first-line value plus the rate times x (sympy)."""
    order = inputs.get("order", "kaw")
    rs = D.rolling_shutter_model(order)
    frame = D.bundle_collinearity_model(order)
    no_rates = {k: 0 for k in D.RATE_SYMBOLS}
    ok = all(zero(a.subs(no_rates) - b) for a, b in zip(rs.residuals, frame.residuals))
    # the rates enter only through EO + k·x: ∂F/∂k_j = x·∂F/∂EO_j (row 0 of the Jacobian: J[0, j] = ∂F₀/∂p_j)
    J0 = [sp.diff(rs.residuals[0], p) for p in rs.parameters[:12]]
    rng = np.random.default_rng(2)
    subs = {s: float(v) for s, v in zip(rs.parameters + rs.data, rng.uniform(0.01, 0.05, len(rs.parameters) + 5))}
    subs.update({D.Xs: 10.0, D.Ys: 5.0, D.Zs: 100.0, D.X: 30.0, D.Y: -20.0, D.Z: 2.0, D.f: 8.8, D.x: 1.3})
    values = _floats(subs)
    for j in range(6):
        ok &= abs(float(J0[6 + j].xreplace(values)) - 1.3 * float(J0[j].xreplace(values))) < 1e-9
    return {"printed_equals_derived": bool(ok)}

