"""Image gradients, interest operators and descriptors — Chapter 5, §5.5 and §5.7–5.9.

* §5.5 gradients: :func:`gradient_backward` (5.5.4), :func:`gradient_sobel` (5.5.6)–(5.5.9),
  :func:`gradient_prewitt` (5.5.10), :func:`gradient_roberts` (5.5.11) and
  :func:`gradient_magnitude` — L2 (5.5.2) or L1 (5.5.3).
* §5.8 interest operators: :func:`moravec` (5.8.1), :func:`harris` (5.8.2)–(5.8.4) in the
  corrected form R = det M − k·(tr M)², :func:`foerstner` (5.8.5)–(5.8.8) (w = |N|/tr N,
  q = 4|N|/(tr N)²), :func:`fast` (5.8.9, segment test on the 16-pixel circle of radius 3),
  :func:`log_kernel` / :func:`log_filter` / :func:`zero_crossings` (5.8.10)–(5.8.13) in the
  corrected form; :func:`nonmax_suppression` and :func:`interest_points` turn a response into points.
* Hanzl, Fotogrammetrie, Modul 01, §8.2 (seed 002 lines 1514–1612): image filters applied by
  correlation with an explicit border rule and rounding (:func:`filter_image`, the kernels
  :data:`HANZL_KERNELS`), the median filter (:func:`median_filter`), the gradient filters
  |g₁| + |g₂| (:func:`edge_filter`) and the 1-D second-difference edge enhancement
  (:func:`second_difference_1d`); §8.4 Förstner's size tr N/|N| (``foerstner(form="size")``)
  and the selection rule w < 0.3·w_med, q > 0.75 (``interest_points(..., selection="hanzl")``).
* §5.9 descriptors: :func:`sift_descriptors` — the 16×16 region rotated to the dominant gradient
  direction, 4×4 cells × 8 orientation bins = 128 features — and :func:`match_descriptors`
  (nearest neighbour with Lowe's ratio test).

Conventions
-----------
Images are arrays ``img[row, col]`` of grey values. The book's x runs along the columns and its y
*upwards*: (5.5.4) g_y = f(x, y) − f(x, y − 1) and Sobel's H_y (top row positive) measure the
change towards the top of the image, i.e. ``f[row] − f[row + 1]``. That is the opposite sign of
``numpy.gradient(img, axis=0)``; Harris, Förstner, Moravec and FAST do not depend on it. Points
are returned as ``(x, y) = (col, row)`` array coordinates (rows downwards), the convention of
OpenCV and of ``matplotlib.pyplot.plot``.

The masks are applied as *correlation* (5.5.7): g = Σ f_ij·H_ij without flipping the mask, so
(5.5.9) holds as printed (``scipy.ndimage.convolve`` would flip it and change the signs). Every
mask has an anchor: the centre for 3×3 masks, the top-left element for Roberts' 2×2 masks (the
anchoring that reproduces Fig. 5.12), the pixel itself for the backward differences.

Border handling (argument ``border``): ``"zero"`` (default of the gradients) sets to 0 every
output pixel whose mask leaves the image — the book's Fig. 5.12 convention for its last row and
column; ``"constant"`` pads the image with zeros, ``"nearest"`` repeats the edge pixel,
``"mirror"`` reflects about the edge pixel (OpenCV's BORDER_REFLECT_101, the detectors' default)
and ``"reflect"`` about the edge (half-sample symmetric), as in :mod:`scipy.ndimage`. Moravec's
and FAST's windows are never padded: their responses are 0 where the window leaves the image.

Errata corrected here (proved in textbook/ch05_features.toml with sympy): (5.8.2) the quadratic
form is (g_x u + g_y v)² = (u, v) M (u, v)ᵀ; (5.8.4) det M = AD − B², tr M = A + D and the
trace must be squared; (5.8.6) the adjugate swaps the diagonal, Q = |N|⁻¹[[Σg_y², −Σg_xg_y],
[−Σg_xg_y, Σg_x²]]; (5.8.7) w is large (not small) for good points; (5.8.12) has a spurious minus
sign; (5.8.13) lost the minus sign of its exponent. Fig. 5.12: the flat background of the Roberts
image is 0, not 10.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy import ndimage as ndi

from . import _checks
from .errors import InputError

__all__ = ["SOBEL_X", "SOBEL_Y", "PREWITT_X", "PREWITT_Y", "ROBERTS_X", "ROBERTS_Y", "FAST_CIRCLE",
           "gradient_backward", "gradient_sobel", "gradient_prewitt", "gradient_roberts",
           "gradient_magnitude", "moravec", "harris", "foerstner", "fast", "log_kernel", "log_filter",
           "zero_crossings", "nonmax_suppression", "interest_points", "DescriptorSet",
           "sift_descriptors", "match_descriptors", "HANZL_KERNELS", "filter_image", "median_filter",
           "edge_filter", "second_difference_1d"]

SOBEL_X = np.array([[-1.0, 0.0, 1.0], [-2.0, 0.0, 2.0], [-1.0, 0.0, 1.0]])
"""H_x of Sobel's operator (5.5.6)."""
SOBEL_Y = np.array([[1.0, 2.0, 1.0], [0.0, 0.0, 0.0], [-1.0, -2.0, -1.0]])
"""H_y of Sobel's operator (5.5.6): top row positive (y upwards)."""
PREWITT_X = np.array([[-1.0, 0.0, 1.0], [-1.0, 0.0, 1.0], [-1.0, 0.0, 1.0]])
"""H_x of Prewitt's operator (5.5.10)."""
PREWITT_Y = np.array([[1.0, 1.0, 1.0], [0.0, 0.0, 0.0], [-1.0, -1.0, -1.0]])
"""H_y of Prewitt's operator (5.5.10)."""
ROBERTS_X = np.array([[0.0, 1.0], [-1.0, 0.0]])
"""H_x of Roberts' operator (5.5.11), anchored at its top-left element."""
ROBERTS_Y = np.array([[1.0, 0.0], [0.0, -1.0]])
"""H_y of Roberts' operator (5.5.11), anchored at its top-left element."""
FAST_CIRCLE = np.array([(0, -3), (1, -3), (2, -2), (3, -1), (3, 0), (3, 1), (2, 2), (1, 3), (0, 3),
                        (-1, 3), (-2, 2), (-3, 1), (-3, 0), (-3, -1), (-2, -2), (-1, -3)])
"""(dx, dy) of the 16 pixels of the Bresenham circle of radius 3 used by FAST (§5.8), in order."""

_BORDERS = ("zero", "constant", "nearest", "mirror", "reflect")
_NP_PAD = {"constant": "constant", "nearest": "edge", "mirror": "reflect", "reflect": "symmetric"}
_NON_NEGATIVE = "{name} must be a non-negative integer, got {value!r}"
_POSITIVE_INT = "{name} must be a positive integer, got {value!r}"


# --- input checks -----------------------------------------------------------------------------------
_IMAGE_MESSAGES = {"type": "{name} must be a 2-D array of grey values, got {type}",
                   "numeric": "{name} must be a 2-D array of grey values: {exc}",
                   "ndim": "{name} must be a 2-D (grey) array, got {ndim} dimension(s) {shape}",
                   "small": "{name} of shape {shape} is smaller than the {min_size}×{min_size} window"}


def _image(img, what: str = "image", min_size: int = 1) -> np.ndarray:
    return _checks.image(img, what, min_size, messages=_IMAGE_MESSAGES)


def _border(border: str) -> str:
    if border not in _BORDERS:
        raise InputError(f"unknown border {border!r}; use one of {_BORDERS}")
    return border


_odd_window = _checks.odd_integer


def _positive(value, what) -> float:
    return _checks.number(value, what, True, not_a_number="{name} must be a positive number, got {value!r}",
                          out_of_range="{name} must be a positive finite number, got {value!r}")


def _correlate(f, H, anchor, border):
    """g[r, c] = Σ_ij f[r + i − a_r, c + j − a_c]·H[i, j] (5.5.7), with the given border rule."""
    H = np.asarray(H, dtype=float)
    ar, ac = anchor
    top, bottom = ar, H.shape[0] - 1 - ar
    left, right = ac, H.shape[1] - 1 - ac
    mode = "edge" if border == "zero" else _NP_PAD[border]
    if mode == "reflect" and min(f.shape) < 2:
        mode = "edge"
    p = np.pad(f, ((top, bottom), (left, right)), mode=mode)
    rows, cols = f.shape
    g = np.zeros_like(f)
    for i in range(H.shape[0]):
        for j in range(H.shape[1]):
            if H[i, j] != 0.0:
                g += H[i, j] * p[i:i + rows, j:j + cols]
    if border == "zero":
        if top:
            g[:top] = 0.0
        if bottom:
            g[rows - bottom:] = 0.0
        if left:
            g[:, :left] = 0.0
        if right:
            g[:, cols - right:] = 0.0
    return g


