"""Chapter 2 worked example (double resection on simulated images, after §2.12) and the printed
partials of §2.8 and §2.11: ``textbook/ch02.toml`` inputs → library calls → named quantities.

The example runs the whole chain of Chapter 2 on two simulated images: relative orientation
(2.7.4)/(2.8.1) → residual y-parallaxes (2.8.2) → model by forward intersection (§2.9, N from the
second formula of (2.4.12)) → exterior orientation of the model (2.11.1)/(2.11.2) → control-point
check → exterior orientation of the images (2.12.1)/(2.12.2). Each table of the book is computed
from the printed data it depends on (the image coordinates, and where the book continues from
its own printed intermediate results — RO angles, model coordinates — from those).

* Correct computations: :func:`relative_orientation_example`, :func:`model_points_example`,
  :func:`model_orientation_example`, :func:`image_orientation_example`.
* "As printed" (the book's program): the same names with ``_as_printed`` — the §2.8 partials with
  their sign error, the §2.11 partials with a₅ = ∂φ_X/∂α_M = 0, and A_i = A'_i·A_M.
* :func:`rounding_monte_carlo` — the spread that printing the inputs rounded (0.001 mm, 0.001 m,
  0.0001°) causes in every quantity: the basis of every ``input-rounding`` bound.
* :func:`ro_partial_check`, :func:`similarity_partial_check` — the ``[[formula]]`` entries.
"""

from __future__ import annotations

import copy
import json
from functools import lru_cache

import numpy as np
import sympy as sp

from .. import derivations
from ..camera import ExteriorOrientation, InteriorOrientation
from ..image_pair import (RelativeOrientation, SimilarityTransform, StereoModel, absolute_orientation, build_model,
                          image_orientation_from_model, relative_orientation)
from ._exact import lambdify

RO_KEYS = ("alpha1", "kappa1", "omega2", "alpha2", "kappa2")
AO_KEYS = ("X0", "Y0", "Z0", "omegaM", "alphaM", "kappaM", "t")
AO_ORDER = "wak"          # the §2.11 partials are written for A_M = (1.3.2)
RO_ORDER = "kaw"          # the data and the §2.8 partials are κ–α–ω (1.3.5)

ROUNDING = {"points": 0.0005, "ro_deg": 0.00005, "model_points": 0.0005}
"""Half a unit of the last printed digit of each rounded input: image coordinates 0.001 mm,
RO angles 0.0001°, model coordinates 0.001 m (object coordinates of the control are exact)."""


# --- inputs --------------------------------------------------------------------------------------
def example_data(inputs: dict):
    """(XYZ, xy1, xy2, io) from the printed 12-point table: N, X, Y, Z, x₁, y₁, x₂, y₂."""
    pts = np.asarray(inputs["points"], dtype=float)
    io = InteriorOrientation(inputs["f_mm"], inputs["x0_mm"], inputs["y0_mm"])
    return pts[:, 1:4], pts[:, 4:6], pts[:, 6:8], io


def _key(inputs: dict) -> str:
    return json.dumps(inputs, sort_keys=True)


def _ro_from_printed(inputs: dict) -> RelativeOrientation:
    """A RelativeOrientation carrying the printed RO angles (for the steps that continue from them)."""
    a1, k1, w2, a2, k2 = np.radians(inputs["ro_deg"])
    return RelativeOrientation("independent", RO_ORDER, 0.0, 0.0, 0.0, float(a1), float(k1), float(w2),
                               float(a2), float(k2), q=np.array([]), adjustment=None)


def _ao_initial(inputs: dict) -> SimilarityTransform:
    a = inputs["ao_approx"]
    return SimilarityTransform(a["X0"], a["Y0"], a["Z0"], *np.radians([a["omega_deg"], a["alpha_deg"],
                                                                        a["kappa_deg"]]), a["t"], order=AO_ORDER)


# --- relative orientation and residual y-parallaxes -------------------------------------------------
@lru_cache(maxsize=64)
def _relative_orientation(key: str, jacobian: str) -> RelativeOrientation:
    inputs = json.loads(key)
    _, xy1, xy2, io = example_data(inputs)
    return relative_orientation(xy1, xy2, io, system="independent", order=RO_ORDER,
                                initial=np.radians(inputs["ro_approx_deg"]), jacobian=jacobian, max_iter=100)


