"""What a run records at each converged step: the step's record (``RunStep``), the rows the
tables keep (``StepBending``, ``SlipFractions``), and what every recorder sees (``StepContext``:
the record, the problem, and the results computed from its state once, on demand) through the
``Recorder`` protocol. The recorders themselves: ``strand.app.recorders``. Units: SI.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import KW_ONLY, dataclass, field
from typing import TYPE_CHECKING, Any, Protocol

import numpy as np
import numpy.typing as npt

if TYPE_CHECKING:
    from ..model.cell_results import CellResults
    from ..model.checkpoint import Checkpoint
    from ..model.pair_results import PairResults
    from ..model.problem import StrandProblem
    from ..model.programme import Position
    from ..setups import TestSetup

__all__ = ["HOLDS", "RunStep", "StepBending", "SlipFractions", "StepContext", "Recorder"]

#: what carried a step, by ``RunStep.hold``
HOLDS = (
    "not held",
    "held by the springs",
    "held by the springs and the wider onset",
    "relaxed to rest",
)


@dataclass(frozen=True)
class RunStep:
    """One converged step of a run: its number (from 1), stage, the parameter it ramps and that
    parameter's value, the programme time (``LoadProgramme.time``), Newton's effort (iterations,
    step cuts before it, wall time s, final residual norm N), the set-up's measures (``state``)
    the iterations of the failed attempts before it, its LUs, and its stabilisation."""

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
    factorisations: int = 0
    _: KW_ONLY
    #: the contact stabilisation's energy over the strain energy (0: not stabilised;
    #: ``strand.solver.Stabiliser``)
    stabilisation: float = 0.0
    #: the hold that carried the step: 0 none, 1 the springs, 2 the springs with the wider
    #: same-layer onset, 3 the relaxation (``strand.solver.StepRecord.hold``)
    hold: int = 0


@dataclass(frozen=True)
class StepBending:
    """The set-up's bending measures at one step of the cycle (a row of
    ``moment_curvature.csv``): the step's number and the ``TestSetup.moment_curvature`` record."""

    step: int
    measures: Any


@dataclass(frozen=True)
class SlipFractions:
    """A row of ``slip.csv``: the step's number, the cycle parameter's value there (its unit),
    and per interface i|i+1 the fraction of its pairs in the measuring zone that slip."""

    step: int
    load: float
    slipping: npt.NDArray[np.float64]


@dataclass
class StepContext:
    """What recorders see at a step: the record, the problem, and the cell results (lazy).

    Attributes:
        step: the step's record.
        problem: the problem at the step's converged state.
        cycle: a step of the cycle (not of the tensioning).
        position: where the run stands in its programme, for checkpoints (None: not kept).
    """

    step: RunStep
    problem: StrandProblem[TestSetup]
    cycle: bool
    _cells: CellResults | None = field(default=None, repr=False)
    _evaluate: Callable[[], CellResults] | None = field(default=None, repr=False)

    _residual: npt.NDArray[np.float64] | None = field(default=None, repr=False)
    _pairs: PairResults | None = field(default=None, repr=False)
    position: Position | None = None
    _checkpoint: Checkpoint | None = field(default=None, repr=False)

    @property
    def checkpoint(self) -> Checkpoint:
        """The state at this step as a ``checkpoint.Checkpoint`` (captured once; collective)."""
        if self._checkpoint is None:
            from ..model.checkpoint import capture

            self._checkpoint = capture(
                self.problem, self.step.number, self.step.time, self.position, self.residual
            )
        return self._checkpoint

    @property
    def pairs(self) -> PairResults:
        """The model's ``pair_results()`` at this step (computed once)."""
        if self._pairs is None:
            self._pairs = self.problem.model.pair_results()
        return self._pairs

    @property
    def cells(self) -> CellResults:
        """``cell_results.CellResults`` at this step (computed once)."""
        if self._cells is None:
            self._cells = self._evaluate()
        return self._cells

    @property
    def residual(self) -> npt.NDArray[np.float64]:
        """Unconstrained residual (N, 6) at this step, in the geometry's point order: the
        reactions at supports."""
        if self._residual is None:
            residual = self.problem.solver.unconstrained_residual()
            self._residual = self.problem.model.gather_nodes(residual)
        return self._residual


class Recorder(Protocol):
    """A run's output, written as the run goes: ``record`` after every converged step,
    ``close`` at the end (or where the run stops)."""

    def record(self, ctx: StepContext) -> None: ...

    def close(self) -> None: ...
