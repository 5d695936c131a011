"""The main job: a strand pulled to its tension, then cycled by its test set-up's load.

``run_case`` builds the strand of a ``Case``, its test set-up and load programme, and runs them
with per-step recorders that write as the run goes (so that a failed step loses nothing):

* ``fields.xdmf`` (+ ``.h5``) and ``fields.bp`` (VTX) — u, θ, section forces and wire/layer ids at
  every converged step, at the programme time (stage k runs from t = k to k + 1);
* ``steps.csv`` — every converged step: stage, time, loads, the set-up's measures, Newton's
  iterations and final residual;
* ``axial_forces.csv`` — the axial force of every element (wire, layer, z, φ) at every step;
* ``moment_curvature.csv`` — the set-up's bending measures at every step of the cycle;
* PNG figures at the end (``plots.results_figures``) and ``summary.txt``.

The folder is checked before any computing and never mixes two runs (``folder.py``). Ctrl-C
stops the run at the last converged step, with its summary and figures.
"""

from __future__ import annotations

import sys
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from .case import Case
from .checkpoint import CheckpointError, read_checkpoint, restore
from .folder import RUN_MARKER, FolderError, prepare_results_folder
from .geometry import LINE, build_geometry
from .kinds import kind_of
from .parallel import is_root, on_root, root_stream
from .post import (
    CellEvaluator,
    CellResults,
    bending_stiffness_bounds,
    cell_results,
    fibre_model,
)
from .problem import StrandProblem
from .programme import LoadProgramme, Position, Stage, run_programme
from .recorders import (
    AxialForceTable,
    BendingTable,
    CheckpointRecorder,
    FieldSeries,
    KeyStates,
    PairHistory,
    RunStep,
    SlipTable,
    SmallSlidingMonitor,
    StepContext,
    StepTable,
    WireSectionHistory,
)
from .solver import (
    Interrupt,
    LoadStepFailure,
    NewtonOptions,
    RunInterrupted,
    StepRecord,
)

__all__ = ["RunResult", "run_case", "run_sweep", "summarize", "setup_and_programme"]


@dataclass
class RunResult:
    """What a run produced: its step records, cell results at key states, the folder, the outcome."""

    folder: Path
    steps: list[RunStep] = field(default_factory=list)
    tensioned: CellResults | None = None  # after tension, before the cycle
    tensioned_pairs: dict | None = None  # contact pair results there (``pair_results``)
    #: what the set-up kind's analytical reference predicts for the run (``SetupKind.reference``)
    reference: object | None = None
    peak: CellResults | None = None  # at the largest abs(cycle load) reached
    peak_w: object | None = None  # nodal unknowns at that state
    failure: str = ""  # why the run stopped early ("" if it did not)
    interrupted: bool = False  # stopped by the user (Ctrl-C)
    warnings: list[str] = field(default_factory=list)  # e.g. beyond small sliding
    seconds: float = 0.0
    setup_seconds: float = 0.0
    #: solver wall times (s): residual/jacobian callbacks, pair terms, insertion, whole solves;
    #: and "output", all recorders together
    timings: dict = field(default_factory=dict)
    #: wall time (s) of each recorder over the run, by class name (the first to ask for the
    #: step's cell results, the axial force table, is charged with evaluating them)
    output_timings: dict = field(default_factory=dict)
    cycle_parameter: str = ""
    #: the state kept in memory at the steps ``run_programme_with_outputs(keep=)`` chose
    kept: object | None = None

    @property
    def iterations(self) -> int:
        return sum(s.iterations for s in self.steps)

    @property
    def cycle_steps(self) -> list[RunStep]:
        """The steps of the cycle (after tensioning)."""
        return [s for s in self.steps if s.parameter == self.cycle_parameter]

    @property
    def peak_step(self) -> RunStep | None:
        """The cycle step at the largest abs(load) (None before any)."""
        return max(self.cycle_steps, key=lambda s: abs(s.load), default=None)

    @property
    def unloaded_steps(self) -> list[RunStep]:
        """The cycle steps back at zero load (the residual states of the loop)."""
        return [s for s in self.cycle_steps if abs(s.load) < 1e-12]


