"""The fibre model of a strand (wires that stretch with it, ends held against rotation) and the
bounds of its bending stiffness, from its cable alone. Units: N, N m².
"""

from __future__ import annotations

import numpy as np

from ..cable.description import Cable

__all__ = ["fibre_model", "bending_stiffness_bounds"]


def fibre_model(cable: Cable, tension: float) -> dict:
    """Axial stiffness (N), strain and wire forces (N) per layer for ends held against rotation
    (docs/theory.md §5.1: ε_w = ε cos²α, F = Σ n E A cos³α ε)."""
    k = 0.0
    per_layer = []
    for lay in cable.layers:
        c = np.cos(lay.alpha)
        n = max(lay.wires, 1)
        k += n * lay.wire.E * lay.wire.area * c**3
        per_layer.append(lay.wire.E * lay.wire.area * c**2)
    eps = tension / k
    return {"EA": k, "strain": eps, "wire_force": [f * eps for f in per_layer]}


def bending_stiffness_bounds(cable: Cable) -> tuple[float, float]:
    """(EI_min, EI_max) in N m²: Σ n EI of free-slipping wires, plus Σ (n/2) E A r² cos³α when
    every layer sticks (docs/theory.md §5.3)."""
    ei_min = sum(
        max(lay.wires, 1) * lay.wire.E * np.pi * lay.wire.diameter**4 / 64 for lay in cable.layers
    )
    stick = sum(
        lay.wires / 2 * lay.wire.E * lay.wire.area * lay.radius**2 * np.cos(lay.alpha) ** 3
        for lay in cable.layers[1:]
    )
    return ei_min, ei_min + stick
