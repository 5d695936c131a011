"""Newton's method (PETSc SNES, MUMPS LU) and load stepping for UFL beams plus pair terms.

The beam lives in UFL; contact pairs, penalty links and nodal loads do not. They enter through the
``PairTerms`` protocol: each term set owns a fixed array of node stencils and returns, for the current
state, all its residual vectors and tangent blocks at once (numpy arrays). The solver

* extends the sparsity pattern of the UFL Jacobian with the stencils, once,
* adds the stencil residuals into the ghosted residual vector and the blocks into the matrix that
  dolfinx assembled (one ``setValuesBlockedLocalRCV`` call per term set),
* masks Dirichlet dofs, lifting the stencils' coupling to prescribed motions onto the free
  rows (as dolfinx's ``apply_lifting`` does for the forms), and
* keeps the last converged state so that a failed step can be rolled back.

``dolfinx.fem.petsc.NonlinearProblem`` has no argument for a user-built matrix (it would allocate a
second, unused Jacobian), so this module drives a ``PETSc.SNES`` directly with the same dolfinx
assembly helpers.
"""

from __future__ import annotations

import signal
import threading
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Protocol

import dolfinx
import dolfinx.fem.petsc as fem_petsc
import numpy as np
import numpy.typing as npt
import ufl
from dolfinx import fem
from mpi4py import MPI
from petsc4py import PETSc

__all__ = [
    "PairTerms",
    "NodalLoad",
    "NewtonOptions",
    "NewtonResult",
    "NewtonSolver",
    "LoadStepper",
    "StepRecord",
    "RampState",
    "LoadStepFailure",
    "RunInterrupted",
    "Interrupt",
]


class PairTerms(Protocol):
    """Residual and tangent contributions assembled outside UFL, e.g. contact pairs.

    ``stencils`` is a fixed (P, k) int32 array of local dof-block (node) indices: term p couples
    the nodes ``stencils[p]``. ``evaluate(w)`` receives the local nodal values (n_blocks, 6) of the
    current iterate (ghosts included) and returns the residual contributions f (P, 6k) and, when
    ``jacobian`` is true, the tangent blocks K = ∂f/∂w (P, 6k, 6k), or None for state-independent
    terms. Each rank returns each term once. ``commit``/``rollback`` accept or discard the history
    built since the last converged step.

    A term set whose blocks are sparse within the stencil may declare ``dofs`` (m,): the positions
    (in 0..6k) of the stencil dofs that f (P, m) and K (P, m, m) hold; the others are zero and are
    neither computed nor inserted (e.g. the rotations of nodes that enter through positions only).
    """

    stencils: npt.NDArray[np.int32]
    # optional: dofs: npt.NDArray[np.intp]

    def evaluate(
        self, w: npt.NDArray[np.float64], jacobian: bool
    ) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64] | None]: ...

    def commit(self) -> None: ...

    def rollback(self) -> None: ...


class NodalLoad:
    """External nodal forces/moments F (n, 6) on nodes ``blocks`` (n,), scaled by ``factor``.

    Its residual contribution is −factor·F (the residual is internal minus external forces).
    """

    def __init__(self, blocks: npt.ArrayLike, values: npt.ArrayLike, factor: float = 0.0):
        self.stencils = np.asarray(blocks, dtype=np.int32).reshape(-1, 1)
        self.values = np.asarray(values, dtype=np.float64).reshape(-1, 6)
        if len(self.values) != len(self.stencils):
            raise ValueError("NodalLoad: one 6-vector of forces/moments per node is needed")
        self.factor = factor

    def evaluate(self, w, jacobian):
        return -self.factor * self.values, None

    def commit(self) -> None:
        pass

    def rollback(self) -> None:
        pass


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
    #: change of load path (docs/theory.md §6). 0 switches it off.
    stall_after: int = 4
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
    petsc: dict = field(
        default_factory=dict
    )  # extra PETSc options, e.g. {"mat_mumps_icntl_14": 80}


