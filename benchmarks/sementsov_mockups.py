"""Table 1 of Sementsov (2019) re-simulated at scale: the SKO of f, x0, y0 per variant, GNSS fixed or weighted.

For every variant of photolib.mockup.TABLE1_VARIANTS: ``--runs`` mock-ups (default 1200) with each GNSS
treatment (the variants without GNSS once), the Monte Carlo SKO against the first-order expectation
(photolib.mockup.variant_precision) and against the book's 30-run SKO of Appendix A, with the percentile
of the book's value in the sampling distribution of a 30-run SD ((n−1)s²/σ² ~ χ²(n−1)) and the mean μ.
Not a test: the notebook (Appendix E) shows the propagation and a 40-run check; this shows that the
propagation is what a long Monte Carlo converges to.

Run:  python benchmarks/sementsov_mockups.py [--runs 1200] [--seed 2019]
"""

from __future__ import annotations

import argparse
import time

import numpy as np
from scipy import stats

from photolib import mockup
from photolib.book import sementsov_simulation as sim


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=1200)
    ap.add_argument("--seed", type=int, default=2019)
    args = ap.parse_args(argv)
    print(f"{'variant':8} {'mode':9} {'MC SKO f, x0, y0':24} {'expected':24} {'book':24} {'book pct':16} "
          f"{'mean μ':>7} {'book μ':>7} {'s':>5}")
    for i, v in enumerate(mockup.TABLE1_VARIANTS):
        book = mockup.error_statistics(sim.appendix_a_errors(v)).sko
        n_book = len(sim.appendix_a_errors(v))
        for mode in (("fixed", "weighted") if mockup.TABLE1_VARIANTS[v].gnss else ("fixed",)):
            t = time.perf_counter()
            r = mockup.simulate_variant(v, args.runs, seed=args.seed + i, gnss_mode=mode)
            dt = time.perf_counter() - t
            sko = r.statistics.sko
            exp = mockup.variant_precision(v, gnss_mode=mode)[0]
            pct = 100 * stats.chi2.cdf((n_book - 1) * (book / exp) ** 2, n_book - 1)
            print(f"{v:8} {mode:9} {np.array2string(sko, precision=3):24} {np.array2string(exp, precision=3):24} "
                  f"{np.array2string(book, precision=3):24} {np.array2string(pct, precision=0):16} "
                  f"{r.mu.mean():7.4f} {sim.appendix_a_mu(v).mean():7.4f} {dt:5.1f}")


if __name__ == "__main__":
    main()
