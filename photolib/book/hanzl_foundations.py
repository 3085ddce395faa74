"""Adapters for Hanzl's mathematical foundations, *Fotogrammetrie, Modul 01*, §2 (seed 002 lines 131–342).

Each function takes the ``inputs`` table of an entry ``hanzl-2…`` of ``textbook/ch01_hanzl.toml``
(filed under Chibunichev Chapter 1) and returns ``{quantity: value}`` (examples) or
``{"printed_equals_derived": bool}`` (formulas). The formula checks compare the transcriptions of
:mod:`photolib.derivations.hanzl_foundations` with their derivations and with the library's own
models (exact zero tests); the counts come from the same derivations and from
:mod:`photolib.plane_transforms`; the Danish constants from :mod:`photolib.lsq`.
:func:`blunder_scene` makes the seeded synthetic resection of the notebook (Hanzl prints no data).
"""

from __future__ import annotations

import numpy as np
import sympy as sp

from .. import lsq
from .. import plane_transforms as pt
from .. import projective
from ..camera import ExteriorOrientation, InteriorOrientation
from ..derivations import collinearity_model
from ..derivations import hanzl_foundations as H
from ..derivations import symbols as S
from ..derivations.plane import congruent_model
from ..derivations.rotation import elementary_rotations, rotation_matrix_symbolic
from ..single_image import project
from ._exact import zero

__all__ = ["formula_check", "rotation_counts", "projection_counts", "transformation_counts", "danish_constants",
           "blunder_scene", "KIND_FORMULAS"]


def _ok(flag) -> dict:
    return {"printed_equals_derived": bool(flag)}


def _same(a, b) -> bool:
    if isinstance(a, (tuple, list)):
        return all(_same(p, q) for p, q in zip(a, b))
    return zero(sp.Matrix(a) - sp.Matrix(b) if isinstance(a, sp.MatrixBase) else a - b)


def _hanzl_to_library():
    """Hanzl's symbols → the library's: r_ij → a_ij of A_ω A_α A_κ, c → f, X₀ → X_S, φ → α."""
    A = rotation_matrix_symbolic("wak")
    sub = {H.R_SYMBOLS[i, j]: A[i, j] for i in range(3) for j in range(3)}
    sub.update({H.C: S.f, H.XC: S.Xs, H.YC: S.Ys, H.ZC: S.Zs})
    return sub


KIND_FORMULAS = {
    "congruent": "x = cos α x̄ − sin α ȳ + t_x, y = sin α x̄ + cos α ȳ + t_y",
    "similarity": "x = q cos α x̄ − q sin α ȳ + t_x, y = q sin α x̄ + q cos α ȳ + t_y",
    "affine": "x = a11 x̄ + a12 ȳ + a13, y = a21 x̄ + a22 ȳ + a23",
    "projective": "X = (a1 x + a2 y + a3)/(c1 x + c2 y + 1), Y = (b1 x + b2 y + b3)/(c1 x + c2 y + 1)",
    "bilinear": "x = a1 + a2 x̄ + a3 ȳ + a4 x̄ȳ, y = b1 + b2 x̄ + b3 ȳ + b4 x̄ȳ",
    "polynomial": "x = a1 + a2 x̄ + a3 ȳ + a4 x̄² + a5 ȳ² + a6 x̄ȳ, likewise y with b",
}
"""The printed forms of Hanzl §2.5 (lines 267–297), compared with :class:`photolib.plane_transforms.PlaneTransform`."""


def _printed_kind(kind: str, params, xb, yb):
    """The printed form of a transformation (lines 267–297), evaluated with numpy."""
    p = params
    if kind == "congruent":
        a, tx, ty = p
        return np.cos(a) * xb - np.sin(a) * yb + tx, np.sin(a) * xb + np.cos(a) * yb + ty
    if kind == "similarity":
        q, a, tx, ty = p
        return (q * np.cos(a) * xb - q * np.sin(a) * yb + tx, q * np.sin(a) * xb + q * np.cos(a) * yb + ty)
    if kind == "affine":
        return p[0] * xb + p[1] * yb + p[2], p[3] * xb + p[4] * yb + p[5]
    if kind == "projective":
        w = p[6] * xb + p[7] * yb + 1
        return (p[0] * xb + p[1] * yb + p[2]) / w, (p[3] * xb + p[4] * yb + p[5]) / w
    if kind == "bilinear":
        return p[0] + p[1] * xb + p[2] * yb + p[3] * xb * yb, p[4] + p[5] * xb + p[6] * yb + p[7] * xb * yb
    m = [np.ones_like(xb), xb, yb, xb * xb, yb * yb, xb * yb]
    return sum(a * t for a, t in zip(p[:6], m)), sum(b * t for b, t in zip(p[6:], m))


