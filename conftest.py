"""pytest configuration shared by tests/, the doctests of photolib/ and nbval over chapters/.

Notebook cells that use the real data of ``../shared/data`` (found through
:func:`photolib.datasets.data_dir`) start with the line ``# real data`` and are leaves: no later
cell uses what they compute. On a machine without that data (a user's fresh clone) nbval skips
exactly those cells, with the reason, instead of failing on their stored outputs; CI has the data
and checks them.
"""

from __future__ import annotations

import pytest

REAL_DATA_MARK = "# real data"


def pytest_collection_modifyitems(config, items):
    from photolib.datasets import data_dir

    folder = data_dir()
    if folder.is_dir():
        return
    skip = pytest.mark.skip(reason=f"real data absent ({folder} does not exist; set PHOTOLIB_DATA): "
                                   "this notebook cell uses it")
    for item in items:
        cell = getattr(item, "cell", None)
        source = cell.get("source", "") if isinstance(cell, dict) else ""
        if source.lstrip().startswith(REAL_DATA_MARK):
            item.add_marker(skip)
