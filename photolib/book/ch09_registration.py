"""Chapter 9, §9.5–9.6 (orientation and registration of scans): formula checks and inline statements.

Adapters for the entries of ``textbook/ch09_registration.toml``. The formula adapter compares the
printed (9.5.1) with :func:`photolib.derivations.registration.rigid_transform_symbolic`; the
statements are checked by the rank of the correction equations of :mod:`photolib.registration`
on hand-placed targets and by a seeded simulation (conditions in the entries' notes).
"""

from __future__ import annotations

import numpy as np
import sympy as sp

from ..derivations import registration as dreg
from ..derivations.rotation import rotation_matrix_symbolic
from ..derivations.symbols import X0, Y0, Z0, alpha, kappa, omega


def _ok(flag) -> dict:
    return {"printed_equals_derived": bool(flag)}


def rigid_formula(inputs: dict) -> dict:
    """(9.5.1): the printed X = X₀ + A·X′ against the derivation, for both rotation orders.

    The printed entries are parsed with symbols X_0, Y_0, Z_0, X', Y', Z' and a_ij (the elements of
    A); A is then substituted by the sympy rotation matrix and the result must equal
    :func:`rigid_transform_symbolic`; additionally the check confirms that the transform has no
    scale (|X − X₀| = |X′| identically).
    """
    names = {"X_0": X0, "Y_0": Y0, "Z_0": Z0, "Xp": dreg.SCANNER_SYMBOLS[0], "Yp": dreg.SCANNER_SYMBOLS[1],
             "Zp": dreg.SCANNER_SYMBOLS[2]}
    a = {f"a{i}{j}": sp.Symbol(f"a{i}{j}", real=True) for i in (1, 2, 3) for j in (1, 2, 3)}
    printed = [sp.parse_expr(t, local_dict={**names, **a}) for t in inputs["XYZ"]]
    ok = len(printed) == 3
    for order in ("kaw", "wak"):
        A = rotation_matrix_symbolic(order, omega, alpha, kappa)
        sub = {a[f"a{i}{j}"]: A[i - 1, j - 1] for i in (1, 2, 3) for j in (1, 2, 3)}
        derived = dreg.rigid_transform_symbolic(order)
        ok &= all(sp.simplify(sp.expand(p.xreplace(sub) - d)) == 0 for p, d in zip(printed, derived))
        rel = derived - sp.Matrix([X0, Y0, Z0])
        ok &= sp.simplify(sp.expand_trig((rel.T * rel)[0] - sum(s ** 2 for s in dreg.SCANNER_SYMBOLS))) == 0
    return _ok(ok)


def _rank(points) -> int:
    """Rank of the 3n×6 correction equations of (9.5.1) at a general rotation for these targets."""
    res, jac = dreg.rigid_model("kaw").compile()
    P = np.asarray(points, dtype=float)
    e = (10.0, -5.0, 2.0, 0.3, -0.2, 0.7)
    B = jac(*e, P[:, 0], P[:, 1], P[:, 2], P[:, 0], P[:, 1], P[:, 2]).reshape(3, 6, len(P)).transpose(2, 0, 1)
    return int(np.linalg.matrix_rank(B.reshape(-1, 6), tol=1e-9))


def minimum_targets(inputs: dict) -> dict:
    """§9.5: six unknowns and three equations per target — 2 by counting, 3 non-collinear by rank.

    ``by_counting`` is the least n with 3n ≥ 6; ``two_targets_rank`` the rank of the correction
    equations with the two targets of ``inputs`` (always 5: the rotation about the line joining
    them stays free); ``minimum`` the least number of the listed targets, taken in order, that
    gives rank 6; ``collinear_rank`` the rank for the collinear set.
    """
    T = np.asarray(inputs["targets"], dtype=float)
    minimum = next(n for n in range(1, len(T) + 1) if _rank(T[:n]) == 6)
    return {"by_counting": int(np.ceil(6 / 3)), "minimum": minimum, "two_targets_rank": _rank(T[:2]),
            "collinear_rank": _rank(inputs["collinear"])}


def more_targets_better(inputs: dict) -> dict:
    """§9.5 "better to have more targets spread over the area": m_κ with 3 targets vs a grid.

    Targets on a square of side ``side``: 3 at its corners, then a 5×5 grid over the same square;
    the r.m.s. error of κ is σ·√Q_κκ (1.8.8) with the a-priori σ ``sigma`` of each coordinate
    (the cofactor Q does not depend on the noise). Returns both in arc seconds and the verdict.
    """
    from ..registration import RigidTransform, rigid_transform
    side, sigma = float(inputs["side"]), float(inputs["sigma"])
    truth = RigidTransform(100.0, 200.0, 10.0, 0.01, -0.02, 0.5)
    three = np.array([[0.0, 0, 0], [side, 0, 0], [0, side, 0]])
    g = np.linspace(0, side, 5)
    grid = np.array([[x, y, 0.0] for x in g for y in g])
    m = {}
    for name, P in (("three", three), ("grid", grid)):
        T = rigid_transform(P, truth.apply(P))
        m[name] = float(sigma * np.sqrt(T.adjustment.Q[5, 5]) * 206264.806)
    return {"m_kappa_three": m["three"], "m_kappa_grid": m["grid"],
            "more_better": "yes" if m["grid"] < m["three"] else "no"}
