"""Chapter 11, §11.1–11.3 (camera calibration): formula checks and the book's numbers.

Adapters for the ``[[formula]]`` and ``[[example]]`` entries of ``textbook/ch11_calibration.toml``.
Formula adapters take the printed formula (sympy text) in ``inputs`` and return
``{"printed_equals_derived": bool}``; the derivations are plain sympy and the sympy models of
:mod:`photolib.derivations` (never the numeric code of :mod:`photolib.calibration`). Example
adapters recompute the book's numbers with :mod:`photolib.calibration`.

Table 11.3 (a Hasselblad with f = 100 mm calibrated classically and with a common projection
centre) prints no data and stays not-reproducible; :func:`long_focus_trend` shows its *trend* on a
synthetic long-focus setup of our own (:func:`long_focus_run`), for the notebook.
"""

from __future__ import annotations

from functools import lru_cache

import sympy as sp

import numpy as np

from ..calibration import certificate_to_mm, self_calibration, target_field_tolerances
from ..camera import ExteriorOrientation, InteriorOrientation
from ..image_pair import intersect_rays
from ..single_image import project
from ..derivations.bundle import self_calibration_model
from ..derivations.distortion import brown_correction_terms
from ..derivations.rotation import rotation_matrix_symbolic
from ..derivations.symbols import IO_SYMBOLS, X, Y, Z, x, x0, y, y0

__all__ = ["distortion_formula", "condition_formula", "chessboard_formula", "tolerance_formula",
           "correction_vectors_formula", "normal_equations_formula", "solution_formula",
           "precision_formula", "unit_weight_formula", "field_example", "certificate_example", "table_check",
           "linearisation_formula", "LONG_FOCUS_CAMERA", "long_focus_field", "long_focus_run", "long_focus_trend"]

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


# --------------------------------------------------------------------------- Table 11.3: the trend
LONG_FOCUS_CAMERA = InteriorOrientation(100.0, 0.08, -0.05, k1=-1.5e-5)
"""The simulated long-focus camera: f = 100 mm (as the book's Hasselblad), principal point off
the centre, radial distortion k₁; frame 49 × 37 mm (f ≈ 2 × the format: "long-focus" by §11.3)."""
_HALF_FRAME = (24.5, 18.5)      # mm


def long_focus_field() -> np.ndarray:
    """A test field for wide-angle cameras, seen by the long-focus camera from 10 m (m, camera frame).

    A wall 10 × 7 m at Z = −10 m (targets every 0.5 m) and one layer of targets 0.5 m in front
    of it (every 1 m): shallow for a 100 mm lens, whose single image covers only ≈ 4.9 × 3.7 m.
    """
    g = np.mgrid[-5:5.01:0.5, -3.5:3.51:0.5].reshape(2, -1).T
    front = np.mgrid[-4.75:4.8:1.0, -3.25:3.3:1.0].reshape(2, -1).T
    return np.vstack([np.column_stack([g, np.full(len(g), -10.0)]),
                      np.column_stack([front, np.full(len(front), -9.5)])])


def _in_frame(XYZ, eo, io):
    xy = project(XYZ, eo, InteriorOrientation(io.f, io.x0, io.y0), distortion=False)   # no fold-over outside
    return (np.abs(xy[:, 0]) < _HALF_FRAME[0] - 1) & (np.abs(xy[:, 1]) < _HALF_FRAME[1] - 1)


