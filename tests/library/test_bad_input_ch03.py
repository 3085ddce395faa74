"""Bad-input catalogue, Chapter 3 (§3.2–§3.9): strip_triangulation, synthetic, triangulation_layouts, and the
geometric conditions of §11.6 added to the bundle (``bundle_adjustment(conditions=...)``)."""

import numpy as np
import pytest

from catalogue import INF, NAN, Case, check_case
from photolib import bundle as bd
from photolib import strip_triangulation as st
from photolib import synthetic as sy
from photolib import triangulation_layouts as tl
from photolib.errors import DegenerateGeometryError, InputError
from photolib.image_pair import SimilarityTransform

_BLK = st.layout_block(1, 3, seed=0)
_MODELS = st.layout_models(_BLK)
_CTL = {p: _BLK.truth([p])[0] for p in (1, 3, 10, 12, 2)}
_FB = sy.footprint_block([[0, 0], [500, 0]], [[0, 0], [500, 0], [250, 300]], [sy.TIE, sy.TIE, sy.CONTROL])
_RES = type("R", (), {"points": _FB.points, "points_std": None, "mu": 0.005})()
_TOL = {"3.7.2 tie height": 15, "3.7.6 control height": 0.15, "3.7.6 control plan": 0.2, "3.7.6 check plan": 0.3,
        "3.7.6 height, category a": 0.2, "3.7.6 limit share, open": 5, "3.7.6 limit factor": 2}
_GEO = np.array([[0, 100, 5], [0, -100, 8], [1000, 0, 6], [2000, 100, 4], [2000, -100, 7.0]])
# a noise-free block whose first image is known (GNSS + INS): the datum lacks only the scale
_AB = sy.aerial_block(2, 4, points_per_image=15, sigma=0.0, seed=1)
_AB0 = _AB.start_values(seed=2)
_FIRST = np.arange(_AB.n_images)[:, None] == 0
_KNOWN = dict(gnss=np.where(_FIRST, _AB.cameras[:, :3], NAN), ins=np.where(_FIRST, _AB.cameras[:, 3:], NAN),
              sigma_centre=1e-4, sigma_angles=1e-7, order=_AB.order)
_D01 = float(np.linalg.norm(_AB.points[0] - _AB.points[1]))


def _cond(conditions, **extra):
    """bundle_adjustment of the block above with the given §11.6 conditions."""
    return bd.bundle_adjustment(_AB.observations, *_AB0, _AB.io, conditions=conditions, **_KNOWN, **extra)

