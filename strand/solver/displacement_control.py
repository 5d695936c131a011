"""Displacement control of a load that a set-up applies: at every load step, the load that brings
a measured displacement to its prescribed value, found by the secant method on whole solves of
the force-controlled problem.

A ``LoadStepper`` ramps the prescribed displacement (the stage's parameter) and asks its solver
for one solve per trial step. ``DisplacementControl`` stands in for that solver: its ``solve``
guesses the load from the states committed along the ramp (the stiffest slope so far at a
reversal, which starts sticking), solves, measures, and corrects the load by the secant through
the step's two converged states nearest the target (bisection when it leaves their bracket),
until the measured displacement is within ``tolerance`` of the prescribed one; a trial whose
Newton fails is tried again halfway to the nearest converged load. Every trial of a step starts
from the committed history (``commit`` takes only the last), so that the step is the
force-controlled step to the load found: the load keeps its distribution and the physics of
the force-controlled test, and the displacement is exact to ``tolerance``. A step that does not
reach it in ``max_solves`` solves counts as a failed solve, and the stepper cuts it.

Why not the alternatives: a penalty spring between the loaded nodes and a prescribed position
leaves an error P/k, and the spring's tangent couples the measuring node to every loaded node;
those stencils cross the ranks' slabs (Y_b is measured 89 mm from the clamp, the saddle sits at
midspan), which the MPI partition does not ghost. Dirichlet conditions on the loaded nodes would
replace the distributed load by a rigid indenter. The exact alternative, a bordered Newton
(the load as one more unknown), belongs in the solver. Units: m, N.
"""

from __future__ import annotations

from collections.abc import Callable

from . import NewtonResult

__all__ = ["DisplacementControl"]


class DisplacementControl:
    """A solver for a ``LoadStepper`` whose parameter prescribes a displacement: each ``solve``
    finds the load that gives it (the secant method on solves of ``solver``).

    Args:
        solver: the force-controlled problem (``NonlinearProblem``: ``solve``, ``commit``,
            ``rollback``, ``w``, ``stop_requested``).
        get_load, set_load: the load it controls (N).
        measure: the measured displacement at the current state (m; the same on every rank).
        prescribed: the displacement the stepper prescribes now (m).
        stiffness: gives a first guess of dP/dδ (N/m), for a step before any was committed.
        tolerance: how close the measured displacement must come to the prescribed one, m.
        max_solves: solves per step before the step counts as failed.
    """

    def __init__(
        self,
        solver,
        get_load: Callable[[], float],
        set_load: Callable[[float], None],
        measure: Callable[[], float],
        prescribed: Callable[[], float],
        stiffness: Callable[[], float],
        *,
        tolerance: float,
        max_solves: int = 8,
    ):
        self.solver = solver
        self.get_load, self.set_load = get_load, set_load
        self.measure, self.prescribed = measure, prescribed
        self.stiffness, self.tolerance, self.max_solves = stiffness, tolerance, max_solves
        self.solves = 0  # solves of the last converged step
        self._stiffest = 0.0  # the largest dP/dδ of a step so far
        self._trial: tuple[float, float] | None = None
        self.start()

    @property
    def w(self):  # the solver's unknowns (no docstring: one API target ``w``, the solver's)
        return self.solver.w

    def stop_requested(self) -> bool:
        return self.solver.stop_requested()

    def start(self) -> None:
        """Take the solver's current state as the committed one, and as the start of the ramp
        (a stage: the prescribed displacement goes one way)."""
        self._path = [(self.get_load(), self.measure())]  # (load, δ) committed along the ramp
        self._w0 = self.solver.w.x.array.copy()

    def commit(self) -> None:
        self.solver.commit()
        (load0, d0), (load, d) = self._path[-1], self._trial
        if d != d0:
            self._stiffest = max(self._stiffest, (load - load0) / (d - d0))
        self._path.append((load, d))
        self._w0 = self.solver.w.x.array.copy()

    def rollback(self) -> None:
        self.solver.rollback()
        self.set_load(self._path[-1][0])

    def solve(self) -> NewtonResult:
        """Solve for the prescribed displacement. The first load follows the ramp's committed
        states (``_first_load``), each next one the secant through the two converged states of
        the step nearest the target (``_next_load``). Each solve after the first starts from
        the unknowns interpolated along the load between the two converged states nearest it
        (before there are two: between the committed state and the stepper's predictor, which
        goes with the first load). A trial that does not converge is tried again halfway to
        the nearest converged load."""
        target = self.prescribed()
        w = self.solver.w.x.array
        slope = self._stiffest if self._stiffest > 0 else self.stiffness()
        load = _first_load(self._path, target, slope)
        states = [(*self._path[-1], self._w0)]  # the step's converged (load, δ, unknowns)
        predictor = (load, w.copy())
        iterations, seconds, lus, d = 0, 0.0, 0, states[0][1]
        for n in range(1, self.max_solves + 1):
            self.set_load(load)
            if n > 1:
                anchors = [(p, u) for p, _, u in states]
                w[:] = _along(anchors if len(anchors) > 1 else [*anchors, predictor], load)
            result = self.solver.solve()
            iterations, seconds = iterations + result.iterations, seconds + result.seconds
            lus += result.factorisations
            if not result.converged:
                if self.solver.stop_requested():
                    break
                self.solver.rollback()
                load = 0.5 * (load + _nearest(states, target)[-1][0])
                continue
            d = self.measure()
            if abs(d - target) <= self.tolerance:
                self._trial, self.solves = (load, d), n
                return NewtonResult(True, iterations, result.reason, result.residuals, seconds, lus)
            states.append((load, d, w.copy()))
            load = _next_load([(p, d) for p, d, _ in states], target, slope)
        reason = (
            f"displacement control: {abs(d - target):.3g} m short of the prescribed "
            f"displacement after {n} solves (the last: {result.reason})"
        )
        return NewtonResult(False, iterations, reason, result.residuals, seconds, lus)


