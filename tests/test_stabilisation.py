"""Contact stabilisation (``strand.solver.Stabiliser``): springs on every pair's relative motion
since the step's start, switched on for the attempts of a step whose cuts are exhausted.

At the pair level: the residual is Sᵀ k Δg_T + k Δg_N ∂g/∂q, the energy ½ k (|Δg_T|² + Δg_N²),
the tangent matches finite differences, and switching off gives back the unstabilised pair exactly. In the stepper: a step
is retried with the springs on before it is cut, the springs are off again once it is committed,
and their energy fraction is recorded; a step that converges without them never sees them.
"""

from __future__ import annotations

import io
from types import SimpleNamespace

import numpy as np
import pytest
from mpi4py import MPI
from test_contact import crossed_pair
from test_step_control import PathSolver, ramp

from strand.app.case import case_from_dict
from strand.app.case_toml import cable_table
from strand.app.run import run_case
from strand.cable.description import cardinal
from strand.contact.normal_laws import CubicOnset, SmoothOnset
from strand.solver import LoadStepFailure, LoadStepper, NewtonResult, Stabiliser
from strand_cases import fd_tangent

K_S = 2e4  # N/m


def _moved_pair(compliance: str, line: bool):
    """Four pairs committed closed, then moved: b slid 2 µm along x and pressed 1 µm."""
    group = crossed_pair("director", line, np.radians(25), compliance=compliance)
    P, k = group.stencils.shape
    rng = np.random.default_rng(11)
    w = np.zeros((P * k, 6))
    w[:, 3:] = rng.normal(scale=0.05, size=(P * k, 3))
    w[group.stencils[:, 1], 2] -= 2e-6
    group.evaluate(w, True)
    group.commit()
    w2 = w.copy()
    w2[group.stencils[:, 1], 0] += 2e-6
    w2[group.stencils[:, 1], 2] -= 1e-6
    w2[:, :3] += rng.normal(scale=1e-8, size=(P * k, 3))
    return group, w2


@pytest.mark.parametrize("line", [False, True])
@pytest.mark.parametrize("compliance", ["penalty", "hertz"])
def test_the_springs_add_their_force_energy_and_exact_tangent(compliance, line):
    group, w = _moved_pair(compliance, line)
    g_old = group.state.gap.copy()  # committed
    f0, K0 = group.evaluate(w, True)
    dg = group.state.gap - g_old
    assert np.abs(dg).max() > 5e-7  # the pairs were pressed
    G = group._kinematics(w[group.stencils], False).gradient
    group.stabilise(K_S)
    f, K = group.evaluate(w, True)
    S, dq = group.slip_operator(), w[group.stencils[:, :2]].reshape(len(group), 12)
    dq = dq - group._q_old
    slip = np.einsum("pij,pj->pi", S, dq)
    assert np.abs(slip).max() > 1e-6  # the pairs moved
    m = S.shape[2]
    spring = K_S * dg[:, None] * G
    spring[:, :m] += np.einsum("pij,pi->pj", S, K_S * slip)
    assert np.allclose(f - f0, spring, rtol=1e-12, atol=1e-12 * np.abs(f).max())
    energy = 0.5 * K_S * (np.sum(slip**2) + np.sum(dg**2))
    assert group.stabilisation_energy == pytest.approx(energy, rel=1e-12)
    K_fd = fd_tangent(group, w)[:, :, group.dofs]
    scale = max(np.abs(K).max(), 1.0)
    assert np.abs(K - K_fd).max() <= 2e-6 * scale
    assert np.abs(K - K0).max() >= 0.5 * K_S  # the springs are in it
    group.stabilise(None)
    f1, K1 = group.evaluate(w, True)
    assert np.array_equal(f1, f0) and np.array_equal(K1, K0)


