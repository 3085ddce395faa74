"""Chapter 1, §1.1–§1.7: checks of the printed formulas (``[[formula]]`` entries of ``textbook/``).

Each function takes the entry's ``inputs`` and returns ``{"printed_equals_derived": bool}``
from a real sympy derivation (plus, where the formula is a library function, a numeric
comparison with that function). The printed forms are transcribed from the seed as they stand;
a check that the printed form disagrees with the derivation marks an erratum.

Rotations: the identities of §1.4 and §1.7 hold for every orthogonal A. They are checked with
A = Q(a, b, c, d)/m, the quaternion matrix (1.3.7) divided by its scale: a rational
parametrisation of all rotations, so the identities are rational-function identities, decided
exactly in sympy's fraction field ℚ(a, b, c, d, …) (every element kept in lowest terms, so a
difference is the zero of the field iff it vanishes identically — the test ``sympy.cancel`` makes,
without building the nested sympy expression first).
"""

from __future__ import annotations

import numpy as np
import sympy as sp
from sympy.polys.fields import field

from .. import camera, single_image
from ._exact import lambdify, zero
from ..derivations import X, Xs, Y, Ys, Z, Zs, f, rotation_matrix_symbolic, x, x0, y, y0

_qa, _qb, _qc, _qd = sp.symbols("q_a q_b q_c q_d", real=True)
f0, H, alpha0 = sp.symbols("f0 H alpha_0", positive=True)
xh, yh = sp.symbols("x^0 y^0", real=True)


def _quaternion_A():
    """(1.3.7) divided by m = a² + b² + c² + d²: an orthogonal matrix for any non-zero (a, b, c, d)."""
    from ..derivations import quaternion_rotation_symbolic
    a, b, c, d = _qa, _qb, _qc, _qd
    return quaternion_rotation_symbolic(a, b, c, d), a**2 + b**2 + c**2 + d**2


def _fraction_field(symbols):
    """{symbol: generator} of the fraction field ℚ(symbols) (elements are kept in lowest terms)."""
    _, *gens = field(list(symbols), sp.QQ)
    return dict(zip(symbols, gens))


def _quaternion_A_field(v):
    """A = Q/m of :func:`_quaternion_A` with entries in the fraction field of ``v``."""
    Q, m = _quaternion_A()
    field_of = next(iter(v.values())).field
    mv = field_of.from_expr(m)
    return [[field_of.from_expr(Q[i, j]) / mv for j in range(3)] for i in range(3)]


class _FieldMatrix:
    """A 3×3 table of field elements indexed like a sympy Matrix (``A[i, j]``)."""

    def __init__(self, rows):
        self._rows = rows

    def __getitem__(self, ij):
        return self._rows[ij[0]][ij[1]]


def _cancel_zero(expr) -> bool:
    return sp.cancel(sp.together(expr)) == 0


def _is_zero(expr) -> bool:
    return zero(expr, _cancel_zero)           # exact canonical form where it is quick, else cancel


# --- §1.1 ----------------------------------------------------------------------------------------
def on_f_tan_tilt(inputs: dict) -> dict:
    """on = f·tg α₀ (§1.1, line 81): derive the nadir point of a camera tilted by α₀ with (1.4.12).

    The camera is tilted about its y axis (A = A_α(α₀)); the plumb line through S meets the
    ground at N = S − (0, 0, H). Its image n = (x_n, y_n) by (1.4.12) lies at |on| from o.
    The numeric part compares with :func:`photolib.single_image.principal_to_nadir_distance`.
    """
    A = rotation_matrix_symbolic("kaw", 0, alpha0, 0)
    star = A.T * sp.Matrix([0, 0, -H])
    xn, yn = -f * star[0] / star[2], -f * star[1] / star[2]
    printed = f * sp.tan(alpha0)
    symbolic = zero(xn - printed) and yn == 0
    numeric = np.isclose(float(single_image.principal_to_nadir_distance(inputs["f_mm"], np.radians(inputs["tilt_deg"]))),
                         float((xn.subs({f: inputs["f_mm"], alpha0: sp.rad(inputs["tilt_deg"]), H: 1000}))), rtol=1e-12)
    return {"printed_equals_derived": bool(symbolic and numeric)}


