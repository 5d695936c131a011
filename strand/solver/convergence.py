"""Newton's settings and when a solve has converged: PETSc's default rules, then strand's stall
test and balance test, as a SNES convergence test."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np
from mpi4py import MPI
from petsc4py import PETSc

__all__ = [
    "NewtonOptions",
    "NewtonResult",
    "NewtonConvergence",
    "STALL_AFTER",
    "LAST_RESORT_ITERATIONS",
    "ITERATIONS",
]

#: ``NewtonOptions.iteration``: Newton, GMRES on a reused LU, L-BFGS
ITERATIONS = ("newton", "reuse_lu", "lbfgs")

#: the stall test's start in strand's own runs (``[steps] stall``, ``strand.StrandProblem``):
#: the 4th iteration (``NewtonOptions.stall_after``)
STALL_AFTER = 4

#: a last resort's iterations at most, over the options' ``max_it``
#: (``NonlinearProblem.last_resort``): Newton on a near-mechanism converges slowly, but
#: converges (1 m of Cardinal with its ring vaulted: its first tension step in 22 iterations
#: without the stall test, where with it the step was cut and the run stopped at 500 N)
LAST_RESORT_ITERATIONS = 2


@dataclass
class NewtonOptions:
    """Newton settings. Residual norms are in N (and N m) for strand's SI units."""

    atol: float = 1e-7
    rtol: float = 1e-9
    #: relative size of the Newton correction ||δw|| / ||w|| taken as converged: it ends solves
    #: that reached the round-off floor of the residual, which grows with the forces carried.
    stol: float = 1e-10
    #: a solve that PETSc ends on ``stol`` counts as converged only if its residual is within
    #: ``floor_factor`` × max(atol, rtol × initial residual): the round-off floor sits within a
    #: few times atol (measured over the test suite: 47 such solves, at 1.0–20× atol), whereas a
    #: blown-up iterate also makes ||δw|| / ||w|| small (residual 3e31 N at ||w|| ~ 1e19 m), and
    #: must be cut, not accepted.
    floor_factor: float = 100.0
    max_it: int = 25
    #: stall test: from iteration ``stall_after`` on, a solve whose residual has not fallen
    #: below ``stall_factor`` × the residual two iterations earlier (and is not yet within
    #: ``floor_factor`` of the tolerance) is stopped as failed, so that its step is cut at
    #: once. In its quadratic basin Newton gains orders of magnitude per iteration; a solve
    #: that has not halved its residual in two iterations is cycling (docs/theory.md §6)
    #: or diverging. In the default Cardinal case with full steps, all such solves but one
    #: ran on to ``max_it`` without converging; the one (leg 3, 8 iterations) recovered by
    #: chance after three iterations without progress, and cutting it moves the results by a
    #: change of load path (docs/theory.md §6). 0 switches it off; None (the default) leaves
    #: it off for a ``NonlinearProblem`` of one's own (a first step that pushes an initial
    #: penetration out may take several slow iterations) and gives a ``strand.StrandProblem``
    #: strand's choice, ``STALL_AFTER``.
    stall_after: int | None = None
    stall_factor: float = 0.5
    #: convergence in physical terms: from the first iteration on, a solve also ends when no
    #: node is out of balance by more than ``force_tol`` (N) in force and ``moment_tol`` (N m)
    #: in moment (largest nodal residual, all ranks); 0 leaves this test out
    force_tol: float = 0.0
    moment_tol: float = 0.0
    #: PETSc's line search: ``basic`` takes full Newton steps; strand's runs take ``cp``
    #: (``[steps] line_search``), which breaks the 2-cycles of slipping contact pairs
    #: (docs/theory.md §6)
    linesearch: str = "basic"
    #: how each iteration's linear system is solved (``ITERATIONS``): ``newton``, a MUMPS LU of
    #: every Jacobian; ``reuse_lu``, GMRES on every Jacobian preconditioned by the LU of an
    #: earlier one, kept across iterations and load steps and factorised afresh when GMRES took
    #: ``krylov_max`` iterations or failed, or after ``lu_reuse`` Jacobians; ``lbfgs``, PETSc's
    #: L-BFGS with the LU of each solve's first Jacobian as its initial inverse (no stall
    #: test: its residual falls slowly and unevenly). A solve of either that fails is solved
    #: again from its start by Newton (``NewtonResult.fallback``).
    iteration: str = "newton"
    #: ``reuse_lu``: the Jacobians one LU serves at most
    lu_reuse: int = 50
    #: ``reuse_lu``: GMRES's iterations at most; a solve that needs them all stales the LU
    krylov_max: int = 30
    #: ``reuse_lu``: GMRES's tolerance on the residual of the Newton system, relative to the
    #: nonlinear residual: an inexact Newton direction this close keeps Newton's iterates
    krylov_rtol: float = 1e-4
    petsc: dict = field(
        default_factory=dict
    )  # extra PETSc options, e.g. {"mat_mumps_icntl_14": 80}

    def __post_init__(self):
        if self.iteration not in ITERATIONS:
            raise ValueError(f"iteration = {self.iteration!r}: expected one of {ITERATIONS}")

    def petsc_options(self) -> dict:
        """The SNES, KSP and PC options these settings stand for (Newton with a line search,
        MUMPS LU; GMRES for ``reuse_lu``, L-BFGS for ``lbfgs``), then the extra ``petsc`` ones,
        without the options prefix."""
        options = {
            "snes_type": "newtonls",
            "snes_linesearch_type": self.linesearch,
            "snes_atol": self.atol,
            "snes_rtol": self.rtol,
            "snes_stol": self.stol,
            "snes_max_it": self.max_it,
            "snes_divergence_tolerance": 1e300,  # never stop on residual growth
            "ksp_type": "preonly",
            "pc_type": "lu",
            "pc_factor_mat_solver_type": "mumps",
        }
        if self.iteration == "reuse_lu":
            options |= {
                "ksp_type": "gmres",
                "ksp_pc_side": "right",  # GMRES minimises the Newton system's own residual
                "ksp_gmres_restart": self.krylov_max,
                "ksp_max_it": self.krylov_max,
                "ksp_rtol": self.krylov_rtol,
                # a GMRES that stops short still gives a direction; the next Jacobian is
                # factorised afresh
                "snes_max_linear_solve_fail": self.max_it + 1,
            }
        elif self.iteration == "lbfgs":
            options |= {
                "snes_type": "qn",
                "snes_qn_type": "lbfgs",
                "snes_qn_scale_type": "jacobian",
                "snes_qn_restart_type": "none",
                "snes_linesearch_type": "cp",
            }
        return options | self.petsc


