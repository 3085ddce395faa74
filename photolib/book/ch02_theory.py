"""Chapter 2, §2.1–§2.13 (theory of a pair of frame images): adapters for ``textbook/ch02.toml``.

Two kinds of functions live here.

* **Inline statements and the §2.13 example** — functions that take an ``[[example]]``'s
  ``inputs`` and return ``{quantity name: value}``: the radius of unaided stereo vision (§2.1),
  the counting statements of relative and absolute orientation (§2.6–§2.8, §2.11), the six
  standard point zones (§2.8), the DMC III accuracy example and the "≈10 %" claim (§2.13).
  The work is done by :mod:`photolib.image_pair`.
* **Printed formulas** — functions that take a ``[[formula]]``'s ``inputs`` (the printed formula
  transcribed as sympy strings, so a test can hand in a deliberately wrong one) and return
  ``{"printed_equals_derived": bool}`` from an independent derivation: sympy, with every rotation
  written as the quaternion matrix (1.3.7) divided by its scale (a rational parametrisation of
  all rotations, so ``sympy.cancel`` decides identities exactly), plus a numeric comparison with
  the library function where there is one.

String symbols of the transcriptions: ``X1, Y1, Z1, X2, Y2, Z2`` for X'ᵢ, Y'ᵢ, Z'ᵢ (ray components),
``BX, BY, BZ`` the base, ``by, bz`` its direction, ``x1, y1, x2, y2, f, x01, y01, f1`` image data,
``B, p, b, Z, H, mx, my, mp, mZ`` for §2.5/§2.13, ``XM, YM, ZM, X0, Y0, Z0, t`` and ``a11 … a33``
for §2.10, ``b, L, gamma, dgamma`` for §2.1.
"""

from __future__ import annotations

from itertools import combinations

import numpy as np
import sympy as sp

from .. import derivations, image_pair
from ..camera import ExteriorOrientation, InteriorOrientation
from ..lsq import redundancy_numbers
from ..rotation import rotation_matrix
from ..single_image import project
from ..synthetic import stereo_pair
from ._exact import is_zero, lambdify, zero

# --- symbols and helpers -------------------------------------------------------------------------
_names = ("X1 Y1 Z1 X2 Y2 Z2 BX BY BZ by bz x1 y1 x2 y2 x01 y01 N lam MX MY MZ "
          "XM YM ZM X0 Y0 Z0 X Y q_a q_b q_c q_d dgamma u v")
_S = {s.name: s for s in sp.symbols(_names, real=True)}
_S.update({s.name: s for s in sp.symbols("f f1 B p b L gamma H t d mx my mp mZ N0", positive=True)})
_S["Z"] = sp.Symbol("Z", real=True)
for _i in range(1, 4):
    for _j in range(1, 4):
        _S[f"a{_i}{_j}"] = sp.Symbol(f"a{_i}{_j}", real=True)
_S["sqrt"] = sp.sqrt


def _p(text: str):
    """Parse a transcribed formula (sympy syntax) with this module's symbols."""
    return sp.sympify(text, locals=_S)


def _zero(expr) -> bool:
    exact = is_zero(expr)          # exact canonical form (rational functions); else sympy's cancel
    return sp.cancel(sp.together(sp.expand(expr))) == 0 if exact is None else exact


def _rotation(prefix: str = "q"):
    """(1.3.7)/m: an orthogonal matrix for any non-zero quaternion (a, b, c, d) — all rotations."""
    a, b, c, d = sp.symbols(f"{prefix}_a {prefix}_b {prefix}_c {prefix}_d", real=True)
    Q = sp.Matrix([
        [d**2 + a**2 - b**2 - c**2, 2 * (a * b - c * d), 2 * (a * c + b * d)],
        [2 * (a * b + c * d), d**2 - a**2 + b**2 - c**2, 2 * (b * c - a * d)],
        [2 * (a * c - b * d), 2 * (b * c + a * d), d**2 - a**2 - b**2 + c**2],
    ])
    return Q / (a**2 + b**2 + c**2 + d**2)


def _ok(*flags) -> dict:
    return {"printed_equals_derived": bool(all(flags))}


def _rays_through(M, S1, S2, N0, lam):
    """Two rays that meet at M: r₁ = (M − S₁)/N₀ (so N = N₀ on ray 1), r₂ = λ(M − S₂)."""
    return (M - S1) / N0, lam * (M - S2)


# =================================================================================================
# Inline statements
# =================================================================================================
def stereo_radius_example(inputs: dict) -> dict:
    """§2.1, line 1083: R = b·ρ″/γ_min with the book's ρ″ (``rho_arcsec``), b in mm → R in m.

    Also returns ``R_exact_rho_m`` with ρ″ = 206 264.8″ for the notebook (not a printed number).
    """
    b_mm, g = inputs["b_mm"], inputs["gamma_min_arcsec"]
    R = image_pair.stereo_vision_radius(b_mm, g, rho=inputs["rho_arcsec"]) / 1000.0
    return {"R_m": float(R),
            "R_exact_rho_m": float(image_pair.stereo_vision_radius(b_mm, g) / 1000.0)}


def component_formula_degeneracy(inputs: dict) -> dict:
    """§2.4, line 1234: which formulas of (2.4.12) break down when the ordinates are ≈ 0?

    The rays of points with zero ordinate (Y'₁ = Y'₂ = 0) are put into the three printed
    denominators; a formula "fails" when its denominator vanishes identically (sympy). Returns
    the numbers of the failing formulas as text, e.g. ``"1, 3"``.
    """
    dens = [_p(s) for s in inputs["denominators"]]
    zero_y = {_S["Y1"]: 0, _S["Y2"]: 0}
    failing = [str(i + 1) for i, den in enumerate(dens) if sp.expand(den.subs(zero_y)) == 0]
    return {"failing_formulas": ", ".join(failing)}


def _coplanarity_all_parameters(order="kaw"):
    """φ of (2.7.3) with all eight parameters as a compiled model (sympy → numpy)."""
    return derivations.coplanarity_all_parameters_model(order).compile()


def synthetic_pair(n, seed=0, order="kaw"):
    """A generic near-vertical pair (f = 100 mm, base 400 m, H ≈ 1000 m, angles up to ±3°).

    Returns (xy1, xy2, io, eo1, eo2, ground points) for ``n`` random points with ±40 m relief,
    from :func:`photolib.synthetic.stereo_pair`.
    """
    pair = stereo_pair(n, seed=seed, order=order, centres=((0.0, 0.0, 1000.0), (400.0, 8.0, 1005.0)),
                       angle_spread_deg=3.0, box=((50.0, 350.0), (-250.0, 250.0)), relief=40.0)
    return pair.xy1, pair.xy2, pair.io, pair.eo1, pair.eo2, pair.points


