"""Chapter 11, §11.4–11.9 (terrestrial stereophotogrammetry): formula checks and the book's numbers.

Adapters for the ``[[formula]]`` and ``[[example]]`` entries of ``textbook/ch11_terrestrial.toml``.
Formula adapters take the printed formula (sympy text) in ``inputs`` and return
``{"printed_equals_derived": bool}``; the derivations come from
:mod:`photolib.derivations.terrestrial` and plain sympy (never from the numeric code of
:mod:`photolib.terrestrial`). Example adapters recompute the book's numbers with
:mod:`photolib.terrestrial` or run small seeded simulations (conditions in the entries' notes).
"""

from __future__ import annotations

import numpy as np
import sympy as sp

from ..derivations import terrestrial as dt
from ..derivations.rotation import rotation_matrix_symbolic

_FUNCS = {"sin": sp.sin, "cos": sp.cos, "sqrt": sp.sqrt, "pi": sp.pi, "Matrix": sp.Matrix}


def _ok(flag) -> dict:
    return {"printed_equals_derived": bool(flag)}


def _parse(text, pool=()):
    """Parse printed sympy text; symbols take the assumptions of same-named symbols in ``pool``."""
    expr = sp.parse_expr(str(text), local_dict=dict(_FUNCS))
    names = {s.name: s for e in pool for s in sp.sympify(e).free_symbols}
    return expr.xreplace({s: names.get(s.name, sp.Symbol(s.name, real=True)) for s in expr.free_symbols})


def _zero(expr) -> bool:
    return sp.simplify(sp.expand(sp.sympify(expr))) == 0


def _same(printed, derived) -> bool:
    return _zero(_parse(printed, [derived]) - derived)


_A = sp.Matrix(3, 3, lambda i, j: sp.Symbol(f"a{i + 1}{j + 1}", real=True))


# --------------------------------------------------------------------------- §11.6
def condition_formula(inputs: dict) -> dict:
    """(11.6.1)–(11.6.5): the printed residual(s) against the sympy condition model ``inputs['model']``."""
    model = {"distance": dt.distance_condition_model, "base": dt.base_condition_model,
             "centre_distance": dt.centre_distance_model, "vertical": dt.vertical_line_model,
             "horizontal": dt.horizontal_plane_model}[inputs["model"]]()
    printed = inputs["F"] if isinstance(inputs["F"], list) else [inputs["F"]]
    if len(printed) != len(model.residuals):
        return _ok(False)
    return _ok(all(_same(p, r) for p, r in zip(printed, model.residuals)))


def plane_formula(inputs: dict) -> dict:
    """(11.6.6): a plane condition must constrain the points; the printed determinant is identically 0."""
    rows = sp.Matrix([[_parse(c) for c in row] for row in inputs["rows"]])
    return _ok(not _zero(rows.det()))


def distance_correction_formula(inputs: dict) -> dict:
    """(11.6.7): δD + l_D = v_D is the linearised (11.6.1), with l_D = D⁰ − D and δD its differential."""
    m = dt.distance_condition_model()
    Fi = m.residuals[0]
    D0 = sp.Symbol("D0", positive=True)
    dist = Fi + dt.D                                                   # D⁰ as a function of the coordinates
    deltas = [sp.Symbol(f"d{p.name}", real=True) for p in m.parameters]
    dD = sum(sp.diff(dist, p) * d for p, d in zip(m.parameters, deltas))
    l_printed = _parse(inputs["l_D"], [dt.D]).subs(sp.Symbol("D0", real=True), D0)
    dD_printed = _parse(inputs["delta_D"], list(m.parameters) + deltas).subs(sp.Symbol("D0", real=True), dist)
    free_term = dist - dt.D                                            # (11.6.1) at the approximation: D⁰ − D
    return _ok(_zero(l_printed.subs(D0, dist) - free_term) and _zero(dD_printed - dD))


def collinearity_formula(inputs: dict) -> dict:
    """(11.6.8): x − x₀ = −f·u/w, y − y₀ = −f·v/w with (u, v, w) = Aᵀ(X − X_S) (A camera → object)."""
    X, Y, Z, Xs, Ys, Zs, f, x0, y0 = sp.symbols("X Y Z X_s Y_s Z_s f x_0 y_0", real=True)
    uvw = _A.T * sp.Matrix([X - Xs, Y - Ys, Z - Zs])
    derived = [x0 - f * uvw[0] / uvw[2], y0 - f * uvw[1] / uvw[2]]
    return _ok(all(_same(p, d) for p, d in zip(inputs["xy"], derived)))


