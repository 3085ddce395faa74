"""Chapter 7, §7.5, §7.6, §7.8 (true orthophotos, point clouds, the least-squares DSM): formula
checks, Fig. 7.12, the §7.8 counts and the datum defect of (7.8.4).

Adapters for the entries of ``textbook/ch07_trueortho.toml``. Formula adapters take the printed
formula (sympy text or a reading of the text) in ``inputs`` and return
``{"printed_equals_derived": bool}``; the derivations come from sympy
(:mod:`photolib.derivations.orthophoto`) and from plain ray geometry. Example adapters call
:mod:`photolib.trueortho` on small modelled scenes (conditions in the entries' notes).
"""

from __future__ import annotations

import numpy as np
import sympy as sp

FIG_7_12_LEFT = ("00000000000", "00000000000", "00000222200", "00011111200", "00011111200",
                 "00011111200", "00000000000", "00000000000", "00000000000", "00000000000")
"""Fig. 7.12, left grid as printed (rows 0–9, columns 0–10): 0 ground, 1 roof, 2 wall."""
FIG_7_12_RIGHT = ("00000000000", "00000000000", "00000.11100", "000...11100", "000...11100",
                  "000......00", "00000000000", "00000000000", "00000000000", "00000000000")
"""Fig. 7.12, right grid as printed; '.' = a blank cell of the OCR (no code printed)."""


def _ok(flag) -> dict:
    return {"printed_equals_derived": bool(flag)}


def transcribed(inputs: dict) -> dict:
    """Pure specifications: nothing to compute."""
    return {}


# --------------------------------------------------------------------------- §7.5
def nadir_angle_criterion(inputs: dict) -> dict:
    """§7.5: "if α < β, element A does not hide element B" against ray geometry.

    Derived: A (on the profile between the nadir and B) hides B iff the ray from S to B passes
    below A's top, Z_ray(r_A) = Z_B + (Z_S − Z_B)(r_B − r_A)/r_B < Z_A. Random configurations
    (seeded) are classified by the printed reading (``"alpha<beta"``: not hidden) and by the ray;
    they must agree everywhere.
    """
    rng = np.random.default_rng(int(inputs.get("seed", 0)))
    n = int(inputs.get("trials", 2000))
    Zs = 100.0
    rA = rng.uniform(0.1, 50, n)
    rB = rA + rng.uniform(0.1, 50, n)
    ZA, ZB = rng.uniform(0, 60, n), rng.uniform(0, 60, n)
    alpha, beta = np.arctan2(rA, Zs - ZA), np.arctan2(rB, Zs - ZB)
    ray = ZB + (Zs - ZB) * (rB - rA) / rB
    hidden = ray < ZA
    reading = inputs.get("reading", "alpha<beta")
    visible = {"alpha<beta": alpha < beta, "alpha>beta": alpha > beta}[reading]
    return _ok(np.array_equal(visible, ~hidden))


def neighbour_only_test(inputs: dict) -> dict:
    """Pitfall 19: comparing each element only with its neighbour towards the nadir misses group occlusion.

    A 41 × 41 DSM (1 m cells) with a box building, S above the centre: the restriction matrix by
    the neighbour-only comparison vs brute-force ray marching (:func:`visibility_mask`,
    method ``"raymarch"``, numpy).
    """
    from ..rectify import RasterGrid
    from ..trueortho import visibility_mask
    n, h = 41, float(inputs.get("height", 12.0))
    dsm = np.zeros((n, n))
    dsm[8:14, 24:30] = h
    grid = RasterGrid(0.0, float(n), 1.0, (n, n))
    S = np.array([20.5, 20.5, float(inputs.get("Zs", 100.0))])
    truth = visibility_mask(dsm, grid, S, method="raymarch")
    X, Y = grid.centres()
    r = np.hypot(X - S[0], Y - S[1])
    with np.errstate(invalid="ignore", divide="ignore"):
        ux, uy = (S[0] - X) / r, (S[1] - Y) / r
    # the neighbour one cell towards the nadir (nearest cell)
    Xn, Yn = np.nan_to_num(X + ux), np.nan_to_num(Y + uy)
    rr, cc = grid.rowcol(Xn, Yn)
    ci = np.clip(np.rint(rr).astype(int), 0, n - 1)
    cj = np.clip(np.rint(cc).astype(int), 0, n - 1)
    zn = dsm[ci, cj]
    rn = np.hypot(Xn - S[0], Yn - S[1])
    neighbour = np.where(r > 1, np.arctan2(rn, S[2] - zn) <= np.arctan2(r, S[2] - dsm), True)
    hidden_truth = int((truth == 0).sum())
    missed = int(((truth == 0) & neighbour).sum())
    return {"hidden_cells": hidden_truth, "missed_by_neighbour_test": missed,
            "neighbour_test_sufficient": "yes" if missed == 0 else "no"}


