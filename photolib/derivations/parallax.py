"""Sympy derivations of Hanzl's §3 "Orientation and point determination from two images".

Hanzl, Fotogrammetrie, Modul 01, §3.1–§3.2.6 (seed 002 lines 344–674); the related sections of the
Russian textbook are Chibunichev §2.4 (intersection), §2.7–§2.8 (relative orientation, q = y₁ − y₂),
§2.10–§2.11 (absolute orientation), §2.5/§2.13 (normal case) and §4.4 (fundamental matrix).

* :func:`y_parallax_coefficients` — the first-order y-parallax q = y₁ − y₂ caused by the eight
  orientation elements dω₁, dφ₁, dκ₁, dω₂, dφ₂, dκ₂, db_y, db_z of a near-vertical pair (§3.2.3.1,
  lines 458–524), derived from the collinearity equations (not typed in);
  :func:`y_parallax_model` — the correction equations of the two five-element systems built from them
  (used by :func:`photolib.image_pair.relative_orientation_parallax`).
* :func:`deformation_coefficients` — the height deformation dz = (h/b)·p_x of a model caused by
  residual errors of the elements (§3.2.3.2, lines 526–568), derived to first order;
  :func:`deformation_model` compiles it (used by :func:`photolib.image_pair.model_deformation`).
* :func:`printed_formulas` / :func:`derived_formulas` — every formula of §3 as printed (transcribed
  from the seed) and as derived here, keyed alike, for the formula checks of the book layer.

Conventions: Hanzl's R = R_ω R_φ R_κ (the ``"wak"`` order, φ ≡ α) maps image → model; the image
vector is (x − x₀, y − y₀, −c); the model origin is projection centre 1, centre 2 is at
(b_x, db_y, db_z), h is the depth of a point below centre 1 (z_m = −h).
"""

from __future__ import annotations

from functools import lru_cache

import sympy as sp

from ..errors import InputError
from .model import Model
from .rotation import rotation_matrix_symbolic

__all__ = ["ELEMENTS", "DEFORMATION_ELEMENTS", "PARALLAX_SYSTEMS", "y_parallax_coefficients", "y_parallax_model",
           "deformation_coefficients", "deformation_model", "printed_formulas", "derived_formulas"]

x1, y1, x2, y2, c, h, bx, b, q = sp.symbols("x1 y1 x2 y2 c h b_x b q", real=True)
xm, ym = sp.symbols("x_m y_m", real=True)
dw1, dp1, dk1, dw2, dp2, dk2, dby, dbz, dbx = sp.symbols(
    "domega1 dphi1 dkappa1 domega2 dphi2 dkappa2 db_y db_z db_x", real=True)
_EPS = sp.Symbol("epsilon")

ELEMENTS = ("domega1", "dphi1", "dkappa1", "domega2", "dphi2", "dkappa2", "db_y", "db_z")
"""Names of the eight elements of the y-parallax (Hanzl line 512), in the order of the symbols here."""
DEFORMATION_ELEMENTS = ("db_x", "db_z", "dphi1", "domega1", "dkappa1", "dphi2", "domega2", "dkappa2")
"""Names of the elements of the model-deformation formula (Hanzl lines 540–548)."""
PARALLAX_SYSTEMS = {"independent": ("dkappa1", "dkappa2", "dphi1", "dphi2", "domega2"),
                    "dependent": ("dkappa2", "domega2", "dphi2", "db_y", "db_z")}
"""The five elements of the independent pair (line 516) and of the dependent pair (line 520)."""

_SYM = dict(zip(ELEMENTS, (dw1, dp1, dk1, dw2, dp2, dk2, dby, dbz)))
_DSYM = dict(zip(DEFORMATION_ELEMENTS, (dbx, dbz, dp1, dw1, dk1, dp2, dw2, dk2)))


def _rot(w, p, k):
    return rotation_matrix_symbolic("wak", w, p, k)


def _project(P, O, R):
    """Image coordinates (x, y) of the model point P seen from centre O with rotation R (image → model)."""
    u = R.T * (P - O)
    return -c * u[0] / u[2], -c * u[1] / u[2]


