"""Per-step recorders: each writes one output of a run as the run goes, from typed step records.

After every converged step the runner builds a ``StepContext`` (the ``RunStep`` record, the
problem, and the cell results computed once, on demand) and hands it to each recorder. A recorder
opens its file when built, appends and flushes at every step (a failed or interrupted run keeps
every step written so far), and closes in ``close``. Units: SI, named in the column headers.
"""

from __future__ import annotations

import csv
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Protocol

import numpy as np

from .parallel import root_open
from .setups.base import columns, values

__all__ = [
    "RunStep",
    "StepContext",
    "Recorder",
    "StepTable",
    "AxialForceTable",
    "BendingTable",
    "FieldSeries",
    "KeyStates",
    "SlipTable",
    "SmallSlidingMonitor",
    "PairHistory",
    "WireSectionHistory",
    "CheckpointRecorder",
]


@dataclass(frozen=True)
class RunStep:
    """One converged step of a run: its number (from 1), stage, the parameter it ramps and that
    parameter's value, the programme time (``LoadProgramme.time``), Newton's effort (iterations,
    step cuts before it, wall time s, final residual norm N), the set-up's measures (``state``)
    and the iterations of the failed attempts before it."""

    number: int
    stage: str
    parameter: str
    load: float
    time: float
    iterations: int
    cuts: int
    seconds: float
    residual: float
    state: Any
    failed_iterations: int = 0


@dataclass
class StepContext:
    """What recorders see at a step: the record, the problem, and the cell results (lazy)."""

    step: RunStep
    problem: Any
    cycle: bool  # a step of the cycle (not of the tensioning)
    _cells: Any = field(default=None, repr=False)
    _evaluate: Any = field(default=None, repr=False)

    _residual: Any = field(default=None, repr=False)
    _pairs: Any = field(default=None, repr=False)
    #: where the run stands in its programme (``programme.Position``), for checkpoints
    position: Any = None
    _checkpoint: Any = field(default=None, repr=False)

    @property
    def checkpoint(self):
        """The state at this step as a ``checkpoint.Checkpoint`` (captured once; collective)."""
        if self._checkpoint is None:
            from .checkpoint import capture

            self._checkpoint = capture(self.problem, self.step.number, self.step.time,
                                       self.position)  # fmt: skip
        return self._checkpoint

    @property
    def pairs(self) -> dict:
        """The model's ``pair_results()`` at this step (computed once)."""
        if self._pairs is None:
            self._pairs = self.problem.model.pair_results()
        return self._pairs

    @property
    def cells(self):
        """``post.CellResults`` at this step (computed once)."""
        if self._cells is None:
            self._cells = self._evaluate()
        return self._cells

    @property
    def residual(self):
        """Unconstrained residual (N, 6) at this step, in the geometry's point order: the
        reactions at supports."""
        if self._residual is None:
            residual = self.problem.solver.unconstrained_residual()
            self._residual = self.problem.model.gather_nodes(residual)
        return self._residual


class Recorder(Protocol):
    def record(self, ctx: StepContext) -> None: ...

    def close(self) -> None: ...


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
    the field series), the set-up's state, Newton's iterations and cuts, wall time (s) and final
    residual norm (N)."""

    def __init__(self, folder: Path, state_type):
        super().__init__(
            Path(folder) / "steps.csv",
            ["step", "stage", "time", *columns(state_type), "iterations", "cuts",
             "failed_iterations", "seconds", "residual_N"],
        )  # fmt: skip

    def record(self, ctx: StepContext) -> None:
        s = ctx.step
        self.writer.writerow(
            [s.number, s.stage, f"{s.time:.12g}", *values(s.state), s.iterations, s.cuts,
             s.failed_iterations, s.seconds, s.residual]
        )  # fmt: skip
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
            [np.full(n, ctx.step.number), np.full(n, load), np.arange(n), cells.wire,
             cells.layer, cells.z, cells.phi, cells.axial]
        )  # fmt: skip
        np.savetxt(self.file, table, delimiter=",", fmt=self.FORMAT)
        self.file.flush()

    def close(self) -> None:
        self.file.close()


class BendingTable(_CsvFile):
    """``moment_curvature.csv``: the set-up's bending measures at every step of the cycle."""

    def __init__(self, folder: Path, record_type):
        super().__init__(Path(folder) / "moment_curvature.csv", ["step", *columns(record_type)])

    def record(self, ctx: StepContext) -> None:
        if not ctx.cycle:
            return
        row = ctx.problem.setup.moment_curvature(ctx.cells, ctx.residual)
        self.writer.writerow([ctx.step.number, *values(row)])
        self.file.flush()


