"""Every demo runs as a test, as a user would run it: a fresh interpreter in an empty folder."""

import subprocess
import sys
from pathlib import Path

import pytest

DEMOS = sorted((Path(__file__).parents[1] / "demos").glob("demo_*.py"))
SLOW = {"demo_strand_bending"}  # two runs of 0.4 m of Cardinal: minutes
CASES = [pytest.param(d, marks=pytest.mark.slow) if d.stem in SLOW else d for d in DEMOS]


@pytest.mark.parametrize("demo", CASES, ids=[d.stem for d in DEMOS])
def test_demo_runs(demo, tmp_path):
    run = subprocess.run(
        [sys.executable, str(demo)], cwd=tmp_path, capture_output=True, text=True, timeout=600
    )
    assert run.returncode == 0, run.stdout[-3000:] + run.stderr[-3000:]
    assert list(tmp_path.glob("results/**/*.png")), "a demo should leave a picture"


def test_there_are_demos():
    assert DEMOS
