"""Every public callable of the library has a numpydoc docstring with the sections a reader needs.

Functions: Parameters (when they take any), Returns, Raises, References (the book's § and
equation numbers) and Examples (run as doctests by pytest: ``--doctest-modules``). Classes:
Parameters or Attributes, References and Examples. Each module's docstring names its chapter.
"""

import importlib
import inspect
import re

import pytest

from test_bad_input_coverage import public_callables
from test_wall import core_modules, module_name

SECTION = re.compile(r"^\s*(Parameters|Returns|Yields|Raises|References|Examples|Attributes|Notes|See Also)\s*\n\s*-{3,}",
                     re.MULTILINE)


def sections(doc: str) -> set:
    return set(SECTION.findall(doc or ""))


def takes_arguments(obj) -> bool:
    try:
        params = inspect.signature(obj).parameters.values()
    except (TypeError, ValueError):
        return False
    return any(p.name not in ("self", "cls") for p in params)


PUBLIC = sorted(public_callables(), key=lambda item: item[0])


@pytest.mark.parametrize("name,obj", PUBLIC, ids=[n for n, _ in PUBLIC])
def test_public_callable_has_numpydoc_sections(name, obj):
    doc = inspect.getdoc(obj) or ""
    found = sections(doc)
    if inspect.isclass(obj):
        needed = {"References", "Examples"}
        if not ({"Parameters", "Attributes"} & found):
            needed.add("Parameters")
    else:
        needed = {"Returns", "Raises", "References", "Examples"}
        if takes_arguments(obj):
            needed.add("Parameters")
    missing = sorted(needed - found)
    assert not missing, f"{name}: docstring lacks {missing}"
    assert ">>>" in doc, f"{name}: the Examples section has no doctest"


@pytest.mark.parametrize("path", core_modules(), ids=module_name)
def test_module_docstring_names_its_place_in_the_book(path):
    module = importlib.import_module(module_name(path))
    doc = module.__doc__ or ""
    assert doc.strip(), f"{module.__name__} has no module docstring"
    if not path.name.startswith("_"):
        assert re.search(r"Chapter|§|Appendix|chapter", doc), \
            f"{module.__name__}: the module docstring does not name its chapter or sections"