def test_a_held_onset_changes_the_law_within_its_width_only():
    """While held with ``onset``, a law with a C¹ onset (the same-layer pairs') is the cubic
    onset of that width: its forces are ``CubicOnset``'s, the tangent matches finite
    differences, the energy adds what the cubic leaves out; a pair pressed past the width feels
    the law as it is; released, the group is the unstabilised one exactly."""
    group, w = _moved_pair("hertz", True)
    group.normal_law = SmoothOnset(group.normal_law)
    f0, K0 = group.evaluate(w, True)
    gap = group.state.gap.copy()
    within = gap > -8e-6
    assert within.sum() == 3  # three pairs press by 3–5 µm, one by 11 µm
    assert group.stabilise(K_S, onset=8e-6)  # a law with an onset: widened
    f, K = group.evaluate(w, True)
    cubic = CubicOnset(group.normal_law, 8e-6)  # on the run's own law
    p = group.state.force
    np.testing.assert_allclose(p, cubic.force(gap)[0], rtol=1e-12)
    assert np.all(p[within] < group.normal_law.force(gap)[0][within])  # softer within
    assert np.array_equal(p[~within], group.normal_law.force(gap)[0][~within])  # the law beyond
    K_fd = fd_tangent(group, w)[:, :, group.dofs]
    assert np.abs(K - K_fd).max() <= 2e-6 * max(np.abs(K).max(), 1.0)
    held = group.stabilisation_energy
    group.stabilise(K_S)  # the springs alone
    group.evaluate(w, True)
    assert held == pytest.approx(group.stabilisation_energy + cubic.energy(gap).sum(), rel=1e-12)
    group.stabilise(K_S, onset=1e-7)  # narrower than the approach: the law's own forces
    group.evaluate(w, True)
    np.testing.assert_allclose(
        group.state.force, CubicOnset(cubic.law, 1e-7).force(gap)[0], rtol=1e-12
    )
    np.testing.assert_allclose(group.state.force, cubic.law.force(gap)[0], rtol=1e-12)
    group.stabilise(None)
    f1, K1 = group.evaluate(w, True)
    assert np.array_equal(f1, f0) and np.array_equal(K1, K0)
    crossings, _ = _moved_pair("hertz", False)  # a Hertz point law: no onset to widen
    assert not crossings.stabilise(K_S, onset=8e-6)


def test_a_negative_spring_is_refused():
    group, _ = _moved_pair("penalty", False)
    with pytest.raises(ValueError, match="stiffness must be >= 0"):
        group.stabilise(-1.0)
    with pytest.raises(ValueError, match="must be > 0"):
        Stabiliser([group], lambda: 1.0, MPI.COMM_SELF, stiffness=0.0)
    with pytest.raises(ValueError, match="onset 0.0 m, must be > 0"):
        Stabiliser([group], lambda: 1.0, MPI.COMM_SELF, onset=0.0)


class Held:
    """A stand-in contact group: records what the stabiliser sets, holds a fixed energy."""

    def __init__(self):
        self.stiffness = None
        self.onset = None
        self.stabilisation_energy = 0.25

    def stabilise(self, stiffness, onset=None):
        self.stiffness = stiffness
        self.onset = onset
        return onset is not None


class HeldSolver(PathSolver):
    """``PathSolver`` whose attempts fail while ``held`` is off and ``fails`` says so."""

    def __init__(self, held: Held, fails):
        super().__init__(lambda lam: lam)
        self.held = held
        self.unheld_fails = fails
        self.fails = lambda lam, predicted: self.held.stiffness is None and self.unheld_fails(lam)
        self.states: list[float | None] = []

    def solve(self):
        self.states.append(self.held.stiffness)
        return super().solve()


def test_a_step_whose_cuts_are_exhausted_is_held_from_its_first_increment_then_released():
    """A step that fails however cut (the next cut would go under ``min_step``) is tried again
    held, from the increment it was first tried at; the springs are off from the next step on."""
    held = Held()
    stabiliser = Stabiliser([held], lambda: 10.0, MPI.COMM_SELF, stiffness=K_S, onset=1e-6)
    solver = HeldSolver(held, fails=lambda lam: lam <= 0.25)
    onsets = []
    solver.solve = lambda solve=solver.solve: onsets.append(held.onset) or solve()
    _, records = ramp(
        solver, 0.0, 1.0, first_step=0.25, min_step=0.01, growth=1.0, stabiliser=stabiliser
    )
    assert [r.load for r in records] == pytest.approx([0.25, 0.5, 0.75, 1.0])
    assert records[0].cuts == 4  # 0.25 → 0.0156: the cut to 0.0078 would go under min_step
    assert solver.states == [None] * 5 + [K_S] + [None] * 3
    assert onsets == [None] * 9  # the springs sufficed: no second hold
    assert [r.stabilisation for r in records] == pytest.approx([0.025, 0, 0, 0])
    assert [r.hold for r in records] == [1, 0, 0, 0]
    assert held.stiffness is None and not stabiliser.on