def run_relative_orientation(inputs: dict, jacobian: str = "derived") -> RelativeOrientation:
    """RO of the example, system α'₁, κ'₁, ω'₂, α'₂, κ'₂ (2.7.4), from the printed approximations."""
    return _relative_orientation(_key(inputs), jacobian)


def _ro_quantities(ro: RelativeOrientation) -> dict:
    adj = ro.adjustment
    out = {f"{k}_deg": float(np.degrees(getattr(ro, k))) for k in RO_KEYS}
    out.update({f"m_{k}_deg": float(np.degrees(s)) for k, s in zip(RO_KEYS, adj.std)})
    out.update({f"r_{RO_KEYS[i]}_{RO_KEYS[j]}": float(adj.corr[i, j]) for i in range(5) for j in range(i + 1, 5)})
    out.update({f"q{i + 1}": float(q) for i, q in enumerate(ro.q)})
    out["mu"] = float(adj.mu)
    return out


def relative_orientation_example(inputs: dict) -> dict:
    """RO elements, m_j, r_ij and the residual y-parallaxes q (2.8.2), sympy-derived partials."""
    return _ro_quantities(run_relative_orientation(inputs, "derived"))


def relative_orientation_example_as_printed(inputs: dict) -> dict:
    """The same with the §2.8 partials as printed (sign error on every f-term)."""
    return _ro_quantities(run_relative_orientation(inputs, "printed"))


# --- model ---------------------------------------------------------------------------------------------
def model_points_example(inputs: dict) -> dict:
    """Model coordinates (§2.9): S₁ = 0, B_X as printed, the printed RO angles, N by the 2nd formula of (2.4.12)."""
    _, xy1, xy2, io = example_data(inputs)
    model = build_model(xy1, xy2, _ro_from_printed(inputs), io, base_length=inputs["base_m"],
                        method="component", formula=2)
    out = {}
    for i, p in enumerate(model.points, start=1):
        out.update({f"XM{i}": float(p[0]), f"YM{i}": float(p[1]), f"ZM{i}": float(p[2])})
    return out


# --- exterior orientation of the model and the control-point check ---------------------------------------
@lru_cache(maxsize=64)
def _model_orientation(key: str, jacobian: str) -> SimilarityTransform:
    inputs = json.loads(key)
    XYZ = example_data(inputs)[0]
    XM = np.asarray(inputs["model_points"], dtype=float)
    return absolute_orientation(XM, XYZ, order=AO_ORDER, initial=_ao_initial(inputs), jacobian=jacobian)


def run_model_orientation(inputs: dict, jacobian: str = "derived") -> SimilarityTransform:
    """(2.11.1)/(2.11.2) on the printed model coordinates, all 12 points as full control, A_M = (1.3.2)."""
    return _model_orientation(_key(inputs), jacobian)


def _ao_quantities(tr: SimilarityTransform, XYZ) -> dict:
    adj = tr.adjustment
    values = tr.vector.copy()
    std = adj.std.copy()
    values[3:6], std[3:6] = np.degrees(values[3:6]), np.degrees(std[3:6])
    names = [k + ("_deg" if k in ("omegaM", "alphaM", "kappaM") else "") for k in AO_KEYS]
    out = dict(zip(names, map(float, values)))
    out.update({f"m_{n}": float(s) for n, s in zip(names, std)})
    out.update({f"r_{AO_KEYS[i]}_{AO_KEYS[j]}": float(adj.corr[i, j]) for i in range(7) for j in range(i + 1, 7)})
    computed = XYZ + tr.residuals                          # transformed model points (2.10.4)
    for i, (c, d) in enumerate(zip(computed, tr.residuals), start=1):
        out.update({f"X{i}": float(c[0]), f"Y{i}": float(c[1]), f"Z{i}": float(c[2]),
                    f"dX{i}": float(d[0]), f"dY{i}": float(d[1]), f"dZ{i}": float(d[2])})
    rms = np.sqrt(np.mean(tr.residuals ** 2, axis=0))     # the book divides by n, not n − 1
    out.update(m_dX=float(rms[0]), m_dY=float(rms[1]), m_dZ=float(rms[2]))
    return out


