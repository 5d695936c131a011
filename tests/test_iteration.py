"""Cheaper iterations than Newton's (``[steps] iteration``): GMRES on each Jacobian
preconditioned by an earlier LU (``reuse_lu``) and L-BFGS on each solve's first LU (``lbfgs``).
On the quick 1+6 strand, tensioned, the same lateral step from the same state: each reaches
Newton's solution; ``reuse_lu`` factorises fewer times than it iterates, over several steps too;
and a solve the cheaper iteration cannot finish is solved again by Newton from its start."""

from __future__ import annotations

import io
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from strand.app.case import CaseError, load_case
from strand.app.run import build_problem
from strand.solver import LoadStepper, NewtonOptions
from strand_cases import SEVEN_WIRE

QUIET = ["output.plots=false", "output.fields=false", "fatigue.outputs=false"]
#: the residual tolerance (N): tight, so that solutions compare far below the step's own size
TIGHT = ["steps.tolerance=1e-6", "steps.balance=0"]


def tensioned(tmp_path: Path, iteration: str, **options):
    """The quick 1+6 pulled to its 10 kN by Newton, then set to ``iteration`` (with these
    ``NewtonOptions``) for what follows: the problem, with the tension committed."""
    tmp_path.mkdir(exist_ok=True)
    path = tmp_path / "seven.toml"
    path.write_text(SEVEN_WIRE)
    case = load_case(path, [*QUIET, *TIGHT, f'steps.iteration="{iteration}"'])
    problem, programme = build_problem(case, io.StringIO())
    s = problem.solver
    tension = programme.stages[0]
    with s._newton():  # every strategy starts from one and the same tensioned state
        LoadStepper(s, tension.first_step, tension.min_step).ramp(
            lambda v: problem.setup.set("tension", v), 0.0, tension.target
        )
    if options:
        s.options.__dict__.update(options)
        s.solver.setTolerances(max_it=s.options.max_it)
        s.solver.getKSP().setTolerances(max_it=s.options.krylov_max)
    return problem


def lateral_step(problem, load: float):
    """One solve of the saddle load ``load`` (N) from the committed state; its result and
    the unknowns it converged to."""
    problem.setup.set("lateral", load)
    result = problem.solver.solve()
    return result, problem.solver.w.x.array.copy()


@pytest.fixture(scope="module")
def newton_step(tmp_path_factory):
    problem = tensioned(tmp_path_factory.mktemp("newton"), "newton")
    result, w = lateral_step(problem, 150.0)
    assert result.converged and result.factorisations == result.iterations
    problem.solver.destroy()
    return w


@pytest.mark.parametrize("iteration", ["reuse_lu", "lbfgs"])
def test_a_cheaper_iteration_reaches_newtons_solution(tmp_path, newton_step, iteration):
    """From the same tensioned state, the saddle load's first 150 N: the converged unknowns
    agree with Newton's to 1e-6 of the largest (the residual tolerance, 1 µN, on stiffnesses
    of ~1e6 N/m bounds the difference by ~1e-12 m against ~1e-4 m of motion), with fewer LU
    factorisations than iterations. L-BFGS is given 100 iterations (Newton takes 7, L-BFGS
    87 with its one LU: measured when this test was written)."""
    options = {"max_it": 100} if iteration == "lbfgs" else {}
    problem = tensioned(tmp_path, iteration, **options)
    result, w = lateral_step(problem, 150.0)
    assert result.converged and not result.fallback, result
    assert result.factorisations < result.iterations
    scale = np.abs(newton_step).max()
    assert np.abs(w - newton_step).max() <= 1e-6 * scale
    problem.solver.destroy()


