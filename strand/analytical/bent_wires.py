"""Wire stresses of a strand under tension bent to a uniform curvature, in full stick and in full
slip (docs/theory.md §5.7). Physics only (numpy).

A wire of layer i (lay angle α, helix radius r, diameter d, modulus E) sits at the angle φ from
the neutral axis of bending (φ = +90° the fibre stretched by a positive curvature κ):

* **tension** (fibre model, ends held against rotation, §5.1): σ_T = E cos²α ε, with
  ε = T / Σ n E A cos³α;
* **axial stress**, full stick (plane sections, §5.3): σ_N = σ_T + E cos²α κ r sin φ;
  full slip: σ_N = σ_T + (f/A) tri(φ), where friction lets a slipped wire's tension change by
  f per radian of φ from the neutral axis (§5.4; ``StickSlipLaw``'s f), tri(φ) = φ on
  abs(φ) ≤ π/2 and π − φ, −π − φ beyond (the quarter turns meet at the extreme fibres); without
  friction f = 0 and σ_N = σ_T;
* **the wire's own bending** (both states): its centre line follows the bent strand, and
  d²x/ds² gains the axis's curvature times (dz/ds)² = cos²α, so the wire bends by
  κ_w = κ cos²α (to O(sin²α, r κ)) and its surface stress is ± E κ_w d/2 about σ_N (the core:
  κ_w = κ).

The surface extremes of a wire's section are σ_N ± E κ_w d/2. Units: m, N, Pa, 1/m, rad.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from ..cable.description import Cable
from .stick_slip import StickSlipLaw

__all__ = ["BentWireStresses", "bent_wire_stresses", "triangle", "BENT_STATES"]

Array = npt.NDArray[np.float64]

#: the states the closed forms describe
BENT_STATES = ("stick", "slip")


def triangle(phi: npt.ArrayLike) -> Array:
    """tri(φ): φ on [−π/2, π/2], π − φ beyond +π/2 and −π − φ beyond −π/2 (φ in rad, taken
    modulo 2π): the slipped wire's tension change per unit f (rad)."""
    p = (np.asarray(phi, float) + np.pi) % (2 * np.pi) - np.pi
    return np.where(p > np.pi / 2, np.pi - p, np.where(p < -np.pi / 2, -np.pi - p, p))


@dataclass(frozen=True, kw_only=True)
class BentWireStresses:
    """The closed-form wire stresses of a bent strand, per layer (0 = core).

    Attributes:
        state: "stick" or "slip".
        tension: the strand's tension T, N.
        curvature: the strand's curvature κ, 1/m.
        tension_stress: σ_T per layer, Pa.
        plane_section: E cos²α κ r per layer, Pa: the sin φ amplitude of the axial stress in
            stick (0 for the core; used in stick only).
        friction_slope: f/A per layer, Pa per rad of φ: the slipped wire's axial stress change
            per radian from the neutral axis, in magnitude (its sign is κ's; 0 for the core, or
            without friction; slip only).
        bending: E κ cos²α d/2 per layer, Pa: the wire's own bending stress at its surface.
    """

    state: str
    tension: float
    curvature: float
    tension_stress: Array
    plane_section: Array
    friction_slope: Array
    bending: Array

    def axial(self, layer: npt.ArrayLike, phi: npt.ArrayLike) -> Array:
        """σ_N (Pa) of wires of ``layer`` at the angles ``phi`` (rad) from the neutral axis."""
        layer = np.asarray(layer, dtype=int)
        phi = np.asarray(phi, float)
        if self.state == "stick":
            change = self.plane_section[layer] * np.sin(phi)
        else:
            change = np.sign(self.curvature) * self.friction_slope[layer] * triangle(phi)
        return self.tension_stress[layer] + change

    @property
    def sine_amplitude(self) -> Array:
        """Per layer, the sin φ Fourier coefficient of σ_N − σ_T (Pa): the plane-section
        amplitude in stick; in slip, 4 f/(π A) × sign κ, the triangle's (of peak (f/A) π/2)."""
        if self.state == "stick":
            return self.plane_section
        return np.sign(self.curvature) * 4 / np.pi * self.friction_slope

    @property
    def largest(self) -> Array:
        """Per layer, the largest surface stress over φ (Pa): σ_T + abs(axial change at
        φ = ±90°) + E κ_w d/2."""
        if self.state == "stick":
            change = np.abs(self.plane_section)
        else:
            change = self.friction_slope * np.pi / 2
        return self.tension_stress + change + self.bending

    def peak(self, layer: npt.ArrayLike, phi: npt.ArrayLike) -> Array:
        """The largest surface stress of the wires' sections, σ_N + E κ_w d/2 (Pa)."""
        return self.axial(layer, phi) + self.bending[np.asarray(layer, dtype=int)]

    def trough(self, layer: npt.ArrayLike, phi: npt.ArrayLike) -> Array:
        """The smallest surface stress of the wires' sections, σ_N − E κ_w d/2 (Pa)."""
        return self.axial(layer, phi) - self.bending[np.asarray(layer, dtype=int)]


def bent_wire_stresses(
    cable: Cable,
    tension: float,
    curvature: float,
    state: str,
    *,
    friction: bool = True,
    rule: str = "cumulative",
) -> BentWireStresses:
    """The closed-form wire stresses of ``cable`` under ``tension`` (N) bent to ``curvature``
    (1/m) in full ``state`` ("stick" or "slip"); ``friction``: the cable's coefficients cap
    the slipped wires' tension change (False: frictionless, no change), with the friction
    ``rule`` of ``StickSlipLaw`` ("cumulative" or "own_tension")."""
    if state not in BENT_STATES:
        raise ValueError(f"state {state!r}: choose {' or '.join(BENT_STATES)}")
    layers = cable.layers
    cos = np.array([np.cos(lay.alpha) for lay in layers])
    E = np.array([lay.wire.E for lay in layers])
    area = np.array([lay.wire.area for lay in layers])
    count = np.array([max(lay.wires, 1) for lay in layers])
    strain = tension / float(np.sum(count * E * area * cos**3))
    slope = np.zeros(len(layers))
    if friction and len(layers) > 1:
        law = StickSlipLaw(cable, tension, rule)
        slope[1:] = [layer.f for layer in law.layers] / area[1:]
    return BentWireStresses(
        state=state,
        tension=float(tension),
        curvature=float(curvature),
        tension_stress=E * cos**2 * strain,
        plane_section=E * cos**2 * curvature * np.array([lay.radius for lay in layers]),
        friction_slope=slope,
        bending=E * cos**2 * abs(curvature) * np.array([lay.wire.diameter / 2 for lay in layers]),
    )
