"""The glossary (textbook/glossary.toml): well-formed entries, and each term's first appearance
in the two source texts is where the glossary says it is.

"First appears" is checked with one tolerance rule for every term (no per-term exceptions), needed
because Russian and Czech inflect and the OCR is imperfect:

* the text proper is searched: for the textbook from "ВВЕДЕНИЕ" to its table of contents at the
  end (title page, imprint and preface skipped); for Hanzl from "1 Úvod" after his table of
  contents to the end;
* a term occurs on a line when its words occur there in order, separated only by spaces or
  brackets, each word matched by its stem: the word without one inflectional ending (the longest
  of a fixed list that leaves at least 3 letters), with an е/о (ru) or e (cs) before the stem's
  last consonant optional (fleeting vowels: снимок/снимка, точка/точек, snímek/snímku), followed
  by any letters; a word in capitals, with digits, or in Latin letters inside a Russian term
  (ЦМР, RPC-коэффициенты, SIFT) matches as a whole word;
* case is ignored, ё counts as е, ``*`` and ``_`` (OCR emphasis) are dropped; Czech is compared
  without diacritics, since the OCR drops and swaps them ("vlíčovací" for "vlícovací").

The term must occur on its recorded line and on no earlier line of the text proper, and the
recorded section must be the one that contains the line.
"""

import re
import unicodedata
from pathlib import Path

import pytest

from photolib.book import glossary
from photolib.book.glossary import Term, glossary_table, lookup, terms
from photolib.errors import InputError

SEEDS = Path(__file__).resolve().parents[3] / "shared" / "seeds"
RU_SEED = SEEDS / "000_0363cf98558e0ca3.txt"
CS_SEED = SEEDS / "002_d5f7929691601478.txt"
needs_seeds = pytest.mark.skipif(not (RU_SEED.is_file() and CS_SEED.is_file()),
                                 reason=f"the OCR seeds of the two texts are not in {SEEDS} (beside the checkout)")

SECTION = re.compile(r"intro|\d{1,2}(\.\d{1,2}){0,3}")

# ---- the tolerance rule ---------------------------------------------------------------------------

RU_ENDINGS = ("ыми", "ого", "ему", "ими", "ых", "их", "ый", "ий", "ой", "ая", "яя", "ое", "ее", "ые", "ие",
              "ия", "ья", "ам", "ом", "ем", "ов", "ев", "ей", "а", "я", "о", "е", "ь", "ы", "и", "й", "у", "ю")
CS_ENDINGS = ("ého", "ému", "ých", "ými", "ími", "ích", "ý", "á", "é", "í", "a", "e", "i", "o", "u", "y", "ů", "ě")
RU_VOWELS, CS_VOWELS = "аеёиоуыэюя", "aeiouy"


def strip_accents(text: str) -> str:
    return "".join(c for c in unicodedata.normalize("NFD", text) if not unicodedata.combining(c))


def normalise(text: str, lang: str) -> str:
    text = text.lower().replace("*", "").replace("_", "")
    return text.replace("ё", "е") if lang == "ru" else strip_accents(unicodedata.normalize("NFC", text))


def word_pattern(word: str, lang: str) -> str:
    whole = (any(c.isdigit() for c in word) or (len(word) >= 2 and word.isupper())
             or (lang == "ru" and re.search("[a-zA-Z]", word)))
    if whole:
        return r"(?<!\w)" + re.escape(normalise(word, lang)) + r"(?!\w)"
    lower = word.lower().replace("ё", "е") if lang == "ru" else unicodedata.normalize("NFC", word.lower())
    stem = lower
    for ending in sorted(RU_ENDINGS if lang == "ru" else CS_ENDINGS, key=len, reverse=True):
        if lower.endswith(ending) and len(lower) - len(ending) >= 3:
            stem = lower[: -len(ending)]
            break
    if lang == "cs":
        stem = strip_accents(stem)
    vowels, fleeting = (RU_VOWELS, "ео") if lang == "ru" else (CS_VOWELS, "e")
    pattern = re.escape(stem)
    if len(stem) >= 4 and stem[-1] not in vowels + "ь":
        head, last = stem[:-1], stem[-1]
        if head[-1] in fleeting and head[-2] not in vowels:          # снимок → сним[ео]?к
            pattern = re.escape(head[:-1]) + f"[{fleeting}]?" + re.escape(last)
        elif head[-1] not in vowels + "ьй":                           # точка → точ[ео]?к
            pattern = re.escape(head) + f"[{fleeting}]?" + re.escape(last)
    return r"(?<!\w)" + pattern + r"\w*"


