"""Figures for Chapter 2, §2.1–§2.13 (theory of a pair of frame images), redrawn from library calls.

* :func:`stereo_acuity` — §2.1, (2.1.1)/(2.1.3): convergence angle and depth resolution of the
  eyes versus distance, with the radius of stereo vision.
* :func:`pair_geometry` — Figs 2.12/2.13: two cameras, the base, the rays to a point, the
  epipolar (basal) plane and the epipolar lines on both images.
* :func:`parallax_field` — Figs 2.10/2.18: x-parallaxes of a synthetic normal-case pair, their
  dependence on the height (2.5.3), and the y-parallaxes left by an orientation error.
* :func:`coplanarity` — (2.7.1): base and rays in one plane (φ = 0) against skew rays (φ ≠ 0).
* :func:`standard_zones` — Fig. 2.14: the six standard zones of relative orientation on the overlap.
* :func:`model_scale` — Figs 2.16/2.17: the base length sets the model scale; the model frame
  against the object frame (2.10.4).
* :func:`accuracy_vs_height` — (2.13.3): m_X, m_Z against flying height and photo base, with
  Monte-Carlo points.

Every function returns the matplotlib Figure (closed, so that a notebook shows it once).
"""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np
from mpl_toolkits.mplot3d.art3d import Poly3DCollection

from ... import image_pair
from .. import ch02_theory
from ...camera import ExteriorOrientation, InteriorOrientation
from ...single_image import project


def _done(fig):
    plt.close(fig)
    return fig


def stereo_acuity(b_mm=65.0, gamma_min_arcsec=30.0):
    """§2.1: γ = b/L (2.1.1) and the depth step ΔL = L²Δγ/b (2.1.3) for Δγ = γ_min, against L.

    The radius of stereo vision R = b·ρ″/γ_min is where γ itself drops to γ_min (ΔL ≈ L):
    433 m with the book's ρ″ = 200 000″, 447 m with ρ″ = 206 265″.
    """
    b = b_mm / 1000.0
    L = np.logspace(-0.7, 3.2, 300)
    rho = image_pair.RHO_SECONDS
    gamma = image_pair.convergence_angle(b, L) * rho
    dL = np.abs(image_pair.depth_change(b, L, gamma_min_arcsec / rho))
    R_book = image_pair.stereo_vision_radius(b, gamma_min_arcsec, rho=2e5)
    R = image_pair.stereo_vision_radius(b, gamma_min_arcsec)
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(10, 3.8))
    ax1.loglog(L, gamma, "C0")
    ax1.axhline(gamma_min_arcsec, color="0.5", ls="--", lw=0.8)
    ax1.set_xlabel("distance L, m")
    ax1.set_ylabel("convergence angle γ, arcsec")
    ax1.set_title("(2.1.1) γ = b/L, b = %.0f mm" % b_mm)
    ax2.loglog(L, dL, "C1", label="ΔL = L²Δγ/b (2.1.3)")
    ax2.loglog(L, L, "0.6", ls=":", label="ΔL = L")
    for r, lab in ((R_book, "ρ″ = 200 000″"), (R, "ρ″ = 206 265″")):
        for ax in (ax1, ax2):
            ax.axvline(r, lw=0.8, color="C3" if r == R_book else "C2")
        ax2.annotate(f"R = {r:.0f} m\n({lab})", (r, 1e-3 if r == R_book else 1e-1), fontsize=8,
                     xytext=(-75 if r == R_book else 5, 0), textcoords="offset points")
    ax2.set_xlabel("distance L, m")
    ax2.set_ylabel("smallest perceived depth step ΔL, m")
    ax2.set_title(f"depth resolution for Δγ = {gamma_min_arcsec:.0f}″")
    ax2.legend(fontsize=8, loc="upper left")
    fig.tight_layout()
    return _done(fig)


