"""Chapter 6, §6.1–6.3 (DSM by correlation): formula checks and inline statements.

Adapters for the ``[[formula]]`` and ``[[example]]`` entries of ``textbook/ch06_surface.toml``.
Formula adapters take the printed formula as sympy text in ``inputs`` and return
``{"printed_equals_derived": bool}``; statements are checked by small seeded computations on the
rendered scene of :func:`photolib.synthetic.terrain_scene` (conditions in the entries' notes).
"""

from __future__ import annotations

import numpy as np
import sympy as sp

from .. import surface
from ..camera import ExteriorOrientation, InteriorOrientation
from ..single_image import project

_NAMES = "x y x_0 y_0 f X Y Z X_s Y_s Z_s a11 a12 a13 a21 a22 a23 a31 a32 a33".split()
_S = {n: sp.Symbol(n, real=True) for n in _NAMES}


def _parse(text):
    return sp.parse_expr(str(text), local_dict=dict(_S))


def _A():
    return sp.Matrix(3, 3, [_S[f"a{i}{j}"] for i in range(1, 4) for j in range(1, 4)])


def ground_formula(inputs: dict) -> dict:
    """(6.1.1): X, Y of the ray X = S + λ·A(x − x₀, y − y₀, −f)ᵀ at height Z (sympy solve for λ)."""
    s = _S
    lam = sp.Symbol("lambda", real=True)
    r = _A() * sp.Matrix([s["x"] - s["x_0"], s["y"] - s["y_0"], -s["f"]])
    sol = sp.solve(sp.Eq(s["Z_s"] + lam * r[2], s["Z"]), lam)[0]
    X = s["X_s"] + sol * r[0]
    Y = s["Y_s"] + sol * r[1]
    ok = sp.cancel(X - _parse(inputs["X"])) == 0 and sp.cancel(Y - _parse(inputs["Y"])) == 0
    return {"printed_equals_derived": bool(ok)}


def image_formula(inputs: dict) -> dict:
    """(6.1.2): x, y from the camera-frame vector Aᵀ(X − S) by the collinearity condition (1.4.12)."""
    s = _S
    d = _A().T * sp.Matrix([s["X"] - s["X_s"], s["Y"] - s["Y_s"], s["Z"] - s["Z_s"]])
    x = s["x_0"] - s["f"] * d[0] / d[2]
    y = s["y_0"] - s["f"] * d[1] / d[2]
    ok = sp.cancel(x - _parse(inputs["x"])) == 0 and sp.cancel(y - _parse(inputs["y"])) == 0
    return {"printed_equals_derived": bool(ok)}


def height_steps_formula(inputs: dict) -> dict:
    """§6.2: do the printed heights Z_i = Z_min + iΔZ (i from ``i_first`` to n) cover [Z_min, Z_max]?

    Derived requirement: the candidates must include Z_min and reach Z_max, i.e. i = 0…⌈(Z_max − Z_min)/ΔZ⌉.
    Checked on a grid of (Z_min, Z_max, ΔZ) with exact rationals.
    """
    i_first = int(inputs["i_first"])
    ok = True
    for lo, hi, dz in ((0, 10, 1), (100, 110, sp.Rational(1, 4)), (0, 10, 3)):
        n_printed = sp.Rational(hi - lo) / dz
        n = int(sp.floor(n_printed)) if inputs.get("n_rounding", "none") == "none" else int(sp.ceiling(n_printed))
        cand = [lo + i * dz for i in range(i_first, n + 1)]
        ok &= bool(cand) and min(cand) == lo and max(cand) >= hi
    return {"printed_equals_derived": ok}


def segment_contains_match(inputs: dict) -> dict:
    """§6.1: the match m₂ lies on the segment cd of (6.1.1)/(6.1.2) (the guide's seg.py pair)."""
    io = InteriorOrientation(100.0, 0.02, -0.01)
    e1 = ExteriorOrientation(1000, 2000, 1500, 0.010, -0.020, 0.30, order="wak")
    e2 = ExteriorOrientation(1600, 2010, 1495, -0.015, 0.012, 0.31, order="wak")
    M = np.array([inputs["point"]], dtype=float)
    m1, m2 = project(M, e1, io), project(M, e2, io)
    c, d = surface.epipolar_segment(m1, e1, e2, io, float(inputs["z_min"]), float(inputs["z_max"]))
    v, w = (d - c)[0], (m2 - c)[0]
    t = float(v @ w / (v @ v))
    off = float(abs(v[0] * w[1] - v[1] * w[0]) / np.linalg.norm(v))
    return {"on_segment": "yes" if 0 <= t <= 1 and off < 1e-9 else "no", "t": t, "distance_mm": off}


def transcribed(inputs: dict) -> dict:
    """Pure specifications: nothing to compute."""
    return {}
