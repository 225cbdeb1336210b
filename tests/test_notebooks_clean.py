"""Committed notebooks carry no outputs, so that their diffs show only the code and text.

The notebooks themselves are executed by nbmake (``testpaths`` in pyproject.toml);
this test only checks what is stored in the repository.
"""

import json
from pathlib import Path

import pytest

NOTEBOOKS = sorted((Path(__file__).resolve().parents[1] / "notebooks").glob("*.ipynb"))


def test_there_are_notebooks():
    assert NOTEBOOKS, "notebooks/*.ipynb not found"


@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: p.name)
def test_notebook_is_stripped(path):
    nb = json.loads(path.read_text())
    dirty = [
        i
        for i, cell in enumerate(nb["cells"])
        if cell["cell_type"] == "code"
        and (cell.get("outputs") or cell.get("execution_count") is not None)
    ]
    assert not dirty, (
        f"{path.name}: cells {dirty} have outputs or execution counts; "
        "strip them (e.g. `jupyter nbconvert --clear-output --inplace`)"
    )
    assert "widgets" not in nb.get("metadata", {}), f"{path.name}: widget state stored"
