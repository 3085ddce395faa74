"""The book's bundle-block layouts, their counts and the §3.7 regulation checks — Chapter 3, §3.5, §3.7.

§3.5 "Построение и уравнивание маршрутной и блочной фототриангуляции по методу связок" counts
unknowns and correction equations for two small blocks whose drawings survive only partly in the
OCR: fig. 3.10 (two strips of one stereopair each, 60 % forward and 60 % side overlap, four tie
points, four XYZ control points held fixed) and fig. 3.13 (two strips of four images, control by
five XYZ points and eight GNSS projection centres, the figure printing how many images see each
point). This module rebuilds both as synthetic blocks *from footprint geometry* (vertical images
with a square footprint L × L, forward base b, strip spacing s; a point is on an image if it lies
strictly inside the footprint), so that

* the per-point image counts and the counts m, k, c, s of (3.5.20)/(3.5.21) follow from the
  geometry instead of being typed in (:func:`images_per_point`, :func:`block_counts`);
* the correction equations (3.5.2)/(3.5.3)/(3.5.17)/(3.5.18)/(3.5.19) can be *built*, densely, in
  the column order of fig. 3.11 (:func:`correction_equation_system`) and the normal matrix
  N = AᵀPA of fig. 3.12 inspected (:func:`normal_matrix_structure`);
* the blocks are adjusted by :func:`photolib.bundle.bundle_adjustment` with seeded noise
  (:meth:`BookBlock.adjust`).

§3.7 "Технология построения сетей фототриангуляции" quotes the Russian *Instruction on
photogrammetric works*; its tolerance numbers are data in ``textbook/ch03.toml`` (example
``3.7-tolerances``). :func:`evaluate_regulations` is **our helper, not the book's**: it compares
an adjustment's control and check-point discrepancies with those tolerances (3.7.5)/(3.7.6), and
:func:`free_strip_height_tolerance_um` evaluates the 3.7.2 height tolerance 15 µm·f/b.

Units: image mm, object metres, angles radians.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from .bundle import BundleResult, bundle_adjustment, bundle_correction_equations
from .camera import InteriorOrientation
from .errors import InputError
from .lsq import block_equations_dense
from .rotation import check_order, rotation_matrix
from .single_image import project_to_images
from .synthetic import CHECK, CONTROL, TIE, Observations

__all__ = ["BookBlock", "BundleSystem", "footprint_visibility", "fig_3_10_block", "fig_3_13_block",
           "images_per_point", "block_counts", "bundle_unknowns", "bundle_equations",
           "correction_equation_system", "normal_matrix_structure", "predicted_point_sigma",
           "check_point_accuracy", "REGULATIONS_ID", "regulation_value", "check_height_factor",
           "free_strip_height_tolerance_um", "evaluate_regulations", "Criterion"]

EO_COLUMN_NAMES = ("X_S", "Y_S", "Z_S", "ω", "α", "κ")


# --- counting formulas (3.5.20), (3.5.21) --------------------------------------------------------
def bundle_unknowns(n: int, k: int) -> int:
    """N = 6n + 3k (3.5.20): n images, k determined points (with weighted control: including it)."""
    if n < 0 or k < 0:
        raise InputError("counts must be non-negative")
    return 6 * n + 3 * k


def bundle_equations(m: int, c: int = 0, i: int = 0, l: int = 0, s: int = 0, j: int = 0) -> int:
    """M = 2m + 3c + 2i + l + 3s + 3j (3.5.21).

    m image measurements (points × images they are measured on), c XYZ control points, i
    planimetric (XY) and l height control points with weighted observations (3.5.17), s GNSS
    projection centres (3.5.18), j images with measured angles (3.5.19). (The book's legend calls
    both the planimetric and the height count "i".)
    """
    if min(m, c, i, l, s, j) < 0:
        raise InputError("counts must be non-negative")
    return 2 * m + 3 * c + 2 * i + l + 3 * s + 3 * j


# --- layouts from footprint geometry -------------------------------------------------------------
def footprint_visibility(points_xy, centres_xy, footprint: float) -> np.ndarray:
    """(k, n) bool: point j lies strictly inside the square footprint of side ``footprint`` of image i.

    Vertical images: the footprint is centred on the nadir (X_S, Y_S). This is the counting rule of
    the reconstructed figs. 3.10/3.13 (a point on the footprint edge is not measured).
    """
    p = np.asarray(points_xy, dtype=float).reshape(-1, 2)
    c = np.asarray(centres_xy, dtype=float).reshape(-1, 2)
    if not footprint > 0:
        raise InputError("footprint must be positive")
    d = np.abs(p[:, None, :] - c[None, :, :])
    return np.all(d < footprint / 2 * (1 - 1e-9), axis=2)


@dataclass(frozen=True)
class BookBlock:
    """A synthetic rebuild of one of the book's block drawings, with truth and seeded observations."""

    name: str
    io: InteriorOrientation
    order: str
    cameras: np.ndarray            # (n, 6) true X_S, Y_S, Z_S, ω, α, κ
    image_labels: tuple            # book labels, e.g. ("P1", "P2", "P3", "P4")
    points: np.ndarray             # (k, 3) true X, Y, Z
    point_labels: tuple            # book labels ("1" … "8") or grid positions ("r1c1" …)
    kind: np.ndarray               # (k,) TIE / CONTROL / CHECK (photolib.synthetic)
    visibility: np.ndarray         # (k, n) bool, from footprint_visibility
    observations: Observations     # noisy image coordinates (mm)
    xy_true: np.ndarray            # (m, 2) noise-free projections
    sigma: float                   # image noise σ (mm) = unit weight σ₀ of (3.5.7)
    control_sigma: float | None    # None: control held fixed (3.5.3); else weighted (3.5.17), m
    gnss: np.ndarray | None        # (n, 3) measured projection centres (3.5.18), m
    gnss_sigma: float              # their accuracy, m
    footprint: float               # L, m
    base: float                    # b, m
    spacing: float                 # s, m
    grid: tuple | None = None      # (rows, cols) when the points form the figure's grid (fig. 3.13)
    noise_seed: int = 0            # seed of the control-coordinate noise (weighted control)

    @property
    def sigma0(self) -> float:
        """Unit-weight σ₀ of (3.5.7): the image noise σ, or 0.005 mm for a noise-free block."""
        return self.sigma if self.sigma > 0 else 0.005

    @property
    def n_images(self) -> int:
        return self.cameras.shape[0]

    @property
    def control(self) -> np.ndarray:
        return np.flatnonzero(self.kind == CONTROL)

    @property
    def unknown_points(self) -> np.ndarray:
        """Indices of the points that are unknowns (all of them when control is weighted)."""
        return np.arange(len(self.points)) if self.control_sigma is not None else np.flatnonzero(self.kind != CONTROL)

    def control_values(self) -> dict:
        """{point index: measured (X, Y, Z)} — the truth (fixed control) or the truth + seeded noise."""
        if self.control_sigma is None:
            return {int(i): self.points[i].copy() for i in self.control}
        rng = np.random.default_rng(self.noise_seed)
        noise = rng.normal(0.0, self.control_sigma, (self.control.size, 3))
        return {int(i): self.points[i] + e for i, e in zip(self.control, noise)}

    def start_values(self, seed: int = 1, centre_sigma: float = 10.0, angle_sigma: float = np.radians(1.0),
                     point_sigma: float = 10.0):
        """Seeded approximations (m, rad, m): the truth perturbed; control starts at its measured values."""
        rng = np.random.default_rng(seed)
        cams = self.cameras.copy()
        cams[:, :3] += rng.normal(0.0, centre_sigma, (self.n_images, 3))
        cams[:, 3:] += rng.normal(0.0, angle_sigma, (self.n_images, 3))
        pts = self.points + rng.normal(0.0, point_sigma, self.points.shape)
        for i, xyz in self.control_values().items():
            pts[i] = xyz
        return cams, pts

    def with_noise(self, seed: int) -> "BookBlock":
        """The same geometry with a new seeded realisation of every noise: image coordinates, GNSS
        centres and (weighted) control coordinates."""
        rng = np.random.default_rng(seed)
        o = self.observations
        obs = Observations(o.image, o.point, self.xy_true + rng.normal(0.0, self.sigma, self.xy_true.shape))
        gnss = None if self.gnss is None else self.cameras[:, :3] + rng.normal(0.0, self.gnss_sigma, (self.n_images, 3))
        return replace(self, observations=obs, gnss=gnss, noise_seed=int(rng.integers(2**31)))

    def adjust(self, seed: int = 1, **kwargs) -> BundleResult:
        """Adjust the block by :func:`photolib.bundle.bundle_adjustment` from seeded start values.

        Control is held fixed (3.5.3) or weighted (3.5.17) as the layout says; GNSS centres (3.5.18)
        are used when the layout has them. ``kwargs`` go to ``bundle_adjustment``.
        """
        cams0, pts0 = self.start_values(seed)
        args = dict(control=self.control_values(), control_sigma=self.control_sigma, sigma_image=self.sigma0,
                    order=self.order, covariance=True)
        if self.gnss is not None:
            args.update(gnss=self.gnss, gnss_sigma=self.gnss_sigma)
        args.update(kwargs)
        return bundle_adjustment(self.observations, cams0, pts0, self.io, **args)


