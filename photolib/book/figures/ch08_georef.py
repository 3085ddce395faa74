"""Figures for Chapter 8, §8.14–8.17 (direct georeferencing, scanner triangulation with fixed
centres, direct vs inverse scanner orthophotos, voxel SGM).

* :func:`lever_arms` — Fig. 8.29 redrawn: GNSS antenna, IMU and sensor with the lever arms and
  the sensor vector R to the ground point M (side view, X–Z plane).
* :func:`fixed_centres` — Figs. 8.30–8.32: a three-line strip, its fixed projection centres
  every Δt, the measured (offset, wiggly) and the adjusted line EO of (8.15.2), and the
  footprints of the three lines.
* :func:`hole_map` — Figs. 8.33–8.34: the direct orthophoto with its holes next to the complete
  inverse one.
* :func:`voxel_slice` — Fig. 8.39: one X–Z slice of the voxel cost C(X, Y, Z) and of the
  aggregated S with the true and the recovered surface.

Every function returns the (closed) matplotlib Figure together with the numbers it shows.
"""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np

from ... import georef
from ...rectify import RasterGrid, orthorectify
from ...rotation import rotation_matrix


def _done(fig):
    plt.close(fig)
    return fig


def lever_arms(*, pitch=0.25, lever_gnss=(0.8, 0.0, 1.2), lever_sensor=(0.6, 0.0, -0.9),
               sensor_vector=(-1.2, 0.0, -5.5), boresight_pitch=-0.15):
    """Side view (X–Z plane) of (8.14.1): object origin O, GNSS antenna, IMU, sensor S and the
    ground point M, with the lever arms and the IMU and sensor axes (schematic metres).

    Returns (fig, points) with the object coordinates of GNSS, IMU, S and M.
    """
    A = rotation_matrix(0.0, pitch, 0.0, "wak")
    bore = rotation_matrix(0.0, boresight_pitch, 0.0, "wak")
    G = np.array([4.0, 0.0, 7.0])
    R = np.asarray(sensor_vector, dtype=float)
    S, A_S = georef.sensor_pose(G, A, lever_gnss, lever_sensor, bore)
    imu = G - A @ np.asarray(lever_gnss)
    M = georef.direct_georeference(R, G, A, lever_gnss, lever_sensor, bore)[0]
    fig, ax = plt.subplots(figsize=(7, 6))
    pts = {"O": np.zeros(3), "GNSS": G, "IMU": imu, "S": S[0], "M": M}
    arrows = [(np.zeros(3), G, "R_ГНСС", "k"), (np.zeros(3), imu, "R_ИИУ", "grey"),
              (imu, G, "A_ИИУ r_ГНСС/ИИУ", "tab:blue"), (imu, S[0], "A_ИИУ r_ИИУ/S", "tab:green"),
              (S[0], M, "A_ИИУ A_ИИУ/S R", "tab:red"), (np.zeros(3), M, "R_M", "tab:purple")]
    for a, b, label, colour in arrows:
        ax.annotate("", xy=(b[0], b[2]), xytext=(a[0], a[2]),
                    arrowprops=dict(arrowstyle="->", color=colour, lw=1.6))
        mid = (a + b) / 2
        ax.text(mid[0] + 0.08, mid[2] + 0.05, label, color=colour, fontsize=9)
    for name, p in pts.items():
        ax.plot(p[0], p[2], "o", color="k", ms=5)
        ax.annotate(name, (p[0], p[2]), textcoords="offset points", xytext=(-14, 6), fontsize=10, weight="bold")
    for origin, Am, label, colour in ((imu, A, "IMU", "tab:blue"), (S[0], A_S[0], "S", "tab:red")):
        for k, axis in ((0, "x"), (2, "z")):
            d = Am[:, k] * 0.9
            ax.annotate("", xy=(origin[0] + d[0], origin[2] + d[2]), xytext=(origin[0], origin[2]),
                        arrowprops=dict(arrowstyle="->", color=colour, lw=0.8, ls=":"))
            ax.text(origin[0] + d[0], origin[2] + d[2], f"{axis}_{label}", fontsize=8, color=colour)
    ax.axhline(M[2], color="sienna", lw=1)
    ax.text(-0.8, M[2] - 0.4, "ground", color="sienna", fontsize=8)
    ax.set_xlim(-1.0, 7.0)
    ax.set_aspect("equal")
    ax.set_xlabel("X (m)")
    ax.set_ylabel("Z (m)")
    ax.set_title("Direct georeferencing (8.14.1): lever arms and boresight (schematic)")
    fig.tight_layout()
    return _done(fig), {k: np.round(v, 3) + 0.0 for k, v in pts.items()}