# --- §1.2 ----------------------------------------------------------------------------------------
def ray_vector(inputs: dict) -> dict:
    """(1.2.1)/(1.2.3): r = (x, y, 0) − (x₀, y₀, f) = (x − x₀, y − y₀, −f); with distortion the
    measured point is first corrected to (x + d_x, y + d_y, 0).

    The printed right-hand side is compared with the difference of the two points (sympy), and
    :func:`photolib.camera.image_vector` with the printed form at random points (numpy).
    """
    dx, dy = sp.symbols("d_x d_y", real=True)
    with_distortion = bool(inputs.get("distortion", False))
    m = sp.Matrix([x + dx, y + dy, 0]) if with_distortion else sp.Matrix([x, y, 0])
    S = sp.Matrix([x0, y0, f])
    printed = (sp.Matrix([x - x0 + dx, y - y0 + dy, -f]) if with_distortion
               else sp.Matrix([x - x0, y - y0, -f]))
    symbolic = zero(m - S - printed)
    rng = np.random.default_rng(0)
    coeffs = dict(k1=2e-5, k2=-1e-9, p1=1e-6, p2=-2e-6) if with_distortion else {}
    io = camera.InteriorOrientation(100.0, 0.2, -0.3, **coeffs)
    pts = rng.uniform(-40, 40, (10, 2))
    d = camera.distortion_correction(pts, io) if with_distortion else np.zeros_like(pts)
    fn = lambdify((x, y, x0, y0, f, dx, dy), list(printed))
    expected = np.column_stack(np.broadcast_arrays(*fn(pts[:, 0], pts[:, 1], io.x0, io.y0, io.f, d[:, 0], d[:, 1])))
    numeric = np.allclose(camera.image_vector(pts, io, distortion=with_distortion), expected, atol=1e-12)
    return {"printed_equals_derived": bool(symbolic and numeric)}


# --- §1.4 ----------------------------------------------------------------------------------------
def _collinearity_printed(A, v=None):
    """(1.4.12) as printed: x, y from object coordinates (``v``: symbol -> value, e.g. field elements)."""
    v = v or {}
    X_, Xs_, Y_, Ys_, Z_, Zs_, f_, x0_, y0_ = (v.get(s, s) for s in (X, Xs, Y, Ys, Z, Zs, f, x0, y0))
    dX, dY, dZ = X_ - Xs_, Y_ - Ys_, Z_ - Zs_
    den = A[0, 2] * dX + A[1, 2] * dY + A[2, 2] * dZ
    return (x0_ - f_ * (A[0, 0] * dX + A[1, 0] * dY + A[2, 0] * dZ) / den,
            y0_ - f_ * (A[0, 1] * dX + A[1, 1] * dY + A[2, 1] * dZ) / den)


def _monoplot_printed(A, xi, yi, Zp, v=None):
    """(1.4.7) as printed: X, Y from image coordinates and the height Z (``v`` as above)."""
    v = v or {}
    Xs_, Ys_, Zs_, f_, x0_, y0_ = (v.get(s, s) for s in (Xs, Ys, Zs, f, x0, y0))
    u, w = xi - x0_, yi - y0_
    den = A[2, 0] * u + A[2, 1] * w - A[2, 2] * f_
    return (Xs_ + (Zp - Zs_) * (A[0, 0] * u + A[0, 1] * w - A[0, 2] * f_) / den,
            Ys_ + (Zp - Zs_) * (A[1, 0] * u + A[1, 1] * w - A[1, 2] * f_) / den)


