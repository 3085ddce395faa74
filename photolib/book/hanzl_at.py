"""Adapters for Hanzl, Fotogrammetrie, Modul 01, §4 (aerotriangulation) and §5 (close range).

Seed ``002_d5f7929691601478.txt`` lines 676–1044. Entries: ``textbook/ch03_hanzl.toml`` (§4, filed under
Chibunichev Chapter 3) and ``textbook/ch11_hanzl.toml`` (§5, under Chapter 11). Inputs → library calls
(:mod:`photolib.additional_parameters`, :mod:`photolib.bundle`, :mod:`photolib.projective`,
:mod:`photolib.terrestrial`, :mod:`photolib.triangulation_layouts`); the sympy forms are in
:mod:`photolib.derivations.hanzl_at`.
"""

from __future__ import annotations

import numpy as np
import sympy as sp

from .. import additional_parameters as apm
from .. import bundle, projective, synthetic, terrestrial
from .. import strip_triangulation as st
from ..camera import ExteriorOrientation, InteriorOrientation
from ..derivations import hanzl_at as D
from ..derivations.collinearity import collinearity_terms
from ..derivations.distortion import brown_correction_terms
from ..derivations.rotation import rotation_matrix_symbolic
from ..derivations.symbols import EO_SYMBOLS, X, Y, Z, Xs, Ys, Zs, f, x, x0, y, y0
from ..rotation import rotation_angles
from ..single_image import project
from ..synthetic import Observations
from ..triangulation_layouts import at_accuracy_rule, correction_equation_system, gnss_at_accuracy
from ._exact import zero as _zero

__all__ = ["formula_check", "ebner_base", "close_range_example", "dlt_count", "gnss_rule_example",
           "at_rule_example"]


def _ok(flag) -> dict:
    return {"printed_equals_derived": bool(flag)}



def _hanzl_collinearity():
    """Hanzl's F(x), G(y) (lines 690–694) with r_ij of R = R_ω R_φ R_κ (order "wak")."""
    R = rotation_matrix_symbolic("wak")
    d = sp.Matrix([X - Xs, Y - Ys, Z - Zs])
    den = R[0, 2] * d[0] + R[1, 2] * d[1] + R[2, 2] * d[2]
    F = x0 - f * (R[0, 0] * d[0] + R[1, 0] * d[1] + R[2, 0] * d[2]) / den
    G = y0 - f * (R[0, 1] * d[0] + R[1, 1] * d[1] + R[2, 1] * d[2]) / den
    return F, G


