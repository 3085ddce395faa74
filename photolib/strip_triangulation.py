"""Strip and block phototriangulation from models — Chapter 3, §3.2–§3.4.

§3.2 "Маршрутная фототриангуляция методом продолжения" (strip triangulation by continuation),
§3.3 "Блочная фототриангуляция по методу независимых маршрутов" (block by independent strips),
§3.4 "Построение и уравнивание маршрутной и блочной фототриангуляции по методу независимых
моделей" (strip and block by independent models).

All three methods work on *models*: point sets in a model's own frame, built from a pair of
adjacent images by relative orientation and intersection (Chapter 2; :func:`pair_model` calls
:func:`photolib.image_pair.relative_orientation` and :func:`photolib.image_pair.build_model`).
A model (or a whole strip model) is tied to another frame by the seven-element spatial
similarity X = X₀ + A_M·X_M·t of (2.10.4) — :class:`photolib.image_pair.SimilarityTransform`.

* §3.2 continuation: :func:`join_model` ((3.2.1) from the tie points of the triple overlap and
  the shared projection centre), :func:`continuation_strip` ((3.2.2), double determinations,
  their differences ΔX, ΔY, ΔZ and means), :func:`orient_strip` ((3.2.3) by control),
  :func:`fit_strip_polynomial` / :class:`StripPolynomial` (second-order correction (3.2.4)/(3.2.5)
  in the strip-aligned auxiliary system (3.2.6)/(3.2.7), centred coordinates).
* §3.3/§3.4 simultaneous adjustment of the seven elements of every unit (strip or model):
  :func:`unit_equations` builds the correction equations (3.3.3)/(3.3.4) of the tie conditions
  (3.3.1)/(3.4.1), the control conditions (3.3.2)/(3.4.2) and the GNSS projection centres
  (3.4.3); :func:`adjust_independent_units` solves them (final coordinates (3.3.5)/(3.4.4) as
  means); :func:`image_orientations` gives the images' exterior orientation by (3.4.5)/(3.4.6).
* Counts: :func:`count_independent_strips` ((3.3.6), (3.3.7)), :func:`count_independent_models`
  (§3.4, N = 7n, M = 3m + 3k + 2i + l + S, S = 6n) and :func:`structure_counts` (m, k, i, l, S
  read off an actual block the way the book counts them).
* Synthetic inputs: :func:`layout_block` (vertical images on a regular layout with tie points in
  the triple-overlap and side-overlap bands, as in figs 3.2, 3.7, 3.8) and :func:`layout_models`.

Sign convention of Chapter 3: every condition is "computed − given = 0", so the free terms are
L = computed − given and the correction equations read B·δ + L = V (as :mod:`photolib.lsq`).
The partial derivatives come from the sympy model :func:`photolib.derivations.similarity_model`
(φ = X − X₀ − t·A_M·X_M of (2.11.1), whose sign is the opposite: ∂G/∂p = −∂φ/∂p). The book
prints no coefficients for (3.3.3)/(3.3.4) and refers to (2.11.2) instead, whose α-derivatives
have the wrong sign on every sin κ term (see the Chapter 2 errata); nothing here uses them.
Units: image coordinates in mm, model coordinates in model units, object coordinates in m,
angles in radians.
"""

from __future__ import annotations

from collections import defaultdict, deque
from dataclasses import dataclass, field

import numpy as np

from . import derivations
from .camera import ExteriorOrientation, InteriorOrientation, as_points
from .errors import DegenerateGeometryError, InputError
from .image_pair import (
    SIMILARITY_NAMES, SimilarityTransform, StereoModel, level_similarity_start, absolute_orientation, build_model,
    image_orientation_from_model, relative_orientation, similarity_closed_form,
)
from .lsq import Adjustment, gauss_newton, solve_normal_equations
from .rotation import DEFAULT_ORDER, check_order, rot_z
from .synthetic import ORIENTATION, TIE, Block, Observations, strip_layout, terrain_height


__all__ = ["centre_id", "UnitModel", "pair_model", "join_model", "ContinuationStrip", "continuation_strip",
           "orient_strip", "POLYNOMIAL_TERMS", "strip_axis_angle", "StripPolynomial", "fit_strip_polynomial",
           "EquationRow", "tie_pairs", "grid_adjacency", "unit_equations", "initial_transforms", "UnitsAdjustment",
           "adjust_independent_units", "image_orientations", "count_independent_strips",
           "count_independent_models", "structure_counts", "layout_block", "layout_models"]


def _float(value, what: str) -> float:
    try:
        return float(value)
    except (TypeError, ValueError):
        raise InputError(f"{what} must be a number, got {value!r}") from None


def _int(value, what: str) -> int:
    if isinstance(value, bool) or not (isinstance(value, (int, np.integer))
                                       or (isinstance(value, (float, np.floating)) and float(value).is_integer())):
        raise InputError(f"{what} must be an integer, got {value!r}")
    return int(value)


def centre_id(image: int) -> str:
    """Identifier of the projection centre of image ``image`` in model point lists: ``"S<k>"``.

    Parameters
    ----------
    image : int
        Image number.

    Returns
    -------
    str

    Raises
    ------
    InputError
        ``image`` is not a non-negative integer.

    References
    ----------
    Chibunichev (2022), §3.2 (the projection centre S as a tie point of adjacent models), §3.4 (3.4.3).

    Examples
    --------
    >>> from photolib.strip_triangulation import centre_id
    >>> centre_id(3)
    'S3'
    """
    return f"S{_int(image, 'image')}"


# --- models ---------------------------------------------------------------------------------------------
@dataclass
class UnitModel:
    """A model or a strip model: identified points in the unit's own frame.

    Parameters
    ----------
    name : str
        Name.
    ids : sequence
        Hashable point labels; projection centres are labelled :func:`centre_id`.
    points : (n, 3) array
        Coordinates in the unit's frame.
    images : tuple of int
        The images whose centres the unit carries.
    stereo : StereoModel, optional
        The Chapter 2 model it came from (needed only for the image orientations (3.4.5)).

    Raises
    ------
    InputError
        Ids and points of different count, duplicate ids, NaN/inf, wrong shapes.

    References
    ----------
    Chibunichev (2022), §3.2 (models, strip models), §3.4 (independent models).

    Examples
    --------
    >>> from photolib.strip_triangulation import UnitModel
    >>> UnitModel("M1", [1, 2, "S0"], [[0, 0, 0], [1, 0, 0], [0, 0, 1]])
    UnitModel('M1': 3 points, images ())
    """

    name: str
    ids: tuple
    points: np.ndarray
    images: tuple = ()
    stereo: StereoModel | None = field(default=None, repr=False)

    def __post_init__(self):
        self.ids = tuple(self.ids)
        self.points = as_points(self.points, 3, f"points of unit {self.name}")
        if len(self.ids) != len(self.points):
            raise InputError(f"unit {self.name}: {len(self.ids)} ids for {len(self.points)} points")
        if len(set(self.ids)) != len(self.ids):
            raise InputError(f"unit {self.name}: point ids are not unique")
        self._index = {p: i for i, p in enumerate(self.ids)}

    def __repr__(self) -> str:
        return f"UnitModel({self.name!r}: {len(self.ids)} points, images {self.images})"

    def __contains__(self, point_id) -> bool:
        return point_id in self._index

    def coords(self, ids) -> np.ndarray:
        """Unit coordinates of the given ids (KeyError names a missing one)."""
        try:
            return self.points[[self._index[p] for p in ids]]
        except KeyError as err:
            raise InputError(f"unit {self.name} has no point {err.args[0]!r}") from None

    def common(self, other: "UnitModel") -> list:
        """Ids measured in both units, in this unit's order."""
        return [p for p in self.ids if p in other]


