"""Chapter 9, §9.1–9.4, §9.7, §9.8, §9.10 (laser-scanning geometry): formula checks and tables.

Adapters for the ``[[formula]]`` and ``[[example]]`` entries of ``textbook/ch09_lidar.toml``.
Formula adapters return ``{"printed_equals_derived": bool}``: the printed formula (sympy text in
the entry's ``inputs``) is compared with an independent derivation (geometry of the ray, the
chain of rigid transforms, sympy ``solve``), and where a library function implements it, the
library is checked on a numeric case too. Example adapters recompute Table 9.1 (swath and
footprint) and run small seeded simulations through :mod:`photolib.lidar`. Each runs in well
under 0.3 s.
"""

from __future__ import annotations

import numpy as np
import sympy as sp

from .. import lidar
from ..derivations import lidar as dlidar

_S = {name: sp.Symbol(name, real=True) for name in
      ("D", "phi", "nu", "v", "t", "K", "lam", "dphi", "B", "f", "p", "alpha", "Z", "H", "theta", "g",
       "Delta", "d", "X_S", "Y_S", "Z_S", "Xp", "Yp", "Zp", "N", "A", "Bp", "C", "Dp", "x", "y", "x_0", "y_0",
       "d_x", "d_y", "X", "Y", "c", "X_S0", "Y_S0", "Z_S0", "m_p")}


def _ok(flag) -> dict:
    return {"printed_equals_derived": bool(flag)}


def _parse(text):
    return sp.parse_expr(text, local_dict=dict(_S))


def _vector(texts):
    return sp.Matrix([_parse(t) for t in texts])


def _zero(M) -> bool:
    return all(sp.simplify(e) == 0 for e in M)


def _mat(name):
    return sp.Matrix(3, 3, sp.symbols(f"{name}_1:10", real=True))


def _vec(name):
    return sp.Matrix(sp.symbols(f"{name}_1:4", real=True))


# --------------------------------------------------------------------------- §9.1–9.2
def als_vector_formula(inputs: dict) -> dict:
    """(9.1.1): the mirror ray at φ from nadir (−z) toward +y, of length D = vt/2."""
    D, phi = _S["D"], _S["phi"]
    printed = _vector(inputs["SM"])
    derived = D * sp.Matrix([0, -sp.sin(-phi), -sp.cos(phi)])      # nadir (0,0,−1) rotated about x by φ
    rot_x = sp.Matrix([[1, 0, 0], [0, sp.cos(phi), -sp.sin(phi)], [0, sp.sin(phi), sp.cos(phi)]])
    derived2 = rot_x * sp.Matrix([0, 0, -D])
    lib = lidar.als_scanner_vector(7.0, 0.3)[0]
    lib_ok = np.allclose(lib, [float(e) for e in printed.subs({D: 7.0, phi: 0.3})])
    return _ok(_zero(printed - derived) and _zero(derived - derived2) and lib_ok)


def als_georef_formula(inputs: dict) -> dict:
    """(9.1.2): R = R_S + A·SM, the rigid transform scanner → object; checked with photolib.lidar."""
    A, S = _mat("a"), _vec("S")
    D, phi = _S["D"], _S["phi"]
    v = sp.Matrix([0, sp.sin(phi), -sp.cos(phi)]) * D
    local = {"A": A, "R_S": S, "SM": v}
    printed = sp.parse_expr(inputs["R"], local_dict=local)
    from ..rotation import rotation_matrix
    An = rotation_matrix(0.02, -0.03, 0.7, order="wak")
    Sn = np.array([100.0, 200.0, 1500.0])
    lib = lidar.als_georeference(1600.0, -0.2, Sn, An)[0]
    num = printed.subs({**dict(zip(A, An.ravel())), **dict(zip(S, Sn)), D: 1600.0, phi: -0.2})
    return _ok(_zero(printed - (S + A * v)) and np.allclose(lib, [float(e) for e in num]))