def formula_check(inputs: dict) -> dict:
    """Compare one printed formula of Hanzl §4–§5 with its sympy derivation (``inputs["item"]``)."""
    item = inputs["item"]
    if item == "collinearity":
        F, G = _hanzl_collinearity()
        t = collinearity_terms("wak")
        ok = _zero(sp.simplify(F - (x0 - f * t[0] / t[2]))) and _zero(sp.simplify(G - (y0 - f * t[1] / t[2])))
    elif item == "io-derivatives":
        # §5.2: a1 = ∂F/∂x0 = 1, ∂F/∂c = (F − x0)/c, and no y0 in F (a1 of v_y is ∂G/∂y0 = 1)
        F, G = _hanzl_collinearity()
        ok = (sp.diff(F, x0) == 1 and sp.diff(F, y0) == 0 and sp.diff(G, y0) == 1
              and _zero(sp.simplify(sp.diff(F, f) - (F - x0) / f)) and _zero(sp.simplify(sp.diff(G, f) - (G - y0) / f))
              and len(EO_SYMBOLS) + 3 + 2 == 11)
    elif item == "ebner":
        ok = D.ebner_gram().is_diagonal() and D.ebner_eo_products().is_zero_matrix
    elif item == "radial":
        # as printed: the three terms all x(r² − r₀²); derived (our reading): r², r⁴, r⁶
        dx, dy, g = D.hanzl17_symbolic()
        r2 = x**2 + y**2
        printed = x * (g[12] + g[13] + g[14]) * (r2 - D.R0**2)
        zero = {p: 0 for p in g[:12] + g[15:]}
        ok = _zero(dx.subs(zero) - printed)
    elif item in ("tangential", "brown-conrady"):
        dx, dy, g = D.hanzl17_symbolic()
        p1, p2 = sp.symbols("p_1 p_2", real=True)
        bx, by = brown_correction_terms(x, y)
        if item == "tangential":
            keep = {g[15]: p1, g[16]: p2}
            sub = {p: 0 for p in g if p not in keep}
            ok = _zero(dx.subs(sub).xreplace(keep) - bx.subs({sp.Symbol(f"k_{i}", real=True): 0 for i in (1, 2, 3)})) \
                and _zero(dy.subs(sub).xreplace(keep) - by.subs({sp.Symbol(f"k_{i}", real=True): 0 for i in (1, 2, 3)}))
        else:
            K1, K2, K3, P1, P2 = sp.symbols("K_1 K_2 K_3 P_1 P_2", real=True)
            r2 = x**2 + y**2
            px = x * (K1 * r2 + K2 * r2**2 + K3 * r2**3) + P1 * (r2 + 2 * x**2) + 2 * P2 * x * y
            py = y * (K1 * r2 + K2 * r2**2 + K3 * r2**3) + P2 * (r2 + 2 * y**2) + 2 * P1 * x * y
            to = {sp.Symbol("k_1", real=True): K1, sp.Symbol("k_2", real=True): K2, sp.Symbol("k_3", real=True): K3,
                  sp.Symbol("p_1", real=True): P1, sp.Symbol("p_2", real=True): P2}
            ok = _zero(px - bx.xreplace(to)) and _zero(py - by.xreplace(to))
    elif item in ("brown18", "murai"):
        # the printed terms are independent functions: the Jacobian of the fields over a 5 × 5 grid has full rank
        dx, dy, params = D.brown18_symbolic() if item == "brown18" else D.murai_symbolic()
        grid = [(sp.Rational(i, 2), sp.Rational(j, 3)) for i in range(-2, 3) for j in range(-2, 3)]
        rows = []
        for gx, gy in grid:
            for comp in (dx, dy):
                rows.append([sp.diff(comp, p).subs({x: gx, y: gy, f: 3}) for p in params])
        ok = sp.Matrix(rows).rank() == len(params)
    elif item == "dlt-v":
        L = sp.symbols("L_1:12", real=True)
        num_x = L[0] * X + L[1] * Y + L[2] * Z + L[3]
        den = L[8] * X + L[9] * Y + L[10] * Z + 1
        printed = L[0] * X + L[1] * Y + L[2] * Z + L[3] - L[8] * X * x - L[9] * Y * x - L[10] * Z * x - x
        ok = _zero(printed - (num_x - x * den))
    elif item == "dlt-intersection":
        L = sp.symbols("L_1:12", real=True)
        den = L[8] * X + L[9] * Y + L[10] * Z + 1
        num_x = L[0] * X + L[1] * Y + L[2] * Z + L[3]
        num_y = L[4] * X + L[5] * Y + L[6] * Z + L[7]
        px = (L[0] - L[8] * x) * X + (L[1] - L[9] * x) * Y + (L[2] - L[10] * x) * Z + L[3]
        py = (L[4] - L[8] * y) * X + (L[5] - L[9] * y) * Y + (L[6] - L[10] * y) * Z + L[7]
        ok = _zero((px - x) - (num_x - x * den)) and _zero((py - y) - (num_y - y * den))
    elif item == "redundancy":
        r, m, n = sp.symbols("r m n", positive=True)
        ok = sp.simplify(r / n - r / m) == 0        # printed r/n against the mean redundancy number r/m
    else:
        raise KeyError(f"unknown formula item {item!r}")
    return _ok(ok)


def ebner_base(inputs: dict) -> dict:
    """b = format·(1 − p): 92 mm for 23 cm and 60 % (line 774)."""
    return {"b": inputs["format_mm"] * (1 - inputs["overlap_percent"] / 100.0)}


def close_range_example(inputs: dict) -> dict:
    """σ_p = q σ_x m_s/√k with m_s = distance / c (§5.4, lines 925–931)."""
    m_s = inputs["distance_m"] * 1000.0 / inputs["c_mm"]
    sp_mm = terrestrial.close_range_point_sigma(inputs["q"], inputs["sigma_x_um"] * 1e-3, m_s, inputs["k"])
    return {"m_s": m_s, "sigma_p": sp_mm}


def dlt_count(inputs: dict) -> dict:
    """11 DLT coefficients = 6 EO + 3 IO + scale difference + skew (line 888), counted on the library's output."""
    io = InteriorOrientation(f=inputs["c_mm"], x0=0.1, y0=-0.2)
    eo = ExteriorOrientation(1.0, 2.0, 30.0, 0.1, -0.05, 0.2)
    L = projective.dlt_from_orientation(io, eo, fx=inputs["c_mm"], fy=1.01 * inputs["c_mm"], skew=0.3)
    o = projective.orientation_from_dlt(L)
    n_eo = o.eo.vector.size
    n_io = len((o.x0, o.y0, o.fx))
    n_extra = len((o.fy, o.skew))
    return {"coefficients": L.size, "EO": n_eo, "IO": n_io, "extra": n_extra, "sum": n_eo + n_io + n_extra}


