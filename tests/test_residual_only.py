"""Residual-only evaluations of the pair terms: the residual callback evaluates the
contact residual without its tangent, the Jacobian callback adds the tangent; the residual and
every Newton iterate are those of full evaluations, bit for bit, on the quick 1+6 strand with
prescribed end motions (uniform bending) and with fixed supports (the saddle test)."""

from __future__ import annotations

import io
from collections import Counter
from pathlib import Path

import dolfinx.fem.petsc as fem_petsc
import numpy as np
import pytest

from strand.app.case import load_case
from strand.app.run import build_problem
from strand.model.programme import run_programme
from strand.solver import LoadStepper
from strand_cases import SEVEN_WIRE

QUIET = ["output.plots=false", "output.fields=false", "fatigue.outputs=false"]
#: uniform bending: every dof of the wire ends at z = 0 and the rotations at z = L prescribed
BENDING = [
    'load.kind="bending"',
    "load.zone=0.04",
    "load.curvature=0.5",
    "steps.curvature=0.1",
    "steps.curvature_max=0.2",
]


def seven_wire(tmp_path: Path, settings: list[str]):
    path = tmp_path / "seven.toml"
    path.write_text(SEVEN_WIRE)
    return build_problem(load_case(path, [*QUIET, *settings]), io.StringIO())


def count_contact_evaluations(problem) -> Counter:
    """Wrap the contact groups' ``evaluate`` to count its calls with (True) and without (False)
    the tangent."""
    counts: Counter = Counter()
    for group in problem.contact:
        evaluate = group.evaluate

        def counted(w, jacobian=True, evaluate=evaluate):
            counts[bool(jacobian)] += 1
            return evaluate(w, jacobian)

        group.evaluate = counted
    return counts


def always_with_tangent(problem) -> None:
    """Every pair-term evaluation with its tangent: the behaviour without residual-only
    evaluations (the Jacobian then finds its tangent cached)."""
    pairs = problem.solver._pairs
    evaluate = pairs.evaluate
    pairs.evaluate = lambda wl, timings, tangent=True: evaluate(wl, timings, True)


def assembled_residual(problem) -> np.ndarray:
    """The residual vector the SNES callback assembles at the current unknowns."""
    s = problem.solver
    s._pairs.forget()
    fem_petsc.assign(s.w, s.x)
    b = s.b.duplicate()
    s._residual(s.solver, s.x, b)
    out = b.array_r.copy()
    b.destroy()
    return out


def test_the_residual_alone_is_the_full_evaluations_residual(tmp_path):
    """In uniform bending at a Newton iterate where crossings stick and slip, the residual-only
    evaluation gives the residual of the full one bit for bit, term set by term set and
    assembled: with the prescribed end motions at their values (no lifting: no tangent is
    computed) and with them moved on (the sets whose stencils touch them are evaluated with
    their tangent, for the lifting K_fb (g − w_b)). The Jacobian then adds the missing
    tangents with one more evaluation of each contact group."""
    problem, programme = seven_wire(tmp_path, BENDING)
    setup, solver = problem.setup, problem.solver
    tension = programme.stages[0]
    LoadStepper(solver, tension.first_step, tension.min_step).ramp(
        lambda v: setup.set("tension", v), 0.0, tension.target
    )
    LoadStepper(solver, 0.1, 0.01).ramp(lambda v: setup.set("curvature", v), 0.0, 0.2)
    iterates = []
    solver.monitor = lambda its, norm: iterates.append(solver.w.x.array.copy())
    setup.set("curvature", 0.3)
    assert solver.solve().converged
    solver.w.x.array[:] = iterates[1]  # an iterate: slips since the last converged step
    pairs, counts = solver._pairs, count_contact_evaluations(problem)
    touching = [len(layout[1]) for layout in pairs._term_layouts()]
    assert touching[0] > 0  # crossings at the wire ends, on prescribed dofs

    for moved in (False, True):
        if moved:
            setup.set("curvature", 0.35)  # the prescribed dofs' values move on: lifting needed
        lift = pairs._prescribed_increment(solver.w.x.array)
        assert (np.abs(lift).max() > 0) == moved
        pairs.forget()
        full = pairs.evaluate(solver.w.x.array, {"terms": 0.0}, tangent=True)
        force, slipping = problem.contact[0].state.force, problem.contact[0].state.slipping
        assert 0 < np.count_nonzero(slipping) < np.count_nonzero(force > 0)  # stick and slip
        pairs.forget()
        counts.clear()
        alone = pairs.evaluate(solver.w.x.array, {"terms": 0.0}, tangent=False)
        expected = Counter({moved: len(problem.contact)})  # a tangent only for the lifting
        assert counts == expected and alone[0].tangent == moved
        for a, b in zip(full, alone, strict=True):
            assert np.array_equal(a.f, b.f) and np.array_equal(a.f_rows, b.f_rows)
        again = pairs.evaluate(solver.w.x.array, {"terms": 0.0}, tangent=True)
        expected[True] += 0 if moved else len(problem.contact)
        assert counts == expected
        for a, b in zip(full, again, strict=True):
            assert (a.K is None and b.K is None) or np.array_equal(a.K, b.K)
        residual = assembled_residual(problem)
        always_with_tangent(problem)
        assert np.array_equal(assembled_residual(problem), residual)
        del pairs.evaluate  # residual-only evaluations again


