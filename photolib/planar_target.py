"""Calibrating a non-metric camera on a planar target: the theory of A.V. Sementsov's thesis —
appendix to Chapter 11 (§11.3, camera calibration; ``chapters/appendix_sementsov.ipynb``).

Source: A.V. Sementsov, «Усовершенствование методики калибровки неметрических цифровых съемочных
камер с использованием дополнительных геометрических условий», PhD thesis, SGUGiT, Novosibirsk
2019 (seed ``004_ae61db45a4af28ce.txt``; equation numbers are the thesis's, line numbers the seed's).

* The α–ω–κ direction cosines: the thesis never prints its matrix, but (8) (lines 593–595) fixes
  a₁ = cos α, a₃ = −sin α, c₁ = sin α, c₃ = cos α for ω = κ = 0, which is the α–ω–χ matrix
  A = R_Y(α)·R_X(ω)·R_Z(κ) of the GNSS-centres appendix: :func:`photolib.gnss_centres.rotation_aok`
  (used here, not redefined). A maps image axes to object axes.
* (6) collinearity (lines 577–579): :func:`project`.
* (12)–(16) the transformed bundle of a tilted image of a plane (lines 669–701): :func:`transformed_bundle`.
* (18) the locus of the projection centres, **corrected** (lines 730–756; the printed centre has the
  wrong sign, the slip starts at line 738): :func:`centre_locus`.
* The three calibration methodologies (lines 771–820): :func:`condition_residual`, :func:`condition_roots`.
* (22) GSD and the permissible tripod offsets (22)–(24), Table 4 (lines 1117–1153):
  :func:`gsd`, :func:`permissible_offsets`.
* §3.4 star field (lines 1268–1295): :func:`max_star_exposure`, :func:`star_unit_vector`,
  :func:`angular_pixel_size`.
* (5) the bundle comparison of §2.1 (lines 520–545), with the best rotation of one bundle onto the
  other (Wahba's problem, solved by :func:`photolib.projective.nearest_rotation`):
  :func:`image_rays`, :func:`compare_bundles`.

Units: the thesis works in pixels for f, x₀, y₀ and in metres for the object; every function here
only needs f, x₀, y₀ and image coordinates in one unit and the object in another. Angles in radians.
The distortion models of §2.1 are in :mod:`photolib.additional_parameters`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from . import _checks
from .camera import as_points
from .errors import DegenerateGeometryError, InputError, PointBehindCameraError
from .mockup import project_points
from .projective import nearest_rotation
from .rotation import _numbers

__all__ = ["RHO_ARCSEC", "SIDEREAL_RATE_PRINTED", "METHODS", "TransformedBundle", "CentreLocus",
           "ConditionRoots", "PermissibleOffsets", "BundleComparison", "project", "transformed_bundle",
           "centre_locus", "condition_residual", "condition_roots", "gsd", "permissible_offsets",
           "max_star_exposure", "star_unit_vector", "angular_pixel_size", "image_rays", "compare_bundles"]

RHO_ARCSEC = 180.0 * 3600.0 / np.pi
"""ρ″ of (5): arcseconds per radian (206 264.806…)."""

SIDEREAL_RATE_PRINTED = 15.0
"""The apparent rotation rate of the sky used at line 1268, 15″/s (360° in 24 h; the sidereal day
gives 15.041″/s)."""

METHODS = ("1-f", "1-Z_S", "1-x0", "1-X_S", "1-alpha", "2.1", "2.2", "3")
"""The calibration methodologies of lines 771–820: 1-… one tilted image and one independently known
quantity (f, Z_S, x₀, X_S or α); 2.1 two images tilted in one plane with equal X_S; 2.2 the same with
one camera (equal principal point); 3 two images tilted in perpendicular planes, one camera."""


def _positive(value, name):
    return _checks.number(value, name, positive=True)


def _tilt(alpha, name="alpha"):
    a = _checks.number(alpha, name)
    if not abs(a) < np.pi / 2:
        raise InputError(f"{name} = {a!r} rad: the tilt must lie within (−π/2, π/2) radians "
                         "(were degrees passed?)")
    if a == 0.0:
        raise DegenerateGeometryError(f"{name} = 0: a horizontal image of a plane leaves f, Z_S and the principal "
                                      "point ambiguous in three dimensions ((13), lines 683–687); the "
                                      "one-parameter family of (12)–(16) needs a tilted image")
    return a


# --- (6) collinearity ---------------------------------------------------------------------------------
def project(points, centre, alpha, omega, kappa, f, x0=0.0, y0=0.0) -> np.ndarray:
    """Image coordinates of object points by the collinearity equations (6).

    x − x₀ = −f·((X−X_S)a₁ + (Y−Y_S)b₁ + (Z−Z_S)c₁)/((X−X_S)a₃ + (Y−Y_S)b₃ + (Z−Z_S)c₃), y likewise
    with a₂, b₂, c₂; the direction cosines are those of A = R_Y(α)·R_X(ω)·R_Z(κ)
    (:func:`photolib.gnss_centres.rotation_aok`), i.e. the image vector (x − x₀, y − y₀, −f) is
    parallel to Aᵀ(P − S).

    Parameters
    ----------
    points : (n, 3) array
        Object points X, Y, Z.
    centre : (3,) array
        Projection centre X_S, Y_S, Z_S.
    alpha, omega, kappa : float
        The angles of the α–ω–κ system (rad).
    f : float
        Principal distance (in the unit of the image coordinates, e.g. pixels), > 0.
    x0, y0 : float
        Principal point.

    Returns
    -------
    (n, 2) ndarray
        x, y.

    Raises
    ------
    InputError
        Bad shapes, NaN/inf, f ≤ 0.
    PointBehindCameraError
        A point lies behind the camera or in the plane through S parallel to the image
        (``points`` of the error lists their indices).

    References
    ----------
    Sementsov (2019), eq. (6), lines 577–587; eq. (8) for α ≠ 0, ω = κ = 0 (lines 589–595).

    Examples
    --------
    >>> project([[0.0, 0.0, 0.0]], [0.0, 0.0, 300.0], 0.0, 0.0, 0.0, 3100.0, 10.0, 10.0)
    array([[10., 10.]])
    """
    P = as_points(points, 3, "object points")
    S = as_points(centre, 3, "projection centre")
    if len(S) != 1:
        raise InputError(f"one projection centre expected, got {len(S)}")
    a, w, k = (_checks.number(v, n) for v, n in ((alpha, "alpha"), (omega, "omega"), (kappa, "kappa")))
    f = _positive(f, "f")
    x0, y0 = _checks.number(x0, "x0"), _checks.number(y0, "y0")
    xy, depth = project_points(P, S[0], (a, w, k), (f, x0, y0))     # the one (6) of the library
    behind = np.flatnonzero(depth >= 0)
    if behind.size:
        raise PointBehindCameraError(f"{behind.size} point(s) lie behind the camera or in the plane of its centre "
                                     f"(first indices {behind[:5].tolist()})", points=behind)
    return xy


# --- (12)–(16) the transformed bundle -----------------------------------------------------------------
@dataclass(frozen=True)
class TransformedBundle:
    """One member (or a family, for an array of k) of the transformed bundle (12)–(16).

    With f′ = k·f the collinearity equations (8) of a plane Z = 0 imaged from (0, 0, Z_S) at tilt α
    are satisfied identically in X, Y by the tilt α′, the principal point x₀ + δx₀, y₀ + δy₀ and the
    centre (δX_S, δY_S, Z′_S) below.

    Attributes
    ----------
    k : float or ndarray
        The coefficient of the transformation (f′ = k f).
    alpha : float
        The true tilt α (rad).
    alpha_prime : float or ndarray
        α′ with sin α′ = k sin α (12), |α′| ≤ π/2.
    f_prime : float or ndarray
        k·f.
    dx0, dy0 : float or ndarray
        δx₀ = f(cos α − cos α′)/sin α (14) and δy₀ = 0 (13), in the unit of f.
    dX_S, dY_S : float or ndarray
        δX_S = −δx₀·Z_S/f (16) and δY_S = 0 (17), in the unit of Z_S.
    Z_S_prime : float or ndarray
        Z′_S = k·Z_S (15).

    References
    ----------
    Sementsov (2019), eqs. (9), (12)–(17), lines 597–721; eq. (19), lines 767–769.

    Examples
    --------
    >>> b = transformed_bundle(np.radians(30.0), 1.0, 3100.0, 300.0)
    >>> float(b.dx0), float(b.Z_S_prime)
    (0.0, 300.0)
    """

    k: object
    alpha: float
    alpha_prime: object
    f_prime: object
    dx0: object
    dy0: object
    dX_S: object
    dY_S: object
    Z_S_prime: object


def transformed_bundle(alpha, k, f, Z_S) -> TransformedBundle:
    """The transformed bundle (12)–(16) of a tilted image of a plane, for one k or an array of k.

    sin α′ = k sin α (12), δy₀ = 0 (13), δx₀/f = (cos α − cos α′)/sin α (14), Z′_S = k Z_S (15),
    δX_S = −δx₀ Z_S/f (16), δY_S = 0 (17); cos α′ = √(1 − k² sin² α) (line 734). The configuration
    is that of (7): X_S = Y_S = 0, plane Z = 0, ω = κ = 0.

    Parameters
    ----------
    alpha : float
        Tilt α (rad), 0 < |α| < π/2.
    k : float or array
        Coefficient(s) of the transformation, 0 < k ≤ 1/|sin α| (beyond it α′ has no real value).
    f : float
        Principal distance, > 0 (δx₀ comes out in its unit).
    Z_S : float
        Height of the centre above the plane, > 0 (δX_S, Z′_S come out in its unit).

    Returns
    -------
    TransformedBundle

    Raises
    ------
    InputError
        NaN/inf, |α| ≥ π/2, k ≤ 0 or k > 1/|sin α|, f or Z_S not positive.
    DegenerateGeometryError
        α = 0: a horizontal image has the three-dimensional ambiguity of (13)/(17), not this family.

    References
    ----------
    Sementsov (2019), eqs. (7)–(17), lines 589–721; line 734.

    Examples
    --------
    >>> b = transformed_bundle(np.radians(30.0), 0.5, 3100.0, 300.0)
    >>> round(float(np.degrees(b.alpha_prime)), 2), round(float(b.dx0), 1), round(float(b.dX_S), 2)
    (14.48, -633.8, 61.33)
    """
    a = _tilt(alpha)
    kk = _numbers(k, "k")
    f = _positive(f, "f")
    Z_S = _positive(Z_S, "Z_S")
    s, c = np.sin(a), np.cos(a)
    if np.any(kk <= 0):
        raise InputError("k must be positive (k ≤ 0 puts the transformed centre on or below the plane, (15))")
    ks = kk * abs(s)
    if np.any(ks > 1.0 + 1e-12):
        raise InputError(f"k must not exceed 1/|sin α| = {1 / abs(s):.6g}: sin α′ = k sin α (12) has no real α′ "
                         f"(largest k given: {float(np.max(kk)):.6g})")
    sp_ = np.clip(kk * s, -1.0, 1.0)
    cp = np.sqrt(np.clip(1.0 - sp_ * sp_, 0.0, None))
    dx0 = f * (c - cp) / s                                            # (14)
    scalar = np.ndim(kk) == 0

    def out(v):
        return float(v) if scalar else v

    return TransformedBundle(k=out(kk), alpha=a, alpha_prime=out(np.arcsin(sp_)), f_prime=out(kk * f),
                             dx0=out(dx0), dy0=out(0.0 * kk), dX_S=out(-dx0 * Z_S / f), dY_S=out(0.0 * kk),
                             Z_S_prime=out(kk * Z_S))


# --- (18) the locus of the centres, corrected ---------------------------------------------------------------
@dataclass(frozen=True)
class CentreLocus:
    """The circle (18), corrected, on which the transformed centres (δX_S, Z′_S) lie.

    (δX_S + Z_S cot α)² + Z′_S² = (Z_S/sin α)²: centre (−Z_S cot α, 0), radius Z_S/|sin α|. The
    family of :func:`transformed_bundle` covers the quarter from k → 0 (α′ = 0, the point
    (Z_S tan(α/2), 0)) to k = 1/|sin α| (α′ = ±90°, the top of the circle); k = 1 is the true centre
    (0, Z_S).

    Attributes
    ----------
    alpha : float
        Tilt (rad).
    Z_S : float
        True height of the centre.
    centre : tuple of float
        (δX_S, Z′_S) of the circle's centre, (−Z_S cot α, 0).
    radius : float
        Z_S/|sin α|.
    k_max : float
        1/|sin α|, the largest k.

    References
    ----------
    Sementsov (2019), eq. (18) and the text after it, lines 730–763 (printed with +Z_S cot α; see
    :func:`photolib.derivations.planar_target.printed_centre_locus`).

    Examples
    --------
    >>> c = centre_locus(np.radians(30.0), 300.0)
    >>> [round(v, 2) for v in c.centre], round(c.radius, 6)
    ([-519.62, 0.0], 600.0)
    """

    alpha: float
    Z_S: float
    centre: tuple
    radius: float
    k_max: float


def centre_locus(alpha, Z_S) -> CentreLocus:
    """The corrected circle (18) of the transformed centres of a tilted image of a plane.

    Parameters
    ----------
    alpha : float
        Tilt α (rad), 0 < |α| < π/2.
    Z_S : float
        Height of the true centre above the plane, > 0.

    Returns
    -------
    CentreLocus

    Raises
    ------
    InputError
        NaN/inf, |α| ≥ π/2, Z_S not positive.
    DegenerateGeometryError
        α = 0 (no circle: the horizontal case is ambiguous in three dimensions).

    References
    ----------
    Sementsov (2019), eq. (18), lines 730–763; corrected: the printed centre +Z_S cot α follows from the
    sign slip of line 738.

    Examples
    --------
    >>> c = centre_locus(np.radians(-30.0), 300.0)
    >>> round(c.centre[0], 2), round(c.k_max, 6)
    (519.62, 2.0)
    """
    a = _tilt(alpha)
    Z_S = _positive(Z_S, "Z_S")
    s, c = np.sin(a), np.cos(a)
    return CentreLocus(alpha=a, Z_S=Z_S, centre=(float(-Z_S * c / s), 0.0), radius=float(Z_S / abs(s)),
                       k_max=float(1.0 / abs(s)))


# --- the methodologies -------------------------------------------------------------------------------------
def _method(method):
    if not isinstance(method, str) or method not in METHODS:
        raise InputError(f"unknown methodology {method!r}; use one of {', '.join(METHODS)}")
    return method


def _k_max(method, a1, a2):
    if method.startswith("1-"):
        return 1.0 / abs(np.sin(a1))
    return min(1.0 / abs(np.sin(a1)), 1.0 / abs(np.sin(a2)))


def condition_residual(method, k, alpha1, alpha2=None) -> np.ndarray:
    """The condition equations of a calibration methodology as functions of k (zero where satisfied).

    With φ_δx₀(k, α)/f = (cos α − √(1 − k² sin² α))/sin α and φ_δX_S(k, α)/Z_S = −φ_δx₀/f:

    * ``"1-f"``: k − 1 (f′ = k f known), ``"1-Z_S"``: k − 1, ``"1-x0"``: φ_δx₀(k, α₁)/f,
      ``"1-X_S"``: φ_δX_S(k, α₁)/Z_S, ``"1-alpha"``: α′ − α₁ (one tilted image, one known quantity);
    * ``"2.1"``: φ_δX_S(k, α₁) − φ_δX_S(k, α₂) (equal X_S of two images tilted in one plane), in units of Z_S;
    * ``"2.2"``: φ_δx₀(k, α₁) − φ_δx₀(k, α₂) (one camera: equal principal point), in units of f;
    * ``"3"``: two rows, φ_δx₀(k, α₁) and φ_δx₀(k, α₂) — image 1 tilted by α₁ about y shifts only x₀,
      image 2 tilted by α₂ (its ω) about x shifts only y₀ (13), and one camera has one principal point,
      so both shifts must vanish.

    Parameters
    ----------
    method : str
        One of :data:`METHODS`.
    k : float or array
        Coefficient(s) of the transformation, 0 < k ≤ the smaller 1/|sin α|.
    alpha1 : float
        Tilt of image 1 (rad), 0 < |α₁| < π/2.
    alpha2 : float, optional
        Tilt of image 2 (rad) for the two-image methodologies.

    Returns
    -------
    (m, len(k)) ndarray
        m = 2 for ``"3"``, else 1.

    Raises
    ------
    InputError
        Unknown method, a missing or extra α₂, bad angles or k.
    DegenerateGeometryError
        A horizontal image (α = 0); α₁ = α₂ for 2.1/2.2 (the condition holds for every k).

    References
    ----------
    Sementsov (2019), §2.2, lines 771–820 and Figs. 27–29; eqs. (12)–(16).

    Examples
    --------
    >>> r = condition_residual("2.1", [0.5, 1.0, 1.5], np.radians(30.0), np.radians(-30.0))
    >>> np.abs(r).round(4)
    array([[0.4089, 0.    , 0.8183]])
    """
    method = _method(method)
    a1 = _tilt(alpha1, "alpha1")
    if method.startswith("1-"):
        if alpha2 is not None:
            raise InputError(f"methodology {method} uses one image: alpha2 must be None")
        a2 = None
    else:
        if alpha2 is None:
            raise InputError(f"methodology {method} needs the tilt alpha2 of the second image")
        a2 = _tilt(alpha2, "alpha2")
        if method in ("2.1", "2.2") and a1 == a2:
            raise DegenerateGeometryError(f"methodology {method}: α₁ = α₂ makes the condition hold for every k — "
                                          "the two images must have different tilts (α₁ ≠ α₂, line 777)")
    kk = np.atleast_1d(_numbers(k, "k")).astype(float)
    if kk.ndim != 1:
        raise InputError(f"k must be a number or a 1-D array, got shape {np.shape(k)}")
    kmax = _k_max(method, a1, a2 if a2 is not None else a1)
    if np.any(kk <= 0) or np.any(kk > kmax * (1 + 1e-12)):
        raise InputError(f"k must lie in (0, {kmax:.6g}] (1/|sin α| of the steeper image)")
    b1 = transformed_bundle(a1, kk, 1.0, 1.0)
    if method in ("1-f", "1-Z_S"):
        rows = [kk - 1.0]
    elif method == "1-x0":
        rows = [b1.dx0]
    elif method == "1-X_S":
        rows = [b1.dX_S]
    elif method == "1-alpha":
        rows = [b1.alpha_prime - a1]
    else:
        b2 = transformed_bundle(a2, kk, 1.0, 1.0)
        if method == "2.1":
            rows = [b1.dX_S - b2.dX_S]
        elif method == "2.2":
            rows = [b1.dx0 - b2.dx0]
        else:
            rows = [b1.dx0, b2.dx0]
    return np.vstack(rows)


@dataclass(frozen=True)
class ConditionRoots:
    """The values of k that satisfy a methodology's conditions (see :func:`condition_roots`).

    Attributes
    ----------
    method : str
        The methodology.
    alpha1, alpha2 : float or None
        The tilts (rad).
    k_max : float
        The end of the searched interval (0, k_max].
    roots : tuple of float
        The roots found, ascending.

    References
    ----------
    Sementsov (2019), §2.2, lines 771–820.

    Examples
    --------
    >>> condition_roots("2.2", np.radians(30.0), np.radians(-30.0)).roots
    (1.0,)
    """

    method: str
    alpha1: float
    alpha2: object
    k_max: float
    roots: tuple


def _bisect(fn, lo, hi, flo, iterations=200):
    for _ in range(iterations):
        mid = 0.5 * (lo + hi)
        if mid in (lo, hi):
            break
        fm = fn(mid)
        if fm == 0.0:
            return mid
        if (fm < 0) == (flo < 0):
            lo, flo = mid, fm
        else:
            hi = mid
    return 0.5 * (lo + hi)


def condition_roots(method, alpha1, alpha2=None, samples: int = 4000) -> ConditionRoots:
    """Every k in (0, k_max] at which a methodology's conditions hold: the thesis's k = 1 is the only one.

    Each condition row of :func:`condition_residual` is sampled at ``samples`` points of
    (0, k_max]; each sign change (or exact zero) is refined by bisection to machine precision. For
    methodology 3 the roots common to both rows (within 1e-9) are returned. Roots where a row
    touches zero without changing sign would be missed; none of the conditions here has one
    (each row is strictly monotonic or changes sign at k = 1, see the tests).

    Parameters
    ----------
    method : str
        One of :data:`METHODS`.
    alpha1 : float
        Tilt of image 1 (rad).
    alpha2 : float, optional
        Tilt of image 2 (rad), for 2.1, 2.2 and 3.
    samples : int
        Number of sample points, ≥ 10.

    Returns
    -------
    ConditionRoots

    Raises
    ------
    InputError
        As :func:`condition_residual`; ``samples`` < 10.
    DegenerateGeometryError
        As :func:`condition_residual`.

    References
    ----------
    Sementsov (2019), §2.2, lines 771–820 (Figs. 27–29: "the solution exists only for k = 1").

    Examples
    --------
    >>> r = condition_roots("2.1", np.radians(30.0), np.radians(60.0))
    >>> [round(v, 12) for v in r.roots]
    [1.0]
    """
    method = _method(method)
    samples = _checks.integer(samples, "samples", 10)
    a1 = _tilt(alpha1, "alpha1")
    a2 = None if alpha2 is None else _tilt(alpha2, "alpha2")
    condition_residual(method, 1.0, a1, a2)                         # validates the combination
    kmax = _k_max(method, a1, a2 if a2 is not None else a1)
    grid = kmax * np.arange(1, samples + 1) / samples
    values = condition_residual(method, grid, a1, a2)
    per_row = []
    for r, g in enumerate(values):
        def fn(kv, r=r):
            return float(condition_residual(method, kv, a1, a2)[r, 0])
        found = [float(grid[i]) for i in np.flatnonzero(g == 0.0)]
        for i in np.flatnonzero(g[:-1] * g[1:] < 0):
            found.append(_bisect(fn, float(grid[i]), float(grid[i + 1]), float(g[i])))
        per_row.append(sorted(found))
    roots = []
    for k_ in per_row[0]:
        if all(any(abs(k_ - other) <= 1e-9 for other in row) for row in per_row[1:]):
            if not roots or abs(k_ - roots[-1]) > 1e-9:
                roots.append(k_)
    return ConditionRoots(method=method, alpha1=a1, alpha2=a2, k_max=float(kmax), roots=tuple(roots))


# --- (22)–(24) GSD and the permissible offsets of the projection centre ------------------------------------
def gsd(H, f_px):
    """Ground sample distance (22): GSD = H / f_pix, the object size of one pixel at distance H.

    Parameters
    ----------
    H : float or array
        Distance to the object (height), > 0, in metres (or any length unit).
    f_px : float
        Principal distance in pixels, > 0.

    Returns
    -------
    float or ndarray
        GSD in the unit of H per pixel.

    Raises
    ------
    InputError
        NaN/inf, non-positive H or f.

    References
    ----------
    Sementsov (2019), eq. (22), lines 1125–1127.

    Examples
    --------
    >>> round(gsd(300.0, 3100.0), 6)
    0.096774
    """
    h = _numbers(H, "H")
    if np.any(h <= 0):
        raise InputError("H (the distance to the object) must be positive")
    f = _positive(f_px, "f_px")
    out = h / f
    return float(out) if np.ndim(out) == 0 else out


@dataclass(frozen=True)
class PermissibleOffsets:
    """Permissible offsets of the projection centre from the tripod's rotation centre, (22)–(24).

    Attributes
    ----------
    l_xy_px, l_z_px : float
        In pixels: l_XY = (m_ξx₀/|Δx₀ slope|)·m = (0.4/0.6)·m, l_Z = (m_ξf/|Δf slope|)·m = (1.7/0.4)·m.
    l_xy, l_z : float
        The same in the unit of H (multiplied by GSD = H/f).
    gsd : float
        H/f_px (22).

    References
    ----------
    Sementsov (2019), eqs. (22)–(24) and Table 4, lines 1105–1153.

    Examples
    --------
    >>> o = permissible_offsets(0.5, 2.0, 3100.0)
    >>> round(o.l_xy * 1000, 2), round(o.l_z * 1000, 2)
    (0.22, 1.37)
    """

    l_xy_px: float
    l_z_px: float
    l_xy: float
    l_z: float
    gsd: float


def permissible_offsets(m_px, H, f_px, *, slope_xy=0.6, xi_xy=0.4, slope_z=0.4, xi_z=1.7) -> PermissibleOffsets:
    """Permissible offsets l_XY, l_Z of the projection centre (22)–(24): bias no larger than the random error.

    The §3.2 simulations gave, in pixels, Δx₀ ≈ −0.6 l_X, Δf ≈ −0.4 l_Z (systematic) and m_ξx₀ ≈ 0.4 m,
    m_ξf ≈ 1.7 m (random, m the image-coordinate precision). Setting |slope·l| = ξ·m gives
    l_Z = (1.7/0.4) m = 4.25 m and l_XY = (0.4/0.6) m = (2/3) m pixels (the thesis prints the second
    coefficient rounded, 0.67; Table 4 was computed with 2/3), then × GSD = H/f for metres (23)/(24).
    The coefficients are specific to the simulated set-up (NEX-5, f = 3100 px, 2 m, ±30° tilts).

    Parameters
    ----------
    m_px : float
        Precision of the image coordinates (pixels), > 0.
    H : float
        Distance from the camera to the target, > 0.
    f_px : float
        Principal distance (pixels), > 0.
    slope_xy, xi_xy, slope_z, xi_z : float
        The empirical coefficients (defaults as printed at lines 1107–1115), > 0.

    Returns
    -------
    PermissibleOffsets

    Raises
    ------
    InputError
        NaN/inf or non-positive values.

    References
    ----------
    Sementsov (2019), eqs. (22)–(24), lines 1105–1143; Table 4, lines 1145–1153.

    Examples
    --------
    >>> o = permissible_offsets(0.5, 20.0, 3100.0)
    >>> round(o.l_xy * 1000, 2), round(o.l_z * 1000, 2)
    (2.15, 13.71)
    """
    m = _positive(m_px, "m_px")
    g = gsd(_positive(H, "H"), f_px)
    coefficients = [_positive(v, n) for v, n in ((slope_xy, "slope_xy"), (xi_xy, "xi_xy"),
                                                 (slope_z, "slope_z"), (xi_z, "xi_z"))]
    sxy, xxy, sz, xz = coefficients
    l_xy_px, l_z_px = xxy / sxy * m, xz / sz * m
    return PermissibleOffsets(l_xy_px=l_xy_px, l_z_px=l_z_px, l_xy=l_xy_px * g, l_z=l_z_px * g, gsd=g)


# --- §3.4 the star field -------------------------------------------------------------------------------------
def max_star_exposure(pixel_arcsec, declination, rate=SIDEREAL_RATE_PRINTED):
    """Longest exposure τ = α″_p / (ω″ cos δ) at which a star moves by less than one pixel.

    Parameters
    ----------
    pixel_arcsec : float
        Angular size of a pixel α″_p (arcsec), > 0.
    declination : float or array
        Declination δ of the star (rad), |δ| ≤ π/2; at the pole (|δ| = π/2) the star does not move and
        τ is infinite.
    rate : float
        Apparent rotation rate ω″ of the sky (arcsec/s), > 0; the thesis uses 15″/s.

    Returns
    -------
    float or ndarray
        τ in seconds.

    Raises
    ------
    InputError
        NaN/inf, non-positive pixel size or rate, |δ| > π/2.

    References
    ----------
    Sementsov (2019), §3.4, lines 1268–1280.

    Examples
    --------
    >>> max_star_exposure(60.0, 0.0)
    4.0
    """
    p = _positive(pixel_arcsec, "pixel_arcsec")
    w = _positive(rate, "rate")
    d = _numbers(declination, "declination")
    if np.any(np.abs(d) > np.pi / 2 + 1e-12):
        raise InputError("declination must lie within [−π/2, π/2] radians (were degrees passed?)")
    c = np.cos(d)
    with np.errstate(divide="ignore"):
        tau = np.where(np.abs(d) >= np.pi / 2 - 1e-15, np.inf, p / (w * np.abs(c)))
    return float(tau) if np.ndim(tau) == 0 else tau


def star_unit_vector(right_ascension, declination) -> np.ndarray:
    """Unit vector to a star in the inertial geocentric frame: e = (cos δ cos α, cos δ sin α, sin δ).

    Parameters
    ----------
    right_ascension : float or array
        α, the right ascension (rad) — not the tilt α of §2.2.
    declination : float or array
        δ (rad), |δ| ≤ π/2.

    Returns
    -------
    (..., 3) ndarray
        e_x, e_y, e_z.

    Raises
    ------
    InputError
        NaN/inf, shapes that do not broadcast, |δ| > π/2.

    References
    ----------
    Sementsov (2019), §3.4, lines 1287–1295.

    Examples
    --------
    >>> star_unit_vector(0.0, np.pi / 2).round(12) + 0.0
    array([0., 0., 1.])
    """
    a = _numbers(right_ascension, "right_ascension")
    d = _numbers(declination, "declination")
    if np.any(np.abs(d) > np.pi / 2 + 1e-12):
        raise InputError("declination must lie within [−π/2, π/2] radians (were degrees passed?)")
    try:
        a, d = np.broadcast_arrays(a, d)
    except ValueError:
        raise InputError(f"right_ascension and declination have shapes {np.shape(a)}, {np.shape(d)} "
                         "that do not broadcast") from None
    return np.stack([np.cos(d) * np.cos(a), np.cos(d) * np.sin(a), np.sin(d)], axis=-1)


def angular_pixel_size(f, pixel=1.0) -> float:
    """Angular size of the central pixel, ρ″·pixel/f (arcsec).

    Parameters
    ----------
    f : float
        Principal distance, > 0 (in pixels with the default ``pixel``, or in mm with ``pixel`` in mm).
    pixel : float
        Pixel size in the unit of f, > 0.

    Returns
    -------
    float
        Arcseconds.

    Raises
    ------
    InputError
        NaN/inf or non-positive values.

    References
    ----------
    Sementsov (2019), §3.4, line 1280 ("≈ 60″") and the note to Table 7, line 1330 ("≈ 62″").

    Examples
    --------
    >>> round(angular_pixel_size(3324.848), 2)
    62.04
    """
    return RHO_ARCSEC * _positive(pixel, "pixel") / _positive(f, "f")


# --- (5) comparing two bundles of rays ------------------------------------------------------------------------
def image_rays(xy, f, x0=0.0, y0=0.0) -> np.ndarray:
    """Unit ray vectors (x − x₀, y − y₀, −f)/‖·‖ of image points (steps (б)–(в) of Fig. 21).

    Apply the distortion corrections first (:mod:`photolib.additional_parameters`); the rays are in
    the image-space frame.

    Parameters
    ----------
    xy : (n, 2) array
        Image coordinates (corrected), in the unit of f.
    f : float
        Principal distance, > 0.
    x0, y0 : float
        Principal point.

    Returns
    -------
    (n, 3) ndarray
        Unit vectors.

    Raises
    ------
    InputError
        Bad shape, NaN/inf, f ≤ 0.

    References
    ----------
    Sementsov (2019), §2.1, lines 520–533 (Fig. 21) and eq. (5).

    Examples
    --------
    >>> image_rays([[0.0, 0.0]], 3100.0)
    array([[ 0.,  0., -1.]])
    """
    p = as_points(xy, 2, "image coordinates")
    f = _positive(f, "f")
    x0, y0 = _checks.number(x0, "x0"), _checks.number(y0, "y0")
    v = np.column_stack([p[:, 0] - x0, p[:, 1] - y0, np.full(len(p), -f)])
    return v / np.linalg.norm(v, axis=1, keepdims=True)


@dataclass(frozen=True)
class BundleComparison:
    """Result of (5): the RMS of the differences of corresponding unit rays after the best rotation.

    Attributes
    ----------
    rms_arcsec : float
        m″_Δα of (5): √(Σ‖X̄₂ᵢ/‖X̄₂ᵢ‖ − X̄₁ᵢ/‖X̄₁ᵢ‖‖²/n)·ρ″, bundle 2 rotated onto bundle 1.
    max_arcsec : float
        The largest single difference (the "maximum deviation" of Figs. C.1–C.3).
    rotation : (3, 3) ndarray
        R minimising Σ‖u₁ᵢ − R u₂ᵢ‖² (proper rotation).
    residuals_arcsec : (n, 3) ndarray
        ρ″·(u₁ᵢ − R u₂ᵢ), the difference vectors (for vector plots).
    n : int
        Number of rays.

    References
    ----------
    Sementsov (2019), eq. (5), lines 520–545; Table 7, lines 1323–1330; Appendix C, lines 2045–2064.

    Examples
    --------
    >>> u = image_rays([[0.0, 0.0], [100.0, 0.0], [0.0, 100.0]], 1000.0)
    >>> compare_bundles(u, u).rms_arcsec < 1e-9
    True
    """

    rms_arcsec: float
    max_arcsec: float
    rotation: np.ndarray
    residuals_arcsec: np.ndarray
    n: int


def _unit_rays(rays, what):
    R = as_points(rays, 3, what)
    norm = np.linalg.norm(R, axis=1)
    if np.any(norm == 0):
        raise InputError(f"{what}: {int(np.sum(norm == 0))} zero vector(s) have no direction")
    return R / norm[:, None]


def compare_bundles(rays1, rays2) -> BundleComparison:
    """Compare two bundles of rays by (5) after rotating bundle 2 onto bundle 1 (steps (г) of Fig. 21).

    Both bundles are normalised to unit vectors; the rotation R minimising Σ‖u₁ᵢ − R u₂ᵢ‖² (Wahba's
    problem; the thesis calls it «доворот» and does not say how it is found) is the rotation nearest
    to B = Σ u₁ᵢ u₂ᵢᵀ (SVD with the determinant guard,
    :func:`photolib.projective.nearest_rotation`). The chord ‖u₁ − R u₂‖ is the small-angle form of
    the angle between the rays (2 sin(θ/2)), as the thesis says (line 535).

    Parameters
    ----------
    rays1, rays2 : (n, 3) arrays
        Corresponding ray vectors (any non-zero length), n ≥ 2.

    Returns
    -------
    BundleComparison

    Raises
    ------
    InputError
        Bad shapes, NaN/inf, different counts, zero vectors.
    DegenerateGeometryError
        Fewer than 2 rays, or all rays parallel (the rotation about their direction is free).

    References
    ----------
    Sementsov (2019), eq. (5), lines 520–545; G. Wahba, SIAM Review 7 (1965) 409; W. Kabsch,
    Acta Cryst. A32 (1976) 922.

    Examples
    --------
    A bundle and the same bundle turned by any rotation agree after the best rotation:

    >>> from photolib.gnss_centres import rotation_aok
    >>> u = image_rays([[0.0, 0.0], [500.0, 0.0], [0.0, 500.0]], 3000.0)
    >>> c = compare_bundles(u, u @ rotation_aok(0.1, -0.2, 0.3).T)
    >>> c.rms_arcsec < 1e-6, bool(np.allclose(c.rotation, rotation_aok(0.1, -0.2, 0.3).T))
    (True, True)
    """
    U = _unit_rays(rays1, "rays1")
    V = _unit_rays(rays2, "rays2")
    if len(U) != len(V):
        raise InputError(f"rays1 has {len(U)} rays but rays2 has {len(V)}")
    if len(U) < 2:
        raise DegenerateGeometryError(f"{len(U)} ray(s): at least 2 non-parallel rays are needed to fix the rotation")
    B = U.T @ V
    s = np.linalg.svd(B, compute_uv=False)
    if s[1] <= 1e-12 * s[0]:
        raise DegenerateGeometryError("all rays are parallel: the rotation about their common direction is free")
    R = nearest_rotation(B)
    D = U - V @ R.T
    d = np.linalg.norm(D, axis=1)
    return BundleComparison(rms_arcsec=float(np.sqrt(np.mean(d * d)) * RHO_ARCSEC),
                            max_arcsec=float(d.max() * RHO_ARCSEC), rotation=R,
                            residuals_arcsec=D * RHO_ARCSEC, n=len(U))
