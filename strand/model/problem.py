"""A strand problem: the model (wires and contact), a test set-up (supports, loads, measures) and
the nonlinear problem (``strand.solver.NonlinearProblem``) that ties them together.

``StrandProblem(geometry, contact, options, setup=SaddleTest)`` is the seed paper's saddle test;
``setup`` (a callable taking the ``StrandModel``, e.g. ``functools.partial(UniformBendingTest,
zone=0.4)``) names the test, and has no default. Units: m, N, Pa.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import replace
from typing import Protocol

import numpy as np
import numpy.typing as npt
from mpi4py import MPI
from petsc4py import PETSc

from forms import ReissnerBeam

from ..cable.geometry import StrandGeometry
from ..solver import NewtonOptions, NonlinearProblem
from ..solver.convergence import STALL_AFTER
from ..solver.ordering import ORDERINGS, cheapest_ordering
from .contact_settings import ContactSettings
from .model import BeamFactory, StrandModel
from .pair_results import PairResults

__all__ = ["StrandProblem", "Conditions"]

Array = npt.NDArray[np.float64]

#: unknowns from which the MUMPS ordering is chosen by trial: below, an LU takes ~0.1 s or less
#: and the trial factorisations would cost more than the choice saves
ORDERING_TRIAL_SIZE = 50_000


class Conditions(Protocol):
    """What the problem takes from its test set-up (a ``strand.setups.TestSetup``, which the
    model does not import: the set-ups are built on the model): its supports and its pair terms
    (ties, nodal loads). ``StrandProblem[S]`` keeps the set-up's own type ``S``, e.g.
    ``StrandProblem[TestSetup]``."""

    bcs: list
    terms: list


class StrandProblem[S: Conditions]:
    """The strand of ``geometry`` in the test ``setup``; ``solver`` is its ``NonlinearProblem``
    (whose ``solver`` in turn is the SNES).

    Args:
        geometry: the strand (``build_geometry``).
        contact: contact settings (normal, penalties, friction).
        options: Newton settings (a ``stall_after`` of None takes strand's ``STALL_AFTER``).
        setup: builds the test set-up from the model (e.g. ``strand.setups.SaddleTest``).
        comm: the ranks the strand is distributed over.
        monitor: called as ``monitor(iteration, residual_norm)`` at every Newton iteration.
        beam: the wires' beam law, ``beam(w, section)`` (``StrandModel``); default
            ``ReissnerBeam``. A history-dependent law's ``history`` (its state, e.g.
            ``InternalVariables``) goes to ``solver``, committed once per converged step.
    """

    def __init__(
        self,
        geometry: StrandGeometry,
        contact: ContactSettings | None = None,
        options: NewtonOptions | None = None,
        *,
        setup: Callable[[StrandModel], S],
        comm: MPI.Comm = MPI.COMM_WORLD,
        monitor: Callable[[int, float], None] | None = None,
        beam: BeamFactory = ReissnerBeam,
    ):
        self.model = StrandModel(geometry, contact, comm, beam=beam)
        self.setup: S = setup(self.model)
        # MUMPS ordering: PORD unless the case sets one; a large strand's pattern is factorised
        # with PORD and AMF once, and the cheaper kept (``strand.solver.ordering``)
        user = options.petsc if options is not None else {}
        mumps = {"mat_mumps_icntl_7": ORDERINGS["pord"]}
        if comm.size > 1:
            # distributed, MUMPS schedules fronts dynamically and its workspace estimate (+20 %)
            # falls short at random (INFOG(1) = −9, "out of memory" at the first factorisation in
            # 2 of 6 runs of 0.1 m of Cardinal on 3 ranks; 0 of 8 with twice the estimate)
            mumps["mat_mumps_icntl_14"] = 100
        options = options or NewtonOptions()
        stall = STALL_AFTER if options.stall_after is None else options.stall_after
        options = replace(options, petsc={**mumps, **options.petsc}, stall_after=stall)
        self.solver = NonlinearProblem(
            self.model.beam.residual(),
            self.model.w,
            self.setup.bcs,
            terms=[*self.model.contact, *self.model.same_layer, *self.setup.terms],
            history=list(getattr(self.model.beam, "history", ())),
            options=options,
            monitor=monitor,
        )
        #: the MUMPS ordering (name) and, when chosen by trial, every candidate's LU operations
        self.ordering: tuple[str, dict[str, float]] = ("pord", {})
        n_unknowns = 6 * self.model.V.dofmap.index_map.size_global
        if "mat_mumps_icntl_7" in user:
            names = {v: k for k, v in ORDERINGS.items()}
            self.ordering = (names.get(int(user["mat_mumps_icntl_7"]), "case's"), {})
        elif n_unknowns >= ORDERING_TRIAL_SIZE:
            self.ordering = cheapest_ordering(self.solver.A)
            prefix = self.solver.solver.getOptionsPrefix()
            PETSc.Options()[f"{prefix}mat_mumps_icntl_7"] = ORDERINGS[self.ordering[0]]

    # the model's parts, for short access
    @property
    def geometry(self) -> StrandGeometry:
        return self.model.geometry

    @property
    def w(self):
        return self.model.w

    @property
    def V(self):
        return self.model.V

    @property
    def beam(self):
        return self.model.beam

    @property
    def cmesh(self):
        return self.model.cmesh

    @property
    def contact(self):
        return self.model.contact

    @property
    def i2b(self):
        return self.model.i2b

    @property
    def nodal(self) -> Array:
        return self.model.nodal

    def positions(self) -> Array:
        return self.model.positions()

    def pair_results(self) -> PairResults:
        return self.model.pair_results()
