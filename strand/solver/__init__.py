"""Newton's method (PETSc SNES, MUMPS LU) and load stepping for UFL beams plus pair terms.

The beam lives in UFL; contact pairs, penalty links and nodal loads do not. They enter through the
``PairTerms`` protocol: each term set owns a fixed array of node stencils and returns, for the
current state, all its residual vectors and tangent blocks at once (numpy arrays).
``NonlinearProblem`` is dolfinx's (``dolfinx.fem.petsc.NonlinearProblem``: its
``petsc_options_prefix``, ``petsc_options`` and ``.solver`` SNES), extended as dolfinx_mpc extends
it. It

* extends the sparsity pattern of the UFL Jacobian with the stencils, once,
* adds the stencil residuals into the ghosted residual vector and the blocks into the matrix that
  dolfinx assembled (one ``setValuesLocalRCV`` call per term set),
* masks Dirichlet dofs, lifting the stencils' coupling to prescribed motions onto the free
  rows (as dolfinx's ``apply_lifting`` does for the forms),
* decides convergence by PETSc's default rules, then strand's stall and balance tests
  (``NewtonOptions``: both off by default, on in strand's own runs), and
* keeps the last converged state so that a failed step can be rolled back (``LoadStepper``),
  with the state of a history-dependent law (``history=``: ``HistoryState`` objects such as
  ``InternalVariables``, a plastic curvature say), committed once per converged step.

Modules: ``terms`` (the pair terms and their assembly), ``history`` (the committed state of a
history-dependent law), ``convergence`` (Newton's settings and tests), ``problem``
(``NonlinearProblem``), ``stepping`` (``LoadStepper`` and its records), ``stabilisation``
(contact springs for a step that would not converge), ``interrupt`` (Ctrl-C), ``ordering`` (the
MUMPS ordering that fills least), ``memory`` (freed memory kept for the next factorisation).
"""

from .convergence import NewtonConvergence, NewtonOptions, NewtonResult
from .history import HistoryState, InternalVariables
from .interrupt import Interrupt
from .memory import keep_freed_memory
from .problem import NonlinearProblem
from .stabilisation import Stabiliser
from .stepping import (
    ErrorControl,
    LoadStepFailure,
    LoadStepper,
    RampState,
    RunInterrupted,
    StepRecord,
)
from .terms import NodalLoad, PairTerms

__all__ = [
    "NonlinearProblem",
    "PairTerms",
    "NodalLoad",
    "HistoryState",
    "InternalVariables",
    "NewtonOptions",
    "NewtonResult",
    "NewtonConvergence",
    "LoadStepper",
    "ErrorControl",
    "StepRecord",
    "RampState",
    "LoadStepFailure",
    "RunInterrupted",
    "Stabiliser",
    "Interrupt",
    "keep_freed_memory",
]
