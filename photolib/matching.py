"""Area-based image matching — Chapter 5, §5.1–5.4 (correlation and least-squares matching).

* §5.1 — the correlation coefficient of two windows, plain (5.1.1) and mean-normalised (5.1.2)
  (:func:`correlation_coefficient`); the correlation surface of a template moved pixel by pixel
  over a search area (:func:`correlation_surface`, vectorised: one FFT correlation and integral
  images); the integer match with its sub-pixel vertex by parabolas (5.1.3)–(5.1.5)
  (:func:`parabola_vertex`) and the sharpness of the peak (:func:`peak_sharpness`, Fig. 5.5),
  combined in :func:`match_point`.
* Hanzl, Fotogrammetrie, Modul 01, §8.3 (seed 002 lines 1614–1644): the same correlation
  coefficient and LS shift, and the sub-pixel maximum of a 2-D quadratic fitted to the correlation
  surface (:func:`quadratic_peak`, with the corrected second normal equation).
* §5.2 — least-squares matching (LSM) with a shift only, (5.2.1)–(5.2.3) (:func:`lsm_shift`).
* §5.4 — LSM with an affine window (5.4.1)–(5.4.4) and a linear radiometric model
  (5.4.5)–(5.4.7) (:func:`lsm_affine`), with the a-posteriori σ of the shifts from the engine
  :mod:`photolib.lsq`. The printed partial derivatives (5.4.4) a₃…a₆ have the wrong sign (see
  :mod:`photolib.derivations.matching`); the library uses the derived Jacobian, and
  ``as_printed=True`` runs the book's coefficients, which make the iteration diverge.

Conventions. Images are numpy arrays ``img[row, col]``; a point is ``(x, y) = (col, row)`` with
pixel centres at integers (the raster system of §1.10 with the centre origin, y down). The
parallaxes are p = x₁ − x₂ and q = y₁ − y₂ as in §5.2, so the window of image 2 is at
x₂ = x₁ − p, y₂ = y₁ − q; q is counted downwards (the book's y axis points up). The book's LSM
solves δ = (AᵀA)⁻¹AᵀL (5.2.3) and moves the window by x₂ = x₁ − p + δ_p: its δ is *minus* the
correction of p. Here the engine's convention is used, B·δ + L = V, δ = −Q·BᵀL, p ← p + δ_p —
the same iteration. Windows touching the image border raise :class:`~photolib.errors.InputError`;
a textureless template raises :class:`~photolib.errors.DegenerateGeometryError`; a weak or
ambiguous correlation peak is flagged (``confident = False``), never reported as a sure match.
Image pyramids and coarse-to-fine search (§5.6) live in :mod:`photolib.epipolar`.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from . import _checks
from .errors import ConvergenceError, DegenerateGeometryError, InputError
from .lsq import solve_normal_equations

__all__ = ["correlation_coefficient", "correlation_surface", "parabola_vertex", "quadratic_peak", "peak_sharpness",
           "MatchResult", "match_point", "LSMResult", "lsm_shift", "lsm_affine"]

_REF = "Chibunichev (2022), §5.1, eqs. (5.1.1)–(5.1.5)"


# --- input checks ------------------------------------------------------------------------------

def _array(value, name, ndim=None, min_size=1):
    if isinstance(value, (str, bytes)) or value is None:
        raise InputError(f"{name} must be a numeric array, got {type(value).__name__}")
    try:
        arr = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise InputError(f"{name} must be a numeric array") from None
    if ndim is not None and arr.ndim not in np.atleast_1d(ndim):
        raise InputError(f"{name} must be a {ndim}-D array, got shape {arr.shape}")
    if arr.size < min_size:
        raise InputError(f"{name} is empty or too small (size {arr.size}, at least {min_size} needed)")
    if not np.all(np.isfinite(arr)):
        raise InputError(f"{name} contains NaN or inf pixels")
    return arr


def _image(value, name):
    return _array(value, name, ndim=2, min_size=4)


def _point(value, name, integer=False):
    if isinstance(value, (str, bytes)) or value is None:
        raise InputError(f"{name} must be (x, y)")
    try:
        arr = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise InputError(f"{name} must be two numbers (x, y)") from None
    if arr.shape != (2,) or not np.all(np.isfinite(arr)):
        raise InputError(f"{name} must be two finite numbers (x, y), got {value!r}")
    if integer:
        if not np.all(arr == np.round(arr)):
            raise InputError(f"{name} must be whole pixels (the centre of a window), got {value!r}")
        return int(arr[0]), int(arr[1])
    return float(arr[0]), float(arr[1])


_positive_int = _checks.integer


def _window(img, x, y, half, name):
    """The (2h+1)² window of ``img`` centred on the integer pixel (x, y); InputError at the border."""
    rows, cols = img.shape
    if x - half < 0 or y - half < 0 or x + half >= cols or y + half >= rows:
        raise InputError(f"the {2 * half + 1}×{2 * half + 1} window of {name} at (x={x}, y={y}) reaches "
                         f"beyond the image border ({cols}×{rows} px)")
    return img[y - half:y + half + 1, x - half:x + half + 1]


def _flat(arr, min_std):
    scale = max(1.0, float(np.max(np.abs(arr))))
    return float(np.std(arr)) <= max(min_std, 1e-9 * scale)


# --- §5.1: correlation -------------------------------------------------------------------------

def correlation_coefficient(a, b, centred: bool = True) -> float:
    """Correlation coefficient of two equal windows: (5.1.2) mean-normalised, or (5.1.1) plain.

    R is the cosine of the angle between the two windows taken as n-vectors (centred first for
    (5.1.2)). (5.1.2) lies in [−1, 1] (an inverted window gives −1) and is invariant to a linear
    change of brightness a → k₀ + k₁a (k₁ > 0); (5.1.1) lies in [0, 1] only for non-negative grey
    values.

    Parameters
    ----------
    a, b : array_like
        Two windows of the same shape (any dimension, at least 2 pixels).
    centred : bool
        True: (5.1.2) with the window means D′ removed; False: (5.1.1).

    Returns
    -------
    float
        R.

    Raises
    ------
    InputError
        Different shapes, NaN/inf, fewer than 2 pixels.
    DegenerateGeometryError
        A window without texture (zero variance for (5.1.2), all zero for (5.1.1)): R is undefined.

    References
    ----------
    Chibunichev (2022), §5.1, eqs. (5.1.1), (5.1.2).

    Examples
    --------
    >>> import numpy as np
    >>> a = np.array([[10., 20., 30.], [40., 10., 60.]])
    >>> correlation_coefficient(a, 3 * a + 40), correlation_coefficient(a, -a)
    (1.0, -1.0)
    >>> round(correlation_coefficient(a, 3 * a + 40, centred=False), 4)
    0.9877
    """
    a = _array(a, "window a", min_size=2)
    b = _array(b, "window b", min_size=2)
    if a.shape != b.shape:
        raise InputError(f"the windows differ in shape: {a.shape} and {b.shape}")
    if centred:
        a, b = a - a.mean(), b - b.mean()
    den = np.sqrt(np.sum(a * a) * np.sum(b * b))
    scale = max(1.0, float(np.max(np.abs(a))), float(np.max(np.abs(b))))
    if den <= 1e-12 * scale ** 2 * a.size:
        raise DegenerateGeometryError("a window has no texture (zero variance): the correlation coefficient "
                                      "is undefined")
    return float(np.clip(np.sum(a * b) / den, -1.0, 1.0))


def _box_sums(img, h, w):
    """Sums of every h×w window of ``img`` (valid positions), by an integral image."""
    c = np.zeros((img.shape[0] + 1, img.shape[1] + 1))
    c[1:, 1:] = np.cumsum(np.cumsum(img, axis=0), axis=1)
    return c[h:, w:] - c[:-h, w:] - c[h:, :-w] + c[:-h, :-w]


def correlation_surface(template, search, centred: bool = True):
    """R of the template at every position of the search area, (5.1.1)/(5.1.2) (Figs. 5.1–5.2).

    The template is moved pixel by pixel over the search area; ``R[i, j]`` is the coefficient
    of the template and ``search[i:i+h, j:j+w]``. Vectorised: the numerators come from one FFT
    correlation, the window sums from integral images, so that the cost does not grow with the
    template size. With ``centred=True`` this is OpenCV's ``TM_CCOEFF_NORMED`` and
    scikit-image's ``match_template``. Positions whose search window has no texture (R undefined)
    are NaN.

    Parameters
    ----------
    template : array_like (h, w)
        The reference matrix on image 1.
    search : array_like (H, W)
        The search area on image 2, H ≥ h and W ≥ w.
    centred : bool
        True: (5.1.2); False: (5.1.1).

    Returns
    -------
    ndarray (H − h + 1, W − w + 1)
        The correlation surface.

    Raises
    ------
    InputError
        Not 2-D, NaN/inf, a template larger than the search area.
    DegenerateGeometryError
        A template without texture.

    References
    ----------
    Chibunichev (2022), §5.1, eqs. (5.1.1), (5.1.2), Figs. 5.1–5.2.

    Examples
    --------
    >>> import numpy as np
    >>> rng = np.random.default_rng(0)
    >>> img = rng.normal(size=(20, 20))
    >>> R = correlation_surface(img[5:10, 8:15], img)
    >>> R.shape, [int(i) for i in np.unravel_index(np.nanargmax(R), R.shape)], round(float(np.nanmax(R)), 6)
    ((16, 14), [5, 8], 1.0)
    """
    t = _array(template, "template", ndim=2, min_size=2)
    s = _array(search, "search area", ndim=2, min_size=2)
    h, w = t.shape
    if s.shape[0] < h or s.shape[1] < w:
        raise InputError(f"the template {t.shape} is larger than the search area {s.shape}")
    n = t.size
    if centred:
        t = t - t.mean()
        s = s - s.mean()         # R (5.1.2) is invariant to it; keeps the window sums accurate
    tt = float(np.sum(t * t))
    scale = max(1.0, float(np.max(np.abs(t))))
    if tt <= 1e-18 * scale ** 2 * n or (centred and _flat(template, 0.0)):
        raise DegenerateGeometryError("the template has no texture: the correlation surface is undefined")
    num = _correlate_valid(s, t)
    s1 = _box_sums(s, h, w)
    s2 = _box_sums(s * s, h, w)
    ss = s2 - s1 * s1 / n if centred else s2
    sscale = max(1.0, float(np.max(np.abs(s)))) ** 2 * n
    with np.errstate(invalid="ignore", divide="ignore"):
        R = num / np.sqrt(tt * np.where(ss > 1e-10 * sscale, ss, np.nan))
    return np.clip(R, -1.0, 1.0)


def _correlate_valid(search, template):
    """Σ template·window for every window position ("valid" cross-correlation, no flip).

    Directly over the sliding windows when that is small, else by FFT (scipy.fft; scipy.signal is
    not imported: with SciPy ≥ 1.16 it pulls in scipy.stats and costs seconds on first use).
    """
    h, w = template.shape
    rows, cols = search.shape[0] - h + 1, search.shape[1] - w + 1
    if rows * cols * h * w <= 4_000_000:
        windows = np.lib.stride_tricks.sliding_window_view(search, template.shape)
        return np.einsum("ijkl,kl->ij", windows, template)
    from scipy import fft
    shape = [fft.next_fast_len(search.shape[0] + h - 1, real=True),
             fft.next_fast_len(search.shape[1] + w - 1, real=True)]
    product = fft.rfft2(search, shape) * fft.rfft2(template[::-1, ::-1], shape)
    full = fft.irfft2(product, shape)
    return full[h - 1:h - 1 + rows, w - 1:w - 1 + cols]


def parabola_vertex(values, offsets=None):
    """Least-squares parabola R = a₀ + a₁x + a₂x² (5.1.3)/(5.1.4) and its vertex x = −a₁/(2a₂) (5.1.5).

    Parameters
    ----------
    values : array_like (k,)
        R at the offsets, k ≥ 3.
    offsets : array_like (k,), optional
        Positions of the values; default −(k−1)/2 … (k−1)/2 (e.g. −1, 0, 1).

    Returns
    -------
    vertex : float
        The abscissa of the maximum, x_max (5.1.5).
    coefficients : ndarray (3,)
        a₀, a₁, a₂ (5.1.3).

    Raises
    ------
    InputError
        Fewer than 3 values, NaN/inf, lengths that differ, repeated offsets.
    DegenerateGeometryError
        a₂ ≥ 0 (no maximum: a flat or a valley-shaped profile), or the vertex lies outside the
        fitted offsets (an extrapolated, unreliable peak).

    References
    ----------
    Chibunichev (2022), §5.1, eqs. (5.1.3)–(5.1.5).

    Examples
    --------
    >>> x, a = parabola_vertex([0.80, 0.95, 0.90])
    >>> round(x, 4), a.round(4).tolist()
    (0.25, [0.95, 0.05, -0.1])
    """

    R = _array(values, "values", ndim=1, min_size=3)
    if offsets is None:
        x = np.arange(R.size, dtype=float) - (R.size - 1) / 2.0
    else:
        x = _array(offsets, "offsets", ndim=1, min_size=3)
        if x.size != R.size:
            raise InputError(f"{R.size} values but {x.size} offsets")
    if np.unique(x).size < 3:
        raise InputError("a parabola needs at least 3 distinct offsets")
    B = np.column_stack([np.ones_like(x), x, x * x])
    a, _ = solve_normal_equations(B, -R, names=("a0", "a1", "a2"))     # B·a − R = v  (5.1.4)
    if not a[2] < -1e-12 * max(1.0, float(np.max(np.abs(R)))):
        raise DegenerateGeometryError(f"the fitted parabola has no maximum (a2 = {a[2]:.3g} ≥ 0): "
                                      "a flat correlation profile")
    vertex = float(-a[1] / (2.0 * a[2]))
    if not (x.min() <= vertex <= x.max()):
        raise DegenerateGeometryError(f"the parabola vertex {vertex:.3f} lies outside the fitted offsets "
                                      f"[{x.min():g}, {x.max():g}]")
    return vertex, a


def quadratic_peak(values, offsets=None):
    """Sub-pixel maximum of a correlation surface by a 2-D quadratic, Hanzl §8.3.

    Fits r = a₀ + a₁x + a₂y + a₃x² + a₄y² + a₅xy by least squares (the engine
    :func:`photolib.lsq.solve_normal_equations`) and sets both partial derivatives to zero:

        0 = a₁ + 2a₃x + a₅y,    0 = a₂ + a₅x + 2a₄y

    (the text prints the second as a₂ + a₄x + 2a₅y, an erratum: see textbook/ch05_hanzl.toml).
    The 2-D counterpart of :func:`parabola_vertex`.

    Parameters
    ----------
    values : array_like (k, l)
        Correlation coefficients on a grid around the integer peak (e.g. 3×3), k, l ≥ 3;
        ``values[row, col]`` with y along the rows.
    offsets : (array_like (l,), array_like (k,)), optional
        x positions of the columns and y positions of the rows; default centred, −1, 0, 1 for 3×3.

    Returns
    -------
    peak : ndarray (2,)
        (x_MAX, y_MAX).
    coefficients : ndarray (6,)
        a₀ … a₅.

    Raises
    ------
    InputError
        Not a finite 2-D grid of at least 3×3, offsets of the wrong length or repeated.
    DegenerateGeometryError
        The fitted quadratic has no maximum (not negative definite: a ridge, a saddle or a valley),
        or the maximum lies outside the fitted grid.

    References
    ----------
    Hanzl, Fotogrammetrie, Modul 01, §8.3 (seed 002 lines 1636–1644); Chibunichev (2022), §5.1,
    eqs. (5.1.3)–(5.1.5) (the 1-D parabolas).

    Examples
    --------
    >>> x, y = np.meshgrid([-1.0, 0.0, 1.0], [-1.0, 0.0, 1.0])
    >>> r = 0.9 - 0.1 * (x - 0.2) ** 2 - 0.05 * (y + 0.3) ** 2 + 0.02 * (x - 0.2) * (y + 0.3)
    >>> peak, a = quadratic_peak(r)
    >>> peak.round(10).tolist()
    [0.2, -0.3]
    """

    R = _array(values, "values", ndim=2, min_size=3)
    if min(R.shape) < 3:
        raise InputError(f"values must be a grid of at least 3×3, got shape {R.shape}")
    if offsets is None:
        xs = np.arange(R.shape[1], dtype=float) - (R.shape[1] - 1) / 2.0
        ys = np.arange(R.shape[0], dtype=float) - (R.shape[0] - 1) / 2.0
    else:
        try:
            ox, oy = offsets
        except (TypeError, ValueError):
            raise InputError("offsets must be a pair (x positions of the columns, y positions of the rows)") from None
        xs = _array(ox, "x offsets", ndim=1, min_size=3)
        ys = _array(oy, "y offsets", ndim=1, min_size=3)
        if xs.size != R.shape[1] or ys.size != R.shape[0]:
            raise InputError(f"offsets of lengths {xs.size}, {ys.size} for a grid of shape {R.shape}")
        if np.unique(xs).size != xs.size or np.unique(ys).size != ys.size:
            raise InputError("offsets must not repeat")
    X, Y = np.meshgrid(xs, ys)
    x, y, r = X.ravel(), Y.ravel(), R.ravel()
    B = np.column_stack([np.ones_like(x), x, y, x * x, y * y, x * y])
    a, _ = solve_normal_equations(B, -r, names=("a0", "a1", "a2", "a3", "a4", "a5"))
    H = np.array([[2.0 * a[3], a[5]], [a[5], 2.0 * a[4]]])
    scale = max(1.0, float(np.max(np.abs(r))))
    if not (H[0, 0] < -1e-12 * scale and np.linalg.det(H) > 1e-24 * scale ** 2):
        raise DegenerateGeometryError("the fitted quadratic has no maximum (not negative definite): "
                                      "a ridge, saddle or flat correlation surface")
    peak = np.linalg.solve(H, -a[1:3])
    if not (xs.min() <= peak[0] <= xs.max() and ys.min() <= peak[1] <= ys.max()):
        raise DegenerateGeometryError(f"the quadratic's maximum ({peak[0]:.3f}, {peak[1]:.3f}) lies outside "
                                      "the fitted grid")
    return peak, a


def _curvatures(R, peak, radius):
    """−2a₂ of the parabolas through the peak along each axis (R per px²)."""
    out = []
    for axis in range(R.ndim):
        idx = list(peak)
        lo, hi = peak[axis] - radius, peak[axis] + radius
        if lo < 0 or hi >= R.shape[axis]:
            raise DegenerateGeometryError("the peak lies on the border of the correlation surface: its "
                                          "sharpness cannot be measured")
        idx[axis] = slice(lo, hi + 1)
        prof = R[tuple(idx)]
        if not np.all(np.isfinite(prof)):
            raise DegenerateGeometryError("the correlation surface is undefined next to the peak")
        x = np.arange(-radius, radius + 1, dtype=float)
        a2 = np.polyfit(x, prof, 2)[0]
        out.append(-2.0 * a2)
    return out


def peak_sharpness(surface, peak=None, radius: int = 1) -> float:
    """Steepness of a correlation peak: the smallest curvature −d²R/dx² across its axes (Fig. 5.5).

    The book judges a match not only by R_max but by how steeply R falls off around it (the
    angle φ of Fig. 5.5): a high but flat peak (low contrast, repetitive texture) is less
    reliable than a lower sharp one. Here the steepness is the curvature −2a₂ of the parabola
    (5.1.3) fitted through the peak along each axis, over ±``radius`` px, in R per px²; the
    smaller of the two is returned (a ridge is flat along one axis). Zero or negative values
    mean a flat peak.

    Parameters
    ----------
    surface : array_like (1-D or 2-D)
        A correlation profile or surface (NaN where undefined).
    peak : int or tuple of int, optional
        Index of the peak; default the maximum.
    radius : int
        Half-width of the parabola fit, ≥ 1.

    Returns
    -------
    float
        The curvature, R per px².

    Raises
    ------
    InputError
        Not 1-D/2-D, empty, all NaN, a peak index outside the surface.
    DegenerateGeometryError
        The peak lies within ``radius`` of the border or next to undefined values.

    References
    ----------
    Chibunichev (2022), §5.1, Fig. 5.5 and eq. (5.1.3).

    Examples
    --------
    >>> sharp = [0.2, 0.4, 0.9, 0.4, 0.2]
    >>> flat = [0.93, 0.95, 0.96, 0.95, 0.93]
    >>> round(peak_sharpness(sharp), 3), round(peak_sharpness(flat), 3)
    (1.0, 0.02)
    """
    if isinstance(surface, (str, bytes)) or surface is None:
        raise InputError("surface must be a numeric array")
    try:
        R = np.asarray(surface, dtype=float)
    except (TypeError, ValueError):
        raise InputError("surface must be a numeric array") from None
    if R.ndim not in (1, 2) or R.size == 0:
        raise InputError(f"surface must be a non-empty 1-D or 2-D array, got shape {R.shape}")
    if np.any(np.isinf(R)) or not np.any(np.isfinite(R)):
        raise InputError("the surface has inf values or no finite value")
    radius = _positive_int(radius, "radius")
    if peak is None:
        peak = np.unravel_index(int(np.nanargmax(R)), R.shape)
    peak = tuple(int(i) for i in np.atleast_1d(np.asarray(peak)))
    if len(peak) != R.ndim or any(not 0 <= i < n for i, n in zip(peak, R.shape)):
        raise InputError(f"peak {peak} is not an index of the surface {R.shape}")
    return float(min(_curvatures(R, peak, radius)))


@dataclass
class MatchResult:
    """The result of :func:`match_point`: the match on image 2 and how far to trust it.

    Attributes
    ----------
    x, y : float
        The sub-pixel position on image 2 (col, row).
    p, q : float
        The parallaxes x₁ − x₂, y₁ − y₂ (§5.2).
    integer : tuple of int
        The integer position (x, y) of the maximum of R.
    r_max : float
        The maximum correlation coefficient.
    sharpness : float
        :func:`peak_sharpness` at the maximum (NaN when the peak is on the border).
    confident : bool
        False when the peak is weak, flat, ambiguous or on the border of the search area.
    reason : str
        Why the match is not confident ("" when it is).
    surface : ndarray
        The correlation surface; ``surface[i, j]`` belongs to the candidate centre
        ``(x0 + j, y0 + i)`` with ``(x0, y0) = origin``.
    origin : tuple of int
        Image-2 position of ``surface[0, 0]``.

    References
    ----------
    Chibunichev (2022), §5.1, eqs. (5.1.2)–(5.1.5), Fig. 5.5.

    Examples
    --------
    >>> m = MatchResult(3.5, 2.0, 1.5, 0.0, (3, 2), 0.99, 0.5, True, "", None, (0, 0))
    >>> m.confident, m.p
    (True, 1.5)
    """

    x: float
    y: float
    p: float
    q: float
    integer: tuple
    r_max: float
    sharpness: float
    confident: bool
    reason: str
    surface: np.ndarray | None = field(default=None, repr=False)
    origin: tuple = (0, 0)


def _subpixel(R, i, j, method, fit_radius):
    """Sub-pixel offsets (dx, dy) of the peak at R[i, j]; raises DegenerateGeometryError if impossible."""
    k = fit_radius
    if i - k < 0 or j - k < 0 or i + k >= R.shape[0] or j + k >= R.shape[1]:
        raise DegenerateGeometryError("the peak lies on the border of the search area")
    if method == "parabola":                         # (5.1.3)–(5.1.5), separately along x and y
        dx, _ = parabola_vertex(R[i, j - k:j + k + 1])
        dy, _ = parabola_vertex(R[i - k:i + k + 1, j])
        return dx, dy
    # "paraboloid": R = c0 + c1 x + c2 y + c3 x² + c4 xy + c5 y² over the (2k+1)² neighbourhood
    patch = R[i - k:i + k + 1, j - k:j + k + 1]
    if not np.all(np.isfinite(patch)):
        raise DegenerateGeometryError("the correlation surface is undefined next to the peak")
    yy, xx = np.mgrid[-k:k + 1, -k:k + 1].astype(float)
    A = np.column_stack([np.ones(xx.size), xx.ravel(), yy.ravel(), xx.ravel() ** 2, (xx * yy).ravel(),
                         yy.ravel() ** 2])
    c = np.linalg.lstsq(A, patch.ravel(), rcond=None)[0]
    H = np.array([[2 * c[3], c[4]], [c[4], 2 * c[5]]])
    if not (np.linalg.det(H) > 0 and H[0, 0] < 0):
        raise DegenerateGeometryError("the fitted paraboloid has no maximum")
    d = np.linalg.solve(H, -c[1:3])
    if np.any(np.abs(d) > k):
        raise DegenerateGeometryError("the paraboloid vertex lies outside the fitted neighbourhood")
    return float(d[0]), float(d[1])


def match_point(left, right, point, approx=None, half_window: int = 7, search_radius: int = 10, *,
                centred: bool = True, subpixel: str | None = "parabola", fit_radius: int = 1,
                min_correlation: float = 0.7, min_sharpness: float = 0.02, min_std: float = 1e-6) -> MatchResult:
    """Find the point of image 2 corresponding to ``point`` of image 1 by correlation (§5.1).

    The (2h+1)² template around ``point`` is moved in 1-px steps over the search area around
    ``approx`` (± ``search_radius``); the maximum of R (5.1.2) gives the match to ±1 px, the
    parabolas (5.1.3)–(5.1.5) through the neighbouring R values give the sub-pixel vertex. The
    match is flagged (``confident = False``, with the reason) when R_max < ``min_correlation``,
    the peak is flatter than ``min_sharpness`` (Fig. 5.5), another position reaches the same R
    (repetitive texture), or the peak lies on the border of the search area (the true match may
    be outside); the integer position is then returned unrefined if refinement is impossible.

    Parameters
    ----------
    left, right : array_like (rows, cols)
        Images 1 and 2.
    point : (x, y) of int
        Template centre on image 1 (col, row).
    approx : (x, y) of int, optional
        Centre of the search area on image 2; default ``point``.
    half_window : int
        h: the template is (2h+1)×(2h+1) (the book: 5×5 … 21×21).
    search_radius : int
        The search area covers ``approx`` ± this many pixels.
    centred : bool
        (5.1.2) if True, else (5.1.1).
    subpixel : {"parabola", "paraboloid", None}
        The book's two 1-D parabolas (5.1.3)–(5.1.5); a 2-D quadratic through the (2k+1)²
        neighbourhood (less biased when the peak is off both grid lines); or integer only.
    fit_radius : int
        k: the parabolas use R within ±k px of the maximum (the book: 2–3 px; k = 1 interpolates).
    min_correlation, min_sharpness : float
        Confidence thresholds on R_max and on :func:`peak_sharpness`.
    min_std : float
        A template whose standard deviation is not above this is textureless.

    Returns
    -------
    MatchResult
        Position, parallaxes, R_max, sharpness, confidence and the surface.

    Raises
    ------
    InputError
        NaN/inf pixels, non-2-D images, non-integer centres, a template or search area that
        reaches beyond the image border, an unknown ``subpixel``.
    DegenerateGeometryError
        A textureless template, or a search area where R is nowhere defined.

    References
    ----------
    Chibunichev (2022), §5.1, eqs. (5.1.1)–(5.1.5), Figs. 5.1–5.5.

    Examples
    --------
    >>> import numpy as np
    >>> from scipy import ndimage as ndi
    >>> rng = np.random.default_rng(1)
    >>> left = ndi.gaussian_filter(rng.normal(size=(60, 60)), 1.5)
    >>> right = ndi.shift(left, (2, -3), order=3)           # x₂ = x₁ − 3, y₂ = y₁ + 2
    >>> m = match_point(left, right, (30, 30), search_radius=6)
    >>> m.integer, (round(m.p, 1), round(m.q, 1)), m.confident
    ((27, 32), (3.0, -2.0), True)
    """
    left = _image(left, "image 1")
    right = _image(right, "image 2")
    x1, y1 = _point(point, "point", integer=True)
    x2, y2 = _point(point if approx is None else approx, "approx", integer=True)
    h = _positive_int(half_window, "half_window")
    r = _positive_int(search_radius, "search_radius")
    k = _positive_int(fit_radius, "fit_radius")
    if subpixel not in ("parabola", "paraboloid", None):
        raise InputError(f"subpixel must be 'parabola', 'paraboloid' or None, got {subpixel!r}")
    for name, value in (("min_correlation", min_correlation), ("min_sharpness", min_sharpness),
                        ("min_std", min_std)):
        if not isinstance(value, (int, float, np.floating, np.integer)) or not np.isfinite(value):
            raise InputError(f"{name} must be a finite number, got {value!r}")
    template = _window(left, x1, y1, h, "image 1")
    search = _window(right, x2, y2, h + r, "image 2 (template plus search radius)")
    if _flat(template, min_std):
        raise DegenerateGeometryError(f"the template at (x={x1}, y={y1}) is textureless (standard deviation "
                                      f"{np.std(template):.3g}): no correlation match is possible")
    R = correlation_surface(template, search, centred=centred)
    if not np.any(np.isfinite(R)):
        raise DegenerateGeometryError("the search area is textureless: R is undefined everywhere")
    i, j = np.unravel_index(int(np.nanargmax(R)), R.shape)
    r_max = float(R[i, j])
    origin = (x2 - r, y2 - r)
    reasons = []
    ties = np.argwhere(np.nan_to_num(R, nan=-2.0) >= r_max - 1e-9 * max(1.0, abs(r_max)))
    if np.any(np.max(np.abs(ties - [i, j]), axis=1) > 1):
        reasons.append("ambiguous: R reaches its maximum at separate positions (repetitive texture)")
    try:
        sharp = float(min(_curvatures(R, (i, j), 1)))
    except DegenerateGeometryError:
        sharp = float("nan")
        reasons.append("the peak lies on the border of the search area")
    dx = dy = 0.0
    if subpixel is not None and np.isfinite(sharp):
        try:
            dx, dy = _subpixel(R, i, j, subpixel, k)
        except DegenerateGeometryError as exc:
            reasons.append(f"no sub-pixel vertex ({exc})")
    if r_max < min_correlation:
        reasons.append(f"weak correlation: R_max = {r_max:.3f} < {min_correlation}")
    if np.isfinite(sharp) and sharp < min_sharpness:
        reasons.append(f"flat peak: sharpness {sharp:.3g} < {min_sharpness}")
    x = origin[0] + j + dx
    y = origin[1] + i + dy
    return MatchResult(float(x), float(y), float(x1 - x), float(y1 - y), (int(origin[0] + j), int(origin[1] + i)),
                       r_max, sharp, not reasons, "; ".join(reasons), R, origin)


# --- §5.2 and §5.4: least-squares matching -------------------------------------------------------

@dataclass
class LSMResult:
    """The result of :func:`lsm_shift` / :func:`lsm_affine`.

    Attributes
    ----------
    x, y : float
        The matched position of the template centre on image 2.
    p, q : float
        The parallaxes x₁ − x₂, y₁ − y₂.
    params : dict
        Every unknown by name (p, q[, b1, b2, c1, c2][, k0, k1]).
    sigma_p, sigma_q : float
        A-posteriori standard errors m_p, m_q = μ√Q_jj (1.8.8), px.
    sigma0 : float
        μ, the r.m.s. grey-value residual (1.8.9).
    iterations : int
        Gauss–Newton steps.
    history : list of IterationRecord
        The approximation, correction and VᵀV of every step (from :mod:`photolib.lsq`).
    confident : bool
        False when m_p or m_q exceed ``max_sigma`` (weak texture in one direction).
    adjustment : Adjustment or None
        The engine's full result (Q, correlations, residuals).

    References
    ----------
    Chibunichev (2022), §5.2, eqs. (5.2.1)–(5.2.3); §5.4, eqs. (5.4.1)–(5.4.7).

    Examples
    --------
    >>> r = LSMResult(10.2, 5.0, -0.2, 0.0, {"p": -0.2, "q": 0.0}, 0.01, 0.01, 1.5, 3, [], True)
    >>> r.params["p"], r.confident
    (-0.2, True)
    """

    x: float
    y: float
    p: float
    q: float
    params: dict
    sigma_p: float
    sigma_q: float
    sigma0: float
    iterations: int
    history: list
    confident: bool
    adjustment: object = field(default=None, repr=False)


class _Resampler:
    """Image 2 and its gradient on a crop, sampled at real positions (bilinear or cubic spline)."""

    def __init__(self, img, x0, y0, reach, interpolation):
        from scipy import ndimage as ndi
        rows, cols = img.shape
        m = int(np.ceil(reach)) + 3
        self.c0, self.r0 = max(0, int(np.floor(x0)) - m), max(0, int(np.floor(y0)) - m)
        c1, r1 = min(cols, int(np.ceil(x0)) + m + 1), min(rows, int(np.ceil(y0)) + m + 1)
        crop = img[self.r0:r1, self.c0:c1]
        gy, gx = np.gradient(crop)                   # central differences: true derivatives per px
        self.order = 1 if interpolation == "bilinear" else 3
        if self.order == 3:
            crop, gx, gy = (ndi.spline_filter(a, order=3, mode="mirror") for a in (crop, gx, gy))
        self.planes = (crop, gx, gy)
        self.shape = crop.shape
        self._ndi = ndi

    def inside(self, X, Y):
        x, y = X - self.c0, Y - self.r0
        return bool(np.all((x >= 0) & (y >= 0) & (x <= self.shape[1] - 1) & (y <= self.shape[0] - 1)))

    def __call__(self, X, Y):
        coords = [Y - self.r0, X - self.c0]
        return [self._ndi.map_coordinates(a, coords, order=self.order, prefilter=False, mode="mirror")
                for a in self.planes]


def _lsm(left, right, point, approx, half_window, model, radiometric, interpolation, as_printed, tol,
         max_iter, max_sigma, min_std):
    from .derivations.matching import LSM_PARAMETERS, lsm_jacobian
    from .lsq import gauss_newton

    left = _image(left, "image 1")
    right = _image(right, "image 2")
    x1, y1 = _point(point, "point", integer=True)
    xa, ya = _point(point if approx is None else approx, "approx")
    h = _positive_int(half_window, "half_window", minimum=2)
    max_iter = _positive_int(max_iter, "max_iter")
    if interpolation not in ("bilinear", "cubic"):
        raise InputError(f"interpolation must be 'bilinear' or 'cubic', got {interpolation!r}")
    for name, value in (("tol", tol), ("max_sigma", max_sigma), ("min_std", min_std)):
        if not isinstance(value, (int, float, np.floating, np.integer)) or not np.isfinite(value) or value < 0:
            raise InputError(f"{name} must be a finite number ≥ 0, got {value!r}")
    if tol <= 0:
        raise InputError("tol must be positive")
    template = _window(left, x1, y1, h, "image 1")
    if _flat(template, min_std):
        raise DegenerateGeometryError(f"the template at (x={x1}, y={y1}) is textureless: least-squares "
                                      "matching has no gradient to work with")
    v, u = np.mgrid[-h:h + 1, -h:h + 1].astype(float)
    u, v, f1 = u.ravel(), v.ravel(), template.ravel()
    rows, cols = right.shape
    if xa - h < 0 or ya - h < 0 or xa + h > cols - 1 or ya + h > rows - 1:
        raise InputError(f"the {2 * h + 1}×{2 * h + 1} window at the approximation (x={xa:g}, y={ya:g}) reaches "
                         f"beyond the border of image 2 ({cols}×{rows} px)")
    sampler = _Resampler(right, xa, ya, 1.5 * h + 4, interpolation)
    jac = lsm_jacobian(as_printed=as_printed, model=model)
    names = ("p", "q") + (("b1", "b2", "c1", "c2") if model == "affine" else ()) + \
        (("k0", "k1") if radiometric else ())
    n_geo = 6 if model == "affine" else 2
    full0 = dict(zip(LSM_PARAMETERS, (x1 - xa, y1 - ya, 1.0, 0.0, 0.0, 1.0, 0.0, 1.0)))
    x0 = np.array([full0[nm] for nm in names])

    def unpack(x):
        d = dict(full0)
        d.update(zip(names, x))
        return d

    def warp(d):
        X = x1 + d["b1"] * u + d["b2"] * v - d["p"]          # (5.4.1), window-centred x₁, y₁
        Y = y1 + d["c1"] * u + d["c2"] * v - d["q"]
        return X, Y

    def linearize(x):
        d = unpack(x)
        X, Y = warp(d)
        if not sampler.inside(X, Y):
            raise ConvergenceError("the matching window left the image (or the search region) during the "
                                   "iteration: the iteration diverges or the approximation is too far off")
        f2, gx, gy = sampler(X, Y)
        L = d["k0"] + d["k1"] * f1 - f2                       # (5.4.5) at the approximation
        B = jac(u, v, gx, gy, f1, radiometric=radiometric)
        return B, L

    grad = np.mean(np.abs(np.gradient(template)))
    tols = [tol, tol] + [tol / h] * (n_geo - 2)
    if radiometric:
        tols += [tol * max(grad, 1e-12), tol * max(grad, 1e-12) / max(np.mean(np.abs(f1)), 1e-12)]
    history = []
    try:
        adj = gauss_newton(linearize, x0, tol=np.array(tols), max_iter=max_iter, names=names,
                           progress=history.append)
    except ConvergenceError as exc:
        if not exc.history:
            exc.history = list(history)
        if as_printed:
            raise ConvergenceError(f"least-squares matching with the printed coefficients (5.4.4) diverges: "
                                   f"{exc}", list(history)) from None
        raise
    d = unpack(adj.x)
    std = dict(zip(names, adj.std))
    X, Y = warp(d)
    x2, y2 = x1 - d["p"], y1 - d["q"]
    if not sampler.inside(X, Y):
        raise ConvergenceError("the converged window lies outside image 2", history)
    confident = bool(std["p"] <= max_sigma and std["q"] <= max_sigma)
    return LSMResult(float(x2), float(y2), float(d["p"]), float(d["q"]),
                     {nm: float(val) for nm, val in zip(names, adj.x)}, float(std["p"]), float(std["q"]),
                     float(adj.mu), int(adj.iterations), list(adj.history), confident, adj)


def lsm_shift(left, right, point, approx=None, half_window: int = 7, *, radiometric: bool = False,
              interpolation: str = "bilinear", tol: float = 1e-4, max_iter: int = 30,
              max_sigma: float = 0.2, min_std: float = 1e-6) -> LSMResult:
    """Least-squares matching with a shift only, (5.2.1)–(5.2.3).

    Minimises the sum of squared grey-value differences f₁(x₁, y₁) − f₂(x₁ − p, y₁ − q) over the
    template (5.2.1). Each step linearises with the gradient (g_x, g_y) of image 2 at the current
    window position (5.2.2), solves the normal equations (5.2.3) with the engine
    :func:`photolib.lsq.gauss_newton`, moves the window and resamples image 2 (bilinear, as in the
    book), until the corrections are below ``tol``. The book's δ of (5.2.3) is minus the
    engine's; both give the same iteration (module docstring).

    Parameters
    ----------
    left, right : array_like (rows, cols)
        Images 1 and 2.
    point : (x, y) of int
        Template centre on image 1.
    approx : (x, y), optional
        Approximate position on image 2 (within 1–2 px, e.g. from :func:`match_point`);
        default ``point``.
    half_window : int
        h: the window is (2h+1)² (≥ 2).
    radiometric : bool
        Also estimate k₀, k₁ of the linear radiometric model (5.4.5).
    interpolation : {"bilinear", "cubic"}
        Resampling of image 2 and its gradient.
    tol : float
        Convergence when |δp|, |δq| < tol px (and the other unknowns equivalently small).
    max_iter : int
        Steps allowed.
    max_sigma : float
        m_p or m_q above this (px) mark the result not confident.
    min_std : float
        Textureless-template threshold (standard deviation of the grey values).

    Returns
    -------
    LSMResult
        Position, parallaxes, σ of the shifts, iteration history.

    Raises
    ------
    InputError
        NaN/inf, non-2-D images, non-integer ``point``, windows beyond the border, bad options.
    DegenerateGeometryError
        A textureless template or a singular normal matrix (no gradient in some direction).
    ConvergenceError
        No convergence in ``max_iter`` steps or the window left the image (``history`` attached).

    References
    ----------
    Chibunichev (2022), §5.2, eqs. (5.2.1)–(5.2.3); engine §1.8, eqs. (1.8.5)–(1.8.10).

    Examples
    --------
    >>> import numpy as np
    >>> from scipy import ndimage as ndi
    >>> rng = np.random.default_rng(0)
    >>> left = ndi.gaussian_filter(rng.normal(size=(64, 64)), 2.0) * 100 + 120
    >>> right = ndi.shift(left, (-0.6, 1.3), order=3)        # x₂ = x₁ + 1.3, y₂ = y₁ − 0.6
    >>> r = lsm_shift(left, right, (32, 32), approx=(33, 31), half_window=7)
    >>> round(r.p, 2), round(r.q, 2), r.sigma_p < 0.05
    (-1.3, 0.6, True)
    """
    return _lsm(left, right, point, approx, half_window, "shift", bool(radiometric), interpolation, False,
                tol, max_iter, max_sigma, min_std)


def lsm_affine(left, right, point, approx=None, half_window: int = 10, *, radiometric: bool = True,
               interpolation: str = "bilinear", as_printed: bool = False, tol: float = 1e-4,
               max_iter: int = 30, max_sigma: float = 0.2, min_std: float = 1e-6) -> LSMResult:
    """Least-squares matching with an affine window and a linear radiometric model, (5.4.1)–(5.4.7).

    The window of image 2 is x₂ = b₁x₁ + b₂y₁ − p, y₂ = c₁x₁ + c₂y₁ − q (5.4.1) with x₁, y₁
    counted from the template centre (so that p, q are the parallaxes of the centre), and the
    grey values obey k₀ + k₁f₁ = f₂ (5.4.5): 8 unknowns (6 without radiometry). The correction
    equations (5.4.6) use the coefficients derived with sympy
    (:func:`photolib.derivations.matching.lsm_partials`): a₁ = g_x, a₂ = g_y, a₃ = −g_x·x₁,
    a₄ = −g_x·y₁, a₅ = −g_y·x₁, a₆ = −g_y·y₁, a₇ = 1, a₈ = f₁. The book prints a₃…a₆ with a
    plus sign (5.4.4): ``as_printed=True`` uses them, and the iteration then diverges — it
    raises :class:`~photolib.errors.ConvergenceError` with the iteration history attached
    (it can only "converge" when the start is already exact).

    Parameters
    ----------
    left, right : array_like (rows, cols)
        Images 1 and 2.
    point : (x, y) of int
        Template centre on image 1.
    approx : (x, y), optional
        Approximate position on image 2 (the book: within 1–2 px); default ``point``.
    half_window : int
        h: the window is (2h+1)² (≥ 2; more unknowns need larger windows than :func:`lsm_shift`).
    radiometric : bool
        Estimate k₀, k₁ (5.4.5)–(5.4.7).
    interpolation : {"bilinear", "cubic"}
        Resampling of image 2 and its gradient.
    as_printed : bool
        Use the printed partials (5.4.4) (diverges; for demonstration).
    tol, max_iter, max_sigma, min_std
        As in :func:`lsm_shift` (b, c converge when |δ|·h < tol).

    Returns
    -------
    LSMResult
        Position, parallaxes, all unknowns (``params``), σ of the shifts, iteration history.

    Raises
    ------
    InputError
        NaN/inf, non-2-D images, non-integer ``point``, windows beyond the border, bad options.
    DegenerateGeometryError
        A textureless template or a singular normal matrix.
    ConvergenceError
        No convergence, or the window left the image; always the case for ``as_printed=True``
        unless the approximation is exact (``history`` attached).

    References
    ----------
    Chibunichev (2022), §5.4, eqs. (5.4.1)–(5.4.7); engine §1.8, eqs. (1.8.5)–(1.8.10).

    Examples
    --------
    >>> import numpy as np
    >>> from scipy import ndimage as ndi
    >>> rng = np.random.default_rng(0)
    >>> left = ndi.gaussian_filter(rng.normal(size=(80, 80)), 2.0) * 100 + 120
    >>> yy, xx = np.mgrid[0:80, 0:80].astype(float)
    >>> # image 2: f₂(x₂, y₂) = 10 + 0.9·f₁ at x₁ = 40 + (x₂ − 41.5)/1.04, y₁ = y₂ + 0.5
    >>> right = 10 + 0.9 * ndi.map_coordinates(left, [yy + 0.5, 40 + (xx - 41.5) / 1.04], order=3)
    >>> r = lsm_affine(left, right, (40, 40), approx=(41, 40), half_window=10)
    >>> round(r.p, 2), round(r.q, 2), round(r.params["b1"], 2), round(r.params["k1"], 2)
    (-1.5, 0.5, 1.04, 0.9)
    >>> try:
    ...     lsm_affine(left, right, (40, 40), approx=(41, 40), half_window=10, as_printed=True)
    ... except ConvergenceError as exc:
    ...     print("diverges after", len(exc.history), "steps")
    diverges after ... steps
    """
    return _lsm(left, right, point, approx, half_window, "affine", bool(radiometric), interpolation,
                bool(as_printed), tol, max_iter, max_sigma, min_std)
