"""Figures for Chapter 3, §3.2–§3.4 (continuation, independent strips and models), from library calls.

* :func:`block_layout` — figs 3.2, 3.7, 3.8: image footprints, principal points, tie points with
  the number of adjacent-unit ties "(m)" and control points with the number of units "[k]".
* :func:`strip_deformation` — figs 3.5/3.6: errors of a strip network along the strip before and
  after the second-order polynomial correction (3.2.4).
* :func:`singular_values` — the spectrum of the column-scaled design of (3.4.1)–(3.4.3): GNSS
  centres alone fix a block, not a single strip.

Every function returns the matplotlib Figure (closed, so that a notebook shows it once).
"""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.patches import Rectangle

from ... import strip_triangulation as st
from ...synthetic import TIE, Block


def _done(fig):
    plt.close(fig)
    return fig


def block_layout(block: Block, units, control=None, adjacency=None, title="", show_footprints=True):
    """Plan of a layout block in the style of figs 3.7/3.8.

    Footprints of the images (thin rectangles, one colour per strip), principal points (⊕),
    tie points (○) labelled with the number of adjacent-unit pairs that share them "(m)",
    orientation points (·), control points (△) labelled "[k]" = number of units measuring them.
    """
    control = control or {}
    ties = st.tie_pairs(units, adjacency)
    pairs = {}
    for p, _, _ in ties:
        pairs[p] = pairs.get(p, 0) + 1
    fig, ax = plt.subplots(figsize=(8, 4.2 + 1.2 * (block.strip.max())))
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    L = block.footprint
    if show_footprints:
        for k, (X, Y) in enumerate(block.cameras[:, :2]):
            c = colours[int(block.strip[k]) % len(colours)]
            ax.add_patch(Rectangle((X - L / 2, Y - L / 2), L, L, fill=False, lw=0.6, ec=c, alpha=0.6))
    ax.plot(*block.cameras[:, :2].T, "k+", ms=10, mew=1.2)
    ax.plot(*block.cameras[:, :2].T, "o", mfc="none", mec="k", ms=8, label="principal point")
    for k, (X, Y) in enumerate(block.cameras[:, :2]):
        cid = st.centre_id(k)
        if cid in pairs:
            ax.annotate(f"({pairs[cid]})", (X, Y), textcoords="offset points", xytext=(6, -12), fontsize=8)
    for p, (X, Y, _), kind in zip(block.point_labels, block.points, block.kind):
        p = int(p)
        if p in control:
            n_units = sum(p in u for u in units)
            ax.plot(X, Y, "^", color="C3", ms=10)
            ax.annotate(f"[{n_units}]", (X, Y), textcoords="offset points", xytext=(6, 4), fontsize=8, color="C3")
            if p in pairs:
                ax.annotate(f"({pairs[p]})", (X, Y), textcoords="offset points", xytext=(6, -12), fontsize=8)
        elif kind == TIE:
            ax.plot(X, Y, "o", color="C0", ms=7, mfc="white")
            if p in pairs:
                ax.annotate(f"({pairs[p]})", (X, Y), textcoords="offset points", xytext=(6, 4), fontsize=8)
        else:
            ax.plot(X, Y, ".", color="0.5", ms=4)
    ax.plot([], [], "o", color="C0", mfc="white", label="tie point (m)")
    ax.plot([], [], "^", color="C3", label="control point [k]")
    ax.plot([], [], ".", color="0.5", label="orientation point")
    ax.set_aspect("equal")
    ax.set_xlabel("X, m")
    ax.set_ylabel("Y, m")
    ax.set_title(title)
    ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=8)
    fig.tight_layout()
    return _done(fig)


def strip_deformation(X, before, after, control_X, title="Strip deformation"):
    """Errors (network − truth) of the strip points along the strip, before and after (3.2.4).

    ``X``: coordinate along the strip (m); ``before``/``after``: (n, 3) errors; ``control_X``:
    along-strip positions of the control points (fig. 3.5 scheme).
    """
    fig, axes = plt.subplots(3, 1, figsize=(8, 6), sharex=True)
    order = np.argsort(X)
    for c, ax in enumerate(axes):
        ax.plot(X[order], before[order, c], "o", ms=4, color="C3", label="after external orientation (3.2.3)")
        ax.plot(X[order], after[order, c], "s", ms=4, color="C2", label="after the polynomial (3.2.4)")
        ax.axhline(0, color="0.6", lw=0.8)
        for x in control_X:
            ax.axvline(x, color="C0", lw=0.8, ls=":")
        ax.set_ylabel(f"Δ{'XYZ'[c]}, m")
    axes[0].legend(fontsize=8, loc="best")
    axes[-1].set_xlabel("X along the strip, m (dotted: control points)")
    axes[0].set_title(title)
    fig.tight_layout()
    return _done(fig)


def singular_values(spectra: dict, title="Column-scaled design of (3.4.1)–(3.4.3)"):
    """Singular values (relative to the largest) of several designs, e.g. block vs strip."""
    fig, ax = plt.subplots(figsize=(7, 3.2))
    for (name, s), m in zip(spectra.items(), "os^d"):
        s = np.asarray(s)
        ax.semilogy(np.arange(1, len(s) + 1), np.maximum(s / s[0], 1e-18), m + "-", ms=4, label=name)
    ax.set_xlabel("index")
    ax.set_ylabel("σ / σ_max")
    ax.set_title(title)
    ax.legend(fontsize=8)
    fig.tight_layout()
    return _done(fig)
