"""RANSAC — the matching strategy of Chapter 5, §5.10, with the pair models of Chapters 2 and 4.

§5.10 describes random sample consensus for corresponding points: draw the minimal number of
correspondences (five for the relative orientation of §2.7), solve the model, evaluate the
residual y-parallax of *all* points, keep the model with the largest consensus set.

* :func:`ransac` — the generic, seeded algorithm: any model given by a fit function, a residual
  function, the minimal sample size and a threshold; the number of samples adapts to the inlier
  ratio found so far, N = ⌈log(1 − P)/log(1 − wˢ)⌉ (:func:`iterations_needed`; not in the book,
  Fischler & Bolles 1981). Degenerate samples (the fit raises a named geometry/convergence
  error) are skipped and counted.
* :func:`ransac_relative_orientation` — the book's variant: five-point samples solved by the
  coplanarity adjustment of §2.7–§2.8 (:func:`photolib.image_pair.relative_orientation`, from
  zero approximations, i.e. for near-vertical pairs), residual = y-parallax q (2.8.2).
* :func:`ransac_essential` — the same five-point samples turned into the essential matrix of
  §4.4 (E = D·A′₂ᵀ·S_b·A′₁·D, :mod:`photolib.projective` conventions), residual = Sampson distance.
* :func:`ransac_fundamental_matrix` — eight-point samples of the fundamental matrix of §4.4
  (:func:`photolib.projective.fundamental_matrix`), residual = Sampson distance.

The five-point sample solved iteratively from zero is the book's relative orientation; it
presumes small angles (aerial pairs). A closed-form five-point solver (Nistér 2004, as in
``cv2.findEssentialMat``) is not part of the book and not implemented here; strongly convergent
pairs should use :func:`ransac_fundamental_matrix` (8 points).

Errors: too few points or bad arguments → :class:`~photolib.errors.InputError`; every sample
degenerate → :class:`~photolib.errors.DegenerateGeometryError`; no consensus set larger than
``min_inliers`` → :class:`~photolib.errors.ConvergenceError` (``history`` holds the best count
after each sample).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from . import _checks
from .camera import InteriorOrientation, image_vector
from .errors import ConvergenceError, DegenerateGeometryError, InputError, PhotolibError
from .image_pair import relative_orientation, y_parallax
from .projective import (D_REFLECTION, fundamental_matrix, normalized_image_coordinates,
                         sampson_distance, skew_matrix)

__all__ = ["RansacResult", "iterations_needed", "ransac", "ransac_relative_orientation",
           "ransac_essential", "ransac_fundamental_matrix", "essential_from_relative_orientation"]


@dataclass(repr=False)
class RansacResult:
    """The outcome of :func:`ransac`.

    Attributes
    ----------
    model : object
        The model fitted to the consensus set (or to the best sample if ``refit`` failed/was off).
    inliers : (n,) ndarray of bool
        The consensus set: residual < threshold.
    iterations : int
        Number of samples drawn.
    residuals : (n,) ndarray
        Residuals of all observations under ``model``.
    degenerate : int
        Number of samples whose fit failed (degenerate geometry, no convergence).

    References
    ----------
    Chibunichev (2022), §5.10; M. Fischler, R. Bolles (1981), Comm. ACM 24(6), 381–395.

    Examples
    --------
    >>> r = RansacResult(1.0, np.array([True, False]), 3, np.array([0.0, 5.0]), 0)
    >>> r.n_inliers, r.inlier_ratio
    (1, 0.5)
    """

    model: object
    inliers: np.ndarray
    iterations: int
    residuals: np.ndarray
    degenerate: int = 0

    def __post_init__(self):
        try:
            self.inliers = np.asarray(self.inliers, dtype=bool).reshape(-1)
            self.residuals = np.asarray(self.residuals, dtype=float).reshape(-1)
        except (TypeError, ValueError) as exc:
            raise InputError(f"RansacResult: malformed arrays: {exc}") from exc
        if self.inliers.shape != self.residuals.shape:
            raise InputError(f"RansacResult: {self.inliers.shape[0]} inlier flags but "
                             f"{self.residuals.shape[0]} residuals")

    @property
    def n_inliers(self) -> int:
        """Size of the consensus set."""
        return int(np.sum(self.inliers))

    @property
    def inlier_ratio(self) -> float:
        """Share of inliers, w."""
        return self.n_inliers / max(len(self.inliers), 1)

    def __repr__(self):
        return (f"RansacResult({self.n_inliers}/{len(self.inliers)} inliers, {self.iterations} samples, "
                f"{self.degenerate} degenerate)")


def iterations_needed(inlier_ratio: float, sample_size: int, confidence: float = 0.99) -> int:
    """Samples needed to draw one outlier-free sample with probability P: ⌈log(1 − P)/log(1 − wˢ)⌉.

    Parameters
    ----------
    inlier_ratio : float
        w ∈ [0, 1].
    sample_size : int
        s, the minimal sample (5 for relative orientation, 8 for F).
    confidence : float
        P ∈ (0, 1).

    Returns
    -------
    int
        N (0 when w = 1; a very large number when w = 0).

    Raises
    ------
    InputError
        w outside [0, 1], s < 1, P outside (0, 1).

    References
    ----------
    Chibunichev (2022), §5.10 (the number of samples is not given there); Fischler & Bolles (1981);
    Hartley & Zisserman (2003), §4.7.1.

    Examples
    --------
    >>> iterations_needed(0.7, 5, 0.99), iterations_needed(0.7, 8, 0.99)
    (26, 78)
    """
    w = _number(inlier_ratio, "inlier_ratio")
    if not 0 <= w <= 1:
        raise InputError(f"inlier_ratio must lie in [0, 1], got {inlier_ratio}")
    s = _count(sample_size, "sample_size")
    P = _confidence(confidence)
    good = w ** s
    if good >= 1:
        return 0
    if good <= 0:
        return 2 ** 31 - 1
    return int(math.ceil(math.log(1 - P) / math.log1p(-good)))


def _number(value, what) -> float:
    return _checks.number(value, what, out_of_range="{name} must be finite, got {value!r}")


_count = _checks.integer


def _confidence(value) -> float:
    P = _number(value, "confidence")
    if not 0 < P < 1:
        raise InputError(f"confidence must lie in (0, 1), got {value}")
    return P


def _subset(data, idx):
    if isinstance(data, tuple):
        return tuple(d[idx] for d in data)
    return data[idx]


def _length(data) -> int:
    if isinstance(data, tuple):
        if not data:
            raise InputError("data is an empty tuple")
        lengths = {len(d) for d in data}
        if len(lengths) != 1:
            raise InputError(f"the arrays of data differ in length: {sorted(lengths)}")
        return lengths.pop()
    return len(data)


_SKIP = (DegenerateGeometryError, ConvergenceError, np.linalg.LinAlgError)


def ransac(data, fit, residual, sample_size: int, threshold: float, confidence: float = 0.99,
           max_iterations: int = 1000, rng=0, min_inliers=None, refit: bool = True) -> RansacResult:
    """Generic seeded RANSAC (§5.10): the model with the largest consensus set.

    Repeatedly draws ``sample_size`` observations without replacement, fits a model to them
    and counts the observations whose residual is below ``threshold``; keeps the largest set
    (ties: the smaller sum of inlier residuals). The number of samples adapts:
    N = :func:`iterations_needed` (w = best inlier ratio so far), capped at ``max_iterations``.
    With ``refit`` the model is finally fitted to all inliers and the inliers recomputed (twice
    at most, while the set grows).

    Parameters
    ----------
    data : array or tuple of arrays
        n observations (indexable by an index array), or a tuple of arrays of length n
        (e.g. ``(xy1, xy2)``); samples are passed to ``fit`` in the same form.
    fit : callable
        ``fit(sample) -> model``; raise :class:`~photolib.errors.DegenerateGeometryError` (or
        :class:`~photolib.errors.ConvergenceError`) for a degenerate sample — it is skipped.
    residual : callable
        ``residual(model, data) -> (n,) array`` of non-negative residuals.
    sample_size : int
        s, the minimal sample.
    threshold : float
        Inlier threshold on the residual, > 0.
    confidence : float
        P of drawing at least one outlier-free sample, in (0, 1).
    max_iterations : int
        Upper limit of samples.
    rng : int or numpy.random.Generator
        Seed (deterministic by default) or generator.
    min_inliers : int, optional
        Smallest acceptable consensus set; default s + 1 (more than the sample itself).
    refit : bool
        Fit the final model to all inliers.

    Returns
    -------
    RansacResult
        Model, inlier mask, samples drawn, residuals, number of degenerate samples.

    Raises
    ------
    InputError
        Fewer observations than ``sample_size`` (or ``min_inliers``), bad arguments, NaN residuals.
    DegenerateGeometryError
        Every sample was degenerate.
    ConvergenceError
        No consensus set larger than ``min_inliers`` − 1 within ``max_iterations`` samples.

    References
    ----------
    Chibunichev (2022), §5.10; M. Fischler, R. Bolles (1981), "Random sample consensus",
    Comm. ACM 24(6), 381–395.

    Examples
    --------
    A line y = 2x + 1 with two gross errors:

    >>> x = np.arange(10.0); y = 2 * x + 1; y[[2, 7]] += 30
    >>> fit = lambda s: np.polyfit(s[:, 0], s[:, 1], 1)
    >>> res = lambda m, d: np.abs(np.polyval(m, d[:, 0]) - d[:, 1])
    >>> r = ransac(np.c_[x, y], fit, res, sample_size=2, threshold=0.1)
    >>> np.round(r.model, 6) + 0.0, np.flatnonzero(~r.inliers)
    (array([2., 1.]), array([2, 7]))
    """
    if not callable(fit) or not callable(residual):
        raise InputError("fit and residual must be callables")
    n = _length(data)
    s = _count(sample_size, "sample_size")
    thr = _number(threshold, "threshold")
    if thr <= 0:
        raise InputError(f"threshold must be positive, got {threshold}")
    P = _confidence(confidence)
    max_it = _count(max_iterations, "max_iterations")
    m_in = s + 1 if min_inliers is None else _count(min_inliers, "min_inliers")
    if n < s:
        raise InputError(f"{n} observations are fewer than the minimal sample of {s}")
    if n < m_in:
        raise InputError(f"{n} observations cannot give the required consensus of {m_in}")
    rng = rng if isinstance(rng, np.random.Generator) else np.random.default_rng(rng)

    def evaluate(model):
        r = np.asarray(residual(model, data), dtype=float)
        if r.shape != (n,):
            raise InputError(f"residual returned shape {r.shape}, expected ({n},)")
        if np.any(np.isnan(r)):
            raise InputError("residual returned NaN")
        return r

    best = None                      # (count, score, model, residuals)
    history = []
    needed, it, degenerate = max_it, 0, 0
    while it < min(needed, max_it):
        it += 1
        idx = rng.choice(n, s, replace=False)
        try:
            model = fit(_subset(data, idx))
        except _SKIP:
            degenerate += 1
            history.append(0 if best is None else best[0])
            continue
        r = evaluate(model)
        mask = r < thr
        count = int(mask.sum())
        score = float(np.sum(r[mask]))
        if best is None or count > best[0] or (count == best[0] and score < best[1]):
            best = (count, score, model, r)
            needed = iterations_needed(count / n, s, P)
        history.append(best[0])
    if best is None:
        raise DegenerateGeometryError(f"all {it} RANSAC samples of {s} were degenerate")
    count, _, model, r = best
    if count < m_in:
        raise ConvergenceError(f"RANSAC found no consensus: the best of {it} samples is supported by "
                               f"{count} of {n} observations (at least {m_in} required)", history)
    if refit:
        for _ in range(2):
            mask = r < thr
            try:
                new_model = fit(_subset(data, np.flatnonzero(mask)))
            except _SKIP:
                break
            new_r = evaluate(new_model)
            if int((new_r < thr).sum()) < int(mask.sum()):
                break
            grew = int((new_r < thr).sum()) > int(mask.sum())
            model, r = new_model, new_r
            if not grew:
                break
    return RansacResult(model, r < thr, it, r, degenerate)


def _pairs(xy1, xy2, minimum, what):
    try:
        a = np.asarray(xy1, dtype=float)
        b = np.asarray(xy2, dtype=float)
    except (TypeError, ValueError) as exc:
        raise InputError(f"{what}: coordinates must be numeric (n, 2) arrays: {exc}") from exc
    if a.ndim != 2 or a.shape[1] != 2 or b.shape != a.shape:
        raise InputError(f"{what}: expected two (n, 2) arrays of the same shape, got {a.shape} and {b.shape}")
    if not (np.all(np.isfinite(a)) and np.all(np.isfinite(b))):
        raise InputError(f"{what}: coordinates contain NaN or inf")
    if len(a) < minimum:
        raise InputError(f"{what} needs at least {minimum} correspondences, got {len(a)}")
    return a, b


def _io(io1, io2):
    if not isinstance(io1, InteriorOrientation):
        raise InputError(f"io1 must be an InteriorOrientation, got {type(io1).__name__}")
    io2 = io1 if io2 is None else io2
    if not isinstance(io2, InteriorOrientation):
        raise InputError(f"io2 must be an InteriorOrientation, got {type(io2).__name__}")
    return io1, io2


def _ro_fit(io1, io2, system):
    def fit(sample):
        a, b = sample
        try:
            return relative_orientation(a, b, io1, io2, system=system, max_iter=30)
        except (InputError, PhotolibError) as exc:
            if isinstance(exc, (DegenerateGeometryError, ConvergenceError)):
                raise
            raise DegenerateGeometryError(f"sample without a relative orientation: {exc}") from exc
    return fit


def _y_parallaxes(ro, xy1, xy2, io1, io2):
    r1 = image_vector(xy1, io1) @ ro.A1.T
    r2 = image_vector(xy2, io2) @ ro.A2.T
    return np.abs(y_parallax(ro.base, r1, r2, io1.f))


def ransac_relative_orientation(xy1, xy2, io1: InteriorOrientation, io2: InteriorOrientation | None = None,
                                threshold: float = 0.01, confidence: float = 0.99, max_iterations: int = 500,
                                rng=0, system: str = "dependent") -> RansacResult:
    """The book's RANSAC (§5.10): five-point relative orientations, residual y-parallax.

    Each sample of five correspondences is solved by the coplanarity adjustment of §2.7–§2.8
    from zero approximations (near-vertical pairs); the consensus set holds the points with
    |q| < ``threshold``, q the residual y-parallax (2.8.2); the final orientation is adjusted
    with all inliers.

    Parameters
    ----------
    xy1, xy2 : (n, 2) arrays
        Image coordinates (mm) of the candidate correspondences, n ≥ 6.
    io1, io2 : InteriorOrientation
        Interior orientation (``io2`` defaults to ``io1``).
    threshold : float
        Largest |q| (mm) of an inlier.
    confidence, max_iterations, rng
        As in :func:`ransac`.
    system : {"dependent", "independent"}
        System of the elements, (2.7.5) or (2.7.4).

    Returns
    -------
    RansacResult
        ``model`` is a :class:`~photolib.image_pair.RelativeOrientation`; residuals are |q| (mm).

    Raises
    ------
    InputError
        Fewer than 6 points, bad shapes, NaN, bad arguments.
    DegenerateGeometryError
        Every five-point sample degenerate.
    ConvergenceError
        No consensus.

    References
    ----------
    Chibunichev (2022), §5.10; §2.7–§2.8, eqs. (2.7.3)–(2.7.5), (2.8.1), (2.8.2).

    Examples
    --------
    >>> from photolib.synthetic import stereo_pair
    >>> p = stereo_pair(30, seed=0, angle_spread_deg=2.0, sigma=0.002)
    >>> xy2 = p.xy2.copy(); xy2[:6, 1] += 0.5
    >>> r = ransac_relative_orientation(p.xy1, xy2, p.io, threshold=0.01)
    >>> r.n_inliers, bool(r.inliers[:6].any())
    (24, False)
    """
    xy1, xy2 = _pairs(xy1, xy2, 6, "RANSAC for the relative orientation")
    io1, io2 = _io(io1, io2)
    if system not in ("dependent", "independent"):
        raise InputError(f"unknown system {system!r}; use 'dependent' (2.7.5) or 'independent' (2.7.4)")
    return ransac((xy1, xy2), _ro_fit(io1, io2, system),
                  lambda ro, d: _y_parallaxes(ro, d[0], d[1], io1, io2),
                  5, threshold, confidence, max_iterations, rng)


def essential_from_relative_orientation(ro) -> np.ndarray:
    """E (layout x₂ᵀEx₁ = 0 for r″ of (4.4.15)) of a relative orientation: D·A′₂ᵀ·S_b·A′₁·D, unit norm.

    Parameters
    ----------
    ro : RelativeOrientation
        Elements of either system.

    Returns
    -------
    (3, 3) ndarray
        E, Frobenius norm 1.

    Raises
    ------
    InputError
        ``ro`` is not a relative orientation.

    References
    ----------
    Chibunichev (2022), §4.4, eqs. (4.4.1), (4.4.7), (4.4.16); §2.7, eq. (2.7.3).

    Examples
    --------
    >>> from photolib.image_pair import RelativeOrientation
    >>> ro = RelativeOrientation("dependent", "kaw", 0, 0, 0, 0, 0, 0, 0, 0, q=np.zeros(5))
    >>> E = essential_from_relative_orientation(ro)
    >>> float(np.array([0.2, 0.1, 1.0]) @ E @ [0.6, 0.1, 1.0])
    0.0
    """
    A1, A2, b = getattr(ro, "A1", None), getattr(ro, "A2", None), getattr(ro, "base", None)
    if A1 is None or A2 is None or b is None:
        raise InputError(f"expected a RelativeOrientation, got {type(ro).__name__}")
    E = D_REFLECTION @ A2.T @ skew_matrix(b / np.linalg.norm(b)) @ A1 @ D_REFLECTION
    return E / np.linalg.norm(E)


def ransac_essential(xy1, xy2, io1: InteriorOrientation, io2: InteriorOrientation | None = None,
                     threshold: float = 0.01, confidence: float = 0.99, max_iterations: int = 500,
                     rng=0) -> RansacResult:
    """The essential matrix from five-point samples (§5.10 with §2.7 and §4.4), Sampson residuals.

    Each five-point sample is solved as a relative orientation (:func:`ransac_relative_orientation`)
    and turned into E (:func:`essential_from_relative_orientation`); the residual is the Sampson
    distance of E in normalised coordinates r″ (4.4.15) times f₁, i.e. in mm of image 1.

    Parameters
    ----------
    xy1, xy2 : (n, 2) arrays
        Image coordinates (mm), n ≥ 6.
    io1, io2 : InteriorOrientation
        Interior orientation (``io2`` defaults to ``io1``).
    threshold : float
        Largest Sampson distance (mm) of an inlier.
    confidence, max_iterations, rng
        As in :func:`ransac`.

    Returns
    -------
    RansacResult
        ``model`` is E (3×3, layout x2Fx1, unit norm).

    Raises
    ------
    InputError
        Fewer than 6 points, bad shapes, NaN, bad arguments.
    DegenerateGeometryError
        Every sample degenerate.
    ConvergenceError
        No consensus.

    References
    ----------
    Chibunichev (2022), §5.10; §4.4, eqs. (4.4.15), (4.4.16); Hartley & Zisserman (2003), §11.4.3.

    Examples
    --------
    >>> from photolib.synthetic import stereo_pair
    >>> p = stereo_pair(30, seed=0, angle_spread_deg=2.0, sigma=0.002)
    >>> xy2 = p.xy2.copy(); xy2[:6, 1] += 0.5
    >>> r = ransac_essential(p.xy1, xy2, p.io, threshold=0.01)
    >>> r.n_inliers, bool(r.inliers[:6].any())
    (24, False)
    """
    xy1, xy2 = _pairs(xy1, xy2, 6, "RANSAC for the essential matrix")
    io1, io2 = _io(io1, io2)
    n1 = normalized_image_coordinates(xy1, io1)[:, :2]
    n2 = normalized_image_coordinates(xy2, io2)[:, :2]
    ro_fit = _ro_fit(io1, io2, "dependent")

    def fit(sample):
        i = sample[2]
        return essential_from_relative_orientation(ro_fit((xy1[i], xy2[i])))

    def residual(E, d):
        return np.abs(sampson_distance(E, n1, n2)) * io1.f

    return ransac((xy1, xy2, np.arange(len(xy1))), fit, residual, 5, threshold, confidence, max_iterations, rng)


def ransac_fundamental_matrix(xy1, xy2, threshold: float, confidence: float = 0.99, max_iterations: int = 2000,
                              rng=0) -> RansacResult:
    """The fundamental matrix of §4.4 from eight-point samples (§5.10), Sampson residuals.

    The generic :func:`ransac` with the normalised eight-point solution
    (:func:`photolib.projective.fundamental_matrix`, rank 2 enforced) and the Sampson distance
    (:func:`photolib.projective.sampson_distance`).

    Parameters
    ----------
    xy1, xy2 : (n, 2) arrays
        Image coordinates, n ≥ 9.
    threshold : float
        Largest Sampson distance of an inlier (image units).
    confidence, max_iterations, rng
        As in :func:`ransac`.

    Returns
    -------
    RansacResult
        ``model`` is F (3×3, layout x2Fx1: x₂ᵀFx₁ = 0).

    Raises
    ------
    InputError
        Fewer than 9 points, bad shapes, NaN, bad arguments.
    DegenerateGeometryError
        Every sample degenerate.
    ConvergenceError
        No consensus.

    References
    ----------
    Chibunichev (2022), §5.10; §4.4, eqs. (4.4.11)–(4.4.14); Hartley & Zisserman (2003), §11.6.

    Examples
    --------
    >>> from photolib.synthetic import stereo_pair
    >>> p = stereo_pair(30, seed=0, angle_spread_deg=2.0, sigma=0.002)
    >>> xy2 = p.xy2.copy(); xy2[:6, 1] += 0.5
    >>> r = ransac_fundamental_matrix(p.xy1, xy2, threshold=0.01)
    >>> r.n_inliers, bool(r.inliers[:6].any())
    (24, False)
    """
    xy1, xy2 = _pairs(xy1, xy2, 9, "RANSAC for the fundamental matrix")

    def fit(sample):
        return fundamental_matrix(sample[0], sample[1])

    def residual(F, d):
        return np.abs(sampson_distance(F, d[0], d[1]))

    return ransac((xy1, xy2), fit, residual, 8, threshold, confidence, max_iterations, rng)
