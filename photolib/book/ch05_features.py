"""Chapter 5, §5.5 and §5.7–5.10: adapters for textbook/ch05_features.toml.

Fig. 5.12 (the only printed numeric data of these sections), the inline statements (window
sizes, k ∈ [0.04, 0.06], 0 ≤ q ≤ 1, 4×4×8 = 128 features, five correspondences for RANSAC) and
the printed formulas (5.5.1)–(5.5.11), (5.8.1)–(5.8.13).

Every formula adapter takes the printed formula transcribed as sympy text in ``inputs`` (so a
test can hand in a deliberately wrong one) and returns ``{"printed_equals_derived": bool}``;
the derivations are sympy's (Taylor expansion, inverse, eigenvalues, derivatives), independent
of :mod:`photolib.features`. Symbols: ``gx gy u v`` (gradient and shift), ``A B C D`` the
elements of M (5.8.3), ``Sxx Sxy Syy`` the sums of (5.8.5), ``l1 l2`` eigenvalues, ``k``, ``x y
sigma`` (5.8.10)–(5.8.13), ``f1 … f9`` the 3×3 neighbourhood (5.5.8), ``f(x, y)`` an image.
"""

from __future__ import annotations

import numpy as np
import sympy as sp

from .. import features as ft
from ..image_pair import relative_orientation
from ..synthetic import stereo_pair

_S = {n: sp.Symbol(n, real=True) for n in
      "gx gy u v A B C D k x y Sxx Sxy Syy f1 f2 f3 f4 f5 f6 f7 f8 f9 t c".split()}
_S.update({n: sp.Symbol(n, positive=True) for n in ("sigma", "l1", "l2", "n", "m")})


def _parse(text, extra=None):
    return sp.parse_expr(str(text), local_dict={**_S, "Matrix": sp.Matrix, "pi": sp.pi, "exp": sp.exp,
                                                  "sqrt": sp.sqrt, **(extra or {})})


def _ok(flag) -> dict:
    return {"printed_equals_derived": bool(flag)}


def _zero(e) -> bool:
    """Exact zero test: expand first; otherwise evaluate at random rational points (a non-zero
    analytic expression vanishes there with probability 0) and confirm a zero with simplify."""
    e = sp.expand(e)
    if e == 0:
        return True
    free = sorted(e.free_symbols, key=lambda s_: s_.name)
    rng = np.random.default_rng(7)
    for _ in range(3):
        pt = {s_: sp.Rational(int(rng.integers(3, 40)), 7) for s_ in free}
        if abs(sp.N(e.subs(pt), 40)) > sp.Float(10) ** -30:
            return False
    return bool(sp.simplify(e) == 0)


def _same(a, b) -> bool:
    if isinstance(a, (sp.MatrixBase, list)):
        d = sp.Matrix(a) - sp.Matrix(b)
        return all(_zero(e) for e in d)
    return _zero(a - b)


# --- Fig. 5.12 ------------------------------------------------------------------------------------------------
def fig_5_12_roberts(inputs: dict) -> dict:
    """G = |g_x| + |g_y| (5.5.3) of the printed 8×8 image by Roberts' masks (5.5.11), cell by cell."""
    f = np.asarray(inputs["image"], dtype=float)
    gx, gy = ft.gradient_roberts(f, anchor=inputs.get("anchor", "top-left"))
    G = ft.gradient_magnitude(gx, gy, "l1")
    return {f"G[{r + 1},{c + 1}]": float(G[r, c]) for r in range(G.shape[0]) for c in range(G.shape[1])}


# --- inline statements -----------------------------------------------------------------------------------------
def foerstner_q_bounds(inputs: dict) -> dict:
    """Smallest and largest q (5.8.8) over a straight edge, a circular corner and random N."""
    rng = np.random.default_rng(int(inputs.get("seed", 0)))
    J = rng.normal(size=(2000, 25, 2))
    J[0, :, 1] = 0.0                                    # straight edge: rank-1 N
    J[1] = 0.0                                          # circular: N = diag(12, 12)
    J[1, :12, 0] = 1.0
    J[1, 12:24, 1] = 1.0
    N = np.einsum("kni,knj->kij", J, J)
    det = N[:, 0, 0] * N[:, 1, 1] - N[:, 0, 1] ** 2
    tr = N[:, 0, 0] + N[:, 1, 1]
    q = 4 * det / tr ** 2
    return {"q_min": float(q.min()), "q_max": float(q.max())}


