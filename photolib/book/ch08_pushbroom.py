"""Chapter 8, §8.1–8.5, §8.7, §8.8 (cases 1–3) — scanner sensor models: formula checks and
inline statements.

Adapters for the ``[[formula]]`` and ``[[example]]`` entries of ``textbook/ch08_pushbroom.toml``.
Formula adapters take the printed formula (as sympy text, or a reading of it) in ``inputs`` and
return ``{"printed_equals_derived": bool}``; the derivations are done here with sympy, independent
of :mod:`photolib.pushbroom`. Statements are checked by counting, by ranks of design matrices at
generic (seeded random) points, and by small seeded simulations with :mod:`photolib.pushbroom`
(conditions in the entries' notes).
"""

from __future__ import annotations

import math

import numpy as np
import sympy as sp

_N = ("x_i", "x_c", "x_0", "y_c", "y_0", "f", "x_mu", "x_n", "X", "Y", "Z", "X_S", "Y_S", "Z_S",
      "Xp", "Yp", "Zp", "Xs", "Ys", "Zs", "x", "y", "z", "theta", "l_y", "y_m", "phi", "alpha", "f_0", "D_0")
_S = {n: sp.Symbol(n, real=True) for n in _N}


def _parse(text):
    return sp.parse_expr(str(text), local_dict=dict(_S))


def _ok(flag) -> dict:
    return {"printed_equals_derived": bool(flag)}


def _rational_rotation(b, c, d, a):
    """An exactly orthogonal rational rotation from the quaternion (a, b, c, d), as (1.3.7)."""
    q = a * a + b * b + c * c + d * d
    M = sp.Matrix([[a*a + b*b - c*c - d*d, 2*(b*c - a*d), 2*(b*d + a*c)],
                   [2*(b*c + a*d), a*a - b*b + c*c - d*d, 2*(c*d - a*b)],
                   [2*(b*d - a*c), 2*(c*d + a*b), a*a - b*b - c*c + d*d]])
    return M / q


# --------------------------------------------------------------------------- rays (8.2.1)–(8.4.3)
def ray_vector_formula(inputs: dict) -> dict:
    """(8.2.1): the ray of a CCD pixel. Derived: its along-track component is the offset x_i of the
    CCD row that forms the image line (the text below the formula, and (8.2.2)); the line
    coordinate x_c only selects the line (the time)."""
    printed = [_parse(t) for t in inputs["vector"]]
    derived = [_S["x_i"] - _S["x_0"], _S["y_c"] - _S["y_0"], -_S["f"]]
    return _ok(all(sp.simplify(p - d) == 0 for p, d in zip(printed, derived)))


def unit_ray_formula(inputs: dict) -> dict:
    """(8.2.2), (8.4.2), (8.4.3): the printed vector divided by the printed norm must be the unit
    vector along (x_line − x₀, y_c − y₀, −f); checked by |r|² ≡ 1 and parallelism."""
    num = sp.Matrix([_parse(t) for t in inputs["numerator"]])
    norm = _parse(inputs["norm"])
    r = num / norm
    unit = sp.simplify(sum(c ** 2 for c in r) - 1) == 0
    line = _S[inputs.get("line_offset", "x_i")]
    ref = sp.Matrix([line - _S["x_0"], _S["y_c"] - _S["y_0"], -_S["f"]])
    parallel = all(sp.simplify(e) == 0 for e in r.cross(ref))
    return _ok(unit and parallel)


def whiskbroom_formula(inputs: dict) -> dict:
    """(8.3.1): r = (0, sin φ, −cos φ), φ = θ·y_m/l_y — unit length, φ = ±θ/2 at the line ends."""
    th, ly, ym = _S["theta"], _S["l_y"], _S["y_m"]
    phi = _parse(inputs["phi"])
    r = sp.Matrix([0, sp.sin(phi), -sp.cos(phi)])
    unit = sp.simplify(r.dot(r) - 1) == 0
    ends = sp.simplify(phi.subs(ym, ly / 2) - th / 2) == 0 and sp.simplify(phi.subs(ym, -ly / 2) + th / 2) == 0
    from ..pushbroom import ray_whiskbroom
    lib = np.allclose(ray_whiskbroom(250.0, 1.0, 1000), [0, math.sin(0.25), -math.cos(0.25)], atol=1e-15)
    return _ok(unit and ends and lib)


