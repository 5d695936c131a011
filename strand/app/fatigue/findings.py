"""What a run's fatigue report found (``FatigueReport``): ``strand.app.fatigue.report``
computes it from the histories, ``strand.app.fatigue.text`` puts it into words. Both import it
from here, so neither imports the other back."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import numpy.typing as npt

from ...fatigue.cycles import Cycles

__all__ = ["FatigueReport"]

Array = npt.NDArray[np.float64]


@dataclass
class FatigueReport:
    """What the report found (arrays per pair, per element, per wire) and its summary text."""

    cycles: Cycles
    crossings: dict[str, Array]
    elements: dict[str, Array]
    wires: dict[str, Array]
    poffenberger_swart: dict | None  # None: no clamp; "holds" False: skipped, "reason" says why
    text: str
    end_zone: float = 0.0  # m, the clamp zone's length at each end
    length: float = 0.0  # m, the span
    tension_check: dict | None = None  # the strand-level T–N check (``tension_check``)
    curves: list = field(default_factory=list)  # per layer its S–N curve, None: not assessed
