"""The tensioned beam and Poffenberger–Swart: the strand as one beam under tension.

**Tensioned beam** (``TensionedBeam``): clamped–clamped span L, tension T held, midspan load P;
on the half span w″ = κ(M), M(x) = T w − (P/2) x + M₀, w(0) = w′(0) = w′(L/2) = 0, shooting on M₀.
For a linear law δ = P/(2T)·[a − (2/k) tanh(ka/2)], a = L/2, k = √(T/EI).

**Poffenberger–Swart** (``poffenberger_swart``; Poffenberger & Swart, *Differential displacement
and dynamic conductor strain*, IEEE Trans. PAS 84, 1965; IEEE Std 1966): the strand as a beam of
stiffness EI_min under tension T leaving a clamp, w″ ∝ e^{−px}, p = √(T/EI_min), so that the
displacement Y at x from the last point of contact fixes the curvature there; the outer wire's
idealised stress amplitude (zero to peak) is σ_a = K Y_b for the peak-to-peak displacement Y_b,

    K = E_a d_a p² / (4 (e^{−px} − 1 + px)),   x = 89 mm (3.5 in) by the standard.

Units: m, N, N m, 1/m.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
import numpy.typing as npt

from ..cable.description import Cable
from .stick_slip import ei_min, masing

__all__ = [
    "TensionedBeam",
    "clamped_deflection",
    "POFFENBERGER_SWART_DISTANCE",
    "poffenberger_swart",
]

Array = npt.NDArray[np.float64]


def clamped_deflection(P: float, T: float, L: float, EI: float) -> float:
    """Midspan deflection of a clamped–clamped beam under tension T and midspan load P, m."""
    a, k = L / 2, np.sqrt(T / EI)
    return P / (2 * T) * (a - 2 / k * np.tanh(k * a / 2))


class TensionedBeam:
    """Clamped–clamped span ``length`` under ``tension`` held constant, midspan load P, with a
    nonlinear odd moment–curvature law given by its inverse ``curvature(M)``."""

    def __init__(self, length: float, tension: float, curvature: Callable[[Array], Array]):
        self.L, self.T, self.kappa = length, tension, curvature

    def _shoot(self, P: Array, M0: Array, n: int) -> tuple[Array, Array]:
        """Integrate the half span for every (P, M₀) at once (RK4 on w, w′); (w′(a), w(a))."""
        a = self.L / 2
        h = a / n
        w = np.zeros_like(P)
        dw = np.zeros_like(P)

        def rhs(x, w, dw):
            return dw, self.kappa(self.T * w - P / 2 * x + M0)

        x = 0.0
        for _ in range(n):
            k1 = rhs(x, w, dw)
            k2 = rhs(x + h / 2, w + h / 2 * k1[0], dw + h / 2 * k1[1])
            k3 = rhs(x + h / 2, w + h / 2 * k2[0], dw + h / 2 * k2[1])
            k4 = rhs(x + h, w + h * k3[0], dw + h * k3[1])
            w = w + h / 6 * (k1[0] + 2 * k2[0] + 2 * k3[0] + k4[0])
            dw = dw + h / 6 * (k1[1] + 2 * k2[1] + 2 * k3[1] + k4[1])
            x += h
        return dw, w

    def deflections(self, loads: npt.ArrayLike, n: int = 400) -> Array:
        """Midspan deflections (m) on the virgin curve for all ``loads`` at once (bisection on the
        clamp moment M₀ of each, vectorised)."""
        P = np.atleast_1d(np.asarray(loads, dtype=float))
        s = np.where(P < 0, -1.0, 1.0)
        lo = np.zeros_like(P)
        hi = P * self.L / 8  # M₀ between 0 and the string-free value PL/8
        hi = np.where(self._shoot(P, hi, n)[0] * s < 0, 4 * hi, hi)
        for _ in range(60):
            mid = 0.5 * (lo + hi)
            above = self._shoot(P, mid, n)[0] * s > 0
            hi, lo = np.where(above, mid, hi), np.where(above, lo, mid)
        return self._shoot(P, 0.5 * (lo + hi), n)[1]

    def deflection(self, P: float, n: int = 400) -> float:
        """Midspan deflection on the virgin curve, m."""
        return float(self.deflections([P], n)[0])

    def cycle(self, loads: npt.ArrayLike, n: int = 400) -> Array:
        """Deflections along a load history starting at 0 (Masing applies to the whole beam:
        the beam equations are linear in w, M and P, so each branch is the virgin solution
        scaled by 2)."""
        loads = np.asarray(loads, dtype=float)
        grid = np.linspace(0.0, 2 * np.abs(loads).max(), 41)
        virgin = self.deflections(grid, n)

        def v(p):
            return np.sign(p) * np.interp(np.abs(p), grid, virgin)

        return masing(v, loads)


#: m, where Poffenberger–Swart's Y_b is measured from the last point of contact (3.5 in)
POFFENBERGER_SWART_DISTANCE = 0.089


def poffenberger_swart(
    cable: Cable,
    tension: float,
    distance: float = POFFENBERGER_SWART_DISTANCE,
    variant: str = "EPRI",
) -> float:
    """K (Pa/m) of σ_a = K Y_b: the outer wires' stress amplitude (zero to peak) per peak-to-peak
    displacement Y_b at ``distance`` (m) from the clamp, under ``tension`` (N), with EI_min of
    ``variant`` and the outer layer's E and diameter."""
    outer = cable.layers[-1].wire
    p = np.sqrt(tension / ei_min(cable, variant))
    px = p * distance
    return float(outer.E * outer.diameter * p**2 / (4 * (np.exp(-px) - 1 + px)))
