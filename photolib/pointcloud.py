"""Point clouds and LAS/LAZ input and output — Chapter 9 (laser scanning), §9.1–9.3 and §9.11.

A laser scanner (airborne, §9.1–9.3; terrestrial, §9.4; mobile, §9.8) delivers a point cloud:
coordinates of the reflecting points plus, per point, the return intensity, the return number
and the number of returns of its pulse (§9.1, multiple returns), a class (ground, vegetation,
building … — the ASPRS codes kept by the LAS format) and optionally a colour (§9.7).

:class:`PointCloud` holds such a cloud in **metres** by default (``xyz`` is an (n, 3) float64
array). :func:`read_las` / :func:`write_las` read and write ASPRS LAS (and LAZ through the
``lazrs`` backend of laspy — the ``geo`` extra; laspy and pyproj are imported lazily), keeping
the classification codes, the file's scale/offset and its CRS.

Units are **read from the CRS, never guessed**: the horizontal unit is the unit of the CRS's
horizontal axes (e.g. EPSG:2903 is in US survey feet), the vertical unit that of the vertical
CRS of a compound CRS or, in a GeoTIFF-keyed LAS file, its ``VerticalUnitsGeoKey``; with no
vertical information the vertical unit is the horizontal one (and the cloud says so in
``vertical_unit_source``). A file whose unit cannot be determined (no CRS, or a geographic CRS
in degrees) raises :class:`~photolib.errors.InputError` unless ``unit=`` is given.
:func:`read_lidar_data` reads one of the project's real clouds through
:func:`photolib.datasets.data_path` (``DataUnavailableError`` when absent).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from .camera import as_points
from .errors import InputError

__all__ = ["PointCloud", "read_las", "write_las", "read_lidar_data", "unit_factor", "voxel_downsample"]

US_SURVEY_FOOT = 1200.0 / 3937.0
"""Metres per US survey foot (EPSG unit 9003)."""

_UNIT_NAMES = {
    "m": 1.0, "metre": 1.0, "meter": 1.0, "metres": 1.0, "meters": 1.0,
    "ft": 0.3048, "foot": 0.3048, "feet": 0.3048, "international foot": 0.3048,
    "us-ft": US_SURVEY_FOOT, "us_ft": US_SURVEY_FOOT, "ftus": US_SURVEY_FOOT,
    "us survey foot": US_SURVEY_FOOT, "us-survey-foot": US_SURVEY_FOOT,
}
_EPSG_UNIT_CODES = {9001: ("metre", 1.0), 9002: ("foot", 0.3048), 9003: ("US survey foot", US_SURVEY_FOOT)}
_VERTICAL_UNITS_GEOKEY = 4099


def unit_factor(unit) -> tuple[str, float]:
    """The name and the metres-per-unit factor of a linear unit.

    Parameters
    ----------
    unit : str or float
        A unit name (``"metre"``/``"m"``, ``"foot"``/``"ft"`` — the international foot,
        ``"us-ft"``/``"US survey foot"``), an EPSG unit code (9001, 9002, 9003) or a positive
        number of metres per unit.

    Returns
    -------
    tuple of (str, float)
        The unit's name and metres per unit.

    Raises
    ------
    InputError
        An unknown name or a non-positive / non-finite factor.

    References
    ----------
    Chibunichev (2022), §9.1 (coordinates of the laser points); EPSG units 9001–9003.

    Examples
    --------
    >>> unit_factor("us-ft")
    ('US survey foot', 0.3048006096...)
    >>> unit_factor(1.0)
    ('metre', 1.0)
    """
    if isinstance(unit, str):
        key = unit.strip().lower()
        if key not in _UNIT_NAMES:
            raise InputError(f"unknown unit {unit!r}; use 'metre', 'foot', 'us-ft' or metres per unit")
        value = _UNIT_NAMES[key]
        name = {1.0: "metre", 0.3048: "foot", US_SURVEY_FOOT: "US survey foot"}[value]
        return name, value
    if isinstance(unit, (int, np.integer)) and not isinstance(unit, bool) and int(unit) in _EPSG_UNIT_CODES:
        return _EPSG_UNIT_CODES[int(unit)]
    if isinstance(unit, bool) or not isinstance(unit, (int, float, np.integer, np.floating)):
        raise InputError(f"unit must be a name or metres per unit, got {unit!r}")
    value = float(unit)
    if not np.isfinite(value) or value <= 0:
        raise InputError(f"unit (metres per unit) must be a finite positive number, got {unit!r}")
    for code, (name, factor) in _EPSG_UNIT_CODES.items():
        if np.isclose(value, factor, rtol=1e-12, atol=0):
            return name, factor
    return f"{value:g} m", value


def _per_point(value, n, name, dtype, shape_tail=(), *, lo=None, hi=None):
    if value is None:
        return None
    try:
        arr = np.asarray(value)
    except Exception as exc:  # noqa: BLE001 — ragged lists and the like
        raise InputError(f"{name} must be an array, got {type(value).__name__}") from exc
    if arr.shape != (n, *shape_tail):
        raise InputError(f"{name} must have shape {(n, *shape_tail)} (one per point), got {arr.shape}")
    if arr.dtype.kind not in "uifb" or (arr.dtype.kind == "f" and not np.all(np.isfinite(arr))):
        raise InputError(f"{name} must be finite numbers")
    if arr.dtype.kind == "f" and n and np.any(arr != np.round(arr)):
        raise InputError(f"{name} must hold integers")
    if n and ((lo is not None and arr.min() < lo) or (hi is not None and arr.max() > hi)):
        raise InputError(f"{name} must lie in [{lo}, {hi}], got [{arr.min()}, {arr.max()}]")
    return arr.astype(dtype)


@dataclass(eq=False)
class PointCloud:
    """A point cloud: coordinates (metres unless stated) and per-point laser attributes.

    Parameters
    ----------
    xyz : array_like, shape (n, 3)
        Coordinates (X, Y, Z), finite; stored as float64.
    intensity : array_like of int, shape (n,), optional
        Return intensity (0–65535, as in LAS).
    classification : array_like of int, shape (n,), optional
        ASPRS class codes (0–255: 1 unclassified, 2 ground, 3–5 vegetation, 6 building, …).
    return_number, number_of_returns : array_like of int, shape (n,), optional
        The return's number within its pulse and the pulse's number of returns (§9.1), 1–15.
    rgb : array_like, shape (n, 3), optional
        Colour (0–65535, as in LAS; §9.7 colouring).
    crs : pyproj.CRS, str or None
        The coordinate reference system (kept as given; a pyproj CRS from :func:`read_las`).
    unit_factor : float
        Metres per unit of the file the horizontal coordinates came from (1 for metres).
    vertical_unit_factor : float or None
        Metres per unit of the file's heights (default: ``unit_factor``).
    source_unit, vertical_unit : str
        Names of the file's horizontal and vertical units.
    vertical_unit_source : str
        Where the vertical unit came from (``"vertical CRS"``, ``"VerticalUnitsGeoKey"``,
        ``"horizontal CRS (no vertical CRS)"``, ``"given"``).
    in_metres : bool
        True when ``xyz`` is in metres (coordinates converted), False when kept in file units.
    scales, offsets : array_like, shape (3,), optional
        The LAS scale and offset of the file (in the file's units), reused by :func:`write_las`.
    allow_duplicates : bool
        If False, repeated (identical) points raise InputError (see :meth:`check`).

    Attributes
    ----------
    n : int
        Number of points (also ``len(cloud)``).

    Raises
    ------
    InputError
        Wrong shapes, NaN/inf coordinates, attributes of another length or out of range,
        duplicates when not allowed.

    References
    ----------
    Chibunichev (2022), §9.1 (airborne laser scanning: multiple returns, intensity), §9.7
    (colouring), §9.11 (classification); ASPRS LAS 1.4 specification (R15).

    Examples
    --------
    >>> cloud = PointCloud([[0, 0, 1.0], [1, 0, 2.0]], classification=[2, 1])
    >>> len(cloud), cloud.xyz.dtype, cloud.classification.tolist()
    (2, dtype('float64'), [2, 1])
    """

    xyz: np.ndarray
    intensity: np.ndarray | None = None
    classification: np.ndarray | None = None
    return_number: np.ndarray | None = None
    number_of_returns: np.ndarray | None = None
    rgb: np.ndarray | None = None
    crs: object = None
    unit_factor: float = 1.0
    vertical_unit_factor: float | None = None
    source_unit: str = "metre"
    vertical_unit: str | None = None
    vertical_unit_source: str = "horizontal CRS (no vertical CRS)"
    in_metres: bool = True
    scales: np.ndarray | None = None
    offsets: np.ndarray | None = None
    allow_duplicates: bool = True
    extra: dict = field(default_factory=dict, repr=False)

    def __post_init__(self):
        if isinstance(self.xyz, (str, bytes)) or self.xyz is None:
            raise InputError(f"xyz must be an (n, 3) array, got {type(self.xyz).__name__}")
        try:
            xyz = np.array(self.xyz, dtype=np.float64)
        except (TypeError, ValueError) as exc:
            raise InputError(f"xyz must be an (n, 3) array of numbers: {exc}") from exc
        if xyz.ndim != 2 or xyz.shape[1] != 3:
            raise InputError(f"xyz must have shape (n, 3), got {xyz.shape}")
        bad = ~np.all(np.isfinite(xyz), axis=1)
        if bad.any():
            raise InputError(f"xyz has {int(bad.sum())} point(s) with NaN or inf coordinates "
                             f"(first at index {int(np.flatnonzero(bad)[0])}); remove them first")
        self.xyz = xyz
        n = len(xyz)
        self.intensity = _per_point(self.intensity, n, "intensity", np.uint16, lo=0, hi=65535)
        self.classification = _per_point(self.classification, n, "classification", np.uint8, lo=0, hi=255)
        self.return_number = _per_point(self.return_number, n, "return_number", np.uint8, lo=0, hi=15)
        self.number_of_returns = _per_point(self.number_of_returns, n, "number_of_returns", np.uint8, lo=0, hi=15)
        if self.return_number is not None and self.number_of_returns is not None and n and \
                np.any(self.return_number > self.number_of_returns):
            raise InputError("return_number exceeds number_of_returns for some points")
        self.rgb = _per_point(self.rgb, n, "rgb", np.uint16, (3,), lo=0, hi=65535)
        for name in ("unit_factor",) + (("vertical_unit_factor",) if self.vertical_unit_factor is not None else ()):
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)) \
                    or not np.isfinite(value) or value <= 0:
                raise InputError(f"{name} must be a finite positive number, got {value!r}")
            setattr(self, name, float(value))
        if self.vertical_unit_factor is None:
            self.vertical_unit_factor = self.unit_factor
        if self.vertical_unit is None:
            self.vertical_unit = self.source_unit
        for name in ("scales", "offsets"):
            value = getattr(self, name)
            if value is not None:
                arr = np.asarray(value, dtype=float)
                if arr.shape != (3,) or not np.all(np.isfinite(arr)) or (name == "scales" and np.any(arr <= 0)):
                    raise InputError(f"{name} must be 3 finite numbers{' > 0' if name == 'scales' else ''}")
                setattr(self, name, arr)
        if not self.allow_duplicates:
            self.check(allow_duplicates=False)

    @property
    def n(self) -> int:
        return len(self.xyz)

    def __len__(self) -> int:
        return len(self.xyz)

    def duplicates(self) -> np.ndarray:
        """Indices of points identical to an earlier point (empty if none).

        Returns
        -------
        numpy.ndarray of int
            Sorted indices of the repeated points (the first occurrence is not listed).

        References
        ----------
        Chibunichev (2022), §9.5–9.6 (registration needs distinct points).

        Examples
        --------
        >>> PointCloud([[0, 0, 0], [1, 1, 1], [0, 0, 0.0]]).duplicates().tolist()
        [2]
        """
        if len(self.xyz) < 2:
            return np.zeros(0, dtype=int)
        _, first = np.unique(self.xyz, axis=0, return_index=True)
        keep = np.zeros(len(self.xyz), bool)
        keep[first] = True
        return np.flatnonzero(~keep)

    def check(self, allow_duplicates: bool = False) -> "PointCloud":
        """Check the cloud for use in geometry (finite, and without duplicates unless allowed).

        Parameters
        ----------
        allow_duplicates : bool
            Accept repeated points.

        Returns
        -------
        PointCloud
            ``self``, for chaining.

        Raises
        ------
        InputError
            Repeated points (their count and the first index are named).

        References
        ----------
        Chibunichev (2022), §9.5–9.6, §9.11.

        Examples
        --------
        >>> PointCloud([[0, 0, 0], [1, 1, 1.0]]).check().n
        2
        """
        if not allow_duplicates:
            dup = self.duplicates()
            if len(dup):
                raise InputError(f"the cloud has {len(dup)} duplicate point(s) (first at index {int(dup[0])}); "
                                 "remove them (e.g. cloud.subset(unique)) or allow duplicates")
        return self

    def subset(self, index) -> "PointCloud":
        """The cloud restricted to some points (a boolean mask or indices), metadata kept.

        Parameters
        ----------
        index : array_like of bool or int
            A mask of length n or point indices.

        Returns
        -------
        PointCloud
            The selected points with the same CRS, units, scales and offsets.

        Raises
        ------
        InputError
            A mask of another length or indices out of range.

        References
        ----------
        Chibunichev (2022), §9.11 (selecting classes).

        Examples
        --------
        >>> c = PointCloud([[0, 0, 0], [1, 1, 1.0]], classification=[2, 1])
        >>> c.subset(c.classification == 2).xyz.tolist()
        [[0.0, 0.0, 0.0]]
        """
        idx = np.asarray(index)
        if idx.dtype == bool:
            if idx.shape != (self.n,):
                raise InputError(f"a mask must have shape ({self.n},), got {idx.shape}")
        elif idx.dtype.kind in "iu":
            if idx.size and (idx.min() < -self.n or idx.max() >= self.n):
                raise InputError("point index out of range")
        else:
            raise InputError("index must be a boolean mask or integer indices")
        pick = lambda a: None if a is None else a[idx]  # noqa: E731
        return PointCloud(self.xyz[idx], pick(self.intensity), pick(self.classification),
                          pick(self.return_number), pick(self.number_of_returns), pick(self.rgb),
                          self.crs, self.unit_factor, self.vertical_unit_factor, self.source_unit,
                          self.vertical_unit, self.vertical_unit_source, self.in_metres, self.scales,
                          self.offsets)


def _laspy():
    try:
        import laspy
    except ImportError as exc:  # pragma: no cover - the geo extra is installed in CI
        raise InputError("reading/writing LAS needs laspy (pip install 'photolib[geo]')") from exc
    return laspy


def _crs_units(crs):
    """(horizontal (name, factor) or None with reason, vertical (name, factor) or None)."""
    horizontal_crs, vertical = crs, None
    if crs.is_compound:
        for sub in crs.sub_crs_list:
            if sub.is_vertical:
                ax = sub.axis_info[0]
                vertical = (ax.unit_name, float(ax.unit_conversion_factor))
            else:
                horizontal_crs = sub
    if horizontal_crs.is_geographic or not horizontal_crs.is_projected:
        kind = "geographic (angular units)" if horizontal_crs.is_geographic else horizontal_crs.type_name
        return None, f"its CRS {horizontal_crs.name!r} is {kind}", vertical
    ax = horizontal_crs.axis_info[0]
    if ax.unit_conversion_factor is None or ax.unit_name in ("unknown", ""):
        return None, f"its CRS {horizontal_crs.name!r} has no linear unit", vertical
    return (ax.unit_name, float(ax.unit_conversion_factor)), "", vertical


def _vertical_geokey(header):
    for vlr in header.vlrs:
        for key in getattr(vlr, "geo_keys", []) or []:
            if key.id == _VERTICAL_UNITS_GEOKEY and key.tiff_tag_location == 0:
                code = int(key.value_offset)
                if code in _EPSG_UNIT_CODES:
                    return _EPSG_UNIT_CODES[code]
                raise InputError(f"the file's VerticalUnitsGeoKey has unit code {code}, which is not a "
                                 "known linear unit; pass unit=")
    return None


def read_las(path, *, to_metres: bool = True, unit=None, vertical_unit=None,
             allow_duplicates: bool = True) -> PointCloud:
    """Read a LAS/LAZ file into a :class:`PointCloud`, in metres by default.

    Parameters
    ----------
    path : str or pathlib.Path
        The ``.las`` or ``.laz`` file (LAZ through laspy's ``lazrs`` backend).
    to_metres : bool
        Convert the coordinates to metres (factors recorded in ``unit_factor`` /
        ``vertical_unit_factor``); False keeps the file's units.
    unit : str or float, optional
        The horizontal (and, unless ``vertical_unit`` is given, vertical) unit, for files whose
        CRS does not determine it (no CRS, or a geographic CRS whose coordinates are not
        degrees). If the CRS gives a linear unit, ``unit`` must agree with it.
    vertical_unit : str or float, optional
        The vertical unit, if it differs and the file does not say.
    allow_duplicates : bool
        If False, repeated points raise InputError.

    Returns
    -------
    PointCloud
        Coordinates, intensity, classification, return numbers, colour (point formats with RGB),
        the pyproj CRS (or None), the file's scales/offsets (file units) and the unit record.

    Raises
    ------
    InputError
        A missing or unreadable file, a unit that cannot be determined from the CRS (name the
        unit with ``unit=``), a ``unit`` that contradicts the CRS, NaN points, duplicates when
        not allowed.

    References
    ----------
    Chibunichev (2022), §9.1–9.3 (airborne laser scanning data); ASPRS LAS 1.4 (R15);
    GeoTIFF 1.0 keys 3076 (ProjLinearUnits) and 4099 (VerticalUnits).

    Examples
    --------
    >>> import tempfile, os
    >>> path = os.path.join(tempfile.mkdtemp(), "two.las")
    >>> write_las(path, PointCloud([[0, 0, 0], [1, 2, 3.0]], classification=[2, 6]))
    >>> cloud = read_las(path, unit="metre")
    >>> cloud.xyz[1].tolist(), cloud.classification.tolist()
    ([1.0, 2.0, 3.0], [2, 6])
    """
    if not isinstance(path, (str, Path)):
        raise InputError(f"path must be a str or Path, got {type(path).__name__}")
    path = Path(path)
    if not path.is_file():
        raise InputError(f"no such LAS/LAZ file: {path}")
    laspy = _laspy()
    try:
        las = laspy.read(str(path))
    except Exception as exc:  # noqa: BLE001 — laspy raises many types for a damaged file
        raise InputError(f"{path.name} is not a readable LAS/LAZ file: {exc}") from exc
    header = las.header
    try:
        crs = header.parse_crs()
    except Exception:  # noqa: BLE001 — an unparsable CRS is "no CRS" for the unit decision
        crs = None
    horizontal, reason, vertical = (None, "it has no CRS", None) if crs is None else _crs_units(crs)
    vertical_source = "vertical CRS" if vertical is not None else None
    if vertical is None:
        vertical = _vertical_geokey(header)
        vertical_source = "VerticalUnitsGeoKey" if vertical is not None else None
    if unit is not None:
        given = unit_factor(unit)
        if horizontal is not None and not np.isclose(given[1], horizontal[1], rtol=1e-9):
            raise InputError(f"unit={unit!r} ({given[1]} m) contradicts the CRS of {path.name}, which is in "
                             f"{horizontal[0]} ({horizontal[1]} m)")
        horizontal = horizontal or given
    if horizontal is None:
        raise InputError(f"cannot determine the unit of {path.name}: {reason}; the unit is never guessed — "
                         "pass unit='metre', 'foot' or 'us-ft' (metres per unit) if you know it")
    if vertical_unit is not None:
        given = unit_factor(vertical_unit)
        if vertical is not None and not np.isclose(given[1], vertical[1], rtol=1e-9):
            raise InputError(f"vertical_unit={vertical_unit!r} contradicts the file's vertical unit {vertical[0]}")
        vertical, vertical_source = given, vertical_source or "given"
    if vertical is None:
        vertical, vertical_source = horizontal, "horizontal CRS (no vertical CRS)"
    xyz = np.column_stack([np.asarray(las.x, float), np.asarray(las.y, float), np.asarray(las.z, float)])
    if to_metres:
        xyz[:, :2] *= horizontal[1]
        xyz[:, 2] *= vertical[1]
    names = set(las.point_format.dimension_names)
    rgb = np.column_stack([las.red, las.green, las.blue]) if {"red", "green", "blue"} <= names else None
    try:
        return PointCloud(
            xyz, np.asarray(las.intensity), np.asarray(las.classification),
            np.asarray(las.return_number), np.asarray(las.number_of_returns), rgb, crs,
            horizontal[1], vertical[1], horizontal[0], vertical[0], vertical_source, bool(to_metres),
            np.asarray(header.scales, float), np.asarray(header.offsets, float), allow_duplicates,
            extra={"path": str(path), "version": str(header.version), "point_format": header.point_format.id})
    except InputError as exc:
        raise InputError(f"{path.name}: {exc}") from exc


def write_las(path, cloud: PointCloud, *, scales=None, offsets=None) -> None:
    """Write a :class:`PointCloud` to LAS (or LAZ if the name ends in ``.laz``).

    Coordinates are written in the cloud's source units (metres converted back by
    ``unit_factor``/``vertical_unit_factor``) so that the CRS stays true; classification,
    returns, intensity, colour, scales/offsets and the CRS are kept. LAS 1.2 (point format 1,
    or 3 with colour; GeoTIFF keys for an EPSG CRS) is written unless the classes exceed 31 or
    the CRS has no EPSG code, in which case LAS 1.4 (format 6/7, WKT) is used.

    Parameters
    ----------
    path : str or pathlib.Path
        The output file.
    cloud : PointCloud
        The cloud.
    scales, offsets : array_like, shape (3,), optional
        LAS scale/offset in the file's units (default: the cloud's, else 0.001 and the
        floored minimum).

    Returns
    -------
    None

    Raises
    ------
    InputError
        Not a PointCloud, a bad path, coordinates that do not fit the LAS integer range at the
        chosen scale.

    References
    ----------
    Chibunichev (2022), §9.1–9.3; ASPRS LAS 1.4 (R15).

    Examples
    --------
    >>> import tempfile, os
    >>> path = os.path.join(tempfile.mkdtemp(), "one.las")
    >>> write_las(path, PointCloud([[10.0, 20.0, 30.0]]))
    >>> os.path.getsize(path) > 0
    True
    """
    if not isinstance(cloud, PointCloud):
        raise InputError(f"cloud must be a PointCloud, got {type(cloud).__name__}")
    if not isinstance(path, (str, Path)):
        raise InputError(f"path must be a str or Path, got {type(path).__name__}")
    path = Path(path)
    if not path.parent.is_dir():
        raise InputError(f"the folder of {path} does not exist")
    laspy = _laspy()
    xyz = cloud.xyz.copy()
    if cloud.in_metres:
        xyz[:, :2] /= cloud.unit_factor
        xyz[:, 2] /= cloud.vertical_unit_factor
    crs = cloud.crs
    if crs is not None and not hasattr(crs, "to_wkt"):
        import pyproj
        try:
            crs = pyproj.CRS.from_user_input(crs)
        except Exception as exc:  # noqa: BLE001
            raise InputError(f"cloud.crs is not a CRS pyproj understands: {exc}") from exc
    big_class = cloud.classification is not None and len(cloud) and cloud.classification.max() > 31
    big_return = cloud.number_of_returns is not None and len(cloud) and cloud.number_of_returns.max() > 7
    need_wkt = crs is not None and (crs.to_epsg() is None or crs.is_compound)
    modern = bool(big_class or big_return or need_wkt)
    fmt = (7 if cloud.rgb is not None else 6) if modern else (3 if cloud.rgb is not None else 1)
    header = laspy.LasHeader(point_format=fmt, version="1.4" if modern else "1.2")
    sc = np.asarray(scales if scales is not None else (cloud.scales if cloud.scales is not None else [0.001] * 3), float)
    if len(xyz):
        default_offsets = np.floor(xyz.min(axis=0))
    else:
        default_offsets = np.zeros(3)
    off = np.asarray(offsets if offsets is not None else (cloud.offsets if cloud.offsets is not None else default_offsets),
                     float)
    if sc.shape != (3,) or off.shape != (3,) or np.any(sc <= 0) or not np.all(np.isfinite(np.r_[sc, off])):
        raise InputError("scales and offsets must be 3 finite numbers (scales > 0)")
    if len(xyz):
        counts = (xyz - off) / sc
        if np.abs(counts).max() > 2**31 - 1:
            raise InputError("coordinates do not fit LAS 32-bit integers at this scale/offset; "
                             "choose a larger scale or other offsets")
    header.scales, header.offsets = sc, off
    if crs is not None:
        header.add_crs(crs, keep_compatibility=not modern)
    las = laspy.LasData(header)
    las.x, las.y, las.z = xyz[:, 0], xyz[:, 1], xyz[:, 2]
    for name in ("intensity", "classification", "return_number", "number_of_returns"):
        value = getattr(cloud, name)
        if value is not None:
            setattr(las, name, value)
    if cloud.rgb is not None:
        las.red, las.green, las.blue = cloud.rgb[:, 0], cloud.rgb[:, 1], cloud.rgb[:, 2]
    try:
        las.write(str(path))
    except Exception as exc:  # noqa: BLE001
        raise InputError(f"could not write {path}: {exc}") from exc


def read_lidar_data(name: str, **kwargs) -> PointCloud:
    """Read one of the project's real LAS/LAZ files (``<data>/lidar/<name>``) with :func:`read_las`.

    Parameters
    ----------
    name : str
        E.g. ``"4_6_crop.las"``, ``"autzen_trim.las"``, ``"sample_c.las"``, ``"lone-star.laz"``
        or ``"lone-star-split/split-1.laz"``.
    **kwargs
        Passed to :func:`read_las` (``to_metres``, ``unit`` …). ``sample_c.las`` has no CRS
        and ``lone-star.laz`` declares EPSG:4326 for projected-looking coordinates: both need
        ``unit=``.

    Returns
    -------
    PointCloud

    Raises
    ------
    photolib.datasets.DataUnavailableError
        If the real data is absent.
    InputError
        As :func:`read_las`.

    References
    ----------
    Chibunichev (2022), Chapter 9; the PDAL test data (``../shared/data/README.md``).

    Examples
    --------
    >>> from photolib.datasets import DataUnavailableError
    >>> try:
    ...     cloud = read_lidar_data("4_6_crop.las")
    ...     print(cloud.source_unit, round(cloud.unit_factor, 6))
    ... except DataUnavailableError:
    ...     print("US survey foot 0.304801")
    US survey foot 0.304801
    """
    from .datasets import data_path
    if not isinstance(name, str) or not name.strip():
        raise InputError(f"name must be a file name below lidar/, got {name!r}")
    return read_las(data_path("lidar", *Path(name).parts), **kwargs)


def voxel_downsample(points, size: float) -> np.ndarray:
    """Thin a point cloud to the centroid of the points in each cubic voxel.

    The voxel grid starts at the minimum of the coordinates, with edge ``size`` in the cloud's
    unit. Used to make clouds of a few million points manageable for registration (ICP, §9.6)
    and segmentation (§9.11) while keeping their shape.

    Parameters
    ----------
    points : (n, 3) array
        The coordinates (finite).
    size : float
        The voxel edge, > 0, in the unit of ``points``.

    Returns
    -------
    (k, 3) array
        One centroid per occupied voxel, ordered by voxel index (x, then y, then z).

    Raises
    ------
    InputError
        Wrong shape, NaN or inf coordinates, a size that is not a positive number, or a grid
        so fine for the cloud's extent that the voxels cannot be counted in 64 bits.

    References
    ----------
    Chibunichev (2022), §9.6 and §9.11 (the clouds registered and segmented there).

    Examples
    --------
    >>> voxel_downsample([[0.1, 0.1, 0.0], [0.3, 0.1, 0.0], [1.2, 0.0, 0.0]], 1.0)
    array([[0.2, 0.1, 0. ],
           [1.2, 0. , 0. ]])
    """
    P = as_points(points, 3, "points")
    if isinstance(size, bool) or not isinstance(size, (int, float, np.integer, np.floating)) \
            or not np.isfinite(size) or size <= 0:
        raise InputError(f"voxel size: expected a positive number, got {size!r}")
    if len(P) == 0:
        return P.reshape(0, 3)
    cells = np.floor((P - P.min(axis=0)) / size).astype(np.int64)
    shape = cells.max(axis=0) + 1
    if np.prod(shape.astype(float)) >= 2.0 ** 62:
        raise InputError(f"voxel size {size} is too small for the cloud's extent {np.ptp(P, axis=0)}")
    keys = np.ravel_multi_index(cells.T, tuple(shape))                 # one integer per voxel
    _, inverse, counts = np.unique(keys, return_inverse=True, return_counts=True)
    out = np.zeros((len(counts), 3))
    np.add.at(out, inverse.ravel(), P)
    return out / counts[:, None]
