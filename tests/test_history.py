"""The state of a history-dependent law (``NonlinearProblem(history=...)``,
``strand.solver.history``): committed once per converged step, restored on rollback, so that the
attempts ``LoadStepper`` discards leave no trace in it.

The law: a cantilever of 10 cells whose bending moment is elastic–plastic with linear kinematic
hardening (the return map of ``demos/demo_plastic_bending.py``), under an end moment m about e_z
(a ``NodalLoad``): every section carries m, so after any monotonic ramp past the yield moment
M_y each cell holds the plastic curvature κ_p = (m − M_y)/H, whatever the steps, exactly.
"""

from __future__ import annotations

import numpy as np
import pytest
import ufl
from dolfinx import fem
from mpi4py import MPI

from forms import CircularSection, ReissnerBeam
from strand.cable.mesh import beam_space, input_to_block, straight_beam_mesh
from strand.solver import InternalVariables, LoadStepper, NodalLoad, NonlinearProblem

L, N_CELLS, D, E = 1.0, 10, 0.01, 210e9
SECTION = CircularSection(D, E, 0.3)
M_Y, H = 1.0, SECTION.EI / 4  # N m, N m²: rotations of a few 0.01 rad
M_END = 1.5 * M_Y  # the end moment (N m)
KAPPA_P = (M_END - M_Y) / H  # 1/m, every cell


class PlasticBeam(ReissnerBeam):
    """Elastic–plastic bending with linear kinematic hardening about e_3 (the demo's law, on one
    axis): yield moment M_Y, hardening H, committed plastic curvature ``kappa_p`` (DG0)."""

    def __init__(self, w, section, kappa_p):
        super().__init__(w, section)
        self.kappa_p = kappa_p

    def plastic_curvature(self):
        EI, k = self.section.EI, self.K[2]
        xi = EI * (k - self.kappa_p) - H * self.kappa_p
        f = abs(xi) - M_Y
        size = ufl.conditional(ufl.gt(f, 0.0), f / (EI + H), 0.0)
        return self.kappa_p + ufl.conditional(ufl.ge(xi, 0.0), size, -size)

    @property
    def M(self):
        K = self.K
        bending = self.section.EI * (K[2] - self.plastic_curvature())
        return ufl.as_vector([self.section.GJ * K[0], self.section.EI * K[1], bending])

    def residual(self, v=None):
        v = ufl.TestFunction(self.w.function_space) if v is None else v
        d_gamma = ufl.derivative(self.Gamma, self.w, v)
        d_kappa = ufl.derivative(self.K, self.w, v)
        return (ufl.dot(self.N, d_gamma) + ufl.dot(self.M, d_kappa)) * self.dx


class Counter:
    """A ``HistoryState`` that counts its calls and keeps the plastic curvature at each commit."""

    def __init__(self, kappa_p: fem.Function):
        self.kappa_p, self.commits, self.rollbacks, self.seen = kappa_p, 0, 0, []

    def commit(self) -> None:
        self.commits += 1
        self.seen.append(self.kappa_p.x.array.copy())  # after InternalVariables' (listed first)

    def rollback(self) -> None:
        self.rollbacks += 1


def plastic_cantilever(petsc_options: dict | None = None):
    """The cantilever, its end moment (``factor`` 0 to 1 of M_END), plastic curvature, state and
    problem."""
    mesh = straight_beam_mesh(MPI.COMM_SELF, L, N_CELLS)
    V = beam_space(mesh)
    w = fem.Function(V)
    kappa_p = fem.Function(fem.functionspace(mesh, ("DG", 0)))
    beam = PlasticBeam(w, SECTION, kappa_p)
    i2b = input_to_block(V)
    bc = fem.dirichletbc(np.zeros(6), i2b[[0]], V)
    moment = NodalLoad(i2b[[N_CELLS]], [[0, 0, 0, 0, 0, M_END]])
    plastic = InternalVariables({kappa_p: beam.plastic_curvature()})
    counter = Counter(kappa_p)
    problem = NonlinearProblem(
        beam.residual(),
        w,
        [bc],
        terms=[moment],
        history=[plastic, counter],
        petsc_options=petsc_options,
    )
    return w, moment, kappa_p, plastic, counter, problem


def test_failed_attempts_leave_the_state_as_the_converged_steps_make_it():
    """Newton limited to 6 iterations fails the ramp's first attempt, the whole load in one step
    (elastic to plastic: 8 iterations), and some later ones; ``LoadStepper`` rolls each back
    and cuts (7 times, measured). The state is then the one the
    converged steps make: each cell's κ_p is (m − M_y)/H to round-off (1e-9 of it), as after one
    step with Newton unlimited; ``commit`` ran once per converged step (a commit at a failed
    attempt's iterate doubles the count) and ``rollback`` once per discarded attempt, and each
    commit saw a state no further than the last."""
    w, moment, kappa_p, plastic, counter, problem = plastic_cantilever({"snes_max_it": 6})
    try:
        stepper = LoadStepper(problem, 1.0, 1e-3)
        stepper.ramp(lambda f: setattr(moment, "factor", f), 0.0, 1.0)
        cuts = sum(r.cuts for r in stepper.history)
        assert cuts >= 1, "the first attempt was meant to fail"
        assert counter.commits == plastic.commits == len(stepper.history)
        assert counter.rollbacks == cuts + sum(r.retries for r in stepper.history)
        np.testing.assert_allclose(kappa_p.x.array, KAPPA_P, rtol=1e-9)
        # every commit saw a converged state: κ_p grows step by step up to its last value
        peaks = np.array([s.max() for s in counter.seen])
        assert np.all(np.diff(peaks) >= 0) and peaks[-1] <= KAPPA_P * (1 + 1e-9)
    finally:
        problem.destroy()

    w1, moment1, kappa_p1, plastic1, _, one_step = plastic_cantilever()
    try:
        moment1.factor = 1.0
        assert one_step.solve().converged
        one_step.commit()
        np.testing.assert_allclose(kappa_p1.x.array, kappa_p.x.array, rtol=1e-9)
        np.testing.assert_allclose(w1.x.array, w.x.array, rtol=1e-9, atol=1e-12)
    finally:
        one_step.destroy()


def test_rollback_restores_the_committed_state():
    """Whatever is written into an internal variable after a commit (a law that updates it as
    it goes), ``NonlinearProblem.rollback`` puts back the committed value, and the unknowns."""
    w, moment, kappa_p, plastic, counter, problem = plastic_cantilever()
    try:
        moment.factor = 1.0
        assert problem.solve().converged
        problem.commit()
        committed, w_committed = kappa_p.x.array.copy(), w.x.array.copy()
        np.testing.assert_allclose(committed, KAPPA_P, rtol=1e-9)
        kappa_p.x.array[:] = -1.0
        moment.factor = 2.0
        problem.solve()
        problem.rollback()
        np.testing.assert_array_equal(kappa_p.x.array, committed)
        np.testing.assert_array_equal(w.x.array, w_committed)
        assert plastic.committed()[0] == pytest.approx(committed)
    finally:
        problem.destroy()


def test_without_a_commit_the_state_stays_as_given():
    """The residual reads the committed state only: a converged solve alone changes nothing in
    it (the plastic curvature is the return map's once committed, not before)."""
    w, moment, kappa_p, plastic, counter, problem = plastic_cantilever()
    try:
        moment.factor = 1.0
        assert problem.solve().converged
        assert np.all(kappa_p.x.array == 0.0)
        assert counter.commits == 0
    finally:
        problem.destroy()
