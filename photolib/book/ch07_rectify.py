"""Chapter 7, §7.1–7.4, §7.7, §7.9 (rectification, orthophoto, tolerances, mosaics, accuracy):
formula checks and inline numbers.

Adapters for the ``[[formula]]`` and ``[[example]]`` entries of ``textbook/ch07_rectify.toml``.
Formula adapters return ``{"printed_equals_derived": bool}``: the printed formulas are compared
with sympy derivations from collinearity (the camera → object matrix A of (1.3.2)) and the
geometry of the figures. Statements are checked by small seeded simulations with
:mod:`photolib.rectify` on an analytic terrain seen by a frame camera; the "image" is made by
ray casting every pixel onto the DEM with :func:`photolib.rectify.monoplot`, so the true ground
position and texture of every pixel are known (conditions in the entries' notes).
"""

from __future__ import annotations

import functools

import numpy as np
import sympy as sp

from .. import rectify


def _ok(flag) -> dict:
    return {"printed_equals_derived": bool(flag)}


_x, _y, _X, _Y, _Z = sp.symbols("x y X Y Z", real=True)


def _rotation():
    """A symbolic rotation in the Euler–Rodrigues form (unit quaternion (1, a, b, c)/√n).

    Every rotation except the half-turns has this form; A is a polynomial matrix over the scalar
    n = 1 + a² + b² + c², so sympy proves identities that need AᵀA = E quickly (with the
    trigonometric form of (1.3.2) the same simplification takes tens of seconds).
    """
    a, b, c = sp.symbols("a b c", real=True)
    n = 1 + a ** 2 + b ** 2 + c ** 2
    A = sp.Matrix([[1 + a**2 - b**2 - c**2, 2 * (a * b - c), 2 * (a * c + b)],
                   [2 * (a * b + c), 1 - a**2 + b**2 - c**2, 2 * (b * c - a)],
                   [2 * (a * c - b), 2 * (b * c + a), 1 - a**2 - b**2 + c**2]])
    return A, n                        # the rotation is A / n


def _product(M, A, n):
    """(M/n)(A/n) for polynomial matrices: E if M·A − n²E expands to zero, else the product."""
    difference = (M * A - n ** 2 * sp.eye(3)).applyfunc(sp.expand)
    return sp.eye(3) if difference == sp.zeros(3, 3) else (M * A) / n ** 2


# --------------------------------------------------------------------------- §7.2 (7.2.1), (7.2.2)
def mapping_formula(inputs: dict) -> dict:
    """(7.2.1)/(7.2.2) printed with ONE function symbol f for both coordinates.

    Derived: for the central projection of a plane (the book's example of the functions) the two
    coordinates are two different functions f₁ ≠ f₂ (the rows of a homography), and the inverse
    mapping F is the inverse homography. Read literally, x^T = f(x, y) = y^T. The check compares
    the printed reading (one function) with a concrete homography.
    """
    h = sp.Matrix(3, 3, lambda i, j: sp.Rational(1 + 3 * i + j, 7) if (i, j) != (2, 2) else 1)
    w = h[2, 0] * _x + h[2, 1] * _y + h[2, 2]
    f1 = (h[0, 0] * _x + h[0, 1] * _y + h[0, 2]) / w
    f2 = (h[1, 0] * _x + h[1, 1] * _y + h[1, 2]) / w
    # the inverse mapping (7.2.2) really inverts (7.2.1)
    hi = h.inv()
    xT, yT = sp.symbols("x_T y_T", real=True)
    wi = hi[2, 0] * xT + hi[2, 1] * yT + hi[2, 2]
    F1 = (hi[0, 0] * xT + hi[0, 1] * yT + hi[0, 2]) / wi
    inverse_ok = sp.cancel(F1.subs({xT: f1, yT: f2}) - _x) == 0
    one_function = inputs.get("reading", "one function") == "one function"
    printed_equal = sp.cancel(f1 - f2) == 0 if one_function else True
    return _ok(inverse_ok and printed_equal)


