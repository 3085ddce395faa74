"""The book's errata, generated from ``textbook/`` — the source of Appendix B of the companion.

Nothing here is hard-coded: every record comes from an entry of ``textbook/chNN.toml`` (read with
:mod:`photolib.book.textbook`) whose status is

* ``erratum`` — an ``[[example.quantity]]`` or a ``[[formula]]`` the book gets wrong; the record
  holds what is printed, what is correct, the diagnosis and how it was proved, and — for examples
  with an "as printed" computation — whether that computation reproduces the printed number;
* ``transcription`` — the same for a number or formula that the OCR transcription of the source
  lost or garbled while the book itself is (most likely) right;
* ``input-rounding`` — a number off in its last digit only because the book rounded its inputs
  (with the admissible bound and its justification);
* ``not-reproducible`` — a number the book does not give the data for (with the reason).

Each record is cited by § and printed page of Chibunichev (2022) ("§1.8, p. ≈24", from the page
anchors of ``textbook/pages.toml``), or by source and section for the other sources; the seed lines
come second. :func:`errata` and :func:`discrepancies` return the records, :func:`group_records`
collects the quantities (or the formulas) of one § that share their diagnosis,
:func:`errata_markdown` renders the appendix (one table per chapter, each diagnosis written once in
a collapsible block), :func:`status_counts` the per-chapter summary.
"""

from __future__ import annotations

import html
import re
from dataclasses import dataclass, field

from ..errors import InputError
from .textbook import WRONG_STATUSES, available_chapters, load_chapter, load_pages, page_citation


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
    correct: str = ""          # erratum / transcription: the correct value / formula
    diagnosis: str = ""
    proof: str = ""
    bound: float | None = None  # input-rounding
    reason: str = ""           # input-rounding / not-reproducible
    as_printed: bool | None = None        # erratum with an "as printed" computation: does it reproduce the book?
    as_printed_value: str = ""            # ... and what it computes
    where: str = ""            # the citation: "§1.8, p. ≈24" or the source and its section

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


def citation(seed: str, section: str, lines) -> str:
    """Where an entry is: "§1.8, p. ≈24" in the book; "Sementsov, PhD thesis (2019), §2.1" or
    "Dobrynin & Pimshina, GNSS-centres paper" for the other sources (``textbook/pages.toml``);
    just the § when the seed has neither page anchors nor a source name."""
    pages = load_pages()
    section = str(section)
    if seed and seed == pages.seed and pages.anchors and lines:
        try:
            return f"§{section}, {page_citation(list(lines))}"
        except InputError:                     # a line outside the anchored range
            return f"§{section}"
    source = pages.sources.get(seed)
    if source is None:
        return f"§{section}"
    if not source["sections"]:
        return source["name"]
    first = source["name"].split(",")[0].split()[0]
    own = section[len(first):].strip() if section.startswith(first) else section
    return f"{source['name']}, {'§' if own[:1].isdigit() else ''}{own}"


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
                             q.status, q.printed, q.unit, bound=q.bound, reason=q.reason,
                             where=citation(ex.seed, ex.section, ex.lines))
                if q.status in WRONG_STATUSES:
                    rec.correct, rec.diagnosis, rec.proof = _value_text(q), q.diagnosis, q.proof
                    if q.as_printed:
                        value, ok = runs.get(q.name, ("", None))
                        rec.as_printed, rec.as_printed_value = (ok if recompute else True), value
                out.append(rec)
        for fm in chapter.formulas:
            if fm.status in statuses:
                out.append(Record(number, fm.section, fm.id, "formula", fm.equation, fm.equation, tuple(fm.lines),
                                  fm.seed, fm.status, fm.printed, correct=fm.correct, diagnosis=fm.diagnosis,
                                  proof=fm.proof, where=citation(fm.seed, fm.section, fm.lines)))
    return sorted(out, key=lambda r: (r.chapter, _section_key(r.section), r.lines[0] if r.lines else 0))


