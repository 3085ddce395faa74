"""Bad-input catalogue for photolib.rpc: NaN/inf, wrong types, shapes, files and ranges."""

import numpy as np
import pytest

from catalogue import INF, NAN, Case, check_case
from photolib.errors import ConvergenceError, DegenerateGeometryError, InputError
from photolib.rpc import RPC, locate, project


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


@pytest.mark.parametrize("case", CASES, ids=lambda c: c.id)
def test_bad_input(case):
    check_case(case)


def test_convergence_error_carries_its_history():
    with pytest.raises(ConvergenceError) as info:
        locate(CUBIC, 200.0, 200.0, 0.0, max_iterations=2)
    assert len(info.value.history) == 3 and info.value.history[-1] > 1e-9
