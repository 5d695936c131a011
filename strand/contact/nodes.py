"""The nodes of beams in a dolfinx mesh: their positions and neighbours, nodes found at points,
and the values there read on any number of ranks.

Nodes are local dof blocks of the beam space V (dolfinx's blocked P1 space of (u, θ)): what
``fem.locate_dofs_geometrical(V, marker)`` and ``locate_dofs_topological(V, 0, vertices)`` return.
A beam is a chain of cells; its nodes' neighbours along it give the chords that stand for its
tangents (``strand.contact.pairs``). Units: m.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
import numpy.typing as npt
from mpi4py import MPI

if TYPE_CHECKING:
    from dolfinx import fem

__all__ = ["BeamNodes", "beam_nodes", "chains", "dof_values", "input_arrays", "locate_nodes"]

Array = npt.NDArray[np.float64]
Blocks = npt.NDArray[np.int32]


@dataclass(frozen=True)
class BeamNodes:
    """The nodes of a beam mesh: positions (n, 3) in m and, per node, its two neighbours along its
    beam (n, 2) (the node itself at a beam's end), as local dof blocks."""

    positions: Array
    neighbours: Blocks
    cells: Blocks  # (E, 2) the cells as pairs of nodes

    def tangents(self, nodes: npt.NDArray[np.integer]) -> Array:
        """Unit chords x₊ − x₋ between the neighbours of ``nodes`` (P, 3)."""
        nb = self.neighbours[nodes]
        c = self.positions[nb[:, 1]] - self.positions[nb[:, 0]]
        return c / np.linalg.norm(c, axis=1)[:, None]


def beam_nodes(V: fem.FunctionSpace) -> BeamNodes:
    """Positions and neighbours of every node of the beam space ``V`` (blocked P1 on a 1D mesh).

    Raises ``ValueError`` at a node shared by more than two cells (beams meet there: pair such
    beams through contact or links, not through shared nodes).
    """
    x = np.asarray(V.tabulate_dof_coordinates(), dtype=float).reshape(-1, 3)
    return chains(x, np.asarray(V.dofmap.list, dtype=np.int32).reshape(-1, 2))


def chains(x: npt.ArrayLike, cells: npt.ArrayLike) -> BeamNodes:
    """``BeamNodes`` of nodes at ``x`` (n, 3) in m joined by two-node ``cells`` (E, 2), e.g. the
    input arrays of a mesh (``input_arrays``). Raises as ``beam_nodes``."""
    x = np.asarray(x, dtype=float).reshape(-1, 3)
    cells = np.asarray(cells, dtype=np.int32).reshape(-1, 2)
    n = len(x)
    degree = np.bincount(cells.ravel(), minlength=n)
    if degree.max(initial=0) > 2:
        node = int(np.argmax(degree))
        raise ValueError(
            f"node {node} at {np.round(x[node], 6).tolist()} joins {degree[node]} cells: contact "
            "pairs need beams that are chains of cells (no junctions)"
        )
    # a node's first cell gives its neighbour in slot 0, its second cell in slot 1 (ends keep
    # themselves there); the chords' signs are arbitrary but fixed, which is all the element needs
    node = np.concatenate([cells[:, 0], cells[:, 1]])
    other = np.concatenate([cells[:, 1], cells[:, 0]])
    order = np.argsort(node, kind="stable")
    node, other = node[order], other[order]
    second = np.concatenate([[False], node[1:] == node[:-1]])
    neighbours = np.repeat(np.arange(n, dtype=np.int32)[:, None], 2, axis=1)
    neighbours[node, second.astype(np.intp)] = other
    return BeamNodes(x, neighbours, cells)


def _chunks(rows: int, columns: int, budget: int = 2**21):
    """Slices of ``rows`` whose (rows × columns) distance tables stay within ``budget`` entries."""
    step = max(1, budget // max(columns, 1))
    return [slice(i, min(i + step, rows)) for i in range(0, rows, step)]


def _nearest(p: Array, x: Array, tol: float = 0.0):
    """For each point of ``p`` (P, 3): the row of ``x`` (n, 3) nearest it, its distance, and how
    many rows are within ``tol`` of it."""
    nearest = np.zeros(len(p), dtype=np.intp)
    distance = np.full(len(p), np.inf)
    within = np.zeros(len(p), dtype=np.int64)
    for rows in _chunks(len(p), len(x)) if len(x) else []:
        d = np.linalg.norm(p[rows, None, :] - x[None, :, :], axis=2)
        nearest[rows] = d.argmin(axis=1)
        distance[rows] = d[np.arange(len(d)), nearest[rows]]
        within[rows] = np.count_nonzero(d <= tol, axis=1)
    return nearest, distance, within


def _points(points) -> Array:
    p = np.atleast_2d(np.asarray(points, dtype=float))
    if p.shape[1] != 3:
        raise ValueError(f"points must be (P, 3) in m; got shape {p.shape}")
    return p


def _tolerance(comm, x: Array, tol: float | None) -> float:
    """``tol``, default 1e-8 of the extent of the points ``x`` of every rank."""
    if tol is not None:
        return tol
    low, high = x.min(axis=0, initial=np.inf), x.max(axis=0, initial=-np.inf)
    if comm.size > 1:
        comm.Allreduce(MPI.IN_PLACE, low, op=MPI.MIN)
        comm.Allreduce(MPI.IN_PLACE, high, op=MPI.MAX)
    return 1e-8 * float(np.max(high - low, initial=1.0) if np.all(np.isfinite(low)) else 1.0)


def _refuse_far(p: Array, closest: Array, tol: float, remedy: str) -> None:
    far = np.flatnonzero(closest > tol)
    if len(far):
        i = far[0]
        raise ValueError(
            f"point {p[i].tolist()} is {closest[i]:.3g} m from the nearest node (tolerance "
            f"{tol:.3g} m): {remedy}"
        )


def locate_nodes(V: fem.FunctionSpace, points: npt.ArrayLike, tol: float | None = None) -> Blocks:
    """The nodes of ``V`` at ``points`` (m, (P, 3) or (3,)) that this rank holds: local dof
    blocks, owned and ghost, as ``fem.locate_dofs_geometrical`` returns them. Collective.

    On one rank every point has its node, in the order of ``points``; on several, a point's node
    appears on the ranks that hold it (in the order of ``points``) and on no other. ``tol`` (m):
    how far a point may be from its node; default 1e-8 of the mesh's extent. A point with no node
    within ``tol`` on any rank raises ``ValueError`` naming it, on every rank.
    """
    comm = V.mesh.comm
    x = np.asarray(V.tabulate_dof_coordinates(), dtype=float).reshape(-1, 3)
    p = _points(points)
    tol = _tolerance(comm, x, tol)
    nearest, distance, _ = _nearest(p, x)
    closest = distance.copy()
    if comm.size > 1:
        comm.Allreduce(MPI.IN_PLACE, closest, op=MPI.MIN)
    _refuse_far(p, closest, tol, "put a node there, or use candidate_pairs")
    return nearest[distance <= tol].astype(np.int32)


def dof_values(u: fem.Function, points: npt.ArrayLike, tol: float | None = None) -> Array:
    """The values of the function ``u`` at the dofs at ``points`` (m, (P, 3) or (3,)), as a
    (P, bs) array in the order of ``points``, on every rank. Collective.

    The points are where ``u``'s dofs sit (``tabulate_dof_coordinates``): nodes of a P1 space
    such as the beam space (bs = 6: u, θ), cell midpoints of a DG0 one (a section force per
    cell). Each value is read on the rank that owns its dof and summed over the ranks, so a
    ghost is counted once: on any number of ranks the result is the serial one. ``tol`` and a
    point with no dof within it: as ``locate_nodes``.
    """
    V = u.function_space
    comm = V.mesh.comm
    owned = V.dofmap.index_map.size_local
    bs = V.dofmap.index_map_bs
    x = np.asarray(V.tabulate_dof_coordinates(), dtype=float).reshape(-1, 3)
    p = _points(points)
    tol = _tolerance(comm, x, tol)
    nearest, distance, found = _nearest(p, x[:owned], tol)
    mine = distance <= tol
    values = np.zeros((len(p), bs))
    values[mine] = u.x.array.reshape(-1, bs)[nearest[mine]]
    if comm.size > 1:
        comm.Allreduce(MPI.IN_PLACE, values, op=MPI.SUM)
        comm.Allreduce(MPI.IN_PLACE, found, op=MPI.SUM)
    if np.any(found > 1):
        i = int(np.argmax(found > 1))
        raise ValueError(f"point {p[i].tolist()} has {found[i]} dofs within {tol:.3g} m: one only")
    closest = np.zeros(len(p))
    if not np.all(found):  # how far the points missed, for the message
        closest = _nearest(p, x)[1]
        if comm.size > 1:
            comm.Allreduce(MPI.IN_PLACE, closest, op=MPI.MIN)
        closest[found > 0] = 0.0
    _refuse_far(p, closest, tol, "give points where the function's dofs are")
    return values


def input_arrays(V) -> tuple[Array, npt.NDArray[np.int64], Blocks]:
    """The mesh of ``V`` as it was given to ``dolfinx.mesh.create_mesh``, on every rank: the input
    points (N, 3) in m, the input cells (E, 2) as rows of them (in their input order and
    orientation), and each input point's local dof block (N,), −1 where this rank holds none.
    Collective (the arrays are gathered from every rank)."""
    mesh = V.mesh
    comm = mesh.comm
    igi = np.asarray(mesh.geometry.input_global_indices, dtype=np.int64)
    gnodes = np.asarray(mesh.geometry.dofmaps[0], dtype=np.int64).reshape(-1, 2)
    block = np.full(len(mesh.geometry.x), -1, dtype=np.int32)
    block[gnodes] = np.asarray(V.dofmap.list, dtype=np.int32).reshape(-1, 2)
    n_cells = len(gnodes)
    original = np.asarray(mesh.topology.original_cell_index, dtype=np.int64)[:n_cells]
    mine = (igi, mesh.geometry.x[: len(igi), :3], original, igi[gnodes])
    parts = comm.allgather(mine) if comm.size > 1 else [mine]
    n_points = 1 + max(int(q[0].max(initial=-1)) for q in parts)
    n_input_cells = 1 + max(int(q[2].max(initial=-1)) for q in parts)
    points = np.zeros((n_points, 3))
    cells = np.zeros((n_input_cells, 2), dtype=np.int64)
    for ids, xs, orig, cs in parts:
        points[ids] = xs
        cells[orig] = cs
    to_block = np.full(n_points, -1, dtype=np.int32)
    to_block[igi] = block[: len(igi)]
    return points, cells, to_block