def pair_model(ids, xy1, xy2, io: InteriorOrientation, images=(0, 1), *, order: str = DEFAULT_ORDER,
               base_length: float = 1.0, name: str | None = None) -> UnitModel:
    """Model of one pair of adjacent images (§3.2, "Построение фотограмметрических моделей").

    Relative orientation in the independent system (α'₁, κ'₁, ω'₂, α'₂, κ'₂ with
    b_y = b_z = ω'₁ = 0, (2.7.4)), then intersection (§2.9): the model frame has its origin at
    the left projection centre and X_M along the base. The two projection centres are added to
    the model's points as :func:`centre_id` of ``images``.

    Parameters
    ----------
    ids : sequence
        Point identifiers, one per measured point.
    xy1, xy2 : (n, 2) arrays
        Image coordinates on the left and right image, mm.
    io : InteriorOrientation
        The camera.
    images : (int, int)
        Numbers of the two images.
    order : {"kaw", "wak"}
        Rotation order.
    base_length : float
        Length of the model base (model units).
    name : str, optional
        Model name (default "M<k1>-<k2>").

    Returns
    -------
    UnitModel

    Raises
    ------
    InputError
        Ids and points of different count, NaN/inf, too few points for relative orientation.
    DegenerateGeometryError, ConvergenceError
        From the relative orientation.

    References
    ----------
    Chibunichev (2022), §3.2; §2.7, eq. (2.7.4); §2.9.

    Examples
    --------
    >>> from photolib.strip_triangulation import layout_block, pair_model
    >>> blk = layout_block(1, 2, seed=0)
    >>> (i1, xy1), (i2, xy2) = blk.measurements(0), blk.measurements(1)
    >>> m = pair_model(list(i1), xy1, xy2, blk.io, (0, 1))
    >>> m.name, len(m.ids), m.ids[-2:]                # 7 common points + the two centres
    ('M0-1', 9, ('S0', 'S1'))
    """
    ids = list(ids)
    if len(ids) != len(np.asarray(xy1)):
        raise InputError(f"pair model: {len(ids)} ids for {len(np.asarray(xy1))} measured points")
    ro = relative_orientation(xy1, xy2, io, system="independent", order=order)
    model = build_model(xy1, xy2, ro, io, base_length=base_length)
    k1, k2 = images
    pts = np.vstack([model.points, model.eo1.center, model.eo2.center])
    return UnitModel(name or f"M{k1}-{k2}", ids + [centre_id(k1), centre_id(k2)], pts, (k1, k2), model)


# --- §3.2 continuation -------------------------------------------------------------------------------------
def join_model(reference: UnitModel, model: UnitModel, *, order: str = DEFAULT_ORDER,
               require_centre: bool = True) -> SimilarityTransform:
    """Seven elements of a model in the frame of ``reference`` from their common points (3.2.1).

    X_M0i + A_Mi·X_Mi·t_i − X_M = 0 for each tie point, solved by least squares
    (:func:`photolib.image_pair.absolute_orientation`, partials from sympy).

    Parameters
    ----------
    reference, model : UnitModel
        The model already in the strip frame, and the model to join.
    order : {"kaw", "wak"}
        Rotation order of the elements.
    require_centre : bool
        Require the projection centre of the shared image among the common points (as the book does).

    Returns
    -------
    SimilarityTransform

    Raises
    ------
    InputError
        Fewer than 3 common points, or the shared centre missing with ``require_centre``.
    DegenerateGeometryError
        Collinear common points.

    References
    ----------
    Chibunichev (2022), §3.2, eq. (3.2.1); §2.10, eq. (2.10.4).

    Examples
    --------
    >>> from photolib.strip_triangulation import layout_block, layout_models
    >>> blk = layout_block(1, 3, seed=0)
    >>> models = layout_models(blk)                      # two pair models
    >>> from photolib.strip_triangulation import join_model
    >>> round(join_model(models[0], models[1]).t, 6)      # both models have the same base length
    1.0
    """
    common = reference.common(model)
    if len(common) < 3:
        raise InputError(f"joining {model.name} to {reference.name}: at least 3 common tie points are "
                         f"needed (3.2.1), got {len(common)}")
    if require_centre and model.images and not any(centre_id(k) in common for k in model.images):
        raise InputError(f"joining {model.name} to {reference.name}: the projection centre of the shared "
                         "image must be one of the tie points (§3.2)")
    return absolute_orientation(model.coords(common), reference.coords(common), order=order)


@dataclass
class ContinuationStrip:
    """Result of the continuation method (§3.2): the strip model and its quality check.

    Attributes
    ----------
    model : UnitModel
        Final strip model (means of the determinations) in the model-1 frame.
    transforms : list of SimilarityTransform
        Model i into the strip frame (identity for model 1).
    differences : dict id -> (3,) array
        ΔX, ΔY, ΔZ: later − earlier determination, per double point.
    determinations : dict id -> int
        Number of models that determine the point.

    References
    ----------
    Chibunichev (2022), §3.2, eqs. (3.2.1), (3.2.2).

    Examples
    --------
    >>> from photolib.strip_triangulation import layout_block, layout_models
    >>> blk = layout_block(1, 3, seed=0)
    >>> models = layout_models(blk)
    >>> from photolib.strip_triangulation import continuation_strip
    >>> continuation_strip(models)                     # doctest: +ELLIPSIS
    ContinuationStrip(2 models, 15 points, 3 double points, r.m.s. ΔX, ΔY, ΔZ = ... m)
    """

    model: UnitModel                 # final strip model (means of the determinations) in the model-1 frame
    transforms: list                 # SimilarityTransform of model i into the strip frame (identity for model 1)
    differences: dict                # id -> (ΔX, ΔY, ΔZ): later − earlier determination, per double point
    determinations: dict             # id -> number of models that determine the point

    def __repr__(self) -> str:
        rms = ", ".join(f"{v:.3g}" for v in self.rms_difference)
        return (f"ContinuationStrip({len(self.transforms)} models, {len(self.model.ids)} points, "
                f"{len(self.differences)} double points, r.m.s. ΔX, ΔY, ΔZ = {rms} m)")

    def blunders(self, tolerance: float) -> list:
        """Ids whose double determinations differ by more than ``tolerance`` in any coordinate."""
        return [p for p, d in self.differences.items() if np.max(np.abs(d)) > tolerance]

    @property
    def rms_difference(self) -> np.ndarray:
        """R.m.s. of ΔX, ΔY, ΔZ over the double points (the accuracy criterion of §3.2)."""
        d = np.array(list(self.differences.values())) if self.differences else np.zeros((0, 3))
        return np.sqrt(np.mean(d ** 2, axis=0)) if len(d) else np.full(3, np.nan)


def continuation_strip(models, *, order: str = DEFAULT_ORDER, require_centre: bool = True,
                       name: str = "strip") -> ContinuationStrip:
    """Strip model by continuation: join every model to the first one in turn, (3.2.1)/(3.2.2).

    Model i (i = 2…n) is fitted to the strip-frame coordinates of model i−1 at their common
    points (tie points of the triple overlap and the shared centre S), then all its points are
    transferred by (3.2.2). Points determined twice give the differences ΔX, ΔY, ΔZ (an accuracy
    criterion that exposes blunders); their final coordinates are the means.

    Parameters
    ----------
    models : sequence of UnitModel
        Pair models in flight order (at least two).
    order : {"kaw", "wak"}
        Rotation order.
    require_centre : bool
        See :func:`join_model`.
    name : str
        Name of the strip model.

    Returns
    -------
    ContinuationStrip

    Raises
    ------
    InputError
        Fewer than two models, too few common points.

    References
    ----------
    Chibunichev (2022), §3.2, eqs. (3.2.1), (3.2.2).

    Examples
    --------
    >>> from photolib.strip_triangulation import layout_block, layout_models
    >>> blk = layout_block(1, 3, seed=0)
    >>> models = layout_models(blk)                      # two pair models
    >>> from photolib.strip_triangulation import continuation_strip
    >>> cs = continuation_strip(models)
    >>> len(cs.model.ids), len(cs.differences), bool((cs.rms_difference < 1e-6).all())
    (15, 3, True)
    """
    models = list(models)
    if len(models) < 2:
        raise InputError("continuation needs at least two models")
    identity = SimilarityTransform(0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, order)
    transforms = [identity]
    placed = [models[0]]
    values = defaultdict(list)
    for p, X in zip(models[0].ids, models[0].points):
        values[p].append(X)
    differences = {}
    for i, model in enumerate(models[1:], start=1):
        previous = placed[-1]
        T = join_model(previous, model, order=order, require_centre=require_centre)    # (3.2.1)
        XM = T.apply(model.points)                                                     # (3.2.2)
        current = UnitModel(model.name, model.ids, XM, model.images)
        for p, X in zip(model.ids, XM):
            if p in previous:
                differences[p] = X - previous.coords([p])[0]
            values[p].append(X)
        transforms.append(T)
        placed.append(current)
    ids = tuple(values)
    mean = np.array([np.mean(values[p], axis=0) for p in ids])
    images = tuple(dict.fromkeys(k for m in models for k in m.images))
    strip = UnitModel(name, ids, mean, images)
    return ContinuationStrip(strip, transforms, differences, {p: len(v) for p, v in values.items()})


