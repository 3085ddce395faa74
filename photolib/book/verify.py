"""Recompute every published number of ``textbook/`` and check its recorded status.

Used three ways, always through :func:`check_example` / :func:`check_formula`:
``photolib verify`` (the command line), the test-suite (one test per entry) and the notebooks
(:func:`example_table` prints the book · computed · status table that ends each example).

Status rules (see ``textbook/README.md``):

* ``reproduced`` — the computed value rounded to the printed decimals equals the printed value.
* ``input-rounding`` — it does not, but ``|computed − printed|`` ≤ the recorded bound.
* ``erratum`` — it does not, and the computed value equals the recorded correct one; if the
  entry says ``as_printed = true`` the example's "as printed" computation must reproduce the
  printed value.
* ``transcription`` — the same check as ``erratum``, for a number or formula that the OCR
  transcription of the source lost or garbled while the book itself is (most likely) right.
* ``not-reproducible`` — the book lacks the data; the check is that no computation claims it.
* ``transcribed`` — data only (specifications); the value is shown, nothing to compute.
"""

from __future__ import annotations

import importlib
import math
import multiprocessing
import os
import re
from dataclasses import dataclass

from .textbook import WRONG_STATUSES, Example, Formula, available_chapters, load_chapter


def resolve(target: str):
    """Import ``"package.module:function"``."""
    module, _, name = target.partition(":")
    return getattr(importlib.import_module(module), name)


@dataclass
class Row:
    """One line of the verification report."""

    chapter: int
    example: str
    quantity: str
    book: str
    computed: str
    status: str
    ok: bool
    detail: str = ""
    as_printed: str = ""
    # The same facts as numbers, for machines (``photolib verify --json``) and for the explanation
    # of a changed status: the printed value, the computed one, the unit, the tolerance of the
    # check (half a unit of the last printed decimal, or the input-rounding bound), the value an
    # erratum expects instead of the printed one, and the recorded reason or diagnosis.
    book_value: object = None
    computed_value: object = None
    unit: str = ""
    tolerance: float | None = None
    expected: object = None
    reason: str = ""
    observed_status: str = ""         # the status the computation supports now (equal to ``status`` when ok)
    delta: float | None = None        # computed − book, for numbers

    def __post_init__(self):
        self.ok = bool(self.ok)          # comparisons of numpy values give numpy.bool_
        self.computed_value = _plain(self.computed_value)
        if self.delta is None and _is_number(self.book_value) and _is_number(self.computed_value):
            self.delta = self.computed_value - self.book_value
        if not self.observed_status:
            self.observed_status = self.status if self.ok else "changed"

    def as_dict(self) -> dict:
        return dict(self.__dict__)

    def explain(self) -> str:
        """Why the recorded status no longer holds, in one paragraph (empty when it holds)."""
        if self.ok:
            return ""
        if self.book == "printed formula":
            return f"recorded {self.status}, but the printed formula now {self.computed.replace('equals', 'equals the')}."
        if self.detail == "nothing computed for this quantity":
            return f"recorded {self.status}, but nothing was computed for this quantity."
        unit = f" {self.unit}" if self.unit else ""
        facts = [f"recorded {self.status}, now {self.observed_status}", f"book {self.book}{unit}",
                 f"computed {self.computed}{unit}"]
        if _is_number(self.book_value) and _is_number(self.computed_value):
            facts.append(f"difference {self.computed_value - self.book_value:+.3g}")
        if self.tolerance is not None:
            facts.append(f"tolerance {self.tolerance:g}")
        if self.detail == "now reproduces":
            verdict = "the computed value now rounds to the printed one: record it as reproduced"
        elif self.status == "reproduced":
            verdict = "the computed value no longer rounds to the printed one"
        elif self.status == "input-rounding":
            verdict = "the difference exceeds the recorded bound"
        elif self.status in WRONG_STATUSES:
            verdict = f"the computed value no longer rounds to the recorded correct value {self.expected}"
        else:
            verdict = "the transcribed value differs from the computed one"
        reason = f" Recorded reason: {self.reason}" if self.reason else ""
        return ", ".join(facts) + f" — {verdict}.{reason}"


def _plain(value):
    """numpy scalars as Python numbers (JSON and comparisons); other values unchanged."""
    if hasattr(value, "item") and getattr(value, "shape", None) == ():
        return value.item()
    return value


def _is_number(value) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool)


