"""Figures for Chapter 3, §3.6, §3.8, §3.9: distortion fields, rig sparsity (fig. 3.18), rolling shutter."""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np

from ...camera import distortion_correction


def distortion_fields(true_io, recovered_io, half: float = 50.0, n: int = 9, scale: float | None = None):
    """Quiver plots of the correction (3.6.2) of the true and the recovered camera, and their difference."""
    g = np.linspace(-half, half, n)
    xy = np.stack(np.meshgrid(g, g), -1).reshape(-1, 2)
    d_true, d_rec = distortion_correction(xy, true_io), distortion_correction(xy, recovered_io)
    fig, axes = plt.subplots(1, 3, figsize=(12, 4), sharey=True)
    s = scale or np.abs(d_true).max() * n / (2 * half) * 1.5
    for ax, d, title in zip(axes, (d_true, d_rec, d_rec - d_true), ("true Δ", "recovered Δ", "recovered − true")):
        ax.quiver(xy[:, 0], xy[:, 1], d[:, 0], d[:, 1], angles="xy", scale_units="xy", scale=s, color="C0")
        ax.set_title(f"{title} (max {1000 * np.abs(d).max():.1f} µm)")
        ax.set_aspect("equal")
        ax.set_xlabel("x, mm")
    axes[0].set_ylabel("y, mm")
    fig.suptitle("Distortion correction (3.6.2), arrows enlarged")
    fig.tight_layout()
    return fig


def rig_sparsity(A_free, A_rig, control_rows=None, splits_free=(), splits_rig=()):
    """Side-by-side structure of the correction equations: fig. 3.11 (free EO) and fig. 3.18 (rig)."""
    fig, axes = plt.subplots(1, 2, figsize=(11, 6))
    for ax, A, splits, title in ((axes[0], A_free, splits_free, "fig. 3.11: EO of every image"),
                                 (axes[1], A_rig, splits_rig, "fig. 3.18: EO per exposure + mounting")):
        img = np.where(np.abs(A) > 0, 0.55, 1.0)
        if control_rows is not None:
            img[control_rows] = np.where(np.abs(A[control_rows]) > 0, 0.25, 1.0)
        ax.imshow(img, cmap="gray", vmin=0, vmax=1, aspect="auto", interpolation="nearest")
        for c in splits:
            ax.axvline(c - 0.5, color="C3", lw=1)
        ax.set_title(f"{title}\n{A.shape[0]} equations × {A.shape[1]} unknowns")
        ax.set_xlabel("unknown")
    axes[0].set_ylabel("correction equation")
    fig.tight_layout()
    return fig


def rolling_shutter_grid(frame_xy, rolling_xy, half: float = 6.6):
    """Image of a ground grid with a global (frame) and a rolling shutter."""
    fig, ax = plt.subplots(figsize=(5.5, 5.5))
    ax.plot(frame_xy[:, 0], frame_xy[:, 1], ".", color="0.6", label="frame (one EO)")
    ax.plot(rolling_xy[:, 0], rolling_xy[:, 1], ".", color="C3", ms=4, label="rolling shutter (EO per line)")
    ax.set_xlim(-half, half)
    ax.set_ylim(-half, half)
    ax.set_aspect("equal")
    ax.set_xlabel("x, mm (readout direction = time)")
    ax.set_ylabel("y, mm")
    ax.legend(loc="upper right", fontsize=8)
    ax.set_title("Rolling shutter: the grid is sheared and stretched")
    fig.tight_layout()
    return fig


def corridor_errors(X, err_without, err_with):
    """Cross-track and height errors of check points along a corridor, GNSS only vs with a dynamic GCP."""
    fig, axes = plt.subplots(2, 1, figsize=(9, 5), sharex=True)
    for ax, c, lab in zip(axes, (1, 2), ("ΔY (cross-track), m", "ΔZ, m")):
        ax.plot(X, err_without[:, c], "o", color="C3", label="GNSS centres only")
        ax.plot(X, err_with[:, c], "s", color="C0", label="GNSS + dynamic control point")
        ax.axhline(0, color="0.5", lw=0.8)
        ax.set_ylabel(lab)
    axes[0].legend(fontsize=8)
    axes[1].set_xlabel("X along the corridor, m")
    fig.tight_layout()
    return fig