def _project(cameras, image, XYZ, io, order):
    """Collinearity (3.5.1) of points in front of their images (else :class:`InputError`)."""
    xy, z_star = project_to_images(cameras, image, XYZ, io, order)
    if np.any(z_star >= 0):
        raise InputError("a point is not in front of its image")
    return xy


def _build(name, centres_xy, points_xy, kind, image_labels, point_labels, *, f, frame_size, flying_height,
           sigma, seed, order, control_sigma, gnss_sigma, use_gnss, base, spacing, grid=None, at_principal=None,
           angle_sigma=np.radians(1.0), relief=15.0):
    check_order(order)
    if not sigma >= 0:
        raise InputError("sigma must be non-negative")
    rng = np.random.default_rng(seed)
    io = InteriorOrientation(f=f)
    footprint = frame_size * flying_height / f
    centres_xy = np.asarray(centres_xy, dtype=float)
    points_xy = np.array(points_xy, dtype=float)
    n = len(centres_xy)
    cameras = np.empty((n, 6))
    cameras[:, :2] = centres_xy
    cameras[:, 2] = flying_height + rng.normal(0.0, 5.0, n)
    cameras[:, 3:] = rng.normal(0.0, angle_sigma, (n, 3))
    Z = 5.0 + relief * rng.uniform(0.0, 1.0, len(points_xy))        # terrain 5 … 20 m
    # points drawn at a principal point ("-ф-" in the figures) lie where the optical axis meets the
    # terrain — not exactly below S, where ∂x/∂Z_S and (for "kaw") ∂x/∂κ would vanish identically
    for j, i in (at_principal or {}).items():
        axis = rotation_matrix(*cameras[i, 3:], order) @ np.array([0.0, 0.0, -1.0])
        points_xy[j] = cameras[i, :2] + (Z[j] - cameras[i, 2]) / axis[2] * axis[:2]
    vis = footprint_visibility(points_xy, centres_xy, footprint)
    points = np.column_stack([points_xy, Z])
    point_idx, image_idx = np.nonzero(vis)
    order_obs = np.lexsort((point_idx, image_idx))                    # image by image, as in fig. 3.11
    image_idx, point_idx = image_idx[order_obs], point_idx[order_obs]
    xy_true = _project(cameras, image_idx, points[point_idx], io, order)
    half = frame_size / 2
    if np.any(np.abs(xy_true) >= half):
        raise InputError(f"{name}: a projected point falls outside the {frame_size} mm frame; reduce the tilts")
    xy = xy_true + rng.normal(0.0, sigma, xy_true.shape) if sigma > 0 else xy_true.copy()
    gnss = None
    if use_gnss:
        gnss = cameras[:, :3] + rng.normal(0.0, gnss_sigma, (n, 3))
    return BookBlock(noise_seed=seed + 101, name=name, io=io, order=order, cameras=cameras, image_labels=tuple(image_labels),
                     points=points, point_labels=tuple(point_labels), kind=np.asarray(kind), visibility=vis,
                     observations=Observations(image_idx, point_idx, xy), xy_true=xy_true, sigma=float(sigma),
                     control_sigma=control_sigma, gnss=gnss, gnss_sigma=float(gnss_sigma), footprint=footprint,
                     base=base, spacing=spacing, grid=grid)