@dataclass
class NewtonResult:
    """Outcome of one Newton solve: ``converged`` means a small residual in physical terms
    (``NonlinearProblem.solve``); ``reason`` is PETSc's, ``residuals`` the norms at every
    iterate."""

    converged: bool
    iterations: int
    reason: str
    residuals: list[float]
    seconds: float
    #: LU factorisations in this solve
    factorisations: int = 0
    #: the cheaper iteration (``NewtonOptions.iteration``) failed and Newton solved it again
    #: from the start; ``iterations`` and ``factorisations`` count both
    fallback: bool = False

    @property
    def residual(self) -> float:
        """Residual norm (N) at the final iterate (nan if none was evaluated)."""
        return self.residuals[-1] if self.residuals else float("nan")


_REASONS = {
    v: k
    for k, v in vars(PETSc.SNES.ConvergedReason).items()
    if isinstance(v, int) and not k.startswith("_")
}


class NewtonConvergence:
    """The convergence test of one SNES (``snes.setConvergenceTest(test)``): PETSc's default
    rules (``SNESConvergedDefault``: ``atol``, ``rtol`` against the first residual, ``stol``,
    ``max_it``), then the stall test and the balance test of ``options``.

    ``record`` must be called with each residual norm before the test (the SNES monitor is);
    ``residual`` is the SNES's residual vector, whose nodal values the balance test reads, on
    the communicator ``comm``.
    """

    def __init__(self, options: NewtonOptions, residual: PETSc.Vec, comm: MPI.Comm):
        self.options = options
        self.residual = residual
        self.comm = comm
        #: the residual norms of the solve under way, one per iterate
        self.residuals: list[float] = []
        #: whether the stall test stopped it
        self.stalled = False
        #: whether the stall test applies (``NonlinearProblem`` sets it for each solve: not
        #: to L-BFGS, whose residual falls slowly and unevenly)
        self.stall_test = True
        #: a last resort's iterations at most, with no stall test (None: the options')
        self.patience: int | None = None

    def reset(self) -> None:
        """Start a new solve."""
        self.residuals = []
        self.stalled = False

    def record(self, norm: float) -> None:
        """The residual norm of the next iterate."""
        self.residuals.append(float(norm))

    def __call__(self, snes, its: int, norms: tuple[float, float, float]) -> int:
        """``norms`` are those of the iterate, of the last Newton correction and of the
        residual; ``record`` has just been given the residual."""
        xnorm, snorm, fnorm = norms
        o = self.options
        reason = PETSc.SNES.ConvergedReason
        if not np.isfinite(fnorm):
            return reason.DIVERGED_FUNCTION_NANORINF
        if fnorm < o.atol or (its > 0 and o.force_tol > 0 and self.in_balance()):
            return reason.CONVERGED_FNORM_ABS
        if its > 0:
            r = self.residuals
            if fnorm <= o.rtol * r[0]:
                return reason.CONVERGED_FNORM_RELATIVE
            if snorm < o.stol * xnorm:
                return reason.CONVERGED_SNORM_RELATIVE
            if (
                self.stall_test
                and self.patience is None
                and 0 < (o.stall_after or 0) <= its
                and fnorm > o.stall_factor * r[its - 2]
                and fnorm > o.floor_factor * max(o.atol, o.rtol * r[0])
            ):
                self.stalled = True
                return reason.DIVERGED_DTOL
        if its >= (o.max_it if self.patience is None else self.patience):
            return reason.DIVERGED_MAX_IT
        return reason.CONVERGED_ITERATING

    def in_balance(self) -> bool:
        """Whether every node's out-of-balance force and moment (the residual; at Dirichlet dofs
        it is the distance to the prescribed value, zero after the first iteration) are within
        ``force_tol`` and ``moment_tol``; collective."""
        r = np.abs(self.residual.array_r.reshape(-1, 6))
        worst = np.array([r[:, :3].max(initial=0.0), r[:, 3:].max(initial=0.0)])
        if self.comm.size > 1:
            self.comm.Allreduce(MPI.IN_PLACE, worst, op=MPI.MAX)
        return bool(worst[0] <= self.options.force_tol and worst[1] <= self.options.moment_tol)

    def accepts(self, reason: int, all_finite: Callable[[], bool]) -> bool:
        """Whether PETSc's ``reason`` is a convergence with a small residual in physical terms:
        finite unknowns (``all_finite``, collective), and on the step-size test (``stol``) a
        residual within ``floor_factor`` of the tolerance (the absolute and relative tests imply
        one by themselves)."""
        if reason <= 0:
            return False
        r = self.residuals
        if not r or not np.all(np.isfinite(r)) or not all_finite():
            return False
        if reason != PETSc.SNES.ConvergedReason.CONVERGED_SNORM_RELATIVE:
            return True
        o = self.options
        return r[-1] <= o.floor_factor * max(o.atol, o.rtol * r[0])

    def reason_name(self, reason: int) -> str:
        """PETSc's name of ``reason``, or ``DIVERGED_STALLED`` if the stall test stopped it."""
        return "DIVERGED_STALLED" if self.stalled else _REASONS.get(reason, str(reason))
