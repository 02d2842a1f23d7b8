"""Every notebook in notebooks/ executes top to bottom without error (nbclient)."""
import json
from pathlib import Path

import pytest

from spinorbit.edge.runner import run_scenario

ROOT = Path(__file__).parents[1]
NOTEBOOKS = sorted((ROOT / "notebooks").glob("*.ipynb"))


@pytest.mark.slow
@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: p.name)
def test_notebook_executes(path):
    nbformat = pytest.importorskip("nbformat")
    from nbclient import NotebookClient

    notebook = nbformat.read(path, as_version=4)
    NotebookClient(notebook, timeout=600, kernel_name="python3", resources={"metadata": {"path": str(ROOT)}}).execute()
    errors = [out for cell in notebook.cells if cell.cell_type == "code"
              for out in cell.get("outputs", []) if out.get("output_type") == "error"]
    assert not errors


# notebooks/verdicts.ipynb reads the verdicts of the runs in the folder it is given (SPINORBIT_RUNS) and says,
# for a scene with no run there, that it was not run and how to run it.


@pytest.mark.slow
def test_the_notebook_reads_the_runs_folder_it_is_given(tmp_path, monkeypatch):
    nbformat = pytest.importorskip("nbformat")
    from nbclient import NotebookClient

    result = run_scenario("free_body", ["span.end=2 d", "output.plots=false"])
    (tmp_path / "free_body").mkdir()
    (tmp_path / "free_body" / "summary.json").write_text(json.dumps(result.summary))
    monkeypatch.setenv("SPINORBIT_RUNS", str(tmp_path))
    monkeypatch.setenv("SPINORBIT_VERDICTS_RUN", "none")
    notebook = nbformat.read(ROOT / "notebooks" / "verdicts.ipynb", as_version=4)
    NotebookClient(notebook, timeout=120, kernel_name="python3", resources={"metadata": {"path": str(ROOT)}}).execute()
    table = next(out["data"]["text/markdown"] for cell in notebook.cells if cell.cell_type == "code"
                 for out in cell.get("outputs", []) if "text/markdown" in out.get("data", {}))
    rows = {line.split("|")[1].strip(" `"): line for line in table.splitlines() if line.startswith("| `")}
    headline = result.summary["verdict"]["headline"].split(": ", 1)[1]
    assert headline in rows["free_body.toml"] and str(tmp_path / "free_body") in rows["free_body.toml"]
    assert "not run (RUN_MISSING = 'all' runs it)" in rows["moon_libration.toml"]
    assert f"no {tmp_path.name}/moon_libration/summary.json" in rows["moon_libration.toml"]
    assert f"Runs read from `{tmp_path}`" in table