def fig_3_10_block(sigma: float = 0.005, seed: int = 310, *, f: float = 100.0, frame_size: float = 125.0,
                   flying_height: float = 1000.0, order: str = "kaw") -> BookBlock:
    """Fig. 3.10: two strips (P1–P2, P3–P4) of one stereopair, 60 % forward and 60 % side overlap.

    Footprint L = frame·H/f (1250 m by default), base b = strip spacing s = 0.4L (500 m). Tie
    points 1, 2, 5, 6 at the nadirs of P1, P2, P3, P4 (seen on all four images); XYZ control 3, 4
    at s/2 beyond strip 1 (on P1, P2 only) and 7, 8 at s/2 beyond strip 2 (on P3, P4 only), held
    fixed (3.5.3). Every image then measures six points: N = 36, M = 48 (book, lines 2080–2083).
    True tilts are small (seeded, σ = 1°), terrain heights 5–20 m.
    """
    L = frame_size * flying_height / f
    b = s = 0.4 * L
    x0, y0 = 1000.0, 1000.0
    centres = [(x0, y0), (x0 + b, y0), (x0, y0 - s), (x0 + b, y0 - s)]
    pts = {1: (x0, y0), 2: (x0 + b, y0), 3: (x0, y0 + s / 2), 4: (x0 + b, y0 + s / 2),
           5: (x0, y0 - s), 6: (x0 + b, y0 - s), 7: (x0, y0 - 1.5 * s), 8: (x0 + b, y0 - 1.5 * s)}
    kind = [CONTROL if k in (3, 4, 7, 8) else TIE for k in pts]
    return _build("fig3.10", centres, list(pts.values()), kind, ("P1", "P2", "P3", "P4"),
                  tuple(str(k) for k in pts), f=f, frame_size=frame_size, flying_height=flying_height,
                  sigma=sigma, seed=seed, order=order, control_sigma=None, gnss_sigma=0.05, use_gnss=False,
                  base=b, spacing=s, at_principal={0: 0, 1: 1, 4: 2, 5: 3})


