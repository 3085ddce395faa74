"""Orthogonal distances of a point from a sphere and a cylinder in sympy: Chapter 9, §9.11.

The models behind the least-squares refinement of the RANSAC primitives of
:mod:`photolib.segmentation` (:func:`~photolib.segmentation.fit_sphere`,
:func:`~photolib.segmentation.fit_cylinder`); the rows of B of the correction equations
(1.8.5) are their derivatives, differentiated here by sympy instead of by hand:

* :func:`sphere_distance_model` — v = ρ − r with ρ = |X − C|: the geometric residual of a point
  X = (X, Y, Z) for the four unknowns centre C = (X_C, Y_C, Z_C) and radius r.
* :func:`cylinder_distance_model` — v = |(X − c) − ((X − c)·a) a| − r: the geometric residual for
  the five unknowns of a cylinder written about a start axis a₀ with a local frame (u, v)
  across it (a₀, u, v orthonormal): the axis m = a₀ + s·u + t·v, a = m/|m| (two direction
  increments s, t), the axis point c = c₀ + p·u + q·v (two shifts across the axis) and the
  radius r. a₀, u, v and c₀ are data, so the parametrisation has no singularity near the start
  axis (s = t = 0 gives a = a₀).

Every function returns sympy objects; nothing is lambdified at import time (the library calls
:meth:`~photolib.derivations.model.Model.compile`, cached per model).
"""

from __future__ import annotations

from functools import lru_cache

import sympy as sp

from .model import Model
from .symbols import X, Y, Z

__all__ = ["sphere_distance_model", "cylinder_distance_model"]

X_C, Y_C, Z_C, r = sp.symbols("X_C Y_C Z_C r", real=True)
s, t, p, q = sp.symbols("s t p q", real=True)
A0 = sp.symbols("a0_x a0_y a0_z", real=True)
U = sp.symbols("u_x u_y u_z", real=True)
V = sp.symbols("v_x v_y v_z", real=True)
C0 = sp.symbols("c0_x c0_y c0_z", real=True)


@lru_cache(maxsize=None)
def sphere_distance_model() -> Model:
    """v = |X − C| − r: the orthogonal distance of a point from a sphere (signed, outside > 0).

    Returns
    -------
    Model
        Parameters X_C, Y_C, Z_C, r (centre and radius); data X, Y, Z (the point).

    Raises
    ------
    InputError
        Never (the model takes no input).

    References
    ----------
    Chibunichev (2022), §9.11 (RANSAC primitives refined by least squares); §1.8,
    eqs. (1.8.3)–(1.8.5) (the correction equations).

    Examples
    --------
    >>> m = sphere_distance_model()
    >>> m.jacobian()[3]
    -1
    >>> res, jac = m.compile()
    >>> res(0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 3.0).ravel().tolist()
    [2.0]
    >>> jac(0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 3.0).ravel().tolist()
    [-0.0, -0.0, -1.0, -1.0]
    """
    rho = sp.sqrt((X - X_C) ** 2 + (Y - Y_C) ** 2 + (Z - Z_C) ** 2)
    return Model("sphere-distance", (X_C, Y_C, Z_C, r), (X, Y, Z), (rho - r,))


@lru_cache(maxsize=None)
def cylinder_distance_model() -> Model:
    """v = |(X − c) − ((X − c)·a) a| − r: the orthogonal distance of a point from a cylinder.

    The axis direction a = m/|m| with m = a₀ + s·u + t·v and the axis point
    c = c₀ + p·u + q·v, where a₀ is a start axis and (u, v) a frame across it.

    Returns
    -------
    Model
        Parameters s, t, p, q, r; data X, Y, Z (the point), then a₀, u, v, c₀ (3 components
        each, in that order).

    Raises
    ------
    InputError
        Never (the model takes no input).

    References
    ----------
    Chibunichev (2022), §9.11 (a cylinder has five parameters: two for the axis direction,
    three for the circle); §1.8, eqs. (1.8.3)–(1.8.5).

    Examples
    --------
    >>> m = cylinder_distance_model()
    >>> [str(v) for v in m.parameters]
    ['s', 't', 'p', 'q', 'r']
    >>> res, jac = m.compile()
    >>> frame = (0, 0, 1.0, 1.0, 0, 0, 0, 1.0, 0, 0, 0, 0)        # a0 = z, u = x, v = y, c0 = 0
    >>> res(0, 0, 0, 0, 2.0, 3.0, 0.0, 5.0, *frame).ravel().tolist()   # 3 from the z axis
    [1.0]
    >>> jac(0, 0, 0, 0, 2.0, 3.0, 0.0, 5.0, *frame).ravel().round(12).tolist()
    [-5.0, 0.0, -1.0, 0.0, -1.0]
    """
    Xv = sp.Matrix([X, Y, Z])
    a0, u, v, c0 = (sp.Matrix(k) for k in (A0, U, V, C0))
    m = a0 + s * u + t * v
    a = m / sp.sqrt(m.dot(m))
    c = c0 + p * u + q * v
    w = Xv - c
    perp = w - w.dot(a) * a
    return Model("cylinder-distance", (s, t, p, q, r), (X, Y, Z) + A0 + U + V + C0,
                 (sp.sqrt(perp.dot(perp)) - r,))