@dataclass
class NewtonResult:
    """Outcome of one Newton solve: ``converged`` means a small residual in physical terms
    (``NewtonSolver.solve``); ``reason`` is PETSc's, ``residuals`` the norms at every iterate."""

    converged: bool
    iterations: int
    reason: str
    residuals: list[float]
    seconds: float

    @property
    def residual(self) -> float:
        """Residual norm (N) at the final iterate (nan if none was evaluated)."""
        return self.residuals[-1] if self.residuals else float("nan")


_REASONS = {
    v: k
    for k, v in vars(PETSc.SNES.ConvergedReason).items()
    if isinstance(v, int) and not k.startswith("_")
}


class NewtonSolver:
    """Newton solver for ``F(w; v) + Σ pair terms = 0`` with Dirichlet conditions ``bcs``.

    Args:
        F: residual form (internal minus external virtual work), linear in the test function.
        w: the unknown; updated in place by ``solve``.
        bcs: Dirichlet conditions on ``w.function_space``.
        terms: ``PairTerms`` objects (contact, links, nodal loads).
        J: Jacobian form; default ``ufl.derivative(F, w)``.
        options: ``NewtonOptions``.
        prefix: PETSc options prefix of this solver (default: one of its own). Its options are
            set under it and removed by ``destroy``, so that solvers never share options.
        monitor: called as ``monitor(iteration, residual_norm)`` at every Newton iteration.
    """

    def __init__(
        self,
        F: ufl.Form,
        w: fem.Function,
        bcs: Sequence[fem.DirichletBC] = (),
        terms: Sequence[PairTerms] = (),
        J: ufl.Form | None = None,
        options: NewtonOptions | None = None,
        prefix: str | None = None,
        monitor: Callable[[int, float], None] | None = None,
    ):
        self.w = w
        self.V = w.function_space
        self.bcs = list(bcs)
        self.terms = list(terms)
        self.options = options or NewtonOptions()
        self.monitor = monitor
        #: an ``Interrupt``: once requested, the current solve stops at its next residual
        self.interrupt: Interrupt | None = None
        comm = self.V.mesh.comm
        if self.V.dofmap.index_map_bs != 6:
            raise ValueError("NewtonSolver expects a blocked (6,)-valued space (u, θ) per node")

        self.F = fem.form(F)
        self.J = fem.form(J if J is not None else ufl.derivative(F, w))

        # Jacobian with the beam's sparsity pattern extended by every stencil, primed once so that
        # the first assembly does not squeeze the extra slots out (PETSc error 63 otherwise).
        sp = fem.create_sparsity_pattern(self.J)
        for t in self.terms:
            _insert_stencils(sp, np.asarray(t.stencils, dtype=np.int32))
        sp.finalize()
        self.A = dolfinx.cpp.la.petsc.create_matrix(comm, sp, None)
        self.A.setOption(PETSc.Mat.Option.NEW_NONZERO_ALLOCATION_ERR, True)
        cols, offsets = sp.graph
        self.A.setValuesBlockedLocalCSR(offsets.astype(np.int32), cols, np.zeros(len(cols) * 36))
        self.A.assemble()

        self.b = fem_petsc.create_vector(self.V)
        self.x = fem_petsc.create_vector(self.V)

        # Dirichlet mask over local dofs (ghosts included): contributions there are dropped.
        n_local = self.V.dofmap.index_map.size_local + self.V.dofmap.index_map.num_ghosts
        self._bc_mask = np.zeros(6 * n_local, dtype=bool)
        for bc in self.bcs:
            dofs, _ = bc.dof_indices()
            self._bc_mask[dofs] = True

        self.prefix = prefix if prefix is not None else f"strand_newton_{id(self):x}_"
        self.snes = PETSc.SNES().create(comm)
        self.snes.setOptionsPrefix(self.prefix)
        opts = PETSc.Options()
        settings = {
            "snes_type": "newtonls",
            "snes_linesearch_type": self.options.linesearch,
            "snes_atol": self.options.atol,
            "snes_rtol": self.options.rtol,
            "snes_stol": self.options.stol,
            "snes_max_it": self.options.max_it,
            "snes_divergence_tolerance": 1e300,  # never stop on residual growth
            "ksp_type": "preonly",
            "pc_type": "lu",
            "pc_factor_mat_solver_type": "mumps",
            **self.options.petsc,
        }
        self._option_names = [f"{self.prefix}{k}" for k in settings]
        for name, v in zip(self._option_names, settings.values(), strict=True):
            opts[name] = v
        self.snes.setFunction(self._residual, self.b)
        self.snes.setJacobian(self._jacobian, self.A, self.A)
        self.snes.setMonitor(self._monitor)
        self.snes.setConvergenceTest(self._converged)
        self.snes.setFromOptions()
        self._residuals: list[float] = []
        self._stalled = False
        self._cache: tuple[np.ndarray, list] | None = None
        self._masks: list | None = None
        self._saved = w.x.array.copy()
        #: wall time (s) in: residual and Jacobian callbacks (everything they do), the pair terms'
        #: evaluation (inside the callbacks), their insertion into PETSc objects (idem), and the
        #: whole of ``solve`` (callbacks + LU + SNES overhead)
        self.timings = {"residual": 0.0, "jacobian": 0.0, "terms": 0.0, "insert": 0.0, "solve": 0.0}

    # -- pair terms ------------------------------------------------------------------------------
    def _masked_terms(self):
        """Residuals and tangents of every term set at the current w, Dirichlet dofs masked.

        Evaluated once per state: SNES asks for the residual, then the Jacobian at the same w.
        """
        wl = self.w.x.array
        if self._cache is not None and np.array_equal(self._cache[0], wl):
            return self._cache[1]
        t0 = time.perf_counter()
        wn = wl.reshape(-1, 6)
        out = []
        lift = None
        for t, (idx, rows, mask) in zip(self.terms, self._term_masks(), strict=True):
            with np.errstate(all="ignore"):  # a wild iterate's inf/nan stops SNES, then a cut
                f, K = t.evaluate(wn, True)
            f_rows = f[rows].copy()  # unmasked, for the reactions
            if len(rows):  # only the few stencils that touch a Dirichlet dof
                if K is not None:
                    if lift is None:
                        lift = self._prescribed_increment(wl)
                    # lifting, as dolfinx's apply_lifting does for the forms: the free rows
                    # get K_fb (g − w_b), so that the step that moves the prescribed dofs to
                    # their values moves the others with them (Newton stays quadratic)
                    d = np.where(mask, lift[idx[rows]], 0.0)
                    f[rows] += np.einsum("pij,pj->pi", K[rows], d)
                    K[rows] = np.where(mask[:, :, None] | mask[:, None, :], 0.0, K[rows])
                f[rows] = np.where(mask, 0.0, f[rows])
            out.append((idx, f, K, rows, f_rows))
        self._cache = (wl.copy(), out)
        self.timings["terms"] += time.perf_counter() - t0
        return out

    def _prescribed_increment(self, wl: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]:
        """g − w at the Dirichlet dofs (local, ghosts included), zero elsewhere."""
        d = np.zeros_like(wl)
        for bc in self.bcs:
            bc.set(d, x0=wl, alpha=1.0)
        return d

    def _term_masks(self):
        """Per term set: local dof indices (P, m) of f and K, the rows (stencils) holding a
        Dirichlet dof, and their dof masks. Built once."""
        if self._masks is None:
            self._masks = []
            for t in self.terms:
                st = np.asarray(t.stencils)
                layout = getattr(t, "dofs", None)
                if layout is None:
                    layout = np.arange(6 * st.shape[1])
                idx = np.ascontiguousarray(6 * st[:, layout // 6] + layout % 6, dtype=np.int32)
                m = self._bc_mask[idx]
                rows = np.flatnonzero(m.any(axis=1))
                self._masks.append((idx, rows, m[rows]))
        return self._masks

    # -- SNES callbacks --------------------------------------------------------------------------
    def _residual(self, snes, x, b):
        t0 = time.perf_counter()
        x.ghostUpdate(PETSc.InsertMode.INSERT, PETSc.ScatterMode.FORWARD)
        fem_petsc.assign(x, self.w)
        if not self._all_finite() or self.stop_requested():
            # a diverged iterate, or Ctrl-C: SNES stops (DIVERGED_FUNCTION_NANORINF)
            b.set(np.nan)
            return
        terms = self._masked_terms()
        t1 = time.perf_counter()
        with b.localForm() as bl:
            bl.set(0.0)
            arr = bl.array_w
            for idx, f, *_ in terms:
                arr += np.bincount(idx.ravel(), weights=f.ravel(), minlength=len(arr))
        self.timings["insert"] += time.perf_counter() - t1
        fem_petsc.assemble_vector(b, self.F)
        fem_petsc.apply_lifting(b, [self.J], bcs=[self.bcs], x0=[x], alpha=-1.0)
        b.ghostUpdate(PETSc.InsertMode.ADD, PETSc.ScatterMode.REVERSE)
        fem_petsc.set_bc(b, self.bcs, x0=x, alpha=-1.0)
        b.ghostUpdate(PETSc.InsertMode.INSERT, PETSc.ScatterMode.FORWARD)
        self.timings["residual"] += time.perf_counter() - t0

    def _jacobian(self, snes, x, J, P):
        t0 = time.perf_counter()
        x.ghostUpdate(PETSc.InsertMode.INSERT, PETSc.ScatterMode.FORWARD)
        fem_petsc.assign(x, self.w)
        terms = self._masked_terms()
        J.zeroEntries()
        fem_petsc.assemble_matrix(J, self.J, self.bcs, diag=1.0)
        J.assemble(PETSc.Mat.AssemblyType.FLUSH)  # the Dirichlet diagonal was INSERTed
        t2 = time.perf_counter()
        for idx, _, K, *_ in terms:
            if K is not None and len(idx):
                J.setValuesLocalRCV(
                    idx, idx, np.ascontiguousarray(K), addv=PETSc.InsertMode.ADD_VALUES
                )
        J.assemble()
        t3 = time.perf_counter()
        self.timings["insert"] += t3 - t2
        self.timings["jacobian"] += t3 - t0

    def _converged(self, snes, its: int, norms: tuple[float, float, float]) -> int:
        """PETSc's default test (``SNESConvergedDefault``: ``atol``, ``rtol`` against the first
        residual, ``stol``, ``max_it``) and then the stall test (``NewtonOptions.stall_after``).
        ``norms`` are those of the iterate, of the last Newton correction and of the residual;
        the monitor has just appended the residual to ``self._residuals``."""
        xnorm, snorm, fnorm = norms
        o = self.options
        reason = PETSc.SNES.ConvergedReason
        if not np.isfinite(fnorm):
            return reason.DIVERGED_FUNCTION_NANORINF
        if fnorm < o.atol or (its > 0 and o.force_tol > 0 and self._in_balance()):
            return reason.CONVERGED_FNORM_ABS
        if its > 0:
            r = self._residuals
            if fnorm <= o.rtol * r[0]:
                return reason.CONVERGED_FNORM_RELATIVE
            if snorm < o.stol * xnorm:
                return reason.CONVERGED_SNORM_RELATIVE
            if (
                0 < o.stall_after <= its
                and fnorm > o.stall_factor * r[its - 2]
                and fnorm > o.floor_factor * max(o.atol, o.rtol * r[0])
            ):
                self._stalled = True
                return reason.DIVERGED_DTOL
        if its >= o.max_it:
            return reason.DIVERGED_MAX_IT
        return reason.CONVERGED_ITERATING

    def _in_balance(self) -> bool:
        """Whether every node's out-of-balance force and moment (the residual; at Dirichlet dofs
        it is the distance to the prescribed value, zero after the first iteration) are within
        ``force_tol`` and ``moment_tol``; collective."""
        r = np.abs(self.b.array_r.reshape(-1, 6))
        worst = np.array([r[:, :3].max(initial=0.0), r[:, 3:].max(initial=0.0)])
        comm = self.V.mesh.comm
        if comm.size > 1:
            comm.Allreduce(MPI.IN_PLACE, worst, op=MPI.MAX)
        return bool(worst[0] <= self.options.force_tol and worst[1] <= self.options.moment_tol)

    def _monitor(self, snes, its, norm):
        self._residuals.append(float(norm))
        if self.monitor is not None:
            self.monitor(its, float(norm))

    # -- public API ------------------------------------------------------------------------------
    def solve(self) -> NewtonResult:
        """Run Newton from the current ``w``. On failure ``w`` holds the last iterate."""
        self._residuals = []
        self._stalled = False
        self._cache = None
        t0 = time.perf_counter()
        fem_petsc.assign(self.w, self.x)
        self.snes.solve(None, self.x)
        self.x.ghostUpdate(PETSc.InsertMode.INSERT, PETSc.ScatterMode.FORWARD)
        fem_petsc.assign(self.x, self.w)
        reason = self.snes.getConvergedReason()
        if reason == PETSc.SNES.ConvergedReason.DIVERGED_LINEAR_SOLVE:
            # a failed factorisation leaves the PC failed: without a reset every later solve
            # (after a step cut, from a good state) would fail at once
            self.snes.getKSP().reset()
        converged = reason > 0 and self._small_residual(reason)
        dt = time.perf_counter() - t0
        self.timings["solve"] += dt
        return NewtonResult(
            converged,
            self.snes.getIterationNumber(),
            "DIVERGED_STALLED" if self._stalled else _REASONS.get(reason, str(reason)),
            list(self._residuals),
            dt,
        )

    def _small_residual(self, reason: int) -> bool:
        """Whether PETSc's converged ``reason`` comes with a small residual in physical terms:
        finite unknowns, and on the step-size test (``stol``) a residual within ``floor_factor``
        of the tolerance (the absolute and relative tests imply one by themselves)."""
        r = self._residuals
        if not r or not np.all(np.isfinite(r)) or not self._all_finite():
            return False
        if reason != PETSc.SNES.ConvergedReason.CONVERGED_SNORM_RELATIVE:
            return True
        o = self.options
        return r[-1] <= o.floor_factor * max(o.atol, o.rtol * r[0])

    def _all_finite(self) -> bool:
        """Whether the unknowns are finite on every rank (the same answer on all: collective)."""
        ok = bool(np.all(np.isfinite(self.w.x.array)))
        comm = self.V.mesh.comm
        return comm.allreduce(ok, op=MPI.LAND) if comm.size > 1 else ok

    def stop_requested(self) -> bool:
        """Whether the user asked to stop (``interrupt``) on any rank; collective, so that every
        rank takes the same branch."""
        asked = self.interrupt is not None and self.interrupt.requested
        comm = self.V.mesh.comm
        return comm.allreduce(asked, op=MPI.LOR) if comm.size > 1 else asked

    def destroy(self) -> None:
        """Free the PETSc objects and remove this solver's options from PETSc's database."""
        self._remove_options()
        for obj in (self.snes, self.A, self.b, self.x):
            obj.destroy()

    def _remove_options(self) -> None:
        opts = PETSc.Options()
        for name in getattr(self, "_option_names", ()):
            opts.delValue(name)
        self._option_names = []

    def __del__(self):
        self._remove_options()

    def unconstrained_residual(self) -> npt.NDArray[np.float64]:
        """Residual (internal minus external forces, N and N m) of the current state with no
        Dirichlet condition applied and no pair term masked, as (n_blocks, 6) over the owned
        nodes: at supported dofs it is the support reaction. Uses the pair terms' last
        evaluation when it was at this state (it is after a solve), so their states and
        histories are left as they are."""
        b = fem_petsc.create_vector(self.V)
        with b.localForm() as bl:
            bl.set(0.0)
            arr = bl.array_w
            for idx, f, _, rows, f_rows in self._masked_terms():
                f = f.copy()
                f[rows] = f_rows
                arr += np.bincount(idx.ravel(), weights=f.ravel(), minlength=len(arr))
        fem_petsc.assemble_vector(b, self.F)
        b.ghostUpdate(PETSc.InsertMode.ADD, PETSc.ScatterMode.REVERSE)
        n_owned = self.V.dofmap.index_map.size_local
        out = b.array_r[: 6 * n_owned].reshape(-1, 6).copy()
        b.destroy()
        return out

    def commit(self) -> None:
        """Accept the current state: it becomes the one ``rollback`` returns to."""
        self._saved[:] = self.w.x.array
        for t in self.terms:
            t.commit()

    def rollback(self) -> None:
        """Return to the last committed state (unknowns and term histories)."""
        self.w.x.array[:] = self._saved
        for t in self.terms:
            t.rollback()
        self._cache = None


def _insert_stencils(sp, stencils: npt.NDArray[np.int32]) -> None:
    """Add the k×k node couplings of every stencil row to a dolfinx sparsity pattern (set-up only)."""
    if stencils.shape[1] < 2:
        return
    for row in np.unique(np.sort(stencils, axis=1), axis=0):
        sp.insert(row, row)


@dataclass
class RampState:
    """Where a ramp stands after a converged step: the increment it tries next, and the load
    and unknowns increments (local array) of that step (the secant predictor's), if any."""

    step: float
    previous: tuple[float, npt.NDArray[np.float64]] | None


@dataclass
class StepRecord:
    """One converged load step."""

    stage: str
    load: float
    iterations: int
    residuals: list[float]
    seconds: float
    cuts: int
    #: Newton iterations spent in the attempts that failed before it (the cuts' cost)
    failed_iterations: int = 0


class LoadStepFailure(RuntimeError):
    """A load step did not converge even after the allowed step cuts."""


class RunInterrupted(LoadStepFailure):
    """The user asked the run to stop (Ctrl-C); the last converged state is kept."""


class Interrupt:
    """Ctrl-C as a request to stop: while active (``with Interrupt() as stop:``), a first Ctrl-C
    sets ``requested``: the Newton solve under way stops at its next residual evaluation and the
    load stepper raises ``RunInterrupted`` at the last converged step, so that a run can write
    its summary. A second Ctrl-C interrupts at once (``KeyboardInterrupt``). Outside the main
    thread, where Python cannot handle signals, it does nothing."""

    def __init__(self, stream=None):
        self.requested = False
        self.stream = stream
        self._previous = None

    def _handle(self, signum, frame):
        if self.requested:
            raise KeyboardInterrupt
        self.requested = True
        if self.stream is not None:
            print("\nstrand: interrupted; stopping at the last converged step (Ctrl-C again to "
                  "stop at once)", file=self.stream, flush=True)  # fmt: skip

    def __enter__(self) -> Interrupt:
        if threading.current_thread() is threading.main_thread():
            self._previous = signal.signal(signal.SIGINT, self._handle)
        return self

    def __exit__(self, *exc) -> None:
        if self._previous is not None:
            signal.signal(signal.SIGINT, self._previous)
            self._previous = None


class LoadStepper:
    """Adaptive load stepping: grow the step after easy solves, halve and retry after failures.

    Args:
        solver: the ``NewtonSolver``.
        first_step: initial load increment (in the units of the load parameter).
        min_step: smallest increment tried before giving up.
        max_step: largest increment (default: unbounded).
        growth: factor applied to the increment after a solve of at most ``easy_iterations``.
        on_step: called with each ``StepRecord`` after the step is committed (write outputs there).
        extrapolate: start each Newton solve of a ramp from the linear extrapolation of the
            last two converged states (not across ramps, whose direction may reverse). Off by
            default: the predictor's initial residual scales the relative tolerance ``rtol``, so
            use it with an absolute tolerance that governs.
    """

    def __init__(
        self,
        solver: NewtonSolver,
        first_step: float,
        min_step: float,
        max_step: float | None = None,
        growth: float = 1.5,
        easy_iterations: int = 6,
        on_step: Callable[[StepRecord], None] | None = None,
        extrapolate: bool = False,
    ):
        if not (0 < min_step <= first_step):
            raise ValueError("LoadStepper: need 0 < min_step <= first_step")
        self.solver = solver
        self.step = first_step
        self.min_step = min_step
        self.max_step = max_step if max_step is not None else np.inf
        self.growth = growth
        self.easy_iterations = easy_iterations
        self.on_step = on_step
        self.extrapolate = extrapolate
        self.history: list[StepRecord] = []
        #: the ramp's state after its last converged step (``ramp(resume=...)`` continues it)
        self.state: RampState | None = None

    def ramp(
        self,
        set_load: Callable[[float], None],
        start: float,
        end: float,
        stage: str = "load",
        resume: RampState | None = None,
    ):
        """Move the load parameter from ``start`` to ``end``; returns the records of this ramp.
        ``resume``: continue a ramp from one of its converged steps (``RampState``, as
        ``self.state`` held it there), so that the steps taken are those of the whole ramp."""
        records = []
        sign = 1.0 if end >= start else -1.0
        current = start
        step = min(self.step, self.max_step)
        cuts, failed = 0, 0  # step cuts and their Newton iterations since the last success
        w = self.solver.w.x.array
        previous = None  # (load increment, unknowns increment) of the last step of this ramp
        if resume is not None:
            step, previous = resume.step, resume.previous
        while sign * (end - current) > 1e-12 * max(1.0, abs(end)):
            if self.solver.stop_requested():
                raise RunInterrupted(
                    f"{stage}: interrupted by the user at {current:.6g} (target {end:.6g}). "
                    "The state at the last converged load is kept and was written."
                )
            trial = current + sign * min(step, abs(end - current))
            set_load(trial)
            start_w = w.copy()
            if self.extrapolate and previous is not None:  # secant predictor along the ramp
                w += (trial - current) / previous[0] * previous[1]
            result = self.solver.solve()
            if result.converged:
                previous = (trial - current, w - start_w)
                self.solver.commit()
                rec = StepRecord(
                    stage, trial, result.iterations, result.residuals, result.seconds, cuts,
                    failed,
                )  # fmt: skip
                current = trial
                if result.iterations <= self.easy_iterations:
                    step = min(step * self.growth, self.max_step)
                cuts, failed = 0, 0
                self.state = RampState(step, previous)
                records.append(rec)
                self.history.append(rec)
                if self.on_step is not None:
                    self.on_step(rec)
            else:
                self.solver.rollback()
                set_load(current)
                if self.solver.stop_requested():
                    continue  # not a failure: stop at the top of the loop
                step /= 2
                cuts += 1
                failed += result.iterations
                if step < self.min_step:
                    raise LoadStepFailure(
                        f"{stage}: no convergence from {current:.6g} towards {trial:.6g} "
                        f"after {cuts} step cuts (increment now {step:.3g} < min_step "
                        f"{self.min_step:.3g}; last Newton: {result.reason}, "
                        f"{result.iterations} iterations, residual {result.residual:.3e}). "
                        "The state at the last converged load is kept and was written."
                    )
        self.step = step
        return records
