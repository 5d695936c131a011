"""Mean-stress corrections of stress cycles (physics only, numpy).

A cycle of amplitude σ_a (half its range) about a mean σ_m is replaced by the amplitude σ_ar of a
fully reversed cycle (zero mean) of the same life, read on an S–N curve measured at zero mean:

* Goodman: σ_a/σ_ar + σ_m/σ_u = 1, so σ_ar = σ_a / (1 − σ_m/σ_u);
* Gerber: σ_a/σ_ar + (σ_m/σ_u)² = 1, so σ_ar = σ_a / (1 − (σ_m/σ_u)²);
* Smith–Watson–Topper (SWT): σ_ar = √(σ_max σ_a), σ_max = σ_m + σ_a; no damage where σ_max ≤ 0
  (Walker's σ_ar = σ_max^(1−γ) σ_a^γ with γ = ½);

σ_u the ultimate tensile strength. A compressive mean (σ_m < 0) is given no credit by Goodman and
Gerber (σ_m taken as 0: Gerber's square would count it as harmful, Goodman's line as beneficial);
a mean at or above σ_u breaks the wire in one cycle (σ_ar = inf). These are the textbook forms,
read here in secondary sources, not in a textbook (docs/fatigue.md names them); Dowling, Calhoun &
Arcari (*Fatigue Fract. Eng. Mater. Struct.* 32, 2009, 163–179; its abstract read) find SWT
reasonable and Goodman highly inaccurate on steels and aluminium alloys.

A curve measured at a mean σ_m0 ≠ 0 takes the amplitude at σ_m0 of the same σ_ar
(``reference_mean``): Goodman σ_ar (1 − σ_m0/σ_u), Gerber σ_ar (1 − (σ_m0/σ_u)²), SWT the root of
(σ_m0 + σ_a0) σ_a0 = σ_ar². A cycle at the curve's own mean is then left as it is. Units: Pa.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

__all__ = ["MEAN_STRESS_LAWS", "MeanStress", "equivalent_amplitude", "fully_reversed_amplitude"]

Array = npt.NDArray[np.float64]

#: ``[fatigue] mean_stress``: no correction, or one of the three laws
MEAN_STRESS_LAWS = ("none", "goodman", "gerber", "swt")
#: the laws' names as the reports print them
LAW_NAMES = {"goodman": "Goodman", "gerber": "Gerber", "swt": "Smith–Watson–Topper"}


def fully_reversed_amplitude(amplitude, mean, tensile_strength: float, law: str) -> Array:
    """σ_ar (Pa) of cycles of ``amplitude`` σ_a ≥ 0 about ``mean`` σ_m (Pa, arrays broadcast)
    by ``law`` (``MEAN_STRESS_LAWS``), σ_u = ``tensile_strength`` (Pa)."""
    s_a, s_m = np.asarray(amplitude, float), np.asarray(mean, float)
    if law == "none":
        return np.broadcast_to(s_a, np.broadcast_shapes(s_a.shape, s_m.shape)).copy()
    if law == "swt":
        return np.sqrt(np.maximum(s_m + s_a, 0.0) * s_a)
    ratio = np.maximum(s_m, 0.0) / tensile_strength
    if law == "goodman":
        left = 1 - ratio
    elif law == "gerber":
        left = 1 - ratio**2
    else:
        raise ValueError(f"mean-stress law {law!r}: expected one of {list(MEAN_STRESS_LAWS)}")
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(s_a == 0, 0.0, np.where(left > 0, s_a / left, np.inf))


def _at_reference(reversed_: Array, reference_mean: float, tensile_strength: float, law: str):
    """The amplitude at the mean ``reference_mean`` (Pa) whose fully reversed one is
    ``reversed_`` (the inverse of ``fully_reversed_amplitude`` at that mean)."""
    if reference_mean == 0 or law == "none":
        return reversed_
    ratio = max(reference_mean, 0.0) / tensile_strength
    if law == "goodman":
        return reversed_ * (1 - ratio)
    if law == "gerber":
        return reversed_ * (1 - ratio**2)
    # SWT: (σ_m0 + σ_a0) σ_a0 = σ_ar², the positive root written without cancellation
    m0 = reference_mean
    with np.errstate(invalid="ignore"):
        return np.where(
            np.isinf(reversed_),
            np.inf,
            2 * reversed_**2 / (m0 + np.sqrt(m0**2 + 4 * reversed_**2)),
        )


def equivalent_amplitude(
    amplitude, mean, tensile_strength: float, law: str, reference_mean: float = 0.0
) -> Array:
    """The amplitude (Pa) at the S–N curve's own mean ``reference_mean`` (Pa; 0: a fully
    reversed curve) with the life of cycles of ``amplitude`` σ_a (Pa) about ``mean`` σ_m (Pa)
    by ``law``; ``law`` "none" returns σ_a unchanged."""
    reversed_ = fully_reversed_amplitude(amplitude, mean, tensile_strength, law)
    return _at_reference(reversed_, reference_mean, tensile_strength, law)


@dataclass(frozen=True)
class MeanStress:
    """The mean-stress correction of one layer's wires: its ``law`` (not "none"), their
    ``tensile_strength`` σ_u (Pa) and the mean of the S–N curve's tests ``reference_mean``
    (Pa; 0: fully reversed)."""

    law: str
    tensile_strength: float
    reference_mean: float = 0.0

    def __post_init__(self):
        if self.law not in MEAN_STRESS_LAWS[1:]:
            raise ValueError(
                f"mean-stress law {self.law!r}: expected one of {MEAN_STRESS_LAWS[1:]}"
            )
        if not self.tensile_strength > 0:
            raise ValueError(f"tensile strength {self.tensile_strength!r} Pa: expected > 0")
        if not self.reference_mean < self.tensile_strength:
            raise ValueError(
                f"the S–N curve's mean stress {self.reference_mean:g} Pa is not below the "
                f"tensile strength {self.tensile_strength:g} Pa"
            )

    def ranges(self, ranges, means) -> Array:
        """The equivalent ranges (Pa) of cycles of ``ranges`` (peak to peak) about ``means``
        (Pa, arrays of one shape): twice ``equivalent_amplitude``."""
        half = 0.5 * np.asarray(ranges, float)
        return 2 * equivalent_amplitude(
            half, means, self.tensile_strength, self.law, self.reference_mean
        )