def polar_formula(inputs: dict) -> dict:
    """(11.6.9): (11.6.8) with X − X_S = D cos ν sin φ, Y − Y_S = D cos ν cos φ, Z − Z_S = D sin ν; D cancels."""
    f, x0, y0, D = sp.symbols("f x_0 y_0 D", real=True)
    phi, nu = sp.symbols("varphi nu", real=True)
    v = sp.Matrix([D * sp.cos(nu) * sp.sin(phi), D * sp.cos(nu) * sp.cos(phi), D * sp.sin(nu)])
    uvw = _A.T * v
    derived = [sp.cancel(x0 - f * uvw[0] / uvw[2]), sp.cancel(y0 - f * uvw[1] / uvw[2])]
    if any(D in d.free_symbols for d in derived):                     # D cancels
        return _ok(False)
    printed = [_parse(p, derived).subs(sp.Symbol("phi", real=True), phi) for p in inputs["xy"]]
    return _ok(all(_zero(p - d) for p, d in zip(printed, derived)))


def polar_linearised_formula(inputs: dict) -> dict:
    """(11.6.10): the correction equations are linear in δω, δα, δκ with the sympy Jacobian of (11.6.9).

    Checks that the printed unknowns are the model's parameters and that the model derived
    with D kept in the direction vector loses D on cancelling, so its Jacobian by ω, α, κ (the
    coefficients a₁…b₃) does not depend on D.
    """
    m = dt.polar_collinearity_model(with_distance=True)
    names = [p.name for p in m.parameters]
    return _ok(names == list(inputs["unknowns"]) and all(dt.D not in sp.cancel(r).free_symbols for r in m.residuals))


# --------------------------------------------------------------------------- §11.7
def _wak():
    return rotation_matrix_symbolic("wak")


def _trig_zero(expr) -> bool:
    """Zero as a polynomial in sin, cos of ω, α, κ modulo sin² + cos² = 1 (fast exact test)."""
    from ..derivations.symbols import alpha, kappa, omega
    e = sp.expand(expr)
    for a in (omega, alpha, kappa):
        s_, c_ = sp.Symbol(f"s_{a.name}"), sp.Symbol(f"c_{a.name}")
        e = sp.expand(e.xreplace({sp.sin(a): s_, sp.cos(a): c_}).subs(s_ ** 2, 1 - c_ ** 2))
    return e == 0


def linking_shift_formula(inputs: dict) -> dict:
    """(11.7.1)→(11.7.2): differencing R₁ = R_S3 + t·A₃·R₃ at M₁ and M₂ removes R_S3."""
    t = sp.Symbol("t", positive=True)
    R_S = sp.Matrix(sp.symbols("X_S3 Y_S3 Z_S3", real=True))
    R3a, R3b = sp.Matrix(sp.symbols("X_a Y_a Z_a", real=True)), sp.Matrix(sp.symbols("X_b Y_b Z_b", real=True))
    A = _wak()
    R1a, R1b = R_S + A * R3a * t, R_S + A * R3b * t
    lhs = R1b - R1a
    rhs = A * (R3b - R3a) * t if inputs.get("form") == "A R_3M t" else sp.zeros(3, 1)
    return _ok(all(_zero(e) for e in (lhs - rhs)))


def linking_linear_formula(inputs: dict) -> dict:
    """(11.7.3)–(11.7.8): with C = A·t the shifted relation is linear in c_ij, row r: X_rM = c_r · R_3M."""
    t = sp.Symbol("t", positive=True)
    A = _wak()
    C = sp.Matrix(3, 3, lambda i, j: sp.Symbol(f"c{i + 1}{j + 1}", real=True))
    R3 = sp.Matrix(sp.symbols("X Y Z", real=True))
    lhs = A * R3 * t
    rows = [_parse(r, list(C) + list(R3)) for r in inputs["rows"]]
    sub = {C[i, j]: A[i, j] * t for i in range(3) for j in range(3)}
    return _ok(len(rows) == 3 and all(_zero(rows[i].xreplace(sub) - lhs[i]) for i in range(3)))


