"""Forward intersection of rays by least squares: Chapter 2, §2.4 (with the collinearity equations (1.8.2)).
"""

from __future__ import annotations

from functools import lru_cache

from .collinearity import collinearity_model
from .model import Model
from .symbols import EO_SYMBOLS, X, Y, Z, f, x, x0, y, y0

__all__ = ["intersection_model"]


@lru_cache(maxsize=None)
def intersection_model(order: str = "kaw") -> Model:
    """Collinearity equations (1.8.2) with the object point (X, Y, Z) as the unknowns.

    The residuals are F_x, F_y of :func:`collinearity_model`; the data are the exterior
    orientation of the image and the measured (x, y) with f, x₀, y₀. Used for the
    least-squares forward intersection of two or more rays (§2.4).

    Parameters
    ----------
    order : {"kaw", "wak"}, optional
        Rotation sequence.

    Returns
    -------
    Model
        Parameters X, Y, Z; data X_S, Y_S, Z_S, ω, α, κ, x, y, f, x₀, y₀.

    Raises
    ------
    InputError
        If ``order`` is unknown.

    References
    ----------
    Chibunichev (2022), §2.4; §1.8, eq. (1.8.2).

    Examples
    --------
    >>> [str(p) for p in intersection_model("kaw").parameters]
    ['X', 'Y', 'Z']
    """
    F_x, F_y = collinearity_model(order).residuals
    return Model(f"intersection-{order}", (X, Y, Z), EO_SYMBOLS + (x, y, f, x0, y0), (F_x, F_y))