def fig_3_13_block(sigma: float = 0.005, seed: int = 313, *, control_sigma: float = 0.05, gnss_sigma: float = 0.05,
                   f: float = 100.0, frame_size: float = 125.0, flying_height: float = 1000.0,
                   order: str = "kaw") -> BookBlock:
    """Fig. 3.13: two strips of four images, 60 % forward and 30 % side overlap.

    b = 0.4L, s = 0.7L. A 5 × 4 grid of 20 points: rows at +s/2, 0 (nadirs of strip 1), −s/2, −s
    (nadirs of strip 2), −1.5s; columns at the nadirs. Control (weighted, (3.5.17), σ =
    ``control_sigma``): the four corners and the right end of the middle row (c = 5); all eight
    projection centres measured by GNSS (3.5.18, σ = ``gnss_sigma``). The footprints give the
    figure's images-per-point counts 2-3-3-2 / 2-3-3-2 / 4-6-6-4 / 2-3-3-2 / 2-3-3-2 (m = 60) —
    with 30 % side overlap only. Book (lines 2164–2186): N = 108, M = 159.
    """
    L = frame_size * flying_height / f
    b, s = 0.4 * L, 0.7 * L
    x0, y0 = 1000.0, 1000.0
    centres = [(x0 + i * b, y0) for i in range(4)] + [(x0 + i * b, y0 - s) for i in range(4)]
    rows = [s / 2, 0.0, -s / 2, -s, -1.5 * s]
    pts = [(x0 + c * b, y0 + y) for y in rows for c in range(4)]
    control = {(0, 0), (0, 3), (4, 0), (4, 3), (2, 3)}
    kind = [CONTROL if (r, c) in control else TIE for r in range(5) for c in range(4)]
    labels = [f"r{r + 1}c{c + 1}" for r in range(5) for c in range(4)]
    images = [f"P{i + 1}" for i in range(8)]
    return _build("fig3.13", centres, pts, kind, images, labels, f=f, frame_size=frame_size,
                  flying_height=flying_height, sigma=sigma, seed=seed, order=order, control_sigma=control_sigma,
                  gnss_sigma=gnss_sigma, use_gnss=True, base=b, spacing=s, grid=(5, 4),
                  at_principal={4 + c: c for c in range(4)} | {12 + c: 4 + c for c in range(4)})


