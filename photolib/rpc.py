"""Rational polynomial coefficients (RPC) of satellite images — Chapter 8, §8.5 and §8.18.

The RPC model (Chibunichev 2022, §8.5, eqs. (8.5.6)–(8.5.9)) replaces the rigorous pushbroom
sensor model by ratios of cubic polynomials of the ground coordinates. This module implements

* :class:`RPC`, the 90 numbers of a model: offsets and scales of the five normalised variables
  (line, sample, latitude, longitude, height) and the four 20-term polynomials in the standard
  NITF RPC00B term order (the order the book prints in (8.5.8)/(8.5.9) with X = L = longitude,
  Y = P = latitude, Z = H = height), read from OSSIM ``.geom`` text and from GDAL's ``RPC``
  metadata domain and written back to it;
* :func:`project`, ground → image, eq. (8.5.7) with (8.5.8)/(8.5.9);
* :func:`locate`, image + height → ground, by the Newton iteration of §8.18, eq. (8.18.1).

Conventions (the book leaves them open; these are RPC00B's and GDAL's):

* every variable is normalised, ``(value - offset) / scale``; latitude and longitude in degrees,
  height in metres above the **ellipsoid** (WGS 84), line and sample in pixels;
* image coordinates are (row, col) = (line, sample) with (0, 0) the **centre** of the first
  pixel. GDAL's RPC transformer reports pixel-corner coordinates: its values are ours + 0.5;
* a crop whose first pixel is at (row0, col0) of the full scene has the RPC
  ``rpc.shifted(row0, col0)`` (line and sample offsets reduced by the crop offset).

Only numpy is needed; no GDAL or rasterio.
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np

from . import _checks
from .errors import ConvergenceError, DegenerateGeometryError, InputError

__all__ = ["RPC", "RPC00B_TERMS", "project", "locate"]

#: The 20 monomials of the RPC00B cubic polynomial in their standard order (L = normalised
#: longitude, P = normalised latitude, H = normalised height); the same order as the book's
#: (8.5.8) with X = L, Y = P, Z = H.
RPC00B_TERMS = ("1", "L", "P", "H", "L*P", "L*H", "P*H", "L**2", "P**2", "H**2",
                "P*L*H", "L**3", "L*P**2", "L*H**2", "L**2*P", "P**3", "P*H**2",
                "L**2*H", "P**2*H", "H**3")

_SCALARS = ("line_off", "samp_off", "lat_off", "long_off", "height_off",
            "line_scale", "samp_scale", "lat_scale", "long_scale", "height_scale")
_POLYS = ("line_num_coeff", "line_den_coeff", "samp_num_coeff", "samp_den_coeff")
_DENOMINATOR_FLOOR = 1e-8          # |normalised denominator| below this: the model is singular there


def _terms(L, P, H):
    """The 20 RPC00B monomials, stacked on a new last axis."""
    one = np.ones(np.broadcast(L, P, H).shape)
    return np.stack(np.broadcast_arrays(
        one, L, P, H, L * P, L * H, P * H, L * L, P * P, H * H,
        P * L * H, L ** 3, L * P * P, L * H * H, L * L * P, P ** 3, P * H * H,
        L * L * H, P * P * H, H ** 3), axis=-1)


def _terms_dL(L, P, H):
    """∂/∂L of the 20 monomials."""
    z = np.zeros(np.broadcast(L, P, H).shape)
    one = z + 1.0
    return np.stack(np.broadcast_arrays(
        z, one, z, z, P, H, z, 2 * L, z, z,
        P * H, 3 * L * L, P * P, H * H, 2 * L * P, z, z,
        2 * L * H, z, z), axis=-1)


def _terms_dP(L, P, H):
    """∂/∂P of the 20 monomials."""
    z = np.zeros(np.broadcast(L, P, H).shape)
    one = z + 1.0
    return np.stack(np.broadcast_arrays(
        z, z, one, z, L, z, H, z, 2 * P, z,
        L * H, z, 2 * L * P, z, L * L, 3 * P * P, H * H,
        z, 2 * P * H, z), axis=-1)


def _float(value, name):
    return _checks.number(value, name, not_a_number="RPC {name} must be a number, got {value!r}",
                          out_of_range="RPC {name} must be a finite number, got {value!r}")


@dataclass(frozen=True)
class RPC:
    """A rational polynomial camera model (RPC00B), eqs. (8.5.6)–(8.5.9).

    ``line = line_num(L, P, H) / line_den(L, P, H) * line_scale + line_off`` and the same for the
    sample, where ``L = (lon - long_off) / long_scale``, ``P = (lat - lat_off) / lat_scale``,
    ``H = (height - height_off) / height_scale`` and each polynomial is ``coeff · terms`` with the
    20 monomials in :data:`RPC00B_TERMS` order:
    1, L, P, H, LP, LH, PH, L², P², H², PLH, L³, LP², LH², L²P, P³, PH², L²H, P²H, H³.

    Parameters
    ----------
    line_off, samp_off : float
        Offsets of the image line (row) and sample (column), pixels; (0, 0) is the centre of
        the first pixel.
    lat_off, long_off : float
        Offsets of latitude and longitude, degrees.
    height_off : float
        Offset of the ellipsoidal height, metres.
    line_scale, samp_scale, lat_scale, long_scale, height_scale : float
        The matching scales (finite, > 0).
    line_num_coeff, line_den_coeff, samp_num_coeff, samp_den_coeff : sequence of 20 float
        The four polynomials in RPC00B order (stored as tuples of floats).

    Raises
    ------
    InputError
        A value that is not a finite number, a scale ≤ 0, a polynomial without exactly 20
        finite coefficients, or a denominator that is identically zero.

    References
    ----------
    Chibunichev (2022), §8.5, eqs. (8.5.6)–(8.5.9). NITF STDI-0002, RPC00B tagged record
    extension (term order and normalisation).

    Examples
    --------
    A toy camera: line = 100 + 50 P, sample = 200 + 80 L (pixels).

    >>> num = lambda k: [0.0] * k + [1.0] + [0.0] * (19 - k)
    >>> rpc = RPC(line_off=100, samp_off=200, lat_off=45, long_off=5, height_off=0,
    ...           line_scale=50, samp_scale=80, lat_scale=0.01, long_scale=0.01, height_scale=500,
    ...           line_num_coeff=num(2), line_den_coeff=num(0),
    ...           samp_num_coeff=num(1), samp_den_coeff=num(0))
    >>> rpc.line_off, len(rpc.line_num_coeff)
    (100.0, 20)
    """

    line_off: float
    samp_off: float
    lat_off: float
    long_off: float
    height_off: float
    line_scale: float
    samp_scale: float
    lat_scale: float
    long_scale: float
    height_scale: float
    line_num_coeff: tuple
    line_den_coeff: tuple
    samp_num_coeff: tuple
    samp_den_coeff: tuple

    def __post_init__(self):
        for name in _SCALARS:
            value = _float(getattr(self, name), name)
            if name.endswith("_scale") and value <= 0:
                raise InputError(f"RPC {name} must be positive, got {value!r}")
            object.__setattr__(self, name, value)
        for name in _POLYS:
            raw = getattr(self, name)
            if isinstance(raw, (str, bytes)) or raw is None:
                raise InputError(f"RPC {name} must be a sequence of 20 numbers, got {type(raw).__name__}")
            try:
                arr = np.asarray(raw, dtype=float)
            except (TypeError, ValueError) as exc:
                raise InputError(f"RPC {name} must be 20 numbers: {exc}") from exc
            if arr.shape != (20,):
                raise InputError(f"RPC {name} must hold exactly 20 coefficients, got shape {arr.shape}")
            if not np.all(np.isfinite(arr)):
                raise InputError(f"RPC {name} contains NaN or inf")
            if name.endswith("den_coeff") and not np.any(arr):
                raise InputError(f"RPC {name} is identically zero: the ratio is undefined")
            object.__setattr__(self, name, tuple(float(v) for v in arr))

    # ------------------------------------------------------------------ readers and writers
    @classmethod
    def from_ossim_geom(cls, path):
        """Read an RPC from an OSSIM ``.geom`` keyword list (``key:  value`` lines).

        Keys used: ``line_off``, ``samp_off``, ``lat_off``, ``long_off``, ``height_off``, the
        five ``*_scale``, and ``line_num_coeff_00`` … ``samp_den_coeff_19``; ``polynomial_format``
        must be ``B`` (RPC00B) when present. Keys may carry a prefix (``image0.line_off``).

        Parameters
        ----------
        path : str or os.PathLike
            The ``.geom`` file.

        Returns
        -------
        RPC
            The model of the full scene described by the file.

        Raises
        ------
        InputError
            A missing or unreadable file, a missing key, a value that is not a number, or a
            polynomial format other than RPC00B.

        References
        ----------
        Chibunichev (2022), §8.5, eqs. (8.5.6)–(8.5.9); OSSIM ``ossimRpcModel`` keyword list.

        Examples
        --------
        >>> import os, tempfile
        >>> lines = [f"{k}:  {v}" for k, v in dict(line_off=10, samp_off=20, lat_off=45,
        ...          long_off=5, height_off=0, line_scale=10, samp_scale=20, lat_scale=0.1,
        ...          long_scale=0.1, height_scale=100).items()]
        >>> for poly, hot in [("line_num", 2), ("line_den", 0), ("samp_num", 1), ("samp_den", 0)]:
        ...     lines += [f"{poly}_coeff_{i:02d}:  {float(i == hot)}" for i in range(20)]
        >>> with tempfile.TemporaryDirectory() as folder:
        ...     path = os.path.join(folder, "toy.geom")
        ...     with open(path, "w") as f:
        ...         _ = f.write("\\n".join(["type:  ossimRpcModel", "polynomial_format:  B"] + lines))
        ...     rpc = RPC.from_ossim_geom(path)
        >>> rpc.samp_scale, rpc.line_num_coeff[2]
        (20.0, 1.0)
        """
        if isinstance(path, (bytes, bytearray)) or not isinstance(path, (str, os.PathLike)):
            raise InputError(f"path must be a str or os.PathLike, got {type(path).__name__}")
        path = Path(path)
        try:
            text = path.read_text(encoding="utf-8", errors="replace")
        except OSError as exc:
            raise InputError(f"cannot read the OSSIM .geom file {path}: {exc}") from exc
        values = {}
        for line in text.splitlines():
            key, sep, value = line.partition(":")
            if sep:
                values[key.strip().rpartition(".")[2].lower()] = value.strip()
        fmt = values.get("polynomial_format", "B").strip().upper()
        if fmt != "B":
            raise InputError(f"{path}: polynomial_format {fmt!r} is not RPC00B ('B'); RPC00A is not supported")
        kwargs = {}
        for name in _SCALARS:
            if name not in values:
                raise InputError(f"{path}: the key {name!r} is missing (not an RPC .geom file?)")
            kwargs[name] = _parse_number(values[name], f"{path.name}: {name}")
        for name in _POLYS:
            coeffs = []
            for i in range(20):
                key = f"{name}_{i:02d}"
                if key not in values:
                    raise InputError(f"{path}: the key {key!r} is missing (not an RPC .geom file?)")
                coeffs.append(_parse_number(values[key], f"{path.name}: {key}"))
            kwargs[name] = coeffs
        return cls(**kwargs)

    @classmethod
    def from_gdal_metadata(cls, metadata):
        """Build an RPC from GDAL's ``RPC`` metadata domain (as ``rasterio``'s ``RPC.to_gdal()``).

        Parameters
        ----------
        metadata : mapping
            Keys ``LINE_OFF``, ``SAMP_OFF``, ``LAT_OFF``, ``LONG_OFF``, ``HEIGHT_OFF``, the five
            ``*_SCALE`` and ``LINE_NUM_COEFF``, ``LINE_DEN_COEFF``, ``SAMP_NUM_COEFF``,
            ``SAMP_DEN_COEFF`` (case-insensitive). Values are strings (the polynomials: 20
            space-separated numbers) or numbers / sequences of numbers. Other keys (``ERR_BIAS``,
            ``MIN_LONG`` …) are ignored.

        Returns
        -------
        RPC

        Raises
        ------
        InputError
            Not a mapping, a missing key, or a value that is not a number.

        References
        ----------
        Chibunichev (2022), §8.5, eqs. (8.5.6)–(8.5.9); GDAL RFC 22 (RPC georeferencing).

        Examples
        --------
        >>> poly = lambda k: " ".join("1" if i == k else "0" for i in range(20))
        >>> md = {"LINE_OFF": "100", "SAMP_OFF": "200", "LAT_OFF": "45", "LONG_OFF": "5",
        ...       "HEIGHT_OFF": "0", "LINE_SCALE": "50", "SAMP_SCALE": "80", "LAT_SCALE": "0.01",
        ...       "LONG_SCALE": "0.01", "HEIGHT_SCALE": "500", "LINE_NUM_COEFF": poly(2),
        ...       "LINE_DEN_COEFF": poly(0), "SAMP_NUM_COEFF": poly(1), "SAMP_DEN_COEFF": poly(0)}
        >>> RPC.from_gdal_metadata(md).lat_scale
        0.01
        """
        if not hasattr(metadata, "items"):
            raise InputError(f"metadata must be a mapping (GDAL's RPC domain), got {type(metadata).__name__}")
        upper = {str(k).upper(): v for k, v in metadata.items()}
        kwargs = {}
        for name in _SCALARS + _POLYS:
            key = name.upper()
            if key not in upper:
                raise InputError(f"the RPC metadata lacks the key {key!r}")
            value = upper[key]
            if name in _POLYS:
                if isinstance(value, str):
                    value = [_parse_number(v, key) for v in value.split()]
                kwargs[name] = value
            else:
                if isinstance(value, str):
                    value = _parse_number(value.split()[0] if value.split() else value, key)
                kwargs[name] = value
        return cls(**kwargs)

    def to_gdal_metadata(self):
        """The dictionary of GDAL's ``RPC`` metadata domain (all values strings, exact round trip).

        Returns
        -------
        dict of str to str
            ``LINE_OFF``, ``SAMP_OFF``, ``LAT_OFF``, ``LONG_OFF``, ``HEIGHT_OFF``, the five
            ``*_SCALE`` as numbers, and ``LINE_NUM_COEFF``, ``LINE_DEN_COEFF``,
            ``SAMP_NUM_COEFF``, ``SAMP_DEN_COEFF`` as 20 space-separated numbers each, written
            with ``repr`` so that reading them back gives the same floats.

        Raises
        ------
        None
            Nothing: the fields were validated when the RPC was built.

        References
        ----------
        Chibunichev (2022), §8.5, eqs. (8.5.6)–(8.5.9); GDAL RFC 22 (RPC georeferencing).

        Examples
        --------
        >>> rpc = RPC.from_gdal_metadata({**{k: "1" for k in ("LINE_OFF", "SAMP_OFF", "LAT_OFF",
        ...     "LONG_OFF", "HEIGHT_OFF", "LINE_SCALE", "SAMP_SCALE", "LAT_SCALE", "LONG_SCALE",
        ...     "HEIGHT_SCALE")}, **{k: " ".join(["1"] + ["0"] * 19) for k in ("LINE_NUM_COEFF",
        ...     "LINE_DEN_COEFF", "SAMP_NUM_COEFF", "SAMP_DEN_COEFF")}})
        >>> md = rpc.to_gdal_metadata()
        >>> md["LINE_OFF"], md["LINE_DEN_COEFF"].split()[:3]
        ('1.0', ['1.0', '0.0', '0.0'])
        >>> RPC.from_gdal_metadata(md) == rpc
        True
        """
        out = {}
        for name in _SCALARS:
            out[name.upper()] = repr(getattr(self, name))
        for name in _POLYS:
            out[name.upper()] = " ".join(repr(v) for v in getattr(self, name))
        return out

    def shifted(self, rows, cols):
        """The RPC of a crop whose first pixel is pixel (``rows``, ``cols``) of this image.

        The line and sample offsets are reduced by the crop offset, so that the returned model
        gives crop coordinates: ``project(rpc.shifted(r0, c0), …) = project(rpc, …) - (r0, c0)``.
        For a GeoTIFF crop carrying its offset in the transform (``c0 = transform.c``,
        ``r0 = transform.f``), use ``rpc.shifted(transform.f, transform.c)``.

        Parameters
        ----------
        rows, cols : float
            The crop's offset in pixels (row = line, col = sample); finite.

        Returns
        -------
        RPC
            A new model (this one is frozen and unchanged).

        Raises
        ------
        InputError
            An offset that is not a finite number.

        References
        ----------
        Chibunichev (2022), §8.5, eqs. (8.5.6)–(8.5.9) (the offsets of the normalisation).

        Examples
        --------
        >>> num = lambda k: [0.0] * k + [1.0] + [0.0] * (19 - k)
        >>> rpc = RPC(100, 200, 45, 5, 0, 50, 80, 0.01, 0.01, 500, num(2), num(0), num(1), num(0))
        >>> crop = rpc.shifted(30, 40)
        >>> crop.line_off, crop.samp_off
        (70.0, 160.0)
        """
        r = _checks.number(rows, "rows")
        c = _checks.number(cols, "cols")
        return replace(self, line_off=self.line_off - r, samp_off=self.samp_off - c)


def _parse_number(text, name):
    try:
        return float(text)
    except (TypeError, ValueError) as exc:
        raise InputError(f"{name}: {text!r} is not a number") from exc


def _check_rpc(rpc):
    if not isinstance(rpc, RPC):
        raise InputError(f"rpc must be a photolib.rpc.RPC, got {type(rpc).__name__}")


def _coordinates(names, values):
    arrays = []
    for name, value in zip(names, values):
        if isinstance(value, (str, bytes)) or value is None:
            raise InputError(f"{name} must be a number or an array of numbers, got {type(value).__name__}")
        try:
            arr = np.asarray(value, dtype=float)
        except (TypeError, ValueError) as exc:
            raise InputError(f"{name} must be numeric: {exc}") from exc
        if arr.size and not np.all(np.isfinite(arr)):
            raise InputError(f"{name} contains NaN or inf")
        arrays.append(arr)
    try:
        return np.broadcast_arrays(*arrays)
    except ValueError as exc:
        raise InputError(f"{', '.join(names)} have shapes that do not broadcast: "
                         f"{[a.shape for a in arrays]}") from exc


def _check_range(normalised, names, limit):
    for arr, name in zip(normalised, names):
        if arr.size and np.max(np.abs(arr)) > limit:
            worst = float(np.max(np.abs(arr)))
            raise InputError(f"{name} lies outside the RPC's valid range: |normalised {name}| = {worst:.3g} "
                             f"> {limit:g} (offset ± {limit:g} × scale); a cubic is meaningless that far out")


def _ratio(num, den, terms, what):
    d = terms @ np.asarray(den)
    bad = np.abs(d) < _DENOMINATOR_FLOOR
    if np.any(bad):
        raise DegenerateGeometryError(f"the {what} denominator of the RPC vanishes (|den| < "
                                      f"{_DENOMINATOR_FLOOR:g}) at {int(bad.sum())} point(s)")
    return (terms @ np.asarray(num)) / d, d


def _limit(extrapolation):
    return _checks.number(extrapolation, "extrapolation", positive=True)


def project(rpc, lon, lat, height, *, extrapolation=3.0):
    """Project ground points into the image with an RPC, eq. (8.5.7) with (8.5.8)/(8.5.9).

    Parameters
    ----------
    rpc : RPC
        The sensor model.
    lon, lat : array_like
        Geodetic longitude and latitude, degrees (broadcast together with ``height``).
    height : array_like
        Height above the ellipsoid, metres.
    extrapolation : float, optional
        Largest accepted |normalised coordinate| (the model is fitted on [-1, 1]; default 3).

    Returns
    -------
    row, col : numpy.ndarray
        Image line and sample, pixels, (0, 0) the centre of the first pixel; the broadcast
        shape of the inputs (0-d for scalars).

    Raises
    ------
    InputError
        Not an RPC, NaN or inf, shapes that do not broadcast, or a point further than
        ``extrapolation`` scales from the offsets.
    DegenerateGeometryError
        A denominator of the model vanishes at a point.

    References
    ----------
    Chibunichev (2022), §8.5, eqs. (8.5.6)–(8.5.9).

    Examples
    --------
    >>> num = lambda k: [0.0] * k + [1.0] + [0.0] * (19 - k)
    >>> rpc = RPC(100, 200, 45, 5, 0, 50, 80, 0.01, 0.01, 500, num(2), num(0), num(1), num(0))
    >>> row, col = project(rpc, [5.0, 5.005], [45.0, 45.01], 0.0)
    >>> row.round(6).tolist(), col.round(6).tolist()
    ([100.0, 150.0], [200.0, 240.0])
    """
    _check_rpc(rpc)
    limit = _limit(extrapolation)
    lon, lat, height = _coordinates(("lon", "lat", "height"), (lon, lat, height))
    L = (lon - rpc.long_off) / rpc.long_scale
    P = (lat - rpc.lat_off) / rpc.lat_scale
    H = (height - rpc.height_off) / rpc.height_scale
    _check_range((L, P, H), ("lon", "lat", "height"), limit)
    terms = _terms(L, P, H)
    line, _ = _ratio(rpc.line_num_coeff, rpc.line_den_coeff, terms, "line")
    samp, _ = _ratio(rpc.samp_num_coeff, rpc.samp_den_coeff, terms, "sample")
    return line * rpc.line_scale + rpc.line_off, samp * rpc.samp_scale + rpc.samp_off


def locate(rpc, row, col, height, *, tolerance=1e-9, max_iterations=30, extrapolation=3.0):
    """Ground position of image points at known heights: Newton inverse of the RPC, eq. (8.18.1).

    For each point, (L, P) is refined from the scene centre by ``e·δ + l = 0``: ``e`` the 2×2
    Jacobian ∂(line, sample)/∂(L, P) of (8.5.7) and ``l`` the image residual, until the
    image residual is below ``tolerance`` pixels.

    Parameters
    ----------
    rpc : RPC
        The sensor model.
    row, col : array_like
        Image line and sample, pixels ((0, 0) the centre of the first pixel).
    height : array_like
        Height above the ellipsoid, metres (broadcast with ``row`` and ``col``).
    tolerance : float, optional
        Convergence threshold on the image residual, pixels (default 1e-9).
    max_iterations : int, optional
        Most Newton steps (default 30).
    extrapolation : float, optional
        Largest accepted |normalised coordinate| of the input and of the iterates (default 3).

    Returns
    -------
    lon, lat : numpy.ndarray
        Degrees; the broadcast shape of the inputs.

    Raises
    ------
    InputError
        Not an RPC, NaN or inf, shapes that do not broadcast, a bad ``tolerance`` or
        ``max_iterations``, or an image point / height too far outside the model's range.
    DegenerateGeometryError
        The Jacobian is singular (the model does not determine the ground point) or a
        denominator vanishes.
    ConvergenceError
        The iteration left the valid range or did not reach ``tolerance``; ``history`` holds the
        largest residual (pixels) after each step.

    References
    ----------
    Chibunichev (2022), §8.18, eq. (8.18.1); the model: §8.5, eqs. (8.5.6)–(8.5.9).

    Examples
    --------
    >>> num = lambda k: [0.0] * k + [1.0] + [0.0] * (19 - k)
    >>> line_num = num(2); line_num[3] = 0.2          # relief displacement along the lines
    >>> rpc = RPC(100, 200, 45, 5, 0, 50, 80, 0.01, 0.01, 500, line_num, num(0), num(1), num(0))
    >>> lon, lat = locate(rpc, [150.0, 100.0], [240.0, 200.0], [0.0, 500.0])
    >>> lon.round(9).tolist(), lat.round(9).tolist()
    ([5.005, 5.0], [45.01, 44.998])
    """
    _check_rpc(rpc)
    limit = _limit(extrapolation)
    tol = _checks.number(tolerance, "tolerance", positive=True)
    iterations = _checks.integer(max_iterations, "max_iterations", 1)
    row, col, height = _coordinates(("row", "col", "height"), (row, col, height))
    r = (row - rpc.line_off) / rpc.line_scale
    c = (col - rpc.samp_off) / rpc.samp_scale
    H = (height - rpc.height_off) / rpc.height_scale
    _check_range((r, c, H), ("row", "col", "height"), limit)
    shape = r.shape
    r, c, H = r.ravel(), c.ravel(), H.ravel()
    L = np.zeros_like(r)
    P = np.zeros_like(r)
    ln, ld = np.asarray(rpc.line_num_coeff), np.asarray(rpc.line_den_coeff)
    sn, sd = np.asarray(rpc.samp_num_coeff), np.asarray(rpc.samp_den_coeff)
    history = []
    for _ in range(iterations + 1):
        t = _terms(L, P, H)
        line, dl = _ratio(ln, ld, t, "line")
        samp, ds = _ratio(sn, sd, t, "sample")
        fr, fc = line - r, samp - c
        tL, tP = _terms_dL(L, P, H), _terms_dP(L, P, H)
        # quotient rule: d(n/d) = (dn - (n/d) dd) / d
        a = (tL @ ln - line * (tL @ ld)) / dl
        b = (tP @ ln - line * (tP @ ld)) / dl
        e = (tL @ sn - samp * (tL @ sd)) / ds
        f = (tP @ sn - samp * (tP @ sd)) / ds
        det = a * f - b * e
        scale = np.maximum(np.abs(a * f), np.abs(b * e)) + np.finfo(float).tiny
        singular = np.abs(det) <= 1e-12 * scale
        if np.any(singular):             # also at a solution: there, too, it would not be unique
            raise DegenerateGeometryError(f"the RPC's Jacobian ∂(line, sample)/∂(lon, lat) is singular at "
                                          f"{int(singular.sum())} point(s): the model does not fix the ground point")
        worst = float(np.max(np.hypot(fr * rpc.line_scale, fc * rpc.samp_scale), initial=0.0))
        history.append(worst)
        if worst <= tol:
            break
        if len(history) > iterations:
            raise ConvergenceError(f"the RPC inverse did not reach {tol:g} px in {iterations} Newton "
                                   f"steps (largest residual {worst:.3g} px)", history)
        L = L - (f * fr - b * fc) / det
        P = P - (a * fc - e * fr) / det
        if np.max(np.abs(L), initial=0.0) > limit or np.max(np.abs(P), initial=0.0) > limit:
            history.append(math.inf)
            raise ConvergenceError(f"the RPC inverse diverged: an iterate left the model's valid range "
                                   f"(|normalised lon/lat| > {limit:g})", history)
    lon = (L * rpc.long_scale + rpc.long_off).reshape(shape)
    lat = (P * rpc.lat_scale + rpc.lat_off).reshape(shape)
    return lon, lat

