"""A strand problem: the model (wires and contact), a test set-up (supports, loads, measures) and
the nonlinear problem (``strand.solver.NonlinearProblem``) that ties them together.

``StrandProblem(geometry, contact, options)`` is the seed paper's saddle test; pass ``setup`` (a
callable taking the ``StrandModel``, e.g. ``functools.partial(UniformBendingTest, zone=0.4)``) for
another. Units: m, N, Pa.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import replace

import numpy as np
import numpy.typing as npt
from mpi4py import MPI

from .contact_settings import ContactSettings
from .geometry import StrandGeometry
from .model import StrandModel
from .pair_results import PairResults
from .setups.base import TestSetup
from .setups.saddle import SaddleTest
from .solver import NewtonOptions, NonlinearProblem
from .solver.convergence import STALL_AFTER

__all__ = ["StrandProblem"]

Array = npt.NDArray[np.float64]


class StrandProblem:
    """The strand of ``geometry`` in the test ``setup``; ``solver`` is its ``NonlinearProblem``
    (whose ``solver`` in turn is the SNES).

    Args:
        geometry: the strand (``build_geometry``).
        contact: contact settings (normal, penalties, friction).
        options: Newton settings (a ``stall_after`` of None takes strand's ``STALL_AFTER``).
        setup: builds the test set-up from the model (default: ``SaddleTest``).
    """

    def __init__(
        self,
        geometry: StrandGeometry,
        contact: ContactSettings | None = None,
        options: NewtonOptions | None = None,
        setup: Callable[[StrandModel], TestSetup] = SaddleTest,
        comm: MPI.Comm = MPI.COMM_WORLD,
        monitor=None,
    ):
        self.model = StrandModel(geometry, contact, comm)
        self.setup = setup(self.model)
        # MUMPS ordering: PORD factorises the Cardinal tangent in 0.53 s against 0.71 s for the
        # default choice (METIS), the same accuracy (2-core machine, 129,492 unknowns)
        mumps = {"mat_mumps_icntl_7": 4}
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
            options=options,
            monitor=monitor,
        )

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