def images_per_point(block: BookBlock) -> np.ndarray:
    """(k,) number of images each point is measured on (the numbers printed in fig. 3.13)."""
    return block.visibility.sum(axis=1)


def block_counts(block: BookBlock) -> dict:
    """The inputs of (3.5.20)/(3.5.21) read off the layout, and N, M from the formulas.

    k counts the point unknowns: with fixed control (fig. 3.10) the determined points only, with
    weighted control (fig. 3.13) all points — the book's two conventions.
    """
    c = int(block.control.size) if block.control_sigma is not None else 0
    s = 0 if block.gnss is None else int(np.isfinite(block.gnss).all(axis=1).sum())
    out = dict(n=block.n_images, k=int(block.unknown_points.size), m=int(block.visibility.sum()), c=c, i=0, l=0,
               s=s, j=0)
    out["N"] = bundle_unknowns(out["n"], out["k"])
    out["M"] = bundle_equations(out["m"], c, 0, 0, s, 0)
    out["points_per_image"] = block.visibility.sum(axis=0)
    return out


# --- the correction equations as one dense system (fig. 3.11) -------------------------------------
@dataclass
class BundleSystem:
    """Dense A·δ + L = V (3.5.5) with weights P (3.5.7), in the column order of fig. 3.11."""

    A: np.ndarray                  # (M, N)
    L: np.ndarray                  # (M,)
    P: np.ndarray                  # (M,) p = σ₀²/m²
    row_kind: np.ndarray           # (M,) "tie" (3.5.2), "control" (3.5.3), "ground" (3.5.17), "gnss" (3.5.18), "ins" (3.5.19)
    columns: list                  # (N,) names, e.g. "P1:X_S", "1:X"
    n_eo: int                      # number of EO columns (6n): δ₁ = first n_eo unknowns

    @property
    def shape(self) -> tuple:
        return self.A.shape

    @property
    def nnz(self) -> int:
        return int(np.count_nonzero(self.A))

    @property
    def rank(self) -> int:
        As = self.A / np.linalg.norm(self.A, axis=0)
        return int(np.linalg.matrix_rank(As))

    def normal(self):
        """N = AᵀPA and Lᴺ = AᵀPL of (3.5.8)."""
        PA = self.P[:, None] * self.A
        return self.A.T @ PA, PA.T @ self.L


