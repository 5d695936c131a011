"""Where the first helical layer's centre is, at each core node: the stencils of a core held on
its ring's axis (``strand.setups.centring``).

At a core node's z, every wire j of layer 1 passes between two of its nodes (a_j, b_j); its
centre there is (1 − t_j) x(a_j) + t_j x(b_j), t_j = (z − z_a)/(z_b − z_a). The layer's centre
is the mean over its n wires, on the strand's axis (the wires sit at 2π/n apart at any z). The
core's end nodes are left out: the set-ups hold the end sections. Units: m.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from .geometry import StrandGeometry

__all__ = ["RingCentres", "ring_centres"]


@dataclass(frozen=True)
class RingCentres:
    """Per interior core node p: ``stencils`` (P, 1 + 2n) input points (the core node, then
    each layer-1 wire's two nodes about its z), ``weights`` (P, 1 + 2n) such that
    Σ_k weights[p, k] x[stencils[p, k]] is the core node's offset from the layer's centre, and
    ``length`` (P,) the core length each node stands for (m)."""

    stencils: npt.NDArray[np.int64]
    weights: npt.NDArray[np.float64]
    length: npt.NDArray[np.float64]

    def __len__(self) -> int:
        return len(self.stencils)


def ring_centres(geometry: StrandGeometry) -> RingCentres:
    """The core's interior nodes and the first helical layer's centre at each (module
    docstring). A strand without a helical layer has none."""
    offsets, z = geometry.wire_offsets, geometry.points[:, 2]
    core = np.arange(offsets[0], offsets[1])
    wires = np.flatnonzero(geometry.wire_layer == 1)
    if not len(wires) or len(core) < 3:
        return RingCentres(np.zeros((0, 1), np.int64), np.zeros((0, 1)), np.zeros(0))
    zc = z[core]
    length = np.zeros(len(core))
    ds = np.diff(zc)
    length[:-1] += ds / 2
    length[1:] += ds / 2
    core, zc, length = core[1:-1], zc[1:-1], length[1:-1]
    n = len(wires)
    stencils = np.empty((len(core), 1 + 2 * n), dtype=np.int64)
    weights = np.empty((len(core), 1 + 2 * n))
    stencils[:, 0], weights[:, 0] = core, 1.0
    for j, w in enumerate(wires):
        zw = z[offsets[w] : offsets[w + 1]]
        a = np.clip(np.searchsorted(zw, zc, side="right") - 1, 0, len(zw) - 2)
        t = (zc - zw[a]) / (zw[a + 1] - zw[a])
        if np.any((t < -1e-9) | (t > 1 + 1e-9)):
            raise ValueError(f"wire {w} of layer 1 does not span the core's length")
        stencils[:, 1 + 2 * j] = offsets[w] + a
        stencils[:, 2 + 2 * j] = offsets[w] + a + 1
        weights[:, 1 + 2 * j] = -(1.0 - t) / n
        weights[:, 2 + 2 * j] = -t / n
    return RingCentres(stencils, weights, length)