def _kind_check(kind: str) -> bool:
    """The printed form equals the library's transformation on 50 random points, 5 random parameter sets."""
    rng = np.random.default_rng(2)
    src = rng.uniform(-1.0, 1.0, (50, 2))
    ok = True
    for _ in range(5):
        if kind == "congruent":
            p = [rng.uniform(-np.pi, np.pi), *rng.normal(size=2)]
            lib = p
        elif kind == "similarity":
            q, a = rng.uniform(0.5, 2.0), rng.uniform(-np.pi, np.pi)
            p = [q, a, *rng.normal(size=2)]
            lib = [q * np.cos(a), q * np.sin(a), p[2], p[3]]               # a = q cos α, b = q sin α
        else:
            p = rng.normal(size=pt.N_PARAMETERS[kind]) * (0.1 if kind == "projective" else 1.0)
            lib = p
        printed = np.column_stack(_printed_kind(kind, p, src[:, 0], src[:, 1]))
        ok &= bool(np.allclose(pt.PlaneTransform(kind, lib).apply(src), printed, rtol=1e-12, atol=1e-12))
    if kind == "congruent":                                                 # and the sympy model of the fit
        xb, yb, xo, yo = congruent_model().data
        a, tx, ty = congruent_model().parameters
        res = congruent_model().residuals
        ok &= _same((res[0] + xo, res[1] + yo),
                    (sp.cos(a) * xb - sp.sin(a) * yb + tx, sp.sin(a) * xb + sp.cos(a) * yb + ty))
    return ok


def formula_check(inputs: dict) -> dict:
    """Compare one printed formula of Hanzl §2 with its derivation (``inputs["item"]``)."""
    item = inputs["item"]
    if item == "2.1-cosines":
        out = H.plane_rotation()
        return _ok(_same(out["from_cosines"], out["printed"]))
    if item == "1.2":
        out = H.plane_rotation()
        return _ok(_same(list(out["conditions_printed"]), [0, 0, 0])
                   and _same(list(out["conditions_vectors"]), [0, 0, 0]))
    if item == "2.1-inverse":
        R = H.plane_rotation()["printed"]
        return _ok(_same(R.T * R, sp.eye(2)))
    if item == "2.2-elementary":
        # the elementary matrices as printed (lines 183–189) = the library's (Chibunichev (1.3.1))
        w, p, k = S.omega, H.PHI, S.kappa
        c, s = sp.cos, sp.sin
        printed = (sp.Matrix([[1, 0, 0], [0, c(w), -s(w)], [0, s(w), c(w)]]),
                   sp.Matrix([[c(p), 0, s(p)], [0, 1, 0], [-s(p), 0, c(p)]]),
                   sp.Matrix([[c(k), -s(k), 0], [s(k), c(k), 0], [0, 0, 1]]))
        return _ok(_same(list(printed), list(elementary_rotations(w, p, k))))
    if item == "2.2-steps":
        return _ok(_same(H.rotation_from_steps(), H.hanzl_rotation()))
    if item == "2.2-table":
        return _ok(_same(H.printed_rotation_table(), H.hanzl_rotation()))
    if item == "2.2-library":
        lib = rotation_matrix_symbolic("wak").xreplace({S.alpha: H.PHI})
        return _ok(_same(H.hanzl_rotation(), lib))
    if item == "2.2-orthogonality":
        R = H.hanzl_rotation()
        return _ok(_same(R.T * R, sp.eye(3)) and _same(R * R.T, sp.eye(3)))
    if item == "2.1-rotated":
        f = H.collinearity_forms()
        return _ok(_same(f["rotated"], f["rotated_derived"]))
    if item == "2.2":
        f = H.collinearity_forms()
        lib = collinearity_model("wak").residuals                 # F = x0 − f X*/Z* − x  (1.8.2)
        sub = _hanzl_to_library()
        as_lib = tuple(e.xreplace(sub) for e in f["printed"])
        return _ok(_same(f["printed"], f["derived"])
                   and _same(as_lib, (lib[0] + S.x, lib[1] + S.y)))
    if item == "2.3":
        f = H.inverse_forms()
        return _ok(_same(f["printed"], f["derived"]))
    if item == "2.4":
        f = H.dlt_coefficients()
        return _ok(len(f["L"]) == 11 and _same(f["substituted"], f["collinearity"]))
    if item == "2.5":
        f = H.plane_projective_coefficients()
        return _ok(len(f["coefficients"]) == 8 and _same(f["substituted"], f["inverse"]))
    if item.startswith("kind:"):
        return _ok(_kind_check(item[5:]))
    if item == "affine-geometric":
        # the geometric form (line 277) = the library's composition R(α)·shear·scales
        qx, qy, a, da = H.affine_forms()["symbols"]
        vals = {qx: 1.3, qy: 0.8, a: 0.4, da: -0.05}
        num = np.array(H.affine_forms()["geometric"].xreplace(vals), dtype=float)
        lib = pt.affine_from_decomposition(1.3, 0.8, 0.4, -0.05)[:2, :2]
        return _ok(np.allclose(num, lib, rtol=1e-14, atol=1e-14))
    if item == "affine-decomposition":
        rel = H.affine_forms()["printed_decomposition"]
        return _ok(all(sp.simplify(e) == 0 for e in rel))
    if item == "2.6-estimate":
        out = H.least_squares_forms(3, 2)
        A, P, l = out["A"], out["P"], out["l"]
        xhat = (A.T * P * A).inv() * A.T * P * l
        return _ok(_same(A.T * P * (A * xhat - l), sp.zeros(2, 1)))            # normal equations hold
    if item == "2.6-middle":
        out = H.least_squares_forms(3, 2)
        return _ok(_same(out["printed_middle"], out["v"]))
    if item == "2.6-final":
        out = H.least_squares_forms(3, 2)
        return _ok(_same(out["printed_final"], out["v"]))
    if item == "2.6-redundancy":
        out = H.least_squares_forms(3, 2)
        return _ok(_same(sum(out["redundancy"]), 3 - 2))
    if item == "2.6-normalized":
        out = H.least_squares_forms(3, 2)
        return _ok(_same(out["normalized_printed"], out["normalized_qvv"]))
    if item == "2.6-danish":
        f = H.danish_weight_forms()
        return _ok(_same(f["printed"], f["derived"]))
    raise KeyError(f"no formula check for item {item!r}")


