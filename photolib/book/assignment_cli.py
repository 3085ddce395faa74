"""Command line of the assignments (issue 13, item 4), for the worked examples of Chapters 1–4.

* ``photolib assignment ID --seed N [--out DIR]`` writes the student sheet ``ID-seedN.md`` and
  ``ID-seedN.ipynb`` and the separate answer key ``ID-seedN-key.toml``.
* ``photolib check ID --seed N answers.toml [--strict]`` regenerates the key from ID and N and
  grades the answers: one line per quantity (correct / WRONG with the expected value and the
  tolerance / missing) and the total.

Exit codes: 0 all correct (``assignment``: files written); 1 some answer wrong or missing; 2 a
usage error (unknown example, example without a generator, malformed answers file), one line on
stderr. The commands join ``photolib`` through :func:`add_assignment_commands` and
:data:`RUNNERS`; :func:`main` runs them on their own (``python -m photolib.book.assignment_cli``).
"""

from __future__ import annotations

import argparse
import sys

USAGE_ERROR = 2
NOT_ALL_CORRECT = 1


def add_assignment_commands(subparsers) -> None:
    """Add the ``assignment`` and ``check`` sub-commands to an argparse ``subparsers`` object."""
    p = subparsers.add_parser("assignment", help="write a student sheet (Markdown, notebook) and its answer key "
                                                 "for a worked example with new data")
    p.add_argument("id", help="the worked example, e.g. 1.8-resection (an unknown id lists those with a generator)")
    p.add_argument("--seed", type=int, required=True, help="seed of the new data (the same seed, the same sheet)")
    p.add_argument("--out", default=".", help="folder to write the files into (default: the current one)")
    p = subparsers.add_parser("check", help="grade an answers.toml against the regenerated answer key")
    p.add_argument("id", help="the worked example of the sheet")
    p.add_argument("--seed", type=int, required=True, help="the seed of the sheet")
    p.add_argument("answers", help="the student's answers.toml (name = value lines)")
    p.add_argument("--strict", action="store_true",
                   help="half a unit of the printed decimal for every number (no input-rounding bounds)")


def _usage_error(error) -> int:
    sys.stderr.write(f"photolib: error: {' '.join(str(error).split())}\n")
    return USAGE_ERROR


def run_assignment(args, out) -> int:
    """``photolib assignment``: write the three files, print their paths."""
    from .assignments import AssignmentError, write_assignment      # imported on use: keeps `photolib` quick
    try:
        files = write_assignment(args.id, args.seed, args.out)
    except AssignmentError as error:
        return _usage_error(error)
    out.write(f"sheet:      {files.markdown}\nnotebook:   {files.notebook}\n"
              f"answer key: {files.key} (keep it from the students)\n")
    return 0


def run_check(args, out) -> int:
    """``photolib check``: grade the answers, print the verdicts; 0 if all correct, else 1."""
    from .assignments import AssignmentError, grade, read_answers
    try:
        result = grade(args.id, args.seed, read_answers(args.answers), strict=args.strict)
    except AssignmentError as error:
        return _usage_error(error)
    out.write(result.report() + "\n")
    return 0 if result.ok else NOT_ALL_CORRECT


RUNNERS = {"assignment": run_assignment, "check": run_check}
"""Command name → run function (``run(args, out) -> exit code``), for ``photolib.book.cli.main``."""


class _Parser(argparse.ArgumentParser):
    def error(self, message):
        self.exit(USAGE_ERROR, f"{self.prog}: error: {message}\n")


def main(argv=None, out=None) -> int:
    """Run ``assignment`` or ``check`` without the rest of ``photolib`` (tests, ``python -m``)."""
    parser = _Parser(prog="photolib", description="assignments with answer keys")
    add_assignment_commands(parser.add_subparsers(dest="command", required=True, parser_class=_Parser))
    args = parser.parse_args(argv)
    return RUNNERS[args.command](args, out or sys.stdout)


if __name__ == "__main__":
    sys.exit(main())
