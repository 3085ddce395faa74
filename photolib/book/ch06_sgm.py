"""Chapter 6, §6.4–6.5 (semi-global matching in image and object space): formula checks and
inline statements.

Adapters for the ``[[formula]]`` and ``[[example]]`` entries of ``textbook/ch06_sgm.toml``.
Formula adapters take the printed formula (as sympy text or as a reading of the text) in
``inputs`` and return ``{"printed_equals_derived": bool}``; the derivations are independent of
:mod:`photolib.sgm` (sympy, exhaustive enumeration of labellings on short chains). Statements are
checked by small seeded simulations on random-dot pairs with known disparity (conditions in the
entries' notes), which do call :mod:`photolib.sgm`.
"""

from __future__ import annotations

import itertools

import numpy as np
import sympy as sp

_S = {n: sp.Symbol(n, real=True) for n in ("D1", "D2", "P1", "P2", "p", "p_q", "Z", "Z_q", "dZ")}


def _parse(text, extra=None):
    local = dict(_S)
    local.update({"Abs": sp.Abs, "Max": sp.Max, "Min": sp.Min, "Piecewise": sp.Piecewise,
                  "Eq": sp.Eq, "Gt": sp.Gt, "sqrt": sp.sqrt})
    if extra:
        local.update(extra)
    return sp.parse_expr(str(text), local_dict=local)


def _ok(flag) -> dict:
    return {"printed_equals_derived": bool(flag)}


# --------------------------------------------------------------------------- costs (6.4.1), (6.5.1)
def cost_formula(inputs: dict) -> dict:
    """(6.4.1)/(6.5.1): is the printed cost a dissimilarity?

    Derived requirements of a matching cost c(D¹, D²) minimised by WTA/SGM: c ≥ 0, c = 0 iff
    D¹ = D², symmetric. The absolute difference |D¹ − D²| satisfies them; the check compares the
    printed expression with it (sympy, real symbols).
    """
    printed = _parse(inputs["cost"])
    derived = sp.Abs(_S["D1"] - _S["D2"])
    return _ok(sp.simplify(printed - derived) == 0)


def signed_cost_wta(inputs: dict) -> dict:
    """Simulation: WTA with the printed signed cost vs the absolute cost on a random-dot pair."""
    from .. import sgm
    left, right, disp = random_dot_pair(int(inputs.get("seed", 7)))
    D = int(inputs.get("max_disparity", 20))
    H, W = left.shape
    signed = np.full((H, W, D + 1), np.inf)
    for p in range(D + 1):
        signed[:, p:, p] = left[:, p:] - right[:, :W - p]
    d_signed = np.argmin(signed, axis=2)
    d_abs = sgm.winner_takes_all(sgm.cost_volume(left, right, D, method="ad"), subpixel=False)
    scored = np.s_[:, D:]
    return {"wta_correct_signed": float(np.mean(np.abs(d_signed - disp)[scored] <= 1)),
            "wta_correct_absolute": float(np.mean(np.abs(d_abs - disp)[scored] <= 1))}


# --------------------------------------------------------------------------- (6.4.2)–(6.4.4)
def _chain_energy(C, labels, P1, P2, penalty):
    e = sum(C[i][l] for i, l in enumerate(labels))
    for a, b in zip(labels[:-1], labels[1:]):
        e += penalty(a - b, P1, P2)
    return e


def _iverson(delta, P1, P2):
    return P1 * (abs(delta) == 1) + P2 * (abs(delta) > 1)


def _recursion(C, P1, P2, normalise=True):
    """(6.4.3) along a chain; ``normalise`` keeps the − min_k L term."""
    L = [list(C[0])]
    for c in C[1:]:
        prev = L[-1]
        m = min(prev)
        D = len(c)
        row = []
        for p in range(D):
            cands = [prev[p], m + P2]
            if p > 0:
                cands.append(prev[p - 1] + P1)
            if p < D - 1:
                cands.append(prev[p + 1] + P1)
            row.append(c[p] + min(cands) - (m if normalise else 0))
        L.append(row)
    return L


def energy_formula(inputs: dict) -> dict:
    """(6.4.2) with Iverson brackets vs the recursion (6.4.3) on short chains (exact integers).

    On one path the energy E(p) = Σ C + Σ P₁[|p − p_q| = 1] + Σ P₂[|p − p_q| > 1] is minimised
    exactly by the recursion without its − min term (dynamic programming): min over all
    labellings of E equals min_p L(end, p). ``inputs["penalty"]`` is the reading of the
    brackets: ``"iverson"`` (the formula) or ``"text"`` (the sentence after it: "P₁ = 1 if
    |p − p_q| = 1, otherwise P₁ = 0", i.e. the penalty fixed at 1 whatever P₁ is).
    """
    rng = np.random.default_rng(int(inputs.get("seed", 1)))
    reading = inputs.get("penalty", "iverson")
    pen = _iverson if reading == "iverson" else (lambda d, P1, P2: 1 * (abs(d) == 1) + P2 * (abs(d) > 1))
    ok = True
    for _ in range(int(inputs.get("trials", 6))):
        n, D = 4, 4
        C = rng.integers(0, 20, (n, D)).tolist()
        P1, P2 = 3, 11
        best = min(_chain_energy(C, lab, P1, P2, pen) for lab in itertools.product(range(D), repeat=n))
        ok &= best == min(_recursion(C, P1, P2, normalise=False)[-1])
    return _ok(ok)


