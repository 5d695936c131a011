"""Contact stabilisation of a load step that would not converge otherwise.

A strand whose wires can roll round the layer below at little cost has near-mechanisms on which
Newton stalls: the frictionless first tension step (a pair closing from zero force has no stick
stiffness yet), a king wire whose layer's gaps are open, a vaulted ring. As Abaqus' contact
stabilisation damps the relative motion of the surfaces, a ``Stabiliser`` holds every pair's
relative motion since the step's start, its slip Δg_T and its change of gap Δg_N (open pairs'
as well: a vaulted ring's radial mode), with a spring k (N/m), in the attempts that follow a
failed one, once its cuts are exhausted (``LoadStepper(stabiliser=…)``), so that a run that
converged without springs converges as before. The springs are not committed: the next step
starts without them, so the forces they held at the converged step are handed to the friction
that the closed pairs then carry (the step commits the state it converged to).

Where the springs' own cuts are exhausted too, a second hold (``onset``) gives the normal laws
with a C¹ onset (the same-layer pairs') a wider one, a cubic over the first ``onset`` of
approach, exact beyond (``strand.contact.normal_laws.CubicOnset``): the neighbours of a packed
layer that sit within nanometres of touching then stop opening and closing every iteration (the
chatter counted on 1 m of Cardinal with its ring vaulted at 500 N, in the bending set-up before
its core was held centred, design notes 2026-11-29).

Where that fails too, the tangent itself may not be positive (past a buckling, as the bending
set-up's free core at 20 kN before it was centred, or with friction's slip tangent); an opt-in
third hold (``relaxation``) solves the step by pseudo-transient continuation instead
(``relaxed_solve``), which leaves nothing held.

What they did is reported as Abaqus reports ALLSD beside ALLIE: the springs' energy at the
converged step, ½ Σ k (|Δg_T|² + Δg_N²), and in a second hold the force the wider onset leaves
out, as an energy ½ Σ Δp²/k_N (``CubicOnset.energy``), over the strain energy of the beams (a
fraction; Abaqus' users aim at a few per cent at most). Units: N/m, m, J.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import KW_ONLY, dataclass, field
from typing import Any, Protocol

from mpi4py import MPI

from .convergence import NewtonResult

__all__ = ["Stabilised", "Stabiliser", "RELAXATION_STEPS", "PLAIN_BELOW"]

#: pseudo-time steps of a relaxed solve (``Stabiliser.relaxed_solve``)
RELAXATION_STEPS = 100
#: the springs' force (N) under which a relaxed solve tries the problem without them
PLAIN_BELOW = 1.0
#: the springs' stiffness after a failed pseudo-time step, and after an easy one (at most
#: ``EASY`` Newton iterations), over the last: the steps stay as long as converge, just stiffer
#: than the tangent's most negative stiffness
STIFFER, SOFTER, EASY = 4.0, 0.5, 2


class Patient(Protocol):
    """A solver that can be patient for a last resort and relax
    (``strand.solver.NonlinearProblem``)."""

    w: Any

    def last_resort(self, on: bool) -> None: ...

    def relax(self, stiffness: float | None, length: float = 1.0) -> None: ...

    def relaxation_force(self) -> float: ...

    def solve(self) -> NewtonResult: ...


class Stabilised(Protocol):
    """A contact group that a ``Stabiliser`` can hold (``strand.contact.PairGroup``)."""

    stabilisation_energy: float

    def stabilise(self, stiffness: float | None, onset: float | None = None) -> bool: ...


@dataclass
class Stabiliser:
    """Springs of ``stiffness`` (N/m per pair) on ``groups``, switched on for the
    attempts of a step whose cuts are exhausted, then with the wider ``onset`` (m) too
    (``escalate``); ``strain_energy()`` the beams' strain energy (J, summed over the ranks of
    ``comm``)."""

    groups: Sequence[Stabilised]
    strain_energy: Callable[[], float]
    comm: MPI.Comm
    stiffness: float = 1e4
    _: KW_ONLY
    #: the width (m) of the C¹ onset of the normal laws that have one (``SmoothOnset``: the
    #: same-layer pairs') in a second hold, once the springs' own cuts are exhausted too, exact
    #: beyond it (``CubicOnset``; None: no second hold)
    onset: float | None = None
    #: the solver whose attempts the springs hold: patient while they are on (no stall test,
    #: ``LAST_RESORT_ITERATIONS``), as the held attempts are the step's last
    newton: Patient | None = None
    #: a third hold, where the second's cuts are exhausted too: pseudo-transient continuation
    #: (``relaxed_solve``) from springs of this stiffness (N/m per node; None: none), with
    #: ``length`` (m) turning it into the rotations' (× length², N m/rad)
    relaxation: float | None = None
    length: float = 1e-3
    #: told one line per pseudo-time step of ``relaxed_solve`` (its progress), if given
    report: Callable[[str], None] | None = None
    #: pseudo-time steps a ``relaxed_solve`` takes at most
    relaxation_steps: int = RELAXATION_STEPS
    on: bool = field(default=False, init=False)
    #: the springs hold with the wider onset (``escalate``)
    widened: bool = field(default=False, init=False)
    #: the step is solved by ``relaxed_solve`` (``escalate``)
    relaxing: bool = field(default=False, init=False)

    def __post_init__(self):
        if not self.stiffness > 0:
            raise ValueError(f"Stabiliser: stiffness {self.stiffness} N/m, must be > 0")
        if self.onset is not None and not self.onset > 0:
            raise ValueError(f"Stabiliser: onset {self.onset} m, must be > 0")
        if self.relaxation is not None and not (self.relaxation > 0 and self.newton):
            raise ValueError(
                f"Stabiliser: relaxation {self.relaxation} N/m needs a solver (newton) and > 0"
            )

    def switch(self, on: bool, widened: bool = False) -> bool:
        """Springs on (at ``stiffness``; ``widened``: with the wider ``onset`` too) or off on
        every group; whether a group on any rank took the wider onset."""
        onset = self.onset if on and widened else None
        took = [g.stabilise(self.stiffness if on else None, onset) for g in self.groups]
        self.on = on
        self.relaxing = False
        self.widened = bool(self.comm.allreduce(any(took), op=MPI.LOR))
        if self.newton is not None:
            self.newton.last_resort(on)
        return self.widened

    @property
    def level(self) -> int:
        """The hold now on: 0 none, 1 the springs, 2 the springs with the wider onset, 3 the
        relaxation."""
        return 3 if self.relaxing else 0 if not self.on else 2 if self.widened else 1

    def escalate(self, relax: bool = True) -> bool:
        """The next hold for a step whose cuts are exhausted: the springs, then (their cuts
        exhausted too) the springs with the wider ``onset``, where a group has a law to widen,
        then (``relax``: the stepper's solver is ``newton``) the springs off and the step
        solved by ``relaxed_solve``; False when there is none left."""
        if self.relaxing:
            return False
        if not self.on:
            self.switch(True)
            return True
        if self.onset is not None and not self.widened and self.switch(True, widened=True):
            return True
        if relax and self.relaxation is not None:
            self.switch(False)
            self.relaxing = True
            return True
        return False

    def relaxed_solve(self) -> NewtonResult:
        """The step solved by pseudo-transient continuation (Kelley & Keyes, SIAM J. Numer.
        Anal. 35, 1998), where Newton's tangent is not positive (past a buckling, or where
        friction's slip tangent is not): solves with every free dof held by a spring c to where
        the last one left it (``NonlinearProblem.relax``), c ``STIFFER`` after a failed one
        and, after a converged one, softer by the ratio of the springs' force to the last where it fell (switched
        evolution relaxation) or by ``SOFTER`` after an easy solve (so that it stays just
        stiffer than the tangent's most negative stiffness, where the motion along the
        unstable mode is fastest), until their force, falling, is under ``PLAIN_BELOW`` and a
        solve without them converges from there. So the state found is an equilibrium of the
        problem itself (nothing is left held: its fraction is 0); the springs choose which
        one, the one a damped motion from the step's start reaches."""
        newton = self.newton
        assert newton is not None and self.relaxation is not None  # __post_init__
        c, last = self.relaxation, None
        its, lus, seconds = 0, 0, 0.0
        result = None
        for _ in range(self.relaxation_steps):
            kept = newton.w.x.array.copy()
            newton.relax(c, self.length)
            r = newton.solve()
            force = newton.relaxation_force() if r.converged else float("inf")
            newton.relax(None)
            its, lus, seconds = its + r.iterations, lus + r.factorisations, seconds + r.seconds
            if self.report is not None:
                self.report(
                    f"relaxing: springs {c:.1e} N/m, {r.iterations} Newton its, "
                    + (f"their force {force:.3g} N" if r.converged else "failed")
                )
            if not r.converged:
                newton.w.x.array[:] = kept  # back to the last relaxed state, held stiffer
                c *= STIFFER
                continue
            if force < PLAIN_BELOW and last is not None and force < last:  # coming to rest
                relaxed = newton.w.x.array.copy()
                result = newton.solve()
                its += result.iterations
                lus += result.factorisations
                seconds += result.seconds
                if result.converged:
                    break
                newton.w.x.array[:] = relaxed
            if last is not None and force < last:
                c *= max(force / last, 0.1)  # softer as it comes to rest
            elif r.iterations <= EASY:
                c *= SOFTER  # an easy solve: a longer pseudo-time step
            last = force
        converged = result is not None and result.converged
        return NewtonResult(
            converged,
            its,
            result.reason if result is not None else "relaxation: no converged solve",
            result.residuals if result is not None else [],
            seconds,
            lus,
        )

    def energy(self) -> float:
        """The hold's energy at the last evaluation (the springs' and the wider onset's),
        all ranks (J)."""
        local = sum(g.stabilisation_energy for g in self.groups) if self.on else 0.0
        return self.comm.allreduce(local, op=MPI.SUM)

    def fraction(self) -> float:
        """``energy()`` over the strain energy at the last evaluation (0 when off)."""
        if not self.on:
            return 0.0
        u = self.strain_energy()
        e = self.energy()
        return e / u if u > 0 else float("inf") if e > 0 else 0.0
