"""Chapter 6, §6.6–6.7 (DTM, TIN, grid, contours; the terrain-situation model): formula checks
and inline statements.

Adapters for the ``[[formula]]`` and ``[[example]]`` entries ``6.6-…``/``6.7-…`` of
``textbook/ch06_dtm.toml``.

The plane (6.6.1) is lost in the OCR (seed lines 3953–3955 are empty; the text after them cites it
once as "(6.7.1)" and once as "(6.6.1)"). Its description survives: "the coefficients A, B, C
come from the three equations A + BX + CY − Z = 0 written for the X, Y, Z of each vertex".
:func:`derive_plane` solves that system with sympy; the result (Cramer's rule) is

    D = (X₂−X₁)(Y₃−Y₁) − (X₃−X₁)(Y₂−Y₁)
    B = [(Z₂−Z₁)(Y₃−Y₁) − (Z₃−Z₁)(Y₂−Y₁)] / D
    C = [(X₂−X₁)(Z₃−Z₁) − (X₃−X₁)(Z₂−Z₁)] / D
    A = Z₁ − B·X₁ − C·Y₁,          Z_i = A + B·X_i + C·Y_i          (6.6.1)

and :func:`plane_formula` checks that this is what :mod:`photolib.dtm` implements and that it is
linear (barycentric) interpolation in the triangle.

The inline statements are checked by seeded simulations on small synthetic terrains (conditions
in each entry's ``notes``); every computation takes well under 0.3 s.
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np
import sympy as sp

from ..camera import ExteriorOrientation
from .. import dtm

X1, Y1, Z1, X2, Y2, Z2, X3, Y3, Z3, X, Y, Z = sp.symbols("X1 Y1 Z1 X2 Y2 Z2 X3 Y3 Z3 X Y Z", real=True)
_A, _B, _C = sp.symbols("A B C", real=True)
_LOCALS = {s.name: s for s in (X1, Y1, Z1, X2, Y2, Z2, X3, Y3, Z3, X, Y, Z, _A, _B, _C)}


def _ok(flag) -> dict:
    return {"printed_equals_derived": bool(flag)}


@lru_cache(maxsize=None)
def derive_plane():
    """Solve A + B·X_k + C·Y_k − Z_k = 0 (k = 1, 2, 3) with sympy: {A, B, C} as expressions."""
    eqs = [_A + _B * x + _C * y - z for x, y, z in ((X1, Y1, Z1), (X2, Y2, Z2), (X3, Y3, Z3))]
    M, rhs = sp.linear_eq_to_matrix(eqs, [_A, _B, _C])
    sol = M.LUsolve(rhs)
    return {k: sp.cancel(v) for k, v in zip("ABC", sol)}


def closed_form():
    """The closed form recorded in photolib.dtm (Cramer's rule relative to vertex 1)."""
    D = (X2 - X1) * (Y3 - Y1) - (X3 - X1) * (Y2 - Y1)
    B = ((Z2 - Z1) * (Y3 - Y1) - (Z3 - Z1) * (Y2 - Y1)) / D
    C = ((X2 - X1) * (Z3 - Z1) - (X3 - X1) * (Z2 - Z1)) / D
    return {"A": Z1 - B * X1 - C * Y1, "B": B, "C": C}


def _parse(text):
    return sp.parse_expr(str(text), local_dict=_LOCALS)


def plane_formula(inputs: dict) -> dict:
    """(6.6.1), lost in the OCR: derive it and check the reconstruction ``inputs["reconstructed"]``.

    Raises AssertionError if the reconstruction, with the sympy solution of the printed system,
    does not pass through the three vertices, differs from the closed form used by
    :mod:`photolib.dtm`, is not barycentric interpolation, or if the library's
    :func:`photolib.dtm.triangle_planes` disagrees with it on a numeric triangle. The printed
    equation is empty (``inputs["printed"]`` = ""), so it cannot equal the derivation; a
    non-empty ``printed`` is compared like any formula.
    """
    sol = derive_plane()
    plane = _parse(inputs["reconstructed"])
    on = plane.subs({_A: sol["A"], _B: sol["B"], _C: sol["C"]})
    for x, y, z in ((X1, Y1, Z1), (X2, Y2, Z2), (X3, Y3, Z3)):
        if sp.cancel(on.subs({X: x, Y: y}) - z) != 0:
            raise AssertionError("the reconstructed plane does not pass through a vertex")
    cf = closed_form()
    for key in "ABC":
        if sp.cancel(cf[key] - sol[key]) != 0:
            raise AssertionError(f"the closed form of {key} in photolib.dtm differs from the sympy solution")
    # barycentric interpolation: λ_k = areas of the sub-triangles / area
    area = lambda a, b, c: (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1])  # noqa: E731
    P, V = (X, Y), ((X1, Y1), (X2, Y2), (X3, Y3))
    tot = area(*V)
    bary = (area(P, V[1], V[2]) * Z1 + area(V[0], P, V[2]) * Z2 + area(V[0], V[1], P) * Z3) / tot
    if sp.cancel(on - bary) != 0:
        raise AssertionError("the plane (6.6.1) is not barycentric interpolation")
    xyz = np.array([[3.0, 1.0, 12.0], [11.0, 2.5, 15.0], [6.0, 9.0, 10.5]])
    tin = dtm.delaunay_tin(xyz[:, :2], xyz[:, 2])
    subs = {s: v for s, v in zip((X1, Y1, Z1, X2, Y2, Z2, X3, Y3, Z3), xyz[tin.triangles[0]].ravel())}
    expect = [float(sol[k].subs(subs)) for k in "ABC"]
    if not np.allclose(dtm.triangle_planes(tin)[0], expect, rtol=1e-12, atol=1e-12):
        raise AssertionError("photolib.dtm.triangle_planes differs from the sympy solution")
    printed = str(inputs.get("printed", "")).strip()
    if not printed:
        return _ok(False)
    return _ok(sp.cancel(_parse(printed).subs({_A: sol["A"], _B: sol["B"], _C: sol["C"]}) - on) == 0)


