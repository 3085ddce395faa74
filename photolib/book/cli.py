"""Command line: ``photolib verify [--chapter N] [--json] [--jobs N]`` and ``photolib --version``.

``verify`` recomputes every published number recorded in ``textbook/`` with the library, prints
one row per quantity (chapter, example, quantity, book value, computed value, status) and a
summary line with the counts per status.

Exit codes: 0 when every entry still has its recorded status; 1 when some entry no longer does
(a regression, or a fix that needs the record updated); 2 for a usage error (unknown chapter,
unknown flag), reported on one line.
"""

from __future__ import annotations

import argparse
import json
import sys

from .. import __version__
from .textbook import available_chapters
from .verify import default_jobs, summary, verify

USAGE_ERROR = 2
STATUS_CHANGED = 1


class _Parser(argparse.ArgumentParser):
    """argparse, but a usage error is one line on stderr and exit code 2 (no usage dump)."""

    def error(self, message):
        self.exit(USAGE_ERROR, f"{self.prog}: error: {message}\n")


def _print_table(rows, out):
    header = ("ch", "example", "quantity", "book", "computed", "status", "")
    table = [header] + [(str(r.chapter), r.example, r.quantity, r.book, r.computed, r.status,
                         "" if r.ok else "<-- CHANGED") for r in rows]
    widths = [max(len(row[i]) for row in table) for i in range(len(header))]
    for row in table:
        out.write("  ".join(cell.ljust(w) for cell, w in zip(row, widths)).rstrip() + "\n")


def build_parser() -> argparse.ArgumentParser:
    parser = _Parser(prog="photolib", description=__doc__.splitlines()[0])
    parser.add_argument("--version", action="version", version=f"photolib {__version__}")
    sub = parser.add_subparsers(dest="command", required=True, parser_class=_Parser)
    p_verify = sub.add_parser("verify", help="recompute the book's published numbers from textbook/")
    p_verify.add_argument("--chapter", type=int, action="append",
                          help="only this chapter (repeatable)")
    p_verify.add_argument("--json", action="store_true", help="print the rows and the summary as JSON")
    p_verify.add_argument("--jobs", type=int, default=None, metavar="N",
                          help="worker processes (default: the CPUs available, at most 8; 1: no workers)")
    return parser


def main(argv=None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)

    if args.chapter:
        known = available_chapters()
        unknown = sorted(set(args.chapter) - set(known))
        if unknown:
            listed = ", ".join(map(str, known))
            sys.stderr.write(f"photolib: error: no published numbers for chapter "
                             f"{', '.join(map(str, unknown))} (available: {listed})\n")
            return USAGE_ERROR

    if args.jobs is not None and args.jobs < 1:
        sys.stderr.write(f"photolib: error: --jobs must be at least 1, got {args.jobs}\n")
        return USAGE_ERROR
    rows = verify(args.chapter, jobs=default_jobs() if args.jobs is None else args.jobs)
    counts = summary(rows)
    if args.json:
        json.dump({"rows": [r.as_dict() for r in rows], "summary": counts}, sys.stdout,
                  ensure_ascii=False, indent=1)
        sys.stdout.write("\n")
    else:
        _print_table(rows, sys.stdout)
        parts = ", ".join(f"{k} {v}" for k, v in counts.items() if k != "changed")
        print(f"\n{len(rows)} published quantities: {parts}; status no longer holds: {counts['changed']}")
    return STATUS_CHANGED if counts["changed"] else 0


if __name__ == "__main__":
    sys.exit(main())
