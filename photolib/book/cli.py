"""Command line for readers, instructors and regression checks of the published numbers.

* ``photolib verify [--chapter N] [--source KEY] [--only-changed] [--wide] [--json] [--jobs N]`` recomputes every
  published number recorded in ``textbook/`` with the library. It prints the summary first (counts
  per status, overall and per chapter), then one row per quantity in 100 columns (``--wide``: full
  cells), then, for every entry whose recorded status no longer holds, what changed: the recorded
  status, the book's and the computed value, the difference, the tolerance and the recorded reason.
  ``--only-changed`` prints only those rows. ``--json`` prints the rows (numbers as numbers, with
  unit, tolerance and reason) and the summaries.
* ``--source KEY`` (verify, list, errata) keeps the entries taken from one text: ``chibunichev`` (the
  textbook), ``gnss``, ``hanzl``, ``mrf``, ``sementsov`` (the keys of ``textbook/pages.toml``).
* ``photolib list [--chapter N]`` lists the worked examples, tables and formulas with their ids.
* ``photolib show ID`` shows one of them: where it is in the book, its inputs, the book · computed ·
  status table and the notes, diagnoses and reasons.
* ``photolib errata [--chapter N] [--json]`` lists the errors found in the book (``erratum``) and
  the numbers and formulas the OCR text of the source lost or garbled (``transcription``), cited by
  printed page ("§1.8, p. ≈24") or source and §, with the correct value and the diagnosis (written
  once for the entries of a § that share it); the OCR lines come last.
* ``photolib assignment ID --seed N [--out DIR]`` writes a student sheet for a worked example
  (its inputs regenerated from a new seeded truth with the book's rounding, as Markdown and as a
  notebook) and a separate answer key with the tolerance of each answer;
  ``photolib check ID --seed N answers.toml [--strict]`` grades a student's answers against it.
* ``photolib --version``.

Exit codes: 0 when every entry still has its recorded status; 1 when some entry no longer does
(a regression, or a fix that needs the record updated); 2 for a usage error (unknown chapter,
id or flag), reported on one line.
"""

from __future__ import annotations

import argparse
import json
import sys
import textwrap

from .. import __version__
from .assignment_cli import RUNNERS as _ASSIGNMENT_RUNNERS, add_assignment_commands
from .textbook import STATUSES, available_chapters, load_chapter, load_pages, source_seeds
from .verify import check_example, check_formula, default_jobs, example_table, summary, verify

USAGE_ERROR = 2
STATUS_CHANGED = 1
WIDTH = 100                      # the terminal width the default output fits


class _Parser(argparse.ArgumentParser):
    """argparse, but a usage error is one line on stderr and exit code 2 (no usage dump)."""

    def error(self, message):
        self.exit(USAGE_ERROR, f"{self.prog}: error: {message}\n")


class _UsageError(Exception):
    """A usage error found after parsing (unknown chapter or id): one line, exit code 2."""


def _clip(text: str, width: int) -> str:
    return text if len(text) <= width else text[: max(width - 1, 0)] + "…"


def _table(header, rows, out, caps=None, right=()):
    """Columns padded to their widest cell; ``caps`` limits a column's width (cells end in "…")."""
    caps = caps or [None] * len(header)
    rows = [[_clip(c, cap) if cap else c for c, cap in zip(row, caps)] for row in [header, *rows]]
    widths = [max(len(row[i]) for row in rows) for i in range(len(header))]
    for n, row in enumerate(rows):
        cells = [c.rjust(w) if i in right and n else c.ljust(w) for i, (c, w) in enumerate(zip(row, widths))]
        out.write("  ".join(cells).rstrip() + "\n")


def _wrap(text: str, indent: str = "    ") -> str:
    return textwrap.fill(" ".join(text.split()), WIDTH, initial_indent=indent, subsequent_indent=indent)


def _chapters(args) -> list[int]:
    known = available_chapters()
    if not getattr(args, "chapter", None):
        return known
    unknown = sorted(set(args.chapter) - set(known))
    if unknown:
        raise _UsageError(f"no published numbers for chapter {', '.join(map(str, unknown))} "
                          f"(available: {', '.join(map(str, known))})")
    return sorted(set(args.chapter))