def plane_system(inputs: dict) -> dict:
    """The printed system A + B·X + C·Y − Z = 0 per vertex: it has exactly one solution for a
    non-degenerate triangle and that solution is the plane through the three vertices."""
    row = _parse(inputs["equation"])
    eqs = [row.subs({X: x, Y: y, Z: z})
           for x, y, z in ((X1, Y1, Z1), (X2, Y2, Z2), (X3, Y3, Z3))]
    M, rhs = sp.linear_eq_to_matrix(eqs, [_A, _B, _C])
    det = sp.factor(M.det())
    unique = sp.cancel(det - ((X2 - X1) * (Y3 - Y1) - (X3 - X1) * (Y2 - Y1))) == 0 or \
        sp.cancel(det + ((X2 - X1) * (Y3 - Y1) - (X3 - X1) * (Y2 - Y1))) == 0
    sol = M.LUsolve(rhs)
    derived = derive_plane()
    same = all(sp.cancel(sol[i] - derived[k]) == 0 for i, k in enumerate("ABC"))
    return _ok(unique and same)


# --- inline statements ------------------------------------------------------------------------------
def _rng(inputs):
    return np.random.default_rng(int(inputs.get("seed", 0)))


def delaunay_rule(inputs: dict) -> dict:
    """§6.6: no vertex inside the circle through a triangle's vertices (a seeded TIN of spot heights)."""
    rng = _rng(inputs)
    n = int(inputs["n_points"])
    xy = rng.uniform(0, 100, (n, 2))
    tin = dtm.delaunay_tin(xy, np.sin(xy[:, 0] / 20) * 5)
    viol = dtm.empty_circumcircle_violations(tin.points, tin.triangles)
    return {"violations": int(len(viol)), "triangles": int(len(tin.triangles))}


