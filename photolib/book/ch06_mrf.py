"""The MRF terrain paper (Baikalova, Dubina, Evtyushkin, Yushakov; appendix to Chapter 6, §6.4):
formula checks and inline statements.

Adapters for the ``[[formula]]`` and ``[[example]]`` entries ``mrf-…`` of
``textbook/ch06_mrf.toml`` (seed ``003_82b4f0b2dd43dc56.txt``). Formula adapters take the
printed formula transcribed as sympy text (so a test can hand in a wrong one) and return
``{"printed_equals_derived": bool}``; the derivations are independent of :mod:`photolib.mrf`:

* the correlation coefficient against Pearson's r, written with centred sums, for symbolic
  windows (polynomial identity decided by ``sympy.expand``);
* the parallax count from the normal-case parallax p(h) = f·B/(H − h) (§2.5) and 1 inch =
  0.0254 m;
* the Gibbs conditional from the joint distribution exp(a ΣV_p + b Σ_pairs Δ) on a tiny grid;
* the geometry (direction cosines, base direction, horizontal images, intersection, the
  similarity (3)) in exact rational arithmetic at random rational points, with rotations from
  Chapter 1's elementary matrices.
"""

from __future__ import annotations

import itertools

import numpy as np
import sympy as sp

from ._exact import zero

_AL, _OM, _CH = sp.symbols("alpha omega chi", real=True)


def _ok(flag) -> dict:
    return {"printed_equals_derived": bool(flag)}


def _rx(t):
    return sp.Matrix([[1, 0, 0], [0, sp.cos(t), -sp.sin(t)], [0, sp.sin(t), sp.cos(t)]])


def _ry(t):
    return sp.Matrix([[sp.cos(t), 0, sp.sin(t)], [0, 1, 0], [-sp.sin(t), 0, sp.cos(t)]])


def _rz(t):
    return sp.Matrix([[sp.cos(t), -sp.sin(t), 0], [sp.sin(t), sp.cos(t), 0], [0, 0, 1]])


def _matrix_from_text(rows, values) -> sp.Matrix:
    loc = {"sin": sp.sin, "cos": sp.cos, "sqrt": sp.sqrt, **values}
    return sp.Matrix([[sp.parse_expr(str(e), local_dict=loc) for e in row] for row in rows])


# =================================================================================================
# correlation (seed lines 18–32)
# =================================================================================================
def correlation_formula(inputs: dict) -> dict:
    """The printed r with its sums a…e against Pearson's r = Σ(s − s̄)(t − t̄)/√(Σ(s − s̄)²Σ(t − t̄)²).

    ``inputs``: ``r`` in a, b, c, d, e, n and ``a``…``e`` as expressions in ``S1``/``S2`` (the
    windows' pixel lists; write ``Sum(S1)``, ``Sum(Sq(S1))``, ``Dot(S1, S2)``). Decided exactly,
    in rational arithmetic, at random integer windows of 4, 9 and 25 pixels: r² and the sign of r
    must equal those of Pearson's r (a wrong rational identity survives a random point only with
    probability zero).
    """
    rng = np.random.default_rng(11)
    flags = []
    for n in (4, 9, 25):
        S1 = [sp.Integer(int(v)) for v in rng.integers(0, 256, n)]
        S2 = [sp.Integer(int(v)) for v in rng.integers(0, 256, n)]
        loc = {"S1": S1, "S2": S2, "Sum": lambda v: sp.Add(*v), "Sq": lambda v: [u ** 2 for u in v],
               "Dot": lambda u, w: sp.Add(*[x * y for x, y in zip(u, w)]), "n": sp.Integer(n), "sqrt": sp.sqrt}
        sums = {k: sp.parse_expr(str(inputs[k]), local_dict=loc) for k in "abcde"}
        r = sp.parse_expr(str(inputs["r"]), local_dict={**loc, **sums})
        m1, m2 = sp.Add(*S1) / n, sp.Add(*S2) / n
        num = sp.Add(*[(s - m1) * (t - m2) for s, t in zip(S1, S2)])
        v1 = sp.Add(*[(s - m1) ** 2 for s in S1])
        v2 = sp.Add(*[(t - m2) ** 2 for t in S2])
        flags.append(sp.expand(r ** 2 - num ** 2 / (v1 * v2)) == 0 and sp.sign(r) == sp.sign(num))
    return _ok(all(flags))


