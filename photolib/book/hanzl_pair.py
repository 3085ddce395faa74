"""Adapters for Hanzl §3 "Orientation and point determination from two images" (seed 002 lines 344–674).

Each function takes the ``inputs`` table of an entry of ``textbook/ch02_hanzl.toml`` (ids ``hanzl-3…``,
filed under Chibunichev Chapter 2) and returns ``{quantity: value}`` (examples) or
``{"printed_equals_derived": bool}`` (formulas). Formula checks compare the transcriptions of
:func:`photolib.derivations.parallax.printed_formulas` with :func:`~photolib.derivations.parallax.derived_formulas`;
the numbers are recomputed with :mod:`photolib.image_pair`. :func:`gruber_pair` builds the synthetic
Gruber-point pair of the notebook (the book prints no data for §3.2.3).
"""

from __future__ import annotations

import numpy as np
import sympy as sp

from .. import image_pair as ip
from ..camera import ExteriorOrientation, InteriorOrientation
from ..derivations import parallax as D
from ..single_image import project
from ._exact import zero as _zero

__all__ = ["formula_check", "example_3_1", "example_3_1_as_printed", "base_ratio", "camera_constant_error",
           "joint_count", "control_counts", "gruber_pair", "GRUBER_TRUTH"]



def formula_check(inputs: dict) -> dict:
    """Printed formula ``inputs["item"]`` (a key of :func:`~photolib.derivations.parallax.printed_formulas`) vs sympy."""
    item = inputs["item"]
    printed, derived = D.printed_formulas()[item], D.derived_formulas()[item]
    return {"printed_equals_derived": bool(_zero(printed - derived))}


def _accuracy(ms, c_mm, z_over_b, x_mm, y_mm, sigma_um):
    """σ_X, σ_Y, σ_Z (m) of Hanzl's normal case through :func:`photolib.image_pair.normal_case_accuracy`.

    Hanzl's m_s = Z/c and B/Z give H = m_s·c and the photo base b = B/m_s = c·(B/Z) (mm).
    """
    H = ms * c_mm / 1000.0                                        # m
    s = sigma_um / 1000.0                                         # mm
    return ip.normal_case_accuracy(H, c_mm, c_mm / z_over_b, s, s, s, x=x_mm, y=y_mm)


def example_3_1(inputs: dict) -> dict:
    """Example 3.1: σ_X = σ_Y and σ_Z for c = 150 mm and c = 300 mm (same m_s, same format)."""
    ms, zb, x, y, s = inputs["m_s"], inputs["Z_over_B"], inputs["x_mm"], inputs["y_mm"], inputs["sigma_um"]
    sx1, sy1, sz1 = _accuracy(ms, inputs["c_mm"], zb, x, y, s)
    k = inputs["c2_mm"] / inputs["c_mm"]                          # Z doubles with c at the same m_s, B does not
    sx2, sy2, sz2 = _accuracy(ms, inputs["c2_mm"], zb * k, x, y, s)
    return {"sigma_X (c = 150 mm)": sx1, "sigma_Y (c = 150 mm)": sy1, "sigma_Z (c = 150 mm)": sz1,
            "sigma_X (c = 300 mm)": sx2, "sigma_Y (c = 300 mm)": sy2, "sigma_Z (c = 300 mm)": sz2}


def example_3_1_as_printed(inputs: dict) -> dict:
    """The book's c = 300 mm numbers: x/c kept at 50/150 = 1/3 (i.e. x = 100 mm at c = 300 mm)."""
    out = example_3_1(inputs)
    k = inputs["c2_mm"] / inputs["c_mm"]
    sx, sy, sz = _accuracy(inputs["m_s"], inputs["c2_mm"], inputs["Z_over_B"] * k, inputs["x_mm"] * k,
                           inputs["y_mm"] * k, inputs["sigma_um"])
    out.update({"sigma_X (c = 300 mm)": sx, "sigma_Y (c = 300 mm)": sy, "sigma_Z (c = 300 mm)": sz})
    return out


