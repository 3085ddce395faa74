"""Benchmark: photolib's bundle adjustment (§3.5) against scipy and COLMAP/Ceres.

Every solver adjusts the *same* problem: a synthetic aerial block (photolib.synthetic,
60 % forward / 30 % side overlap, tens of tie points per image, f = 100 mm, σ = 0.005 mm),
identical start values (truth perturbed by 5 m / 0.5°), control points held fixed, the same
unweighted least-squares objective (image residuals). Each method runs in a fresh process so
that its peak memory (ru_maxrss of that process) can be measured.

Methods:

* ``photolib`` — :func:`photolib.bundle.bundle_adjustment` (Gauss–Newton, reduction (3.5.16),
  band Cholesky of the reduced matrix).
* ``scipy`` — :func:`scipy.optimize.least_squares` (method "trf", x_scale="jac") with the
  analytic sparse Jacobian of the same sympy model. With a sparse Jacobian "trf" solves each
  trust-region step by LSMR; with its default tolerances (1e-6) the steps are too inexact to reach
  the solution of the others (at 100 images it stalled 4 mm away after 478 evaluations), with 1e-10
  it stopped 1.3e-4 m away at 1000 images; so LSMR gets atol = btol = 1e-12 and ftol = xtol =
  gtol = 1e-12, which reaches the common solution within 1e-5 m in a handful of iterations.
* ``colmap`` — COLMAP's Ceres bundle adjuster through pycolmap (a PINHOLE camera with fixed
  intrinsics, control points constant). pycolmap is a benchmark-only dependency; give the
  interpreter that has it with ``--colmap-python`` (default: this interpreter).
* ``colmap-gn`` — the same Ceres problem run as plain Gauss–Newton: Levenberg–Marquardt with an
  initial (and maximal) trust region of 1e16, so that the damping vanishes and every step is the
  Gauss–Newton step; the fair per-iteration comparison with photolib.
* ``photolib-before`` (with ``--before ROOT``) — photolib from another checkout (e.g. a clone of
  the code before a change), run by that checkout's own benchmark worker in the same run.

Blocks: ``--points-per-image 40`` (default, ~38 observations per image) and the denser block of
issue 8, ``--dense`` (= ``--points-per-image 150``: 1000 images, ~43 000 points, ~143
observations per image).

Usage::

    python benchmarks/bundle_adjustment.py                       # sizes 10, 100, 1000
    python benchmarks/bundle_adjustment.py --sizes 10 100 --methods photolib colmap
    python benchmarks/bundle_adjustment.py --colmap-python /path/to/venv/bin/python
    python benchmarks/bundle_adjustment.py --sizes 10 100 1000 5000 --methods photolib colmap --json out.json
    python benchmarks/bundle_adjustment.py --sizes 1000 --dense --methods photolib colmap colmap-gn \
        --before /tmp/engine_before --repeat 3

A run that exceeds ``--timeout`` seconds is stopped and reported as a lower bound, with the
progress it had made (function evaluations, cost) as evidence.

Not part of the test suite; timings depend on the machine and its load (``uptime`` is recorded).
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
LAYOUTS = {10: (2, 5), 100: (5, 20), 1000: (20, 50)}    # images → (strips, images per strip)
PIXEL = 0.01                                             # mm per pixel for COLMAP (10 µm)
POINTS_PER_IMAGE = int(os.environ.get("PHOTOLIB_BENCH_POINTS_PER_IMAGE", 40))   # set by --points-per-image
SIGMA = 0.005


# --- the common problem ---------------------------------------------------------------------------
def make_problem(n_images: int):
    sys.path.insert(0, str(ROOT))
    from photolib import synthetic
    strips, per_strip = LAYOUTS.get(n_images) or (max(1, round(np.sqrt(n_images / 2.5))), 0)
    if per_strip == 0:
        per_strip = max(2, round(n_images / strips))
    blk = synthetic.aerial_block(strips, per_strip, points_per_image=POINTS_PER_IMAGE, sigma=SIGMA, seed=1)
    cams0, pts0 = blk.start_values(seed=2)
    return blk, cams0, pts0


def image_rms(blk, cams, pts):
    """r.m.s. image residual (mm, per coordinate) of a solution, computed by the book's (3.5.1)."""
    from photolib.single_image import project_to_images
    o = blk.observations
    xy, _ = project_to_images(cams, o.image, pts[o.point], blk.io, blk.order)
    return float(np.sqrt(np.mean((xy - o.xy) ** 2)))


