"""strand's NonlinearProblem (dolfinx's, with pair terms outside UFL and strand's convergence tests),
nodal loads, step cutting, history rollback."""

from dataclasses import replace

import dolfinx.fem.petsc
import numpy as np
import pytest
from dolfinx import fem
from mpi4py import MPI

from beam_cases import cantilever, section_stiffness
from forms import CircularSection, ReissnerBeam
from strand.cable.mesh import beam_space, input_to_block, polyline_mesh
from strand.solver import LoadStepFailure, LoadStepper, NewtonOptions, NodalLoad, NonlinearProblem

S = section_stiffness()


class AxialSpring:
    """Linear springs of stiffness k (N/m) on u_x between node pairs, with a committed history
    counter (number of committed states) to observe commit/rollback."""

    def __init__(self, pairs, k):
        self.stencils = np.asarray(pairs, dtype=np.int32)
        self.k = k
        self.committed = 0
        self.rollbacks = 0

    def evaluate(self, w, jacobian):
        P = len(self.stencils)
        du = w[self.stencils[:, 0], 0] - w[self.stencils[:, 1], 0]
        f = np.zeros((P, 12))
        f[:, 0], f[:, 6] = self.k * du, -self.k * du
        K = np.zeros((P, 12, 12))
        K[:, 0, 0] = K[:, 6, 6] = self.k
        K[:, 0, 6] = K[:, 6, 0] = -self.k
        return f, K

    def commit(self):
        self.committed += 1

    def rollback(self):
        self.rollbacks += 1


def two_bars(n_cells=8, length=1.0, gap=0.05):
    """Two parallel bars along x, clamped at x = 0; returns the pieces and their tip blocks."""
    s = np.linspace(0.0, length, n_cells + 1)
    x = np.vstack([np.column_stack([s, 0 * s, 0 * s]), np.column_stack([s, 0 * s + gap, 0 * s])])
    c = np.column_stack([np.arange(n_cells), np.arange(1, n_cells + 1)])
    cells = np.vstack([c, c + n_cells + 1])
    mesh = polyline_mesh(MPI.COMM_WORLD, x, cells)
    V = beam_space(mesh)
    i2b = input_to_block(V)
    roots = i2b[[0, n_cells + 1]]
    tips = i2b[[n_cells, 2 * n_cells + 1]]
    return mesh, V, roots, tips


def test_pair_term_couples_two_bars_exactly():
    """A spring between two bar tips (a pair term outside UFL, on an extended sparsity pattern) and a
    nodal load on one tip: u1 = F(kb + k)/(kb(kb + 2k)), u2 = F k/(kb(kb + 2k)), kb = EA/L."""
    mesh, V, roots, tips = two_bars()
    w = fem.Function(V)
    beam = ReissnerBeam(w, CircularSection(0.01, 210e9, 0.3))
    bc = fem.dirichletbc(np.zeros(6), roots, V)
    k, F = 3.0e8, 5.0e3
    spring = AxialSpring([tips], k)
    load = NodalLoad([tips[0]], [[F, 0, 0, 0, 0, 0]], factor=1.0)
    solver = NonlinearProblem(beam.residual(), w, [bc], terms=[spring, load])
    result = solver.solve()
    assert result.converged and result.iterations <= 2
    kb = S["EA"] / 1.0
    u = w.x.array.reshape(-1, 6)[tips, 0]
    assert u[0] == pytest.approx(F * (kb + k) / (kb * (kb + 2 * k)), rel=1e-9)
    assert u[1] == pytest.approx(F * k / (kb * (kb + 2 * k)), rel=1e-9)


def test_pair_terms_on_clamped_dofs_are_masked():
    """A spring tying a free tip to a clamped root: its entries on the clamped dofs are dropped, so
    the root stays fixed and the tip feels a spring to ground: u = F/(kb + k)."""
    mesh, V, roots, tips = two_bars()
    w = fem.Function(V)
    beam = ReissnerBeam(w, CircularSection(0.01, 210e9, 0.3))
    bc = fem.dirichletbc(np.zeros(6), roots, V)
    k, F = 1.0e8, 2.0e3
    solver = NonlinearProblem(
        beam.residual(),
        w,
        [bc],
        terms=[
            AxialSpring([[tips[0], roots[1]]], k),
            NodalLoad([tips[0]], [[F, 0, 0, 0, 0, 0]], 1.0),
        ],
    )
    assert solver.solve().converged
    wn = w.x.array.reshape(-1, 6)
    assert wn[tips[0], 0] == pytest.approx(F / (S["EA"] + k), rel=1e-9)
    assert np.all(wn[roots] == 0.0)


