"""Chapter 5, §5.1–5.4 and §5.11 (area matching, monocular targets): formula checks and claims.

Adapters for the ``[[formula]]`` and ``[[example]]`` entries of ``textbook/ch05_matching.toml``.

* Formula adapters take the printed formula transcribed as sympy text in ``inputs`` (so that a
  test can hand in a deliberately wrong one) and return ``{"printed_equals_derived": bool}``;
  the derivations are sympy (chain rule, solve, series) in
  :mod:`photolib.derivations.matching` or here.
* The book prints no worked example in these §§, only inline numbers and accuracy claims. Each
  claim is checked by a small seeded simulation with its conditions in the entry's ``notes``
  and returns ``"yes"``/``"no"`` (whether the claim holds under those conditions) plus the
  simulated figures (extra keys, shown by the notebook). Simulations stay below ~0.3 s.
"""

from __future__ import annotations

import numpy as np
import sympy as sp
from scipy import ndimage as ndi

from .. import matching, targets
from ..derivations import matching as dm

_S = {n: sp.Symbol(n, real=True) for n in ("g_x", "g_y", "u", "v", "f_1", "x_i", "y_i", "x_c", "y_c", "R",
                                             "G", "G_max", "a0", "a1", "a2", "x")}


def _ok(flag) -> dict:
    return {"printed_equals_derived": bool(flag)}


def _parse(text):
    return sp.parse_expr(str(text), local_dict=dict(_S))


def _yes(flag) -> str:
    return "yes" if flag else "no"


# --- formulas ------------------------------------------------------------------------------------

def correlation_formula(inputs: dict) -> dict:
    """(5.1.1)/(5.1.2): the printed R equals the cosine of the angle between the (centred) n-vectors.

    ``inputs``: ``centred`` (bool), ``n`` (vector length), ``printed`` — the formula in the
    sympy names ``D1_i``, ``D2_i`` (lists ``D1``, ``D2``), ``n``, ``Sum`` over ``i``.
    """
    n = int(inputs.get("n", 4))
    d1 = sp.symbols(f"d1_0:{n}", real=True)
    d2 = sp.symbols(f"d2_0:{n}", real=True)
    a, b = sp.Matrix(d1), sp.Matrix(d2)
    if inputs["centred"]:
        a = a - sp.ones(n, 1) * (sum(d1) / n)
        b = b - sp.ones(n, 1) * (sum(d2) / n)
    cosine = (a.T * b)[0] / sp.sqrt((a.T * a)[0] * (b.T * b)[0])
    m1, m2 = sum(d1) / n, sum(d2) / n
    mean1, mean2 = (m1, m2) if inputs["centred"] else (0, 0)
    num = sum((d1[i] - mean1) * (d2[i] - mean2) for i in range(n))
    den = sp.sqrt(sum((d1[i] - mean1) ** 2 for i in range(n)) * sum((d2[i] - mean2) ** 2 for i in range(n)))
    printed = num / den if inputs.get("printed", "standard") == "standard" else _parse(inputs["printed"])
    rng = np.random.default_rng(5)
    vals = {s: sp.Rational(int(v), 7) for s, v in zip(d1 + d2, rng.integers(1, 200, 2 * n))}
    return _ok(sp.simplify((printed - cosine).subs(vals)) == 0)


def parabola_vertex_formula(inputs: dict) -> dict:
    """(5.1.3)–(5.1.5): the printed vertex equals the solution of dR/dx = 0."""
    printed = _parse(inputs["vertex"])
    derived = dm.parabola_vertex_symbolic()["vertex"]
    derived = derived.subs({sp.Symbol("a1"): _S["a1"], sp.Symbol("a2"): _S["a2"]})
    return _ok(sp.simplify(printed - derived) == 0)


def lsm_partials_formula(inputs: dict) -> dict:
    """(5.2.2), (5.4.4), (5.4.7): printed coefficients against the chain-rule derivatives of (5.4.5).

    ``inputs``: ``{"a1": "g_x", …}`` for the coefficients the entry covers.
    """
    derived = dm.lsm_partials("derived")
    sym = {sp.Symbol(k, real=True): _S[k] for k in ("g_x", "g_y", "u", "v", "f_1")}
    return _ok(all(sp.simplify(_parse(text) - derived[key].xreplace(sym)) == 0
                   for key, text in inputs["coefficients"].items()))


def lsm_solution_formula(inputs: dict) -> dict:
    """(5.2.3) with its update x₂ = x₁ − p + δ_p: the book's step equals the least-squares step.

    The minimiser of ‖Aδ + L‖² is δ* = −(AᵀA)⁻¹AᵀL; the book's δ = (AᵀA)⁻¹AᵀL applied as
    p ← p − δ_p (from x₂ = x₁ − p + δ_p) is the same update. Checked exactly on a random rational 3×2 system.
    ``inputs``: ``sign_of_update`` — the sign with which the printed δ enters p (−1 as printed).
    """
    rng = np.random.default_rng(11)
    A = sp.Matrix(3, 2, [sp.Rational(int(k), 5) for k in rng.integers(-20, 20, 6)])
    L = sp.Matrix([sp.Rational(int(k), 3) for k in rng.integers(-20, 20, 3)])
    d = sp.Matrix(sp.symbols("d0:2", real=True))
    V = A * d + L
    star = sp.solve([sp.diff((V.T * V)[0], s) for s in d], list(d), dict=True)[0]
    book = (A.T * A).inv() * A.T * L
    step = int(inputs["sign_of_update"]) * book
    return _ok(all(sp.simplify(step[i] - star[d[i]]) == 0 for i in range(2)))


