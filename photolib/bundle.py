"""Bundle block adjustment — Chapter 3, §3.5, with the extensions of §3.6, §3.8 and §3.9.

Extensions (second half of the module): self-calibration (3.6.1)–(3.6.3) with f, x₀, y₀, k₁…p₂ as
block-wide unknowns and the correlation report of §3.6 (:func:`self_calibrating_bundle_adjustment`);
multi-camera rigs with constant mounting elements (3.8.2)–(3.8.15) (:func:`rig_bundle_adjustment`);
rolling-shutter images (3.9.1)/(3.9.2) with their implicit projection (:func:`rolling_shutter_project`,
:func:`rolling_shutter_bundle_adjustment`); the unknown counts (3.5.20), (3.8.1), (3.8.2), §3.6, §3.9.

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
with ``python -m photolib.bundle``. The bundle's own equations use the printed model of one observation
(``collinearity_<order>_point``) inside a loop compiled by numba (:mod:`photolib._block_kernels`).

The linear algebra is the one engine of :mod:`photolib.lsq`: its block path
:func:`~photolib.lsq.block_gauss_newton` eliminates the points (3.5.16) with 3×3 block inverses
and factorises the sparse reduced system of the image unknowns, so blocks of thousands of
images are adjusted in seconds. The Jacobian comes from the sympy model
:func:`~photolib.derivations.bundle_collinearity_model`.

Weights follow (3.5.7), p = σ₀²/m², with the unit weight σ₀ equal to the image measurement
accuracy, so μ (3.5.12) is in millimetres of the image and estimates the image noise.

Chapter 11, §11.6 adds the geometric conditions of terrestrial surveys — measured distances
between points (11.6.1), the base (11.6.2), centre-to-point distances (11.6.3), vertical lines
(11.6.4), horizontal planes (11.6.5) and the (corrected) plane condition — to the bundle as
weighted correction equations (11.6.7) (``conditions=`` of :func:`bundle_adjustment` and
:func:`self_calibrating_bundle_adjustment`; F and ∂F/∂p from
:func:`photolib.terrestrial.condition_equations`). They join the datum test (a distance gives the
scale). A condition couples several points, which the per-point 3×3 elimination (3.5.16) of the
block solver cannot hold, so a block with conditions is solved by the dense solver of the same
engine (:func:`photolib.lsq.gauss_newton`), with the same correction equations.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import scipy.linalg  # noqa: F401 — imported here so that the solver's local imports cost nothing
import scipy.sparse.csgraph  # noqa: F401 — (reverse Cuthill–McKee of the block pattern)
import scipy.sparse.linalg  # noqa: F401
from scipy.special import stdtrit

from . import _bundle_generated
from . import additional_parameters as apm
from .camera import ExteriorOrientation, ExteriorOrientations, InteriorOrientation, correct_distortion
from .errors import ConvergenceError, DegenerateGeometryError, InputError, PointBehindCameraError
from .lsq import (BlockCorrectionEquations, GlobalBlockCorrectionEquations, block_equations_dense, block_gauss_newton,
                  gauss_newton, global_block_equations_dense)
from .rotation import check_order, rotation_angles, rotation_matrix
from .single_image import project_to_images

__all__ = ["BundleResult", "CheckPointStatistics", "bundle_adjustment", "bundle_correction_equations",
           "check_point_statistics",
           # §3.6 self-calibration
           "IO_NAMES", "DISTORTION_NAMES", "CorrelationReport", "SelfCalibrationResult",
           "self_calibrating_bundle_adjustment", "self_calibration_correction_equations",
           # Hanzl §4.4 additional parameters
           "APTestReport", "additional_parameter_tests", "select_additional_parameters",
           # §3.8 rigs
           "MOUNT_NAMES", "RigResult", "rig_image_orientation", "rig_bundle_adjustment",
           "rig_design_matrix",
           # §3.9 rolling shutter
           "RollingShutterResult", "rolling_shutter_project", "rolling_shutter_correction_equations",
           "rolling_shutter_bundle_adjustment",
           # counts
           "count_bundle_unknowns", "count_self_calibration_unknowns", "count_rig_unknowns",
           "count_rolling_shutter_unknowns"]


@dataclass
class BundleResult:
    """Adjusted block: exterior orientations, points, μ, m_j, residuals and the iteration record.

    Attributes
    ----------
    cameras : ndarray (n, 6)
        Adjusted X_S, Y_S, Z_S (m), ω, α, κ (rad).
    points : ndarray (k, 3)
        Adjusted points (m).
    mu : float
        μ (3.5.12), mm of the image.
    dof : int
        M − N.
    cameras_std, points_std : ndarray or None
        m_j (3.5.11); None when the covariance was not computed.
    residuals : ndarray (m, 2)
        v_x, v_y (mm, computed − measured).
    control_residuals, gnss_residuals, ins_residuals : ndarray
        V of weighted control (3.5.17), GNSS centres (3.5.18), INS angles (3.5.19); 0 where none.
    iterations : int
    history : list of IterationRecord
    order : str
    timings : dict
        Seconds per stage of the solver.
    condition_residuals : ndarray
        V of the geometric conditions of §11.6 (``conditions=`` of :func:`bundle_adjustment`), one
        per condition equation in the order of the conditions (a vertical line gives two, X then
        Y), in the units of the condition; empty without conditions.

    References
    ----------
    Chibunichev (2022), §3.5, eqs. (3.5.1)–(3.5.12); §1.8, eqs. (1.8.5)–(1.8.10).

    Examples
    --------
    >>> import numpy as np
    >>> from photolib import synthetic
    >>> blk = synthetic.aerial_block(2, 4, points_per_image=15, sigma=0.0, seed=1)
    >>> cams0, pts0 = blk.start_values(seed=2)
    >>> control = {int(i): blk.points[i] for i in blk.control}
    >>> res = bundle_adjustment(blk.observations, cams0, pts0, blk.io, control=control, order=blk.order)
    >>> float(np.abs(res.cameras - blk.cameras).max()) < 1e-6      # noise-free block: the truth
    True
    >>> len(res.orientations), res.orientations.order == blk.order
    (8, True)
    >>> print(res.summary().splitlines()[0][:52])
    Bundle adjustment (§3.5): 8 images, 37 points, 4 ite
    """

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
    condition_residuals: np.ndarray = field(default_factory=lambda: np.zeros(0))  # v of the §11.6 conditions

    def eo(self, i: int) -> ExteriorOrientation:
        """Exterior orientation of image ``i``."""
        return ExteriorOrientation.from_vector(self.cameras[i], order=self.order)

    @property
    def orientations(self) -> ExteriorOrientations:
        """All adjusted exterior orientations as one vectorised collection carrying the order."""
        return ExteriorOrientations.from_vectors(self.cameras, order=self.order)

    @property
    def rms_image_residual(self) -> float:
        """√(mean of v_x² + v_y² over observations / 2) — r.m.s. per coordinate, mm."""
        return float(np.sqrt(np.mean(self.residuals ** 2)))

    def summary(self) -> str:
        """A short readable text: size, iterations, μ and the r.m.s. accuracy of the unknowns."""
        lines = [f"Bundle adjustment (§3.5): {len(self.cameras)} images, {len(self.points)} points, "
                 f"{self.iterations} iterations, dof {self.dof}",
                 f"  mu = {1000 * float(self.mu):.4g} µm (r.m.s. error of unit weight, image)",
                 f"  r.m.s. image residual = {1000 * self.rms_image_residual:.4g} µm"]
        if self.cameras_std is not None:
            c = np.sqrt(np.mean(self.cameras_std ** 2, axis=0))
            lines.append(f"  r.m.s. m of the centres: {float(c[0]):.4g}, {float(c[1]):.4g}, {float(c[2]):.4g} m; "
                         f"of the angles: {', '.join(f'{float(np.degrees(v) * 3600):.3g}' for v in c[3:])} arc-seconds")
        return "\n".join(lines)

    def __repr__(self) -> str:
        return (f"<{type(self).__name__}: {len(self.cameras)} images, {len(self.points)} points, "
                f"mu={1000 * float(self.mu):.4g} µm, dof={self.dof}, {self.iterations} iterations>")


def _as_observations(observations):
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
        integral = np.issubdtype(idx.dtype, np.integer)        # integers: finite and whole by type
        if idx.size and ((not integral and (not np.all(np.isfinite(idx.astype(float)))
                                             or np.any(idx != np.round(idx)))) or idx.min() < 0):
            raise InputError(f"observations: {name} indices must be non-negative integers")
    if not np.all(np.isfinite(xy)):
        raise InputError("observations: image coordinates contain NaN or inf")
    return image.astype(np.intp), point.astype(np.intp), xy


_OLD_NAMES = {"control_sigma": "sigma_control", "gnss_sigma": "sigma_centre", "ins_sigma": "sigma_angles",
              "io_sigma": "sigma_io", "weight": "weights"}


def _renamed(legacy, func, **current):
    """The values of renamed parameters, accepting their former spellings (``control_sigma=`` …)."""
    for old, value in legacy.items():
        new = _OLD_NAMES.get(old)
        if new is None or new not in current:
            raise InputError(f"{func}() got an unexpected keyword argument {old!r}")
        current[new] = value
    return tuple(current.values())


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
                                order: str = "kaw", weights: float = 1.0, **legacy) -> BlockCorrectionEquations:
    """Correction equations (3.5.2) of all image observations at the approximation.

    Rows k: a₁…a₆ (→ ``B1``), a₇…a₉ (→ ``B2``), l_x = x₀ − f x*/z* − x (→ ``L``) and the same for y,
    from the sympy model :func:`~photolib.derivations.bundle_collinearity_model`. Raises
    :class:`DegenerateGeometryError` if a point lies behind its image (z* ≥ 0).

    Parameters
    ----------
    image, point : int arrays (m,)
        Image and point of every observation.
    xy : ndarray (m, 2)
        Measured image coordinates, mm.
    cameras : ndarray (n, 6)
        Approximate exterior orientations (X_S, Y_S, Z_S, ω, α, κ).
    points : ndarray (k, 3)
        Approximate points.
    io : InteriorOrientation
        f, x₀, y₀ (mm).
    order : {"kaw", "wak"}
        Rotation sequence.
    weights : float or array (m, 2)
        Weights of the image coordinates (``weight=`` is accepted as the former name).

    Returns
    -------
    BlockCorrectionEquations
        B1 (m, 2, 6), B2 (m, 2, 3), L (m, 2) and the weights.

    Raises
    ------
    PointBehindCameraError
        A point lies behind its image (z* ≥ 0); ``points`` names them.

    References
    ----------
    Chibunichev (2022), §3.5, eqs. (3.5.1)–(3.5.3).

    Examples
    --------
    >>> import numpy as np
    >>> from photolib import synthetic
    >>> blk = synthetic.aerial_block(2, 4, points_per_image=15, sigma=0.0, seed=1)
    >>> cams0, pts0 = blk.start_values(seed=2)
    >>> control = {int(i): blk.points[i] for i in blk.control}
    >>> o = blk.observations
    >>> eq = bundle_correction_equations(o.image, o.point, o.xy, blk.cameras, blk.points, blk.io, blk.order)
    >>> eq.B1.shape[1:], eq.B2.shape[1:], float(np.abs(eq.L).max()) < 1e-9     # at the truth L = 0
    ((2, 6), (2, 3), True)
    """
    (weights,) = _renamed(legacy, "bundle_correction_equations", weights=weights)
    from . import _block_kernels
    check_order(order)
    image, point = np.asarray(image, np.intp), np.asarray(point, np.intp)
    m = image.size
    B1, B2, L, zstar = np.empty((m, 2, 6)), np.empty((m, 2, 3)), np.empty((m, 2)), np.empty(m)
    # the sympy-printed model of one observation, in a compiled loop over the observations
    _block_kernels.collinearity(order == "wak", np.ascontiguousarray(cameras, dtype=float),
                                np.ascontiguousarray(points, dtype=float), image, point,
                                np.ascontiguousarray(xy, dtype=float), float(io.f), float(io.x0), float(io.y0),
                                B1, B2, L, zstar)
    _raise_behind(zstar, point)
    return BlockCorrectionEquations(frame=image, point=point, B1=B1, B2=B2, L=L, P=weights)


def _per_item(sigma, n, what):
    s = np.broadcast_to(np.asarray(sigma, dtype=float), (n, 3)).copy() if np.ndim(sigma) < 2 else \
        np.asarray(sigma, dtype=float)
    if s.shape != (n, 3) or np.any(~(s > 0)):
        raise InputError(f"{what}: σ must be positive, one value, three values or an ({n}, 3) array")
    return s


def _similarity_rows(Xc):
    """d(X)/d(t, r, s) of the infinitesimal similarity dX = t + r × X + s·X at the points Xc: (p, 3, 7)."""
    D = np.zeros((len(Xc), 3, 7))
    D[:, 0, 0] = D[:, 1, 1] = D[:, 2, 2] = 1.0
    D[:, 0, 4], D[:, 0, 5], D[:, 0, 6] = Xc[:, 2], -Xc[:, 1], Xc[:, 0]
    D[:, 1, 3], D[:, 1, 5], D[:, 1, 6] = -Xc[:, 2], Xc[:, 0], Xc[:, 1]
    D[:, 2, 3], D[:, 2, 4], D[:, 2, 6] = Xc[:, 1], -Xc[:, 0], Xc[:, 2]
    return D


def _datum_rank(anchor_xyz, anchor_mask, angle_rows, centre, scale, extra_rows=None):
    """Rank (of 7) of the similarity transformations (datum) that the control fixes.

    Each controlled coordinate of a point X (control point or GNSS centre) is moved by an
    infinitesimal similarity as dX = t + r × X + s·X; INS angles by ≈ r. ``extra_rows`` (r, 7)
    are further rows of the same kind — the geometric conditions of §11.6
    (:func:`_condition_datum_rows`). The block is free to move in the directions of the null
    space of these rows — its datum defect.
    """
    Xc = (np.asarray(anchor_xyz, dtype=float).reshape(-1, 3) - centre) / scale
    D = _similarity_rows(Xc)
    ins = np.asarray(angle_rows, bool).reshape(-1, 3)
    M = D[np.asarray(anchor_mask, bool).reshape(-1, 3)]
    if ins.size:
        angles = np.hstack([np.zeros((3, 3)), np.eye(3), np.zeros((3, 1))])
        M = np.vstack([M, np.broadcast_to(angles, (len(ins), 3, 7))[ins]])
    if extra_rows is not None and len(extra_rows):
        M = np.vstack([M.reshape(-1, 7), np.asarray(extra_rows, dtype=float).reshape(-1, 7)])
    if M.size == 0:
        return 0
    sv = np.linalg.svd(M, compute_uv=False)
    return int(np.sum(sv > 1e-6 * max(sv[0], 1.0)))


@dataclass
class _Block:
    """A validated block with its control, GNSS and INS observations (from :func:`_prepare_block`)."""

    image: np.ndarray            # (m,) image index of each observation
    point: np.ndarray            # (m,) point index of each observation
    xy: np.ndarray               # (m, 2) measured image coordinates, mm (distortion corrected if asked)
    cams: np.ndarray             # (n, 6) start values of the exterior orientations
    pts: np.ndarray              # (k, 3) start values of the points (fixed control inserted)
    n: int                       # number of images
    k: int                       # number of points
    free_points: np.ndarray      # (k,) False for control held fixed (3.5.3)
    point_obs: tuple | None      # (values, weights) of weighted control (3.5.17)
    frame_obs: tuple | None      # (values, weights) of GNSS centres / INS angles (3.5.18)/(3.5.19)
    ctrl_idx: np.ndarray         # indices of the control points
    ctrl_xyz: np.ndarray         # their coordinates (NaN: not controlled)
    conditions: tuple = ()       # validated geometric conditions of §11.6 (_Condition)


def _prepare_block(observations, cameras0, points0, io, control, control_sigma, gnss, gnss_sigma, ins, ins_sigma,
                   sigma_image, order, correct_distortion_first=True, conditions=None):
    """Validate a block and assemble control, GNSS and INS observations — shared by every bundle variant.

    ``conditions``, parsed by :func:`_parse_conditions`, join the datum test. Returns a
    :class:`_Block`. Raises the errors documented in :func:`bundle_adjustment`.
    """
    check_order(order)
    if not isinstance(io, InteriorOrientation):
        raise InputError("io must be an InteriorOrientation")
    image, point, xy = _as_observations(observations)
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
    if np.unique(image.astype(np.int64) * k + point).size < image.size:
        raise InputError("a point is measured twice in the same image")
    if not sigma_image > 0:
        raise InputError("sigma_image must be positive")
    conditions = _parse_conditions(conditions, n, k)
    if correct_distortion_first and io.has_distortion:
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
                                 "give sigma_control to use planimetric or height control")
            free_points[ctrl_idx] = False
            pts[ctrl_idx] = ctrl_xyz
        else:
            s = _per_item(control_sigma, ctrl_idx.size, "sigma_control")
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
        s = _per_item(sig, n, {"gnss": "sigma_centre", "ins": "sigma_angles"}[what])
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

    # connectivity: images linked through common points (the connected components of the graph of
    # images and points, an edge image → point for every observation; union–find, compiled)
    from . import _block_kernels
    labels = np.empty(n, np.intp)
    n_parts = int(_block_kernels.image_components(image, point, n, k, labels))
    if n_parts > 1:
        sizes = np.bincount(labels)
        raise DegenerateGeometryError(
            f"the block falls apart into {n_parts} groups of images without common points "
            f"(sizes {sizes.tolist()}); connect them with tie points or adjust them separately")

    # datum: the control must fix the 7 parameters of a spatial similarity
    anchors = pts[ctrl_idx]
    masks = np.ones((ctrl_idx.size, 3), bool) if control_sigma is None else np.isfinite(ctrl_xyz)
    angle_rows = np.zeros((0, 3), bool)
    if frame_obs is not None:
        has = frame_weights[:, :3] > 0
        anchors = np.concatenate([anchors, np.where(has, frame_values[:, :3], 0.0)[has.any(1)]])
        masks = np.concatenate([masks, has[has.any(1)]])
        ang = frame_weights[:, 3:] > 0
        angle_rows = ang[ang.any(1)]
    centre = cams[:, :3].mean(axis=0)
    scale = max(float(np.ptp(cams[:, :2], axis=0).max()), float(np.abs(cams[:, 2] - pts[:, 2].mean()).mean()), 1.0)
    extra = None if not conditions else _condition_datum_rows(conditions, cams, pts, centre, scale)
    rank = _datum_rank(anchors, masks, angle_rows, centre, scale, extra)
    if rank < 7:
        what = "the control and the conditions fix" if conditions else "the control fixes"
        raise DegenerateGeometryError(
            f"datum defect: {what} only {rank} of the 7 datum parameters (3 shifts, 3 rotations, "
            "scale); add control points (at least 3 not on one line, e.g. XYZ points in the block corners), "
            "GNSS centres or, for the scale, a measured distance (§11.6)")

    return _Block(image=image, point=point, xy=xy, cams=cams, pts=pts, n=n, k=k, free_points=free_points,
                  point_obs=point_obs, frame_obs=frame_obs, ctrl_idx=ctrl_idx, ctrl_xyz=ctrl_xyz,
                  conditions=conditions)


def bundle_adjustment(observations, cameras0, points0, io: InteriorOrientation, *, control=None,
                      sigma_control=None, gnss=None, sigma_centre=0.05, ins=None, sigma_angles=np.radians(0.005),
                      conditions=None, sigma_image: float = 0.005, order: str = "kaw", max_iter: int = 30,
                      tol_centre: float = 1e-5, tol_angle: float = 1e-9, tol_point: float = 1e-5,
                      covariance: bool | str = "auto", dense_limit: int = 0, progress=None, **legacy) -> BundleResult:
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
    conditions : list of (kind, indices, measured, sigma), optional
        Geometric conditions of terrestrial surveys, §11.6 (11.6.1)–(11.6.7), added to the
        adjustment as weighted correction equations ∂F/∂p·δ + F = v with weight (σ_image/σ)²; F
        and ∂F/∂p are those of :func:`photolib.terrestrial.condition_equations`. ``kind`` and
        ``indices``: ``"distance"`` (point i, point j) (11.6.1); ``"base"`` (image i, image j):
        the distance of their projection centres (11.6.2); ``"centre_distance"`` (point i,
        image j) (11.6.3); ``"vertical"`` (point i, point j): X_i = X_j, Y_i = Y_j (11.6.4);
        ``"horizontal"`` (point i, point j): Z_i = Z_j (11.6.5); ``"coplanar"`` (points i, j,
        k, l): the corrected plane condition replacing (11.6.6). ``measured``: the measured
        length (m) of the three distance kinds, None for the others. ``sigma``: its accuracy in
        the units of F (m; m³ for ``"coplanar"``, whose F is the determinant, six times the volume
        of the tetrahedron). Conditions join the datum test: a distance fixes the scale, a
        vertical line the two tilts, a horizontal pair one tilt. A condition couples several
        points, so with conditions the block is solved by the dense path of the engine
        (:func:`photolib.lsq.gauss_newton` on :func:`photolib.lsq.block_equations_dense` plus
        the condition rows) instead of the reduction (3.5.16): meant for terrestrial blocks of
        up to a few hundred unknowns; ``covariance`` and ``dense_limit`` are then ignored (m_j
        are always computed).
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
        with the band Cholesky after a bandwidth-reducing renumbering of the images
        (:class:`photolib.lsq._Factorisation`). The default 0 always uses the band one: it is as
        fast for small blocks and needs far less memory for large ones.
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
        into groups of images without common points.
    PointBehindCameraError
        The start values put points behind an image that measures them (``points`` names them).
    ConvergenceError
        The iteration diverged (also: points moved behind an image during it) or did not converge
        in ``max_iter`` steps.

    References
    ----------
    Chibunichev (2022), §3.5, eqs. (3.5.1)–(3.5.12); §1.8, eqs. (1.8.5)–(1.8.10). Weighted control, GNSS and INS:
    eqs. (3.5.17)–(3.5.19); reduction (3.5.13)–(3.5.16). Conditions: §11.6, eqs. (11.6.1)–(11.6.7).

    Examples
    --------
    >>> import numpy as np
    >>> from photolib import synthetic
    >>> blk = synthetic.aerial_block(2, 4, points_per_image=15, sigma=0.0, seed=1)
    >>> cams0, pts0 = blk.start_values(seed=2)
    >>> control = {int(i): blk.points[i] for i in blk.control}
    >>> res = bundle_adjustment(blk.observations, cams0, pts0, blk.io, control=control, order=blk.order)
    >>> res.iterations, float(np.abs(res.points - blk.points).max()) < 1e-6
    (4, True)

    A measured distance (11.6.1) gives the scale: one image's position and attitude known (as
    GNSS and INS) leave only the scale free, and the distance of points 0 and 1 fixes it.

    >>> d01 = float(np.linalg.norm(blk.points[0] - blk.points[1]))
    >>> res = bundle_adjustment(blk.observations, cams0, pts0, blk.io, order=blk.order,
    ...                         gnss=np.where(np.arange(8)[:, None] == 0, blk.cameras[:, :3], np.nan),
    ...                         ins=np.where(np.arange(8)[:, None] == 0, blk.cameras[:, 3:], np.nan),
    ...                         sigma_centre=1e-4, sigma_angles=1e-7, conditions=[("distance", (0, 1), d01, 0.001)])
    >>> float(np.abs(res.points - blk.points).max()) < 1e-4, res.condition_residuals.shape
    (True, (1,))
    """
    sigma_control, sigma_centre, sigma_angles = _renamed(
        legacy, "bundle_adjustment", sigma_control=sigma_control, sigma_centre=sigma_centre, sigma_angles=sigma_angles)
    b = _prepare_block(observations, cameras0, points0, io, control, sigma_control, gnss, sigma_centre, ins,
                       sigma_angles, sigma_image, order, conditions=conditions)
    image, point, xy, cams, pts, n, k = b.image, b.point, b.xy, b.cams, b.pts, b.n, b.k
    free_points, point_obs, frame_obs = b.free_points, b.point_obs, b.frame_obs
    if b.conditions:
        return _bundle_with_conditions(b, io, order, sigma_image, gnss is not None, ins is not None, max_iter,
                                       (tol_centre, tol_angle, tol_point), progress)

    use_cov = (6 * n <= 3000) if covariance == "auto" else bool(covariance)
    # the correction equations at the start values: points behind an image there (bad start values)
    # raise PointBehindCameraError as such; the iteration's first step reuses them
    start = [bundle_correction_equations(image, point, xy, cams, pts, io, order)]

    def linearize(frames, points):
        if start:
            eq = start.pop()
            if np.array_equal(frames, cams) and np.array_equal(points, pts):
                return eq
        return bundle_correction_equations(image, point, xy, frames, points, io, order)

    try:
        adj = block_gauss_newton(linearize, cams, pts, frame_observations=frame_obs, point_observations=point_obs,
                                 free_points=free_points, tol_frames=[tol_centre] * 3 + [tol_angle] * 3,
                                 tol_points=tol_point, max_iter=max_iter, covariance=use_cov, dense_limit=dense_limit,
                                 progress=progress)
    except PointBehindCameraError as exc:
        raise ConvergenceError(f"the iteration diverged: {exc}") from exc
    zeros3 = np.zeros((n, 3))
    fr = adj.frame_residuals if frame_obs is not None else np.zeros((n, 6))
    return BundleResult(cameras=adj.frames, points=adj.points, mu=adj.mu, dof=adj.dof,
                        cameras_std=adj.frames_std, points_std=adj.points_std, residuals=adj.residuals,
                        control_residuals=adj.point_residuals if point_obs is not None else np.zeros((k, 3)),
                        gnss_residuals=fr[:, :3] if gnss is not None else zeros3,
                        ins_residuals=fr[:, 3:] if ins is not None else zeros3,
                        iterations=adj.iterations, history=adj.history, order=order,
                        timings=adj.timings)