def peak_mb() -> float:
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0


def log(msg):
    print(msg, file=sys.stderr, flush=True)


# --- workers ------------------------------------------------------------------------------------
def run_photolib(blk, cams0, pts0):
    from photolib.bundle import bundle_adjustment
    control = {int(i): blk.points[i] for i in blk.control}
    try:         # numba's start-up and the cached machine code of the compiled loops: once per process,
        from photolib import _block_kernels      # reported separately (like loading COLMAP's library)
        kernel_load = _block_kernels.load()
    except ImportError:                          # a checkout before the compiled loops (--before)
        kernel_load = None
    t = time.perf_counter()
    res = bundle_adjustment(blk.observations, cams0, pts0, blk.io, control=control, sigma_image=SIGMA,
                            order=blk.order, covariance=False,
                            progress=lambda r: log(f"  photolib it {r.iteration}: VtPV={r.vtpv:.6g} "
                                                   f"max|d|={r.delta[0]:.3g}/{r.delta[1]:.3g}"))
    wall = time.perf_counter() - t
    parts = {k: round(v, 4) for k, v in res.timings.items()}
    parts["other (input checks, loop)"] = round(wall - sum(parts.values()), 4)
    if kernel_load is not None:
        parts["kernel load before the timed run (not in the time)"] = round(kernel_load, 4)
    parts["blas threads in the factorisation"] = _factorisation_threads(blk)
    return res.cameras, res.points, wall, res.iterations, parts


def _factorisation_threads(blk):
    """BLAS threads the band Cholesky used at this block size (after the timed run, not timed).

    photolib limits BLAS to one thread when the band of S holds more than
    ``photolib.lsq._ONE_THREAD_FROM`` numbers; below that the step is compiled (no BLAS call:
    0 threads; a checkout before the compiled step used the BLAS library's own thread count).
    Computed from the block pattern the solver builds (same function, same inputs).
    """
    try:
        from photolib import lsq
        o, n, k = blk.observations, blk.n_images, len(blk.points)
        free_points = np.ones(k, bool)
        free_points[blk.control] = False
        pattern = lsq._block_pattern(np.asarray(o.image, np.intp), np.asarray(o.point, np.intp), n, k, 6,
                                     np.ones(n, bool), free_points)
        stored = (pattern["bandwidth"] + 1) * pattern["order"].size
        if stored > lsq._ONE_THREAD_FROM:
            return 1.0
        if hasattr(lsq, "_solve_block_compiled"):
            return 0.0
        info = [i for i in lsq._blas_controller().info() if i.get("user_api") == "blas"]
        return float(max((i["num_threads"] for i in info), default=-1))
    except (ImportError, AttributeError, KeyError):          # another checkout (--before): unknown
        return -1.0