# =================================================================================================
# the number of candidate parallaxes (seed lines 34–38)
# =================================================================================================
def parallax_count_formula(inputs: dict) -> dict:
    """N as printed against N = Δh·(dp/dh)/pixel with p = f·B/(H − h), f = H/M, pixel = 0.0254/DPI m."""
    Hmax, Hmin, B, DPI, H, M, h = sp.symbols("H_max H_min B DPI H M h", positive=True)
    f = H / M
    p = f * B / (H - h)
    dpdh = sp.diff(p, h).subs(h, 0)                   # first order about the datum
    derived = (Hmax - Hmin) * dpdh / (sp.Rational(254, 10000) / DPI)
    from sympy.parsing.sympy_parser import rationalize, standard_transformations
    printed = sp.parse_expr(str(inputs["N"]), local_dict={"H_max": Hmax, "H_min": Hmin, "B": B, "DPI": DPI,
                                                           "H": H, "M": M},
                            transformations=standard_transformations + (rationalize,))   # 0.0254 exactly
    return _ok(sp.cancel(printed / derived) == 1)


def parallax_count_example(inputs: dict) -> dict:
    """N for the guide's illustrative case, with the correct and the printed constant (no printed N)."""
    from ..mrf import parallax_count
    args = (inputs["h_max"], inputs["h_min"], inputs["base"], inputs["dpi"], inputs["flying_height"],
            inputs["scale"])
    return {"N": parallax_count(*args), "N_as_printed": parallax_count(*args, constant=0.245)}


# =================================================================================================
# the Gibbs model (seed lines 46–60)
# =================================================================================================
def gibbs_conditional(inputs: dict) -> dict:
    """P(x, y, p) as printed is the conditional of exp(a·ΣV_p + b·Σ_{8-neighbour pairs}(p − p′)²)?

    Enumerated exactly on a 2×2 grid (every pixel neighbours the other three) with three labels,
    symbolic a, b and random rational V_p: the conditional of pixel (0, 0) given the others,
    computed from the joint, against the printed formula with V_s = Σ over the neighbours.
    """
    a, b = sp.symbols("a b", real=True)
    labels = [0, 1, 2]
    rng = np.random.default_rng(1)
    Vp = {(i, k): sp.Rational(int(rng.integers(-9, 10)), 10) for i in range(4) for k in labels}
    pairs = list(itertools.combinations(range(4), 2))          # on a 2×2 grid all pairs are 8-neighbours

    def joint(cfg):
        return sp.exp(a * sum(Vp[(i, cfg[i])] for i in range(4)) + b * sum((cfg[i] - cfg[j]) ** 2 for i, j in pairs))

    flags = []
    for rest in [(0, 1, 2), (2, 2, 1)]:
        den = sum(joint((k, *rest)) for k in labels)
        loc = {"a": a, "b": b, "exp": sp.exp, "Vp": lambda q: Vp[(0, int(q))],
               "Vs": lambda q: sum((q - r) ** 2 for r in rest)}
        total = sum(sp.parse_expr(str(inputs["summand"]), local_dict={**loc, "q": q}) for q in labels)
        for p in labels:
            derived = joint((p, *rest)) / den
            val = sp.parse_expr(str(inputs["numerator"]), local_dict={**loc, "p": p}) / total
            for av, bv in ((sp.Rational(7, 5), sp.Rational(-3, 10)), (sp.Integer(2), sp.Rational(1, 2))):
                diff = sp.N((val - derived).subs({a: av, b: bv}), 40)
                flags.append(abs(diff) < sp.Float("1e-30"))
    return _ok(all(flags))