def _image_corners(eo, f, half, k):
    """3-D corners of an image frame of half-size ``half`` drawn at distance k·f in front of S."""
    c = np.array([[-half, -half], [half, -half], [half, half], [-half, half], [-half, -half]])
    return eo.center + k * np.column_stack([c, np.full(len(c), -f)]) @ eo.matrix.T


def pair_geometry(seed=0):
    """Figs 2.12/2.13: S₁, S₂, the base B, the rays to a ground point M through its images m₁,
    m₂, the epipolar plane S₁S₂M and its traces (epipolar lines) on the two image planes."""
    rng = np.random.default_rng(seed)
    io = InteriorOrientation(100.0)
    eo1 = ExteriorOrientation(0.0, 0.0, 1000.0, *np.radians(rng.uniform(-4, 4, 3)))
    eo2 = ExteriorOrientation(600.0, 40.0, 1030.0, *np.radians(rng.uniform(-4, 4, 3)))
    M = np.array([[380.0, 180.0, 0.0]])
    k = 2.5                                                  # image planes drawn 2.5× enlarged
    fig = plt.figure(figsize=(8, 6.5))
    ax = fig.add_subplot(projection="3d")
    normal = np.cross(eo2.center - eo1.center, M[0] - eo1.center)   # normal of the epipolar plane
    for i, (eo, col) in enumerate(((eo1, "C0"), (eo2, "C1")), start=1):
        frame = _image_corners(eo, io.f, 60.0, k)
        ax.plot(*frame.T, color=col, lw=1)
        m = project(M, eo, io)[0]
        m3 = eo.center + k * np.array([m[0], m[1], -io.f]) @ eo.matrix.T
        ax.plot(*np.array([eo.center, M[0]]).T, color=col, lw=1)
        ax.scatter(*m3, color=col, s=15)
        ax.text(*m3, f"  m{i}", color=col)
        ax.text(*eo.center, f"  S{i}", color=col, fontsize=11)
        n_img = eo.matrix[:, 2]                               # normal of the image plane
        d = np.cross(normal, n_img)
        d /= np.linalg.norm(d)
        ax.plot(*np.array([m3 - 120 * d, m3 + 120 * d]).T, color=col, ls="--", lw=1.2)
    ax.plot(*np.array([eo1.center, eo2.center]).T, "k", lw=2)
    ax.text(*(eo1.center + eo2.center) / 2, "  B", fontsize=11)
    tri = np.array([eo1.center, eo2.center, M[0]])
    ax.add_collection3d(Poly3DCollection([tri], alpha=0.15, facecolor="C2"))
    ax.scatter(*M[0], color="k")
    ax.text(*M[0], "  M", fontsize=11)
    gx, gy = np.meshgrid([-150, 750], [-250, 350])
    ax.plot_surface(gx, gy, 0 * gx, alpha=0.08, color="0.5")
    ax.set_xlabel("X, m")
    ax.set_ylabel("Y, m")
    ax.set_zlabel("Z, m")
    ax.set_title("Pair geometry: base, corresponding rays, epipolar plane (green)\n"
                 "and epipolar lines (dashed) on both images")
    ax.view_init(22, -62)
    return _done(fig)


def _hill(X, Y):
    return 60.0 * np.exp(-((X - 250.0) ** 2 + (Y - 20.0) ** 2) / (2 * 130.0**2))


