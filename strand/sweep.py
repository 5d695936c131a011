"""Sweeps: the cycle of a case at several amplitudes (``[load] sweep``), each from the same
tensioned state, and the table that compares them (``sweep.csv``, ``sweep.txt``): effort, and the
set-up kind's measure (``SetupKind.measure``) at the peak and back at zero load."""

from __future__ import annotations

import sys
import time
from dataclasses import dataclass
from pathlib import Path

from .build import build_problem, results_folder, settings_text, setup_and_programme
from .case import Case
from .checkpoint import restore
from .folder import FolderError, writable_folder
from .kinds import kind_of
from .parallel import is_root, on_root, root_stream
from .programme import LoadProgramme, Position
from .run_result import RunResult, Start
from .runner import run_programme_with_outputs

__all__ = ["run_sweep", "SweepTable", "sweep_table"]


def run_sweep(
    case: Case, folder: str | Path | None = None, stream=None, overwrite: bool = False
) -> list[RunResult]:
    """Run the cycle of ``case`` at every amplitude of ``[load] sweep`` from one tensioned state:
    the tension once, into ``folder``/tension, then each amplitude restored from that state
    into ``folder``/<parameter>_<amplitude>, each with all its outputs (its first row is the
    tensioned state); ``sweep.csv`` and ``sweep.txt`` in ``folder`` compare them."""
    stream = root_stream(stream or sys.stdout)
    t0 = time.perf_counter()
    folder = Path(folder or case.output.folder)
    kind = kind_of(case)
    parameter = kind.parameter
    names = {a: f"{parameter}_{a:g}" for a in case.load.sweep}
    top = on_root(lambda: _sweep_folder(folder, overwrite, case))
    folders = {
        key: results_folder(case, top / key, overwrite) for key in ["tension", *names.values()]
    }
    problem, programme = build_problem(case, stream)
    results = []
    try:
        tension = LoadProgramme(programme.stages[:1], parameter)
        print(f"--- sweep: tension, then {parameter} amplitudes {list(case.load.sweep)} ---",
              file=stream, flush=True)  # fmt: skip
        tensioned = run_programme_with_outputs(
            case, problem, tension, folders["tension"], stream, keep=lambda s: True
        )
        if tensioned.failure:
            return [tensioned]
        state, last = tensioned.kept, tensioned.steps[-1]
        for amplitude, name in names.items():
            member = kind.with_amplitude(case, amplitude)
            _, member_programme = setup_and_programme(member)
            print(f"--- sweep: {parameter} amplitude {amplitude:g} ---", file=stream, flush=True)
            restore(problem, state)
            start = Start(Position(1, None), last)
            results.append(
                run_programme_with_outputs(
                    member, problem, member_programme, folders[name], stream, start
                )  # fmt: skip
            )
            if results[-1].interrupted:
                break
    finally:
        problem.solver.destroy()
    table = sweep_table(case, parameter, problem.setup.units[parameter], results)
    if is_root():
        (top / "sweep.csv").write_text(table.csv)
        (top / "sweep.txt").write_text(
            table.text + f"sweep wall time {time.perf_counter() - t0:.0f} s\n"
        )
    print(table.text, file=stream, flush=True)
    return [tensioned, *results]


def _sweep_folder(folder: Path, overwrite: bool, case: Case) -> Path:
    """The sweep's own folder: it holds the members' folders and the sweep table."""
    path = writable_folder(folder)
    marker = path / "sweep.txt"  # written first
    others = [p for p in path.iterdir() if not p.name.startswith(".") and p.is_file()]
    if others and not marker.exists():
        raise FolderError(f"{path}: holds files that are not a strand sweep's; give another folder")
    if marker.exists() and not overwrite:
        raise FolderError(
            f"{path}: holds an earlier sweep; give another folder (--out) or replace it "
            "(--overwrite)"
        )
    for p in others:
        p.unlink()
    (path / "sweep.txt").write_text(settings_text(case))
    return path


@dataclass(frozen=True)
class SweepTable:
    """The sweep's table as text (``sweep.txt``) and as CSV (``sweep.csv``)."""

    text: str
    csv: str


def sweep_table(case: Case, parameter: str, unit: str, results: list[RunResult]) -> SweepTable:
    """One row per amplitude (of ``parameter``, in ``unit`` as in column names): its effort and
    what the set-up measured at the peak and back at zero load (the kind's ``measure``)."""
    head = [f"amplitude_{unit}", "steps", "iterations", "cuts", "seconds"]
    measure = kind_of(case).measure
    head += [f"peak_{measure}", f"unloaded_{measure}", "outcome"]
    rows = []
    for r in results:
        cycle = r.cycle_steps
        amp = max((abs(s.load) for s in cycle), default=0.0)
        peak = r.peak_step
        zero = r.unloaded_steps
        rows.append([
            f"{amp:g}", str(len(cycle)), str(sum(s.iterations for s in cycle)),
            str(sum(s.cuts for s in cycle)), f"{r.seconds:.1f}",
            f"{getattr(peak.state, measure):.12g}" if peak else "nan",
            f"{getattr(zero[0].state, measure):.12g}" if zero else "nan",
            "interrupted" if r.interrupted else "failed" if r.failure else "done",
        ])  # fmt: skip
    text = [f"sweep of {parameter} from one tensioned state ({case.load.tension / 1e3:g} kN):",
            "  " + "  ".join(head)]  # fmt: skip
    text += ["  " + "  ".join(row) for row in rows]
    csv_text = "\n".join(",".join(r) for r in [head, *rows]) + "\n"
    return SweepTable("\n".join(text) + "\n", csv_text)
