"""Terrain relief from a stereo pair by a Markov random field — the paper by Baikalova, Dubina,
Evtyushkin and Yushakov ("Algorithm for terrain relief reconstruction from a stereo pair").

The paper's pipeline, step by step (it is the classical pipeline of Chapter 5, §5.1 — area
correlation (5.1.1)/(5.1.2) — and Chapter 6, §6.4 — a dense parallax map regularised by a
smoothness term — with the smoothness imposed by a Gibbs random field instead of SGM's paths):

* the base shift of the scans (x₀, y₀) by the maximum of the correlation over the overlap:
  :func:`find_overlap_shift`; the number of candidate parallaxes: :func:`parallax_count`
  (with 0.0254 m per inch where the paper prints 0.245);
* the windowed correlation coefficient r(x₁, y₁, p) for every pixel and every candidate
  parallax, in the paper's computational form (its OCR repaired: a square root and two
  squares) — it equals Pearson's r — by box sums: :func:`correlation_coefficient`,
  :func:`correlation_volume`; the correlation-only estimate :func:`winner_takes_all`;
* the MRF relaxation: the Gibbs conditional P(x, y, p) ∝ exp(a·V_p + b·V_s) with V_p = r and
  the smoothness potential V_s = Σ over the 8 neighbours of (p − p′)², sampled by sequential
  (raster-scan) Gibbs sweeps from the correlation-only start, and the per-pixel maximum of the
  sampled marginals (the MPM estimate): :func:`gibbs_relaxation`, :func:`mrf_energy`. The paper
  calls a and b inverse temperatures; with its V_s, b must be **negative** (else roughness is
  rewarded);
* parallaxes → coordinates: relative orientation in the paper's base-oriented elements
  α′₁, χ′₁, α′₂, ω′₂, χ′₂ (printed "α′₁, ω′₁, …": ω′₁ is χ′₁), the base direction τ, v,
  the right image's angles and centre (steps 1–4): :func:`orient_pair`,
  :func:`direction_cosines` (1), :func:`direction_cosine_angles`, :func:`base_direction`;
  reduction to horizontal images (2) (step 5): :func:`reduce_to_horizontal`; intersection of
  horizontal images (step 6, without the printed "+ p" in Z): :func:`intersect_horizontal`;
  both from pixels and parallaxes: :func:`parallax_to_model`;
* absolute orientation of the free model (step 7): the convergence rotation
  :func:`convergence_rotation` and the 7-element similarity (3) from ≥ 2 full + 1 height
  control points with α = ζ, ω = ξ, χ = ν (printed "ω = ν, χ = ξ"): :func:`orient_model`.

The relative and absolute orientation adjustments are those of Chapter 2 (§2.7–§2.8 and
§2.10–§2.11: :func:`photolib.image_pair.relative_orientation`,
:func:`photolib.image_pair.absolute_orientation`); this module only converts their rotation
matrices to the paper's α–ω–χ angles, A(α, ω, χ) = R_Y(−α)·R_X(ω)·R_Z(χ) (1), which maps image
axes to model axes like every rotation of Chapter 1.

Conventions: images are 2-D float arrays indexed [row, column]; the left pixel (x₁, y₁) =
(column, row) is compared with the right pixel x₂ = x₁ + x₀ + p, y₂ = y₁ + y₀ (the paper's
sign: Middlebury's disparity d is p = −d). Image coordinates in mm with y up; angles in radians.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from . import _checks
from .camera import InteriorOrientation, as_points
from .errors import DegenerateGeometryError, InputError, PointBehindCameraError
from .rotation import _as_rotation, _numbers

__all__ = ["INCH", "correlation_coefficient", "correlation_volume", "find_overlap_shift", "parallax_count",
           "winner_takes_all", "mrf_energy", "gibbs_relaxation", "direction_cosines", "direction_cosine_angles",
           "base_direction", "orient_pair", "reduce_to_horizontal", "intersect_horizontal", "parallax_to_model",
           "convergence_rotation", "orient_model"]

INCH = 0.0254
"""Metres per inch: the constant of the parallax-count formula (printed as 0.245)."""

_FLAT = 1e-10      # window variance (relative to the image variance) below which a window is textureless


# =================================================================================================
# input checks
# =================================================================================================
_IMAGE_MESSAGES = {"type": "{name}: expected a 2-D array of brightnesses, got {type}",
                   "numeric": "{name}: expected a 2-D array of numbers",
                   "ndim": "{name}: expected a non-empty 2-D array, got shape {shape}",
                   "small": "{name}: expected a non-empty 2-D array, got shape {shape}"}


def _image(img, what: str) -> np.ndarray:
    return _checks.image(img, what, messages=_IMAGE_MESSAGES)


_window = _checks.odd_integer


def _integer_values(values, what: str) -> np.ndarray:
    arr = _numbers(values, what)
    if arr.ndim != 1 or arr.size == 0:
        raise InputError(f"{what}: expected a non-empty 1-D sequence, got shape {arr.shape}")
    if not np.all(arr == np.round(arr)):
        raise InputError(f"{what}: the candidate parallaxes must be whole pixels")
    if len(np.unique(arr)) != len(arr):
        raise InputError(f"{what}: the candidate parallaxes must be distinct")
    return arr.astype(np.int64)


def _shift(shift) -> tuple:
    arr = _numbers(shift, "shift")
    if arr.shape != (2,) or not np.all(arr == np.round(arr)):
        raise InputError(f"shift: expected two whole numbers (x₀, y₀), got {shift!r}")
    return int(arr[0]), int(arr[1])


def _positive(value, what: str) -> float:
    return _checks.positive_scalar(_numbers(value, what), value, what,
                                   message="{name} must be a positive number, got {value!r}")


# =================================================================================================
# correlation
# =================================================================================================
def correlation_coefficient(window1, window2) -> float:
    """The paper's correlation coefficient of two windows, r = (e − ab/n)/√((c − a²/n)(d − b²/n)).

    a = ΣS₁, b = ΣS₂, c = ΣS₁², d = ΣS₂², e = ΣS₁S₂ over the n pixels of the windows. The
    printed formula lost its exponents in the OCR ("·2" is a square, "·1/2" a square root);
    restored, it is Pearson's correlation coefficient (the identity is checked with sympy in
    ``textbook/ch06_mrf.toml``, entry ``mrf-correlation``).

    Parameters
    ----------
    window1, window2 : array_like
        Brightnesses of the two windows, of equal shape (any number of dimensions, ≥ 2 pixels).

    Returns
    -------
    float
        r in [−1, 1].

    Raises
    ------
    InputError
        Different shapes, fewer than 2 pixels, NaN/inf.
    DegenerateGeometryError
        A textureless (constant) window: r is undefined.

    References
    ----------
    Baikalova et al., the correlation formula (seed lines 18–32); Chibunichev (2022), §5.1,
    eqs. (5.1.1), (5.1.2).

    Examples
    --------
    >>> round(correlation_coefficient([[1, 2], [3, 4]], [[2, 4], [6, 9]]), 6)
    0.994377
    """
    w1 = _numbers(window1, "window 1").ravel()
    w2 = _numbers(window2, "window 2")
    if np.shape(window1) != w2.shape:
        raise InputError(f"the windows differ in shape: {np.shape(window1)} and {w2.shape}")
    w2 = w2.ravel()
    n = w1.size
    if n < 2:
        raise InputError("a window needs at least 2 pixels")
    m1, m2 = w1.mean(), w2.mean()          # centred first: the same r, without cancellation
    s1, s2 = w1 - m1, w2 - m2
    a, b, c, d, e = s1.sum(), s2.sum(), (s1 * s1).sum(), (s2 * s2).sum(), (s1 * s2).sum()
    v1, v2 = c - a * a / n, d - b * b / n
    scale = max(1.0, m1 * m1, m2 * m2)
    if v1 <= _FLAT * n * scale or v2 <= _FLAT * n * scale:
        raise DegenerateGeometryError("a textureless (constant) window: the correlation coefficient is undefined")
    return float(np.clip((e - a * b / n) / math.sqrt(v1 * v2), -1.0, 1.0))


def _box_sums(img: np.ndarray, win: int) -> np.ndarray:
    """Sums over the win×win window centred at each pixel (separable running sums); NaN off the border."""
    H, W = img.shape
    out = np.full((H, W), np.nan)
    if H < win or W < win:
        return out
    c = np.cumsum(img, axis=1)
    rows = c[:, win - 1:].copy()
    rows[:, 1:] -= c[:, :-win]
    c = np.cumsum(rows, axis=0)
    s = c[win - 1:].copy()
    s[1:] -= c[:-win]
    h = win // 2
    out[h:H - h, h:W - h] = s
    return out


def correlation_volume(left, right, parallaxes, window: int = 7, shift=(0, 0)) -> np.ndarray:
    """r(x₁, y₁, p) for every left pixel and every candidate parallax, by box sums.

    The window of the left pixel (x₁, y₁) is compared with the window of the right pixel
    x₂ = x₁ + x₀ + p, y₂ = y₁ + y₀. The five sums a, b, c, d, e of the paper are box sums over
    the window, computed for all pixels at once with running sums (one pass per parallax; no
    loop over pixels). The images are first centred and scaled by the left image's mean and
    standard deviation (r does not change) so that the sums do not lose digits.

    Parameters
    ----------
    left, right : (H, W), (H₂, W₂) arrays
        Brightnesses of the left and right images.
    parallaxes : sequence of int
        Candidate parallaxes p (pixels), distinct whole numbers.
    window : int
        Odd window size (the textbook's 5…21; the default 7).
    shift : (int, int)
        The base shift (x₀, y₀) of the scans, e.g. from :func:`find_overlap_shift`.

    Returns
    -------
    (P, H, W) float32 array
        r for each parallax; NaN where it is undefined: the window leaves the left or the right
        image (border windows), or one of the two windows is textureless.

    Raises
    ------
    InputError
        Not 2-D images, NaN/inf pixels, a bad window, non-integer or repeated parallaxes, a left
        image smaller than the window.

    References
    ----------
    Baikalova et al., the correlation formula and the parallax search (seed lines 16–40);
    Chibunichev (2022), §5.1, eqs. (5.1.1), (5.1.2); §6.4 (the cost volume).

    Examples
    --------
    >>> import numpy as np
    >>> rng = np.random.default_rng(0)
    >>> right = rng.random((20, 40))
    >>> left = right[:, 3:33]                   # the left pixel x is seen at x + 3 on the right
    >>> r = correlation_volume(left, right, [0, 1, 2, 3, 4], window=5)
    >>> int(np.nanargmax(r[:, 10, 15])), float(np.round(r[3, 10, 15], 6))
    (3, 1.0)
    """
    L = _image(left, "left image")
    R = _image(right, "right image")
    win = _window(window)
    P = _integer_values(parallaxes, "parallaxes")
    x0, y0 = _shift(shift)
    H, W = L.shape
    if H < win or W < win:
        raise InputError(f"the left image {L.shape} is smaller than the {win}×{win} window")
    mean, std = L.mean(), L.std()
    std = std if std > 0 else 1.0
    L = (L - mean) / std
    R = (R - mean) / std
    n = win * win
    a = _box_sums(L, win)
    c = _box_sums(L * L, win)
    var1 = c - a * a / n
    out = np.full((len(P), H, W), np.nan, dtype=np.float32)
    H2, W2 = R.shape
    rows = np.arange(H) + y0
    row_ok = (rows >= 0) & (rows < H2)
    for k, p in enumerate(P):
        cols = np.arange(W) + x0 + p
        col_ok = (cols >= 0) & (cols < W2)
        if not row_ok.any() or not col_ok.any():
            continue
        Rp = np.zeros((H, W))
        valid = np.zeros((H, W))
        r_idx, c_idx = np.flatnonzero(row_ok), np.flatnonzero(col_ok)
        Rp[np.ix_(r_idx, c_idx)] = R[np.ix_(rows[r_idx], cols[c_idx])]
        valid[np.ix_(r_idx, c_idx)] = 1.0
        full = _box_sums(valid, win) > n - 0.5
        b = _box_sums(Rp, win)
        d = _box_sums(Rp * Rp, win)
        e = _box_sums(L * Rp, win)
        var2 = d - b * b / n
        with np.errstate(invalid="ignore", divide="ignore"):
            r = (e - a * b / n) / np.sqrt(var1 * var2)
        ok = full & (var1 > _FLAT * n) & (var2 > _FLAT * n)
        out[k][ok] = np.clip(r[ok], -1.0, 1.0)
    return out


def _overlap_r(L, R, dx, dy, min_area):
    H, W = L.shape
    H2, W2 = R.shape
    x_lo, x_hi = max(0, -dx), min(W, W2 - dx)
    y_lo, y_hi = max(0, -dy), min(H, H2 - dy)
    if x_hi - x_lo < 2 or y_hi - y_lo < 2 or (x_hi - x_lo) * (y_hi - y_lo) < min_area:
        return np.nan
    a = L[y_lo:y_hi, x_lo:x_hi]
    b = R[y_lo + dy:y_hi + dy, x_lo + dx:x_hi + dx]
    a = a - a.mean()
    b = b - b.mean()
    den = math.sqrt(float((a * a).sum() * (b * b).sum()))
    if den <= _FLAT * a.size:
        return np.nan
    return float((a * b).sum() / den)


def _halve(img):
    H, W = (img.shape[0] // 2) * 2, (img.shape[1] // 2) * 2
    return 0.25 * (img[0:H:2, 0:W:2] + img[1:H:2, 0:W:2] + img[0:H:2, 1:W:2] + img[1:H:2, 1:W:2])


def find_overlap_shift(left, right, max_shift=None, min_overlap: float = 0.3) -> tuple:
    """The base shift (x₀, y₀) of two scans by the maximum correlation of their overlap.

    For every integer shift the right pixel (x + x₀, y + y₀) is paired with the left pixel
    (x, y), and Pearson's r of the overlapping parts is computed; the shift with the largest r
    wins. The search runs on an image pyramid (2×2 means): the whole range on the coarsest
    level, then ±2 pixels around the doubled estimate on every finer level.

    Parameters
    ----------
    left, right : 2-D arrays
        The two scans.
    max_shift : int or (int, int), optional
        Largest |x₀| and |y₀| searched; by default half the left image's width and height.
    min_overlap : float
        Smallest overlap, as a fraction of the left image's area, for a shift to count (small
        overlaps give high r by chance).

    Returns
    -------
    (int, int, float)
        x₀, y₀ and the correlation coefficient at the maximum.

    Raises
    ------
    InputError
        Not 2-D images, NaN/inf, a negative ``max_shift``, ``min_overlap`` outside (0, 1].
    DegenerateGeometryError
        No shift gives a defined correlation (textureless images or no overlap large enough).

    References
    ----------
    Baikalova et al., introduction: the overlap and the base found automatically by the maximum
    correlation coefficient (seed line 12); Chibunichev (2022), §5.1, eq. (5.1.1).

    Examples
    --------
    >>> import numpy as np
    >>> rng = np.random.default_rng(1)
    >>> scene = rng.random((80, 120))
    >>> find_overlap_shift(scene[5:65, 0:90], scene[0:60, 20:110])[:2]
    (-20, 5)
    """
    L = _image(left, "left image")
    R = _image(right, "right image")
    if not (isinstance(min_overlap, (int, float)) and 0 < min_overlap <= 1):
        raise InputError(f"min_overlap must be in (0, 1], got {min_overlap!r}")
    if max_shift is None:
        mx, my = L.shape[1] // 2, L.shape[0] // 2
    else:
        arr = _numbers(max_shift, "max_shift")
        arr = np.broadcast_to(arr, (2,)) if arr.ndim == 0 else arr
        if arr.shape != (2,) or np.any(arr < 0) or not np.all(arr == np.round(arr)):
            raise InputError(f"max_shift: expected non-negative whole numbers, got {max_shift!r}")
        mx, my = int(arr[0]), int(arr[1])
    pyramid = [(L, R)]
    while min(pyramid[-1][0].shape + pyramid[-1][1].shape) >= 128:
        pyramid.append((_halve(pyramid[-1][0]), _halve(pyramid[-1][1])))
    best = None
    for level in range(len(pyramid) - 1, -1, -1):
        Ll, Rl = pyramid[level]
        f = 2 ** level
        min_area = min_overlap * Ll.size
        if best is None:
            xs = range(-(mx // f), mx // f + 1)
            ys = range(-(my // f), my // f + 1)
        else:
            bx, by = 2 * best[0], 2 * best[1]
            xs = range(max(bx - 2, -(mx // f)), min(bx + 2, mx // f) + 1)
            ys = range(max(by - 2, -(my // f)), min(by + 2, my // f) + 1)
        scores = [(_overlap_r(Ll, Rl, dx, dy, min_area), dx, dy) for dy in ys for dx in xs]
        scores = [s for s in scores if np.isfinite(s[0])]
        if not scores:
            if best is None:
                raise DegenerateGeometryError("no shift gives a defined correlation: the images are textureless "
                                              "or no overlap reaches min_overlap")
            best = (2 * best[0], 2 * best[1], best[2])
            continue
        r, dx, dy = max(scores)
        best = (dx, dy, r)
    return int(best[0]), int(best[1]), float(best[2])


def parallax_count(h_max, h_min, base, dpi, flying_height, scale, constant: float = INCH) -> float:
    """Number of candidate parallaxes N = (H_max − H_min)·B·DPI/(H·M·0.0254).

    The photo base is b = B/M, a height difference Δh changes the x-parallax by b·Δh/H (first
    order), and one scanned pixel is 0.0254/DPI m. The paper prints the constant as 0.245
    (a garbled 0.0254), which makes N about ten times too small; ``constant=0.245`` reproduces
    the print.

    Parameters
    ----------
    h_max, h_min : float
        Highest and lowest expected terrain heights (m).
    base : float
        Air base B (m).
    dpi : float
        Scanner resolution (dots per inch).
    flying_height : float
        Flying height H above the terrain (m).
    scale : float
        Photo scale denominator M.
    constant : float
        Metres per inch (the default; the print has 0.245).

    Returns
    -------
    float
        N (pixels; round up for a search range).

    Raises
    ------
    InputError
        Non-positive base, dpi, height, scale or constant; h_max < h_min; NaN.

    References
    ----------
    Baikalova et al., the formula for N (seed lines 34–38); Chibunichev (2022), §2.13 (the
    parallax of a height difference).

    Examples
    --------
    >>> round(parallax_count(300.0, 100.0, 2160.0, 300, 2100.0, 30000), 1)
    81.0
    """
    hi = float(_numbers(h_max, "h_max"))
    lo = float(_numbers(h_min, "h_min"))
    if hi < lo:
        raise InputError(f"h_max ({hi}) is below h_min ({lo})")
    B = _positive(base, "base")
    D = _positive(dpi, "dpi")
    H = _positive(flying_height, "flying_height")
    M = _positive(scale, "scale")
    k = _positive(constant, "constant")
    return (hi - lo) * B * D / (H * M * k)


def _volume(r, parallaxes):
    try:
        vol = np.asarray(r, dtype=float)
    except (TypeError, ValueError):
        raise InputError("r: expected a (P, H, W) array of correlation coefficients") from None
    if vol.ndim != 3 or 0 in vol.shape:
        raise InputError(f"r: expected a non-empty (P, H, W) array, got shape {vol.shape}")
    if np.any(np.isinf(vol)):
        raise InputError("r contains inf")
    P = _integer_values(parallaxes, "parallaxes")
    if len(P) != vol.shape[0]:
        raise InputError(f"r has {vol.shape[0]} parallax layers but {len(P)} parallaxes were given")
    return vol, P


def winner_takes_all(r, parallaxes) -> tuple:
    """The correlation-only estimate: p̂ = argmax_p r(x, y, p) at every pixel.

    Parameters
    ----------
    r : (P, H, W) array
        Correlation volume (:func:`correlation_volume`); NaN = undefined.
    parallaxes : sequence of int
        The P candidate parallaxes.

    Returns
    -------
    (H, W) float array, (H, W) float array
        p̂ (NaN where no candidate is defined) and the maximum r there (NaN likewise). The paper
        calls pixels with maximum r ≤ 0.5 weakly correlated.

    Raises
    ------
    InputError
        Not a (P, H, W) array, inf, a parallax list of another length.

    References
    ----------
    Baikalova et al., the estimate by the maximum of the correlation function (seed line 40);
    Chibunichev (2022), §6.4 (winner-takes-all).

    Examples
    --------
    >>> import numpy as np
    >>> r = np.array([[[0.1]], [[0.9]], [[0.3]]])
    >>> p, rmax = winner_takes_all(r, [-1, 0, 1])
    >>> float(p[0, 0]), float(rmax[0, 0])
    (0.0, 0.9)
    """
    vol, P = _volume(r, parallaxes)
    defined = np.isfinite(vol).any(axis=0)
    idx = np.argmax(np.where(np.isfinite(vol), vol, -np.inf), axis=0)
    p = np.where(defined, P[idx].astype(float), np.nan)
    rmax = np.where(defined, np.take_along_axis(np.nan_to_num(vol, nan=-np.inf), idx[None], 0)[0], np.nan)
    return p, rmax


# =================================================================================================
# the MRF relaxation
# =================================================================================================
@dataclass(repr=False)
class MRFResult:
    """Result of :func:`gibbs_relaxation` (not in ``__all__``: a container).

    Attributes
    ----------
    parallax : (H, W) array
        The MPM estimate: at each pixel the parallax most often sampled after the burn-in.
    confidence : (H, W) array
        Its sampled marginal probability (share of the retained sweeps).
    marginals : (P, H, W) float32 array
        The sampled marginals of every candidate.
    initial : (H, W) array
        The start (correlation-only estimate unless given).
    energy : (sweeps + 1,) array
        :func:`mrf_energy` of the start and after every sweep.
    last : (H, W) array
        The last sampled map.
    """

    parallax: np.ndarray
    confidence: np.ndarray
    marginals: np.ndarray = field(repr=False)
    initial: np.ndarray = field(repr=False)
    energy: np.ndarray = field(repr=False)
    last: np.ndarray = field(repr=False)


def _data_term(vol):
    """V_p = r, with undefined candidates (NaN) set to −1, the least likely correlation."""
    return np.ascontiguousarray(np.where(np.isfinite(vol), vol, -1.0), dtype=np.float64)


def _labels_of(parallax, P, shape):
    arr = _numbers(parallax, "parallax map")
    if arr.shape != shape:
        raise InputError(f"parallax map: expected shape {shape}, got {arr.shape}")
    order = np.argsort(P)
    pos = np.searchsorted(P[order], arr)
    pos = np.clip(pos, 0, len(P) - 1)
    idx = order[pos]
    if not np.all(P[idx] == arr):
        raise InputError("parallax map: every value must be one of the candidate parallaxes")
    return np.ascontiguousarray(idx, dtype=np.int64)


def _check_ab(a, b, as_printed):
    a = float(_numbers(a, "a"))
    b = float(_numbers(b, "b"))
    if a < 0:
        raise InputError(f"a (the inverse temperature of the correlation potential) must be ≥ 0, got {a}")
    if b > 0 and not as_printed:
        raise InputError(f"b = {b} > 0 rewards rough parallax maps: with V_s = Σ(p − p′)² the smoothness "
                         "weight b must be negative (the paper's sign is an erratum); pass as_printed=True to "
                         "sample it anyway")
    return a, b


def mrf_energy(parallax, r, parallaxes, a: float = 10.0, b: float = -0.5, as_printed: bool = False) -> float:
    """Energy U(p) = −a·Σ_x V_p(x, p_x) − b·Σ_{x~y} (p_x − p_y)² of a parallax map.

    The joint Gibbs distribution whose conditionals are the paper's P(x, y, p) is
    exp(−U)/Z: each unordered pair of 8-neighbours x ~ y counted once, V_p = r (undefined r
    counted as −1). With b < 0 the smoothness term is a penalty; the relaxation lowers U.

    Parameters
    ----------
    parallax : (H, W) array
        A map whose values are candidate parallaxes.
    r : (P, H, W) array
        Correlation volume.
    parallaxes : sequence of int
        The candidate parallaxes (the layers of ``r``).
    a, b : float
        The inverse temperatures; a ≥ 0, b ≤ 0.
    as_printed : bool
        Allow b > 0 (the paper's sign taken literally).

    Returns
    -------
    float
        U.

    Raises
    ------
    InputError
        Shapes that do not agree, values that are not candidates, b > 0 without ``as_printed``.

    References
    ----------
    Baikalova et al., the Gibbs probability and V_s (seed lines 46–56).

    Examples
    --------
    >>> import numpy as np
    >>> r = np.zeros((2, 1, 2))
    >>> mrf_energy(np.array([[0, 1]]), r, [0, 1], a=1.0, b=-2.0)
    2.0
    """
    from . import _mrf_kernels
    vol, P = _volume(r, parallaxes)
    a, b = _check_ab(a, b, as_printed)
    labels = _labels_of(parallax, P, vol.shape[1:])
    return float(_mrf_kernels.energy(_data_term(vol), labels, P.astype(np.float64), a, b))


def gibbs_relaxation(r, parallaxes, a: float = 10.0, b: float = -0.5, sweeps: int = 40, burn_in: int = 10,
                     seed: int = 0, initial=None, as_printed: bool = False) -> MRFResult:
    """The paper's MRF relaxation: Gibbs sampling of P(x, y, p) and the per-pixel marginal maxima.

    P(x, y, p) = exp(a·V_p + b·V_s)/Σ_{pᵢ} exp(a·V_p(pᵢ) + b·V_s(pᵢ)) with V_p = r(x, y, p)
    (undefined r counted as −1) and V_s = Σ over the 8 neighbours of (p − p′)², p′ the current
    map. Scheme: sequential (raster-scan) Gibbs sampling — each pixel in turn draws its parallax
    from P given the current neighbours — for ``sweeps`` sweeps from the correlation-only map
    (the paper's suggested start), with numba's generator seeded by ``seed`` (a run is
    deterministic). After ``burn_in`` sweeps the samples are counted per pixel; the estimate is
    the most frequent value (maximum of the sampled marginals, MPM). At constant a, b the chain is
    stationary with a limit independent of the start, as the paper says.

    Parameters
    ----------
    r : (P, H, W) array
        Correlation volume (:func:`correlation_volume`).
    parallaxes : sequence of int
        The candidate parallaxes (layers of ``r``).
    a : float
        Inverse temperature of the correlation potential (≥ 0).
    b : float
        Weight of the smoothness potential, **negative** (the paper's sign is an erratum: b > 0
        rewards roughness); parallax units are pixels.
    sweeps, burn_in : int
        Number of sweeps, and of the first sweeps not counted (0 ≤ burn_in < sweeps).
    seed : int
        Seed of the sampler.
    initial : (H, W) array, optional
        Start map (values among ``parallaxes``); the winner-takes-all map by default.
    as_printed : bool
        Allow b > 0 (to show what the printed sign does).

    Returns
    -------
    MRFResult
        MPM map, its marginal probability, the marginals, the start, the energy per sweep
        (:func:`mrf_energy`) and the last sample.

    Raises
    ------
    InputError
        A bad volume or parallax list, a > 0 violated, b > 0 without ``as_printed``, bad sweep
        counts or seed, a start map of another shape or with non-candidate values.

    References
    ----------
    Baikalova et al., the MRF model (seed lines 42–60); Gimelfarb (1991), Pattern Recognition
    N.1, 39–49; Chibunichev (2022), §6.4 (a smoothness term on a parallax map).

    Examples
    --------
    >>> import numpy as np
    >>> r = np.full((3, 4, 4), 0.2)
    >>> r[1] = 0.9                                 # every pixel prefers parallax 0
    >>> r[2, 1, 1] = 1.0                           # one outlier prefers 1
    >>> res = gibbs_relaxation(r, [-1, 0, 1], a=10.0, b=-2.0, sweeps=30, burn_in=5)
    >>> res.parallax
    array([[0., 0., 0., 0.],
           [0., 0., 0., 0.],
           [0., 0., 0., 0.],
           [0., 0., 0., 0.]])
    """
    vol, P = _volume(r, parallaxes)
    a, b = _check_ab(a, b, as_printed)
    for name, value in (("sweeps", sweeps), ("burn_in", burn_in), ("seed", seed)):
        _checks.integer(value, name, 0, message="{name} must be a non-negative integer, got {value!r}")
    if not 0 <= burn_in < sweeps:
        raise InputError(f"need 0 ≤ burn_in < sweeps, got burn_in={burn_in}, sweeps={sweeps}")
    data = _data_term(vol)
    if initial is None:
        labels = np.ascontiguousarray(np.argmax(data, axis=0), dtype=np.int64)
    else:
        labels = _labels_of(initial, P, vol.shape[1:])
    from . import _mrf_kernels                      # numba, compiled on first use
    values = P.astype(np.float64)
    start = values[labels]
    counts = np.zeros(data.shape, dtype=np.int32)
    energies = np.zeros(sweeps)
    e0 = _mrf_kernels.energy(data, labels, values, a, b)
    labels = _mrf_kernels.gibbs_sweeps(data, labels.copy(), values, a, b, int(sweeps), int(burn_in),
                                       int(seed), counts, energies)
    kept = sweeps - burn_in
    best = np.argmax(counts, axis=0)
    marg = (counts / kept).astype(np.float32)
    conf = np.take_along_axis(marg, best[None], 0)[0].astype(float)
    return MRFResult(values[best], conf, marg, start, np.concatenate([[e0], energies]), values[labels])


# =================================================================================================
# geometry: steps 1–6
# =================================================================================================
def direction_cosines(alpha, omega, chi) -> np.ndarray:
    """The paper's direction-cosine matrix (1), A(α, ω, χ) = R_Y(−α)·R_X(ω)·R_Z(χ).

    a₁ = cos α cos χ − sin α sin ω sin χ, a₂ = −cos α sin χ − sin α sin ω cos χ,
    a₃ = −sin α cos ω; b₁ = cos ω sin χ, b₂ = cos ω cos χ, b₃ = −sin ω;
    c₁ = sin α cos χ + cos α sin ω sin χ, c₂ = −sin α sin χ + cos α sin ω cos χ, c₃ = cos α cos ω.
    It maps image axes to model axes ((2): X′ = A·(x, y, −f)); R_Y, R_X, R_Z are the
    counter-clockwise rotations of Chapter 1 (:func:`photolib.rotation.rot_y` …), so the paper's
    α turns the other way round than the book's.

    Parameters
    ----------
    alpha, omega, chi : float
        Angles (rad).

    Returns
    -------
    (3, 3) array
        Rows (a₁ a₂ a₃), (b₁ b₂ b₃), (c₁ c₂ c₃).

    Raises
    ------
    InputError
        NaN, inf or non-numbers.

    References
    ----------
    Baikalova et al., eq. (1) (seed lines 70–74); Chibunichev (2022), §1.3, eqs. (1.3.1)–(1.3.5).

    Examples
    --------
    >>> direction_cosines(0.0, 0.0, 0.0)
    array([[1., 0., 0.],
           [0., 1., 0.],
           [0., 0., 1.]])
    """
    al, om, ch = (float(_numbers(v, name)) for v, name in ((alpha, "alpha"), (omega, "omega"), (chi, "chi")))
    sa, ca, so, co, sc, cc = math.sin(al), math.cos(al), math.sin(om), math.cos(om), math.sin(ch), math.cos(ch)
    return np.array([[ca * cc - sa * so * sc, -ca * sc - sa * so * cc, -sa * co],
                     [co * sc, co * cc, -so],
                     [sa * cc + ca * so * sc, -sa * sc + ca * so * cc, ca * co]]) + 0.0


def direction_cosine_angles(A) -> tuple:
    """α, ω, χ of a rotation matrix in the paper's sequence (1): ω = −asin b₃, α = atan2(−a₃, c₃), χ = atan2(b₁, b₂).

    Parameters
    ----------
    A : (3, 3) array
        A rotation matrix.

    Returns
    -------
    (float, float, float)
        α, ω, χ (rad), with |ω| ≤ π/2.

    Raises
    ------
    InputError
        Not a 3×3 rotation, NaN.
    DegenerateGeometryError
        ω = ±90° (gimbal lock): α and χ are not separable.

    References
    ----------
    Baikalova et al., eq. (1) (seed lines 70–74); Chibunichev (2022), §1.3, eq. (1.3.3).

    Examples
    --------
    >>> [round(v, 6) for v in direction_cosine_angles(direction_cosines(0.1, -0.2, 0.3))]
    [0.1, -0.2, 0.3]
    """
    A = _as_rotation(A, "A")
    if A.shape != (3, 3):
        raise InputError(f"A: expected one 3×3 rotation, got shape {A.shape}")
    if abs(A[1, 2]) > 1 - 1e-12:
        raise DegenerateGeometryError("ω = ±90°: α and χ cannot be separated in the sequence α–ω–χ")
    omega = math.asin(-A[1, 2])
    alpha = math.atan2(-A[0, 2], A[2, 2])
    chi = math.atan2(A[1, 0], A[1, 1])
    return alpha, omega, chi


def base_direction(A_left, alpha1, chi1) -> tuple:
    """Step 2: τ and v of the base from A(τ, V) = A(α₁, ω₁, χ₁)·A(α′₁, 0, χ′₁).

    Convention (the paper states none; this one makes steps 2 and 3 consistent as printed):
    A(α′₁, 0, χ′₁) maps the base frame into the left image's axes, so its first column
    (cos α′₁ cos χ′₁, sin χ′₁, sin α′₁ cos χ′₁) is the base direction seen from the left image,
    and the first column of A(τ, V) is the base direction in the model frame,
    (cos v cos τ, cos v sin τ, sin v) as in step 4.

    Parameters
    ----------
    A_left : (3, 3) array
        A(α₁, ω₁, χ₁) of the left image (the identity in the paper's step 1).
    alpha1, chi1 : float
        α′₁, χ′₁ (rad).

    Returns
    -------
    (float, float)
        τ (direction angle) and v (inclination), rad.

    Raises
    ------
    InputError
        A_left not a rotation, NaN.

    References
    ----------
    Baikalova et al., steps 2 and 4 (seed lines 66–94).

    Examples
    --------
    >>> [round(v, 6) for v in base_direction(direction_cosines(0, 0, 0), 0.0, 0.1)]
    [0.1, 0.0]
    """
    A1 = _as_rotation(A_left, "A_left")
    if A1.shape != (3, 3):
        raise InputError(f"A_left: expected one 3×3 rotation, got shape {A1.shape}")
    col = (A1 @ direction_cosines(alpha1, 0.0, chi1))[:, 0]
    return math.atan2(col[1], col[0]), math.asin(max(-1.0, min(1.0, col[2])))


@dataclass(repr=False)
class PairOrientation:
    """Orientation of a pair in the paper's elements (steps 1–4), from :func:`orient_pair`.

    Attributes
    ----------
    alpha1, chi1, alpha2, omega2, chi2 : float
        The relative orientation in the base-oriented system (rad).
    tau, v : float
        Direction angle and inclination of the base.
    A1, A2 : (3, 3) arrays
        A(α₁, ω₁, χ₁) and A(α₂, ω₂, χ₂): image → model.
    S1, S2 : (3,) arrays
        Projection centres.
    f : float
        Principal distance (mm).
    relative : RelativeOrientation
        The Chapter-2 adjustment the elements come from.
    """

    alpha1: float
    chi1: float
    alpha2: float
    omega2: float
    chi2: float
    tau: float
    v: float
    A1: np.ndarray
    A2: np.ndarray
    S1: np.ndarray
    S2: np.ndarray
    f: float
    relative: object = None

    @property
    def base(self) -> np.ndarray:
        """(B_x, B_y, B_z) = S₂ − S₁."""
        return self.S2 - self.S1


def orient_pair(xy1, xy2, io: InteriorOrientation, base_length: float = 1.0, left_angles=(0.0, 0.0, 0.0),
                left_centre=(0.0, 0.0, 0.0)) -> PairOrientation:
    """Steps 1–4: relative orientation, base direction, the right image's angles and centre.

    Step 1 is the coplanarity adjustment of Chapter 2 in the independent (base-oriented) system
    (:func:`photolib.image_pair.relative_orientation`); its result is re-expressed in the
    paper's elements: α′₁, χ′₁ with A(α′₁, 0, χ′₁) mapping the base frame into the left image
    (first column = base direction), and α′₂, ω′₂, χ′₂ of the right image in that base frame
    (printed "α′₁, ω′₁, α′₂, ω′₂, χ′₂": the base system has ω′₁ ≡ 0 and needs χ′₁). Step 2:
    :func:`base_direction`; step 3: A₂ = A(τ, V)·A(α′₂, ω′₂, χ′₂); step 4:
    S₂ = S₁ + B·(cos v cos τ, cos v sin τ, sin v).

    Parameters
    ----------
    xy1, xy2 : (n, 2) arrays
        Corresponding image coordinates (mm), n ≥ 5, not collinear.
    io : InteriorOrientation
        The camera of both images.
    base_length : float
        B (the free model's scale), positive.
    left_angles : (α₁, ω₁, χ₁)
        Angles of the left image (0 in the paper's step 1).
    left_centre : (3,) array
        S₁.

    Returns
    -------
    PairOrientation
        The paper's elements, τ, v, both rotations and centres.

    Raises
    ------
    InputError
        Too few points, wrong shapes, NaN, non-positive base length, not an InteriorOrientation.
    DegenerateGeometryError
        Collinear points, a zero base (from Chapter 2), ω′₂ = ±90°.
    PointBehindCameraError, ConvergenceError
        From the relative orientation adjustment.

    References
    ----------
    Baikalova et al., steps 1–4 (seed lines 64–96); Chibunichev (2022), §2.7–§2.8,
    eqs. (2.7.4), (2.8.1).

    Examples
    --------
    >>> import numpy as np
    >>> from photolib.synthetic import stereo_pair
    >>> pair = stereo_pair(12, seed=0, angle_spread_deg=2.0)
    >>> po = orient_pair(pair.xy1, pair.xy2, pair.io, base_length=400.0)
    >>> truth = pair.eo1.matrix.T @ (pair.centres[1] - pair.centres[0])
    >>> bool(np.allclose(po.base, truth, atol=1e-6))
    True
    """
    from .image_pair import relative_orientation
    if not isinstance(io, InteriorOrientation):
        raise InputError(f"io must be an InteriorOrientation, got {type(io).__name__}")
    B = _positive(base_length, "base_length")
    S1 = _numbers(left_centre, "left_centre")
    if S1.shape != (3,):
        raise InputError(f"left_centre: expected 3 coordinates, got shape {S1.shape}")
    ang = _numbers(left_angles, "left_angles")
    if ang.shape != (3,):
        raise InputError(f"left_angles: expected (α₁, ω₁, χ₁), got shape {ang.shape}")
    ro = relative_orientation(xy1, xy2, io, system="independent", order="wak")
    R21 = ro.A1.T @ ro.A2                          # image 2 → image 1 axes (gauge-free)
    b1 = ro.A1.T @ ro.base_direction               # the base in image-1 axes
    alpha1 = math.atan2(b1[2], b1[0])
    chi1 = math.asin(max(-1.0, min(1.0, b1[1])))
    M = direction_cosines(alpha1, 0.0, chi1)       # base frame → image 1
    alpha2, omega2, chi2 = direction_cosine_angles(M.T @ R21)
    A1 = direction_cosines(*ang)
    tau, v = base_direction(A1, alpha1, chi1)
    A2 = A1 @ M @ direction_cosines(alpha2, omega2, chi2)
    S2 = S1 + B * np.array([math.cos(v) * math.cos(tau), math.cos(v) * math.sin(tau), math.sin(v)])
    return PairOrientation(alpha1, chi1, alpha2, omega2, chi2, tau, v, A1, A2, S1.astype(float), S2, float(io.f), ro)


def reduce_to_horizontal(xy, f, A) -> np.ndarray:
    """Step 5, (2): coordinates on the horizontal image, x₀ = −f·X′/Z′, y₀ = −f·Y′/Z′.

    (X′, Y′, Z′) = A·(x, y, −f): X′ = x a₁ + y a₂ − f a₃, Y′ = x b₁ + y b₂ − f b₃,
    Z′ = x c₁ + y c₂ − f c₃.

    Parameters
    ----------
    xy : (n, 2) array
        Image coordinates relative to the principal point (mm).
    f : float
        Principal distance (mm), positive.
    A : (3, 3) array
        A(α, ω, χ) of the image.

    Returns
    -------
    (n, 2) array
        x₀, y₀.

    Raises
    ------
    InputError
        Wrong shapes, NaN, f ≤ 0, A not a rotation.
    PointBehindCameraError
        A ray that does not point downwards (Z′ ≥ 0): no horizontal image point.

    References
    ----------
    Baikalova et al., step 5, eq. (2) (seed lines 98–118); Chibunichev (2022), §1.6.

    Examples
    --------
    >>> reduce_to_horizontal([[1.0, 2.0]], 100.0, direction_cosines(0, 0, 0))
    array([[1., 2.]])
    """
    P = as_points(xy, 2, "image coordinates")
    fv = _positive(f, "f")
    A = _as_rotation(A, "A")
    if A.shape != (3, 3):
        raise InputError(f"A: expected one 3×3 rotation, got shape {A.shape}")
    rays = np.column_stack([P, np.full(len(P), -fv)]) @ A.T
    bad = rays[:, 2] >= -1e-12 * fv
    if np.any(bad):
        raise PointBehindCameraError("a ray does not point below the horizon (Z′ ≥ 0): no horizontal image point",
                                     points=np.flatnonzero(bad))
    return -fv * rays[:, :2] / rays[:, 2:3]


def intersect_horizontal(xy10, xy20, base, f, centre=(0.0, 0.0, 0.0)) -> np.ndarray:
    """Step 6: X = X_S1 + N·x₁₀, Y = Y_S1 + N·y₁₀, Z = Z_S1 − f·N, N = (B_x + x₂₀B_z/f)/(x₁₀ − x₂₀).

    The intersection of the two rays of horizontal images in the X–Z plane of the left ray (the
    y-parallax is not used). The paper prints Z = Z_S1 + p + dZ; the "+ p" has no geometric
    basis (the parallax enters through x₂₀) and is left out (``textbook/ch06_mrf.toml``,
    ``mrf-step6-intersection``).

    Parameters
    ----------
    xy10, xy20 : (n, 2) arrays
        Horizontal-image coordinates of the left and right images (mm).
    base : (3,) array
        (B_x, B_y, B_z); the base must run mainly along x.
    f : float
        Principal distance (mm).
    centre : (3,) array
        S₁.

    Returns
    -------
    (n, 3) array
        X, Y, Z.

    Raises
    ------
    InputError
        Wrong shapes, NaN, f ≤ 0, different counts.
    DegenerateGeometryError
        x₁₀ = x₂₀ (zero x-parallax: the rays are parallel in X) or a base without an x component.
    PointBehindCameraError
        N ≤ 0: the intersection lies behind the cameras.

    References
    ----------
    Baikalova et al., step 6 (seed lines 120–128); Chibunichev (2022), §2.5, eq. (2.5.1).

    Examples
    --------
    >>> intersect_horizontal([[10.0, 5.0]], [[-30.0, 5.0]], [400.0, 0.0, 0.0], 100.0, [0, 0, 1000.0])
    array([[100.,  50.,   0.]])
    """
    P1 = as_points(xy10, 2, "left horizontal coordinates")
    P2 = as_points(xy20, 2, "right horizontal coordinates")
    if len(P1) != len(P2):
        raise InputError(f"{len(P1)} left and {len(P2)} right points")
    Bv = _numbers(base, "base")
    S = _numbers(centre, "centre")
    if Bv.shape != (3,) or S.shape != (3,):
        raise InputError("base and centre must be 3-vectors")
    fv = _positive(f, "f")
    if abs(Bv[0]) <= 1e-9 * np.linalg.norm(Bv) or not np.linalg.norm(Bv) > 0:
        raise DegenerateGeometryError("the base has no x component: the horizontal-pair formula of step 6 "
                                      "needs a base along x")
    dx = P1[:, 0] - P2[:, 0]
    small = np.abs(dx) <= 1e-12 * fv
    if np.any(small):
        raise DegenerateGeometryError(f"{int(small.sum())} point(s) with zero x-parallax x₁₀ − x₂₀: the rays "
                                      "do not intersect")
    N = (Bv[0] + P2[:, 0] * Bv[2] / fv) / dx
    if np.any(N <= 0):
        raise PointBehindCameraError("the intersection lies behind the cameras (N ≤ 0)",
                                     points=np.flatnonzero(N <= 0))
    return np.column_stack([S[0] + N * P1[:, 0], S[1] + N * P1[:, 1], S[2] - fv * N])


def parallax_to_model(pixels, parallax, pair: PairOrientation, pixel_size: float, principal_point,
                      shift=(0, 0)) -> np.ndarray:
    """Parallaxes → model coordinates: steps 5 and 6 for pixels of the left scan.

    The right pixel of a left pixel (x₁, y₁) = (column, row) with parallax p is
    (x₁ + x₀ + p, y₁ + y₀); pixels become image coordinates by
    x = (column − c_x)·s, y = −(row − c_y)·s (y up), are reduced to horizontal images with
    A₁, A₂ (:func:`reduce_to_horizontal`) and intersected (:func:`intersect_horizontal`).

    Parameters
    ----------
    pixels : (n, 2) array
        (column, row) of left pixels.
    parallax : (n,) array
        Their parallaxes p (pixels; may be fractional).
    pair : PairOrientation
        From :func:`orient_pair`.
    pixel_size : float
        Scan pixel size s (mm): 25.4/DPI.
    principal_point : (c_x, c_y)
        The principal point in pixels (both scans).
    shift : (int, int)
        The base shift (x₀, y₀) of the scans.

    Returns
    -------
    (n, 3) array
        Model coordinates X, Y, Z.

    Raises
    ------
    InputError
        Wrong shapes, NaN, non-positive pixel size, ``pair`` of another type.
    DegenerateGeometryError, PointBehindCameraError
        From steps 5 and 6.

    References
    ----------
    Baikalova et al., steps 5–6 (seed lines 98–128).

    Examples
    --------
    >>> from photolib.camera import InteriorOrientation
    >>> import numpy as np
    >>> E = np.eye(3)
    >>> po = PairOrientation(0, 0, 0, 0, 0, 0, 0, E, E, np.zeros(3), np.array([4.0, 0, 0]), 100.0)
    >>> parallax_to_model([[60.0, 50.0]], [-40.0], po, 0.1, (50.0, 50.0))
    array([[   1.,    0., -100.]])
    """
    if not isinstance(pair, PairOrientation):
        raise InputError(f"pair must be a PairOrientation (from orient_pair), got {type(pair).__name__}")
    px = as_points(pixels, 2, "pixels")
    p = _numbers(parallax, "parallax")
    if p.shape != (len(px),):
        raise InputError(f"parallax: expected shape ({len(px)},), got {p.shape}")
    s = _positive(pixel_size, "pixel_size")
    c = _numbers(principal_point, "principal_point")
    if c.shape != (2,):
        raise InputError("principal_point: expected (c_x, c_y)")
    x0, y0 = _shift(shift)
    xy1 = np.column_stack([(px[:, 0] - c[0]) * s, -(px[:, 1] - c[1]) * s])
    xy2 = np.column_stack([(px[:, 0] + x0 + p - c[0]) * s, -(px[:, 1] + y0 - c[1]) * s])
    h1 = reduce_to_horizontal(xy1, pair.f, pair.A1)
    h2 = reduce_to_horizontal(xy2, pair.f, pair.A2)
    return intersect_horizontal(h1, h2, pair.base, pair.f, pair.S1)


# =================================================================================================
# step 7: absolute orientation
# =================================================================================================
def convergence_rotation(points, G0) -> np.ndarray:
    """Step 7: X = X′cos G₀ − Y′sin G₀, Y = Y′cos G₀ + X′sin G₀, Z = Z′ (meridian convergence G₀).

    Parameters
    ----------
    points : (n, 3) array
        X′, Y′, Z′.
    G0 : float
        Convergence of the axial meridian and the meridian of the origin (rad).

    Returns
    -------
    (n, 3) array
        X, Y, Z.

    Raises
    ------
    InputError
        Wrong shapes, NaN.

    References
    ----------
    Baikalova et al., step 7 (seed lines 134–138).

    Examples
    --------
    >>> convergence_rotation([[1.0, 0.0, 5.0]], np.pi / 2).round(12)
    array([[0., 1., 5.]])
    """
    P = as_points(points, 3, "points")
    g = float(_numbers(G0, "G0"))
    c, s = math.cos(g), math.sin(g)
    return np.column_stack([P[:, 0] * c - P[:, 1] * s, P[:, 1] * c + P[:, 0] * s, P[:, 2]])


@dataclass(repr=False)
class ModelOrientation:
    """Exterior orientation of a free model in the paper's elements (3), from :func:`orient_model`.

    Attributes
    ----------
    X0, Y0, Z0 : float
        Origin of the photogrammetric system in the geodetic one.
    zeta, xi, nu : float
        Longitudinal tilt ζ (= α), transverse tilt ξ (= ω) and rotation ν (= χ), rad.
    t : float
        Scale (multiplies the model coordinates).
    transform : SimilarityTransform
        The Chapter-2 adjustment (μ, m_j, residuals).
    """

    X0: float
    Y0: float
    Z0: float
    zeta: float
    xi: float
    nu: float
    t: float
    transform: object = None

    @property
    def matrix(self) -> np.ndarray:
        """A(α = ζ, ω = ξ, χ = ν)."""
        return direction_cosines(self.zeta, self.xi, self.nu)

    def apply(self, model_points) -> np.ndarray:
        """(3): X = X₀ + t·A·X′."""
        P = as_points(model_points, 3, "model points")
        return np.array([self.X0, self.Y0, self.Z0]) + self.t * P @ self.matrix.T


def orient_model(model_points, control_points, components=None) -> ModelOrientation:
    """Step 7, (3): the seven elements X₀, Y₀, Z₀, ζ, ξ, ν, t of a model from control points.

    X = X₀ + t·(a₁X′ + a₂Y′ + a₃Z′), … with a₁ … c₃ from (1) at α = ζ, ω = ξ, χ = ν (printed
    "ω = ν, χ = ξ", which would make the transverse tilt a rotation about Z). Each full control
    point gives three equations, a height point one: 2 full + 1 height points give exactly the 7
    needed. Solved by the least-squares absolute orientation of Chapter 2
    (:func:`photolib.image_pair.absolute_orientation`); its rotation is converted to ζ, ξ, ν.

    Parameters
    ----------
    model_points : (n, 3) array
        Model coordinates X′, Y′, Z′ of the control points.
    control_points : (n, 3) array
        Their geodetic X, Y, Z (unknown ones may be NaN).
    components : (n, 3) bool array, optional
        Known coordinates (all by default): full points (True, True, True), height points
        (False, False, True).

    Returns
    -------
    ModelOrientation
        The seven elements and the adjustment.

    Raises
    ------
    InputError
        Wrong shapes, NaN in known coordinates, fewer than 7 equations.
    DegenerateGeometryError
        Collinear control, not enough control of the right kinds, ξ = ±90°.
    ConvergenceError
        From the adjustment.

    References
    ----------
    Baikalova et al., step 7, eq. (3) (seed lines 140–146); Chibunichev (2022), §2.10–§2.11,
    eqs. (2.10.4), (2.11.1), (2.11.2).

    Examples
    --------
    >>> import numpy as np
    >>> M = np.array([[0.0, 0, 0], [10, 0, 1], [0, 10, -1], [10, 10, 0]])
    >>> G = 2.0 * M @ direction_cosines(0.01, 0.02, 0.5).T + [100, 200, 30]
    >>> mask = np.array([[1, 1, 1], [1, 1, 1], [0, 0, 1], [0, 0, 0]], bool)
    >>> mo = orient_model(M, np.where(mask, G, np.nan), mask)
    >>> [round(v, 6) for v in (mo.zeta, mo.xi, mo.nu, mo.t)]
    [0.01, 0.02, 0.5, 2.0]
    """
    from .image_pair import absolute_orientation
    T = absolute_orientation(model_points, control_points, components, order="wak")
    zeta, xi, nu = direction_cosine_angles(T.matrix)
    return ModelOrientation(T.X0, T.Y0, T.Z0, zeta, xi, nu, T.t, T)