# --- §5.5 gradients ------------------------------------------------------------------------------------
def gradient_backward(img, border: str = "zero"):
    """Backward differences (5.5.4): g_x = f(x, y) − f(x − 1, y), g_y = f(x, y) − f(x, y − 1).

    With y upwards, f(x, y − 1) is the pixel *below*: ``gx[r, c] = f[r, c] − f[r, c − 1]`` and
    ``gy[r, c] = f[r, c] − f[r + 1, c]``.

    Parameters
    ----------
    img : (rows, cols) array
        Grey values.
    border : {"zero", "constant", "nearest", "mirror", "reflect"}
        ``"zero"``: 0 in the first column (g_x) and the last row (g_y), where the difference
        leaves the image; otherwise the image is padded (module notes).

    Returns
    -------
    gx, gy : ndarray
        The two components, same shape as ``img``.

    Raises
    ------
    InputError
        Not a 2-D array, NaN/inf pixels, an unknown border rule.

    References
    ----------
    Chibunichev (2022), §5.5, eq. (5.5.4).

    Examples
    --------
    >>> gx, gy = gradient_backward([[1.0, 2.0, 4.0], [0.0, 0.0, 0.0]])
    >>> gx
    array([[0., 1., 2.],
           [0., 0., 0.]])
    >>> gy
    array([[1., 2., 4.],
           [0., 0., 0.]])
    """
    f = _image(img)
    border = _border(border)
    return (_correlate(f, [[-1.0, 1.0]], (0, 1), border),
            _correlate(f, [[1.0], [-1.0]], (0, 0), border))


def _three_by_three(img, Hx, Hy, border, scale):
    """Separable 3×3 masks: H_x = s ⊗ d, H_y = −d ⊗ s with s the smoothing row ([1, 2, 1] or [1, 1, 1])."""
    f = _image(img)
    border = _border(border)
    smooth = Hx[:, 2]
    mode = "nearest" if border == "zero" else border
    gx = ndi.correlate1d(ndi.correlate1d(f, smooth, axis=0, mode=mode), [-1.0, 0.0, 1.0], axis=1, mode=mode)
    gy = ndi.correlate1d(ndi.correlate1d(f, smooth, axis=1, mode=mode), [1.0, 0.0, -1.0], axis=0, mode=mode)
    if border == "zero":
        for g in (gx, gy):
            g[0] = g[-1] = 0.0
            g[:, 0] = g[:, -1] = 0.0
    return gx / scale, gy / scale


def gradient_sobel(img, border: str = "zero", normalize: bool = False):
    """Sobel's gradient (5.5.6)/(5.5.7): correlation with H_x, H_y, i.e. exactly (5.5.9).

    g_x = (f₃ + 2f₆ + f₉) − (f₁ + 2f₄ + f₇), g_y = (f₁ + 2f₂ + f₃) − (f₇ + 2f₈ + f₉) for the 3×3
    neighbourhood f₁…f₉ (row by row) of each pixel.

    Parameters
    ----------
    img : (rows, cols) array
        Grey values.
    border : {"zero", "constant", "nearest", "mirror", "reflect"}
        Border rule (module notes); ``"zero"`` gives 0 on the outermost rows and columns.
    normalize : bool
        Divide by 8 so that a unit ramp gives 1 (a true derivative); the book's masks give 8.

    Returns
    -------
    gx, gy : ndarray
        The two components (g_y towards the top of the image).

    Raises
    ------
    InputError
        Not a 2-D array, NaN/inf, an unknown border rule.

    References
    ----------
    Chibunichev (2022), §5.5, eqs. (5.5.5)–(5.5.9).

    Examples
    --------
    >>> ramp = np.tile(np.arange(4.0), (3, 1))          # grows by 1 per column
    >>> gx, gy = gradient_sobel(ramp)
    >>> gx[1]
    array([0., 8., 8., 0.])
    >>> float(gy[1, 1])
    0.0
    """
    return _three_by_three(img, SOBEL_X, SOBEL_Y, border, 8.0 if normalize else 1.0)


def gradient_prewitt(img, border: str = "zero", normalize: bool = False):
    """Prewitt's gradient (5.5.10): correlation with H_x = [−1 0 1] in every row, H_y likewise.

    Parameters
    ----------
    img : (rows, cols) array
        Grey values.
    border : {"zero", "constant", "nearest", "mirror", "reflect"}
        Border rule (module notes).
    normalize : bool
        Divide by 6 (a unit ramp gives 1).

    Returns
    -------
    gx, gy : ndarray
        The two components (g_y towards the top of the image).

    Raises
    ------
    InputError
        Not a 2-D array, NaN/inf, an unknown border rule.

    References
    ----------
    Chibunichev (2022), §5.5, eqs. (5.5.7), (5.5.10).

    Examples
    --------
    >>> col = np.arange(4.0)[:, None] * np.ones((1, 3))    # grows by 1 per row (downwards)
    >>> gx, gy = gradient_prewitt(col, normalize=True)
    >>> float(gy[1, 1]), float(gx[1, 1])
    (-1.0, 0.0)
    """
    return _three_by_three(img, PREWITT_X, PREWITT_Y, border, 6.0 if normalize else 1.0)


def gradient_roberts(img, border: str = "zero", anchor: str = "top-left"):
    """Roberts' cross gradient (5.5.11): the 2×2 masks H_x = [[0, 1], [−1, 0]], H_y = [[1, 0], [0, −1]].

    Anchored at the top-left element (``anchor="top-left"``, the anchoring that reproduces the
    printed ring of Fig. 5.12): ``gx[r, c] = f[r, c+1] − f[r+1, c]``, ``gy[r, c] = f[r, c] − f[r+1, c+1]``.

    Parameters
    ----------
    img : (rows, cols) array
        Grey values.
    border : {"zero", "constant", "nearest", "mirror", "reflect"}
        ``"zero"``: 0 in the last row and column (top-left anchor) or the first (bottom-right).
    anchor : {"top-left", "bottom-right"}
        Which element of the 2×2 mask is the output pixel.

    Returns
    -------
    gx, gy : ndarray
        The two (diagonal) components.

    Raises
    ------
    InputError
        Not a 2-D array, NaN/inf, an unknown border rule or anchor.

    References
    ----------
    Chibunichev (2022), §5.5, eq. (5.5.11), Fig. 5.12.

    Examples
    --------
    >>> f = np.full((4, 4), 10.0); f[1:3, 1:3] = 20.0
    >>> gx, gy = gradient_roberts(f)
    >>> gradient_magnitude(gx, gy, norm="l1")
    array([[10., 20., 10.,  0.],
           [20.,  0., 20.,  0.],
           [10., 20., 10.,  0.],
           [ 0.,  0.,  0.,  0.]])
    """
    f = _image(img)
    border = _border(border)
    anchors = {"top-left": (0, 0), "bottom-right": (1, 1)}
    if anchor not in anchors:
        raise InputError(f"unknown anchor {anchor!r}; use 'top-left' or 'bottom-right'")
    return (_correlate(f, ROBERTS_X, anchors[anchor], border),
            _correlate(f, ROBERTS_Y, anchors[anchor], border))


def gradient_magnitude(gx, gy, norm: str = "l2"):
    """Length of the gradient: G = √(g_x² + g_y²) (5.5.2) or the approximation |g_x| + |g_y| (5.5.3).

    Parameters
    ----------
    gx, gy : arrays of the same shape
        Gradient components.
    norm : {"l2", "l1"}
        (5.5.2) or (5.5.3).

    Returns
    -------
    ndarray
        G, same shape.

    Raises
    ------
    InputError
        Different shapes, NaN/inf, an unknown norm.

    References
    ----------
    Chibunichev (2022), §5.5, eqs. (5.5.2), (5.5.3).

    Examples
    --------
    >>> gradient_magnitude(np.array([3.0]), np.array([-4.0])), gradient_magnitude(np.array([3.0]), np.array([-4.0]), "l1")
    (array([5.]), array([7.]))
    """
    try:
        gx = np.asarray(gx, dtype=float)
        gy = np.asarray(gy, dtype=float)
    except (TypeError, ValueError) as exc:
        raise InputError(f"gradient components must be numeric arrays: {exc}") from exc
    if gx.shape != gy.shape:
        raise InputError(f"gx and gy differ in shape: {gx.shape} vs {gy.shape}")
    if gx.size == 0:
        raise InputError("empty gradient arrays")
    if not (np.all(np.isfinite(gx)) and np.all(np.isfinite(gy))):
        raise InputError("gradient components contain NaN or inf")
    if norm == "l2":
        return np.hypot(gx, gy)
    if norm == "l1":
        return np.abs(gx) + np.abs(gy)
    raise InputError(f"unknown norm {norm!r}; use 'l2' (5.5.2) or 'l1' (5.5.3)")


_GRADIENTS = {"sobel": lambda f, b: gradient_sobel(f, b, normalize=True),
              "prewitt": lambda f, b: gradient_prewitt(f, b, normalize=True),
              "backward": gradient_backward,
              "roberts": gradient_roberts}


def _gradient(f, gradient, border):
    if gradient not in _GRADIENTS:
        raise InputError(f"unknown gradient {gradient!r}; use one of {sorted(_GRADIENTS)}")
    return _GRADIENTS[gradient](f, border)


# --- window sums ---------------------------------------------------------------------------------------
def _offset_sum(a, r0, r1, c0, c1, shape):
    """out[r, c] = Σ_{i=r0..r1, j=c0..c1} a[r + i, c + j] where all indices exist, else 0."""
    S = np.zeros((a.shape[0] + 1, a.shape[1] + 1))
    S[1:, 1:] = a.cumsum(0).cumsum(1)
    rows, cols = shape
    out = np.zeros(shape)
    rlo, rhi = max(0, -r0), min(rows, a.shape[0] - r1)      # r + r0 ≥ 0 and r + r1 ≤ a.rows − 1
    clo, chi = max(0, -c0), min(cols, a.shape[1] - c1)
    if rlo >= rhi or clo >= chi:
        return out, (slice(0, 0), slice(0, 0))
    r = np.arange(rlo, rhi)[:, None]
    c = np.arange(clo, chi)[None, :]
    out[rlo:rhi, clo:chi] = (S[r + r1 + 1, c + c1 + 1] - S[r + r0, c + c1 + 1]
                             - S[r + r1 + 1, c + c0] + S[r + r0, c + c0])
    return out, (slice(rlo, rhi), slice(clo, chi))


