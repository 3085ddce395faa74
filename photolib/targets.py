"""Automated monocular measurement of targets — Chapter 5, §5.11.

* The centroid of a target (5.11.1) after noise thresholds (5.11.2) (:func:`threshold_target`,
  :func:`centroid`): about 0.1 px on clean targets, biased by local disturbances (glare,
  shadows, Fig. 5.30).
* The circle fitted to the edge pixels, (5.11.3)–(5.11.4) (:func:`circle_fit`), by iterated least
  squares through the engine :mod:`photolib.lsq`, with the gradient weight (5.11.5)
  (:func:`gradient_weight`) and the robust weight (5.11.6) (:func:`robust_weight`) that
  suppresses local disturbances; the partial derivatives come from
  :func:`photolib.derivations.matching.circle_partials`.
* The Kadnichansky cross target (Figs. 5.32–5.34): the 7×7 detection mask with the corner means
  a₁…a₄ and the differences g₁…g₄ (:func:`kadnichansky_detect`), then edge points from gradient
  profiles, two fitted lines and their intersection (:func:`kadnichansky_center`).
* Correlation with one target image as template for all similar targets (:func:`find_targets`),
  built on :func:`photolib.matching.correlation_surface`.

Conventions as in :mod:`photolib.matching`: ``img[row, col]``, points ``(x, y) = (col, row)``,
pixel centres at integers, y down. The Kadnichansky mask layout (Fig. 5.33) is not legible in the
source: the corner groups are taken as b×b blocks (b = 2) in the mask corners, numbered clockwise
from the top-left, and the target as four quadrants with the top-right and bottom-left bright
(the sign pattern g₁ > G, g₂ < −G, g₃ > G, g₄ < −G of the text).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from . import _checks
from .errors import ConvergenceError, DegenerateGeometryError, InputError
from .matching import _array, _image, _point, correlation_surface

__all__ = ["threshold_target", "centroid", "gradient_weight", "robust_weight", "CircleFit", "circle_fit",
           "kadnichansky_detect", "CrossFit", "kadnichansky_center", "find_targets"]

_positive_int = _checks.integer


def _number(value, name, positive=False):
    if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)) \
            or not np.isfinite(value) or (positive and value <= 0):
        raise InputError(f"{name} must be a finite{' positive' if positive else ''} number, got {value!r}")
    return float(value)


def threshold_target(image, t_upper: float, t_lower: float):
    """Clip the grey values of a target image by the noise thresholds T₁, T₂ (5.11.2).

    f ← f_max − T₁ where f > f_max − T₁ (flattens the noisy top), f ← 0 where f < T₂ (removes the
    background), unchanged otherwise (the branch the print omits).

    Parameters
    ----------
    image : array_like (rows, cols)
        Grey values of a bright target on a dark background.
    t_upper : float
        T₁ ≥ 0, the upper noise threshold.
    t_lower : float
        T₂, the lower noise threshold.

    Returns
    -------
    ndarray
        The thresholded image.

    Raises
    ------
    InputError
        NaN/inf, non-2-D input, T₁ < 0, non-numeric thresholds.

    References
    ----------
    Chibunichev (2022), §5.11, eq. (5.11.2).

    Examples
    --------
    >>> threshold_target([[10., 50., 100.], [95., 30., 5.]], t_upper=10, t_lower=20).tolist()
    [[0.0, 50.0, 90.0], [90.0, 30.0, 0.0]]
    """
    f = _array(image, "image", ndim=2, min_size=1).copy()
    t1 = _number(t_upper, "t_upper")
    t2 = _number(t_lower, "t_lower")
    if t1 < 0:
        raise InputError("t_upper must be ≥ 0")
    top = f.max() - t1
    low = f < t2
    f[f > top] = top
    f[low] = 0.0
    return f


def centroid(image, dark: bool = False):
    """The centroid of the grey-value distribution (5.11.1): x_c = ΣΣx·f / ΣΣf, y_c = ΣΣy·f / ΣΣf.

    Parameters
    ----------
    image : array_like (rows, cols)
        Non-negative weights f (grey values, thresholded grey values (5.11.2), or gradients).
    dark : bool
        A dark target on a bright background: use f_max − f.

    Returns
    -------
    tuple of float
        (x_c, y_c), pixel centres at integers.

    Raises
    ------
    InputError
        NaN/inf, non-2-D input, negative values (a centroid needs non-negative weights).
    DegenerateGeometryError
        All weights zero (nothing to measure).

    References
    ----------
    Chibunichev (2022), §5.11, eq. (5.11.1).

    Examples
    --------
    >>> centroid([[0., 0., 0.], [0., 1., 3.], [0., 0., 0.]])
    (1.75, 1.0)
    """
    f = _array(image, "image", ndim=2, min_size=1)
    if dark:
        f = f.max() - f
    if np.any(f < 0):
        raise InputError("the centroid (5.11.1) needs non-negative weights; threshold the image first (5.11.2)")
    total = f.sum()
    if not total > 0:
        raise DegenerateGeometryError("all weights are zero: there is no target to measure")
    rows, cols = np.indices(f.shape)
    return float((cols * f).sum() / total), float((rows * f).sum() / total)


def gradient_weight(gradient, g_max=None):
    """The gradient weight (5.11.5) of edge pixels: P′ = exp(−(G_max/G − 1)).

    The print reads e^{−|G_max|/G_i − 1}; the form used equals 1 at the strongest edge pixel and
    differs from the literal reading by the constant factor e², which does not change a
    least-squares estimate. Pixels with G = 0 get weight 0.

    Parameters
    ----------
    gradient : array_like
        Gradient magnitudes G_i ≥ 0.
    g_max : float, optional
        G_max; default the largest G_i.

    Returns
    -------
    ndarray
        P′ in [0, 1] for G ≤ G_max.

    Raises
    ------
    InputError
        NaN/inf, negative gradients, empty input, g_max ≤ 0.

    References
    ----------
    Chibunichev (2022), §5.11, eq. (5.11.5).

    Examples
    --------
    >>> gradient_weight([10., 5., 0.]).round(4).tolist()
    [1.0, 0.3679, 0.0]
    """
    G = _array(gradient, "gradient", min_size=1)
    if np.any(G < 0):
        raise InputError("gradient magnitudes must be ≥ 0")
    gm = float(G.max()) if g_max is None else _number(g_max, "g_max", positive=True)
    if not gm > 0:
        raise InputError("the largest gradient is 0: no edge pixels")
    with np.errstate(divide="ignore"):
        return np.where(G > 0, np.exp(1.0 - gm / np.where(G > 0, G, 1.0)), 0.0)


def robust_weight(residuals, mu: float, iteration: int):
    """The robust weight (5.11.6) of the circle fit: 1 for |v| ≤ 2μ, else e^{−0.1(|v|/μ)^4} (N ≤ 3) or ^3.

    Parameters
    ----------
    residuals : array_like
        v_i of (5.11.4).
    mu : float
        μ, the r.m.s. error of unit weight (> 0).
    iteration : int
        N, the iteration number (≥ 1): exponent 4 for N ≤ 3, 3 afterwards.

    Returns
    -------
    ndarray
        P″ in (0, 1].

    Raises
    ------
    InputError
        NaN/inf, empty residuals, μ ≤ 0, N < 1.

    References
    ----------
    Chibunichev (2022), §5.11, eq. (5.11.6).

    Examples
    --------
    >>> robust_weight([0.5, 3.0], mu=1.0, iteration=1).round(4).tolist()
    [1.0, 0.0003]
    >>> robust_weight([0.5, 3.0], mu=1.0, iteration=4).round(4).tolist()
    [1.0, 0.0672]
    """
    v = np.abs(_array(residuals, "residuals", min_size=1))
    mu = _number(mu, "mu", positive=True)
    n = _positive_int(iteration, "iteration")
    e = 4 if n <= 3 else 3
    return np.where(v <= 2 * mu, 1.0, np.exp(-0.1 * (v / mu) ** e))


@dataclass
class CircleFit:
    """A circle fitted to the edge pixels of a target, (5.11.3)–(5.11.6).

    Attributes
    ----------
    x, y : float
        The centre (col, row).
    radius : float
        R, px.
    sigma_x, sigma_y, sigma_radius : float
        m_j = μ√Q_jj (1.8.8). Conservative: neighbouring edge pixels are not independent
        observations (their residuals are mostly the systematic width of the blurred edge band,
        shared by the whole ring), so μ measures that width rather than the noise; on a blurred
        noisy disc (R = 6.3 px, blur 0.8 px, noise σ = 2) m_x, m_y are ≈ 0.11 px while the actual
        centre error is ≈ 0.016 px r.m.s. (seeded simulation, 20 discs). Read them as upper bounds.
    mu : float
        μ with the effective redundancy Σp − 3.
    iterations : int
        Steps made.
    edge_points : ndarray (n, 2)
        The edge pixels used (x, y).
    weights : ndarray (n,)
        Their final weights P′·P″.

    References
    ----------
    Chibunichev (2022), §5.11, eqs. (5.11.3)–(5.11.6).

    Examples
    --------
    >>> CircleFit(3.0, 4.0, 2.0, 0.01, 0.01, 0.01, 0.1, 5, None, None).radius
    2.0
    """

    x: float
    y: float
    radius: float
    sigma_x: float
    sigma_y: float
    sigma_radius: float
    mu: float
    iterations: int
    edge_points: np.ndarray | None = field(default=None, repr=False)
    weights: np.ndarray | None = field(default=None, repr=False)


def _sobel(f):
    from scipy import ndimage as ndi
    return ndi.sobel(f, axis=1, mode="nearest") / 8.0, ndi.sobel(f, axis=0, mode="nearest") / 8.0


def circle_fit(image, center=None, radius=None, *, gradient_weights: bool = True, robust: bool = True,
               edge_fraction: float = 0.05, tol: float = 1e-5, max_iter: int = 30) -> CircleFit:
    """Fit the circle (5.11.3) to the edge pixels of a round target by iterated least squares (5.11.4).

    Edge pixels are those whose Sobel gradient magnitude G exceeds ``edge_fraction``·G_max. Each
    gives (x_i − x_c)² + (y_i − y_c)² − R² = 0 (5.11.3), linearised (5.11.4) with the sympy-derived
    a₁ = −2(x_i − x_c), a₂ = −2(y_i − y_c), a₃ = −2R. The start is the centroid of G (5.11.1) and
    the distance from it to the pixel of largest gradient (the book). Weights: P′ (5.11.5) from
    the gradient, times P″ (5.11.6) from the residuals of the previous step; μ uses the effective
    redundancy Σp − 3 (with n − 3 it shrinks as weights fall and the fit collapses). Each step is
    a solve of the engine :func:`photolib.lsq.solve_normal_equations`.

    Parameters
    ----------
    image : array_like (rows, cols)
        A patch containing one round target (bright or dark).
    center : (x, y), optional
        Start centre; default the centroid of the gradient magnitude.
    radius : float, optional
        Start radius; default the distance to the largest-gradient pixel.
    gradient_weights, robust : bool
        Use P′ (5.11.5) and P″ (5.11.6).
    edge_fraction : float
        Edge pixels: G > edge_fraction·G_max (0 < … < 1).
    tol : float
        Convergence when every correction is below ``tol`` px (after the 3 first steps if robust).
    max_iter : int
        Steps allowed.

    Returns
    -------
    CircleFit
        Centre, radius, their σ, μ, edge pixels and weights.

    Raises
    ------
    InputError
        NaN/inf, non-2-D input, bad options.
    DegenerateGeometryError
        No gradient (flat patch), fewer than 4 edge pixels, a singular normal matrix (edge pixels on
        a line).
    ConvergenceError
        No convergence in ``max_iter`` steps, or the radius collapses.

    References
    ----------
    Chibunichev (2022), §5.11, eqs. (5.11.1), (5.11.3)–(5.11.6).

    Examples
    --------
    >>> import numpy as np
    >>> y, x = (np.mgrid[0:40 * 8, 0:40 * 8] + 0.5) / 8 - 0.5
    >>> disc = (40 + 160 * ((x - 20.3) ** 2 + (y - 18.6) ** 2 <= 6.0 ** 2)).reshape(40, 8, 40, 8).mean((1, 3))
    >>> c = circle_fit(disc)
    >>> round(c.x, 1), round(c.y, 1), round(c.radius, 1)
    (20.3, 18.6, 6.0)
    """
    from .derivations.matching import circle_partials
    from .lsq import solve_normal_equations

    f = _image(image, "image")
    frac = _number(edge_fraction, "edge_fraction", positive=True)
    if frac >= 1:
        raise InputError("edge_fraction must be below 1")
    tol = _number(tol, "tol", positive=True)
    max_iter = _positive_int(max_iter, "max_iter")
    gx, gy = _sobel(f)
    G = np.hypot(gx, gy)
    gmax = float(G.max())
    if not gmax > 1e-12 * max(1.0, float(np.abs(f).max())):
        raise DegenerateGeometryError("the patch has no gradient: there is no target edge to fit")
    sel = G > frac * gmax
    ys, xs = np.nonzero(sel)
    if xs.size < 4:
        raise DegenerateGeometryError(f"only {xs.size} edge pixels: a circle needs more")
    xs, ys = xs.astype(float), ys.astype(float)
    P1 = gradient_weight(G[sel], gmax) if gradient_weights else np.ones(xs.size)
    if center is None:
        xc, yc = centroid(G)
    else:
        xc, yc = _point(center, "center")
    if radius is None:
        iy, ix = np.unravel_index(int(np.argmax(G)), G.shape)
        r = float(np.hypot(ix - xc, iy - yc))
    else:
        r = _number(radius, "radius", positive=True)
    if not r > 0:
        raise DegenerateGeometryError("the start radius is zero")
    fn = circle_partials()["numpy"]
    P2 = np.ones(xs.size)
    Q = np.eye(3)
    mu = 0.0
    for it in range(1, max_iter + 1):
        l, a1, a2, a3 = (np.broadcast_to(np.asarray(a, dtype=float), xs.shape) for a in fn(xc, yc, r, xs, ys))
        B = np.column_stack([a1, a2, a3])
        P = P1 * P2
        use = P > 1e-12                  # (5.11.6) can underflow to 0: such pixels carry no weight
        if use.sum() < 4:
            raise DegenerateGeometryError("fewer than 4 edge pixels keep a weight: no circle can be fitted")
        delta, Q = solve_normal_equations(B[use], l[use], weights=P[use], names=("x_c", "y_c", "R"))
        xc, yc, r = xc + delta[0], yc + delta[1], r + delta[2]
        if not (np.isfinite(r) and r > 0.5):
            raise ConvergenceError(f"the circle radius collapsed to {r:.3g} at step {it}")
        v = B @ delta + l
        red = P.sum() - 3.0
        mu = float(np.sqrt(max((P * v * v).sum(), 0.0) / red)) if red > 0 else float("nan")
        if robust and np.isfinite(mu) and mu > 0:
            P2 = robust_weight(v, mu, it)
        if np.all(np.abs(delta) < tol) and (not robust or it > 3):
            break
    else:
        raise ConvergenceError(f"the circle fit did not converge in {max_iter} steps")
    ang = np.arctan2(ys - yc, xs - xc)
    octant = np.floor((ang + np.pi) / (np.pi / 4)).astype(int) % 8
    share = np.bincount(octant, weights=P1 * P2, minlength=8) / max(float(np.sum(P1 * P2)), 1e-300)
    if np.count_nonzero(share > 0.02) < 6:
        raise DegenerateGeometryError("the weighted edge pixels do not surround the fitted centre (fewer than 6 of "
                                      "8 directions covered): the edge is not a closed round target")
    rows, cols = f.shape
    if not (0 <= xc <= cols - 1 and 0 <= yc <= rows - 1 and r < np.hypot(rows, cols) / 2):
        raise DegenerateGeometryError(f"the fitted circle (centre ({xc:.1f}, {yc:.1f}), R = {r:.1f}) does not "
                                      "lie in the patch: the edge pixels do not outline a round target")
    # residuals in (5.11.3) are in px²; m_j = μ·√Q_jj treats the edge pixels as independent, while
    # their residuals are mostly the systematic width of the blurred edge band: m_j is conservative
    std = mu * np.sqrt(np.diag(Q))
    return CircleFit(float(xc), float(yc), float(r), float(std[0]), float(std[1]), float(std[2]), mu, it,
                     np.column_stack([xs, ys]), P1 * P2)


def _block_means(f, b):
    c = np.zeros((f.shape[0] + 1, f.shape[1] + 1))
    c[1:, 1:] = np.cumsum(np.cumsum(f, 0), 1)
    return (c[b:, b:] - c[:-b, b:] - c[b:, :-b] + c[:-b, :-b]) / (b * b)


def kadnichansky_detect(image, threshold: float, *, mask: int = 7, block: int = 2):
    """Detect a Kadnichansky cross target with the 7×7 mask (§5.11, Figs. 5.32–5.33).

    At every mask position (step 1 px) a₁…a₄ are the mean grey values of the b×b corner groups
    (clockwise from the top-left) and g₁ = a₂ − a₁, g₂ = a₃ − a₂, g₃ = a₄ − a₃, g₄ = a₁ − a₄.
    A position is a candidate if g₁ > G, g₂ < −G, g₃ > G, g₄ < −G; the one with the largest
    S = g₁ − g₂ + g₃ − g₄ is the target centre to 1 px.

    Parameters
    ----------
    image : array_like (rows, cols)
        The image.
    threshold : float
        G > 0, the empirical grey-level threshold.
    mask : int
        Odd mask size (the book: 7).
    block : int
        b, the size of the corner groups (1 ≤ b ≤ mask // 2).

    Returns
    -------
    position : tuple of int
        (x, y) of the best mask centre.
    score : float
        Its S.

    Raises
    ------
    InputError
        NaN/inf, non-2-D input, image smaller than the mask, bad mask/block/threshold.
    DegenerateGeometryError
        No position passes the four tests (no target, or G too high).

    References
    ----------
    Chibunichev (2022), §5.11, Figs. 5.32–5.33.

    Examples
    --------
    >>> import numpy as np
    >>> img = np.full((15, 15), 40.0)
    >>> img[:8, 8:] = img[8:, :8] = 200.0        # top-right and bottom-left bright, centre (7.5, 7.5)
    >>> kadnichansky_detect(img, threshold=50)
    ((7, 7), 640.0)
    """
    f = _image(image, "image")
    G = _number(threshold, "threshold", positive=True)
    m = _positive_int(mask, "mask", minimum=3)
    b = _positive_int(block, "block")
    if m % 2 == 0 or b > m // 2:
        raise InputError(f"mask must be odd and block ≤ mask // 2, got mask={m}, block={b}")
    rows, cols = f.shape
    if rows < m or cols < m:
        raise InputError(f"the image ({cols}×{rows}) is smaller than the {m}×{m} mask")
    k = m // 2
    M = _block_means(f, b)                           # M[r, c]: mean of f[r:r+b, c:c+b]
    i = np.arange(k, rows - k)[:, None]
    j = np.arange(k, cols - k)[None, :]
    a1 = M[i - k, j - k]
    a2 = M[i - k, j + k - b + 1]
    a3 = M[i + k - b + 1, j + k - b + 1]
    a4 = M[i + k - b + 1, j - k]
    g1, g2, g3, g4 = a2 - a1, a3 - a2, a4 - a3, a1 - a4
    ok = (g1 > G) & (g2 < -G) & (g3 > G) & (g4 < -G)
    if not np.any(ok):
        raise DegenerateGeometryError(f"no position passes the mask tests with G = {G:g}: no target found")
    S = np.where(ok, g1 - g2 + g3 - g4, -np.inf)
    best = float(S.max())
    tied = np.argwhere(S >= best - 1e-9 * max(1.0, abs(best)))
    # a crisp target gives a plateau of equal S: take the tied position nearest to its middle
    r, c = tied[np.argmin(np.sum((tied - tied.mean(axis=0)) ** 2, axis=1))]
    return (int(c + k), int(r + k)), float(S[r, c])


@dataclass
class CrossFit:
    """The centre of a cross target: the intersection of the fitted lines A and B (§5.11).

    Attributes
    ----------
    x, y : float
        The centre (col, row).
    line_a : tuple of float
        (P_A, Q_A) of the near-horizontal line y = P_A·x + Q_A.
    line_b : tuple of float
        (P′_B, Q′_B) of the near-vertical line written x = P′_B·y + Q′_B (y = P·x + Q cannot
        represent a vertical line).
    points_a, points_b : ndarray (n, 2)
        The sub-pixel edge points (x, y) of each line.
    rms_a, rms_b : float
        R.m.s. residuals of the line fits, px.

    References
    ----------
    Chibunichev (2022), §5.11, Figs. 5.32–5.34.

    Examples
    --------
    >>> CrossFit(3.0, 4.0, (0.0, 4.0), (0.0, 3.0), None, None, 0.0, 0.0).x
    3.0
    """

    x: float
    y: float
    line_a: tuple
    line_b: tuple
    points_a: np.ndarray | None = field(default=None, repr=False)
    points_b: np.ndarray | None = field(default=None, repr=False)
    rms_a: float = 0.0
    rms_b: float = 0.0


def _peak(profile):
    k = int(np.argmax(profile[1:-1])) + 1
    a, b, c = profile[k - 1], profile[k], profile[k + 1]
    den = a - 2 * b + c
    if not den < 0:
        raise DegenerateGeometryError("an edge profile has no peak: the cross edges are not visible")
    return k + 0.5 * (a - c) / den                    # 3-point vertex (5.1.5)


def _line(s, t):
    """t = P·s + Q by least squares (engine); returns P, Q, r.m.s. residual."""
    from .lsq import solve_normal_equations
    B = np.column_stack([s, np.ones_like(s)])
    d, _ = solve_normal_equations(B, -t, names=("P", "Q"))
    return float(d[0]), float(d[1]), float(np.sqrt(np.mean((B @ d - t) ** 2)))


def kadnichansky_center(image, position, *, reach: int = 9, inner: int = 3, profile: int = 6) -> CrossFit:
    """Refine a cross-target centre: edge points by gradient profiles, two lines, their intersection.

    Around the detected position (:func:`kadnichansky_detect`), profiles of |g_y| across the
    near-horizontal edge (columns x₀ ± inner … ± reach) and of |g_x| across the near-vertical
    edge (rows y₀ ± inner … ± reach) give sub-pixel edge points (parabola vertex (5.1.5)); lines
    A: y = P_A x + Q_A and B: x = P′_B y + Q′_B are fitted by least squares and intersected.

    Parameters
    ----------
    image : array_like (rows, cols)
        The image.
    position : (x, y) of int
        The approximate centre (1 px).
    reach : int
        The farthest profile from the centre, px.
    inner : int
        The nearest profile (the centre itself is blurred), 1 ≤ inner ≤ reach − 2.
    profile : int
        Half-length of each profile, px (≥ 2).

    Returns
    -------
    CrossFit
        Centre, lines and edge points.

    Raises
    ------
    InputError
        NaN/inf, non-2-D image, a position whose profiles reach beyond the border, bad options.
    DegenerateGeometryError
        A profile without an edge peak, or parallel lines.

    References
    ----------
    Chibunichev (2022), §5.11, Figs. 5.32–5.34; eq. (5.1.5) for the profile peaks.

    Examples
    --------
    >>> import numpy as np
    >>> from scipy import ndimage as ndi
    >>> y, x = (np.mgrid[0:40 * 8, 0:40 * 8] + 0.5) / 8 - 0.5
    >>> hi = ((x > 20.3) & (y < 18.6)) | ((x < 20.3) & (y > 18.6))
    >>> img = ndi.gaussian_filter((40 + 160 * hi).reshape(40, 8, 40, 8).mean((1, 3)), 0.7)
    >>> c = kadnichansky_center(img, kadnichansky_detect(img, 40)[0])
    >>> round(c.x, 2), round(c.y, 2)
    (20.3, 18.6)
    """
    f = _image(image, "image")
    x0, y0 = _point(position, "position", integer=True)
    reach = _positive_int(reach, "reach", minimum=3)
    inner = _positive_int(inner, "inner")
    profile = _positive_int(profile, "profile", minimum=2)
    if inner > reach - 2:
        raise InputError("inner must be ≤ reach − 2 (at least 3 profiles per line... per side)")
    rows, cols = f.shape
    ext = max(reach, profile) + 1
    if x0 - ext < 0 or y0 - ext < 0 or x0 + ext >= cols or y0 + ext >= rows:
        raise InputError(f"the profiles around (x={x0}, y={y0}) reach beyond the image border")
    gx, gy = _sobel(f)
    offs = [d for d in range(-reach, reach + 1) if abs(d) >= inner]
    pa, pb = [], []
    for d in offs:
        prof = np.abs(gy[y0 - profile:y0 + profile + 1, x0 + d])
        pa.append((x0 + d, y0 - profile + _peak(prof)))
        prof = np.abs(gx[y0 + d, x0 - profile:x0 + profile + 1])
        pb.append((x0 - profile + _peak(prof), y0 + d))
    A, Bp = np.array(pa), np.array(pb)
    PA, QA, ra = _line(A[:, 0], A[:, 1])            # y = P_A x + Q_A
    PB, QB, rb = _line(Bp[:, 1], Bp[:, 0])          # x = P'_B y + Q'_B
    den = 1.0 - PA * PB
    if abs(den) < 1e-9:
        raise DegenerateGeometryError("the two edge lines are parallel")
    y = (PA * QB + QA) / den
    x = PB * y + QB
    return CrossFit(float(x), float(y), (PA, QA), (PB, QB), A, Bp, ra, rb)


def find_targets(image, template, threshold: float = 0.8, *, min_distance=None, subpixel: bool = True):
    """Find all repetitions of a target by correlation with one target image as template (§5.11).

    The correlation surface (5.1.2) of the template over the whole image
    (:func:`photolib.matching.correlation_surface`); local maxima at least ``min_distance`` apart
    with R ≥ ``threshold`` are targets; with ``subpixel`` each is refined by the parabolas
    (5.1.3)–(5.1.5) where its neighbours are defined.

    Parameters
    ----------
    image : array_like (rows, cols)
        The image with the targets.
    template : array_like (h, w)
        One target (its centre is the template centre ((w − 1)/2, (h − 1)/2)).
    threshold : float
        Minimum R, in (−1, 1].
    min_distance : int, optional
        Minimum spacing of targets, px; default half the smaller template side.
    subpixel : bool
        Refine the positions.

    Returns
    -------
    ndarray (k, 3)
        x, y, R of every target, sorted by decreasing R (k = 0 when none is found).

    Raises
    ------
    InputError
        NaN/inf, non-2-D arrays, a template larger than the image, a bad threshold.
    DegenerateGeometryError
        A textureless template.

    References
    ----------
    Chibunichev (2022), §5.11 (correlation method); §5.1, eqs. (5.1.2)–(5.1.5).

    Examples
    --------
    >>> import numpy as np
    >>> cross = np.zeros((7, 7)); cross[3, :] = cross[:, 3] = 1.0
    >>> img = np.zeros((30, 30)); img[5:12, 5:12] = cross; img[15:22, 20:27] = cross
    >>> find_targets(img, cross, 0.9)[:, :2].tolist()
    [[8.0, 8.0], [23.0, 18.0]]
    """
    from scipy import ndimage as ndi

    f = _image(image, "image")
    t = _array(template, "template", ndim=2, min_size=4)
    thr = _number(threshold, "threshold")
    if not -1 < thr <= 1:
        raise InputError("threshold must lie in (−1, 1]")
    if min_distance is None:
        md = max(1, min(t.shape) // 2)
    else:
        md = _positive_int(min_distance, "min_distance")
    R = correlation_surface(t, f)
    Rf = np.nan_to_num(R, nan=-2.0)
    peaks = np.argwhere((Rf == ndi.maximum_filter(Rf, size=2 * md + 1, mode="constant", cval=-2.0)) & (Rf >= thr))
    out = []
    for i, j in peaks:
        dx = dy = 0.0
        if subpixel:
            for axis in (0, 1):
                lo = (i - 1, j) if axis == 0 else (i, j - 1)
                hi = (i + 1, j) if axis == 0 else (i, j + 1)
                if min(lo) < 0 or hi[0] >= R.shape[0] or hi[1] >= R.shape[1]:
                    continue
                a, b, c = Rf[lo], Rf[i, j], Rf[hi]
                den = a - 2 * b + c
                if den < 0 and a > -2 and c > -2:
                    d = 0.5 * (a - c) / den
                    if axis == 0:
                        dy = d
                    else:
                        dx = d
        out.append((j + (t.shape[1] - 1) / 2 + dx, i + (t.shape[0] - 1) / 2 + dy, float(R[i, j])))
    res = np.array(out, dtype=float).reshape(-1, 3)
    return res[np.argsort(-res[:, 2], kind="stable")] if len(res) else res
