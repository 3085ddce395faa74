"""Hanzl §3 (two images) through the library: truth from sympy, synthetic pairs and OpenCV.

Hanzl, Fotogrammetrie, Modul 01, §3.1–§3.2.6 (seed 002 lines 344–674).
"""

import warnings

import numpy as np
import pytest
import sympy as sp

from photolib import image_pair as ip
from photolib import projective as pj
from photolib.bundle import bundle_adjustment
from photolib.camera import ExteriorOrientation, InteriorOrientation
from photolib.derivations import parallax as D
from photolib.errors import DegenerateGeometryError
from photolib.single_image import project

IO = InteriorOrientation(153.0)
B, H, D_Y = 920.0, 1530.0, 900.0


def gruber_pair(system, truth, noise=0.0, seed=0):
    """Six Gruber points (Fig. 3.3) with ±30 m relief imaged by a pair with the given true elements."""
    rng = np.random.default_rng(seed)
    P = np.array([[0, 0], [B, 0], [0, D_Y], [B, D_Y], [0, -D_Y], [B, -D_Y]], float)
    P = np.column_stack([P, rng.uniform(-30, 30, len(P))])
    t = dict.fromkeys(ip._ALL_RO, 0.0) | truth
    e1 = ExteriorOrientation(0, 0, H, t["omega1"], t["alpha1"], t["kappa1"], order="wak")
    e2 = ExteriorOrientation(B, B * t["b_y"], H + B * t["b_z"], t["omega2"], t["alpha2"], t["kappa2"], order="wak")
    xy1, xy2 = project(P, e1, IO), project(P, e2, IO)
    return xy1 + rng.normal(0, noise, xy1.shape), xy2 + rng.normal(0, noise, xy2.shape)


TRUTH = {"dependent": dict(b_y=0.01, b_z=-0.02, omega2=0.004, alpha2=-0.003, kappa2=0.005),
         "independent": dict(alpha1=0.003, kappa1=-0.004, omega2=0.002, alpha2=-0.005, kappa2=0.006)}


# --- §3.1 closed-form intersection ------------------------------------------------------------------
def test_closed_form_intersection_recovers_points_and_equals_least_squares():
    rng = np.random.default_rng(5)
    P = np.column_stack([rng.uniform(0, 900, 8), rng.uniform(-600, 600, 8), rng.uniform(-40, 40, 8)])
    e1 = ExteriorOrientation(0, 0, 1530, 0.01, -0.02, 0.03, order="wak")
    e2 = ExteriorOrientation(920, 15, 1520, -0.015, 0.02, -0.01, order="wak")
    xy1, xy2 = project(P, e1, IO), project(P, e2, IO)
    closed = ip.intersection_known_eo(xy1, xy2, e1, e2, IO)
    assert np.allclose(closed, P, atol=1e-8)
    lsq = ip.intersect_rays([xy1, xy2], [e1, e2], [IO, IO]).points
    assert np.allclose(closed, lsq, atol=1e-8)


def test_closed_form_printed_plus_c_fails_round_trip():
    """The printed '+r13 c', '+r33 c' (lines 352–360) do not reproduce the ray of (2.3)."""
    P, Dd = D.printed_formulas(), D.derived_formulas()
    assert sp.simplify(P["3.1-kx"] - Dd["3.1-kx"]) != 0
    assert sp.simplify(P["3.1-Z"] - Dd["3.1-Z"]) == 0
    fixed = P["3.1-kx"].subs(sp.Symbol("c", real=True), -sp.Symbol("c", real=True))
    assert sp.simplify(fixed - Dd["3.1-kx"]) == 0          # only the sign of c differs


def test_closed_form_base_along_y_raises_or_warns():
    e1 = ExteriorOrientation(0, 0, 1000)
    e2 = ExteriorOrientation(0, 400, 1000)                    # base along Y: k_x1 = k_x2 for every point
    xy1 = [[20.0, 10.0]]
    xy2 = [[20.0, -30.0]]
    with pytest.raises(DegenerateGeometryError, match="k_x1 = k_x2"):
        ip.intersection_known_eo(xy1, xy2, e1, e2, InteriorOrientation(100.0))
    e2b = ExteriorOrientation(20, 400, 1000)                  # nearly along Y
    xy2b = project(np.array([[200.0, 100.0, 0.0]]), e2b, InteriorOrientation(100.0))
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        out = ip.intersection_known_eo(xy1, xy2b, e1, e2b, InteriorOrientation(100.0))
    assert any(issubclass(w.category, RuntimeWarning) for w in caught)
    assert np.allclose(out, [[200.0, 100.0, 0.0]], atol=1e-6)


