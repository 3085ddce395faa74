"""§3.5/§3.7 algorithms of photolib.triangulation_layouts on blocks built here (no book layer).

Expected values: the counting formulas (3.5.20)/(3.5.21) evaluated by hand for the geometry of
each test block, the per-point image counts of a layout laid out by hand, and tolerance
arithmetic with the Instruction's numbers typed from the book (§3.7).
"""

import numpy as np
import pytest

from photolib import triangulation_layouts as tl
from photolib.errors import InputError
from photolib.synthetic import CONTROL, TIE, footprint_block, footprint_visibility

TOL = {"3.7.2 tie height": 15, "3.7.6 control height": 0.15, "3.7.6 control plan": 0.2, "3.7.6 check plan": 0.3,
       "3.7.6 height, category a": 0.2, "3.7.6 height, category b": 0.25, "3.7.6 height, category c": 0.35,
       "3.7.7 height, category a": 0.4, "3.7.7 height, category b": 0.5, "3.7.7 height, category c": 0.7,
       "3.7.6 limit share, open": 5, "3.7.6 limit share, wooded": 10, "3.7.6 limit factor": 2}


@pytest.fixture(scope="module")
def strip3():
    """One strip of three images (b = 500 m, L = 1250 m), six points: 3 seen on all, 3 on two images."""
    centres = [(0, 0), (500, 0), (1000, 0)]
    pts = [(0, 0), (500, 0), (1000, 0), (250, 300), (750, -300), (-200, 100)]
    kind = [TIE, TIE, TIE, CONTROL, CONTROL, CONTROL]
    return footprint_block(centres, pts, kind, at_principal={0: 0, 1: 1, 2: 2}, seed=4)


def test_formulas():
    assert tl.bundle_unknowns(8, 20) == 108 and tl.bundle_equations(60, c=5, s=8) == 159
    assert tl.bundle_equations(10, 1, 1, 1, 1, 1) == 20 + 3 + 2 + 1 + 3 + 3
    with pytest.raises(InputError):
        tl.bundle_equations(-1)
    with pytest.raises(InputError):
        tl.bundle_unknowns(2.5, 1)


def test_visibility_by_hand():
    # L = 1: images at x = 0, 0.4; a point at x = 0.45 is inside both (|0.45| < 0.5), at 0.5 on the edge
    vis = footprint_visibility([[0.45, 0], [0.5, 0], [0.8, 0.1]], [[0, 0], [0.4, 0]], 1.0)
    assert vis.tolist() == [[True, True], [False, True], [False, True]]


def test_fig_3_13_grid_needs_30_percent_side_overlap():
    """At 60 % side overlap (s = 0.4L) the 5 × 4 grid of fig. 3.13 is seen on more images."""
    L, b = 1.0, 0.4
    for s, same in ((0.7, True), (0.4, False)):
        centres = [(i * b, 0.0) for i in range(4)] + [(i * b, -s) for i in range(4)]
        pts = [(c * b, y) for y in (s / 2, 0, -s / 2, -s, -1.5 * s) for c in range(4)]
        counts = footprint_visibility(pts, centres, L).sum(axis=1).reshape(5, 4).tolist()
        assert (counts == [[2, 3, 3, 2], [2, 3, 3, 2], [4, 6, 6, 4], [2, 3, 3, 2], [2, 3, 3, 2]]) is same


def test_counts_equal_the_built_system(strip3):
    per_point = tl.images_per_point(strip3).tolist()
    # footprint ±625 m: (0,0) on images 0, 1; (500,0) on all; (1000,0) on 1, 2; (250,300) on 0, 1;
    # (750,−300) on 1, 2; (−200,100) on 0 only — the principal points move a little with the tilts
    assert per_point == [2, 3, 2, 2, 2, 1]
    c = tl.block_counts(strip3)
    assert (c["n"], c["k"], c["m"]) == (3, 3, 12)
    assert (c["N"], c["M"]) == (6 * 3 + 3 * 3, 2 * 12)
    system = tl.correction_equation_system(strip3)
    assert system.shape == (c["M"], c["N"])
    assert set(system.row_kind) == {"tie", "control"}
    st = tl.normal_matrix_structure(system)
    assert st["N11_block"] == "6×6" and st["N22_block"] == "3×3"
    assert st["N12_zero_fraction"] == pytest.approx(2 / 9)    # 7 of 3·3 image–point blocks filled


def test_weighted_control_gnss_and_ins_rows(strip3):
    from dataclasses import replace
    blk = replace(strip3, control_sigma=0.05, gnss=strip3.cameras[:, :3].copy(), gnss_sigma=0.05)
    ins = np.full((3, 3), np.nan)
    ins[1] = blk.cameras[1, 3:]
    s = tl.correction_equation_system(blk, planimetric=[3], height=[4], ins=ins)
    c = tl.block_counts(blk)
    assert s.shape == (tl.bundle_equations(12, c=1, i=1, l=1, s=3, j=1), tl.bundle_unknowns(3, 6))
    assert (c["k"], c["c"], c["s"]) == (6, 3, 3)
    with pytest.raises(InputError):
        tl.correction_equation_system(strip3, planimetric=[3])          # fixed control
    with pytest.raises(InputError):
        tl.correction_equation_system(strip3, cameras=np.full((3, 6), np.nan))


def test_regulation_arithmetic():
    assert tl.check_height_factor(1.0, 10000, TOL) == 0.2
    assert tl.check_height_factor(0.5, 2000, TOL) == 0.25
    assert tl.check_height_factor(10.0, 25000, TOL, stage="common") == 0.7
    with pytest.raises(InputError):
        tl.check_height_factor(0.5, 10000, TOL)
    with pytest.raises(InputError):
        tl.check_height_factor(1.0, 10000, {})                       # tolerance missing
    assert tl.free_strip_height_tolerance_um(153.0, 92.0, TOL) == pytest.approx(15 * 153 / 92)
    control = np.array([[0.1, 0.0, 0.05], [0.0, -0.1, -0.05]])
    good = np.array([[0.3, 0.4, 0.10]] * 19 + [[0.0, 0.0, 0.25]])
    rows = tl.evaluate_regulations(control, good, 2000, 0.5, TOL)
    assert [r.passed for r in rows] == [True] * 6
    assert rows[2].tolerance == pytest.approx(0.125) and rows[3].tolerance == pytest.approx(0.6)
    assert "passed" in repr(rows[0]) and " m " in repr(rows[0])
