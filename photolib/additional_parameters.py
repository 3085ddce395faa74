"""Additional parameters (AP) of image deformation — the models of A.V. Sementsov's thesis §2.1,
appendix to Chapter 11 (§11.3, camera calibration; ``chapters/appendix_sementsov.ipynb``).

Source: A.V. Sementsov, PhD thesis, SGUGiT 2019 (seed ``004_ae61db45a4af28ce.txt``), eqs. (2)–(4),
lines 472–500. Three models of the corrections σx, σy of image coordinates:

* ``"ebner12"`` — the orthogonal 12-parameter set (2) attributed to Grün and Ebner, **as printed**
  (reproductions of Ebner 1976 differ in some signs and labels; orthogonality does not depend on them)
  with the one typo fixed: the printed ``b_4`` of σy is c₄. b is the spacing of the 3 × 3 grid of standard points
  (x, y ∈ {−b, 0, b}) on which the 12 fields are mutually orthogonal; the thesis does not define it,
  so it is a required argument. :func:`ebner12`.
* ``"brown"`` — Brown's physically motivated model (3): affine/deformation terms a₁…a₇, b₁…b₇, the
  radial terms c₁…c₇ (scaled by x/f, y/f) and k₁…k₃, the decentring terms p₁, p₂. :func:`brown`.
* ``"photomod"`` — the model of the PHOTOMOD workstation (4): radial k₁…k₃, tangential P₁, P₂ and the
  uniform deformation a₁, a₂, b₁, b₂, **with the letters as printed** (b₁, b₂ in σx, a₁, a₂ in σy).
  :func:`photomod`. The thesis uses its radial–tangential part for all the calibrations of Table B.1.

Direction. The thesis does not say whether σ is the *correction* added to a measured coordinate or the
*distortion* added to the ideal one (nor where the centre of the coordinates is). Every function here
evaluates σ at the coordinates it is given: :func:`apply_ap` returns xy + σ(xy) and :func:`invert_ap`
solves u + σ(u) = xy by fixed-point iteration. Under the reading adopted in the appendix — σ is a
correction added to measured coordinates reduced to the principal point, as in (1.2.2)/(1.2.3) of
Chapter 1 — :func:`apply_ap` undistorts (measured → ideal) and :func:`invert_ap` gives the measured
point of an ideal one; under the other reading the roles swap. The Table B.1/Table 7 comparison of
the appendix favours the correction reading (75.0″/83.4″ against the printed 75.8″/87.0″, the
distortion reading gives 196.6″/123.2″).

Hanzl's models (Hanzl, Fotogrammetrie, Modul 01, §4.4 and §5.4.1, seed 002 lines 759–982), kept
apart in :data:`HANZL_MODELS` (the functions below accept both families):

* ``"hanzl17"`` — Ebner's orthogonal set g₁…g₁₂ with **Hanzl's signs** (the standard Ebner 1976 set:
  +g₅(y² − 2b²/3), −g₄(2y² − 4b²/3), unlike the thesis' (2)), the radial g₁₃…g₁₅ x(r² − r₀²),
  x(r⁴ − r₀⁴), x(r⁶ − r₀⁶) (the OCR prints (r² − r₀²) three times, line 776: transcription) and the
  tangential g₁₆, g₁₇. b = image base (92 mm for 23 cm and 60 % overlap), r₀ the radius of zero
  radial distortion. :func:`hanzl17`.
* ``"brown18"`` — Brown's 18 parameters a₁…a₁₈ (lines 966–968), in x, y and c. :func:`brown18`.
* ``"murai"`` — Murai's K₁, K₂, P₁…P₆ (lines 970–972). :func:`murai`.

Hanzl's dx, dy are corrections of the measured coordinates (the same reading as above). The ORIENT
polynomial (lines 976–982) is garbled in the source and not implemented.

For self-calibration (e.g. Ebner's set as an option of a bundle adjustment): :func:`ap_corrections`
gives (dx, dy) for any model, :func:`parameter_names` its parameter names, :func:`ap_basis` the
derivatives ∂σ/∂parameter (every model is linear in its parameters, so the basis is σ at the unit
parameter vectors — no hand-written derivatives). The sympy forms are in
:mod:`photolib.derivations.planar_target`.
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np

from . import _checks
from .camera import as_points
from .errors import ConvergenceError, InputError
from .rotation import _numbers

__all__ = ["MODELS", "HANZL_MODELS", "EBNER12_NAMES", "BROWN_NAMES", "PHOTOMOD_NAMES", "HANZL17_NAMES",
           "BROWN18_NAMES", "MURAI_NAMES", "parameter_names", "ebner12", "brown", "photomod", "hanzl17", "brown18",
           "murai", "ap_corrections", "ap_basis", "apply_ap", "invert_ap"]

MODELS = ("ebner12", "brown", "photomod")
"""The AP models: (2), (3), (4)."""

EBNER12_NAMES = tuple(f"c{i}" for i in range(1, 13))
"""Parameters of (2): c₁ … c₁₂."""

BROWN_NAMES = (tuple(f"a{i}" for i in range(1, 8)) + tuple(f"b{i}" for i in range(1, 8))
               + tuple(f"c{i}" for i in range(1, 8)) + ("k1", "k2", "k3", "p1", "p2"))
"""Parameters of (3): a₁…a₇, b₁…b₇, c₁…c₇, k₁, k₂, k₃, p₁, p₂ (26)."""

PHOTOMOD_NAMES = ("k1", "k2", "k3", "P1", "P2", "a1", "a2", "b1", "b2")
"""Parameters of (4): k₁, k₂, k₃, P₁, P₂, a₁, a₂, b₁, b₂."""

HANZL_MODELS = ("hanzl17", "brown18", "murai")
"""Hanzl's models: Ebner + radial + tangential (§4.4), Brown 18 and Murai (§5.4.1)."""

