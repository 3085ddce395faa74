"""Counts, correction equations and accuracy checks of bundle blocks — Chapter 3, §3.5, §3.7.

§3.5 "Построение и уравнивание маршрутной и блочной фототриангуляции по методу связок" counts
unknowns and correction equations of a block and describes the structure of its correction and
normal equations. This module holds those algorithms for any :class:`photolib.synthetic.Block`:

* the counting formulas N = 6n + 3k (3.5.20) and M = 2m + 3c + 2i + l + 3s + 3j (3.5.21)
  (:func:`bundle_unknowns`, :func:`bundle_equations`) and their inputs read off a block
  (:func:`images_per_point`, :func:`block_counts`);
* the correction equations (3.5.2)/(3.5.3)/(3.5.17)/(3.5.18)/(3.5.19) built densely in the
  column order of fig. 3.11 (:func:`correction_equation_system`, :class:`BundleSystem`) and the
  structure of N = AᵀPA of fig. 3.12 (:func:`normal_matrix_structure`);
* accuracy of adjusted points against the truth (:func:`predicted_point_sigma` — m_j of (3.5.11)
  with σ₀, :func:`check_point_accuracy`).

§3.7 "Технология построения сетей фототриангуляции" quotes the Russian *Instruction on
photogrammetric works*. :func:`evaluate_regulations` (**our helper, not the book's**) compares an
adjustment's control and check-point discrepancies with the tolerances of 3.7.6;
:func:`check_height_factor` and :func:`free_strip_height_tolerance_um` evaluate 3.7.6/3.7.7 and
3.7.2. The tolerance numbers themselves are the caller's data (a mapping with the keys
:data:`TOLERANCE_NAMES`); the book layer passes the values transcribed in ``textbook/ch03.toml``.
The rebuilt blocks of figs. 3.10 and 3.13 are book content: ``photolib.book.ch03_layouts``.

Hanzl, Fotogrammetrie, Modul 01, §4.3 and §4.5 (seed 002 lines 742–744, 826) gives two empirical
accuracy rules of aerotriangulation, here as small functions: σ_XY ≈ 5 µm·m_s, σ_Z ≈ 0.005 % h
(:func:`at_accuracy_rule`) and INPHO's GNSS-supported AT m_XY = 1.5 m_s σ₀, m_Z = 2.2 m_s σ₀
(:func:`gnss_at_accuracy`). They are rules of thumb, not derived from the adjustment.

Units: image mm, object metres, angles radians.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from . import _checks
from .bundle import bundle_correction_equations
from .errors import InputError
from .lsq import block_equations_dense
from .synthetic import CONTROL, Block, footprint_visibility  # noqa: F401  (footprint_visibility: re-export)

__all__ = ["bundle_unknowns", "bundle_equations", "images_per_point", "block_counts", "BundleSystem",
           "correction_equation_system", "normal_matrix_structure", "predicted_point_sigma",
           "check_point_accuracy", "TOLERANCE_NAMES", "Criterion", "check_height_factor",
           "free_strip_height_tolerance_um", "evaluate_regulations", "at_accuracy_rule", "gnss_at_accuracy"]

EO_COLUMN_NAMES = ("X_S", "Y_S", "Z_S", "ω", "α", "κ")


def _nonneg_int(what, value) -> int:
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)):
        if not (isinstance(value, (float, np.floating)) and float(value).is_integer()):
            raise InputError(f"counts must be non-negative integers: {what} = {value!r}")
    if value < 0:
        raise InputError(f"counts must be non-negative: {what} = {value!r}")
    return int(value)


def _check_block(block):
    if not isinstance(block, Block):
        raise InputError(f"expected a photolib.synthetic.Block, got {type(block).__name__}")


# --- counting formulas (3.5.20), (3.5.21) --------------------------------------------------------
def bundle_unknowns(n: int, k: int) -> int:
    """Number of unknowns of the bundle method, N = 6n + 3k (3.5.20).

    Parameters
    ----------
    n : int
        Images (six exterior-orientation elements each).
    k : int
        Determined points (with weighted control (3.5.17): including the control points).

    Returns
    -------
    int
        N.

    Raises
    ------
    InputError
        A negative or non-integer count.

    References
    ----------
    Chibunichev (2022), §3.5, eq. (3.5.20).

    Examples
    --------
    >>> from photolib.triangulation_layouts import bundle_unknowns
    >>> bundle_unknowns(4, 2)          # fig. 3.10: 4 images, tie points 1, 2, 5, 6 → 36 with k = 4
    30
    >>> bundle_unknowns(4, 4)
    36
    """
    return 6 * _nonneg_int("n", n) + 3 * _nonneg_int("k", k)


def bundle_equations(m: int, c: int = 0, i: int = 0, l: int = 0, s: int = 0, j: int = 0) -> int:  # noqa: E741
    """Number of correction equations, M = 2m + 3c + 2i + l + 3s + 3j (3.5.21).

    Parameters
    ----------
    m : int
        Image measurements (points × images they are measured on).
    c, i, l : int
        XYZ, planimetric (XY) and height control points with weighted observations (3.5.17). (The
        book's legend calls both the planimetric and the height count "i".)
    s : int
        GNSS projection centres (3.5.18).
    j : int
        Images with measured angles (3.5.19).

    Returns
    -------
    int
        M.

    Raises
    ------
    InputError
        A negative or non-integer count.

    References
    ----------
    Chibunichev (2022), §3.5, eqs. (3.5.17)–(3.5.21).

    Examples
    --------
    >>> from photolib.triangulation_layouts import bundle_equations
    >>> bundle_equations(24)                 # fig. 3.10: 4 images × 6 points
    48
    >>> bundle_equations(60, c=5, s=8)       # fig. 3.13
    159
    """
    counts = {k: _nonneg_int(k, v) for k, v in dict(m=m, c=c, i=i, l=l, s=s, j=j).items()}
    return (2 * counts["m"] + 3 * counts["c"] + 2 * counts["i"] + counts["l"] + 3 * counts["s"]
            + 3 * counts["j"])


def images_per_point(block: Block) -> np.ndarray:
    """Number of images each point is measured on (the numbers printed in fig. 3.13).

    Parameters
    ----------
    block : Block
        A synthetic block.

    Returns
    -------
    (k,) int array

    Raises
    ------
    InputError
        ``block`` is not a :class:`photolib.synthetic.Block`.

    References
    ----------
    Chibunichev (2022), §3.5, fig. 3.13.

    Examples
    --------
    >>> from photolib.synthetic import footprint_block, TIE
    >>> from photolib.triangulation_layouts import images_per_point
    >>> blk = footprint_block([[0, 0], [500, 0]], [[0, 0], [500, 0], [-300, 0]], [TIE] * 3, sigma=0)
    >>> images_per_point(blk).tolist()
    [2, 2, 1]
    """
    _check_block(block)
    return block.visibility.sum(axis=1)


def block_counts(block: Block) -> dict:
    """The inputs of (3.5.20)/(3.5.21) read off a block, and N, M from the formulas.

    k counts the point unknowns: with fixed control (fig. 3.10) the determined points only, with
    weighted control (fig. 3.13) all points — the book's two conventions.

    Parameters
    ----------
    block : Block
        A synthetic block (control fixed or weighted, GNSS centres optional).

    Returns
    -------
    dict
        ``n, k, m, c, i, l, s, j, N, M`` and ``points_per_image`` (n,).

    Raises
    ------
    InputError
        ``block`` is not a :class:`photolib.synthetic.Block`.

    References
    ----------
    Chibunichev (2022), §3.5, eqs. (3.5.20), (3.5.21); figs. 3.10, 3.13.

    Examples
    --------
    >>> from photolib.synthetic import footprint_block, TIE, CONTROL
    >>> from photolib.triangulation_layouts import block_counts
    >>> blk = footprint_block([[0, 0], [500, 0]], [[0, 0], [500, 0], [250, 300]], [TIE, TIE, CONTROL])
    >>> c = block_counts(blk)
    >>> c["n"], c["k"], c["m"], c["N"], c["M"]
    (2, 2, 6, 18, 12)
    """
    _check_block(block)
    vis = block.visibility
    c = int(block.control.size) if block.control_sigma is not None else 0
    s = 0 if block.gnss is None else int(np.isfinite(block.gnss).all(axis=1).sum())
    out = dict(n=block.n_images, k=int(block.unknown_points.size), m=int(vis.sum()), c=c, i=0, l=0, s=s, j=0)
    out["N"] = bundle_unknowns(out["n"], out["k"])
    out["M"] = bundle_equations(out["m"], c, 0, 0, s, 0)
    out["points_per_image"] = vis.sum(axis=0)
    return out


# --- the correction equations as one dense system (fig. 3.11) -------------------------------------
@dataclass(repr=False)
class BundleSystem:
    """Dense correction equations A·δ + L = V (3.5.5) with weights P (3.5.7), columns as in fig. 3.11.

    Attributes
    ----------
    A : (M, N) array
        Coefficients.
    L : (M,) array
        Free terms.
    P : (M,) array
        Weights p = σ₀²/m² of the equations.
    row_kind : (M,) array of str
        "tie" (3.5.2), "control" (3.5.3), "ground" (3.5.17), "gnss" (3.5.18), "ins" (3.5.19).
    columns : list of str
        Names of the N unknowns, e.g. "P1:X_S", "1:X".
    n_eo : int
        Number of EO columns (6n): δ₁ is the first ``n_eo`` unknowns.

    References
    ----------
    Chibunichev (2022), §3.5, eqs. (3.5.5), (3.5.7), (3.5.8); figs. 3.11, 3.12.

    Examples
    --------
    >>> import numpy as np
    >>> from photolib.triangulation_layouts import BundleSystem
    >>> s = BundleSystem(np.eye(2), np.zeros(2), np.ones(2), np.array(["tie", "tie"]), ["a", "b"], 0)
    >>> s
    BundleSystem(A 2×2, rank 2, 2 non-zeros; rows: 2 tie)
    """

    A: np.ndarray
    L: np.ndarray
    P: np.ndarray
    row_kind: np.ndarray
    columns: list
    n_eo: int

    def __repr__(self) -> str:
        kinds, counts = np.unique(self.row_kind, return_counts=True)
        rows = ", ".join(f"{c} {k}" for k, c in zip(kinds, counts))
        return f"BundleSystem(A {self.A.shape[0]}×{self.A.shape[1]}, rank {self.rank}, {self.nnz} non-zeros; rows: {rows})"

    @property
    def shape(self) -> tuple:
        """(M, N)."""
        return self.A.shape

    @property
    def nnz(self) -> int:
        """Number of non-zero coefficients of A."""
        return int(np.count_nonzero(self.A))

    @property
    def rank(self) -> int:
        """Rank of A (columns equilibrated)."""
        norms = np.linalg.norm(self.A, axis=0)
        As = self.A / np.where(norms > 0, norms, 1.0)
        return int(np.linalg.matrix_rank(As))

    def normal(self):
        """N = AᵀPA and Lᴺ = AᵀPL of (3.5.8)."""
        PA = self.P[:, None] * self.A
        return self.A.T @ PA, PA.T @ self.L


def _as_array(value, shape, what):
    try:
        arr = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise InputError(f"{what} must be numbers") from None
    if arr.shape != shape:
        raise InputError(f"{what}: expected shape {shape}, got {arr.shape}")
    if not np.all(np.isfinite(arr)):
        raise InputError(f"{what} contain NaN or inf")
    return arr


def correction_equation_system(block: Block, cameras=None, points=None, *, planimetric=(), height=(),
                               ins=None, ins_sigma: float = np.radians(0.005)) -> BundleSystem:
    """Build a block's correction equations densely at (``cameras``, ``points``) (default: the truth).

    Rows, in this order: the image observations image by image ((3.5.2) for unknown points,
    (3.5.3) for fixed control), then for weighted control (3.5.17) three rows per XYZ point (two
    for a point listed in ``planimetric``, one for ``height``), then GNSS centres (3.5.18), then
    INS angles (3.5.19) for the images whose row of ``ins`` (n, 3) is finite. Columns: the six EO
    of every image, then X, Y, Z of every unknown point. The image rows come from
    :func:`photolib.bundle.bundle_correction_equations` through
    :func:`photolib.lsq.block_equations_dense`.

    Parameters
    ----------
    block : Block
        The block (observations, control, GNSS, labels).
    cameras : (n, 6) array, optional
        Approximate EO; default the truth.
    points : (k, 3) array, optional
        Approximate points; default the truth.
    planimetric, height : iterable of int
        Control points observed in X, Y only / in Z only (weighted control only).
    ins : (n, 3) array, optional
        Measured angles per image (NaN rows: none).
    ins_sigma : float
        Their accuracy, rad.

    Returns
    -------
    BundleSystem

    Raises
    ------
    InputError
        Wrong shapes or NaN/inf in ``cameras``/``points``, planimetric/height control with fixed
        control, ``ins`` of the wrong shape, a non-positive ``ins_sigma``.

    References
    ----------
    Chibunichev (2022), §3.5, eqs. (3.5.2), (3.5.3), (3.5.5), (3.5.17)–(3.5.19); fig. 3.11.

    Examples
    --------
    >>> from photolib.synthetic import footprint_block, TIE, CONTROL
    >>> from photolib.triangulation_layouts import correction_equation_system
    >>> blk = footprint_block([[0, 0], [500, 0]], [[0, 0], [500, 0], [250, 300]], [TIE, TIE, CONTROL])
    >>> correction_equation_system(blk).shape
    (12, 18)
    """
    _check_block(block)
    n, k = block.n_images, len(block.points)
    cams = block.cameras if cameras is None else _as_array(cameras, (n, 6), "cameras")
    pts = block.points if points is None else _as_array(points, (k, 3), "points")
    o = block.observations
    eq = bundle_correction_equations(o.image, o.point, o.xy, cams, pts, block.io, block.order)
    free = np.zeros(k, bool)
    free[block.unknown_points] = True
    B, L, _ = block_equations_dense(eq, n, k, free)
    fixed_obs = ~free[o.point]
    kinds = np.repeat(np.where(fixed_obs, "control", "tie"), 2)
    P = np.ones(B.shape[0])
    col_of_point = np.cumsum(free) - 1
    columns = [f"{lab}:{c}" for lab in block.image_labels for c in EO_COLUMN_NAMES]
    columns += [f"{block.point_labels[j]}:{c}" for j in np.flatnonzero(free) for c in "XYZ"]
    rows, Ls, Ps, ks = [], [], [], []

    def direct(col, l_value, weight, kind):
        r = np.zeros(B.shape[1])
        r[col] = 1.0
        rows.append(r)
        Ls.append(l_value)
        Ps.append(weight)
        ks.append(kind)

    planimetric, height = set(planimetric), set(height)
    if block.control_sigma is not None:
        w = (block.sigma0 / block.control_sigma) ** 2
        for j, xyz in block.control_values().items():
            axes = (0, 1) if j in planimetric else (2,) if j in height else (0, 1, 2)
            for a in axes:
                direct(6 * n + 3 * col_of_point[j] + a, pts[j, a] - xyz[a], w, "ground")   # l = X⁰ − X (3.5.17)
    elif planimetric or height:
        raise InputError("planimetric/height control needs weighted control (control_sigma)")
    if block.gnss is not None:
        w = (block.sigma0 / block.gnss_sigma) ** 2
        for i in range(n):
            if np.all(np.isfinite(block.gnss[i])):
                for a in range(3):
                    direct(6 * i + a, cams[i, a] - block.gnss[i, a], w, "gnss")              # (3.5.18)
    if ins is not None:
        try:
            ins = np.asarray(ins, dtype=float)
        except (TypeError, ValueError):
            raise InputError("ins must be numbers") from None
        if ins.shape != (n, 3):
            raise InputError(f"ins: expected ({n}, 3), got {ins.shape}")
        if not (np.isfinite(ins_sigma) and ins_sigma > 0):
            raise InputError("ins_sigma must be a positive number (rad)")
        w = (block.sigma0 / ins_sigma) ** 2
        for i in range(n):
            if np.all(np.isfinite(ins[i])):
                for a in range(3):
                    direct(6 * i + 3 + a, cams[i, 3 + a] - ins[i, a], w, "ins")              # (3.5.19)
    if rows:
        B = np.vstack([B, np.array(rows)])
        L = np.concatenate([L, Ls])
        P = np.concatenate([P, Ps])
        kinds = np.concatenate([kinds, ks])
    return BundleSystem(A=B, L=L, P=P, row_kind=kinds, columns=columns, n_eo=6 * n)


def normal_matrix_structure(system: BundleSystem) -> dict:
    """The structure of N = AᵀPA stated for fig. 3.12, measured on a built system.

    Parameters
    ----------
    system : BundleSystem
        From :func:`correction_equation_system`.

    Returns
    -------
    dict
        ``N11_block`` / ``N22_block`` ("6×6" / "3×3" when N₁₁ / N₂₂ are block-diagonal with full
        blocks of that size, else "not block-diagonal"), ``N12_zero_fraction`` (share of structurally
        zero entries of N₁₂: no row of A has non-zeros in both columns) and ``N12_pattern`` ("sparse" when more than half of N₁₂ is zero,
        else "dense").

    Raises
    ------
    InputError
        ``system`` is not a :class:`BundleSystem`.

    References
    ----------
    Chibunichev (2022), §3.5, eqs. (3.5.8), (3.5.12); fig. 3.12.

    Examples
    --------
    >>> from photolib.synthetic import footprint_block, TIE, CONTROL
    >>> from photolib.triangulation_layouts import correction_equation_system, normal_matrix_structure
    >>> blk = footprint_block([[0, 0], [500, 0]], [[0, 0], [500, 0], [250, 300]], [TIE, TIE, CONTROL])
    >>> st = normal_matrix_structure(correction_equation_system(blk))
    >>> st["N11_block"], st["N22_block"], st["N12_pattern"]
    ('6×6', '3×3', 'dense')
    """
    if not isinstance(system, BundleSystem):
        raise InputError(f"expected a BundleSystem, got {type(system).__name__}")
    q = system.n_eo
    # The structure of N = AᵀPA from the structure of A (P is positive and diagonal): an entry is
    # structurally non-zero when two columns of A share a row. Integer arithmetic, so that an
    # accidental floating-point cancellation (which differs between BLAS kernels) cannot count.
    rows_of = (np.asarray(system.A) != 0).astype(np.int64)
    nz = (rows_of.T @ rows_of) != 0

    def block_kind(M, size):
        n_blocks = M.shape[0] // size
        mask = np.kron(np.eye(n_blocks, dtype=bool), np.ones((size, size), bool))
        if np.all(M[mask]) and not np.any(M[~mask]):
            return f"{size}×{size}"
        return "not block-diagonal"

    N12 = nz[:q, q:]
    zero = 1.0 - N12.mean() if N12.size else 1.0
    return {"N11_block": block_kind(nz[:q, :q], 6), "N22_block": block_kind(nz[q:, q:], 3),
            "N12_zero_fraction": float(zero), "N12_pattern": "sparse" if zero > 0.5 else "dense"}


# --- accuracy of the adjusted points --------------------------------------------------------------
def predicted_point_sigma(result, sigma_image: float) -> np.ndarray:
    """A-priori standard deviations σ₀·√Q_jj of the adjusted points (m_j of (3.5.11) with μ → σ₀).

    ``bundle_adjustment`` reports m_j = μ√Q_jj; with the weights p = σ₀²/m² the a-priori value
    replaces μ by σ₀ = ``sigma_image``.

    Parameters
    ----------
    result : BundleResult
        Of :func:`photolib.bundle.bundle_adjustment` run with ``covariance=True``.
    sigma_image : float
        σ₀, mm.

    Returns
    -------
    (k, 3) array
        σ of X, Y, Z, m (NaN when μ = 0).

    Raises
    ------
    InputError
        No covariance in ``result``, a non-positive or non-finite ``sigma_image``.

    References
    ----------
    Chibunichev (2022), §3.5, eqs. (3.5.7), (3.5.11).

    Examples
    --------
    >>> from types import SimpleNamespace
    >>> import numpy as np
    >>> from photolib.triangulation_layouts import predicted_point_sigma
    >>> predicted_point_sigma(SimpleNamespace(points_std=np.array([[0.2, 0.2, 0.4]]), mu=0.01), 0.005)
    array([[0.1, 0.1, 0.2]])
    """
    if not (isinstance(sigma_image, (int, float, np.floating)) and np.isfinite(sigma_image) and sigma_image > 0):
        raise InputError("sigma_image must be a positive number (mm)")
    std = getattr(result, "points_std", None)
    mu = getattr(result, "mu", None)
    if std is None or mu is None:
        raise InputError("the adjustment was run without covariance (no points_std)")
    return std * (sigma_image / mu) if mu > 0 else std * np.nan


def check_point_accuracy(block: Block, result, indices=None) -> dict:
    """Errors of the adjusted points against the truth: r.m.s. per axis and the predicted σ.

    Parameters
    ----------
    block : Block
        The block whose truth is compared.
    result : BundleResult
        Its adjustment (with covariance).
    indices : array of int, optional
        Points to compare; default the points not used as control.

    Returns
    -------
    dict
        ``indices``, ``errors`` (c, 3), ``rms`` (3,) and ``predicted`` (3,) = r.m.s. of σ₀√Q_jj
        over the same points, m.

    Raises
    ------
    InputError
        Not a block, a result without covariance or with another number of points, indices out of
        range or empty.

    References
    ----------
    Chibunichev (2022), §3.5, eq. (3.5.11); §3.7 (check points).

    Examples
    --------
    >>> from types import SimpleNamespace
    >>> import numpy as np
    >>> from photolib.synthetic import footprint_block, TIE, CONTROL
    >>> from photolib.triangulation_layouts import check_point_accuracy
    >>> blk = footprint_block([[0, 0], [500, 0]], [[0, 0], [500, 0], [250, 300]], [TIE, TIE, CONTROL])
    >>> res = SimpleNamespace(points=blk.points + [0.0, 0.0, 0.1], points_std=np.full((3, 3), 0.1), mu=0.005)
    >>> check_point_accuracy(blk, res)["rms"]
    array([0. , 0. , 0.1])
    """
    _check_block(block)
    pts = getattr(result, "points", None)
    if pts is None or np.shape(pts) != block.points.shape:
        raise InputError("the result does not hold the block's points")
    if indices is None:
        idx = np.flatnonzero(block.kind != CONTROL)
    else:
        idx = np.asarray(indices).reshape(-1)
        if idx.dtype.kind not in "iu":
            raise InputError("indices must be integers")
    if idx.size == 0 or idx.min() < 0 or idx.max() >= len(block.points):
        raise InputError(f"indices must select some of the {len(block.points)} points")
    err = np.asarray(pts)[idx] - block.points[idx]
    pred = predicted_point_sigma(result, block.sigma0)[idx]
    return {"indices": idx, "errors": err, "rms": np.sqrt(np.mean(err ** 2, axis=0)),
            "predicted": np.sqrt(np.mean(pred ** 2, axis=0))}


# --- §3.7 regulation tolerances (our helper; the numbers are the caller's) ------------------------
TOLERANCE_NAMES = ("3.7.2 tie height", "3.7.6 control height", "3.7.6 control plan", "3.7.6 check plan",
                   "3.7.6 height, category a", "3.7.6 height, category b", "3.7.6 height, category c",
                   "3.7.7 height, category a", "3.7.7 height, category b", "3.7.7 height, category c",
                   "3.7.6 limit share, open", "3.7.6 limit share, wooded", "3.7.6 limit factor")
"""Keys of the ``tolerances`` mapping (the quantity names of the book's example ``3.7-tolerances``)."""


def _tolerance(tolerances, name) -> float:
    try:
        value = tolerances[name]
    except (KeyError, TypeError, IndexError):
        raise InputError(f"tolerances: give a mapping with the value of {name!r}") from None
    try:
        value = float(value)
    except (TypeError, ValueError):
        raise InputError(f"tolerances[{name!r}] must be a number, got {value!r}") from None
    if not np.isfinite(value) or value < 0:
        raise InputError(f"tolerances[{name!r}] must be a finite non-negative number")
    return value


def _positive(value, what) -> float:
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise InputError(f"{what} must be a number, got {value!r}") from None
    if not (np.isfinite(v) and v > 0):
        raise InputError(f"{what} must be a finite positive number, got {value!r}")
    return v


def check_height_factor(contour_interval: float, scale_denominator: float, tolerances, stage: str = "check") -> float:
    """The factor of the contour interval h for mean height discrepancies, 3.7.6 / 3.7.7.

    ``stage="check"``: check points after external orientation (clause 3.7.6); ``stage="common"``: common
    points of adjacent strips (clause 3.7.7). The category is (a) h = 1 m, or h = 0.5 m at 1:1000 and
    1:500; (b) h = 2 or 2.5 m, or h = 0.5 m at 1:2000 and 1:5000; (c) h = 5 or 10 m.

    Parameters
    ----------
    contour_interval : float
        h, m.
    scale_denominator : float
        Map scale 1 : ``scale_denominator``.
    tolerances : mapping
        Values for the keys "3.7.6 height, category a" … "3.7.7 height, category c".
    stage : {"check", "common"}
        Which clause.

    Returns
    -------
    float
        The factor (e.g. 0.2 for 0.2h).

    Raises
    ------
    InputError
        A combination the Instruction does not cover, an unknown stage, NaN/inf, a missing tolerance.

    References
    ----------
    Chibunichev (2022), §3.7, Instruction clauses 3.7.6, 3.7.7.

    Examples
    --------
    >>> from photolib.triangulation_layouts import check_height_factor
    >>> tol = {"3.7.6 height, category a": 0.2, "3.7.6 height, category b": 0.25}
    >>> check_height_factor(0.5, 2000, tol)
    0.25
    """
    h, sc = _positive(contour_interval, "contour_interval"), _positive(scale_denominator, "scale_denominator")
    clause = {"check": "3.7.6", "common": "3.7.7"}.get(stage) if isinstance(stage, str) else None
    if clause is None:
        raise InputError("stage must be 'check' or 'common'")
    if h == 1.0 or (h == 0.5 and sc in (1000.0, 500.0)):
        cat = "a"
    elif h in (2.0, 2.5) or (h == 0.5 and sc in (2000.0, 5000.0)):
        cat = "b"
    elif h in (5.0, 10.0):
        cat = "c"
    else:
        raise InputError(f"contour interval {h} m at 1:{sc:g} is not covered by 3.7.6/3.7.7")
    return _tolerance(tolerances, f"{clause} height, category {cat}")


def free_strip_height_tolerance_um(f_mm: float, base_image_mm: float, tolerances) -> float:
    """3.7.2: r.m.s. height discrepancy of tie points in a free strip ≤ 15 µm · f / b.

    Parameters
    ----------
    f_mm : float
        Focal length, mm.
    base_image_mm : float
        Photo base at image scale, mm.
    tolerances : mapping
        The value of "3.7.2 tie height" (µm; the Instruction says 15).

    Returns
    -------
    float
        The tolerance, µm at image scale.

    Raises
    ------
    InputError
        Non-positive or non-finite f or base, a missing tolerance.

    References
    ----------
    Chibunichev (2022), §3.7, Instruction clause 3.7.2.

    Examples
    --------
    >>> from photolib.triangulation_layouts import free_strip_height_tolerance_um
    >>> free_strip_height_tolerance_um(100.0, 50.0, {"3.7.2 tie height": 15})
    30.0
    """
    f_mm, b = _positive(f_mm, "f_mm"), _positive(base_image_mm, "base_image_mm")
    return _tolerance(tolerances, "3.7.2 tie height") * f_mm / b


@dataclass(frozen=True)
class Criterion:
    """One tolerance check of :func:`evaluate_regulations`.

    Attributes
    ----------
    clause : str
        The Instruction's clause, e.g. "3.7.6".
    what : str
        What is checked.
    value, tolerance : float
        Measured value and its tolerance, in ``unit``.
    unit : str
        "m" or "%".
    passed : bool
        ``value <= tolerance``.

    References
    ----------
    Chibunichev (2022), §3.7, Instruction clause 3.7.6.

    Examples
    --------
    >>> from photolib.triangulation_layouts import Criterion
    >>> Criterion("3.7.6", "mean |ΔZ| at check points", 0.031, 0.1, "m", True)
    3.7.6 mean |ΔZ| at check points: 0.031 m ≤ 0.100 m (passed)
    """

    clause: str
    what: str
    value: float
    tolerance: float
    unit: str
    passed: bool

    def __repr__(self) -> str:
        rel = "≤" if self.passed else ">"
        return (f"{self.clause} {self.what}: {self.value:.3f} {self.unit} {rel} {self.tolerance:.3f} {self.unit} "
                f"({'passed' if self.passed else 'FAILED'})")


def _errors(values, what):
    try:
        arr = np.asarray(values, dtype=float)
    except (TypeError, ValueError):
        raise InputError(f"{what} must be numbers") from None
    if arr.size % 3 or (arr.ndim == 2 and arr.shape[1] != 3) or arr.ndim > 2:
        raise InputError(f"{what}: expected an array of shape (c, 3), got {arr.shape}")
    arr = arr.reshape(-1, 3)
    if not np.all(np.isfinite(arr)):
        raise InputError(f"{what} contain NaN or inf")
    return arr


def evaluate_regulations(control_errors, check_errors, scale_denominator: float, contour_interval: float,
                         tolerances, wooded: bool = False) -> list:
    """Evaluate a controlled block against the 3.7.6 tolerances (our helper, not in the book).

    Our reading of the Instruction: a "mean" discrepancy is the mean absolute height error and
    the mean length of the planimetric error vector; a "limit" discrepancy is one that reaches
    ``limit factor`` (twice) the tolerance for the mean ("предельно допустимые расхождения, равные
    удвоенным средним"), and the share of check points with such discrepancies must not exceed
    5 % (10 % in forest).

    Parameters
    ----------
    control_errors, check_errors : (c, 3) arrays
        Adjusted − geodetic coordinates (m) at the control points and at independent check points.
    scale_denominator : float
        Map (plan) scale 1 : ``scale_denominator``; planimetric tolerances are mm at map scale.
    contour_interval : float
        h, m.
    tolerances : mapping
        Values for :data:`TOLERANCE_NAMES` (the book layer passes the transcribed §3.7 numbers).
    wooded : bool
        Forested area: limit discrepancies allowed in 10 % of the check points instead of 5 %.

    Returns
    -------
    list of Criterion

    Raises
    ------
    InputError
        NaN/inf or wrong shapes, no check point, an uncovered contour interval, a missing tolerance.

    References
    ----------
    Chibunichev (2022), §3.7, Instruction clauses 3.7.6, 3.7.7.

    Examples
    --------
    >>> from photolib.triangulation_layouts import evaluate_regulations
    >>> tol = {"3.7.6 control height": 0.2, "3.7.6 control plan": 0.2, "3.7.6 check plan": 0.35,
    ...        "3.7.6 height, category b": 0.25, "3.7.6 limit share, open": 5, "3.7.6 limit factor": 2}
    >>> rows = evaluate_regulations([[0.01, 0.0, 0.02]], [[0.1, 0.0, 0.05]], 2000, 0.5, tol)
    >>> [r.passed for r in rows]
    [True, True, True, True, True, True]
    """
    ce = _errors(control_errors, "control_errors")
    ke = _errors(check_errors, "check_errors")
    if ke.shape[0] == 0:
        raise InputError("give at least one check point")
    h, sc = _positive(contour_interval, "contour_interval"), _positive(scale_denominator, "scale_denominator")
    mm = sc / 1000.0                                                              # 1 mm at map scale in m
    out = []
    if ce.shape[0]:
        t = _tolerance(tolerances, "3.7.6 control height") * h
        v = float(np.mean(np.abs(ce[:, 2])))
        out.append(Criterion("3.7.6", "mean |ΔZ| at control points", v, t, "m", v <= t))
        t = _tolerance(tolerances, "3.7.6 control plan") * mm
        v = float(np.mean(np.hypot(ce[:, 0], ce[:, 1])))
        out.append(Criterion("3.7.6", "mean ΔXY at control points", v, t, "m", v <= t))
    t_h = check_height_factor(h, sc, tolerances) * h
    t_p = _tolerance(tolerances, "3.7.6 check plan") * mm
    dz, dp = np.abs(ke[:, 2]), np.hypot(ke[:, 0], ke[:, 1])
    out.append(Criterion("3.7.6", "mean |ΔZ| at check points", float(dz.mean()), t_h, "m", bool(dz.mean() <= t_h)))
    out.append(Criterion("3.7.6", "mean ΔXY at check points", float(dp.mean()), t_p, "m", bool(dp.mean() <= t_p)))
    share = _tolerance(tolerances, "3.7.6 limit share, wooded" if wooded else "3.7.6 limit share, open")
    factor = _tolerance(tolerances, "3.7.6 limit factor")
    for what, e, t in (("height", dz, t_h), ("plan", dp, t_p)):
        frac = float(np.mean(e >= factor * t))
        out.append(Criterion("3.7.6", f"share of check points with {what} error ≥ {factor:g}× tolerance",
                             100.0 * frac, share, "%", frac <= share / 100.0))
    return out


def at_accuracy_rule(scale_number: float, flying_height: float, *, image_sigma_um: float = 5.0) -> tuple:
    """Hanzl's rule of thumb for aerotriangulation: σ_XY ≈ 5 µm·m_s, σ_Z ≈ 0.005 % h.

    Valid, in the text, for signalised points, a wide-angle camera and additional parameters; with
    residual systematic errors or natural points the accuracy may be 2–3 times worse.

    Parameters
    ----------
    scale_number : float
        Image scale number m_s (e.g. 10000), > 0.
    flying_height : float
        Flying height above ground h, m, > 0.
    image_sigma_um : float
        The 5 µm of the rule (image-space accuracy), µm, > 0.

    Returns
    -------
    (float, float)
        σ_XY and σ_Z, m.

    Raises
    ------
    InputError
        Non-finite or non-positive arguments.

    References
    ----------
    Hanzl, Fotogrammetrie, Modul 01, §4.3 (seed 002 line 744); Chibunichev §3.5 (accuracy of the bundle).

    Examples
    --------
    >>> sxy, sz = at_accuracy_rule(10000, 1530.0)
    >>> round(sxy, 4), round(sz, 4)
    (0.05, 0.0765)
    """
    m_s = _checks.number(scale_number, "scale_number", positive=True)
    h = _checks.number(flying_height, "flying_height", positive=True)
    s_um = _checks.number(image_sigma_um, "image_sigma_um", positive=True)
    return s_um * 1e-6 * m_s, 0.005e-2 * h


def gnss_at_accuracy(scale_number: float, sigma0_um: float) -> tuple:
    """INPHO's empirical accuracy of GNSS-supported aerotriangulation: m_XY = 1.5 m_s σ₀, m_Z = 2.2 m_s σ₀.

    From 23 blocks with 60 % / 20 % overlap and c = 15 cm; control and projection centres then
    had m_XYZ = m_s σ₀ (also returned).

    Parameters
    ----------
    scale_number : float
        Image scale number m_s, > 0.
    sigma0_um : float
        σ₀ of the block adjustment (image space), µm, > 0.

    Returns
    -------
    (float, float, float)
        m_XY, m_Z and m_XYZ = m_s σ₀, m.

    Raises
    ------
    InputError
        Non-finite or non-positive arguments.

    References
    ----------
    Hanzl, Fotogrammetrie, Modul 01, §4.5 (seed 002 line 826); Chibunichev §3.5, eq. (3.5.18).

    Examples
    --------
    >>> [round(v, 3) for v in gnss_at_accuracy(10000, 5.0)]
    [0.075, 0.11, 0.05]
    """
    m_s = _checks.number(scale_number, "scale_number", positive=True)
    s0 = _checks.number(sigma0_um, "sigma0_um", positive=True) * 1e-6
    return 1.5 * m_s * s0, 2.2 * m_s * s0, m_s * s0