def test_a_step_is_cut_as_without_springs_and_held_only_once_cuts_are_exhausted():
    """A failed step is cut as without springs (a run that converged stays the same); only
    where the next cut would go under ``min_step`` is it held, as a last resort, and the ramp
    then goes on through the loads where it has its near-mechanism."""
    held = Held()
    stabiliser = Stabiliser([held], lambda: 10.0, MPI.COMM_SELF, stiffness=K_S)
    solver = HeldSolver(held, fails=lambda lam: 0.3 < lam <= 0.5)  # a near-mechanism there
    kwargs = dict(first_step=0.25, min_step=0.01, growth=1.0, stabiliser=stabiliser)
    _, records = ramp(solver, 0.0, 1.0, **kwargs)
    assert records[-1].load == pytest.approx(1.0)
    assert records[1].cuts == 3 and records[1].load == pytest.approx(0.25 + 0.25 / 8)  # as before
    stabilised = [r for r in records if r.stabilisation]
    assert stabilised and all(0.3 < r.load <= 0.5 for r in stabilised)
    assert all(r.stabilisation == pytest.approx(0.025) for r in stabilised)
    first = records.index(stabilised[0])
    assert records[first].load - records[first - 1].load == pytest.approx(0.015625)
    assert held.stiffness is None and not stabiliser.on


def test_a_step_the_springs_cannot_hold_is_held_again_with_the_wider_onset():
    """Where the held attempts' cuts are exhausted too, the step is tried once more from its
    first increment, held with the wider onset as well; without an onset it fails there."""
    held = Held()
    stabiliser = Stabiliser([held], lambda: 10.0, MPI.COMM_SELF, stiffness=K_S, onset=1e-6)
    solver = HeldSolver(held, fails=lambda lam: lam <= 0.25)
    solver.fails = lambda lam, predicted: held.onset is None and lam <= 0.25
    onsets = []
    solver.solve = lambda solve=solver.solve: onsets.append(held.onset) or solve()
    kwargs = dict(first_step=0.25, min_step=0.01, growth=1.0)
    _, records = ramp(solver, 0.0, 1.0, stabiliser=stabiliser, **kwargs)
    assert [r.load for r in records] == pytest.approx([0.25, 0.5, 0.75, 1.0])
    assert records[0].cuts == 8  # 4 unheld, 4 held by the springs alone, each to 0.0156
    assert onsets == [None] * 10 + [1e-6] + [None] * 3
    assert solver.states[:11] == [None] * 5 + [K_S] * 6
    assert [r.hold for r in records] == [2, 0, 0, 0]
    assert held.stiffness is None and held.onset is None and not stabiliser.widened
    with pytest.raises(LoadStepFailure, match="no convergence from 0 "):
        ramp(
            HeldSolver(Held(), fails=lambda lam: lam <= 0.25),
            0.0,
            1.0,
            stabiliser=Stabiliser([Held()], lambda: 10.0, MPI.COMM_SELF, stiffness=K_S),
            **kwargs,
        )
    rigid = Held()  # a group with no law to widen: no second hold, its attempts not wasted
    rigid.stabilise = lambda stiffness, onset=None: Held.stabilise(rigid, stiffness) and False
    solver = HeldSolver(rigid, fails=lambda lam: lam <= 0.25)
    solver.fails = lambda lam, predicted: lam <= 0.25  # held or not
    stabiliser = Stabiliser([rigid], lambda: 10.0, MPI.COMM_SELF, stiffness=K_S, onset=1e-6)
    with pytest.raises(LoadStepFailure, match="after 9 step cuts"):
        ramp(solver, 0.0, 1.0, stabiliser=stabiliser, **kwargs)
    assert len(solver.states) == 10 and not stabiliser.on


def test_without_a_stabiliser_the_same_ramp_fails():
    """The loads where the stand-in has its near-mechanism cannot be stepped over by cuts."""
    held = Held()
    solver = HeldSolver(held, fails=lambda lam: 0.3 < lam <= 0.5)
    with pytest.raises(LoadStepFailure, match="no convergence from 0.296875"):
        ramp(solver, 0.0, 1.0, first_step=0.25, min_step=0.01, growth=1.0)