def relative_orientation_counts(inputs: dict) -> dict:
    """§2.6–§2.7 counting statements, from the rank of the Jacobian of (2.7.3).

    At the solution of a generic noise-free pair (φ = 0 at every point) the 8 parameters
    b_y, b_z, ω'₁, α'₁, κ'₁, ω'₂, α'₂, κ'₂ enter φ with a Jacobian of rank 5 (``n_elements``):
    3 of them (``n_fixed``) only turn the model frame. ``min_points`` is the smallest number of
    points for which the 5 columns of the book's system b_y, b_z, ω'₂, α'₂, κ'₂ reach rank 5.
    ``admissible_systems`` counts the
    5-element subsets of full rank at the normal case (angles 0, base along X_M), where the
    groups {ω'₁, ω'₂}, {b_z, α'₁, α'₂}, {b_y, κ'₁, κ'₂} are exactly the rotations of the model
    frame about X_M, Y_M, Z_M; ``one_per_group`` says whether they are exactly the subsets that
    leave out one parameter of each group. (For a tilted pair the groups are mixed by the
    angles: the forbidden subsets become ill-conditioned rather than exactly singular.)
    """
    order = inputs.get("order", "kaw")
    _, jac = _coplanarity_all_parameters(order)
    xy1, xy2, io, eo1, eo2, _ = synthetic_pair(inputs.get("n_points", 12), inputs.get("seed", 0), order)
    base = eo2.center - eo1.center                      # the model frame = the object frame: φ = 0
    p0 = np.array([base[1] / base[0], base[2] / base[0], *eo1.vector[3:], *eo2.vector[3:]])
    J = np.asarray(jac(*p0, xy1[:, 0], xy1[:, 1], io.f, xy2[:, 0], xy2[:, 1], io.f), float).T   # (n, 8)
    rank = lambda M: int(np.linalg.matrix_rank(M, tol=1e-9 * np.abs(J).max()))   # noqa: E731
    n_elements = rank(J)
    names = [s.name for s in derivations.RELATIVE_ORIENTATION_PARAMETERS]
    groups = [{"omega_1", "omega_2"}, {"b_z", "alpha_1", "alpha_2"}, {"b_y", "kappa_1", "kappa_2"}]
    # the groups are rotations of the model frame about X_M, Y_M, Z_M; they are exact at the
    # normal case (all angles 0, base along X_M), so the admissible systems are counted there
    rng = np.random.default_rng(inputs.get("seed", 0))
    P = np.column_stack([rng.uniform(50, 350, 12), rng.uniform(-250, 250, 12), rng.uniform(-40, 40, 12)])
    io0 = InteriorOrientation(100.0)
    n1 = project(P, ExteriorOrientation(0.0, 0.0, 1000.0, 0.0, 0.0, 0.0, order=order), io0)
    n2 = project(P, ExteriorOrientation(400.0, 0.0, 1000.0, 0.0, 0.0, 0.0, order=order), io0)
    J0 = np.asarray(jac(*np.zeros(8), n1[:, 0], n1[:, 1], io0.f, n2[:, 0], n2[:, 1], io0.f), float).T
    tol0 = 1e-9 * np.abs(J0).max()
    full_rank = [c for c in combinations(range(8), 5) if np.linalg.matrix_rank(J0[:, c], tol=tol0) == 5]
    one_per_group = {frozenset(c) for c in full_rank} == {
        frozenset(c) for c in combinations(range(8), 5)
        if all(len(g - {names[i] for i in c}) == 1 for g in groups)}
    dependent = [names.index(s) for s in ("b_y", "b_z", "omega_2", "alpha_2", "kappa_2")]
    min_points = next(k for k in range(1, len(J) + 1) if rank(J[:k][:, dependent]) == 5)
    return {"n_parameters": len(names), "n_elements": n_elements, "n_fixed": len(names) - n_elements,
            "n_groups": len(groups), "min_points": min_points,
            "admissible_systems": len(full_rank), "one_per_group": "yes" if one_per_group else "no"}


def absolute_orientation_counts(inputs: dict) -> dict:
    """§2.6 and §2.11 counting statements, from the rank of the Jacobian of (2.11.1).

    ``n_elements``: rank with many full control points (7). ``min_full_points``: the smallest
    number of non-collinear full (XYZ) points giving rank 7 (3 collinear give 6).
    ``min_full_with_height``: full points needed besides one height point; ``min_height_with_2_xy``:
    height points needed besides two planimetric points.
    """
    rng = np.random.default_rng(inputs.get("seed", 0))
    order = inputs.get("order", "kaw")
    _, jac = derivations.similarity_model(order).compile()
    XM = np.column_stack([rng.uniform(-1, 1, 8), rng.uniform(-1, 1, 8), rng.uniform(-2.2, -1.8, 8)])
    p = np.array([1000.0, 1000.0, 1000.0, 0.01, -0.02, 0.03, 400.0])
    J = np.asarray(jac(*p, XM[:, 0], XM[:, 1], XM[:, 2], 0 * XM[:, 0], 0 * XM[:, 0], 0 * XM[:, 0]), float)
    J = J.reshape(3, 7, len(XM)).transpose(2, 0, 1)             # (points, X/Y/Z row, 7)
    tol = 1e-9 * np.abs(J).max()

    def rank(rows):
        return int(np.linalg.matrix_rank(np.concatenate(rows), tol=tol)) if rows else 0

    full = lambda i: J[i]            # noqa: E731
    planimetric = lambda i: J[i, :2]  # noqa: E731
    height = lambda i: J[i, 2:]      # noqa: E731
    n_elements = rank([full(i) for i in range(len(XM))])
    min_full = next(k for k in range(1, 8) if rank([full(i) for i in range(k)]) == 7)
    min_full_h = next(k for k in range(1, 7) if rank([full(i) for i in range(k)] + [height(7)]) == 7)
    min_h_2xy = next(k for k in range(1, 7) if rank([planimetric(0), planimetric(1)]
                                                    + [height(2 + i) for i in range(k)]) == 7)
    collinear = XM[0] + np.outer([0.0, 1.0, 2.0], XM[1] - XM[0])
    Jc = np.asarray(jac(*p, collinear[:, 0], collinear[:, 1], collinear[:, 2], *([np.zeros(3)] * 3)), float)
    Jc = Jc.reshape(3, 7, 3).transpose(2, 0, 1).reshape(9, 7)
    return {"n_elements": n_elements, "min_equations": n_elements, "min_full_points": min_full,
            "rank_3_collinear": int(np.linalg.matrix_rank(Jc, tol=tol)),
            "min_full_with_height": min_full_h, "min_height_with_2_xy": min_h_2xy}