def tilted_focal_formula(inputs: dict) -> dict:
    """(8.4.1): the tilted camera keeps the nadir scale f₀/D₀ at the slant distance D₀/cos α."""
    fH = sp.Symbol("f_H", positive=True)
    a, f0, D0 = _S["alpha"], _S["f_0"], _S["D_0"]
    derived = sp.solve(sp.Eq(fH / (D0 / sp.cos(a)), f0 / D0), fH)[0]
    return _ok(sp.simplify(_parse(inputs["f_tilted"]) - derived) == 0)


# --------------------------------------------------------------------------- rigorous model §8.5, §8.7
def ground_formula(inputs: dict) -> dict:
    """(8.5.1)/(8.7.1): the ray S + λ(X′, Y′, Z′) at height Z. Every printed line must be one of
    the two derived equations (an unparsable or extra line fails)."""
    Xp, Yp, Zp, Z = _S["Xp"], _S["Yp"], _S["Zp"], _S["Z"]
    lam = (Z - _S["Z_S"]) / Zp
    derived = [_S["X_S"] + lam * Xp, _S["Y_S"] + lam * Yp]
    try:
        printed = [_parse(t) for t in inputs["lines"]]
    except Exception:  # noqa: BLE001 — an unparsable printed line (OCR fragment) is not the formula
        return _ok(False)
    return _ok(len(printed) == 2 and all(sp.simplify(p - d) == 0 for p, d in zip(printed, derived)))


def inverse_formula(inputs: dict) -> dict:
    """(8.5.2)/(8.8.5): with the unit ray (x, y, z) ∥ (X*, Y*, Z*) = Aᵀ(P − S), x = z·X*/Z* and
    y = z·Y*/Z*. The printed left-hand sides are compared with the derived x, y."""
    c = sp.Symbol("c", positive=True)
    Xs, Ys, Zs = _S["Xs"], _S["Ys"], _S["Zs"]
    ray = {"x": c * Xs, "y": c * Ys, "z": c * Zs}            # the ray is parallel to (X*, Y*, Z*)
    rhs = [ray["z"] * Xs / Zs, ray["z"] * Ys / Zs]
    lhs = [ray[name] for name in inputs["left"]]
    return _ok(all(sp.simplify(a - b) == 0 for a, b in zip(lhs, rhs)))


def eo_polynomial_formula(inputs: dict) -> dict:
    """(8.5.3)–(8.5.5): the elements E = E₀ + k·Δt [+ d·Δt²]. Checks: the printed constant term is
    the first-line element E₀ (the symbols the text defines: X_S0 … κ0), and the chain rule the
    resection uses, ∂F/∂k = Δt·∂F/∂E₀ (and ∂F/∂d = Δt²·∂F/∂E₀), for any model function F."""
    E0, k, d, dt = sp.symbols("E_0 k d Delta_t", real=True)
    F = sp.Function("F")
    degree = int(inputs.get("degree", 1))
    E = E0 + k * dt + (d * dt ** 2 if degree == 2 else 0)
    chain = sp.simplify(sp.diff(F(E), k) - dt * sp.diff(F(E), E0)) == 0
    if degree == 2:
        chain = chain and sp.simplify(sp.diff(F(E), d) - dt ** 2 * sp.diff(F(E), E0)) == 0
    defined = {"X_S0", "Y_S0", "Z_S0", "omega_0", "alpha_0", "kappa_0"}
    return _ok(chain and all(t in defined for t in inputs["constant_terms"]))


# --------------------------------------------------------------------------- approximating models
def _design(kind, P, rows, cols):
    H = np.column_stack([P, np.ones(len(P))])
    Z4 = np.zeros((len(P), 4))
    if kind == "dlt":
        return np.vstack([np.hstack([H, Z4, -rows[:, None] * P]), np.hstack([Z4, H, -cols[:, None] * P])])
    if kind == "affine":
        return np.vstack([np.hstack([H, Z4]), np.hstack([Z4, H])])
    return np.vstack([np.hstack([H, -rows[:, None] * P, Z4]), np.hstack([np.zeros((len(P), 7)), H])])


