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
from .single_image import project_to_images
from .rotation import check_order

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


def aerial_block(n_strips: int = 2, images_per_strip: int = 5, *, f: float = 100.0, frame_size: float = 100.0,
                 flying_height: float = 1000.0, forward_overlap: float = 0.6, side_overlap: float = 0.3,
                 points_per_image: int = 30, relief: float = 30.0, sigma: float = 0.005,
                 angle_sigma: float = np.radians(1.0), height_sigma: float = 5.0,
                 control: str | np.ndarray = "perimeter", control_interval: int = 4, n_check: int = 10,
                 order: str = "kaw", seed: int = 0, io: InteriorOrientation | None = None,
                 strip_heights=None) -> SyntheticBlock:
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
    io : InteriorOrientation, optional
        The camera (replaces ``f``): its principal point and distortion (1.2.2) are simulated — the
        observations are the ideal projections moved by the inverse of the correction
        (:func:`photolib.camera.apply_distortion`), as a real distorting lens records them (§3.6).
    strip_heights : sequence of float, optional
        Flying height of each strip (replaces ``flying_height`` for the centres; overlaps are
        laid out for ``flying_height``). Different heights help self-calibration separate f from Z_S.

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
    camera = io if io is not None else InteriorOrientation(f=f)
    io = InteriorOrientation(f=camera.f, x0=camera.x0, y0=camera.y0)    # ideal projection
    f = camera.f
    heights = np.full(n_strips, float(flying_height)) if strip_heights is None else \
        np.asarray(strip_heights, dtype=float)
    if heights.shape != (n_strips,) or np.any(~(heights > 0)):
        raise InputError(f"strip_heights: give {n_strips} positive flying heights")
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
    cameras[:, 2] = mean_height + heights[strip] + rng.normal(0, height_sigma, n)
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
        xy, zs = project_to_images(cameras, np.full(near.size, j), points[near], io, order)
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
    xy_true, _ = project_to_images(cameras, image_idx, points[point_idx], io, order)
    if camera.has_distortion:
        from .camera import apply_distortion
        xy_true = apply_distortion(xy_true, camera)
    xy = xy_true + rng.normal(0.0, sigma, xy_true.shape) if sigma > 0 else xy_true.copy()
    return SyntheticBlock(io=camera, order=order, cameras=cameras, points=points, kind=kind,
                          observations=Observations(image_idx, point_idx, xy), xy_true=xy_true, sigma=float(sigma),
                          strip=strip, frame_size=float(frame_size), base=float(base), strip_spacing=float(spacing))


# --- Chapter 3, §3.8–§3.9: rigs, rolling shutter, corridors ----------------------------------------
@dataclass(frozen=True)
class RigBlock:
    """A simulated multi-camera block (§3.8): reference EO per exposure, constant mounting elements."""

    ios: tuple                     # InteriorOrientation per camera
    order: str
    exposures: np.ndarray          # (n, 6) true EO of the reference camera (camera 0)
    mounts: np.ndarray             # (n_s − 1, 6) true B_X, B_Y, B_Z, ω′, α′, κ′
    points: np.ndarray             # (k, 3)
    kind: np.ndarray               # (k,) TIE / CONTROL / CHECK
    exposure_of_image: np.ndarray  # (n_images,)
    camera_of_image: np.ndarray    # (n_images,)
    observations: Observations
    sigma: float

    @property
    def control(self) -> np.ndarray:
        return np.flatnonzero(self.kind == CONTROL)

    @property
    def image_cameras(self) -> np.ndarray:
        """True EO of every image (3.8.5)/(3.8.8)."""
        from .bundle import rig_image_orientation
        mounts = np.vstack([np.zeros((1, 6)), self.mounts])
        return rig_image_orientation(self.exposures[self.exposure_of_image], mounts[self.camera_of_image], self.order)


def _observe(cams, points, io_of_image, frame_half, rng, sigma, order):
    """Project every point into every image (ideal, no distortion), keep those inside the frame."""
    image_idx, point_idx, xy_all = [], [], []
    for j in range(cams.shape[0]):
        io = io_of_image[j]
        xy, zs = project_to_images(cams, np.full(len(points), j), points, io, order)
        inside = (np.abs(xy[:, 0] - io.x0) < frame_half) & (np.abs(xy[:, 1] - io.y0) < frame_half) & (zs < 0)
        image_idx.append(np.full(inside.sum(), j))
        point_idx.append(np.flatnonzero(inside))
        xy_all.append(xy[inside])
    image_idx, point_idx, xy = np.concatenate(image_idx), np.concatenate(point_idx), np.vstack(xy_all)
    noisy = xy + rng.normal(0.0, sigma, xy.shape) if sigma > 0 else xy.copy()
    return Observations(image_idx, point_idx, noisy)


