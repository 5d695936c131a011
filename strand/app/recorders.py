"""Per-step recorders: each writes one output of a run as the run goes, from typed step records.

After every converged step the runner builds a ``StepContext`` (``strand.app.step_records``: the
``RunStep`` record, the problem, and the cell results computed once, on demand) and hands it to
each recorder. A recorder opens its file when built, appends and flushes at every step (a failed
or interrupted run keeps every step written so far), and closes in ``close``. Units: SI, named in
the column headers.
"""

from __future__ import annotations

import csv
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np
import numpy.typing as npt

from ..beam.parallel import root_open
from ..beam.records import columns, values
from .step_records import SlipFractions, StepBending, StepContext

if TYPE_CHECKING:
    from ..model.cell_results import CellResults
    from ..model.layer_pressure import LayerPressure
    from ..model.pair_results import PairResults

__all__ = [
    "StepTable",
    "AxialForceTable",
    "BendingTable",
    "FieldSeries",
    "KeyStates",
    "state_layer_pressure",
    "SlipTable",
    "SmallSlidingMonitor",
    "CheckpointRecorder",
]


class _CsvFile:
    def __init__(self, path: Path, header: list[str]):
        self.file = root_open(path, "w", newline="")  # noqa: SIM115 (closed in close)
        self.writer = csv.writer(self.file)
        self.writer.writerow(header)
        self.file.flush()

    def close(self) -> None:
        self.file.close()


class StepTable(_CsvFile):
    """``steps.csv``: one row per converged step: number, stage, programme time (the time of
    the field series), the set-up's state, with a ``gauge`` (``reactions.ReactionGauge``) the
    strand's reactions at both ends (``EndReactions``, also kept in ``reactions`` by step
    number), Newton's iterations, cuts and LU factorisations, the contact stabilisation's energy
    fraction and hold (0 none, 1 springs, 2 springs and wider onset, 3 relaxed), wall time (s)
    and final residual norm (N)."""

    def __init__(self, folder: Path, state_type, gauge=None):
        from ..model.reactions import EndReactions

        self.gauge = gauge
        self.reactions: dict[int, EndReactions] = {}
        measured = columns(EndReactions) if gauge is not None else []
        super().__init__(
            Path(folder) / "steps.csv",
            [
                "step",
                "stage",
                "time",
                *columns(state_type),
                *measured,
                "iterations",
                "cuts",
                "failed_iterations",
                "factorisations",
                "stabilisation",
                "hold",
                "seconds",
                "residual_N",
            ],
        )

    def record(self, ctx: StepContext) -> None:
        s = ctx.step
        measured = []
        if self.gauge is not None:
            self.reactions[s.number] = self.gauge.measure(ctx.residual)
            measured = values(self.reactions[s.number])
        self.writer.writerow(
            [
                s.number,
                s.stage,
                f"{s.time:.12g}",
                *values(s.state),
                *measured,
                s.iterations,
                s.cuts,
                s.failed_iterations,
                s.factorisations,
                s.stabilisation,
                s.hold,
                s.seconds,
                s.residual,
            ]
        )
        self.file.flush()


class AxialForceTable:
    """``axial_forces.csv``: the axial force of every element at every step, with its wire,
    layer, initial z (m) and current angle φ (deg), and the value of the set-up's load
    ``parameter`` (in ``unit``) at the step."""

    FORMAT = ["%d", "%.6g", "%d", "%d", "%d", "%.6e", "%.2f", "%.9e"]

    def __init__(self, folder: Path, parameter: str, unit: str):
        self.parameter = parameter
        self.file = root_open(Path(folder) / "axial_forces.csv", "w", newline="")  # noqa: SIM115
        self.file.write(f"step,{parameter}_{unit},element,wire,layer,z_m,phi_deg,N_N\n")
        self.file.flush()

    def record(self, ctx: StepContext) -> None:
        cells = ctx.cells
        n = len(cells.axial)
        load = ctx.problem.setup.get(self.parameter)
        table = np.column_stack(
            [
                np.full(n, ctx.step.number),
                np.full(n, load),
                np.arange(n),
                cells.wire,
                cells.layer,
                cells.z,
                cells.phi,
                cells.axial,
            ]
        )
        np.savetxt(self.file, table, delimiter=",", fmt=self.FORMAT)
        self.file.flush()

    def close(self) -> None:
        self.file.close()