def _generic(kind, n, seed):
    rng = np.random.default_rng(seed)
    P = rng.uniform(-1, 1, (n, 3))
    rows = rng.uniform(-1, 1, n)
    cols = rng.uniform(-1, 1, n)
    return _design(kind, P, rows, cols)


_COEFS = {"dlt": 11, "affine": 8, "parallel-perspective": 11}


def minimum_points(kind, seed=0):
    """Fewest generic GCPs for which the linearised design of the model has full column rank."""
    n = 1
    while np.linalg.matrix_rank(_generic(kind, n, seed)) < _COEFS[kind]:
        n += 1
    return n


def approximate_model_formula(inputs: dict) -> dict:
    """(8.5.10)–(8.5.12): the model is linear in its coefficients after multiplying by the
    denominator; the printed coefficient count equals the rank of that design at generic points."""
    kind = inputs["kind"]
    rank = np.linalg.matrix_rank(_generic(kind, 20, int(inputs.get("seed", 0))))
    return _ok(rank == int(inputs["coefficients"]) == _COEFS[kind])


def approximate_model_counts(inputs: dict) -> dict:
    """Coefficients and the fewest GCPs of the DLT, affine and parallel-perspective models."""
    seed = int(inputs.get("seed", 0))
    out = {}
    for kind, key in (("dlt", "dlt"), ("affine", "affine"), ("parallel-perspective", "pp")):
        out[f"{key}_coefficients"] = _COEFS[kind]
        out[f"{key}_min_gcp"] = minimum_points(kind, seed)
    return out


# --------------------------------------------------------------------------- resection §8.5
def _space_sensor(quadratic=False):
    from ..pushbroom import EOPolynomial, Pushbroom
    eo = EOPolynomial([1000.0, -500.0, 475e3, 0.01, 0.02, 0.005], [7000, 5, -2, 1e-6, -1e-6, 2e-6],
                      [0.1, -0.05, 0.01, 1e-9, 2e-9, -1e-9] if quadratic else None)
    return Pushbroom(3.8, 8e-6, 38000, 1 / 7000, eo, n_rows=30000)


def _airborne_sensor(quadratic=False):
    from ..pushbroom import EOPolynomial, Pushbroom
    eo = EOPolynomial([0.0, 0.0, 3000.0, 0.01, -0.02, 0.03], [60, 1, 0.5, 1e-3, -2e-3, 1e-3],
                      [0.2, -0.1, 0.05, 1e-4, 2e-4, -1e-4] if quadratic else None)
    return Pushbroom(0.1, 6.5e-6, 12000, 1 / 600, eo, n_rows=20000)


def _gcps(cam, n, top, seed):
    rng = np.random.default_rng(seed)
    rows, cols = rng.uniform(0, cam.n_rows, n), rng.uniform(0, cam.n_columns - 1, n)
    Z = rng.uniform(0, top, n) if top > 0 else np.zeros(n)
    X, Y = cam.ground(rows, cols, Z)
    return rows, cols, np.column_stack([X, Y, Z])


def resection_counts(inputs: dict) -> dict:
    """Unknowns of the linear/quadratic time-polynomial resection and the fewest GCPs, with a
    rank check: the column-scaled Jacobian at the minimum number of hilly GCPs has full rank."""
    from ..pushbroom import resection_condition
    degree = int(inputs["degree"])
    n_unknown = 6 + 6 * degree
    n_min = math.ceil(n_unknown / 2)
    cam = _airborne_sensor(quadratic=degree == 2)
    rows, cols, XYZ = _gcps(cam, n_min, 300.0, int(inputs.get("seed", 3)))
    cond = resection_condition(cam, rows, cols, XYZ, degree=degree)
    return {"unknowns": n_unknown, "min_gcp": n_min if cond < 1e8 else None, "condition": cond}


