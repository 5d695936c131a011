"""Contact between neighbouring wires of one layer: where they face each other, and their gaps.

The wires of a helical layer are identical helices turned by 2π/n. Their centre lines come closest
at a distance D found exactly (``helix_clearance``): D² = min_s 2r²(1 − cos(s + 2π/n)) + (s/ω)²,
ω = tan α / r the helix's angular rate. D − d is the layer's nominal gap. Cardinal's (from its
helices): layer 1 −14.1 µm (its six equal steel wires would overlap: they touch one another),
layers 2–4 +62.0, +78.2, +65.6 µm (``tests/test_same_layer.py`` asserts them).

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
  offset is 0, the normal a → c is perpendicular to both wires and |x_c − x_a| is D; its
  tributary is the arc between the midpoints to its wire's neighbouring stations.

Neither normal changes the gap under rigid rotations (a frozen normal closes it by d ω²/2). The
normal law is the Hertz line law over the node's tributary length of wire (with a C¹ onset,
``contact.normal_laws.SmoothOnset``: these pairs start touching without load), the friction
Mindlin's with the layer's Coulomb coefficient.

A layer of n wires has n (D − d) of spare circumference, measured between centre lines. How
stranding spreads it over the n gaps (``[contact] same_layer``, ``spread_gaps``) is the layer's
state:

* ``"nominal"``: spread evenly, every neighbour at the nominal gap D − d;
* ``"packed"``: bunched, every neighbour touching and the whole spare circumference in the one
  gap between the last and first wires;
* ``"random"``: split at random, uniformly over every split (a Dirichlet(1, …, 1) draw of the
  shares, ``[contact] gap_seed``: the same seed, the same gaps).

A layer whose helices would overlap (D < d: Cardinal's steel layer) has no spare circumference:
its wires touch one another all round, a closed ring, whatever the setting. It then rests on the
layer below too (``[contact] first_layer = "on_core"``, the default, as if the core were the
king wire that just fits: a core 0.85 % thicker for Cardinal), or stands off it as a vault
(``"ring"``: the ring widened until its helices just touch at their lay length, ``ring_lift``,
the core's line pairs open by that lift: 14.2 µm for Cardinal). A thicker core, a king wire,
is the cable's ``core.diameter``: it opens the first layer's gaps.

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

from dataclasses import dataclass, replace

import numpy as np
import numpy.typing as npt

from ..cable.description import Cable, CableError, Layer
from ..cable.geometry import StrandGeometry
from ..contact.candidates import closest_on_segments
from ..contact.element import ContactGroup
from ..contact.friction_laws import FrictionLaw
from ..contact.kinematics import rotation_matrix
from ..contact.normal_laws import NormalLaw, SmoothOnset
from ..contact.segment import SegmentGroup
from .compliances import Wires, compliance_named
from .partition import owned_rows

__all__ = [
    "FIRST_LAYER",
    "SAME_LAYER",
    "SAME_LAYER_STENCILS",
    "SameLayerPairs",
    "helix_clearance",
    "first_layer_lift",
    "ring_lift",
    "spread_gaps",
    "same_layer_pairs",
    "same_layer_laws",
    "same_layer_groups",
    "facing_point_motion",
]

Array = npt.NDArray[np.float64]
Int = npt.NDArray[np.int64]

#: choices of ``[contact] same_layer``: off, or how a layer's spare circumference is spread
SAME_LAYER = ("off", "nominal", "packed", "random")
#: choices of ``[contact] first_layer``: the first helical layer on the core, or vaulted over it
FIRST_LAYER = ("on_core", "ring")
#: choices of ``[contact] same_layer_stencil``: node to segment [a, b₀, b₁], node a to the
#: neighbour's nearest node c [c, a], or station a to the node c that faces it exactly [c, a]
#: (small sliding, on a geometry with facing stations)
SAME_LAYER_STENCILS = ("segment", "node", "facing")
#: the stencils of two nodes [c, a], pairs of ``contact.element.ContactGroup``
TWO_NODE_STENCILS = ("node", "facing")


def helix_clearance(layer: Layer) -> float:
    """The smallest distance between the centre lines of two neighbouring wires of ``layer``, m
    (golden-section search over the phase lag s ∈ [−2π/n, 0], to round-off)."""
    r, n = layer.radius, layer.wires
    omega = np.tan(layer.alpha) / r
    step = 2 * np.pi / n
    if omega == 0:  # straight wires: side by side at 2π/n
        return float(2 * r * np.sin(step / 2))

    def square(s):
        return 2 * r * r * (1 - np.cos(s + step)) + (s / omega) ** 2

    lo, hi = -step, 0.0
    golden = (np.sqrt(5) - 1) / 2
    for _ in range(200):
        a, b = hi - golden * (hi - lo), lo + golden * (hi - lo)
        if square(a) < square(b):
            hi = b
        else:
            lo = a
    return float(np.sqrt(square(0.5 * (lo + hi))))


def ring_lift(layer: Layer) -> float:
    """How far ``layer``'s wires must move out, at their lay length, for their helices to just
    touch one another, m: 0 where they do not overlap (bisection to 1e-12 m of the radius)."""
    d = layer.wire.diameter
    if helix_clearance(layer) >= d:
        return 0.0

    def clearance(lift: float) -> float:
        r = layer.radius + lift
        angle = np.degrees(np.arctan(np.tan(layer.alpha) * r / layer.radius))  # same lay length
        return helix_clearance(replace(layer, radius=r, lay_angle=float(angle)))

    lo, hi = 0.0, d
    while hi - lo > 1e-12:
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if clearance(mid) < d else (lo, mid)
    return 0.5 * (lo + hi)


def spread_gaps(spare: float, n: int, how: str, rng: np.random.Generator | None = None) -> Array:
    """The n gaps between neighbours k | k + 1 of a layer (m, the last between wires n − 1 and
    0) that has ``spare`` circumference (m): ``how`` "nominal" (evenly), "packed" (all in the
    last) or "random" (shares drawn from ``rng``, Dirichlet(1, …, 1)). No spare (≤ 0): every
    neighbour touching."""
    if spare <= 0:
        return np.zeros(n)
    if how == "nominal":
        return np.full(n, spare / n)
    if how == "packed":
        return np.r_[np.zeros(n - 1), spare]
    if how == "random":
        if rng is None:
            raise ValueError("random gaps need a random generator")
        return spare * rng.dirichlet(np.ones(n))
    raise ValueError(f"same-layer gaps {how!r}: choose one of {', '.join(SAME_LAYER[1:])}")


def first_layer_lift(cable: Cable, first_layer: str) -> float:
    """The initial gap of the core's line pairs, m: 0 on the core, ``ring_lift`` of the first
    helical layer for a ring (``CableError`` where its helices do not overlap: no ring)."""
    if first_layer not in FIRST_LAYER:
        raise CableError(
            f"contact first_layer {first_layer!r} is unknown; choose {' or '.join(FIRST_LAYER)}"
        )
    if first_layer == "on_core" or len(cable.layers) < 2:
        return 0.0
    layer = cable.layers[1]
    gap = helix_clearance(layer) - layer.wire.diameter
    if gap >= 0:
        raise CableError(
            f'contact first_layer = "ring": the first layer\'s wires do not touch one another '
            f"(their nominal gap is {gap * 1e6:+.1f} µm), so they cannot vault over the core; "
            'use "on_core"'
        )
    return ring_lift(layer)


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