def swath_footprint_formula(inputs: dict) -> dict:
    """§9.2: the edge rays at ±Θ/2 (±g/2) from nadir meet flat ground H below at ±H·tan(Θ/2)."""
    H, th, g = _S["H"], _S["theta"], _S["g"]
    edge = lambda half: sp.Matrix([0, sp.sin(half), -sp.cos(half)]) * (H / sp.cos(half))  # noqa: E731
    derived_sw = 2 * edge(th / 2)[1]
    derived_d = 2 * edge(g / 2)[1]
    ok = sp.simplify(_parse(inputs["SW"]) - derived_sw) == 0 and sp.simplify(_parse(inputs["D"]) - derived_d) == 0
    ok = ok and np.isclose(lidar.swath_width(1000.0, 1.0), 2000 * np.tan(0.5))
    return _ok(ok)


def table_9_1_als(inputs: dict) -> dict:
    """Table 9.1 (ALS): SW = 2H·tan(Θ/2) at H = the maximal range, D = 2·1000 m·tan(g/2)."""
    out = {}
    for key, row in inputs["units"].items():
        H, fov, g = row["range_max"], row["fov_deg"], row.get("g_mrad")
        if fov < 180:
            out[f"SW_{key}"] = lidar.swath_width(H, np.radians(fov))
        if g:
            out[f"D1000_{key}"] = 100 * lidar.footprint_diameter(1000.0, g * 1e-3)
    return out


# --------------------------------------------------------------------------- §9.4
def polar_formula(inputs: dict) -> dict:
    """(9.4.1): a vector of length D at azimuth φ (from +Y′ toward +X′) and elevation ν."""
    D, phi, nu = _S["D"], _S["phi"], _S["nu"]
    printed = _vector(inputs["XYZ"])
    horizontal = sp.Matrix([sp.sin(phi), sp.cos(phi), 0]) * sp.cos(nu)
    derived = D * (horizontal + sp.Matrix([0, 0, sp.sin(nu)]))
    unit = sp.simplify((derived.T * derived)[0] - D ** 2) == 0
    P = lidar.polar_to_xyz(5.0, 0.4, -0.2)
    back = lidar.xyz_to_polar(P)
    return _ok(_zero(printed - derived) and unit and np.allclose([b[0] for b in back], [5.0, 0.4, -0.2]))


def pulse_formula(inputs: dict) -> dict:
    """(9.4.2): the pulse covers 2D in the time t at the speed v."""
    D = sp.solve(sp.Eq(2 * _S["D"], _S["v"] * _S["t"]), _S["D"])[0]
    return _ok(sp.simplify(_parse(inputs["D"]) - D) == 0 and np.isclose(lidar.pulse_range(2e-6, 3e8), 300.0))


def phase_formula(inputs: dict) -> dict:
    """(9.4.3): the phase accumulates over the round trip 2D: 2D = (K + Δφ/2π)·λ."""
    D = sp.solve(sp.Eq(2 * _S["D"], (_S["K"] + _S["dphi"] / (2 * sp.pi)) * _S["lam"]), _S["D"])[0]
    printed = _parse(inputs["D"])
    lib = lidar.phase_range(3, np.pi, 10.0)
    return _ok(sp.simplify(printed - D) == 0 and np.isclose(lib, float(D.subs({_S["K"]: 3, _S["dphi"]: sp.pi,
                                                                              _S["lam"]: 10}))))


def triangulation_formula(inputs: dict) -> dict:
    """(9.4.4): Z solved from the geometry of Fig. 9.15 (derivations.lidar.triangulation_depth_model)."""
    m = dlidar.triangulation_depth_model()
    p, f, B, a = m["symbols"]
    printed = sp.parse_expr(inputs["Z"], local_dict={"B": B, "f": f, "p": p, "alpha": a})
    return _ok(sp.simplify(printed - m["Z"]) == 0
               and np.isclose(lidar.triangulation_depth(1.0, 20.0, 100.0, 0.1), float(m["Z"].subs({p: 1, f: 20, B: 100,
                                                                                                   a: 0.1}))))


def triangulation_sigma_formula(inputs: dict) -> dict:
    """(9.4.5): m_Z = |∂Z/∂p|·m_p of (9.4.4), which is Z²/(fB)·m_p exactly."""
    m = dlidar.triangulation_depth_model()
    p, f, B, a = m["symbols"]
    Zs, mp = sp.Symbol("Z", positive=True), sp.Symbol("m_p", positive=True)
    printed = sp.parse_expr(inputs["m_Z"], local_dict={"Z": Zs, "f": f, "B": B, "m_p": mp})
    derived = sp.Abs(m["dZ_dp"]) * mp
    return _ok(sp.simplify(printed.subs(Zs, m["Z"]) - derived) == 0)