def orthogonality_formula(inputs: dict) -> dict:
    """(11.7.9)/(11.7.10): the rows of C = tA are orthogonal: c₂·c₁ = c₃·c₁ = c₃·c₂ = 0 (sympy)."""
    t = sp.Symbol("t", positive=True)
    C = t * _wak()
    c = sp.Matrix(3, 3, lambda i, j: sp.Symbol(f"c{i + 1}{j + 1}", real=True))
    sub = {c[i, j]: C[i, j] for i in range(3) for j in range(3)}
    return _ok(all(_trig_zero(_parse(e, list(c)).xreplace(sub)) for e in inputs["equations"]))


def scale_formula(inputs: dict) -> dict:
    """(11.7.11)–(11.7.13): t = √(c₁₁² + c₁₂² + c₁₃²) and A = C/t for C = tA."""
    t = sp.Symbol("t", positive=True)
    A = _wak()
    C = t * A
    c = sp.Matrix(3, 3, lambda i, j: sp.Symbol(f"c{i + 1}{j + 1}", real=True))
    sub = {c[i, j]: C[i, j] for i in range(3) for j in range(3)}
    t_sq = _parse(inputs["t"], list(c)).xreplace(sub) ** 2            # t² from the printed row norm
    if not _trig_zero(t_sq - t ** 2):
        return _ok(False)
    return _ok(all(_zero(e) for e in (C / t - A)))


def chaining_formula(inputs: dict) -> dict:
    """(11.7.14)/(11.7.15): image 3 oriented in model 2, carried to the object frame, images the same points.

    Numeric check with :func:`photolib.single_image.project` (collinearity is invariant under the
    similarity transforms): the rotation A₀·A·A′₃ and the centre X_S1 + t·A₀·(X_S)_M reproduce
    the image coordinates computed in model 2. ``inputs['order']`` is the printed product order.
    """
    from ..camera import ExteriorOrientation, InteriorOrientation
    from ..rotation import rotation_angles, rotation_matrix
    from ..single_image import project
    rng = np.random.default_rng(int(inputs.get("seed", 0)))
    io = InteriorOrientation(50.0)
    A, t, shift = rotation_matrix(0.3, 0.2, -0.5, "wak"), 1.3, np.array([2.0, 1.0, -1.0])
    A0, t0, XS1 = rotation_matrix(1.5, 0.1, 0.2, "wak"), 25.0, np.array([100.0, 200.0, 50.0])
    A3p, S3 = rotation_matrix(1.4, 0.2, 0.1, "wak"), np.array([0.5, -0.3, 0.2])
    rays = np.column_stack([rng.uniform(-0.3, 0.3, (6, 2)), -np.ones(6)])
    P_m2 = S3 + (rays @ A3p.T) * rng.uniform(2, 4, (6, 1))
    xy = project(P_m2, ExteriorOrientation(*S3, *rotation_angles(A3p, "wak"), order="wak"), io)
    mats = {"A0": A0, "A": A, "A3p": A3p}
    A3 = mats[inputs["order"][0]] @ mats[inputs["order"][1]] @ mats[inputs["order"][2]]
    XS = XS1 + t0 * A0 @ (shift + t * A @ S3)                                    # (11.7.15)
    P_obj = XS1 + t0 * (shift + t * P_m2 @ A.T) @ A0.T
    xy_obj = project(P_obj, ExteriorOrientation(*XS, *rotation_angles(A3, "wak"), order="wak"), io)
    return _ok(np.allclose(xy_obj, xy, atol=1e-9))


# --------------------------------------------------------------------------- §11.8
def intersection_scale_formula(inputs: dict) -> dict:
    """(11.8.1): N solved from N₁X′₁ = B + N₂X′₂ (X and Y rows)."""
    r = dt.normal_case_relations()
    return _ok(_same(inputs["N"], r["N_general"]))


