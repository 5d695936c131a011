"""Restarts: a run continued from a checkpoint of any converged step takes the steps and reaches
the results of the run that was never stopped (to 1e-10: frictional contact keeps history that a
restart must carry: tractions, normals, normal forces, friction history, sliding segments, and the
load stepper's increment and predictor)."""

from __future__ import annotations

import csv
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from strand.app.case import load_case
from strand.app.cli import main
from strand.app.run import build_problem, run_case, run_programme_with_outputs
from strand.model.checkpoint import read_checkpoint, write_checkpoint
from strand_cases import MPIRUN, SEVEN_WIRE, needs_mpirun

QUIET = ["output.plots=false", "output.fields=false", "fatigue.outputs=false"]


def steps(folder: Path) -> tuple[list[str], np.ndarray]:
    with open(folder / "steps.csv") as f:
        rows = list(csv.reader(f))
    keep = [i for i, n in enumerate(rows[0]) if n not in ("stage", "seconds", "residual_N")]
    return [rows[0][i] for i in keep], np.array([[float(r[i]) for i in keep] for r in rows[1:]])


def uninterrupted_with_checkpoint(case, folder: Path, k: int) -> Path:
    """Run ``case`` whole into ``folder``, keeping the state of step ``k`` as a checkpoint."""
    problem, programme = build_problem(case)
    folder.mkdir()
    (folder / "settings.txt").write_text("uninterrupted")
    result = run_programme_with_outputs(
        case, problem, programme, folder, sys.stdout, keep=lambda s: s.number == k
    )
    assert not result.failure and result.kept.number == k
    problem.solver.destroy()
    write_checkpoint(folder / f"step_{k}.h5", result.kept)
    return folder / f"step_{k}.h5"


def assert_continues(whole: Path, continued: Path, k: int, rtol: float) -> None:
    head, a = steps(whole)
    _, b = steps(continued)
    assert b[0, 0] == k and len(b) == len(a) - k + 1  # the restart state, then the rest
    its = head.index("iterations")
    effort = slice(its, its + 4)  # iterations, cuts, failed iterations, LU factorisations
    assert np.array_equal(a[k:, effort], b[1:, effort])
    rel = np.abs(a[k - 1 :] - b) / np.maximum(np.abs(a).max(axis=0), 1e-300)
    rel[0, effort] = 0.0  # the restart row has no Newton effort of its own
    assert rel.max() <= rtol, f"{head[int(np.argmax(rel.max(axis=0)))]}: {rel.max():.2e}"
    A = np.loadtxt(whole / "axial_forces.csv", delimiter=",", skiprows=1)
    B = np.loadtxt(continued / "axial_forces.csv", delimiter=",", skiprows=1)
    A = A[A[:, 0] >= k]
    assert A.shape == B.shape and np.abs(A[:, 7] - B[:, 7]).max() <= rtol * np.abs(A[:, 7]).max()


@pytest.fixture
def seven(tmp_path):
    path = tmp_path / "seven.toml"
    path.write_text(SEVEN_WIRE)
    return path


@pytest.mark.parametrize(
    "settings, k",
    [
        ([], 6),
        (['contact.model="large"'], 8),
        (['contact.same_layer="nominal"'], 6),
        (
            [
                'load.kind="bending"',
                "load.zone=0.04",
                "load.curvature=0.5",
                "steps.curvature=0.1",
                "steps.curvature_max=0.2",
            ],
            11,
        ),
    ],
    ids=[
        "small sliding, after a step cut",
        "large sliding",
        "same-layer contact",
        "uniform bending",
    ],
)
def test_a_run_continued_from_any_step_is_the_uninterrupted_run(seven, tmp_path, settings, k):
    case = load_case(seven, [*QUIET, *settings])
    checkpoint = uninterrupted_with_checkpoint(case, tmp_path / "whole", k)
    state = read_checkpoint(checkpoint)
    assert state.step is not None and state.stage >= 1  # mid-ramp: the predictor must carry
    run_case(case, tmp_path / "continued", restart=checkpoint)
    assert_continues(tmp_path / "whole", tmp_path / "continued", k, 1e-10)


