"""What a run produced, as typed records: its steps, bending measures and slip shares, the states
kept for the summary and figures, the set-up kind's reference, the outcome and the effort
(``RunResult``); and where a run starts when not from the unloaded strand (``Start``). The summary
and figures are made from these, never from the files the run wrote. Units: SI; times in s."""

from __future__ import annotations

from dataclasses import KW_ONLY, dataclass, field
from pathlib import Path
from typing import Any

from ..model.cell_results import CellResults
from ..model.pair_results import PairResults
from ..model.programme import Position
from .step_records import RunStep, SlipFractions, StepBending

__all__ = ["RunResult", "Start"]


@dataclass
class RunResult:
    """What a run produced: its step records, cell results at key states, the folder, the outcome."""

    folder: Path
    steps: list[RunStep] = field(default_factory=list)
    #: the set-up's bending measures at every cycle step (``moment_curvature.csv``)
    bending: list[StepBending] = field(default_factory=list)
    #: the slipping share of each interface's pairs in the measuring zone (``slip.csv``)
    slip: list[SlipFractions] = field(default_factory=list)
    #: the strand's reactions at both ends (``reactions.EndReactions``) by step number
    reactions: dict[int, Any] = field(default_factory=dict)
    tensioned: CellResults | None = None  # after tension, before the cycle
    tensioned_pairs: PairResults | None = None  # the contact pairs there
    #: at the tension's last step (``tensioned`` unless a load was then applied and held)
    tension_end: CellResults | None = None
    tension_end_pairs: PairResults | None = None  # the contact pairs there
    first_cycle: CellResults | None = None  # at the first step of the cycle
    #: the fatigue report of the run (``fatigue.findings.FatigueReport``; None without one)
    fatigue: Any = None
    #: what the set-up kind's analytical reference predicts for the run (``SetupKind.reference``)
    reference: Any = None
    peak: CellResults | None = None  # at the largest abs(cycle load) reached
    peak_w: Any = None  # nodal unknowns at that state
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
    kept: Any = None
    _: KW_ONLY
    #: where each layer's pressure goes (``layer_pressure.LayerPressure`` per helical layer)
    #: at the tensioned state and at the largest abs(cycle load)
    tensioned_layers: list | None = None
    peak_layers: list | None = None

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


@dataclass(frozen=True)
class Start:
    """Where a run starts when not from the unloaded strand: the programme ``position`` and the
    record of the step whose state the problem holds (written again as the run's first row)."""

    position: Position
    step: RunStep