def foerstner_w_meaning(inputs: dict) -> dict:
    """Is w (5.8.7) small or large at the points the operator should select (corners, q ≈ 1)?"""
    f = np.zeros((41, 41))
    f[20:, 20:] = 100.0
    w, q = ft.foerstner(f)
    corner = w[20, 20]
    edge = w[20, 32]
    return {"w_at_good_points": "large" if corner > edge else "small"}


def descriptor_size(inputs: dict) -> dict:
    """Length of the §5.9 descriptor and the side of its region, from the library."""
    rng = np.random.default_rng(0)
    img = rng.uniform(0, 255, (48, 48))
    cells, cell = int(inputs["cells"]), int(inputs["cell_size"])
    d = ft.sift_descriptors(img, [[24.0, 24.0]], cells=cells, cell_size=cell, bins=int(inputs["bins"]))
    return {"region_side": float(cells * cell), "n_features": float(d.vectors.shape[1])}


def ransac_minimal_sample(inputs: dict) -> dict:
    """Fewest correspondences that determine the five elements of relative orientation (§5.10).

    With n points of a synthetic near-vertical pair the coplanarity adjustment (§2.8) is solved
    from zero; n is enough if the Jacobian of the n conditions has rank 5 (all five elements
    determined) and the solution equals the true orientation.
    """
    p = stereo_pair(8, seed=int(inputs.get("seed", 0)), angle_spread_deg=2.0)
    truth = p.eo1.matrix.T @ p.eo2.matrix
    for n in range(4, 9):
        try:
            ro = relative_orientation(p.xy1[:n], p.xy2[:n], p.io, max_iter=50)
        except Exception:            # noqa: BLE001 — fewer points than elements: no solution
            continue
        if np.allclose(ro.A1.T @ ro.A2, truth, atol=1e-8):
            return {"min_points": float(n)}
    return {"min_points": None}


# --- (5.5.x) gradients -----------------------------------------------------------------------------------------
def _image_function(img):
    """f(x, y) on an array with x = column and y = −row (the book's y upwards)."""
    def f(x, y):
        return img[-int(y), int(x)]
    return f


def gradient_definition(inputs: dict) -> dict:
    """(5.5.1): G = (∂f/∂x, ∂f/∂y); checked: on a quadratic surface the printed components equal
    the (exact for quadratics) central Sobel derivative of the sampled image (y upwards)."""
    X, Y = _S["x"], _S["y"]
    f = 3 * X + 2 * Y + sp.Rational(1, 2) * X ** 2 - X * Y + sp.Rational(1, 4) * Y ** 2
    comps = [_parse(t, {"f": f}) for t in inputs["printed"]]
    rows, cols = np.mgrid[0:9, 0:9]
    img = sp.lambdify((X, Y), f)(cols.astype(float), -rows.astype(float))
    gx, gy = ft.gradient_sobel(img, normalize=True)
    r, c = 4, 5
    at = {X: c, Y: -r}
    return _ok(abs(float(comps[0].subs(at)) - gx[r, c]) < 1e-9 and abs(float(comps[1].subs(at)) - gy[r, c]) < 1e-9)


def gradient_magnitude_formula(inputs: dict) -> dict:
    """(5.5.2) is the Euclidean length of (5.5.1); (5.5.3) is the L1 length, within [1, √2] of it."""
    e = _parse(inputs["printed"], {"abs": sp.Abs})
    gx, gy = _S["gx"], _S["gy"]
    if inputs["norm"] == "l2":
        return _ok(_same(e, sp.sqrt(sp.Matrix([gx, gy]).dot(sp.Matrix([gx, gy])))))
    l2 = sp.sqrt(gx ** 2 + gy ** 2)
    rng = np.random.default_rng(1)
    vals = rng.normal(size=(200, 2))
    fn = sp.lambdify((gx, gy), e)
    ratios = np.array([fn(a, b) / np.hypot(a, b) for a, b in vals])
    exact = _same(e, sp.Abs(gx) + sp.Abs(gy))
    return _ok(exact and ratios.min() >= 1 - 1e-12 and ratios.max() <= np.sqrt(2) + 1e-12 and l2 is not None)


