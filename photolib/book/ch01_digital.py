"""Chapter 1, §1.10–§1.12 examples and formula checks: ``textbook/`` inputs → library → quantities.

Formula adapters return ``{"printed_equals_derived": bool}`` (plus diagnostic keys); the
derivations are done here with sympy from the geometry the text describes.
"""

from __future__ import annotations

import numpy as np
import sympy as sp

from .. import digital, scanners
from ..camera import as_points
from ._exact import zero


# ---------------------------------------------------------------- §1.10 worked examples
def subpixel_corner_example(inputs: dict) -> dict:
    """§1.10: element a'_{i'j'} of an n× magnified pixel (i, j), origin at the corner (1.10.2)."""
    x, y = digital.subpixel_coordinates(inputs["i"], inputs["j"], inputs["i_sub"], inputs["j_sub"],
                                        inputs["n"], origin="corner")
    return {"x_p": x, "y_p": y}


def physical_example(inputs: dict) -> dict:
    """§1.10: the same element in physical units, x_c = Δ·x_p (1.10.3)."""
    x, y = digital.subpixel_coordinates(inputs["i"], inputs["j"], inputs["i_sub"], inputs["j_sub"],
                                        inputs["n"], origin="corner")
    xc, yc = digital.pixel_to_physical(x, y, inputs["pixel_size_um"])
    return {"x_c": xc, "y_c": yc}


def subpixel_center_example(inputs: dict) -> dict:
    """§1.10: the same element with the origin at the centre of the lower-left pixel (1.10.5)."""
    x, y = digital.subpixel_coordinates(inputs["i"], inputs["j"], inputs["i_sub"], inputs["j_sub"],
                                        inputs["n"], origin="center")
    return {"x_p": x, "y_p": y}


# ---------------------------------------------------------------- §1.11 / §1.12 statements
def min_fiducials_example(inputs: dict) -> dict:
    """§1.11: smallest number of fiducials for which the (1.11.2) equations determine a0…b2.

    Builds the design matrix of (1.11.2) for n generic (seeded random) fiducials and finds the
    smallest n at which its rank reaches 6; also reports the rank for 3 collinear fiducials.
    """
    rng = np.random.default_rng(inputs.get("seed", 0))

    def rank(pts):
        B = np.zeros((2 * len(pts), 6))
        B[0::2, 0], B[0::2, 1:3] = 1.0, pts
        B[1::2, 3], B[1::2, 4:6] = 1.0, pts
        return np.linalg.matrix_rank(B)

    n_min = next(n for n in range(1, 10) if rank(rng.uniform(-110, 110, (n, 2))) == 6)
    t = np.array([-1.0, 0.3, 2.0])[:, None]
    collinear = np.hstack([t, 2 * t + 1]) * 50
    return {"min_fiducials": n_min, "rank_collinear_3": int(rank(collinear))}


def radiometric_levels_example(inputs: dict) -> dict:
    """§1.12: 8 bit → 2⁸ = 256 grey levels, numbered 0…255."""
    levels = scanners.radiometric_levels(inputs["bits"])
    return {"levels": levels, "min_level": 0, "max_level": levels - 1}


# ---------------------------------------------------------------- formula checks (sympy)
def formula_1_10_5(inputs: dict) -> dict:
    """(1.10.5) equals (1.10.2) with the origin moved to the centre of the corner pixel (−½ px)."""
    i, j, ii, jj, n = sp.symbols("i j i' j' n", positive=True)
    derived = (j + (jj + sp.Rational(1, 2)) / n - sp.Rational(1, 2),
               i + (ii + sp.Rational(1, 2)) / n - sp.Rational(1, 2))
    printed = ((j - sp.Rational(1, 2)) + (jj + sp.Rational(1, 2)) / n,
               (i - sp.Rational(1, 2)) + (ii + sp.Rational(1, 2)) / n)
    return {"printed_equals_derived": all(zero(p - d) for p, d in zip(printed, derived))}


