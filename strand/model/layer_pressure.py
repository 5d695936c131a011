"""Where each layer's pressure goes: per helical layer, the radial load its wires put on the
crossings below, the share its same-layer ring carries, and the fibre model's pressure.

A helical wire of axial force T (N), lay angle α and lay radius r (m) is curved by
κ = sin²α / r (1/m), so its tension presses it inward by T sin²α / r per metre of wire
(docs/theory.md §5.6), T sin²α / (r cos α) per metre of strand. The fibre model's line pressure of
a layer of n wires, per metre of strand (N/m), is

    q_fibre = n T sin²α / (r cos α).

It goes down, through the crossings (or the core's line contact) below, and round, through the
contacts between neighbours of the layer. Neighbours pressed together by a line force f (N/m of
strand) along their centre-to-centre chord, the n wires at 2π/n apart on the circle of radius r:
each chord leans by π/n from the tangent, so each wire is pushed outward by 2 f sin(π/n) by its
two neighbours, and the ring carries q_ring = 2 n f sin(π/n) (N/m). That is the ring relation: a
closed ring of hoop force H (here per metre of strand, N/m) carries the radial pressure H / r per
unit circumference, 2π H over the whole circumference, the limit of 2 n f sin(π/n) for large n.
Radial equilibrium of layer i per metre of strand (the crossings above it, layer i + 1's load
on it, pushing inward too):

    q_fibre,i + q_below,i+1 = q_below,i + q_ring,i.

``layer_pressure`` measures, over the middle half of the span (away from the ends' grips):

* ``crossings_below``: Σ F n·e_r over the pairs between layers i − 1 and i (crossings, or the
  core's line pairs for layer 1), per metre of strand, F the pair's normal force, n its normal
  (inner → outer), e_r the radial direction from the core's current centre line;
* ``ring``: Σ F (n·e_r(b) − n·e_r(a)) + t·(e_r(a) − e_r(b)) over the layer's same-layer pairs
  (a → neighbour b, t the friction force on a), per metre: the outward resultant of the
  neighbours' pushes, 2 f sin(π/n) per contact for a regular ring, and of their friction
  (``ring_friction``: 1.7 % of a tensioned 1+6 ring's load); ``hoop``: the mean contact's
  normal line force in the cross-section's plane, H (N/m), with ``ring − ring_friction`` ≈
  2 n sin(π/n) H;
* the gap: the layer's widest initial gap (``same_layer.same_layer_pairs``; packed layers gather
  their spare circumference between their last and first wires); ``gap_force`` is that
  contact's line force (N/m of strand), ``bounding`` the line forces of the contacts either side
  of it (for a packed layer: last but one | last wire, first | second), ``gap_min`` the smallest
  gap across it (m) and ``gap_closed`` whether it touches anywhere in the middle half (a gap ≤ 0
  with a force > 0).

Units: m, N, N/m.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from ..cable.geometry import StrandGeometry
from .pair_results import PairResults
from .same_layer import SameLayerPairs

__all__ = ["LayerPressure", "layer_pressure", "layer_wire_forces", "fibre_pressure"]

Array = npt.NDArray[np.float64]


@dataclass(frozen=True, kw_only=True)
class LayerPressure:
    """Where one helical layer's pressure goes, per metre of strand over the middle half.

    Attributes:
        layer: the layer (1 = first helical layer).
        wire_force: mean axial force of its wires there, N.
        fibre: the fibre model's line pressure n T sin²α / (r cos α), N/m.
        crossings_below: radial load on the pairs between layers i − 1 and i, N/m.
        ring: radial load the layer's same-layer pairs carry, N/m (0 without them): their
            normal forces' and their friction's.
        ring_friction: the friction's part of ``ring``, N/m.
        hoop: the ring's hoop force H per metre of strand, N/m (ring ≈ 2 n sin(π/n) H).
        gap_force: line force across the layer's widest initial gap (packed: last | first
            wire), N/m.
        bounding: line forces of the contacts either side of the gap, N/m.
        gap_min: smallest gap across the layer's gap, m (NaN without same-layer pairs).
        gap_closed: whether the gap touches anywhere in the middle half.
    """

    layer: int
    wire_force: float
    fibre: float
    crossings_below: float
    ring: float = 0.0
    ring_friction: float = 0.0
    hoop: float = 0.0
    gap_force: float = 0.0
    bounding: tuple[float, float] = (0.0, 0.0)
    gap_min: float = float("nan")
    gap_closed: bool = False


def fibre_pressure(geometry: StrandGeometry, wire_force: npt.ArrayLike) -> Array:
    """Per helical layer 1, 2, …: n T sin²α / (r cos α), N/m of strand, for its wires' axial
    forces ``wire_force`` (N, one per helical layer)."""
    layers = geometry.cable.layers[1:]
    T = np.asarray(wire_force, dtype=float)
    return np.array(
        [
            lay.wires * t * np.sin(lay.alpha) ** 2 / (lay.radius * np.cos(lay.alpha))
            for lay, t in zip(layers, T, strict=True)
        ]
    )


def in_middle_half(z: npt.ArrayLike, length: float) -> npt.NDArray[np.bool_]:
    """Whether heights ``z`` (m) lie in the middle half [L/4, 3L/4) of a span ``length`` (m).
    Half-open, so that a sum over it divided by L/2 is per metre when points repeat along z
    (a pair at each end would count twice), and to round-off: nodes at L/4 and 3L/4 land on
    either side of the exact value."""
    z, tol = np.asarray(z), 1e-12 * length
    return (z >= 0.25 * length - tol) & (z < 0.75 * length - tol)


def layer_wire_forces(
    layer: npt.ArrayLike,
    z: npt.ArrayLike,
    axial: npt.ArrayLike,
    length: float,
    *,
    core: bool = False,
) -> Array:
    """Mean axial force (N) of the cells of each helical layer 1, 2, … (and first of the core,
    layer 0, with ``core``) whose midpoint ``z`` (m) lies in the middle half of the span
    ``length`` (``in_middle_half``; ``cell_results.CellResults``' arrays)."""
    layer, z, axial = (np.asarray(v) for v in (layer, z, axial))
    middle = in_middle_half(z, length)
    n = int(layer.max()) if len(layer) else 0
    return np.array([axial[middle & (layer == i)].mean() for i in range(0 if core else 1, n + 1)])


def _widest(pairs: SameLayerPairs, wire_of_a: npt.NDArray[np.int64], wires) -> int:
    """Which of ``wires`` (one layer's, in order) starts the widest gap to the next: the last
    of the widest (packed layers: the last wire)."""
    initial = np.array([pairs.gap[wire_of_a == w].max(initial=-np.inf) for w in wires])
    return len(wires) - 1 - int(np.argmax(initial[::-1]))


def _radial(geometry: StrandGeometry, x: Array, z0: Array, core: Array) -> Array:
    """Unit radial directions at the current points ``x`` (P, 3) of initial heights ``z0``: from
    the core's current centre line ``core`` (its points' positions, z = 0 to L), across it."""
    z_core = geometry.points[geometry.wire_offsets[0] : geometry.wire_offsets[1], 2]
    centre = np.column_stack([np.interp(z0, z_core, core[:, k]) for k in range(3)])
    tangent = _radial_axis(geometry, z0, core)
    d = x - centre
    d -= np.einsum("ij,ij->i", d, tangent)[:, None] * tangent
    return d / np.linalg.norm(d, axis=1)[:, None]


def layer_pressure(
    geometry: StrandGeometry,
    crossings: PairResults,
    wire_force: npt.ArrayLike,
    positions: Array | None = None,
    *,
    same_layer: SameLayerPairs | None = None,
    same_layer_state: dict[str, Array] | None = None,
) -> list[LayerPressure]:
    """Where each helical layer's pressure goes at one state (module docstring).

    Args:
        geometry: the strand.
        crossings: its pairs' results at the state (``StrandModel.pair_results``).
        wire_force: mean axial force of each helical layer's wires, N (``layer_wire_forces``).
        positions: current positions of the geometry's points (N, 3), m (default: initial).
        same_layer: the same-layer pairs (``StrandModel.same_layer_pairs``; None: none).
        same_layer_state: their ``gap``, ``force``, ``normal`` and friction ``traction`` at
            the state (``StrandModel.same_layer_history``).
    """
    g = geometry
    x = g.points if positions is None else np.asarray(positions, dtype=float)
    core = x[g.wire_offsets[0] : g.wire_offsets[1]]
    L = g.length
    window = L / 2
    fibre = fibre_pressure(g, wire_force)
    p = g.pairs
    z_a = g.points[p.a, 2]
    inside = in_middle_half(z_a, L)
    e_r = _radial(g, 0.5 * (x[p.a] + x[p.b]), 0.5 * (z_a + g.points[p.b, 2]), core)
    radial = crossings.force * np.einsum("ij,ij->i", crossings.normal, e_r)
    wire_of = np.searchsorted(g.wire_offsets, np.arange(len(g.points)), side="right") - 1

    ring_terms = None
    if same_layer is not None and same_layer_state and len(same_layer):
        s, st = same_layer, same_layer_state
        xb = (1 - s.weight[:, None]) * x[s.b0] + s.weight[:, None] * x[s.b1]
        zb = (1 - s.weight) * g.points[s.b0, 2] + s.weight * g.points[s.b1, 2]
        # groups whose anchor is the neighbour (node stencil, large sliding) give the normal
        # b → a and the friction on b: turn both to a → b and the friction on a
        n = np.asarray(st["normal"], dtype=float)
        turn = np.where(np.einsum("ij,ij->i", n, xb - x[s.a]) < 0, -1.0, 1.0)
        n = turn[:, None] * n
        er_a = _radial(g, x[s.a], g.points[s.a, 2], core)
        er_b = _radial(g, xb, zb, core)
        force = np.asarray(st["force"], dtype=float)
        ring_terms = force * np.einsum("ij,ij->i", n, er_b - er_a)
        traction = turn[:, None] * np.asarray(st.get("traction", np.zeros_like(n)), dtype=float)
        friction_terms = np.einsum("ij,ij->i", traction, er_a - er_b)
        axis = _radial_axis(g, g.points[s.a, 2], core)
        in_plane = np.linalg.norm(n - np.einsum("ij,ij->i", n, axis)[:, None] * axis, axis=1)
        s_inside = in_middle_half(g.points[s.a, 2], L)
        s_wire = wire_of[s.a]

    out = []
    for i, lay in enumerate(g.cable.layers[1:], start=1):
        below = radial[inside & (p.interface == i - 1)].sum() / window
        record = {
            "layer": i,
            "wire_force": float(np.asarray(wire_force)[i - 1]),
            "fibre": float(fibre[i - 1]),
            "crossings_below": float(below),
        }
        if ring_terms is not None and lay.wires > 1:
            mine = s_inside & (s.layer == i)
            wires = np.flatnonzero(g.wire_layer == i)
            k = _widest(s, s_wire, wires)
            gap_pairs = mine & (s_wire == wires[k])
            either_side = (wires[k - 1], wires[(k + 1) % len(wires)])
            line = [force[mine & (s_wire == w)].sum() / window for w in either_side]
            gaps = np.asarray(st["gap"])[gap_pairs]
            record |= {
                "ring": float((ring_terms + friction_terms)[mine].sum() / window),
                "ring_friction": float(friction_terms[mine].sum() / window),
                "hoop": float((force * in_plane)[mine].sum() / (lay.wires * window)),
                "gap_force": float(force[gap_pairs].sum() / window),
                "bounding": (float(line[0]), float(line[1])),
                "gap_min": float(gaps.min()) if len(gaps) else float("nan"),
                "gap_closed": bool(np.any((gaps <= 0) & (force[gap_pairs] > 0))),
            }
        out.append(LayerPressure(**record))
    return out


def _radial_axis(geometry: StrandGeometry, z0: Array, core: Array) -> Array:
    """The core's current unit tangent at initial heights ``z0``."""
    z_core = geometry.points[geometry.wire_offsets[0] : geometry.wire_offsets[1], 2]
    t = np.column_stack([np.interp(z0, z_core, np.gradient(core[:, k], z_core)) for k in range(3)])
    return t / np.linalg.norm(t, axis=1)[:, None]