def test_step_cutting_recovers_and_commits_only_converged_steps():
    """A roll-up step too large for 8 Newton iterations is cut, then completed; the history of the
    pair terms is committed once per converged step and rolled back once per failed attempt."""
    spring = AxialSpring(np.zeros((0, 2)), 0.0)
    case = cantilever(20, terms=[spring], options=NewtonOptions(max_it=8))
    M = np.pi * S["EI"]
    stepper = LoadStepper(case.solver, first_step=1.0, min_step=1e-3)
    solves = []  # every Newton solve's outcome, the failed ones too
    solve = case.solver.solve
    case.solver.solve = lambda: solves.append(solve()) or solves[-1]
    records = stepper.ramp(lambda lam: setattr(case.moment, "value", [0, 0, lam * M]), 0.0, 1.0)
    assert records[-1].load == pytest.approx(1.0)
    assert sum(r.cuts for r in records) >= 1
    # the failed attempts' iterations are charged to the step that follows them
    assert (
        sum(r.failed_iterations for r in records)
        == sum(r.iterations for r in solves if not r.converged)
        > 0
    )
    assert spring.committed == len(records)
    assert spring.rollbacks == sum(r.cuts for r in records)
    assert case.tip_theta[2] == pytest.approx(np.pi, rel=1e-9)


def test_unreachable_step_stops_with_clear_message_and_keeps_last_state():
    case = cantilever(20, options=NewtonOptions(max_it=2))
    M = np.pi * S["EI"]
    written = []
    stepper = LoadStepper(case.solver, first_step=0.5, min_step=0.1, on_step=written.append)
    solves = []  # every attempt's Newton solve
    solve = case.solver.solve
    case.solver.solve = lambda: solves.append(solve()) or solves[-1]
    with pytest.raises(LoadStepFailure, match=r"roll-up: no convergence from 0 towards") as e:
        stepper.ramp(
            lambda lam: setattr(case.moment, "value", [0, 0, lam * M]), 0.0, 1.0, "roll-up"
        )
    # the failure carries what its attempts cost, which no step record holds
    assert len(solves) >= 3 and not any(r.converged for r in solves)
    assert e.value.iterations == sum(r.iterations for r in solves)
    assert e.value.factorisations == sum(r.factorisations for r in solves) > 0
    assert str(e.value).endswith("The problem holds the state of the last converged load, 0.")
    assert "written" not in str(e.value)  # the library writes nothing, and says nothing of it
    assert written == []  # nothing converged, nothing reported as converged
    assert np.all(case.w.x.array == 0.0)  # back at the last converged state
    assert np.allclose(case.moment.value, 0.0)  # and at its load


def test_newton_converges_quadratically_on_tip_force():
    """Consistent tangent: the order of convergence estimated from the last three residuals above
    the round-off floor is about 2 (an inconsistent tangent gives 1)."""
    case = cantilever(16)
    case.force.value = [0.0, 0.3 * S["EI"], 0.0]
    result = case.solver.solve()
    assert result.converged
    r = np.array([x for x in result.residuals if x > 1e-6])
    order = np.log(r[-1] / r[-2]) / np.log(r[-2] / r[-3])
    assert order > 1.8, result.residuals


class MisjudgedSpring(AxialSpring):
    """``AxialSpring`` whose tangent claims ``scale`` × its stiffness: Newton then converges only
    linearly, removing a fraction 1/scale of the spring's error per iteration."""

    def __init__(self, pairs, k, scale):
        super().__init__(pairs, k)
        self.scale = scale

    def evaluate(self, w, jacobian):
        f, K = super().evaluate(w, jacobian)
        return f, self.scale * K


def spring_to_ground(scale, options):
    """A bar tip pulled against a stiff spring to its clamped twin; the spring's tangent is off
    by ``scale``. Returns the solver."""
    mesh, V, roots, tips = two_bars()
    w = fem.Function(V)
    beam = ReissnerBeam(w, CircularSection(0.01, 210e9, 0.3))
    bc = fem.dirichletbc(np.zeros(6), roots, V)
    terms = [
        MisjudgedSpring([[tips[0], roots[1]]], 1e10, scale),
        NodalLoad([tips[0]], [[1e3, 0, 0, 0, 0, 0]], 1.0),
    ]
    return NonlinearProblem(beam.residual(), w, [bc], terms=terms, options=options)