def _known_points(control) -> tuple:
    """Control as (ids, XYZ (n, 3) with NaN for unknown components, mask (n, 3))."""
    if control is None:
        return (), np.zeros((0, 3)), np.zeros((0, 3), bool)
    ids = tuple(control)
    try:
        XYZ = np.array([np.asarray(control[p], dtype=float).reshape(3) for p in ids]) if ids else np.zeros((0, 3))
    except (TypeError, ValueError):
        raise InputError("control/GNSS points: give three numbers (X, Y, Z; NaN for unknown) per id") from None
    if np.any(np.isinf(XYZ)):
        raise InputError("control/GNSS points contain inf")
    mask = np.isfinite(XYZ)
    bad = [p for p, m in zip(ids, mask) if m[0] != m[1] or not m.any()]
    if bad:
        raise InputError(f"control points {bad}: give X, Y, Z (full), X, Y (planimetric, Z = NaN) or Z only")
    return ids, XYZ, mask


def orient_strip(strip: UnitModel, control: dict, *, order: str = DEFAULT_ORDER):
    """External orientation of a strip model by control points (3.2.3), as for one model (§2.11).

    Parameters
    ----------
    strip : UnitModel
        The strip model.
    control : dict id -> (X, Y, Z)
        Object coordinates; NaN for an unknown component (planimetric or height points).
    order : {"kaw", "wak"}
        Rotation order.

    Returns
    -------
    (SimilarityTransform, (n, 3) array)
        The seven elements and all strip points in the object frame, in ``strip.ids`` order.

    Raises
    ------
    InputError
        Control points not in the strip, fewer than 7 control equations, malformed control.
    DegenerateGeometryError
        Control on one line.

    References
    ----------
    Chibunichev (2022), §3.2, eq. (3.2.3); §2.11.

    Examples
    --------
    >>> from photolib.strip_triangulation import layout_block, layout_models
    >>> blk = layout_block(1, 3, seed=0)
    >>> models = layout_models(blk)                      # two pair models
    >>> ctl = {p: blk.truth([p])[0] for p in (1, 3, 10, 12, 2)}
    >>> from photolib.strip_triangulation import continuation_strip, orient_strip
    >>> cs = continuation_strip(models)
    >>> T, XYZ = orient_strip(cs.model, ctl)
    >>> bool(abs(XYZ - blk.truth(cs.model.ids)).max() < 1e-6)
    True
    """
    ids, XYZ, mask = _known_points(control)
    ids_in = [p for p in ids if p in strip]
    if len(ids_in) < len(ids):
        missing = [p for p in ids if p not in strip]
        raise InputError(f"control points {missing} are not in the strip model")
    if mask.sum() < 7:
        raise InputError(f"external orientation of the strip needs at least 7 control equations, got {int(mask.sum())}")
    T = absolute_orientation(strip.coords(ids), XYZ, components=mask, order=order)
    return T, T.apply(strip.points)


# --- §3.2 polynomial correction ------------------------------------------------------------------------------
POLYNOMIAL_TERMS = ("1", "X", "Y", "XY", "X^2")
"""The five terms of each line of (3.2.4): A₀ + A₁X + A₂Y + A₃XY + A₄X² (no Y² term)."""


def strip_axis_angle(transform: SimilarityTransform) -> float:
    """κ_M of fig. 3.6: the direction of the strip model's X_M axis in the object XY plane.

    The horizontal projection of the first column of A_M; equal to κ_M when ω_M = α_M = 0.

    Parameters
    ----------
    transform : SimilarityTransform
        The external orientation of the strip model (3.2.3).

    Returns
    -------
    float
        κ_M, rad.

    Raises
    ------
    InputError
        ``transform`` is not a SimilarityTransform.

    References
    ----------
    Chibunichev (2022), §3.2, fig. 3.6, eqs. (3.2.6), (3.2.7).

    Examples
    --------
    >>> from photolib.image_pair import SimilarityTransform
    >>> from photolib.strip_triangulation import strip_axis_angle
    >>> round(strip_axis_angle(SimilarityTransform(0, 0, 0, 0.0, 0.0, 0.3, 1.0, "wak")), 6)
    0.3
    """
    if not isinstance(transform, SimilarityTransform):
        raise InputError(f"expected a SimilarityTransform, got {type(transform).__name__}")
    a = transform.matrix[:, 0]
    return float(np.arctan2(a[1], a[0]))


def _monomials(XY, centre, scale):
    u = (XY[:, 0] - centre[0]) / scale
    v = (XY[:, 1] - centre[1]) / scale
    return np.column_stack([np.ones_like(u), u, v, u * v, u * u])


@dataclass
class StripPolynomial:
    """Second-order correction of a strip (3.2.4) in the auxiliary system X* = A_κᵀX (3.2.6).

    ``coefficients[c]`` = (A₀…A₄), (B₀…B₄), (C₀…C₄) for c = X, Y, Z, of the *centred* starred
    coordinates (X* − X*_c, Y* − Y*_c), ``centre`` = (X*_c, Y*_c). Centring only re-parametrises
    (3.2.4): the corrected coordinates are the same as with the book's uncentred X, Y.

    Attributes
    ----------
    coefficients : (3, 5) array
        Rows X, Y, Z; columns the terms :data:`POLYNOMIAL_TERMS`.
    kappa : float
        κ_M, rad.
    centre : (2,) array
        X*_c, Y*_c, m.
    residuals : (n, 3) array
        Corrected − geodetic at the control points, m.
    dof : int
        Redundancy 3n − 15.

    References
    ----------
    Chibunichev (2022), §3.2, eqs. (3.2.4)–(3.2.7).

    Examples
    --------
    >>> import numpy as np
    >>> from photolib.strip_triangulation import fit_strip_polynomial
    >>> geo = np.array([[0, 100, 5], [0, -100, 8], [1000, 0, 6], [2000, 100, 4], [2000, -100, 7.0]])
    >>> fit_strip_polynomial(geo + [0.0, 0.0, 0.5], geo)      # doctest: +ELLIPSIS
    StripPolynomial(κ_M = 0.000°, 5 control points, dof 0, r.m.s. residual ... m)
    """

    coefficients: np.ndarray     # (3, 5)
    kappa: float                 # κ_M of (3.2.6)/(3.2.7)
    centre: np.ndarray           # (2,) X*_c, Y*_c
    residuals: np.ndarray        # corrected − geodetic at the control points, object frame
    dof: int

    def __repr__(self) -> str:
        rms = float(np.sqrt(np.mean(self.residuals ** 2))) if self.residuals.size else 0.0
        return (f"StripPolynomial(κ_M = {np.degrees(self.kappa):.3f}°, {len(self.residuals)} control points, "
                f"dof {self.dof}, r.m.s. residual {rms:.3g} m)")

    def correction(self, XYZ) -> np.ndarray:
        """ΔX*, ΔY*, ΔZ* of (3.2.4) in the starred system for object points ``XYZ``."""
        star = as_points(XYZ, 3, "network points") @ rot_z(self.kappa)      # (3.2.6): X* = A_κᵀX
        return _monomials(star, self.centre, 1.0) @ self.coefficients.T

    def apply(self, XYZ) -> np.ndarray:
        """Corrected coordinates X_и: (3.2.6), (3.2.4), then back by (3.2.7)."""
        A = rot_z(self.kappa)
        star = as_points(XYZ, 3, "network points") @ A                      # (3.2.6)
        corrected = star + _monomials(star, self.centre, 1.0) @ self.coefficients.T   # (3.2.4)
        return corrected @ A.T                                               # (3.2.7): X_и = A_κ X*_и


