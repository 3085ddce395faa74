"""Exceptions raised by photolib.

Every failure names its cause: bad input (NaN, wrong shapes, too few points), a degenerate
geometry that makes a problem singular, or an iteration that did not converge.
"""


class PhotolibError(Exception):
    """Base class of all photolib errors."""


class InputError(PhotolibError, ValueError):
    """The input is malformed: wrong shape, NaN/inf, too few points, an unknown option."""


class DegenerateGeometryError(PhotolibError, ValueError):
    """The geometry leaves the problem singular (collinear or coplanar points, parallel rays...)."""


class ConvergenceError(PhotolibError, RuntimeError):
    """An iterative solution did not converge; ``history`` holds the iterations made."""

    def __init__(self, message, history=None):
        super().__init__(message)
        self.history = history or []
