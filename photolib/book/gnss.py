"""Adapters for the GNSS-centres paper (Dobrynin & Pimshina, seed ``001_723f59c162a2adba.txt``).

Each function takes the ``inputs`` table of an entry of ``textbook/ch02.toml`` (ids ``gnss-…``)
and returns ``{quantity: value}`` (examples) or ``{"printed_equals_derived": bool}``
(formulas). The paper prints no data set: every example runs on the synthetic stand-in
:func:`photolib.gnss_centres.synthetic_pair`, defined by the entry's inputs.
"""

from __future__ import annotations

import numpy as np
import sympy as sp

from .. import derivations as D
from .. import gnss_centres as G
from ._exact import lambdify, zero

_TOL = 1e-9


# --- formulas ----------------------------------------------------------------------------------------
def _numeric_equal(e1, e2, symbols, seed=0, n=40) -> bool:
    """Evaluate two expressions at ``n`` random points (angles ±0.5 rad, coordinates ±100) and compare."""
    rng = np.random.default_rng(seed)
    f1 = lambdify(symbols, e1, "numpy")
    f2 = lambdify(symbols, e2, "numpy")
    vals = []
    for s in symbols:
        name = str(s)
        if name.startswith(("alpha", "omega", "chi")):
            vals.append(rng.uniform(-0.5, 0.5, n))
        elif name in ("f",):
            vals.append(rng.uniform(80, 160, n))
        elif name.startswith("B_"):
            vals.append(rng.uniform(-800, 800, n))
        elif name in ("Z_S",):
            vals.append(rng.uniform(1200, 2000, n))
        elif name in ("X_S", "Y_S", "X", "Y"):
            vals.append(rng.uniform(-3000, 3000, n))
        else:
            vals.append(rng.uniform(-100, 100, n))
    a = np.broadcast_to(np.asarray(f1(*vals), dtype=float), (n,))
    b = np.broadcast_to(np.asarray(f2(*vals), dtype=float), (n,))
    scale = np.maximum(np.abs(a), np.abs(b)).max() or 1.0
    return bool(np.all(np.abs(a - b) <= _TOL * scale))


def _free(*exprs):
    return sorted(set().union(*(sp.sympify(e).free_symbols for e in exprs)), key=str)


def _cosine_check(keys) -> bool:
    printed, derived = D.printed_gnss_cosine_partials(), D.derived_gnss_cosine_partials()
    return all(k in printed and zero(printed[k] - derived[k]) for k in keys)


def _coef_check(printed: dict, derived: dict, keys) -> bool:
    return all(_numeric_equal(printed[k], derived[k], _free(printed[k], derived[k])) for k in keys)


def formula_check(inputs: dict) -> dict:
    """Compare one printed formula of the paper with its sympy derivation (``inputs["item"]``)."""
    item = inputs["item"]
    if item == "rotation":                                             # (6)
        ok = zero(D.printed_gnss_direction_cosines() - D.gnss_rotation_symbolic())
    elif item == "coplanarity-expansion":                              # line 127
        X1s, Y1s, Z1s, X2s, Y2s, Z2s = sp.symbols("X1 Y1 Z1 X2 Y2 Z2")
        det = sp.Matrix([[D.B_Y, D.B_X, D.B_Z], [X1s, Y1s, Z1s], [X2s, Y2s, Z2s]]).det()
        printed = (D.B_Y * (Y1s * Z2s - Z1s * Y2s) - D.B_X * (X1s * Z2s - Z1s * X2s)
                   + D.B_Z * (X1s * Y2s - Y1s * X2s))
        ok = sp.expand(det - printed) == 0
    elif item == "collinearity":                                       # (3) with (4): image of a ground point
        ok = _collinearity_round_trip()
    elif item.startswith("cosines:"):                                  # (7)
        keys = [tuple(k.split("/")) for k in item.split(":")[1].split(",")]
        ok = _cosine_check(keys)
    elif item.startswith("vector:"):                                   # (8)
        keys = item.split(":")[1].split(",")
        p, d = D.printed_gnss_vector_partials(), D.derived_gnss_vector_partials()
        ok = all(zero(p[k] - d[k]) for k in keys)
    elif item.startswith("coplanarity:"):                              # (5): printed structure, true A…F
        keys = item.split(":")[1].split(",")
        d1 = D.derived_gnss_vector_partials(D.x1, D.y1, D.alpha1, D.omega1, D.chi1)
        d2 = D.derived_gnss_vector_partials(D.x2, D.y2, D.alpha2, D.omega2, D.chi2)
        ok = _coef_check(D.printed_gnss_coplanarity_coefficients(d1, d2), D.derived_gnss_coplanarity_coefficients(), keys)
    elif item.startswith("ground:"):                                   # (9): printed structure, true A…F
        keys = item.split(":")[1].split(",")
        ok = _coef_check(D.printed_gnss_ground_coefficients(D.derived_gnss_vector_partials()),
                         D.derived_gnss_ground_coefficients(), keys)
    elif item == "intersection":                                       # line 212
        ok = _intersection_forms_equal()
    elif item == "initial-chi":                                        # lines 177–179
        ok = _initial_chi_rule()
    else:
        raise KeyError(f"unknown formula item {item!r}")
    return {"printed_equals_derived": bool(ok)}


