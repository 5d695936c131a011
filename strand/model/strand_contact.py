"""The contact pairs of a strand, built on the generic contact package (``strand.contact``).

The strand geometry found its pairs analytically (``strand.cable.geometry``): crossings where two
wires are radially aligned, and every layer-1 node against the core. Here they become ``NodePairs``
(nodes as dof blocks, the geometry's radial normals, gaps zero by construction) and, with the laws
that ``ContactSettings`` choose, the small-sliding ``ContactGroup`` of each kind, or the
large-sliding ``SlidingGroup`` of each window size on the wires as node chains (``sliding_groups``;
windows in ``strand.contact.windows``). In large sliding the same-layer pairs
(``strand.model.same_layer``) are line pairs too: each node against its neighbour wire's centreline,
the facing point re-found in a window around the segment it starts on
(``same_layer_sliding_groups``). ``centreline_gaps`` measures the pairs' clearance on deformed
centrelines (diagnostics). Units: m, N.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from ..beam.partition import DistributionError, owned_rows
from ..cable.geometry import LINE, POINT, StrandGeometry
from ..contact.element import ContactGroup
from ..contact.friction_laws import FrictionLaw
from ..contact.measure import segment_distance
from ..contact.normal_laws import NormalLaw
from ..contact.pairs import NodePairs, contact_terms, crossing_angle
from ..contact.sliding import SlidingGroup
from ..contact.windows import NodeChains, SlidingWindows, chain_windows, sliding_group
from .compliances import Wires, compliance_named
from .contact_settings import ContactSettings
from .layer_states import first_layer_lift
from .same_layer import SameLayerPairs, same_layer_laws

__all__ = [
    "strand_pairs",
    "pair_stencils",
    "contact_groups",
    "pair_laws",
    "wire_neighbours",
    "wire_chains",
    "sliding_windows",
    "sliding_groups",
    "same_layer_windows",
    "same_layer_sliding_groups",
    "centreline_gaps",
]


def wire_neighbours(geometry: StrandGeometry, nodes: npt.NDArray[np.int64]):
    """Input indices of the previous and next node on the same wire (the node itself at ends)."""
    wire = geometry.point_wire[nodes]
    lo, hi = geometry.wire_offsets[wire], geometry.wire_offsets[wire + 1] - 1
    return np.maximum(nodes - 1, lo), np.minimum(nodes + 1, hi)


def pair_stencils(geometry: StrandGeometry, sel=None) -> npt.NDArray[np.int64]:
    """(P, 6) input nodes of the geometry's pairs ``sel`` (default: all) in ``ROLES`` order:
    a, b and their neighbours along their wires (a first: the anchor of a distributed pair)."""
    pairs = geometry.pairs
    sel = np.arange(len(pairs)) if sel is None else np.asarray(sel)
    a, b = pairs.a[sel], pairs.b[sel]
    return np.column_stack([a, b, *wire_neighbours(geometry, a), *wire_neighbours(geometry, b)])


def strand_pairs(
    geometry: StrandGeometry,
    input_to_block: npt.NDArray[np.int32],
    sel,
    *,
    core_gap: float = 0.0,
) -> NodePairs:
    """The geometry's pairs ``sel`` (all of one kind) as ``NodePairs`` on the local dof blocks
    ``input_to_block`` (``mesh.input_to_block``): initial gaps zero, but ``core_gap`` (m) for
    the core's line pairs (``layer_states.first_layer_lift``)."""
    pairs = geometry.pairs
    sel = np.asarray(sel)
    points = pair_stencils(geometry, sel)
    blocks = input_to_block[points]
    if np.any(blocks < 0):
        raise DistributionError(
            "contact pairs whose nodes are not all on this process: distribute the mesh with "
            "strand.beam.partition.slab_partitioner and keep the pairs this rank owns (owned_rows)"
        )
    kinds = pairs.kind[sel]
    if len(np.unique(kinds)) > 1:
        raise ValueError("strand_pairs: the selected pairs mix crossings and line pairs")
    return NodePairs(
        blocks.astype(np.int32),
        geometry.points[points],
        bool(len(kinds) and kinds[0] == LINE),
        pairs.radius_a[sel],
        pairs.radius_b[sel],
        pairs.normal[sel],
        np.where(pairs.interface[sel] == 0, core_gap, 0.0),
        pairs.tributary[sel],
        sel,
    )


