"""Chapter 3, §3.2–§3.4 entries: inputs from ``textbook/ch03.toml`` → library calls → named quantities.

The book prints no coordinates for §3.2–§3.4; its numbers are counts. The count adapters
rebuild the block layouts as synthetic blocks (:func:`photolib.strip_triangulation.layout_block`),
build the actual correction equations and read N and M off the design matrix.
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np
import sympy as sp

from .. import strip_triangulation as st
from ..synthetic import TIE
from ..derivations import rotation_matrix_symbolic
from ._exact import zero


@lru_cache(maxsize=None)
def _fig38():
    """Fig. 3.8: 2 strips × 4 images (3 models each), 60 % forward / 30 % side overlap."""
    blk = st.layout_block(2, 4, side_overlap=0.3, seed=38)
    models = st.layout_models(blk)
    control_at = [(0, 0.5), (3, 0.5), (3, -0.5), (0, -1.5), (3, -1.5)]   # 4 corners + middle right [2]
    control = {p: blk.truth([p])[0] for p in (blk.point_at(*g) for g in control_at)}
    gnss = {st.centre_id(k): blk.cameras[k, :3] for k in range(len(blk.cameras))}
    return blk, models, control, gnss, st.grid_adjacency(2, 3)


@lru_cache(maxsize=None)
def _fig37():
    """A 3-strip block consistent with the text of fig. 3.7 (the figure itself is lost in the OCR):
    7 tie points in each of the two inter-strip overlaps (m = 14, two of them control points),
    four control corners measured in one strip and the two overlap control points measured in
    two strips (k = 4 + 2·2 = 8)."""
    blk = st.layout_block(3, 7, side_overlap=0.3, principal_rows=True, seed=37)
    strips = [st.continuation_strip(st.layout_models(blk, [s]), name=f"strip {s + 1}").model for s in range(3)]
    control_at = [(0, 0.5), (6, 0.5), (0, -2.5), (6, -2.5), (3, -0.5), (3, -1.5)]
    control = {p: blk.truth([p])[0] for p in (blk.point_at(*g) for g in control_at)}
    return blk, strips, control


def fig37_counts(inputs: dict) -> dict:
    """§3.3, fig. 3.7: N = 7n (3.3.6), M = 3m + 3k (3.3.7), from the design of the block."""
    _, strips, control = _fig37()
    x0 = st.initial_transforms(strips, control)
    B, _, _ = st.unit_equations(strips, x0, control)
    c = st.structure_counts(strips, control)
    N, M = st.count_independent_strips(inputs["n"], inputs["m"], inputs["k"])
    if (c["n"], c["m"], c["k"]) != (inputs["n"], inputs["m"], inputs["k"]) or B.shape != (M, N):
        raise AssertionError(f"the synthetic fig. 3.7 block does not have the printed structure: {c}, {B.shape}")
    return {"N": int(B.shape[1]), "M": int(B.shape[0]), "m": c["m"], "k": c["k"]}


def fig38_counts(inputs: dict) -> dict:
    """§3.4, fig. 3.8: N, M without and with GNSS centres, from the design of the rebuilt block."""
    _, models, control, gnss, adjacency = _fig38()
    x0 = st.initial_transforms(models, control)
    B, _, _ = st.unit_equations(models, x0, control, None, adjacency)
    Bg, _, rows = st.unit_equations(models, x0, control, gnss, adjacency)
    c = st.structure_counts(models, control, gnss, adjacency)
    return {"N": int(B.shape[1]), "m": c["m"], "k": c["k"], "M": int(B.shape[0]),
            "S": sum(r.kind == "gnss" for r in rows), "M_gnss": int(Bg.shape[0])}


def polynomial_control(inputs: dict) -> dict:
    """§3.2: number of coefficients of (3.2.4) and the least number of full control points.

    The coefficients are counted from the design of (3.2.5); the minimum is the smallest number
    of points of the fig. 3.5 scheme (2 at the start, 1 in the middle, 2 at the end, then more)
    whose design has full rank.
    """
    L = inputs["strip_length_m"]
    w = inputs["strip_width_m"]
    scheme = [(0, w / 2), (0, -w / 2), (L / 2, 0), (L, w / 2), (L, -w / 2), (L / 4, w / 3), (3 * L / 4, -w / 3)]
    XY = np.array(scheme)
    D = st._monomials(XY, XY.mean(axis=0), L / 2)
    n_coef = 3 * D.shape[1]
    minimum = next(n for n in range(1, len(XY) + 1) if 3 * np.linalg.matrix_rank(D[:n]) == n_coef)
    return {"coefficients": n_coef, "min_points": minimum}


def gnss_datum(inputs: dict) -> dict:
    """§3.4: least number of ground control points with GNSS centres, block vs single strip.

    For 0, 1, 2, … full control points (off the flight line) build the correction equations and
    take the first number that gives a design of full rank 7n.
    """
    def minimum(blk, models, adjacency):
        gnss = {st.centre_id(k): blk.cameras[k, :3] for k in range(len(blk.cameras))}
        candidates = [p for p, kind in zip(blk.point_labels, blk.kind) if kind == TIE]
        for n_ctl in range(len(candidates)):
            control = {int(p): blk.truth([int(p)])[0] for p in candidates[:n_ctl]} or None
            try:
                x0 = st.initial_transforms(models, control, gnss)
            except Exception:      # noqa: BLE001 — no start, no datum
                continue
            B, _, _ = st.unit_equations(models, x0, control, gnss, adjacency)
            s = np.linalg.svd(B / np.linalg.norm(B, axis=0), compute_uv=False)
            if s[-1] > inputs["rcond"] * s[0]:
                return n_ctl
        return None

    blk, models, _, _, adjacency = _fig38()
    strip = st.layout_block(1, 4, seed=38)
    return {"block": minimum(blk, models, adjacency), "strip": minimum(strip, st.layout_models(strip), None)}


# --- printed formulas -------------------------------------------------------------------------------------------
def auxiliary_rotation(inputs: dict) -> dict:
    """(3.2.6)/(3.2.7): the printed A_κM and A_κMᵀ against the κ rotation of (1.3.2)."""
    k = sp.Symbol("kappa_M", real=True)
    printed = sp.Matrix([[sp.cos(k), -sp.sin(k), 0], [sp.sin(k), sp.cos(k), 0], [0, 0, 1]])
    printed_T = sp.Matrix([[sp.cos(k), sp.sin(k), 0], [-sp.sin(k), sp.cos(k), 0], [0, 0, 1]])
    derived = rotation_matrix_symbolic("wak", 0, 0, k)
    ok = zero(printed - derived) and zero(printed_T - derived.T)
    ok = ok and zero(printed * printed_T - sp.eye(3))   # (3.2.7) undoes (3.2.6)
    return {"printed_equals_derived": bool(ok)}


def image_rotation_chain(inputs: dict) -> dict:
    """(3.4.5) A = A_M·A′: the image ray r in the object frame by (2.10.4) after the model frame."""
    w, a, k, w1, a1, k1 = sp.symbols("omega_M alpha_M kappa_M omega' alpha' kappa'", real=True)
    x, y, f = sp.symbols("x y f", real=True)
    AM = rotation_matrix_symbolic(inputs["order"], w, a, k)
    A1 = rotation_matrix_symbolic(inputs["order"], w1, a1, k1)
    r = sp.Matrix([x, y, -f])
    # direction of the ray in the object frame: model direction A′r turned by A_M (the t > 0 factor drops out)
    derived_direction = AM * (A1 * r)
    printed = (AM * A1) * r
    return {"printed_equals_derived": zero(derived_direction - printed)}


def angle_extraction(inputs: dict) -> dict:
    """(3.4.6): do the printed ω′, α′, κ′ = arctg(−a23/a33), arcsin a13, arctg(−a12/a11) of
    A = A_M A′ equal the angles ω′, α′, κ′ of A′ (as the primes say)? Checked numerically at a
    generic A_M; with ``primes = false`` the same expressions are compared with the angles of A."""
    from ..rotation import rotation_matrix
    rng = np.random.default_rng(0)
    ok = True
    for _ in range(5):
        m, rel = rng.uniform(-0.3, 0.3, 3), rng.uniform(-0.3, 0.3, 3)
        A = rotation_matrix(*m, "wak") @ rotation_matrix(*rel, "wak")          # (3.4.5)
        printed = np.array([np.arctan(-A[1, 2] / A[2, 2]), np.arcsin(A[0, 2]), np.arctan(-A[0, 1] / A[0, 0])])
        if inputs["primes"]:
            target = rel                                                          # angles of A′
        else:
            from ..rotation import rotation_angles
            target = np.array(rotation_angles(A, "wak"))                          # angles of A
        ok = ok and np.allclose(printed, target, atol=1e-12)
    # and symbolically: the expressions invert (1.3.2) for |ω|, |κ| < 90°
    w, a, k = sp.symbols("omega alpha kappa", real=True)
    R = rotation_matrix_symbolic("wak", w, a, k)
    sym_ok = zero(-R[1, 2] / R[2, 2] - sp.tan(w)) and zero(R[0, 2] - sp.sin(a)) \
        and zero(-R[0, 1] / R[0, 0] - sp.tan(k))
    return {"printed_equals_derived": bool(ok and sym_ok)}


def fig38_formula(inputs: dict) -> dict:
    """§3.4 example: the printed "M = 2m + 3k" against M = 3m + 3k + 2i + l + S with i = l = S = 0."""
    m, k, i, l, S = sp.symbols("m k i l S", integer=True, nonnegative=True)
    derived = (3 * m + 3 * k + 2 * i + l + S).subs({i: 0, l: 0, S: 0})
    printed = sp.sympify(inputs["printed"], locals={"m": m, "k": k})
    return {"printed_equals_derived": zero(printed - derived)}