HANZL17_NAMES = tuple(f"g{i}" for i in range(1, 18))
"""g₁ … g₁₇ of §4.4: g₁…g₁₂ Ebner, g₁₃…g₁₅ radial, g₁₆, g₁₇ tangential."""

BROWN18_NAMES = tuple(f"a{i}" for i in range(1, 19))
"""a₁ … a₁₈ of Brown's model in §5.4.1."""

MURAI_NAMES = ("K1", "K2", "P1", "P2", "P3", "P4", "P5", "P6")
"""K₁, K₂, P₁ … P₆ of Murai's model in §5.4.1."""

_NAMES = {"ebner12": EBNER12_NAMES, "brown": BROWN_NAMES, "photomod": PHOTOMOD_NAMES, "hanzl17": HANZL17_NAMES,
          "brown18": BROWN18_NAMES, "murai": MURAI_NAMES}
_ALL = MODELS + HANZL_MODELS


def _model(model) -> str:
    if not isinstance(model, str) or model not in _ALL:
        raise InputError(f"unknown AP model {model!r}; use one of {', '.join(_ALL)}")
    return model


def parameter_names(model) -> tuple:
    """The parameter names of an AP model, in the order :func:`ap_corrections` expects a sequence.

    Parameters
    ----------
    model : {"ebner12", "brown", "photomod", "hanzl17", "brown18", "murai"}
        (2), (3), (4) or Hanzl's models.

    Returns
    -------
    tuple of str

    Raises
    ------
    InputError
        Unknown model.

    References
    ----------
    Sementsov (2019), eqs. (2)–(4), lines 472–500.

    Examples
    --------
    >>> parameter_names("photomod")
    ('k1', 'k2', 'k3', 'P1', 'P2', 'a1', 'a2', 'b1', 'b2')
    """
    return _NAMES[_model(model)]


