"""Benchmark: point-cloud ground classification (§9.11) against the ASPRS ground class, photolib vs
the cloth-simulation filter (CSF) side by side; RANSAC roof planes against the building class.

Data (``../shared/data/lidar`` through :func:`photolib.datasets.data_path`; the script exits with
a message when the data, laspy or CSF is absent):

* ``4_6_crop.las`` (23 875 points, EPSG:2903, US survey feet) and ``autzen_trim.las``
  (110 000 points, Lambert conformal conic in international feet), classes 1 / 2 (ground).
  Read with :func:`photolib.pointcloud.read_las`; the unit comes from the CRS.
* ``sample_c.las`` (14 408 points, no CRS: metres, by its extent and heights; classes 2–6, 6 =
  building).

Ground (type I = ground rejected / ground, type II = objects accepted / objects, total =
misclassified / all; Sithole & Vosselman 2004):

* photolib: :func:`photolib.segmentation.classify_ground` on the file's coordinates (feet), the
  parameters fixed a priori in metres and converted with the CRS's factor (the same as
  ``benchmarks/dtm_filter.py``): cell 0.9144 m, window ≤ 20 m, slope 0.5, dh₀ 0.3048 m,
  dh_max 3.048 m, band 0.3048 m.
* CSF (``pip install cloth-simulation-filter``, ``bench`` extra): the cloud converted to metres
  (CSF's cloth dynamics are not scale-free: its time step and gravity assume metres), CSF's
  defaults except rigidness 2 ("relief") and slope smoothing on: cloth 0.5 m, class threshold
  0.5 m, 500 iterations, time step 0.65. Labelled rows run it with the same physical lengths on
  the cloud in metres and in raw feet: with a 1 m cloth the result depends on the unit.

Roofs: :func:`photolib.segmentation.detect_shapes` (RANSAC planes, threshold 0.15 m, normal within
20°, ≥ 50 points, ≤ 40 planes) on the whole cloud; the ground is the lowest plane of ≥ 200 points;
a roof is a plane sloping less than 60° whose median height is ≥ 2.5 m above it. Scored against
class 6: recall = building points on roofs / building points, precision = building points on
roofs / roof points. The morphological ground filter is not used there: the building covers
87 % of the tile and touches its edges, which no window-based filter handles.

Usage::

    python benchmarks/ground_filter_lidar.py              # median of 3 runs
    python benchmarks/ground_filter_lidar.py --repeat 1
"""

from __future__ import annotations

import argparse
import contextlib
import os
import time

import numpy as np

FT = 0.3048                       # the a-priori parameters are set in metres, converted per file


def scores(pred, truth):
    return (np.mean(~pred[truth]) * 100, np.mean(pred[~truth]) * 100, np.mean(pred != truth) * 100)


@contextlib.contextmanager
def _quiet():
    """CSF prints progress to the C stdout: silence it."""
    fd = os.dup(1)
    with open(os.devnull, "w") as null:
        os.dup2(null.fileno(), 1)
        try:
            yield
        finally:
            os.dup2(fd, 1)
            os.close(fd)


def run_csf(xyz, resolution, threshold, rigidness=2, smooth=True):
    import CSF
    csf = CSF.CSF()
    csf.params.bSloopSmooth = smooth
    csf.params.cloth_resolution = resolution
    csf.params.rigidness = rigidness
    csf.params.class_threshold = threshold
    csf.params.time_step = 0.65
    csf.params.interations = 500
    with _quiet():
        csf.setPointCloud(xyz - xyz.mean(axis=0))
        ground, other = CSF.VecInt(), CSF.VecInt()
        csf.do_filtering(ground, other, False)
    pred = np.zeros(len(xyz), bool)
    pred[np.asarray(list(ground), dtype=int)] = True
    return pred


def timed(fn, repeat):
    times, out = [], None
    for _ in range(max(1, repeat)):
        t = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t)
    return out, float(np.median(times))


def ground_level_share(xyz, truth, band):
    """Share of non-ground (class ≠ 2) points within ``band`` of the reference ground surface
    (mean Z of the 5 nearest class-2 points in plan): unclassified points at ground level."""
    from scipy.spatial import cKDTree
    _, idx = cKDTree(xyz[truth, :2]).query(xyz[~truth, :2], k=5)
    h = xyz[~truth, 2] - xyz[truth, 2][idx].mean(axis=1)
    return float(np.mean(np.abs(h) <= band) * 100)


