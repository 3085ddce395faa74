"""Synthetic blocks with known truth — test data for Chapter 3 (§3.1–§3.9).

The book prints no image coordinates for its phototriangulation examples, so strip, block and
bundle triangulation are demonstrated, tested and benchmarked on simulated blocks. Every
generator returns the one block type :class:`Block` (ground truth, noisy observations, the
simulation settings), whose points carry one :class:`PointKind` each:

* :func:`aerial_block` — strips of vertical frame images over gently rolling terrain with a
  chosen forward and side overlap (60 % / 30 % by default, the layout of fig. 3.13, §3.1, §3.5);
* :func:`footprint_block` — given projection centres and points, the points seen on an image are
  those inside its square footprint (the counting rule of figs. 3.10/3.13, §3.5), optionally as
  the images of a multi-camera rig (§3.8);
* :func:`rig_block` — a Penta-like five-camera rig (§3.8, figs. 3.14, 3.16);
* :func:`rolling_shutter_block` — a UAV block shot with a rolling shutter (§3.9, (3.9.1)/(3.9.2));
* :func:`corridor_strip` — a single-strip UAV corridor with GNSS centres and a moving target
  (§3.9, figs. 3.25/3.26).

For Chapters 5–6 (matching, DSM, DTM) the ground truth is a rendered scene:
:func:`terrain_scene` (ground, buildings, trees, texture → :class:`TerrainScene`) and
:func:`render_image` (z-buffered rendering into a Chapter-1 frame camera → :class:`Rendering`,
with the object point seen by every pixel); :func:`pixel_to_image` / :func:`image_to_pixel`
convert between pixel positions and image coordinates of such a frame.

The camera layout of the regular generators (footprint, base, strip spacing, strip and column
of every image) is one function, :func:`strip_layout`; the regular layouts of §3.2–§3.4 are
:func:`photolib.strip_triangulation.layout_block`. Projections use the collinearity equations
(1.4.12)/(3.5.1). Everything is seeded.

Units as everywhere in photolib: image coordinates and f in mm, object coordinates in metres,
angles in radians.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from enum import IntEnum
from typing import NamedTuple

import numpy as np

from .camera import InteriorOrientation
from .errors import DegenerateGeometryError, InputError, PointBehindCameraError
from .single_image import project_to_images
from .rotation import check_order

__all__ = ["PointKind", "TIE", "CONTROL", "CHECK", "ORIENTATION", "Observations", "Block", "StripLayout",
           "strip_layout", "terrain_height", "footprint_visibility", "aerial_block", "footprint_block",
           "rig_block", "rolling_shutter_block", "corridor_strip", "StereoPair", "stereo_pair",
           "TerrainScene", "terrain_scene", "Rendering", "render_image", "pixel_to_image", "image_to_pixel",
           "MicroFrameCamera", "microframe_camera"]


class PointKind(IntEnum):
    """What a point of a synthetic block is: the one point-kind enumeration of photolib.

    Attributes
    ----------
    TIE : 0
        A tie (pass) point: its coordinates are unknowns of the adjustment.
    CONTROL : 1
        A ground control point: known object coordinates (held fixed (3.5.3) or weighted (3.5.17)).
    CHECK : 2
        A check point: adjusted like a tie point, compared with its truth afterwards (§3.7).
    ORIENTATION : 3
        A relative-orientation point of one model only (not an inter-model tie, §3.2–§3.4).

    References
    ----------
    Chibunichev (2022), §3.2 (tie and orientation points), §3.5 (control, (3.5.3), (3.5.17)),
    §3.7 (check points).

    Examples
    --------
    >>> from photolib.synthetic import PointKind, CONTROL
    >>> PointKind(1) is CONTROL, int(PointKind.CHECK)
    (True, 2)
    """

    TIE = 0
    CONTROL = 1
    CHECK = 2
    ORIENTATION = 3

    @classmethod
    def _missing_(cls, value):
        raise InputError(f"unknown point kind {value!r}; use one of "
                         + ", ".join(f"{k.name} = {k.value}" for k in cls))


TIE, CONTROL, CHECK, ORIENTATION = PointKind.TIE, PointKind.CONTROL, PointKind.CHECK, PointKind.ORIENTATION


def _finite(value, what: str, positive: bool = False, nonnegative: bool = False) -> float:
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise InputError(f"{what} must be a number, got {value!r}") from None
    if not np.isfinite(v) or (positive and not v > 0) or (nonnegative and not v >= 0):
        raise InputError(f"{what} must be a finite{' positive' if positive else ''}"
                         f"{' non-negative' if nonnegative else ''} number, got {value!r}")
    return v


def _count(value, what: str, minimum: int) -> int:
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)):
        if not (isinstance(value, (float, np.floating)) and float(value).is_integer()):
            raise InputError(f"{what} must be an integer, got {value!r}")
    if int(value) < minimum:
        raise InputError(f"{what} must be at least {minimum}, got {value!r}")
    return int(value)


@dataclass(frozen=True, eq=False)
class Observations:
    """Image measurements: point ``point[k]`` measured at ``xy[k]`` (mm) on image ``image[k]``.

    Parameters
    ----------
    image, point : (m,) int arrays
        Image and point index of every measurement (non-negative).
    xy : (m, 2) float array
        Measured image coordinates x, y in mm (finite).

    Raises
    ------
    InputError
        Shapes that do not match, negative or non-integer indices, NaN or inf coordinates.

    References
    ----------
    Chibunichev (2022), §3.5: the measured x, y of (3.5.1)/(3.5.2), image by image (fig. 3.11).

    Examples
    --------
    >>> from photolib.synthetic import Observations
    >>> obs = Observations([0, 0, 1], [0, 1, 0], [[1.0, 2.0], [3.0, 4.0], [5.0, 6.0]])
    >>> len(obs), obs
    (3, Observations(3 measurements of 2 points on 2 images))
    """

    image: np.ndarray      # (m,) int
    point: np.ndarray      # (m,) int
    xy: np.ndarray         # (m, 2) float, mm

    def __post_init__(self):
        idx = {}
        for name in ("image", "point"):
            raw = np.asarray(getattr(self, name))
            if raw.ndim != 1:
                raise InputError(f"observations: {name} must be a 1-D array of indices, got shape {raw.shape}")
            if raw.size and (raw.dtype.kind not in "iu" and not (raw.dtype.kind == "f"
                                                                 and np.all(np.isfinite(raw))
                                                                 and np.all(raw == np.round(raw)))):
                raise InputError(f"observations: {name} indices must be integers")
            arr = raw.astype(np.intp)
            if arr.size and arr.min() < 0:
                raise InputError(f"observations: negative {name} index")
            idx[name] = arr
        try:
            xy = np.asarray(self.xy, dtype=float)
        except (TypeError, ValueError):
            raise InputError("observations: xy must be numbers") from None
        if xy.size == 0:
            xy = xy.reshape(0, 2)
        if xy.ndim != 2 or xy.shape[1] != 2:
            raise InputError(f"observations: xy must have shape (m, 2), got {xy.shape}")
        if not (len(idx["image"]) == len(idx["point"]) == len(xy)):
            raise InputError(f"observations: {len(idx['image'])} image indices, {len(idx['point'])} point "
                             f"indices and {len(xy)} coordinate pairs")
        if not np.all(np.isfinite(xy)):
            raise InputError("observations: xy contain NaN or inf")
        object.__setattr__(self, "image", idx["image"])
        object.__setattr__(self, "point", idx["point"])
        object.__setattr__(self, "xy", xy)

    def __len__(self) -> int:
        return int(self.image.shape[0])

    def __repr__(self) -> str:
        return (f"Observations({len(self)} measurements of {np.unique(self.point).size} points "
                f"on {np.unique(self.image).size} images)")


class StripLayout(NamedTuple):
    """The camera layout of a regular block: see :func:`strip_layout`.

    Attributes
    ----------
    footprint : float
        Side L of the square ground footprint of an image, m.
    base : float
        Photo base b = (1 − p)·L, m.
    spacing : float
        Distance between strip axes (1 − q)·L, m.
    strip, column : (n,) int arrays
        Strip and position in the strip of every image (strip by strip).

    References
    ----------
    Chibunichev (2022), §3.1 and §3.7 (forward overlap p ≥ 60 %, side overlap q ≥ 30 %).

    Examples
    --------
    >>> from photolib.synthetic import StripLayout
    >>> StripLayout(1000.0, 400.0, 700.0, [0, 0], [0, 1]).base
    400.0
    """

    footprint: float
    base: float
    spacing: float
    strip: np.ndarray
    column: np.ndarray


def strip_layout(n_strips: int, images_per_strip: int, *, f: float, frame_size: float, flying_height: float,
                 forward_overlap: float, side_overlap: float) -> StripLayout:
    """Footprint, base, strip spacing and the strip/column of every image of a regular block.

    The one layout arithmetic of the synthetic generators: strips run along X and are stacked
    along −Y; images are numbered strip by strip.

    Parameters
    ----------
    n_strips, images_per_strip : int
        Block size (at least one strip of one image).
    f, frame_size : float
        Focal length and side of the square image format, mm.
    flying_height : float
        Height above the terrain, m; the footprint is L = frame_size · flying_height / f.
    forward_overlap, side_overlap : float
        Overlaps as fractions: p in (0, 1), q in [0, 1).

    Returns
    -------
    StripLayout
        ``footprint``, ``base`` = (1 − p)L, ``spacing`` = (1 − q)L, ``strip``, ``column``.

    Raises
    ------
    InputError
        Non-positive or non-finite sizes, overlaps outside their range, too few images.

    References
    ----------
    Chibunichev (2022), §3.1 (layout of strips), §3.7 (overlaps of the Instruction, 3.1.1).

    Examples
    --------
    >>> from photolib.synthetic import strip_layout
    >>> lay = strip_layout(2, 3, f=100.0, frame_size=100.0, flying_height=1000.0,
    ...                    forward_overlap=0.6, side_overlap=0.3)
    >>> lay.footprint, lay.base, lay.spacing, lay.strip.tolist(), lay.column.tolist()
    (1000.0, 400.0, 700.0, [0, 0, 0, 1, 1, 1], [0, 1, 2, 0, 1, 2])
    """
    n_strips = _count(n_strips, "n_strips", 1)
    images_per_strip = _count(images_per_strip, "images_per_strip", 1)
    f = _finite(f, "f", positive=True)
    frame_size = _finite(frame_size, "frame_size", positive=True)
    flying_height = _finite(flying_height, "flying_height", positive=True)
    p = _finite(forward_overlap, "forward_overlap")
    q = _finite(side_overlap, "side_overlap")
    if not (0 < p < 1 and 0 <= q < 1):
        raise InputError("overlaps must be fractions: forward in (0, 1), side in [0, 1)")
    footprint = frame_size * flying_height / f
    strip = np.repeat(np.arange(n_strips), images_per_strip)
    column = np.tile(np.arange(images_per_strip), n_strips)
    return StripLayout(footprint, (1 - p) * footprint, (1 - q) * footprint, strip, column)


def footprint_visibility(points_xy, centres_xy, footprint: float) -> np.ndarray:
    """Which points lie strictly inside the square footprint of which image (vertical images).

    The footprint of side ``footprint`` is centred on the nadir (X_S, Y_S); a point on its edge
    is not measured. This is the counting rule of the rebuilt figs. 3.10/3.13.

    Parameters
    ----------
    points_xy : (k, 2) array
        X, Y of the points, m.
    centres_xy : (n, 2) array
        X_S, Y_S of the projection centres, m.
    footprint : float
        Side L of the footprint, m.

    Returns
    -------
    (k, n) bool array
        ``True`` where point j is inside the footprint of image i.

    Raises
    ------
    InputError
        NaN/inf or wrong shapes, a non-positive footprint.

    References
    ----------
    Chibunichev (2022), §3.5, figs. 3.10 and 3.13 (images per point).

    Examples
    --------
    >>> from photolib.synthetic import footprint_visibility
    >>> footprint_visibility([[0, 0], [400, 0], [700, 0]], [[0, 0], [500, 0]], 1000.0).astype(int)
    array([[1, 0],
           [1, 1],
           [0, 1]])
    """
    from .camera import as_points
    p = as_points(points_xy, 2, "points_xy") if np.size(points_xy) else np.zeros((0, 2))
    c = as_points(centres_xy, 2, "centres_xy")
    footprint = _finite(footprint, "footprint", positive=True)
    d = np.abs(p[:, None, :] - c[None, :, :])
    return np.all(d < footprint / 2 * (1 - 1e-9), axis=2)


_NAN = float("nan")


@dataclass(frozen=True, eq=False, repr=False)
class Block:
    """A simulated block: ground truth, observations and the simulation settings — photolib's one block type.

    The variants are optional fields: a multi-camera rig (§3.8) sets ``ios``, ``exposures``,
    ``mounts``, ``exposure_of_image``, ``camera_of_image``; a rolling-shutter block (§3.9) sets
    ``rates``; a corridor (§3.9) sets ``gnss`` and ``target``; a rebuild of a book figure sets
    ``name``, ``image_labels``, ``point_labels`` and ``grid``; a regular layout of §3.2–§3.4 sets
    ``column`` and ``grid_position``.

    Parameters
    ----------
    io : InteriorOrientation
        The camera (of camera 0 for a rig).
    order : {"kaw", "wak"}
        Rotation order of the angles.
    cameras : (n, 6) array
        True X_S, Y_S, Z_S, ω, α, κ of every image.
    points : (k, 3) array
        True X, Y, Z.
    kind : (k,) array of PointKind
        TIE, CONTROL, CHECK or ORIENTATION.
    observations : Observations
        The (noisy) measurements.
    xy_true : (m, 2) array, optional
        The noise-free measurements.
    sigma : float
        Image noise σ, mm.
    strip, column : (n,) int arrays, optional
        Strip and position in the strip of every image.
    frame_size, footprint, base, strip_spacing : float
        Image format (mm), footprint side, photo base, distance of strip axes (m).
    name : str
        A name, e.g. "fig3.10".
    image_labels, point_labels : tuple, optional
        Labels of the images and points (default: their indices).
    grid : (rows, cols), optional
        The points form a grid of this shape (fig. 3.13).
    grid_position : (k, 2) array, optional
        (column, row) of each point in base / strip-spacing units (regular layouts).
    control_sigma : float, optional
        None: control is held fixed (3.5.3); else its coordinates are weighted (3.5.17), m.
    gnss : (n, 3) array, optional
        Measured projection centres (3.5.18), m (NaN rows: not measured).
    gnss_sigma : float
        Their accuracy, m.
    noise_seed : int
        Seed of the noise of weighted control coordinates.
    start_sigma : (3,) tuple
        Default spread of :meth:`start_values`: centres (m), angles (rad), points (m).
    ios, exposures, mounts, exposure_of_image, camera_of_image : optional
        Rig (§3.8): camera per rig camera, reference EO per exposure, mounting elements of cameras
        1 … n_s − 1 (B_X, B_Y, B_Z, ω′, α′, κ′), exposure and camera of every image.
    rates : (n, 6) array, optional
        Rolling shutter (§3.9): k₁ … k₆ of (3.9.2) per image.
    target : (n,) int array, optional
        Corridor (§3.9): the dynamic control point seen on image i (−1: none).

    Raises
    ------
    InputError
        Wrong shapes, NaN/inf in the truth, observations of non-existent images or points.

    References
    ----------
    Chibunichev (2022), §3.5 (bundle block, (3.5.1)–(3.5.3), (3.5.17)–(3.5.19)), §3.8 ((3.8.5),
    (3.8.8)), §3.9 ((3.9.1)/(3.9.2)).

    Examples
    --------
    >>> from photolib.synthetic import aerial_block
    >>> blk = aerial_block(1, 3, points_per_image=8, n_check=0, seed=0)
    >>> blk.n_images, blk.cameras.shape
    (3, (3, 6))
    >>> blk                                    # doctest: +ELLIPSIS
    Block(3 images, ... points (... tie, ... control), ... measurements, σ = 5 µm, order kaw)
    """

    io: InteriorOrientation
    order: str
    cameras: np.ndarray
    points: np.ndarray
    kind: np.ndarray
    observations: Observations
    xy_true: np.ndarray | None = None
    sigma: float = 0.0
    strip: np.ndarray | None = None
    column: np.ndarray | None = None
    frame_size: float = _NAN
    footprint: float = _NAN
    base: float = _NAN
    strip_spacing: float = _NAN
    name: str = ""
    image_labels: tuple | None = None
    point_labels: tuple | None = None
    grid: tuple | None = None
    grid_position: np.ndarray | None = None
    control_sigma: float | None = None
    gnss: np.ndarray | None = None
    gnss_sigma: float = _NAN
    noise_seed: int = 0
    start_sigma: tuple = (5.0, float(np.radians(0.5)), 5.0)
    ios: tuple | None = None
    exposures: np.ndarray | None = None
    mounts: np.ndarray | None = None
    exposure_of_image: np.ndarray | None = None
    camera_of_image: np.ndarray | None = None
    rates: np.ndarray | None = None
    target: np.ndarray | None = None

    def __post_init__(self):
        from .camera import as_points
        if not isinstance(self.io, InteriorOrientation):
            raise InputError(f"io must be an InteriorOrientation, got {type(self.io).__name__}")
        check_order(self.order)
        cams = np.asarray(self.cameras, dtype=float)
        if cams.ndim != 2 or cams.shape[1] != 6 or not np.all(np.isfinite(cams)):
            raise InputError(f"cameras: expected a finite (n, 6) array, got shape {cams.shape}")
        pts = as_points(self.points, 3, "points") if np.size(self.points) else np.zeros((0, 3))
        kind = np.asarray(self.kind)
        if kind.shape != (len(pts),):
            raise InputError(f"kind: expected {len(pts)} point kinds, got shape {kind.shape}")
        for k in np.unique(kind):
            PointKind(int(k))
        if not isinstance(self.observations, Observations):
            raise InputError("observations must be photolib.synthetic.Observations")
        o = self.observations
        if len(o) and (o.image.max() >= len(cams) or o.point.max() >= len(pts)):
            raise InputError("observations refer to images or points the block does not have")
        object.__setattr__(self, "cameras", cams)
        object.__setattr__(self, "points", pts)
        object.__setattr__(self, "kind", kind)
        if self.image_labels is None:
            object.__setattr__(self, "image_labels", tuple(str(i) for i in range(len(cams))))
        if self.point_labels is None:
            object.__setattr__(self, "point_labels", tuple(range(len(pts))))
        if self.gnss is not None and np.shape(self.gnss) != (len(cams), 3):
            raise InputError(f"gnss: expected ({len(cams)}, 3), got {np.shape(self.gnss)}")

    # --- summary ---------------------------------------------------------------------------------
    def __repr__(self) -> str:
        counts = ", ".join(f"{int(np.sum(self.kind == k))} {k.name.lower()}" for k in PointKind
                           if np.any(self.kind == k))
        head = f"'{self.name}': " if self.name else ""
        extra = []
        if self.ios is not None:
            extra.append(f"rig of {len(self.ios)} cameras, {len(self.exposures)} exposures")
        if self.rates is not None:
            extra.append("rolling shutter")
        if self.gnss is not None:
            extra.append(f"GNSS centres σ = {self.gnss_sigma * 100:g} cm")
        if self.control_sigma is not None:
            extra.append(f"weighted control σ = {self.control_sigma * 100:g} cm")
        return (f"Block({head}{self.n_images} images, {len(self.points)} points ({counts}), "
                f"{len(self.observations)} measurements, σ = {self.sigma * 1000:g} µm, order {self.order}"
                + "".join(f"; {e}" for e in extra) + ")")

    # --- views -----------------------------------------------------------------------------------
    @property
    def n_images(self) -> int:
        """Number of images n."""
        return self.cameras.shape[0]

    @property
    def block(self) -> "Block":
        """The block itself (the former wrapper classes had a ``block`` attribute)."""
        return self

    @property
    def control(self) -> np.ndarray:
        """Indices of the control points."""
        return np.flatnonzero(self.kind == CONTROL)

    @property
    def check(self) -> np.ndarray:
        """Indices of the check points."""
        return np.flatnonzero(self.kind == CHECK)

    @property
    def unknown_points(self) -> np.ndarray:
        """Indices of the points that are unknowns (all of them when control is weighted)."""
        if self.control_sigma is not None:
            return np.arange(len(self.points))
        return np.flatnonzero(self.kind != CONTROL)

    @property
    def visibility(self) -> np.ndarray:
        """(k, n) bool: point j is measured on image i."""
        vis = np.zeros((len(self.points), self.n_images), bool)
        vis[self.observations.point, self.observations.image] = True
        return vis

    @property
    def image_cameras(self) -> np.ndarray:
        """True EO of every image ((3.8.5)/(3.8.8) for a rig): the same as ``cameras``."""
        return self.cameras

    @property
    def sigma0(self) -> float:
        """Unit-weight σ₀ of (3.5.7): the image noise σ, or 0.005 mm for a noise-free block."""
        return self.sigma if self.sigma > 0 else 0.005

    def measurements(self, image: int):
        """(labels, xy) of the points measured on ``image``, in point order."""
        if not 0 <= int(image) < self.n_images:
            raise InputError(f"no image {image} in a block of {self.n_images}")
        sel = np.flatnonzero(self.observations.image == int(image))
        sel = sel[np.argsort(self.observations.point[sel], kind="stable")]
        return np.asarray(self.point_labels)[self.observations.point[sel]], self.observations.xy[sel]

    def truth(self, ids) -> np.ndarray:
        """True object coordinates of point labels and centre ids ("S<k>")."""
        index = {p: i for i, p in enumerate(self.point_labels)}
        out = []
        for p in ids:
            if isinstance(p, str) and p.startswith("S") and p[1:].isdigit():
                out.append(self.cameras[int(p[1:]), :3])
            elif p in index:
                out.append(self.points[index[p]])
            else:
                raise InputError(f"the block has no point {p!r}")
        return np.array(out).reshape(-1, 3)

    def images_of_strip(self, s: int) -> np.ndarray:
        """Images of strip ``s`` in flight order."""
        if self.strip is None:
            raise InputError("the block has no strips")
        sel = self.strip == s
        order = np.argsort(self.column[sel]) if self.column is not None else np.arange(sel.sum())
        return np.flatnonzero(sel)[order]

    def point_at(self, column: float, row: float):
        """Label of the point at grid position (column, row) of a regular layout."""
        if self.grid_position is None:
            raise InputError("the block has no grid positions")
        hit = np.flatnonzero(np.all(np.isclose(self.grid_position, [column, row]), axis=1))
        if hit.size != 1:
            raise InputError(f"no point at grid position ({column}, {row})")
        return self.point_labels[hit[0]]

    # --- simulation helpers ----------------------------------------------------------------------
    @property
    def orientations(self):
        """The true exterior orientations as one vectorised collection carrying the order."""
        from .camera import ExteriorOrientations
        return ExteriorOrientations.from_vectors(self.cameras, order=self.order)

    def control_values(self) -> dict:
        """{point index: measured (X, Y, Z)}: the truth (fixed control) or truth + seeded noise."""
        if self.control_sigma is None:
            return {int(i): self.points[i].copy() for i in self.control}
        rng = np.random.default_rng(self.noise_seed)
        noise = rng.normal(0.0, self.control_sigma, (self.control.size, 3))
        return {int(i): self.points[i] + e for i, e in zip(self.control, noise)}

    def start_values(self, seed: int = 1, centre_sigma: float | None = None, angle_sigma: float | None = None,
                     point_sigma: float | None = None):
        """Seeded approximations: the truth perturbed by Gaussian errors (m, rad, m).

        Control points start at their measured values (:meth:`control_values`). The spreads
        default to ``start_sigma``. Returns ``(cameras0, points0)``.
        """
        cs, as_, ps = (d if v is None else v for v, d in zip((centre_sigma, angle_sigma, point_sigma),
                                                              self.start_sigma))
        rng = np.random.default_rng(seed)
        cams = self.cameras.copy()
        cams[:, :3] += rng.normal(0.0, cs, (self.n_images, 3))
        cams[:, 3:] += rng.normal(0.0, as_, (self.n_images, 3))
        pts = self.points + rng.normal(0.0, ps, self.points.shape)
        for i, xyz in self.control_values().items():
            pts[i] = xyz
        return cams, pts

    def with_noise(self, seed: int) -> "Block":
        """The same geometry with a new seeded realisation of the image noise, the GNSS centres and
        the (weighted) control coordinates."""
        if self.xy_true is None:
            raise InputError("the block keeps no noise-free measurements")
        rng = np.random.default_rng(seed)
        o = self.observations
        obs = Observations(o.image, o.point, self.xy_true + rng.normal(0.0, self.sigma, self.xy_true.shape))
        gnss = None if self.gnss is None else self.cameras[:, :3] + rng.normal(0.0, self.gnss_sigma, (self.n_images, 3))
        return replace(self, observations=obs, gnss=gnss, noise_seed=int(rng.integers(2**31)))

    def adjust(self, seed: int = 1, **kwargs):
        """Adjust the block by :func:`photolib.bundle.bundle_adjustment` from seeded start values.

        Control is held fixed (3.5.3) or weighted (3.5.17) as the block says; GNSS centres (3.5.18)
        are used when the block has them. ``kwargs`` go to ``bundle_adjustment``.
        """
        from .bundle import bundle_adjustment
        cams0, pts0 = self.start_values(seed)
        args = dict(control=self.control_values(), control_sigma=self.control_sigma, sigma_image=self.sigma0,
                    order=self.order, covariance=True)
        if self.gnss is not None:
            args.update(gnss=self.gnss, gnss_sigma=self.gnss_sigma)
        args.update(kwargs)
        return bundle_adjustment(self.observations, cams0, pts0, self.io, **args)


def terrain_height(X, Y, mean: float = 150.0, relief: float = 30.0, wavelength: float = 3000.0):
    """A smooth synthetic terrain: mean height plus two crossing sine waves of amplitude ``relief``/2.

    Parameters
    ----------
    X, Y : array_like
        Object coordinates, m (broadcast against each other).
    mean, relief, wavelength : float
        Mean height, amplitude scale and wavelength of the waves, m.

    Returns
    -------
    ndarray
        Heights Z, m.

    Raises
    ------
    InputError
        NaN/inf coordinates or parameters, a non-positive wavelength.

    References
    ----------
    Chibunichev (2022), §3.5 (the terrain of the simulated blocks; not a formula of the book).

    Examples
    --------
    >>> from photolib.synthetic import terrain_height
    >>> float(terrain_height(0.0, 0.0))
    150.0
    """
    try:
        X, Y = np.asarray(X, dtype=float), np.asarray(Y, dtype=float)
    except (TypeError, ValueError):
        raise InputError("X, Y must be numbers") from None
    if not (np.all(np.isfinite(X)) and np.all(np.isfinite(Y))):
        raise InputError("X, Y contain NaN or inf")
    mean, relief = _finite(mean, "mean"), _finite(relief, "relief")
    k = 2 * np.pi / _finite(wavelength, "wavelength", positive=True)
    return mean + 0.5 * relief * (np.sin(k * X) * np.cos(0.7 * k * Y) + np.sin(0.45 * k * (X + Y)))


def aerial_block(n_strips: int = 2, images_per_strip: int = 5, *, f: float = 100.0, frame_size: float = 100.0,
                 flying_height: float = 1000.0, forward_overlap: float = 0.6, side_overlap: float = 0.3,
                 points_per_image: int = 30, relief: float = 30.0, sigma: float = 0.005,
                 angle_sigma: float = np.radians(1.0), height_sigma: float = 5.0,
                 control: str | np.ndarray = "perimeter", control_interval: int = 4, n_check: int = 10,
                 order: str = "kaw", seed: int = 0, io: InteriorOrientation | None = None,
                 strip_heights=None) -> Block:
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
    control_interval : int
        Spacing of the perimeter control, in bases.
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
        laid out for ``flying_height``). Different heights help self-calibration separate f from Z_S
        only together with GNSS centres or relief: over flat ground each image's Z_S absorbs a
        change of f whatever its height.

    Returns
    -------
    Block
        With ``strip``, ``column``, ``frame_size``, ``footprint``, ``base`` and ``strip_spacing``.

    Raises
    ------
    InputError
        Fewer than one strip of two images, overlaps outside (0, 1), NaN/inf or non-positive sizes,
        a negative σ, an unknown control layout or rotation order.

    References
    ----------
    Chibunichev (2022), §3.1 (layout), §3.5 (collinearity (3.5.1), fig. 3.13: 60 %/30 % overlap),
    §3.6 (distortion (1.2.2)/(3.6.2)).

    Examples
    --------
    >>> from photolib.synthetic import aerial_block, CHECK
    >>> blk = aerial_block(2, 4, points_per_image=12, n_check=3, seed=3)
    >>> blk.n_images, blk.base, blk.strip_spacing, int((blk.kind == CHECK).sum())
    (8, 400.0, 700.0, 3)
    """
    check_order(order)
    if _count(n_strips, "n_strips", 1) < 1 or _count(images_per_strip, "images_per_strip", 0) < 2:
        raise InputError("a block needs at least one strip of two images")
    if not (0 < _finite(forward_overlap, "forward_overlap") < 1 and 0 <= _finite(side_overlap, "side_overlap") < 1):
        raise InputError("overlaps must be fractions in (0, 1)")
    sigma = _finite(sigma, "sigma", nonnegative=True)
    points_per_image = _finite(points_per_image, "points_per_image", positive=True)
    relief = _finite(relief, "relief")
    angle_sigma = _finite(angle_sigma, "angle_sigma", nonnegative=True)
    height_sigma = _finite(height_sigma, "height_sigma", nonnegative=True)
    n_check = _count(n_check, "n_check", 0)
    rng = np.random.default_rng(seed)
    if io is not None and not isinstance(io, InteriorOrientation):
        raise InputError(f"io must be an InteriorOrientation, got {type(io).__name__}")
    camera = io if io is not None else InteriorOrientation(f=f)
    io = InteriorOrientation(f=camera.f, x0=camera.x0, y0=camera.y0)    # ideal projection
    f = camera.f
    if strip_heights is None:
        heights = np.full(n_strips, _finite(flying_height, "flying_height", positive=True))
    else:
        try:
            heights = np.asarray(strip_heights, dtype=float)
        except (TypeError, ValueError):
            raise InputError("strip_heights must be numbers") from None
    if heights.shape != (n_strips,) or np.any(~(heights > 0)) or not np.all(np.isfinite(heights)):
        raise InputError(f"strip_heights: give {n_strips} positive flying heights")
    lay = strip_layout(n_strips, images_per_strip, f=f, frame_size=frame_size, flying_height=flying_height,
                       forward_overlap=forward_overlap, side_overlap=side_overlap)
    footprint, base, spacing, strip, along = lay
    mean_height = 150.0

    # projection centres and angles
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
            step = max(1, _count(control_interval, "control_interval", 1))
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
        try:
            ctrl_xy = np.asarray(control, dtype=float)
        except (TypeError, ValueError):
            raise InputError("control must be a layout name or an (c, 2) array of X, Y") from None
        if ctrl_xy.ndim != 2 or ctrl_xy.shape[1] != 2 or not np.all(np.isfinite(ctrl_xy)):
            raise InputError("control must be a layout name or a finite (c, 2) array of X, Y")
    all_xy = np.vstack([tie_xy, ctrl_xy])
    points = np.column_stack([all_xy, terrain_height(all_xy[:, 0], all_xy[:, 1], mean_height, relief)])
    kind = np.concatenate([np.full(n_tie, TIE), np.full(len(ctrl_xy), CONTROL)]).astype(int)

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
    return Block(io=camera, order=order, cameras=cameras, points=points, kind=kind,
                 observations=Observations(image_idx, point_idx, xy), xy_true=xy_true, sigma=float(sigma),
                 strip=strip, column=along, frame_size=float(frame_size), footprint=float(footprint),
                 base=float(base), strip_spacing=float(spacing))


