"""Mock-up ("макетные") calibration experiments on a planar target — the Sementsov appendix (Appendix E).

A.V. Sementsov, «Усовершенствование методики калибровки неметрических цифровых съемочных камер с
использованием дополнительных геометрических условий», PhD dissertation, SGUGiT, Novosibirsk 2019
(seed ``004_ae61db45a4af28ce.txt``; line numbers refer to it). The dissertation tests its
calibration methods on simulated images, §2.4 (lines 916–935), §3.1 (lines 1000–1043, Table 1,
Appendix A) and §3.2 (lines 1045–1201, Tables 2–6). This module is that laboratory:

* the §2.4 recipe — camera, target, stations, projection by the collinearity equations (6), frame
  filter, random errors: :class:`MockupCamera`, :class:`MockupStation`, :func:`planar_grid`,
  :func:`project_points`, :func:`tripod_centres` (eq. (20)), :func:`simulate_mockup`;
* the calibration network adjusted by the one engine (:func:`photolib.lsq.gauss_newton`) with
  Jacobians from :mod:`photolib.derivations.mockup`: :func:`calibrate_network` — f, x₀, y₀ per
  camera, α, ω, κ per image, projection centres shared by images, the target either known
  (control, §3.1) or unknown points on a known plane (§3.2, 7-parameter gauge), GNSS-measured centre
  components held *fixed* or *weighted*, and the tripod-head model (20) S_i = S₀ + A_i·l;
* the statistics of Appendix A: :func:`error_statistics` (mean, max, min, SKO with ddof = 1,
  m ∓ σ, Pearson correlations);
* the variants of Table 1 (lines 1006–1018) as data, :data:`TABLE1_VARIANTS`, one mock-up of a
  variant (:func:`variant_mockup`), its Monte Carlo (:func:`simulate_variant`) and the expected
  spread of its errors by first-order propagation (:func:`variant_precision`);
* the §3.2 tripod mock-up (Table 2 images about a tripod head, a 25 cm grid 2 m away):
  :data:`TABLE2_ANGLES`, :func:`tripod_mockup`.

Conventions. A = R_Y(α)·R_X(ω)·R_Z(κ) maps camera to object axes (the matrix of eq. (8); it is
:func:`photolib.gnss_centres.rotation_aok`). Image coordinates x, y, and f, x₀, y₀ are in pixels, x
along the long side of the frame, measured from the frame centre (x₀ = y₀ = 10 px in the book's
mock-ups are offsets from the centre); object coordinates in metres; angles in radians (the variant
tables in degrees, as printed). A horizontal image (α = ω = κ = 0) looks along −Z.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from . import _checks
from .derivations.mockup import mockup_collinearity_model, mockup_tripod_model
from .errors import ConvergenceError, DegenerateGeometryError, InputError
from .gnss_centres import rotation_aok
from .lsq import Adjustment, AdjustmentView, blas_on_one_thread, gauss_newton

__all__ = ["MockupCamera", "MockupStation", "MockupImage", "MockupObservations", "GnssCentre",
           "NetworkCalibration", "ErrorStatistics", "MockupVariant", "VariantRuns", "NEX5", "TABLE1_VARIANTS",
           "TABLE2_ANGLES", "planar_grid", "project_points", "tripod_centres", "simulate_mockup",
           "simulate_gnss", "calibrate_network", "error_statistics", "variant_mockup", "simulate_variant", "variant_precision",
           "tripod_mockup"]

_REF = "Sementsov (2019)"
_COMPONENTS = "XYZ"


# =================================================================================================
# cameras, stations, observations
# =================================================================================================
@dataclass(frozen=True)
class MockupCamera:
    """A simulated frame camera in pixels: focal length, principal point and frame size.

    Parameters
    ----------
    f : float
        Focal length (px), > 0.
    x0, y0 : float
        Principal point (px) from the frame centre.
    width, height : float
        Frame size (px); x runs along ``width``.

    Raises
    ------
    InputError
        A non-number, NaN/inf, f ≤ 0 or a frame side ≤ 0.

    References
    ----------
    Sementsov (2019), §3.2, lines 1049–1050 (Sony NEX-5: 4592 × 3056 px, f = 3100 px,
    x₀ = y₀ = 10 px); §2.4, line 922 (the camera parameters come first).

    Examples
    --------
    >>> MockupCamera(3100.0, 10.0, 10.0).io
    array([3100.,   10.,   10.])
    """

    f: float
    x0: float = 0.0
    y0: float = 0.0
    width: float = 4592.0
    height: float = 3056.0

    def __post_init__(self):
        for name in ("f", "x0", "y0", "width", "height"):
            positive = name in ("f", "width", "height")
            object.__setattr__(self, name, _checks.number(getattr(self, name), f"camera {name}", positive))

    @property
    def io(self) -> np.ndarray:
        """(f, x₀, y₀) in pixels."""
        return np.array([self.f, self.x0, self.y0])


NEX5 = MockupCamera(3100.0, 10.0, 10.0, 4592.0, 3056.0)
"""The simulated Sony NEX-5 with the E 16 mm lens of §3.2 (lines 1049–1050); §3.1 names the same camera
(line 1004) but prints no f in pixels: the mock-ups of §3.1 use these values too (an assumption)."""


@dataclass(frozen=True)
class MockupStation:
    """One image of a mock-up: its angles, its camera and the projection centre it belongs to.

    Parameters
    ----------
    angles : 3 floats
        α, ω, κ in radians (A = R_Y(α)·R_X(ω)·R_Z(κ)).
    camera : int
        Index of the camera that takes the image.
    centre : int
        Index of its projection centre; images with the same index share one centre (with the
        tripod model: one rotation point S₀ of the tripod head).

    Raises
    ------
    InputError
        Angles that are not three finite numbers, a negative or non-integer index.

    References
    ----------
    Sementsov (2019), §2.4, line 924 (centres and tilt angles per image); Table 1, lines 1006–1018.

    Examples
    --------
    >>> s = MockupStation(np.radians([30.0, 0.0, 0.0]))
    >>> round(float(np.degrees(s.angles[0])), 6), s.camera, s.centre
    (30.0, 0, 0)
    """

    angles: np.ndarray
    camera: int = 0
    centre: int = 0

    def __post_init__(self):
        object.__setattr__(self, "angles", _vector(self.angles, 3, "station angles"))
        object.__setattr__(self, "camera", _checks.integer(self.camera, "station camera", 0))
        object.__setattr__(self, "centre", _checks.integer(self.centre, "station centre", 0))


@dataclass(frozen=True)
class MockupImage:
    """The measured points of one mock-up image.

    Attributes
    ----------
    camera, centre : int
        Indices of the camera and of the projection centre (as the station).
    point_ids : (k,) int ndarray
        Indices of the target points seen (rows of :attr:`MockupObservations.points`).
    xy : (k, 2) ndarray
        Their measured image coordinates (px, with the simulated errors).

    References
    ----------
    Sementsov (2019), §2.4, lines 925–926 (points outside the frame are filtered out, random
    errors are added).

    Examples
    --------
    >>> im = MockupImage(0, 0, np.array([0, 1]), np.zeros((2, 2)))
    >>> im.xy.shape
    (2, 2)
    """

    camera: int
    centre: int
    point_ids: np.ndarray
    xy: np.ndarray

    def __post_init__(self):
        object.__setattr__(self, "camera", _checks.integer(self.camera, "image camera", 0))
        object.__setattr__(self, "centre", _checks.integer(self.centre, "image centre", 0))
        ids = np.asarray(self.point_ids)
        if ids.ndim != 1 or (ids.size and ids.dtype.kind not in "iu"):
            raise InputError(f"point_ids must be a 1-D array of integers, got {ids.dtype} of shape {ids.shape}")
        if ids.size and (ids.min() < 0 or len(np.unique(ids)) != ids.size):
            raise InputError("point_ids must be distinct non-negative indices")
        xy = np.asarray(self.xy, dtype=float) if not isinstance(self.xy, (str, bytes)) else None
        if xy is None or xy.shape != (ids.size, 2):
            raise InputError(f"xy must have shape ({ids.size}, 2) (one row per point id), "
                             f"got {None if xy is None else xy.shape}")
        if not np.all(np.isfinite(xy)):
            raise InputError("image coordinates xy contain NaN or inf")
        object.__setattr__(self, "point_ids", ids.astype(int))
        object.__setattr__(self, "xy", xy)


@dataclass(frozen=True)
class MockupObservations:
    """A simulated calibration experiment: the truth and the measurements.

    Attributes
    ----------
    points : (n, 3) ndarray
        The target points (m).
    cameras : tuple of MockupCamera
        The true cameras.
    centres : (s, 3) ndarray
        The true projection centres (with ``l``: the tripod rotation points S₀).
    stations : tuple of MockupStation
        The true angles, camera and centre of every image.
    images : tuple of MockupImage
        The measured image points.
    sigma : float
        Standard deviation of the simulated image errors (px).
    l : (3,) ndarray or None
        The tripod offset of eq. (20) (m, camera frame); None for cameras turned about their
        projection centre.

    References
    ----------
    Sementsov (2019), §2.4, lines 920–935.

    Examples
    --------
    >>> obs = simulate_mockup(planar_grid(1000, 50), [NEX5], [[0, 0, 300.0]], [MockupStation([0, 0, 0])], seed=1)
    >>> len(obs.images), obs.images[0].xy.shape[0] > 20
    (1, True)
    """

    points: np.ndarray
    cameras: tuple
    centres: np.ndarray
    stations: tuple
    images: tuple
    sigma: float
    l: np.ndarray | None = None

    def __post_init__(self):
        object.__setattr__(self, "points", _array(self.points, (3,), "points"))
        object.__setattr__(self, "cameras", tuple(_cameras(self.cameras)))
        object.__setattr__(self, "centres", _array(self.centres, (3,), "centres"))
        st = _stations(self.stations, len(self.cameras), len(self.centres))
        object.__setattr__(self, "stations", tuple(st))
        images = tuple(self.images) if isinstance(self.images, (list, tuple)) else None
        if images is None or not all(isinstance(im, MockupImage) for im in images):
            raise InputError("images must be a sequence of MockupImage")
        if len(images) != len(st):
            raise InputError(f"{len(images)} images but {len(st)} stations")
        for i, (im, s) in enumerate(zip(images, st)):
            if (im.camera, im.centre) != (s.camera, s.centre):
                raise InputError(f"image {i}: camera/centre ({im.camera}, {im.centre}) differ from its station's "
                                 f"({s.camera}, {s.centre})")
            if im.point_ids.size and im.point_ids.max() >= len(self.points):
                raise InputError(f"image {i} refers to point {im.point_ids.max()}, but there are {len(self.points)}")
        object.__setattr__(self, "images", images)
        object.__setattr__(self, "sigma", _checks.number(self.sigma, "sigma", True, allow_zero=True))
        if self.l is not None:
            object.__setattr__(self, "l", _vector(self.l, 3, "l"))

    @property
    def image_centres(self) -> np.ndarray:
        """The true projection centre of every image (eq. (20) when ``l`` is set)."""
        return _image_centres(self.centres, self.stations, self.l)


@dataclass(frozen=True)
class GnssCentre:
    """GNSS-measured components of one projection centre.

    Parameters
    ----------
    centre : int
        Index of the projection centre.
    measured : 3 floats
        The measured X, Y, Z (m); only the ``known`` components are used.
    sigma : 3 floats
        Their standard deviations (m), > 0.
    known : str
        Which components were measured, a non-empty subset of ``"XYZ"`` (e.g. ``"XY"``).

    Raises
    ------
    InputError
        Unknown components, NaN/inf, a non-positive σ of a known component, a negative index.

    References
    ----------
    Sementsov (2019), §3.1, Table 1 (lines 1006–1018) and line 1024 (σ 0.1 m in plan, 0.3 m in
    height).

    Examples
    --------
    >>> GnssCentre(0, [0.05, -0.1, 300.2], [0.1, 0.1, 0.3], "XY").mask.tolist()
    [True, True, False]
    """

    centre: int
    measured: np.ndarray
    sigma: np.ndarray
    known: str = "XYZ"

    def __post_init__(self):
        object.__setattr__(self, "centre", _checks.integer(self.centre, "GNSS centre", 0))
        object.__setattr__(self, "measured", _vector(self.measured, 3, "GNSS measured centre"))
        object.__setattr__(self, "sigma", _vector(self.sigma, 3, "GNSS sigma"))
        object.__setattr__(self, "known", _known(self.known))
        if np.any(self.sigma[self.mask] <= 0):
            raise InputError(f"GNSS sigma of the known components must be positive, got {self.sigma.tolist()}")

    @property
    def mask(self) -> np.ndarray:
        """Boolean (3,): which of X, Y, Z are known."""
        return np.array([c in self.known for c in _COMPONENTS])


def _known(value) -> str:
    if not isinstance(value, str) or not value or any(c not in _COMPONENTS for c in value) \
            or len(set(value)) != len(value):
        raise InputError(f"known GNSS components must be a non-empty subset of 'XYZ', got {value!r}")
    return "".join(c for c in _COMPONENTS if c in value)


def _vector(value, n, what) -> np.ndarray:
    if isinstance(value, (str, bytes)):
        raise InputError(f"{what} must be {n} numbers, got {value!r}")
    try:
        v = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise InputError(f"{what} must be {n} numbers, got {value!r}") from None
    if v.shape != (n,):
        raise InputError(f"{what} must be {n} numbers, got shape {v.shape}")
    if not np.all(np.isfinite(v)):
        raise InputError(f"{what} contain NaN or inf")
    return v


def _array(value, shape_tail, what) -> np.ndarray:
    if isinstance(value, (str, bytes)):
        raise InputError(f"{what} must be numbers, got {value!r}")
    try:
        a = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise InputError(f"{what} must be numbers, got {type(value).__name__}") from None
    if a.ndim != 1 + len(shape_tail) or a.shape[1:] != tuple(shape_tail):
        want = "(n, " + ", ".join(map(str, shape_tail)) + ")"
        raise InputError(f"{what} must have shape {want}, got {a.shape}")
    if not np.all(np.isfinite(a)):
        raise InputError(f"{what} contain NaN or inf")
    return a


# =================================================================================================
# the §2.4 recipe
# =================================================================================================
def planar_grid(half_size, step, z=0.0, half_height=None) -> np.ndarray:
    """Points of a planar target: a square lattice of ``step`` over ±``half_size`` at height ``z``.

    Parameters
    ----------
    half_size : float
        Half of the side of the target along X (m), > 0.
    step : float
        Spacing of the points (m), > 0.
    z : float, optional
        Height of the target plane (m).
    half_height : float, optional
        Half of the side along Y (default ``half_size``).

    Returns
    -------
    (n, 3) ndarray
        X, Y, Z of the points, X fastest; the lattice contains the origin.

    Raises
    ------
    InputError
        Non-positive or non-finite sizes, or more than 10⁶ points.

    References
    ----------
    Sementsov (2019), §3.1, line 1004 (a plane 2 × 2 km with points every 50 m); §3.2, line 1049
    (points every 25 cm).

    Examples
    --------
    >>> planar_grid(1000, 50).shape            # 41 × 41 points of §3.1
    (1681, 3)
    >>> planar_grid(0.5, 0.25, z=-2.0)[:2].tolist()
    [[-0.5, -0.5, -2.0], [-0.25, -0.5, -2.0]]
    """
    half = _checks.number(half_size, "half_size", True)
    step = _checks.number(step, "step", True)
    z = _checks.number(z, "z")
    half_y = half if half_height is None else _checks.number(half_height, "half_height", True)
    nx, ny = int(np.floor(half / step + 1e-9)), int(np.floor(half_y / step + 1e-9))
    if (2 * nx + 1) * (2 * ny + 1) > 1_000_000:
        raise InputError(f"the grid would have {(2 * nx + 1) * (2 * ny + 1)} points (more than 10⁶)")
    gx, gy = np.meshgrid(np.arange(-nx, nx + 1) * step, np.arange(-ny, ny + 1) * step)
    return np.column_stack([gx.ravel(), gy.ravel(), np.full(gx.size, z)])


def project_points(points, centre, angles, camera) -> tuple:
    """Image coordinates of object points by the collinearity equations (6), with their depth.

    x = x₀ − f·X*/Z*, y = y₀ − f·Y*/Z*, (X*, Y*, Z*)ᵀ = Aᵀ(P − S), A = R_Y(α)·R_X(ω)·R_Z(κ).
    A point is in front of the camera when Z* < 0.

    Parameters
    ----------
    points : (n, 3) array
        Object points (m).
    centre : 3 floats
        Projection centre S (m).
    angles : 3 floats
        α, ω, κ (rad).
    camera : MockupCamera or 3 floats
        The camera, or (f, x₀, y₀) in pixels.

    Returns
    -------
    xy : (n, 2) ndarray
        Image coordinates (px); NaN for a point in the plane Z* = 0 through the centre.
    depth : (n,) ndarray
        Z* (m); negative in front of the camera.

    Raises
    ------
    InputError
        Bad shapes, NaN/inf, f ≤ 0.

    References
    ----------
    Sementsov (2019), §2.2, eq. (6), seed lines 577–579; eq. (8), lines 593–595.

    Examples
    --------
    >>> xy, depth = project_points([[30.0, 0.0, 0.0]], [0, 0, 300.0], [0, 0, 0], NEX5)
    >>> xy.round(6).tolist(), depth.tolist()
    ([[320.0, 10.0]], [-300.0])
    """
    P = _array(points, (3,), "points")
    S = _vector(centre, 3, "centre")
    a = _vector(angles, 3, "angles")
    io = _io(camera)
    d = (P - S) @ rotation_aok(*a)
    with np.errstate(divide="ignore", invalid="ignore"):
        xy = np.column_stack([io[1] - io[0] * d[:, 0] / d[:, 2], io[2] - io[0] * d[:, 1] / d[:, 2]])
    xy[d[:, 2] == 0] = np.nan
    return xy, d[:, 2].copy()


def _io(camera) -> np.ndarray:
    if isinstance(camera, MockupCamera):
        return camera.io
    io = _vector(camera, 3, "camera (f, x0, y0)")
    if io[0] <= 0:
        raise InputError(f"focal length must be positive, got f = {io[0]}")
    return io


def tripod_centres(S0, angles, l) -> np.ndarray:
    """Projection centres of images turned about a tripod head: S_i = S₀ + A_i·l, eq. (20).

    Parameters
    ----------
    S0 : 3 floats
        The rotation point of the tripod head (m).
    angles : (k, 3) array
        α, ω, κ of every image (rad).
    l : 3 floats
        Offset of the projection centre from S₀ in the camera frame (m).

    Returns
    -------
    (k, 3) ndarray
        The centres; they lie on the sphere of radius |l| about S₀ (Fig. 36).

    Raises
    ------
    InputError
        Bad shapes or NaN/inf.

    References
    ----------
    Sementsov (2019), §2.3, eq. (20), seed lines 883–895.

    Examples
    --------
    >>> S = tripod_centres([0, 0, 0], np.radians([[0, 0, 0], [30, 0, 0]]), [0.0, 0.0, 0.1])
    >>> S.round(6).tolist()
    [[0.0, 0.0, 0.1], [-0.05, 0.0, 0.086603]]
    """
    S0 = _vector(S0, 3, "S0")
    a = _array(angles, (3,), "angles")
    lv = _vector(l, 3, "l")
    return S0 + np.einsum("kij,j->ki", rotation_aok(a[:, 0], a[:, 1], a[:, 2]), lv)


def _image_centres(centres, stations, l):
    S = np.array([centres[s.centre] for s in stations], dtype=float)
    if l is None:
        return S
    angles = np.array([s.angles for s in stations])
    return S + np.einsum("kij,j->ki", rotation_aok(angles[:, 0], angles[:, 1], angles[:, 2]), l)


def _rng(seed):
    if isinstance(seed, np.random.Generator):
        return seed
    if seed is None or (isinstance(seed, (int, np.integer)) and not isinstance(seed, bool) and seed >= 0):
        return np.random.default_rng(seed)
    raise InputError(f"seed must be a non-negative integer, a numpy Generator or None, got {seed!r}")


def simulate_mockup(points, cameras, centres, stations, *, sigma=0.5, seed=None, l=None) -> MockupObservations:
    """Simulate the images of a planar target by the recipe of §2.4.

    For every station: project the target by (6) with the true camera, centre and angles; drop
    points behind the camera and points outside the frame (|x|, |y| up to half the frame, from the
    frame centre); add independent normal errors of ``sigma`` px to x and y.

    Parameters
    ----------
    points : (n, 3) array
        The target points (m).
    cameras : sequence of MockupCamera
        The true cameras.
    centres : (s, 3) array
        The true projection centres (m); with ``l`` the tripod rotation points S₀.
    stations : sequence of MockupStation
        One per image.
    sigma : float, optional
        Standard deviation of the image errors (px), ≥ 0 (default 0.5, lines 1021, 1077).
    seed : int, numpy.random.Generator or None, optional
        The random generator (or its seed).
    l : 3 floats, optional
        Tripod offset: the image centres become S_i = centres[c] + A_i·l (eq. (20)).

    Returns
    -------
    MockupObservations
        Truth and measurements.

    Raises
    ------
    InputError
        Bad shapes, NaN/inf, an index outside ``cameras``/``centres``, a negative sigma, an image
        that sees fewer than 3 target points.

    References
    ----------
    Sementsov (2019), §2.4, lines 920–935; §3.1, lines 1004, 1021; §3.2, lines 1049–1077.

    Examples
    --------
    >>> obs = simulate_mockup(planar_grid(1000, 50), [NEX5], [[0, 0, 300.0]],
    ...                       [MockupStation(np.radians([30.0, 0, 0]))], sigma=0.5, seed=0)
    >>> obs.images[0].xy.shape                 # points of the 2 × 2 km plane inside a 30° image
    (117, 2)
    """
    P = _array(points, (3,), "points")
    cams = _cameras(cameras)
    C = _array(centres, (3,), "centres")
    st = _stations(stations, len(cams), len(C))
    sigma = _checks.number(sigma, "sigma", True, allow_zero=True)
    lv = None if l is None else _vector(l, 3, "l")
    rng = _rng(seed)
    S_img = _image_centres(C, st, lv)
    images = []
    for i, (s, S) in enumerate(zip(st, S_img)):
        cam = cams[s.camera]
        xy, depth = project_points(P, S, s.angles, cam)
        ok = (depth < 0) & (np.abs(xy[:, 0]) <= cam.width / 2) & (np.abs(xy[:, 1]) <= cam.height / 2)
        ids = np.flatnonzero(ok)
        if ids.size < 3:
            raise InputError(f"image {i} sees {ids.size} target points inside its frame (at least 3 needed)")
        meas = xy[ids] + sigma * rng.standard_normal((ids.size, 2))
        images.append(MockupImage(s.camera, s.centre, ids, meas))
    return MockupObservations(P, tuple(cams), C, tuple(st), tuple(images), sigma, lv)


def _cameras(cameras):
    if isinstance(cameras, MockupCamera):
        cameras = [cameras]
    try:
        cams = list(cameras)
    except TypeError:
        raise InputError(f"cameras must be a sequence of MockupCamera, got {type(cameras).__name__}") from None
    if not cams or not all(isinstance(c, MockupCamera) for c in cams):
        raise InputError("cameras must be a non-empty sequence of MockupCamera")
    return cams


def _stations(stations, n_cameras, n_centres):
    if isinstance(stations, MockupStation):
        stations = [stations]
    try:
        st = list(stations)
    except TypeError:
        raise InputError(f"stations must be a sequence of MockupStation, got {type(stations).__name__}") from None
    if not st or not all(isinstance(s, MockupStation) for s in st):
        raise InputError("stations must be a non-empty sequence of MockupStation")
    for i, s in enumerate(st):
        if s.camera >= n_cameras:
            raise InputError(f"image {i} uses camera {s.camera}, but there are {n_cameras} cameras")
        if s.centre >= n_centres:
            raise InputError(f"image {i} uses centre {s.centre}, but there are {n_centres} centres")
    return st


def simulate_gnss(observations: MockupObservations, known="XYZ", sigma=(0.1, 0.1, 0.3), *, centre=0,
                  seed=None) -> GnssCentre:
    """A GNSS measurement of one true projection centre: the truth plus normal errors.

    Parameters
    ----------
    observations : MockupObservations
        The mock-up (its true centre ``centre`` is measured).
    known : str, optional
        The measured components, a subset of ``"XYZ"``.
    sigma : 3 floats, optional
        σ of X, Y, Z (m); default 0.1, 0.1, 0.3 m (line 1024).
    centre : int, optional
        Index of the centre.
    seed : int, numpy.random.Generator or None, optional
        The random generator (or its seed).

    Returns
    -------
    GnssCentre
        All three components are drawn (the unknown ones are ignored by the adjustment).

    Raises
    ------
    InputError
        Not a mock-up, a centre outside it, bad components or σ.

    References
    ----------
    Sementsov (2019), §3.1, Table 1 (lines 1006–1018) and line 1024.

    Examples
    --------
    >>> obs = variant_mockup("2-1", seed=0)
    >>> g = simulate_gnss(obs, "Z", seed=1)
    >>> g.known, bool(abs(g.measured[2] - 300.0) < 2.0)
    ('Z', True)
    """
    if not isinstance(observations, MockupObservations):
        raise InputError(f"observations must be MockupObservations, got {type(observations).__name__}")
    c = _checks.integer(centre, "centre", 0)
    if c >= len(observations.centres):
        raise InputError(f"centre {c} is not in the mock-up ({len(observations.centres)} centres)")
    sig = _vector(sigma, 3, "GNSS sigma")
    if np.any(sig < 0):
        raise InputError(f"GNSS sigma must not be negative, got {sig.tolist()}")
    rng = _rng(seed)
    measured = observations.centres[c] + sig * rng.standard_normal(3)
    return GnssCentre(c, measured, sig, known)


# =================================================================================================
# the network adjustment
# =================================================================================================
@dataclass(repr=False)
class NetworkCalibration(AdjustmentView):
    """The adjusted calibration network: interior and exterior orientation with their σ.

    Attributes
    ----------
    cameras, cameras_std : (c, 3) ndarray
        f, x₀, y₀ of every camera (px) and their a-posteriori σ (1.8.8).
    centres, centres_std : (s, 3) ndarray
        The projection centres (with the tripod model: the rotation points S₀), m; σ = 0 for
        components held fixed (GNSS "fixed", the gauge).
    angles, angles_std : (k, 3) ndarray
        α, ω, κ of every image (rad).
    image_centres : (k, 3) ndarray
        The projection centre of every image (eq. (20) with the tripod model).
    l, l_std : (3,) ndarray or None
        The tripod offset (m) and its σ; None without the tripod model.
    points, points_std : (n, 3) ndarray
        The target points (adjusted on the plane when ``targets == "plane"``; σ = 0 for fixed ones).
    point_used : (n,) bool ndarray
        Points that entered the adjustment.
    targets, gnss_mode : str
        The options used.
    adjustment : Adjustment
        The engine's result (μ in pixels, Q, names, history).

    References
    ----------
    Sementsov (2019), §3.1–§3.2 (Appendix A: μ and the errors of f, x₀, y₀); Chibunichev (2022),
    §1.8, eqs. (1.8.8)–(1.8.10).

    Examples
    --------
    >>> obs = variant_mockup("2-1", seed=3)
    >>> res = calibrate_network(obs)
    >>> res.cameras.shape, res.mu < 0.6
    ((1, 3), True)
    """

    cameras: np.ndarray
    cameras_std: np.ndarray
    centres: np.ndarray
    centres_std: np.ndarray
    angles: np.ndarray
    angles_std: np.ndarray
    image_centres: np.ndarray
    l: np.ndarray | None
    l_std: np.ndarray | None
    points: np.ndarray
    points_std: np.ndarray
    point_used: np.ndarray
    targets: str
    gnss_mode: str
    adjustment: Adjustment = field(repr=False)

    def io_errors(self, observations: MockupObservations) -> np.ndarray:
        """Estimated minus true (f, x₀, y₀) of every camera, (c, 3) px (the σ_f, σ_x₀, σ_y₀ of Appendix A)."""
        if not isinstance(observations, MockupObservations):
            raise InputError(f"observations must be MockupObservations, got {type(observations).__name__}")
        if len(observations.cameras) != len(self.cameras):
            raise InputError("the mock-up has a different number of cameras")
        return self.cameras - np.array([c.io for c in observations.cameras])

    def __repr__(self) -> str:
        cams = "; ".join(f"f = {c[0]:.3f} ± {s[0]:.3f}, x0 = {c[1]:.3f} ± {s[1]:.3f}, y0 = {c[2]:.3f} ± {s[2]:.3f}"
                         for c, s in zip(self.cameras, self.cameras_std))
        return (f"NetworkCalibration ({self.targets} targets, GNSS {self.gnss_mode}"
                f"{', tripod model' if self.l is not None else ''}): {self.iterations} iterations, "
                f"μ = {self.mu:.4f} px; {cams}")


TARGETS = ("control", "plane")
GNSS_MODES = ("fixed", "weighted")
DATUMS = ("first-image", "minimal")


def calibrate_network(observations: MockupObservations, *, targets="control", gnss=(), gnss_mode="fixed",
                      tripod=False, datum="first-image", cameras0=None, centres0=None, angles0=None, l0=None,
                      points0=None, sigma_image=None, max_iter=30, tol=1e-8) -> NetworkCalibration:
    """Adjust a calibration network of mock-up images: interior orientation from a planar target.

    Unknowns: f, x₀, y₀ of every camera (images may share a camera); α, ω, κ of every image; the
    projection centres (images may share one); with ``tripod=True`` the centres are written by
    eq. (20), S_i = S₀ + A_i·l, and the unknowns are S₀ per centre index and one offset l.
    Observations: the image coordinates, weight 1 (a-priori σ₀ = ``sigma_image``, so μ is in
    pixels), and with ``gnss_mode="weighted"`` the GNSS components as direct observations of the
    centre with weights σ₀²/σ².

    * ``targets="control"`` (§3.1): the target points are known (control).
    * ``targets="plane"`` (§3.2): the points are unknown on their known plane Z = const (2
      unknowns each; only points seen in at least two images are used). The plane fixes the
      Z-shift and two tilts of the similarity; the first image's centre (S₀ with the tripod
      model) is held at its approximation (X, Y shift and scale) and so is its κ (rotation about
      the plane normal): the 7-parameter gauge, ``datum="minimal"``. That gauge needs centres that
      differ: when all images share one centre, the tilt of the bundle against the plane is not
      observable (the points slide along their rays) and the normal equations are singular. The
      default ``datum="first-image"`` therefore also holds the first image's α and ω (the book
      started from the true plane orientation, line 1179); with the tripod model and true l ≠ 0
      the two extra constraints are redundant.
    * GNSS (§3.1, Table 1): ``gnss_mode="fixed"`` holds the known components at their measured
      values (constants, as the book's variants 1-1/1-2 evidently did); ``"weighted"`` adjusts
      them with their σ.

    Solved by :func:`photolib.lsq.gauss_newton`; B from :func:`photolib.derivations.mockup_collinearity_model`
    or :func:`~photolib.derivations.mockup_tripod_model`.

    Parameters
    ----------
    observations : MockupObservations
        The mock-up (its truth supplies the default approximations).
    targets : {"control", "plane"}, optional
        Known target points, or unknown points on the plane.
    gnss : sequence of GnssCentre, optional
        GNSS-measured centre components (not with ``targets="plane"`` or ``tripod=True``).
    gnss_mode : {"fixed", "weighted"}, optional
        How the GNSS components enter.
    tripod : bool, optional
        Write the centres by eq. (20) with an unknown offset l.
    datum : {"first-image", "minimal"}, optional
        The gauge of ``targets="plane"`` (see above); ignored with known targets.
    cameras0 : (c, 3) array, optional
        Approximate f, x₀, y₀ (default: the true cameras).
    centres0 : (s, 3) array, optional
        Approximate centres / S₀ (default: the true ones). Fixed GNSS components are replaced by
        the measured values.
    angles0 : (k, 3) array, optional
        Approximate angles (default: the true ones).
    l0 : 3 floats, optional
        Approximate tripod offset (default 0: the single-centre solution is the start, §2.3 stage 1).
    points0 : (n, 3) array, optional
        Approximate target points for ``targets="plane"`` (default: the true ones; their Z is the
        plane and is kept).
    sigma_image : float, optional
        A-priori σ of the image coordinates (px); default the simulated σ (1 px if that is 0).
    max_iter : int, optional
        Gauss–Newton iterations allowed.
    tol : float, optional
        Convergence threshold on the corrections (px, m and rad alike).

    Returns
    -------
    NetworkCalibration
        Estimates, a-posteriori σ, μ (px), iterations.

    Raises
    ------
    InputError
        Not a mock-up, unknown options, bad approximations, GNSS with the plane or tripod mode, a
        target that is not one plane (``targets="plane"``), an image with fewer than 3 points,
        fewer observations than unknowns.
    DegenerateGeometryError
        A singular network, e.g. a camera whose every image is horizontal over the plane while
        the centre height is free (only f/Z_S enters: the transformed bundle of §2.2).
    ConvergenceError
        No convergence in ``max_iter`` iterations.

    References
    ----------
    Sementsov (2019), §2.2 (eqs. (6)–(17)), §2.3 (eq. (20)), §2.4, §3.1 (Table 1, Appendix A),
    §3.2 (Tables 2–6); Chibunichev (2022), §1.8, eqs. (1.8.5)–(1.8.10).

    Examples
    --------
    Variant 2-1 (one camera, two images tilted ±30° from one centre, no GNSS):

    >>> obs = variant_mockup("2-1", seed=0, sigma=0.0)
    >>> res = calibrate_network(obs, cameras0=[[3000.0, 0.0, 0.0]])
    >>> res.cameras.round(6).tolist(), res.iterations < 10
    ([[3100.0, 10.0, 10.0]], True)
    """
    if not isinstance(observations, MockupObservations):
        raise InputError(f"observations must be MockupObservations, got {type(observations).__name__}")
    if targets not in TARGETS:
        raise InputError(f"targets must be 'control' or 'plane', got {targets!r}")
    if gnss_mode not in GNSS_MODES:
        raise InputError(f"gnss_mode must be 'fixed' or 'weighted', got {gnss_mode!r}")
    if not isinstance(tripod, (bool, np.bool_)):
        raise InputError(f"tripod must be True or False, got {tripod!r}")
    if datum not in DATUMS:
        raise InputError(f"datum must be 'first-image' or 'minimal', got {datum!r}")
    gnss = _gnss_list(gnss, len(observations.centres))
    if gnss and (targets == "plane" or tripod):
        raise InputError("GNSS centres combine only with known targets and without the tripod model "
                         "(the plane mode has its own 7-parameter gauge)")
    max_iter = _checks.integer(max_iter, "max_iter", 1)
    tol = _checks.number(tol, "tol", True)
    obs = observations
    n_cam, n_cen, n_img = len(obs.cameras), len(obs.centres), len(obs.images)
    cam0 = _start(cameras0, np.array([c.io for c in obs.cameras]), (n_cam, 3), "cameras0")
    if np.any(cam0[:, 0] <= 0):
        raise InputError("cameras0: focal lengths must be positive")
    cen0 = _start(centres0, obs.centres, (n_cen, 3), "centres0")
    ang0 = _start(angles0, np.array([s.angles for s in obs.stations]), (n_img, 3), "angles0")
    lv0 = np.zeros(3) if l0 is None else _vector(l0, 3, "l0")
    pts0 = _start(points0, obs.points, obs.points.shape, "points0")
    sigma0 = obs.sigma if sigma_image is None and obs.sigma > 0 else (1.0 if sigma_image is None else sigma_image)
    sigma0 = _checks.number(sigma0, "sigma_image", True)
    for i, im in enumerate(obs.images):
        if len(im.point_ids) < 3:
            raise InputError(f"image {i} has {len(im.point_ids)} points (at least 3 needed)")

    # --- which centre components are fixed ------------------------------------------------------
    fixed_centre = np.zeros((n_cen, 3), bool)
    gnss_rows = []                                     # (centre, component, measured, sigma)
    for g in gnss:
        if gnss_mode == "fixed":
            fixed_centre[g.centre, g.mask] = True
            cen0[g.centre, g.mask] = g.measured[g.mask]
        else:
            gnss_rows += [(g.centre, k, g.measured[k], g.sigma[k]) for k in np.flatnonzero(g.mask)]
    used = np.zeros(len(obs.points), bool)
    for im in obs.images:
        used[im.point_ids] = True
    if targets == "plane":
        z = pts0[used, 2]
        if np.ptp(z) > 1e-9 * max(1.0, np.abs(z).max()):
            raise InputError("targets='plane' needs the target points on one plane Z = const")
        counts = np.zeros(len(obs.points), int)
        for im in obs.images:
            counts[im.point_ids] += 1
        used = counts >= 2
        fixed_centre[obs.images[0].centre] = True     # gauge: X, Y shift and scale
    z_known = fixed_centre[:, 2].copy()
    for c, k, _, _ in gnss_rows:
        z_known[c] |= k == 2
    _check_horizontal(obs, ang0, z_known, pts0)

    # --- the unknowns -----------------------------------------------------------------------------
    names, x0 = [], []

    def add(name, value):
        names.append(name)
        x0.append(float(value))
        return len(names) - 1

    cam_col = np.array([[add(f"{p}[cam {c}]", cam0[c, k]) for k, p in enumerate(("f", "x0", "y0"))]
                        for c in range(n_cam)])
    cen_col = np.array([[-1 if fixed_centre[c, k] else add(("S0" if tripod else "S") + f"{'XYZ'[k]}[{c}]", cen0[c, k])
                         for k in range(3)] for c in range(n_cen)])
    l_col = np.array([add(f"l_{'XYZ'[k]}", lv0[k]) for k in range(3)]) if tripod else None
    fixed_angle = np.zeros((n_img, 3), bool)
    if targets == "plane":
        fixed_angle[0, 2] = True                       # gauge: rotation about the plane normal
        if datum == "first-image":
            fixed_angle[0, :2] = True                  # and the tilt of the bundle against the plane
    ang_col = np.array([[-1 if fixed_angle[i, k] else
                         add(f"{('alpha', 'omega', 'kappa')[k]}[{i}]", ang0[i, k]) for k in range(3)]
                        for i in range(n_img)])
    pt_col = -np.ones((len(obs.points), 3), int)
    if targets == "plane":
        for j in np.flatnonzero(used):
            pt_col[j, 0] = add(f"X[{j}]", pts0[j, 0])
            pt_col[j, 1] = add(f"Y[{j}]", pts0[j, 1])
    x_start = np.array(x0)
    n_unknown = len(names)

    # --- observation index arrays -----------------------------------------------------------------
    keep = [used[im.point_ids] for im in obs.images]
    img_of = np.concatenate([np.full(k.sum(), i) for i, k in enumerate(keep)])
    pid = np.concatenate([im.point_ids[k] for im, k in zip(obs.images, keep)])
    xy = np.concatenate([im.xy[k] for im, k in zip(obs.images, keep)])
    cam_of = np.array([obs.images[i].camera for i in img_of])
    cen_of = np.array([obs.images[i].centre for i in img_of])
    n_obs = len(pid)
    for i, k in enumerate(keep):
        if k.sum() < 3:
            raise InputError(f"image {i} keeps {k.sum()} points seen in at least two images (at least 3 needed)")
    m = 2 * n_obs + len(gnss_rows)
    if m < n_unknown:
        raise InputError(f"{m} observations cannot determine {n_unknown} unknowns (too few points)")

    if tripod:
        model_cols = [cam_col[cam_of, 0], cam_col[cam_of, 1], cam_col[cam_of, 2],
                      cen_col[cen_of, 0], cen_col[cen_of, 1], cen_col[cen_of, 2],
                      np.full(n_obs, l_col[0]), np.full(n_obs, l_col[1]), np.full(n_obs, l_col[2]),
                      ang_col[img_of, 0], ang_col[img_of, 1], ang_col[img_of, 2],
                      pt_col[pid, 0], pt_col[pid, 1], pt_col[pid, 2]]
        res_fn, jac_fn = mockup_tripod_model().compile()
    else:
        model_cols = [cam_col[cam_of, 0], cam_col[cam_of, 1], cam_col[cam_of, 2],
                      cen_col[cen_of, 0], cen_col[cen_of, 1], cen_col[cen_of, 2],
                      ang_col[img_of, 0], ang_col[img_of, 1], ang_col[img_of, 2],
                      pt_col[pid, 0], pt_col[pid, 1], pt_col[pid, 2]]
        res_fn, jac_fn = mockup_collinearity_model().compile()
    n_par = len(model_cols)
    base_cam, base_cen, base_ang, base_pts = cam0.copy(), cen0.copy(), ang0.copy(), pts0.copy()
    rows = np.arange(n_obs)

    def unpack(xv):
        cam, cen, ang, pts = base_cam.copy(), base_cen.copy(), base_ang.copy(), base_pts.copy()
        cam[...] = xv[cam_col]
        cen[cen_col >= 0] = xv[cen_col[cen_col >= 0]]
        ang[ang_col >= 0] = xv[ang_col[ang_col >= 0]]
        pts[pt_col >= 0] = xv[pt_col[pt_col >= 0]]
        lv = xv[l_col] if tripod else None
        return cam, cen, ang, pts, lv

    def arguments(xv):
        cam, cen, ang, pts, lv = unpack(xv)
        args = [cam[cam_of, 0], cam[cam_of, 1], cam[cam_of, 2], cen[cen_of, 0], cen[cen_of, 1], cen[cen_of, 2]]
        if tripod:
            args += [np.full(n_obs, lv[0]), np.full(n_obs, lv[1]), np.full(n_obs, lv[2])]
        args += [ang[img_of, 0], ang[img_of, 1], ang[img_of, 2], pts[pid, 0], pts[pid, 1], pts[pid, 2],
                 xy[:, 0], xy[:, 1]]
        return args

    def linearize(xv):
        args = arguments(xv)
        F = res_fn(*args)                                   # (2, n_obs)
        J = jac_fn(*args).reshape(2, n_par, n_obs)
        B = np.zeros((m, n_unknown))
        for r in range(2):
            for j, col in enumerate(model_cols):
                sel = col >= 0
                B[2 * rows[sel] + r, col[sel]] = J[r, j, sel]
        L = np.empty(m)
        L[0:2 * n_obs:2], L[1:2 * n_obs:2] = F[0], F[1]
        if gnss_rows:
            cen = unpack(xv)[1]
            for q, (c, k, meas, _) in enumerate(gnss_rows):
                B[2 * n_obs + q, cen_col[c, k]] = 1.0
                L[2 * n_obs + q] = cen[c, k] - meas
        return B, L

    weights = np.ones(m)
    for q, (_, _, _, s) in enumerate(gnss_rows):
        weights[2 * n_obs + q] = (sigma0 / s) ** 2
    try:
        with blas_on_one_thread():    # a few hundred unknowns: threads only wait for each other
            adj = gauss_newton(linearize, x_start, weights, tol=tol, max_iter=max_iter, names=tuple(names))
    except DegenerateGeometryError as exc:
        hint = ""
        if targets == "plane" and datum == "minimal":
            hint = (" (datum='minimal' leaves the tilt of the bundle against the plane free while the centres "
                    "coincide: start the tripod offset l0 ≠ 0 or use datum='first-image')")
        raise DegenerateGeometryError(f"the calibration network is singular: {exc}{hint}") from exc
    except ConvergenceError as exc:
        raise ConvergenceError(f"the calibration network did not converge: {exc}", exc.history) from exc
    cam, cen, ang, pts, lv = unpack(adj.x)
    std = adj.std

    def sd(cols):
        out = np.zeros(cols.shape)
        out[cols >= 0] = std[cols[cols >= 0]]
        return out

    image_centres = cen[[im.centre for im in obs.images]]
    if tripod:
        image_centres = image_centres + np.einsum("kij,j->ki", rotation_aok(ang[:, 0], ang[:, 1], ang[:, 2]), lv)
    return NetworkCalibration(cameras=cam, cameras_std=sd(cam_col), centres=cen, centres_std=sd(cen_col),
                              angles=ang, angles_std=sd(ang_col), image_centres=image_centres,
                              l=lv, l_std=sd(l_col) if tripod else None, points=pts, points_std=sd(pt_col),
                              point_used=used, targets=targets, gnss_mode=gnss_mode, adjustment=adj)


def _gnss_list(gnss, n_centres):
    if gnss is None:
        return []
    if isinstance(gnss, GnssCentre):
        gnss = [gnss]
    try:
        items = list(gnss)
    except TypeError:
        raise InputError(f"gnss must be a sequence of GnssCentre, got {type(gnss).__name__}") from None
    if not all(isinstance(g, GnssCentre) for g in items):
        raise InputError("gnss must be a sequence of GnssCentre")
    seen = set()
    for g in items:
        if g.centre >= n_centres:
            raise InputError(f"GNSS centre {g.centre} is not in the mock-up ({n_centres} centres)")
        if g.centre in seen:
            raise InputError(f"GNSS centre {g.centre} is given twice")
        seen.add(g.centre)
    return items


def _start(value, default, shape, what):
    if value is None:
        return np.array(default, dtype=float).copy()
    a = np.asarray(value, dtype=float) if not isinstance(value, (str, bytes)) else None
    if a is None or a.shape != tuple(shape):
        raise InputError(f"{what} must have shape {tuple(shape)}, got {None if a is None else a.shape}")
    if not np.all(np.isfinite(a)):
        raise InputError(f"{what} contain NaN or inf")
    return a.copy()


_HORIZONTAL = 1e-3     # rad: an image within this of α = ω = 0 counts as horizontal


def _check_horizontal(obs, ang0, z_known, pts0):
    """Refuse the classic singular case: a camera whose every image is horizontal over a horizontal
    plane target while the height of a centre is free — f and Z_S enter only as f/Z_S (§2.2,
    Fig. 23, the transformed bundle with k for f and Z_S)."""
    used = np.zeros(len(pts0), bool)
    for im in obs.images:
        used[im.point_ids] = True
    z = pts0[used, 2]
    if np.ptp(z) > 1e-9 * max(1.0, np.abs(z).max()):
        return                                          # not a plane target: no verdict here
    for c in range(len(obs.cameras)):
        imgs = [i for i, im in enumerate(obs.images) if im.camera == c]
        if not imgs:
            continue
        horizontal = all(np.hypot(ang0[i, 0], ang0[i, 1]) < _HORIZONTAL for i in imgs)
        z_free = any(not z_known[obs.images[i].centre] for i in imgs)
        if horizontal and z_free:
            raise DegenerateGeometryError(
                f"camera {c}: every image ({', '.join(map(str, imgs))}) is horizontal (α = ω = 0) over the "
                "plane target and the centre height Z_S is free — f and Z_S enter only as f/Z_S and cannot "
                "be separated (the transformed bundle, Sementsov §2.2, Fig. 23); fix Z_S (GNSS) or tilt an image")


# =================================================================================================
# Appendix A statistics
# =================================================================================================
@dataclass(frozen=True)
class ErrorStatistics:
    """The statistics of Appendix A for a set of errors (one column per quantity).

    Attributes
    ----------
    n : int
        Number of rows (mock-ups; 2-3 pools both cameras).
    mean, max, min, sko : ndarray
        Per column: mean («сред.»), largest, smallest, and SKO («СКО»), the sample standard
        deviation with ddof = 1.
    m_minus_sigma, m_plus_sigma : ndarray
        mean − SKO and mean + SKO («m − σ», «m + σ»).
    corr : (k, k) ndarray
        Pearson correlation matrix (Table A.21 prints corr[0, 1], corr[0, 2], corr[1, 2]).

    References
    ----------
    Sementsov (2019), Appendix A, Tables A.2–A.20 (lines 1562–2000) and A.21 (lines 2002–2015).

    Examples
    --------
    >>> s = error_statistics([[1.0, 2.0], [3.0, 1.0], [2.0, 0.0]])
    >>> s.mean.tolist(), s.sko.tolist()
    ([2.0, 1.0], [1.0, 1.0])
    """

    n: int
    mean: np.ndarray
    max: np.ndarray
    min: np.ndarray
    sko: np.ndarray
    m_minus_sigma: np.ndarray
    m_plus_sigma: np.ndarray
    corr: np.ndarray

    @property
    def pairs(self) -> np.ndarray:
        """The upper-triangle correlations in Table A.21's order: (0,1), (0,2), (1,2), …"""
        i, j = np.triu_indices(self.corr.shape[0], 1)
        return self.corr[i, j]


def error_statistics(errors) -> ErrorStatistics:
    """Mean, max, min, SKO (sample SD, ddof = 1), m ∓ σ and Pearson correlations, as in Appendix A.

    Parameters
    ----------
    errors : (n, k) array
        One row per mock-up (σ_f, σ_x₀, σ_y₀ of Appendix A: estimated minus true, px); n ≥ 2.

    Returns
    -------
    ErrorStatistics
        The statistics per column and the correlation matrix (NaN where a column is constant).

    Raises
    ------
    InputError
        Not a 2-D array of finite numbers, fewer than 2 rows.

    References
    ----------
    Sementsov (2019), Appendix A, Tables A.2–A.21, seed lines 1562–2015.

    Examples
    --------
    >>> s = error_statistics([[-0.69, 0.23], [3.07, -1.42], [2.11, -0.49]])
    >>> s.max.tolist(), s.min.tolist(), round(float(s.m_plus_sigma[0]), 4)
    ([3.07, 0.23], [-0.69, -1.42], 3.4503)
    >>> round(float(s.pairs[0]), 4)                 # Pearson's r (scipy.stats.pearsonr gives the same)
    -0.9398
    """
    E = _errors(errors)
    n = E.shape[0]
    mean = E.mean(axis=0)
    sko = E.std(axis=0, ddof=1)
    dev = E - mean
    with np.errstate(divide="ignore", invalid="ignore"):
        cov = dev.T @ dev
        d = np.sqrt(np.diag(cov))
        corr = cov / np.outer(d, d)
    np.fill_diagonal(corr, np.where(d > 0, 1.0, np.nan))
    return ErrorStatistics(n, mean, E.max(axis=0), E.min(axis=0), sko, mean - sko, mean + sko, corr)


def _errors(errors) -> np.ndarray:
    if isinstance(errors, (str, bytes)):
        raise InputError(f"errors must be numbers, got {errors!r}")
    try:
        E = np.asarray(errors, dtype=float)
    except (TypeError, ValueError):
        raise InputError("errors must be an (n, k) array of numbers") from None
    if E.ndim == 1:
        E = E[:, None]
    if E.ndim != 2 or E.shape[1] < 1:
        raise InputError(f"errors must be an (n, k) array, got shape {E.shape}")
    if E.shape[0] < 2:
        raise InputError(f"the statistics need at least 2 rows, got {E.shape[0]}")
    if not np.all(np.isfinite(E)):
        raise InputError("errors contain NaN or inf")
    return E


# =================================================================================================
# Table 1: the variants of §3.1
# =================================================================================================
@dataclass(frozen=True)
class MockupVariant:
    """One variant of Table 1: its images, cameras, centres and GNSS-known components.

    Attributes
    ----------
    name : str
        "0-1" … "3-2".
    methodology : str
        The calibration methodology of §2.2 (reference, 1, 2 or 3).
    angles_deg : tuple of (α, ω, κ)
        The tilt angles of the images, degrees, as printed.
    cameras : tuple of int
        Camera index of every image.
    centres : tuple of int
        Centre index of every image (equal indices: S₁ = S₂).
    gnss : str
        Centre components known from GNSS ("XYZ", "XY", "Z", "X" or "").
    description : str
        The row of Table 1 in English.
    lines : tuple of int
        The seed line of the row.

    References
    ----------
    Sementsov (2019), §3.1, Table 1, seed lines 1006–1018.

    Examples
    --------
    >>> v = TABLE1_VARIANTS["2-3"]
    >>> v.cameras, v.centres, v.gnss
    ((0, 1), (0, 0), '')
    """

    name: str
    methodology: str
    angles_deg: tuple
    cameras: tuple
    centres: tuple
    gnss: str
    description: str
    lines: tuple

    @property
    def n_cameras(self) -> int:
        return max(self.cameras) + 1

    @property
    def n_centres(self) -> int:
        return max(self.centres) + 1


def _v(name, meth, angles, cams, cens, gnss, text, line):
    return MockupVariant(name, meth, tuple(angles), tuple(cams), tuple(cens), gnss, text, (line, line))


_T30, _TM30, _W30, _H = (30.0, 0.0, 0.0), (-30.0, 0.0, 0.0), (0.0, 30.0, 0.0), (0.0, 0.0, 0.0)
TABLE1_VARIANTS = {
    "0-1": _v("0-1", "reference", [_H], [0], [0], "XYZ",
              "1 image, α = 0° (horizontal); X_S, Y_S, Z_S known from GNSS", 1009),
    "1-1": _v("1-1", "1", [_T30], [0], [0], "XYZ", "1 image, α = 30°; X_S, Y_S, Z_S known from GNSS", 1010),
    "1-2": _v("1-2", "1", [_T30], [0], [0], "XY", "1 image, α = 30°; X_S and Y_S known from GNSS", 1011),
    "1-3": _v("1-3", "1", [_T30], [0], [0], "Z", "1 image, α = 30°; Z_S known from GNSS", 1012),
    "1-4": _v("1-4", "1", [_T30], [0], [0], "X", "1 image, α = 30°; X_S known from GNSS", 1013),
    "2-1": _v("2-1", "2", [_T30, _TM30], [0, 0], [0, 0], "",
              "1 camera, 2 images, α₁ = 30°, α₂ = −30°; S₁ = S₂", 1014),
    "2-2": _v("2-2", "2", [_T30, _TM30], [0, 0], [0, 1], "",
              "1 camera, 2 images, α₁ = 30°, α₂ = −30°; S₁ ≠ S₂", 1015),
    "2-3": _v("2-3", "2", [_T30, _TM30], [0, 1], [0, 0], "",
              "2 cameras, 2 images, α₁ = 30°, α₂ = −30°; S₁ = S₂", 1016),
    "3-1": _v("3-1", "3", [_T30, _W30], [0, 0], [0, 0], "",
              "1 camera, 2 images, α₁ = 30°, ω₂ = 30°; S₁ = S₂", 1017),
    "3-2": _v("3-2", "3", [_T30, _W30], [0, 0], [0, 1], "",
              "1 camera, 2 images, α₁ = 30°, ω₂ = 30°; S₁ ≠ S₂", 1018),
}
"""The ten variants of Table 1 (§3.1, lines 1006–1018). Angles not printed for an image are 0
(the second image of 3-1/3-2 is "ω₂ = 30°", α₂ = 0)."""


def variant_mockup(name, *, seed=None, sigma=0.5, camera=NEX5, height=300.0, half_size=1000.0,
                   step=50.0) -> MockupObservations:
    """One mock-up of a Table 1 variant: the §3.1 target seen from (0, 0, ``height``).

    The target is the 2 × 2 km plane Z = 0 with points every 50 m (line 1004); every centre is
    at (0, 0, 300 m) (Z_S = 300 m is printed; the plan position of the centres, also of
    "S₁ ≠ S₂", is not — an assumption); the camera is :data:`NEX5`.

    Parameters
    ----------
    name : str
        A key of :data:`TABLE1_VARIANTS`.
    seed : int, numpy.random.Generator or None, optional
        The random generator (or its seed).
    sigma : float, optional
        σ of the image coordinates (px), default 0.5 (line 1021).
    camera : MockupCamera, optional
        The true camera (both cameras of 2-3 are equal).
    height, half_size, step : float, optional
        Z_S, half the target side and the point spacing (m).

    Returns
    -------
    MockupObservations
        The simulated images (no GNSS: see :func:`simulate_gnss`).

    Raises
    ------
    InputError
        An unknown variant or bad numbers.

    References
    ----------
    Sementsov (2019), §3.1, lines 1004–1024, Table 1.

    Examples
    --------
    >>> obs = variant_mockup("3-1", seed=0)
    >>> [im.xy.shape[0] for im in obs.images]      # α₁ = 30° across the long side, ω₂ = 30° across the short one
    [117, 88]
    """
    v = _variant(name)
    if not isinstance(camera, MockupCamera):
        raise InputError(f"camera must be a MockupCamera, got {type(camera).__name__}")
    h = _checks.number(height, "height", True)
    stations = [MockupStation(np.radians(a), c, s) for a, c, s in zip(v.angles_deg, v.cameras, v.centres)]
    centres = np.tile([0.0, 0.0, h], (v.n_centres, 1))
    return simulate_mockup(planar_grid(half_size, step), [camera] * v.n_cameras, centres, stations,
                           sigma=sigma, seed=seed)


def _variant(name) -> MockupVariant:
    if not isinstance(name, str) or name not in TABLE1_VARIANTS:
        raise InputError(f"unknown Table 1 variant {name!r}; use one of {', '.join(TABLE1_VARIANTS)}")
    return TABLE1_VARIANTS[name]


@dataclass(frozen=True)
class VariantRuns:
    """A Monte Carlo of one Table 1 variant.

    Attributes
    ----------
    variant : str
        The variant name.
    gnss_mode : str
        "fixed" or "weighted".
    errors : (runs · c, 3) ndarray
        σ_f, σ_x₀, σ_y₀ (estimated − true, px); for two cameras (2-3) the rows of camera 1 and 2
        of each mock-up follow each other, as in Table A.15.
    mu : (runs,) ndarray
        μ of every mock-up (px).
    gnss_errors : (runs, 3) ndarray or None
        The simulated GNSS errors (measured − true X, Y, Z of the centre, m; all three drawn, the
        unknown components unused); None for a variant without GNSS.

    References
    ----------
    Sementsov (2019), §3.1, Appendix A.

    Examples
    --------
    >>> r = simulate_variant("2-1", runs=3, seed=0)
    >>> r.errors.shape, r.mu.shape
    ((3, 3), (3,))
    """

    variant: str
    gnss_mode: str
    errors: np.ndarray
    mu: np.ndarray
    gnss_errors: np.ndarray | None = None

    @property
    def statistics(self) -> ErrorStatistics:
        """:func:`error_statistics` of :attr:`errors`."""
        return error_statistics(self.errors)


def simulate_variant(name, runs=30, *, seed=None, gnss_mode="fixed", sigma=0.5,
                     gnss_sigma=(0.1, 0.1, 0.3)) -> VariantRuns:
    """Monte Carlo of a Table 1 variant: ``runs`` mock-ups, each calibrated by :func:`calibrate_network`.

    Each mock-up draws new image errors (σ = ``sigma``) and, for the variants with GNSS, a new
    GNSS measurement of the known centre components (σ = ``gnss_sigma``); the adjustment starts
    from the truth (the least-squares solution does not depend on the start).

    Parameters
    ----------
    name : str
        A key of :data:`TABLE1_VARIANTS`.
    runs : int, optional
        Number of mock-ups (the book made 30 per variant, line 1021).
    seed : int, numpy.random.Generator or None, optional
        The random generator (or its seed).
    gnss_mode : {"fixed", "weighted"}, optional
        How the GNSS components enter the adjustment.
    sigma : float, optional
        σ of the image coordinates (px).
    gnss_sigma : 3 floats, optional
        σ of the GNSS X, Y, Z (m).

    Returns
    -------
    VariantRuns
        The IO errors and μ of every mock-up.

    Raises
    ------
    InputError
        An unknown variant or option, runs < 2.

    References
    ----------
    Sementsov (2019), §3.1, lines 1002–1043, Appendix A.

    Examples
    --------
    >>> r = simulate_variant("1-1", runs=4, seed=1, gnss_mode="fixed")
    >>> r.errors.shape
    (4, 3)
    """
    v = _variant(name)
    runs = _checks.integer(runs, "runs", 2)
    if gnss_mode not in GNSS_MODES:
        raise InputError(f"gnss_mode must be 'fixed' or 'weighted', got {gnss_mode!r}")
    sig = _checks.number(sigma, "sigma", True)
    gsig = _vector(gnss_sigma, 3, "gnss_sigma")
    rng = _rng(seed)
    errors, mus, gnss_errors = [], [], []
    for _ in range(runs):
        obs = variant_mockup(name, seed=rng, sigma=sig)
        gnss = [simulate_gnss(obs, v.gnss, gsig, seed=rng)] if v.gnss else []
        res = calibrate_network(obs, gnss=gnss, gnss_mode=gnss_mode)
        errors.append(res.io_errors(obs))
        mus.append(res.mu)
        if gnss:
            gnss_errors.append(gnss[0].measured - obs.centres[0])
    return VariantRuns(name, gnss_mode, np.concatenate(errors), np.array(mus),
                       np.array(gnss_errors) if gnss_errors else None)


def variant_precision(name, *, gnss_mode="fixed", sigma=0.5, gnss_sigma=(0.1, 0.1, 0.3)) -> np.ndarray:
    """Expected standard deviations of the errors of f, x₀, y₀ in a Table 1 variant (first-order propagation).

    The image errors (σ = ``sigma``) propagate through the cofactors of the adjustment, σ²·Q; with
    ``gnss_mode="weighted"`` the GNSS errors are observations of the same adjustment and are in Q
    too. With ``gnss_mode="fixed"`` the measured components are constants of the adjustment, so
    their errors pass into the estimate through its sensitivity to the held values, ∂(f, x₀, y₀)/∂S_k
    (a central difference of the noise-free adjustment, ±1 cm): var = σ²·Q_jj + Σ_k (∂_j/∂S_k)²·σ_k².
    The SKO of a Monte Carlo of the variant (:func:`simulate_variant`) scatters about these values.

    Parameters
    ----------
    name : str
        A key of :data:`TABLE1_VARIANTS`.
    gnss_mode : {"fixed", "weighted"}, optional
        How the GNSS components enter the adjustment.
    sigma : float, optional
        σ of the image coordinates (px).
    gnss_sigma : 3 floats, optional
        σ of the GNSS X, Y, Z (m).

    Returns
    -------
    (c, 3) ndarray
        Expected SD of the errors of f, x₀, y₀ per camera (px).

    Raises
    ------
    InputError
        An unknown variant or option, a non-positive σ.

    References
    ----------
    Sementsov (2019), §3.1, Table 1, Appendix A; Chibunichev (2022), §1.8, eq. (1.8.8).

    Examples
    --------
    >>> variant_precision("2-1").round(2).tolist()
    [[0.13, 0.26, 0.49]]
    >>> variant_precision("1-1", gnss_mode="fixed").round(2).tolist()     # the book's 30 mock-ups: 2.00, 2.60, 1.34
    [[1.99, 2.63, 1.33]]
    """
    v = _variant(name)
    if gnss_mode not in GNSS_MODES:
        raise InputError(f"gnss_mode must be 'fixed' or 'weighted', got {gnss_mode!r}")
    sig = _checks.number(sigma, "sigma", True)
    gsig = _vector(gnss_sigma, 3, "gnss_sigma")
    if np.any(gsig <= 0):
        raise InputError(f"gnss_sigma must be positive, got {gsig.tolist()}")
    obs = variant_mockup(name, sigma=0.0)
    truth = obs.centres[0]
    gnss = [GnssCentre(0, truth, gsig, v.gnss)] if v.gnss else []
    res = calibrate_network(obs, gnss=gnss, gnss_mode=gnss_mode, sigma_image=sig)
    var = _io_cofactors(res) * sig ** 2
    if gnss and gnss_mode == "fixed":
        step = 0.01
        for k in np.flatnonzero(gnss[0].mask):
            d = np.zeros(3)
            d[k] = step
            hi = calibrate_network(obs, gnss=[GnssCentre(0, truth + d, gsig, v.gnss)]).cameras
            lo = calibrate_network(obs, gnss=[GnssCentre(0, truth - d, gsig, v.gnss)]).cameras
            var = var + ((hi - lo) / (2 * step) * gsig[k]) ** 2
    return np.sqrt(var)


def _io_cofactors(res: NetworkCalibration) -> np.ndarray:
    """Q_jj of f, x₀, y₀ of every camera (the first 3c unknowns), shape (c, 3)."""
    q = np.diag(res.adjustment.Q)[:3 * len(res.cameras)]
    return q.reshape(len(res.cameras), 3)


# =================================================================================================
# §3.2: the tripod mock-up
# =================================================================================================
TABLE2_ANGLES = ((0.0, 0.0, 0.0), (30.0, 0.0, 0.0), (-30.0, 0.0, 0.0), (0.0, 30.0, 0.0), (0.0, -30.0, 0.0))
"""α, ω, κ (degrees) of the five images of Table 2 (§3.2, lines 1062–1068)."""


def tripod_mockup(l=(0.0, 0.0, 0.0), *, sigma=0.5, seed=None, distance=2.0, step=0.25, half_size=3.0,
                  camera=NEX5) -> MockupObservations:
    """The §3.2 mock-up: five images (Table 2) turned about a tripod head in front of a wall target.

    The target is the plane Z = −``distance`` (2 m, line 1051) with points every 25 cm (line
    1049) over ±``half_size``; the tripod rotation point S₀ is the origin; axes as in Fig. 41 (X, Y
    along the plane, Z away from it); image i has its centre at S₀ + A_i·l (eq. (20)).

    Parameters
    ----------
    l : 3 floats, optional
        The offset of the projection centre from S₀ in the camera frame (m).
    sigma : float, optional
        σ of the image coordinates (px); 0.5 or 0.1 in Table 3.
    seed : int, numpy.random.Generator or None, optional
        The random generator (or its seed).
    distance, step, half_size : float, optional
        Distance to the plane, point spacing, half the target side (m).
    camera : MockupCamera, optional
        The camera (default :data:`NEX5`).

    Returns
    -------
    MockupObservations
        One centre (S₀ = 0) shared by the five images, ``l`` set.

    Raises
    ------
    InputError
        Bad numbers.

    References
    ----------
    Sementsov (2019), §3.2, lines 1047–1081 (Tables 2 and 3), eq. (20) (lines 883–885).

    Examples
    --------
    >>> obs = tripod_mockup(sigma=0.0)
    >>> obs.images[0].xy.shape[0]                # points on the central image (the book: 74)
    77
    """
    if not isinstance(camera, MockupCamera):
        raise InputError(f"camera must be a MockupCamera, got {type(camera).__name__}")
    dist = _checks.number(distance, "distance", True)
    stations = [MockupStation(np.radians(a)) for a in TABLE2_ANGLES]
    return simulate_mockup(planar_grid(half_size, step, z=-dist), [camera], np.zeros((1, 3)), stations,
                           sigma=sigma, seed=seed, l=_vector(l, 3, "l"))