class BendingTable(_CsvFile):
    """``moment_curvature.csv``: the set-up's bending measures at every step of the cycle, also
    kept in ``rows`` (``StepBending``)."""

    def __init__(self, folder: Path, record_type):
        super().__init__(Path(folder) / "moment_curvature.csv", ["step", *columns(record_type)])
        self.rows: list[StepBending] = []

    def record(self, ctx: StepContext) -> None:
        if not ctx.cycle:
            return
        row = ctx.problem.setup.moment_curvature(ctx.cells, ctx.residual)
        self.rows.append(StepBending(ctx.step.number, row))
        self.writer.writerow([ctx.step.number, *values(row)])
        self.file.flush()


class FieldSeries:
    """``fields.xdmf`` (+ ``fields.h5``) and, with ``vtx``, ``fields.bp``: u, θ, section forces and the
    cell ids at every step, at the step's programme time as written in ``steps.csv`` (ParaView's
    time axis), each frame named ``step <n>`` after its row there; ``fields_loads.csv`` beside
    them gives the set-up's loads at every frame. With ``initial``, the series opens with the
    unloaded strand at t = 0 (frame ``step 0``: zero displacement, loads 0), the state before
    the first step of a run from the start."""

    def __init__(self, folder: Path, problem, vtx: bool = True, initial: bool = True):
        from ..beam.fields import FieldWriter, cell_function

        mesh, g = problem.cmesh.mesh, problem.geometry
        ids = [cell_function(mesh, g.cell_wire, "wire"), cell_function(mesh, g.cell_layer, "layer")]
        self.setup = problem.setup
        self.loads = {f"{p}_{self.setup.units[p]}": p for p in self.setup.parameters}
        self.writer = FieldWriter(
            Path(folder) / "fields.xdmf", problem.beam, ids, vtx=vtx, loads=list(self.loads)
        )
        if initial:
            self.writer.write(0.0, "step 0", self._loads())

    def _loads(self) -> dict[str, float]:
        return {name: self.setup.get(p) for name, p in self.loads.items()}

    def record(self, ctx: StepContext) -> None:
        # the time as steps.csv writes it (12 digits), so that the two axes are equal
        t = float(f"{ctx.step.time:.12g}")
        self.writer.write(t, f"step {ctx.step.number}", self._loads())

    def close(self) -> None:
        self.writer.close()


class KeyStates:
    """Keeps the cell results and contact pair results of the tensioned state (last step before
    the cycle) and of the tension's last step (the same state unless a load is then applied and
    held, as ``tension_cycle``'s saddle load), the cell results of the first cycle step, and
    those of the largest abs(cycle load) reached, with the nodal unknowns there ((N, 6) in the
    geometry's point order; for summary and figures)."""

    def __init__(self) -> None:
        self.tensioned: CellResults | None = None
        self.tensioned_pairs: PairResults | None = None
        #: where each layer's pressure goes (``layer_pressure.LayerPressure`` per layer) at the
        #: tensioned state and at the largest abs(cycle load)
        self.tensioned_layers: list[LayerPressure] | None = None
        self.peak_layers: list[LayerPressure] | None = None
        self.tension_end: CellResults | None = None
        self.tension_end_pairs: PairResults | None = None
        self.first_cycle: CellResults | None = None
        self.peak: CellResults | None = None
        self.peak_w: npt.NDArray[np.float64] | None = None
        self._peak_load = 0.0

    def record(self, ctx: StepContext) -> None:
        if not ctx.cycle:
            self.tensioned = ctx.cells
            self.tensioned_pairs = ctx.pairs
            self.tensioned_layers = state_layer_pressure(ctx)
            if ctx.step.parameter == "tension":
                self.tension_end, self.tension_end_pairs = ctx.cells, ctx.pairs
            return
        if self.first_cycle is None:
            self.first_cycle = ctx.cells
        if abs(ctx.step.load) > abs(self._peak_load):
            self._peak_load = ctx.step.load
            self.peak = ctx.cells
            self.peak_w = ctx.problem.model.node_values()
            self.peak_layers = state_layer_pressure(ctx)

    def close(self) -> None:
        pass


