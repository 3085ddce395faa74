"""Bad-input catalogue for the adjustment engine (photolib.lsq) and the bundle adjustment
(photolib.bundle): NaN/inf, wrong shapes and types, too few observations, datum defects,
divergence, points behind a camera. Every case must give a named photolib error or a correct
result (expected values from ground truth: noise-free synthetic blocks, closed-form fits)."""

from dataclasses import fields

import numpy as np
import pytest

from catalogue import INF, NAN, Case, check_case
from photolib import bundle as bd
from photolib import lsq, synthetic
from photolib.camera import InteriorOrientation
from photolib.errors import ConvergenceError, DegenerateGeometryError, InputError, PointBehindCameraError

# --- a straight line y = a + b·t (dense engine), truth a = 1.09, b = 1.94 by the closed form -------------
T = np.array([0.0, 1.0, 2.0, 3.0])
Y = np.array([1.1, 2.9, 5.2, 6.8])
B_LINE = np.column_stack([np.ones(4), T])


def line(x):
    return B_LINE, x[0] + x[1] * T - Y


def line_nan(x):
    return B_LINE, np.full(4, NAN)


def exp_model(x):                     # y = exp(c·t): nonlinear, needs several iterations from c = 0
    return (T * np.exp(x[0] * T))[:, None], np.exp(x[0] * T) - np.exp(0.7 * T)


def close(expected, atol=1e-9):
    return lambda r: np.allclose(np.asarray(r, dtype=float), expected, atol=atol)


def line_ok(adj):
    return np.allclose(adj.x, [1.09, 1.94], atol=1e-12) and adj.dof == 2


# --- a toy block (q = 1 offsets, points measured directly): frames/points known exactly ------------------
TRUTH = np.array([[1.0, 2.0, 3.0], [4.0, 5.0, 6.0]])
FRAME, POINT = np.array([0, 0, 1, 1]), np.array([0, 1, 0, 1])
PRIOR = (np.zeros((2, 1)), np.ones((2, 1)))


def toy_linearize(frames, points):
    r = points[POINT] + frames[FRAME, :1] - TRUTH[POINT]
    return lsq.BlockCorrectionEquations(FRAME, POINT, np.ones((4, 3, 1)), np.broadcast_to(np.eye(3), (4, 3, 3)).copy(), r)


RNG = np.random.default_rng(0)
EQ = lsq.BlockCorrectionEquations(np.repeat([0, 1], 5), np.tile(np.arange(5), 2), RNG.normal(size=(10, 2, 6)),
                                  RNG.normal(size=(10, 2, 3)), np.zeros((10, 2)))
EQ_NAN = lsq.BlockCorrectionEquations(EQ.frame, EQ.point, EQ.B1, EQ.B2, np.full((10, 2), NAN))
EQ_SHAPE = lsq.BlockCorrectionEquations(EQ.frame, EQ.point, EQ.B1, EQ.B2[:, :, :2], EQ.L)
GEQ = lsq.GlobalBlockCorrectionEquations(EQ.frame, EQ.point, EQ.B1, EQ.B2, EQ.L, B3=np.ones((10, 2, 1)))
FPRIOR = (np.zeros((2, 6)), np.ones((2, 6)))
N3 = np.array([[4.0, 1.0, 0.5], [1.0, 3.0, 0.2], [0.5, 0.2, 2.0]])
L3 = np.array([1.0, 2.0, 3.0])