def recursion_formula(inputs: dict) -> dict:
    """(6.4.3): L_r with the − min_k term has the argmin of the unnormalised recursion, whose
    minimum is the chain minimum of (6.4.2) (exhaustive check on random integer chains), and
    its values differ from it by a constant per pixel."""
    rng = np.random.default_rng(int(inputs.get("seed", 2)))
    ok = True
    for _ in range(int(inputs.get("trials", 6))):
        C = rng.integers(0, 20, (5, 5)).tolist()
        Ln = _recursion(C, 2, 9, True)
        Lu = _recursion(C, 2, 9, False)
        for a, b in zip(Ln, Lu):
            diff = np.array(b) - np.array(a)
            ok &= bool(np.all(diff == diff[0])) and int(np.argmin(a)) == int(np.argmin(b))
        best = min(_chain_energy(C, lab, 2, 9, _iverson) for lab in itertools.product(range(5), repeat=5))
        ok &= best == min(Lu[-1])
    return _ok(ok)


def previous_pixel_formula(inputs: dict) -> dict:
    """(6.4.3) text: x_r = x − r, y_r = y − r. With one scalar step r ∈ {−1, 1} subtracted from
    both coordinates only the 2 diagonal predecessors arise; the derived form (x, y) − r with the
    vector r = (r_x, r_y) over the 8 neighbours gives 8 distinct predecessors."""
    if inputs.get("reading") == "scalar":
        preds = {(-r, -r) for r in (-1, 1)}
    else:
        preds = {(-rx, -ry) for rx in (-1, 0, 1) for ry in (-1, 0, 1) if (rx, ry) != (0, 0)}
    return _ok(len(preds) == 8)


def printed_directions(inputs: dict) -> dict:
    """The printed list r₁ = (1, 0), r₂ = (1, 1), …, r₈ = (1, −1): the 8 neighbours in 45° steps,
    the same set as photolib's 8 paths."""
    from .. import sgm
    angles = np.deg2rad(45.0 * np.arange(8))
    listed = [(int(np.sign(np.round(np.cos(t), 9))), int(np.sign(np.round(np.sin(t), 9)))) for t in angles]
    as_printed = listed[0] == (1, 0) and listed[1] == (1, 1) and listed[-1] == (1, -1)
    library = {(dx, dy) for dy, dx in sgm._DIRECTIONS[8]}
    return {"n_paths": len(set(listed)) if as_printed and set(listed) == library else -1}


def sum_formula(inputs: dict) -> dict:
    """(6.4.4): S = Σ_r L_r — photolib's aggregation equals the sum of the 8 single-path costs."""
    from .. import sgm
    rng = np.random.default_rng(int(inputs.get("seed", 3)))
    C = rng.uniform(0, 10, (7, 8, 5)).astype(np.float32)
    S = sgm.aggregate_costs(C, 1.0, 4.0)
    total = sum(sgm.path_cost(C, (dx, dy), 1.0, 4.0) for dy, dx in sgm._DIRECTIONS[8])
    return _ok(np.allclose(S, total, rtol=1e-5, atol=1e-3))


# --------------------------------------------------------------------------- §6.5
def voxel_energy_formula(inputs: dict) -> dict:
    """(6.5.2): the brackets [|Z − Z_q| = 1], [|Z − Z_q| > 1] with Z in metres equal the step
    penalties [|Z − Z_q| = ΔZ], [|Z − Z_q| > ΔZ] for every ΔZ only if the printed threshold is ΔZ."""
    threshold = _parse(inputs["threshold"])
    ok = True
    for dz in (sp.Rational(1, 4), sp.Rational(1, 2), 1, 2):
        for k in range(0, 4):
            diff = k * dz
            printed = (sp.Eq(diff, threshold.subs(_S["dZ"], dz)), sp.Gt(diff, threshold.subs(_S["dZ"], dz)))
            derived = (k == 1, k > 1)
            ok &= bool(printed[0]) == derived[0] and bool(printed[1]) == derived[1]
    return _ok(ok)


