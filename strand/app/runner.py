"""The runner: a problem taken through its load programme with the run's recorders, then the
summary, the fatigue report and the figures.

``run_programme_with_outputs`` is what ``strand run`` and every sweep member do once the problem
is built (``strand.app.build``). After every converged step a ``Recording``
(``strand.app.recording``) makes the step's record, hands it to each recorder
(``strand.app.recorders``) and prints a progress line; Ctrl-C or a step that cannot converge stops
the programme at the last converged step, whose outputs are then finished like a complete run's.
Times in s.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import replace
from pathlib import Path
from typing import TYPE_CHECKING

from ..beam.parallel import is_root
from ..model.problem import StrandProblem
from ..model.programme import LoadProgramme, run_programme
from ..setups import TestSetup
from ..solver import Interrupt, LoadStepFailure, RunInterrupted
from .build import step_control
from .checks import tension_warning
from .kinds import SetupKind, kind_of
from .recording import Outcome, Recording
from .run_files import write_folder_readme
from .run_result import RunResult, Start
from .settings import Case
from .step_records import RunStep
from .summary import summarize

if TYPE_CHECKING:
    from .fatigue.findings import FatigueReport

__all__ = ["run_programme_with_outputs", "run_fatigue_report"]


def _warn_of_tension(case: Case, warnings: list[str], stream) -> None:
    """A tension far from the strand's breaking strength (``checks.tension_warning``), printed
    and kept (in ``warnings``) for the summary."""
    warning = tension_warning(case)
    if warning:
        warnings.append(warning)
        print(f"strand: warning: {warning}", file=stream, flush=True)


def run_programme_with_outputs(
    case: Case,
    problem: StrandProblem[TestSetup],
    programme: LoadProgramme,
    folder: Path,
    stream,
    start: Start | None = None,
    t_start: float | None = None,
    *,
    keep: Callable[[RunStep], bool] | None = None,
    kind: SetupKind | None = None,
) -> RunResult:
    """Take ``problem`` through ``programme`` (from ``start``, or from the beginning) with the
    case's recorders writing into ``folder``, then write the summary, fatigue report and
    figures. ``keep(step)``: the steps after which the state is kept in memory as
    ``RunResult.kept`` (a ``Checkpoint``; the last such step's). ``kind``: the case's set-up
    kind, as the run resolved it (None: resolved here, for a caller that starts from the case)."""
    t_start = time.perf_counter() if t_start is None else t_start
    kind = kind_of(case) if kind is None else kind
    warnings: list[str] = []
    if start is None:  # a run from the unloaded strand: warned once, before the first step
        _warn_of_tension(case, warnings, stream)
    recording = Recording(
        case,
        kind,
        problem,
        programme,
        folder,
        stream,
        warnings=warnings,
        keep=keep,
        fresh=start is None,
    )
    setup_seconds = time.perf_counter() - t_start
    outcome = _take_programme(problem, programme, recording, start, stream)
    recorded = recording.result(outcome, setup_seconds)
    result = replace(  # the reference is the kind's reading of the recorded run
        recorded,
        reference=kind.reference(case, recorded),
        seconds=time.perf_counter() - t_start,
        timings=dict(problem.solver.timings, output=recording.seconds),
    )
    summary = summarize(case, result, problem, kind.summary_lines(case, result))
    print(summary, file=stream, flush=True)
    if is_root():  # the summary, report and figures read what every rank has (or rank 0 wrote)
        (folder / "summary.txt").write_text(summary)
        result = _report_and_figures(case, result, problem, recording, stream)
        write_folder_readme(folder)
    return result


def _take_programme(
    problem: StrandProblem[TestSetup],
    programme: LoadProgramme,
    recording: Recording,
    start: Start | None,
    stream,
) -> Outcome:
    """Run the programme with ``recording``'s callback; a stop (Ctrl-C) or a failed step ends
    it at the last converged step, said on ``stream`` and in the outcome; the recorders close."""
    outcome = Outcome()
    try:
        if start is not None:
            recording.start_from(start)
        with Interrupt(stream) as interrupt:
            problem.solver.interrupt = interrupt
            run_programme(
                problem,
                programme,
                recording.on_step,
                start.position if start else None,
                **step_control(recording.case),
                report=recording.progress.note,
            )
    except RunInterrupted as stop:
        outcome = Outcome(
            f"{stop} {_written(recording.folder)}",
            interrupted=True,
            lost_iterations=stop.iterations,
            lost_factorisations=stop.factorisations,
        )
        print(f"strand: stopped: {outcome.failure}", file=stream, flush=True)
    except LoadStepFailure as failure:
        outcome = Outcome(
            f"{failure} {_written(recording.folder)} {STALLED}",
            lost_iterations=failure.iterations,
            lost_factorisations=failure.factorisations,
        )
        print(f"strand: step failed: {outcome.failure}", file=stream, flush=True)
    finally:
        problem.solver.interrupt = None
        recording.close()
    return outcome


#: where a user whose step failed learns what to count and what to try
STALLED = "What stalled and what to try: docs/user-guide/running.md, 'A tension that stops early'."


def _written(folder: Path) -> str:
    """What a run that stopped early has written: its steps, in its folder."""
    return f"The steps up to the last converged one are written in {folder}."


def _report_and_figures(
    case: Case, result: RunResult, problem: StrandProblem[TestSetup], recording: Recording, stream
) -> RunResult:
    """The fatigue report (with a cycle and the histories) and the figures, on rank 0;
    ``result`` with the report."""
    report = None
    if case.fatigue.outputs and len(result.cycle_steps):
        seconds = recording.seconds_of("fatigue_histories")
        report = run_fatigue_report(case, result, seconds, stream, clamp=recording.kind.clamp)
        result = replace(result, fatigue=report)
    if case.output.plots:
        from .fatigue.figures import fatigue_figures
        from .plots import results_figures

        paths = results_figures(case, result, problem, recording.kind)
        if report is not None:
            paths += fatigue_figures(result.folder, report)
        for path in paths:
            print(f"figure: {path}", file=stream)
    return result


def run_fatigue_report(
    case: Case, result: RunResult, recording: float, stream, *, clamp: bool
) -> FatigueReport | None:
    """The fatigue report of the run's histories (``strand.app.fatigue.report``): ``fatigue.txt``
    and the CSV files, with the cost of the histories (``recording`` s) and the report beside the
    run's; ``clamp``: the set-up clamps the strand at z = 0 (``SetupKind.clamp``)."""
    from .fatigue.report import ReportError, fatigue_report

    t0 = time.perf_counter()
    try:
        report = fatigue_report(
            result.folder,
            case.cable,
            case.load.tension,
            case.fatigue,
            case.load.direction,
            clamp=clamp,
        )
    except ReportError as e:
        print(f"strand: no fatigue report: {e}", file=stream, flush=True)
        return None
    seconds = time.perf_counter() - t0
    size = sum((result.folder / f).stat().st_size for f in ("contact_pairs.h5", "wire_sections.h5"))
    cost = (
        f"fatigue outputs: histories {size / 1e6:.1f} MB, recorded in {recording:.1f} s, report "
        f"{seconds:.1f} s; the run {result.seconds:.0f} s"
    )
    with open(result.folder / "fatigue.txt", "a") as f:
        f.write(cost + "\n")
    print(report.text + cost, file=stream, flush=True)
    return report