def _relative_mount(reference, other, order):
    """Mounting elements (B, ω′, α′, κ′) that carry the reference EO to ``other`` ((3.8.5), (3.8.8) inverted)."""
    from .rotation import rotation_angles, rotation_matrix
    A1 = rotation_matrix(*reference[3:], order)
    A2 = rotation_matrix(*other[3:], order)
    return np.concatenate([A1.T @ (other[:3] - reference[:3]), rotation_angles(A1.T @ A2, order)])


def footprint_block(centres_xy, points_xy, kind, *, f: float = 100.0, frame_size: float = 125.0,
                    flying_height: float = 1000.0, sigma: float = 0.005, seed: int = 0, order: str = "kaw",
                    control_sigma: float | None = None, gnss_sigma: float | None = None, name: str = "",
                    image_labels=None, point_labels=None, grid=None, at_principal=None,
                    angle_sigma: float = np.radians(1.0), relief: float = 15.0, camera_of_image=None,
                    exposure_of_image=None, base: float = _NAN, strip_spacing: float = _NAN,
                    start_sigma=(10.0, float(np.radians(1.0)), 10.0)) -> Block:
    """A block of near-vertical images whose points are measured where they lie inside a footprint.

    The projection centres are at ``centres_xy`` and height ``flying_height`` (seeded spread
    5 m), the angles are seeded (σ = ``angle_sigma``), the terrain heights uniform in 5 … 5 +
    ``relief`` m. A point is measured on every image whose square footprint L = frame · H / f
    contains it strictly (:func:`footprint_visibility`); observations are ordered image by image
    (fig. 3.11) and projected by the collinearity equations (3.5.1).

    Parameters
    ----------
    centres_xy : (n, 2) array
        Nadirs X_S, Y_S of the images, m.
    points_xy : (k, 2) array
        X, Y of the points, m.
    kind : (k,) sequence of PointKind
        TIE, CONTROL or CHECK of every point.
    f, frame_size, flying_height : float
        Focal length and format (mm), flying height (m).
    sigma : float
        Image noise σ, mm (0: exact).
    seed : int
        Seed of the whole simulation.
    order : {"kaw", "wak"}
        Rotation order.
    control_sigma : float, optional
        None: control held fixed (3.5.3); else weighted (3.5.17), σ in m.
    gnss_sigma : float, optional
        If given, every projection centre is measured by GNSS with this σ (3.5.18), m.
    name, image_labels, point_labels, grid
        Stored in the block (labels default to P1, P2, … and 1, 2, …).
    at_principal : dict {point: image}, optional
        Points placed where the optical axis of that image meets the terrain (the principal
        point, "-ф-" in the figures), not exactly below S where some derivatives vanish.
    angle_sigma, relief : float
        Spread of the true angles (rad) and of the terrain heights (m).
    camera_of_image, exposure_of_image : (n,) int arrays, optional
        The images are the exposures of a rig (§3.8): the mounting of camera c is that of the first
        exposure (from its seeded EO), and every other image of camera c follows from its exposure's
        camera-0 image by (3.8.5)/(3.8.8).
    base, strip_spacing : float
        Stored in the block (m).
    start_sigma : (3,) tuple
        Default spread of :meth:`Block.start_values`.

    Returns
    -------
    Block

    Raises
    ------
    InputError
        NaN/inf or wrong shapes, a negative σ, a point that projects outside the frame, a rig
        without a reference camera in every exposure.

    References
    ----------
    Chibunichev (2022), §3.5, figs. 3.10, 3.11, 3.13; §3.8 ((3.8.5), (3.8.8), fig. 3.18).

    Examples
    --------
    >>> from photolib.synthetic import footprint_block, TIE, CONTROL
    >>> blk = footprint_block([[0, 0], [500, 0]], [[0, 0], [500, 0], [250, 300]], [TIE, TIE, CONTROL])
    >>> blk.visibility.sum(axis=0).tolist(), len(blk.observations)
    ([3, 3], 6)
    """
    from .camera import as_points
    from .rotation import rotation_matrix
    check_order(order)
    sigma = _finite(sigma, "sigma", nonnegative=True)
    f = _finite(f, "f", positive=True)
    frame_size = _finite(frame_size, "frame_size", positive=True)
    flying_height = _finite(flying_height, "flying_height", positive=True)
    angle_sigma = _finite(angle_sigma, "angle_sigma", nonnegative=True)
    relief = _finite(relief, "relief", nonnegative=True)
    if control_sigma is not None:
        control_sigma = _finite(control_sigma, "control_sigma", positive=True)
    if gnss_sigma is not None:
        gnss_sigma = _finite(gnss_sigma, "gnss_sigma", nonnegative=True)
    centres_xy = as_points(centres_xy, 2, "centres_xy")
    points_xy = as_points(points_xy, 2, "points_xy").copy()
    kind = np.array([int(PointKind(int(k))) for k in np.asarray(kind).ravel()], dtype=int)
    if kind.shape != (len(points_xy),):
        raise InputError(f"kind: expected {len(points_xy)} point kinds, got {kind.shape[0]}")
    rng = np.random.default_rng(seed)
    io = InteriorOrientation(f=f)
    footprint = frame_size * flying_height / f
    n = len(centres_xy)
    cameras = np.empty((n, 6))
    cameras[:, :2] = centres_xy
    cameras[:, 2] = flying_height + rng.normal(0.0, 5.0, n)
    cameras[:, 3:] = rng.normal(0.0, angle_sigma, (n, 3))
    Z = 5.0 + relief * rng.uniform(0.0, 1.0, len(points_xy))
    rig = {}
    if camera_of_image is not None or exposure_of_image is not None:
        c_img = np.asarray(camera_of_image, dtype=int).reshape(-1)
        e_img = np.asarray(exposure_of_image, dtype=int).reshape(-1)
        if c_img.shape != (n,) or e_img.shape != (n,) or c_img.min() < 0 or e_img.min() < 0:
            raise InputError(f"camera_of_image and exposure_of_image: give {n} non-negative indices each")
        ref = {int(e): i for i, (e, c) in enumerate(zip(e_img, c_img)) if c == 0}
        if set(ref) != set(e_img.tolist()):
            raise InputError("every exposure of the rig needs an image of the reference camera 0")
        n_cam = int(c_img.max()) + 1
        mounts = np.empty((n_cam - 1, 6))
        for c in range(1, n_cam):
            first = np.flatnonzero(c_img == c)
            if first.size == 0:
                raise InputError(f"rig camera {c} has no image")
            i = int(first[0])
            mounts[c - 1] = _relative_mount(cameras[ref[int(e_img[i])]], cameras[i], order)
        from .bundle import rig_image_orientation
        for i in np.flatnonzero(c_img > 0):
            cameras[i] = rig_image_orientation(cameras[ref[int(e_img[i])]], mounts[c_img[i] - 1], order)
        rig = dict(ios=(io,) * n_cam, exposures=cameras[[ref[e] for e in sorted(ref)]].copy(), mounts=mounts,
                   exposure_of_image=e_img, camera_of_image=c_img)
    for j, i in (at_principal or {}).items():
        axis = rotation_matrix(*cameras[i, 3:], order) @ np.array([0.0, 0.0, -1.0])
        points_xy[j] = cameras[i, :2] + (Z[j] - cameras[i, 2]) / axis[2] * axis[:2]
    vis = footprint_visibility(points_xy, centres_xy, footprint)
    points = np.column_stack([points_xy, Z])
    point_idx, image_idx = np.nonzero(vis)
    order_obs = np.lexsort((point_idx, image_idx))                    # image by image, as in fig. 3.11
    image_idx, point_idx = image_idx[order_obs], point_idx[order_obs]
    xy_true, z_star = project_to_images(cameras, image_idx, points[point_idx], io, order)
    if np.any(z_star >= 0):
        raise InputError(f"{name or 'block'}: a point is not in front of its image")
    if np.any(np.abs(xy_true) >= frame_size / 2):
        raise InputError(f"{name or 'block'}: a projected point falls outside the {frame_size:g} mm frame; "
                         "reduce the tilts")
    xy = xy_true + rng.normal(0.0, sigma, xy_true.shape) if sigma > 0 else xy_true.copy()
    gnss = None
    if gnss_sigma is not None:
        gnss = cameras[:, :3] + rng.normal(0.0, gnss_sigma, (n, 3))
    image_labels = tuple(image_labels) if image_labels is not None else tuple(f"P{i + 1}" for i in range(n))
    point_labels = tuple(point_labels) if point_labels is not None else tuple(str(j + 1) for j in range(len(points)))
    return Block(io=io, order=order, cameras=cameras, points=points, kind=kind,
                 observations=Observations(image_idx, point_idx, xy), xy_true=xy_true, sigma=float(sigma),
                 frame_size=frame_size, footprint=footprint, base=float(base), strip_spacing=float(strip_spacing),
                 name=name, image_labels=image_labels, point_labels=point_labels, grid=grid,
                 control_sigma=control_sigma, gnss=gnss, gnss_sigma=_NAN if gnss_sigma is None else float(gnss_sigma),
                 noise_seed=int(seed) + 101, start_sigma=tuple(start_sigma), **rig)


