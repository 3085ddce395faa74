"""Figures for the theory part of the Sementsov appendix (seed 004; ``chapters/appendix_sementsov.ipynb``).

* :func:`transformed_bundle_family` — Figs. 23–25 redrawn for a tilted image: the members of the
  transformed bundle (12)–(16) for several k, each imaging the plane points identically.
* :func:`centre_locus` — Fig. 26: the transformed centres on the corrected circle (18), with the
  printed (wrong) circle overlaid.
* :func:`condition_curves` — Figs. 27–28: δX_S(k) and δx₀(k) for α = ±30°, crossing only at k = 1.
* :func:`radial_curves` — the radial corrections of the three calibrations of Table B.1.
* :func:`residual_fields` — the residual ray differences of the spatial- and planar-target calibrations
  against the star calibration (the analogue of Figs. C.2–C.3, from Table B.1 only).

Every function returns the matplotlib Figure, closed (a notebook cell shows it once).
"""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np

from ... import additional_parameters as ap
from ... import planar_target as pt

__all__ = ["transformed_bundle_family", "centre_locus", "condition_curves", "radial_curves", "residual_fields"]


def _done(fig):
    plt.close(fig)
    return fig


def transformed_bundle_family(alpha_deg=30.0, ks=(0.5, 0.75, 1.0, 1.25, 1.5), f=3100.0, Z_S=300.0,
                              ground=(-250.0, 0.0, 250.0, 500.0, 750.0)):
    """Section through the plane of tilt: each member (k) of the transformed bundle and its rays to the
    same ground points; the image plane is drawn at the distance f′ = k f from the centre (1 px = 2 cm)."""
    a = np.radians(alpha_deg)
    fig, ax = plt.subplots(figsize=(8.5, 5.6), constrained_layout=True)
    ax.axhline(0.0, color="0.3", lw=2)
    G = np.asarray(ground, float)
    ax.plot(G, np.zeros_like(G), "ks", ms=5, label="plane points (Z = 0)")
    colours = plt.cm.viridis(np.linspace(0.0, 0.9, len(ks)))
    scale = 0.02                                      # metres of the drawing per pixel of f′ (enlarged)
    for k, c in zip(ks, colours):
        b = pt.transformed_bundle(a, k, f, Z_S)
        S = np.array([b.dX_S, b.Z_S_prime])
        for g in G:
            ax.plot([S[0], g], [S[1], 0.0], color=c, lw=0.6, alpha=0.6)
        axis = np.array([np.sin(b.alpha_prime), -np.cos(b.alpha_prime)])          # optical axis, looking down
        centre = S + axis * b.f_prime * scale
        across = np.array([axis[1], -axis[0]])
        ends = np.array([centre - across * 30.0, centre + across * 30.0])
        ax.plot(ends[:, 0], ends[:, 1], color=c, lw=2.5)
        ax.plot(*S, "o", color=c, ms=6,
                label=f"k = {k:g}: f′ = {b.f_prime:.0f} px, α′ = {np.degrees(b.alpha_prime):.1f}°, "
                      f"δx₀ = {round(b.dx0) + 0:+d} px, S = ({round(b.dX_S) + 0:+d}, {b.Z_S_prime:.0f}) m")
    ax.set(aspect="equal", xlabel="X (in the plane of tilt), m", ylabel="Z, m",
           title=f"Transformed bundles, α = {alpha_deg:g}°, f = {f:g} px, Z_S = {Z_S:g} m\n"
                 "(same image of every plane point; image planes drawn at f′, 1 px = 2 cm)")
    ax.legend(fontsize=7.5, loc="upper center", bbox_to_anchor=(0.5, -0.15), ncol=1)
    return _done(fig)