def _first_order(expr, symbols):
    """The part of ``expr`` of order ≤ 1 in ``symbols`` (a Taylor expansion about 0)."""
    scaled = expr.subs({s: _EPS * s for s in symbols}, simultaneous=True)
    return sp.expand(sp.series(scaled, _EPS, 0, 2).removeO().subs(_EPS, 1))


@lru_cache(maxsize=None)
def y_parallax_coefficients() -> dict:
    """∂q/∂e at e = 0 for q = y₁ − y₂ and the eight elements of Hanzl line 512, derived by sympy.

    A model point P = (X, Y, −h) is projected into image 1 (centre 0, rotation R(dω₁, dφ₁, dκ₁))
    and image 2 (centre (b_x, db_y, db_z), rotation R(dω₂, dφ₂, dκ₂)) with the exact collinearity
    equations; q = y₁ − y₂ is differentiated by each element at zero, and X, Y are written with the
    image coordinates of the undisturbed pair (X = h x₁/c, Y = h y₁/c for image-1 elements;
    X − b_x = h x₂/c, Y = h y₂/c for image-2 elements and the base).

    Returns
    -------
    dict
        {element name: sympy expression in x1, y1, x2, y2, c, h}, keys :data:`ELEMENTS`.

    Raises
    ------
    InputError
        Never (no input).

    References
    ----------
    Hanzl, Fotogrammetrie, Modul 01, §3.2.3.1 (seed 002 lines 458–524), line 510;
    Chibunichev (2022), §2.8 (q = y₁ − y₂).

    Examples
    --------
    >>> co = y_parallax_coefficients()
    >>> co["domega1"], co["db_y"]
    (-c - y1**2/c, c/h)
    """
    X, Y = sp.symbols("X Y", real=True)
    P = sp.Matrix([X, Y, -h])
    _, ya = _project(P, sp.Matrix([0, 0, 0]), _rot(dw1, dp1, dk1))
    _, yb = _project(P, sp.Matrix([bx, dby, dbz]), _rot(dw2, dp2, dk2))
    qexpr = ya - yb
    zero = {s: 0 for s in _SYM.values()}
    out = {}
    for name, s in _SYM.items():
        d = sp.diff(qexpr, s).subs(zero)
        subs = {X: h * x1 / c, Y: h * y1 / c} if name.endswith("1") else {X: bx + h * x2 / c, Y: h * y2 / c}
        out[name] = sp.simplify(sp.expand(d.subs(subs)))
    return out


def y_parallax_model(system: str) -> Model:
    """Correction equations of the first-order relative orientation, Hanzl §3.2.3.1 (lines 512–520).

    F = Σ aₑ·dₑ − q over the five elements of ``system`` with aₑ from :func:`y_parallax_coefficients`
    (the measured q = y₁ − y₂ is a datum). B = ∂F/∂d comes from :meth:`Model.jacobian`.

    Parameters
    ----------
    system : {"independent", "dependent"}
        Independent pair dκ₁, dκ₂, dφ₁, dφ₂, dω₂ (line 516) or dependent pair dκ₂, dω₂, dφ₂, db_y,
        db_z (line 520), :data:`PARALLAX_SYSTEMS`.

    Returns
    -------
    Model
        Parameters: the five elements; data x1, y1, x2, y2, c, h, q.

    Raises
    ------
    InputError
        Unknown system.

    References
    ----------
    Hanzl, Fotogrammetrie, Modul 01, §3.2.3.1 (seed 002 lines 512–524); Chibunichev (2022), §2.7–§2.8.

    Examples
    --------
    >>> m = y_parallax_model("dependent")
    >>> [str(s) for s in m.parameters]
    ['dkappa2', 'domega2', 'dphi2', 'db_y', 'db_z']
    """
    if system not in PARALLAX_SYSTEMS:
        raise InputError(f"unknown system {system!r}; use 'independent' or 'dependent'")
    return _y_parallax_model(system)