# --- §3.2.2 joint orientation count -------------------------------------------------------------------
def test_joint_orientation_count_is_33_not_31():
    counts = ip.orientation_counts(1, 2, 2, 5)
    assert counts == {"observations": 40, "unknowns": 33, "redundancy": 7, "absolute_equations": 9}
    assert 2 * 6 + 5 * 3 + 2 * 1 + 2 * 2 == 33               # the book's own terms
    assert ip.orientation_counts(2, 0, 1)["absolute_equations"] == 7
    assert ip.orientation_counts(0, 2, 3)["absolute_equations"] == 7


def test_joint_adjustment_of_the_count_example_has_redundancy_7():
    """1 full + 2 XY + 2 Z control + 5 new points through the bundle adjustment: r = 40 − 33 = 7."""
    rng = np.random.default_rng(3)
    cams = np.array([[0, 0, 1530, 0.002, -0.003, 0.001], [920, 10, 1525, -0.001, 0.002, 0.004]])
    P = np.column_stack([rng.uniform(50, 870, 10), rng.uniform(-700, 700, 10), rng.uniform(-30, 30, 10)])
    obs = [[j, i, *project(P, ExteriorOrientation(*cams[j], order="wak"), IO)[i]] for j in range(2) for i in range(10)]
    control = {0: P[0]}
    control |= {i: np.array([P[i, 0], P[i, 1], np.nan]) for i in (1, 2)}
    control |= {i: np.array([np.nan, np.nan, P[i, 2]]) for i in (3, 4)}
    cams0 = cams + [5, -5, 3, 0.001, -0.001, 0.002]
    res = bundle_adjustment(np.array(obs), cams0, P + rng.normal(0, 5, P.shape), IO, control=control,
                            sigma_control=1e-4, order="wak")
    # weighted control: 49 observations (40 + 3 + 2·2 + 2·1), 42 unknowns (12 + 10·3) — the same redundancy
    assert res.dof == ip.orientation_counts(1, 2, 2, 5)["redundancy"] == 7
    assert np.allclose(res.points, P, atol=1e-6) and np.allclose(res.cameras, cams, atol=1e-8)


# --- §3.2.3.1 relative orientation from y-parallaxes --------------------------------------------------
def test_y_parallax_coefficients_equal_printed_for_q_y1_minus_y2():
    P, Dd = D.printed_formulas(), D.derived_formulas()
    assert sp.simplify(P["510-py"] - Dd["510-py"]) != 0      # text's p_y = y2 − y1: wrong sign
    assert sp.simplify(P["510-py"] + Dd["510-py"]) == 0      # holds for q = y1 − y2
    for key in ("514-independent", "518-dependent", "494-y1m", "502-y2m"):
        assert sp.simplify(P[key] - Dd[key]) == 0, key
    assert sp.simplify(P["482-ym"] - Dd["482-ym"]) != 0      # "−c dω" misprint
    assert sp.simplify(P["482-xm"] - Dd["482-xm"]) == 0


def test_coefficients_match_numerical_derivative_of_collinearity():
    """Independent check: finite differences of projected points reproduce the sympy coefficients."""
    co = D.y_parallax_coefficients()
    Pm = np.array([[300.0, 400.0, -30.0]])
    h = H + 30.0
    base = dict(omega1=0, alpha1=0, kappa1=0, omega2=0, alpha2=0, kappa2=0, b_y=0, b_z=0)

    def q(t):
        e1 = ExteriorOrientation(0, 0, H, t["omega1"], t["alpha1"], t["kappa1"], order="wak")
        e2 = ExteriorOrientation(B, t["b_y"], H + t["b_z"], t["omega2"], t["alpha2"], t["kappa2"], order="wak")
        return float(project(Pm, e1, IO)[0, 1] - project(Pm, e2, IO)[0, 1])
    x1, y1 = project(Pm, ExteriorOrientation(0, 0, H), IO)[0]
    x2, y2 = project(Pm, ExteriorOrientation(B, 0, H), IO)[0]
    names = {"domega1": "omega1", "dphi1": "alpha1", "dkappa1": "kappa1", "domega2": "omega2", "dphi2": "alpha2",
             "dkappa2": "kappa2", "db_y": "b_y", "db_z": "b_z"}
    syms = {s: sp.Symbol(s, real=True) for s in ("x1", "y1", "x2", "y2", "c", "h")}
    for hz, lib in names.items():
        e = 1e-7
        num = (q(base | {lib: e}) - q(base | {lib: -e})) / (2 * e)
        val = float(co[hz].subs({syms["x1"]: x1, syms["y1"]: y1, syms["x2"]: x2, syms["y2"]: y2,
                                 syms["c"]: 153.0, syms["h"]: h}))
        assert num == pytest.approx(val, rel=1e-5, abs=1e-9), hz


