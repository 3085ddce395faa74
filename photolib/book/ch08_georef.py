"""Chapter 8, §8.14–8.17 (direct georeferencing, scanner aerial triangulation, scanner
orthophotos, Resurs-P quasi-image and object-space SGM): formula checks and inline statements.

Adapters for the ``[[formula]]`` and ``[[example]]`` entries of ``textbook/ch08_georef.toml``.
Formula adapters return ``{"printed_equals_derived": bool}``: the printed formulas (as sympy
text in the entries' ``inputs``) are compared with independent sympy derivations (a chain of
rigid transforms for (8.14.1), the collinearity condition, exhaustive enumeration of labellings
for (8.17.2)–(8.17.3)). Statements are checked by small seeded simulations with
:mod:`photolib.georef` (conditions in the entries' notes). Every check runs in well under 0.3 s.
"""

from __future__ import annotations

import itertools
from math import comb

import numpy as np
import sympy as sp


def _ok(flag) -> dict:
    return {"printed_equals_derived": bool(flag)}


def _vec(name):
    return sp.Matrix(sp.symbols(f"{name}_1:4", real=True))


def _mat(name):
    return sp.Matrix(3, 3, sp.symbols(f"{name}_1:10", real=True))


def _zero(M) -> bool:
    return all(sp.expand(e) == 0 for e in M)


# --------------------------------------------------------------------------- §8.14
def direct_georef_formula(inputs: dict) -> dict:
    """(8.14.1) against the composition of rigid transforms sensor → IMU → object.

    Derivation: a vector R in the sensor frame is R_IMU-frame = A_IMU/S·R + r_IMU/S (sensor origin
    in the IMU frame); in the object frame R_M = A_IMU·(…) + R_IMU; the antenna, at r_GNSS/IMU in
    the IMU frame, is at R_GNSS = A_IMU·r_GNSS/IMU + R_IMU, which fixes R_IMU. Generic 3×3 symbols
    (no orthogonality needed). The printed text (``inputs``) is parsed with the matrices
    ``A`` (A_IMU), ``Ab`` (A_IMU/S) and vectors ``R``, ``r_s`` (r_IMU/S), ``r_g``, ``R_GNSS``.
    """
    A, Ab = _mat("a"), _mat("b")
    R, r_s, r_g, G = _vec("R"), _vec("s"), _vec("g"), _vec("G")
    R_imu = G - A * r_g                                     # from the antenna equation
    assert _zero(A * r_g + R_imu - G)
    derived = A * (Ab * R + r_s) + R_imu
    local = {"A": A, "Ab": Ab, "R": R, "r_s": r_s, "r_g": r_g, "R_GNSS": G}
    local["R_IMU"] = sp.parse_expr(inputs["R_IMU"], local_dict=local)
    printed = sp.parse_expr(inputs["R_M"], local_dict=local)
    ok = _zero(printed - derived)
    # the library implements the same thing
    from ..georef import direct_georeference
    from ..rotation import rotation_matrix
    rng = np.random.default_rng(1)
    An, Abn = rotation_matrix(0.03, -0.02, 1.1, "wak"), rotation_matrix(1e-3, -2e-3, 5e-3, "wak")
    Rn, sn, gn, Gn = rng.normal(0, 10, (4, 3))
    lib = direct_georeference(Rn, Gn, An, gn, sn, Abn)[0]
    ok &= np.allclose(lib, An @ (Abn @ Rn + sn) + Gn - An @ gn, atol=1e-9)
    return _ok(ok)


def frame_vector_formula(inputs: dict) -> dict:
    """R = N·r, r = (x − x₀, y − y₀, −f): every point S + N·A·r satisfies the collinearity
    equations x = x₀ − f·u_x/u_z, y = y₀ − f·u_y/u_z, u = Aᵀ(R_M − S), for any N ≠ 0 (A an exact
    rational rotation: the identity uses only AᵀA = E)."""
    x, y, x0, y0, f, N = sp.symbols("x y x_0 y_0 f N", real=True)
    local = {"x": x, "y": y, "x_0": x0, "y_0": y0, "f": f}
    r = sp.Matrix([sp.parse_expr(c, local_dict=local) for c in inputs["r"]])
    # an exact rational rotation by the Cayley transform A = (E − K)⁻¹(E + K), K skew-symmetric
    p, q, s = sp.Rational(1, 3), sp.Rational(-2, 7), sp.Rational(1, 5)
    K = sp.Matrix([[0, -s, q], [s, 0, -p], [-q, p, 0]])
    A = (sp.eye(3) - K).inv() * (sp.eye(3) + K)
    assert A.T * A == sp.eye(3) and A.det() == 1
    u = A.T * (N * A * r)
    return _ok(sp.simplify(x0 - f * u[0] / u[2] - x) == 0 and sp.simplify(y0 - f * u[1] / u[2] - y) == 0)


