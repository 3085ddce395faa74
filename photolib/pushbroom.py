"""Scanner sensor models — Chapter 8, §8.1–8.5, §8.7, §8.8 (cases 1–3) and the line EO table of §8.15.

Frames and conventions (the book's, made explicit):

* **Scanner frame** S x y z (§8.2, Fig. 8.5): origin at the projection centre, **x along the
  flight** (the along-track direction of the image lines), **y along the CCD line**, z completing a
  right-handed system (up for a nadir view). A ray of pixel ``col`` is (8.2.1)/(8.2.2)
  r = (x_i − x₀, y_c − y₀, −f)/|r_m|, with y_c = (col − (n_columns − 1)/2)·pixel_size (origin in
  the middle of the line, Fig. 8.7) and x_i the along-track offset of the CCD line (or of the
  staggered matrix that images the column; 0 for a single linear CCD).
* **Image pixel coordinates** (row, col) have (0, 0) at the **centre of the first pixel** (as
  :mod:`photolib.rpc`); a row is one scanner line, imaged at Δt = row·line_period after the first
  line (8.5.4), so the book's x_c (the line) is the row and y_c follows from the column.
* **Exterior orientation** as polynomials in time (8.5.3)/(8.5.5). The parameter vector is fixed as
  (X_S0, Y_S0, Z_S0, ω0, α0, κ0, k₁…k₆[, d₁…d₆]) — the order of (8.5.3); the book lists the angles
  as (α, ω, κ) in (8.8.6), which is only the order of the list. A = A_ω A_α A_κ of (1.3.2)
  (``rotation_matrix(..., order="wak")``) maps the scanner frame to the object frame. Angles in
  radians, rates per second, times in seconds. Or, as measured by GNSS/IMU or adjusted by (8.15.2),
  a **table of line EO** (:class:`EOTable`), interpolated linearly between lines; both feed the
  one sensor type :class:`Pushbroom` (:class:`photolib.georef.TabulatedLineScanner` wraps it).

Contents: rays (8.2.1)/(8.2.2), staggered layouts (Fig. 8.4), whiskbroom (8.3.1), three-line
cameras (8.4.2)/(8.4.3), tilted focal lengths (8.4.1); :class:`EOPolynomial` and the per-line
table :class:`EOTable` (GNSS/IMU, §8.15); :class:`Pushbroom`
(image → ground at Z (8.5.1)/(8.7.1), ground → image by a Newton search for the line (8.5.2),
monoplotting over a DEM (8.7.1), a projector for orthorectification); the time-polynomial
resection on GCPs (8.5.2)–(8.5.5) with the flat-terrain ambiguity of Fig. 8.14; the approximating
DLT (8.5.10), affine (8.5.11) and parallel-perspective (8.5.12) models; stereo: the rigorous
intersection (8.8.1) and the first-line orientation of a pair from coplanarity and collinearity
with known EO increments (8.8.2)–(8.8.7). Least squares through :mod:`photolib.lsq`; Jacobians
from :mod:`photolib.derivations.scanner`.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Callable

import numpy as np

from .errors import ConvergenceError, DegenerateGeometryError, InputError, PointBehindCameraError
from .lsq import Adjustment, gauss_newton, solve_normal_equations
from .rotation import rotation_matrix

__all__ = ["EO_NAMES", "ray_linear_ccd", "staggered_offsets", "ray_whiskbroom", "ray_three_line",
           "tilted_focal_length", "line_field_of_view", "EOPolynomial", "EOTable", "Pushbroom", "PushbroomResection", "resect_pushbroom",
           "resection_condition", "ApproximateModel", "fit_approximate_model", "fit_dlt", "fit_affine",
           "fit_parallel_perspective", "intersect_scanner_rays", "intersect_pushbroom", "first_line_rays",
           "PairOrientation", "orient_pushbroom_pair"]

EO_NAMES = ("X_S0", "Y_S0", "Z_S0", "omega0", "alpha0", "kappa0", "k1", "k2", "k3", "k4", "k5", "k6",
            "d1", "d2", "d3", "d4", "d5", "d6")
"""Names of the time-polynomial EO parameters, in the library's order (8.5.3)/(8.5.5)."""

_FLAT_COND = 1e9          # condition number (columns scaled to unit norm) taken as singular


# --------------------------------------------------------------------------- validation helpers
def _floats(value, name, *, ndim=None) -> np.ndarray:
    if isinstance(value, (str, bytes)) or value is None:
        raise InputError(f"{name} must be numbers, got {type(value).__name__}")
    try:
        arr = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise InputError(f"{name} must be numbers") from None
    if ndim is not None and arr.ndim != ndim:
        raise InputError(f"{name} must have {ndim} dimension(s), got shape {arr.shape}")
    if not np.all(np.isfinite(arr)):
        raise InputError(f"{name} contains NaN or inf")
    return arr


def _numbers(value, name) -> np.ndarray:
    """Numbers, NaN allowed (it marks missing values), inf not."""
    if isinstance(value, (str, bytes)) or value is None:
        raise InputError(f"{name} must be numbers, got {type(value).__name__}")
    try:
        arr = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise InputError(f"{name} must be numbers") from None
    if np.any(np.isinf(arr)):
        raise InputError(f"{name} contains inf")
    return arr


def _positive(value, name) -> float:
    arr = _floats(value, name)
    if arr.ndim != 0 or arr <= 0:
        raise InputError(f"{name} must be one positive number, got {value!r}")
    return float(arr)


def _same(*arrays, names):
    try:
        out = np.broadcast_arrays(*arrays)
    except ValueError:
        raise InputError(f"{', '.join(names)} have shapes {[np.shape(a) for a in arrays]} that do not match") from None
    return [np.array(a, dtype=float).ravel() for a in out], out[0].shape


def _points3(XYZ, name="object points") -> np.ndarray:
    arr = _floats(XYZ, name)
    if arr.ndim == 1 and arr.shape == (3,):
        arr = arr[None]
    if arr.ndim != 2 or arr.shape[1] != 3:
        raise InputError(f"{name} must be an (n, 3) array, got shape {arr.shape}")
    if arr.shape[0] == 0:
        raise InputError(f"{name}: no points")
    return arr


# --------------------------------------------------------------------------- rays §8.2–8.4
def ray_linear_ccd(y_c, f, x_i=0.0, x0=0.0, y0=0.0) -> np.ndarray:
    """Unit ray of an opto-electronic scanner pixel in the scanner frame, (8.2.1)/(8.2.2).

    r = (x_i − x₀, y_c − y₀, −f)/|r_m|, |r_m| = √((x_i − x₀)² + (y_c − y₀)² + f²). The printed
    (8.2.1) has x_c in the first component; the line coordinate x_c only selects the line (time),
    the ray uses the CCD offset x_i, as (8.2.2) and the text say.

    Parameters
    ----------
    y_c : float or array
        Coordinate along the CCD line (same unit as ``f``), origin in the middle of the line.
    f : float
        Focal length.
    x_i : float or array
        Along-track offset of the CCD line or staggered matrix (0 for a single linear CCD).
    x0, y0 : float
        Principal point in the scanner frame.

    Returns
    -------
    ndarray (..., 3)
        Unit vectors (x, y, z).

    Raises
    ------
    InputError
        NaN/inf, non-positive ``f``, shapes that do not broadcast.

    References
    ----------
    Chibunichev (2022), §8.2, eqs. (8.2.1)–(8.2.2).

    Examples
    --------
    >>> ray_linear_ccd(0.03, 4.0, x_i=0.0).round(6)
    array([ 0.      ,  0.0075  , -0.999972])
    """
    f = _positive(f, "f")
    y_c, x_i = _floats(y_c, "y_c"), _floats(x_i, "x_i")
    x0, y0 = float(_floats(x0, "x0")), float(_floats(y0, "y0"))
    try:
        a, b = np.broadcast_arrays(x_i - x0, y_c - y0)
    except ValueError:
        raise InputError(f"y_c {y_c.shape} and x_i {x_i.shape} do not broadcast") from None
    r = np.stack([a, b, np.full(a.shape, -f)], axis=-1)
    return r / np.linalg.norm(r, axis=-1, keepdims=True)


def staggered_offsets(matrix_columns, offsets) -> np.ndarray:
    """Per-column along-track offsets x_i of a staggered focal plane (Fig. 8.4, (8.2.1)).

    The image line is assembled from matrices laid out along the line; matrix i contributes
    ``matrix_columns[i]`` columns and sits at the along-track offset ``offsets[i]`` (even and odd
    matrices alternate, e.g. +d and −d).

    Parameters
    ----------
    matrix_columns : sequence of int
        Columns each matrix contributes to the image line, in order along the line.
    offsets : sequence of float
        The calibrated offset x_i of each matrix (same unit as the focal length).

    Returns
    -------
    ndarray (sum(matrix_columns),)
        x_i of every image column.

    Raises
    ------
    InputError
        Different lengths, no matrix, a non-positive or non-integer column count, NaN/inf.

    References
    ----------
    Chibunichev (2022), §8.2, eqs. (8.2.1)–(8.2.2), Fig. 8.4; §8.17.

    Examples
    --------
    >>> staggered_offsets([2, 3, 2], [0.01, -0.01, 0.01])
    array([ 0.01,  0.01, -0.01, -0.01, -0.01,  0.01,  0.01])
    """
    cols = _floats(matrix_columns, "matrix_columns", ndim=1)
    off = _floats(offsets, "offsets", ndim=1)
    if cols.size == 0 or cols.size != off.size:
        raise InputError(f"matrix_columns ({cols.size}) and offsets ({off.size}) must be non-empty and of one length")
    if np.any(cols < 1) or np.any(cols != np.round(cols)):
        raise InputError("matrix_columns must be positive integers")
    return np.repeat(off, cols.astype(int))


def ray_whiskbroom(y_m, theta, l_y) -> np.ndarray:
    """Unit ray of an opto-mechanical (whiskbroom) scanner, (8.3.1).

    r = (0, sin φ, −cos φ), φ = θ·y_m/l_y; x is the mirror rotation axis (along-track).

    Parameters
    ----------
    y_m : float or array
        Pixel coordinate from the middle of the line (pixels), |y_m| ≤ l_y/2.
    theta : float
        Total field-of-view angle (radians), below π.
    l_y : float
        Line length in pixels.

    Returns
    -------
    ndarray (..., 3)
        Unit vectors.

    Raises
    ------
    InputError
        NaN/inf, non-positive θ or l_y, θ ≥ π, a pixel outside the line.

    References
    ----------
    Chibunichev (2022), §8.3, eq. (8.3.1).

    Examples
    --------
    >>> ray_whiskbroom(500.0, 1.2, 1000).round(6)          # the line end: φ = θ/2
    array([ 0.      ,  0.564642, -0.825336])
    """
    theta, l_y = _positive(theta, "theta"), _positive(l_y, "l_y")
    if theta >= np.pi:
        raise InputError(f"theta = {theta} rad: a field of view of π or more is not a scanner line")
    y_m = _floats(y_m, "y_m")
    if np.any(np.abs(y_m) > l_y / 2 + 1e-9):
        raise InputError(f"y_m must lie within ±l_y/2 = ±{l_y / 2}")
    phi = theta * y_m / l_y
    return np.stack([np.zeros_like(phi), np.sin(phi), -np.cos(phi)], axis=-1)


