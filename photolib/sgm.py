"""Semi-global matching in image space and in object space — Chapter 6, §6.4–6.5.

§6.4 (image space, a rectified pair — the normal case of §2.5 — so that corresponding points lie
on the same row; the left pixel at column x matches the right pixel at x − p, p = x₁ − x₂):

* :func:`cost_volume` — the cost cube C(x, y, p) (6.4.1). The book prints the *signed* difference
  D¹ − D²; a cost must be the *absolute* difference |D¹(x, y) − D²(x − p, y)| (erratum, see
  ``textbook/ch06_sgm.toml``). Also the census transform with Hamming distance and 1 − NCC
  (the cost (6.5.5) of §6.5 used in image space). Public and reused by :mod:`photolib.mrf`.
* :func:`aggregate_costs` — the path costs L_r (6.4.3) along 8 (or 4, or 16) directions and
  their sum S (6.4.4), the approximate minimisation of the energy (6.4.2) with penalties P₁
  (|Δp| = 1) and P₂ (|Δp| > 1); :func:`path_cost` gives one L_r.
* :func:`winner_takes_all` (argmin of a volume, with parabola sub-pixel refinement),
  :func:`right_disparity`, :func:`left_right_check`, :func:`fill_invalid`,
  :func:`vertical_parallax` (a check that the pair is rectified) and the whole pipeline
  :func:`semi_global_matching` → :class:`SGMResult`.
* :func:`disparity_to_points` — the forward intersection of every matched pixel with the pair's
  orientation (:func:`photolib.image_pair.forward_intersection`, §2.4).

§6.5 (object space): :func:`voxel_cost_volume` — the cost (6.5.1) (absolute difference, min over
image pairs) or (6.5.5) (1 − NCC) of voxels (X, Y, Z) projected into ≥ 2 oriented images by the
collinearity equations (:func:`photolib.single_image.project`), and :func:`voxel_sgm` — paths
over X–Y (6.5.3), sum (6.5.4), Z = argmin.

The path recursion runs in numba kernels (:mod:`photolib._sgm_kernels`, compiled on first use);
there is no Python loop over pixels.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from . import _checks
from .errors import DegenerateGeometryError, InputError

__all__ = ["COSTS", "cost_volume", "census_transform", "aggregate_costs", "path_cost",
           "winner_takes_all", "right_disparity", "left_right_check", "fill_invalid",
           "vertical_parallax", "SGMResult", "semi_global_matching", "disparity_to_points",
           "voxel_cost_volume", "VoxelSGMResult", "voxel_sgm"]

COSTS = ("ad", "census", "ncc")

#: the 8 path directions r = (dy, dx) of (6.4.3): 4 axis and 4 diagonal neighbours
_DIRECTIONS = {
    8: ((0, 1), (0, -1), (1, 0), (-1, 0), (1, 1), (-1, -1), (1, -1), (-1, 1)),
    4: ((0, 1), (0, -1), (1, 0), (-1, 0)),
    2: ((0, 1), (0, -1)),
}

# default penalties (P1, P2) per cost, in the cost's units
_DEFAULT_PENALTIES = {"ad": (8.0, 64.0), "census": (8.0, 100.0), "ncc": (0.2, 1.6)}


def _kernels():
    from . import _sgm_kernels
    return _sgm_kernels


# --------------------------------------------------------------------------- validation
_IMAGE_MESSAGES = {"numeric": "{name} must be a 2-D numeric image",
                   "ndim": "{name} must be a 2-D grey image, got shape {shape}",
                   "small": "{name} is too small ({shape}); at least 2×2 pixels are needed",
                   "finite": "{name} has NaN or inf pixels"}


def _image(a, name):
    return _checks.image(a, name, 2, messages=_IMAGE_MESSAGES, reject=())


def _pair(left, right):
    left = _image(left, "left image")
    right = _image(right, "right image")
    if left.shape != right.shape:
        raise InputError(f"left and right images must have the same size, got {left.shape} and {right.shape}")
    return left, right


def _int(value, name, low=None):
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, np.integer, float, np.floating)):
        raise InputError(f"{name} must be a whole number, got {value!r}")
    if not np.isfinite(value) or value != int(value):
        raise InputError(f"{name} must be a whole number, got {value!r}")
    value = int(value)
    if low is not None and value < low:
        raise InputError(f"{name} must be ≥ {low}, got {value}")
    return value


def _positive(value, name, allow_zero=False):
    return _checks.number(value, name, True, allow_zero=allow_zero,
                          out_of_range="{name} must be ≥ 0, got {v}" if allow_zero else "{name} must be > 0, got {v}")


def _range(max_disparity, min_disparity, width):
    dmax = _int(max_disparity, "max_disparity")
    dmin = _int(min_disparity, "min_disparity")
    if dmax - dmin <= 0:
        raise InputError(f"the disparity range must be positive: max_disparity={dmax} ≤ min_disparity={dmin}")
    if dmin < 0:
        raise InputError(f"min_disparity must be ≥ 0 (left x ↔ right x − p, p ≥ 0), got {dmin}")
    if dmax >= width:
        raise InputError(f"max_disparity={dmax} is not smaller than the image width {width}")
    return dmax, dmin


def _window(window, name="window"):
    if np.ndim(window) == 0:
        window = (window, window)
    if len(window) != 2:
        raise InputError(f"{name} must be an odd size or (rows, cols), got {window!r}")
    rows, cols = (_int(w, name, 1) for w in window)
    if rows % 2 == 0 or cols % 2 == 0:
        raise InputError(f"{name} sizes must be odd, got {rows}×{cols}")
    return rows, cols


def _volume(volume, name="cost volume"):
    try:
        vol = np.asarray(volume, dtype=np.float32)
    except (TypeError, ValueError) as exc:
        raise InputError(f"{name} must be a numeric (rows, cols, disparities) array") from exc
    if vol.ndim != 3 or min(vol.shape) < 1:
        raise InputError(f"{name} must be a non-empty (rows, cols, disparities) array, got shape {vol.shape}")
    if not np.all(np.isfinite(vol)):
        raise InputError(f"{name} has NaN or inf entries")
    return np.ascontiguousarray(vol)


# --------------------------------------------------------------------------- §6.4 costs
def census_transform(image, window=5) -> np.ndarray:
    """Census transform: one bit per window pixel, set where it is darker than the centre.

    Parameters
    ----------
    image : (rows, cols) array
        Grey image.
    window : int or (int, int)
        Odd window size (rows, cols); at most 64 − 1 comparisons (e.g. 5×5, 7×7, 7×9).

    Returns
    -------
    numpy.ndarray
        uint64 bit strings, shape of the image; the border is edge-replicated.

    Raises
    ------
    InputError
        Not a 2-D finite image, an even window or one with more than 64 bits.

    References
    ----------
    Chibunichev (2022), §6.4 (the cost of (6.4.1) may be any dissimilarity); R. Zabih and
    J. Woodfill, "Non-parametric local transforms for computing visual correspondence", 1994.

    Examples
    --------
    >>> bits = census_transform(np.array([[0., 1, 2], [3, 4, 5], [6, 7, 8]]), 3)
    >>> int(bits[1, 1]) == 0b11110000     # the first four neighbours are darker
    True
    """
    image = _image(image, "image")
    rows, cols = _window(window)
    if rows * cols - 1 > 64:
        raise InputError(f"a {rows}×{cols} census window needs {rows * cols - 1} bits; at most 64 fit")
    hr, hc = rows // 2, cols // 2
    padded = np.pad(image, ((hr, hr), (hc, hc)), mode="edge")
    H, W = image.shape
    return _kernels().census(padded, H, W, rows, cols)


def _box(a, rows, cols):
    from scipy.ndimage import uniform_filter
    return uniform_filter(a, size=(rows, cols), mode="reflect")


def cost_volume(left, right, max_disparity, *, min_disparity=0, method="census", window=None) -> np.ndarray:
    """The matching-cost cube C(x, y, p) of a rectified pair, (6.4.1) with |·|.

    Entry ``[y, x, k]`` compares the left pixel (x, y) with the right pixel (x − p, y) at
    disparity p = ``min_disparity + k``. Where x − p falls outside the right image the entry
    holds the largest possible cost of the method (AD: the grey range of the pair; census: the
    number of bits; NCC: 2).

    Parameters
    ----------
    left, right : (rows, cols) arrays
        Rectified grey images of equal size, finite.
    max_disparity : int
        Largest disparity p (pixels), < width.
    min_disparity : int, optional
        Smallest disparity, ≥ 0 and < ``max_disparity``.
    method : {"ad", "census", "ncc"}
        ``"ad"``: |D¹(x, y) − D²(x − p, y)| (6.4.1) corrected, summed over ``window`` (default 1×1);
        ``"census"``: Hamming distance of census bit strings (default 5×5);
        ``"ncc"``: 1 − NCC over the window (6.5.5) (default 5×5), in [0, 2]; a window without
        texture in either image gets cost 1 (no information).
    window : int or (int, int), optional
        Odd window size (rows, cols).

    Returns
    -------
    numpy.ndarray
        float32 array (rows, cols, max_disparity − min_disparity + 1).

    Raises
    ------
    InputError
        Images of different sizes, NaN/inf pixels, not 2-D, a disparity range ≤ 0 or ≥ the
        width, an unknown method, an even window.

    References
    ----------
    Chibunichev (2022), §6.4, eq. (6.4.1) (erratum: absolute, not signed difference) and
    §6.5, eq. (6.5.5); H. Hirschmüller, "Stereo processing by semiglobal matching and mutual
    information", IEEE TPAMI 30(2), 2008.

    Examples
    --------
    >>> rng = np.random.default_rng(0)
    >>> right = rng.uniform(0, 255, (20, 40))
    >>> left = np.roll(right, 3, axis=1)            # left x ↔ right x − 3
    >>> C = cost_volume(left, right, 6, method="ad")
    >>> C.shape, int(np.argmin(C[10, 20]))
    ((20, 40, 7), 3)
    """
    left, right = _pair(left, right)
    H, W = left.shape
    dmax, dmin = _range(max_disparity, min_disparity, W)
    if method not in COSTS:
        raise InputError(f"unknown cost method {method!r}; use one of {COSTS}")
    D = dmax - dmin + 1
    if method == "census":
        rows, cols = _window(5 if window is None else window)
        bits = rows * cols - 1
        cl = census_transform(left, (rows, cols))
        cr = census_transform(right, (rows, cols))
        return _kernels().hamming_volume(cl, cr, D, dmin, np.float32(bits))
    rows, cols = _window((1 if method == "ad" else 5) if window is None else window)
    C = np.empty((H, W, D), np.float32)
    if method == "ad":
        fill = float(max(np.ptp(left), np.ptp(right), 1.0))
        for k in range(D):
            p = dmin + k
            diff = np.full((H, W), fill)
            diff[:, p:] = np.abs(left[:, p:] - right[:, :W - p])
            if rows * cols > 1:
                diff = _box(diff, rows, cols)
            C[:, :, k] = diff
        return C
    # 1 − NCC over the window (6.5.5)
    ml = _box(left, rows, cols)
    vl = np.maximum(_box(left * left, rows, cols) - ml * ml, 0.0)
    mr = _box(right, rows, cols)
    vr = np.maximum(_box(right * right, rows, cols) - mr * mr, 0.0)
    scale = max(np.ptp(left), np.ptp(right), 1.0)
    tiny = (1e-6 * scale) ** 2
    for k in range(D):
        p = dmin + k
        shifted = np.zeros_like(right)
        shifted[:, p:] = right[:, :W - p]
        ms = np.zeros_like(mr)
        ms[:, p:] = mr[:, :W - p]
        vs = np.zeros_like(vr)
        vs[:, p:] = vr[:, :W - p]
        cov = _box(left * shifted, rows, cols) - ml * ms
        denom = np.sqrt(vl * vs)
        ok = (vl > tiny) & (vs > tiny)
        ncc = np.where(ok, cov / np.where(ok, denom, 1.0), 0.0)
        cost = 1.0 - np.clip(ncc, -1.0, 1.0)
        cost[:, :p] = 2.0
        C[:, :, k] = cost
    return C


# --------------------------------------------------------------------------- §6.4 aggregation
def _penalties(P1, P2):
    P1 = _positive(P1, "P1", allow_zero=True)
    P2 = _positive(P2, "P2", allow_zero=True)
    if P2 < P1:
        raise InputError(f"P2 must not be smaller than P1 (large jumps cost more), got P1={P1}, P2={P2}")
    return P1, P2


def _guide(guide, shape, gamma):
    if gamma is None:
        return np.zeros((1, 1)), 0.0
    gamma = _positive(gamma, "p2_gamma")
    if guide is None:
        raise InputError("an intensity-adapted P2 (p2_gamma) needs the guide image")
    g = _image(guide, "guide image")
    if g.shape != shape:
        raise InputError(f"the guide image {g.shape} must have the volume's size {shape}")
    return g, gamma


def aggregate_costs(volume, P1, P2, *, paths=8, guide=None, p2_gamma=None) -> np.ndarray:
    """Aggregated cost S(x, y, p) = Σ_r L_r(x, y, p), (6.4.3)–(6.4.4).

    Each path cost follows L_r(x, y, p) = C(x, y, p) + min{L_r(x_r, y_r, p),
    L_r(x_r, y_r, p ∓ 1) + P₁, min_i L_r(x_r, y_r, i) + P₂} − min_k L_r(x_r, y_r, k), where
    (x_r, y_r) = (x, y) − r is the previous pixel on the path; a path starts at the image border
    with L_r = C.

    Parameters
    ----------
    volume : (rows, cols, n) array
        Cost volume, e.g. from :func:`cost_volume`, finite.
    P1, P2 : float
        Penalties (cost units) for a disparity change of 1 and of more than 1, 0 ≤ P1 ≤ P2.
    paths : {8, 4, 2}
        Number of path directions: 8 (the book: 4 axis + 4 diagonal neighbours), 4 or 2 (the
        row only, i.e. dynamic programming along epipolar lines).
    guide : (rows, cols) array, optional
        Grey image for the intensity-adapted P2.
    p2_gamma : float, optional
        If given, P2 on each step is max(P1, P2·γ/(γ + |ΔI|)), with ΔI the grey step of ``guide``
        between the pixel and its predecessor (smaller penalty across edges; Hirschmüller 2008).

    Returns
    -------
    numpy.ndarray
        float32 array of the volume's shape.

    Raises
    ------
    InputError
        A volume that is not 3-D or holds NaN/inf, negative penalties, P2 < P1, an unknown
        number of paths, a missing or mis-sized guide.

    References
    ----------
    Chibunichev (2022), §6.4, eqs. (6.4.2)–(6.4.4); Hirschmüller (2008).

    Examples
    --------
    >>> C = np.zeros((3, 4, 3), np.float32); C[..., 1] = -1; C[1, 1] = [0, 0.5, 0]
    >>> S = aggregate_costs(C, 1.0, 4.0)
    >>> int(C[1, 1].argmin()), int(S[1, 1].argmin())   # the neighbours pull the pixel to p = 1
    (0, 1)
    """
    vol = _volume(volume)
    P1, P2 = _penalties(P1, P2)
    if paths not in _DIRECTIONS:
        raise InputError(f"paths must be one of {sorted(_DIRECTIONS)}, got {paths!r}")
    g, gamma = _guide(guide, vol.shape[:2], p2_gamma)
    dirs = np.array(_DIRECTIONS[paths], np.int64)
    k = _kernels()
    if paths in (8, 4):
        # the same sums, all forward directions in one sweep and all backward ones in another
        return k.aggregate_sweeps(vol, paths == 8, P1, P2, g, gamma)
    return k.aggregate(vol, dirs, P1, P2, g, gamma)


def path_cost(volume, direction, P1, P2) -> np.ndarray:
    """One path cost L_r(x, y, p) of (6.4.3) for the direction r = (dx, dy).

    Parameters
    ----------
    volume : (rows, cols, n) array
        Cost volume.
    direction : (int, int)
        r = (dx, dy) with dx, dy ∈ {−1, 0, 1}, not both 0; the previous pixel is (x − dx, y − dy)
        (x along columns, y along rows).
    P1, P2 : float
        Penalties, 0 ≤ P1 ≤ P2.

    Returns
    -------
    numpy.ndarray
        float32 array of the volume's shape.

    Raises
    ------
    InputError
        A bad volume, penalties or direction.

    References
    ----------
    Chibunichev (2022), §6.4, eq. (6.4.3).

    Examples
    --------
    >>> C = np.array([[[0., 3.], [3., 0.], [0., 3.]]], np.float32)   # one row, 2 disparities
    >>> path_cost(C, (1, 0), 1.0, 2.0)[0]
    array([[0., 3.],
           [3., 1.],
           [1., 3.]], dtype=float32)
    """
    vol = _volume(volume)
    P1, P2 = _penalties(P1, P2)
    try:
        dx, dy = (int(v) for v in direction)
        ok = len(tuple(direction)) == 2 and all(v == int(v) for v in direction)
    except (TypeError, ValueError):
        ok = False
    if not ok or dx not in (-1, 0, 1) or dy not in (-1, 0, 1) or (dx == 0 and dy == 0):
        raise InputError(f"direction must be (dx, dy) with entries in {{−1, 0, 1}}, not both 0, got {direction!r}")
    return _kernels().single_path(vol, dy, dx, P1, P2, np.zeros((1, 1)), 0.0)


# --------------------------------------------------------------------------- disparity selection
_SUBPIXEL = {False: 0, None: 0, True: 1, "parabola": 1, "vfit": 2}


def _subpixel_mode(subpixel):
    try:
        return _SUBPIXEL[subpixel]
    except (KeyError, TypeError):
        raise InputError(f"subpixel must be True/'parabola', 'vfit' or False, got {subpixel!r}") from None


def winner_takes_all(volume, *, min_disparity=0, subpixel=True) -> np.ndarray:
    """Disparity of least cost per pixel (argmin over p), with sub-pixel refinement.

    The parabola through the costs at p − 1, p, p + 1 has its vertex at
    p + (C₋ − C₊) / (2(C₋ − 2C₀ + C₊)) (the 3-point form of (5.1.3)–(5.1.5)); the equiangular
    ("V") fit, better suited to costs with a V-shaped minimum (AD, census), at
    p + (C₋ − C₊) / (2(max(C₋, C₊) − C₀)). Either is applied where the minimum is interior and
    the curvature positive, and clipped to ±0.5.

    Parameters
    ----------
    volume : (rows, cols, n) array
        Cost (C) or aggregated cost (S) volume.
    min_disparity : int, optional
        The disparity of index 0.
    subpixel : {True, "parabola", "vfit", False}, optional
        Refinement: the parabola (True), the equiangular fit, or none.

    Returns
    -------
    numpy.ndarray
        float64 disparities (rows, cols).

    Raises
    ------
    InputError
        A volume that is not 3-D or holds NaN/inf, an unknown sub-pixel method.

    References
    ----------
    Chibunichev (2022), §6.4 (argmin of S, Fig. 6.6 б for WTA on C); §5.1, eqs. (5.1.3)–(5.1.5).

    Examples
    --------
    >>> C = np.array([[[4., 1., 2., 9.]]])
    >>> winner_takes_all(C, min_disparity=10)
    array([[11.25]])
    >>> winner_takes_all(C, min_disparity=10, subpixel="vfit")
    array([[11.33333333]])
    """
    vol = _volume(volume)
    dmin = _int(min_disparity, "min_disparity")
    disp = _kernels().wta_subpixel(vol, _subpixel_mode(subpixel))
    return disp + dmin


def right_disparity(volume, *, min_disparity=0) -> np.ndarray:
    """Disparity map of the right image taken from the left image's volume.

    The right pixel (x_r, y) at disparity p is the left pixel (x_r + p, y), so
    p_right(x_r, y) = argmin_p S(x_r + p, y, p) (Hirschmüller 2008, §2.4); no second matching run.

    Parameters
    ----------
    volume : (rows, cols, n) array
        Aggregated (or raw) cost volume of the left image.
    min_disparity : int, optional
        The disparity of index 0.

    Returns
    -------
    numpy.ndarray
        float64 integer disparities of the right image, NaN where no disparity fits the image.

    Raises
    ------
    InputError
        A bad volume.

    References
    ----------
    Chibunichev (2022), §6.4; Hirschmüller (2008).

    Examples
    --------
    >>> S = np.ones((1, 4, 2)); S[0, :, 1] = 0     # everything at p = 1
    >>> right_disparity(S)
    array([[1., 1., 1., 0.]])
    """
    vol = _volume(volume)
    dmin = _int(min_disparity, "min_disparity")
    if dmin != 0:
        H, W, D = vol.shape
        shifted = np.full((H, W, D), np.inf, np.float32)
        for k in range(D):
            p = dmin + k
            if p < W:
                shifted[:, :W - p, k] = vol[:, p:, k]
        # shifted[y, xr, k] = S(xr + p, y): argmin over k, skipping impossible entries
        best = np.argmin(shifted, axis=2)
        out = (best + dmin).astype(np.float64)
        out[~np.isfinite(np.min(shifted, axis=2))] = np.nan
        return out
    idx = _kernels().right_argmin(vol)
    return np.where(idx >= 0, idx, np.nan).astype(np.float64)


def left_right_check(disparity_left, disparity_right, tolerance=1.0) -> np.ndarray:
    """Left–right consistency: NaN where the right image's disparity disagrees.

    The left pixel (x, y) with disparity p is kept when |p − p_right(round(x − p), y)| ≤
    ``tolerance``; occluded pixels (seen only by the left camera) fail the test.

    Parameters
    ----------
    disparity_left, disparity_right : (rows, cols) arrays
        Disparity maps of the left and right image (NaN = invalid).
    tolerance : float
        Largest accepted disagreement (px), ≥ 0.

    Returns
    -------
    numpy.ndarray
        The left disparities with NaN where the check fails or the partner is outside.

    Raises
    ------
    InputError
        Maps of different shapes, not 2-D, inf values, a negative tolerance.

    References
    ----------
    Chibunichev (2022), §6.4; Hirschmüller (2008), §2.5 (consistency check).

    Examples
    --------
    >>> dl = np.array([[0., 1., 1., 3.]]); dr = np.array([[1., 1., 1., 1.]])
    >>> left_right_check(dl, dr)
    array([[ 0.,  1.,  1., nan]])
    """
    try:
        dl = np.asarray(disparity_left, dtype=np.float64)
        dr = np.asarray(disparity_right, dtype=np.float64)
    except (TypeError, ValueError) as exc:
        raise InputError("disparity maps must be numeric arrays") from exc
    if dl.ndim != 2 or dl.shape != dr.shape:
        raise InputError(f"disparity maps must be 2-D of one shape, got {dl.shape} and {dr.shape}")
    if np.any(np.isinf(dl)) or np.any(np.isinf(dr)):
        raise InputError("disparity maps must not hold inf (use NaN for invalid pixels)")
    tolerance = _positive(tolerance, "tolerance", allow_zero=True)
    H, W = dl.shape
    x = np.arange(W)[None, :]
    xr = np.round(x - np.nan_to_num(dl, nan=1e9)).astype(np.int64)
    inside = (xr >= 0) & (xr < W) & np.isfinite(dl)
    partner = np.take_along_axis(dr, np.clip(xr, 0, W - 1), axis=1)
    ok = inside & (np.abs(dl - partner) <= tolerance)
    return np.where(ok, dl, np.nan)


def fill_invalid(disparity) -> np.ndarray:
    """Fill NaN disparities with the smaller of the nearest valid ones left and right in the row.

    Invalid pixels are mostly occlusions, which belong to the background (the smaller
    disparity); rows without any valid pixel stay NaN.

    Parameters
    ----------
    disparity : (rows, cols) array
        Disparities with NaN where invalid.

    Returns
    -------
    numpy.ndarray
        The filled map.

    Raises
    ------
    InputError
        Not 2-D or holding inf.

    References
    ----------
    Chibunichev (2022), §6.4; Hirschmüller (2008), §2.8 (occlusion filling).

    Examples
    --------
    >>> fill_invalid(np.array([[5., np.nan, np.nan, 2., np.nan]]))
    array([[5., 2., 2., 2., 2.]])
    """
    try:
        d = np.asarray(disparity, dtype=np.float64)
    except (TypeError, ValueError) as exc:
        raise InputError("disparity must be a numeric array") from exc
    if d.ndim != 2 or d.size == 0:
        raise InputError(f"disparity must be a non-empty 2-D map, got shape {d.shape}")
    if np.any(np.isinf(d)):
        raise InputError("disparity must not hold inf (use NaN for invalid pixels)")
    return _kernels().fill_rows(np.ascontiguousarray(d))


def vertical_parallax(left, right, max_disparity=None, *, search=3) -> np.ndarray:
    """Residual vertical parallax of a pair in its left and right halves (px).

    For every row offset dy = −``search`` … ``search`` the census cost (5×5 Hamming distance) of
    the left pixel (x, y) and the right pixel (x − p, y + dy) is minimised over p and averaged
    over each half of the image; the dy of least mean cost, refined by a parabola, is the
    vertical parallax there. A rectified (epipolar, §5.6) pair gives |dy| < 1 in both halves; a
    vertical shift gives equal non-zero values, a rotation (κ difference) opposite ones. A value
    of ±``search`` means "at least that much".

    Parameters
    ----------
    left, right : (rows, cols) arrays
        Grey images of equal size (at least 16×16).
    max_disparity : int, optional
        Largest disparity searched (default: a quarter of the width).
    search : int, optional
        Largest row offset tried (px), ≥ 1.

    Returns
    -------
    numpy.ndarray
        (2,) the offsets of the left and right halves, pixels (right row = left row + dy).

    Raises
    ------
    InputError
        Bad or mismatched images, a bad range.
    DegenerateGeometryError
        Textureless images (no cost minimum to measure).

    References
    ----------
    Chibunichev (2022), §5.6 (normal images: the search runs along rows) and §6.4 (SGM needs
    transformed images).

    Examples
    --------
    >>> rng = np.random.default_rng(1)
    >>> right = rng.uniform(0, 255, (64, 96))
    >>> np.round(vertical_parallax(np.roll(right, 4, axis=1), right), 1) + 0.0
    array([0., 0.])
    >>> np.round(vertical_parallax(np.roll(right, (2, 4), axis=(0, 1)), right), 1) + 0.0
    array([-2., -2.])
    """
    left, right = _pair(left, right)
    H, W = left.shape
    if H < 16 or W < 16:
        raise InputError(f"the rectification check needs at least 16×16 pixels, got {left.shape}")
    search = _int(search, "search", 1)
    if 2 * search + 4 > H:
        raise InputError(f"search={search} is too large for {H} rows")
    dmax = max(W // 4, 1) if max_disparity is None else _int(max_disparity, "max_disparity", 1)
    if dmax >= W // 2:
        dmax = W // 2 - 1
    if np.ptp(left) == 0 or np.ptp(right) == 0:
        raise DegenerateGeometryError("a textureless image: the vertical parallax cannot be measured")
    cl = census_transform(left, 5)
    cr = census_transform(right, 5)
    rows = np.arange(search, H - search)
    rows = rows[:: max(1, rows.size // 24)]
    half = W // 2
    prof = np.empty((2 * search + 1, 2))
    k = _kernels()
    for i, dy in enumerate(range(-search, search + 1)):
        C = k.hamming_volume(np.ascontiguousarray(cl[rows]), np.ascontiguousarray(cr[rows + dy]),
                             dmax + 1, 0, np.float32(24))
        m = C.min(axis=2)[:, dmax:]
        cols = np.arange(dmax, W)
        prof[i, 0] = m[:, cols < max(half, dmax + 1)].mean() if np.any(cols < half) else m.mean()
        prof[i, 1] = m[:, cols >= half].mean()
    if np.ptp(prof) == 0:
        raise DegenerateGeometryError("no cost minimum over the row offsets: textureless or repetitive images")
    out = []
    for j in range(2):
        p = prof[:, j]
        i = int(np.argmin(p))
        delta = 0.0
        if 0 < i < p.size - 1:
            curv = p[i - 1] - 2 * p[i] + p[i + 1]
            if curv > 0:
                delta = 0.5 * (p[i - 1] - p[i + 1]) / curv
        out.append(i - search + delta)
    return np.array(out)


# --------------------------------------------------------------------------- the pipeline
@dataclass(frozen=True)
class SGMResult:
    """Result of :func:`semi_global_matching`.

    Attributes
    ----------
    disparity : numpy.ndarray
        Left disparities p = x₁ − x₂ (px, float), NaN where invalid (unless filled).
    invalid : numpy.ndarray
        Boolean mask of the pixels that failed the left–right check (before any filling).
    disparity_right : numpy.ndarray
        Integer disparities of the right image (from the same aggregated volume).
    wta : numpy.ndarray or None
        Winner-takes-all disparities on the raw cost C (Fig. 6.6 б), if asked for
        (``return_wta=True``), for comparison.
    min_disparity, max_disparity : int
        The search range.

    References
    ----------
    Chibunichev (2022), §6.4.

    Examples
    --------
    >>> rng = np.random.default_rng(0); right = rng.uniform(0, 255, (24, 48))
    >>> r = semi_global_matching(np.roll(right, 2, axis=1), right, 5, check_rectified=False)
    >>> float(np.nanmedian(r.disparity)), r.disparity.shape
    (2.0, (24, 48))
    """

    disparity: np.ndarray
    invalid: np.ndarray
    disparity_right: np.ndarray
    wta: np.ndarray
    min_disparity: int
    max_disparity: int


def _median(d, size):
    from scipy.ndimage import median_filter
    return median_filter(d, size=size, mode="nearest")


def semi_global_matching(left, right, max_disparity, *, min_disparity=0, cost="census", window=None,
                         P1=None, P2=None, p2_gamma=None, paths=8, subpixel=True, median=3,
                         lr_tolerance=1.0, fill=False, check_rectified=True,
                         rectified_tolerance=1.0, return_wta=False) -> SGMResult:
    """Dense disparities of a rectified pair by semi-global matching, §6.4.

    Cost cube (6.4.1) → path costs along ``paths`` directions (6.4.3) → sum (6.4.4) → argmin
    with parabola sub-pixel refinement → optional median filter → left–right check (NaN) →
    optional filling of the invalid pixels from the background side of their row.

    Parameters
    ----------
    left, right : (rows, cols) arrays
        Rectified (epipolar) grey images of equal size: the left pixel (x, y) is seen at
        (x − p, y) in the right image.
    max_disparity : int
        Largest disparity searched (px).
    min_disparity : int, optional
        Smallest disparity, ≥ 0.
    cost : {"census", "ad", "ncc"}
        Matching cost, see :func:`cost_volume`; ``window`` as there.
    window : int or (int, int), optional
        Cost window.
    P1, P2 : float, optional
        Penalties in cost units; defaults per cost: census (8, 100), AD (8, 64), NCC (0.2, 1.6).
    p2_gamma : float, optional
        Adapt P2 to the left image's grey steps (see :func:`aggregate_costs`).
    paths : {8, 4, 2}
        Number of path directions.
    subpixel : {True, "parabola", "vfit", False}
        Sub-pixel refinement (see :func:`winner_takes_all`).
    median : int or None
        Size of the median filter applied to the disparities (None or 1: none).
    lr_tolerance : float or None
        Tolerance of the left–right check (None: no check).
    fill : bool
        Fill invalid pixels with :func:`fill_invalid`.
    check_rectified : bool
        Measure the vertical parallax (:func:`vertical_parallax`) first and refuse a pair that
        is not rectified.
    rectified_tolerance : float
        Largest accepted |vertical parallax| (px).
    return_wta : bool
        Also return the winner-takes-all disparities of the raw cost.

    Returns
    -------
    SGMResult

    Raises
    ------
    InputError
        Bad or mismatched images, NaN pixels, a disparity range ≤ 0, bad penalties or options,
        or a pair that is not rectified (vertical parallax above ``rectified_tolerance``).

    References
    ----------
    Chibunichev (2022), §6.4, eqs. (6.4.1)–(6.4.4); Hirschmüller (2008).

    Examples
    --------
    >>> rng = np.random.default_rng(3)
    >>> right = rng.uniform(0, 255, (30, 60))
    >>> left = np.roll(right, 4, axis=1)
    >>> result = semi_global_matching(left, right, 8, check_rectified=False)
    >>> float(np.nanmedian(result.disparity[:, 10:]))
    4.0
    """
    left, right = _pair(left, right)
    dmax, dmin = _range(max_disparity, min_disparity, left.shape[1])
    if cost not in COSTS:
        raise InputError(f"unknown cost {cost!r}; use one of {COSTS}")
    dP1, dP2 = _DEFAULT_PENALTIES[cost]
    P1 = dP1 if P1 is None else P1
    P2 = dP2 if P2 is None else P2
    P1, P2 = _penalties(P1, P2)
    _subpixel_mode(subpixel)
    if median not in (None, 0, 1):
        median = _int(median, "median", 1)
    if lr_tolerance is not None:
        lr_tolerance = _positive(lr_tolerance, "lr_tolerance", allow_zero=True)
    if check_rectified:
        tol = _positive(rectified_tolerance, "rectified_tolerance")
        if min(left.shape) >= 16:
            try:
                dy = vertical_parallax(left, right, dmax)
            except (DegenerateGeometryError, InputError):
                dy = np.zeros(2)
            if np.max(np.abs(dy)) > tol:
                raise InputError(
                    f"the pair is not rectified: vertical parallax ≈ {dy[0]:.1f} px (left half), "
                    f"{dy[1]:.1f} px (right half); SGM (§6.4) needs epipolar images — resample "
                    f"the pair to the normal case first (§5.6), or pass check_rectified=False")
    C = cost_volume(left, right, dmax, min_disparity=dmin, method=cost, window=window)
    wta = winner_takes_all(C, min_disparity=dmin, subpixel=subpixel) if return_wta else None
    S = aggregate_costs(C, P1, P2, paths=paths, guide=left if p2_gamma is not None else None,
                        p2_gamma=p2_gamma)
    disp = winner_takes_all(S, min_disparity=dmin, subpixel=subpixel)
    dright = right_disparity(S, min_disparity=dmin)
    if median not in (None, 0, 1):
        disp = _median(disp, median)
        ok = np.isfinite(dright)
        dright = np.where(ok, _median(np.where(ok, dright, 0.0), median), np.nan)
    if lr_tolerance is not None:
        disp = left_right_check(disp, dright, lr_tolerance)
    invalid = ~np.isfinite(disp)
    if fill and invalid.any():
        disp = fill_invalid(disp)
    return SGMResult(disp, invalid, dright, wta, dmin, dmax)


# --------------------------------------------------------------------------- points
def disparity_to_points(disparity, eo1, eo2, io, pixel_size, *, io2=None) -> np.ndarray:
    """Object points of every valid pixel of a disparity map, by forward intersection (§2.4).

    The left pixel (column u, row v) has book image coordinates (x₁, y₁) (origin at the image
    centre, y up, :func:`photolib.conventions.opencv_pixels_to_image`); its partner on the
    rectified right image is (x₁ − p·δ, y₁), δ the pixel size. Both rays are intersected with
    :func:`photolib.image_pair.forward_intersection`.

    Parameters
    ----------
    disparity : (rows, cols) array
        Disparities p (px), NaN where invalid.
    eo1, eo2 : photolib.camera.ExteriorOrientation
        Exterior orientation of the (rectified) left and right images.
    io : photolib.camera.InteriorOrientation
        Interior orientation of the left image (and of the right one unless ``io2``).
    pixel_size : float
        Pixel side (mm).
    io2 : photolib.camera.InteriorOrientation, optional
        Interior orientation of the right image.

    Returns
    -------
    numpy.ndarray
        (rows, cols, 3) object coordinates X, Y, Z, NaN where the disparity is invalid.

    Raises
    ------
    InputError
        A disparity map that is not 2-D or holds inf, a bad pixel size or orientation.
    DegenerateGeometryError
        No valid disparity, a zero base or parallel rays.
    PointBehindCameraError
        Rays that meet behind a camera (e.g. negative disparities in the normal case).

    References
    ----------
    Chibunichev (2022), §6.4 (a forward intersection per pixel gives the dense cloud);
    §2.4, eqs. (2.4.4), (2.4.9)–(2.4.12).

    Examples
    --------
    >>> from photolib.camera import ExteriorOrientation, InteriorOrientation
    >>> io = InteriorOrientation(100.0)
    >>> e1, e2 = ExteriorOrientation(0, 0, 1000), ExteriorOrientation(100, 0, 1000)
    >>> P = disparity_to_points(np.full((3, 3), 1000.0), e1, e2, io, 0.01)
    >>> np.round(P[1, 1], 6) + 0.0                  # Z = 1000 − f·B/(p·δ) = 0
    array([0., 0., 0.])
    """
    from .camera import ExteriorOrientation, InteriorOrientation
    from .conventions import opencv_pixels_to_image
    from .image_pair import forward_intersection

    try:
        d = np.asarray(disparity, dtype=np.float64)
    except (TypeError, ValueError) as exc:
        raise InputError("disparity must be a numeric array") from exc
    if d.ndim != 2 or d.size == 0:
        raise InputError(f"disparity must be a non-empty 2-D map, got shape {d.shape}")
    if np.any(np.isinf(d)):
        raise InputError("disparity must not hold inf (use NaN for invalid pixels)")
    if not isinstance(eo1, ExteriorOrientation) or not isinstance(eo2, ExteriorOrientation):
        raise InputError("eo1 and eo2 must be photolib.camera.ExteriorOrientation")
    if not isinstance(io, InteriorOrientation) or (io2 is not None and not isinstance(io2, InteriorOrientation)):
        raise InputError("io (and io2) must be photolib.camera.InteriorOrientation")
    pixel_size = _positive(pixel_size, "pixel_size")
    valid = np.isfinite(d)
    if not valid.any():
        raise DegenerateGeometryError("no valid disparity to intersect")
    rows, cols = np.nonzero(valid)
    uv1 = np.column_stack([cols, rows]).astype(float)
    xy1 = opencv_pixels_to_image(uv1, pixel_size, d.shape)
    xy2 = xy1.copy()
    xy2[:, 0] -= d[valid] * pixel_size
    pts = forward_intersection(xy1, xy2, eo1, eo2, io, io if io2 is None else io2)
    out = np.full(d.shape + (3,), np.nan)
    out[valid] = pts
    return out


# --------------------------------------------------------------------------- §6.5 voxels
def _grid_axis(values, name):
    try:
        a = np.asarray(values, dtype=np.float64)
    except (TypeError, ValueError) as exc:
        raise InputError(f"{name} must be a 1-D numeric array") from exc
    if a.ndim != 1 or a.size < 2:
        raise InputError(f"{name} must be a 1-D array of at least 2 values, got shape {a.shape}")
    if not np.all(np.isfinite(a)):
        raise InputError(f"{name} has NaN or inf values")
    step = np.diff(a)
    if not (np.all(step > 0) and np.allclose(step, step[0], rtol=1e-6, atol=0)):
        raise InputError(f"{name} must be increasing with a constant step")
    return a


def _sample(image, uv):
    from scipy.ndimage import map_coordinates
    H, W = image.shape
    u, v = uv[:, 0], uv[:, 1]
    inside = (u >= 0) & (u <= W - 1) & (v >= 0) & (v <= H - 1)
    vals = map_coordinates(image, [v, u], order=1, mode="nearest")
    return np.where(inside, vals, np.nan)


def voxel_cost_volume(images, orientations, io, pixel_size, X, Y, Z, *, cost="ad", window=3) -> np.ndarray:
    """The voxel cost C(X, Y, Z) from ≥ 2 oriented images, (6.5.1) or (6.5.5).

    Every voxel is projected into every image with the collinearity equations
    (:func:`photolib.single_image.project`) and its grey value is interpolated bilinearly.
    ``cost="ad"``: C = min over image pairs of |Dᵢ − Dⱼ| (6.5.1 with |·|, the erratum of
    (6.4.1)); ``cost="ncc"``: C = min over pairs of 1 − NCC over a ``window``×``window``
    neighbourhood of X–Y nodes at the same Z (6.5.5). Voxels seen by fewer than two images get
    the largest cost (AD: the images' grey range; NCC: 2).

    Parameters
    ----------
    images : sequence of (rows, cols) arrays
        At least two grey images (finite).
    orientations : sequence of photolib.camera.ExteriorOrientation
        Their exterior orientations.
    io : photolib.camera.InteriorOrientation or sequence of them
        Interior orientation(s); image coordinates have their origin at the image centre.
    pixel_size : float
        Pixel side (mm).
    X, Y, Z : 1-D arrays
        Node coordinates of the voxel grid (m), increasing with a constant step ΔX, ΔY, ΔZ.
    cost : {"ad", "ncc"}
        The cost.
    window : int
        Odd NCC window in X–Y nodes (ignored for AD).

    Returns
    -------
    numpy.ndarray
        float32 (len(Y), len(X), len(Z)).

    Raises
    ------
    InputError
        Fewer than 2 images, mismatched lists, bad images or grids, an unknown cost.
    PointBehindCameraError
        Voxels behind a camera.

    References
    ----------
    Chibunichev (2022), §6.5, eqs. (6.5.1), (6.5.5).

    Examples
    --------
    >>> from photolib.camera import ExteriorOrientation, InteriorOrientation
    >>> rng = np.random.default_rng(0); img = rng.uniform(0, 255, (50, 50))
    >>> eo = ExteriorOrientation(0, 0, 100)
    >>> C = voxel_cost_volume([img, img], [eo, eo], InteriorOrientation(10.0), 0.1,
    ...                       np.arange(-5, 6.0), np.arange(-5, 6.0), np.array([0.0, 1.0]))
    >>> C.shape, float(C.max())
    ((11, 11, 2), 0.0)
    """
    from .camera import ExteriorOrientation, InteriorOrientation
    from .conventions import image_to_opencv_pixels
    from .single_image import project

    if isinstance(images, np.ndarray) and images.ndim == 2:
        raise InputError("images must be a sequence of at least two images")
    try:
        images = [_image(im, f"image {i}") for i, im in enumerate(images)]
        orientations = list(orientations)
    except TypeError as exc:
        raise InputError("images and orientations must be sequences") from exc
    if len(images) < 2:
        raise InputError(f"the voxel cost needs at least 2 images, got {len(images)}")
    if len(orientations) != len(images):
        raise InputError(f"{len(images)} images but {len(orientations)} orientations")
    if not all(isinstance(e, ExteriorOrientation) for e in orientations):
        raise InputError("orientations must be photolib.camera.ExteriorOrientation")
    ios = list(io) if isinstance(io, (list, tuple)) else [io] * len(images)
    if len(ios) != len(images) or not all(isinstance(i, InteriorOrientation) for i in ios):
        raise InputError("io must be an InteriorOrientation or one per image")
    pixel_size = _positive(pixel_size, "pixel_size")
    X = _grid_axis(X, "X")
    Y = _grid_axis(Y, "Y")
    Z = _grid_axis(Z, "Z")
    if cost not in ("ad", "ncc"):
        raise InputError(f"voxel cost must be 'ad' (6.5.1) or 'ncc' (6.5.5), got {cost!r}")
    if cost == "ncc":
        w = _window(window)[0]
    GX, GY = np.meshgrid(X, Y)
    ny, nx, nz = Y.size, X.size, Z.size
    n = len(images)
    worst = 2.0 if cost == "ncc" else float(max(max(np.ptp(im) for im in images), 1.0))
    C = np.empty((ny, nx, nz), np.float32)
    for k, z in enumerate(Z):
        pts = np.column_stack([GX.ravel(), GY.ravel(), np.full(GX.size, z)])
        D = []
        for im, eo, i_o in zip(images, orientations, ios):
            xy = project(pts, eo, i_o)
            uv = image_to_opencv_pixels(xy, pixel_size, im.shape)
            D.append(_sample(im, uv).reshape(ny, nx))
        best = np.full((ny, nx), np.inf)
        for i in range(n):
            for j in range(i + 1, n):
                both = np.isfinite(D[i]) & np.isfinite(D[j])
                if cost == "ad":
                    c = np.abs(D[i] - D[j])
                else:
                    a = np.where(both, D[i], 0.0)
                    b = np.where(both, D[j], 0.0)
                    ma, mb = _box(a, w, w), _box(b, w, w)
                    va = np.maximum(_box(a * a, w, w) - ma * ma, 0.0)
                    vb = np.maximum(_box(b * b, w, w) - mb * mb, 0.0)
                    cov = _box(a * b, w, w) - ma * mb
                    ok = (va > 1e-9) & (vb > 1e-9)
                    c = 1.0 - np.where(ok, cov / np.sqrt(np.where(ok, va * vb, 1.0)), 0.0)
                c = np.where(both, c, np.inf)
                best = np.minimum(best, c)
        C[:, :, k] = np.where(np.isfinite(best), best, worst)
    return C


@dataclass(frozen=True)
class VoxelSGMResult:
    """Result of :func:`voxel_sgm`.

    Attributes
    ----------
    Z : numpy.ndarray
        Heights (len(Y), len(X)) in m: argmin over Z of S(X, Y, Z), parabola-refined.
    Z_wta : numpy.ndarray
        Heights by winner-takes-all on the raw voxel cost.
    X, Y, levels : numpy.ndarray
        The grid.

    References
    ----------
    Chibunichev (2022), §6.5, eqs. (6.5.3)–(6.5.4).

    Examples
    --------
    >>> VoxelSGMResult.__name__
    'VoxelSGMResult'
    """

    Z: np.ndarray
    Z_wta: np.ndarray
    X: np.ndarray
    Y: np.ndarray
    levels: np.ndarray


def voxel_sgm(images, orientations, io, pixel_size, X, Y, Z, *, cost="ad", window=3, P1=None, P2=None,
              paths=8, subpixel=True) -> VoxelSGMResult:
    """A regular DSM by semi-global matching in object space (voxels), §6.5.

    Voxel cost (6.5.1) or (6.5.5) from :func:`voxel_cost_volume`, path costs over the X–Y grid
    with Z levels as labels (6.5.3) (|Z − Z_q| counted in steps ΔZ), their sum (6.5.4), and for
    every node the Z of least aggregated cost.

    Parameters
    ----------
    images, orientations, io, pixel_size, X, Y, Z, cost, window
        As in :func:`voxel_cost_volume`.
    P1, P2 : float, optional
        Penalties for |ΔZ| = 1 step and > 1 step, in cost units; defaults: AD 0.02 and 0.2 of
        the images' grey range, NCC 0.05 and 0.5.
    paths : {8, 4, 2}
        Path directions over X–Y.
    subpixel : bool
        Parabola refinement of Z between levels.

    Returns
    -------
    VoxelSGMResult

    Raises
    ------
    InputError
        As :func:`voxel_cost_volume`, plus bad penalties.
    PointBehindCameraError
        Voxels behind a camera.

    References
    ----------
    Chibunichev (2022), §6.5, eqs. (6.5.1)–(6.5.5).

    Examples
    --------
    >>> from photolib.camera import ExteriorOrientation, InteriorOrientation
    >>> rng = np.random.default_rng(0); img = rng.uniform(0, 255, (50, 50))
    >>> eo = ExteriorOrientation(0, 0, 100)
    >>> r = voxel_sgm([img, img], [eo, eo], InteriorOrientation(10.0), 0.1,
    ...               np.arange(-5, 6.0), np.arange(-5, 6.0), np.array([0.0, 1.0, 2.0]))
    >>> r.Z.shape
    (11, 11)
    """
    Cv = voxel_cost_volume(images, orientations, io, pixel_size, X, Y, Z, cost=cost, window=window)
    if cost == "ad":
        grey = float(max(max(np.ptp(np.asarray(im, dtype=float)) for im in images), 1e-12))
        dP1, dP2 = 0.02 * grey, 0.2 * grey
    else:
        dP1, dP2 = 0.05, 0.5
    P1 = dP1 if P1 is None else P1
    P2 = dP2 if P2 is None else P2
    S = aggregate_costs(Cv, P1, P2, paths=paths)
    Z = np.asarray(Z, dtype=np.float64)
    dz = Z[1] - Z[0]
    z = Z[0] + dz * winner_takes_all(S, subpixel=subpixel)
    zw = Z[0] + dz * winner_takes_all(Cv, subpixel=subpixel)
    return VoxelSGMResult(z, zw, np.asarray(X, float), np.asarray(Y, float), Z)
