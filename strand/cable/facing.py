"""Facing stations of a strand's helical layers (``build_geometry(facing=True)``, ``[contact]
same_layer_stencil = "facing"``; docs/theory.md §3.4).

The wires of each helical layer carry facing stations: wire j at z₀ + jδ + kΔ, where δ
(``facing_offset``) is how far along z wire j + 1 faces wire j, so that station k of wire j + 1
is exactly where station k of wire j faces it (``FacingPairs``). ``plan_stations`` gives the z
each wire must carry for them, before the geometry places its nodes; ``station_pairs`` then finds
the pairs' nodes among them. Units: m.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from .description import CableError

__all__ = ["FacingPairs", "facing_offset", "FACING_TOL"]

#: m along z: a facing station closer than this to a crossing or an end is no station (the node
#: there stands alone), and a wrap receiver closer than this to another node is left out
FACING_TOL = 1e-5
#: m along z: a wrap receiver this close to a station of wire 0 is that station (straight wires)
FACING_SAME = 1e-12


@dataclass
class FacingPairs:
    """Same-layer pairs on facing stations, by input point (``build_geometry(facing=True)``).

    Station ``a`` of wire j (a layer's wires in order of phase) and the node ``c`` of wire j + 1
    (wire 0 after the last) at z + δ of the layer (``facing_offset``): the two centres are the
    closest points of the two helices, ‖x_c − x_a‖ their clearance D.
    """

    a: npt.NDArray[np.int64]
    c: npt.NDArray[np.int64]
    tributary: npt.NDArray[np.float64]  # m of wire a (arc) each pair stands for

    def __len__(self) -> int:
        return len(self.a)


def facing_offset(layer) -> float:
    """δ (m, along z): wire j + 1 of ``layer`` faces wire j at z from z + δ, at every z.

    With β = 2π/n and ω the layer's angular rate, ‖x_{j+1}(z + Δz) − x_j(z)‖² =
    2r²(1 − cos(β + ωΔz)) + Δz², whose minimum over Δz is at δ = −r²ω sin(β + ωδ) (Newton's
    method from its first-order root −r²ω sin β/(1 + r²ω² cos β), to round-off); 0 for straight
    wires and for a layer of one wire."""
    r, n, omega = layer.radius, layer.wires, layer.angular_rate
    if omega == 0 or n < 2:
        return 0.0
    beta = 2 * math.pi / n
    delta = -r * r * omega * math.sin(beta) / (1 + (r * omega) ** 2 * math.cos(beta))
    for _ in range(50):
        step = (delta + r * r * omega * math.sin(beta + omega * delta)) / (
            1 + (r * omega) ** 2 * math.cos(beta + omega * delta)
        )
        delta -= step
        if abs(step) <= 1e-15 * r:
            break
    return delta


def plan_stations(layers, first_wire, fixed, length, h_max, merge_tol):
    """The facing stations of every helical layer of two wires or more (``layers``, whose wires
    are ``first_wire[i]:first_wire[i + 1]``): the z each wire must carry are appended to its list
    of ``fixed`` z (which hold the crossings), and the plan returned, per layer its wires and
    pairs (``_facing_layer``), for ``station_pairs`` once the nodes are placed."""
    tol = max(FACING_TOL, 2 * merge_tol)
    plan = []
    for i in range(1, len(layers)):
        wires = range(first_wire[i], first_wire[i + 1])
        if len(wires) < 2:
            continue
        carry, pairs = _facing_layer(
            layers[i], [fixed[w] for w in wires], length, h_max, merge_tol, tol
        )
        for w, z in zip(wires, carry, strict=True):
            fixed[w].append(z)
        plan.append((wires, pairs))
    return plan


def station_pairs(plan, offsets, node_z) -> FacingPairs:
    """The pairs of ``plan`` (``plan_stations``) by input point: wire w's points are
    ``offsets[w]:offsets[w + 1]``, at the sorted heights ``node_z[w]``, among which every station
    and receiver is exactly."""
    found = [np.zeros(0, np.int64), np.zeros(0, np.int64), np.zeros(0)]
    for wires, pairs in plan:
        for j, z_a, z_c, tributary in pairs:
            wa, wc = wires[j], wires[(j + 1) % len(wires)]
            found[0] = np.append(found[0], offsets[wa] + _exact_index(node_z[wa], z_a))
            found[1] = np.append(found[1], offsets[wc] + _exact_index(node_z[wc], z_c))
            found[2] = np.append(found[2], tributary)
    return FacingPairs(*found)


def _far(z, others, tol):
    """Whether each of ``z`` lies at least ``tol`` from every one of ``others`` (sorted)."""
    if not len(others):
        return np.ones(len(z), dtype=bool)
    i = np.searchsorted(others, z)
    below = others[np.clip(i - 1, 0, len(others) - 1)]
    above = others[np.clip(i, 0, len(others) - 1)]
    return np.minimum(np.abs(z - below), np.abs(z - above)) >= tol


def _facing_layer(layer, fixed, length, h_max, merge_tol, tol):
    """The facing stations of one helical layer of n ≥ 2 wires, whose fixed z (crossings) per
    wire are ``fixed``: per wire the z it must carry, and the pairs (j, z_a, z_c, tributary) of
    each wire j, sorted by z_a.

    Station k of wire j is at z₀ + jδ + kΔ in [0, L], Δ = h_max cos α − 2 (tol + merge_tol): a
    station that is dropped (within ``tol`` of a crossing or an end) leaves at most Δ + 2 (tol +
    merge_tol) between nodes, so no cell exceeds h_max and none is split. Station k of wire
    j + 1 receives station k of wire j; wire n − 1's stations face wire 0 at z₀ + nδ + kΔ, added
    to wire 0 as receivers, which start no pair (no cascade). A pair is kept where both its
    station and its receiver are."""
    n, cos_a = layer.wires, math.cos(layer.alpha)
    delta = facing_offset(layer)
    spacing = h_max * cos_a - 2 * (tol + merge_tol)
    if not spacing > 4 * tol:
        raise CableError(
            f"h_max = {h_max!r} m is too short for facing stations (same_layer_stencil = "
            f'"facing"): they need h_max > {(6 * tol + 2 * merge_tol) / cos_a:.3g} m here'
        )
    z0 = 0.5 * spacing
    ends = np.array([0.0, length])

    def lattice(j):
        base = z0 + j * delta  # one formula: a receiver is bitwise its station
        k = np.arange(math.floor(-base / spacing) - 1, math.ceil((length - base) / spacing) + 2)
        z = base + k * spacing
        inside = (z >= 0) & (z <= length)
        return k[inside], z[inside]

    occupied = [np.sort(np.concatenate([ends, *f])) if f else ends for f in fixed]
    stations = []
    for j in range(n):
        k, z = lattice(j)
        stations.append((k, z, _far(z, occupied[j], tol)))
    carry = [z[kept] for _, z, kept in stations]
    pairs = []
    for j in range(n):
        k, z, kept = stations[j]
        if j < n - 1:
            k_next, z_next, kept_next = stations[j + 1]
            _, ia, ic = np.intersect1d(k, k_next, assume_unique=True, return_indices=True)
            ok = kept[ia] & kept_next[ic]
            z_a, z_c = z[ia][ok], z_next[ic][ok]
        else:  # the wrap: receivers on wire 0, away from its nodes (or on one of its stations)
            z_r = z0 + n * delta + k * spacing
            inside = (z_r >= 0) & (z_r <= length)
            own = carry[0]
            if len(own):
                at = np.minimum(np.searchsorted(own, z_r), len(own) - 1)
                below = np.maximum(at - 1, 0)
                at = np.where(np.abs(own[below] - z_r) < np.abs(own[at] - z_r), below, at)
                same = np.abs(own[at] - z_r) <= FACING_SAME
                z_r = np.where(same, own[at], z_r)  # that station is the receiver
            else:
                same = np.zeros(len(z_r), dtype=bool)
            alone = _far(z_r, occupied[0], tol) & _far(z_r, own, tol)
            ok = kept & inside & (same | alone)
            z_a, z_c = z[ok], z_r[ok]
            carry[0] = np.sort(np.concatenate([own, z_r[ok & ~same]]))
        bounds = np.concatenate([[0.0], 0.5 * (z_a[1:] + z_a[:-1]), [length]])
        pairs.append((j, z_a, z_c, np.diff(bounds) / cos_a if len(z_a) else np.zeros(0)))
    return carry, pairs


def _exact_index(z_nodes, z):
    i = np.minimum(np.searchsorted(z_nodes, z), len(z_nodes) - 1)
    if np.any(z_nodes[i] != z):
        raise RuntimeError("internal error: a facing station has no node")
    return i
