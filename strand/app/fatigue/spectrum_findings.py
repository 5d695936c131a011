"""What a spectrum's Miner sum found (``SpectrumReport``): per element (``SpectrumElements``),
per contact pair (``SpectrumCrossings``), per wire and zone (``SpectrumWires``) and on the strand's
tension (``SpectrumTension``). ``strand.app.fatigue.spectrum`` computes it from the sweep members'
fatigue reports, ``strand.app.fatigue.spectrum_text`` puts it into words. D is the damage in the
period the spectrum's counts are given for; A amplitudes. Units: SI (m, N).
"""

from __future__ import annotations

from dataclasses import dataclass

from .findings import Array, Flags, Ints, Names

__all__ = [
    "SpectrumReport",
    "SpectrumElements",
    "SpectrumCrossings",
    "SpectrumWires",
    "SpectrumTension",
]


@dataclass(frozen=True, kw_only=True)
class SpectrumElements:
    """Per element (E,): where it lies and its damage D over the spectrum's period.

    Attributes:
        wire, layer: the element's wire and layer (0: the core).
        z: initial height of its midpoint, m.
        clamp: in a clamp zone, not in the free span.
        damage: D = Σᵢ nᵢ dᵢ at its worst surface point (NaN: not assessed).
        shares: (A, E) each amplitude's share nᵢ dᵢ / D.
    """

    wire: Ints
    layer: Ints
    z: Array
    clamp: Flags
    damage: Array
    shares: Array


@dataclass(frozen=True, kw_only=True)
class SpectrumCrossings:
    """Per contact pair (P,): where it lies and its damage D over the spectrum's period.

    Attributes:
        interface: the inner layer i of its interface i|i+1.
        wire_a, wire_b: its wire on the inner and on the outer layer.
        z: initial height of the pair, m.
        clamp: in a clamp zone, not in the free span.
        line: a line pair rather than a crossing.
        damage: D = Σᵢ nᵢ dᵢ of its wires' facing surfaces (NaN: not assessed).
        shares: (A, P) each amplitude's share nᵢ dᵢ / D.
    """

    interface: Ints
    wire_a: Ints
    wire_b: Ints
    z: Array
    clamp: Flags
    line: Flags
    damage: Array
    shares: Array


@dataclass(frozen=True, kw_only=True)
class SpectrumWires:
    """A row (R,) per wire and zone where the zone has elements: the wire's element of largest
    D there.

    Attributes:
        wire, layer: the wire and its layer.
        zone: the zone's name (``strand.fatigue.zones.ZONES``).
        curve: the wire's S–N curve key (``findings.WireResults.curve``).
        element: the element of largest D (-1: not assessed).
        z: its initial height, m (NaN: not assessed).
        damage: its D (NaN: not assessed).
        shares: (R, A) each amplitude's share of it.
    """

    wire: Ints
    layer: Ints
    zone: Names
    curve: Names
    element: Ints
    z: Array
    damage: Array
    shares: Array


@dataclass(frozen=True, kw_only=True)
class SpectrumTension:
    """The strand-level T–N sums over the spectrum, and per member (A,) its tension.

    Attributes:
        dnv: DNV-OS-E301's D = Σᵢ nᵢ D_T,i.
        dnv_shares: (A,) each amplitude's share of it.
        api: API RP 2SK's D (None: a member has no breaking strength to check it with).
        range: (A,) each member's largest tension range, N.
        mean: (A,) each member's mean tension, N.
        cycle: (A,) whether each member's tension cycles.
    """

    dnv: float
    dnv_shares: Array
    api: float | None
    range: Array
    mean: Array
    cycle: Flags


@dataclass(frozen=True, kw_only=True)
class SpectrumReport:
    """Miner's sum of a spectrum over the cycle parameter's ``amplitudes`` (A,), in its
    ``unit``, with their ``counts`` (A,) in the spectrum's period and the sweep members'
    ``names``: per element, per pair, per wire and zone, and on the strand's tension; its
    text (``spectrum.txt``).

    Attributes:
        end_zone: the clamp zone's length at each end, m.
        length: the span, m.
        mean_stress, design_factor: the case's mean-stress correction and design fatigue
            factor, the members' (``findings.FatigueReport``), which every D includes.
    """

    parameter: str
    unit: str
    amplitudes: Array
    counts: Array
    names: list[str]
    elements: SpectrumElements
    crossings: SpectrumCrossings
    wires: SpectrumWires
    tension: SpectrumTension
    end_zone: float
    length: float = 0.0
    mean_stress: str = "none"
    design_factor: float = 1.0
    text: str = ""
