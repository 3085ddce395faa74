"""Figures for Chapter 9 (laser scanning), drawn from library calls.

* :func:`als_geometry` — §9.1–9.2 (Figs. 9.2/9.9): the fan of pulses of (9.1.1)/(9.1.2) over
  flat ground (level and rolled), the swath SW = 2H·tan(Θ/2) of the Table 9.1 scanners against
  the printed values, and the footprint 2H·tan(g/2) with the printed 25 cm at 1000 m.
* :func:`laser_line_scanner` — §9.4 (Figs. 9.18/9.19): the simulated image of the test object
  with the laser trace, the reconstructed profile and its error against the simulation's truth
  (:func:`photolib.lidar.simulate_laser_line_scanner`, :func:`photolib.lidar.laser_line_scan`).
* :func:`icp_before_after` — §9.6 (Figs. 9.22/9.23): two stations of one scene before and after
  point-to-plane ICP (:func:`photolib.registration.icp`, the parameters of
  ``benchmarks/icp_lonestar.py``), with the histogram of nearest-neighbour distances.
  :func:`lone_star_stations` builds the stations from the real scan ``lone-star.laz``,
  :func:`synthetic_stations` from a synthetic room (no data needed).
* :func:`roof_segments` — §9.11 (Fig. 9.41): RANSAC planes and the roof rule of
  ``benchmarks/ground_filter_lidar.py`` against the ASPRS building class (``sample_c.las``, or
  :func:`synthetic_building`).
* :func:`dtm_from_classified` — §9.11 (Fig. 9.43): the ground filter
  (:func:`photolib.segmentation.classify_ground`, the benchmark's parameters set in metres and
  converted to the file's unit), the DTM of its ground points beside the DTM of the file's class-2
  points and their difference (``4_6_crop.las``, or :func:`synthetic_classified_cloud`).

Every figure function returns the matplotlib Figure (closed, so that a notebook shows it once)
together with the numbers it shows, rounded.
"""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.colors import LightSource
from matplotlib.lines import Line2D

from ... import dtm, lidar, segmentation
from ...pointcloud import PointCloud, read_lidar_data, voxel_downsample
from ...registration import RigidTransform, icp
from ...rotation import rotation_matrix

# the offset of benchmarks/icp_lonestar.py: ω, α, κ = 2°, −3°, 3.5° and (0.30, −0.35, 0.20) m
ICP_OFFSET = RigidTransform(0.30, -0.35, 0.20, *np.deg2rad([2.0, -3.0, 3.5]))
# the ICP settings of benchmarks/icp_lonestar.py
ICP_SETTINGS = dict(method="point-to-plane", max_distance=1.0, max_iter=100, tol_rotation=1e-6,
                    tol_translation=1e-5, coarse_fraction=0.1, raise_on_max_iter=False)
# the ground-filter parameters of benchmarks/ground_filter_lidar.py, in metres
GROUND_METRES = dict(cell_size=0.9144, max_window=20.0, dh0=0.3048, dh_max=3.048, band=0.3048)
GROUND_SLOPE = 0.5
# the roof rule of benchmarks/ground_filter_lidar.py (metres)
ROOF_SETTINGS = dict(threshold=0.15, angle_deg=20.0, min_inliers=50, max_shapes=40, ground_min=200,
                     above_ground=2.5, max_slope_deg=60.0)


def _done(fig):
    plt.close(fig)
    return fig


def _legend(ax, items, **kw):
    """A legend of round markers (colour, text): readable whatever the scatter's point size."""
    handles = [Line2D([], [], ls="", marker="o", ms=5, color=c, label=t) for c, t in items]
    ax.legend(handles=handles, fontsize=7, **kw)


# --------------------------------------------------------------------------------------------- §9.1–9.2
def _table_9_1():
    """Table 9.1 (airborne scanners) as transcribed in textbook/ch09_lidar.toml."""
    from ..textbook import load_chapter
    return load_chapter(9).example("9.2-table-9.1-als").inputs["units"]