def scanner_vector_formula(inputs: dict) -> dict:
    """R = N·r with (x, y, z) the unit vector (8.2.2) of the scanner pixel: unit length and
    parallel to the ray (x_i − x₀, y_c − y₀, −f) (cross product zero)."""
    xi, yc, x0, y0, f = sp.symbols("x_i y_c x_0 y_0 f", real=True)
    ray = sp.Matrix([xi - x0, yc - y0, -f])
    local = {"x_i": xi, "y_c": yc, "x_0": x0, "y_0": y0, "f": f, "sqrt": sp.sqrt}
    r = sp.Matrix([sp.parse_expr(c, local_dict=local) for c in inputs["r"]])
    return _ok(sp.cancel(r.dot(r) - 1) == 0 and all(sp.cancel(e) == 0 for e in r.cross(ray)))


def range_vector_formula(inputs: dict) -> dict:
    """R = D·(0, sin φ, −cos φ): length D, in the sensor's y–z plane, at the angle φ from −z
    towards +y; and A·R gives the radar equations (8.11.5) term by term."""
    D, phi = sp.symbols("D phi", positive=True)
    local = {"D": D, "phi": phi, "sin": sp.sin, "cos": sp.cos}
    R = sp.Matrix([sp.parse_expr(c, local_dict=local) for c in inputs["R"]])
    ok = sp.simplify(R.dot(R) - D ** 2) == 0 and R[0] == 0
    ok &= sp.simplify(R[1] - D * sp.sin(phi)) == 0 and sp.simplify(-R[2] - D * sp.cos(phi)) == 0
    A = _mat("a")
    a = lambda i, j: A[i - 1, j - 1]                      # noqa: E731
    radar = sp.Matrix([(a(k, 2) * sp.sin(phi) - a(k, 3) * sp.cos(phi)) * D for k in (1, 2, 3)])
    return _ok(ok and _zero(A * R - radar))


def range_vector_check(inputs: dict) -> dict:
    return range_vector_formula(inputs)


# --------------------------------------------------------------------------- §8.15
def collinearity_formula(inputs: dict) -> dict:
    """(8.15.1) against x = −f·u_x/u_z, y = −f·u_y/u_z with u = Aᵀ(X − X_S, Y − Y_S, Z − Z_S): the
    printed a_ij (a₁₁, a₂₁, a₃₁ in the numerator of x) are the columns of A."""
    A = _mat("a")
    X, Y, Z, Xs, Ys, Zs, f = sp.symbols("X Y Z X_s Y_s Z_s f", real=True)
    u = A.T * sp.Matrix([X - Xs, Y - Ys, Z - Zs])
    local = {"X": X, "Y": Y, "Z": Z, "X_s": Xs, "Y_s": Ys, "Z_s": Zs, "f": f}
    local.update({f"a{i}{j}": A[i - 1, j - 1] for i in range(1, 4) for j in range(1, 4)})
    x = sp.parse_expr(inputs["x"], local_dict=local)
    y = sp.parse_expr(inputs["y"], local_dict=local)
    return _ok(sp.simplify(x + f * u[0] / u[2]) == 0 and sp.simplify(y + f * u[1] / u[2]) == 0)


def interpolation_formula(inputs: dict) -> dict:
    """(8.15.2): E = c·E_k + (1 − c)·E_{k+1} − δE with δE = c·M_k + (1 − c)·M_{k+1} − M(t) equals
    M(t) + [c·(E_k − M_k) + (1 − c)·(E_{k+1} − M_{k+1})]: the measurement plus the linear
    interpolation of the corrections at the fixed centres; it gives E_k at t = t_k (c = 1,
    M(t_k) = M_k) and reproduces M(t) + b when E_k − M_k = b for all k."""
    E_k, E_k1, M_k, M_k1, M_t, t, t_k, t_k1, b = sp.symbols("E_k E_k1 M_k M_k1 M_t t t_k t_k1 b", real=True)
    local = {"E_k": E_k, "E_k1": E_k1, "M_k": M_k, "M_k1": M_k1, "M_t": M_t, "t": t, "t_k": t_k, "t_k1": t_k1}
    c = sp.parse_expr(inputs["c"], local_dict=local)
    local["c"] = c
    delta = sp.parse_expr(inputs["delta"], local_dict=local)
    local["delta"] = delta
    E = sp.parse_expr(inputs["E"], local_dict=local)
    derived = M_t + c * (E_k - M_k) + (1 - c) * (E_k1 - M_k1)
    ok = sp.cancel(E - derived) == 0
    ok &= sp.cancel(E.subs({t: t_k}).subs({M_t: M_k}) - E_k) == 0
    ok &= sp.cancel(E.subs({E_k: M_k + b, E_k1: M_k1 + b}) - (M_t + b)) == 0
    return _ok(ok)


