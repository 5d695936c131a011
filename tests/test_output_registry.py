"""The output registry (``strand.app.outputs``): an output registered from outside the
application writes its file in a run's folder, next to the built-ins, and the folder's
``README.txt`` says what it holds."""

from __future__ import annotations

import csv
import re
from pathlib import Path

import pytest

from strand.app.cli import main
from strand.app.outputs import register_output, registered_outputs, unregister_output
from strand_cases import SEVEN_WIRE


class MaxDeflection:
    """``max_deflection.txt``: the largest set-up deflection of the run, m."""

    def __init__(self, run):
        self.path = Path(run.folder) / "max_deflection.txt"
        self.largest = 0.0

    def record(self, ctx) -> None:
        self.largest = max(self.largest, abs(ctx.step.state.deflection))

    def close(self) -> None:
        self.path.write_text(f"{self.largest:.9e}\n")


@pytest.fixture
def max_deflection():
    register_output(
        "max_deflection",
        MaxDeflection,
        files={"max_deflection.txt": "the largest deflection of the run, m"},
    )
    yield
    unregister_output("max_deflection")
    assert "max_deflection" not in [o.name for o in registered_outputs()]


def test_a_registered_output_writes_its_file_in_the_runs_folder(tmp_path, max_deflection):
    case = tmp_path / "seven.toml"
    case.write_text(SEVEN_WIRE.replace("[output]", "[output]\nfields = false"))
    out = tmp_path / "out"
    assert main(["run", str(case), "--out", str(out)]) == 0
    with open(out / "steps.csv") as f:
        deflections = [abs(float(s["deflection_m"])) for s in csv.DictReader(f)]
    assert float((out / "max_deflection.txt").read_text()) == pytest.approx(max(deflections))
    assert (out / "steps.csv").exists() and (out / "slip.csv").exists()  # the built-ins too
    readme = (out / "README.txt").read_text()
    assert re.search(r"^max_deflection\.txt +the largest deflection of the run, m$", readme, re.M)