def errata(chapters=None, recompute: bool = True, statuses=WRONG_STATUSES) -> list[Record]:
    """Every ``erratum`` and ``transcription`` entry (example quantities and formulas) of the given
    chapters (all by default); ``Record.status`` tells the two kinds apart.

    With ``recompute`` the "as printed" computations are run, so that ``as_printed`` says whether
    they still reproduce the book's number; without it, the recorded claim is reported.
    ``statuses`` selects one kind, e.g. ``("erratum",)``.
    """
    unknown = set(statuses) - set(WRONG_STATUSES)
    if unknown:
        raise InputError(f"statuses must be among {WRONG_STATUSES}, got {sorted(unknown)}")
    return _records(chapters, tuple(statuses), recompute)


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


# --- grouping: one diagnosis for the entries that share it -----------------------------------------------
_ABBREVIATIONS = ("e.g.", "i.e.", "cf.", "Fig.", "Figs.", "Eq.", "eq.", "No.", "vs.", "al.", "Sec.", "p.", "pp.",
                  "App.", "etc.", "approx.", "resp.")
SHARED_CLAUSE = 40        # a group shares at least one clause this long (or the whole text) ...
SHARED_PART = 0.35        # ... and its shared clauses make up this part of each text


def _clauses(text: str) -> list[str]:
    """The sentences and colon/semicolon clauses of a text, split outside parentheses."""
    text = " ".join(str(text).split())
    out, depth, start = [], 0, 0
    for i, ch in enumerate(text):
        if ch in "([{":
            depth += 1
        elif ch in ")]}":
            depth = max(depth - 1, 0)
        elif ch in ".;:" and depth == 0 and i + 1 < len(text) and text[i + 1] == " ":
            piece = text[start:i + 1]
            if ch == "." and (piece.endswith(_ABBREVIATIONS) or re.search(r"\b[A-Za-z]\.$", piece)):
                continue
            out.append(piece.strip())
            start = i + 2
    if text[start:].strip():
        out.append(text[start:].strip())
    return out


@dataclass
class Group:
    """Records of one § (quantities, or formulas) with one status that share their diagnosis.

    ``common`` is the text every record shares ("…" where a record has clauses of its own),
    ``notes[i]`` the clauses of ``records[i]`` that are not shared; the same for the proofs.
    """

    records: list
    common: str = ""
    notes: list = field(default_factory=list)
    common_proof: str = ""
    proof_notes: list = field(default_factory=list)

    @property
    def first(self) -> Record:
        return self.records[0]

    @property
    def status(self) -> str:
        return self.first.status

    @property
    def lines(self) -> tuple:
        starts = [r.lines[0] for r in self.records if r.lines]
        ends = [r.lines[-1] for r in self.records if r.lines]
        return (min(starts), max(ends)) if starts else ()

    @property
    def where(self) -> str:
        sections = list(dict.fromkeys(r.section for r in self.records))
        where = citation(self.first.seed, sections[0], self.lines)
        if len(sections) > 1 and where.startswith(f"§{sections[0]}"):
            where = ", ".join(f"§{s}" for s in sections) + where[len(sections[0]) + 1:]
        return where

    @property
    def label(self) -> str:
        """"(1.8.3) a1 … b6 (11 formulas)", "Xs, Ys" or the one item."""
        items = list(dict.fromkeys(r.item for r in self.records))
        if len(items) <= 3:
            return ", ".join(items)
        prefix = _common_prefix(items)
        noun = "formulas" if self.first.kind == "formula" else "values"
        return f"{items[0]} … {items[-1][len(prefix):]} ({len(items)} {noun})"


def _common_prefix(items) -> str:
    """The longest common prefix of the items that ends with a space (a whole word)."""
    prefix = items[0]
    for item in items[1:]:
        while not item.startswith(prefix):
            prefix = prefix[:-1]
    return prefix[:prefix.rfind(" ") + 1] if " " in prefix else ""


