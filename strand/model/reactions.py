"""The strand's own reactions at its two end sections: tension, torque and bending moments.

At a converged state the unconstrained residual r (``NonlinearProblem.unconstrained_residual``)
is, node by node, the strand's internal force (wires and contacts) plus the residual of the
set-up's own pair terms (end links, nodal loads, a core strut): r = f_strand + f_setup, with r
the support's reaction at a supported dof and zero (within Newton's tolerance) elsewhere. At
every node of an end section, f_strand = r − f_setup is the force the end section (its supports,
links and loads together) applies to the strand, whatever the set-up; r is taken as zero at the
free dofs, its value at equilibrium. Summed over the section's wire
ends, about the core's current end point, it gives the end's force and couple. For the saddle
test under tension alone, the end tension equals the applied one and the two torques are equal
and opposite (tests/test_reactions.py). Units: N, N m.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt
from dolfinx.fem import petsc as fem_petsc
from petsc4py import PETSc

from ..beam.records import quantity
from ..solver.terms import PairAssembler

__all__ = ["EndReactions", "ReactionGauge", "end_reactions"]

Array = npt.NDArray[np.float64]


@dataclass(frozen=True)
class EndReactions:
    """What the end sections apply to the strand: at z = 0 (``_0``) and z = L (``_L``), the
    tension (the pull along the outward normal, −z at z = 0 and +z at z = L), the torque
    about +z and the bending moments about the global x and y axes through the core's current
    end point. Under tension alone both tensions equal the applied one and the two torques (and
    moments) are equal and opposite."""

    end_tension_0: float = quantity("N", "pull of the end section z = 0 on the strand, along −z")
    end_tension_L: float = quantity("N", "pull of the end section z = L on the strand, along +z")
    end_torque_0: float = quantity("Nm", "couple of the end z = 0 on the strand about +z")
    end_torque_L: float = quantity("Nm", "couple of the end z = L on the strand about +z")
    end_moment_x_0: float = quantity("Nm", "couple of the end z = 0 about x (core end point)")
    end_moment_y_0: float = quantity("Nm", "couple of the end z = 0 about y (core end point)")
    end_moment_x_L: float = quantity("Nm", "couple of the end z = L about x (core end point)")
    end_moment_y_L: float = quantity("Nm", "couple of the end z = L about y (core end point)")


def end_resultant(ends: npt.ArrayLike, positions: Array, forces: Array) -> tuple[Array, Array]:
    """Force (3,) and couple (3,) about ``positions[ends[0]]`` (the core's end) of the nodal
    forces and moments ``forces`` (N, 6) on the points ``ends``."""
    ends = np.asarray(ends)
    f = forces[ends]
    lever = positions[ends] - positions[ends[0]]
    return f[:, :3].sum(axis=0), (np.cross(lever, f[:, :3]) + f[:, 3:]).sum(axis=0)


def end_reactions(model, strand_forces: Array) -> EndReactions:
    """The ``EndReactions`` of ``model`` (a ``StrandModel``) from the strand's own nodal forces
    ``strand_forces`` (N, 6) in the geometry's point order."""
    x = model.positions()
    f0, m0 = end_resultant(model.wire_ends(0), x, strand_forces)
    fL, mL = end_resultant(model.wire_ends(1), x, strand_forces)
    return EndReactions(
        -float(f0[2]),
        float(fL[2]),
        float(m0[2]),
        float(mL[2]),
        float(m0[0]),
        float(m0[1]),
        float(mL[0]),
        float(mL[1]),
    )


class ReactionGauge:
    """Measures a ``StrandProblem``'s ``EndReactions``: the unconstrained residual at the
    supported dofs (the supports' reactions; zero elsewhere, its value at equilibrium, so that
    Newton's leftover at free dofs stays out), less the set-up's pair terms evaluated at the
    current state."""

    def __init__(self, problem):
        self.problem = problem
        self._setup_terms = PairAssembler(problem.setup.terms, [], problem.V)
        V = problem.V
        n_local = V.dofmap.index_map.size_local + V.dofmap.index_map.num_ghosts
        supported = np.zeros(6 * n_local)
        for bc in problem.setup.bcs:
            supported[bc.dof_indices()[0]] = 1.0
        n_owned = V.dofmap.index_map.size_local
        #: (N, 6) 1 at the supported dofs, 0 elsewhere, in the geometry's point order
        self.supported = problem.model.gather_nodes(supported[: 6 * n_owned].reshape(-1, 6))

    def setup_forces(self) -> Array:
        """The set-up's pair terms' residual (N, 6), in the geometry's point order (every rank;
        collective)."""
        V = self.problem.V
        b = fem_petsc.create_vector(V)
        with b.localForm() as local:
            local.set(0.0)
            wl = self.problem.model.w.x.array
            evaluated = self._setup_terms.evaluate(wl, {"terms": 0.0})
            self._setup_terms.add_residuals(local.array_w, evaluated)
        b.ghostUpdate(PETSc.InsertMode.ADD, PETSc.ScatterMode.REVERSE)
        n_owned = V.dofmap.index_map.size_local
        out = b.array_r[: 6 * n_owned].reshape(-1, 6).copy()
        b.destroy()
        return self.problem.model.gather_nodes(out)

    def measure(self, residual: Array) -> EndReactions:
        """The reactions at the current state, given the unconstrained residual (N, 6) in the
        geometry's point order (``StepContext.residual``)."""
        return end_reactions(self.problem.model, self.supported * residual - self.setup_forces())
