"""Figures for Chapter 8, §8.9–8.13 (radar images, radar stereo, InSAR).

* :func:`side_looking_geometry` — Fig. 8.16/8.18/8.23–8.25 redrawn: a side-looking radar over a
  terrain profile with range circles D₀ … D_k; a valley point and a mountain point on one circle
  (one image pixel: layover) and the stretch of the profile in layover.
* :func:`insar_geometry` — Fig. 8.27 a: S₁, S₂, the baseline B at tilt α, the look angle φ,
  the ranges D₁, D₂, the heights H and h, with the sign convention of photolib.radar.
* :func:`height_vs_phase` — h against ΔΦ by (8.13.3) → (8.13.4) → (8.13.2), and δh against B₀
  by (8.13.5).
* :func:`critical_baseline_curve` — (8.13.6) against the look angle for Envisat-like parameters.
* :func:`interferogram_panels` — Fig. 8.28: heights, wrapped interferogram, unwrapped phase,
  recovered heights and their error.

Every figure function returns the matplotlib Figure (closed, so that a notebook shows it once)
together with the numbers it shows, rounded.
"""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np

from ... import radar


def _done(fig):
    plt.close(fig)
    return fig


def side_looking_geometry(H=8000.0, D0=9000.0, Dk=13000.0, n_circles=5):
    """A radar at height H looking to +u over a profile with a steep hill facing it.

    Returns (fig, info) where info holds the two equal-range points and the layover fraction.
    """
    S = np.array([0.0, 0.0, H])
    u = np.linspace(4000, 10000, 601)
    h = 1800.0 * np.exp(-((u - 8000.0) / 500.0) ** 2)       # a hill with a steep near-range slope
    D = np.hypot(u, H - h)
    lay = radar.layover_mask(D)
    fig, ax = plt.subplots(figsize=(8, 4.5))
    ax.fill_between(u / 1e3, -200, h, color="0.85")
    ax.plot(u / 1e3, h, "k-", lw=1)
    ax.plot(u[lay] / 1e3, h[lay], "r.", ms=2, label="layover (equal ranges)")
    t = np.linspace(-0.2, np.pi / 2, 200)
    for Dc in np.linspace(D0, Dk, n_circles):
        ax.plot(Dc * np.sin(t) / 1e3, (H - Dc * np.cos(t)), color="tab:blue", lw=0.6)
    ax.plot([0], [H], "k^", ms=8)
    ax.annotate("S", (0, H), xytext=(3, 5), textcoords="offset points")
    # one range circle through the hill top: the valley point at the same range
    top = int(np.argmax(h))
    Dt = D[top]
    phi_valley = radar.look_angle_from_height(S, np.eye(3), Dt, 0.0)
    valley = radar.radar_point(S, np.eye(3), Dt, phi_valley)
    ax.plot(Dt * np.sin(t) / 1e3, H - Dt * np.cos(t), "m-", lw=1.2, label=f"D = {Dt / 1e3:.2f} km")
    ax.plot([u[top] / 1e3, valley[1] / 1e3], [h[top], valley[2]], "mo")
    for p in ((u[top], h[top]), (valley[1], valley[2])):
        ax.plot([0, p[0] / 1e3], [H, p[1]], "m:", lw=0.8)
    ax.set_xlim(-0.3, 11)
    ax.set_ylim(-300, H + 600)
    ax.set_xlabel("ground range u, km")
    ax.set_ylabel("height, m")
    ax.set_title("Side-looking radar: range circles D₀…D_k; equal ranges share a pixel (Fig. 8.18)")
    ax.legend(loc="upper right", fontsize=8)
    info = {"hill_top": (round(float(u[top]), 1), round(float(h[top]), 1)),
            "valley_point": (round(float(valley[1]), 1), round(float(valley[2]), 1)),
            "range_m": round(float(Dt), 1), "layover_percent": round(100 * float(lay.mean()), 1)}
    return _done(fig), info


def insar_geometry(H=8.0, B=1.5, alpha_deg=30.0, phi_deg=35.0, h=1.5):
    """Fig. 8.27 a (schematic units): returns (fig, check) with (8.13.1) evaluated on the drawing."""
    al, ph = np.radians(alpha_deg), np.radians(phi_deg)
    S1 = np.array([0.0, H])
    D1 = (H - h) / np.cos(ph)
    M = S1 + D1 * np.array([np.sin(ph), -np.cos(ph)])
    S2 = S1 - B * np.array([np.cos(al), np.sin(al)])
    D2 = np.linalg.norm(M - S2)
    fig, ax = plt.subplots(figsize=(6, 5))
    ax.axhline(0, color="k", lw=0.8)
    ax.plot([S1[0], S1[0]], [0, H], "k--", lw=0.6)
    ax.plot([M[0], M[0]], [0, M[1]], "k--", lw=0.6)
    ax.plot(*zip(S1, M), "tab:blue", label="D₁")
    ax.plot(*zip(S2, M), "tab:orange", label="D₂")
    ax.plot(*zip(S2, S1), "k-", lw=2, label="B (S₂ → S₁ = B(cos α, sin α))")
    for P, name in ((S1, "S₁"), (S2, "S₂"), (M, "M")):
        ax.plot(*P, "ko")
        ax.annotate(name, P, xytext=(5, 5), textcoords="offset points")
    ax.annotate("H", (S1[0], H / 2), xytext=(5, 0), textcoords="offset points")
    ax.annotate("h", (M[0], M[1] / 2), xytext=(5, 0), textcoords="offset points")
    ax.annotate("φ", (S1[0] + 0.3 * np.sin(ph / 2), H - 1.2 * np.cos(ph / 2)))
    ax.set_aspect("equal")
    ax.set_xlabel("u (toward the imaged side)")
    ax.set_ylabel("w (up)")
    ax.set_title("InSAR geometry (Fig. 8.27 a)")
    ax.set_xlim(-2.5, 6.5)
    ax.legend(fontsize=8, loc="lower left")
    phi = radar.insar_look_angle(D1, D2, B, al)
    check = {"phi_deg": round(float(np.degrees(phi)), 6),
             "h_from_8_13_2": round(float(radar.insar_height(H, D1, phi)), 6)}
    return _done(fig), check


