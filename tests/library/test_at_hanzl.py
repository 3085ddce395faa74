"""Hanzl §4–§5 through the library: the AP models against sympy, Ebner's orthogonality, the AP option of the
self-calibrating bundle (sympy-derived columns, exact recovery of a simulated deformation, the t-test
elimination), the accuracy rules, the close-range examples, the redundancy numbers and the DLT (§5.3).
Truth: sympy, synthetic ground truth, scipy."""

import numpy as np
import pytest
import sympy as sp
from scipy import stats

from photolib import additional_parameters as ap
from photolib import bundle, projective, synthetic, terrestrial
from photolib import triangulation_layouts as tl
from photolib.camera import ExteriorOrientation, InteriorOrientation
from photolib.derivations import hanzl_at as D
from photolib.derivations.symbols import f, x, y
from photolib.errors import DegenerateGeometryError, InputError
from photolib.synthetic import Observations

B = 92.0


EBNER_TRUE = {"g1": 4e-5, "g3": -8e-7, "g5": 1.5e-6, "g11": 6e-10}


def ebner_simulation(seed=5, noise_seed=7, sigma=0.002, select=True):
    """A seeded 3 × 6 wide-angle block (c = 153 mm, 23 cm, m_s = 10 000) whose images carry EBNER_TRUE."""
    blk = synthetic.aerial_block(3, 6, f=153.0, frame_size=230.0, flying_height=1530.0, points_per_image=40,
                                 sigma=0.0, relief=60.0, seed=seed)
    o = blk.observations
    xy = ap.invert_ap("hanzl17", o.xy, EBNER_TRUE, b=B, r0=0.0, tol=1e-14)
    xy = xy + np.random.default_rng(noise_seed).normal(0.0, sigma, xy.shape)
    obs = Observations(o.image, o.point, xy)
    cams0, pts0 = blk.start_values(seed=2)
    kw = dict(calibrate=(), ap_names=[f"g{i}" for i in range(1, 13)], ap_base=B, control=blk.control_values(),
              order=blk.order, sigma_image=sigma)
    full = bundle.self_calibrating_bundle_adjustment(obs, cams0, pts0, blk.io, additional_parameters="hanzl17", **kw)
    if not select:
        return full, None, [], blk
    sel, removed = bundle.select_additional_parameters(obs, cams0, pts0, blk.io, additional_parameters="hanzl17",
                                                       **kw)
    return full, sel, removed, blk


def _sym(model):
    if model == "hanzl17":
        dx, dy, p = D.hanzl17_symbolic()
        extra, sy_extra = {"b": 1.3, "r0": 0.7}, (D.B_EBNER, D.R0)
    elif model == "brown18":
        dx, dy, p = D.brown18_symbolic()
        extra, sy_extra = {"f": 2.5}, (f,)
    else:
        dx, dy, p = D.murai_symbolic()
        extra, sy_extra = {}, ()
    return dx, dy, p, extra, sy_extra


@pytest.mark.parametrize("model", ap.HANZL_MODELS)
def test_models_and_bases_equal_their_sympy_forms(model):
    dx, dy, p, extra, sy_extra = _sym(model)
    rng = np.random.default_rng(3)
    xy = rng.uniform(-2, 2, (25, 2))
    vals = rng.normal(0, 0.1, len(p))
    fn = sp.lambdify((x, y) + sy_extra + tuple(p), [dx, dy], "numpy")
    ref = np.column_stack(fn(xy[:, 0], xy[:, 1], *extra.values(), *vals))
    assert np.allclose(ap.ap_corrections(model, xy, vals, **extra), ref, atol=1e-12)
    J = sp.lambdify((x, y) + sy_extra, sp.Matrix([dx, dy]).jacobian(sp.Matrix(p)), "numpy")
    Bm = ap.ap_basis(model, xy, **extra)
    for i, (xi, yi) in enumerate(xy):
        assert np.allclose(Bm[i], np.array(J(xi, yi, *extra.values()), dtype=float), atol=1e-12)


def test_named_functions_equal_ap_corrections():
    xy = np.array([[10.0, -20.0], [50.0, 30.0]])
    g = {f"g{i}": 1e-6 * i for i in range(1, 18)}
    assert np.allclose(ap.hanzl17(xy, g, B, 40.0), ap.ap_corrections("hanzl17", xy, g, b=B, r0=40.0))
    a = {f"a{i}": 1e-7 * i for i in range(1, 19)}
    assert np.allclose(ap.brown18(xy, a, 50.0), ap.ap_corrections("brown18", xy, a, f=50.0))
    m = dict(zip(ap.MURAI_NAMES, np.arange(1, 9) * 1e-7))
    assert np.allclose(ap.murai(xy, m), ap.ap_corrections("murai", xy, m))


