"""Shared input validation of the library's public functions.

The checks that several modules (Chapters 5 and 6: epipolar geometry, surfaces, targets, matching,
interest operators, RANSAC, SGM, DTMs, the MRF relaxation) made alike: a finite number, an
integer with a lower bound, an odd window size, a finite 2-D image of a least size. Each raises
:class:`~photolib.errors.InputError`. The messages are templates (``str.format`` fields named in
each function) so that every caller keeps the wording its tests and users know; the defaults are
the wording most callers share.

Private: nothing here is public API (``__all__`` is empty); this module imports only numpy and
:mod:`photolib.errors`.
"""

from __future__ import annotations

import numpy as np

from .errors import InputError

__all__ = []

_NOT_A_NUMBER = "{name} must be a number, got {value!r}"
_NOT_AN_INTEGER = "{name} must be an integer ≥ {minimum}, got {value!r}"
_NOT_FINITE_PIXELS = "{name} contains NaN or inf pixels"


def number(value, name, positive=False, *, allow_zero=False, not_a_number=_NOT_A_NUMBER, out_of_range=None):
    """``float(value)``, finite; with ``positive`` also > 0 (≥ 0 with ``allow_zero``).

    Templates: ``not_a_number`` when ``float()`` refuses the value, ``out_of_range`` when it is
    not finite or breaks the sign condition (default "{name} must be a finite [positive] number,
    got {value!r}"); fields ``name``, ``value`` (as given) and ``v`` (as a float).
    """
    try:
        v = float(value)
    except (TypeError, ValueError) as exc:
        raise InputError(not_a_number.format(name=name, value=value)) from exc
    if not np.isfinite(v) or (positive and (v < 0 or (v == 0 and not allow_zero))):
        if out_of_range is None:
            out_of_range = "{name} must be a finite" + (" positive" if positive else "") + " number, got {value!r}"
        raise InputError(out_of_range.format(name=name, value=value, v=v))
    return v


def integer(value, name, minimum=1, *, odd=False, message=_NOT_AN_INTEGER, too_small=None):
    """``value`` as an int: a Python or numpy integer (not a bool) ≥ ``minimum``, odd if ``odd``.

    Templates: ``message`` for a value that is no integer, ``too_small`` (default: ``message``) for
    one below ``minimum`` or even where ``odd``; fields ``name``, ``value`` and ``minimum``.
    """
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)):
        raise InputError(message.format(name=name, value=value, minimum=minimum))
    if value < minimum or (odd and value % 2 == 0):
        raise InputError((message if too_small is None else too_small).format(name=name, value=value,
                                                                               minimum=minimum))
    return int(value)


def odd_integer(value, name="window", minimum=3):
    """An odd integer ≥ ``minimum``, such as a window size (the message names ``name``)."""
    return integer(value, name, minimum, odd=True,
                   message="{name} must be an odd integer ≥ {minimum}, got {value!r}",
                   too_small="{name} must be an odd integer ≥ {minimum}, got {value}")


def image(value, name, min_size=1, *, messages, reject=(str, bytes, type(None))):
    """A finite 2-D float array with at least ``min_size`` rows and columns.

    ``reject``: types refused before conversion. ``messages``: templates keyed by the failure —
    ``"type"`` (a rejected type; field ``type``), ``"numeric"`` (numpy cannot make floats of it;
    field ``exc``), ``"ndim"`` (not 2-D; fields ``ndim``, ``shape``), ``"small"`` (a side below
    ``min_size``; fields ``shape``, ``min_size``) and optionally ``"finite"`` (NaN or inf; default
    "{name} contains NaN or inf pixels"); every template may use ``name``.
    """
    if isinstance(value, reject):
        raise InputError(messages["type"].format(name=name, type=type(value).__name__))
    try:
        arr = np.asarray(value, dtype=float)
    except (TypeError, ValueError) as exc:
        raise InputError(messages["numeric"].format(name=name, exc=exc)) from exc
    if arr.ndim != 2:
        raise InputError(messages["ndim"].format(name=name, ndim=arr.ndim, shape=arr.shape))
    if min(arr.shape) < min_size:
        raise InputError(messages["small"].format(name=name, shape=arr.shape, min_size=min_size))
    if not np.all(np.isfinite(arr)):
        raise InputError(messages.get("finite", _NOT_FINITE_PIXELS).format(name=name))
    return arr


def positive_scalar(arr, value, name, *, allow_zero=False, message):
    """``float(arr)`` for a 0-d array ``arr`` (already converted from ``value``) that is > 0 (≥ 0 with
    ``allow_zero``); otherwise :class:`InputError` from ``message`` (fields ``name``, ``value``)."""
    if arr.ndim != 0 or not (arr >= 0 if allow_zero else arr > 0):
        raise InputError(message.format(name=name, value=value))
    return float(arr)
