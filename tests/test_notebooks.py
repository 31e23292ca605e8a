"""The notebooks of the documentation (docs/notebooks/*.md, MyST markdown) run from top to bottom
in a fresh kernel, as the site's build runs them: a cell that raises fails the test, and each
notebook asserts the numbers it teaches, so a wrong number fails it too."""

import pathlib

import jupytext
import nbformat
import pytest
from nbclient import NotebookClient
from nbclient.exceptions import CellExecutionError

NOTEBOOKS = sorted((pathlib.Path(__file__).resolve().parents[1] / "docs" / "notebooks").glob("*.md"))


def run(nb, folder):
    # The kernel draws with matplotlib's non-interactive backend, in the notebook's own folder.
    NotebookClient(nb, timeout=120, kernel_name="python3", resources={"metadata": {"path": str(folder)}},
                   startup_timeout=60).execute()
    return nb


def test_there_are_notebooks():
    assert len(NOTEBOOKS) >= 2


@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: p.stem)
def test_notebook_runs_and_its_assertions_hold(path):
    nb = jupytext.read(path)
    code = [c for c in nb.cells if c.cell_type == "code"]
    assert code and sum("assert" in c.source for c in code) >= 3, "a notebook checks what it teaches"
    run(nb, path.parent)
    errors = [o for c in code for o in c.get("outputs", []) if o.get("output_type") == "error"]
    assert not errors


def test_a_wrong_number_fails_the_run(tmp_path):
    nb = nbformat.v4.new_notebook(cells=[nbformat.v4.new_code_cell("import robokin as rk\nx = rk.robots.prr().dof"),
                                         nbformat.v4.new_code_cell("assert x == 4")])
    with pytest.raises(CellExecutionError, match="AssertionError"):
        run(nb, tmp_path)