@lru_cache(maxsize=None)
def _y_parallax_model(system):
    co = y_parallax_coefficients()
    names = PARALLAX_SYSTEMS[system]
    F = sum(co[n] * _SYM[n] for n in names) - q
    return Model(f"hanzl-y-parallax-{system}", tuple(_SYM[n] for n in names), (x1, y1, x2, y2, c, h, q), (F,))


@lru_cache(maxsize=None)
def _x_parallax_first_order():
    """p_x = x₁ₘ − x₂ₘ in the plane z = −h, first order in the elements (x₁, x₂ independent)."""
    def model_xy(O, R, x, y):
        d = R * sp.Matrix([x, y, -c])
        lam = (-h - O[2]) / d[2]
        return O[0] + lam * d[0], O[1] + lam * d[1]
    X1, _ = model_xy(sp.Matrix([0, 0, 0]), _rot(dw1, dp1, dk1), x1, y1)
    X2, _ = model_xy(sp.Matrix([bx, dby, dbz]), _rot(dw2, dp2, dk2), x2, y2)
    return _first_order(X1 - X2, list(_SYM.values()))


@lru_cache(maxsize=None)
def _x_parallax_model_coordinates():
    """p_x in model coordinates: x₁ = c x_m/h, x₂ = c(x_m − b)/h, y = c y_m/h, h/c·x₁ − h/c·x₂ − b_x = −db_x."""
    px = _x_parallax_first_order()
    px = px.subs({x1: c * xm / h, y1: c * ym / h, x2: c * (xm - b) / h, y2: c * ym / h}, simultaneous=True)
    px = px.subs(bx, b + dbx)
    return sp.expand(px)


@lru_cache(maxsize=None)
def deformation_coefficients() -> dict:
    """∂dz/∂e of the model deformation dz = (h/b)·p_x, Hanzl §3.2.3.2 (lines 526–568), derived.

    p_x = x₁ₘ − x₂ₘ of the two rays in the plane z = −h is expanded to first order in the elements,
    written in model coordinates (x₁ = c x_m/h, x₂ = c(x_m − b)/h, y₁ = y₂ = c y_m/h, b_x = b + db_x)
    and multiplied by h/b (the intersection rises by h·p_x/b).

    Returns
    -------
    dict
        {element name: sympy expression in x_m, y_m, h, b}, keys :data:`DEFORMATION_ELEMENTS`.

    Raises
    ------
    InputError
        Never (no input).

    References
    ----------
    Hanzl, Fotogrammetrie, Modul 01, §3.2.3.2 (seed 002 lines 526–568).

    Examples
    --------
    >>> co = deformation_coefficients()
    >>> co["dkappa1"] + co["dkappa2"]
    0
    """
    dz = sp.expand(h / b * _x_parallax_model_coordinates())
    return {name: sp.factor(dz.coeff(s)) for name, s in _DSYM.items()}


@lru_cache(maxsize=None)
def deformation_model() -> Model:
    """dz as a :class:`Model` (parameters: the elements, data x_m, y_m, h, b) for fast evaluation.

    Returns
    -------
    Model
        Parameters :data:`DEFORMATION_ELEMENTS`; data x_m, y_m, h, b; one residual dz.

    Raises
    ------
    InputError
        Never (no input).

    References
    ----------
    Hanzl, Fotogrammetrie, Modul 01, §3.2.3.2 (seed 002 lines 544–548).

    Examples
    --------
    >>> res, _ = deformation_model().compile()
    >>> float(res(0, 0, 0, 0.001, 0, 0, 0.001, 0, 300.0, 200.0, 1500.0, 900.0)[0])   # equal dω
    0.2
    """
    co = deformation_coefficients()
    dz = sum(co[n] * _DSYM[n] for n in DEFORMATION_ELEMENTS)
    return Model("hanzl-model-deformation", tuple(_DSYM[n] for n in DEFORMATION_ELEMENTS), (xm, ym, h, b), (dz,))


