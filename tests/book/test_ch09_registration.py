"""Chapter 9 §9.5–9.6 adapters (photolib/book/ch09_registration.py) and their textbook entries.

The formula adapter accepts (9.5.1) and rejects a transposed A or a scaled transform (expected
from the sympy derivation); the statements' figures come from the rank of the correction equations.
"""

import pytest

from photolib.book import ch09_registration as c
from photolib.book.textbook import load_chapter
from photolib.book.verify import check_example, check_formula

GOOD = ["X_0 + a11*Xp + a12*Yp + a13*Zp", "Y_0 + a21*Xp + a22*Yp + a23*Zp", "Z_0 + a31*Xp + a32*Yp + a33*Zp"]


@pytest.mark.parametrize("bad", [
    ["X_0 + a11*Xp + a21*Yp + a31*Zp", "Y_0 + a12*Xp + a22*Yp + a32*Zp", "Z_0 + a13*Xp + a23*Yp + a33*Zp"],
    ["X_0 + 2*(a11*Xp + a12*Yp + a13*Zp)", GOOD[1], GOOD[2]],
], ids=["transposed A", "scaled"])
def test_rigid_formula(bad):
    assert c.rigid_formula({"XYZ": GOOD})["printed_equals_derived"]
    assert not c.rigid_formula({"XYZ": bad})["printed_equals_derived"]


def test_two_targets_always_leave_a_rotation_free():
    out = c.minimum_targets({"targets": [[0, 0, 0], [1, 2, 3], [4, 0, 1]], "collinear": [[0, 0, 0], [1, 0, 0], [3, 0, 0]]})
    assert out == {"by_counting": 2, "minimum": 3, "two_targets_rank": 5, "collinear_rank": 5}


def test_every_entry_of_the_fragment_verifies():
    chapter = load_chapter(9)
    mine = lambda entries: [e for e in entries if e.id.startswith(("9.5", "9.6"))]  # noqa: E731
    formulas, examples = mine(chapter.formulas), mine(chapter.examples)
    assert formulas and examples
    for f in formulas:
        assert check_formula(f).ok, f.id
    for ex in examples:
        assert all(row.ok for row in check_example(ex)), ex.id
