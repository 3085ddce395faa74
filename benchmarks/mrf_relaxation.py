"""The MRF relaxation of Baikalova et al. against winner-takes-all and SGM on the SAME cost.

One cost for all three: the paper's windowed correlation r (photolib.mrf.correlation_volume,
7×7) — the MRF samples exp(a·r + b·V_s), winner-takes-all takes argmax r, and SGM aggregates the
cost 1 − r (undefined r: cost 2, the largest) with photolib.sgm.aggregate_costs (8 paths) and
takes photolib.sgm.winner_takes_all (integer, no sub-pixel, no left–right check, no median, so
that only the regulariser differs). Scored on Middlebury Cones (../shared/data, skipped if absent)
and scikit-image's Motorcycle: bad-2.0 on the pairs' evaluation masks (non-occluded where the set
provides it), invalid pixels counted as bad, and the time of each regulariser (median of
``--repeats`` runs; the cost volume's time is shown once, it is shared).

Run:  python benchmarks/mrf_relaxation.py [--repeats 3] [--sweeps 30]
"""

from __future__ import annotations

import argparse
import time

import numpy as np

from photolib import datasets, mrf, sgm


def bad(d, pair, tol=2.0):
    m = pair.evaluate
    err = np.abs(d[m] - pair.disparity[m])
    return float(np.mean(~(err <= tol)))          # NaN (invalid) counts as bad


def timed(fn, repeats):
    times, out = [], None
    for _ in range(repeats):
        t = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t)
    return out, float(np.median(times))


def run(pair, repeats, sweeps, window, settings, P1, P2):
    dmax = pair.max_disparity
    P = -np.arange(0, dmax + 1)                     # the paper's p = −d (x₂ = x₁ + p)
    r, t_cost = timed(lambda: mrf.correlation_volume(pair.left, pair.right, P, window=window), 1)
    rows = []
    (p_wta, _), t = timed(lambda: mrf.winner_takes_all(r, P), repeats)
    rows.append(("winner-takes-all (argmax r)", bad(-p_wta, pair), t))
    cost = np.ascontiguousarray(np.where(np.isfinite(r), 1.0 - r, 2.0).transpose(1, 2, 0), dtype=np.float32)
    d_sgm, t = timed(lambda: sgm.winner_takes_all(sgm.aggregate_costs(cost, P1, P2, paths=8), subpixel=False),
                     repeats)
    rows.append((f"SGM, 8 paths, P1 = {P1}, P2 = {P2} (cost 1 − r)", bad(d_sgm, pair), t))
    for a, b in settings:
        res, t = timed(lambda: mrf.gibbs_relaxation(r, P, a=a, b=b, sweeps=sweeps, burn_in=sweeps // 3, seed=0),
                       repeats)
        rows.append((f"MRF Gibbs MPM, a = {a}, b = {b}, {sweeps} sweeps", bad(-res.parallax, pair), t))
    return t_cost, rows


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--sweeps", type=int, default=30)
    ap.add_argument("--window", type=int, default=7)
    args = ap.parse_args(argv)
    settings = [(10.0, -0.5), (20.0, -0.1)]
    pairs = []
    try:
        pairs.append(datasets.middlebury_cones())
    except datasets.DataUnavailableError as exc:
        print(f"Cones skipped: real data absent ({exc})")
    pairs.append(datasets.motorcycle())
    for pair in pairs:
        t_cost, rows = run(pair, args.repeats, args.sweeps, args.window, settings, 0.2, 1.6)
        print(f"\n### {pair.name} ({pair.left.shape[1]}×{pair.left.shape[0]}, disparities 0–{pair.max_disparity}); "
              f"cost volume ({args.window}×{args.window} correlation): {t_cost:.2f} s\n")
        print("| regulariser on the same cost | bad-2.0 (invalid = bad) | time (s) | time / WTA |")
        print("|---|---|---|---|")
        t0 = rows[0][2]
        for name, b, t in rows:
            print(f"| {name} | {100 * b:.1f} % | {t:.3f} | {t / t0:.1f}× |")


if __name__ == "__main__":
    main()
