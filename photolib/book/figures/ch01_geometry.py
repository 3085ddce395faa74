"""Figures for Chapter 1, §1.1–§1.7 (single-image geometry), redrawn from library calls.

* :func:`central_projection_section` — Fig. 1.3: S, o, n, N, f, H, α₀ and on = f·tan α₀.
* :func:`vertical_lines_to_nadir` — Figs 1.5/1.6: vertical edges of buildings meet at the nadir point.
* :func:`rotation_axes` — Figs 1.10–1.13: the object axes turned by ω, α, κ.
* :func:`height_displacement_map` — Fig. 1.15 / (1.6.1): ΔR = ΔZ·r/f over the image format.
* :func:`rectification_keystone` — Fig. 1.16 / (1.7.5): a square grid of the tilted image seen
  on the horizontal image.

Every function returns the matplotlib Figure (closed, so that a notebook shows it once).
"""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np

from ...camera import ExteriorOrientation, InteriorOrientation
from ...rotation import rot_x, rot_y, rot_z, rotation_matrix
from ...single_image import (
    planimetric_error_from_height_error, principal_to_nadir_distance, project, tilted_to_horizontal,
)


def _done(fig):
    plt.close(fig)
    return fig


def central_projection_section(f=3.0, H=10.0, tilt_deg=20.0):
    """Fig. 1.3 in the principal plane: a positive image P of focal length ``f`` tilted by α₀,
    flying height ``H`` above the object plane E (arbitrary units, f exaggerated)."""
    t = np.radians(tilt_deg)
    S = np.array([0.0, H])
    axis = np.array([np.sin(t), -np.cos(t)])             # principal ray direction
    along = np.array([np.cos(t), np.sin(t)])             # image plane direction in the section
    o = S + f * axis
    on = float(principal_to_nadir_distance(f, t))
    n = o - on * along                                   # plumb line through S meets P here
    N = np.array([0.0, 0.0])
    O = S + H / np.cos(t) * axis                         # the principal ray meets E
    fig, ax = plt.subplots(figsize=(7, 5.5))
    ax.axhline(0, color="0.4", lw=1)
    ax.text(-6.5, 0.25, "E (object plane)", color="0.3")
    p1, p2 = o - 1.9 * f * along, o + 1.6 * f * along
    ax.plot(*np.c_[p1, p2], color="tab:blue", lw=2)
    ax.text(*(p2 + [0.2, 0.0]), "P (image)", color="tab:blue")
    ax.plot(*np.c_[S, O], color="tab:orange", lw=1.2, ls="--")
    ax.plot(*np.c_[S, N], color="k", lw=1.2)
    ax.plot(*np.c_[o, n], color="tab:red", lw=3)
    for name, p, off in (("S", S, (0.2, 0.2)), ("o", o, (0.25, -0.1)), ("n", n, (-0.5, -0.1)),
                         ("N", N, (0.2, 0.25)), ("O", O, (0.2, 0.25))):
        ax.plot(*p, "ko", ms=4)
        ax.text(p[0] + off[0], p[1] + off[1], name, fontsize=12, style="italic")
    ax.text(*(S + 0.5 * f * axis + [0.25, 0.0]), "f", fontsize=12, color="tab:orange")
    ax.text(-0.8, H / 2, "H", fontsize=12)
    arc = np.linspace(-np.pi / 2, -np.pi / 2 + t, 30)
    ax.plot(S[0] + 1.2 * np.cos(arc), S[1] + 1.2 * np.sin(arc), "k", lw=0.8)
    ax.text(S[0] + 0.15, S[1] - 1.7, r"$\alpha_0$", fontsize=12)
    ax.annotate(rf"$on = f\,\tan\alpha_0 = {on:.2f}$", xy=(n + o) / 2, xytext=(-6.5, 4.0),
                arrowprops=dict(arrowstyle="->", color="tab:red"), color="tab:red", fontsize=11)
    ax.set_aspect("equal")
    ax.set_xlim(-7, 7)
    ax.set_ylim(-0.8, H + 1)
    ax.set_axis_off()
    ax.set_title("Elements of a central projection in the principal plane (cf. Fig. 1.3)")
    return _done(fig)


