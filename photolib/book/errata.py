"""The book's errata, generated from ``textbook/`` — the source of Appendix B of the companion.

Nothing here is hard-coded: every record comes from an entry of ``textbook/chNN.toml`` (read with
:mod:`photolib.book.textbook`) whose status is

* ``erratum`` — an ``[[example.quantity]]`` or a ``[[formula]]`` the book gets wrong; the record
  holds what is printed, what is correct, the diagnosis and how it was proved, and — for examples
  with an "as printed" computation — whether that computation reproduces the printed number;
* ``input-rounding`` — a number off in its last digit only because the book rounded its inputs
  (with the admissible bound and its justification);
* ``not-reproducible`` — a number the book does not give the data for (with the reason).

:func:`errata` and :func:`discrepancies` return the records, :func:`errata_markdown` renders the
appendix, :func:`status_counts` the per-chapter summary.
"""

from __future__ import annotations

from dataclasses import dataclass

from .textbook import available_chapters, load_chapter


@dataclass
class Record:
    """One published number or formula whose status is not simply ``reproduced``/``transcribed``."""

    chapter: int
    section: str
    id: str
    kind: str                  # "quantity" or "formula"
    item: str                  # the quantity name or the equation
    title: str
    lines: tuple
    seed: str
    status: str
    printed: str               # as printed (text of the number, or LaTeX of the formula)
    unit: str = ""
    correct: str = ""          # erratum: the correct value / formula
    diagnosis: str = ""
    proof: str = ""
    bound: float | None = None  # input-rounding
    reason: str = ""           # input-rounding / not-reproducible
    as_printed: bool | None = None        # erratum with an "as printed" computation: does it reproduce the book?
    as_printed_value: str = ""            # ... and what it computes

    def as_dict(self) -> dict:
        return dict(self.__dict__)


def _section_key(section: str):
    """Sort key for "1.10" after "1.9"; non-numeric parts sort after numbers, without type errors."""
    return tuple((0, int(p), "") if p.isdigit() else (1, 0, p) for p in str(section).split("."))


def _value_text(q) -> str:
    """The correct value of an erratum quantity, with its decimals (decimal point)."""
    d = q.correct_decimals if q.correct_decimals is not None else q.decimals
    if isinstance(q.correct, (int, float)) and not isinstance(q.correct, bool) and d is not None:
        return f"{q.correct:.{d}f}"
    return str(q.correct)


def _as_printed_runs(example) -> dict:
    """{quantity name: (value text, reproduces the printed value?)} from the "as printed" computation."""
    from .verify import format_value, matches_printed, resolve
    values = resolve(example.as_printed_compute)(example.inputs)
    out = {}
    for q in example.quantities:
        v = values.get(q.name)
        out[q.name] = (format_value(v, q.decimals) if v is not None else "", matches_printed(v, q.value, q.decimals))
    return out


def _records(chapters, statuses, recompute: bool) -> list[Record]:
    out = []
    for number in chapters if chapters is not None else available_chapters():
        chapter = load_chapter(number)
        for ex in chapter.examples:
            hits = [q for q in ex.quantities if q.status in statuses]
            if not hits:
                continue
            runs = _as_printed_runs(ex) if recompute and ex.as_printed_compute and any(
                q.status == "erratum" and q.as_printed for q in hits) else {}
            for q in hits:
                rec = Record(number, ex.section, ex.id, "quantity", q.name, ex.title, tuple(ex.lines), ex.seed,
                             q.status, q.printed, q.unit, bound=q.bound, reason=q.reason)
                if q.status == "erratum":
                    rec.correct, rec.diagnosis, rec.proof = _value_text(q), q.diagnosis, q.proof
                    if q.as_printed:
                        value, ok = runs.get(q.name, ("", None))
                        rec.as_printed, rec.as_printed_value = (ok if recompute else True), value
                out.append(rec)
        for fm in chapter.formulas:
            if fm.status in statuses:
                out.append(Record(number, fm.section, fm.id, "formula", fm.equation, fm.equation, tuple(fm.lines),
                                  fm.seed, fm.status, fm.printed, correct=fm.correct, diagnosis=fm.diagnosis,
                                  proof=fm.proof))
    return sorted(out, key=lambda r: (r.chapter, _section_key(r.section), r.lines[0] if r.lines else 0))


def errata(chapters=None, recompute: bool = True) -> list[Record]:
    """Every ``erratum`` entry (example quantities and formulas) of the given chapters (all by default).

    With ``recompute`` the "as printed" computations are run, so that ``as_printed`` says whether
    they still reproduce the book's number; without it, the recorded claim is reported.
    """
    return _records(chapters, ("erratum",), recompute)


