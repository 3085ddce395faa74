"""Bundle block adjustment — Chapter 3, §3.5.

§3.5 "Построение и уравнивание маршрутной и блочной фототриангуляции по методу связок"
(building and adjusting strip and block phototriangulation by the bundle method).

Every measured image point gives the two collinearity equations (3.5.1); linearised they are
the correction equations (3.5.2) in the six exterior-orientation unknowns of the image and the
three coordinates of the point — (3.5.3) when the point is a control point held fixed. Control
known only to an accuracy comparable with the phototriangulation enters instead as weighted
observations of the coordinates (3.5.17); GNSS projection centres (3.5.18) and INS angles
(3.5.19) are weighted observations of the image unknowns. All of them are solved together by
least squares, VᵀPV = min (3.5.5)–(3.5.12), iterated.

The Jacobian is derived by sympy (:func:`photolib.derivations.bundle_collinearity_model`) and
printed to numpy code once (:func:`photolib.derivations.numpy_source`); the printed code is kept
in ``photolib/_bundle_generated.py`` so that adjusting a block does not import sympy (≈ 50 MB,
≈ 1 s). ``tests/test_bundle.py`` regenerates it from sympy and fails if it differs; rewrite it
with ``python -m photolib.bundle``.

The linear algebra is the one engine of :mod:`photolib.lsq`: its block path
:func:`~photolib.lsq.block_gauss_newton` eliminates the points (3.5.16) with 3×3 block inverses
and factorises the sparse reduced system of the image unknowns, so blocks of thousands of
images are adjusted in seconds. The Jacobian comes from the sympy model
:func:`~photolib.derivations.bundle_collinearity_model`.

Weights follow (3.5.7), p = σ₀²/m², with the unit weight σ₀ equal to the image measurement
accuracy, so μ (3.5.12) is in millimetres of the image and estimates the image noise.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import scipy.linalg  # noqa: F401 — imported here so that the solver's local imports cost nothing
import scipy.sparse.linalg  # noqa: F401
from scipy import sparse
from scipy.sparse.csgraph import connected_components

from . import _bundle_generated
from .camera import ExteriorOrientation, InteriorOrientation, correct_distortion
from .errors import ConvergenceError, DegenerateGeometryError, InputError
from .lsq import BlockCorrectionEquations, block_gauss_newton
from .rotation import check_order, rotation_matrix

__all__ = ["BundleResult", "CheckPointStatistics", "bundle_adjustment", "bundle_correction_equations",
           "check_point_statistics", "as_observations"]


@dataclass
class BundleResult:
    """Adjusted block: exterior orientations, points, μ, m_j, residuals and the iteration record."""

    cameras: np.ndarray              # (n, 6) X_S, Y_S, Z_S, ω, α, κ
    points: np.ndarray               # (k, 3) X, Y, Z
    mu: float                        # (3.5.12), mm of the image
    dof: int                         # M − N
    cameras_std: np.ndarray | None   # (n, 6) m_j (3.5.11); None when not computed
    points_std: np.ndarray | None    # (k, 3) m_j; zeros for fixed control
    residuals: np.ndarray            # (m, 2) v_x, v_y of the image observations, mm (computed − measured)
    control_residuals: np.ndarray    # (k, 3) v of weighted control (3.5.17), m; 0 elsewhere
    gnss_residuals: np.ndarray       # (n, 3) v of GNSS centres (3.5.18), m; 0 elsewhere
    ins_residuals: np.ndarray        # (n, 3) v of INS angles (3.5.19), rad; 0 elsewhere
    iterations: int
    history: list
    order: str
    timings: dict = field(default_factory=dict)

    def eo(self, i: int) -> ExteriorOrientation:
        """Exterior orientation of image ``i``."""
        return ExteriorOrientation.from_vector(self.cameras[i], order=self.order)

    @property
    def rms_image_residual(self) -> float:
        """√(mean of v_x² + v_y² over observations / 2) — r.m.s. per coordinate, mm."""
        return float(np.sqrt(np.mean(self.residuals ** 2)))


def as_observations(observations):
    """(image, point, xy) arrays from an object with those attributes, a dict, or an (m, 4) array."""
    if hasattr(observations, "image"):
        image, point, xy = observations.image, observations.point, observations.xy
    elif isinstance(observations, dict):
        image, point, xy = observations["image"], observations["point"], observations["xy"]
    else:
        arr = np.asarray(observations, dtype=float)
        if arr.ndim != 2 or arr.shape[1] != 4:
            raise InputError("observations: give image/point/xy arrays or an (m, 4) array [image, point, x, y]")
        image, point, xy = arr[:, 0], arr[:, 1], arr[:, 2:]
    image, point = np.asarray(image), np.asarray(point)
    xy = np.asarray(xy, dtype=float)
    if image.ndim != 1 or point.shape != image.shape or xy.shape != (image.size, 2):
        raise InputError(f"observations: image {image.shape}, point {point.shape} and xy {xy.shape} do not match")
    for name, idx in (("image", image), ("point", point)):
        if idx.size and (not np.all(np.isfinite(idx.astype(float))) or np.any(idx != np.round(idx)) or idx.min() < 0):
            raise InputError(f"observations: {name} indices must be non-negative integers")
    if not np.all(np.isfinite(xy)):
        raise InputError("observations: image coordinates contain NaN or inf")
    return image.astype(np.intp), point.astype(np.intp), xy


def _stack_cameras(cameras0, order):
    if len(cameras0) and isinstance(cameras0[0], ExteriorOrientation):
        if any(c.order != order for c in cameras0):
            raise InputError(f"all exterior orientations must use order {order!r}")
        return np.array([c.vector for c in cameras0])
    cams = np.array(cameras0, dtype=float)
    if cams.ndim != 2 or cams.shape[1] != 6:
        raise InputError(f"cameras0: expected (n, 6) X_S, Y_S, Z_S, ω, α, κ, got {cams.shape}")
    if not np.all(np.isfinite(cams)):
        raise InputError("cameras0 contain NaN or inf")
    return cams


def bundle_correction_equations(image, point, xy, cameras, points, io: InteriorOrientation,
                                order: str = "kaw", weight: float = 1.0) -> BlockCorrectionEquations:
    """Correction equations (3.5.2) of all image observations at the approximation.

    Rows k: a₁…a₆ (→ ``B1``), a₇…a₉ (→ ``B2``), l_x = x₀ − f x*/z* − x (→ ``L``) and the same for y,
    from the sympy model :func:`~photolib.derivations.bundle_collinearity_model`. Raises
    :class:`DegenerateGeometryError` if a point lies behind its image (z* ≥ 0).
    """
    A = rotation_matrix(cameras[:, 3], cameras[:, 4], cameras[:, 5], order)
    zstar = np.einsum("ki,ki->k", A[image][:, :, 2], points[point] - cameras[image, :3])
    if np.any(zstar >= 0):
        bad = np.flatnonzero(zstar >= 0)[:10]
        raise DegenerateGeometryError(
            f"observations {bad.tolist()}: the point is not in front of the image (z* ≥ 0)")
    fn = getattr(_bundle_generated, f"collinearity_{order}")
    c, X = cameras[image], points[point]
    F, J = fn(c[:, 0], c[:, 1], c[:, 2], c[:, 3], c[:, 4], c[:, 5], X[:, 0], X[:, 1], X[:, 2],
              xy[:, 0], xy[:, 1], io.f, io.x0, io.y0)
    J = J.reshape(2, 9, -1).transpose(2, 0, 1)
    return BlockCorrectionEquations(frame=image, point=point, B1=J[:, :, :6], B2=J[:, :, 6:], L=F.T,
                                    P=weight)


def _per_item(sigma, n, what):
    s = np.broadcast_to(np.asarray(sigma, dtype=float), (n, 3)).copy() if np.ndim(sigma) < 2 else \
        np.asarray(sigma, dtype=float)
    if s.shape != (n, 3) or np.any(~(s > 0)):
        raise InputError(f"{what}: σ must be positive, one value, three values or an ({n}, 3) array")
    return s


def _datum_rank(anchor_xyz, anchor_mask, angle_rows, centre, scale):
    """Rank (of 7) of the similarity transformations (datum) that the control fixes.

    Each controlled coordinate of a point X (control point or GNSS centre) is moved by an
    infinitesimal similarity as dX = t + r × X + s·X; INS angles by ≈ r. The block is free to
    move in the directions of the null space of these rows — its datum defect.
    """
    rows = []
    for X, mask in zip(anchor_xyz, anchor_mask):
        Xc = (X - centre) / scale
        D = np.array([[1, 0, 0, 0, Xc[2], -Xc[1], Xc[0]],
                      [0, 1, 0, -Xc[2], 0, Xc[0], Xc[1]],
                      [0, 0, 1, Xc[1], -Xc[0], 0, Xc[2]]], dtype=float)
        rows.append(D[mask])
    for mask in angle_rows:
        D = np.hstack([np.zeros((3, 3)), np.eye(3), np.zeros((3, 1))])
        rows.append(D[mask])
    if not rows:
        return 0
    M = np.vstack(rows)
    if M.size == 0:
        return 0
    sv = np.linalg.svd(M, compute_uv=False)
    return int(np.sum(sv > 1e-6 * max(sv[0], 1.0)))


def bundle_adjustment(observations, cameras0, points0, io: InteriorOrientation, *, control=None,
                      control_sigma=None, gnss=None, gnss_sigma=0.05, ins=None, ins_sigma=np.radians(0.005),
                      sigma_image: float = 0.005, order: str = "kaw", max_iter: int = 30,
                      tol_centre: float = 1e-5, tol_angle: float = 1e-9, tol_point: float = 1e-5,
                      covariance: bool | str = "auto", dense_limit: int = 0, progress=None) -> BundleResult:
    """Adjust a block of frame images by the bundle method, §3.5.

    Parameters
    ----------
    observations : Observations, dict or (m, 4) array
        Measured image coordinates (mm): ``image``, ``point``, ``xy`` (see
        :class:`photolib.synthetic.Observations`). Distortion of ``io`` is corrected first (1.2.3).
    cameras0 : (n, 6) array or list of ExteriorOrientation
        Approximate X_S, Y_S, Z_S, ω, α, κ of every image (angles of sequence ``order``).
    points0 : (k, 3) array
        Approximate coordinates of every point (control points may hold anything; they are
        replaced by ``control``).
    io : InteriorOrientation
        Known interior orientation (f, x₀, y₀, distortion), mm.
    control : dict {point index: (X, Y, Z)} or (indices, (c, 3) array), optional
        Geodetic control. With ``control_sigma=None`` the points are held fixed (rigid insertion,
        (3.5.3)); otherwise they are unknowns with weighted observations (3.5.17), and a NaN
        coordinate makes a planimetric (Z NaN) or height (X, Y NaN) control point.
    control_sigma : None, float, (3,) or (c, 3)
        Accuracy m of the control coordinates (m).
    gnss : (n, 3) array, optional
        GNSS projection centres (3.5.18), NaN rows for images without them; accuracy ``gnss_sigma`` (m).
    ins : (n, 3) array, optional
        Measured ω, α, κ (3.5.19), NaN rows where missing; accuracy ``ins_sigma`` (rad).
    sigma_image : float
        Accuracy of the image measurements (mm) — the unit weight σ₀ of (3.5.7).
    order : {"kaw", "wak"}
        Rotation sequence of the angles.
    max_iter, tol_centre, tol_angle, tol_point
        Iteration limit and the corrections (m, rad, m) below which the iteration stops.
    covariance : bool or "auto"
        Compute m_j (3.5.11) of all unknowns (needs the dense inverse of the reduced matrix,
        O((6n)²) memory); ``"auto"`` does it for up to 500 free images.
    dense_limit : int
        Reduced systems (3.5.16) up to this size are factorised with dense Cholesky, larger ones
        with the sparse symmetric factorisation. The default 0 always uses the sparse one: it is
        as fast for small blocks and does not depend on multithreaded BLAS, which on a busy
        machine made the dense path 10–40× slower in our measurements.
    progress : callable, optional
        Called with each :class:`photolib.lsq.IterationRecord`.

    Returns
    -------
    BundleResult

    Raises
    ------
    InputError
        Malformed input; a free point measured in only one image; an image with fewer than three points.
    DegenerateGeometryError
        Too little control to fix the datum (position, rotation, scale); a block that falls apart
        into groups of images without common points; points behind an image.
    ConvergenceError
        The iteration diverged or did not converge in ``max_iter`` steps.
    """
    check_order(order)
    if not isinstance(io, InteriorOrientation):
        raise InputError("io must be an InteriorOrientation")
    image, point, xy = as_observations(observations)
    cams = _stack_cameras(cameras0, order)
    pts = np.array(points0, dtype=float)
    if pts.ndim != 2 or pts.shape[1] != 3 or not np.all(np.isfinite(pts)):
        raise InputError(f"points0: expected a finite (k, 3) array, got shape {np.shape(points0)}")
    n, k = cams.shape[0], pts.shape[0]
    if image.size == 0:
        raise InputError("no image observations")
    if image.max() >= n or point.max() >= k:
        raise InputError(f"observations refer to image {image.max()} / point {point.max()} "
                         f"but only {n} images / {k} points are given")
    if np.any(np.bincount(image * k + point, minlength=n * k) > 1):
        raise InputError("a point is measured twice in the same image")
    if not sigma_image > 0:
        raise InputError("sigma_image must be positive")
    if io.has_distortion:
        xy = correct_distortion(xy, io)

    # control (3.5.3) fixed or (3.5.17) weighted
    free_points = np.ones(k, bool)
    point_obs = None
    ctrl_idx = np.zeros(0, np.intp)
    ctrl_xyz = np.zeros((0, 3))
    if control is not None:
        if isinstance(control, dict):
            ctrl_idx = np.array(list(control.keys()), dtype=np.intp)
            ctrl_xyz = np.array([control[i] for i in control], dtype=float).reshape(-1, 3)
        else:
            ctrl_idx = np.asarray(control[0], dtype=np.intp)
            ctrl_xyz = np.asarray(control[1], dtype=float).reshape(-1, 3)
        if ctrl_idx.size != ctrl_xyz.shape[0] or (ctrl_idx.size and (ctrl_idx.min() < 0 or ctrl_idx.max() >= k)):
            raise InputError("control: indices must refer to the points and match the coordinates")
        if np.unique(ctrl_idx).size != ctrl_idx.size:
            raise InputError("control: a point is given twice")
        if control_sigma is None:
            if not np.all(np.isfinite(ctrl_xyz)):
                raise InputError("fixed control points need all three coordinates (NaN found); "
                                 "give control_sigma to use planimetric or height control")
            free_points[ctrl_idx] = False
            pts[ctrl_idx] = ctrl_xyz
        else:
            s = _per_item(control_sigma, ctrl_idx.size, "control_sigma")
            values = np.full((k, 3), np.nan)
            weights = np.zeros((k, 3))
            values[ctrl_idx] = ctrl_xyz
            weights[ctrl_idx] = np.where(np.isfinite(ctrl_xyz), (sigma_image / s) ** 2, 0.0)
            point_obs = (values, weights)
            known = np.isfinite(ctrl_xyz)
            start = pts[ctrl_idx]
            pts[ctrl_idx] = np.where(known, ctrl_xyz, start)

    # GNSS centres (3.5.18) and INS angles (3.5.19)
    frame_values = np.full((n, 6), np.nan)
    frame_weights = np.zeros((n, 6))
    for data, sig, cols, what in ((gnss, gnss_sigma, slice(0, 3), "gnss"), (ins, ins_sigma, slice(3, 6), "ins")):
        if data is None:
            continue
        data = np.asarray(data, dtype=float)
        if data.shape != (n, 3):
            raise InputError(f"{what}: expected an ({n}, 3) array with NaN rows where missing, got {data.shape}")
        s = _per_item(sig, n, f"{what}_sigma")
        frame_values[:, cols] = data
        frame_weights[:, cols] = np.where(np.isfinite(data), (sigma_image / s) ** 2, 0.0)
    frame_obs = (frame_values, frame_weights) if np.any(frame_weights > 0) else None

    # every free point must be intersected by at least two rays (or be observed directly)
    rays = np.bincount(point, minlength=k)
    direct = np.zeros(k, bool) if point_obs is None else np.all(point_obs[1] > 0, axis=1)
    single = np.flatnonzero(free_points & (rays < 2) & ~direct)
    if single.size:
        raise InputError(f"points {single[:10].tolist()} are measured in fewer than two images; "
                         "a free point needs at least two rays (remove them or give their coordinates)")
    per_image = np.bincount(image, minlength=n)
    weak = np.flatnonzero(per_image < 3)
    if weak.size:
        raise InputError(f"images {weak[:10].tolist()} have fewer than three measured points")

    # connectivity: images linked through common points
    incidence = sparse.csr_matrix((np.ones(image.size), (image, point)), shape=(n, k))
    n_parts, labels = connected_components(incidence @ incidence.T, directed=False)
    if n_parts > 1:
        sizes = np.bincount(labels)
        raise DegenerateGeometryError(
            f"the block falls apart into {n_parts} groups of images without common points "
            f"(sizes {sizes.tolist()}); connect them with tie points or adjust them separately")

    # datum: the control must fix the 7 parameters of a spatial similarity
    anchors, masks, angle_rows = [], [], []
    if ctrl_idx.size:
        anchors += list(pts[ctrl_idx])
        masks += list(np.ones((ctrl_idx.size, 3), bool) if control_sigma is None else np.isfinite(ctrl_xyz))
    if frame_obs is not None:
        has = frame_weights[:, :3] > 0
        anchors += list(np.where(has, frame_values[:, :3], 0.0)[has.any(1)])
        masks += list(has[has.any(1)])
        ang = frame_weights[:, 3:] > 0
        angle_rows += list(ang[ang.any(1)])
    centre = cams[:, :3].mean(axis=0)
    scale = max(float(np.ptp(cams[:, :2], axis=0).max()), float(np.abs(cams[:, 2] - pts[:, 2].mean()).mean()), 1.0)
    rank = _datum_rank(anchors, masks, angle_rows, centre, scale)
    if rank < 7:
        raise DegenerateGeometryError(
            f"datum defect: the control fixes only {rank} of the 7 datum parameters (3 shifts, 3 rotations, "
            "scale); add control points (at least 3 not on one line, e.g. XYZ points in the block corners) "
            "or GNSS centres")

    use_cov = (6 * n <= 3000) if covariance == "auto" else bool(covariance)

    def linearize(frames, points):
        return bundle_correction_equations(image, point, xy, frames, points, io, order)

    try:
        adj = block_gauss_newton(linearize, cams, pts, frame_observations=frame_obs, point_observations=point_obs,
                                 free_points=free_points, tol_frames=[tol_centre] * 3 + [tol_angle] * 3,
                                 tol_points=tol_point, max_iter=max_iter, covariance=use_cov, dense_limit=dense_limit,
                                 progress=progress)
    except DegenerateGeometryError as exc:
        if "not in front" in str(exc):
            raise ConvergenceError(f"the iteration diverged: {exc}") from exc
        raise
    zeros3 = np.zeros((n, 3))
    fr = adj.frame_residuals if frame_obs is not None else np.zeros((n, 6))
    return BundleResult(cameras=adj.frames, points=adj.points, mu=adj.mu, dof=adj.dof,
                        cameras_std=adj.frames_std, points_std=adj.points_std, residuals=adj.residuals,
                        control_residuals=adj.point_residuals if point_obs is not None else np.zeros((k, 3)),
                        gnss_residuals=fr[:, :3] if gnss is not None else zeros3,
                        ins_residuals=fr[:, 3:] if ins is not None else zeros3,
                        iterations=adj.iterations, history=adj.history, order=order,
                        timings=adj.timings)


@dataclass(frozen=True)
class CheckPointStatistics:
    """Errors of adjusted points against independent (check) coordinates."""

    n: int
    mean: np.ndarray          # (3,) mean error X, Y, Z (m)
    rms: np.ndarray           # (3,) r.m.s. error (m)
    max_abs: np.ndarray       # (3,) largest |error| (m)
    predicted: np.ndarray | None  # (3,) r.m.s. of the a-posteriori m_j (3.5.11) at the same points

    @property
    def ratio(self) -> np.ndarray | None:
        """rms / predicted: ≈ 1 when the accuracy estimate is honest."""
        return None if self.predicted is None else self.rms / self.predicted


def check_point_statistics(result: BundleResult, true_points, indices) -> CheckPointStatistics:
    """Compare adjusted points ``indices`` with their true (check) coordinates ``true_points``.

    ``true_points`` is either the (len(indices), 3) check coordinates or the full (k, 3) array.
    """
    idx = np.asarray(indices, dtype=np.intp)
    truth = np.asarray(true_points, dtype=float)
    if truth.shape == result.points.shape:
        truth = truth[idx]
    if truth.shape != (idx.size, 3) or idx.size == 0:
        raise InputError("check points: give indices and their (c, 3) true coordinates")
    err = result.points[idx] - truth
    pred = None if result.points_std is None else np.sqrt(np.mean(result.points_std[idx] ** 2, axis=0))
    return CheckPointStatistics(n=idx.size, mean=err.mean(axis=0), rms=np.sqrt(np.mean(err ** 2, axis=0)),
                                max_abs=np.abs(err).max(axis=0), predicted=pred)


def generated_source() -> str:
    """Text of ``photolib/_bundle_generated.py``, printed from the sympy models (imports sympy)."""
    from .derivations import bundle_collinearity_model, numpy_source
    parts = ['"""GENERATED by ``python -m photolib.bundle`` from photolib.derivations.bundle_collinearity_model',
             "— do not edit. Residuals (3.5.1) and Jacobian (3.5.2) of the bundle model, one function per",
             'rotation sequence; see :func:`photolib.derivations.numpy_source`."""', "", "import numpy", ""]
    for order in ("kaw", "wak"):
        parts += ["", numpy_source(bundle_collinearity_model(order), f"collinearity_{order}")]
    return "\n".join(parts)


if __name__ == "__main__":
    from pathlib import Path
    target = Path(__file__).with_name("_bundle_generated.py")
    target.write_text(generated_source())
    print(f"wrote {target}")
