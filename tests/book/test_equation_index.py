"""The equation → code index: the book's equation numbers as data, the library's citations of them."""

from pathlib import Path

import pytest

from photolib.book import equation_index as index

SEED = Path(__file__).resolve().parents[3] / "shared" / "seeds" / "000_0363cf98558e0ca3.txt"


def test_every_number_the_library_cites_is_an_equation_of_the_book():
    assert index.unknown_citations() == {}


def test_ranges_are_expanded_within_a_section_only():
    assert index.cited_numbers("(11.6.1)–(11.6.3)") == {"11.6.1", "11.6.2", "11.6.3"}
    assert index.cited_numbers("(1.8.2)-(1.8.4), (2.1.1)") == {"1.8.2", "1.8.3", "1.8.4", "2.1.1"}
    assert index.cited_numbers("(1.8.9)–(1.9.1)") == {"1.8.9", "1.9.1"}
    assert index.cited_numbers("clause 3.7.6, (12.1.1), (0.1.1)") == set()


def test_the_equation_list_is_ordered_and_unique():
    numbers = [eq.number for eq in index.book_equations()]
    assert len(numbers) == len(set(numbers)) > 300
    for eq in index.book_equations():
        assert (eq.line is None) != (eq.cited is None), eq      # printed with its formula, or only cited


@pytest.mark.skipif(not SEED.is_file(), reason=f"the OCR of the book ({SEED}) is not beside the checkout")
def test_the_lines_are_where_the_seed_prints_the_numbers():
    lines = SEED.read_text(encoding="utf-8").split("\n")
    for eq in index.book_equations():
        text = lines[(eq.line or eq.cited) - 1].replace(" ", "")
        if eq.unnumbered:
            assert f"({eq.number})" not in "".join(lines), eq     # the book really has no such number
        else:
            assert f"({eq.number})" in text or f"tag{{{eq.number}}}" in text, eq


def test_an_implemented_equation_names_its_functions():
    rows = {r["equation"]: r for r in index.index_rows(9)}
    assert "photolib.lidar.polar_to_xyz" in rows["(9.4.1)"]["implemented_by"]
    done, total = index.coverage()
    assert 0 < done <= total == len(index.book_equations())
