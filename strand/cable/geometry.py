"""Strand geometry in numpy: helical centrelines, contact points, nodes and contact pairs.

Every wire of layer i ≥ 1 is a helix of radius r_i about the z axis, φ(z) = φ0 + ω_i z with
ω_i = ±tan(α_i)/r_i (+ for Z, − for S lay) and φ0 = 2πj/n_i; the core is straight along z. Layers
touch radially: r_i = r_{i−1} + (d_{i−1} + d_i)/2.

Contact points (small-sliding model: found once, here, and never re-paired):

* crossing points between wires of adjacent helical layers, where the two centres are radially
  aligned: φ_a(z) = φ_b(z) mod 2π, i.e. z_k = (φ0_b − φ0_a + 2πk)/(ω_a − ω_b). By the two-fold symmetry of
  both helices about that radial line, this is where their distance is smallest, equal to
  (d_a + d_b)/2: the initial gap is zero to round-off, and the normal is radial;
* the core | layer-1 line contact, discretised by pairing every layer-1 node with a core node at the
  same z (radially aligned too), each standing for its tributary length of the line.

Every contact point is a mesh node of both wires; elements are then split so that none exceeds
``h_max`` (arc length).

With ``facing=True`` (``[contact] same_layer_stencil = "facing"``) the wires of each helical layer
also carry facing stations, where the wires of a layer face each other exactly, and the geometry
their pairs (``strand.cable.facing``; docs/theory.md §3.4). Units: m.
"""

from __future__ import annotations

import math
from dataclasses import KW_ONLY, dataclass, field

import numpy as np
import numpy.typing as npt

from .description import Cable, CableError
from .facing import FacingPairs, plan_stations, station_pairs

__all__ = ["ContactPairs", "StrandGeometry", "build_geometry", "POINT", "LINE"]

POINT, LINE = 0, 1


@dataclass
class ContactPairs:
    """Node pairs in contact, indexed by input point (row of ``StrandGeometry.points``).

    ``a`` is on the inner wire, ``b`` on the outer one; ``normal`` points from a to b.
    """

    a: npt.NDArray[np.int64]
    b: npt.NDArray[np.int64]
    kind: npt.NDArray[np.int8]  # POINT (crossing) or LINE (core | layer 1)
    interface: npt.NDArray[np.int8]  # i for the interface between layers i and i + 1
    radius_a: npt.NDArray[np.float64]  # m
    radius_b: npt.NDArray[np.float64]  # m
    normal: npt.NDArray[np.float64]  # (P, 3) initial unit normal, from a to b
    friction: npt.NDArray[np.float64]  # Coulomb coefficient
    tributary: npt.NDArray[np.float64]  # m of contact line a LINE pair stands for; 0 for POINT

    def __len__(self) -> int:
        return len(self.a)

    def select(self, mask) -> ContactPairs:
        return ContactPairs(**{k: v[mask] for k, v in vars(self).items()})


@dataclass
class StrandGeometry:
    """Nodes, two-node cells and contact pairs of a strand of length ``length`` (m)."""

    cable: Cable
    length: float
    h_max: float
    points: npt.NDArray[np.float64]  # (N, 3) m
    cells: npt.NDArray[np.int64]  # (E, 2) point indices, oriented towards +z
    cell_wire: npt.NDArray[np.int32]  # (E,)
    wire_layer: npt.NDArray[np.int32]  # (W,)
    wire_offsets: npt.NDArray[np.int64]  # (W + 1,) points of wire w: offsets[w]:offsets[w+1]
    pairs: ContactPairs
    wire_phase: npt.NDArray[np.float64] = field(repr=False, default=None)  # (W,) φ0 (rad)
    _: KW_ONLY
    facing: FacingPairs | None = field(repr=False, default=None)  # facing stations' pairs

    @property
    def cell_layer(self) -> npt.NDArray[np.int32]:
        return self.wire_layer[self.cell_wire]

    @property
    def point_wire(self) -> npt.NDArray[np.int32]:
        return np.repeat(
            np.arange(len(self.wire_layer), dtype=np.int32), np.diff(self.wire_offsets)
        )

    def centres(self, wires: npt.ArrayLike, z: npt.ArrayLike) -> npt.NDArray[np.float64]:
        """Initial centreline points (m) of wires ``wires`` at heights ``z`` (broadcast)."""
        return _centres(self.cable, self.wire_phase, self.wire_layer, wires, z)

    def tangents(self) -> npt.NDArray[np.float64]:
        """Initial unit tangents of the centrelines at every point (N, 3), towards +z (analytic)."""
        radius, rate, phi = _helix(
            self.cable, self.wire_phase, self.wire_layer, self.point_wire, self.points[:, 2]
        )
        t = np.column_stack(
            [-radius * rate * np.sin(phi), radius * rate * np.cos(phi), np.ones(len(phi))]
        )
        return t / np.linalg.norm(t, axis=1)[:, None]

    def cell_lengths(self) -> npt.NDArray[np.float64]:
        return np.linalg.norm(np.diff(self.points[self.cells], axis=1)[:, 0], axis=1)

    def gaps(self) -> npt.NDArray[np.float64]:
        """Initial gaps (x_b − x_a)·n − r_a − r_b of the pairs (m); zero to round-off by design."""
        p = self.pairs
        d = self.points[p.b] - self.points[p.a]
        return np.einsum("ij,ij->i", d, p.normal) - p.radius_a - p.radius_b


