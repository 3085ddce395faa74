"""Hanzl §6 and §8–§10.1: adapters for ``textbook/ch10_hanzl.toml`` and ``textbook/ch05_hanzl.toml``.

V. Hanzl, *Fotogrammetrie, Modul 01* (seed 002): §6 acquisition of aerial images (filed under
Chibunichev Ch. 10), §8 the digital image, the bilinear formulas of §9 and the normalised images
of §10.1 (filed under Ch. 5). Inputs → library calls (:mod:`photolib.planning`,
:mod:`photolib.features`, :mod:`photolib.matching`, :mod:`photolib.digital`,
:mod:`photolib.epipolar`); the formula adapters take the printed formula transcribed as sympy
text in ``inputs`` and return ``{"printed_equals_derived": bool}`` from an independent sympy
derivation.
"""

from __future__ import annotations

import math

import numpy as np
import sympy as sp

from .. import digital, features as ft, matching, planning
from ..epipolar import pyramid
from ._exact import zero as _zero

_NAMES = ("x y dx dy a0 a1 a2 a3 a4 a5 d X Y Z1 Z2 Z3 Z4 Sxx Sxy Syy l1 l2 r c dc tau s m_s p q v t "
          "A1 A2 R1 R2 gx gy l")
_S = {n: sp.Symbol(n, real=True) for n in _NAMES.split()}


def _parse(text, extra=None):
    return sp.parse_expr(str(text), local_dict={**_S, "sqrt": sp.sqrt, "tan": sp.tan, **(extra or {})})


def _ok(flag) -> dict:
    return {"printed_equals_derived": bool(flag)}



def _rows(matrix) -> dict:
    """A matrix as {"row_1": "11 -3 1 1 1", ...} (integers as printed)."""
    return {f"row_{i + 1}": " ".join(str(int(v)) for v in row) for i, row in enumerate(np.asarray(matrix))}


def _sig(x: float, digits: int) -> float:
    """x rounded to ``digits`` significant digits (the presentation of Tab. 6.1)."""
    if x == 0:
        return 0.0
    return float(round(x, digits - 1 - int(math.floor(math.log10(abs(x))))))


# --- §6 acquisition (ch10_hanzl.toml) -------------------------------------------------------------------
def diffraction(inputs: dict) -> dict:
    """§6.3.1: r = 1.22 λ k."""
    return {"r": planning.diffraction_radius(inputs["k"], inputs["wavelength_um"])}


def smear(inputs: dict) -> dict:
    """§6.3.3: s = v t / m_s, in µm (v from km/h)."""
    s = planning.image_motion(inputs["speed_kmh"] / 3.6, inputs["exposure_s"], inputs["scale_number"])
    return {"smear": s * 1e6, "effective": 0.5 * s * 1e6}


def sensor_format(inputs: dict) -> dict:
    """§6.2: a sensor's side = pixels × pixel size (mm), and pixels in megapixels."""
    nx, ny, p = inputs["pixels_x"], inputs["pixels_y"], inputs.get("pixel_um", 0.0)
    return {"side_x": nx * p / 1000.0, "side_y": ny * p / 1000.0, "megapixels": nx * ny / 1e6}


def table_6_1(inputs: dict) -> dict:
    """Tab. 6.1: m_s = 200 √m_k, printed to two significant digits."""
    ms = planning.photo_scale_from_map(np.array(inputs["map_scale_numbers"], float), inputs["constant"])
    return {f"ms_{int(mk)}": _sig(float(v), 2) for mk, v in zip(inputs["map_scale_numbers"], ms)}


def target_rule(inputs: dict) -> dict:
    """§6.5: the divisors of the target rule recovered from photolib.planning.target_sizes (m → cm)."""
    ms = 10000.0
    t = planning.target_sizes(ms)
    return {"arm_divisor": ms / (t.arm_length * 100), "width_divisor": ms / (t.arm_width * 100),
            "square_divisor": ms / (t.square_side * 100)}


def feet(inputs: dict) -> dict:
    """§6.7: flying height 5000 ft in metres (international foot 0.3048 m)."""
    return {"height_m": inputs["feet"] * 0.3048}


