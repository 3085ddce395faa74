"""Aerial survey planning — Chapter 10, §10.3 (the technical project of an aerial phototopographic survey),
with Hanzl's §6 (acquisition of aerial images).

§10.3 lists what the technical project computes for the aerial photography — flying height over
the mean plane, ground sample distance (GSD), forward and side overlap, strip spacing, base and
exposure interval — but prints no formula; this module supplies the standard arithmetic:

* :func:`ground_sample_distance` and :func:`flying_height_for_gsd`: GSD = pixel · H / f;
* :func:`plan_block`: a rectangular block of parallel strips (:class:`FlightPlan`) with the
  footprint L = GSD · pixels, base b = (1 − p)·L, strip spacing s = (1 − q)·L, the number of strips
  for single coverage across the block and of exposures per strip for continuous stereo coverage
  along it, and the exposure interval b / v;
* the same over real relief: :func:`strip_over_relief` intersects the rays of every image of a
  strip of vertical images with a DEM and gives each image's GSD and the forward overlap of each
  consecutive pair as an image-area fraction, with its minimum (:class:`StripOverRelief`);
  :func:`dem_to_local` resamples a geographic DEM (EPSG:4326, e.g. SRTM) into a local metric
  transverse-Mercator frame, :func:`surface_dem` samples an analytic surface (a synthetic DEM);
* GCP marker design from the GSD rules of §10.3 (:func:`gcp_marker`, :func:`check_marker`): a cross
  whose arms are at least 4–20 GSD long and 2–3 GSD wide, the whole mark fitting a square of at
  least 8 pixels;
* the IMU tolerances under which §10.3 lets aerial triangulation be skipped (σ roll, pitch
  ≤ 0.005°, σ heading ≤ 0.01°, relief from ALS, plans not larger than 1:2000):
  :func:`skip_aerial_triangulation`, and what an attitude error means on the ground at the flying
  height: :func:`imu_ground_error`.

Hanzl, Fotogrammetrie, Modul 01, §6 (seed 002 lines 1046–1288): the diffraction limit
(:func:`diffraction_radius`), image motion (:func:`image_motion`), AWAR (:func:`awar`), flight
planning with the image-scale number and overlaps in per cent (:func:`photo_flight_plan`), the
empirical image scale of Tab. 6.1 (:func:`photo_scale_from_map`), target sizes (:func:`target_sizes`)
and the camera constant / radial distortion from goniometer angles (:func:`goniometer_distortion`).

Units: focal length and pixel size in mm (any one unit for both), flying heights, GSD and ground
sizes in m, angles in radians, speeds in m/s. Block frame: strips run along X; images are vertical
(nadir) with the camera x axis along the flight.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable, NamedTuple

import numpy as np

from . import _checks
from .errors import DegenerateGeometryError, InputError
from .lsq import solve_normal_equations
from .rectify import RasterGrid, dem_height

__all__ = ["ground_sample_distance", "flying_height_for_gsd", "FlightPlan", "plan_block",
           "StripOverRelief", "strip_over_relief", "dem_to_local", "surface_dem",
           "MarkerDesign", "gcp_marker", "MarkerCheck", "check_marker",
           "ImuGroundError", "imu_ground_error", "ATDecision", "skip_aerial_triangulation",
           "diffraction_radius", "image_motion", "awar", "PhotoFlightPlan", "photo_flight_plan",
           "photo_scale_from_map", "TargetSizes", "target_sizes", "GoniometerCalibration", "goniometer_distortion"]

# §10.3 (line 5841): marker rules, in GSD (pixels on the ground)
_ARM_MIN, _ARM_MAX, _WIDTH_MIN, _WIDTH_MAX, _SQUARE_MIN = 4.0, 20.0, 2.0, 3.0, 8.0
# §10.3 (line 5853): IMU accuracy that allows skipping aerial triangulation
_SIGMA_ROLL_PITCH = math.radians(0.005)
_SIGMA_HEADING = math.radians(0.01)
_LARGEST_PLAN = 2000.0


def _num(value, name, positive=False, allow_zero=False):
    return _checks.number(value, name, positive, allow_zero=allow_zero)


def _fraction(value, name, low_open=True):
    v = _num(value, name)
    if not (0.0 < v < 1.0 if low_open else 0.0 <= v < 1.0):
        lo = "(0, 1)" if low_open else "[0, 1)"
        raise InputError(f"{name} must be a fraction in {lo} (e.g. 0.6 for 60 %), got {value!r}"
                         + ("; an overlap of 100 % or more never advances" if v >= 1 else ""))
    return v


def _sensor(sensor):
    try:
        arr = np.asarray(sensor, dtype=float)
    except (TypeError, ValueError):
        raise InputError(f"sensor must be (pixels along track, pixels across track), got {sensor!r}") from None
    if arr.shape != (2,) or not np.all(np.isfinite(arr)) or np.any(arr < 1):
        raise InputError(f"sensor must be two pixel counts ≥ 1 (along track, across track), got {sensor!r}")
    return float(arr[0]), float(arr[1])


def _ceil(n):
    return int(math.ceil(n - 1e-9))


# ------------------------------------------------------------------------------------- GSD
def ground_sample_distance(pixel_size: float, f: float, flying_height: float) -> float:
    """Ground sample distance of a vertical image over a horizontal plane: GSD = pixel · H / f.

    Parameters
    ----------
    pixel_size, f : float
        Pixel size and focal length, one unit (mm); positive.
    flying_height : float
        Height of the projection centre above the plane, m; positive.

    Returns
    -------
    float
        GSD, m (the unit of ``flying_height``).

    Raises
    ------
    InputError
        Non-positive or non-finite values.

    References
    ----------
    Chibunichev (2022), §10.3 (the nominal spatial resolution on the ground, listed among the
    flight parameters); the image scale 1/m = f/H of §1.1.

    Examples
    --------
    >>> from photolib.planning import ground_sample_distance
    >>> round(ground_sample_distance(0.0052, 100.0, 1500.0), 4)
    0.078
    """
    p = _num(pixel_size, "pixel_size", True)
    return p * _num(flying_height, "flying_height", True) / _num(f, "f", True)


def flying_height_for_gsd(gsd: float, pixel_size: float, f: float) -> float:
    """Flying height above the mean plane that gives a required GSD: H = GSD · f / pixel.

    Parameters
    ----------
    gsd : float
        Required ground sample distance, m; positive.
    pixel_size, f : float
        Pixel size and focal length, one unit (mm); positive.

    Returns
    -------
    float
        H, m.

    Raises
    ------
    InputError
        Non-positive or non-finite values.

    References
    ----------
    Chibunichev (2022), §10.3 (flying height over the mean plane and GSD, listed parameters).

    Examples
    --------
    >>> from photolib.planning import flying_height_for_gsd
    >>> round(flying_height_for_gsd(0.05, 0.0046, 50.0), 1)
    543.5
    """
    g = _num(gsd, "gsd", True)
    return g * _num(f, "f", True) / _num(pixel_size, "pixel_size", True)


# ------------------------------------------------------------------------------------- block
@dataclass(frozen=True)
class FlightPlan:
    """A rectangular block of parallel strips of vertical images: see :func:`plan_block`.

    Attributes
    ----------
    flying_height, altitude : float
        Height above the mean plane and altitude (mean plane height + H), m.
    gsd : float
        Ground sample distance on the mean plane, m.
    footprint_along, footprint_across : float
        Ground footprint of an image along and across the flight, m.
    forward_overlap, side_overlap : float
        p and q as fractions.
    base, strip_spacing : float
        b = (1 − p)·L_along and s = (1 − q)·L_across, m.
    n_strips, images_per_strip, n_images : int
        Block size.
    exposure_interval : float
        b / v, s (NaN when no speed was given).
    strip_y, exposure_x : ndarray
        Strip axes (Y) and exposure positions along a strip (X) in the block frame, m.

    References
    ----------
    Chibunichev (2022), §10.3 (flight parameters of the technical project), §3.1 (strips, p, q).

    Examples
    --------
    >>> from photolib.planning import plan_block
    >>> plan = plan_block(3000.0, 2000.0, f=100.0, pixel_size=0.01, sensor=(10000, 10000), gsd=0.1)
    >>> plan.n_strips, plan.images_per_strip, plan.exposure_centres().shape
    (3, 8, (24, 2))
    """

    flying_height: float
    altitude: float
    gsd: float
    footprint_along: float
    footprint_across: float
    forward_overlap: float
    side_overlap: float
    base: float
    strip_spacing: float
    n_strips: int
    images_per_strip: int
    n_images: int
    exposure_interval: float
    strip_y: np.ndarray
    exposure_x: np.ndarray

    def exposure_centres(self) -> np.ndarray:
        """(n_images, 2) plan positions (X, Y) of all exposures, strip by strip."""
        X, Y = np.meshgrid(self.exposure_x, self.strip_y)
        return np.column_stack([X.ravel(), Y.ravel()])


def plan_block(length: float, width: float, *, f: float, pixel_size: float, sensor, gsd: float | None = None,
               flying_height: float | None = None, forward_overlap: float = 0.6, side_overlap: float = 0.3,
               speed: float | None = None, mean_height: float = 0.0, stereo: bool = True) -> FlightPlan:
    """Plan a rectangular block: height, GSD, footprint, base, strip spacing, strips and exposures.

    The block is ``[0, length] × [0, width]`` with strips along X. Strips: the fewest whose
    footprints cover the width, n_s = ⌈(W − L_across)/s⌉ + 1, centred on the block. Exposures: with
    ``stereo`` the fewest whose consecutive-pair overlaps (stereo models) cover the length; a strip
    of n images with base b covers (n − 3)·b + L_along in stereo, so n = ⌈(A − L_along)/b⌉ + 3
    (at least 2; p ≥ 50 % is needed for a gap-free stereo strip); without ``stereo`` single
    coverage, n = ⌈(A − L_along)/b⌉ + 1.

    Parameters
    ----------
    length, width : float
        Block size along and across the flight, m; positive.
    f, pixel_size : float
        Focal length and pixel size, mm.
    sensor : (int, int)
        Pixels along and across the flight.
    gsd, flying_height : float
        Exactly one of them: the GSD required (m) or the height above the mean plane (m).
    forward_overlap, side_overlap : float
        p in (0, 1) and q in [0, 1), fractions.
    speed : float, optional
        Ground speed, m/s, for the exposure interval.
    mean_height : float
        Height of the mean plane, m (gives ``altitude``).
    stereo : bool
        Stereo coverage along the strips (default) or single coverage.

    Returns
    -------
    FlightPlan

    Raises
    ------
    InputError
        Non-positive sizes, overlaps of 100 % or more (or negative), both or neither of ``gsd`` and
        ``flying_height``, p < 50 % with ``stereo``, a bad sensor.

    References
    ----------
    Chibunichev (2022), §10.3 (flying height, speed, GSD, forward and side overlap, strip spacing,
    exposure interval or base, listed for the technical project); §3.1 (layout of strips).

    Examples
    --------
    >>> from photolib.planning import plan_block
    >>> plan = plan_block(5000.0, 3000.0, f=100.0, pixel_size=0.005, sensor=(10000, 14000), gsd=0.1,
    ...                   speed=60.0)
    >>> plan.flying_height, plan.footprint_along, plan.base, plan.strip_spacing
    (2000.0, 1000.0, 400.0, 980.0)
    >>> plan.n_strips, plan.images_per_strip, round(plan.exposure_interval, 2)
    (3, 13, 6.67)
    """
    A = _num(length, "length", True)
    W = _num(width, "width", True)
    f = _num(f, "f", True)
    pix = _num(pixel_size, "pixel_size", True)
    n_along, n_across = _sensor(sensor)
    if (gsd is None) == (flying_height is None):
        raise InputError("give exactly one of gsd and flying_height")
    if gsd is not None:
        H = flying_height_for_gsd(gsd, pix, f)
    else:
        H = _num(flying_height, "flying_height", True)
    g = pix * H / f
    p = _fraction(forward_overlap, "forward_overlap")
    q = _fraction(side_overlap, "side_overlap", low_open=False)
    if stereo and p < 0.5:
        raise InputError(f"forward_overlap {p:.0%} < 50 % leaves gaps between the stereo models of a strip; "
                         f"raise it (60 % is usual) or plan with stereo=False")
    Lx, Ly = g * n_along, g * n_across
    b, s = (1 - p) * Lx, (1 - q) * Ly
    n_s = max(1, 1 + _ceil((W - Ly) / s))
    m = max(2, _ceil((A - Lx) / b) + 3) if stereo else max(1, 1 + _ceil((A - Lx) / b))
    if speed is None:
        dt = float("nan")
    else:
        dt = b / _num(speed, "speed", True)
    strip_y = W / 2 + (np.arange(n_s) - (n_s - 1) / 2) * s
    exposure_x = A / 2 + (np.arange(m) - (m - 1) / 2) * b
    return FlightPlan(H, _num(mean_height, "mean_height") + H, g, Lx, Ly, p, q, b, s, n_s, m, n_s * m, dt,
                      strip_y, exposure_x)


# ------------------------------------------------------------------------------------- relief
@dataclass(frozen=True)
class StripOverRelief:
    """A strip of vertical images over a DEM: per-image GSD and forward overlaps (:func:`strip_over_relief`).

    Attributes
    ----------
    centres : (n, 2) ndarray
        Plan positions of the exposures, m.
    altitude : float
        Altitude of the projection centres (the DEM's height datum), m.
    gsd_mean, gsd_min, gsd_max : (n,) ndarray
        GSD over each image's sample rays (pixel · (Z_S − Z) / f), m.
    forward_overlap : (n − 1,) ndarray
        Fraction of image i's area whose ground is also inside image i + 1's frame.
    min_overlap : float
        The smallest forward overlap; ``min_pair`` its pair index i.
    min_pair : int
    footprints : (n, m, 2) ndarray
        Ground outlines (X, Y) of the frames over the terrain, closed-order border points.

    References
    ----------
    Chibunichev (2022), §10.3 (forward overlap and GSD of the flight parameters), §7.3 (the DEM).

    Examples
    --------
    >>> import numpy as np
    >>> from photolib.planning import strip_over_relief, surface_dem
    >>> dem, grid = surface_dem(lambda X, Y: 0 * X, (-2000, -1000, 4000, 1000), 50.0)
    >>> s = strip_over_relief(dem, grid, (0, 0), (2000, 0), altitude=1000.0, base=400.0, f=100.0,
    ...                       pixel_size=0.01, sensor=(10000, 10000), samples=40)
    >>> np.round(s.forward_overlap, 3).tolist(), round(s.min_overlap, 3)
    ([0.6, 0.6, 0.6, 0.6, 0.6], 0.6)
    """

    centres: np.ndarray
    altitude: float
    gsd_mean: np.ndarray
    gsd_min: np.ndarray
    gsd_max: np.ndarray
    forward_overlap: np.ndarray
    min_overlap: float
    min_pair: int
    footprints: np.ndarray


def _dem(dem, grid):
    if not isinstance(grid, RasterGrid):
        raise InputError(f"dem_grid must be a RasterGrid, got {type(grid).__name__}")
    try:
        dem = np.asarray(dem, dtype=float)
    except (TypeError, ValueError):
        raise InputError("dem must be a 2-D array of heights") from None
    if dem.ndim != 2 or dem.shape != tuple(grid.shape):
        raise InputError(f"dem of shape {dem.shape} does not match its grid {tuple(grid.shape)}")
    if dem.shape[0] < 2 or dem.shape[1] < 2:
        raise InputError("a DEM needs at least 2 × 2 cells")
    return dem


def _point(value, name):
    try:
        arr = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise InputError(f"{name} must be a plan point (X, Y)") from None
    if arr.shape != (2,) or not np.all(np.isfinite(arr)):
        raise InputError(f"{name} must be a finite plan point (X, Y), got {value!r}")
    return arr


def _heights(dem, grid, X, Y):
    Z = dem_height(dem, grid, X, Y, outside="nan")
    if np.isnan(Z).any():
        raise InputError("the image footprints leave the DEM (or meet a void): shorten the strip, "
                         "fly lower or use a larger DEM")
    return Z


def _intersect(dem, grid, S, altitude, dirs, zmin, zmax, step):
    """First intersection of rays S + t·(dx, dy, −1) with the DEM, by marching then bisection.

    ``S`` (k, 2) plan positions of the centres, ``dirs`` (k, 2) horizontal slopes (u/f, v/f);
    returns the ground heights Z (k,)."""
    h0, h1 = altitude - zmax, altitude - zmin            # depth below the centre
    slope = float(np.max(np.hypot(dirs[:, 0], dirs[:, 1])))
    n = max(int(math.ceil((h1 - h0) * max(slope, 1e-12) / step)), 1)

    def gap(h):      # ray height minus terrain height; > 0 above the terrain
        return (altitude - h) - _heights(dem, grid, S[:, 0] + h * dirs[:, 0], S[:, 1] + h * dirs[:, 1])

    k = len(dirs)
    lo = np.full(k, h0)
    hi = np.full(k, h1)
    found = np.zeros(k, bool)
    prev = h0
    for h in np.linspace(h0, h1, n + 1)[1:]:
        todo = ~found
        below = np.zeros(k, bool)
        below[todo] = ((altitude - h) - _heights(dem, grid, S[todo, 0] + h * dirs[todo, 0],
                                                 S[todo, 1] + h * dirs[todo, 1])) <= 0
        hi[below] = h
        lo[below] = prev
        found |= below
        if found.all():
            break
        prev = h
    if not found.all():
        raise DegenerateGeometryError("a ray did not meet the DEM (terrain out of the height range)")
    for _ in range(int(math.ceil(math.log2(max((h1 - h0) / n, 1e-3) / 1e-4))) + 1):   # to 0.1 mm
        mid = 0.5 * (lo + hi)
        below = gap(mid) <= 0
        hi = np.where(below, mid, hi)
        lo = np.where(below, lo, mid)
    return altitude - 0.5 * (lo + hi)


def strip_over_relief(dem, dem_grid: RasterGrid, start, end, *, altitude: float, base: float, f: float,
                      pixel_size: float, sensor, samples: int = 60) -> StripOverRelief:
    """Per-image GSD and forward overlap of a strip of vertical images flown over a DEM.

    Exposures are spaced by ``base`` from ``start`` towards ``end`` at a constant ``altitude``;
    every image is vertical with its x axis along the flight. A regular grid of ``samples`` ×
    ``samples`` rays through the centres of equal cells of each frame is intersected with the
    DEM (the first crossing, marched in steps of half a DEM cell and refined by bisection); the
    GSD of a ray is pixel · (Z_S − Z)/f and the forward overlap of a pair (i, i + 1) is the
    fraction of image i's cells whose ground point falls inside the frame of image i + 1 (an
    image-area fraction, resolved to 1/``samples``; occlusion in image i + 1 is not tested). Over
    a plane at depth H below the camera it equals 1 − b/L exactly; over relief the overlap drops
    where the ground rises.

    Parameters
    ----------
    dem : (R, C) array
        Heights, m, in a metric frame (see :func:`dem_to_local`); no voids under the footprints.
    dem_grid : RasterGrid
        Its grid.
    start, end : (2,) array_like
        Plan positions of the first exposure and of the direction's end, m.
    altitude : float
        Altitude of the projection centres, m (above every terrain point under the strip).
    base : float
        Distance between exposures, m (e.g. :attr:`FlightPlan.base`).
    f, pixel_size : float
        Focal length and pixel size, mm.
    sensor : (int, int)
        Pixels along and across the flight.
    samples : int
        Rays per frame side (≥ 3); the overlaps are resolved to 1/``samples``.

    Returns
    -------
    StripOverRelief

    Raises
    ------
    InputError
        Bad DEM or grid, start = end, a strip shorter than one base, footprints leaving the DEM,
        non-positive sizes.
    DegenerateGeometryError
        The altitude is not above the terrain under the strip or inside its footprints.

    References
    ----------
    Chibunichev (2022), §10.3 (forward overlap, GSD and flying height over the mean plane in the
    technical project); §7.3, eq. (7.3.1) (bilinear DEM heights).

    Examples
    --------
    >>> from photolib.planning import strip_over_relief, surface_dem
    >>> dem, grid = surface_dem(lambda X, Y: 0.1 * X, (-2000, -1000, 4000, 1000), 25.0)
    >>> s = strip_over_relief(dem, grid, (0, 0), (800, 0), altitude=1200.0, base=400.0, f=100.0,
    ...                       pixel_size=0.01, sensor=(10000, 10000), samples=200)
    >>> s.forward_overlap.round(2).tolist()     # analytic over the plane Z = 0.1 X: 0.672, 0.661
    [0.67, 0.66]
    """
    dem = _dem(dem, dem_grid)
    start, end = _point(start, "start"), _point(end, "end")
    Zs = _num(altitude, "altitude")
    b = _num(base, "base", True)
    f = _num(f, "f", True)
    pix = _num(pixel_size, "pixel_size", True)
    n_along, n_across = _sensor(sensor)
    k = _checks.integer(samples, "samples", 3)
    d = end - start
    length = float(np.hypot(*d))
    if length < b:
        raise InputError(f"the strip from start to end ({length:.1f} m) is shorter than one base ({b} m)")
    along = d / length
    left = np.array([-along[1], along[0]])
    n_img = int(math.floor(length / b + 1e-9)) + 1
    centres = start + np.outer(np.arange(n_img) * b, along)
    a, c = n_along * pix / 2, n_across * pix / 2
    t = (np.arange(k) + 0.5) / k * 2 - 1                        # cell centres in (−1, 1)
    U, V = np.meshgrid(t * a, t * c, indexing="ij")
    e = np.linspace(-1, 1, k)
    border = np.concatenate([np.column_stack([e * a, np.full(k, -c)]), np.column_stack([np.full(k, a), e * c]),
                             np.column_stack([e[::-1] * a, np.full(k, c)]),
                             np.column_stack([np.full(k, -a), e[::-1] * c])])
    uv = np.vstack([np.column_stack([U.ravel(), V.ravel()]), border])
    dirs = (uv[:, :1] * along + uv[:, 1:] * left) / f              # horizontal offset per metre of depth
    finite = dem[np.isfinite(dem)]
    if finite.size == 0:
        raise InputError("the DEM has no heights")
    zmin, zmax = float(finite.min()), float(finite.max())
    # heights under the strip line decide whether the camera is above the terrain
    under = _heights(dem, dem_grid, centres[:, 0], centres[:, 1])
    if np.any(under >= Zs):
        raise DegenerateGeometryError(f"altitude {Zs} m is not above the terrain under the strip "
                                      f"(up to {under.max():.1f} m)")
    zmax = min(zmax, Zs - 1e-6)
    step = 0.5 * min(dem_grid.dx, dem_grid.dy)
    n_cells = k * k
    S_all = np.repeat(centres, len(dirs), axis=0)
    dirs_all = np.tile(dirs, (n_img, 1))
    Z_all = _intersect(dem, dem_grid, S_all, Zs, dirs_all, zmin, zmax, step)
    XY_all = S_all + (Zs - Z_all)[:, None] * dirs_all
    Xc, Yc = dem_grid.centres()
    box = ((Xc >= XY_all[:, 0].min()) & (Xc <= XY_all[:, 0].max()) & (Yc >= XY_all[:, 1].min())
           & (Yc <= XY_all[:, 1].max()))
    if np.nanmax(np.where(box, dem, -np.inf)) >= Zs:
        raise DegenerateGeometryError(f"the terrain reaches the flying altitude {Zs} m inside the footprints "
                                      f"(up to {np.nanmax(np.where(box, dem, -np.inf)):.1f} m): fly higher")
    ground = [(XY_all[i * len(dirs):(i + 1) * len(dirs)], Z_all[i * len(dirs):(i + 1) * len(dirs)])
              for i in range(n_img)]
    gsd = [pix * (Zs - Z[:n_cells]) / f for _, Z in ground]
    overlaps = []
    for i in range(n_img - 1):
        XY, Z = ground[i]
        XY, Z = XY[:n_cells], Z[:n_cells]
        rel = XY - centres[i + 1]
        depth = Zs - Z
        u = f * (rel @ along) / depth
        v = f * (rel @ left) / depth
        inside = (np.abs(u) <= a) & (np.abs(v) <= c)
        overlaps.append(float(inside.mean()))
    overlaps = np.array(overlaps)
    j = int(np.argmin(overlaps)) if overlaps.size else -1
    return StripOverRelief(centres, Zs, np.array([g.mean() for g in gsd]), np.array([g.min() for g in gsd]),
                           np.array([g.max() for g in gsd]), overlaps,
                           float(overlaps[j]) if overlaps.size else float("nan"), j,
                           np.stack([XY[n_cells:] for XY, _ in ground]))


def surface_dem(surface: Callable, bounds, spacing: float):
    """Sample an analytic surface Z(X, Y) on a DEM grid (a synthetic DEM that needs no data).

    Parameters
    ----------
    surface : callable
        ``surface(X, Y)`` → heights (e.g. :func:`photolib.synthetic.terrain_height`), vectorised.
    bounds : (xmin, ymin, xmax, ymax)
        Extent of the grid's outer pixel edges, m.
    spacing : float
        Cell size, m.

    Returns
    -------
    heights : ndarray
    grid : RasterGrid

    Raises
    ------
    InputError
        Bad bounds (empty, non-finite), a non-positive spacing, a surface returning the wrong
        shape or non-finite heights, a non-callable surface.

    References
    ----------
    Chibunichev (2022), §7.3 (DEM grid, eq. (7.3.1)); the terrain of §3.5's simulations.

    Examples
    --------
    >>> from photolib.planning import surface_dem
    >>> from photolib.synthetic import terrain_height
    >>> dem, grid = surface_dem(terrain_height, (0, 0, 1000, 500), 100.0)
    >>> dem.shape, grid.extent
    ((5, 10), (0.0, 0.0, 1000.0, 500.0))
    """
    if not callable(surface):
        raise InputError("surface must be a callable Z(X, Y)")
    try:
        x0, y0, x1, y1 = (float(v) for v in bounds)
    except (TypeError, ValueError):
        raise InputError(f"bounds must be (xmin, ymin, xmax, ymax), got {bounds!r}") from None
    if not all(math.isfinite(v) for v in (x0, y0, x1, y1)) or x1 <= x0 or y1 <= y0:
        raise InputError(f"bounds must be finite with xmin < xmax and ymin < ymax, got {bounds!r}")
    h = _num(spacing, "spacing", True)
    shape = (max(int(round((y1 - y0) / h)), 2), max(int(round((x1 - x0) / h)), 2))
    grid = RasterGrid(x0, y1, h, shape)
    X, Y = grid.centres()
    Z = np.asarray(surface(X, Y), dtype=float)
    if Z.shape != X.shape:
        Z = np.broadcast_to(Z, X.shape).astype(float) if Z.ndim == 0 else Z
    if Z.shape != X.shape or not np.all(np.isfinite(Z)):
        raise InputError("surface(X, Y) must return finite heights of the grid's shape")
    return Z.copy(), grid


def dem_to_local(heights, grid: RasterGrid, crs, *, spacing: float | None = None, bounds=None):
    """Resample a DEM into a local metric frame: transverse Mercator centred on the DEM.

    The frame (east X, north Y, metres, scale 1 on its central meridian; the distortion is below
    1e-5 within ±30 km of it) has its origin at the centre of the DEM; the output grid is the
    largest axis-aligned rectangle inside the DEM (or ``bounds`` in that frame) and heights are
    bilinear (:func:`photolib.georaster.dem_on_grid`). Heights keep their datum (SRTM: above
    the EGM96 geoid), so a flying altitude must be given in the same datum.

    Parameters
    ----------
    heights : (R, C) array
        DEM heights, m.
    grid : RasterGrid
        Its grid in ``crs``.
    crs : CRS
        The DEM's CRS (geographic, e.g. EPSG:4326, or projected).
    spacing : float, optional
        Output cell size, m (default: the DEM's north–south cell size in metres, rounded).
    bounds : (xmin, ymin, xmax, ymax), optional
        Output extent in the local frame, m.

    Returns
    -------
    heights : ndarray
    local_grid : RasterGrid
    local_crs : pyproj.CRS

    Raises
    ------
    InputError
        Bounds outside the DEM, bad inputs.
    GeoDependencyError
        pyproj missing.

    References
    ----------
    Chibunichev (2022), §7.3 (DEM in the map projection of the orthophoto), §10.3 (flight planning
    over the mean plane).

    Examples
    --------
    >>> import numpy as np
    >>> from photolib.rectify import RasterGrid
    >>> from photolib.planning import dem_to_local
    >>> Z, g, crs = dem_to_local(np.full((60, 60), 500.0), RasterGrid(40.0, 40.0, 0.001, (60, 60)),
    ...                          "EPSG:4326", spacing=100.0)
    >>> float(Z.mean()), g.shape
    (500.0, (65, 50))
    """
    from .georaster import _crs, _import, dem_on_grid, transform_points
    pyproj = _import("pyproj")
    heights = _dem(heights, grid)
    src = _crs(crs)
    X0, Y0, X1, Y1 = grid.extent
    cx, cy = (X0 + X1) / 2, (Y0 + Y1) / 2
    if src.is_geographic:
        lon0, lat0 = cx, cy
    else:
        lon0, lat0 = (float(v[0]) for v in transform_points([cx], [cy], src, "EPSG:4326"))
    local = pyproj.CRS.from_proj4(f"+proj=tmerc +lat_0={lat0} +lon_0={lon0} +k=1 +x_0=0 +y_0=0 "
                                  f"+ellps=WGS84 +units=m +no_defs")
    # the DEM's centre-of-pixel boundary in the local frame
    Xc, Yc = grid.centres()
    edges = [(Xc[:, 0], Yc[:, 0]), (Xc[:, -1], Yc[:, -1]), (Xc[0, :], Yc[0, :]), (Xc[-1, :], Yc[-1, :])]
    ex = [transform_points(x, y, src, local) for x, y in edges]
    inner = (float(np.max(ex[0][0])), float(np.max(ex[3][1])), float(np.min(ex[1][0])), float(np.min(ex[2][1])))
    if spacing is None:
        ys = ex[0][1]
        spacing = float(np.round(abs(ys[0] - ys[-1]) / (len(ys) - 1))) or 1.0
    h = _num(spacing, "spacing", True)
    if bounds is None:
        x0, y0, x1, y1 = inner
    else:
        try:
            x0, y0, x1, y1 = (float(v) for v in bounds)
        except (TypeError, ValueError):
            raise InputError(f"bounds must be (xmin, ymin, xmax, ymax), got {bounds!r}") from None
        if not (x0 >= inner[0] and y0 >= inner[1] and x1 <= inner[2] and y1 <= inner[3] and x0 < x1 and y0 < y1):
            raise InputError(f"bounds {bounds!r} are not inside the DEM's local extent "
                             f"({inner[0]:.0f}, {inner[1]:.0f}, {inner[2]:.0f}, {inner[3]:.0f}) m")
    shape = (int((y1 - y0) // h), int((x1 - x0) // h))
    if min(shape) < 2:
        raise InputError(f"the local grid would have {shape} cells: spacing {h} m is too large")
    local_grid = RasterGrid(x0, y0 + shape[0] * h, h, shape)
    return dem_on_grid(heights, grid, src, local_grid, local), local_grid, local


# ------------------------------------------------------------------------------------- markers
class MarkerDesign(NamedTuple):
    """Cross-shaped GCP marker sizes for a GSD: see :func:`gcp_marker`.

    Attributes
    ----------
    gsd : float
        Ground sample distance, m.
    arm_min, arm_max : float
        The range 4–20 GSD within which the arm's minimum length is chosen, m.
    width_min, width_max : float
        Arm width 2–3 GSD, m.
    square_min : float
        Side of the smallest square the whole mark must fill, 8 GSD, m.

    References
    ----------
    Chibunichev (2022), §10.3 (marking of ground control points).

    Examples
    --------
    >>> from photolib.planning import MarkerDesign
    >>> MarkerDesign(0.1, 0.4, 2.0, 0.2, 0.3, 0.8).square_min
    0.8
    """

    gsd: float
    arm_min: float
    arm_max: float
    width_min: float
    width_max: float
    square_min: float


def gcp_marker(gsd: float) -> MarkerDesign:
    """Sizes of a cross-shaped GCP marker from the GSD rules of §10.3.

    Each arm at least 4–20 GSD long (the book gives the minimum as a range), 2–3 GSD wide, the
    whole mark inscribed in a square of at least 8 pixels. With arms measured from the centre the
    two rules agree: a cross with 4-GSD arms spans 8 GSD.

    Parameters
    ----------
    gsd : float
        Ground sample distance of the planned photography, m.

    Returns
    -------
    MarkerDesign

    Raises
    ------
    InputError
        A non-positive or non-finite GSD.

    References
    ----------
    Chibunichev (2022), §10.3 (line 5841 of the seed: marker arms, width, square).

    Examples
    --------
    >>> from photolib.planning import gcp_marker
    >>> m = gcp_marker(0.05)
    >>> round(m.arm_min, 3), round(m.arm_max, 3), round(m.width_min, 3), round(m.width_max, 3), round(m.square_min, 3)
    (0.2, 1.0, 0.1, 0.15, 0.4)
    """
    g = _num(gsd, "gsd", True)
    return MarkerDesign(g, _ARM_MIN * g, _ARM_MAX * g, _WIDTH_MIN * g, _WIDTH_MAX * g, _SQUARE_MIN * g)


class MarkerCheck(NamedTuple):
    """A marker measured in pixels against the §10.3 rules: see :func:`check_marker`.

    Attributes
    ----------
    arm_px, width_px, span_px : float
        Arm length (from the centre), arm width and the whole cross (2 · arm) in GSD.
    arm_ok, width_ok, square_ok : bool
        arm ≥ 4 GSD; 2 ≤ width ≤ 3 GSD; span ≥ 8 GSD.
    ok : bool
        All three.

    References
    ----------
    Chibunichev (2022), §10.3.

    Examples
    --------
    >>> from photolib.planning import MarkerCheck
    >>> MarkerCheck(5.0, 2.5, 10.0, True, True, True, True).ok
    True
    """

    arm_px: float
    width_px: float
    span_px: float
    arm_ok: bool
    width_ok: bool
    square_ok: bool
    ok: bool


def check_marker(arm_length: float, arm_width: float, gsd: float) -> MarkerCheck:
    """Check a cross marker (arm length from the centre, arm width, m) against the GSD rules.

    Parameters
    ----------
    arm_length, arm_width : float
        Arm length measured from the centre of the cross and arm width, m; positive, width < 2·arm.
    gsd : float
        Ground sample distance, m.

    Returns
    -------
    MarkerCheck

    Raises
    ------
    InputError
        Non-positive sizes, a width not smaller than the cross.

    References
    ----------
    Chibunichev (2022), §10.3 (line 5841 of the seed).

    Examples
    --------
    >>> from photolib.planning import check_marker
    >>> c = check_marker(0.5, 0.12, 0.05)
    >>> round(c.arm_px, 2), round(c.width_px, 2), c.ok
    (10.0, 2.4, True)
    >>> check_marker(0.5, 0.3, 0.05).width_ok
    False
    """
    arm = _num(arm_length, "arm_length", True)
    width = _num(arm_width, "arm_width", True)
    g = _num(gsd, "gsd", True)
    if width >= 2 * arm:
        raise InputError(f"arm_width {width} m is not smaller than the cross (2 × arm = {2 * arm} m)")
    a, w = arm / g, width / g
    tol = 1e-9
    arm_ok = a >= _ARM_MIN - tol
    width_ok = _WIDTH_MIN - tol <= w <= _WIDTH_MAX + tol
    square_ok = 2 * a >= _SQUARE_MIN - tol
    return MarkerCheck(a, w, 2 * a, bool(arm_ok), bool(width_ok), bool(square_ok),
                       bool(arm_ok and width_ok and square_ok))


# ------------------------------------------------------------------------------------- IMU
class ImuGroundError(NamedTuple):
    """Ground displacement caused by attitude errors: see :func:`imu_ground_error`.

    Attributes
    ----------
    roll_nadir, pitch_nadir : float
        H · tan σ at the nadir, m.
    roll_edge, pitch_edge : float
        H · (tan(θ + σ) − tan θ) at the off-nadir angle θ of the frame edge, m.
    heading_edge : float
        Displacement 2 r sin(σ/2) of a point at ground distance r = H tan θ from the nadir, m.
    total_edge : float
        The root sum of squares of the three edge terms, m.

    References
    ----------
    Chibunichev (2022), §10.3 (line 5853: IMU accuracy), §1.3 (angular elements).

    Examples
    --------
    >>> from photolib.planning import ImuGroundError
    >>> ImuGroundError(1, 1, 1, 1, 1, 1.7).total_edge
    1.7
    """

    roll_nadir: float
    pitch_nadir: float
    roll_edge: float
    pitch_edge: float
    heading_edge: float
    total_edge: float


def imu_ground_error(sigma_roll: float, sigma_pitch: float, sigma_heading: float, flying_height: float,
                     half_field: float = 0.0) -> ImuGroundError:
    """Ground displacement of image points due to attitude errors of a vertical camera.

    A tilt error σ moves the ground point of a ray at off-nadir angle θ (in the plane of the tilt)
    by H · (tan(θ + σ) − tan θ) (= H tan σ at the nadir, ≈ H σ / cos²θ); a heading error turns
    the footprint about the nadir, moving a point at ground distance r = H tan θ by 2 r sin(σ/2).

    Parameters
    ----------
    sigma_roll, sigma_pitch, sigma_heading : float
        Attitude errors, rad (non-negative).
    flying_height : float
        H above the ground, m.
    half_field : float
        θ of the frame edge (half the field of view), rad, in [0, π/2).

    Returns
    -------
    ImuGroundError

    Raises
    ------
    InputError
        Negative or non-finite angles, θ outside [0, π/2), a non-positive height.

    References
    ----------
    Chibunichev (2022), §10.3 (line 5853: σ roll, pitch ≤ 0.005°, σ heading ≤ 0.01°).

    Examples
    --------
    >>> import math
    >>> from photolib.planning import imu_ground_error
    >>> e = imu_ground_error(math.radians(0.005), math.radians(0.005), math.radians(0.01), 1000.0,
    ...                      math.atan(0.5))
    >>> round(e.roll_nadir, 4), round(e.roll_edge, 4), round(e.heading_edge, 4)
    (0.0873, 0.1091, 0.0873)
    """
    sr = _num(sigma_roll, "sigma_roll", True, allow_zero=True)
    sp_ = _num(sigma_pitch, "sigma_pitch", True, allow_zero=True)
    sh = _num(sigma_heading, "sigma_heading", True, allow_zero=True)
    H = _num(flying_height, "flying_height", True)
    th = _num(half_field, "half_field", True, allow_zero=True)
    if th >= math.pi / 2 or max(sr, sp_, sh) >= math.pi / 2 or th + max(sr, sp_) >= math.pi / 2:
        raise InputError("half_field and the attitude errors must stay below π/2 rad (are they in degrees?)")

    def tilt(s, t):
        return H * (math.tan(t + s) - math.tan(t))

    re_, pe = tilt(sr, th), tilt(sp_, th)
    he = 2 * H * math.tan(th) * math.sin(sh / 2)
    return ImuGroundError(tilt(sr, 0.0), tilt(sp_, 0.0), re_, pe, he, math.sqrt(re_ ** 2 + pe ** 2 + he ** 2))


class ATDecision(NamedTuple):
    """Whether aerial triangulation may be skipped: see :func:`skip_aerial_triangulation`.

    Attributes
    ----------
    skip : bool
        True when every condition of §10.3 holds.
    reasons : tuple of str
        The conditions that fail (empty when ``skip``).

    References
    ----------
    Chibunichev (2022), §10.3.

    Examples
    --------
    >>> from photolib.planning import ATDecision
    >>> ATDecision(True, ()).skip
    True
    """

    skip: bool
    reasons: tuple


def skip_aerial_triangulation(sigma_roll: float, sigma_pitch: float, sigma_heading: float, *,
                              relief_from_lidar: bool, plan_scale: float,
                              cadastral_points: bool = False) -> ATDecision:
    """The §10.3 rule: may aerial triangulation be skipped with these IMU accuracies?

    It may when the relief comes from airborne laser scanning, no high-accuracy cadastral points
    are required, the plan (orthophoto) is not larger than 1:2000, and the IMU's standard errors
    are at most 0.005° in roll and pitch and 0.01° in heading. Stereotopographic relief always
    requires triangulation.

    Parameters
    ----------
    sigma_roll, sigma_pitch, sigma_heading : float
        IMU standard errors, rad.
    relief_from_lidar : bool
        Relief surveyed by ALS (True) or stereotopographically (False).
    plan_scale : float
        Scale denominator of the plan or orthophoto (2000 for 1:2000).
    cadastral_points : bool
        High-accuracy coordinates of boundary points are required.

    Returns
    -------
    ATDecision

    Raises
    ------
    InputError
        Negative or non-finite errors, a non-positive scale denominator, non-bool flags.

    References
    ----------
    Chibunichev (2022), §10.3 (line 5853 of the seed).

    Examples
    --------
    >>> import math
    >>> from photolib.planning import skip_aerial_triangulation
    >>> skip_aerial_triangulation(math.radians(0.004), math.radians(0.004), math.radians(0.01),
    ...                           relief_from_lidar=True, plan_scale=2000).skip
    True
    >>> skip_aerial_triangulation(math.radians(0.004), math.radians(0.006), 0.0,
    ...                           relief_from_lidar=True, plan_scale=500).reasons
    ('σ pitch 0.0060° > 0.005°', 'a plan at 1:500 is larger than 1:2000')
    """
    sr = _num(sigma_roll, "sigma_roll", True, allow_zero=True)
    sp_ = _num(sigma_pitch, "sigma_pitch", True, allow_zero=True)
    sh = _num(sigma_heading, "sigma_heading", True, allow_zero=True)
    scale = _num(plan_scale, "plan_scale", True)
    for name, flag in (("relief_from_lidar", relief_from_lidar), ("cadastral_points", cadastral_points)):
        if not isinstance(flag, (bool, np.bool_)):
            raise InputError(f"{name} must be True or False, got {flag!r}")
    tol = 1e-12
    reasons = []
    if not relief_from_lidar:
        reasons.append("stereotopographic relief requires aerial triangulation")
    for name, s, limit in (("roll", sr, _SIGMA_ROLL_PITCH), ("pitch", sp_, _SIGMA_ROLL_PITCH),
                           ("heading", sh, _SIGMA_HEADING)):
        if s > limit + tol:
            reasons.append(f"σ {name} {math.degrees(s):.4f}° > {math.degrees(limit):g}°")
    if scale < _LARGEST_PLAN:
        reasons.append(f"a plan at 1:{scale:g} is larger than 1:{_LARGEST_PLAN:g}")
    if cadastral_points:
        reasons.append("high-accuracy cadastral points are required")
    return ATDecision(not reasons, tuple(reasons))


# ------------------------------------------------------------------------------------- Hanzl §6
# Hanzl, Fotogrammetrie, Modul 01, §6 "Pořízení leteckých snímků" (seed 002 lines 1046–1288):
# camera calibration by goniometer (§6.1), image quality (§6.3), flight planning (§6.4) and the sizes
# of signalised control points (§6.5). Symbols as in the text: m_s is the image-scale *number*
# (e.g. 10 000), c the camera constant, s the side of the image format, p, q overlaps in per cent.
_HANZL = "Hanzl, Fotogrammetrie, Modul 01"


def _positive_array(value, name, min_size=1):
    try:
        arr = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise InputError(f"{name} must be an array of numbers, got {value!r}") from None
    arr = np.atleast_1d(arr)
    if arr.ndim != 1 or arr.size < min_size:
        raise InputError(f"{name} must be a 1-D array of at least {min_size} number(s), got shape {arr.shape}")
    if not np.all(np.isfinite(arr)):
        raise InputError(f"{name} contains NaN or inf")
    return arr


def diffraction_radius(f_number: float, wavelength: float = 0.55) -> float:
    """Radius of the first dark Airy ring, r = 1.22 · λ · f/D (the diffraction limit of a lens).

    Two points are resolved when their Airy discs are at least r apart (Rayleigh's criterion).

    Parameters
    ----------
    f_number : float
        k = f/D, focal length over the diameter of the entrance pupil; positive.
    wavelength : float
        λ, µm (default 0.55 µm, the mean wavelength of visible light used by the text).

    Returns
    -------
    float
        r in the unit of ``wavelength`` (µm).

    Raises
    ------
    InputError
        Non-positive or non-finite values.

    References
    ----------
    Hanzl, Fotogrammetrie, Modul 01, §6.3.1 (seed 002 lines 1131–1133): for k = 4, r = 2.7 µm.

    Examples
    --------
    >>> from photolib.planning import diffraction_radius
    >>> round(diffraction_radius(4.0), 3)
    2.684
    """
    return 1.22 * _num(wavelength, "wavelength", True) * _num(f_number, "f_number", True)


def image_motion(speed: float, exposure_time: float, scale_number: float) -> float:
    """Theoretical image motion (smear) during the exposure, s = v · t / m_s.

    Experience says only about half of it shows in the image (the text); forward motion
    compensation (FMC, TDI) removes it.

    Parameters
    ----------
    speed : float
        Ground speed of the aircraft, m/s (≥ 0).
    exposure_time : float
        t, s; positive.
    scale_number : float
        m_s, the image-scale number (1 : m_s); positive.

    Returns
    -------
    float
        Length of the smear in the image, m (multiply by 1e6 for µm).

    Raises
    ------
    InputError
        Negative speed, non-positive time or scale number, NaN/inf.

    References
    ----------
    Hanzl, Fotogrammetrie, Modul 01, §6.3.3 (seed 002 lines 1155–1159): 180 km/h, 1/200 s, 1:10 000
    give 25 µm.

    Examples
    --------
    >>> from photolib.planning import image_motion
    >>> round(image_motion(180 / 3.6, 1 / 200, 10000) * 1e6, 6)
    25.0
    """
    v = _num(speed, "speed", True, allow_zero=True)
    return v * _num(exposure_time, "exposure_time", True) / _num(scale_number, "scale_number", True)


def awar(areas, resolutions) -> float:
    """Area-weighted average resolution, AWAR = Σ A_i R_i / Σ A_i.

    Parameters
    ----------
    areas : array_like (n,)
        Areas A_i of the parts of the image (any unit); non-negative, not all zero.
    resolutions : array_like (n,)
        Resolution R_i measured in each part (lines/mm); non-negative.

    Returns
    -------
    float
        The AWAR, in the unit of ``resolutions``.

    Raises
    ------
    InputError
        Different lengths, negative values, all areas zero, NaN/inf.

    References
    ----------
    Hanzl, Fotogrammetrie, Modul 01, §6.3.2 (seed 002 lines 1143–1147).

    Examples
    --------
    >>> from photolib.planning import awar
    >>> awar([1.0, 3.0], [100.0, 60.0])
    70.0
    """
    A = _positive_array(areas, "areas")
    R = _positive_array(resolutions, "resolutions")
    if A.size != R.size:
        raise InputError(f"{A.size} areas but {R.size} resolutions")
    if np.any(A < 0) or np.any(R < 0):
        raise InputError("areas and resolutions must be non-negative")
    if A.sum() <= 0:
        raise InputError("the areas sum to zero: no weights")
    return float((A * R).sum() / A.sum())


class PhotoFlightPlan(NamedTuple):
    """The flight-planning quantities of Hanzl §6.4: see :func:`photo_flight_plan`.

    Attributes
    ----------
    scale_number : float
        m_s = h / c.
    flying_height : float
        h = c · m_s above the terrain, m.
    altitude : float
        Z = Z_ter + h, m.
    base : float
        B = s · m_s · (1 − p/100), m.
    strip_spacing : float
        A = s · m_s · (1 − q/100), m.
    footprint : float
        s · m_s, the side of an image on the ground, m.
    base_height_ratio : float
        B / h.

    References
    ----------
    Hanzl, Fotogrammetrie, Modul 01, §6.4 (seed 002 lines 1163–1175).

    Examples
    --------
    >>> from photolib.planning import PhotoFlightPlan
    >>> PhotoFlightPlan(10000.0, 1530.0, 1730.0, 920.0, 1725.0, 2300.0, 0.6).base
    920.0
    """

    scale_number: float
    flying_height: float
    altitude: float
    base: float
    strip_spacing: float
    footprint: float
    base_height_ratio: float


def photo_flight_plan(c: float, scale_number: float, format_side: float = 230.0, *, forward_overlap: float = 60.0,
                      side_overlap: float = 25.0, terrain_height: float = 0.0) -> PhotoFlightPlan:
    """Flight planning of Hanzl §6.4: h = c·m_s, Z = Z_ter + h, B = s m_s (1 − p/100), A = s m_s (1 − q/100).

    The same arithmetic as :func:`plan_block` (Chibunichev §10.3) written with the image-scale
    number and overlaps in per cent, for a square film format.

    Parameters
    ----------
    c : float
        Camera constant, mm.
    scale_number : float
        m_s (image scale 1 : m_s).
    format_side : float
        s, side of the (square) image format, mm (23 × 23 cm film: 230).
    forward_overlap, side_overlap : float
        p and q in per cent, in [0, 100) (usually 60 and 25; 25–35 % without GPS navigation).
    terrain_height : float
        Z_ter, m.

    Returns
    -------
    PhotoFlightPlan

    Raises
    ------
    InputError
        Non-positive c, m_s or s; overlaps outside [0, 100); NaN/inf.

    References
    ----------
    Hanzl, Fotogrammetrie, Modul 01, §6.4 (seed 002 lines 1163–1175); Chibunichev (2022), §10.3.

    Examples
    --------
    >>> from photolib.planning import photo_flight_plan
    >>> p = photo_flight_plan(153.0, 10000, 230.0, terrain_height=200.0)
    >>> round(p.flying_height, 6), round(p.altitude, 6), round(p.base, 6), round(p.strip_spacing, 6)
    (1530.0, 1730.0, 920.0, 1725.0)
    """
    cc = _num(c, "c", True)
    ms = _num(scale_number, "scale_number", True)
    s = _num(format_side, "format_side", True)
    p = _num(forward_overlap, "forward_overlap")
    q = _num(side_overlap, "side_overlap")
    for v, name in ((p, "forward_overlap"), (q, "side_overlap")):
        if not 0.0 <= v < 100.0:
            raise InputError(f"{name} must be a percentage in [0, 100) (e.g. 60), got {v!r}")
    z = _num(terrain_height, "terrain_height")
    h = cc * ms / 1000.0
    foot = s * ms / 1000.0
    B = foot * (1.0 - p / 100.0)
    return PhotoFlightPlan(ms, h, z + h, B, foot * (1.0 - q / 100.0), foot, B / h)


def photo_scale_from_map(map_scale_number, constant: float = 200.0):
    """Empirical image-scale number for a map scale, m_s = c·√m_k (Hanzl's Table 6.1 rule).

    Here c = 200 is an empirical constant, *not* the camera constant.

    Parameters
    ----------
    map_scale_number : float or array_like
        m_k, the map-scale number (map 1 : m_k); positive.
    constant : float
        The empirical constant (200 in the text).

    Returns
    -------
    float or ndarray
        m_s, unrounded (the table prints it to two significant digits).

    Raises
    ------
    InputError
        Non-positive or non-finite values.

    References
    ----------
    Hanzl, Fotogrammetrie, Modul 01, §6.4, Tab. 6.1 (seed 002 lines 1183–1193).

    Examples
    --------
    >>> from photolib.planning import photo_scale_from_map
    >>> round(photo_scale_from_map(10000), 6)
    20000.0
    """
    k = _num(constant, "constant", True)
    mk = _positive_array(map_scale_number, "map_scale_number")
    if np.any(mk <= 0):
        raise InputError(f"map_scale_number must be positive, got {map_scale_number!r}")
    out = k * np.sqrt(mk)
    return float(out[0]) if np.ndim(map_scale_number) == 0 else out


class TargetSizes(NamedTuple):
    """Sizes of signalised control points (Hanzl §6.5): see :func:`target_sizes`.

    Attributes
    ----------
    arm_length, arm_width, square_side : float
        Cross arm length m_s/80 cm, arm width m_s/500 cm, side of a square target m_s/300 cm,
        given here in metres.

    References
    ----------
    Hanzl, Fotogrammetrie, Modul 01, §6.5 (seed 002 line 1209).

    Examples
    --------
    >>> from photolib.planning import TargetSizes
    >>> TargetSizes(1.25, 0.2, 0.33).arm_width
    0.2
    """

    arm_length: float
    arm_width: float
    square_side: float


def target_sizes(scale_number: float) -> TargetSizes:
    """Signal sizes from the image-scale number: arm m_s/80, width m_s/500, square m_s/300 (in cm).

    Compare :func:`gcp_marker`, the GSD-based rules of Chibunichev §10.3.

    Parameters
    ----------
    scale_number : float
        m_s; positive.

    Returns
    -------
    TargetSizes
        In metres.

    Raises
    ------
    InputError
        Non-positive or non-finite m_s.

    References
    ----------
    Hanzl, Fotogrammetrie, Modul 01, §6.5 (seed 002 line 1209); Chibunichev (2022), §10.3.

    Examples
    --------
    >>> from photolib.planning import target_sizes
    >>> t = target_sizes(10000)
    >>> round(t.arm_length, 6), round(t.arm_width, 6), round(t.square_side, 4)
    (1.25, 0.2, 0.3333)
    """
    ms = _num(scale_number, "scale_number", True)
    return TargetSizes(ms / 80.0 / 100.0, ms / 500.0 / 100.0, ms / 300.0 / 100.0)


class GoniometerCalibration(NamedTuple):
    """Camera constant and radial distortion from goniometer angles: see :func:`goniometer_distortion`.

    Attributes
    ----------
    dc : float
        Correction of the camera constant, in the unit of ``r``.
    c : float
        The adjusted camera constant c + dc.
    dr : ndarray
        Radial distortion with the adjusted constant, dr = r − (c + dc)·tan τ.
    dr0 : ndarray
        Radial distortion with the nominal constant, dr = r − c·tan τ.
    criterion : str
        ``"lsq"`` or ``"minmax"``.

    References
    ----------
    Hanzl, Fotogrammetrie, Modul 01, §6.1 (seed 002 lines 1062–1068).

    Examples
    --------
    >>> from photolib.planning import GoniometerCalibration
    >>> GoniometerCalibration(0.01, 153.01, np.zeros(2), np.zeros(2), "lsq").c
    153.01
    """

    dc: float
    c: float
    dr: np.ndarray
    dr0: np.ndarray
    criterion: str


def goniometer_distortion(r, tau, c: float, criterion: str = "lsq") -> GoniometerCalibration:
    """Radial distortion dr = r − c·tan τ from a goniometer, with the camera constant adjusted by dc.

    The goniometer measures, for graduation marks at radii r from the principal point of
    autocollimation, the angles τ of the rays. With the nominal constant c the distortion is
    dr = r − c tan τ; the constant is then changed to c + dc so that the distortion curve
    dr = r − (c + dc) tan τ is balanced:

    * ``"minmax"`` — |dr_min| = |dr_max|, i.e. dc minimises max |dr| (the exact minimax solution,
      found among the breakpoints of the piecewise-linear objective);
    * ``"lsq"`` — Σ dr² = min, dc = Σ (r − c tan τ) tan τ / Σ tan² τ (the engine
      :func:`photolib.lsq.solve_normal_equations` with one unknown).

    Parameters
    ----------
    r : array_like (n,)
        Radii of the marks, mm (≥ 0).
    tau : array_like (n,)
        Their field angles τ, radians, in [0, π/2).
    c : float
        Nominal camera constant, mm.
    criterion : {"lsq", "minmax"}
        How dc is chosen.

    Returns
    -------
    GoniometerCalibration

    Raises
    ------
    InputError
        Different lengths, NaN/inf, angles outside [0, π/2), negative radii, unknown criterion.
    DegenerateGeometryError
        All angles zero (dc undetermined).

    References
    ----------
    Hanzl, Fotogrammetrie, Modul 01, §6.1, Fig. 6.2–6.3 (seed 002 lines 1062–1068).

    Examples
    --------
    >>> from photolib.planning import goniometer_distortion
    >>> tau = np.radians([0.0, 10.0, 20.0, 30.0])
    >>> r = 152.0 * np.tan(tau)                   # a distortion-free lens with c = 152 mm
    >>> round(goniometer_distortion(r, tau, 150.0).dc, 9)
    2.0
    """

    rr = _positive_array(r, "r")
    t = _positive_array(tau, "tau")
    if rr.size != t.size:
        raise InputError(f"{rr.size} radii but {t.size} angles")
    if np.any(rr < 0):
        raise InputError("radii r must be non-negative")
    if np.any(t < 0) or np.any(t >= math.pi / 2):
        raise InputError("angles tau must lie in [0, π/2) radians")
    cc = _num(c, "c", True)
    if criterion not in ("lsq", "minmax"):
        raise InputError(f"criterion must be 'lsq' or 'minmax', got {criterion!r}")
    tn = np.tan(t)
    if np.all(tn <= 0):
        raise DegenerateGeometryError("all angles are zero: the camera constant is undetermined")
    dr0 = rr - cc * tn
    if criterion == "lsq":
        delta, _ = solve_normal_equations(tn[:, None], -dr0, names=("dc",))   # tanτ·dc − dr0 = v
        dc = float(delta[0])
    else:
        # max_i |dr0_i − dc·t_i| is convex and piecewise linear in dc: its minimum is at a breakpoint,
        # an intersection of two of the lines ±(dr0_i − dc·t_i).
        e, s = dr0, tn
        cand = [e[s > 0] / s[s > 0]]
        i, j = np.triu_indices(e.size, 1)
        den = s[i] + s[j]
        cand.append((e[i] + e[j])[den > 0] / den[den > 0])
        dif = s[i] - s[j]
        ok = np.abs(dif) > 1e-15
        cand.append((e[i] - e[j])[ok] / dif[ok])
        cand = np.concatenate(cand)
        obj = np.abs(e[None, :] - cand[:, None] * s[None, :]).max(axis=1)
        dc = float(cand[np.argmin(obj)])
    return GoniometerCalibration(dc, cc + dc, rr - (cc + dc) * tn, dr0, criterion)

