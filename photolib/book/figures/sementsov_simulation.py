"""Figures for the Sementsov appendix (Appendix E), simulations: §3.1 (Table 1, Appendix A, Fig. 40) and
§3.2 (Figs. 36, 42, 45, 46).

* :func:`variant_errors` — the analogue of Fig. 40: mean ± SKO and min/max of σ_f, σ_x₀, σ_y₀ of the
  ten variants, from the printed Appendix A rows.
* :func:`sko_comparison` — the book's SKOs beside the expected ones (first-order propagation) with
  the GNSS centre components held fixed or weighted, and a Monte Carlo.
* :func:`offset_sweep` — the analogue of Fig. 42: Δ(l) of f, x₀, y₀ with the ±m_ξ corridor on a
  logarithmic l axis, for the four series of Table 3.
* :func:`offset_error_bars` — the analogue of Figs. 45/46: errors of the reference calibration, of
  the one-centre calibration with the offset and of the tripod model (20).
* :func:`tripod_sphere` — the analogue of Fig. 36: the centres S_i = S₀ + A_i·l of the Table 2 images
  on the sphere of radius |l| about S₀.

Every function returns a matplotlib Figure, closed so that a notebook cell shows it once.
"""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np

from ... import mockup
from ...gnss_centres import rotation_aok

__all__ = ["variant_errors", "sko_comparison", "offset_sweep", "offset_error_bars", "tripod_sphere"]

_LABELS = ("σ_f", "σ_x₀", "σ_y₀")


def _done(fig):
    plt.close(fig)
    return fig


def variant_errors(errors: dict, title="Appendix A: errors of the interior orientation per variant (book data)"):
    """Fig. 40 analogue: per variant mean ± SKO (bar) and min … max (whisker) of σ_f, σ_x₀, σ_y₀ (px).

    ``errors`` maps a variant name to its (n, 3) error rows (e.g.
    :func:`photolib.book.sementsov_simulation.appendix_a_errors`).
    """
    names = list(errors)
    fig, axes = plt.subplots(1, 3, figsize=(12, 3.8), sharey=True, constrained_layout=True)
    x = np.arange(len(names))
    for k, ax in enumerate(axes):
        stats = [mockup.error_statistics(errors[v]) for v in names]
        mean = np.array([s.mean[k] for s in stats])
        sko = np.array([s.sko[k] for s in stats])
        lo = np.array([s.min[k] for s in stats])
        hi = np.array([s.max[k] for s in stats])
        ax.vlines(x, lo, hi, color="0.6", lw=1, label="min … max")
        ax.errorbar(x, mean, yerr=sko, fmt="o", color="C0", ms=4, capsize=4, lw=2.5, label="mean ± SKO")
        ax.axhline(0, color="k", lw=0.5)
        ax.set_xticks(x, names, rotation=45)
        ax.set(title=_LABELS[k], xlabel="variant")
        ax.grid(axis="y", alpha=0.3)
    axes[0].set_ylabel("error, px")
    axes[0].legend(fontsize=8, loc="lower left")
    fig.suptitle(title)
    return _done(fig)


def sko_comparison(book: dict, fixed: dict, weighted: dict, monte_carlo: dict | None = None,
                   title="SKO of the book (30 mock-ups) and re-simulated"):
    """The book's SKO per variant beside the expected SKO with GNSS held fixed and weighted.

    ``book``, ``fixed``, ``weighted`` map a variant to three SKOs (f, x₀, y₀; px); ``monte_carlo``
    optionally maps ``(variant, mode)`` to three Monte Carlo SKOs. Logarithmic y axis.
    """
    names = list(book)
    fig, axes = plt.subplots(1, 3, figsize=(12, 3.8), sharey=True, constrained_layout=True)
    x = np.arange(len(names))
    for k, ax in enumerate(axes):
        ax.bar(x - 0.2, [fixed[v][k] for v in names], 0.4, color="C0", alpha=0.55, label="expected, GNSS fixed")
        ax.bar(x + 0.2, [weighted[v][k] for v in names], 0.4, color="C2", alpha=0.55, label="expected, GNSS weighted")
        ax.plot(x, [book[v][k] for v in names], "kD", ms=6, label="book (Appendix A)")
        if monte_carlo:
            for mode, dx, c in (("fixed", -0.2, "C0"), ("weighted", 0.2, "C2")):
                pts = [(i + dx, monte_carlo[(v, mode)][k]) for i, v in enumerate(names) if (v, mode) in monte_carlo]
                if pts:
                    px, py = zip(*pts)
                    ax.plot(px, py, "o", mfc="none", mec=c, ms=7, label=f"Monte Carlo, {mode}")
        ax.set_yscale("log")
        ax.set_xticks(x, names, rotation=45)
        ax.set(title=f"SKO of {_LABELS[k]}", xlabel="variant")
        ax.grid(axis="y", which="both", alpha=0.3)
    axes[0].set_ylabel("SKO, px")
    axes[0].legend(fontsize=7, loc="lower left")
    fig.suptitle(title)
    return _done(fig)


