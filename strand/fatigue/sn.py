"""S–N curves and Miner's rule (physics only, numpy).

An ``SNCurve`` gives the number of cycles to failure N of a stress amplitude σ_a (zero to peak),
σ_a = A N^b up to the knee N_k and A₂ N^b₂ beyond (the form of the CIGRE Safe Border Line). Miner's
rule sums the damage D = Σ nᵢ/N(σ_a,i) of counted cycles; D = 1 is failure.

Built-in curves (``SN_CURVES``), each for one wire material (``SNCurve.material``):

* aluminium: the CIGRE Safe Border Lines for the aluminium wires of conductors (CIGRE SC22 WG04,
  "Endurance capability of conductors", 1988; as quoted in the EPRI Transmission Line Reference
  Book: Wind-Induced Conductor Motion, 2nd ed., 2006, ch. 3): they bound from below the fatigue
  tests of conductors at suspension clamps, in the idealised outer-wire stress amplitude σ_a (MPa)
  of Poffenberger–Swart, and take no account of mean stress;
* steel: the characteristic S–N curves of prestressing steel (cold-drawn high-strength wire and
  strand, the wire of spiral strands) of EN 1992-1-1:2004, Table 6.4N, given as a stress range
  Δσ_Rsk at N* = 10⁶ cycles with slopes k₁ = 5 above and k₂ below: Δσ = Δσ_Rsk (N/N*)^(−1/k).
  ``en1992-prestressing-steel`` is the row of pre-tensioning and of single strands in plastic
  ducts (Δσ_Rsk = 185 MPa, k₂ = 9); ``en1992-steel-duct`` the row of curved tendons in steel
  ducts (120 MPa, k₂ = 7), whose lower curve comes from the wires fretting on the duct: the
  choice where a steel wire frets. Characteristic values (5 % fractile), without partial factor.

A user's own curve (``user_curve``) is given in the form of the offshore standards, N = a₁ Δσ^(−m₁)
(Δσ the stress range in MPa) up to the knee N_k, slope m₂ beyond it and continuous there; its
intercept as log₁₀ a₁ or as the range Δσ₀ at a cycle count N₀. A curve given as the mean of its
tests moves to the characteristic one, or back, by ``CHARACTERISTIC_SDS`` standard deviations of
log₁₀ N at every stress (DNV-OS-C201, Sec. 7 A104: S–N curves "based on a 97.6% probability of
survival, corresponding to the mean-minus-two-standard-deviation curves"), so the knee keeps its
stress and its cycle count moves with the curve.

Stresses here are in Pa.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

__all__ = [
    "SNCurve",
    "SN_CURVES",
    "CHARACTERISTIC_SDS",
    "miner_damage",
    "STEEL_MODULUS",
    "USER_SOURCE",
    "user_curve",
    "wire_material",
]

Array = npt.NDArray[np.float64]


@dataclass(frozen=True)
class SNCurve:
    """σ_a = A N^b (MPa) for N ≤ ``knee``, A₂ N^b₂ beyond (``A2`` 0: one slope throughout);
    ``material`` the wires it is for ("aluminium", "steel" or "" for a user's curve)."""

    name: str
    A: float
    b: float
    knee: float = math.inf
    A2: float = 0.0
    b2: float = 0.0
    source: str = ""
    material: str = ""

    @classmethod
    def from_range(
        cls,
        name: str,
        range_at_knee: float,
        knee: float,
        k1: float,
        k2: float,
        source: str = "",
        material: str = "",
    ) -> SNCurve:
        """The curve Δσ = Δσ* (N/N*)^(−1/k₁) for N ≤ N*, (N/N*)^(−1/k₂) beyond, of a stress
        range ``range_at_knee`` Δσ* (MPa) at ``knee`` N* cycles (Eurocode's form)."""
        amplitude = range_at_knee / 2
        return cls(
            name,
            amplitude * knee ** (1 / k1),
            -1 / k1,
            knee,
            amplitude * knee ** (1 / k2),
            -1 / k2,
            source,
            material,
        )

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


_CIGRE = "CIGRE SC22 WG04 (1988); EPRI Orange Book (2006), ch. 3"
_EN1992 = "EN 1992-1-1:2004, Table 6.4N"

SN_CURVES = {
    "cigre-sbl-multilayer": SNCurve(
        "CIGRE Safe Border Line, conductors of two or more aluminium layers",
        450.0,
        -0.2,
        2e7,
        263.0,
        -0.17,
        _CIGRE,
        "aluminium",
    ),
    "cigre-sbl-single-layer": SNCurve(
        "CIGRE Safe Border Line, conductors of one aluminium layer",
        730.0,
        -0.2,
        2e7,
        430.0,
        -0.17,
        _CIGRE,
        "aluminium",
    ),
    "en1992-prestressing-steel": SNCurve.from_range(
        "prestressing steel wire and strand (Δσ_Rsk = 185 MPa at 1e6, k1 = 5, k2 = 9)",
        185.0,
        1e6,
        5.0,
        9.0,
        f"{_EN1992}, pre-tensioning and single strands in plastic ducts",
        "steel",
    ),
    "en1992-steel-duct": SNCurve.from_range(
        "prestressing steel fretting on a steel duct (Δσ_Rsk = 120 MPa at 1e6, k1 = 5, k2 = 7)",
        120.0,
        1e6,
        5.0,
        7.0,
        f"{_EN1992}, curved tendons in steel ducts",
        "steel",
    ),
}


#: standard deviations of log₁₀ N between a mean S–N curve and its characteristic one
CHARACTERISTIC_SDS = 2.0
#: the ``source`` of a user's own curve
USER_SOURCE = "the case file ([fatigue] user_sn_*)"


def user_curve(
    m1: float,
    knee: float,
    *,
    log_a: float = 0.0,
    point: tuple[float, float] | None = None,
    m2: float = 0.0,
    shift: float = 0.0,
    name: str = "user curve",
    source: str = USER_SOURCE,
) -> SNCurve:
    """The curve N = a₁ Δσ^(−m₁) (Δσ in MPa) up to ``knee`` cycles, slope ``m2`` beyond (0: m₁
    throughout), continuous at the knee; the intercept ``log_a`` = log₁₀ a₁, or ``point`` = (Δσ₀
    in Pa, N₀): the range Δσ₀ at N₀ cycles, on whichever side of the knee N₀ lies. ``shift``
    moves every life by 10^shift (log₁₀ N + shift), the knee's cycles with it."""
    k2 = m2 or m1
    if point is not None:
        stress_range, cycles = point
        k = m1 if cycles <= knee else k2
        at_knee = stress_range / 1e6 * (cycles / knee) ** (1 / k)
    else:
        at_knee = (10.0**log_a / knee) ** (1 / m1)
    return SNCurve.from_range(name, at_knee, knee * 10.0**shift, m1, k2, source)


def miner_damage(ranges, counts, curve: SNCurve) -> float | Array:
    """Miner's damage Σ nᵢ/N(σ_a,i) of cycles of stress ``ranges`` (Pa, peak to peak; σ_a is half)
    counted ``counts`` times (1 full, ½ half cycles). The sum runs over the last axis: ranges
    (M, C) of M histories give their M damages (cycles of zero range add none)."""
    ranges, counts = np.atleast_1d(np.asarray(ranges, float)), np.asarray(counts, float)
    damage = np.sum(counts / curve.life(ranges / 2), axis=-1)
    return float(damage) if damage.ndim == 0 else damage


#: wires stiffer than this are steel, the others aluminium (steel 180–210 GPa, Al 55–70 GPa)
STEEL_MODULUS = 100e9


def wire_material(E: float) -> str:
    """A wire's material, "steel" or "aluminium", from its Young's modulus ``E`` (Pa)."""
    return "steel" if E >= STEEL_MODULUS else "aluminium"
