"""Chapter 10, §10.1–10.5 — aerial phototopographic survey: adapters for ``textbook/ch10_planning.toml``.

Chapter 10 prints no formula and no worked example; its numbers are specifications (transcribed
in the fragment). Two kinds are computed here: the 8-pixel square of the GCP marker rule, which
follows from the 4-GSD minimum arm (:mod:`photolib.planning`), and the counts the text states
in words for lists it then enumerates.
"""

from __future__ import annotations

from photolib.planning import check_marker


def gcp_marker_rules(inputs: dict) -> dict:
    """The span of the smallest conforming cross (arms of ``arm_min_gsd`` from the centre), in pixels."""
    g = 1.0
    c = check_marker(inputs["arm_min_gsd"] * g, inputs["width_min_gsd"] * g, g)
    return {"square_side": c.span_px}


def count_listed(inputs: dict) -> dict:
    """The number of items the text enumerates right after stating their count."""
    return {"count": len(inputs["items"])}