def flat_terrain(inputs: dict) -> dict:
    """Fig. 8.14: condition numbers of the linear resection on flat and hilly GCPs, free and with
    one element fixed (Resurs-P-like sensor, 12 GCPs; columns scaled to unit norm)."""
    from ..pushbroom import resection_condition
    cam = _space_sensor()
    seed = int(inputs.get("seed", 0))
    rows, cols, flat = _gcps(cam, 12, 0.0, seed)
    out = {"cond_flat_free": resection_condition(cam, rows, cols, flat)}
    for name in ("Z_S0", "X_S0", "alpha0"):
        out[f"cond_flat_fixed_{name}"] = resection_condition(cam, rows, cols, flat, fixed=(name,))
    r2, c2, hilly = _gcps(cam, 12, 2000.0, seed)
    out["cond_hilly_free"] = resection_condition(cam, r2, c2, hilly)
    out["flat_free"] = "singular" if out["cond_flat_free"] > 1e10 else "regular"
    worst = max(out[f"cond_flat_fixed_{n}"] for n in ("Z_S0", "X_S0", "alpha0"))
    out["flat_fixed_one"] = "regular" if worst < 1e8 else "singular"
    return out


def approximation_errors(inputs: dict) -> dict:
    """§8.5 claim: the time-polynomial EO model describes a pushbroom better than the DLT, affine
    and parallel-perspective approximations. Seeded simulation: Resurs-P-like image, 30 000 lines,
    heights 0–1000 m, 20 GCPs, 200 check points; largest check-point error (px) of each model."""
    from ..pushbroom import fit_affine, fit_dlt, fit_parallel_perspective, resect_pushbroom, EOPolynomial
    cam = _space_sensor()
    seed = int(inputs.get("seed", 10))
    rows, cols, XYZ = _gcps(cam, int(inputs.get("n_gcp", 20)), 1000.0, seed)
    cr, cc, chk = _gcps(cam, 200, 1000.0, seed + 1)
    start = cam.with_eo(EOPolynomial(cam.eo.eo0 + [50, -40, 30, 1e-5, -1e-5, 1e-4], cam.eo.k + [0.3, 0.2, 0, 0, 0, 0]))
    models = {"time_polynomial": resect_pushbroom(start, rows, cols, XYZ).sensor,
              "dlt": fit_dlt(XYZ, rows, cols), "affine": fit_affine(XYZ, rows, cols),
              "parallel_perspective": fit_parallel_perspective(XYZ, rows, cols),
              "parallel_perspective_cols": fit_parallel_perspective(XYZ, rows, cols, perspective="cols")}
    out = {}
    for name, m in models.items():
        pr, pc = m.project(*chk.T)
        out[f"err_{name}"] = float(max(np.max(np.abs(pr - cr)), np.max(np.abs(pc - cc))))
    printed_models = ("time_polynomial", "dlt", "affine", "parallel_perspective")
    out["best_model"] = min(printed_models, key=lambda n: out[f"err_{n}"]).replace("_", "-")
    return out


# --------------------------------------------------------------------------- stereo §8.8
def intersection_formula(inputs: dict) -> dict:
    """(8.8.1) with N = |B × r₂|/|r₁ × r₂| (the frame formula of §2.4): for two rays through one
    point, S₁ + N·r₁ is that point (exact rational arithmetic at a seeded random configuration)."""
    rng = np.random.default_rng(int(inputs.get("seed", 1)))
    P, S1, S2 = (sp.Matrix([sp.Rational(int(v), 7) for v in rng.integers(-50, 50, 3)]) for _ in range(3))
    r1, r2 = (P - S1) * sp.Rational(3, 2), (P - S2) * sp.Rational(2, 5)   # arbitrary ray lengths
    B = S2 - S1
    N = sp.sqrt(B.cross(r2).dot(B.cross(r2))) / sp.sqrt(r1.cross(r2).dot(r1.cross(r2)))
    return _ok(sp.simplify(S1 + N * r1 - P) == sp.zeros(3, 1))


def first_line_formula(inputs: dict) -> dict:
    """(8.8.2): r = ΔA·r′ expresses a ray of line j in the first line's scanner frame when the
    attitude composes as A_j = A₀·ΔA_j (the increment applied in the scanner frame): then
    A₀·r = A_j·r′. Symbolic check with generic matrices; ``composition = "A0*dA"``."""
    A0 = sp.Matrix(3, 3, sp.symbols("a0:9", real=True))
    dA = sp.Matrix(3, 3, sp.symbols("d0:9", real=True))
    rp = sp.Matrix(sp.symbols("r0:3", real=True))
    Aj = A0 * dA if inputs.get("composition", "A0*dA") == "A0*dA" else dA * A0
    return _ok(sp.expand(A0 * (dA * rp) - Aj * rp) == sp.zeros(3, 1))