def ray_three_line(y_c, f, line, x_forward, x_backward, x0=0.0, y0=0.0) -> np.ndarray:
    """Unit ray of one CCD line of a three-line camera, (8.4.2)/(8.4.3) (nadir line: (8.2.2)).

    Parameters
    ----------
    y_c : float or array
        Coordinate along the CCD line.
    f : float
        Focal length.
    line : {"forward", "nadir", "backward"}
        Which line (П, nadir, Н of Fig. 8.13).
    x_forward, x_backward : float
        Calibrated along-track offsets x_П, x_Н of the forward and backward lines.
    x0, y0 : float
        Principal point.

    Returns
    -------
    ndarray (..., 3)
        Unit vectors.

    Raises
    ------
    InputError
        An unknown line name, NaN/inf, non-positive ``f``.

    References
    ----------
    Chibunichev (2022), §8.4, eqs. (8.4.2)–(8.4.3), Fig. 8.13.

    Examples
    --------
    >>> ray_three_line(0.0, 1.0, "forward", 0.5, -0.5).round(6)
    array([ 0.447214,  0.      , -0.894427])
    """
    offsets = {"forward": x_forward, "nadir": 0.0, "backward": x_backward}
    if not isinstance(line, str) or line not in offsets:
        raise InputError(f"line must be 'forward', 'nadir' or 'backward', got {line!r}")
    _floats(x_forward, "x_forward"), _floats(x_backward, "x_backward")
    return ray_linear_ccd(y_c, f, offsets[line], x0, y0)


def tilted_focal_length(f0, alpha):
    """Focal length of a camera tilted by α that keeps the nadir camera's scale, (8.4.1).

    1/m = f₀/D₀ and D = D₀/cos α, hence f = f₀/cos α (both the forward and the backward camera).

    Parameters
    ----------
    f0 : float or array
        Focal length of the nadir camera.
    alpha : float or array
        Tilt angle (radians), |α| < π/2.

    Returns
    -------
    float or ndarray
        f₀/cos α.

    Raises
    ------
    InputError
        NaN/inf, non-positive f₀, |α| ≥ π/2.

    References
    ----------
    Chibunichev (2022), §8.4, eq. (8.4.1), Fig. 8.12.

    Examples
    --------
    >>> round(tilted_focal_length(1.0, np.pi / 3), 12)
    2.0
    """
    f0, alpha = _floats(f0, "f0"), _floats(alpha, "alpha")
    if np.any(f0 <= 0):
        raise InputError("f0 must be positive")
    if np.any(np.abs(alpha) >= np.pi / 2):
        raise InputError("|alpha| must be below π/2 (radians)")
    out = f0 / np.cos(alpha)
    return float(out) if out.ndim == 0 else out


def line_field_of_view(n_pixels, pixel_size, f):
    """Field of view across the track of a linear CCD of ``n_pixels`` centred on the principal point.

    The line is n·p long; its ends are seen at ±atan(n·p / 2f) from the optical axis (the ray
    (8.2.2) of the first and the last pixel), so the full angle is Θ = 2·atan(n·p / 2f).

    Parameters
    ----------
    n_pixels : int or float
        Pixels in the line (> 0).
    pixel_size : float
        Pixel pitch, in the unit of ``f`` (> 0).
    f : float
        Focal length (camera constant), > 0.

    Returns
    -------
    float
        Θ in radians.

    Raises
    ------
    InputError
        NaN/inf or non-positive values.

    References
    ----------
    Chibunichev (2022), §8.2, eq. (8.2.2); Hanzl, Fotogrammetrie, Modul 01, §12.1–§12.2 (seed 002
    lines 1886–1912: the ADS40 and STARIMAGER lines, whose "46°" the text's own numbers do not give).

    Examples
    --------
    >>> round(float(np.degrees(line_field_of_view(12000, 0.0065, 62.5))), 1)   # ADS40
    63.9
    """
    n, p, f = (_positive(v, name) for v, name in ((n_pixels, "n_pixels"), (pixel_size, "pixel_size"), (f, "f")))
    return float(2.0 * np.arctan(n * p / (2.0 * f)))


# --------------------------------------------------------------------------- EO in time §8.5
@dataclass(frozen=True, eq=False)
class EOPolynomial:
    """Exterior orientation of a scanner as polynomials in time, (8.5.3)–(8.5.5).

    E(Δt) = E₀ + k·Δt [+ d·Δt²] for E = (X_S, Y_S, Z_S, ω, α, κ), Δt = t − t₀ (8.5.4).

    Parameters
    ----------
    eo0 : array_like (6,)
        X_S0, Y_S0, Z_S0 (m), ω0, α0, κ0 (rad) at the first line.
    k : array_like (6,)
        Rates k₁…k₆ (m/s, rad/s).
    d : array_like (6,), optional
        Accelerations d₁…d₆ (m/s², rad/s²) of the quadratic model (8.5.5); None for the linear model.

    Raises
    ------
    InputError
        Wrong lengths, NaN/inf.

    References
    ----------
    Chibunichev (2022), §8.5, eqs. (8.5.3)–(8.5.5); §1.3, eq. (1.3.2).

    Examples
    --------
    >>> eo = EOPolynomial([0, 0, 475e3, 0, 0, 0], [7000, 0, 0, 0, 0, 0])
    >>> S, A = eo.at([0.0, 2.0])
    >>> S[1].tolist(), eo.vector().size
    ([14000.0, 0.0, 475000.0], 12)
    """

    eo0: np.ndarray
    k: np.ndarray
    d: np.ndarray | None = None

    def __post_init__(self):
        for name in ("eo0", "k") + (("d",) if self.d is not None else ()):
            arr = _floats(getattr(self, name), name, ndim=1)
            if arr.shape != (6,):
                raise InputError(f"{name} must have 6 elements (X_S, Y_S, Z_S, ω, α, κ), got {arr.shape}")
            object.__setattr__(self, name, arr)

    @property
    def degree(self) -> int:
        """1 for the linear model (8.5.3), 2 for the quadratic one (8.5.5)."""
        return 1 if self.d is None else 2

    def vector(self) -> np.ndarray:
        """The parameter vector (X_S0 … κ0, k₁ … k₆[, d₁ … d₆]) — the order of :data:`EO_NAMES`."""
        return np.concatenate([self.eo0, self.k] + ([self.d] if self.d is not None else []))

    @classmethod
    def from_vector(cls, vector) -> "EOPolynomial":
        """The inverse of :meth:`vector` (12 elements: linear, 18: quadratic)."""
        v = _floats(vector, "EO vector", ndim=1)
        if v.size not in (12, 18):
            raise InputError(f"an EO vector has 12 (linear) or 18 (quadratic) elements, got {v.size}")
        return cls(v[:6], v[6:12], v[12:] if v.size == 18 else None)

    def elements(self, dt) -> np.ndarray:
        """The six elements at times Δt, shape (n, 6)."""
        dt = _floats(dt, "dt").ravel()[:, None]
        e = self.eo0 + self.k * dt
        if self.d is not None:
            e = e + self.d * dt ** 2
        return e

    def at(self, dt):
        """(S, A) at times Δt: centres (n, 3) and matrices A = A_ω A_α A_κ (n, 3, 3)."""
        e = self.elements(dt)
        return e[:, :3], rotation_matrix(e[:, 3], e[:, 4], e[:, 5], order="wak")


@dataclass(frozen=True, eq=False)
class EOTable:
    """Exterior orientation of a scanner tabulated line by line (GNSS/IMU, or the result of (8.15.2)).

    Line i of the table is the EO at Δt = i·line_period (8.5.4); between lines every element —
    the angles included — is interpolated linearly (as (8.15.2) interpolates between fixed
    centres), and the rotation matrix is built from the interpolated angles. **Outside the table**
    (Δt < 0 or Δt > (n_lines − 1)·line_period) the first or last segment is extrapolated
    linearly (``extrapolate=True``, so that a Newton line search may step past the ends), or an
    InputError is raised (``extrapolate=False``). :meth:`Pushbroom.project` with ``bracket=True``
    never leaves the table: points no tabulated line sees get NaN.

    Parameters
    ----------
    table : array_like (n_lines, 6)
        (X_S, Y_S, Z_S, ω, α, κ) of every line (m, rad), n_lines ≥ 2.
    line_period : float
        Time between table lines (s).
    order : {"wak", "kaw"}
        Rotation sequence of the table's angles: A = A_ω A_α A_κ (1.3.2) or A_κ A_α A_ω (1.3.4).
    extrapolate : bool
        Extrapolate linearly outside the table (True) or raise InputError (False).

    Raises
    ------
    InputError
        Fewer than 2 lines, a table that is not (n, 6), NaN/inf, a non-positive period, an
        unknown order.

    References
    ----------
    Chibunichev (2022), §8.5, eq. (8.5.4); §8.15, eq. (8.15.2); §1.3, eqs. (1.3.2), (1.3.4).

    Examples
    --------
    >>> eo = EOTable([[0, 0, 1000, 0, 0, 0], [10, 0, 1000, 0, 0, 0.02]], line_period=0.1)
    >>> eo.elements([0.05, 0.2]).round(6).tolist()
    [[5.0, 0.0, 1000.0, 0.0, 0.0, 0.01], [20.0, 0.0, 1000.0, 0.0, 0.0, 0.04]]
    """

    table: np.ndarray
    line_period: float = 1.0
    order: str = "wak"
    extrapolate: bool = True

    def __post_init__(self):
        t = _floats(self.table, "EO table", ndim=2)
        if t.shape[1] != 6:
            raise InputError(f"the EO table must be (n_lines, 6) (X_S, Y_S, Z_S, ω, α, κ), got shape {t.shape}")
        if len(t) < 2:
            raise InputError(f"an EO table needs at least 2 lines to interpolate, got {len(t)}")
        object.__setattr__(self, "table", t)
        object.__setattr__(self, "line_period", _positive(self.line_period, "line_period"))
        if self.order not in ("wak", "kaw"):
            raise InputError(f"order must be 'wak' (1.3.2) or 'kaw' (1.3.4), got {self.order!r}")
        if not isinstance(self.extrapolate, (bool, np.bool_)):
            raise InputError(f"extrapolate must be True or False, got {self.extrapolate!r}")

    def __repr__(self) -> str:
        return (f"EOTable(<{self.n_lines} lines>, line_period={self.line_period!r}, order={self.order!r}, "
                f"extrapolate={self.extrapolate!r})")

    @property
    def n_lines(self) -> int:
        """Number of tabulated lines."""
        return len(self.table)

    def elements(self, dt) -> np.ndarray:
        """The six elements at times Δt (linear between lines), shape (n, 6)."""
        line = _floats(dt, "dt").ravel() / self.line_period
        last = self.n_lines - 1
        if not self.extrapolate and np.any((line < -1e-9) | (line > last + 1e-9)):
            raise InputError(f"times outside the EO table (lines 0…{last}) and extrapolate=False")
        i = np.clip(np.floor(line), 0, last - 1).astype(np.int64)
        w = (line - i)[:, None]
        return (1 - w) * self.table[i] + w * self.table[i + 1]

    def at(self, dt):
        """(S, A) at times Δt: centres (n, 3) and matrices A (n, 3, 3) in the table's ``order``."""
        e = self.elements(dt)
        return e[:, :3], rotation_matrix(e[:, 3], e[:, 4], e[:, 5], order=self.order)


