"""Digital image coordinates — Chapter 1, §1.10 (Наблюдение и измерение цифровых изображений).

Also Hanzl, Fotogrammetrie, Modul 01, §10.1 (seed 002 lines 1781–1787): the coordinates of a
normalised image, x_N = (λ/λ_N) R_N⁻¹ R x (:func:`normalized_image_coordinates`); its grey values
come from the original by :func:`bilinear` (Hanzl §9's a₀ + a₁X + a₂Y + a₃XY on a pixel cell).

A digital image is a matrix a_ij of brightness values; the row number i and the column number j
both start at 0. Two pixel coordinate systems are in use (Fig. 1.19 of the book):

* the **left-handed raster system**: origin at the top-left corner of the image, x along the rows
  (to the right), y down the columns; rows are counted from the top. Every file format and most
  image software use it, and so does a numpy array ``img[row, col]``;
* the **right-handed photogrammetric system**: origin at the bottom-left corner, x to the right,
  y up; rows are counted from the bottom.

The formulas (1.10.1)–(1.10.5) read the same in both systems as long as ``i`` is counted in the
system used; :func:`flip_rows` and :func:`flip_y` convert between the two.

Two choices of origin exist (the ``origin`` argument):

* ``"corner"`` — origin at the outer corner of the corner pixel, pixel centres at half-integers,
  (1.10.1)/(1.10.2);
* ``"center"`` — origin at the centre of the corner pixel, pixel centres at integers,
  (1.10.4)/(1.10.5) (Fig. 1.21).

:func:`bilinear` and :func:`shift_image` work on arrays and therefore take coordinates in the
raster system with the corner origin: the centre of ``img[r, c]`` is at ``(x_p, y_p) = (c + 0.5,
r + 0.5)``.
"""

from __future__ import annotations

import numpy as np

from .errors import DegenerateGeometryError, InputError
from .rotation import _numbers

__all__ = ["ORIGINS", "pixel_center", "subpixel_coordinates", "pixel_to_physical", "flip_rows", "flip_y",
           "normalized_image_coordinates",
           "bilinear", "shift_image"]

ORIGINS = ("corner", "center")


def _origin_offset(origin: str) -> float:
    if not isinstance(origin, str) or origin not in ORIGINS:
        raise InputError(f"origin must be 'corner' or 'center', got {origin!r}")
    return 0.5 if origin == "corner" else 0.0


def _finite(name, value):
    return _numbers(value, name)


def _rows(n_rows) -> int:
    arr = _numbers(n_rows, "n_rows")
    if arr.ndim != 0 or arr != np.round(arr) or arr < 1:
        raise InputError(f"n_rows must be a whole number ≥ 1, got {n_rows!r}")
    return int(arr)


def _index(name, value):
    if isinstance(value, (str, bytes)):
        raise InputError(f"{name} must be integers, got {value!r}")
    arr = np.asarray(value)
    if arr.dtype.kind == "f":
        if not np.all(np.isfinite(arr)):
            raise InputError(f"{name} contains NaN or inf")
        if not np.all(arr == np.round(arr)):
            raise InputError(f"{name} must be whole numbers, got {value!r}")
    elif arr.dtype.kind not in "iub":
        raise InputError(f"{name} must be integers, got {value!r}")
    if np.any(arr < 0):
        raise InputError(f"{name} must be ≥ 0 (rows and columns are counted from 0), got {value!r}")
    return arr.astype(float)


def _out(value):
    return float(value) if np.ndim(value) == 0 else value


def pixel_center(i, j, origin: str = "corner"):
    """Pixel coordinates of the centre of pixel a_ij, (1.10.1) or (1.10.4).

    Parameters
    ----------
    i, j : int or array of int
        Row and column number, counted from 0. In the right-handed system of the book the rows
        are counted from the bottom (use :func:`flip_rows` for a raster row index).
    origin : {"corner", "center"}
        ``"corner"``: x_p = j + 0.5, y_p = i + 0.5 (1.10.1);
        ``"center"``: x_p = j, y_p = i (1.10.4), origin at the centre of the corner pixel.

    Returns
    -------
    x_p, y_p : float or array, in pixels.

    Raises
    ------
    InputError
        Negative or fractional indices, NaN/inf, non-numbers, an unknown origin.

    References
    ----------
    Chibunichev (2022), §1.10, eqs. (1.10.1), (1.10.4), Figs. 1.19–1.21.

    Examples
    --------
    >>> pixel_center(2, 3), pixel_center(2, 3, origin="center")
    ((3.5, 2.5), (3.0, 2.0))
    """
    off = _origin_offset(origin)
    i, j = _index("row i", i), _index("column j", j)
    return _out(j + off), _out(i + off)