def grid_from_tin_exact(inputs: dict) -> dict:
    """§6.6: grid heights from the plane of the enclosing triangle reproduce any plane exactly."""
    rng = _rng(inputs)
    worst = 0.0
    for _ in range(int(inputs["n_planes"])):
        a, b, c = rng.uniform(-50, 50), rng.uniform(-1, 1), rng.uniform(-1, 1)
        xy = np.vstack([rng.uniform(0, 100, (40, 2)), [[0, 0], [100, 0], [0, 100], [100, 100]]])
        tin = dtm.delaunay_tin(xy, a + b * xy[:, 0] + c * xy[:, 1])
        g = np.linspace(0, 100, 26)
        Xg, Yg = np.meshgrid(g, g)
        worst = max(worst, float(np.max(np.abs(dtm.grid_from_tin(tin, g, g) - (a + b * Xg + c * Yg)))))
    return {"max_error": round(worst, 12) + 0.0}         # rounding noise (~1e-14 m) below the 12 decimals


def contours_linear(inputs: dict) -> dict:
    """Fig. 6.17: contours by linear interpolation in squares and triangles; on a plane every
    vertex lies exactly at its level; on a cone they approach circles as the grid is refined."""
    a, b, c = 2.0, 0.3, -0.2
    g = np.linspace(0, 40, 21)
    Xg, Yg = np.meshgrid(g, g)
    levels = [1.0, 4.0, 7.5]
    worst = 0.0
    for lines in dtm.contours_from_grid(a + b * Xg + c * Yg, levels, g, g).items():
        for p in lines[1]:
            worst = max(worst, float(np.max(np.abs(a + b * p[:, 0] + c * p[:, 1] - lines[0]))))
    rng = _rng(inputs)
    xy = np.vstack([rng.uniform(0, 40, (60, 2)), [[0, 0], [40, 0], [0, 40], [40, 40]]])
    tin = dtm.delaunay_tin(xy, a + b * xy[:, 0] + c * xy[:, 1])
    for level, lines in dtm.contours_from_tin(tin, levels).items():
        for p in lines:
            worst = max(worst, float(np.max(np.abs(a + b * p[:, 0] + c * p[:, 1] - level))))
    return {"max_level_error": round(worst, 12) + 0.0}


def _scene(rng, n=80, relief=4.0):
    Xg, Yg = np.meshgrid(np.arange(n, dtype=float), np.arange(n, dtype=float))
    ground = 100 + relief * np.sin(Xg / 20) + 0.75 * relief * np.cos(Yg / 25)
    surface = ground.copy()
    objects = np.zeros(ground.shape, bool)
    for _ in range(4):                                              # buildings: flat roofs
        w, h = rng.integers(8, 20, 2)
        r, c = rng.integers(3, n - 23, 2)
        surface[r:r + h, c:c + w] = ground[r:r + h, c:c + w].max() + rng.uniform(5, 15)
        objects[r:r + h, c:c + w] = True
    for _ in range(6):                                              # trees: paraboloid crowns
        cx, cy, rad, ht = *rng.uniform(3, n - 3, 2), rng.uniform(2, 4), rng.uniform(5, 10)
        crown = ht * np.clip(1 - ((Xg - cx) ** 2 + (Yg - cy) ** 2) / rad ** 2, 0, None)
        tall = (crown > 0.5) & ~objects
        surface[tall] = ground[tall] + crown[tall]
        objects |= tall
    return ground, surface, objects


def dsm_editing(inputs: dict) -> dict:
    """§6.6 (1): a DTM from the DSM by removing buildings, structures and vegetation."""
    rng = _rng(inputs)
    ground, surface, objects = _scene(rng)
    noisy = surface + rng.normal(0, float(inputs["noise"]), surface.shape)
    dtm_grid, flagged = dtm.filter_dsm(noisy, 1.0, max_window=float(inputs["max_window"]),
                                       slope=float(inputs["slope"]))
    found = flagged[objects].mean()
    false = flagged[~objects].mean()
    rmse = float(np.sqrt(np.mean((dtm_grid - ground) ** 2)))
    removed = "removed" if found >= 0.98 and false <= 0.02 and rmse <= 0.3 else "not removed"
    return {"objects": removed, "objects_found_percent": 100 * found, "ground_flagged_percent": 100 * false,
            "rmse_m": rmse, "dsm_rmse_m": float(np.sqrt(np.mean((surface - ground) ** 2)))}


