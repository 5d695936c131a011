"""The runner: a problem taken through its load programme with the run's recorders, then the
summary, the fatigue report and the figures.

``run_programme_with_outputs`` is what ``strand run`` and every sweep member do once the problem
is built (``strand.app.build``). After every converged step a ``Recording`` makes the step's record,
hands it to each recorder (``strand.app.recorders``) and prints a progress line; Ctrl-C or a step
that cannot converge stops the programme at the last converged step, whose outputs are then
finished like a complete run's. Times in s.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass, replace
from pathlib import Path
from typing import TYPE_CHECKING

from ..beam.parallel import is_root
from ..model.cell_results import CellEvaluator, cell_results
from ..model.problem import StrandProblem
from ..model.programme import LoadProgramme, Position, Stage, run_programme
from ..setups import TestSetup
from ..solver import Interrupt, LoadStepFailure, RunInterrupted, StepRecord
from .build import step_control
from .checks import tension_warning
from .kinds import SetupKind, kind_of
from .outputs import Run, registered_outputs
from .recorders import BendingTable, KeyStates, SlipTable, StepTable
from .run_files import write_folder_readme
from .run_result import RunResult, Start
from .settings import Case
from .step_records import Recorder, RunStep, StepContext
from .summary import summarize, wire_stress_line, yield_warnings

if TYPE_CHECKING:
    from ..model.checkpoint import Checkpoint
    from .fatigue.findings import FatigueReport

__all__ = ["run_programme_with_outputs", "Recording", "Progress", "run_fatigue_report"]


class Progress:
    """One line per converged step: a bar over the whole load programme, load, iterations, time."""

    def __init__(self, programme: LoadProgramme, units: dict[str, tuple[str, float]], stream):
        self.share = {
            stage: weight / (length or 1.0)
            for stage, weight, length in zip(
                programme.stages, programme.weights(), programme.path_lengths(), strict=True
            )
        }
        self.units = units  # parameter → (unit label, scale)
        self.stream = stream
        self.done = 0.0
        self.previous: dict[str, float] = {}
        self.t0 = time.perf_counter()

    def step(self, stage: Stage, value: float, its: int, cuts: int, extra: str = "") -> None:
        self.done += self.share[stage] * abs(value - self.previous.get(stage.parameter, 0.0))
        self.previous[stage.parameter] = value
        width = 24
        filled = int(round(width * min(self.done, 1.0)))
        bar = "#" * filled + "." * (width - filled)
        cut = f", {cuts} cut{'s' * (cuts > 1)}" if cuts else ""
        unit, scale = self.units.get(stage.parameter, ("", 1.0))
        load = f"{value / scale:8.2f} {unit} {stage.parameter}"
        print(
            f"[{bar}] {stage.name:8s} {load}  {its:2d} Newton its{cut}"
            f"  {extra}  {time.perf_counter() - self.t0:6.1f} s",
            file=self.stream,
            flush=True,
        )


def case_recorders(
    case: Case,
    problem: StrandProblem[TestSetup],
    folder: Path,
    parameter: str,
    key_states: KeyStates,
    evaluator: CellEvaluator,
    stream,
    *,
    warnings: list[str],
    fresh: bool = True,
) -> dict[str, list[Recorder]]:
    """The recorders of the registered outputs (``outputs``) the case's settings ask for, by
    output name in the order registered, writing into ``folder``; ``parameter``: the cycle's
    load parameter; ``fresh``: the run starts from the unloaded strand (its field series opens
    with it at t = 0), not from a restart or a sweep's tensioned state."""
    run = Run(
        case=case,
        problem=problem,
        folder=Path(folder),
        parameter=parameter,
        unit=problem.setup.units[parameter],
        key_states=key_states,
        evaluator=evaluator,
        stream=stream,
        warnings=warnings,
        fresh=fresh,
    )
    recorders: dict[str, list[Recorder]] = {}
    for output in registered_outputs():
        made = output.make(run) if output.make is not None else None
        if made is not None:
            recorders[output.name] = made if isinstance(made, list) else [made]
    return recorders