def _weighted_sum(a, window, weight, sigma, border):
    """Σ_W P·a over the window (box: plain sum; gaussian: normalised Gaussian truncated to the window)."""
    mode = "constant" if border in ("zero", "constant") else border
    h = window // 2
    if weight == "box":
        return ndi.uniform_filter(a, window, mode=mode) * window * window
    if weight == "gaussian":
        s = h / 2.0 if sigma is None else _positive(sigma, "sigma")
        return ndi.gaussian_filter(a, s, mode=mode, truncate=h / s)
    raise InputError(f"unknown weight {weight!r}; use 'gaussian' or 'box'")


def _structure_tensor(img, window, weight, sigma, gradient, border):
    f = _image(img, min_size=1)
    window = _odd_window(window)
    border = _border(border)
    gx, gy = _gradient(f, gradient, border)
    return (_weighted_sum(gx * gx, window, weight, sigma, border),
            _weighted_sum(gx * gy, window, weight, sigma, border),
            _weighted_sum(gy * gy, window, weight, sigma, border))


# --- §5.8 interest operators ---------------------------------------------------------------------------------
def moravec(img, window: int = 5, variant: str = "book"):
    """Moravec's operator (5.8.1): M = min(M₁, M₂, M₃, M₄) of the mean squared neighbour differences.

    For an n×n window (n odd) around each pixel, M₁ is the mean of [f(x, y) − f(x, y + 1)]² over
    the n(n − 1) vertically adjacent pairs inside the window, M₂ the same for horizontal pairs,
    M₃ and M₄ for the (n − 1)² pairs along the two diagonals — (5.8.1) with its lower limit
    −n/2 (the print's "n/2" is an OCR loss) and n/2 read as ⌊n/2⌋, so that the index ranges hold
    n and n − 1 values as the normalisers say. Pixels whose window leaves the image get 0.

    Parameters
    ----------
    img : (rows, cols) array
        Grey values.
    window : int
        Odd window size n = m (the book leaves it open; 5 by default).
    variant : {"book", "shift", "diagonal"}
        ``"book"``: (5.8.1) as above. ``"shift"``: Moravec's original form, the unnormalised sum of
        squared differences between the window and the window shifted by one pixel, minimum over
        the 8 shifts. ``"diagonal"``: the same over the shifts (dr, dc) with 0 < |dr|, |dc| ≤
        window // 2 only — what scikit-image 0.26's ``corner_moravec(window_size=window // 2)``
        computes (its loop skips every shift with a zero component). 0 where the shifted window
        leaves the image.

    Returns
    -------
    ndarray
        M, same shape as ``img``; threshold it (the book's "1"/"0" mask) or pass it to
        :func:`nonmax_suppression`.

    Raises
    ------
    InputError
        Not a 2-D array, NaN/inf, an even or too small window, an image smaller than it.

    References
    ----------
    Chibunichev (2022), §5.8, eq. (5.8.1); H. Moravec (1980), Stanford AIM-340.

    Examples
    --------
    >>> f = np.zeros((9, 9)); f[4:, 4:] = 1.0          # a corner at (4, 4)
    >>> M = moravec(f, window=3)
    >>> [int(v) for v in np.unravel_index(M.argmax(), M.shape)], round(float(M.max()), 4)
    ([4, 4], 0.3333)
    """
    n = _odd_window(window)
    f = _image(img, min_size=n)
    h = n // 2
    shape = f.shape
    if variant in ("shift", "diagonal"):
        if variant == "shift":
            shifts = [(dr, dc) for dr in (-1, 0, 1) for dc in (-1, 0, 1) if (dr, dc) != (0, 0)]
        else:
            shifts = [(dr, dc) for dr in range(-h, h + 1) for dc in range(-h, h + 1) if dr != 0 and dc != 0]
        reach = h + max(max(abs(a), abs(b)) for a, b in shifts)
        rows, cols = shape
        if rows <= 2 * reach or cols <= 2 * reach:
            raise InputError(f"image of shape {shape} is too small for the shifted {n}×{n} window")
        M = np.full(shape, np.inf)
        for dr, dc in shifts:
            d = np.zeros(shape)
            m = max(abs(dr), abs(dc))
            d[m:rows - m, m:cols - m] = (f[m:rows - m, m:cols - m]
                                         - f[m + dr:rows - m + dr, m + dc:cols - m + dc]) ** 2
            M = np.minimum(M, ndi.uniform_filter(d, n, mode="constant") * n * n)
        valid = np.zeros(shape, bool)
        valid[reach:rows - reach, reach:cols - reach] = True
        return np.where(valid, M, 0.0)
    if variant != "book":
        raise InputError(f"unknown variant {variant!r}; use 'book' (5.8.1), 'shift' or 'diagonal'")
    pairs = {
        "M1": ((f[:-1, :] - f[1:, :]) ** 2, -h, h - 1, -h, h, n * (n - 1)),
        "M2": ((f[:, :-1] - f[:, 1:]) ** 2, -h, h, -h, h - 1, n * (n - 1)),
        "M3": ((f[:-1, :-1] - f[1:, 1:]) ** 2, -h, h - 1, -h, h - 1, (n - 1) ** 2),
        "M4": ((f[:-1, 1:] - f[1:, :-1]) ** 2, -h, h - 1, -h, h - 1, (n - 1) ** 2),
    }
    M = None
    for d, r0, r1, c0, c1, norm in pairs.values():
        s, _ = _offset_sum(d, r0, r1, c0, c1, shape)
        M = s / norm if M is None else np.minimum(M, s / norm)
    valid = np.zeros(shape, bool)
    valid[h:shape[0] - h, h:shape[1] - h] = True
    return np.where(valid, M, 0.0)


def harris(img, window: int = 5, k: float = 0.04, weight: str = "gaussian", sigma=None,
           gradient: str = "sobel", border: str = "mirror"):
    """Harris's response R = det M − k·(tr M)² (5.8.2)–(5.8.4), corrected.

    M = Σ_W P·[[g_x², g_x g_y], [g_x g_y, g_y²]] = [[A, B], [B, D]] (5.8.3) is the autocorrelation
    matrix of the gradients over the n×n window W with weight P; det M = λ₁λ₂ = AD − B², tr M =
    λ₁ + λ₂ = A + D and R = det M − k (tr M)² (Harris & Stephens 1988). The print's
    "R = λ₁λ₂ − k(λ₁ + λ₂)" lacks the square: without it R is not homogeneous in the grey scale
    and k ∈ [0.04, 0.06] has no meaning. Corners give R > 0, edges R < 0, flat areas R ≈ 0.

    Parameters
    ----------
    img : (rows, cols) array
        Grey values.
    window : int
        Odd window size n (the book: "usually 5×5").
    k : float
        Harris's constant, the book's k ∈ [0.04, 0.06] (other values are accepted).
    weight : {"gaussian", "box"}
        P(x, y) (Fig. 5.21): a normalised Gaussian truncated to the window, or 1 (plain sums, the
        weight of ``cv2.cornerHarris``).
    sigma : float, optional
        σ of the Gaussian weight (pixels); default (window // 2)/2, σ = 1 for 5×5, the weight
        truncated at the window's edge. Give
        ``window=9, sigma=1`` for scikit-image's ``corner_harris(sigma=1)`` (truncated at 4σ).
    gradient : {"sobel", "prewitt", "backward", "roberts"}
        The gradient operator (the book leaves it open); Sobel and Prewitt divided by 8 and 6.
    border : {"mirror", "reflect", "nearest", "constant", "zero"}
        Border rule for the gradients and the window sums.

    Returns
    -------
    ndarray
        R, same shape as ``img`` (grey units⁴).

    Raises
    ------
    InputError
        Not a 2-D array, NaN/inf, an even window, k outside (0, 0.25), unknown options.

    References
    ----------
    Chibunichev (2022), §5.8, eqs. (5.8.2)–(5.8.4); C. Harris, M. Stephens (1988), Alvey Vision Conf.

    Examples
    --------
    >>> f = np.zeros((21, 21)); f[10:, 10:] = 1.0
    >>> R = harris(f)
    >>> [int(v) for v in np.unravel_index(R.argmax(), R.shape)], bool(R[10, 17] < 0), float(R[3, 3])
    ([10, 10], True, 0.0)
    """
    try:
        k = float(k)
    except (TypeError, ValueError) as exc:
        raise InputError(f"k must be a number, got {k!r}") from exc
    if not 0 < k < 0.25:
        raise InputError(f"k must lie in (0, 0.25) (the book: 0.04–0.06), got {k}")
    A, B, D = _structure_tensor(img, window, weight, sigma, gradient, border)
    return A * D - B * B - k * (A + D) ** 2