def standard_zones(n_per_zone: int = 2, seed: int = 0, half_x: float = 35.0, half_y: float = 80.0):
    """Image-1 coordinates (mm) of ``n_per_zone`` points in each of the six standard zones (§2.8).

    The zones sit on the two principal points' columns (x ≈ 0 and x ≈ b, b = ``half_x``·2/2…)
    and on three rows (top, middle, bottom) of the overlap, as in Fig. 2.14; zone k = 1…6 is
    numbered row by row. Returns (points (6·n, 2), zone number of each point).
    """
    rng = np.random.default_rng(seed)
    centres = np.array([[cx, cy] for cy in (half_y * 0.8, 0.0, -half_y * 0.8) for cx in (0.0, half_x)])
    pts = np.concatenate([c + rng.uniform(-0.1, 0.1, (n_per_zone, 2)) * [half_x, half_y] for c in centres])
    return pts, np.repeat(np.arange(1, 7), n_per_zone)


def standard_zone_counts(inputs: dict) -> dict:
    """§2.8, line 1384: 12–18 points, in pairs or triples, in the six standard zones."""
    lo, zones_lo = standard_zones(inputs["per_zone_min"])
    hi, _ = standard_zones(inputs["per_zone_max"])
    return {"n_points_min": len(lo), "n_points_max": len(hi), "n_zones": len(set(zones_lo.tolist()))}


def blunder_localisation(n_per_zone: int, seed: int = 0, blunder_mm: float = 0.05, sigma_mm: float = 0.003,
                         blunder_point: int = 4):
    """Relative orientation of a synthetic pair with one gross error, points in the six zones.

    A near-vertical pair (f = 100 mm, base 40 mm at image scale) is simulated, ``sigma_mm`` noise
    is added to image 2 and ``blunder_mm`` to y₂ of point ``blunder_point``; the dependent system
    (2.7.5) is solved by :func:`photolib.image_pair.relative_orientation`. Returns the standardised
    residuals wᵢ = vᵢ/(μ√rᵢ) (rᵢ the redundancy numbers), the index of the largest |wᵢ| (None when
    the largest are equal to rounding, as with redundancy 1), the ratio
    of the two largest |wᵢ| (1 when the blunder cannot be told apart) and m of the elements.
    """
    rng = np.random.default_rng(seed)
    io = InteriorOrientation(100.0)
    H, B = 1000.0, 400.0
    eo1 = ExteriorOrientation(0.0, 0.0, H, *np.radians(rng.uniform(-2, 2, 3)))
    eo2 = ExteriorOrientation(B, 5.0, H + 3.0, *np.radians(rng.uniform(-2, 2, 3)))
    zone_xy, _ = standard_zones(n_per_zone, seed, half_x=B / H * 100.0, half_y=80.0)
    P = np.column_stack([zone_xy * H / 100.0, rng.uniform(-30, 30, len(zone_xy))])
    xy1, xy2 = project(P, eo1, io), project(P, eo2, io)
    xy2 = xy2 + rng.normal(0.0, sigma_mm, xy2.shape)
    xy2[blunder_point, 1] += blunder_mm
    ro = image_pair.relative_orientation(xy1, xy2, io, system="dependent")
    _, jac = derivations.coplanarity_model("dependent", "kaw").compile()
    J = np.asarray(jac(*ro.adjustment.x, xy1[:, 0], xy1[:, 1], io.f, xy2[:, 0], xy2[:, 1], io.f), float).T
    r = redundancy_numbers(J, ro.adjustment.Q)                         # unit weights
    v = ro.adjustment.residuals
    w = v / (ro.adjustment.mu * np.sqrt(np.clip(r, 1e-15, None)))
    order = np.argsort(-np.abs(w))
    ratio = float(abs(w[order[0]]) / abs(w[order[1]]))
    # equal |w| (to rounding: with redundancy 1 all are equal) locate nothing; which one rounding
    # makes largest depends on the BLAS kernel, so it is not reported
    largest = None if ratio < 1.0 + 1e-9 else int(order[0])
    return {"w": w, "redundancy": r, "largest": largest, "ratio": ratio, "std": ro.adjustment.std,
            "dof": ro.adjustment.dof}


def dmc3_accuracy(inputs: dict) -> dict:
    """§2.13 example (lines 1673–1688): a-priori accuracy of a DMC III pair, H = 2000 m, 60 %.

    The stated data are pixel counts, the pixel size and the errors in pixels; the book rewrites
    them rounded (56.9 mm, 2 μm, 1.2 μm, 22.8 mm). The main quantities are computed from the stated
    data by :func:`photolib.image_pair.photo_base` and
    :func:`photolib.image_pair.normal_case_accuracy` (approximate forms, as the book); the
    ``*_printed_chain`` quantities repeat the book's displayed arithmetic with its rounded values.
    """
    px_mm = inputs["pixel_um"] * 1e-3
    frame = inputs["frame_px_x"] * px_mm
    b = image_pair.photo_base(frame, inputs["overlap_percent"])
    m_xy, m_p = inputs["m_xy_px"] * px_mm, inputs["m_p_px"] * px_mm
    H, f = inputs["H_m"], inputs["f_mm"]
    mX, mY, mZ = image_pair.normal_case_accuracy(H, f, b, m_xy, m_xy, m_p, approximate=True)
    pX, _, pZ = image_pair.normal_case_accuracy(H, f, inputs["b_printed_mm"], inputs["m_xy_printed_um"] * 1e-3,
                                                inputs["m_xy_printed_um"] * 1e-3, inputs["m_p_printed_um"] * 1e-3,
                                                approximate=True)
    return {"frame_mm": float(frame), "b_mm": float(b), "m_xy_um": m_xy * 1e3, "m_p_um": m_p * 1e3,
            "m_X": float(mX), "m_Y": float(mY), "m_Z": float(mZ),
            "m_X_printed_chain": float(pX), "m_Z_printed_chain": float(pZ)}