def model_orientation_example(inputs: dict) -> dict:
    """Seven elements, m_j, r_ij, the transformed control points, dX = computed − given and their rms."""
    return _ao_quantities(run_model_orientation(inputs, "derived"), example_data(inputs)[0])


def model_orientation_example_as_printed(inputs: dict) -> dict:
    """The same with the book's program: printed §2.11 partials and a₅ = ∂φ_X/∂α_M = 0."""
    return _ao_quantities(run_model_orientation(inputs, "book-program"), example_data(inputs)[0])


# --- exterior orientation of the images --------------------------------------------------------------------
def _image_orientation(inputs: dict, jacobian: str, product: str) -> dict:
    ro = _ro_from_printed(inputs)
    eo1 = ExteriorOrientation(0.0, 0.0, 0.0, ro.omega1, ro.alpha1, ro.kappa1, RO_ORDER)
    eo2 = ExteriorOrientation(*map(float, inputs["base_m"] * ro.base), ro.omega2, ro.alpha2, ro.kappa2, RO_ORDER)
    model = StereoModel(np.asarray(inputs["model_points"], dtype=float), eo1, eo2, ro)
    tr = run_model_orientation(inputs, jacobian)
    out = {}
    for i, eo in enumerate(image_orientation_from_model(model, tr, order=RO_ORDER, product=product), start=1):
        out.update({f"Xs{i}": float(eo.Xs), f"Ys{i}": float(eo.Ys), f"Zs{i}": float(eo.Zs)})
        out.update(zip((f"omega{i}_deg", f"alpha{i}_deg", f"kappa{i}_deg"), map(float, eo.angles_degrees)))
    return out


def image_orientation_example(inputs: dict) -> dict:
    """(2.12.1), A_i = A_M·A'_i (2.12.2), angles by (1.3.6) (the data are κ–α–ω)."""
    return _image_orientation(inputs, "derived", "model-first")


def image_orientation_example_as_printed(inputs: dict) -> dict:
    """The book's program: A_M from the a₅ = 0 adjustment and the product taken as A'_i·A_M."""
    return _image_orientation(inputs, "book-program", "image-first")


# --- input rounding -----------------------------------------------------------------------------------------
def perturb_printed_inputs(inputs: dict, rng) -> dict:
    """A copy of ``inputs`` with every rounded input moved uniformly within ± half its last printed unit."""
    out = copy.deepcopy(inputs)
    if "points" in out:
        pts = np.asarray(out["points"], dtype=float)
        pts[:, 4:8] += rng.uniform(-ROUNDING["points"], ROUNDING["points"], pts[:, 4:8].shape)
        out["points"] = pts.tolist()
    for key in ("ro_deg", "model_points"):
        if key in out:
            v = np.asarray(out[key], dtype=float)
            out[key] = (v + rng.uniform(-ROUNDING[key], ROUNDING[key], v.shape)).tolist()
    return out


def rounding_monte_carlo(inputs: dict, compute, n: int = 200, seed: int = 2022, perturb=None) -> dict:
    """Standard deviation of every quantity of ``compute`` over ``n`` re-roundings of the printed inputs.

    The book printed its simulated image coordinates to 0.001 mm (and its intermediate RO angles
    and model coordinates to 0.0001° and 0.001 m); its own program worked with the unrounded
    values. Replacing each rounded input by a uniform draw within ± half a unit models that lost
    information. An ``input-rounding`` bound is 3σ of this spread plus half a unit of the printed
    result (see :func:`rounding_bound`). ``perturb(inputs, rng)`` replaces the default
    :func:`perturb_printed_inputs` for other examples (Chapter 4 re-rounds the image coordinates only).
    """
    perturb = perturb_printed_inputs if perturb is None else perturb
    rng = np.random.default_rng(seed)
    runs = [compute(perturb(inputs, rng)) for _ in range(n)]
    return {k: float(np.std([r[k] for r in runs])) for k in runs[0] if isinstance(runs[0][k], float)}