def _params(model, params) -> np.ndarray:
    names = _NAMES[model]
    if isinstance(params, Mapping):
        unknown = sorted(set(params) - set(names))
        if unknown:
            raise InputError(f"{model}: unknown parameter(s) {unknown}; the parameters are {', '.join(names)}")
        values = [params.get(n, 0.0) for n in names]
    else:
        if isinstance(params, (str, bytes)):
            raise InputError(f"{model}: parameters must be numbers, got the string {params!r}")
        values = params
    arr = np.asarray(_numbers(values, f"{model} parameters"), dtype=float)
    if arr.shape != (len(names),):
        raise InputError(f"{model}: expected {len(names)} parameters ({', '.join(names)}), got shape {arr.shape}")
    return arr


def _xy(xy):
    return as_points(xy, 2, "image coordinates")


def _ebner(x, y, c, b):
    q = 2.0 * b * b / 3.0
    X2, Y2 = x * x - q, y * y - q
    sx = (c[0] * x + c[1] * y - c[2] * (2 * x * x - 2 * q) + c[3] * x * y - c[4] * Y2 + c[6] * x * Y2
          + c[8] * X2 * y + c[10] * X2 * Y2)
    sy = (-c[0] * y + c[1] * x + c[2] * x * y + c[3] * (2 * y * y - 2 * q) + c[5] * X2 + c[7] * X2 * y
          + c[9] * x * Y2 + c[11] * X2 * Y2)
    return np.column_stack([sx, sy])


def ebner12(xy, params, b) -> np.ndarray:
    """σx, σy of the orthogonal 12-parameter set (2), as printed (``b_4`` read as c₄).

    σx = c₁x + c₂y − c₃(2x² − 4b²/3) + c₄xy − c₅(y² − 2b²/3) + c₇x(y² − 2b²/3) + c₉(x² − 2b²/3)y
    + c₁₁(x² − 2b²/3)(y² − 2b²/3);
    σy = −c₁y + c₂x + c₃xy + c₄(2y² − 4b²/3) + c₆(x² − 2b²/3) + c₈(x² − 2b²/3)y + c₁₀x(y² − 2b²/3)
    + c₁₂(x² − 2b²/3)(y² − 2b²/3).

    Parameters
    ----------
    xy : (n, 2) array
        Image coordinates relative to the image centre (the centre of the 3 × 3 grid).
    params : sequence of 12 numbers or mapping
        c₁ … c₁₂ (a mapping may omit parameters, which are then 0).
    b : float
        Spacing of the 3 × 3 grid of standard points (x, y ∈ {−b, 0, b}), > 0, in the unit of xy.

    Returns
    -------
    (n, 2) ndarray
        σx, σy.

    Raises
    ------
    InputError
        Bad shapes, NaN/inf, unknown parameter names, b ≤ 0.

    References
    ----------
    Sementsov (2019), eq. (2), lines 476–480; H. Ebner, Self calibrating block adjustment,
    Bildmessung und Luftbildwesen 44 (1976) 128–139; A. Grün (1978) [69].

    Examples
    --------
    >>> ebner12([[1.0, 0.0]], {"c1": 2.0}, b=1.0)
    array([[2., 0.]])
    """
    p = _xy(xy)
    c = _params("ebner12", params)
    b = _checks.number(b, "b", positive=True)
    return _ebner(p[:, 0], p[:, 1], c, b)


def _brown(x, y, p, f):
    a, bb, c = p[0:7], p[7:14], p[14:21]
    k1, k2, k3, p1, p2 = p[21:26]
    r2 = x * x + y * y
    radial_c = (c[0] * x * x + c[1] * x * y + c[2] * y * y + c[3] * x ** 3 + c[4] * x * x * y + c[5] * x * y * y
                + c[6] * y ** 3) / f
    radial_k = k1 * r2 + k2 * r2 ** 2 + k3 * r2 ** 3
    sx = (a[0] * x + a[1] * y + a[2] * x * x + a[3] * x * y + a[4] * y * y + a[5] * x * x * y + a[6] * x * y * y
          + x * radial_c + x * radial_k + p1 * (y * y + 3 * x * x) + 2 * p2 * x * y)
    sy = (bb[0] * x + bb[1] * y + bb[2] * x * x + bb[3] * x * y + bb[4] * y * y + bb[5] * x * x * y
          + bb[6] * x * y * y + y * radial_c + y * radial_k + 2 * p1 * x * y + p2 * (3 * y * y + x * x))
    return np.column_stack([sx, sy])