def ground_benchmark(repeat):
    from photolib.datasets import data_path
    from photolib.pointcloud import read_las
    from photolib.segmentation import classify_ground
    print("| file | filter | parameters (file units) | type I % | type II % | total % | time (median) |")
    print("|---|---|---|---|---|---|---|")
    notes = []
    for name in ("4_6_crop.las", "autzen_trim.las"):
        cloud = read_las(data_path("lidar", name), to_metres=False)
        xyz, truth, u = cloud.xyz, cloud.classification == 2, cloud.unit_factor
        unit = "ftUS" if "US" in cloud.source_unit else "ft"
        p = dict(cell_size=0.9144 / u, max_window=20.0 / u, slope=0.5, dh0=0.3048 / u, dh_max=3.048 / u,
                 band=0.3048 / u)
        classify_ground(xyz[:2000], **p)                             # compile the numba kernel first
        res, t = timed(lambda: classify_ground(xyz, **p).ground, repeat)
        a, b, c = scores(res, truth)
        print(f"| {name} | photolib PMF + band | cell {p['cell_size']:.2f}, window ≤ {p['max_window']:.1f}, "
              f"slope 0.5, dh₀ {p['dh0']:.2f}, dh_max {p['dh_max']:.2f}, band {p['band']:.2f} {unit} "
              f"| {a:.1f} | {b:.1f} | {c:.1f} | {t:.2f} s |")
        xyz_m = xyz * np.array([u, u, cloud.vertical_unit_factor or u])
        res, t = timed(lambda: run_csf(xyz_m, 0.5, 0.5), repeat)
        a, b, c = scores(res, truth)
        print(f"| {name} | CSF (cloud in metres) | cloth 0.5 m = {0.5 / u:.2f} {unit}, threshold 0.5 m = "
              f"{0.5 / u:.2f} {unit}, rigidness 2, slope smoothing | {a:.1f} | {b:.1f} | {c:.1f} | {t:.2f} s |")
        if name == "4_6_crop.las":                              # labelled: CSF is not scale-free
            for res_m in (0.5, 1.0):
                for label, cloud_xyz, f in (("metres", xyz_m, 1.0), (f"raw {unit}", xyz, 1.0 / u)):
                    pred = run_csf(cloud_xyz, res_m * f, 0.5 * f)
                    a, b, c = scores(pred, truth)
                    print(f"| {name} | CSF labelled unit test: cloud in {label} | cloth {res_m:g} m, threshold "
                          f"0.5 m (in the cloud's unit) | {a:.1f} | {b:.1f} | {c:.1f} | — |")
        share = ground_level_share(xyz, truth, 0.3048 / u)
        notes.append(f"{name}: {truth.mean() * 100:.1f} % class 2; {share:.1f} % of the other points lie within "
                     f"0.3 m of the class-2 surface")
    print()
    for n in notes:
        print("*", n)


def roof_benchmark(repeat):
    from photolib.datasets import data_path
    from photolib.pointcloud import read_las
    from photolib.segmentation import detect_shapes
    cloud = read_las(data_path("lidar", "sample_c.las"), unit="metre")
    xyz, building = cloud.xyz, cloud.classification == 6

    def roofs():
        segs = detect_shapes(xyz, "plane", 0.15, min_inliers=50, max_shapes=40,
                             angle_threshold=np.radians(20), rng=0)
        med = np.array([np.median(xyz[s.indices, 2]) for s in segs])
        size = np.array([len(s.indices) for s in segs])
        z_ground = med[size >= 200].min()
        pred = np.zeros(len(xyz), bool)
        n_roofs = 0
        for s, m in zip(segs, med):
            if m >= z_ground + 2.5 and abs(s.model.normal[2]) >= np.cos(np.radians(60)):
                pred[s.indices] = True
                n_roofs += 1
        return pred, len(segs), n_roofs
    (pred, n_planes, n_roofs), t = timed(roofs, repeat)
    recall, precision = pred[building].mean() * 100, building[pred].mean() * 100
    print(f"\nsample_c.las: {len(xyz)} points, {building.mean() * 100:.1f} % class 6 (building)\n")
    print("| method | planes (roofs) | recall of building points % | precision % | time (median) |")
    print("|---|---|---|---|---|")
    print(f"| photolib RANSAC planes (0.15 m, 20°, ≥ 50 points) + roof rule | {n_planes} ({n_roofs}) "
          f"| {recall:.1f} | {precision:.1f} | {t:.2f} s |")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=3)
    args = ap.parse_args(argv)
    try:
        import laspy  # noqa: F401
        import CSF  # noqa: F401
    except ImportError as exc:
        print(f"{exc.name} is not installed (bench extra): benchmark skipped")
        return 0
    from photolib.datasets import DataUnavailableError
    try:
        ground_benchmark(args.repeat)
        roof_benchmark(args.repeat)
    except DataUnavailableError as exc:
        print(f"real data absent, benchmark skipped: {exc}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