def parallax_field(seed=0, omega2_error_deg=0.3):
    """Figs 2.10/2.18 on a synthetic normal-case pair over a Gaussian hill.

    (a) corresponding points of both images and their x-parallax vectors p = x₁ − x₂;
    (b) p against ground height with the normal-case law p = Bf/(H − h) from (2.5.3);
    (c) y-parallaxes q = y₁ − y₂ that appear when image 2 is turned by ``omega2_error_deg``.
    """
    rng = np.random.default_rng(seed)
    f, H, B = 100.0, 1000.0, 400.0
    io = InteriorOrientation(f)
    X = rng.uniform(40, 360, 120)
    Y = rng.uniform(-300, 300, 120)
    P = np.column_stack([X, Y, _hill(X, Y)])
    eo1 = ExteriorOrientation(0.0, 0.0, H, 0.0, 0.0, 0.0)
    eo2 = ExteriorOrientation(B, 0.0, H, 0.0, 0.0, 0.0)
    xy1, xy2 = project(P, eo1, io), project(P, eo2, io)
    p, q = image_pair.parallaxes(xy1, xy2)
    fig, axes = plt.subplots(1, 3, figsize=(13, 4.3))
    ax = axes[0]
    ax.scatter(*xy1.T, s=8, c=P[:, 2], cmap="viridis", label="image 1")
    ax.scatter(*xy2.T, s=8, marker="x", color="0.5", label="image 2")
    ax.quiver(xy2[:, 0], xy2[:, 1], p, q, angles="xy", scale_units="xy", scale=1, width=0.002, color="0.6")
    ax.set_aspect("equal")
    ax.set_xlabel("x, mm")
    ax.set_ylabel("y, mm")
    ax.set_title("(a) corresponding points, p = x₁ − x₂")
    ax.legend(fontsize=8, loc="lower left")
    ax = axes[1]
    ax.scatter(P[:, 2], p, s=8, c=P[:, 2], cmap="viridis")
    h = np.linspace(0, P[:, 2].max(), 50)
    ax.plot(h, B * f / (H - h), "k", lw=1, label="p = Bf/(H − h)  (2.5.3)")
    ax.axhline(B * f / H, color="0.5", ls="--", lw=0.8, label="b = Bf/H (flat terrain)")
    ax.set_xlabel("ground height h, m")
    ax.set_ylabel("x-parallax p, mm")
    ax.set_title("(b) the x-parallax measures height")
    ax.legend(fontsize=8)
    ax = axes[2]
    eo2w = ExteriorOrientation(B, 0.0, H, np.radians(omega2_error_deg), 0.0, 0.0)
    xy2w = project(P, eo2w, io)
    _, qw = image_pair.parallaxes(xy1, xy2w)
    ax.quiver(*xy1.T, 0 * qw, qw, angles="xy", scale_units="xy", scale=0.05, width=0.003, color="C3")
    ax.set_aspect("equal")
    ax.set_xlabel("x, mm")
    ax.set_ylabel("y, mm")
    ax.set_title(f"(c) y-parallax q = y₁ − y₂, ω₂ off by {omega2_error_deg}°\n(arrows ×20)")
    fig.tight_layout()
    return _done(fig)