# --------------------------------------------------------------------------- the sensor
@dataclass(frozen=True, eq=False)
class Pushbroom:
    """A pushbroom (linear-CCD, optionally staggered) scanner with EO in time, §8.2, §8.5, §8.15–8.16.

    The EO is either polynomials in time (:class:`EOPolynomial`, (8.5.3)/(8.5.5)) or a per-line
    table (:class:`EOTable`, GNSS/IMU or the result of (8.15.2)); the geometry is the same.

    Parameters
    ----------
    focal_length : float
        f (m).
    pixel_size : float
        CCD pixel size (m).
    n_columns : int
        Pixels per image line.
    line_period : float
        Time between lines (s); Δt = row·line_period (8.5.4).
    eo : EOPolynomial or EOTable
        The exterior orientation (8.5.3)/(8.5.5), or a table of line EO (its line i is row i only
        when its ``line_period`` equals the sensor's).
    x0, y0 : float
        Principal point in the scanner frame (m).
    x_offsets : float or array_like (n_columns,)
        Along-track offset x_i of the CCD (one value) or of the matrix imaging each column
        (:func:`staggered_offsets`), (8.2.1).
    n_rows : int, optional
        Number of lines (the start of the line search and the span of the bracketed search); with
        an :class:`EOTable` whose line period is the sensor's, default and maximum: the table's lines.

    Raises
    ------
    InputError
        Non-positive sizes, NaN/inf, an ``eo`` that is neither an :class:`EOPolynomial` nor an
        :class:`EOTable`, offsets of the wrong length, more rows than a table has lines.

    References
    ----------
    Chibunichev (2022), §8.2, eqs. (8.2.1)–(8.2.2); §8.5, eqs. (8.5.1)–(8.5.5); §8.7, eq. (8.7.1).

    Examples
    --------
    >>> eo = EOPolynomial([0, 0, 475e3, 0, 0, 0], [7000, 0, 0, 0, 0, 0])
    >>> cam = Pushbroom(3.8, 8e-6, 1001, 1 / 7000, eo)
    >>> X, Y = cam.ground([100.0], [600.0], 0.0)
    >>> [round(float(v), 6) for v in (X[0], Y[0])]
    [100.0, 100.0]
    >>> [round(float(v[0]), 9) for v in cam.project(X, Y, 0.0)]
    [100.0, 600.0]
    """

    focal_length: float
    pixel_size: float
    n_columns: int
    line_period: float
    eo: EOPolynomial | EOTable
    x0: float = 0.0
    y0: float = 0.0
    x_offsets: float | np.ndarray = 0.0
    n_rows: int | None = None

    def __post_init__(self):
        for name in ("focal_length", "pixel_size", "line_period"):
            object.__setattr__(self, name, _positive(getattr(self, name), name))
        n = _positive(self.n_columns, "n_columns")
        if n != int(n):
            raise InputError(f"n_columns must be an integer, got {self.n_columns!r}")
        object.__setattr__(self, "n_columns", int(n))
        if self.n_rows is not None:
            r = _positive(self.n_rows, "n_rows")
            object.__setattr__(self, "n_rows", int(r))
        if not isinstance(self.eo, (EOPolynomial, EOTable)):
            raise InputError(f"eo must be an EOPolynomial or an EOTable, got {type(self.eo).__name__}")
        if isinstance(self.eo, EOTable) and self.eo.line_period == self.line_period:
            if self.n_rows is None:
                object.__setattr__(self, "n_rows", self.eo.n_lines)
            elif self.n_rows > self.eo.n_lines:
                raise InputError(f"n_rows = {self.n_rows} but the EO table has {self.eo.n_lines} lines")
        for name in ("x0", "y0"):
            v = _floats(getattr(self, name), name)
            if v.ndim:
                raise InputError(f"{name} must be one number")
            object.__setattr__(self, name, float(v))
        off = _floats(self.x_offsets, "x_offsets")
        if off.ndim not in (0, 1) or (off.ndim == 1 and off.size != self.n_columns):
            raise InputError(f"x_offsets must be one number or one per column ({self.n_columns}), got shape {off.shape}")
        object.__setattr__(self, "x_offsets", off)

    # -- image geometry
    def with_eo(self, eo) -> "Pushbroom":
        """The same sensor with another exterior orientation."""
        return Pushbroom(self.focal_length, self.pixel_size, self.n_columns, self.line_period, eo,
                         self.x0, self.y0, self.x_offsets, self.n_rows)

    def y_c(self, cols) -> np.ndarray:
        """Coordinate along the CCD line y_c (m) of image columns (origin in the middle, Fig. 8.7)."""
        return (np.asarray(cols, dtype=float) - (self.n_columns - 1) / 2.0) * self.pixel_size

    def offset_of(self, cols) -> np.ndarray:
        """Along-track offset x_i of the matrix imaging each column (8.2.1)."""
        cols = np.asarray(cols, dtype=float)
        if self.x_offsets.ndim == 0:
            return np.full(cols.shape, float(self.x_offsets))
        idx = np.clip(np.floor(cols + 0.5).astype(int), 0, self.n_columns - 1)
        return self.x_offsets[idx]

    def rays(self, cols) -> np.ndarray:
        """Unit rays (8.2.2) of image columns in the scanner frame, shape (n, 3)."""
        cols = _floats(cols, "cols").ravel()
        return ray_linear_ccd(self.y_c(cols), self.focal_length, self.offset_of(cols), self.x0, self.y0)

    def object_rays(self, rows, cols):
        """Projection centres S (n, 3) and object-frame rays A·r (n, 3) of image points (8.5.1)."""
        (rows, cols), _ = _same(_floats(rows, "rows"), _floats(cols, "cols"), names=("rows", "cols"))
        S, A = self.eo.at(rows * self.line_period)
        return S, np.einsum("nij,nj->ni", A, self.rays(cols))

    def ground(self, rows, cols, Z, *, invalid: str = "raise"):
        """Image → ground on the height Z, (8.5.1)/(8.7.1).

        X = X_Si + (Z − Z_Si)X′/Z′, Y = Y_Si + (Z − Z_Si)Y′/Z′, (X′, Y′, Z′)ᵀ = A_i·r.

        Parameters
        ----------
        rows, cols : array_like
            Image pixel coordinates (broadcast together with Z).
        Z : float or array_like
            Height of each point.
        invalid : {"raise", "nan"}
            ``"raise"``: errors below; ``"nan"`` (for DEM iterations such as §8.16's): NaN inputs
            propagate and rays that do not reach the plane (parallel or behind) give NaN.

        Returns
        -------
        X, Y : ndarray
            Ground coordinates, in the broadcast shape of the inputs.

        Raises
        ------
        InputError
            NaN/inf (with ``invalid="raise"``), shapes that do not broadcast, an unknown ``invalid``.
        DegenerateGeometryError
            A ray parallel to the plane Z = const.
        PointBehindCameraError
            The plane lies behind the sensor (above it for a nadir view).

        References
        ----------
        Chibunichev (2022), §8.5, eq. (8.5.1); §8.7, eq. (8.7.1).

        Examples
        --------
        >>> eo = EOPolynomial([0, 0, 1000, 0, 0, 0], [100, 0, 0, 0, 0, 0])
        >>> cam = Pushbroom(0.1, 1e-5, 101, 0.01, eo)
        >>> [round(float(v), 9) for v in cam.ground(0.0, 60.0, 0.0)]
        [0.0, 1.0]
        """
        if invalid == "nan":
            (rows, cols, Z), shape = _same(*(_numbers(v, n) for v, n in ((rows, "rows"), (cols, "cols"), (Z, "Z"))),
                                           names=("rows", "cols", "Z"))
            X, Y = np.full(rows.shape, np.nan), np.full(rows.shape, np.nan)
            ok = np.isfinite(rows) & np.isfinite(cols)
            S, R = self.object_rays(rows[ok], cols[ok])
            with np.errstate(divide="ignore", invalid="ignore"):
                lam = (Z[ok] - S[:, 2]) / R[:, 2]
            lam = np.where(lam > 0, lam, np.nan)           # behind, parallel or NaN height
            X[ok], Y[ok] = S[:, 0] + lam * R[:, 0], S[:, 1] + lam * R[:, 1]
            return X.reshape(shape), Y.reshape(shape)
        if invalid != "raise":
            raise InputError(f"invalid must be 'raise' or 'nan', got {invalid!r}")
        (rows, cols, Z), shape = _same(_floats(rows, "rows"), _floats(cols, "cols"), _floats(Z, "Z"),
                                       names=("rows", "cols", "Z"))
        S, R = self.object_rays(rows, cols)
        if np.any(np.abs(R[:, 2]) < 1e-12):
            raise DegenerateGeometryError("a ray is parallel to the plane Z = const: no ground point")
        lam = (Z - S[:, 2]) / R[:, 2]
        if np.any(lam <= 0):
            bad = np.flatnonzero(lam <= 0)
            raise PointBehindCameraError(f"the plane Z lies behind the sensor for points {bad[:10].tolist()}", bad)
        return (S[:, 0] + lam * R[:, 0]).reshape(shape), (S[:, 1] + lam * R[:, 1]).reshape(shape)

    def _along_track(self, P, rows, xi):
        """g(row) = f·X* + (x_i − x₀)·Z*: zero when the point lies in the plane of the CCD line."""
        S, A = self.eo.at(rows * self.line_period)
        v = np.einsum("nji,nj->ni", A, P - S)          # (X*, Y*, Z*) = Aᵀ(P − S), (8.5.2)
        return self.focal_length * v[:, 0] + (xi - self.x0) * v[:, 2], v

    def project(self, X, Y, Z, rows0=None, tol: float = 1e-9, max_iter: int = 50, *, bracket: bool = False):
        """Ground → image, (8.5.2): a Newton search for the line whose plane contains the point.

        For a point P the line (time) is the root of g(row) = f·X* + (x_i − x₀)·Z* with
        (X*, Y*, Z*)ᵀ = A(t)ᵀ(P − S(t)), i.e. x = z·X*/Z* of (8.5.2) for the CCD's x; then
        y_c = y₀ − f·Y*/Z* gives the column. With staggered matrices the search is made with the
        offset x_i of each matrix in turn and the first solution whose column belongs to that
        matrix is kept; a point that falls in a gap between matrices (no consistent solution: the
        yaw moved it across the matrix boundary) gets NaN — it is not imaged. A point imaged twice
        (double coverage at a boundary) gets the solution of the matrix with the smaller offset.

        With ``bracket=True`` the search stays within the image lines 0 … n_rows − 1: the root is
        bracketed on a coarse scan of 17 lines and refined by Newton steps safeguarded by
        bisection. Points that no line of the span sees, points behind the sensor and NaN inputs
        then get NaN instead of an error (what orthorectification and voxel matching want; the
        natural search for an :class:`EOTable`).

        Parameters
        ----------
        X, Y, Z : array_like
            Ground coordinates (broadcast together).
        rows0 : float or array_like, optional
            Start of the line search (default: the middle of the image, or row 0).
        tol : float
            Convergence of the line (rows).
        max_iter : int
            Newton steps allowed.
        bracket : bool
            Bracketed search within rows 0 … n_rows − 1, NaN for points not imaged (needs ``n_rows``).

        Returns
        -------
        rows, cols : ndarray
            Image pixel coordinates ((0, 0) = centre of the first pixel); NaN for points in a gap
            of a staggered focal plane (and, with ``bracket=True``, for points not imaged).

        Raises
        ------
        InputError
            NaN/inf (without ``bracket``), shapes that do not broadcast, ``bracket`` without ``n_rows``.
        ConvergenceError
            The line search did not converge.
        PointBehindCameraError
            A point behind the sensor (Z* ≥ 0).

        References
        ----------
        Chibunichev (2022), §8.5, eq. (8.5.2).

        Examples
        --------
        >>> eo = EOPolynomial([0, 0, 1000, 0.01, -0.02, 0.1], [100, 1, 0, 1e-3, 0, 0])
        >>> cam = Pushbroom(0.1, 1e-5, 1001, 0.01, eo)
        >>> X, Y = cam.ground([250.0], [700.0], 20.0)
        >>> [round(float(v[0]), 9) for v in cam.project(X, Y, 20.0)]
        [250.0, 700.0]
        """
        if bracket:
            if self.n_rows is None or self.n_rows < 2:
                raise InputError("the bracketed line search needs n_rows ≥ 2 (the span of the image lines)")
            (X, Y, Z), shape = _same(_numbers(X, "X"), _numbers(Y, "Y"), _numbers(Z, "Z"), names=("X", "Y", "Z"))
        else:
            (X, Y, Z), shape = _same(_floats(X, "X"), _floats(Y, "Y"), _floats(Z, "Z"), names=("X", "Y", "Z"))
        P = np.column_stack([X, Y, Z])
        if rows0 is None:
            start = 0.0 if self.n_rows is None else (self.n_rows - 1) / 2.0
            rows = np.full(len(P), start)
        else:
            rows = np.broadcast_to(_floats(rows0, "rows0"), X.shape).astype(float).copy()
        out_rows, out_cols = np.full(len(P), np.nan), np.full(len(P), np.nan)
        todo = np.ones(len(P), bool)
        for offset in np.unique(self.x_offsets):        # staggered: try each matrix's offset
            xi = np.full(int(todo.sum()), float(offset))
            if bracket:
                r, v, seen = self._bracketed_rows(P[todo], xi, tol, max_iter)
                seen &= v[:, 2] < 0                           # behind the sensor: not imaged
            else:
                r, v = self._newton_rows(P[todo], rows[todo], xi, tol, max_iter)
                seen = np.ones(len(r), bool)
                if np.any(v[:, 2] >= 0):
                    bad = np.flatnonzero(todo)[v[:, 2] >= 0]
                    raise PointBehindCameraError(f"points {bad[:10].tolist()} lie behind the sensor (Z* ≥ 0)", bad)
            with np.errstate(divide="ignore", invalid="ignore"):
                c = (self.y0 - self.focal_length * v[:, 1] / v[:, 2]) / self.pixel_size + (self.n_columns - 1) / 2.0
            ok = seen & ((self.offset_of(np.where(seen, c, 0.0)) == offset) if self.x_offsets.ndim else True)
            idx = np.flatnonzero(todo)[ok]
            out_rows[idx], out_cols[idx] = r[ok], c[ok]
            todo[idx] = False
            if not todo.any():
                break
        return out_rows.reshape(shape), out_cols.reshape(shape)

    def _newton_rows(self, P, rows, xi, tol, max_iter):
        h = 0.5
        step = np.full(len(P), np.inf)
        for _ in range(max_iter):
            g, v = self._along_track(P, rows, xi)
            dg = (self._along_track(P, rows + h, xi)[0] - self._along_track(P, rows - h, xi)[0]) / (2 * h)
            if np.any(dg == 0):
                raise DegenerateGeometryError("the point does not move across the scanner line plane in time "
                                              "(zero along-track rate): no imaging line")
            step = g / dg
            rows = rows - step
            if not np.all(np.isfinite(rows)):
                raise ConvergenceError("the line search diverged (NaN)")
            if np.all(np.abs(step) < tol):
                return rows, self._along_track(P, rows, xi)[1]
        if np.all(np.abs(step) < 1e-6):          # converged to rounding (the residual is noise)
            return rows, self._along_track(P, rows, xi)[1]
        raise ConvergenceError(f"the line search did not converge in {max_iter} steps "
                               f"(largest last step {np.max(np.abs(step)):.3g} rows)")

    def _bracketed_rows(self, P, xi, tol, max_iter):
        """Root of g(row) within rows 0 … n_rows − 1: sign change on 17 coarse lines, then Newton
        steps kept inside the bracket (bisection otherwise). Returns rows, (X*, Y*, Z*), found."""
        last = self.n_rows - 1
        samples = np.unique(np.linspace(0, last, min(self.n_rows, 17)).round())
        with np.errstate(invalid="ignore"):
            g = np.stack([self._along_track(P, np.full(len(P), s), xi)[0] for s in samples], axis=1)
            change = (g[:, :-1] * g[:, 1:] <= 0) & np.isfinite(g[:, :-1]) & np.isfinite(g[:, 1:])
        found = change.any(axis=1)
        j = np.argmax(change, axis=1)
        lo, hi = samples[j].astype(float), samples[j + 1].astype(float)
        glo = g[np.arange(len(P)), j]
        r = 0.5 * (lo + hi)
        h = 1e-3
        done = ~found
        step = np.zeros(len(P))
        for _ in range(max_iter):
            gr = self._along_track(P, r, xi)[0]
            same = np.sign(gr) == np.sign(glo)
            lo, glo, hi = np.where(same, r, lo), np.where(same, gr, glo), np.where(same, hi, r)
            rh = np.where(r + h <= last, r + h, r - h)        # forward difference, inside the span
            with np.errstate(divide="ignore", invalid="ignore"):
                newton = r - gr * (rh - r) / (self._along_track(P, rh, xi)[0] - gr)
            inside = np.isfinite(newton) & (newton >= lo) & (newton <= hi)
            new = np.where(inside, newton, 0.5 * (lo + hi))
            step = np.where(found, new - r, 0.0)
            r = np.where(found, new, r)
            done = np.abs(step) < tol
            if np.all(done):
                break
        if not np.all(np.abs(step) < 1e-6):
            raise ConvergenceError(f"the bracketed line search did not converge in {max_iter} steps "
                                   f"(largest last step {np.max(np.abs(step)):.3g} rows)")
        with np.errstate(invalid="ignore"):
            v = self._along_track(P, r, xi)[1]
        return r, v, found

    def monoplot(self, rows, cols, dem: Callable, z_start=None, tol: float = 1e-4, max_iter: int = 50):
        """Ground coordinates of image points over a DEM: (8.7.1) iterated on Z as in §7.7.

        Z₁ = ``z_start`` → (X₁, Y₁) by (8.7.1) → Z₂ = DEM(X₁, Y₁) → … until X, Y change by less
        than ``tol``.

        Parameters
        ----------
        rows, cols : array_like
            Image pixel coordinates.
        dem : callable
            ``dem(X, Y) -> Z`` (arrays); NaN where the DEM has no data.
        z_start : float or array_like, optional
            First height (default: the DEM under the rays' points at height 0).
        tol : float
            Convergence in X, Y (m).
        max_iter : int
            Iterations allowed.

        Returns
        -------
        X, Y, Z : ndarray
            Ground coordinates on the DEM.

        Raises
        ------
        InputError
            NaN/inf coordinates, a ``dem`` that is not callable or returns the wrong shape.
        DegenerateGeometryError
            A ray leaves the DEM (NaN height): the DEM does not cover the footprint.
        ConvergenceError
            No convergence (slopes steeper than the rays).

        References
        ----------
        Chibunichev (2022), §8.7, eq. (8.7.1); §7.7, eq. (7.7.1), Fig. 7.19.

        Examples
        --------
        >>> eo = EOPolynomial([0, 0, 1000, 0, 0, 0], [100, 0, 0, 0, 0, 0])
        >>> cam = Pushbroom(0.1, 1e-5, 1001, 0.01, eo)
        >>> X, Y, Z = cam.monoplot([10.0], [800.0], lambda X, Y: 50 + 0.1 * Y)
        >>> [round(float(v[0]), 4) for v in (X, Y, Z)]
        [10.0, 28.4148, 52.8415]
        """
        if not callable(dem):
            raise InputError("dem must be a callable dem(X, Y) -> Z")
        (rows, cols), shape = _same(_floats(rows, "rows"), _floats(cols, "cols"), names=("rows", "cols"))

        def height(X, Y):
            Zd = np.asarray(dem(X, Y), dtype=float)
            if Zd.shape != X.shape:
                raise InputError(f"dem returned shape {Zd.shape} for {X.shape} points")
            if not np.all(np.isfinite(Zd)):
                bad = np.flatnonzero(~np.isfinite(Zd))
                raise DegenerateGeometryError(f"rays of points {bad[:10].tolist()} leave the DEM (no height at "
                                              f"X, Y = {X[bad[0]]:.1f}, {Y[bad[0]]:.1f}): the DEM does not cover the footprint")
            return Zd

        if z_start is None:
            Z = height(*self.ground(rows, cols, np.zeros_like(rows)))
        else:
            Z = np.broadcast_to(_floats(z_start, "z_start"), rows.shape).astype(float).copy()
        try:
            X, Y = self.ground(rows, cols, Z)
        except PointBehindCameraError:
            raise ConvergenceError("monoplotting: the DEM height under the ray lies above the sensor "
                                   "(slopes steeper than the rays, or a wrong z_start)") from None
        for _ in range(max_iter):
            Z = height(X, Y)
            try:
                Xn, Yn = self.ground(rows, cols, Z)
            except PointBehindCameraError:
                raise ConvergenceError("monoplotting diverged: the DEM heights rose above the sensor "
                                       "(slopes steeper than the rays)") from None
            moved = np.hypot(Xn - X, Yn - Y)
            X, Y = Xn, Yn
            if np.all(moved < tol):
                return X.reshape(shape), Y.reshape(shape), height(X, Y).reshape(shape)
        raise ConvergenceError(f"monoplotting did not converge in {max_iter} iterations "
                               f"(largest last move {np.max(moved):.3g} m; slopes steeper than the rays?)")

    def projector(self, rows0=None) -> Callable:
        """A callable ``project(X, Y, Z) -> (rows, cols)`` for orthorectification engines.

        Parameters
        ----------
        rows0 : float, optional
            Start of the line search (as :meth:`project`).

        Returns
        -------
        callable
            The ground → image projection (8.5.2) of this sensor.

        References
        ----------
        Chibunichev (2022), §8.5, eq. (8.5.2); §8.16.

        Examples
        --------
        >>> eo = EOPolynomial([0, 0, 1000, 0, 0, 0], [100, 0, 0, 0, 0, 0])
        >>> proj = Pushbroom(0.1, 1e-5, 101, 0.01, eo).projector()
        >>> [round(float(v), 9) for v in proj(5.0, 1.0, 0.0)]
        [5.0, 60.0]
        """
        def project(X, Y, Z):
            return self.project(X, Y, Z, rows0=rows0)
        return project


