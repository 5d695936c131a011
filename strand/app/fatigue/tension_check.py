"""The mooring standards' strand-level check on a run's histories: the strand's tension at
midspan per step, and DNV-OS-E301's and API RP 2SK's T–N damage of its cycles beside the
wire-level model's largest (``strand.fatigue.tn`` holds the curves). Units: N, m."""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from ...cable.description import Cable
from ...fatigue.cycles import repeating_cycles
from ...fatigue.tn import TENSION_CYCLE_SHARE, tension_damage
from ..history import History
from .findings import TensionCheck, WireResults

__all__ = ["strand_tension", "midspan_axial_sum", "tension_check"]

Array = npt.NDArray[np.float64]


def strand_tension(sections: History, cable: Cable | None = None) -> Array:
    """The strand's tension (N) per step at midspan: the z component of the force resultant of
    the cross-section z = L/2, Σ n over the wires it cuts (their axial and shear forces,
    ``midspan_force``). Where the lateral loads have no axial component, equilibrium of the
    half strand makes it the end force, up to the axial forces that same-layer contact pairs
    carry across the section where their nodes lie on both sides of it (docs/fatigue.md).
    Histories written before ``midspan_force`` was recorded: ``midspan_axial_sum`` (``cable``
    needed)."""
    if "midspan_force" not in sections.arrays:
        return midspan_axial_sum(sections, cable)
    return sections["midspan_force"][:, 2]


def midspan_axial_sum(sections: History, cable: Cable) -> Array:
    """Σ N cos α (N) per step over every wire's element nearest midspan, α its layer's lay
    angle: the tension without the wires' shear forces (~3e-5 low on a 1+6)."""
    st = sections.static
    middle = 0.5 * (st["z"].min() + st["z"].max())
    cells = [
        np.flatnonzero(st["wire"] == w)[np.argmin(np.abs(st["z"][st["wire"] == w] - middle))]
        for w in np.unique(st["wire"])
    ]
    cos = np.cos([lay.alpha for lay in cable.layers])
    return sections["axial"][:, cells] @ cos[st["layer"][cells]]


def tension_check(
    sections: History,
    cable: Cable,
    breaking_strength: float,
    wires: WireResults,
    factor: float = 1.0,
) -> TensionCheck:
    """The mooring standards' strand-level check on the strand's tension history, repeating:
    DNV-OS-E301's and (with a breaking strength, N) API RP 2SK's damage per cycle, times
    ``factor`` (the design fatigue factor, as the wire-level damage), beside the wire-level
    model's largest; ``cycle`` False where the tension stays within
    ``TENSION_CYCLE_SHARE`` of its mean. ``mean`` and ``range`` (N) are the largest cycle's:
    (max + min)/2 and max − min of the history. A mean over the recorded steps would weigh
    each leg by how finely the run stepped it."""
    tension = strand_tension(sections, cable)
    cycles = repeating_cycles(tension)
    area = sum(lay.wires * lay.wire.area for lay in cable.layers)
    dnv, api = tension_damage(cycles.range, cycles.count, cycles.mean, area, breaking_strength)
    largest = float(cycles.range.max()) if len(cycles) else 0.0
    mean = 0.5 * float(tension.max() + tension.min())
    damage = wires.whole.damage
    worst = _worst(damage)
    free = _worst(wires.free_span.damage)
    clamp = wires.clamp_zone.damage
    return TensionCheck(
        mean=mean,
        range=largest,
        area=area,
        cycle=largest >= TENSION_CYCLE_SHARE * abs(mean),
        dnv=factor * dnv,
        api=None if api is None else factor * api,
        wire=worst,
        wire_damage=float(damage[worst]) if worst is not None else np.nan,
        wire_in_clamp=worst is not None and bool(clamp[worst] >= damage[worst]),
        free_wire=free,
        free_damage=float(wires.free_span.damage[free]) if free is not None else np.nan,
    )


def _worst(damage: np.ndarray) -> int | None:
    """The wire of largest damage (None: none assessed)."""
    return None if np.all(np.isnan(damage)) else int(np.nanargmax(damage))
