"""The main job: a strand pulled to its tension, then cycled by a lateral saddle load at midspan.

``run_case`` builds the strand of a ``Case``, ramps the tension, runs the lateral cycle, and writes
as it goes (so that a failed step loses nothing):

* ``fields.xdmf`` — u, θ, section forces and wire/layer ids at every converged step (ParaView);
* ``steps.csv`` — every converged step: stage, loads, deflection, Newton iterations, time;
* ``axial_forces.csv`` — the axial force of every element (wire, layer, z, φ) at every step;
* ``moment_curvature.csv`` — midspan bending moment and curvature at every lateral step;
* PNG figures at the end (``plots.results_figures``) and ``summary.txt``.
"""

from __future__ import annotations

import csv
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

import strand  # noqa: F401

from .case import Case  # isort: skip
from .geometry import build_geometry  # isort: skip
from .output import FieldWriter, cell_function  # isort: skip
from .post import (  # isort: skip
    CellResults,
    CellEvaluator,
    bending_stiffness_bounds,
    cell_results,
    fibre_model,
    midspan_moment_curvature,
)
from .problem import StrandProblem  # isort: skip
from .solver import LoadStepFailure, LoadStepper, NewtonOptions, StepRecord  # isort: skip

__all__ = ["RunResult", "run_case", "summarize"]

FORCE_COLUMNS = ["%d", "%.6g", "%d", "%d", "%d", "%.6e", "%.2f", "%.6e"]


@dataclass
class RunResult:
    """What a run produced: per-step rows, cell results at key states, the folder, the outcome."""

    folder: Path
    steps: list[dict] = field(default_factory=list)
    tensioned: CellResults | None = None  # after tension, before the lateral load
    peak: CellResults | None = None  # at the largest |P| reached
    peak_w: np.ndarray | None = None  # nodal unknowns at that state
    failure: str = ""
    seconds: float = 0.0
    setup_seconds: float = 0.0
    #: solver wall times (s): residual/jacobian callbacks, pair terms, insertion, whole solves
    timings: dict = field(default_factory=dict)

    @property
    def iterations(self) -> int:
        return sum(s["iterations"] for s in self.steps)

    @property
    def lateral_steps(self) -> list[dict]:
        """The step rows of the lateral cycle (after tensioning)."""
        return [s for s in self.steps if s["stage"] != "tension"]

    @property
    def peak_step(self) -> dict | None:
        """The lateral step row at the largest |P| (None before any)."""
        return max(self.lateral_steps, key=lambda s: abs(s["lateral"]), default=None)

    @property
    def unloaded_steps(self) -> list[dict]:
        """The lateral step rows back at P = 0 (the residual deflections of the loop)."""
        return [s for s in self.lateral_steps if abs(s["lateral"]) < 1e-9]


class _Progress:
    """One line per converged step: a bar over the whole load path, load, iterations, time."""

    def __init__(self, stream):
        self.done = 0.0  # fraction of the load path
        self.stream = stream
        self.t0 = time.perf_counter()

    def step(self, stage: str, load: str, its: int, cuts: int, extra=""):
        width = 24
        filled = int(round(width * min(self.done, 1.0)))
        bar = "#" * filled + "." * (width - filled)
        cut = f", {cuts} cut{'s' * (cuts > 1)}" if cuts else ""
        print(
            f"[{bar}] {stage:8s} {load}  {its:2d} Newton its{cut}"
            f"  {extra}  {time.perf_counter() - self.t0:6.1f} s",
            file=self.stream,
            flush=True,
        )


def _settings_text(case: Case) -> str:
    lines = [f"case: {case.source}", f"cable: {case.cable.name}"]
    for name in ("mesh", "contact", "load", "steps", "output"):
        lines.append(f"[{name}]")
        for k, v in vars(getattr(case, name)).items():
            lines.append(f"{k} = {v!r}")
    return "\n".join(lines) + "\n"