def format_value(value, decimals) -> str:
    if value is None:
        return "—"
    if isinstance(value, bool):
        return "yes" if value else "no"
    if _is_number(value):
        if decimals is None:
            return f"{value:g}"
        if decimals == 0 and abs(value - round(value)) < 1e-9:
            return str(int(round(value)))
        shown = max(decimals + 2, 0)
        return f"{round(value, shown) + 0.0:.{shown}f}"
    return str(value)


def matches_printed(computed, printed, decimals) -> bool:
    """True if ``computed`` rounded to ``decimals`` gives ``printed`` (texts must be equal)."""
    if computed is None:
        return False
    if _is_number(printed):
        if not _is_number(computed) or not math.isfinite(computed):
            return False
        half = 0.5 * 10.0 ** (-(decimals or 0))
        return abs(computed - printed) <= half * (1 + 1e-9) + 1e-12
    return computed == printed


def check_example(example: Example) -> list[Row]:
    """Recompute an example and judge each of its quantities against its recorded status."""
    computed = resolve(example.compute)(example.inputs) if example.compute else {}
    as_printed = resolve(example.as_printed_compute)(example.inputs) if example.as_printed_compute else {}
    rows = []
    for q in example.quantities:
        value = computed.get(q.name)
        printed_run = as_printed.get(q.name)
        same = matches_printed(value, q.value, q.decimals)
        detail = ""
        tolerance = 0.5 * 10.0 ** (-(q.decimals or 0)) if _is_number(q.value) else None
        if q.status == "reproduced":
            ok = same
        elif q.status == "input-rounding":
            ok = (not same) and _is_number(value) and abs(value - q.value) <= q.bound
            detail = f"bound {q.bound}"
            tolerance = q.bound
        elif q.status in WRONG_STATUSES:
            right = matches_printed(value, q.correct, q.correct_decimals if q.correct_decimals is not None else q.decimals)
            ok = (not same) and right
            if q.as_printed:
                ok = ok and matches_printed(printed_run, q.value, q.decimals)
            shown = q.correct_decimals if q.correct_decimals is not None else q.decimals
            detail = f"correct {q.correct:.{shown}f}" if _is_number(q.correct) and shown is not None \
                else f"correct {q.correct}"
        elif q.status == "not-reproducible":
            ok = not same
        else:  # transcribed
            ok = value is None or same
        if not ok and value is None and q.status != "transcribed":
            detail = "nothing computed for this quantity"
        elif not ok and same and q.status in ("input-rounding", *WRONG_STATUSES, "not-reproducible"):
            detail = "now reproduces"
        observed = q.status if ok else _observed_status(value, q, same)
        rows.append(Row(example.chapter, example.id, q.name, q.printed, format_value(value, q.decimals),
                        q.status, ok, detail, format_value(printed_run, q.decimals) if printed_run is not None else "",
                        book_value=q.value, computed_value=value if _is_number(_plain(value)) or isinstance(value, str)
                        else None, unit=q.unit, tolerance=tolerance,
                        expected=q.correct if q.status in WRONG_STATUSES else None,
                        reason=q.diagnosis or q.reason, observed_status=observed))
    return rows


def _observed_status(value, q, same: bool) -> str:
    """The status that the computed value supports, whatever was recorded (for a changed row)."""
    if value is None:
        return "not computed"
    if same:
        return "reproduced"
    if _is_number(value) and q.bound is not None and abs(value - q.value) <= q.bound:
        return "input-rounding"
    if q.correct is not None and matches_printed(value, q.correct,
                                                 q.correct_decimals if q.correct_decimals is not None else q.decimals):
        return q.status if q.status in WRONG_STATUSES else "erratum"
    return "differs (unclassified)"


def check_formula(formula: Formula) -> Row:
    """Compare a printed formula with its sympy derivation: ``reproduced`` iff they agree; an
    ``erratum`` or ``transcription`` iff the printed (as transcribed) form differs."""
    agrees = bool(resolve(formula.compute)(formula.inputs)["printed_equals_derived"])
    ok = agrees if formula.status == "reproduced" else not agrees
    wrong = formula.status if formula.status in WRONG_STATUSES else "erratum"
    return Row(formula.chapter, formula.id, formula.equation, "printed formula",
               "equals derivation" if agrees else "differs from derivation", formula.status, ok,
               reason=formula.diagnosis, observed_status="reproduced" if agrees else wrong)