def foerstner(img, window: int = 5, gradient: str = "backward", weight: str = "box", sigma=None,
              border: str = "mirror", form: str = "weight"):
    """Förstner's operator (5.8.5)–(5.8.8): the weight w = |N|/tr N and the roundness q = 4|N|/(tr N)².

    N = [[Σg_x², Σg_xg_y], [Σg_xg_y, Σg_y²]] (5.8.5) over the window, by default with the backward
    differences (5.5.4) and plain sums as the book says. Q = N⁻¹ = |N|⁻¹[[Σg_y², −Σg_xg_y],
    [−Σg_xg_y, Σg_x²]] (the print's (5.8.6) forgets to swap the diagonal); w = 1/tr Q =
    λ₁λ₂/(λ₁ + λ₂) (λ of N) is the *weight* of a point — large for a small error ellipse, so good
    points have large w (the text says "small"); q = 1 − ((λ₁ − λ₂)/(λ₁ + λ₂))² ∈ [0, 1] is 1 for
    a circular ellipse and 0 on a straight edge. Where tr N = 0 (no texture) w = q = 0.

    Parameters
    ----------
    img : (rows, cols) array
        Grey values.
    window : int
        Odd window size (the book: e.g. 5×5).
    gradient : {"backward", "sobel", "prewitt", "roberts"}
        (5.5.4) as the book says; Förstner's original uses Roberts.
    weight : {"box", "gaussian"}
        Plain sums (the book) or a Gaussian truncated to the window.
    sigma : float, optional
        σ of the Gaussian weight. ``window=9, sigma=1, gradient="sobel", weight="gaussian",
        border="constant"`` is scikit-image's ``corner_foerstner(sigma=1)`` (w up to a factor 1/64).
    border : {"mirror", "reflect", "nearest", "constant", "zero"}
        Border rule.
    form : {"weight", "size"}
        ``"weight"``: w = |N|/tr N (Chibunichev (5.8.7), Förstner's weight, large at good points);
        ``"size"``: Hanzl's size of the error ellipse w = tr Q = tr N/|N| = λ₁ + λ₂ (λ of Q), the
        reciprocal, small at good points and ``inf`` where |N| = 0 (Hanzl §8.4; his printed
        "w = 1/(λ₁ + λ₂)" is an erratum, see textbook/ch05_hanzl.toml).

    Returns
    -------
    w, q : ndarray
        Same shape as ``img``.

    Raises
    ------
    InputError
        Not a 2-D array, NaN/inf, an even window, unknown options.

    References
    ----------
    Chibunichev (2022), §5.8, eqs. (5.8.5)–(5.8.8); W. Förstner, E. Gülch (1987), ISPRS Interlaken;
    Hanzl, Fotogrammetrie, Modul 01, §8.4 (seed 002 lines 1646–1670) for ``form="size"``.

    Examples
    --------
    >>> f = np.zeros((15, 15)); f[7:, 7:] = 1.0
    >>> w, q = foerstner(f)
    >>> round(float(q[7, 7]), 3), float(q[7, 2]), float(w[2, 2])
    (1.0, 0.0, 0.0)
    >>> size, _ = foerstner(f, form="size")
    >>> bool(np.isclose(size[7, 7], 1 / w[7, 7])), float(size[2, 2])
    (True, inf)
    """
    if form not in ("weight", "size"):
        raise InputError(f"form must be 'weight' or 'size', got {form!r}")
    A, B, D = _structure_tensor(img, window, weight, sigma, gradient, border)
    det = A * D - B * B
    tr = A + D
    tiny = tr <= 1e-12 * max(float(tr.max(initial=0.0)), 1e-300)
    safe = np.where(tiny, 1.0, tr)
    w = np.maximum(np.where(tiny, 0.0, det / safe), 0.0)
    q = np.where(tiny, 0.0, 4.0 * det / safe ** 2)
    if form == "size":
        with np.errstate(divide="ignore"):
            w = np.where(w > 0, 1.0 / np.where(w > 0, w, 1.0), np.inf)
    return w, np.clip(q, 0.0, 1.0)


def fast(img, threshold: float = 20.0, n: int = 9):
    """FAST segment test (5.8.9) on the 16-pixel circle of radius 3; returns the corner score.

    Each circle pixel u is classified against the centre f: d (darker) if f(u) ≤ f − t, b
    (brighter) if f(u) ≥ f + t, s otherwise (5.8.9). The pixel is a corner if the circle holds
    a *contiguous arc* of n pixels that are all d or all b (Rosten & Drummond; the book's first
    sentence "similar brightness" inverts the test). The score is the largest t for which the
    pixel is still a corner, max over arcs of the smallest |f(u) − f| on the arc — so
    ``score ≥ threshold`` is the segment test itself. Non-corners and the 3-pixel border get 0.
    (OpenCV classifies with strict inequalities: for integer images ``cv2.FAST`` with threshold
    t finds the pixels with score ≥ t + 1 here.)

    Parameters
    ----------
    img : (rows, cols) array
        Grey values (7×7 or larger).
    threshold : float
        t of (5.8.9), > 0.
    n : int
        Arc length, 9…16 (FAST-9 by default; 12 is the original high-speed test).

    Returns
    -------
    ndarray
        Score, same shape as ``img``; 0 where the segment test fails.

    Raises
    ------
    InputError
        Not a 2-D array, NaN/inf, an image smaller than 7×7, t ≤ 0, n outside 9…16.

    References
    ----------
    Chibunichev (2022), §5.8, eq. (5.8.9); E. Rosten, T. Drummond (2006), ECCV.

    Examples
    --------
    >>> f = np.zeros((15, 15)); f[7:, 7:] = 100.0
    >>> s = fast(f, threshold=20)
    >>> float(s[6, 6]), float(s[7, 7]), float(s[7, 2])
    (0.0, 100.0, 0.0)
    """
    f = _image(img, min_size=7)
    t = _positive(threshold, "threshold")
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or not 9 <= n <= 16:
        raise InputError(f"n must be an integer in 9…16, got {n!r}")
    rows, cols = f.shape
    c = f[3:rows - 3, 3:cols - 3]
    # pre-test (exact): an arc of n of the 16 pixels contains at least ⌊n/4⌋ of the 4 compass pixels
    need = n // 4
    compass = [f[3 + dy:rows - 3 + dy, 3 + dx:cols - 3 + dx] for dx, dy in FAST_CIRCLE[[0, 4, 8, 12]]]
    brighter = sum((q - c >= t).astype(np.int8) for q in compass)
    darker = sum((c - q >= t).astype(np.int8) for q in compass)
    r_idx, c_idx = np.nonzero((brighter >= need) | (darker >= need))
    score = np.zeros_like(f)
    if len(r_idx):
        r_idx, c_idx = r_idx + 3, c_idx + 3
        centre = f[r_idx, c_idx]
        ring = np.stack([f[r_idx + dy, c_idx + dx] for dx, dy in FAST_CIRCLE])      # (16, K)
        best = np.zeros_like(centre)
        for diff in (ring - centre, centre - ring):                                   # brighter, darker arcs
            best = np.maximum(best, _circular_window_min(diff, n).max(axis=0))
        score[r_idx, c_idx] = np.where(best >= t, best, 0.0)
    return score


def _circular_window_min(a, n):
    """out[s] = min(a[s], …, a[s + n − 1]) (indices mod 16) for s = 0…15, by doubling windows."""
    ext = np.concatenate([a, a[:n - 1]])                 # length 16 + n − 1
    powers = {1: ext}
    k = 1
    while 2 * k <= n:
        prev = powers[k]
        powers[2 * k] = np.minimum(prev[:-k], prev[k:])
        k *= 2
    out, offset = None, 0
    for p in sorted(powers, reverse=True):
        if n - offset >= p:
            part = powers[p][offset:offset + 16]
            out = part if out is None else np.minimum(out, part)
            offset += p
    return out


def log_kernel(sigma: float, radius=None):
    """The Laplacian-of-Gaussian mask (5.8.13), corrected, sampled and made zero-sum.

    LoG(x, y) = (x² + y² − 2σ²)/(2πσ⁶)·e^{−(x² + y²)/(2σ²)} = W″_x + W″_y of the Gaussian (5.8.10),
    with W″_x = (x² − σ²)/(2πσ⁶)·e^{−r²/(2σ²)} (the print's (5.8.12) has a spurious minus and
    (5.8.13) has lost the minus of its exponent). Negative at the centre, zero at r = σ√2. The
    samples on −radius…radius are shifted by their mean so that the mask sums to zero (a flat
    image gives 0).

    Parameters
    ----------
    sigma : float
        σ (pixels), the scale.
    radius : int, optional
        Half-size of the mask; ⌈4σ⌉ by default.

    Returns
    -------
    (2·radius + 1, 2·radius + 1) ndarray
        The mask.

    Raises
    ------
    InputError
        σ ≤ 0 or not finite; radius < 1.

    References
    ----------
    Chibunichev (2022), §5.8, eqs. (5.8.10)–(5.8.13); D. Marr, E. Hildreth (1980), Proc. R. Soc. B.

    Examples
    --------
    >>> K = log_kernel(1.0)
    >>> K.shape, bool(K[4, 4] < 0), abs(float(K.sum())) < 1e-15
    ((9, 9), True, True)
    """
    s = _positive(sigma, "sigma")
    if radius is None:
        radius = int(np.ceil(4 * s))
    _checks.integer(radius, "radius", message=_POSITIVE_INT)
    r = np.arange(-radius, radius + 1, dtype=float)
    X, Y = np.meshgrid(r, r)
    R2 = X * X + Y * Y
    K = (R2 - 2 * s * s) / (2 * np.pi * s ** 6) * np.exp(-R2 / (2 * s * s))
    return K - K.mean()