def three_line_coverage(inputs: dict) -> dict:
    """Views of a ground point: one strip of a three-line camera, and the overlap of two strips.

    Two parallel strips of :func:`photolib.georef.three_line_block`'s camera (lines at
    x = +20, 0, −20 mm, f = 62.5 mm, H = 1000 m, 801 pixels of 0.05 mm: swath 641 m) 400 m apart;
    ground points along the middle of strip 1 and in the overlap band of the two strips are
    projected into each line of each strip and counted where they fall on the CCD.
    """
    from ..georef import TabulatedLineScanner
    n = 301
    t = np.arange(n) / 10.0
    strips = []
    for y in (0.0, float(inputs.get("strip_spacing", 400.0))):
        eo = np.column_stack([50 * t, np.full(n, y), np.full(n, 1000.0), np.zeros((n, 3))])
        strips.append([TabulatedLineScanner(eo, 62.5, 0.05, 801, x) for x in (20.0, 0.0, -20.0)])

    def views(X, Y):
        count = np.zeros(len(X), int)
        for strip in strips:
            for s in strip:
                r, c = s.project(X, Y, np.zeros_like(X))
                count += (np.isfinite(r) & (c >= 0) & (c <= 800)).astype(int)
        return count

    X = np.array([600.0, 750.0, 900.0])
    single = views(X, np.full(3, -150.0))
    double = views(X, np.full(3, 200.0))
    return {"views_one_strip": int(single.min()) if np.all(single == single[0]) else -1,
            "views_overlap": int(double.min()) if np.all(double == double[0]) else -1,
            "stereo_pairs": comb(3, 2)}


def imu_quality_interval(inputs: dict) -> dict:
    """Simulation of the sentence "the more accurate the IMU, the longer the interval between
    fixed centres can be": with the fixed centres exact, the error of the interpolated line EO
    (8.15.2) is the IMU's drift minus its linear interpolation (a Brownian bridge). Seeded random
    walks of two IMU grades (σ per √s of 1 and 10 µrad); for each, the longest fixed-centre
    interval (from 1, 2, 4, … 32 s) whose worst angular error stays below the tolerance."""
    from ..georef import interpolate_fixed_centres
    rng = np.random.default_rng(int(inputs.get("seed", 3)))
    rate, T = 20.0, 64.0
    t = np.arange(int(T * rate) + 1) / rate
    tol = float(inputs.get("tolerance_urad", 20.0)) * 1e-6
    longest = {}
    for grade in inputs.get("grades_urad_per_sqrt_s", [1.0, 10.0]):
        walks = np.cumsum(rng.normal(0, grade * 1e-6 / np.sqrt(rate), (len(t), 3)), axis=0)
        truth = np.zeros((len(t), 6))
        measured = truth.copy()
        measured[:, 3:] -= walks
        best = 0.0
        for dt in (1, 2, 4, 8, 16, 32):
            fixed = np.arange(0, len(t), int(dt * rate))
            E = interpolate_fixed_centres(t, t[fixed], truth[fixed], measured, measured[fixed])
            if np.abs(E[:, 3:]).max() < tol:
                best = float(dt)
        longest[grade] = best
    g = sorted(longest)
    return {"better_imu_longer_interval": "yes" if longest[g[0]] > longest[g[-1]] else "no",
            "interval_good_imu_s": longest[g[0]], "interval_poor_imu_s": longest[g[-1]]}


def truncated_sentence(inputs: dict) -> dict:
    """Nothing can be computed for a sentence whose conclusion is lost."""
    return {}