def als_geometry(H=1000.0, fov_deg=60.0, divergence=0.25e-3, roll_deg=7.0, n_rays=13):
    """Figs. 9.2/9.9: scan fan, swath and footprint on flat ground.

    The pulses at mirror angles φ ∈ [−Θ/2, Θ/2] are georeferenced by (9.1.2)
    (:func:`photolib.lidar.als_georeference`) from a scanner H above flat ground, level and
    rolled by ``roll_deg`` about the flight axis (the range D of each pulse is the one that
    reaches Z = 0). The swath and footprint curves use :func:`photolib.lidar.swath_width` and
    :func:`photolib.lidar.footprint_diameter` with the Table 9.1 rows.

    Returns
    -------
    (Figure, dict)
        ``swath_m`` (SW at H), ``swath_check_m`` (edge-to-edge distance of the georeferenced
        fan), ``footprint_nadir_m``, ``footprint_edge_across_m`` (the footprint of the edge
        pulse across the track on the ground), rounded to mm.
    """
    fov = np.radians(fov_deg)
    phi = np.linspace(-fov / 2, fov / 2, n_rays)
    origin = np.array([0.0, 0.0, H])

    def fan(A):
        d = lidar.als_scanner_vector(1.0, phi) @ A.T          # unit ray directions in the object frame
        return lidar.als_georeference(H / -d[:, 2], phi, origin, A)

    level = fan(np.eye(3))
    rolled = fan(rotation_matrix(np.radians(roll_deg), 0.0, 0.0, order="wak"))
    sw = lidar.swath_width(H, fov)
    fp = lidar.footprint_diameter(H, divergence)
    edge = np.array([fov / 2 - divergence / 2, fov / 2 + divergence / 2])
    edge_pts = lidar.als_georeference(H / np.cos(edge), edge, origin, np.eye(3))
    fp_edge = float(edge_pts[1, 1] - edge_pts[0, 1])

    fig, axes = plt.subplots(1, 3, figsize=(15, 4.6))
    ax = axes[0]
    for p in rolled:
        ax.plot([0, p[1]], [H, p[2]], color="C1", lw=0.7, ls="--")
    for p in level:
        ax.plot([0, p[1]], [H, p[2]], color="C0", lw=0.9)
    ax.plot([], [], color="C0", label="level (A = E)")
    ax.plot([], [], color="C1", ls="--", label=f"rolled {roll_deg:g}° (A from the IMU)")
    ax.axhline(0, color="k", lw=1)
    ax.annotate("", xy=(level[-1, 1], -0.06 * H), xytext=(level[0, 1], -0.06 * H),
                arrowprops=dict(arrowstyle="<->", color="k"))
    ax.text(0, -0.1 * H, f"SW = 2H·tan(Θ/2) = {sw:.0f} m", ha="center", va="top")
    ax.text(-0.05 * H, 0.75 * H, f"Θ = {fov_deg:g}°", color="C0", ha="right", fontsize=9)
    ax.plot(0, H, "ks")
    ax.set(xlabel="Y across the track, m", ylabel="Z, m", ylim=(-0.2 * H, 1.1 * H), aspect="equal",
           title=f"(9.1.2): {n_rays} pulses from H = {H:g} m")
    ax.legend(loc="upper right", fontsize=8)

    units = _table_9_1()
    ax = axes[1]
    for k, (key, row) in enumerate(units.items()):
        if row["fov_deg"] >= 180:                             # a 360° scanner has no swath by this formula
            continue
        h = np.linspace(0.0, row["range_max"], 50)
        fov_k = np.radians(row["fov_deg"])
        ax.plot(h, 2 * h * np.tan(fov_k / 2), color=f"C{k}", label=f"{row['model']} (Θ = {row['fov_deg']}°)")
        sw_k = lidar.swath_width(row["range_max"], fov_k)
        ax.plot(row["range_max"], row["SW_m"], "o", mfc="none", color=f"C{k}", ms=9)
        ax.plot(row["range_max"], sw_k, "x", color=f"C{k}")
        ax.annotate(f"{row['SW_m']} / {sw_k:.0f}", (row["range_max"], sw_k), textcoords="offset points",
                    xytext=(-8, 6 if key != "VQ1560i" else -14), ha="right", fontsize=7, color=f"C{k}")
    ax.plot([], [], "ko", mfc="none", label="printed SW (at H = max. range)")
    ax.plot([], [], "kx", label="2H·tan(Θ/2) (labels: printed / computed, m)")
    ax.set(xlabel="H, m", ylabel="SW, m", title="Table 9.1: swath width", xlim=(0, 6200), ylim=(0, 8500))
    ax.legend(fontsize=7, loc="upper left")
    ax.grid(True, lw=0.3)

    ax = axes[2]
    h = np.geomspace(10, 6000, 60)
    ax.plot(h, 100 * lidar.footprint_diameter(h, 0.25e-3), "C0", label="g = 0.25 mrad (AX80, ALS80, VQ-1560i)")
    g_mini = 2 * np.arctan(0.16 / 2 / 100.0)                  # 16 cm at 100 m (miniVUX-1DL)
    ax.plot(h[h <= 250], 100 * lidar.footprint_diameter(h[h <= 250], g_mini), "C4",
            label=f"g = {1000 * g_mini:.2f} mrad (miniVUX-1DL, from 16 cm at 100 m)")
    ax.plot([1000, 100], [25, 16], "ko", mfc="none", ms=9, label="printed: 25 cm at 1000 m, 16 cm at 100 m")
    ax.set(xscale="log", yscale="log", xlabel="H, m", ylabel="footprint D = 2H·tan(g/2), cm",
           title="Footprint diameter")
    ax.legend(fontsize=7, loc="upper left")
    ax.grid(True, which="both", lw=0.3)
    fig.tight_layout()
    numbers = {"swath_m": round(sw, 3), "swath_check_m": round(float(level[-1, 1] - level[0, 1]), 3),
               "footprint_nadir_m": round(fp, 3), "footprint_edge_across_m": round(fp_edge, 3)}
    return _done(fig), numbers