def smoothness_sign(inputs: dict) -> dict:
    """With the printed sign (b > 0, an inverse temperature) does V_s favour smooth maps?

    Neighbours all at p′ = 0; the conditional of p = 0 against p = 1 is exp(−8b)·(data ratio):
    the smooth value is preferred iff b·V_s decreases with roughness, i.e. iff b < 0. ``inputs``:
    ``b_sign`` (+1 as printed: inverse temperatures are positive) and ``Delta`` (Δ(p, q)).
    """
    b = sp.Symbol("b", positive=True) * int(inputs["b_sign"])
    Vs = lambda p: sum(sp.parse_expr(str(inputs["Delta"]), local_dict={"p": p, "q": 0}) for _ in range(8))  # noqa: E731
    ratio = sp.exp(b * Vs(0)) / sp.exp(b * Vs(1))      # P(p = 0)/P(p = 1) at equal data
    values = [ratio.subs(b.free_symbols.pop(), v) for v in (sp.Rational(1, 10), sp.Integer(1), sp.Integer(3))]
    return _ok(all(v > 1 for v in values))


def stationary_limit(inputs: dict) -> dict:
    """Seeded simulation: marginals after burn-in from two different starts agree (stationary limit)."""
    from ..mrf import gibbs_relaxation
    rng = np.random.default_rng(int(inputs["seed"]))
    P = np.arange(5)
    r = rng.uniform(-1, 1, (5, 6, 6))
    sweeps, burn = int(inputs["sweeps"]), int(inputs["burn_in"])
    one = gibbs_relaxation(r, P, a=2.0, b=-0.3, sweeps=sweeps, burn_in=burn, seed=1)
    two = gibbs_relaxation(r, P, a=2.0, b=-0.3, sweeps=sweeps, burn_in=burn, seed=2,
                           initial=rng.integers(0, 5, (6, 6)).astype(float))
    diff = float(np.abs(one.marginals - two.marginals).max())
    sigma = np.sqrt(0.25 / (sweeps - burn))            # worst-case binomial σ of one marginal
    return {"limit_independent_of_start": "yes" if diff < 6 * sigma else "no", "max_marginal_difference": diff}


def neighbourhood(inputs: dict) -> dict:
    """Count of (i, j) ∈ {−1, 0, 1}² without (0, 0)."""
    return {"neighbours": sum(1 for i in (-1, 0, 1) for j in (-1, 0, 1) if (i, j) != (0, 0))}


# =================================================================================================
# geometry (seed lines 64–146)
# =================================================================================================
def direction_cosines_formula(inputs: dict) -> dict:
    """(1) as printed equals R_Y(−α)·R_X(ω)·R_Z(χ) (Chapter 1's elementary rotations) and is orthogonal."""
    A = _matrix_from_text(inputs["A"], {"alpha": _AL, "omega": _OM, "chi": _CH})
    derived = _ry(-_AL) * _rx(_OM) * _rz(_CH)
    return _ok(zero(A - derived) and zero(A.T * A - sp.eye(3)))


def _paper_A(al, om, ch):
    return _ry(-al) * _rx(om) * _rz(ch)


def _rational_rotation(rng):
    q = [sp.Rational(int(rng.integers(-8, 9)), 8) for _ in range(3)] + [sp.Rational(int(rng.integers(8, 24)), 8)]
    a, b, c, d = q
    Q = sp.Matrix([[d**2 + a**2 - b**2 - c**2, 2 * (a * b - c * d), 2 * (a * c + b * d)],
                   [2 * (a * b + c * d), d**2 - a**2 + b**2 - c**2, 2 * (b * c - a * d)],
                   [2 * (a * c - b * d), 2 * (b * c + a * d), d**2 - a**2 - b**2 + c**2]])
    return Q / (a**2 + b**2 + c**2 + d**2)