def _source(args) -> str | None:
    """The seed file selected by ``--source KEY`` (None: every source)."""
    key = getattr(args, "source", None)
    if not key:
        return None
    seeds = source_seeds()
    if key not in seeds:
        raise _UsageError(f"unknown source {key!r} (known: {', '.join(sorted(seeds))})")
    return seeds[key]


def _source_name(seed: str | None) -> str:
    return "" if seed is None else load_pages().sources[seed]["name"]


# --- verify ------------------------------------------------------------------------------------------
def _per_chapter(rows) -> list[dict]:
    chapters = sorted({r.chapter for r in rows})
    return [{"chapter": c, **summary([r for r in rows if r.chapter == c])} for c in chapters]


def _summary_text(rows, counts, per_chapter, out):
    chapters = [p["chapter"] for p in per_chapter]
    span = (f"chapter {chapters[0]}" if len(chapters) == 1 else
            f"chapters {', '.join(map(str, chapters))}" if len(chapters) < 4 else
            f"chapters {chapters[0]}–{chapters[-1]}")
    parts = " · ".join(f"{s} {counts[s]}" for s in STATUSES if counts.get(s))
    out.write(textwrap.fill(f"{len(rows)} published quantities and formulas in {span}: {parts}", WIDTH) + "\n")
    out.write(f"status no longer holds: {counts['changed']}\n\n")
    if len(per_chapter) > 1:
        header = ["chapter", *STATUSES, "changed"]
        body = [[str(p["chapter"]), *(str(p.get(s, 0)) for s in STATUSES), str(p["changed"])]
                for p in per_chapter]
        _table(header, body, out, right=range(len(header)))
        out.write("\n")


def _shown_values(row) -> tuple[str, str]:
    """The book and computed cells; a formula row shows whether the printed form equals sympy's."""
    if row.book == "printed formula":
        return "formula", ("= sympy" if row.computed.startswith("equals") else "≠ sympy")
    return row.book, row.computed


def _rows_text(rows, out, wide: bool):
    header = ["ch", "example", "quantity", "book", "computed", "status", "check"]
    body = [[str(r.chapter), r.example, r.quantity, *_shown_values(r), r.status, "ok" if r.ok else "CHANGED"]
            for r in rows]
    caps = None if wide else [2, 21, 16, 13, 13, 16, 7]    # 88 + 6 separators of 2 = 100 columns
    _table(header, body, out, caps)


def _run_verify(args, out) -> int:
    chapters = _chapters(args)
    if args.jobs is not None and args.jobs < 1:
        raise _UsageError(f"--jobs must be at least 1, got {args.jobs}")
    source = _source(args)
    rows = verify(chapters, jobs=default_jobs() if args.jobs is None else args.jobs, source=source)
    if not rows:
        raise _UsageError(f"no entries from {_source_name(source)} in the chapters selected")
    counts, per_chapter = summary(rows), _per_chapter(rows)
    changed = [r for r in rows if not r.ok]
    if args.json:
        shown = changed if args.only_changed else rows
        json.dump({"version": __version__, "summary": counts, "chapters": per_chapter,
                   "rows": [dict(r.as_dict(), explanation=r.explain(), version=__version__) for r in shown]},
                  out, ensure_ascii=False, indent=1, default=str)
        out.write("\n")
        return STATUS_CHANGED if changed else 0
    if source:
        out.write(f"source: {_source_name(source)}\n")
    _summary_text(rows, counts, per_chapter, out)
    shown = changed if args.only_changed else rows
    if shown:
        _rows_text(shown, out, args.wide)
    if changed:
        out.write("\nWhat changed:\n")
        for r in changed:
            out.write(f"  ch {r.chapter} {r.example} / {r.quantity}\n{_wrap(r.explain())}\n")
    out.write(f"\n{len(rows)} checked; status no longer holds: {counts['changed']}\n")
    return STATUS_CHANGED if changed else 0


# --- list and show ----------------------------------------------------------------------------------
def _entries(chapters, source=None):
    for number in chapters:
        chapter = load_chapter(number)
        for ex in chapter.examples:
            if source is None or ex.seed == source:
                yield number, ex, "example"
        for fm in chapter.formulas:
            if source is None or fm.seed == source:
                yield number, fm, "formula"


def _statuses(entry, kind) -> str:
    if kind == "formula":
        return entry.status
    counts = {}
    for q in entry.quantities:
        counts[q.status] = counts.get(q.status, 0) + 1
    return ", ".join(f"{n} {s}" for s, n in counts.items())