# --- every formula of §3, printed and derived ---------------------------------------------------------
def _printed():
    r = sp.Matrix(3, 3, lambda i, j: sp.Symbol(f"r{i + 1}{j + 1}", real=True))
    x, y, x0, y0 = sp.symbols("x y x_0 y_0", real=True)
    X01, X02, Z01, Z02, Z, kx1, kx2 = sp.symbols("X_01 X_02 Z_01 Z_02 Z k_x1 k_x2", real=True)
    U, V, W, dm, dO, dP, dK, dXp, dYp, dZp = sp.symbols("U V W dm dOmega dPhi dK dX_p dY_p dZ_p", real=True)
    B, px, Za, spx, dc = sp.symbols("B p_x Z_abs sigma_px dc", positive=True)
    xb, yb = x - x0, y - y0
    den = r[2, 0] * xb + r[2, 1] * yb + r[2, 2] * c
    P = {
        # §3.1 lines 352–360: ratios k_x, k_y ("k_z") printed with +r13 c, +r33 c
        "3.1-kx": (r[0, 0] * xb + r[0, 1] * yb + r[0, 2] * c) / den,
        "3.1-ky": (r[1, 0] * xb + r[1, 1] * yb + r[1, 2] * c) / den,
        "3.1-Z": (X02 - X01 + Z01 * kx1 - Z02 * kx2) / (kx1 - kx2),
        # §3.2.3.1 line 482 (model coordinates of image 1 with dR)
        "482-xm": -h * (x - y * dk1 - c * dp1) / (-x * dp1 + y * dw1 - c),
        "482-ym": -h * (x * dk1 + y - c * dw1) / (-x * dp1 + y * dw1 - c),
        "490-y1m": -h * (-x1 / c * dk1 - y1 / c - y1 ** 2 / c ** 2 * dw1 + x1 * y1 / c ** 2 * dp1 - dw1),
        "494-y1m": h * (x1 / c * dk1 + y1 / c + (1 + y1 ** 2 / c ** 2) * dw1 - x1 * y1 / c ** 2 * dp1),
        "502-y2m": dby + y2 / c * dbz + h * (x2 / c * dk2 + y2 / c + (1 + y2 ** 2 / c ** 2) * dw2
                                             - x2 * y2 / c ** 2 * dp2),
        # line 510 with its definition p_y = y2 − y1 (line 508)
        "510-py": (x2 * dk2 - x1 * dk1 + (c + y2 ** 2 / c) * dw2 - (c + y1 ** 2 / c) * dw1 - x2 * y2 / c * dp2
                   + x1 * y1 / c * dp1 + c / h * dby + y2 / h * dbz),
        "514-independent": x2 * dk2 - x1 * dk1 - x2 * y2 / c * dp2 + x1 * y1 / c * dp1 + (c + y2 ** 2 / c) * dw2,
        "518-dependent": x2 * dk2 + (c + y2 ** 2 / c) * dw2 - x2 * y2 / c * dp2 + c / h * dby + y2 / h * dbz,
        # §3.2.3.2 lines 530–532, 540–542, 546–548
        "530-px": (h / c * x1 - (h + h * x1 ** 2 / c ** 2) * dp1 + h * x1 * y1 / c ** 2 * dw1 - h * y1 / c * dk1 - bx
                   - h / c * x2 - (h + h * x2 ** 2 / c ** 2) * dp2 + h * x2 * y2 / c ** 2 * dw2 - h * y2 / c * dk2
                   - x2 / c * dbz),
        "540-px": (-dbx - (xm - b) / h * dbz - h * (1 + xm ** 2 / h ** 2) * dp1 - xm * ym / h * dw1 + ym * dk1
                   + h * (1 + (xm - b) ** 2 / h ** 2) * dp2 - (xm - b) * ym / h * dw2 + ym * dk2),
        "546-dz": (-h / b * dbx - (xm - b) / b * dbz - (h ** 2 / b + xm ** 2 / b ** 2) * dp1 - xm * ym / b * dw1
                   + h * ym / b * dk1 + (h ** 2 / b + (xm - b) ** 2 / b ** 2) * dp2 - (xm - b) * ym / b * dw2
                   + h * ym / b * dk2),
        # §3.2.4 lines 586–592
        "584-mdR": sp.eye(3) + sp.Matrix([[dm, -dK, dP], [dK, dm, -dO], [-dP, dO, dm]]),
        "592-v": sp.Matrix([dXp + U * dm + W * dP - V * dK, dYp + V * dm - W * dO + U * dK,
                            dZp + W * dm + V * dO - U * dP]),
        # §3.2.5 line 608: C with +x0, +y0
        "608-C": sp.Matrix([[1, 0, x0], [0, 1, y0], [0, 0, -c]]),
        # §3.2.6 lines 648–660
        "646-Z": -c * B / (x1 - x2),
        "654-sigmaZ": (Za / c) * Za / B * spx,                                 # m_s = Z/c (line 658)
        "672-dZ": (-Za) / c * dc,                                              # Z = −Z_abs below the camera
    }
    XX, YY, ZZ, X0_, Y0_, Z0_ = sp.symbols("X Y Z X_0 Y_0 Z_0", real=True)
    dX, dY, dZ = XX - X0_, YY - Y0_, ZZ - Z0_
    P["392-F"] = x0 - c * (r[0, 0] * dX + r[1, 0] * dY + r[2, 0] * dZ) / (r[0, 2] * dX + r[1, 2] * dY + r[2, 2] * dZ)
    P["394-G"] = y0 - c * (r[0, 1] * dX + r[1, 1] * dY + r[2, 1] * dZ) / (r[0, 2] * dX + r[1, 2] * dY + r[2, 2] * dZ)
    P["396-b1"] = sp.diff(P["394-G"], Y0_)                                  # "b1 = ∂G/∂Y0"
    Om, Ph, Ka, mm, Xp, Yp, Zp_ = sp.symbols("Omega Phi K m X_p Y_p Z_p", real=True)
    P["444-similarity"] = sp.Matrix([Xp, Yp, Zp_]) + mm * _rot(Om, Ph, Ka) * sp.Matrix([xm, ym, sp.Symbol("z_m")])
    P["478-dR"] = sp.Matrix([[1, -dk1, dp1], [dk1, 1, -dw1], [-dp1, dw1, 1]])
    P["506-condition"] = (h * (x2 / c * dk2 - x1 / c * dk1 + (y2 - y1) / c + (1 + y2 ** 2 / c ** 2) * dw2)
                          - h * (1 + y1 ** 2 / c ** 2) * dw1 - x2 * y2 / c ** 2 * dp2 + x1 * y1 / c ** 2 * dp1
                          + dby + y2 / c * dbz)
    bxs, bys, bzs = sp.symbols("b_x b_y b_z", real=True)
    P["600-B"] = sp.Matrix([[0, -bzs, bys], [bzs, 0, -bxs], [-bys, bxs, 0]])
    P["604-B"] = sp.Matrix([[0, 0, 0], [0, 0, -1], [0, 1, 0]])
    fs = sp.Matrix(3, 3, lambda i, j: sp.Symbol(f"f{i + 1}{j + 1}", real=True))
    P["618-expanded"] = (x1 * x2 * fs[0, 0] + x1 * y2 * fs[0, 1] + x1 * fs[0, 2] + x2 * y1 * fs[1, 0]
                         + y1 * y2 * fs[1, 1] + y1 * fs[1, 2] + x2 * fs[2, 0] + y2 * fs[2, 1] + fs[2, 2])
    P["622-normalised"] = (x1 * x2 * fs[0, 0] + x1 * y2 * fs[0, 1] + x1 * fs[0, 2] + x2 * y1 * fs[1, 0]
                           + y1 * y2 * fs[1, 1] + y1 * fs[1, 2] + x2 * fs[2, 0] + y2 * fs[2, 1])
    P["636-X"] = X01 + (Z - Z01) * (r[0, 0] * x + r[0, 1] * y - r[0, 2] * c) / (r[2, 0] * x + r[2, 1] * y - r[2, 2] * c)
    R1s = sp.Matrix(3, 3, lambda i, j: sp.Symbol(f"a{i + 1}{j + 1}", real=True))
    R2s = sp.Matrix(3, 3, lambda i, j: sp.Symbol(f"e{i + 1}{j + 1}", real=True))
    x01, y01, x02, y02, c1, c2 = sp.symbols("x_01 y_01 x_02 y_02 c_1 c_2", real=True)
    Cc = lambda xo, yo, cc: sp.Matrix([[1, 0, -xo], [0, 1, -yo], [0, 0, -cc]])  # noqa: E731 — C with −x0 (608)
    P["614-F"] = Cc(x01, y01, c1).T * R1s.T * P["600-B"] * R2s * Cc(x02, y02, c2)
    P["642-normal"] = sp.Matrix([Z * x1 / (-c), Z * y1 / (-c), B + Z * x2 / (-c)])
    sxx = sp.Symbol("sigma_x", positive=True)
    P["650-sigmaX"] = (x1 / c * (Za / c) * Za / B * spx) ** 2 + ((Za / c) * sxx) ** 2
    return P