def _helix(cable: Cable, phase, wire_layer, wires, z):
    """Helix radius r (m), angular rate ω (rad/m) and angle φ = φ0 + ω z of wires at heights z."""
    lay = wire_layer[wires]
    radius = np.array([layer.radius for layer in cable.layers])[lay]
    rate = np.array([layer.angular_rate for layer in cable.layers])[lay]
    return radius, rate, phase[wires] + rate * z


def _centres(cable: Cable, phase, wire_layer, wires, z) -> npt.NDArray[np.float64]:
    """Helix centres: (r cos φ, r sin φ, z) with φ = φ0 + ω z, for wire ids and z (broadcast)."""
    wires, z = np.broadcast_arrays(np.asarray(wires), np.asarray(z, dtype=np.float64))
    radius, _, phi = _helix(cable, phase, wire_layer, wires, z)
    return np.stack([radius * np.cos(phi), radius * np.sin(phi), z], axis=-1)


def _crossings(lay_a, lay_b, length):
    """All (z, j_a, j_b) where wire j_a of lay_a and wire j_b of lay_b are radially aligned."""
    w_rel = lay_a.angular_rate - lay_b.angular_rate
    if abs(w_rel) * length < 1e-9:
        raise CableError(
            "two adjacent helical layers have the same lay and pitch: their wires touch along "
            "lines, which is only modelled between the core and layer 1"
        )
    ja, jb = np.meshgrid(np.arange(lay_a.wires), np.arange(lay_b.wires), indexing="ij")
    ja, jb = ja.ravel(), jb.ravel()
    dphi = 2 * np.pi * (jb / lay_b.wires - ja / lay_a.wires)
    # z = (dphi + 2πk)/w_rel ∈ [0, L]
    k_lo = np.ceil((np.minimum(0, w_rel * length) - dphi) / (2 * np.pi) - 1e-12).astype(int)
    k_hi = np.floor((np.maximum(0, w_rel * length) - dphi) / (2 * np.pi) + 1e-12).astype(int)
    count = np.maximum(k_hi - k_lo + 1, 0)
    rep = np.repeat(np.arange(len(ja)), count)
    k = k_lo[rep] + (np.arange(count.sum()) - np.repeat(np.cumsum(count) - count, count))
    z = np.clip((dphi[rep] + 2 * np.pi * k) / w_rel, 0.0, length)
    return z, ja[rep], jb[rep]


def _node_z(z_fixed, length, cos_alpha, h_max, merge_tol):
    """Sorted node z on one wire: the fixed ones (contact points, ends), merged when closer than
    ``merge_tol``, then intervals split evenly so no cell exceeds h_max in arc length."""
    z = np.unique(np.concatenate([[0.0, length], z_fixed]))
    if len(z) > 1:
        keep = np.concatenate([[True], np.diff(z) > merge_tol])
        z = z[keep]
        z[-1] = length
    dz = np.diff(z)
    n_sub = np.maximum(np.ceil(dz / cos_alpha / h_max - 1e-9).astype(int), 1)
    starts = np.repeat(z[:-1], n_sub)
    frac = np.arange(n_sub.sum()) - np.repeat(np.cumsum(n_sub) - n_sub, n_sub)
    return np.append(starts + frac * np.repeat(dz / n_sub, n_sub), length)


def _index_of(z_nodes, z, tol):
    i = np.clip(np.searchsorted(z_nodes, z), 1, len(z_nodes) - 1)
    i = np.where(np.abs(z_nodes[i - 1] - z) < np.abs(z_nodes[i] - z), i - 1, i)
    if np.any(np.abs(z_nodes[i] - z) > tol):
        raise RuntimeError("internal error: a contact point has no node")
    return i


