"""The strand model: every wire a Reissner beam, the contact pairs between them — no supports and
no loads (those belong to a test set-up, ``strand.setups``).

``StrandModel`` owns the dolfinx mesh, the unknown w = (u, θ) per node, the layer sections, the beam
forms and the contact groups; it reports positions, wire ends and pair results in the geometry's
order. Units: m, N, Pa, rad.
"""

from __future__ import annotations

from collections.abc import Callable

import dolfinx
import numpy as np
import numpy.typing as npt
from dolfinx import fem
from mpi4py import MPI

from forms import CircularSection, ReissnerBeam

from ..beam.fields import cell_function
from ..beam.partition import DistributionError, owned_rows
from ..cable.centring import ring_centres
from ..cable.geometry import StrandGeometry
from ..cable.mesh import CableMesh, beam_space, cable_mesh, input_to_block
from .contact_settings import ContactSettings
from .layer_states import first_layer_lift
from .pair_results import PairResults
from .same_layer import SameLayerPairs, same_layer_groups, same_layer_pairs
from .strand_contact import (
    contact_groups,
    pair_stencils,
    same_layer_sliding_groups,
    same_layer_windows,
    sliding_groups,
    sliding_windows,
)

__all__ = [
    "BeamFactory",
    "StrandModel",
    "chosen_same_layer_pairs",
    "layer_section",
    "strand_stencils",
]

Array = npt.NDArray[np.float64]

#: builds a strand's beam from its unknown w (the (6,)-valued P1 function of every wire) and the
#: layers' section (``layer_section``): ``ReissnerBeam`` or a law of one's own with its interface
BeamFactory = Callable[[fem.Function, CircularSection], ReissnerBeam]

#: the (P, 3) arrays of ``StrandModel.pair_results``
PAIR_VECTORS = ("friction", "normal", "slip", "sliding")


def layer_section(cmesh: CableMesh) -> CircularSection:
    """Circular sections with the diameter and elastic constants of each cell's layer (DG0):
    d (m), E (Pa), ν, and the cable's ``shear_coefficient`` κ and ``torsional_stiffness`` GJ
    (N m²) where a layer gives them (a layer that does not takes the round section's; neither
    is data of the forms when no layer gives it). Its ``layer`` (DG0) is each cell's layer
    index, 0 the core, for a beam law on some layers only."""
    g = cmesh.geometry
    wires = [lay.wire for lay in g.cable.layers]
    own = [CircularSection(w.diameter, w.E, w.nu) for w in wires]  # the round sections'

    def per_cell(values, name):
        return cell_function(cmesh.mesh, np.array(values, dtype=float)[g.cell_layer], name)

    def option(key, default):
        given = [getattr(w, key) for w in wires]
        if all(v is None for v in given):
            return None
        values = [default(s) if v is None else v for v, s in zip(given, own, strict=True)]
        return per_cell(values, key)

    section = CircularSection(
        per_cell([w.diameter for w in wires], "d"),
        per_cell([w.E for w in wires], "E"),
        per_cell([w.nu for w in wires], "nu"),
        shear_coefficient=option("shear_coefficient", lambda s: s.shear_coefficient),
        torsional_stiffness=option("torsional_stiffness", lambda s: s.GJ),
    )
    section.layer = per_cell(np.arange(len(wires)), "layer")
    return section


def chosen_same_layer_pairs(
    geometry: StrandGeometry, settings: ContactSettings
) -> SameLayerPairs | None:
    """The same-layer pairs ``settings`` choose (``[contact] same_layer``, its stencil and gap
    seed), None when off."""
    if settings.same_layer == "off":
        return None
    return same_layer_pairs(
        geometry, settings.same_layer, settings.same_layer_stencil, seed=settings.gap_seed
    )