def brown(xy, params, f) -> np.ndarray:
    """σx, σy of Brown's model (3) as printed.

    σx = a₁x + a₂y + a₃x² + a₄xy + a₅y² + a₆x²y + a₇xy² + (x/f)(c₁x² + c₂xy + c₃y² + c₄x³ + c₅x²y + c₆xy²
    + c₇y³) + x(k₁r² + k₂r⁴ + k₃r⁶) + p₁(y² + 3x²) + 2p₂xy, σy likewise with b₁…b₇, y/f,
    2p₁xy + p₂(3y² + x²); r² = x² + y².

    Parameters
    ----------
    xy : (n, 2) array
        Image coordinates (reduced to the principal point).
    params : sequence of 26 numbers or mapping
        In the order of :data:`BROWN_NAMES`.
    f : float
        Principal distance (unit of xy), > 0.

    Returns
    -------
    (n, 2) ndarray
        σx, σy.

    Raises
    ------
    InputError
        Bad shapes, NaN/inf, unknown parameter names, f ≤ 0.

    References
    ----------
    Sementsov (2019), eq. (3), lines 482–492; D.C. Brown (1974) [66].

    Examples
    --------
    >>> brown([[1.0, 0.0]], {"p1": 1.0}, f=100.0)
    array([[3., 0.]])
    """
    p = _xy(xy)
    q = _params("brown", params)
    f = _checks.number(f, "f", positive=True)
    return _brown(p[:, 0], p[:, 1], q, f)


def _photomod(x, y, p):
    k1, k2, k3, P1, P2, a1, a2, b1, b2 = p
    r2 = x * x + y * y
    radial = k1 * r2 + k2 * r2 ** 2 + k3 * r2 ** 3
    sx = -x * radial - P1 * (2 * x * x + r2) - 2 * P2 * x * y - b1 * x - b2 * y
    sy = -y * radial - P2 * (2 * y * y + r2) - 2 * P1 * x * y - a1 * x - a2 * y
    return np.column_stack([sx, sy])


def photomod(xy, params) -> np.ndarray:
    """σx, σy of the PHOTOMOD model (4), letters as printed.

    σx = −k₁xr² − k₂xr⁴ − k₃xr⁶ − P₁(2x² + r²) − 2P₂xy − b₁x − b₂y,
    σy = −k₁yr² − k₂yr⁴ − k₃yr⁶ − P₂(2y² + r²) − 2P₁xy − a₁x − a₂y, r² = x² + y².
    The radial–tangential part is minus Brown's correction (1.2.2) of Chapter 1 with p = P.

    Parameters
    ----------
    xy : (n, 2) array
        Image coordinates reduced to the centre of distortion (the principal point in the appendix).
        Table B.1's coefficients are in pixel units (k₁ px⁻², k₂ px⁻⁴, k₃ px⁻⁶, P px⁻¹).
    params : sequence of 9 numbers or mapping
        In the order of :data:`PHOTOMOD_NAMES`.

    Returns
    -------
    (n, 2) ndarray
        σx, σy.

    Raises
    ------
    InputError
        Bad shapes, NaN/inf, unknown parameter names.

    References
    ----------
    Sementsov (2019), eq. (4), lines 494–504; Table B.1, lines 2024–2036.

    Examples
    --------
    >>> photomod([[1000.0, 0.0]], {"k1": -1e-8})
    array([[10.,  0.]])
    """
    p = _xy(xy)
    return _photomod(p[:, 0], p[:, 1], _params("photomod", params))