def log_filter(img, sigma: float = 2.0, border: str = "mirror"):
    """The image filtered by the LoG mask of :func:`log_kernel` (5.8.13).

    Parameters
    ----------
    img : (rows, cols) array
        Grey values.
    sigma : float
        σ of the operator (pixels).
    border : {"mirror", "reflect", "nearest", "constant", "zero"}
        Border rule (``"zero"`` sets to 0 the pixels whose mask leaves the image).

    Returns
    -------
    ndarray
        LoG response (negative inside bright blobs, zero crossings on edges).

    Raises
    ------
    InputError
        Not a 2-D array, NaN/inf, σ ≤ 0, an unknown border rule.

    References
    ----------
    Chibunichev (2022), §5.8, eq. (5.8.13).

    Examples
    --------
    >>> f = np.zeros((21, 21)); f[8:13, 8:13] = 100.0
    >>> L = log_filter(f, sigma=1.5)
    >>> bool(L[10, 10] < 0), bool(abs(L[0, 0]) < 1e-9)
    (True, True)
    """
    f = _image(img)
    K = log_kernel(sigma)
    border = _border(border)
    r = K.shape[0] // 2
    return _correlate(f, K, (r, r), border)


def zero_crossings(response, min_contrast: float = 0.0):
    """Pixels where a (LoG) response changes sign towards its right or lower neighbour (5.8.13).

    Of the two pixels of a sign change the one with the smaller |response| is marked, if the jump
    |L₁ − L₂| exceeds ``min_contrast`` (suppresses the crossings of noise).

    Parameters
    ----------
    response : (rows, cols) array
        E.g. :func:`log_filter`.
    min_contrast : float
        Smallest jump across the crossing, ≥ 0.

    Returns
    -------
    ndarray of bool
        The edge mask.

    Raises
    ------
    InputError
        Not a 2-D array, NaN/inf, a negative ``min_contrast``.

    References
    ----------
    Chibunichev (2022), §5.8, eq. (5.8.13); Marr & Hildreth (1980).

    Examples
    --------
    >>> zero_crossings(np.array([[-2.0, -1.0, 3.0, 4.0]])).astype(int)
    array([[0, 1, 0, 0]])
    """
    L = _image(response, "response")
    mc = _checks.number(min_contrast, "min_contrast", True, allow_zero=True,
                        out_of_range="{name} must be ≥ 0, got {value!r}")
    out = np.zeros(L.shape, bool)
    for a, b, sa, sb in ((L[:, :-1], L[:, 1:], (slice(None), slice(None, -1)), (slice(None), slice(1, None))),
                         (L[:-1, :], L[1:, :], (slice(None, -1), slice(None)), (slice(1, None), slice(None)))):
        cross = (a * b < 0) & (np.abs(a - b) > mc)
        first = cross & (np.abs(a) <= np.abs(b))
        out[sa] |= first
        out[sb] |= cross & ~first
    return out


def nonmax_suppression(response, size: int = 5, threshold=None, relative: float = 0.01,
                       max_points=None, border: int = 0):
    """Local maxima of a response: the interest points (x, y) = (col, row), strongest first.

    A pixel is kept if it is the maximum of its size×size neighbourhood and larger than the
    neighbourhood's minimum (a flat area has no maxima), its response is > 0,
    > ``threshold`` (absolute, if given) and ≥ ``relative``·max(response). A flat (textureless)
    response gives no points — an empty (0, 2) array, not an error. Of a plateau of equal maxima
    only the first pixel in row-major order is kept.

    Parameters
    ----------
    response : (rows, cols) array
        Detector response (Harris R, Förstner w, Moravec M, FAST score, |LoG|).
    size : int
        Odd neighbourhood size (≥ 3).
    threshold : float, optional
        Absolute threshold.
    relative : float
        Threshold relative to the strongest response, in [0, 1).
    max_points : int, optional
        Keep at most this many (the strongest).
    border : int
        Ignore pixels closer than this to the image edge.

    Returns
    -------
    (n, 2) ndarray
        Points (x, y), by decreasing response.

    Raises
    ------
    InputError
        Not a 2-D array, NaN/inf, an even size, bad thresholds.

    References
    ----------
    Chibunichev (2022), §5.8 (thresholding the operators' responses; Figs. 5.19, 5.22–5.26).

    Examples
    --------
    >>> R = np.zeros((7, 7)); R[2, 3] = 5.0; R[2, 4] = 4.0; R[5, 5] = 1.0
    >>> nonmax_suppression(R, size=3)
    array([[3., 2.],
           [5., 5.]])
    >>> nonmax_suppression(np.zeros((7, 7))).shape
    (0, 2)
    """
    R = _image(response, "response")
    size = _odd_window(size, "size")
    try:
        rel = float(relative)
    except (TypeError, ValueError) as exc:
        raise InputError(f"relative must be a number, got {relative!r}") from exc
    if not 0 <= rel < 1:
        raise InputError(f"relative must lie in [0, 1), got {relative!r}")
    thr = 0.0
    if threshold is not None:
        thr = _checks.number(threshold, "threshold", out_of_range="{name} must be finite, got {value!r}")
    _checks.integer(border, "border", 0, message=_NON_NEGATIVE)
    if max_points is not None:
        _checks.integer(max_points, "max_points", 0, message=_NON_NEGATIVE)
    top = float(R.max())
    if not top > 0:
        return np.zeros((0, 2))
    mx = ndi.maximum_filter(R, size=size, mode="constant", cval=-np.inf)
    mn = ndi.minimum_filter(R, size=size, mode="nearest")
    keep = (R == mx) & (R > mn) & (R > max(thr, 0.0)) & (R >= rel * top)     # R > mn: not inside a flat area
    if border:
        keep[:border] = keep[R.shape[0] - border:] = False
        keep[:, :border] = keep[:, R.shape[1] - border:] = False
    rc = np.argwhere(keep)
    if len(rc) > 1:                                  # plateaus: keep the first pixel of each
        vals = R[rc[:, 0], rc[:, 1]]
        order = np.lexsort((rc[:, 1], rc[:, 0], -vals))
        rc = rc[order]
        h = size // 2
        taken = np.zeros(R.shape, bool)
        chosen = []
        for r, c in rc:
            if taken[r, c]:
                continue
            chosen.append((r, c))
            blocked = R[max(r - h, 0):r + h + 1, max(c - h, 0):c + h + 1] == R[r, c]
            taken[max(r - h, 0):r + h + 1, max(c - h, 0):c + h + 1] |= blocked
        rc = np.array(chosen)
    if max_points is not None:
        rc = rc[:max_points]
    return rc[:, ::-1].astype(float).reshape(-1, 2)


def interest_points(img, operator: str = "harris", size: int = 9, threshold=None, relative: float = 0.01,
                    max_points=None, border=None, **options):
    """Detect interest points with one operator of §5.8 followed by :func:`nonmax_suppression`.

    The responses: Harris R (5.8.4), Förstner w (5.8.7) where q ≥ ``q_min`` (default 0.5, not
    printed in the book), Moravec M (5.8.1), the FAST score (5.8.9) and σ²·|LoG| (5.8.13).

    Parameters
    ----------
    img : (rows, cols) array
        Grey values.
    operator : {"harris", "foerstner", "moravec", "fast", "log"}
        The detector.
    size, threshold, relative, max_points
        As in :func:`nonmax_suppression`.
    border : int, optional
        Margin without points; by default the operator's reach (window // 2 + 1, 3 for FAST,
        ⌈4σ⌉ for LoG).
    **options
        Passed to the operator (``window``, ``k``, ``gradient``, ``weight``, ``sigma``,
        ``threshold_fast`` → FAST's t, ``n``, ``q_min``). Förstner also takes ``selection``:
        ``"weight"`` (default: w where q ≥ q_min, q_min = 0.5) or ``"hanzl"`` — Hanzl's rule
        (§8.4, seed 002 lines 1666–1668): local minima of the size tr N/|N| below
        ``w_factor`` (0.3) × its median over the image, with roundness q > ``q_min`` (0.75);
        use ``relative=0`` to apply only that rule.

    Returns
    -------
    (n, 2) ndarray
        Points (x, y) = (col, row), strongest first; empty for a textureless image.

    Raises
    ------
    InputError
        Bad image, unknown operator or options.

    References
    ----------
    Chibunichev (2022), §5.7–§5.8, eqs. (5.8.1)–(5.8.13).

    Examples
    --------
    >>> f = np.zeros((31, 31)); f[10:21, 10:21] = 100.0
    >>> p = interest_points(f, "harris", relative=0.1)
    >>> p[np.lexsort(p.T[::-1])]
    array([[10., 10.],
           [10., 20.],
           [20., 10.],
           [20., 20.]])
    >>> interest_points(np.full((31, 31), 7.0), "foerstner").shape
    (0, 2)
    """
    opts = dict(options)
    if operator == "harris":
        R = harris(img, **opts)
        reach = opts.get("window", 5) // 2 + 1
    elif operator == "foerstner":
        selection = opts.pop("selection", "weight")
        if selection not in ("weight", "hanzl"):
            raise InputError(f"selection must be 'weight' or 'hanzl', got {selection!r}")
        q_min = float(opts.pop("q_min", 0.5 if selection == "weight" else 0.75))
        if not 0 <= q_min <= 1:
            raise InputError(f"q_min must lie in [0, 1], got {q_min}")
        w_factor = opts.pop("w_factor", 0.3) if selection == "hanzl" else None
        w, q = foerstner(img, **opts)
        if selection == "weight":
            R = np.where(q >= q_min, w, 0.0)
        else:                                        # Hanzl §8.4: size tr N/|N| < w_factor·median, q > q_min
            w_factor = _positive(w_factor, "w_factor")
            with np.errstate(divide="ignore"):
                ellipse = np.where(w > 0, 1.0 / np.where(w > 0, w, 1.0), np.inf)     # tr N/|N|
            w_p = w_factor * float(np.median(ellipse))
            R = np.where((q > q_min) & (ellipse < w_p), w, 0.0)  # local minima of the size = maxima of w
        reach = opts.get("window", 5) // 2 + 1
    elif operator == "moravec":
        R = moravec(img, **opts)
        reach = opts.get("window", 5) // 2
    elif operator == "fast":
        t = opts.pop("threshold_fast", 20.0)
        R = fast(img, t, **opts)
        reach = 3
    elif operator == "log":
        sigma = opts.pop("sigma", 2.0)
        R = sigma ** 2 * np.abs(log_filter(img, sigma, **opts))
        scale = float(np.abs(_image(img)).max())
        R[R <= 1e-9 * max(scale, 1e-300)] = 0.0          # round-off of the zero-sum mask on flat areas
        reach = int(np.ceil(4 * _positive(sigma, "sigma")))
    else:
        raise InputError(f"unknown operator {operator!r}; use harris, foerstner, moravec, fast or log")
    if border is None:
        border = reach
    pts = nonmax_suppression(R, size, threshold, relative, max_points, border)
    if len(pts) > 1:                                 # strongest first, ties by position
        vals = R[pts[:, 1].astype(int), pts[:, 0].astype(int)]
        pts = pts[np.lexsort((pts[:, 0], pts[:, 1], -vals))]
    return pts


