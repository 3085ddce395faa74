"""ICP on the terrestrial scan lone-star.laz (Chapter 9, §9.6): photolib.registration.icp vs small_gicp.

A known offset (≈ 5° about a tilted axis and ≈ 0.5 m) is applied to the full cloud, both clouds
are voxel-downsampled at 5 cm (centroid per voxel, on independent grids because the source is
moved first), and both libraries register the same arrays: photolib point-to-plane (plain and
coarse-to-fine) and point-to-point, small_gicp PLANE_ICP and GICP. Rotation and translation errors against the known
offset, wall time (median of a few repeats, normals and k-d trees included) and the time ratio.

Run: python benchmarks/icp_lonestar.py [--repeats 3] [--threads 1]
(needs ../shared/data/lidar/lone-star.laz, laspy[lazrs] and small_gicp: the `geo` and `bench` extras).
"""

from __future__ import annotations

import argparse
import time

import numpy as np

from photolib import datasets
from photolib.pointcloud import voxel_downsample
from photolib.registration import RigidTransform, icp

OFFSET = RigidTransform(0.30, -0.35, 0.20, *np.deg2rad([2.0, -3.0, 3.5]))


def errors(T_est):
    err = OFFSET.inverse().compose(T_est)
    return np.rad2deg(err.rotation_angle), float(np.linalg.norm(err.shift))


def timed(fn, repeats):
    times, result = [], None
    for _ in range(repeats):
        t0 = time.perf_counter()
        result = fn()
        times.append(time.perf_counter() - t0)
    return float(np.median(times)), result


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--threads", type=int, default=1)
    ap.add_argument("--voxel", type=float, default=0.05)
    ap.add_argument("--split", action="store_true", help="also register each tile of lone-star-split")
    args = ap.parse_args()
    try:
        path = datasets.data_path("lidar", "lone-star.laz")
    except datasets.DataUnavailableError as exc:
        print(f"real data absent: {exc}")
        return
    import laspy
    import small_gicp
    las = laspy.read(path)
    crs = las.header.parse_crs()
    unit = crs.axis_info[0].unit_name if crs is not None else "none"
    if crs is not None and crs.is_geographic and np.abs(las.header.maxs[:2]).max() > 360:
        unit = (f"header CRS '{crs.name}' is geographic (degrees) but X, Y reach "
                f"{np.abs(las.header.maxs[:2]).max():.0f}: a wrong CRS record; the extent "
                f"{np.ptp([las.header.mins, las.header.maxs], axis=0).round(1).tolist()} is metres")
    full = np.column_stack([las.x, las.y, las.z]).astype(float)
    full_mean = full.mean(axis=0)
    full -= full_mean                                         # local frame (the offset is applied here)
    target = voxel_downsample(full, args.voxel)
    source = voxel_downsample(OFFSET.inverse().apply(full), args.voxel)
    print(f"lone-star.laz: {len(full)} points, unit {unit}; {args.voxel} m voxels: target {len(target)}, "
          f"source {len(source)}; offset {np.rad2deg(OFFSET.rotation_angle):.2f}° / "
          f"{np.linalg.norm(OFFSET.shift):.3f} m; median of {args.repeats}, {args.threads} thread(s)\n")
    w = -1 if args.threads > 1 else 1
    rows = []
    for name, method, coarse in (("photolib point-to-plane", "point-to-plane", None),
                                 ("photolib point-to-plane, coarse 10 %", "point-to-plane", 0.1),
                                 ("photolib point-to-point, coarse 10 %", "point-to-point", 0.1)):
        t, r = timed(lambda: icp(source, target, method=method, max_distance=1.0, max_iter=100,
                                 tol_rotation=1e-6, tol_translation=1e-5, workers=w, coarse_fraction=coarse,
                                 raise_on_max_iter=False), args.repeats)
        rows.append((name, t, *errors(r.transform), r.iterations))
    for name, kind in (("small_gicp PLANE_ICP", "PLANE_ICP"), ("small_gicp GICP", "GICP")):
        t, r = timed(lambda: small_gicp.align(target, source, registration_type=kind,
                                              downsampling_resolution=args.voxel, max_correspondence_distance=1.0,
                                              num_threads=args.threads, max_iterations=100), args.repeats)
        rows.append((name, t, *errors(RigidTransform.from_homogeneous(r.T_target_source)), r.iterations))
    ref = rows[3][1]
    print("| method | time (s) | × small_gicp PLANE_ICP | rotation error (°) | translation error (mm) | iterations |")
    print("|---|---|---|---|---|---|")
    for name, t, rot, tr, it in rows:
        print(f"| {name} | {t:.2f} | {t / ref:.2f} | {rot:.5f} | {tr * 1000:.2f} | {it} |")
    if args.split:
        split(args, full_mean, target, w, small_gicp, laspy)


def split(args, full_mean, target, w, small_gicp, laspy):
    """Each tile of lone-star-split, moved by the offset, registered to the whole (unmoved) scan."""
    print("\nlone-star-split: each tile moved by the same offset and registered to the whole scan\n")
    print("| tile | points (voxels) | photolib p2plane coarse (s) | rot (°) / trans (mm) "
          "| small_gicp PLANE_ICP (s) | rot (°) / trans (mm) | time ratio |")
    print("|---|---|---|---|---|---|---|")
    for i in range(1, 5):
        try:
            path = datasets.data_path("lidar", "lone-star-split", f"split-{i}.laz")
        except datasets.DataUnavailableError as exc:
            print(f"real data absent: {exc}")
            return
        las = laspy.read(path)
        tile = np.column_stack([las.x, las.y, las.z]).astype(float) - full_mean
        source = voxel_downsample(OFFSET.inverse().apply(tile), args.voxel)
        t1, r1 = timed(lambda: icp(source, target, max_distance=1.0, max_iter=100, tol_rotation=1e-6,
                                   tol_translation=1e-5, workers=w, coarse_fraction=0.1,
                                   raise_on_max_iter=False), args.repeats)
        t2, r2 = timed(lambda: small_gicp.align(target, source, registration_type="PLANE_ICP",
                                                downsampling_resolution=args.voxel, max_correspondence_distance=1.0,
                                                num_threads=args.threads, max_iterations=100), args.repeats)
        e1 = errors(r1.transform)
        e2 = errors(RigidTransform.from_homogeneous(r2.T_target_source))
        print(f"| {i} | {len(source)} | {t1:.2f} | {e1[0]:.5f} / {e1[1] * 1000:.2f} | {t2:.2f} | "
              f"{e2[0]:.5f} / {e2[1] * 1000:.2f} | {t1 / t2:.2f} |")


if __name__ == "__main__":
    main()
