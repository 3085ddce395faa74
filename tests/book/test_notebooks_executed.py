"""Guard: nbval passes vacuously on cells without stored outputs, so every notebook under
``chapters/`` must be committed executed, top to bottom, with its outputs stored."""

import json
from pathlib import Path

import pytest

CHAPTERS = Path(__file__).resolve().parents[2] / "chapters"
NOTEBOOKS = sorted(p for p in CHAPTERS.rglob("*.ipynb") if ".ipynb_checkpoints" not in p.parts)


def test_there_are_notebooks():
    assert NOTEBOOKS, "no notebooks under chapters/"


@pytest.mark.parametrize("path", NOTEBOOKS, ids=[p.name for p in NOTEBOOKS])
def test_every_code_cell_executed_in_order(path):
    cells = [c for c in json.loads(path.read_text(encoding="utf-8"))["cells"] if c["cell_type"] == "code"]
    code = [c for c in cells if "".join(c["source"]).strip()]
    assert code, f"{path.name} has no code cells"
    counts = [c.get("execution_count") for c in code]
    missing = [i for i, n in enumerate(counts) if n is None]
    assert not missing, f"{path.name}: code cells {missing} were never executed (no stored outputs)"
    assert counts == list(range(1, len(code) + 1)), (
        f"{path.name}: execution counts {counts} show the notebook was not run once from top to bottom")
    assert any(c.get("outputs") for c in code), f"{path.name}: no cell has stored outputs"
    for i, c in enumerate(code):
        for out in c.get("outputs", []):
            assert out.get("output_type") != "error", f"{path.name}: cell {i} stored an error"