def term_pattern(term: str, lang: str) -> re.Pattern:
    return re.compile(r"[\s()]+".join(word_pattern(w, lang) for w in term.split()))


def test_the_rule_on_known_forms():
    assert term_pattern("снимок", "ru").search(normalise("по снимкам", "ru"))
    assert term_pattern("опорная точка", "ru").search(normalise("опорных точек", "ru"))
    assert term_pattern("ЦМР", "ru").search(normalise("получается ЦМР.", "ru"))
    assert not term_pattern("ЦМР", "ru").search(normalise("ЦМРЫ", "ru"))
    assert term_pattern("vlícovací bod", "cs").search(normalise("tři vlíčovací body", "cs"))
    assert term_pattern("snímek", "cs").search(normalise("digitálních snímků", "cs"))
    assert term_pattern("homologické paprsky", "cs").search(normalise("(homologické) paprsky", "cs"))
    assert not term_pattern("опорная точка", "ru").search(normalise("точка опорная", "ru"))      # order counts


# ---- the two texts ----------------------------------------------------------------------------------

def read(path: Path, lang: str) -> list[str]:
    lines = path.read_text(encoding="utf-8").split("\n")
    return [unicodedata.normalize("NFC", line) for line in lines] if lang == "cs" else lines


@pytest.fixture(scope="module")
def textbook():
    """(lines, first line of the text proper, last line, {line: section})."""
    lines = read(RU_SEED, "ru")
    start = next(i for i, line in enumerate(lines, 1) if line.strip() == "ВВЕДЕНИЕ")
    end = next(i for i, line in enumerate(lines, 1) if i > start and line.strip().lower() == "оглавление") - 1
    sections, current, chapter = {}, "intro", 0
    for i in range(start, end + 1):
        text = lines[i - 1].strip()
        heading = re.match(r"§\s*(\d+\.\d+)\.", text)
        if heading:
            current = heading.group(1)
            chapter = int(current.split(".")[0])
        elif re.fullmatch(r"ГЛАВА\s+\S+", text):
            title = next(t.strip() for t in lines[i:i + 4] if t.strip())
            if title == title.upper():          # a chapter opening, not a running head in the text
                chapter += 1
                current = str(chapter)
        sections[i] = current
    return lines, start, end, sections


@pytest.fixture(scope="module")
def hanzl():
    lines = read(CS_SEED, "cs")
    start = next(i for i, line in enumerate(lines, 1) if i > 20 and line.strip() == "1 Úvod")
    contents = [m.group(1) for line in lines[:start - 1]
                if (m := re.match(r"(\d+(?:\.\d+)*)\s+\S", line.strip()))]
    sections, current, k = {}, None, 0
    for i in range(start, len(lines) + 1):
        text = lines[i - 1].strip()
        heading = re.match(r"(\d+(?:\.\d+)*)\.?\s+\S", text)
        if heading and k < len(contents) and heading.group(1) == contents[k] and len(text) < 110:
            current, k = contents[k], k + 1
        sections[i] = current
    assert k == len(contents), f"only {k} of Hanzl's {len(contents)} headings were found"
    return lines, start, len(lines), sections


def first_appearance_errors(entries, text, lang):
    lines, start, end, sections = text
    normalised = [normalise(line, lang) for line in lines]
    errors = []
    for t in entries:
        term, line, section = (t.ru, t.ru_line, t.ru_section) if lang == "ru" else (t.cs, t.cs_line, t.cs_section)
        if term is None:
            continue
        pattern = term_pattern(term, lang)
        if not start <= line <= end:
            errors.append(f"{t.en}: line {line} is outside the text proper ({start}–{end})")
            continue
        if not pattern.search(normalised[line - 1]):
            errors.append(f"{t.en}: {term!r} does not occur on line {line}")
        earlier = next((i for i in range(start, line) if pattern.search(normalised[i - 1])), None)
        if earlier:
            errors.append(f"{t.en}: {term!r} occurs already on line {earlier} ({sections[earlier]}), "
                          f"before {line}")
        if sections[line] != section:
            errors.append(f"{t.en}: line {line} is in section {sections[line]}, not {section}")
    return errors