def discrepancies(chapters=None) -> list[Record]:
    """The ``input-rounding`` and ``not-reproducible`` entries (not errors of the book)."""
    return _records(chapters, ("input-rounding", "not-reproducible"), False)


def status_counts(chapters=None) -> list[dict]:
    """Per chapter: the number of published quantities and formulas in each status."""
    from .textbook import STATUSES
    rows = []
    for number in chapters if chapters is not None else available_chapters():
        chapter = load_chapter(number)
        counts = dict.fromkeys(STATUSES, 0)
        for ex in chapter.examples:
            for q in ex.quantities:
                counts[q.status] += 1
        for fm in chapter.formulas:
            counts[fm.status] += 1
        rows.append({"chapter": number, "title": chapter.title, **counts, "total": sum(counts.values())})
    return rows


def _lines(rec: Record) -> str:
    if not rec.lines:
        return ""
    a, b = rec.lines[0], rec.lines[-1]
    return f"line {a}" if a == b else f"lines {a}–{b}"


def _math(text: str) -> str:
    return f"${text}$" if text and "$" not in text else text


def _one_line(text: str) -> str:
    return " ".join(str(text).split())


def _entry(rec: Record) -> list[str]:
    where = f"{_lines(rec)} of `{rec.seed}`" if rec.seed else _lines(rec)
    unit = f" {rec.unit}" if rec.unit and rec.unit not in rec.printed else ""
    if rec.kind == "formula":
        head = f"- **{rec.item}** (`{rec.id}`, {where})"
        printed, correct = _math(rec.printed), _math(rec.correct)
    else:
        head = f"- **{rec.item}** in *{rec.title}* (`{rec.id}`, {where})"
        printed, correct = f"{rec.printed}{unit}", f"{rec.correct}{f' {rec.unit}' if rec.unit else ''}"
    out = [head]
    if rec.status == "erratum":
        out += [f"  - printed: {printed}", f"  - correct: {correct}", f"  - diagnosis: {_one_line(rec.diagnosis)}",
                f"  - proof: {_one_line(rec.proof)}"]
        if rec.as_printed is not None:
            state = "reproduces" if rec.as_printed else "does **not** reproduce"
            value = f" ({rec.as_printed_value})" if rec.as_printed_value else ""
            out.append(f"  - the \"as printed\" computation {state} the book's number{value}")
    elif rec.status == "input-rounding":
        out += [f"  - printed: {printed}; admissible deviation ±{rec.bound:g}{unit}",
                f"  - why: {_one_line(rec.reason)}"]
    else:
        out += [f"  - printed: {printed}", f"  - why not reproducible: {_one_line(rec.reason)}"]
    return out


def _grouped(records, level: str) -> list[str]:
    lines, chapter, section = [], None, None
    for rec in records:
        if rec.chapter != chapter:
            chapter, section = rec.chapter, None
            ch = load_chapter(rec.chapter)
            lines += ["", f"{level} Chapter {rec.chapter}. {ch.title}" + (f" ({ch.title_original})" if ch.title_original else "")]
        if rec.section != section:
            section = rec.section
            lines += ["", f"{level}# §{rec.section}", ""]
        lines += _entry(rec)
    return lines


def errata_markdown(chapters=None, recompute: bool = True, heading_level: int = 2) -> str:
    """The errata as a Markdown document grouped by chapter and section, followed by the
    input-rounding and not-reproducible entries in their own sections."""
    h = "#" * heading_level
    found = errata(chapters, recompute)
    other = discrepancies(chapters)
    lines = [f"{h} Errata", ""]
    if found:
        lines.append(f"{len(found)} published number(s) or formula(s) are wrong in the book.")
        lines += _grouped(found, h + "#")
    else:
        lines.append("No erratum is recorded.")
    rounding = [r for r in other if r.status == "input-rounding"]
    missing = [r for r in other if r.status == "not-reproducible"]
    lines += ["", f"{h} Differences caused by rounded inputs", ""]
    lines += (["These are not errors: the book printed its inputs rounded, and that moves the last digit "
               "of the result by at most the stated bound."] + _grouped(rounding, h + "#")) if rounding else ["None."]
    lines += ["", f"{h} Numbers that cannot be reproduced", ""]
    lines += (["The book does not print the data these numbers were computed from."] + _grouped(missing, h + "#")
              ) if missing else ["None."]
    return "\n".join(lines).strip() + "\n"