def corrected_formula_check(inputs: dict) -> dict:
    """The corrected forms recorded in the errata equal the derivation (used by the tests)."""
    item = inputs["item"]
    if item == "cosines":
        p = D.printed_gnss_cosine_partials()
        d = D.derived_gnss_cosine_partials()
        a1, a2, a3, b1, b2, b3, c1, c2, c3 = D.printed_gnss_direction_cosines()
        fixes = {("a1", "omega"): a3 * sp.sin(D.chi), ("c2", "chi"): -c1}
        ok = all(zero(v - d[k]) for k, v in fixes.items()) and len({**p, **fixes}) == 27
    elif item == "vector":
        c, d = D.corrected_gnss_vector_partials(), D.derived_gnss_vector_partials()
        ok = all(zero(c[k] - d[k]) for k in d)
    elif item == "coplanarity":
        ok = _coef_check(D.corrected_gnss_coplanarity_coefficients(), D.derived_gnss_coplanarity_coefficients(),
                         D.GNSS_COEFFICIENTS)
    elif item == "ground":
        c, d = D.corrected_gnss_ground_coefficients(), D.derived_gnss_ground_coefficients()
        ok = all(zero(c[k] - d[k]) for k in d)
    else:
        raise KeyError(item)
    return {"printed_equals_derived": bool(ok)}


def _collinearity_round_trip() -> bool:
    """Project ground points into an image with (6) (camera coordinates q = Aᵀ(ΔY, ΔX, ΔZ)), then
    apply (4) and (3) as printed: X, Y must come back (numerically at random poses)."""
    rng = np.random.default_rng(5)
    for _ in range(20):
        ang = rng.uniform(-0.3, 0.3, 3) + np.array([0, 0, rng.uniform(0, 2 * np.pi)])
        S = np.array([rng.uniform(-1e4, 1e4), rng.uniform(-1e4, 1e4), rng.uniform(1000, 3000)])
        P = np.column_stack([S[0] + rng.uniform(-800, 800, 5), S[1] + rng.uniform(-800, 800, 5),
                             rng.uniform(0, 300, 5)])
        A = np.array(D.printed_gnss_direction_cosines().subs({D.alpha: ang[0], D.omega: ang[1], D.chi: ang[2]}),
                     dtype=float)
        f, x0, y0 = 100.0, 0.01, -0.02
        q = np.column_stack([P[:, 1] - S[1], P[:, 0] - S[0], P[:, 2] - S[2]]) @ A
        x, y = x0 - f * q[:, 0] / q[:, 2], y0 - f * q[:, 1] / q[:, 2]
        Xs, Ys, Zs = (np.array([x - x0, y - y0, np.full(5, -f)]).T @ A.T).T          # (4)
        Yc = (P[:, 2] - S[2]) * Xs / Zs + S[1]                                        # (3)
        Xc = (P[:, 2] - S[2]) * Ys / Zs + S[0]
        if not (np.allclose(Xc, P[:, 0], atol=1e-8) and np.allclose(Yc, P[:, 1], atol=1e-8)):
            return False
    return True


def _intersection_forms_equal() -> bool:
    """sympy: for intersecting rays, S₁* + N r₁ = S₂* + N′ r₂ (image frame, b = (B_Y, B_X, B_Z)),
    each printed form of N simplifies to N."""
    N, Np = sp.symbols("N N'", positive=True)
    forms, (X1s, Y1s, Z1s, X2s, Y2s, Z2s) = D.printed_gnss_intersection_scale()
    b = sp.Matrix([D.B_Y, D.B_X, D.B_Z])
    r1 = sp.Matrix([X1s, Y1s, Z1s])
    r2 = (N * r1 - b) / Np
    sub = {X2s: r2[0], Y2s: r2[1], Z2s: r2[2]}
    return all(zero(num.subs(sub) / den.subs(sub) - N) for num, den in forms)