def test_a_held_increment_is_tried_from_one_start_only():
    """The retry from the other starting guess is for unheld attempts: each unheld increment is
    tried from the secant predictor and from the converged state, but a held increment that
    fails is halved at once (commit 784822a), so that a held step, up to 100 pseudo-time steps
    at hold 3, costs no more than before the retry was made per increment."""
    held = Held()
    stabiliser = Stabiliser([held], lambda: 10.0, MPI.COMM_SELF, stiffness=K_S)
    solver = HeldSolver(held, fails=lambda lam: 0.5 < lam <= 0.75)
    unheld, held_attempts = solver.fails, []

    def fails(lam, predicted):
        """Held, only the first attempt fails: from the predictor at the full increment (from
        the converged state it would converge, so a retry would take it)."""
        if held.stiffness is None:
            return unheld(lam, predicted)
        held_attempts.append(lam)
        return len(held_attempts) == 1

    solver.fails = fails
    kwargs = dict(first_step=0.25, min_step=0.05, growth=1.0, extrapolate=True, retry=True)
    _, records = ramp(solver, 0.0, 1.0, stabiliser=stabiliser, **kwargs)
    assert [r.load for r in records] == pytest.approx([0.25, 0.5, 0.625, 0.75, 0.875, 1.0])
    tried = [
        (round(lam, 9), p, k is not None)
        for (lam, p), k in zip(solver.attempts, solver.states, strict=True)
    ]
    # unheld, from 0.5: 0.75, 0.625 and 0.5625 fail from both starts; the next cut would go
    # under min_step
    assert tried[2:10] == [
        (0.75, True, False),
        (0.75, False, False),
        (0.625, True, False),
        (0.625, False, False),
        (0.5625, True, False),
        (0.5625, False, False),
        (0.75, True, True),  # held from the first increment; fails, and is not retried
        (0.625, True, True),  # halved at once, and converges
    ]
    assert (records[2].retries, records[2].cuts, records[2].hold) == (3, 3, 1)
    assert held.stiffness is None and not stabiliser.on


def _ring_19(stabilise: float) -> dict:
    """Cardinal's core and first two layers (1+6+12), 0.5 m, its steel ring vaulted over the
    core (``first_layer = "ring"``), pulled to 15 kN, with the springs ``stabilise`` (N/m)."""
    cable = cable_table(cardinal())
    cable["layer"] = cable["layer"][:2]
    return {
        "cable": cable | {"name": "1+6+12"},
        "mesh": {"length": 0.5},
        "load": {"tension": 15e3, "cycle": [0.0]},
        "contact": {"first_layer": "ring"},
        "steps": {"stabilise": stabilise},
        "output": {"fields": False, "plots": False, "checkpoint": False},
        "fatigue": {"outputs": False},
    }


@pytest.mark.slow
def test_a_vaulted_ring_starts_only_when_stabilised_and_the_springs_leave_no_trace(tmp_path):
    """A ring of touching circles is a mechanism but for its wires' bending: on 0.5 m of a
    1+6+12 no tension step converges, however cut (measured: 7 cuts from 1 kN, also from a
    200 N first step). With the springs the first step converges, held by 9.6e-4 of the strain
    energy at 1e4 N/m (measured; the ring's pairs close as it shrinks onto the core, and their
    change of gap is held too); the next ones need none. Springs ten times softer give the
    same strand at 15 kN (measured: axial forces within 2.6e-4, contact forces 1.0 %): what
    they held was handed back. The strain is the fibre model's within 2 % (measured 1.2 %)."""
    off = io.StringIO()
    result = run_case(case_from_dict(_ring_19(0.0)), tmp_path / "off", stream=off)
    assert result.failure and not result.steps
    assert "'A tension that stops early'" in result.failure  # where the user is sent
    runs, summaries = {}, {}
    for k in (1e4, 1e3):
        out = io.StringIO()
        runs[k] = run_case(case_from_dict(_ring_19(k)), tmp_path / f"k{k:g}", stream=out)
        r = runs[k]
        assert not r.failure and r.steps[-1].load == pytest.approx(15e3)
        held = [s.stabilisation for s in r.steps if s.stabilisation]
        assert 1 <= len(held) <= 2 and 0 < max(held) < 1e-3
        summaries[k] = out.getvalue()
        effort = next(line for line in summaries[k].splitlines() if line.startswith("done"))
        assert f"energy at most {max(held):.1e} of the strain energy" in effort
        assert "with the wider onset" not in effort and {s.hold for s in r.steps} == {0, 1}
    stiff, soft = (runs[k].tension_end for k in (1e4, 1e3))
    scale = np.abs(stiff.axial).max()
    assert np.abs(stiff.axial - soft.axial).max() <= 1e-3 * scale
    pairs = [runs[k].tension_end_pairs.force for k in (1e4, 1e3)]
    assert np.abs(pairs[0] - pairs[1]).max() <= 0.02 * np.abs(pairs[0]).max()
    strain = next(line for line in summaries[1e4].splitlines() if "strain (µε)" in line)
    model, fibre = (float(v) for v in strain.split()[2:4])
    assert model == pytest.approx(fibre, rel=0.02)


