"""Load steps sized by an error estimate (``ErrorControl``), and the retry of a failed attempt
with the predictor switched: on a stand-in solver whose solution path u(λ) is known,
so that the secant predictor's miss is computed by hand; then on the quick 1+6 strand."""

from __future__ import annotations

import io
from dataclasses import replace
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest

from strand.app.case import load_case
from strand.app.run import build_problem, run_case
from strand.solver import ErrorControl, LoadStepper, NewtonResult, RampState
from strand_cases import SEVEN_WIRE


class PathSolver:
    """What ``LoadStepper`` uses of a solver, on one node whose converged unknowns are
    ``path(λ)`` (6,): x-translation u(λ), y-translation −λ/2 and large nonlinear rotations
    (which the error estimate must leave out). ``fails(λ, predicted)`` says which attempts
    fail (``predicted``: started from the secant predictor); every attempt is logged."""

    def __init__(self, u, fails=lambda load, predicted: False):
        self.u = u
        self.fails = fails
        self.load = 0.0
        self.w = SimpleNamespace(x=SimpleNamespace(array=self.path(0.0)))
        self._saved = self.w.x.array.copy()
        self.attempts: list[tuple[float, bool]] = []

    def path(self, lam: float) -> np.ndarray:
        return np.array([self.u(lam), -0.5 * lam, 0.0, 10 * lam**2, 30 * lam**3, 0.0])

    def set_load(self, lam: float) -> None:
        self.load = lam

    def solve(self) -> NewtonResult:
        predicted = not np.array_equal(self.w.x.array, self._saved)
        self.attempts.append((self.load, predicted))
        if self.fails(self.load, predicted):
            self.w.x.array[:] = np.nan
            return NewtonResult(False, 3, "DIVERGED_MAX_IT", [1.0, 2.0, 3.0, 4.0], 0.0)
        self.w.x.array[:] = self.path(self.load)
        return NewtonResult(True, 2, "CONVERGED_FNORM_ABS", [1.0, 1e-3, 1e-9], 0.0)

    def commit(self) -> None:
        self._saved = self.w.x.array.copy()

    def rollback(self) -> None:
        self.w.x.array[:] = self._saved

    def stop_requested(self) -> bool:
        return False


def ramp(solver: PathSolver, start: float, end: float, **kwargs):
    """The records of one ramp of ``solver`` from ``start`` to ``end`` (LoadStepper ``kwargs``)."""
    solver.set_load(start)
    solver.w.x.array[:] = solver.path(start)
    solver.commit()
    stepper = LoadStepper(solver, **kwargs)
    return stepper, stepper.ramp(solver.set_load, start, end)


def increments(records, start: float) -> np.ndarray:
    return np.diff([start, *(r.load for r in records)])


@pytest.mark.parametrize("extrapolate", [False, True])
def test_the_error_estimate_is_the_secant_predictors_miss(extrapolate):
    """On u = λ³ the secant predictor u_n + (h/h_p)(u_n − u_{n−1}) misses u(λ_n + h) by exactly
    h (h + h_p)(3λ_n + h − h_p), whatever the steps (here growing 1.5× each), and whether or
    not the solve starts from it; on u = λ² by h (h + h_p), 2h² for equal steps."""
    for u, miss, growth in [
        (lambda x: x**3, lambda lam, h, hp: h * (h + hp) * (3 * lam + h - hp), 1.5),
        (lambda x: x**2, lambda lam, h, hp: h * (h + hp), 1.5),
        (lambda x: x**2, lambda lam, h, hp: 2 * h**2, 1.0),
    ]:
        _, records = ramp(
            PathSolver(u),
            1.0,
            2.0,
            first_step=0.1,
            min_step=1e-3,
            growth=growth,
            extrapolate=extrapolate,
        )
        loads = np.array([1.0, *(r.load for r in records)])
        assert len(records) >= 5 and np.isnan(records[0].error)  # a ramp's first: no predictor
        for n in range(1, len(records)):
            lam, h, hp = loads[n], loads[n + 1] - loads[n], loads[n] - loads[n - 1]
            assert records[n].error == pytest.approx(miss(lam, h, hp), rel=1e-9)


def test_a_settling_ramp_predicts_from_its_second_step_on():
    """``settles``: the ramp's first step (a strand's first tension step, in which its pairs
    close) is no guide: the second attempt starts from the converged state and has no error
    estimate; the third starts from the secant predictor of the second. Without it, the second
    is predicted from the first."""
    for settles, predicted in [
        (True, [False, False, True, True]),
        (False, [False, True, True, True]),
    ]:
        solver = PathSolver(lambda x: x**2)
        _, records = ramp(
            solver,
            0.0,
            1.0,
            first_step=0.1,
            min_step=1e-3,
            growth=1.0,
            extrapolate=True,
            settles=settles,
        )
        assert [p for _, p in solver.attempts[:4]] == predicted
        assert np.isnan(records[0].error)
        assert np.isnan(records[1].error) == settles
        assert not np.isnan(records[2].error)


