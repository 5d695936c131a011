"""The states a layer's geometry allows: how close its neighbouring wires' helices come, and how
stranding spreads the layer's spare circumference over its gaps.

The wires of a helical layer are identical helices turned by 2π/n. Their centre lines come closest
at a distance D found exactly (``helix_clearance``): D² = min_s 2r²(1 − cos(s + 2π/n)) + (s/ω)²,
ω = tan α / r the helix's angular rate. D − d is the layer's nominal gap. Cardinal's (from its
helices): layer 1 −14.1 µm (its six equal steel wires would overlap: they touch one another),
layers 2–4 +62.0, +78.2, +65.6 µm (``tests/test_same_layer.py`` asserts them).

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

The pairs that carry these gaps between neighbouring wires: ``same_layer``.

Units: m.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import numpy.typing as npt

from ..cable.description import Cable, CableError, Layer

__all__ = [
    "FIRST_LAYER",
    "SAME_LAYER",
    "SAME_LAYER_STENCILS",
    "helix_clearance",
    "ring_lift",
    "spread_gaps",
    "first_layer_lift",
]

Array = npt.NDArray[np.float64]

#: choices of ``[contact] same_layer``: off, or how a layer's spare circumference is spread
SAME_LAYER = ("off", "nominal", "packed", "random")
#: choices of ``[contact] first_layer``: the first helical layer on the core, or vaulted over it
FIRST_LAYER = ("on_core", "ring")
#: choices of ``[contact] same_layer_stencil``: node to segment [a, b₀, b₁], node a to the
#: neighbour's nearest node c [c, a], or station a to the node c that faces it exactly [c, a]
#: (small sliding, on a geometry with facing stations)
SAME_LAYER_STENCILS = ("segment", "node", "facing")


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