def base_ratio(inputs: dict) -> dict:
    """Z/B of a pair with p % overlap: Z/B = c/(s(1 − p/100)) (s the format side, photolib.image_pair.photo_base)."""
    b = ip.photo_base(inputs["format_mm"], inputs["overlap_percent"])
    return {"Z/B": inputs["c_mm"] / b}


def camera_constant_error(inputs: dict) -> dict:
    """dZ = (Z/c)·dc = m_s·dc (m)."""
    return {"dZ": inputs["m_s"] * inputs["dc_mm"] / 1000.0}


def joint_count(inputs: dict) -> dict:
    """§3.2.2: observations and unknowns of the joint orientation (photolib.image_pair.orientation_counts)."""
    n = ip.orientation_counts(inputs["full"], inputs["planimetric"], inputs["height"], inputs["new"])
    return {"unknowns": n["unknowns"], "observations": n["observations"]}


def control_counts(inputs: dict) -> dict:
    """§3.2.3 (lines 446–452): equations of the absolute orientation, elements left for relative orientation,
    §3.2.3.1 (lines 512–514): eight y-parallax elements of which three are fixed, §3.2.5 (line 624): points for F."""
    a = ip.orientation_counts(2, 0, 1)["absolute_equations"]
    b = ip.orientation_counts(0, 2, 3)["absolute_equations"]
    eo = 6 * inputs["images"]
    elements = len(D.ELEMENTS)
    return {"equations (2 full + 1 height)": a, "equations (2 planimetric + 3 height)": b,
            "relative orientation elements": eo - inputs["absolute_elements"],
            "y-parallax elements": elements, "elements fixed": elements - len(D.PARALLAX_SYSTEMS["dependent"]),
            "points for F": len([s for s in D.derived_formulas()["622-normalised"].free_symbols if s.name[0] == "f"])}


GRUBER_TRUTH = {"dependent": dict(b_y=0.01, b_z=-0.02, omega2=0.004, alpha2=-0.003, kappa2=0.005),
                "independent": dict(alpha1=0.003, kappa1=-0.004, omega2=0.002, alpha2=-0.005, kappa2=0.006)}
"""True elements (rad; b_y, b_z as fractions of the base) of the synthetic Gruber pairs of the notebook."""


def gruber_pair(system: str, truth: dict | None = None, c=153.0, base=920.0, height=1530.0, d=900.0,
                relief=30.0, noise=0.0, seed=0):
    """A synthetic near-vertical pair with the six Gruber points (Fig. 3.3): (xy1, xy2, io, object points).

    Points at (0, 0), (b, 0), (0, ±d), (b, ±d) in the plane of the model with random relief ±``relief``;
    image 1 at (0, 0, H), image 2 at (b, b·b_y, H + b·b_z); angles Hanzl's R = R_ω R_φ R_κ (``"wak"``).
    """
    truth = GRUBER_TRUTH[system] if truth is None else truth
    rng = np.random.default_rng(seed)
    io = InteriorOrientation(c)
    P = np.array([[0, 0], [base, 0], [0, d], [base, d], [0, -d], [base, -d]], float)
    P = np.column_stack([P, rng.uniform(-relief, relief, len(P))])
    t = dict(b_y=0.0, b_z=0.0, omega1=0.0, alpha1=0.0, kappa1=0.0, omega2=0.0, alpha2=0.0, kappa2=0.0) | truth
    e1 = ExteriorOrientation(0, 0, height, t["omega1"], t["alpha1"], t["kappa1"], order="wak")
    e2 = ExteriorOrientation(base, base * t["b_y"], height + base * t["b_z"], t["omega2"], t["alpha2"], t["kappa2"],
                             order="wak")
    xy1, xy2 = project(P, e1, io), project(P, e2, io)
    return xy1 + rng.normal(0, noise, xy1.shape), xy2 + rng.normal(0, noise, xy2.shape), io, P