def _derived():
    r = sp.Matrix(3, 3, lambda i, j: sp.Symbol(f"r{i + 1}{j + 1}", real=True))
    x, y, x0, y0 = sp.symbols("x y x_0 y_0", real=True)
    X01, X02, Z01, Z02, Z, kx1, kx2 = sp.symbols("X_01 X_02 Z_01 Z_02 Z k_x1 k_x2", real=True)
    U, V, W, dm, dO, dP, dK, dXp, dYp, dZp = sp.symbols("U V W dm dOmega dPhi dK dX_p dY_p dZ_p", real=True)
    B, px, Za, spx, dc = sp.symbols("B p_x Z_abs sigma_px dc", positive=True)
    ray = r * sp.Matrix([x - x0, y - y0, -c])                                 # (2.3): X − X0 = λ R x̄
    zsol = sp.solve(sp.Eq(X01 + (Z - Z01) * kx1, X02 + (Z - Z02) * kx2), Z)[0]
    dR = sp.Matrix([[1, -dk1, dp1], [dk1, 1, -dw1], [-dp1, dw1, 1]])          # line 478
    v1 = dR * sp.Matrix([x, y, -c])
    lam = -h / v1[2]
    w1 = v1.subs({x: x1, y: y1}, simultaneous=True)                         # the same for point (x1, y1)
    co = y_parallax_coefficients()
    qlin = sum(co[n] * _SYM[n] for n in ELEMENTS)                            # q = y1 − y2
    first = [dw1, dp1, dk1]
    y2m = dby + (h + dbz) * (x2 / c * dk2 + y2 / c + (1 + y2 ** 2 / c ** 2) * dw2 - x2 * y2 / c ** 2 * dp2)
    dzco = deformation_coefficients()
    pxm = sum(b / h * dzco[n] * _DSYM[n] for n in DEFORMATION_ELEMENTS)
    dR_abs = sp.Matrix([[1, -dK, dP], [dK, 1, -dO], [-dP, dO, 1]])
    Xabs = sp.Matrix([dXp, dYp, dZp]) + (1 + dm) * dR_abs * sp.Matrix([U, V, W])
    Zn = sp.solve(sp.Eq(Z * x1 / (-c), B + Z * x2 / (-c)), Z)[0]
    Zp = -c * B / px
    XX, YY, ZZ, X0_, Y0_, Z0_ = sp.symbols("X Y Z X_0 Y_0 Z_0", real=True)
    u = r.T * sp.Matrix([XX - X0_, YY - Y0_, ZZ - Z0_])                       # (2.2): image vector ∥ Rᵀ(X − X0)
    G = y0 - c * u[1] / u[2]
    Om, Ph, Ka, mm, Xp, Yp, Zp_ = sp.symbols("Omega Phi K m X_p Y_p Z_p", real=True)
    Xsim = sp.solve(list(sp.Matrix([XX, YY, ZZ]) - sp.Matrix([Xp, Yp, Zp_]) - mm * _rot(Om, Ph, Ka)
                         * sp.Matrix([xm, ym, sp.Symbol("z_m")])), [XX, YY, ZZ], dict=True)[0]
    bxs, bys, bzs = sp.symbols("b_x b_y b_z", real=True)
    pv = sp.Matrix(sp.symbols("p_x2 p_y2 p_z2", real=True))
    Bsk = sp.Matrix(3, 3, lambda i, j: sp.diff(sp.Matrix([bxs, bys, bzs]).cross(pv)[i], pv[j]))   # b × p = B p
    fs = sp.Matrix(3, 3, lambda i, j: sp.Symbol(f"f{i + 1}{j + 1}", real=True))
    bilinear = sp.expand((sp.Matrix([[x1, y1, 1]]) * fs * sp.Matrix([x2, y2, 1]))[0])
    Zn_ = sp.Symbol("Z", real=True)
    Xn = Zp * x1 / (-c)                                                       # X = Z x1/(−c), Z = −cB/p_x
    sxx = sp.Symbol("sigma_x", positive=True)
    varX = (sp.diff(Xn, px) * spx) ** 2 + (sp.diff(Xn, x1) * sxx) ** 2
    ray0 = sp.Matrix([[r[0, 0], r[0, 1], r[0, 2]], [r[1, 0], r[1, 1], r[1, 2]], [r[2, 0], r[2, 1], r[2, 2]]]) \
        * sp.Matrix([x, y, -c])
    R1s = sp.Matrix(3, 3, lambda i, j: sp.Symbol(f"a{i + 1}{j + 1}", real=True))
    R2s = sp.Matrix(3, 3, lambda i, j: sp.Symbol(f"e{i + 1}{j + 1}", real=True))
    x01, y01, x02, y02, c1, c2 = sp.symbols("x_01 y_01 x_02 y_02 c_1 c_2", real=True)
    p1 = R1s * sp.Matrix([x1 - x01, y1 - y01, -c1])
    p2 = R2s * sp.Matrix([x2 - x02, y2 - y02, -c2])
    cop = sp.expand(p1.dot(sp.Matrix([bxs, bys, bzs]).cross(p2)))              # p1ᵀ(b × p2)
    h1, h2 = [x1, y1, 1], [x2, y2, 1]
    Fd = sp.Matrix(3, 3, lambda i, j: sp.Poly(cop, x1, y1, x2, y2).coeff_monomial(
        (h1[i] if i < 2 else 1) * (h2[j] if j < 2 else 1)))
    extra = {
        "614-F": Fd,
        "392-F": x0 - c * u[0] / u[2],
        "394-G": G,
        "396-b1": sp.diff(G, X0_),                                           # the coefficient of dX0 in v_y
        "444-similarity": sp.Matrix([Xsim[XX], Xsim[YY], Xsim[ZZ]]),
        "478-dR": sp.Matrix(3, 3, lambda i, j: _first_order(_rot(dw1, dp1, dk1)[i, j], [dw1, dp1, dk1])),
        "506-condition": _first_order(y2m, [dby, dbz, dw2, dp2, dk2])
        - _first_order(-h * w1[1] / w1[2], first),                            # y2m − y1m = 0
        "600-B": Bsk,
        "604-B": Bsk.subs({bxs: 1, bys: 0, bzs: 0}),
        "618-expanded": bilinear,
        "622-normalised": sp.expand(bilinear / fs[2, 2]).subs({fs[i, j]: fs[i, j] * fs[2, 2] for i in range(3)
                                                               for j in range(3) if (i, j) != (2, 2)}),
        "636-X": X01 + (Z - Z01) * ray0[0] / ray0[2],
        "642-normal": sp.Matrix([(X01 + (Zn_ - Z01) * ray0[0] / ray0[2]).subs({x: x1, y: y1}),
                                 (X01 + (Zn_ - Z01) * ray0[1] / ray0[2]).subs({x: x1, y: y1}),
                                 (X02 + (Zn_ - Z02) * ray0[0] / ray0[2]).subs({x: x2, y: y2})])
        .subs({r[i, j]: int(i == j) for i in range(3) for j in range(3)})
        .subs({X01: 0, Z01: 0, Z02: 0, X02: B, Zn_: Z}),                      # R = I, centres (0,0,0), (B,0,0)
        "650-sigmaX": sp.simplify(varX.subs(px, c * B / Za)),
    }
    return extra | {
        "3.1-kx": ray[0] / ray[2],
        "3.1-ky": ray[1] / ray[2],
        "3.1-Z": zsol,
        "482-xm": lam * v1[0],
        "482-ym": lam * v1[1],
        "490-y1m": _first_order(-h * (w1[1] / c) / (w1[2] / c), first),
        "494-y1m": _first_order(-h * w1[1] / w1[2], first),
        "502-y2m": _first_order(y2m, [dby, dbz, dw2, dp2, dk2]),
        "510-py": -qlin,                                                      # p_y = y2 − y1 as defined
        "514-independent": sum(co[n] * _SYM[n] for n in PARALLAX_SYSTEMS["independent"]),
        "518-dependent": sum(co[n] * _SYM[n] for n in PARALLAX_SYSTEMS["dependent"]),
        "530-px": _x_parallax_first_order(),
        "540-px": sp.expand(pxm),
        "546-dz": sum(dzco[n] * _DSYM[n] for n in DEFORMATION_ELEMENTS),
        "584-mdR": sp.Matrix(3, 3, lambda i, j: _first_order(((1 + dm) * dR_abs)[i, j], [dm, dO, dP, dK])),
        "592-v": sp.Matrix([_first_order(Xabs[i], [dm, dO, dP, dK, dXp, dYp, dZp]) - sp.Matrix([U, V, W])[i]
                            for i in range(3)]),
        "608-C": sp.Matrix([[1, 0, -x0], [0, 1, -y0], [0, 0, -c]]),
        "646-Z": Zn,
        "654-sigmaZ": sp.simplify(sp.diff(Zp, px).subs(px, c * B / Za)) * spx,   # ∂Z/∂p_x·σ, Z = −Z_abs
        "672-dZ": sp.simplify(sp.diff(Zp, c).subs(px, c * B / Za)) * dc,
    }


