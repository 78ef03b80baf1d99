"""The worked notebook docs/examples/phasmid_tour.ipynb executes end to end (nbclient)."""
import os

import nbformat
from nbclient import NotebookClient

import phasmid
from conftest import SOURCE_DIR


def test_tour_notebook_runs(monkeypatch):
    path = os.path.join(SOURCE_DIR, "docs", "examples", "phasmid_tour.ipynb")
    # The kernel imports the phasmid this test imports (it starts in docs/examples).
    package_dir = os.path.dirname(os.path.dirname(os.path.abspath(phasmid.__file__)))
    monkeypatch.setenv("PYTHONPATH", os.pathsep.join([package_dir, os.environ.get("PYTHONPATH", "")]))
    monkeypatch.setenv("PYDEVD_DISABLE_FILE_VALIDATION", "1")
    nb = nbformat.read(path, as_version=4)
    NotebookClient(nb, timeout=300, kernel_name="python3",
                   resources={"metadata": {"path": os.path.dirname(path)}}).execute()
    outputs = [o for c in nb.cells if c.cell_type == "code" for o in c.get("outputs", [])]
    assert not [o for o in outputs if o.output_type == "error"]
    assert sum(1 for o in outputs if "image/png" in o.get("data", {})) == 3  # angle, fit, sweep
    text = "".join(o.get("text", "") for o in outputs)
    assert "converged: True" in text and "period_ms" in text