def subpixel_coordinates(i, j, i_sub, j_sub, n, origin: str = "corner"):
    """Pixel coordinates of element a'_{i'j'} of an n×-magnified display, (1.10.2) or (1.10.5).

    Each pixel a_ij of the original image is shown as an n×n block; element (i', j') of that
    block has the coordinates, in pixels of the original image,

    * ``"corner"``: x_p = j + (j' + 0.5)/n, y_p = i + (i' + 0.5)/n (1.10.2);
    * ``"center"``: x_p = (j − 0.5) + (j' + 0.5)/n, y_p = (i − 0.5) + (i' + 0.5)/n (1.10.5).

    ``i`` and ``i_sub`` are counted in the same direction (from the bottom in the right-handed
    system, from the top in the raster system).

    Parameters
    ----------
    i, j : int
        Row and column of the original pixel (from 0).
    i_sub, j_sub : int
        Row i' and column j' inside the n×n block, 0 ≤ i', j' < n.
    n : int
        Magnification, a positive integer.
    origin : {"corner", "center"}
        As for :func:`pixel_center`.

    Returns
    -------
    x_p, y_p : float or array
        In pixels of the original image.

    Raises
    ------
    InputError
        Bad indices (negative, fractional, i' or j' ≥ n), n < 1, NaN/inf, non-numbers.

    References
    ----------
    Chibunichev (2022), §1.10, eqs. (1.10.2), (1.10.5).

    Examples
    --------
    >>> subpixel_coordinates(0, 0, 0, 1, 2)
    (0.75, 0.25)
    """
    n_arr = np.asarray(n)
    if n_arr.dtype.kind not in "iu" and not (n_arr.dtype.kind == "f" and np.all(np.isfinite(n_arr))
                                             and np.all(n_arr == np.round(n_arr))):
        raise InputError(f"magnification n must be an integer, got {n!r}")
    if np.any(n_arr < 1):
        raise InputError(f"magnification n must be ≥ 1, got {n!r}")
    i_sub, j_sub = _index("sub-row i'", i_sub), _index("sub-column j'", j_sub)
    if np.any(i_sub >= n_arr) or np.any(j_sub >= n_arr):
        raise InputError(f"sub-element indices must be < n = {n!r}, got i'={i_sub}, j'={j_sub}")
    x0, y0 = pixel_center(i, j, origin)
    # the block of pixel (i, j) starts half a pixel before its centre
    x_p = np.asarray(x0) - 0.5 + (j_sub + 0.5) / n_arr
    y_p = np.asarray(y0) - 0.5 + (i_sub + 0.5) / n_arr
    return _out(x_p), _out(y_p)


def pixel_to_physical(x_p, y_p, pixel_size):
    """Physical coordinates from pixel coordinates, x_c = Δ·x_p, y_c = Δ·y_p (1.10.3), (1.11.5).

    ``pixel_size`` Δ is the side of the (square) pixel; the result is in its unit. The inverse,
    x_p = x̄/Δ of (1.11.5), is ``pixel_to_physical(x, y, 1/Δ)``.

    Parameters
    ----------
    x_p, y_p : float or array
        Pixel coordinates.
    pixel_size : float
        Δ, > 0.

    Returns
    -------
    x_c, y_c : float or array
        In the unit of Δ.

    Raises
    ------
    InputError
        NaN/inf, non-numbers, Δ ≤ 0.

    References
    ----------
    Chibunichev (2022), §1.10, eq. (1.10.3); §1.11, eq. (1.11.5).

    Examples
    --------
    >>> pixel_to_physical(100.5, 20.5, 0.01)
    (1.005, 0.205)
    """
    x_p, y_p = _finite("x_p", x_p), _finite("y_p", y_p)
    d = _finite("pixel size", pixel_size)
    if np.any(d <= 0):
        raise InputError(f"pixel size must be positive, got {pixel_size!r}")
    return _out(d * x_p), _out(d * y_p)


