"""dolfinx's ``NonlinearProblem`` with pair terms and strand's convergence tests.

``NonlinearProblem`` extends ``dolfinx.fem.petsc.NonlinearProblem`` the way dolfinx_mpc's does: the
same arguments (``petsc_options_prefix``, ``petsc_options``), the same ``.solver`` SNES, ``A``,
``b``, ``x``, ``F``, ``J`` and ``u``, with its own Jacobian matrix (the forms' sparsity pattern
extended by the pair stencils) and its own SNES callbacks, which add the pair terms
(``strand.solver.terms``) to what dolfinx assembles. SNES decides convergence by PETSc's default
rules, then the stall and balance tests (``strand.solver.convergence``). It also keeps the last
converged state, so that a failed load step can be rolled back, with the pair terms' histories
and the ``history`` states of a history-dependent law (``strand.solver.history``).
"""

from __future__ import annotations

import time
from collections.abc import Callable, Sequence
from contextlib import contextmanager

import dolfinx.fem.petsc as fem_petsc
import numpy as np
import numpy.typing as npt
import ufl
from dolfinx import fem
from mpi4py import MPI
from petsc4py import PETSc

from .convergence import LAST_RESORT_ITERATIONS, NewtonConvergence, NewtonOptions, NewtonResult
from .history import HistoryState
from .interrupt import Interrupt
from .terms import PairAssembler, PairTerms, create_extended_matrix

__all__ = ["NonlinearProblem"]


