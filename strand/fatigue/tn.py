"""Strand-level T–N curves of spiral strand from offshore mooring standards (physics only, numpy).

The mooring industry checks a spiral strand's fatigue from its tension alone: cycles of tension
range ΔT (counted by rainflow on the tension history) against a design curve, Miner's rule on top.

* DNV-OS-E301 *Position mooring* (Oct. 2010, Ch. 2 Sec. 2, fatigue limit state; the same
  constants in DNVGL-OS-E301, 2018): n_c(s) = a_D s^(−m), s the nominal stress range (MPa) of
  the tension range over the strand's nominal metallic area; spiral rope a_D = 1.7·10¹⁷,
  m = 4.8 (six-strand rope 3.4·10¹⁴, 4.0).
* API RP 2SK *Design and Analysis of Stationkeeping Systems for Floating Structures* (3rd ed.,
  2005, fatigue T–N curves): N R^M = K, R = ΔT/MBS the tension range over the reference
  (minimum) breaking strength, spiral strand M = 5.05, log₁₀ K = 3.25 − 3.43 L_m with L_m the
  mean tension over MBS (six-strand rope 4.09, 3.20 − 2.79 L_m).

The constants were read from a public implementation that cites these editions (not from the
standards' text); check them against the edition a design basis names. Units: N, m², Pa.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

__all__ = [
    "DNV_SPIRAL_ROPE",
    "API_SPIRAL_STRAND",
    "TENSION_CYCLE_SHARE",
    "dnv_spiral_rope_life",
    "api_spiral_strand_life",
    "tension_damage",
]

Array = npt.NDArray[np.float64]

#: DNV-OS-E301 spiral rope: (a_D, m) of n_c(s) = a_D s^-m, s in MPa
DNV_SPIRAL_ROPE = (1.7e17, 4.8)
#: API RP 2SK spiral strand: (M, log10 K at L_m = 0, d log10 K / d L_m) of N R^M = K
API_SPIRAL_STRAND = (5.05, 3.25, -3.43)
#: a tension history whose largest range is below this share of its mean has no tension cycle
TENSION_CYCLE_SHARE = 0.01


def dnv_spiral_rope_life(tension_range, area: float) -> Array:
    """Cycles to failure of tension ranges ΔT (N) of a spiral rope of nominal metallic ``area``
    (m²), DNV-OS-E301; inf where ΔT = 0."""
    a_d, m = DNV_SPIRAL_ROPE
    s = np.abs(np.asarray(tension_range, float)) / area / 1e6  # MPa
    with np.errstate(divide="ignore"):
        return a_d * s ** (-m)


def api_spiral_strand_life(tension_range, breaking_strength: float, mean_tension) -> Array:
    """Cycles to failure of tension ranges ΔT (N) at mean tensions (N) of a spiral strand of
    minimum breaking strength ``breaking_strength`` (N), API RP 2SK; inf where ΔT = 0."""
    M, log_k0, slope = API_SPIRAL_STRAND
    R = np.abs(np.asarray(tension_range, float)) / breaking_strength
    K = 10.0 ** (log_k0 + slope * np.asarray(mean_tension, float) / breaking_strength)
    with np.errstate(divide="ignore"):
        return K * R ** (-M)


def tension_damage(ranges, counts, means, area: float, breaking_strength: float = 0.0):
    """Miner's damage of tension cycles (``ranges``, ``means`` in N, ``counts`` 1 or ½):
    (DNV-OS-E301's, API RP 2SK's or None without a breaking strength)."""
    ranges, counts = np.asarray(ranges, float), np.asarray(counts, float)
    if ranges.size == 0:
        return 0.0, (0.0 if breaking_strength > 0 else None)
    dnv = float(np.sum(counts / dnv_spiral_rope_life(ranges, area)))
    if breaking_strength <= 0:
        return dnv, None
    api = api_spiral_strand_life(ranges, breaking_strength, means)
    return dnv, float(np.sum(counts / api))
