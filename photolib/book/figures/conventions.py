"""Figures for the Conventions appendix: camera axes, elementary rotations, image/pixel systems,
distortion models (Chapter 1, §1.2–§1.3 and §1.10)."""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np

from ... import conventions as cv
from ...camera import correct_distortion
from ...rotation import rot_x, rot_y, rot_z

_COLORS = ("tab:red", "tab:green", "tab:blue")


def _arrow3d(ax, origin, vec, color, label, lw=2.0):
    ax.quiver(*origin, *vec, color=color, linewidth=lw, arrow_length_ratio=0.15)
    tip = np.asarray(origin) + 1.12 * np.asarray(vec)
    ax.text(*tip, label, color=color, fontsize=11, ha="center", va="center")


def camera_axes_figure(f: float = 0.45):
    """Camera axes of a level (nadir) camera in the book/Hanzl/Wolf convention and in OpenCV's,
    drawn in the object system (X east, Y north, Z up), with the image plane and one ray."""
    fig = plt.figure(figsize=(11, 5))
    S = np.array([0.0, 0.0, 1.9])
    setups = [
        ("Book (§1.2), Hanzl, Wolf: looks along −z", np.eye(3), ("x", "y", "z"), -1.0),
        ("OpenCV: looks along +z, y down", cv.BOOK_TO_OPENCV_CAMERA, ("x", "y", "z"), 1.0),
    ]
    for n, (title, axes_in_book, names, look) in enumerate(setups):
        ax = fig.add_subplot(1, 2, n + 1, projection="3d")
        # object system
        for k, lab in enumerate("XYZ"):
            e = np.eye(3)[k] * 0.8
            _arrow3d(ax, (0, 0, 0), e, "0.45", lab, lw=1.2)
        # camera axes: rows of axes_in_book are the camera axes in book-camera (= object) terms
        for k in range(3):
            _arrow3d(ax, S, axes_in_book[k] * 0.5, _COLORS[k], names[k])
        # image plane (positive, in front of S) and the viewing direction
        zc = -f
        sq = np.array([[-.35, -.35], [.35, -.35], [.35, .35], [-.35, .35], [-.35, -.35]])
        ax.plot(S[0] + sq[:, 0], S[1] + sq[:, 1], np.full(5, S[2] + zc), color="0.3")
        P = np.array([0.5, 0.35, 0.0])
        ax.plot(*np.column_stack([S, P]), color="tab:orange", linestyle="--")
        ax.scatter(*P, color="tab:orange")
        ax.text(*(P + [0.05, 0, 0.05]), "P", color="tab:orange")
        ax.scatter(*S, color="k")
        ax.text(*(S + [-.12, -.12, .05]), "S", color="k")
        ax.set_title(title, fontsize=10)
        ax.set_xlim(-.8, .8), ax.set_ylim(-.8, .8), ax.set_zlim(0, 2.5)
        ax.set_box_aspect((1, 1, 1.2))
        ax.view_init(elev=18, azim=-60)
        ax.set_xticks([]), ax.set_yticks([]), ax.set_zticks([])
    fig.suptitle("Camera axes of a nadir image (grey: object system OXYZ; dashed: the ray to P)")
    fig.tight_layout()
    return fig


def elementary_rotations_figure(angle_deg: float = 30.0):
    """A_ω, A_α, A_κ: each rotates the other two axes counter-clockwise seen from the tip of its axis."""
    fig, axes = plt.subplots(1, 3, figsize=(11, 3.8))
    t = np.radians(angle_deg)
    cases = [("A_ω about X", rot_x(t), (1, 2), "YZ"), ("A_α about Y", rot_y(t), (2, 0), "ZX"),
             ("A_κ about Z", rot_z(t), (0, 1), "XY")]
    for ax, (title, M, (i, j), plane) in zip(axes, cases):
        for k, style in ((i, "-"), (j, "-")):
            e = np.eye(3)[k]
            ax.annotate("", xy=(e[i], e[j]), xytext=(0, 0), arrowprops=dict(arrowstyle="->", color="0.5"))
            ax.text(1.08 * e[i], 1.08 * e[j], "XYZ"[k], color="0.4")
            r = M @ e                  # the rotated axis
            ax.annotate("", xy=(r[i], r[j]), xytext=(0, 0), arrowprops=dict(arrowstyle="->", color="tab:blue"))
            ax.text(1.12 * r[i], 1.12 * r[j], "xyz"[k] + "′", color="tab:blue")
        arc = np.linspace(0, t, 30)
        ax.plot(0.45 * np.cos(arc), 0.45 * np.sin(arc), color="tab:red")
        ax.text(0.5 * np.cos(t / 2) + .03, 0.5 * np.sin(t / 2), f"{angle_deg:g}°", color="tab:red")
        ax.set_xlabel(plane[0]), ax.set_ylabel(plane[1])
        ax.set_title(f"{title} (axis out of the page)", fontsize=10)
        ax.set_xlim(-.75, 1.3), ax.set_ylim(-.3, 1.3), ax.set_aspect("equal")
    fig.tight_layout()
    return fig


