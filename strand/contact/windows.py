"""Large-sliding pairs from node pairs and the beams' node chains.

A large-sliding pair starts where a ``NodePairs`` pair is (its nodes a and b) and may slide along
both beams within a window: the stretch of each beam's chain of nodes that reaches ``reach`` (m of
initial arc length) either side of the pair's node, or the beam's end. A line pair's node b is its
own window (a point against beam a). Pairs whose windows have the same sizes share a
``SlidingGroup`` (``strand.contact.sliding``):

>>> pairs = candidate_pairs(V, lower, upper, r, r, reach=1e-4)                # doctest: +SKIP
>>> groups = sliding_terms(V, pairs, [lower, upper], 5e-3, PenaltyLaw(1e7))  # doctest: +SKIP
>>> NonlinearProblem(beam.residual(), w, bcs, terms=groups).solve()          # doctest: +SKIP

Chains are nodes in order along each beam (``locate_nodes`` of its points in order); the
Hermite centrelines take the nodes' initial unit tangents, by default the chords between each
node's neighbours along its chain. Units: m.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import fields, is_dataclass, replace
from typing import TYPE_CHECKING, NamedTuple

import numpy as np
import numpy.typing as npt

if TYPE_CHECKING:
    from dolfinx import fem

from .errors import ContactError
from .friction_laws import FrictionLaw
from .nodes import beam_nodes
from .normal_laws import NormalLaw
from .pairs import NodePairs
from .sliding import SlidingGroup

__all__ = ["NodeChains", "SlidingWindows", "chain_windows", "sliding_group", "sliding_terms"]

Array = npt.NDArray[np.float64]
Nodes = npt.NDArray[np.int64]


class NodeChains:
    """Beams as chains of nodes, each in order along its beam, with the arc length along them.

    Args:
        chains: per beam, its nodes (at least two) in order along it.
        positions: (n, 3) initial positions of the nodes, m, indexed by node.

    Attributes:
        nodes: every chain's nodes, chain after chain; offsets: (C + 1,) where each chain starts
            in ``nodes``; chain: (N,) the chain of each entry of ``nodes``; where: (n,) the entry
            of each node in ``nodes`` (−1: on no chain); arc: (N,) the arc length of the
            concatenated chains, m (constant across a chain's end).
    """

    def __init__(self, chains: Sequence[npt.ArrayLike], positions: npt.ArrayLike):
        chains = [np.asarray(c, dtype=np.int64).ravel() for c in chains]
        self.positions = np.asarray(positions, dtype=float)
        n = len(self.positions)
        if not chains or min(len(c) for c in chains) < 2:
            raise ContactError("each chain needs at least two nodes (one cell of its beam)")
        self.nodes = np.concatenate(chains)
        if self.nodes.min() < 0 or self.nodes.max() >= n:
            raise ContactError(f"chain nodes must be rows of positions, in 0..{n - 1}")
        self.offsets = np.concatenate([[0], np.cumsum([len(c) for c in chains])])
        self.chain = np.repeat(np.arange(len(chains)), np.diff(self.offsets))
        self.where = np.full(n, -1, dtype=np.int64)
        self.where[self.nodes] = np.arange(len(self.nodes))
        if np.count_nonzero(self.where >= 0) < len(self.nodes):
            raise ContactError("a node is on two chains, or twice on one")
        step = np.linalg.norm(np.diff(self.positions[self.nodes], axis=0), axis=1)
        step[self.offsets[1:-1] - 1] = 0.0  # no length between a chain's last node and the next
        self.arc = np.concatenate([[0.0], np.cumsum(step)])

    def stretch(self, nodes: npt.ArrayLike, reach: float):
        """Per node: the entries (in ``self.nodes``) of the first and last node of the shortest
        stretch of its chain reaching ``reach`` (m of initial arc length) either side of it, or
        the chain's end; and (P, 2) whether each is its chain's end."""
        at = self.where[np.asarray(nodes)]
        if np.any(at < 0):
            node = int(np.asarray(nodes)[np.flatnonzero(at < 0)[0]])
            raise ContactError(f"node {node} of a pair is on none of the chains")
        # one increasing key over all chains: chain c's arc length shifted past every earlier one
        key = self.arc + self.chain * (self.arc[-1] + 2 * reach + 1.0)
        lo, hi = self.offsets[self.chain[at]], self.offsets[self.chain[at] + 1] - 1
        first = np.maximum(np.searchsorted(key, key[at] - reach, side="right") - 1, lo)
        last = np.minimum(np.searchsorted(key, key[at] + reach, side="left"), hi)
        return first, last, np.column_stack([first == lo, last == hi])

    def tangents(self) -> Array:
        """(n, 3) unit chords between each chain node's neighbours along its chain (one-sided at
        the chain's ends); zero for nodes on no chain."""
        i = np.arange(len(self.nodes))
        prev = np.maximum(i - 1, self.offsets[self.chain])
        following = np.minimum(i + 1, self.offsets[self.chain + 1] - 1)
        chord = self.positions[self.nodes[following]] - self.positions[self.nodes[prev]]
        out = np.zeros_like(self.positions)
        out[self.nodes] = chord / np.linalg.norm(chord, axis=1)[:, None]
        return out


class SlidingWindows(NamedTuple):
    """The windows of the large-sliding pairs ``rows`` (of their ``NodePairs``), of one size:
    ``nodes`` (P, na + nb), beam a's window in order along it then beam b's (a line pair: b
    alone); ``na``; ``ends`` (P, 4), whether the first/last node of a's window, then of b's, is
    its beam's end."""

    rows: npt.NDArray[np.intp]
    nodes: Nodes
    na: int
    ends: npt.NDArray[np.bool_]

    def select(self, mask) -> SlidingWindows:
        """The windows ``mask`` (boolean or indices) of these."""
        return SlidingWindows(self.rows[mask], self.nodes[mask], self.na, self.ends[mask])


def chain_windows(
    pairs: NodePairs, chains: NodeChains, reach: float, on_segment: bool = False
) -> list[SlidingWindows]:
    """The windows of ``pairs`` on ``chains`` within ``reach`` (m), grouped by their sizes.
    ``on_segment``: the pairs' contact points start on the segments from their nodes a to the
    next nodes of a's chain, and a's windows reach that far either side of the whole segment."""
    if not (isinstance(reach, int | float) and reach > 0):
        raise ContactError(f"sliding reach = {reach!r}: must be a positive number (m)")
    P = len(pairs)
    a_first, a_last, a_ends = chains.stretch(pairs.a, reach)
    if on_segment:
        at = chains.where[pairs.a]
        if np.any(at + 1 >= chains.offsets[chains.chain[at] + 1]):
            raise ContactError("a pair starting on a segment has its node a at its chain's end")
        _, a_last, next_ends = chains.stretch(chains.nodes[at + 1], reach)
        a_ends = np.column_stack([a_ends[:, 0], next_ends[:, 1]])
    if pairs.line:
        b_first = b_last = np.zeros(P, dtype=np.int64)
        b_ends = np.ones((P, 2), dtype=bool)
    else:
        b_first, b_last, b_ends = chains.stretch(pairs.b, reach)
        if np.any(chains.chain[a_first] == chains.chain[b_first]):
            raise ContactError("a crossing pair joins two nodes of one chain")
    sizes = np.column_stack([a_last - a_first + 1, b_last - b_first + 1])
    out = []
    for na, nb in np.unique(sizes, axis=0):
        sel = np.flatnonzero((sizes[:, 0] == na) & (sizes[:, 1] == nb))
        a_nodes = chains.nodes[a_first[sel, None] + np.arange(na)]
        if pairs.line:
            b_nodes = pairs.b[sel, None].astype(np.int64)
        else:
            b_nodes = chains.nodes[b_first[sel, None] + np.arange(nb)]
        nodes = np.concatenate([a_nodes, b_nodes], axis=1)
        out.append(SlidingWindows(sel, nodes, int(na), np.column_stack([a_ends[sel], b_ends[sel]])))
    return out


def sliding_group(
    pairs: NodePairs,
    windows: SlidingWindows,
    chains: NodeChains,
    normal_law: NormalLaw,
    friction_law: FrictionLaw | None = None,
    *,
    tangents: npt.ArrayLike | None = None,
    blocks: npt.ArrayLike | None = None,
    weights: npt.ArrayLike | None = None,
    slip: str = "surface",
) -> SlidingGroup:
    """The large-sliding group of ``pairs`` (one per window of ``windows``, in order) whose
    contact points start at the pairs' nodes, or on a's segments (``weights``).

    Args:
        normal_law, friction_law: the pairs' laws (friction None: frictionless).
        tangents: (n, 3) initial unit tangents of the centrelines at the nodes (default: chords,
            ``NodeChains.tangents``).
        blocks: (n,) the local dof block of each node, if nodes are not dof blocks themselves.
        weights: (P,) where the contact points start on the segments from node a to the next
            node of a's chain, in [0, 1] (windows from ``chain_windows(..., on_segment=True)``;
            default: at node a).
        slip: the friction's slip measure, "surface" or "centreline" (``SlidingGroup``).
    """
    nodes, na = windows.nodes, windows.na
    if len(pairs) != len(nodes):
        raise ContactError(f"{len(pairs)} pairs for {len(nodes)} windows")
    nb = nodes.shape[1] - na
    # the closest points start at the pair's nodes: ξ = 0 on the segment they begin (1 on the
    # last segment when the node ends the window), or at ξ = weight on that segment
    a_pos = chains.where[pairs.a] - chains.where[nodes[:, 0]]
    b_pos = 0 * a_pos if pairs.line else chains.where[pairs.b] - chains.where[nodes[:, na]]
    start_a = np.minimum(a_pos, na - 2)
    start_b = np.zeros(len(pairs), dtype=np.intp) if pairs.line else np.minimum(b_pos, nb - 2)
    start_parameters = np.column_stack([a_pos - start_a, b_pos - start_b]).astype(float)
    if weights is not None:
        weights = np.asarray(weights, dtype=float)
        if np.any((weights < 0) | (weights > 1)) or np.any(a_pos > na - 2):
            raise ContactError("segment weights must lie in [0, 1], on a segment of a's window")
        start_parameters[:, 0] = weights
    tangents = chains.tangents() if tangents is None else np.asarray(tangents, dtype=float)
    stencils = nodes if blocks is None else np.asarray(blocks)[nodes]
    return SlidingGroup(
        stencils,
        chains.positions[nodes],
        na,
        pairs.line,
        np.column_stack([start_a, start_b]),
        normal_law,
        friction_law=friction_law,
        index=pairs.index,
        wire_end=windows.ends,
        radius_a=pairs.radius_a,
        radius_b=pairs.radius_b,
        start_parameters=start_parameters,
        tangents=tangents[nodes],
        initial_gap=pairs.initial_gap,
        slip=slip,
    )


def _law_rows(law, rows: npt.NDArray[np.intp], n: int):
    """``law``, given for ``n`` pairs, for the pairs ``rows``: its per-pair arrays cut to them."""
    if law is None or np.array_equal(rows, np.arange(n)):
        return law
    if not is_dataclass(law):
        raise ContactError(
            f"{type(law).__name__} is split by window size: give a dataclass law (as those of "
            "strand.contact.normal_laws and friction_laws) whose per-pair values are arrays of one "
            "value per pair"
        )
    cut = {}
    for f in fields(law):
        value = getattr(law, f.name)
        if np.ndim(value) == 1 and len(value) == n:
            cut[f.name] = np.asarray(value)[rows]
    return replace(law, **cut)


def _check_order(chains: NodeChains, cells) -> None:
    """Every two consecutive nodes of a chain must share a cell of the mesh."""
    n = len(chains.positions)
    joined = np.sort(np.asarray(cells, dtype=np.int64), axis=1) @ [n, 1]
    steps = np.sort(np.column_stack([chains.nodes[:-1], chains.nodes[1:]]), axis=1)
    inside = chains.chain[:-1] == chains.chain[1:]
    bad = np.flatnonzero(inside & ~np.isin(steps @ [n, 1], joined))
    if len(bad):
        u, v = steps[bad[0]]
        raise ContactError(
            f"chain nodes {u} and {v} share no cell of V: give each beam's nodes in order along it"
        )


def sliding_terms(
    V: fem.FunctionSpace,
    pairs: NodePairs,
    chains: Sequence[npt.ArrayLike],
    reach: float,
    normal_law: NormalLaw,
    friction_law: FrictionLaw | None = None,
    *,
    tangents: npt.ArrayLike | None = None,
    slip: str = "surface",
) -> list[SlidingGroup]:
    """Large-sliding contact on ``pairs``: the ``PairTerms`` to give
    ``NonlinearProblem(terms=...)``, one ``SlidingGroup`` per window size.

    Args:
        V: the beam space (blocked P1 of (u, θ)) whose dof blocks the pairs' nodes are.
        chains: each beam's nodes, in order along it; the pairs' nodes lie on them.
        reach: sliding room either side of each pair, m (arc length along each beam).
        normal_law, friction_law: as ``contact_terms``: one for all pairs, or with values per
            pair (cut to each group's pairs).
        tangents: (n, 3) initial unit tangents at the nodes (default: chords between each node's
            neighbours along its chain).
        slip: the friction's slip measure, "surface" or "centreline" (``SlidingGroup``).
    """
    nodes = beam_nodes(V)
    node_chains = NodeChains(chains, nodes.positions)
    _check_order(node_chains, nodes.cells)
    groups = []
    for windows in chain_windows(pairs, node_chains, reach):
        laws = (_law_rows(law, windows.rows, len(pairs)) for law in (normal_law, friction_law))
        groups.append(
            sliding_group(
                pairs.select(windows.rows),
                windows,
                node_chains,
                *laws,
                tangents=tangents,
                slip=slip,
            )
        )
    return groups