class _Progress:
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


def _settings_text(case: Case) -> str:
    lines = [f"case: {case.source}", f"cable: {case.cable.name}"]
    for name in ("mesh", "contact", "load", "steps", "output"):
        lines.append(f"[{name}]")
        section = getattr(case, name)
        items = section.items() if name in ("load", "steps") else vars(section).items()
        for k, v in items:
            lines.append(f"{k} = {v!r}")
    return "\n".join(lines) + "\n"


def setup_and_programme(case: Case):
    """The test set-up factory (taking the model) and the load programme of ``case``."""
    kind = kind_of(case)
    return kind.setup(case), kind.programme(case)


def run_case(
    case: Case,
    folder: str | Path | None = None,
    stream=None,
    overwrite: bool = False,
    restart: str | Path | None = None,
) -> RunResult:
    """Run ``case``; outputs go to ``folder`` (default: the case's output folder), which must be
    new or empty, or hold an earlier run to be replaced with ``overwrite`` (``FolderError``
    otherwise, raised before any computing). ``restart``: a checkpoint (``checkpoint.h5`` of an
    earlier run of the same strand) to continue from, with this case's load programme; the new
    folder's first step is the checkpoint's state."""
    stream = root_stream(stream or sys.stdout)  # printed once in a distributed run
    t_start = time.perf_counter()
    checkpoint = None
    if restart is not None:
        checkpoint = read_checkpoint(restart)
    folder = _results_folder(case, folder or case.output.folder, overwrite, restart)
    problem, programme = build_problem(case, stream)
    try:
        start = None if checkpoint is None else _restart(problem, programme, checkpoint, restart)
        return run_programme_with_outputs(case, problem, programme, folder, stream, start, t_start)
    finally:
        problem.solver.destroy()


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
    _, programme = setup_and_programme(case)
    parameter = programme.cycle_parameter
    names = {a: f"{parameter}_{a:g}" for a in case.load.sweep}
    top = on_root(lambda: _sweep_folder(folder, overwrite, case))
    folders = {
        key: _results_folder(case, top / key, overwrite) for key in ["tension", *names.values()]
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
            member = kind_of(case).with_amplitude(case, amplitude)
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
    from .folder import writable_folder

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
    (path / "sweep.txt").write_text(_settings_text(case))
    return path


@dataclass(frozen=True)
class SweepTable:
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


def _results_folder(case: Case, folder, overwrite: bool, restart=None) -> Path:
    """The run's folder, prepared on rank 0 (``folder.prepare_results_folder``) with the run's
    settings written first; every rank gets the verdict."""

    def prepare() -> Path:
        path = prepare_results_folder(folder, overwrite)
        text = _settings_text(case)
        if restart is not None:
            text += f"restart = {str(restart)!r}\n"
        (path / RUN_MARKER).write_text(text)
        return path

    return on_root(prepare)


def newton_options(case: Case) -> NewtonOptions:
    """Newton's settings from ``[steps]``: the residual tolerance, and the balance test against
    the mean wire tension (forces) and that force on the largest wire diameter (moments)."""
    s = case.steps
    force = s.balance * case.load.tension / case.cable.n_wires
    diameter = max(layer.wire.diameter for layer in case.cable.layers)
    return NewtonOptions(
        atol=s.tolerance, max_it=s.max_iterations, force_tol=force, moment_tol=force * diameter,
        stall_after=NewtonOptions.stall_after if s.stall else 0, linesearch=s.line_search,
    )  # fmt: skip


def build_problem(case: Case, stream=None) -> tuple[StrandProblem, LoadProgramme]:
    """The strand of ``case`` in its test set-up, with the Newton solver, and its programme;
    one line about it on ``stream``."""
    geometry = build_geometry(case.cable, case.mesh.length, case.mesh.h_max)
    options = newton_options(case)
    setup, programme = setup_and_programme(case)
    problem = StrandProblem(geometry, case.contact, options, setup=setup)
    size = problem.model.comm.size
    print(
        f"{case.cable.name}: L = {case.mesh.length:g} m, {len(geometry.wire_layer)} wires, "
        f"{len(geometry.cells)} elements, {6 * len(geometry.points)} unknowns, "
        f"{len(geometry.pairs)} contact pairs, normal = {case.contact.normal}, friction "
        f"{'on' if case.contact.friction else 'off'}" + (f"; {size} MPI ranks" if size > 1 else ""),
        file=stream,
        flush=True,
    )
    if not case.contact.friction and case.contact.normal == "frozen":
        print(
            "frictionless: contact normals frozen at t = 0 (geometry-following normals do not "
            "converge without friction); gaps are approximate in bending (up to ~50 µm on "
            "Cardinal at 4.3 kN), so pair forces are indicative only",
            file=stream,
            flush=True,
        )
    return problem, programme


def _restart(problem: StrandProblem, programme: LoadProgramme, checkpoint, path) -> Start:
    """Put ``checkpoint`` into ``problem`` and say where the programme continues from; a
    checkpoint of another strand or programme is refused in one line (``CheckpointError``)."""
    g = problem.geometry
    if checkpoint.w.shape != (len(g.points), 6) or any(
        len(v) != len(g.pairs) for v in checkpoint.pairs.values()
    ):
        raise CheckpointError(
            f"{path}: written for another strand ({len(checkpoint.w)} points, "
            f"{len(next(iter(checkpoint.pairs.values()), []))} contact pairs; this case has "
            f"{len(g.points)} and {len(g.pairs)}): give the case it was written with"
        )
    if not 0 <= checkpoint.stage < len(programme.stages):
        raise CheckpointError(
            f"{path}: its stage {checkpoint.stage} is not in this case's load programme "
            f"({len(programme.stages)} stages)"
        )
    position = restore(problem, checkpoint)
    stage = programme.stages[checkpoint.stage]
    state = problem.setup.state()
    step = RunStep(checkpoint.number, stage.name, stage.parameter,
                   problem.setup.get(stage.parameter), checkpoint.time, 0, 0, 0.0, 0.0,
                   state)  # fmt: skip
    return Start(position, step)


@dataclass(frozen=True)
class Start:
    """Where a run starts when not from the unloaded strand: the programme ``position`` and the
    record of the step whose state the problem holds (written again as the run's first row)."""

    position: Position
    step: RunStep


def run_programme_with_outputs(
    case: Case,
    problem: StrandProblem,
    programme: LoadProgramme,
    folder: Path,
    stream,
    start: Start | None = None,
    t_start: float | None = None,
    keep: Callable[[RunStep], bool] | None = None,
) -> RunResult:
    """Take ``problem`` through ``programme`` (from ``start``, or from the beginning) with the
    case's recorders writing into ``folder``, then write the summary, fatigue report and
    figures. ``keep(step)``: the steps after which the state is kept in memory as
    ``RunResult.kept`` (a ``Checkpoint``; the last such step's)."""
    t_start = time.perf_counter() if t_start is None else t_start
    result = RunResult(folder)
    geometry = problem.geometry
    evaluator = CellEvaluator(problem.model)
    result.cycle_parameter = programme.cycle_parameter
    key_states = KeyStates()
    su = problem.setup
    cycle = programme.cycle_parameter
    recorders = [
        StepTable(folder, su.state_type),
        AxialForceTable(folder, cycle, su.units[cycle]),
        BendingTable(folder, su.bending_type),
        SlipTable(folder, geometry, su.measuring_zone, cycle, su.units[cycle]),
        key_states,
    ]
    if case.contact.model == "small":
        recorders.append(SmallSlidingMonitor(problem.model, stream, result.warnings))
    if case.output.fields:
        recorders.append(FieldSeries(folder, problem, vtx=case.output.vtx))
    if case.fatigue.outputs:
        initial = cell_results(problem.model, su.direction, evaluator)
        recorders += [
            PairHistory(folder, problem.model, cycle),
            WireSectionHistory(folder, problem.model, initial, su.direction, cycle),
        ]
    if case.output.checkpoint:
        recorders.append(CheckpointRecorder(folder))
    result.setup_seconds = time.perf_counter() - t_start
    kind = kind_of(case)
    progress = _Progress(
        programme, {"tension": ("kN", 1e3), kind.parameter: kind.progress_unit}, stream
    )
    output_seconds = 0.0

    def record(step: RunStep, position: Position) -> StepContext:
        nonlocal output_seconds
        t_out = time.perf_counter()
        result.steps.append(step)
        ctx = StepContext(
            step, problem, step.parameter == programme.cycle_parameter, position=position,
            _evaluate=lambda: cell_results(problem.model, problem.setup.direction, evaluator),
        )  # fmt: skip
        for r in recorders:
            t_r = time.perf_counter()
            r.record(ctx)
            name = type(r).__name__
            result.output_timings[name] = (
                result.output_timings.get(name, 0.0) + time.perf_counter() - t_r
            )
        if keep is not None and keep(step):
            result.kept = ctx.checkpoint
        output_seconds += time.perf_counter() - t_out
        return ctx

    def on_step(stage: Stage, rec: StepRecord, position: Position) -> None:
        value = problem.setup.get(stage.parameter)
        index = position.stage
        number = result.steps[-1].number + 1 if result.steps else 1  # after any start row
        step = RunStep(
            number, rec.stage, stage.parameter, value,
            programme.time(index, value), rec.iterations, rec.cuts, rec.seconds,
            rec.residuals[-1] if rec.residuals else 0.0, problem.setup.state(),
            rec.failed_iterations,
        )  # fmt: skip
        ctx = record(step, position)
        extra = step.state.progress() if ctx.cycle else " " * 14
        progress.step(stage, value, rec.iterations, rec.cuts, extra)

    try:
        if start is not None:  # the state the run starts from, as its first row
            record(start.step, start.position)
            progress.previous[start.step.parameter] = start.step.load
            for i in range(start.position.stage):  # the stages done before it
                s = programme.stages[i]
                progress.previous[s.parameter] = s.target
        with Interrupt(stream) as interrupt:
            problem.solver.interrupt = interrupt
            run_programme(problem, programme, on_step, start.position if start else None)
    except RunInterrupted as stop:
        result.failure, result.interrupted = str(stop), True
        print(f"strand: stopped: {stop}", file=stream, flush=True)
    except LoadStepFailure as failure:
        result.failure = str(failure)
        print(f"strand: step failed: {failure}", file=stream, flush=True)
    finally:
        problem.solver.interrupt = None
        for r in recorders:
            r.close()
    result.tensioned, result.peak, result.peak_w = (
        key_states.tensioned,
        key_states.peak,
        key_states.peak_w,
    )
    result.tensioned_pairs = key_states.tensioned_pairs
    result.reference = kind.reference(case, result)
    result.seconds = time.perf_counter() - t_start
    result.timings = dict(problem.solver.timings, output=output_seconds)
    summary = summarize(case, result, problem)
    print(summary, file=stream, flush=True)
    if is_root():  # the summary, report and figures read what every rank has (or rank 0 wrote)
        (folder / "summary.txt").write_text(summary)
        report = None
        if case.fatigue.outputs and len(result.cycle_steps):
            recording = sum(
                result.output_timings.get(type(r).__name__, 0.0)
                for r in recorders
                if isinstance(r, PairHistory | WireSectionHistory)
            )
            report = run_fatigue_report(case, result, recording, stream)
        if case.output.plots:
            from .plots import fatigue_figures, results_figures

            paths = results_figures(case, result, problem)
            if report is not None:
                paths += fatigue_figures(folder, report)
            for path in paths:
                print(f"figure: {path}", file=stream)
    return result


def run_fatigue_report(case: Case, result: RunResult, recording: float, stream):
    """The fatigue report of the run's histories (``strand.fatigue_report``): ``fatigue.txt`` and
    the CSV files, with the cost of the histories (``recording`` s) and the report beside the
    run's."""
    from .fatigue_report import ReportError, fatigue_report

    t0 = time.perf_counter()
    try:
        report = fatigue_report(
            result.folder, case.cable, case.load.tension, case.fatigue, case.load.direction,
            clamp=kind_of(case).clamp,
        )  # fmt: skip
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


def summarize(case: Case, result: RunResult, problem: StrandProblem) -> str:
    """The closing summary: effort, key results, and the tension stage against the fibre model."""
    its = result.iterations
    failed = sum(s.failed_iterations for s in result.steps)
    cuts = sum(s.cuts for s in result.steps)
    outcome = "INTERRUPTED" if result.interrupted else "FAILED" if result.failure else "done"
    lines = [
        f"{outcome}: {len(result.steps)} steps, {its} Newton iterations (+ {failed} in {cuts} "
        f"failed attempts), {result.seconds:.0f} s ({result.seconds / max(its + failed, 1):.2f} s "
        f"per iteration, set-up {result.setup_seconds:.0f} s); results in {result.folder}",
    ]
    t = result.tensioned
    tension_rows = [s for s in result.steps if s.parameter == "tension"]
    if t is not None and tension_rows:
        # the last converged tension: the target, or where a failed run stopped
        tension = tension_rows[-1].load
        ref = fibre_model(case.cable, tension)
        L = case.mesh.length
        strain = tension_rows[-1].state.end_displacement / L
        lines.append(f"after tension ({tension / 1e3:g} kN)   model    fibre model  diff")
        lines.append(
            f"  strain (µε)              {1e6 * strain:8.0f}  {1e6 * ref['strain']:8.0f}  "
            f"{100 * (strain / ref['strain'] - 1):+6.1f} %"
        )
        middle = np.abs(t.z - L / 2) < L / 4
        for i, f_ref in enumerate(ref["wire_force"]):
            f = t.axial[middle & (t.layer == i)].mean()
            name = "core" if i == 0 else f"layer {i}"
            lines.append(
                f"  wire force {name:8s} (N)  {f:8.0f}  {f_ref:8.0f}  {100 * (f / f_ref - 1):+6.1f} %"
            )
        lines.append(contact_force_line(problem.model.geometry, result.tensioned_pairs))
    lines += kind_of(case).summary_lines(case, result)
    ei_min, ei_max = bending_stiffness_bounds(case.cable)
    lines.append(f"bending stiffness bounds: EI_min {ei_min:.1f} N m², EI_max {ei_max:.0f} N m²")
    for w in result.warnings:
        lines.append(f"warning: {w}")
    if result.failure:
        lines.append(f"{'stopped' if result.interrupted else 'failure'}: {result.failure}")
    return "\n".join(lines) + "\n"


def contact_force_line(geometry, pairs: dict) -> str:
    """Mean contact forces per interface over the middle half of the strand: line pairs per metre
    of layer-1 wire (N/m), crossings per crossing (N)."""
    p = geometry.pairs
    z = geometry.points[p.a, 2]
    middle = np.abs(z - geometry.length / 2) < geometry.length / 4
    parts = []
    for i in range(len(geometry.cable.layers) - 1):
        sel = middle & (p.interface == i)
        if not np.any(sel):
            continue
        line = p.kind[sel] == LINE
        if np.all(line):
            q = pairs["force"][sel].sum() / p.tributary[sel].sum()
            parts.append(f"{i}|{i + 1} {q:.0f} N/m")
        else:
            parts.append(f"{i}|{i + 1} {pairs['force'][sel].mean():.1f} N")
    return "  mean contact force, middle half: " + ", ".join(parts)
