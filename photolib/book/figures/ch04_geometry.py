"""Figures for Chapter 4, §4.1–§4.4 (projective transformations), drawn from library calls.

The book has no figures in Chapter 4; these illustrate its statements on synthetic data.

* :func:`synthetic_camera`, :func:`synthetic_pair` — the scenes the notebook and the figures share
  (a near-vertical camera and a pair modelled on the orientation of the §4.4 example).
* :func:`dlt_flattening` — §4.2/§4.3: singular values and condition number of the resection
  equations (4.2.1), raw and with Hartley's normalisation, and the error of the recovered
  projection centre as the control points flatten towards a plane.
* :func:`epipolar_geometry` — §4.4: both images with corresponding points, epipolar lines
  l₂ = F r₁, l₁ = Fᵀ r₂ (layout x₂ᵀFx₁ = 0) and the epipoles (null vectors of F and Fᵀ).
* :func:`essential_solutions` — the four (rotation, base) pairs of an essential matrix
  (:func:`photolib.projective.essential_candidates`, in their canonical order) and the cheirality
  test that keeps one.
* :func:`ransac_matches` — RANSAC for F on matches with gross errors: inliers, outliers and the
  Sampson distances.
* :func:`homography_rectification` — the plane-to-plane projective transformation (8 parameters)
  as the tool of rectification: an oblique image of a facade and its rectification, linear vs
  least squares.

Every figure function returns the matplotlib Figure (closed, so that a notebook shows it once).
"""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np

from ... import projective
from ...camera import ExteriorOrientation, InteriorOrientation
from ...errors import DegenerateGeometryError
from ...rotation import rot_y
from ...single_image import project
from ...synthetic import stereo_pair


def _done(fig):
    plt.close(fig)
    return fig


# --- shared synthetic scenes ------------------------------------------------------------------------
def synthetic_camera(n=20, relief=150.0, seed=0):
    """A near-vertical camera (f = 100 mm, H ≈ 1000 m, κ-α-ω angles of a few degrees) and n
    control points spread over 1000 × 1000 m with heights ±``relief``. Returns io, eo, XYZ, xy."""
    rng = np.random.default_rng(seed)
    io = InteriorOrientation(100.0, 0.02, -0.01)
    eo = ExteriorOrientation.from_degrees(1000.0, 1000.0, 1000.0, 2.0, 5.0, 7.0)
    XYZ = np.column_stack([rng.uniform(550, 1450, n), rng.uniform(550, 1450, n), rng.uniform(-1, 1, n) * relief])
    return io, eo, XYZ, project(XYZ, eo, io)


def synthetic_pair(n=40, seed=1, sigma=0.0):
    """A stereo pair with the exterior orientation of the §4.4 example (f = 100 mm, B = 500 m,
    H = 1000 m; ω, α, κ = 1°, 3°, 2° and −2°, −1°, 5°), n ground points with ±50 m relief in the
    overlap and image noise ``sigma`` (mm), from :func:`photolib.synthetic.stereo_pair`.
    Returns io, eo1, eo2, XYZ, xy1, xy2."""
    pair = stereo_pair(n, seed=seed, centres=((1000.0, 1000.0, 1000.0), (1500.0, 1000.0, 1000.0)),
                       angles=np.radians([[1.0, 3.0, 2.0], [-2.0, -1.0, 5.0]]),
                       box=((950.0, 1550.0), (450.0, 1550.0)), relief=50.0, sigma=sigma)
    return pair.io, pair.eo1, pair.eo2, pair.points, pair.xy1, pair.xy2


# --- §4.2 coplanar control --------------------------------------------------------------------------
def flattening_study(reliefs, n=20, sigma=0.01, trials=20, seed=0):
    """Numbers behind :func:`dlt_flattening`.

    For each relief amplitude (m) of the control points: the singular values of the design
    matrix of (4.2.1) with unit-length columns (raw coordinates), the condition number of the
    Hartley-normalised homogeneous system, and the r.m.s. error of the projection centre from
    ``trials`` noisy resections (σ = ``sigma`` mm, :func:`photolib.projective.dlt_resection`).
    """
    rng = np.random.default_rng(seed)
    rows = []
    for relief in reliefs:
        io, eo, XYZ, xy = synthetic_camera(n, relief, seed)
        B, _ = projective.dlt_design(XYZ, xy)
        s_raw = np.linalg.svd(B / np.linalg.norm(B, axis=0), compute_uv=False)
        T, U = projective.normalizing_transform(xy), projective.normalizing_transform(XYZ)
        Xn = np.column_stack([XYZ, np.ones(n)]) @ U.T
        xn = np.column_stack([xy, np.ones(n)]) @ T.T
        A = np.zeros((2 * n, 12))
        A[0::2, 0:4], A[0::2, 8:12] = Xn, -xn[:, :1] * Xn
        A[1::2, 4:8], A[1::2, 8:12] = Xn, -xn[:, 1:2] * Xn
        s_norm = np.linalg.svd(A, compute_uv=False)
        errors = []
        for _ in range(trials):
            noisy = xy + rng.normal(0, sigma, xy.shape)
            try:
                errors.append(np.linalg.norm(projective.dlt_resection(XYZ, noisy).orientation().center - eo.center))
            except DegenerateGeometryError:
                errors.append(np.nan)
        rows.append((relief, s_raw, s_norm, s_norm[0] / s_norm[-2], float(np.sqrt(np.nanmean(np.square(errors))))))
    return rows