def _stalling_solve(convergence, residuals: list[float]) -> tuple[int, int]:
    """Feed a residual history to a SNES convergence test, as PETSc's Newton would: the
    iteration it stops at and its reason (0: never stopped)."""
    convergence.reset()
    for its, r in enumerate(residuals):
        convergence.record(r)
        reason = convergence(None, its, (1.0, 1.0, r))
        if reason != 0:
            return its, reason
    return len(residuals), 0


def test_a_last_resort_is_patient_and_the_springs_make_it_so():
    """Held attempts are a step's last: Newton's stall test (a residual not halved in two
    iterations, from the 4th) is off and it may take ``LAST_RESORT_ITERATIONS`` times its
    iterations; switched off,
    the options hold again. The stabiliser makes the solver patient exactly while it is on."""
    from petsc4py import PETSc

    from strand.solver import NewtonOptions
    from strand.solver.convergence import LAST_RESORT_ITERATIONS, NewtonConvergence

    options = NewtonOptions(stall_after=4, max_it=12, atol=1e-9, rtol=0.0)
    test = NewtonConvergence(options, PETSc.Vec().createSeq(6), MPI.COMM_SELF)
    slow = list(10.0 * 0.8 ** np.arange(60))  # linear, 0.8 an iteration: converging slowly
    reasons = PETSc.SNES.ConvergedReason
    its, reason = _stalling_solve(test, slow)
    assert (its, reason) == (4, reasons.DIVERGED_DTOL) and test.stalled
    test.patience = LAST_RESORT_ITERATIONS * options.max_it
    its, reason = _stalling_solve(test, slow)
    assert (its, reason) == (test.patience, reasons.DIVERGED_MAX_IT) and test.patience > 12
    assert not test.stalled
    test.patience = None
    assert _stalling_solve(test, slow)[0] == 4

    class Solver:
        patient: list[bool] = []

        def last_resort(self, on):
            self.patient.append(on)

    held, solver = Held(), Solver()
    stabiliser = Stabiliser([held], lambda: 1.0, MPI.COMM_SELF, stiffness=K_S, newton=solver)
    stabiliser.switch(True)
    assert held.stiffness == K_S and solver.patient == [True]
    stabiliser.switch(False)
    assert held.stiffness is None and solver.patient == [True, False]


class Fold:
    """A one-unknown stand-in for ``NonlinearProblem`` past a buckling: R(x) = x³ − 3x − f,
    whose tangent 3x² − 3 is negative between its folds. Its Newton fails at an iterate where
    the tangent (with the relaxation's c) is not positive, as a line search stalls on a
    direction that is no descent one; ``relax`` holds x to its value by c. One node: x is its
    first dof, the others stay 0."""

    def __init__(self, x: float, load: float):
        self.w = SimpleNamespace(x=SimpleNamespace(array=np.array([x, 0, 0, 0, 0, 0.0])))
        self._saved = self.w.x.array.copy()
        self.load = load
        self.held: tuple[float, float] | None = None  # (c, x_ref)
        self.log: list[tuple[float | None, bool]] = []  # (c, converged) of every solve
        self.norms: list[list[float]] = []  # the residuals of every solve
        self.patient: list[bool] = []

    def residual(self, x: float) -> float:
        c, ref = self.held or (0.0, 0.0)
        return x**3 - 3 * x - self.load + c * (x - ref)

    def solve(self) -> NewtonResult:
        x, c = float(self.w.x.array[0]), self.held[0] if self.held else 0.0
        norms = []
        for its in range(20):
            r = self.residual(x)
            norms.append(abs(r))
            if abs(r) < 1e-12:
                break
            tangent = 3 * x**2 - 3 + c
            if tangent <= 0:
                its = -1
                break
            x -= r / tangent
        converged = its >= 0 and norms[-1] < 1e-12
        self.norms.append(norms)
        self.w.x.array[0] = x
        self.log.append((self.held[0] if self.held else None, converged))
        return NewtonResult(converged, len(norms), "", norms, 0.0, len(norms))

    def relax(self, stiffness, length=1.0):
        self.held = None if stiffness is None else (stiffness, float(self.w.x.array[0]))

    def relaxation_force(self) -> float:
        c, ref = self.held
        return abs(c * (self.w.x.array[0] - ref))

    def last_resort(self, on):
        self.patient.append(on)

    def set_load(self, load):
        self.load = load

    def commit(self):
        self._saved = self.w.x.array.copy()

    def rollback(self):
        self.w.x.array[:] = self._saved

    def stop_requested(self):
        return False