def _bundle_with_conditions(b, io, order, sigma_image, with_gnss, with_ins, max_iter, tols, progress):
    """:func:`bundle_adjustment` with the conditions of §11.6: the dense path (:func:`_dense_block_adjustment`)."""
    bundle_correction_equations(b.image, b.point, b.xy, b.cams, b.pts, io, order)    # bad start values: as such
    tol_centre, tol_angle, tol_point = tols

    def linearize(frames, points, glob):
        return bundle_correction_equations(b.image, b.point, b.xy, frames, points, io, order)

    try:
        adj = _dense_block_adjustment(b, linearize, None, None, b.conditions, sigma_image,
                                      ([tol_centre] * 3 + [tol_angle] * 3, tol_point, 0.0), max_iter, progress)
    except PointBehindCameraError as exc:
        raise ConvergenceError(f"the iteration diverged: {exc}") from exc
    zeros3 = np.zeros((b.n, 3))
    return BundleResult(cameras=adj.frames, points=adj.points, mu=adj.mu, dof=adj.dof, cameras_std=adj.frames_std,
                        points_std=adj.points_std, residuals=adj.residuals,
                        control_residuals=adj.point_residuals if b.point_obs is not None else np.zeros((b.k, 3)),
                        gnss_residuals=adj.frame_residuals[:, :3] if with_gnss else zeros3,
                        ins_residuals=adj.frame_residuals[:, 3:] if with_ins else zeros3,
                        iterations=adj.iterations, history=adj.history, order=order,
                        condition_residuals=adj.condition_residuals)