# --------------------------------------------------------------------------- §8.16
def ray_ground_formula(inputs: dict) -> dict:
    """(8.16.1) as printed: X = X_s + (Z − Z_s)X'/Z' and a column (X', Y', Y', Z')ᵀ = A·(x − x₀,
    y − y₀, −f)ᵀ. ``inputs["vector"]`` lists the printed left-hand column; it must have the three
    components of A·r, and the pair X, Y of (7.7.1)/(8.7.1) must be given (``inputs["formulas"]``)."""
    A = _mat("a")
    x, y, x0, y0, f, X, Y, Z, Xs, Ys, Zs = sp.symbols("x y x_0 y_0 f X Y Z X_s Y_s Z_s", real=True)
    derived = A * sp.Matrix([x - x0, y - y0, -f])
    column = inputs["vector"]
    if len(column) != 3:
        return _ok(False)
    names = dict(zip(("Xp", "Yp", "Zp"), derived))
    local = {"X_s": Xs, "Y_s": Ys, "Z_s": Zs, "Z": Z, **names}
    printed = [sp.parse_expr(e, local_dict=local) for e in inputs["formulas"]]
    want = [Xs + (Z - Zs) * derived[0] / derived[2], Ys + (Z - Zs) * derived[1] / derived[2]]
    return _ok(len(printed) == 2 and all(sp.simplify(p - w) == 0 for p, w in zip(printed, want)))


def forward_rpc_formula(inputs: dict) -> dict:
    """(8.16.2) is the forward RPC model (8.5.6) of §8.5: the same ratios R₁/R₂, R₃/R₄ of
    polynomials in (x, y, Z)."""
    R1, R2, R3, R4 = (sp.Function(n) for n in ("R1", "R2", "R3", "R4"))
    x, y, Z = sp.symbols("x y Z", real=True)
    local = {"R1": R1, "R2": R2, "R3": R3, "R4": R4, "x": x, "y": y, "Z": Z}
    X = sp.parse_expr(inputs["X"], local_dict=local)
    Y = sp.parse_expr(inputs["Y"], local_dict=local)
    return _ok(sp.simplify(X - R1(x, y, Z) / R2(x, y, Z)) == 0 and sp.simplify(Y - R3(x, y, Z) / R4(x, y, Z)) == 0)


def _terrain(X, Y):
    return 100.0 + 20.0 * np.sin(X / 40.0) * np.cos(Y / 55.0)


def _texture(X, Y):
    return 100 + 60 * np.sin(X / 6.0) * np.cos(Y / 9.0) + 40 * np.cos((X - Y) / 13.0)


def _small_scanner(n_lines=50, n_cols=51, step=0.8):
    from ..georef import TabulatedLineScanner
    i = np.arange(n_lines, dtype=float)
    eo = np.column_stack([step * i, 0.5 * np.sin(i / 9.0), np.full(n_lines, 1100.0),
                          2e-3 * np.sin(i / 5.0), np.full(n_lines, 1e-3), np.full(n_lines, 0.01)])
    return TabulatedLineScanner(eo, 62.5, 0.05, n_cols)


def _render(s):
    rows, cols = np.mgrid[0:s.shape[0], 0:s.shape[1]].astype(float)
    Z = np.full(rows.shape, 100.0)
    for _ in range(12):
        X, Y = s.ground(rows, cols, Z)
        Z = _terrain(X, Y)
    return _texture(X, Y)


def direct_vs_inverse(inputs: dict) -> dict:
    """Direct and inverse orthophotos of one synthetic scanner image (§8.16).

    A nadir line scanner (f = 62.5 mm, 0.05 mm pixels, H ≈ 1000 m: 0.8 m across, lines every
    0.8 m, attitude wiggle 2 mrad) over an analytic terrain (±20 m) and texture; the orthophoto
    grid has ``ortho_pixel`` m pixels inside the image. Direct: every scanner pixel monoplotted
    onto the DEM (:func:`photolib.georef.direct_orthorectify`); inverse: every ortho pixel
    projected into the image by the line search (:meth:`TabulatedLineScanner.project`) through
    :func:`photolib.rectify.orthorectify`.
    """
    from ..georef import direct_orthorectify
    from ..rectify import RasterGrid, orthorectify
    s = _small_scanner()
    image = _render(s)
    dem_grid = RasterGrid(-30.0, 50.0, 1.0, (100, 110))
    Xd, Yd = dem_grid.centres()
    dem = _terrain(Xd, Yd)
    px = float(inputs.get("ortho_pixel", 0.5))
    grid = RasterGrid(8.0, 12.0, px, (int(22 / px), int(24 / px)))
    direct = direct_orthorectify(image, s.ground, dem, dem_grid, grid)
    inverse = orthorectify(image, s.project, dem, dem_grid, grid)
    hole_direct = float(direct.holes.mean())
    hole_inverse = float(np.mean(~np.isfinite(inverse)))
    return {"direct_has_holes": "yes" if hole_direct > 0 and hole_inverse == 0 else "no",
            "holes_direct": round(hole_direct, 3), "holes_inverse": hole_inverse,
            "direct_iterations": int(direct.iterations),
            "inverse_without_rpc_problematic": "no" if np.isfinite(inverse).all() and
            np.sqrt(np.mean((inverse - _texture(*grid.centres())) ** 2)) < 2.0 else "yes"}


