"""Book adapters of Sementsov's thesis (theory part): the claims made in the notes of
textbook/ch11_sementsov.toml beyond what the generic textbook test checks."""

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from photolib.book import sementsov_theory as book
from photolib.book.textbook import load_chapter

RHO = 180 / np.pi * 3600


def test_corrected_forms_of_the_errata_hold():
    assert book.corrected_formula_check({"item": "18"})["printed_equals_derived"]
    assert book.corrected_formula_check({"item": "2"})["printed_equals_derived"]


def test_table4_with_the_printed_coefficient_gives_2_16():
    inputs = load_chapter(11).example("sementsov-table-4").inputs
    printed = book.table4_as_printed(inputs)
    exact = book.table4(inputs)
    assert round(printed["l_XY at 20 m"], 2) == 2.16 and round(exact["l_XY at 20 m"], 2) == 2.15
    assert round(printed["l_XY at 2 m"], 2) == round(exact["l_XY at 2 m"], 2) == 0.22


def _independent_rays(cal, xy, sign):
    """Table B.1 rays written out from (4) directly (no library code)."""
    x, y = xy[:, 0] - cal["x0"], xy[:, 1] - cal["y0"]
    r2 = x * x + y * y
    rad = cal["k1"] * r2 + cal["k2"] * r2**2 + cal["k3"] * r2**3
    sx = -x * rad - cal["P1"] * (2 * x * x + r2) - 2 * cal["P2"] * x * y
    sy = -y * rad - cal["P2"] * (2 * y * y + r2) - 2 * cal["P1"] * x * y
    v = np.column_stack([x + sign * sx, y + sign * sy, np.full(len(x), -cal["f"])])
    return v / np.linalg.norm(v, axis=1, keepdims=True)


@pytest.mark.parametrize("reading,sign", [("correction", 1.0), ("distortion", -1.0)])
def test_b1_proxy_agrees_with_an_independent_computation(reading, sign):
    params = book.table_b1_parameters()
    got = book.b1_bundle_comparison(reading=reading)
    gx, gy = np.meshgrid(np.linspace(-2406, 2406, 25), np.linspace(-1582, 1582, 17))
    xy = np.column_stack([gx.ravel(), gy.ravel()])
    ref = _independent_rays(params["stars"], xy, sign)
    for cal in ("spatial", "planar"):
        v = _independent_rays(params[cal], xy, sign)
        rot, _ = Rotation.align_vectors(ref, v)
        d = np.linalg.norm(ref - rot.apply(v), axis=1)
        assert np.isclose(got[cal].rms_arcsec, np.sqrt(np.mean(d**2)) * RHO, rtol=1e-9)
        assert np.isclose(got[cal].max_arcsec, d.max() * RHO, rtol=1e-9)


def _independent_comparison(nodes=(25, 17), sign=1.0):
    params = book.table_b1_parameters()
    gx, gy = np.meshgrid(np.linspace(-2406, 2406, nodes[0]), np.linspace(-1582, 1582, nodes[1]))
    xy = np.column_stack([gx.ravel(), gy.ravel()])
    ref = _independent_rays(params["stars"], xy, sign)
    out = {}
    for cal in ("spatial", "planar"):
        v = _independent_rays(params[cal], xy, sign)
        rot, _ = Rotation.align_vectors(ref, v)
        d = np.linalg.norm(ref - rot.apply(v), axis=1)
        out[cal] = (np.sqrt(np.mean(d**2)) * RHO, d.max() * RHO)
    return out


def test_b1_proxy_values_quoted_in_the_notes():
    """The numbers in the notes of sementsov-table-7 / -figures-c, from the independent computation."""
    cor, dis = _independent_comparison(), _independent_comparison(sign=-1.0)
    assert [round(cor[c][0], 1) for c in ("spatial", "planar")] == [75.0, 83.4]
    assert [round(dis[c][0], 1) for c in ("spatial", "planar")] == [196.6, 123.2]
    assert [round(cor[c][1], 1) for c in ("spatial", "planar")] == [196.3, 147.4]
    runs = [_independent_comparison(nodes) for nodes in ((13, 9), (25, 17), (49, 33), (97, 65))]
    spatial, planar = [r["spatial"][0] for r in runs], [r["planar"][0] for r in runs]
    assert (round(min(spatial), 1), round(max(spatial), 1)) == (72.3, 78.5)
    assert (round(min(planar), 1), round(max(planar), 1)) == (82.9, 84.0)


def test_experiment_count_reason_adds_up():
    ex = load_chapter(11).example("sementsov-experiment-count")
    counts = ex.inputs["counts"]
    assert sum(counts.values()) == 1240 and 1740 - 1240 == 500
    assert sum(counts.values()) - counts["§3.2 control sets without offset: 4 series × 20"] == 1160
