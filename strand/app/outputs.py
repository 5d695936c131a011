"""The registry of a run's outputs: each a name, how to make its recorder from the run (``Run``)
and the files it writes, with what each holds (the folder's ``README.txt``).

``recording.case_recorders`` makes the recorders of every registered output, in the order
registered (a ``make`` returns None where the case does not ask for its output); the folder's
``README.txt`` describes the files from here (``run_files.outputs``), those of the outputs the
run writes itself at its end too (the case, the summary, the fatigue report and the figures:
registered without ``make``). Adding an output file::

    register_output("max_deflection", MaxDeflection,
                    files={"max_deflection.txt": "the largest deflection, m"})

where ``MaxDeflection(run)`` is a recorder (``step_records.Recorder``: ``record(ctx)`` at every
converged step, ``close()`` at the end) writing into ``run.folder``.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from ..beam.registry import Registry
from ..model.cell_results import CellEvaluator, cell_results
from ..model.reactions import ReactionGauge
from .fatigue.recorders import PairHistory, WireSectionHistory
from .recorders import (
    AxialForceTable,
    BendingTable,
    CheckpointRecorder,
    FieldSeries,
    KeyStates,
    SlipTable,
    SmallSlidingMonitor,
    StepTable,
)
from .step_records import Recorder

__all__ = ["Run", "Output", "register_output", "unregister_output", "registered_outputs"]


@dataclass(frozen=True, kw_only=True)
class Run:
    """What an output's recorder is made from: the case, the problem, the run's ``folder``, the
    cycle's load ``parameter`` and its ``unit``, the run's ``KeyStates`` and ``CellEvaluator``,
    the progress ``stream``, the list the run's ``warnings`` go to, and ``fresh``: the run
    starts from the unloaded strand (not from a restart or a sweep's tensioned state)."""

    case: Any
    problem: Any
    folder: Path
    parameter: str
    unit: str
    key_states: KeyStates
    evaluator: CellEvaluator
    stream: Any
    warnings: list[str] = field(default_factory=list)
    fresh: bool = True


#: make(run) → a recorder, a list of them, or None (the case does not ask for the output)
Make = Callable[[Run], "Recorder | list[Recorder] | None"]


@dataclass(frozen=True)
class Output:
    """A registered output: its name, ``make`` (None: no recorder, the run writes the files
    itself) and the ``files`` it writes (name → what)."""

    name: str
    make: Make | None
    files: dict[str, str]


_OUTPUTS: Registry[Output] = Registry("output")


def register_output(name: str, make: Make | None, *, files: dict[str, str] | None = None) -> Output:
    """Record the output ``name`` in every run: ``make(run)`` (``Run``) gives its recorder(s)
    or None (None for ``make``: the run writes the files itself); ``files``: the files they
    write, each with what it holds (``README.txt``)."""
    return _OUTPUTS.register(name, Output(name, make, dict(files or {})))


def unregister_output(name: str) -> None:
    """Take the output ``name`` out of the registry."""
    _OUTPUTS.unregister(name)


def registered_outputs() -> tuple[Output, ...]:
    """The registered outputs, in the order they were registered."""
    return _OUTPUTS.entries()


def _fatigue(run: Run) -> list[Recorder] | None:
    if not run.case.fatigue.outputs:
        return None
    su = run.problem.setup
    initial = cell_results(run.problem.model, su.direction, run.evaluator)
    return [
        PairHistory(run.folder, run.problem.model, run.parameter),
        WireSectionHistory(run.folder, run.problem.model, initial, su.direction, run.parameter),
    ]


# the files a run writes itself, outside its recorders (the set-up kind, the settings and the
# outcome decide which are there)
register_output(
    "case",
    None,
    files={
        "case.toml": "the whole case of the run, every setting and the cable written out, with "
        "the strand version: `strand run case.toml --out <new folder>` runs it again",
        "README.txt": "this list",
    },
)
register_output(
    "summary",
    None,
    files={
        "summary.txt": "the outcome, effort, the tensioned state against the fibre model, the "
        "set-up's own results and any warning",
    },
)
register_output(
    "fatigue_report",
    None,
    files={
        "fatigue.txt": "the fatigue report: stress ranges, S-N damage, fretting",
        "crossings.csv": "fatigue: per contact pair, the worst cycle's slip amplitude and forces",
        "wire_stresses.csv": "fatigue: per element, the surface stresses at its point of largest "
        "stress range (range, mean, peak) and their damage",
        "wires.csv": "fatigue: per wire, the largest stress range and its damage",
    },
)
register_output(
    "figures",
    None,
    files={
        "load_deflection.png": "figure: load against deflection over the cycle",
        "moment_curvature.png": "figure: bending moment against curvature",
        "axial_force_sectors.png": "figure: wire axial forces per layer and sector",
        "axial_force_change.png": "figure: change of wire axial forces over the cycle",
        "deformed_axial_force.png": "figure: the deformed strand coloured by axial force "
        "(displacements across the axis magnified, factor in the title)",
        "fretting_map.png": "figure: the contact pairs that slid, per interface",
        "stress_range.png": "figure: every layer's stress ranges, the largest marked, "
        "against the S-N curves",
        "layer_pressure.png": "figure: per layer, its pressure on the crossings below, its "
        "same-layer ring's share and the fibre model, tensioned and at the peak",
    },
)
# the recorders' outputs
register_output(
    "steps",
    lambda run: StepTable(run.folder, run.problem.setup.state_type, ReactionGauge(run.problem)),
    files={
        "steps.csv": "one row per converged load step: stage, programme time, loads, the "
        "set-up's measures, Newton iterations, residual (N), wall time (s)"
    },
)
register_output(
    "axial_forces",
    lambda run: AxialForceTable(run.folder, run.parameter, run.unit),
    files={
        "axial_forces.csv": "the axial force (N) of every element at every step, with its "
        "wire, layer, height z (m) and angle"
    },
)
register_output(
    "moment_curvature",
    lambda run: BendingTable(run.folder, run.problem.setup.bending_type),
    files={
        "moment_curvature.csv": "the set-up's section measures (bending moment, curvature, "
        "axial sum) at every step of the cycle"
    },
)
register_output(
    "slip",
    lambda run: SlipTable(
        run.folder, run.problem.geometry, run.problem.setup.measuring_zone, run.parameter, run.unit
    ),
    files={
        "slip.csv": "per interface, the share of contact pairs slipping in the measuring "
        "zone, at every step"
    },
)
register_output("key_states", lambda run: run.key_states)
register_output(
    "small_sliding_check",
    lambda run: (
        SmallSlidingMonitor(run.problem.model, run.stream, run.warnings)
        if run.case.contact.model == "small"
        else None
    ),
)
register_output(
    "fields",
    lambda run: (
        FieldSeries(run.folder, run.problem, vtx=run.case.output.vtx, initial=run.fresh)
        if run.case.output.fields
        else None
    ),
    files={
        "fields.xdmf": "field time series for ParaView (with fields.h5): displacement, "
        "rotation, section forces, wire and layer ids; time t = k to k + 1 is stage k of "
        "steps.csv",
        "fields.h5": "the data of fields.xdmf",
        "fields_loads.csv": "the set-up's loads at every frame of the field series (t = 0 the "
        "unloaded strand, then each step of steps.csv)",
        "fields.bp": "the same fields as VTX (ADIOS2), a folder: ParaView",
    },
)
register_output(
    "fatigue_histories",
    _fatigue,
    files={
        "contact_pairs.h5": "every contact pair's history: gap, normal force, traction, slip",
        "contact_points.xdmf": "the contact pairs' history as points, for ParaView",
        "wire_sections.h5": "every element's section forces (axial force, bending moments, "
        "torque) and spin, at the tensioned state and every cycle step",
    },
)
register_output(
    "checkpoint",
    lambda run: CheckpointRecorder(run.folder) if run.case.output.checkpoint else None,
    files={
        "checkpoint.h5": "the last converged state: `strand run <case> --restart checkpoint.h5`",
        "tensioned.h5": "the state after tension, before the cycle (a restart point)",
    },
)