def strand_stencils(
    geometry: StrandGeometry,
    settings: ContactSettings,
    same_layer: SameLayerPairs | None = None,
) -> list[npt.NDArray[np.int64]]:
    """Input nodes that a strand's terms couple, anchor first, which a distributed mesh keeps
    whole on the rank owning the anchor (``cable_mesh``): the contact pairs' (small or large
    sliding; the same-layer pairs ``same_layer``, default: those ``settings`` choose), and each
    end section (the core's end, then every other wire end), which the set-ups tie to a pilot;
    with a core that touches no wire (a vaulted first layer), each core node and its first
    layer's centre (``ring_centres``), which the bending set-ups tie together."""
    if settings.model == "large":
        out = [nodes for _, nodes, _, _ in sliding_windows(geometry, settings.reach)]
    else:
        out = [pair_stencils(geometry)]
    pairs = same_layer if same_layer is not None else chosen_same_layer_pairs(geometry, settings)
    if pairs is not None:
        if settings.model == "large":
            out += [w.nodes for w in same_layer_windows(geometry, pairs, settings.reach)]
        else:
            out.append(pairs.stencils)
    if first_layer_lift(geometry.cable, settings.first_layer) > 0:  # a core that touches none
        out.append(ring_centres(geometry).stencils)  # the bending set-ups hold it centred
    offsets = geometry.wire_offsets
    return out + [offsets[:-1][None, :], (offsets[1:] - 1)[None, :]]