def coplanarity(seed=0, kappa_error_deg=3.0):
    """(2.7.1): with the correct orientation the base and both rays lie in one plane (φ = 0);
    with image 2 turned by ``kappa_error_deg`` the rays are skew and φ = B·(r₁ × r₂) ≠ 0.

    Returns a figure with the two cases side by side; the common perpendicular of the skew
    rays (their shortest gap, the spatial counterpart of the y-parallax) is drawn in red.
    """
    io = InteriorOrientation(100.0)
    eo1 = ExteriorOrientation(0.0, 0.0, 1000.0, 0.0, 0.0, 0.0)
    eo2 = ExteriorOrientation(500.0, 0.0, 1000.0, 0.0, 0.0, 0.0)
    M = np.array([[250.0, 250.0, 0.0]])
    xy1, xy2 = project(M, eo1, io), project(M, eo2, io)
    fig = plt.figure(figsize=(11, 4.8))
    B = eo2.center - eo1.center
    for j, err in enumerate((0.0, kappa_error_deg)):
        eo2w = ExteriorOrientation(*eo2.center, 0.0, 0.0, np.radians(err))
        r1 = image_pair.image_rays(xy1, eo1, io)[0]
        r2 = image_pair.image_rays(xy2, eo2w, io)[0]
        phi = float(image_pair.coplanarity(B / B[0], r1[None], r2[None])[0])
        ax = fig.add_subplot(1, 2, j + 1, projection="3d")
        # closest points of the two rays
        A_ = np.array([[r1 @ r1, -r1 @ r2], [r1 @ r2, -r2 @ r2]])
        s, t = np.linalg.solve(A_, [B @ r1, B @ r2])
        P1, P2 = eo1.center + s * r1, eo2.center + t * r2
        ax.plot(*np.array([eo1.center, P1]).T, "C0")
        ax.plot(*np.array([eo2.center, P2]).T, "C1")
        ax.plot(*np.array([eo1.center, eo2.center]).T, "k", lw=2)
        if err:
            ax.plot(*np.array([P1, P2]).T, "C3", lw=2)
        ax.add_collection3d(Poly3DCollection([np.array([eo1.center, eo2.center, P1])], alpha=0.15, facecolor="C2"))
        ax.text(*eo1.center, " S1")
        ax.text(*eo2.center, " S2")
        gap = f"\ngap {np.linalg.norm(P2 - P1):.1f} m" if err else ""
        ax.set_title(("coplanar: " if not err else f"image 2 turned by κ = {err}°: ")
                     + f"φ = B·(r₁×r₂) = {phi:.3g} mm²" + gap)
        ax.view_init(18, -70)
        ax.set_xlabel("X")
        ax.set_ylabel("Y")
        ax.set_zlabel("Z")
    fig.tight_layout()
    return _done(fig)


def standard_zones(n_per_zone=2, seed=0, b=35.0, half_y=80.0):
    """Fig. 2.14: the stereo overlap on image 1 (principal point o₁ at x = 0, the transferred
    principal point o₂′ at x = b), the six standard zones (rows top/middle/bottom × the two
    principal-point columns) and ``n_per_zone`` points per zone."""
    pts, zone = ch02_theory.standard_zones(n_per_zone, seed, half_x=b, half_y=half_y)
    fig, ax = plt.subplots(figsize=(5, 6.5))
    ax.add_patch(plt.Rectangle((-0.45 * b, -half_y * 1.05), 1.9 * b, 2.1 * half_y, fill=False, lw=1.2))
    for k, (cx, cy) in enumerate([(cx, cy) for cy in (0.8 * half_y, 0.0, -0.8 * half_y) for cx in (0.0, b)], 1):
        ax.add_patch(plt.Rectangle((cx - 0.2 * b, cy - 0.15 * half_y), 0.4 * b, 0.3 * half_y, color="C2", alpha=0.25))
        ax.text(cx + 0.22 * b, cy + 0.1 * half_y, str(k), fontsize=12)
    ax.scatter(*pts.T, c=zone, cmap="tab10", vmin=1, vmax=10, s=25, zorder=3)
    ax.plot([0, b], [0, 0], "k+", ms=12)
    ax.text(0, -8, "o₁", ha="center")
    ax.text(b, -8, "o₂′", ha="center")
    ax.set_xlim(-0.7 * b, 1.7 * b)
    ax.set_aspect("equal")
    ax.set_xlabel("x₁, mm")
    ax.set_ylabel("y₁, mm")
    ax.set_title(f"Six standard zones, {n_per_zone} points each ({6 * n_per_zone} points)")
    return _done(fig)