# --- Hanzl §8.2 filters ----------------------------------------------------------------------------------
def _k(rows, factor=1.0):
    return factor * np.array(rows, dtype=float)


HANZL_KERNELS = {
    "laplace": _k([[0, 1, 0], [1, -4, 1], [0, 1, 0]]),
    "sharpen": _k([[0, -1, 0], [-1, 5, -1], [0, -1, 0]]),
    "sharpen_9": _k([[-1, -1, -1], [-1, 9, -1], [-1, -1, -1]]),
    "sharpen_17": _k([[-1, -1, -1], [-1, 17, -1], [-1, -1, -1]], 1.0 / 9.0),
    "laplace_8": _k([[1, 1, 1], [1, -8, 1], [1, 1, 1]]),
    "mean": _k(np.ones((3, 3)), 1.0 / 9.0),
    "binomial": _k([[1, 2, 1], [2, 4, 2], [1, 2, 1]], 1.0 / 16.0),
    "gradient_1": _k([[-1, 1, 1], [-1, -2, 1], [-1, 1, 1]]),
    "gradient_2": _k([[-1, -1, -1], [1, -2, 1], [1, 1, 1]]),
    "gradient_3": _k([[1, 1, 1], [1, -2, -1], [1, -1, -1]]),
    "gradient_4": _k([[-1, -1, 1], [-1, -2, 1], [1, 1, 1]]),
    "sobel_1": _k([[1, 0, -1], [2, 0, -2], [1, 0, -1]]),
    "sobel_2": _k([[1, 2, 1], [0, 0, 0], [-1, -2, -1]]),
    "prewitt_1": _k([[1, 0, -1], [1, 0, -1], [1, 0, -1]]),
    "prewitt_2": _k([[1, 1, 1], [0, 0, 0], [-1, -1, -1]]),
    "roberts_1": _k([[1, 0], [0, -1]]),
    "roberts_2": _k([[0, 1], [-1, 0]]),
}
"""The kernels of Hanzl §8.2 (seed 002 lines 1552–1612) as printed, with their factors: the Laplace
operator, the sharpening operators (identity − Laplace and the stronger variants), the mean and
binomial smoothing kernels, the four directional "gradient" kernels, and the pairs of Sobel,
Prewitt and Roberts (note: Hanzl's Sobel/Prewitt x kernels are the negatives of :data:`SOBEL_X`,
:data:`PREWITT_X`). Applied by correlation (no flip) with :func:`filter_image`."""

_ROUNDING = ("none", "half-up", "half-even")
_FILTER_BORDERS = ("constant", "nearest", "mirror", "reflect")


def _kernel(kernel):
    if isinstance(kernel, str):
        if kernel not in HANZL_KERNELS:
            raise InputError(f"unknown kernel {kernel!r}; use an array or one of {sorted(HANZL_KERNELS)}")
        return HANZL_KERNELS[kernel]
    try:
        K = np.asarray(kernel, dtype=float)
    except (TypeError, ValueError):
        raise InputError(f"kernel must be a 2-D array of numbers or a name, got {kernel!r}") from None
    if K.ndim != 2 or K.size == 0:
        raise InputError(f"kernel must be a non-empty 2-D array, got shape {K.shape}")
    if not np.all(np.isfinite(K)):
        raise InputError("kernel contains NaN or inf")
    return K


def _filter_border(border, cval):
    if border not in _FILTER_BORDERS:
        raise InputError(f"unknown border {border!r}; use one of {_FILTER_BORDERS}")
    return _checks.number(cval, "cval", out_of_range="{name} must be finite, got {value!r}")


def _round(g, rounding):
    if rounding not in _ROUNDING:
        raise InputError(f"unknown rounding {rounding!r}; use one of {_ROUNDING}")
    if rounding == "half-up":
        return np.floor(g + 0.5)
    if rounding == "half-even":
        return np.round(g)
    return g


def _pad(f, top, bottom, left, right, border, cval):
    if border == "constant":
        return np.pad(f, ((top, bottom), (left, right)), mode="constant", constant_values=cval)
    mode = _NP_PAD[border]
    if mode == "reflect" and min(f.shape) < 2:
        mode = "edge"
    return np.pad(f, ((top, bottom), (left, right)), mode=mode)


def filter_image(img, kernel, border: str = "nearest", cval: float = 0.0, rounding: str = "none"):
    """Apply a kernel by *correlation* (Hanzl's "convolution"), with an explicit border rule and rounding.

    ḡ(i, j) = Σ_{k=−m..m} Σ_{l=−n..n} g(i + k, j + l) · w(m + 1 + k, n + 1 + l) (Hanzl §8.2): the
    kernel is laid on the image without flipping it (the text's example z = am + bn + … + iu), so
    this is correlation (``scipy.ndimage.correlate``), not convolution; it matters for asymmetric
    kernels (Sobel, Prewitt, Roberts, the directional gradients). The output pixel is the one
    under the kernel element ((rows − 1)//2, (cols − 1)//2): the centre of an odd kernel, the
    top-left element of Roberts' 2×2 kernels ("pixel 1,1", Hanzl).

    Parameters
    ----------
    img : (rows, cols) array
        Grey values.
    kernel : 2-D array or str
        The weights w, or a name of :data:`HANZL_KERNELS`.
    border : {"nearest", "constant", "mirror", "reflect"}
        Pixels outside the image: the edge pixel repeated (replicate), ``cval``, reflected about
        the edge pixel, or about the edge (as in :mod:`scipy.ndimage`).
    cval : float
        The constant for ``border="constant"`` (e.g. the background grey value).
    rounding : {"none", "half-up", "half-even"}
        Rounding of the result to integer grey values: none, ⌊x + ½⌋ (the book's printed
        matrices) or numpy's round-half-to-even.

    Returns
    -------
    ndarray
        Same shape as ``img``.

    Raises
    ------
    InputError
        Not a finite 2-D image or kernel, unknown kernel name, border or rounding.

    References
    ----------
    Hanzl, Fotogrammetrie, Modul 01, §8.2 (seed 002 lines 1522–1612); Chibunichev (2022), §5.5,
    eq. (5.5.7) (the same correlation).

    Examples
    --------
    >>> g = np.full((5, 5), 2.0); g[1, 1], g[1, 3], g[2, 3], g[3, 2], g[3, 3] = 1, 3, 9, 4, 1
    >>> filter_image(g, "mean", border="nearest", rounding="half-up")[1:4, 1:4]
    array([[2., 3., 3.],
           [2., 3., 3.],
           [2., 3., 3.]])
    """
    f = _image(img)
    K = _kernel(kernel)
    cval = _filter_border(border, cval)
    ar, ac = (K.shape[0] - 1) // 2, (K.shape[1] - 1) // 2
    p = _pad(f, ar, K.shape[0] - 1 - ar, ac, K.shape[1] - 1 - ac, border, cval)
    rows, cols = f.shape
    g = np.zeros_like(f)
    for i in range(K.shape[0]):
        for j in range(K.shape[1]):
            if K[i, j] != 0.0:
                g += K[i, j] * p[i:i + rows, j:j + cols]
    return _round(g, rounding)


