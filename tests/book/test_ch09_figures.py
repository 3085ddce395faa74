"""Chapter 9 figures (photolib/book/figures/ch09_lidar.py): each returns a closed matplotlib Figure.

Synthetic inputs always run; the real-data figures (lone-star.laz, sample_c.las, 4_6_crop.las)
skip with the reason when ../shared/data (or $PHOTOLIB_DATA) is absent. Expected values come
from independent formulas (numpy trigonometry), the book (Table 9.1: 25 cm at 1000 m), synthetic
ground truth, the files' CRS and the targets of the data README / benchmarks (≤ 7 % ground error).
"""

import numpy as np
import pytest

plt = pytest.importorskip("matplotlib.pyplot")
from matplotlib.figure import Figure  # noqa: E402

from photolib import datasets  # noqa: E402
from photolib.book.figures import ch09_lidar as figs  # noqa: E402


def closed_figure(fig):
    return isinstance(fig, Figure) and fig.number not in plt.get_fignums()


def real(fn, *args, **kwargs):
    try:
        return fn(*args, **kwargs)
    except datasets.DataUnavailableError as missing:
        pytest.skip(f"real data absent (../shared/data or PHOTOLIB_DATA): {missing}")


def test_als_geometry_swath_and_footprint():
    fig, n = figs.als_geometry(H=1000.0, fov_deg=60.0, divergence=0.25e-3)
    assert closed_figure(fig)
    assert n["swath_m"] == pytest.approx(2000 * np.tan(np.radians(30)), abs=1e-3)
    assert n["swath_check_m"] == pytest.approx(n["swath_m"], abs=1e-3)        # the georeferenced fan
    assert n["footprint_nadir_m"] == pytest.approx(0.25, abs=1e-3)              # Table 9.1: 25 cm at 1000 m
    g, phi = 0.25e-3, np.radians(30)
    assert n["footprint_edge_across_m"] == pytest.approx(1000 * (np.tan(phi + g / 2) - np.tan(phi - g / 2)), abs=1e-3)


def test_laser_line_scanner_profile_within_a_millimetre():
    fig, n = figs.laser_line_scanner(seed=5, sigma_xy=0.001)
    assert closed_figure(fig)
    assert n["points"] == 40 and n["max_error_mm"] < 1.0


def test_laser_line_scanner_noise_free_is_exact():
    _, n = figs.laser_line_scanner(seed=1, sigma_xy=0.0)
    assert n["max_error_mm"] < 1e-3


def test_voxel_downsample_centroids():
    pts = np.array([[0.1, 0.1, 0.1], [0.3, 0.1, 0.1], [1.5, 0.2, 0.2], [1.7, 0.4, 0.2]])
    out = figs.voxel_downsample(pts, 1.0)
    assert np.allclose(out, [[0.2, 0.1, 0.1], [1.6, 0.3, 0.2]])


def test_icp_figure_on_synthetic_stations_recovers_the_offset():
    source, target = figs.synthetic_stations()
    fig, n = figs.icp_before_after(source, target, offset=figs.ICP_OFFSET)
    assert closed_figure(fig)
    assert n["converged"] and n["rotation_error_deg"] < 0.05 and n["translation_error_mm"] < 5.0
    assert n["median_after_mm"] < n["median_before_mm"]


def test_roof_figure_on_a_synthetic_building():
    xyz, cls = figs.synthetic_building()
    fig, n = figs.roof_segments(xyz, cls)
    assert closed_figure(fig)
    assert n["roofs"] == 2 and n["recall_pct"] > 95 and n["precision_pct"] > 95


def test_dtm_figure_on_a_synthetic_classified_cloud():
    fig, n = figs.dtm_from_classified(figs.synthetic_classified_cloud())
    assert closed_figure(fig)
    assert n["unit"] == "metre" and n["total_pct"] < 2.0 and n["p95_abs_m"] < 0.1


# --------------------------------------------------------------------------------------- real data
def test_icp_figure_on_lone_star():
    pytest.importorskip("laspy")
    source, target = real(figs.lone_star_stations, voxel=0.2)
    fig, n = figs.icp_before_after(source, target, offset=figs.ICP_OFFSET)
    assert closed_figure(fig)
    assert n["converged"] and n["rotation_error_deg"] < 0.01 and n["translation_error_mm"] < 1.0


def test_roof_figure_on_sample_c():
    pytest.importorskip("laspy")
    from photolib.pointcloud import read_lidar_data
    cloud = real(read_lidar_data, "sample_c.las", unit="metre")
    fig, n = figs.roof_segments(cloud.xyz, cloud.classification)
    assert closed_figure(fig)
    assert n["points"] == 14408 and n["roofs"] >= 1 and n["recall_pct"] > 90 and n["precision_pct"] > 90


def test_dtm_figure_on_4_6_crop_states_the_unit():
    pytest.importorskip("laspy")
    from photolib.pointcloud import read_lidar_data
    cloud = real(read_lidar_data, "4_6_crop.las", to_metres=False)
    fig, n = figs.dtm_from_classified(cloud, name="4_6_crop.las: ")
    assert closed_figure(fig)
    assert n["unit"] == "US survey foot"                                  # EPSG:2903
    assert "US survey foot" in fig._suptitle.get_text()
    assert n["total_pct"] <= 7.0                                          # the target of the data README