class NonlinearProblem(fem_petsc.NonlinearProblem):
    """``F(u; v) + Σ pair terms = 0`` with Dirichlet conditions ``bcs``, solved by PETSc SNES
    (Newton, MUMPS LU by default).

    Args:
        F: residual form (internal minus external virtual work), linear in the test function.
        u: the unknown on a blocked (6,)-valued space (u, θ per node); updated in place by
            ``solve``.
        bcs: Dirichlet conditions on ``u.function_space``.
        terms: ``PairTerms`` objects (contact, links, nodal loads).
        history: ``HistoryState`` objects, e.g. ``InternalVariables``: the state of a
            history-dependent law (plastic curvatures), committed once per converged step
            (``commit``) and restored by ``rollback``; they add nothing to the residual.
        J: Jacobian form; default ``ufl.derivative(F, u)``.
        options: ``NewtonOptions``: tolerances, line search, the stall and balance tests.
        petsc_options_prefix: options prefix of the SNES (and ``A_``, ``b_``, ``x_`` after it
            for those); default: one of this problem's own.
        petsc_options: PETSc options set under the prefix, after (and over) those of
            ``options``. They stay in PETSc's database while the problem lives (the MUMPS
            ones are read at the first factorisation) and ``destroy`` removes them.
        monitor: called as ``monitor(iteration, residual_norm)`` at every Newton iteration.
        form_compiler_options, jit_options: as for ``dolfinx.fem.form``.
    """

    def __init__(
        self,
        F: ufl.Form,
        u: fem.Function,
        bcs: Sequence[fem.DirichletBC] | None = None,
        *,
        terms: Sequence[PairTerms] = (),
        history: Sequence[HistoryState] = (),
        J: ufl.Form | None = None,
        options: NewtonOptions | None = None,
        petsc_options_prefix: str | None = None,
        petsc_options: dict | None = None,
        monitor: Callable[[int, float], None] | None = None,
        form_compiler_options: dict | None = None,
        jit_options: dict | None = None,
    ):
        # Not the base constructor: it allocates the forms' Jacobian and binds dolfinx's
        # callbacks to it, and this problem's matrix must hold the pair stencils (dolfinx_mpc's
        # NonlinearProblem builds its own for its constraints in the same way). The attributes
        # are the base class's, so that its properties and ``__del__`` hold.
        V = u.function_space
        if V.dofmap.index_map_bs != 6:
            raise ValueError(
                f"{type(self).__name__} expects a blocked (6,)-valued space (u, θ) per node"
            )
        if petsc_options_prefix is None:
            petsc_options_prefix = f"strand_newton_{id(self):x}_"
        if petsc_options_prefix == "":
            raise ValueError("PETSc options prefix cannot be empty.")
        jit = dict(form_compiler_options=form_compiler_options, jit_options=jit_options)
        self._u: fem.Function = u  # one Function, not the base class's blocked list
        self._F = fem.form(F, **jit)
        self._J = fem.form(J if J is not None else ufl.derivative(F, u), **jit)
        self._preconditioner = None
        self._P_mat = None
        self.bcs = list(bcs) if bcs is not None else []
        self.terms = list(terms)
        self.history = list(history)
        self.options = options or NewtonOptions()
        self.monitor = monitor
        #: an ``Interrupt``: once requested, the current solve stops at its next residual
        self.interrupt: Interrupt | None = None
        self._pairs = PairAssembler(self.terms, self.bcs, V)
        self._A = create_extended_matrix(self._J, [t.stencils for t in self.terms])
        self._b = fem_petsc.create_vector(V)
        self._x = fem_petsc.create_vector(V)
        self._convergence = NewtonConvergence(self.options, self._b, V.mesh.comm)

        self._petsc_options_prefix = petsc_options_prefix
        self._snes = PETSc.SNES().create(V.mesh.comm)
        self._snes.setOptionsPrefix(petsc_options_prefix)
        self._A.setOptionsPrefix(f"{petsc_options_prefix}A_")
        self._b.setOptionsPrefix(f"{petsc_options_prefix}b_")
        self._x.setOptionsPrefix(f"{petsc_options_prefix}x_")
        settings = {**self.options.petsc_options(), **(petsc_options or {})}
        self._option_names = [f"{petsc_options_prefix}{k}" for k in settings]
        opts = PETSc.Options()
        for name, v in zip(self._option_names, settings.values(), strict=True):
            opts[name] = v
        self._snes.setFunction(self._residual, self._b)
        # ``reuse_lu`` factorises a matrix of its own, a copy of the Jacobian taken when the LU
        # is renewed: MUMPS factorises again only when that copy changes (PCSetUp compares its
        # state), while GMRES works on the current Jacobian
        self._P = self._A.duplicate() if self.options.iteration == "reuse_lu" else self._A
        self._lu_age = 0  # Jacobians the kept LU served (``reuse_lu``); 0: none kept
        self._newton_only = False  # the fall-back solve: a fresh LU at every iteration
        self._factorisations = 0
        self._snes.setJacobian(self._jacobian, self._A, self._P)
        self._snes.setMonitor(self._monitor)
        self._snes.setConvergenceTest(self._convergence)
        self._snes.setFromOptions()
        self._saved = u.x.array.copy()
        #: ``relax``: (stiffness per dof, the unknowns the springs hold to, a work vector)
        self._relax: tuple[PETSc.Vec, PETSc.Vec, PETSc.Vec] | None = None
        self._kept_residual: npt.NDArray[np.float64] | None = None  # ``keep_residual``
        #: wall time (s) in: residual and Jacobian callbacks (everything they do), the pair terms'
        #: evaluation (inside the callbacks), their insertion into PETSc objects (idem), and the
        #: whole of ``solve`` (callbacks + LU + SNES overhead); and counts: the callbacks
        #: (``residual_calls``, ``jacobian_calls``) and the pair terms (stencils) evaluated with
        #: their tangent (``tangent_terms``) or without (``residual_terms``)
        self.timings = {
            "residual": 0.0,
            "jacobian": 0.0,
            "terms": 0.0,
            "insert": 0.0,
            "solve": 0.0,
            "residual_calls": 0,
            "jacobian_calls": 0,
            "tangent_terms": 0,
            "residual_terms": 0,
        }

    @property
    def w(self) -> fem.Function:
        """The unknown ``u`` (displacements and rotations)."""
        return self._u

    @property
    def V(self) -> fem.FunctionSpace:
        """The space of ``u``."""
        return self._u.function_space

    # -- SNES callbacks --------------------------------------------------------------------------
    def _residual(self, snes, x, b):
        t0 = time.perf_counter()
        self.timings["residual_calls"] += 1
        x.ghostUpdate(PETSc.InsertMode.INSERT, PETSc.ScatterMode.FORWARD)
        fem_petsc.assign(x, self._u)
        if not self._all_finite() or self.stop_requested():
            # a diverged iterate, or Ctrl-C: SNES stops (DIVERGED_FUNCTION_NANORINF)
            b.set(np.nan)
            return
        # the residual alone: a line search's trial points need no tangent
        terms = self._pairs.evaluate(self._u.x.array, self.timings, tangent=False)
        t1 = time.perf_counter()
        with b.localForm() as bl:
            bl.set(0.0)
            self._pairs.add_residuals(bl.array_w, terms)
        self.timings["insert"] += time.perf_counter() - t1
        fem_petsc.assemble_vector(b, self._F)
        fem_petsc.apply_lifting(b, [self._J], bcs=[self.bcs], x0=[x], alpha=-1.0)
        b.ghostUpdate(PETSc.InsertMode.ADD, PETSc.ScatterMode.REVERSE)
        fem_petsc.set_bc(b, self.bcs, x0=x, alpha=-1.0)
        if self._relax is not None:  # + D (x − x_ref), zero at the Dirichlet dofs
            d, ref, work = self._relax
            work.waxpy(-1.0, ref, x)
            work.pointwiseMult(work, d)
            b.axpy(1.0, work)
        b.ghostUpdate(PETSc.InsertMode.INSERT, PETSc.ScatterMode.FORWARD)
        self.timings["residual"] += time.perf_counter() - t0

    def _jacobian(self, snes, x, J, P):
        t0 = time.perf_counter()
        self.timings["jacobian_calls"] += 1
        x.ghostUpdate(PETSc.InsertMode.INSERT, PETSc.ScatterMode.FORWARD)
        fem_petsc.assign(x, self._u)
        terms = self._pairs.evaluate(self._u.x.array, self.timings)
        J.zeroEntries()
        fem_petsc.assemble_matrix(J, self._J, self.bcs, diag=1.0)
        J.assemble(PETSc.Mat.AssemblyType.FLUSH)  # the Dirichlet diagonal was INSERTed
        t2 = time.perf_counter()
        self._pairs.add_tangents(J, terms)
        J.assemble()
        if self._relax is not None:  # + D
            J.setDiagonal(self._relax[0], addv=PETSc.InsertMode.ADD_VALUES)
            J.assemble()
        if self._P is self._A:  # a fresh LU of every Jacobian
            self._factorisations += 1
        elif self._renew_lu(snes):
            J.copy(P, structure=PETSc.Mat.Structure.SAME_NONZERO_PATTERN)
            self._factorisations += 1
        t3 = time.perf_counter()
        self.timings["insert"] += t3 - t2
        self.timings["jacobian"] += t3 - t0

    def _renew_lu(self, snes) -> bool:
        """``reuse_lu``: whether this Jacobian's LU replaces the one kept: in the fall-back
        solve, when none is kept (the first, or after a failed factorisation), once it served
        ``lu_reuse`` Jacobians, and when the last GMRES solve failed or needed all its
        ``krylov_max`` iterations (the LU went stale)."""
        o = self.options
        ksp = snes.getKSP()
        stale = ksp.getConvergedReason() < 0 or ksp.getIterationNumber() >= o.krylov_max
        if self._newton_only or self._lu_age == 0 or stale or self._lu_age >= o.lu_reuse:
            self._lu_age = 1
            return True
        self._lu_age += 1
        return False

    def _monitor(self, snes, its, norm):
        self._convergence.record(norm)
        if self.monitor is not None:
            self.monitor(its, float(norm))

    # -- solving ---------------------------------------------------------------------------------
    def solve(self) -> NewtonResult:
        """Run Newton from the current ``u``. On failure ``u`` holds the last iterate. With a
        cheaper iteration than Newton's (``NewtonOptions.iteration``), a failed solve is solved
        again by Newton from the same start."""
        newton = self.options.iteration == "newton" or self._newton_only
        start = None if newton else self._u.x.array.copy()  # for the fall-back
        first = self._solve_once()
        if first.converged or newton or self.stop_requested():
            return first
        self._pairs.rollback()  # the pairs' state too (large sliding's segments) as it was
        for state in self.history:  # and a law's, as the last commit left it
            state.rollback()
        self._u.x.array[:] = start
        with self._newton():
            second = self._solve_once()
        return NewtonResult(
            second.converged,
            first.iterations + second.iterations,
            second.reason,
            second.residuals,
            first.seconds + second.seconds,
            first.factorisations + second.factorisations,
            fallback=True,
        )

    @contextmanager
    def _newton(self):
        """Inside, this problem's SNES runs Newton: a fresh LU at every iteration, and a failed
        linear solve ends the solve (the settings return from PETSc's options database)."""
        lbfgs = self.options.iteration == "lbfgs"
        linear_failures = self._snes.getMaxLinearSolveFailures()
        self._snes.setMaxLinearSolveFailures(1)
        self._newton_only = True
        if lbfgs:
            self._snes.setType("newtonls")
            self._snes.getLineSearch().setType(self.options.linesearch)
        try:
            yield
        finally:
            self._newton_only = False
            self._snes.setMaxLinearSolveFailures(linear_failures)
            if lbfgs:
                self._snes.setFromOptions()  # back to the options' L-BFGS

    def last_resort(self, on: bool) -> None:
        """Give the next solves a last resort's patience (on): no stall test, and up to
        ``LAST_RESORT_ITERATIONS`` times the options' iterations; or the options' again (off).
        For the attempts of a step whose cuts are exhausted (``Stabiliser``), which would
        otherwise end the run."""
        patience = LAST_RESORT_ITERATIONS * self.options.max_it if on else None
        self._convergence.patience = patience
        self._snes.setTolerances(max_it=patience or self.options.max_it)

    def _solve_once(self) -> NewtonResult:
        # the stall test is Newton's: L-BFGS's residual falls slowly and unevenly
        self._convergence.stall_test = self._newton_only or self.options.iteration != "lbfgs"
        self._convergence.reset()
        self._pairs.forget()
        self._kept_residual = None
        factorisations = self._factorisations
        t0 = time.perf_counter()
        fem_petsc.assign(self._u, self._x)
        self._snes.solve(None, self._x)
        self._x.ghostUpdate(PETSc.InsertMode.INSERT, PETSc.ScatterMode.FORWARD)
        fem_petsc.assign(self._x, self._u)
        reason = self._snes.getConvergedReason()
        ksp = self._snes.getKSP()
        failed_pc = ksp.getPC().getFailedReason() != 0  # reuse_lu goes on past a failed solve
        if self.V.mesh.comm.size > 1:
            failed_pc = self.V.mesh.comm.allreduce(failed_pc, op=MPI.LOR)
        if reason == PETSc.SNES.ConvergedReason.DIVERGED_LINEAR_SOLVE or failed_pc:
            # a failed factorisation leaves the PC failed: without a reset every later solve
            # (after a step cut, from a good state) would fail at once
            ksp.reset()
            self._lu_age = 0  # reuse_lu: the next Jacobian's LU, made and counted
        converged = self._convergence.accepts(reason, self._all_finite)
        dt = time.perf_counter() - t0
        self.timings["solve"] += dt
        return NewtonResult(
            converged,
            self._snes.getIterationNumber(),
            self._convergence.reason_name(reason),
            list(self._convergence.residuals),
            dt,
            self._factorisations - factorisations,
        )

    def _all_finite(self) -> bool:
        """Whether the unknowns are finite on every rank (the same answer on all: collective)."""
        ok = bool(np.all(np.isfinite(self._u.x.array)))
        comm = self.V.mesh.comm
        return comm.allreduce(ok, op=MPI.LAND) if comm.size > 1 else ok

    def stop_requested(self) -> bool:
        """Whether the user asked to stop (``interrupt``) on any rank; collective, so that every
        rank takes the same branch."""
        asked = self.interrupt is not None and self.interrupt.requested
        comm = self.V.mesh.comm
        return comm.allreduce(asked, op=MPI.LOR) if comm.size > 1 else asked

    def unconstrained_residual(self) -> npt.NDArray[np.float64]:
        """Residual (internal minus external forces, N and N m) of the current state with no
        Dirichlet condition applied and no pair term masked, as (n_blocks, 6) over the owned
        nodes: at supported dofs it is the support reaction. Uses the pair terms' last
        evaluation when it was at this state (it is after a solve), so their states and
        histories are left as they are. After ``keep_residual``, the residual kept, until the
        next solve."""
        if self._kept_residual is not None:
            return self._kept_residual.copy()
        b = fem_petsc.create_vector(self.V)
        with b.localForm() as bl:
            bl.set(0.0)
            terms = self._pairs.evaluate(self._u.x.array, self.timings, tangent=False)
            self._pairs.add_residuals(bl.array_w, terms, reactions=True)
        fem_petsc.assemble_vector(b, self._F)
        b.ghostUpdate(PETSc.InsertMode.ADD, PETSc.ScatterMode.REVERSE)
        n_owned = self.V.dofmap.index_map.size_local
        out = b.array_r[: 6 * n_owned].reshape(-1, 6).copy()
        b.destroy()
        return out

    def keep_residual(self, residual: npt.NDArray[np.float64]) -> None:
        """Take ``residual`` (n_owned, 6) as the current state's unconstrained residual until
        the next solve: a restored state's, as its converged iterate gave it (the committed
        contact history does not give it back to round-off)."""
        self._kept_residual = np.array(residual, dtype=float).reshape(-1, 6)

    # -- pseudo-transient relaxation -------------------------------------------------------------
    def relax(self, stiffness: float | None, length: float = 1.0) -> None:
        """Hold every free dof to its current value by a spring (``stiffness`` N/m on the
        displacements, ``stiffness`` × ``length``² N m/rad on the rotations; None: off): the
        residual gains D (w − w_now) and the Jacobian D, a diagonal that no Dirichlet dof
        carries. A pseudo-time step of pseudo-transient continuation
        (``Stabiliser.relaxed_solve``): its solves stay well posed where the tangent is not
        (past a buckling, or where friction's slip tangent is not)."""
        if self._relax is not None:
            for v in self._relax:
                v.destroy()
            self._relax = None
        if stiffness is None:
            return
        if not stiffness > 0 or not length > 0:
            raise ValueError(f"relax: stiffness {stiffness} N/m and length {length} m must be > 0")
        d = self._x.duplicate()
        n = d.getLocalSize()
        per_dof = np.empty((n // 6, 6))
        per_dof[:, :3] = stiffness
        per_dof[:, 3:] = stiffness * length**2
        diagonal = per_dof.ravel()
        diagonal[self._pairs.bc_mask[:n]] = 0.0
        d.array[:] = diagonal
        ref = self._x.duplicate()
        fem_petsc.assign(self._u, ref)
        self._relax = (d, ref, self._x.duplicate())

    def relaxation_force(self) -> float:
        """The 2-norm (N, N m) of the springs' force D (w − w_ref) at the current unknowns:
        after a converged relaxed solve, the residual of the problem without them (0: off)."""
        if self._relax is None:
            return 0.0
        d, ref, work = self._relax
        fem_petsc.assign(self._u, work)
        work.axpy(-1.0, ref)
        work.pointwiseMult(work, d)
        return float(work.norm(PETSc.NormType.NORM_2))  # type: ignore[arg-type]

    # -- load steps ------------------------------------------------------------------------------
    def commit(self) -> None:
        """Accept the current state: it becomes the one ``rollback`` returns to. Call it once
        per converged step (``LoadStepper`` does): the pair terms and then the ``history``
        states commit what they built since the last one, the latter reading the unknowns."""
        self._saved[:] = self._u.x.array
        self._pairs.commit()
        for state in self.history:
            state.commit()

    def rollback(self) -> None:
        """Return to the last committed state (unknowns, term histories, ``history`` states)."""
        self._u.x.array[:] = self._saved
        self._pairs.rollback()
        for state in self.history:
            state.rollback()

    # -- PETSc objects ---------------------------------------------------------------------------
    def destroy(self) -> None:
        """Free the PETSc objects and remove this problem's options from PETSc's database."""
        if getattr(self, "_relax", None) is not None:
            self.relax(None)
        self._remove_options()
        for obj in (self._snes, self._A, self._b, self._x):
            obj.destroy()
        if self._P is not self._A:
            self._P.destroy()

    def _remove_options(self) -> None:
        opts = PETSc.Options()
        for name in getattr(self, "_option_names", ()):
            opts.delValue(name)
        self._option_names = []

    def __del__(self):
        self._remove_options()
        if hasattr(self, "_snes"):
            super().__del__()
