"""dolfinx meshes of wires: 1D manifolds embedded in 3D, and node ↔ dof-block maps."""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import basix.ufl
import dolfinx
import numpy as np
import numpy.typing as npt
from dolfinx import fem
from mpi4py import MPI

from ..beam.partition import slab_partitioner
from .geometry import StrandGeometry

__all__ = [
    "polyline_mesh",
    "straight_beam_mesh",
    "beam_space",
    "node_to_block",
    "input_to_block",
    "CableMesh",
    "cable_mesh",
    "write_centrelines",
    "geometry_to_gmsh",
    "mesh_from_gmsh",
]


def polyline_mesh(
    comm: MPI.Comm,
    points: npt.ArrayLike,
    cells: npt.ArrayLike,
    partitioner: Callable[..., Any] | None = None,
) -> dolfinx.mesh.Mesh:
    """A mesh of straight two-node cells: ``points`` (N, 3) in m, ``cells`` (E, 2) node indices.

    Rank 0 provides the arrays; other ranks may pass empty ones. Each cell is oriented from its
    first to its second node, which fixes the sign of the tangent.
    """
    x = np.asarray(points, dtype=np.float64).reshape(-1, 3)
    c = np.asarray(cells, dtype=np.int64).reshape(-1, 2)
    if comm.rank != 0:
        x, c = np.zeros((0, 3)), np.zeros((0, 2), dtype=np.int64)
    element = basix.ufl.element("Lagrange", "interval", 1, shape=(3,))
    kwargs: dict[str, Any] = {"partitioner": partitioner} if partitioner is not None else {}
    return dolfinx.mesh.create_mesh(comm, cells=c, x=x, e=element, **kwargs)


def straight_beam_mesh(
    comm: MPI.Comm,
    length: float,
    n_cells: int,
    direction: npt.ArrayLike = (1.0, 0.0, 0.0),
    origin: npt.ArrayLike = (0.0, 0.0, 0.0),
) -> dolfinx.mesh.Mesh:
    """A straight beam of ``length`` (m) split into ``n_cells`` equal cells."""
    s = np.linspace(0.0, length, n_cells + 1)
    d = np.asarray(direction, dtype=float)
    x = np.asarray(origin, dtype=float) + s[:, None] * (d / np.linalg.norm(d))
    cells = np.column_stack([np.arange(n_cells), np.arange(1, n_cells + 1)])
    return polyline_mesh(comm, x, cells)


def beam_space(mesh: dolfinx.mesh.Mesh) -> fem.FunctionSpace:
    """Blocked P1 space of (u, θ) ∈ R⁶ per node."""
    return fem.functionspace(mesh, ("Lagrange", 1, (6,)))


def node_to_block(V: fem.FunctionSpace) -> npt.NDArray[np.int32]:
    """Map local geometry node index → local dof block index (built cellwise, so exact)."""
    mesh = V.mesh
    gdofs = mesh.geometry.dofmaps[0]
    out = np.full(mesh.geometry.x.shape[0], -1, dtype=np.int32)
    out[gdofs] = V.dofmap.list
    return out


def input_to_block(V: fem.FunctionSpace) -> npt.NDArray[np.int32]:
    """Map input point index (row of ``points`` given to ``polyline_mesh``) → local dof block.

    Entries for input points not present on this rank are −1.
    """
    mesh = V.mesh
    igi = np.asarray(mesh.geometry.input_global_indices, dtype=np.int64)
    n_input = mesh.comm.allreduce(int(igi.max(initial=-1)) + 1, op=MPI.MAX)
    out = np.full(n_input, -1, dtype=np.int32)
    out[igi] = node_to_block(V)[: len(igi)]
    return out


@dataclass
class CableMesh:
    """A strand as one dolfinx mesh: cells tagged by wire and layer, pairs by dof block.

    ``wire_tags``/``layer_tags`` are cell ``MeshTags`` (values: wire id, layer id with 0 = core).
    """

    geometry: StrandGeometry
    mesh: dolfinx.mesh.Mesh
    wire_tags: dolfinx.mesh.MeshTags
    layer_tags: dolfinx.mesh.MeshTags

    def pair_blocks(self, V: fem.FunctionSpace) -> npt.NDArray[np.int32]:
        """(P, 2) local dof blocks of the contact pairs' nodes (a, b), robust to node reordering."""
        i2b = input_to_block(V)
        p = self.geometry.pairs
        return np.column_stack([i2b[p.a], i2b[p.b]]).astype(np.int32)


