"""Semi-global matching (Chapter 6, §6.4) on Middlebury pairs: photolib vs OpenCV vs CNES Pandora.

One run, the same grey images and the same disparity range for every matcher:

* photolib.sgm.semi_global_matching — census 7×9, 8 paths, P2 adapted to the grey steps,
  parabola sub-pixel, 3×3 median, left–right check, invalid pixels filled from the background
  side of their row (numba, one thread);
* OpenCV ``cv2.StereoSGBM`` (MODE_SGBM, block 5, P1 = 8·5², P2 = 32·5², LR check 1 px,
  uniqueness 10, speckle filter) — the matcher most users would pick;
* CNES Pandora (census 5×5 + libSGM P1 = 8, P2 = 32, V-fit sub-pixel, 3×3 median,
  accurate cross-check), the configuration of Pandora's documentation;
* winner-takes-all on photolib's census cost (no aggregation), to show what (6.4.3)–(6.4.4) add.

Score: bad-2.0 = share of the scored pixels (Cones: non-occluded with known disparity;
Motorcycle: known disparity) whose disparity is invalid or off by more than 2 px. Times are
the median of ``--repeats`` runs, wall clock, inputs already in memory (Pandora reads its
GeoTIFFs from a temporary folder, as its API requires). Cones is skipped when the real data
(../shared/data or $PHOTOLIB_DATA) is absent; Motorcycle comes with scikit-image.

Run:  python benchmarks/sgm_middlebury.py [--repeats 3] [--no-pandora]
"""

from __future__ import annotations

import argparse
import logging
import os
import platform
import statistics
import tempfile
import time
import warnings

import numpy as np

from photolib import datasets, sgm

PHOTOLIB = dict(cost="census", window=(7, 9), P1=8.0, P2=100.0, p2_gamma=20.0, median=3,
                lr_tolerance=1.0, fill=True, subpixel=True)


def bad(disparity, pair, threshold=2.0):
    """bad-2.0 in percent, invalid (NaN) pixels counted as bad."""
    err = np.abs(disparity - pair.disparity)
    wrong = ~(err <= threshold)
    return 100.0 * float(wrong[pair.evaluate].mean())


def timed(fn, repeats):
    times, out = [], None
    for _ in range(repeats):
        t = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t)
    return out, statistics.median(times)


def run_photolib(pair, dmax):
    return sgm.semi_global_matching(pair.left, pair.right, dmax, **PHOTOLIB).disparity


def run_wta(pair, dmax):
    C = sgm.cost_volume(pair.left, pair.right, dmax, method="census", window=(7, 9))
    return sgm.winner_takes_all(C)


def run_opencv(pair, dmax):
    import cv2
    num = int(np.ceil((dmax + 1) / 16) * 16)
    block = 5
    matcher = cv2.StereoSGBM_create(minDisparity=0, numDisparities=num, blockSize=block,
                                    P1=8 * block * block, P2=32 * block * block, disp12MaxDiff=1,
                                    uniquenessRatio=10, speckleWindowSize=100, speckleRange=2,
                                    mode=cv2.STEREO_SGBM_MODE_SGBM)
    left = np.clip(np.rint(pair.left), 0, 255).astype(np.uint8)
    right = np.clip(np.rint(pair.right), 0, 255).astype(np.uint8)
    d = matcher.compute(left, right).astype(np.float64) / 16.0
    d[d < 0] = np.nan
    return d


