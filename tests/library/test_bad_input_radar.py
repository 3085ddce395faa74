"""Bad-input catalogue for photolib.radar and photolib.derivations.radar (Chapter 8, §8.9–8.13)."""

import numpy as np
import pytest

from catalogue import INF, NAN, Case, check_case
from photolib import radar as r
from photolib.datasets import DataUnavailableError
from photolib.derivations import radar as dr
from photolib.errors import DegenerateGeometryError, InputError

S, I3 = np.array([0.0, 0.0, 8000.0]), np.eye(3)
M = np.array([0.0, 6000.0, 100.0])
G = r.InsarGeometry()
FLAT = np.zeros((6, 7))
IFG = r.simulate_interferogram(FLAT, 25.0)

CASES = [
    # §8.9
    Case(r.slant_range, ([1.0, NAN], 850e3, 7.8), raises=InputError, match="NaN", why="NaN coordinate"),
    Case(r.slant_range, (1.0, -5.0, 7.8), raises=InputError, why="negative near range"),
    Case(r.slant_range, (-1e6, 10.0, 1.0), raises=InputError, match="non-positive", why="range below zero"),
    Case(r.slant_range, ("a", 10.0, 1.0), raises=InputError, why="a string"),
    Case(r.range_coordinate, ([], 10.0, 1.0), raises=InputError, match="empty", why="empty"),
    Case(r.range_coordinate, (5.0, 10.0, 0.0), raises=InputError, why="zero scale"),
    # §8.11
    Case(r.range_vector, (INF, 0.3), raises=InputError, why="inf range"),
    Case(r.range_vector, (100.0, 30.0), raises=InputError, match="radians", why="degrees"),
    Case(r.range_vector, ([1.0, 2.0], [0.1, 0.2, 0.3]), raises=InputError, match="broadcast", why="mismatched sizes"),
    Case(r.range_vector, (1.0, 0.1, "up"), raises=InputError, match="side", why="unknown side"),
    Case(r.radar_point, (S[:2], I3, 100.0, 0.3), raises=InputError, match="3-vector", why="wrong shape of S"),
    Case(r.radar_point, (S, 2 * I3, 100.0, 0.3), raises=InputError, match="rotation", why="A not a rotation"),
    Case(r.radar_point, (S, I3, 0.0, 0.3), raises=InputError, why="zero range"),
    Case(r.radar_project, (S, I3, S), raises=DegenerateGeometryError, why="point at the emission point"),
    Case(r.radar_project, (S, I3, np.zeros((2, 2))), raises=InputError, why="wrong shape of M"),
    Case(r.radar_project, (S, I3, M), raises=None, why="plain point",
         check=lambda t: abs(t[0] - np.hypot(6000.0, 7900.0)) < 1e-9 and abs(t[2]) < 1e-12),
    Case(r.look_angle_from_height, (S, I3, 5000.0, 0.0), raises=DegenerateGeometryError, match="does not reach",
         why="range shorter than the height difference"),
    Case(r.look_angle_from_height, (S, np.array([[0, 0, 1.0], [0, 1, 0], [-1, 0, 0]]), 9000.0, 0.0),
         raises=DegenerateGeometryError, match="horizontal", why="emission plane horizontal"),
    Case(r.look_angle_from_height, (S, I3, 10000.0, 0.0), {"method": "secant"}, raises=InputError, why="unknown method"),
    Case(r.look_angle_from_height, (S, I3, 10000.0, 0.0), {"root": "both"}, raises=InputError, why="unknown root"),
    Case(r.look_angle_from_height, (S, I3, 10000.0, 0.0), {"method": "newton", "phi0": -0.6},
         raises=DegenerateGeometryError, match="mirror", why="Newton started on the mirror side"),
    Case(r.look_angle_from_height, (S, I3, 10000.0, NAN), raises=InputError, why="NaN height"),
    Case(r.look_angle_vertical, (9000.0, 8000.0), raises=DegenerateGeometryError, why="H > D"),
    Case(r.look_angle_vertical, (0.0, 8000.0), raises=InputError, why="H = 0"),
    Case(r.layover_mask, ([],), raises=InputError, why="empty"),
    Case(r.layover_mask, ([1.0, 2.0],), {"axis": 3}, raises=InputError, match="axis", why="bad axis"),
    Case(r.layover_mask, ([1.0, NAN],), raises=InputError, why="NaN range"),
    # §8.12
    Case(r.RadarStereo, (np.zeros(3), np.zeros(2), 0.0, None), raises=None, why="plain record",
         check=lambda x: x.misclosure == 0.0),
    Case(r.radar_stereo, (S, I3, 10000.0, S, I3, 10000.0), raises=DegenerateGeometryError, match="base",
         why="zero base"),
    Case(r.radar_stereo, (S, I3, 10000.0, S + [0, 0, 1000.0], I3, NAN), raises=InputError, why="NaN range"),
    Case(r.radar_stereo, (S, I3, 10000.0, S + [0, 0, 1000.0], I3, 10900.0), {"phi0": [0.1, 0.2, 0.3]},
         raises=InputError, match="two angles", why="three start angles"),
    Case(r.radar_stereo, (S, I3, 10000.0, S + [0, 0, 1000.0], I3, 100.0), raises=DegenerateGeometryError,
         why="second range cannot reach the datum"),
    Case(r.radar_intersection, (S[None], I3[None], [10000.0]), raises=InputError, match="2 images",
         why="too few images"),
    Case(r.radar_intersection, (np.stack([S, S + 1]), np.stack([I3, I3]), [1.0, 2.0, 3.0]), raises=InputError,
         why="mismatched sizes"),
    Case(r.radar_intersection, (np.stack([S, S]), np.stack([I3, I3]), [10000.0, 10000.0]),
         raises=DegenerateGeometryError, why="both images from one point"),
    # §8.13
    Case(r.insar_look_angle, (1000.0, 2000.0, 100.0, 0.0), raises=DegenerateGeometryError, why="inconsistent ranges"),
    Case(r.insar_look_angle, (1000.0, 1000.0, 0.0, 0.0), raises=InputError, why="zero baseline"),
    Case(r.insar_look_angle_from_difference, (1000.0, 500.0, 100.0, 0.0), raises=DegenerateGeometryError,
         why="|ΔD| > B"),
    Case(r.insar_look_angle_from_difference, (1000.0, NAN, 100.0, 0.0), raises=InputError, why="NaN ΔD"),
    Case(r.insar_height, (-1.0, 1000.0, 0.3), raises=InputError, why="negative H"),
    Case(r.range_difference_to_phase, (1.0, 0.05, "twice"), raises=InputError, match="passes", why="unknown passes"),
    Case(r.range_difference_to_phase, (1.0, 0.0), raises=InputError, why="zero wavelength"),
    Case(r.phase_to_range_difference, ([INF], 0.05), raises=InputError, why="inf phase"),
    Case(r.perpendicular_baseline, (-250.0, 0.3, 0.4), raises=InputError, why="negative baseline"),
    Case(r.height_precision, (858e3, 0.056, 0.4, 250.0, -0.1), raises=InputError, why="negative noise"),
    Case(r.height_precision, (858e3, 0.056, 0.4, 0.0, 0.1), raises=InputError, why="zero baseline"),
    Case(r.height_of_ambiguity, (858e3, 0.056, 0.4, 250.0, "x"), raises=InputError, why="unknown passes"),
    Case(r.critical_baseline, (850e3, 0.056, 1.6, 9.37), raises=InputError, match="π/2", why="look angle ≥ 90°"),
    Case(r.critical_baseline, (850e3, 0.056, 0.4, 0.0), raises=InputError, why="zero resolution"),
    Case(r.range_resolution, (0.0,), raises=InputError, why="zero bandwidth"),
    Case(r.wrap_phase, ("x",), raises=InputError, why="a string"),
    Case(r.unwrap_phase_ls, (np.zeros(5),), raises=InputError, match="2-D", why="1-D input"),
    Case(r.unwrap_phase_ls, (np.full((3, 3), NAN),), raises=InputError, why="NaN phase"),
    Case(r.unwrap_phase_ls, (np.zeros((1, 5)),), raises=InputError, why="one row"),
    Case(r.InsarGeometry, (), {"look_angle": 23.0}, raises=InputError, why="look angle in degrees"),
    Case(r.InsarGeometry, (), {"B": -1.0}, raises=InputError, why="negative baseline"),
    Case(r.InsarGeometry, (), {"passes": "triple"}, raises=InputError, why="unknown passes"),
    Case(r.Interferogram, (FLAT, FLAT, FLAT, FLAT, G, FLAT.astype(bool)), raises=None, why="plain record",
         check=lambda x: x.wrapped.shape == (6, 7)),
    Case(r.simulate_interferogram, (np.zeros(5), 25.0), raises=InputError, match="2-D", why="1-D heights"),
    Case(r.simulate_interferogram, (FLAT, 0.0), raises=InputError, why="zero pixel size"),
    Case(r.simulate_interferogram, (FLAT, 25.0), {"geometry": "envisat"}, raises=InputError, why="wrong geometry type"),
    Case(r.simulate_interferogram, (FLAT + 1e6, 25.0), raises=InputError, match="above", why="terrain above the sensor"),
    Case(r.simulate_interferogram, (FLAT, 25.0), {"sigma_phase": -1.0}, raises=InputError, why="negative noise"),
    Case(r.insar_heights, (IFG.wrapped, IFG.D1[:3], G, ([0], [0], [0.0])), raises=InputError, why="mismatched sizes"),
    Case(r.insar_heights, (IFG.wrapped, IFG.D1, G, ([0], [99], [0.0])), raises=InputError, match="outside",
         why="reference outside the grid"),
    Case(r.insar_heights, (IFG.wrapped, IFG.D1, G, ([0.5], [0], [0.0])), raises=InputError, why="fractional reference"),
    Case(r.insar_heights, (IFG.wrapped, IFG.D1, G, 5), raises=InputError, why="malformed reference"),
    Case(r.insar_heights, (IFG.wrapped, IFG.D1, G, ([0], [0], [0.0])), raises=None, why="flat ground",
         check=lambda h: float(np.abs(h).max()) < 1e-6),
    Case(r.load_dem_local, (), {"window": (0, 0, 1, 5)}, raises=InputError, why="window of one row"),
    Case(r.load_dem_local, (), {"window": "all"}, raises=InputError, why="malformed window"),
    Case(r.load_dem_local, ("/no/such/dem.tif",), raises=DataUnavailableError, why="missing file"),
    # derivations
    Case(dr.look_sign, ("up",), raises=InputError, why="unknown side"),
    Case(dr.radar_range_vector_symbolic, (3,), raises=InputError, why="side not a string"),
    Case(dr.radar_point_symbolic, ("both",), raises=InputError, why="unknown side"),
    Case(dr.radar_height_model, ("x",), raises=InputError, why="unknown side"),
    Case(dr.radar_stereo_model, ("x",), raises=InputError, why="unknown side"),
    Case(dr.range_doppler_model, (), raises=None, why="no input", check=lambda m: len(m.residuals) == 2),
    Case(dr.insar_relations, (), raises=None, why="no input", check=lambda d: d["dh_ratio_limit"] == 1),
]


@pytest.mark.parametrize("case", CASES, ids=lambda c: c.id)
def test_bad_input(case):
    if case.function is r.load_dem_local and case.raises is DataUnavailableError:
        pytest.importorskip("rasterio")
    check_case(case)
