"""photolib.pointcloud: PointCloud, LAS/LAZ round trips, units read from the CRS (Chapter 9)."""

import numpy as np
import pytest

from photolib.datasets import DataUnavailableError
from photolib.errors import InputError
from photolib.pointcloud import US_SURVEY_FOOT, PointCloud, read_las, read_lidar_data, unit_factor, write_las

pyproj = pytest.importorskip("pyproj")
pytest.importorskip("laspy")


def _cloud(n=200, seed=0, **kw):
    rng = np.random.default_rng(seed)
    xyz = np.column_stack([rng.uniform(500000, 500100, n), rng.uniform(4e6, 4e6 + 100, n), rng.uniform(100, 120, n)])
    nret = rng.integers(1, 4, n)
    return PointCloud(np.round(xyz, 3), intensity=rng.integers(0, 65535, n), classification=rng.choice([1, 2, 6], n),
                      return_number=np.minimum(rng.integers(1, 4, n), nret), number_of_returns=nret, **kw)


def test_round_trip_keeps_everything(tmp_path):
    crs = pyproj.CRS.from_epsg(32637)
    cloud = _cloud(crs=crs, rgb=np.tile([[10, 20, 30]], (200, 1)))
    write_las(tmp_path / "a.las", cloud, scales=[0.001] * 3, offsets=[500000, 4e6, 0])
    back = read_las(tmp_path / "a.las")
    np.testing.assert_allclose(back.xyz, cloud.xyz, atol=5e-4)
    for name in ("intensity", "classification", "return_number", "number_of_returns", "rgb"):
        np.testing.assert_array_equal(getattr(back, name), getattr(cloud, name))
    np.testing.assert_array_equal(back.scales, [0.001] * 3)
    np.testing.assert_array_equal(back.offsets, [500000, 4e6, 0])
    assert back.crs.to_epsg() == 32637 and back.source_unit == "metre" and back.unit_factor == 1.0


def test_round_trip_laz_and_feet(tmp_path):
    crs = pyproj.CRS.from_epsg(2903)  # US survey feet
    cloud = _cloud(crs=crs, unit_factor=US_SURVEY_FOOT, source_unit="US survey foot")
    write_las(tmp_path / "a.laz", cloud)
    back = read_las(tmp_path / "a.laz")
    assert back.source_unit == "US survey foot"
    np.testing.assert_allclose(back.xyz, cloud.xyz, atol=0.001)
    raw = read_las(tmp_path / "a.laz", to_metres=False)
    np.testing.assert_allclose(raw.xyz[:, :2] * US_SURVEY_FOOT, cloud.xyz[:, :2], atol=0.001)
    assert not raw.in_metres


def test_compound_crs_vertical_unit(tmp_path):
    crs = pyproj.CRS("EPSG:32637+8228")  # UTM metres + NAVD88 height (ft)
    cloud = _cloud(crs=crs, vertical_unit_factor=0.3048, vertical_unit="foot")
    write_las(tmp_path / "c.las", cloud)
    back = read_las(tmp_path / "c.las")
    assert back.vertical_unit_source == "vertical CRS" and back.vertical_unit_factor == pytest.approx(0.3048)
    np.testing.assert_allclose(back.xyz, cloud.xyz, atol=0.001)


def test_no_crs_needs_unit(tmp_path):
    write_las(tmp_path / "n.las", _cloud())
    with pytest.raises(InputError, match="never guessed"):
        read_las(tmp_path / "n.las")
    feet = read_las(tmp_path / "n.las", unit="us-ft")
    np.testing.assert_allclose(feet.xyz[:, 2], _cloud().xyz[:, 2] * US_SURVEY_FOOT, atol=1e-9)


def test_unit_contradicting_crs(tmp_path):
    write_las(tmp_path / "m.las", _cloud(crs=pyproj.CRS.from_epsg(32637)))
    with pytest.raises(InputError, match="contradicts"):
        read_las(tmp_path / "m.las", unit="foot")


def test_unit_factor_values():
    assert unit_factor("US survey foot")[1] == pytest.approx(1200 / 3937, rel=1e-15)
    assert unit_factor(9002) == ("foot", 0.3048)
    assert unit_factor("m") == ("metre", 1.0)


def test_nan_and_duplicates():
    with pytest.raises(InputError, match="NaN"):
        PointCloud([[0, 0, 0], [np.nan, 1, 1]])
    with pytest.raises(InputError, match="duplicate"):
        PointCloud([[0, 0, 0], [1, 1, 1], [0, 0, 0]], allow_duplicates=False)
    cloud = PointCloud([[0, 0, 0], [1, 1, 1], [0, 0, 0]])
    assert cloud.duplicates().tolist() == [2]
    with pytest.raises(InputError, match="duplicate"):
        cloud.check()
    assert cloud.subset(np.array([0, 1])).check().n == 2


def _real(name, **kw):
    try:
        return read_lidar_data(name, **kw)
    except DataUnavailableError:
        pytest.skip(f"real data absent: lidar/{name}")


def test_real_feet_files_in_metres():
    crop = _real("4_6_crop.las")
    assert crop.crs.to_epsg() == 2903 and crop.source_unit == "US survey foot"
    assert crop.vertical_unit_source == "VerticalUnitsGeoKey"
    raw = _real("4_6_crop.las", to_metres=False)
    # header extent (README): X 1639600–1639800 US ft, so 200 ft = 60.96 m of extent
    assert np.ptp(raw.xyz[:, 0]) == pytest.approx(199.98, abs=0.01)
    assert np.ptp(crop.xyz[:, 0]) == pytest.approx(199.98 * 1200 / 3937, abs=1e-3)
    assert set(np.unique(crop.classification)) == {1, 2}
    autzen = _real("autzen_trim.las")
    assert autzen.source_unit == "foot" and autzen.unit_factor == 0.3048 and len(autzen) == 110000
    raw = _real("autzen_trim.las", to_metres=False)
    np.testing.assert_allclose(autzen.xyz, raw.xyz * 0.3048, rtol=1e-12)


def test_real_files_without_a_linear_unit():
    for name in ("sample_c.las", "lone-star.laz"):
        with pytest.raises(InputError, match="unit"):
            _real(name)


def test_voxel_downsample_matches_a_plain_dictionary_of_voxels():
    """Each occupied voxel gives the mean of its points (checked against a pure-Python grouping)."""
    from collections import defaultdict

    from photolib.pointcloud import voxel_downsample
    P = np.random.default_rng(5).uniform(-3, 7, (2000, 3))
    groups = defaultdict(list)
    lo = P.min(axis=0)
    for p in P:
        groups[tuple(np.floor((p - lo) / 0.8).astype(int))].append(p)
    expected = np.array([np.mean(groups[k], axis=0) for k in sorted(groups)])
    np.testing.assert_allclose(voxel_downsample(P, 0.8), expected, rtol=0, atol=1e-12)