def fig310_block(rig: bool = False, sigma: float = 0.005, seed: int = 0, order: str = "kaw"):
    """The block of fig. 3.10 (two strips × one stereopair) — layout reconstructed from the text.

    Images P1, P2 (strip 1) and P3, P4 (strip 2), f = 100 mm, H ≈ 1000 m, base 500 m; tie points
    1, 2, 5, 6 at the principal points, seen in all four images; control points 3, 4 (seen in
    P1, P2) and 7, 8 (seen in P3, P4) — six points per image, 48 correction equations.
    With ``rig=True`` P1/P2 and P3/P4 are two exposures of a stereo camera (§3.8, fig. 3.18): P2
    and P4 follow from P1 and P3 by the same mounting elements (base 500 m along the x axis of
    the reference camera, as in the book's formal example).
    Returns a :class:`RigBlock` (camera 0 = P1, P3; camera 1 = P2, P4); points are numbered
    1…8 in the book and 0…7 here.
    """
    rng = np.random.default_rng(seed)
    deg = np.pi / 180
    io = InteriorOrientation(f=100.0)
    points = np.array([[1000, 1000, 12.0], [1500, 1000, 15.0], [1000, 1250, 20.0], [1500, 1250, 5.0],
                       [1000, 500, 8.0], [1500, 500, 10.0], [1000, 250, 14.0], [1500, 250, 9.0]])
    kind = np.array([TIE, TIE, CONTROL, CONTROL, TIE, TIE, CONTROL, CONTROL])
    exposures = np.array([[1000, 1000, 1000, 0.5 * deg, 1.0 * deg, 0.3 * deg],
                          [1000, 500, 998, 0.2 * deg, -0.6 * deg, -0.4 * deg]])
    mounts = np.array([[500.0, 3.0, 2.0, -0.9 * deg, -0.2 * deg, 0.2 * deg]])
    from .bundle import rig_image_orientation
    cams = np.vstack([exposures[0], rig_image_orientation(exposures[0], mounts[0], order),
                      exposures[1], rig_image_orientation(exposures[1], mounts[0], order)])
    if not rig:
        cams[1] += [0.0, 0.0, 2.0, -0.9 * deg, -0.2 * deg, 0.5 * deg]    # independent EO for the classic block
        cams[3] += [0.0, 0.0, 3.0, 0.5 * deg, 0.3 * deg, 0.6 * deg]
    visible = {0: [0, 1, 2, 3, 4, 5], 1: [0, 1, 2, 3, 4, 5], 2: [0, 1, 4, 5, 6, 7], 3: [0, 1, 4, 5, 6, 7]}
    image = np.concatenate([np.full(6, j) for j in range(4)])
    point = np.concatenate([visible[j] for j in range(4)])
    xy, _ = project_to_images(cams, image, points[point], io, order)
    xy = xy + rng.normal(0.0, sigma, xy.shape) if sigma > 0 else xy
    return RigBlock(ios=(io, io), order=order, exposures=exposures if rig else cams[[0, 2]],
                    mounts=mounts if rig else np.full((1, 6), np.nan), points=points, kind=kind,
                    exposure_of_image=np.array([0, 0, 1, 1]), camera_of_image=np.array([0, 1, 0, 1]),
                    observations=Observations(image, point, xy), sigma=float(sigma)), cams