def cable_mesh(
    geometry: StrandGeometry,
    comm: MPI.Comm = MPI.COMM_WORLD,
    stencils: Sequence[npt.ArrayLike] = (),
) -> CableMesh:
    """Build the dolfinx mesh of a ``StrandGeometry`` (rank 0 holds the input arrays). On several
    ranks it is cut in axial slabs, ghosted so that each row of ``stencils`` (input node indices,
    anchor first: contact pairs, end sections) is whole on the rank owning its anchor
    (``strand.beam.partition``)."""
    partitioner = None
    if comm.size > 1:
        partitioner = slab_partitioner(geometry.points[:, 2], geometry.cells, stencils)
    mesh = polyline_mesh(comm, geometry.points, geometry.cells, partitioner)
    n_local = mesh.topology.index_map(1).size_local
    cells = np.arange(n_local, dtype=np.int32)
    original = np.asarray(mesh.topology.original_cell_index)[:n_local]
    wire = dolfinx.mesh.meshtags(mesh, 1, cells, geometry.cell_wire[original].astype(np.int32))
    layer = dolfinx.mesh.meshtags(mesh, 1, cells, geometry.cell_layer[original].astype(np.int32))
    wire.name, layer.name = "wire", "layer"
    return CableMesh(geometry, mesh, wire, layer)


def write_centrelines(geometry: StrandGeometry, path: str | Path) -> None:
    """Export the wire centrelines (polylines with wire and layer cell data) with meshio, for
    other tools; the format follows the file suffix (.vtu, .msh, .xdmf, ...)."""
    import meshio

    meshio.Mesh(
        geometry.points,
        [("line", geometry.cells)],
        cell_data={"wire": [geometry.cell_wire], "layer": [geometry.cell_layer]},
    ).write(str(path))


def geometry_to_gmsh(geometry: StrandGeometry, model: Any = None) -> Any:
    """Put the strand's nodes and cells into a gmsh model as one curve per wire, meshed exactly
    as ``geometry`` (gmsh node tag = input point index + 1), with a physical group per wire
    (tag = wire id + 1, name "wire <w> layer <l>"). Returns the model."""
    import gmsh

    if model is None:
        if not gmsh.isInitialized():
            gmsh.initialize(["-v", "0"])
        model = gmsh.model
    model.add(geometry.cable.name)
    for w, lay in enumerate(geometry.wire_layer):
        s, e = geometry.wire_offsets[w], geometry.wire_offsets[w + 1]
        model.addDiscreteEntity(1, w + 1)
        model.mesh.addNodes(1, w + 1, np.arange(s, e) + 1, geometry.points[s:e].ravel())
        cells = geometry.cells[geometry.cell_wire == w]
        model.mesh.addElementsByType(w + 1, 1, [], (cells + 1).ravel())
        model.addPhysicalGroup(1, [w + 1], w + 1, name=f"wire {w} layer {lay}")
    return model


def mesh_from_gmsh(
    model: Any, comm: MPI.Comm = MPI.COMM_WORLD, rank: int = 0
) -> tuple[dolfinx.mesh.Mesh, dolfinx.mesh.MeshTags]:
    """A user's 1D gmsh model (one physical group per wire) as a dolfinx mesh.

    Returns (mesh, wire_tags) with wire id = physical tag − 1. The mesh's input point index is the
    gmsh node tag − 1, so ``input_to_block`` maps gmsh nodes to dof blocks as for strand's own
    meshes.
    """
    import dolfinx.io.gmsh

    data = dolfinx.io.gmsh.model_to_mesh(model, comm, rank, gdim=3)
    tags = data.cell_tags
    wire = dolfinx.mesh.meshtags(data.mesh, 1, tags.indices, tags.values - 1)
    wire.name = "wire"
    return data.mesh, wire
