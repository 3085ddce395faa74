"""Chapter 5, §5.6 (search-space reduction): formula checks and inline statements.

Adapters for the ``[[formula]]`` and ``[[example]]`` entries of ``textbook/ch05_epipolar.toml``.
Formula adapters take the printed formula as sympy text in ``inputs`` (a test can hand in a wrong
one) and return ``{"printed_equals_derived": bool}``. The § prints no worked example; its inline
statements are checked by small seeded computations with the conditions in the entry's notes.
"""

from __future__ import annotations

import numpy as np
import sympy as sp

from .. import epipolar
from ..camera import ExteriorOrientation, InteriorOrientation
from ..single_image import project

_NAMES = ("x_1 y_1 x_c y_c f X_1 Y_1 Z_1 a11 a12 a13 a21 a22 a23 a31 a32 a33 "
          "b11 b12 b13 b21 b22 b23 b31 b32 b33").split()
_S = {n: sp.Symbol(n, real=True) for n in _NAMES}


def _parse(text):
    return sp.parse_expr(str(text), local_dict=dict(_S))


def _rays():
    s = _S
    A1 = sp.Matrix(3, 3, [s[f"b{i}{j}"] for i in range(1, 4) for j in range(1, 4)])   # A'1
    A2 = sp.Matrix(3, 3, [s[f"a{i}{j}"] for i in range(1, 4) for j in range(1, 4)])   # A'2
    r1 = A1 * sp.Matrix([s["x_1"], s["y_1"], -s["f"]])
    rc = A2 * sp.Matrix([s["x_c"], s["y_c"], -s["f"]])
    return r1, rc


def coplanarity_formula(inputs: dict) -> dict:
    """(5.6.1): det[B; r₁; r_c] with B = (1, 0, 0) equals the printed Y′₁Z′_c − Y′_cZ′₁."""
    r1, rc = _rays()
    det = sp.Matrix([[1, 0, 0], list(r1), list(rc)]).det()
    printed = sp.parse_expr(str(inputs["printed"]), local_dict={**_S, "Y_c": rc[1], "Z_c": rc[2],
                                                                 "Y_1": r1[1], "Z_1": r1[2]})
    return {"printed_equals_derived": sp.expand(det - printed) == 0}


def unnumbered_formula(inputs: dict) -> dict:
    """The unnumbered line after (5.6.1): the coplanarity written with Y′_c, Z′_c expanded (A′₂ = a_ij)."""
    _, rc = _rays()
    s = _S
    derived = s["Y_1"] * rc[2] - s["Z_1"] * rc[1]
    return {"printed_equals_derived": sp.expand(derived - _parse(inputs["printed"])) == 0}


def epipolar_ordinate_formula(inputs: dict) -> dict:
    """(5.6.2): the printed y_c against the solution of the unnumbered equation for y_c."""
    _, rc = _rays()
    s = _S
    sol = sp.solve(sp.Eq(s["Y_1"] * rc[2] - s["Z_1"] * rc[1], 0), s["y_c"])
    return {"printed_equals_derived": len(sol) == 1 and sp.cancel(sol[0] - _parse(inputs["printed"])) == 0}


def _epi_pair():
    """The guide's pair (epi.py): f = 0.1, B = (1, 0, 0), α′₁ = 1.2°, κ′₁ = −0.8°, ω′₂ = 0.7°, α′₂ = −1.5°, κ′₂ = 2°."""
    io = InteriorOrientation(0.1)
    e1 = ExteriorOrientation.from_degrees(0, 0, 0, 0.0, 1.2, -0.8, order="wak")
    e2 = ExteriorOrientation.from_degrees(1, 0, 0, 0.7, -1.5, 2.0, order="wak")
    return io, e1, e2


def epipolar_ordinate_numeric(inputs: dict) -> dict:
    """y_c of (5.6.2), corrected and as printed, against the projection of the model point."""
    io, e1, e2 = _epi_pair()
    M = np.array([inputs["model_point"]], dtype=float)
    m1, m2 = project(M, e1, io), project(M, e2, io)
    y = epipolar.epipolar_ordinate(m1[0], m2[0, 0], e1.matrix, e2.matrix, io.f)
    return {"y_c": y, "y_true": float(m2[0, 1]), "difference": abs(y - float(m2[0, 1]))}