# --------------------------------------------------------------------------------------------- §9.4
def laser_line_scanner(seed=5, sigma_xy=0.001):
    """Figs. 9.18/9.19: the laser-line scanner with the two-plate test object, simulated.

    Left: the simulated image (12 × 12 mm frame) with the marks and the laser trace on plate P1,
    plate P2 and the object. Middle: the reconstruction in object space — the plates' trace
    points (ray ∩ plate, (9.4.8) with the corrected (9.4.9)), the laser plane P3 fitted to them,
    the object profile (ray ∩ P3) coloured from the image by (9.4.10). Right: the profile's
    error against the simulation's truth.

    Returns
    -------
    (Figure, dict)
        ``max_error_mm`` and ``rms_error_mm`` of the profile (0.01 mm), ``points``.
    """
    scene = lidar.simulate_laser_line_scanner(seed=seed, sigma_xy=sigma_xy)
    res = lidar.laser_line_scan(scene.marks_xyz, scene.marks_xy, scene.marks_plate, scene.trace_xy,
                                scene.trace_label, scene.io, image=scene.image, pixel_size=scene.pixel_size)
    truth = scene.trace_xyz[scene.trace_label == 0]
    err = 1000 * np.linalg.norm(res.points - truth, axis=1)
    rows, cols = scene.image.shape
    half_x, half_y = cols * scene.pixel_size / 2, rows * scene.pixel_size / 2

    fig = plt.figure(figsize=(15, 4.8))
    ax = fig.add_subplot(1, 3, 1)
    ax.imshow(scene.image, cmap="gray", extent=(-half_x, half_x, -half_y, half_y), origin="upper")
    names = {1: "trace on P1", 2: "trace on P2", 0: "trace on the object"}
    for lab, colour in ((1, "C0"), (2, "C2"), (0, "C3")):
        t = scene.trace_xy[scene.trace_label == lab]
        ax.plot(t[:, 0], t[:, 1], ".", color=colour, ms=4, label=names[lab])
    ax.plot(scene.marks_xy[:, 0], scene.marks_xy[:, 1], "y+", ms=7, label="marks")
    ax.set(xlabel="x, mm", ylabel="y, mm", title="Image: marks and laser trace")
    ax.legend(fontsize=7, loc="lower left")

    ax = fig.add_subplot(1, 3, 2, projection="3d")
    for a, b in ((0, 1), (1, 0)):                              # plate outlines Y = 0 and X = 0
        c = np.array([[0, 0], [1, 0], [1, 1], [0, 1], [0, 0]], float)
        P = np.zeros((5, 3))
        P[:, a], P[:, 2] = c[:, 0], c[:, 1]
        ax.plot(P[:, 0], P[:, 1], P[:, 2], color="0.4", lw=1)
    ax.scatter(*scene.marks_xyz.T, marker="+", color="y", s=20)
    n1 = int(np.sum(scene.trace_label == 1))
    ax.scatter(*res.plate_points[:n1].T, color="C0", s=6, label="ray ∩ P1")
    ax.scatter(*res.plate_points[n1:].T, color="C2", s=6, label="ray ∩ P2 (→ laser plane P3)")
    t = np.linspace(0, 2 * np.pi, 60)
    cx = scene.object_centre[0] + scene.object_radius * np.cos(t)
    cy = scene.object_centre[1] + scene.object_radius * np.sin(t)
    for z in (0.0, 0.8):
        ax.plot(cx, cy, np.full_like(t, z), color="0.6", lw=0.6)
    colours = np.clip(np.nan_to_num(res.colours, nan=0.0), 0, 1) if res.colours is not None else "C3"
    ax.scatter(*res.points.T, c=colours, cmap="gray", vmin=0, vmax=1, edgecolors="C3", s=18,
               label="object profile (colour (9.4.10))")
    S = res.eo.center
    ax.scatter(*S, color="k", marker="^", s=30, label="camera S (resection)")
    ax.set(xlabel="X, m", ylabel="Y, m", zlabel="Z, m", title="Object space")
    ax.view_init(elev=25, azim=45)
    ax.legend(fontsize=7, loc="upper left")

    ax = fig.add_subplot(1, 3, 3)
    ang = np.degrees(np.arctan2(truth[:, 1] - scene.object_centre[1], truth[:, 0] - scene.object_centre[0]))
    ax.plot(ang, err, "o-", color="C3", ms=3)
    ax.set(xlabel="azimuth on the cylinder, °", ylabel="|profile point − truth|, mm",
           title=f"Profile error (image noise {sigma_xy * 1000:g} µm)")
    ax.grid(True, lw=0.3)
    fig.tight_layout()
    numbers = {"points": int(len(err)), "max_error_mm": round(float(err.max()), 2),
               "rms_error_mm": round(float(np.sqrt(np.mean(err ** 2))), 2)}
    return _done(fig), numbers