def base_direction_formula(inputs: dict) -> dict:
    """Steps 2–4: A(τ, V) = A₁·A(α′₁, 0, χ′₁), A₂ = A(τ, V)·A(α′₂, ω′₂, χ′₂), B = B(cos v cos τ, cos v sin τ, sin v).

    Reading: A(α′₁, 0, χ′₁) maps the base frame into image 1 (first column = base direction in
    image-1 axes). At random angles (floating point, 1e-12): does the first column of the printed
    A(τ, V) give the base direction in the model frame, and do steps 2–3 give the true rotation of
    image 2? ``inputs``: ``A_tau`` (expression in A1, Ab), ``A2`` (in A_tau, A2p), ``base``
    (3 strings in tau, v).
    """
    rng = np.random.default_rng(3)
    flags = []
    A_num = lambda al, om, ch: sp.Matrix(np.array(_paper_A(al, om, ch).subs({}).evalf(), dtype=float))  # noqa: E731
    for _ in range(3):
        al1, ch1, al2, om2, ch2 = (float(v) for v in rng.uniform(-0.3, 0.3, 5))
        A1 = sp.Matrix(np.array(_rational_rotation(rng), dtype=float))     # the left image (any A₁)
        Ab = A_num(al1, 0.0, ch1)                                          # base frame → image 1
        A2p = A_num(al2, om2, ch2)                                         # image 2 → base frame
        loc = {"A1": A1, "Ab": Ab, "A2p": A2p, "Matrix": sp.Matrix}
        A_tau = sp.parse_expr(str(inputs["A_tau"]), local_dict=loc)
        true_base = np.array(A1 * Ab[:, 0], dtype=float).ravel()          # the base in the model frame
        tau, v = float(np.arctan2(true_base[1], true_base[0])), float(np.arcsin(true_base[2]))
        Bvec = np.array([float(sp.parse_expr(e, local_dict={"tau": sp.Float(tau), "v": sp.Float(v), "cos": sp.cos,
                                                            "sin": sp.sin})) for e in inputs["base"]])
        A2 = sp.parse_expr(str(inputs["A2"]), local_dict={**loc, "A_tau": A_tau})
        true_A2 = A1 * Ab * A2p
        err = np.concatenate([np.array(A_tau[:, 0], dtype=float).ravel() - true_base, Bvec - true_base,
                              np.array(A2 - true_A2, dtype=float).ravel()])
        flags.append(bool(np.abs(err).max() < 1e-12))
    return _ok(all(flags))


def relative_elements_rank(inputs: dict) -> dict:
    """Step 1: are the printed five elements determinable from the coplanarity condition?

    The rank of ∂(coplanarity)/∂(elements) over 12 generic point pairs of a near-vertical pair
    (base along x, rotations of (1)) at the paper's first approximation (all angles 0): 5 for a
    valid set. Also the condition number at the true solution. ``inputs["elements"]``: five of
    ``alpha1 omega1 chi1 alpha2 omega2 chi2`` (the others fixed at their true values, χ′₁ = 0.03
    rad, or 0 if not an element).
    """
    names = list(inputs["elements"])
    rng = np.random.default_rng(0)
    P = np.column_stack([rng.uniform(-300, 300, 12), rng.uniform(-300, 300, 12), rng.uniform(-1100, -900, 12)])
    B = np.array([400.0, 0.0, 0.0])
    truth = dict(alpha1=0.02, omega1=0.0, chi1=0.03, alpha2=-0.01, omega2=0.015, chi2=0.02)

    def A(al, om, ch):
        return np.array(_paper_A(al, om, ch).evalf(), dtype=float)

    A1t, A2t = A(truth["alpha1"], 0.0, truth["chi1"]), A(truth["alpha2"], truth["omega2"], truth["chi2"])
    r1 = P @ A1t                     # image-1 ray components (A1ᵀ P row-wise)
    r2 = (P - B) @ A2t

    def cop(x):
        el = dict.fromkeys(truth, 0.0)
        el.update({k: truth[k] for k in truth if k not in names})
        el.update(dict(zip(names, x)))
        m1 = r1 @ A(el["alpha1"], el["omega1"], el["chi1"]).T
        m2 = r2 @ A(el["alpha2"], el["omega2"], el["chi2"]).T
        return np.einsum("ij,ij->i", np.cross(np.broadcast_to(B, m1.shape), m1), m2)

    def jac(x):
        return np.column_stack([(cop(x + h) - cop(x - h)) / 2e-6 for h in np.eye(5) * 1e-6])

    s0 = np.linalg.svd(jac(np.zeros(5)), compute_uv=False)        # the paper's first approximation
    rank = int(np.sum(s0 > 1e-8 * s0[0]))
    st = np.linalg.svd(jac(np.array([truth[k] for k in names])), compute_uv=False)
    return _ok(rank == 5) | {"rank_at_start": rank, "condition_at_solution": float(st[0] / st[-1])}