def simulate_pair_accuracy(seed: int = 0, n_points: int = 4000, tilt_deg: float = 3.0, relief_m: float = 20.0,
                           H_m: float = 2000.0, f_mm: float = 92.0, frame_px=(14592, 25728), pixel_um: float = 3.9,
                           m_xy_px: float = 0.5, m_p_px: float = 0.3, overlap_percent: float = 60.0) -> dict:
    """Monte-Carlo check of (2.13.3): simulated ("maket") pair versus the a-priori formulas.

    Ground points are spread over the stereo overlap (relief ±``relief_m``) and imaged by
    collinearity (1.4.12) on a pair with angles up to ±``tilt_deg`` and a nearly horizontal
    base (the premise of §2.13). Measurement follows the error model of (2.13.1): x₁, y₁ with
    m_x = m_y, the parallaxes p, q with m_p, all independent; image 2 is x₁ − p, y₁ − q. Points
    are intersected on ray 1 (:func:`photolib.image_pair.forward_intersection`, as §2.4) with the
    true orientation. Returns the r.m.s. errors of X, Y, Z, the full formula (2.13.3) evaluated
    at each point's x₁, y₁ (r.m.s. over the points), the approximate forms, and the deviations
    rms/predicted − 1 in percent.
    """
    rng = np.random.default_rng(seed)
    px = pixel_um * 1e-3
    lx, ly = frame_px[0] * px, frame_px[1] * px
    b = image_pair.photo_base(lx, overlap_percent)
    s = H_m / f_mm                                         # ground metres per image mm
    io = InteriorOrientation(f_mm)
    t = np.radians(tilt_deg)
    eo1 = ExteriorOrientation(0.0, 0.0, H_m, *rng.uniform(-t, t, 3))
    eo2 = ExteriorOrientation(b * s, rng.uniform(-5, 5), H_m + rng.uniform(-5, 5), *rng.uniform(-t, t, 3))
    X = rng.uniform(b * s - 0.45 * lx * s, 0.45 * lx * s, n_points)
    Y = rng.uniform(-0.45 * ly * s, 0.45 * ly * s, n_points)
    P = np.column_stack([X, Y, rng.uniform(-relief_m, relief_m, n_points)])
    xy1, xy2 = project(P, eo1, io), project(P, eo2, io)
    m_xy, m_p = m_xy_px * px, m_p_px * px
    meas1 = xy1 + rng.normal(0.0, m_xy, xy1.shape)
    meas_pq = (xy1 - xy2) + rng.normal(0.0, m_p, xy1.shape)
    est = image_pair.forward_intersection(meas1, meas1 - meas_pq, eo1, eo2, io)
    rms = np.sqrt(np.mean((est - P) ** 2, axis=0))
    mX, mY, mZ = image_pair.normal_case_accuracy(H_m, f_mm, b, m_xy, m_xy, m_p, x=xy1[:, 0], y=xy1[:, 1])
    full = np.array([np.sqrt(np.mean(mX ** 2)), np.sqrt(np.mean(mY ** 2)), mZ])
    approx = np.array(image_pair.normal_case_accuracy(H_m, f_mm, b, m_xy, m_xy, m_p, approximate=True))
    return {"rms": rms, "full": full, "approx": approx,
            "deviation_full_percent": 100.0 * (rms / full - 1.0),
            "deviation_approx_percent": 100.0 * (rms / approx - 1.0)}


def ten_percent_claim(inputs: dict) -> dict:
    """§2.13, line 1671: "(2.13.3) estimate the accuracy within about 10 % of the real one".

    Runs :func:`simulate_pair_accuracy` for each seed of ``inputs["seeds"]`` (other keys passed
    on) and answers "yes" if every |deviation| of X, Y and Z stays ≤ ``inputs["limit_percent"]``,
    separately for the full formulas and for the approximate forms m_X ≈ (Z/f)m_x, m_Y ≈ (Z/f)m_y.
    """
    opts = {k: v for k, v in inputs.items() if k not in ("seeds", "limit_percent")}
    runs = [simulate_pair_accuracy(seed=s, **opts) for s in inputs["seeds"]]
    worst_full = max(float(np.max(np.abs(r["deviation_full_percent"]))) for r in runs)
    worst_approx = max(float(np.max(np.abs(r["deviation_approx_percent"]))) for r in runs)
    limit = inputs["limit_percent"]
    return {"full_within_limit": "yes" if worst_full <= limit else "no",
            "approx_within_limit": "yes" if worst_approx <= limit else "no",
            "worst_full_percent": worst_full, "worst_approx_percent": worst_approx}


# =================================================================================================
# Printed formulas
# =================================================================================================
# --- §2.1 ------------------------------------------------------------------------------------------
def convergence_angle_formula(inputs: dict) -> dict:
    """(2.1.1) γ_F = b/L: the first-order term of the exact angle 2·arctg(b/2L) at which the eye
    base b is seen from F on its mid-perpendicular (sympy series); numerically the library's
    :func:`photolib.image_pair.convergence_angle` equals the printed form."""
    b, L = _S["b"], _S["L"]
    printed = _p(inputs["printed"])
    exact = 2 * sp.atan(b / (2 * L))
    symbolic = _zero(sp.series(exact, b, 0, 3).removeO() - printed)
    fn = lambdify((b, L), printed)
    numeric = np.isclose(float(image_pair.convergence_angle(0.065, 0.25)), fn(0.065, 0.25), rtol=1e-12)
    return _ok(symbolic, numeric)


def physiological_parallax_formula(inputs: dict) -> dict:
    """(2.1.2) p = ⌒f₁a₁ − ⌒f₂a₂ is the arc measure of the difference γ_A − γ_F.

    Plane model: eyes at (∓b/2, 0), fixation point F = (0, L), point A = (u, v); a retinal arc
    is d times the angle between the visual axis and the ray to A, positive for images left of
    the fovea (targets right of F, the retinal image being inverted). sympy: the printed
    difference of arcs equals d·(γ_A − γ_F); numerically it vanishes for points A on the circle
    through both eyes and F (the horopter of the text: no physiological parallax there).
    """
    b, L, d, u, v = (_S[k] for k in ("b", "L", "d", "u", "v"))
    theta = lambda ex, px, py: sp.atan((px - ex) / py)      # noqa: E731  direction, right of forward
    arc1 = d * (theta(-b / 2, u, v) - theta(-b / 2, 0, L))
    arc2 = d * (theta(b / 2, u, v) - theta(b / 2, 0, L))
    gamma_A = theta(-b / 2, u, v) - theta(b / 2, u, v)
    gamma_F = theta(-b / 2, 0, L) - theta(b / 2, 0, L)
    a1, a2 = sp.symbols("arc1 arc2", real=True)
    printed = sp.sympify(inputs["printed"], locals={"arc1": a1, "arc2": a2}).subs({a1: arc1, a2: arc2})
    # the arcs are sums of the same arctangents: the difference cancels term by term after expansion
    symbolic = zero(printed - d * (gamma_A - gamma_F), fallback=lambda e: sp.expand(e) == 0)
    # horopter: the circle through (−b/2, 0), (b/2, 0), (0, L): centre (0, c), c = (L² − b²/4)/(2L)
    bb, LL, dd = 0.065, 2.0, 0.017
    c = (LL**2 - bb**2 / 4) / (2 * LL)
    rad = LL - c
    phi = np.random.default_rng(0).uniform(0.3, 2.8, 5)
    fn = lambdify((b, L, d, u, v), printed)
    on_circle = np.abs(fn(bb, LL, dd, rad * np.cos(phi), c + rad * np.sin(phi))) < 1e-12
    off = abs(fn(bb, LL, dd, 0.1, 1.5)) > 1e-6
    return _ok(symbolic, bool(np.all(on_circle)), off)


