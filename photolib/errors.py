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


class PointBehindCameraError(DegenerateGeometryError):
    """A point lies behind (or in the plane of) a camera that is supposed to see it.

    ``points`` holds the indices of the offending points (or observations) where known, so that
    a caller can react to the condition itself instead of matching the message text.
    """

    def __init__(self, message, points=None):
        super().__init__(message)
        self.points = [] if points is None else list(points)


class DegreesWarning(UserWarning):
    """An angle larger than 2π in magnitude was passed where radians are expected."""


__all__ = ["PhotolibError", "InputError", "DegenerateGeometryError", "ConvergenceError",
           "PointBehindCameraError", "DegreesWarning"]
