"""The worked notebook docs/examples/phasmid_tour.ipynb executes end to end (nbclient)."""
import os

import nbformat
from nbclient import NotebookClient

from conftest import SOURCE_DIR


def test_tour_notebook_runs(tmp_path):
    path = os.path.join(SOURCE_DIR, "docs", "examples", "phasmid_tour.ipynb")
    nb = nbformat.read(path, as_version=4)
    NotebookClient(nb, timeout=300, kernel_name="python3",
                   resources={"metadata": {"path": os.path.dirname(path)}}).execute()
    outputs = [o for c in nb.cells if c.cell_type == "code" for o in c.get("outputs", [])]
    assert not [o for o in outputs if o.output_type == "error"]
    assert sum(1 for o in outputs if "image/png" in o.get("data", {})) == 3  # angle, fit, sweep
    text = "".join(o.get("text", "") for o in outputs)
    assert "converged: True" in text and "period_ms" in text
