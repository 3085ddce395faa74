"""Chapter 3, §3.5 counts and printed formulas: ``textbook/ch03.toml`` inputs → library calls.

Examples (the counts are read off *built* equation systems, not only the formulas):

* :func:`fig_3_10_counts` — N = 36, M = 48 of the fig. 3.10 block (lines 2080–2083).
* :func:`fig_3_10_structure` — the structure of A and N stated for figs. 3.11/3.12.
* :func:`fig_3_13_counts` — n, k, N, m, c, s, M of the fig. 3.13 block and its images-per-point grid.

Formulas (each returns ``{"printed_equals_derived": bool}`` from a sympy check):

* :func:`normal_equation_check` — (3.5.8), (3.5.9), (3.5.10) against the minimum of VᵀPV.
* :func:`partitioned_check` — (3.5.13), (3.5.14), (3.5.15), (3.5.16) and the derivation lines.
* :func:`weighted_observation_check` — the free terms l = X⁰ − X of (3.5.17)–(3.5.19).
* :func:`count_formula_check` — (3.5.20)/(3.5.21) against the shape of built systems.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import sympy as sp

from ..errors import InputError
from ..triangulation_layouts import (block_counts, bundle_equations, bundle_unknowns, correction_equation_system,
                                     images_per_point, normal_matrix_structure)
from ._exact import zero
from .ch03_layouts import bundle_system_counts as _system_counts, fig_3_10_block, fig_3_13_block


# --- examples ------------------------------------------------------------------------------------
def fig_3_10_counts(inputs: dict) -> dict:
    """Fig. 3.10: build the correction equations of the rebuilt block and count rows and columns."""
    blk = fig_3_10_block(sigma=inputs.get("sigma_mm", 0.005), seed=inputs.get("seed", 310))
    system = correction_equation_system(blk)
    c = _system_counts(system)
    per_image = blk.visibility.sum(axis=0)
    return {"n": c["n"], "k": c["k"], "N": c["N"], "M": c["M"],
            "points_per_image": int(per_image[0]) if np.all(per_image == per_image[0]) else float("nan")}


def fig_3_10_structure(inputs: dict) -> dict:
    """Figs. 3.11/3.12: block structure of N = AᵀPA of the rebuilt fig. 3.10 system."""
    blk = fig_3_10_block(sigma=inputs.get("sigma_mm", 0.005), seed=inputs.get("seed", 310))
    st = normal_matrix_structure(correction_equation_system(blk))
    return {"N11 blocks": st["N11_block"], "N22 blocks": st["N22_block"], "N12 pattern": st["N12_pattern"]}


def fig_3_13_counts(inputs: dict) -> dict:
    """Fig. 3.13: images per point from the footprints, and n, k, N, m, c, s, M of the built system."""
    blk = fig_3_13_block(sigma=inputs.get("sigma_mm", 0.005), seed=inputs.get("seed", 313))
    system = correction_equation_system(blk)
    out = _system_counts(system)
    grid = images_per_point(blk).reshape(blk.grid)
    out.update({f"images per point, row {r + 1}": " ".join(map(str, row)) for r, row in enumerate(grid)})
    out["N12 pattern"] = normal_matrix_structure(system)["N12_pattern"]
    return out


# --- printed formulas ------------------------------------------------------------------------------
def _is_zero(M, size=600) -> bool:
    """Exact zero test of a sympy matrix/expression: every entry's numerator expands to 0.

    ``size``: term limit of the exact test's intermediate fractions (beyond it: expand the numerator).
    """
    return zero(M, lambda e: sp.expand(sp.numer(sp.together(e))) == 0, size=size)


def _ls_problem():
    """A generic weighted LSQ problem with 3 equations and 2 unknowns (all entries symbols)."""
    A = sp.Matrix(3, 2, sp.symbols("a0:6"))
    L = sp.Matrix(sp.symbols("l0:3"))
    P = sp.diag(*sp.symbols("p0:3", positive=True))
    d = sp.Matrix(sp.symbols("d0:2"))
    return A, L, P, d


def normal_equation_check(inputs: dict) -> dict:
    """(3.5.8)–(3.5.10) against the stationary point of Φ = (Aδ + L)ᵀP(Aδ + L), symbolically.

    ``inputs["form"]``: "3.5.8" — AᵀPAδ + AᵀPL is ½∇Φ; "3.5.9" — δ = −N⁻¹Lᴺ is the minimiser;
    "3.5.10" — δ = QLᴺ (Q = N⁻¹) as printed.
    """
    A, L, P, d = _ls_problem()
    V = A * d + L
    phi = (V.T * P * V)[0, 0]
    grad = sp.Matrix([sp.diff(phi, x) for x in d])
    N, LN = A.T * P * A, A.T * P * L
    best = N.LUsolve(-LN)                      # solves ½∇Φ = Nδ + Lᴺ = 0
    form = inputs["form"]
    if form == "3.5.8":
        ok = _is_zero(grad / 2 - (N * d + LN))
    elif form == "3.5.9":
        ok = _is_zero(-N.inv() * LN - best, size=4000)
    elif form == "3.5.10":
        ok = _is_zero(N.inv() * LN - best, size=4000)
    else:
        raise InputError(f"unknown form {form!r}")
    if not _is_zero(grad.subs(dict(zip(d, best))), size=4000):      # guard: it is the stationary point
        raise AssertionError("the reference minimiser does not zero the gradient")
    return {"printed_equals_derived": bool(ok)}


def _simp(e):
    return sp.cancel(sp.together(e))


def _partitioned_symbols():
    """Scalar blocks: N = [[a, b], [b, c]], Lᴺ = (l1, l2), the solution of (3.5.13) N·δ = Lᴺ."""
    a, b, c, l1, l2, x1, x2 = sp.symbols("a b c l1 l2 delta1 delta2")
    d1, d2 = sp.Matrix([[a, b], [b, c]]).LUsolve(sp.Matrix([l1, l2]))
    return a, b, c, l1, l2, x1, x2, _simp(d1), _simp(d2)


def _rational_partition(seed: int = 0):
    """An exact symmetric positive-definite 5×5 N split 3 + 2, and a rational Lᴺ."""
    rng = np.random.default_rng(seed)
    G = sp.Matrix(5, 5, [sp.Rational(int(v), 7) for v in rng.integers(-20, 20, 25)])
    N = G * G.T + sp.eye(5)
    LN = sp.Matrix([sp.Rational(k + 1, 3) for k in range(5)])
    return N, LN


def partitioned_check(inputs: dict) -> dict:
    """(3.5.13)–(3.5.16) and the derivation lines, symbolically (scalar blocks) and exactly (3 + 2 blocks).

    ``inputs["form"]``:

    * "3.5.13" — N·δ = Lᴺ with Lᴺ = AᵀPL as defined in (3.5.8): does it give the minimiser?
    * "3.5.14" — the second row as printed, N₁₁ᵀδ₁ + N₂₂δ₂ = L₂ᴺ, against the block product of (3.5.13).
    * "3.5.15-line" — N₁₂ᵀN₁₁⁻¹L₁ᴺ − N₁₂ᵀN₁₁⁻¹N₁₂δ₂ + N₂₂δ₂ − L₂ᴺ = 0 (line before (3.5.15)).
    * "3.5.15" — (N₁₂ᵀN₁₁⁻¹N₁₂ − N₂₂)δ₂ = L₂ᴺ − N₁₂ᵀN₁₁⁻¹L₁ᴺ as printed.
    * "3.5.16-line" — N₁₁δ₁ + N₁₂N₂₂⁻¹L₂ᴺ − N₁₂N₂₂⁻¹δ₁ − L₁ᴺ = 0 (line before (3.5.16)).
    * "3.5.16" — (N₁₁ − N₁₂N₂₂⁻¹N₁₂ᵀ)δ₁ = L₁ᴺ − N₁₂N₂₂⁻¹L₂ᴺ.

    (3.5.14)–(3.5.16) are judged against (3.5.13) as printed (its own right-hand side).
    """
    form = inputs["form"]
    a, b, c, l1, l2, x1, x2, d1, d2 = _partitioned_symbols()
    N, LN = _rational_partition()
    n11, n12, n22, L1, L2 = N[:3, :3], N[:3, 3:], N[3:, 3:], LN[:3, :], LN[3:, :]
    full = N.LUsolve(LN)
    if form == "3.5.13":
        # with Lᴺ = AᵀPL of (3.5.8) the minimiser is −N⁻¹Lᴺ; (3.5.13) gives +N⁻¹Lᴺ
        A, L, P, d = _ls_problem()
        Nn, LNn = A.T * P * A, A.T * P * L
        ok = _is_zero(Nn.LUsolve(LNn) - Nn.LUsolve(-LNn))
    elif form == "3.5.14":
        # block product of (3.5.13): second row is N12ᵀδ1 + N22δ2; printed: N11ᵀδ1 + N22δ2
        scalar = _simp((a * x1 + c * x2) - (b * x1 + c * x2)) == 0
        exact = (n11.T * full[:3, :]).shape == (n22 * full[3:, :]).shape      # 3-vector + 2-vector: undefined
        ok = scalar and exact
    elif form == "3.5.15-line":
        line = b / a * l1 - b / a * b * x2 + c * x2 - l2
        ok = _simp(line.subs(x2, d2)) == 0 and \
            _simp(sp.solve(line, x2)[0] - d2) == 0
    elif form == "3.5.15":
        printed = (n12.T * n11.inv() * n12 - n22).LUsolve(L2 - n12.T * n11.inv() * L1)
        scalar = _simp((l2 - b / a * l1) / (b / a * b - c) - d2) == 0
        ok = scalar and printed == full[3:, :]
    elif form == "3.5.16-line":
        line = a * x1 + b / c * l2 - b / c * x1 - l1
        ok = _simp(sp.solve(line, x1)[0] - d1) == 0
    elif form == "3.5.16":
        exact = (n11 - n12 * n22.inv() * n12.T).LUsolve(L1 - n12 * n22.inv() * L2) == full[:3, :]
        scalar = _simp((l1 - b / c * l2) / (a - b / c * b) - d1) == 0
        ok = scalar and exact
    else:
        raise InputError(f"unknown form {form!r}")
    return {"printed_equals_derived": bool(ok)}


def weighted_observation_check(inputs: dict) -> dict:
    """(3.5.17)–(3.5.19): δ + l = v with l = X⁰ − X is the residual of the adjusted value X⁰ + δ.

    The residual of a directly observed unknown is v = adjusted − measured = (X⁰ + δ) − X; the
    printed l = X⁰ − X (approximate − measured) makes δ + l exactly that.
    """
    X0, X, d = sp.symbols("X0 X delta")
    v = (X0 + d) - X
    return {"printed_equals_derived": bool(sp.expand(d + (X0 - X) - v) == 0)}


def count_formula_check(inputs: dict) -> dict:
    """(3.5.20)/(3.5.21) against the shape of correction equations built for several blocks.

    Fig. 3.10 (fixed control, k = determined points), fig. 3.13 (weighted XYZ control + GNSS), and
    fig. 3.13 variants with planimetric and height control points, GNSS on only some images and
    INS angles on some images. ``inputs["formula"]`` is "3.5.20" (columns) or "3.5.21" (rows).
    """
    which = inputs["formula"]
    cases = []
    b10 = fig_3_10_block(sigma=0.005)
    cases.append((correction_equation_system(b10), block_counts(b10)))
    b13 = fig_3_13_block(sigma=0.005)
    cases.append((correction_equation_system(b13), block_counts(b13)))
    # variant: control r1c1 planimetric, r5c4 height; GNSS on images 1–5 only; INS on images 2, 4, 6
    gnss = b13.gnss.copy()
    gnss[5:] = np.nan
    var = replace(b13, gnss=gnss)
    ins = np.full((8, 3), np.nan)
    ins[[1, 3, 5]] = b13.cameras[[1, 3, 5], 3:]
    system = correction_equation_system(var, planimetric=[0], height=[19], ins=ins)
    counts = dict(n=8, k=20, m=60, c=3, i=1, l=1, s=5, j=3)
    cases.append((system, counts))
    ok = True
    for system, k in cases:
        if which == "3.5.20":
            ok &= system.A.shape[1] == bundle_unknowns(k["n"], k["k"])
        elif which == "3.5.21":
            ok &= system.A.shape[0] == bundle_equations(k["m"], k["c"], k["i"], k["l"], k["s"], k["j"])
        else:
            raise InputError(f"unknown formula {which!r}")
    return {"printed_equals_derived": bool(ok)}