def image_ray_formula(inputs: dict) -> dict:
    """(9.4.6): the image ray A·(x − x₀ + d_x, y − y₀ + d_y, −f) of (1.2.3) — d_x, d_y are listed but missing."""
    x, y, x0, y0, f, dx, dy = (_S[k] for k in ("x", "y", "x_0", "y_0", "f", "d_x", "d_y"))
    printed = _vector(inputs["r"])
    derived = sp.Matrix([x - x0 + dx, y - y0 + dy, -f])
    return _ok(_zero(printed - derived))


def plane_formula(inputs: dict) -> dict:
    """(9.4.7): A X + B Y + C Z + D = 0 ⇔ n·X − p = 0 with the unit normal of (9.11.1), times a scale."""
    m = dlidar.plane_model()
    a, b, p = m["parameters"]
    X, Y, Z = m["data"]
    printed = sp.parse_expr(inputs["plane"], local_dict={"A": _S["A"], "B": _S["Bp"], "C": _S["C"], "D": _S["Dp"],
                                                         "X": X, "Y": Y, "Z": Z})
    sub = {_S["A"]: sp.cos(a) * sp.cos(b), _S["Bp"]: sp.sin(a) * sp.cos(b), _S["C"]: sp.sin(b), _S["Dp"]: -p}
    fit = lidar.fit_plane([[0, 0, 1.0], [1, 0, 1], [0, 1, 1], [1, 1, 1]])
    return _ok(sp.simplify(printed.subs(sub) - m["residual"]) == 0 and np.allclose(abs(fit.plane[2]), 1))


def ray_plane_substitution(inputs: dict) -> dict:
    """(9.4.8): (9.4.6) substituted into (9.4.7)."""
    m = dlidar.ray_plane_model()
    A, B, C, D, XS, YS, ZS, Xp, Yp, Zp = m["symbols"]
    N = sp.Symbol("N", real=True)
    local = {"A": A, "B": B, "C": C, "D": D, "X_s": XS, "Y_s": YS, "Z_s": ZS, "Xp": Xp, "Yp": Yp, "Zp": Zp, "N": N}
    printed = sp.parse_expr(inputs["equation"], local_dict=local)
    return _ok(sp.expand(printed - m["equation"]) == 0)


def ray_plane_scale(inputs: dict) -> dict:
    """(9.4.9): N solved from (9.4.8) by sympy carries a minus sign the printed formula lacks."""
    m = dlidar.ray_plane_model()
    A, B, C, D, XS, YS, ZS, Xp, Yp, Zp = m["symbols"]
    local = {"A": A, "B": B, "C": C, "D": D, "X_s": XS, "Y_s": YS, "Z_s": ZS, "Xp": Xp, "Yp": Yp, "Zp": Zp}
    printed = sp.parse_expr(inputs["N"], local_dict=local)
    return _ok(sp.simplify(printed - m["N"]) == 0)


def collinearity_formula(inputs: dict) -> dict:
    """(9.4.10) and (9.7.5): x = x₀ − f·u_x/u_z with u = Aᵀ(X − X_S) — the third row of (9.7.4) eliminated."""
    A = _mat("a")
    X, Y, Z, XS, YS, ZS, f = (_S[k] for k in ("X", "Y", "Z", "X_S", "Y_S", "Z_S", "f"))
    x0, y0 = _S["x_0"], _S["y_0"]
    u = A.T * sp.Matrix([X - XS, Y - YS, Z - ZS])
    a = {f"a{i}{j}": A[i - 1, j - 1] for i in range(1, 4) for j in range(1, 4)}
    local = {**a, **{k: _S[k] for k in ("X", "Y", "Z", "X_S", "Y_S", "Z_S", "f", "x_0", "y_0")}}
    px, py = (sp.parse_expr(inputs[k], local_dict=local) for k in ("x", "y"))
    with_pp = inputs.get("principal_point", True)
    dx, dy = (x0, y0) if with_pp else (0, 0)
    return _ok(sp.simplify(px - (dx - f * u[0] / u[2])) == 0 and sp.simplify(py - (dy - f * u[1] / u[2])) == 0)