def test_ebner_orthogonal_on_the_gruber_grid_and_to_the_eo_fields():
    grid = np.array([(i * B, j * B) for i in (-1, 0, 1) for j in (-1, 0, 1)])
    Bm = ap.ap_basis("hanzl17", grid, b=B, r0=0.0)[:, :, :12]
    G = np.einsum("nci,ncj->ij", Bm, Bm)
    assert np.max(np.abs(G - np.diag(np.diag(G)))) < 1e-12 * np.max(np.abs(G))
    c = 153.0                               # numeric EO fields of a vertical image (independent of the sympy ones)
    gx, gy = grid[:, 0], grid[:, 1]
    eo = [(np.ones(9), np.zeros(9)), (np.zeros(9), np.ones(9)), (gx, gy), (gx * gy / c, c + gy**2 / c),
          (c + gx**2 / c, gx * gy / c), (gy, -gx)]
    E = np.stack([np.column_stack(e) for e in eo], axis=-1)          # (9, 2, 6)
    prod = np.einsum("nci,ncj->ij", Bm, E)
    assert np.max(np.abs(prod)) < 1e-9 * np.sqrt(np.max(np.abs(G)))
    assert D.ebner_gram().is_diagonal() and D.ebner_eo_products().is_zero_matrix


def test_radial_terms_vanish_at_r0_and_are_independent():
    r0 = 80.0
    ang = np.linspace(0, 2 * np.pi, 7)
    on = np.column_stack([r0 * np.cos(ang), r0 * np.sin(ang)])
    Bm = ap.ap_basis("hanzl17", on, b=B, r0=r0)
    assert np.max(np.abs(Bm[:, :, 12:15])) < 1e-6 * r0**7
    rr = np.column_stack([np.linspace(5, 115, 20), np.zeros(20)])
    cols = ap.ap_basis("hanzl17", rr, b=B, r0=r0)[:, 0, 12:15]
    assert np.linalg.matrix_rank(cols / np.abs(cols).max(axis=0)) == 3
    # the printed (OCR) form would be one field: x(g13 + g14 + g15)(r² − r0²)
    dx, _, g = D.hanzl17_symbolic()
    printed = x * (g[12] + g[13] + g[14]) * (x**2 + y**2 - D.R0**2)
    assert sp.expand(dx.subs({p: 0 for p in g[:12] + g[15:]}) - printed) != 0


def test_bundle_ap_columns_are_minus_the_basis_by_sympy():
    # the corrected coordinate is x_m + dx(x_m; g); the residual L = computed − (x_m + dx) (3.6.1), so
    # ∂L/∂g_i = −∂dx/∂g_i: the columns the bundle appends are −ap_basis
    dx, dy, g = D.hanzl17_symbolic()
    xc = sp.Symbol("x_computed")
    L = xc - (x + dx)
    for gi in g:
        assert sp.expand(sp.diff(L, gi) + sp.diff(dx, gi)) == 0


def test_noise_free_deformation_is_recovered_exactly():
    blk = synthetic.aerial_block(2, 5, f=153.0, frame_size=230.0, flying_height=1530.0, points_per_image=30,
                                 sigma=0.0, relief=60.0, seed=5)
    g_true = {"g1": 4e-5, "g3": -8e-7, "g5": 1.5e-6, "g11": 6e-10, "g16": 2e-6}
    o = blk.observations
    xy = ap.invert_ap("hanzl17", o.xy, g_true, b=B, r0=0.0, tol=1e-14)
    cams0, pts0 = blk.start_values(seed=2)
    res = bundle.self_calibrating_bundle_adjustment(
        Observations(o.image, o.point, xy), cams0, pts0, blk.io, calibrate=(), additional_parameters="hanzl17",
        ap_names=[f"g{i}" for i in range(1, 13)] + ["g16"], ap_base=B, control=blk.control_values(),
        order=blk.order, sigma_image=0.002)
    assert res.mu < 1e-9
    for nm, v in res.ap_values.items():
        assert abs(v - g_true.get(nm, 0.0)) < 1e-7 * max(abs(g_true.get(nm, 0.0)), 1e-30) + 1e-15
    assert np.allclose(res.points, blk.points, atol=1e-5)
    assert res.ap_model == "hanzl17" and res.ap_cofactors.shape == (13, 13)