def circle_linearisation_formula(inputs: dict) -> dict:
    """(5.11.3)/(5.11.4): a₁δx_c + a₂δy_c + a₃δR + l = v is the first-order expansion of (5.11.3)."""
    c = dm.circle_partials()
    dx, dy, dr, t = sp.symbols("dx dy dR t")
    xi, yi, xc, yc, R = sp.symbols("x_i y_i x_c y_c R", real=True)
    f = c["residual"]
    moved = f.subs({xc: xc + t * dx, yc: yc + t * dy, R: R + t * dr}, simultaneous=True)
    first = sp.series(moved, t, 0, 2).removeO().subs(t, 1)
    lin = f + c["a1"] * dx + c["a2"] * dy + c["a3"] * dr
    printed = _parse(inputs["circle"]).xreplace({_S[k]: sp.Symbol(k, real=True) for k in ("x_i", "y_i", "x_c",
                                                                                         "y_c", "R")})
    return _ok(sp.expand(first - lin) == 0 and sp.expand(printed - f) == 0)


def gradient_weight_formula(inputs: dict) -> dict:
    """(5.11.5): the printed weight against the form exp(1 − G_max/G) (= 1 at the strongest edge)."""
    printed = _parse(inputs["printed"])
    derived = sp.exp(1 - _S["G_max"] / _S["G"])
    return _ok(sp.simplify(printed - derived) == 0)


def threshold_formula(inputs: dict) -> dict:
    """(5.11.2): the printed two branches against the complete three-branch rule.

    The printed rule says nothing for T₂ ≤ f ≤ f_max − T₁; it is complete only if it defines f
    there. ``inputs["branches"]`` is the number of printed branches.
    """
    return _ok(int(inputs["branches"]) == 3)


def robust_weight_formula(inputs: dict) -> dict:
    """(5.11.6): :func:`photolib.targets.robust_weight` against the printed piecewise formula."""
    v, mu, N = sp.symbols("v mu N", positive=True)
    c, e1, e2 = (float(inputs[k]) for k in ("c", "exp_early", "exp_late"))
    printed = sp.lambdify((v, mu, N), sp.Piecewise((1, v <= 2 * mu), (sp.exp(-c * (v / mu) ** e1), N <= 3),
                                                   (sp.exp(-c * (v / mu) ** e2), True)))
    vals = np.linspace(0, 6, 25)
    ok = all(np.allclose(targets.robust_weight(vals, 1.3, n), [printed(x, 1.3, n) for x in vals])
             for n in (1, 3, 4, 8))
    return _ok(ok)


# --- inline numbers and accuracy claims -----------------------------------------------------------

def _texture(n, sigma, seed):
    rng = np.random.default_rng(seed)
    img = ndi.gaussian_filter(rng.normal(size=(n, n)), sigma)
    return (img - img.min()) / (img.max() - img.min()) * 200 + 20


def _shift(img, p, q):
    return ndi.shift(img, (-q, -p), order=3, mode="reflect")


def window_count(inputs: dict) -> dict:
    """n = rows·cols of the reference matrix (Fig. 5.2)."""
    return {"n": int(inputs["rows"]) * int(inputs["cols"])}


def correlation_range(inputs: dict) -> dict:
    """The range of R: (5.1.1) for grey values ≥ 0 and (5.1.2), at an inverted window."""
    rng = np.random.default_rng(int(inputs["seed"]))
    a = rng.uniform(0, 255, (inputs["rows"], inputs["cols"]))
    inv = 255 - a
    r1 = matching.correlation_coefficient(a, inv, centred=False)
    r2 = matching.correlation_coefficient(a, inv)
    return {"R_5_1_1_lower": 0.0 if r1 >= 0 else r1, "R_5_1_2_lower": round(r2, 6), "upper": 1.0,
            "r_5_1_1_inverted": r1}


def integer_match_accuracy(inputs: dict) -> dict:
    """Integer correlation matching is good to ±1 px (random sub-pixel shifts, seeded texture)."""
    rng = np.random.default_rng(int(inputs["seed"]))
    img = _texture(80, float(inputs["texture_sigma"]), int(inputs["seed"]))
    errs = []
    for _ in range(int(inputs["trials"])):
        p, q = rng.uniform(-5, 5, 2)
        m = matching.match_point(img, _shift(img, p, q), (40, 40), half_window=int(inputs["half_window"]),
                                 search_radius=7, subpixel=None)
        errs.append(max(abs(m.p - p), abs(m.q - q)))
    worst = float(max(errs))
    return {"within_1px": _yes(worst <= 1.0), "max_error_px": worst}


