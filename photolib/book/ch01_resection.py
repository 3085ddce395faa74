"""Chapter 1, §1.8–§1.9 examples and printed formulas: ``textbook/ch01.toml`` inputs → library calls.

* :func:`resection_example` — the §1.8 worked example, rigorous solution (1.8.2)–(1.8.10).
* :func:`resection_example_as_printed` / :func:`as_printed_resection` — what the printed
  coefficients a₁…b₆ of (1.8.3) do with the same data.
* :func:`angles_example` — the §1.9 worked example (equality of angles).
* :func:`equation_count_example` — the counts n(n−1)/2 and 2n − 3 of §1.9.
* :func:`resection_partial_check`, :func:`angle_partial_check`, :func:`cs_definition_check`,
  :func:`angle_reconstruction_check` — the ``[[formula]]`` entries: printed vs derived.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import sympy as sp

from .. import derivations
from ..camera import ExteriorOrientation, InteriorOrientation
from ..errors import ConvergenceError
from ..lsq import Adjustment, gauss_newton
from ..resection import (DEFAULT_TOL, EO_NAMES, angle_equation_count, _collinearity_linearizer,
                         independent_angle_equations, resection_by_angles, space_resection)
from ._exact import lambdify

CORRELATION_NAMES = tuple((i, j, f"r_{EO_NAMES[i]}_{EO_NAMES[j]}") for i in range(6) for j in range(i + 1, 6))


# --- inputs ------------------------------------------------------------------------------------
def example_data(inputs: dict):
    """(XYZ, xy, io, eo0, eo_true) from the §1.8/§1.9 example inputs as printed."""
    pts = np.asarray(inputs["points"], dtype=float)          # N, X, Y, Z, x, y
    io = InteriorOrientation(inputs["f_mm"], inputs["x0_mm"], inputs["y0_mm"])
    a, t = inputs["approx"], inputs["true_eo"]
    order = inputs.get("order", "kaw")
    eo0 = ExteriorOrientation.from_degrees(a["Xs"], a["Ys"], a["Zs"], a.get("omega_deg", 0.0),
                                           a.get("alpha_deg", 0.0), a.get("kappa_deg", 0.0), order)
    eo_true = ExteriorOrientation.from_degrees(t["Xs"], t["Ys"], t["Zs"], t["omega_deg"], t["alpha_deg"],
                                               t["kappa_deg"], order)
    return pts[:, 1:4], pts[:, 4:6], io, eo0, eo_true


def _quantities(x, std, corr) -> dict:
    out = dict(zip(("Xs", "Ys", "Zs"), map(float, x[:3])))
    out.update(zip(("omega_deg", "alpha_deg", "kappa_deg"), map(float, np.degrees(x[3:]))))
    out.update(zip(("m_Xs", "m_Ys", "m_Zs"), map(float, std[:3])))
    out.update(zip(("m_omega_deg", "m_alpha_deg", "m_kappa_deg"), map(float, np.degrees(std[3:]))))
    out.update({name: float(corr[i, j]) for i, j, name in CORRELATION_NAMES})
    return out


# --- §1.8 ----------------------------------------------------------------------------------------
def resection_example(inputs: dict) -> dict:
    """§1.8 example: rigorous space resection (sympy-derived partials) from the book's approximations."""
    XYZ, xy, io, eo0, _ = example_data(inputs)
    res = space_resection(XYZ, xy, io, eo0, order=inputs.get("order", "kaw"))
    return _quantities(res.eo.vector, res.std, res.corr)


@dataclass
class AsPrinted:
    """What the printed a₁…b₆ do with the §1.8 data.

    ``literal_error``: the ConvergenceError of the iteration exactly as the book writes it
    (l = F = computed − measured, X′ = X⁰ + δ). ``flipped``: the same coefficients with the free
    terms taken as measured − computed, which makes the iteration converge (to the point where
    B_printedᵀV = 0); its accuracy is computed from the printed coefficients.
    """

    literal_error: ConvergenceError
    flipped: Adjustment