@dataclass(frozen=True)
class CheckPointStatistics:
    """Errors of adjusted points against independent (check) coordinates.

    Attributes
    ----------
    n : int
        Number of check points.
    mean, rms, max_abs : ndarray (3,)
        Mean, r.m.s. and largest absolute error in X, Y, Z (m).
    predicted : ndarray (3,) or None
        r.m.s. of the a-posteriori m_j (3.5.11) at the same points.

    References
    ----------
    Chibunichev (2022), §3.5, eq. (3.5.11); §3.7 (accuracy checks on independent points).

    Examples
    --------
    >>> import numpy as np
    >>> s = CheckPointStatistics(2, np.zeros(3), np.full(3, 0.1), np.full(3, 0.15), np.full(3, 0.1))
    >>> s.ratio
    array([1., 1., 1.])
    """

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

    Parameters
    ----------
    result : BundleResult
        An adjusted block.
    true_points : array_like
        The (len(indices), 3) check coordinates or the full (k, 3) array.
    indices : int array
        The check points.

    Returns
    -------
    CheckPointStatistics

    Raises
    ------
    InputError
        Shapes that do not match, no check points, indices outside the block, NaN.

    References
    ----------
    Chibunichev (2022), §3.5, eq. (3.5.11); §3.7.

    Examples
    --------
    >>> import numpy as np
    >>> from photolib import synthetic
    >>> blk = synthetic.aerial_block(2, 4, points_per_image=15, sigma=0.0, seed=1)
    >>> cams0, pts0 = blk.start_values(seed=2)
    >>> control = {int(i): blk.points[i] for i in blk.control}
    >>> res = bundle_adjustment(blk.observations, cams0, pts0, blk.io, control=control, order=blk.order)
    >>> stats = check_point_statistics(res, blk.points, blk.check)
    >>> stats.n == len(blk.check), bool(np.all(stats.rms < 1e-6))
    (True, True)
    """
    if not hasattr(result, "points") or not hasattr(result, "points_std"):
        raise InputError("result must be a BundleResult")
    try:
        idx = np.asarray(indices).reshape(-1)
        truth = np.asarray(true_points, dtype=float)
    except (TypeError, ValueError) as exc:
        raise InputError(f"check points: indices and coordinates must be numbers: {exc}") from None
    if idx.size == 0 or not np.issubdtype(idx.dtype, np.integer) or idx.min() < 0 or idx.max() >= len(result.points):
        raise InputError(f"check points: give integer indices of adjusted points (0…{len(result.points) - 1})")
    idx = idx.astype(np.intp)
    if truth.shape == result.points.shape:
        truth = truth[idx]
    if truth.shape != (idx.size, 3):
        raise InputError("check points: give indices and their (c, 3) true coordinates")
    if not np.all(np.isfinite(truth)):
        raise InputError("check points: the true coordinates contain NaN or inf")
    err = result.points[idx] - truth
    pred = None if result.points_std is None else np.sqrt(np.mean(result.points_std[idx] ** 2, axis=0))
    return CheckPointStatistics(n=idx.size, mean=err.mean(axis=0), rms=np.sqrt(np.mean(err ** 2, axis=0)),
                                max_abs=np.abs(err).max(axis=0), predicted=pred)


# =================================================================================================
# §11.6 geometric conditions of terrestrial surveys added to the bundle
# =================================================================================================
# What each condition of photolib.terrestrial.condition_equations ties, in the order of its point
# arrays: "point" = an object point (index into the points), "image" = the projection centre of an
# image (index into the images); whether it has a measured value; how many equations it gives.
_CONDITION_ITEMS = {"distance": ("point", "point"), "base": ("image", "image"),
                    "centre_distance": ("point", "image"), "vertical": ("point", "point"),
                    "horizontal": ("point", "point"), "coplanar": ("point", "point", "point", "point")}
_CONDITION_MEASURED = {"distance", "base", "centre_distance"}
# The similarity subgroup under which each condition F = 0 stays satisfied — the datum parameters
# it cannot fix (columns t_X, t_Y, t_Z, r_X, r_Y, r_Z, s of the datum rows): lengths are invariant
# under shifts and rotations; a vertical line or a horizontal pair under shifts, the rotation about
# the vertical and the scale; four coplanar points under every similarity.
_CONDITION_FIXES = {"distance": (6,), "base": (6,), "centre_distance": (6,), "vertical": (3, 4),
                    "horizontal": (3, 4), "coplanar": ()}


@dataclass(frozen=True)
class _Condition:
    """One validated condition of §11.6 (from :func:`_parse_conditions`)."""

    kind: str
    items: tuple          # ("point" | "image", index) per point array of condition_equations
    measured: float | None
    sigma: float
    rows: int             # equations it gives (2 for a vertical line)


def _parse_conditions(conditions, n, k):
    """Validate ``conditions`` of :func:`bundle_adjustment`: a list of (kind, indices, measured, σ).

    Returns a tuple of :class:`_Condition` (empty for None). Raises :class:`InputError` naming the
    condition and the problem.
    """
    if conditions is None:
        return ()
    if isinstance(conditions, (str, bytes)) or not isinstance(conditions, (list, tuple)):
        raise InputError("conditions: give a list of (kind, indices, measured, sigma) tuples")
    out = []
    for c, spec in enumerate(conditions):
        where = f"conditions[{c}]"
        if isinstance(spec, (str, bytes)) or not isinstance(spec, (list, tuple)) or len(spec) != 4:
            raise InputError(f"{where}: expected (kind, indices, measured, sigma), got {spec!r}")
        kind, indices, measured, sigma = spec
        if not isinstance(kind, str) or kind not in _CONDITION_ITEMS:
            raise InputError(f"{where}: unknown condition {kind!r}; use one of {tuple(_CONDITION_ITEMS)}")
        items = _CONDITION_ITEMS[kind]
        try:
            idx = np.asarray(indices).reshape(-1)
        except (TypeError, ValueError):
            idx = np.zeros(0)
        if idx.size != len(items) or not (np.issubdtype(idx.dtype, np.integer) or
                                          (np.issubdtype(idx.dtype, np.floating) and np.all(np.isfinite(idx))
                                           and np.all(idx == np.round(idx)))):
            raise InputError(f"{where}: the {kind!r} condition needs {len(items)} integer indices "
                             f"({', '.join(items)}), got {indices!r}")
        idx = idx.astype(np.int64)
        for what, i in zip(items, idx):
            size = n if what == "image" else k
            if not 0 <= i < size:
                raise InputError(f"{where}: {what} index {int(i)} is outside 0…{size - 1}")
        pairs = list(zip(items, idx.tolist()))
        if len(set(pairs)) < len(pairs):
            raise InputError(f"{where}: the {kind!r} condition names the same {pairs[0][0]} twice")
        if kind in _CONDITION_MEASURED:
            try:
                value = float(measured)
            except (TypeError, ValueError):
                value = float("nan")
            if not (np.isfinite(value) and value > 0):
                raise InputError(f"{where}: the {kind!r} condition needs a finite positive measured length, "
                                 f"got {measured!r}")
        elif measured is not None:
            raise InputError(f"{where}: the {kind!r} condition takes no measured value (give None)")
        else:
            value = None
        try:
            s = float(sigma)
        except (TypeError, ValueError):
            s = float("nan")
        if not (np.isfinite(s) and s > 0):
            raise InputError(f"{where}: sigma must be a finite positive number (units of the condition), "
                             f"got {sigma!r}")
        out.append(_Condition(kind, tuple((w, int(i)) for w, i in pairs), value, s, 2 if kind == "vertical" else 1))
    return tuple(out)


def _condition_terms(conditions, cams, pts):
    """F and ∂F/∂(coordinates) of every condition at the given centres and points, grouped by kind.

    The values come from :func:`photolib.terrestrial.condition_equations` (its sympy Jacobians).
    Returns a list of (condition positions, F (c, q), J (c, q, 3·items)) per kind.
    """
    from .terrestrial import condition_equations
    groups = {}
    for c, cond in enumerate(conditions):
        groups.setdefault(cond.kind, []).append(c)
    out = []
    for kind, members in groups.items():
        coords = [np.array([(cams[i, :3] if w == "image" else pts[i]) for w, i in
                            (conditions[c].items[s] for c in members)]) for s in range(len(_CONDITION_ITEMS[kind]))]
        measured = [conditions[c].measured for c in members] if kind in _CONDITION_MEASURED else None
        F, J = condition_equations(kind, coords, measured)
        out.append((members, F, J))
    return out


def _condition_datum_rows(conditions, cams, pts, centre, scale):
    """Rows (r, 7) of the datum parameters the conditions fix, for :func:`_datum_rank`.

    Each condition row is ∂F/∂(coordinates)·dX/d(t, r, s) at the start values, normalised by
    |∂F/∂X|. The columns of the similarities that leave the condition satisfied
    (``_CONDITION_FIXES``) are zeroed: at start values that do not meet the condition they would
    show a spurious, tiny datum information (a vertical line that is not yet vertical "fixes"
    the scale).
    """
    rows = []
    for members, _, J in _condition_terms(conditions, cams, pts):
        for c, Jc in zip(members, J):
            cond = conditions[c]
            X = np.array([(cams[i, :3] if w == "image" else pts[i]) for w, i in cond.items])
            D = _similarity_rows((X - centre) / scale).reshape(-1, 7)             # (3·items, 7)
            R = Jc @ D
            R /= np.maximum(np.linalg.norm(Jc, axis=1, keepdims=True), 1e-300)
            mask = np.zeros(7, bool)
            mask[list(_CONDITION_FIXES[cond.kind])] = True
            rows.append(np.where(mask, R, 0.0))
    return np.vstack(rows) if rows else np.zeros((0, 7))


@dataclass
class _DenseResult:
    """The parts of an adjustment solved by :func:`_dense_block_adjustment`, shaped as the block path's."""

    frames: np.ndarray
    points: np.ndarray
    globals: np.ndarray
    mu: float
    dof: int
    residuals: np.ndarray            # (m, 2) image observations
    frame_residuals: np.ndarray      # (n, 6)
    point_residuals: np.ndarray      # (k, 3)
    condition_residuals: np.ndarray  # one per condition equation
    frames_std: np.ndarray
    points_std: np.ndarray
    globals_std: np.ndarray
    Q1: np.ndarray
    Q2: np.ndarray
    Q3: np.ndarray
    Q13: np.ndarray
    Q23: np.ndarray
    iterations: int
    history: list


def _dense_block_adjustment(b: _Block, linearize, globals0, global_obs, conditions, sigma_image, tols, max_iter,
                            progress=None, global_names=()) -> _DenseResult:
    """A bundle block with the geometric conditions of §11.6, solved by the dense path of the one engine.

    A condition couples the coordinates of several points (or centres), which the block solver's
    elimination of each point by its own 3×3 block (3.5.16) cannot hold. So the correction
    equations of the block (``linearize(frames, points, globals)``, the same ones the block
    solver uses) are written out as one dense system (:func:`photolib.lsq.block_equations_dense`,
    columns images | block-wide unknowns | free points), the direct observations of control, GNSS,
    INS and prior calibration values appended as rows δ + l = v, and every condition as
    ∂F/∂p·δ + F = v with weight (σ_image/σ)² — (11.6.7) for a distance — and the whole is iterated
    by :func:`photolib.lsq.gauss_newton`. The dense normal matrix has 6n + g + 3k rows: meant for
    terrestrial blocks of tens of images and hundreds of points.
    """
    n, k = b.n, b.k
    g = 0 if globals0 is None else len(globals0)
    free = b.free_points
    col_of_point = np.cumsum(free) - 1
    nf = 6 * n + g                                      # first point column
    n_unknowns = nf + 3 * int(free.sum())

    def point_columns(i):
        return nf + 3 * col_of_point[i] + np.arange(3)

    # the direct observations as rows: (column, value, weight)
    prior_cols, prior_vals, prior_wts = [], [], []
    if b.frame_obs is not None:
        i, c = np.nonzero(b.frame_obs[1] > 0)
        prior_cols.append(6 * i + c); prior_vals.append(b.frame_obs[0][i, c]); prior_wts.append(b.frame_obs[1][i, c])
    if g and global_obs is not None:
        (j,) = np.nonzero(global_obs[1] > 0)
        prior_cols.append(6 * n + j); prior_vals.append(global_obs[0][j]); prior_wts.append(global_obs[1][j])
    if b.point_obs is not None:
        i, c = np.nonzero((b.point_obs[1] > 0) & free[:, None])
        prior_cols.append(nf + 3 * col_of_point[i] + c); prior_vals.append(b.point_obs[0][i, c])
        prior_wts.append(b.point_obs[1][i, c])
    pcol = np.concatenate(prior_cols).astype(np.intp) if prior_cols else np.zeros(0, np.intp)
    pval = np.concatenate(prior_vals) if prior_vals else np.zeros(0)
    pwt = np.concatenate(prior_wts) if prior_wts else np.zeros(0)
    # the condition rows, in the order of the conditions
    first_row = np.concatenate([[0], np.cumsum([c.rows for c in conditions])]).astype(np.intp)
    n_cond = int(first_row[-1])
    cond_wt = np.concatenate([np.full(c.rows, (sigma_image / c.sigma) ** 2) for c in conditions]) \
        if conditions else np.zeros(0)
    m_img = 2 * b.image.size
    weights = np.concatenate([np.ones(m_img), pwt, cond_wt])

    def unpack(x):
        frames = x[:6 * n].reshape(n, 6)
        glob = x[6 * n:nf]
        points = b.pts.copy()
        points[free] = x[nf:].reshape(-1, 3)
        return frames, points, glob

    def dense(x):
        frames, points, glob = unpack(x)
        eq = linearize(frames, points, glob)
        if g:
            B0, L0, _ = global_block_equations_dense(eq, n, k, free)
        else:
            B0, L0, _ = block_equations_dense(eq, n, k, free)
        B = np.zeros((m_img + pcol.size + n_cond, n_unknowns))
        L = np.zeros(B.shape[0])
        B[:m_img], L[:m_img] = B0, L0
        r = m_img + np.arange(pcol.size)
        B[r, pcol] = 1.0
        L[r] = x[pcol] - pval
        base = m_img + pcol.size
        for members, F, J in _condition_terms(conditions, frames, points):
            for c, Fc, Jc in zip(members, F, J):
                rows = base + first_row[c] + np.arange(conditions[c].rows)
                L[rows] = Fc
                for s, (what, i) in enumerate(conditions[c].items):
                    if what == "image":
                        B[np.ix_(rows, 6 * i + np.arange(3))] = Jc[:, 3 * s:3 * s + 3]
                    elif free[i]:
                        B[np.ix_(rows, point_columns(i))] = Jc[:, 3 * s:3 * s + 3]
        return B, L

    x0 = np.concatenate([b.cams.ravel(), np.zeros(0) if not g else np.asarray(globals0, float),
                         b.pts[free].ravel()])
    tol = np.concatenate([np.tile(np.broadcast_to(tols[0], (6,)), n), np.broadcast_to(tols[2], (g,)),
                          np.full(3 * int(free.sum()), float(tols[1]))])
    names = [f"{nm}[{i}]" for i in range(n) for nm in EO_NAMES] + list(global_names) + \
        [f"{c}[{i}]" for i in np.flatnonzero(free) for c in "XYZ"]
    adj = gauss_newton(dense, x0, weights, tol=tol, max_iter=max_iter, names=names, progress=progress)
    frames, points, glob = unpack(adj.x)
    V = adj.residuals
    frame_res, point_res = np.zeros((n, 6)), np.zeros((k, 3))
    rv = V[m_img:m_img + pcol.size]
    flat = np.zeros(n_unknowns)
    flat[pcol] = rv
    frame_res[:] = flat[:6 * n].reshape(n, 6)
    point_res[free] = flat[nf:].reshape(-1, 3)
    # cofactor blocks in the shapes of the block solver (for the m_j and the correlation report)
    Q = adj.Q
    Q1 = np.array([Q[6 * i:6 * i + 6, 6 * i:6 * i + 6] for i in range(n)])
    Q2, Q23 = np.zeros((k, 3, 3)), np.zeros((k, 3, g))
    for i in np.flatnonzero(free):
        pc = point_columns(i)
        Q2[i] = Q[np.ix_(pc, pc)]
        Q23[i] = Q[pc, 6 * n:nf]
    Q3 = Q[6 * n:nf, 6 * n:nf]
    Q13 = Q[:6 * n, 6 * n:nf].reshape(n, 6, g)
    mu = adj.mu
    return _DenseResult(frames=frames, points=points, globals=glob, mu=mu, dof=adj.dof,
                        residuals=V[:m_img].reshape(-1, 2), frame_residuals=frame_res, point_residuals=point_res,
                        condition_residuals=V[m_img + pcol.size:].copy(),
                        frames_std=mu * np.sqrt(np.einsum("kii->ki", Q1)),
                        points_std=mu * np.sqrt(np.einsum("kii->ki", Q2)), globals_std=mu * np.sqrt(np.diag(Q3)),
                        Q1=Q1, Q2=Q2, Q3=Q3, Q13=Q13, Q23=Q23, iterations=adj.iterations, history=adj.history)