@pytest.mark.parametrize("system", ["dependent", "independent"])
def test_parallax_relative_orientation_recovers_truth(system):
    xy1, xy2 = gruber_pair(system, TRUTH[system])
    full = ip.relative_orientation_parallax(xy1, xy2, IO, system=system)
    for name, value in TRUTH[system].items():
        assert getattr(full, name) == pytest.approx(value, abs=1e-10)
    # the single linear solution is right to first order: its error is O(e²) (halving e quarters it)
    errors = []
    for k in (1.0, 0.5):
        truth = {n: k * v for n, v in TRUTH[system].items()}
        first = ip.relative_orientation_parallax(*gruber_pair(system, truth), IO, system=system, iterate=False)
        errors.append(max(abs(getattr(first, n) - v) for n, v in truth.items()))
    emax = max(abs(v) for v in TRUTH[system].values())
    assert errors[0] < 2 * emax ** 2 and 3.0 < errors[0] / errors[1] < 5.0
    assert np.abs(full.q).max() < 1e-10
    assert full.order == "wak" and full.system == system


@pytest.mark.parametrize("system", ["dependent", "independent"])
def test_parallax_relative_orientation_agrees_with_coplanarity(system):
    xy1, xy2 = gruber_pair(system, TRUTH[system])
    ours = ip.relative_orientation_parallax(xy1, xy2, IO, system=system)
    rigorous = ip.relative_orientation(xy1, xy2, IO, system=system, order="wak")
    for name in ip.RO_NAMES[system]:
        assert getattr(ours, name) == pytest.approx(getattr(rigorous, name), abs=1e-10)
    noisy1, noisy2 = gruber_pair(system, TRUTH[system], noise=0.004, seed=2)
    ours = ip.relative_orientation_parallax(noisy1, noisy2, IO, system=system)
    rigorous = ip.relative_orientation(noisy1, noisy2, IO, system=system, order="wak")
    for name in ip.RO_NAMES[system]:     # different objective functions, same estimate well within m_j
        assert abs(getattr(ours, name) - getattr(rigorous, name)) < 0.1 * ours.std[name]


def test_text_definition_y2_minus_y1_flips_every_element():
    """With p_y = y2 − y1 (line 508) the printed equations return the negated elements (erratum P3)."""
    xy1, xy2 = gruber_pair("dependent", TRUTH["dependent"])
    model = D.y_parallax_model("dependent")
    _, jac = model.compile()
    h = np.full(6, H)
    J = np.asarray(jac(*np.zeros(5), xy1[:, 0], xy1[:, 1], xy2[:, 0], xy2[:, 1], 153.0, h, 0.0)).reshape(5, -1).T
    wrong = np.linalg.lstsq(J, xy2[:, 1] - xy1[:, 1], rcond=None)[0]
    right = np.linalg.lstsq(J, xy1[:, 1] - xy2[:, 1], rcond=None)[0]
    t = TRUTH["dependent"]
    truth = np.array([t["kappa2"], t["omega2"], t["alpha2"], B * t["b_y"], B * t["b_z"]])   # h in m: db in m
    assert np.allclose(right, truth, rtol=0.1, atol=5e-4)
    assert np.allclose(wrong, -right)


# --- §3.2.3.2 model deformation -----------------------------------------------------------------------
def test_model_deformation_rigid_motions():
    xm, ym = np.meshgrid(np.linspace(0, 920, 5), np.linspace(-900, 900, 5))
    assert np.allclose(ip.model_deformation(xm, ym, 1530.0, 920.0, {"dkappa1": 1e-3, "dkappa2": 1e-3}), 0)
    assert np.allclose(ip.model_deformation(xm, ym, 1530.0, 920.0, {"domega1": 1e-3, "domega2": 1e-3}), ym * 1e-3)