# --- Chapter 3, §3.8–§3.9: rigs, rolling shutter, corridors ----------------------------------------
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
    return image_idx, point_idx, xy, noisy


def rig_block(n_strips: int = 2, exposures_per_strip: int = 6, *, tilt_deg: float = 40.0, f: float = 50.0,
              frame_size: float = 36.0, flying_height: float = 600.0, forward_overlap: float = 0.7,
              side_overlap: float = 0.5, n_points: int = 600, relief: float = 40.0, sigma: float = 0.003,
              n_control: int = 8, order: str = "kaw", seed: int = 0) -> Block:
    """A Penta-like rig (§3.8, figs. 3.14, 3.16): a nadir camera and four obliques tilted ``tilt_deg``.

    The obliques look forward, back, right and left (tilts about the reference camera's y and x
    axes), with lever arms of 0.1–0.3 m. Points are scattered over the area all cameras see;
    ``n_control`` of them (spread over the block) are control. Seeded.

    Parameters
    ----------
    n_strips, exposures_per_strip : int
        Layout of the exposures (of the nadir camera).
    tilt_deg : float
        Tilt of the oblique cameras, degrees (this one parameter is in degrees, as its name says).
    f, frame_size, flying_height, forward_overlap, side_overlap : float
        Camera (mm), height (m) and overlaps of the nadir camera.
    n_points, n_control : int
        Points scattered, and how many of them are control.
    relief, sigma : float
        Terrain relief (m), image noise (mm).
    order : {"kaw", "wak"}
        Rotation order.
    seed : int
        Seed.

    Returns
    -------
    Block
        With ``ios``, ``exposures`` (n, 6), ``mounts`` (4, 6), ``exposure_of_image``,
        ``camera_of_image``; ``cameras`` holds the EO of every image.

    Raises
    ------
    InputError
        Bad sizes or overlaps, NaN/inf, a negative σ, too few points.

    References
    ----------
    Chibunichev (2022), §3.8, (3.8.1), (3.8.2), (3.8.5), (3.8.8), figs. 3.14, 3.16.

    Examples
    --------
    >>> from photolib.synthetic import rig_block
    >>> rb = rig_block(1, 2, n_points=150, n_control=4, seed=1)
    >>> len(rb.ios), rb.exposures.shape, rb.mounts.shape, rb.n_images
    (5, (2, 6), (4, 6), 10)
    """
    check_order(order)
    _count(n_strips, "n_strips", 1)
    _count(exposures_per_strip, "exposures_per_strip", 1)
    n_points = _count(n_points, "n_points", 3)
    n_control = _count(n_control, "n_control", 0)
    sigma = _finite(sigma, "sigma", nonnegative=True)
    tilt_deg = _finite(tilt_deg, "tilt_deg")
    relief = _finite(relief, "relief")
    rng = np.random.default_rng(seed)
    deg = np.pi / 180
    lay = strip_layout(n_strips, exposures_per_strip, f=f, frame_size=frame_size, flying_height=flying_height,
                       forward_overlap=forward_overlap, side_overlap=side_overlap)
    foot, base, spacing, strip, along = lay
    io = InteriorOrientation(f=f)
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
    image, point, xy_true, noisy = _observe(cams, points, [io] * cams.shape[0], frame_size / 2 * 0.98, rng, sigma,
                                            order)
    count = np.bincount(point, minlength=n_points)
    keep = count >= 2
    if keep.sum() < 3:
        raise InputError("fewer than 3 points are seen on two images; give more points or more overlap")
    new = np.cumsum(keep) - 1
    sel = keep[point]
    image, point, xy_true, noisy = image[sel], new[point[sel]], xy_true[sel], noisy[sel]
    points = points[keep]
    kind = np.full(len(points), int(TIE))
    centre = np.array([(exposures_per_strip - 1) * base / 2, -(n_strips - 1) * spacing / 2])
    angle = np.arctan2(points[:, 1] - centre[1], points[:, 0] - centre[0])
    far = np.hypot(*(points[:, :2] - centre).T)
    chosen = []
    for sector in range(n_control):
        in_sector = np.flatnonzero(np.floor((angle + np.pi) / (2 * np.pi) * n_control) == sector)
        if in_sector.size:
            chosen.append(in_sector[np.argmax(far[in_sector] * (np.bincount(point, minlength=len(points))[in_sector] >= 3))])
    kind[chosen] = CONTROL
    return Block(io=io, order=order, cameras=cams, points=points, kind=kind,
                 observations=Observations(image, point, noisy), xy_true=xy_true, sigma=float(sigma),
                 strip=strip[e_img], column=along[e_img], frame_size=float(frame_size), footprint=float(foot),
                 base=float(base), strip_spacing=float(spacing), ios=tuple([io] * n_cam), exposures=exposures,
                 mounts=mounts, exposure_of_image=e_img, camera_of_image=c_img)