def _buildings(rng, count=9):
    """Box-shaped buildings: (footprint corners (4, 2), height) on the plane Z = 0."""
    out = []
    for cx, cy in rng.uniform(-350, 350, (count, 2)):
        w, d = rng.uniform(30, 70, 2)
        rot = rng.uniform(0, np.pi / 2)
        c, s = np.cos(rot), np.sin(rot)
        corners = np.array([[-w, -d], [w, -d], [w, d], [-w, d]]) / 2 @ np.array([[c, s], [-s, c]]) + [cx, cy]
        out.append((corners, rng.uniform(15, 60)))
    return out


def vertical_lines_to_nadir(omega_deg=10.0, alpha_deg=4.0, kappa_deg=0.0, f=50.0, H=600.0, seed=3):
    """Figs 1.5/1.6: synthetic buildings on a tilted image; their vertical edges, extended, meet at
    the nadir point n = the image of the ground point vertically below S."""
    rng = np.random.default_rng(seed)
    eo = ExteriorOrientation.from_degrees(0.0, 0.0, H, omega_deg, alpha_deg, kappa_deg)
    io = InteriorOrientation(f)
    nadir = project([eo.Xs, eo.Ys, 0.0], eo, io)[0]
    fig, ax = plt.subplots(figsize=(6.5, 6.5))
    ax.add_patch(plt.Rectangle((-30, -30), 60, 60, fill=False, color="0.5", lw=1))
    for corners, h in _buildings(rng):
        base = project(np.c_[corners, np.zeros(4)], eo, io)
        top = project(np.c_[corners, np.full(4, h)], eo, io)
        ax.fill(*top.T, color="tab:gray", alpha=0.35)
        ax.fill(*base.T, fill=False, color="tab:brown", lw=0.8)
        for b, t in zip(base, top):
            ax.plot(*np.c_[b, t], color="k", lw=1.5)
            ax.plot(*np.c_[t, nadir], color="tab:red", lw=0.5, ls=":")
    ax.plot(0, 0, "b+", ms=12, mew=2)
    ax.text(0.8, 0.8, "o", color="b", fontsize=12, style="italic")
    ax.plot(*nadir, "ro", ms=6)
    ax.text(nadir[0] + 0.8, nadir[1] + 0.8, "n", color="r", fontsize=12, style="italic")
    ax.set_aspect("equal")
    lim = max(32.0, np.abs(nadir).max() + 3)
    ax.set_xlim(-lim, lim)
    ax.set_ylim(-lim, lim)
    ax.set_xlabel("x, mm")
    ax.set_ylabel("y, mm")
    ax.set_title(f"Vertical edges converge to the nadir point (ω = {omega_deg:g}°, α = {alpha_deg:g}°, "
                 f"on = {np.hypot(*nadir):.2f} mm)", fontsize=10)
    return _done(fig)


def _draw_frame(ax, R, origin, colors, labels, lw=2.0, ls="-"):
    for j in range(3):
        v = R[:, j]
        ax.plot(*np.c_[origin, origin + v], color=colors[j], lw=lw, ls=ls)
        ax.text(*(origin + 1.12 * v), labels[j], color=colors[j], fontsize=11)


def rotation_axes(omega_deg=20.0, alpha_deg=-25.0, kappa_deg=30.0, order="kaw"):
    """Figs 1.10–1.13: the object axes X, Y, Z (thin) and the camera axes x, y, z after each
    elementary rotation of the chosen sequence (columns of A: camera axes in object space)."""
    w, a, k = np.radians([omega_deg, alpha_deg, kappa_deg])
    steps = {"kaw": [("A_κ", rot_z(k)), ("A_κ A_α", rot_z(k) @ rot_y(a)), ("A_κ A_α A_ω", rotation_matrix(w, a, k, "kaw"))],
             "wak": [("A_ω", rot_x(w)), ("A_ω A_α", rot_x(w) @ rot_y(a)), ("A_ω A_α A_κ", rotation_matrix(w, a, k, "wak"))]}[order]
    fig = plt.figure(figsize=(11, 3.8))
    for i, (name, R) in enumerate(steps):
        ax = fig.add_subplot(1, 3, i + 1, projection="3d")
        _draw_frame(ax, np.eye(3), np.zeros(3), ["0.6"] * 3, ["X", "Y", "Z"], lw=1, ls="--")
        _draw_frame(ax, R, np.zeros(3), ["tab:red", "tab:green", "tab:blue"], ["x", "y", "z"])
        ax.set_xlim(-1, 1)
        ax.set_ylim(-1, 1)
        ax.set_zlim(-1, 1)
        ax.set_box_aspect((1, 1, 1))
        ax.view_init(elev=22, azim=-60)
        ax.set_xticks([])
        ax.set_yticks([])
        ax.set_zticks([])
        ax.set_title(f"A = {name}", fontsize=10)
    fig.suptitle(f"Camera axes after the rotations ω = {omega_deg:g}°, α = {alpha_deg:g}°, κ = {kappa_deg:g}° "
                 f"(sequence {'κ–α–ω (1.3.4)' if order == 'kaw' else 'ω–α–κ (1.3.2)'})", fontsize=10)
    return _done(fig)