def depth_change_formula(inputs: dict) -> dict:
    """(2.1.3) ΔL = −bΔγ/γ² = −L²Δγ/b: differential of L = b/γ from (2.1.1), both members
    (sympy); numerically :func:`photolib.image_pair.depth_change` equals the second member."""
    b, L, g, dg = _S["b"], _S["L"], _S["gamma"], _S["dgamma"]
    first, second = (_p(s) for s in inputs["printed"])
    derived = sp.diff(b / g, g) * dg
    ok1 = _zero(first - derived)
    ok2 = _zero(second - derived.subs(g, b / L))
    fn = lambdify((b, L, dg), second)
    numeric = np.isclose(float(image_pair.depth_change(0.065, 100.0, 1e-4)), fn(0.065, 100.0, 1e-4), rtol=1e-12)
    return _ok(ok1, ok2, numeric)


# --- §2.4 ------------------------------------------------------------------------------------------
def ray_direction_formula(inputs: dict) -> dict:
    """(2.4.4) (X', Y', Z')ᵀ = A(x − x₀, y − y₀, −f)ᵀ is the direction S → M.

    sympy: with x, y of the printed collinearity equations (1.4.12) and a general matrix A
    (symbols a₁₁ … a₃₃), A·(printed vector) = (−f/Z*)·A·Aᵀ·(M − S) identically,
    Z* = (Aᵀ(M − S))₃;
    for a rotation (A·Aᵀ = E, checked for every rotation with the quaternion form (1.3.7)) the ray is
    therefore parallel to M − S. Numerically :func:`photolib.image_pair.image_rays` equals the
    printed vector turned by A.
    """
    A = _A_symbols()
    X, Y, Z, Xs, Ys, Zs, x0, y0 = (derivations.X, derivations.Y, derivations.Z, derivations.Xs,
                                   derivations.Ys, derivations.Zs, derivations.x0, derivations.y0)
    f = _S["f"]
    d = sp.Matrix([X - Xs, Y - Ys, Z - Zs])
    star = A.T * d
    x = x0 - f * star[0] / star[2]
    y = y0 - f * star[1] / star[2]
    xs, ys = sp.symbols("x_img y_img", real=True)
    printed = sp.Matrix([sp.sympify(s, locals={**_S, "x": xs, "y": ys, "x0": x0, "y0": y0, "f": f})
                         for s in inputs["printed"]])
    ray = (A * printed).subs({xs: x, ys: y})
    symbolic = all(_zero(c) for c in ray * star[2] / (-f) - A * A.T * d)
    Q = _rotation()
    m = sum(v**2 for v in sp.symbols("q_a q_b q_c q_d", real=True))
    Qn = Q * m                                           # the quaternion matrix (1.3.7) itself
    orthogonal = (Qn * Qn.T - m**2 * sp.eye(3)).applyfunc(sp.expand) == sp.zeros(3, 3)
    rng = np.random.default_rng(1)
    io = InteriorOrientation(100.0, 0.1, -0.2)
    eo = ExteriorOrientation(10.0, 20.0, 1000.0, *np.radians(rng.uniform(-5, 5, 3)))
    xy = rng.uniform(-40, 40, (6, 2))
    fn = lambdify((xs, ys, x0, y0, f), list(printed))
    vec = np.column_stack(np.broadcast_arrays(*fn(xy[:, 0], xy[:, 1], io.x0, io.y0, io.f)))
    numeric = np.allclose(image_pair.image_rays(xy, eo, io), vec @ eo.matrix.T, atol=1e-12)
    return _ok(symbolic, orthogonal, numeric)


def cross_product_components(inputs: dict) -> dict:
    """(2.4.7)/(2.4.8): N(r₁ × r₂) = B × r₂ follows from (N r₁ − B) × r₂ = 0 (2.4.5)–(2.4.6);
    the printed i, j, k components of both cross products are compared with sympy's."""
    r1 = sp.Matrix([_S["X1"], _S["Y1"], _S["Z1"]])
    r2 = sp.Matrix([_S["X2"], _S["Y2"], _S["Z2"]])
    B = sp.Matrix([_S["BX"], _S["BY"], _S["BZ"]])
    lhs = [_p(s) for s in inputs["printed_left"]]
    rhs = [_p(s) for s in inputs["printed_right"]]
    c, d = r1.cross(r2), B.cross(r2)
    expansion = ((_S["N"] * r1 - B).cross(r2) - (_S["N"] * c - d)).applyfunc(sp.expand) == sp.zeros(3, 1)
    return _ok(expansion, *(_zero(lhs[i] - c[i]) for i in range(3)), *(_zero(rhs[i] - d[i]) for i in range(3)))


def _intersecting_substitution():
    """Rays through a common point M from S₁ = 0 and S₂ = B with N = N₀ on ray 1, as a
    substitution for the symbols X1 … Z2."""
    M = sp.Matrix([_S["MX"], _S["MY"], _S["MZ"]])
    B = sp.Matrix([_S["BX"], _S["BY"], _S["BZ"]])
    r1, r2 = _rays_through(M, sp.zeros(3, 1), B, _S["N0"], _S["lam"])
    names = ("X1", "Y1", "Z1", "X2", "Y2", "Z2")
    return dict(zip((_S[n] for n in names), list(r1) + list(r2)))