def flip_rows(i, n_rows):
    """Row index between the raster system (from the top) and the right-handed one (from the bottom).

    i' = n_rows − 1 − i. The map is its own inverse (an involution), so the same call converts
    either way.

    Parameters
    ----------
    i : int or array of int
        Row index, 0 ≤ i < n_rows.
    n_rows : int
        Number of rows of the image, ≥ 1.

    Returns
    -------
    int or ndarray
        The row index counted from the other side.

    Raises
    ------
    InputError
        Indices out of range, fractional or negative, n_rows < 1, non-numbers.

    References
    ----------
    Chibunichev (2022), §1.10, Fig. 1.19.

    Examples
    --------
    >>> flip_rows(0, 6)
    5
    """
    n_rows = _rows(n_rows)
    arr = _index("row i", i)
    if np.any(arr > n_rows - 1):
        raise InputError(f"row index out of range 0..{n_rows - 1}: {i!r}")
    out = (n_rows - 1 - arr).astype(int)
    return int(out) if out.ndim == 0 else out


def flip_y(y_p, n_rows, origin: str = "corner"):
    """y pixel coordinate between the raster and the right-handed system (Fig. 1.19 a ↔ b).

    ``"corner"``: y' = n_rows − y; ``"center"``: y' = (n_rows − 1) − y. An involution, like
    :func:`flip_rows`; x is the same in both systems.

    Parameters
    ----------
    y_p : float or array
        y pixel coordinate in one system.
    n_rows : int
        Number of rows of the image, ≥ 1.
    origin : {"corner", "center"}
        Where the pixel coordinates have their origin.

    Returns
    -------
    float or ndarray
        y in the other system.

    Raises
    ------
    InputError
        NaN/inf, non-numbers, n_rows < 1, an unknown origin.

    References
    ----------
    Chibunichev (2022), §1.10, Fig. 1.19.

    Examples
    --------
    >>> flip_y(0.5, 6)
    5.5
    """
    off = _origin_offset(origin)
    y_p = _finite("y_p", y_p)
    n_rows = _rows(n_rows)
    # corner: off = 0.5 → n_rows − y; center: off = 0 → (n_rows − 1) − y
    return _out(n_rows - 1 + 2 * off - y_p)


def _as_image(image):
    if isinstance(image, (str, bytes)):
        raise InputError(f"image must be an array of numbers, got {type(image).__name__}")
    img = np.asarray(image)
    if img.dtype.kind not in "biuf":
        img = _numbers(img, "image")
    if img.ndim not in (2, 3) or (img.ndim == 3 and img.shape[2] < 1):
        raise InputError(f"image must be (H, W) or (H, W, channels), got shape {img.shape}")
    if img.shape[0] < 2 or img.shape[1] < 2:
        raise InputError(f"bilinear interpolation needs at least 2×2 pixels, got {img.shape[:2]}")
    img = img.astype(float)
    if not np.all(np.isfinite(img)):
        raise InputError("image contains NaN or inf")
    return img


def _bilinear(img, x, y):
    """(1.10.7) at raster positions already checked to be inside the pixel-centre hull."""
    h, w = img.shape[:2]
    u, v = x - 0.5, y - 0.5                         # position in pixel-centre units
    c0 = np.clip(np.floor(u).astype(int), 0, w - 1)
    r0 = np.clip(np.floor(v).astype(int), 0, h - 1)
    c1, r1 = np.minimum(c0 + 1, w - 1), np.minimum(r0 + 1, h - 1)   # on the last row/column Δ = 0
    dx, dy = u - c0, v - r0                         # Δx_p, Δy_p of (1.10.7): offsets inside the cell
    if img.ndim == 3:
        dx, dy = dx[..., None], dy[..., None]
    D_K, D_M = img[r0, c0], img[r1, c0]             # K, M: one column
    D_L, D_N = img[r0, c1], img[r1, c1]             # L, N: the next column
    D_1 = D_K + (D_M - D_K) * dy
    D_2 = D_L + (D_N - D_L) * dy
    return D_1 + (D_2 - D_1) * dx