def long_focus_run(seed: int, *, sigma: float = 0.002, pan: float = 0.11, tilt: float = 0.085,
                   base: float = 2.0, calibrate=("f", "x0", "y0", "k1")) -> dict:
    """One seeded run: calibrate classically and with a common centre, then intersect 49 check points.

    Four images of :func:`long_focus_field` are taken from **one** projection centre, the camera
    turned by ±``pan`` and ±``tilt`` (rad) about it (§11.3, Figs 11.30–11.32); image noise
    ``sigma`` (mm). They are calibrated twice by :func:`photolib.calibration.self_calibration`:
    classically (six exterior elements per image) and with the common centre
    (``common_centre=True``: one centre, three angles per image), as the book does with its four
    Hasselblad images. A normal-case stereo pair (base ``base`` m, stations known) then measures
    49 check points 9–11 m away (a 7 × 7 grid with relief); each calibration intersects them
    (:func:`photolib.image_pair.intersect_rays`). X, Y are across the view, Z the depth.

    Returns
    -------
    dict
        ``{"classical": {...}, "common_centre": {...}}``, each with ``rms`` (m_X, m_Y, m_Z in mm
        over the 49 points), ``f_error`` (mm) and ``sigma_f`` (mm, (11.3.6)).
    """
    rng = np.random.default_rng(seed)
    field = long_focus_field()
    centre = np.array([0.05, -0.03, 0.0])
    objects, images, starts = [], [], []
    for w in (-tilt, tilt):
        for a in (-pan, pan):
            eo = ExteriorOrientation(*centre, w, a, rng.normal(0.0, 0.01))
            seen = field[_in_frame(field, eo, LONG_FOCUS_CAMERA)]
            objects.append(seen)
            images.append(project(seen, eo, LONG_FOCUS_CAMERA) + rng.normal(0.0, sigma, (len(seen), 2)))
            starts.append([0.0, 0.0, 0.2, w, a, 0.0])
    g = np.mgrid[-1.5:1.51:0.5, -1.2:1.21:0.4].reshape(2, -1).T
    check = np.column_stack([g, -10.0 + 0.8 * np.sin(1.3 * g[:, 0]) * np.cos(g[:, 1])])
    pair = [ExteriorOrientation(s * base / 2, 0.0, 0.0, 0.0, 0.0, 0.0) for s in (-1, 1)]
    measured = [project(check, e, LONG_FOCUS_CAMERA) + rng.normal(0.0, sigma, (len(check), 2)) for e in pair]
    out = {}
    for label, common in (("classical", False), ("common_centre", True)):
        cal = self_calibration(objects, images, InteriorOrientation(97.0), starts, calibrate=calibrate,
                               common_centre=common, sigma_image=sigma, max_correlation=1.0)
        points = intersect_rays(measured, pair, cal.io).points
        out[label] = {"rms": 1000.0 * np.sqrt(np.mean((points - check) ** 2, axis=0)),
                      "f_error": cal.io.f - LONG_FOCUS_CAMERA.f, "sigma_f": cal.io_std["f"]}
    return out


def long_focus_trend(n_runs: int = 12, first_seed: int = 0, **kwargs):
    """Table 11.3's comparison on simulation: r.m.s. check-point errors averaged over seeded runs.

    Runs :func:`long_focus_run` for seeds ``first_seed`` … ``first_seed + n_runs − 1`` and pools
    the squared errors (r.m.s. over all runs and points). Returns ``(table, numbers)``: a
    :class:`photolib.book.verify.Table` with the book's printed values (Table 11.3, from
    ``textbook/ch11_calibration.toml``) beside the simulated ones — a different, synthetic setup,
    so only the trend compares — and a dict of the simulated numbers (rounded).
    """
    from .textbook import load_chapter
    from .verify import Table
    runs = [long_focus_run(first_seed + i, **kwargs) for i in range(n_runs)]
    numbers = {}
    for label in ("classical", "common_centre"):
        rms = np.sqrt(np.mean([r[label]["rms"] ** 2 for r in runs], axis=0))
        numbers[label] = {"m_X": round(float(rms[0]), 2), "m_Y": round(float(rms[1]), 2),
                          "m_Z": round(float(rms[2]), 2),
                          "f_error_rms": round(float(np.sqrt(np.mean([r[label]["f_error"] ** 2 for r in runs]))), 4),
                          "sigma_f": round(float(np.mean([r[label]["sigma_f"] for r in runs])), 4)}
    book = {q.name: q.printed for q in load_chapter(11).example("11.3-table-11.3").quantities}
    rows = [[f"m_{c}", book[f"m{c}_classical"], book[f"m{c}_common_centre"],
             f"{numbers['classical'][f'm_{c}']:.2f}", f"{numbers['common_centre'][f'm_{c}']:.2f}"] for c in "XYZ"]
    rows.append(["σ_f (11.3.6)", "—", "“almost 2× better”", f"{numbers['classical']['sigma_f']:.4f}",
                 f"{numbers['common_centre']['sigma_f']:.4f}"])
    rows.append(["r.m.s. true f error", "—", "—", f"{numbers['classical']['f_error_rms']:.4f}",
                 f"{numbers['common_centre']['f_error_rms']:.4f}"])
    table = Table(["r.m.s. error", "book: classical", "book: common centre",
                   "simulated: classical (mm)", "simulated: common centre (mm)"], rows,
                  f"Table 11.3 (Hasselblad, 49 check points; not reproducible) beside a synthetic long-focus "
                  f"setup, {n_runs} seeded runs")
    return table, numbers