def horizontal_reduction_formula(inputs: dict) -> dict:
    """(2): x₀ = −f X′/Z′ is where the ray A(x, y, −f) meets the horizontal image plane z = −f."""
    rng = np.random.default_rng(5)
    flags = []
    for _ in range(3):
        A = _rational_rotation(rng)
        x, y = (sp.Rational(int(rng.integers(-80, 81)), 2) for _ in range(2))
        f = sp.Rational(int(rng.integers(80, 160)), 1)
        Xp, Yp, Zp = A * sp.Matrix([x, y, -f])
        lam = -f / Zp                                          # the ray scaled to z = −f
        loc = {"f": f, "Xp": Xp, "Yp": Yp, "Zp": Zp}
        x0 = sp.parse_expr(str(inputs["x0"]), local_dict=loc)
        y0 = sp.parse_expr(str(inputs["y0"]), local_dict=loc)
        flags.append(sp.simplify(x0 - lam * Xp) == 0 and sp.simplify(y0 - lam * Yp) == 0)
    return _ok(all(flags))


def intersection_formula(inputs: dict) -> dict:
    """Step 6 at random exact geometry: do the printed X, Y, Z (with N) give the object point?

    Horizontal images of a point P from S₁ and S₂ = S₁ + B: x_i0 = −f(X − X_Si)/(Z − Z_Si) ….
    The parallax p of the printed Z is the x-parallax x₁₀ − x₂₀ (the paper's p is in pixels; any
    non-zero value shows the term is spurious). ``inputs``: ``N``, ``X``, ``Y``, ``Z`` strings.
    """
    rng = np.random.default_rng(6)
    flags = []
    for _ in range(3):
        S1 = sp.Matrix([sp.Rational(int(rng.integers(-50, 51)), 1) for _ in range(2)] + [1000])
        B = sp.Matrix([sp.Rational(int(rng.integers(300, 500)), 1), sp.Rational(int(rng.integers(-20, 21)), 1),
                       sp.Rational(int(rng.integers(-20, 21)), 1)])
        P = sp.Matrix([sp.Rational(int(rng.integers(-200, 600)), 1), sp.Rational(int(rng.integers(-200, 200)), 1),
                       sp.Rational(int(rng.integers(-50, 50)), 1)])
        f = sp.Integer(100)
        d1, d2 = P - S1, P - S1 - B
        x10, y10 = -f * d1[0] / d1[2], -f * d1[1] / d1[2]
        x20 = -f * d2[0] / d2[2]
        loc = {"Bx": B[0], "By": B[1], "Bz": B[2], "f": f, "x10": x10, "y10": y10, "x20": x20,
               "Xs1": S1[0], "Ys1": S1[1], "Zs1": S1[2], "p": x10 - x20}
        N = sp.parse_expr(str(inputs["N"]), local_dict=loc)
        loc["N"] = N
        XYZ = [sp.parse_expr(str(inputs[k]), local_dict=loc) for k in ("X", "Y", "Z")]
        flags.append(all(sp.simplify(u - w) == 0 for u, w in zip(XYZ, P)))
    return _ok(all(flags))