def height_displacement_map(f=50.0, dZ=10.0, half_x=30.0, half_y=25.0):
    """(1.6.1): contour map of ΔR = ΔZ·r/f (metres) over an image format 2·half_x × 2·half_y mm."""
    x, y = np.meshgrid(np.linspace(-half_x, half_x, 121), np.linspace(-half_y, half_y, 101))
    _, _, dR = planimetric_error_from_height_error(x, y, f, dZ)
    fig, ax = plt.subplots(figsize=(7, 5))
    cs = ax.contourf(x, y, dR, levels=np.arange(0, 8.5, 0.5), cmap="viridis")
    ax.contour(x, y, dR, levels=np.arange(1, 8, 1), colors="w", linewidths=0.6)
    fig.colorbar(cs, ax=ax, label="ΔR, m")
    corner = planimetric_error_from_height_error(half_x, half_y, f, dZ)[2]
    ax.plot(half_x, half_y, "r*", ms=14, clip_on=False)
    ax.annotate(f"corner: ΔR = {float(corner):.1f} m", (half_x, half_y), xytext=(half_x - 26, half_y - 6),
                color="w", arrowprops=dict(arrowstyle="->", color="w"))
    ax.set_aspect("equal")
    ax.set_xlabel("x, mm")
    ax.set_ylabel("y, mm")
    ax.set_title(f"Planimetric error ΔR = ΔZ·r/f for f = {f:g} mm, ΔZ = {dZ:g} m (1.6.1)")
    return _done(fig)


def rectification_keystone(omega_deg=0.0, alpha_deg=20.0, kappa_deg=0.0, f=100.0, f0=100.0, half=40.0, lines=9):
    """(1.7.5): a square grid drawn on the tilted image, transferred to the horizontal image taken
    from the same centre — squares become trapezoids (the keystone)."""
    A = rotation_matrix(*np.radians([omega_deg, alpha_deg, kappa_deg]), order="kaw")
    ticks = np.linspace(-half, half, lines)
    dense = np.linspace(-half, half, 60)
    fig, (left, right) = plt.subplots(1, 2, figsize=(11, 5))
    for t in ticks:
        for pts in (np.c_[np.full_like(dense, t), dense], np.c_[dense, np.full_like(dense, t)]):
            left.plot(*pts.T, color="tab:blue", lw=0.8)
            right.plot(*tilted_to_horizontal(pts, A, f, f0).T, color="tab:blue", lw=0.8)
    corners = np.array([[-half, -half], [half, -half], [half, half], [-half, half], [-half, -half]])
    right.plot(*tilted_to_horizontal(corners, A, f, f0).T, color="k", lw=1.5)
    left.plot(*corners.T, color="k", lw=1.5)
    left.set_title(f"tilted image P (f = {f:g} mm)")
    right.set_title(f"horizontal image P⁰ (f⁰ = {f0:g} mm), by (1.7.5)")
    for ax in (left, right):
        ax.set_aspect("equal")
        ax.set_xlabel("mm")
        ax.plot(0, 0, "r+", ms=10)
    fig.suptitle(f"Rectification of a square grid: ω = {omega_deg:g}°, α = {alpha_deg:g}°, κ = {kappa_deg:g}°")
    return _done(fig)
