"""A tutorial opened as a notebook: a demo converted by jupytext, as the tutorials index says,
and executed cell by cell in a Jupyter kernel (nbclient, ipykernel: the ``notebook`` extra). It
passes its own checks, prints the numbers its tutorial shows and draws its figures inline."""

from __future__ import annotations

from pathlib import Path

import pytest
from test_demos import assert_same_numbers, recorded_output

ROOT = Path(__file__).resolve().parents[1]
#: the quickest demo with figures: two crossed beams, pressed, then sheared to and fro (~4 s)
DEMO = ROOT / "demos" / "demo_crossed_beams.py"


def test_a_demo_runs_as_a_notebook(tmp_path):
    jupytext = pytest.importorskip("jupytext", reason="jupytext converts the demos (dev extra)")
    nbclient = pytest.importorskip(
        "nbclient", reason="the notebook extra: pip install -e .[notebook]"
    )
    pytest.importorskip("ipykernel", reason="the notebook extra: pip install -e .[notebook]")
    notebook = jupytext.read(DEMO)
    nbclient.NotebookClient(
        notebook,
        timeout=600,
        kernel_name="python3",
        resources={"metadata": {"path": str(tmp_path)}},  # the kernel's working folder
    ).execute()
    code = [cell for cell in notebook.cells if cell.cell_type == "code"]
    outputs = [out for cell in code for out in cell.get("outputs", [])]
    assert not [out for out in outputs if out.output_type == "error"]
    printed = "".join(out.get("text", "") for out in outputs if out.output_type == "stream")
    assert_same_numbers(printed, recorded_output(DEMO), f"{DEMO.stem} as a notebook")
    inline = [out for out in outputs if "image/png" in out.get("data", {})]
    assert len(inline) >= 2, "the two figures drawn inline"
    assert (tmp_path / "results").is_dir()