# --------------------------------------------------------------------------- §8.17
def cost_formula(inputs: dict) -> dict:
    """(8.17.1): a cost minimised over Z must be a dissimilarity (≥ 0, 0 iff equal); the printed
    signed difference is compared with |d¹ − d²|."""
    d1, d2 = sp.symbols("d1 d2", real=True)
    printed = sp.parse_expr(inputs["cost"], local_dict={"d1": d1, "d2": d2, "Abs": sp.Abs})
    return _ok(sp.simplify(printed - sp.Abs(d1 - d2)) == 0)


def _chain_energy(C, labels, P1, P2):
    e = sum(C[i][l] for i, l in enumerate(labels))
    for a, b in zip(labels[:-1], labels[1:]):
        e += P1 * (abs(a - b) == 1) + P2 * (abs(a - b) > 1)
    return e


def _literal_path(C, P1, P2, normalise=True):
    """(8.17.3) literally along a chain: labels are the Z levels i·ΔZ, Z ± ΔZ the neighbours."""
    L = [list(C[0])]
    for c in C[1:]:
        prev, m, D = L[-1], min(L[-1]), len(c)
        row = []
        for z in range(D):
            cands = [prev[z], m + P2]
            if z > 0:
                cands.append(prev[z - 1] + P1)
            if z < D - 1:
                cands.append(prev[z + 1] + P1)
            row.append(c[z] + min(cands) - (m if normalise else 0))
        L.append(row)
    return L


def energy_formula(inputs: dict) -> dict:
    """(8.17.2) with Iverson brackets, |Z − Z_q| in steps ΔZ: on random integer chains the least
    energy over all labellings equals the minimum of the path recursion (8.17.3) without its
    − min term (dynamic programming is exact on one path)."""
    rng = np.random.default_rng(int(inputs.get("seed", 1)))
    ok = True
    for _ in range(int(inputs.get("trials", 4))):
        C = rng.integers(0, 20, (4, 4)).tolist()
        best = min(_chain_energy(C, lab, 3, 11) for lab in itertools.product(range(4), repeat=4))
        ok &= best == min(_literal_path(C, 3, 11, normalise=False)[-1])
    return _ok(ok)


def recursion_formula(inputs: dict) -> dict:
    """(8.17.3): the literal recursion equals :func:`photolib.sgm.path_cost` along a row of a
    voxel volume, and its minimum plus the subtracted minima equals the brute-force chain
    minimum of (8.17.2)."""
    from .. import sgm
    rng = np.random.default_rng(int(inputs.get("seed", 2)))
    ok = True
    for _ in range(int(inputs.get("trials", 3))):
        C = rng.integers(0, 20, (5, 5)).astype(float)
        lit = np.array(_literal_path(C.tolist(), 2.0, 9.0))
        lib = sgm.path_cost(C[None].astype(np.float32), (1, 0), 2.0, 9.0)[0]
        ok &= np.allclose(lit, lib)
        best = min(_chain_energy(C.tolist(), lab, 2.0, 9.0) for lab in itertools.product(range(5), repeat=5))
        ok &= abs(lit[-1].min() + sum(r.min() for r in lit[:-1]) - best) < 1e-9
    return _ok(ok)


def sum_formula(inputs: dict) -> dict:
    """(8.17.4): :func:`photolib.sgm.aggregate_costs` with 8 paths equals the sum of the 8
    single-direction path costs on a random voxel volume (Y, X, Z)."""
    from .. import sgm
    rng = np.random.default_rng(int(inputs.get("seed", 3)))
    C = rng.uniform(0, 10, (6, 7, 5)).astype(np.float32)
    dirs = [(1, 0), (-1, 0), (0, 1), (0, -1), (1, 1), (-1, -1), (1, -1), (-1, 1)]
    total = sum(sgm.path_cost(C, d, 1.0, 4.0).astype(float) for d in dirs)
    return _ok(np.allclose(total, sgm.aggregate_costs(C, 1.0, 4.0, paths=8), atol=1e-3))


def eight_directions(inputs: dict) -> dict:
    """The 8 path directions of (8.17.3)–(8.17.4): the neighbours of a node in 45° steps, and
    aggregate_costs(paths=8) is their sum."""
    ok = sum_formula({"seed": 3})["printed_equals_derived"]
    n = len({(dx, dy) for dx in (-1, 0, 1) for dy in (-1, 0, 1) if (dx, dy) != (0, 0)})
    return {"n_paths": n if ok else -1}


def transcribed(inputs: dict) -> dict:
    """Pure specifications: nothing to compute."""
    return {}
