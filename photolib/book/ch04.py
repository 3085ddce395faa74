"""Chapter 4 worked examples: ``textbook/ch04.toml`` inputs → library calls → named quantities.

* §4.3 example (seed lines 2751–2829): DLT resection (4.2.1)–(4.2.3) of two simulated images from
  ten control points, interior orientation (4.2.4), projection centres (4.2.5), rotation matrices
  (4.2.6) and angles (1.3.6), forward intersection (4.3.1) and the correlation matrix of
  L₁…L₁₁ (1.8.10). :func:`dlt_example` (correct formulas) and :func:`dlt_example_as_printed`
  ((4.2.5) exactly as printed, without its minus sign) return every printed number by name.
* §4.4 example (seed lines 2930–2993): fundamental and essential matrices from the first 8 of 12
  points by the book's unnormalised SVD solution of (4.4.14) with f₃₃ = 1, the epipolar residuals
  of all 12 points, and the normalised coordinates (4.4.15): :func:`fe_example`.
* :func:`rounding_monte_carlo` — the spread of every quantity when the image coordinates, printed
  to 0.001 mm, are re-drawn within ± 0.0005 mm: the basis of each ``input-rounding`` bound
  (3σ plus half a printed unit, :func:`photolib.book.ch02.rounding_bound`).

Conventions of the printed tables (established in ``tests/test_ch04_examples.py``):

* the data were generated with the κ–α–ω matrix (1.3.5), so the angles are read back by (1.3.6);
* the book reads the angles off the matrix (4.2.6) itself, which is not exactly orthogonal for
  an 11-parameter DLT fitted to noisy data; :func:`dlt_example` does the same (the nearest
  rotation, ``DLTOrientation.eo``, is shown beside it in the notebook);
* L₉ and L₁₀ are printed multiplied by 10⁵ (names ``L9e5_img1`` …), L₁₁ unscaled;
* the correlation matrix printed is that of image 2;
* the printed F and E are in the layout x₂ᵀFx₁ = 0 (l₂ = F r₁), the transpose of the matrix
  that (4.4.13)/(4.4.14) define.
"""

from __future__ import annotations

import copy
import json
from functools import lru_cache

import numpy as np

from .. import projective as pj
from ..camera import InteriorOrientation
from . import ch02
from .ch02 import rounding_bound  # noqa: F401  (same bound policy as Chapter 2: 3σ + half a printed unit)

ROUNDING_MM = 0.0005
"""Half a unit of the printed image coordinates (0.001 mm); object coordinates are exact."""

L_NAMES = ("L1", "L2", "L3", "L4", "L5", "L6", "L7", "L8", "L9e5", "L10e5", "L11")
"""Printed columns of the L table: L₉ and L₁₀ appear multiplied by 10⁵."""
L_SCALE = np.array([1.0] * 8 + [1e5, 1e5, 1.0])


def _key(inputs: dict) -> str:
    return json.dumps(inputs, sort_keys=True)


# --- §4.3 --------------------------------------------------------------------------------------
def dlt_example_data(inputs: dict):
    """(XYZ, xy1, xy2, io) from the printed table: N, X, Y, Z, x₁, y₁, x₂, y₂."""
    pts = np.asarray(inputs["points"], dtype=float)
    io = InteriorOrientation(inputs["f_mm"], inputs["x0_mm"], inputs["y0_mm"])
    return pts[:, 1:4], pts[:, 4:6], pts[:, 6:8], io


@lru_cache(maxsize=64)
def _dlt_run(key: str):
    inputs = json.loads(key)
    XYZ, xy1, xy2, _ = dlt_example_data(inputs)
    res = tuple(pj.dlt_resection(XYZ, xy, method="book") for xy in (xy1, xy2))
    inter = pj.dlt_intersection([r.L for r in res], [xy1, xy2])
    return res, inter


def dlt_resections(inputs: dict):
    """The two :class:`~photolib.projective.DLTResection` results (4.2.1)–(4.2.3) and the
    :class:`~photolib.projective.DLTIntersection` (4.3.1) of the ten points."""
    return _dlt_run(_key(inputs))


def _dlt_quantities(inputs: dict, printed_centre: bool) -> dict:
    res, inter = dlt_resections(inputs)
    out = {}
    for i, r in enumerate(res, 1):
        out.update({f"{n}_img{i}": float(v) for n, v in zip(L_NAMES, r.L * L_SCALE)})
        o = r.orientation("kaw", printed=printed_centre)
        out.update({f"x0_img{i}": o.x0, f"y0_img{i}": o.y0, f"fx_img{i}": o.fx, f"fy_img{i}": o.fy})
        out.update({f"{c}_img{i}": float(v) for c, v in zip(("Xs", "Ys", "Zs"), o.center)})
        w, a, k = np.degrees(o.book_angles)                      # (1.3.6) on the matrix (4.2.6)
        out.update({f"omega_deg_img{i}": float(w), f"alpha_deg_img{i}": float(a), f"kappa_deg_img{i}": float(k)})
        out.update({f"a{p + 1}{q + 1}_img{i}": float(o.A_printed[p, q]) for p in range(3) for q in range(3)})
    corr = res[1].corr                                           # the book prints image 2's
    for p in range(11):
        for q in range(p + 1, 11):
            out[f"r_L{p + 1}_L{q + 1}"] = float(corr[p, q])
    for j, P in enumerate(inter.XYZ, 1):
        out.update({f"X{j}": float(P[0]), f"Y{j}": float(P[1]), f"Z{j}": float(P[2])})
    return out