def fit_strip_polynomial(network, geodetic, kappa: float = 0.0, *, rcond: float = 1e-9) -> StripPolynomial:
    """Coefficients of (3.2.4) from full control points by (3.2.5), least squares if n > 5.

    Parameters
    ----------
    network : (n, 3)
        X, Y, Z of the control points after the external orientation (3.2.3).
    geodetic : (n, 3)
        Their geodetic coordinates X_и, Y_и, Z_и.
    kappa : float
        κ_M, the angle of the strip axis in the object frame (fig. 3.6, :func:`strip_axis_angle`);
        the fit is made in X* = A_κᵀX (3.2.6).
    rcond : float
        Rank threshold of the normal equations.

    Notes
    -----
    Each point gives three linear equations X + A₀ + A₁X + A₂Y + A₃XY + A₄X² − X_и = v (3.2.5),
    15 unknowns in all, so at least 5 points spread along and across the strip (fig. 3.5). The
    system is linear: one step of :func:`photolib.lsq.solve_normal_equations`. Internally the
    centred coordinates are divided by half the strip length for conditioning; the returned
    coefficients are for the centred coordinates in metres.

    Returns
    -------
    StripPolynomial

    Raises
    ------
    InputError
        Shapes that differ, NaN/inf, fewer than 5 points.
    DegenerateGeometryError
        Control points that do not determine (3.2.4) (on one line, not spread across the strip).

    References
    ----------
    Chibunichev (2022), §3.2, eqs. (3.2.4)–(3.2.7), fig. 3.5.

    Examples
    --------
    >>> import numpy as np
    >>> from photolib.strip_triangulation import fit_strip_polynomial
    >>> geo = np.array([[0, 100, 5], [0, -100, 8], [1000, 0, 6], [2000, 100, 4], [2000, -100, 7.0]])
    >>> net = geo + [0.0, 0.0, 0.5]            # a constant height error: Z + C₀ − Z_и = 0 gives C₀ = −0.5
    >>> poly = fit_strip_polynomial(net, geo)
    >>> float(poly.coefficients[2, 0].round(6)), bool(abs(poly.apply(net) - geo).max() < 1e-9)
    (-0.5, True)
    """
    net = as_points(network, 3, "network coordinates of the control points")
    geo = as_points(geodetic, 3, "geodetic coordinates of the control points")
    if net.shape != geo.shape:
        raise InputError(f"network and geodetic coordinates differ in shape: {net.shape} vs {geo.shape}")
    if len(net) < 5:
        raise InputError(f"the 15 coefficients of (3.2.4) need at least 5 full control points, got {len(net)}")
    A = rot_z(kappa)
    star, star_geo = net @ A, geo @ A                                       # (3.2.6)
    centre = star[:, :2].mean(axis=0)
    scale = max(float(np.max(np.abs(star[:, :2] - centre))), 1e-300)
    D = _monomials(star, centre, scale)
    s = np.linalg.svd(D, compute_uv=False)
    if s[-1] < rcond * s[0]:
        raise DegenerateGeometryError(
            "the control points do not determine the polynomial (3.2.4): they must not lie on one line "
            "and must be spread along and across the strip (2 at each end + 1 in the middle, fig. 3.5)")
    coef = np.empty((3, 5))
    for c in range(3):
        delta, _ = solve_normal_equations(D, star[:, c] - star_geo[:, c], names=POLYNOMIAL_TERMS)  # (3.2.5)
        coef[c] = delta / np.array([1.0, scale, scale, scale ** 2, scale ** 2])
    poly = StripPolynomial(coef, float(kappa), centre, np.zeros_like(net), 3 * len(net) - 15)
    poly.residuals = poly.apply(net) - geo
    return poly


# --- §3.3/§3.4 simultaneous adjustment of units ----------------------------------------------------------------
@dataclass
class EquationRow:
    """What one correction equation of §3.3/§3.4 stands for.

    Parameters
    ----------
    kind : str
        "tie" (3.3.1)/(3.4.1), "control" (3.3.2)/(3.4.2) or "gnss" (3.4.3).
    point : hashable
        The point id.
    units : tuple of int
        (i, j) for a tie, (i,) otherwise.
    component : str
        "X", "Y" or "Z".

    References
    ----------
    Chibunichev (2022), §3.3, eqs. (3.3.1)–(3.3.4); §3.4, eqs. (3.4.1)–(3.4.3).

    Examples
    --------
    >>> from photolib.strip_triangulation import EquationRow
    >>> EquationRow("tie", 7, (0, 1), "Z").kind
    'tie'
    """

    kind: str            # "tie" (3.3.1)/(3.4.1), "control" (3.3.2)/(3.4.2), "gnss" (3.4.3)
    point: object
    units: tuple         # (i, j) for a tie, (i,) otherwise
    component: str       # "X", "Y" or "Z"


def tie_pairs(units, adjacency=None) -> list:
    """(point, i, j) for every point measured in two units i < j that are allowed to be tied.

    The book counts one tie per pair of *adjacent* models (fig. 3.8: a point in a 2 × 2 set of
    models gives 4 ties), see :func:`grid_adjacency`.

    Parameters
    ----------
    units : sequence of UnitModel
        Strips or models.
    adjacency : collection of (i, j), optional
        Allowed unit pairs; None ties every pair of units sharing a point.

    Returns
    -------
    list of (id, int, int)

    Raises
    ------
    InputError
        ``units`` holds something that is not a UnitModel.

    References
    ----------
    Chibunichev (2022), §3.3, eq. (3.3.1); §3.4, eq. (3.4.1), fig. 3.8.

    Examples
    --------
    >>> from photolib.strip_triangulation import layout_block, layout_models
    >>> blk = layout_block(1, 3, seed=0)
    >>> models = layout_models(blk)                      # two pair models
    >>> from photolib.strip_triangulation import tie_pairs
    >>> tie_pairs(models)
    [(2, 0, 1), (5, 0, 1), ('S1', 0, 1)]
    """
    units = list(units)
    if not all(isinstance(u, UnitModel) for u in units):
        raise InputError("units must be UnitModel instances")
    allowed = None if adjacency is None else {tuple(sorted(p)) for p in adjacency}
    where = defaultdict(list)
    for u, unit in enumerate(units):
        for p in unit.ids:
            where[p].append(u)
    out = []
    for p, us in where.items():
        for a in range(len(us)):
            for b in range(a + 1, len(us)):
                if allowed is None or (us[a], us[b]) in allowed:
                    out.append((p, us[a], us[b]))
    return out


def grid_adjacency(n_strips: int, per_strip: int) -> set:
    """Adjacent models of a regular block (units numbered strip by strip).

    Neighbours along a strip and the models with the same position in neighbouring strips.

    Parameters
    ----------
    n_strips, per_strip : int
        Strips, and units per strip.

    Returns
    -------
    set of (int, int)

    Raises
    ------
    InputError
        Non-positive or non-integer sizes.

    References
    ----------
    Chibunichev (2022), §3.4, fig. 3.8.

    Examples
    --------
    >>> from photolib.strip_triangulation import grid_adjacency
    >>> sorted(grid_adjacency(2, 2))
    [(0, 1), (0, 2), (1, 3), (2, 3)]
    """
    if _int(n_strips, "n_strips") < 1 or _int(per_strip, "per_strip") < 1:
        raise InputError("a block needs at least one strip of one unit")
    idx = lambda s, c: s * per_strip + c    # noqa: E731
    pairs = set()
    for s in range(n_strips):
        for c in range(per_strip):
            if c + 1 < per_strip:
                pairs.add((idx(s, c), idx(s, c + 1)))
            if s + 1 < n_strips:
                pairs.add((idx(s, c), idx(s + 1, c)))
    return pairs


def _similarity_functions(order):
    return derivations.similarity_model(order).compile()