# =================================================================================================
# §3.6 Self-calibration, §3.8 multi-camera rigs, §3.9 UAV specifics (rolling shutter, corridors)
# =================================================================================================
EO_NAMES = ("X_S", "Y_S", "Z_S", "omega", "alpha", "kappa")
IO_NAMES = ("f", "x0", "y0", "k1", "k2", "k3", "p1", "p2")
DISTORTION_NAMES = IO_NAMES[3:]
MOUNT_NAMES = ("B_X", "B_Y", "B_Z", "omega'", "alpha'", "kappa'")
RATE_NAMES = ("k1 (dX_S/dx)", "k2 (dY_S/dx)", "k3 (dZ_S/dx)", "k4 (domega/dx)", "k5 (dalpha/dx)", "k6 (dkappa/dx)")


# --- counts: (3.5.20), §3.6, (3.8.1)/(3.8.2), §3.9 ------------------------------------------------
def _count_arg(value, what):
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < 0:
        raise InputError(f"{what} must be a non-negative integer, got {value!r}")
    return int(value)


def count_bundle_unknowns(n_images: int, n_points: int) -> int:
    """N = 6n + 3k of (3.5.20): six EO per image, three coordinates per determined point.

    Parameters
    ----------
    n_images, n_points : int
        Images and determined points.

    Returns
    -------
    int
        N = 6n + 3k.

    Raises
    ------
    InputError
        A negative or non-integer count, an unknown option.

    References
    ----------
    Chibunichev (2022), §3.5, eq. (3.5.20).

    Examples
    --------
    >>> count_bundle_unknowns(4, 10)
    54
    """
    return 6 * _count_arg(n_images, "n_images") + 3 * _count_arg(n_points, "n_points")


def count_self_calibration_unknowns(n_images: int, n_points: int, calibrate=IO_NAMES) -> int:
    """(3.5.20) plus the block-wide unknowns of §3.6: + 5 for k₁, k₂, k₃, p₁, p₂ (the text), + 8 with f, x₀, y₀ ((3.6.3)).

    Parameters
    ----------
    n_images, n_points : int
        Images and determined points.
    calibrate : sequence of str
        The block-wide unknowns (names from IO_NAMES).

    Returns
    -------
    int
        N of (3.5.20) plus one per calibrated unknown.

    Raises
    ------
    InputError
        A negative or non-integer count, an unknown option.

    References
    ----------
    Chibunichev (2022), §3.5, eq. (3.5.20); §3.6, eq. (3.6.3).

    Examples
    --------
    >>> count_self_calibration_unknowns(4, 10), count_self_calibration_unknowns(4, 10, DISTORTION_NAMES)
    (62, 59)
    """
    names = _check_calibrate(calibrate)
    return count_bundle_unknowns(n_images, n_points) + len(names)


def count_rig_unknowns(n_exposures: int, n_cameras: int, n_points: int = 0, parameterisation: str = "rig") -> int:
    """Unknowns of a multi-camera block: N₁ = 6·n_s·n + 3k (3.8.1, ``"free"``) or N₂ = 6(n + n_s − 1) + 3k (3.8.2, ``"rig"``).

    n = exposures (images of one camera), n_s = cameras in the rig, k = determined points.

    Parameters
    ----------
    n_exposures, n_cameras : int
        Exposures and cameras of the rig.
    n_points : int
        Determined points.
    parameterisation : {"rig", "free"}
        (3.8.2) or (3.8.1).

    Returns
    -------
    int
        N₁ or N₂.

    Raises
    ------
    InputError
        A negative or non-integer count, an unknown option.

    References
    ----------
    Chibunichev (2022), §3.8, eqs. (3.8.1), (3.8.2).

    Examples
    --------
    >>> count_rig_unknowns(2, 2, 4, "rig"), count_rig_unknowns(2, 2, 4, "free")
    (30, 36)
    """
    n, ns, k = (_count_arg(v, w) for v, w in ((n_exposures, "n_exposures"), (n_cameras, "n_cameras"),
                                                (n_points, "n_points")))
    if ns < 1:
        raise InputError("a rig has at least one camera")
    if parameterisation == "free":
        return 6 * ns * n + 3 * k
    if parameterisation == "rig":
        return 6 * (n + ns - 1) + 3 * k
    raise InputError(f"parameterisation must be 'free' (3.8.1) or 'rig' (3.8.2), got {parameterisation!r}")


def count_rolling_shutter_unknowns(n_images: int, n_points: int = 0, model: str = "full") -> int:
    """§3.9: 12 unknowns per rolling-shutter image (6 EO + 6 rates, (3.9.2)), 9 in the simplified model, + 3k.

    Parameters
    ----------
    n_images, n_points : int
        Images and determined points.
    model : {"full", "linear"}
        12 or 9 unknowns per image.

    Returns
    -------
    int
        N.

    Raises
    ------
    InputError
        A negative or non-integer count, an unknown option.

    References
    ----------
    Chibunichev (2022), §3.9, eqs. (3.9.1), (3.9.2).

    Examples
    --------
    >>> count_rolling_shutter_unknowns(3, 10), count_rolling_shutter_unknowns(3, 10, "linear")
    (66, 57)
    """
    per = {"full": 12, "linear": 9}.get(model)
    if per is None:
        raise InputError(f"model must be 'full' (12 per image) or 'linear' (9), got {model!r}")
    return per * _count_arg(n_images, "n_images") + 3 * _count_arg(n_points, "n_points")


# --- §3.6 self-calibration ---------------------------------------------------------------------
def _check_calibrate(calibrate):
    names = tuple(calibrate)
    unknown = [c for c in names if c not in IO_NAMES]
    if unknown or len(set(names)) != len(names) or not names:
        raise InputError(f"calibrate: choose distinct names among {IO_NAMES}, got {names}")
    return tuple(c for c in IO_NAMES if c in names)


def _io_vector(io: InteriorOrientation) -> np.ndarray:
    return np.array([io.f, io.x0, io.y0, io.k1, io.k2, io.k3, io.p1, io.p2], dtype=float)


def _zstar_check(cameras, points, image, point, order):
    A = rotation_matrix(cameras[:, 3], cameras[:, 4], cameras[:, 5], order)
    _raise_behind(np.einsum("ki,ki->k", A[image][:, :, 2], points[point] - cameras[image, :3]), point)


def _raise_behind(zstar, point):
    """PointBehindCameraError for the observations whose point has z* ≥ 0 (behind the image)."""
    behind = zstar >= 0
    if behind.any():
        bad = np.flatnonzero(behind)
        raise PointBehindCameraError(
            f"observations {bad[:10].tolist()}: the point is not in front of the image (z* ≥ 0)",
            points=np.unique(np.asarray(point)[bad]).tolist())


def self_calibration_correction_equations(image, point, xy, cameras, points, io_values, calibrate=IO_NAMES,
                                          order: str = "kaw") -> GlobalBlockCorrectionEquations:
    """Correction equations (3.6.3) of all observations: a₁…a₆ (B1), a₇…a₉ (B2), a₁₀…a₁₇ (B3).

    ``io_values`` are the current f, x₀, y₀, k₁, k₂, k₃, p₁, p₂; B3 holds the columns of the
    names in ``calibrate`` (in the order of :data:`IO_NAMES`). Free terms
    l = x₀ − f x*/z* − x − Δ_x (3.6.1). Derivatives from :func:`photolib.derivations.self_calibration_model`.

    Parameters
    ----------
    image, point, xy, cameras, points
        As in :func:`bundle_correction_equations`.
    io_values : array_like (8,)
        Current f, x₀, y₀, k₁, k₂, k₃, p₁, p₂.
    calibrate : sequence of str
        The block-wide unknowns.
    order : {"kaw", "wak"}

    Returns
    -------
    GlobalBlockCorrectionEquations
        B1 (m, 2, 6), B2 (m, 2, 3), B3 (m, 2, g), L (m, 2).

    Raises
    ------
    InputError
        Unknown names in ``calibrate``.
    PointBehindCameraError
        A point behind its image.

    References
    ----------
    Chibunichev (2022), §3.6, eqs. (3.6.1)–(3.6.3).

    Examples
    --------
    >>> import numpy as np
    >>> from photolib import synthetic
    >>> blk = synthetic.aerial_block(2, 4, points_per_image=15, sigma=0.0, seed=1)
    >>> cams0, pts0 = blk.start_values(seed=2)
    >>> control = {int(i): blk.points[i] for i in blk.control}
    >>> o = blk.observations
    >>> io = [blk.io.f, blk.io.x0, blk.io.y0, 0, 0, 0, 0, 0]
    >>> eq = self_calibration_correction_equations(o.image, o.point, o.xy, blk.cameras, blk.points, io)
    >>> eq.B3.shape[1:], float(np.abs(eq.L).max()) < 1e-9
    ((2, 8), True)
    """
    names = _check_calibrate(calibrate)
    _zstar_check(cameras, points, image, point, order)
    fn = getattr(_bundle_generated, f"selfcal_{order}")
    c, X = cameras[image], points[point]
    F, J = fn(c[:, 0], c[:, 1], c[:, 2], c[:, 3], c[:, 4], c[:, 5], X[:, 0], X[:, 1], X[:, 2],
              *[float(v) for v in io_values], xy[:, 0], xy[:, 1])
    J = J.reshape(2, 17, -1).transpose(2, 0, 1)
    cols = [9 + IO_NAMES.index(nm) for nm in names]
    return GlobalBlockCorrectionEquations(frame=image, point=point, B1=J[:, :, :6], B2=J[:, :, 6:9], L=F.T,
                                          P=1.0, B3=J[:, :, cols])


@dataclass
class CorrelationReport:
    """Correlations of the block-wide unknowns (§3.6): among themselves and with the EO and points.

    ``among[i, j]`` is r between unknowns i and j of ``names``; ``with_eo[i, c]`` the largest |r|
    over all images between unknown i and EO component c (X_S … κ), signed; ``with_points[i, c]``
    the same over all free points and X, Y, Z.

    Attributes
    ----------
    names : tuple of str
        The block-wide unknowns.
    among : ndarray (g, g)
        r between them.
    with_eo, with_points : ndarray
        Largest signed |r| with each EO component / point coordinate.

    References
    ----------
    Chibunichev (2022), §3.6 (correlation of the calibration with the exterior orientation); §1.8, eq. (1.8.10).

    Examples
    --------
    >>> import numpy as np
    >>> from photolib import synthetic
    >>> from photolib.camera import InteriorOrientation
    >>> true_io = InteriorOrientation(f=100.0, x0=0.05, y0=-0.03)
    >>> blk = synthetic.aerial_block(3, 4, io=true_io, strip_heights=(800, 1000, 1200), relief=150.0,
    ...                              points_per_image=20, sigma=0.0, seed=3)
    >>> cams0, pts0 = blk.start_values(seed=1)
    >>> res = self_calibrating_bundle_adjustment(blk.observations, cams0, pts0, InteriorOrientation(f=99.0),
    ...     calibrate=("f", "x0", "y0"), control={int(i): blk.points[i] for i in blk.control}, order=blk.order)
    >>> rep = res.correlations
    >>> rep.names, bool(np.allclose(np.diag(rep.among), 1.0))
    (('f', 'x0', 'y0'), True)
    """

    names: tuple
    among: np.ndarray
    with_eo: np.ndarray
    with_points: np.ndarray
    limit: float

    def high(self) -> list:
        """(a, b, r) for every pair with |r| > ``limit`` — candidates to drop or re-model."""
        out = []
        g = len(self.names)
        for i in range(g):
            for j in range(i + 1, g):
                if abs(self.among[i, j]) > self.limit:
                    out.append((self.names[i], self.names[j], float(self.among[i, j])))
            for c, nm in enumerate(EO_NAMES):
                if abs(self.with_eo[i, c]) > self.limit:
                    out.append((self.names[i], f"{nm} (an image)", float(self.with_eo[i, c])))
            for c, nm in enumerate("XYZ"):
                if abs(self.with_points[i, c]) > self.limit:
                    out.append((self.names[i], f"{nm} (a point)", float(self.with_points[i, c])))
        return out

    def __str__(self) -> str:
        w = max(8, max(len(n) for n in self.names) + 1)
        lines = ["correlations among the block-wide unknowns:",
                 " " * w + "".join(f"{n:>8}" for n in self.names)]
        lines += [f"{a:<{w}}" + "".join(f"{v:8.2f}" for v in row) for a, row in zip(self.names, self.among)]
        lines += ["largest |r| with the exterior orientation (over all images) and with the points:",
                  " " * w + "".join(f"{n:>8}" for n in EO_NAMES + ("X", "Y", "Z"))]
        lines += [f"{a:<{w}}" + "".join(f"{v:8.2f}" for v in np.concatenate([e, p]))
                  for a, e, p in zip(self.names, self.with_eo, self.with_points)]
        high = self.high()
        lines.append(f"|r| > {self.limit}: " + ("none" if not high else
                                                 "; ".join(f"{a}–{b} {r:+.3f}" for a, b, r in high)))
        return "\n".join(lines)