def correction_equation_system(block: BookBlock, cameras=None, points=None, *, planimetric=(), height=(),
                               ins=None, ins_sigma: float = np.radians(0.005)) -> BundleSystem:
    """Build the block's correction equations densely at (``cameras``, ``points``) (default: truth).

    Rows, in this order: the image observations image by image ((3.5.2) for unknown points, (3.5.3)
    for fixed control), then for weighted control (3.5.17) three rows per XYZ point (two for a
    point listed in ``planimetric``, one for ``height``), then GNSS centres (3.5.18), then INS
    angles (3.5.19) for the images whose row of ``ins`` (n, 3) is finite. Columns: the six EO of
    every image, then X, Y, Z of every unknown point. The image rows come from
    :func:`photolib.bundle.bundle_correction_equations` through :func:`photolib.lsq.block_equations_dense`.
    """
    cams = block.cameras if cameras is None else np.asarray(cameras, dtype=float)
    pts = block.points if points is None else np.asarray(points, dtype=float)
    o = block.observations
    n, k = block.n_images, len(pts)
    eq = bundle_correction_equations(o.image, o.point, o.xy, cams, pts, block.io, block.order)
    free = np.zeros(k, bool)
    free[block.unknown_points] = True
    B, L, _ = block_equations_dense(eq, n, k, free)
    fixed_obs = ~free[o.point]
    kinds = np.repeat(np.where(fixed_obs, "control", "tie"), 2)
    P = np.ones(B.shape[0])
    col_of_point = np.cumsum(free) - 1
    columns = [f"{lab}:{c}" for lab in block.image_labels for c in EO_COLUMN_NAMES]
    columns += [f"{block.point_labels[j]}:{c}" for j in np.flatnonzero(free) for c in "XYZ"]
    rows, Ls, Ps, ks = [], [], [], []

    def direct(col, l_value, weight, kind):
        r = np.zeros(B.shape[1])
        r[col] = 1.0
        rows.append(r)
        Ls.append(l_value)
        Ps.append(weight)
        ks.append(kind)

    planimetric, height = set(planimetric), set(height)
    if block.control_sigma is not None:
        w = (block.sigma0 / block.control_sigma) ** 2
        for j, xyz in block.control_values().items():
            axes = (0, 1) if j in planimetric else (2,) if j in height else (0, 1, 2)
            for a in axes:
                direct(6 * n + 3 * col_of_point[j] + a, pts[j, a] - xyz[a], w, "ground")   # l = X⁰ − X (3.5.17)
    elif planimetric or height:
        raise InputError("planimetric/height control needs weighted control (control_sigma)")
    if block.gnss is not None:
        w = (block.sigma0 / block.gnss_sigma) ** 2
        for i in range(n):
            if np.all(np.isfinite(block.gnss[i])):
                for a in range(3):
                    direct(6 * i + a, cams[i, a] - block.gnss[i, a], w, "gnss")              # (3.5.18)
    if ins is not None:
        ins = np.asarray(ins, dtype=float)
        if ins.shape != (n, 3):
            raise InputError(f"ins: expected ({n}, 3), got {ins.shape}")
        w = (block.sigma0 / ins_sigma) ** 2
        for i in range(n):
            if np.all(np.isfinite(ins[i])):
                for a in range(3):
                    direct(6 * i + 3 + a, cams[i, 3 + a] - ins[i, a], w, "ins")              # (3.5.19)
    if rows:
        B = np.vstack([B, np.array(rows)])
        L = np.concatenate([L, Ls])
        P = np.concatenate([P, Ps])
        kinds = np.concatenate([kinds, ks])
    return BundleSystem(A=B, L=L, P=P, row_kind=kinds, columns=columns, n_eo=6 * n)


