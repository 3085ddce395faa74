"""Interest operators of Chapter 5, §5.8 (photolib.features) against scikit-image and OpenCV.

On the left image of the Middlebury 2014 "Motorcycle" pair bundled with scikit-image (500×741,
grey, float64), in ONE run: each photolib operator is configured to the peer's convention, the
responses are compared (largest relative difference after the known scale factor), the strongest
points after the same non-maximum suppression are compared (share of identical points, share
within 1 px), and the times are the median of 7 repeats (time ratio = photolib / peer).

Conventions (see tests/library/test_features.py): skimage corner_harris / corner_foerstner use
unnormalised Sobel and a Gaussian σ = 1 (9×9) with zero padding → photolib window=9, sigma=1,
gradient="sobel", weight="gaussian", border="constant" (R × 8⁴, w × 8²); skimage corner_moravec
takes only diagonal shifts → photolib variant="diagonal"; cv2.cornerHarris(blockSize=5, ksize=3)
sums the window unweighted with BORDER_REFLECT_101 → weight="box", border="mirror" (a constant
factor); cv2.FAST uses strict inequalities → photolib threshold t + 1 on the uint8 image.

Run:  python benchmarks/interest_operators.py   (prints a markdown table)
"""

from __future__ import annotations

import time

import numpy as np

from photolib import features as ft
from photolib.datasets import motorcycle


def median_time(fn, repeats=7):
    out = fn()
    times = []
    for _ in range(repeats):
        t = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t)
    return float(np.median(times)), out


def point_agreement(a, b):
    """Share of a's points that b has exactly / within 1 px (a, b: (n, 2))."""
    if len(a) == 0 or len(b) == 0:
        return 0.0, 0.0
    from scipy.spatial import cKDTree
    d, _ = cKDTree(b).query(a)
    return float(np.mean(d == 0)), float(np.mean(d <= 1.0))


def rel_diff(ours, theirs, scale):
    ref = np.abs(theirs).max()
    return float(np.abs(ours * scale - theirs).max() / ref)


def main():
    import cv2
    from skimage import feature as skf

    img = motorcycle().left
    u8 = np.clip(np.round(img), 0, 255).astype(np.uint8)
    f32 = img.astype(np.float32)
    nms = dict(size=9, relative=0.01, border=6, max_points=500)
    rows = []

    def add(name, peer, t_ours, t_peer, R_ours, R_peer, scale, pts_ours=None, pts_peer=None):
        if pts_ours is None:
            pts_ours = ft.nonmax_suppression(R_ours * scale, **nms)
            pts_peer = ft.nonmax_suppression(np.asarray(R_peer, float), **nms)
        same, near = point_agreement(pts_ours, pts_peer)
        rd = "—" if R_peer is None else f"{rel_diff(R_ours, np.asarray(R_peer, float), scale):.1e}"
        rows.append([name, peer, f"{t_ours * 1e3:.1f}", f"{t_peer * 1e3:.1f}", f"{t_ours / t_peer:.2f}", rd,
                     f"{len(pts_ours)}/{len(pts_peer)}", f"{100 * same:.1f}", f"{100 * near:.1f}"])

    t1, R1 = median_time(lambda: ft.harris(img, window=9, sigma=1.0, k=0.05, weight="gaussian",
                                           gradient="sobel", border="constant"))
    t2, R2 = median_time(lambda: skf.corner_harris(img, k=0.05, sigma=1))
    add("harris", "skimage corner_harris", t1, t2, R1, R2, 8.0 ** 4)

    t1, R1 = median_time(lambda: ft.harris(f32.astype(float), window=5, k=0.04, weight="box",
                                           gradient="sobel", border="mirror"))
    t2, R2 = median_time(lambda: cv2.cornerHarris(f32, 5, 3, 0.04))
    big = np.abs(R2) > 1e-3 * np.abs(R2).max()
    add("harris", "cv2.cornerHarris", t1, t2, R1, R2, float(np.median(R2[big] / R1[big])))

    t1, (w1, q1) = median_time(lambda: ft.foerstner(img, window=9, sigma=1.0, weight="gaussian",
                                                    gradient="sobel", border="constant"))
    t2, (w2, q2) = median_time(lambda: skf.corner_foerstner(img, sigma=1))
    add("foerstner w (q ≥ 0.5)", "skimage corner_foerstner", t1, t2, np.where(q1 >= 0.5, w1, 0),
        np.where(q2 >= 0.5, w2, 0), 64.0)

    t1, M1 = median_time(lambda: ft.moravec(img, 5, variant="diagonal"))
    t2, M2 = median_time(lambda: skf.corner_moravec(img, window_size=2))
    add("moravec (diagonal shifts)", "skimage corner_moravec", t1, t2, M1, M2, 1.0)

    tb, Mb = median_time(lambda: ft.moravec(img, 5))
    pb = ft.nonmax_suppression(Mb, **nms)
    pm = ft.nonmax_suppression(M2, **nms)
    same, near = point_agreement(pb, pm)
    rows.append(["moravec (book 5.8.1)", "skimage corner_moravec", f"{tb * 1e3:.1f}", f"{t2 * 1e3:.1f}",
                 f"{tb / t2:.2f}", "(other measure)", f"{len(pb)}/{len(pm)}", f"{100 * same:.1f}", f"{100 * near:.1f}"])

    for t in (10, 20):
        det = cv2.FastFeatureDetector_create(t, False, cv2.FAST_FEATURE_DETECTOR_TYPE_9_16)
        t1, S = median_time(lambda: ft.fast(u8.astype(float), t + 1))
        t2, kp = median_time(lambda: det.detect(u8))
        ours = np.argwhere(S > 0)[:, ::-1].astype(float)
        theirs = np.array([k.pt for k in kp], float).reshape(-1, 2)
        add(f"FAST-9, t = {t}, no NMS", "cv2.FAST", t1, t2, S, None, 1.0, ours, theirs)

    header = ["photolib", "peer", "photolib ms", "peer ms", "time ratio", "max rel. response diff",
              "points (ours/peer)", "identical %", "within 1 px %"]
    print("| " + " | ".join(header) + " |")
    print("|" + "---|" * len(header))
    for r in rows:
        print("| " + " | ".join(r) + " |")
    print(f"\nimage: Motorcycle left {img.shape[1]}×{img.shape[0]}, float64; NMS 9×9, ≥ 1 % of max, "
          f"border 6 px, ≤ 500 points; median of 7 runs.")


if __name__ == "__main__":
    main()
