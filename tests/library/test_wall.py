"""The wall between the library and the book layer.

The library (every module of ``photolib`` outside ``photolib/book/``) never imports the book
layer (textbook reader, adapters, verify, errata, figures, command line), never imports
matplotlib and never reads ``textbook/``. Library tests (``tests/library``) never import the
book layer either. Checked twice: statically from the source (every import statement, also
those inside functions) and dynamically (every core module imports with the book layer and
matplotlib made unimportable).
"""

import ast
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
PACKAGE = ROOT / "photolib"
BOOK = PACKAGE / "book"
FORBIDDEN = ("photolib.book", "matplotlib", "mpl_toolkits",
             # the book layer's former places (moved into photolib.book)
             "photolib.textbook", "photolib.verify", "photolib.errata", "photolib.plots", "photolib.cli")


def core_modules():
    """Paths of the library's modules: everything in photolib/ outside photolib/book/."""
    return sorted(p for p in PACKAGE.rglob("*.py") if BOOK not in p.parents)


def module_name(path: Path) -> str:
    parts = list(path.relative_to(ROOT).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts = parts[:-1]
    return ".".join(parts)


def imported_names(path: Path):
    """Absolute names of every module imported anywhere in the file (relative imports resolved)."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    package = module_name(path) if path.name == "__init__.py" else module_name(path).rpartition(".")[0]
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            for alias in node.names:
                yield node.lineno, alias.name
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.split(".")
                base = base[: len(base) - (node.level - 1)]
                stem = ".".join(base + ([node.module] if node.module else []))
            else:
                stem = node.module
            yield node.lineno, stem
            for alias in node.names:                     # "from photolib import book"
                yield node.lineno, f"{stem}.{alias.name}"


def string_constants(path: Path):
    """String literals that are not docstrings (a docstring may *mention* textbook/)."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    docstrings = set()
    for node in ast.walk(tree):
        if isinstance(node, (ast.Module, ast.ClassDef, ast.FunctionDef, ast.AsyncFunctionDef)):
            body = getattr(node, "body", [])
            if body and isinstance(body[0], ast.Expr) and isinstance(body[0].value, ast.Constant):
                docstrings.add(id(body[0].value))
    for node in ast.walk(tree):
        if isinstance(node, ast.Constant) and isinstance(node.value, str) and id(node) not in docstrings:
            yield node.lineno, node.value


def test_the_core_is_not_empty_and_the_book_layer_exists():
    names = {module_name(p) for p in core_modules()}
    assert {"photolib.lsq", "photolib.rotation", "photolib.camera"} <= names
    assert (BOOK / "verify.py").is_file() and (BOOK / "textbook.py").is_file()


@pytest.mark.parametrize("path", core_modules(), ids=lambda p: module_name(p))
def test_core_module_does_not_import_the_book_layer(path):
    bad = [(line, name) for line, name in imported_names(path)
           if any(name == f or name.startswith(f + ".") for f in FORBIDDEN)]
    assert not bad, f"{path.relative_to(ROOT)} imports the book layer or matplotlib: {bad}"


@pytest.mark.parametrize("path", core_modules(), ids=lambda p: module_name(p))
def test_core_module_does_not_read_textbook(path):
    bad = [(line, text) for line, text in string_constants(path) if "textbook" in text.lower()]
    assert not bad, f"{path.relative_to(ROOT)} refers to textbook/ in code: {bad}"


@pytest.mark.parametrize("path", sorted((ROOT / "tests" / "library").glob("*.py")), ids=lambda p: p.name)
def test_library_tests_do_not_import_the_book_layer(path):
    bad = [(line, name) for line, name in imported_names(path)
           if name == "photolib.book" or name.startswith("photolib.book.")]
    assert not bad, f"tests/library/{path.name} imports the book layer: {bad}"


def test_every_core_module_imports_without_the_book_layer_and_matplotlib():
    names = [module_name(p) for p in core_modules()]
    code = ("import importlib, sys\n"
            "for blocked in ('matplotlib', 'mpl_toolkits', 'photolib.book'):\n"
            "    sys.modules[blocked] = None\n"
            f"for name in {names!r}:\n"
            "    importlib.import_module(name)\n"
            "leaked = sorted(m for m in sys.modules if m.startswith(('photolib.book', 'matplotlib'))"
            " and sys.modules[m] is not None)\n"
            "assert not leaked, leaked\n")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT, timeout=600)
    assert done.returncode == 0, done.stderr[-3000:]