class PandoraRunner:
    """Pandora's Python API on the pair's grey images written as float32 GeoTIFFs."""

    def __init__(self, pair, dmax, folder):
        import rasterio
        self.paths = []
        for name, image in (("left", pair.left), ("right", pair.right)):
            path = os.path.join(folder, f"{name}.tif")
            with rasterio.open(path, "w", driver="GTiff", width=image.shape[1], height=image.shape[0],
                               count=1, dtype="float32") as f:
                f.write(image.astype(np.float32), 1)
            self.paths.append(path)
        # Pandora's disparity: right column = left column + d, so Middlebury's d is −d there
        self.cfg = {
            "input": {"left": {"img": self.paths[0], "disp": [-int(dmax), 0], "nodata": "NaN"},
                      "right": {"img": self.paths[1], "nodata": "NaN"}},
            "pipeline": {
                "matching_cost": {"matching_cost_method": "census", "window_size": 5, "subpix": 1},
                "optimization": {"optimization_method": "sgm",
                                 "penalty": {"penalty_method": "sgm_penalty", "P1": 8, "P2": 32,
                                             "p2_method": "constant"}},
                "disparity": {"disparity_method": "wta", "invalid_disparity": "NaN"},
                "refinement": {"refinement_method": "vfit"},
                "filter": {"filter_method": "median", "filter_size": 3},
                "validation": {"validation_method": "cross_checking_accurate",
                               "cross_checking_threshold": 1.0}}}

    def __call__(self):
        import pandora
        from pandora.check_configuration import check_conf
        from pandora.img_tools import create_dataset_from_inputs
        from pandora.state_machine import PandoraMachine
        machine = PandoraMachine()
        cfg = check_conf(self.cfg, machine)
        left = create_dataset_from_inputs(input_config=cfg["input"]["left"])
        right = create_dataset_from_inputs(input_config=cfg["input"]["right"])
        out, _ = pandora.run(machine, left, right, cfg)
        return -np.asarray(out["disparity_map"].values, dtype=np.float64)


def pandora_available():
    try:
        import pandora
        import pandora_plugin_libsgm  # noqa: F401 — the SGM step is this plugin
        pandora.import_plugin()
        return True
    except ImportError:
        return False


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--no-pandora", action="store_true")
    args = parser.parse_args(argv)
    warnings.filterwarnings("ignore")
    logging.getLogger("transitions").setLevel(logging.ERROR)
    logging.getLogger("transitions.core").setLevel(logging.ERROR)

    pairs = []
    try:
        pairs.append(("Cones", datasets.middlebury_cones()))
    except datasets.DataUnavailableError as missing:
        print(f"Cones skipped: real data absent ({missing})")
    pairs.append(("Motorcycle", datasets.motorcycle()))
    use_pandora = not args.no_pandora and pandora_available()
    if not use_pandora and not args.no_pandora:
        print("Pandora skipped: pandora or pandora_plugin_libsgm is not installed")

    # compile the numba kernels once, outside the timings
    warm = datasets.motorcycle()
    sgm.semi_global_matching(warm.left[:64, :160], warm.right[:64, :160], 40, **PHOTOLIB)

    import cv2
    print(f"machine: {platform.processor() or platform.machine()}, {os.cpu_count()} cores; "
          f"OpenCV threads {cv2.getNumThreads()}; median of {args.repeats} runs\n")
    print("| pair | matcher | bad-2.0 (%) | invalid (%) | time (s) | time / StereoSGBM | Pandora / time |")
    print("|---|---|---:|---:|---:|---:|---:|")
    for name, pair in pairs:
        dmax = pair.max_disparity
        rows = []
        d, t_cv = timed(lambda: run_opencv(pair, dmax), args.repeats)
        rows.append(("OpenCV StereoSGBM", d, t_cv))
        if use_pandora:
            with tempfile.TemporaryDirectory() as folder:
                runner = PandoraRunner(pair, dmax, folder)
                d, t_pa = timed(runner, args.repeats)
            rows.append(("CNES Pandora census+SGM", d, t_pa))
        else:
            t_pa = None
        d, t = timed(lambda: run_wta(pair, dmax), args.repeats)
        rows.append(("photolib WTA (census 7×9, no aggregation)", d, t))
        d, t = timed(lambda: run_photolib(pair, dmax), args.repeats)
        rows.append(("**photolib SGM**", d, t))
        for label, disp, seconds in rows:
            ratio = f"{seconds / t_cv:.1f}×"
            speed = f"{t_pa / seconds:.1f}×" if t_pa else "—"
            print(f"| {name} | {label} | {bad(disp, pair):.2f} | {100 * np.isnan(disp)[pair.evaluate].mean():.1f} "
                  f"| {seconds:.3f} | {ratio} | {speed} |")
    print("\nTarget (issue 9): photolib SGM bad-2.0 ≤ 6 % on Cones, time ≤ 20× StereoSGBM's, "
          "≥ 5× faster than Pandora.")


if __name__ == "__main__":
    main()
