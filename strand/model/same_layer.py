"""Contact between neighbouring wires of one layer: where they face each other, and their gaps.

The wires of a helical layer are identical helices turned by 2π/n, their centre lines at least D
apart (``layer_states.helix_clearance``); D − d is the layer's nominal gap.

Each node a of wire j (in order of phase) faces the point of wire j+1's polyline nearest to it,
at ξ on the segment [b₀, b₁]. Its pair (``[contact] same_layer_stencil``) is either

* ``"segment"`` (the default): a ``contact.segment.SegmentGroup`` pair [a, b₀, b₁] with the
  weight ξ and the centre-to-centre normal across the neighbour's chord (``neighbour``); or
* ``"node"``: a line pair of ``contact.element.ContactGroup`` [c, a] with the node c of the
  segment nearest the facing point, the gap a's distance from the line of c's director tangent
  (``director``), and the slip of the facing point, ``offset`` s along that tangent, carried by
  c's section: two nodes, so the LU does not tie every node to its neighbours' segments
  (docs/theory.md §3.4); or
* ``"facing"`` (small sliding, on a geometry built with facing stations:
  ``cable.geometry.build_geometry(facing=True)``): the node stencil [c, a] where the mesh puts c
  exactly where station a faces wire j+1 (z + δ, ``cable.facing.facing_offset``), so the
  offset is 0, the normal a → c is perpendicular to both wires and ‖x_c − x_a‖ is D; its
  tributary is the arc between the midpoints to its wire's neighbouring stations.

Neither normal changes the gap under rigid rotations (a frozen normal closes it by d ω²/2). The
normal law is the Hertz line law over the node's tributary length of wire (with a C¹ onset,
``contact.normal_laws.SmoothOnset``: these pairs start touching without load), the friction
Mindlin's with the layer's Coulomb coefficient.

A layer of n wires has n (D − d) of spare circumference. How stranding spreads it over the n
gaps (``[contact] same_layer``, ``layer_states.spread_gaps``) is the layer's state; a layer whose
helices would overlap touches all round, on the core or vaulted over it (``[contact]
first_layer``, ``layer_states.first_layer_lift``).

In large sliding (``[contact] model = "large"``) the same pairs are line pairs of
``strand.contact.sliding``: node a against the neighbour's C¹ centreline, its facing point
re-found at every iteration within the sliding reach either side of the segment it starts on
(``strand_contact.same_layer_sliding_groups``), with the same gaps, laws and surface slip. The
facing point must be re-found: on the main job (Cardinal, 1 m, 40 kN, ±4.3 kN saddle, packed
layers, segments of 0.8–4.0 mm) the facing points move along their neighbours by up to 16 µm
at 40 kN, 0.8 % of their segments, but by up to 0.14 mm at the largest saddle load, 7 % of a
segment (``facing_point_motion`` on that run's tensioned state and on its fields there): a
facing point that starts near a node passes onto the next segment. The default reach, 1 mm,
holds them. Re-found facing points also lie on the neighbour's curve where the small-sliding
ones lie on its chord: on a tensioned 1+6 the small-sliding pairs carry 2 % less force at
h = 4 mm, 1 % less at 2 mm (an O(h) error; ``tests/test_sliding_variants.py``).

Units: m, N.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from ..beam.partition import owned_rows
from ..cable.geometry import StrandGeometry
from ..contact.candidates import closest_on_segments
from ..contact.element import ContactGroup
from ..contact.friction_laws import FrictionLaw
from ..contact.kinematics import rotation_matrix
from ..contact.normal_laws import NormalLaw, SmoothOnset
from ..contact.segment import SegmentGroup
from .compliances import Wires, compliance_named
from .layer_states import SAME_LAYER, SAME_LAYER_STENCILS, helix_clearance, spread_gaps

__all__ = [
    "SAME_LAYER_STENCILS",
    "SameLayerPairs",
    "same_layer_pairs",
    "same_layer_laws",
    "same_layer_groups",
    "facing_point_motion",
]

Array = npt.NDArray[np.float64]
Int = npt.NDArray[np.int64]

#: the stencils of two nodes [c, a], pairs of ``contact.element.ContactGroup``
TWO_NODE_STENCILS = ("node", "facing")


@dataclass(frozen=True)
class SameLayerPairs:
    """Node-to-segment pairs between neighbouring wires of the helical layers (input points).

    Attributes:
        a, b0, b1: (P,) node a and the segment (b₀, b₁) of the next wire that faces it.
        weight: (P,) ξ of the facing point on the segment.
        normal: (P, 3) unit normals a → facing point at t = 0.
        gap: (P,) initial gaps, m.
        tributary: (P,) length of wire a each pair stands for, m.
        layer: (P,) the layer.
        nearest: (P,) the node of the segment nearest the facing point, c.
        offset: (P,) where the facing point lies from c along the neighbour's tangent, m.
        stencil: the pairs' stencil, one of ``SAME_LAYER_STENCILS``.
    """

    a: Int
    b0: Int
    b1: Int
    weight: Array
    normal: Array
    gap: Array
    tributary: Array
    layer: npt.NDArray[np.int32]
    nearest: Int
    offset: Array
    stencil: str = "segment"

    def __len__(self) -> int:
        return len(self.a)

    @property
    def stencils(self) -> Int:
        """Input nodes of each pair, anchor first: (P, 3) [a, b₀, b₁] or (P, 2) [c, a]."""
        if self.stencil in TWO_NODE_STENCILS:
            return np.column_stack([self.nearest, self.a])
        return np.column_stack([self.a, self.b0, self.b1])


def _wire_pairs(geometry: StrandGeometry, w: int, w_next: int):
    """Each node of wire ``w`` against the nearest point of wire ``w_next``'s polyline: nodes a,
    segments (b₀, b₁), ξ, the vectors a → facing point and the tributary lengths; nodes whose
    nearest point is an end of the neighbour are left out."""
    g = geometry
    pa = np.arange(g.wire_offsets[w], g.wire_offsets[w + 1])
    pb = np.arange(g.wire_offsets[w_next], g.wire_offsets[w_next + 1])
    X, s0, s1 = g.points[pa], g.points[pb[:-1]], g.points[pb[1:]]
    distance, xi = closest_on_segments(X, s0, s1)
    j = np.argmin(distance, axis=1)
    t = xi[np.arange(len(pa)), j]
    keep = ((t > 0) | (j > 0)) & ((t < 1) | (j < len(s0) - 1))  # faces the neighbour's span
    lengths = np.linalg.norm(np.diff(X, axis=0), axis=1)
    tributary = 0.5 * (np.r_[0.0, lengths] + np.r_[lengths, 0.0])
    facing = s0[j] + t[:, None] * (s1[j] - s0[j]) - X
    return pa[keep], pb[j][keep], pb[j + 1][keep], t[keep], facing[keep], tributary[keep]


def _empty_pairs(stencil: str) -> SameLayerPairs:
    empty, none = np.zeros(0), np.zeros(0, np.int64)
    return SameLayerPairs(
        none,
        none,
        none,
        empty,
        np.zeros((0, 3)),
        empty,
        empty,
        np.zeros(0, np.int32),
        none,
        empty,
        stencil,
    )


def _layer_spreads(geometry: StrandGeometry, gaps: str, seed: int) -> dict[int, Array]:
    """The gaps k | k + 1 of every helical layer of two wires or more (``spread_gaps``, drawn
    layer after layer from ``seed``)."""
    g = geometry
    rng = np.random.default_rng(seed)
    spreads = {}
    for i, layer in enumerate(g.cable.layers[1:], start=1):
        n = int(np.count_nonzero(g.wire_layer == i))
        if n < 2:
            continue
        spare = n * (helix_clearance(layer) - layer.wire.diameter)
        spreads[i] = spread_gaps(spare, n, gaps, rng)
    return spreads


def _facing_pairs(geometry: StrandGeometry, spreads: dict[int, Array]) -> SameLayerPairs:
    """The geometry's pairs on facing stations (``cable.facing.FacingPairs``) as two-node
    pairs [c, a]: the facing point is node c (weight 0 on the segment from c to the next node,
    no offset), the normal a → c, the gap that of the wires' place in the layer."""
    g = geometry
    f = g.facing
    if f is None:
        raise ValueError(
            'the same-layer stencil "facing" needs a geometry with facing stations: '
            "build_geometry(..., facing=True)"
        )
    if not len(f):
        return _empty_pairs("facing")
    wire = g.point_wire[f.a]
    layer = g.wire_layer[wire]
    first = np.searchsorted(g.wire_layer, layer)  # the layer's first wire
    gap = np.array([spreads[i][k] for i, k in zip(layer, wire - first, strict=True)])
    if np.any(g.point_wire[f.c + 1] != g.point_wire[f.c]):
        raise RuntimeError("internal error: a facing receiver is the last node of its wire")
    facing = g.points[f.c] - g.points[f.a]
    normal = facing / np.linalg.norm(facing, axis=1)[:, None]
    zero = np.zeros(len(f))
    return SameLayerPairs(
        f.a, f.c, f.c + 1, zero, normal, gap, f.tributary, layer, f.c, zero, "facing"
    )


