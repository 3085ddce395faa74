"""Figures for Chapter 8, §8.2–8.5 (scanner sensor models).

* :func:`pushbroom_geometry` — Figs. 8.2/8.5: per-line projection centres along the trajectory
  and the fan of rays of a few lines, with their ground footprints (side and plan view).
* :func:`staggered_layout` — Fig. 8.4: a staggered focal plane (even/odd matrices at the
  along-track offsets x_i) and the ground lines the two matrix rows see at one instant.
* :func:`flat_terrain_ambiguity` — Fig. 8.14: two EO solutions that send the rays of the same
  image points through the same flat-ground points, and the condition numbers of the resection.

Every figure function returns the matplotlib Figure (closed, so that a notebook shows it once)
together with the numbers it shows, rounded.
"""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np

from ... import pushbroom as pb


def _done(fig):
    plt.close(fig)
    return fig


def demo_sensor(n_rows=2000, offsets=0.0, n_columns=2001):
    """A small airborne pushbroom (H = 1 km, f = 0.1 m, 10 µm, 0.1 m GSD) with a gentle roll drift."""
    eo = pb.EOPolynomial([0.0, 0.0, 1000.0, 0.0, 0.0, 0.0], [50.0, 0.0, 0.0, 5e-3, 0.0, 0.0])
    return pb.Pushbroom(0.1, 1e-5, n_columns, 1 / 500, eo, x_offsets=offsets, n_rows=n_rows)


def pushbroom_geometry(sensor=None, lines=(0, 700, 1400), n_rays=9):
    """Per-line centres S(t) and ray fans (side view X–Z and plan view X–Y of the footprints)."""
    sensor = demo_sensor() if sensor is None else sensor
    fig = plt.figure(figsize=(11, 4.2))
    ax1 = fig.add_subplot(1, 2, 1, projection="3d")
    ax2 = fig.add_subplot(1, 2, 2)
    rows_all = np.linspace(0, sensor.n_rows - 1, 50)
    S_all, _ = sensor.eo.at(rows_all * sensor.line_period)
    ax1.plot(S_all[:, 0], S_all[:, 1], S_all[:, 2], "k-", lw=1, label="trajectory S(t)")
    cols = np.linspace(0, sensor.n_columns - 1, n_rays)
    foot = {}
    for i, row in enumerate(lines):
        r = np.full(n_rays, float(row))
        S, _ = sensor.object_rays(r, cols)
        X, Y = sensor.ground(r, cols, 0.0)
        colour = f"C{i}"
        for x, y in zip(X, Y):
            ax1.plot([S[0, 0], x], [S[0, 1], y], [S[0, 2], 0.0], colour, lw=0.6)
        ax1.plot([S[0, 0]], [S[0, 1]], [S[0, 2]], "o", color=colour,
                 label=f"line {row}: S at t = {row * sensor.line_period:.1f} s")
        ax2.plot(X, Y, "-", color=colour, lw=2)
        foot[row] = (round(float(X[0]), 2), round(float(Y[0]), 2), round(float(Y[-1]), 2))
    ax1.set_xlabel("X (m)"); ax1.set_ylabel("Y (m)"); ax1.set_zlabel("Z (m)")
    ax1.set_title("one projection centre and one ray fan per line")
    ax1.legend(fontsize=7, loc="center right")
    ax2.plot(S_all[:, 0], S_all[:, 1], "k-", lw=1)
    ax2.set_xlabel("X (m)"); ax2.set_ylabel("Y (m)"); ax2.set_title("plan: ground lines (a roll rate shifts them sideways)")
    ax2.set_aspect("equal", adjustable="datalim")
    fig.tight_layout()
    return _done(fig), foot


def staggered_layout(matrix_columns=(600, 600, 600, 600), offsets=(0.002, -0.002, 0.002, -0.002)):
    """Focal-plane layout of staggered matrices and the two ground lines seen at one instant."""
    xi = pb.staggered_offsets(list(matrix_columns), list(offsets))
    sensor = demo_sensor(offsets=xi, n_columns=len(xi))
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 3.6))
    start = 0
    for k, (n, off) in enumerate(zip(matrix_columns, offsets)):
        y0 = (start - (len(xi) - 1) / 2) * sensor.pixel_size * 1e3
        y1 = (start + n - 1 - (len(xi) - 1) / 2) * sensor.pixel_size * 1e3
        ax1.add_patch(plt.Rectangle((y0, off * 1e3 - 0.15), y1 - y0, 0.3, color="C0" if k % 2 == 0 else "C1",
                                    alpha=0.6))
        ax1.text((y0 + y1) / 2, off * 1e3, f"matrix {k + 1}\nx_i = {off * 1e3:+.1f} mm", ha="center",
                 va="center", fontsize=7)
        start += n
    ax1.set_xlim(-13, 13); ax1.set_ylim(-3, 3)
    ax1.set_xlabel("y (mm, along the CCD line)"); ax1.set_ylabel("x (mm, along the flight)")
    ax1.set_title("staggered focal plane (Fig. 8.4)")
    cols = np.arange(len(xi), dtype=float)
    X, Y = sensor.ground(np.full(len(xi), 500.0), cols, 0.0)
    ax2.scatter(Y, X, c=np.where(xi > 0, "C0", "C1"), s=2)
    ax2.set_xlabel("Y (m)"); ax2.set_ylabel("X (m)")
    ax2.set_title("ground seen by line 500: two rows of matrices")
    fig.tight_layout()
    gap = float(np.ptp(X))
    return _done(fig), round(gap, 3)