def normal_matrix_formula(inputs: dict) -> dict:
    """§11.8: A(ω = 90°, α = κ = 0), the rays (x, f, y) and N = B_X/p in the normal case."""
    r = dt.normal_case_relations()
    A = sp.Matrix(inputs["A"])
    s = r["symbols"]
    ok = A == r["A_normal"] and all(_same(p, d) for p, d in zip(inputs["ray"], r["ray_normal"]))
    return _ok(ok and _same(inputs["N"], r["N_normal"].subs(s["p"], sp.Symbol("p", real=True))))


def normal_point_formula(inputs: dict) -> dict:
    """(11.8.2)/(11.8.3): X = (B_X/p)x₁, Y = (B_X/p)f, Z = (B_X/p)y₁ ⇔ X = (Y/f)x₁, Z = (Y/f)y₁."""
    r = dt.normal_case_relations()
    XYZ = r["XYZ"]
    s = r["symbols"]
    pool = list(XYZ.free_symbols)
    printed = [_parse(e, pool) for e in inputs["XYZ"]]
    Ysym = sp.Symbol("Y", real=True)
    printed = [e.xreplace({Ysym: XYZ[1]}) for e in printed]
    return _ok(all(_zero(p - d) for p, d in zip(printed, XYZ)) and s["p"] in XYZ[1].free_symbols)


def accuracy_formula(inputs: dict) -> dict:
    """(11.8.4): first-order propagation of (11.8.3) in x₁, y₁, p; p → b, the ∂X/∂p, ∂Z/∂p terms dropped.

    Derived: m_X = |∂X/∂x₁|m_x, m_Y = |∂Y/∂p|m_p, m_Z = |∂Z/∂y₁|m_y at p = b; the printed forms
    are compared after substituting Y = B_X f/b.
    """
    r = dt.normal_case_relations()
    s = r["symbols"]
    b, mx, my, mp = sp.symbols("b m_x m_y m_p", positive=True)
    BX, f = sp.Symbol("B_X", positive=True), s["f"]
    sub = {s["p"]: b, s["B_X"]: BX}
    derived = [(r["dX_dx1"] * mx).xreplace(sub), (-r["dY_dp"] * mp).xreplace(sub), (r["dZ_dy1"] * my).xreplace(sub)]
    Yv = BX * f / b
    pool = [mx, my, mp, b, f]
    printed = [_parse(e, pool).xreplace({sp.Symbol("Y", real=True): Yv}) for e in inputs["m"]]
    return _ok(all(_zero(p - d) for p, d in zip(printed, derived)))


def base_formula(inputs: dict) -> dict:
    """(11.8.5): two frames of length l_x shifted by b overlap by l_x − b = P %·l_x ⇒ b = l_x(100 − P)/100."""
    lx, P, b = sp.symbols("l_x P b", positive=True)
    derived = sp.solve(sp.Eq(lx - b, P / 100 * lx), b)[0]
    return _ok(_same(inputs["b"], derived))


def coverage_formula(inputs: dict) -> dict:
    """(11.8.6)/(11.8.7): a pixel (1 px at f px) seen at depth Y covers Δ = Y/f; a frame l px covers l·Δ."""
    Y, f, lx, ly = sp.symbols("Y f l_x l_y", positive=True)
    delta = Y * 1 / f                                                  # similar triangles, 1 px at distance f
    ok = _same(inputs["delta"], delta)
    Dsym = sp.Symbol("Delta", positive=True)
    H = [_parse(e, [lx, ly, Dsym]).xreplace({Dsym: delta}) for e in inputs["H"]]
    return _ok(ok and _zero(H[0] - lx * delta) and _zero(H[1] - ly * delta))


# --------------------------------------------------------------------------- examples
_CAMS = ("phaseone", "sony")


def _design(inputs, delta_decimals=None):
    from ..terrestrial import stereo_design
    out = {}
    for cam in _CAMS:
        c = inputs[cam]
        for orient in ("horizontal", "vertical"):
            d = stereo_design(c["f_px"], c["frame_px"], inputs["Y"], inputs["overlap"], inputs["m_px"], orient,
                              delta_decimals=delta_decimals)
            key = f"{cam}_{orient}"
            out.update({f"b_{key}": d.b, f"mX_{key}": d.m_X, f"mY_{key}": d.m_Y, f"mZ_{key}": d.m_Z,
                        f"B_{key}": d.B, f"stereo_width_{key}": d.stereo_width})
            if orient == "horizontal":
                out.update({f"delta_{cam}": d.delta, f"HX_{cam}": d.H_X, f"HZ_{cam}": d.H_Z})
    return out