def monoplot_collinearity_round_trip(inputs: dict) -> dict:
    """(1.4.7) ∘ (1.4.12) = identity: project (X, Y, Z) by the printed (1.4.12), bring it back by
    the printed (1.4.7) with the same Z, and get (X, Y) exactly (every rotation A = Q/m; exact
    rational-function arithmetic in ℚ(a, b, c, d, X, Y, Z, …), see the module docstring)."""
    v = _fraction_field([_qa, _qb, _qc, _qd, X, Y, Z, Xs, Ys, Zs, f, x0, y0])
    A = _FieldMatrix(_quaternion_A_field(v))
    xi, yi = _collinearity_printed(A, v)
    Xb, Yb = _monoplot_printed(A, xi, yi, v[Z], v)
    return {"printed_equals_derived": bool(Xb - v[X] == 0 and Yb - v[Y] == 0)}


# --- §1.5 ----------------------------------------------------------------------------------------
def horizontal_image_formulas(inputs: dict) -> dict:
    """(1.5.3) and (1.5.5) from the printed (1.4.12) with A = E, x₀ = y₀ = 0 (and, for (1.5.5),
    S at the origin and H = −Z); both printed members of (1.5.5) are compared."""
    xi, yi = (e.subs({x0: 0, y0: 0}) for e in _collinearity_printed(sp.eye(3)))
    eq = inputs["equation"]
    if eq == "(1.5.3)":
        printed = (-f / (Z - Zs) * (X - Xs), -f / (Z - Zs) * (Y - Ys))
        ok = _is_zero(xi - printed[0]) and _is_zero(yi - printed[1])
    elif eq == "(1.5.5)":
        origin = {Xs: 0, Ys: 0, Zs: 0}
        xi, yi = xi.subs(origin), yi.subs(origin)
        first = (-f / Z * X, -f / Z * Y)
        second = (f / H * X, f / H * Y)
        ok = (_is_zero(xi - first[0]) and _is_zero(yi - first[1])
              and _is_zero(xi.subs(Z, -H) - second[0]) and _is_zero(yi.subs(Z, -H) - second[1]))
    else:
        raise KeyError(eq)
    return {"printed_equals_derived": bool(ok)}


def horizontal_image_scale(inputs: dict) -> dict:
    """Scale of a horizontal image of flat terrain (line 446). The scale 1/m is the ratio of an
    image length to the ground length: by (1.5.5) it is ∂x/∂X = f/H (dimensionless). The printed
    right-hand side ``inputs["printed"]`` ("1/H" as printed, "f/H" for the correction) is compared
    with it symbolically and, for the RC30-like numbers in ``inputs``, with
    :func:`photolib.single_image.horizontal_image_scale`."""
    xi = _collinearity_printed(sp.eye(3))[0].subs({x0: 0, y0: 0, Xs: 0, Ys: 0, Zs: 0, Z: -H})
    derived = sp.diff(xi, X)
    printed = {"1/H": 1 / H, "f/H": f / H}[inputs["printed"]]
    symbolic = _is_zero(derived - printed)
    f_m, H_m = inputs["f_mm"] / 1000.0, inputs["H_m"]             # both lengths in metres
    numeric = np.isclose(float(printed.subs({f: f_m, H: H_m})), 1.0 / single_image.horizontal_image_scale(
        inputs["f_mm"], H_m), rtol=1e-12)
    return {"printed_equals_derived": bool(symbolic and numeric)}


# --- §1.6 ----------------------------------------------------------------------------------------
def height_error_magnitude(inputs: dict) -> dict:
    """(1.6.1): ΔX = x·ΔZ/f, ΔY = y·ΔZ/f are the magnitudes of the change of (1.5.4)
    X = −Z·x/f, Y = −Z·y/f when Z changes by ΔZ (exact: (1.5.4) is linear in Z)."""
    dZ = sp.symbols("Delta_Z", real=True)
    X154, Y154 = -Z / f * x, -Z / f * y
    dX = X154.subs(Z, Z + dZ) - X154
    dY = Y154.subs(Z, Z + dZ) - Y154
    printed_dX, printed_dY = x / f * dZ, y / f * dZ
    # equal magnitudes of real quantities: equal squares (an exact polynomial identity)
    ok = (zero(dX ** 2 - printed_dX ** 2) and zero(dY ** 2 - printed_dY ** 2)
          and zero(dX + printed_dX))         # the sign: a point raised by ΔZ moves towards the nadir
    xs, ys = np.array([30.0, -12.0]), np.array([25.0, 7.5])
    _, _, dR = single_image.planimetric_error_from_height_error(xs, ys, 50.0, 10.0)
    ok = ok and np.allclose(dR, np.hypot(xs / 50.0 * 10.0, ys / 50.0 * 10.0), rtol=1e-14)
    return {"printed_equals_derived": bool(ok)}