def rolling_shutter_block(n_strips: int = 2, images_per_strip: int = 5, *, speed: float = 10.0,
                          readout: float = 0.03, angular_rate_deg: float = 3.0, sigma: float = 0.0015,
                          points_per_image: int = 60, model: str = "full", seed: int = 0) -> Block:
    """UAV block (f = 8.8 mm, 13.2 mm sensor, H = 100 m, 80/70 % overlap) shot with a rolling shutter.

    The readout runs along x and takes ``readout`` seconds for the whole sensor, while the UAV
    flies at ``speed`` m/s along X and rotates at up to ``angular_rate_deg`` °/s: the rates k of
    (3.9.2) are these velocities times readout / sensor width (per mm of x). ``model="linear"``
    keeps the angles constant (k₄ = k₅ = k₆ = 0). Observations by
    :func:`photolib.bundle.rolling_shutter_project` plus Gaussian noise σ (mm).

    Parameters
    ----------
    n_strips, images_per_strip : int
        Block size.
    speed, readout, angular_rate_deg : float
        Flying speed (m/s), readout time (s), largest angular rate (degrees per second).
    sigma : float
        Image noise, mm.
    points_per_image : int
        Tie-point density.
    model : {"full", "linear"}
        Rates of all six EO elements, or of the centre only.
    seed : int
        Seed.

    Returns
    -------
    Block
        ``cameras`` = EO at the line x = 0, ``rates`` (n, 6), rolling-shutter ``observations``.

    Raises
    ------
    InputError
        An unknown model, NaN/inf or negative rates and σ, a bad block size.

    References
    ----------
    Chibunichev (2022), §3.9, (3.9.1), (3.9.2).

    Examples
    --------
    >>> from photolib.synthetic import rolling_shutter_block
    >>> rsb = rolling_shutter_block(1, 3, points_per_image=20, model="linear")
    >>> rsb.rates.shape, bool((rsb.rates[:, 3:] == 0).all())
    ((3, 6), True)
    """
    if model not in ("full", "linear"):
        raise InputError("model must be 'full' or 'linear'")
    speed = _finite(speed, "speed")
    readout = _finite(readout, "readout", nonnegative=True)
    angular_rate_deg = _finite(angular_rate_deg, "angular_rate_deg")
    sigma = _finite(sigma, "sigma", nonnegative=True)
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
    rates[:, 0] = heading * speed * per_mm + rng.normal(0, 0.1 * abs(speed) * per_mm, n)
    rates[:, 1] = rng.normal(0, 0.1 * abs(speed) * per_mm, n)
    rates[:, 2] = rng.normal(0, 0.05 * abs(speed) * per_mm, n)
    if model == "full":
        rates[:, 3:] = rng.uniform(-1, 1, (n, 3)) * np.radians(angular_rate_deg) * per_mm
    o = blk.observations
    xy_true = rolling_shutter_project(blk.cameras, rates, blk.points[o.point], blk.io, blk.order, image=o.image)
    xy = xy_true + rng.normal(0.0, sigma, xy_true.shape) if sigma > 0 else xy_true
    return replace(blk, observations=Observations(o.image, o.point, xy), xy_true=xy_true, sigma=float(sigma),
                   rates=rates)