def worked_example(inputs: dict) -> dict:
    """§11.8 worked example: b, m_X, m_Y, m_Z, B and the stereo width for both cameras and frames (exact Δ)."""
    return _design(inputs)


def worked_example_as_printed(inputs: dict) -> dict:
    """The book's computation: Δ rounded to 0.0001 m before B = Δ·b, and the base printed as the stereo width."""
    out = _design(inputs, delta_decimals=4)
    for k in list(out):
        if k.startswith("stereo_width_"):
            out[k] = out["B_" + k[len("stereo_width_"):]]
    return out


def normal_case_omega(inputs: dict) -> dict:
    """§11.4: ω of a terrestrial image with a horizontal optical axis (normal case) is 90°."""
    from ..terrestrial import case_orientations
    e1, _ = case_orientations("normal", 1.0)
    return {"omega_deg": float(np.degrees(e1.omega))}


def strip_triple_overlap(inputs: dict) -> dict:
    """§11.5: with a forward overlap P, images i and i + 2 overlap by 2P − 100 %; positive ⇔ triple overlap."""
    P = float(inputs["overlap"])
    triple = 2 * P - 100.0
    return {"overlap": P, "triple_overlap_exists": "yes" if triple > 0 else "no", "triple_overlap_percent": triple}


def polar_min_points(inputs: dict) -> dict:
    """§11.6: fewest directions for ω, α, κ by (11.6.9): the rank of (11.6.10) reaches 3.

    The design matrix by central differences of :func:`photolib.terrestrial.polar_project`.
    """
    from ..camera import InteriorOrientation
    from ..terrestrial import polar_project
    io = InteriorOrientation(50.0)
    phi, nu = np.array([-0.3, 0.2, 0.1]), np.array([0.1, -0.05, 0.2])
    p0, h = np.array([np.pi / 2 + 0.02, 0.05, 0.01]), 1e-6
    for n in (1, 2, 3):
        cols = [((polar_project(phi[:n], nu[:n], *(p0 + h * e), io) - polar_project(phi[:n], nu[:n], *(p0 - h * e), io))
                 / (2 * h)).ravel() for e in np.eye(3)]
        if np.linalg.matrix_rank(np.column_stack(cols), tol=1e-6) == 3:
            return {"min_points": n}
    return {"min_points": None}


def linking_min_points(inputs: dict) -> dict:
    """§11.7: fewest common points (M₁ included) for which (11.7.6) determines a row of C."""
    rng = np.random.default_rng(0)
    P = rng.uniform(-5, 5, (6, 3))
    for n in range(2, 7):
        d = P[1:n] - P[0]
        if len(d) >= 3 and np.linalg.matrix_rank(d) == 3:
            return {"min_points": n}
    return {"min_points": None}


def linking_simulation(inputs: dict) -> dict:
    """§11.7: the book's linear linking vs Umeyama's SVD on a seeded simulation (noise in model 1)."""
    from ..rotation import rotation_matrix
    from ..terrestrial import link_models_linear, link_models_svd
    rng = np.random.default_rng(int(inputs["seed"]))
    A = rotation_matrix(*np.radians(inputs["angles_deg"]), "wak")
    t, shift = float(inputs["t"]), np.asarray(inputs["shift"], float)
    P3 = rng.uniform(-5, 5, (int(inputs["n"]), 3))
    P1 = shift + t * P3 @ A.T + rng.normal(0, float(inputs["sigma"]), P3.shape)
    lin, svd = link_models_linear(P1, P3), link_models_svd(P1, P3)
    good = abs(lin.t / t - 1) < 0.01 and np.abs(lin.A - A).max() < 0.01
    return {"approximate_values_usable": "yes" if good else "no",
            "linear_rotation_error": float(np.abs(lin.A - A).max()),
            "svd_rotation_error": float(np.abs(svd.A - A).max())}