def verify(chapters=None, jobs: int = 1, source: str | None = None) -> list[Row]:
    """Rows for every entry of the given chapters (all by default).

    ``source`` (a seed file name, see :func:`photolib.book.textbook.source_seeds`) keeps only the
    entries taken from that text, e.g. Hanzl's study text filed under several chapters.

    ``jobs`` > 1 checks the entries in that many worker processes (forked after the adapters are
    imported, so each worker starts with the modules loaded); the rows come back in the same
    order and are the same as with ``jobs=1`` (every check is deterministic: seeded simulations,
    exact symbolic tests). Where ``fork`` is not available the entries are checked in this process.
    """
    entries = []
    for number in chapters or available_chapters():
        chapter = load_chapter(number)
        entries += [(check_example, example) for example in chapter.examples
                    if source is None or example.seed == source]
        entries += [(check_formula, formula) for formula in chapter.formulas
                    if source is None or formula.seed == source]
    jobs = min(int(jobs), len(entries))
    if jobs > 1 and "fork" in multiprocessing.get_all_start_methods():
        for target in {entry.compute for _, entry in entries if entry.compute}:
            resolve(target)                      # import every adapter once, before the fork
        global _ENTRIES
        _ENTRIES = entries
        try:
            with multiprocessing.get_context("fork").Pool(jobs) as pool:
                checked = pool.map(_check_entry, range(len(entries)), chunksize=1)
        finally:
            _ENTRIES = None
    else:
        checked = [_rows(check, entry) for check, entry in entries]
    return [row for rows in checked for row in rows]


_ENTRIES = None          # the entries of a parallel verify, inherited by the forked workers


def _rows(check, entry) -> list[Row]:
    rows = check(entry)
    return rows if isinstance(rows, list) else [rows]


def _check_entry(index: int) -> list[Row]:
    check, entry = _ENTRIES[index]
    return _rows(check, entry)


def default_jobs() -> int:
    """Worker processes for ``photolib verify``: the CPUs this process may use, at most 8."""
    try:
        cpus = len(os.sched_getaffinity(0))
    except AttributeError:                # not on Linux
        cpus = os.cpu_count() or 1
    return max(1, min(cpus, 8))


def summary(rows) -> dict:
    """Counts per status and of entries whose status no longer holds."""
    counts = {}
    for r in rows:
        counts[r.status] = counts.get(r.status, 0) + 1
    counts["changed"] = sum(not r.ok for r in rows)
    return counts


# Colours of the statuses in the notebooks' tables (and the legend under each result table).
STATUS_COLOURS = {
    "reproduced": "#1a7f37",          # green: the book's number comes out
    "input-rounding": "#0969da",      # blue: differs only by the book's rounding of its inputs
    "erratum": "#bc4c00",             # orange: the book is wrong; the correct value is shown
    "transcription": "#1b7c83",       # teal: the OCR source lost or garbled it; the book is most likely right
    "not-reproducible": "#6e7781",    # grey: the book does not print the data
    "transcribed": "#8250df",         # purple: data, nothing to compute
    "CHANGED": "#cf222e",             # red: the recorded status no longer holds
}
_NUMBER_CELL = re.compile(r"^[−+-]?\d[\d\s]*(?:[.,](\d+))?(?:[eE][−+-]?\d+)?$")


def _decimal_parts(text: str):
    """(integer part, fraction digits) of a number cell, or None for text."""
    m = _NUMBER_CELL.match(text.strip())
    if not m:
        return None
    return len(m.group(1) or "")