def test_stall_test_stops_a_stagnating_solve_early():
    """A tangent 10× too stiff makes the residual fall by only 0.9 per iteration: without the
    stall test the solve runs to max_it; with it, it stops at ``stall_after`` iterations as
    DIVERGED_STALLED, with the same residuals up to there."""
    off = spring_to_ground(10.0, NewtonOptions(max_it=20, stall_after=0)).solve()
    on = spring_to_ground(10.0, NewtonOptions(max_it=20, stall_after=4)).solve()
    assert not off.converged and off.iterations == 20 and off.reason == "DIVERGED_MAX_IT"
    assert not on.converged and on.iterations == 4 and on.reason == "DIVERGED_STALLED"
    assert on.residuals == off.residuals[:5]
    assert on.residuals[4] > 0.5 * on.residuals[2]


class SaturatingSpring:
    """A force F_s arctan((u_x − c)/ε) (N) on one node's u_x, with its exact tangent: it
    saturates at ±F_s π/2 within a few ε of c, as a slipping pair's friction force does with
    its direction. Newton on such a force, from far off, jumps to and fro about c."""

    def __init__(self, node, F_s, eps, c):
        self.stencils = np.array([[node]], dtype=np.int32)
        self.F_s, self.eps, self.c = F_s, eps, c

    def evaluate(self, w, jacobian):
        x = (w[self.stencils[0, 0], 0] - self.c) / self.eps
        f, K = np.zeros((1, 6)), np.zeros((1, 6, 6))
        f[0, 0] = self.F_s * np.arctan(x)
        K[0, 0, 0] = self.F_s / self.eps / (1 + x * x)
        return f, K

    def commit(self):
        pass

    def rollback(self):
        pass


#: centre c of the saturating spring (m): the tip's exact solution u_x
SPRING_CENTRE = 10e-6


def saturating_tip(options):
    """A bar tip held by a saturating spring (1 kN, ε = 1 µm) centred at c = 10 µm and pulled
    by EA/L × c, so that u_x = c exactly at the solution. Returns the solver and the tip's
    block."""
    mesh, V, roots, tips = two_bars()
    w = fem.Function(V)
    beam = ReissnerBeam(w, CircularSection(0.01, 210e9, 0.3))
    bc = fem.dirichletbc(np.zeros(6), roots, V)
    c = SPRING_CENTRE
    terms = [
        SaturatingSpring(tips[0], 1e3, 1e-6, c),
        NodalLoad([tips[0]], [[S["EA"] * c, 0, 0, 0, 0, 0]], 1.0),
    ]
    return NonlinearProblem(beam.residual(), w, [bc], terms=terms, options=options), tips[0]


def test_line_search_breaks_the_two_cycle_of_full_newton_steps():
    """Full Newton steps (``basic``) on the saturating spring fall into a 2-cycle about the
    solution (u ≈ c ± 94 µm, with an exact tangent) until the stall test stops them; from an
    iterate of that cycle they stay in it. A line search, the critical-point one (``cp``,
    strand's default for its runs) or backtracking (``bt``, ``l2``), converges from there to
    the exact solution u = c in at most 4 iterations. (From much farther off, cp's one secant
    step can stop short: the stall test and the step cut are there for that.)"""
    options = NewtonOptions(max_it=12, atol=1e-6, rtol=1e-14, stall_after=4)
    c = SPRING_CENTRE
    solver, tip = saturating_tip(replace(options, linesearch="basic"))
    full = solver.solve()
    r = full.residuals
    assert not full.converged and full.reason == "DIVERGED_STALLED"
    assert r[-1] > 0.9 * r[-3] > 1e3  # no progress in two iterations: it cycles
    cycle = solver.w.x.array.copy()  # the last iterate: a point of the cycle
    assert abs(cycle.reshape(-1, 6)[tip, 0] - c) > 80e-6

    def from_cycle(search):
        solver, tip = saturating_tip(replace(options, linesearch=search))
        solver.w.x.array[:] = cycle
        return solver, tip, solver.solve()

    assert not from_cycle("basic")[2].converged
    for search in ("cp", "bt", "l2"):
        solver, tip, result = from_cycle(search)
        assert result.converged and result.iterations <= 4, (search, result.residuals)
        assert solver.w.x.array.reshape(-1, 6)[tip, 0] == pytest.approx(c, rel=1e-9)


def test_stall_test_leaves_converging_solves_alone():
    """Exact (scale 1) and halving (scale 2: the residual falls by 1/2 per iteration, 1/4 per
    two) solves take the same iterations and residuals with and without the stall test."""
    for scale in (1.0, 2.0):
        runs = [
            spring_to_ground(scale, NewtonOptions(max_it=60, stall_after=n)).solve() for n in (0, 4)
        ]
        assert all(r.converged for r in runs)
        assert runs[0].residuals == runs[1].residuals
    assert runs[0].iterations > 4  # the halving solve does pass through the stall test