def formula_1_10_6(inputs: dict) -> dict:
    """(1.10.6): the fragment is the image moved as a whole, so the shift is one constant Δx_p.

    Printed: x_pi = x'_pi + Δx_pi, a shift with the pixel index i. A rigid move of the fragment
    (its origin at x'_oc = Δx_p, as the text says) keeps the spacing of any two pixels; the
    check compares x_p2 − x_p1 with x'_p2 − x'_p1 for both forms.
    """
    xp1, xp2, dx = sp.symbols("x'_p1 x'_p2 Delta_x_p")
    dx1, dx2 = sp.symbols("Delta_x_p1 Delta_x_p2")
    derived_spacing = sp.simplify((xp2 + dx) - (xp1 + dx) - (xp2 - xp1))
    printed_spacing = sp.simplify((xp2 + dx2) - (xp1 + dx1) - (xp2 - xp1))
    return {"printed_equals_derived": bool(printed_spacing == 0 and derived_spacing == 0),
            "derived_is_translation": bool(derived_spacing == 0)}


def formula_1_10_7(inputs: dict) -> dict:
    """(1.10.7) equals the unique bilinear interpolant c0 + c1·u + c2·v + c3·u·v through K, M, L, N.

    K = (0, 0), M = (0, 1) in one column, L = (1, 0), N = (1, 1) in the next; u = Δx_p, v = Δy_p.
    """
    u, v = sp.symbols("Delta_x_p Delta_y_p")
    DK, DM, DL, DN = sp.symbols("D_K D_M D_L D_N")
    c = sp.symbols("c0:4")
    f = c[0] + c[1] * u + c[2] * v + c[3] * u * v
    sol = sp.solve([f.subs({u: 0, v: 0}) - DK, f.subs({u: 0, v: 1}) - DM,
                    f.subs({u: 1, v: 0}) - DL, f.subs({u: 1, v: 1}) - DN], c)
    derived = f.subs(sol)
    D1 = DK + (DM - DK) * v
    D2 = DL + (DN - DL) * v
    printed = D1 + (D2 - D1) * u
    return {"printed_equals_derived": sp.expand(printed - derived) == 0}


def _trig_simplify_zero(e) -> bool:
    return sp.simplify(sp.expand_trig(e)) == 0


def _similarity_symbols():
    return sp.symbols("xbar ybar a0 b0 phi k_x k_y x y", real=True)


def _derived_forward():
    """Camera x, y of a scanner point: projection on the image axes (angle φ), scaled by k_x, k_y."""
    xb, yb, a0, b0, phi, kx, ky, x, y = _similarity_symbols()
    ex = sp.Matrix([sp.cos(phi), sp.sin(phi)])          # image x axis in the scanner system (1.11.8)
    ey = sp.Matrix([-sp.sin(phi), sp.cos(phi)])         # image y axis, +90° from x
    d = sp.Matrix([xb - a0, yb - b0])
    return kx * ex.dot(d), ky * ey.dot(d)


def formula_1_11_6(inputs: dict) -> dict:
    """(1.11.6): printed (OCR) form vs the transformation derived from the geometry.

    Also reports whether the reconstruction x = k_x[a1(x̄−a0) + a2(ȳ−b0)],
    y = k_y[−a2(x̄−a0) + a1(ȳ−b0)] equals the derivation, is inverted exactly by the exact form of
    (1.11.10), and maps mark 2 onto the x axis (y = 0) when φ is taken by (1.11.8).
    """
    xb, yb, a0, b0, phi, kx, ky, x, y = _similarity_symbols()
    a1, a2 = sp.cos(phi), sp.sin(phi)
    fx, fy = _derived_forward()
    printed = (kx * (a1 * (xb - a0) + (yb - b0)), ky * (-a2 * (xb - a0) + (yb - b0)))
    recon = (kx * (a1 * (xb - a0) + a2 * (yb - b0)), ky * (-a2 * (xb - a0) + a1 * (yb - b0)))
    same = lambda p, q: all(zero(s - t, _trig_simplify_zero) for s, t in zip(p, q))  # noqa: E731
    exact_inv = (a0 + a1 * x / kx - a2 * y / ky, b0 + a2 * x / kx + a1 * y / ky)
    round_trip = [zero(r.subs({xb: exact_inv[0], yb: exact_inv[1]}, simultaneous=True) - t)
                  for r, t in zip(recon, (x, y))]
    # mark 2 at distance L from mark 1 = origin, along φ: y must vanish
    L = sp.symbols("L", positive=True)
    mark2 = {xb: a0 + L * a1, yb: b0 + L * a2}
    return {"printed_equals_derived": same(printed, (fx, fy)),
            "reconstruction_equals_derived": same(recon, (fx, fy)),
            "exact_inverse_round_trip": all(round_trip),
            "mark2_on_x_axis": zero(recon[1].subs(mark2)),
            "printed_mark2_on_x_axis": zero(printed[1].subs(mark2))}