def as_printed_resection(inputs: dict) -> AsPrinted:
    """Run the §1.8 example with the printed coefficients of (1.8.3), both readings of the free term."""
    XYZ, xy, io, eo0, _ = example_data(inputs)
    try:
        space_resection(XYZ, xy, io, eo0, jacobian="printed")
    except ConvergenceError as err:
        literal = err
    else:  # pragma: no cover — would mean the printed partials work, contradicting the erratum
        raise AssertionError("the printed partials converged: the §1.8 erratum no longer holds")
    linearize = _collinearity_linearizer(XYZ, xy, io, "kaw", "printed")

    def flipped(p):
        B, L = linearize(p)
        return B, -L                              # l = x − x′ instead of x′ − x

    adj = gauss_newton(flipped, eo0.vector, tol=np.asarray(DEFAULT_TOL), max_iter=100, names=EO_NAMES)
    return AsPrinted(literal, adj)


def resection_example_as_printed(inputs: dict) -> dict:
    """The "as printed" run of §1.8 (see :class:`AsPrinted`).

    The literal iteration diverges, so it yields no numbers; the values returned are those of
    the flipped-free-term reading, the only way the printed coefficients give a result at all.
    """
    run = as_printed_resection(inputs)
    out = _quantities(run.flipped.x, run.flipped.std, run.flipped.corr)
    out["literal_iteration"] = f"diverges ({len(run.literal_error.history)} iterations)"
    return out


# --- §1.9 ----------------------------------------------------------------------------------------
def angles_example(inputs: dict) -> dict:
    """§1.9 example: projection centre from all 10 pairs, φ = cos ASB − cos aSb, dof = m − n."""
    XYZ, xy, io, eo0, _ = example_data(inputs)
    res = resection_by_angles(XYZ, xy, io, eo0.center, pairs="all")
    out = dict(zip(("Xs", "Ys", "Zs"), map(float, res.center)))
    out.update(zip(("m_Xs", "m_Ys", "m_Zs"), map(float, res.std)))
    out.update(r12=float(res.corr[0, 1]), r13=float(res.corr[0, 2]), r23=float(res.corr[1, 2]))
    return out


def equation_count_example(inputs: dict) -> dict:
    """§1.9 counts: equations for 4 and 5 points, the minimum number of points for 3 unknowns."""
    minimum = next(n for n in range(2, 10) if independent_angle_equations(n) >= 3)
    return {"equations_4_points": angle_equation_count(4), "equations_5_points": angle_equation_count(5),
            "minimum_points": minimum}


# --- printed formulas ------------------------------------------------------------------------
def _general_points(count: int, seed: int):
    """Random exterior orientations and object points in general position (x₀ = y₀ = 0).

    The printed partials use x′, y′ for the computed image coordinates; they are the reduced
    ones x′ − x₀ only when x₀ = y₀ = 0, the book's setting, so the comparison uses that.
    """
    rng = np.random.default_rng(seed)
    eo = rng.uniform([-50, -50, 800, -0.4, -0.4, -np.pi], [50, 50, 1200, 0.4, 0.4, np.pi], (count, 6))
    pts = rng.uniform([-400, -400, 0], [400, 400, 200], (count, 3))
    f = rng.uniform(50, 200, count)
    return eo, pts, f


def resection_partial_check(inputs: dict) -> dict:
    """Printed coefficient of (1.8.3) vs the sympy derivative of (1.8.2), at 20 random points.

    ``inputs = {"coefficient": "a1"}``. Equal means max relative difference < 1e-9.
    """
    name = inputs["coefficient"]
    key = derivations.RESECTION_COEFFICIENTS.index(name)
    eo, pts, f = _general_points(20, seed=18)
    args = (*eo.T, *pts.T, np.zeros(len(f)), np.zeros(len(f)), f, 0.0, 0.0)
    printed = derivations.printed_resection_jacobian()(*args)[key]
    derived = derivations.collinearity_model("kaw").compile()[1](*args)[key]
    scale = np.maximum(np.abs(derived), 1e-12)
    return {"printed_equals_derived": bool(np.max(np.abs(printed - derived) / scale) < 1e-9)}