def three_view_matching(inputs: dict) -> dict:
    """§11.9: targets identified on three images by epipolar lines (seeded scene, conditions in the notes)."""
    from ..camera import ExteriorOrientation, InteriorOrientation
    from ..projective import epipolar_lines, fundamental_from_orientation
    from ..single_image import project
    from ..terrestrial import match_three_views
    rng = np.random.default_rng(int(inputs["seed"]))
    io = InteriorOrientation(50.0)
    eos = [ExteriorOrientation(x, 0.0, z, np.pi / 2, a, 0.0, order="wak")
           for x, z, a in ((0.0, 0.0, -0.15), (3.0, 0.0, 0.15), (1.5, 2.5, 0.0))]
    n = int(inputs["targets"])
    P = np.column_stack([rng.uniform(-1, 4, n), rng.uniform(9, 12, n), rng.uniform(-1.5, 3, n)])
    xy = [project(P, e, io) + rng.normal(0, inputs["sigma_mm"], (n, 2)) for e in eos]
    perm2, perm3 = rng.permutation(n), rng.permutation(n)
    F = lambda a, b: fundamental_from_orientation(io, eos[a], io, eos[b])   # noqa: E731
    thr = float(inputs["threshold_mm"])
    lines = epipolar_lines(F(0, 1), xy[0], image=2)
    cand = (np.abs(np.column_stack([xy[1][perm2], np.ones(n)]) @ lines.T) <= thr).sum(axis=0)
    m = match_three_views(xy[0], xy[1][perm2], xy[2][perm3], F(0, 1), F(0, 2), F(1, 2), thr)
    inv2, inv3 = np.argsort(perm2), np.argsort(perm3)
    correct = np.all(inv2[m[:, 0]] == m[:, 1]) and np.all(inv3[m[:, 0]] == m[:, 2])
    return {"two_view_ambiguous": "yes" if np.mean(cand > 1) > 0.2 else "no",
            "three_views_identify": "yes" if correct and len(m) >= 0.95 * n else "no",
            "matched": len(m), "ambiguous_share": float(np.mean(cand > 1))}


def case_corrections(inputs: dict) -> dict:
    """§11.8: tilted (Y/cos ω) and deviated (b·cos α) corrections, seeded Monte Carlo along the optical axis.

    A point on the axis of camera 1 at distance D; noise σ on x₁, y₁, x₂ (so m_p = σ√2); the
    spread along the axis of the intersected point (11.8.1) against (11.8.4) with the correction,
    Y = the horizontal distance D·cos ω (tilted) or the distance along the axis D (deviated).
    """
    from ..camera import InteriorOrientation
    from ..single_image import project
    from ..terrestrial import base_intersection, case_orientations, normal_case_accuracy
    rng = np.random.default_rng(int(inputs["seed"]))
    f, B, D, s, n = 50.0, float(inputs["B"]), float(inputs["D"]), float(inputs["sigma_mm"]), int(inputs["n"])
    io = InteriorOrientation(f)
    out = {}
    for case, angle in (("tilted", inputs["tilt"]), ("deviated", inputs["deviation"])):
        kw = {"tilt": angle} if case == "tilted" else {"deviation": angle}
        e1, e2 = case_orientations(case, B, **kw)
        axis = e1.matrix @ [0, 0, -1.0]
        P = D * axis
        xy1, xy2 = project([P], e1, io)[0], project([P], e2, io)[0]
        noise = rng.normal(0, s, (n, 3))
        a = np.tile(xy1, (n, 1)) + noise[:, :2]
        b2 = np.column_stack([xy2[0] + noise[:, 2], np.full(n, xy2[1])])
        Q = base_intersection(a, b2, e1, e2, io) if case == "tilted" else _ray_points(a, b2, e1, e2, io)
        spread = float(np.std((Q - P) @ axis, ddof=1))
        b_img = f * B / D
        if case == "tilted":
            pred = normal_case_accuracy(D * np.cos(angle), f, b_img, s, s, s * np.sqrt(2), tilt=angle)[1]
        else:
            pred = normal_case_accuracy(D, f, b_img, s, s, s * np.sqrt(2), deviation=angle)[1]
        out[f"{case}_ratio"] = spread / pred
        out[f"{case}_correction_holds"] = "yes" if abs(spread / pred - 1) < float(inputs["tolerance"]) else "no"
    return out


def _ray_points(a, b, e1, e2, io):
    from ..image_pair import forward_intersection
    return forward_intersection(a, b, e1, e2, io)