def scale_norm_formula(inputs: dict) -> dict:
    """(2.4.10)/(2.4.11) N = |B × r₂|/|r₁ × r₂|: for rays that meet at M (constructed so that
    N₀ is the true scale on ray 1) the printed numerator² equals N₀²·denominator² (sympy), and
    numerically :func:`photolib.image_pair.intersection_scale` (method="norm") agrees."""
    num, den = (_p(s) for s in inputs["printed"])        # numerator, denominator (square roots)
    sub = _intersecting_substitution()
    symbolic = _zero((num**2 - _S["N0"] ** 2 * den**2).subs(sub))
    rng = np.random.default_rng(2)
    B = np.array([400.0, 12.0, -5.0])
    M = rng.uniform(-300, 300, (5, 3)) + [200, 0, -1000]
    r1, r2 = M / 2.5, 0.7 * (M - B)
    fn = lambdify([_S[k] for k in ("X1", "Y1", "Z1", "X2", "Y2", "Z2", "BX", "BY", "BZ")], num / den)
    printed_N = fn(*r1.T, *r2.T, *B)
    numeric = np.allclose(printed_N, 2.5) and np.allclose(image_pair.intersection_scale(B, r1, r2, method="norm"), 2.5)
    return _ok(symbolic, numeric)


def scale_component_formulas(inputs: dict) -> dict:
    """(2.4.12) the three component ratios: each equals the true N₀ for rays that meet (sympy),
    and :func:`photolib.image_pair.intersection_scale` (method="component", formula=k) agrees."""
    sub = _intersecting_substitution()
    forms = [_p(s) for s in inputs["printed"]]
    symbolic = [_zero((fm - _S["N0"]).subs(sub)) for fm in forms]
    rng = np.random.default_rng(3)
    B = np.array([400.0, 12.0, -5.0])
    M = rng.uniform(-300, 300, (5, 3)) + [200, 0, -1000]
    r1, r2 = M / 2.5, 0.7 * (M - B)
    numeric = all(np.allclose(image_pair.intersection_scale(B, r1, r2, method="component", formula=k), 2.5)
                  for k in (1, 2, 3))
    return _ok(*symbolic, numeric)


# --- §2.5 ------------------------------------------------------------------------------------------
def normal_case_scale(inputs: dict) -> dict:
    """(2.5.1): every member of the printed chain equals the second formula of (2.4.12) with the
    normal-case rays (xᵢ, yᵢ, −f) and B = (B, 0, 0) (sympy), and the last one is B/p, p = x₁ − x₂."""
    x1, y1, x2, y2, f, B, p = (_S[k] for k in ("x1", "y1", "x2", "y2", "f", "B", "p"))
    sub = {_S["X1"]: x1, _S["Y1"]: y1, _S["Z1"]: -f, _S["X2"]: x2, _S["Y2"]: y2, _S["Z2"]: -f,
           _S["BX"]: B, _S["BY"]: 0, _S["BZ"]: 0}
    chain = [_p(s).subs(sub).subs(p, x1 - x2) for s in inputs["printed"]]
    second = ((_S["BX"] * _S["Z2"] - _S["BZ"] * _S["X2"]) / (_S["X1"] * _S["Z2"] - _S["X2"] * _S["Z1"])).subs(sub)
    return _ok(*(_zero(m - second) for m in chain))


def normal_case_coordinates(inputs: dict) -> dict:
    """(2.5.3)/(2.5.4): with the normal-case images x₁ = −fX/Z, y₁ = −fY/Z, x₂ = −f(X − B)/Z of a
    point (X, Y, Z) (S₁ at the origin, S₂ = (B, 0, 0)), the printed formulas give back X, Y, Z
    (sympy); :func:`photolib.image_pair.normal_case_intersection` numerically."""
    Xs, Ys, Zs = sp.symbols("X_obj Y_obj Z_obj", real=True)
    f, B, p = _S["f"], _S["B"], _S["p"]
    x1, y1, x2 = -f * Xs / Zs, -f * Ys / Zs, -f * (Xs - B) / Zs
    forms = [_p(s) for s in inputs["printed"]]
    sub = {_S["x1"]: x1, _S["y1"]: y1, _S["x2"]: x2, _S["p"]: x1 - x2}
    Zval = forms[2].subs(sub)
    outs = [fm.subs(sub).subs(_S["Z"], Zval) for fm in forms]
    symbolic = all(_zero(o - t) for o, t in zip(outs, (Xs, Ys, Zs)))
    P = np.array([[120.0, -80.0, -1000.0], [300.0, 200.0, -960.0]])
    fx = lambda P_: -100.0 * P_[:, :2] / P_[:, 2:]            # noqa: E731
    xy1, xy2 = fx(P), fx(P - [400.0, 0, 0])
    numeric = np.allclose(image_pair.normal_case_intersection(xy1[:, 0], xy1[:, 1], xy2[:, 0], 100.0, 400.0), P)
    return _ok(symbolic, numeric)


# --- §2.7 ------------------------------------------------------------------------------------------
def _det_rows(rows):
    return sp.Matrix([[_p(c) for c in row] for row in rows]).det()


def coplanarity_formula(inputs: dict) -> dict:
    """(2.7.1)/(2.7.2): the printed determinant equals the mixed product B·(r₁ × r₂) and vanishes
    identically for rays that meet (sympy); (2.7.3): the determinant with (1, b_y, b_z),
    b_y = B_Y/B_X, b_z = B_Z/B_X, is (2.7.2)/B_X. :func:`photolib.image_pair.coplanarity` numerically."""
    det = _det_rows(inputs["printed_rows"])
    r1 = sp.Matrix([_S["X1"], _S["Y1"], _S["Z1"]])
    r2 = sp.Matrix([_S["X2"], _S["Y2"], _S["Z2"]])
    B = sp.Matrix([_S["BX"], _S["BY"], _S["BZ"]])
    mixed = B.dot(r1.cross(r2))
    if inputs.get("normalised", False):
        derived = (mixed / _S["BX"]).subs({_S["BY"]: _S["by"] * _S["BX"], _S["BZ"]: _S["bz"] * _S["BX"]})
        same = _zero(det - derived)
        vanish = _zero(det.subs({_S["by"]: _S["BY"] / _S["BX"], _S["bz"]: _S["BZ"] / _S["BX"]})
                       .subs(_intersecting_substitution()))
    else:
        same = _zero(det - mixed)
        vanish = _zero(det.subs(_intersecting_substitution()))
    rng = np.random.default_rng(4)
    base = np.array([1.0, 0.03, -0.02])
    a, c = rng.normal(size=(4, 3)), rng.normal(size=(4, 3))
    fn = lambdify([_S[k] for k in ("X1", "Y1", "Z1", "X2", "Y2", "Z2")], mixed.subs(
        {_S["BX"]: base[0], _S["BY"]: base[1], _S["BZ"]: base[2]}))
    numeric = np.allclose(image_pair.coplanarity(base, a, c), fn(*a.T, *c.T), atol=1e-12)
    return _ok(same, vanish, numeric)