def run_case(case: Case, folder: str | Path | None = None, stream=sys.stdout) -> RunResult:
    """Run ``case``; outputs go to ``folder`` (default: the case's output folder)."""
    folder = Path(folder or case.output.folder)
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "settings.txt").write_text(_settings_text(case))
    result = RunResult(folder)
    t_start = time.perf_counter()

    geometry = build_geometry(case.cable, case.mesh.length, case.mesh.h_max)
    options = NewtonOptions(atol=case.steps.tolerance, max_it=case.steps.max_iterations)
    problem = StrandProblem(
        geometry,
        case.contact,
        options,
        saddle_length=case.load.saddle_length,
        direction=case.load.direction,
    )
    evaluator = CellEvaluator(problem)
    n_cells = len(geometry.cells)
    print(
        f"{case.cable.name}: L = {case.mesh.length:g} m, {len(geometry.wire_layer)} wires, "
        f"{n_cells} elements, {problem.w.x.array.size} unknowns, {len(geometry.pairs)} contact "
        f"pairs, normal = {case.contact.normal}, friction {'on' if case.contact.friction else 'off'}",
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
    writer = None
    if case.output.fields:
        ids = [
            cell_function(problem.cmesh.mesh, geometry.cell_wire, "wire"),
            cell_function(problem.cmesh.mesh, geometry.cell_layer, "layer"),
        ]
        writer = FieldWriter(folder / "fields.xdmf", problem.beam, ids)
    steps_file = open(folder / "steps.csv", "w", newline="")  # noqa: SIM115 (closed below)
    steps_csv = csv.writer(steps_file)
    steps_csv.writerow(
        ["step", "stage", "tension_N", "lateral_N", "deflection_m", "end_displacement_m",
         "iterations", "cuts", "seconds"]
    )  # fmt: skip
    forces_file = open(folder / "axial_forces.csv", "w", newline="")  # noqa: SIM115
    forces_file.write("step,lateral_N,element,wire,layer,z_m,phi_deg,N_N\n")
    mk_file = open(folder / "moment_curvature.csv", "w", newline="")  # noqa: SIM115
    mk_csv = csv.writer(mk_file)
    mk_csv.writerow(["step", "lateral_N", "curvature_1_per_m", "moment_Nm", "axial_sum_N"])
    result.setup_seconds = time.perf_counter() - t_start

    # progress: tension counts for 10 % of the path (a few steps), the lateral cycle for the rest
    lateral_path = np.abs(np.diff([0.0, *case.load.cycle])).sum() * abs(case.load.lateral)
    tension_weight = 0.1 if lateral_path > 0 else 1.0
    progress = _Progress(stream)
    elements = np.arange(n_cells)
    peak_load = 0.0

    def on_step(rec: StepRecord) -> None:
        nonlocal peak_load, output_seconds
        t_out = time.perf_counter()
        k = len(result.steps) + 1
        row = {
            "step": k,
            "stage": rec.stage,
            "tension": problem.tension,
            "lateral": problem.lateral,
            "deflection": problem.midspan_deflection(),
            "end_displacement": problem.end_displacement(),
            "iterations": rec.iterations,
            "cuts": rec.cuts,
            "seconds": rec.seconds,
        }
        result.steps.append(row)
        steps_csv.writerow(list(row.values()))
        steps_file.flush()
        cells = cell_results(problem, evaluator)
        table = np.column_stack(
            [np.full(n_cells, k), np.full(n_cells, problem.lateral), elements, cells.wire,
             cells.layer, cells.z, cells.phi, cells.axial]
        )  # fmt: skip
        np.savetxt(forces_file, table, delimiter=",", fmt=FORCE_COLUMNS)
        forces_file.flush()
        if rec.stage != "tension":
            M, kappa, axial = midspan_moment_curvature(problem, cells)
            mk_csv.writerow([k, problem.lateral, kappa, M, axial])
            mk_file.flush()
            if abs(problem.lateral) > abs(peak_load):
                peak_load = problem.lateral
                result.peak = cells
                result.peak_w = problem.w.x.array.copy()
        if writer is not None:
            writer.write(float(k))
        output_seconds += time.perf_counter() - t_out
        # progress
        if rec.stage == "tension":
            result.tensioned = cells  # the last tension step is the tensioned state
            progress.done = tension_weight * abs(problem.tension / case.load.tension)
            load = f"{problem.tension / 1e3:8.2f} kN tension"
            extra = " " * 14
        else:
            before = result.steps[-2]["lateral"] if len(result.steps) > 1 else 0.0
            progress.done += (1 - tension_weight) * abs(problem.lateral - before) / lateral_path
            load = f"{problem.lateral / 1e3:8.2f} kN lateral"
            extra = f"δ = {1e3 * row['deflection']:7.2f} mm"
        progress.step(rec.stage, load, rec.iterations, rec.cuts, extra)

    output_seconds = 0.0
    steps = case.steps
    try:
        tension = LoadStepper(
            problem.solver, steps.tension, steps.tension / 2**steps.cuts,
            growth=steps.growth, on_step=on_step,
        )  # fmt: skip
        tension.ramp(problem.set_tension, 0.0, case.load.tension, "tension")
        lateral = LoadStepper(
            problem.solver, steps.lateral, steps.lateral / 2**steps.cuts,
            max_step=steps.lateral_max, growth=steps.growth, on_step=on_step, extrapolate=True,
        )  # fmt: skip
        current = 0.0
        for i, target in enumerate(case.load.cycle):
            P = target * case.load.lateral
            lateral.step = steps.lateral  # every leg starts small: the direction reverses
            lateral.ramp(problem.set_lateral, current, P, f"leg {i + 1}")
            current = P
    except LoadStepFailure as failure:
        result.failure = str(failure)
        print(f"strand: step failed: {failure}", file=stream, flush=True)
    finally:
        for f in (steps_file, forces_file, mk_file):
            f.close()
        if writer is not None:
            writer.close()
    result.seconds = time.perf_counter() - t_start
    result.timings = dict(problem.solver.timings, output=output_seconds)
    summary = summarize(case, result, problem)
    (folder / "summary.txt").write_text(summary)
    print(summary, file=stream, flush=True)
    if case.output.plots:
        from .plots import results_figures

        for path in results_figures(case, result, problem):
            print(f"figure: {path}", file=stream)
    return result


def summarize(case: Case, result: RunResult, problem: StrandProblem) -> str:
    """The closing summary: effort, key results, and the tension stage against the fibre model."""
    its = result.iterations
    lines = [
        f"{'FAILED' if result.failure else 'done'}: {len(result.steps)} steps, {its} Newton "
        f"iterations, {result.seconds:.0f} s ({result.seconds / max(its, 1):.2f} s per iteration, "
        f"set-up {result.setup_seconds:.0f} s); results in {result.folder}",
    ]
    t = result.tensioned
    if t is not None:
        ref = fibre_model(case.cable, case.load.tension)
        L = case.mesh.length
        tension_rows = [s for s in result.steps if s["stage"] == "tension"]
        strain = tension_rows[-1]["end_displacement"] / L
        lines.append(f"after tension ({case.load.tension / 1e3:g} kN)   model    fibre model  diff")
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
    peak = result.peak_step
    if peak is not None:
        lines.append(
            f"largest lateral load {peak['lateral'] / 1e3:.2f} kN: midspan deflection "
            f"{1e3 * peak['deflection']:.2f} mm, end displacement {1e3 * peak['end_displacement']:.3f} mm"
        )
        zero = result.unloaded_steps
        if zero:
            lines.append(
                "back at P = 0: deflection "
                + ", ".join(f"{1e3 * s['deflection']:+.2f} mm" for s in zero)
            )
    ei_min, ei_max = bending_stiffness_bounds(case.cable)
    lines.append(f"bending stiffness bounds: EI_min {ei_min:.1f} N m², EI_max {ei_max:.0f} N m²")
    if result.failure:
        lines.append(f"failure: {result.failure}")
    return "\n".join(lines) + "\n"