def backward_differences(inputs: dict) -> dict:
    """(5.5.4): the printed differences are the exact derivative of a linear image (first-order Taylor)."""
    X, Y, a, b = _S["x"], _S["y"], sp.Symbol("a"), sp.Symbol("b")
    lin = sp.Lambda((X, Y), a * X + b * Y + 7)
    ex, ey = (_parse(t, {"f": lin}) for t in inputs["printed"])
    return _ok(_same(ex, sp.diff(lin(X, Y), X)) and _same(ey, sp.diff(lin(X, Y), Y)))


def _mask(rows):
    return sp.Matrix([[_parse(e) for e in r] for r in rows])


def derivative_masks(inputs: dict) -> dict:
    """(5.5.6)/(5.5.10)/(5.5.11): the printed masks against their construction.

    Sobel = [1, 2, 1]ᵀ smoothing ⊗ central difference, Prewitt = [1, 1, 1]ᵀ ⊗ central difference,
    H_y the same turned so that it measures towards the top (y upwards; top row positive);
    Roberts = the differences along the two diagonals of a 2×2 block (x: up-right minus down-left,
    y: up-left minus down-right).
    """
    Hx, Hy = _mask(inputs["Hx"]), _mask(inputs["Hy"])
    kind = inputs["operator"]
    if kind in ("sobel", "prewitt"):
        s = sp.Matrix([1, 2, 1]) if kind == "sobel" else sp.Matrix([1, 1, 1])
        d = sp.Matrix([[-1, 0, 1]])
        Dx = s * d
        Dy = sp.Matrix([1, 0, -1]) * s.T
        return _ok(_same(Hx, Dx) and _same(Hy, Dy))
    Dx = sp.Matrix([[0, 1], [-1, 0]])      # f(up-right) − f(down-left)
    Dy = sp.Matrix([[1, 0], [0, -1]])      # f(up-left) − f(down-right)
    return _ok(_same(Hx, Dx) and _same(Hy, Dy))


def sobel_nine_pixels(inputs: dict) -> dict:
    """(5.5.7)–(5.5.9): Σ f_ij·H_ij of the 3×3 block f₁…f₉ with the Sobel masks vs the printed sums."""
    F = sp.Matrix(3, 3, [_S[f"f{i}"] for i in range(1, 10)])
    Hx = sp.Matrix([[-1, 0, 1], [-2, 0, 2], [-1, 0, 1]])
    Hy = sp.Matrix([[1, 2, 1], [0, 0, 0], [-1, -2, -1]])
    gx = sum(F[i, j] * Hx[i, j] for i in range(3) for j in range(3))
    gy = sum(F[i, j] * Hy[i, j] for i in range(3) for j in range(3))
    px, py = (_parse(t) for t in inputs["printed"])
    return _ok(sp.expand(px - gx) == 0 and sp.expand(py - gy) == 0)