def epipolar_ordinate_printed(inputs: dict) -> dict:
    io, e1, e2 = _epi_pair()
    M = np.array([inputs["model_point"]], dtype=float)
    m1, m2 = project(M, e1, io), project(M, e2, io)
    return {"y_c": epipolar.epipolar_ordinate(m1[0], m2[0, 0], e1.matrix, e2.matrix, io.f, as_printed=True)}


def pyramid_levels(inputs: dict) -> dict:
    """A pyramid by 2×2 means: pixels merged per level and the number of levels (Fig. 5.15)."""
    size = int(inputs["size"])
    img = np.random.default_rng(0).random((size, size))
    levels = epipolar.pyramid(img, int(inputs["levels_above"]))
    merged = levels[0].size / levels[1].size
    mean_ok = bool(np.allclose(levels[1][0, 0], img[:2, :2].mean()))
    return {"pixels_merged": merged, "levels": len(levels), "mean_rule": "yes" if mean_ok else "no"}


def coarse_to_fine(inputs: dict) -> dict:
    """Coarse-to-fine correlation: ±s px on top, ±r px below recover a large shift (the guide's sift_pyr.py set-up)."""
    from scipy.ndimage import gaussian_filter
    rng = np.random.default_rng(int(inputs["seed"]))
    base = gaussian_filter(rng.normal(size=(300, 300)), 3.0)
    p, q = inputs["shift"]
    img2 = np.roll(base, (-q, -p), axis=(0, 1))
    m = epipolar.match_coarse_to_fine(base, img2, (150, 150), levels=int(inputs["levels_above"]),
                                      search_radius=int(inputs["top_radius"]),
                                      refine_radius=int(inputs["refine_radius"]))
    ok = (round(m.p), round(m.q)) == (p, q) and m.confident
    return {"found": "yes" if ok else "no", "refine_radius": int(inputs["refine_radius"]),
            "p": m.p, "q": m.q}


def normal_case(inputs: dict) -> dict:
    """After resampling to the normal case the y-parallax of every point is zero (px)."""
    io = InteriorOrientation(35.0)
    e1 = ExteriorOrientation(0, 0, 500, 0.03, -0.04, 0.05)
    e2 = ExteriorOrientation(120, 8, 497, -0.02, 0.03, -0.04)
    shape, d = (300, 400), 0.02
    from ..synthetic import image_to_pixel
    rp = epipolar.rectify_pair(np.zeros(shape), np.zeros(shape), io, e1, e2, d)
    P = np.random.default_rng(int(inputs["seed"])).uniform([0, -60, -30], [120, 60, 30], (40, 3))
    rows = [rp.to_rectified(image_to_pixel(project(P, e, io), shape, d), i)[:, 1] for i, e in enumerate((e1, e2))]
    before = [image_to_pixel(project(P, e, io), shape, d)[:, 1] for e in (e1, e2)]
    return {"max_q_px": float(np.max(np.abs(rows[0] - rows[1]))),
            "max_q_before_px": float(np.max(np.abs(before[0] - before[1])))}


def three_images(inputs: dict) -> dict:
    """The intersection of two epipolar lines on image 3 is the homologous point (Fig. 5.18)."""
    io = InteriorOrientation(100.0)
    eos = [ExteriorOrientation(0, 0, 1000), ExteriorOrientation(400, 10, 1000, 0.0, 0.02, 0.1),
           ExteriorOrientation(200, 350, 990, -0.02, 0.0, 0.0)]
    P = np.random.default_rng(int(inputs["seed"])).uniform([50, 50, -20], [350, 250, 40], (10, 3))
    xy = [project(P, e, io) for e in eos]
    err = np.max(np.abs(epipolar.epipolar_intersection(xy[0], xy[1], *eos, io) - xy[2]))
    return {"max_error_mm": float(err)}


def transcribed(inputs: dict) -> dict:
    """Pure specifications: nothing to compute."""
    return {}