def test_balance_test_ends_a_solve_once_every_node_is_in_balance():
    """With ``force_tol`` (N) and ``moment_tol`` (N m), a solve ends at the first iterate whose
    largest nodal force and moment residuals are within them, before the 2-norm test would; a
    force tolerance out of reach leaves the solve as it was."""
    tight = NewtonOptions(atol=1e-9, rtol=1e-14, max_it=60)
    exact = spring_to_ground(2.0, tight).solve()
    solver = spring_to_ground(2.0, replace(tight, force_tol=1e-3, moment_tol=1e-3))
    balanced = solver.solve()
    worst = np.abs(solver.b.array_r).reshape(-1, 6).max(axis=0)
    assert balanced.converged and balanced.iterations < exact.iterations
    assert worst[:3].max() <= 1e-3 and worst[3:].max() <= 1e-3
    assert balanced.residuals == exact.residuals[: balanced.iterations + 1]
    unreachable = spring_to_ground(2.0, replace(tight, force_tol=1e-300, moment_tol=1e-3))
    assert unreachable.solve().residuals == exact.residuals


def test_nodal_load_validates_shapes():
    with pytest.raises(ValueError, match="one 6-vector"):
        NodalLoad([0, 1], [[1, 0, 0, 0, 0, 0]])


def test_secant_predictor_saves_iterations_and_reaches_the_same_state():
    """Extrapolating the last converged increment starts each step closer to its solution."""
    results = {}
    for extrapolate in (False, True):
        case = cantilever(16, options=NewtonOptions(atol=1e-9, rtol=1e-14))
        stepper = LoadStepper(case.solver, 0.1, 1e-3, growth=1.0, extrapolate=extrapolate)
        force = case.force

        def set_load(lam, force=force):
            force.value = [0, lam * 0.5 * S["EI"], 0]

        stepper.ramp(set_load, 0.0, 1.0)
        results[extrapolate] = (sum(r.iterations for r in stepper.history), case.tip_u.copy())
    assert results[True][0] < results[False][0]
    assert np.allclose(results[True][1], results[False][1], rtol=1e-8, atol=1e-12)


def test_a_failed_factorisation_does_not_poison_the_next_solve():
    """A tangent with a NaN makes MUMPS fail (DIVERGED_LINEAR_SOLVE); once the state is rolled
    back, the next solve from a good state must factor afresh and converge (PETSc keeps a failed
    PC failed: without a reset, every later attempt failed at iteration 0)."""
    mesh, V, roots, tips = two_bars()
    w = fem.Function(V)
    beam = ReissnerBeam(w, CircularSection(0.01, 210e9, 0.3))
    bc = fem.dirichletbc(np.zeros(6), roots, V)
    spring = AxialSpring([tips], 3.0e8)
    evaluate = spring.evaluate

    def poisoned(w, jacobian):
        f, K = evaluate(w, jacobian)
        return f, K * np.nan

    load = NodalLoad([tips[0]], [[5e3, 0, 0, 0, 0, 0]], factor=1.0)
    solver = NonlinearProblem(beam.residual(), w, [bc], terms=[spring, load])
    spring.evaluate = poisoned
    failed = solver.solve()
    assert not failed.converged and failed.reason == "DIVERGED_LINEAR_SOLVE"
    solver.rollback()
    spring.evaluate = evaluate
    result = solver.solve()
    assert result.converged and result.iterations <= 2


def test_each_problem_has_its_own_petsc_options_and_removes_them():
    """Two problems in one process: the second does not inherit the first one's extra options,
    and ``destroy`` leaves no option of a problem in PETSc's database (none reported unused)."""
    from petsc4py import PETSc

    opts = PETSc.Options()
    first = cantilever(4, options=NewtonOptions(petsc={"mat_mumps_icntl_14": 80})).solver
    second = cantilever(4).solver
    prefixes = (first.solver.getOptionsPrefix(), second.solver.getOptionsPrefix())
    assert prefixes[0] != prefixes[1]
    assert opts.getInt(f"{prefixes[0]}mat_mumps_icntl_14") == 80
    assert not opts.hasName(f"{prefixes[1]}mat_mumps_icntl_14")
    assert second.solver.getKSP().getPC().getType() == "lu"
    first.destroy()
    second.destroy()
    left = [k for k in opts.getAll() if k.startswith(prefixes)]
    assert left == []


