"""Proofs in textbook/ cite tests by path and name: every cited test must exist where it is cited."""

import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
CITATION = re.compile(r"(tests/[\w/]+\.py)((?:(?:::|, ::)test_\w+)*)")


def citations():
    for toml in sorted((ROOT / "textbook").glob("*.toml")):
        for line_no, line in enumerate(toml.read_text(encoding="utf-8").splitlines(), 1):
            for m in CITATION.finditer(line):
                yield f"{toml.name}:{line_no}", m.group(1), re.findall(r"test_\w+", m.group(2))


@pytest.mark.parametrize("where,path,names", list(citations()), ids=lambda v: v if isinstance(v, str) else None)
def test_cited_test_exists(where, path, names):
    file = ROOT / path
    assert file.is_file(), f"{where}: {path} does not exist"
    defined = set(re.findall(r"^def (test_\w+)", file.read_text(encoding="utf-8"), re.M))
    missing = [n for n in names if n not in defined]
    assert not missing, f"{where}: {path} has no {missing}"
