"""The library guide's first script (docs/user-guide/first_script.py), run as a user runs it: a
fresh interpreter, then ``mpirun -n 2``. Both give the closed form's contact force and
deflection and the same numbers, printed once."""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from strand_cases import MPIRUN, needs_mpirun

SCRIPT = Path(__file__).parents[1] / "docs" / "user-guide" / "first_script.py"
GUIDE = Path(__file__).parents[1] / "docs" / "user-guide" / "library.md"
NUMBER = r"[-+]?\d+(?:\.\d+)?(?:e[-+]?\d+)?"


def run(ranks: int, cwd: Path) -> str:
    cmd = [sys.executable, str(SCRIPT)]
    if ranks > 1:
        cmd = [str(MPIRUN), "-n", str(ranks), *cmd]
    done = subprocess.run(cmd, cwd=cwd, capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stdout[-2000:] + done.stderr[-2000:]
    return done.stdout


def numbers(text: str, name: str) -> tuple[float, float]:
    """The value and the closed form of the printed line that starts with ``name``."""
    line = next(line for line in text.splitlines() if line.startswith(name))
    value, closed = re.findall(r"= ([-+0-9.e]+)", line)
    return float(value), float(closed)


@pytest.fixture(scope="module")
def serial(tmp_path_factory) -> str:
    return run(1, tmp_path_factory.mktemp("serial"))


def test_the_first_script_gives_the_closed_form(serial):
    """The wires share P = 1 N as P/(2 + k/K_N); the deflection is (P − p)/k within the
    two-node cells' O(1/n²) stiffness (0.26 % with 40 cells)."""
    p, p_closed = numbers(serial, "contact force")
    assert p == pytest.approx(p_closed, rel=1e-6)
    assert 0.49 < p < 0.5  # half the load, less the contact's compliance
    deflection, closed = numbers(serial, "deflection")
    assert deflection == pytest.approx(closed, rel=5e-3)
    assert deflection < closed  # the cells are stiff, not soft


def values(text: str) -> list[float]:
    return [float(v) for v in re.findall(NUMBER, text)]


def test_the_guide_shows_what_the_script_prints(serial):
    """The output in the guide is the script's, to 1e-6 (other BLAS, MPI or PETSc builds may
    change the last digits)."""
    shown = GUIDE.read_text().split("```text\n", 1)[1].split("```", 1)[0]
    assert re.sub(NUMBER, "#", shown) == re.sub(NUMBER, "#", serial)
    np.testing.assert_allclose(values(shown), values(serial), rtol=1e-6)


@needs_mpirun
def test_the_first_script_on_2_ranks_prints_the_serial_numbers(serial, tmp_path):
    parallel = run(2, tmp_path)
    assert parallel.count("contact force") == 1  # printed once
    assert re.sub(NUMBER, "#", parallel) == re.sub(NUMBER, "#", serial)
    assert len(values(serial)) == 7  # steps, iterations, p, 2, p closed, deflection, closed
    np.testing.assert_allclose(values(parallel), values(serial), rtol=1e-8)