def flat_terrain_ambiguity(seed=0):
    """Fig. 8.14: condition numbers of the resection on flat/hilly GCPs, free and with one element
    fixed (Resurs-P-like sensor), and two EO sets imaging flat ground almost identically."""
    eo = pb.EOPolynomial([1000.0, -500.0, 475e3, 0.01, 0.02, 0.005], [7000, 5, -2, 1e-6, -1e-6, 2e-6])
    cam = pb.Pushbroom(3.8, 8e-6, 38000, 1 / 7000, eo, n_rows=30000)
    rng = np.random.default_rng(seed)
    rows, cols = rng.uniform(0, 30000, 12), rng.uniform(0, 37999, 12)
    X, Y = cam.ground(rows, cols, 0.0)
    flat = np.column_stack([X, Y, np.zeros(12)])
    Zh = rng.uniform(0, 2000, 12)
    Xh, Yh = cam.ground(rows, cols, Zh)
    hilly = np.column_stack([Xh, Yh, Zh])
    cases = {"flat, free": pb.resection_condition(cam, rows, cols, flat)}
    for name in ("Z_S0", "X_S0", "alpha0"):
        cases[f"flat, {name} fixed"] = pb.resection_condition(cam, rows, cols, flat, fixed=(name,))
    cases["hilly (0–2 km), free"] = pb.resection_condition(cam, rows, cols, hilly)
    # the ambiguity: hold X_S0 20 km ahead and let the resection find the rest (loose priors keep
    # the narrow-field normal matrix inside the engine's limit); the rays still hit the same points
    dX = 20000.0
    start = cam.with_eo(pb.EOPolynomial(eo.eo0 + [dX, 0, 0, 0, dX / eo.eo0[2], 0], eo.k))
    sigma = [1e5] * 3 + [1.0] * 3 + [1e4] * 3 + [1e-2] * 3
    other = pb.resect_pushbroom(start, rows, cols, flat, fixed=("X_S0",), sigma_eo=sigma).sensor
    r2, c2 = other.project(X, Y, np.zeros(12))
    shift = float(np.max(np.hypot(r2 - rows, c2 - cols)))
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 3.8))
    for sensor, colour, label in ((cam, "C0", "EO 1"), (other, "C3", f"EO 2: X_S0 + {dX / 1e3:.0f} km (resected)")):
        rr, cc = sensor.project(X[:5], Y[:5], np.zeros(5))
        S, _ = sensor.object_rays(rr, cc)                     # each point: the centre of its own line
        for x, s_ in zip(X[:5], S):
            ax1.plot([s_[0] / 1e3, x / 1e3], [s_[2] / 1e3, 0], colour, lw=0.7)
        ax1.plot(S[:, 0] / 1e3, S[:, 2] / 1e3, "o", color=colour, ms=3, label=label)
    ax1.axhline(0, color="k", lw=1)
    ax1.set_xlabel("X (km)"); ax1.set_ylabel("Z (km)"); ax1.legend(fontsize=7)
    ax1.set_title(f"flat ground: the two EO sets differ on the image by ≤ {shift:.1e} px", fontsize=9)
    names = list(cases)
    ax2.barh(names, [np.log10(cases[n]) for n in names], color=["C3", "C0", "C0", "C0", "C2"])
    ax2.set_xlabel("log10 condition number (columns scaled)")
    ax2.set_title("resection conditioning (12 GCPs)")
    fig.tight_layout()
    dZ = float(other.eo.eo0[2] - eo.eo0[2])
    return _done(fig), {k: float(f"{v:.2g}") for k, v in cases.items()}, {"dX_S0": dX, "dZ_S0": round(dZ, 0),
                                                                           "max_image_shift_px": float(f"{shift:.1g}")}