def density_vs_relief(inputs: dict) -> dict:
    """§6.6: the stronger the relief, the denser the DTM must be (for the same height accuracy).

    Terrain Z = a·sin(X/λ)·cos(Y/λ); grids of spacing h interpolated back (bilinear = TIN of the
    grid) at random points; the largest h whose RMSE stays below ``tolerance`` for amplitudes a
    and 4a."""
    rng = _rng(inputs)
    tol, lam = float(inputs["tolerance"]), float(inputs["wavelength"])
    q = rng.uniform(0, 200, (2000, 2))
    spacings = [1.0, 2.0, 2.5, 4.0, 5.0, 8.0, 10.0, 20.0, 25.0]

    def largest(amplitude):
        f = lambda x, y: amplitude * np.sin(x / lam) * np.cos(y / lam)  # noqa: E731
        best = None
        for h in spacings:
            g = np.arange(0, 200 + h / 2, h)
            Xg, Yg = np.meshgrid(g, g)
            from scipy.interpolate import RegularGridInterpolator
            est = RegularGridInterpolator((g, g), f(Xg, Yg).T)(q)
            if np.sqrt(np.mean((est - f(q[:, 0], q[:, 1])) ** 2)) <= tol:
                best = h
        return best

    a = float(inputs["amplitude"])
    h1, h4 = largest(a), largest(4 * a)
    return {"denser": "denser" if h4 < h1 else "not denser", "spacing_low_relief_m": h1,
            "spacing_high_relief_m": h4}


def _look_at(centre, target):
    d = np.asarray(target, float) - np.asarray(centre, float)
    d /= np.linalg.norm(d)
    zc = -d
    up = np.array([0.0, 1.0, 0.0]) if abs(d[1]) < 0.9 else np.array([1.0, 0.0, 0.0])
    xc = np.cross(up, zc)
    xc /= np.linalg.norm(xc)
    return ExteriorOrientation.from_matrix(centre, np.column_stack([xc, np.cross(zc, xc), zc]))


def texture_choice(inputs: dict) -> dict:
    """§6.7: for each face the image whose optical axis is closest to the face normal.

    A 10 × 10 × 8 m box; a nadir image, an oblique pair looking north at 30° and 60° depression
    (both see the south wall), an oblique looking south. Returns the chosen image per face."""
    names = ["nadir", "south, 30° down", "south, 60° down", "north, 45° down"]
    c = np.array([5.0, 5.0, 4.0])
    cams = [ExteriorOrientation(5.0, 5.0, 300.0),
            _look_at(c + 80 * np.array([0, -np.cos(np.pi / 6), np.sin(np.pi / 6)]), c),
            _look_at(c + 80 * np.array([0, -np.cos(np.pi / 3), np.sin(np.pi / 3)]), c),
            _look_at(c + 80 * np.array([0, np.cos(np.pi / 4), np.sin(np.pi / 4)]), c)]
    faces = np.array([[[0, 0, 8], [10, 0, 8], [10, 10, 8]],                  # roof, normal +Z
                      [[0, 0, 0], [10, 0, 0], [10, 0, 8]],                   # south wall, −Y
                      [[10, 10, 0], [0, 10, 0], [0, 10, 8]]], float)         # north wall, +Y
    choice = dtm.select_texture_images(faces, cams)
    pick = [names[k] if k >= 0 else "none" for k in choice.image]
    return {"roof": pick[0], "south_wall": pick[1], "north_wall": pick[2],
            "south_wall_angle_deg": float(np.degrees(choice.angle[1]))}


def grid_storage(inputs: dict) -> dict:
    """§6.6: a grid is stored as heights only; X = X₀ + column·step, Y = Y₀ + row·step."""
    step, x0, y0 = float(inputs["step"]), float(inputs["x0"]), float(inputs["y0"])
    xy = np.array([[x0, y0], [x0 + 40, y0], [x0, y0 + 40], [x0 + 40, y0 + 40]])
    tin = dtm.delaunay_tin(xy, 2.0 + 0.5 * (xy[:, 0] - x0) + 0.25 * (xy[:, 1] - y0))
    G = dtm.grid_from_tin(tin, x0 + step * np.arange(9), y0 + step * np.arange(9))
    r, c = 3, 7                                          # height at row 3, column 7
    return {"node_height": float(G[r, c]), "node_x": x0 + c * step, "node_y": y0 + r * step}