def dlt_flattening(reliefs=None, n=20, sigma=0.01, trials=20, seed=0):
    """§4.2: what coplanar control does to the DLT (see :func:`flattening_study`)."""
    reliefs = np.logspace(2.3, -2, 14) if reliefs is None else np.asarray(reliefs, float)
    rows = flattening_study(reliefs, n, sigma, trials, seed)
    rel = np.array([r[0] for r in rows])
    cond = np.array([r[3] for r in rows])
    err = np.array([r[4] for r in rows])
    fig, (a1, a2, a3) = plt.subplots(1, 3, figsize=(13, 3.8))
    s_norm = np.array([r[2] for r in rows])
    for k in range(11):
        a1.loglog(rel, s_norm[:, k], color="C3" if k >= 8 else "0.55", lw=1.4 if k >= 8 else 0.8)
    a1.set_title("singular values σ₁…σ₁₁ of the normalised\n(4.2.1) (the 3 smallest in red)")
    a2.loglog(rel, cond, "o-", ms=3)
    a2.set_title("condition number σ₁/σ₁₁ of the\nnormalised system")
    a3.loglog(rel, err, "o-", ms=3, color="C1")
    a3.set_title(f"r.m.s. error of the centre (4.2.5), m\nσ = {sigma * 1000:.0f} µm, {trials} trials")
    for ax in (a1, a2, a3):
        ax.set_xlabel("relief of the control points ±, m")
        ax.invert_xaxis()
        ax.grid(True, which="major", lw=0.4)
    fig.tight_layout()
    return _done(fig)


# --- §4.4 epipolar geometry -------------------------------------------------------------------------
def epipoles(F):
    """Epipoles e₁ (F e₁ = 0) and e₂ (Fᵀ e₂ = 0) in image coordinates, layout x₂ᵀFx₁ = 0."""
    _, _, Vt = np.linalg.svd(F)
    e1 = Vt[-1]
    _, _, Vt2 = np.linalg.svd(F.T)
    e2 = Vt2[-1]
    return e1[:2] / e1[2], e2[:2] / e2[2]


def _draw_lines(ax, lines, half, color):
    xs = np.array([-half, half])
    for a, b, c in lines:
        if abs(b) > abs(a):
            ax.plot(xs, -(a * xs + c) / b, color=color, lw=0.7)
        else:
            ys = xs
            ax.plot(-(b * ys + c) / a, ys, color=color, lw=0.7)


def epipolar_geometry(F, xy1, xy2, half=115.0, n_lines=8):
    """Both images: the points, the epipolar lines of the first ``n_lines`` points, the epipoles.

    ``F`` in the layout x₂ᵀFx₁ = 0 (l₂ = F r₁, the book's line formula and numeric F).
    """
    e1, e2 = epipoles(F)
    l2 = projective.epipolar_lines(F, xy1[:n_lines], image=2)
    l1 = projective.epipolar_lines(F, xy2[:n_lines], image=1)
    fig, axes = plt.subplots(1, 2, figsize=(11, 5.2))
    for ax, xy, lines, e, name in ((axes[0], xy1, l1, e1, "image 1: l₁ = Fᵀr₂"),
                                   (axes[1], xy2, l2, e2, "image 2: l₂ = F r₁")):
        ax.add_patch(plt.Rectangle((-half, -half), 2 * half, 2 * half, fill=False, color="0.3"))
        _draw_lines(ax, lines, half, "C0")
        ax.plot(xy[:, 0], xy[:, 1], ".", color="0.5", ms=4)
        ax.plot(xy[:n_lines, 0], xy[:n_lines, 1], "o", color="C3", ms=4)
        if np.all(np.abs(e) < half):
            ax.plot(*e, "k*", ms=12)
            ax.annotate("epipole", e, xytext=(6, 6), textcoords="offset points")
        name += f"\nepipole at ({e[0]:.0f}, {e[1]:.0f}) mm"
        ax.set_xlim(-half, half)
        ax.set_ylim(-half, half)
        ax.set_aspect("equal")
        ax.set_xlabel("x, mm")
        ax.set_ylabel("y, mm")
        ax.set_title(name)
    fig.suptitle("Epipolar lines meet at the epipole, the image of the other projection centre")
    fig.tight_layout(rect=(0, 0, 1, 0.95))
    return _done(fig)


