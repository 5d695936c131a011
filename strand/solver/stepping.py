"""Adaptive load stepping on a ``NonlinearProblem``: steps that grow after easy solves and are
halved and retried after failures, with the records of the converged steps.

``ErrorControl`` (optional) sizes the steps from an estimate of each step's load-step error
instead: the miss of the secant predictor w_pred = w_n + (Δλ/Δλ_prev) Δw_prev, e = max over the
nodes of |w_{n+1} − w_pred| on the translations (m). It is the local error of first-order path
following, e = ½ w'' Δλ (Δλ + Δλ_prev) + O(Δλ³) on a smooth path, hence the next increment
Δλ (safety √(tol/e)), clamped.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import KW_ONLY, dataclass
from typing import TYPE_CHECKING

import numpy as np
import numpy.typing as npt
from mpi4py import MPI

if TYPE_CHECKING:
    from .problem import NonlinearProblem
    from .stabilisation import Stabiliser

__all__ = [
    "LoadStepper",
    "ErrorControl",
    "StepRecord",
    "RampState",
    "LoadStepFailure",
    "RunInterrupted",
    "predictor_miss",
]

Array = npt.NDArray[np.float64]


@dataclass
class RampState:
    """Where a ramp stands after a converged step: the increment it tries next, and the load
    and unknowns increments (local array) of that step (the secant predictor's), if any."""

    step: float
    previous: tuple[float, Array] | None


@dataclass
class StepRecord:
    """One converged load step."""

    stage: str
    load: float
    iterations: int
    residuals: list[float]
    seconds: float
    cuts: int
    #: Newton iterations spent in the attempts that failed (or were rejected) before it
    failed_iterations: int = 0
    #: the step's load-step error estimate, the secant predictor's miss (m; ``predictor_miss``);
    #: nan for the first step of a ramp, which has no predictor
    error: float = float("nan")
    #: attempts retried at the same increment with the predictor switched (``retry``)
    retries: int = 0
    #: converged attempts rejected for a miss over ``ErrorControl.reject_factor`` × tol
    rejections: int = 0
    #: LU factorisations of the step, failed attempts included (``NewtonResult.factorisations``)
    factorisations: int = 0
    _: KW_ONLY
    #: the contact stabilisation's energy over the strain energy at the converged step
    #: (``Stabiliser.fraction``); 0: the step converged without it
    stabilisation: float = 0.0
    #: the hold that carried the step (``Stabiliser.level``): 0 none, 1 the springs, 2 the
    #: springs with the wider onset, 3 the relaxation (an equilibrium: fraction 0)
    hold: int = 0


@dataclass(frozen=True)
class ErrorControl:
    """Load increments from the load-step error estimate (``predictor_miss``, m).

    After a converged step of increment Δλ with miss e, the next increment is
    Δλ clamp(safety √(tol/e), shrink_min, grow_max) (e ∝ Δλ² on a smooth path), at most
    ``grow_after_cut`` times Δλ after a step that needed cuts (a larger one just failed).
    A step whose miss exceeds ``reject_factor`` × tol is rejected and retried at the
    increment this gives (inf: never), unless it is already at ``min_step``.

    ``tol`` = 1 µm: 1e-3 of a millimetre of midspan deflection, and a fifth of the elastic slip
    over which a frictional pair builds its traction (the penalty law's default g_lim, 5 µm),
    so that a step does not carry pairs through their stick–slip transition with an error of
    the transition's size.
    """

    tol: float = 1e-6
    safety: float = 0.9
    shrink_min: float = 0.2
    grow_max: float = 2.0
    grow_after_cut: float = 1.0
    reject_factor: float = np.inf

    def __post_init__(self):
        if not (self.tol > 0 and 0 < self.shrink_min <= 1 <= self.grow_max):
            raise ValueError("ErrorControl: need tol > 0 and 0 < shrink_min <= 1 <= grow_max")
        if self.reject_factor < 1:
            raise ValueError("ErrorControl: reject_factor must be at least 1")

    def factor(self, error: float) -> float:
        """The next increment over this one for a step of miss ``error`` (m)."""
        if error <= 0:
            return self.grow_max
        ideal = self.safety * np.sqrt(self.tol / error)
        return float(np.clip(ideal, self.shrink_min, self.grow_max))

    def rejects(self, error: float) -> bool:
        """Whether a step of miss ``error`` (m) is rejected."""
        return bool(error > self.reject_factor * self.tol)


def predictor_miss(increment: float, dw: Array, previous: tuple[float, Array]) -> float:
    """The secant predictor's miss on this rank: max over the nodes of |Δw − (Δλ/Δλ_p) Δw_p|
    on the translations (m), for a step of load increment Δλ = ``increment`` and unknowns
    increment ``dw`` (local, (u, θ) per node) after one of ``previous`` = (Δλ_p, Δw_p).

    The max-norm, not an RMS: the quantities read (deflections, pair slips) are local, and an
    RMS would dilute the few pairs that change state as the mesh grows. Rotations (rad) are
    left out, so that ``ErrorControl.tol`` is a length."""
    load_step, dw_prev = previous
    miss = (dw - (increment / load_step) * dw_prev).reshape(-1, 6)[:, :3]
    return float(np.abs(miss).max(initial=0.0))


def _all_ranks_max(solver, value: float) -> float:
    """``value``'s max over the ranks that share ``solver.w`` (a dolfinx ``Function``; for
    unknowns without a function space: ``value``)."""
    space = getattr(solver.w, "function_space", None)
    comm = space.mesh.comm if space is not None else None
    return comm.allreduce(value, op=MPI.MAX) if comm is not None and comm.size > 1 else value


class LoadStepFailure(RuntimeError):
    """A load step did not converge even after the allowed step cuts. The problem is rolled
    back to the last converged step; the library writes nothing (``on_step`` wrote what it
    wrote), so the message says nothing of files: an application adds what it has written.
    ``iterations`` and ``factorisations``: the Newton iterations and LUs of the attempts made
    since the last converged step (no step record holds them)."""

    def __init__(self, message: str, *, iterations: int = 0, factorisations: int = 0):
        super().__init__(message)
        self.iterations = iterations
        self.factorisations = factorisations


class RunInterrupted(LoadStepFailure):
    """The user asked the run to stop (Ctrl-C); the problem holds the last converged state."""


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
        controller: an ``ErrorControl``: after the first step of a ramp, it sizes the
            increments (``growth`` and ``easy_iterations`` then apply to the first step only).
            None (the default): the rule above.
        retry: after a failed attempt, try the same increment once more from the last
            converged state with the predictor switched (off if ``extrapolate``, else on)
            before halving: every increment is tried from both starting guesses, where a
            predictor exists; not while the ``stabiliser`` holds the step (its attempts start
            where the unheld ones did).
        settles: the ramp's first step is no guide to the next (e.g. a strand's first
            tension step, in which its contact pairs close): no predictor, and no error
            estimate, is taken from it.
        stabiliser: a ``Stabiliser``: the contact springs, a last resort for a step whose
            cuts are exhausted (the next would go under ``min_step``): the step is tried again
            from the increment it was first tried at, with the springs on, and cut again if
            need be; those cuts exhausted too, once more with the wider onset as well
            (``Stabiliser.escalate``). They are switched off when it is committed, and their
            energy fraction recorded (``StepRecord.stabilisation``). A run that converges
            without them is unchanged, step for step. None (the default): none.
    """

    def __init__(
        self,
        solver: NonlinearProblem,
        first_step: float,
        min_step: float,
        max_step: float | None = None,
        *,
        growth: float = 1.5,
        easy_iterations: int = 6,
        on_step: Callable[[StepRecord], None] | None = None,
        extrapolate: bool = False,
        controller: ErrorControl | None = None,
        retry: bool = False,
        settles: bool = False,
        stabiliser: Stabiliser | None = None,
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
        self.controller = controller
        self.retry = retry
        self.settles = settles
        self.stabiliser = stabiliser
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
        records: list[StepRecord] = []
        sign = 1.0 if end >= start else -1.0
        current = start
        step = min(self.step, self.max_step)
        # since the last success: step cuts, their Newton iterations, retries, rejections, LUs
        cuts, failed, retries, rejections, lus = 0, 0, 0, 0, 0
        predict = self.extrapolate  # start the next attempt from the secant predictor
        retried = False  # whether this increment was tried from the other starting guess
        w = self.solver.w.x.array
        first_try = step  # the increment the step being taken was first tried at
        previous = None  # (load increment, unknowns increment) of the last step of this ramp
        if resume is not None:
            step, previous = resume.step, resume.previous
        while sign * (end - current) > 1e-12 * max(1.0, abs(end)):
            if self.solver.stop_requested():
                raise RunInterrupted(
                    f"{stage}: interrupted by the user at {current:.6g} (target {end:.6g}). "
                    "The problem holds the state of that last converged load.",
                    iterations=failed,
                    factorisations=lus,
                )
            trial = current + sign * min(step, abs(end - current))
            set_load(trial)
            start_w = w.copy()
            if predict and previous is not None:  # secant predictor along the ramp
                w += (trial - current) / previous[0] * previous[1]
            holding = self.stabiliser.level if self.stabiliser is not None else 0
            if cuts == 0 and retries == 0 and not holding:
                first_try = step  # the increment this step was first tried at
            if holding == 3:
                assert self.stabiliser is not None  # holding
                result = self.stabiliser.relaxed_solve()
            else:
                result = self.solver.solve()
            lus += result.factorisations
            if result.converged:
                h, dw = trial - current, w - start_w
                error, proposal = self._estimate(h, dw, previous, cuts)
                if proposal is not None and self._rejects(error, abs(h), proposal):
                    self.solver.rollback()
                    set_load(current)
                    step = proposal
                    failed += result.iterations
                    rejections += 1
                    predict = self.extrapolate
                    retried = False
                    continue
                settling = self.settles and resume is None and not records
                previous = None if settling else (h, dw)
                stabilisation = self._release()
                self.solver.commit()
                rec = StepRecord(
                    stage,
                    trial,
                    result.iterations,
                    result.residuals,
                    result.seconds,
                    cuts,
                    failed,
                    error,
                    retries,
                    rejections,
                    lus,
                    stabilisation=stabilisation,
                    hold=holding,
                )
                current = trial
                if proposal is not None:
                    step = proposal
                elif result.iterations <= self.easy_iterations:
                    step = min(step * self.growth, self.max_step)
                cuts, failed, retries, rejections, lus = 0, 0, 0, 0, 0
                predict = self.extrapolate
                retried = False
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
                failed += result.iterations
                if self.retry and not retried and not holding and previous is not None:
                    retries += 1
                    retried = True
                    predict = not self.extrapolate  # the same increment, predictor switched
                    continue
                retried = False
                predict = self.extrapolate
                if (
                    self.stabiliser is not None
                    and step / 2 < self.min_step
                    and self.stabiliser.escalate(relax=self.solver is self.stabiliser.newton)
                ):  # cuts exhausted: the step again, held (then held harder)
                    step = first_try
                    continue
                step /= 2
                cuts += 1
                if step < self.min_step:
                    self._release()
                    raise LoadStepFailure(
                        f"{stage}: no convergence from {current:.6g} towards {trial:.6g} "
                        f"after {cuts} step cuts (increment now {step:.3g} < min_step "
                        f"{self.min_step:.3g}; last Newton: {result.reason}, "
                        f"{result.iterations} iterations, residual {result.residual:.3e}). "
                        f"The problem holds the state of the last converged load, {current:.6g}.",
                        iterations=failed,
                        factorisations=lus,
                    )
        self.step = step
        return records

    def _release(self) -> float:
        """Switch the stabiliser off; its energy fraction at the last evaluation (0: was off)."""
        if self.stabiliser is None or not self.stabiliser.level:
            return 0.0
        fraction = self.stabiliser.fraction()
        self.stabiliser.switch(False)
        return fraction

    def _estimate(
        self, h: float, dw: Array, previous: tuple[float, Array] | None, cuts: int
    ) -> tuple[float, float | None]:
        """A converged step's error estimate (m; nan for a ramp's first step) and, with a
        controller, the next increment it gives (None without), within [min_step, max_step];
        ``h``, ``dw``: the step's load and unknowns increments, ``cuts``: the cuts it took."""
        if previous is None:
            return float("nan"), None
        error = _all_ranks_max(self.solver, predictor_miss(h, dw, previous))
        c = self.controller
        if c is None:
            return error, None
        factor = c.factor(error)
        if cuts > 0:
            factor = min(factor, c.grow_after_cut)
        return error, float(np.clip(abs(h) * factor, self.min_step, self.max_step))

    def _rejects(self, error: float, increment: float, proposal: float) -> bool:
        """Whether the controller rejects a converged step of ``increment``: not if its
        retry, at ``proposal``, would be no smaller (at ``min_step``)."""
        assert self.controller is not None  # called only with an error controller
        return self.controller.rejects(error) and proposal < increment