def voxel_recursion_formula(inputs: dict) -> dict:
    """(6.5.3) with labels Z = iΔZ: the recursion over Z ± ΔZ equals (6.4.3) on the indices i;
    the last term must be min over k of L(X_r, Y_r, kΔZ) (``inputs["last_min_index"]``)."""
    if inputs.get("last_min_index", "k") != "k":
        return _ok(False)
    rng = np.random.default_rng(4)
    C = rng.integers(0, 20, (5, 6)).tolist()
    dz = 0.25
    Zs = [i * dz for i in range(6)]
    L = [dict(zip(Zs, C[0]))]
    for c in C[1:]:
        prev = L[-1]
        m = min(prev.values())
        row = {}
        for i, Z in enumerate(Zs):
            cands = [prev[Z], m + 9]
            if Z - dz in prev:
                cands.append(prev[Z - dz] + 2)
            if Z + dz in prev:
                cands.append(prev[Z + dz] + 2)
            row[Z] = c[i] + min(cands) - m
        L.append(row)
    ref = _recursion(C, 2, 9, True)
    return _ok(all(np.allclose([r[Z] for Z in Zs], q) for r, q in zip(L, ref)))


def ncc_cost_formula(inputs: dict) -> dict:
    """(6.5.5): the printed 1 − Σ(D¹ − D̄¹)(D² − D̄²)/√(Σ(D¹ − D̄¹)² Σ(D² − D̄²)²) equals 1 − Pearson's r
    (exact rationals, n = 5), lies in [0, 2], and matches photolib's NCC cost at one pixel."""
    from .. import sgm
    n = int(inputs.get("n", 5))
    a = sp.symbols(f"a0:{n}", real=True)
    b = sp.symbols(f"b0:{n}", real=True)
    ma, mb = sum(a) / n, sum(b) / n
    printed = 1 - sum((ai - ma) * (bi - mb) for ai, bi in zip(a, b)) / sp.sqrt(
        sum((ai - ma) ** 2 for ai in a) * sum((bi - mb) ** 2 for bi in b))
    rng = np.random.default_rng(5)
    ok = True
    for _ in range(3):
        va, vb = rng.integers(0, 255, n), rng.integers(0, 255, n)
        val = printed.subs(dict(zip(a, [sp.Integer(int(v)) for v in va])) | dict(zip(b, [sp.Integer(int(v)) for v in vb])))
        ok &= abs(float(val) - (1 - np.corrcoef(va, vb)[0, 1])) < 1e-12 and 0 <= float(val) <= 2
    left = rng.uniform(0, 255, (9, 20))
    right = rng.uniform(0, 255, (9, 20))
    C = sgm.cost_volume(left, right, 3, method="ncc", window=5)
    wl, wr = left[2:7, 8:13].ravel(), right[2:7, 6:11].ravel()
    ok &= abs(C[4, 10, 2] - (1 - np.corrcoef(wl, wr)[0, 1])) < 1e-4
    return _ok(ok)


# --------------------------------------------------------------------------- statements
def random_dot_pair(seed=7, noise=2.0):
    """The guide's random-dot stereogram: 80×120, background p = 5, a 30×40 square at p = 12."""
    from scipy import ndimage as ndi
    rng = np.random.default_rng(seed)
    H, W = 80, 120
    right = ndi.gaussian_filter(rng.uniform(0, 255, (H, W)), 0.7)
    right = (right - right.min()) / np.ptp(right) * 255
    disp = np.full((H, W), 5.0)
    disp[25:55, 40:80] = 12.0
    Y, X = np.mgrid[0:H, 0:W].astype(float)
    left = ndi.map_coordinates(right, [Y, X - disp], order=1, mode="nearest") + rng.normal(0, noise, (H, W))
    return left, right, disp


def wta_vs_sgm(inputs: dict) -> dict:
    """Fig. 6.6 б: WTA on the raw AD cost is only a first approximation; SGM with penalties
    scaled to the cost (and with the text's P₁ = 1, P₂ = 2) on the same cost."""
    from .. import sgm
    left, right, disp = random_dot_pair(int(inputs.get("seed", 7)))
    D = 20
    C = sgm.cost_volume(left, right, D, method="ad")
    scored = np.s_[:, D:]

    def share(d):
        return float(np.mean(np.abs(d - disp)[scored] <= 1))

    wta = share(sgm.winner_takes_all(C, subpixel=False))
    scaled = share(sgm.winner_takes_all(sgm.aggregate_costs(C, *inputs["penalties"]), subpixel=False))
    unit = share(sgm.winner_takes_all(sgm.aggregate_costs(C, 1.0, 2.0), subpixel=False))
    return {"sgm_better": "yes" if scaled > wta + 0.1 else "no", "wta_correct": wta,
            "sgm_correct": scaled, "sgm_unit_penalties_correct": unit}


def third_term_no_effect(inputs: dict) -> dict:
    """(6.4.3): the − min_k L_r term changes no argmin (exhaustive on random chains)."""
    ok = recursion_formula({"seed": inputs.get("seed", 6), "trials": 4})["printed_equals_derived"]
    return {"argmin_unchanged": "yes" if ok else "no"}


def transcribed(inputs: dict) -> dict:
    """Pure specifications: nothing to compute."""
    return {}
