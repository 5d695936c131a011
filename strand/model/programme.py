"""Load programmes: the sequence of stages a run takes its test set-up through.

A ``Stage`` ramps one load parameter of the set-up (``"tension"``, ``"lateral"``, ``"curvature"``)
from wherever it is to a target, in adaptive steps; a ``LoadProgramme`` is the ordered list of
stages. ``run_programme`` drives a ``StrandProblem`` through it and calls back after every
converged step, so that recorders write as the run goes. Units: those of each parameter (SI).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from ..solver import ErrorControl, LoadStepper, RampState, Stabiliser, StepRecord

__all__ = ["Stage", "LoadProgramme", "Position", "run_programme", "cycle_stages"]


@dataclass(frozen=True)
class Stage:
    """One ramp: ``parameter`` to ``target`` in steps starting at ``first_step``, growing by
    ``growth`` after easy solves up to ``max_step``, halved down to ``min_step`` on failure.
    ``extrapolate`` starts each solve from the secant predictor of the last two steps;
    ``settles``: not from the first step's (``LoadStepper``)."""

    name: str
    parameter: str
    target: float
    first_step: float
    min_step: float
    max_step: float = math.inf
    growth: float = 1.5
    extrapolate: bool = False
    settles: bool = False


@dataclass(frozen=True)
class LoadProgramme:
    """Stages in order; ``cycle_parameter`` names the parameter the cycle stages vary."""

    stages: tuple[Stage, ...]
    cycle_parameter: str

    def starts(self) -> list[float]:
        """Where every stage starts: the target of the last stage of its parameter (0 at first)."""
        reached: dict[str, float] = {}
        starts = []
        for s in self.stages:
            starts.append(reached.get(s.parameter, 0.0))
            reached[s.parameter] = s.target
        return starts

    def path_lengths(self) -> list[float]:
        """The distance abs(target − start) of every stage, every parameter starting at 0."""
        return [abs(s.target - a) for s, a in zip(self.stages, self.starts(), strict=True)]

    def time(self, index: int, value: float) -> float:
        """Programme time at ``value`` of the parameter of stage ``index`` (from 0): the stage's
        index plus the fraction of its ramp done, so that stage k runs from k to k + 1 (e.g.
        t = 1 is the end of the tension, 1.5 half-way up the first leg). It grows along the
        run, whereas a cycle's load goes up and down: the time axis of the field series."""
        start = self.starts()[index]
        span = self.stages[index].target - start
        return index + (1.0 if span == 0 else float(np.clip((value - start) / span, 0.0, 1.0)))

    def weights(self) -> list[float]:
        """Share of the whole programme (for progress): stages of other parameters (tensioning)
        count for 10 % together when there is a cycle, the cycle stages by their path length;
        a cycle that goes nowhere (targets all 0: tension only) counts for nothing."""
        lengths = self.path_lengths()
        cycle = [s.parameter == self.cycle_parameter for s in self.stages]
        cycle_path = sum(l for l, c in zip(lengths, cycle, strict=True) if c)
        n_other = sum(1 for c in cycle if not c)
        other_share = 0.1 if cycle_path > 0 else 1.0
        return [
            ((1 - other_share) * l / cycle_path if cycle_path > 0 else 0.0)
            if c
            else other_share / max(n_other, 1)
            for l, c in zip(lengths, cycle, strict=True)
        ]


def cycle_stages(
    parameter: str,
    amplitude: float,
    cycle,
    first_step: float,
    max_step: float,
    *,
    cuts: int,
    growth: float,
    predictor: bool = True,
) -> list[Stage]:
    """Legs ``leg 1, leg 2, …`` to the targets ``cycle`` × ``amplitude``; every leg starts with
    ``first_step`` (the direction may reverse) and uses the secant predictor (``predictor``)."""
    return [
        Stage(
            f"leg {i + 1}",
            parameter,
            c * amplitude,
            first_step,
            first_step / 2**cuts,
            max_step,
            growth,
            extrapolate=predictor,
        )
        for i, c in enumerate(cycle)
    ]


@dataclass(frozen=True)
class Position:
    """Where a run stands in its programme after a converged step: the stage under way (index)
    and its ramp's state (``RampState``), from which ``run_programme`` can continue."""

    stage: int
    ramp: RampState | None = None


def run_programme(
    problem,
    programme: LoadProgramme,
    on_step: Callable[[Stage, StepRecord, Position], None] | None = None,
    start: Position | None = None,
    *,
    controller: ErrorControl | None = None,
    retry: bool = False,
    stabilisation: float | None = None,
    held_onset: float | None = None,
    relaxation: float | None = None,
    report: Callable[[str], None] | None = None,
) -> None:
    """Take ``problem`` (its ``setup`` and ``solver``) through every stage; ``on_step(stage,
    record, position)`` after every committed step. ``start``: continue from a position (the
    problem already in the state reached there: ``strand.model.checkpoint``). ``controller`` and
    ``retry``: ``LoadStepper``'s, for every stage (default: growth after easy solves, no
    retry). ``stabilisation``: the contact springs (N/m) of a step whose cuts are exhausted,
    ``held_onset`` the width (m) of the same-layer pairs' onset while held, ``relaxation``
    the first stiffness (N/m per node) of the pseudo-transient continuation after them, told
    to ``report`` a line per pseudo-time step (``Stabiliser``).
    Raises
    ``LoadStepFailure`` when a step cannot be cut small enough to converge (the last converged
    state stays in the problem)."""
    setup = problem.setup
    first = start.stage if start is not None else 0
    stabiliser = None
    if stabilisation:
        model = problem.model
        stabiliser = Stabiliser(
            [*model.contact, *model.same_layer],
            model.strain_energy,
            model.comm,
            stabilisation,
            onset=held_onset,
            newton=problem.solver,
            relaxation=relaxation,
            report=report,
            length=model.geometry.cable.largest_wire_diameter,
        )
    for index, stage in enumerate(programme.stages):
        if index < first:
            continue
        solver = setup.driver(problem.solver, stage.parameter)  # a stand-in for a controlled load
        stepper = LoadStepper(
            solver,
            stage.first_step,
            stage.min_step,
            max_step=stage.max_step,
            growth=stage.growth,
            extrapolate=stage.extrapolate,
            controller=controller,
            retry=retry,
            settles=stage.settles,
            stabiliser=stabiliser,
        )
        if on_step is not None:
            stepper.on_step = lambda rec, stage=stage, index=index, stepper=stepper: on_step(
                stage, rec, Position(index, stepper.state)
            )

        def set_load(value, name=stage.parameter):
            setup.set(name, value)

        resume = start.ramp if start is not None and index == first else None
        stepper.ramp(set_load, setup.get(stage.parameter), stage.target, stage.name, resume)
