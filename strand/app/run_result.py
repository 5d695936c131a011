"""What a run produced, as typed records: its steps, bending measures and slip shares, the states
kept for the summary and figures, the set-up kind's reference, the outcome and the effort
(``RunResult``); and where a run starts when not from the unloaded strand (``Start``). The summary
and figures are made from these, never from the files the run wrote. Units: SI; times in s."""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np
import numpy.typing as npt

from ..model.cell_results import CellResults
from ..model.pair_results import PairResults
from ..model.programme import Position
from .step_records import RunStep, SlipFractions, StepBending

if TYPE_CHECKING:
    from ..model.checkpoint import Checkpoint
    from ..model.layer_pressure import LayerPressure
    from ..model.reactions import EndReactions
    from .fatigue.findings import FatigueReport

__all__ = ["RunResult", "Start"]


@dataclass(frozen=True, kw_only=True)
class RunResult:
    """What a run produced: its step records, cell results at key states, the folder, the outcome.
    Made once, when the run has ended (``runner.run_programme_with_outputs``); the fatigue
    report, made after the summary, comes with a copy (``dataclasses.replace``)."""

    folder: Path
    steps: tuple[RunStep, ...] = ()
    #: the set-up's bending measures at every cycle step (``moment_curvature.csv``)
    bending: tuple[StepBending, ...] = ()
    #: the slipping share of each interface's pairs in the measuring zone (``slip.csv``)
    slip: tuple[SlipFractions, ...] = ()
    #: the strand's reactions at both ends by step number
    reactions: dict[int, EndReactions] = field(default_factory=dict)
    tensioned: CellResults | None = None  # after tension, before the cycle
    tensioned_pairs: PairResults | None = None  # the contact pairs there
    #: at the tension's last step (``tensioned`` unless a load was then applied and held)
    tension_end: CellResults | None = None
    tension_end_pairs: PairResults | None = None  # the contact pairs there
    first_cycle: CellResults | None = None  # at the first step of the cycle
    #: the fatigue report of the run (None without one, and on ranks other than 0)
    fatigue: FatigueReport | None = None
    #: what the set-up kind's analytical reference predicts for the run (``SetupKind.reference``:
    #: a record of the kind's own, which only that kind reads; None without one)
    reference: object = None
    peak: CellResults | None = None  # at the largest abs(cycle load) reached
    #: nodal unknowns there, (N, 6) in the geometry's point order
    peak_w: npt.NDArray[np.float64] | None = None
    failure: str = ""  # why the run stopped early ("" if it did not)
    interrupted: bool = False  # stopped by the user (Ctrl-C)
    #: the Newton iterations and LUs of the attempts after the last converged step of a run that
    #: failed or was interrupted there ((0, 0) if none): no step record holds them
    failed_step_effort: tuple[int, int] = (0, 0)
    warnings: tuple[str, ...] = ()  # e.g. beyond small sliding
    seconds: float = 0.0
    setup_seconds: float = 0.0
    #: solver wall times (s) and counts: residual/jacobian callbacks, pair terms, insertion,
    #: whole solves; and "output", all recorders together
    timings: dict[str, float] = field(default_factory=dict)
    #: wall time (s) of each recorder over the run, by class name (the first to ask for the
    #: step's cell results, the axial force table, is charged with evaluating them)
    output_timings: dict[str, float] = field(default_factory=dict)
    cycle_parameter: str = ""
    #: the state kept in memory at the steps ``run_programme_with_outputs(keep=)`` chose
    kept: Checkpoint | None = None
    #: where each layer's pressure goes (``LayerPressure`` per helical layer) at the tensioned
    #: state and at the largest abs(cycle load)
    tensioned_layers: tuple[LayerPressure, ...] | None = None
    peak_layers: tuple[LayerPressure, ...] | None = None

    @property
    def iterations(self) -> int:
        """Newton iterations of the converged attempts."""
        return sum(s.iterations for s in self.steps)

    @property
    def failed_iterations(self) -> int:
        """Newton iterations of the attempts that failed, those after the last step included."""
        return sum(s.failed_iterations for s in self.steps) + self.failed_step_effort[0]

    @property
    def factorisations(self) -> int:
        """LU factorisations, those of the attempts after the last step included."""
        return sum(s.factorisations for s in self.steps) + self.failed_step_effort[1]

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


@dataclass(frozen=True)
class Start:
    """Where a run starts when not from the unloaded strand: the programme ``position`` and the
    record of the step whose state the problem holds (written again as the run's first row)."""

    position: Position
    step: RunStep