# --- §1.7 ----------------------------------------------------------------------------------------
def rectification_round_trip(inputs: dict) -> dict:
    """(1.7.5) and (1.7.10) as printed are mutually inverse for every rotation A = Q/m (sympy):
    tilted → horizontal → tilted returns (x, y), horizontal → tilted → horizontal (x⁰, y⁰); exact
    rational-function arithmetic in ℚ(a, b, c, d, x, y, …), see the module docstring."""
    v = _fraction_field([_qa, _qb, _qc, _qd, x, y, x0, y0, f, f0, xh, yh])
    A = _FieldMatrix(_quaternion_A_field(v))
    x_, y_, x0_, y0_, f_, f0_, xh_, yh_ = (v[s] for s in (x, y, x0, y0, f, f0, xh, yh))

    def to_horizontal(xi, yi):                                        # (1.7.5)
        u, w = xi - x0_, yi - y0_
        den = A[2, 0] * u + A[2, 1] * w - A[2, 2] * f_
        return (-f0_ * (A[0, 0] * u + A[0, 1] * w - A[0, 2] * f_) / den,
                -f0_ * (A[1, 0] * u + A[1, 1] * w - A[1, 2] * f_) / den)

    def to_tilted(xo, yo):                                            # (1.7.10)
        den = A[0, 2] * xo + A[1, 2] * yo - A[2, 2] * f0_
        return (x0_ - f_ * (A[0, 0] * xo + A[1, 0] * yo - A[2, 0] * f0_) / den,
                y0_ - f_ * (A[0, 1] * xo + A[1, 1] * yo - A[2, 1] * f0_) / den)

    xb, yb = to_tilted(*to_horizontal(x_, y_))
    xo, yo = to_horizontal(*to_tilted(xh_, yh_))
    ok = all(e == 0 for e in (xb - x_, yb - y_, xo - xh_, yo - yh_))   # field elements: exact zero
    return {"printed_equals_derived": bool(ok)}


# --- §1.3 statements checked here (not examples) ----------------------------------------------------
def rotation_singularity(inputs: dict) -> dict:
    """Line 272: at α = 90° or 270° cos α = 0, so a₃₃ and a₁₁ vanish and (1.3.3)/(1.3.6) leave ω
    and κ undetermined: both arctangents become 0/0 for either sequence (sympy)."""
    w, k = sp.symbols("omega kappa", real=True)
    ok = True
    for a in (sp.pi / 2, 3 * sp.pi / 2):
        kaw = rotation_matrix_symbolic("kaw", w, a, k)
        wak = rotation_matrix_symbolic("wak", w, a, k)
        ok = ok and all(zero(e) for e in (kaw[0, 0], kaw[2, 2], kaw[1, 0], kaw[2, 1],   # (1.3.6)
                                                       wak[0, 0], wak[2, 2], wak[0, 1], wak[1, 2]))  # (1.3.3)
    # and only there: at a generic α the denominators are cos α·cos κ, cos α·cos ω
    a = sp.symbols("alpha", real=True)
    kaw = rotation_matrix_symbolic("kaw", w, a, k)
    ok = ok and zero(kaw[2, 2] - sp.cos(a) * sp.cos(w)) and zero(kaw[0, 0] - sp.cos(a) * sp.cos(k))
    return {"printed_equals_derived": bool(ok)}
