"""Figures for the appendix on the MRF terrain paper (Baikalova, Dubina, Evtyushkin, Yushakov,
"Algorithm for terrain relief reconstruction from a stereo pair"; appendix to Chapter 6, §6.4).

* :func:`synthetic_scans` — two overlapping "scans" of one textured terrain with a known base
  shift (x₀, y₀) and a known per-pixel x-parallax field, with the paper's two hard cases: a
  periodic band (several correlation maxima) and a textureless patch (weak correlation).
* :func:`overlap_search` — the correlation of the overlapping parts against the shift, and the
  maximum found by :func:`photolib.mrf.find_overlap_shift`.
* :func:`wta_vs_mrf` — the per-pixel parallax by windowed correlation (winner-takes-all) against
  the MRF relaxation and the truth, with error maps and scores per region.
* :func:`sampler_energy` — the energy U of the Gibbs sampler over the sweeps and the sampled
  marginal maximum (confidence) per pixel.
* :func:`geometry_steps` — steps 1–7 (relative orientation → horizontal images → intersection →
  absolute orientation) on a synthetic tilted pair with known points: a diagram and a table of
  residuals.
* :func:`motorcycle_crop` — a crop of scikit-image's Motorcycle pair: WTA against MRF on the
  paper's correlation cost, with the ground truth and bad-2.0.

Every function returns the matplotlib Figure (closed, so that a notebook shows it once) with the
numbers it shows, rounded. Everything is seeded: the outputs are deterministic.
"""

from __future__ import annotations

from dataclasses import dataclass

import matplotlib.pyplot as plt
import numpy as np
from scipy.ndimage import gaussian_filter, map_coordinates

from ... import mrf
from ...synthetic import stereo_pair
from ..verify import Table

__all__ = ["SyntheticScans", "synthetic_scans", "overlap_search", "wta_vs_mrf", "sampler_energy",
           "geometry_steps", "motorcycle_crop"]


def _done(fig):
    plt.close(fig)
    return fig


@dataclass
class SyntheticScans:
    """Two scans of one terrain with ground truth (paper's convention x₂ = x₁ + x₀ + p, y₂ = y₁ + y₀).

    Attributes
    ----------
    left, right : (H, W) arrays
        The scans (texture plus noise).
    shift : (int, int)
        The true base shift (x₀, y₀).
    parallax : (H, W) array
        The true x-parallax p of every left pixel (px, fractional).
    periodic, flat : (H, W) bool arrays
        Left pixels in the periodic band and in the textureless patch.
    """

    left: np.ndarray
    right: np.ndarray
    shift: tuple
    parallax: np.ndarray
    periodic: np.ndarray
    flat: np.ndarray


def synthetic_scans(shape=(72, 120), shift=(24, -3), seed=3, noise=0.15) -> SyntheticScans:
    """A seeded pair: smooth relief parallax 5 ± 4.5 px, a periodic band (period 5 px) and a flat patch."""
    rng = np.random.default_rng(seed)
    H, W = shape
    x0, y0 = shift
    pad = 40
    T = gaussian_filter(rng.standard_normal((H + 2 * pad, W + 2 * pad + abs(x0) + 20)), 1.0)
    T /= T.std()
    yy, xx = np.mgrid[0:H, 0:W].astype(float)
    p_true = 5.0 + 3.0 * np.sin(xx / 17.0) + 1.5 * np.cos(yy / 11.0)
    # the hard cases are properties of the terrain: a band of periodic texture, a textureless patch
    # the hard cases are properties of the terrain: a band of periodic texture, a textureless patch
    # (placed in T so that they lie on the left scan's rows 20–33 and 50–61)
    ty, tx = np.mgrid[0:T.shape[0], 0:T.shape[1]].astype(float)
    band = (ty >= pad + y0 + 20) & (ty < pad + y0 + 34)
    T[band] = 1.2 * np.sin(2 * np.pi * tx[band] / 5.0)
    T[pad + y0 + 50:pad + y0 + 62, pad + x0 + 20:pad + x0 + 60] = 0.0
    # right scan: T at (y + pad, x + pad); left scan: left(x₁, y₁) = right(x₁ + x₀ + p, y₁ + y₀)
    right = T[pad:pad + H, pad:pad + W].copy()
    left = map_coordinates(T, [yy + pad + y0, xx + pad + x0 + p_true], order=3)
    left = left + noise * rng.standard_normal(left.shape)
    right = right + noise * rng.standard_normal(right.shape)
    periodic = (yy >= 20) & (yy < 34)
    flat = (yy >= 50) & (yy < 62) & (xx + p_true >= 20) & (xx + p_true < 60)
    return SyntheticScans(left, right, (x0, y0), p_true, periodic, flat)