def _hanzl17(x, y, g, b, r0):
    q = 2.0 * b * b / 3.0
    X2, Y2 = x * x - q, y * y - q
    r2 = x * x + y * y
    rad = g[12] * (r2 - r0 ** 2) + g[13] * (r2 ** 2 - r0 ** 4) + g[14] * (r2 ** 3 - r0 ** 6)
    dx = (g[0] * x + g[1] * y - g[2] * (2 * x * x - 2 * q) + g[3] * x * y + g[4] * Y2 + g[6] * x * Y2
          + g[8] * y * X2 + g[10] * X2 * Y2 + x * rad + g[15] * (r2 + 2 * x * x) + g[16] * 2 * x * y)
    dy = (-g[0] * y + g[1] * x + g[2] * x * y - g[3] * (2 * y * y - 2 * q) + g[5] * X2 + g[7] * y * X2
          + g[9] * x * Y2 + g[11] * X2 * Y2 + y * rad + g[15] * 2 * x * y + g[16] * (r2 + 2 * y * y))
    return np.column_stack([dx, dy])


def hanzl17(xy, params, b, r0=0.0) -> np.ndarray:
    """dx, dy of Hanzl's §4.4 set: Ebner's 12 orthogonal parameters, radial g₁₃…g₁₅, tangential g₁₆, g₁₇.

    dx = g₁x + g₂y − g₃(2x² − 4b²/3) + g₄xy + g₅(y² − 2b²/3) + g₇x(y² − 2b²/3) + g₉y(x² − 2b²/3)
    + g₁₁(x² − 2b²/3)(y² − 2b²/3) + x[g₁₃(r² − r₀²) + g₁₄(r⁴ − r₀⁴) + g₁₅(r⁶ − r₀⁶)] + g₁₆(r² + 2x²) + 2g₁₇xy;
    dy = −g₁y + g₂x + g₃xy − g₄(2y² − 4b²/3) + g₆(x² − 2b²/3) + g₈y(x² − 2b²/3) + g₁₀x(y² − 2b²/3)
    + g₁₂(x² − 2b²/3)(y² − 2b²/3) + y[…] + 2g₁₆xy + g₁₇(r² + 2y²).

    The radial powers r⁴ − r₀⁴, r⁶ − r₀⁶ are our reading of the OCR, which prints (r² − r₀²) for all
    three terms (line 776; identical terms could not be separate unknowns).

    Parameters
    ----------
    xy : (n, 2) array
        Image coordinates relative to the image centre (the centre of Ebner's 3 × 3 grid).
    params : sequence of 17 numbers or mapping
        g₁ … g₁₇ (:data:`HANZL17_NAMES`; a mapping may omit parameters, which are then 0).
    b : float
        Image base (grid spacing x, y ∈ {−b, 0, b}), > 0: 92 mm for a 23 cm format at 60 % overlap.
    r0 : float
        Radius of zero radial distortion, ≥ 0.

    Returns
    -------
    (n, 2) ndarray
        dx, dy.

    Raises
    ------
    InputError
        Bad shapes, NaN/inf, unknown parameter names, b ≤ 0, r0 < 0.

    References
    ----------
    Hanzl, Fotogrammetrie, Modul 01, §4.4 (seed 002 lines 759–796); H. Ebner (1976); Chibunichev §3.6.

    Examples
    --------
    >>> hanzl17([[92.0, 0.0]], {"g1": 1e-5}, b=92.0)
    array([[0.00092, 0.     ]])
    """
    p = _xy(xy)
    g = _params("hanzl17", params)
    (b, r0), _ = _extras("hanzl17", b, None, r0)
    return _hanzl17(p[:, 0], p[:, 1], g, b, r0)


def _brown18(x, y, a, c):
    a = np.concatenate([[0.0], a])
    r2 = x * x + y * y
    common = a[13] * (x * x - y * y) + a[14] * x * x * y * y + a[15] * (x ** 4 - y ** 4)
    rad = a[16] * r2 + a[17] * r2 ** 2 + a[18] * r2 ** 3
    dx = (a[1] * x + a[2] * y + a[3] * x * y + a[4] * y * y + a[5] * x * x * y + a[6] * x * y * y
          + a[7] * x * x * y * y + x / c * common + x * rad)
    dy = (a[8] * x * y + a[9] * x * x + a[10] * x * x * y + a[11] * x * y * y + a[12] * x * x * y * y
          + y / c * common + y * rad)
    return np.column_stack([dx, dy])