def test_model_deformation_equals_exact_intersection_to_first_order():
    """dz from the formula vs. the height change of the intersected rays of a disturbed model (synthetic)."""
    h, b = 1530.0, 920.0
    rng = np.random.default_rng(4)
    P = np.column_stack([rng.uniform(0, b, 6), rng.uniform(-800, 800, 6), np.full(6, -h)])
    e1, e2 = ExteriorOrientation(0, 0, 0, order="wak"), ExteriorOrientation(b, 0, 0, order="wak")
    xy1, xy2 = project(P, e1, IO), project(P, e2, IO)
    for name, lib, d in (("dphi2", "alpha2", 1e-4), ("domega2", "omega2", 1e-4), ("dkappa1", "kappa1", 1e-4),
                         ("db_z", None, 0.05)):
        t = dict(omega1=0, alpha1=0, kappa1=0, omega2=0, alpha2=0, kappa2=0, bz=0.0)
        if lib:
            t[lib] = d
        else:
            t["bz"] = d
        f1 = ExteriorOrientation(0, 0, 0, t["omega1"], t["alpha1"], t["kappa1"], order="wak")
        f2 = ExteriorOrientation(b, 0, t["bz"], t["omega2"], t["alpha2"], t["kappa2"], order="wak")
        Z = ip.intersect_rays([xy1, xy2], [f1, f2], [IO, IO]).points[:, 2]
        dz = ip.model_deformation(P[:, 0], P[:, 1], h, b, {name: d})
        assert np.allclose(Z + h, dz, atol=1e-3 * np.abs(dz).max() + 1e-6), name


def test_printed_deformation_formulas_are_errata():
    P, Dd = D.printed_formulas(), D.derived_formulas()
    for key in ("530-px", "540-px", "546-dz"):
        assert sp.simplify(P[key] - Dd[key]) != 0, key
    co = D.deformation_coefficients()
    assert sp.simplify(co["dkappa1"] + co["dkappa2"]) == 0
    printed = P["546-dz"]
    k1, k2 = sp.Symbol("dkappa1", real=True), sp.Symbol("dkappa2", real=True)
    k = sp.Symbol("k")
    assert sp.simplify(printed.subs({k1: k, k2: k}).subs({s: 0 for s in printed.free_symbols
                                                          if s.name.startswith("d")})) != 0


# --- §3.2.4 absolute orientation ----------------------------------------------------------------------
def test_absolute_orientation_correction_equations_are_first_order_expansion():
    P, Dd = D.printed_formulas(), D.derived_formulas()
    assert (P["592-v"] - Dd["592-v"]).applyfunc(sp.simplify) == sp.zeros(3, 1)
    assert (P["584-mdR"] - Dd["584-mdR"]).applyfunc(sp.simplify) == sp.zeros(3, 3)


def test_absolute_orientation_with_two_planimetric_and_three_height_points():
    rng = np.random.default_rng(8)
    model = rng.uniform(-1, 1, (5, 3)) * [400, 400, 30]
    t = ip.SimilarityTransform(1000.0, 2000.0, 300.0, 0.01, -0.02, 0.3, 1.7, order="wak")
    obj = t.apply(model)
    comp = np.array([[1, 1, 0], [1, 1, 0], [0, 0, 1], [0, 0, 1], [0, 0, 1]], bool)
    fit = ip.absolute_orientation(model, np.where(comp, obj, np.nan), components=comp, order="wak")
    assert np.allclose(fit.apply(model), obj, atol=1e-6)


# --- §3.2.5 fundamental matrix ------------------------------------------------------------------------
def _oriented_pair(n=20):
    io1, io2 = InteriorOrientation(153.0, 0.021, -0.013), InteriorOrientation(151.0, -0.017, 0.009)
    e1 = ExteriorOrientation(0, 0, 1500, 0.01, -0.02, 0.03, order="wak")
    e2 = ExteriorOrientation(600, 12, 1492, -0.015, 0.02, -0.01, order="wak")
    rng = np.random.default_rng(1)
    P = np.column_stack([rng.uniform(-300, 900, n), rng.uniform(-400, 400, n), rng.uniform(-50, 50, n)])
    return io1, io2, e1, e2, project(P, e1, io1), project(P, e2, io2)