def _overlap_r(L, R, dx, dy, min_area):
    H, W = L.shape
    x_lo, x_hi = max(0, -dx), min(W, R.shape[1] - dx)
    y_lo, y_hi = max(0, -dy), min(H, R.shape[0] - dy)
    if (x_hi - x_lo) * (y_hi - y_lo) < min_area or x_hi - x_lo < 2 or y_hi - y_lo < 2:
        return np.nan
    a = L[y_lo:y_hi, x_lo:x_hi].ravel()
    b = R[y_lo + dy:y_hi + dy, x_lo + dx:x_hi + dx].ravel()
    return float(np.corrcoef(a, b)[0, 1])


def overlap_search(scans: SyntheticScans, max_shift=(48, 8), min_overlap=0.3):
    """r of the overlap against (x₀, y₀) and the maximum by :func:`photolib.mrf.find_overlap_shift`.

    Returns (fig, found) with found = {"x0", "y0", "r", "true"}.
    """
    L, R = scans.left, scans.right
    x0, y0, rmax = mrf.find_overlap_shift(L, R, max_shift=max_shift, min_overlap=min_overlap)
    xs = np.arange(-max_shift[0], max_shift[0] + 1)
    ys = np.arange(-max_shift[1], max_shift[1] + 1)
    area = min_overlap * L.size
    grid = np.array([[_overlap_r(L, R, dx, dy, area) for dx in xs] for dy in ys])
    fig, axes = plt.subplots(1, 2, figsize=(10, 3.4), gridspec_kw={"width_ratios": [1.4, 1]})
    im = axes[0].imshow(grid, origin="lower", aspect="auto", cmap="viridis",
                        extent=(xs[0] - 0.5, xs[-1] + 0.5, ys[0] - 0.5, ys[-1] + 0.5))
    axes[0].plot(x0, y0, "r+", ms=12, mew=2, label=f"maximum ({x0}, {y0})")
    axes[0].set_xlabel("x₀ (px)")
    axes[0].set_ylabel("y₀ (px)")
    axes[0].set_title("r of the overlapping parts")
    axes[0].legend(loc="lower left", fontsize=8)
    fig.colorbar(im, ax=axes[0])
    row = grid[list(ys).index(y0)]
    axes[1].plot(xs, row, "k-")
    axes[1].axvline(x0, color="r", ls="--", lw=1)
    axes[1].set_xlabel("x₀ (px)")
    axes[1].set_ylabel("r")
    axes[1].set_title(f"section at y₀ = {y0}")
    fig.tight_layout()
    found = {"x0": x0, "y0": y0, "r": round(rmax, 3), "true": tuple(scans.shift)}
    return _done(fig), found


def _scores(est, truth, mask):
    err = np.abs(est - truth)[mask]
    return {"rmse": round(float(np.sqrt(np.nanmean(err ** 2))), 2),
            "bad1": round(float(100.0 * np.mean(~(err <= 1.0))), 1)}