def formula_1_11_7(inputs: dict) -> dict:
    """(1.11.7): the printed a0, b0 equal the sympy intersection of the lines 1–2 and 4–3."""
    x1, y1, x2, y2, x3, y3, x4, y4, X, Y = sp.symbols("x1 y1 x2 y2 x3 y3 x4 y4 X Y", real=True)
    c1 = (y2 - y1) / (x2 - x1)
    c2 = (y3 - y4) / (x3 - x4)
    # lines through the marks written without slopes (cross products), then solved
    l12 = (X - x1) * (y2 - y1) - (Y - y1) * (x2 - x1)
    l43 = (X - x4) * (y3 - y4) - (Y - y4) * (x3 - x4)
    sol = sp.solve([l12, l43], [X, Y], dict=True)[0]
    a0 = ((y4 - y1) + c1 * x1 - c2 * x4) / (c1 - c2)
    b0_first = y1 + c1 * (a0 - x1)
    b0_second = y4 + c2 * (a0 - x4)
    ok = all(zero(p - sol[s]) for p, s in ((a0, X), (b0_first, Y), (b0_second, Y)))
    return {"printed_equals_derived": bool(ok)}


def formula_1_11_10(inputs: dict) -> dict:
    """(1.11.10): the printed inverse vs the inverse of (1.11.6) solved by sympy.

    ``printed_equals_derived`` is False: they differ by a2·(1/k_y − 1/k_x)·(y, x). The extra key
    ``equal_when_kx_eq_ky`` confirms that the printed form is exact for k_x = k_y.
    """
    xb, yb, a0, b0, phi, kx, ky, x, y = _similarity_symbols()
    fx, fy = _derived_forward()
    sol = sp.solve([fx - x, fy - y], [xb, yb], dict=True)[0]
    a1, a2 = sp.cos(phi), sp.sin(phi)
    printed = (a0 + (a1 * x - a2 * y) / kx, b0 + (a2 * x + a1 * y) / ky)
    diff = [p - sol[s] for p, s in zip(printed, (xb, yb))]
    expected_diff = (a2 * (1 / ky - 1 / kx) * y, a2 * (1 / ky - 1 / kx) * x)
    return {"printed_equals_derived": all(zero(d) for d in diff),
            "equal_when_kx_eq_ky": all(zero(d.subs(ky, kx)) for d in diff),
            "difference_is_a2_dk": all(zero(d - e) for d, e in zip(diff, expected_diff))}


def book_origin(measured):
    """The scanner origin a₀, b₀ by the slope form (1.11.7) exactly as printed.

    Uses the slopes c₁ of line 1–2 and c₂ of line 3–4 of the four side fiducials, so it fails
    (returns NaN) when line 3–4 is vertical — the case an aligned scan produces; the library's
    :func:`photolib.interior.fiducial_similarity` solves the same intersection as a 2×2 system
    and has no such case. Shown in the Chapter 1 notebook beside the library's answer.
    """
    p = as_points(measured, 2, "measured fiducials")
    (x1, y1), (x2, y2), (x3, y3), (x4, y4) = p
    with np.errstate(divide="ignore", invalid="ignore"):
        c1 = (y2 - y1) / (x2 - x1)
        c2 = (y3 - y4) / (x3 - x4)
        a0 = ((y4 - y1) + c1 * x1 - c2 * x4) / (c1 - c2)
    return float(a0), float(y1 + c1 * (a0 - x1))
