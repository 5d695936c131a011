"""Adaptive load stepping on a ``NonlinearProblem``: steps that grow after easy solves and are
halved and retried after failures, with the records of the converged steps."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
import numpy.typing as npt

if TYPE_CHECKING:
    from .problem import NonlinearProblem

__all__ = ["LoadStepper", "StepRecord", "RampState", "LoadStepFailure", "RunInterrupted"]


@dataclass
class RampState:
    """Where a ramp stands after a converged step: the increment it tries next, and the load
    and unknowns increments (local array) of that step (the secant predictor's), if any."""

    step: float
    previous: tuple[float, npt.NDArray[np.float64]] | None


@dataclass
class StepRecord:
    """One converged load step."""

    stage: str
    load: float
    iterations: int
    residuals: list[float]
    seconds: float
    cuts: int
    #: Newton iterations spent in the attempts that failed before it (the cuts' cost)
    failed_iterations: int = 0


class LoadStepFailure(RuntimeError):
    """A load step did not converge even after the allowed step cuts."""


class RunInterrupted(LoadStepFailure):
    """The user asked the run to stop (Ctrl-C); the last converged state is kept."""


class LoadStepper:
    """Adaptive load stepping: grow the step after easy solves, halve and retry after failures.

    Args:
        solver: the ``NonlinearProblem``.
        first_step: initial load increment (in the units of the load parameter).
        min_step: smallest increment tried before giving up.
        max_step: largest increment (default: unbounded).
        growth: factor applied to the increment after a solve of at most ``easy_iterations``.
        on_step: called with each ``StepRecord`` after the step is committed (write outputs there).
        extrapolate: start each Newton solve of a ramp from the linear extrapolation of the
            last two converged states (not across ramps, whose direction may reverse). Off by
            default: the predictor's initial residual scales the relative tolerance ``rtol``, so
            use it with an absolute tolerance that governs.
    """

    def __init__(
        self,
        solver: NonlinearProblem,
        first_step: float,
        min_step: float,
        max_step: float | None = None,
        growth: float = 1.5,
        easy_iterations: int = 6,
        on_step: Callable[[StepRecord], None] | None = None,
        extrapolate: bool = False,
    ):
        if not (0 < min_step <= first_step):
            raise ValueError("LoadStepper: need 0 < min_step <= first_step")
        self.solver = solver
        self.step = first_step
        self.min_step = min_step
        self.max_step = max_step if max_step is not None else np.inf
        self.growth = growth
        self.easy_iterations = easy_iterations
        self.on_step = on_step
        self.extrapolate = extrapolate
        self.history: list[StepRecord] = []
        #: the ramp's state after its last converged step (``ramp(resume=...)`` continues it)
        self.state: RampState | None = None

    def ramp(
        self,
        set_load: Callable[[float], None],
        start: float,
        end: float,
        stage: str = "load",
        resume: RampState | None = None,
    ):
        """Move the load parameter from ``start`` to ``end``; returns the records of this ramp.
        ``resume``: continue a ramp from one of its converged steps (``RampState``, as
        ``self.state`` held it there), so that the steps taken are those of the whole ramp."""
        records = []
        sign = 1.0 if end >= start else -1.0
        current = start
        step = min(self.step, self.max_step)
        cuts, failed = 0, 0  # step cuts and their Newton iterations since the last success
        w = self.solver.w.x.array
        previous = None  # (load increment, unknowns increment) of the last step of this ramp
        if resume is not None:
            step, previous = resume.step, resume.previous
        while sign * (end - current) > 1e-12 * max(1.0, abs(end)):
            if self.solver.stop_requested():
                raise RunInterrupted(
                    f"{stage}: interrupted by the user at {current:.6g} (target {end:.6g}). "
                    "The state at the last converged load is kept and was written."
                )
            trial = current + sign * min(step, abs(end - current))
            set_load(trial)
            start_w = w.copy()
            if self.extrapolate and previous is not None:  # secant predictor along the ramp
                w += (trial - current) / previous[0] * previous[1]
            result = self.solver.solve()
            if result.converged:
                previous = (trial - current, w - start_w)
                self.solver.commit()
                rec = StepRecord(
                    stage, trial, result.iterations, result.residuals, result.seconds, cuts,
                    failed,
                )  # fmt: skip
                current = trial
                if result.iterations <= self.easy_iterations:
                    step = min(step * self.growth, self.max_step)
                cuts, failed = 0, 0
                self.state = RampState(step, previous)
                records.append(rec)
                self.history.append(rec)
                if self.on_step is not None:
                    self.on_step(rec)
            else:
                self.solver.rollback()
                set_load(current)
                if self.solver.stop_requested():
                    continue  # not a failure: stop at the top of the loop
                step /= 2
                cuts += 1
                failed += result.iterations
                if step < self.min_step:
                    raise LoadStepFailure(
                        f"{stage}: no convergence from {current:.6g} towards {trial:.6g} "
                        f"after {cuts} step cuts (increment now {step:.3g} < min_step "
                        f"{self.min_step:.3g}; last Newton: {result.reason}, "
                        f"{result.iterations} iterations, residual {result.residual:.3e}). "
                        "The state at the last converged load is kept and was written."
                    )
        self.step = step
        return records