def _correlation_report(adj, names, limit):
    q3 = np.diag(adj.Q3)
    s3 = np.sqrt(q3)
    among = adj.Q3 / np.outer(s3, s3)
    s1 = np.sqrt(np.einsum("kii->ki", adj.Q1))
    r13 = adj.Q13 / (s1[:, :, None] * s3[None, None, :])                 # (n, 6, g)
    s2 = np.sqrt(np.einsum("kii->ki", adj.Q2))
    with np.errstate(invalid="ignore", divide="ignore"):
        r23 = np.where(s2[:, :, None] > 0, adj.Q23 / (s2[:, :, None] * s3[None, None, :]), 0.0)

    def signed_max(r):
        flat = r.reshape(-1, r.shape[1], r.shape[2])
        idx = np.abs(flat).argmax(axis=0)
        return np.take_along_axis(flat, idx[None], axis=0)[0].T          # (g, components)

    return CorrelationReport(tuple(names), among, signed_max(r13), signed_max(r23), float(limit))


@dataclass
class SelfCalibrationResult(BundleResult):
    """:class:`BundleResult` of a self-calibrating adjustment plus the recovered camera (§3.6).

    Attributes
    ----------
    io : InteriorOrientation
        The adjusted interior orientation and distortion.
    calibrated : tuple of str
        Names of the estimated block-wide unknowns.
    io_std : dict
        m_j (3.5.11) of each.
    correlations : CorrelationReport
        Their correlations (§3.6).
    cameras, points, mu, ...
        As in :class:`BundleResult`.

    References
    ----------
    Chibunichev (2022), §3.6, eqs. (3.6.1)–(3.6.3).

    Examples
    --------
    >>> import numpy as np
    >>> from photolib import synthetic
    >>> from photolib.camera import InteriorOrientation
    >>> true_io = InteriorOrientation(f=100.0, x0=0.05, y0=-0.03)
    >>> blk = synthetic.aerial_block(3, 4, io=true_io, strip_heights=(800, 1000, 1200), relief=150.0,
    ...                              points_per_image=20, sigma=0.0, seed=3)
    >>> cams0, pts0 = blk.start_values(seed=1)
    >>> res = self_calibrating_bundle_adjustment(blk.observations, cams0, pts0, InteriorOrientation(f=99.0),
    ...     calibrate=("f", "x0", "y0"), control={int(i): blk.points[i] for i in blk.control}, order=blk.order)
    >>> round(float(res.io.f), 6), round(float(res.io.x0), 6), round(float(res.io.y0), 6)
    (100.0, 0.05, -0.03)
    """

    io: InteriorOrientation | None = None          # adjusted interior orientation and distortion
    calibrated: tuple = ()                        # names of the estimated block-wide unknowns
    io_std: dict = field(default_factory=dict)    # m_j (3.5.11) of each, mm / mm⁻ⁿ
    correlations: CorrelationReport | None = None
    ap_model: str | None = None                   # additional-parameter model (Hanzl §4.4), if any
    ap_values: dict = field(default_factory=dict)  # its adjusted parameters g_i
    ap_cofactors: np.ndarray | None = None        # Q_gg of the APs (σ_g = μ √q_ii)


@dataclass(frozen=True)
class _APSetup:
    model: str
    names: tuple
    index: tuple
    kwargs: dict
    tolerances: tuple

    def basis(self, xy):
        return apm.ap_basis(self.model, xy, **self.kwargs)[:, :, list(self.index)]


def _ap_setup(model, names, base, r0, io0):
    if model is None:
        if names is not None or base is not None or r0 is not None:
            raise InputError("ap_names, ap_base and ap_r0 need additional_parameters= (the AP model)")
        return None
    all_names = apm.parameter_names(model)
    names = all_names if names is None else tuple(names)
    bad = [nm for nm in names if nm not in all_names]
    if bad or len(set(names)) != len(names) or not names:
        raise InputError(f"ap_names: choose distinct names among {all_names}, got {names}")
    kwargs = {}
    if model in ("ebner12", "hanzl17"):
        if base is None:
            raise InputError(f"{model} needs ap_base, the image base b (e.g. 92 mm for 23 cm and 60 % overlap)")
        kwargs["b"] = base
    if model == "hanzl17":
        kwargs["r0"] = 0.0 if r0 is None else r0
    if model in ("brown", "brown18"):
        if not isinstance(io0, InteriorOrientation):
            raise InputError("io0 must be an InteriorOrientation (start values of the calibration)")
        kwargs["f"] = io0.f
    apm.ap_basis(model, np.zeros((1, 2)), **kwargs)          # validates b, r0, f
    return _APSetup(model, names, tuple(all_names.index(nm) for nm in names), kwargs, ())


def self_calibrating_bundle_adjustment(observations, cameras0, points0, io0: InteriorOrientation, *,
                                       calibrate=IO_NAMES, sigma_io=None, control=None, sigma_control=None,
                                       gnss=None, sigma_centre=0.05, ins=None, sigma_angles=np.radians(0.005),
                                       conditions=None, sigma_image: float = 0.005, order: str = "kaw",
                                       max_iter: int = 30, tol_centre: float = 1e-5, tol_angle: float = 1e-9,
                                       tol_point: float = 1e-5, correlation_limit: float = 0.9,
                                       additional_parameters=None, ap_names=None, ap_base=None, ap_r0=None,
                                       **legacy) -> SelfCalibrationResult:
    """Bundle adjustment with self-calibration, §3.6: (3.6.1)–(3.6.3).

    The interior orientation f, x₀, y₀ and the distortion coefficients k₁, k₂, k₃, p₁, p₂ of
    (3.6.2) (= (1.2.2): the correction Δ is *added to the measured coordinates*, computed from
    them reduced to the principal point) are unknowns common to every image. They enter every
    correction equation (3.6.3) and join the reduced system after the points are eliminated
    (:func:`photolib.lsq.solve_block_normal_equations`).

    Parameters
    ----------
    observations, cameras0, points0, control, control_sigma, gnss, gnss_sigma, ins, ins_sigma, sigma_image, order
        As in :func:`bundle_adjustment` (the measured coordinates are *not* corrected beforehand).
    io0 : InteriorOrientation
        Start values of all eight; the ones not in ``calibrate`` stay fixed at them.
    calibrate : sequence of names from :data:`IO_NAMES`
        The block-wide unknowns: all eight by default (as (3.6.3) is written); ``DISTORTION_NAMES``
        for the five polynomial coefficients the text counts.
    io_sigma : dict {name: σ}, optional
        Prior calibration values of ``io0`` as weighted observations with these accuracies.
    conditions : list of (kind, indices, measured, sigma), optional
        Geometric conditions of §11.6, as in :func:`bundle_adjustment` (the block is then solved
        by the dense path of the engine, the block-wide unknowns as columns after the images).
    correlation_limit : float
        |r| above which :attr:`CorrelationReport.high` flags a pair.
    additional_parameters : str, optional
        A model of :mod:`photolib.additional_parameters` (e.g. ``"hanzl17"``: Ebner's twelve
        orthogonal parameters with Hanzl's radial g₁₃…g₁₅ and tangential g₁₆, g₁₇, §4.4 of Hanzl's text;
        ``"ebner12"``, ``"brown18"``, ``"murai"``, ...). Its parameters become further block-wide unknowns
        (start 0) after those of ``calibrate``; the correction dx, dy is *added to the measured
        coordinates*, evaluated at them (relative to the image centre), so the equations are linear in
        the parameters and their columns are −:func:`~photolib.additional_parameters.ap_basis`.
        ``calibrate`` may then be empty (``()``): the APs alone.
    ap_names : sequence of str, optional
        The subset of the model's parameters to estimate (default all), e.g. g1…g12 for Ebner's set.
    ap_base, ap_r0 : float, optional
        The model's b (Ebner's image base, e.g. 92 mm) and r₀ (hanzl17); the c of ``"brown"`` and
        ``"brown18"`` is ``io0.f``.

    Raises
    ------
    DegenerateGeometryError
        Besides the cases of :func:`bundle_adjustment`: the block cannot separate a block-wide
        unknown from the others — e.g. f from the heights Z_S of flat terrain seen in nadir images
        (a change of f is then exactly a change of every flying height) — with the unknowns named.

    Returns
    -------
    SelfCalibrationResult

    References
    ----------
    Chibunichev (2022), §3.6, eqs. (3.6.1)–(3.6.3); §3.5, eqs. (3.5.9)–(3.5.16); conditions: §11.6,
    eqs. (11.6.1)–(11.6.7).

    Examples
    --------
    >>> import numpy as np
    >>> from photolib import synthetic
    >>> from photolib.camera import InteriorOrientation
    >>> true_io = InteriorOrientation(f=100.0, x0=0.05, y0=-0.03)
    >>> blk = synthetic.aerial_block(3, 4, io=true_io, strip_heights=(800, 1000, 1200), relief=150.0,
    ...                              points_per_image=20, sigma=0.0, seed=3)
    >>> cams0, pts0 = blk.start_values(seed=1)
    >>> res = self_calibrating_bundle_adjustment(blk.observations, cams0, pts0, InteriorOrientation(f=99.0),
    ...     calibrate=("f", "x0", "y0"), control={int(i): blk.points[i] for i in blk.control}, order=blk.order)
    >>> round(float(res.io.f), 6), sorted(res.io_std)
    (100.0, ['f', 'x0', 'y0'])
    """
    sigma_io, sigma_control, sigma_centre, sigma_angles = _renamed(
        legacy, "self_calibrating_bundle_adjustment", sigma_io=sigma_io, sigma_control=sigma_control,
        sigma_centre=sigma_centre, sigma_angles=sigma_angles)
    ap = _ap_setup(additional_parameters, ap_names, ap_base, ap_r0, io0)
    names = _check_calibrate(calibrate) if (ap is None or tuple(calibrate)) else ()
    if not isinstance(io0, InteriorOrientation):
        raise InputError("io0 must be an InteriorOrientation (start values of the calibration)")
    if not 0 < correlation_limit < 1:
        raise InputError("correlation_limit must lie in (0, 1)")
    b = _prepare_block(observations, cameras0, points0, io0, control, sigma_control, gnss, sigma_centre, ins,
                       sigma_angles, sigma_image, order, correct_distortion_first=False, conditions=conditions)
    full = _io_vector(io0)
    cols = [IO_NAMES.index(nm) for nm in names]
    g0 = full[cols]
    n_io = len(names)
    if ap is not None:
        ap_cols_all = -ap.basis(b.xy)                                  # (m, 2, p): ∂L/∂g, constant
        # stop when a step moves no image point by more than 1e-7 (mm)
        ap_tol = [1e-7 / max(float(np.abs(ap_cols_all[:, :, j]).max()), 1e-300) for j in range(len(ap.names))]
        names = names + ap.names
        g0 = np.concatenate([g0, np.zeros(len(ap.names))])
    gobs = None
    if sigma_io:
        vals, wts = np.full(len(names), np.nan), np.zeros(len(names))
        for nm, sg in dict(sigma_io).items():
            if nm not in names or not sg > 0:
                raise InputError(f"sigma_io: {nm!r} must be a calibrated unknown with a positive σ")
            vals[names.index(nm)] = g0[names.index(nm)]
            wts[names.index(nm)] = (sigma_image / sg) ** 2
        gobs = (vals, wts)

    _zstar_check(b.cams, b.pts, b.image, b.point, order)  # bad start values: PointBehindCameraError, as such

    def linearize(frames, points, glob):
        v = full.copy()
        v[cols] = glob[:n_io]
        eq = self_calibration_correction_equations(b.image, b.point, b.xy, frames, points, v,
                                                   names[:n_io] or ("f",), order)
        if ap is None:
            return eq
        B3 = np.concatenate([eq.B3[:, :, :n_io], ap_cols_all], axis=2)
        L = eq.L + np.einsum("mcp,p->mc", ap_cols_all, glob[n_io:])
        return GlobalBlockCorrectionEquations(frame=eq.frame, point=eq.point, B1=eq.B1, B2=eq.B2, L=L, P=1.0, B3=B3)

    tol_g = np.array([1e-7 if nm in ("f", "x0", "y0") else 1e-6 * (0.1 ** (2 * (IO_NAMES.index(nm) - 2)))
                      if nm.startswith("k") else 1e-10 for nm in names[:n_io]]
                     + ([] if ap is None else ap_tol))
    try:
        if b.conditions:
            adj = _dense_block_adjustment(b, linearize, g0, gobs, b.conditions, sigma_image,
                                          ([tol_centre] * 3 + [tol_angle] * 3, tol_point, tol_g), max_iter,
                                          global_names=names)
        else:
            adj = block_gauss_newton(linearize, b.cams, b.pts, g0, frame_observations=b.frame_obs,
                                     point_observations=b.point_obs, global_observations=gobs,
                                     free_points=b.free_points, tol_frames=[tol_centre] * 3 + [tol_angle] * 3,
                                     tol_points=tol_point, tol_globals=tol_g, max_iter=max_iter, covariance=True,
                                     global_names=names, frame_names=EO_NAMES)
    except PointBehindCameraError as exc:
        raise ConvergenceError(f"the iteration diverged: {exc}") from exc
    v = full.copy()
    v[cols] = adj.globals[:n_io]
    io = InteriorOrientation(*v)
    n, k = b.n, b.k
    fr = adj.frame_residuals if b.frame_obs is not None else np.zeros((n, 6))
    zeros3 = np.zeros((n, 3))
    return SelfCalibrationResult(
        cameras=adj.frames, points=adj.points, mu=adj.mu, dof=adj.dof, cameras_std=adj.frames_std,
        points_std=adj.points_std, residuals=adj.residuals,
        control_residuals=adj.point_residuals if b.point_obs is not None else np.zeros((k, 3)),
        gnss_residuals=fr[:, :3] if gnss is not None else zeros3, ins_residuals=fr[:, 3:] if ins is not None else zeros3,
        iterations=adj.iterations, history=adj.history, order=order, io=io, calibrated=names,
        io_std=dict(zip(names, adj.globals_std)), correlations=_correlation_report(adj, names, correlation_limit),
        condition_residuals=getattr(adj, "condition_residuals", np.zeros(0)),
        ap_model=None if ap is None else ap.model,
        ap_values={} if ap is None else dict(zip(ap.names, adj.globals[n_io:].tolist())),
        ap_cofactors=None if ap is None else np.array(adj.Q3)[n_io:, n_io:])