def wta_vs_mrf(scans: SyntheticScans, parallaxes, shift, *, window=5, a=10.0, b=-0.5, sweeps=30, burn_in=10,
               seed=0):
    """Truth, winner-takes-all, MRF and their errors on the synthetic scans.

    The candidate parallaxes are relative to the found ``shift``; the truth is converted to them.
    Returns (fig, table, result, r) — scores (RMSE px, % off by > 1 px) over the whole interior,
    the periodic band and the flat patch; the :class:`photolib.mrf.MRFResult`; the volume.
    """
    P = np.asarray(parallaxes)
    r = mrf.correlation_volume(scans.left, scans.right, P, window=window, shift=shift)
    wta, rmax = mrf.winner_takes_all(r, P)
    res = mrf.gibbs_relaxation(r, P, a=a, b=b, sweeps=sweeps, burn_in=burn_in, seed=seed)
    truth = scans.parallax + scans.shift[0] - shift[0]
    inside = np.all(np.isfinite(r), axis=0)               # windows inside both scans for every p
    regions = [("all defined pixels", inside), ("periodic band", inside & scans.periodic),
               ("textureless patch", inside & scans.flat)]
    rows = []
    for name, m in regions:
        w, g = _scores(wta, truth, m), _scores(res.parallax, truth, m)
        rows.append([name, int(m.sum()), w["rmse"], g["rmse"], f"{w['bad1']} %", f"{g['bad1']} %"])
    table = Table(["region", "pixels", "RMSE WTA (px)", "RMSE MRF (px)", "> 1 px WTA", "> 1 px MRF"], rows,
                  f"Synthetic scans: WTA vs MRF (a = {a}, b = {b}, {sweeps} sweeps, burn-in {burn_in})")
    lo, hi = float(P.min()), float(P.max())
    fig, axes = plt.subplots(2, 3, figsize=(10, 4.6))
    for ax, img, title in ((axes[0, 0], np.where(inside, truth, np.nan), "truth p"),
                           (axes[0, 1], np.where(inside, wta, np.nan), "winner-takes-all (max r)"),
                           (axes[0, 2], np.where(inside, res.parallax, np.nan), "MRF (marginal maxima)")):
        im = ax.imshow(img, cmap="viridis", vmin=lo, vmax=hi)
        ax.set_title(title, fontsize=10)
    fig.colorbar(im, ax=axes[0, :].tolist(), shrink=0.8, label="p (px)")
    axes[1, 0].imshow(scans.left, cmap="gray")
    axes[1, 0].contour(scans.periodic, [0.5], colors="c", linewidths=1)
    axes[1, 0].contour(scans.flat, [0.5], colors="m", linewidths=1)
    axes[1, 0].set_title("left scan (cyan: periodic, magenta: flat)", fontsize=9)
    for ax, est, title in ((axes[1, 1], wta, "|error| WTA"), (axes[1, 2], res.parallax, "|error| MRF")):
        im = ax.imshow(np.where(inside, np.abs(est - truth), np.nan), cmap="magma", vmin=0, vmax=5)
        ax.set_title(title, fontsize=10)
    fig.colorbar(im, ax=axes[1, :].tolist(), shrink=0.8, label="px")
    for ax in axes.ravel():
        ax.set_xticks([])
        ax.set_yticks([])
    return _done(fig), table, res, r


def sampler_energy(result, *, weak=None):
    """U(p) after every sweep, and the per-pixel marginal maximum; returns (fig, summary)."""
    E = np.asarray(result.energy)
    fig, axes = plt.subplots(1, 2, figsize=(10, 3.3), gridspec_kw={"width_ratios": [1.3, 1]})
    axes[0].plot(np.arange(len(E)), E, "k.-")
    axes[0].set_xlabel("sweep (0 = winner-takes-all start)")
    axes[0].set_ylabel("U = −aΣr − bΣ(p − p′)²")
    axes[0].set_title("energy of the sampled map")
    im = axes[1].imshow(result.confidence, cmap="cividis", vmin=0, vmax=1)
    if weak is not None:
        axes[1].contour(weak, [0.5], colors="r", linewidths=0.8)
    axes[1].set_title("marginal probability of the estimate", fontsize=10)
    axes[1].set_xticks([])
    axes[1].set_yticks([])
    fig.colorbar(im, ax=axes[1], shrink=0.85)
    fig.tight_layout()
    summary = {"U_start": round(float(E[0]), 1), "U_end": round(float(E[-1]), 1),
               "U_min": round(float(E.min()), 1),
               "median_confidence": round(float(np.median(result.confidence)), 2)}
    return _done(fig), summary


def _rms(v):
    return float(np.sqrt(np.mean(np.square(v))))


