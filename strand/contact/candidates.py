"""Finding contact pairs between two beams: the nodes of one within reach of the other's surface.

``candidate_pairs`` searches a dolfinx mesh's beam space and gives the ``NodePairs``
(``strand.contact.pairs``) between two beams; ``candidate_stencils`` finds the same pairs on the
mesh's input arrays, before it is built or distributed (the stencils a partitioner keeps whole).
Every node of beam b is measured against beam a's centreline (``closest_on_segments``). Units: m.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
import numpy.typing as npt

if TYPE_CHECKING:
    from dolfinx import fem

from .errors import ContactError
from .nodes import BeamNodes, _chunks, chains, input_arrays
from .pairs import NodePairs, _pairs_of, _per_pair

__all__ = ["candidate_pairs", "candidate_stencils", "closest_on_segments"]

Array = npt.NDArray[np.float64]


def closest_on_segments(p: Array, s0: Array, s1: Array) -> tuple[Array, Array]:
    """For points p (N, 3) and segments [s0, s1] (S, 3): distances (N, S) and parameters."""
    u = s1 - s0
    uu = np.einsum("si,si->s", u, u)
    t = np.einsum("nsi,si->ns", p[:, None, :] - s0[None], u) / np.where(uu > 0, uu, 1.0)
    t = np.clip(t, 0.0, 1.0)
    q = s0[None] + t[..., None] * u[None]
    return np.linalg.norm(p[:, None, :] - q, axis=2), t


def candidate_pairs(
    V: fem.FunctionSpace,
    beam_a: npt.ArrayLike,
    beam_b: npt.ArrayLike,
    radius_a: float,
    radius_b: float,
    reach: float,
    *,
    line: bool = False,
    initial_gap: npt.ArrayLike | None = None,
) -> NodePairs:
    """The pairs between two beams whose surfaces are within ``reach`` (m) of each other.
    Collective: on several ranks, each rank gets the pairs whose node a it owns.

    Every node of beam b is measured against beam a's centreline (its closest point on a's
    cells) and paired with the node of a nearer that point. Crossing beams (``line=False``) get
    one pair per crossing: the closest node of each run of nodes within reach. Beams lying along
    each other (``line=True``) get a pair at every node of b within reach, standing for its
    tributary length. Put nodes at the crossings for exact crossing pairs: a pair between nodes
    away from a crossing still measures the distance between the two centrelines there (n is
    normal to both), but it presses the beams at those nodes.

    The search runs on the whole mesh (``nodes.input_arrays``), so it finds the same pairs on
    any number of ranks, numbered alike (``NodePairs.index``). On several ranks each pair's
    nodes and their neighbours must all be on the rank owning its node a: build the mesh with
    ``strand.beam.partition.slab_partitioner(z, cells, [candidate_stencils(points, cells, ...)])``;
    otherwise ``ContactError`` on every rank.

    Args:
        beam_a, beam_b: the nodes (local dof blocks of ``V``, ghosts allowed) of each beam; on
            several ranks, each rank gives those it holds (``locate_nodes``).
        radius_a, radius_b: the beams' radii, m.
        reach: largest initial gap of a pair, m (pairs of a larger gap never close at small
            sliding if reach is chosen as the largest expected approach).
        initial_gap: as ``node_pairs`` (default: measured; one per pair: in ``index`` order).
    """
    comm = V.mesh.comm
    points, cells, to_block = input_arrays(V)
    of_block = np.full(int(to_block.max(initial=-1)) + 1, -1, dtype=np.int64)
    held = np.flatnonzero(to_block >= 0)
    of_block[to_block[held]] = held

    def inputs(blocks) -> npt.NDArray[np.int64]:
        mine = of_block[np.asarray(blocks, dtype=np.int64).reshape(-1)]
        return np.unique(np.concatenate(comm.allgather(mine))) if comm.size > 1 else mine

    table = candidate_stencils(
        points, cells, inputs(beam_a), inputs(beam_b), radius_a, radius_b, reach, line=line
    )
    blocks = to_block[table]
    n_owned = V.dofmap.index_map.size_local
    rows = np.flatnonzero((blocks[:, 0] >= 0) & (blocks[:, 0] < n_owned))
    split = int(np.count_nonzero(np.any(blocks[rows] < 0, axis=1)))
    split = comm.allreduce(split) if comm.size > 1 else split
    if split:
        raise ContactError(
            f"candidate_pairs: {split} of {len(table)} pairs have nodes on other ranks than their "
            "node a's: build the mesh with strand.beam.partition.slab_partitioner(z, cells, "
            "[candidate_stencils(points, cells, ...)]) to keep each pair on one rank"
        )
    gap = None if initial_gap is None else _per_pair(initial_gap, len(table), "initial_gap")[rows]
    return _pairs_of(blocks[rows], points[table[rows]], radius_a, radius_b, line, gap, None, rows)


def candidate_stencils(
    points: npt.ArrayLike,
    cells: npt.ArrayLike,
    beam_a: npt.ArrayLike,
    beam_b: npt.ArrayLike,
    radius_a: float,
    radius_b: float,
    reach: float,
    *,
    line: bool = False,
) -> npt.NDArray[np.int64]:
    """``candidate_pairs`` on a mesh's input arrays, before it is built or distributed: the
    pairs' nodes as rows (P, 6) of ``points`` (N, 3) (m), in the order of ``ROLES`` (a, b and
    their neighbours along ``cells`` (E, 2)), between the beams whose nodes are the rows
    ``beam_a`` and ``beam_b``. These are the stencils to give ``slab_partitioner``."""
    nodes = chains(points, cells)
    on_a = np.zeros(len(nodes.positions), dtype=bool)
    on_a[np.asarray(beam_a, dtype=np.int64)] = True
    nb = np.unique(np.asarray(beam_b, dtype=np.int64))
    if np.any(on_a[nb]):
        raise ValueError("beam_a and beam_b share nodes: give the nodes of two separate beams")
    segments = nodes.cells[on_a[nodes.cells].all(axis=1)]
    if len(segments) == 0 or len(nb) == 0:
        raise ValueError("each beam needs at least one cell (two nodes) of V")
    x = nodes.positions
    gap = np.empty(len(nb))
    a = np.empty(len(nb), dtype=np.int64)
    for rows in _chunks(len(nb), len(segments)):
        dist, t = closest_on_segments(x[nb[rows]], x[segments[:, 0]], x[segments[:, 1]])
        best = dist.argmin(axis=1)
        k = np.arange(len(best))
        gap[rows] = dist[k, best] - radius_a - radius_b
        a[rows] = np.where(t[k, best] < 0.5, segments[best, 0], segments[best, 1])
    near = gap <= reach
    keep = np.flatnonzero(near)
    if not line:
        keep = _closest_of_each_run(nb, near, gap, nodes)
    if len(keep) == 0:
        raise ValueError(
            f"no node of beam b is within reach = {reach:.3g} m of beam a's surface (smallest "
            f"gap {gap.min():.3g} m)"
        )
    a, b = a[keep], nb[keep]
    return np.column_stack([a, b, nodes.neighbours[a], nodes.neighbours[b]]).astype(np.int64)


def _closest_of_each_run(nb, near, gap, nodes: BeamNodes) -> npt.NDArray[np.intp]:
    """Positions (in ``nb``) of the node of least gap in each run of consecutive near nodes."""
    where = {int(n): i for i, n in enumerate(nb)}
    label = -np.ones(len(nb), dtype=np.intp)
    runs = 0
    for i in np.flatnonzero(near):  # flood each run along the beam (set-up only)
        if label[i] >= 0:
            continue
        label[i] = runs
        stack = [i]
        while stack:
            j = stack.pop()
            for k in nodes.neighbours[nb[j]]:
                m = where.get(int(k))
                if m is not None and near[m] and label[m] < 0:
                    label[m] = runs
                    stack.append(m)
        runs += 1
    return np.array(
        [np.flatnonzero(label == r)[gap[label == r].argmin()] for r in range(runs)], dtype=np.intp
    )