def _along(anchors: list, load: float):
    """The unknowns at ``load``, linear between the two (load, unknowns) ``anchors`` whose
    loads are nearest it (the nearer one's if they share their load)."""
    (l1, w1), (l2, w2) = sorted(anchors, key=lambda a: -abs(a[0] - load))[-2:]
    return w2 + (load - l2) / (l2 - l1) * (w2 - w1) if l2 != l1 else w2.copy()


def _nearest(states: list, target: float) -> list:
    """The (at most) two ``states`` (load, δ, …) whose δ is nearest ``target``, the nearest
    last."""
    return sorted(states, key=lambda s: -abs(s[1] - target))[-2:]


def _first_load(path: list[tuple[float, float]], target: float, slope: float) -> float:
    """The first load (N) to try for the displacement ``target`` (m), from the (load, δ)
    states committed along the ramp: the quadratic P(δ) through the last three, the secant
    through the last two, or ``slope`` (N/m) from the only one; the quadratic only while it
    goes the secant's way, at most twice as far."""
    p2, d2 = path[-1]
    linear = p2 + slope * (target - d2)
    if len(path) > 1:
        p1, d1 = path[-2]
        secant = (p2 - p1) / (d2 - d1) if d2 != d1 else 0.0
        linear = p2 + (target - d2) * (secant if secant > 0 else slope)
    if len(path) < 3 or linear == p2:
        return linear
    (pa, da), (pb, db), (pc, dc) = path[-3:]
    quadratic = (
        pa * (target - db) * (target - dc) / ((da - db) * (da - dc))
        + pb * (target - da) * (target - dc) / ((db - da) * (db - dc))
        + pc * (target - da) * (target - db) / ((dc - da) * (dc - db))
    )
    return quadratic if 0 < (quadratic - p2) / (linear - p2) <= 2 else linear


def _next_load(states: list[tuple[float, float]], target: float, slope: float) -> float:
    """The load (N) to try next for the displacement ``target`` (m), from the (load, δ)
    ``states`` of the step (δ grows with P): the secant through the two nearest the target
    (``slope``, N/m, where it is not positive), inside the bracket of the target (bisected
    otherwise)."""
    (p1, d1), (p2, d2) = _nearest(states, target)
    secant = (p2 - p1) / (d2 - d1) if d2 != d1 else 0.0
    guess = p2 + (target - d2) * (secant if secant > 0 else slope)
    below = [p for p, d in states if d < target]
    above = [p for p, d in states if d > target]
    if below and above:
        lo, hi = max(below), min(above)
        if not lo < guess < hi:
            return 0.5 * (lo + hi)
    return guess