def rounding_bound(sigma: float, decimals: int) -> float:
    """3σ of the input-rounding spread plus half a unit of the printed decimals, rounded up to 10⁻⁽ᵈ⁺²⁾."""
    grid = 10.0 ** (-(decimals + 2))
    return float(np.ceil((3.0 * sigma + 0.5 * 10.0 ** (-decimals)) / grid - 1e-9) * grid)


# --- printed formulas ------------------------------------------------------------------------------------------
def _random_values(symbols, count, seed, ranges):
    rng = np.random.default_rng(seed)
    return {s: rng.uniform(*ranges.get(s.name, (-0.5, 0.5)), count) for s in symbols}


def ro_partial_check(inputs: dict) -> dict:
    """A printed §2.8 quantity vs sympy at 20 random points: ``inputs = {"term": ...}``.

    ``"a1"``, ``"a2"``: the printed determinants of (2.8.1) vs ∂φ/∂b_y, ∂φ/∂b_z of (2.7.5).
    ``"X_omega"`` etc.: the printed ∂X'₂/∂ω₂ … vs ∂(A'₂(x₂, y₂, −f₂)ᵀ)/∂θ, A'₂ = (1.3.5).
    """
    d = derivations
    term = inputs["term"]
    if term in ("a1", "a2"):
        phi = d.coplanarity_model("dependent", "kaw").residuals[0]
        printed = (-sp.Matrix([[d.x1, -d.f1], [d.X, d.Z]]).det() if term == "a1"
                   else sp.Matrix([[d.x1, d.y1], [d.X, d.Y]]).det())
        r2 = d.rotation_matrix_symbolic("kaw", d.omega2, d.alpha2, d.kappa2) * sp.Matrix([d.x2, d.y2, -d.f2])
        printed = printed.subs({d.X: r2[0], d.Y: r2[1], d.Z: r2[2]})
        derived = sp.diff(phi, d.b_y if term == "a1" else d.b_z)
    else:
        C, name = term.split("_")
        printed = d.printed_relative_orientation_partials()[(C, name)]
        derived = d.derived_relative_orientation_partials("kaw", z_sign=-1)[(C, name)]
    symbols = sorted((sp.sympify(printed) - derived).free_symbols | derived.free_symbols, key=str)
    vals = _random_values(symbols, 20, 28, {"f_1": (50, 200), "f_2": (50, 200), "x_1": (-100, 100),
                                            "y_1": (-100, 100), "x_2": (-100, 100), "y_2": (-100, 100)})
    p = lambdify(symbols, printed, "numpy")(*vals.values()) if symbols else float(printed)
    q = lambdify(symbols, derived, "numpy")(*vals.values())
    p, q = np.broadcast_arrays(np.asarray(p, float), np.asarray(q, float))
    return {"printed_equals_derived": bool(np.allclose(p, q, rtol=1e-10, atol=1e-9))}


def similarity_partial_check(inputs: dict) -> dict:
    """Printed coefficients of (2.11.2) vs the sympy derivatives of (2.11.1) with A_M = (1.3.2).

    ``inputs = {"coefficients": ["a5"]}`` (several names: all must agree). 20 random points with
    angles up to ±0.5 rad, so that an error that vanishes for κ_M = 0 is not missed.
    """
    d = derivations
    printed, derived = d.printed_similarity_partials(), d.derived_similarity_partials("wak")
    symbols = [d.X0, d.Y0, d.Z0, d.omegaM, d.alphaM, d.kappaM, d.t_M, d.XM, d.YM, d.ZM, d.X, d.Y, d.Z]
    vals = _random_values(symbols, 20, 211, {"t": (0.5, 10), "X_M": (-200, 200), "Y_M": (-200, 200),
                                             "Z_M": (-250, -150)})
    ok = True
    for name in inputs["coefficients"]:
        p = np.broadcast_to(lambdify(symbols, printed[name], "numpy")(*vals.values()), (20,))
        q = np.broadcast_to(lambdify(symbols, derived[name], "numpy")(*vals.values()), (20,))
        ok = ok and bool(np.allclose(p, q, rtol=1e-10, atol=1e-9))
    return {"printed_equals_derived": ok}