def build_geometry(
    cable: Cable,
    length: float = 1.0,
    h_max: float = 4e-3,
    merge_tol: float = 1e-6,
    facing: bool = False,
) -> StrandGeometry:
    """Nodes at every contact point, cells of at most ``h_max`` (m), and the contact pairs.

    Contact points on one wire closer than ``merge_tol`` (m, along z) share a node. ``facing``:
    the helical layers' wires carry facing stations too, and the geometry their same-layer
    pairs (``StrandGeometry.facing``; module docstring); without it, none.
    """
    if not length > 0:
        raise CableError(f"length = {length!r} m: must be positive")
    if not h_max > 0:
        raise CableError(f"h_max = {h_max!r} m: must be positive")
    layers = cable.layers
    steepest = max(layer.alpha for layer in layers)
    if not h_max * math.cos(steepest) > merge_tol:
        raise CableError(
            f"h_max = {h_max!r} m: elements must span more than merge_tol = {merge_tol!r} m along "
            f"the axis (h_max > {merge_tol / math.cos(steepest):.4g} m here): nodes closer than "
            "that merge"
        )
    n_layers = len(layers)
    wire_layer = np.concatenate(
        [np.full(lay.wires, i, dtype=np.int32) for i, lay in enumerate(layers)]
    )
    first_wire = np.concatenate([[0], np.cumsum([lay.wires for lay in layers])])
    phase = np.concatenate([2 * np.pi * np.arange(lay.wires) / lay.wires for lay in layers])

    # crossing points per interface i | i + 1 (i ≥ 1), and the z that each wire must carry
    fixed: list[list[np.ndarray]] = [[] for _ in wire_layer]
    crossings = []
    for i in range(1, n_layers - 1):
        z, ja, jb = _crossings(layers[i], layers[i + 1], length)
        wa, wb = first_wire[i] + ja, first_wire[i + 1] + jb
        crossings.append((i, z, wa, wb))
        for w_ids, zz in ((wa, z), (wb, z)):
            order = np.argsort(w_ids, kind="stable")
            split = np.split(zz[order], np.searchsorted(w_ids[order], np.unique(w_ids)))
            for w, chunk in zip(np.unique(w_ids), split[1:], strict=True):
                fixed[w].append(chunk)

    # facing stations (and wire 0's receivers) per helical layer of two wires or more
    if facing:
        facing_plan = plan_stations(layers, first_wire, fixed, length, h_max, merge_tol)

    node_z = [None] * len(wire_layer)
    for w, lay_id in enumerate(wire_layer):
        if lay_id == 0:
            continue
        zf = np.concatenate(fixed[w]) if fixed[w] else np.zeros(0)
        node_z[w] = _node_z(zf, length, np.cos(layers[lay_id].alpha), h_max, merge_tol)
    # the core carries a node at the z of every layer-1 node (line contact pairs)
    l1 = range(first_wire[1], first_wire[2])
    node_z[0] = _node_z(np.concatenate([node_z[w] for w in l1]), length, 1.0, h_max, merge_tol)

    # points and cells
    counts = np.array([len(z) for z in node_z])
    offsets = np.concatenate([[0], np.cumsum(counts)])
    wire_of_point = np.repeat(np.arange(len(node_z)), counts)
    lay_of_point = wire_layer[wire_of_point]
    points = _centres(cable, phase, wire_layer, wire_of_point, np.concatenate(node_z))
    first = np.delete(np.arange(offsets[-1] - 1), offsets[1:-1] - 1)
    cells = np.column_stack([first, first + 1])
    cell_wire = wire_of_point[first].astype(np.int32)

    # pairs
    tol = max(merge_tol, 1e-12 * length)
    parts = []
    for i, z, wa, wb in crossings:
        a = np.empty(len(z), dtype=np.int64)
        b = np.empty(len(z), dtype=np.int64)
        for w in np.unique(np.concatenate([wa, wb])):
            on_a, on_b = wa == w, wb == w
            a[on_a] = offsets[w] + _index_of(node_z[w], z[on_a], tol)
            b[on_b] = offsets[w] + _index_of(node_z[w], z[on_b], tol)
        parts.append((a, b, POINT, i, 0.0))
    # line pairs: every layer-1 node with the core node at its z
    for w in l1:
        zb = node_z[w]
        a = offsets[0] + _index_of(node_z[0], zb, tol)
        b = offsets[w] + np.arange(len(zb))
        ds = np.diff(zb) / np.cos(layers[1].alpha)
        trib = np.concatenate([[0.0], ds]) / 2 + np.concatenate([ds, [0.0]]) / 2
        parts.append((a, b, LINE, 0, trib))
    a = np.concatenate([p[0] for p in parts])
    b = np.concatenate([p[1] for p in parts])
    kind = np.concatenate([np.full(len(p[0]), p[2], dtype=np.int8) for p in parts])
    interface = np.concatenate([np.full(len(p[0]), p[3], dtype=np.int8) for p in parts])
    tributary = np.concatenate([np.broadcast_to(p[4], len(p[0])) for p in parts]).astype(float)
    radial = points[b, :2] / np.linalg.norm(points[b, :2], axis=1)[:, None]
    normal = np.column_stack([radial, np.zeros(len(b))])
    half_d = np.array([lay.wire.diameter / 2 for lay in layers])
    pairs = ContactPairs(
        a=a,
        b=b,
        kind=kind,
        interface=interface,
        radius_a=half_d[lay_of_point[a]],
        radius_b=half_d[lay_of_point[b]],
        normal=normal,
        friction=np.array([lay.friction for lay in layers])[interface],
        tributary=tributary,
    )
    facing_pairs = station_pairs(facing_plan, offsets, node_z) if facing else None
    return StrandGeometry(
        cable,
        length,
        h_max,
        points,
        cells,
        cell_wire,
        wire_layer,
        offsets,
        pairs,
        phase,
        facing=facing_pairs,
    )
