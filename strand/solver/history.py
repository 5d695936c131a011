"""The state of a history-dependent law, committed after converged steps only.

A plasticity law (or damage, or any law with internal variables) computes its stresses from the
current unknowns *and* the state of the last converged step: the plastic curvature κ_p of each
section, say. That state must change only once a step has converged: ``LoadStepper`` tries a
step, and rolls back an attempt that fails (or that its error control rejects) before trying a
smaller one, so a state updated during Newton's iterations would keep what a discarded attempt
did to it.

``NonlinearProblem(..., history=[...])`` takes objects of the ``HistoryState`` protocol: their
``commit()`` is called once per converged step, after the unknowns are saved (by
``NonlinearProblem.commit``, which ``LoadStepper`` and ``DisplacementControl`` call), and their
``rollback()`` whenever the problem returns to its last committed state. Unlike ``PairTerms``
they add nothing to the residual.

``InternalVariables`` is the usual case: dolfinx functions (DG0 or quadrature, one value per
Gauss point) that hold the committed state, each updated at commit from a UFL expression of the
converged unknowns and the committed state (the return map's result). The residual uses the
committed state, so Newton never changes it:

>>> kappa_p = fem.Function(fem.functionspace(mesh, ("DG", 0, (2,))))  # doctest: +SKIP
>>> plastic = InternalVariables({kappa_p: beam.plastic_curvature()})  # doctest: +SKIP
>>> NonlinearProblem(beam.residual(), w, bcs, history=[plastic])  # doctest: +SKIP

``demos/demo_plastic_bending.py`` bends a wire past yield with it and checks its residual
curvature against the closed form.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Protocol

import numpy as np
import ufl
from dolfinx import fem

__all__ = ["HistoryState", "InternalVariables"]


class HistoryState(Protocol):
    """A state that follows the converged steps: ``commit()`` accepts the current (converged)
    state as the one the next step starts from; ``rollback()`` returns to the last accepted one.
    ``NonlinearProblem.commit`` calls ``commit`` once per converged step, after saving the
    unknowns (so ``commit`` may read them); ``NonlinearProblem.rollback`` calls ``rollback``
    after restoring them."""

    def commit(self) -> None: ...

    def rollback(self) -> None: ...


class InternalVariables:
    """Internal variables held by dolfinx functions, each updated at every converged step from
    a UFL expression: ``updates`` maps each function to its new value, an expression of the
    unknowns and of the functions' committed values (e.g. κ_p + Δκ_p of a return map).

    ``commit`` evaluates every expression at the functions' interpolation points (a DG0
    function: the cell midpoints, the Gauss point of the beam's one-point rule) before assigning
    any, so that each sees the others' committed values, then keeps a copy; ``rollback`` puts
    that copy back (the functions as the last converged step left them, whatever was written
    into them since). Units: those of the functions.
    """

    def __init__(self, updates: Mapping[fem.Function, ufl.core.expr.Expr]):
        self.functions = list(updates)
        self._expressions = [
            fem.Expression(expr, f.function_space.element.interpolation_points)
            for f, expr in updates.items()
        ]
        self._scratch = [fem.Function(f.function_space) for f in self.functions]
        self._committed = [f.x.array.copy() for f in self.functions]
        #: converged steps committed so far
        self.commits = 0

    def commit(self) -> None:
        """Evaluate every update at the current unknowns, then make them the committed state."""
        for scratch, expression in zip(self._scratch, self._expressions, strict=True):
            scratch.interpolate(expression)  # every local cell, ghosts included
        for f, scratch, saved in zip(self.functions, self._scratch, self._committed, strict=True):
            f.x.array[:] = scratch.x.array
            f.x.scatter_forward()  # ghosts as their owners computed them
            saved[:] = f.x.array
        self.commits += 1

    def rollback(self) -> None:
        """Return every function to its value at the last commit (at construction: as given)."""
        for f, saved in zip(self.functions, self._committed, strict=True):
            f.x.array[:] = saved

    def committed(self) -> list[np.ndarray]:
        """Copies of the committed values, one local array per function (ghosts included)."""
        return [a.copy() for a in self._committed]