def _steps(seed, n_points, sigma):
    pair = stereo_pair(n_points, seed=seed, angle_spread_deg=3.0, relief=60.0, sigma=sigma)
    S1, S2 = pair.centres
    io = pair.io
    po = mrf.orient_pair(pair.xy1, pair.xy2, io, base_length=float(np.linalg.norm(S2 - S1)))   # steps 1–4
    q = np.asarray(po.relative.q)
    c = np.array([io.x0, io.y0])
    h1 = mrf.reduce_to_horizontal(pair.xy1 - c, io.f, po.A1)                                  # step 5
    h2 = mrf.reduce_to_horizontal(pair.xy2 - c, io.f, po.A2)
    model = mrf.intersect_horizontal(h1, h2, po.base, io.f, po.S1)                            # step 6
    truth_model = (pair.points - S1) @ pair.eo1.matrix                # the true points in the left camera's axes
    d2 = truth_model - (S2 - S1) @ pair.eo1.matrix                    # ... seen from the true S₂
    h2_true = -io.f * d2[:, :2] / d2[:, 2:3]
    # step 7: control points 0 and 1 with X, Y, Z, point 2 with Z only; the other points are checks
    mask = np.zeros((n_points, 3), bool)
    mask[0] = mask[1] = True
    mask[2, 2] = True
    mo = mrf.orient_model(model, np.where(mask, pair.points, np.nan), mask)
    check = np.abs(mo.apply(model[3:]) - pair.points[3:])
    true_base = (S2 - S1) @ pair.eo1.matrix
    tau_true = np.arctan2(true_base[1], true_base[0])
    return {"q": 1000 * _rms(q),
            "tau": float(np.degrees(abs(po.tau - tau_true))),
            "h2": 1000 * _rms(h2 - h2_true),
            "model": _rms(model - truth_model),
            "check_plan": float(check[:, :2].max()),
            "check_height": float(check[:, 2].max()),
            "t": float(mo.t)}


def geometry_steps(seed=2, n_points=30, sigmas=(0.0, 0.002)):
    """Steps 1–7 on a seeded tilted pair (f = 100 mm, B = 400 m, H = 1000 m, relief ± 60 m, angles ± 3°).

    The same pair with exact image coordinates and with Gaussian noise of each ``sigmas`` (mm).
    Returns (fig, table, numbers): the diagram, the residual table and its values (rounded).
    """
    runs = [_steps(seed, n_points, s) for s in sigmas]
    names = [("q", "step 1: RMS residual y-parallax q (µm)", 2),
             ("tau", "steps 2–4: |τ − true τ| (°)", 4),
             ("h2", "step 5: RMS error of the right horizontal image (µm)", 2),
             ("model", "step 6: RMS free model − truth (m)", 3),
             ("check_plan", "step 7: max plan error at the check points (m)", 3),
             ("check_height", "step 7: max height error at the check points (m)", 3),
             ("t", "step 7: scale t of the free model", 5)]
    numbers = {key: [round(run[key], d) + 0.0 for run in runs] for key, _, d in names}
    header = ["step"] + [("exact coordinates" if s == 0 else f"noise {1000 * s:g} µm") for s in sigmas]
    table = Table(header, [[label] + [f"{v:.{d}f}" for v in numbers[key]] for key, label, d in names],
                  f"Steps 1–7 on a tilted synthetic pair ({n_points} points; control 2 XYZ + 1 Z)")
    last = runs[-1]
    fig, ax = plt.subplots(figsize=(11, 2.2))
    ax.set_axis_off()
    ax.set_xlim(0, 10)
    ax.set_ylim(0.2, 1.9)
    boxes = [("1–4 relative orientation\nα′₁ χ′₁ α′₂ ω′₂ χ′₂ → τ, v, S₂", f"RMS q = {last['q']:.2f} µm"),
             ("5 horizontal images (2)\nx₀ = −fX′/Z′, y₀ = −fY′/Z′", f"RMS error {last['h2']:.1f} µm"),
             ("6 intersection\nN = (B_x + x₂₀B_z/f)/(x₁₀ − x₂₀)", f"RMS model error {last['model']:.2f} m"),
             ("7 absolute orientation (3)\n2 XYZ + 1 Z control",
              f"check: plan {last['check_plan']:.2f} m, height {last['check_height']:.2f} m")]
    for i, (text, res) in enumerate(boxes):
        x = 0.15 + 2.5 * i
        ax.add_patch(plt.Rectangle((x, 0.75), 2.1, 1.05, fc="#eef3fa", ec="k"))
        ax.text(x + 1.05, 1.28, text, ha="center", va="center", fontsize=8)
        ax.text(x + 1.05, 0.45, res, ha="center", va="center", fontsize=8.5, color="darkred")
        if i < len(boxes) - 1:
            ax.annotate("", xy=(x + 2.45, 1.28), xytext=(x + 2.1, 1.28), arrowprops={"arrowstyle": "->"})
    ax.set_title(f"The paper's geometric steps (residuals with {1000 * sigmas[-1]:g} µm image noise)", fontsize=10)
    return _done(fig), table, numbers


