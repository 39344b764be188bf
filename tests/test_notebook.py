"""examples/notebook.ipynb (issue 25) executed as a user's Jupyter would run it (nbclient,
a fresh IPython kernel): every cell runs without an error, and its printed results are
the API's own (the oracle: the same calls made here)."""
from __future__ import annotations

from pathlib import Path

import pytest

nbformat = pytest.importorskip("nbformat", reason="the notebook test needs the test extra (nbclient, ipykernel)")
nbclient = pytest.importorskip("nbclient", reason="the notebook test needs the test extra (nbclient, ipykernel)")
pytest.importorskip("ipykernel", reason="the notebook test needs the test extra (nbclient, ipykernel)")

NOTEBOOK = Path(__file__).resolve().parents[1] / "examples" / "notebook.ipynb"


def _text(output) -> str:
    return output.get("text") or output.get("data", {}).get("text/plain", "")


@pytest.mark.slow
def test_the_example_notebook_runs_and_says_what_the_api_says(tmp_path):
    import isorock
    nb = nbformat.read(NOTEBOOK, as_version=4)
    nbclient.NotebookClient(nb, timeout=600, kernel_name="python3",
                            resources={"metadata": {"path": str(tmp_path)}}).execute()
    outputs = [o for c in nb.cells if c.cell_type == "code" for o in c.outputs]
    assert not [o for o in outputs if o.output_type == "error"]
    printed = "\n".join(_text(o) for o in outputs)
    bust = dict(height=0.6, width=0.2, mass=80, base_mass=150, period=2.0, damping_ratio=0.15)
    tr = isorock.run(engine="analytic", motion="sine:amp=0.3,freq=1,cycles=2", pga=0.5, **bust)
    assert f"θmax/α = {tr.theta_max_over_alpha:.3f}, impacts {tr.impact_count}" in printed
    assert "Result: all" in printed and "refused: pga = -1.0" in printed
    assert not list(tmp_path.iterdir())  # the notebook writes no file where it runs