@dataclass
class APTestReport:
    """Statistical tests of the additional parameters of a self-calibrating bundle (Hanzl §4.4).

    Attributes
    ----------
    names : tuple of str
        The estimated additional parameters.
    values, std : ndarray
        g_i and σ₀√q_ii (σ₀ = the adjustment's μ).
    t : ndarray
        t_i = g_i / (σ₀√q_ii).
    quantile : float
        Two-sided Student quantile t_{1−α/2}(dof).
    significant : ndarray of bool
        |t_i| > quantile.
    correlated : list of (str, str, float)
        Pairs with |r_ij| = |q_ij|/√(q_ii q_jj) above the limit.

    References
    ----------
    Hanzl, Fotogrammetrie, Modul 01, §4.4 (seed 002 lines 788–794); Chibunichev §3.6.

    Examples
    --------
    >>> rep = APTestReport(("g1",), np.array([2.0]), np.array([1.0]), np.array([2.0]), 1.96,
    ...                    np.array([True]), [])
    >>> rep.insignificant()
    ()
    """

    names: tuple
    values: np.ndarray
    std: np.ndarray
    t: np.ndarray
    quantile: float
    significant: np.ndarray
    correlated: list

    def insignificant(self) -> tuple:
        """Names of the parameters whose |t| does not exceed the quantile."""
        return tuple(nm for nm, ok in zip(self.names, self.significant) if not ok)


def additional_parameter_tests(result: SelfCalibrationResult, *, alpha: float = 0.05,
                               correlation_limit: float = 0.9) -> APTestReport:
    """Significance t-test and correlation test of the additional parameters (Hanzl §4.4).

    t_i = g_i/(σ₀√q_ii) is compared with the two-sided quantile of Student's t with the
    adjustment's degrees of freedom (null hypothesis: g_i is not significant); pairs with
    r_ij = q_ij/√(q_ii q_jj) above ``correlation_limit`` (0.9 in the text) are listed.

    Parameters
    ----------
    result : SelfCalibrationResult
        Of :func:`self_calibrating_bundle_adjustment` with ``additional_parameters``.
    alpha : float
        Significance level, in (0, 1) (0.05: the 95 % of the text).
    correlation_limit : float
        In (0, 1).

    Returns
    -------
    APTestReport

    Raises
    ------
    InputError
        A result without additional parameters; α or the limit outside (0, 1).

    References
    ----------
    Hanzl, Fotogrammetrie, Modul 01, §4.4, r_ij and t_i (seed 002 lines 788–794); Chibunichev §3.6.

    Examples
    --------
    >>> from photolib import synthetic
    >>> from photolib.camera import InteriorOrientation
    >>> blk = synthetic.aerial_block(2, 4, points_per_image=20, sigma=0.002, seed=1)
    >>> cams0, pts0 = blk.start_values(seed=2)
    >>> res = self_calibrating_bundle_adjustment(blk.observations, cams0, pts0, blk.io, calibrate=(),
    ...     additional_parameters="hanzl17", ap_names=("g1", "g2"), ap_base=40.0,
    ...     control={int(i): blk.points[i] for i in blk.control}, order=blk.order)
    >>> additional_parameter_tests(res).names
    ('g1', 'g2')
    """
    if not isinstance(result, SelfCalibrationResult) or not result.ap_values:
        raise InputError("additional_parameter_tests needs a self-calibration result with additional_parameters")
    if not 0 < alpha < 1 or not 0 < correlation_limit < 1:
        raise InputError("alpha and correlation_limit must lie in (0, 1)")

    names = tuple(result.ap_values)
    g = np.array([result.ap_values[nm] for nm in names])
    Q = np.asarray(result.ap_cofactors, dtype=float)
    q = np.diag(Q)
    std = result.mu * np.sqrt(q)
    with np.errstate(divide="ignore", invalid="ignore"):
        t = np.where(std > 0, g / std, np.inf)
    quant = float(stdtrit(max(int(result.dof), 1), 1 - alpha / 2))
    r = Q / np.sqrt(np.outer(q, q))
    pairs = [(names[i], names[j], float(r[i, j])) for i in range(len(names)) for j in range(i + 1, len(names))
             if abs(r[i, j]) > correlation_limit]
    return APTestReport(names, g, std, t, quant, np.abs(t) > quant, pairs)


def select_additional_parameters(observations, cameras0, points0, io0: InteriorOrientation, *,
                                 additional_parameters, ap_names=None, alpha: float = 0.05,
                                 correlation_limit: float = 0.9, **kwargs) -> tuple:
    """Self-calibration with additional parameters, eliminated step by step (Hanzl §4.4).

    Start with all the given parameters; while a pair correlates above ``correlation_limit``, drop
    the member with the smaller |t|; then drop the least significant parameter while its |t| is
    below the quantile, re-adjusting after each removal (the text: start with more parameters and
    eliminate them by statistical tests).

    Parameters
    ----------
    observations, cameras0, points0, io0
        As in :func:`self_calibrating_bundle_adjustment`.
    additional_parameters : str
        The AP model.
    ap_names : sequence of str, optional
        The candidate parameters (default all of the model).
    alpha, correlation_limit : float
        As in :func:`additional_parameter_tests`.
    **kwargs
        Passed to :func:`self_calibrating_bundle_adjustment` (``ap_base``, ``calibrate``, ``control``, ...).

    Returns
    -------
    (SelfCalibrationResult, list of (str, str))
        The final adjustment and the removals in order as (name, reason), reason
        ``"correlation"`` or ``"t-test"``. If every parameter is removed the result is that of the
        last adjustment that still had one and the list says so.

    Raises
    ------
    InputError
        As :func:`self_calibrating_bundle_adjustment` / :func:`additional_parameter_tests`.

    References
    ----------
    Hanzl, Fotogrammetrie, Modul 01, §4.4 (seed 002 lines 786–796); Chibunichev §3.6.

    Examples
    --------
    >>> from photolib import synthetic
    >>> blk = synthetic.aerial_block(2, 4, points_per_image=20, sigma=0.002, seed=1)
    >>> cams0, pts0 = blk.start_values(seed=2)
    >>> res, removed = select_additional_parameters(blk.observations, cams0, pts0, blk.io, calibrate=(),
    ...     additional_parameters="hanzl17", ap_names=("g1", "g2"), ap_base=40.0,
    ...     control={int(i): blk.points[i] for i in blk.control}, order=blk.order)
    >>> len(removed) >= 1                     # no deformation was simulated
    True
    """

    current = list(apm.parameter_names(additional_parameters) if ap_names is None else ap_names)
    removed = []
    while True:
        res = self_calibrating_bundle_adjustment(observations, cameras0, points0, io0,
                                                 additional_parameters=additional_parameters, ap_names=current,
                                                 correlation_limit=correlation_limit, **kwargs)
        rep = additional_parameter_tests(res, alpha=alpha, correlation_limit=correlation_limit)
        tabs = dict(zip(rep.names, np.abs(rep.t)))
        if rep.correlated:
            a, b_, _ = max(rep.correlated, key=lambda p: abs(p[2]))
            drop, why = (a if tabs[a] < tabs[b_] else b_), "correlation"
        elif rep.insignificant():
            drop, why = min(rep.insignificant(), key=tabs.get), "t-test"
        else:
            return res, removed
        removed.append((drop, why))
        if len(current) == 1:
            return res, removed
        current.remove(drop)


# --- §3.8 multi-camera rigs ----------------------------------------------------------------------
def rig_image_orientation(exposure_eo, mount, order: str = "kaw") -> np.ndarray:
    """EO (X_S, Y_S, Z_S, ω, α, κ) of a rig camera from the reference EO and its mounting elements.

    S₂ = S₁ + A₁B (3.8.5), C₂ = A₁A₂′ (3.8.8); the angles of C₂ by (1.3.3)/(1.3.6). Arrays of
    shape (..., 6) broadcast.

    Parameters
    ----------
    exposure_eo : array_like (..., 6)
        EO of the reference camera.
    mount : array_like (..., 6)
        Mounting elements B_X, B_Y, B_Z (m, reference-camera frame), ω′, α′, κ′ (rad).
    order : {"kaw", "wak"}

    Returns
    -------
    ndarray (..., 6)
        EO of the rig camera.

    Raises
    ------
    InputError
        Shapes other than (..., 6); NaN.

    References
    ----------
    Chibunichev (2022), §3.8, eqs. (3.8.5), (3.8.8); §1.3, eqs. (1.3.3), (1.3.6).

    Examples
    --------
    >>> import numpy as np
    >>> eo = np.array([100.0, 200.0, 1000.0, 0.01, -0.02, 0.3])
    >>> bool(np.allclose(rig_image_orientation(eo, np.zeros(6)), eo))        # no offset, no rotation
    True
    >>> rig_image_orientation(np.zeros(6), [1.0, 2.0, 3.0, 0, 0, 0])[:3]       # A₁ = E: S₂ = S₁ + B
    array([1., 2., 3.])
    """
    check_order(order)
    try:
        e = np.asarray(exposure_eo, dtype=float)
        mnt = np.asarray(mount, dtype=float)
    except (TypeError, ValueError) as exc:
        raise InputError(f"exposure_eo and mount must be numbers: {exc}") from None
    if e.ndim == 0 or mnt.ndim == 0 or e.shape[-1] != 6 or mnt.shape[-1] != 6:
        raise InputError("exposure_eo and mount must end in 6 values")
    if not (np.all(np.isfinite(e)) and np.all(np.isfinite(mnt))):
        raise InputError("exposure_eo and mount contain NaN or inf")
    A1 = rotation_matrix(e[..., 3], e[..., 4], e[..., 5], order)
    A2 = rotation_matrix(mnt[..., 3], mnt[..., 4], mnt[..., 5], order)
    S2 = e[..., :3] + np.einsum("...ij,...j->...i", A1, mnt[..., :3] * np.ones_like(e[..., :3]))
    ang = rotation_angles(A1 @ A2, order)
    return np.concatenate([S2, np.stack(np.broadcast_arrays(*ang), axis=-1)], axis=-1)


def _rig_layout(exposure_of_image, camera_of_image):
    e = np.asarray(exposure_of_image)
    c = np.asarray(camera_of_image)
    if e.ndim != 1 or c.shape != e.shape or e.size == 0:
        raise InputError("exposure_of_image and camera_of_image must be 1-D arrays of the same length")
    for nm, a in (("exposure_of_image", e), ("camera_of_image", c)):
        if not np.all(np.isfinite(a.astype(float))) or np.any(a != np.round(a)) or a.min() < 0:
            raise InputError(f"{nm} must hold non-negative integers")
    e, c = e.astype(np.intp), c.astype(np.intp)
    if np.unique(e * (c.max() + 1) + c).size != e.size:
        raise InputError("two images share the same exposure and camera")
    n_exp, n_cam = int(e.max()) + 1, int(c.max()) + 1
    ref = np.full(n_exp, -1)
    ref[e[c == 0]] = np.flatnonzero(c == 0)
    return e, c, n_exp, n_cam, ref


def _rig_correction_equations(image, point, xy, exposure_of_image, camera_of_image, exposures, mounts, points,
                             ios, order: str = "kaw") -> GlobalBlockCorrectionEquations:
    """Correction equations (3.8.14) (reference camera) and (3.8.15) (other cameras) of a rig block.

    Frames are the exposures (δX_S1 … δκ₁); the block-wide unknowns are the 6 mounting elements
    B_X, B_Y, B_Z, ω′, α′, κ′ of every camera but the reference one (camera 0), so B3 has
    6(n_s − 1) columns and an observation in camera c only fills the six of its camera.
    Derivatives from :func:`photolib.derivations.rig_collinearity_model`.
    """
    e_img, c_img = np.asarray(exposure_of_image), np.asarray(camera_of_image)
    ex, cam = e_img[image], c_img[image]
    n_cam = mounts.shape[0] + 1
    m = image.size
    B1, B2, L = np.zeros((m, 2, 6)), np.zeros((m, 2, 3)), np.zeros((m, 2))
    B3 = np.zeros((m, 2, 6 * (n_cam - 1)))
    per_image = rig_image_orientation(exposures[e_img], np.vstack([np.zeros((1, 6)), mounts])[c_img], order)
    _zstar_check(per_image, points, image, point, order)
    for c in range(n_cam):
        sel = np.flatnonzero(cam == c)
        if not sel.size:
            continue
        io = ios[c]
        e, X = exposures[ex[sel]], points[point[sel]]
        if c == 0:
            F, J = getattr(_bundle_generated, f"collinearity_{order}")(
                e[:, 0], e[:, 1], e[:, 2], e[:, 3], e[:, 4], e[:, 5], X[:, 0], X[:, 1], X[:, 2],
                xy[sel, 0], xy[sel, 1], io.f, io.x0, io.y0)
            J = J.reshape(2, 9, -1).transpose(2, 0, 1)
            B1[sel], B2[sel] = J[:, :, :6], J[:, :, 6:]
        else:
            mt = mounts[c - 1]
            F, J = getattr(_bundle_generated, f"rig_{order}")(
                e[:, 0], e[:, 1], e[:, 2], e[:, 3], e[:, 4], e[:, 5], *mt, X[:, 0], X[:, 1], X[:, 2],
                xy[sel, 0], xy[sel, 1], io.f, io.x0, io.y0)
            J = J.reshape(2, 15, -1).transpose(2, 0, 1)
            B1[sel], B2[sel] = J[:, :, :6], J[:, :, 12:]
            B3[sel, :, 6 * (c - 1):6 * c] = J[:, :, 6:12]
        L[sel] = F.T
    return GlobalBlockCorrectionEquations(frame=ex, point=point, B1=B1, B2=B2, L=L, P=1.0, B3=B3)