def corridor_strip(n_images: int = 16, *, wander: float = 0.5, gnss_sigma: float = 0.03, sigma: float = 0.002,
                   points_per_image: int = 40, with_target: bool = True, seed: int = 0) -> Block:
    """A mapKITE-like corridor (§3.9, figs. 3.25/3.26): one UAV strip along a road, GNSS centres only.

    UAV with f = 8.8 mm, 13.2 mm sensor, H = 100 m, 80 % forward overlap. The projection centres
    lie almost on a line (lateral wander ``wander`` m), so GNSS centres alone leave the block
    free to roll about the flight line. With ``with_target`` a vehicle below the UAV carries a
    target whose position (GNSS/INS) is known at every exposure: a new control point in each image.

    Parameters
    ----------
    n_images : int
        Images in the strip (at least 2).
    wander, gnss_sigma, sigma : float
        Lateral scatter of the centres (m), GNSS accuracy (m), image noise (mm).
    points_per_image : int
        Tie-point density.
    with_target : bool
        Add the vehicle-borne target (CONTROL, one per image).
    seed : int
        Seed.

    Returns
    -------
    Block
        With ``gnss`` (n, 3), ``gnss_sigma`` and ``target`` (n,) (−1: none); road points are CHECK.

    Raises
    ------
    InputError
        NaN/inf or negative σ, fewer than two images.

    References
    ----------
    Chibunichev (2022), §3.9, figs. 3.25, 3.26; GNSS centres (3.5.18).

    Examples
    --------
    >>> from photolib.synthetic import corridor_strip
    >>> co = corridor_strip(6, points_per_image=20)
    >>> co.gnss.shape, co.target.tolist()[:3]
    ((6, 3), [...])
    """
    n_images = _count(n_images, "n_images", 2)
    wander = _finite(wander, "wander", nonnegative=True)
    gnss_sigma = _finite(gnss_sigma, "gnss_sigma", nonnegative=True)
    sigma = _finite(sigma, "sigma", nonnegative=True)
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
        kind = np.concatenate([kind, np.full(n_images, int(CONTROL))])
        t_xy, _ = project_to_images(cams, np.arange(n_images), pts[target], blk.io, blk.order)
        image = np.concatenate([image, np.arange(n_images)])
        point = np.concatenate([point, target])
        xy_true = np.vstack([xy_true, t_xy])
    xy = xy_true + rng.normal(0.0, sigma, xy_true.shape) if sigma > 0 else xy_true.copy()
    gnss = cams[:, :3] + rng.normal(0.0, gnss_sigma, (n_images, 3))
    return replace(blk, cameras=cams, points=pts, kind=kind, observations=Observations(image, point, xy),
                   xy_true=xy_true, sigma=float(sigma), gnss=gnss, gnss_sigma=float(gnss_sigma), target=target,
                   point_labels=tuple(range(len(pts))))


# --- Chapter 2 / Chapter 4 / the GNSS appendix: one stereo pair ------------------------------------
@dataclass(frozen=True)
class StereoPair:
    """A simulated stereo pair with known truth (§2.4–§2.12, §4.3–§4.4, the GNSS appendix).

    Attributes
    ----------
    io : InteriorOrientation or None
        The camera (None when a custom ``projector`` was used).
    order : str
        Rotation sequence of ``angles`` (for the default Chapter-1 projection).
    centres : (2, 3) array
        True projection centres S₁, S₂ (m).
    angles : (2, 3) array
        True angles of each image (rad), in the sequence ``order`` (or the projector's system).
    points : (n, 3) array
        Object points (m).
    xy1, xy2 : (n, 2) arrays
        Measured image coordinates (mm), with the noise ``sigma``.
    xy1_true, xy2_true : (n, 2) arrays
        Noise-free projections.
    sigma : float
        Standard deviation of the Gaussian image noise (mm).

    References
    ----------
    Chibunichev (2022), §2.4, eq. (2.4.4); §1.4, eq. (1.4.12).

    Examples
    --------
    >>> pair = stereo_pair(6, seed=0)
    >>> pair.xy1.shape, pair.eo2.center
    ((6, 2), array([ 400.,    0., 1000.]))
    """

    io: InteriorOrientation | None
    order: str
    centres: np.ndarray
    angles: np.ndarray
    points: np.ndarray
    xy1: np.ndarray
    xy2: np.ndarray
    xy1_true: np.ndarray
    xy2_true: np.ndarray
    sigma: float

    def __post_init__(self):
        from .camera import as_points
        checked = {"centres": as_points(self.centres, 3, "centres"), "angles": as_points(self.angles, 3, "angles")}
        if checked["centres"].shape != (2, 3) or checked["angles"].shape != (2, 3):
            raise InputError(f"a stereo pair has two centres and two angle triples, got shapes "
                             f"{checked['centres'].shape} and {checked['angles'].shape}")
        checked["points"] = as_points(self.points, 3, "points")
        n = len(checked["points"])
        for name in ("xy1", "xy2", "xy1_true", "xy2_true"):
            checked[name] = as_points(getattr(self, name), 2, name)
            if len(checked[name]) != n:
                raise InputError(f"{name} has {len(checked[name])} rows for {n} object points")
        if not (np.isfinite(self.sigma) and self.sigma >= 0):
            raise InputError(f"sigma must be a finite non-negative number, got {self.sigma!r}")
        for name, value in checked.items():          # the dataclass is frozen
            object.__setattr__(self, name, value)

    def _eo(self, i):
        from .camera import ExteriorOrientation
        return ExteriorOrientation(*map(float, self.centres[i]), *map(float, self.angles[i]), order=self.order)

    @property
    def eo1(self):
        """Exterior orientation of image 1 (Chapter-1 conventions)."""
        return self._eo(0)

    @property
    def eo2(self):
        """Exterior orientation of image 2 (Chapter-1 conventions)."""
        return self._eo(1)

    def __repr__(self) -> str:
        b = np.linalg.norm(self.centres[1] - self.centres[0])
        return (f"StereoPair({len(self.points)} points, base {b:.1f} m, σ = {self.sigma * 1000:.1f} µm, "
                f"order {self.order})")


def stereo_pair(n_points: int = 12, *, seed: int = 0, rng=None, f: float = 100.0,
                io: InteriorOrientation | None = None, order: str = "kaw",
                centres=((0.0, 0.0, 1000.0), (400.0, 0.0, 1000.0)), angles=((0.0, 0.0, 0.0), (0.0, 0.0, 0.0)),
                angle_spread=None, angle_spread_deg=None, box=((50.0, 350.0), (-250.0, 250.0)), ground_xy=None,
                mean_height: float = 0.0, relief: float = 40.0, sigma: float = 0.0, projector=None) -> StereoPair:
    """Simulate a stereo pair: two cameras, object points with relief, (noisy) image coordinates.

    The one synthetic-pair generator of photolib: near-vertical aerial pairs (Chapters 2 and 4),
    convergent terrestrial pairs (give ``centres`` and ``angles``, e.g. image 2 turned by the
    convergence angle about the vertical) and the GNSS-centre pairs of the Dobrynin–Pimshina
    method (with their own ``projector``). The random numbers are drawn in a fixed sequence —
    the angle perturbations of image 1 then image 2 (only if a spread is given, even a zero one), X then Y of the
    points (only without ``ground_xy``), their heights, the noise of image 1 then image 2 (only
    for ``sigma`` > 0) — so a pair is a function of its arguments.

    Parameters
    ----------
    n_points : int
        Number of object points scattered uniformly over ``box`` (ignored with ``ground_xy``).
    seed : int
        Seed of the random generator (ignored when ``rng`` is given).
    rng : numpy.random.Generator, optional
        A generator to draw from instead of a fresh one.
    f : float
        Focal length (mm) of the default camera; ``io`` replaces it.
    io : InteriorOrientation, optional
        The camera (distortion is not simulated).
    order : {"kaw", "wak"}
        Rotation sequence of ``angles``.
    centres : (2, 3) array_like
        Projection centres S₁, S₂ (m); the base is their difference.
    angles : (2, 3) array_like
        Nominal angles of the images (rad).
    angle_spread, angle_spread_deg : float or array of 3, optional
        Half-width of uniform perturbations added to every angle, in radians or in degrees
        (drawn in degrees, then converted); per angle if an array of 3. None (default): no
        perturbation and no random numbers drawn for the angles.
    box : ((x_lo, x_hi), (y_lo, y_hi))
        Planimetric area of the object points (m).
    ground_xy : (n, 2) array, optional
        Fixed planimetric positions of the points instead of random ones.
    mean_height, relief : float
        Heights are ``mean_height`` + uniform(−relief, relief) (m).
    sigma : float
        Gaussian image noise (mm); 0 gives exact coordinates.
    projector : callable, optional
        ``projector(points, centre, angles) -> xy`` replacing the collinearity equations
        (1.4.12) (e.g. the α–ω–χ system of the GNSS appendix).

    Returns
    -------
    StereoPair

    Raises
    ------
    InputError
        Bad shapes, a negative σ or relief, NaN.
    DegenerateGeometryError
        A point behind a camera (from the projection).

    References
    ----------
    Chibunichev (2022), §1.4, eq. (1.4.12); §2.4–§2.5; §4.4. Dobrynin & Pimshina, eqs. (3), (4).

    Examples
    --------
    >>> p = stereo_pair(8, seed=1, sigma=0.005)
    >>> p.points.shape, round(p.sigma, 3)
    ((8, 3), 0.005)
    """
    from .single_image import project

    check_order(order)
    rng = np.random.default_rng(seed) if rng is None else rng
    C = np.array(centres, dtype=float)
    A = np.array(angles, dtype=float)
    if C.shape != (2, 3) or A.shape != (2, 3) or not (np.all(np.isfinite(C)) and np.all(np.isfinite(A))):
        raise InputError("centres and angles: expected finite (2, 3) arrays (one row per image)")
    if not (np.isfinite(sigma) and sigma >= 0 and np.isfinite(relief) and relief >= 0):
        raise InputError("sigma and relief must be finite and non-negative")
    if angle_spread_deg is not None:
        spread = np.broadcast_to(np.asarray(angle_spread_deg, dtype=float), (3,))
        A = A + np.stack([np.radians(rng.uniform(-spread, spread)) for _ in range(2)])
    elif angle_spread is not None:
        spread = np.broadcast_to(np.asarray(angle_spread, dtype=float), (3,))
        A = A + np.stack([rng.uniform(-spread, spread) for _ in range(2)])
    if ground_xy is None:
        (x_lo, x_hi), (y_lo, y_hi) = box
        xy = np.column_stack([rng.uniform(x_lo, x_hi, n_points), rng.uniform(y_lo, y_hi, n_points)])
    else:
        xy = np.asarray(ground_xy, dtype=float)
        if xy.ndim != 2 or xy.shape[1] != 2 or not np.all(np.isfinite(xy)):
            raise InputError("ground_xy: expected a finite (n, 2) array")
    points = np.column_stack([xy, mean_height + rng.uniform(-relief, relief, len(xy))])
    if projector is None:
        camera = InteriorOrientation(f) if io is None else io
        from .camera import ExteriorOrientation
        xy_true = [project(points, ExteriorOrientation(*C[i], *A[i], order=order), camera) for i in range(2)]
    else:
        camera = io
        xy_true = [projector(points, C[i], A[i]) for i in range(2)]
    xy_meas = list(xy_true)
    if sigma:
        xy_meas = [x + rng.normal(0, sigma, x.shape) for x in xy_true]
    return StereoPair(camera, order, C, A, points, xy_meas[0], xy_meas[1], xy_true[0], xy_true[1], float(sigma))