def rig_block(n_strips: int = 2, exposures_per_strip: int = 6, *, tilt_deg: float = 40.0, f: float = 50.0,
              frame_size: float = 36.0, flying_height: float = 600.0, forward_overlap: float = 0.7,
              side_overlap: float = 0.5, n_points: int = 600, relief: float = 40.0, sigma: float = 0.003,
              n_control: int = 8, order: str = "kaw", seed: int = 0) -> RigBlock:
    """A Penta-like rig (§3.8, figs. 3.14, 3.16): a nadir camera and four obliques tilted ``tilt_deg``.

    The obliques look forward, back, right and left (tilts about the reference camera's y and x
    axes), with lever arms of 0.1–0.3 m. Points are scattered over the area all cameras see;
    ``n_control`` of them (spread over the block) are control. Seeded.
    """
    check_order(order)
    rng = np.random.default_rng(seed)
    deg = np.pi / 180
    io = InteriorOrientation(f=f)
    foot = frame_size * flying_height / f
    base, spacing = (1 - forward_overlap) * foot, (1 - side_overlap) * foot
    strip = np.repeat(np.arange(n_strips), exposures_per_strip)
    along = np.tile(np.arange(exposures_per_strip), n_strips)
    n = strip.size
    exposures = np.column_stack([along * base + rng.normal(0, 2, n), -strip * spacing + rng.normal(0, 2, n),
                                 150 + flying_height + rng.normal(0, 3, n), rng.normal(0, 1.0 * deg, (n, 3))])
    t = tilt_deg * deg
    mounts = np.array([[0.20, 0.00, -0.05, 0.0, t, 0.0], [-0.20, 0.02, -0.05, 0.0, -t, 0.0],
                       [0.00, 0.25, -0.05, -t, 0.0, 0.0], [0.01, -0.25, -0.05, t, 0.0, 0.0]])
    mounts[:, 3:] += rng.normal(0, 0.3 * deg, (4, 3))
    reach = flying_height * np.tan(t) + foot
    lo = np.array([-reach, -(n_strips - 1) * spacing - reach])
    hi = np.array([(exposures_per_strip - 1) * base + reach, reach])
    xy = rng.uniform(lo, hi, (n_points, 2))
    points = np.column_stack([xy, terrain_height(xy[:, 0], xy[:, 1], 150.0, relief)])
    from .bundle import rig_image_orientation
    n_cam = 5
    e_img = np.repeat(np.arange(n), n_cam)
    c_img = np.tile(np.arange(n_cam), n)
    cams = rig_image_orientation(exposures[e_img], np.vstack([np.zeros((1, 6)), mounts])[c_img], order)
    obs = _observe(cams, points, [io] * cams.shape[0], frame_size / 2 * 0.98, rng, sigma, order)
    count = np.bincount(obs.point, minlength=n_points)
    keep = count >= 2
    new = np.cumsum(keep) - 1
    sel = keep[obs.point]
    obs = Observations(obs.image[sel], new[obs.point[sel]], obs.xy[sel])
    points = points[keep]
    kind = np.full(len(points), TIE)
    centre = np.array([(exposures_per_strip - 1) * base / 2, -(n_strips - 1) * spacing / 2])
    angle = np.arctan2(points[:, 1] - centre[1], points[:, 0] - centre[0])
    far = np.hypot(*(points[:, :2] - centre).T)
    chosen = []
    for sector in range(n_control):
        in_sector = np.flatnonzero(np.floor((angle + np.pi) / (2 * np.pi) * n_control) == sector)
        if in_sector.size:
            chosen.append(in_sector[np.argmax(far[in_sector] * (np.bincount(obs.point, minlength=len(points))[in_sector] >= 3))])
    kind[chosen] = CONTROL
    return RigBlock(ios=tuple([io] * n_cam), order=order, exposures=exposures, mounts=mounts, points=points, kind=kind,
                    exposure_of_image=e_img, camera_of_image=c_img, observations=obs, sigma=float(sigma))


@dataclass(frozen=True)
class RollingShutterBlock:
    """A simulated UAV block with rolling-shutter images (§3.9)."""

    block: SyntheticBlock          # geometry; ``block.cameras`` = EO at the line x = 0
    rates: np.ndarray              # (n, 6) true k₁ … k₆ of (3.9.2)
    observations: Observations     # rolling-shutter measurements