def centre_locus(alpha_deg=30.0, Z_S=300.0, f=3100.0, marked=(0.25, 0.5, 1.0, 1.5, 2.0)):
    """The centres (δX_S, Z′_S) of the family for k ∈ (0, 1/sin α] on the corrected circle (18), and the
    printed circle of (18) (centre +Z_S cot α)."""
    a = np.radians(alpha_deg)
    loc = pt.centre_locus(a, Z_S)
    ks = np.linspace(1e-6, loc.k_max, 400)
    b = pt.transformed_bundle(a, ks, f, Z_S)
    t = np.linspace(0, 2 * np.pi, 361)
    fig, ax = plt.subplots(figsize=(7.5, 5.0), constrained_layout=True)
    ax.plot(loc.centre[0] + loc.radius * np.cos(t), loc.radius * np.sin(t), "C0-", lw=1,
            label=f"(18) corrected: centre ({loc.centre[0]:.1f}, 0), radius {loc.radius:.0f} m")
    printed_c = -loc.centre[0]
    ax.plot(printed_c + loc.radius * np.cos(t), loc.radius * np.sin(t), "C3--", lw=1,
            label=f"(18) as printed: centre ({printed_c:.1f}, 0)")
    ax.plot(b.dX_S, b.Z_S_prime, "k-", lw=3, alpha=0.6, label="family (12)–(16), 0 < k ≤ 1/sin α")
    for k in marked:
        m = pt.transformed_bundle(a, min(k, loc.k_max), f, Z_S)
        ax.plot(m.dX_S, m.Z_S_prime, "ko", ms=5)
        ax.annotate(f"k = {k:g}", (m.dX_S, m.Z_S_prime), xytext=(6, 4), textcoords="offset points", fontsize=8)
    ax.plot([loc.centre[0], printed_c], [0, 0], "x", color="0.3", ms=8)
    ax.axhline(0, color="0.6", lw=0.8)
    ax.set(aspect="equal", xlabel="δX_S, m", ylabel="Z′_S, m", ylim=(-0.15 * loc.radius, 1.1 * loc.radius),
           title=f"Fig. 26 redrawn: centres of the transformed bundles, α = {alpha_deg:g}°, Z_S = {Z_S:g} m")
    ax.legend(fontsize=8, loc="lower left")
    return _done(fig)


def condition_curves(alpha_deg=30.0, f=3100.0, Z_S=300.0):
    """δX_S(k) (methodology 2.1) and δx₀(k) (2.2) for α = ±α_deg: the curves cross only at k = 1."""
    a = np.radians(alpha_deg)
    ks = np.linspace(1e-3, 1.0 / np.sin(a), 400)
    fig, axes = plt.subplots(1, 2, figsize=(10, 3.8), constrained_layout=True)
    for sign, style in ((1, "C0-"), (-1, "C1--")):
        b = pt.transformed_bundle(sign * a, ks, f, Z_S)
        axes[0].plot(ks, b.dX_S, style, label=f"α = {sign * alpha_deg:+g}°")
        axes[1].plot(ks, b.dx0, style, label=f"α = {sign * alpha_deg:+g}°")
    for ax, what, fig_no in ((axes[0], "δX_S, m (2.1: equal X_S)", 27), (axes[1], "δx₀, px (2.2: one camera)", 28)):
        ax.axvline(1.0, color="0.5", lw=0.8)
        ax.axhline(0.0, color="0.5", lw=0.8)
        ax.set(xlabel="k", ylabel=what, title=f"Fig. {fig_no} redrawn")
        ax.legend(fontsize=8)
    return _done(fig)


def radial_curves(params, r_max=2950.0):
    """Radial correction −r(k₁r² + k₂r⁴ + k₃r⁶) of (4) for each calibration of Table B.1 (pixels).

    ``params`` maps a calibration name to its Table B.1 parameters (keys k1, k2, k3).
    """
    r = np.linspace(0.0, r_max, 300)
    fig, ax = plt.subplots(figsize=(7, 4), constrained_layout=True)
    for name, p in params.items():
        s = ap.photomod(np.column_stack([r, np.zeros_like(r)]), {k: p[k] for k in ("k1", "k2", "k3")})
        ax.plot(r, s[:, 0], label=name)
    ax.axhline(0, color="0.5", lw=0.8)
    ax.axvline(np.hypot(2456, 1632), color="0.7", lw=0.8, ls=":")
    ax.set(xlabel="r, px (frame corner dotted)", ylabel="radial correction σ_r, px",
           title="Table B.1: radial corrections of eq. (4)")
    ax.legend(fontsize=8)
    return _done(fig)


def residual_fields(comparisons, xy, scale=3.0):
    """Arrows of the ray differences u_star − R·u_cal (image x, y components, arcsec) at the frame points
    ``xy`` for each comparison in ``comparisons`` ({name: BundleComparison})."""
    fig, axes = plt.subplots(1, len(comparisons), figsize=(5.2 * len(comparisons), 3.9), constrained_layout=True)
    for ax, (name, c) in zip(np.atleast_1d(axes), comparisons.items()):
        d = c.residuals_arcsec
        ax.quiver(xy[:, 0], xy[:, 1], d[:, 0], d[:, 1], angles="xy", scale_units="xy", scale=1.0 / scale,
                  width=0.003)
        ax.set(aspect="equal", xlim=(-2456, 2456), ylim=(-1632, 1632), xlabel="x, px", ylabel="y, px",
               title=f"{name} vs stars: r.m.s. {c.rms_arcsec:.1f}″, max {c.max_arcsec:.1f}″")
    return _done(fig)