def essential_solutions(E, xy1, xy2, io, n_points=12):
    """The four decompositions of E in a vertical section (X–Z of the model frame).

    Camera 1 at the origin, camera 2 at the unit base b; the viewing directions (−z axes of the
    cameras) as arrows; the points N₁r₁ (model units). Only one candidate puts them in front of both.
    """
    cands = projective.essential_candidates(E, xy1[:n_points], xy2[:n_points], io)
    D = projective.D_REFLECTION
    r1 = projective.normalized_image_coordinates(xy1[:n_points], io) @ D
    best = max(cands, key=lambda c: c.n_front)
    Pb = best.N1[:, None] * r1
    lim = max(2.0, 1.15 * np.abs(np.vstack([Pb[:, [0, 2]], best.base[[0, 2]][None]])).max())
    fig, axes = plt.subplots(1, 4, figsize=(14, 4.0), sharey=True)
    for ax, cand, k in zip(axes, cands, range(1, 5)):
        b, A2 = cand.base, cand.A2
        P = np.clip((cand.N1[:, None] * r1)[:, [0, 2]], -lim, lim)    # points beyond the box on its edge
        good = (cand.N1 > 0) & (cand.N2 > 0)
        ax.plot(P[good, 0], P[good, 1], "o", color="C2", ms=4, label="in front of both")
        ax.plot(P[~good, 0], P[~good, 1], "x", color="C3", ms=5, label="behind a camera")
        for S, A, name in ((np.zeros(3), np.eye(3), "S₁"), (b, A2, "S₂")):
            view = A @ np.array([0.0, 0.0, -0.25 * lim])
            ax.plot(S[0], S[2], "ks", ms=6)
            ax.annotate("", xy=(S[0] + view[0], S[2] + view[2]), xytext=(S[0], S[2]),
                        arrowprops=dict(arrowstyle="->", color="k"))
            ax.annotate(name, (S[0], S[2]), xytext=(4, 4), textcoords="offset points")
        ax.set_title(f"candidate {k}: {cand.n_front}/{n_points} in front", fontsize=10)
        ax.set_xlabel("X (model, |b| = 1)")
        ax.set_xlim(-lim, lim)
        ax.set_ylim(-lim, lim)
        ax.set_aspect("equal")
    axes[0].set_ylabel("Z (model)")
    axes[0].legend(fontsize=7, loc="upper left")
    fig.suptitle("The four decompositions of E (arrows: viewing directions); the cheirality test keeps the one "
                 "with every point in front")
    fig.tight_layout(rect=(0, 0, 1, 0.93))
    return _done(fig)


def ransac_matches(xy1, xy2, result, outliers, threshold):
    """RANSAC for F: image-2 points with their distance to the epipolar line, and Sampson distances."""
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(11, 4.4))
    inl = result.inliers
    lines = projective.epipolar_lines(result.model, xy1, image=2)          # unit normals (a, b)
    off = np.einsum("ni,ni->n", lines, np.column_stack([xy2, np.ones(len(xy2))]))
    foot = xy2 - off[:, None] * lines[:, :2]
    for k in np.flatnonzero(~inl):
        a1.plot([xy2[k, 0], foot[k, 0]], [xy2[k, 1], foot[k, 1]], color="C3", lw=0.8)
    a1.plot(xy2[inl, 0], xy2[inl, 1], "o", color="C2", ms=3, label=f"inliers ({inl.sum()})")
    a1.plot(xy2[~inl, 0], xy2[~inl, 1], "x", color="C3", ms=5, label=f"rejected ({(~inl).sum()})")
    a1.set_aspect("equal")
    a1.set_xlabel("x₂, mm")
    a1.set_ylabel("y₂, mm")
    a1.set_title("image 2: rejected points and their\ndistance to the epipolar line l₂ = F r₁")
    a1.legend(fontsize=8, loc="lower left")
    dist = projective.sampson_distance(result.model, xy1, xy2)
    truth = np.ones(len(xy1), bool)
    truth[outliers] = False
    bins = np.logspace(np.log10(max(dist.min(), 1e-5)), np.log10(dist.max() * 1.1), 40)
    a2.hist(dist[truth], bins=bins, color="C2", alpha=0.7, label="true matches")
    a2.hist(dist[~truth], bins=bins, color="C3", alpha=0.7, label="gross errors")
    a2.axvline(threshold, color="k", ls="--", lw=0.8, label=f"threshold {threshold} mm")
    a2.set_xscale("log")
    a2.set_xlabel("Sampson distance to the final F, mm")
    a2.set_ylabel("number of matches")
    a2.legend(fontsize=8)
    a2.set_title(f"RANSAC: {result.iterations} samples of 8 points")
    fig.tight_layout()
    return _done(fig)


