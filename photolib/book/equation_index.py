"""The equation → code index: every equation number of the textbook with the library functions
that implement it.

The book's equation numbers are data (``textbook/equations.toml``, taken once from the seed); the
implementations are found in the library's own docstrings, which cite the equations they implement
(``(1.8.2)``, or a range ``(11.6.1)–(11.6.7)``). Nothing is listed by hand, so the index stays
true as the library grows, and a docstring citing a number the book does not have is caught by the
tests.
"""

from __future__ import annotations

import importlib
import inspect
import pkgutil
import re
import tomllib
from dataclasses import dataclass
from functools import lru_cache

from .textbook import textbook_dir

_NUMBER = r"((?:[1-9]|1[01])\.\d{1,2}\.\d{1,2})"
_CITATION = re.compile(r"\(" + _NUMBER + r"\)(?:\s*[–-]\s*\(" + _NUMBER + r"\))?")


@dataclass(frozen=True)
class BookEquation:
    """An equation number of the book and where the seed prints it (or, if the OCR lost it, cites it)."""

    number: str
    line: int | None
    cited: int | None = None
    unnumbered: bool = False          # printed without a number; photolib gives it this one

    @property
    def key(self) -> tuple:
        return tuple(int(p) for p in self.number.split("."))


@lru_cache(maxsize=None)
def book_equations() -> tuple[BookEquation, ...]:
    """Every equation number of the textbook, in the book's order."""
    raw = tomllib.loads((textbook_dir() / "equations.toml").read_text(encoding="utf-8"))
    equations = [BookEquation(e["number"], e.get("line"), e.get("cited"), e.get("unnumbered", False))
                 for e in raw["equation"]]
    return tuple(sorted(equations, key=lambda e: e.key))


def cited_numbers(text: str) -> set[str]:
    """The equation numbers a text cites; a range ``(a.b.c)–(a.b.d)`` of one section is expanded.

    >>> sorted(cited_numbers("eqs. (11.6.1)–(11.6.3) and (1.8.2)"), key=lambda n: n.split("."))
    ['1.8.2', '11.6.1', '11.6.2', '11.6.3']
    """
    found = set()
    for m in _CITATION.finditer(text or ""):
        first, last = m.group(1), m.group(2)
        found.add(first)
        if last:
            a, b = first.rsplit(".", 1), last.rsplit(".", 1)
            if a[0] == b[0] and int(a[1]) < int(b[1]):
                found.update(f"{a[0]}.{k}" for k in range(int(a[1]), int(b[1]) + 1))
            else:
                found.add(last)
    return found


def _library_modules():
    import photolib
    for info in pkgutil.walk_packages(photolib.__path__, "photolib."):
        name = info.name
        if name.startswith("photolib.book") or any(part.startswith("_") for part in name.split(".")[1:]):
            continue
        yield importlib.import_module(name)


def _documented(obj):
    """The docstrings of a public function or class (with its public methods and properties)."""
    yield inspect.getdoc(obj) or ""
    if inspect.isclass(obj):
        for attr, member in vars(obj).items():
            if not attr.startswith("_"):
                member = getattr(member, "fget", None) or getattr(member, "__func__", member)
                yield inspect.getdoc(member) or ""


@lru_cache(maxsize=None)
def code_citations() -> dict[str, tuple[str, ...]]:
    """{equation number: the public library objects whose docstrings cite it}."""
    index: dict[str, set[str]] = {}
    for module in _library_modules():
        for attr in getattr(module, "__all__", []):
            obj = getattr(module, attr)
            if not (inspect.isfunction(obj) or inspect.isclass(obj)) or obj.__module__ != module.__name__:
                continue
            for number in set().union(*(cited_numbers(doc) for doc in _documented(obj))):
                index.setdefault(number, set()).add(f"{module.__name__}.{attr}")
    return {number: tuple(sorted(names)) for number, names in index.items()}


def index_rows(chapter: int | None = None) -> list[dict]:
    """One row per equation of the book (of one chapter): number, seed line, implementing objects."""
    cited = code_citations()
    rows = []
    for eq in book_equations():
        if chapter is not None and eq.key[0] != chapter:
            continue
        rows.append({"equation": f"({eq.number})", "line": eq.line, "cited_at": eq.cited,
                     "unnumbered": eq.unnumbered, "implemented_by": cited.get(eq.number, ())})
    return rows


def unknown_citations() -> dict[str, tuple[str, ...]]:
    """Numbers cited by library docstrings that the book does not have (typos, or another source's)."""
    known = {eq.number for eq in book_equations()}
    return {n: names for n, names in code_citations().items() if n not in known}


def coverage(chapter: int | None = None) -> tuple[int, int]:
    """(equations cited by some library object, equations in the book), overall or for a chapter."""
    rows = index_rows(chapter)
    return sum(bool(r["implemented_by"]) for r in rows), len(rows)


def index_table(chapter: int):
    """The index of one chapter as a table for the notebook."""
    from .verify import Table
    body = []
    for r in index_rows(chapter):
        where = (f"{r['line']} (unnumbered in the book)" if r["unnumbered"] else str(r["line"]) if r["line"]
                 else f"number lost in the OCR (cited at {r['cited_at']})")
        names = ", ".join(n.removeprefix("photolib.") for n in r["implemented_by"]) or "—"
        body.append([r["equation"], where, names])
    done, total = coverage(chapter)
    return Table(["equation", "seed line", "implemented by"], body,
                 f"Chapter {chapter}: {done} of {total} equations cited by the library")