def _factor(texts) -> tuple[str, list[str]]:
    """(shared text with "…" for the clauses of one's own, the own clauses of each text)."""
    split = [_clauses(t) for t in texts]
    common = [c for c in split[0] if all(c in s for s in split[1:])] if len(split) > 1 else split[0]
    shown, gap = [], False
    for c in split[0]:
        if c in common:
            if gap and shown:
                shown.append("…")
            shown.append(c)
            gap = False
        else:
            gap = True
    own = [" ".join(c for c in s if c not in common) for s in split]
    return " ".join(shown), own


def _joins(group_clauses: list, text: str, whole: str) -> list | None:
    """The clauses still shared if ``text`` joins a group (whose first text is ``whole``), or None."""
    if text == whole:
        return group_clauses
    clauses = _clauses(text)
    shared = [c for c in group_clauses if c in clauses]
    size = sum(len(c) + 1 for c in shared)
    if any(len(c) >= SHARED_CLAUSE for c in shared) and size >= SHARED_PART * max(len(text), len(whole)):
        return shared
    return None


def group_records(records, by: str = "example") -> list[Group]:
    """Collect records that share their diagnosis (or, for discrepancies, their reason).

    ``by="example"`` groups the quantities (of the worked examples) or the formulas of one § (of one
    chapter, status and seed); ``by="chapter"`` all records of a chapter, status and seed. Records join
    a group when they share at least one clause of ``SHARED_CLAUSE`` characters with every member
    and these shared clauses make up ``SHARED_PART`` of both texts (or when the texts are equal);
    the groups keep the order of the records.
    """
    if by not in ("example", "chapter"):
        raise InputError(f"by must be 'example' or 'chapter', got {by!r}")
    buckets, groups = {}, []
    for rec in records:
        text = rec.diagnosis or rec.reason
        if by == "chapter":
            key = (rec.chapter, rec.status, rec.seed)
        else:
            key = (rec.chapter, rec.status, rec.kind, rec.seed, rec.section)
        for entry in buckets.setdefault(key, []):
            shared = _joins(entry["clauses"], text, entry["text"])
            if shared is not None:
                entry["clauses"] = shared
                entry["group"].records.append(rec)
                break
        else:
            group = Group([rec])
            buckets[key].append({"clauses": _clauses(text), "text": text, "group": group})
            groups.append(group)
    for group in groups:
        group.common, group.notes = _factor([r.diagnosis or r.reason for r in group.records])
        group.common_proof, group.proof_notes = _factor([r.proof for r in group.records])
    return groups


# --- Markdown (MyST) -------------------------------------------------------------------------------------
_MD_SPECIAL = re.compile(r"([\\`*_{}\[\]<>#|$~&])")


def _md(text: str) -> str:
    """Plain text for MyST Markdown: one line, every character that could start markup escaped
    (``*`` and ``_`` of Z* or x_0, ``$`` that would open mathematics, ``|`` of a table)."""
    return _MD_SPECIAL.sub(r"\\\1", " ".join(str(text).split()))


def _is_prose(text: str) -> bool:
    """A formula field that is a remark, not LaTeX (e.g. "(lost in the OCR: …)")."""
    return bool(re.match(r"^\((lost|not printed|missing)\b", text.strip()))


def _math_cell(latex: str) -> str:
    """Inline mathematics that survives a table cell: | becomes \\vert (a table would split at |)."""
    if not latex:
        return ""
    if _is_prose(latex):
        return _md(latex)
    tex = " ".join(latex.split()).replace("\\|", "\\Vert ").replace("|", "\\vert ")
    return f"${tex}$"


def _display_math(latex: str) -> str:
    if _is_prose(latex):
        return _md(latex)
    return "$$\n" + " ".join(latex.split()) + "\n$$"


def _cell(text: str) -> str:
    return _md(text)


_SHORT_FORMULA = 60       # a formula this long or shorter is shown in the chapter table itself