def offset_sweep(l_m, sweeps: dict, m_xi, sigmas=(0.5, 0.1), pixels_per_m=3100.0 / 2.0,
                 title="Tripod offset: systematic error Δ(l) and the corridor ±m_ξ (cf. Fig. 42)"):
    """Fig. 42 analogue: noise-free Δ of f, x₀, y₀ against the offset l (log axis) with ±m_ξ corridors.

    ``l_m``: offsets (m); ``sweeps``: ``{"l_X": (k, 3) errors, "l_Z": (k, 3) errors}`` (px, noise
    free); ``m_xi``: the random part per pixel of image noise (f, x₀, y₀); one panel per series of
    Table 3 (axis × σ in ``sigmas``). The top axis shows l in pixels.
    """
    l_m = np.asarray(l_m, dtype=float)
    series = [(axis, s) for s in sigmas for axis in sweeps]
    fig, axes = plt.subplots(1, len(series), figsize=(3.6 * len(series), 3.8), constrained_layout=True)
    for n, (ax, (axis, s)) in enumerate(zip(np.atleast_1d(axes), series), 1):
        d = np.asarray(sweeps[axis])
        for k in range(3):
            c = f"C{k}"
            ax.plot(l_m, d[:, k], "-o", ms=3, color=c, label=f"Δ of {_LABELS[k]}")
            ax.fill_between(l_m, d[:, k] - m_xi[k] * s, d[:, k] + m_xi[k] * s, color=c, alpha=0.2)
        ax.set_xscale("log")
        ax.set_yscale("symlog", linthresh=1.0)
        ax.set(title=f"series {n}: {axis}, m = {s:g} px", xlabel="l, m")
        ax.grid(alpha=0.3, which="both")
        top = ax.secondary_xaxis("top", functions=(lambda v: v * pixels_per_m, lambda v: v / pixels_per_m))
        top.set_xlabel("l, px", fontsize=8)
    np.atleast_1d(axes)[0].set_ylabel("Δ ± m_ξ, px (symlog)")
    np.atleast_1d(axes)[0].legend(fontsize=7, loc="lower left")
    fig.suptitle(title)
    return _done(fig)


def offset_error_bars(results: dict, title="Tables 5/6 re-simulated: errors of f, x₀, y₀ (mean ± SD)"):
    """Figs. 45/46 analogue: mean ± SD of the errors per calibration variant.

    ``results`` maps a label to ``{"errors": (sets, 3)}`` (e.g.
    :func:`photolib.book.sementsov_simulation.offset_modelling`). Left panel: all variants on a
    symlog axis (the unmodelled offset biases by tens of pixels); right: the variants without that
    bias, linear.
    """
    labels = list(results)
    colour = {lab: f"C{i}" for i, lab in enumerate(labels)}
    fig, axes = plt.subplots(1, 2, figsize=(12, 4), constrained_layout=True)
    for ax, keep, scale in ((axes[0], labels, "symlog"),
                            (axes[1], [lab for lab in labels if np.abs(results[lab]["errors"].mean(0)).max() < 5],
                             "linear")):
        reach = 0.0
        for j, lab in enumerate(keep):
            E = results[lab]["errors"]
            ax.errorbar(np.arange(3) + 0.12 * (j - (len(keep) - 1) / 2), E.mean(0), yerr=E.std(0, ddof=1), fmt="o",
                        capsize=4, label=lab, color=colour[lab])
            reach = max(reach, float(np.max(np.abs(E.mean(0)) + E.std(0, ddof=1))))
        ax.axhline(0, color="k", lw=0.5)
        ax.set_xticks(range(3), _LABELS)
        if scale == "symlog":
            ax.set_yscale("symlog", linthresh=1.0)
            ax.set_ylim(-3 * reach, 3 * reach)
        ax.set(ylabel="error, px", title="all variants" if scale == "symlog" else "without the unmodelled offset")
        ax.grid(axis="y", alpha=0.3)
        ax.legend(fontsize=7)
    fig.suptitle(title)
    return _done(fig)


def tripod_sphere(l=(0.005, 0.065, -0.04), S0=(0.0, 0.0, 0.0), angles_deg=mockup.TABLE2_ANGLES,
                  title="Centres of the Table 2 images on the sphere of radius |l| about S₀ (cf. Fig. 36)"):
    """Fig. 36 analogue: S_i = S₀ + A_i·l (eq. (20)) for the five images, the sphere and the optical axes."""
    l, S0 = np.asarray(l, dtype=float), np.asarray(S0, dtype=float)
    ang = np.radians(np.asarray(angles_deg, dtype=float))
    S = mockup.tripod_centres(S0, ang, l)
    r = np.linalg.norm(l)
    fig = plt.figure(figsize=(6, 5.5), constrained_layout=True)
    ax = fig.add_subplot(projection="3d")
    u, v = np.meshgrid(np.linspace(0, 2 * np.pi, 37), np.linspace(0, np.pi, 19))
    ax.plot_wireframe(S0[0] + r * np.cos(u) * np.sin(v), S0[1] + r * np.sin(u) * np.sin(v), S0[2] + r * np.cos(v),
                      color="0.8", lw=0.5)
    ax.scatter(*S0, color="k", s=30)
    ax.text(*S0, "  S₀", fontsize=9)
    axes_dir = -np.stack([rotation_aok(*a)[:, 2] for a in ang])      # optical axis = −z of the camera
    for i, (Si, d) in enumerate(zip(S, axes_dir), 1):
        ax.scatter(*Si, color=f"C{i - 1}", s=40)
        ax.plot(*np.c_[S0, Si], color=f"C{i - 1}", lw=1)
        ax.quiver(*Si, *(d * r * 0.8), color=f"C{i - 1}", lw=1.5, arrow_length_ratio=0.25)
        ax.text(*Si, f"  S{i}", fontsize=9)
    ax.set(xlabel="X, m", ylabel="Y, m", zlabel="Z, m", title=title)
    ax.set_box_aspect((1, 1, 1))
    lim = r * 1.3
    ax.set(xlim=(S0[0] - lim, S0[0] + lim), ylim=(S0[1] - lim, S0[1] + lim), zlim=(S0[2] - lim, S0[2] + lim))
    return _done(fig)