def run_scipy(blk, cams0, pts0):
    from scipy import sparse
    from scipy.optimize import least_squares
    from photolib import _bundle_generated                      # the sympy model's printed code
    fn = getattr(_bundle_generated, f"collinearity_{blk.order}")
    o = blk.observations
    n, k = blk.n_images, len(blk.points)
    free = np.ones(k, bool)
    free[blk.control] = False
    col_of_point = np.full(k, -1)
    col_of_point[free] = 6 * n + 3 * np.arange(free.sum())
    m = len(o)
    on = free[o.point]
    # sparsity pattern: rows 2k, 2k+1; columns 6 image unknowns + 3 point coordinates (if free)
    rows_c = np.repeat(np.arange(2 * m), 6)
    cols_c = (6 * np.repeat(o.image, 2)[:, None] + np.arange(6)).ravel()
    rows_p = np.repeat(np.arange(2 * m).reshape(m, 2)[on].ravel(), 3)
    cols_p = (np.repeat(col_of_point[o.point[on]], 2)[:, None] + np.arange(3)).ravel()
    rows = np.concatenate([rows_c, rows_p])
    cols = np.concatenate([cols_c, cols_p])
    n_par = 6 * n + 3 * int(free.sum())
    pts_fixed = blk.points.copy()

    def unpack(p):
        cams = p[:6 * n].reshape(n, 6)
        pts = pts_fixed.copy()
        pts[free] = p[6 * n:].reshape(-1, 3)
        return cams, pts

    def evaluate(p):
        cams, pts = unpack(p)
        c, X = cams[o.image], pts[o.point]
        return fn(c[:, 0], c[:, 1], c[:, 2], c[:, 3], c[:, 4], c[:, 5], X[:, 0], X[:, 1], X[:, 2],
                  o.xy[:, 0], o.xy[:, 1], blk.io.f, blk.io.x0, blk.io.y0)

    started, started_at = time.perf_counter(), time.time()
    state = {"nfev": 0, "shown": started}

    def fun(p):
        F, _ = evaluate(p)
        r = F.T.ravel()
        state["nfev"] += 1
        now = time.perf_counter()
        PROGRESS.write_text(json.dumps({"nfev": state["nfev"], "cost": 0.5 * float(r @ r),
                                        "seconds": now - started, "started_at": started_at}))
        if now - state["shown"] > 10:
            log(f"  scipy: {state['nfev']} evaluations, cost {0.5 * float(r @ r):.6g}, {now - started:.0f} s")
            state["shown"] = now
        return r

    def jac(p):
        _, J = evaluate(p)
        J = J.reshape(2, 9, m).transpose(2, 0, 1)                # (m, 2, 9)
        vals = np.concatenate([J[:, :, :6].ravel(), J[on][:, :, 6:].ravel()])
        return sparse.csr_matrix((vals, (rows, cols)), shape=(2 * m, n_par))

    x0 = np.concatenate([cams0.ravel(), pts0[free].ravel()])
    t = time.perf_counter()
    sol = least_squares(fun, x0, jac=jac, method="trf", x_scale="jac", ftol=1e-12, xtol=1e-12, gtol=1e-12,
                        max_nfev=100, tr_options={"atol": 1e-12, "btol": 1e-12}, verbose=2)
    wall = time.perf_counter() - t
    cams, pts = unpack(sol.x)
    return cams, pts, wall, int(sol.njev), {"status": int(sol.status), "nfev": int(sol.nfev)}


def run_colmap_gn(blk, cams0, pts0):
    """Ceres as plain Gauss–Newton: LM whose trust region never limits the step."""
    return run_colmap(blk, cams0, pts0, gauss_newton=True)