def coplanarity_formula(inputs: dict) -> dict:
    """(8.8.3)/(8.8.4): the determinant |B; A₁r₁; A₂r₂| vanishes for the rays of one object point
    (exact rational check with exactly orthogonal rational rotation matrices, quaternion form (1.3.7))."""
    rng = np.random.default_rng(int(inputs.get("seed", 2)))
    P, S1, S2 = (sp.Matrix([int(v) for v in rng.integers(-100, 100, 3)]) for _ in range(3))
    A1 = _rational_rotation(1, 2, -3, 40)
    A2 = _rational_rotation(-2, 1, 1, 30)
    r1, r2 = A1.T * (P - S1), A2.T * (P - S2)         # rays in the scanner frames
    M = sp.Matrix.hstack(S2 - S1, A1 * r1, A2 * r2).T
    return _ok(sp.simplify(M.det()) == 0)


def coplanarity_partials(inputs: dict) -> dict:
    """(8.8.6): a₁…a₁₂ of the determinant F = B·(R₁ × R₂), B = S₂ − S₁, R_i = A_i r_i, by the
    product rule — the form in which photolib assembles them: ∂F/∂S₁ = −R₁ × R₂,
    ∂F/∂S₂ = R₁ × R₂, ∂F/∂θ₁ = B·(∂R₁/∂θ₁ × R₂), ∂F/∂θ₂ = B·(R₁ × ∂R₂/∂θ₂)."""
    t1, t2 = sp.symbols("theta_1 theta_2", real=True)
    S1 = sp.Matrix(sp.symbols("S1_0:3", real=True))
    S2 = sp.Matrix(sp.symbols("S2_0:3", real=True))
    R1 = sp.Matrix([sp.Function(f"R1_{i}")(t1) for i in range(3)])
    R2 = sp.Matrix([sp.Function(f"R2_{i}")(t2) for i in range(3)])
    B = S2 - S1
    F = B.dot(R1.cross(R2))
    checks = [sp.simplify(sp.diff(F, S1[i]) + R1.cross(R2)[i]) == 0 for i in range(3)]
    checks += [sp.simplify(sp.diff(F, S2[i]) - R1.cross(R2)[i]) == 0 for i in range(3)]
    checks.append(sp.simplify(sp.diff(F, t1) - B.dot(sp.diff(R1, t1).cross(R2))) == 0)
    checks.append(sp.simplify(sp.diff(F, t2) - B.dot(R1.cross(sp.diff(R2, t2)))) == 0)
    return _ok(all(checks) and int(inputs.get("unknowns", 12)) == 12)


def collinearity_partials(inputs: dict) -> dict:
    """(8.8.7): with S_ij = S_i0 + ΔS_ij (ΔS measured), the coefficients by the first-line centre
    equal those by the line's centre: ∂F/∂X_S0 = ∂F/∂X_S for any F(X − X_S, …)."""
    X, XS0, dX = sp.symbols("X X_S0 DeltaX", real=True)
    F = sp.Function("F")
    u = sp.Symbol("u", real=True)
    lhs = sp.diff(F(X - (XS0 + dX)), XS0)
    rhs = sp.diff(F(u), u).subs(u, X - XS0 - dX) * -1
    return _ok(sp.simplify(lhs - rhs) == 0 and int(inputs.get("unknowns_per_image", 6)) == 6)


# --------------------------------------------------------------------------- Table 8.1, §8.2 claims
def focal_lengths(inputs: dict) -> dict:
    """§8.2: 'f as a rule more than one metre' — f = Δ·H/GSD from Table 8.1 with an assumed pixel
    pitch Δ (not in the book; 8 µm by default, typical of these sensors)."""
    pitch = float(inputs.get("pixel_pitch", 8e-6))
    f = {name: pitch * H * 1e3 / gsd for name, gsd, H in inputs["table"]}
    out = {f"f_{name}": v for name, v in f.items()}
    out["f_min"] = min(f.values())
    out["f_more_than_1m"] = "more than 1 m" if min(f.values()) > 1.0 else "not always"
    return out
