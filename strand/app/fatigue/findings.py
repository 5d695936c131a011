"""What a run's fatigue report found (``FatigueReport``): per contact pair (``CrossingResults``),
per element (``ElementResults``), per wire over the whole wire and per zone (``WireResults``, each
zone a ``WireZone``), the strand-level T–N check (``TensionCheck``) and Poffenberger–Swart at the
clamp (``PoffenbergerSwartCheck``).

``strand.app.fatigue.report`` computes it from the histories, ``strand.app.fatigue.text`` puts it
into words; both import it from here, so neither imports the other back. Damages are Miner's per
steady repetition of the run's cycle. Units: SI (m, N, Pa, J), angles in degrees.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from ...fatigue.cycles import Cycles
from ...fatigue.sn import SNCurve

__all__ = [
    "FatigueReport",
    "CrossingResults",
    "ElementResults",
    "WireZone",
    "WireResults",
    "TensionCheck",
    "PoffenbergerSwartCheck",
]

Array = npt.NDArray[np.float64]
Ints = npt.NDArray[np.int64]
Flags = npt.NDArray[np.bool_]
Names = npt.NDArray[np.character]  # strings (np.str_)


@dataclass(frozen=True, kw_only=True)
class CrossingResults:
    """Per contact pair (P,): where it lies, and its worst counted cycle (largest Ruiz F₂, or
    largest slip amplitude where no cycle has an F₂ > 0).

    Attributes:
        interface: the inner layer i of the pair's interface i|i+1.
        wire_a, wire_b: its wire on the inner and on the outer layer.
        z: initial height of the pair (the midpoint of its two nodes), m.
        angle: its angle φ about the strand's axis at t = 0, from the x axis, deg.
        line: a line pair (wires along each other) rather than a crossing.
        clamp: in a clamp zone (``strand.fatigue.zones``), not in the free span.
        stuck: its Coulomb slide stayed below ``[fatigue] stuck_slip`` throughout.
        slip_amplitude: amplitude of the slip, m.
        displacement_amplitude: amplitude of the relative displacement, m.
        friction_amplitude: amplitude of the friction force, N.
        peak_force, mean_force: peak and mean normal force over the cycle, N.
        semi_axis_a, semi_axis_b: Hertz contact semi-axes, m (a line pair: the half-width
            across the line and half the tributary length along it).
        peak_pressure: Hertz peak pressure p₀, Pa.
        surface_stress: the two wires' largest surface stress over the cycle, Pa.
        ruiz_f1: Ruiz's F₁ = τδ, J/m².
        ruiz_f2: Ruiz's F₂ = σ_T τδ, Pa J/m².
        energy: friction energy dissipated per repetition (all its counted cycles), J.
        damage: Miner damage of the two wires' facing surfaces, the larger (NaN: neither wire's
            layer has an S–N curve).
        assessed: whose curve gives it: "both", "inner", "outer" or "not assessed".
    """

    interface: Ints
    wire_a: Ints
    wire_b: Ints
    z: Array
    angle: Array
    line: Flags
    clamp: Flags
    stuck: Flags
    slip_amplitude: Array
    displacement_amplitude: Array
    friction_amplitude: Array
    peak_force: Array
    mean_force: Array
    semi_axis_a: Array
    semi_axis_b: Array
    peak_pressure: Array
    surface_stress: Array
    ruiz_f1: Array
    ruiz_f2: Array
    energy: Array
    damage: Array
    assessed: Names


@dataclass(frozen=True, kw_only=True)
class ElementResults:
    """Per element (E,): where it lies, and the surface point of largest stress range over the
    history.

    Attributes:
        wire, layer: the element's wire and layer (0: the core).
        z: initial height of its midpoint, m.
        clamp: in a clamp zone, not in the free span.
        angle: that point's angle ψ from the strand's outward radius, deg.
        range, mean, peak: its surface stress range, mean and largest value, Pa.
        shear_range: range of the torsional shear stress, Pa.
        damage: Miner damage at the element's worst surface point (NaN: its layer has no S–N
            curve).
    """

    wire: Ints
    layer: Ints
    z: Array
    clamp: Flags
    angle: Array
    range: Array
    mean: Array
    peak: Array
    shear_range: Array
    damage: Array


@dataclass(frozen=True, kw_only=True)
class WireZone:
    """Per wire (W,), over the part of it in one zone (or all of it): its element of largest
    stress range, and its largest damage (NaN: not assessed, or no element there).

    Attributes:
        range: the largest surface stress range, Pa.
        z: initial height of that element, m.
        angle: the angle ψ of its worst surface point, deg.
        damage: the largest Miner damage of its elements.
        repetitions: repetitions of the cycle to failure, 1/damage (inf where the damage is 0).
    """

    range: Array
    z: Array
    angle: Array
    damage: Array
    repetitions: Array


@dataclass(frozen=True, kw_only=True)
class WireResults:
    """Per wire (W,): its layer and S–N curve, over the whole wire and per zone.

    Attributes:
        layer: the wire's layer (0: the core).
        curve: its layer's S–N curve, a key of ``strand.fatigue.sn.SN_CURVES``, "custom" or
            "not assessed".
        whole, free_span, clamp_zone: the whole wire, its part in the free span and in the
            clamp zones.
    """

    layer: Ints
    curve: Names
    whole: WireZone
    free_span: WireZone
    clamp_zone: WireZone

    def zone(self, clamp: bool) -> WireZone:
        """The clamp zone's results (``clamp``) or the free span's."""
        return self.clamp_zone if clamp else self.free_span


@dataclass(frozen=True, kw_only=True)
class TensionCheck:
    """The mooring standards' strand-level T–N check on the strand's tension at midspan, beside
    the wire-level model's largest damage on the same history.

    Attributes:
        mean: the largest cycle's mean tension, (max + min)/2 of the history, N.
        range: the largest cycle's tension range, N.
        area: the strand's metallic area, m².
        cycle: the tension cycles (a range of at least ``TENSION_CYCLE_SHARE`` of the mean).
        dnv: DNV-OS-E301's damage of the tension cycles.
        api: API RP 2SK's damage (None: no breaking strength given).
        wire: the wire of largest wire-level damage (None: no wire assessed).
        wire_damage: its damage (NaN: none assessed).
        wire_in_clamp: whether that damage lies in a clamp zone.
        free_wire: the wire of largest damage in the free span (None: no free span, or no
            wire assessed there).
        free_damage: its damage there (NaN: none).
    """

    mean: float
    range: float
    area: float
    cycle: bool
    dnv: float
    api: float | None
    wire: int | None
    wire_damage: float
    wire_in_clamp: bool = False
    free_wire: int | None = None
    free_damage: float = float("nan")


@dataclass(frozen=True, kw_only=True)
class PoffenbergerSwartCheck:
    """Poffenberger–Swart's outer-wire stress amplitude at the clamp against the model's, where
    its long-span assumption holds (``holds``; else the ``reason``, and NaN for the rest).

    Attributes:
        holds: the span is long enough for it (``strand.fatigue.poffenberger.span_check``).
        reason: why it does not hold ("" where it does).
        distance: the measuring point's distance from the clamp, m.
        span: the span, m.
        K: Poffenberger–Swart's factor, Pa/m.
        y_b: Y_b, the peak-to-peak displacement of the strand axis at ``distance``, m.
        sigma_a: its amplitude K Y_b, Pa.
        model: half the model's largest outer-wire stress range at the clamp mouth, Pa.
        ratio: ``model`` / ``sigma_a``.
        span_error: the relative error of its clamp curvature from the finite span.
    """

    holds: bool
    reason: str = ""
    distance: float
    span: float
    K: float = np.nan
    y_b: float = np.nan
    sigma_a: float = np.nan
    model: float = np.nan
    ratio: float = np.nan
    span_error: float = np.nan


@dataclass(frozen=True, kw_only=True)
class FatigueReport:
    """What the report found and its summary text (``fatigue.txt``).

    Attributes:
        cycles: the load cycles counted on one steady repetition of the run's cycle.
        crossings, elements, wires: the results per contact pair, element and wire.
        tension_check: the strand-level T–N check.
        poffenberger_swart: Poffenberger–Swart at the clamp (None: the set-up has no clamp).
        curves: per layer its S–N curve (None: not assessed).
        end_zone: the clamp zone's length at each end, m.
        length: the span, m.
        mean_stress: the wire-level mean-stress correction, a law of
            ``strand.fatigue.meanstress.MEAN_STRESS_LAWS`` ("none": the ranges as they are).
        design_factor: the design fatigue factor every damage (wire-level and T–N) includes.
        text: the summary, ``fatigue.txt``.
    """

    cycles: Cycles
    crossings: CrossingResults
    elements: ElementResults
    wires: WireResults
    tension_check: TensionCheck
    poffenberger_swart: PoffenbergerSwartCheck | None
    curves: list[SNCurve | None]
    end_zone: float
    length: float
    mean_stress: str = "none"
    design_factor: float = 1.0
    text: str = ""