def run_colmap(blk, cams0, pts0, gauss_newton=False):
    import pycolmap
    from photolib.rotation import rotation_matrix
    o = blk.observations
    n = blk.n_images
    flip = np.diag([1.0, -1.0, -1.0])
    size = int(round(blk.frame_size / PIXEL))
    f_px = blk.io.f / PIXEL
    cx, cy = size / 2 + blk.io.x0 / PIXEL, size / 2 - blk.io.y0 / PIXEL     # book x0, y0 → pixels
    rec = pycolmap.Reconstruction()
    camera = pycolmap.Camera(model="PINHOLE", width=size, height=size, params=[f_px, f_px, cx, cy], camera_id=1)
    rec.add_camera_with_trivial_rig(camera)
    # book image (x, y) → COLMAP pixel (u, v) = (cx + (x − x0)/pixel, cy − (y − y0)/pixel)
    uv = np.column_stack([cx + (o.xy[:, 0] - blk.io.x0) / PIXEL, cy - (o.xy[:, 1] - blk.io.y0) / PIXEL])
    A = rotation_matrix(cams0[:, 3], cams0[:, 4], cams0[:, 5], blk.order)
    order = np.argsort(o.image, kind="stable")
    starts = np.searchsorted(o.image[order], np.arange(n + 1))
    point2d_index = np.empty(len(o), int)
    for j in range(n):
        obs = order[starts[j]:starts[j + 1]]
        point2d_index[obs] = np.arange(obs.size)
        R = flip @ A[j].T                                           # R_cv = diag(1, −1, −1)·Aᵀ
        t = -R @ cams0[j, :3]
        image = pycolmap.Image(name=f"img{j}", keypoints=uv[obs], camera_id=1, image_id=j + 1)
        rec.add_image_with_trivial_frame(image, pycolmap.Rigid3d(np.column_stack([R, t])))
    order_p = np.argsort(o.point, kind="stable")
    pstarts = np.searchsorted(o.point[order_p], np.arange(len(blk.points) + 1))
    point_id = np.empty(len(blk.points), int)
    for p in range(len(blk.points)):
        track = pycolmap.Track()
        for k in order_p[pstarts[p]:pstarts[p + 1]]:
            track.add_element(int(o.image[k]) + 1, int(point2d_index[k]))
        point_id[p] = rec.add_point3D(pts0[p], track)

    config = pycolmap.BundleAdjustmentConfig()
    for j in range(n):
        config.add_image(j + 1)
    config.set_constant_cam_intrinsics(1)
    for p in blk.control:
        config.add_constant_point(int(point_id[p]))
    options = pycolmap.BundleAdjustmentOptions()
    options.refine_focal_length = False
    options.refine_principal_point = False
    options.refine_extra_params = False
    options.print_summary = False
    so = options.ceres.solver_options
    so.function_tolerance = 1e-15
    so.gradient_tolerance = 1e-15
    so.parameter_tolerance = 1e-12
    so.max_num_iterations = 100
    so.minimizer_progress_to_stdout = True
    if gauss_newton:                        # μ = 1/radius ≈ 0: the LM step is the Gauss–Newton step
        so.initial_trust_region_radius = 1e16
        so.max_trust_region_radius = 1e16
    solver = os.environ.get("PHOTOLIB_BENCH_COLMAP_SOLVER", "auto")
    if solver != "auto":                    # e.g. SPARSE_SCHUR instead of COLMAP's choice by block size
        options.ceres.auto_select_solver_type = False
        so.linear_solver_type = getattr(type(so.linear_solver_type), solver.upper())
    t0 = time.perf_counter()
    adjuster = pycolmap.create_default_bundle_adjuster(options, config, rec)
    summary = adjuster.solve()
    wall = time.perf_counter() - t0
    cams = np.empty((n, 6))
    from photolib.rotation import rotation_angles
    for j in range(n):
        pose = rec.image(j + 1).cam_from_world()
        M = np.asarray(pose.matrix())
        R, tvec = M[:, :3], M[:, 3]
        cams[j, :3] = -R.T @ tvec
        cams[j, 3:] = rotation_angles((flip @ R).T, blk.order)
    pts = np.array([rec.point3D(int(point_id[p])).xyz for p in range(len(blk.points))])
    brief = summary.brief_report() if hasattr(summary, "brief_report") else ""
    iters = -1
    try:
        iters = int(str(brief).split("Iterations:")[1].split(",")[0])
    except (IndexError, ValueError):
        pass
    extra = {"report": str(brief).strip()}
    ceres = getattr(summary, "ceres_summary", None)
    for key in ("linear_solver_type_used", "num_threads_used"):
        if ceres is not None and hasattr(ceres, key):
            extra[key] = str(getattr(ceres, key))
    return cams, pts, wall, iters, extra


PROGRESS = Path(os.devnull)        # the scipy worker's progress file (evidence when it is stopped)


def worker(method: str, size: int, out: Path):
    global PROGRESS
    PROGRESS = out.with_suffix(".progress")
    blk, cams0, pts0 = make_problem(size)
    base_mb = peak_mb()
    runner = {"photolib": run_photolib, "scipy": run_scipy, "colmap": run_colmap, "colmap-gn": run_colmap_gn}[method]
    cams, pts, wall, iters, extra = runner(blk, cams0, pts0)
    np.save(out.with_suffix(".npy"), cams)
    result = dict(method=method, images=blk.n_images, points=len(blk.points), observations=len(blk.observations),
                  wall=wall, iterations=iters, rms_image_mm=image_rms(blk, cams, pts),
                  centre_rms_m=float(np.sqrt(np.mean(np.sum((cams[:, :3] - blk.cameras[:, :3]) ** 2, axis=1)))),
                  peak_mb=peak_mb(), baseline_mb=base_mb, extra=extra)
    out.write_text(json.dumps(result))


