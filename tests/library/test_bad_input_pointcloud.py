"""Bad-input catalogue for photolib.pointcloud: NaN and duplicate points, units never guessed."""

import numpy as np
import pytest

from catalogue import INF, NAN, Case, check_case
from photolib import pointcloud as pc
from photolib.datasets import DataUnavailableError
from photolib.errors import InputError

pytest.importorskip("laspy")

_OK = [[0.0, 0, 0], [1, 1, 1]]


def _no_crs_file(tmp):
    path = tmp / "nocrs.las"
    pc.write_las(path, pc.PointCloud(_OK))
    return path


def _not_las(tmp):
    path = tmp / "text.las"
    path.write_text("not a LAS file")
    return path


CASES = [
    Case(pc.voxel_downsample, ([[0, 0, NAN]], 1.0), raises=InputError, match="NaN", why="NaN coordinate"),
    Case(pc.voxel_downsample, ([[0.0, 0.0]], 1.0), raises=InputError, why="2-D points"),
    Case(pc.voxel_downsample, (_OK, 0.0), raises=InputError, match="positive", why="zero voxel size"),
    Case(pc.voxel_downsample, (_OK, NAN), raises=InputError, match="positive", why="NaN voxel size"),
    Case(pc.voxel_downsample, ([[0.0, 0, 0], [1e12, 1e12, 1e12]], 1e-3), raises=InputError, match="too small",
         why="a grid too fine to index"),
    Case(pc.voxel_downsample, ([[0.0, 0, 0], [0.0, 0, 0]], 1.0), raises=None,
         check=lambda r: r.shape == (1, 3) and np.all(r == 0), why="duplicate points: one voxel"),
    Case(pc.PointCloud, ([[0, 0, NAN]],), raises=InputError, match="NaN", why="NaN coordinate"),
    Case(pc.PointCloud, ([[0, 0, INF]],), raises=InputError, match="NaN or inf", why="inf coordinate"),
    Case(pc.PointCloud, (np.zeros((4, 2)),), raises=InputError, match="shape", why="two columns"),
    Case(pc.PointCloud, ("xyz",), raises=InputError, why="a string"),
    Case(pc.PointCloud, ([[0, 0, 0], [0, 0, 0]],), {"allow_duplicates": False}, raises=InputError,
         match="duplicate", why="duplicate points refused"),
    Case(pc.PointCloud, (_OK,), {"classification": [1]}, raises=InputError, why="attribute of another length"),
    Case(pc.PointCloud, (_OK,), {"classification": [1, 300]}, raises=InputError, why="class code > 255"),
    Case(pc.PointCloud, (_OK,), {"return_number": [3, 1], "number_of_returns": [2, 1]}, raises=InputError,
         why="return number above number of returns"),
    Case(pc.PointCloud, (_OK,), {"unit_factor": 0.0}, raises=InputError, why="zero unit factor"),
    Case(pc.PointCloud, (np.zeros((0, 3)),), raises=None, check=lambda c: len(c) == 0, why="empty cloud is valid"),
    Case(pc.PointCloud([[0, 0, 0.0], [0, 0, 0]]).check, (), raises=InputError, match="duplicate",
         why="check() finds duplicates"),
    Case(pc.PointCloud([[0, 0, 0.0], [0, 0, 1]]).duplicates, (), raises=None, check=lambda d: len(d) == 0,
         why="no duplicates"),
    Case(pc.PointCloud(_OK).subset, (np.array([True]),), raises=InputError, why="mask of another length"),
    Case(pc.PointCloud(_OK).subset, ([5],), raises=InputError, why="index out of range"),
    Case(pc.unit_factor, ("furlong",), raises=InputError, why="unknown unit name"),
    Case(pc.unit_factor, (-1.0,), raises=InputError, why="negative factor"),
    Case(pc.unit_factor, (NAN,), raises=InputError, why="NaN factor"),
    Case(pc.read_las, ("/no/such/file.las",), raises=InputError, match="no such", why="missing file"),
    Case(pc.read_las, (3,), raises=InputError, why="not a path"),
    Case(pc.write_las, ("/tmp/x.las", np.zeros((2, 3))), raises=InputError, why="an array, not a PointCloud"),
    Case(pc.write_las, ("/no/such/dir/x.las", pc.PointCloud(_OK)), raises=InputError, why="missing folder"),
    Case(pc.read_lidar_data, ("",), raises=InputError, why="empty name"),
    Case(pc.read_lidar_data, ("no-such.las",), raises=DataUnavailableError, why="missing data file"),
]


@pytest.mark.parametrize("case", CASES, ids=lambda c: c.id)
def test_bad_input(case):
    check_case(case)


def test_unit_never_guessed(tmp_path):
    check_case(Case(pc.read_las, (_no_crs_file(tmp_path),), raises=InputError, match="never guessed",
                    why="LAS without CRS: unit not determined"))


def test_not_a_las_file(tmp_path):
    check_case(Case(pc.read_las, (_not_las(tmp_path),), raises=InputError, match="not a readable",
                    why="text file"))


def test_tiny_scale_overflows(tmp_path):
    check_case(Case(pc.write_las, (tmp_path / "o.las", pc.PointCloud([[0, 0, 0.0], [1e6, 0, 0]])),
                    {"scales": [1e-9] * 3}, raises=InputError, match="fit", why="coordinates overflow"))