def run(tmp_path: Path, settings: list[str], residual_only: bool):
    """The quick 1+6's whole programme: every Newton iterate, the steps' residual histories,
    the contact groups' evaluations (``count_contact_evaluations``) and the solver's
    ``timings``."""
    problem, programme = seven_wire(tmp_path, settings)
    assert problem.solver.options.linesearch == "cp"
    if not residual_only:
        always_with_tangent(problem)
    counts = count_contact_evaluations(problem)
    iterates, records = [], []
    s = problem.solver
    s.monitor = lambda its, norm: iterates.append(s.w.x.array.copy())
    run_programme(problem, programme, lambda stage, rec, position: records.append(rec))
    s.destroy()
    return iterates, [r.residuals for r in records], counts, dict(s.timings), len(problem.contact)


@pytest.mark.parametrize("settings", [[], BENDING], ids=["saddle", "uniform bending"])
def test_a_run_takes_the_same_iterates_with_fewer_contact_tangents(tmp_path, settings):
    """The quick 1+6's whole programme (the cp line search: a trial point, then the point it
    settles on, per iteration) with residual-only evaluations and with every evaluation full:
    the same Newton iterates and residual histories, bit for bit, and the same callbacks. With
    fixed supports the contact tangent is computed once per Jacobian, exactly; with prescribed
    end motions also where the lifting needs it, still fewer times than with full evaluations
    (the counts are printed)."""
    it_a, res_a, counts_a, tm_a, groups = run(tmp_path, settings, residual_only=True)
    it_b, res_b, counts_b, tm_b, _ = run(tmp_path, settings, residual_only=False)
    assert len(it_a) == len(it_b)
    assert all(np.array_equal(a, b) for a, b in zip(it_a, it_b, strict=True))
    assert res_a == res_b
    for key in ("residual_calls", "jacobian_calls"):
        assert tm_a[key] == tm_b[key] > 0
    print(
        f"contact tangents: {counts_b[True]} with full evaluations, {counts_a[True]} with "
        f"residual-only ones (+{counts_a[False]} residuals alone); "
        f"{tm_a['jacobian_calls']} Jacobians, {tm_a['residual_calls']} residuals"
    )
    assert counts_b[False] == 0
    if not settings:
        assert counts_a[True] == tm_a["jacobian_calls"] * groups
    else:
        assert tm_a["jacobian_calls"] * groups <= counts_a[True] < counts_b[True]
    assert tm_a["tangent_terms"] < tm_b["tangent_terms"]
