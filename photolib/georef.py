"""Direct georeferencing, scanner aerial triangulation, scanner orthophotos, the Resurs-P
quasi-frame image and object-space SGM over scans — Chapter 8, §8.14–8.17.

§8.14 (direct georeferencing, (8.14.1)). A sensor, a GNSS antenna and an IMU are rigidly
mounted together. Conventions (all vectors are columns, A maps the *first* named frame's
components into the *second*'s):

* ``A_imu`` — the IMU attitude: IMU frame → object frame (A_ИИУ of the book);
* ``boresight`` — the boresight matrix A_ИИУ/S: **sensor frame → IMU frame**;
* ``lever_gnss`` — r_ГНСС/ИИУ: the antenna phase centre **in IMU-frame components, measured
  from the IMU origin** (so R_IMU = R_GNSS − A_imu·lever_gnss);
* ``lever_sensor`` — r_ИИУ/S: the sensor origin S in IMU-frame components, from the IMU origin.

Then the sensor origin is S = R_IMU + A_imu·lever_sensor, its attitude A_S = A_imu·boresight,
and a point seen along the sensor vector R is R_M = S + A_S·R (8.14.1). R depends on the
sensor: a frame-camera ray N·(x − x₀, y − y₀, −f) (:func:`frame_vector`, N from a ``scale`` or
a known height ``Z``), a scanner unit ray N·(x, y, z) (:func:`scanner_vector`, (8.2.2)), a lidar
or radar range vector D·(0, sin φ, −cos φ) (:func:`photolib.radar.range_vector`; a radar vector computed by
:mod:`photolib.radar` is accepted as any sensor-frame vector). :func:`sensor_pose` gives S and
A_S, :func:`ground_to_sensor` inverts (8.14.1).

§8.15 (aerial triangulation of a three-line scanner block with fixed projection centres). The
line EO is interpolated between fixed centres (every Δt) by (8.15.2), keeping the
high-frequency part measured by GNSS/IMU (:func:`interpolate_fixed_centres`); the collinearity
equations (8.15.1) of tie and control points plus the GNSS/IMU observation equations of the
fixed centres (with an optional constant offset, e.g. a boresight/lever-arm bias) are adjusted by
:func:`photolib.lsq.gauss_newton` (:func:`fixed_centre_triangulation`; Jacobians from sympy in
:mod:`photolib.derivations.georef`). :class:`TabulatedLineScanner` is a line scanner whose
per-line EO is a table (GNSS/IMU or the result of (8.15.2)) — a millimetre-unit front of the one
scanner model, :class:`photolib.pushbroom.Pushbroom` with an :class:`photolib.pushbroom.EOTable`;
:func:`three_line_block` simulates a small block with known offsets.

§8.16 (scanner orthophotos). :func:`direct_orthorectify` — the direct method: every scanner
pixel is monoplotted onto the DEM by the (8.16.1)/(7.7.1) iteration and its brightness moved to
the nearest orthophoto pixel; empty pixels ("holes") remain. The inverse method is
:func:`photolib.rectify.orthorectify` with the sensor's ground → image projection (a 1-D Newton
search for the line, :meth:`TabulatedLineScanner.project`, or an RPC): contrary to the book's
remark it does not need RPCs.

§8.17 (Resurs-P). :func:`quasi_frame_image` — a central-projection quasi-image (x₀ = y₀ = 0,
f = const, chosen angles, centre e.g. the mean of the scanner centres) filled from several scans
through the DEM; :func:`object_space_sgm` — the voxel SGM (8.17.1)–(8.17.4) with the cost
|d¹ − d²| (the printed signed difference is an erratum) minimised over all scan pairs
(:func:`scan_voxel_cost`) and the path aggregation of :func:`photolib.sgm.aggregate_costs`.

Angles in radians. Rotation sequence: A = A_ω A_α A_κ, (1.3.2) (``order="wak"``), unless stated.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import numpy as np

from .errors import ConvergenceError, DegenerateGeometryError, InputError, PointBehindCameraError

__all__ = ["frame_vector", "scanner_vector", "sensor_pose", "direct_georeference",
           "ground_to_sensor", "interpolate_fixed_centres", "TabulatedLineScanner", "ThreeLineBlock",
           "three_line_block", "FixedCentreAdjustment", "fixed_centre_triangulation", "DirectOrtho",
           "direct_orthorectify", "QuasiFrame", "quasi_frame_image", "scan_voxel_cost", "object_space_sgm"]


# --------------------------------------------------------------------------- validation helpers
def _array(value, name, shape_tail=None, ndim=None):
    if isinstance(value, (str, bytes)) or value is None:
        raise InputError(f"{name} must be numeric, got {type(value).__name__}")
    try:
        a = np.asarray(value, dtype=np.float64)
    except (TypeError, ValueError):
        raise InputError(f"{name} must be numeric") from None
    if ndim is not None and a.ndim not in ((ndim,) if isinstance(ndim, int) else ndim):
        raise InputError(f"{name} must have {ndim} dimension(s), got shape {a.shape}")
    if shape_tail is not None and a.shape[a.ndim - len(shape_tail):] != tuple(shape_tail):
        raise InputError(f"{name} must end in shape {tuple(shape_tail)}, got {a.shape}")
    if a.size == 0:
        raise InputError(f"{name} is empty")
    if not np.all(np.isfinite(a)):
        raise InputError(f"{name} has NaN or inf values")
    return a


def _positive(value, name):
    if isinstance(value, (bool, np.bool_)):
        raise InputError(f"{name} must be a number")
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise InputError(f"{name} must be a number, got {value!r}") from None
    if not np.isfinite(v) or v <= 0:
        raise InputError(f"{name} must be positive and finite, got {value!r}")
    return v


def _vectors(value, name):
    a = _array(value, name, (3,), (1, 2))
    return np.atleast_2d(a)


def _rotations(value, name):
    from .rotation import _as_rotation
    a = _array(value, name, (3, 3), (2, 3))
    return _as_rotation(a, name)


def _order(order):
    if order not in ("wak", "kaw"):
        raise InputError(f"order must be 'wak' (1.3.2) or 'kaw' (1.3.4), got {order!r}")
    return order


def _rot(angles, order):
    """A of (1.3.2) ("wak") element by element for stacks of angles (…, 3) → (…, 3, 3)."""
    angles = np.asarray(angles, dtype=np.float64)
    if order != "wak":
        from .rotation import _rotation_matrix
        return _rotation_matrix(angles[..., 0], angles[..., 1], angles[..., 2], order)
    cw, ca, ck = (np.cos(angles[..., i]) for i in range(3))
    sw, sa, sk = (np.sin(angles[..., i]) for i in range(3))
    A = np.empty(angles.shape[:-1] + (3, 3))
    A[..., 0, 0], A[..., 0, 1], A[..., 0, 2] = ca * ck, -ca * sk, sa
    A[..., 1, 0], A[..., 1, 1], A[..., 1, 2] = cw * sk + sw * sa * ck, cw * ck - sw * sa * sk, -sw * ca
    A[..., 2, 0], A[..., 2, 1], A[..., 2, 2] = sw * sk - cw * sa * ck, sw * ck + cw * sa * sk, cw * ca
    return A


def _callable(value, name):
    if not callable(value):
        raise InputError(f"{name} must be a callable")
    return value


# --------------------------------------------------------------------------- §8.14
def frame_vector(xy, f, x0=0.0, y0=0.0) -> np.ndarray:
    """The frame-camera ray r = (x − x₀, y − y₀, −f) of (8.14.1) (R = N·r).

    Parameters
    ----------
    xy : (n, 2) or (2,) array
        Measured image coordinates (mm).
    f, x0, y0 : float
        Interior orientation (mm).

    Returns
    -------
    numpy.ndarray
        (n, 3) ray vectors in the sensor frame.

    Raises
    ------
    InputError
        NaN/inf, a wrong shape, f ≤ 0.

    References
    ----------
    Chibunichev (2022), §8.14, eq. (8.14.1) and the frame-camera vector after it.

    Examples
    --------
    >>> frame_vector([1.0, 2.0], 100.0)
    array([[   1.,    2., -100.]])
    """
    xy = np.atleast_2d(_array(xy, "xy", (2,), (1, 2)))
    f = _positive(f, "f")
    x0 = float(_array(x0, "x0", ndim=0))
    y0 = float(_array(y0, "y0", ndim=0))
    return np.column_stack([xy[:, 0] - x0, xy[:, 1] - y0, np.full(len(xy), -f)])


def scanner_vector(y_c, f, x_line=0.0, x0=0.0, y0=0.0) -> np.ndarray:
    """The unit ray (x, y, z) of a linear-CCD scanner pixel, (8.2.2), used as R = N·r in (8.14.1).

    Parameters
    ----------
    y_c : float or (n,) array
        Coordinate of the pixel along the CCD line (mm, origin at the line's middle).
    f : float
        Focal length (mm).
    x_line : float
        Along-track offset x_i of the CCD line in the focal plane (mm; 0 for a nadir line,
        ± for the forward/backward lines of a three-line camera, (8.4.2)/(8.4.3)).
    x0, y0 : float
        Principal point (mm).

    Returns
    -------
    numpy.ndarray
        (n, 3) unit vectors.

    Raises
    ------
    InputError
        NaN/inf, f ≤ 0.

    References
    ----------
    Chibunichev (2022), §8.2, eqs. (8.2.1)–(8.2.2); §8.14.

    Examples
    --------
    >>> scanner_vector(0.0, 100.0).round(6) + 0.0
    array([[ 0.,  0., -1.]])
    """
    y_c = np.atleast_1d(_array(y_c, "y_c", ndim=(0, 1)))
    f = _positive(f, "f")
    xl, x0, y0 = (float(_array(v, n, ndim=0)) for v, n in ((x_line, "x_line"), (x0, "x0"), (y0, "y0")))
    r = np.column_stack([np.full(y_c.size, xl - x0), y_c - y0, np.full(y_c.size, -f)])
    return r / np.linalg.norm(r, axis=1, keepdims=True)


def _pose(gnss, A_imu, lever_gnss, lever_sensor, boresight):
    G = _vectors(gnss, "gnss")
    A = _rotations(A_imu, "A_imu")
    lg = _array(lever_gnss, "lever_gnss", (3,), 1)
    ls = _array(lever_sensor, "lever_sensor", (3,), 1)
    Ab = _rotations(boresight, "boresight")
    if A.ndim == 2:
        A = A[None]
    n = max(len(G), len(A))
    if len(G) not in (1, n) or len(A) not in (1, n):
        raise InputError(f"gnss has {len(G)} positions but A_imu {len(A)} attitudes (give one or equal numbers)")
    G = np.broadcast_to(G, (n, 3))
    A = np.broadcast_to(A, (n, 3, 3))
    R_imu = G - A @ lg
    S = R_imu + A @ ls
    return S, A @ Ab


def sensor_pose(gnss, A_imu, lever_gnss, lever_sensor, boresight):
    """Position S and attitude A_S of the sensor from GNSS/IMU, the lever arms and the boresight.

    S = R_GNSS − A_imu·r_GNSS/IMU + A_imu·r_IMU/S and A_S = A_imu·A_IMU/S: the first two terms
    of (8.14.1) and the product of its rotations (the EO of the sensor, e.g. of a frame image).

    Parameters
    ----------
    gnss : (3,) or (n, 3) array
        GNSS antenna positions R_GNSS (object frame, m).
    A_imu : (3, 3) or (n, 3, 3) array
        IMU attitudes (IMU → object).
    lever_gnss : (3,) array
        r_GNSS/IMU: the antenna in IMU components from the IMU origin (m).
    lever_sensor : (3,) array
        r_IMU/S: the sensor origin in IMU components from the IMU origin (m).
    boresight : (3, 3) array
        A_IMU/S: sensor → IMU.

    Returns
    -------
    S : (n, 3) ndarray
    A_S : (n, 3, 3) ndarray
        Sensor → object.

    Raises
    ------
    InputError
        NaN/inf, wrong shapes, non-rotation matrices, mismatched counts.

    References
    ----------
    Chibunichev (2022), §8.14, eq. (8.14.1).

    Examples
    --------
    >>> S, A = sensor_pose([0, 0, 1000.0], np.eye(3), [0, 0, 1.0], [0, 0, -0.5], np.eye(3))
    >>> S
    array([[   0. ,    0. ,  998.5]])
    """
    return _pose(gnss, A_imu, lever_gnss, lever_sensor, boresight)


def direct_georeference(vectors, gnss, A_imu, lever_gnss, lever_sensor, boresight, *, scale=None, Z=None,
                        ) -> np.ndarray:
    """Object coordinates of points seen along sensor vectors, (8.14.1).

    R_M = R_IMU + A_IMU·r_IMU/S + A_IMU·A_IMU/S·R, R_IMU = R_GNSS − A_IMU·r_GNSS/IMU. The sensor
    vector R is ``vectors`` times ``scale`` (N of a frame or scanner ray), or times the N that
    puts the point at height ``Z``, or ``vectors`` as they are (lidar/radar range vectors,
    :func:`photolib.radar.range_vector`, or any vector in the sensor frame).

    Parameters
    ----------
    vectors : (3,) or (n, 3) array
        Sensor-frame vectors (rays r or range vectors R).
    gnss, A_imu, lever_gnss, lever_sensor, boresight
        As in :func:`sensor_pose`; one per vector or one for all.
    scale : float or (n,) array, optional
        N in R = N·r.
    Z : float or (n,) array, optional
        Known heights (monoplotting); excludes ``scale``.

    Returns
    -------
    numpy.ndarray
        (n, 3) points R_M.

    Raises
    ------
    InputError
        NaN/inf, wrong shapes, mismatched counts, both ``scale`` and ``Z``.
    PointBehindCameraError
        With ``Z``: a ray that does not reach the height in front of the sensor (N ≤ 0), or
        a horizontal ray.

    References
    ----------
    Chibunichev (2022), §8.14, eq. (8.14.1).

    Examples
    --------
    >>> r = frame_vector([0.0, 0.0], 100.0)
    >>> direct_georeference(r, [0, 0, 1000.0], np.eye(3), [0, 0, 0], [0, 0, 0], np.eye(3), Z=0.0)
    array([[0., 0., 0.]])
    """
    V = _vectors(vectors, "vectors")
    S, A = _pose(gnss, A_imu, lever_gnss, lever_sensor, boresight)
    n = max(len(V), len(S))
    if len(V) not in (1, n) or len(S) not in (1, n):
        raise InputError(f"{len(V)} vectors but {len(S)} sensor poses (give one or equal numbers)")
    V = np.broadcast_to(V, (n, 3))
    S = np.broadcast_to(S, (n, 3))
    A = np.broadcast_to(A, (n, 3, 3))
    W = np.einsum("nij,nj->ni", A, V)
    if scale is not None and Z is not None:
        raise InputError("give either scale or Z, not both")
    if scale is not None:
        N = np.broadcast_to(np.atleast_1d(_array(scale, "scale", ndim=(0, 1))), (n,))
    elif Z is not None:
        Zv = np.broadcast_to(np.atleast_1d(_array(Z, "Z", ndim=(0, 1))), (n,))
        with np.errstate(divide="ignore", invalid="ignore"):
            N = (Zv - S[:, 2]) / W[:, 2]
        bad = ~(np.isfinite(N) & (N > 0))
        if np.any(bad):
            raise PointBehindCameraError(f"{int(bad.sum())} ray(s) do not reach the given height in front of "
                                         "the sensor", np.flatnonzero(bad))
    else:
        N = np.ones(n)
    return S + N[:, None] * W


def ground_to_sensor(points, gnss, A_imu, lever_gnss, lever_sensor, boresight) -> np.ndarray:
    """The sensor-frame vector R of object points: the inverse of (8.14.1), R = A_Sᵀ(R_M − S).

    Parameters
    ----------
    points : (3,) or (n, 3) array
        Object points R_M.
    gnss, A_imu, lever_gnss, lever_sensor, boresight
        As in :func:`sensor_pose`.

    Returns
    -------
    numpy.ndarray
        (n, 3) vectors in the sensor frame (a frame camera's image point is
        x = x₀ − f·R_x/R_z, y = y₀ − f·R_y/R_z; a lidar's range is |R|).

    Raises
    ------
    InputError
        NaN/inf, wrong shapes, mismatched counts.

    References
    ----------
    Chibunichev (2022), §8.14, eq. (8.14.1).

    Examples
    --------
    >>> ground_to_sensor([0, 0, 0.0], [0, 0, 1000.0], np.eye(3), [0, 0, 0], [0, 0, 0], np.eye(3))
    array([[    0.,     0., -1000.]])
    """
    P = _vectors(points, "points")
    S, A = _pose(gnss, A_imu, lever_gnss, lever_sensor, boresight)
    n = max(len(P), len(S))
    if len(P) not in (1, n) or len(S) not in (1, n):
        raise InputError(f"{len(P)} points but {len(S)} sensor poses (give one or equal numbers)")
    P = np.broadcast_to(P, (n, 3))
    return np.einsum("nji,nj->ni", np.broadcast_to(A, (n, 3, 3)), P - np.broadcast_to(S, (n, 3)))


# --------------------------------------------------------------------------- §8.15
def _fixed_weights(t, t_fixed):
    """Index k of the interval [t_k, t_{k+1}] holding each t and the coefficient c of (8.15.2)."""
    k = np.clip(np.searchsorted(t_fixed, t, side="right") - 1, 0, len(t_fixed) - 2)
    c = (t_fixed[k + 1] - t) / (t_fixed[k + 1] - t_fixed[k])
    return k, c


def _times(t_fixed):
    tf = _array(t_fixed, "t_fixed", ndim=1)
    if tf.size < 2:
        raise InputError("at least two fixed projection centres are needed")
    if np.any(np.diff(tf) <= 0):
        raise InputError("t_fixed must be strictly increasing")
    return tf


def _delta(c, k, measured, measured_fixed, m, K):
    if (measured is None) != (measured_fixed is None):
        raise InputError("give both measured (at t) and measured_fixed (at t_fixed), or neither")
    if measured is None:
        return np.zeros((m, 6))
    M = _array(measured, "measured", (6,), 2)
    Mf = _array(measured_fixed, "measured_fixed", (6,), 2)
    if len(M) != m:
        raise InputError(f"measured has {len(M)} rows for {m} times")
    if len(Mf) != K:
        raise InputError(f"measured_fixed has {len(Mf)} rows for {K} fixed centres")
    return c[:, None] * Mf[k] + (1 - c[:, None]) * Mf[k + 1] - M


def interpolate_fixed_centres(t, t_fixed, eo_fixed, measured=None, measured_fixed=None) -> np.ndarray:
    """Line EO between fixed projection centres, (8.15.2).

    E = c·E_k + (1 − c)·E_{k+1} − δE with c = (t_{k+1} − t)/(t_{k+1} − t_k) and
    δE = c·E_k^meas + (1 − c)·E_{k+1}^meas − E^meas(t): the linear interpolation of the fixed
    centres plus the measured (GNSS/IMU) deviation from the linear interpolation of the
    measurements. Without measurements δE = 0 (linear interpolation).

    Parameters
    ----------
    t : float or (m,) array
        Times of the lines, within [t_fixed[0], t_fixed[-1]].
    t_fixed : (K,) array
        Times of the fixed centres, increasing, K ≥ 2.
    eo_fixed : (K, 6) array
        EO (X_S, Y_S, Z_S, ω, α, κ) of the fixed centres.
    measured : (m, 6) array, optional
        GNSS/IMU EO at the times ``t``.
    measured_fixed : (K, 6) array, optional
        GNSS/IMU EO at ``t_fixed``.

    Returns
    -------
    numpy.ndarray
        (m, 6) line EO.

    Raises
    ------
    InputError
        NaN/inf, mismatched sizes, times outside the fixed centres, only one of the measurements.

    References
    ----------
    Chibunichev (2022), §8.15, the interpolation formulas after (8.15.1).

    Examples
    --------
    >>> E = interpolate_fixed_centres(0.25, [0.0, 1.0], [[0, 0, 0, 0, 0, 0], [4.0, 0, 0, 0, 0, 0]])
    >>> float(E[0, 0])
    1.0
    """
    t = np.atleast_1d(_array(t, "t", ndim=(0, 1)))
    tf = _times(t_fixed)
    E = _array(eo_fixed, "eo_fixed", (6,), 2)
    if len(E) != len(tf):
        raise InputError(f"eo_fixed has {len(E)} rows for {len(tf)} fixed times")
    if np.any(t < tf[0] - 1e-12 * max(1.0, abs(tf[0]))) or np.any(t > tf[-1] + 1e-12 * max(1.0, abs(tf[-1]))):
        raise InputError("times outside the span of the fixed projection centres (no extrapolation)")
    k, c = _fixed_weights(t, tf)
    d = _delta(c, k, measured, measured_fixed, len(t), len(tf))
    return c[:, None] * E[k] + (1 - c[:, None]) * E[k + 1] - d


class TabulatedLineScanner:
    """A line (pushbroom) scanner whose EO is tabulated per line — §8.15 (after triangulation), §8.16.

    A thin millimetre-unit front of the one scanner model, :class:`photolib.pushbroom.Pushbroom`
    with an :class:`photolib.pushbroom.EOTable` (``sensor``): row r of the image is the line exposed
    at time r (in line periods); its EO is the table row r (linearly interpolated between rows for a
    fractional r, extrapolated linearly by the end segments outside the table). Column c lies on the
    CCD line at y = (c − (n_cols − 1)/2)·pixel_size (mm, origin at the line's middle); the line is
    offset along track by ``x_line`` in the focal plane, so the sensor ray is (x_line, y, −f), (8.2.1).

    Parameters
    ----------
    eo : (n_lines, 6) array
        (X_S, Y_S, Z_S, ω, α, κ) of every line, n_lines ≥ 2.
    f : float
        Focal length (mm).
    pixel_size : float
        Pixel size along the CCD (mm).
    n_cols : int
        Pixels per line.
    x_line : float
        Along-track offset of the CCD line (mm).
    order : {"wak", "kaw"}
        Rotation sequence of the table's angles.

    Attributes
    ----------
    shape : tuple
        (n_lines, n_cols).
    sensor : photolib.pushbroom.Pushbroom
        The sensor in metres (line period 1), usable wherever a Pushbroom is.

    Raises
    ------
    InputError
        NaN/inf, wrong shapes, non-positive sizes.

    References
    ----------
    Chibunichev (2022), §8.2, (8.2.1)–(8.2.2); §8.5, (8.5.1)–(8.5.2); §8.15; §8.16, (8.16.1).

    Examples
    --------
    >>> eo = np.column_stack([np.arange(100.0), np.zeros(100), np.full(100, 1000.0), np.zeros((100, 3))])
    >>> s = TabulatedLineScanner(eo, 100.0, 0.01, 101)
    >>> X, Y = s.ground(10.0, 60.0, 0.0)
    >>> float(X), float(Y)
    (10.0, 1.0)
    >>> [float(v) for v in s.project(X, Y, 0.0)]
    [10.0, 60.0]
    """

    def __init__(self, eo, f, pixel_size, n_cols, x_line=0.0, order="wak"):
        from .pushbroom import EOTable, Pushbroom
        self.f = _positive(f, "f")
        self.pixel_size = _positive(pixel_size, "pixel_size")
        if isinstance(n_cols, (bool, np.bool_)) or not isinstance(n_cols, (int, np.integer)) or n_cols < 2:
            raise InputError(f"n_cols must be an integer ≥ 2, got {n_cols!r}")
        self.n_cols = int(n_cols)
        self.x_line = float(_array(x_line, "x_line", ndim=0))
        self.order = _order(order)
        table = EOTable(_array(eo, "eo", (6,), 2), 1.0, self.order)
        self.eo = table.table
        self.sensor = Pushbroom(self.f / 1000, self.pixel_size / 1000, self.n_cols, 1.0, table,
                                x_offsets=self.x_line / 1000)

    @property
    def shape(self):
        return (len(self.eo), self.n_cols)

    def line_eo(self, rows):
        """EO of (fractional) rows: S (…, 3) and A (…, 3, 3), linear between table rows."""
        rows = np.asarray(rows, dtype=np.float64)
        S, A = self.sensor.eo.at(rows)
        return S.reshape(rows.shape + (3,)), A.reshape(rows.shape + (3, 3))

    def ground(self, rows, cols, Z):
        """Object X, Y of image positions on the heights Z, (8.5.1)/(8.16.1).

        Returns (X, Y) arrays of the broadcast shape; NaN for rays that do not reach Z.
        """
        return self.sensor.ground(rows, cols, Z, invalid="nan")

    def project(self, X, Y, Z, *, tol=1e-9, max_iter=60):
        """Image (rows, cols) of object points, (8.5.2): a bracketed 1-D search for the line.

        :meth:`photolib.pushbroom.Pushbroom.project` with ``bracket=True``: the line is bracketed
        on a coarse scan of the table and refined by safeguarded Newton steps. Points that no line
        sees (or behind the sensor) get NaN (see :meth:`projector`).
        """
        return self.sensor.project(X, Y, Z, tol=tol, max_iter=max_iter, bracket=True)

    def projector(self, outside=-1e9):
        """``project(X, Y, Z) -> (rows, cols)`` for :func:`photolib.rectify.orthorectify`: points no
        line sees get the position ``outside`` (far off the image, so the engine fills them)."""
        def project(X, Y, Z):
            r, c = self.project(X, Y, Z)
            bad = ~(np.isfinite(r) & np.isfinite(c))
            return np.where(bad, outside, r), np.where(bad, outside, c)
        return project


@dataclass(frozen=True)
class ThreeLineBlock:
    """A simulated three-line scanner strip with GNSS/IMU, made by :func:`three_line_block`.

    Attributes
    ----------
    t : (n_lines,) ndarray
        Line times (s).
    eo_true, eo_measured : (n_lines, 6) ndarray
        True line EO and the GNSS/IMU measurement (true − offset, plus noise).
    offset : (6,) ndarray
        The constant difference true − measured (position m, angles rad).
    fixed : (K,) ndarray
        Line indices of the fixed projection centres.
    f, pixel_size : float
        Focal length and pixel size (mm).
    n_cols : int
        Pixels per line.
    x_lines : (3,) ndarray
        Along-track offsets of the forward, nadir and backward lines (mm).
    points : (P, 3) ndarray
        True object points.
    control : (P,) bool ndarray
        Control points (the rest are tie points).
    view, point : (o,) int ndarray
        Line (0 forward, 1 nadir, 2 backward) and point of each observation.
    rows : (o,) ndarray
        Observed (fractional) line of each observation.
    xy : (o, 2) ndarray
        Observed image coordinates (mm): x = the line's offset, y along the CCD (with noise).

    References
    ----------
    Chibunichev (2022), §8.15, Figs. 8.30–8.32.

    Examples
    --------
    >>> ThreeLineBlock.__name__
    'ThreeLineBlock'
    """

    t: np.ndarray
    eo_true: np.ndarray
    eo_measured: np.ndarray
    offset: np.ndarray
    fixed: np.ndarray
    f: float
    pixel_size: float
    n_cols: int
    x_lines: np.ndarray
    points: np.ndarray
    control: np.ndarray
    view: np.ndarray
    point: np.ndarray
    rows: np.ndarray
    xy: np.ndarray

    def scanners(self, which="true"):
        """The three :class:`TabulatedLineScanner` of the strip (``"true"`` or ``"measured"`` EO)."""
        eo = self.eo_true if which == "true" else self.eo_measured
        return [TabulatedLineScanner(eo, self.f, self.pixel_size, self.n_cols, x) for x in self.x_lines]

    def at_rows(self, table):
        """Rows of a per-line table (e.g. the EO) interpolated at the observed rows."""
        table = np.asarray(table, dtype=np.float64)
        r = np.clip(self.rows, 0, len(table) - 1)
        i = np.clip(np.floor(r).astype(np.int64), 0, len(table) - 2)
        w = (r - i)[:, None] if table.ndim == 2 else r - i
        return (1 - w) * table[i] + w * table[i + 1]


def three_line_block(*, seed=0, n_points=24, n_control=6, duration=30.0, line_rate=10.0, fixed_every=5.0,
                     offset=(0.6, -0.4, 0.8, 1.0e-3, -8.0e-4, 1.5e-3), wiggle=(0.3, 2.0e-4),
                     sigma_image=0.0, sigma_gnss=0.0, sigma_imu=0.0) -> ThreeLineBlock:
    """Simulate a small three-line scanner strip with a GNSS/IMU trajectory, §8.15.

    Flight along X at 50 m/s, 1000 m above a hilly terrain (≈ ±40 m); f = 62.5 mm, lines at
    x = +20 (forward), 0 (nadir), −20 mm (backward), 801 pixels of 0.05 mm. The true trajectory is
    smooth plus a high-frequency wiggle (amplitudes ``wiggle`` = (m, rad), 0.7–1.3 Hz); the
    measured one is the true one minus a constant ``offset`` (plus white noise). Points lie where
    all three lines see them; every point is observed once on each line.

    Parameters
    ----------
    seed : int
        Random seed.
    n_points, n_control : int
        Number of points and how many of them are control points (n_control ≤ n_points).
    duration, line_rate, fixed_every : float
        Strip duration (s), lines per second, spacing of the fixed projection centres (s).
    offset : (6,) sequence
        True − measured EO (m, m, m, rad, rad, rad).
    wiggle : (2,) sequence
        Amplitudes of the high-frequency position (m) and attitude (rad) motion.
    sigma_image, sigma_gnss, sigma_imu : float
        Noise of the image coordinates (mm), GNSS positions (m), IMU angles (rad).

    Returns
    -------
    ThreeLineBlock

    Raises
    ------
    InputError
        Non-positive sizes, too few points, more control than points, negative noise.

    References
    ----------
    Chibunichev (2022), §8.15, Figs. 8.30–8.32.

    Examples
    --------
    >>> b = three_line_block(n_points=6, n_control=3)
    >>> b.xy.shape, len(b.fixed)
    ((18, 2), 7)
    """
    for v, name in ((duration, "duration"), (line_rate, "line_rate"), (fixed_every, "fixed_every")):
        _positive(v, name)
    for v, name in ((sigma_image, "sigma_image"), (sigma_gnss, "sigma_gnss"), (sigma_imu, "sigma_imu")):
        if isinstance(v, (str, bytes)) or not np.isfinite(float(v)) or float(v) < 0:
            raise InputError(f"{name} must be a finite number ≥ 0, got {v!r}")
    if not isinstance(n_points, (int, np.integer)) or not isinstance(n_control, (int, np.integer)):
        raise InputError("n_points and n_control must be integers")
    if n_points < 1 or n_control < 0 or n_control > n_points:
        raise InputError(f"need 1 ≤ n_points and 0 ≤ n_control ≤ n_points, got {n_points}, {n_control}")
    off = _array(offset, "offset", (6,), 1)
    wig = _array(wiggle, "wiggle", (2,), 1)
    rng = np.random.default_rng(seed)
    n = int(round(duration * line_rate)) + 1
    t = np.arange(n) / line_rate
    step = int(round(fixed_every * line_rate))
    if step < 1 or step >= n:
        raise InputError("fixed_every must be at least one line and shorter than the strip")
    fixed = np.arange(0, n, step)
    if fixed[-1] != n - 1:
        fixed = np.append(fixed, n - 1)
    v = 50.0
    eo = np.column_stack([
        v * t + wig[0] * np.sin(2 * np.pi * 0.9 * t),
        3.0 * np.sin(0.1 * t) + wig[0] * np.sin(2 * np.pi * 1.1 * t + 1),
        1000.0 + 0.4 * t + wig[0] * np.sin(2 * np.pi * 0.7 * t + 2),
        0.01 * np.sin(0.2 * t) + wig[1] * np.sin(2 * np.pi * 1.3 * t),
        -0.005 + 0.004 * np.cos(0.15 * t) + wig[1] * np.sin(2 * np.pi * 0.8 * t + 1),
        0.02 + 0.002 * t + wig[1] * np.sin(2 * np.pi * 1.0 * t + 2),
    ])
    measured = eo - off
    measured[:, :3] += rng.normal(0, sigma_gnss, (n, 3)) if sigma_gnss else 0.0
    measured[:, 3:] += rng.normal(0, sigma_imu, (n, 3)) if sigma_imu else 0.0
    f, pix, ncol = 62.5, 0.05, 801
    x_lines = np.array([20.0, 0.0, -20.0])
    d = 1000.0 * 20.0 / f
    L = v * t[-1]
    X = rng.uniform(d + 0.08 * (L - 2 * d), L - d - 0.08 * (L - 2 * d), n_points)
    Y = rng.uniform(-280.0, 280.0, n_points)
    Z = 40.0 * np.sin(X / 230.0) * np.cos(Y / 170.0) + 10.0 * np.sin((X + Y) / 60.0)
    points = np.column_stack([X, Y, Z])
    scanners = [TabulatedLineScanner(eo, f, pix, ncol, x) for x in x_lines]
    view, point, rows, xy = [], [], [], []
    for i, s in enumerate(scanners):
        r, c = s.project(X, Y, Z)
        if not np.all(np.isfinite(r)) or np.any((c < 0) | (c > ncol - 1)):
            raise InputError("a simulated point falls outside a line's image (enlarge the strip)")
        view.append(np.full(n_points, i))
        point.append(np.arange(n_points))
        rows.append(r)
        yv = (c - (ncol - 1) / 2) * pix + (rng.normal(0, sigma_image, n_points) if sigma_image else 0.0)
        xy.append(np.column_stack([np.full(n_points, x_lines[i]), yv]))
    control = np.zeros(n_points, bool)
    control[rng.choice(n_points, n_control, replace=False)] = True
    return ThreeLineBlock(t, eo, measured, off, fixed, f, pix, ncol, x_lines, points, control,
                          np.concatenate(view), np.concatenate(point), np.concatenate(rows), np.concatenate(xy))


@dataclass(frozen=True)
class FixedCentreAdjustment:
    """Result of :func:`fixed_centre_triangulation`.

    Attributes
    ----------
    eo_fixed : (K, 6) ndarray
        Adjusted EO of the fixed projection centres.
    points : (P, 3) ndarray
        Adjusted points (control points as given).
    offset : (6,) ndarray or None
        Estimated constant offset (adjusted − measured) of the GNSS/IMU EO.
    adjustment : photolib.lsq.Adjustment
        The least-squares result (μ, m_j, iterations, residuals).

    References
    ----------
    Chibunichev (2022), §8.15, eq. (8.15.1), (8.15.2).

    Examples
    --------
    >>> FixedCentreAdjustment.__name__
    'FixedCentreAdjustment'
    """

    eo_fixed: np.ndarray
    points: np.ndarray
    offset: np.ndarray | None
    adjustment: object


def fixed_centre_triangulation(t, xy, point, t_fixed, points0, *, f, control=None, measured=None,
                               measured_fixed=None, eo_fixed0=None, sigma_image=0.005, sigma_position=0.1,
                               sigma_attitude=1e-4, estimate_offset=True, order="wak",
                               max_iter=30) -> FixedCentreAdjustment:
    """Aerial triangulation of scanner lines with fixed projection centres, (8.15.1)–(8.15.2).

    Unknowns: the EO of the fixed centres, the tie points and (``estimate_offset``) a constant
    offset b of the GNSS/IMU EO. Equations: the collinearity equations (8.15.1) of every
    observation with the line EO of (8.15.2) (weight 1/σ_image²), and, with measurements, the
    GNSS/IMU observation equations E_k − b − E_k^meas = v of every fixed centre (weights
    1/σ_position², 1/σ_attitude²). Control points are held fixed. Solved by
    :func:`photolib.lsq.gauss_newton`; partial derivatives from
    :func:`photolib.derivations.georef.fixed_centre_functions`.

    Parameters
    ----------
    t : (o,) array
        Time of every observation (its line's time).
    xy : (o, 2) array
        Observed image coordinates (mm) in the scanner frame (x = the CCD line's offset).
    point : (o,) int array
        Point index of every observation.
    t_fixed : (K,) array
        Times of the fixed centres (covering all ``t``).
    points0 : (P, 3) array
        Approximate points; the exact coordinates for control points.
    f : float
        Focal length (mm).
    control : (P,) bool array, optional
        Control points (default: none).
    measured, measured_fixed : (o, 6) and (K, 6) arrays, optional
        GNSS/IMU EO at the observation times and at the fixed centres.
    eo_fixed0 : (K, 6) array, optional
        Approximate fixed-centre EO (default ``measured_fixed``).
    sigma_image, sigma_position, sigma_attitude : float
        A-priori σ of the image coordinates (mm), GNSS positions (m), IMU angles (rad).
    estimate_offset : bool
        Add the constant offset b to the GNSS/IMU equations.
    order : {"wak", "kaw"}
        Rotation sequence.
    max_iter : int
        Gauss–Newton iterations allowed.

    Returns
    -------
    FixedCentreAdjustment

    Raises
    ------
    InputError
        NaN/inf, mismatched sizes, point indices out of range, neither ``measured_fixed`` nor
        ``eo_fixed0``, times outside the fixed centres, an observation on a control point only.
    DegenerateGeometryError
        A singular system (too few control points, a tie point on fewer than 2 lines).
    ConvergenceError
        No convergence.

    References
    ----------
    Chibunichev (2022), §8.15, eq. (8.15.1) and the interpolation formulas after it.

    Examples
    --------
    >>> b = three_line_block(n_points=12, n_control=6)
    >>> tf = b.t[b.fixed]
    >>> res = fixed_centre_triangulation(b.at_rows(b.t), b.xy, b.point, tf, b.points, f=b.f,
    ...     control=b.control, measured=b.at_rows(b.eo_measured), measured_fixed=b.eo_measured[b.fixed])
    >>> bool(np.abs(res.offset - b.offset).max() < 1e-6)
    True
    """
    from . import lsq
    from .derivations.georef import fixed_centre_functions

    t = _array(t, "t", ndim=1)
    xy = _array(xy, "xy", (2,), 2)
    o = len(t)
    if len(xy) != o:
        raise InputError(f"{o} times but {len(xy)} image observations")
    try:
        pt = np.asarray(point)
    except Exception:  # noqa: BLE001
        raise InputError("point must be an integer array") from None
    if pt.shape != (o,) or not np.issubdtype(pt.dtype, np.integer):
        raise InputError(f"point must be {o} integers, got shape {pt.shape} dtype {pt.dtype}")
    tf = _times(t_fixed)
    K = len(tf)
    P0 = _array(points0, "points0", (3,), 2)
    if pt.min() < 0 or pt.max() >= len(P0):
        raise InputError("a point index is outside points0")
    f = _positive(f, "f")
    ctrl = np.zeros(len(P0), bool) if control is None else np.asarray(control)
    if ctrl.shape != (len(P0),) or ctrl.dtype != bool:
        raise InputError(f"control must be a boolean array of {len(P0)} values")
    _order(order)
    sig_i, sig_p, sig_a = (_positive(v, n) for v, n in ((sigma_image, "sigma_image"),
                                                         (sigma_position, "sigma_position"),
                                                         (sigma_attitude, "sigma_attitude")))
    if np.any(t < tf[0] - 1e-9) or np.any(t > tf[-1] + 1e-9):
        raise InputError("observation times outside the span of the fixed projection centres")
    k, c = _fixed_weights(t, tf)
    delta = _delta(c, k, measured, measured_fixed, o, K)
    has_meas = measured_fixed is not None
    Mf = _array(measured_fixed, "measured_fixed", (6,), 2) if has_meas else None
    if eo_fixed0 is None:
        if not has_meas:
            raise InputError("give eo_fixed0 (approximate fixed-centre EO) when there are no GNSS/IMU data")
        E0 = Mf.copy()
    else:
        E0 = _array(eo_fixed0, "eo_fixed0", (6,), 2)
        if len(E0) != K:
            raise InputError(f"eo_fixed0 has {len(E0)} rows for {K} fixed centres")
    counts = np.bincount(pt, minlength=len(P0))
    free = ~ctrl
    if np.any(free & (counts < 2)):
        raise DegenerateGeometryError(f"tie point(s) {np.flatnonzero(free & (counts < 2)).tolist()} are seen "
                                      "on fewer than 2 lines")
    free_idx = np.flatnonzero(free)
    col_of = -np.ones(len(P0), np.int64)
    col_of[free_idx] = 6 * K + 3 * np.arange(free_idx.size)
    n_off = 6 if (estimate_offset and has_meas) else 0
    n = 6 * K + 3 * free_idx.size + n_off
    res_f, jac_f = fixed_centre_functions(order)
    data = np.column_stack([c, delta, np.full(o, f), xy])
    m_img = 2 * o
    m = m_img + (6 * K if has_meas else 0)
    if m < n:
        raise DegenerateGeometryError(f"{m} equations for {n} unknowns")
    weights = np.concatenate([np.full(m_img, 1 / sig_i ** 2)] +
                             ([np.tile(np.r_[np.full(3, 1 / sig_p ** 2), np.full(3, 1 / sig_a ** 2)], K)]
                              if has_meas else []))

    def unpack(x):
        E = x[:6 * K].reshape(K, 6)
        P = P0.copy()
        P[free_idx] = x[6 * K:6 * K + 3 * free_idx.size].reshape(-1, 3)
        b = x[6 * K + 3 * free_idx.size:] if n_off else np.zeros(6)
        return E, P, b

    rows_o = np.arange(o)

    def linearize(x):
        E, P, b = unpack(x)
        params = np.column_stack([E[k], E[k + 1], P[pt]])
        L_img = res_f(params, data)
        J = jac_f(params, data)
        B = np.zeros((m, n))
        for q in range(2):
            r = 2 * rows_o + q
            for j in range(6):
                B[r, 6 * k + j] += J[:, q, j]
                B[r, 6 * (k + 1) + j] += J[:, q, 6 + j]
            has = col_of[pt] >= 0
            for j in range(3):
                B[r[has], col_of[pt[has]] + j] = J[has, q, 12 + j]
        L = np.empty(m)
        L[:m_img] = L_img.ravel()
        if has_meas:
            i = np.arange(6 * K)
            B[m_img + i, i] = 1.0
            if n_off:
                B[m_img + i, n - 6 + (i % 6)] = -1.0
            L[m_img:] = (E - b - Mf).ravel()
        return B, L

    x0 = np.concatenate([E0.ravel(), P0[free_idx].ravel(), np.zeros(n_off)])
    tol = np.concatenate([np.tile([1e-6, 1e-6, 1e-6, 1e-10, 1e-10, 1e-10], K),
                          np.full(3 * free_idx.size, 1e-6), np.array([1e-6] * 3 + [1e-10] * 3)[:n_off]])
    adj = lsq.gauss_newton(linearize, x0, weights, tol=tol, max_iter=max_iter)
    E, P, b = unpack(adj.x)
    return FixedCentreAdjustment(E, P, b if n_off else None, adj)


# --------------------------------------------------------------------------- §8.16
@dataclass(frozen=True)
class DirectOrtho:
    """Result of :func:`direct_orthorectify`.

    Attributes
    ----------
    image : ndarray
        The orthophoto (mean brightness of the pixels that landed in each cell; NaN = hole).
    count : ndarray
        How many scanner pixels landed in each cell (0 = hole).
    iterations : int
        Monoplotting iterations of the slowest pixel.
    dropped : int
        Scanner pixels that left the DEM or did not converge.

    References
    ----------
    Chibunichev (2022), §8.16, Figs. 8.33–8.34.

    Examples
    --------
    >>> DirectOrtho.__name__
    'DirectOrtho'
    """

    image: np.ndarray
    count: np.ndarray
    iterations: int
    dropped: int

    @property
    def holes(self) -> np.ndarray:
        """Boolean map of the empty orthophoto pixels."""
        return self.count == 0


def _monoplot(ground, rows, cols, dem, dem_grid, tol, max_iter):
    from .rectify import dem_height
    Z = np.full(rows.shape, float(np.nanmean(dem)))
    X, Y = (np.asarray(v, dtype=np.float64) for v in ground(rows, cols, Z))
    if X.shape != rows.shape or Y.shape != rows.shape:
        raise InputError(f"ground() returned shapes {X.shape}, {Y.shape} for {rows.shape} positions")
    done = np.zeros(rows.shape, bool)
    it = 0
    for it in range(1, max_iter + 1):
        Z = dem_height(dem, dem_grid, X, Y, outside="nan")
        Xn, Yn = (np.asarray(v, dtype=np.float64) for v in ground(rows, cols, Z))
        with np.errstate(invalid="ignore"):
            done = (np.abs(Xn - X) < tol) & (np.abs(Yn - Y) < tol)
        X, Y = Xn, Yn
        if np.all(done | ~np.isfinite(X)):
            break
    ok = done & np.isfinite(X) & np.isfinite(Y)
    Z = dem_height(dem, dem_grid, np.where(ok, X, np.nan), np.where(ok, Y, np.nan), outside="nan")
    return X, Y, Z, ok & np.isfinite(Z), it


def direct_orthorectify(image, ground: Callable, dem, dem_grid, grid, *, tol=1e-3, max_iter=30) -> DirectOrtho:
    """Orthophoto of a scanner image by the direct method, §8.16.

    Every scanner pixel (row, col) is intersected with the DEM by the iteration of Fig. 8.34:
    Z₁ = mean DEM height, (X, Y) = ground(row, col, Z) ((8.16.1) with the pixel's own EO, or
    (8.16.2)), Z = DEM(X, Y) bilinearly, repeat until X and Y change by less than ``tol``. Its
    brightness is moved to the orthophoto pixel containing (X, Y) (the mean where several land).
    Pixels of the orthophoto that no scanner pixel reaches stay empty — the "holes" of §8.16;
    compare :func:`photolib.rectify.orthorectify` (inverse method, no holes).

    Parameters
    ----------
    image : (R, C) array
        The scanner image.
    ground : callable
        ``ground(rows, cols, Z) -> (X, Y)`` (e.g. :meth:`TabulatedLineScanner.ground`).
    dem : (r, c) array
        Heights on ``dem_grid``.
    dem_grid, grid : photolib.rectify.RasterGrid
        Grids of the DEM and of the orthophoto.
    tol : float
        Convergence tolerance in X and Y (m).
    max_iter : int
        Iterations allowed.

    Returns
    -------
    DirectOrtho

    Raises
    ------
    InputError
        NaN/inf or a non-2-D image, a bad DEM, grids that are not RasterGrid, a ``ground``
        returning wrong shapes.
    ConvergenceError
        No scanner pixel converged.

    References
    ----------
    Chibunichev (2022), §8.16, eqs. (8.16.1)–(8.16.2), Figs. 8.33–8.34; §7.7, (7.7.1).

    Examples
    --------
    >>> from photolib.rectify import RasterGrid
    >>> g = RasterGrid(-0.5, 0.5, 1.0, (4, 4))
    >>> flat = lambda r, c, Z: (np.asarray(c, float), -np.asarray(r, float))
    >>> o = direct_orthorectify(np.arange(16.0).reshape(4, 4), flat, np.zeros((4, 4)), g, g)
    >>> float(o.image[1, 2]), int(o.holes.sum())
    (6.0, 0)
    """
    from .rectify import RasterGrid
    img = _array(image, "image", ndim=2)
    if not isinstance(dem_grid, RasterGrid) or not isinstance(grid, RasterGrid):
        raise InputError("dem_grid and grid must be photolib.rectify.RasterGrid")
    dem = np.asarray(dem, dtype=np.float64)
    if dem.shape != dem_grid.shape:
        raise InputError(f"dem has shape {dem.shape}, its grid {dem_grid.shape}")
    if not np.any(np.isfinite(dem)):
        raise InputError("the DEM has no finite heights")
    _callable(ground, "ground")
    tol = _positive(tol, "tol")
    rows, cols = np.mgrid[0:img.shape[0], 0:img.shape[1]].astype(np.float64)
    X, Y, Z, ok, it = _monoplot(ground, rows, cols, dem, dem_grid, tol, int(max_iter))
    if not np.any(ok):
        raise ConvergenceError("no scanner pixel could be intersected with the DEM (outside it or no convergence)")
    r, c = grid.rowcol(X[ok], Y[ok])
    ri, ci = np.floor(np.asarray(r) + 0.5).astype(np.int64), np.floor(np.asarray(c) + 0.5).astype(np.int64)
    inside = (ri >= 0) & (ri < grid.shape[0]) & (ci >= 0) & (ci < grid.shape[1])
    flat = ri[inside] * grid.shape[1] + ci[inside]
    size = grid.shape[0] * grid.shape[1]
    count = np.bincount(flat, minlength=size).reshape(grid.shape)
    total = np.bincount(flat, weights=img[ok][inside], minlength=size).reshape(grid.shape)
    with np.errstate(invalid="ignore", divide="ignore"):
        out = np.where(count > 0, total / np.maximum(count, 1), np.nan)
    return DirectOrtho(out, count, it, int((~ok).sum()))


# --------------------------------------------------------------------------- §8.17
@dataclass(frozen=True)
class QuasiFrame:
    """A central-projection quasi-image made from scans, §8.17 (Fig. 8.38).

    Attributes
    ----------
    image : ndarray
        The quasi-image (NaN where no scan sees the ground point).
    count : ndarray
        Number of scans averaged in each pixel.
    centre : (3,) ndarray
        Projection centre S.
    angles : (3,) ndarray
        ω, α, κ (rad).
    f, pixel_size : float
        Focal length and pixel size (mm); x₀ = y₀ = 0.
    order : str
        Rotation sequence.

    References
    ----------
    Chibunichev (2022), §8.17, Fig. 8.38.

    Examples
    --------
    >>> QuasiFrame.__name__
    'QuasiFrame'
    """

    image: np.ndarray
    count: np.ndarray
    centre: np.ndarray
    angles: np.ndarray
    f: float
    pixel_size: float
    order: str

    def project(self, X, Y, Z):
        """(rows, cols) of object points in the quasi-image by the collinearity equations."""
        A = _rot(self.angles, self.order)
        P = np.stack(np.broadcast_arrays(*(np.asarray(v, dtype=np.float64) for v in (X, Y, Z))), axis=-1)
        u = (P - self.centre) @ A
        with np.errstate(divide="ignore", invalid="ignore"):
            x = -self.f * u[..., 0] / u[..., 2]
            y = -self.f * u[..., 1] / u[..., 2]
        h, w = self.image.shape
        return (h - 1) / 2 - y / self.pixel_size, x / self.pixel_size + (w - 1) / 2


def quasi_frame_image(scans, projectors, dem, dem_grid, centre, f, pixel_size, shape, *,
                      angles=(0.0, 0.0, 0.0), order="wak", method="bilinear", tol=1e-3,
                      max_iter=30) -> QuasiFrame:
    """The Resurs-P quasi-image: several scans re-projected into one central projection, §8.17.

    For every quasi-image pixel (x₀ = y₀ = 0, focal length ``f``, given centre and angles — the
    book: zero angles and the mean of the scanner centres) the ray is intersected with the DEM
    (the (8.16.1)/(7.7.1) iteration), the ground point is projected into every scan by its sensor
    model (RPCs (8.6.1) in the book, or the rigorous model) and the brightness averaged over the
    scans that see it (overlaps). The result's collinearity projection
    (:meth:`QuasiFrame.project`) of any DEM point therefore shows the same brightness as the
    scanner projection.

    Parameters
    ----------
    scans : sequence of (R, C) arrays
        Scan images.
    projectors : sequence of callables
        ``project(X, Y, Z) -> (rows, cols)`` of every scan.
    dem : (r, c) array
        Heights on ``dem_grid``.
    dem_grid : photolib.rectify.RasterGrid
        The DEM's grid.
    centre : (3,) array
        Projection centre of the quasi-image (m).
    f, pixel_size : float
        Focal length and pixel size (mm).
    shape : (int, int)
        Rows and columns of the quasi-image.
    angles : (3,) array
        ω, α, κ of the quasi-image (rad).
    order : {"wak", "kaw"}
        Rotation sequence.
    method : {'nearest', 'bilinear', 'bicubic'}
        Resampling of the scans.
    tol, max_iter
        Monoplotting tolerance (m) and iterations.

    Returns
    -------
    QuasiFrame

    Raises
    ------
    InputError
        No scans, mismatched lists, NaN/inf, bad shapes, a bad DEM or grid.

    References
    ----------
    Chibunichev (2022), §8.17, Fig. 8.38; (8.16.1); (7.7.1).

    Examples
    --------
    >>> from photolib.rectify import RasterGrid
    >>> g = RasterGrid(-5.0, 5.0, 1.0, (10, 10))
    >>> scan = np.arange(100.0).reshape(10, 10)
    >>> proj = lambda X, Y, Z: (4.5 - np.asarray(Y), np.asarray(X) + 4.5)
    >>> q = quasi_frame_image([scan], [proj], np.zeros((10, 10)), g, [0, 0, 100.0], 100.0, 1.0, (5, 5))
    >>> float(q.image[2, 2])
    49.5
    """
    from .rectify import RasterGrid, resample
    if isinstance(scans, np.ndarray):
        scans = [scans]
    try:
        scans = [_array(s, f"scan {i}", ndim=2) for i, s in enumerate(scans)]
        projectors = list(projectors)
    except TypeError:
        raise InputError("scans and projectors must be sequences") from None
    if not scans:
        raise InputError("no scans")
    if len(projectors) != len(scans):
        raise InputError(f"{len(scans)} scans but {len(projectors)} projectors")
    for p in projectors:
        _callable(p, "a projector")
    if not isinstance(dem_grid, RasterGrid):
        raise InputError("dem_grid must be a photolib.rectify.RasterGrid")
    dem = np.asarray(dem, dtype=np.float64)
    if dem.shape != dem_grid.shape or not np.any(np.isfinite(dem)):
        raise InputError(f"dem must be finite heights of shape {dem_grid.shape}")
    S = _array(centre, "centre", (3,), 1)
    ang = _array(angles, "angles", (3,), 1)
    f = _positive(f, "f")
    pix = _positive(pixel_size, "pixel_size")
    try:
        h, w = (int(v) for v in shape)
    except (TypeError, ValueError):
        raise InputError(f"shape must be (rows, cols), got {shape!r}") from None
    if h < 1 or w < 1:
        raise InputError(f"shape must be positive, got {shape!r}")
    _order(order)
    A = _rot(ang, order)
    rr, cc = np.mgrid[0:h, 0:w].astype(np.float64)
    x, y = (cc - (w - 1) / 2) * pix, ((h - 1) / 2 - rr) * pix
    W = np.stack([x, y, np.full(x.shape, -f)], axis=-1) @ A.T

    def ground(rows, cols, Z):
        with np.errstate(divide="ignore", invalid="ignore"):
            N = (Z - S[2]) / W[..., 2]
        N = np.where(N > 0, N, np.nan)
        return S[0] + N * W[..., 0], S[1] + N * W[..., 1]

    X, Y, Z, ok, _ = _monoplot(ground, rr, cc, dem, dem_grid, _positive(tol, "tol"), int(max_iter))
    total = np.zeros((h, w))
    count = np.zeros((h, w), np.int64)
    for scan, proj in zip(scans, projectors):
        r, c = (np.asarray(v, dtype=np.float64) for v in proj(np.where(ok, X, 0.0), np.where(ok, Y, 0.0),
                                                              np.where(ok, Z, 0.0)))
        if r.shape != (h, w) or c.shape != (h, w):
            raise InputError(f"a projector returned shape {r.shape} for {(h, w)} points")
        good = ok & np.isfinite(r) & np.isfinite(c)
        v = np.full((h, w), np.nan)
        v[good] = resample(scan, r[good], c[good], method)
        good &= np.isfinite(v)
        total[good] += v[good]
        count[good] += 1
    with np.errstate(invalid="ignore", divide="ignore"):
        img = np.where(count > 0, total / np.maximum(count, 1), np.nan)
    return QuasiFrame(img, count, S, ang, f, pix, order)


def scan_voxel_cost(images, projectors, X, Y, Z, *, method="bilinear") -> np.ndarray:
    """The voxel cost C(X, Y, Z) of (8.17.1) over scans: min over scan pairs of |d¹ − d²|.

    Every voxel is projected into every scan by its sensor model (RPCs (8.6.1) in the book, or a
    rigorous model), the brightness resampled, and the smallest absolute difference over the
    pairs of scans that both see it kept (the book's choice, pitfall 16; the printed signed
    difference d¹ − d² is an erratum). Voxels seen by fewer than two scans get the largest cost
    (the scans' grey range).

    Parameters
    ----------
    images : sequence of (R, C) arrays
        At least two scans.
    projectors : sequence of callables
        ``project(X, Y, Z) -> (rows, cols)`` of every scan.
    X, Y, Z : 1-D arrays
        Node coordinates of the voxel grid, increasing with constant steps ΔX, ΔY, ΔZ.
    method : {'nearest', 'bilinear', 'bicubic'}
        Resampling.

    Returns
    -------
    numpy.ndarray
        float32 (len(Y), len(X), len(Z)) — the layout of :func:`photolib.sgm.voxel_cost_volume`.

    Raises
    ------
    InputError
        Fewer than 2 scans, mismatched lists, NaN/inf, bad grids.

    References
    ----------
    Chibunichev (2022), §8.17, eq. (8.17.1) (with |·|); §6.5, (6.5.1).

    Examples
    --------
    >>> img = np.random.default_rng(0).uniform(0, 255, (20, 20))
    >>> p = lambda X, Y, Z: (10 - np.asarray(Y), np.asarray(X) + 10)
    >>> C = scan_voxel_cost([img, img], [p, p], np.arange(-3, 4.0), np.arange(-3, 4.0), [0.0, 1.0])
    >>> C.shape, float(C.max())
    ((7, 7, 2), 0.0)
    """
    from .rectify import resample
    from .sgm import _grid_axis
    if isinstance(images, np.ndarray):
        raise InputError("images must be a sequence of at least two scans")
    try:
        images = [_array(s, f"scan {i}", ndim=2) for i, s in enumerate(images)]
        projectors = list(projectors)
    except TypeError:
        raise InputError("images and projectors must be sequences") from None
    if len(images) < 2:
        raise InputError(f"the voxel cost needs at least 2 scans, got {len(images)}")
    if len(projectors) != len(images):
        raise InputError(f"{len(images)} scans but {len(projectors)} projectors")
    for p in projectors:
        _callable(p, "a projector")
    X, Y, Z = _grid_axis(X, "X"), _grid_axis(Y, "Y"), _grid_axis(Z, "Z")
    GX, GY = np.meshgrid(X, Y)
    worst = float(max(max(np.ptp(im) for im in images), 1.0))
    C = np.empty((Y.size, X.size, Z.size), np.float32)
    per = max(1, 200_000 // GX.size)                 # Z levels per projector call
    for k0 in range(0, Z.size, per):
        zs = Z[k0:k0 + per]
        shape = GX.shape + (zs.size,)
        PX = np.broadcast_to(GX[..., None], shape)
        PY = np.broadcast_to(GY[..., None], shape)
        PZ = np.broadcast_to(zs, shape)
        D = []
        for im, proj in zip(images, projectors):
            r, c = (np.asarray(v, dtype=np.float64) for v in proj(PX, PY, PZ))
            if r.shape != shape or c.shape != shape:
                raise InputError(f"a projector returned shape {r.shape} for {shape} points")
            v = np.full(shape, np.nan)
            good = np.isfinite(r) & np.isfinite(c)
            v[good] = resample(im, r[good], c[good], method)
            D.append(v)
        best = np.full(shape, np.inf)
        for i in range(len(D)):
            for j in range(i + 1, len(D)):
                with np.errstate(invalid="ignore"):
                    best = np.fmin(best, np.abs(D[i] - D[j]))
        C[:, :, k0:k0 + zs.size] = np.where(np.isfinite(best), best, worst)
    return C


def object_space_sgm(images, projectors, X, Y, Z, *, P1=None, P2=None, paths=8, subpixel=True,
                     method="bilinear"):
    """A DSM from scans by semi-global matching in object space, (8.17.1)–(8.17.4).

    The voxel cost of :func:`scan_voxel_cost`, the path costs L_r over the X–Y grid with the Z
    levels as labels (8.17.3) (|Z − Z_q| in steps ΔZ, penalties P₁/P₂ of (8.17.2)), their sum
    S (8.17.4) (:func:`photolib.sgm.aggregate_costs`) and Z = argmin_Z S per node
    (:func:`photolib.sgm.winner_takes_all`).

    Parameters
    ----------
    images, projectors, X, Y, Z, method
        As in :func:`scan_voxel_cost`.
    P1, P2 : float, optional
        Penalties in cost units (default 0.02 and 0.2 of the scans' grey range).
    paths : {8, 4, 2}
        Path directions (the book: 8).
    subpixel : bool
        Parabola refinement of Z between levels.

    Returns
    -------
    photolib.sgm.VoxelSGMResult
        Z (len(Y), len(X)), Z_wta, X, Y, levels.

    Raises
    ------
    InputError
        As :func:`scan_voxel_cost`, plus bad penalties or paths.

    References
    ----------
    Chibunichev (2022), §8.17, eqs. (8.17.1)–(8.17.4); §6.5.

    Examples
    --------
    >>> img = np.random.default_rng(0).uniform(0, 255, (20, 20))
    >>> p = lambda X, Y, Z: (10 - np.asarray(Y), np.asarray(X) + 10)
    >>> r = object_space_sgm([img, img], [p, p], np.arange(-3, 4.0), np.arange(-3, 4.0), [0.0, 1.0, 2.0])
    >>> r.Z.shape
    (7, 7)
    """
    from .sgm import VoxelSGMResult, aggregate_costs, winner_takes_all
    C = scan_voxel_cost(images, projectors, X, Y, Z, method=method)
    grey = float(max(max(np.ptp(np.asarray(im, dtype=float)) for im in images), 1e-12))
    P1 = 0.02 * grey if P1 is None else P1
    P2 = 0.2 * grey if P2 is None else P2
    S = aggregate_costs(C, P1, P2, paths=paths)
    Zl = np.asarray(Z, dtype=np.float64)
    dz = Zl[1] - Zl[0]
    return VoxelSGMResult(Zl[0] + dz * winner_takes_all(S, subpixel=subpixel),
                          Zl[0] + dz * winner_takes_all(C, subpixel=subpixel),
                          np.asarray(X, float), np.asarray(Y, float), Zl)