def unit_equations(units, params, control=None, gnss=None, adjacency=None, *, order: str = DEFAULT_ORDER):
    """Correction equations of §3.3/§3.4 at the approximation ``params`` (n_units × 7).

    * ties (3.3.1)/(3.4.1): G(p_i; X_Mi) − G(p_j; X_Mj) = 0, three rows, columns of units i and j
      ((3.3.3): a₁…a₇ = ∂G/∂p_i, a₈…a₁₄ = −∂G/∂p_j);
    * control (3.3.2)/(3.4.2): G(p_i; X_Mi) − X = 0 for every unit measuring the point, three rows
      for a full point, two (X, Y) for a planimetric, one (Z) for a height point (3.3.4);
    * GNSS centres (3.4.3): G(p_i; X_SkMi) − X_Sk = 0 for every unit carrying centre k.

    G = X₀ + A_M·X_M·t (2.10.4).

    Parameters
    ----------
    units : sequence of UnitModel
        Strips or models.
    params : (n_units, 7) array
        X₀, Y₀, Z₀, ω_M, α_M, κ_M, t of every unit.
    control, gnss : dict id -> (X, Y, Z), optional
        Ground control (NaN: unknown component) and GNSS centres.
    adjacency : collection of (i, j), optional
        See :func:`tie_pairs`.
    order : {"kaw", "wak"}
        Rotation order.

    Returns
    -------
    (B, L, rows)
        B·δ + L = V with L = computed − given; ``rows`` an :class:`EquationRow` per equation.

    Raises
    ------
    InputError
        ``params`` of the wrong shape or with NaN/inf, no equations at all, malformed control.

    References
    ----------
    Chibunichev (2022), §3.3, eqs. (3.3.1)–(3.3.4); §3.4, eqs. (3.4.1)–(3.4.3); §2.10, eq. (2.10.4).

    Examples
    --------
    >>> from photolib.strip_triangulation import layout_block, layout_models
    >>> blk = layout_block(1, 3, seed=0)
    >>> models = layout_models(blk)                      # two pair models
    >>> ctl = {p: blk.truth([p])[0] for p in (1, 3, 10, 12, 2)}
    >>> from photolib.strip_triangulation import initial_transforms, unit_equations
    >>> B, L, rows = unit_equations(models, initial_transforms(models, ctl), ctl)
    >>> B.shape, rows[0].kind                 # 3m + 3k = 3·3 + 3·6 rows, 7n columns
    ((27, 14), 'tie')
    """
    units = list(units)
    if not units or not all(isinstance(u, UnitModel) for u in units):
        raise InputError("units must be a non-empty sequence of UnitModel")
    try:
        params = np.asarray(params, dtype=float)
    except (TypeError, ValueError):
        raise InputError("params must be numbers") from None
    if params.size != 7 * len(units) or not np.all(np.isfinite(params)):
        raise InputError(f"params: expected {len(units)} × 7 finite elements, got shape {params.shape}")
    params = params.reshape(len(units), 7)
    res_fn, jac_fn = _similarity_functions(order)
    n = 7 * len(units)

    def G_and_J(u, ids):
        XM = units[u].coords(ids)
        zero = np.zeros(len(ids))
        phi = res_fn(*params[u], XM[:, 0], XM[:, 1], XM[:, 2], zero, zero, zero).T      # = −G
        J = jac_fn(*params[u], XM[:, 0], XM[:, 1], XM[:, 2], zero, zero, zero)
        J = J.reshape(3, 7, len(ids)).transpose(2, 0, 1)                                 # ∂φ/∂p
        return -phi, -J

    B_rows, L_rows, rows = [], [], []
    for p, i, j in tie_pairs(units, adjacency):
        Gi, Ji = G_and_J(i, [p])
        Gj, Jj = G_and_J(j, [p])
        B = np.zeros((3, n))
        B[:, 7 * i:7 * i + 7] = Ji[0]
        B[:, 7 * j:7 * j + 7] = -Jj[0]
        B_rows.append(B)
        L_rows.append(Gi[0] - Gj[0])
        rows += [EquationRow("tie", p, (i, j), c) for c in "XYZ"]
    for kind, known in (("control", control), ("gnss", gnss)):
        ids, XYZ, mask = _known_points(known)
        for p, X, m in zip(ids, XYZ, mask):
            for u, unit in enumerate(units):
                if p not in unit:
                    continue
                Gu, Ju = G_and_J(u, [p])
                B = np.zeros((3, n))
                B[:, 7 * u:7 * u + 7] = Ju[0]
                B_rows.append(B[m])
                L_rows.append((Gu[0] - np.where(m, X, 0.0))[m])
                rows += [EquationRow(kind, p, (u,), c) for c, used in zip("XYZ", m) if used]
    if not B_rows:
        raise InputError("no correction equations: the units share no points and no control is given")
    return np.vstack(B_rows), np.concatenate(L_rows), rows


def _compose(outer: SimilarityTransform, inner: SimilarityTransform, order) -> SimilarityTransform:
    """outer ∘ inner: X = X₀ₒ + tₒAₒ(X₀ᵢ + tᵢAᵢX_M)."""
    A = outer.matrix @ inner.matrix
    return SimilarityTransform.from_matrix(outer.shift + outer.t * outer.matrix @ inner.shift, A,
                                           outer.t * inner.t, order)


def _collinear(P, rel=1e-6) -> bool:
    if len(P) < 3:
        return True
    s = np.linalg.svd(P - P.mean(axis=0), compute_uv=False)
    return s[0] == 0 or s[1] < rel * s[0]


_ROLL_MESSAGE = ("the datum is not determined: the known points ({what}) lie (nearly) on one line, so the "
                 "block can roll about that line — the flight line of a single strip whose GNSS centres "
                 "are practically collinear (§3.4). Add at least one ground control point off the line")


def initial_transforms(units, control=None, gnss=None, *, order: str = DEFAULT_ORDER) -> np.ndarray:
    """Approximate seven elements of every unit (n_units × 7).

    1. Free networks: units sharing ≥ 3 non-collinear points are chained as in the continuation
       method (closed-form similarity, :func:`photolib.image_pair.similarity_closed_form`); this
       splits the block into rigid components (e.g. the strips of fig. 3.8).
    2. Each component is carried onto its known points — control, GNSS centres and the points
       it shares with components already placed — by :func:`photolib.image_pair.absolute_orientation`
       when they are not collinear; otherwise by a level start (ω = α = 0, a 2-D similarity plus
       a height shift). The adjustment then fixes what the start leaves out.

    Parameters
    ----------
    units : sequence of UnitModel
        Strips or models.
    control, gnss : dict id -> (X, Y, Z), optional
        Known points.
    order : {"kaw", "wak"}
        Rotation order.

    Returns
    -------
    (n_units, 7) array

    Raises
    ------
    InputError
        Malformed control.
    DegenerateGeometryError
        A component can be neither tied to the block nor oriented by its own known points.

    References
    ----------
    Chibunichev (2022), §3.2, eq. (3.2.1); §3.3; §3.4.

    Examples
    --------
    >>> from photolib.strip_triangulation import layout_block, layout_models
    >>> blk = layout_block(1, 3, seed=0)
    >>> models = layout_models(blk)                      # two pair models
    >>> ctl = {p: blk.truth([p])[0] for p in (1, 3, 10, 12, 2)}
    >>> from photolib.strip_triangulation import initial_transforms
    >>> initial_transforms(models, ctl).shape
    (2, 7)
    """
    units = list(units)
    identity = SimilarityTransform(0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, order)
    comp_of, free, comps = {}, {}, []
    for root in range(len(units)):
        if root in free:
            continue
        free[root], comp_of[root] = identity, len(comps)
        members, queue = [root], deque([root])
        while queue:
            u = queue.popleft()
            Xu = UnitModel("free", units[u].ids, free[u].apply(units[u].points))
            for v in range(len(units)):
                if v in free:
                    continue
                common = units[v].common(units[u])
                if len(common) >= 3 and not _collinear(units[v].coords(common)):
                    free[v] = similarity_closed_form(units[v].coords(common), Xu.coords(common), order)
                    comp_of[v] = len(comps)
                    members.append(v)
                    queue.append(v)
        comps.append(members)

    def free_points(c):
        det = defaultdict(list)
        for u in comps[c]:
            for p, X in zip(units[u].ids, free[u].apply(units[u].points)):
                det[p].append(X)
        return {p: np.mean(v, axis=0) for p, v in det.items()}

    known = {}
    for k in (control, gnss):
        k_ids, k_XYZ, _ = _known_points(k)
        known.update(zip(k_ids, k_XYZ))
    placed_points, datum = {}, {}
    pending = list(range(len(comps)))
    for level_start in (False, True):
        progress = True
        while progress and pending:
            progress = False
            for c in list(pending):
                fp = free_points(c)
                ids = [p for p in fp if p in known or p in placed_points]
                if not ids:
                    continue
                XYZ = np.array([known[p] if p in known else placed_points[p] for p in ids])
                mask = np.isfinite(XYZ)
                XM = np.array([fp[p] for p in ids])
                full = mask.all(axis=1)
                if mask.sum() >= 7 and not _collinear(XM[full]):
                    T = absolute_orientation(XM, XYZ, components=mask, order=order)
                elif level_start and mask[:, 0].sum() >= 2 and mask[:, 2].sum() >= 1 \
                        and np.ptp(XM[mask[:, 0], :2], axis=0).max() > 0:
                    T = level_similarity_start(XM, np.where(mask, XYZ, 0.0), mask, order)
                else:
                    continue
                datum[c] = T
                placed_points.update({p: T.apply(X[None])[0] for p, X in fp.items()})
                pending.remove(c)
                progress = True
                if level_start:
                    break          # a level start may let the other components be placed rigorously
    if pending:
        names = [units[u].name for c in pending for u in comps[c]]
        raise DegenerateGeometryError(f"units {names} can be neither tied to the rest of the block nor "
                                      "oriented by their own control/GNSS points: no datum for them")
    return np.array([_compose(datum[comp_of[u]], free[u], order).vector for u in range(len(units))])