def same_layer_pairs(
    geometry: StrandGeometry, gaps: str = "nominal", stencil: str = "segment", *, seed: int = 0
) -> SameLayerPairs:
    """The pairs between neighbouring wires of every helical layer, with ``gaps`` "nominal",
    "packed" or "random" (drawn from ``seed``, layer after layer) and the ``stencil`` "segment",
    "node" or "facing" (module docstring; "facing" needs a geometry with facing stations)."""
    if gaps not in SAME_LAYER[1:]:
        raise ValueError(f"same-layer gaps {gaps!r}: choose one of {', '.join(SAME_LAYER[1:])}")
    if stencil not in SAME_LAYER_STENCILS:
        raise ValueError(f"same-layer stencil {stencil!r}: choose {', '.join(SAME_LAYER_STENCILS)}")
    g = geometry
    spreads = _layer_spreads(g, gaps, seed)
    if stencil == "facing":
        return _facing_pairs(g, spreads)
    parts = []
    for i, spread in spreads.items():
        wires = np.flatnonzero(g.wire_layer == i)
        for k, w in enumerate(wires):
            a, b0, b1, xi, facing, tributary = _wire_pairs(g, w, wires[(k + 1) % len(wires)])
            gap = np.full(len(a), spread[k])
            normal = facing / np.linalg.norm(facing, axis=1)[:, None]
            parts.append((a, b0, b1, xi, normal, gap, tributary, np.full(len(a), i, np.int32)))
    if not parts:
        return _empty_pairs(stencil)
    a, b0, b1, xi, normal, gap, tributary, layer = (
        np.concatenate(c) for c in zip(*parts, strict=True)
    )
    nearest = np.where(xi < 0.5, b0, b1)
    chord = g.points[b1] - g.points[b0]
    length = np.linalg.norm(chord, axis=1)
    offset = np.where(xi < 0.5, xi, xi - 1.0) * length
    return SameLayerPairs(a, b0, b1, xi, normal, gap, tributary, layer, nearest, offset, stencil)


