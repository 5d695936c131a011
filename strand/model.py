"""The strand model: every wire a Reissner beam, the contact pairs between them — no supports and
no loads (those belong to a test set-up, ``strand.setups``).

``StrandModel`` owns the dolfinx mesh, the unknown w = (u, θ) per node, the layer sections, the beam
forms and the contact groups; it reports positions, wire ends and pair results in the geometry's
order. Units: m, N, Pa, rad.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

import strand  # noqa: F401

import dolfinx  # isort: skip
from dolfinx import fem  # isort: skip
from mpi4py import MPI  # isort: skip

from forms import CircularSection, ReissnerBeam  # isort: skip

from .contact.element import ContactSettings  # isort: skip
from .contact.strand_pairs import contact_groups  # isort: skip
from .contact.sliding import sliding_groups  # isort: skip
from .geometry import StrandGeometry  # isort: skip
from .mesh import CableMesh, beam_space, cable_mesh, input_to_block  # isort: skip
from .output import cell_function  # isort: skip

__all__ = ["StrandModel", "layer_section"]

Array = npt.NDArray[np.float64]


def layer_section(cmesh: CableMesh) -> CircularSection:
    """Circular sections with the diameter and elastic constants of each cell's layer (DG0)."""
    g = cmesh.geometry
    wires = [lay.wire for lay in g.cable.layers]
    values = {
        name: cell_function(cmesh.mesh, np.array([get(w) for w in wires])[g.cell_layer], name)
        for name, get in (("d", lambda w: w.diameter), ("E", lambda w: w.E), ("nu", lambda w: w.nu))
    }
    return CircularSection(values["d"], values["E"], values["nu"])


class StrandModel:
    """The wires of ``geometry`` as Reissner beams in one dolfinx mesh, and their contact pairs.

    Args:
        geometry: the strand (``build_geometry``).
        contact: contact settings (normal, penalties, friction, small or large sliding).
    """

    def __init__(
        self,
        geometry: StrandGeometry,
        contact: ContactSettings | None = None,
        comm: MPI.Comm = MPI.COMM_WORLD,
    ):
        self.geometry = geometry
        self.contact_settings = cs = contact or ContactSettings()
        self.cmesh = cable_mesh(geometry, comm)
        self.V = beam_space(self.cmesh.mesh)
        self.w = fem.Function(self.V, name="w")
        self.section = layer_section(self.cmesh)
        self.beam = ReissnerBeam(self.w, self.section)
        self.i2b = input_to_block(self.V)
        if cs.model == "large":
            self.contact = sliding_groups(geometry, self.i2b, cs)
        else:
            self.contact = contact_groups(geometry, self.i2b, cs)

    @property
    def nodal(self) -> Array:
        """(n_blocks, 6) nodal unknowns (u in m, θ in rad)."""
        return self.w.x.array.reshape(-1, 6)

    def positions(self) -> Array:
        """Current positions (m) of the geometry's points, in the geometry's order (N, 3)."""
        g = self.geometry
        return g.points + self.nodal[self.i2b[np.arange(len(g.points))], :3]

    def wire_ends(self, end: int) -> npt.NDArray[np.int64]:
        """Input indices of every wire's first (``end`` = 0, z = 0) or last (1, z = L) point; the
        core's comes first."""
        offsets = self.geometry.wire_offsets
        ends = offsets[:-1] if end == 0 else offsets[1:] - 1
        z = 0.0 if end == 0 else self.geometry.length
        assert np.allclose(self.geometry.points[ends, 2], z)
        return ends

    def end_vertices(self, end: int) -> npt.NDArray[np.int32]:
        """Mesh vertices of the end section z = 0 (``end`` = 0) or z = L (1)."""
        mesh = self.cmesh.mesh
        L = self.geometry.length
        z = 0.0 if end == 0 else L
        mesh.topology.create_connectivity(0, 1)
        return dolfinx.mesh.locate_entities(mesh, 0, lambda p: np.abs(p[2] - z) < 1e-9 * L)

    def core_points(self) -> npt.NDArray[np.int64]:
        """Input indices of the core's points, from z = 0 to L."""
        offsets = self.geometry.wire_offsets
        return np.arange(offsets[0], offsets[1])

    def pair_results(self) -> dict[str, Array]:
        """Per geometry pair: gap (m), normal force (N), traction magnitude (N), slipping flag,
        and the vectors (P, 3) of the friction force ``friction`` (N, on a), the normal a → b
        ``normal``, and the friction history since t = 0 (``FrictionHistory``): ``slip`` and
        ``sliding`` (m), with the dissipated energy ``work`` (J)."""
        n = len(self.geometry.pairs)
        out = {k: np.zeros(n) for k in ("gap", "force", "traction", "work")}
        out["slipping"] = np.zeros(n, dtype=bool)
        for k in ("friction", "normal", "slip", "sliding"):
            out[k] = np.zeros((n, 3))
        for g in self.contact:
            s, h = g.state, g.history
            out["gap"][g.index] = s.gap
            out["force"][g.index] = s.force
            out["traction"][g.index] = np.linalg.norm(s.traction, axis=1)
            out["slipping"][g.index] = s.slipping
            out["friction"][g.index] = s.traction
            out["normal"][g.index] = s.normal
            out["slip"][g.index] = h.slip
            out["sliding"][g.index] = h.sliding
            out["work"][g.index] = h.work
        return out