def test_on_a_linear_path_the_steps_grow_to_the_largest_and_end_exactly():
    """No miss on u = 2λ: after the first step (the growth rule: ×1.5) every step doubles
    (grow_max) up to max_step, and the ramp ends on its end."""
    _, records = ramp(
        PathSolver(lambda x: 2 * x),
        0.0,
        1.0,
        first_step=0.01,
        min_step=1e-4,
        max_step=0.1,
        controller=ErrorControl(),
    )
    h = increments(records, 0.0)
    assert h[:6] == pytest.approx([0.01, 0.015, 0.03, 0.06, 0.1, 0.1], rel=1e-12)
    assert np.all(h[4:-1] == pytest.approx(0.1, rel=1e-12)) and h[-1] <= 0.1
    assert records[-1].load == pytest.approx(1.0, abs=1e-12)
    assert all(r.error < 1e-15 for r in records[1:])


@pytest.mark.parametrize("c", [1.0, 100.0])
def test_the_steps_settle_where_the_miss_is_the_tolerance(c):
    """On u = c λ² the miss of equal steps h is 2c h², so the controller settles at
    h* = safety √(tol / 2c), with a miss safety² tol: ten times smaller steps for 100 times
    the curvature."""
    control = ErrorControl(tol=1e-3, safety=0.9)
    _, records = ramp(
        PathSolver(lambda x: c * x**2), 0.0, 1.0, first_step=1e-3, min_step=1e-6, controller=control
    )
    h = increments(records, 0.0)
    late = slice(len(h) // 2, -1)  # settled, before the last (truncated) step
    assert h[late] == pytest.approx(0.9 * np.sqrt(1e-3 / (2 * c)), rel=0.02)
    assert np.array([r.error for r in records[late]]) == pytest.approx(0.81e-3, rel=0.05)
    assert records[-1].load == pytest.approx(1.0, abs=1e-12)


def test_the_steps_shrink_along_a_ramp_whose_curvature_grows():
    """u = exp(3λ): u'' grows e^{1.5}-fold from λ = 0.5 to 1, so the settled steps, ∝ 1/√u'',
    shrink by e^{-0.75} = 0.47 over that half."""
    _, records = ramp(
        PathSolver(lambda x: np.exp(3 * x)),
        0.0,
        1.0,
        first_step=1e-3,
        min_step=1e-6,
        controller=ErrorControl(tol=1e-4),
    )
    h = increments(records, 0.0)
    loads = np.array([r.load for r in records])
    middle = h[np.argmin(np.abs(loads - 0.5))]
    near_end = h[np.argmin(np.abs(loads - 0.95))]
    assert near_end / middle == pytest.approx(np.exp(-0.75 * 0.9), rel=0.05)


def test_a_step_over_a_kink_is_rejected_and_taken_smaller():
    """u = 10⟨λ − 0.5⟩: the step across the kink misses by 10 × its part beyond 0.5. With
    reject_factor = 4 that step is rejected (its iterations charged to the step that follows)
    and retried smaller, so that every accepted step's miss is within 4 tol; without
    rejection the step is kept, with its miss."""
    solver = PathSolver(lambda x: 10 * max(x - 0.5, 0.0))
    control = ErrorControl(tol=1e-3, reject_factor=4.0)
    _, records = ramp(
        solver, 0.0, 1.0, first_step=0.07, min_step=1e-4, growth=1.0, controller=control
    )
    assert all(r.error <= 4e-3 for r in records[1:])
    rejected = [r for r in records if r.rejections]
    assert rejected and all(r.failed_iterations == 2 * r.rejections for r in rejected)
    assert len(solver.attempts) == len(records) + sum(r.rejections for r in records)
    assert records[-1].load == pytest.approx(1.0, abs=1e-12)
    _, kept = ramp(
        PathSolver(solver.u),
        0.0,
        1.0,
        first_step=0.07,
        min_step=1e-4,
        growth=1.0,
        controller=replace(control, reject_factor=np.inf),
    )
    assert max(r.error for r in kept[1:]) > 4e-3 and not any(r.rejections for r in kept)


def test_a_failed_attempt_is_retried_with_the_predictor_switched_then_halved():
    """With ``retry``, a failed attempt is tried again at the same increment from the last
    converged state, without the predictor if it was on (with it if off); if that fails too,
    the increment is halved, and the halved one is tried from both starts in turn again. A
    ramp's first step has no predictor to switch: it is halved at once."""

    def predictor_fails(lam, predicted):  # the predictor overshoots at λ = 0.4
        return predicted and lam == pytest.approx(0.4)

    solver = PathSolver(lambda x: x**2, predictor_fails)
    _, records = ramp(
        solver, 0.0, 0.5, first_step=0.1, min_step=1e-3, growth=1.0, extrapolate=True, retry=True
    )
    assert [r.load for r in records] == pytest.approx([0.1, 0.2, 0.3, 0.4, 0.5])
    assert solver.attempts[3:5] == [(pytest.approx(0.4), True), (pytest.approx(0.4), False)]
    assert (records[3].retries, records[3].cuts, records[3].failed_iterations) == (1, 0, 3)

    def large_steps_fail(lam, predicted):  # any increment over 0.15 past λ = 0.2 fails
        return lam > 0.2 + 1e-9 and lam - solver.committed > 0.15 + 1e-9

    solver = PathSolver(lambda x: x**2, large_steps_fail)
    commit = solver.commit
    solver.committed = 0.0
    solver.commit = lambda: (commit(), setattr(solver, "committed", solver.load))
    _, records = ramp(solver, 0.0, 0.6, first_step=0.2, min_step=1e-3, growth=2.0, retry=True)
    tried = [(round(lam, 9), p) for lam, p in solver.attempts]
    # λ = 0.2, then 0.6 (+0.4) fails, its retry with the predictor fails, 0.4 (+0.2) fails
    # from both starts, 0.3 (+0.1) converges at its first
    assert tried[:6] == [
        (0.2, False),
        (0.6, False),
        (0.6, True),
        (0.4, False),
        (0.4, True),
        (0.3, False),
    ]
    assert (records[1].load, records[1].retries, records[1].cuts) == (pytest.approx(0.3), 2, 2)

    first_fails = PathSolver(lambda x: x**2, lambda lam, predicted: lam == pytest.approx(0.2))
    _, records = ramp(
        first_fails, 0.0, 0.3, first_step=0.2, min_step=1e-3, retry=True, extrapolate=True
    )
    assert [round(lam, 9) for lam, _ in first_fails.attempts[:2]] == [0.2, 0.1]
    assert records[0].retries == 0 and records[0].cuts == 1


def test_a_halved_increment_is_tried_from_the_converged_state_too():
    """The king wire's stall at 625 N (design notes 2026-11-30): past some load every attempt
    started from the secant predictor fails, and so do the large ones from the converged
    state, while a small increment from the converged state converges. Trying each increment
    from both starts carries the ramp; trying the other start once per step, then only the
    predictor, cut it to nothing."""

    def predictor_and_large_steps_fail(lam, predicted):
        past = lam > 0.2 + 1e-9
        return past and (predicted or lam - solver.committed > 0.06 + 1e-9)

    solver = PathSolver(lambda x: x**2, predictor_and_large_steps_fail)
    commit = solver.commit
    solver.committed = 0.0
    solver.commit = lambda: (commit(), setattr(solver, "committed", solver.load))
    _, records = ramp(
        solver, 0.0, 0.3, first_step=0.1, min_step=1e-2, growth=1.0, extrapolate=True, retry=True
    )
    assert records[-1].load == pytest.approx(0.3)
    # 0.3 (+0.1) fails from both starts, 0.25 (+0.05) from the predictor, then converges
    tried = [(round(lam, 9), p) for lam, p in solver.attempts]
    assert tried[2:6] == [(0.3, True), (0.3, False), (0.25, True), (0.25, False)]


def test_a_controlled_ramp_resumed_from_any_step_takes_the_same_steps():
    """``RampState`` (the next increment and the last step's increments) is all the controller
    needs: a ramp continued from the state of step k takes the steps of the whole one."""
    u = lambda x: np.sin(3 * x)  # noqa: E731
    kwargs = dict(
        first_step=0.02, min_step=1e-5, controller=ErrorControl(tol=1e-4), extrapolate=True
    )
    whole, states = PathSolver(u), []
    whole.set_load(0.0)
    stepper = LoadStepper(whole, **kwargs)
    stepper.on_step = lambda rec: states.append(
        RampState(stepper.state.step, (stepper.state.previous[0], stepper.state.previous[1].copy()))
    )
    records = stepper.ramp(whole.set_load, 0.0, 1.0)
    k = 5
    resumed = PathSolver(u)
    resumed.w.x.array[:] = resumed.path(records[k].load)
    resumed.commit()
    rest = LoadStepper(resumed, **kwargs).ramp(
        resumed.set_load, records[k].load, 1.0, resume=states[k]
    )
    assert [r.load for r in rest] == [r.load for r in records[k + 1 :]]
    assert [r.error for r in rest] == [r.error for r in records[k + 1 :]]


# -- the quick 1+6 strand --------------------------------------------------------------------------
QUIET = ["output.plots=false", "output.fields=false", "fatigue.outputs=false"]


def run_seven_wire(tmp_path: Path, scale: float = 1.0, controller=None) -> tuple[np.ndarray, int]:
    """The quick 1+6's programme: tension in eighth steps, then a lateral cycle out and back
    with the case's increments times ``scale`` and ``controller``; returns the displacements
    (m) at its end and the number of steps."""
    path = tmp_path / "seven.toml"
    path.write_text(SEVEN_WIRE)
    problem, programme = build_problem(load_case(path, QUIET), io.StringIO())
    setup = problem.setup
    steps = 0
    for stage in programme.stages:
        tension = stage.parameter == "tension"
        k = 1 / 8 if tension else scale
        stepper = LoadStepper(
            problem.solver,
            k * stage.first_step,
            k * stage.min_step,
            max_step=k * stage.max_step,
            growth=stage.growth,
            extrapolate=stage.extrapolate,
            controller=None if tension else controller,
        )
        records = stepper.ramp(
            lambda v, name=stage.parameter: setup.set(name, v),
            setup.get(stage.parameter),
            stage.target,
            stage.name,
        )
        steps += len(records)
    w = problem.w.x.array.reshape(-1, 6)[:, :3].copy()
    problem.solver.destroy()
    return w, steps


@pytest.mark.slow
def test_the_controlled_seven_wire_run_is_as_close_to_halved_steps_as_the_rule(tmp_path):
    """On the quick 1+6 (frictional crossings: the end state after the lateral cycle depends
    on the load path), the run whose lateral legs take the controller's steps converges, and
    its end state differs from the run with halved steps by no more than the default rule's
    does. The tension is applied in the same fine steps in all three: a ramp's first step is
    the rule's (no predictor yet), and the tension's first one dominates the differences
    otherwise."""
    reference, n_half = run_seven_wire(tmp_path, 0.5)
    rule, n_rule = run_seven_wire(tmp_path, 1.0)
    controlled, n_controlled = run_seven_wire(tmp_path, 1.0, ErrorControl())
    error_rule = np.abs(rule - reference).max()
    error_controlled = np.abs(controlled - reference).max()
    print(
        f"steps: halved {n_half}, rule {n_rule}, controlled {n_controlled}; "
        f"max |Δu| against halved: rule {error_rule:.3e} m, controlled {error_controlled:.3e} m"
    )
    assert error_controlled <= error_rule


@pytest.mark.parametrize("control", ["growth", "error"])
def test_a_case_file_chooses_the_step_control(tmp_path, control):
    """``[steps] control`` reaches every ramp of a run: on leg 1 of the quick 1+6, every step
    taken without a cut follows its rule from the step before: × 1.5 after a solve of at most
    6 iterations (else × 1) under the growth rule; under the controller with a tolerance no step
    misses (1 m), × 2 (``grow_max``), or × 1 right after a cut (``grow_after_cut``), except after
    the leg's first step, which has no predictor to miss (the growth rule then); both within
    ``lateral_max`` (150 N) and what is left of the leg."""
    case = load_case(
        Path(__file__).parents[1] / "cases" / "quick_1x6.toml",
        [
            f'steps.control="{control}"',
            "steps.error_tolerance=1.0",
            "load.cycle=[1.0]",
            "output.fields=false",
            "output.plots=false",
            "output.checkpoint=false",
            "fatigue.outputs=false",
        ],
    )
    result = run_case(case, tmp_path / control, stream=io.StringIO())
    assert not result.failure
    leg = [s for s in result.steps if s.stage == "leg 1"]
    loads = np.array([0.0] + [s.load for s in leg])
    checked = 0
    for k in range(1, len(leg)):
        if leg[k].cuts:
            continue
        before = loads[k] - loads[k - 1]
        if control == "growth" or k == 1:  # the controller sizes the steps after the first
            factor = 1.5 if leg[k - 1].iterations <= 6 else 1.0
        else:
            factor = 1.0 if leg[k - 1].cuts else 2.0
        expected = min(before * factor, 150.0, 300.0 - loads[k])
        assert loads[k + 1] - loads[k] == pytest.approx(expected), (k, loads)
        checked += 1
    assert checked >= 2