# --- driver -------------------------------------------------------------------------------------
def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--sizes", type=int, nargs="+", default=[10, 100, 1000])
    ap.add_argument("--methods", nargs="+", default=["photolib", "scipy", "colmap"])
    ap.add_argument("--colmap-python", default=os.environ.get("PHOTOLIB_BENCH_PYTHON", sys.executable))
    ap.add_argument("--timeout", type=float, default=600.0,
                    help="seconds per solver run; a longer run is stopped and reported as a lower bound")
    ap.add_argument("--repeat", type=int, default=1, help="runs per method; the fastest is reported")
    ap.add_argument("--colmap-solver", default="auto",
                    help="Ceres linear solver for COLMAP: 'auto' = COLMAP's choice (dense Schur up to 50 images, "
                         "sparse Schur up to 1000, iterative Schur above) or a Ceres name such as SPARSE_SCHUR")
    ap.add_argument("--points-per-image", type=int, default=POINTS_PER_IMAGE,
                    help="tie-point density of the synthetic block (points measured per image, default 40)")
    ap.add_argument("--dense", action="store_true",
                    help="the denser block of issue 8: --points-per-image 150 (~143 observations per image)")
    ap.add_argument("--before", type=Path,
                    help="another photolib checkout (e.g. a clone before a change): adds the method photolib-before")
    ap.add_argument("--json", type=Path, help="write all results to this file")
    ap.add_argument("--worker", nargs=3, metavar=("METHOD", "SIZE", "OUT"), help=argparse.SUPPRESS)
    args = ap.parse_args(argv)
    if args.worker:
        worker(args.worker[0], int(args.worker[1]), Path(args.worker[2]))
        return 0

    if args.dense:
        args.points_per_image = 150
    if args.before is not None and "photolib-before" not in args.methods:
        args.methods = ["photolib-before"] + list(args.methods)
    os.environ["PHOTOLIB_BENCH_POINTS_PER_IMAGE"] = str(args.points_per_image)   # inherited by the workers
    results = []
    load_before = os.getloadavg()
    with tempfile.TemporaryDirectory() as tmp:
        for size in args.sizes:
            for method in args.methods:
                python = args.colmap_python if method.startswith("colmap") else sys.executable
                root, script, worker_method = ROOT, __file__, method
                if method == "photolib-before":
                    if args.before is None:
                        log("  photolib-before needs --before ROOT")
                        break
                    root = args.before.resolve()
                    script, worker_method = str(root / "benchmarks" / "bundle_adjustment.py"), "photolib"
                best = None
                for rep in range(args.repeat):
                    out = Path(tmp) / f"{method}_{size}_{rep}.json"
                    log(f"[{size} images] {method} (run {rep + 1}/{args.repeat}) ...")
                    env = dict(os.environ, PYTHONPATH=str(root) + os.pathsep + os.environ.get("PYTHONPATH", ""),
                               PHOTOLIB_BENCH_COLMAP_SOLVER=args.colmap_solver)
                    try:
                        proc = subprocess.run([python, script, "--worker", worker_method, str(size), str(out)],
                                              env=env, stdout=sys.stderr, timeout=args.timeout)
                    except subprocess.TimeoutExpired:
                        progress = out.with_suffix(".progress")
                        evidence = json.loads(progress.read_text()) if progress.exists() else {}
                        # lower bound of the solve time: from the solver's start to the stop (setup excluded)
                        solving = time.time() - evidence["started_at"] if evidence else 0.0
                        log(f"  {method}: stopped after {args.timeout:.0f} s ({solving:.0f} s solving): {evidence}")
                        best = dict(method=method, requested=size, timed_out=True, wall=solving, evidence=evidence)
                        break
                    if proc.returncode != 0 or not out.exists():
                        log(f"  {method}: failed (exit code {proc.returncode})")
                        break
                    r = json.loads(out.read_text())
                    r["method"] = method
                    r["centres"] = str(out.with_suffix(".npy"))
                    r["requested"] = size
                    if best is None or r["wall"] < best["wall"]:
                        best = r
                if best is not None:
                    results.append(best)
                    if not best.get("timed_out"):
                        log(f"  {method}: {best['wall']:.2f} s, {best['iterations']} it, "
                            f"rms {best['rms_image_mm'] * 1000:.3f} µm, peak {best['peak_mb']:.0f} MB")
        print(f"load average before/after: {load_before} / {os.getloadavg()}; {os.cpu_count()} cores")
        report(results)
        if args.json:
            for r in results:
                r.pop("centres", None)
            results.append({"load_before": load_before, "load_after": os.getloadavg(), "cores": os.cpu_count()})
            args.json.write_text(json.dumps(results, indent=1))
    return 0