# --------------------------------------------------------------------------- §9.7
def camera_vector_formula(inputs: dict) -> dict:
    """(9.7.1)–(9.7.4): R = R_M − R_S = N·A·r ⇒ r = Aᵀ(R_M − R_S)/N for an orthogonal A.

    A is an exact rational rotation (from the quaternion (1, 2, 3, 4)/√30, Cayley form) so that
    the identity is checked by expansion, not by trigonometric simplification.
    """
    a, b, c, d = 1, 2, 3, 4
    n = sp.Integer(a * a + b * b + c * c + d * d)
    A = sp.Matrix([[a*a + b*b - c*c - d*d, 2*(b*c - a*d), 2*(b*d + a*c)],
                   [2*(b*c + a*d), a*a - b*b + c*c - d*d, 2*(c*d - a*b)],
                   [2*(b*d - a*c), 2*(c*d + a*b), a*a - b*b - c*c + d*d]]) / n
    assert A.T * A == sp.eye(3)
    RM, RS, N = _vec("M"), _vec("S"), sp.Symbol("N", positive=True)
    r = sp.parse_expr(inputs["r"], local_dict={"A": A, "R_M": RM, "R_S": RS, "N": N})
    return _ok(all(e == 0 for e in sp.expand(N * A * r - (RM - RS))))


def camera_centre_formula(inputs: dict) -> dict:
    """(9.7.7): c_i must be c times the unit viewing direction of (9.4.1); the printed sin φ_k is not."""
    m = dlidar.scanner_camera_rotation()
    phi, nu = m["symbols"]
    printed = sp.parse_expr(inputs["direction"], local_dict={"phi": phi, "nu": nu})
    printed = sp.Matrix(printed)
    S, A = lidar.scanner_camera_pose(0.3, 0.2, [0, 0, 0], 1.0)
    lib_ok = np.allclose(S, [float(e) for e in m["direction"].subs({phi: 0.3, nu: 0.2})])
    return _ok(_zero(printed - m["direction"]) and lib_ok)


def camera_rotation_statement(inputs: dict) -> dict:
    """§9.7 (line 5567): a_ij from (α, ω, κ) = (φ_k, ν_k, 0) should look along (9.4.1)'s direction."""
    m = dlidar.scanner_camera_rotation()
    return _ok(_zero(m["literal"] - m["direction"]))


# --------------------------------------------------------------------------- §9.8
def mobile_chain_formula(inputs: dict) -> dict:
    """(9.8.1): scanner → IMU (A_IMU/S, r_IMU/S) → object (A_IMU, R_IMU); R_IMU from the antenna."""
    A, Ab = _mat("a"), _mat("b")
    R, r_s, r_g, G = _vec("R"), _vec("s"), _vec("g"), _vec("G")
    R_imu = G - A * r_g
    derived = A * (Ab * R + r_s) + R_imu
    local = {"A": A, "Ab": Ab, "R": R, "r_s": r_s, "r_g": r_g, "R_GNSS": G}
    local["R_IMU"] = sp.parse_expr(inputs["R_IMU"], local_dict=local)
    printed = sp.parse_expr(inputs["R_M"], local_dict=local)
    return _ok(_zero(sp.expand(printed - derived)))


def mobile_lever_formula(inputs: dict) -> dict:
    """(9.8.2) and its coordinate form (9.8.3): R_GNSS + A(r_GNSS/S + A_b R), r_GNSS/S = r_IMU/S − r_GNSS/IMU."""
    A, Ab = _mat("a"), _mat("b")
    R, r_s, r_g, G = _vec("R"), _vec("s"), _vec("g"), _vec("G")
    derived = G - A * r_g + A * r_s + A * Ab * R
    local = {"A": A, "Ab": Ab, "R": R, "r_s": r_s, "r_g": r_g, "R_GNSS": G, "r_gs": r_s - r_g}
    printed = sp.parse_expr(inputs["R_M"], local_dict=local)
    from ..rotation import rotation_matrix
    An, Abn = rotation_matrix(0.1, 0.2, 0.3, order="wak"), rotation_matrix(0.01, -0.02, 0.03, order="wak")
    lib = lidar.mobile_georeference([1.0, 2, 3], [10.0, 20, 30], An, [0.5, -0.2, 1.0], Abn)[0]
    ref = np.array([10.0, 20, 30]) + An @ (np.array([0.5, -0.2, 1.0]) + Abn @ [1.0, 2, 3])
    return _ok(_zero(sp.expand(printed - derived)) and np.allclose(lib, ref))


