"""Every public callable of the library is in the bad-input catalogue (or exempt, with a reason).

The public API of a core module is its ``__all__``; each module must define one. The catalogue is
the union of ``CASES`` over ``tests/library/test_bad_input_*.py``.
"""

import importlib
import inspect
from pathlib import Path

import pytest

from test_wall import core_modules, module_name

HERE = Path(__file__).resolve().parent

# Public callables that take no input that could be bad, with the reason.
EXEMPT = {
    "photolib.errors": "exception and warning classes",
}


def catalogue_functions():
    covered = set()
    for path in sorted(HERE.glob("test_bad_input_*.py")):
        if path.name == Path(__file__).name:
            continue
        module = importlib.import_module(path.stem)
        for case in getattr(module, "CASES", []):
            fn = case.function
            covered.add(getattr(fn, "__func__", fn))
            owner = getattr(fn, "__self__", None)          # a classmethod: count its class too
            if isinstance(owner, type):
                covered.add(owner)
    return covered


def public_callables():
    for path in core_modules():
        name = module_name(path)
        if path.name.startswith("_") and path.name != "__init__.py":
            continue                                       # private modules (generated code)
        if name in EXEMPT or name == "photolib":
            continue
        module = importlib.import_module(name)
        for attr in getattr(module, "__all__", []):
            obj = getattr(module, attr)
            if inspect.isclass(obj) and issubclass(obj, BaseException):
                continue
            if callable(obj) and getattr(obj, "__module__", "") == name:
                yield f"{name}.{attr}", obj


@pytest.mark.parametrize("path", [p for p in core_modules() if not p.name.startswith("_")],
                         ids=module_name)
def test_every_core_module_declares_its_public_api(path):
    module = importlib.import_module(module_name(path))
    assert hasattr(module, "__all__"), f"{module.__name__} has no __all__"
    missing = [n for n in module.__all__ if not hasattr(module, n)]
    assert not missing, f"{module.__name__}.__all__ names missing objects: {missing}"


def test_every_public_callable_is_in_the_catalogue():
    covered = catalogue_functions()
    missing = sorted(name for name, obj in public_callables()
                     if obj not in covered and name.rpartition(".")[0] not in EXEMPT)
    assert not missing, f"{len(missing)} public callables have no bad-input case: {missing}"