def coplanarity_system(inputs: dict) -> dict:
    """(2.7.4) and (2.7.5): the printed condition of each system equals (2.7.3) with the system's
    three fixed parameters set to zero, as derived in :func:`photolib.derivations.coplanarity_expression`
    (rays A'ᵢ(xᵢ, yᵢ, −fᵢ) of the rotation sequence ``order``, reduced coordinates)."""
    order = inputs.get("order", "kaw")
    system = inputs["system"]
    D = derivations
    phi = D.coplanarity_expression(order)
    fixed = {s: 0 for s in D.RELATIVE_ORIENTATION_PARAMETERS if s not in D.RELATIVE_ORIENTATION_SYSTEMS[system]}
    derived = phi.subs(fixed)
    r1 = D.rotation_matrix_symbolic(order, D.omega1, D.alpha1, D.kappa1) * sp.Matrix([D.x1, D.y1, -D.f1])
    r2 = D.rotation_matrix_symbolic(order, D.omega2, D.alpha2, D.kappa2) * sp.Matrix([D.x2, D.y2, -D.f2])
    loc = {**_S, "X1": r1[0], "Y1": r1[1], "Z1": r1[2], "X2": r2[0], "Y2": r2[1], "Z2": r2[2],
           "x1": D.x1, "y1": D.y1, "f1": D.f1, "x01": 0, "y01": 0, "by": D.b_y, "bz": D.b_z}
    if "printed_rows" in inputs:
        printed = sp.Matrix([[sp.sympify(c, locals=loc) for c in row] for row in inputs["printed_rows"]]).det()
    else:
        printed = sp.sympify(inputs["printed"], locals=loc)
    printed = printed.subs(fixed)
    diff = lambdify(list(D.RELATIVE_ORIENTATION_PARAMETERS) + [D.x1, D.y1, D.f1, D.x2, D.y2, D.f2],
                       printed - derived)
    rng = np.random.default_rng(5)
    vals = rng.uniform(-0.3, 0.3, (20, 14))
    vals[:, 10] = vals[:, 13] = 100.0
    numeric = np.allclose([diff(*v) for v in vals], 0.0, atol=1e-9)
    symbolic = sp.expand(sp.expand_trig(printed - derived)) == 0
    return _ok(symbolic or numeric, numeric)


# --- §2.9 ------------------------------------------------------------------------------------------
def model_base_components(inputs: dict) -> dict:
    """§2.9: B_Y, B_Z of the model base from B_X and the direction (1, b_y, b_z) of §2.7
    (b_y = B_Y/B_X, b_z = B_Z/B_X); sympy, and :func:`photolib.image_pair.build_model` puts S₂ at
    B_X·(1, b_y, b_z)."""
    BX, by, bz = _S["BX"], _S["by"], _S["bz"]
    BY_p, BZ_p = (_p(s) for s in inputs["printed"])
    symbolic = _zero(BY_p - by * BX) and _zero(BZ_p - bz * BX)
    xy1, xy2, io, *_ = synthetic_pair(8, 6)
    ro = image_pair.relative_orientation(xy1, xy2, io, system="dependent")
    model = image_pair.build_model(xy1, xy2, ro, io, base_length=250.0)
    fn = lambdify((BX, by, bz), [BY_p, BZ_p])
    numeric = np.allclose(model.eo2.center[1:], fn(250.0, ro.b_y, ro.b_z), atol=1e-9)
    return _ok(symbolic, numeric)


# --- §2.10 / §2.12 ---------------------------------------------------------------------------------
def _A_symbols():
    return sp.Matrix(3, 3, lambda i, j: _S[f"a{i + 1}{j + 1}"])


def similarity_formula(inputs: dict) -> dict:
    """(2.10.4) and its component form (2.10.5): the printed components must equal
    R₀ + t·A_M·R_M (2.10.3) row by row (sympy, general A_M and t). For (2.10.4) itself the
    similarity is also checked: distances scale by t exactly (A_M any rotation), and
    :class:`photolib.image_pair.SimilarityTransform` applies the printed form numerically."""
    A = _A_symbols()
    RM = sp.Matrix([_S["XM"], _S["YM"], _S["ZM"]])
    R0 = sp.Matrix([_S["X0"], _S["Y0"], _S["Z0"]])
    derived = R0 + A * RM * _S["t"]                                               # (2.10.3)
    printed = [_p(s) for s in inputs["printed"]]
    same = all(_zero(printed[i] - derived[i]) for i in range(3))
    # similarity property of the printed form: distances scale by t (random rotations A_M)
    fn = lambdify([*R0, *(A[i, j] for i in range(3) for j in range(3)), *RM, _S["t"]], printed)
    rng = np.random.default_rng(6)
    dist = True
    for w, a, k in rng.uniform(-1, 1, (5, 3)):
        AM = rotation_matrix(w, a, k, "wak")
        P = rng.uniform(-1, 1, (2, 3))
        img = [np.array(fn(1.0, 2.0, 3.0, *AM.ravel(), *p, 7.0), float) for p in P]
        dist &= np.isclose(np.linalg.norm(img[0] - img[1]), 7.0 * np.linalg.norm(P[0] - P[1]), rtol=1e-12)
    T = image_pair.SimilarityTransform(1000.0, 2000.0, 300.0, 0.02, -0.01, 0.3, 450.0)
    pts = np.random.default_rng(7).uniform(-1, 1, (4, 3))
    num = np.column_stack(np.broadcast_arrays(*fn(*T.shift, *T.matrix.ravel(), *pts.T, T.t)))
    numeric = np.allclose(T.apply(pts), num, atol=1e-9)
    return _ok(same, bool(dist), numeric)