def brown18(xy, params, c) -> np.ndarray:
    """dx, dy of Brown's 18-parameter model as printed by Hanzl (§5.4.1).

    dx = a₁x + a₂y + a₃xy + a₄y² + a₅x²y + a₆xy² + a₇x²y² + (x/c)(a₁₃(x² − y²) + a₁₄x²y² + a₁₅(x⁴ − y⁴))
    + x(a₁₆r² + a₁₇r⁴ + a₁₈r⁶); dy = a₈xy + a₉x² + a₁₀x²y + a₁₁xy² + a₁₂x²y² + (y/c)(…) + y(…).

    Parameters
    ----------
    xy : (n, 2) array
        Image coordinates reduced to the principal point.
    params : sequence of 18 numbers or mapping
        a₁ … a₁₈ (:data:`BROWN18_NAMES`).
    c : float
        Camera constant (unit of xy), > 0.

    Returns
    -------
    (n, 2) ndarray
        dx, dy.

    Raises
    ------
    InputError
        Bad shapes, NaN/inf, unknown parameter names, c ≤ 0.

    References
    ----------
    Hanzl, Fotogrammetrie, Modul 01, §5.4.1 (seed 002 lines 966–968), after D.C. Brown (1976).

    Examples
    --------
    >>> brown18([[2.0, 1.0]], {"a3": 0.5, "a9": 0.25}, c=50.0)
    array([[1., 1.]])
    """
    p = _xy(xy)
    a = _params("brown18", params)
    _, c = _extras("brown18", None, c)
    return _brown18(p[:, 0], p[:, 1], a, c)


def _murai(x, y, q):
    K1, K2, P1, P2, P3, P4, P5, P6 = q
    r2 = x * x + y * y
    rad = K1 * r2 + K2 * r2 ** 2
    return np.column_stack([x * rad + P1 * x + P2 * y + P3 * x * y + P4 * y * y, y * rad + P5 * x * y + P6 * x * x])


def murai(xy, params) -> np.ndarray:
    """dx, dy of Murai's model as printed by Hanzl (§5.4.1).

    dx = x(K₁r² + K₂r⁴) + (P₁x + P₂y + P₃xy + P₄y²), dy = y(K₁r² + K₂r⁴) + (P₅xy + P₆x²).

    Parameters
    ----------
    xy : (n, 2) array
        Image coordinates reduced to the principal point.
    params : sequence of 8 numbers or mapping
        K₁, K₂, P₁ … P₆ (:data:`MURAI_NAMES`).

    Returns
    -------
    (n, 2) ndarray
        dx, dy.

    Raises
    ------
    InputError
        Bad shapes, NaN/inf, unknown parameter names.

    References
    ----------
    Hanzl, Fotogrammetrie, Modul 01, §5.4.1 (seed 002 lines 970–972).

    Examples
    --------
    >>> murai([[1.0, 1.0]], {"K1": 0.5, "P6": 1.0})
    array([[1., 2.]])
    """
    p = _xy(xy)
    return _murai(p[:, 0], p[:, 1], _params("murai", params))


def _evaluate(model, p, q, b, f):
    if model == "ebner12":
        return _ebner(p[:, 0], p[:, 1], q, b)
    if model == "brown":
        return _brown(p[:, 0], p[:, 1], q, f)
    if model == "hanzl17":
        return _hanzl17(p[:, 0], p[:, 1], q, b[0], b[1])
    if model == "brown18":
        return _brown18(p[:, 0], p[:, 1], q, f)
    if model == "murai":
        return _murai(p[:, 0], p[:, 1], q)
    return _photomod(p[:, 0], p[:, 1], q)