def model_scale(seed=0):
    """Figs 2.16/2.17. (a) One relative orientation, three base lengths B_X: the models built by
    :func:`photolib.image_pair.build_model` are similar, their size ∝ B_X (section X_M–Z_M).
    (b) Plan view of a model in its own frame and of the object after (2.10.4)."""
    xy1, xy2, io, eo1, eo2, P = ch02_theory.synthetic_pair(25, seed)
    ro = image_pair.relative_orientation(xy1, xy2, io, system="dependent")
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 4.3))
    for BX, col in ((0.5, "C0"), (1.0, "C1"), (2.0, "C2")):
        m = image_pair.build_model(xy1, xy2, ro, io, base_length=BX)
        ax1.scatter(m.points[:, 0], m.points[:, 2], s=10, color=col, label=f"B_X = {BX}")
        ax1.plot([0, m.eo2.center[0]], [0, m.eo2.center[2]], color=col, lw=2)
    ax1.set_xlabel("X_M")
    ax1.set_ylabel("Z_M")
    ax1.set_title("(a) model scale is set by B_X (S₁ at the origin)")
    ax1.legend(fontsize=8)
    m = image_pair.build_model(xy1, xy2, ro, io, base_length=1.0)
    T = image_pair.absolute_orientation(m.points, P)
    ax2.scatter(P[:, 0], P[:, 1], s=12, color="k", label="object points")
    shown = m.points * 150.0                                   # the model, enlarged to be visible
    ax2.scatter(shown[:, 0], shown[:, 1], s=12, color="C1", label="model points ×150 (own frame)")
    ax2.annotate("", T.shift[:2], (0, 0), arrowprops=dict(arrowstyle="->"))
    ax2.text(*(T.shift[:2] / 2), "  R₀", fontsize=11)
    ax2.set_aspect("equal")
    ax2.set_xlabel("X, m")
    ax2.set_ylabel("Y, m")
    ax2.set_title(f"(b) object = R₀ + t·A_M·model (2.10.4), t = {T.t:.1f}")
    ax2.legend(fontsize=8)
    fig.tight_layout()
    return _done(fig)


def accuracy_vs_height(f_mm=92.0, frame_x_mm=14592 * 3.9e-3, m_xy_mm=0.5 * 3.9e-3, m_p_mm=0.3 * 3.9e-3,
                       overlaps=(60, 70, 80), simulate=True):
    """(2.13.3) for the DMC III of the §2.13 example: m_X (≈ (H/f)m_x) and m_Z = (H/b)m_p against
    the flying height for several forward overlaps (b = l_x(100 − P)/100), with Monte-Carlo
    r.m.s. errors of :func:`photolib.book.ch02_theory.simulate_pair_accuracy` at 60 %."""
    H = np.linspace(300, 4000, 50)
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 4.2))
    for ov in overlaps:
        b = image_pair.photo_base(frame_x_mm, ov)
        # normal_case_accuracy checks H > 0 with a scalar test, so it is called per height
        mZ = [image_pair.normal_case_accuracy(h, f_mm, b, m_xy_mm, m_xy_mm, m_p_mm, approximate=True)[2] for h in H]
        ax1.plot(H, mZ, label=f"m_Z, {ov} % (b = {b:.1f} mm)")
    ax1.plot(H, H / f_mm * m_xy_mm, "k--", label="m_X ≈ m_Y ≈ (H/f)m_x")
    if simulate:
        for Hs in (1000.0, 2000.0, 3000.0):
            r = ch02_theory.simulate_pair_accuracy(seed=0, n_points=1500, H_m=Hs)
            ax1.plot(Hs, r["rms"][2], "o", color="C0", ms=5)
            ax1.plot(Hs, r["rms"][0], "s", color="k", ms=4)
    ax1.set_xlabel("flying height H, m")
    ax1.set_ylabel("r.m.s. error, m")
    ax1.set_title("DMC III (f = 92 mm): error grows ∝ H\n(markers: simulation, 60 %)")
    ax1.legend(fontsize=8)
    b = np.linspace(5, 40, 100)
    for Hh in (1000, 2000, 3000):
        ax2.plot(b, Hh / b * m_p_mm, label=f"H = {Hh} m")
    ax2.axvline(image_pair.photo_base(frame_x_mm, 60), color="0.5", ls=":", lw=1)
    ax2.set_xlabel("photo base b, mm (image scale)")
    ax2.set_ylabel("m_Z, m")
    ax2.set_title("m_Z = (H/b)m_p: a longer base helps heights")
    ax2.legend(fontsize=8)
    fig.tight_layout()
    return _done(fig)
