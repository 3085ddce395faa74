"""Glossary of the photogrammetric terms, Russian · English · Czech — reader of ``textbook/glossary.toml``.

The appendix "Glossary (Russian · English · Czech)" of the book: the terms of Chibunichev's textbook
(chapters 1–11) and of Hanzl's Czech study text (sections 1–14), each with the section and seed line
where it first appears in each text. The data are in ``textbook/glossary.toml`` (format and the rule
for "first appears" in its header); this module only reads, searches and tabulates them.
"""

from __future__ import annotations

import re
import tomllib
from dataclasses import dataclass
from functools import lru_cache

from ..errors import InputError
from .textbook import textbook_dir

__all__ = ["Term", "terms", "lookup", "glossary_table"]

_REQUIRED = ("en", "ru", "ru_section", "ru_line")
_CZECH = ("cs", "cs_section", "cs_line")
_KEYS = set(_REQUIRED) | set(_CZECH) | {"note"}
_SECTION = re.compile(r"intro|\d{1,2}(\.\d{1,2}){0,3}")


@dataclass(frozen=True)
class Term:
    """One glossary entry: an English term with its Russian and (where Hanzl uses it) Czech form.

    Parameters
    ----------
    en : str
        The English term (our words).
    ru : str
        The Russian term as the textbook prints it, in the nominative.
    ru_section : str
        The textbook's § where it first appears (``"1.2"``; ``"6"`` for the opening of chapter 6
        before its first §; ``"intro"`` for the introduction).
    ru_line : int
        Seed line of that first appearance (seed ``000_0363cf98558e0ca3.txt``).
    cs, cs_section, cs_line : str, str, int or None
        The same for Hanzl's text (seed ``002_d5f7929691601478.txt``); ``None`` if he does not use
        the term.
    note : str
        A different meaning, a false friend or an abbreviation; may be empty.

    References
    ----------
    Chibunichev, *Фотограмметрия* (2022), all chapters; Hanzl, *Fotogrammetrie, modul 01*, §1–§14.

    Examples
    --------
    >>> t = lookup("principal point")[0]
    >>> t.ru, t.ru_section, t.cs
    ('главная точка снимка', '1.1', 'hlavní bod snímku')
    """

    en: str
    ru: str
    ru_section: str
    ru_line: int
    cs: str | None = None
    cs_section: str | None = None
    cs_line: int | None = None
    note: str = ""


def _entry(raw: dict, index: int) -> Term:
    where = f"textbook/glossary.toml, [[term]] number {index + 1} ({raw.get('en', '?')!r})"
    missing = [k for k in _REQUIRED if k not in raw]
    if missing:
        raise InputError(f"{where}: missing key(s) {missing}")
    unknown = sorted(set(raw) - _KEYS)
    if unknown:
        raise InputError(f"{where}: unknown key(s) {unknown}")
    czech = [k for k in _CZECH if k in raw]
    if czech and len(czech) != len(_CZECH):
        raise InputError(f"{where}: the Czech keys come together ({list(_CZECH)}), found only {czech}")
    for key in ("ru_section", "cs_section"):
        if key in raw and not _SECTION.fullmatch(str(raw[key])):
            raise InputError(f"{where}: {key} = {raw[key]!r} is not a section such as '1.2' or 'intro'")
    for key in ("ru_line", "cs_line"):
        if key in raw and (not isinstance(raw[key], int) or raw[key] < 1):
            raise InputError(f"{where}: {key} = {raw[key]!r} is not a seed line number")
    return Term(**raw)