# --- plane-to-plane homography ------------------------------------------------------------------------
def facade_scene(seed=2, sigma=0.02):
    """An oblique image of a 40 × 24 m facade (plane Y = 0): a grid of lines and 12 control points.

    Returns a dict with the grid lines on the facade (X, Z, m) and in the image (x, y, mm), the
    control points on both, and the noisy measured image coordinates (σ = ``sigma`` mm).
    """
    rng = np.random.default_rng(seed)
    io = InteriorOrientation(50.0)
    # a terrestrial camera 45 m in front of the facade, looking at it obliquely (camera −z → +Y)
    eo = ExteriorOrientation.from_degrees(-12.0, -45.0, 6.0, 90.0 - 8.0, 0.0, 0.0, order="wak")
    eo = ExteriorOrientation.from_matrix(eo.center, eo.matrix @ rot_y(np.radians(-25.0)), "wak")
    lines = []
    for X in np.linspace(0, 40, 11):
        lines.append(np.column_stack([np.full(30, X), np.linspace(0, 24, 30)]))
    for Z in np.linspace(0, 24, 7):
        lines.append(np.column_stack([np.linspace(0, 40, 30), np.full(30, Z)]))
    to3 = lambda XZ: np.column_stack([XZ[:, 0], np.zeros(len(XZ)), XZ[:, 1]])  # noqa: E731
    img_lines = [project(to3(L), eo, io) for L in lines]
    ctrl = np.column_stack([rng.uniform(2, 38, 12), rng.uniform(2, 22, 12)])
    xy = project(to3(ctrl), eo, io)
    return {"io": io, "eo": eo, "lines": lines, "image_lines": img_lines, "control": ctrl,
            "image_control": xy, "measured": xy + rng.normal(0, sigma, xy.shape), "sigma": sigma}


def homography_rectification(scene=None):
    """Rectification of the facade by a homography: the image, the rectified grid from 4 points
    (linear, exact fit) and from all 12 points by least squares, with the control residuals."""
    sc = facade_scene() if scene is None else scene
    meas, ctrl = sc["measured"], sc["control"]
    H4 = projective.homography_dlt(meas[:4], ctrl[:4])
    lsq = projective.homography_lsq(meas, ctrl)
    fig, axes = plt.subplots(1, 3, figsize=(14, 4.2))
    for L in sc["image_lines"]:
        axes[0].plot(L[:, 0], L[:, 1], color="0.4", lw=0.7)
    axes[0].plot(meas[:, 0], meas[:, 1], "o", color="C3", ms=4)
    axes[0].plot(meas[:4, 0], meas[:4, 1], "s", mfc="none", color="C0", ms=8)
    axes[0].set_title("oblique image of the facade, mm\n(squares: the 4 points of the exact solution)")
    for ax, H, name in ((axes[1], H4, "4 points, linear (exact fit)"), (axes[2], lsq.H, "12 points, least squares")):
        for L, Limg in zip(sc["lines"], sc["image_lines"]):
            ax.plot(L[:, 0], L[:, 1], color="0.8", lw=2.5)
            R = projective.apply_homography(H, Limg)
            ax.plot(R[:, 0], R[:, 1], color="C0", lw=0.8)
        res = projective.apply_homography(H, meas) - ctrl
        check = slice(4, None)
        rms = np.sqrt(np.mean(np.sum(res[check] ** 2, axis=1)))
        ax.quiver(ctrl[:, 0], ctrl[:, 1], res[:, 0], res[:, 1], angles="xy", scale_units="xy", scale=0.02,
                  color="C3", width=0.004)
        ax.set_title(f"rectified: {name}\nr.m.s. at points 5–12: {rms * 100:.1f} cm (arrows ×50)")
        ax.set_xlabel("X, m")
        ax.set_ylabel("Z, m")
    for ax in axes:
        ax.set_aspect("equal")
    fig.tight_layout()
    return _done(fig)