def bilinear(image, x_p, y_p):
    """Brightness at fractional pixel positions by bilinear interpolation (1.10.7).

    With K, M the two neighbouring pixels in one column and L, N those in the next column,

        D_1 = D_K + (D_M − D_K)·Δy_p,   D_2 = D_L + (D_N − D_L)·Δy_p,   D = D_1 + (D_2 − D_1)·Δx_p,

    where Δx_p, Δy_p are the offsets of the position from the centre of K inside the 2×2 cell
    (not the shift of (1.10.6), whose symbols the book reuses).

    Parameters
    ----------
    image : array (H, W) or (H, W, C)
        ``image[row, col]``; a colour image is interpolated channel by channel (R, G, B).
    x_p, y_p : float or array
        Positions in the **raster system with the corner origin**: the centre of ``image[r, c]``
        is at (c + 0.5, r + 0.5), y grows downwards. A position must lie within the hull of the
        pixel centres, 0.5 ≤ x_p ≤ W − 0.5 and 0.5 ≤ y_p ≤ H − 0.5.

    Returns
    -------
    float array of the broadcast shape of ``x_p, y_p`` (plus the channel axis for colour).

    Raises
    ------
    InputError
        A position outside the pixel centres, an image smaller than 2×2 or of a wrong shape,
        NaN/inf, non-numbers.

    References
    ----------
    Chibunichev (2022), §1.10, eq. (1.10.7).

    Examples
    --------
    >>> bilinear([[0.0, 10.0], [20.0, 30.0]], 1.0, 1.0)
    15.0
    """
    img = _as_image(image)
    xf, yf = _finite("x_p", x_p), _finite("y_p", y_p)
    try:
        x, y = np.broadcast_arrays(xf, yf)
    except ValueError:
        raise InputError(f"x_p and y_p have shapes {np.shape(x_p)}, {np.shape(y_p)} that do not broadcast") from None
    h, w = img.shape[:2]
    outside = (x < 0.5) | (x > w - 0.5) | (y < 0.5) | (y > h - 0.5)
    if np.any(outside):
        k = np.flatnonzero(outside.ravel())[0]
        raise InputError(
            f"position (x_p={x.ravel()[k]:g}, y_p={y.ravel()[k]:g}) is outside the pixel centres "
            f"[0.5, {w - 0.5}]×[0.5, {h - 0.5}] of a {h}×{w} image")
    out = _bilinear(img, x, y)
    return float(out) if out.ndim == 0 else out


def shift_image(image, dx_p, dy_p, fill=np.nan):
    """Resample an image moved by (Δx_p, Δy_p) under a fixed measuring mark, (1.10.6)–(1.10.7).

    Pixel i of the new fragment, centred at (x'_pi, y'_pi), takes its value from the original
    image at x_pi = x'_pi + Δx_p, y_pi = y'_pi + Δy_p (1.10.6), interpolated by (1.10.7). A point
    that was at (x, y) in the original appears at (x − Δx_p, y − Δy_p) in the fragment, so a mark
    fixed at the fragment pixel (x, y) now points at the original (x + Δx_p, y + Δy_p).

    Coordinates and shifts are in the raster system (x right, y down), in pixels.

    Parameters
    ----------
    image : array (H, W) or (H, W, C)
        The original image, ``image[row, col]``.
    dx_p, dy_p : float
        The shift Δx_p, Δy_p in pixels.
    fill : float or None
        Value of fragment pixels whose source lies outside the original pixel centres; ``None``
        raises :class:`InputError` instead.

    Returns
    -------
    ndarray
        The resampled fragment, of the shape of ``image``.

    Raises
    ------
    InputError
        NaN/inf, non-numbers, a bad image, or (with ``fill=None``) a shift leaving the image.

    References
    ----------
    Chibunichev (2022), §1.10, eqs. (1.10.6)–(1.10.7).

    Examples
    --------
    >>> shift_image([[0.0, 10.0], [20.0, 30.0]], 0.5, 0.0)
    array([[ 5., nan],
           [25., nan]])
    """
    img = _as_image(image)
    dx, dy = _finite("dx_p", dx_p), _finite("dy_p", dy_p)
    if dx.ndim or dy.ndim:
        raise InputError("the shift dx_p, dy_p must be two numbers")
    dx, dy = float(dx), float(dy)
    if fill is not None:
        fill_arr = _numbers(fill, "fill") if not (isinstance(fill, float) and np.isnan(fill)) else np.asarray(fill)
        if fill_arr.ndim:
            raise InputError("fill must be one number or None")
        fill = float(fill_arr)
    h, w = img.shape[:2]
    yy, xx = np.mgrid[0:h, 0:w] + 0.5
    xs, ys = xx + dx, yy + dy                       # (1.10.6)
    inside = (xs >= 0.5) & (xs <= w - 0.5) & (ys >= 0.5) & (ys <= h - 0.5)
    if fill is None and not np.all(inside):
        raise InputError(f"a shift of ({dx:g}, {dy:g}) px moves part of the fragment outside the image")
    out = np.full(img.shape, np.nan if fill is None else float(fill))
    out[inside] = _bilinear(img, xs[inside], ys[inside])
    return out


