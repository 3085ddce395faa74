"""Rational polynomial coefficients (RPC) of satellite images — Chapter 8, §8.5–8.8 and §8.18.

The RPC model (Chibunichev 2022, §8.5, eqs. (8.5.6)–(8.5.9)) replaces the rigorous pushbroom
sensor model by ratios of cubic polynomials of the ground coordinates. This module implements

* :class:`RPC`, the 90 numbers of a model: offsets and scales of the five normalised variables
  (line, sample, latitude, longitude, height) and the four 20-term polynomials in the standard
  NITF RPC00B term order (the order the book prints in (8.5.8)/(8.5.9) with X = L = longitude,
  Y = P = latitude, Z = H = height), read from OSSIM ``.geom`` text and from GDAL's ``RPC``
  metadata domain and written back to it;
* :func:`project`, ground → image, eq. (8.5.7) with (8.5.8)/(8.5.9);
* :func:`locate`, image + height → ground, by the Newton iteration of §8.18, eq. (8.18.1)
  (from 1000 points on in the numba kernel of the private module photolib._rpc_kernels, each
  point started from its neighbour's solution — about 20× faster than the vectorised loop);
* :func:`fit_rpc` / :func:`fit_rpc_points` / :func:`rpc_grid`, an RPC fitted to any sensor model by
  the terrain-independent grid of §8.6 (image grid × height planes; five planes by default, since
  three leave the H³ terms undetermined), with the diagnostics of :class:`RPCFit`;
* :func:`fit_bias` and :class:`BiasCorrectedRPC`, the image-space bias compensation
  (8.6.1)–(8.6.4) (shift / affine / second order from 1 / 3 / 6 GCPs, least squares beyond);
* :func:`intersect_rpc`, the least-squares stereo intersection (8.8.9) of §8.8 case 4;
* :func:`conventional_frame_rpc`, one RPC for micro-frames combined into a conventional frame
  (Kanopus-V, §8.18).

Conventions (the book leaves them open; these are RPC00B's and GDAL's):

* every variable is normalised, ``(value - offset) / scale``; latitude and longitude in degrees,
  height in metres above the **ellipsoid** (WGS 84), line and sample in pixels;
* image coordinates are (row, col) = (line, sample) with (0, 0) the **centre** of the first
  pixel. GDAL's RPC transformer reports pixel-corner coordinates: its values are ours + 0.5;
* a crop whose first pixel is at (row0, col0) of the full scene has the RPC
  ``rpc.shifted(row0, col0)`` (line and sample offsets reduced by the crop offset).
* a fitted RPC (:func:`fit_rpc`) may use any ground frame: ``lon`` then stands for X (L of
  RPC00B) and ``lat`` for Y (P), e.g. metres of a local frame, as the book's (8.5.9) does.

Only numpy (and numba, imported on first use by :func:`locate`) is needed; no GDAL or rasterio.
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np

from . import _checks
from .errors import ConvergenceError, DegenerateGeometryError, InputError

__all__ = ["RPC", "RPC00B_TERMS", "project", "locate", "RPCFit", "rpc_grid", "fit_rpc_points", "fit_rpc",
           "BIAS_MODELS", "BiasCorrectedRPC", "fit_bias", "RPCIntersection", "intersect_rpc",
           "conventional_frame_rpc"]

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


def _terms_dH(L, P, H):
    """∂/∂H of the 20 monomials."""
    z = np.zeros(np.broadcast(L, P, H).shape)
    one = z + 1.0
    return np.stack(np.broadcast_arrays(
        z, z, z, one, z, L, P, z, z, 2 * H,
        P * L, z, z, 2 * L * H, z, z, 2 * P * H,
        L * L, P * P, 3 * H * H), axis=-1)


#: Degree in H of each RPC00B term (used to drop the terms a few height planes cannot determine).
_H_DEGREE = np.array([t.count("H") + (1 if "H**2" in t else 0) + (2 if "H**3" in t else 0) for t in RPC00B_TERMS])


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
    rpc : RPC or BiasCorrectedRPC
        The sensor model (a bias-compensated one applies its image-space correction, (8.6.1)).
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
    if isinstance(rpc, BiasCorrectedRPC):
        return rpc.project(lon, lat, height, extrapolation=extrapolation)
    _check_rpc(rpc)
    limit = _limit(extrapolation)
    lon, lat, height = _coordinates(("lon", "lat", "height"), (lon, lat, height))
    L = (lon - rpc.long_off) / rpc.long_scale
    P = (lat - rpc.lat_off) / rpc.lat_scale
    H = (height - rpc.height_off) / rpc.height_scale
    _check_range((L, P, H), ("lon", "lat", "height"), limit)
    if L.size >= _KERNEL_FROM:
        from ._rpc_kernels import project_kernel

        line, samp = np.empty(L.shape), np.empty(L.shape)
        smallest = project_kernel(np.ascontiguousarray(L).ravel(), np.ascontiguousarray(P).ravel(),
                                  np.ascontiguousarray(H).ravel(), *_coefficient_arrays(rpc),
                                  line.reshape(-1), samp.reshape(-1))
        if smallest >= _DENOMINATOR_FLOOR:
            return line * rpc.line_scale + rpc.line_off, samp * rpc.samp_scale + rpc.samp_off
    terms = _terms(L, P, H)     # small inputs, and the named error of a vanishing denominator
    line, _ = _ratio(rpc.line_num_coeff, rpc.line_den_coeff, terms, "line")
    samp, _ = _ratio(rpc.samp_num_coeff, rpc.samp_den_coeff, terms, "sample")
    return line * rpc.line_scale + rpc.line_off, samp * rpc.samp_scale + rpc.samp_off


def _coefficient_arrays(rpc):
    """The four coefficient vectors as contiguous float arrays (line num/den, sample num/den)."""
    return tuple(np.ascontiguousarray(c, dtype=np.float64) for c in
                 (rpc.line_num_coeff, rpc.line_den_coeff, rpc.samp_num_coeff, rpc.samp_den_coeff))


def locate(rpc, row, col, height, *, tolerance=1e-9, max_iterations=30, extrapolation=3.0):
    """Ground position of image points at known heights: Newton inverse of the RPC, eq. (8.18.1).

    For each point, (L, P) is refined from the scene centre by ``e·δ + l = 0``: ``e`` the 2×2
    Jacobian ∂(line, sample)/∂(L, P) of (8.5.7) and ``l`` the image residual, until the
    image residual is below ``tolerance`` pixels.

    Parameters
    ----------
    rpc : RPC or BiasCorrectedRPC
        The sensor model (a bias-compensated one first turns the measured coordinates into the
        RPC's, x + δ of (8.6.1)).
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
    if isinstance(rpc, BiasCorrectedRPC):
        return rpc.locate(row, col, height, tolerance=tolerance, max_iterations=max_iterations,
                          extrapolation=extrapolation)
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
    if r.size >= _KERNEL_FROM:
        L, P = _locate_kernel(rpc, r, c, H, tol, iterations, limit)
    else:
        L, P = _locate_numpy(rpc, r, c, H, tol, iterations, limit)
    lon = (L * rpc.long_scale + rpc.long_off).reshape(shape)
    lat = (P * rpc.lat_scale + rpc.lat_off).reshape(shape)
    return lon, lat



#: From this many points on, :func:`locate` runs the numba kernel (photolib._rpc_kernels); below it
#: the vectorised numpy loop, which needs no compilation.
_KERNEL_FROM = 1000


def _locate_numpy(rpc, r, c, H, tol, iterations, limit):
    """The Newton iteration (8.18.1) for all points at once (normalised coordinates)."""
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
    return L, P


def _locate_kernel(rpc, r, c, H, tol, iterations, limit):
    """The same iteration point by point in the numba kernel; errors as :func:`_locate_numpy`."""
    from ._rpc_kernels import locate_kernel
    L, P, status, history = locate_kernel(r, c, H, np.asarray(rpc.line_num_coeff), np.asarray(rpc.line_den_coeff),
                                          np.asarray(rpc.samp_num_coeff), np.asarray(rpc.samp_den_coeff),
                                          rpc.line_scale, rpc.samp_scale, tol, iterations, limit, _DENOMINATOR_FLOOR)
    history = [float(v) for v in history]
    if np.any(status == 2):
        raise DegenerateGeometryError(f"a denominator of the RPC vanishes (|den| < {_DENOMINATOR_FLOOR:g}) at "
                                      f"{int(np.sum(status == 2))} point(s) of the inverse iteration")
    if np.any(status == 3):
        raise DegenerateGeometryError(f"the RPC's Jacobian ∂(line, sample)/∂(lon, lat) is singular at "
                                      f"{int(np.sum(status == 3))} point(s): the model does not fix the ground point")
    if np.any(status == 4):
        raise ConvergenceError(f"the RPC inverse diverged at {int(np.sum(status == 4))} point(s): an iterate left "
                               f"the model's valid range (|normalised lon/lat| > {limit:g})", history + [math.inf])
    if np.any(status == 1):
        raise ConvergenceError(f"the RPC inverse did not reach {tol:g} px in {iterations} Newton steps at "
                               f"{int(np.sum(status == 1))} point(s) (largest residual {history[-1]:.3g} px)", history)
    return L, P


# ====================================================================================== §8.6 fitting
def _rpc_eval(rpc, lon, lat, height, extrapolation=3.0):
    """Rows, cols and their Jacobian ∂(row, col)/∂(lon, lat, height), shape (..., 2, 3)."""
    L = (lon - rpc.long_off) / rpc.long_scale
    P = (lat - rpc.lat_off) / rpc.lat_scale
    H = (height - rpc.height_off) / rpc.height_scale
    _check_range((L, P, H), ("lon", "lat", "height"), extrapolation)
    t = _terms(L, P, H)
    derivs = (_terms_dL(L, P, H), _terms_dP(L, P, H), _terms_dH(L, P, H))
    scales = (rpc.long_scale, rpc.lat_scale, rpc.height_scale)
    out, jac = [], []
    for num, den, what, sc, off in ((rpc.line_num_coeff, rpc.line_den_coeff, "line", rpc.line_scale, rpc.line_off),
                                    (rpc.samp_num_coeff, rpc.samp_den_coeff, "sample", rpc.samp_scale, rpc.samp_off)):
        num, den = np.asarray(num), np.asarray(den)
        ratio, d = _ratio(num, den, t, what)
        out.append(ratio * sc + off)
        jac.append(np.stack([(dt @ num - ratio * (dt @ den)) / d * sc / s for dt, s in zip(derivs, scales)], axis=-1))
    return out[0], out[1], np.stack(jac, axis=-2)


@dataclass(frozen=True, eq=False)
class RPCFit:
    """An RPC fitted to image ↔ ground correspondences, with the diagnostics of the fit (§8.6).

    Attributes
    ----------
    rpc : RPC
        The fitted model (denominator constants fixed to 1).
    unknowns : int
        Free coefficients per image coordinate: 39 (20 numerator + 19 denominator) unless terms
        were dropped.
    rank : tuple of int
        Numerical rank of the column-scaled design matrix of the line and of the sample fit. A rank
        below ``unknowns`` means combinations of coefficients the points do not determine (the
        minimum-norm solution sets them); harmless inside the sampled domain, fatal when the
        missing direction matters between the samples (H³ on three height planes).
    condition : tuple of float
        Condition numbers (largest / smallest singular value) of the two column-scaled designs.
    fit_error : float
        Largest image distance between the correspondences and the fitted RPC, pixels.
    check_error : float
        Largest image distance at independent check points (random rows, columns and heights,
        i.e. between the height planes), pixels; NaN when not checked.
    dropped : tuple of str
        Terms fixed to zero in numerators and denominators (H-powers the distinct heights cannot
        determine).
    n_points : int
        Number of correspondences used.

    References
    ----------
    Chibunichev (2022), §8.6 (terrain-independent grid), eqs. (8.5.7)–(8.5.9).

    Examples
    --------
    >>> fit = fit_rpc(lambda r, c, h: (5 + 1e-4 * c, 45 - 1e-4 * r + 1e-7 * h), (200, 300), (0, 1000), step=20)
    >>> fit.unknowns, fit.check_error < 1e-6
    (39, True)
    """

    rpc: RPC
    unknowns: int
    rank: tuple
    condition: tuple
    fit_error: float
    check_error: float
    dropped: tuple
    n_points: int

    def __post_init__(self):
        _check_rpc(self.rpc)


def _points(names, values, minimum=0):
    arrays = []
    for name, value in zip(names, values):
        if isinstance(value, (str, bytes)) or value is None:
            raise InputError(f"{name} must be an array of numbers, got {type(value).__name__}")
        try:
            arr = np.asarray(value, dtype=float).ravel()
        except (TypeError, ValueError) as exc:
            raise InputError(f"{name} must be numeric: {exc}") from exc
        if not np.all(np.isfinite(arr)):
            raise InputError(f"{name} contains NaN or inf")
        arrays.append(arr)
    sizes = {a.size for a in arrays}
    if len(sizes) != 1:
        raise InputError(f"{', '.join(names)} must have the same number of points, got "
                         f"{[a.size for a in arrays]}")
    return arrays


def _normaliser(values, name):
    lo, hi = float(np.min(values)), float(np.max(values))
    if hi - lo <= 1e-12 * max(1.0, abs(hi)):
        raise DegenerateGeometryError(f"the points do not vary in {name} (all ≈ {lo:g}): the RPC's "
                                      f"normalisation of {name} is undefined")
    return 0.5 * (lo + hi), 0.5 * (hi - lo)


def _solve_ratio(u, T, keep, rcond, refine):
    """Linearised least squares of u = (T·a)/(T·b), b₀ = 1, over the kept terms; returns a, b, rank, cond."""
    from .lsq import blas_on_one_thread      # a multithreaded BLAS crawls on a shared machine
    with blas_on_one_thread():
        return _solve_ratio_serial(u, T, keep, rcond, refine)


def _solve_ratio_serial(u, T, keep, rcond, refine):
    cols = np.concatenate([T[:, keep], -u[:, None] * T[:, 1:][:, keep[1:]]], axis=1)
    n_num = int(keep.sum())
    weight = np.ones_like(u)
    for _ in range(1 + refine):
        G = cols * weight[:, None]
        norms = np.linalg.norm(G, axis=0)
        norms[norms == 0] = 1.0
        U, sv, Vt = np.linalg.svd(G / norms, full_matrices=False)
        rank = int(np.sum(sv > rcond * sv[0]))
        sol = Vt[:rank].T @ ((U[:, :rank].T @ (u * weight)) / sv[:rank])
        if rank < sol.size:
            # The points leave directions undetermined: for a sensor close to a low-degree ratio
            # (a frame camera, a short pushbroom) numerator and denominator may share any common
            # factor q. Among the equally good solutions take the one whose denominator is closest
            # to the constant 1 (q ≈ 1), so that no pole of q crosses the image between the nodes.
            null = Vt[rank:].T / norms[:, None]
            den_part = slice(n_num, sol.size)
            z = np.linalg.lstsq(null[den_part], -(sol / norms)[den_part], rcond=None)[0]
            sol = sol / norms + null @ z
        else:
            sol = sol / norms
        a = np.zeros(20)
        b = np.zeros(20)
        a[keep] = sol[:n_num]
        b[0] = 1.0
        b[1:][keep[1:]] = sol[n_num:]
        den = T @ b
        if np.any(np.abs(den) < _DENOMINATOR_FLOOR):
            raise DegenerateGeometryError("the fitted RPC denominator vanishes at a fitting point")
        weight = 1.0 / np.abs(den)            # turn the algebraic residual u·den − num into u − num/den
    cond = float(sv[0] / sv[-1]) if sv[-1] > 0 else math.inf
    return a, b, rank, cond


def fit_rpc_points(row, col, lon, lat, height, *, height_terms="auto", rcond=1e-12, refine=1):
    """Fit an RPC (denominator constants 1, 2 × 39 unknowns) to image ↔ ground correspondences.

    Offsets are the centres and scales the half-ranges of the five variables, so that every
    normalised variable spans [−1, 1]. Each image coordinate u (line, sample) is fitted by the
    linearised equation ``T·a − u·(T·b) = 0`` with ``b₁ = 1`` (the usual direct RPC solution,
    pitfall 9b of the guide: 78, not 80, unknowns), then re-weighted once by 1/|T·b| so that the
    residual is the image error. The solver is numpy's SVD least squares (``lstsq``) on the
    design with unit-norm columns, **not** photolib.lsq's normal equations: the design of a
    sensor-derived grid is nearly rank deficient (the rational form is over-parameterised for a
    smooth sensor; condition numbers of 1e8 and more after column scaling), the normal matrix
    would square that beyond double precision, and the minimum-norm solution of the truncated SVD
    (singular values below ``rcond`` × largest dropped) is the well-defined answer.

    Parameters
    ----------
    row, col : array_like
        Image coordinates of the correspondences, pixels.
    lon, lat, height : array_like
        Their ground coordinates (degrees and metres, or any X, Y, Z: ``lon`` plays X = L and
        ``lat`` Y = P of (8.5.9)). Same number of points as ``row``.
    height_terms : {"auto", "all"}
        ``"auto"`` fixes to zero the terms whose power of H is at least the number of distinct
        heights (with three planes: H³, which on three heights is a combination of 1, H, H²);
        ``"all"`` keeps the 20 terms (the book's literal procedure — ill-posed on three planes).
    rcond : float
        Relative cut-off of the singular values (default 1e-12).
    refine : int
        Re-weighting passes after the linear solution (default 1).

    Returns
    -------
    RPCFit
        The model and its diagnostics (``check_error`` is NaN: no independent check here).

    Raises
    ------
    InputError
        NaN/inf, non-numeric input, different numbers of points, a bad option.
    DegenerateGeometryError
        Fewer than 39 points (the unknowns per coordinate), no spread in a coordinate, fewer than
        two distinct heights, or a vanishing denominator.

    References
    ----------
    Chibunichev (2022), §8.6 and §8.18, eqs. (8.5.7)–(8.5.9); Tao & Hu (2001), "A comprehensive
    study of the rational function model", PE&RS 67(12) (terrain-independent solution).

    Examples
    --------
    >>> g = np.linspace(0, 99, 10)
    >>> r, c, h = [a.ravel() for a in np.meshgrid(g, g, [0.0, 250, 500, 750, 1000], indexing="ij")]
    >>> fit = fit_rpc_points(r, c, 5 + 1e-4 * c, 45 - 1e-4 * r + 1e-7 * h, h)
    >>> fit.fit_error < 1e-9, fit.dropped
    (True, ())
    """
    row, col, lon, lat, height = _points(("row", "col", "lon", "lat", "height"), (row, col, lon, lat, height))
    if height_terms not in ("auto", "all"):
        raise InputError(f"height_terms must be 'auto' or 'all', got {height_terms!r}")
    rc = _checks.number(rcond, "rcond", positive=True)
    refine = _checks.integer(refine, "refine", 0)
    n = row.size
    if n < 39:
        raise DegenerateGeometryError(f"an RPC has 39 unknowns per image coordinate (20 + 19 with the "
                                      f"denominator constant fixed to 1): {n} correspondences are too few")
    offs = [_normaliser(v, name) for v, name in zip((row, col, lat, lon, height),
                                                    ("row", "col", "lat", "lon", "height"))]
    (line_off, line_scale), (samp_off, samp_scale), (lat_off, lat_scale), (long_off, long_scale), \
        (height_off, height_scale) = offs
    L = (lon - long_off) / long_scale
    P = (lat - lat_off) / lat_scale
    H = (height - height_off) / height_scale
    distinct = np.unique(np.round(H, 9)).size
    keep = np.ones(20, dtype=bool)
    if height_terms == "auto":
        keep = _H_DEGREE < distinct
    dropped = tuple(t for t, k in zip(RPC00B_TERMS, keep) if not k)
    T = _terms(L, P, H)
    ul = (row - line_off) / line_scale
    us = (col - samp_off) / samp_scale
    ln, ld, rank_l, cond_l = _solve_ratio(ul, T, keep, rc, refine)
    sn, sd, rank_s, cond_s = _solve_ratio(us, T, keep, rc, refine)
    rpc = RPC(line_off, samp_off, lat_off, long_off, height_off, line_scale, samp_scale, lat_scale, long_scale,
              height_scale, ln, ld, sn, sd)
    r2, c2 = project(rpc, lon, lat, height)
    err = float(np.max(np.hypot(r2 - row, c2 - col)))
    return RPCFit(rpc, int(2 * keep.sum() - 1), (rank_l, rank_s), (cond_l, cond_s), err, math.nan, dropped, n)


def _grid_axis(size, step):
    axis = np.arange(0.0, size, step)
    if axis[-1] < size - 1:
        axis = np.append(axis, size - 1.0)
    return axis


def _shape(image_shape):
    if isinstance(image_shape, (str, bytes)) or not hasattr(image_shape, "__len__") or len(image_shape) != 2:
        raise InputError(f"image_shape must be (rows, cols), got {image_shape!r}")
    return tuple(_checks.integer(v, "image_shape", 2) for v in image_shape)


def _planes(height_range, levels):
    if isinstance(height_range, (str, bytes)) or not hasattr(height_range, "__len__") or len(height_range) != 2:
        raise InputError(f"height_range must be (lowest, highest), got {height_range!r}")
    lo = _checks.number(height_range[0], "height_range[0]")
    hi = _checks.number(height_range[1], "height_range[1]")
    if not hi > lo:
        raise InputError(f"height_range must be increasing (lowest < highest), got {height_range!r}")
    n = _checks.integer(levels, "levels", 2)
    return np.linspace(lo, hi, n), lo, hi


def _call_ground(ground_of, rows, cols, heights):
    if not callable(ground_of):
        raise InputError(f"ground_of must be a callable (rows, cols, heights) -> (lon, lat), got "
                         f"{type(ground_of).__name__}")
    try:
        out = ground_of(rows, cols, heights)
        lon, lat = out
        lon = np.broadcast_to(np.asarray(lon, dtype=float), rows.shape)
        lat = np.broadcast_to(np.asarray(lat, dtype=float), rows.shape)
    except (TypeError, ValueError) as exc:
        raise InputError(f"ground_of must return two arrays (lon, lat) shaped like its input: {exc}") from exc
    bad = ~(np.isfinite(lon) & np.isfinite(lat))
    if np.any(bad):
        raise InputError(f"ground_of returned NaN or inf at {int(bad.sum())} grid point(s), e.g. row "
                         f"{rows[bad][0]:g}, col {cols[bad][0]:g}, height {heights[bad][0]:g}")
    return lon, lat


def rpc_grid(ground_of, image_shape, heights, *, step=100):
    """The terrain-independent grid of §8.6: image grid nodes × height planes → ground points.

    Parameters
    ----------
    ground_of : callable
        The rigorous sensor, ``ground_of(rows, cols, heights) -> (lon, lat)`` on arrays of one
        shape (e.g. a pushbroom's ``ground``, a frame camera's monoplotting (8.5.1)/(8.7.1)).
    image_shape : (int, int)
        Rows and columns of the image; pixel (0, 0) is the centre of the first pixel.
    heights : sequence of float
        The height planes Z₁, Z₂, … (metres).
    step : float
        Grid spacing in pixels along rows and columns (the book: every 100th pixel); the last
        row and column are always included.

    Returns
    -------
    row, col, lon, lat, height : numpy.ndarray
        One entry per grid node and plane (flat arrays).

    Raises
    ------
    InputError
        A bad shape, step or height, a ``ground_of`` that is not callable or returns NaN/inf.

    References
    ----------
    Chibunichev (2022), §8.6 (Fig. 8.15) and §8.18 (Fig. 8.41).

    Examples
    --------
    >>> r, c, lon, lat, h = rpc_grid(lambda r, c, h: (c, -r), (201, 301), [0.0, 500.0], step=100)
    >>> r.size, sorted(set(c.tolist()))
    (24, [0.0, 100.0, 200.0, 300.0])
    """
    rows_n, cols_n = _shape(image_shape)
    step = _checks.number(step, "step", positive=True)
    if isinstance(heights, (str, bytes)):
        raise InputError("heights must be numbers")
    try:
        planes = np.asarray(heights, dtype=float).ravel()
    except (TypeError, ValueError) as exc:
        raise InputError(f"heights must be numbers: {exc}") from exc
    if planes.size == 0 or not np.all(np.isfinite(planes)):
        raise InputError("heights must be a non-empty sequence of finite numbers")
    R, C, Hh = np.meshgrid(_grid_axis(rows_n, step), _grid_axis(cols_n, step), planes, indexing="ij")
    R, C, Hh = R.ravel(), C.ravel(), Hh.ravel()
    lon, lat = _call_ground(ground_of, R, C, Hh)
    return R, C, np.array(lon), np.array(lat), Hh


def _check_points(n, seed, rows_n, cols_n, lo, hi):
    rng = np.random.default_rng(seed)
    return (rng.uniform(0, rows_n - 1, n), rng.uniform(0, cols_n - 1, n), rng.uniform(lo, hi, n))


def fit_rpc(ground_of, image_shape, height_range, *, levels=5, step=100, height_terms="auto", check=200,
            seed=0, rcond=1e-12):
    """Fit an RPC to a rigorous sensor model by the terrain-independent grid of §8.6.

    The image is sampled every ``step`` pixels, every node is intersected with ``levels`` equally
    spaced height planes over ``height_range`` by the sensor's own ``ground_of`` and the RPC is
    fitted to the correspondences by :func:`fit_rpc_points`. It is then checked at ``check``
    random image points at random heights — between the planes, where a badly posed fit fails.
    The book suggests three planes (lowest, mean, highest height); on three planes H³ equals a
    combination of 1, H and H², so the cubic-in-height terms are not determined: the default is
    five planes, and with ``height_terms="auto"`` (default) fewer planes drop the undetermined
    terms instead of guessing them.

    Parameters
    ----------
    ground_of : callable
        ``ground_of(rows, cols, heights) -> (lon, lat)`` (any X, Y may stand for lon, lat).
    image_shape : (int, int)
        Rows and columns of the image.
    height_range : (float, float)
        Lowest and highest terrain height of the scene, metres.
    levels : int
        Number of height planes (default 5; at least 2).
    step : float
        Grid spacing, pixels (default 100, the book's example).
    height_terms : {"auto", "all"}
        See :func:`fit_rpc_points`.
    check : int
        Number of random check points (0: no check).
    seed : int
        Seed of the check points.
    rcond : float
        Singular-value cut-off of the least squares.

    Returns
    -------
    RPCFit
        With ``check_error`` the largest image error at the check points, pixels.

    Raises
    ------
    InputError
        Bad shapes, ranges or options; a ``ground_of`` that fails or returns NaN/inf.
    DegenerateGeometryError
        Too few grid nodes for the 39 unknowns (a step too coarse), or a degenerate sensor.

    References
    ----------
    Chibunichev (2022), §8.6, eqs. (8.5.7)–(8.5.9); guide pitfall 9(e) (three planes).

    Examples
    --------
    >>> cam = lambda r, c, h: (5 + 1e-4 * c + 2e-9 * c * h, 45 - 1e-4 * r + 1e-7 * h)
    >>> fit = fit_rpc(cam, (500, 400), (0, 1500), step=50)
    >>> fit.unknowns, fit.check_error < 1e-6
    (39, True)
    """
    rows_n, cols_n = _shape(image_shape)
    planes, lo, hi = _planes(height_range, levels)
    n_check = _checks.integer(check, "check", 0)
    r, c, lon, lat, h = rpc_grid(ground_of, (rows_n, cols_n), planes, step=step)
    fit = fit_rpc_points(r, c, lon, lat, h, height_terms=height_terms, rcond=rcond)
    if n_check:
        cr, cc, ch = _check_points(n_check, seed, rows_n, cols_n, lo, hi)
        clon, clat = _call_ground(ground_of, cr, cc, ch)
        pr, pc = project(fit.rpc, clon, clat, ch, extrapolation=1.5)
        fit = replace(fit, check_error=float(np.max(np.hypot(pr - cr, pc - cc))))
    return fit


# ====================================================================================== §8.6 bias
#: The image-space bias models of (8.6.2)–(8.6.4): name → (terms, minimum number of GCPs).
BIAS_MODELS = {"shift": (("1",), 1), "affine": (("1", "x", "y"), 3),
               "poly2": (("1", "x", "y", "x*y", "x**2", "y**2"), 6)}


def _bias_terms(model, x, y):
    one = np.ones_like(x)
    full = (one, x, y, x * y, x * x, y * y)
    return np.stack(full[:len(BIAS_MODELS[model][0])], axis=-1)


@dataclass(frozen=True, eq=False)
class BiasCorrectedRPC:
    """An RPC with an image-space bias correction, eq. (8.6.1): ``x + δx(x, y) = P₁/P₂``.

    ``δ = RPC(X, Y, Z) − measured`` (pitfall 10 of the guide): the RPC's image coordinates minus the
    measured ones, a polynomial (8.6.2)–(8.6.4) of the measured line x and sample y, normalised
    by the RPC's line and sample offsets and scales: x̃ = (x − line_off)/line_scale,
    ỹ = (y − samp_off)/samp_scale. Projecting subtracts δ (solved exactly: x = RPC − δ(x)),
    locating adds it before the RPC's own inverse.

    Parameters
    ----------
    rpc : RPC
        The vendor's (or fitted) model.
    model : {"shift", "affine", "poly2"}
        (8.6.2), (8.6.3) or (8.6.4).
    line_coeff, samp_coeff : tuple of float
        c₀ … and d₀ … of δx (line) and δy (sample), pixels, in the order 1, x̃, ỹ, x̃ỹ, x̃², ỹ².
    rms : float
        Root mean square of the remaining image residuals at the GCPs, √(mean(vx² + vy²)), pixels
        (0 when the GCPs determine the model exactly).
    n_gcp : int
        Number of GCPs used.

    References
    ----------
    Chibunichev (2022), §8.6, eqs. (8.6.1)–(8.6.4); Fraser & Hanley (2003), PE&RS 69(1).

    Examples
    --------
    >>> num = lambda k: [0.0] * k + [1.0] + [0.0] * (19 - k)
    >>> rpc = RPC(100, 200, 45, 5, 0, 50, 80, 0.01, 0.01, 500, num(2), num(0), num(1), num(0))
    >>> fixed = BiasCorrectedRPC(rpc, "shift", (1.5,), (-2.0,))
    >>> [float(v) for v in project(fixed, 5.0, 45.0, 0.0)]
    [98.5, 202.0]
    """

    rpc: RPC
    model: str
    line_coeff: tuple
    samp_coeff: tuple
    rms: float = 0.0
    n_gcp: int = 0

    def __post_init__(self):
        _check_rpc(self.rpc)
        if self.model not in BIAS_MODELS:
            raise InputError(f"model must be one of {sorted(BIAS_MODELS)}, got {self.model!r}")
        k = len(BIAS_MODELS[self.model][0])
        for name in ("line_coeff", "samp_coeff"):
            arr = np.asarray(getattr(self, name), dtype=float).ravel()
            if arr.shape != (k,) or not np.all(np.isfinite(arr)):
                raise InputError(f"{name} must be {k} finite numbers for the {self.model} model")
            object.__setattr__(self, name, tuple(float(v) for v in arr))

    def correction(self, row, col):
        """δx, δy of (8.6.2)–(8.6.4) at image coordinates (pixels; broadcast shape).

        Parameters
        ----------
        row, col : array_like
            Measured line and sample, pixels.

        Returns
        -------
        d_row, d_col : numpy.ndarray
            δx and δy, pixels (RPC minus measured).

        Raises
        ------
        InputError
            NaN/inf or shapes that do not broadcast.

        References
        ----------
        Chibunichev (2022), §8.6, eqs. (8.6.2)–(8.6.4).

        Examples
        --------
        >>> num = lambda k: [0.0] * k + [1.0] + [0.0] * (19 - k)
        >>> rpc = RPC(100, 200, 45, 5, 0, 50, 80, 0.01, 0.01, 500, num(2), num(0), num(1), num(0))
        >>> fixed = BiasCorrectedRPC(rpc, "affine", (1.0, 0.5, 0.0), (0.0, 0.0, 2.0))
        >>> [float(v) for v in fixed.correction(150.0, 280.0)]
        [1.5, 2.0]
        """
        row, col = _coordinates(("row", "col"), (row, col))
        t = _bias_terms(self.model, (row - self.rpc.line_off) / self.rpc.line_scale,
                        (col - self.rpc.samp_off) / self.rpc.samp_scale)
        return t @ np.asarray(self.line_coeff), t @ np.asarray(self.samp_coeff)

    def to_rpc_space(self, row, col):
        """Measured image coordinates → the RPC's: x + δx, y + δy (the left side of (8.6.1)).

        Parameters
        ----------
        row, col : array_like
            Measured line and sample, pixels.

        Returns
        -------
        row, col : numpy.ndarray
            The coordinates the uncorrected RPC assigns to the same ground point.

        Raises
        ------
        InputError
            NaN/inf or shapes that do not broadcast.

        References
        ----------
        Chibunichev (2022), §8.6, eq. (8.6.1).

        Examples
        --------
        >>> num = lambda k: [0.0] * k + [1.0] + [0.0] * (19 - k)
        >>> rpc = RPC(100, 200, 45, 5, 0, 50, 80, 0.01, 0.01, 500, num(2), num(0), num(1), num(0))
        >>> [float(v) for v in BiasCorrectedRPC(rpc, "shift", (1.5,), (-2.0,)).to_rpc_space(98.5, 202.0)]
        [100.0, 200.0]
        """
        row, col = _coordinates(("row", "col"), (row, col))
        dr, dc = self.correction(row, col)
        return row + dr, col + dc

    def project(self, lon, lat, height, *, extrapolation=3.0, tolerance=1e-10, max_iterations=20):
        """Ground → measured image coordinates: x = RPC(X, Y, Z) − δx(x, y), solved by iteration.

        Parameters
        ----------
        lon, lat, height : array_like
            Ground points (as :func:`project`).
        extrapolation : float
            As :func:`project`.
        tolerance : float
            Convergence of the fixed point x = RPC − δ(x), pixels.
        max_iterations : int
            Most fixed-point steps.

        Returns
        -------
        row, col : numpy.ndarray
            Pixels.

        Raises
        ------
        InputError
            As :func:`project`.
        DegenerateGeometryError
            A vanishing RPC denominator.
        ConvergenceError
            The correction varies so fast with x that the fixed point does not converge.

        References
        ----------
        Chibunichev (2022), §8.6, eq. (8.6.1).

        Examples
        --------
        >>> num = lambda k: [0.0] * k + [1.0] + [0.0] * (19 - k)
        >>> rpc = RPC(100, 200, 45, 5, 0, 50, 80, 0.01, 0.01, 500, num(2), num(0), num(1), num(0))
        >>> fixed = BiasCorrectedRPC(rpc, "affine", (1.0, 0.5, 0.0), (0.0, 0.0, 2.0))
        >>> row, col = fixed.project(5.0, 45.005, 0.0)
        >>> bool(abs(row + fixed.correction(row, col)[0] - 125.0) < 1e-9)
        True
        """
        r0, c0 = project(self.rpc, lon, lat, height, extrapolation=extrapolation)
        tol = _checks.number(tolerance, "tolerance", positive=True)
        n = _checks.integer(max_iterations, "max_iterations", 1)
        row, col = r0, c0
        history = []
        for _ in range(n):
            dr, dc = self.correction(row, col)
            new_r, new_c = r0 - dr, c0 - dc
            change = float(np.max(np.hypot(new_r - row, new_c - col), initial=0.0))
            history.append(change)
            row, col = new_r, new_c
            if change <= tol:
                return row, col
        raise ConvergenceError(f"the bias-corrected projection x = RPC − δ(x) did not converge to {tol:g} px "
                               f"in {n} steps", history)

    def locate(self, row, col, height, **kwargs):
        """Measured image coordinates + height → ground: the RPC inverse (8.18.1) at x + δ.

        Parameters
        ----------
        row, col, height : array_like
            As :func:`locate`.
        **kwargs
            ``tolerance``, ``max_iterations``, ``extrapolation`` of :func:`locate`.

        Returns
        -------
        lon, lat : numpy.ndarray

        Raises
        ------
        InputError, DegenerateGeometryError, ConvergenceError
            As :func:`locate`.

        References
        ----------
        Chibunichev (2022), §8.6, eq. (8.6.1); §8.18, eq. (8.18.1).

        Examples
        --------
        >>> num = lambda k: [0.0] * k + [1.0] + [0.0] * (19 - k)
        >>> rpc = RPC(100, 200, 45, 5, 0, 50, 80, 0.01, 0.01, 500, num(2), num(0), num(1), num(0))
        >>> lon, lat = BiasCorrectedRPC(rpc, "shift", (1.5,), (-2.0,)).locate(98.5, 202.0, 0.0)
        >>> round(float(lon), 9), round(float(lat), 9)
        (5.0, 45.0)
        """
        r, c = self.to_rpc_space(row, col)
        return locate(self.rpc, r, c, height, **kwargs)


def fit_bias(rpc, row, col, lon, lat, height, model="affine", *, weights=None):
    """Estimate the image-space bias correction (8.6.1) of an RPC from ground control points.

    At every GCP δ = RPC(X, Y, Z) − measured; the coefficients of (8.6.2) shift, (8.6.3) affine or
    (8.6.4) second-order polynomial are solved from them: exactly with the minimum number of
    GCPs (1, 3, 6), by least squares (photolib.lsq.solve_normal_equations) with more.

    Parameters
    ----------
    rpc : RPC
        The model to correct.
    row, col : array_like
        Measured image coordinates of the GCPs, pixels.
    lon, lat, height : array_like
        Their ground coordinates.
    model : {"shift", "affine", "poly2"}
        The correction model (default ``"affine"``).
    weights : array_like, optional
        One weight per GCP (both coordinates); unit weights if omitted.

    Returns
    -------
    BiasCorrectedRPC

    Raises
    ------
    InputError
        Not an RPC, an unknown model, NaN/inf, different numbers of points, bad weights.
    DegenerateGeometryError
        Fewer GCPs than the model needs (1 / 3 / 6) or a configuration that does not determine
        it (collinear GCPs for the affine model, …).

    References
    ----------
    Chibunichev (2022), §8.6, eqs. (8.6.1)–(8.6.4); the example of §8.7 (Table 8.2).

    Examples
    --------
    >>> num = lambda k: [0.0] * k + [1.0] + [0.0] * (19 - k)
    >>> rpc = RPC(100, 200, 45, 5, 0, 50, 80, 0.01, 0.01, 500, num(2), num(0), num(1), num(0))
    >>> fixed = fit_bias(rpc, [98.0], [203.0], [5.0], [45.0], [0.0], "shift")
    >>> fixed.line_coeff, fixed.samp_coeff
    ((2.0,), (-3.0,))
    """
    from . import lsq
    _check_rpc(rpc)
    if model not in BIAS_MODELS:
        raise InputError(f"model must be one of {sorted(BIAS_MODELS)}, got {model!r}")
    row, col, lon, lat, height = _points(("row", "col", "lon", "lat", "height"), (row, col, lon, lat, height))
    need = BIAS_MODELS[model][1]
    if row.size < need:
        raise DegenerateGeometryError(f"the {model} bias model (8.6.{2 + list(BIAS_MODELS).index(model)}) has "
                                      f"{need} unknowns per coordinate: it needs at least {need} GCP(s), got {row.size}")
    w = None
    if weights is not None:
        (w,) = _points(("weights",), (weights,))
        if w.size != row.size or np.any(w <= 0):
            raise InputError("weights must be one positive number per GCP")
    pr, pc = project(rpc, lon, lat, height)
    dr, dc = pr - row, pc - col                              # δ = RPC − measured, (8.6.1)
    B = _bias_terms(model, (row - rpc.line_off) / rpc.line_scale, (col - rpc.samp_off) / rpc.samp_scale)
    names = BIAS_MODELS[model][0]
    try:
        cr = lsq.solve_normal_equations(B, -dr, w, names=names)[0]
        cc = lsq.solve_normal_equations(B, -dc, w, names=names)[0]
    except DegenerateGeometryError as exc:
        raise DegenerateGeometryError(f"the GCPs do not determine the {model} bias model: {exc}") from exc
    vr, vc = B @ cr - dr, B @ cc - dc
    rms = float(np.sqrt(np.mean(vr ** 2 + vc ** 2)))
    return BiasCorrectedRPC(rpc, model, tuple(cr), tuple(cc), rms, int(row.size))


# ====================================================================================== §8.8 stereo
@dataclass(frozen=True, eq=False)
class RPCIntersection:
    """Ground points intersected from two or more RPC images, eq. (8.8.9).

    Attributes
    ----------
    lon, lat, height : numpy.ndarray
        (n,) ground coordinates.
    residuals : numpy.ndarray
        (n, images, 2) image residuals v (line, sample) of (8.8.9) at the solution, pixels.
    rms : numpy.ndarray
        (n,) root mean square residual per point, √(mean(v²)) over its 2·images equations, pixels.
    iterations : int
        Gauss–Newton steps taken.

    References
    ----------
    Chibunichev (2022), §8.8 case 4, eq. (8.8.9).

    Examples
    --------
    >>> num = lambda k, v=1.0: [0.0] * k + [v] + [0.0] * (19 - k)
    >>> left = RPC(100, 200, 45, 5, 0, 50, 80, 0.01, 0.01, 500, num(2), num(0), num(1), num(0))
    >>> right = replace(left, samp_num_coeff=tuple(np.add(num(1), num(3, 0.3))))
    >>> res = intersect_rpc([left, right], [[100.0], [100.0]], [[200.0], [224.0]])
    >>> round(float(res.height[0]), 6), res.residuals.shape
    (500.0, (1, 2, 2))
    """

    lon: np.ndarray
    lat: np.ndarray
    height: np.ndarray
    residuals: np.ndarray
    rms: np.ndarray
    iterations: int

    def __post_init__(self):
        n = np.shape(self.lon)
        if len(n) != 1 or np.shape(self.lat) != n or np.shape(self.height) != n or np.shape(self.rms) != n \
                or np.ndim(self.residuals) != 3 or np.shape(self.residuals)[0] != n[0]:
            raise InputError("RPCIntersection: lon, lat, height, rms must be (n,) and residuals (n, images, 2)")


def intersect_rpc(models, rows, cols, *, height=None, tolerance=1e-9, max_iterations=20, min_angle_condition=1e12):
    """Least-squares forward intersection with RPCs, eq. (8.8.9), vectorised over points.

    For every point the correction equations ``b₁δX + b₂δY + b₃δZ + l_x = v_x``,
    ``c₁δX + c₂δY + c₃δZ + l_y = v_y`` of every image (partial derivatives of (8.5.7) from the
    RPC00B term derivatives, checked against sympy in the tests) are solved by Gauss–Newton with
    unknowns scaled by the first model's lon/lat/height scales. The start is the first image's
    ray at ``height`` (default: its height offset). Bias-corrected models enter through (8.6.1):
    their measured coordinates are first moved to the RPC's, x + δ.

    Parameters
    ----------
    models : sequence of RPC or BiasCorrectedRPC
        Two or more image models.
    rows, cols : array_like
        (images, n) or (images,) measured line and sample of each point in each image, pixels.
    height : float, optional
        Start height, metres.
    tolerance : float
        Stop when the update moves every projection by less than this, pixels.
    max_iterations : int
        Most Gauss–Newton steps.
    min_angle_condition : float
        Largest accepted condition number of a point's 3 × 3 normal matrix (near-parallel rays).

    Returns
    -------
    RPCIntersection

    Raises
    ------
    InputError
        Fewer than two models, a model of the wrong type, NaN/inf, shapes that do not match.
    DegenerateGeometryError
        The rays of a point are (nearly) parallel: its normal matrix is singular.
    ConvergenceError
        No convergence in ``max_iterations`` (the ``history`` holds the largest update, px).

    References
    ----------
    Chibunichev (2022), §8.8 case 4, eq. (8.8.9); the model: §8.5, eqs. (8.5.7)–(8.5.9).

    Examples
    --------
    >>> num = lambda k, v=1.0: [0.0] * k + [v] + [0.0] * (19 - k)
    >>> left = RPC(100, 200, 45, 5, 0, 50, 80, 0.01, 0.01, 500, num(2), num(0), num(1), num(0))
    >>> right = replace(left, samp_num_coeff=tuple(np.add(num(1), num(3, 0.3))))
    >>> res = intersect_rpc([left, right], [100.0, 100.0], [200.0, 224.0])
    >>> round(float(res.lon[0]), 9), round(float(res.lat[0]), 9), round(float(res.height[0]), 6)
    (5.0, 45.0, 500.0)
    """
    if isinstance(models, (RPC, BiasCorrectedRPC)) or not hasattr(models, "__len__"):
        raise InputError("models must be a sequence of two or more RPC / BiasCorrectedRPC")
    models = list(models)
    if len(models) < 2:
        raise InputError(f"an intersection needs two or more images, got {len(models)}")
    for m in models:
        if not isinstance(m, (RPC, BiasCorrectedRPC)):
            raise InputError(f"models must be RPC or BiasCorrectedRPC, got {type(m).__name__}")
    k = len(models)
    arrays = []
    for name, value in (("rows", rows), ("cols", cols)):
        if isinstance(value, (str, bytes)) or value is None:
            raise InputError(f"{name} must be an array of numbers")
        try:
            arr = np.asarray(value, dtype=float)
        except (TypeError, ValueError) as exc:
            raise InputError(f"{name} must be numeric: {exc}") from exc
        if arr.ndim == 1:
            arr = arr[:, None]
        if arr.ndim != 2 or arr.shape[0] != k:
            raise InputError(f"{name} must have shape (images, n) = ({k}, n), got {np.shape(value)}")
        if not np.all(np.isfinite(arr)):
            raise InputError(f"{name} contains NaN or inf")
        arrays.append(arr)
    rows, cols = arrays
    if rows.shape != cols.shape:
        raise InputError(f"rows and cols differ in shape: {rows.shape} and {cols.shape}")
    tol = _checks.number(tolerance, "tolerance", positive=True)
    n_iter = _checks.integer(max_iterations, "max_iterations", 1)
    limit = _checks.number(min_angle_condition, "min_angle_condition", positive=True)
    rpcs, obs_r, obs_c = [], [], []
    for m, r, c in zip(models, rows, cols):
        if isinstance(m, BiasCorrectedRPC):
            r, c = m.to_rpc_space(r, c)
            m = m.rpc
        rpcs.append(m)
        obs_r.append(r)
        obs_c.append(c)
    obs = np.stack([np.stack(obs_r, axis=-1), np.stack(obs_c, axis=-1)], axis=-1)   # (n, k, 2)
    first = rpcs[0]
    h0 = first.height_off if height is None else _checks.number(height, "height")
    n = rows.shape[1]
    lon, lat = locate(first, obs[:, 0, 0], obs[:, 0, 1], np.full(n, h0))
    h = np.full(n, float(h0))
    scale = np.array([first.long_scale, first.lat_scale, first.height_scale])
    history = []
    for it in range(1, n_iter + 1):
        pred, jac = [], []
        for m in rpcs:
            r, c, J = _rpc_eval(m, lon, lat, h)
            pred.append(np.stack([r, c], axis=-1))
            jac.append(J * scale)                                  # per normalised unknown
        pred = np.stack(pred, axis=1)                              # (n, k, 2)
        B = np.stack(jac, axis=1).reshape(n, 2 * k, 3)             # b, c of (8.8.9)
        Lf = (pred - obs).reshape(n, 2 * k)                        # l_x, l_y
        N = np.einsum("nij,nik->njk", B, B)
        cond = np.linalg.cond(N) if n else np.zeros(0)
        bad = ~np.isfinite(cond) | (cond > limit)
        if np.any(bad):
            raise DegenerateGeometryError(f"the RPC rays of {int(bad.sum())} point(s) are (nearly) parallel: the "
                                          f"normal matrix of (8.8.9) is singular (condition > {limit:g})")
        delta = -np.linalg.solve(N, np.einsum("nij,ni->nj", B, Lf)[..., None])[..., 0]
        move = float(np.max(np.abs(np.einsum("nij,nj->ni", B, delta)), initial=0.0))
        history.append(move)
        lon = lon + delta[:, 0] * scale[0]
        lat = lat + delta[:, 1] * scale[1]
        h = h + delta[:, 2] * scale[2]
        if move <= tol:
            break
    else:
        raise ConvergenceError(f"the RPC intersection did not converge to {tol:g} px in {n_iter} steps", history)
    pred = np.stack([np.stack(project(m, lon, lat, h), axis=-1) for m in rpcs], axis=1)
    v = pred - obs
    rms = np.sqrt(np.mean(v.reshape(n, -1) ** 2, axis=1))
    return RPCIntersection(lon, lat, h, v, rms, it)


# ====================================================================================== §8.18
def conventional_frame_rpc(rpcs, offsets, shapes, height_range, *, levels=5, step=100, check=200, seed=0):
    """One RPC for a conventional frame assembled from micro-frames with their own RPCs (§8.18).

    Each micro-frame i (``shapes[i]`` pixels, placed at ``offsets[i]`` = (row, col) of its first
    pixel in the conventional frame, e.g. from tie points) is sampled every ``step`` pixels on
    ``levels`` height planes; its RPC inverse (8.18.1) gives the ground point of every node; the
    nodes are moved to conventional-frame coordinates and one RPC is fitted to all of them
    (:func:`fit_rpc_points`). The check projects random points of random micro-frames at random
    heights with the combined RPC and compares them with their micro-frame position + offset.

    Parameters
    ----------
    rpcs : sequence of RPC
        The micro-frames' models.
    offsets : (m, 2) array_like
        Row and column of each micro-frame's pixel (0, 0) in the conventional frame.
    shapes : (m, 2) array_like of int
        Rows and columns of each micro-frame.
    height_range : (float, float)
        Lowest and highest terrain height, metres.
    levels, step : int, float
        Height planes (default 5; the book: 3, see :func:`fit_rpc`) and grid spacing.
    check : int
        Number of check points (0: none).
    seed : int
        Seed of the check points.

    Returns
    -------
    RPCFit
        The conventional frame's RPC (image coordinates in the conventional frame).

    Raises
    ------
    InputError
        Mismatched lengths, a model that is not an RPC, bad shapes, offsets or heights.
    DegenerateGeometryError, ConvergenceError
        From the micro-frames' inverses or the fit.

    References
    ----------
    Chibunichev (2022), §8.18, eq. (8.18.1) and Figs. 8.40–8.42.

    Examples
    --------
    >>> num = lambda k, v=1.0: [0.0] * k + [v] + [0.0] * (19 - k)
    >>> a = RPC(50, 50, 45, 5, 500, 50, 50, 0.01, 0.01, 500, num(2, -1), num(0), num(1), num(0))
    >>> b = a.shifted(0, 90)                       # the neighbouring matrix of one focal plane
    >>> fit = conventional_frame_rpc([a, b], [(0, 0), (0, 90)], [(101, 101), (101, 101)], (0, 1000), step=25)
    >>> fit.check_error < 1e-6
    True
    """
    if isinstance(rpcs, RPC) or not hasattr(rpcs, "__len__"):
        raise InputError("rpcs must be a sequence of RPC")
    rpcs = list(rpcs)
    for m in rpcs:
        _check_rpc(m)
    try:
        offs = np.asarray(offsets, dtype=float)
        shp = np.asarray(shapes)
    except (TypeError, ValueError) as exc:
        raise InputError(f"offsets and shapes must be numeric: {exc}") from exc
    if offs.shape != (len(rpcs), 2) or shp.shape != (len(rpcs), 2) or not rpcs:
        raise InputError(f"offsets and shapes must be ({len(rpcs)}, 2) arrays, one row per RPC; got "
                         f"{offs.shape} and {shp.shape}")
    if not np.all(np.isfinite(offs)):
        raise InputError("offsets contain NaN or inf")
    planes, lo, hi = _planes(height_range, levels)
    n_check = _checks.integer(check, "check", 0)
    parts = [[], [], [], [], []]
    for m, (r0, c0), s in zip(rpcs, offs, shp):
        rows_n, cols_n = _shape(tuple(s))
        R, C, Hh = np.meshgrid(_grid_axis(rows_n, step), _grid_axis(cols_n, step), planes, indexing="ij")
        R, C, Hh = R.ravel(), C.ravel(), Hh.ravel()
        lon, lat = locate(m, R, C, Hh)
        for lst, val in zip(parts, (R + r0, C + c0, lon, lat, Hh)):
            lst.append(val)
    fit = fit_rpc_points(*[np.concatenate(p) for p in parts])
    if n_check:
        rng = np.random.default_rng(seed)
        which = rng.integers(0, len(rpcs), n_check)
        worst = 0.0
        for i in np.unique(which):
            cnt = int(np.sum(which == i))
            rows_n, cols_n = _shape(tuple(shp[i]))
            cr, cc, ch = rng.uniform(0, rows_n - 1, cnt), rng.uniform(0, cols_n - 1, cnt), rng.uniform(lo, hi, cnt)
            lon, lat = locate(rpcs[i], cr, cc, ch)
            pr, pc = project(fit.rpc, lon, lat, ch, extrapolation=1.5)
            worst = max(worst, float(np.max(np.hypot(pr - cr - offs[i, 0], pc - cc - offs[i, 1]))))
        fit = replace(fit, check_error=worst)
    return fit