class FieldSeries:
    """``fields.xdmf`` (+ ``fields.h5``) and, with ``vtx``, ``fields.bp``: u, θ, section forces and the
    cell ids at every step, at the step's programme time (ParaView's time axis; ``steps.csv``
    gives the loads at each time)."""

    def __init__(self, folder: Path, problem, vtx: bool = True):
        from .output import FieldWriter, cell_function

        mesh, g = problem.cmesh.mesh, problem.geometry
        ids = [cell_function(mesh, g.cell_wire, "wire"), cell_function(mesh, g.cell_layer, "layer")]
        self.writer = FieldWriter(Path(folder) / "fields.xdmf", problem.beam, ids, vtx=vtx)

    def record(self, ctx: StepContext) -> None:
        self.writer.write(ctx.step.time)

    def close(self) -> None:
        self.writer.close()


class KeyStates:
    """Keeps the cell results and contact pair results of the tensioned state (last step before
    the cycle), and the cell results of the largest abs(cycle load) reached, with the nodal unknowns
    there ((N, 6) in the geometry's point order; for summary and figures)."""

    def __init__(self):
        self.tensioned = None
        self.tensioned_pairs = None
        self.peak = None
        self.peak_w = None
        self._peak_load = 0.0

    def record(self, ctx: StepContext) -> None:
        if not ctx.cycle:
            self.tensioned = ctx.cells
            self.tensioned_pairs = ctx.pairs
        elif abs(ctx.step.load) > abs(self._peak_load):
            self._peak_load = ctx.step.load
            self.peak = ctx.cells
            self.peak_w = ctx.problem.model.node_values()

    def close(self) -> None:
        pass


class SlipTable(_CsvFile):
    """``slip.csv``: per interface i|i+1, the fraction of its contact pairs that slip (at the
    Coulomb cap) among those whose inner node lies within ``zone`` = (z_min, z_max) (m), at
    every step, with the step's value of the cycle parameter."""

    def __init__(self, folder: Path, geometry, zone: tuple[float, float], parameter: str,
                 unit: str):  # fmt: skip
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

    def record(self, ctx: StepContext) -> None:
        slipping = ctx.pairs["slipping"]
        fractions = [slipping[m].mean() if m.any() else 0.0 for m in self.masks]
        load = ctx.problem.setup.get(self.parameter)
        self.writer.writerow([ctx.step.number, load, *fractions])
        self.file.flush()


class SmallSlidingMonitor:
    """Checks at every step that the pairs fixed at t = 0 still face each other
    (``post.sliding_check``); at the first step where they do not, prints a warning to ``stream``
    and keeps it in ``warnings`` (for the summary). Not used with large sliding."""

    def __init__(self, model, stream, warnings: list[str]):
        self.model = model
        self.stream = stream
        self.warnings = warnings
        self.warned = False

    def record(self, ctx: StepContext) -> None:
        if self.warned:
            return
        from .post import sliding_check

        m = self.model
        check = sliding_check(m.geometry, m.positions(), ctx.pairs["gap"])
        if len(check.exceeded()):
            self.warned = True
            text = f"step {ctx.step.number}: {check.message()}"
            self.warnings.append(text)
            print(f"strand: warning: {text}", file=self.stream, flush=True)

    def close(self) -> None:
        pass


class _CycleHistory:
    """A history file whose first step is the tensioned state (the last step before the cycle),
    then every step of the cycle: the reference that slips and energies are counted from."""

    def __init__(self, parameter: str):
        self.parameter = parameter  # the cycle's load parameter, written with every step
        self._tensioned = None  # (RunStep, arrays, load) of the latest tension step
        self.started = False

    def _arrays(self, ctx: StepContext) -> dict:
        raise NotImplementedError

    def record(self, ctx: StepContext) -> None:
        load = ctx.problem.setup.get(self.parameter)
        if not ctx.cycle:
            self._tensioned = (ctx.step, self._arrays(ctx), load)
        else:
            if not self.started:
                self.started = True
                if self._tensioned is not None:
                    self._write(*self._tensioned)
            self._write(ctx.step, self._arrays(ctx), load)

    def _write(self, step: RunStep, arrays: dict, load: float) -> None:
        self.writer.write(step.number, step.time, arrays, load=load)


