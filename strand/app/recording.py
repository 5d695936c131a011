"""A run's recording: the recorders the case's settings ask for, and what the run does with them
after every converged step (the step's record, handed to each recorder, and a progress line).

``case_recorders`` makes the recorders of the registered outputs (``strand.app.outputs``);
``Recording`` holds them through one run: its ``on_step``, ``run_programme``'s callback, makes the
step's record (``RunStep``), hands it to every recorder (timed each) and prints the ``Progress``
line, and its ``result`` makes the run's ``RunResult`` of what was recorded and how the programme
ended (``Outcome``) once the run has ended. The runner (``strand.app.runner``) takes the programme
with it. Times in s.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

from ..model.cell_results import CellEvaluator, cell_results
from ..model.problem import StrandProblem
from ..model.programme import LoadProgramme, Position, Stage
from ..setups import TestSetup
from ..solver import StepRecord
from .kinds import SetupKind
from .outputs import Run, registered_outputs
from .recorders import BendingTable, KeyStates, SlipTable, StepTable
from .run_result import RunResult, Start
from .settings import Case
from .step_records import HOLDS, Recorder, RunStep, StepContext
from .summary import wire_stress_line, yield_warnings

if TYPE_CHECKING:
    from ..model.checkpoint import Checkpoint

__all__ = ["Recording", "Progress"]


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

    def note(self, line: str) -> None:
        """A line within a step (a relaxation's pseudo-time step), with the elapsed time."""
        print(
            f"{'':26} {line}  {time.perf_counter() - self.t0:6.1f} s", file=self.stream, flush=True
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
            hold=rec.hold,
        )
        ctx = self.record(step, position)
        extra = step.state.progress() if ctx.cycle else " " * 14
        if rec.hold == 3:  # an equilibrium of the strand: nothing held
            extra += f"  {HOLDS[rec.hold]}"
        elif rec.hold:
            extra += f"  {HOLDS[rec.hold]}: {rec.stabilisation:.1e} of the strain energy"
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
