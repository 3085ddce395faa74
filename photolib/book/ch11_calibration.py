"""Chapter 11, §11.1–11.3 (camera calibration): formula checks and the book's numbers.

Adapters for the ``[[formula]]`` and ``[[example]]`` entries of ``textbook/ch11_calibration.toml``.
Formula adapters take the printed formula (sympy text) in ``inputs`` and return
``{"printed_equals_derived": bool}``; the derivations are plain sympy and the sympy models of
:mod:`photolib.derivations` (never the numeric code of :mod:`photolib.calibration`). Example
adapters recompute the book's numbers with :mod:`photolib.calibration`.
"""

from __future__ import annotations

from functools import lru_cache

import sympy as sp

from ..calibration import certificate_to_mm, target_field_tolerances
from ..derivations.bundle import self_calibration_model
from ..derivations.distortion import brown_correction_terms
from ..derivations.rotation import rotation_matrix_symbolic
from ..derivations.symbols import IO_SYMBOLS, X, Y, Z, x, x0, y, y0

__all__ = ["distortion_formula", "condition_formula", "chessboard_formula", "tolerance_formula",
           "correction_vectors_formula", "normal_equations_formula", "solution_formula",
           "precision_formula", "unit_weight_formula", "field_example", "certificate_example", "table_check",
           "linearisation_formula"]

_SYMS = {s.name: s for s in (x, y, X, Y, Z) + IO_SYMBOLS}


def _ok(flag) -> dict:
    return {"printed_equals_derived": bool(flag)}


def _parse(text, extra=None):
    local = dict(_SYMS)
    local.update({"sqrt": sp.sqrt})
    local.update(extra or {})
    expr = sp.sympify(sp.parse_expr(str(text), local_dict=local))
    known = set().union(*[sp.sympify(v).free_symbols for v in local.values() if isinstance(v, sp.Basic)])
    return expr.xreplace({s: sp.Symbol(s.name, real=True) for s in expr.free_symbols
                          if s.name not in local and s not in known})


def _zero(expr) -> bool:
    """Exact identity test: a non-zero value at one rational point disproves it quickly; else expand."""
    expr = sp.sympify(expr)
    point = {s: sp.Rational(3 + 2 * i, 7 + i) for i, s in enumerate(sorted(expr.free_symbols, key=str))}
    if sp.nsimplify(expr.xreplace(point)) != 0:
        return False
    return sp.expand(expr) == 0


# --------------------------------------------------------------------------- (11.3.1)
def distortion_formula(inputs: dict) -> dict:
    """(11.3.1) and the certificates' form: printed d_x, d_y against Brown's model of (1.2.2).

    ``inputs['dx']``, ``inputs['dy']`` in the symbols x, y, x_0, y_0, k_1…p_2 and ``r``;
    ``inputs['terms']`` lists the coefficients kept (the certificates keep k₁, k₂ only).
    """
    xb, yb = x - x0, y - y0
    r = sp.sqrt(xb ** 2 + yb ** 2)
    dx, dy = brown_correction_terms(xb, yb)
    dropped = {s: 0 for s in IO_SYMBOLS[3:] if s.name not in inputs.get("terms", [s.name for s in IO_SYMBOLS[3:]])}
    printed = [_parse(inputs[k], {"r": r}) for k in ("dx", "dy")]
    return _ok(all(_zero(p - sp.sympify(d).subs(dropped)) for p, d in zip(printed, (dx, dy))))


# --------------------------------------------------------------------------- (11.3.2), (11.3.8)
@lru_cache(maxsize=None)
def _selfcal_residuals():
    return tuple(self_calibration_model("kaw").residuals)


def condition_formula(inputs: dict) -> dict:
    """(11.3.2): the printed condition equations with a_ij = A (κ–α–ω) and d of (11.3.1) reduced.

    Compared with :func:`photolib.derivations.self_calibration_model` (the §3.6 model).
    """
    A = rotation_matrix_symbolic("kaw")
    local = {f"a{i + 1}{j + 1}": A[i, j] for i in range(3) for j in range(3)}
    sym = {s.name: s for s in self_calibration_model("kaw").parameters}
    local.update(sym)
    dx, dy = brown_correction_terms(x - x0, y - y0)
    local.update({"d_x": dx, "d_y": dy})
    printed = [_parse(inputs[k], local) for k in ("Fx", "Fy")]
    return _ok(all(_zero(p - d) for p, d in zip(printed, _selfcal_residuals())))


