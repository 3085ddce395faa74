"""Figures for Hanzl §3, two images (seed 002 lines 344–674; ``chapters/appendix_hanzl_3_two_images.ipynb``).

* :func:`gruber_layout` — Fig. 3.3: the six Gruber points in the two images of a 60 % overlap.
* :func:`model_deformation_maps` — Fig. 3.4 regenerated: the height deformation dz of a model caused by
  dκ₂, dφ₂, db_z and dω₂ (the corrected formula, :func:`photolib.image_pair.model_deformation`).
* :func:`normal_case_laws` — the three accuracy laws of §3.2.6 (σ_Z against m_s, B/Z and Z).

Every function returns the matplotlib Figure, closed (a notebook cell shows it once).
"""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np

from ... import image_pair as ip

__all__ = ["gruber_layout", "model_deformation_maps", "normal_case_laws"]


def _done(fig):
    plt.close(fig)
    return fig


def gruber_layout(xy1, xy2, side=230.0):
    """Both images (format ``side`` mm) with the measured Gruber points numbered 1–6."""
    fig, axes = plt.subplots(1, 2, figsize=(8.0, 4.2), constrained_layout=True)
    for ax, xy, name in zip(axes, (xy1, xy2), ("image 1", "image 2")):
        h = side / 2
        ax.plot([-h, h, h, -h, -h], [-h, -h, h, h, -h], color="0.4")
        ax.plot(np.asarray(xy)[:, 0], np.asarray(xy)[:, 1], "o", color="tab:red")
        for i, (x, y) in enumerate(np.asarray(xy), start=1):
            ax.annotate(str(i), (x, y), textcoords="offset points", xytext=(5, 5))
        ax.axhline(0, color="0.8", lw=0.8)
        ax.axvline(0, color="0.8", lw=0.8)
        ax.set_aspect("equal")
        ax.set_title(name)
        ax.set_xlabel("x (mm)")
        ax.set_ylabel("y (mm)")
    fig.suptitle("Gruber points of relative orientation (Hanzl Fig. 3.3)")
    return _done(fig)


def model_deformation_maps(h=1530.0, b=920.0, half_width=900.0, angle=1e-4, db_z=1.0):
    """dz (m) over the model area 0 ≤ x_m ≤ b, |y_m| ≤ ``half_width`` for dκ₂, dφ₂, db_z and dω₂ (Fig. 3.4)."""
    xm, ym = np.meshgrid(np.linspace(0.0, b, 41), np.linspace(-half_width, half_width, 61))
    cases = [("dkappa2", angle, f"dκ₂ = {angle * 1e3:g} mrad"), ("dphi2", angle, f"dφ₂ = {angle * 1e3:g} mrad"),
             ("db_z", db_z, f"db_z = {db_z:g} m"), ("domega2", angle, f"dω₂ = {angle * 1e3:g} mrad")]
    fig, axes = plt.subplots(1, 4, figsize=(11.0, 4.4), constrained_layout=True, sharey=True)
    for ax, (name, value, label) in zip(axes, cases):
        dz = ip.model_deformation(xm, ym, h, b, {name: value})
        lim = max(float(np.abs(dz).max()), 1e-12)
        im = ax.contourf(xm, ym, dz, levels=np.linspace(-lim, lim, 17), cmap="RdBu_r")
        ax.contour(xm, ym, dz, levels=[0.0], colors="k", linewidths=0.8)
        ax.set_title(label)
        ax.set_xlabel("x_m (m)")
        ax.set_aspect("equal")
        bar = fig.colorbar(im, ax=ax, orientation="horizontal", label="dz (m)", shrink=0.9)
        bar.set_ticks([-lim, 0.0, lim])
        bar.set_ticklabels([f"{-lim:.2f}", "0", f"{lim:.2f}"])
    axes[0].set_ylabel("y_m (m)")
    fig.suptitle(f"Model deformation dz = (h/b)·p_x, h = {h:g} m, b = {b:g} m (Hanzl Fig. 3.4, corrected formula)")
    return _done(fig)


def normal_case_laws(ms=10000.0, c=150.0, sigma_um=10.0):
    """σ_Z of the normal case: against m_s (B/Z fixed), against B/Z (m_s fixed) and against Z (B fixed)."""
    s = sigma_um / 1000.0
    fig, axes = plt.subplots(1, 3, figsize=(11.0, 3.4), constrained_layout=True)
    scales = np.linspace(2000.0, 30000.0, 50)
    axes[0].plot(scales, [ip.normal_case_accuracy(m * c / 1000, c, c / 1.6, s, s, s)[2] for m in scales])
    axes[0].set_xlabel("m_s (B/Z = 1/1.6)")
    ratios = np.linspace(0.2, 1.0, 50)
    axes[1].plot(ratios, [ip.normal_case_accuracy(ms * c / 1000, c, c * r, s, s, s)[2] for r in ratios])
    axes[1].set_xlabel(f"B/Z (m_s = {ms:g})")
    B = ms * c / 1000 / 1.6
    Z = np.linspace(500.0, 3000.0, 50)
    axes[2].plot(Z, [ip.normal_case_accuracy(z, c, c * B / z, s, s, s)[2] for z in Z])
    axes[2].set_xlabel(f"Z (m), B = {B:g} m")
    for ax in axes:
        ax.set_ylabel("σ_Z (m)")
        ax.grid(alpha=0.3)
    fig.suptitle(f"Accuracy laws of the normal case (Hanzl §3.2.6), c = {c:g} mm, σ_px = {sigma_um:g} µm")
    return _done(fig)
