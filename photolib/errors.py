"""Exceptions and warnings raised by photolib — shared by every chapter (Chapters 1–4 and the appendices).

Every failure names its cause: bad input (NaN, wrong shapes, too few points), a degenerate
geometry that makes a problem singular (collinear control in a resection, §1.8; parallel rays
in an intersection, §2.4; a datum defect in a block, §3.5), a point behind a camera, or an
iteration that did not converge (the least-squares engine of §1.8, (1.8.5)–(1.8.10)).
Callers react to the class, never to the message text.
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
