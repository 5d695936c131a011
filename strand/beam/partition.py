"""Distributing a strand over MPI ranks so that every contact pair is evaluated on one rank.

A pair couples nodes of two wires; dolfinx's default partitioner deals out whole wires (the mesh
has one component per wire) and so splits 43 % of the pairs between ranks, with neither node
visible from the other side. ``slab_partitioner`` instead cuts the strand into axial slabs of
equal cell counts (every cell goes to the rank of its midpoint's slab), and ghosts:

* along every wire, the cells next to a rank's own (one cell of overlap: terms that couple a node
  to its wire neighbours, such as the core strut of the bending test, see both);
* for every *stencil* (a row of input node indices whose first entry is its anchor), every cell
  touching any of its nodes, on every rank that owns a cell touching the anchor.

dolfinx gives a vertex to one of the ranks that own a cell containing it, so whichever rank owns
the anchor's vertex holds the whole stencil (as owned or ghost nodes). A term is therefore
evaluated exactly once, by the rank that owns its anchor (``owned_rows``), and its residual and
tangent reach the other ranks through the ghosted vector and the distributed matrix.
"""

from __future__ import annotations

from collections.abc import Sequence

import dolfinx
import numpy as np
import numpy.typing as npt
from mpi4py import MPI

__all__ = ["slab_partitioner", "slab_destinations", "owned_rows", "DistributionError"]

Int = npt.NDArray[np.int64]


class DistributionError(RuntimeError):
    """A term whose nodes are not all on the rank that evaluates it."""


def _node_cells(cells: Int, n_nodes: int) -> Int:
    """(n_nodes, d) cells touching each node, padded with −1 (d: the largest node degree)."""
    flat = cells.ravel()
    order = np.argsort(flat, kind="stable")
    counts = np.bincount(flat, minlength=n_nodes)
    d = max(int(counts.max(initial=0)), 1)
    out = np.full((n_nodes, d), -1, dtype=np.int64)
    start = np.concatenate([[0], np.cumsum(counts)[:-1]])
    slot = np.arange(len(flat)) - np.repeat(start, counts)
    out[flat[order], slot] = order // cells.shape[1]
    return out


def slab_destinations(
    z: npt.ArrayLike, cells: npt.ArrayLike, nparts: int, stencils: Sequence[npt.ArrayLike] = ()
) -> tuple[Int, list[Int]]:
    """Owner rank of every cell (axial slabs of equal cell counts by midpoint height ``z`` (m) of
    the input nodes) and, per cell, the ranks it is ghosted on (sorted, owner excluded)."""
    cells = np.asarray(cells, dtype=np.int64).reshape(-1, 2)
    z = np.asarray(z, dtype=np.float64)
    n_cells = len(cells)
    mid = z[cells].mean(axis=1)
    order = np.argsort(mid, kind="stable")
    owner = np.empty(n_cells, dtype=np.int64)
    owner[order] = np.arange(n_cells) * nparts // max(n_cells, 1)
    if nparts == 1:
        return owner, [np.zeros(0, dtype=np.int64)] * n_cells
    node_cells = _node_cells(cells, len(z))
    ghost_cell, ghost_rank = [], []
    # one cell of overlap along the wires
    around = node_cells[cells].reshape(n_cells, -1)  # cells sharing a node with each cell
    c = np.repeat(np.arange(n_cells), around.shape[1])
    nb = around.ravel()
    keep = nb >= 0
    ghost_cell.append(nb[keep])
    ghost_rank.append(owner[c[keep]])
    # every stencil complete on every rank that may own its anchor
    for st in stencils:
        st = np.asarray(st, dtype=np.int64)
        if st.size == 0:
            continue
        st = st.reshape(len(st), -1)
        anchor_cells = node_cells[st[:, 0]]  # (P, d)
        needed = node_cells[st].reshape(len(st), -1)  # (P, k d)
        ranks = np.where(anchor_cells >= 0, owner[anchor_cells], -1)
        r = np.broadcast_to(ranks[:, :, None], (len(st), ranks.shape[1], needed.shape[1]))
        cc = np.broadcast_to(needed[:, None, :], r.shape)
        keep = (r >= 0) & (cc >= 0)
        ghost_cell.append(cc[keep])
        ghost_rank.append(r[keep])
    gc, gr = np.concatenate(ghost_cell), np.concatenate(ghost_rank)
    keep = gr != owner[gc]
    pairs = np.unique(np.column_stack([gc[keep], gr[keep]]), axis=0)
    split = np.searchsorted(pairs[:, 0], np.arange(n_cells + 1))
    ghosts = [pairs[split[i] : split[i + 1], 1] for i in range(n_cells)]
    return owner, ghosts


def slab_partitioner(z: npt.ArrayLike, cells: npt.ArrayLike, stencils: Sequence = ()):
    """A dolfinx cell partitioner (``create_mesh(..., partitioner=)``) for a wire mesh whose input
    cells ``cells`` (E, 2) join nodes at heights ``z`` (m), held by rank 0: axial slabs, with the
    ghosts that make every row of ``stencils`` (input node indices, anchor first) whole on the
    rank owning its anchor (module docstring)."""
    all_cells = np.asarray(cells, dtype=np.int64).reshape(-1, 2)

    def partition(comm: MPI.Comm, nparts: int, cell_types, cells_list):
        local = np.asarray(cells_list[0], dtype=np.int64).reshape(-1, 2)
        if len(local) == 0:
            return dolfinx.cpp.graph.AdjacencyList_int32(
                np.zeros(0, dtype=np.int32), np.zeros(1, dtype=np.int32)
            )
        if not np.array_equal(local, all_cells):
            raise DistributionError("slab_partitioner: rank 0 must hold every cell, in order")
        owner, ghosts = slab_destinations(z, all_cells, nparts, stencils)
        counts = 1 + np.array([len(g) for g in ghosts], dtype=np.int32)
        offsets = np.concatenate([[0], np.cumsum(counts)]).astype(np.int32)
        data = np.empty(offsets[-1], dtype=np.int32)
        data[offsets[:-1]] = owner
        rest = np.concatenate([[0], np.cumsum(counts - 1)])
        if rest[-1]:
            slots = np.repeat(offsets[:-1] + 1, counts - 1) + (
                np.arange(rest[-1]) - np.repeat(rest[:-1], counts - 1)
            )
            data[slots] = np.concatenate(ghosts)
        return dolfinx.cpp.graph.AdjacencyList_int32(data, offsets)

    return partition


def owned_rows(stencils: npt.ArrayLike, n_owned: int, what: str = "terms") -> npt.NDArray[np.intp]:
    """Rows of ``stencils`` (P, k) of local dof blocks (−1: absent on this rank) that this rank
    evaluates: those whose anchor (first node) it owns (block < ``n_owned``). Raises
    ``DistributionError`` if such a row misses a node (the mesh was not built to hold it)."""
    st = np.asarray(stencils)
    st = st[:, None] if st.ndim == 1 else st
    rows = np.flatnonzero((st[:, 0] >= 0) & (st[:, 0] < n_owned))
    missing = np.flatnonzero(np.any(st[rows] < 0, axis=1))
    if len(missing):
        raise DistributionError(
            f"{len(missing)} {what} have their anchor node on this rank but not all their other "
            "nodes: build the mesh with their stencils (strand.beam.partition.slab_partitioner)"
        )
    return rows
