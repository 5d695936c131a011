"""The nodes of beams in a dolfinx mesh: their positions and neighbours, and nodes found at points.

Nodes are local dof blocks of the beam space V (dolfinx's blocked P1 space of (u, θ)): what
``fem.locate_dofs_geometrical(V, marker)`` and ``locate_dofs_topological(V, 0, vertices)`` return.
A beam is a chain of cells; its nodes' neighbours along it give the chords that stand for its
tangents (``strand.contact.pairs``). Units: m.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

__all__ = ["BeamNodes", "beam_nodes", "locate_nodes"]

Array = npt.NDArray[np.float64]
Blocks = npt.NDArray[np.int32]


@dataclass(frozen=True)
class BeamNodes:
    """The nodes of a beam mesh: positions (n, 3) in m and, per node, its two neighbours along its
    beam (n, 2) (the node itself at a beam's end), as local dof blocks."""

    positions: Array
    neighbours: Blocks
    cells: Blocks  # (E, 2) the cells as pairs of nodes

    def tangents(self, nodes) -> Array:
        """Unit chords x₊ − x₋ between the neighbours of ``nodes`` (P, 3)."""
        nb = self.neighbours[nodes]
        c = self.positions[nb[:, 1]] - self.positions[nb[:, 0]]
        return c / np.linalg.norm(c, axis=1)[:, None]


def beam_nodes(V) -> BeamNodes:
    """Positions and neighbours of every node of the beam space ``V`` (blocked P1 on a 1D mesh).

    Raises ``ValueError`` at a node shared by more than two cells (beams meet there: pair such
    beams through contact or links, not through shared nodes).
    """
    x = np.asarray(V.tabulate_dof_coordinates(), dtype=float).reshape(-1, 3)
    cells = np.asarray(V.dofmap.list, dtype=np.int32).reshape(-1, 2)
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


def locate_nodes(V, points, tol: float | None = None) -> Blocks:
    """The nodes (local dof blocks) of ``V`` at ``points`` (m, (P, 3) or (3,)).

    ``tol`` (m): how far a point may be from its node; default 1e-8 of the mesh's extent. A point
    farther than that raises ``ValueError`` naming it.
    """
    x = np.asarray(V.tabulate_dof_coordinates(), dtype=float).reshape(-1, 3)
    p = np.atleast_2d(np.asarray(points, dtype=float))
    if p.shape[1] != 3:
        raise ValueError(f"points must be (P, 3) in m; got shape {p.shape}")
    if tol is None:
        tol = 1e-8 * float(np.ptp(x, axis=0).max(initial=1.0))
    nearest = np.empty(len(p), dtype=np.intp)
    distance = np.empty(len(p))
    for rows in _chunks(len(p), len(x)):
        d = np.linalg.norm(p[rows, None, :] - x[None, :, :], axis=2)
        nearest[rows] = d.argmin(axis=1)
        distance[rows] = d[np.arange(len(d)), nearest[rows]]
    far = np.flatnonzero(distance > tol)
    if len(far):
        i = far[0]
        raise ValueError(
            f"point {p[i].tolist()} is {distance[i]:.3g} m from the nearest node (tolerance "
            f"{tol:.3g} m): put a node there, or use candidate_pairs"
        )
    return nearest.astype(np.int32)