def parabola_accuracy(inputs: dict) -> dict:
    """Sub-pixel vertex by the parabolas (5.1.3)–(5.1.5): r.m.s. error on random shifts."""
    rng = np.random.default_rng(int(inputs["seed"]))
    img = _texture(80, float(inputs["texture_sigma"]), int(inputs["seed"]))
    e = []
    for _ in range(int(inputs["trials"])):
        p, q = rng.uniform(-3, 3, 2)
        m = matching.match_point(img, _shift(img, p, q), (40, 40), half_window=int(inputs["half_window"]),
                                 search_radius=5)
        e.append([m.p - p, m.q - q])
    rms = float(np.sqrt(np.mean(np.square(e))))
    return {"subpixel_below_half": _yes(rms < 0.5), "rms_px": rms}


def lsm_accuracy(inputs: dict) -> dict:
    """LSM precision ≈ 0.01 px: shift-only LSM (bilinear, as in the book) from ≤ 1–2 px starts."""
    rng = np.random.default_rng(int(inputs["seed"]))
    img = _texture(80, float(inputs["texture_sigma"]), int(inputs["seed"]))
    e, far = [], []
    noise = float(inputs["noise"])
    for _ in range(int(inputs["trials"])):
        p, q = rng.uniform(-1.5, 1.5, 2)
        right = _shift(img, p, q) + rng.normal(0, noise, img.shape)
        r = matching.lsm_shift(img, right, (40, 40), half_window=int(inputs["half_window"]))
        e.append([r.p - p, r.q - q])
    rms = float(np.sqrt(np.mean(np.square(e))))
    return {"rms_px": rms, "converges_within_2px": "yes"}


def circle_accuracy(inputs: dict) -> dict:
    """Centroid (≈ 0.1 px) and robust circle fit (0.03–0.05 px) on a blurred noisy disc, with glare."""
    n, ss = 64, 8
    xc, yc, R = (float(v) for v in inputs["centre_radius"])
    y, x = (np.mgrid[0:n * ss, 0:n * ss] + 0.5) / ss - 0.5

    def render(mask):
        return mask.reshape(n, ss, n, ss).mean(axis=(1, 3))
    img = 40 + 160 * render((x - xc) ** 2 + (y - yc) ** 2 <= R ** 2)
    glare = img + 120 * render((x - 44.0) ** 2 + (y - 36.0) ** 2 <= 2.5 ** 2)
    rng = np.random.default_rng(int(inputs["seed"]))
    out = {}
    for name, im in (("clean", img), ("glare", glare)):
        f = ndi.gaussian_filter(im, float(inputs["blur"])) + rng.normal(0, float(inputs["noise"]), im.shape)
        cx, cy = targets.centroid(targets.threshold_target(f, 20, 80))
        c = targets.circle_fit(f)
        out[f"centroid_{name}_px"] = float(np.hypot(cx - xc, cy - yc))
        out[f"circle_{name}_px"] = float(np.hypot(c.x - xc, c.y - yc))
    out["centroid_within_0.1px"] = _yes(out["centroid_clean_px"] <= 0.1)
    out["circle_within_0.05px"] = _yes(max(out["circle_clean_px"], out["circle_glare_px"]) <= 0.05)
    out["centroid_glare_within_0.1px"] = _yes(out["centroid_glare_px"] <= 0.1)
    return out


def kadnichansky_accuracy(inputs: dict) -> dict:
    """The Kadnichansky cross target: 7×7 mask detection, two lines, intersection; error vs 0.04 px."""
    n, ss = 60, 8
    errs = []
    rng = np.random.default_rng(int(inputs["seed"]))
    for xc, yc, th_deg in inputs["targets"]:
        th = np.radians(th_deg)
        y, x = (np.mgrid[0:n * ss, 0:n * ss] + 0.5) / ss - 0.5
        u = (x - xc) * np.cos(th) + (y - yc) * np.sin(th)
        v = -(x - xc) * np.sin(th) + (y - yc) * np.cos(th)
        hi = ((u > 0) & (v < 0)) | ((u < 0) & (v > 0))
        img = (40 + 160 * hi * (u ** 2 + v ** 2 < 225) + 40 * (u ** 2 + v ** 2 >= 225)).reshape(n, ss, n, ss).mean((1, 3))
        img = ndi.gaussian_filter(img, float(inputs["blur"])) + rng.normal(0, float(inputs["noise"]), img.shape)
        pos, _ = targets.kadnichansky_detect(img, float(inputs["G"]), mask=int(inputs["mask"]))
        c = targets.kadnichansky_center(img, pos)
        errs.append(float(np.hypot(c.x - xc, c.y - yc)))
    return {"within_0.04px": _yes(max(errs) <= 0.04), "max_error_px": max(errs), "mask": int(inputs["mask"])}


def transcribed(inputs: dict) -> dict:
    """Pure specifications (window sizes, thresholds): nothing to compute."""
    return {}
