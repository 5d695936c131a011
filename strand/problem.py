"""The strand tension–bending problem: wires as Reissner beams, contact pairs, end section, loads.

Set-up (physics.md B): end z = 0 clamped; end z = L a rigid section that keeps all wire ends in one
plane, free to move axially and held against every rotation; the tension is a force on that section
(a pilot node, the core's end, tied to the other wire ends by stiff penalty links on u_z); the lateral
load P is a saddle at midspan: inward radial forces on the outer-layer nodes of the pressed face,
weighted so that they sum to exactly P along the load direction. Units: m, N, Pa.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np
import numpy.typing as npt

import strand  # noqa: F401

import dolfinx  # isort: skip
from dolfinx import fem  # isort: skip
from mpi4py import MPI  # isort: skip

from forms import CircularSection, ReissnerBeam  # isort: skip

from .contact.element import ContactSettings, contact_groups  # isort: skip
from .contact.sliding import sliding_groups  # isort: skip
from .geometry import StrandGeometry  # isort: skip
from .mesh import CableMesh, beam_space, cable_mesh, input_to_block  # isort: skip
from .output import cell_function  # isort: skip
from .solver import NewtonOptions, NewtonSolver, NodalLoad  # isort: skip

__all__ = ["PenaltyLinks", "saddle_weights", "layer_section", "StrandProblem"]

Array = npt.NDArray[np.float64]


class PenaltyLinks:
    """Penalty ties u_c(b) = u_c(a) between node pairs (a, b) on one displacement component c.

    A ``PairTerms`` with constant 12×12 blocks: residual k(u_b − u_a)(−1, +1) on component c.
    """

    def __init__(self, pairs: npt.ArrayLike, stiffness: float, component: int = 2):
        self.stencils = np.asarray(pairs, dtype=np.int32).reshape(-1, 2)
        self.k = stiffness
        self.c = component
        K = np.zeros((12, 12))
        i, j = component, 6 + component
        K[i, i] = K[j, j] = stiffness
        K[i, j] = K[j, i] = -stiffness
        self._K = np.broadcast_to(K, (len(self.stencils), 12, 12))

    def evaluate(self, w, jacobian):
        du = w[self.stencils[:, 1], self.c] - w[self.stencils[:, 0], self.c]
        f = np.zeros((len(du), 12))
        f[:, self.c] = -self.k * du
        f[:, 6 + self.c] = self.k * du
        return f, (self._K.copy() if jacobian else None)

    def commit(self) -> None:
        pass

    def rollback(self) -> None:
        pass


def saddle_weights(points: Array, direction: Array) -> tuple[npt.NDArray[np.intp], Array]:
    """Nodes and nodal force vectors (per unit load) of a saddle pressing along ``direction``.

    ``points`` (n, 3) are candidate outer-layer nodes. The pressed ones are those on the face the
    load comes from (inward radial direction e_i with cosψ_i = e_i·direction > 0). Their forces
    w_i e_i use w_i = cosψ_i (α + β sinψ_i), with α, β such that Σ w_i e_i = direction exactly:
    no net force across the load direction.
    """
    d = np.asarray(direction, float)
    d = d / np.linalg.norm(d)
    radial = points.copy()
    radial[:, 2] = 0.0
    inward = -radial / np.linalg.norm(radial, axis=1)[:, None]
    side = np.cross([0.0, 0.0, 1.0], d)
    cos_psi, sin_psi = inward @ d, inward @ side
    pressed = np.flatnonzero(cos_psi > 1e-12)
    if len(pressed) < 2:
        raise ValueError("the saddle covers fewer than two outer-layer nodes; lengthen it")
    c, s = cos_psi[pressed], sin_psi[pressed]
    A = np.array([[np.sum(c * c), np.sum(c * c * s)], [np.sum(c * s), np.sum(c * s * s)]])
    alpha, beta = np.linalg.solve(A, [1.0, 0.0])
    weights = c * (alpha + beta * s)
    return pressed, weights[:, None] * inward[pressed]


def layer_section(cmesh: CableMesh) -> CircularSection:
    """Circular sections with the diameter and elastic constants of each cell's layer (DG0)."""
    g = cmesh.geometry
    wires = [lay.wire for lay in g.cable.layers]
    values = {
        name: cell_function(cmesh.mesh, np.array([get(w) for w in wires])[g.cell_layer], name)
        for name, get in (("d", lambda w: w.diameter), ("E", lambda w: w.E), ("nu", lambda w: w.nu))
    }
    return CircularSection(values["d"], values["E"], values["nu"])


@dataclass
class StrandLoads:
    """Load handles: tension on the pilot (N) and the saddle for each sign of P (N)."""

    tension: NodalLoad
    saddle_positive: NodalLoad
    saddle_negative: NodalLoad