def rolling_shutter_block(n_strips: int = 2, images_per_strip: int = 5, *, speed: float = 10.0,
                          readout: float = 0.03, angular_rate_deg: float = 3.0, sigma: float = 0.0015,
                          points_per_image: int = 60, model: str = "full", seed: int = 0) -> RollingShutterBlock:
    """UAV block (f = 8.8 mm, 13.2 mm sensor, H = 100 m, 80/70 % overlap) shot with a rolling shutter.

    The readout runs along x and takes ``readout`` seconds for the whole sensor, while the UAV
    flies at ``speed`` m/s along X and rotates at up to ``angular_rate_deg`` °/s: the rates k of
    (3.9.2) are these velocities times readout / sensor width (per mm of x). ``model="linear"``
    keeps the angles constant (k₄ = k₅ = k₆ = 0). Observations by
    :func:`photolib.bundle.rolling_shutter_project` plus Gaussian noise σ (mm).
    """
    from .bundle import rolling_shutter_project
    blk = aerial_block(n_strips, images_per_strip, f=8.8, frame_size=13.2, flying_height=100.0, forward_overlap=0.8,
                       side_overlap=0.7, points_per_image=points_per_image, relief=15.0, sigma=0.0,
                       angle_sigma=np.radians(3.0), height_sigma=1.0, n_check=0, seed=seed,
                       control="perimeter", control_interval=2)
    rng = np.random.default_rng(seed + 1)
    n = blk.n_images
    per_mm = readout / blk.frame_size
    rates = np.zeros((n, 6))
    heading = np.where(blk.strip % 2 == 0, 1.0, -1.0)
    rates[:, 0] = heading * speed * per_mm + rng.normal(0, 0.1 * speed * per_mm, n)
    rates[:, 1] = rng.normal(0, 0.1 * speed * per_mm, n)
    rates[:, 2] = rng.normal(0, 0.05 * speed * per_mm, n)
    if model == "full":
        rates[:, 3:] = rng.uniform(-1, 1, (n, 3)) * np.radians(angular_rate_deg) * per_mm
    elif model != "linear":
        raise InputError("model must be 'full' or 'linear'")
    o = blk.observations
    xy = rolling_shutter_project(blk.cameras, rates, blk.points[o.point], blk.io, blk.order, image=o.image)
    xy = xy + rng.normal(0.0, sigma, xy.shape) if sigma > 0 else xy
    return RollingShutterBlock(block=blk, rates=rates, observations=Observations(o.image, o.point, xy))


@dataclass(frozen=True)
class CorridorBlock:
    """A single-strip UAV corridor (§3.9, fig. 3.26) with GNSS centres and a vehicle-borne target."""

    block: SyntheticBlock          # strip geometry; the target points are CONTROL, the road points CHECK
    gnss: np.ndarray               # (n, 3) measured projection centres
    target: np.ndarray             # (n,) index of the dynamic control point seen in image i (−1: none)


def corridor_strip(n_images: int = 16, *, wander: float = 0.5, gnss_sigma: float = 0.03, sigma: float = 0.002,
                   points_per_image: int = 40, with_target: bool = True, seed: int = 0) -> CorridorBlock:
    """A mapKITE-like corridor (§3.9, figs. 3.25/3.26): one UAV strip along a road, GNSS centres only.

    UAV with f = 8.8 mm, 13.2 mm sensor, H = 100 m, 80 % forward overlap. The projection centres
    lie almost on a line (lateral wander ``wander`` m), so GNSS centres alone leave the block
    free to roll about the flight line. With ``with_target`` a vehicle below the UAV carries a
    target whose position (GNSS/INS) is known at every exposure: a new control point in each image.
    """
    blk = aerial_block(1, n_images, f=8.8, frame_size=13.2, flying_height=100.0, forward_overlap=0.8,
                       side_overlap=0.0, points_per_image=points_per_image, relief=8.0, sigma=0.0,
                       angle_sigma=np.radians(2.0), height_sigma=0.3, control=np.zeros((0, 2)), n_check=20,
                       seed=seed)
    rng = np.random.default_rng(seed + 7)
    cams = blk.cameras.copy()
    cams[:, 1] = rng.normal(0.0, wander, n_images)
    pts, kind = blk.points, blk.kind.copy()
    o = blk.observations
    image, point = o.image, o.point
    # re-project with the wandering centres; keep the same visibility
    xy_true, _ = project_to_images(cams, image, pts[point], blk.io, blk.order)
    target = np.full(n_images, -1)
    if with_target:
        tgt = np.column_stack([cams[:, 0] + rng.normal(0, 3.0, n_images), rng.normal(0, 2.0, n_images)])
        tz = terrain_height(tgt[:, 0], tgt[:, 1], 150.0, 8.0) + 1.8          # target on the vehicle roof
        target = len(pts) + np.arange(n_images)
        pts = np.vstack([pts, np.column_stack([tgt, tz])])
        kind = np.concatenate([kind, np.full(n_images, CONTROL)])
        t_xy, _ = project_to_images(cams, np.arange(n_images), pts[target], blk.io, blk.order)
        image = np.concatenate([image, np.arange(n_images)])
        point = np.concatenate([point, target])
        xy_true = np.vstack([xy_true, t_xy])
    xy = xy_true + rng.normal(0.0, sigma, xy_true.shape) if sigma > 0 else xy_true.copy()
    gnss = cams[:, :3] + rng.normal(0.0, gnss_sigma, (n_images, 3))
    from dataclasses import replace
    blk = replace(blk, cameras=cams, points=pts, kind=kind, observations=Observations(image, point, xy),
                  xy_true=xy_true, sigma=float(sigma))
    return CorridorBlock(block=blk, gnss=gnss, target=target)