def test_a_relaxed_solve_comes_to_rest_where_newton_cannot_start():
    """From x = 0, between the folds of R = x³ − 3x − ½ (tangent −3), Newton fails; pseudo-
    transient continuation (springs c from x to where the last solve left it, c = 1 too soft:
    four times stiffer, then softer as the springs' force falls) moves x as a damped motion
    would, to the stable root beyond the fold, 1.8100379…, where the plain Newton then converges: an
    equilibrium of R itself, not of R with springs."""
    fold = Fold(0.0, 0.5)
    assert not fold.solve().converged
    fold.w.x.array[:] = 0.0
    lines: list[str] = []  # its progress, a line per pseudo-time step
    stabiliser = Stabiliser(
        [], lambda: 1.0, MPI.COMM_SELF, newton=fold, relaxation=1.0, report=lines.append
    )
    result = stabiliser.relaxed_solve()
    assert len(lines) == len(fold.log) - 2  # every relaxed solve, not the two plain ones
    assert lines[0].endswith("failed") and "springs 4.0e+00 N/m" in lines[1]
    assert all(" N/m, " in line for line in lines)
    root = np.roots([1, 0, -3, -0.5]).real.max()
    assert result.converged and fold.w.x.array[0] == pytest.approx(root, rel=1e-12)
    assert fold.log[1:3] == [(1.0, False), (4.0, True)]  # too soft, then four times stiffer
    assert fold.log[-1] == (None, True) and fold.held is None  # the plain solve, springs off
    assert all(c is not None for c, _ in fold.log[1:-1])
    assert (
        result.iterations
        == result.factorisations
        == sum(  # every solve's, counted
            len(norms) for norms in fold.norms[1:]
        )
    )


def test_the_relaxation_is_the_third_hold_and_leaves_nothing_held():
    """A step that neither the cuts nor the springs (nor the wider onset) carry is solved by
    the relaxation from its first increment: recorded as hold 3, fraction 0 (an equilibrium);
    the next steps are plain again. Without a relaxation the same ramp fails; a stepper whose
    solver is not the relaxation's (a displacement control) does not relax."""
    held = Held()
    fold = Fold(-2.0, 0.0)  # the stable root left of the folds, R' > 0
    fold.solve()
    fold.commit()
    steps: list[float | None] = []
    plain = fold.solve

    def solve():  # cuts and springs fail in the fold's middle: tangent ≤ 0
        steps.append(held.stiffness)
        return plain()

    fold.solve = solve
    stabiliser = Stabiliser(
        [held], lambda: 1.0, MPI.COMM_SELF, stiffness=K_S, newton=fold, relaxation=1.0
    )
    stepper = LoadStepper(fold, 1.0, 0.1, growth=1.0, stabiliser=stabiliser)
    records = stepper.ramp(fold.set_load, 0.0, 3.0)
    assert [r.load for r in records][-1] == pytest.approx(3.0)
    holds = [r.hold for r in records]
    assert 3 in holds and set(holds) <= {0, 3}
    assert all(r.stabilisation == 0 for r in records)
    jumped = holds.index(3)
    assert records[jumped - 1].load <= 2.0 < records[jumped].load  # past the fold at f = 2
    assert fold.w.x.array[0] == pytest.approx(np.roots([1, 0, -3, -3.0]).real.max())
    assert not stabiliser.level and fold.held is None
    fold = Fold(-2.0, 0.0)
    fold.solve()
    fold.commit()
    without = Stabiliser([Held()], lambda: 1.0, MPI.COMM_SELF, stiffness=K_S, newton=fold)
    with pytest.raises(LoadStepFailure):
        LoadStepper(fold, 1.0, 0.1, growth=1.0, stabiliser=without).ramp(fold.set_load, 0, 3)