def chessboard_formula(inputs: dict) -> dict:
    """(11.3.8): (11.3.2) with X_S = Y_S = Z_S = ω = α = κ = 0 and the board point X = X_o + A_i(X', Y', 0)ᵀ.

    The printed equations (in X, Y, Z of the camera frame, d_x, d_y of (11.3.1)) against the
    §3.6 model specialised to the camera at the origin.
    """
    model = self_calibration_model("kaw")
    sym = {s.name: s for s in model.parameters}
    zero = {sym[n]: 0 for n in ("X_S", "Y_S", "Z_S", "omega", "alpha", "kappa")}
    dx, dy = brown_correction_terms(x - x0, y - y0)
    local = dict(sym)
    local.update({"d_x": dx, "d_y": dy})
    printed = [_parse(inputs[k], local) for k in ("Fx", "Fy")]
    return _ok(all(_zero(sp.together(p - sp.sympify(d).subs(zero)))
                   for p, d in zip(printed, _selfcal_residuals())))


# --------------------------------------------------------------------------- test field
def tolerance_formula(inputs: dict) -> dict:
    """m_X = m_Y = 0.1·Z_min/f·Δ: propagate σ_x = p·Δ through X = x·Z/f (the frontal image, §1.4)."""
    p, Zmin, fl, D = sp.symbols("p Z_min f Delta", positive=True)
    xs = sp.Symbol("x", real=True)
    derived = sp.Abs(sp.diff(xs * Zmin / fl, xs)) * p * D
    printed = _parse(inputs["m_XY"], {"Z_min": Zmin, "f": fl, "Delta": D, "p": p})
    return _ok(_zero(printed - derived.subs(p, sp.Rational(inputs["precision_px"]))))


# --------------------------------------------------------------------------- (11.3.3)–(11.3.7)
def correction_vectors_formula(inputs: dict) -> dict:
    """(11.3.3) for k points: V must list v_x1, v_y1, …, v_xk, v_yk (one residual per equation).

    ``inputs['V']``: the printed names (the ellipsis dropped), compared with the residual names of
    the first and last point in (11.3.2) order.
    """
    derived = ["v_x1", "v_y1", "v_xk", "v_yk"]
    return _ok(list(inputs["V"]) == derived)


def _lsq_symbols(m=3, n=2):
    B = sp.Matrix(m, n, lambda i, j: sp.Symbol(f"b{i}{j}", real=True))
    L = sp.Matrix(m, 1, lambda i, j: sp.Symbol(f"l{i}", real=True))
    P = sp.diag(*[sp.Symbol(f"p{i}", positive=True) for i in range(m)])
    d = sp.Matrix(n, 1, lambda i, j: sp.Symbol(f"delta{i}", real=True))
    return B, L, P, d


def normal_equations_formula(inputs: dict) -> dict:
    """(11.3.4): BᵀPBδ + BᵀPL = 0 is ½∇_δ of VᵀPV with V = Bδ + L (11.3.3)."""
    B, L, P, d = _lsq_symbols()
    V = B * d + L
    grad = sp.Matrix([sp.diff((V.T * P * V)[0], di) for di in d]) / 2
    printed = B.T * P * B * d + B.T * P * L if inputs["form"] == "BtPB d + BtPL" else None
    return _ok(printed is not None and all(_zero(e) for e in grad - printed))


def solution_formula(inputs: dict) -> dict:
    """(11.3.5): the solution of Nδ + Lᴺ = 0 against δ = sign·Q·Lᴺ, Q = N⁻¹ (``inputs['sign']`` = ±1)."""
    n11, n12, n22, l1, l2 = sp.symbols("n11 n12 n22 l1 l2", real=True)
    N = sp.Matrix([[n11, n12], [n12, n22]])
    LN = sp.Matrix([l1, l2])
    delta = sp.Matrix(sp.symbols("d1 d2"))
    sol = sp.solve(list(N * delta + LN), list(delta), dict=True)[0]
    derived = sp.Matrix([sol[s] for s in delta])
    printed = int(inputs["sign"]) * N.inv() * LN
    return _ok(all(sp.simplify(e) == 0 for e in derived - printed))


_B_NUM = sp.Matrix([[1, 2], [3, -1], [0, 4], [2, 1]])