def normal_matrix_structure(system: BundleSystem) -> dict:
    """The structure of N = AᵀPA stated for fig. 3.12, measured on the built system.

    Returns ``N11_block`` / ``N22_block`` ("6×6" / "3×3" when N₁₁ / N₂₂ are block-diagonal with full
    blocks of that size, else "not block-diagonal"), ``N12_zero_fraction`` (share of exactly zero
    entries of N₁₂) and ``N12_pattern`` ("sparse" when more than half of N₁₂ is zero, else "dense").
    """
    N, _ = system.normal()
    q = system.n_eo
    nz = N != 0

    def block_kind(M, size):
        n_blocks = M.shape[0] // size
        mask = np.kron(np.eye(n_blocks, dtype=bool), np.ones((size, size), bool))
        if np.all(M[mask]) and not np.any(M[~mask]):
            return f"{size}×{size}"
        return "not block-diagonal"

    N12 = nz[:q, q:]
    zero = 1.0 - N12.mean() if N12.size else 1.0
    return {"N11_block": block_kind(nz[:q, :q], 6), "N22_block": block_kind(nz[q:, q:], 3),
            "N12_zero_fraction": float(zero), "N12_pattern": "sparse" if zero > 0.5 else "dense"}


# --- accuracy of the adjusted points --------------------------------------------------------------
def predicted_point_sigma(result: BundleResult, sigma_image: float) -> np.ndarray:
    """(k, 3) a-priori standard deviations σ₀·√Q_jj of the points (m_j of (3.5.11) with μ → σ₀).

    ``bundle_adjustment`` reports m_j = μ√Q_jj; with the weights p = σ₀²/m² the a-priori value
    replaces μ by σ₀ = ``sigma_image``.
    """
    if result.points_std is None:
        raise InputError("the adjustment was run without covariance")
    return result.points_std * (sigma_image / result.mu) if result.mu > 0 else result.points_std * np.nan


def check_point_accuracy(block: BookBlock, result: BundleResult, indices=None) -> dict:
    """Errors of the adjusted points against the truth: r.m.s. per axis and the predicted σ.

    ``indices`` default: the tie points (the points not used as control). Returns ``rms`` (3,),
    ``predicted`` (3,) = r.m.s. of σ₀√Q_jj over the same points, ``errors`` (c, 3).
    """
    idx = np.flatnonzero(block.kind != CONTROL) if indices is None else np.asarray(indices, dtype=np.intp)
    err = result.points[idx] - block.points[idx]
    pred = predicted_point_sigma(result, block.sigma0)[idx]
    return {"indices": idx, "errors": err, "rms": np.sqrt(np.mean(err ** 2, axis=0)),
            "predicted": np.sqrt(np.mean(pred ** 2, axis=0))}


# --- §3.7 regulation tolerances (our helper; numbers from textbook/ch03.toml) ---------------------
REGULATIONS_ID = "3.7-tolerances"


def regulation_value(name: str) -> float:
    """A tolerance of §3.7 as transcribed in ``textbook/ch03.toml`` (example ``3.7-tolerances``)."""
    from .textbook import load_chapter
    ex = load_chapter(3).example(REGULATIONS_ID)
    for q in ex.quantities:
        if q.name == name:
            return q.value
    raise KeyError(f"{REGULATIONS_ID} has no quantity {name!r}")


def check_height_factor(contour_interval: float, scale_denominator: float, stage: str = "check") -> float:
    """The factor of the contour interval h for mean height discrepancies, 3.7.6 / 3.7.7.

    ``stage="check"``: check points after external orientation (3.7.6: 0.2h, 0.25h, 0.35h);
    ``stage="common"``: common points of adjacent strips (3.7.7: 0.4h, 0.5h, 0.7h). The category is
    (a) h = 1 m, or h = 0.5 m at 1:1000 and 1:500; (b) h = 2 or 2.5 m, or h = 0.5 m at 1:2000 and
    1:5000; (c) h = 5 or 10 m. Other combinations are not covered by the Instruction: InputError.
    """
    h, sc = float(contour_interval), float(scale_denominator)
    if h == 1.0 or (h == 0.5 and sc in (1000.0, 500.0)):
        cat = "a"
    elif h in (2.0, 2.5) or (h == 0.5 and sc in (2000.0, 5000.0)):
        cat = "b"
    elif h in (5.0, 10.0):
        cat = "c"
    else:
        raise InputError(f"contour interval {h} m at 1:{sc:g} is not covered by 3.7.6/3.7.7")
    clause = {"check": "3.7.6", "common": "3.7.7"}.get(stage)
    if clause is None:
        raise InputError("stage must be 'check' or 'common'")
    return regulation_value(f"{clause} height, category {cat}")


