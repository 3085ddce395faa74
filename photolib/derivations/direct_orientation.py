"""Sympy model of the boresight-misalignment calibration of a GNSS/IMU-equipped frame camera.

Hanzl, §7.3 (seed 002, lines 1332–1356): the basic calibration model has six unknowns, three
GNSS shifts and three misalignment angles (boresight misalignment, BSMA), found by comparing the
directly measured exterior orientation with the photogrammetric one. Written here as collinearity
equations of control points whose exterior orientation is the GNSS/IMU one corrected by the six
unknowns:

* projection centre S = R_GNSS + d (d = (dX, dY, dZ), object frame);
* attitude A = A_IMU · A_b(Δω, Δα, Δκ), A_b = A_ω A_α A_κ of (1.3.2) (Chibunichev 2022,
  camera → IMU; compare the boresight of §3.5/§8.14 and (9.8.3) of the mobile-mapping model
  :func:`photolib.derivations.lidar.mobile_mapping_model`);
* image point x = −f·u/w, y = −f·v/w with (u, v, w) = Aᵀ(X − S) (the collinearity equations
  (1.8.1) in the form used by :func:`photolib.lidar.scanner_camera_project`).

The numeric functions are lambdified once (``functools.lru_cache``), as in
:mod:`photolib.derivations.lidar`.
"""

from __future__ import annotations

from functools import lru_cache

import sympy as sp

from .model import _lambdified_parts
from .rotation import rotation_matrix_symbolic

__all__ = ["BORESIGHT_PARAMETERS", "boresight_model", "boresight_functions"]

BORESIGHT_PARAMETERS = ("dX", "dY", "dZ", "d_omega", "d_alpha", "d_kappa")
"""Names of the six unknowns of the Hanzl §7.3 boresight calibration (3 GNSS shifts + 3 angles)."""


def boresight_model():
    """Collinearity of a control point with the GNSS/IMU pose corrected by the 6 calibration unknowns.

    Returns
    -------
    dict
        ``parameters`` (dX, dY, dZ, Δω, Δα, Δκ), ``data`` (R_GNSS 3, A_IMU 9 row-major, X 3, f,
        x, y), ``residual`` (2×1: model − measured image coordinates) and ``jacobian`` (2×6).

    Raises
    ------
    None
        Builds a fixed model; takes no input.

    References
    ----------
    Hanzl, §7.3 (seed 002 lines 1350–1352: 6-parameter model, 3 GPS shifts + 3 angles);
    Chibunichev (2022), eqs. (1.3.2), (1.8.1), §3.5 and §8.14 (boresight).

    Examples
    --------
    >>> m = boresight_model()
    >>> m["jacobian"].shape
    (2, 6)
    """
    d = sp.Matrix(sp.symbols("dX dY dZ", real=True))
    dw, da, dk = sp.symbols("d_omega d_alpha d_kappa", real=True)
    gnss = sp.Matrix(sp.symbols("G_X G_Y G_Z", real=True))
    a = sp.symbols("a11 a12 a13 a21 a22 a23 a31 a32 a33", real=True)
    A_imu = sp.Matrix(3, 3, a)
    X = sp.Matrix(sp.symbols("X Y Z", real=True))
    f, x, y = sp.symbols("f x y", real=True)
    A = A_imu * rotation_matrix_symbolic("wak", dw, da, dk)
    u = A.T * (X - gnss - d)
    residual = sp.Matrix([-f * u[0] / u[2] - x, -f * u[1] / u[2] - y])
    params = (*d, dw, da, dk)
    return {"parameters": params, "data": (*gnss, *a, *X, f, x, y), "residual": residual,
            "jacobian": residual.jacobian(params)}


@lru_cache(maxsize=None)
def boresight_functions():
    """Lambdified residual (2 arrays) and Jacobian (12 arrays, row-major 2×6) of :func:`boresight_model`.

    Returns
    -------
    tuple of callables
        ``(residual, jacobian)`` of ``(*parameters, *data)``.

    Raises
    ------
    None
        Builds a fixed model; takes no input.

    References
    ----------
    Hanzl, §7.3 (seed 002 lines 1350–1352).

    Examples
    --------
    >>> r, J = boresight_functions()
    >>> eye = [1, 0, 0, 0, 1, 0, 0, 0, 1]
    >>> [float(v) for v in r(*([0.0] * 6), 0, 0, 1000.0, *eye, 100.0, 0, 0.0, 100.0, 0, 0)]
    [10.0, 0.0]
    """
    return _lambdified_parts(boresight_model())