CASES = [
    # --- synthetic ---------------------------------------------------------------------------------
    Case(sy.PointKind, (7,), raises=InputError, why="unknown kind"),
    Case(sy.Observations, ([0, 1], [0], [[0, 0], [1, 1]]), raises=InputError, why="lengths differ"),
    Case(sy.Observations, ([0], [0], [[NAN, 0]]), raises=InputError, why="NaN coordinate"),
    Case(sy.Observations, ([-1], [0], [[0, 0]]), raises=InputError, why="negative index"),
    Case(sy.Observations, ([0.5], [0], [[0, 0]]), raises=InputError, why="fractional index"),
    Case(sy.Observations, ([0], [0], "ab"), raises=InputError, why="text coordinates"),
    Case(sy.Block, (_FB.io, "kaw", np.full((2, 6), NAN), _FB.points, _FB.kind, _FB.observations),
         raises=InputError, why="NaN cameras"),
    Case(sy.Block, (_FB.io, "kaw", _FB.cameras, _FB.points, [0], _FB.observations), raises=InputError,
         why="kinds of the wrong length"),
    Case(sy.Block, ("camera", "kaw", _FB.cameras, _FB.points, _FB.kind, _FB.observations), raises=InputError,
         why="io of the wrong type"),
    Case(sy.Block, (_FB.io, "kaw", _FB.cameras[:1], _FB.points, _FB.kind, _FB.observations), raises=InputError,
         why="observations of a missing image"),
    Case(sy.StripLayout, (1.0, 0.4, 0.7, [0], [0]), raises=None, check=lambda r: r.base == 0.4,
         why="a plain record (no validation needed)"),
    Case(sy.strip_layout, (1, 2), dict(f=100, frame_size=100, flying_height=1000, forward_overlap=1.2,
                                       side_overlap=0.3), raises=InputError, why="overlap > 1"),
    Case(sy.strip_layout, (0, 2), dict(f=100, frame_size=100, flying_height=1000, forward_overlap=0.6,
                                       side_overlap=0.3), raises=InputError, why="no strip"),
    Case(sy.strip_layout, (1, 2), dict(f=NAN, frame_size=100, flying_height=1000, forward_overlap=0.6,
                                       side_overlap=0.3), raises=InputError, why="NaN f"),
    Case(sy.terrain_height, ([NAN], [0.0]), raises=InputError, why="NaN X"),
    Case(sy.terrain_height, (0.0, 0.0), dict(wavelength=0.0), raises=InputError, why="zero wavelength"),
    Case(sy.footprint_visibility, ([[0, 0]], [[0, 0]], -1.0), raises=InputError, why="negative footprint"),
    Case(sy.footprint_visibility, ([[INF, 0]], [[0, 0]], 1.0), raises=InputError, why="inf point"),
    Case(sy.footprint_visibility, ([[0, 0, 0]], [[0, 0]], 1.0), raises=InputError, why="3-D points"),
    Case(sy.aerial_block, (1, 1), raises=InputError, why="one image"),
    Case(sy.aerial_block, (), dict(sigma=NAN), raises=InputError, why="NaN sigma"),
    Case(sy.aerial_block, (), dict(sigma=-0.1), raises=InputError, why="negative sigma"),
    Case(sy.aerial_block, (), dict(control="nowhere"), raises=InputError, why="unknown control layout"),
    Case(sy.aerial_block, (), dict(control=[[0, NAN]]), raises=InputError, why="NaN control"),
    Case(sy.aerial_block, (), dict(strip_heights=[1000]), raises=InputError, why="wrong number of heights"),
    Case(sy.aerial_block, (), dict(order="xyz"), raises=InputError, why="unknown order"),
    Case(sy.footprint_block, ([[0, 0]], [[0, 0]], [sy.TIE, sy.TIE]), raises=InputError, why="kinds ≠ points"),
    Case(sy.footprint_block, ([[0, NAN]], [[0, 0]], [sy.TIE]), raises=InputError, why="NaN centre"),
    Case(sy.footprint_block, ([[0, 0]], [[0, 0]], [9]), raises=InputError, why="unknown kind"),
    Case(sy.footprint_block, ([[0, 0]], [[0, 0]], [sy.TIE]), dict(angle_sigma=1.0), raises=InputError,
         why="tilts that throw points out of the frame"),
    Case(sy.footprint_block, ([[0, 0], [500, 0]], [[0, 0]], [sy.TIE]),
         dict(camera_of_image=[1, 1], exposure_of_image=[0, 0]), raises=InputError, why="rig without camera 0"),
    Case(sy.rig_block, (), dict(n_points=2), raises=InputError, why="too few points"),
    Case(sy.rig_block, (), dict(sigma=INF), raises=InputError, why="inf sigma"),
    Case(sy.rolling_shutter_block, (), dict(model="cubic"), raises=InputError, why="unknown model"),
    Case(sy.rolling_shutter_block, (), dict(readout=NAN), raises=InputError, why="NaN readout"),
    Case(sy.corridor_strip, (1,), raises=InputError, why="one image"),
    Case(sy.corridor_strip, (), dict(gnss_sigma=-1.0), raises=InputError, why="negative GNSS σ"),
    # --- bundle with the conditions of §11.6 -------------------------------------------------------
    Case(bd.bundle_adjustment, (_AB.observations, *_AB0, _AB.io), dict(conditions=[("slope", (0, 1), None, 0.1)],
                                                                       **_KNOWN),
         raises=InputError, match="unknown condition", why="unknown condition kind"),
    Case(bd.bundle_adjustment, (_AB.observations, *_AB0, _AB.io),
         dict(conditions=[("distance", (0, len(_AB.points)), 5.0, 0.01)], **_KNOWN), raises=InputError,
         match="outside", why="condition point index out of range"),
    Case(bd.bundle_adjustment, (_AB.observations, *_AB0, _AB.io),
         dict(conditions=[("base", (0, _AB.n_images), 5.0, 0.01)], **_KNOWN), raises=InputError, match="outside",
         why="condition image index out of range"),
    Case(bd.bundle_adjustment, (_AB.observations, *_AB0, _AB.io),
         dict(conditions=[("distance", (0, 1), NAN, 0.01)], **_KNOWN), raises=InputError, match="measured",
         why="NaN measured distance"),
    Case(bd.bundle_adjustment, (_AB.observations, *_AB0, _AB.io),
         dict(conditions=[("distance", (0, 1), None, 0.01)], **_KNOWN), raises=InputError, match="measured",
         why="distance without a measured value"),
    Case(bd.bundle_adjustment, (_AB.observations, *_AB0, _AB.io),
         dict(conditions=[("vertical", (0, 1), 3.0, 0.01)], **_KNOWN), raises=InputError, match="no measured",
         why="a measured value for a vertical line"),
    Case(bd.bundle_adjustment, (_AB.observations, *_AB0, _AB.io),
         dict(conditions=[("horizontal", (0, 1), None, -1.0)], **_KNOWN), raises=InputError, match="sigma",
         why="negative condition σ"),
    Case(bd.bundle_adjustment, (_AB.observations, *_AB0, _AB.io),
         dict(conditions=[("coplanar", (0, 1, 2), None, 0.01)], **_KNOWN), raises=InputError, match="4 integer",
         why="three points for the plane condition"),
    Case(bd.bundle_adjustment, (_AB.observations, *_AB0, _AB.io),
         dict(conditions=[("vertical", (2, 2), None, 0.01)], **_KNOWN), raises=InputError, match="twice",
         why="the same point twice"),
    Case(bd.bundle_adjustment, (_AB.observations, *_AB0, _AB.io), dict(conditions="distance", **_KNOWN),
         raises=InputError, match="list", why="conditions not a list"),
    Case(bd.bundle_adjustment, (_AB.observations, *_AB0, _AB.io),
         dict(conditions=[("vertical", (0, 1), None, 0.01)], **_KNOWN), raises=DegenerateGeometryError,
         match="6 of the 7", why="a vertical line gives no scale: datum defect"),
    Case(_cond, ([("distance", (0, 1), _D01, 0.001)],), raises=None,
         check=lambda r: float(np.abs(r.points - _AB.points).max()) < 1e-4,
         why="a measured distance completes the datum (the scale)"),
    Case(bd.self_calibrating_bundle_adjustment, (_AB.observations, *_AB0, _AB.io),
         dict(conditions=[("distance", (0, 1), INF, 0.01)], calibrate=("f",), **_KNOWN), raises=InputError,
         match="measured", why="inf measured distance (self-calibration)"),
    # --- strip_triangulation -----------------------------------------------------------------------
    Case(st.centre_id, ("x",), raises=InputError, why="not an image number"),
    Case(st.UnitModel, ("M", [1, 1], np.zeros((2, 3))), raises=InputError, why="duplicate ids"),
    Case(st.UnitModel, ("M", [1], [[NAN, 0, 0]]), raises=InputError, why="NaN point"),
    Case(st.UnitModel, ("M", [1, 2], np.zeros((1, 3))), raises=InputError, why="ids ≠ points"),
    Case(st.pair_model, ([1, 2], np.zeros((3, 2)), np.zeros((3, 2)), _BLK.io), raises=InputError,
         why="ids ≠ points"),
    Case(st.pair_model, (list(range(6)), np.full((6, 2), NAN), np.zeros((6, 2)), _BLK.io), raises=InputError,
         why="NaN image coordinates"),
    Case(st.join_model, (_MODELS[0], st.UnitModel("x", [100, 101], np.zeros((2, 3)))), raises=InputError,
         why="fewer than 3 common points"),
    Case(st.continuation_strip, ([_MODELS[0]],), raises=InputError, why="one model"),
    Case(st.orient_strip, (_MODELS[0], {1: _CTL[1]}), raises=InputError, why="too few control equations"),
    Case(st.orient_strip, (_MODELS[0], {999: _CTL[1]}), raises=InputError, why="control not in the strip"),
    Case(st.strip_axis_angle, ("transform",), raises=InputError, why="wrong type"),
    Case(st.fit_strip_polynomial, (_GEO[:4], _GEO[:4]), raises=InputError, why="4 points"),
    Case(st.fit_strip_polynomial, (_GEO, _GEO[:, :2]), raises=InputError, why="2-D geodetic"),
    Case(st.fit_strip_polynomial, (_GEO * [1, 0, 1], _GEO * [1, 0, 1]), raises=DegenerateGeometryError,
         why="control on one line"),
    Case(st.StripPolynomial, (np.zeros((3, 5)), 0.0, np.zeros(2), np.zeros((0, 3)), 0), raises=None,
         check=lambda r: np.allclose(r.apply(_GEO), _GEO), why="zero polynomial changes nothing"),
    Case(st.EquationRow, ("tie", 1, (0, 1), "X"), raises=None, check=lambda r: r.units == (0, 1),
         why="a plain record"),
    Case(st.ContinuationStrip, (_MODELS[0], [], {}, {}), raises=None,
         check=lambda r: np.all(np.isnan(r.rms_difference)), why="no double points: r.m.s. undefined (NaN)"),
    Case(st.UnitsAdjustment, (_MODELS, [], None, [], {}, {}, (0, 0)), raises=None,
         check=lambda r: r.shape == (0, 0), why="a plain record"),
    Case(st.tie_pairs, (["model"],), raises=InputError, why="not UnitModels"),
    Case(st.grid_adjacency, (0, 3), raises=InputError, why="no strip"),
    Case(st.grid_adjacency, (1.5, 3), raises=InputError, why="fractional"),
    Case(st.unit_equations, (_MODELS, np.full((2, 7), NAN), _CTL), raises=InputError, why="NaN parameters"),
    Case(st.unit_equations, (_MODELS, np.zeros((3, 7)), _CTL), raises=InputError, why="wrong shape"),
    Case(st.initial_transforms, (_MODELS, {1: [1.0, NAN, 2.0]}), raises=InputError, why="X without Y"),
    Case(st.adjust_independent_units, ([],), raises=InputError, why="no units"),
    Case(st.adjust_independent_units, (_MODELS,), raises=InputError, why="no datum"),
    Case(st.adjust_independent_units, (_MODELS, _CTL), dict(sigma_tie=0.0), raises=InputError, why="σ = 0"),
    Case(st.image_orientations, (_MODELS, []), raises=InputError, why="no transforms"),
    Case(st.image_orientations, ([st.UnitModel("x", [1], np.zeros((1, 3)))],
                                 [SimilarityTransform(0, 0, 0, 0, 0, 0, 1.0)]), raises=InputError,
         why="unit without a stereo model"),
    Case(st.count_independent_strips, (3, -1, 8), raises=InputError, why="negative count"),
    Case(st.count_independent_models, (0, 1, 1), raises=InputError, why="no model"),
    Case(st.structure_counts, (_MODELS, {1: "abc"}), raises=InputError, why="text control"),
    Case(st.layout_block, (1, 1), raises=InputError, why="one image"),
    Case(st.layout_block, (), dict(sigma=NAN), raises=InputError, why="NaN sigma"),
    Case(st.layout_block, (), dict(forward_overlap=1.5), raises=InputError, why="overlap > 1"),
    Case(st.layout_models, (_FB,), raises=InputError, why="block without strips"),
    Case(st.layout_models, (_BLK, [5]), raises=InputError, why="missing strip"),
    # --- triangulation_layouts ---------------------------------------------------------------------
    Case(tl.bundle_unknowns, (-1, 2), raises=InputError, why="negative"),
    Case(tl.bundle_unknowns, (NAN, 2), raises=InputError, why="NaN"),
    Case(tl.bundle_equations, (2.5,), raises=InputError, why="fractional"),
    Case(tl.images_per_point, ("block",), raises=InputError, why="not a block"),
    Case(tl.block_counts, (None,), raises=InputError, why="not a block"),
    Case(tl.BundleSystem, (np.eye(2), np.zeros(2), np.ones(2), np.array(["tie", "tie"]), ["a", "b"], 0),
         raises=None, check=lambda r: r.rank == 2, why="a plain record"),
    Case(tl.correction_equation_system, (_FB, np.full((2, 6), NAN)), raises=InputError, why="NaN cameras"),
    Case(tl.correction_equation_system, (_FB, np.zeros((3, 6))), raises=InputError, why="wrong shape"),
    Case(tl.correction_equation_system, (_FB,), dict(ins=np.zeros((5, 3))), raises=InputError, why="bad INS"),
    Case(tl.correction_equation_system, (_FB,), dict(height=[2]), raises=InputError,
         why="height control with fixed control"),
    Case(tl.normal_matrix_structure, (np.eye(3),), raises=InputError, why="not a BundleSystem"),
    Case(tl.predicted_point_sigma, (_RES, 0.005), raises=InputError, why="no covariance"),
    Case(tl.predicted_point_sigma, (_RES, NAN), raises=InputError, why="NaN σ₀"),
    Case(tl.check_point_accuracy, (_FB, _RES, [7]), raises=InputError, why="index out of range"),
    Case(tl.check_point_accuracy, (_FB, object()), raises=InputError, why="not a result"),
    Case(tl.Criterion, ("3.7.6", "x", 1.0, 2.0, "m", True), raises=None, check=lambda r: r.passed,
         why="a plain record"),
    Case(tl.check_height_factor, (0.5, 10000, _TOL), raises=InputError, why="not covered by 3.7.6"),
    Case(tl.check_height_factor, (NAN, 10000, _TOL), raises=InputError, why="NaN h"),
    Case(tl.check_height_factor, (1.0, 10000, _TOL, "final"), raises=InputError, why="unknown stage"),
    Case(tl.check_height_factor, (1.0, 10000, None), raises=InputError, why="no tolerances"),
    Case(tl.free_strip_height_tolerance_um, (0.0, 92.0, _TOL), raises=InputError, why="f = 0"),
    Case(tl.free_strip_height_tolerance_um, (100.0, 50.0, {"3.7.2 tie height": "x"}), raises=InputError,
         why="text tolerance"),
    Case(tl.evaluate_regulations, ([[0, 0, 0]], np.zeros((0, 3)), 2000, 1.0, _TOL), raises=InputError,
         why="no check point"),
    Case(tl.evaluate_regulations, ([[0, 0, NAN]], [[0, 0, 0]], 2000, 1.0, _TOL), raises=InputError,
         why="NaN error"),
    Case(tl.evaluate_regulations, ([[0, 0]], [[0, 0, 0]], 2000, 1.0, _TOL), raises=InputError,
         why="2-D errors"),
]


@pytest.mark.parametrize("case", CASES, ids=lambda c: c.id)
def test_bad_input(case):
    check_case(case)