def fig_7_12(inputs: dict) -> dict:
    """Fig. 7.12 from a modelled box building under a vertical frame camera.

    The camera (f, Δ, EO) and the box (X_min, X_max, Y_min, Y_max, Z_base, Z_top) are the
    entry's inputs; the index matrix is computed by :func:`photolib.trueortho.index_matrix` on a
    10 × 11 crop (rows ``crop_row0``…) of the frame. The right grid is the orthophoto on the
    same lattice (ground pixel = image pixel on flat ground Z = 0): the footprint gets the roof
    (1), the ground the building hides from S (dead zone) is blank ('.'), the rest 0.
    """
    from ..camera import ExteriorOrientation, InteriorOrientation
    from ..rectify import frame_projector
    from ..trueortho import index_matrix
    eo = ExteriorOrientation(*inputs["centre"])
    frame = tuple(inputs["frame"])
    project = frame_projector(eo, InteriorOrientation(float(inputs["f"])), float(inputs["pixel"]), frame)
    r0, c0 = inputs["crop_origin"]
    crop = lambda X, Y, Z: tuple(np.asarray(a) - o for a, o in zip(project(X, Y, Z), (r0, c0)))  # noqa: E731
    box = np.asarray(inputs["box"], float)
    left = index_matrix((10, 11), crop, [box], eo.center)
    rows, cols = np.mgrid[0:10, 0:11].astype(float)
    # ground X, Y of each crop pixel centre on Z = 0 (vertical camera: linear)
    gsd = (eo.Zs - 0.0) / float(inputs["f"]) * float(inputs["pixel"])
    X = eo.Xs + (cols + c0 - (frame[1] - 1) / 2) * gsd
    Y = eo.Ys - (rows + r0 - (frame[0] - 1) / 2) * gsd
    foot = (X >= box[0]) & (X <= box[1]) & (Y >= box[2]) & (Y <= box[3])
    right = np.where(foot, "1", np.where(left > 0, ".", "0"))
    out = {f"left row {i}": "".join(str(v) for v in left[i]) for i in range(10)}
    out.update({f"right row {i}": "".join(right[i]) for i in range(10)})
    return out


# --------------------------------------------------------------------------- §7.6
def max_z_rule(inputs: dict) -> dict:
    """§7.6: a pixel with points of different Z (a wall) takes the brightness of the highest point.

    Seeded cloud: ground (d = 0.2, Z = 0) for X < 10, roof (d = 0.9, Z = 10) for X > 10, wall
    points (d = 0.5) at X = 10 with Z uniform in [0, 10]; 1 m ortho pixels; the pixel whose
    centre is 0.5 m from the wall, by the radius mean and by the max-Z rule.
    """
    from ..rectify import RasterGrid
    from ..trueortho import ortho_from_points
    rng = np.random.default_rng(int(inputs.get("seed", 2)))
    g = np.column_stack([rng.uniform(0, 20, 4000), rng.uniform(0, 10, 4000)])
    z = np.where(g[:, 0] > 10, 10.0, 0.0)
    wall = np.column_stack([np.full(1000, 10.0), rng.uniform(0, 10, 1000), rng.uniform(0, 10, 1000)])
    pts = np.vstack([np.column_stack([g, z]), wall])
    d = np.r_[np.where(z > 0, 0.9, 0.2), np.full(1000, 0.5)]
    grid = RasterGrid(0.0, 10.0, 1.0, (10, 20))
    mean = ortho_from_points(pts, d, grid, "radius_mean")[:, 10]
    top = ortho_from_points(pts, d, grid, "max_z", z_tol=0.02)[:, 10]
    e_mean, e_top = float(np.abs(mean - 0.9).max()), float(np.abs(top - 0.9).max())
    return {"radius_mean_error": e_mean, "max_z_error": e_top,
            "max_z_gives_roof": "yes" if e_top < 0.1 else "no", "mean_gives_roof": "yes" if e_mean < 0.1 else "no"}


# --------------------------------------------------------------------------- §7.8
_F, _Z, _k = sp.symbols("F Z k_i", real=True)


def photometric_formula(inputs: dict) -> dict:
    """(7.8.1): the printed condition against F − k_i·f_i(x_i, y_i) (f_i the image brightness)."""
    from ..derivations.orthophoto import photometric_condition
    x, y = sp.symbols("x_i y_i", real=True)
    local = {"F": sp.Symbol("F", real=True), "k_i": sp.Symbol("k_i", real=True), "x_i": x, "y_i": y,
             "f_i": sp.Function("f_i"), "t_i": sp.Function("t_i")}
    printed = sp.parse_expr(inputs["condition"], local_dict=local)
    return _ok(sp.simplify(printed - photometric_condition()) == 0)