def height_vs_phase(geometry=None, D=None):
    """h against the unwrapped ΔΦ, and δh(σ_Φ = 1 rad) against B₀; returns (fig, table)."""
    g = radar.InsarGeometry() if geometry is None else geometry
    D = g.H / np.cos(g.look_angle) if D is None else D
    h = np.linspace(-500, 3000, 50)
    w = h - g.H
    u = np.sqrt(D ** 2 - w ** 2)
    S2 = -g.B * np.array([np.cos(g.alpha), np.sin(g.alpha)])
    dD = np.hypot(u - S2[0], w - S2[1]) - D
    phase = radar.range_difference_to_phase(dD, g.wavelength)
    back = radar.insar_height(g.H, D, radar.insar_look_angle_from_difference(
        D, radar.phase_to_range_difference(phase, g.wavelength), g.B, g.alpha))
    Bp = np.linspace(50, 1000, 50)
    dh = radar.height_precision(D, g.wavelength, g.look_angle, Bp, 1.0)
    fig, (a, b) = plt.subplots(1, 2, figsize=(10, 3.8))
    a.plot((phase - phase[0]) / (2 * np.pi), h)
    a.set_xlabel("ΔΦ − ΔΦ(h = −500 m), cycles")
    a.set_ylabel("h, m")
    a.set_title("(8.13.3) → (8.13.4) → (8.13.2) at one slant range")
    b.plot(Bp, dh)
    b.set_xlabel("B₀, m")
    b.set_ylabel("δh for δΦ = 1 rad, m")
    b.set_title("(8.13.5)")
    fig.tight_layout()
    table = {"cycles_per_km": round(float((phase[-1] - phase[0]) / (2 * np.pi) / 3.5), 2),
             "roundtrip_max_error_m": float(np.round(np.abs(back - h).max(), 6)),
             "dh_at_250m": round(float(radar.height_precision(D, g.wavelength, g.look_angle, 250.0, 1.0)), 2)}
    return _done(fig), table


def critical_baseline_curve(H=790e3, wavelength=0.05624, bandwidth=16e6):
    """(8.13.6) against the look angle (flat Earth, D = H/cos φ); returns (fig, table)."""
    phi = np.radians(np.linspace(15, 45, 61))
    dr = radar.range_resolution(bandwidth)
    Bc = radar.critical_baseline(H / np.cos(phi), wavelength, phi, dr)
    fig, ax = plt.subplots(figsize=(6, 3.8))
    ax.plot(np.degrees(phi), Bc)
    ax.axvline(23, color="0.6", ls="--")
    ax.axhspan(200, 300, color="tab:green", alpha=0.2, label="B = 200–300 m (§8.13)")
    ax.set_xlabel("look angle φ, °")
    ax.set_ylabel("critical baseline B₀, m")
    ax.set_title(f"(8.13.6): λ = {wavelength * 100:.3f} cm, δ_D = {dr:.2f} m, H = {H / 1e3:.0f} km")
    ax.legend(fontsize=8)
    table = {f"{d}°": round(float(radar.critical_baseline(H / np.cos(np.radians(d)), wavelength, np.radians(d), dr)))
             for d in (15, 23, 30, 45)}
    return _done(fig), table


def interferogram_panels(heights, pixel_size, *, sigma_phase=0.3, seed=1, title="synthetic DEM"):
    """Fig. 8.28: heights → wrapped interferogram → LS unwrapping → heights; returns (fig, stats)."""
    ifg = radar.simulate_interferogram(heights, pixel_size, sigma_phase=sigma_phase, seed=seed)
    u = radar.unwrap_phase_ls(ifg.wrapped)
    hh = radar.insar_heights(u, ifg.D1, ifg.geometry, ([0], [0], [heights[0, 0]]))
    err = hh - heights
    fig, axes = plt.subplots(1, 4, figsize=(14, 3.6))
    for ax, img, name, cmap in zip(axes, (heights, ifg.wrapped, u, err),
                                   ("DEM h, m", "wrapped ΔΦ (flattened), rad", "unwrapped (LS, DCT), rad",
                                    "recovered h − DEM, m"),
                                   ("terrain", "twilight", "viridis", "RdBu")):
        im = ax.imshow(img, cmap=cmap)
        ax.set_title(name, fontsize=9)
        ax.set_xticks([])
        ax.set_yticks([])
        fig.colorbar(im, ax=ax, fraction=0.046)
    fig.suptitle(f"InSAR over the {title}: σ_Φ = {sigma_phase} rad, the radar looks toward increasing column (→)")
    g = ifg.geometry
    pred = radar.height_precision(float(ifg.D1.mean()), g.wavelength, g.look_angle,
                                  radar.perpendicular_baseline(g.B, g.alpha, g.look_angle), sigma_phase)
    stats = {"grid": heights.shape, "relief_m": round(float(np.ptp(heights)), 1),
             "fringes": round(float(np.ptp(ifg.phase - ifg.flat_phase) / (2 * np.pi)), 1),
             "rms_height_error_m": round(float(np.std(err)), 2), "predicted_8_13_5_m": round(float(pred), 2),
             "layover_percent": round(100 * float(ifg.layover.mean()), 2)}
    return _done(fig), stats