def median_filter(img, size: int = 3, border: str = "nearest", cval: float = 0.0):
    """Rank-order (median) filter: each pixel becomes the median of its size×size neighbourhood.

    Non-linear; removes isolated extreme values (Hanzl §8.2.2).

    Parameters
    ----------
    img : (rows, cols) array
        Grey values.
    size : int
        Odd window size (≥ 3).
    border : {"nearest", "constant", "mirror", "reflect"}
        Pixels outside the image, as in :func:`filter_image`.
    cval : float
        The constant for ``border="constant"``.

    Returns
    -------
    ndarray
        Same shape as ``img``.

    Raises
    ------
    InputError
        Not a finite 2-D image, an even or too small size, unknown border.

    References
    ----------
    Hanzl, Fotogrammetrie, Modul 01, §8.2.2 (seed 002 lines 1594–1602).

    Examples
    --------
    >>> g = np.full((5, 5), 2.0); g[1, 1], g[1, 3], g[2, 3], g[3, 2], g[3, 3] = 1, 3, 9, 4, 1
    >>> bool(np.all(median_filter(g) == 2.0))
    True
    """
    f = _image(img)
    size = _odd_window(size, "size")
    cval = _filter_border(border, cval)
    h = size // 2
    p = _pad(f, h, h, h, h, border, cval)
    win = np.lib.stride_tricks.sliding_window_view(p, (size, size))
    return np.median(win.reshape(f.shape + (size * size,)), axis=-1)


_EDGE_PAIRS = {"sobel": ("sobel_1", "sobel_2"), "prewitt": ("prewitt_1", "prewitt_2"),
               "roberts": ("roberts_1", "roberts_2")}


def edge_filter(img, operator: str = "sobel", border: str = "nearest", cval: float = 0.0):
    """Hanzl's gradient filters: |ḡ| = |g₁| + |g₂| of a pair of kernels (Roberts: max(|g₁|, |g₂|)).

    Parameters
    ----------
    img : (rows, cols) array
        Grey values.
    operator : {"sobel", "prewitt", "roberts"}
        The kernel pair of :data:`HANZL_KERNELS`.
    border, cval
        As in :func:`filter_image`.

    Returns
    -------
    ndarray
        The edge strength, same shape as ``img``.

    Raises
    ------
    InputError
        As :func:`filter_image`; an unknown operator.

    References
    ----------
    Hanzl, Fotogrammetrie, Modul 01, §8.2.2 (seed 002 lines 1604–1612); Chibunichev (2022),
    §5.5, eq. (5.5.3) (the L1 magnitude).

    Examples
    --------
    >>> f = np.zeros((5, 5)); f[:, 3:] = 10.0
    >>> edge_filter(f, "sobel")[2]
    array([ 0.,  0., 40., 40.,  0.])
    """
    if operator not in _EDGE_PAIRS:
        raise InputError(f"unknown operator {operator!r}; use one of {sorted(_EDGE_PAIRS)}")
    k1, k2 = _EDGE_PAIRS[operator]
    g1 = np.abs(filter_image(img, k1, border, cval))
    g2 = np.abs(filter_image(img, k2, border, cval))
    return np.maximum(g1, g2) if operator == "roberts" else g1 + g2


def second_difference_1d(profile, ends: str = "zero"):
    """1-D edge enhancement of Hanzl's Tab. 8.1: Δg″_i = g_{i−1} − 2g_i + g_{i+1}, enhanced g − Δg″.

    Parameters
    ----------
    profile : array_like (n,)
        Grey values g along a line, n ≥ 3.
    ends : {"zero", "nan"}
        Δg″ at the two ends (no neighbour on one side): 0 (as the book's table does at its last
        position, so that the end values stay unchanged) or NaN.

    Returns
    -------
    d2, enhanced : ndarray (n,)
        The second differences and g − Δg″.

    Raises
    ------
    InputError
        Not a finite 1-D array of at least 3 values, unknown ``ends``.

    References
    ----------
    Hanzl, Fotogrammetrie, Modul 01, §8.2.1, Tab. 8.1 (seed 002 lines 1536–1550).

    Examples
    --------
    >>> d2, e = second_difference_1d([5, 5, 5, 6, 8, 10, 12, 14, 15, 14])
    >>> d2.astype(int).tolist(), e.astype(int).tolist()
    ([0, 0, 1, 1, 0, 0, 0, -1, -2, 0], [5, 5, 4, 5, 8, 10, 12, 15, 17, 14])
    """
    try:
        g = np.asarray(profile, dtype=float)
    except (TypeError, ValueError):
        raise InputError(f"profile must be a 1-D array of numbers, got {profile!r}") from None
    if g.ndim != 1 or g.size < 3:
        raise InputError(f"profile must be a 1-D array of at least 3 values, got shape {g.shape}")
    if not np.all(np.isfinite(g)):
        raise InputError("profile contains NaN or inf")
    if ends not in ("zero", "nan"):
        raise InputError(f"ends must be 'zero' or 'nan', got {ends!r}")
    d2 = np.full(g.size, 0.0 if ends == "zero" else np.nan)
    d2[1:-1] = g[:-2] - 2.0 * g[1:-1] + g[2:]
    return d2, g - d2


# --- §5.9 descriptors ---------------------------------------------------------------------------------------
@dataclass(repr=False)
class DescriptorSet:
    """SIFT-style descriptors of a set of points (§5.9).

    Attributes
    ----------
    points : (n, 2) ndarray
        The points (x, y) = (col, row).
    orientation : (n,) ndarray
        Dominant gradient direction of each region (rad, from the +x axis towards +row).
    vectors : (n, d) ndarray
        Unit feature vectors, d = cells²·bins (128 for the book's 4×4×8); zero where not valid.
    valid : (n,) ndarray of bool
        False for textureless regions (no gradient): those are never matched.

    References
    ----------
    Chibunichev (2022), §5.9, Fig. 5.27; D. Lowe (2004), IJCV 60(2).

    Examples
    --------
    >>> d = DescriptorSet(np.zeros((1, 2)), np.zeros(1), np.zeros((1, 128)), np.array([False]))
    >>> len(d), d.vectors.shape[1]
    (1, 128)
    """

    points: np.ndarray
    orientation: np.ndarray
    vectors: np.ndarray
    valid: np.ndarray

    def __post_init__(self):
        try:
            self.points = np.asarray(self.points, dtype=float).reshape(-1, 2)
            self.orientation = np.asarray(self.orientation, dtype=float).reshape(-1)
            self.vectors = np.asarray(self.vectors, dtype=float)
            self.valid = np.asarray(self.valid, dtype=bool).reshape(-1)
        except (TypeError, ValueError) as exc:
            raise InputError(f"DescriptorSet: malformed arrays: {exc}") from exc
        n = len(self.points)
        if self.vectors.ndim != 2 or len(self.vectors) != n or len(self.orientation) != n or len(self.valid) != n:
            raise InputError(f"DescriptorSet: {n} points but orientation {self.orientation.shape}, "
                             f"vectors {self.vectors.shape}, valid {self.valid.shape}")
        if not (np.all(np.isfinite(self.points)) and np.all(np.isfinite(self.vectors))
                and np.all(np.isfinite(self.orientation))):
            raise InputError("DescriptorSet: NaN or inf values")

    def __len__(self):
        return len(self.points)

    def __repr__(self):
        return (f"DescriptorSet({len(self)} points, {self.vectors.shape[1]} features, "
                f"{int(np.sum(self.valid))} valid)")


def _points(points, what="points") -> np.ndarray:
    try:
        p = np.asarray(points, dtype=float)
    except (TypeError, ValueError) as exc:
        raise InputError(f"{what} must be an (n, 2) array of (x, y): {exc}") from exc
    if p.size == 0:
        return np.zeros((0, 2))
    if p.ndim == 1 and p.shape == (2,):
        p = p[None, :]
    if p.ndim != 2 or p.shape[1] != 2:
        raise InputError(f"{what} must be an (n, 2) array of (x, y), got shape {p.shape}")
    if not np.all(np.isfinite(p)):
        raise InputError(f"{what} contain NaN or inf")
    return p