def _extras(model, b, f, r0=None):
    if model in ("ebner12", "hanzl17"):
        if b is None:
            raise InputError(f"{model} needs b, the spacing of the 3 × 3 grid of standard points (the image base)")
        b = _checks.number(b, "b", positive=True)
        if model == "hanzl17":
            if r0 is None:
                raise InputError("hanzl17 needs r0, the radius of zero radial distortion (0 allowed)")
            return (b, _checks.number(r0, "r0", positive=True, allow_zero=True)), None
        return b, None
    if model in ("brown", "brown18"):
        if f is None:
            raise InputError(f"{model} needs f, the principal distance (terms scaled by x/f, y/f)")
        return None, _checks.number(f, "f", positive=True)
    return None, None


def ap_corrections(model, xy, params, *, b=None, f=None, r0=None) -> np.ndarray:
    """σx, σy of any AP model at the given coordinates — the one entry point for self-calibration.

    Parameters
    ----------
    model : {"ebner12", "brown", "photomod", "hanzl17", "brown18", "murai"}
        (2), (3), (4) or Hanzl's models.
    xy : (n, 2) array
        Image coordinates (see the model's function for their origin).
    params : sequence or mapping
        The parameters (:func:`parameter_names`).
    b : float, optional
        Grid spacing, required by ``"ebner12"``.
    f : float, optional
        Principal distance, required by ``"brown"`` and ``"brown18"`` (Hanzl's c).
    r0 : float, optional
        Radius of zero radial distortion, required by ``"hanzl17"`` (≥ 0).

    Returns
    -------
    (n, 2) ndarray
        σx, σy.

    Raises
    ------
    InputError
        Unknown model, bad coordinates or parameters, a missing b or f.

    References
    ----------
    Sementsov (2019), eqs. (2)–(4), lines 472–500.

    Examples
    --------
    >>> ap_corrections("ebner12", [[1.0, 1.0]], {"c2": 1.0}, b=1.0)
    array([[1., 1.]])
    """
    model = _model(model)
    p = _xy(xy)
    q = _params(model, params)
    b, f = _extras(model, b, f, r0)
    return _evaluate(model, p, q, b, f)


def ap_basis(model, xy, *, b=None, f=None, r0=None) -> np.ndarray:
    """∂(σx, σy)/∂parameters: the columns of the AP part of the design matrix.

    Each model is linear in its parameters, so column j is σ evaluated with parameter j = 1 and the
    others 0 (exact, no finite differences).

    Parameters
    ----------
    model : {"ebner12", "brown", "photomod", "hanzl17", "brown18", "murai"}
        (2), (3), (4) or Hanzl's models.
    xy : (n, 2) array
        Image coordinates.
    b, f, r0 : float, optional
        As for :func:`ap_corrections`.

    Returns
    -------
    (n, 2, p) ndarray
        ``[i, 0, j]`` = ∂σxᵢ/∂parameter j, ``[i, 1, j]`` = ∂σyᵢ/∂parameter j.

    Raises
    ------
    InputError
        Unknown model, bad coordinates, a missing b or f.

    References
    ----------
    Sementsov (2019), eqs. (2)–(4); Chibunichev (2022), §3.6 (self-calibration).

    Examples
    --------
    >>> ap_basis("photomod", [[1.0, 2.0]])[0, :, 5:] + 0.0
    array([[ 0.,  0., -1., -2.],
           [-1., -2.,  0.,  0.]])
    """
    model = _model(model)
    p = _xy(xy)
    b, f = _extras(model, b, f, r0)
    eye = np.eye(len(_NAMES[model]))
    return np.stack([_evaluate(model, p, e, b, f) for e in eye], axis=-1)