def _values(rec: Record) -> tuple[str, str]:
    """(printed, correct) cells of a record."""
    if rec.kind == "formula":
        return _math_cell(rec.printed), _math_cell(rec.correct)
    unit = f" {rec.unit}" if rec.unit and rec.unit not in rec.printed else ""
    correct = f"{rec.correct} {rec.unit}" if rec.unit and rec.correct else rec.correct
    return _cell(f"{rec.printed}{unit}"), _cell(correct)


def _table(header, rows) -> list[str]:
    return (["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
            + ["| " + " | ".join(r) + " |" for r in rows])


def _source_line(group: Group) -> str:
    seed, lines = group.first.seed, group.lines
    span = "" if not lines else f", line {lines[0]}" if lines[0] == lines[1] else f", lines {lines[0]}–{lines[1]}"
    ids = ", ".join(f"`{i}`" for i in dict.fromkeys(r.id for r in group.records))
    return f"OCR source: `{seed}`{span}; textbook/ entry {ids}." if seed else f"textbook/ entry {ids}."


def _as_printed_text(rec: Record) -> str:
    if rec.as_printed is None:
        return ""
    state = "reproduces" if rec.as_printed else "does not reproduce"
    value = f" ({rec.as_printed_value})" if rec.as_printed_value else ""
    return f"The \"as printed\" computation {state} the book's number{value}."


def _kind(status: str) -> str:
    return "**transcription**" if status == "transcription" else "erratum"


def _chapter_heading(number: int, level: str) -> str:
    ch = load_chapter(number)
    return f"{level} Chapter {number}. {ch.title}" + (f" ({ch.title_original})" if ch.title_original else "")


def _details(group: Group) -> list[str]:
    """The collapsible block of a group: the diagnosis once, the values of its members, the proof once."""
    summary = html.escape(f"{group.where} · {group.label}: diagnosis and proof", quote=False)
    out = ["", "<details>", f"<summary>{summary}</summary>", ""]
    single = len(group.records) == 1
    rec = group.first
    out += [f"**Diagnosis.** {_md(group.common)}", ""]
    if single:
        if rec.kind == "formula" and (len(rec.printed) > _SHORT_FORMULA or len(rec.correct) > _SHORT_FORMULA):
            out += ["Printed (as the OCR gives it):", "", _display_math(rec.printed), "", "Correct:", "",
                    _display_math(rec.correct), ""]
        extra = " ".join(t for t in (group.notes[0], _as_printed_text(rec)) if t)
        if extra:
            out += [_md(extra), ""]
    else:
        rows, previous = [], None
        with_runs = any(r.as_printed is not None for r in group.records)
        for r, note, pnote in zip(group.records, group.notes, group.proof_notes):
            printed, correct = _values(r)
            run = ([_cell(r.as_printed_value + (" ✓" if r.as_printed else " ✗")) if r.as_printed is not None else ""]
                   if with_runs else [])
            text = " ".join(t for t in (note, f"Proof: {pnote}" if pnote else "") if t)
            if rows and rows[-1][1:3 + len(run)] == [printed, correct, *run] and text == previous:
                rows[-1][0] += ", " + _cell(r.item)          # the same values and note: one row
                continue
            rows.append([_cell(r.item), printed, correct, *run, "as above" if text and text == previous else _md(text)])
            previous = text
        header = ["", "printed", "correct"] + (["as printed"] if with_runs else []) + ["note"]
        out += _table(header, rows) + [""]
        if with_runs:
            out += ["*As printed*: what the book's own (flawed) computation, repeated by photolib, gives; ✓ where it "
                    "reproduces the printed number.", ""]
    if group.common_proof:
        out += [f"**Proof.** {_md(group.common_proof)}", ""]
    if single and group.proof_notes[0] and group.proof_notes[0] != group.common_proof:
        out += [_md(group.proof_notes[0]), ""]
    out += [_source_line(group), "", "</details>"]
    return out


def _errata_chapter(groups, level: str) -> list[str]:
    rows, blocks, title = [], [], None
    for g in groups:
        rec = g.first
        values = {_values(r) for r in g.records}
        if len(values) == 1 and not (rec.kind == "formula" and (len(rec.printed) > _SHORT_FORMULA
                                                                 or len(rec.correct) > _SHORT_FORMULA)):
            printed, correct = values.pop()            # one value (or all members print the same)
        else:
            printed = correct = "see below"
        label = _cell(g.label)
        titles = list(dict.fromkeys(r.title for r in g.records if r.kind == "quantity" and r.title))
        if titles:
            label += " — same example" if titles == [title] else f" — {_cell('; '.join(titles))}"
            title = titles[-1]
        rows.append([_cell(g.where), label, printed, correct, _kind(g.status)])
        blocks += _details(g)
    return ["", _chapter_heading(groups[0].first.chapter, level), ""] + _table(
        ["§ · page", "equation / quantity", "printed", "correct", "kind"], rows) + blocks


def _discrepancy_chapter(groups, level: str) -> list[str]:
    out = ["", _chapter_heading(groups[0].first.chapter, level), ""]
    for g in groups:
        n = len(g.records)
        values = []
        for r, note in zip(g.records, g.notes):
            unit = f" {r.unit}" if r.unit and r.unit not in r.printed else ""
            bound = f" ±{r.bound:g}{unit}" if r.bound is not None else ""
            own = f" ({note})" if note else ""
            values.append(f"{r.item} = {r.printed}{unit}{bound}{own}")
        head = f"{g.where} — {n} value{'s' if n > 1 else ''}"
        label = "printed, admissible deviation" if g.status == "input-rounding" else "printed"
        out.append(f"- **{_md(head)}.** {_md(g.common)} *Values ({label}):* {_md('; '.join(values))}.")
    return out


def errata_markdown(chapters=None, recompute: bool = True, heading_level: int = 2) -> str:
    """The errata as MyST Markdown: per chapter one table (§ · page, equation/quantity, printed,
    correct, kind), then one collapsible ``<details>`` block per row with its diagnosis and proof,
    written once for the entries that share them; then the input-rounding and not-reproducible
    entries, one paragraph per shared reason."""
    h = "#" * heading_level
    found = errata(chapters, recompute)
    other = discrepancies(chapters)
    groups = group_records(found)
    lines = [f"{h} Errata", ""]
    if found:
        wrong = sum(r.status == "erratum" for r in found)
        lost = len(found) - wrong
        lines.append(f"{len(found)} published numbers or formulas are wrong as the OCR text gives them: {wrong} "
                     f"errors of the book (*erratum*) and {lost} defects of the OCR transcription (**transcription**: "
                     f"the source lost or garbled them, the book is most likely right), in {len(groups)} rows. "
                     "Pages are those of the printed book (\"p. ≈N\": interpolated between the page numbers the OCR "
                     "kept); open a row's block for its diagnosis, proof and OCR lines.")
        for number in dict.fromkeys(g.first.chapter for g in groups):
            lines += _errata_chapter([g for g in groups if g.first.chapter == number], h + "#")
    else:
        lines.append("No erratum is recorded.")
    rounding = group_records([r for r in other if r.status == "input-rounding"], by="chapter")
    missing = group_records([r for r in other if r.status == "not-reproducible"], by="chapter")
    lines += ["", f"{h} Differences caused by rounded inputs", ""]
    if rounding:
        lines.append("These are not errors: the book printed its inputs rounded, and that moves the last digit "
                     "of the result by at most the stated bound. One paragraph per shared justification.")
        for number in dict.fromkeys(g.first.chapter for g in rounding):
            lines += _discrepancy_chapter([g for g in rounding if g.first.chapter == number], h + "#")
    else:
        lines.append("None.")
    lines += ["", f"{h} Numbers that cannot be reproduced", ""]
    if missing:
        lines.append("The book does not print the data these numbers were computed from.")
        for number in dict.fromkeys(g.first.chapter for g in missing):
            lines += _discrepancy_chapter([g for g in missing if g.first.chapter == number], h + "#")
    else:
        lines.append("None.")
    return "\n".join(lines).strip() + "\n"