@dataclass
class RigResult:
    """Adjusted rig block (§3.8): reference EO per exposure, mounting elements, points, accuracy.

    Attributes
    ----------
    exposures : ndarray (n, 6)
        EO of the reference camera per exposure.
    mounts : ndarray (n_s − 1, 6)
        Mounting elements of the other cameras.
    points, mu, dof, residuals, iterations, order
        As in :class:`BundleResult`.
    exposures_std, mounts_std, points_std : ndarray
        m_j (3.5.11).
    mount_correlation : ndarray
        Correlations of the mounting elements.
    n_unknowns : int
        N₂ of (3.8.2).

    References
    ----------
    Chibunichev (2022), §3.8, eqs. (3.8.2)–(3.8.15).

    Examples
    --------
    >>> import numpy as np
    >>> from photolib import synthetic
    >>> rb = synthetic.rig_block(sigma=0.0, seed=0)
    >>> res = rig_bundle_adjustment(rb.observations, rb.exposure_of_image, rb.camera_of_image, rb.exposures,
    ...                             rb.mounts, rb.points, rb.ios, control={int(i): rb.points[i] for i in rb.control},
    ...                             order=rb.order)
    >>> res.mounts.shape, float(np.abs(res.mounts - rb.mounts).max()) < 1e-6
    ((4, 6), True)
    """

    exposures: np.ndarray            # (n, 6) EO of the reference camera per exposure
    mounts: np.ndarray               # (n_s − 1, 6) B_X, B_Y, B_Z (m, reference-camera frame), ω′, α′, κ′
    points: np.ndarray
    mu: float
    dof: int
    exposures_std: np.ndarray
    mounts_std: np.ndarray
    points_std: np.ndarray
    mount_correlation: np.ndarray    # (6(n_s−1), 6(n_s−1))
    residuals: np.ndarray
    iterations: int
    order: str
    n_unknowns: int

    def image_orientation(self, exposure: int, camera: int) -> np.ndarray:
        """EO of camera ``camera`` at ``exposure`` by (3.8.5)/(3.8.8)."""
        mount = np.zeros(6) if camera == 0 else self.mounts[camera - 1]
        return rig_image_orientation(self.exposures[exposure], mount, self.order)


def _ios_per_camera(ios, n_cam):
    ios = [ios] * n_cam if isinstance(ios, InteriorOrientation) else list(ios)
    if len(ios) != n_cam or not all(isinstance(i, InteriorOrientation) for i in ios):
        raise InputError(f"ios: give one InteriorOrientation or one per camera ({n_cam})")
    return ios


def rig_bundle_adjustment(observations, exposure_of_image, camera_of_image, exposures0, mounts0, points0, ios, *,
                          control=None, sigma_control=None, gnss=None, sigma_centre=0.05, sigma_image: float = 0.005,
                          order: str = "kaw", max_iter: int = 30, tol_centre: float = 1e-5, tol_angle: float = 1e-9,
                          tol_point: float = 1e-5, **legacy) -> RigResult:
    """Bundle adjustment of a multi-camera rig with constant mounting elements, §3.8 (3.8.2)–(3.8.15).

    Unknowns: the EO of the reference camera (camera 0, e.g. the nadir camera) per exposure, the 6
    mounting elements of every other camera (lever arm B in the reference-camera frame and the
    rotation A₂′, constant over the flight) and the points — N₂ = 6(n + n_s − 1) + 3k (3.8.2).
    The free alternative, every image with its own EO (3.8.1), is :func:`bundle_adjustment`.

    Parameters
    ----------
    observations : as in :func:`bundle_adjustment`; ``image`` indexes the images.
    exposure_of_image, camera_of_image : int arrays (n_images,)
        Exposure and camera of each image; every exposure must contain a camera-0 image.
    exposures0 : (n, 6), mounts0 : (n_s − 1, 6), points0 : (k, 3)
        Approximations.
    ios : InteriorOrientation or one per camera
        Known interior orientation (distortion corrected first).
    gnss : (n, 3), optional
        GNSS centres of the reference camera per exposure (NaN rows where missing).

    Returns
    -------
    RigResult

    Raises
    ------
    InputError
        Malformed layout or approximations; an exposure without a reference-camera image.
    DegenerateGeometryError
        Datum defect; mounting elements not separable from the exposures.
    ConvergenceError
        Divergence or no convergence.

    References
    ----------
    Chibunichev (2022), §3.8, eqs. (3.8.2)–(3.8.15).

    Examples
    --------
    >>> import numpy as np
    >>> from photolib import synthetic
    >>> rb = synthetic.rig_block(sigma=0.0, seed=0)
    >>> res = rig_bundle_adjustment(rb.observations, rb.exposure_of_image, rb.camera_of_image, rb.exposures,
    ...                             rb.mounts, rb.points, rb.ios, control={int(i): rb.points[i] for i in rb.control},
    ...                             order=rb.order)
    >>> res.n_unknowns == count_rig_unknowns(len(rb.exposures), 5, len(rb.points) - len(rb.control))
    True
    """
    sigma_control, sigma_centre = _renamed(legacy, "rig_bundle_adjustment", sigma_control=sigma_control,
                                           sigma_centre=sigma_centre)
    check_order(order)
    e_img, c_img, n_exp, n_cam, ref = _rig_layout(exposure_of_image, camera_of_image)
    if np.any(ref < 0):
        raise InputError(f"exposures {np.flatnonzero(ref < 0)[:10].tolist()} have no reference-camera (camera 0) image")
    ios = _ios_per_camera(ios, n_cam)
    exp0 = np.array(exposures0, dtype=float)
    mnt0 = np.array(mounts0, dtype=float).reshape(-1, 6) if n_cam > 1 else np.zeros((0, 6))
    if exp0.shape != (n_exp, 6) or mnt0.shape != (n_cam - 1, 6):
        raise InputError(f"exposures0 must be ({n_exp}, 6) and mounts0 ({n_cam - 1}, 6)")
    if not (np.all(np.isfinite(exp0)) and np.all(np.isfinite(mnt0))):
        raise InputError("exposures0/mounts0 contain NaN or inf")
    cams_img = rig_image_orientation(exp0[e_img], np.vstack([np.zeros((1, 6)), mnt0])[c_img], order)
    gnss_img = None
    if gnss is not None:
        gn = np.asarray(gnss, dtype=float)
        if gn.shape != (n_exp, 3):
            raise InputError(f"gnss: expected ({n_exp}, 3) reference-camera centres")
        gnss_img = np.full((e_img.size, 3), np.nan)
        gnss_img[ref] = gn
    # validation with the per-image orientation; distortion of each camera corrected here
    b = _prepare_block(observations, cams_img, points0, ios[0], control, sigma_control, gnss_img, sigma_centre, None,
                       np.radians(0.005), sigma_image, order, correct_distortion_first=False)
    xy = b.xy.copy()
    for c in range(n_cam):
        sel = c_img[b.image] == c
        if ios[c].has_distortion and sel.any():
            xy[sel] = correct_distortion(xy[sel], ios[c])
    frame_obs = None
    if b.frame_obs is not None:
        frame_obs = (b.frame_obs[0][ref], b.frame_obs[1][ref])

    def linearize(frames, points, glob):
        return _rig_correction_equations(b.image, b.point, xy, e_img, c_img, frames, glob.reshape(-1, 6), points,
                                        ios, order)

    mount_names = [f"{nm} (camera {c})" for c in range(1, n_cam) for nm in MOUNT_NAMES]
    try:
        adj = block_gauss_newton(linearize, exp0, b.pts, mnt0.ravel(), frame_observations=frame_obs,
                                        point_observations=b.point_obs, free_points=b.free_points,
                                        tol_frames=[tol_centre] * 3 + [tol_angle] * 3, tol_points=tol_point,
                                        tol_globals=np.tile([tol_centre] * 3 + [tol_angle] * 3, n_cam - 1),
                                        max_iter=max_iter, covariance=True, global_names=mount_names,
                                        frame_names=EO_NAMES)
    except PointBehindCameraError as exc:
        raise ConvergenceError(f"the iteration diverged: {exc}") from exc
    s = np.sqrt(np.diag(adj.Q3)) if adj.Q3.size else np.zeros(0)
    corr = adj.Q3 / np.outer(s, s) if s.size else np.zeros((0, 0))
    n_unk = 6 * n_exp + adj.globals.size + 3 * int(b.free_points.sum())
    return RigResult(exposures=adj.frames, mounts=adj.globals.reshape(-1, 6), points=adj.points, mu=adj.mu,
                     dof=adj.dof, exposures_std=adj.frames_std, mounts_std=adj.globals_std.reshape(-1, 6),
                     points_std=adj.points_std, mount_correlation=corr, residuals=adj.residuals,
                     iterations=adj.iterations, order=order, n_unknowns=n_unk)


def rig_design_matrix(observations, exposure_of_image, camera_of_image, exposures, mounts, points, ios, *,
                      free_points=None, parameterisation: str = "rig", order: str = "kaw"):
    """Dense correction-equation matrix of a small rig block — the structure of fig. 3.18 / fig. 3.11.

    ``"rig"``: columns = EO per exposure | mounting elements | free points (fig. 3.18);
    ``"free"``: columns = EO per image | free points (fig. 3.11, (3.8.1)). Returns (A, L).

    Parameters
    ----------
    observations, exposure_of_image, camera_of_image, exposures, mounts, points, ios
        As in :func:`rig_bundle_adjustment` (values at which to linearise).
    free_points : bool array, optional
        Points that are unknowns (default: all).
    parameterisation : {"rig", "free"}
        Column layout of fig. 3.18 or fig. 3.11.
    order : {"kaw", "wak"}

    Returns
    -------
    A : ndarray
        The dense correction-equation matrix.
    L : ndarray
        The free terms.

    Raises
    ------
    InputError
        Malformed input or an unknown parameterisation.

    References
    ----------
    Chibunichev (2022), §3.8, eqs. (3.8.1), (3.8.2), (3.8.14), (3.8.15); figs. 3.11, 3.18.

    Examples
    --------
    >>> import numpy as np
    >>> from photolib import synthetic
    >>> rb = synthetic.rig_block(sigma=0.0, seed=0)
    >>> A, L = rig_design_matrix(rb.observations, rb.exposure_of_image, rb.camera_of_image, rb.exposures,
    ...                          rb.mounts, rb.points, rb.ios, order=rb.order)
    >>> A.shape[1] == count_rig_unknowns(len(rb.exposures), 5, len(rb.points)), float(np.abs(L).max()) < 1e-9
    (True, True)
    """
    image, point, xy = _as_observations(observations)
    e_img, c_img, n_exp, n_cam, _ = _rig_layout(exposure_of_image, camera_of_image)
    ios = _ios_per_camera(ios, n_cam)
    exposures, points = np.asarray(exposures, dtype=float), np.asarray(points, dtype=float)
    mounts = np.asarray(mounts, dtype=float).reshape(-1, 6)
    if parameterisation == "rig":
        eq = _rig_correction_equations(image, point, xy, e_img, c_img, exposures, points=points, mounts=mounts,
                                      ios=ios, order=order)
        B, L, _ = global_block_equations_dense(eq, n_exp, points.shape[0], free_points)
    elif parameterisation == "free":
        cams = rig_image_orientation(exposures[e_img], np.vstack([np.zeros((1, 6)), mounts])[c_img], order)
        rows = []
        for c in range(n_cam):
            rows.append(c_img[image] == c)
        B_parts = np.zeros((2 * image.size, 6 * e_img.size + 3 * int(np.sum(
            np.ones(points.shape[0], bool) if free_points is None else free_points))))
        Lv = np.zeros(2 * image.size)
        for c, sel in enumerate(rows):
            if not sel.any():
                continue
            eq = bundle_correction_equations(image[sel], point[sel], xy[sel], cams, points, ios[c], order)
            Bc, Lc, _ = block_equations_dense(eq, e_img.size, points.shape[0], free_points)
            idx = np.flatnonzero(sel)
            r = np.column_stack([2 * idx, 2 * idx + 1]).ravel()
            B_parts[r], Lv[r] = Bc, Lc
        B, L = B_parts, Lv
    else:
        raise InputError(f"parameterisation must be 'rig' or 'free', got {parameterisation!r}")
    return B, L


# --- §3.9 rolling shutter ----------------------------------------------------------------------
def _rs_frames(cameras, rates, n):
    cams = np.asarray(cameras, dtype=float).reshape(-1, 6)
    rt = np.zeros((cams.shape[0], 6)) if rates is None else np.asarray(rates, dtype=float).reshape(-1, 6)
    if rt.shape != cams.shape:
        raise InputError(f"rates must have the shape of the exterior orientations {cams.shape}, got {rt.shape}")
    if not (np.all(np.isfinite(cams)) and np.all(np.isfinite(rt))):
        raise InputError("exterior orientation or rates contain NaN or inf")
    return cams, rt