def flight_formula(inputs: dict) -> dict:
    """§6.4: B = s m_s (1 − p/100) [A the same with q]: the ground side s·m_s of an image times the
    non-overlapping fraction, derived from the positions of two consecutive footprints."""
    s, ms, ov = _S["s"], _S["m_s"], _S[inputs["overlap"]]
    side = s * ms                                   # footprint side on the ground (h/c = m_s)
    start2 = sp.Symbol("x2")                        # next footprint starts at x2 and overlaps side·ov/100
    advance = sp.solve(sp.Eq(side - start2, side * ov / 100), start2)[0]
    return _ok(_zero(_parse(inputs["printed"]) - advance))


def flight_plan_numbers(inputs: dict) -> dict:
    """§6.4 with the common values: h, B, A for c, m_s, s, p, q (an illustration)."""
    fp = planning.photo_flight_plan(inputs["c_mm"], inputs["scale_number"], inputs["format_mm"],
                                    forward_overlap=inputs["p"], side_overlap=inputs["q"])
    return {"p": inputs["p"], "q": inputs["q"], "h": fp.flying_height, "B": fp.base, "A": fp.strip_spacing}


def goniometer_formula(inputs: dict) -> dict:
    """§6.1: dr = r − (c + dc) tan τ; with the LS criterion Σ dr² = min, the library's dc is the
    stationary point of the sympy sum (checked on synthetic goniometer data)."""
    r, c, dc, tau = _S["r"], _S["c"], _S["dc"], _S["tau"]
    printed = _parse(inputs["printed"])
    derived = r - (c + dc) * sp.tan(tau)            # measured radius minus the ideal radius of c + dc
    rng = np.random.default_rng(1)
    taus = np.radians(np.linspace(0.0, 40.0, 9))
    rs = 153.02 * np.tan(taus) + rng.normal(0, 0.002, taus.size)
    g = planning.goniometer_distortion(rs, taus, 153.0, "lsq")
    total = sum(printed.subs({r: float(ri), tau: float(ti), c: 153.0}) ** 2 for ri, ti in zip(rs, taus))
    slope = sp.diff(total, dc).subs(dc, g.dc)
    return _ok(_zero(printed - derived) and abs(float(slope)) < 1e-9)


def awar_formula(inputs: dict) -> dict:
    """§6.3.2: AWAR = Σ A_i R_i / Σ A_i; sympy: the printed expression on 3 parts equals the library's."""
    A = sp.symbols("A_1:4", positive=True)
    R = sp.symbols("R_1:4", positive=True)
    printed = sum(a * r for a, r in zip(A, R)) / sum(A)
    rng = np.random.default_rng(2)
    av, rv = rng.uniform(1, 5, 3), rng.uniform(30, 100, 3)
    val = float(printed.subs({**dict(zip(A, av)), **dict(zip(R, rv))}))
    # equal weights: the plain mean; one part: its own resolution
    plain = sp.simplify(printed.subs({A[1]: A[0], A[2]: A[0]}) - sum(R) / 3) == 0
    return _ok(plain and abs(val - planning.awar(av, rv)) < 1e-12)


# --- §8 digital image (ch05_hanzl.toml) ---------------------------------------------------------------------
def quantisation(inputs: dict) -> dict:
    """§8.1: 256 levels ↔ 8 bits."""
    return {"levels": 2 ** int(inputs["bits"])}


def correlation_formula(inputs: dict) -> dict:
    """§8.2: ḡ(i, j) = ΣΣ g(i + k, j + l)·w(m + 1 + k, n + 1 + l) at (2, 2) of a 3×3 image equals the
    printed z = am + bn + … + iu (correlation: no kernel flip)."""
    G = sp.Matrix(3, 3, sp.symbols("a b c d e f g h i"))
    W = sp.Matrix(3, 3, sp.symbols("m n o p q r s t u"))
    m = n = 1
    i = j = 2
    gbar = sum(G[i + k - 1, j + l_ - 1] * W[m + k, n + l_] for k in range(-m, m + 1) for l_ in range(-n, n + 1))
    printed = sp.parse_expr(inputs["printed"], local_dict={str(s_): s_ for s_ in list(G) + list(W)})
    return _ok(sp.expand(gbar - printed) == 0)