def apply_ap(model, xy, params, *, b=None, f=None, r0=None) -> np.ndarray:
    """xy + σ(xy): the coordinates with the AP corrections added at the coordinates themselves.

    Under the correction reading (measured coordinates reduced to the principal point, as in
    (1.2.3)) this is the undistortion measured → ideal.

    Parameters
    ----------
    model : {"ebner12", "brown", "photomod", "hanzl17", "brown18", "murai"}
        (2), (3), (4) or Hanzl's models.
    xy : (n, 2) array
        Image coordinates.
    params : sequence or mapping
        The parameters.
    b, f, r0 : float, optional
        As for :func:`ap_corrections`.

    Returns
    -------
    (n, 2) ndarray

    Raises
    ------
    InputError
        As :func:`ap_corrections`.

    References
    ----------
    Sementsov (2019), eqs. (2)–(4); Chibunichev (2022), eq. (1.2.3).

    Examples
    --------
    >>> apply_ap("photomod", [[1000.0, 0.0]], {"k1": -1e-8})
    array([[1010.,    0.]])
    """
    p = _xy(xy)
    return p + ap_corrections(model, p, params, b=b, f=f, r0=r0)


def invert_ap(model, xy, params, *, b=None, f=None, r0=None, tol: float = 1e-10, max_iter: int = 100) -> np.ndarray:
    """Solve u + σ(u) = xy for u by the fixed-point iteration u ← xy − σ(u) (the inverse of :func:`apply_ap`).

    Under the correction reading this gives the measured (distorted) point of an ideal one; under
    the distortion reading it is the undistortion. The iteration converges where σ changes more
    slowly than the coordinates (‖∂σ/∂u‖ < 1), true for every realistic lens.

    Parameters
    ----------
    model : {"ebner12", "brown", "photomod", "hanzl17", "brown18", "murai"}
        (2), (3), (4) or Hanzl's models.
    xy : (n, 2) array
        The coordinates to invert.
    params : sequence or mapping
        The parameters.
    b, f, r0 : float, optional
        As for :func:`ap_corrections`.
    tol : float
        Stop when the largest change is below tol·max(1, max|xy|).
    max_iter : int
        Iterations allowed, ≥ 1.

    Returns
    -------
    (n, 2) ndarray
        u; ``apply_ap(model, u, params)`` gives ``xy``.

    Raises
    ------
    InputError
        As :func:`ap_corrections`; tol not positive, max_iter < 1.
    ConvergenceError
        The iteration did not settle in ``max_iter`` steps or diverged (its ``history`` holds the
        largest change of each step).

    References
    ----------
    Sementsov (2019), eqs. (2)–(4); Chibunichev (2022), eqs. (1.2.2)–(1.2.3).

    Examples
    --------
    >>> u = invert_ap("photomod", [[1010.0, 0.0]], {"k1": -1e-8})
    >>> bool(np.allclose(apply_ap("photomod", u, {"k1": -1e-8}), [[1010.0, 0.0]], atol=1e-8))
    True
    """
    model = _model(model)
    v = _xy(xy)
    q = _params(model, params)
    b, f = _extras(model, b, f, r0)
    tol = _checks.number(tol, "tol", positive=True)
    max_iter = _checks.integer(max_iter, "max_iter", 1)
    scale = max(1.0, float(np.max(np.abs(v))) if v.size else 1.0)
    u = v.copy()
    history = []
    for _ in range(max_iter):
        with np.errstate(over="ignore", invalid="ignore"):
            new = v - _evaluate(model, u, q, b, f)
        step = float(np.max(np.abs(new - u))) if v.size else 0.0
        history.append(step)
        if not np.isfinite(step):
            raise ConvergenceError(f"inverting the {model} corrections diverged after {len(history)} step(s): the "
                                   "corrections grow faster than the coordinates (|∂σ/∂u| ≥ 1); are the "
                                   "parameters in the units of the coordinates?", history)
        u = new
        if step <= tol * scale:
            return u
    raise ConvergenceError(f"inverting the {model} corrections did not converge in {max_iter} iterations (last "
                           f"change {history[-1]:.3g}, tolerance {tol * scale:.3g}); the corrections change nearly "
                           "as fast as the coordinates (|∂σ/∂u| close to or above 1)", history)