def motorcycle_crop(pair, *, factor=2, rows=(40, 160), cols=(150, 330), window=7, a=20.0, b=-0.1, sweeps=20,
                    burn_in=6, seed=0):
    """WTA vs MRF on a crop of a Middlebury pair (block means by ``factor``), truth and bad-2.0.

    The candidate parallaxes are p = −d, d = 0 … max_disparity/factor (the paper's x₂ = x₁ + p).
    Returns (fig, scores) with bad-2.0 (%) over the crop's scored pixels (invalid counted as bad).
    """
    k = int(factor)
    H, W = (np.array(pair.left.shape) // k) * k

    def blocks(img, how):
        return how(img[:H, :W].reshape(H // k, k, W // k, k), axis=(1, 3))

    sl = np.s_[rows[0]:rows[1], cols[0]:cols[1]]
    dmax = int(np.ceil(pair.max_disparity / k))
    left = blocks(pair.left, np.mean)[sl]
    full_right = blocks(pair.right, np.mean)
    right = full_right[rows[0]:rows[1], max(cols[0] - dmax, 0):cols[1]]
    x_off = cols[0] - max(cols[0] - dmax, 0)
    disp = (blocks(pair.disparity, np.mean) / k)[sl]
    evaluate = (blocks(pair.evaluate, np.all))[sl] & np.isfinite(disp)
    P = -np.arange(0, dmax + 1)
    r = mrf.correlation_volume(left, right, P, window=window, shift=(x_off, 0))
    wta, _ = mrf.winner_takes_all(r, P)
    res = mrf.gibbs_relaxation(r, P, a=a, b=b, sweeps=sweeps, burn_in=burn_in, seed=seed)
    defined = np.any(np.isfinite(r), axis=0)
    d_wta = np.where(defined, -wta, np.nan)
    d_mrf = np.where(defined, -res.parallax, np.nan)

    def bad(d):
        return round(float(100.0 * np.mean(~(np.abs(d - disp) <= 2.0)[evaluate])), 1)

    ok_wta = np.abs(d_wta - disp) <= 2.0
    ok_mrf = np.abs(d_mrf - disp) <= 2.0
    fixed, broken = evaluate & ok_mrf & ~ok_wta, evaluate & ok_wta & ~ok_mrf
    scores = {"crop": f"{left.shape[1]}×{left.shape[0]} px at 1/{k}", "d range": f"0–{dmax}",
              "WTA": bad(d_wta), "MRF": bad(d_mrf),
              "fixed by MRF": round(float(100.0 * fixed.sum() / evaluate.sum()), 1),
              "broken by MRF": round(float(100.0 * broken.sum() / evaluate.sum()), 1)}
    fig, axes = plt.subplots(1, 5, figsize=(14, 2.7))
    axes[0].imshow(left, cmap="gray")
    axes[0].set_title("left (crop)", fontsize=10)
    for ax, img, title in ((axes[1], np.where(evaluate, disp, np.nan), "ground truth d"),
                           (axes[2], d_wta, f"WTA, bad-2.0 {scores['WTA']} %"),
                           (axes[3], d_mrf, f"MRF, bad-2.0 {scores['MRF']} %")):
        im = ax.imshow(img, cmap="viridis", vmin=0, vmax=dmax)
        ax.set_title(title, fontsize=10)
    fig.colorbar(im, ax=axes[3], shrink=0.85, label="d = −p (px)")
    change = np.full(left.shape + (3,), 0.85)
    change[fixed] = (0.1, 0.6, 0.1)
    change[broken] = (0.85, 0.1, 0.1)
    axes[4].imshow(change)
    axes[4].set_title(f"fixed {scores['fixed by MRF']} % / broken {scores['broken by MRF']} %", fontsize=9)
    for ax in axes:
        ax.set_xticks([])
        ax.set_yticks([])
    return _done(fig), scores