def table_8_1(inputs: dict) -> dict:
    """Tab. 8.1: second differences (positions 2…10) and g − Δg″, contrast before and after."""
    g = np.array(inputs["g"], float)
    d2, e = ft.second_difference_1d(g)
    out = {f"d2_{k + 1}": float(d2[k]) for k in range(1, g.size)}
    out.update({f"enh_{k + 1}": float(e[k]) for k in range(1, g.size)})
    out["contrast_before"] = float(g.max() - g.min())
    out["contrast_after"] = float(e.max() - e.min())
    return out


def sharpen_formula(inputs: dict) -> dict:
    """§8.2.1: identity − Laplace = the printed sharpening kernel; the Laplace kernel is the sum of
    the second differences along x and y (Tab. 8.1's Δg″ in 2-D)."""
    printed = sp.Matrix(inputs["printed"])
    identity = sp.zeros(3, 3)
    identity[1, 1] = 1
    dxx = sp.Matrix([[0, 0, 0], [1, -2, 1], [0, 0, 0]])
    laplace = dxx + dxx.T
    return _ok(laplace == sp.Matrix(ft.HANZL_KERNELS["laplace"].astype(int).tolist())
               and printed == identity - laplace)


def kernel_factors(inputs: dict) -> dict:
    """§8.2 note: the factor in front of a kernel is 1/(sum of its coefficients), or 1 for sum 0."""
    out = {}
    for name, raw in inputs["kernels"].items():
        total = float(np.sum(raw))
        out[name] = total if abs(total) > 1e-12 else 1.0
    return out


def _matrix(inputs):
    return np.array(inputs["image"], float)


def filter_example(inputs: dict) -> dict:
    """E5–E7: a kernel of :data:`photolib.features.HANZL_KERNELS` by correlation with the stated border."""
    g = ft.filter_image(_matrix(inputs), inputs["kernel"], border=inputs["border"], cval=inputs.get("cval", 0.0),
                        rounding=inputs.get("rounding", "none"))
    return _rows(g)


def median_example(inputs: dict) -> dict:
    """E8: 3×3 median."""
    return _rows(ft.median_filter(_matrix(inputs), 3, border=inputs["border"]))


def ncc_formula(inputs: dict) -> dict:
    """§8.3: r = Σ(g_r − ḡ_r)(g_s − ḡ_s)/√(Σ(g_r − ḡ_r)² Σ(g_s − ḡ_s)²) against the printed denominator,
    on symbolic windows of 3 pixels (means removed)."""
    u = sp.symbols("u1:4", real=True)
    w = sp.symbols("w1:4", real=True)
    mu, mw = sum(u) / 3, sum(w) / 3
    du, dw = [x - mu for x in u], [x - mw for x in w]
    num = sum(a * b for a, b in zip(du, dw))
    derived = num / sp.sqrt(sum(a ** 2 for a in du) * sum(b ** 2 for b in dw))
    if inputs["form"] == "printed":                  # one Σ over the product of squares under the root
        printed = num / sp.sqrt(sum(a ** 2 * b ** 2 for a, b in zip(du, dw)))
    else:
        printed = derived
    pt = {x: sp.Rational(k * k + 1, 3) for k, x in enumerate(u + w)}
    same = abs(sp.N((printed - derived).subs(pt), 30)) < 1e-20
    # the library's coefficient equals the derived one on the same numbers
    lib = matching.correlation_coefficient(np.array([float(pt[x]) for x in u]), np.array([float(pt[x]) for x in w]))
    return _ok(same and abs(lib - float(derived.subs(pt))) < 1e-12)


def ls_shift_formula(inputs: dict) -> dict:
    """§8.3: v = a₁dx + a₂dy + g_r(x, y) − g_s(x, y) — the first-order expansion of
    g_r(x + dx, y + dy) − g_s(x, y) (a₁, a₂ = ∂g/∂x, ∂g/∂y)."""
    x, y, dx, dy = _S["x"], _S["y"], _S["dx"], _S["dy"]
    g = sp.Function("g_r")
    gs = sp.Function("g_s")(x, y)
    eps = sp.Symbol("eps")
    full = g(x + eps * dx, y + eps * dy) - gs
    lin = sp.series(full, eps, 0, 2).removeO().subs(eps, 1).doit()
    a1, a2 = sp.Derivative(g(x, y), x), sp.Derivative(g(x, y), y)
    printed = _parse(inputs["printed"], {"a1": a1, "a2": a2, "g_r": g(x, y), "g_s": gs})
    diff = sp.simplify((lin - printed).doit())
    return _ok(diff == 0)


