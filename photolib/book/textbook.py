"""The book's published numbers as data — reader of ``textbook/chNN.toml``.

One TOML file per chapter (format in ``textbook/README.md``). Each ``[[example]]`` holds the
inputs as printed and one ``[[example.quantity]]`` per published number with its printed
decimals, unit and status; each ``[[formula]]`` records a printed formula checked against
sympy. This module only reads and validates; :mod:`photolib.book.verify` recomputes.
"""

from __future__ import annotations

import os
import tomllib
from dataclasses import dataclass, field
from functools import lru_cache
from importlib import resources
from pathlib import Path

from ..errors import InputError

STATUSES = ("reproduced", "input-rounding", "erratum", "not-reproducible", "transcribed")


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
    correct: object = None              # erratum: the correct value
    correct_decimals: int | None = None
    diagnosis: str = ""                 # erratum: what is wrong
    proof: str = ""                     # erratum: how it was established
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
    if q.status == "erratum" and (q.correct is None or not q.diagnosis or not q.proof):
        raise InputError(f"{where}/{q.name}: an erratum needs 'correct', 'diagnosis' and 'proof'")
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
        if fm["status"] not in ("reproduced", "erratum"):
            raise InputError(f"{path.name}:{fm['id']}: a formula is 'reproduced' or 'erratum'")
        if fm["status"] == "erratum" and not (fm.get("correct") and fm.get("diagnosis") and fm.get("proof")):
            raise InputError(f"{path.name}:{fm['id']}: an erratum needs 'correct', 'diagnosis' and 'proof'")
        formulas.append(Formula(chapter=number, seed=fm.get("seed", seed), **{k: v for k, v in fm.items() if k != "seed"}))
    return Chapter(number, raw["title"], raw.get("title_original", ""), seed, raw.get("lines", []), examples, formulas)


def available_chapters() -> list[int]:
    """Chapter numbers that have a ``textbook/chNN.toml``."""
    return sorted(int(p.stem[2:]) for p in textbook_dir().glob("ch[0-9][0-9].toml"))