def contact_groups(
    geometry: StrandGeometry,
    input_to_block: npt.NDArray[np.int32],
    settings: ContactSettings,
    n_owned: int | None = None,
) -> list[ContactGroup]:
    """The contact pairs of a strand as ``ContactGroup`` objects (one per pair kind present).
    With ``n_owned`` (a distributed mesh: the number of dof blocks this rank owns), only the
    pairs whose node a this rank owns (``partition.owned_rows``)."""
    groups = []
    lift = first_layer_lift(geometry.cable, settings.first_layer)
    for kind in (POINT, LINE):
        sel = np.flatnonzero(geometry.pairs.kind == kind)
        if n_owned is not None:
            blocks = input_to_block[pair_stencils(geometry, sel)]
            sel = sel[owned_rows(blocks, n_owned, "contact pairs")]
        if len(sel):
            pairs = strand_pairs(geometry, input_to_block, sel, core_gap=lift)
            laws = pair_laws(geometry, sel, settings, pairs.tangents)
            groups.append(contact_terms(pairs, *laws, normal=settings.normal, slip=settings.slip))
    return groups


def pair_laws(
    geometry: StrandGeometry, sel, settings: ContactSettings, tangents
) -> tuple[NormalLaw, FrictionLaw | None]:
    """The normal and friction laws of the geometry's pairs ``sel`` (all of one kind), from the
    compliance ``settings`` name (``compliances``).

    ``tangents`` (P, 2, 3): the initial unit tangents of the wires at a and b (their crossing
    angle sizes a Hertz contact).
    """
    pairs = geometry.pairs
    wires = [layer.wire for layer in geometry.cable.layers]
    inner, outer = pairs.interface[sel], pairs.interface[sel] + 1
    E_a, nu_a = (np.array([getattr(w, key) for w in wires])[inner] for key in ("E", "nu"))
    E_b, nu_b = (np.array([getattr(w, key) for w in wires])[outer] for key in ("E", "nu"))
    chosen = Wires(
        line=bool(np.all(pairs.kind[sel] == LINE)),
        radius_a=pairs.radius_a[sel],
        radius_b=pairs.radius_b[sel],
        E_a=E_a,
        nu_a=nu_a,
        E_b=E_b,
        nu_b=nu_b,
        mu=pairs.friction[sel] if settings.friction else None,
        tributary=pairs.tributary[sel],
        angle=crossing_angle(tangents),
    )
    return compliance_named(settings.compliance).build(chosen, settings)


def wire_chains(geometry: StrandGeometry) -> NodeChains:
    """The wires as chains of their input nodes (in order along each, with the points)."""
    nodes = np.arange(len(geometry.points))
    return NodeChains(np.split(nodes, geometry.wire_offsets[1:-1]), geometry.points)


def sliding_windows(
    geometry: StrandGeometry, reach: float, chains: NodeChains | None = None
) -> list[SlidingWindows]:
    """The windows of the large-sliding pairs, crossings first, per window size: ``rows`` the
    geometry's pairs, ``nodes`` (P, na + nb) their input nodes (wire a's first), ``na`` and
    ``ends`` (``contact.windows.chain_windows``). Each pair's window holds the segments of its
    wires within ``reach`` (m) of its initial nodes; a line pair's node b is its own window."""
    chains = wire_chains(geometry) if chains is None else chains
    points = np.arange(len(geometry.points), dtype=np.int32)
    out = []
    for kind in (POINT, LINE):
        sel = np.flatnonzero(geometry.pairs.kind == kind)
        if len(sel):
            pairs = strand_pairs(geometry, points, sel)
            out += [w._replace(rows=sel[w.rows]) for w in chain_windows(pairs, chains, reach)]
    return out


def sliding_groups(
    geometry: StrandGeometry,
    input_to_block: npt.NDArray[np.int32],
    settings: ContactSettings,
    n_owned: int | None = None,
) -> list[SlidingGroup]:
    """Large-sliding versions of the geometry's pairs (windows: ``sliding_windows``), with the
    laws of ``settings``; pairs with windows of equal sizes share a group. With ``n_owned`` (a
    distributed mesh: the number of dof blocks this rank owns), only the pairs whose window
    starts on an owned node (``partition.owned_rows``)."""
    chains = wire_chains(geometry)
    lift = first_layer_lift(geometry.cable, settings.first_layer)
    tangents = geometry.tangents()  # analytic: helices touch at nodes, the points start there
    points = np.arange(len(geometry.points), dtype=np.int32)
    groups = []
    for windows in sliding_windows(geometry, settings.reach, chains):
        if n_owned is not None:
            blocks = input_to_block[windows.nodes]
            windows = windows.select(owned_rows(blocks, n_owned, "contact pairs"))
        if not len(windows.rows):
            continue
        pairs = strand_pairs(geometry, points, windows.rows, core_gap=lift)  # on input nodes
        pair_tangents = np.stack([tangents[pairs.a], tangents[pairs.b]], axis=1)
        laws = pair_laws(geometry, windows.rows, settings, pair_tangents)
        options = {"tangents": tangents, "blocks": input_to_block, "slip": settings.slip}
        groups.append(sliding_group(pairs, windows, chains, *laws, **options))
    return groups


