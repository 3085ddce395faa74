"""Chapter 3, §3.5 and §3.7: the book's block drawings and regulation table, rebuilt (book layer).

§3.5 counts unknowns and correction equations for two small blocks whose drawings survive only
partly in the OCR: fig. 3.10 (two strips of one stereopair each, 60 % forward and 60 % side
overlap, four tie points, four XYZ control points held fixed) and fig. 3.13 (two strips of four
images, control by five XYZ points and eight GNSS projection centres, the figure printing how
many images see each point). :func:`fig_3_10_block` and :func:`fig_3_13_block` rebuild both as
:class:`photolib.synthetic.Block` *from footprint geometry*
(:func:`photolib.synthetic.footprint_block`), so that the counts follow from the geometry.
:func:`fig_3_10_block` with ``rig=True`` is the same block shot with a stereo camera (§3.8,
fig. 3.18): P2 and P4 follow from P1 and P3 by one set of mounting elements.

§3.7 quotes the *Instruction on photogrammetric works*; its tolerance numbers are data in
``textbook/ch03.toml`` (example ``3.7-tolerances``). :func:`regulation_value` /
:func:`regulation_tolerances` read them, and :func:`check_height_factor`,
:func:`free_strip_height_tolerance_um` and :func:`evaluate_regulations` call the library
functions of :mod:`photolib.triangulation_layouts` with them.

For the notebook this module also re-exports the library's counting and system functions, so
``from photolib.book import ch03_layouts as tl`` offers everything ``tl.…`` used before.
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np

from .. import triangulation_layouts as _tl
from ..synthetic import CHECK, CONTROL, TIE, Block, PointKind, footprint_block, footprint_visibility  # noqa: F401
from ..triangulation_layouts import (BundleSystem, Criterion, block_counts, bundle_equations,  # noqa: F401
                                     bundle_unknowns, check_point_accuracy, correction_equation_system,
                                     images_per_point, normal_matrix_structure, predicted_point_sigma)

BookBlock = Block          # the former name of the rebuilt blocks' type

REGULATIONS_ID = "3.7-tolerances"


def fig_3_10_block(sigma: float = 0.005, seed: int = 310, *, f: float = 100.0, frame_size: float = 125.0,
                   flying_height: float = 1000.0, order: str = "kaw", rig: bool = False) -> Block:
    """Fig. 3.10: two strips (P1–P2, P3–P4) of one stereopair, 60 % forward and 60 % side overlap.

    Footprint L = frame·H/f (1250 m by default), base b = strip spacing s = 0.4L (500 m). Tie
    points 1, 2, 5, 6 at the principal points of P1, P2, P3, P4 (seen on all four images); XYZ
    control 3, 4 at s/2 beyond strip 1 (on P1, P2 only) and 7, 8 at s/2 beyond strip 2 (on P3, P4
    only), held fixed (3.5.3). Every image then measures six points: N = 36, M = 48 (book, lines
    2080–2083). True tilts are small (seeded, σ = 1°), terrain heights 5–20 m.

    With ``rig=True`` P1/P2 and P3/P4 are two exposures of a stereo camera (§3.8, fig. 3.18):
    camera 0 = P1, P3; camera 1 = P2, P4, whose EO follow from P1, P3 by the mounting elements
    of the first exposure.
    """
    L = frame_size * flying_height / f
    b = s = 0.4 * L
    x0, y0 = 1000.0, 1000.0
    centres = [(x0, y0), (x0 + b, y0), (x0, y0 - s), (x0 + b, y0 - s)]
    pts = {1: (x0, y0), 2: (x0 + b, y0), 3: (x0, y0 + s / 2), 4: (x0 + b, y0 + s / 2),
           5: (x0, y0 - s), 6: (x0 + b, y0 - s), 7: (x0, y0 - 1.5 * s), 8: (x0 + b, y0 - 1.5 * s)}
    kind = [CONTROL if k in (3, 4, 7, 8) else TIE for k in pts]
    rig_args = dict(exposure_of_image=[0, 0, 1, 1], camera_of_image=[0, 1, 0, 1]) if rig else {}
    return footprint_block(centres, list(pts.values()), kind, f=f, frame_size=frame_size,
                           flying_height=flying_height, sigma=sigma, seed=seed, order=order, control_sigma=None,
                           gnss_sigma=None, name="fig3.10", image_labels=("P1", "P2", "P3", "P4"),
                           point_labels=tuple(str(k) for k in pts), base=b, strip_spacing=s,
                           at_principal={0: 0, 1: 1, 4: 2, 5: 3}, **rig_args)


def fig_3_13_block(sigma: float = 0.005, seed: int = 313, *, control_sigma: float = 0.05, gnss_sigma: float = 0.05,
                   f: float = 100.0, frame_size: float = 125.0, flying_height: float = 1000.0,
                   order: str = "kaw") -> Block:
    """Fig. 3.13: two strips of four images, 60 % forward and 30 % side overlap.

    b = 0.4L, s = 0.7L. A 5 × 4 grid of 20 points: rows at +s/2, 0 (nadirs of strip 1), −s/2, −s
    (nadirs of strip 2), −1.5s; columns at the nadirs. Control (weighted, (3.5.17), σ =
    ``control_sigma``): the four corners and the right end of the middle row (c = 5); all eight
    projection centres measured by GNSS (3.5.18, σ = ``gnss_sigma``). The footprints give the
    figure's images-per-point counts 2-3-3-2 / 2-3-3-2 / 4-6-6-4 / 2-3-3-2 / 2-3-3-2 (m = 60) —
    with 30 % side overlap only. Book (lines 2164–2186): N = 108, M = 159.
    """
    L = frame_size * flying_height / f
    b, s = 0.4 * L, 0.7 * L
    x0, y0 = 1000.0, 1000.0
    centres = [(x0 + i * b, y0) for i in range(4)] + [(x0 + i * b, y0 - s) for i in range(4)]
    rows = [s / 2, 0.0, -s / 2, -s, -1.5 * s]
    pts = [(x0 + c * b, y0 + y) for y in rows for c in range(4)]
    control = {(0, 0), (0, 3), (4, 0), (4, 3), (2, 3)}
    kind = [CONTROL if (r, c) in control else TIE for r in range(5) for c in range(4)]
    labels = [f"r{r + 1}c{c + 1}" for r in range(5) for c in range(4)]
    images = [f"P{i + 1}" for i in range(8)]
    return footprint_block(centres, pts, kind, f=f, frame_size=frame_size, flying_height=flying_height,
                           sigma=sigma, seed=seed, order=order, control_sigma=control_sigma, gnss_sigma=gnss_sigma,
                           name="fig3.13", image_labels=images, point_labels=labels, grid=(5, 4), base=b,
                           strip_spacing=s,
                           at_principal={4 + c: c for c in range(4)} | {12 + c: 4 + c for c in range(4)})


# --- §3.7 regulation tolerances (numbers from textbook/ch03.toml) ---------------------------------
@lru_cache(maxsize=None)
def regulation_tolerances() -> dict:
    """{quantity name: value} of the example ``3.7-tolerances`` (numeric values only)."""
    from .textbook import load_chapter
    ex = load_chapter(3).example(REGULATIONS_ID)
    return {q.name: q.value for q in ex.quantities if isinstance(q.value, (int, float))}


def regulation_value(name: str) -> float:
    """A tolerance of §3.7 as transcribed in ``textbook/ch03.toml`` (example ``3.7-tolerances``)."""
    tol = regulation_tolerances()
    if name not in tol:
        raise KeyError(f"{REGULATIONS_ID} has no quantity {name!r}")
    return tol[name]


def check_height_factor(contour_interval: float, scale_denominator: float, stage: str = "check") -> float:
    """3.7.6 / 3.7.7 factor of h with the book's tolerances (:func:`photolib.triangulation_layouts.check_height_factor`)."""
    return _tl.check_height_factor(contour_interval, scale_denominator, regulation_tolerances(), stage)


def free_strip_height_tolerance_um(f_mm: float, base_image_mm: float) -> float:
    """3.7.2: 15 µm · f / b with the book's number (:func:`photolib.triangulation_layouts.free_strip_height_tolerance_um`)."""
    return _tl.free_strip_height_tolerance_um(f_mm, base_image_mm, regulation_tolerances())


def evaluate_regulations(control_errors, check_errors, scale_denominator: float, contour_interval: float,
                         wooded: bool = False) -> list:
    """3.7.6 checks with the book's tolerances (:func:`photolib.triangulation_layouts.evaluate_regulations`)."""
    return _tl.evaluate_regulations(control_errors, check_errors, scale_denominator, contour_interval,
                                    regulation_tolerances(), wooded)


def bundle_system_counts(system: BundleSystem) -> dict:
    """n, k, N, M, m, c, s read off the rows and columns of a built system."""
    kinds = system.row_kind
    return {"n": system.n_eo // 6, "k": (system.A.shape[1] - system.n_eo) // 3, "N": int(system.A.shape[1]),
            "M": int(system.A.shape[0]), "m": int(np.isin(kinds, ("tie", "control")).sum() // 2),
            "c": int((kinds == "ground").sum() // 3), "s": int((kinds == "gnss").sum() // 3)}