def mobile_calibration(inputs: dict) -> dict:
    """§9.8: the lever arm and boresight recovered from a simulated static test field."""
    from ..rotation import rotation_matrix
    rng = np.random.default_rng(inputs["seed"])
    lever, angles = np.array(inputs["lever"]), np.radians(inputs["boresight_deg"])
    sigma = inputs["sigma"]
    bore = rotation_matrix(*angles, order="wak")
    targets = rng.uniform([-15, -15, 0], [15, 15, 6], (inputs["targets"], 3))
    R, G, A = [], [], []
    for k in range(inputs["poses"]):
        A_imu = rotation_matrix(*rng.normal(0, 0.02, 2), 2 * np.pi * k / inputs["poses"], order="wak")
        gnss = rng.uniform(-3, 3, 3) + [0, 0, 2.5]
        local = (A_imu.T @ (targets - gnss).T).T - lever
        R.append((bore.T @ local.T).T + rng.normal(0, sigma, local.shape))
        G.append(np.tile(gnss, (len(targets), 1)))
        A.append(np.tile(A_imu, (len(targets), 1, 1)))
    cal = lidar.calibrate_mobile_system(np.vstack(R), np.vstack(G), np.concatenate(A),
                                        np.tile(targets, (inputs["poses"], 1)), sigma_target=sigma)
    err = np.abs(np.concatenate([cal.lever - lever, cal.angles - angles])) / cal.std
    return {"calibrated": "yes" if np.all(err < 3) else "no",
            "lever_error_mm": float(1000 * np.abs(cal.lever - lever).max())}


# --------------------------------------------------------------------------- §9.4 laser-line scanner
def laser_line_pipeline(inputs: dict) -> dict:
    """§9.4 stages 1–5 on a simulated scene (photolib.lidar.simulate_laser_line_scanner)."""
    s = lidar.simulate_laser_line_scanner(seed=inputs["seed"], sigma_xy=inputs["sigma_xy"], n_marks=8, n_trace=15)
    r = lidar.laser_line_scan(s.marks_xyz, s.marks_xy, s.marks_plate, s.trace_xy, s.trace_label, s.io,
                              eo0=s.eo)
    err = np.abs(r.points - s.trace_xyz[s.trace_label == 0]).max()
    printed_sign = []
    for k in (1, 2):
        plane = r.plates[k - 1].plane
        rays = lidar.image_rays(s.trace_xy[s.trace_label == k], r.eo, s.io)
        N_printed = (plane[:3] @ r.eo.center + plane[3]) / (rays @ plane[:3])
        printed_sign.append(np.all(N_printed < 0))
    return {"profile": "yes" if err < 0.003 else "no", "profile_error_mm": float(1000 * err),
            "printed_sign_behind": "yes" if all(printed_sign) else "no"}


# --------------------------------------------------------------------------- §9.10
def max_range_formula(inputs: dict) -> dict:
    """(9.10.1): an angular error dφ moves a point at range D sideways by D·tan dφ; set that to Δ."""
    D = sp.solve(sp.Eq(_S["D"] * sp.tan(_S["dphi"]), _S["Delta"]), _S["D"])[0]
    printed = sp.parse_expr(inputs["D"], local_dict={"Delta": _S["Delta"], "dphi": _S["dphi"]})
    return _ok(sp.simplify(printed - D) == 0 and np.isclose(lidar.tls_max_range(0.005, 1e-4), 0.005 / np.tan(1e-4)))


def angular_step_formula(inputs: dict) -> dict:
    """(9.10.2): a step Δφ separates points at range D by D·tan Δφ; set that to d ⇒ Δφ = arctan(d/D)."""
    step = sp.Symbol("step", positive=True)
    derived = sp.solve(sp.Eq(_S["D"] * sp.tan(step), _S["d"]), step)
    printed = sp.solve(sp.parse_expr(inputs["equation"], local_dict={"step": step, "d": _S["d"], "D": _S["D"],
                                                                     "atan": sp.atan}), step)
    return _ok(printed == derived)