@needs_seeds
def test_russian_terms_first_appear_on_their_lines(textbook):
    errors = first_appearance_errors(terms(), textbook, "ru")
    assert not errors, "\n".join(errors)


@needs_seeds
def test_czech_terms_first_appear_on_their_lines(hanzl):
    errors = first_appearance_errors(terms(), hanzl, "cs")
    assert not errors, "\n".join(errors)


# ---- the data -----------------------------------------------------------------------------------------

def test_entries_have_the_required_keys_and_a_sensible_size():
    entries = terms()
    assert 150 <= len(entries) <= 250
    for t in entries:
        assert isinstance(t, Term)
        assert t.en.strip() and t.ru.strip() and isinstance(t.ru_line, int), t
        assert (t.cs is None) == (t.cs_section is None) == (t.cs_line is None), t
    assert sum(t.cs is not None for t in entries) >= 100          # most terms are also Hanzl's


def test_no_duplicate_english_terms():
    names = [t.en.casefold() for t in terms()]
    assert len(names) == len(set(names)), sorted({n for n in names if names.count(n) > 1})


def test_sections_are_well_formed():
    for t in terms():
        assert SECTION.fullmatch(t.ru_section), t
        assert t.cs_section is None or SECTION.fullmatch(t.cs_section) and t.cs_section != "intro", t
        assert t.ru_line >= 1 and (t.cs_line is None or t.cs_line >= 1), t


def test_the_words_of_each_language_are_in_their_script():
    cyrillic, latin = re.compile("[а-яё]", re.I), re.compile("[a-z]", re.I)
    for t in terms():
        assert cyrillic.search(t.ru) or t.ru.isupper(), t.ru                  # ЦМР, but also DLT, SIFT
        assert not cyrillic.search(t.en), t.en
        assert t.cs is None or (latin.search(t.cs) and not cyrillic.search(t.cs)), t.cs


def test_lookup_searches_all_three_languages():
    found = [t.en for t in lookup("ОБРАТНАЯ ФОТОГРАММЕТРИЧЕСКАЯ")]
    assert found == ["space resection", "double resection-intersection"]
    assert [t.ru for t in lookup("zpět")] == ["обратная фотограмметрическая засечка"]
    assert {t.cs for t in lookup("overlap")} >= {"podélný překryt", "příčný překryt", "trojnásobný překryt"}
    assert lookup("ёё-no-such-term") == []
    assert lookup("  Normal case ")[0].ru == "нормальный случай"


@pytest.mark.parametrize("bad", ["", "   ", None, 3])
def test_lookup_rejects_bad_words(bad):
    with pytest.raises(InputError):
        lookup(bad)


def test_the_table_groups_by_letter_and_keeps_every_term():
    total = 0
    for letter in sorted({t.en[0].upper() for t in terms()}):
        table = glossary_table(letter)
        assert table.header == ["English", "Russian (§)", "Czech (§)"]
        assert all(row[0][0].upper() == letter for row in table.rows)
        assert [r[0].casefold() for r in table.rows] == sorted(r[0].casefold() for r in table.rows)
        total += len(table.rows)
    assert total == len(terms()) == len(glossary_table().rows)
    row = next(r for r in glossary_table("p").rows if r[0] == "principal point")
    assert row == ["principal point", "главная точка снимка (§1.1)", "hlavní bod snímku (§6.1)"]
    assert glossary_table("f", with_notes=True).header[-1] == "Note"


@pytest.mark.parametrize("bad", ["ab", "", "1", "ž", 5])
def test_the_table_rejects_bad_letters(bad):
    with pytest.raises(InputError):
        glossary_table(bad)


def test_a_malformed_entry_is_reported_by_name():
    with pytest.raises(InputError, match="missing key"):
        glossary._entry({"en": "x", "ru": "икс"}, 0)
    with pytest.raises(InputError, match="Czech keys"):
        glossary._entry({"en": "x", "ru": "икс", "ru_section": "1.1", "ru_line": 5, "cs": "x"}, 0)
    with pytest.raises(InputError, match="not a section"):
        glossary._entry({"en": "x", "ru": "икс", "ru_section": "§1.1", "ru_line": 5}, 0)