class StrandModel:
    """The wires of ``geometry`` as Reissner beams in one dolfinx mesh, and their contact pairs.

    Args:
        geometry: the strand (``build_geometry``).
        contact: contact settings (normal, penalties, friction, small or large sliding).
        comm: the ranks the mesh is distributed over.
        beam: the beam law of every wire, called once as ``beam(w, section)`` with the unknown
            ``w`` of the whole strand and the layers' section (``layer_section``: cell-wise d,
            E, ν, κ, GJ and ``layer``); default ``ReissnerBeam``. A law of one's own subclasses
            ``ReissnerBeam`` (``forms``' "what to override"); its ``residual()`` is the wires'
            part of the problem, its ``N`` and ``M`` are what the field files and section cuts
            read. The fatigue stresses (``strand.fatigue.stress``) stay Navier's, of a linear
            elastic round wire.
    """

    def __init__(
        self,
        geometry: StrandGeometry,
        contact: ContactSettings | None = None,
        comm: MPI.Comm = MPI.COMM_WORLD,
        *,
        beam: BeamFactory = ReissnerBeam,
    ):
        self.geometry = geometry
        self.contact_settings = cs = contact or ContactSettings()
        self.comm = comm
        #: contact between neighbouring wires of a layer (``[contact] same_layer``): the pairs
        #: in the geometry's order (None when off) and the group this rank evaluates
        self.same_layer_pairs = chosen_same_layer_pairs(geometry, cs)
        stencils = strand_stencils(geometry, cs, self.same_layer_pairs)
        self.cmesh = cable_mesh(geometry, comm, stencils)
        self.V = beam_space(self.cmesh.mesh)
        self.w = fem.Function(self.V, name="w")
        self.section = layer_section(self.cmesh)
        self.beam = beam(self.w, self.section)
        self._energy_form: fem.Form | None = None  # compiled at the first ``strain_energy``
        self.i2b = input_to_block(self.V)
        #: dof blocks this rank owns (0 … n_owned − 1; ghosts follow), and their input points
        self.n_owned = self.V.dofmap.index_map.size_local
        self.owned_points = np.flatnonzero((self.i2b >= 0) & (self.i2b < self.n_owned))
        owned = self.n_owned if comm.size > 1 else None
        if cs.model == "large":
            self.contact = sliding_groups(geometry, self.i2b, cs, owned)
        else:
            self.contact = contact_groups(geometry, self.i2b, cs, owned)
        builder = same_layer_sliding_groups if cs.model == "large" else same_layer_groups
        self.same_layer = (
            []
            if self.same_layer_pairs is None
            else builder(geometry, self.same_layer_pairs, self.i2b, cs, owned)
        )
        n_pairs = comm.allreduce(sum(len(g.index) for g in self.contact), op=MPI.SUM)
        if n_pairs != len(geometry.pairs):
            raise DistributionError(
                f"{n_pairs} contact pairs evaluated over the ranks instead of "
                f"{len(geometry.pairs)}: each must be evaluated on exactly one"
            )

    def strain_energy(self) -> float:
        """The beams' strain energy at the current unknowns, all ranks (J)."""
        if self._energy_form is None:
            self._energy_form = fem.form(self.beam.energy())
        return self.comm.allreduce(fem.assemble_scalar(self._energy_form), op=MPI.SUM)

    def owned_rows(self, points: npt.ArrayLike, what: str = "terms") -> npt.NDArray[np.intp]:
        """Rows of ``points`` (P, k input node indices, anchor first) that this rank evaluates:
        those whose anchor it owns (``partition.owned_rows``); all rows on one rank."""
        points = np.asarray(points)
        return owned_rows(self.i2b[points], self.n_owned, what)

    def gather_nodes(self, values: Array) -> Array:
        """Nodal values given per local dof block (at least the owned ones, (n, k)) as an
        (N, k) array in the geometry's point order, on every rank."""
        values = np.asarray(values)
        if self.comm.size == 1:
            return values[self.i2b]
        out = np.zeros((len(self.i2b), *values.shape[1:]), dtype=values.dtype)
        out[self.owned_points] = values[self.i2b[self.owned_points]]
        self.comm.Allreduce(MPI.IN_PLACE, out, op=MPI.SUM)
        return out

    def node_values(self) -> Array:
        """(N, 6) nodal unknowns (u in m, θ in rad) in the geometry's point order, every rank."""
        return self.gather_nodes(self.nodal)

    @property
    def nodal(self) -> Array:
        """(n_blocks, 6) nodal unknowns (u in m, θ in rad) of this rank's dof blocks (ghosts
        included); ``node_values`` gives them all in the geometry's order."""
        return self.w.x.array.reshape(-1, 6)

    def positions(self) -> Array:
        """Current positions (m) of the geometry's points, in the geometry's order (N, 3), on
        every rank."""
        return self.geometry.points + self.node_values()[:, :3]

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

    def gather_pairs(
        self,
        per_group: list[dict[str, np.ndarray]],
        shapes: dict[str, tuple] | None = None,
        groups: list | None = None,
        n_pairs: int | None = None,
    ) -> dict[str, Array]:
        """Per-pair arrays of contact groups (a dict per group of ``groups``, default
        ``contact``, first axis its pairs) in their pairs' global order (``n_pairs`` of them,
        default the geometry's), on every rank. ``shapes``: each array's shape beyond the pair
        axis (default: from the groups of every rank; a rank may hold none)."""
        groups = self.contact if groups is None else groups
        if shapes is None:
            shapes = {k: v.shape[1:] for arrays in per_group for k, v in arrays.items()}
            if self.comm.size > 1:
                for other in self.comm.allgather(shapes):
                    shapes.update(other)
        n = len(self.geometry.pairs) if n_pairs is None else n_pairs
        out = {k: np.zeros((n, *shapes[k])) for k in sorted(shapes)}  # one order on every rank
        for g, arrays in zip(groups, per_group, strict=True):
            for k, v in arrays.items():
                out[k][g.index] = v
        if self.comm.size > 1:  # each pair lives on one rank: the sums are exact
            for value in out.values():
                self.comm.Allreduce(MPI.IN_PLACE, value, op=MPI.SUM)
        return out

    def same_layer_history(self) -> dict[str, Array]:
        """The same-layer pairs' history arrays in ``same_layer_pairs`` order, every rank
        (empty without same-layer contact)."""
        if self.same_layer_pairs is None:
            return {}
        arrays = [g.history_arrays() for g in self.same_layer]
        return self.gather_pairs(arrays, groups=self.same_layer, n_pairs=len(self.same_layer_pairs))

    def pair_results(self) -> PairResults:
        """Every geometry pair's gap, forces, slip state and friction history at the current
        state (``PairResults``), on every rank."""
        per_group = []
        for g in self.contact:
            s, h = g.state, g.history
            per_group.append(
                {
                    "gap": s.gap,
                    "force": s.force,
                    "traction": np.linalg.norm(s.traction, axis=1),
                    "work": h.work,
                    "slipping": s.slipping.astype(float),
                    "friction": s.traction,
                    "normal": s.normal,
                    "slip": h.slip,
                    "sliding": h.sliding,
                }
            )
        shapes = {k: () for k in ("gap", "force", "traction", "work", "slipping")}
        out = self.gather_pairs(per_group, shapes | dict.fromkeys(PAIR_VECTORS, (3,)))
        return PairResults(**{**out, "slipping": out["slipping"] > 0.5})