# --- Chapters 5–6: a textured terrain with buildings and trees, rendered into frame cameras -------------
def _smooth_noise(rng, shape, sigma_cells: float) -> np.ndarray:
    """Gaussian-filtered white noise scaled to unit standard deviation (``sigma_cells`` in grid cells)."""
    from scipy.ndimage import gaussian_filter
    field = gaussian_filter(rng.standard_normal(shape), sigma_cells, mode="reflect")
    return (field - field.mean()) / max(field.std(), 1e-12)


def _pair_range(value, what: str, positive: bool = True) -> tuple[float, float]:
    arr = np.asarray(value, dtype=object)
    if arr.shape != (2,):
        raise InputError(f"{what} must be a (low, high) pair, got {value!r}")
    lo, hi = (_finite(v, what, positive=positive, nonnegative=not positive) for v in value)
    if lo > hi:
        raise InputError(f"{what}: low {lo} exceeds high {hi}")
    return lo, hi


def _tri_interpolate(x, y, values, X, Y, what: str = "points"):
    """Piecewise-linear interpolation on the scene's triangulation (two triangles per cell, diagonal
    from node (i, j) to node (i + 1, j + 1)); NaN outside the grid."""
    try:
        X, Y = np.broadcast_arrays(np.asarray(X, dtype=float), np.asarray(Y, dtype=float))
    except (TypeError, ValueError):
        raise InputError(f"{what}: X and Y must be numbers of broadcastable shapes") from None
    if not (np.all(np.isfinite(X)) and np.all(np.isfinite(Y))):
        raise InputError(f"{what}: X, Y contain NaN or inf")
    dx, dy = x[1] - x[0], y[1] - y[0]
    fu, fv = (X - x[0]) / dx, (Y - y[0]) / dy
    inside = (fu >= -1e-9) & (fu <= len(x) - 1 + 1e-9) & (fv >= -1e-9) & (fv <= len(y) - 1 + 1e-9)
    j = np.clip(np.floor(fu).astype(int), 0, len(x) - 2)
    i = np.clip(np.floor(fv).astype(int), 0, len(y) - 2)
    u, v = np.clip(fu - j, 0, 1), np.clip(fv - i, 0, 1)
    z00, z01, z10, z11 = values[i, j], values[i, j + 1], values[i + 1, j], values[i + 1, j + 1]
    lower = u >= v                        # triangle (i, j), (i, j + 1), (i + 1, j + 1)
    out = np.where(lower, z00 + u * (z01 - z00) + v * (z11 - z01), z00 + v * (z10 - z00) + u * (z11 - z10))
    return np.where(inside, out, np.nan)


@dataclass(frozen=True, eq=False, repr=False)
class TerrainScene:
    """A synthetic scene with known truth: ground (DTM), surface (DSM), buildings, trees, texture.

    The surface is a regular grid of heights; between the nodes it is piecewise linear on two
    triangles per cell (split along the diagonal from node (i, j) to node (i + 1, j + 1)) — the
    surface :func:`render_image` draws and :meth:`surface_at` interpolates, so the two agree
    exactly. Building walls therefore slope across one grid cell.

    Attributes
    ----------
    x : (nx,) array
        X of the grid columns, ascending, m.
    y : (ny,) array
        Y of the grid rows, ascending (row 0 is the smallest Y: plot with ``origin="lower"``), m.
    ground : (ny, nx) array
        Bare-earth heights (the DTM), m.
    surface : (ny, nx) array
        Surface heights (the DSM): ground plus buildings plus tree canopies, m.
    buildings : (ny, nx) bool array
        Nodes on a building (roof).
    trees : (ny, nx) bool array
        Nodes under a tree canopy higher than 0.3 m above the ground.
    albedo : (ny, nx) array
        Texture (reflectance) in [0, 1] at the nodes.
    footprints : (b, 4) array
        Building footprints X_min, X_max, Y_min, Y_max, m.
    seed : int
        The seed the scene was drawn with.

    References
    ----------
    Chibunichev (2022), §6.1–6.3 (DSM), §6.5 (voxel SGM), §6.6–6.7 (DTM): the book prints no
    test scene; this is the ground truth its algorithms are tested against.

    Examples
    --------
    >>> from photolib.synthetic import terrain_scene
    >>> sc = terrain_scene(extent=40.0, spacing=1.0, n_buildings=1, seed=0)
    >>> sc
    TerrainScene(41 × 41 nodes, spacing 1.0 m, 1 buildings, 0 trees)
    >>> bool(np.all(sc.surface >= sc.ground)), bool(sc.albedo.min() >= 0)
    (True, True)
    """

    x: np.ndarray
    y: np.ndarray
    ground: np.ndarray
    surface: np.ndarray
    buildings: np.ndarray
    trees: np.ndarray
    albedo: np.ndarray
    footprints: np.ndarray
    seed: int = 0

    def __post_init__(self):
        x = np.asarray(self.x, dtype=float)
        y = np.asarray(self.y, dtype=float)
        if x.ndim != 1 or y.ndim != 1 or len(x) < 2 or len(y) < 2:
            raise InputError("a scene needs at least 2 × 2 grid nodes (1-D x and y axes)")
        if not (np.all(np.isfinite(x)) and np.all(np.isfinite(y))):
            raise InputError("scene axes contain NaN or inf")
        dx, dy = np.diff(x), np.diff(y)
        if not (np.all(dx > 0) and np.allclose(dx, dx[0]) and np.all(dy > 0) and np.allclose(dy, dy[0])):
            raise InputError("scene axes must be ascending and regularly spaced")
        checked = {"x": x, "y": y}
        for name in ("ground", "surface", "albedo"):
            arr = np.asarray(getattr(self, name), dtype=float)
            if arr.shape != (len(y), len(x)):
                raise InputError(f"scene {name} must have shape {(len(y), len(x))}, got {arr.shape}")
            if not np.all(np.isfinite(arr)):
                raise InputError(f"scene {name} contains NaN or inf")
            checked[name] = arr
        for name in ("buildings", "trees"):
            arr = np.asarray(getattr(self, name), dtype=bool)
            if arr.shape != (len(y), len(x)):
                raise InputError(f"scene {name} must have shape {(len(y), len(x))}, got {arr.shape}")
            checked[name] = arr
        checked["footprints"] = np.asarray(self.footprints, dtype=float).reshape(-1, 4)
        for name, value in checked.items():
            object.__setattr__(self, name, value)

    @property
    def spacing(self) -> float:
        """Grid spacing along X, m."""
        return float(self.x[1] - self.x[0])

    @property
    def X(self) -> np.ndarray:
        """(ny, nx) X of every node."""
        return np.broadcast_to(self.x[None, :], self.surface.shape).copy()

    @property
    def Y(self) -> np.ndarray:
        """(ny, nx) Y of every node."""
        return np.broadcast_to(self.y[:, None], self.surface.shape).copy()

    @property
    def extent(self) -> tuple:
        """(X_min, X_max, Y_min, Y_max) of the grid, m (matplotlib's ``extent`` order)."""
        return float(self.x[0]), float(self.x[-1]), float(self.y[0]), float(self.y[-1])

    def surface_at(self, X, Y) -> np.ndarray:
        """DSM height at (X, Y) on the rendered triangulation (NaN outside the grid)."""
        return _tri_interpolate(self.x, self.y, self.surface, X, Y, "surface_at")

    def ground_at(self, X, Y) -> np.ndarray:
        """DTM height at (X, Y) (NaN outside the grid)."""
        return _tri_interpolate(self.x, self.y, self.ground, X, Y, "ground_at")

    def albedo_at(self, X, Y) -> np.ndarray:
        """Texture at (X, Y), piecewise linear like the surface (NaN outside the grid)."""
        return _tri_interpolate(self.x, self.y, self.albedo, X, Y, "albedo_at")

    def discontinuity_distance(self, step: float = 1.0) -> np.ndarray:
        """(ny, nx) distance (m) of every node from the nearest height step larger than ``step`` m
        between neighbouring nodes (building walls, tree edges): mask test areas with it."""
        from scipy.ndimage import distance_transform_edt
        s = self.surface
        edge = np.zeros(s.shape, bool)
        dzx = np.abs(np.diff(s, axis=1)) > step
        dzy = np.abs(np.diff(s, axis=0)) > step
        edge[:, :-1] |= dzx
        edge[:, 1:] |= dzx
        edge[:-1, :] |= dzy
        edge[1:, :] |= dzy
        if not edge.any():
            return np.full(s.shape, np.inf)
        return distance_transform_edt(~edge) * self.spacing

    def __repr__(self) -> str:
        return (f"TerrainScene({len(self.y)} × {len(self.x)} nodes, spacing {self.spacing:.1f} m, "
                f"{len(self.footprints)} buildings, {self._n_trees} trees)")

    @property
    def _n_trees(self) -> int:
        from scipy.ndimage import label
        return int(label(self.trees)[1])