def same_layer_laws(
    geometry: StrandGeometry, pairs: SameLayerPairs, rows, settings
) -> tuple[Array, NormalLaw, FrictionLaw | None]:
    """The wire radii (m) and the laws of the pairs ``rows``: Hertz line contact over their
    tributary lengths and Mindlin friction ("hertz" compliance), or the line penalty ``k_line``
    and elastic slip ("penalty"), or what another registered compliance builds for line pairs
    (``compliances``); the normal law with a C¹ onset (``SmoothOnset``)."""
    layers = geometry.cable.layers
    wire = [layers[i].wire for i in pairs.layer[rows]]
    radius = np.array([w.diameter / 2 for w in wire])
    mu = np.array([layers[i].friction for i in pairs.layer[rows]])
    E, nu = np.array([w.E for w in wire]), np.array([w.nu for w in wire])
    chosen = Wires(
        line=True,
        radius_a=radius,
        radius_b=radius,
        E_a=E,
        nu_a=nu,
        E_b=E,
        nu_b=nu,
        mu=mu if settings.friction else None,
        tributary=pairs.tributary[rows],
        angle=np.zeros(len(rows)),
    )
    law, friction = compliance_named(settings.compliance).build(chosen, settings)
    return radius, SmoothOnset(law), friction


def same_layer_groups(
    geometry: StrandGeometry,
    pairs: SameLayerPairs,
    input_to_block: npt.NDArray[np.int32],
    settings,
    n_owned: int | None = None,
) -> list[SegmentGroup]:
    """``pairs`` (``same_layer_pairs``) as one small-sliding ``SegmentGroup`` (none if there are
    none), with the laws of ``same_layer_laws``. With ``n_owned`` (distributed), the pairs whose
    node a this rank owns. (Large sliding: ``strand_contact.same_layer_sliding_groups``.)"""
    rows = np.arange(len(pairs))
    if n_owned is not None:
        rows = owned_rows(input_to_block[pairs.stencils], n_owned, "same-layer pairs")
    if not len(rows):
        return []
    radius, law, friction = same_layer_laws(geometry, pairs, rows, settings)
    if pairs.stencil in TWO_NODE_STENCILS:
        c, a = pairs.nearest[rows], pairs.a[rows]
        tangents = geometry.tangents()
        return [
            ContactGroup(
                input_to_block[pairs.stencils[rows]],
                geometry.points[np.column_stack([c, a])],
                True,
                radius,
                radius,
                -pairs.normal[rows],
                law,
                friction_law=friction,
                normal="director",
                tangent0=np.stack([tangents[c], tangents[a]], axis=1),
                index=rows,
                initial_gap=pairs.gap[rows],
                offset=pairs.offset[rows],
            )
        ]
    return [
        SegmentGroup(
            input_to_block[pairs.stencils[rows]],
            pairs.weight[rows],
            radius,
            radius,
            pairs.normal[rows],
            law,
            friction_law=friction,
            initial_gap=pairs.gap[rows],
            index=rows,
            normal="neighbour",
            initial_positions=geometry.points[pairs.stencils[rows]],
        )
    ]


def facing_point_motion(geometry: StrandGeometry, pairs: SameLayerPairs, w: npt.ArrayLike) -> Array:
    """How far each pair's facing point has moved along the neighbour wire, m (P,): the offset
    of node a from the facing material point b(ξ) along the neighbour's current tangent, less
    its value at t = 0, for the nodal unknowns ``w`` (N, 6) in the geometry's order. A rigid
    motion gives 0; the facing point leaves its segment once this exceeds the room from ξ to
    the segment's end."""
    w = np.asarray(w, dtype=float)
    tangents = geometry.tangents()
    xi = pairs.weight[:, None]

    def offset(u, theta):
        x = geometry.points + u
        t = np.einsum("nij,nj->ni", rotation_matrix(theta), tangents)
        t_b = (1 - xi) * t[pairs.b0] + xi * t[pairs.b1]
        d = (1 - xi) * x[pairs.b0] + xi * x[pairs.b1] - x[pairs.a]
        return np.einsum("pi,pi->p", d, t_b) / np.linalg.norm(t_b, axis=1)

    return offset(w[:, :3], w[:, 3:]) - offset(0 * w[:, :3], 0 * w[:, 3:])