def dlt_example(inputs: dict) -> dict:
    """Every printed number of the §4.3 example by the correct formulas ((4.2.5) with its minus sign)."""
    return _dlt_quantities(inputs, printed_centre=False)


def dlt_example_as_printed(inputs: dict) -> dict:
    """The same with (4.2.5) as printed, S = M⁻¹(L₄, L₈, 1)ᵀ: the negated centres of the book's table."""
    return _dlt_quantities(inputs, printed_centre=True)


# --- §4.4 --------------------------------------------------------------------------------------
def fe_example_data(inputs: dict):
    """(xy1, xy2, io) from the printed table: N, x₁, y₁, x₂, y₂ (the z = 1 columns omitted)."""
    pts = np.asarray(inputs["points"], dtype=float)
    return pts[:, 1:3], pts[:, 3:5], InteriorOrientation(inputs["f_mm"], inputs["x0_mm"], inputs["y0_mm"])


@lru_cache(maxsize=64)
def _fe_run(key: str):
    inputs = json.loads(key)
    xy1, xy2, io = fe_example_data(inputs)
    n = int(inputs["n_solve"])
    F = pj.fundamental_matrix(xy1[:n], xy2[:n], method="book")             # layout x2Fx1 (the printed one)
    E = pj.essential_matrix(xy1[:n], xy2[:n], io, method="book")
    return F, E


def fe_matrices(inputs: dict):
    """(F, E) of the §4.4 example: the book's solution (SVD null vector of (4.4.14), f₃₃ = e₃₃ = 1,
    no rank constraint) from the first ``n_solve`` points, in the printed layout x₂ᵀFx₁ = 0."""
    return _fe_run(_key(inputs))


def fe_example(inputs: dict) -> dict:
    """Every printed number of the §4.4 example: F, its residuals, r″ (4.4.15), E, its residuals."""
    xy1, xy2, io = fe_example_data(inputs)
    F, E = fe_matrices(inputs)
    out = {}
    for name, M in (("F", F), ("E", E)):
        out.update({f"{name}{p + 1}{q + 1}": float(M[p, q]) for p in range(3) for q in range(3)})
    h1 = pj.normalized_image_coordinates(xy1, io)
    h2 = pj.normalized_image_coordinates(xy2, io)
    for j in range(len(xy1)):
        out.update({f"x1n_{j + 1}": float(h1[j, 0]), f"y1n_{j + 1}": float(h1[j, 1]),
                    f"x2n_{j + 1}": float(h2[j, 0]), f"y2n_{j + 1}": float(h2[j, 1])})
    vF = pj.epipolar_residuals(F, xy1, xy2)
    vE = pj.epipolar_residuals(E, h1[:, :2], h2[:, :2])
    out.update({f"vF_{j + 1}": float(v) for j, v in enumerate(vF)})
    out.update({f"vE_{j + 1}": float(v) for j, v in enumerate(vE)})
    return out


# --- input rounding ------------------------------------------------------------------------------------
def perturb_image_coordinates(inputs: dict, rng) -> dict:
    """A copy of ``inputs`` with every printed image coordinate moved uniformly within ± 0.0005 mm.

    The §4.3 table is N, X, Y, Z, x₁, y₁, x₂, y₂ (columns 4–7 rounded, the object coordinates
    are exact), the §4.4 table N, x₁, y₁, x₂, y₂ (columns 1–4).
    """
    out = copy.deepcopy(inputs)
    pts = np.asarray(out["points"], dtype=float)
    cols = {8: [4, 5, 6, 7], 5: [1, 2, 3, 4]}[pts.shape[1]]
    pts[:, cols] += rng.uniform(-ROUNDING_MM, ROUNDING_MM, (len(pts), len(cols)))
    out["points"] = pts.tolist()
    return out


def rounding_monte_carlo(inputs: dict, compute, n: int = 200, seed: int = 2022) -> dict:
    """Standard deviation of every quantity of ``compute`` over ``n`` re-roundings of the image coordinates.

    The book's program worked with unrounded simulated coordinates and printed them to 0.001 mm;
    a uniform draw within ± half a unit around each printed value models that lost information
    (Chapter 2's :func:`photolib.book.ch02.rounding_monte_carlo` with :func:`perturb_image_coordinates`).
    """
    return ch02.rounding_monte_carlo(inputs, compute, n, seed, perturb=perturb_image_coordinates)
