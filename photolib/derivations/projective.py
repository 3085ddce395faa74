"""The plane-to-plane projective transformation (homography): Chapter 1, §1.7, eq. (1.7.5); Chapter 4, §4.1, eq. (4.1.7).
"""

from __future__ import annotations

from functools import lru_cache

from .model import Model
from .symbols import H_SYMBOLS, x, x_t, y, y_t

__all__ = ["homography_model"]


@lru_cache(maxsize=None)
def homography_model() -> Model:
    """Plane-to-plane projective transformation with h₃₃ = 1 (8 parameters, cf. (1.7.5) and (4.1.7)).

    F_x = (h₁x + h₂y + h₃)/(h₇x + h₈y + 1) − x_t, F_y = (h₄x + h₅y + h₆)/(h₇x + h₈y + 1) − y_t.
    Used by :func:`photolib.projective.homography_lsq`.

    Returns
    -------
    Model
        Parameters h₁…h₈; data (x, y, x_t, y_t): source point and its measured image.

    Raises
    ------
    InputError
        Never (no input).

    References
    ----------
    Chibunichev (2022), §1.7, eq. (1.7.5); §4.1, eq. (4.1.7).

    Examples
    --------
    >>> res, jac = homography_model().compile()
    >>> res(1, 0, 0, 0, 1, 0, 0, 0, 2.0, 3.0, 2.0, 3.0).ravel().tolist()   # the identity
    [0.0, 0.0]
    """
    h1, h2, h3, h4, h5, h6, h7, h8 = H_SYMBOLS
    w = h7 * x + h8 * y + 1
    return Model("homography", tuple(H_SYMBOLS), (x, y, x_t, y_t),
                 ((h1 * x + h2 * y + h3) / w - x_t, (h4 * x + h5 * y + h6) / w - y_t))