def terrain_scene(extent=200.0, spacing: float = 0.5, *, base_height: float = 100.0, relief: float = 10.0,
                  relief_scale: float = 60.0, n_buildings: int = 6, building_size=(10.0, 30.0),
                  building_height=(6.0, 20.0), n_trees: int = 0, tree_height=(4.0, 10.0), tree_radius=(2.0, 4.0),
                  texture_scale: float = 1.5, texture_contrast: float = 0.18, seed: int = 0) -> TerrainScene:
    """A seeded synthetic scene: rolling ground, flat-roofed buildings, optional trees, a random texture.

    Ground: ``base_height`` plus smooth random relief (Gaussian-filtered noise of correlation
    length ``relief_scale``, scaled to a peak-to-peak range of ``relief``). Buildings:
    axis-aligned rectangles (sides drawn from ``building_size``) with flat roofs ``building_height``
    above the highest ground under them, at least 4 m apart and 5 m from the border (fewer are
    placed if they do not fit). Trees: paraboloid canopies (``tree_radius``, ``tree_height``)
    off the buildings. Texture: band-pass random noise (correlation ``texture_scale`` m, standard
    deviation ``texture_contrast``, plus a grid-scale component) around 0.5, roofs shifted in brightness, canopies darker,
    clipped to [0, 1]. The random numbers are drawn in a fixed order, so a scene is a function
    of its arguments.

    Parameters
    ----------
    extent : float or (float, float)
        Size of the area along X and Y, m; the grid starts at X = Y = 0.
    spacing : float
        Grid spacing, m.
    base_height, relief, relief_scale : float
        Mean ground height, peak-to-peak relief and its correlation length, m.
    n_buildings : int
        Buildings to place (≥ 0).
    building_size, building_height : (float, float)
        Ranges of the footprint sides and of the heights above ground, m.
    n_trees : int
        Trees to place (≥ 0).
    tree_height, tree_radius : (float, float)
        Ranges of the canopy height and radius, m.
    texture_scale, texture_contrast : float
        Correlation length of the texture (m) and its standard deviation.
    seed : int
        Seed.

    Returns
    -------
    TerrainScene

    Raises
    ------
    InputError
        NaN/inf or non-positive sizes, ranges with low > high, negative counts, a grid with fewer
        than 3 × 3 nodes.

    References
    ----------
    Chibunichev (2022), §6.1–6.3 and §6.6–6.7: the DSM (surface with buildings and vegetation)
    and the DTM (bare earth) the algorithms there estimate.

    Examples
    --------
    >>> from photolib.synthetic import terrain_scene
    >>> sc = terrain_scene(extent=(100.0, 80.0), spacing=1.0, n_buildings=2, n_trees=3, seed=1)
    >>> sc.surface.shape, len(sc.footprints), bool(sc.buildings.any()), bool(sc.trees.any())
    ((81, 101), 2, True, True)
    """
    if np.ndim(extent) > 1 or np.size(extent) not in (1, 2):
        raise InputError(f"extent must be one size or (size_x, size_y), got {extent!r}")
    ext = np.broadcast_to(np.asarray(extent, dtype=object).ravel(), (2,))
    wx, wy = (_finite(v, "extent", positive=True) for v in ext)
    spacing = _finite(spacing, "spacing", positive=True)
    base_height = _finite(base_height, "base_height")
    relief = _finite(relief, "relief", nonnegative=True)
    relief_scale = _finite(relief_scale, "relief_scale", positive=True)
    n_buildings = _count(n_buildings, "n_buildings", 0)
    n_trees = _count(n_trees, "n_trees", 0)
    bs = _pair_range(building_size, "building_size")
    bh = _pair_range(building_height, "building_height")
    th = _pair_range(tree_height, "tree_height")
    tr = _pair_range(tree_radius, "tree_radius")
    texture_scale = _finite(texture_scale, "texture_scale", positive=True)
    texture_contrast = _finite(texture_contrast, "texture_contrast", nonnegative=True)
    seed = _count(seed, "seed", 0)
    nx, ny = int(round(wx / spacing)) + 1, int(round(wy / spacing)) + 1
    if nx < 3 or ny < 3:
        raise InputError(f"the grid would have {ny} × {nx} nodes: make the extent larger or the spacing smaller")
    x, y = np.arange(nx) * spacing, np.arange(ny) * spacing
    rng = np.random.default_rng(seed)
    # ground
    g = _smooth_noise(rng, (ny, nx), relief_scale / spacing)
    g = (g - g.min()) / max(g.max() - g.min(), 1e-12) - 0.5
    ground = base_height + relief * g
    surface = ground.copy()
    X, Y = np.meshgrid(x, y)
    # buildings
    margin, gap = 5.0, 4.0
    boxes = []
    for _ in range(200 * max(n_buildings, 1)):
        if len(boxes) >= n_buildings:
            break
        sx, sy = rng.uniform(*bs, 2)
        x0 = rng.uniform(margin, max(margin, wx - margin - sx))
        y0 = rng.uniform(margin, max(margin, wy - margin - sy))
        box = (x0, x0 + sx, y0, y0 + sy)
        if box[1] > wx - margin + 1e-9 or box[3] > wy - margin + 1e-9:
            continue
        if any(box[0] < b[1] + gap and b[0] < box[1] + gap and box[2] < b[3] + gap and b[2] < box[3] + gap
               for b in boxes):
            continue
        boxes.append(box)
    buildings = np.zeros((ny, nx), bool)
    heights = rng.uniform(*bh, len(boxes))
    roof_shift = rng.uniform(-0.2, 0.2, len(boxes))
    for (bx0, bx1, by0, by1), h in zip(boxes, heights):
        m = (X >= bx0) & (X <= bx1) & (Y >= by0) & (Y <= by1)
        if not m.any():
            continue
        surface[m] = ground[m].max() + h
        buildings |= m
    # trees
    trees = np.zeros((ny, nx), bool)
    canopy = np.zeros((ny, nx))
    placed = 0
    for _ in range(50 * max(n_trees, 1)):
        if placed >= n_trees:
            break
        r, h = rng.uniform(*tr), rng.uniform(*th)
        cx, cy = rng.uniform(0, wx), rng.uniform(0, wy)
        d2 = ((X - cx) ** 2 + (Y - cy) ** 2) / r ** 2
        m = d2 < 1
        if not m.any() or np.any(buildings[((X - cx) ** 2 + (Y - cy) ** 2) < (r + gap / 2) ** 2]):
            continue
        canopy = np.maximum(canopy, np.where(m, h * (1 - d2), 0.0))
        placed += 1
    trees = canopy > 0.3
    surface = np.where(buildings, surface, ground + canopy)
    # texture
    tex = 0.5 * _smooth_noise(rng, (ny, nx), 0.7) \
        + 0.7 * _smooth_noise(rng, (ny, nx), texture_scale / spacing) \
        + 0.5 * _smooth_noise(rng, (ny, nx), 3 * texture_scale / spacing)
    albedo = 0.5 + texture_contrast * tex / max(tex.std(), 1e-12)
    for (bx0, bx1, by0, by1), s in zip(boxes, roof_shift):
        m = (X >= bx0) & (X <= bx1) & (Y >= by0) & (Y <= by1)
        albedo[m] += s
    albedo[trees] -= 0.15
    albedo = np.clip(albedo, 0.0, 1.0)
    return TerrainScene(x, y, ground, surface, buildings, trees, albedo,
                        np.array(boxes, dtype=float).reshape(-1, 4), seed)


def pixel_to_image(col, row, shape, pixel_size: float):
    """Image coordinates x, y (mm) of pixel positions of a frame of ``shape`` = (rows, cols).

    The frame convention of the renderer: pixel centres at integer (col, row) with row 0 at the
    top (``img[row, col]``), the fiducial centre (origin of x, y) at the centre of the frame,
    x to the right and y up: x = (col − (cols − 1)/2)·Δ, y = ((rows − 1)/2 − row)·Δ.

    Parameters
    ----------
    col, row : float or array
        Column and row positions (fractional allowed).
    shape : (int, int)
        Rows and columns of the frame.
    pixel_size : float
        Δ, mm.

    Returns
    -------
    x, y : float or ndarray
        Image coordinates, mm (floats for scalar input).

    Raises
    ------
    InputError
        NaN/inf, a bad shape, Δ ≤ 0.

    References
    ----------
    Chibunichev (2022), §1.10, (1.10.3)–(1.10.5) (pixel → physical coordinates, Fig. 1.19).

    Examples
    --------
    >>> from photolib.synthetic import pixel_to_image
    >>> pixel_to_image(0.0, 0.0, (3, 5), 0.01)
    (-0.02, 0.01)
    """
    h, w = _frame_shape(shape)
    d = _finite(pixel_size, "pixel_size", positive=True)
    col, row = _finite_array(col, "col"), _finite_array(row, "row")
    try:
        col, row = np.broadcast_arrays(col, row)
    except ValueError:
        raise InputError(f"col and row have shapes {col.shape} and {row.shape} that do not broadcast") from None
    x, y = (col - (w - 1) / 2) * d, ((h - 1) / 2 - row) * d
    return (float(x), float(y)) if np.ndim(x) == 0 else (x, y)


def image_to_pixel(xy, shape, pixel_size: float) -> np.ndarray:
    """Pixel positions (col, row) of image coordinates (mm): the inverse of :func:`pixel_to_image`.

    Parameters
    ----------
    xy : (n, 2) array
        Image coordinates x, y, mm.
    shape : (int, int)
        Rows and columns of the frame.
    pixel_size : float
        Δ, mm.

    Returns
    -------
    (n, 2) ndarray
        col, row (centre of ``img[r, c]`` at (c, r)).

    Raises
    ------
    InputError
        NaN/inf, wrong shapes, Δ ≤ 0.

    References
    ----------
    Chibunichev (2022), §1.10, (1.10.3)–(1.10.5).

    Examples
    --------
    >>> from photolib.synthetic import image_to_pixel
    >>> image_to_pixel([[-0.02, 0.01]], (3, 5), 0.01)
    array([[0., 0.]])
    """
    from .camera import as_points
    h, w = _frame_shape(shape)
    d = _finite(pixel_size, "pixel_size", positive=True)
    xy = as_points(xy, 2, "image coordinates")
    return np.column_stack([xy[:, 0] / d + (w - 1) / 2, (h - 1) / 2 - xy[:, 1] / d])


def _finite_array(value, what):
    try:
        arr = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise InputError(f"{what} must be numbers") from None
    if not np.all(np.isfinite(arr)):
        raise InputError(f"{what} contains NaN or inf")
    return arr


def _frame_shape(shape) -> tuple[int, int]:
    try:
        h, w = shape
    except (TypeError, ValueError):
        raise InputError(f"shape must be (rows, cols), got {shape!r}") from None
    return _count(h, "image rows", 2), _count(w, "image columns", 2)


@dataclass(frozen=True, eq=False, repr=False)
class Rendering:
    """An image rendered by :func:`render_image`, with the object point seen by every pixel.

    Attributes
    ----------
    image : (rows, cols) float array
        Brightness (the scene's albedo, plus noise if asked); ``background`` where nothing is seen.
    depth : (rows, cols) float array
        Distance from the projection centre to the surface point seen, m (NaN: nothing seen).
    XYZ : (rows, cols, 3) float array
        Object coordinates of the surface point seen by each pixel centre, m (NaN: nothing).
    visible : (rows, cols) bool array
        Pixels that see the scene.
    io : InteriorOrientation
    eo : ExteriorOrientation
    pixel_size : float
        Δ, mm (pixel ↔ mm conversion: :func:`pixel_to_image`, :func:`image_to_pixel`).

    References
    ----------
    Chibunichev (2022), §1.4, (1.4.12) (projection); §1.10 (pixel coordinates).

    Examples
    --------
    >>> from photolib.camera import InteriorOrientation, ExteriorOrientation
    >>> from photolib.synthetic import terrain_scene, render_image
    >>> sc = terrain_scene(extent=40.0, spacing=1.0, n_buildings=0, seed=0)
    >>> r = render_image(sc, InteriorOrientation(50.0), ExteriorOrientation(20.0, 20.0, 300.0), (16, 16),
    ...                  pixel_size=0.05)
    >>> r
    Rendering(16 × 16 pixels, 256 see the scene, Δ = 0.050 mm)
    """

    image: np.ndarray
    depth: np.ndarray
    XYZ: np.ndarray
    visible: np.ndarray
    io: InteriorOrientation
    eo: object
    pixel_size: float

    @property
    def shape(self) -> tuple:
        """(rows, cols)."""
        return self.image.shape

    def pixel_to_image(self, col, row):
        """x, y (mm) of pixel positions of this frame (see :func:`pixel_to_image`)."""
        return pixel_to_image(col, row, self.shape, self.pixel_size)

    def image_to_pixel(self, xy):
        """(col, row) of image coordinates (mm) of this frame (see :func:`image_to_pixel`)."""
        return image_to_pixel(xy, self.shape, self.pixel_size)

    def project(self, XYZ) -> np.ndarray:
        """(n, 2) pixel positions (col, row) of object points by (1.4.12) (no occlusion test)."""
        from .single_image import project
        return self.image_to_pixel(project(XYZ, self.eo, self.io))

    def __repr__(self) -> str:
        h, w = self.shape
        return (f"Rendering({h} × {w} pixels, {int(self.visible.sum())} see the scene, "
                f"Δ = {self.pixel_size:.3f} mm)")