def _initial_chi_rule() -> bool:
    """For direction angles in (0°, 90°) and (90°, 180°), the printed χ makes the image x axis
    (A·(1, 0, 0) at α = ω = 0, in (X*, Y*) = (east, north)) point along the base."""
    for az in np.r_[np.linspace(1, 89, 23), np.linspace(91, 179, 23)]:
        chi = 90.0 - az if az < 90 else 450.0 - az
        axis = G.rotation_aok(0.0, 0.0, np.radians(chi)) @ np.array([1.0, 0.0, 0.0])
        base = np.array([np.sin(np.radians(az)), np.cos(np.radians(az)), 0.0])       # (east, north, up)
        if not np.allclose(axis, base, atol=1e-12):
            return False
    return True


# --- examples on the synthetic stand-in ------------------------------------------------------------------
def _pair(inputs, az, seed=None, **extra):
    keys = ("f", "H", "base", "dZ_S", "tilt_deg", "chi_offset_deg", "across", "relief")
    kw = {k: inputs[k] for k in keys if k in inputs}
    kw.update(extra)
    return G.synthetic_pair(az, seed=inputs.get("seed", 0) if seed is None else seed, **kw)


def equation_count(inputs: dict) -> dict:
    """Lines 17, 184, 200: unknowns, the rank of coplanarity alone, the equation count, the rank with control."""
    sp_ = _pair(inputs, inputs["azimuth_deg"])
    n = inputs["tie_points"]
    xy1, xy2 = sp_.xy1[:n], sp_.xy2[:n]
    C, c1, c2 = sp_.control_args
    B, L = G.correction_equations(sp_.angles, xy1, xy2, sp_.S1, sp_.S2, C, c1, c2, sp_.f)
    B0, _ = G.correction_equations(sp_.angles, sp_.xy1, sp_.xy2, sp_.S1, sp_.S2, np.zeros((0, 3)),
                                   np.zeros((0, 2)), np.zeros((0, 2)), sp_.f)
    scaled = lambda M: M / np.linalg.norm(M, axis=1, keepdims=True)  # noqa: E731
    rank = lambda M: int(np.linalg.matrix_rank(scaled(M), tol=1e-8))  # noqa: E731
    return {"unknown angles": len(G.ANGLE_NAMES),
            "rank of the coplanarity equations alone": rank(B0),
            "equations (5 tie points, 1 control point)": int(len(L)),
            "rank with one control point": rank(B)}


def _convergence(inputs, partials):
    out = {}
    for az in inputs["azimuths_deg"]:
        iters, ok = [], True
        for seed in range(inputs["trials"]):
            sp_ = _pair(inputs, az, seed=seed)
            h = G.iteration_history(*sp_.args, partials=partials, tol=inputs["tol"], max_iter=inputs["max_iter"])
            err = np.max(np.abs(h.angles - sp_.angles)) if h.converged else np.inf
            good = h.converged and err < np.radians(inputs["accept_arcsec"] / 3600)
            ok &= good and h.iterations <= 8
            iters.append(h.iterations if good else np.inf)
            if not good:        # both outputs are now fixed ("no", "no convergence"): the other pairs cannot change them
                break
        label = f"az {az:g}°"
        out[f"converges within 8 iterations [{label}]"] = "yes" if ok else "no"
        worst = max(iters)
        out[f"iterations, worst of {inputs['trials']} pairs [{label}]"] = int(worst) if np.isfinite(worst) else "no convergence"
    return out


def convergence(inputs: dict) -> dict:
    """Line 202 ("6–8 approximations usually suffice"): the derived partials on the stand-in."""
    return _convergence(inputs, "derived")


def convergence_as_printed(inputs: dict) -> dict:
    """The same runs with the paper's printed partials (5), (8), (9)."""
    return _convergence(inputs, "printed")


def intersection_forms(inputs: dict) -> dict:
    """Line 212: which of the three printed forms of N gives N and which is 0/0, by flight direction."""
    out = {}
    for name, az in inputs["flights"].items():
        sp_ = _pair(inputs, az, dZ_S=0.0)
        r1 = G.image_space_vectors(sp_.xy1, sp_.angles[:3], sp_.f)
        r2 = G.image_space_vectors(sp_.xy2, sp_.angles[3:], sp_.f)
        num, den = G.intersection_forms(r1, r2, sp_.S2 - sp_.S1)
        N_true = (sp_.ground[:, 2] - sp_.S1[2]) / r1[:, 2]
        size = (np.linalg.norm(r1, axis=1) * np.linalg.norm(r2, axis=1))[:, None]
        zero = np.abs(den) < 1e-12 * size
        with np.errstate(divide="ignore", invalid="ignore"):
            good = np.abs(num / den - N_true[:, None]) <= 1e-9 * np.abs(N_true[:, None])
        for k in range(3):
            if zero[:, k].any():
                value = f"0/0 at {int(zero[:, k].sum())} of {len(zero)} points"
            elif good[:, k].all():
                value = "N"
            else:
                value = "wrong"
            out[f"form {k + 1} [{name}]"] = value
    return out