def _angle_args(count: int, seed: int):
    rng = np.random.default_rng(seed)
    S = rng.uniform([-50, -50, 800], [50, 50, 1200], (count, 3))
    A = rng.uniform([-400, -400, 0], [400, 400, 200], (count, 3))
    B = rng.uniform([-400, -400, 0], [400, 400, 200], (count, 3))
    return S, A, B


def angle_partial_check(inputs: dict) -> dict:
    """Printed a₁, b₁, c₁ of §1.9 vs ∂φ/∂X_S, ∂φ/∂Y_S, ∂φ/∂Z_S of (1.9.1), at 20 random points."""
    name = inputs["coefficient"]
    j = ("a1", "b1", "c1").index(name)
    S, A, B = _angle_args(20, seed=19)
    d = derivations
    printed = lambdify((d.Xs, d.Ys, d.Zs, d.XA, d.YA, d.ZA, d.XB, d.YB, d.ZB),
                          d.printed_angle_equality_partials()[name], "numpy")(*S.T, *A.T, *B.T)
    zeros = np.zeros(len(S))
    derived = d.angle_equality_model().compile()[1](*S.T, *A.T, *B.T, zeros, zeros, zeros, zeros, 100.0, 0.0, 0.0)[j]
    return {"printed_equals_derived": bool(np.max(np.abs(printed - derived) / np.abs(derived)) < 1e-9)}


def cs_definition_check(inputs: dict) -> dict:
    """Third distance line of §1.9: printed "AS = √((X_C−X_S)²+…)" vs the AS of the first line.

    a₂, b₂, c₂ need CS = |C − S|; the printed line calls it AS, which is defined as |A − S| two
    lines above. The two do not agree at random points, so the printed line is a typo for CS.
    """
    S, A, C = _angle_args(20, seed=20)
    printed_as = np.linalg.norm(C - S, axis=1)
    defined_as = np.linalg.norm(A - S, axis=1)
    return {"printed_equals_derived": bool(np.allclose(printed_as, defined_as, rtol=1e-12))}


def angle_reconstruction_check(inputs: dict) -> dict:
    """(1.9.1)/(1.9.2), lost in the OCR: check our reconstruction against the printed partials.

    The reconstructed φ = cos ASB − cos aSb must have the printed a₁, b₁, c₁ as its derivatives
    (for 1.9.2 also: the linearisation φ(S + δ) ≈ φ(S) + a δX + b δY + c δZ to second order).
    Raises if it does not. The printed equation itself is missing, so it cannot equal anything:
    ``printed_equals_derived`` is False.
    """
    for name in ("a1", "b1", "c1"):
        if not _reconstruction_matches(name):
            raise AssertionError(f"reconstructed (1.9.1) does not give the printed {name}")
    if inputs.get("equation") == "1.9.2":
        residual_fn, jacobian_fn = derivations.angle_equality_model().compile()
        S, A, B = _angle_args(5, seed=21)
        img = (np.full(5, 10.0), np.full(5, -20.0), np.full(5, 30.0), np.full(5, 5.0), 100.0, 0.0, 0.0)
        delta = np.array([0.3, -0.2, 0.25])
        phi0 = residual_fn(*S.T, *A.T, *B.T, *img)[0]
        phi1 = residual_fn(*(S + delta).T, *A.T, *B.T, *img)[0]
        lin = phi0 + delta @ jacobian_fn(*S.T, *A.T, *B.T, *img)
        # remainder of a first-order Taylor step must shrink by ~4 when δ is halved
        phi_half = residual_fn(*(S + delta / 2).T, *A.T, *B.T, *img)[0]
        lin_half = phi0 + (delta / 2) @ jacobian_fn(*S.T, *A.T, *B.T, *img)
        ratio = np.abs(phi1 - lin) / np.abs(phi_half - lin_half)
        if not np.all((ratio > 3.0) & (ratio < 5.0)):
            raise AssertionError("(1.9.2) is not the first-order expansion of (1.9.1)")
    return {"printed_equals_derived": False}


def _reconstruction_matches(name: str) -> bool:
    """The derivative of the reconstructed φ (derivations.angle_equality_model) equals the printed one."""
    return angle_partial_check({"coefficient": name})["printed_equals_derived"]