def test_the_problem_is_dolfinx_nonlinear_problem_with_pair_couplings():
    """dolfinx's conventions hold: ``petsc_options_prefix`` names the SNES (``solver``) and, after
    it, A, b and x; ``petsc_options`` override those of ``NewtonOptions`` and reach MUMPS at its
    first factorisation; the Jacobian ``A`` holds the spring's coupling of the two bar tips,
    −k (N/m), outside the forms' sparsity pattern; an empty prefix is refused, as by dolfinx."""
    mesh, V, roots, tips = two_bars()
    w = fem.Function(V)
    beam = ReissnerBeam(w, CircularSection(0.01, 210e9, 0.3))
    bc = fem.dirichletbc(np.zeros(6), roots, V)
    k = 3.0e8
    terms = [AxialSpring([tips], k), NodalLoad([tips[0]], [[5e3, 0, 0, 0, 0, 0]], factor=1.0)]
    petsc_options = {"mat_mumps_icntl_14": 77, "snes_max_it": 3}
    problem = NonlinearProblem(
        beam.residual(),
        w,
        [bc],
        terms=terms,
        options=NewtonOptions(max_it=25),
        petsc_options_prefix="bars_",
        petsc_options=petsc_options,
    )
    assert isinstance(problem, dolfinx.fem.petsc.NonlinearProblem) and problem.u is w
    assert problem.solver.getOptionsPrefix() == "bars_"
    assert [o.getOptionsPrefix() for o in (problem.A, problem.b, problem.x)] == [
        "bars_A_",
        "bars_b_",
        "bars_x_",
    ]
    assert problem.solver.getTolerances()[3] == 3  # max_it, over NewtonOptions' 25
    assert problem.solve().converged
    assert problem.solver.getKSP().getPC().getFactorMatrix().getMumpsIcntl(14) == 77
    rows = problem.A.getLGMap()[0].apply(6 * np.asarray(tips))
    assert problem.A.getValue(rows[0], rows[1]) == pytest.approx(-k)
    problem.destroy()
    with pytest.raises(ValueError, match="prefix cannot be empty"):
        NonlinearProblem(beam.residual(), w, [bc], petsc_options_prefix="")


def test_relaxation_springs_hold_the_free_dofs_and_carry_the_residual():
    """``relax(c, ℓ)``: every free dof held to its value by c (translations) or c ℓ²
    (rotations). Two bars clamped at x = 0, an axial force F and a moment on a tip: with the
    springs the bar's axial equations are (K + c I) u = F (a chain: the tip moves less than
    F L/EA), the clamped dofs stay at 0, and the springs' force D (u − 0) equals the residual
    of the problem without them at that state; released, one more solve gives the state of
    the problem never held."""
    mesh, V, roots, tips = two_bars()
    w = fem.Function(V)
    beam = ReissnerBeam(w, CircularSection(0.01, 210e9, 0.3))
    bc = fem.dirichletbc(np.zeros(6), roots, V)
    F, M = 5.0e3, 2.0
    load = NodalLoad([tips[0]], [[F, 0, 0, 0, 0, M]], factor=1.0)
    solver = NonlinearProblem(beam.residual(), w, [bc], terms=[load])
    c, ell = 1.0e8, 0.01
    solver.relax(c, ell)
    assert solver.solve().converged
    wn = w.x.array.reshape(-1, 6)
    assert np.all(wn[roots] == 0.0)
    tip = wn[tips[0], 0]
    assert 0 < tip < F * 1.0 / S["EA"]
    # the springs' force is the residual of the problem without them, at the same state
    free = np.ones(len(wn), bool)
    free[roots] = False
    plain = solver.unconstrained_residual()[free[: len(solver.unconstrained_residual())]]
    held = np.concatenate([c * wn[free, :3].ravel(), c * ell**2 * wn[free, 3:].ravel()])
    assert np.linalg.norm(plain) == pytest.approx(np.linalg.norm(held), rel=1e-6)
    assert solver.relaxation_force() == pytest.approx(np.linalg.norm(held), rel=1e-6)
    solver.relax(None)
    assert solver.relaxation_force() == 0.0
    assert solver.solve().converged
    w_ref = fem.Function(V)  # the problem never held
    beam_ref = ReissnerBeam(w_ref, CircularSection(0.01, 210e9, 0.3))
    reference = NonlinearProblem(beam_ref.residual(), w_ref, [bc], terms=[load])
    assert reference.solve().converged
    np.testing.assert_allclose(w.x.array, w_ref.x.array, rtol=0, atol=1e-12)
    assert wn[tips[0], 0] == pytest.approx(F * 1.0 / S["EA"], rel=1e-2)  # bent: a little less
    reference.destroy()
    with pytest.raises(ValueError, match="must be > 0"):
        solver.relax(-1.0)
    solver.destroy()
