"""Bad-input catalogue for photolib.rpc: NaN/inf, wrong types, shapes, files and ranges."""

import numpy as np
import pytest

from catalogue import INF, NAN, Case, check_case
from photolib.errors import ConvergenceError, DegenerateGeometryError, InputError
from photolib.synthetic import MicroFrameCamera, microframe_camera
from photolib.rpc import (RPC, BiasCorrectedRPC, RPCFit, RPCIntersection, conventional_frame_rpc, fit_bias, fit_rpc,
                          fit_rpc_points, intersect_rpc, locate, project, rpc_grid)


def unit(k):
    return [0.0] * k + [1.0] + [0.0] * (19 - k)


OFFSETS = dict(line_off=100, samp_off=200, lat_off=45, long_off=5, height_off=0, line_scale=50, samp_scale=80,
               lat_scale=0.01, long_scale=0.01, height_scale=500)
TOY = RPC(**OFFSETS, line_num_coeff=unit(2), line_den_coeff=unit(0), samp_num_coeff=unit(1), samp_den_coeff=unit(0))
# a denominator 1 + L that vanishes at lon = long_off - long_scale = 4.99
SINGULAR_DEN = RPC(**OFFSETS, line_num_coeff=unit(2), line_den_coeff=np.r_[1.0, 1.0, [0.0] * 18],
                   samp_num_coeff=unit(1), samp_den_coeff=unit(0))
# line and sample both depend on L only: the Jacobian ∂(line, sample)/∂(L, P) is singular
NO_LAT = RPC(**OFFSETS, line_num_coeff=unit(1), line_den_coeff=unit(0), samp_num_coeff=unit(1),
             samp_den_coeff=unit(0))
# line = P + P³ with sample = L: locate converges, but slowly from far out
CUBIC = RPC(**OFFSETS, line_num_coeff=np.r_[[0, 0, 1.0], [0.0] * 12, [1.0], [0.0] * 4], line_den_coeff=unit(0),
            samp_num_coeff=unit(1), samp_den_coeff=unit(0))
# line = 0.1·P − P³: no real root near the centre for large rows, Newton wanders off
DIVERGE = RPC(**OFFSETS, line_num_coeff=np.r_[[0, 0, 0.1], [0.0] * 12, [-1.0], [0.0] * 4],
              line_den_coeff=unit(0), samp_num_coeff=unit(1), samp_den_coeff=unit(0))
GOOD_MD = TOY.to_gdal_metadata()


def geom_file(tmp_name, text):
    import tempfile
    from pathlib import Path
    path = Path(tempfile.mkdtemp()) / tmp_name
    path.write_text(text)
    return path


BAD_FORMAT = geom_file("a.geom", "polynomial_format:  A\nline_off: 1\n")
MISSING_KEY = geom_file("b.geom", "\n".join(f"{k.lower()}:  {v}" for k, v in GOOD_MD.items() if "COEFF" not in k))
NOT_NUMBER = geom_file("c.geom", "line_off:  abc\n")


def with_(**changes):
    kwargs = dict(OFFSETS, line_num_coeff=unit(2), line_den_coeff=unit(0), samp_num_coeff=unit(1),
                  samp_den_coeff=unit(0))
    kwargs.update(changes)
    return kwargs


