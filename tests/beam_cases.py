"""Small beam problems shared by the tests: a cantilever with loads at its tip."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import ufl
from dolfinx import fem
from dolfinx import mesh as dmesh
from mpi4py import MPI

from forms import CircularSection, ReissnerBeam, moment_virtual_work
from strand.cable.mesh import beam_space, straight_beam_mesh
from strand.solver import NewtonOptions, NonlinearProblem

D, E, NU = 0.01, 210e9, 0.3  # m, Pa, -


@dataclass
class Cantilever:
    mesh: object
    V: object
    w: fem.Function
    beam: ReissnerBeam
    force: fem.Constant  # spatial tip force (N)
    moment: fem.Constant  # spatial tip moment (N m)
    solver: NonlinearProblem
    tip_block: int
    length: float

    @property
    def tip_u(self) -> np.ndarray:
        return self.w.x.array.reshape(-1, 6)[self.tip_block, :3]

    @property
    def tip_theta(self) -> np.ndarray:
        return self.w.x.array.reshape(-1, 6)[self.tip_block, 3:]


def cantilever(
    n_cells: int,
    length: float = 1.0,
    direction=(1.0, 0.0, 0.0),
    terms=(),
    options=None,
    section: CircularSection | None = None,
) -> Cantilever:
    """Clamped at the origin, free end at ``length * direction``; tip force and moment constants.
    The section defaults to steel of diameter ``D``."""
    d = np.asarray(direction, float) / np.linalg.norm(direction)
    mesh = straight_beam_mesh(MPI.COMM_WORLD, length, n_cells, direction=d)
    V = beam_space(mesh)
    w = fem.Function(V, name="w")
    beam = ReissnerBeam(w, section or CircularSection(D, E, NU))
    force = fem.Constant(mesh, np.zeros(3))
    moment = fem.Constant(mesh, np.zeros(3))
    at_tip = lambda x: np.isclose(x.T @ d, length)  # noqa: E731
    at_root = lambda x: np.isclose(np.linalg.norm(x, axis=0), 0.0)  # noqa: E731
    tip = dmesh.locate_entities_boundary(mesh, 0, at_tip)
    root = dmesh.locate_entities_boundary(mesh, 0, at_root)
    tags = dmesh.meshtags(mesh, 0, tip, np.ones_like(tip))
    ds = ufl.Measure("ds", mesh, subdomain_data=tags)
    v = ufl.TestFunction(V)
    v_u = ufl.as_vector([v[i] for i in range(3)])
    v_t = ufl.as_vector([v[i] for i in range(3, 6)])
    tip_moment = moment_virtual_work(moment, beam.theta, v_t) * ds(1)
    F = beam.residual(v) - ufl.dot(force, v_u) * ds(1) - tip_moment
    # the tip force does not depend on w: without it the tangent is the same form as that of a
    # cantilever under a tip moment alone (demo_cantilever_rollup), one compiled kernel for both
    J = ufl.derivative(beam.residual(v) - tip_moment, w)
    bc = fem.dirichletbc(np.zeros(6), fem.locate_dofs_topological(V, 0, root), V)
    solver = NonlinearProblem(F, w, [bc], terms=terms, J=J, options=options or NewtonOptions())
    tip_block = int(fem.locate_dofs_topological(V, 0, tip)[0])
    return Cantilever(mesh, V, w, beam, force, moment, solver, tip_block, length)


def section_stiffness():
    A, I = np.pi * D**2 / 4, np.pi * D**4 / 64  # noqa: E741
    G = E / (2 * (1 + NU))
    return {"EA": E * A, "EI": E * I, "GJ": G * 2 * I}