def peak_formula(inputs: dict) -> dict:
    """§8.3: ∂r/∂x = 0 or ∂r/∂y = 0 of r = a₀ + a₁x + a₂y + a₃x² + a₄y² + a₅xy, against the printed equation;
    the library's :func:`photolib.matching.quadratic_peak` solves the derived pair."""
    x, y = _S["x"], _S["y"]
    a = [_S[f"a{k}"] for k in range(6)]
    r = a[0] + a[1] * x + a[2] * y + a[3] * x ** 2 + a[4] * y ** 2 + a[5] * x * y
    derived = sp.diff(r, _S[inputs["variable"]])
    printed = _parse(inputs["printed"], {"x_MAX": x, "y_MAX": y})
    same = _zero(printed - derived)
    # library: exact quadratic with a₃ ≠ a₄ → its maximum solves the derived equations
    X, Y = np.meshgrid([-1.0, 0.0, 1.0], [-1.0, 0.0, 1.0])
    coef = [0.9, 0.03, -0.02, -0.10, -0.04, 0.01]
    surf = sum(cf * m for cf, m in zip(coef, [1, X, Y, X * X, Y * Y, X * Y]))
    peak, _ = matching.quadratic_peak(surf)
    sub = dict(zip(a, coef))
    sub.update({x: peak[0], y: peak[1]})
    lib_ok = abs(float(derived.subs(sub))) < 1e-10
    return _ok(same and lib_ok)


def peak_as_printed(inputs: dict) -> dict:
    """The maximum from the printed equations vs the corrected ones for a quadratic with a₃ ≠ a₄."""
    a1, a2, a3, a4, a5 = 0.03, -0.02, -0.10, -0.04, 0.01
    right = np.linalg.solve([[2 * a3, a5], [a5, 2 * a4]], [-a1, -a2])
    printed = np.linalg.solve([[2 * a3, a5], [a4, 2 * a5]], [-a1, -a2])
    return {"x_correct": float(right[0]), "y_correct": float(right[1]),
            "x_printed": float(printed[0]), "y_printed": float(printed[1])}


def normal_matrix_formula(inputs: dict) -> dict:
    """§8.4: N = AᵀA of v = g_x dx + g_y dy − l over a window (3 symbolic pixels) against the printed sums."""
    gx = sp.symbols("gx1:4", real=True)
    gy = sp.symbols("gy1:4", real=True)
    A = sp.Matrix([[a, b] for a, b in zip(gx, gy)])
    sxx, sxy, syy = (sum(a * a for a in gx), sum(a * b for a, b in zip(gx, gy)), sum(b * b for b in gy))
    printed = sp.Matrix(2, 2, [_parse(e, {"Sxx": sxx, "Sxy": sxy, "Syy": syy}) for e in inputs["printed"]])
    return _ok((A.T * A - printed).expand() == sp.zeros(2, 2))


def _n_with_eigen():
    l1, l2 = sp.Symbol("n1", positive=True), sp.Symbol("n2", positive=True)
    rot = sp.Matrix([[sp.Rational(3, 5), -sp.Rational(4, 5)], [sp.Rational(4, 5), sp.Rational(3, 5)]])
    return rot * sp.diag(l1, l2) * rot.T


def foerstner_size_formula(inputs: dict) -> dict:
    """§8.4: the size of the error ellipse, tr Q = tr N/det N, and its expression in λ₁, λ₂ (eigenvalues
    of Q = N⁻¹), against the printed chain ``printed`` (one member, in l1, l2 or Sxx, Sxy, Syy)."""
    N = _n_with_eigen()
    Q = N.inv()
    lq = sorted(Q.eigenvals().keys(), key=str)
    derived = Q.trace()
    printed = _parse(inputs["printed"]).subs({_S["l1"]: lq[0], _S["l2"]: lq[1], _S["Sxx"]: N[0, 0],
                                              _S["Sxy"]: N[0, 1], _S["Syy"]: N[1, 1]}, simultaneous=True)
    return _ok(_zero(printed - derived))


