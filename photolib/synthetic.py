"""Synthetic aerial blocks with known truth — test data for Chapter 3 (§3.1, §3.5).

The book prints no image coordinates for its phototriangulation examples, so the bundle method
is demonstrated, tested and benchmarked on simulated blocks: :func:`aerial_block` lays out
strips of vertical frame images over gently rolling terrain with a chosen forward and side
overlap (60 % / 30 % by default, the layout of fig. 3.13), scatters tie points so that each
image sees a chosen number of them, places control and check points, projects everything with
the collinearity equations (1.4.12)/(3.5.1) and adds Gaussian image noise. Everything is seeded.

Units as everywhere in photolib: image coordinates and f in mm, object coordinates in metres,
angles in radians.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .camera import InteriorOrientation
from .errors import InputError
from .rotation import check_order, rotation_matrix

TIE, CONTROL, CHECK = 0, 1, 2
"""Point kinds in :attr:`SyntheticBlock.kind`."""


@dataclass(frozen=True)
class Observations:
    """Image measurements: point ``point[k]`` measured at ``xy[k]`` (mm) on image ``image[k]``."""

    image: np.ndarray      # (m,) int
    point: np.ndarray      # (m,) int
    xy: np.ndarray         # (m, 2) float, mm

    def __len__(self) -> int:
        return int(self.image.shape[0])


@dataclass(frozen=True)
class SyntheticBlock:
    """A simulated block: ground truth, noisy observations and the simulation settings."""

    io: InteriorOrientation
    order: str
    cameras: np.ndarray        # (n, 6) true X_S, Y_S, Z_S, ω, α, κ
    points: np.ndarray         # (k, 3) true X, Y, Z
    kind: np.ndarray           # (k,) TIE / CONTROL / CHECK
    observations: Observations  # noisy measurements
    xy_true: np.ndarray        # (m, 2) noise-free projections
    sigma: float               # image noise σ (mm)
    strip: np.ndarray          # (n,) strip number of each image
    frame_size: float          # side of the square image format (mm)
    base: float                # photo base (m)
    strip_spacing: float       # distance between strip axes (m)

    @property
    def control(self) -> np.ndarray:
        return np.flatnonzero(self.kind == CONTROL)

    @property
    def check(self) -> np.ndarray:
        return np.flatnonzero(self.kind == CHECK)

    @property
    def n_images(self) -> int:
        return self.cameras.shape[0]

    def start_values(self, seed: int = 1, centre_sigma: float = 5.0, angle_sigma: float = np.radians(0.5),
                     point_sigma: float = 5.0):
        """Seeded approximations: the truth perturbed by Gaussian errors (m, rad, m).

        Control points keep their true coordinates (they are known). Returns ``(cameras0, points0)``.
        """
        rng = np.random.default_rng(seed)
        cams = self.cameras.copy()
        cams[:, :3] += rng.normal(0.0, centre_sigma, (self.n_images, 3))
        cams[:, 3:] += rng.normal(0.0, angle_sigma, (self.n_images, 3))
        pts = self.points + rng.normal(0.0, point_sigma, self.points.shape)
        pts[self.control] = self.points[self.control]
        return cams, pts


def terrain_height(X, Y, mean: float = 150.0, relief: float = 30.0, wavelength: float = 3000.0):
    """A smooth synthetic terrain: mean height plus two crossing sine waves of amplitude ``relief``/2."""
    X, Y = np.asarray(X, dtype=float), np.asarray(Y, dtype=float)
    k = 2 * np.pi / wavelength
    return mean + 0.5 * relief * (np.sin(k * X) * np.cos(0.7 * k * Y) + np.sin(0.45 * k * (X + Y)))


def _project(cameras, image, XYZ, io, order):
    """Collinearity (3.5.1) of points ``XYZ[k]`` in images ``image[k]`` → (xy, z*)."""
    A = rotation_matrix(cameras[:, 3], cameras[:, 4], cameras[:, 5], order)[image]
    star = np.einsum("kji,kj->ki", A, XYZ - cameras[image, :3])          # Aᵀ(X − X_S)
    xy = np.column_stack([io.x0 - io.f * star[:, 0] / star[:, 2], io.y0 - io.f * star[:, 1] / star[:, 2]])
    return xy, star[:, 2]


def aerial_block(n_strips: int = 2, images_per_strip: int = 5, *, f: float = 100.0, frame_size: float = 100.0,
                 flying_height: float = 1000.0, forward_overlap: float = 0.6, side_overlap: float = 0.3,
                 points_per_image: int = 30, relief: float = 30.0, sigma: float = 0.005,
                 angle_sigma: float = np.radians(1.0), height_sigma: float = 5.0,
                 control: str | np.ndarray = "perimeter", control_interval: int = 4, n_check: int = 10,
                 order: str = "kaw", seed: int = 0) -> SyntheticBlock:
    """Simulate a block of vertical aerial images over smooth terrain.

    Parameters
    ----------
    n_strips, images_per_strip : int
        Block size; strips run along X and are stacked along −Y.
    f, frame_size : float
        Focal length and side of the square image format (mm). Default: f = 100 mm, 100 × 100 mm.
    flying_height : float
        Height of the projection centres above the mean terrain (m); the image scale is 1 : H/f.
    forward_overlap, side_overlap : float
        Overlaps as fractions: base b = (1 − p)·L, strip spacing = (1 − q)·L with L the footprint.
    points_per_image : int
        Average number of tie points measured per image (they are scattered uniformly).
    relief : float
        Peak-to-peak-ish amplitude of the terrain (m), see :func:`terrain_height`.
    sigma : float
        Standard deviation of the Gaussian image noise (mm); 0 gives exact measurements.
    angle_sigma, height_sigma : float
        Spread of the true ω, α, κ (rad) and of the flying height (m) about the nominal.
    control : "perimeter", "corners" or an (c, 2) array of X, Y
        Control point layout: ``"perimeter"`` puts points at the block corners and every
        ``control_interval`` bases along the first and last strip and at both ends of every
        second strip (the usual aerial-triangulation scheme); ``"corners"`` only the four corners
        and the block centre (the "envelope" of §3.5).
    n_check : int
        Tie points (seen in ≥ 3 images) turned into check points.
    order : {"kaw", "wak"}
        Rotation sequence of the true angles.
    seed : int
        Seed of the random generator: the whole block is a function of its arguments.

    Returns
    -------
    SyntheticBlock
    """
    check_order(order)
    if n_strips < 1 or images_per_strip < 2:
        raise InputError("a block needs at least one strip of two images")
    if not (0 < forward_overlap < 1 and 0 <= side_overlap < 1):
        raise InputError("overlaps must be fractions in (0, 1)")
    rng = np.random.default_rng(seed)
    io = InteriorOrientation(f=f)
    footprint = frame_size * flying_height / f
    base = (1 - forward_overlap) * footprint
    spacing = (1 - side_overlap) * footprint
    mean_height = 150.0

    # projection centres and angles
    strip = np.repeat(np.arange(n_strips), images_per_strip)
    along = np.tile(np.arange(images_per_strip), n_strips)
    n = strip.size
    cameras = np.empty((n, 6))
    cameras[:, 0] = along * base + rng.normal(0, 0.02 * base, n)
    cameras[:, 1] = -strip * spacing + rng.normal(0, 0.02 * spacing, n)
    cameras[:, 2] = mean_height + flying_height + rng.normal(0, height_sigma, n)
    cameras[:, 3:] = rng.normal(0, angle_sigma, (n, 3))

    # tie points scattered uniformly over the covered area
    x_lo, x_hi = -footprint / 2, (images_per_strip - 1) * base + footprint / 2
    y_lo, y_hi = -(n_strips - 1) * spacing - footprint / 2, footprint / 2
    area = (x_hi - x_lo) * (y_hi - y_lo)
    n_tie = int(round(points_per_image * area / footprint ** 2))
    tie_xy = np.column_stack([rng.uniform(x_lo, x_hi, n_tie), rng.uniform(y_lo, y_hi, n_tie)])

    # control points
    if isinstance(control, str):
        xs_end = [0.0, (images_per_strip - 1) * base]
        if control == "corners":
            ys = [0.0, -(n_strips - 1) * spacing]
            ctrl = [(x, y) for x in xs_end for y in ys] + [(xs_end[1] / 2, ys[1] / 2)]
        elif control == "perimeter":
            ctrl = []
            step = max(1, control_interval)
            cols = sorted(set(list(range(0, images_per_strip, step)) + [images_per_strip - 1]))
            edge_strips = sorted({0, n_strips - 1})
            for s in edge_strips:
                offset = spacing * 0.35 * (-1 if s == n_strips - 1 and n_strips > 1 else 1)
                ctrl += [(c * base, -s * spacing + offset) for c in cols]
            for s in range(1, n_strips - 1):
                if s % 2 == 0:
                    ctrl += [(x, -s * spacing) for x in xs_end]
            # in a single-strip block a second row makes the datum well determined
            if n_strips == 1:
                ctrl += [(c * base, -spacing * 0.35) for c in cols]
        else:
            raise InputError(f"unknown control layout {control!r}; use 'perimeter', 'corners' or an array")
        ctrl_xy = np.array(ctrl, dtype=float)
    else:
        ctrl_xy = np.asarray(control, dtype=float)
        if ctrl_xy.ndim != 2 or ctrl_xy.shape[1] != 2:
            raise InputError("control must be a layout name or an (c, 2) array of X, Y")
    all_xy = np.vstack([tie_xy, ctrl_xy])
    points = np.column_stack([all_xy, terrain_height(all_xy[:, 0], all_xy[:, 1], mean_height, relief)])
    kind = np.concatenate([np.full(n_tie, TIE), np.full(len(ctrl_xy), CONTROL)])

    # which images see which points: project every point near an image into it
    half = frame_size / 2 * 0.98
    image_idx, point_idx = [], []
    for j in range(n):
        near = np.flatnonzero(np.max(np.abs(points[:, :2] - cameras[j, :2]), axis=1) < 0.8 * footprint)
        xy, zs = _project(cameras, np.full(near.size, j), points[near], io, order)
        inside = (np.abs(xy[:, 0] - io.x0) < half) & (np.abs(xy[:, 1] - io.y0) < half) & (zs < 0)
        image_idx.append(np.full(inside.sum(), j))
        point_idx.append(near[inside])
    image_idx = np.concatenate(image_idx)
    point_idx = np.concatenate(point_idx)

    # drop points seen in fewer than two images (they cannot be intersected), renumber
    count = np.bincount(point_idx, minlength=len(points))
    keep = count >= 2
    new_index = np.cumsum(keep) - 1
    sel = keep[point_idx]
    image_idx, point_idx = image_idx[sel], new_index[point_idx[sel]]
    points, kind, count = points[keep], kind[keep], count[keep]

    # check points: tie points seen in at least three images, spread by random choice
    candidates = np.flatnonzero((kind == TIE) & (count >= 3))
    if n_check > 0 and candidates.size:
        kind[rng.choice(candidates, size=min(n_check, candidates.size), replace=False)] = CHECK

    order_obs = np.lexsort((point_idx, image_idx))
    image_idx, point_idx = image_idx[order_obs], point_idx[order_obs]
    xy_true, _ = _project(cameras, image_idx, points[point_idx], io, order)
    xy = xy_true + rng.normal(0.0, sigma, xy_true.shape) if sigma > 0 else xy_true.copy()
    return SyntheticBlock(io=io, order=order, cameras=cameras, points=points, kind=kind,
                          observations=Observations(image_idx, point_idx, xy), xy_true=xy_true, sigma=float(sigma),
                          strip=strip, frame_size=float(frame_size), base=float(base), strip_spacing=float(spacing))
