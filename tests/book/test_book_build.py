"""The book builds, API reference included, with zero warnings (as the README's main job does)."""

import importlib.util
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


@pytest.mark.skipif(importlib.util.find_spec("jupyter_book") is None,
                    reason="Jupyter Book is not installed (it comes with the `book` and `test` extras)")
def test_book_builds_without_warnings(tmp_path):
    done = subprocess.run([str(Path(sys.executable).with_name("jupyter-book")), "build", str(ROOT), "--path-output", str(tmp_path),
                           "--warningiserror", "--keep-going"],
                          capture_output=True, text=True, timeout=1200)
    warnings = [line for line in (done.stdout + done.stderr).splitlines() if "WARNING" in line or "ERROR" in line]
    assert done.returncode == 0 and not warnings, "\n".join(warnings[:40]) or done.stderr[-3000:]
    html = tmp_path / "_build" / "html"
    assert (html / "chapters" / "api.html").is_file()
    assert (html / "chapters" / "api" / "photolib.lsq.html").is_file()
    # Formulas typeset offline: MathJax is served from the book itself, never from a CDN.
    mathjax = html / "_static" / "mathjax" / "tex-chtml.js"
    assert mathjax.is_file(), "MathJax was not copied into the built book"
    assert (html / "_static" / "mathjax" / "output" / "chtml" / "fonts" / "woff-v2").is_dir()
    page = (html / "chapters" / "ch01_single_image.html").read_text(encoding="utf-8")
    assert "_static/mathjax/tex-chtml.js" in page
    assert "cdn.jsdelivr.net/npm/mathjax" not in page and "mathjax@" not in page