def _run_list(args, out) -> int:
    body = []
    for number, entry, kind in _entries(_chapters(args), _source(args)):
        title = entry.title if kind == "example" else f"{entry.equation} (formula)"
        body.append([str(number), entry.id, f"§{entry.section}", _statuses(entry, kind), title])
    caps = None if args.wide else [2, 28, 7, 24, 27]
    _table(["ch", "id", "§", "statuses", "title"], body, out, caps)
    out.write(f"\n{len(body)} entries; `photolib show ID` shows one\n")
    return 0


def _find(entry_id: str, chapters):
    hits = [(n, e, k) for n, e, k in _entries(chapters) if e.id == entry_id]
    if not hits:
        near = sorted({e.id for _, e, _ in _entries(chapters) if entry_id.lower() in e.id.lower()})
        hint = f"; similar: {', '.join(near[:5])}" if near else "; `photolib list` shows the ids"
        raise _UsageError(f"no example or formula {entry_id!r}{hint}")
    if len(hits) > 1:
        raise _UsageError(f"{entry_id!r} is in chapters {', '.join(str(n) for n, _, _ in hits)}: add --chapter")
    return hits[0]


def _inputs_text(inputs: dict, wide: bool) -> list[str]:
    lines = []
    for key, value in inputs.items():
        text = json.dumps(value, ensure_ascii=False, default=str)
        lines.append(f"    {key} = {text if wide else _clip(text, WIDTH - 7 - len(key))}")
    return lines


def _run_show(args, out) -> int:
    number, entry, kind = _find(args.id, _chapters(args))
    seed = f"seed {entry.seed}, " if entry.seed else ""
    lines = f"lines {entry.lines[0]}–{entry.lines[-1]}" if entry.lines else ""
    if kind == "formula":
        row = check_formula(entry)
        out.write(f"{entry.id}: §{entry.section} {entry.equation}\n  chapter {number}, {seed}{lines}\n")
        out.write(f"  printed: {entry.printed}\n  status: {entry.status} — the printed formula "
                  f"{row.computed}; {'ok' if row.ok else 'CHANGED'}\n")
        for label, text in (("correct", entry.correct), ("diagnosis", entry.diagnosis), ("proof", entry.proof),
                            ("notes", entry.notes)):
            if text:
                out.write(f"  {label}:\n{_wrap(text)}\n")
        return 0 if row.ok else STATUS_CHANGED
    out.write(textwrap.fill(f"{entry.id}: §{entry.section} {entry.title}", WIDTH, subsequent_indent="  ")
              + f"\n  chapter {number}, {seed}{lines}\n")
    if entry.calls:
        out.write(_wrap(f"computed by: {entry.calls}", "  ") + "\n")
    if entry.compute:
        out.write(_wrap(f"adapter: {entry.compute}(inputs)", "  ") + "\n")
    if entry.inputs:
        out.write("  inputs (as printed):\n" + "\n".join(_inputs_text(entry.inputs, args.wide)) + "\n")
    out.write("\n" + repr(example_table(number, entry.id)) + "\n")
    rows = check_example(entry)
    reasons = {}                                   # one paragraph per distinct diagnosis or reason
    for q in entry.quantities:
        why = q.diagnosis or q.reason
        if why:
            reasons.setdefault((q.status, why), []).append(q.name)
    for (status, why), names in reasons.items():
        out.write(f"\n{_wrap(', '.join(names) + f' ({status}):', '  ')}\n{_wrap(why)}\n")
    for r in rows:
        if not r.ok:
            out.write(f"\n  CHANGED {r.quantity}:\n{_wrap(r.explain())}\n")
    if entry.notes:
        out.write(f"\n  notes:\n{_wrap(entry.notes)}\n")
    return 0 if all(r.ok for r in rows) else STATUS_CHANGED