# --- a tiny noise-free aerial block (§3.5) ----------------------------------------------------------------
BLK = synthetic.aerial_block(2, 4, points_per_image=15, sigma=0.0, seed=1)
C0, P0 = BLK.start_values(seed=2)
CTRL = {int(i): BLK.points[i] for i in BLK.control}
OBS = BLK.observations
IO = BLK.io
RES = bd.bundle_adjustment(OBS, C0, P0, IO, control=CTRL, order=BLK.order)
XY_NAN = dict(image=OBS.image, point=OBS.point, xy=np.where(np.arange(len(OBS))[:, None] == 3, NAN, OBS.xy))
UNDERGROUND = C0.copy()
UNDERGROUND[:, 2] = -500.0                            # every camera below the terrain: points behind
FEW = dict(image=OBS.image[OBS.image != 0].tolist() + [0, 0], point=OBS.point[OBS.image != 0].tolist() + [0, 1],
           xy=np.vstack([OBS.xy[OBS.image != 0], OBS.xy[:2]]))   # image 0 with two points only
FLAT = synthetic.aerial_block(2, 5, relief=0.0, angle_sigma=0.0, height_sigma=0.0, sigma=0.0, seed=1)
FC0, FP0 = FLAT.start_values(seed=1)

# self-calibration, rig and rolling-shutter results for the result classes
SC_IO = InteriorOrientation(f=100.0, x0=0.05, y0=-0.03)
SCB = synthetic.aerial_block(3, 4, io=SC_IO, strip_heights=(800, 1000, 1200), relief=150.0, points_per_image=20,
                             sigma=0.0, seed=3)
SC0, SP0 = SCB.start_values(seed=1)
SC = bd.self_calibrating_bundle_adjustment(SCB.observations, SC0, SP0, InteriorOrientation(f=99.0),
                                           calibrate=("f", "x0", "y0"), order=SCB.order,
                                           control={int(i): SCB.points[i] for i in SCB.control})
RB = synthetic.rig_block(sigma=0.0, seed=0)
RIG = bd.rig_bundle_adjustment(RB.observations, RB.exposure_of_image, RB.camera_of_image, RB.exposures, RB.mounts,
                               RB.points, RB.ios, control={int(i): RB.points[i] for i in RB.control}, order=RB.order)
RSB = synthetic.rolling_shutter_block(sigma=0.0, model="linear")
RS0, RP0 = RSB.block.start_values(seed=1)
RS = bd.rolling_shutter_bundle_adjustment(RSB.observations, RS0, RP0, RSB.block.io, model="linear",
                                          control={int(i): RSB.block.points[i] for i in RSB.block.control},
                                          order=RSB.block.order)


def as_kwargs(obj, cls):
    return {f.name: getattr(obj, f.name) for f in fields(cls)}


def truth_cameras(res):
    return np.allclose(res.cameras, BLK.cameras, atol=1e-6)