def rolling_shutter_project(eo0, rates, XYZ, io: InteriorOrientation, order: str = "kaw", *, image=None,
                            tol: float = 1e-10, max_iter: int = 50, return_iterations: bool = False):
    """Project object points into rolling-shutter images, (3.9.1) with (3.9.2), by iteration.

    The EO of the line that records a point depends on that point's own image coordinate x:
    EO(x) = EO₀ + k·x (3.9.2). The projection is therefore implicit; it is solved by the
    fixed-point iteration x ← x₀ − f x*/z*(EO(x)), starting from the frame projection
    (x = 0). The iteration contracts when the image moves little during the readout (the usual
    case: a few iterations); otherwise :class:`ConvergenceError` is raised.

    Parameters
    ----------
    eo0 : (6,) or (n, 6)
        EO at the line x = 0 (X_S0, …, κ₀).
    rates : (6,) or (n, 6) or None
        k₁ … k₆ of (3.9.2): change of X_S, Y_S, Z_S (m/mm) and of ω, α, κ (rad/mm) per mm of x.
        ``None`` or zeros: a frame (global-shutter) image.
    XYZ : (k, 3)
        Object points.
    image : int array (k,), optional
        Image of each point when several EO are given.
    tol, max_iter
        Stop when every |Δx| < tol (mm); raise after ``max_iter`` iterations.
    return_iterations : bool
        Also return the number of iterations used.

    Parameters
    ----------
    eo0 : array_like (6,) or (n, 6)
        EO at the line x = 0 (one or one per image).
    rates : array_like (6,) or (n, 6) or None
        k₁ … k₆ per mm of x (None: a frame camera).
    XYZ : array_like (k, 3) or (3,)
        Object points.
    io : InteriorOrientation
    order : {"kaw", "wak"}
    image : int array (k,), optional
        The image of each point (needed with several EO).
    tol, max_iter
        Convergence of the fixed-point iteration (mm, steps).
    return_iterations : bool
        Also return the number of iterations.

    Returns
    -------
    xy : ndarray (k, 2)
        Image coordinates, mm (and the iteration count if asked).

    Raises
    ------
    InputError
        Malformed input.
    PointBehindCameraError
        A point behind the image line.
    ConvergenceError
        The iteration does not contract (rates far too large).

    References
    ----------
    Chibunichev (2022), §3.9, eqs. (3.9.1), (3.9.2).

    Examples
    --------
    >>> import numpy as np
    >>> from photolib import synthetic
    >>> blk = synthetic.aerial_block(1, 3, f=8.8, frame_size=13.2, flying_height=100.0, sigma=0.0, seed=4)
    >>> o = blk.observations
    >>> xy = rolling_shutter_project(blk.cameras, None, blk.points[o.point], blk.io, blk.order, image=o.image)
    >>> bool(np.allclose(xy, blk.xy_true, atol=1e-10))          # zero rates: the frame projection
    True
    """
    check_order(order)
    if not isinstance(io, InteriorOrientation):
        raise InputError("io must be an InteriorOrientation")
    X = np.asarray(XYZ, dtype=float)
    X = X.reshape(1, 3) if X.shape == (3,) else X
    if X.ndim != 2 or X.shape[1] != 3 or not np.all(np.isfinite(X)):
        raise InputError("XYZ must be a finite (k, 3) array")
    cams, rt = _rs_frames(eo0, rates, X.shape[0])
    if image is None and cams.shape[0] > 1:
        raise InputError(f"{cams.shape[0]} exterior orientations are given: say with `image` which one each point belongs to")
    idx = np.zeros(X.shape[0], np.intp) if image is None else np.asarray(image, dtype=np.intp)
    if idx.shape != (X.shape[0],) or idx.min(initial=0) < 0 or idx.max(initial=0) >= cams.shape[0]:
        raise InputError("image must give a valid image index for every point")
    x = np.zeros(X.shape[0])
    each = np.arange(X.shape[0])
    for it in range(1, max_iter + 1):
        e = cams[idx] + rt[idx] * x[:, None]                 # the orientation at the time of line x (3.9.2)
        xy, z_star = project_to_images(e, each, X, io, order)
        if np.any(z_star >= 0):
            raise PointBehindCameraError(
                f"points {np.flatnonzero(z_star >= 0)[:10].tolist()} are not in front of the image line (z* ≥ 0)",
                points=np.flatnonzero(z_star >= 0).tolist())
        step = np.abs(xy[:, 0] - x)
        x = xy[:, 0]
        if not np.all(np.isfinite(x)):
            break
        if np.all(step < tol):
            return (xy, it) if return_iterations else xy
    bad = np.flatnonzero(~(step < tol))[:10].tolist()
    raise ConvergenceError(
        f"rolling-shutter projection (3.9.1)/(3.9.2) did not converge in {max_iter} iterations for points {bad} "
        f"(last |Δx| up to {np.nanmax(step):.3g} mm): the image moves too fast during the readout for the "
        "fixed-point iteration — are the rates k₁…k₆ per mm of x and realistic?")


def rolling_shutter_correction_equations(image, point, xy, frames, points, io: InteriorOrientation,
                                         order: str = "kaw", model: str = "full") -> BlockCorrectionEquations:
    """Correction equations of rolling-shutter images: 12 (``"full"``) or 9 (``"linear"``) unknowns per image.

    ``frames`` rows are (X_S0, Y_S0, Z_S0, ω₀, α₀, κ₀, k₁, …, k₆) or the first 9 of them. The
    measured x of each observation fixes its line (3.9.2). Derivatives from
    :func:`photolib.derivations.rolling_shutter_model`.

    Parameters
    ----------
    image, point, xy
        As in :func:`bundle_correction_equations`.
    frames : ndarray (n, 12) or (n, 9)
        EO at x = 0 and the rates.
    points : ndarray (k, 3)
    io : InteriorOrientation
    order : {"kaw", "wak"}
    model : {"full", "linear"}

    Returns
    -------
    BlockCorrectionEquations
        B1 (m, 2, 12 or 9), B2 (m, 2, 3), L (m, 2).

    Raises
    ------
    InputError
        An unknown model.
    PointBehindCameraError
        A point behind its image.

    References
    ----------
    Chibunichev (2022), §3.9, eqs. (3.9.1), (3.9.2).

    Examples
    --------
    >>> import numpy as np
    >>> from photolib import synthetic
    >>> blk = synthetic.aerial_block(1, 3, f=8.8, frame_size=13.2, flying_height=100.0, sigma=0.0, seed=4)
    >>> o = blk.observations
    >>> frames = np.hstack([blk.cameras, np.zeros((blk.n_images, 6))])
    >>> eq = rolling_shutter_correction_equations(o.image, o.point, blk.xy_true, frames, blk.points, blk.io, blk.order)
    >>> eq.B1.shape[1:], float(np.abs(eq.L).max()) < 1e-9
    ((2, 12), True)
    """
    q = {"full": 12, "linear": 9}.get(model)
    if q is None:
        raise InputError(f"model must be 'full' or 'linear', got {model!r}")
    fr = np.zeros((frames.shape[0], 12))
    fr[:, :q] = frames
    c, X = fr[image], points[point]
    e = c[:, :6] + c[:, 6:] * xy[:, :1]
    _zstar_check(e, X, np.arange(image.size), np.arange(image.size), order)
    F, J = getattr(_bundle_generated, f"rolling_{order}")(*[c[:, i] for i in range(12)], X[:, 0], X[:, 1], X[:, 2],
                                                          xy[:, 0], xy[:, 1], io.f, io.x0, io.y0)
    J = J.reshape(2, 15, -1).transpose(2, 0, 1)
    return BlockCorrectionEquations(frame=image, point=point, B1=J[:, :, :q], B2=J[:, :, 12:], L=F.T, P=1.0)


@dataclass
class RollingShutterResult:
    """Adjusted rolling-shutter block (§3.9).

    Attributes
    ----------
    cameras : ndarray (n, 6)
        EO at the line x = 0.
    rates : ndarray (n, 6)
        k₁ … k₆ (zeros for the angular rates in the linear model).
    points, mu, dof, residuals, iterations
        As in :class:`BundleResult`.
    cameras_std, rates_std, points_std : ndarray or None
        m_j (3.5.11).
    model : str
    n_unknowns : int

    References
    ----------
    Chibunichev (2022), §3.9, eqs. (3.9.1), (3.9.2).

    Examples
    --------
    >>> import numpy as np
    >>> from photolib import synthetic
    >>> rb = synthetic.rolling_shutter_block(sigma=0.0, model="linear")
    >>> b = rb.block
    >>> cams0, pts0 = b.start_values(seed=1)
    >>> res = rolling_shutter_bundle_adjustment(rb.observations, cams0, pts0, b.io, model="linear",
    ...                                         control={int(i): b.points[i] for i in b.control}, order=b.order)
    >>> bool(np.allclose(res.rates, rb.rates, atol=1e-8)), res.model
    (True, 'linear')
    """

    cameras: np.ndarray          # (n, 6) EO at the line x = 0
    rates: np.ndarray            # (n, 6) k₁ … k₆ (zeros for the angular rates in the linear model)
    points: np.ndarray
    mu: float
    dof: int
    cameras_std: np.ndarray | None
    rates_std: np.ndarray | None
    points_std: np.ndarray | None
    residuals: np.ndarray
    iterations: int
    model: str
    n_unknowns: int


def rolling_shutter_bundle_adjustment(observations, cameras0, points0, io: InteriorOrientation, *, rates0=None,
                                      model: str = "full", control=None, sigma_control=None, gnss=None,
                                      sigma_centre=0.05, sigma_image: float = 0.005, order: str = "kaw",
                                      max_iter: int = 30, covariance: bool = True, **legacy) -> RollingShutterResult:
    """Bundle adjustment of rolling-shutter images, §3.9: (3.9.1) with (3.9.2).

    Per image 12 unknowns (EO at the line x = 0 and the six rates k₁…k₆) or, with
    ``model="linear"``, 9 (the angles held constant over the readout). GNSS centres, if given,
    observe X_S0, Y_S0, Z_S0. Other parameters as in :func:`bundle_adjustment`.

    Parameters
    ----------
    observations, cameras0, points0, io, control, sigma_control, gnss, sigma_centre, sigma_image, order, max_iter
        As in :func:`bundle_adjustment` (``cameras0``: the EO at the line x = 0).
    rates0 : (n, 6) array, optional
        Start values of k₁ … k₆ (zeros if omitted).
    model : {"full", "linear"}
        12 or 9 unknowns per image.
    covariance : bool
        Compute m_j of all unknowns.

    Returns
    -------
    RollingShutterResult

    Raises
    ------
    InputError
        Malformed input; too few points per image for the model.
    DegenerateGeometryError
        Datum defect, undetermined points.
    ConvergenceError
        Divergence or no convergence.

    References
    ----------
    Chibunichev (2022), §3.9, eqs. (3.9.1), (3.9.2); §3.5, eqs. (3.5.9)–(3.5.16).

    Examples
    --------
    >>> import numpy as np
    >>> from photolib import synthetic
    >>> rb = synthetic.rolling_shutter_block(sigma=0.0, model="linear")
    >>> b = rb.block
    >>> cams0, pts0 = b.start_values(seed=1)
    >>> res = rolling_shutter_bundle_adjustment(rb.observations, cams0, pts0, b.io, model="linear",
    ...                                         control={int(i): b.points[i] for i in b.control}, order=b.order)
    >>> bool(np.allclose(res.cameras, b.cameras, atol=1e-6))
    True
    """
    sigma_control, sigma_centre = _renamed(legacy, "rolling_shutter_bundle_adjustment", sigma_control=sigma_control,
                                           sigma_centre=sigma_centre)
    q = {"full": 12, "linear": 9}.get(model)
    if q is None:
        raise InputError(f"model must be 'full' (12 unknowns per image) or 'linear' (9), got {model!r}")
    b = _prepare_block(observations, cameras0, points0, io, control, sigma_control, gnss, sigma_centre, None,
                       np.radians(0.005), sigma_image, order)
    cams, rt = _rs_frames(b.cams, rates0, 0)
    frames0 = np.hstack([cams, rt])[:, :q]
    per_image = np.bincount(b.image, minlength=b.n)
    if np.any(per_image < q // 2 + 1):
        raise InputError(f"images {np.flatnonzero(per_image < q // 2 + 1)[:10].tolist()} have too few points for "
                         f"{q} unknowns per image (need at least {q // 2 + 1})")
    frame_obs = None
    if b.frame_obs is not None:
        fv, fw = np.full((b.n, q), np.nan), np.zeros((b.n, q))
        fv[:, :3], fw[:, :3] = b.frame_obs[0][:, :3], b.frame_obs[1][:, :3]
        frame_obs = (fv, fw)

    def linearize(frames, points):
        return rolling_shutter_correction_equations(b.image, b.point, b.xy, frames, points, io, order, model)

    tol = [1e-5] * 3 + [1e-9] * 3 + [1e-7] * 3 + [1e-11] * 3
    try:
        adj = block_gauss_newton(linearize, frames0, b.pts, frame_observations=frame_obs,
                                 point_observations=b.point_obs, free_points=b.free_points, tol_frames=tol[:q],
                                 tol_points=1e-5, max_iter=max_iter, covariance=covariance)
    except PointBehindCameraError as exc:
        raise ConvergenceError(f"the iteration diverged: {exc}") from exc
    full = np.zeros((b.n, 12))
    full[:, :q] = adj.frames
    std = None
    if adj.frames_std is not None:
        std = np.zeros((b.n, 12))
        std[:, :q] = adj.frames_std
    return RollingShutterResult(cameras=full[:, :6], rates=full[:, 6:], points=adj.points, mu=adj.mu, dof=adj.dof,
                                cameras_std=None if std is None else std[:, :6],
                                rates_std=None if std is None else std[:, 6:], points_std=adj.points_std,
                                residuals=adj.residuals, iterations=adj.iterations, model=model,
                                n_unknowns=q * b.n + 3 * int(b.free_points.sum()))


def _scalar_source(order: str) -> str:
    """One observation of the bundle model as scalar code (for the compiled loop of :mod:`photolib._block_kernels`).

    The same sympy expressions as ``collinearity_<order>`` — residuals F_x, F_y and the 18
    derivatives a₁…a₉, b₁…b₉ (3.5.2) — plus z* of (1.4.10), all through one common-subexpression
    elimination, returned as a tuple of 21 floats.
    """
    import sympy as sp
    from sympy.printing.numpy import NumPyPrinter
    from .derivations import bundle_collinearity_model
    from .derivations.collinearity import collinearity_terms
    model = bundle_collinearity_model(order)
    exprs = list(model.residuals) + list(model.jacobian()) + [collinearity_terms(order)[2]]
    replacements, reduced = sp.cse(exprs, symbols=sp.numbered_symbols("_t"), optimizations="basic")
    printer = NumPyPrinter({"fully_qualified_modules": True, "inline": True})
    args = [printer.doprint(a) for a in list(model.parameters) + list(model.data)]
    lines = [f"def collinearity_{order}_point({', '.join(args)}):",
             f'    """One observation of {model.name!r}: (F_x, F_y, a₁…a₉, b₁…b₉, z*) as floats."""']
    lines += [f"    {printer.doprint(sym)} = {printer.doprint(expr)}" for sym, expr in replacements]
    lines.append(f"    return ({', '.join(printer.doprint(e) for e in reduced)})")
    return "\n".join(lines) + "\n"


def generated_source() -> str:
    """Text of ``photolib/_bundle_generated.py``, printed from the sympy models (imports sympy)."""
    from .derivations import (bundle_collinearity_model, numpy_source, rig_collinearity_model, rolling_shutter_model,
                              self_calibration_model)
    parts = ['"""GENERATED by ``python -m photolib.bundle`` from photolib.derivations.bundle_collinearity_model',
             "— do not edit. Residuals (3.5.1) and Jacobian (3.5.2) of the bundle model, one function per",
             "rotation sequence; then the Chapter 3 extensions: self-calibration (3.6.1)/(3.6.3), rig cameras",
             '(3.8.13)/(3.8.15), rolling shutter (3.9.1)/(3.9.2); see :func:`photolib.derivations.numpy_source`."""',
             "", "import numpy", ""]
    for order in ("kaw", "wak"):
        parts += ["", numpy_source(bundle_collinearity_model(order), f"collinearity_{order}")]
    for order in ("kaw", "wak"):
        parts += ["", _scalar_source(order)]
    for model, name in ((self_calibration_model, "selfcal"), (rig_collinearity_model, "rig"),
                        (rolling_shutter_model, "rolling")):
        for order in ("kaw", "wak"):
            parts += ["", numpy_source(model(order), f"{name}_{order}")]
    return "\n".join(parts)


if __name__ == "__main__":
    from pathlib import Path
    target = Path(__file__).with_name("_bundle_generated.py")
    target.write_text(generated_source())
    print(f"wrote {target}")