def test_hanzl_fundamental_matrix_equals_projective_and_opencv():
    cv2 = pytest.importorskip("cv2")
    io1, io2, e1, e2, xy1, xy2 = _oriented_pair()
    F = pj.fundamental_coplanarity(io1, e1.matrix, io2, e2.matrix, e2.center - e1.center)
    h1, h2 = np.column_stack([xy1, np.ones(len(xy1))]), np.column_stack([xy2, np.ones(len(xy2))])
    Fn = F / np.linalg.norm(F)
    assert np.abs(np.einsum("ni,ij,nj->n", h1, Fn, h2)).max() < 1e-12
    assert np.linalg.matrix_rank(Fn, tol=1e-9) == 2
    ref = pj.fundamental_from_orientation(io1, e1, io2, e2, layout="x1Fx2")
    assert min(np.abs(Fn - ref).max(), np.abs(Fn + ref).max()) < 1e-12
    Fcv, _ = cv2.findFundamentalMat(xy2.astype(np.float64), xy1.astype(np.float64), cv2.FM_8POINT)
    Fcv = Fcv / np.linalg.norm(Fcv)                             # OpenCV: x2ᵀFx1 with (pts1, pts2) = (xy2, xy1)
    assert min(np.abs(Fn - Fcv).max(), np.abs(Fn + Fcv).max()) < 1e-5


def test_printed_interior_matrix_breaks_the_condition():
    io1, io2, e1, e2, xy1, xy2 = _oriented_pair()
    wrong = lambda io: np.array([[1, 0, io.x0], [0, 1, io.y0], [0, 0, -io.f]])  # noqa: E731 — line 608
    B = pj.skew_matrix(e2.center - e1.center)
    Fw = wrong(io1).T @ e1.matrix.T @ B @ e2.matrix @ wrong(io2)
    h1, h2 = np.column_stack([xy1, np.ones(len(xy1))]), np.column_stack([xy2, np.ones(len(xy2))])
    assert np.abs(np.einsum("ni,ij,nj->n", h1, Fw / np.linalg.norm(Fw), h2)).max() > 1e-4


def test_eight_unknowns_need_the_plus_one():
    """f33 = 1: the 8 coefficients solve x1x2f11 + … + y2f32 + 1 = 0 (the printed form drops the +1)."""
    io1, io2, e1, e2, xy1, xy2 = _oriented_pair(12)
    F = pj.fundamental_coplanarity(io1, e1.matrix, io2, e2.matrix, e2.center - e1.center)
    F = F / F[2, 2]
    (x1, y1), (x2, y2) = xy1.T, xy2.T
    rows = np.column_stack([x1 * x2, x1 * y2, x1, x2 * y1, y1 * y2, y1, x2, y2])
    f = np.linalg.lstsq(rows, -np.ones(len(x1)), rcond=None)[0]
    assert np.allclose(np.append(f, 1).reshape(3, 3), F, rtol=1e-6, atol=1e-9)
    assert np.allclose(pj.fundamental_matrix(xy1, xy2, method="book", layout="x1Fx2"), F, rtol=1e-6, atol=1e-9)
    f0 = np.linalg.lstsq(rows, np.zeros(len(x1)), rcond=None)[0]           # as printed: only the trivial solution
    assert np.allclose(f0, 0)


# --- §3.2.6 normal case -------------------------------------------------------------------------------
def test_normal_case_formulas_and_example_3_1():
    P, Dd = D.printed_formulas(), D.derived_formulas()
    for key in ("646-Z", "654-sigmaZ", "672-dZ"):
        assert sp.simplify(P[key] - Dd[key]) == 0, key
    ms, c, bz, x, s = 10000.0, 150.0, 1 / 1.6, 50.0, 0.010
    sX, sY, sZ = ip.normal_case_accuracy(ms * c / 1000, c, c * bz, s, s, s, x=x, y=x)
    assert (round(sX, 2), round(sZ, 2)) == (0.11, 0.16)
    sX, _, sZ = ip.normal_case_accuracy(ms * 300 / 1000, 300, 300 / 3.2, s, s, s, x=x, y=x)
    assert round(sZ, 2) == 0.32 and round(sX, 4) == 0.1133      # the book prints 0.15
    sX, _, _ = ip.normal_case_accuracy(ms * 300 / 1000, 300, 300 / 3.2, s, s, s, x=100.0, y=100.0)
    assert round(sX, 2) == 0.15                                  # x/c kept at 1/3