def accumulation_formula(inputs: dict) -> dict:
    """The unnumbered accumulation formula of §7.2 (l. 4048), read as an expression E = 0.

    Derived from the text: the output brightness is assembled from the increments of the k
    source pixels covering it in proportion to the covered areas s (Fig. 7.3); for k = 2:
    d^T = (s₁d₁ + s₂d₂)/(s₁ + s₂) (the plain sum Σ s·d when the areas add up to one pixel). The
    printed line is x = f(x^T, y^T) — it does not contain d^T at all.
    """
    dT, s1, s2, d1, d2 = sp.symbols("dT s1 s2 d1 d2", positive=True)
    local = {"dT": dT, "s1": s1, "s2": s2, "d1": d1, "d2": d2, "x": _x, "xT": sp.Symbol("xT"),
             "yT": sp.Symbol("yT"), "f": sp.Function("f")}
    printed = sp.parse_expr(inputs["printed"], local_dict=local)
    if dT not in printed.free_symbols:
        return _ok(False)
    solved = sp.solve(printed, dT)
    derived = (s1 * d1 + s2 * d2) / (s1 + s2)
    return _ok(len(solved) == 1 and sp.cancel(solved[0] - derived) == 0)


def forward_weights(inputs: dict) -> dict:
    """§7.2: a source pixel mapped to (x^T, y^T) covers four output pixels (Fig. 7.3)."""
    xT, yT = float(inputs["xT"]), float(inputs["yT"])
    shape = (int(yT) + 3, int(xT) + 3)
    _, weight = rectify.rectify_forward(np.array([[1.0]]), np.array([[yT]]), np.array([[xT]]), shape)
    covered = np.argwhere(weight > 0)
    out = {"pixels_covered": int(len(covered))}
    for i, j in covered:
        out[f"w_{j}_{i}"] = float(weight[i, j])
    return out