def free_strip_height_tolerance_um(f_mm: float, base_image_mm: float) -> float:
    """3.7.2: r.m.s. height discrepancy of tie points in a free strip ≤ 15 µm · f / b (µm at image scale)."""
    if not (f_mm > 0 and base_image_mm > 0):
        raise InputError("f and the image base must be positive")
    return regulation_value("3.7.2 tie height") * f_mm / base_image_mm


@dataclass(frozen=True)
class Criterion:
    """One tolerance check: clause, what, measured value, tolerance, passed."""

    clause: str
    what: str
    value: float
    tolerance: float
    unit: str
    passed: bool


def evaluate_regulations(control_errors, check_errors, scale_denominator: float, contour_interval: float,
                         wooded: bool = False) -> list:
    """Evaluate a controlled block against the 3.7.6 tolerances (our helper, not in the book).

    Parameters
    ----------
    control_errors, check_errors : (c, 3) arrays
        Adjusted − geodetic coordinates (m) at the control points and at independent check points.
    scale_denominator : float
        Map (plan) scale 1 : ``scale_denominator``; planimetric tolerances are mm at map scale.
    contour_interval : float
        h, m.
    wooded : bool
        Forested area: limit discrepancies allowed in 10 % of the check points instead of 5 %.

    Our reading of the Instruction: a "mean" discrepancy is the mean absolute height error and the
    mean length of the planimetric error vector; a "limit" discrepancy is one that reaches twice
    the tolerance for the mean ("предельно допустимые расхождения, равные удвоенным средним"), and
    the share of check points with such discrepancies must not exceed 5 % (10 % in forest).
    """
    ce = np.asarray(control_errors, dtype=float).reshape(-1, 3)
    ke = np.asarray(check_errors, dtype=float).reshape(-1, 3)
    if ke.shape[0] == 0 or not (np.all(np.isfinite(ce)) and np.all(np.isfinite(ke))):
        raise InputError("give finite (c, 3) control and check-point errors (at least one check point)")
    h, mm = float(contour_interval), float(scale_denominator) / 1000.0           # 1 mm at map scale in m
    out = []
    if ce.shape[0]:
        t = regulation_value("3.7.6 control height") * h
        v = float(np.mean(np.abs(ce[:, 2])))
        out.append(Criterion("3.7.6", "mean |ΔZ| at control points", v, t, "m", v <= t))
        t = regulation_value("3.7.6 control plan") * mm
        v = float(np.mean(np.hypot(ce[:, 0], ce[:, 1])))
        out.append(Criterion("3.7.6", "mean ΔXY at control points", v, t, "m", v <= t))
    t_h = check_height_factor(h, scale_denominator) * h
    t_p = regulation_value("3.7.6 check plan") * mm
    dz, dp = np.abs(ke[:, 2]), np.hypot(ke[:, 0], ke[:, 1])
    out.append(Criterion("3.7.6", "mean |ΔZ| at check points", float(dz.mean()), t_h, "m", dz.mean() <= t_h))
    out.append(Criterion("3.7.6", "mean ΔXY at check points", float(dp.mean()), t_p, "m", dp.mean() <= t_p))
    share = regulation_value("3.7.6 limit share, wooded" if wooded else "3.7.6 limit share, open")
    factor = regulation_value("3.7.6 limit factor")
    for what, e, t in (("height", dz, t_h), ("plan", dp, t_p)):
        frac = float(np.mean(e >= factor * t))
        out.append(Criterion("3.7.6", f"share of check points with {what} error ≥ {factor:g}× tolerance",
                             100.0 * frac, share, "%", frac <= share / 100.0))
    return out
