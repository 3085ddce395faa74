"""Chapter 10 entries of textbook/ch10_planning.toml: every status holds; the marker rules agree."""

import math

import pytest

from photolib.book import verify
from photolib.book.textbook import load_chapter
from photolib.planning import check_marker, gcp_marker, imu_ground_error, skip_aerial_triangulation

IDS = ["10.1-map-scales", "10.2-combined-scales", "10.3-space-ortho-scale", "10.3-gcp-marker",
       "10.3-imu-tolerance", "10.4-update-cycle", "10.5-stereo-methods", "10.5-algorithm-groups",
       "10.5-table-10.1"]


@pytest.mark.parametrize("example_id", IDS)
def test_entry_statuses_hold(example_id):
    rows = verify.check_example(load_chapter(10).example(example_id))
    assert rows and all(r.ok for r in rows), [r for r in rows if not r.ok]


def test_table_10_1_has_eight_systems_and_every_row():
    ex = load_chapter(10).example("10.5-table-10.1")
    names = [q.name for q in ex.quantities]
    assert sum(n.startswith("year[") for n in names) == 8
    assert sum(n.startswith("row[") for n in names) == 19
    for q in ex.quantities:
        if q.name.startswith("row["):
            assert len(q.value.split()) == 8, q.name          # one cell per system


def test_transcribed_marker_rules_are_the_library_rules():
    ex = {q.name: q.value for q in load_chapter(10).example("10.3-gcp-marker").quantities}
    m = gcp_marker(1.0)
    assert (m.arm_min, m.arm_max, m.width_min, m.width_max, m.square_min) == (
        ex["arm_min_low"], ex["arm_min_high"], ex["width_low"], ex["width_high"], ex["square_side"])
    assert check_marker(ex["arm_min_low"], ex["width_low"], 1.0).ok


def test_imu_tolerances_are_the_library_limits_and_notes_figures():
    ex = {q.name: q.value for q in load_chapter(10).example("10.3-imu-tolerance").quantities}
    rp, h = math.radians(ex["sigma_roll_pitch"]), math.radians(ex["sigma_heading"])
    assert skip_aerial_triangulation(rp, rp, h, relief_from_lidar=True,
                                     plan_scale=ex["smallest_plan_denominator"]).skip
    assert not skip_aerial_triangulation(rp * 1.001, rp, h, relief_from_lidar=True, plan_scale=2000).skip
    e = imu_ground_error(rp, rp, h, 1000.0, math.atan(0.5))      # the figures quoted in the notes
    assert (round(e.roll_nadir, 3), round(e.roll_edge, 3), round(e.heading_edge, 3)) == (0.087, 0.109, 0.087)


def test_flight_plan_figure_on_synthetic_relief():
    from photolib.book.figures import ch10_planning as figs
    scene = figs.synthetic_scene(length=9000.0)
    fig, numbers = figs.flight_plan_over_relief(scene)
    assert len(fig.axes) == 4
    assert numbers["overlap_min"] < numbers["overlap_planned"] < numbers["overlap_max"]
    assert numbers["gsd_cm_range"][0] < 30.0 < numbers["gsd_cm_range"][1]
