"""S–N curves and Miner's rule (physics only, numpy).

An ``SNCurve`` gives the number of cycles to failure N of a stress amplitude σ_a (zero to peak),
σ_a = A N^b up to the knee N_k and A₂ N^b₂ beyond (the form of the CIGRE Safe Border Line). Miner's
rule sums the damage D = Σ nᵢ/N(σ_a,i) of counted cycles; D = 1 is failure.

The built-in curves are the CIGRE Safe Border Lines for the aluminium wires of conductors
(CIGRE SC22 WG04, "Endurance capability of conductors", 1988; as quoted in the EPRI
Transmission Line Reference Book: Wind-Induced Conductor Motion, 2nd ed., 2006, ch. 3): they bound
from below the fatigue tests of conductors at suspension clamps, in the idealised outer-wire stress
amplitude σ_a (MPa) of Poffenberger–Swart, and take no account of mean stress. Stresses here are
in Pa.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

__all__ = ["SNCurve", "SN_CURVES", "miner_damage"]

Array = npt.NDArray[np.float64]


@dataclass(frozen=True)
class SNCurve:
    """σ_a = A N^b (MPa) for N ≤ ``knee``, A₂ N^b₂ beyond (``A2`` 0: one slope throughout)."""

    name: str
    A: float
    b: float
    knee: float = math.inf
    A2: float = 0.0
    b2: float = 0.0
    source: str = ""

    def __post_init__(self):
        if not (self.A > 0 and self.b < 0 and self.knee > 0):
            raise ValueError(f"S–N curve {self.name!r}: needs A > 0, b < 0 and a positive knee")
        if self.A2 and not (self.A2 > 0 and self.b2 < 0):
            raise ValueError(f"S–N curve {self.name!r}: needs A2 > 0 and b2 < 0 beyond the knee")

    def life(self, amplitude) -> Array:
        """Cycles to failure N of stress amplitudes σ_a (Pa); inf where σ_a = 0."""
        s = np.abs(np.asarray(amplitude, float)) / 1e6  # MPa
        with np.errstate(divide="ignore"):
            n1 = (s / self.A) ** (1 / self.b)
            if not self.A2:
                return n1
            n2 = np.maximum((s / self.A2) ** (1 / self.b2), self.knee)
        return np.where(n1 <= self.knee, n1, n2)


SN_CURVES = {
    "cigre-sbl-multilayer": SNCurve(
        "CIGRE Safe Border Line, conductors of two or more aluminium layers", 450.0, -0.2, 2e7,
        263.0, -0.17, "CIGRE SC22 WG04 (1988); EPRI Orange Book (2006), ch. 3",
    ),
    "cigre-sbl-single-layer": SNCurve(
        "CIGRE Safe Border Line, conductors of one aluminium layer", 730.0, -0.2, 2e7, 430.0,
        -0.17, "CIGRE SC22 WG04 (1988); EPRI Orange Book (2006), ch. 3",
    ),
}  # fmt: skip


def miner_damage(ranges, counts, curve: SNCurve) -> float:
    """Miner's damage Σ nᵢ/N(σ_a,i) of cycles of stress ``ranges`` (Pa, peak to peak; σ_a is half)
    counted ``counts`` times (1 full, ½ half cycles)."""
    ranges, counts = np.asarray(ranges, float), np.asarray(counts, float)
    if ranges.size == 0:
        return 0.0
    return float(np.sum(counts / curve.life(ranges / 2)))