def state_layer_pressure(ctx: StepContext) -> list[LayerPressure]:
    """Where each layer's pressure goes at the step (``layer_pressure.layer_pressure``), from the
    wires' axial forces in the middle half; collective."""
    from ..model.layer_pressure import layer_pressure, layer_wire_forces

    model, cells = ctx.problem.model, ctx.cells
    forces = layer_wire_forces(cells.layer, cells.z, cells.axial, model.geometry.length)
    return layer_pressure(
        model.geometry,
        ctx.pairs,
        forces,
        model.positions(),
        same_layer=model.same_layer_pairs,
        same_layer_state=model.same_layer_history(),
    )


class SlipTable(_CsvFile):
    """``slip.csv``: per interface i|i+1, the fraction of its contact pairs that slip (at the
    Coulomb cap) among those whose inner node lies within ``zone`` = (z_min, z_max) (m), at
    every step, with the step's value of the cycle parameter; also kept in ``rows``
    (``SlipFractions``)."""

    def __init__(
        self, folder: Path, geometry, zone: tuple[float, float], parameter: str, unit: str
    ):
        pairs = geometry.pairs
        z = geometry.points[pairs.a, 2]
        inside = (z >= zone[0]) & (z <= zone[1])
        self.n_interfaces = len(geometry.cable.layers) - 1
        self.masks = [inside & (pairs.interface == i) for i in range(self.n_interfaces)]
        self.parameter = parameter
        super().__init__(
            Path(folder) / "slip.csv",
            ["step", f"{parameter}_{unit}"]
            + [f"slipping_{i}|{i + 1}" for i in range(self.n_interfaces)],
        )
        self.rows: list[SlipFractions] = []

    def record(self, ctx: StepContext) -> None:
        slipping = ctx.pairs.slipping
        fractions = [slipping[m].mean() if m.any() else 0.0 for m in self.masks]
        load = ctx.problem.setup.get(self.parameter)
        self.rows.append(SlipFractions(ctx.step.number, load, np.array(fractions, dtype=float)))
        self.writer.writerow([ctx.step.number, load, *fractions])
        self.file.flush()


class SmallSlidingMonitor:
    """Checks at every step that the pairs fixed at t = 0 still face each other
    (``sliding_check.sliding_check``); at the first step where they do not, prints a warning to ``stream``
    and keeps it in ``warnings`` (for the summary). Not used with large sliding."""

    def __init__(self, model, stream, warnings: list[str]):
        self.model = model
        self.stream = stream
        self.warnings = warnings
        self.warned = False

    def record(self, ctx: StepContext) -> None:
        if self.warned:
            return
        from ..model.sliding_check import sliding_check

        m = self.model
        check = sliding_check(m.geometry, m.positions(), ctx.pairs.gap)
        if len(check.exceeded()):
            self.warned = True
            text = f"step {ctx.step.number}: {check.message()}"
            self.warnings.append(text)
            print(f"strand: warning: {text}", file=self.stream, flush=True)

    def close(self) -> None:
        pass


class CheckpointRecorder:
    """``checkpoint.h5``: the last converged state with everything the next step starts from
    (``strand.model.checkpoint``), replaced after every step, so that ``strand run --restart`` can
    continue a stopped run; ``tensioned.h5``: the same at the last step before the cycle, the
    state other load cycles can start from."""

    def __init__(self, folder: Path):
        self.folder = Path(folder)

    def record(self, ctx: StepContext) -> None:
        from ..model.checkpoint import write_checkpoint

        if ctx.position is None:
            return
        write_checkpoint(self.folder / "checkpoint.h5", ctx.checkpoint)
        if not ctx.cycle:
            write_checkpoint(self.folder / "tensioned.h5", ctx.checkpoint)

    def close(self) -> None:
        pass