# --------------------------------------------------------------------------- resection §8.5
def _line_model():
    from .derivations.scanner import scanner_collinearity_model
    return scanner_collinearity_model().compile()


def _resection_setup(sensor, rows, cols, XYZ, degree, fixed):
    if not isinstance(sensor, Pushbroom):
        raise InputError(f"sensor must be a Pushbroom, got {type(sensor).__name__}")
    if not isinstance(sensor.eo, EOPolynomial):
        raise InputError("the resection estimates the time-polynomial EO (8.5.3)/(8.5.5): give a sensor with an "
                         f"EOPolynomial (e.g. fitted to the table) as the approximation, not an {type(sensor.eo).__name__}")
    if isinstance(degree, bool) or degree not in (1, 2):
        raise InputError(f"degree must be 1 (linear (8.5.3)) or 2 (quadratic (8.5.5)), got {degree!r}")
    XYZ = _points3(XYZ, "GCP object coordinates")
    rows, cols = _floats(rows, "rows", ndim=1), _floats(cols, "cols", ndim=1)
    if not (len(rows) == len(cols) == len(XYZ)):
        raise InputError(f"rows ({len(rows)}), cols ({len(cols)}) and GCPs ({len(XYZ)}) differ in number")
    if isinstance(fixed, str):
        fixed = (fixed,)
    names = EO_NAMES[:12 if degree == 1 else 18]
    bad = [n for n in fixed if n not in names]
    if bad:
        raise InputError(f"unknown fixed parameters {bad}; choose from {list(names)}")
    free = [i for i, n in enumerate(names) if n not in fixed]
    n_unknown = len(free)
    need = -(-n_unknown // 2)
    if 2 * len(XYZ) < n_unknown:
        raise InputError(f"the {'linear' if degree == 1 else 'quadratic'} model has {n_unknown} unknowns: "
                         f"{len(XYZ)} GCPs give {2 * len(XYZ)} equations (at least {need} GCPs)")
    eo = sensor.eo
    if eo.degree != degree:
        eo = EOPolynomial(eo.eo0, eo.k, np.zeros(6) if degree == 2 else None)
    return XYZ, rows, cols, names, free, eo.vector()


def _centring(rows, line_period, degree, names, free, centred):
    """p = T·q: q holds, for every element none of whose parameters is fixed, its value and rate at
    the mean GCP time t_c (E(t) = E_c + k_c(t − t_c) + d(t − t_c)²) — the first-line value and rate
    are strongly correlated when the GCPs lie far from the first line; the others stay as they are."""
    n = len(names)
    T = np.eye(n)
    labels = list(names)
    if not centred:
        return T, labels
    tc = float(np.mean(rows)) * line_period
    for j in range(6):
        group = [j, j + 6] + ([j + 12] if degree == 2 else [])
        if not all(g in free for g in group):
            continue
        T[j, j + 6] = -tc
        T[j + 6, j + 6] = 1.0
        if degree == 2:
            T[j, j + 12] = tc ** 2
            T[j + 6, j + 12] = -2 * tc
        labels[j] = names[j][:-1] + "(tc)" if names[j].endswith("0") else names[j] + "(tc)"
        labels[j + 6] = names[j + 6] + "(tc)"
    return T, labels


def _resection_linearize(sensor, rows, cols, XYZ, degree, free, q_full, T):
    res_fn, jac_fn = _line_model()
    dt = rows * sensor.line_period
    r = sensor.rays(cols)
    scale = sensor.focal_length / sensor.pixel_size         # residuals ≈ pixels

    def linearize(x):
        q = q_full.copy()
        q[free] = x
        eo = EOPolynomial.from_vector(T @ q)
        e = eo.elements(dt)
        args = (*e.T, XYZ[:, 0], XYZ[:, 1], XYZ[:, 2], r[:, 0], r[:, 1], r[:, 2])
        F = res_fn(*args)                                    # (2, n)
        J = jac_fn(*args).reshape(2, 6, -1)                  # ∂F/∂(X_S … κ) of each line
        cols_ = [J, J * dt] + ([J * dt ** 2] if degree == 2 else [])
        B = np.concatenate(cols_, axis=1)                    # (2, 6·degree+6, n): chain rule
        B = np.transpose(B, (2, 0, 1)).reshape(-1, B.shape[1]) * scale
        L = F.T.reshape(-1) * scale
        return (B @ T)[:, free], L
    return linearize


def resection_condition(sensor, rows, cols, XYZ, degree: int = 1, fixed=(), centred: bool = False) -> float:
    """Condition number of the time-polynomial resection at the sensor's EO (Fig. 8.14).

    The Jacobian of (8.5.2) with (8.5.3)/(8.5.5) by the free parameters, each column scaled to unit
    norm (so that units do not matter); ratio of its largest to its smallest singular value.

    Parameters
    ----------
    sensor : Pushbroom
        Sensor whose EO is the point of linearisation.
    rows, cols : array_like (n,)
        Image coordinates of the GCPs.
    XYZ : array_like (n, 3)
        Object coordinates of the GCPs.
    degree : {1, 2}
        Linear (12 unknowns) or quadratic (18) model.
    fixed : sequence of str
        Parameters held fixed (names of :data:`EO_NAMES`, e.g. ``("Z_S0",)``).
    centred : bool
        False: the book's unknowns (first-line values and rates, (8.5.3)); True: the unknowns
        :func:`resect_pushbroom` iterates on (values and rates at the mean GCP time for elements
        with no fixed parameter), which removes the value–rate correlation.

    Returns
    -------
    float
        The condition number (≈ 1e10 and more is numerically singular).

    Raises
    ------
    InputError
        Wrong shapes, NaN/inf, too few GCPs, an unknown parameter name.

    References
    ----------
    Chibunichev (2022), §8.5, eqs. (8.5.2)–(8.5.5), Fig. 8.14.

    Examples
    --------
    >>> eo = EOPolynomial([0, 0, 475e3, 0.01, 0.02, 0.005], [7000, 5, -2, 1e-6, -1e-6, 2e-6])
    >>> cam = Pushbroom(3.8, 8e-6, 38000, 1 / 7000, eo, n_rows=30000)
    >>> rng = np.random.default_rng(0)
    >>> r, c = rng.uniform(0, 30000, 12), rng.uniform(0, 38000, 12)
    >>> X, Y = cam.ground(r, c, 0.0)
    >>> flat = np.column_stack([X, Y, np.zeros(12)])
    >>> resection_condition(cam, r, c, flat) > 1e9, resection_condition(cam, r, c, flat, fixed=["Z_S0"]) < 1e9
    (True, True)
    """
    XYZ, rows, cols, names, free, p = _resection_setup(sensor, rows, cols, XYZ, degree, fixed)
    T, _ = _centring(rows, sensor.line_period, degree, names, free, centred)
    q = np.linalg.solve(T, p)
    B, _ = _resection_linearize(sensor, rows, cols, XYZ, degree, free, q, T)(q[free])
    B = B / np.linalg.norm(B, axis=0)
    s = np.linalg.svd(B, compute_uv=False)
    return float(s[0] / max(s[-1], 1e-300))


@dataclass
class PushbroomResection:
    """Result of :func:`resect_pushbroom`.

    Attributes
    ----------
    sensor : Pushbroom
        The sensor with the estimated EO.
    adjustment : Adjustment
        The least-squares result (free parameters only; residuals ≈ pixels).
    names : tuple of str
        Names of the free parameters (order of ``adjustment.x``); ``"X_S(tc)"``, ``"k1(tc)"`` …
        are the value and rate at the mean GCP time t_c (see :func:`resect_pushbroom`).
    fixed : tuple of str
        Parameters held at their approximate values.
    condition : float
        Condition number of the column-scaled Jacobian at the start (:func:`resection_condition`).

    References
    ----------
    Chibunichev (2022), §8.5, eqs. (8.5.2)–(8.5.5).

    Examples
    --------
    >>> PushbroomResection.__name__
    'PushbroomResection'
    """

    sensor: Pushbroom
    adjustment: Adjustment
    names: tuple
    fixed: tuple
    condition: float


def resect_pushbroom(sensor, rows, cols, XYZ, degree: int = 1, fixed=(), weights=None, *, sigma_eo=None,
                     tol: float = 1e-8, max_iter: int = 30, max_condition: float = _FLAT_COND) -> PushbroomResection:
    """Time-polynomial EO of a scanner from GCPs: the resection of §8.5, (8.5.2)–(8.5.5).

    Each GCP gives two equations (8.5.2) at its line's time Δt = row·line_period; the unknowns are
    the 12 (linear (8.5.3)) or 18 (quadratic (8.5.5)) parameters of :data:`EO_NAMES`, so at least
    6 or 9 GCPs. On flat terrain the problem is singular (Fig. 8.14): a shift of the centre along
    the flight, a change of height and a pitch produce the same rays through the same points. The
    start is checked; above ``max_condition`` the function raises, naming the cure: fix one of
    X_S0, Z_S0, α0 (``fixed=("Z_S0",)``, best for space imagery). Fixed parameters keep the values
    of ``sensor.eo``, which is also the approximation. For an element none of whose parameters
    is fixed, the iteration solves for its value and rate at the mean GCP time t_c (the first-line
    value and the rate are almost collinear when the GCPs lie far from the first line); the
    result is converted back to the first-line form (8.5.3) in ``sensor``.

    Parameters
    ----------
    sensor : Pushbroom
        Interior geometry and approximate EO (its degree is raised to ``degree`` if needed).
    rows, cols : array_like (n,)
        Measured image coordinates of the GCPs.
    XYZ : array_like (n, 3)
        Object coordinates of the GCPs.
    degree : {1, 2}
        Linear or quadratic model.
    fixed : sequence of str
        Names (of :data:`EO_NAMES`) held fixed.
    weights : array_like (2n,), optional
        Weights of the equations (x, y of each GCP in turn); unit weights (σ = 1 px) if omitted.
    sigma_eo : array_like (12,) or (18,), optional
        A-priori σ of the approximate EO (units of :data:`EO_NAMES`), added as weighted
        pseudo-observations of the iterated unknowns (for elements solved at t_c, of their value
        and rate there). A soft version of fixing: it cures the flat-terrain ambiguity and the
        narrow-field correlations; with it the condition check is skipped. ``inf`` = no prior.
    tol : float
        Convergence: every correction moves no residual by more than ``tol`` pixels.
    max_iter : int
        Iterations allowed.
    max_condition : float
        Largest acceptable condition number at the start.

    Returns
    -------
    PushbroomResection
        The estimated sensor, the adjustment and the condition number.

    Raises
    ------
    InputError
        Wrong shapes, NaN/inf, too few GCPs for the model, an unknown parameter name.
    DegenerateGeometryError
        The flat-terrain ambiguity of Fig. 8.14 (or another singular geometry).
    ConvergenceError
        No convergence.

    References
    ----------
    Chibunichev (2022), §8.5, eqs. (8.5.2)–(8.5.5), Fig. 8.14; §8.7.

    Examples
    --------
    >>> eo = EOPolynomial([0, 0, 475e3, 0.01, -0.02, 0.03], [7000, 10, -2, 1e-5, 2e-5, -1e-5])
    >>> truth = Pushbroom(3.8, 8e-6, 38000, 1 / 7000, eo, n_rows=30000)
    >>> rng = np.random.default_rng(1)
    >>> r, c, Z = rng.uniform(0, 30000, 10), rng.uniform(0, 38000, 10), rng.uniform(0, 2000, 10)
    >>> X, Y = truth.ground(r, c, Z)
    >>> start = truth.with_eo(EOPolynomial(eo.eo0 + [30, -20, 0, 1e-5, 0, 0], eo.k))
    >>> out = resect_pushbroom(start, r, c, np.column_stack([X, Y, Z]), fixed=("Z_S0",))
    >>> bool(np.allclose(out.sensor.project(X, Y, Z), (r, c), atol=1e-6))
    True
    """
    XYZ, rows, cols, names, free, p = _resection_setup(sensor, rows, cols, XYZ, degree, fixed)
    T, labels = _centring(rows, sensor.line_period, degree, names, free, True)
    q = np.linalg.solve(T, p)
    linearize = _resection_linearize(sensor, rows, cols, XYZ, degree, free, q, T)
    B0, _ = linearize(q[free])
    Bs = B0 / np.linalg.norm(B0, axis=0)
    s = np.linalg.svd(Bs, compute_uv=False)
    cond = float(s[0] / max(s[-1], 1e-300))
    prior = None
    if sigma_eo is not None:
        sig = _floats(sigma_eo, "sigma_eo", ndim=1) if not np.any(np.isinf(np.asarray(sigma_eo, float))) \
            else np.asarray(sigma_eo, float)
        if sig.shape != (len(names),) or np.any(np.isnan(sig)) or np.any(sig <= 0):
            raise InputError(f"sigma_eo must hold {len(names)} positive values (inf = no prior)")
        prior = 1.0 / sig[free] ** 2
        q0 = q[free].copy()
        base = linearize
        n_obs = 2 * len(XYZ)
        gcp_w = np.ones(n_obs) if weights is None else _floats(weights, "weights", ndim=1)
        if gcp_w.shape != (n_obs,):
            raise InputError(f"weights: one per equation ({n_obs}), got {gcp_w.shape}")
        weights = np.concatenate([gcp_w, prior])

        def linearize(x):
            B, L = base(x)
            return np.vstack([B, np.eye(len(x))]), np.concatenate([L, x - q0])
    if cond > max_condition and prior is None:
        spread = np.ptp(XYZ[:, 2])
        raise DegenerateGeometryError(
            f"resection singular (condition {cond:.1e}): flat-terrain ambiguity of the scanner resection "
            f"(Fig. 8.14; GCP heights span {spread:.1f} m) — different centres and attitudes send rays through "
            f"the same points; fix one element, e.g. fixed=('Z_S0',) (or 'alpha0', 'X_S0')")
    fixed_names = tuple(n for n in names if names.index(n) not in free)
    tol_x = tol / np.max(np.abs(B0), axis=0)
    if prior is not None:                                 # zero-weight priors leave tol unchanged
        pass              # a change that moves no residual by ≥ tol px
    adj = gauss_newton(linearize, q[free], weights, tol=tol_x, max_iter=max_iter,
                       names=[labels[i] for i in free])
    q_new = q.copy()
    q_new[free] = adj.x
    return PushbroomResection(sensor.with_eo(EOPolynomial.from_vector(T @ q_new)), adj,
                              tuple(labels[i] for i in free), fixed_names, cond)


# --------------------------------------------------------------------------- approximating models
_KINDS = {"dlt": 11, "affine": 8, "parallel-perspective": 11}
_MIN_GCP = {"dlt": 6, "affine": 4, "parallel-perspective": 7}
# (8.5.12): the row equation alone has 7 coefficients L1–L7 (the column equation 4, separate), so
# it needs 7 GCPs, not the printed 6 (6 GCPs give 12 equations for 11 unknowns, but only 6 of them
# constrain L1–L7).


@dataclass(frozen=True, eq=False)
class ApproximateModel:
    """An approximating scanner model: DLT (8.5.10), affine (8.5.11) or parallel-perspective (8.5.12).

    The book's x (the line) is the image row, y the column. Coefficients refer to normalised
    coordinates u = (value − offset)/scale (as RPCs do), which keeps the fit well conditioned;
    :meth:`raw_coefficients` gives the book's A₁…C₃ / L₁…L₁₁ in the original units.

    Attributes
    ----------
    kind : str
        ``"dlt"``, ``"affine"`` or ``"parallel-perspective"``.
    coefficients : ndarray
        11, 8 or 11 normalised coefficients in the book's order.
    offsets, scales : ndarray (5,)
        Normalisation of (row, col, X, Y, Z).
    rms : float
        RMS of the fit residuals (pixels, rows and columns together).
    perspective : {"rows", "cols"}
        Parallel-perspective only: which image coordinate is the rational one — ``"rows"`` as
        printed in (8.5.12), ``"cols"`` for the across-track (CCD-line) perspective of a real
        pushbroom; with ``"cols"`` the coefficients describe (col, row) in the book's (x, y) roles.

    References
    ----------
    Chibunichev (2022), §8.5, eqs. (8.5.10)–(8.5.12).

    Examples
    --------
    >>> rng = np.random.default_rng(0)
    >>> XYZ = rng.uniform(0, 100, (4, 3))
    >>> m = fit_affine(XYZ, XYZ[:, 0] + 2 * XYZ[:, 2], XYZ[:, 1] - XYZ[:, 2] + 5)
    >>> m.raw_coefficients().round(9) + 0.0
    array([ 1.,  0.,  2.,  0.,  0.,  1., -1.,  5.])
    """

    kind: str
    coefficients: np.ndarray
    offsets: np.ndarray
    scales: np.ndarray
    rms: float = 0.0
    perspective: str = "rows"

    def __post_init__(self):
        if not isinstance(self.kind, str) or self.kind not in _KINDS:
            raise InputError(f"kind must be one of {sorted(_KINDS)}, got {self.kind!r}")
        c = _floats(self.coefficients, "coefficients", ndim=1)
        if c.size != _KINDS[self.kind]:
            raise InputError(f"the {self.kind} model has {_KINDS[self.kind]} coefficients, got {c.size}")
        o, sc = _floats(self.offsets, "offsets", ndim=1), _floats(self.scales, "scales", ndim=1)
        if o.shape != (5,) or sc.shape != (5,) or np.any(sc <= 0):
            raise InputError("offsets and scales must hold 5 values (row, col, X, Y, Z), scales positive")
        if self.perspective not in ("rows", "cols"):
            raise InputError(f"perspective must be 'rows' or 'cols', got {self.perspective!r}")
        object.__setattr__(self, "coefficients", c)
        object.__setattr__(self, "offsets", o)
        object.__setattr__(self, "scales", sc)

    def _matrices(self, c):
        """Numerators/denominators as 4-vectors on (X, Y, Z, 1): (row num, row den, col num, col den)."""
        one = np.array([0.0, 0.0, 0.0, 1.0])
        if self.kind == "dlt":
            den = np.r_[c[8:11], 1.0]
            return c[0:4], den, c[4:8], den
        if self.kind == "affine":
            return c[0:4], one, c[4:8], one
        return c[0:4], np.r_[c[4:7], 1.0], c[7:11], one

    def project(self, X, Y, Z):
        """Image (rows, cols) of ground points by the model.

        Parameters
        ----------
        X, Y, Z : array_like
            Ground coordinates (broadcast together).

        Returns
        -------
        rows, cols : ndarray

        Raises
        ------
        InputError
            NaN/inf, shapes that do not broadcast.
        DegenerateGeometryError
            A point on the vanishing plane of the model (denominator ≈ 0).

        References
        ----------
        Chibunichev (2022), §8.5, eqs. (8.5.10)–(8.5.12).

        Examples
        --------
        >>> m = fit_affine(np.eye(4, 3) * 10, [10, 0, 0, 0], [0, 10, 0, 0])
        >>> [round(float(v), 9) for v in m.project(5.0, 5.0, 0.0)]
        [5.0, 5.0]
        """
        (X, Y, Z), shape = _same(_floats(X, "X"), _floats(Y, "Y"), _floats(Z, "Z"), names=("X", "Y", "Z"))
        o, s = self.offsets, self.scales
        H = np.column_stack([(X - o[2]) / s[2], (Y - o[3]) / s[3], (Z - o[4]) / s[4], np.ones_like(X)])
        rn, rd, cn, cd = self._matrices(self.coefficients)
        drow, dcol = H @ rd, H @ cd
        if np.any(np.abs(drow) < 1e-12) or np.any(np.abs(dcol) < 1e-12):
            raise DegenerateGeometryError("a point lies on the vanishing plane of the model (denominator ≈ 0)")
        rows = (H @ rn) / drow * s[0] + o[0]
        cols = (H @ cn) / dcol * s[1] + o[1]
        if self.perspective == "cols":
            rows, cols = cols, rows
        return rows.reshape(shape), cols.reshape(shape)

    def raw_coefficients(self) -> np.ndarray:
        """The coefficients for unnormalised coordinates, in the book's order (A…, B…, C… or L₁…L₁₁)."""
        o, s = self.offsets, self.scales
        D = np.diag([1 / s[2], 1 / s[3], 1 / s[4], 1.0])
        D[:3, 3] = -o[2:] / s[2:]
        rn, rd, cn, cd = (v @ D for v in self._matrices(self.coefficients))
        rn = rn * s[0] + rd * o[0]
        cn = cn * s[1] + cd * o[1]
        if abs(rd[3]) < 1e-300 or abs(cd[3]) < 1e-300:
            raise DegenerateGeometryError("the model's denominator vanishes at the origin of the raw coordinates")
        rn, cn, rd, cd = rn / rd[3], cn / cd[3], rd / rd[3], cd / cd[3]
        if self.kind == "dlt":
            return np.r_[rn, cn, rd[:3]]
        if self.kind == "affine":
            return np.r_[rn, cn]
        return np.r_[rn, rd[:3], cn]


def fit_approximate_model(kind: str, XYZ, rows, cols, weights=None, perspective: str = "rows") -> ApproximateModel:
    """Fit an approximating model (8.5.10)–(8.5.12) to GCPs by least squares.

    The rational equations are multiplied by their denominators, x·(C·X + 1) = A·X + A₄, which is
    linear in the coefficients; the normal equations are solved by
    :func:`photolib.lsq.solve_normal_equations` in normalised coordinates. The minimum numbers of
    GCPs: DLT 6 (11 coefficients), affine 4 (8), parallel-perspective **7** (11 coefficients, but the
    row equation alone has 7 of them, L₁…L₇, and the column equation only constrains L₈…L₁₁; the
    book's "6 GCPs" leaves L₁…L₇ underdetermined).

    Parameters
    ----------
    kind : {"dlt", "affine", "parallel-perspective"}
        The model.
    XYZ : array_like (n, 3)
        Ground coordinates of the GCPs.
    rows, cols : array_like (n,)
        Their image coordinates (rows = the book's x, the line; cols = y).
    weights : array_like (2n,), optional
        Weights of the linearised equations (rows first, then columns).
    perspective : {"rows", "cols"}
        Parallel-perspective only: the rational coordinate (``"rows"`` as printed).

    Returns
    -------
    ApproximateModel

    Raises
    ------
    InputError
        Unknown kind, wrong shapes, NaN/inf, fewer GCPs than the model needs.
    DegenerateGeometryError
        Degenerate GCPs (e.g. all at one height, or collinear): the coefficients are not determined.

    References
    ----------
    Chibunichev (2022), §8.5, eqs. (8.5.10)–(8.5.12).

    Examples
    --------
    >>> rng = np.random.default_rng(2)
    >>> XYZ = rng.uniform(-50, 50, (6, 3))
    >>> P = np.array([[1.0, 0.2, 0.1, 5], [0.1, 1.1, -0.3, 7], [1e-3, 2e-3, 1e-3, 1]])
    >>> h = np.c_[XYZ, np.ones(6)] @ P.T
    >>> m = fit_dlt(XYZ, h[:, 0] / h[:, 2], h[:, 1] / h[:, 2])
    >>> bool(np.allclose(m.raw_coefficients(), np.r_[P[0], P[1], P[2, :3]]))
    True
    """
    if not isinstance(kind, str) or kind not in _KINDS:
        raise InputError(f"kind must be one of {sorted(_KINDS)}, got {kind!r}")
    XYZ = _points3(XYZ, "GCP object coordinates")
    rows, cols = _floats(rows, "rows", ndim=1), _floats(cols, "cols", ndim=1)
    n = len(XYZ)
    if not (len(rows) == len(cols) == n):
        raise InputError(f"rows ({len(rows)}), cols ({len(cols)}) and GCPs ({n}) differ in number")
    if n < _MIN_GCP[kind]:
        raise InputError(f"the {kind} model has {_KINDS[kind]} coefficients: at least {_MIN_GCP[kind]} GCPs, got {n}")
    if perspective not in ("rows", "cols") or (perspective == "cols" and kind != "parallel-perspective"):
        raise InputError(f"perspective must be 'rows' (or 'cols' for the parallel-perspective model), got {perspective!r}")
    if perspective == "cols":
        rows, cols = cols, rows
    data = np.column_stack([rows, cols, XYZ])
    offsets = data.mean(axis=0)
    scales = np.max(np.abs(data - offsets), axis=0)
    scales[scales == 0] = 1.0
    u = (data - offsets) / scales
    H = np.column_stack([u[:, 2:], np.ones(n)])
    x, y = u[:, 0], u[:, 1]
    Z0 = np.zeros((n, 4))
    if kind == "dlt":
        Bx = np.hstack([H, Z0, -x[:, None] * H[:, :3]])
        By = np.hstack([Z0, H, -y[:, None] * H[:, :3]])
    elif kind == "affine":
        Bx, By = np.hstack([H, Z0]), np.hstack([Z0, H])
    else:
        Z3 = np.zeros((n, 3))
        Bx = np.hstack([H, -x[:, None] * H[:, :3], Z0])
        By = np.hstack([Z0[:, :4], Z3, H])
    B = np.vstack([Bx, By])
    L = -np.concatenate([x, y])
    names = [f"c{i + 1}" for i in range(_KINDS[kind])]
    try:
        coef, _ = solve_normal_equations(B, L, weights, names=names)
    except DegenerateGeometryError as exc:
        raise DegenerateGeometryError(f"the GCPs do not determine the {kind} model (degenerate layout: "
                                      f"coplanar, collinear or at one height?): {exc}") from None
    model = ApproximateModel(kind, coef, offsets, scales)
    pr, pc = model.project(XYZ[:, 0], XYZ[:, 1], XYZ[:, 2])
    rms = float(np.sqrt(np.mean(np.concatenate([pr - rows, pc - cols]) ** 2)))
    return ApproximateModel(kind, coef, offsets, scales, rms, perspective)


def fit_dlt(XYZ, rows, cols, weights=None) -> ApproximateModel:
    """The projective (DLT) model (8.5.10): 11 coefficients, at least 6 GCPs.

    Parameters
    ----------
    XYZ : array_like (n, 3)
        Ground coordinates of the GCPs.
    rows, cols : array_like (n,)
        Image coordinates.
    weights : array_like (2n,), optional
        Weights (see :func:`fit_approximate_model`).

    Returns
    -------
    ApproximateModel

    Raises
    ------
    InputError
        Fewer than 6 GCPs, wrong shapes, NaN/inf.
    DegenerateGeometryError
        Coplanar or otherwise degenerate GCPs.

    References
    ----------
    Chibunichev (2022), §8.5, eq. (8.5.10).

    Examples
    --------
    >>> rng = np.random.default_rng(3)
    >>> XYZ = rng.uniform(0, 10, (8, 3))
    >>> fit_dlt(XYZ, XYZ[:, 0], XYZ[:, 1]).rms < 1e-9
    True
    """
    return fit_approximate_model("dlt", XYZ, rows, cols, weights)


def fit_affine(XYZ, rows, cols, weights=None) -> ApproximateModel:
    """The affine model (8.5.11): 8 coefficients, at least 4 GCPs.

    Parameters
    ----------
    XYZ : array_like (n, 3)
        Ground coordinates of the GCPs.
    rows, cols : array_like (n,)
        Image coordinates.
    weights : array_like (2n,), optional
        Weights.

    Returns
    -------
    ApproximateModel

    Raises
    ------
    InputError
        Fewer than 4 GCPs, wrong shapes, NaN/inf.
    DegenerateGeometryError
        Coplanar GCPs.

    References
    ----------
    Chibunichev (2022), §8.5, eq. (8.5.11).

    Examples
    --------
    >>> XYZ = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1.0]])
    >>> fit_affine(XYZ, [1, 2, 1, 1], [0, 0, 3, 0]).raw_coefficients().round(9) + 0.0
    array([1., 0., 0., 1., 0., 3., 0., 0.])
    """
    return fit_approximate_model("affine", XYZ, rows, cols, weights)


def fit_parallel_perspective(XYZ, rows, cols, weights=None, perspective: str = "rows") -> ApproximateModel:
    """The parallel-perspective model (8.5.12): 11 coefficients, at least 7 GCPs (the book: 6).

    As printed, the rational (perspective) part is the book's x — the row, along-track — and the
    column is affine. (In much of the pushbroom literature the perspective direction is the CCD
    line; the book's assignment is the default, ``perspective="cols"`` gives the other. Fitted to
    a pushbroom, the printed form leaves tens of pixels across the track; see the tests.)

    Parameters
    ----------
    XYZ : array_like (n, 3)
        Ground coordinates of the GCPs.
    rows, cols : array_like (n,)
        Image coordinates.
    weights : array_like (2n,), optional
        Weights.
    perspective : {"rows", "cols"}
        The rational coordinate (``"rows"`` as printed).

    Returns
    -------
    ApproximateModel

    Raises
    ------
    InputError
        Fewer than 7 GCPs (the row equation has 7 coefficients), wrong shapes, NaN/inf.
    DegenerateGeometryError
        Coplanar or otherwise degenerate GCPs.

    References
    ----------
    Chibunichev (2022), §8.5, eq. (8.5.12).

    Examples
    --------
    >>> rng = np.random.default_rng(4)
    >>> XYZ = rng.uniform(0, 10, (7, 3))
    >>> rows = (XYZ[:, 0] + 1) / (0.01 * XYZ[:, 1] + 1)
    >>> fit_parallel_perspective(XYZ, rows, XYZ[:, 1] - XYZ[:, 2]).rms < 1e-9
    True
    """
    return fit_approximate_model("parallel-perspective", XYZ, rows, cols, weights, perspective)


# --------------------------------------------------------------------------- stereo §8.8
def intersect_scanner_rays(S1, r1, S2, r2) -> np.ndarray:
    """Forward intersection of two scanner rays, each with its own centre, (8.8.1).

    R = S₁ⱼ + Nⱼ·A₁ⱼr₁ⱼ with Nⱼ = |Bⱼ × r₂ⱼ|/|r₁ⱼ × r₂ⱼ| (the frame-camera scalar of §2.4,
    :func:`photolib.image_pair.intersection_scale` with ``method="norm"``), Bⱼ = S₂ⱼ − S₁ⱼ.

    Parameters
    ----------
    S1, S2 : array_like (n, 3)
        Projection centres of the lines that imaged each point on images 1 and 2.
    r1, r2 : array_like (n, 3)
        Rays in the object frame (A·r).

    Returns
    -------
    ndarray (n, 3)
        Object points (on ray 1, as (8.8.1)).

    Raises
    ------
    InputError
        Wrong shapes, NaN/inf.
    DegenerateGeometryError
        Zero base or parallel rays.
    PointBehindCameraError
        The rays meet behind sensor 1.

    References
    ----------
    Chibunichev (2022), §8.8, eq. (8.8.1); §2.4, eqs. (2.4.10)–(2.4.11).

    Examples
    --------
    >>> intersect_scanner_rays([[0, 0, 100.0]], [[0.1, 0, -1]], [[20, 0, 100.0]], [[-0.1, 0, -1]])
    array([[10.,  0.,  0.]])
    """
    from .image_pair import intersection_scale
    S1, S2 = _points3(S1, "S1"), _points3(S2, "S2")
    r1, r2 = _points3(r1, "r1"), _points3(r2, "r2")
    if not (len(S1) == len(S2) == len(r1) == len(r2)):
        raise InputError("S1, r1, S2, r2 must have one row per point")
    N = intersection_scale(S2 - S1, r1, r2, method="norm")
    if np.any(N <= 0):
        bad = np.flatnonzero(N <= 0)
        raise PointBehindCameraError(f"the rays of points {bad.tolist()} meet behind sensor 1", bad)
    return S1 + N[:, None] * r1


def intersect_pushbroom(sensor1, rows1, cols1, sensor2, rows2, cols2) -> np.ndarray:
    """Object points from a scanner stereo pair with known EO (case 1 of §8.8), (8.8.1).

    Parameters
    ----------
    sensor1, sensor2 : Pushbroom
        The two images' sensors.
    rows1, cols1, rows2, cols2 : array_like (n,)
        Corresponding image points.

    Returns
    -------
    ndarray (n, 3)

    Raises
    ------
    InputError
        Not a Pushbroom, wrong shapes, NaN/inf.
    DegenerateGeometryError
        Parallel rays.
    PointBehindCameraError
        The rays meet behind sensor 1.

    References
    ----------
    Chibunichev (2022), §8.8, eq. (8.8.1).

    Examples
    --------
    >>> e1 = EOPolynomial([0, -300, 1000, 0, 0, 0], [100, 0, 0, 0, 0, 0])
    >>> e2 = EOPolynomial([0, 300, 1000, 0, 0, 0], [100, 0, 0, 0, 0, 0])
    >>> c1, c2 = Pushbroom(0.1, 1e-5, 10001, 0.01, e1), Pushbroom(0.1, 1e-5, 10001, 0.01, e2)
    >>> P = np.array([[20.0, 10.0, 50.0]])
    >>> (rc1, rc2) = c1.project(*P.T), c2.project(*P.T)
    >>> intersect_pushbroom(c1, *rc1, c2, *rc2).round(6) + 0.0
    array([[20., 10., 50.]])
    """
    for s, name in ((sensor1, "sensor1"), (sensor2, "sensor2")):
        if not isinstance(s, Pushbroom):
            raise InputError(f"{name} must be a Pushbroom, got {type(s).__name__}")
    a = [_floats(v, n, ndim=1) for v, n in ((rows1, "rows1"), (cols1, "cols1"), (rows2, "rows2"), (cols2, "cols2"))]
    if len({len(v) for v in a}) != 1:
        raise InputError("rows1, cols1, rows2, cols2 must have the same length")
    S1, R1 = sensor1.object_rays(a[0], a[1])
    S2, R2 = sensor2.object_rays(a[2], a[3])
    return intersect_scanner_rays(S1, R1, S2, R2)


def first_line_rays(rays, d_angles) -> np.ndarray:
    """Rays turned into the scanner frame of the first line, (8.8.2): r = ΔA(Δω, Δα, Δκ)·r′.

    With the attitude of line j written A_j = A₀·ΔA_j (increments measured on board relative to
    the first line, applied in the scanner frame), A_j r′ = A₀(ΔA_j r′), so ΔA_j r′ is the ray in
    the first line's frame.

    Parameters
    ----------
    rays : array_like (n, 3)
        Unit rays r′ in the scanner frame of their own lines ((8.2.2), (8.3.1), (8.4.2), (8.4.3)).
    d_angles : array_like (n, 3)
        Increments (Δω, Δα, Δκ) (rad) of each ray's line relative to the first line.

    Returns
    -------
    ndarray (n, 3)

    Raises
    ------
    InputError
        Wrong shapes, NaN/inf.

    References
    ----------
    Chibunichev (2022), §8.8, eq. (8.8.2).

    Examples
    --------
    >>> first_line_rays([[0.0, 0.0, -1.0]], [[0.0, 0.1, 0.0]]).round(6)
    array([[-0.099833,  0.      , -0.995004]])
    """
    r, d = _points3(rays, "rays"), _points3(d_angles, "d_angles")
    if len(r) != len(d):
        raise InputError(f"rays ({len(r)}) and d_angles ({len(d)}) differ in number")
    dA = rotation_matrix(d[:, 0], d[:, 1], d[:, 2], order="wak")
    return np.einsum("nij,nj->ni", dA, r)


@dataclass
class PairOrientation:
    """First-line EO of both images of a scanner pair (case 3 of §8.8), :func:`orient_pushbroom_pair`.

    Attributes
    ----------
    eo1, eo2 : ndarray (6,)
        (X_S0, Y_S0, Z_S0, ω0, α0, κ0) of the first line of images 1 and 2.
    adjustment : Adjustment
        The joint least-squares adjustment (12 unknowns, (8.8.6)/(8.8.7)).
    n_tie, n_gcp : int
        Numbers of coplanarity and collinearity equations' points.

    References
    ----------
    Chibunichev (2022), §8.8, eqs. (8.8.2)–(8.8.7).

    Examples
    --------
    >>> PairOrientation.__name__
    'PairOrientation'
    """

    eo1: np.ndarray
    eo2: np.ndarray
    adjustment: Adjustment
    n_tie: int = 0
    n_gcp: int = 0
    names: tuple = field(default=("X_S10", "Y_S10", "Z_S10", "omega10", "alpha10", "kappa10",
                                  "X_S20", "Y_S20", "Z_S20", "omega20", "alpha20", "kappa20"))


def _triplets(group, name, with_points):
    if not isinstance(group, (tuple, list)) or len(group) != (3 if with_points else 4):
        raise InputError(f"{name} must be a tuple of {'(rays, d_position, XYZ)' if with_points else '(r1, r2, dS1, dS2)'}")
    arrs = [_points3(a, f"{name}[{i}]") for i, a in enumerate(group)]
    if len({len(a) for a in arrs}) != 1:
        raise InputError(f"the arrays of {name} differ in length")
    return arrs


def orient_pushbroom_pair(ties, gcps1, gcps2, eo1_approx, eo2_approx, weights=None, *,
                          sigma_coplanarity: float = 1e-6, sigma_ray: float = 1e-6,
                          tol=(1e-6, 1e-11), max_iter: int = 30) -> PairOrientation:
    """First-line EO of both images of a scanner pair with known EO increments (case 3 of §8.8).

    All rays are first turned into their image's first-line frame (:func:`first_line_rays`,
    (8.8.2)); the centre of line j is S_i0 + ΔS_ij (8.8.4). Unknowns: the twelve first-line
    elements (X_S10, Y_S10, Z_S10, ω10, α10, κ10, X_S20, …, κ20). Equations: the coplanarity
    (8.8.3) of every tie point, linearised to (8.8.6), normalised by |B| so that it is a
    dimensionless triple product of unit vectors, and the collinearity (8.8.5) of every GCP on
    each image, linearised to (8.8.7). Solved jointly by :func:`photolib.lsq.gauss_newton`.

    Parameters
    ----------
    ties : tuple (r1, r2, dS1, dS2)
        Tie points: first-line-frame unit rays on images 1 and 2 (n, 3) and the centre
        increments ΔS of their lines (n, 3).
    gcps1, gcps2 : tuple (rays, dS, XYZ)
        GCPs measured on image 1 / 2: first-line-frame rays, centre increments, object points.
    eo1_approx, eo2_approx : array_like (6,)
        Approximate first-line EO.
    weights : array_like, optional
        Weights of all equations (ties first, then the x/y equations of the GCPs of image 1, then
        image 2); default 1/σ² from ``sigma_coplanarity`` and ``sigma_ray``.
    sigma_coplanarity, sigma_ray : float
        A-priori σ of the normalised coplanarity and of a unit-ray component (rad).
    tol : (float, float) or array_like (12,)
        Convergence: corrections below (m for positions, rad for angles), or one value per unknown.
    max_iter : int
        Iterations allowed.

    Returns
    -------
    PairOrientation

    Raises
    ------
    InputError
        Wrong shapes, NaN/inf, too few equations for 12 unknowns.
    DegenerateGeometryError
        Not enough control (e.g. no GCP on one image and a datum left free).
    ConvergenceError
        No convergence.

    References
    ----------
    Chibunichev (2022), §8.8, eqs. (8.8.2)–(8.8.7).

    Examples
    --------
    See ``tests/library/test_pushbroom.py::test_orient_pair_recovers_truth``:

    >>> orient_pushbroom_pair.__name__
    'orient_pushbroom_pair'
    """
    from .derivations.scanner import rotated_ray_model
    t1, t2, tdS1, tdS2 = _triplets(ties, "ties", False)
    g1 = _triplets(gcps1, "gcps1", True)
    g2 = _triplets(gcps2, "gcps2", True)
    e1 = _floats(eo1_approx, "eo1_approx", ndim=1)
    e2 = _floats(eo2_approx, "eo2_approx", ndim=1)
    if e1.shape != (6,) or e2.shape != (6,):
        raise InputError("eo1_approx and eo2_approx must have 6 elements (X_S, Y_S, Z_S, ω, α, κ)")
    sc, sr = _positive(sigma_coplanarity, "sigma_coplanarity"), _positive(sigma_ray, "sigma_ray")
    n_eq = len(t1) + 2 * len(g1[0]) + 2 * len(g2[0])
    if n_eq < 12:
        raise InputError(f"{n_eq} equations cannot determine the 12 first-line elements")
    res_fn, jac_fn = _line_model()
    ray_fn, ray_jac = rotated_ray_model().compile()

    def rotated(e, r):
        R = ray_fn(e[3], e[4], e[5], r[:, 0], r[:, 1], r[:, 2]).T                # (n, 3)
        dR = ray_jac(e[3], e[4], e[5], r[:, 0], r[:, 1], r[:, 2]).reshape(3, 3, -1)  # [comp, angle, n]
        return R, np.transpose(dR, (2, 1, 0))                                       # (n, angle, comp)

    def collinearity(e, rays, dS, XYZ):
        S = e[:3] + dS
        args = (S[:, 0], S[:, 1], S[:, 2], *np.broadcast_arrays(*e[3:], S[:, 0])[:3],
                XYZ[:, 0], XYZ[:, 1], XYZ[:, 2], rays[:, 0], rays[:, 1], rays[:, 2])
        F = res_fn(*args)
        J = jac_fn(*args).reshape(2, 6, -1)
        return np.transpose(J, (2, 0, 1)).reshape(-1, 6), F.T.reshape(-1)

    def linearize(x):
        a, b = x[:6], x[6:]
        blocks, free = [], []
        if len(t1):
            R1, dR1 = rotated(a, t1)
            R2, dR2 = rotated(b, t2)
            Bv = (b[:3] + tdS2) - (a[:3] + tdS1)
            nb = np.linalg.norm(Bv, axis=1)
            if np.any(nb == 0):
                raise DegenerateGeometryError("zero base between the two images' lines")
            c = np.cross(R1, R2)
            F = np.einsum("ij,ij->i", Bv, c) / nb                                   # (8.8.3) / |B|
            Bm = np.zeros((len(t1), 12))
            Bm[:, 0:3] = -c / nb[:, None]
            Bm[:, 6:9] = c / nb[:, None]
            Bm[:, 3:6] = np.einsum("nj,naj->na", Bv, np.cross(dR1, R2[:, None, :])) / nb[:, None]
            Bm[:, 9:12] = np.einsum("nj,naj->na", Bv, np.cross(R1[:, None, :], dR2)) / nb[:, None]
            blocks.append(Bm)
            free.append(F)
        for (rays, dS, XYZ), off, e in ((g1, 0, a), (g2, 6, b)):
            if len(rays):
                J, F = collinearity(e, rays, dS, XYZ)
                Bm = np.zeros((len(F), 12))
                Bm[:, off:off + 6] = J
                blocks.append(Bm)
                free.append(F)
        return np.vstack(blocks), np.concatenate(free)

    if weights is None:
        weights = np.concatenate([np.full(len(t1), 1 / sc ** 2),
                                  np.full(2 * (len(g1[0]) + len(g2[0])), 1 / sr ** 2)])
    names = PairOrientation.__dataclass_fields__["names"].default
    tol = _floats(tol, "tol").ravel()
    if tol.size == 2:
        tol = np.tile(np.repeat(tol, 3), 2)
    if tol.size not in (1, 12):
        raise InputError("tol: one value, (positions, angles) or 12 values")
    adj = gauss_newton(linearize, np.concatenate([e1, e2]), weights, tol=tol, max_iter=max_iter, names=names)
    return PairOrientation(adj.x[:6].copy(), adj.x[6:].copy(), adj, len(t1), len(g1[0]) + len(g2[0]))
