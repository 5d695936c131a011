"""Every demo runs as a test, as a user would run it: a fresh interpreter in an empty folder,
serially and on two processes (``mpirun -n 2 python demo.py``), as dolfinx tests its demos (the
longest, ``SLOW``, on two processes only, against its serial recording).

Each demo checks itself against its closed form (its asserts). Both runs must pass those checks,
draw the figures the tutorials show and print the numbers the tutorials show, recorded from a
serial run in ``docs/_static/tutorials/<demo>/outputs.json`` (``scripts/record_figures.py``): on
two processes a demo gives the serial results, printed once.
"""

import json
import re
import subprocess
import sys
from pathlib import Path

import pytest

from strand_cases import MPIRUN, needs_mpirun

ROOT = Path(__file__).parents[1]
DEMOS = sorted((ROOT / "demos").glob("demo_*.py"))
RECORDED = ROOT / "docs" / "_static" / "tutorials"
#: demos whose serial run is their recording's alone (``scripts/record_figures.py``): the
#: strand-bending demo bends 0.4 m of Cardinal through a cycle, the suite's longest run; on two
#: ranks it must print the numbers that serial run recorded
SLOW = {"demo_strand_bending"}
CASES = [pytest.param(d, marks=pytest.mark.slow) if d.stem in SLOW else d for d in DEMOS]
SERIAL = [d for d in DEMOS if d.stem not in SLOW]

#: a number as printed: sign, digits, decimals, exponent
NUMBER = re.compile(r"(?<![\w.])[-+−]?\d+(?:\.\d+)?(?:e[-+−]?\d+)?(?![\w.])")
#: what a run prints that is not a result: times, and the progress lines of strand's runner
NOT_RESULTS = re.compile(r"\d s\b|\bs\)|\d+:\d\d|seconds|wall")


def recorded_output(demo: Path) -> str:
    cells = json.loads((RECORDED / demo.stem / "outputs.json").read_text())
    return "".join(c["output"] for c in cells)


def numbers(text: str) -> list[str]:
    """The numbers ``text`` prints, as printed, but on lines of times and progress and the
    number of ranks strand's runner names."""
    text = re.sub(r"; \d+ MPI ranks$", "", text, flags=re.M)
    lines = [line for line in text.splitlines() if not NOT_RESULTS.search(line)]
    return NUMBER.findall("\n".join(lines).replace("−", "-"))


def last_digit(printed: str) -> float:
    """One unit of the last digit printed: 1e-4 for 0.8106, 1e-3 for 2.6e-3, 0 for 12 (integers,
    such as counts of steps and iterations, must be equal)."""
    mantissa, _, exponent = printed.lower().partition("e")
    if "." not in mantissa:
        return 0.0 if not exponent else 10.0 ** int(exponent)
    return 10.0 ** (int(exponent or 0) - len(mantissa.split(".")[1]))


def assert_same_numbers(printed: str, expected: str, what: str) -> None:
    """``printed`` gives ``expected``'s numbers, each within a unit of its last digit (a rounding
    either side); numbers below 1e-9 are round-off residues (of a residual, of a difference of
    two equal results) and only need to stay below it."""
    got, want = numbers(printed), numbers(expected)
    assert len(got) == len(want), f"{what}: {len(got)} numbers printed, {len(want)} expected"
    for g, w in zip(got, want, strict=True):
        a, b = float(g), float(w)
        if abs(a) < 1e-9 and abs(b) < 1e-9:
            continue
        assert abs(a - b) <= max(last_digit(g), last_digit(w)) * (1 + 1e-9), f"{what}: {g} ≠ {w}"


def run(demo: Path, cwd: Path, ranks: int = 1) -> subprocess.CompletedProcess:
    command = [sys.executable, str(demo)]
    if ranks > 1:
        command = [str(MPIRUN), "-n", str(ranks), *command]
    done = subprocess.run(command, cwd=cwd, capture_output=True, text=True, timeout=1200)
    assert done.returncode == 0, done.stdout[-3000:] + done.stderr[-3000:]
    return done


def drawn(cwd: Path) -> set[str]:
    return {p.name for p in cwd.glob("results/**/*.png")}


@pytest.mark.parametrize("demo", SERIAL, ids=[d.stem for d in SERIAL])
def test_demo_runs(demo, tmp_path):
    """Serially the demo passes its checks, draws the figures its tutorial shows and prints the
    numbers its tutorial shows."""
    done = run(demo, tmp_path)
    shown = {p.name for p in (RECORDED / demo.stem).glob("*.png")}
    assert shown and shown <= drawn(tmp_path), "a demo draws the figures its tutorial shows"
    assert_same_numbers(done.stdout, recorded_output(demo), demo.stem)


@needs_mpirun
@pytest.mark.parametrize("demo", CASES, ids=[d.stem for d in DEMOS])
def test_demo_runs_on_2_ranks(demo, tmp_path):
    """On two processes the demo passes the same checks, draws the same figures and prints the
    serial run's numbers, once."""
    done = run(demo, tmp_path, ranks=2)
    shown = {p.name for p in (RECORDED / demo.stem).glob("*.png")}
    assert shown <= drawn(tmp_path)
    assert_same_numbers(done.stdout, recorded_output(demo), f"{demo.stem} on 2 ranks")
    assert "start it without mpirun" not in done.stderr


def test_the_numbers_are_compared_to_their_last_digit():
    assert_same_numbers("v/L = 0.81061, 4 steps, 2.6e-3", "v/L = 0.81062, 4 steps, 2.7e-3", "ok")
    assert_same_numbers("residual 3.1e-12 N", "residual 8.0e-13 N", "round-off")
    for printed, expected in (
        ("0.81061", "0.81063"),
        ("5 steps", "6 steps"),
        ("2.6e-3", "2.6e-4"),
        ("1.0 and 2.0", "1.0"),
    ):
        with pytest.raises(AssertionError):
            assert_same_numbers(printed, expected, "differs")
    progress = "step 3: 12 iterations, 1.5 s\nP = 300 N\n61 wires; 2 MPI ranks"
    assert numbers(progress) == ["300", "61"]


def test_there_are_demos():
    assert DEMOS
