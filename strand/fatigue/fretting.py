"""Fretting at wire contacts: per load cycle, what each pair's history says (physics only, numpy).

A pair's history over the converged steps (index 0: the start of the cycles) holds its normal force
p, friction force t, the relative tangential displacement of its two surface points (``slip``), its
Coulomb part (``sliding``: zero while the pair sticks) and the energy friction dissipated, all
summed from t = 0. A load cycle counted by rainflow runs between two turning points i → j of the
load; between them every quantity moves from one extreme to the other, so its amplitude is half
the change ‖x_j − x_i‖. Per pair and counted cycle:

* slip amplitude δ = ‖sliding_j − sliding_i‖/2 (gross slip; zero in stick) and the amplitude of the
  relative displacement of the surface points (with the contact's elastic compliance);
* friction force amplitude Q = ‖t_j − t_i‖/2, peak and mean normal force over the window;
* dissipated energy: 2 × count × the work done over the window (the half loop i → j, doubled for
  full cycles);
* Ruiz's fretting parameters (Ruiz, Boddington & Chen, Exp. Mech. 24, 1984): the wear parameter
  F₁ = τ δ (J/m²) and the fretting-fatigue parameter F₂ = σ_T τ δ (J Pa/m²), with τ = Q/area the
  mean friction traction over the Hertz contact area and σ_T the largest tensile surface stress of
  the two wires at the contact over the cycle.

Cycles of a repeating history (``cycles.repeating_cycles``) may run over its end (i > j): their
window is i…end, then start…j (``cycles.cycle_steps``), their work the work over both parts (the
closure from the last step to the first dissipates nothing), and their changes x_j − x_i between
the two states.

Units: m, N, J, Pa.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from .cycles import Cycles, cycle_steps

__all__ = ["CrossingCycles", "crossing_cycles", "ruiz_parameters", "stuck_throughout"]

Array = npt.NDArray[np.float64]


@dataclass(frozen=True)
class CrossingCycles:
    """Per counted cycle and pair, arrays (C, P): slip amplitude (m), displacement amplitude (m),
    friction force amplitude (N), peak and mean normal force (N), dissipated energy (J)."""

    slip_amplitude: Array
    displacement_amplitude: Array
    friction_amplitude: Array
    peak_force: Array
    mean_force: Array
    energy: Array


def _half_change(x: Array, i: int, j: int) -> Array:
    return 0.5 * np.linalg.norm(x[j] - x[i], axis=-1)


def _work(work: Array, i: int, j: int) -> Array:
    """The work done from step i to j, over the end of the history where i > j."""
    return work[j] - work[i] if i <= j else work[-1] - work[i] + work[j] - work[0]


def crossing_cycles(
    cycles: Cycles, force: Array, traction: Array, slip: Array, sliding: Array, work: Array
) -> CrossingCycles:
    """Per-cycle results of pair histories over the steps: ``force`` (S, P), ``traction``,
    ``slip``, ``sliding`` (S, P, 3), ``work`` (S, P); ``cycles`` counted on the load at the same
    steps, once through or repeating."""
    rows = []
    for i, j, c in zip(cycles.start, cycles.end, cycles.count, strict=True):
        window = force[cycle_steps(i, j, len(force))]
        rows.append(
            (
                _half_change(sliding, i, j),
                _half_change(slip, i, j),
                _half_change(traction, i, j),
                window.max(axis=0),
                window.mean(axis=0),
                2 * c * _work(work, i, j),
            )
        )
    n = force.shape[1]
    stacked = [np.array([r[k] for r in rows]).reshape(len(rows), n) for k in range(6)]
    return CrossingCycles(*stacked)


def ruiz_parameters(
    friction_amplitude, area, slip_amplitude, surface_stress
) -> tuple[Array, Array]:
    """Ruiz's F₁ = τδ (J/m²) and F₂ = σ_T τδ (J Pa/m²) with τ = Q/``area`` (Pa; 0 where the
    contact has no area) and σ_T = max(``surface_stress``, 0) (Pa): a compressed surface does not
    grow fretting cracks."""
    Q, area = np.asarray(friction_amplitude, float), np.asarray(area, float)
    tau = np.divide(Q, area, out=np.zeros(np.broadcast(Q, area).shape), where=area > 0)
    f1 = tau * np.asarray(slip_amplitude, float)
    return f1, np.maximum(np.asarray(surface_stress, float), 0.0) * f1


def stuck_throughout(sliding: Array, threshold: float) -> npt.NDArray[np.bool_]:
    """Pairs whose Coulomb slide ``sliding`` (S, P, 3; m, from the first step) never leaves a
    ball of radius ``threshold`` (m) round its first value: stuck over the whole history, their
    round-off slides (1e-23 m and less) counted as none."""
    sliding = np.asarray(sliding, float)
    if len(sliding) == 0:
        return np.ones(sliding.shape[1], bool)
    return np.linalg.norm(sliding - sliding[:1], axis=-1).max(axis=0) < threshold