@needs_mpirun
def test_a_serial_checkpoint_continues_on_two_ranks(seven, tmp_path):
    case = load_case(seven, QUIET)
    checkpoint = uninterrupted_with_checkpoint(case, tmp_path / "whole", 7)
    out = tmp_path / "continued"
    args = ["run", str(seven), "--restart", str(checkpoint), "--out", str(out)]
    args += [a for s in QUIET for a in ("--set", s)]
    done = subprocess.run(
        [str(MPIRUN), "-n", "2", sys.executable, "-m", "strand.app", *args],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert done.returncode == 0, done.stderr[-2000:]
    assert_continues(tmp_path / "whole", out, 7, 1e-8)  # LU round-off of another distribution


def test_checkpoints_are_written_as_the_run_goes_and_bad_ones_refused(seven, tmp_path, capsys):
    out = tmp_path / "run"
    assert (
        main(["run", str(seven), "--out", str(out), *sum((["--set", s] for s in QUIET), [])]) == 0
    )
    last, tensioned = read_checkpoint(out / "checkpoint.h5"), read_checkpoint(out / "tensioned.h5")
    _, a = steps(out)
    assert last.number == len(a) and tensioned.loads["lateral"] == 0.0
    assert tensioned.loads["tension"] == pytest.approx(10e3) and tensioned.stage == 0
    # a checkpoint of another strand, and a file that is none: one line each, exit code 2
    capsys.readouterr()
    longer = ["--set", "mesh.length=0.12"]
    code = main(
        [
            "run",
            str(seven),
            "--restart",
            str(out / "checkpoint.h5"),
            "--out",
            str(tmp_path / "other"),
            *longer,
        ]
    )
    err = capsys.readouterr().err
    assert code == 2 and err.count("\n") == 1 and "written for another strand" in err
    code = main(
        ["run", str(seven), "--restart", str(out / "steps.csv"), "--out", str(tmp_path / "third")]
    )
    err = capsys.readouterr().err
    assert code == 2 and err.count("\n") == 1 and "cannot read the checkpoint" in err


@pytest.mark.slow  # 10 s on a fresh clone
def test_a_sweep_cycles_each_amplitude_from_one_tensioned_state_as_separate_runs_would(
    seven, tmp_path
):
    """Each amplitude of ``[load] sweep`` starts from the one tensioned state; its outputs are
    those of a separate run of that amplitude (tension included), to 1e-10."""
    out = tmp_path / "sweep"
    args = ["run", str(seven), "--out", str(out), "--set", "load.sweep=[150.0, 300.0]"]
    assert main([*args, *sum((["--set", s] for s in QUIET), [])]) == 0
    tension_steps = len(steps(out / "tension")[1])
    for amplitude in (150.0, 300.0):
        alone = tmp_path / f"alone_{amplitude:g}"
        case = load_case(seven, [*QUIET, f"load.lateral={amplitude}"])
        run_case(case, alone)
        member = out / f"lateral_{amplitude:g}"
        # the member's first row is the tensioned state, the last tension step of a separate run
        assert_continues(alone, member, tension_steps, 1e-10)
        assert (member / "summary.txt").read_text().count("after tension") == 1
    with open(out / "sweep.csv") as f:
        rows = list(csv.DictReader(f))
    assert [float(r["amplitude_N"]) for r in rows] == [150.0, 300.0]
    peaks = [float(r["peak_deflection_m"]) for r in rows]
    _, alone = steps(tmp_path / "alone_300")
    assert peaks[1] == pytest.approx(alone[:, 4].max(), rel=1e-10) and peaks[0] < peaks[1]
    # a second sweep into the folder is refused unless --overwrite
    assert main(args) == 2
