"""Sympy models of the plane transformations of Hanzl's §2.5 that are not linear in their parameters.

* :func:`congruent_model` — the congruent (rigid, 3-parameter) transformation, lines 265–267.

The linear ones (similarity in a = q cos α, b = q sin α, affine, bilinear, second-degree
polynomial) are solved directly by :func:`photolib.lsq.solve_normal_equations`; the projective
one by :mod:`photolib.derivations.projective`.
"""

from __future__ import annotations

from functools import lru_cache

import sympy as sp

from .model import Model

__all__ = ["congruent_model"]


@lru_cache(maxsize=None)
def congruent_model():
    """Sympy model of the congruent (3-parameter) transformation, Hanzl §2.5, lines 265–267.

    F_x = cos α·x̄ − sin α·ȳ + t_x − x, F_y = sin α·x̄ + cos α·ȳ + t_y − y; the Jacobian used by
    :func:`photolib.plane_transforms.fit_plane_transform` comes from :meth:`photolib.derivations.model.Model.jacobian`.

    Returns
    -------
    photolib.derivations.model.Model
        Parameters α, t_x, t_y; data x̄, ȳ, x, y.

    Raises
    ------
    InputError
        Never (no input).

    References
    ----------
    Hanzl, §2.5, lines 265–267.

    Examples
    --------
    >>> res, jac = congruent_model().compile()
    >>> res(0.0, 1.0, 2.0, 3.0, 4.0, 4.0, 6.0).ravel().tolist()
    [0.0, 0.0]
    """
    alpha, tx, ty, xb, yb, x, y = sp.symbols("alpha t_x t_y xbar ybar x_obs y_obs", real=True)
    return Model("plane-congruent", (alpha, tx, ty), (xb, yb, x, y),
                 (sp.cos(alpha) * xb - sp.sin(alpha) * yb + tx - x,
                  sp.sin(alpha) * xb + sp.cos(alpha) * yb + ty - y))