@lru_cache(maxsize=None)
def printed_formulas() -> dict:
    """Every formula of Hanzl §3 as printed (transcribed from seed 002), as sympy expressions.

    Keys are ``"<seed line>-<name>"`` (``"3.1-kx"`` … for §3.1); :func:`derived_formulas` has the
    same keys. The printed sign slips are kept: "+r₁₃c"/"+r₃₃c" (§3.1), "−c dω" (line 482), the
    image-2 signs of p_x (line 532), the dω₁/dκ₁ signs and the b² denominators (lines 540–548),
    "+x₀, +y₀" in C (line 608). In "546-dz" and "540-px" the printed "κ₂" is read as dκ₂.

    Returns
    -------
    dict
        {key: sympy expression or matrix}.

    Raises
    ------
    InputError
        Never (no input).

    References
    ----------
    Hanzl, Fotogrammetrie, Modul 01, §3.1–§3.2.6 (seed 002 lines 344–674).

    Examples
    --------
    >>> sorted(printed_formulas())[:3]
    ['3.1-Z', '3.1-kx', '3.1-ky']
    """
    return _printed()


@lru_cache(maxsize=None)
def derived_formulas() -> dict:
    """The formulas of :func:`printed_formulas` derived by sympy (same keys).

    §3.1 from (2.3) X − X₀ = λR(x − x₀, y − y₀, −c) and the equality of the X equations; §3.2.3.1 from
    the exact collinearity of both images (:func:`y_parallax_coefficients`), "510-py" for the text's
    own definition p_y = y₂ − y₁; §3.2.3.2 from :func:`deformation_coefficients`; §3.2.4 the
    first-order expansion of (1 + dm)dR·(U, V, W); §3.2.5 C mapping (x, y, 1) to (x − x₀, y − y₀, −c);
    §3.2.6 Z = −cB/p_x from the equal X of the normal case and its derivatives by p_x and c.

    Returns
    -------
    dict
        {key: sympy expression or matrix}.

    Raises
    ------
    InputError
        Never (no input).

    References
    ----------
    Hanzl, Fotogrammetrie, Modul 01, §3.1–§3.2.6 (seed 002 lines 344–674).

    Examples
    --------
    >>> import sympy as sp
    >>> P, D = printed_formulas(), derived_formulas()
    >>> sp.simplify(P["514-independent"] - D["514-independent"]), sp.simplify(P["510-py"] + D["510-py"])
    (0, 0)
    """
    return _derived()
