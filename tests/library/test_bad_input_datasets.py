"""Bad-input catalogue for photolib.datasets: missing data, empty settings, wrong types."""

import numpy as np
import pytest

from catalogue import Case, check_case
from photolib import datasets
from photolib.errors import InputError


@pytest.fixture
def no_data(monkeypatch, tmp_path):
    monkeypatch.setenv("PHOTOLIB_DATA", str(tmp_path / "nowhere"))


def test_missing_data_is_named(no_data):
    for function in (datasets.middlebury_cones, lambda: datasets.data_path("stereo", "cones")):
        with pytest.raises(datasets.DataUnavailableError, match="PHOTOLIB_DATA"):
            function()


def test_empty_variable(monkeypatch):
    monkeypatch.setenv("PHOTOLIB_DATA", " ")
    with pytest.raises(InputError, match="empty"):
        datasets.data_dir()


def test_data_dir_follows_the_variable(monkeypatch, tmp_path):
    monkeypatch.setenv("PHOTOLIB_DATA", str(tmp_path))
    assert datasets.data_dir() == tmp_path


def test_not_an_image(tmp_path):
    text = tmp_path / "notes.png"
    text.write_text("not an image")
    with pytest.raises(InputError, match="not an image"):
        datasets.read_image(text)


def test_float_tiff_keeps_values(tmp_path):
    PIL = pytest.importorskip("PIL.Image")
    values = np.arange(12, dtype=np.float32).reshape(3, 4) / 4
    PIL.fromarray(values, mode="F").save(tmp_path / "d.tif")
    np.testing.assert_array_equal(datasets.read_image(tmp_path / "d.tif"), values)


CASES = [
    Case(datasets.data_path, (), why="no component", raises=InputError),
    Case(datasets.data_path, ("stereo", 3), why="a component is not a string", raises=InputError),
    Case(datasets.data_path, ("no-such-folder-here",), why="missing file", raises=datasets.DataUnavailableError),
    Case(datasets.read_image, ("/no/such/file.png",), why="missing file", raises=datasets.DataUnavailableError),
    Case(datasets.read_image, (np.zeros((2, 2)),), why="an array instead of a path", raises=InputError),
    Case(datasets.data_dir, (), raises=None, check=lambda p: p.name == "data" or p.exists(), why="default location"),
    Case(datasets.motorcycle, (), raises=None, why="bundled pair: known disparities are finite and positive",
         check=lambda pair: bool(np.all(pair.disparity[pair.evaluate] > 0))),
    Case(datasets.StereoBenchmark, ("x", np.zeros((3, 4)), np.zeros((3, 5)), np.zeros((3, 4)),
                                    np.ones((3, 4), bool), 2), why="images of different sizes", raises=InputError),
    Case(datasets.StereoBenchmark, ("x", np.full((3, 4), np.nan), np.zeros((3, 4)), np.zeros((3, 4)),
                                    np.ones((3, 4), bool), 2), why="NaN pixels", raises=InputError),
    Case(datasets.middlebury_cones, (), raises=(datasets.DataUnavailableError, type(None)), why="present or named"),
]


@pytest.mark.parametrize("case", CASES, ids=lambda c: c.id)
def test_bad_input(case):
    if case.function is datasets.middlebury_cones:
        try:
            pair = datasets.middlebury_cones()
        except datasets.DataUnavailableError:
            pytest.skip("real data absent (../shared/data or PHOTOLIB_DATA): the missing case is tested above")
        assert np.nanmax(pair.disparity) == 55 and pair.evaluate.any()
        return
    check_case(case)