class PairHistory(_CycleHistory):
    """``contact_pairs.h5`` (``strand.history``) and ``contact_points.xdmf`` (its ParaView series):
    per contact pair, at the tensioned state and every cycle step, the contact point, normal force
    (N), friction force vector (N, on the inner wire a; the outer one b takes its opposite), gap
    (m), state (0 open, 1 stick, 2 slip), and since the start of the cycle: the relative
    displacement of the surface points ``slip``
    and its Coulomb part ``sliding`` (vectors, m) and the energy friction dissipated ``work``
    (J). Static: the pair's wires, interface, kind (1: line), initial z (m) and angle φ about the
    axis (deg, from the x axis), crossing angle (deg), tributary length and radii (m)."""

    def __init__(self, folder: Path, model, parameter: str):
        super().__init__(parameter)
        from .contact.pairs import crossing_angle
        from .geometry import LINE
        from .history import HistoryWriter
        from .strand_contact import wire_neighbours

        g, p = model.geometry, model.geometry.pairs
        self.model, self.a, self.b = model, p.a, p.b
        self.r_a, self.r_b = p.radius_a, p.radius_b
        x0 = 0.5 * (g.points[p.a] + g.points[p.b])
        tangents = np.stack([g.points[nxt] - g.points[prev]
                             for prev, nxt in (wire_neighbours(g, p.a), wire_neighbours(g, p.b))],
                            axis=1)  # fmt: skip
        tangents /= np.linalg.norm(tangents, axis=2)[..., None]
        static = {
            "vertex": np.arange(len(p.a), dtype=np.int32)[:, None],
            "wire_a": g.point_wire[p.a], "wire_b": g.point_wire[p.b],
            "interface": p.interface, "line": (p.kind == LINE).astype(np.int8),
            "z": x0[:, 2], "angle": np.degrees(np.arctan2(x0[:, 1], x0[:, 0])),
            "crossing_angle": np.degrees(crossing_angle(tangents)),
            "tributary": p.tributary, "radius_a": p.radius_a, "radius_b": p.radius_b,
        }  # fmt: skip
        self.folder = Path(folder)
        self.writer = HistoryWriter(self.folder / "contact_pairs.h5", static, kind="contact pairs")
        self._origin = None

    def _arrays(self, ctx: StepContext) -> dict:
        r = ctx.pairs
        x = self.model.positions()
        n = r["normal"]
        point = x[self.a] + (self.r_a + 0.5 * r["gap"])[:, None] * n
        state = np.where(r["force"] > 0, np.where(r["slipping"], 2, 1), 0).astype(np.int8)
        return {
            "position": point, "force": r["force"], "friction": r["friction"], "gap": r["gap"],
            "state": state, "slip": r["slip"], "sliding": r["sliding"], "work": r["work"],
        }  # fmt: skip

    def _write(self, step: RunStep, arrays: dict, load: float) -> None:
        from .history import write_points_xdmf

        if self._origin is None:  # the start of the cycle: slips and work count from here
            self._origin = {k: arrays[k].copy() for k in ("slip", "sliding", "work")}
        arrays = dict(arrays, **{k: arrays[k] - v for k, v in self._origin.items()})
        super()._write(step, arrays, load)
        if self.writer.file is not None:  # the rank that writes (rank 0)
            write_points_xdmf(self.folder / "contact_points.xdmf", self.writer)

    def close(self) -> None:
        self.writer.close()


class WireSectionHistory(_CycleHistory):
    """``wire_sections.h5`` (``strand.history``): per element, at the tensioned state and every
    cycle step, the axial force N (N), the bending moments M₁, M₂ (N m) about e₁ (the strand's
    outward radius; the load direction for the core) and e₂ = t × e₁, and the torque T (N m):
    what surface stresses follow from (``strand.fatigue.stress``), and the displacement of the
    core's nodes ``core_u`` (m). Static: wire, layer, initial z (m), angle φ (deg, as
    ``axial_forces.csv``), wire diameter (m), and the core nodes' initial z ``core_z``."""

    def __init__(self, folder: Path, model, cells_now, direction, parameter: str):
        super().__init__(parameter)
        from .history import HistoryWriter

        g = model.geometry
        diameters = np.array([lay.wire.diameter for lay in g.cable.layers])
        self.direction = np.asarray(direction, float)
        self.model, self.core = model, model.core_points()
        static = {"wire": g.cell_wire, "layer": g.cell_layer, "z": cells_now.z,
                  "phi": cells_now.phi, "diameter": diameters[g.cell_layer],
                  "core_z": g.points[self.core, 2]}  # fmt: skip
        self.writer = HistoryWriter(Path(folder) / "wire_sections.h5", static, kind="wire sections")

    def _arrays(self, ctx: StepContext) -> dict:
        from .fatigue.stress import section_components, section_frames

        c = ctx.cells
        e1, e2 = section_frames(c.tangent, c.radial, fallback=self.direction)
        m = section_components(c.moment, c.tangent, e1, e2)
        u = self.model.positions()[self.core] - self.model.geometry.points[self.core]
        return {"axial": c.axial, "m1": m[:, 0], "m2": m[:, 1], "torque": m[:, 2], "core_u": u}

    def close(self) -> None:
        self.writer.close()


class CheckpointRecorder:
    """``checkpoint.h5``: the last converged state with everything the next step starts from
    (``strand.checkpoint``), replaced after every step, so that ``strand run --restart`` can
    continue a stopped run; ``tensioned.h5``: the same at the last step before the cycle, the
    state other load cycles can start from."""

    def __init__(self, folder: Path):
        self.folder = Path(folder)

    def record(self, ctx: StepContext) -> None:
        from .checkpoint import write_checkpoint

        if ctx.position is None:
            return
        write_checkpoint(self.folder / "checkpoint.h5", ctx.checkpoint)
        if not ctx.cycle:
            write_checkpoint(self.folder / "tensioned.h5", ctx.checkpoint)

    def close(self) -> None:
        pass