@dataclass
class UnitsAdjustment:
    """Result of the simultaneous adjustment of independent strips (§3.3) or models (§3.4).

    Attributes
    ----------
    units : list of UnitModel
        The adjusted units.
    transforms : list of SimilarityTransform
        Seven elements per unit (object frame).
    adjustment : Adjustment
        The least-squares record (μ, Q, residuals, history) of :mod:`photolib.lsq`.
    rows : list of EquationRow
        One per correction equation.
    points : dict id -> (3,) array
        Final X, Y, Z (mean over units, (3.3.5)/(3.4.4)), m.
    spread : dict id -> (3,) array
        Largest deviation from the mean per coordinate (multi-unit points), m.
    shape : (int, int)
        (M, N) of the design matrix.

    References
    ----------
    Chibunichev (2022), §3.3, eq. (3.3.5); §3.4, eq. (3.4.4).

    Examples
    --------
    >>> from photolib.strip_triangulation import layout_block, layout_models
    >>> blk = layout_block(1, 3, seed=0)
    >>> models = layout_models(blk)
    >>> ctl = {p: blk.truth([p])[0] for p in (1, 3, 10, 12, 2)}
    >>> from photolib.strip_triangulation import adjust_independent_units
    >>> adjust_independent_units(models, ctl)          # doctest: +ELLIPSIS
    UnitsAdjustment(2 units, 15 points, M × N = 27 × 14, μ = ... m, ... iterations)
    """

    units: list
    transforms: list            # SimilarityTransform per unit (object frame)
    adjustment: Adjustment
    rows: list                  # EquationRow per correction equation
    points: dict                # id -> final X, Y, Z (mean over units, (3.3.5)/(3.4.4))
    spread: dict                # id -> max |deviation from the mean| per coordinate (multi-unit points)
    shape: tuple                # (M, N) of the design matrix

    def __repr__(self) -> str:
        mu = getattr(self.adjustment, "mu", float("nan"))
        its = getattr(self.adjustment, "iterations", "?")
        return (f"UnitsAdjustment({len(self.units)} units, {len(self.points)} points, "
                f"M × N = {self.shape[0]} × {self.shape[1]}, μ = {mu:.3g} m, {its} iterations)")

    def residuals(self, kind: str) -> np.ndarray:
        """Residuals V of the equations of one kind ("tie", "control", "gnss")."""
        return self.adjustment.residuals[[r.kind == kind for r in self.rows]]


def _datum_check(B, P=None, names=(), *, rcond: float = 1e-7, known_points=None, what="control"):
    """Raise :class:`DegenerateGeometryError` if B (columns scaled) is (nearly) rank-deficient.

    Returns the singular values of the column-equilibrated, weighted design (largest first).
    """
    B = np.asarray(B, dtype=float)
    w = np.ones(len(B)) if P is None else np.sqrt(np.asarray(P, dtype=float))
    Bw = B * w[:, None]
    norms = np.linalg.norm(Bw, axis=0)
    if np.any(norms == 0):
        raise DegenerateGeometryError("the equations do not depend on "
                                      + ", ".join(str(names[i]) if i < len(names) else str(i)
                                                  for i in np.flatnonzero(norms == 0)))
    s = np.linalg.svd(Bw / norms, compute_uv=False)
    if s[-1] < rcond * s[0]:
        if known_points is not None and _collinear(np.asarray(known_points), 1e-3):
            raise DegenerateGeometryError(_ROLL_MESSAGE.format(what=what)
                                          + f" (smallest/largest singular value {s[-1] / s[0]:.1e})")
        raise DegenerateGeometryError(f"the block's equations are (nearly) singular (smallest/largest "
                                      f"singular value {s[-1] / s[0]:.1e}): the datum or a tie is missing")
    return s


def adjust_independent_units(units, control=None, gnss=None, *, adjacency=None, order: str = DEFAULT_ORDER,
                             sigma_tie: float = 1.0, sigma_control: float = 1.0, sigma_gnss: float = 1.0,
                             initial=None, rcond: float = 1e-7, tol: float = 1e-9,
                             max_iter: int = 30) -> UnitsAdjustment:
    """Simultaneous exterior orientation of independent strips (§3.3) or models (§3.4).

    Parameters
    ----------
    units : list of UnitModel
        Strip models (§3.2) or pair models (:func:`pair_model`), each in its own frame.
    control : dict id -> (X, Y, Z)
        Ground control; NaN marks an unknown component (planimetric or height points).
    gnss : dict centre id -> (X_S, Y_S, Z_S)
        GNSS projection centres (3.4.3), ids :func:`centre_id`.
    adjacency : set of (i, j), optional
        Unit pairs that give tie equations (default: every pair sharing a point).
    sigma_tie, sigma_control, sigma_gnss : float
        A-priori standard deviations (m) of the three kinds of equations; weights p = 1/σ².
    initial : (n_units, 7) array, optional
        Start values (default :func:`initial_transforms`).
    rcond, tol, max_iter
        Rank threshold of the datum check, convergence tolerance and iteration limit.

    Notes
    -----
    The unknowns are the seven elements X₀, Y₀, Z₀, ω_M, α_M, κ_M, t of every unit, N = 7n
    (3.3.6). The correction equations (:func:`unit_equations`) are iterated by
    :func:`photolib.lsq.gauss_newton` from :func:`initial_transforms`. Before iterating, the rank
    of the design is checked: a single strip with GNSS centres only rolls freely about its
    flight line (§3.4) and raises :class:`DegenerateGeometryError` saying so. Final coordinates
    are the means over the units (3.3.5)/(3.4.4).

    Returns
    -------
    UnitsAdjustment

    Raises
    ------
    InputError
        No units, no datum at all (neither control nor GNSS), fewer equations than unknowns,
        malformed control, non-positive σ.
    DegenerateGeometryError
        A datum defect (e.g. a single strip with GNSS centres only rolls about its flight line).
    ConvergenceError
        The iteration did not converge.

    References
    ----------
    Chibunichev (2022), §3.3, eqs. (3.3.1)–(3.3.7); §3.4, eqs. (3.4.1)–(3.4.4).

    Examples
    --------
    >>> from photolib.strip_triangulation import layout_block, layout_models
    >>> blk = layout_block(1, 3, seed=0)
    >>> models = layout_models(blk)
    >>> ctl = {p: blk.truth([p])[0] for p in (1, 3, 10, 12, 2)}
    >>> from photolib.strip_triangulation import adjust_independent_units
    >>> res = adjust_independent_units(models, ctl)
    >>> res.shape, bool(max(abs(res.points[p] - blk.truth([p])[0]).max() for p in res.points) < 1e-6)
    ((27, 14), True)
    """
    check_order(order)
    units = list(units)
    if not units:
        raise InputError("no units to adjust")
    for name, v in dict(sigma_tie=sigma_tie, sigma_control=sigma_control, sigma_gnss=sigma_gnss).items():
        if not (np.isfinite(_float(v, name)) and v > 0):
            raise InputError(f"{name} must be a finite positive number")
    if control is None and gnss is None:
        raise InputError("neither ground control nor GNSS centres given: the block has no datum (§3.3, §3.4)")
    x0 = initial_transforms(units, control, gnss, order=order) if initial is None \
        else np.asarray(initial, dtype=float).reshape(len(units), 7)
    names = [f"{u.name}.{s}" for u in units for s in SIMILARITY_NAMES]

    def weights(rows):
        sig = {"tie": sigma_tie, "control": sigma_control, "gnss": sigma_gnss}
        return np.array([1.0 / sig[r.kind] ** 2 for r in rows])

    B, L, rows = unit_equations(units, x0, control, gnss, adjacency, order=order)
    P = weights(rows)
    if B.shape[0] < B.shape[1]:
        raise InputError(f"{B.shape[0]} correction equations cannot determine {B.shape[1]} unknowns")
    known = [X for k in (control, gnss) if k for X in k.values()]
    what = "GNSS centres" if gnss and not control else "control and GNSS points"
    _datum_check(B, P, names, rcond=rcond, known_points=np.nan_to_num(np.array(known)) if known else None,
                what=what)

    def linearize(x):
        Bx, Lx, _ = unit_equations(units, x, control, gnss, adjacency, order=order)
        return Bx, Lx

    scale = np.abs(x0[:, 6]).reshape(-1, 1)
    tol_v = (np.array([1.0, 1.0, 1.0, 1e-3, 1e-3, 1e-3, 1e-3]) * tol * np.hstack(
        [np.ones((len(units), 6)), scale])).ravel()
    adj = gauss_newton(linearize, x0.ravel(), P, tol=tol_v, max_iter=max_iter, names=names)
    x = adj.x.reshape(len(units), 7)
    transforms = [SimilarityTransform(*map(float, p), order=order) for p in x]
    det = defaultdict(list)
    for T, unit in zip(transforms, units):
        for p, X in zip(unit.ids, T.apply(unit.points)):            # (3.3.5)/(3.4.4)
            det[p].append(X)
    points = {p: np.mean(v, axis=0) for p, v in det.items()}
    spread = {p: np.max(np.abs(np.array(v) - points[p]), axis=0) for p, v in det.items() if len(v) > 1}
    return UnitsAdjustment(units, transforms, adj, rows, points, spread, B.shape)


