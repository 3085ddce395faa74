"""Chapter 9, §9.11 (point-cloud segmentation and classification): the formula (9.11.1) and the
inline statements, adapters for ``textbook/ch09_segmentation.toml``.

(9.11.1) p = X cos α cos β + Y sin α cos β + Z sin β is derived with sympy as p = n·X with the
unit normal n(α, β) of azimuth α and elevation β; the statements (minimal samples of RANSAC,
centring before the Hough transform, the effect of the angular step, robustness of RANSAC) are
checked by sympy/numeric rank arguments and small seeded simulations through
:mod:`photolib.segmentation` (conditions in each entry's ``notes``).
"""

from __future__ import annotations

import math

import numpy as np
import sympy as sp

from .. import segmentation as sg

_X, _Y, _Z, _a, _b, _p = sp.symbols("X Y Z alpha beta p", real=True)
_LOCALS = {"X": _X, "Y": _Y, "Z": _Z, "alpha": _a, "beta": _b, "p": _p, "cos": sp.cos, "sin": sp.sin}


def normal_vector():
    """The unit normal of azimuth α and elevation β."""
    return sp.Matrix([sp.cos(_a) * sp.cos(_b), sp.sin(_a) * sp.cos(_b), sp.sin(_b)])


def hough_plane(inputs: dict) -> dict:
    """(9.11.1): the printed right-hand side equals n(α, β)·X with |n| = 1, and the library's
    :func:`photolib.segmentation.plane_from_angles` is that plane (checked numerically)."""
    n = normal_vector()
    if sp.trigsimp(sp.expand(n.dot(n))) != 1:
        raise AssertionError("n(α, β) is not a unit vector")
    derived = n.dot(sp.Matrix([_X, _Y, _Z]))
    printed = sp.parse_expr(inputs["printed_rhs"], local_dict=_LOCALS)
    same = sp.expand(printed - derived) == 0
    a, b, p = 0.7, -0.3, 4.2
    pl = sg.plane_from_angles(a, b, p)
    X = np.array([[1.0, 2.0, 0.0], [-3.0, 0.5, 2.0]])
    X = X - (X @ pl.normal - p)[:, None] * pl.normal              # project onto the plane
    nn = np.array([float(c) for c in n.subs({_a: a, _b: b})])
    if not np.allclose(X @ nn, p, atol=1e-12):
        raise AssertionError("photolib.segmentation.plane_from_angles disagrees with (9.11.1)")
    return {"printed_equals_derived": bool(same)}


# --- RANSAC minimal samples ------------------------------------------------------------------------
def _residuals(shape, theta, X):
    if shape == "line":                      # point p, direction d: X − p ∥ d
        return np.cross(X - theta[:3], theta[3:6]).ravel()
    if shape == "plane":                     # n·X − d
        return X @ theta[:3] - theta[3]
    if shape == "sphere":
        return np.linalg.norm(X - theta[:3], axis=1) - theta[3]
    w = X - theta[:3]                        # cylinder: axis point, axis direction, radius
    a = theta[3:6] / np.linalg.norm(theta[3:6])
    return np.linalg.norm(np.cross(w, a), axis=1) - theta[6]


def _on_shape(shape, rng, n):
    if shape == "line":
        return np.array([1.0, 2, 3, 0.3, -0.5, 0.8]), np.array([1.0, 2, 3]) + rng.uniform(-3, 3, (n, 1)) * [0.3, -0.5, 0.8]
    if shape == "plane":
        nrm = np.array([0.2, -0.4, 0.9]) / np.linalg.norm([0.2, -0.4, 0.9])
        xy = rng.uniform(-3, 3, (n, 2))
        Z = (1.5 - nrm[0] * xy[:, 0] - nrm[1] * xy[:, 1]) / nrm[2]
        return np.r_[nrm, 1.5], np.column_stack([xy, Z])
    if shape == "sphere":
        d = rng.normal(size=(n, 3))
        d /= np.linalg.norm(d, axis=1)[:, None]
        return np.array([1.0, -1, 2, 2.5]), np.array([1.0, -1, 2]) + 2.5 * d
    a = np.array([0.3, 0.1, 1.0]) / np.linalg.norm([0.3, 0.1, 1.0])
    u = np.cross(a, [1.0, 0, 0]); u /= np.linalg.norm(u)
    v = np.cross(a, u)
    t, h = rng.uniform(0, 2 * np.pi, n), rng.uniform(-2, 2, n)
    P = np.array([0.5, 0.5, 0]) + h[:, None] * a + 1.2 * (np.cos(t)[:, None] * u + np.sin(t)[:, None] * v)
    return np.r_[0.5, 0.5, 0, a, 1.2], P


def minimal_samples(inputs: dict) -> dict:
    """§9.11: 2 points fix a line, 3 a plane, 5 a cylinder (and 4 a sphere). For each shape the
    number of independent parameters (the rank of ∂v/∂θ for many points on the shape, θ an
    over-parametrisation) divided by the conditions one point imposes (the rank for one point),
    rounded up."""
    rng = np.random.default_rng(int(inputs.get("seed", 0)))
    out = {}
    for shape in ("line", "plane", "sphere", "cylinder"):
        theta, P = _on_shape(shape, rng, 40)

        def jac(points):
            h = 1e-6
            cols = []
            for k in range(len(theta)):
                e = np.zeros(len(theta)); e[k] = h
                cols.append((_residuals(shape, theta + e, points) - _residuals(shape, theta - e, points)) / (2 * h))
            return np.column_stack(cols)
        dof = np.linalg.matrix_rank(jac(P), tol=1e-6)
        per_point = np.linalg.matrix_rank(jac(P[:1]), tol=1e-6)
        out[f"{shape}_points"] = int(math.ceil(dof / per_point))
        out[f"{shape}_parameters"] = int(dof)
    return out


