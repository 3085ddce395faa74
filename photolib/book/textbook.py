"""The book's published numbers as data — reader of ``textbook/chNN.toml`` and ``textbook/pages.toml``.

One TOML file per chapter (format in ``textbook/README.md``). Each ``[[example]]`` holds the
inputs as printed and one ``[[example.quantity]]`` per published number with its printed
decimals, unit and status; each ``[[formula]]`` records a printed formula checked against
sympy. This module only reads and validates; :mod:`photolib.book.verify` recomputes.

``textbook/pages.toml`` maps the line numbers of the book's OCR text (the seed) to the printed
pages of Chibunichev (2022): :func:`book_page` and :func:`page_citation` turn a seed line into
"p. 57" (exact) or "p. ≈57" (interpolated between the page anchors), :func:`source_citation`
names the other sources (papers, a thesis) that have no page anchors.
"""

from __future__ import annotations

import os
import tomllib
from dataclasses import dataclass, field
from functools import lru_cache
from importlib import resources
from pathlib import Path

from ..errors import InputError

STATUSES = ("reproduced", "input-rounding", "erratum", "transcription", "not-reproducible", "transcribed")
# The two statuses of a wrong printed value: an error of the book, and a defect of the OCR
# transcription of the source (the book itself most likely right). Both record the correct value.
WRONG_STATUSES = ("erratum", "transcription")


def textbook_dir() -> Path:
    """The folder of published numbers.

    In order: ``$PHOTOLIB_TEXTBOOK``; the ``textbook/`` folder of a source checkout (an editable
    install reads the files being edited); the copy packaged with an installed wheel
    (``photolib.book.published``, built from ``textbook/`` by ``pyproject.toml``).
    """
    env = os.environ.get("PHOTOLIB_TEXTBOOK")
    if env:
        return Path(env)
    checkout = Path(__file__).resolve().parents[2] / "textbook"
    if (checkout / "ch01.toml").is_file():
        return checkout
    packaged = Path(str(resources.files("photolib.book"))) / "published"
    if (packaged / "ch01.toml").is_file():
        return packaged
    raise FileNotFoundError("the published numbers were not found: neither a checkout's textbook/ nor "
                            "the packaged photolib.book.published; set PHOTOLIB_TEXTBOOK to the folder")


@dataclass
class Quantity:
    """One published number (or text value) with its status."""

    name: str
    printed: str
    value: object
    status: str
    decimals: int | None = None
    unit: str = ""
    bound: float | None = None          # input-rounding: the largest admissible |computed − printed|
    reason: str = ""                    # input-rounding / not-reproducible: why
    correct: object = None              # erratum / transcription: the correct value
    correct_decimals: int | None = None
    diagnosis: str = ""                 # erratum / transcription: what is wrong
    proof: str = ""                     # erratum / transcription: how it was established
    as_printed: bool = False            # erratum: the "as printed" computation reproduces the book


@dataclass
class Example:
    """A worked example, table or inline statement of the book."""

    chapter: int
    id: str
    section: str
    lines: list
    title: str
    compute: str | None
    calls: str = ""
    as_printed_compute: str | None = None
    inputs: dict = field(default_factory=dict)
    quantities: list = field(default_factory=list)
    notes: str = ""
    seed: str = ""


@dataclass
class Formula:
    """A printed formula compared with its sympy derivation."""

    chapter: int
    id: str
    section: str
    equation: str
    lines: list
    printed: str
    status: str
    compute: str
    inputs: dict = field(default_factory=dict)
    correct: str = ""
    diagnosis: str = ""
    proof: str = ""
    notes: str = ""
    seed: str = ""


@dataclass
class Chapter:
    number: int
    title: str
    title_original: str
    seed: str
    lines: list
    examples: list
    formulas: list

    def example(self, example_id: str) -> Example:
        for ex in self.examples:
            if ex.id == example_id:
                return ex
        raise KeyError(f"chapter {self.number} has no example {example_id!r}")


def _article(status: str) -> str:
    return "an erratum" if status == "erratum" else f"a {status}"


def _quantity(raw: dict, where: str) -> Quantity:
    raw = dict(raw)
    for key in ("name", "printed", "value", "status"):
        if key not in raw:
            raise InputError(f"{where}: quantity lacks {key!r}")
    if raw["status"] not in STATUSES:
        raise InputError(f"{where}: unknown status {raw['status']!r}")
    q = Quantity(**raw)
    if q.status == "input-rounding" and (q.bound is None or not q.reason):
        raise InputError(f"{where}/{q.name}: input-rounding needs 'bound' and 'reason'")
    if q.status in WRONG_STATUSES and (q.correct is None or not q.diagnosis or not q.proof):
        raise InputError(f"{where}/{q.name}: {_article(q.status)} needs 'correct', 'diagnosis' and 'proof'")
    if q.status == "not-reproducible" and not q.reason:
        raise InputError(f"{where}/{q.name}: not-reproducible needs 'reason'")
    return q


