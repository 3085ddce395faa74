"""Photogrammetric camera calibration — Chapter 11, §11.1–11.3.

§11.3 "Фотограмметрическая калибровка цифровых съемочных камер" (photogrammetric calibration of
digital cameras).

* The distortion model (11.3.1) is Brown's model of Chapter 1, (1.2.2), with the coordinates
  reduced to the principal point (the print writes plain x, y in the terms while r is reduced;
  the certificates of Figs 11.20/11.21 reduce them): :func:`photolib.camera.distortion_correction`
  is used as it is. :func:`certificate_to_mm` / :func:`certificate_to_pixels` convert a
  calibration certificate between pixel and millimetre units (f·Δ, k₁/Δ², k₂/Δ⁴, …) and
  :func:`target_field_tolerances` gives the accuracy required of a 3-D test field,
  m_X = m_Y = 0.1·Z_min/f·Δ and m_Z = ΔZ/20 000.
* :func:`self_calibration` solves the collinearity condition equations (11.3.2) with the interior
  orientation f, x₀, y₀, k₁, k₂, k₃, p₁, p₂ and the exterior orientation of every image unknown —
  14 unknowns for one image of a test field, (11.3.3)–(11.3.7) — through the one least-squares
  engine (:func:`photolib.lsq.gauss_newton`, δ = −Q·Lᴺ: the print's (11.3.5) drops the minus).
  The Jacobian is the sympy model :func:`photolib.derivations.self_calibration_model` of §3.6
  (printed once to numpy in ``photolib._bundle_generated``), with the object points held fixed.
  Several images share the interior orientation: the chessboard method (11.3.8) with the camera
  fixed and the boards moving is the same adjustment written in the board's frame (each view's
  exterior orientation is the inverse of the board's pose; the print's +d_x in (11.3.8) is the
  sign slip — the correction is added to the measured coordinates as in (11.3.2)); the
  long-focus method with a common projection centre is ``common_centre=True``.
  A flat target seen frontally cannot separate f from the distance Z_S (Fig. 11.23): the normal
  matrix is singular or the correlation |r(f, Z_S)| exceeds ``max_correlation``, and
  :class:`~photolib.errors.DegenerateGeometryError` says so; oblique views cure it.
* :func:`find_chessboard` finds the inner corners of a chessboard in an image with the Chapter 5
  operators — Harris's response (:func:`photolib.features.harris`) and non-maximum suppression —
  keeps the X-junctions, refines them to sub-pixel precision by Förstner's operator (the point
  nearest, in least squares, to all edge lines through the window, Förstner & Gülch 1987 — the
  same estimator as OpenCV's ``cornerSubPix``) and orders them into the board's grid.
  :func:`calibrate_chessboard` chains detection-independent start values (homographies, Zhang
  2000) and :func:`self_calibration`.

Units: image coordinates, f and x₀, y₀ in any length unit (mm, or pixels with y up); the
distortion coefficients in the matching powers of that unit. Angles in radians.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .camera import ExteriorOrientation, InteriorOrientation, as_points
from .errors import DegenerateGeometryError, InputError

__all__ = ["IO_NAMES", "EO_NAMES", "target_field_tolerances", "certificate_to_mm", "certificate_to_pixels",
           "calibration_residuals", "CalibrationResult", "self_calibration", "planar_start_values",
           "find_chessboard", "refine_corners", "render_chessboard", "calibrate_chessboard",
           "pixels_to_image", "image_to_pixels"]

IO_NAMES = ("f", "x0", "y0", "k1", "k2", "k3", "p1", "p2")
"""The eight interior-orientation unknowns of (11.3.2), in the order of δ (11.3.3)."""

EO_NAMES = ("X_S", "Y_S", "Z_S", "omega", "alpha", "kappa")
"""The six exterior-orientation unknowns of (11.3.2)."""

_POWER = {"f": 1, "x0": 1, "y0": 1, "k1": -2, "k2": -4, "k3": -6, "p1": -1, "p2": -1}


def _positive(value, what) -> float:
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise InputError(f"{what} must be a number, got {value!r}") from None
    if not np.isfinite(v) or v <= 0:
        raise InputError(f"{what} must be a positive finite number, got {value!r}")
    return v


# --- §11.3: test field and certificates ---------------------------------------------------------
def target_field_tolerances(f, pixel_size, z_min, depth, precision_px: float = 0.1):
    """Largest admissible r.m.s. errors of the test-field coordinates (§11.3).

    m_X = m_Y = p·Z_min/f·Δ (the image precision p in pixels projected to the nearest target) and
    m_Z = ΔZ/20 000.

    Parameters
    ----------
    f : float
        Focal length (same unit as ``pixel_size``).
    pixel_size : float
        Pixel side Δ.
    z_min : float
        Distance from the camera to the nearest target (the unit of the result m_X, m_Y).
    depth : float
        Depth ΔZ of the test field (the unit of m_Z).
    precision_px : float
        Automatic image-measurement precision in pixels (the book's 0.1).

    Returns
    -------
    tuple of float
        (m_XY, m_Z).

    Raises
    ------
    InputError
        A non-positive or non-finite argument.

    References
    ----------
    Chibunichev (2022), §11.3 (test-field accuracy and the worked example).

    Examples
    --------
    >>> [round(v, 6) for v in target_field_tolerances(50.0, 0.005, 6000.0, 2000.0)]
    [0.06, 0.1]
    """
    f, d, z, dz, p = (_positive(v, w) for v, w in ((f, "f"), (pixel_size, "pixel_size"), (z_min, "z_min"),
                                                   (depth, "depth"), (precision_px, "precision_px")))
    return p * z / f * d, dz / 20000.0


def _certificate(values, factor_power):
    if not isinstance(values, dict) or not values:
        raise InputError("the certificate must be a non-empty dict {name: value} of f, x0, y0, k1, k2, k3, p1, p2")
    out = {}
    for name, v in values.items():
        base = name[:-6] if isinstance(name, str) and name.endswith("_sigma") else name
        if base not in _POWER:
            raise InputError(f"unknown certificate entry {name!r}; use {IO_NAMES} (or name_sigma)")
        try:
            v = float(v)
        except (TypeError, ValueError):
            raise InputError(f"certificate entry {name!r} must be a number") from None
        if not np.isfinite(v):
            raise InputError(f"certificate entry {name!r} is not finite")
        out[name] = v * factor_power(_POWER[base])
    return out


def certificate_to_mm(values, pixel_size_mm):
    """A calibration certificate in pixels → millimetres (Figs 11.20 → 11.21).

    Lengths are multiplied by the pixel size Δ; a coefficient of r^(n) by Δ^(−n):
    f_mm = f_px·Δ, k₁,mm = k₁,px/Δ², k₂,mm = k₂,px/Δ⁴, k₃/Δ⁶, p/Δ. Entries ``<name>_sigma`` (their
    r.m.s. errors) scale alike.

    Parameters
    ----------
    values : dict
        {name: value} with names among f, x0, y0, k1, k2, k3, p1, p2 (optionally ``_sigma``).
    pixel_size_mm : float
        Pixel side Δ in mm.

    Returns
    -------
    dict
        The same entries in mm units.

    Raises
    ------
    InputError
        Unknown names, non-numbers, a non-positive pixel size.

    References
    ----------
    Chibunichev (2022), §11.3, Figs 11.20–11.21; eq. (11.3.1).

    Examples
    --------
    >>> c = certificate_to_mm({"f": 8075.4, "k1": -2.1391e-9}, 0.0062)
    >>> round(c["f"], 4), float(f"{c['k1']:.4e}")
    (50.0675, -5.5648e-05)
    """
    d = _positive(pixel_size_mm, "pixel_size_mm")
    return _certificate(values, lambda n: d ** n)


def certificate_to_pixels(values, pixel_size_mm):
    """A calibration certificate in millimetres → pixels, the inverse of :func:`certificate_to_mm`.

    Parameters
    ----------
    values : dict
        {name: value} in mm units.
    pixel_size_mm : float
        Pixel side Δ in mm.

    Returns
    -------
    dict
        The same entries in pixel units.

    Raises
    ------
    InputError
        Unknown names, non-numbers, a non-positive pixel size.

    References
    ----------
    Chibunichev (2022), §11.3, Figs 11.20–11.21; eq. (11.3.1).

    Examples
    --------
    >>> round(certificate_to_pixels({"f": 50.068}, 0.0062)["f"], 1)
    8075.5
    """
    d = _positive(pixel_size_mm, "pixel_size_mm")
    return _certificate(values, lambda n: d ** (-n))


# --- pixel ↔ image coordinates ------------------------------------------------------------------
def _shape(shape):
    try:
        rows, cols = (int(v) for v in shape)
    except (TypeError, ValueError):
        raise InputError(f"shape must be (rows, cols), got {shape!r}") from None
    if rows < 1 or cols < 1:
        raise InputError(f"shape must be positive, got {shape!r}")
    return rows, cols


def pixels_to_image(uv, shape):
    """OpenCV pixel coordinates (u right, v down) → image coordinates in pixels (x right, y up).

    The origin is the centre of the sensor (§1.2), so x = u − (cols − 1)/2, y = (rows − 1)/2 − v.

    Parameters
    ----------
    uv : (n, 2) array
        Pixel coordinates, (0, 0) the centre of the top-left pixel.
    shape : (int, int)
        (rows, cols) of the image.

    Returns
    -------
    ndarray
        (n, 2) image coordinates in pixels.

    Raises
    ------
    InputError
        Wrong shape, NaN/inf.

    References
    ----------
    Chibunichev (2022), §1.2 (the image coordinate system); §11.3.

    Examples
    --------
    >>> pixels_to_image([[0.0, 0.0]], (480, 640))
    array([[-319.5,  239.5]])
    """
    rows, cols = _shape(shape)
    uv = as_points(uv, 2, "pixel coordinates")
    return np.column_stack([uv[:, 0] - (cols - 1) / 2, (rows - 1) / 2 - uv[:, 1]])


def image_to_pixels(xy, shape):
    """Image coordinates in pixels (y up, origin at the centre) → OpenCV pixels (u, v).

    Parameters
    ----------
    xy : (n, 2) array
        Image coordinates in pixels.
    shape : (int, int)
        (rows, cols).

    Returns
    -------
    ndarray
        (n, 2) pixel coordinates.

    Raises
    ------
    InputError
        Wrong shape, NaN/inf.

    References
    ----------
    Chibunichev (2022), §1.2; §11.3.

    Examples
    --------
    >>> image_to_pixels([[-319.5, 239.5]], (480, 640))
    array([[0., 0.]])
    """
    rows, cols = _shape(shape)
    xy = as_points(xy, 2, "image coordinates")
    return np.column_stack([xy[:, 0] + (cols - 1) / 2, (rows - 1) / 2 - xy[:, 1]])


# --- (11.3.2): condition equations ------------------------------------------------------------
def _selfcal(eo, XYZ, io_values, xy):
    """F (m, 2) and J (m, 2, 17) of (11.3.2) from the sympy model of §3.6."""
    from . import _bundle_generated

    fn = _bundle_generated.selfcal_kaw
    F, J = fn(eo[:, 0], eo[:, 1], eo[:, 2], eo[:, 3], eo[:, 4], eo[:, 5], XYZ[:, 0], XYZ[:, 1], XYZ[:, 2],
              *[float(v) for v in io_values], xy[:, 0], xy[:, 1])
    return np.asarray(F).T, np.asarray(J).reshape(2, 17, -1).transpose(2, 0, 1)


def _io_tuple(io):
    if not isinstance(io, InteriorOrientation):
        raise InputError(f"io must be an InteriorOrientation, got {type(io).__name__}")
    return np.array([getattr(io, n) for n in IO_NAMES], dtype=float)


def _eo_array(eo):
    if isinstance(eo, ExteriorOrientation):
        if eo.order != "kaw":
            raise InputError("exterior orientations must use the book's κ–α–ω sequence (order='kaw')")
        return np.array([eo.Xs, eo.Ys, eo.Zs, eo.omega, eo.alpha, eo.kappa], dtype=float)
    a = np.asarray(eo, dtype=float) if not isinstance(eo, (str, bytes)) else None
    if a is None or a.shape != (6,) or not np.all(np.isfinite(a)):
        raise InputError("an exterior orientation must be an ExteriorOrientation or 6 finite numbers "
                         "(X_S, Y_S, Z_S, ω, α, κ)")
    return a


def calibration_residuals(XYZ, xy, io: InteriorOrientation, eo):
    """Free terms of (11.3.2): l = x₀ − f·U/W − x − d_x, l_y alike (zero for exact data).

    d_x, d_y of (11.3.1) are evaluated at the measured coordinates reduced to the principal point
    (the correction is *added* to the measured coordinates, as in (1.2.3)).

    Parameters
    ----------
    XYZ : (n, 3) array
        Test-field coordinates.
    xy : (n, 2) array
        Measured image coordinates.
    io : InteriorOrientation
    eo : ExteriorOrientation (order "kaw") or (6,) array

    Returns
    -------
    ndarray
        (n, 2) values of the two equations.

    Raises
    ------
    InputError
        Wrong shapes, NaN/inf, mismatched sizes.

    References
    ----------
    Chibunichev (2022), §11.3, eqs. (11.3.1)–(11.3.2).

    Examples
    --------
    >>> from photolib.camera import InteriorOrientation
    >>> calibration_residuals([[0.0, 0.0, -10.0]], [[0.0, 0.0]], InteriorOrientation(50.0), [0, 0, 0, 0, 0, 0])
    array([[0., 0.]])
    """
    XYZ = as_points(XYZ, 3, "object points")
    xy = as_points(xy, 2, "image points")
    if len(XYZ) != len(xy):
        raise InputError(f"{len(XYZ)} object points but {len(xy)} image points")
    e = np.tile(_eo_array(eo), (len(xy), 1))
    F, _ = _selfcal(e, XYZ, _io_tuple(io), xy)
    return F


@dataclass
class CalibrationResult:
    """Result of :func:`self_calibration`: the camera, the views and their accuracy (11.3.6)–(11.3.7).

    Attributes
    ----------
    io : InteriorOrientation
        Adjusted interior orientation and distortion (units of the image coordinates).
    io_std : dict
        m_j = μ√Q_jj (11.3.6) of each calibrated element.
    eo : list of ExteriorOrientation
        Adjusted exterior orientation of each image (order "kaw").
    eo_std : ndarray
        (n_images, 6) their m_j.
    mu : float
        μ (11.3.7), in the unit of the image coordinates when ``sigma_image`` is that unit.
    residuals : list of ndarray
        Per image, (k_i, 2) residuals V of the image coordinates.
    rms : float
        √(Σ|v|²/Σk): the r.m.s. reprojection error per point (OpenCV's "RMS").
    names : tuple of str
        Names of the unknowns (columns of ``corr``).
    corr : ndarray
        Correlation matrix of the unknowns.
    calibrated : tuple of str
        The interior elements estimated.
    iterations : int
        Gauss–Newton steps.

    References
    ----------
    Chibunichev (2022), §11.3, eqs. (11.3.3)–(11.3.7).

    Examples
    --------
    >>> r = CalibrationResult(InteriorOrientation(50.0), {}, [], np.zeros((0, 6)), 0.0, [], 0.0, (), np.eye(0), (), 0)
    >>> r.io.f
    50.0
    """

    io: InteriorOrientation
    io_std: dict
    eo: list
    eo_std: np.ndarray
    mu: float
    residuals: list
    rms: float
    names: tuple
    corr: np.ndarray
    calibrated: tuple
    iterations: int
    extra: dict = field(default_factory=dict)

    def correlation(self, a: str, b: str) -> float:
        """r between two unknowns named as in :attr:`names` (e.g. ``"f"``, ``"Z_S[0]"``)."""
        try:
            i, j = self.names.index(a), self.names.index(b)
        except ValueError:
            raise InputError(f"unknown names {a!r}/{b!r}; choose among {self.names}") from None
        return float(self.corr[i, j])


def _check_calibrate(calibrate):
    names = tuple(calibrate) if not isinstance(calibrate, str) else (calibrate,)
    bad = [n for n in names if n not in IO_NAMES]
    if bad or not names or len(set(names)) != len(names):
        raise InputError(f"calibrate: choose distinct names among {IO_NAMES}, got {calibrate!r}")
    return tuple(n for n in IO_NAMES if n in names)


def self_calibration(object_points, image_points, io0: InteriorOrientation, eo0, *, calibrate=IO_NAMES,
                     common_centre: bool = False, sigma_image: float = 1.0, max_correlation: float = 0.9999,
                     max_iter: int = 50) -> CalibrationResult:
    """Calibration by the collinearity equations (11.3.2), solved by least squares (11.3.3)–(11.3.7).

    Unknowns: the interior elements named in ``calibrate`` (all eight by default: with the six
    exterior elements of one image these are the book's n = 14) and the exterior orientation of
    every image; the object points are known. With several images (the chessboard method (11.3.8),
    or one test field shot repeatedly) the interior orientation is common; with
    ``common_centre=True`` the projection centre is common too and each image has only its three
    angles (the long-focus method of §11.3). Solved by Gauss–Newton, δ = −Q·Lᴺ; the printed
    (11.3.5) "δ = Q·Lᴺ" lacks the minus sign.

    Internally the image coordinates are scaled to O(1) (divided by f₀) so that the normal matrix
    is well conditioned; the results are returned in the input units.

    Parameters
    ----------
    object_points : (k, 3) array or list of them
        Test-field coordinates; one array per image (or one array for all images).
    image_points : (k, 2) array or list of them
        Measured image coordinates (y up, origin near the principal point), one per image.
    io0 : InteriorOrientation
        Start values (and the fixed values of the elements not calibrated).
    eo0 : ExteriorOrientation / (6,) array, or a list of them
        Start values of each image's exterior orientation (order "kaw").
    calibrate : sequence of str
        Interior elements to estimate (subset of :data:`IO_NAMES`).
    common_centre : bool
        One projection centre for all images (long-focus calibration).
    sigma_image : float
        A-priori σ of an image coordinate (weights p = 1, μ in these units).
    max_correlation : float
        |r| between an interior element and another unknown above which the geometry is called
        degenerate (e.g. f and Z_S for a frontal flat target).
    max_iter : int
        Iterations allowed.

    Returns
    -------
    CalibrationResult

    Raises
    ------
    InputError
        Wrong shapes, NaN/inf, mismatched sizes, unknown names, fewer observations than unknowns.
    DegenerateGeometryError
        The target's geometry cannot separate the unknowns (singular normal matrix, or |r| above
        ``max_correlation``): the pair is named — for a flat target seen frontally, f and Z_S.
    ConvergenceError
        No convergence.

    References
    ----------
    Chibunichev (2022), §11.3, eqs. (11.3.1)–(11.3.8); §3.6, eqs. (3.6.1)–(3.6.3).

    Examples
    --------
    >>> import numpy as np
    >>> from photolib.camera import InteriorOrientation
    >>> g = np.mgrid[-2:3, -2:3].reshape(2, -1).T.astype(float)
    >>> XYZ = np.column_stack([g, -10.0 - (g ** 2).sum(1) % 3])          # three depth levels
    >>> true = InteriorOrientation(50.0, 0.1, -0.2)
    >>> from photolib.single_image import project
    >>> from photolib.camera import ExteriorOrientation
    >>> xy = project(XYZ, ExteriorOrientation(0, 0, 0, 0, 0, 0), true)
    >>> r = self_calibration(XYZ, xy, InteriorOrientation(48.0), [0.1, 0, 0.2, 0, 0, 0],
    ...                      calibrate=("f", "x0", "y0"))
    >>> round(r.io.f, 6), round(r.io.x0, 6), round(r.io.y0, 6)
    (50.0, 0.1, -0.2)
    """
    from . import lsq

    names_io = _check_calibrate(calibrate)
    single = isinstance(image_points, np.ndarray) or (
        isinstance(image_points, (list, tuple)) and len(image_points) > 0
        and np.ndim(image_points[0]) == 1)
    imgs = [image_points] if single else list(image_points)
    if not imgs:
        raise InputError("no images given")
    imgs = [as_points(p, 2, f"image points of image {i}") for i, p in enumerate(imgs)]
    n = len(imgs)
    if isinstance(object_points, (list, tuple)) and len(object_points) == n and np.ndim(object_points[0]) == 2:
        objs = [as_points(p, 3, f"object points of image {i}") for i, p in enumerate(object_points)]
    else:
        o = as_points(object_points, 3, "object points")
        objs = [o] * n
    for i, (o, p) in enumerate(zip(objs, imgs)):
        if len(o) != len(p):
            raise InputError(f"image {i}: {len(o)} object points but {len(p)} image points")
    if isinstance(eo0, ExteriorOrientation) or (
            isinstance(eo0, (list, tuple, np.ndarray)) and len(eo0) > 0
            and all(isinstance(v, (int, float, np.number)) for v in np.asarray(eo0, dtype=object).ravel()[:6])
            and np.ndim(eo0) == 1):
        eos = [_eo_array(eo0)]
    else:
        eos = [_eo_array(e) for e in eo0]
    if len(eos) != n:
        raise InputError(f"{n} images but {len(eos)} start orientations")
    io_full = _io_tuple(io0)
    sig = _positive(sigma_image, "sigma_image")
    if not 0 < max_correlation <= 1:
        raise InputError("max_correlation must lie in (0, 1]")
    # scale the image to O(1): lengths / s, k_n · s^(2n), p · s
    s = float(io0.f)
    scale = np.array([s ** _POWER[nm] for nm in IO_NAMES])
    io_s = io_full / scale
    xy_all = np.vstack(imgs) / s
    XYZ_all = np.vstack(objs)
    img_of = np.repeat(np.arange(n), [len(p) for p in imgs])
    cols_io = [IO_NAMES.index(nm) for nm in names_io]
    g = len(cols_io)
    if common_centre:
        x0 = np.concatenate([io_s[cols_io], eos[0][:3], np.concatenate([e[3:] for e in eos])])
        names = names_io + ("X_S", "Y_S", "Z_S") + tuple(f"{a}[{i}]" for i in range(n) for a in EO_NAMES[3:])
    else:
        x0 = np.concatenate([io_s[cols_io], np.concatenate(eos)])
        names = names_io + tuple(f"{a}[{i}]" for i in range(n) for a in EO_NAMES)
    m = 2 * len(xy_all)
    if m < len(x0):
        raise InputError(f"{m} equations for {len(x0)} unknowns: too few points")

    def unpack(x):
        io_v = io_s.copy()
        io_v[cols_io] = x[:g]
        if common_centre:
            centre = x[g:g + 3]
            ang = x[g + 3:].reshape(n, 3)
            eo = np.column_stack([np.tile(centre, (n, 1)), ang])
        else:
            eo = x[g:].reshape(n, 6)
        return io_v, eo

    def linearize(x):
        io_v, eo = unpack(x)
        F, J = _selfcal(eo[img_of], XYZ_all, io_v, xy_all)
        B = np.zeros((len(xy_all), 2, len(x)))
        B[:, :, :g] = J[:, :, [9 + c for c in cols_io]]
        for i in range(n):
            rows = img_of == i
            if common_centre:
                B[rows, :, g:g + 3] = J[rows, :, :3]
                B[rows, :, g + 3 + 3 * i:g + 6 + 3 * i] = J[rows, :, 3:6]
            else:
                B[rows, :, g + 6 * i:g + 6 * i + 6] = J[rows, :, :6]
        return B.reshape(-1, len(x)), F.reshape(-1)

    tol = np.concatenate([np.full(g, 1e-10), np.full(len(x0) - g, 1e-9)])
    try:
        adj = lsq.gauss_newton(linearize, x0, tol=tol, max_iter=max_iter, names=names)
    except DegenerateGeometryError as exc:
        raise DegenerateGeometryError(
            f"the calibration is singular: the target's geometry cannot separate the unknowns ({exc}); "
            "a flat target seen frontally cannot separate f from the distance Z_S — take oblique views "
            "(or a 3-D test field)") from exc
    corr = adj.corr
    for i in range(g):
        for j in range(len(names)):
            if j != i and abs(corr[i, j]) > max_correlation:
                raise DegenerateGeometryError(
                    f"|r({names[i]}, {names[j]})| = {abs(corr[i, j]):.6f} > {max_correlation}: the target's "
                    "geometry cannot separate them (a flat target seen frontally cannot separate f from Z_S; "
                    "take oblique views from several sides)")
    io_v, eo = unpack(adj.x)
    io = InteriorOrientation(*(float(v) for v in io_v * scale))
    mu_unit = adj.mu * s            # μ of the scaled problem → input units
    std = np.asarray(adj.std)
    io_std = {nm: float(std[k] * scale[IO_NAMES.index(nm)]) for k, nm in enumerate(names_io)}
    if common_centre:
        eo_std = np.column_stack([np.tile(std[g:g + 3], (n, 1)), std[g + 3:].reshape(n, 3)])
    else:
        eo_std = std[g:].reshape(n, 6)
    V = adj.residuals.reshape(-1, 2) * s
    res = [V[img_of == i] for i in range(n)]
    rms = float(np.sqrt(np.sum(V ** 2) / len(V)))
    eo_list = [ExteriorOrientation(*e, order="kaw") for e in eo]
    return CalibrationResult(io=io, io_std=io_std, eo=eo_list, eo_std=eo_std, mu=float(mu_unit),
                             residuals=res, rms=rms, names=names, corr=np.asarray(corr), calibrated=names_io,
                             iterations=adj.iterations)


# --- planar start values (Zhang 2000) --------------------------------------------------------------
def planar_start_values(board_xy, image_points, f0=None):
    """Start values for flat-target calibration: f and each view's exterior orientation.

    For each view the homography H of board → image (:func:`photolib.projective.homography_dlt`) is
    computed; with the principal point at the origin and square pixels, its two orthogonality
    constraints h₁ᵀωh₂ = 0 and h₁ᵀωh₁ = h₂ᵀωh₂ (ω = diag(1/f², 1/f², 1)) give 1/f² by linear least
    squares over all views (Zhang 2000), unless ``f0`` is given; then R, t follow from K⁻¹H and are
    converted to the book's exterior orientation of the camera in the board's frame
    (:func:`photolib.conventions.opencv_to_eo`).

    Parameters
    ----------
    board_xy : (k, 2) array
        Board coordinates (X′, Y′) of the targets (Z′ = 0).
    image_points : list of (k, 2) arrays
        Image coordinates (y up, origin near the principal point) of each view.
    f0 : float, optional
        Known approximate focal length (same units as the image coordinates).

    Returns
    -------
    tuple
        (f, list of ExteriorOrientation).

    Raises
    ------
    InputError
        Wrong shapes, NaN/inf, fewer than 4 points.
    DegenerateGeometryError
        Every view frontal (f undetermined — give ``f0``) or a degenerate homography.

    References
    ----------
    Chibunichev (2022), §11.3, eq. (11.3.8); Zhang, Z. (2000), A flexible new technique for camera
    calibration, IEEE TPAMI 22(11).

    Examples
    --------
    >>> import numpy as np
    >>> b = np.mgrid[0:4, 0:3].reshape(2, -1).T.astype(float)
    >>> f, eos = planar_start_values(b, [b * 100 + 1.0], f0=500.0)
    >>> f, len(eos)
    (500.0, 1)
    """
    from .conventions import opencv_to_eo
    from .projective import homography_dlt

    board = as_points(board_xy, 2, "board coordinates")
    if len(board) < 4:
        raise InputError(f"{len(board)} board points: at least 4 are needed")
    if isinstance(image_points, np.ndarray) and image_points.ndim == 2:
        image_points = [image_points]
    views = [as_points(p, 2, f"image points of view {i}") for i, p in enumerate(image_points)]
    if not views:
        raise InputError("no views given")
    Hs = []
    for i, p in enumerate(views):
        if len(p) != len(board):
            raise InputError(f"view {i}: {len(p)} image points for {len(board)} board points")
        uv = np.column_stack([p[:, 0], -p[:, 1]])          # OpenCV axes (y down), origin at the principal point
        Hs.append(homography_dlt(board, uv))
    extent = float(np.max(np.abs(board - board.mean(0))))
    perspective = max(float(np.hypot(H[2, 0], H[2, 1]) * extent / abs(H[2, 2])) for H in Hs)
    if f0 is None and perspective < 1e-6:
        raise DegenerateGeometryError("every view is frontal (no perspective in the homographies): "
                                      "the focal length is undetermined — tilt the board or give f0")
    if f0 is None:
        a, b = [], []
        for H in Hs:
            h1, h2 = H[:, 0], H[:, 1]
            a += [h1[0] * h2[0] + h1[1] * h2[1], h1[0] ** 2 + h1[1] ** 2 - h2[0] ** 2 - h2[1] ** 2]
            b += [h1[2] * h2[2], h1[2] ** 2 - h2[2] ** 2]
        a, b = np.array(a), np.array(b)
        denom = np.dot(a, a)
        w = -np.dot(a, b) / denom if denom > 0 else np.nan
        if not np.isfinite(w) or w <= 0:
            raise DegenerateGeometryError("the views cannot fix the focal length (all frontal?): give f0")
        f = float(1.0 / np.sqrt(w))
    else:
        f = _positive(f0, "f0")
    Kinv = np.diag([1.0 / f, 1.0 / f, 1.0])
    eos = []
    for i, H in enumerate(Hs):
        M = Kinv @ H
        lam = 1.0 / np.linalg.norm(M[:, 0])
        if M[2, 2] * lam < 0:
            lam = -lam
        r1, r2, t = lam * M[:, 0], lam * M[:, 1], lam * M[:, 2]
        R = np.column_stack([r1, r2, np.cross(r1, r2)])
        U, _, Vt = np.linalg.svd(R)
        R = U @ Vt
        if np.linalg.det(R) < 0:
            raise DegenerateGeometryError(f"view {i}: the homography does not decompose into a rotation")
        eos.append(opencv_to_eo(R, t, order="kaw", singular="kappa-zero"))
    return f, eos


# --- chessboard corners ----------------------------------------------------------------------------
def _gray(image, name):
    a = np.asarray(image) if not isinstance(image, (str, bytes)) else None
    if a is None or a.dtype == object or not np.issubdtype(a.dtype, np.number):
        raise InputError(f"image {name}: expected a numeric array")
    if a.ndim == 3 and a.shape[2] in (3, 4):
        a = a[..., :3].astype(float) @ np.array([0.299, 0.587, 0.114])
    if a.ndim != 2:
        raise InputError(f"image {name}: expected a (rows, cols) grey image, got shape {a.shape}")
    if min(a.shape) < 16:
        raise InputError(f"image {name}: too small ({a.shape})")
    a = a.astype(float)
    if not np.all(np.isfinite(a)):
        raise InputError(f"image {name}: contains NaN or inf")
    return a


def refine_corners(image, corners, half_window: int = 5, max_iter: int = 20, tol: float = 0.01):
    """Sub-pixel refinement of X-junction corners by Förstner's operator.

    The corner is the point p minimising Σ w (gᵀ(q − p))² over the window: every pixel q whose
    gradient g is not zero lies on an edge through the corner, so its gradient is orthogonal to
    q − p. The normal equations (Σ w g gᵀ) p = Σ w g gᵀ q are those of Förstner's point operator
    (Chapter 5); iterated with the window re-centred (w Gaussian of σ = half_window/2).

    Parameters
    ----------
    image : (rows, cols) array
        Grey image.
    corners : (n, 2) array
        Approximate corners (u, v) = (col, row) in pixels.
    half_window : int
        Half size of the square window (≥ 2).
    max_iter : int
        Iterations per corner.
    tol : float
        Stop when the shift is below this (pixels).

    Returns
    -------
    ndarray
        (n, 2) refined corners (u, v).

    Raises
    ------
    InputError
        Wrong shapes, NaN/inf, a corner whose window leaves the image.
    DegenerateGeometryError
        A textureless window (singular normal matrix).

    References
    ----------
    Chibunichev (2022), §5.8 (Förstner's operator), §11.3; Förstner, W., Gülch, E. (1987).

    Examples
    --------
    >>> img = render_chessboard((3, 3), 20.0, np.eye(3) + [[0, 0, 10], [0, 0, 10], [0, 0, 0]], (80, 80))
    >>> refine_corners(img, [[29.0, 31.0]]).round(2) + 0.0
    array([[30., 30.]])
    """
    from scipy import ndimage

    img = _gray(image, "")
    pts = as_points(corners, 2, "corners")
    h = int(half_window)
    if h < 2:
        raise InputError("half_window must be ≥ 2")
    gx, gy = _gradients(img)
    out, ok, why = _refine(gx, gy, pts, h, max_iter, tol)
    if not ok.all():
        k = int(np.flatnonzero(~ok)[0])
        if why[k] == "border":
            raise InputError(f"corner {k} at (u, v) = ({pts[k, 0]:.1f}, {pts[k, 1]:.1f}): its window leaves the image")
        raise DegenerateGeometryError(f"corner {k}: textureless or single-edge window, no corner")
    return out


def _gradients(img):
    from scipy import ndimage

    gy, gx = np.gradient(ndimage.gaussian_filter(img, 0.7))
    return gx, gy


def _refine(gx, gy, pts, h, max_iter=20, tol=0.01, max_shift=None):
    """Förstner refinement of many corners; (refined, ok mask, reason per corner)."""
    off = np.arange(-h, h + 1)
    du, dv = np.meshgrid(off, off)
    rows, cols = gx.shape
    out = np.array(pts, dtype=float).copy()
    ok = np.ones(len(out), bool)
    why = [""] * len(out)
    sigma_w = max(h / 2.0, 1.0)
    for k in range(len(out)):
        p = out[k].copy()
        for _ in range(max_iter):
            c, r = int(round(p[0])), int(round(p[1]))
            if c - h < 1 or r - h < 1 or c + h > cols - 2 or r + h > rows - 2:
                ok[k], why[k] = False, "border"
                break
            qx, qy = c + du, r + dv
            Gx, Gy = gx[r - h:r + h + 1, c - h:c + h + 1], gy[r - h:r + h + 1, c - h:c + h + 1]
            w = np.exp(-((qx - p[0]) ** 2 + (qy - p[1]) ** 2) / (2 * sigma_w ** 2))
            a, b, d = (w * Gx * Gx).sum(), (w * Gx * Gy).sum(), (w * Gy * Gy).sum()
            bx = (w * (Gx * Gx * qx + Gx * Gy * qy)).sum()
            by = (w * (Gx * Gy * qx + Gy * Gy * qy)).sum()
            det = a * d - b * b
            if not det > 1e-12 * max(a + d, 1e-300) ** 2:
                ok[k], why[k] = False, "texture"
                break
            new = np.array([(d * bx - b * by) / det, (a * by - b * bx) / det])
            shift = np.hypot(*(new - p))
            p = new
            if shift < tol:
                break
        if ok[k] and max_shift is not None and np.hypot(*(p - pts[k])) > max_shift:
            ok[k], why[k] = False, "shift"
        out[k] = p
    return out, ok, why


def _ring_test(sm, u, v, radius, contrast, min_opposite):
    from scipy import ndimage

    t = np.linspace(0, 2 * np.pi, 48, endpoint=False)
    vals = ndimage.map_coordinates(sm, [v + radius * np.sin(t), u + radius * np.cos(t)], order=1, mode="nearest")
    vals = vals - vals.mean()
    if np.ptp(vals) < contrast:
        return False
    s = np.sign(vals)
    s[s == 0] = 1
    changes = int(np.count_nonzero(s != np.roll(s, 1)))
    opposite = np.corrcoef(vals, np.roll(vals, 24))[0, 1]
    return changes == 4 and (min_opposite is None or opposite > min_opposite)


def _grow_grid(pts, seed, tree, need):
    d, nn = tree.query(pts[seed], k=min(9, len(pts)))
    p0 = pts[seed]
    v1 = pts[nn[1]] - p0
    v2 = None
    for j in nn[2:]:
        v = pts[j] - p0
        cosang = abs(np.dot(v, v1)) / (np.linalg.norm(v) * np.linalg.norm(v1))
        ratio = np.linalg.norm(v) / np.linalg.norm(v1)
        if cosang < 0.5 and 0.5 < ratio < 2.0:
            v2 = v
            break
    if v2 is None:
        return None
    grid = {(0, 0): seed}
    used = {seed}
    queue = [(0, 0)]
    base = {(1, 0): v1, (0, 1): v2}
    while queue:
        i, j = queue.pop(0)
        p = pts[grid[(i, j)]]
        for di, dj in ((1, 0), (-1, 0), (0, 1), (0, -1)):
            key = (i + di, j + dj)
            if key in grid:
                continue
            back = (i - di, j - dj)
            if back in grid:
                step = p - pts[grid[back]]
            else:
                # the step of a neighbouring row/column, else the seed's lattice vector
                step = None
                for side in ((dj, di), (-dj, -di)):
                    a, b = (i + side[0], j + side[1]), (i + side[0] + di, j + side[1] + dj)
                    if a in grid and b in grid:
                        step = pts[grid[b]] - pts[grid[a]]
                        break
                if step is None:
                    step = base[(abs(di), abs(dj))] * (di + dj)
            q = p + step
            dist, k = tree.query(q)
            if dist < 0.3 * np.linalg.norm(step) and k not in used:
                grid[key] = int(k)
                used.add(int(k))
                queue.append(key)
                if len(grid) > 4 * need:
                    return None
    return grid


def _full_window(grid, pts, cols_p, rows_p):
    """The one fully populated cols×rows window of a grown grid, as (rows, cols, 2), or None."""
    ij = np.array(list(grid.keys()))
    i0, j0 = ij.min(0)
    i1, j1 = ij.max(0)
    found = []
    for ni, nj, transpose in ((cols_p, rows_p, False), (rows_p, cols_p, True)):
        if transpose and cols_p == rows_p:
            break
        for a in range(i0, i1 - ni + 2):
            for b in range(j0, j1 - nj + 2):
                if all((a + di, b + dj) in grid for di in range(ni) for dj in range(nj)):
                    found.append((a, b, ni, nj, transpose))
    if len(found) != 1:
        return None
    a, b, ni, nj, transpose = found[0]
    W = np.array([[pts[grid[(a + di, b + dj)]] for dj in range(nj)] for di in range(ni)])   # (ni, nj, 2)
    return W if transpose else W.transpose(1, 0, 2)                                            # (rows, cols, 2)


def find_chessboard(image, pattern_size, *, name: str = "image", half_window: int = 5,
                    relative: float = 0.01, max_candidates: int = 600):
    """Inner corners of a chessboard, found with the Chapter 5 operators and ordered into its grid.

    1. Harris's response (:func:`photolib.features.harris`, Gaussian window σ = 1.5) and
       non-maximum suppression (:func:`photolib.features.nonmax_suppression`) give candidates.
    2. Only X-junctions are kept: on rings of radius 4 and 7 px the grey values, less their mean,
       change sign exactly four times and opposite quadrants agree (a corner of the board's border
       or of the background changes sign twice).
    3. Each is refined to sub-pixel precision by :func:`refine_corners` (Förstner's operator).
    4. From a seed corner and its two lattice vectors the grid is grown corner by corner, each
       step predicted from the previous one in the same row or column (perspective-tolerant); the
       grid must have exactly ``pattern_size`` corners.

    Parameters
    ----------
    image : (rows, cols) or (rows, cols, 3) array
        The image.
    pattern_size : (int, int)
        Inner corners per row and per column, OpenCV's (columns, rows), e.g. (9, 6).
    name : str
        The image's name, quoted in the error when no board is found.
    half_window : int
        Half window of the sub-pixel refinement.
    relative : float
        Harris threshold relative to the strongest response.
    max_candidates : int
        Largest number of Harris candidates examined.

    Returns
    -------
    ndarray
        (rows·cols, 2) corners (u, v) in pixels, row by row (``cols`` per row), the first corner
        nearer the image's top-left, u increasing along a row in the image's reading sense.

    Raises
    ------
    InputError
        Not an image, NaN/inf, a bad pattern size.
    DegenerateGeometryError
        No board of that size in the image (the message names the image).

    References
    ----------
    Chibunichev (2022), §11.3 (calibration by a chessboard, Fig. 11.28); §5.8, eqs. (5.8.2)–(5.8.4)
    (Harris), Förstner's operator.

    Examples
    --------
    >>> H = np.array([[20.0, 0, 30], [0, 20, 25], [0, 0, 1]])
    >>> img = render_chessboard((5, 4), 1.0, H, (140, 160))
    >>> c = find_chessboard(img, (4, 3))
    >>> c.shape, c[0].round(2).tolist()
    ((12, 2), [50.0, 45.0])
    """
    from scipy import ndimage
    from scipy.spatial import cKDTree

    from .features import harris, nonmax_suppression

    img = _gray(image, name)
    try:
        cols_p, rows_p = (int(v) for v in pattern_size)
    except (TypeError, ValueError):
        raise InputError(f"pattern_size must be (columns, rows), got {pattern_size!r}") from None
    if cols_p < 2 or rows_p < 2:
        raise InputError(f"pattern_size must be at least (2, 2), got {pattern_size!r}")
    need = cols_p * rows_p
    lo, hi = np.percentile(img, [1, 99])
    if hi - lo <= 0:
        raise DegenerateGeometryError(f"{name}: chessboard {cols_p}×{rows_p} not found (the image is flat)")
    R = harris(img, window=7, sigma=1.5)
    cand = nonmax_suppression(R, size=7, relative=relative, max_points=max_candidates, border=half_window + 3)
    gx, gy = _gradients(img)
    good, ok, _ = _refine(gx, gy, np.asarray(cand, dtype=float), int(half_window), max_shift=float(half_window))
    good = good[ok]
    sm = ndimage.gaussian_filter(img, 1.0)
    contrast = 0.2 * (hi - lo)
    inside = ((good[:, 0] > 9) & (good[:, 1] > 9) & (good[:, 0] < img.shape[1] - 10)
              & (good[:, 1] < img.shape[0] - 10))
    pts = np.array([q for q, ok in zip(good, inside)
                    if ok and _ring_test(sm, q[0], q[1], 4.0, contrast, None)
                    and _ring_test(sm, q[0], q[1], 7.0, contrast, 0.3)]).reshape(-1, 2)
    if len(pts) < need:
        raise DegenerateGeometryError(
            f"{name}: chessboard {cols_p}×{rows_p} not found ({len(pts)} X-junctions for {need} corners)")
    # merge duplicates (two candidates refined to one corner)
    tree = cKDTree(pts)
    drop = {j for i, j in sorted(tree.query_pairs(1.5))}
    pts = np.array([p for k, p in enumerate(pts) if k not in drop])
    tree = cKDTree(pts)
    centre = np.median(pts, axis=0)
    order = np.argsort(np.hypot(*(pts - centre).T))
    for seed in order[:40]:
        grid = _grow_grid(pts, int(seed), tree, need)
        if grid is None or len(grid) < need:
            continue
        G = _full_window(grid, pts, cols_p, rows_p)
        if G is None:
            continue
        along, down = G[0, 1] - G[0, 0], G[1, 0] - G[0, 0]
        if along[0] * down[1] - along[1] * down[0] < 0:        # reading order: along a row, then down
            G = G[:, ::-1]
        if G[-1, -1].sum() < G[0, 0].sum():                    # first corner nearer the top-left
            G = G[::-1, ::-1]
        return G.reshape(-1, 2)
    raise DegenerateGeometryError(f"{name}: chessboard {cols_p}×{rows_p} not found "
                                  f"({len(pts)} X-junctions, none forms the {cols_p}×{rows_p} grid)")


def render_chessboard(squares, square_size, H, shape, *, supersample: int = 8, dark: float = 20.0,
                      light: float = 230.0, margin: float = 1.0):
    """A chessboard rendered through a homography with anti-aliasing (synthetic ground truth).

    The board has ``squares`` = (columns, rows) squares of side ``square_size`` in its own (X′, Y′)
    plane, the top-left square dark, surrounded by a light margin of ``margin`` squares; pixel
    (u, v) shows the board point H⁻¹(u, v), averaged over supersample² sub-pixels (pixel centres at
    integers). Its inner corners are at H·(i·s, j·s) for i = 1…columns−1, j = 1…rows−1.

    Parameters
    ----------
    squares : (int, int)
        Squares per row and per column.
    square_size : float
        Side of a square (board units).
    H : (3, 3) array
        Board (X′, Y′, 1) → pixel (u, v, 1).
    shape : (int, int)
        (rows, cols) of the image.
    supersample : int
        Sub-pixels per pixel side.
    dark, light : float
        Grey values.
    margin : float
        Light border around the board, in squares.

    Returns
    -------
    ndarray
        (rows, cols) float image; the background (outside the board and margin) mid-grey.

    Raises
    ------
    InputError
        Bad sizes, a singular H.

    References
    ----------
    Chibunichev (2022), §11.3, Fig. 11.28.

    Examples
    --------
    >>> img = render_chessboard((2, 2), 10.0, np.eye(3), (20, 20))
    >>> float(img[2, 2]), float(img[2, 12])
    (20.0, 230.0)
    """
    try:
        nc, nr = (int(v) for v in squares)
        rows, cols = _shape(shape)
    except (TypeError, ValueError):
        raise InputError("squares and shape must be pairs of integers") from None
    if nc < 1 or nr < 1:
        raise InputError("squares must be positive")
    s = _positive(square_size, "square_size")
    H = np.asarray(H, dtype=float)
    if H.shape != (3, 3) or not np.all(np.isfinite(H)) or abs(np.linalg.det(H)) < 1e-12:
        raise InputError("H must be a finite, non-singular 3×3 matrix")
    n = int(supersample)
    if n < 1:
        raise InputError("supersample must be ≥ 1")
    Hi = np.linalg.inv(H)
    sub = (np.arange(n) + 0.5) / n - 0.5
    vv, uu = np.meshgrid(np.arange(rows), np.arange(cols), indexing="ij")
    acc = np.zeros((rows, cols))
    for dv in sub:
        for du in sub:
            u, v = uu + du, vv + dv
            w = Hi[2, 0] * u + Hi[2, 1] * v + Hi[2, 2]
            X = (Hi[0, 0] * u + Hi[0, 1] * v + Hi[0, 2]) / w
            Y = (Hi[1, 0] * u + Hi[1, 1] * v + Hi[1, 2]) / w
            i, j = np.floor(X / s), np.floor(Y / s)
            val = np.where((i + j) % 2 == 0, dark, light)
            inside = (X >= 0) & (X < nc * s) & (Y >= 0) & (Y < nr * s)
            border = (X >= -margin * s) & (X < (nc + margin) * s) & (Y >= -margin * s) & (Y < (nr + margin) * s)
            acc += np.where(inside, val, np.where(border, light, 0.5 * (dark + light)))
    return acc / n ** 2


def calibrate_chessboard(corners, pattern_size, square_size, shape, *, calibrate=("f", "x0", "y0", "k1", "k2", "k3",
                                                                                   "p1", "p2"),
                         f0=None) -> CalibrationResult:
    """Calibration by a chessboard moved in front of a fixed camera, (11.3.8).

    The corners of each view (OpenCV pixels, as :func:`find_chessboard` returns them) are turned
    into image coordinates in pixels (y up, origin at the image centre, :func:`pixels_to_image`);
    the start values come from :func:`planar_start_values`, and :func:`self_calibration` adjusts the
    common interior orientation and every view's orientation. f, x₀, y₀ and the distortion are in
    pixels (k₁ in px⁻², …); :func:`photolib.conventions.camera_matrix_pixels` and
    :func:`photolib.conventions.brown_to_opencv` (pixel size 1) turn them into OpenCV's K and
    distCoeffs.

    Parameters
    ----------
    corners : list of (cols·rows, 2) arrays
        Corners of each view in pixels, row by row.
    pattern_size : (int, int)
        (columns, rows) of inner corners.
    square_size : float
        Side of a square (the unit of the views' positions).
    shape : (int, int)
        (rows, cols) of the images.
    calibrate : sequence of str
        Interior elements to estimate.
    f0 : float, optional
        Approximate focal length in pixels (else from the homographies).

    Returns
    -------
    CalibrationResult

    Raises
    ------
    InputError
        Wrong shapes, fewer than 3 views, corners not matching the pattern.
    DegenerateGeometryError
        Views that cannot separate the unknowns (e.g. all frontal).

    References
    ----------
    Chibunichev (2022), §11.3, eq. (11.3.8), Fig. 11.28.

    Examples
    --------
    >>> import numpy as np
    >>> from photolib.camera import InteriorOrientation
    >>> from photolib.single_image import project
    >>> from photolib.rotation import rotation_matrix
    >>> board = np.mgrid[0:6, 0:5].T.reshape(-1, 2) * 1.0
    >>> io = InteriorOrientation(500.0, 3.0, -2.0, k1=-1e-7)
    >>> views = []
    >>> for w, a in [(0.5, 0.0), (-0.5, 0.1), (0.1, 0.5), (0.0, -0.5)]:
    ...     eo = ExteriorOrientation(2.5 + 8 * np.sin(a), 2.0 - 8 * np.sin(w), 8.0, w, a, 0.0)
    ...     xy = project(np.column_stack([board, np.zeros(30)]), eo, io)
    ...     views.append(image_to_pixels(xy, (480, 640)))
    >>> r = calibrate_chessboard(views, (6, 5), 1.0, (480, 640), calibrate=("f", "x0", "y0", "k1"))
    >>> round(r.io.f, 4), round(r.io.x0, 4), round(r.io.y0, 4), round(r.rms, 8)
    (500.0, 3.0, -2.0, 0.0)
    """
    cols_p, rows_p = (int(v) for v in pattern_size)
    s = _positive(square_size, "square_size")
    if isinstance(corners, np.ndarray) and corners.ndim == 2:
        corners = [corners]
    views = [pixels_to_image(as_points(c, 2, f"corners of view {i}"), shape) for i, c in enumerate(corners)]
    if len(views) < 3:
        raise InputError(f"{len(views)} views: the chessboard method needs at least 3 (tilted) views")
    for i, v in enumerate(views):
        if len(v) != cols_p * rows_p:
            raise InputError(f"view {i}: {len(v)} corners for a {cols_p}×{rows_p} pattern")
    board = np.array([(j * s, -i * s) for i in range(rows_p) for j in range(cols_p)], dtype=float)
    f, eos = planar_start_values(board, views, f0=f0)
    XYZ = np.column_stack([board, np.zeros(len(board))])
    return self_calibration(XYZ, views, InteriorOrientation(f), eos, calibrate=calibrate)