def at_rule_example(inputs: dict) -> dict:
    """σ_XY, σ_Z of the §4.3 rule for the given scale and height (illustration)."""
    sxy, sz = at_accuracy_rule(inputs["m_s"], inputs["h_m"])
    return {"sigma_XY": sxy, "sigma_Z": sz}


def gnss_rule_example(inputs: dict) -> dict:
    """m_XY, m_Z of INPHO's rule (§4.5) for the given scale and σ₀ (illustration)."""
    mxy, mz, mxyz = gnss_at_accuracy(inputs["m_s"], inputs["sigma0_um"])
    return {"m_XY": mxy, "m_Z": mz, "m_XYZ": mxyz}


# --- simulations for the appendix (seeded; each a few seconds at most) ------------------------------------------
EBNER_TRUE = {"g1": 4e-5, "g3": -8e-7, "g5": 1.5e-6, "g11": 6e-10}
"""The simulated image deformation of the appendix (Hanzl's g's; a few µm to tens of µm in the image)."""


def wide_angle_block(seed: int = 5, sigma: float = 0.0, points_per_image: int = 40, n_strips: int = 3,
                     images_per_strip: int = 6):
    """A small wide-angle block: c = 153 mm, 23 × 23 cm, m_s = 10 000 (h = 1 530 m), 60 % / 30 % overlap."""
    return synthetic.aerial_block(n_strips, images_per_strip, f=153.0, frame_size=230.0, flying_height=1530.0,
                                  points_per_image=points_per_image, sigma=sigma, relief=60.0, seed=seed)


def ebner_simulation(g_true=None, *, seed: int = 5, noise_seed: int = 7, sigma: float = 0.002, select: bool = True):
    """Self-calibration with Ebner's 12 parameters on a block whose images carry the deformation ``g_true``.

    The measured coordinates are the ideal projections moved so that measured + dx(measured) = ideal
    (:func:`photolib.additional_parameters.invert_ap`), plus seeded noise σ (mm). Returns
    ``(full, selected, removed, block)``: the adjustment with all twelve, the one after the elimination
    (``None`` if ``select`` is False) and the removals.
    """
    g_true = EBNER_TRUE if g_true is None else g_true
    blk = wide_angle_block(seed)
    o = blk.observations
    xy = apm.invert_ap("hanzl17", o.xy, g_true, b=92.0, r0=0.0, tol=1e-14)
    xy = xy + np.random.default_rng(noise_seed).normal(0.0, sigma, xy.shape)
    obs = Observations(o.image, o.point, xy)
    cams0, pts0 = blk.start_values(seed=2)
    kw = dict(calibrate=(), additional_parameters="hanzl17", ap_names=[f"g{i}" for i in range(1, 13)], ap_base=92.0,
              control=blk.control_values(), order=blk.order, sigma_image=sigma)
    full = bundle.self_calibrating_bundle_adjustment(obs, cams0, pts0, blk.io, **kw)
    if not select:
        return full, None, [], blk
    kw.pop("additional_parameters")
    sel, removed = bundle.select_additional_parameters(obs, cams0, pts0, blk.io, additional_parameters="hanzl17",
                                                       **kw)
    return full, sel, removed, blk


def at_rule_simulation(seeds=(0, 1, 2), sigma_um: float = 3.0) -> dict:
    """RMS errors of the free points of the seeded wide-angle block against the §4.3 rule.

    Signalised points are modelled by Gaussian image noise σ (2–4 µm in the text: 3 µm here) and no
    systematic error; the block is adjusted by :func:`photolib.bundle.bundle_adjustment` with its
    perimeter control fixed. Returns the pooled RMS of X, Y (per coordinate) and Z in metres, the
    rule's values and the image-space RMS (µm) of the planimetric errors divided by m_s.
    """
    exy, ez = [], []
    for s in seeds:
        blk = wide_angle_block(s, sigma=sigma_um * 1e-3, points_per_image=30)
        cams0, pts0 = blk.start_values(seed=s + 1)
        res = bundle.bundle_adjustment(blk.observations, cams0, pts0, blk.io, control=blk.control_values(),
                                       order=blk.order, sigma_image=sigma_um * 1e-3)
        free = np.setdiff1d(np.arange(len(blk.points)), blk.control)
        e = res.points[free] - blk.points[free]
        exy.append(e[:, :2].ravel())
        ez.append(e[:, 2])
    rxy = float(np.sqrt(np.mean(np.concatenate(exy) ** 2)))
    rz = float(np.sqrt(np.mean(np.concatenate(ez) ** 2)))
    sxy, sz = at_accuracy_rule(10000.0, 1530.0)
    return {"rms_XY": rxy, "rms_Z": rz, "rule_XY": sxy, "rule_Z": sz, "rms_XY_image_um": rxy / 10000.0 * 1e6,
            "rms_Z_percent_h": rz / 1530.0 * 100}