# --- counts ------------------------------------------------------------------------------------------------
def rotation_counts(inputs: dict) -> dict:
    """§2.1/§2.2: elements, orthogonality conditions and independent parameters of R (2-D and 3-D)."""
    out2 = H.plane_rotation()
    R2 = out2["printed"]
    R3 = H.hanzl_rotation()
    M = sp.MatrixSymbol("M", 3, 3).as_explicit()
    G = M.T * M - sp.eye(3)
    conditions3 = {sp.expand(G[i, j]) for i in range(3) for j in range(i, 3)}
    return {"elements 2-D": len(R2), "conditions 2-D": len(out2["conditions_printed"]),
            "independent 2-D": len(R2) - len(out2["conditions_printed"]),
            "angles in R 2-D": len(R2.free_symbols),
            "conditions 3-D": len(conditions3), "independent 3-D": len(R3) - len(conditions3),
            "angles in R 3-D": len(R3.free_symbols)}


def projection_counts(inputs: dict) -> dict:
    """§2.3/§2.4: the eleven L of (2.4) and the eight parameters of (2.5)."""
    return {"DLT coefficients": len(H.dlt_coefficients()["L"]),
            "library DLT coefficients": len(projective.DLT_NAMES),
            "plane projective parameters": len(H.plane_projective_coefficients()["coefficients"])}


def transformation_counts(inputs: dict) -> dict:
    """§2.5 (I22): parameters and minimum identical points of the six transformations."""
    out = {}
    for kind in inputs["kinds"]:
        out[f"{kind} parameters"] = pt.N_PARAMETERS[kind]
        out[f"{kind} minimum points"] = pt.MIN_POINTS[kind]
    return out


def danish_constants(inputs: dict) -> dict:
    """§2.6: the constants of the Danish weight function used by :func:`photolib.lsq.robust_gauss_newton`."""
    return {"k": lsq.DANISH_FACTOR, "d (2nd iteration)": lsq.DANISH_EXPONENTS[0],
            "d (3rd to n-th iteration)": lsq.DANISH_EXPONENTS[1]}


# --- the synthetic resection of the notebook ------------------------------------------------------------------
def blunder_scene(seed: int = 1, n: int = 20, fraction: float = 0.2, sigma: float = 0.005, f: float = 100.0):
    """A seeded near-vertical image of n control points, a fraction of them with blunders of 0.1–0.5 mm.

    Returns
    -------
    XYZ : (n, 3) m; xy : (n, 2) mm; eo : ExteriorOrientation (truth); io : InteriorOrientation;
    bad : sorted indices of the points with blunders.
    """
    rng = np.random.default_rng(seed)
    io = InteriorOrientation(f)
    XYZ = np.column_stack([rng.uniform(0, 2000, n), rng.uniform(0, 2000, n), rng.uniform(0, 80, n)])
    eo = ExteriorOrientation.from_degrees(1000, 1000, 1500, *rng.uniform(-4, 4, 3))
    xy = project(XYZ, eo, io) + rng.normal(0, sigma, (n, 2))
    nb = int(round(fraction * n))
    bad = np.sort(rng.choice(n, nb, replace=False))
    xy[bad] += rng.choice([-1, 1], (nb, 2)) * rng.uniform(0.1, 0.5, (nb, 2))
    return XYZ, xy, eo, io, bad