def image_orientations(units, transforms, order: str | None = None) -> dict:
    """Exterior orientation of every image from its models' elements, (3.4.4)–(3.4.6).

    For each model, S = X₀ + A_M·S_M·t and A = A_M·A' (3.4.5) via
    :func:`photolib.image_pair.image_orientation_from_model`; an image in two models gets the mean
    centre and the mean rotation (projected back onto a rotation matrix); the angles follow by
    (3.4.6) in ``order`` (the book's (3.4.6) is the ω-α-κ extraction, ``order="wak"``).

    Parameters
    ----------
    units : sequence of UnitModel
        Pair models carrying their stereo model (:func:`pair_model`).
    transforms : sequence of SimilarityTransform
        Their adjusted elements.
    order : {"kaw", "wak"}, optional
        Order of the returned angles (default: that of the transforms).

    Returns
    -------
    dict image -> ExteriorOrientation

    Raises
    ------
    InputError
        A unit without a stereo model, units and transforms of different count.

    References
    ----------
    Chibunichev (2022), §3.4, eqs. (3.4.4)–(3.4.6).

    Examples
    --------
    >>> from photolib.strip_triangulation import layout_block, layout_models
    >>> blk = layout_block(1, 3, seed=0)
    >>> models = layout_models(blk)                      # two pair models
    >>> ctl = {p: blk.truth([p])[0] for p in (1, 3, 10, 12, 2)}
    >>> from photolib.strip_triangulation import adjust_independent_units, image_orientations
    >>> eos = image_orientations(models, adjust_independent_units(models, ctl).transforms)
    >>> sorted(eos), bool(abs(eos[1].vector - blk.cameras[1]).max() < 1e-6)
    ([0, 1, 2], True)
    """
    units, transforms = list(units), list(transforms)
    if len(units) != len(transforms) or not units:
        raise InputError(f"{len(units)} units and {len(transforms)} transforms")
    centres, matrices = defaultdict(list), defaultdict(list)
    for unit, T in zip(units, transforms):
        if unit.stereo is None or len(unit.images) != 2:
            raise InputError(f"unit {unit.name} carries no stereo model; image orientations need pair models")
        eos = image_orientation_from_model(unit.stereo, T)
        for k, eo in zip(unit.images, eos):
            centres[k].append(eo.center)
            matrices[k].append(eo.matrix)
    out = {}
    for k in centres:
        U, _, Vt = np.linalg.svd(np.mean(matrices[k], axis=0))
        A = U @ np.diag([1.0, 1.0, np.linalg.det(U @ Vt)]) @ Vt
        out[k] = ExteriorOrientation.from_matrix(np.mean(centres[k], axis=0), A, order or transforms[0].order)
    return out


# --- counts -----------------------------------------------------------------------------------------------------
def count_independent_strips(n: int, m: int, k: int, i: int = 0, l: int = 0) -> tuple:   # noqa: E741
    """(N, M) of the independent-strip method: N = 7n (3.3.6), M = 3m + 3k + 2i + l (3.3.7).

    Parameters
    ----------
    n : int
        Strips.
    m : int
        Inter-strip tie points.
    k, i, l : int
        Full, planimetric and height control points measured in strips (counted once per strip).

    Returns
    -------
    (int, int)

    Raises
    ------
    InputError
        Negative or non-integer counts, no strip.

    References
    ----------
    Chibunichev (2022), §3.3, eqs. (3.3.6), (3.3.7), fig. 3.7.

    Examples
    --------
    >>> from photolib.strip_triangulation import count_independent_strips
    >>> count_independent_strips(3, 14, 8)
    (21, 66)
    """
    _check_counts(n=n, m=m, k=k, i=i, l=l)
    return 7 * n, 3 * m + 3 * k + 2 * i + l


def count_independent_models(n: int, m: int, k: int, i: int = 0, l: int = 0, gnss: bool = False) -> tuple:  # noqa: E741
    """(N, M, S) of the independent-model method (§3.4): N = 7n, M = 3m + 3k + 2i + l + S.

    Parameters
    ----------
    n : int
        Models.
    m : int
        Tie points on adjacent models (one per pair of adjacent models sharing the point,
        projection centres included).
    k, i, l : int
        Full, planimetric and height control points measured on models.
    gnss : bool
        S = 6n equations of GNSS centres (two centres × three coordinates per model), else 0.

    Returns
    -------
    (int, int, int)

    Raises
    ------
    InputError
        Negative or non-integer counts, no model.

    References
    ----------
    Chibunichev (2022), §3.4, fig. 3.8, eq. (3.4.3).

    Examples
    --------
    >>> from photolib.strip_triangulation import count_independent_models
    >>> count_independent_models(6, 18, 6, gnss=True)
    (42, 108, 36)
    """
    _check_counts(n=n, m=m, k=k, i=i, l=l)
    S = 6 * n if gnss else 0
    return 7 * n, 3 * m + 3 * k + 2 * i + l + S, S


def _check_counts(**values):
    bad = {k: v for k, v in values.items() if int(v) != v or v < 0}
    if bad:
        raise InputError(f"counts must be non-negative integers: {bad}")
    if values["n"] < 1:
        raise InputError("at least one unit is needed")


def structure_counts(units, control=None, gnss=None, adjacency=None) -> dict:
    """n, m, k, i, l, S of an actual block, counted as the book does (§3.3, §3.4).

    m = number of (point, adjacent unit pair) ties; k, i, l = full, planimetric, height control
    points counted once per unit that measures them; S = 3 × (GNSS centre, unit) pairs.

    Parameters
    ----------
    units : sequence of UnitModel
        Strips or models.
    control, gnss : dict id -> (X, Y, Z), optional
        Known points.
    adjacency : collection of (i, j), optional
        See :func:`tie_pairs`.

    Returns
    -------
    dict

    Raises
    ------
    InputError
        Malformed control.

    References
    ----------
    Chibunichev (2022), §3.3, eqs. (3.3.6), (3.3.7); §3.4.

    Examples
    --------
    >>> from photolib.strip_triangulation import layout_block, layout_models
    >>> blk = layout_block(1, 3, seed=0)
    >>> models = layout_models(blk)                      # two pair models
    >>> ctl = {p: blk.truth([p])[0] for p in (1, 3, 10, 12, 2)}
    >>> from photolib.strip_triangulation import structure_counts
    >>> structure_counts(models, ctl)
    {'n': 2, 'm': 3, 'k': 6, 'i': 0, 'l': 0, 'S': 0}
    """
    units = list(units)
    out = {"n": len(units), "m": len(tie_pairs(units, adjacency)), "k": 0, "i": 0, "l": 0, "S": 0}
    ids, _, mask = _known_points(control)
    for p, msk in zip(ids, mask):
        key = "k" if msk.all() else ("i" if msk[0] else "l")
        out[key] += sum(p in u for u in units)
    g_ids, _, _ = _known_points(gnss)
    out["S"] = 3 * sum(p in u for p in g_ids for u in units)
    return out