CASES = [
    # the synthetic micro-frame camera of §8.18 (photolib.synthetic)
    Case(microframe_camera, (), raises=None, check=lambda cam: len(cam.offsets) == 6, why="no input: a fixed synthetic camera"),
    Case(MicroFrameCamera, (None, None, 0.0074, (10, 10), (5, 5), ((0, 0),)), raises=None, check=lambda cam: cam.pixel_size > 0,
         why="a plain record; its methods validate"),
    Case(microframe_camera().ground_of, (6,), raises=InputError, match="matrix number", why="no such matrix"),
    Case(microframe_camera().ground_of, (True,), raises=InputError, why="a bool index"),
    Case(microframe_camera().project, ([[0.0, NAN, 0.0]],), raises=InputError, why="NaN point"),
    Case(microframe_camera().project, ([[0.0, 0.0]],), raises=InputError, why="2-D points"),
    # the constructor
    Case(RPC, kwargs=with_(line_off=NAN), why="NaN offset", raises=InputError, match="line_off"),
    Case(RPC, kwargs=with_(lat_scale=0.0), why="zero scale", raises=InputError, match="positive"),
    Case(RPC, kwargs=with_(height_scale=-5.0), why="negative scale", raises=InputError, match="positive"),
    Case(RPC, kwargs=with_(samp_off="x"), why="text offset", raises=InputError, match="number"),
    Case(RPC, kwargs=with_(line_num_coeff=[1.0] * 19), why="19 coefficients", raises=InputError, match="20"),
    Case(RPC, kwargs=with_(samp_num_coeff=[INF] + [0.0] * 19), why="inf coefficient", raises=InputError),
    Case(RPC, kwargs=with_(line_den_coeff=[0.0] * 20), why="zero denominator", raises=InputError, match="zero"),
    Case(RPC, kwargs=with_(line_num_coeff="1 0 0"), why="a string for coefficients", raises=InputError),
    Case(RPC, kwargs=with_(line_num_coeff=[["a"]] * 20), why="non-numeric coefficients", raises=InputError),
    # readers and writers
    Case(RPC.from_ossim_geom, ("/no/such/file.geom",), why="missing file", raises=InputError, match="cannot read"),
    Case(RPC.from_ossim_geom, (42,), why="not a path", raises=InputError),
    Case(RPC.from_ossim_geom, (BAD_FORMAT,), why="RPC00A format", raises=InputError, match="RPC00B"),
    Case(RPC.from_ossim_geom, (MISSING_KEY,), why="no coefficients", raises=InputError, match="missing"),
    Case(RPC.from_ossim_geom, (NOT_NUMBER,), why="a value that is no number", raises=InputError, match="number"),
    Case(RPC.from_gdal_metadata, ([1, 2],), why="not a mapping", raises=InputError, match="mapping"),
    Case(RPC.from_gdal_metadata, ({k: v for k, v in GOOD_MD.items() if k != "LAT_OFF"},),
         why="missing LAT_OFF", raises=InputError, match="LAT_OFF"),
    Case(RPC.from_gdal_metadata, ({**GOOD_MD, "LINE_NUM_COEFF": "1 2 3"},), why="3 coefficients",
         raises=InputError, match="20"),
    Case(RPC.from_gdal_metadata, ({**GOOD_MD, "SAMP_SCALE": "nan"},), why="NaN scale", raises=InputError),
    Case(RPC.from_gdal_metadata, ({**GOOD_MD, "LINE_DEN_COEFF": "1 x" + " 0" * 18},), why="a word among numbers",
         raises=InputError, match="not a number"),
    Case(RPC.from_gdal_metadata, ({**GOOD_MD, "LAT_OFF": "45.0 degrees"},), raises=None,
         why="trailing text after a number (as GDAL tolerates)", check=lambda r: r.lat_off == 45.0),
    Case(TOY.to_gdal_metadata, (), raises=None, why="round trip", check=lambda md: RPC.from_gdal_metadata(md) == TOY),
    Case(TOY.shifted, (NAN, 0), why="NaN row offset", raises=InputError),
    Case(TOY.shifted, ("a", 0), why="text offset", raises=InputError),
    # project
    Case(project, ("rpc", 5.0, 45.0, 0.0), why="not an RPC", raises=InputError, match="RPC"),
    Case(project, (TOY, NAN, 45.0, 0.0), why="NaN longitude", raises=InputError, match="lon"),
    Case(project, (TOY, 5.0, 45.0, INF), why="inf height", raises=InputError, match="height"),
    Case(project, (TOY, [5.0, 5.0], [45.0, 45.0, 45.0], 0.0), why="mismatched sizes", raises=InputError,
         match="broadcast"),
    Case(project, (TOY, 5.0, 46.0, 0.0), why="latitude 100 scales away", raises=InputError, match="valid range"),
    Case(project, (TOY, 5.0, 45.0, 0.0), kwargs={"extrapolation": 0.0}, why="zero extrapolation",
         raises=InputError),
    Case(project, (TOY, "5", 45.0, 0.0), why="a string coordinate", raises=InputError),
    Case(project, (SINGULAR_DEN, 4.99, 45.0, 0.0), why="denominator vanishes", raises=DegenerateGeometryError,
         match="denominator"),
    Case(project, (TOY, [], [], []), raises=None, why="no points", check=lambda rc: rc[0].shape == (0,)),
    # locate
    Case(locate, (None, 100.0, 200.0, 0.0), why="not an RPC", raises=InputError, match="RPC"),
    Case(locate, (TOY, NAN, 200.0, 0.0), why="NaN row", raises=InputError, match="row"),
    Case(locate, (TOY, 100.0, 200.0, [0.0, 1.0, 2.0]), kwargs={}, why="broadcast heights", raises=None,
         check=lambda ll: ll[0].shape == (3,) and np.allclose(ll[0], 5.0)),
    Case(locate, (TOY, [1.0, 2.0], [1.0, 2.0, 3.0], 0.0), why="mismatched sizes", raises=InputError),
    Case(locate, (TOY, 1e6, 200.0, 0.0), why="row far outside the image", raises=InputError, match="valid range"),
    Case(locate, (TOY, 100.0, 200.0, 0.0), kwargs={"tolerance": -1.0}, why="negative tolerance", raises=InputError),
    Case(locate, (TOY, 100.0, 200.0, 0.0), kwargs={"max_iterations": 0}, why="no iterations", raises=InputError),
    Case(locate, (NO_LAT, 100.0, 200.0, 0.0), why="latitude does not enter the model",
         raises=DegenerateGeometryError, match="singular"),
    Case(locate, (CUBIC, 200.0, 200.0, 0.0), kwargs={"max_iterations": 2}, why="too few iterations",
         raises=ConvergenceError, match="did not reach"),
    Case(locate, (DIVERGE, 140.0, 200.0, 0.0), why="Newton leaves the model's range",
         raises=(ConvergenceError, DegenerateGeometryError)),
]