@lru_cache(maxsize=None)
def load_chapter(number: int) -> Chapter:
    """Read and validate ``textbook/chNN.toml`` and its fragments ``textbook/chNN_*.toml``.

    A chapter may be split into fragments by topic (``ch05_matching.toml`` …); their examples
    and formulas are appended, in file-name order, to those of ``chNN.toml``, which carries the
    chapter's title. Ids must be unique across all the files of a chapter.
    """
    path = textbook_dir() / f"ch{number:02d}.toml"
    if not path.exists():
        raise FileNotFoundError(f"no textbook data for chapter {number}: {path}")
    with path.open("rb") as fh:
        raw = tomllib.load(fh)
    for fragment in sorted(textbook_dir().glob(f"ch{number:02d}_*.toml")):
        with fragment.open("rb") as fh:
            part = tomllib.load(fh)
        unknown = set(part) - {"example", "formula", "seed"}
        if unknown:
            raise InputError(f"{fragment.name}: a fragment holds only examples and formulas, not {sorted(unknown)}")
        part_seed = part.get("seed")
        for kind in ("example", "formula"):
            for entry in part.get(kind, []):
                if part_seed and "seed" not in entry:
                    entry = {**entry, "seed": part_seed}
                raw.setdefault(kind, []).append(entry)
    seed = raw.get("seed", "")
    examples, seen = [], set()
    for ex in raw.get("example", []):
        where = f"{path.name}:{ex.get('id')}"
        if ex["id"] in seen:
            raise InputError(f"{where}: duplicate id")
        seen.add(ex["id"])
        quantities = [_quantity(q, where) for q in ex.get("quantity", [])]
        examples.append(Example(
            chapter=number, id=ex["id"], section=ex["section"], lines=ex["lines"], title=ex["title"],
            compute=ex.get("compute"), calls=ex.get("calls", ""), as_printed_compute=ex.get("as_printed_compute"),
            inputs=ex.get("inputs", {}), quantities=quantities, notes=ex.get("notes", ""),
            seed=ex.get("seed", seed)))
    formulas = []
    for fm in raw.get("formula", []):
        if fm["id"] in seen:
            raise InputError(f"{path.name}:{fm['id']}: duplicate id")
        seen.add(fm["id"])
        if fm["status"] not in ("reproduced", *WRONG_STATUSES):
            raise InputError(f"{path.name}:{fm['id']}: a formula is 'reproduced', 'erratum' or 'transcription'")
        if fm["status"] in WRONG_STATUSES and not (fm.get("correct") and fm.get("diagnosis") and fm.get("proof")):
            raise InputError(f"{path.name}:{fm['id']}: {_article(fm['status'])} needs 'correct', 'diagnosis' and 'proof'")
        formulas.append(Formula(chapter=number, seed=fm.get("seed", seed), **{k: v for k, v in fm.items() if k != "seed"}))
    return Chapter(number, raw["title"], raw.get("title_original", ""), seed, raw.get("lines", []), examples, formulas)


def available_chapters() -> list[int]:
    """Chapter numbers that have a ``textbook/chNN.toml``."""
    return sorted(int(p.stem[2:]) for p in textbook_dir().glob("ch[0-9][0-9].toml"))


# --- printed pages ------------------------------------------------------------------------------------
PAGE_ANCHOR_KINDS = ("heading", "number", "glued")
_ENDS_PAGE = ("number", "glued")          # the printed page number: its page ends on (or inside) that line


@dataclass(frozen=True)
class PageAnchor:
    """A seed line whose printed page is known (``textbook/pages.toml``).

    ``kind`` is ``"heading"`` (a heading listed in the book's table of contents: the line is on
    ``page``), ``"number"`` (a line holding only the printed page number: page ``page`` ends
    there) or ``"glued"`` (the page number glued into the text: page ``page`` ends inside the line).
    """

    line: int
    page: int
    kind: str
    note: str = ""


@dataclass(frozen=True)
class PageMap:
    """The page anchors of the book's seed and the names of the other sources."""

    seed: str
    anchors: tuple
    sources: dict