def test_reuse_lu_keeps_one_lu_over_iterations_and_steps(tmp_path):
    """Over the saddle load's steps to 300 N, GMRES on the kept LU needs it refactorised once
    every several iterations, and the counts the solves report are the LUs MUMPS made."""
    from petsc4py import PETSc

    PETSc.Log.begin()  # MUMPS's factorisations counted by PETSc's log
    problem = tensioned(tmp_path, "reuse_lu")
    event = PETSc.Log.Event("MatLUFactorNum")
    before = event.getPerfInfo()["count"]
    records = LoadStepper(problem.solver, 50.0, 1.0).ramp(
        lambda v: problem.setup.set("lateral", v), 0.0, 300.0
    )
    lus = sum(r.factorisations for r in records)
    its = sum(r.iterations + r.failed_iterations for r in records)
    assert event.getPerfInfo()["count"] - before == lus
    assert lus <= its / 2, (lus, its)
    problem.solver.destroy()


@pytest.mark.parametrize("lu_reuse", [1, 2])
def test_one_lu_serves_at_most_lu_reuse_jacobians(tmp_path, lu_reuse):
    """With ``lu_reuse`` = 1 every Jacobian is factorised (Newton's count); with 2, at least
    every other one."""
    problem = tensioned(tmp_path, "reuse_lu", lu_reuse=lu_reuse)
    calls = problem.solver.timings["jacobian_calls"]
    result, _ = lateral_step(problem, 150.0)
    jacobians = problem.solver.timings["jacobian_calls"] - calls
    assert result.converged and jacobians >= 3
    if lu_reuse == 1:
        assert result.factorisations == jacobians
    else:
        assert jacobians // 2 <= result.factorisations < jacobians
    problem.solver.destroy()


@pytest.mark.parametrize("iteration", ["reuse_lu", "lbfgs"])
def test_a_solve_the_cheaper_iteration_cannot_finish_falls_back_to_newton(
    tmp_path, monkeypatch, iteration
):
    """The whole 300 N in one solve, 12 iterations allowed: Newton's own solve from that
    start converges (it is checked first); the cheaper iteration stalls or runs out of
    iterations (L-BFGS; GMRES given one iteration on the tensioned state's LU, never renewed:
    a chord iteration), and the solve is done again by Newton from the same start:
    converged, flagged, its iterations and LUs counted with the failed ones', and at Newton's
    solution. (Left to itself, ``reuse_lu`` renews the LU whenever GMRES fails, and this
    step converges without falling back: 9 iterations, 5 LUs.)"""
    newton = tensioned(tmp_path / "newton", "newton")
    reference, w_newton = lateral_step(newton, 300.0)
    assert reference.converged
    newton.solver.destroy()
    options = {"krylov_max": 1} if iteration == "reuse_lu" else {}
    problem = tensioned(tmp_path, iteration, **options)
    s = problem.solver
    if iteration == "reuse_lu":  # the tensioned state's LU, renewed only by the fall-back
        monkeypatch.setattr(s, "_renew_lu", lambda snes: s._newton_only)
    result, w = lateral_step(problem, 300.0)
    assert result.converged and result.fallback, result
    # Newton's solve again after the failed one's iterations and its LUs (the chord made none,
    # L-BFGS one), from the very same start: the same residuals to round-off (reuse_lu's
    # Newton solves by GMRES on the fresh LU, not by the LU alone)
    assert result.factorisations == reference.factorisations + (iteration == "lbfgs")
    r0 = reference.residuals[0]
    assert np.allclose(result.residuals, reference.residuals, rtol=1e-8, atol=1e-10 * r0)
    assert np.abs(w - w_newton).max() <= 1e-6 * np.abs(w_newton).max()
    if iteration == "lbfgs":
        assert s.solver.getType() == "qn"  # L-BFGS again for the next solve
    s.destroy()


def test_an_unknown_iteration_is_refused_before_any_computing(tmp_path):
    path = tmp_path / "seven.toml"
    path.write_text(SEVEN_WIRE)
    with pytest.raises(CaseError, match=r"\[steps\] iteration = 'chord'"):
        load_case(path, ['steps.iteration="chord"'])
    with pytest.raises(ValueError, match="iteration = 'chord'"):
        replace(NewtonOptions(), iteration="chord")