CASES = [
    # --- lsq: the dense engine ----------------------------------------------------------------------
    Case(lsq.blas_on_one_thread, (), raises=None, check=lambda ctx: hasattr(ctx, "__enter__"),
         why="takes no input: a context manager"),
    Case(lsq.gauss_newton, (line, [NAN, 0.0]), raises=InputError, match="NaN", why="NaN start"),
    Case(lsq.gauss_newton, (line, [[0.0, 0.0]]), raises=InputError, why="2-D start"),
    Case(lsq.gauss_newton, (line, ["a", 0.0]), raises=InputError, why="string start"),
    Case(lsq.gauss_newton, ("line", [0.0, 0.0]), raises=InputError, why="linearize not callable"),
    Case(lsq.gauss_newton, (line, [0.0, 0.0], [1.0, 1.0]), raises=InputError, why="weights of the wrong length"),
    Case(lsq.gauss_newton, (line, [0.0, 0.0], [1.0, -1.0, 1.0, 1.0]), raises=InputError, why="negative weight"),
    Case(lsq.gauss_newton, (line, [0.0, 0.0], [1.0, NAN, 1.0, 1.0]), raises=InputError, why="NaN weight"),
    Case(lsq.gauss_newton, (line_nan, [0.0, 0.0]), raises=InputError, match="NaN", why="NaN free terms"),
    Case(lsq.gauss_newton, (lambda x: (B_LINE[:1], np.zeros(1)), [0.0, 0.0]), raises=InputError,
         why="too few observations (1 equation, 2 unknowns)"),
    Case(lsq.gauss_newton, (lambda x: (np.ones((4, 2)), x[0] + x[1] - Y), [0.0, 0.0]),
         raises=DegenerateGeometryError, why="datum defect: only a + b is determined"),
    Case(lsq.gauss_newton, (exp_model, [0.0]), {"max_iter": 1}, raises=ConvergenceError, why="no convergence"),
    Case(lsq.gauss_newton, (lambda x: ((T * np.exp(x[0] * T))[:, None], np.exp(x[0] * T) - 1e300), [5.0]),
         raises=(InputError, ConvergenceError), why="divergence to inf"),
    Case(lsq.gauss_newton, (line, [0.0, 0.0]), {"max_iter": 0}, raises=InputError, why="max_iter 0"),
    Case(lsq.gauss_newton, (line, [0.0, 0.0]), {"tol": [1.0, 2.0, 3.0]}, raises=InputError, why="tol shape"),
    Case(lsq.gauss_newton, (line, [0.0, 0.0], np.ones(4)), raises=None, check=line_ok, why="positional weights"),
    Case(lsq.gauss_newton, (line, [0.0, 0.0]), {"P": np.ones(4)}, raises=None, check=line_ok, why="former keyword P"),
    Case(lsq.gauss_newton, (exp_model, [0.0]), raises=None, check=lambda a: abs(a.x[0] - 0.7) < 1e-10,
         why="nonlinear, far start"),
    Case(lsq.solve_normal_equations, (B_LINE, np.array([1.0, NAN, 0.0, 0.0])), raises=InputError, why="NaN L"),
    Case(lsq.solve_normal_equations, (B_LINE, np.zeros(3)), raises=InputError, why="L of the wrong length"),
    Case(lsq.solve_normal_equations, (B_LINE[:1], np.zeros(1)), raises=InputError, why="m < n"),
    Case(lsq.solve_normal_equations, ([["a", "b"]], [0.0]), raises=InputError, why="strings"),
    Case(lsq.solve_normal_equations, (np.ones((4, 2)), np.zeros(4)), raises=DegenerateGeometryError,
         why="singular N"),
    Case(lsq.solve_normal_equations, (B_LINE, -Y), raises=None, check=lambda r: np.allclose(r[0], [1.09, 1.94]),
         why="a straight line"),
    Case(lsq.accuracy, (np.array([NAN, 0.1]), np.eye(1)), raises=InputError, why="NaN residual"),
    Case(lsq.accuracy, (np.zeros(3), np.ones((2, 3))), raises=InputError, why="non-square Q"),
    Case(lsq.accuracy, (np.array([0.1, -0.1, 0.1, -0.1]), np.diag([1.0, 4.0])), raises=None,
         check=lambda r: np.isclose(r[0], np.sqrt(0.02)) and np.allclose(r[1], [np.sqrt(0.02), 2 * np.sqrt(0.02)]),
         why="μ, m_j by hand"),
    Case(lsq.redundancy_numbers, (B_LINE, np.eye(3)), raises=InputError, why="Q of the wrong size"),
    Case(lsq.redundancy_numbers, (B_LINE, np.full((2, 2), NAN)), raises=InputError, why="NaN Q"),
    Case(lsq.redundancy_numbers, (B_LINE, np.eye(2), np.zeros(4)), raises=InputError, why="zero weights"),
    Case(lsq.redundancy_numbers, (np.ones((4, 1)), np.array([[0.25]])), raises=None, check=close([0.75] * 4),
         why="mean of four: r = 3/4"),
    Case(lsq.point_weights, (np.ones(3), 2), raises=InputError, why="wrong shape"),
    Case(lsq.point_weights, ([1.0, 0.0], 2), raises=InputError, why="zero weight"),
    Case(lsq.point_weights, ([1.0, INF], 2), raises=InputError, why="inf"),
    Case(lsq.point_weights, (["a", "b"], 2), raises=InputError, why="strings"),
    Case(lsq.point_weights, ([1.0, 4.0], 2), raises=None, check=close([1, 1, 4, 4]), why="one per point"),
    Case(lsq.solve_partitioned_normal_equations, (N3[:1, :1], N3[:1, 1:], N3[1:, 1:], L3[:1], L3[1:]),
         {"eliminate": "frames"}, raises=InputError, why="unknown eliminate"),
    Case(lsq.solve_partitioned_normal_equations, (N3[:1, :1], N3[1:, :1], N3[1:, 1:], L3[:1], L3[1:]),
         raises=InputError, why="N12 transposed"),
    Case(lsq.solve_partitioned_normal_equations, (N3[:1, :1], N3[:1, 1:], np.zeros((2, 2)), L3[:1], L3[1:]),
         raises=DegenerateGeometryError, why="singular N22"),
    Case(lsq.solve_partitioned_normal_equations, (N3[:1, :1], N3[:1, 1:], N3[1:, 1:], [NAN], L3[1:]),
         raises=InputError, why="NaN"),
    Case(lsq.solve_partitioned_normal_equations, (N3[:1, :1], N3[:1, 1:], N3[1:, 1:], L3[:1], L3[1:]),
         {"eliminate": "eo"}, raises=None,
         check=lambda r: np.allclose(np.concatenate(r), np.linalg.solve(N3, L3)), why="against numpy"),
    # --- lsq: the block-sparse solver --------------------------------------------------------------------
    Case(lsq.solve_block_normal_equations, ("eq", 2, 5), raises=InputError, why="not block equations"),
    Case(lsq.solve_block_normal_equations, (EQ_NAN, 2, 5), {"frame_prior": FPRIOR}, raises=InputError, why="NaN L"),
    Case(lsq.solve_block_normal_equations, (EQ_SHAPE, 2, 5), raises=InputError, why="B2 with 2 columns"),
    Case(lsq.solve_block_normal_equations, (EQ, 2, 4), raises=InputError, why="point index outside"),
    Case(lsq.solve_block_normal_equations, (EQ, 2, 5), raises=DegenerateGeometryError,
         why="datum defect: no control"),
    Case(lsq.solve_block_normal_equations, (EQ, 2, 5), {"frame_prior": FPRIOR, "global_prior": (0, 1)},
         raises=InputError, why="global prior without globals"),
    Case(lsq.solve_block_normal_equations, (EQ, 2, 5), {"frame_prior": FPRIOR}, raises=None,
         check=lambda s: np.allclose(s.delta1, 0) and np.allclose(s.delta2, 0), why="consistent equations: δ = 0"),
    Case(lsq.block_gauss_newton, (toy_linearize, np.full((2, 1), NAN), TRUTH), raises=InputError, why="NaN frames"),
    Case(lsq.block_gauss_newton, (toy_linearize, np.zeros((2, 1)), TRUTH[:, :2]), raises=InputError,
         why="points with two coordinates"),
    Case(lsq.block_gauss_newton, (toy_linearize, np.zeros((2, 1)), TRUTH), {"max_iter": 0}, raises=InputError,
         why="max_iter 0"),
    Case(lsq.block_gauss_newton, (toy_linearize, np.zeros((2, 1)), TRUTH), raises=DegenerateGeometryError,
         why="datum defect: offsets and points inseparable"),
    Case(lsq.block_gauss_newton, (toy_linearize, np.zeros((2, 1)), TRUTH + 0.1),
         {"frame_observations": PRIOR, "max_iter": 1}, raises=ConvergenceError, why="max_iter 1"),
    Case(lsq.block_gauss_newton, (toy_linearize, np.zeros((2, 1)), TRUTH), {"free_points": [True]},
         raises=InputError, why="free_points of the wrong length"),
    Case(lsq.block_gauss_newton, (toy_linearize, np.zeros((2, 1)), TRUTH + 0.1), {"frame_observations": PRIOR},
         raises=None, check=lambda a: np.allclose(a.points, TRUTH, atol=1e-9), why="toy block"),
    Case(lsq.block_equations_dense, (EQ, 2, 5), {"free_points": [True] * 4}, raises=InputError,
         why="free_points of the wrong length"),
    Case(lsq.block_equations_dense, (EQ, 2, 5), raises=None, check=lambda r: r[0].shape == (20, 27), why="shape"),
    Case(lsq.global_block_equations_dense, (GEQ, 2, 4), raises=InputError, why="point index outside"),
    Case(lsq.global_block_equations_dense, (GEQ, 2, 5), raises=None, check=lambda r: r[0].shape == (20, 28),
         why="shape"),
    # --- lsq: result and equation types -------------------------------------------------------------------
    Case(lsq.Adjustment, (np.array([1.09, 1.94]), np.zeros(4), 0.1, np.eye(2), np.full(2, 0.1), np.eye(2), 2, 2),
         {"names": ("a", "b")}, raises=None, check=lambda a: "a = 1.09 ± 0.1" in a.summary(), why="summary"),
    Case(lsq.IterationRecord, (1, np.zeros(2), np.ones(2), 2.0), raises=None, check=lambda r: r.vtpv == 2.0,
         why="plain record"),
    Case(lsq.AdjustmentView, (), raises=None, check=lambda v: isinstance(v, lsq.AdjustmentView), why="mixin"),
    Case(lsq.BlockSolution, (np.zeros((2, 6)), np.zeros((5, 3))), raises=None,
         check=lambda s: s.delta3 is None, why="no globals"),
    Case(lsq.BlockCorrectionEquations, (EQ.frame, EQ.point, EQ.B1, EQ.B2, EQ.L), raises=None,
         check=lambda e: e.P == 1.0, why="unit weights by default"),
    Case(lsq.GlobalBlockCorrectionEquations, (EQ.frame, EQ.point, EQ.B1, EQ.B2, EQ.L), raises=None,
         check=lambda e: e.B3 is None, why="no global columns"),
    # --- bundle -----------------------------------------------------------------------------------------
    Case(bd.bundle_adjustment, (XY_NAN, C0, P0, IO), {"control": CTRL}, raises=InputError, match="NaN",
         why="NaN image coordinate"),
    Case(bd.bundle_adjustment, (OBS, C0[:, :5], P0, IO), {"control": CTRL}, raises=InputError,
         why="cameras with 5 columns"),
    Case(bd.bundle_adjustment, (OBS, C0, P0, IO), {"control": CTRL, "order": "xyz"}, raises=InputError,
         why="unknown order"),
    Case(bd.bundle_adjustment, (FEW, C0, P0, IO), {"control": CTRL}, raises=InputError,
         why="an image with two points"),
    Case(bd.bundle_adjustment, (OBS, C0, P0, IO), raises=DegenerateGeometryError, match="datum",
         why="no control: datum defect"),
    Case(bd.bundle_adjustment, (OBS, UNDERGROUND, P0, IO), {"control": CTRL}, raises=PointBehindCameraError,
         why="start values below the terrain: points behind the cameras"),
    Case(bd.bundle_adjustment, (OBS, C0, P0, IO), {"control": CTRL, "sigma_control": -1.0}, raises=InputError,
         why="negative sigma_control"),
    Case(bd.bundle_adjustment, (OBS, C0, P0, IO), {"control": CTRL, "sigma_contrl": 0.05}, raises=InputError,
         why="misspelt keyword"),
    Case(bd.bundle_adjustment, (OBS, C0, P0, IO), {"control": CTRL, "max_iter": 1}, raises=ConvergenceError,
         why="max_iter 1"),
    Case(bd.bundle_adjustment, (OBS, C0, P0, IO), {"control": CTRL, "control_sigma": 1e-4}, raises=None,
         check=truth_cameras, why="former keyword control_sigma"),
    Case(bd.bundle_correction_equations, (OBS.image, OBS.point, OBS.xy, UNDERGROUND, BLK.points, IO, BLK.order),
         raises=PointBehindCameraError, why="points behind"),
    Case(bd.bundle_correction_equations, (OBS.image, OBS.point, OBS.xy, BLK.cameras, BLK.points, IO, BLK.order),
         raises=None, check=lambda e: np.abs(e.L).max() < 1e-9, why="at the truth L = 0"),
    Case(bd.check_point_statistics, (RES, BLK.points, []), raises=InputError, why="no check points"),
    Case(bd.check_point_statistics, (RES, BLK.points, [10_000]), raises=InputError, why="index outside"),
    Case(bd.check_point_statistics, (RES, np.full_like(BLK.points, NAN), BLK.check), raises=InputError,
         why="NaN truth"),
    Case(bd.check_point_statistics, ("result", BLK.points, BLK.check), raises=InputError, why="not a result"),
    Case(bd.check_point_statistics, (RES, BLK.points, BLK.check), raises=None,
         check=lambda s: s.n == len(BLK.check) and np.all(s.rms < 1e-6), why="noise-free: zero errors"),
    Case(bd.count_bundle_unknowns, (-1, 3), raises=InputError, why="negative"),
    Case(bd.count_bundle_unknowns, (4, 10), raises=None, check=lambda n: n == 54, why="(3.5.20)"),
    Case(bd.count_self_calibration_unknowns, (4, 10, ("f", "q")), raises=InputError, why="unknown name"),
    Case(bd.count_self_calibration_unknowns, (4, 10), raises=None, check=lambda n: n == 62, why="+8"),
    Case(bd.count_rig_unknowns, (2, 2, 4, "both"), raises=InputError, why="unknown parameterisation"),
    Case(bd.count_rig_unknowns, (2, 2, 4), raises=None, check=lambda n: n == 30, why="(3.8.2)"),
    Case(bd.count_rolling_shutter_unknowns, (3, 10, "quadratic"), raises=InputError, why="unknown model"),
    Case(bd.count_rolling_shutter_unknowns, (NAN, 10), raises=InputError, why="NaN"),
    Case(bd.count_rolling_shutter_unknowns, (3, 10), raises=None, check=lambda n: n == 66, why="12 per image"),
    Case(bd.self_calibration_correction_equations, (OBS.image, OBS.point, OBS.xy, BLK.cameras, BLK.points,
                                                    [100, 0, 0, 0, 0, 0, 0, 0], ("f", "q")),
         raises=InputError, why="unknown calibrate name"),
    Case(bd.self_calibration_correction_equations, (OBS.image, OBS.point, OBS.xy, UNDERGROUND, BLK.points,
                                                    [100, 0, 0, 0, 0, 0, 0, 0]),
         raises=PointBehindCameraError, why="points behind"),
    Case(bd.self_calibrating_bundle_adjustment, (OBS, C0, P0, 100.0), raises=InputError, why="io0 a number"),
    Case(bd.self_calibrating_bundle_adjustment, (FLAT.observations, FC0, FP0, InteriorOrientation(f=100.0)),
         {"calibrate": ("f",), "control": {int(i): FLAT.points[i] for i in FLAT.control}},
         raises=DegenerateGeometryError, match="cannot separate", why="flat terrain, nadir images: f vs Z_S"),
    Case(bd.self_calibrating_bundle_adjustment, (OBS, C0, P0, IO), {"control": CTRL, "io_sigma": {"f": -1.0}},
         raises=InputError, why="negative σ of f (former keyword)"),
    Case(bd.rig_image_orientation, (np.zeros(5), np.zeros(6)), raises=InputError, why="5 values"),
    Case(bd.rig_image_orientation, (np.full(6, NAN), np.zeros(6)), raises=InputError, why="NaN"),
    Case(bd.rig_image_orientation, (np.zeros(6), [1.0, 2.0, 3.0, 0, 0, 0]), raises=None,
         check=close([1, 2, 3, 0, 0, 0]), why="A₁ = E: S₂ = S₁ + B"),
    Case(bd.rig_bundle_adjustment, (RB.observations, RB.exposure_of_image, np.maximum(RB.camera_of_image, 1),
                                    RB.exposures, RB.mounts, RB.points, RB.ios),
         raises=InputError, why="exposures without reference image"),
    Case(bd.rig_bundle_adjustment, (RB.observations, RB.exposure_of_image, RB.camera_of_image, RB.exposures[:, :5],
                                    RB.mounts, RB.points, RB.ios), raises=InputError, why="exposures with 5 columns"),
    Case(bd.rig_design_matrix, (RB.observations, RB.exposure_of_image, RB.camera_of_image, RB.exposures,
                                RB.mounts, RB.points, RB.ios), {"parameterisation": "both"},
         raises=InputError, why="unknown parameterisation"),
    Case(bd.rolling_shutter_project, (BLK.cameras, None, BLK.points[OBS.point], IO), raises=InputError,
         why="several orientations without image"),
    Case(bd.rolling_shutter_project, (BLK.cameras[0], None, [[NAN, 0.0, 0.0]], IO), raises=InputError, why="NaN"),
    Case(bd.rolling_shutter_project, (BLK.cameras[0], None, BLK.cameras[0, :3] + [0, 0, 100.0], IO),
         raises=PointBehindCameraError, why="point above the camera"),
    Case(bd.rolling_shutter_project, (BLK.cameras, None, BLK.points[OBS.point], IO, BLK.order),
         {"image": OBS.image}, raises=None, check=close(BLK.xy_true, 1e-10), why="zero rates: frame projection"),
    Case(bd.rolling_shutter_correction_equations, (OBS.image, OBS.point, OBS.xy, np.zeros((8, 12)), BLK.points, IO),
         {"model": "quadratic"}, raises=InputError, why="unknown model"),
    Case(bd.rolling_shutter_bundle_adjustment, (OBS, C0, P0, IO), {"control": CTRL, "model": "quadratic"},
         raises=InputError, why="unknown model"),
    Case(bd.rolling_shutter_bundle_adjustment, (OBS, C0, P0, IO), {"control": CTRL, "gnss": np.zeros((3, 3))},
         raises=InputError, why="gnss of the wrong shape"),
    # --- bundle: result types rebuilt from real results ----------------------------------------------------
    Case(bd.BundleResult, (), as_kwargs(RES, bd.BundleResult), raises=None, check=truth_cameras, why="rebuilt"),
    Case(bd.CheckPointStatistics, (2, np.zeros(3), np.full(3, 0.1), np.full(3, 0.2), None), raises=None,
         check=lambda s: s.ratio is None, why="no prediction"),
    Case(bd.CorrelationReport, (), as_kwargs(SC.correlations, bd.CorrelationReport), raises=None,
         check=lambda r: np.allclose(np.diag(r.among), 1.0), why="rebuilt"),
    Case(bd.SelfCalibrationResult, (), as_kwargs(SC, bd.SelfCalibrationResult), raises=None,
         check=lambda r: abs(r.io.f - 100.0) < 1e-6, why="rebuilt"),
    Case(bd.RigResult, (), as_kwargs(RIG, bd.RigResult), raises=None,
         check=lambda r: np.allclose(r.mounts, RB.mounts, atol=1e-6), why="rebuilt"),
    Case(bd.RollingShutterResult, (), as_kwargs(RS, bd.RollingShutterResult), raises=None,
         check=lambda r: np.allclose(r.rates, RSB.rates, atol=1e-8), why="rebuilt"),
]


@pytest.mark.parametrize("case", CASES, ids=[c.id for c in CASES])
def test_bad_input(case):
    check_case(case)