# ----------------------------------------------------------------------------- fitting, bias, stereo
def toy_ground(rows, cols, heights):
    """An affine 'sensor' with relief displacement along the rows."""
    return 5 + 1e-4 * np.asarray(cols), 45 - 1e-4 * np.asarray(rows) + 1e-7 * np.asarray(heights)


def nan_ground(rows, cols, heights):
    lon, lat = toy_ground(rows, cols, heights)
    return np.where(np.asarray(cols) > 50, np.nan, lon), lat


GRID = rpc_grid(toy_ground, (101, 101), [0.0, 250.0, 500.0, 750.0, 1000.0], step=20)
FIT = fit_rpc_points(*GRID)
ONE_GCP = ([98.0], [203.0], [5.0], [45.0], [0.0])
SHIFTED = BiasCorrectedRPC(TOY, "shift", (1.5,), (-2.0,))
STEREO_RIGHT = RPC(**OFFSETS, line_num_coeff=unit(2), line_den_coeff=unit(0),
                   samp_num_coeff=np.add(unit(1), np.r_[[0.0] * 3, 0.3, [0.0] * 16]), samp_den_coeff=unit(0))
PARALLAX = ([[100.0], [100.0]], [[200.0], [224.0]])

CASES += [
    # the grid and the fits
    Case(rpc_grid, ("not callable", (10, 10), [0.0]), why="sensor not callable", raises=InputError, match="callable"),
    Case(rpc_grid, (nan_ground, (101, 101), [0.0]), why="sensor returns NaN", raises=InputError, match="NaN"),
    Case(rpc_grid, (toy_ground, (101,), [0.0]), why="1-D image shape", raises=InputError, match="rows, cols"),
    Case(rpc_grid, (toy_ground, (101, 101), []), why="no height planes", raises=InputError),
    Case(rpc_grid, (toy_ground, (101, 101), [NAN]), why="NaN height", raises=InputError),
    Case(rpc_grid, (toy_ground, (101, 101), [0.0]), kwargs={"step": 0}, why="zero step", raises=InputError),
    Case(rpc_grid, (lambda r, c, h: 5.0, (11, 11), [0.0]), why="sensor returns one value", raises=InputError,
         match="two arrays"),
    Case(fit_rpc_points, tuple(g[:38] for g in GRID), why="38 points for 39 unknowns",
         raises=DegenerateGeometryError, match="39"),
    Case(fit_rpc_points, GRID[:4] + (np.zeros_like(GRID[4]),), why="one height only",
         raises=DegenerateGeometryError, match="height"),
    Case(fit_rpc_points, (GRID[0], GRID[1], np.full_like(GRID[2], 5.0), GRID[3], GRID[4]),
         why="no spread in longitude", raises=DegenerateGeometryError, match="lon"),
    Case(fit_rpc_points, (GRID[0][:-1],) + GRID[1:], why="mismatched sizes", raises=InputError, match="same number"),
    Case(fit_rpc_points, (np.r_[NAN, GRID[0][1:]],) + GRID[1:], why="NaN row", raises=InputError, match="NaN"),
    Case(fit_rpc_points, GRID, kwargs={"height_terms": "some"}, why="unknown option", raises=InputError),
    Case(fit_rpc_points, ("abc",) + GRID[1:], why="text rows", raises=InputError),
    Case(fit_rpc_points, rpc_grid(toy_ground, (101, 101), [0.0, 500.0, 1000.0], step=20), raises=None,
         why="three distinct heights: H³ dropped, not guessed", check=lambda f: f.dropped == ("H**3",)),
    Case(fit_rpc, (toy_ground, (101, 101), (1000.0, 0.0)), why="decreasing height range", raises=InputError,
         match="increasing"),
    Case(fit_rpc, (toy_ground, (101, 101), (0.0, 1000.0)), kwargs={"levels": 1}, why="one level",
         raises=InputError),
    Case(fit_rpc, (toy_ground, (101, 101), (0.0, INF)), why="inf height", raises=InputError),
    Case(fit_rpc, (toy_ground, (101, 101), (0.0, 1000.0)), kwargs={"step": 100}, why="grid too coarse",
         raises=DegenerateGeometryError, match="39"),
    Case(fit_rpc, (toy_ground, (101, 101), (0.0, 1000.0)), kwargs={"step": 20, "levels": 3, "height_terms": "all"},
         raises=None, why="the book's three planes, all terms: rank-deficient, reported",
         check=lambda f: f.rank[0] < 39 and np.isfinite(f.check_error)),
    Case(RPCFit, ("rpc", 39, (39, 39), (1.0, 1.0), 0.0, 0.0, (), 100), why="not an RPC", raises=InputError),
    # bias compensation
    Case(fit_bias, (TOY,) + ONE_GCP, kwargs={"model": "affine"}, why="1 GCP for the affine model",
         raises=DegenerateGeometryError, match="at least 3"),
    Case(fit_bias, (TOY, [], [], [], [], []), kwargs={"model": "shift"}, why="no GCP",
         raises=DegenerateGeometryError, match="at least 1"),
    Case(fit_bias, (TOY,) + tuple([v] * 5 for v in (98.0, 203.0, 5.0, 45.0, 0.0)), kwargs={"model": "poly2"},
         why="5 GCPs for the second-order model", raises=DegenerateGeometryError, match="at least 6"),
    Case(fit_bias, (TOY, [90.0, 100.0, 110.0], [190.0, 200.0, 210.0], [4.99, 5.0, 5.01], [44.99, 45.0, 45.01],
                    [0.0] * 3), kwargs={"model": "affine"}, why="collinear GCPs", raises=DegenerateGeometryError),
    Case(fit_bias, (TOY,) + ONE_GCP, kwargs={"model": "cubic"}, why="unknown model", raises=InputError),
    Case(fit_bias, (None,) + ONE_GCP, why="not an RPC", raises=InputError, match="RPC"),
    Case(fit_bias, (TOY, [NAN], [203.0], [5.0], [45.0], [0.0]), kwargs={"model": "shift"}, why="NaN measurement",
         raises=InputError),
    Case(fit_bias, (TOY, [98.0, 99.0], [203.0], [5.0], [45.0], [0.0]), kwargs={"model": "shift"},
         why="mismatched sizes", raises=InputError),
    Case(fit_bias, (TOY,) + ONE_GCP, kwargs={"model": "shift", "weights": [-1.0]}, why="negative weight",
         raises=InputError),
    Case(fit_bias, (TOY,) + ONE_GCP, kwargs={"model": "shift"}, raises=None, why="sign δ = RPC − measured",
         check=lambda b: b.line_coeff == (2.0,) and b.samp_coeff == (-3.0,)),
    Case(BiasCorrectedRPC, (TOY, "affine", (1.0,), (0.0, 0.0, 0.0)), why="too few coefficients",
         raises=InputError, match="3 finite"),
    Case(BiasCorrectedRPC, (TOY, "shift", (NAN,), (0.0,)), why="NaN coefficient", raises=InputError),
    Case(BiasCorrectedRPC, ("rpc", "shift", (0.0,), (0.0,)), why="not an RPC", raises=InputError),
    Case(BiasCorrectedRPC, (TOY, "spline", (0.0,), (0.0,)), why="unknown model", raises=InputError),
    Case(SHIFTED.correction, ([1.0, 2.0], [1.0, 2.0, 3.0]), why="mismatched sizes", raises=InputError),
    Case(SHIFTED.to_rpc_space, (NAN, 200.0), why="NaN row", raises=InputError),
    Case(SHIFTED.project, (5.0, 46.0, 0.0), why="ground point far outside", raises=InputError, match="valid range"),
    Case(BiasCorrectedRPC(TOY, "affine", (0.0, 80.0, 0.0), (0.0, 0.0, 0.0)).project, (5.0, 45.002, 0.0),
         why="a correction steeper than the image (no fixed point)", raises=ConvergenceError),
    Case(SHIFTED.locate, (98.5, 202.0, INF), why="inf height", raises=InputError),
    # stereo intersection (8.8.9)
    Case(intersect_rpc, ([TOY],) + PARALLAX, why="one image", raises=InputError, match="two or more"),
    Case(intersect_rpc, (TOY,) + PARALLAX, why="a single RPC, not a sequence", raises=InputError),
    Case(intersect_rpc, ([TOY, "x"],) + PARALLAX, why="not a model", raises=InputError),
    Case(intersect_rpc, ([TOY, TOY],) + PARALLAX, why="identical views: parallel rays",
         raises=DegenerateGeometryError, match="parallel"),
    Case(intersect_rpc, ([TOY, STEREO_RIGHT], [[100.0], [NAN]], [[200.0], [224.0]]), why="NaN row",
         raises=InputError),
    Case(intersect_rpc, ([TOY, STEREO_RIGHT], [[100.0, 1.0], [100.0, 1.0]], [[200.0], [224.0]]),
         why="rows and cols differ", raises=InputError),
    Case(intersect_rpc, ([TOY, STEREO_RIGHT], [100.0, 100.0, 100.0], [200.0, 224.0, 0.0]),
         why="three rows for two images", raises=InputError, match="images"),
    Case(intersect_rpc, ([TOY, STEREO_RIGHT],) + PARALLAX, kwargs={"max_iterations": 0}, why="no iterations",
         raises=InputError),
    Case(intersect_rpc, ([TOY, STEREO_RIGHT],) + PARALLAX, raises=None, why="a clean pair",
         check=lambda r: abs(r.height[0] - 500.0) < 1e-6),
    Case(intersect_rpc, ([SHIFTED, STEREO_RIGHT], [[98.5], [100.0]], [[202.0], [224.0]]), raises=None,
         why="a bias-corrected model", check=lambda r: abs(r.height[0] - 500.0) < 1e-6),
    Case(RPCIntersection, (np.zeros(2), np.zeros(2), np.zeros(3), np.zeros((2, 2, 2)), np.zeros(2), 1),
         why="inconsistent lengths", raises=InputError),
    # §8.18 conventional frame
    Case(conventional_frame_rpc, ([TOY], [(0, 0), (0, 90)], [(101, 101)], (0.0, 1000.0)),
         why="more offsets than RPCs", raises=InputError, match="one row per RPC"),
    Case(conventional_frame_rpc, (TOY, [(0, 0)], [(101, 101)], (0.0, 1000.0)), why="a single RPC",
         raises=InputError),
    Case(conventional_frame_rpc, ([TOY], [(NAN, 0)], [(101, 101)], (0.0, 1000.0)), why="NaN offset",
         raises=InputError),
    Case(conventional_frame_rpc, (["rpc"], [(0, 0)], [(101, 101)], (0.0, 1000.0)), why="not an RPC",
         raises=InputError),
    Case(conventional_frame_rpc, ([TOY], [(0, 0)], [(101, 101)], (0.0, 1000.0)), kwargs={"step": 200},
         why="grid too coarse", raises=DegenerateGeometryError, match="39"),
    Case(conventional_frame_rpc, ([TOY], [(0, 0)], [(1, 101)], (0.0, 1000.0)), why="a one-row micro-frame",
         raises=InputError),
]


@pytest.mark.parametrize("case", CASES, ids=lambda c: c.id)
def test_bad_input(case):
    check_case(case)


def test_convergence_error_carries_its_history():
    with pytest.raises(ConvergenceError) as info:
        locate(CUBIC, 200.0, 200.0, 0.0, max_iterations=2)
    assert len(info.value.history) == 3 and info.value.history[-1] > 1e-9