# --- (5.8.x) interest operators ----------------------------------------------------------------------------------
def moravec_terms(inputs: dict) -> dict:
    """(5.8.1) M₁: the printed summation limits must give the n(m − 1) terms of its normaliser."""
    ok = True
    for n in (3, 5, 7):
        m = n
        lo = int(float(_parse(inputs["i_lower"]).subs(_S["n"], n)))     # n/2 read as ⌊n/2⌋ (towards 0)
        hi = int(float(_parse(inputs["i_upper"]).subs(_S["n"], n)))
        jlo, jhi = -(m // 2), m // 2 - 1
        terms = len(range(lo, hi + 1)) * len(range(jlo, jhi + 1))
        ok &= terms == n * (m - 1)
    return _ok(ok)


def harris_quadratic_form(inputs: dict) -> dict:
    """(5.8.2): f(x+u, y+v) − f(x, y) ≈ g_x u + g_y v (Taylor), so E ≈ Σ P (g_x u + g_y v)² = (u, v) M (u, v)ᵀ.

    Checked on a generic cubic image f(x, y) with symbolic coefficients: the first-order term in
    ε of f(x + εu, y + εv) − f(x, y), squared, against the printed square and the printed
    quadratic form, with g_x = ∂f/∂x, g_y = ∂f/∂y.
    """
    X, Y, u, v = _S["x"], _S["y"], _S["u"], _S["v"]
    a = sp.symbols("a1:10")
    mons = [X, Y, X ** 2, X * Y, Y ** 2, X ** 3, X ** 2 * Y, X * Y ** 2, Y ** 3]

    def f(px, py):
        return sum(ai * mi.subs({X: px, Y: py}, simultaneous=True) for ai, mi in zip(a, mons))
    eps = sp.Symbol("eps")
    first = sp.expand(f(X + eps * u, Y + eps * v) - f(X, Y)).coeff(eps, 1)
    derived = sp.expand(first ** 2)
    gx, gy = sp.diff(f(X, Y), X), sp.diff(f(X, Y), Y)
    rep = {_S["gx"]: gx, _S["gy"]: gy}
    printed_square = sp.expand(_parse(inputs["printed_square"]).subs(rep, simultaneous=True))
    M = sp.Matrix([[gx ** 2, gx * gy], [gx * gy, gy ** 2]])
    vec = sp.Matrix([_parse(e) for e in inputs["printed_vector"]])
    printed_form = sp.expand((vec.T * M * vec)[0])
    return _ok(sp.expand(printed_square - derived) == 0 and sp.expand(printed_form - derived) == 0)


def autocorrelation_matrix(inputs: dict) -> dict:
    """(5.8.3)/(5.8.5): M (N) is JᵀJ of the linearised shift model, rows J = (g_x, g_y)."""
    gx, gy = _S["gx"], _S["gy"]
    J = sp.Matrix([[gx, gy]])
    return _ok(_same(_mask(inputs["printed"]), J.T * J))


def harris_det_trace_response(inputs: dict) -> dict:
    """(5.8.4) with M = [[A, B], [C, D]], C = B (5.8.3): λ₁λ₂ = det M, λ₁ + λ₂ = tr M, R = det − k·tr²."""
    A, B, D, k, l1, l2 = (_S[s] for s in ("A", "B", "D", "k", "l1", "l2"))
    M = sp.Matrix([[A, B], [B, D]])
    what = inputs["quantity"]
    printed = _parse(inputs["printed"]).subs(_S["C"], B)
    if what == "det":
        return _ok(_same(printed, M.det()))
    if what == "trace":
        return _ok(_same(printed, M.trace()))
    # response: homogeneous of degree 4 in the gradients (scale invariance of k): R(s²λ) = s⁴R(λ)
    s = sp.Symbol("s", positive=True)
    derived = l1 * l2 - k * (l1 + l2) ** 2
    homogeneous = _zero(printed.subs({l1: s ** 2 * l1, l2: s ** 2 * l2}, simultaneous=True) - s ** 4 * printed)
    return _ok(homogeneous and _same(printed, derived))


def foerstner_inverse(inputs: dict) -> dict:
    """(5.8.6): Q = N⁻¹ = |N|⁻¹·adj N — sympy's inverse against the printed matrix."""
    Sxx, Sxy, Syy = _S["Sxx"], _S["Sxy"], _S["Syy"]
    N = sp.Matrix([[Sxx, Sxy], [Sxy, Syy]])
    printed = _mask(inputs["printed_adjugate"]) / N.det()
    return _ok(_same(printed, N.inv()))


def foerstner_w(inputs: dict) -> dict:
    """(5.8.7): w = 1/(λ₁ + λ₂) with λ the eigenvalues of Q = N⁻¹, = |N|/tr N; the printed last form."""
    Sxx, Sxy, Syy = _S["Sxx"], _S["Sxy"], _S["Syy"]
    N = sp.Matrix([[Sxx, Sxy], [Sxy, Syy]])
    derived = 1 / N.inv().trace()
    return _ok(_same(_parse(inputs["printed"]), derived))


def foerstner_q(inputs: dict) -> dict:
    """(5.8.8): q = 4|N|/(tr N)² = 1 − ((λ₁ − λ₂)/(λ₁ + λ₂))² with λ the eigenvalues of N (so 0 ≤ q ≤ 1)."""
    l1, l2 = _S["l1"], _S["l2"]
    Sxx, Sxy, Syy = _S["Sxx"], _S["Sxy"], _S["Syy"]
    printed = _parse(inputs["printed"])
    rot = sp.Matrix([[sp.Rational(3, 5), -sp.Rational(4, 5)], [sp.Rational(4, 5), sp.Rational(3, 5)]])
    N = rot * sp.diag(l1, l2) * rot.T            # any symmetric N with eigenvalues l1, l2
    val = printed.subs({Sxx: N[0, 0], Sxy: N[0, 1], Syy: N[1, 1]}, simultaneous=True)
    return _ok(_same(val, 1 - ((l1 - l2) / (l1 + l2)) ** 2))


def fast_classification(inputs: dict) -> dict:
    """(5.8.9): the three printed conditions put every grey value in exactly one class, and the
    library's segment test uses them (≥ t counts): a ring 9 pixels brighter by exactly t is a corner."""
    t, c = 10.0, 100.0
    conds = [_parse(e, {"f_u": sp.Symbol("f_u"), "f_c": sp.Symbol("f_c")}) for e in inputs["printed"]]
    fu, fc, T = sp.Symbol("f_u"), sp.Symbol("f_c"), _S["t"]
    tests = [sp.lambdify((fu, fc, T), cond) for cond in conds]
    ok = True
    for val in np.linspace(c - 2 * t, c + 2 * t, 81):
        hits = sum(bool(fn(val, c, t)) for fn in tests)
        ok &= hits == 1
    img = np.full((9, 9), c)
    for dx, dy in ft.FAST_CIRCLE[:9]:
        img[4 + dy, 4 + dx] = c + t
    ok &= ft.fast(img, t)[4, 4] == t and ft.fast(img, t + 1e-9)[4, 4] == 0
    return _ok(ok)


def _gaussian():
    X, Y, s = _S["x"], _S["y"], _S["sigma"]
    return sp.exp(-(X ** 2 + Y ** 2) / (2 * s ** 2)) / (2 * sp.pi * s ** 2)


def gaussian_formula(inputs: dict) -> dict:
    """(5.8.10): the rotationally symmetric normal density of σ: integral 1, variance σ² per axis,
    depends on x, y only through r² (checked by quadrature at σ = 1.3 and σ = 2.7)."""
    X, Y, s = _S["x"], _S["y"], _S["sigma"]
    W = _parse(inputs["printed"])
    ok = True
    for sig in (1.3, 2.7):
        fn = sp.lambdify((X, Y), W.subs(s, sig), "numpy")
        g = np.linspace(-12 * sig, 12 * sig, 481)          # trapezoid on a fine grid: spectrally exact here
        GX, GY = np.meshgrid(g, g)
        vals = fn(GX, GY)
        h = g[1] - g[0]
        one = vals.sum() * h * h
        var = (GX ** 2 * vals).sum() * h * h
        ok &= abs(one - 1) < 1e-9 and abs(var - sig ** 2) < 1e-9 * sig ** 2
        ok &= abs(fn(3.0, 4.0) - fn(5.0, 0.0)) < 1e-15
    return _ok(ok)


def gaussian_derivative(inputs: dict) -> dict:
    """(5.8.11)–(5.8.13): the printed derivatives of (5.8.10) against sympy's."""
    X, Y = _S["x"], _S["y"]
    W = _gaussian()
    derived = {"Wx": sp.diff(W, X), "Wy": sp.diff(W, Y), "Wxx": sp.diff(W, X, 2), "Wyy": sp.diff(W, Y, 2),
               "LoG": sp.diff(W, X, 2) + sp.diff(W, Y, 2)}
    return _ok(all(_same(_parse(text), derived[name]) for name, text in inputs["printed"].items()))