def normalized_image_coordinates(xy, c: float, rotation, rotation_n, c_n=None):
    """Image coordinates on a normalised image: x_N = (λ/λ_N) R_N⁻¹ R x, x = (x, y, −c).

    From X = X₀ + λ R x = X₀ + λ_N R_N x_N (same projection centre): the ray of the original
    image turned into the normalised image's frame, scaled so that its third component is −c_N.
    A projective (homography) relation between the two images.

    Parameters
    ----------
    xy : array_like (n, 2) or (2,)
        Image coordinates (x, y) relative to the principal point, mm.
    c : float
        Camera constant of the original image, mm.
    rotation, rotation_n : (3, 3) array_like
        R (original image → object) and R_N (normalised image → object), orthonormal.
    c_n : float, optional
        Camera constant of the normalised image (default ``c``).

    Returns
    -------
    ndarray (n, 2) or (2,)
        (x_N, y_N), mm.

    Raises
    ------
    InputError
        Non-finite or wrongly shaped input, c ≤ 0, a matrix that is not a rotation.
    DegenerateGeometryError
        A ray parallel to the normalised image plane (λ/λ_N undefined) or pointing behind it.

    References
    ----------
    Hanzl, Fotogrammetrie, Modul 01, §10.1 (seed 002 lines 1781–1787); Chibunichev (2022), §5.6
    and §6.1 (epipolar images, :func:`photolib.epipolar.rectify_pair`).

    Examples
    --------
    >>> normalized_image_coordinates([10.0, -5.0], 150.0, np.eye(3), np.eye(3)).tolist()
    [10.0, -5.0]
    """

    try:
        p = np.asarray(xy, dtype=float)
        R = np.asarray(rotation, dtype=float)
        Rn = np.asarray(rotation_n, dtype=float)
    except (TypeError, ValueError):
        raise InputError("xy, rotation and rotation_n must be arrays of numbers") from None
    single = p.shape == (2,)
    pts = p.reshape(1, 2) if single else p
    if pts.ndim != 2 or pts.shape[1] != 2 or not np.all(np.isfinite(pts)):
        raise InputError(f"xy must be finite (x, y) pairs, got shape {p.shape}")
    for M, name in ((R, "rotation"), (Rn, "rotation_n")):
        if M.shape != (3, 3) or not np.all(np.isfinite(M)) or not np.allclose(M.T @ M, np.eye(3), atol=1e-9) \
                or np.linalg.det(M) < 0:
            raise InputError(f"{name} must be a 3×3 rotation matrix")
    cc = float(_finite("c", c))
    cn = cc if c_n is None else float(_finite("c_n", c_n))
    if not (cc > 0 and cn > 0):
        raise InputError(f"c and c_n must be positive, got {c!r}, {c_n!r}")
    rays = np.column_stack([pts, np.full(len(pts), -cc)])
    v = rays @ (Rn.T @ R).T                            # R_N⁻¹ R x
    if np.any(v[:, 2] >= -1e-12 * cc):
        raise DegenerateGeometryError("a ray is parallel to or behind the normalised image plane")
    out = -cn * v[:, :2] / v[:, 2:3]                   # λ/λ_N = −c_N / (R_N⁻¹ R x)_3
    return out[0] if single else out