def nearest_neighbour(inputs: dict) -> dict:
    """§7.2: rounding x = 150.3, y = 21.7 to the nearest pixel (x ↔ column j, y ↔ row i)."""
    x, y = float(inputs["x"]), float(inputs["y"])
    rows, cols = int(y) + 3, int(x) + 3
    index = np.arange(rows * cols, dtype=float).reshape(rows, cols)
    k = int(rectify.resample(index, [y], [x], "nearest")[0])
    return {"j": k % cols, "i": k // cols}


def forward_holes(inputs: dict) -> dict:
    """§7.2: forward mapping leaves empty output pixels; the inverse method does not."""
    s = float(inputs["scale"])
    n = int(inputs["size"])
    image = np.random.default_rng(int(inputs["seed"])).random((n, n))
    rr, cc = np.mgrid[0:n, 0:n].astype(float)
    m = int(s * (n - 1)) + 1
    out, _ = rectify.rectify_forward(image, s * rr, s * cc, (m, m))
    R, C = np.mgrid[0:m, 0:m].astype(float)
    inverse = rectify.resample(image, R / s, C / s, "bilinear")
    return {"forward_holes": "yes" if np.isnan(out).any() else "no",
            "inverse_holes": "yes" if np.isnan(inverse).any() else "no",
            "forward_hole_fraction": float(np.isnan(out).mean())}


# --------------------------------------------------------------------------- §7.3
def bilinear_dem_formula(inputs: dict) -> dict:
    """(7.3.1) equals the bilinear interpolant Z₁(1−u)(1−v) + Z₂(1−u)v + Z₃u(1−v) + Z₄uv with
    u = ΔX/ΔD, v = ΔY/ΔD (nodes 1 = (X₁, Y₁), 2 = (X₁, Y₁+ΔD), 3 = (X₁+ΔD, Y₁), 4 = (X₁+ΔD, Y₁+ΔD)),
    and photolib.rectify.dem_height on a random cell."""
    Z1, Z2, Z3, Z4, dX, dY, D = sp.symbols("Z1 Z2 Z3 Z4 dX dY D", positive=True)
    loc = {"Z1": Z1, "Z2": Z2, "Z3": Z3, "Z4": Z4, "dX": dX, "dY": dY, "D": D}
    ZK = sp.parse_expr(inputs["Z_K"], local_dict=loc)
    ZM = sp.parse_expr(inputs["Z_M"], local_dict=loc)
    Zi = sp.parse_expr(inputs["Z_i"], local_dict={**loc, "Z_K": ZK, "Z_M": ZM})
    u, v = dX / D, dY / D
    derived = Z1 * (1 - u) * (1 - v) + Z2 * (1 - u) * v + Z3 * u * (1 - v) + Z4 * u * v
    symbolic = sp.expand(Zi - derived) == 0
    rng = np.random.default_rng(0)
    heights = rng.uniform(100, 200, (2, 2))                   # rows north → south
    grid = rectify.RasterGrid(0.0, 20.0, 10.0, (2, 2))       # node 1 = (5, 5) = row 1, col 0
    x, y = rng.uniform(5, 15), rng.uniform(5, 15)
    values = {Z1: heights[1, 0], Z2: heights[0, 0], Z3: heights[1, 1], Z4: heights[0, 1], dX: x - 5, dY: y - 5, D: 10}
    numeric = abs(float(Zi.subs(values)) - float(rectify.dem_height(heights, grid, x, y))) < 1e-9
    return _ok(symbolic and numeric)


def collinearity_formula(inputs: dict) -> dict:
    """(7.3.2): x = x₀ − f x*/z*, y = y₀ − f y*/z*, (x*, y*, z*) = Aᵀ(X − X_S). Derived: a point
    on the ray X = S + λA(x − x₀, y − y₀, −f) (λ > 0) must give back (x, y); the printed matrix
    applied to λA r gives λ(MA)r, which returns (x, y) for every ray iff MA = E."""
    A, n = _rotation()
    M = A.T if inputs.get("matrix", "A^T") == "A^T" else A
    product = _product(M, A, n)
    if product != sp.eye(3):          # then some ray does not come back (e.g. λ(AA)r for a turn)
        return _ok(False)
    f, x0, y0, lam = sp.symbols("f x_0 y_0 lambda", positive=True)
    r = sp.Matrix([_x - x0, _y - y0, -f])
    star = lam * product * r
    x_back = x0 - f * star[0] / star[2]
    y_back = y0 - f * star[1] / star[2]
    return _ok(sp.cancel(x_back - _x) == 0 and sp.cancel(y_back - _y) == 0)


def ortho_pixel_formula(inputs: dict) -> dict:
    """§7.3: ortho pixel ≈ Δ × m. Derived: the ground footprint of one pixel Δ of a vertical
    image taken from height H with focal length f is Δ·H/f, and 1/m = f/H."""
    delta, H, f = sp.symbols("Delta H f", positive=True)
    m = H / f
    printed = sp.parse_expr(inputs["printed"], local_dict={"Delta": delta, "m": m})
    footprint = delta * H / f
    numeric = abs(rectify.ortho_pixel_size(0.01, 14000) - 0.14) < 1e-12
    return _ok(sp.simplify(printed - footprint) == 0 and numeric)


def topocentric_axes(inputs: dict) -> dict:
    """§7.3: X along the meridian (north), Z along the normal, Y completes a right-handed system."""
    B0, L0 = float(inputs["B0"]), float(inputs["L0"])
    R = rectify.topocentric_matrix(B0, L0)
    east = np.array([-np.sin(L0), np.cos(L0), 0.0])
    north = np.array([-np.sin(B0) * np.cos(L0), -np.sin(B0) * np.sin(L0), np.cos(B0)])
    right_handed = np.allclose(np.cross(R[0], R[1]), R[2])
    y_axis = "west" if np.dot(R[1], east) < -0.999 else ("east" if np.dot(R[1], east) > 0.999 else "?")
    return {"y_axis": y_axis, "right_handed": "yes" if right_handed else "no",
            "x_axis": "north" if np.dot(R[0], north) > 0.999 else "?"}


# --------------------------------------------------------------------------- §7.4
def admissible_relief_formula(inputs: dict) -> dict:
    """(7.4.1)/(7.4.2): h_max = (f/r)ΔR_max. Derived: a point at height h above the rectification
    plane, horizontal distance R from the nadir of a vertical photo from height H (above that
    plane) images at r = fR/(H − h); its projection onto the plane lies at rH/f, displaced by
    ΔR = rH/f − R = r·h/f exactly; solving ΔR = ΔR_max for h gives the printed formula."""
    f, H, h, R, dRmax, r = sp.symbols("f H h R Delta_R_max r", positive=True)
    r_of = f * R / (H - h)
    dR = sp.simplify(r_of * H / f - R)
    exact = sp.simplify(dR - r_of * h / f) == 0
    h_solved = sp.solve(sp.Eq(r * h / f, dRmax), h)[0]
    printed = sp.parse_expr(inputs["printed"], local_dict={"f": f, "r": r, "Delta_R_max": dRmax})
    numeric = abs(rectify.admissible_height(100.0, 50.0, 0.6) - 1.2) < 1e-12
    return _ok(exact and sp.simplify(printed - h_solved) == 0 and numeric)


def map_tolerance(inputs: dict) -> dict:
    """§7.4 ΔR_max = 0.3 mm on the map = 0.3·M mm on the ground; §7.9 tolerances 0.5 and 0.7 mm."""
    M = float(inputs.get("M", 2000))
    report = rectify.ortho_accuracy([[0.0, 0.0]], [[0.0, 0.0]], M)
    return {"dR_max_mm": rectify.map_tolerance(M) / M * 1000.0,
            "mean_error_mm": report.tolerance_mm, "cutline_mm": report.cutline_tolerance_mm}


@functools.lru_cache(maxsize=4)
def _scene(size: int = 100, tilt_deg: float = 2.0):
    """An analytic terrain, a frame camera and its ray-cast image (the texture at each pixel's
    ground point, found by monoplotting the pixel centre on the DEM)."""
    from ..camera import ExteriorOrientation, InteriorOrientation
    from ..synthetic import pixel_to_image
    grid = rectify.RasterGrid(-100.0, 300.0, 1.0, (400, 400))
    X, Y = grid.centres()
    dem = 120.0 + 8.0 * np.sin(X / 37.0) * np.cos(Y / 53.0) + 0.02 * X
    io = InteriorOrientation(100.0)
    tilt = np.radians(tilt_deg)
    eo = ExteriorOrientation(100.0, 100.0, 1120.0, tilt, -0.7 * tilt, 0.1)
    pixel = 0.05                                              # mm; GSD ≈ 0.5 m
    rr, cc = np.mgrid[0:size, 0:size].astype(float)
    x, y = pixel_to_image(cc.ravel(), rr.ravel(), (size, size), pixel)
    ground = rectify.monoplot(np.column_stack([x, y]), eo, io, dem, grid, tol=1e-7).XYZ
    image = texture(ground[:, 0], ground[:, 1]).reshape(size, size)
    return dem, grid, eo, io, pixel, image, ground.reshape(size, size, 3)


def texture(X, Y):
    """The analytic texture of the simulations (period 5–14 m, contrast ±0.25)."""
    return 0.5 + 0.15 * np.sin(X / 1.6 + 0.3 * np.cos(Y / 2.3)) + 0.1 * np.cos(Y / 1.9)


def resampling_quality(inputs: dict) -> dict:
    """§7.2–7.3: nearest neighbour degrades the result; bilinear is the usual choice; bicubic better."""
    dem, grid, eo, io, pixel, image, _ = _scene(int(inputs.get("size", 100)), float(inputs.get("tilt_deg", 2.0)))
    project = rectify.frame_projector(eo, io, pixel, image.shape)
    ortho_grid = rectify.RasterGrid.aligned(85.0, 85.0, 115.0, 115.0, 0.5)
    Xc, Yc = ortho_grid.centres()
    truth = texture(Xc, Yc)
    rms = {m: float(np.sqrt(np.nanmean((rectify.orthorectify(image, project, dem, grid, ortho_grid, m) - truth) ** 2)))
           for m in rectify.RESAMPLING_METHODS}
    return {"rms_nearest": rms["nearest"], "rms_bilinear": rms["bilinear"], "rms_bicubic": rms["bicubic"],
            "nearest_worse": "yes" if rms["nearest"] > rms["bilinear"] else "no",
            "bicubic_better": "yes" if rms["bicubic"] < rms["bilinear"] else "no"}


def dem_error_displacement(inputs: dict) -> dict:
    """§7.4, Fig. 7.7 and (7.4.2): the orthophoto shift of a DEM error ΔZ against r·ΔZ/f.

    A wide-angle frame (f = 100 mm, image points up to r = 100 mm from the principal point)
    over the analytic terrain: the image position of a ground point is fixed, so its shift on the
    orthophoto is the distance between the monoplotted positions of its image point on the true
    DEM and on the DEM raised by ΔZ. Returned: the largest relative deviation from r·ΔZ/f with r
    measured from the principal point (the book's definition) and from the nadir point.
    """
    from ..camera import ExteriorOrientation, InteriorOrientation
    from ..single_image import project
    tilt = np.radians(float(inputs["tilt_deg"]))
    dZ = float(inputs["dZ"])
    grid = rectify.RasterGrid(-1500.0, 1500.0, 10.0, (300, 300))
    X, Y = grid.centres()
    dem = 120.0 + 8.0 * np.sin(X / 370.0) * np.cos(Y / 530.0)
    io = InteriorOrientation(100.0)
    eo = ExteriorOrientation(0.0, 0.0, 1120.0, tilt * 0.6, tilt * 0.8, 0.1)   # tilt = √(ω² + α²)
    t = np.linspace(-1.0, 1.0, 9)
    u, v = np.meshgrid(t, t)
    xy = 70.0 * np.column_stack([u.ravel(), v.ravel()])                     # r ≤ 99 mm
    xy = xy[np.hypot(*xy.T) > 1.0]
    good = rectify.monoplot(xy, eo, io, dem, grid, tol=1e-7).XYZ
    bad = rectify.monoplot(xy, eo, io, dem + dZ, grid, tol=1e-7).XYZ
    shift = np.hypot(*(bad - good)[:, :2].T)
    nadir = project(np.array([[eo.Xs, eo.Ys, 120.0]]), eo, io)[0]
    out = {}
    for name, centre in (("principal", np.zeros(2)), ("nadir", nadir)):
        predicted = rectify.relief_displacement(np.hypot(*(xy - centre).T), dZ, io.f)
        out[f"max_relative_error_{name}"] = float(np.max(np.abs(shift / predicted - 1.0)))
    return out


# --------------------------------------------------------------------------- §7.7
def monoplot_formula(inputs: dict) -> dict:
    """(7.7.1): X = X_S + (Z − Z_S)X′/Z′, Y likewise, (X′, Y′, Z′) = A(x − x₀, y − y₀, −f).
    Derived: the object point at height Z on the ray S + λA(x − x₀, y − y₀, −f); and (7.3.2)
    maps it back to (x, y) (with AᵀA = E)."""
    An, n = _rotation()
    A = An / n
    f, x0, y0, XS, YS, ZS = sp.symbols("f x_0 y_0 X_S Y_S Z_S", real=True)
    r = sp.Matrix([_x - x0, _y - y0, -f])
    ray = A * r
    lam = (_Z - ZS) / ray[2]                                   # the ray reaches height Z
    Xp, Yp, Zp = ray
    X_printed = XS + (_Z - ZS) * Xp / Zp
    Y_printed = YS + (_Z - ZS) * Yp / Zp
    on_ray = sp.cancel(X_printed - (XS + lam * ray[0])) == 0 and sp.cancel(Y_printed - (YS + lam * ray[1])) == 0
    star = lam * _product(An.T, An, n) * r           # Aᵀ(X − S) of the printed point
    back = sp.cancel(x0 - f * star[0] / star[2] - _x) == 0 and sp.cancel(y0 - f * star[1] / star[2] - _y) == 0
    return _ok(on_ray and back)


def monoplot_iteration(inputs: dict) -> dict:
    """Fig. 7.19: the iteration from the mean DEM height converges to the ray–DEM intersection."""
    dem, grid, eo, io, pixel, image, ground = _scene(100, float(inputs.get("tilt_deg", 2.0)))
    from ..synthetic import pixel_to_image
    rows = np.array([3, 40, 70, 96])
    x, y = pixel_to_image(rows.astype(float), rows.astype(float), image.shape, pixel)
    result = rectify.monoplot(np.column_stack([x, y]), eo, io, dem, grid, tol=float(inputs["tol"]))
    error = np.abs(result.XYZ - ground[rows, rows]).max()
    return {"converges": "yes" if error < 10 * float(inputs["tol"]) else "no",
            "max_iterations": int(result.iterations.max())}


def mosaic_rules(inputs: dict) -> dict:
    """§7.7: X₀M = min(X₀₁, X₀₂), Y₀M = max(Y₀₁, Y₀₂); each row from P1 up to and including the
    boundary pixel, then from P2."""
    g1 = rectify.RasterGrid(*inputs["origin1"], 1.0, (6, 8))
    g2 = rectify.RasterGrid(*inputs["origin2"], 1.0, (6, 8))
    x_cut = float(inputs["x_cut"])
    _, grid, source = rectify.mosaic([np.zeros(g1.shape), np.ones(g2.shape)], [g1, g2],
                                     [[x_cut, -1e6], [x_cut, 1e6]], return_source=True)
    row = int(round((grid.y0 - max(g1.y0, g2.y0) + 1) / grid.dy))    # a row both orthos cover
    boundary = int(np.floor((x_cut - grid.x0) / grid.dx))
    return {"X0M": grid.x0, "Y0M": grid.y0,
            "boundary_pixel_from": "P1" if source[row, boundary] == 0 else "P2",
            "next_pixel_from": "P2" if source[row, boundary + 1] == 1 else "P1"}


# --------------------------------------------------------------------------- §7.9
def apriori_check(inputs: dict) -> dict:
    """§7.9: the a-priori check (monoplotting the control points' image measurements on the DEM
    from their known heights) passes with the true orientation and flags an attitude error."""
    from ..camera import ExteriorOrientation
    from ..single_image import project
    dem, grid, eo, io, pixel, image, ground = _scene(100, 2.0)
    control = ground[[10, 40, 70, 90, 95], [90, 20, 60, 80, 15]]
    xy = project(control, eo, io)
    M = float(inputs["M"])
    ok = rectify.apriori_accuracy(xy, control, eo, io, dem, grid, M)
    dw = float(inputs["d_omega"])
    wrong = ExteriorOrientation(eo.Xs, eo.Ys, eo.Zs, eo.omega + dw, eo.alpha, eo.kappa)
    bad = rectify.apriori_accuracy(xy, control, wrong, io, dem, grid, M)
    return {"true_orientation_passes": "yes" if ok.passes else "no",
            "attitude_error_detected": "yes" if not bad.passes else "no",
            "mean_error_mm_wrong": bad.mean_error_mm}