# --------------------------------------------------------------------------------------------- §9.6
def stations_from_cloud(points, voxel, offset=ICP_OFFSET):
    """Two "stations" of one cloud, as in ``benchmarks/icp_lonestar.py``.

    The cloud is centred; the target is its voxel centroids, the source the voxel centroids of the
    cloud moved by ``offset.inverse()`` (independent voxel grids, so no point has an exact
    partner). Registering the source to the target must give ``offset``.
    """
    P = np.asarray(points, float)
    P = P - P.mean(axis=0)
    return voxel_downsample(offset.inverse().apply(P), voxel), voxel_downsample(P, voxel)


def lone_star_stations(voxel=0.2, offset=ICP_OFFSET):
    """The stations of :func:`stations_from_cloud` from the real scan ``lidar/lone-star.laz``.

    The file declares EPSG:4326 (degrees) for projected coordinates, so the unit is given
    (``unit="metre"``). Raises :class:`photolib.datasets.DataUnavailableError` without the data.
    """
    cloud = read_lidar_data("lone-star.laz", unit="metre")
    return stations_from_cloud(cloud.xyz, voxel, offset)


def _room(n, g):
    k = n // 4
    floor = np.column_stack([g.uniform(0, 10, k), g.uniform(0, 8, k), np.zeros(k)])
    floor[:, 2] = 0.1 * np.sin(floor[:, 0]) * np.cos(0.7 * floor[:, 1])
    wall1 = np.column_stack([np.zeros(k), g.uniform(0, 8, k), g.uniform(0, 4, k)])
    wall2 = np.column_stack([g.uniform(0, 10, k), np.zeros(k), g.uniform(0, 4, k)])
    box = np.column_stack([g.uniform(4, 6, k), g.uniform(3, 5, k), g.uniform(0, 1.5, k)])
    box[: k // 2, 2] = 1.5                                     # the box's lid and one side
    box[k // 2:, 0] = 4.0
    return np.vstack([floor, wall1, wall2, box])


def synthetic_stations(n=6000, seed=2, offset=ICP_OFFSET):
    """Two independent samplings of a synthetic room corner (wavy floor, two walls, a box), the
    second moved by ``offset.inverse()``: (source, target), no data needed."""
    target = _room(n, np.random.default_rng(seed))
    source = offset.inverse().apply(_room(n, np.random.default_rng(seed + 1)))
    return source, target


def _nn_distances(points, tree):
    return tree.query(points)[0]


def icp_before_after(source, target, offset=None, label="", slab=0.5, max_plot=8000, **settings):
    """Figs. 9.22/9.23: two stations before and after ICP, coloured by station.

    Plan views and a vertical section (a slab ``slab`` thick across Y at the target's median Y)
    before (as scanned) and after (source moved by the ICP transform), and the histogram of the
    distances from each source point to its nearest target point before and after. ICP:
    :func:`photolib.registration.icp` with ``ICP_SETTINGS`` (those of
    ``benchmarks/icp_lonestar.py``) updated by ``settings``.

    Returns
    -------
    (Figure, dict)
        ``iterations``, ``converged``, medians of the distances before/after (mm, rounded to
        1 mm) and, with a known ``offset``, ``rotation_error_deg``/``translation_error_mm``
        (unrounded: round them for printing).
    """
    from scipy.spatial import cKDTree
    src, tgt = np.asarray(source, float), np.asarray(target, float)
    res = icp(src, tgt, **{**ICP_SETTINGS, **settings})
    moved = res.transform.apply(src)
    tree = cKDTree(tgt)
    before, after = _nn_distances(src, tree), _nn_distances(moved, tree)
    step_s, step_t = max(1, len(src) // max_plot), max(1, len(tgt) // max_plot)
    y0 = float(np.median(tgt[:, 1]))
    in_t = np.abs(tgt[:, 1] - y0) < slab / 2

    fig = plt.figure(figsize=(15, 9.5), layout="constrained")
    grid = fig.add_gridspec(2, 3, width_ratios=[1, 1.25, 1])
    for row, (S, when) in enumerate(((src, "before (as scanned)"), (moved, "after ICP"))):
        ax = fig.add_subplot(grid[row, 0])
        ax.scatter(tgt[::step_t, 0], tgt[::step_t, 1], s=0.2, color="C0", alpha=0.5, rasterized=True)
        ax.scatter(S[::step_s, 0], S[::step_s, 1], s=0.2, color="C3", alpha=0.5, rasterized=True)
        ax.axhspan(y0 - slab / 2, y0 + slab / 2, color="k", alpha=0.15)
        ax.set(aspect="equal", xlabel="X, m", ylabel="Y, m", title=f"{label}plan, {when}")
        if row == 0:
            _legend(ax, [("C0", f"station 1 (target, {len(tgt)} points)"),
                         ("C3", f"station 2 (source, {len(src)} points)")], loc="best")
        ax = fig.add_subplot(grid[row, 1])
        in_s = np.abs(S[:, 1] - y0) < slab / 2
        ax.scatter(tgt[in_t, 0], tgt[in_t, 2], s=1.0, color="C0", rasterized=True)
        ax.scatter(S[in_s, 0], S[in_s, 2], s=1.0, color="C3", rasterized=True)
        ax.set(aspect="equal", xlabel="X, m", ylabel="Z, m",
               title=f"section Y = {y0:.1f} ± {slab / 2:g} m (shaded in the plan), {when}")
    ax = fig.add_subplot(grid[:, 2])
    lo = max(min(before.min(), after.min()), 1e-4)
    bins = np.geomspace(lo, max(before.max(), after.max()), 60)
    ax.hist(before, bins=bins, color="0.5", alpha=0.7, label=f"before: median {1000 * np.median(before):.0f} mm")
    ax.hist(after, bins=bins, color="C2", alpha=0.7, label=f"after: median {1000 * np.median(after):.0f} mm")
    ax.set(xscale="log", xlabel="distance to the nearest target point, m", ylabel="source points",
           title=f"Residual distances ({res.method}, {res.iterations} iterations)")
    ax.legend(fontsize=8, loc="upper left")
    numbers = {"iterations": int(res.iterations), "converged": bool(res.converged),
               "median_before_mm": round(1000 * float(np.median(before))),
               "median_after_mm": round(1000 * float(np.median(after)))}
    if offset is not None:
        err = offset.inverse().compose(res.transform)
        numbers["rotation_error_deg"] = float(np.rad2deg(err.rotation_angle))
        numbers["translation_error_mm"] = 1000 * float(np.linalg.norm(err.shift))
        fig.suptitle(f"{label}known offset {np.rad2deg(offset.rotation_angle):.2f}° / "
                     f"{1000 * np.linalg.norm(offset.shift):.0f} mm; ICP error "
                     f"{numbers['rotation_error_deg']:.4f}° / {numbers['translation_error_mm']:.1f} mm")
    return _done(fig), numbers


# --------------------------------------------------------------------------------------------- §9.11
def synthetic_building(seed=0):
    """A synthetic tile: sloping ground (class 2) and a gable-roofed building (class 6), metres."""
    g = np.random.default_rng(seed)
    ground = g.uniform(0, 60, (3000, 2))
    ground = ground[~((np.abs(ground[:, 0] - 30) < 12) & (np.abs(ground[:, 1] - 30) < 8))]
    zg = 100 + 0.02 * ground[:, 0]
    roof = g.uniform([18, 22], [42, 38], (2500, 2))
    zr = 100.6 + 8 - 0.5 * np.abs(roof[:, 1] - 30)
    xyz = np.vstack([np.column_stack([ground, zg]), np.column_stack([roof, zr])])
    xyz += g.normal(0, 0.03, xyz.shape) * [0, 0, 1]
    cls = np.r_[np.full(len(ground), 2), np.full(len(roof), 6)]
    return xyz, cls


def roof_segments(xyz, classification, building_class=6, **settings):
    """Fig. 9.41: RANSAC planes of a cloud, the roof rule, against the file's building class.

    :func:`photolib.segmentation.detect_shapes` (RANSAC planes: threshold 0.15 m, point normal
    within 20° of the plane's, ≥ 50 points, ≤ 40 planes, seed 0); the ground is the lowest plane
    of ≥ 200 points; a roof is a plane sloping less than 60° whose median height is ≥ 2.5 m above
    the ground plane's — the rule of ``benchmarks/ground_filter_lidar.py`` (``ROOF_SETTINGS``,
    updated by ``settings``; lengths in the cloud's unit, metres for these values).

    Returns
    -------
    (Figure, dict)
        ``points``, ``planes``, ``roofs``, ``recall_pct``/``precision_pct`` of the roof points
        against the class (0.1 %).
    """
    s = {**ROOF_SETTINGS, **settings}
    P = np.asarray(xyz, float)
    building = np.asarray(classification) == building_class
    segs = segmentation.detect_shapes(P, "plane", s["threshold"], min_inliers=s["min_inliers"],
                                      max_shapes=s["max_shapes"], angle_threshold=np.radians(s["angle_deg"]),
                                      rng=0)
    med = np.array([np.median(P[g.indices, 2]) for g in segs])
    size = np.array([len(g.indices) for g in segs])
    z_ground = med[size >= s["ground_min"]].min() if np.any(size >= s["ground_min"]) else -np.inf
    label = np.full(len(P), -1)
    roof = np.zeros(len(P), bool)
    n_roofs = 0
    for k, (g, m) in enumerate(zip(segs, med)):
        label[g.indices] = k
        if m >= z_ground + s["above_ground"] and abs(g.model.normal[2]) >= np.cos(np.radians(s["max_slope_deg"])):
            roof[g.indices] = True
            n_roofs += 1
    recall = 100 * roof[building].mean() if building.any() else float("nan")
    precision = 100 * building[roof].mean() if roof.any() else float("nan")
    x0, y0 = P[:, 0].min(), P[:, 1].min()
    X, Y = P[:, 0] - x0, P[:, 1] - y0

    fig, axes = plt.subplots(1, 3, figsize=(16, 5.2), sharex=True, sharey=True)
    ax = axes[0]
    ax.scatter(X[label < 0], Y[label < 0], s=1, color="0.8", rasterized=True)
    cmap = plt.get_cmap("tab10")
    items = []
    for k in range(len(segs)):
        on = label == k
        ax.scatter(X[on], Y[on], s=1, color=cmap(k % 10), rasterized=True)
        items.append((cmap(k % 10), f"{'roof' if roof[on].all() else 'plane'} {k + 1}: {int(on.sum())} points"))
    items.append(("0.8", f"in no plane: {int((label < 0).sum())}"))
    ax.set(aspect="equal", xlabel="X − X_min, m", ylabel="Y − Y_min, m",
           title=f"RANSAC planes ({len(segs)}), in the order found")
    _legend(ax, items, loc="upper left")
    ax = axes[1]
    ax.scatter(X[~building], Y[~building], s=1, color="0.7", rasterized=True)
    ax.scatter(X[building], Y[building], s=1, color="C3", rasterized=True)
    ax.set(aspect="equal", xlabel="X − X_min, m", title="The file's classification")
    _legend(ax, [("0.7", f"other classes: {int((~building).sum())}"),
                 ("C3", f"class {building_class} (building): {int(building.sum())}")], loc="upper left")
    ax = axes[2]
    kinds = np.where(roof & building, 0, np.where(building, 1, np.where(roof, 2, 3)))
    names = ["roof plane and class 6", "class 6 only (missed)", "roof plane only (false)", "neither"]
    colours = ["C2", "C3", "C1", "0.85"]
    for k in (3, 0, 1, 2):
        on = kinds == k
        ax.scatter(X[on], Y[on], s=1 if k in (0, 3) else 4, color=colours[k], rasterized=True)
    ax.set(aspect="equal", xlabel="X − X_min, m",
           title=f"{n_roofs} roof planes vs class {building_class}: recall {recall:.1f} %, precision {precision:.1f} %")
    _legend(ax, [(colours[k], f"{names[k]}: {int(np.sum(kinds == k))}") for k in range(4)], loc="upper left")
    fig.tight_layout()
    numbers = {"points": int(len(P)), "planes": len(segs), "roofs": n_roofs,
               "recall_pct": round(float(recall), 1), "precision_pct": round(float(precision), 1)}
    return _done(fig), numbers


def synthetic_classified_cloud(seed=0):
    """A synthetic airborne tile in metres: rolling ground (class 2), two buildings and trees (class 1)."""
    g = np.random.default_rng(seed)
    xy = g.uniform(0, 80, (12000, 2))
    ground = 50 + 3 * np.sin(xy[:, 0] / 15) + 0.05 * xy[:, 1]
    z = ground.copy()
    cls = np.full(len(xy), 2)
    for cx, cy, w, h in ((25, 30, 8, 7.0), (58, 55, 10, 5.0)):
        on = (np.abs(xy[:, 0] - cx) < w) & (np.abs(xy[:, 1] - cy) < w * 0.7)
        z[on] += h
        cls[on] = 1
    tree = (np.hypot(xy[:, 0] - 60, xy[:, 1] - 15) < 6) & (g.random(len(xy)) < 0.7)
    z[tree] += g.uniform(2, 9, tree.sum())
    cls[tree] = 1
    z += g.normal(0, 0.02, len(z))
    return PointCloud(np.column_stack([xy, z]), classification=cls)


def _unique_lowest(xy, z):
    """One height per X, Y (the lowest): a DTM holds one Z per position (Chapter 6's 2.5D model)."""
    keys, inverse = np.unique(xy, axis=0, return_inverse=True)
    low = np.full(len(keys), np.inf)
    np.minimum.at(low, inverse.ravel(), z)
    return keys, low


def _tin_grid(xyz, x, y):
    keys, low = _unique_lowest(xyz[:, :2], xyz[:, 2])
    return dtm.grid_from_tin(dtm.delaunay_tin(keys, low), x, y)


def _hillshade(Z, cell):
    from scipy import ndimage
    valid = np.isfinite(Z)
    filled = Z[tuple(ndimage.distance_transform_edt(~valid, return_distances=False, return_indices=True))]
    shade = LightSource(azdeg=315, altdeg=45).hillshade(filled, vert_exag=2.0, dx=cell, dy=cell)
    return np.where(valid, shade, np.nan)


def dtm_from_classified(cloud: PointCloud, name="", ground_class=2, **settings):
    """Fig. 9.43: a DTM from the ground filter beside the DTM of the file's ground class.

    :func:`photolib.segmentation.classify_ground` runs in the cloud's own unit with the
    parameters of ``benchmarks/ground_filter_lidar.py`` given in metres (``GROUND_METRES``,
    updated by ``settings``) and converted by the cloud's unit factors (``unit_factor``,
    ``vertical_unit_factor``; none when the cloud is already in metres). Both DTMs are the TIN
    (:func:`photolib.dtm.delaunay_tin`) of their ground points gridded at the filter's cell
    centres (:func:`photolib.dtm.grid_from_tin`); they are shown as hillshades in metres with
    their difference.

    Returns
    -------
    (Figure, dict)
        ``unit`` (the file's), ``type_I_pct``, ``type_II_pct``, ``total_pct`` (0.1 %), the DTM
        difference in metres: ``median_abs_m``, ``p95_abs_m`` (0.01 m) and ``cells``.
    """
    s = {**GROUND_METRES, **settings}
    h = 1.0 if cloud.in_metres else cloud.unit_factor                # metres per unit of X, Y
    v = 1.0 if cloud.in_metres else cloud.vertical_unit_factor       # metres per unit of Z
    P = cloud.xyz
    res = segmentation.classify_ground(P, s["cell_size"] / h, s["max_window"] / h, slope=GROUND_SLOPE * h / v,
                                       dh0=s["dh0"] / v, dh_max=s["dh_max"] / v, band=s["band"] / v)
    truth = cloud.classification == ground_class
    t1, t2 = 100 * np.mean(~res.ground[truth]), 100 * np.mean(res.ground[~truth])
    total = 100 * np.mean(res.ground != truth)
    grid = res.grid
    ny, nx = grid.shape
    x = grid.x0 + (np.arange(nx) + 0.5) * grid.dx
    y = grid.y0 - (np.arange(ny) + 0.5) * grid.pixel_size[1]
    ours = _tin_grid(P[res.ground], x, y) * v
    ref = _tin_grid(P[truth], x, y) * v
    diff = ours - ref
    ok = np.isfinite(diff)
    cell_m = grid.dx * h
    ext = (0, nx * cell_m, 0, ny * cell_m)
    unit = "metre" if cloud.in_metres and cloud.source_unit == "metre" else cloud.source_unit

    fig, axes = plt.subplots(1, 3, figsize=(16, 5.6), layout="constrained")
    lo, hi = np.nanpercentile(np.r_[ours[ok], ref[ok]], [1, 99])
    for ax, Z, title in ((axes[0], ours, f"DTM of the filter's ground ({100 * res.ground.mean():.1f} % of points)"),
                         (axes[1], ref, f"DTM of class {ground_class} ({100 * truth.mean():.1f} % of points)")):
        ax.imshow(_hillshade(Z, cell_m), cmap="gray", extent=ext, origin="upper")
        im = ax.imshow(Z, cmap="terrain", alpha=0.45, extent=ext, origin="upper", vmin=lo, vmax=hi)
        ax.set(xlabel="X − X_min, m", ylabel="Y − Y_min, m", title=title)
    fig.colorbar(im, ax=axes[:2].tolist(), shrink=0.8, label="height, m")
    ax = axes[2]
    lim = max(0.3, float(np.nanpercentile(np.abs(diff), 99))) if ok.any() else 0.3
    im = ax.imshow(diff, cmap="RdBu_r", vmin=-lim, vmax=lim, extent=ext, origin="upper")
    wrong = res.ground != truth
    px = (P[wrong, 0] - grid.x0) * h
    py = (P[wrong, 1] - (grid.y0 - ny * grid.pixel_size[1])) * h
    ax.scatter(px, py, s=0.5, color="k", alpha=0.4, rasterized=True)
    ax.set(xlabel="X − X_min, m", title=f"filter DTM − class-{ground_class} DTM")
    _legend(ax, [("k", f"points classified differently ({total:.1f} %)")], loc="lower left")
    fig.colorbar(im, ax=ax, shrink=0.8, label="ΔZ, m")
    factor = "" if cloud.in_metres else f" (1 unit = {h:.7f} m, from the CRS)"
    fig.suptitle(f"{name}unit {unit}{factor}; filter run in the file's unit: cell {s['cell_size'] / h:.2f}, "
                 f"window ≤ {s['max_window'] / h:.1f}, band {s['band'] / v:.2f}; type I {t1:.1f} %, "
                 f"type II {t2:.1f} %, total {total:.1f} %")
    numbers = {"unit": unit, "type_I_pct": round(float(t1), 1), "type_II_pct": round(float(t2), 1),
               "total_pct": round(float(total), 1), "cells": int(ok.sum()),
               "median_abs_m": round(float(np.median(np.abs(diff[ok]))), 2) if ok.any() else float("nan"),
               "p95_abs_m": round(float(np.percentile(np.abs(diff[ok]), 95)), 2) if ok.any() else float("nan")}
    return _done(fig), numbers
