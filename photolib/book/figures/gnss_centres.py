"""Figures for the GNSS-centres appendix (Dobrynin & Pimshina, seed 001): geometry and convergence."""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np


def pair_plan(pairs, titles, ax=None):
    """Plan view (east right, north up) of synthetic pairs: centres, base, tie points, control point."""
    if ax is None:
        _, ax = plt.subplots(1, len(pairs), figsize=(4 * len(pairs), 4), constrained_layout=True)
    for a, p, t in zip(np.atleast_1d(ax), pairs, titles):
        a.plot(p.ground[:, 1], p.ground[:, 0], "k.", label="tie points")
        c = list(p.control)
        a.plot(p.ground[c, 1], p.ground[c, 0], "r^", ms=9, label="control point")
        a.plot([p.S1[1], p.S2[1]], [p.S1[0], p.S2[0]], "b-o", label="base S₁S₂")
        a.annotate("S₁", (p.S1[1], p.S1[0]), xytext=(5, -12), textcoords="offset points")
        a.annotate("S₂", (p.S2[1], p.S2[0]), xytext=(5, 5), textcoords="offset points")
        a.set(aspect="equal", xlabel="Y (east), m", ylabel="X (north), m", title=t)
    np.atleast_1d(ax)[0].legend(fontsize=8, loc="lower left")
    return ax


def convergence_histories(histories, title=""):
    """max |δ| per iteration (log scale): one panel per flight direction, derived vs printed partials.

    ``histories`` maps a panel label to ``{"derived": [IterationHistory...], "printed": [...]}``.
    """
    fig, axes = plt.subplots(1, len(histories), figsize=(3.3 * len(histories), 3.4), sharey=True,
                             constrained_layout=True)
    for ax, (label, runs) in zip(np.atleast_1d(axes), histories.items()):
        for kind, colour in (("derived", "C0"), ("printed", "C3")):
            for i, h in enumerate(runs[kind]):
                ax.semilogy(np.arange(1, len(h.max_correction) + 1), np.degrees(h.max_correction) * 3600,
                            color=colour, lw=1, alpha=0.7, label=f"{kind} partials" if i == 0 else None)
        ax.set(title=label, xlabel="iteration")
    np.atleast_1d(axes)[0].set_ylabel("max |δ|, arcsec")
    np.atleast_1d(axes)[0].legend(fontsize=8)
    if title:
        fig.suptitle(title)
    return fig
