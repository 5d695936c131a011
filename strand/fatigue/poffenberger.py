"""Where Poffenberger–Swart holds: its long-span assumption, checked on the tensioned beam.

Poffenberger–Swart (``strand.analytical.poffenberger_swart``) reads the clamp's curvature from
the displacement Y at x from the clamp as if the span were semi-infinite: w = (κ₀/p²)(e^{−px} −
1 + px), p = √(T/EI). In a clamped span 2a with a midspan load (docs/theory.md, the tensioned
beam; ``test_poffenberger_swart_is_the_clamped_tensioned_beam``) the displacement at x ≤ a is

    w(x) = P/(2T) [x − sinh(kx)/k + tanh(ka/2)(cosh(kx) − 1)/k],   w″(0) = P k tanh(ka/2)/(2T),

so P–S's curvature k² w(x)/(e^{−kx} − 1 + kx) misses the clamp's by terms in e^{−ka}. The span
is long enough where that error stays within a tolerance (10 %) for every bending stiffness the
strand can have, EI_min (all wires slipping) to EI_max (all sticking, the longest decay length
√(EI_max/T)): the error grows with EI, so EI_max decides. And the measuring point must lie
before the load, x < a. Units: m, N.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..analytical.stick_slip import StickSlipLaw
from ..cable.description import Cable

__all__ = ["SPAN_TOLERANCE", "SpanCheck", "span_error", "span_check"]

#: the largest relative error of P–S's clamp curvature from the finite span
SPAN_TOLERANCE = 0.1


@dataclass(frozen=True)
class SpanCheck:
    """Whether P–S holds on a span: its relative error with EI_max, the decay length
    √(EI_max/T) (m) and, where it does not hold, why (one line)."""

    holds: bool
    error: float
    decay_length: float
    reason: str = ""


def span_error(k: float, half_span: float, distance: float) -> float:
    """Relative error of P–S's clamp curvature, read at ``distance`` x from the clamp of a
    clamped span 2a = 2 ``half_span`` under tension, loaded at midspan, k = √(T/EI) (1/m)."""
    x, a = distance, half_span
    w = x - np.sinh(k * x) / k + np.tanh(k * a / 2) * (np.cosh(k * x) - 1) / k  # × P/(2T)
    curvature = k * np.tanh(k * a / 2)  # × P/(2T)
    return float(k**2 * w / (np.exp(-k * x) - 1 + k * x) / curvature - 1)


def span_check(
    cable: Cable, tension: float, span: float, distance: float, tolerance: float = SPAN_TOLERANCE
) -> SpanCheck:
    """P–S on a clamped ``span`` (m) under ``tension`` (N), read at ``distance`` (m)."""
    ei_max = StickSlipLaw(cable, tension).ei_max
    decay = float(np.sqrt(ei_max / tension))
    a = span / 2
    if distance >= a:
        return SpanCheck(
            False,
            np.nan,
            decay,
            f"its measuring point x = {1e3 * distance:.0f} mm "
            f"lies beyond the midspan load ({1e3 * a:.0f} mm from the clamp)",
        )
    error = span_error(1 / decay, a, distance)
    if abs(error) > tolerance:
        return SpanCheck(
            False,
            error,
            decay,
            (
                f"the span {span:.3g} m is too short for its long-span assumption: with EI_max the "
                f"clamp's curvature decays over √(EI_max/T) = {1e3 * decay:.0f} mm, and the finite "
                f"span changes the clamp curvature read at x = {1e3 * distance:.0f} mm by "
                f"{100 * error:+.0f} % (more than {100 * tolerance:.0f} %)"
            ),
        )
    return SpanCheck(True, error, decay)