@lru_cache(maxsize=None)
def load_pages() -> PageMap:
    """Read and validate ``textbook/pages.toml`` (an empty map when the file is absent).

    The anchors must increase in line; their pages must not decrease, and after an anchor that
    ends a page (``"number"``, ``"glued"``) the next anchor must be on a later page.
    """
    path = textbook_dir() / "pages.toml"
    if not path.exists():
        return PageMap("", (), {})
    with path.open("rb") as fh:
        raw = tomllib.load(fh)
    anchors = []
    for i, a in enumerate(raw.get("anchor", [])):
        try:
            anchor = PageAnchor(int(a["line"]), int(a["page"]), a["kind"], a.get("note", ""))
        except KeyError as missing:
            raise InputError(f"pages.toml: anchor {i + 1} lacks {missing}") from None
        if anchor.kind not in PAGE_ANCHOR_KINDS:
            raise InputError(f"pages.toml: anchor at line {anchor.line} has unknown kind {anchor.kind!r} "
                             f"(one of {', '.join(PAGE_ANCHOR_KINDS)})")
        if anchors:
            prev = anchors[-1]
            later = prev.page + 1 if prev.kind in _ENDS_PAGE else prev.page
            if anchor.line <= prev.line or anchor.page < later:
                raise InputError(f"pages.toml: anchor line {anchor.line} → p. {anchor.page} does not follow "
                                 f"line {prev.line} → p. {prev.page} ({prev.kind}): lines must increase and "
                                 "pages must not go back")
        anchors.append(anchor)
    sources = {seed: {"name": s.get("name", seed), "sections": bool(s.get("sections", False)),
                      "key": s.get("key", "")}
               for seed, s in raw.get("source", {}).items()}
    keys = [s["key"] for s in sources.values() if s["key"]]
    if len(keys) != len(set(keys)):
        raise InputError(f"pages.toml: the source keys must be unique, got {keys}")
    return PageMap(raw.get("seed", ""), tuple(anchors), sources)


def book_page(line: int) -> tuple[int, bool]:
    """The printed page of Chibunichev (2022) on which a line of its OCR text (the seed) stands.

    Between the page anchors of ``textbook/pages.toml`` (headings of the table of contents and
    the page numbers the OCR kept) the page is bounded below by the last anchor before the line
    and above by the next one; when both bounds agree the page is ``exact``. Otherwise it is the
    linear interpolation between the two anchors (a heading counted in the middle of its page, a
    printed page number at the end of its page), kept within the bounds, and ``exact`` is False:
    cite it as "p. ≈N".

    Parameters
    ----------
    line : int
        1-based line of the seed named in ``textbook/pages.toml`` (``000_0363cf98558e0ca3.txt``).

    Returns
    -------
    (page, exact) : tuple of int and bool

    Raises
    ------
    InputError
        If ``line`` is not a positive integer or lies outside the lines the anchors cover.

    References
    ----------
    The anchors: the contents of the book (seed lines 6970 ff.) and the page numbers printed in the
    text (e.g. "19" at seed line 429); see the header of ``textbook/pages.toml``.

    Examples
    --------
    >>> book_page(410)          # the heading of §1.5, p. 19 in the contents
    (19, True)
    >>> book_page(420)          # between §1.5 (p. 19) and the printed "19" at line 429
    (19, True)
    >>> book_page(500)          # between §1.7 (p. 21) and §1.8 (p. 23)
    (22, False)
    """
    if isinstance(line, bool) or not isinstance(line, int) or line < 1:
        raise InputError(f"line must be a positive integer (a line of the seed), got {line!r}")
    anchors = load_pages().anchors
    if not anchors:
        raise InputError("no page anchors: textbook/pages.toml is missing or empty")
    if not anchors[0].line <= line <= anchors[-1].line:
        raise InputError(f"line {line} is outside the lines the page anchors cover "
                         f"({anchors[0].line}–{anchors[-1].line})")
    before = [a for a in anchors if a.line <= line]
    after = [a for a in anchors if a.line >= line]
    low = max(a.page if a.line == line or a.kind not in _ENDS_PAGE else a.page + 1 for a in before)
    high = min(a.page for a in after)
    if low >= high:
        return high, True
    a, b = before[-1], after[0]
    position = lambda x: x.page + (1.0 if x.kind in _ENDS_PAGE else 0.5)  # noqa: E731
    estimate = position(a) + (line - a.line) / (b.line - a.line) * (position(b) - position(a))
    return min(max(int(estimate), low), high), False


def source_seeds() -> dict[str, str]:
    """The source keys of ``textbook/pages.toml`` and the seed file each selects.

    Entries filed under the book's chapters may come from other texts (the GNSS-centres paper,
    Hanzl's study text, the MRF paper, Sementsov's thesis); ``photolib verify --source KEY``
    selects the entries of one of them.

    Examples
    --------
    >>> source_seeds()["hanzl"]
    '002_d5f7929691601478.txt'
    """
    return {s["key"]: seed for seed, s in load_pages().sources.items() if s["key"]}


def page_citation(lines) -> str:
    """"p. 19", "p. ≈22" or "pp. ≈22–23" for a seed line or a (first, last) line range.

    Examples
    --------
    >>> page_citation([410, 420])
    'p. 19'
    >>> page_citation(500)
    'p. ≈22'
    """
    first, last = (lines, lines) if isinstance(lines, int) else (lines[0], lines[-1])
    (p1, exact1), (p2, exact2) = book_page(first), book_page(last)
    mark = "" if exact1 and exact2 else "≈"
    return f"p. {mark}{p1}" if p1 == p2 else f"pp. {mark}{p1}–{p2}"