class Table:
    """A small table that prints as text (and as a styled HTML table in Jupyter).

    In HTML, cells are padded, numbers are right-aligned on their decimal point (decimal comma
    of the book or decimal point of photolib alike), and statuses are coloured, with a legend
    when the table shows statuses.
    """

    def __init__(self, header, rows, title=""):
        self.header, self.rows, self.title = list(header), [list(map(str, r)) for r in rows], title

    def __repr__(self):
        widths = [max(len(h), *(len(r[i]) for r in self.rows)) if self.rows else len(h)
                  for i, h in enumerate(self.header)]
        line = lambda cells: "  ".join(c.ljust(w) for c, w in zip(cells, widths)).rstrip()  # noqa: E731
        out = ([self.title] if self.title else []) + [line(self.header), line(["-" * w for w in widths])]
        return "\n".join(out + [line(r) for r in self.rows])

    def _numeric_columns(self):
        """{column: the most fraction digits} for columns whose non-empty cells are all numbers."""
        columns = {}
        for i in range(len(self.header)):
            cells = [r[i] for r in self.rows if i < len(r) and r[i].strip() not in ("", "—")]
            parts = [_decimal_parts(c) for c in cells]
            if cells and all(p is not None for p in parts):
                columns[i] = max(parts)
        return columns

    def _repr_html_(self):
        import html
        numeric = self._numeric_columns()
        pad = "padding:0.2em 0.7em;border-bottom:1px solid #d0d7de;"
        head = "".join(f'<th style="{pad}text-align:{"right" if i in numeric else "left"}">{html.escape(h)}</th>'
                       for i, h in enumerate(self.header))
        statuses = set()
        body = []
        for r in self.rows:
            cells = []
            for i, c in enumerate(r):
                style = pad
                text = html.escape(c)
                if i in numeric and c.strip() not in ("", "—"):
                    missing = numeric[i] - _decimal_parts(c)
                    if _decimal_parts(c) == 0 and numeric[i] and not re.search(r"[.,]", c):
                        filler = "\u2008" + "\u2007" * numeric[i]        # punctuation space + figure spaces
                    else:
                        filler = "\u2007" * missing
                    text += filler
                    style += "text-align:right;font-variant-numeric:tabular-nums;white-space:nowrap;"
                elif i in numeric:
                    style += "text-align:right;"
                elif len(c) <= 14:
                    style += "white-space:nowrap;"          # short labels and line ranges stay on one line
                word = c.split(" ")[0]
                if word in STATUS_COLOURS:
                    statuses.add(word)
                    style += f"color:{STATUS_COLOURS[word]};font-weight:600;"
                cells.append(f'<td style="{style}">{text}</td>')
            body.append("<tr>" + "".join(cells) + "</tr>")
        caption = (f'<caption style="caption-side:top;text-align:left;font-weight:600;padding:0.3em 0">'
                   f"{html.escape(self.title)}</caption>") if self.title else ""
        legend = ""
        if statuses:
            keys = [s for s in STATUS_COLOURS if s in statuses]
            legend = ('<div style="font-size:0.85em;margin-top:0.3em">' + " · ".join(
                f'<span style="color:{STATUS_COLOURS[k]};font-weight:600">{html.escape(k)}</span>'
                f"{html.escape(': ' + _LEGEND[k])}" for k in keys) + "</div>")
        return (f'<div style="overflow-x:auto"><table style="border-collapse:collapse;margin:0.5em 0">{caption}'
                f"<thead><tr>{head}</tr></thead><tbody>{''.join(body)}</tbody></table>{legend}</div>")


_LEGEND = {
    "reproduced": "the book's number comes out",
    "input-rounding": "differs only through the book's rounding of its inputs",
    "erratum": "the book is wrong (correct value given)",
    "transcription": "lost or garbled in the OCR of the source, the book most likely right (correct value given)",
    "not-reproducible": "the book does not print the data",
    "transcribed": "data, nothing to compute",
    "CHANGED": "the recorded status no longer holds",
}


def example_table(chapter: int, example_id: str) -> Table:
    """The book · computed · status table that ends each worked example in the notebooks."""
    example = load_chapter(chapter).example(example_id)
    rows = check_example(example)
    with_printed = any(r.as_printed for r in rows)
    with_units = any(q.unit for q in example.quantities)
    header = (["quantity", "book", "computed"] + (["unit"] if with_units else [])
              + (["as printed"] if with_printed else []) + ["status", "check"])
    body = []
    for r, q in zip(rows, example.quantities):
        cells = [r.quantity, r.book, r.computed] + ([q.unit] if with_units else [])
        cells += [r.as_printed] if with_printed else []
        body.append(cells + [r.status + (f" ({r.detail})" if r.detail else ""), "ok" if r.ok else "CHANGED"])
    return Table(header, body, f"§{example.section} {example.title}")


def formula_table(chapter: int, select, title: str) -> Table:
    """The printed formula · sympy · status table of the notebooks, for formulas of one chapter.

    ``select`` is an id prefix (``"hanzl-7.3.2"``: every formula whose id starts with it, in the
    chapter's order), a set of ids (in the chapter's order) or a list or tuple of ids (in that order).
    """
    formulas = load_chapter(chapter).formulas
    if isinstance(select, str):
        chosen = [fm for fm in formulas if fm.id.startswith(select)]
    elif isinstance(select, (set, frozenset)):
        chosen = [fm for fm in formulas if fm.id in select]
    else:
        by_id = {fm.id: fm for fm in formulas}
        missing = [i for i in select if i not in by_id]
        if missing:
            raise KeyError(f"chapter {chapter} has no formula {missing[0]!r}")
        chosen = [by_id[i] for i in select]
    rows = []
    for fm in chosen:
        r = check_formula(fm)
        rows.append([fm.equation, f"{fm.lines[0]}–{fm.lines[1]}", r.computed, fm.status, "ok" if r.ok else "CHANGED"])
    return Table(["formula", "seed lines", "printed vs sympy", "status", "check"], rows, title)