def convergence_rotation_formula(inputs: dict) -> dict:
    """Step 7: the printed X, Y are the rotation about Z by G₀ (orthogonal, det +1)."""
    G, Xp, Yp, Zp = sp.symbols("G0 Xp Yp Zp", real=True)
    loc = {"G0": G, "Xp": Xp, "Yp": Yp, "Zp": Zp, "cos": sp.cos, "sin": sp.sin}
    out = sp.Matrix([sp.parse_expr(str(inputs[k]), local_dict=loc) for k in ("X", "Y", "Z")])
    return _ok(zero(out - _rz(G) * sp.Matrix([Xp, Yp, Zp])))


def similarity_angle_map(inputs: dict) -> dict:
    """(3) with the printed angle map: is ν a rotation (heights unchanged) and ξ a transverse tilt?

    The model's X axis runs along the base. A longitudinal tilt ζ turns the X–Z plane (heights
    change along X), a transverse tilt ξ the Y–Z plane (heights change along Y), the rotation ν
    keeps every height. ``inputs``: ``alpha``, ``omega``, ``chi`` as the names ``zeta``, ``xi``,
    ``nu`` (the map to the angles of (1)). Checked by the derivative of A at zero.
    """
    zeta, xi, nu = sp.symbols("zeta xi nu", real=True)
    loc = {"zeta": zeta, "xi": xi, "nu": nu}
    A = _paper_A(*(sp.parse_expr(str(inputs[k]), local_dict=loc) for k in ("alpha", "omega", "chi")))
    at0 = {zeta: 0, xi: 0, nu: 0}
    dz = lambda t: sp.diff(A, t).subs(at0)[2, :]             # noqa: E731 — the height row of ∂A
    ok = (dz(nu) == sp.zeros(1, 3)                            # rotation: heights unchanged
          and dz(xi)[0] == 0 and dz(xi)[1] != 0               # transverse tilt: Z changes along Y only
          and dz(zeta)[1] == 0 and dz(zeta)[0] != 0)          # longitudinal tilt: Z changes along X only
    return _ok(ok)


def minimum_control(inputs: dict) -> dict:
    """Rank of the Jacobian of (3) in the 7 elements for control sets: 2 full + 1 height, 2 full, 1 full + 4 height."""
    rng = np.random.default_rng(2)
    M = np.column_stack([rng.uniform(-60, 60, (5, 2)), rng.uniform(-5, 5, 5)])

    def model(x, pts):
        A = np.array(_paper_A(x[3], x[4], x[5]).evalf(), dtype=float)
        return x[:3] + x[6] * pts @ A.T

    x0 = np.array([1000.0, 2000.0, 150.0, 0.02, -0.01, 0.5, 8.0])

    def rank(mask):
        def g(x):
            return model(x, M)[mask]
        J = np.column_stack([(g(x0 + h) - g(x0 - h)) / 2e-6 for h in np.eye(7) * 1e-6])
        s = np.linalg.svd(J, compute_uv=False)
        return int(np.sum(s > 1e-8 * s[0]))

    full2_h1 = np.zeros((5, 3), bool)
    full2_h1[:2] = True
    full2_h1[2, 2] = True
    full2 = np.zeros((5, 3), bool)
    full2[:2] = True
    return {"unknowns": 7, "equations_per_point": 3, "rank_2_full_1_height": rank(full2_h1),
            "rank_2_full": rank(full2), "min_points": 3 if rank(full2_h1) == 7 and rank(full2) < 7 else 0}


def inline_values(inputs: dict) -> dict:
    """Nothing computed: the entry's quantities are transcribed or not reproducible."""
    return {}