def render_image(scene: TerrainScene, interior, exterior, shape, *, pixel_size: float = 0.01,
                 supersample: int = 2, noise: float = 0.0, background: float = 0.0, seed: int = 0,
                 ignore_distortion: bool = False) -> Rendering:
    """Render the textured surface of a scene into a frame camera with a z-buffer.

    The surface is the scene's triangulated DSM (see :class:`TerrainScene`); the camera follows
    Chapter 1: a pixel at (col, row) has image coordinates x, y of :func:`pixel_to_image`
    (frame centre = fiducial centre) and the ray X = S + t·A·(x − x₀, y − y₀, −f) of (1.4.5);
    vertices are projected by the collinearity equations (1.4.12). For each pixel centre the
    nearest intersection of its ray with the surface is found exactly (ray–plane intersection
    with the triangle that covers it), giving ``XYZ`` and ``depth``; the brightness is the
    albedo at the surface point, averaged over ``supersample ** 2`` sub-pixel rays (anti-aliasing),
    plus Gaussian noise. Triangles with a vertex behind the camera are not drawn.

    Parameters
    ----------
    scene : TerrainScene
        From :func:`terrain_scene`.
    interior : InteriorOrientation
        f, x₀, y₀ in mm (distortion is not rendered: see ``ignore_distortion``).
    exterior : ExteriorOrientation
        Projection centre and angles (radians).
    shape : (int, int)
        Rows and columns of the frame.
    pixel_size : float
        Δ, mm.
    supersample : int
        Sub-pixel rays per side for the brightness (1: the pixel centre only).
    noise : float
        Standard deviation of Gaussian noise added to the image (brightness units).
    background : float
        Brightness of pixels that see nothing.
    seed : int
        Seed of the noise.
    ignore_distortion : bool
        Render a camera with distortion coefficients as if it had none (otherwise InputError).

    Returns
    -------
    Rendering
        ``image``, ``depth``, ``XYZ``, ``visible`` and the orientation.

    Raises
    ------
    InputError
        Wrong types, a bad shape or pixel size, a camera with distortion, a projection centre
        below the surface of the scene.
    PointBehindCameraError
        The whole scene is behind the camera.
    DegenerateGeometryError
        The scene is entirely outside the frame.

    References
    ----------
    Chibunichev (2022), §1.4, eqs. (1.4.5), (1.4.10)–(1.4.12); §1.10 (pixel coordinates).

    Examples
    --------
    >>> from photolib.camera import InteriorOrientation, ExteriorOrientation
    >>> from photolib.synthetic import terrain_scene, render_image
    >>> sc = terrain_scene(extent=60.0, spacing=0.5, n_buildings=1, seed=2)
    >>> eo = ExteriorOrientation(30.0, 30.0, 400.0)
    >>> r = render_image(sc, InteriorOrientation(50.0), eo, (32, 32), pixel_size=0.05)
    >>> r.image.shape, r.XYZ.shape, bool(r.visible.all())
    ((32, 32), (32, 32, 3), True)
    >>> c, rw = 16, 16
    >>> bool(abs(r.XYZ[rw, c, 2] - sc.surface_at(r.XYZ[rw, c, 0], r.XYZ[rw, c, 1])) < 1e-9)
    True
    """
    from .camera import ExteriorOrientation, _expect
    from .single_image import camera_coordinates
    _expect(scene, TerrainScene, "scene")
    _expect(interior, InteriorOrientation, "interior")
    _expect(exterior, ExteriorOrientation, "exterior")
    h, w = _frame_shape(shape)
    d = _finite(pixel_size, "pixel_size", positive=True)
    k = _count(supersample, "supersample", 1)
    noise = _finite(noise, "noise", nonnegative=True)
    background = _finite(background, "background")
    seed = _count(seed, "seed", 0)
    if interior.has_distortion and not ignore_distortion:
        raise InputError("the renderer draws distortion-free images: pass ignore_distortion=True to render a "
                         "camera with distortion coefficients as an ideal one")
    S = exterior.center
    z_under = scene.surface_at(S[0], S[1])
    if np.isfinite(z_under) and S[2] <= z_under:
        raise InputError(f"the projection centre (Z = {S[2]:.2f} m) is below the surface of the scene "
                         f"({float(z_under):.2f} m)")
    P = np.stack([scene.X, scene.Y, scene.surface], axis=-1)
    star = camera_coordinates(P.reshape(-1, 3), exterior).reshape(P.shape)
    front = star[..., 2] < -1e-9
    if not front.any():
        raise PointBehindCameraError("the whole scene is behind the camera (Z* >= 0 for every node)")
    with np.errstate(divide="ignore", invalid="ignore"):
        zs = np.where(front, star[..., 2], -1.0)
        xm = interior.x0 - interior.f * star[..., 0] / zs
        ym = interior.y0 - interior.f * star[..., 1] / zs
    A = np.ascontiguousarray(exterior.matrix)
    from . import _render_kernels as kern

    def trace(hh, ww, dd):
        col = xm / dd + (ww - 1) / 2
        row = (hh - 1) / 2 - ym / dd
        col, row = np.where(front, col, 0.0), np.where(front, row, 0.0)
        t, _ = kern.rasterise(col, row, front, P, S, A, float(interior.x0), float(interior.y0),
                              float(interior.f), dd, hh, ww)
        hit = np.isfinite(t)
        cc, rr = np.meshgrid(np.arange(ww, dtype=float), np.arange(hh, dtype=float))
        x = (cc - (ww - 1) / 2) * dd - interior.x0
        y = ((hh - 1) / 2 - rr) * dd - interior.y0
        ray = np.stack([x, y, np.full_like(x, -interior.f)], axis=-1) @ A.T
        XYZ = np.where(hit[..., None], S + np.where(hit, t, 0.0)[..., None] * ray, np.nan)
        dist = np.where(hit, np.where(hit, t, 0.0) * np.linalg.norm(ray, axis=-1), np.nan)
        return hit, XYZ, dist

    hit, XYZ, depth = trace(h, w, d)
    if k == 1:
        value = np.where(hit, scene.albedo_at(np.nan_to_num(XYZ[..., 0]), np.nan_to_num(XYZ[..., 1])), background)
    else:
        hit_f, XYZ_f, _ = trace(h * k, w * k, d / k)
        val = np.where(hit_f, scene.albedo_at(np.nan_to_num(XYZ_f[..., 0]), np.nan_to_num(XYZ_f[..., 1])), np.nan)
        val = np.where(np.isfinite(val), val, background)
        value = val.reshape(h, k, w, k).mean(axis=(1, 3))
        value = np.where(hit | hit_f.reshape(h, k, w, k).any(axis=(1, 3)), value, background)
    if not hit.any():
        raise DegenerateGeometryError("the scene lies entirely outside the frame")
    if noise > 0:
        value = value + np.random.default_rng(seed).normal(0.0, noise, value.shape)
    return Rendering(value.astype(float), depth, XYZ, hit, interior, exterior, d)


@dataclass(frozen=True)
class MicroFrameCamera:
    """A frame camera whose focal plane is tiled by several matrices (micro-frames), §8.18.

    Attributes
    ----------
    interior : InteriorOrientation
        The camera (f, mm).
    exterior : ExteriorOrientation
        Its exterior orientation.
    pixel_size : float
        Δ, mm.
    frame_shape : (int, int)
        Rows and columns of the conventional frame that holds all matrices.
    matrix_shape : (int, int)
        Rows and columns of one matrix.
    offsets : tuple of (int, int)
        (row, column) of each matrix's first pixel in the conventional frame.

    References
    ----------
    Chibunichev (2022), §8.18, Figs. 8.40–8.42 (micro-frames combined into one image).

    Examples
    --------
    >>> cam = microframe_camera()
    >>> len(cam.offsets), cam.matrix_shape
    (6, (985, 1920))
    """

    interior: InteriorOrientation
    exterior: object
    pixel_size: float
    frame_shape: tuple
    matrix_shape: tuple
    offsets: tuple

    def ground_of(self, index: int):
        """The sensor of matrix ``index`` as ``(rows, cols, heights) -> (X, Y)`` (matrix pixels).

        Parameters
        ----------
        index : int
            The matrix, 0 … len(offsets) − 1.

        Returns
        -------
        callable
            Image → ground at given heights, through :func:`photolib.single_image.image_to_ground`.

        Raises
        ------
        InputError
            An index out of range.

        References
        ----------
        Chibunichev (2022), §8.18.

        Examples
        --------
        >>> X, Y = microframe_camera().ground_of(0)(492.0, 959.5, 0.0)
        >>> bool(abs(X) < 1e4 and abs(Y) < 1e4)
        True
        """
        from .single_image import image_to_ground

        if isinstance(index, bool) or not isinstance(index, (int, np.integer)) or not 0 <= index < len(self.offsets):
            raise InputError(f"index must be a matrix number 0…{len(self.offsets) - 1}, got {index!r}")
        r0, c0 = self.offsets[index]

        def ground_of(rows, cols, heights):
            shape = np.shape(rows)
            xy = np.stack(pixel_to_image(np.ravel(cols) + c0, np.ravel(rows) + r0, self.frame_shape,
                                         self.pixel_size), -1)
            XYZ = image_to_ground(xy, np.ravel(np.broadcast_to(heights, shape)), self.exterior, self.interior)
            return XYZ[:, 0].reshape(shape), XYZ[:, 1].reshape(shape)
        return ground_of

    def project(self, XYZ) -> np.ndarray:
        """Rows and columns of object points in the conventional frame (collinearity), (n, 2).

        Parameters
        ----------
        XYZ : (n, 3) array
            Object points.

        Returns
        -------
        ndarray
            (n, 2): row, column.

        Raises
        ------
        InputError
            Bad shapes or NaN (from :func:`photolib.single_image.project`).

        References
        ----------
        Chibunichev (2022), §8.18; §1.4 (collinearity).

        Examples
        --------
        >>> cam = microframe_camera()
        >>> X, Y = cam.ground_of(0)(10.0, 20.0, 100.0)
        >>> cam.project([[float(X), float(Y), 100.0]]).round(6).tolist()
        [[10.0, 20.0]]
        """
        from .single_image import project

        col_row = image_to_pixel(project(XYZ, self.exterior, self.interior), self.frame_shape, self.pixel_size)
        return col_row[:, ::-1]


def microframe_camera() -> MicroFrameCamera:
    """A synthetic Kanopus-V-like micro-frame camera (parameters NOT from the book), §8.18.

    f = 1797.5 mm, 7.4 µm pixels, 510 km above flat ground (≈ 2.1 m GSD), six 985 × 1920 matrices in
    two staggered rows 1500 px apart along track with 100 px overlap across track; a slightly tilted
    exterior orientation (ω, α, κ = 0.004, −0.003, 0.02 rad, order ω–α–κ).

    Returns
    -------
    MicroFrameCamera

    Raises
    ------
    InputError
        Never (no input).

    References
    ----------
    Chibunichev (2022), §8.18; the Kanopus-V figures (f, matrix size, GSD, orbit) follow the
    ISPRS Archives XXXIX-B4 (2012) description, not the book.

    Examples
    --------
    >>> microframe_camera().frame_shape
    (2485, 11020)
    """
    from .camera import ExteriorOrientation

    return MicroFrameCamera(InteriorOrientation(f=1797.5),
                            ExteriorOrientation(0.0, 0.0, 510e3, 0.004, -0.003, 0.02, order="wak"),
                            0.0074, (2485, 11020), (985, 1920),
                            ((0, 0), (0, 3640), (0, 7280), (1500, 1820), (1500, 5460), (1500, 9100)))
