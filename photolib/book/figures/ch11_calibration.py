"""Figures for Chapter 11, §11.3 (camera calibration by a flat test object).

* :func:`board_homography` — board plane (X′, Y′) → pixel of a camera with focal length f (px)
  looking at the board from ``dist`` board units, tilted by ω, α (the board pose of (11.3.8)).
* :func:`rendered_board_detection` — a chessboard rendered through that homography
  (:func:`photolib.calibration.render_chessboard`), the inner corners found by
  :func:`photolib.calibration.find_chessboard` against the true ones, with a magnified corner.
* :func:`rendered_calibration` — several tilted views of the rendered board calibrated by
  :func:`photolib.calibration.calibrate_chessboard`; f, x₀, y₀ against the truth.
* :func:`real_board_residuals` — real images (OpenCV's sample ``left01…14.jpg``, found through
  :mod:`photolib.datasets`): photolib's corners of every view, photolib's calibration of all of
  them (11.3.8), and one view with its detections and exaggerated reprojection residual vectors.

Every figure function returns the matplotlib Figure (closed, so that a notebook shows it once)
together with the numbers it shows, rounded.
"""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np

from ... import calibration as cal
from ... import datasets
from ...rotation import rotation_matrix

__all__ = ["board_homography", "rendered_board_detection", "rendered_calibration", "real_board_residuals"]


def _done(fig):
    plt.close(fig)
    return fig


def board_homography(omega, alpha, f=600.0, dist=10.0, shape=(480, 640), centre=(3.0, 2.0)):
    """Board (X′, Y′, 1) → pixel (u, v, 1) of a pinhole camera (principal point at the image centre).

    The camera looks at the board point ``centre`` from ``dist`` along the board normal turned by
    A(ω, α, 0) (κ–α–ω); pixel rows grow downwards (y of the image up).
    """
    A = rotation_matrix(omega, alpha, 0.0, "kaw")
    R = np.diag([1.0, -1.0, -1.0]) @ A.T
    S = np.array([centre[0], centre[1], 0.0]) + A @ np.array([0.0, 0.0, dist])
    t = -R @ S
    K = np.array([[f, 0, (shape[1] - 1) / 2], [0, f, (shape[0] - 1) / 2], [0, 0, 1]])
    return K @ np.column_stack([R[:, 0], R[:, 1], t])


def _true_corners(H, squares):
    g = np.array([(i, j) for j in range(1, squares[1]) for i in range(1, squares[0])], dtype=float)
    t = (H @ np.column_stack([g, np.ones(len(g))]).T).T
    return t[:, :2] / t[:, 2:]


def rendered_board_detection(omega=0.35, alpha=-0.25, squares=(7, 5), shape=(480, 640)):
    """Rendered board, detected vs true inner corners, and a 4× magnified corner window.

    Returns (figure, {"corners": n, "rms_px": …, "max_px": …}).
    """
    H = board_homography(omega, alpha, shape=shape)
    img = cal.render_chessboard(squares, 1.0, H, shape)
    found = np.asarray(cal.find_chessboard(img, (squares[0] - 1, squares[1] - 1), name="rendered"), float)
    truth = _true_corners(H, squares)
    from scipy.spatial import cKDTree

    d, idx = cKDTree(truth).query(found)
    fig, (a, b) = plt.subplots(1, 2, figsize=(10, 4), gridspec_kw={"width_ratios": [1.6, 1]})
    a.imshow(img, cmap="gray", vmin=0, vmax=255)
    a.plot(truth[:, 0], truth[:, 1], "o", mfc="none", mec="tab:green", ms=9, label="true corner")
    a.plot(found[:, 0], found[:, 1], "+", color="tab:red", ms=8, label="find_chessboard")
    a.plot(found[0, 0], found[0, 1], "s", mfc="none", mec="tab:orange", ms=12, label="first corner (origin)")
    a.set_title(f"rendered board, ω = {omega:.2f}, α = {alpha:.2f} rad")
    a.legend(loc="lower right", fontsize=8)
    a.set_axis_off()
    k = int(np.argmax(d))
    u, v = np.round(truth[idx[k]]).astype(int)
    r = 8
    b.imshow(img[v - r:v + r + 1, u - r:u + r + 1], cmap="gray", vmin=0, vmax=255,
             extent=(u - r - 0.5, u + r + 0.5, v + r + 0.5, v - r - 0.5))
    b.plot(*truth[idx[k]], "o", mfc="none", mec="tab:green", ms=14)
    b.plot(*found[k], "+", color="tab:red", ms=14, mew=2)
    b.set_title(f"worst corner: {d[k]:.3f} px from the truth")
    fig.tight_layout()
    return _done(fig), {"corners": int(len(set(idx))), "rms_px": round(float(np.sqrt(np.mean(d ** 2))), 3),
                        "max_px": round(float(d.max()), 3)}


