"""Command line: ``photolib verify [--chapter N] [--json]``.

Recomputes every published number recorded in ``textbook/`` with the library, prints one row
per quantity (chapter, example, quantity, book value, computed value, status) and a summary
line with the counts per status. Exits with status 1 when an entry no longer has the status
recorded for it.
"""

from __future__ import annotations

import argparse
import json
import sys

from .verify import summary, verify


def _print_table(rows, out):
    header = ("ch", "example", "quantity", "book", "computed", "status", "")
    table = [header] + [(str(r.chapter), r.example, r.quantity, r.book, r.computed, r.status,
                         "" if r.ok else "<-- CHANGED") for r in rows]
    widths = [max(len(row[i]) for row in table) for i in range(len(header))]
    for row in table:
        out.write("  ".join(cell.ljust(w) for cell, w in zip(row, widths)).rstrip() + "\n")


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(prog="photolib", description=__doc__.splitlines()[0])
    sub = parser.add_subparsers(dest="command", required=True)
    p_verify = sub.add_parser("verify", help="recompute the book's published numbers from textbook/")
    p_verify.add_argument("--chapter", type=int, action="append", help="only this chapter (repeatable)")
    p_verify.add_argument("--json", action="store_true", help="print the rows and the summary as JSON")
    args = parser.parse_args(argv)

    rows = verify(args.chapter)
    counts = summary(rows)
    if args.json:
        json.dump({"rows": [r.as_dict() for r in rows], "summary": counts}, sys.stdout, ensure_ascii=False, indent=1)
        sys.stdout.write("\n")
    else:
        _print_table(rows, sys.stdout)
        parts = ", ".join(f"{k} {v}" for k, v in counts.items() if k != "changed")
        print(f"\n{len(rows)} published quantities: {parts}; status no longer holds: {counts['changed']}")
    return 1 if counts["changed"] else 0


if __name__ == "__main__":
    sys.exit(main())