def precision_formula(inputs: dict) -> dict:
    """(11.3.6): cov(δ̂) = Q·BᵀP·(μ²P⁻¹)·PB·Q = μ²Q, so m_j = μ√Q_jj (exact, symbolic weights)."""
    m, n = _B_NUM.shape
    P = sp.diag(*[sp.Symbol(f"p{i}", positive=True) for i in range(m)])
    mu = sp.Symbol("mu", positive=True)
    Q = (_B_NUM.T * P * _B_NUM).inv()
    cov = Q * _B_NUM.T * P * (mu ** 2 * P.inv()) * P * _B_NUM * Q
    printed = [_parse(inputs["m_j"], {"mu": mu, "Q_jj": Q[j, j]}) for j in range(n)]
    return _ok(all(sp.cancel(printed[j] ** 2 - cov[j, j]) == 0 for j in range(n)))  # both ≥ 0


def unit_weight_formula(inputs: dict) -> dict:
    """(11.3.7): E[VᵀPV] = μ²·tr(I − B·Q·BᵀP) = μ²(m − n), so μ̂² = VᵀPV/(m − n) is unbiased."""
    m, n = _B_NUM.shape
    P = sp.diag(*[sp.Symbol(f"p{i}", positive=True) for i in range(m)])
    Q = (_B_NUM.T * P * _B_NUM).inv()
    dof = sp.simplify((sp.eye(m) - _B_NUM * Q * _B_NUM.T * P).trace())
    printed = _parse(inputs["denominator"], {"m": m, "n": n})
    return _ok(sp.simplify(dof - printed) == 0)


# --------------------------------------------------------------------------- examples
def field_example(inputs: dict) -> dict:
    """Worked example of §11.3: m_X = m_Y and m_Z by :func:`photolib.calibration.target_field_tolerances`."""
    mxy, mz = target_field_tolerances(inputs["f_mm"], inputs["pixel_mm"], inputs["z_min_m"] * 1000.0,
                                      inputs["depth_m"] * 1000.0, inputs["precision_px"])
    return {"m_XY": mxy, "m_Z": mz}


def certificate_example(inputs: dict) -> dict:
    """Fig. 11.20 (pixels) → Fig. 11.21 (mm) by :func:`photolib.calibration.certificate_to_mm`."""
    c = certificate_to_mm(dict(inputs["pixels"]), inputs["pixel_mm"])
    scale = inputs.get("scale", {})          # mantissas in the fixed powers of ten of the print
    return {k: v / 10.0 ** scale.get(k, 0) for k, v in c.items()}


def table_check(inputs: dict) -> dict:
    """Tables 11.1/11.2: sensor (or scan) sides = resolution × pixel size, and the pixel count in Mp.

    ``inputs['resolution']``: ["W×H", …] as printed; ``inputs['pixel_um']``: pixel sizes in µm.
    """
    out = {}
    for i, (res, pix) in enumerate(zip(inputs["resolution"], inputs["pixel_um"])):
        w, h = (int(v) for v in str(res).replace("x", "×").split("×"))
        out[f"width[{i}]"] = w * float(pix) / 1000.0
        out[f"height[{i}]"] = h * float(pix) / 1000.0
        out[f"megapixels[{i}]"] = w * h / 1e6
    return out


def linearisation_formula(inputs: dict) -> dict:
    """(11.3.3): V = F(p⁰ + δ) to first order is Bδ + L with B = ∂F/∂p at p⁰ and L = F(p⁰).

    Checked on the camera-at-origin condition F = x₀ − f·X/Z − x − d_x (f, x₀, k₁, Z unknown).
    """
    t = sp.Symbol("t", real=True)
    dx, _ = brown_correction_terms(x - x0, y - y0)
    F = x0 - _SYMS["f"] * X / Z - x - sp.sympify(dx).subs({s: 0 for s in IO_SYMBOLS[4:]})
    params = [_SYMS["f"], x0, IO_SYMBOLS[3], Z]
    deltas = sp.symbols("d_f d_x0 d_k1 d_Z", real=True)
    moved = F.subs({p: p + t * d for p, d in zip(params, deltas)}, simultaneous=True)
    first_order = sp.diff(moved, t).subs(t, 0)
    B = sp.Matrix([[sp.diff(F, p) for p in params]])
    printed = (B * sp.Matrix(deltas))[0] if inputs["form"] == "B delta + L" else 0
    return _ok(_zero(first_order - printed) and _zero(moved.subs(t, 0) - F))