def collinearity_formula(inputs: dict) -> dict:
    """(7.8.2) ≡ (7.3.2): the printed a_jk form, with a_jk the elements of A (1.3.2), equals Aᵀ·ΔX."""
    from ..derivations.orthophoto import check_782_equals_732
    return _ok(check_782_equals_732(inputs.get("order", "wak")))


def correction_structure(inputs: dict) -> dict:
    """(7.8.3)/(7.8.4): the printed unknowns are exactly those (7.8.1) depends on, and a₁ = 1.

    The derived coefficients (sympy) of (7.8.1) by the unknowns the printed equation lists must
    all be non-zero, and the derivative by every other quantity of the model must vanish (EO
    known: X_S … κ are data).
    """
    from ..derivations.orthophoto import correction_coefficients
    eo = bool(inputs.get("eo_unknown", False))
    c = correction_coefficients(eo_unknown=eo)
    printed = list(inputs["unknowns"])
    derived = ["F", "Z", "k_i"] + (["X_S", "Y_S", "Z_S", "alpha", "omega", "kappa"] if eo else [])
    nonzero = all(c[f"a{n}"] != 0 for n in range(1, len(derived) + 1))
    return _ok(nonzero and printed == derived and c["a1"] == 1)


def counts_formula(inputs: dict) -> dict:
    """N = 2P + (S − 1) + 6S, M = PS: the printed counts against a count of the model's unknowns."""
    P, S = sp.symbols("P S", positive=True, integer=True)
    local = {"P": P, "S": S}
    N = sp.parse_expr(inputs["N"], local_dict=local)
    M = sp.parse_expr(inputs["M"], local_dict=local)
    per_pixel = 2                      # F and Z
    gains = S - 1                      # one k fixed to 1
    eo = 6 * S                         # X_S, Y_S, Z_S, α, ω, κ per image
    return _ok(sp.simplify(N - (per_pixel * P + gains + eo)) == 0 and sp.simplify(M - P * S) == 0)


def counts_example(inputs: dict) -> dict:
    """The book's example P = 100, S = 2, EO known, and the third image (:func:`lsq_unknown_count`)."""
    from ..trueortho import lsq_unknown_count
    P = int(inputs["P"])
    N2, M2 = lsq_unknown_count(P, 2, eo_known=True)
    N3, M3 = lsq_unknown_count(P, 3, eo_known=True)
    return {"N (S = 2)": N2, "M (S = 2)": M2, "S = 2 solvable": "yes" if N2 <= M2 else "no",
            "M (S = 3)": M3, "S = 3 solvable": "yes" if N3 < M3 else "no"}


def two_images_refused(inputs: dict) -> dict:
    """:func:`lsq_dsm_ortho` with two images raises DegenerateGeometryError (N > M)."""
    from ..camera import ExteriorOrientation, InteriorOrientation
    from ..errors import DegenerateGeometryError
    from ..rectify import RasterGrid
    from ..trueortho import lsq_dsm_ortho
    P = int(inputs.get("side", 10))
    rng = np.random.default_rng(0)
    images = [rng.uniform(size=(60, 60)) for _ in range(2)]
    eos = [ExteriorOrientation(-20.0, 0.0, 200.0), ExteriorOrientation(20.0, 0.0, 200.0)]
    try:
        lsq_dsm_ortho(images, eos, InteriorOrientation(50.0), 0.1, RasterGrid(-5.0, 5.0, 10.0 / P, (P, P)),
                      np.zeros((P, P)))
    except DegenerateGeometryError:
        return {"S = 2 solvable": "no"}
    return {"S = 2 solvable": "yes"}