# --- errata -------------------------------------------------------------------------------------------
def _run_errata(args, out) -> int:
    """The errata grouped as in the appendix: the printed page (or source and §) first, the kind
    (erratum: an error of the book; transcription: lost or garbled in the OCR), the values, the
    diagnosis once per group, and the OCR lines last."""
    from .errata import errata, group_records
    source = _source(args)
    records = [r for r in errata(_chapters(args), recompute=False) if source is None or r.seed == source]
    if args.json:
        json.dump([r.as_dict() for r in records], out, ensure_ascii=False, indent=1, default=str)
        out.write("\n")
        return 0
    chapter = None
    for group in group_records(records):
        first = group.first
        if first.chapter != chapter:
            chapter = first.chapter
            out.write(f"\nChapter {chapter}. {load_chapter(chapter).title}\n")
        item = group.label if first.kind == "quantity" else f"eq. {group.label}" if group.label.startswith("(") \
            else group.label
        head = f"{group.where}, {item} [{group.status}]"
        if len(group.records) == 1:
            unit = f" {first.unit}" if first.unit else ""
            head += f": printed {first.printed}{'' if first.unit and first.unit in first.printed else unit}, " \
                    f"correct {first.correct}{unit}"
        out.write(textwrap.fill(head, WIDTH, initial_indent="  ", subsequent_indent="    ") + "\n")
        if len(group.records) > 1:
            for r, note in zip(group.records, group.notes):
                unit = f" {r.unit}" if r.unit else ""
                shown = r.printed if not unit or r.unit in r.printed else r.printed + unit
                line = f"{r.item}: printed {shown}, correct {r.correct}{unit}" + (f" — {note}" if note else "")
                out.write(textwrap.fill(" ".join(line.split()), WIDTH, initial_indent="    ",
                                        subsequent_indent="      ") + "\n")
        out.write(_wrap(group.common, "      ") + "\n")
        lines = group.lines
        span = "" if not lines else f", line {lines[0]}" if lines[0] == lines[1] else f", lines {lines[0]}–{lines[1]}"
        out.write(_wrap(f"(seed {first.seed}{span}; {', '.join(dict.fromkeys(r.id for r in group.records))})",
                        "      ") + "\n")
    wrong = sum(r.status == "erratum" for r in records)
    out.write(f"\n{wrong} errors of the book (erratum) and {len(records) - wrong} defects of the OCR transcription "
              f"(transcription): {len(records)} errata\n")
    return 0


def build_parser() -> argparse.ArgumentParser:
    parser = _Parser(prog="photolib", description=__doc__.splitlines()[0])
    parser.add_argument("--version", action="version", version=f"photolib {__version__}")
    sub = parser.add_subparsers(dest="command", required=True, parser_class=_Parser)

    def chapter_option(p, source=True):
        p.add_argument("--chapter", type=int, action="append", help="only this chapter (repeatable)")
        if source:
            p.add_argument("--source", metavar="KEY",
                           help="only the entries from one source text: " + ", ".join(sorted(source_seeds())))

    p_verify = sub.add_parser("verify", help="recompute the book's published numbers from textbook/")
    chapter_option(p_verify)
    p_verify.add_argument("--only-changed", action="store_true",
                          help="only the entries whose recorded status no longer holds")
    p_verify.add_argument("--wide", action="store_true", help="full cells instead of 100 columns")
    p_verify.add_argument("--json", action="store_true", help="print the rows and the summaries as JSON")
    p_verify.add_argument("--jobs", type=int, default=None, metavar="N",
                          help="worker processes (default: the CPUs available, at most 8; 1: no workers)")
    p_list = sub.add_parser("list", help="list the worked examples, tables and formulas with their ids")
    chapter_option(p_list)
    p_list.add_argument("--wide", action="store_true", help="full cells instead of 100 columns")
    p_show = sub.add_parser("show", help="show one example or formula: inputs, book · computed · status, notes")
    p_show.add_argument("id", help="the id, as `photolib list` prints it")
    chapter_option(p_show, source=False)
    p_show.add_argument("--wide", action="store_true", help="the inputs in full")
    p_errata = sub.add_parser("errata", help="list the errors found in the book and the OCR transcription defects")
    chapter_option(p_errata)
    p_errata.add_argument("--json", action="store_true", help="print the errata as JSON")
    add_assignment_commands(sub)
    return parser


def main(argv=None, out=None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    out = out or sys.stdout
    run = {"verify": _run_verify, "list": _run_list, "show": _run_show, "errata": _run_errata,
           **_ASSIGNMENT_RUNNERS}[args.command]
    try:
        return run(args, out)
    except BrokenPipeError:              # e.g. `photolib verify | head`: the reader stopped reading
        sys.stderr.close()
        return 0
    except _UsageError as error:
        sys.stderr.write(f"photolib: error: {error}\n")
        return USAGE_ERROR


if __name__ == "__main__":
    sys.exit(main())