def test_ebner_parameters_recover_a_simulated_deformation():
    full, sel, removed, _ = ebner_simulation(seed=5, noise_seed=7, sigma=0.002)
    rep = bundle.additional_parameter_tests(full)
    for nm, v, s in zip(rep.names, rep.values, rep.std):
        assert abs(v - EBNER_TRUE.get(nm, 0.0)) < 3.5 * s            # each within 3.5σ of the truth
    assert set(sel.ap_values) == set(EBNER_TRUE)                      # the simulated ones kept ...
    assert {nm for nm, why in removed} == {f"g{i}" for i in range(1, 13)} - set(EBNER_TRUE)   # ... the rest dropped
    rep_sel = bundle.additional_parameter_tests(sel)
    assert rep_sel.significant.all()


def test_t_test_quantile_and_correlations_against_scipy():
    full, _, _, _ = ebner_simulation(select=False)
    rep = bundle.additional_parameter_tests(full, alpha=0.05)
    assert np.isclose(rep.quantile, stats.t.ppf(0.975, full.dof))
    Q = full.ap_cofactors
    s = np.sqrt(np.diag(Q))
    assert np.allclose(full.correlations.among, Q / np.outer(s, s))
    assert np.allclose(rep.t, rep.values / (full.mu * s))


def test_accuracy_rules():
    sxy, sz = tl.at_accuracy_rule(10000, 1530.0)
    assert np.isclose(sxy, 5e-6 * 10000) and np.isclose(sz, 0.00005 * 1530.0)
    mxy, mz, m = tl.gnss_at_accuracy(10000, 5.0)
    assert np.allclose([mxy, mz, m], [1.5 * 0.05, 2.2 * 0.05, 0.05])


def test_close_range_examples():
    assert np.isclose(terrestrial.close_range_point_sigma(0.7, 5e-3, 400.0, 2), 0.7 * 5e-3 * 400 / np.sqrt(2))
    assert round(terrestrial.close_range_point_sigma(0.7, 5e-3, 400.0, 2), 1) == 1.0
    assert np.isclose(terrestrial.close_range_point_sigma(2.0, 15e-3, 400.0, 1), 12.0)


def _dlt_scene(n=20, seed=0):
    rng = np.random.default_rng(seed)
    XYZ = np.column_stack([rng.uniform(-5, 5, n), rng.uniform(-3, 3, n), rng.uniform(-2, 2, n)])
    io = InteriorOrientation(f=50.0, x0=0.2, y0=-0.1)
    eo = ExteriorOrientation(0.0, 0.0, 25.0, 0.05, -0.03, 0.4)
    return XYZ, io, eo


def test_redundancy_numbers_sum_and_relative_redundancy():
    XYZ, io, eo = _dlt_scene(20)
    L = projective.dlt_from_orientation(io, eo)
    xy = projective.dlt_project(L, XYZ)
    A, _ = projective.dlt_design(XYZ, xy)
    m, n = A.shape
    Qvv = np.eye(m) - A @ np.linalg.solve(A.T @ A, A.T)
    ri = np.diag(Qvv)
    assert np.isclose(ri.sum(), m - n) and (ri > -1e-12).all() and (ri < 1 + 1e-12).all()
    rbar = terrestrial.relative_redundancy(ri)
    assert np.isclose(rbar, (m - n) / m)
    assert (m - n) / n > 1                         # the printed r/n is not a share in [0, 1]
    assert round((m - n) / n, 2) == 2.64           # the number quoted in textbook/ch11_hanzl.toml


def test_dlt_eleven_coefficients_and_linear_intersection():
    XYZ, io, eo = _dlt_scene(12, seed=1)
    eo2 = ExteriorOrientation(8.0, 0.0, 25.0, 0.05, 0.25, 0.4)
    L1, L2 = projective.dlt_from_orientation(io, eo), projective.dlt_from_orientation(io, eo2)
    xy1, xy2 = projective.dlt_project(L1, XYZ), projective.dlt_project(L2, XYZ)
    res = projective.dlt_resection(XYZ, xy1)
    assert res.L.size == 11 and np.allclose(res.L, L1, rtol=1e-7, atol=1e-9)
    o = projective.orientation_from_dlt(res.L)
    assert np.isclose(o.fx, 50.0) and np.allclose(o.center, eo.vector[:3], atol=1e-6)
    X = projective.dlt_intersection([L1, L2], [xy1, xy2])
    assert np.allclose(X.XYZ, XYZ, atol=1e-7)
    with pytest.raises((DegenerateGeometryError, InputError)):
        flat = XYZ.copy()
        flat[:, 2] = 0.0
        projective.dlt_resection(flat, projective.dlt_project(L1, flat))