def datum_defect(inputs: dict) -> dict:
    """Rank defect of the linearised (7.8.4) system at the solution, without and with GCPs.

    An analytic scene: a smooth surface Z(X, Y) with a texture F(X, Y), S images with gains; at
    the solution f_i(x, y) = F/k_i on the surface, so the image gradient is ∇F·(∂(x, y)/∂(X, Y) along
    the surface)⁻¹/k_i. The columns are F, Z per pixel, k_i and the six EO elements per image
    (a₁…a₉ of (7.8.4); EO partials from :func:`photolib.derivations.orthophoto.eo_partials_function`);
    the rank defect is counted from the singular values (relative threshold 1e-9).
    """
    from ..camera import ExteriorOrientation, InteriorOrientation
    from ..derivations.orthophoto import eo_partials_function, height_partials_function
    from ..single_image import project
    n, S, H = int(inputs["side"]), int(inputs["images"]), float(inputs["height"])
    io = InteriorOrientation(50.0)
    X, Y = (a.ravel() for a in np.meshgrid(np.linspace(-10, 10, n), np.linspace(-10, 10, n)))
    Z = 2.0 + 0.05 * X - 0.03 * Y + 0.01 * X * Y + 0.02 * X ** 2
    ZX, ZY = 0.05 + 0.01 * Y + 0.04 * X, -0.03 + 0.01 * X
    F = 0.5 + 0.2 * np.sin(0.9 * X + 0.3) * np.cos(0.7 * Y - 0.2)
    FX = 0.2 * 0.9 * np.cos(0.9 * X + 0.3) * np.cos(0.7 * Y - 0.2)
    FY = -0.2 * 0.7 * np.sin(0.9 * X + 0.3) * np.sin(0.7 * Y - 0.2)
    P = X.size
    eos = [ExteriorOrientation(30 * np.cos(a), 30 * np.sin(a), H, 0.01 * s, -0.02 * s, 0.03 * s)
           for s, a in enumerate(np.linspace(0, 2 * np.pi, S, endpoint=False))]
    gains = 1.0 + 0.1 * np.arange(S)
    rows = []
    for i, eo in enumerate(eos):
        hz = height_partials_function(eo.order)(X, Y, Z, *eo.vector, io.f, io.x0, io.y0)      # (2, P)
        pe = eo_partials_function(eo.order)(X, Y, Z, *eo.vector, io.f, io.x0, io.y0)         # (2, 6, P)
        h = 1e-6                                    # ∂(x, y)/∂(X, Y) at fixed Z, by central differences
        J = np.empty((P, 2, 2))
        for c, (dx, dy) in enumerate(((h, 0.0), (0.0, h))):
            up = project(np.column_stack([X + dx, Y + dy, Z]), eo, io)
            dn = project(np.column_stack([X - dx, Y - dy, Z]), eo, io)
            J[:, :, c] = (up - dn) / (2 * h)
        Js = J + hz.T[:, :, None] * np.stack([ZX, ZY], axis=1)[:, None, :]   # along the surface
        g = np.einsum("pj,pji->pi", np.column_stack([FX, FY]), np.linalg.inv(Js)) * gains[i]   # ∇f_i, f_i = F/k_i
        k = 1.0 / gains[i]                          # F = k_i f_i
        B = np.zeros((P, 2 * P + 7 * S))
        B[np.arange(P), 2 * np.arange(P)] = 1.0
        B[np.arange(P), 2 * np.arange(P) + 1] = -k * np.einsum("pi,ip->p", g, hz)
        B[:, 2 * P + 7 * i] = -F / k                # −f_i
        B[:, 2 * P + 7 * i + 1:2 * P + 7 * i + 7] = -k * np.einsum("pi,ijp->pj", g, pe)
        rows.append(B)
    B = np.vstack(rows)
    gcp = np.array([[-8.0, -8.0, 1.0], [8.0, -6.0, 3.0], [-5.0, 9.0, 2.0]])
    gcp_rows = []                                   # collinearity (7.8.2) of the GCPs: EO columns only
    for i, eo in enumerate(eos):
        pe = eo_partials_function(eo.order)(gcp[:, 0], gcp[:, 1], gcp[:, 2], *eo.vector, io.f, io.x0, io.y0)
        R = np.zeros((2 * len(gcp), B.shape[1]))
        R[:, 2 * P + 7 * i + 1:2 * P + 7 * i + 7] = np.concatenate([pe[0].T, pe[1].T])
        gcp_rows.append(R.reshape(2, len(gcp), -1).transpose(1, 0, 2))            # (GCP, x/y, column)

    def defect(M):
        M = np.delete(M, 2 * P, axis=1)             # the reference gain k_0 = 1
        sv = np.linalg.svd(M / np.linalg.norm(M, axis=0), compute_uv=False)
        return int(np.sum(sv < 1e-7 * sv[0])) + (M.shape[1] - sv.size)

    with_gcps = lambda k: np.vstack([B] + [R[:k].reshape(-1, B.shape[1]) for R in gcp_rows])
    d0 = defect(B)
    return {"unknowns N": B.shape[1] - 1, "equations M": B.shape[0], "datum defect": d0,
            "GCP equations needed": "yes" if d0 > 0 else "no",
            "defect with 2 GCPs": defect(with_gcps(2)), "defect with 3 GCPs": defect(with_gcps(3))}
