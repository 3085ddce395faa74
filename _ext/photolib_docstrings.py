"""Sphinx extension for the API reference: docstrings write |x| for absolute values and norms.

reStructuredText reads ``|text|`` as a substitution reference; in the library's docstrings it is
mathematics (|w|, |q|², |S₂ − S₁|). Escape the bars outside inline literals and doctest blocks
before the docstring is parsed.
"""

import re

LITERAL = re.compile(r"(``.*?``)")


def _escape_bars(line: str) -> str:
    parts = LITERAL.split(line)
    return "".join(p if p.startswith("``") else p.replace("|", r"\|") for p in parts)


def escape_absolute_value_bars(app, what, name, obj, options, lines):
    in_doctest = False
    for i, line in enumerate(lines):
        stripped = line.lstrip()
        if stripped.startswith(">>>"):
            in_doctest = True
        elif not stripped:
            in_doctest = False
        if in_doctest or "|" not in line or stripped.startswith(("+-", "|=")):
            continue
        lines[i] = _escape_bars(line)


def setup(app):
    app.connect("autodoc-process-docstring", escape_absolute_value_bars, priority=400)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