def sift_descriptors(img, points, cells: int = 4, cell_size: int = 4, bins: int = 8,
                     rotate: bool = True, clip: float = 0.2):
    """SIFT-style descriptors of §5.9: a cells×cells array of 8-direction gradient histograms.

    For each point: (1) the dominant gradient direction θ — the peak of a 36-bin histogram of
    gradient directions weighted by magnitude and a Gaussian (σ = half the region), refined by a
    parabola; (2) a (cells·cell_size)² region (16×16 pixels for the book's 4×4 cells of 4×4 px)
    sampled bilinearly on a grid turned by θ; (3) in each cell a histogram of the gradient
    directions relative to θ in ``bins`` bins (linear interpolation between neighbouring bins),
    weighted by magnitude and a Gaussian; the 4×4×8 = 128 values are normalised, clipped at
    ``clip`` and normalised again (Lowe), which makes them invariant to linear grey changes.
    The book's keypoints carry no scale, so these descriptors are rotation- but not scale-invariant.

    Parameters
    ----------
    img : (rows, cols) array
        Grey values.
    points : (n, 2) array
        Points (x, y) = (col, row), e.g. from :func:`interest_points`.
    cells : int
        l of the book: the descriptor is l×l cells (4).
    cell_size : int
        Pixels per cell side (4: the region is 4l×4l = 16×16 px).
    bins : int
        Orientation bins per cell (8).
    rotate : bool
        Turn the region to the dominant direction (§5.9 step 2); False: upright descriptors.
    clip : float
        Clipping of the normalised vector, in (0, 1].

    Returns
    -------
    DescriptorSet
        Points, orientations, (n, cells²·bins) vectors and the validity mask.

    Raises
    ------
    InputError
        Bad image or points, NaN/inf, a region (turned by any angle) that leaves the image,
        bad sizes.

    References
    ----------
    Chibunichev (2022), §5.9, Fig. 5.27; D. Lowe (2004), "Distinctive image features from
    scale-invariant keypoints", IJCV 60(2), 91–110.

    Examples
    --------
    >>> rng = np.random.default_rng(0)
    >>> from scipy import ndimage as ndi
    >>> img = ndi.gaussian_filter(rng.normal(size=(64, 64)), 2.0)
    >>> d = sift_descriptors(img, [[32.0, 30.0], [20.0, 40.0]])
    >>> d.vectors.shape, bool(np.allclose(np.linalg.norm(d.vectors, axis=1), 1.0))
    ((2, 128), True)
    """
    f = _image(img)
    pts = _points(points)
    for name, v in (("cells", cells), ("cell_size", cell_size), ("bins", bins)):
        _checks.integer(v, name, message=_POSITIVE_INT)
    try:
        clip = float(clip)
    except (TypeError, ValueError) as exc:
        raise InputError(f"clip must be a number in (0, 1], got {clip!r}") from exc
    if not 0 < clip <= 1:
        raise InputError(f"clip must lie in (0, 1], got {clip}")
    half = cells * cell_size / 2.0
    reach = half * np.sqrt(2.0) + 1.0
    rows, cols = f.shape
    if len(pts):
        out = ((pts[:, 0] < reach) | (pts[:, 0] > cols - 1 - reach)
               | (pts[:, 1] < reach) | (pts[:, 1] > rows - 1 - reach))
        if np.any(out):
            raise InputError(f"{int(out.sum())} point(s) lie closer than {reach:.1f} px to the border: "
                             f"the turned {2 * half:.0f}×{2 * half:.0f} region leaves the image "
                             f"(first: {pts[np.argmax(out)].tolist()})")
    d = cells * cells * bins
    if not len(pts):
        return DescriptorSet(pts, np.zeros(0), np.zeros((0, d)), np.zeros(0, bool))
    gx = ndi.correlate(f, SOBEL_X / 8.0, mode="mirror")       # array frame: x right, y (row) down
    gy = ndi.correlate(f, -SOBEL_Y / 8.0, mode="mirror")
    # sample offsets (pixel centres of the region) in the local frame
    side = cells * cell_size
    u = np.arange(side) - half + 0.5
    V, U = np.meshgrid(u, u, indexing="ij")                    # V: local row offset, U: local column
    weight = np.exp(-(U ** 2 + V ** 2) / (2 * half ** 2))
    n = len(pts)
    x0 = pts[:, 0][:, None, None]
    y0 = pts[:, 1][:, None, None]

    def sample(a, X, Y):
        return ndi.map_coordinates(a, [Y.ravel(), X.ravel()], order=1, mode="nearest").reshape(X.shape)

    if rotate:
        X, Y = x0 + U, y0 + V
        ax, ay = sample(gx, X, Y), sample(gy, X, Y)
        mag = np.hypot(ax, ay) * weight
        ang = np.arctan2(ay, ax)
        nb = 36
        b = np.floor((ang % (2 * np.pi)) / (2 * np.pi) * nb).astype(int) % nb
        hist = np.zeros((n, nb))
        np.add.at(hist, (np.repeat(np.arange(n), side * side), b.reshape(n, -1).ravel()), mag.reshape(n, -1).ravel())
        hist = (np.roll(hist, 1, 1) + 2 * hist + np.roll(hist, -1, 1)) / 4.0        # circular smoothing
        k = hist.argmax(1)
        hm, h0, hp = hist[np.arange(n), (k - 1) % nb], hist[np.arange(n), k], hist[np.arange(n), (k + 1) % nb]
        den = hm - 2 * h0 + hp
        off = np.where(den < 0, 0.5 * (hm - hp) / np.where(den < 0, den, -1.0), 0.0)
        theta = ((k + 0.5 + off) * 2 * np.pi / nb + np.pi) % (2 * np.pi) - np.pi
    else:
        theta = np.zeros(n)
    c, s = np.cos(theta)[:, None, None], np.sin(theta)[:, None, None]
    X = x0 + c * U - s * V
    Y = y0 + s * U + c * V
    ax, ay = sample(gx, X, Y), sample(gy, X, Y)
    mag = np.hypot(ax, ay) * weight
    rel = (np.arctan2(ay, ax) - theta[:, None, None]) % (2 * np.pi)
    pos = rel / (2 * np.pi) * bins - 0.5
    lo = np.floor(pos).astype(int)
    frac = pos - lo
    cell = ((np.floor((V + half) / cell_size).astype(int) * cells) + np.floor((U + half) / cell_size).astype(int))
    cell = np.broadcast_to(cell, mag.shape)
    desc = np.zeros((n, cells * cells, bins))
    idx = np.repeat(np.arange(n), side * side)
    for shift, wgt in ((0, 1 - frac), (1, frac)):
        np.add.at(desc, (idx, cell.reshape(n, -1).ravel(), ((lo + shift) % bins).reshape(n, -1).ravel()),
                  (mag * wgt).reshape(n, -1).ravel())
    desc = desc.reshape(n, d)
    norm = np.linalg.norm(desc, axis=1)
    valid = norm > 1e-12 * max(float(np.abs(f).max()), 1.0)
    desc = np.where(valid[:, None], desc / np.where(valid, norm, 1.0)[:, None], 0.0)
    desc = np.minimum(desc, clip)
    norm = np.linalg.norm(desc, axis=1)
    desc = np.where(valid[:, None], desc / np.where(valid, norm, 1.0)[:, None], 0.0)
    return DescriptorSet(pts, np.where(valid, theta, 0.0), desc, valid)


def match_descriptors(d1, d2, ratio: float = 0.8, cross_check: bool = True):
    """Match descriptors by nearest neighbour with Lowe's ratio test (Fig. 5.28).

    A descriptor of set 1 is matched to its nearest neighbour in set 2 (Euclidean distance) if
    that distance is below ``ratio`` times the distance to the second nearest; with
    ``cross_check`` the match must also be mutual. Invalid (textureless) descriptors are never
    matched; with fewer than two valid descriptors in set 2 the ratio is undefined and nothing
    is matched.

    Parameters
    ----------
    d1, d2 : DescriptorSet or (n, d) arrays
        The two sets (same d).
    ratio : float
        Ratio threshold in (0, 1] (0.8 as Lowe).
    cross_check : bool
        Keep mutual nearest neighbours only.

    Returns
    -------
    (m, 2) ndarray of int
        Index pairs (i in set 1, j in set 2), by increasing distance.

    Raises
    ------
    InputError
        Different lengths d, NaN/inf, bad ratio.

    References
    ----------
    Chibunichev (2022), §5.9, Fig. 5.28; D. Lowe (2004), IJCV 60(2), §7.1.

    Examples
    --------
    >>> a = np.eye(4)[:3]
    >>> match_descriptors(a, np.eye(4)[[2, 0, 1, 3]])
    array([[0, 1],
           [1, 2],
           [2, 0]])
    """
    def vectors(d, what):
        if isinstance(d, DescriptorSet):
            return d.vectors, d.valid
        try:
            v = np.asarray(d, dtype=float)
        except (TypeError, ValueError) as exc:
            raise InputError(f"{what} must be descriptors: {exc}") from exc
        if v.ndim != 2:
            raise InputError(f"{what} must be an (n, d) array, got shape {v.shape}")
        if not np.all(np.isfinite(v)):
            raise InputError(f"{what} contain NaN or inf")
        return v, np.linalg.norm(v, axis=1) > 0

    v1, ok1 = vectors(d1, "descriptors 1")
    v2, ok2 = vectors(d2, "descriptors 2")
    if v1.shape[1] != v2.shape[1]:
        raise InputError(f"descriptor lengths differ: {v1.shape[1]} vs {v2.shape[1]}")
    try:
        ratio = float(ratio)
    except (TypeError, ValueError) as exc:
        raise InputError(f"ratio must be a number in (0, 1], got {ratio!r}") from exc
    if not 0 < ratio <= 1:
        raise InputError(f"ratio must lie in (0, 1], got {ratio}")
    i1 = np.flatnonzero(ok1)
    i2 = np.flatnonzero(ok2)
    if len(i1) == 0 or len(i2) < 2:
        return np.zeros((0, 2), int)
    a, b = v1[i1], v2[i2]
    D = np.sqrt(np.maximum((a * a).sum(1)[:, None] + (b * b).sum(1)[None, :] - 2 * a @ b.T, 0.0))
    order = np.argsort(D, axis=1, kind="stable")
    nn, second = order[:, 0], order[:, 1]
    rows = np.arange(len(i1))
    d_nn, d_2 = D[rows, nn], D[rows, second]
    keep = d_nn < ratio * d_2
    if cross_check:
        back = np.argmin(D, axis=0)
        keep &= back[nn] == rows
    sel = np.flatnonzero(keep)
    sel = sel[np.argsort(d_nn[sel], kind="stable")]
    return np.column_stack([i1[sel], i2[nn[sel]]]).astype(int).reshape(-1, 2)