class StrandProblem:
    """A strand of ``geometry`` under end tension and a midspan saddle load.

    Args:
        geometry: the strand (``build_geometry``).
        contact: contact settings (normal, penalties, friction).
        options: Newton settings.
        saddle_length: axial length of the saddle centred at midspan, m.
        direction: direction of a positive lateral load.
        link_stiffness: penalty of the rigid-end links, N/m.
    """

    def __init__(
        self,
        geometry: StrandGeometry,
        contact: ContactSettings | None = None,
        options: NewtonOptions | None = None,
        saddle_length: float = 0.02,
        direction=(1.0, 0.0, 0.0),
        link_stiffness: float = 1e11,
        comm: MPI.Comm = MPI.COMM_WORLD,
        monitor=None,
    ):
        self.geometry = geometry
        self.contact_settings = contact or ContactSettings()
        self.cmesh = cable_mesh(geometry, comm)
        mesh = self.cmesh.mesh
        self.V = V = beam_space(mesh)
        self.w = fem.Function(V, name="w")
        self.section = layer_section(self.cmesh)
        self.beam = ReissnerBeam(self.w, self.section)
        self.i2b = i2b = input_to_block(V)
        L = geometry.length
        self.direction = np.asarray(direction, float) / np.linalg.norm(direction)

        # ends: z = 0 clamped; z = L: only u_z free, tied to the pilot (the core's end node)
        tol = 1e-9 * L
        mesh.topology.create_connectivity(0, 1)
        start = dolfinx.mesh.locate_entities(mesh, 0, lambda p: np.abs(p[2]) < tol)
        end = dolfinx.mesh.locate_entities(mesh, 0, lambda p: np.abs(p[2] - L) < tol)
        bcs = [fem.dirichletbc(np.zeros(6), fem.locate_dofs_topological(V, 0, start), V)]
        for i in (0, 1, 3, 4, 5):
            Vi = V.sub(i)
            bcs.append(fem.dirichletbc(0.0, fem.locate_dofs_topological(Vi, 0, end), Vi))
        self.bcs = bcs
        ends = geometry.wire_offsets[1:] - 1  # last point of each wire, at z = L
        assert np.allclose(geometry.points[ends, 2], L)
        self.pilot = int(i2b[ends[0]])
        self.links = PenaltyLinks(
            np.column_stack([np.full(len(ends) - 1, self.pilot), i2b[ends[1:]]]), link_stiffness
        )

        # loads
        tension = NodalLoad([self.pilot], [[0, 0, 1.0, 0, 0, 0]])
        outer_layer = len(geometry.cable.layers) - 1
        outer = np.flatnonzero(geometry.wire_layer[geometry.point_wire] == outer_layer)
        near = outer[np.abs(geometry.points[outer, 2] - L / 2) <= saddle_length / 2 + 1e-12]
        saddles = []
        for sign in (1.0, -1.0):
            idx, forces = saddle_weights(geometry.points[near], sign * self.direction)
            values = np.zeros((len(idx), 6))
            values[:, :3] = sign * forces  # per unit signed load P
            saddles.append(NodalLoad(i2b[near[idx]], values))
        self.loads = StrandLoads(tension, *saddles)

        cs = self.contact_settings
        if cs.model == "large":
            self.contact = sliding_groups(
                geometry, i2b, cs.k_point, cs.k_line, cs.g_lim, cs.friction, cs.reach
            )
        else:
            self.contact = contact_groups(geometry, i2b, cs)
        # MUMPS ordering: PORD factorises the Cardinal tangent in 0.53 s against 0.71 s for the
        # default choice (METIS), the same accuracy (2-core machine, 129,492 unknowns)
        options = options or NewtonOptions()
        options = replace(options, petsc={"mat_mumps_icntl_7": 4, **options.petsc})
        terms = [*self.contact, self.links, tension, *saddles]
        self.solver = NewtonSolver(
            self.beam.residual(), self.w, bcs, terms=terms, options=options, monitor=monitor
        )
        # midspan core nodes, for the deflection
        core = np.arange(geometry.wire_offsets[0], geometry.wire_offsets[1])
        self._mid_core = i2b[core[np.argmin(np.abs(geometry.points[core, 2] - L / 2))]]

    # -- loads -------------------------------------------------------------------------------------
    def set_tension(self, T: float) -> None:
        """Axial force on the end section, N."""
        self.loads.tension.factor = T

    def set_lateral(self, P: float) -> None:
        """Lateral saddle load at midspan, N (signed along ``direction``)."""
        self.loads.saddle_positive.factor = max(P, 0.0)
        self.loads.saddle_negative.factor = min(P, 0.0)

    @property
    def tension(self) -> float:
        return self.loads.tension.factor

    @property
    def lateral(self) -> float:
        return self.loads.saddle_positive.factor + self.loads.saddle_negative.factor

    # -- results -----------------------------------------------------------------------------------
    @property
    def nodal(self) -> Array:
        """(n_blocks, 6) nodal unknowns (u in m, θ in rad)."""
        return self.w.x.array.reshape(-1, 6)

    def positions(self) -> Array:
        """Current positions (m) of the geometry's points, in the geometry's order (N, 3)."""
        g = self.geometry
        return g.points + self.nodal[self.i2b[np.arange(len(g.points))], :3]

    def end_displacement(self) -> float:
        """Axial displacement of the end section (the pilot's u_z), m."""
        return float(self.nodal[self.pilot, 2])

    def midspan_deflection(self) -> float:
        """Lateral displacement of the core at midspan along ``direction``, m."""
        return float(self.nodal[self._mid_core, :3] @ self.direction)

    def pair_results(self) -> dict[str, Array]:
        """Gap (m), normal force (N), traction magnitude (N), slipping flag per geometry pair."""
        n = len(self.geometry.pairs)
        out = {k: np.zeros(n) for k in ("gap", "force", "traction")}
        out["slipping"] = np.zeros(n, dtype=bool)
        for g in self.contact:
            s = g.state
            out["gap"][g.index] = s.gap
            out["force"][g.index] = s.force
            out["traction"][g.index] = np.linalg.norm(s.traction, axis=1)
            out["slipping"][g.index] = s.slipping
        return out