def _same_layer_line_pairs(geometry: StrandGeometry, pairs: SameLayerPairs, rows) -> NodePairs:
    """The same-layer pairs ``rows`` as line pairs on input nodes: the first node b₀ of the
    neighbour's facing segment (its wire the beam a of a line pair) against node a."""
    curve, node = pairs.b0[rows], pairs.a[rows]
    nodes = np.column_stack(
        [curve, node, *wire_neighbours(geometry, curve), *wire_neighbours(geometry, node)]
    )
    radius = np.array([geometry.cable.layers[i].wire.diameter / 2 for i in pairs.layer[rows]])
    return NodePairs(
        nodes.astype(np.int32),
        geometry.points[nodes],
        True,
        radius,
        radius,
        -pairs.normal[rows],
        pairs.gap[rows],
        pairs.tributary[rows],
        np.asarray(rows),
    )


def same_layer_windows(
    geometry: StrandGeometry, pairs: SameLayerPairs, reach: float, chains: NodeChains | None = None
) -> list[SlidingWindows]:
    """The windows of the same-layer pairs in large sliding, per window size: ``rows`` of
    ``pairs``, ``nodes`` (P, na + 1) the neighbour wire's window (``reach`` either side of the
    facing segment) then node a."""
    chains = wire_chains(geometry) if chains is None else chains
    line_pairs = _same_layer_line_pairs(geometry, pairs, np.arange(len(pairs)))
    return chain_windows(line_pairs, chains, reach, on_segment=True)


def same_layer_sliding_groups(
    geometry: StrandGeometry,
    pairs: SameLayerPairs,
    input_to_block: npt.NDArray[np.int32],
    settings: ContactSettings,
    n_owned: int | None = None,
) -> list[SlidingGroup]:
    """``pairs`` (``same_layer.same_layer_pairs``) in large sliding: line pairs of node a
    against the neighbour's centreline from its facing point, one ``SlidingGroup`` per window
    size, with the initial gaps of ``pairs``, the laws of ``same_layer.same_layer_laws`` and the
    surface points' slip (as the small-sliding same-layer pairs). With ``n_owned``
    (distributed), the pairs whose window starts on an owned node."""
    chains = wire_chains(geometry)
    tangents = geometry.tangents()
    groups = []
    for windows in same_layer_windows(geometry, pairs, settings.reach, chains):
        if n_owned is not None:
            blocks = input_to_block[windows.nodes]
            windows = windows.select(owned_rows(blocks, n_owned, "same-layer pairs"))
        if not len(windows.rows):
            continue
        _, law, friction = same_layer_laws(geometry, pairs, windows.rows, settings)
        groups.append(
            sliding_group(
                _same_layer_line_pairs(geometry, pairs, windows.rows),
                windows,
                chains,
                law,
                friction,
                tangents=tangents,
                blocks=input_to_block,
                weights=pairs.weight[windows.rows],
            )
        )
    return groups


def centreline_gaps(
    geometry: StrandGeometry, x: npt.NDArray[np.float64], reach: int = 2
) -> npt.NDArray[np.float64]:
    """Clearance of every pair (m): closest distance between the two wires' polylines within
    ``reach`` cells of the pair's nodes, minus the radii. For line pairs (nearly parallel wires):
    the distance from node b to the core's polyline. ``x`` (N, 3) are the node positions.
    """
    pairs = geometry.pairs
    offsets, wire = geometry.wire_offsets, geometry.point_wire

    def segments(nodes):
        lo, hi = offsets[wire[nodes]], offsets[wire[nodes] + 1] - 1
        first = np.clip(nodes[:, None] + np.arange(-reach, reach), lo[:, None], hi[:, None] - 1)
        return x[first], x[first + 1]

    p0, p1 = segments(pairs.a)
    q0, q1 = segments(pairs.b)
    line = pairs.kind == LINE
    q0[line], q1[line] = p0[line], p1[line]
    p0[line] = p1[line] = x[pairs.b[line], None]
    d = segment_distance(p0[:, :, None], p1[:, :, None], q0[:, None], q1[:, None])
    return d.reshape(len(pairs.a), -1).min(axis=1) - pairs.radius_a - pairs.radius_b