def image_orientation_formula(inputs: dict) -> dict:
    """(2.12.1), (2.12.2) and the angles of §2.12 (= (1.3.3)), at random configurations.

    Derivation: a model is the object scaled by 1/t and turned by A_Mᵀ about R₀, so an image
    with centre S and matrix A has S_M = A_Mᵀ(S − R₀)/t and A' = A_MᵀA in the model frame. The
    printed S = R₀ + A_M·S_M·t and A = A_M·A' must give S and A back (random rotations A_M, A);
    the printed angle formulas must return ω, α, κ of A = A_ω A_α A_κ (1.3.2); and
    :func:`photolib.image_pair.image_orientation_from_model` must recover the true orientation of a
    simulated pair after relative and absolute orientation.
    """
    A = _A_symbols()
    t = _S["t"]
    SMs = sp.symbols("XSM YSM ZSM", real=True)
    loc = {**_S, "XSM": SMs[0], "YSM": SMs[1], "ZSM": SMs[2], "arctg": sp.atan, "arcsin": sp.asin}
    centre_fn = lambdify([_S["X0"], _S["Y0"], _S["Z0"], *A, *SMs, t],
                            [sp.sympify(s, locals=loc) for s in inputs["printed_centre"]])
    angle_fns = [lambdify(list(A), sp.sympify(s, locals=loc)) for s in inputs["printed_angles"]]
    rng = np.random.default_rng(8)
    ok_centre = ok_matrix = ok_angles = True
    for _ in range(10):
        AM = rotation_matrix(*rng.uniform(-1, 1, 3), "wak")
        w, a, k = rng.uniform(-0.5, 0.5, 3)
        Ai = rotation_matrix(w, a, k, "wak")
        R0, S, tt = rng.uniform(-500, 500, 3), rng.uniform(-500, 500, 3), rng.uniform(0.5, 3000)
        SM, Ap = AM.T @ (S - R0) / tt, AM.T @ Ai
        ok_centre &= np.allclose(np.array(centre_fn(*R0, *AM.ravel(), *SM, tt), float), S, atol=1e-9)
        ok_matrix &= np.allclose(AM @ Ap, Ai, atol=1e-12)                          # (2.12.2)
        ok_angles &= np.allclose([fn(*Ai.ravel()) for fn in angle_fns], [w, a, k], atol=1e-12)
    xy1, xy2, io, eo1, eo2, P = synthetic_pair(10, 9)
    ro = image_pair.relative_orientation(xy1, xy2, io, system="independent")
    model = image_pair.build_model(xy1, xy2, ro, io, base_length=1.0)
    T = image_pair.absolute_orientation(model.points, P, order="wak")
    e1, e2 = image_pair.image_orientation_from_model(model, T, order="wak")
    numeric = np.allclose(e1.center, eo1.center, atol=1e-6) and np.allclose(e2.matrix, eo2.matrix, atol=1e-9)
    return _ok(bool(ok_centre), bool(ok_matrix), bool(ok_angles), numeric)


# --- §2.13 -----------------------------------------------------------------------------------------
def accuracy_partials(inputs: dict) -> dict:
    """(2.13.2): the printed partial derivatives of (2.5.4) (sympy), with Z = −Bf/p for the
    equalities of ∂Z/∂p and p = b for the last member."""
    x1, y1, f, Z, B, p, b = (_S[k] for k in ("x1", "y1", "f", "Z", "B", "p", "b"))
    X, Y = -Z / f * x1, -Z / f * y1
    Zp = -B / p * f
    pr = {k: _p(v) for k, v in inputs["printed"].items()}
    ok = [_zero(pr["dX_dZ"] - sp.diff(X, Z)), _zero(pr["dX_dx1"] - sp.diff(X, x1)),
          _zero(pr["dY_dZ"] - sp.diff(Y, Z)), _zero(pr["dY_dy1"] - sp.diff(Y, y1))]
    dZdp = sp.diff(Zp, p)
    for key in ("dZ_dp", "dZ_dp_2"):
        ok.append(_zero(pr[key].subs(Z, Zp) - dZdp))
    ok.append(_zero(pr["dZ_dp_3"].subs(Z, Zp).subs(b, p) - dZdp))
    return _ok(*ok)


def accuracy_formulas(inputs: dict) -> dict:
    """(2.13.1)/(2.13.3): error propagation through (2.5.4) with the independent measurements
    x₁, y₁, p (sympy). X = x₁B/p, Y = y₁B/p, Z = −Bf/p give
    m_X² = (∂X/∂x₁)²m_x² + (∂X/∂p)²m_p², i.e. (x₁m_Z/f)² + (Z m_x/f)² with m_Z = |∂Z/∂p| m_p and
    p = b; Z in (2.13.3) stands for the flying height H = |Z| (positive). The printed forms are
    compared squared (they are square roots); :func:`photolib.image_pair.normal_case_accuracy`
    numerically."""
    x1, y1, f, B, p, b, H, mx, my, mp, mZ = (_S[k] for k in ("x1", "y1", "f", "B", "p", "b", "H", "mx", "my",
                                                               "mp", "mZ"))
    X, Y, Zf = x1 * B / p, y1 * B / p, -B * f / p
    var = lambda F, a, ma: sp.diff(F, a) ** 2 * ma**2 + sp.diff(F, p) ** 2 * mp**2   # noqa: E731
    sub = {B: H * b / f, p: b}                         # flat terrain: p = b and H = Bf/b
    mZ2 = (sp.diff(Zf, p) ** 2 * mp**2).subs(sub)
    mX2 = var(X, x1, mx).subs(sub)
    mY2 = var(Y, y1, my).subs(sub)
    loc = {**_S, "Z": H, "x": x1, "y": y1}
    pX, pY, pZ = (sp.sympify(s, locals=loc) for s in inputs["printed"])
    ok = [_zero(pZ**2 - mZ2), _zero((pX**2).subs(mZ, sp.sqrt(mZ2)) - mX2), _zero((pY**2).subs(mZ, sp.sqrt(mZ2)) - mY2)]
    fn = lambdify((H, f, b, mx, my, mp, x1, y1), [pX.subs(mZ, pZ), pY.subs(mZ, pZ), pZ])
    lib = image_pair.normal_case_accuracy(2000.0, 92.0, 22.8, 0.002, 0.0015, 0.0012, x=25.0, y=-40.0)
    numeric = np.allclose(lib, fn(2000.0, 92.0, 22.8, 0.002, 0.0015, 0.0012, 25.0, -40.0), rtol=1e-12)
    return _ok(*ok, numeric)


def photo_base_formula(inputs: dict) -> dict:
    """§2.13 b = l_x(100 % − P_x)/100 %: the principal point of image 2 is b from that of image 1
    (image scale), so the two frames of side l_x share l_x − b, and the overlap is P_x = (l_x − b)/l_x
    (sympy solve); :func:`photolib.image_pair.photo_base` numerically."""
    lx, Px, b = sp.symbols("l_x P_x b", positive=True)
    derived = sp.solve(sp.Eq(Px / 100, (lx - b) / lx), b)[0]
    printed = sp.sympify(inputs["printed"], locals={"l_x": lx, "P_x": Px})
    numeric = np.isclose(image_pair.photo_base(56.9, 60.0), float(printed.subs({lx: 56.9, Px: 60})), rtol=1e-12)
    return _ok(_zero(printed - derived), numeric)