def foerstner_roundness_formula(inputs: dict) -> dict:
    """§8.4: q = 1 − ((λ₁ − λ₂)/(λ₁ + λ₂))² = 4 det N / tr² N (eigenvalues of N or of Q alike)."""
    N = _n_with_eigen()
    derived = 4 * N.det() / N.trace() ** 2
    ok = True
    for M in (N, N.inv()):
        lam = list(M.eigenvals().keys())
        printed = _parse(inputs["printed"]).subs({_S["l1"]: lam[0], _S["l2"]: lam[1]}, simultaneous=True)
        ok = ok and _zero(printed - derived)
    return _ok(ok)


def pyramid_sizes(inputs: dict) -> dict:
    """§8.5: a 4096 × 4096 image reduced by 2 per level (photolib.epipolar.pyramid, 2×2 mean)."""
    n = int(inputs["size"])
    levels = pyramid(np.zeros((n, n)), int(inputs["levels"]))
    return {"level_1": float(levels[1].shape[0]), "ratio": levels[0].shape[0] / levels[1].shape[0]}


def bilinear_formula(inputs: dict) -> dict:
    """§9: a₀ … a₃ of Z = a₀ + a₁X + a₂Y + a₃XY on the cell P1(0,0), P2(d,0), P3(0,d), P4(d,d) — sympy
    solves the four printed conditions; the grey-value form is the same with g for Z. Also checks
    that :func:`photolib.digital.bilinear` equals the polynomial inside a pixel cell."""
    d, X, Y = _S["d"], _S["X"], _S["Y"]
    Z = [_S[f"Z{k}"] for k in range(1, 5)]
    a = sp.symbols("b0:4")
    model = lambda x_, y_: a[0] + a[1] * x_ + a[2] * y_ + a[3] * x_ * y_    # noqa: E731
    sol = sp.solve([model(0, 0) - Z[0], model(d, 0) - Z[1], model(0, d) - Z[2], model(d, d) - Z[3]], a)
    printed = [_parse(e) for e in inputs["printed"]]
    same = all(_zero(p - sol[ak]) for p, ak in zip(printed, a))
    img = np.array([[3.0, 7.0], [2.0, 11.0]])
    sub = {Z[0]: 3.0, Z[1]: 7.0, Z[2]: 2.0, Z[3]: 11.0, d: 1.0}
    lib = all(abs(digital.bilinear(img, 0.5 + xv, 0.5 + yv)
                  - float(sum(sol[ak].subs(sub) * m for ak, m in zip(a, [1, xv, yv, xv * yv])))) < 1e-12
              for xv, yv in [(0.25, 0.5), (0.9, 0.1)])
    return _ok(same and lib)


def normalised_formula(inputs: dict) -> dict:
    """§10.1: from X₀ + λRx = X₀ + λ_N R_N x_N, x_N = (λ/λ_N) R_N⁻¹ R x. sympy with general 3×3 matrices R
    and a non-trivial invertible R_N (so the solution is unique): the printed x_N makes the two rays equal."""
    R = sp.Matrix(3, 3, sp.symbols("r1:10", real=True))
    a, b = sp.symbols("a_N b_N", real=True)             # an invertible R_N (rotation·scale about z, tilt)
    RN = sp.Matrix([[a, -b, 0], [b, a, 0], [0, 0, 1]]) * sp.Matrix([[1, 0, 0], [0, 1, a], [0, 0, 1]])
    lam, lamN, c = sp.symbols("lambda lambda_N c", positive=True)
    xv = sp.Matrix([_S["x"], _S["y"], -c])
    printed = (lam / lamN) * RN.inv() * R * xv if inputs["form"] == "printed" else RN.T * R * xv
    residual = lamN * RN * printed - lam * R * xv
    return _ok(all(sp.cancel(sp.together(e)) == 0 for e in residual))