def bundle_vs_models(seeds=(4, 5, 6), sigma_um: float = 3.0) -> dict:
    """Bundle (§4.1) against independent models (§4.2) on the same seeded 2 × 6 wide-angle layout.

    Both use the same image measurements and the same eight full control points (corners, ends of the
    middle row, the middle of the outer rows); the errors of the remaining tie points are pooled over the
    seeds. Returns RMS X/Y (per coordinate) and Z of both, m.
    """
    control_at = [(0, 0.5), (5, 0.5), (0, -1.5), (5, -1.5), (0, -0.5), (5, -0.5), (3, 0.5), (3, -1.5)]
    out = {"bundle": ([], []), "models": ([], [])}
    for s in seeds:
        blk = st.layout_block(2, 6, f=153.0, frame_size=230.0, flying_height=1530.0, sigma=sigma_um * 1e-3,
                              principal_rows=True, seed=s)
        labels = [blk.point_at(*g) for g in control_at]
        index = {p: i for i, p in enumerate(blk.point_labels)}
        ctrl = {index[p]: blk.points[index[p]] for p in labels}
        rng = np.random.default_rng(s)
        cams0 = blk.cameras.copy()
        cams0[:, :3] += rng.normal(0, 5.0, (blk.n_images, 3))
        cams0[:, 3:] += rng.normal(0, 0.005, (blk.n_images, 3))
        pts0 = blk.points + rng.normal(0, 5.0, blk.points.shape)
        for i, v in ctrl.items():
            pts0[i] = v
        res = bundle.bundle_adjustment(blk.observations, cams0, pts0, blk.io, control=ctrl, order=blk.order,
                                       sigma_image=sigma_um * 1e-3)
        free = np.array([i for i in range(len(blk.points)) if i not in ctrl])
        eb = res.points[free] - blk.points[free]
        um = st.adjust_independent_units(st.layout_models(blk), {p: blk.truth([p])[0] for p in labels},
                                         order=blk.order)
        em = np.array([um.points[blk.point_labels[i]] for i in free]) - blk.points[free]
        for key, e in (("bundle", eb), ("models", em)):
            out[key][0].append(e[:, :2].ravel())
            out[key][1].append(e[:, 2])
    rms = {}
    for key, (xy, z) in out.items():
        rms[key] = (float(np.sqrt(np.mean(np.concatenate(xy) ** 2))), float(np.sqrt(np.mean(np.concatenate(z) ** 2))))
    return rms


def normal_patterns(seed: int = 4):
    """Non-zero patterns of N = AᵀA for the bundle (fig. 4.3 left) and for independent models (right).

    A small 1 × 4 layout; the bundle system has its image unknowns first, then the points
    (:func:`photolib.triangulation_layouts.correction_equation_system`); the models system has 7
    unknowns per model (:func:`photolib.strip_triangulation.unit_equations`) — in photolib's
    formulation of §3.4 the tie points are eliminated (model coordinates averaged), so its N holds
    the model blocks only. Returns ``(N_bundle != 0, n_eo_columns, N_models != 0)``.
    """
    blk = st.layout_block(1, 4, f=153.0, frame_size=230.0, flying_height=1530.0, seed=seed)
    sysb = correction_equation_system(blk)
    Ab = (np.asarray(sysb.A) != 0).astype(np.int64)
    models = st.layout_models(blk)
    control = {p: blk.truth([p])[0] for p in (blk.point_at(0, 0.35 * blk.footprint / blk.strip_spacing),
                                              blk.point_at(3, 0.35 * blk.footprint / blk.strip_spacing),
                                              blk.point_at(0, -0.35 * blk.footprint / blk.strip_spacing),
                                              blk.point_at(3, -0.35 * blk.footprint / blk.strip_spacing))}
    x0 = st.initial_transforms(models, control)
    B, _, _ = st.unit_equations(models, x0, control)
    nz = np.asarray(B) != 0
    # structural pattern: a row involves a model when any of its 7 derivatives is non-zero
    unit = nz.reshape(nz.shape[0], -1, 7).any(axis=2)
    Am = np.repeat(unit, 7, axis=1).astype(np.int64)
    return (Ab.T @ Ab) != 0, int(sysb.n_eo), (Am.T @ Am) != 0


