"""**Axial–torsional stiffness** (``costello_stiffness``) and the torque of a tensioned strand
whose ends are held against rotation (``held_end_torque``): Costello's thin-rod theory of a straight
strand (helix radii fixed): each wire's strain ξ, curvature and twist changes from the strand's
strain ε and twist rate θ′, its tension T = EAξ, moments G′ = EIΔκ′, H = GJΔτ, shear
N′ = Hκ′ − G′τ (Love), summed into the strand's F and M; linearised numerically.

Units: m, N, N m, rad.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from ..cable.description import Cable

__all__ = ["costello_stiffness", "held_end_torque"]

Array = npt.NDArray[np.float64]


def costello_stiffness(cable: Cable, step: float = 1e-7) -> Array:
    """Costello's linear axial–torsional stiffness [[∂F/∂ε, ∂F/∂θ′], [∂M/∂ε, ∂M/∂θ′]] of a straight
    strand (N, N m, N m, N m²), θ′ the twist rate (rad/m) positive about the strand axis +z.

    Per helical layer (docs/theory.md §5.2; helix radius r fixed, no Poisson contraction; h = ±1 the
    hand): tan α′ = (tan α + h r θ′)/(1 + ε), ξ = √((1 + ε)² + (tan α + h r θ′)²) cos α − 1,
    κ′ = sin²α/r, τ = sin α cos α/r; F = E_cA_cε + Σ n(T cos α + N′ sin α) and
    M = G_cJ_cθ′ + Σ n h(H cos α + G′ sin α + T r sin α − N′ r cos α). Central differences of step
    ``step``; the result is slightly unsymmetric (exact kinematics with Love's resultants).
    """

    def resultants(eps: float, twist: float) -> Array:
        core = cable.layers[0].wire
        F = core.E * core.area * eps
        M = core.E / (2 * (1 + core.nu)) * np.pi * core.diameter**4 / 32 * twist
        for lay in cable.layers[1:]:
            w, a, r, h = lay.wire, lay.alpha, lay.radius, lay.hand
            G, inertia = w.E / (2 * (1 + w.nu)), np.pi * w.diameter**4 / 64
            tan_new = (np.tan(a) + h * r * twist) / (1 + eps)
            a_new = np.arctan(tan_new)
            xi = np.hypot(1 + eps, np.tan(a) + h * r * twist) * np.cos(a) - 1
            kappa, tau = np.sin(a) ** 2 / r, np.sin(a) * np.cos(a) / r
            d_kappa = np.sin(a_new) ** 2 / r - kappa
            d_tau = np.sin(a_new) * np.cos(a_new) / r - tau
            T, Gp, H = w.E * w.area * xi, w.E * inertia * d_kappa, G * 2 * inertia * d_tau
            N = H * kappa - Gp * tau
            F += lay.wires * (T * np.cos(a) + N * np.sin(a))
            M += (
                lay.wires
                * h
                * (H * np.cos(a) + Gp * np.sin(a) + T * r * np.sin(a) - N * r * np.cos(a))
            )
        return np.array([F, M])

    d_eps = (resultants(step, 0.0) - resultants(-step, 0.0)) / (2 * step)
    twist_step = step / max(lay.radius for lay in cable.layers)
    d_twist = (resultants(0.0, twist_step) - resultants(0.0, -twist_step)) / (2 * twist_step)
    return np.column_stack([d_eps, d_twist])


def held_end_torque(cable: Cable, tension: float) -> float:
    """Costello's torque (N m, about +z, on a section's face of outward normal +z) of a straight
    strand under ``tension`` (N) with its ends held against rotation: M = k_θε T / k_εε, with
    k_θε the mean of the two coupling terms of ``costello_stiffness`` (they differ by a few %,
    Love's resultants with exact kinematics; a symmetric model sits between them)."""
    C = costello_stiffness(cable)
    return float(0.5 * (C[0, 1] + C[1, 0]) * tension / C[0, 0])
