"""Chapter 9, §9.11 adapters (photolib/book/ch09_segmentation.py) and textbook/ch09_segmentation.toml.

(9.11.1) is checked independently here (numpy: the plane's points satisfy it; a wrong printed
formula is rejected); the minimal-sample counts against an independent count of constraints;
every entry of the fragment keeps its recorded status.
"""

import math

import numpy as np

from photolib.book import ch09_segmentation as c
from photolib.book.textbook import load_chapter
from photolib.book.verify import check_example, check_formula

RHS = "X*cos(alpha)*cos(beta) + Y*sin(alpha)*cos(beta) + Z*sin(beta)"


def test_hough_plane_formula_and_wrong_variants():
    assert c.hough_plane({"printed_rhs": RHS})["printed_equals_derived"]
    # swapped sin/cos in the Y term, or a missing cos β: rejected
    assert not c.hough_plane({"printed_rhs": RHS.replace("Y*sin(alpha)*cos(beta)", "Y*cos(alpha)*sin(beta)")})[
        "printed_equals_derived"]
    assert not c.hough_plane({"printed_rhs": "X*cos(alpha) + Y*sin(alpha) + Z*sin(beta)"})["printed_equals_derived"]


def test_hough_plane_numeric_independent():
    # points of the plane through (1, 2, 3) with normal from α = 40°, β = 25° satisfy (9.11.1) with p = n·(1, 2, 3)
    a, b = math.radians(40), math.radians(25)
    n = np.array([math.cos(a) * math.cos(b), math.sin(a) * math.cos(b), math.sin(b)])
    t = np.cross(n, [0, 0, 1.0])
    s = np.cross(n, t)
    pts = np.array([1.0, 2, 3]) + np.outer([0.3, -2, 5], t) + np.outer([1, 4, -0.5], s)
    lhs = pts[:, 0] * math.cos(a) * math.cos(b) + pts[:, 1] * math.sin(a) * math.cos(b) + pts[:, 2] * math.sin(b)
    np.testing.assert_allclose(lhs, n @ [1.0, 2, 3], atol=1e-12)


def test_minimal_samples_match_parameter_counting():
    r = c.minimal_samples({"seed": 5})
    # independent: parameters of each shape / conditions per point
    expected = {"line": (4, 2), "plane": (3, 1), "sphere": (4, 1), "cylinder": (5, 1)}
    for shape, (dof, per) in expected.items():
        assert r[f"{shape}_parameters"] == dof
        assert r[f"{shape}_points"] == math.ceil(dof / per)


def test_centring_and_step_statements():
    r = c.hough_centring({"seed": 0, "size": 10.0, "offset": [1e5, 1e5, 0.0]})
    assert r["p_range"] == "smaller" and r["p_range_centred"] <= 2 * math.sqrt(3) * 10.0
    # without an offset the centroid is near the cube's centre and the raw range is still larger
    r0 = c.hough_centring({"seed": 0, "size": 10.0, "offset": [0.0, 0.0, 0.0]})
    assert r0["p_range_raw"] > r0["p_range_centred"]


def fragment_entries():
    chapter = load_chapter(9)
    examples = [e for e in chapter.examples if e.id.startswith("9.11")]
    formulas = [f for f in chapter.formulas if f.compute.startswith("photolib.book.ch09_segmentation:")]
    return examples, formulas


def test_fragment_entries_keep_their_status():
    examples, formulas = fragment_entries()
    assert len(examples) >= 6 and len(formulas) == 1
    for e in examples:
        for row in check_example(e):
            assert row.ok, f"{e.id}/{row.quantity}: {row.computed} vs {row.book} ({row.status})"
    for f in formulas:
        assert check_formula(f).ok, f.id