def image_systems_figure(n_rows: int = 6, n_cols: int = 8):
    """Image plane systems: book o'xy (mm, y up, origin at the centre), OpenCV (u, v) (v down,
    origin at the centre of the top-left pixel) and the raster system of §1.10 (rows from the top)."""
    fig, ax = plt.subplots(figsize=(7, 5.2))
    for r in range(n_rows + 1):
        ax.plot([0, n_cols], [r, r], color="0.85", lw=0.8)
    for c in range(n_cols + 1):
        ax.plot([c, c], [0, n_rows], color="0.85", lw=0.8)
    W, H = n_cols, n_rows
    arrow = dict(arrowstyle="->", lw=2)
    # book: origin at the sensor centre, x right, y up
    ax.annotate("", xy=(W / 2 + 2, H / 2), xytext=(W / 2, H / 2), arrowprops={**arrow, "color": "tab:blue"})
    ax.annotate("", xy=(W / 2, H / 2 + 2), xytext=(W / 2, H / 2), arrowprops={**arrow, "color": "tab:blue"})
    ax.text(W / 2 + 2.1, H / 2 - .1, "x (mm)", color="tab:blue")
    ax.text(W / 2 - .3, H / 2 + 2.15, "y (mm)", color="tab:blue")
    ax.text(W / 2 + .1, H / 2 - .35, "o′", color="tab:blue")
    # OpenCV pixels: origin at the centre of the top-left pixel, u right, v down
    o = (0.5, H - 0.5)
    ax.annotate("", xy=(o[0] + 2, o[1]), xytext=o, arrowprops={**arrow, "color": "tab:red"})
    ax.annotate("", xy=(o[0], o[1] - 2), xytext=o, arrowprops={**arrow, "color": "tab:red"})
    ax.text(o[0] + 2.1, o[1] - .1, "u (OpenCV)", color="tab:red")
    ax.text(o[0] + .1, o[1] - 2.3, "v", color="tab:red")
    # raster (left-handed) system of §1.10: origin at the top-left corner, j right, i down
    ax.annotate("", xy=(1.5, H), xytext=(0, H), arrowprops={**arrow, "color": "tab:green"})
    ax.annotate("", xy=(0, H - 1.5), xytext=(0, H), arrowprops={**arrow, "color": "tab:green"})
    ax.text(1.2, H + .15, "j (column)", color="tab:green")
    ax.text(-1.3, H - 1.6, "i (row)", color="tab:green")
    # right-handed photogrammetric pixel system of §1.10: origin at the bottom-left corner
    ax.annotate("", xy=(1.5, 0), xytext=(0, 0), arrowprops={**arrow, "color": "tab:purple"})
    ax.annotate("", xy=(0, 1.5), xytext=(0, 0), arrowprops={**arrow, "color": "tab:purple"})
    ax.text(1.2, -.45, "x_p", color="tab:purple")
    ax.text(-.75, 1.3, "y_p", color="tab:purple")
    ax.set_xlim(-1.6, W + 2.8), ax.set_ylim(-1, H + 1), ax.set_aspect("equal"), ax.axis("off")
    ax.set_title("Image systems on one sensor (grid = pixels)")
    fig.tight_layout()
    return fig


def distortion_figure(io, dist, format_half_size_mm, n: int = 15):
    """Left: the book's distortion (measured − ideal) over the format. Right: the position error of
    OpenCV's model with the fitted ``dist`` (μm)."""
    h = np.broadcast_to(np.asarray(format_half_size_mm, dtype=float), (2,))
    gx, gy = np.meshgrid(np.linspace(-h[0], h[0], n), np.linspace(-h[1], h[1], n))
    measured = np.column_stack([gx.ravel(), gy.ravel()])
    ideal = correct_distortion(measured, io)
    pp = np.array([io.x0, io.y0])
    flip = np.array([1.0, -1.0])
    model = pp + cv.opencv_distort((ideal - pp) * flip / io.f, dist) * flip * io.f
    err_um = (model - measured) * 1000
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(11, 4.6))
    d_um = (measured - ideal) * 1000
    a1.quiver(ideal[:, 0], ideal[:, 1], d_um[:, 0], d_um[:, 1], color="tab:blue")
    a1.set_title(f"distortion, measured − ideal (max {np.hypot(*d_um.T).max():.0f} μm)", fontsize=10)
    mag = np.hypot(*err_um.T).reshape(gx.shape)
    cs = a2.contourf(gx, gy, mag, levels=12, cmap="viridis")
    fig.colorbar(cs, ax=a2, label="μm")
    a2.set_title("error of the converted OpenCV model", fontsize=10)
    for a in (a1, a2):
        a.set_xlabel("x, mm"), a.set_ylabel("y, mm"), a.set_aspect("equal")
    fig.tight_layout()
    return fig