@lru_cache(maxsize=None)
def terms() -> tuple[Term, ...]:
    """Every glossary entry, in the order of ``textbook/glossary.toml`` (grouped by topic).

    Returns
    -------
    tuple of Term

    Raises
    ------
    InputError
        If an entry lacks a required key, has an unknown key or a malformed section or line, or if
        an English term occurs twice.

    References
    ----------
    ``textbook/glossary.toml``; the sources are Chibunichev's textbook and Hanzl's module 01.

    Examples
    --------
    >>> all_terms = terms()
    >>> 150 <= len(all_terms) <= 250
    True
    >>> all_terms[0].en, all_terms[0].ru, all_terms[0].cs
    ('photogrammetry', 'фотограмметрия', 'fotogrammetrie')
    """
    raw = tomllib.loads((textbook_dir() / "glossary.toml").read_text(encoding="utf-8"))
    entries = tuple(_entry(e, i) for i, e in enumerate(raw.get("term", [])))
    seen = set()
    for t in entries:
        key = t.en.casefold()
        if key in seen:
            raise InputError(f"textbook/glossary.toml: the English term {t.en!r} occurs twice")
        seen.add(key)
    return entries


def _fold(text: str) -> str:
    return text.casefold().replace("ё", "е")


def lookup(word: str) -> list[Term]:
    """The entries whose English, Russian or Czech term contains ``word``.

    Case-insensitive substring search over the three languages (``ё`` is read as ``е``); the notes
    are not searched.

    Parameters
    ----------
    word : str
        Any part of a term in any of the three languages, e.g. ``"parallax"``, ``"засечка"``,
        ``"vlícovací"``.

    Returns
    -------
    list of Term
        In glossary order; empty if nothing matches.

    Raises
    ------
    InputError
        If ``word`` is not a string or is blank.

    References
    ----------
    ``textbook/glossary.toml``.

    Examples
    --------
    >>> [t.en for t in lookup("ПАРАЛЛАКС")]
    ['parallax', 'x-parallax (longitudinal parallax)', 'y-parallax (transverse parallax)']
    >>> [t.ru for t in lookup("vlícovací bod")]
    ['опорная точка', 'плановая опорная точка', 'высотная опорная точка', 'планово-высотная опорная точка']
    """
    if not isinstance(word, str):
        raise InputError(f"lookup needs a string, got {type(word).__name__}")
    if not word.strip():
        raise InputError("lookup needs a non-blank word")
    needle = _fold(word.strip())
    return [t for t in terms() if any(needle in _fold(s) for s in (t.en, t.ru, t.cs or ""))]


def _where(section: str) -> str:
    return "introduction" if section == "intro" else f"§{section}"


def glossary_table(letter: str | None = None, with_notes: bool = False):
    """The glossary as a table English · Russian (§) · Czech (§), sorted by the English term.

    Parameters
    ----------
    letter : str, optional
        Only the terms whose English form begins with this letter (case-insensitive); all terms if
        omitted.
    with_notes : bool, default False
        Add a fourth column with the entry's note.

    Returns
    -------
    photolib.book.verify.Table
        One row per term; a term Hanzl does not use shows "—" in the Czech column.

    Raises
    ------
    InputError
        If ``letter`` is not a single letter, or no English term begins with it.

    References
    ----------
    ``textbook/glossary.toml``; sections are the textbook's § and Hanzl's numbered sections.

    Examples
    --------
    >>> table = glossary_table("q")
    >>> table.header
    ['English', 'Russian (§)', 'Czech (§)']
    >>> table.rows
    [['quaternion', 'кватернион (§1.3)', '—']]
    """
    from .verify import Table

    chosen = terms()
    if letter is not None:
        if not isinstance(letter, str) or len(letter) != 1 or not letter.isalpha():
            raise InputError(f"letter must be a single letter, got {letter!r}")
        chosen = [t for t in chosen if t.en[:1].casefold() == letter.casefold()]
        if not chosen:
            raise InputError(f"no English term of the glossary begins with {letter!r}")
    rows = []
    for t in sorted(chosen, key=lambda t: t.en.casefold()):
        row = [t.en, f"{t.ru} ({_where(t.ru_section)})",
               f"{t.cs} ({_where(t.cs_section)})" if t.cs else "—"]
        rows.append(row + ([t.note or ""] if with_notes else []))
    header = ["English", "Russian (§)", "Czech (§)"] + (["Note"] if with_notes else [])
    title = f"Glossary: {letter.upper()}" if letter is not None else "Glossary"
    return Table(header, rows, title)