def report(results):
    """Markdown: one row per run, then the ratios and the four targets for every size."""
    print("\n| images | points | obs | method | solve s | iterations | rms image µm | centre err vs truth m "
          "| Δ centres vs COLMAP m | peak MB (baseline) |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    verdicts = []
    for size in sorted({r["requested"] for r in results}):
        group = [r for r in results if r["requested"] == size]
        done = [r for r in group if not r.get("timed_out")]
        ref = next((r for r in done if r["method"] == "colmap"), None)
        ref_c = np.load(ref["centres"]) if ref else None
        diffs = {}
        for r in group:
            if r.get("timed_out"):
                ev = r.get("evidence", {})
                print(f"| {size} | | | {r['method']} | > {r['wall']:.0f} (stopped after {ev.get('nfev', '?')} "
                      f"evaluations, cost {ev.get('cost', float('nan')):.6g}) | | | | | |")
                continue
            if ref_c is not None:
                diffs[r["method"]] = float(np.abs(np.load(r["centres"])[:, :3] - ref_c[:, :3]).max())
            diff = f"{diffs[r['method']]:.1e}" if r["method"] in diffs else "—"
            how = ""
            if r["method"].startswith("colmap"):
                ex = r.get("extra", {})
                term = ex.get("report", "").split("Termination:")[-1].strip()
                how = f" ({ex.get('linear_solver_type_used', '?').split('.')[-1]}, {term})"
            elif r["method"] == "scipy":
                how = f" ({r['extra'].get('nfev')} evaluations, status {r['extra'].get('status')})"
            print(f"| {r['images']} | {r['points']} | {r['observations']} | {r['method']} | {r['wall']:.3f} | "
                  f"{r['iterations']}{how} | {r['rms_image_mm'] * 1000:.4f} | {r['centre_rms_m']:.4f} | {diff} | "
                  f"{r['peak_mb']:.0f} ({r['baseline_mb']:.0f}) |")
        pl = next((r for r in done if r["method"] == "photolib"), None)
        sc = next((r for r in group if r["method"] == "scipy"), None)
        if pl is None:
            continue
        def met(ok):               # the targets are set for blocks of 1000 images and more
            return ("met" if ok else "NOT met") if size >= 1000 else "target set at 1000 images"

        gn = next((r for r in done if r["method"] == "colmap-gn"), None)
        before = next((r for r in done if r["method"] == "photolib-before"), None)
        if before is not None:
            verdicts.append(f"{size} images: photolib after/before time ×{pl['wall'] / before['wall']:.2f} "
                            f"(≤ 1, no regression: {'met' if pl['wall'] <= before['wall'] else 'NOT met'}); "
                            f"{before['iterations']} → {pl['iterations']} iterations")
        if gn is not None:
            t = pl["wall"] / gn["wall"]
            verdict = ("met" if t <= 1.1 else "NOT met") if size >= 1000 else "target set at 1000 images"
            verdicts.append(f"{size} images: photolib/Ceres-as-Gauss–Newton time ×{t:.2f} (≤ 1.1: {verdict}); "
                            f"iterations {pl['iterations']} / {gn['iterations']}")
        if ref is not None and size < 1000:
            t = pl["wall"] / ref["wall"]
            verdicts.append(f"{size} images: photolib/COLMAP time ×{t:.2f} (≤ 1, no slower than COLMAP: "
                            f"{'met' if t <= 1 else 'NOT met'})")
        if ref is not None:
            t, m = pl["wall"] / ref["wall"], pl["peak_mb"] / ref["peak_mb"]
            verdicts.append(f"{size} images: photolib/COLMAP time ×{t:.2f} (≤ 1.5: {met(t <= 1.5)}); "
                            f"peak memory ×{m:.2f} (≤ 1: {met(m <= 1)}; "
                            f"increments over baseline {pl['peak_mb'] - pl['baseline_mb']:.0f} vs "
                            f"{ref['peak_mb'] - ref['baseline_mb']:.0f} MB); Δ centres photolib–COLMAP "
                            f"{diffs.get('photolib', float('nan')):.1e} m (≤ 1e-4: {met(diffs.get('photolib', 1) <= 1e-4)})")
        if sc is not None:
            k = sc["wall"] / pl["wall"]
            bound = "≥ " if sc.get("timed_out") else ""
            same = "" if sc.get("timed_out") or "scipy" not in diffs else f", its Δ centres vs COLMAP {diffs['scipy']:.1e} m"
            verdicts.append(f"{size} images: scipy/photolib time {bound}×{k:.1f} (≥ 10: {met(k >= 10)}{same})")
        parts = ", ".join(f"{k} {v:.3f}" for k, v in pl.get("extra", {}).items())
        verdicts.append(f"{size} images: photolib time split (s): {parts}")
    print()
    for line in verdicts:
        print(f"* {line}")
    print()


if __name__ == "__main__":
    sys.exit(main())
