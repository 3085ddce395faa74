"""The bad-input catalogue: every public function of the library, given bad input, must either
raise a *named* photolib error or return a correct result; never a generic numpy/Python error
and never a silent wrong answer.

Each ``tests/library/test_bad_input_<area>.py`` holds a list ``CASES`` of :class:`Case` and runs
them with :func:`check_case`; ``test_bad_input_coverage.py`` checks that every public callable of
the library (every name in a core module's ``__all__``) appears in some case or in the short
list of exemptions there, each with its reason.

A case names the function, the arguments, the error class expected (a subclass of
:class:`photolib.errors.PhotolibError`) and optionally a regular expression the message must
match. A case that should *succeed* (the correct result for a tricky input) gives ``check``, a
function of the result that returns True when the result is right.
"""

from __future__ import annotations

import re
import warnings
from dataclasses import dataclass, field
from typing import Any, Callable

import numpy as np

from photolib.errors import PhotolibError

NAN = float("nan")
INF = float("inf")


@dataclass
class Case:
    """One bad input for one public function."""

    function: Callable
    args: tuple = ()
    kwargs: dict = field(default_factory=dict)
    raises: type | None = PhotolibError      # the error class expected; None: must succeed
    match: str | None = None                 # a regex the message must contain
    check: Callable[[Any], bool] | None = None  # for cases that must succeed: is the result right?
    warns: type | None = None                # a warning class that must be issued
    why: str = ""                            # what is wrong with the input, in words

    @property
    def id(self) -> str:
        name = getattr(self.function, "__qualname__", repr(self.function))
        return f"{name}: {self.why}" if self.why else name


def check_case(case: Case):
    """Run one case; fail on a generic error, a wrong error class, or a silent result."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            result = case.function(*case.args, **case.kwargs)
        except PhotolibError as exc:
            if case.raises is None:
                raise AssertionError(f"{case.id}: expected a result, got {type(exc).__name__}: {exc}") from exc
            assert isinstance(exc, case.raises), \
                f"{case.id}: expected {case.raises.__name__}, got {type(exc).__name__}: {exc}"
            assert str(exc).strip(), f"{case.id}: the error has no message"
            if case.match:
                assert re.search(case.match, str(exc), re.IGNORECASE), \
                    f"{case.id}: message {str(exc)!r} does not match {case.match!r}"
            return
        except Exception as exc:  # noqa: BLE001 — the point of the catalogue
            raise AssertionError(f"{case.id}: a generic {type(exc).__name__} instead of a named "
                                 f"photolib error: {exc}") from exc
    if case.warns is not None:
        assert any(issubclass(w.category, case.warns) for w in caught), \
            f"{case.id}: no {case.warns.__name__} was issued"
    if case.raises is not None:
        raise AssertionError(f"{case.id}: silent result {_short(result)} instead of "
                             f"{case.raises.__name__}")
    if case.check is not None:
        assert case.check(result), f"{case.id}: the result {_short(result)} is wrong"


def _short(value) -> str:
    text = repr(value)
    return text if len(text) < 200 else text[:200] + "…"


def finite(result) -> bool:
    """True if every number in the result (array, float, tuple of those) is finite."""
    try:
        return bool(np.all(np.isfinite(np.asarray(result, dtype=float))))
    except (TypeError, ValueError):
        return False