def convergent_network(seed: int = 0, sigma_um: float = 2.0, n_stations: int = 8, distance: float = 20.0, arc: float = 70.0,
                       io: InteriorOrientation | None = None):
    """A seeded convergent multi-station close-range network (Hanzl fig. 5.3): a 12 × 4 × 8 m object seen
    from ``n_stations`` stations on an arc at ``distance`` m, c = 50 mm, 36 × 24 mm frame.

    Returns ``(observations, cameras, points, control_indices, io, order)`` with the truth in
    ``cameras``/``points``; the observations carry Gaussian noise σ (µm).
    """
    rng = np.random.default_rng(seed)
    io = InteriorOrientation(f=50.0, x0=0.05, y0=-0.03) if io is None else io
    order = "wak"
    pts = np.column_stack([rng.uniform(-6, 6, 60), rng.uniform(0, 4, 60), rng.uniform(0, 8, 60)])
    centre = np.array([0.0, 2.0, 4.0])
    cams = []
    for ang in np.linspace(-arc, arc, n_stations):
        a = np.radians(ang)
        S = centre + distance * np.array([np.sin(a), -np.cos(a), 0.0]) + np.array([0, 0, rng.uniform(-1, 1)])
        d = (centre - S) / np.linalg.norm(centre - S)
        xa = np.cross(d, [0.0, 0.0, 1.0])
        xa /= np.linalg.norm(xa)
        za = -d
        ya = np.cross(za, xa)
        A = np.column_stack([xa, ya, za])
        cams.append(np.concatenate([S, rotation_angles(A, order)]))
    cams = np.array(cams)
    image, point, xy = [], [], []
    for k, c in enumerate(cams):
        p = project(pts, ExteriorOrientation(*c, order=order), io, distortion=False)
        inside = (np.abs(p[:, 0]) < 17.5) & (np.abs(p[:, 1]) < 11.5)
        image += [k] * int(inside.sum())
        point += np.flatnonzero(inside).tolist()
        xy.append(p[inside])
    xy = np.vstack(xy) + rng.normal(0.0, sigma_um * 1e-3, (len(image), 2))
    control = np.array([int(np.argmin(np.linalg.norm(pts - q, axis=1))) for q in
                        ([-6, 0, 0], [6, 0, 0], [-6, 0, 8], [6, 0, 8], [0, 4, 4], [0, 0, 4])])
    return Observations(np.array(image), np.array(point), xy), cams, pts, np.unique(control), io, order


def close_range_simulation(seed: int = 0, sigma_um: float = 2.0) -> dict:
    """§5.2: bundle with the interior orientation (c, x₀, y₀) unknown on :func:`convergent_network`; the mean
    point error σ_p of the free points against the empirical σ_p = q σ_x m_s/√k, and the implied q."""
    obs, cams, pts, control, io, order = convergent_network(seed, sigma_um)
    rng = np.random.default_rng(seed + 1)
    cams0 = cams.copy()
    cams0[:, :3] += rng.normal(0, 0.3, cams0[:, :3].shape)
    cams0[:, 3:] += rng.normal(0, 0.01, cams0[:, 3:].shape)
    pts0 = pts + rng.normal(0, 0.3, pts.shape)
    pts0[control] = pts[control]
    res = bundle.self_calibrating_bundle_adjustment(obs, cams0, pts0, InteriorOrientation(f=49.0),
                                                    calibrate=("f", "x0", "y0"),
                                                    control={int(i): pts[i] for i in control}, order=order,
                                                    sigma_image=sigma_um * 1e-3)
    free = np.setdiff1d(np.arange(len(pts)), control)
    e = res.points[free] - pts[free]
    sigma_p = float(np.sqrt(np.mean(np.sum(e**2, axis=1))))
    m_s = 20.0 * 1000.0 / 50.0
    k = 1
    return {"result": res, "io_true": io, "sigma_p_mm": sigma_p * 1000.0,
            "images_per_point": float(np.bincount(obs.point).mean()),
            "q_implied": sigma_p * 1000.0 * np.sqrt(k) / (sigma_um * 1e-3 * m_s),
            "rule_mm": (terrestrial.close_range_point_sigma(0.4, sigma_um * 1e-3, m_s, k),
                        terrestrial.close_range_point_sigma(0.7, sigma_um * 1e-3, m_s, k))}