def fixed_centres(block: georef.ThreeLineBlock, result: georef.FixedCentreAdjustment | None = None, *,
                  element: int = 3):
    """The EO element ``element`` (default ω) along the strip: truth, GNSS/IMU, fixed centres and the
    line EO of (8.15.2); plus a plan view of the trajectory and the three lines' ground footprints.

    Returns (fig, figures) with the largest error of the measured and of the adjusted line EO.
    """
    names = ("X_S (m)", "Y_S (m)", "Z_S (m)", "ω (mrad)", "α (mrad)", "κ (mrad)")
    scale = 1e3 if element >= 3 else 1.0
    t = block.t
    tf = t[block.fixed]
    fig, axes = plt.subplots(2, 1, figsize=(9, 7))
    ax = axes[0]
    ax.plot(t, block.eo_true[:, element] * scale, "k-", lw=1, label="true")
    ax.plot(t, block.eo_measured[:, element] * scale, "-", color="tab:orange", lw=1, label="GNSS/IMU (offset)")
    out = {"max error measured": float(np.abs(block.eo_measured - block.eo_true)[:, element].max() * scale)}
    if result is not None:
        E = georef.interpolate_fixed_centres(t, tf, result.eo_fixed, block.eo_measured, block.eo_measured[block.fixed])
        lin = georef.interpolate_fixed_centres(t, tf, result.eo_fixed)
        ax.plot(t, lin[:, element] * scale, "--", color="tab:green", lw=1, label="fixed centres, linear only")
        ax.plot(t, E[:, element] * scale, ":", color="tab:red", lw=2, label="(8.15.2): linear + δ")
        ax.plot(tf, result.eo_fixed[:, element] * scale, "ks", ms=6, label="fixed centres (adjusted)")
        out["max error adjusted"] = float(np.abs(E - block.eo_true)[:, element].max() * scale)
    for x in tf:
        ax.axvline(x, color="grey", lw=0.5)
    ax.set_xlabel("t (s)")
    ax.set_ylabel(names[element])
    ax.legend(fontsize=8, ncol=2)
    ax.set_title("Line EO between fixed projection centres")
    ax = axes[1]
    ax.plot(block.eo_true[:, 0], block.eo_true[:, 1], "k-", lw=1)
    ax.plot(block.eo_true[block.fixed, 0], block.eo_true[block.fixed, 1], "ks", ms=6)
    colours = ("tab:blue", "tab:green", "tab:purple")
    for s, colour, label in zip(block.scanners(), colours, ("forward", "nadir", "backward")):
        rows = block.fixed.astype(float)
        X0, Y0 = s.ground(rows, np.zeros(rows.size), 0.0)
        X1, Y1 = s.ground(rows, np.full(rows.size, s.n_cols - 1.0), 0.0)
        for j in range(rows.size):
            ax.plot([X0[j], X1[j]], [Y0[j], Y1[j]], "-", color=colour, lw=1.2,
                    label=f"{label} line at the fixed centres" if j == 0 else None)
    pts = block.points
    ax.plot(pts[~block.control, 0], pts[~block.control, 1], "k+", label="tie points")
    ax.plot(pts[block.control, 0], pts[block.control, 1], "r^", label="control points")
    ax.set_xlabel("X (m)")
    ax.set_ylabel("Y (m)")
    ax.set_aspect("equal")
    ax.legend(fontsize=7, loc="upper left", ncol=2)
    fig.tight_layout()
    return _done(fig), {k: round(v, 4) for k, v in out.items()}


def hole_map(scanner, image, dem, dem_grid: RasterGrid, grid: RasterGrid):
    """Direct (holes in red) and inverse orthophotos of one scanner image; returns (fig, fractions)."""
    direct = georef.direct_orthorectify(image, scanner.ground, dem, dem_grid, grid)
    inverse = orthorectify(image, scanner.project, dem, dem_grid, grid)
    fig, axes = plt.subplots(1, 3, figsize=(12, 4))
    axes[0].imshow(image, cmap="gray")
    axes[0].set_title("scanner image (rows = lines)")
    shown = np.ma.masked_invalid(direct.image)
    cmap = plt.get_cmap("gray").copy()
    cmap.set_bad("red")
    axes[1].imshow(shown, cmap=cmap, extent=(grid.extent[0], grid.extent[2], grid.extent[1], grid.extent[3]))
    axes[1].set_title(f"direct method: {100 * direct.holes.mean():.0f} % holes (red)")
    axes[2].imshow(inverse, cmap="gray", extent=(grid.extent[0], grid.extent[2], grid.extent[1], grid.extent[3]))
    axes[2].set_title(f"inverse method: {100 * np.mean(~np.isfinite(inverse)):.0f} % holes")
    for ax in axes[1:]:
        ax.set_xlabel("X (m)")
        ax.set_ylabel("Y (m)")
    fig.tight_layout()
    return _done(fig), {"holes direct": round(float(direct.holes.mean()), 3),
                        "holes inverse": round(float(np.mean(~np.isfinite(inverse))), 3)}


def voxel_slice(C, S, X, Z, z_true, z_wta, z_sgm, row: int):
    """Slice ``row`` (one Y) of the voxel cost C (with the WTA heights) and of S = Σ L_r (with the
    SGM heights), the true surface over both."""
    fig, axes = plt.subplots(2, 1, figsize=(8, 6), sharex=True)
    ext = (X[0], X[-1], Z[0], Z[-1])
    for ax, V, z_found, label, title in (
            (axes[0], C, z_wta, "argmin_Z C (WTA)", "voxel cost C(X, Y, Z) (8.17.1): min over scan pairs of |d¹ − d²|"),
            (axes[1], S, z_sgm, "argmin_Z S (SGM)", "aggregated S(X, Y, Z) = Σ_r L_r (8.17.4)")):
        im = ax.imshow(V[row].T, origin="lower", aspect="auto", extent=ext, cmap="viridis")
        ax.plot(X, z_true[row], "w-", lw=1.5, label="true surface")
        ax.plot(X, z_found[row], "r.", ms=4, label=label)
        ax.set_ylabel("Z (m)")
        ax.set_title(title, fontsize=10)
        fig.colorbar(im, ax=ax)
    for ax in axes:
        ax.legend(loc="upper right", fontsize=8)
    axes[1].set_xlabel("X (m)")
    fig.tight_layout()
    return _done(fig)