def rendered_calibration(poses=((0.4, 0.0), (-0.4, 0.1), (0.1, 0.4), (0.0, -0.4), (0.3, 0.3)), f=600.0,
                         squares=(7, 5), shape=(480, 640)):
    """Calibrate f, x₀, y₀ from rendered tilted views (11.3.8); the truth is f, x₀ = y₀ = 0.

    Returns (figure: the views' corners in one frame, {"f": …, "x0": …, "y0": …, "rms_px": …}).
    """
    corners = []
    for w, a in poses:
        img = cal.render_chessboard(squares, 1.0, board_homography(w, a, f=f, shape=shape), shape)
        corners.append(np.asarray(cal.find_chessboard(img, (squares[0] - 1, squares[1] - 1)), float))
    r = cal.calibrate_chessboard(corners, (squares[0] - 1, squares[1] - 1), 1.0, shape, calibrate=("f", "x0", "y0"))
    fig, ax = plt.subplots(figsize=(6, 4.5))
    for (w, a), c in zip(poses, corners):
        ax.plot(c[:, 0], c[:, 1], ".", label=f"ω = {w:+.1f}, α = {a:+.1f}")
    ax.set_xlim(0, shape[1]); ax.set_ylim(shape[0], 0); ax.set_aspect("equal")
    ax.set_title(f"{len(poses)} tilted views: f = {r.io.f:.2f} px (true {f:.0f})")
    ax.legend(fontsize=7, loc="upper right")
    return _done(fig), {"f": round(float(r.io.f), 2), "x0": round(float(r.io.x0), 2), "y0": round(float(r.io.y0), 2),
                        "rms_px": round(float(r.rms), 3)}


def real_board_residuals(view="left01.jpg", exaggeration=150.0, pattern=(9, 6), square_size=25.0,
                         calibrate=("f", "x0", "y0", "k1", "k2", "k3", "p1", "p2")):
    """Chessboard method (11.3.8) on real images: detections and reprojection residuals of one view.

    Finds the corners of every ``left*.jpg`` of OpenCV's sample set (``calibration/opencv_chessboard``
    of the real data) with :func:`photolib.calibration.find_chessboard`, calibrates the camera from
    all views with :func:`photolib.calibration.calibrate_chessboard` (f, x₀, y₀ and Brown's
    distortion, in pixels), and draws ``view`` with its detected corners and the residual vectors
    v (model − measured, (11.3.3)) magnified ``exaggeration`` times, with a scale bar; a second panel
    pools the residuals of every view. Raises :class:`photolib.datasets.DataUnavailableError` where
    the data is absent.

    Returns (figure, {"views", "corners", "f_px", "x0_px", "y0_px", "rms_px", "view_rms_px",
    "max_px"}), rounded.
    """
    folder = datasets.data_path("calibration", "opencv_chessboard")
    paths = sorted(folder.glob("left*.jpg"))
    images = [datasets.read_image(p) for p in paths]
    corners = [np.asarray(cal.find_chessboard(img, pattern, name=p.name), float) for p, img in zip(paths, images)]
    shape = images[0].shape
    r = cal.calibrate_chessboard(corners, pattern, square_size, shape, calibrate=calibrate)
    k = [p.name for p in paths].index(view)
    found, v = corners[k], r.residuals[k]                       # v in image coordinates (x right, y up), px
    du, dv = v[:, 0], -v[:, 1]                                  # → pixel columns / rows (rows grow downwards)
    view_rms = float(np.sqrt(np.mean(np.sum(v ** 2, axis=1))))
    fig, (a, b) = plt.subplots(1, 2, figsize=(11, 4.3), gridspec_kw={"width_ratios": [1.55, 1]})
    a.imshow(images[k], cmap="gray", vmin=0, vmax=255)
    a.plot(found[:, 0], found[:, 1], "+", color="tab:red", ms=6, label="find_chessboard")
    a.quiver(found[:, 0], found[:, 1], du, dv, angles="xy", scale_units="xy", scale=1.0 / exaggeration,
             color="yellow", width=0.004, label=f"residual × {exaggeration:g}")
    lo = np.maximum(found.min(axis=0) - 60.0, 0.0)                # the board and a margin
    hi = np.minimum(found.max(axis=0) + 60.0, [shape[1] - 1.0, shape[0] - 1.0])
    a.set_xlim(lo[0], hi[0])
    a.set_ylim(hi[1], lo[1])
    bar = 0.5                                                    # px
    x0, y0 = lo[0] + 12.0, hi[1] - 14.0
    a.plot([x0, x0 + bar * exaggeration], [y0, y0], color="yellow", lw=3)
    a.text(x0, y0 - 7, f"{bar} px × {exaggeration:g}", color="yellow", fontsize=8,
           bbox={"facecolor": "black", "alpha": 0.6, "pad": 1.5, "edgecolor": "none"})
    a.set_title(f"{view}: corners and residuals; RMS {view_rms:.3f} px (this view), {r.rms:.3f} px (all)",
                fontsize=9)
    a.legend(loc="upper right", fontsize=7)
    a.set_axis_off()
    allv = np.vstack(r.residuals)
    b.plot(allv[:, 0], allv[:, 1], ".", ms=2, color="tab:blue")
    t = np.linspace(0, 2 * np.pi, 200)
    b.plot(r.rms * np.cos(t), r.rms * np.sin(t), color="tab:red", label=f"RMS {r.rms:.3f} px")
    b.set_aspect("equal")
    b.set_xlabel("v_x (px)")
    b.set_ylabel("v_y (px)")
    b.set_title(f"residuals of all {len(paths)} views ({len(allv)} corners)", fontsize=9)
    b.legend(fontsize=7, loc="upper right")
    fig.tight_layout()
    return _done(fig), {"views": len(paths), "corners": int(len(allv)), "f_px": round(float(r.io.f), 1),
                        "x0_px": round(float(r.io.x0), 1), "y0_px": round(float(r.io.y0), 1),
                        "rms_px": round(float(r.rms), 3), "view_rms_px": round(view_rms, 3),
                        "max_px": round(float(np.sqrt(np.sum(allv ** 2, axis=1)).max()), 2)}
