"""Terrestrial stereophotogrammetry — Chapter 11, §11.4–11.9.

* §11.4 the base coordinate system (:func:`base_system`): origin at S₁, Z up (the vertical of
  S₁), X along the horizontal projection of the base, Y completing a right-handed frame (toward
  the object for a left-to-right base). ω of a terrestrial image is ≈ 90°.
* §11.5 the standard cases (:func:`case_rotation`, :func:`case_orientations`): normal
  (ω = 90°, α = κ = 0), deviated (α ≠ 0), tilted (ω = 90° + tilt), convergent (α₁ = −γ/2,
  α₂ = +γ/2). They use A = A_ω A_α A_κ of (1.3.2) (order ``"wak"``): with ω = 90° the angle α
  turns the optical axis in the horizontal plane, which the κ–α–ω sequence would not do.
* §11.6 condition equations (11.6.1)–(11.6.5) and the corrected plane condition (the printed
  (11.6.6) is identically zero) with sympy Jacobians (:func:`condition_equations`), collinearity
  in polar coordinates (11.6.9) (:func:`polar_project`) and the angles of an image from
  measured bearings and vertical angles (11.6.10) (:func:`orientation_from_directions`).
* §11.7 approximate EO of arbitrarily oriented images: the book's linear model linking
  (11.7.1)–(11.7.13) (:func:`link_models_linear`), Umeyama's SVD solution for comparison
  (:func:`link_models_svd`), and the chaining (11.7.14)/(11.7.15) (:func:`chain_rotation`,
  :func:`centre_in_object`).
* §11.8 accuracy of the normal case: (11.8.1) (:func:`base_intersection`), (11.8.2)
  (:func:`normal_case_point`), (11.8.4) with the tilted/deviated corrections
  (:func:`normal_case_accuracy`), its Monte Carlo check (:func:`normal_case_monte_carlo`) and
  the design of a survey, (11.8.5)–(11.8.7) (:func:`stereo_design`).
* §11.9 three-view matching of targets by epipolar lines (:func:`match_three_views`) and the
  probe tip from its intersected marks (:func:`probe_tip`).

Hanzl, Fotogrammetrie, Modul 01, §5.4 (seed 002 lines 921–946): the empirical accuracy of
multi-station close-range photogrammetry σ_p = q σ_x m_s/√k (:func:`close_range_point_sigma`) and the
relative redundancy r̄ (:func:`relative_redundancy`; the text prints r/n, the mean redundancy
number is r/m).

Units: image coordinates and f in mm (or all in pixels — only ratios matter in §11.8), object
coordinates in m, angles in radians. The aerial normal case of Chapter 2 (base along X, depth
along −Z) is reused: the terrestrial frame has depth along +Y and height along Z.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from . import _checks
from .camera import ExteriorOrientation, InteriorOrientation, as_points
from .errors import DegenerateGeometryError, InputError, PointBehindCameraError
from .image_pair import (image_rays, intersect_rays, intersection_scale, normal_case_intersection,
                         photo_base, similarity_closed_form)
from .image_pair import normal_case_accuracy as _aerial_accuracy
from .lsq import gauss_newton
from .rotation import rotation_matrix

__all__ = ["CASES", "BaseSystem", "base_system", "case_rotation", "case_orientations", "normal_case_point",
           "base_intersection", "normal_case_accuracy", "normal_case_monte_carlo", "StereoDesign",
           "stereo_design", "condition_equations", "polar_project", "orientation_from_directions",
           "ModelLink", "link_models_linear", "link_models_svd", "chain_rotation", "centre_in_object",
           "match_three_views", "probe_tip", "close_range_point_sigma", "relative_redundancy"]

CASES = ("normal", "deviated", "tilted", "convergent")
"""The standard cases of terrestrial stereo photography (§11.5)."""


def _num(value, name, positive=False):
    return _checks.number(value, name, positive)


def _vec3(value, name):
    return as_points(value, 3, name)[0] if np.ndim(value) == 1 else _bad_vec(name)


def _bad_vec(name):
    raise InputError(f"{name}: expected a 3-vector")


# --- §11.4 ------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class BaseSystem:
    """The base coordinate system of a terrestrial pair (§11.4, Fig. 11.34).

    Attributes
    ----------
    origin : (3,) ndarray
        S₁ in the object frame.
    axes : (3, 3) ndarray
        Rows: the unit X, Y, Z axes of the base system in the object frame (Z vertical).

    References
    ----------
    Chibunichev (2022), §11.4, Fig. 11.34.

    Examples
    --------
    >>> s = base_system([0.0, 0.0, 0.0], [3.0, 4.0, 1.0])
    >>> s.to_base([[3.0, 4.0, 1.0]]).round(9) + 0.0
    array([[5., 0., 1.]])
    """

    origin: np.ndarray
    axes: np.ndarray

    def to_base(self, points) -> np.ndarray:
        """Object → base coordinates of (n, 3) points."""
        return (as_points(points, 3, "points") - self.origin) @ self.axes.T

    def to_object(self, points) -> np.ndarray:
        """Base → object coordinates of (n, 3) points."""
        return self.origin + as_points(points, 3, "points") @ self.axes


def base_system(S1, S2) -> BaseSystem:
    """The base system of §11.4 from the projection centres S₁, S₂ (object frame, Z up).

    Parameters
    ----------
    S1, S2 : 3-vectors
        Left and right projection centres (m), object Z vertical.

    Returns
    -------
    BaseSystem
        Origin S₁; X along the horizontal projection of S₂ − S₁, Z vertical, Y = Z × X.

    Raises
    ------
    InputError
        Not 3-vectors, NaN/inf.
    DegenerateGeometryError
        A vertical (or zero) base: its horizontal projection has no direction (use a vertical
        base system with Z horizontal instead).

    References
    ----------
    Chibunichev (2022), §11.4, Fig. 11.34.

    Examples
    --------
    >>> base_system([1.0, 1.0, 0.0], [1.0, 3.0, 0.0]).axes.round(9) + 0.0
    array([[ 0.,  1.,  0.],
           [-1.,  0.,  0.],
           [ 0.,  0.,  1.]])
    """
    S1, S2 = _vec3(S1, "S1"), _vec3(S2, "S2")
    h = (S2 - S1)[:2]
    n = np.hypot(*h)
    if n < 1e-12 * max(1.0, np.linalg.norm(S2 - S1)):
        raise DegenerateGeometryError("the base is vertical or zero: its horizontal projection has no direction")
    ex = np.array([h[0] / n, h[1] / n, 0.0])
    ez = np.array([0.0, 0.0, 1.0])
    return BaseSystem(S1.copy(), np.vstack([ex, np.cross(ez, ex), ez]))


# --- §11.5 ------------------------------------------------------------------------------------------
def case_rotation(case: str, image: int = 1, *, deviation: float = 0.0, tilt: float = 0.0,
                  convergence: float = 0.0) -> np.ndarray:
    """A (camera → base system) of an image in one of the standard cases of §11.5.

    ω = 90° + tilt, α = deviation (± convergence/2), κ = 0 in A = A_ω A_α A_κ (1.3.2); the optical
    axis A(0, 0, −1)ᵀ is then (−sin α cos τ, cos α cos τ, sin τ): α > 0 turns it toward −X,
    τ = tilt > 0 raises it.

    Parameters
    ----------
    case : {"normal", "deviated", "tilted", "convergent"}
        The case.
    image : {1, 2}
        Left or right image (matters only for the convergent case: α₁ = −γ/2, α₂ = +γ/2, the
        axes turned toward each other for a base along +X).
    deviation, tilt, convergence : float
        α of the deviated case, the tilt τ of the tilted case, the convergence angle γ (rad).

    Returns
    -------
    (3, 3) ndarray
        A.

    Raises
    ------
    InputError
        Unknown case, image not 1 or 2, NaN angles, |γ| ≥ π.

    References
    ----------
    Chibunichev (2022), §11.5, Figs. 11.35–11.38; §11.8 (the normal-case matrix); §1.3, eq. (1.3.2).

    Examples
    --------
    >>> case_rotation("normal").round(12) + 0.0
    array([[ 1.,  0.,  0.],
           [ 0.,  0., -1.],
           [ 0.,  1.,  0.]])
    """
    if case not in CASES:
        raise InputError(f"unknown case {case!r}; use one of {CASES}")
    if image not in (1, 2):
        raise InputError(f"image must be 1 or 2, got {image!r}")
    dev, tau, gam = _num(deviation, "deviation"), _num(tilt, "tilt"), _num(convergence, "convergence")
    if abs(gam) >= np.pi:
        raise InputError(f"the convergence angle must be below π in magnitude, got {gam}")
    omega, alpha = np.pi / 2, 0.0
    if case == "deviated":
        alpha = dev
    elif case == "tilted":
        omega += tau
    elif case == "convergent":
        alpha = gam / 2 if image == 2 else -gam / 2
    return rotation_matrix(omega, alpha, 0.0, "wak")


def case_orientations(case: str, base: float, *, deviation: float = 0.0, tilt: float = 0.0,
                      convergence: float = 0.0, height: float = 0.0) -> tuple:
    """The two exterior orientations of a pair of the given case in the base system (§11.5).

    S₁ = (0, 0, 0), S₂ = (B, 0, height) (a horizontal base with ``height = 0``).

    Parameters
    ----------
    case : {"normal", "deviated", "tilted", "convergent"}
        As in :func:`case_rotation`.
    base : float
        B (m), positive.
    deviation, tilt, convergence : float
        As in :func:`case_rotation` (rad).
    height : float
        Z of S₂ (m).

    Returns
    -------
    (ExteriorOrientation, ExteriorOrientation)
        Order ``"wak"``.

    Raises
    ------
    InputError
        As :func:`case_rotation`, a non-positive base.

    References
    ----------
    Chibunichev (2022), §11.5; §11.8 (X_S1 = Y_S1 = Z_S1 = 0, B_Y = 0).

    Examples
    --------
    >>> e1, e2 = case_orientations("normal", 5.0)
    >>> e2.center, round(float(e1.omega), 6)
    (array([5., 0., 0.]), 1.570796)
    """
    B = _num(base, "the base", positive=True)
    h = _num(height, "height")
    case_rotation(case, 1, deviation=deviation, tilt=tilt, convergence=convergence)     # validates
    omega = np.pi / 2 + (_num(tilt, "tilt") if case == "tilted" else 0.0)
    out = []
    for i, S in ((1, (0.0, 0.0, 0.0)), (2, (B, 0.0, h))):
        alpha = {"deviated": _num(deviation, "deviation"),
                 "convergent": (1 if i == 2 else -1) * _num(convergence, "convergence") / 2}.get(case, 0.0)
        out.append(ExteriorOrientation(*S, omega, alpha, 0.0, order="wak"))
    return tuple(out)


# --- §11.8 ------------------------------------------------------------------------------------------
def normal_case_point(x1, y1, x2, f, B) -> np.ndarray:
    """(11.8.2): X = (B_X/p)x₁, Y = (B_X/p)f, Z = (B_X/p)y₁ with p = x₁ − x₂ (base system).

    The aerial normal case of §2.5 (:func:`photolib.image_pair.normal_case_intersection`) with
    the depth along +Y instead of −Z: (X, Y, Z)_terrestrial = (X, −Z, Y)_aerial.

    Parameters
    ----------
    x1, y1, x2 : float or arrays
        Image coordinates (mm or px).
    f : float
        Focal length (same unit).
    B : float
        Base B_X (its unit is that of the result).

    Returns
    -------
    (n, 3) ndarray
        X, Y, Z in the base system.

    Raises
    ------
    InputError
        NaN/inf, f ≤ 0, incompatible shapes.
    DegenerateGeometryError
        Zero parallax.

    References
    ----------
    Chibunichev (2022), §11.8, eqs. (11.8.2), (11.8.3); §2.5, eq. (2.5.3).

    Examples
    --------
    >>> normal_case_point(1160.0, 870.0, -3480.0, 17400.0, 8.0)
    array([[ 2. , 30. ,  1.5]])
    """
    P = normal_case_intersection(x1, y1, x2, f, B)
    return np.column_stack([P[:, 0], -P[:, 2], P[:, 1]])


def base_intersection(xy1, xy2, eo1: ExteriorOrientation, eo2: ExteriorOrientation,
                      io1: InteriorOrientation, io2: InteriorOrientation | None = None) -> np.ndarray:
    """(11.8.1): X = X_S1 + N·X′₁, N = (B_X Y′₂ − B_Y X′₂)/(X′₁Y′₂ − X′₂Y′₁).

    The third formula of (2.4.12) (Z components of B × r₂ and r₁ × r₂), suited to a depth along
    Y; computed by :func:`photolib.image_pair.intersection_scale` with ``formula=3``.

    Parameters
    ----------
    xy1, xy2 : (n, 2) arrays
        Image coordinates (mm).
    eo1, eo2 : ExteriorOrientation
        Orientation in the base (or object) system.
    io1, io2 : InteriorOrientation
        Cameras (``io2`` defaults to ``io1``).

    Returns
    -------
    (n, 3) ndarray
        X, Y, Z.

    Raises
    ------
    InputError
        Bad shapes or types.
    DegenerateGeometryError
        Parallel rays, a denominator ≈ 0 (rays in a vertical plane).
    PointBehindCameraError
        N ≤ 0.

    References
    ----------
    Chibunichev (2022), §11.8, eq. (11.8.1); §2.4, eq. (2.4.12).

    Examples
    --------
    >>> io = InteriorOrientation(17400.0)
    >>> e1, e2 = case_orientations("normal", 8.0)
    >>> base_intersection([[1160.0, 870.0]], [[-3480.0, 870.0]], e1, e2, io).round(9) + 0.0
    array([[ 2. , 30. ,  1.5]])
    """
    io2 = io1 if io2 is None else io2
    a, b = as_points(xy1, 2, "xy1"), as_points(xy2, 2, "xy2")
    if len(a) != len(b):
        raise InputError(f"xy1 has {len(a)} points, xy2 {len(b)}")
    r1, r2 = image_rays(a, eo1, io1), image_rays(b, eo2, io2)
    N = intersection_scale(eo2.center - eo1.center, r1, r2, method="component", formula=3)
    if np.any(N <= 0):
        bad = np.flatnonzero(N <= 0)
        raise PointBehindCameraError(f"points {bad.tolist()} lie behind camera 1 (N ≤ 0)", points=bad)
    return eo1.center + N[:, None] * r1


def normal_case_accuracy(Y, f, b, m_x, m_y, m_p, *, tilt: float = 0.0, deviation: float = 0.0) -> tuple:
    """(11.8.4): m_X = (Y/f)m_x, m_Y = (Y/b)m_p, m_Z = (Y/f)m_y, with the case corrections.

    Tilted case: Y is replaced by Y/cos ω (ω the tilt from the horizontal); deviated case: b by
    b·cos α (§11.8, after the example). The approximations of the book are kept: p replaced by
    b (exact at the design distance) and the term (x₁/p)m_p of m_X dropped (a point near the
    image centre) — :func:`normal_case_monte_carlo` measures what that costs.

    Parameters
    ----------
    Y : float
        Distance to the object (m).
    f, b : float
        Focal length and image base (px or mm).
    m_x, m_y, m_p : float
        Errors of x, y and the parallax (unit of f).
    tilt, deviation : float
        ω of the tilted case and α of the deviated case (rad).

    Returns
    -------
    (m_X, m_Y, m_Z)
        Floats in the unit of Y (Y the depth, Z the height).

    Raises
    ------
    InputError
        NaN/inf, non-positive Y, f, b; |tilt| or |deviation| ≥ π/2.

    References
    ----------
    Chibunichev (2022), §11.8, eqs. (11.8.3), (11.8.4); §2.13, eqs. (2.13.1)–(2.13.3).

    Examples
    --------
    >>> [round(v, 5) for v in normal_case_accuracy(30.0, 17400.0, 4640.0, 0.5, 0.5, 0.5)]
    [0.00086, 0.00323, 0.00086]
    """
    tau, dev = _num(tilt, "tilt"), _num(deviation, "deviation")
    if abs(tau) >= np.pi / 2 or abs(dev) >= np.pi / 2:
        raise InputError("tilt and deviation must be below 90° in magnitude")
    Yc = _num(Y, "Y", positive=True) / np.cos(tau)
    bc = _num(b, "b", positive=True) * np.cos(dev)
    mX, mZ, mY = _aerial_accuracy(Yc, _num(f, "f", positive=True), bc, _num(m_x, "m_x"), _num(m_y, "m_y"),
                                  _num(m_p, "m_p"), approximate=True)
    return mX, mY, mZ


def normal_case_monte_carlo(Y, f, B, X=0.0, Z=0.0, m_x=0.5, m_y=0.5, m_p=0.5, n: int = 20000, rng=0) -> tuple:
    """Seeded Monte Carlo of the normal case (11.8.2): the spread of X, Y, Z of one point.

    The point (X, Y, Z) of the base system is projected into both images; x₁, y₁ and the
    parallax p get independent normal errors m_x, m_y, m_p; (11.8.2) is evaluated for every draw.

    Parameters
    ----------
    Y, f, B : float
        Depth (m), focal length (px), base (m).
    X, Z : float
        The point's other coordinates (m).
    m_x, m_y, m_p : float
        Errors (px).
    n : int
        Draws.
    rng : int or numpy.random.Generator
        Seed.

    Returns
    -------
    (s_X, s_Y, s_Z)
        Standard deviations (m).

    Raises
    ------
    InputError
        NaN, non-positive Y, f, B; n < 2.

    References
    ----------
    Chibunichev (2022), §11.8, eqs. (11.8.2), (11.8.4).

    Examples
    --------
    >>> s = normal_case_monte_carlo(30.0, 17400.0, 8.0, n=20000, rng=1)
    >>> [round(v * 1000, 1) for v in s]            # mm; (11.8.4): 0.86, 3.23, 0.86
    [0.9, 3.2, 0.9]
    """
    Y, f, B = _num(Y, "Y", positive=True), _num(f, "f", positive=True), _num(B, "B", positive=True)
    X, Z = _num(X, "X"), _num(Z, "Z")
    sig = [_num(v, name, positive=True) for v, name in ((m_x, "m_x"), (m_y, "m_y"), (m_p, "m_p"))]
    n = _checks.integer(n, "n", 2)
    gen = rng if isinstance(rng, np.random.Generator) else np.random.default_rng(rng)
    x1, y1, p = f * X / Y, f * Z / Y, f * B / Y
    e = gen.normal(0.0, 1.0, (n, 3)) * sig
    P = normal_case_point(x1 + e[:, 0], y1 + e[:, 1], x1 + e[:, 0] - (p + e[:, 2]), f, B)
    s = P.std(axis=0, ddof=1)
    return float(s[0]), float(s[1]), float(s[2])


@dataclass(frozen=True)
class StereoDesign:
    """A normal-case survey design (§11.8): base, accuracy, coverage.

    Attributes
    ----------
    b : float
        Image base (px), (11.8.5).
    m_X, m_Y, m_Z : float
        A-priori errors (m), (11.8.4).
    delta : float
        Object pixel Δ = Y/f (m/px), (11.8.7) (rounded when asked).
    H_X, H_Z : float
        Object coverage of one image (m), (11.8.6).
    B : float
        Object base Δ·b (m).
    stereo_width : float
        Horizontal width covered by both images, P % of H_X (m).

    References
    ----------
    Chibunichev (2022), §11.8, eqs. (11.8.4)–(11.8.7).

    Examples
    --------
    >>> d = stereo_design(17400.0, (11600, 8700), 30.0)
    >>> round(d.B, 3), round(d.stereo_width, 3)
    (8.0, 12.0)
    """

    b: float
    m_X: float
    m_Y: float
    m_Z: float
    delta: float
    H_X: float
    H_Z: float
    B: float
    stereo_width: float


def stereo_design(f, frame, Y, overlap: float = 60.0, m_px: float = 0.5, orientation: str = "horizontal",
                  delta_decimals: int | None = None) -> StereoDesign:
    """Design a normal-case pair (§11.8): b (11.8.5), m (11.8.4), Δ (11.8.7), H (11.8.6), B = Δb.

    Parameters
    ----------
    f : float
        Focal length (px).
    frame : (int, int)
        Frame size (px) of the long and short side.
    Y : float
        Distance to the object (m).
    overlap : float
        Forward overlap P (%), in [0, 100).
    m_px : float
        m_x = m_y = m_p (px).
    orientation : {"horizontal", "vertical"}
        "horizontal": l_x = the long side; "vertical": l_x = the short side.
    delta_decimals : int, optional
        Round Δ to these decimals before H and B (the book rounds to 4: 0.0017, 0.0026).

    Returns
    -------
    StereoDesign

    Raises
    ------
    InputError
        NaN, non-positive sizes, an overlap outside [0, 100), an unknown orientation.

    References
    ----------
    Chibunichev (2022), §11.8, eqs. (11.8.4)–(11.8.7), worked example.

    Examples
    --------
    >>> d = stereo_design(11670.0, (5470, 3650), 30.0, orientation="vertical", delta_decimals=4)
    >>> d.b, round(d.B, 3)
    (1460.0, 3.796)
    """
    f, Y = _num(f, "f", positive=True), _num(Y, "Y", positive=True)
    fr = np.asarray(frame, dtype=float) if not isinstance(frame, str) else None
    if fr is None or fr.shape != (2,) or not np.all(np.isfinite(fr)) or np.any(fr <= 0):
        raise InputError(f"frame must be two positive sizes (px), got {frame!r}")
    if orientation not in ("horizontal", "vertical"):
        raise InputError(f"orientation must be 'horizontal' or 'vertical', got {orientation!r}")
    long_, short = max(fr), min(fr)
    lx, ly = (long_, short) if orientation == "horizontal" else (short, long_)
    P = _num(overlap, "overlap")
    b = photo_base(lx, P)                                                       # (11.8.5)
    m = _num(m_px, "m_px", positive=True)
    mX, mY, mZ = normal_case_accuracy(Y, f, b, m, m, m)                          # (11.8.4)
    delta = Y / f                                                               # (11.8.7)
    if delta_decimals is not None:
        delta = round(delta, _checks.integer(delta_decimals, "delta_decimals", 0))
    HX, HZ = lx * delta, ly * delta                                             # (11.8.6)
    return StereoDesign(float(b), mX, mY, mZ, float(delta), float(HX), float(HZ), float(delta * b),
                        float(HX * P / 100.0))


# --- §11.6 ------------------------------------------------------------------------------------------
_CONDITIONS = {"distance": (2, True), "base": (2, True), "centre_distance": (2, True), "vertical": (2, False),
               "horizontal": (2, False), "coplanar": (4, False)}


def _condition_model(kind):
    from .derivations import terrestrial as dt
    return {"distance": dt.distance_condition_model, "base": dt.base_condition_model,
            "centre_distance": dt.centre_distance_model, "vertical": dt.vertical_line_model,
            "horizontal": dt.horizontal_plane_model, "coplanar": dt.coplanarity4_model}[kind]()


def condition_equations(kind: str, points, measured=None) -> tuple:
    """Residuals F and coefficients ∂F/∂(coordinates) of the geometric conditions of §11.6.

    ``kind`` and the points (each an (n, 3) array, one row per condition):

    * ``"distance"`` (11.6.1): P_i, P_j and the measured distances D_ij;
    * ``"base"`` (11.6.2): S_i, S_j and the measured base B;
    * ``"centre_distance"`` (11.6.3): P_i, S_i and D_i;
    * ``"vertical"`` (11.6.4): P_i, P_j (two equations each);
    * ``"horizontal"`` (11.6.5, read Z_i − Z_j = 0): P_i, P_j;
    * ``"coplanar"``: P_i, P_j, P_k, P_l — det[P_j − P_i; P_k − P_i; P_l − P_i] = 0, replacing the
      printed (11.6.6), which is identically zero.

    The correction equation of each condition is ∂F/∂p·δ + F = v, e.g. (11.6.7) δD + l_D = v_D.

    Parameters
    ----------
    kind : str
        One of the names above.
    points : sequence of (n, 3) arrays
        The points (2 or 4 arrays).
    measured : (n,) array, optional
        D or B for the distance conditions (required there).

    Returns
    -------
    (F, J)
        F (n, q) residuals at the given coordinates and J (n, q, 3·k) their derivatives by the
        coordinates of the k points in the order given (q = 2 for "vertical", else 1).

    Raises
    ------
    InputError
        Unknown kind, a wrong number of point arrays, bad shapes, NaN, missing or surplus
        ``measured``.
    DegenerateGeometryError
        Coincident points in a distance condition (the derivative is undefined).

    References
    ----------
    Chibunichev (2022), §11.6, eqs. (11.6.1)–(11.6.7).

    Examples
    --------
    >>> F, J = condition_equations("distance", [[[0.0, 0, 0]], [[3.0, 4, 0]]], [4.9])
    >>> F.round(9), J[0, 0].round(9)
    (array([[0.1]]), array([-0.6, -0.8, -0. ,  0.6,  0.8,  0. ]))
    """
    if kind not in _CONDITIONS:
        raise InputError(f"unknown condition {kind!r}; use one of {tuple(_CONDITIONS)}")
    k, has_data = _CONDITIONS[kind]
    if isinstance(points, np.ndarray) and points.ndim == 3:
        points = list(points)
    if not isinstance(points, (list, tuple)) or len(points) != k:
        raise InputError(f"the {kind!r} condition needs {k} point arrays")
    P = [as_points(p, 3, f"points {i + 1}") for i, p in enumerate(points)]
    n = len(P[0])
    if any(len(p) != n for p in P):
        raise InputError("the point arrays have different lengths")
    args = [c for p in P for c in p.T]
    if has_data:
        if measured is None:
            raise InputError(f"the {kind!r} condition needs the measured distances")
        d = np.atleast_1d(np.asarray(measured, dtype=float)) if not isinstance(measured, str) else None
        if d is None or d.shape not in ((n,), (1,)) or not np.all(np.isfinite(d)):
            raise InputError(f"measured: expected {n} finite values")
        if np.any(np.linalg.norm(P[0] - P[1], axis=1) == 0):
            raise DegenerateGeometryError("coincident points: the distance condition has no derivative there")
        args.append(np.broadcast_to(d, (n,)))
    elif measured is not None:
        raise InputError(f"the {kind!r} condition takes no measured values")
    res_fn, jac_fn = _condition_model(kind).compile()
    F = np.broadcast_to(np.asarray(res_fn(*args)).reshape(res_fn.count, -1), (res_fn.count, n)).T
    J = np.broadcast_to(np.asarray(jac_fn(*args)).reshape(jac_fn.count, -1), (jac_fn.count, n)).T
    J = J.reshape(n, res_fn.count, 3 * k)
    return np.ascontiguousarray(F), np.ascontiguousarray(J)


def _polar_funcs():
    from .derivations import terrestrial as dt
    return dt.polar_collinearity_model().compile()


def polar_project(phi, nu, omega, alpha, kappa, io: InteriorOrientation) -> np.ndarray:
    """(11.6.9): image coordinates of the directions (bearing φ, vertical angle ν).

    Parameters
    ----------
    phi, nu : (n,) arrays
        Bearing (from +Y toward +X) and vertical angle (rad) measured from the projection centre.
    omega, alpha, kappa : float
        Angles of the image (A = A_ω A_α A_κ, (1.3.2)).
    io : InteriorOrientation
        The camera (f, x₀, y₀).

    Returns
    -------
    (n, 2) ndarray
        x, y (mm).

    Raises
    ------
    InputError
        NaN, mismatched lengths, a wrong camera type.
    PointBehindCameraError
        A direction behind the camera.

    References
    ----------
    Chibunichev (2022), §11.6, eqs. (11.6.8), (11.6.9).

    Examples
    --------
    >>> polar_project([0.0], [0.0], np.pi / 2, 0.0, 0.0, InteriorOrientation(100.0)).round(9) + 0.0
    array([[0., 0.]])
    """
    if not isinstance(io, InteriorOrientation):
        raise InputError("io must be an InteriorOrientation")
    a = np.column_stack(_finite_pair(phi, nu))
    A = rotation_matrix(omega, alpha, kappa, "wak")
    d = np.column_stack([np.cos(a[:, 1]) * np.sin(a[:, 0]), np.cos(a[:, 1]) * np.cos(a[:, 0]), np.sin(a[:, 1])]) @ A
    if np.any(d[:, 2] >= 0):
        raise PointBehindCameraError("a direction points behind the camera", points=np.flatnonzero(d[:, 2] >= 0))
    return np.column_stack([io.x0 - io.f * d[:, 0] / d[:, 2], io.y0 - io.f * d[:, 1] / d[:, 2]])


def _finite_pair(phi, nu):
    try:
        a, b = np.broadcast_arrays(np.atleast_1d(np.asarray(phi, dtype=float)), np.atleast_1d(np.asarray(nu, dtype=float)))
    except (TypeError, ValueError):
        raise InputError("phi and nu must be numbers of one length") from None
    if a.ndim != 1 or not (np.all(np.isfinite(a)) and np.all(np.isfinite(b))):
        raise InputError("phi and nu must be finite 1-D arrays")
    return a, b


def orientation_from_directions(xy, phi, nu, io: InteriorOrientation, start=(np.pi / 2, 0.0, 0.0), **kwargs):
    """ω, α, κ of an image from measured directions to imaged points (11.6.9)/(11.6.10).

    Least squares (photolib.lsq.gauss_newton) on the correction equations (11.6.10), whose
    coefficients a₁…b₃ are the sympy Jacobian of (11.6.9); at least two directions.

    Parameters
    ----------
    xy : (n, 2) array
        Image coordinates of the points (mm).
    phi, nu : (n,) arrays
        Bearings and vertical angles (rad).
    io : InteriorOrientation
        The camera.
    start : 3 floats
        Approximate ω, α, κ (default the normal case).
    **kwargs
        Passed to :func:`photolib.lsq.gauss_newton` (``tol``, ``max_iter``, ``weights``).

    Returns
    -------
    Adjustment
        ``x`` = (ω, α, κ), μ, m_j.

    Raises
    ------
    InputError
        Bad shapes, NaN.
    DegenerateGeometryError
        Fewer than two directions, or two identical directions.
    ConvergenceError
        No convergence.

    References
    ----------
    Chibunichev (2022), §11.6, eqs. (11.6.9), (11.6.10).

    Examples
    --------
    >>> io = InteriorOrientation(100.0)
    >>> phi, nu = np.array([-0.2, 0.1, 0.3]), np.array([0.05, -0.1, 0.2])
    >>> xy = polar_project(phi, nu, 1.6, 0.1, 0.02, io)
    >>> orientation_from_directions(xy, phi, nu, io).x.round(9)
    array([1.6 , 0.1 , 0.02])
    """
    if not isinstance(io, InteriorOrientation):
        raise InputError("io must be an InteriorOrientation")
    xy = as_points(xy, 2, "xy")
    phi, nu = _finite_pair(phi, nu)
    if len(phi) != len(xy):
        raise InputError(f"{len(xy)} image points but {len(phi)} directions")
    dirs = np.column_stack([np.cos(nu) * np.sin(phi), np.cos(nu) * np.cos(phi), np.sin(nu)])
    if len(xy) < 2 or np.linalg.matrix_rank(dirs, tol=1e-9) < 2:
        raise DegenerateGeometryError("at least two different directions are needed (11.6.9)")
    res_fn, jac_fn = _polar_funcs()
    n = len(xy)
    data = (phi, nu, xy[:, 0], xy[:, 1], io.f, io.x0, io.y0)

    def linearize(p):
        F = np.broadcast_to(res_fn(*p, *data), (2, n))
        J = np.broadcast_to(jac_fn(*p, *data), (6, n)).reshape(2, 3, n)
        return np.concatenate([J[0].T, J[1].T]), np.concatenate([F[0], F[1]])

    start = as_points(start, 3, "start")[0]
    return gauss_newton(linearize, start, names=("omega", "alpha", "kappa"), **kwargs)


# --- §11.7 ------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class ModelLink:
    """Transform of model 2 into model 1, R₁ = R_S3 + t·A·R₃ (11.7.1).

    Attributes
    ----------
    shift : (3,) ndarray
        R_S3.
    A : (3, 3) ndarray
        Rotation (from C/t: orthogonal only approximately for the book's method).
    t : float
        Scale.
    C : (3, 3) ndarray or None
        The linear matrix C = tA of (11.7.3) (book method only).

    References
    ----------
    Chibunichev (2022), §11.7, eqs. (11.7.1)–(11.7.13).

    Examples
    --------
    >>> L = ModelLink(np.zeros(3), np.eye(3), 2.0, None)
    >>> L.apply([[1.0, 2.0, 3.0]])
    array([[2., 4., 6.]])
    """

    shift: np.ndarray
    A: np.ndarray
    t: float
    C: np.ndarray | None = None

    def apply(self, points) -> np.ndarray:
        """Model-2 points in model 1 by (11.7.1)."""
        return self.shift + self.t * as_points(points, 3, "points") @ self.A.T


def _pairs(P1, P3, minimum):
    P1, P3 = as_points(P1, 3, "model-1 points"), as_points(P3, 3, "model-2 points")
    if len(P1) != len(P3):
        raise InputError(f"{len(P1)} model-1 points but {len(P3)} model-2 points")
    if len(P1) < minimum:
        raise DegenerateGeometryError(f"at least {minimum} common points are needed, got {len(P1)}")
    return P1, P3


def link_models_linear(P1, P3, *, common: int = 0, orthogonality: bool = True) -> ModelLink:
    """The book's linear model linking (11.7.2)–(11.7.13): C row by row, then t = ‖c₁‖, A = C/t.

    Both point sets are shifted to the common point M₁ (row ``common``) (11.7.2); each row of C
    is the least-squares solution of (11.7.6)–(11.7.8), rows 2 and 3 with the orthogonality
    equations (11.7.9)/(11.7.10) appended (unit weight, as the book writes them); then
    t = √(c₁₁² + c₁₂² + c₁₃²) (11.7.12) and A = C/t (11.7.13). A is orthogonal only
    approximately — good for start values, the book's purpose; re-orthonormalise before taking
    angles (:func:`photolib.projective.nearest_rotation`).

    Parameters
    ----------
    P1, P3 : (n, 3) arrays
        Coordinates of the common points in model 1 and model 2, n ≥ 4.
    common : int
        Index of M₁.
    orthogonality : bool
        Append (11.7.9)/(11.7.10).

    Returns
    -------
    ModelLink

    Raises
    ------
    InputError
        Bad shapes, NaN, different counts, ``common`` out of range.
    DegenerateGeometryError
        Fewer than 4 points, or the difference vectors from M₁ coplanar (C undetermined).

    References
    ----------
    Chibunichev (2022), §11.7, eqs. (11.7.1)–(11.7.13).

    Examples
    --------
    >>> P3 = np.array([[0.0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1], [1, 1, 1]])
    >>> L = link_models_linear(2 * P3 + 5, P3)
    >>> round(L.t, 9), L.shift.round(9)
    (2.0, array([5., 5., 5.]))
    """
    P1, P3 = _pairs(P1, P3, 4)
    c = _checks.integer(common, "common", 0)
    if c >= len(P1):
        raise InputError(f"common point index {c} out of range for {len(P1)} points")
    d1, d3 = np.delete(P1 - P1[c], c, axis=0), np.delete(P3 - P3[c], c, axis=0)     # (11.7.2)
    s = np.linalg.svd(d3, compute_uv=False)
    if s[-1] < 1e-9 * s[0]:
        raise DegenerateGeometryError("the model-2 points are coplanar with M1: C of (11.7.5) is undetermined")
    C = np.zeros((3, 3))
    for r in range(3):                                                               # (11.7.6)–(11.7.8)
        M, L = d3, d1[:, r]
        if orthogonality and r:
            M = np.vstack([M, C[:r]])                                                # (11.7.9)/(11.7.10)
            L = np.concatenate([L, np.zeros(r)])
        C[r] = np.linalg.lstsq(M, L, rcond=None)[0]
    t = float(np.linalg.norm(C[0]))                                                  # (11.7.12)
    A = C / t                                                                        # (11.7.13)
    return ModelLink(P1[c] - t * A @ P3[c], A, t, C)


def link_models_svd(P1, P3) -> ModelLink:
    """Reference solution of (11.7.1): Umeyama's closed-form similarity (SVD, reflection-guarded).

    The rotation is unique (the sign ambiguity of the SVD is removed by the determinant guard),
    so no sign normalisation of the singular vectors leaks into the result.

    Parameters
    ----------
    P1, P3 : (n, 3) arrays
        Common points in model 1 and model 2, n ≥ 3, not collinear.

    Returns
    -------
    ModelLink
        With ``C`` = None.

    Raises
    ------
    InputError
        Bad shapes, different counts.
    DegenerateGeometryError
        Fewer than 3 or collinear points.

    References
    ----------
    Chibunichev (2022), §11.7, eq. (11.7.1); §2.11 (:func:`photolib.image_pair.similarity_closed_form`).

    Examples
    --------
    >>> P3 = np.array([[0.0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]])
    >>> round(link_models_svd(3 * P3, P3).t, 9)
    3.0
    """
    P1, P3 = _pairs(P1, P3, 3)
    T = similarity_closed_form(P3, P1, order="wak")
    return ModelLink(T.shift, T.matrix, float(T.t), None)


def chain_rotation(A0, A, A3p) -> np.ndarray:
    """(11.7.14): A₃ = A₀·A·A′₃ — image 3 in the object frame.

    Parameters
    ----------
    A0 : (3, 3) array
        Common model → object (from exterior orientation of the common model).
    A : (3, 3) array
        Model 2 → model 1 (11.7.13).
    A3p : (3, 3) array
        Image 3 → model 2 (relative orientation).

    Returns
    -------
    (3, 3) ndarray

    Raises
    ------
    InputError
        Not 3×3 or NaN.

    References
    ----------
    Chibunichev (2022), §11.7, eq. (11.7.14).

    Examples
    --------
    >>> chain_rotation(np.eye(3), np.eye(3), np.eye(3))[0]
    array([1., 0., 0.])
    """
    Ms = []
    for M, name in ((A0, "A0"), (A, "A"), (A3p, "A3p")):
        M = np.asarray(M, dtype=float) if not isinstance(M, str) else None
        if M is None or M.shape != (3, 3) or not np.all(np.isfinite(M)):
            raise InputError(f"{name} must be a finite 3×3 matrix")
        Ms.append(M)
    return Ms[0] @ Ms[1] @ Ms[2]


def centre_in_object(XS1, A0, XS_model, t) -> np.ndarray:
    """(11.7.15): X_S = X_S1 + t·A₀·(X_S)_M — a projection centre in the object frame.

    Parameters
    ----------
    XS1 : 3-vector
        Origin of the common model in the object frame.
    A0 : (3, 3) array
        Common model → object.
    XS_model : (n, 3) array
        Centres in the common model.
    t : float
        Scale of the common model.

    Returns
    -------
    (n, 3) ndarray

    Raises
    ------
    InputError
        Bad shapes, NaN, t ≤ 0.

    References
    ----------
    Chibunichev (2022), §11.7, eq. (11.7.15).

    Examples
    --------
    >>> centre_in_object([1.0, 2, 3], np.eye(3), [[1.0, 0, 0]], 2.0)
    array([[3., 2., 3.]])
    """
    A0 = chain_rotation(A0, np.eye(3), np.eye(3))
    return _vec3(XS1, "XS1") + _num(t, "t", positive=True) * as_points(XS_model, 3, "XS_model") @ A0.T


# --- §11.9 ------------------------------------------------------------------------------------------
def match_three_views(xy1, xy2, xy3, F12, F13, F23, threshold: float) -> np.ndarray:
    """Corresponding targets on three images by epipolar ("basis") lines (§11.9, Fig. 11.56).

    For each point P of image 1: the candidates on image 2 are the points within ``threshold``
    of its epipolar line; for each candidate the epipolar lines of P (from image 1) and of the
    candidate (from image 2) are intersected on image 3; the match is the image-3 point nearest
    to any of these intersections, if nearer than ``threshold``. A point of image 2 or 3 taken
    by two points of image 1 makes both matches ambiguous; they are dropped.

    Parameters
    ----------
    xy1, xy2, xy3 : (n_i, 2) arrays
        Target centres on the three images.
    F12, F13, F23 : (3, 3) arrays
        Fundamental matrices, layout x_bᵀ F_ab x_a = 0
        (:func:`photolib.projective.fundamental_from_orientation`).
    threshold : float
        Distance to a line / intersection accepted (unit of the coordinates).

    Returns
    -------
    (m, 3) ndarray of int
        Index triples (i1, i2, i3), sorted by i1.

    Raises
    ------
    InputError
        Bad shapes, NaN, a non-positive threshold.
    DegenerateGeometryError
        A point at an epipole.

    References
    ----------
    Chibunichev (2022), §11.9, Figs. 11.55–11.56; §4.4, eq. (4.4.16); §5.6, Fig. 5.18.

    Examples
    --------
    >>> from photolib.projective import fundamental_from_orientation
    >>> from photolib.single_image import project
    >>> io = InteriorOrientation(50.0)
    >>> eos = [ExteriorOrientation(x, 0.0, z, np.pi / 2, 0.0, 0.0, order="wak") for x, z in ((0, 0), (3, 0), (1.5, 2))]
    >>> P = np.array([[0.5, 10, 0.2], [1.0, 11, 1.0], [2.0, 9, -0.5]])
    >>> xy = [project(P, e, io) for e in eos]
    >>> F = lambda a, b: fundamental_from_orientation(io, eos[a], io, eos[b])
    >>> match_three_views(xy[0], xy[1][::-1], xy[2], F(0, 1), F(0, 2), F(1, 2), 0.01).tolist()
    [[0, 2, 0], [1, 1, 1], [2, 0, 2]]
    """
    from .projective import epipolar_lines
    p1, p2, p3 = (as_points(v, 2, f"xy{i}") for i, v in ((1, xy1), (2, xy2), (3, xy3)))
    thr = _num(threshold, "threshold", positive=True)
    if thr == 0:
        raise InputError("threshold must be positive")
    l12 = epipolar_lines(F12, p1, image=2)
    l13 = epipolar_lines(F13, p1, image=2)
    l23 = epipolar_lines(F23, p2, image=2)
    h2 = np.column_stack([p2, np.ones(len(p2))])
    h3 = np.column_stack([p3, np.ones(len(p3))])
    found = []
    for i in range(len(p1)):
        cand = np.flatnonzero(np.abs(h2 @ l12[i]) <= thr)
        best = (np.inf, -1, -1)
        for j in cand:
            h = np.cross(l13[i], l23[j])
            if abs(h[2]) < 1e-12 * np.linalg.norm(h):
                continue                                      # parallel lines: no intersection
            q = h[:2] / h[2]
            d = np.hypot(*(p3 - q).T)
            k = int(np.argmin(d))
            if d[k] < best[0]:
                best = (d[k], j, k)
        if best[0] <= thr:
            found.append((i, best[1], best[2]))
    out = np.array(found, dtype=int).reshape(-1, 3)
    keep = np.ones(len(out), bool)
    for col in (1, 2):
        vals, counts = np.unique(out[:, col], return_counts=True)
        keep &= ~np.isin(out[:, col], vals[counts > 1])
    return out[keep]


def probe_tip(xy_list, eo_list, io, marks_probe, tip_probe) -> tuple:
    """The object point touched by a probe (§11.9, Fig. 11.51): intersect its marks, map the tip.

    The marks are intersected by least squares (:func:`photolib.image_pair.intersect_rays`),
    the rigid transform probe → object is fitted to them (Umeyama's rotation, scale fixed to 1
    since the probe is rigid and measured) and the tip, known in the probe frame, is mapped.

    Parameters
    ----------
    xy_list : sequence of (k, 2) arrays
        The k marks on each of ≥ 2 images (mm).
    eo_list : sequence of ExteriorOrientation
        Orientation of the images in the object frame.
    io : InteriorOrientation
        Camera (or a list).
    marks_probe : (k, 3) array
        The marks in the probe frame (m), k ≥ 3, not collinear.
    tip_probe : 3-vector
        The tip in the probe frame.

    Returns
    -------
    (tip, marks)
        The tip (3,) and the intersected marks (k, 3) in the object frame.

    Raises
    ------
    InputError
        Bad shapes, NaN, mismatched counts.
    DegenerateGeometryError
        Fewer than 3 marks, collinear marks, parallel rays.

    References
    ----------
    Chibunichev (2022), §11.9, Figs. 11.50–11.52; §2.4.

    Examples
    --------
    >>> from photolib.single_image import project
    >>> io = InteriorOrientation(50.0)
    >>> eos = [ExteriorOrientation(x, 0.0, 0.0, np.pi / 2, a, 0.0, order="wak") for x, a in ((0, -0.1), (2, 0.1))]
    >>> marks = np.array([[0.0, 0, 0], [0.1, 0, 0], [0, 0.1, 0], [0, 0, 0.1]])
    >>> obj = marks + [1.0, 10.0, 0.0]
    >>> tip, _ = probe_tip([project(obj, e, io) for e in eos], eos, io, marks, [0.0, 0.0, -0.2])
    >>> tip.round(6) + 0.0
    array([ 1. , 10. , -0.2])
    """
    marks = as_points(marks_probe, 3, "marks_probe")
    tip = _vec3(tip_probe, "tip_probe")
    if len(marks) < 3:
        raise DegenerateGeometryError(f"at least 3 probe marks are needed, got {len(marks)}")
    if not isinstance(xy_list, (list, tuple)) or len(xy_list) < 2:
        raise InputError("xy_list: images of the marks on at least two images are needed")
    if any(len(as_points(xy, 2, "marks on an image")) != len(marks) for xy in xy_list):
        raise InputError("every image must show all the probe marks in the order of marks_probe")
    r = intersect_rays(xy_list, eo_list, io)
    T = similarity_closed_form(marks, r.points, order="wak")
    A = T.matrix
    shift = r.points.mean(axis=0) - A @ marks.mean(axis=0)               # rigid: scale 1
    return shift + A @ tip, r.points


def close_range_point_sigma(q: float, sigma_x: float, scale_number: float, k: float = 1.0) -> float:
    """Empirical mean point error of close-range photogrammetry, σ_p = q σ_x m_s/√k (Hanzl §5.4).

    σ_p = √(σ_X² + σ_Y² + σ_Z²) is the expected mean position error; q the configuration factor
    (0.4–0.7 for convergent multi-station networks, 1.5–2.0 for the normal case), σ_x the image
    coordinate error, m_s the mean scale number (distance / camera constant) and k the mean
    number of images taken from one station.

    Parameters
    ----------
    q : float
        Configuration factor, > 0.
    sigma_x : float
        Image coordinate error (any unit; σ_p comes out in the same unit), > 0.
    scale_number : float
        m_s, > 0.
    k : float
        Images per station, ≥ 1.

    Returns
    -------
    float
        σ_p, in the unit of ``sigma_x``.

    Raises
    ------
    InputError
        Non-finite or non-positive arguments, k < 1.

    References
    ----------
    Hanzl, Fotogrammetrie, Modul 01, §5.4 (seed 002 lines 921–931); Chibunichev §11.8 (accuracy
    of the normal case).

    Examples
    --------
    >>> round(close_range_point_sigma(0.7, 0.005, 20000 / 50, k=2), 4)      # mm: Example 1
    0.9899
    """
    q = _checks.number(q, "q", positive=True)
    s = _checks.number(sigma_x, "sigma_x", positive=True)
    m = _checks.number(scale_number, "scale_number", positive=True)
    k = _checks.number(k, "k", positive=True)
    if k < 1:
        raise InputError(f"k (images per station) must be at least 1, got {k!r}")
    return q * s * m / float(np.sqrt(k))


def relative_redundancy(redundancy_numbers) -> float:
    """Relative redundancy r̄ = r/m, the mean of the redundancy numbers r_i = (Q_vv P)_ii (Hanzl §5.4).

    Hanzl prints r̄ = r/n with n the number of unknowns (line 946); a share that lies in [0, 1] and
    is required to be ≥ 0.6 must be the mean r_i, i.e. r divided by the number of observations m.

    Parameters
    ----------
    redundancy_numbers : array_like (m,)
        r_i of every observation, each in [0, 1] (up to rounding).

    Returns
    -------
    float
        r̄ = Σ r_i / m.

    Raises
    ------
    InputError
        Empty, non-finite or outside [0, 1] (by more than 1e-9).

    References
    ----------
    Hanzl, Fotogrammetrie, Modul 01, §5.4 (seed 002 lines 942–946).

    Examples
    --------
    >>> relative_redundancy([0.5, 0.7, 0.9])
    0.7
    """
    if isinstance(redundancy_numbers, (str, bytes)) or redundancy_numbers is None:
        raise InputError("redundancy_numbers: give finite r_i in [0, 1], at least one")
    try:
        r = np.asarray(redundancy_numbers, dtype=float).ravel()
    except (TypeError, ValueError):
        raise InputError("redundancy_numbers: give finite r_i in [0, 1], at least one") from None
    if r.size == 0 or not np.all(np.isfinite(r)) or np.any(r < -1e-9) or np.any(r > 1 + 1e-9):
        raise InputError("redundancy_numbers: give finite r_i in [0, 1], at least one")
    return round(float(r.mean()), 15)