# --- Hough: centring and the angular step --------------------------------------------------------
def hough_centring(inputs: dict) -> dict:
    """§9.11: moving the origin to the centroid minimises the range of p (seeded cloud in map
    coordinates: the range of p over all normal directions, raw vs centred)."""
    rng = np.random.default_rng(int(inputs["seed"]))
    X = rng.uniform(0, float(inputs["size"]), (200, 3)) + np.asarray(inputs["offset"], float)
    dirs = rng.normal(size=(500, 3))
    dirs /= np.linalg.norm(dirs, axis=1)[:, None]
    raw = X @ dirs.T
    cen = (X - X.mean(axis=0)) @ dirs.T
    r_raw, r_cen = float(raw.max() - raw.min()), float(cen.max() - cen.min())
    return {"p_range": "smaller" if r_cen < r_raw else "not smaller", "p_range_raw": r_raw, "p_range_centred": r_cen}


def hough_step(inputs: dict) -> dict:
    """§9.11: a finer (α, β) step finds the plane more accurately but costs more computation
    (mean angular error of the raw Hough cell over seeded random planes, before the
    least-squares refinement; cost as the number of votes cast)."""
    rng = np.random.default_rng(int(inputs["seed"]))
    dp = float(inputs["p_step"])
    planes = []
    for _ in range(int(inputs["n_planes"])):
        n_true = rng.normal(size=3)
        n_true /= np.linalg.norm(n_true)
        u = np.cross(n_true, [1.0, 0, 0]); u /= np.linalg.norm(u)
        v = np.cross(n_true, u)
        st = rng.uniform(-5, 5, (int(inputs["n_points"]), 2))
        planes.append((n_true, st[:, :1] * u + st[:, 1:] * v + rng.normal(0, 0.002, (len(st), 1)) * n_true))
    errors, votes = [], []
    for step in inputs["steps_deg"]:
        d = math.radians(step)
        n_a, n_b = int(round(math.pi / d)), int(round(math.pi / d)) + 1
        A, B = np.meshgrid(np.arange(n_a) * math.pi / n_a, np.linspace(-math.pi / 2, math.pi / 2, n_b), indexing="ij")
        dirs = np.column_stack([(np.cos(A) * np.cos(B)).ravel(), (np.sin(A) * np.cos(B)).ravel(), np.sin(B).ravel()])
        err, cast = 0.0, 0
        for n_true, P in planes:
            k = np.floor((P - P.mean(0)) @ dirs.T / dp).astype(np.int64)   # (9.11.1) per point and cell
            k -= k.min(axis=0)
            K = int(k.max()) + 1
            acc = np.bincount((k + np.arange(len(dirs)) * K).ravel(), minlength=len(dirs) * K)
            best = int(np.argmax(acc.reshape(len(dirs), K).max(axis=1)))  # the strongest cell
            err += math.degrees(math.acos(min(1.0, abs(dirs[best] @ n_true))))
            cast += P.shape[0] * len(dirs)
        errors.append(err / len(planes))
        votes.append(cast)
    finer_better = all(errors[i + 1] < errors[i] for i in range(len(errors) - 1))
    costlier = all(votes[i + 1] > votes[i] for i in range(len(votes) - 1))
    return {"trend": "finer is more accurate and slower" if finer_better and costlier else "no such trend",
            "mean_errors_deg": [round(e, 3) for e in errors], "votes": votes}


def ransac_outliers(inputs: dict) -> dict:
    """§9.11: RANSAC estimates the shape reliably despite many points not on it (a plane with
    ``outlier_share`` uniform outliers; normal and inlier errors after least-squares refinement)."""
    rng = np.random.default_rng(int(inputs["seed"]))
    n_in = int(inputs["n_points"])
    n_out = int(round(n_in * inputs["outlier_share"] / (1 - inputs["outlier_share"])))
    xy = rng.uniform(-5, 5, (n_in, 2))
    P = np.column_stack([xy, 0.2 * xy[:, 0] + rng.normal(0, 0.01, n_in)])
    X = np.vstack([P, rng.uniform(-5, 5, (n_out, 3))])
    r = sg.ransac_shape(X, "plane", 0.03, rng=0)
    n_true = np.array([-0.2, 0, 1.0]) / np.linalg.norm([-0.2, 0, 1.0])
    err = math.degrees(math.acos(min(1.0, abs(r.model.normal @ n_true))))
    recall = float(r.inliers[:n_in].mean())
    precision = float(r.inliers[:n_in].sum() / r.n_inliers)
    ok = err < 0.2 and recall > 0.97 and precision > 0.97
    return {"estimate": "reliable" if ok else "not reliable", "normal_error_deg": err, "recall": recall,
            "precision": precision}