class Recording:
    """The recorders and progress lines of one run: ``on_step`` after every converged step
    (``run_programme``'s callback) records it into ``steps`` and every recorder; ``result``
    makes the run's ``RunResult`` of them once the run has ended.

    Args:
        kind: the case's set-up kind, as the run resolved it (``kinds.kind_of``).
        folder: where the recorders write.
        warnings: the run's warnings so far; the recorders add theirs to it.
        keep: the steps after which the state is kept in memory as ``kept``.
        fresh: the run starts from the unloaded strand (not from a ``Start``).
    """

    def __init__(
        self,
        case: Case,
        kind: SetupKind,
        problem: StrandProblem[TestSetup],
        programme: LoadProgramme,
        folder: Path,
        stream,
        *,
        warnings: list[str],
        keep: Callable[[RunStep], bool] | None = None,
        fresh: bool = True,
    ):
        self.problem, self.programme, self.folder, self.keep = problem, programme, folder, keep
        self.case, self.kind, self.stream = case, kind, stream
        self.steps: list[RunStep] = []
        self.warnings = warnings
        #: wall time (s) of each recorder over the run, by class name
        self.output_timings: dict[str, float] = {}
        self.kept: Checkpoint | None = None  # the state at the last step ``keep`` chose
        self.evaluator = CellEvaluator(problem.model)
        self.key_states = KeyStates()
        self.outputs = case_recorders(
            case,
            problem,
            folder,
            programme.cycle_parameter,
            self.key_states,
            self.evaluator,
            stream,
            warnings=warnings,
            fresh=fresh,
        )
        self.recorders = [r for made in self.outputs.values() for r in made]
        self.bending: BendingTable = self.recorder("moment_curvature")
        self.slip: SlipTable = self.recorder("slip")
        self.steps_table: StepTable = self.recorder("steps")
        units = {"tension": ("kN", 1e3), kind.parameter: kind.progress_unit}
        self.progress = Progress(programme, units, stream)
        self.seconds = 0.0  # wall time of all recorders together

    def record(self, step: RunStep, position: Position) -> StepContext:
        """Hand ``step`` to every recorder (timed each), keep its state if asked."""
        t_out = time.perf_counter()
        problem = self.problem
        self.steps.append(step)
        ctx = StepContext(
            step,
            problem,
            step.parameter == self.programme.cycle_parameter,
            position=position,
            _evaluate=lambda: cell_results(problem.model, problem.setup.direction, self.evaluator),
        )
        for r in self.recorders:
            t_r = time.perf_counter()
            r.record(ctx)
            name = type(r).__name__
            self.output_timings[name] = (
                self.output_timings.get(name, 0.0) + time.perf_counter() - t_r
            )
        if self.keep is not None and self.keep(step):
            self.kept = ctx.checkpoint
        self.seconds += time.perf_counter() - t_out
        return ctx

    def on_step(self, stage: Stage, rec: StepRecord, position: Position) -> None:
        """The record of a converged step of ``stage`` (``run_programme``'s callback)."""
        setup = self.problem.setup
        value = setup.get(stage.parameter)
        steps = self.steps
        number = steps[-1].number + 1 if steps else 1  # after any start row
        step = RunStep(
            number,
            rec.stage,
            stage.parameter,
            value,
            self.programme.time(position.stage, value),
            rec.iterations,
            rec.cuts,
            rec.seconds,
            rec.residuals[-1] if rec.residuals else 0.0,
            setup.state(),
            rec.failed_iterations,
            rec.factorisations,
            stabilisation=rec.stabilisation,
        )
        ctx = self.record(step, position)
        extra = step.state.progress() if ctx.cycle else " " * 14
        if rec.stabilisation:
            extra += f"  stabilised: {rec.stabilisation:.1e} of the strain energy"
        self.progress.step(stage, value, rec.iterations, rec.cuts, extra)
        if stage.parameter == "tension" and value == stage.target:
            self.tensioned(ctx)

    def tensioned(self, ctx: StepContext) -> None:
        """At the end of the tension: the mean wire stress per layer, and a warning (kept for
        the summary) for every layer whose wires pass the yield stress given with the cable."""
        cable, length = self.case.cable, self.problem.geometry.length
        print(wire_stress_line(cable, ctx.cells, length).strip(), file=self.stream, flush=True)
        for warning in yield_warnings(cable, ctx.cells):
            self.warnings.append(warning)
            print(f"strand: warning: {warning}", file=self.stream, flush=True)

    def start_from(self, start: Start) -> None:
        """The state the run starts from, as its first row; the stages before it done."""
        self.record(start.step, start.position)
        self.progress.previous[start.step.parameter] = start.step.load
        for stage in self.programme.stages[: start.position.stage]:
            self.progress.previous[stage.parameter] = stage.target

    def recorder(self, output: str) -> Recorder:
        """The recorder of the registered output ``output`` (``outputs``), one that makes one."""
        (recorder,) = self.outputs[output]
        return recorder

    def seconds_of(self, *outputs: str) -> float:
        """Wall time (s) of the recorders of the registered ``outputs`` over the run."""
        timings = self.output_timings
        return sum(
            timings.get(type(r).__name__, 0.0)
            for name in outputs
            for r in self.outputs.get(name, [])
        )

    def close(self) -> None:
        for r in self.recorders:
            r.close()

    def result(self, outcome: Outcome, setup_seconds: float) -> RunResult:
        """The run's record of what has been recorded, with its ``outcome``; no reference,
        fatigue report or times but ``setup_seconds`` yet."""
        keys = self.key_states
        return RunResult(
            folder=self.folder,
            steps=tuple(self.steps),
            bending=tuple(self.bending.rows),
            slip=tuple(self.slip.rows),
            reactions=self.steps_table.reactions,
            tensioned=keys.tensioned,
            tensioned_pairs=keys.tensioned_pairs,
            tension_end=keys.tension_end,
            tension_end_pairs=keys.tension_end_pairs,
            first_cycle=keys.first_cycle,
            peak=keys.peak,
            peak_w=keys.peak_w,
            failure=outcome.failure,
            interrupted=outcome.interrupted,
            failed_step_effort=(outcome.lost_iterations, outcome.lost_factorisations),
            warnings=tuple(self.warnings),
            setup_seconds=setup_seconds,
            output_timings=self.output_timings,
            cycle_parameter=self.programme.cycle_parameter,
            kept=self.kept,
            tensioned_layers=_tuple_or_none(keys.tensioned_layers),
            peak_layers=_tuple_or_none(keys.peak_layers),
        )


def _tuple_or_none[T](items: list[T] | None) -> tuple[T, ...] | None:
    return None if items is None else tuple(items)


@dataclass(frozen=True)
class Outcome:
    """How a load programme ended: ``failure``, why it stopped early ("" if it did not), and
    whether the user stopped it (Ctrl-C)."""

    failure: str = ""
    interrupted: bool = False
    #: the Newton iterations and LUs of the attempts after the last converged step
    #: (``LoadStepFailure``, ``RunInterrupted``)
    lost_iterations: int = 0
    lost_factorisations: int = 0


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
            f"{failure} {_written(recording.folder)}",
            lost_iterations=failure.iterations,
            lost_factorisations=failure.factorisations,
        )
        print(f"strand: step failed: {outcome.failure}", file=stream, flush=True)
    finally:
        problem.solver.interrupt = None
        recording.close()
    return outcome


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