# --- synthetic layouts ----------------------------------------------------------------------------------------
def layout_block(n_strips: int = 1, images_per_strip: int = 7, *, f: float = 100.0, frame_size: float = 230.0,
                 flying_height: float = 1000.0, forward_overlap: float = 0.6, side_overlap: float = 0.3,
                 principal_rows: bool = False, row_offset: float = 0.35, orientation_offset: float = 0.15,
                 relief: float = 30.0, angle_sigma: float = np.radians(1.0), lateral_sigma: float = 0.0,
                 height_sigma: float = 0.0, sigma: float = 0.0, distortion_k1: float = 0.0,
                 order: str = DEFAULT_ORDER, seed: int = 0) -> Block:
    """Simulate vertical images on the regular layout of figs 3.2, 3.7, 3.8.

    Strips run along X (base b = (1 − p)L, L the footprint side), stacked along −Y (spacing
    s = (1 − q)L) — :func:`photolib.synthetic.strip_layout`. Tie points sit in the columns of the
    principal points, x = c·b, on the rows y = s/2 − j·s (the outer edges and the side-overlap
    bands, as in fig. 3.8) and, with ``principal_rows``, also on the strip axes; a row at
    ±``row_offset``·L is used instead of ±s/2 for a single strip. Each column point is in the
    triple overlap of images c−1, c, c+1, i.e. common to two adjacent models. Orientation points
    at x = (c + ½)·b, y = −j·s + {−1, 0, 1}·``orientation_offset``·L belong to one model only (they
    complete the relative orientation). The projection centres lie exactly on straight flight
    lines unless ``lateral_sigma`` / ``height_sigma`` (m) scatter them. Observations are the
    collinearity projections (1.4.12) into every image that sees a point.

    Parameters
    ----------
    n_strips, images_per_strip : int
        Block size (at least one strip of two images).
    f, frame_size, flying_height : float
        Focal length and image format (mm), flying height above the mean terrain (m).
    forward_overlap, side_overlap : float
        Overlaps p, q as fractions.
    principal_rows : bool
        Also put tie points on the strip axes.
    row_offset, orientation_offset : float
        Offsets of the tie rows of a single strip and of the orientation points, in footprints.
    relief : float
        Terrain relief, m (:func:`photolib.synthetic.terrain_height`).
    angle_sigma, lateral_sigma, height_sigma : float
        Seeded spread of the true angles (rad), of the centres across the strip and in height (m).
    sigma : float
        Image noise, mm.
    distortion_k1 : float
        Uncorrected radial distortion k₁ (mm⁻²) — the systematic error of §3.2.
    order : {"kaw", "wak"}
        Rotation order.
    seed : int
        Seed.

    Returns
    -------
    photolib.synthetic.Block
        Point labels 1, 2, …; ``kind`` TIE or ORIENTATION; ``grid_position`` (column, row) in base
        and strip-spacing units (:meth:`~photolib.synthetic.Block.point_at`); ``strip``, ``column``.

    Raises
    ------
    InputError
        Too few images, overlaps outside their range, NaN/inf or negative spreads and σ.

    References
    ----------
    Chibunichev (2022), §3.2 (fig. 3.2, (3.2.1)), §3.3 (fig. 3.7), §3.4 (fig. 3.8).

    Examples
    --------
    >>> from photolib.strip_triangulation import layout_block
    >>> blk = layout_block(1, 4, seed=0)
    >>> blk.n_images, blk.point_at(1, 0.35 * blk.footprint / blk.strip_spacing), blk.base
    (4, 2, 920.0)
    """
    check_order(order)
    if _int(n_strips, "n_strips") < 1 or _int(images_per_strip, "images_per_strip") < 2:
        raise InputError("a layout needs at least one strip of two images")
    for name, value in dict(relief=relief, row_offset=row_offset, orientation_offset=orientation_offset).items():
        if not np.isfinite(_float(value, name)):
            raise InputError(f"{name} must be finite")
    for name, value in dict(angle_sigma=angle_sigma, lateral_sigma=lateral_sigma, height_sigma=height_sigma,
                            sigma=sigma).items():
        v = _float(value, name)
        if not (np.isfinite(v) and v >= 0):
            raise InputError(f"{name} must be a finite non-negative number")
    if not np.isfinite(_float(distortion_k1, "distortion_k1")):
        raise InputError("distortion_k1 must be finite")
    lay = strip_layout(n_strips, images_per_strip, f=f, frame_size=frame_size, flying_height=flying_height,
                       forward_overlap=forward_overlap, side_overlap=side_overlap)
    L, b, s, strip, column = lay
    rng = np.random.default_rng(seed)
    mean_h = 150.0
    n = strip.size
    cams = np.empty((n, 6))
    cams[:, 0] = column * b
    cams[:, 1] = -strip * s + rng.normal(0, lateral_sigma, n) if lateral_sigma else -strip * s
    cams[:, 2] = mean_h + flying_height + (rng.normal(0, height_sigma, n) if height_sigma else 0.0)
    cams[:, 3:] = rng.normal(0, angle_sigma, (n, 3))

    rows = [s / 2 - j * s for j in range(n_strips + 1)] if n_strips > 1 else [row_offset * L, -row_offset * L]
    if principal_rows:
        rows += [-j * s for j in range(n_strips)]
    grid, xy, kind = [], [], []
    for y in sorted(set(np.round(rows, 9)), reverse=True):
        for c in range(images_per_strip):
            grid.append((c, y / s))
            xy.append((c * b, y))
            kind.append(TIE)
    for j in range(n_strips):
        for c in range(images_per_strip - 1):
            for d in (1, 0, -1):
                y = -j * s + d * orientation_offset * L
                grid.append((c + 0.5, y / s))
                xy.append(((c + 0.5) * b, y))
                kind.append(ORIENTATION)
    xy = np.array(xy)
    points = np.column_stack([xy, terrain_height(xy[:, 0], xy[:, 1], mean_h, relief)])
    ids = np.arange(1, len(points) + 1)
    io = InteriorOrientation(f=f)
    io_true = InteriorOrientation(f=f, k1=distortion_k1) if distortion_k1 else io
    from .single_image import project
    image_idx, point_idx, meas_all, true_all = [], [], [], []
    half = frame_size / 2
    for k in range(n):
        eo = ExteriorOrientation(*cams[k], order=order)
        near = np.max(np.abs(points[:, :2] - cams[k, :2]), axis=1) < 0.75 * L
        p_xy = project(points[near], eo, io_true, distortion=bool(distortion_k1))
        inside = np.all(np.abs(p_xy) < half * 0.999, axis=1)
        sel = np.flatnonzero(near)[inside]
        meas = p_xy[inside] + (rng.normal(0, sigma, (inside.sum(), 2)) if sigma else 0.0)
        image_idx.append(np.full(sel.size, k))
        point_idx.append(sel)
        meas_all.append(meas)
        true_all.append(p_xy[inside])
    obs = Observations(np.concatenate(image_idx), np.concatenate(point_idx), np.vstack(meas_all))
    return Block(io=io, order=order, cameras=cams, points=points, kind=np.array(kind, dtype=int), observations=obs,
                 xy_true=np.vstack(true_all), sigma=float(sigma), strip=strip, column=column,
                 frame_size=float(frame_size), footprint=float(L), base=float(b), strip_spacing=float(s),
                 point_labels=tuple(int(i) for i in ids), grid_position=np.array(grid))


def layout_models(block: Block, strips=None, *, base_length: float | None = None) -> list:
    """Independent pair models of adjacent images of each strip of ``block`` (§3.2, §3.4).

    Each model holds the points measured on both images plus the two projection centres.

    Parameters
    ----------
    block : photolib.synthetic.Block
        A regular layout (:func:`layout_block`).
    strips : iterable of int, optional
        Strips to use (default all).
    base_length : float, optional
        Model base (model units); default the nominal base b, so t ≈ 1.

    Returns
    -------
    list of UnitModel

    Raises
    ------
    InputError
        ``block`` without strips, a strip that does not exist.

    References
    ----------
    Chibunichev (2022), §3.2 (models of a strip), §3.4 (independent models).

    Examples
    --------
    >>> from photolib.strip_triangulation import layout_block, layout_models
    >>> blk = layout_block(1, 3, seed=0)
    >>> models = layout_models(blk)                      # two pair models
    >>> [m.name for m in models]
    ['M0-1', 'M1-2']
    """
    if not isinstance(block, Block) or block.strip is None:
        raise InputError("layout_models needs a photolib.synthetic.Block with strips (layout_block)")
    strips = range(int(block.strip.max()) + 1) if strips is None else list(strips)
    if any(_int(k, "strip") not in set(block.strip.tolist()) for k in strips):
        raise InputError(f"the block has strips 0 … {int(block.strip.max())}")
    B = block.base if base_length is None else base_length
    models = []
    for s in strips:
        imgs = block.images_of_strip(s)
        for k1, k2 in zip(imgs[:-1], imgs[1:]):
            id1, xy1 = block.measurements(k1)
            id2, xy2 = block.measurements(k2)
            common, i1, i2 = np.intersect1d(id1, id2, return_indices=True)
            models.append(pair_model([int(p) for p in common], xy1[i1], xy2[i2], block.io, (int(k1), int(k2)),
                                     order=block.order, base_length=B))
    return models
