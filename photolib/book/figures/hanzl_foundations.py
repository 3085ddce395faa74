"""Figures for Hanzl's mathematical foundations, §2 (seed 002; ``chapters/appendix_hanzl_2_foundations.ipynb``).

* :func:`transformation_grids` — Obr. 2.4 redrawn: a square grid under the six plane transformations of
  §2.5 (:class:`photolib.plane_transforms.PlaneTransform`).
* :func:`weight_functions` — Obr. 2.5 redrawn: the Danish weight function exp(−0.05 t^d) for d = 4.4 and
  3.0 (:func:`photolib.lsq.danish_weight`) against the constant weight of least squares.
* :func:`resection_residuals` — the image residuals of a resection with planted blunders: ordinary least
  squares against the robust (Danish) adjustment.

Every function returns the matplotlib Figure, closed (a notebook cell shows it once).
"""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np

from ... import lsq
from ... import plane_transforms as pt

__all__ = ["transformation_grids", "weight_functions", "resection_residuals", "GRID_EXAMPLES"]

GRID_EXAMPLES = {
    "congruent": [np.radians(15.0), 0.15, -0.1],
    "similarity": [0.8 * np.cos(np.radians(-10.0)), 0.8 * np.sin(np.radians(-10.0)), 0.1, 0.1],
    "affine": [1.0, 0.35, 0.0, 0.1, 0.75, 0.0],
    "projective": [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.35, 0.2],
    "bilinear": [0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.45],
    "polynomial": [0.0, 1.0, 0.0, 0.0, 0.25, 0.0, 0.0, 0.0, 1.0, -0.3, 0.0, 0.0],
}
"""Illustrative parameters of each transformation for :func:`transformation_grids` (unit square, centred)."""

_CZECH = {"congruent": "shodnostní", "similarity": "podobnostní", "affine": "afinní",
          "projective": "kolineární", "bilinear": "bilineární", "polynomial": "polynomická"}


def _done(fig):
    plt.close(fig)
    return fig


def transformation_grids(n: int = 7):
    """Obr. 2.4: an n × n grid on [−0.5, 0.5]² (grey) and its image under each transformation (blue)."""
    g = np.linspace(-0.5, 0.5, n)
    fine = np.linspace(-0.5, 0.5, 60)
    fig, axes = plt.subplots(2, 3, figsize=(10.5, 7.0), constrained_layout=True)
    for ax, kind in zip(axes.ravel(), pt.KINDS):
        T = pt.PlaneTransform(kind, GRID_EXAMPLES[kind])
        for v in g:
            for line in (np.column_stack([np.full_like(fine, v), fine]), np.column_stack([fine, np.full_like(fine, v)])):
                ax.plot(line[:, 0], line[:, 1], color="0.8", lw=0.8)
                img = T.apply(line)
                ax.plot(img[:, 0], img[:, 1], color="tab:blue", lw=1.0)
        ax.set_title(f"{kind} ({_CZECH[kind]})\n{pt.N_PARAMETERS[kind]} parameters, "
                     f"at least {pt.MIN_POINTS[kind]} points", fontsize=9)
        ax.set_aspect("equal")
        ax.set_xlim(-1.0, 1.0)
        ax.set_ylim(-1.0, 1.0)
        ax.tick_params(labelsize=7)
    fig.suptitle("Hanzl Obr. 2.4 redrawn: a grid (grey) under the six plane transformations of §2.5 (blue)")
    return _done(fig)


def weight_functions(t_max: float = 5.0):
    """Obr. 2.5: weight factor against the standardised residual t = |v√p|/σ₀."""
    t = np.linspace(0.0, t_max, 400)
    fig, ax = plt.subplots(figsize=(7.5, 4.2), constrained_layout=True)
    ax.plot(t, np.ones_like(t), color="0.5", ls="--", label="least squares: p = 1")
    for d, style in zip(lsq.DANISH_EXPONENTS, ("-", "-.")):
        ax.plot(t, lsq.danish_weight(t, d), style, lw=2, label=f"Danish, d = {d} (iteration {'2' if d == 4.4 else '3…n'})")
    ax.plot(t, -0.05 * t ** 3.0, ":", color="tab:red", label="as transcribed (exp lost), d = 3.0")
    ax.set_ylim(-0.3, 1.1)
    ax.axhline(0.0, color="k", lw=0.5)
    ax.set_xlabel("standardised residual t = |v√p| / σ₀")
    ax.set_ylabel("weight factor p(v)")
    ax.set_title("Hanzl Obr. 2.5 redrawn: the weight function of the Danish method")
    ax.legend(fontsize=8)
    return _done(fig)


def resection_residuals(xy, plain_residuals, robust_residuals, bad, rejected, scale: float = 100.0):
    """Residual vectors (mm, exaggerated ``scale`` ×) of plain LS and of the robust resection at the image points.

    Parameters
    ----------
    xy : (n, 2) image points (mm); plain_residuals, robust_residuals : (n, 2) v_x, v_y (mm);
    bad : indices of the planted blunders; rejected : bool (n,) points rejected by the robust method.
    """
    xy = np.asarray(xy, float)
    fig, axes = plt.subplots(1, 2, figsize=(11.0, 5.2), constrained_layout=True)
    for ax, V, title in zip(axes, (plain_residuals, robust_residuals),
                            ("ordinary least squares (all points)", "Danish method, then LS without the rejected")):
        V = np.asarray(V, float)
        good = np.setdiff1d(np.arange(len(xy)), bad)
        ax.quiver(xy[good, 0], xy[good, 1], V[good, 0], V[good, 1], angles="xy", scale_units="xy",
                  scale=1.0 / scale, color="tab:blue", width=0.004, label="good points")
        ax.quiver(xy[bad, 0], xy[bad, 1], V[bad, 0], V[bad, 1], angles="xy", scale_units="xy",
                  scale=1.0 / scale, color="tab:red", width=0.004, label="planted blunders")
        rej = np.flatnonzero(rejected) if ax is axes[1] else np.array([], int)
        if rej.size:
            ax.plot(xy[rej, 0], xy[rej, 1], "o", mfc="none", mec="k", ms=11, label="rejected")
        ax.plot(xy[:, 0], xy[:, 1], "k.", ms=3)
        ax.set_aspect("equal")
        ax.set_xlim(-115, 115)
        ax.set_ylim(-115, 115)
        ax.set_xlabel("x (mm)")
        ax.set_ylabel("y (mm)")
        ax.set_title(f"{title}\nresiduals × {scale:g}", fontsize=10)
        ax.legend(fontsize=8, loc="lower right")
    return _done(fig)
