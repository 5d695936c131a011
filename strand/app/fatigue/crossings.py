"""Fretting at every contact pair of a run's history (``contact_pairs.h5``): the worst counted
cycle's slip, forces, Hertz contact, surface stress and Ruiz's parameters, whether the pair stayed
stuck throughout, and the Miner damage of the two wires' surfaces facing each other
(``crossing_results``). The physics is the library's (``strand.fatigue.fretting``,
``strand.contact.hertz``). Units: m, N, Pa, J.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from ...cable.description import Cable
from ...contact.hertz import contact_ellipse, line_contact
from ...fatigue.cycles import Cycles, cycle_steps
from ...fatigue.fretting import crossing_cycles, ruiz_parameters, stuck_throughout
from ..history import History
from .findings import CrossingResults
from .wire_stresses import repeating_damage, surface_stress_at

__all__ = ["crossing_results"]

Array = npt.NDArray[np.float64]
Cells = npt.NDArray[np.int64]


def _pair_cells_and_angles(pairs: History, sections: History) -> list[tuple[Cells, Array]]:
    """The element of each pair's node on wire a and on wire b (the first whose midpoint lies
    above the pair's z, or the wire's last), and the surface angle ψ (rad) facing the other wire:
    the strand's pairs touch along its radius, so ψ = 0 (outward) on the inner wire a and ψ = π
    (towards the core) on the outer wire b."""
    elements, pair = sections.static, pairs.static
    out = []
    for wire, psi in ((pair["wire_a"], 0.0), (pair["wire_b"], np.pi)):
        cells = np.empty(len(wire), dtype=np.int64)
        for w in np.unique(wire):
            mine = np.flatnonzero(elements["wire"] == w)
            sel = np.flatnonzero(wire == w)
            k = np.clip(np.searchsorted(elements["z"][mine], pair["z"][sel]), 0, len(mine) - 1)
            cells[sel] = mine[k]
        out.append((cells, np.full(len(wire), psi)))
    return out


def crossing_results(
    pairs: History,
    sections: History,
    cable: Cable,
    curves: list,
    cycles: Cycles,
    *,
    stuck_slip: float,
    clamp: npt.NDArray[np.bool_],
    mean_stress: list | None = None,
    factor: float = 1.0,
) -> CrossingResults:
    """Per pair: the worst counted cycle's fretting results, Hertz contact, Ruiz's parameters,
    whether it stayed stuck throughout (``stuck_slip``, m) and the Miner damage of the wires'
    facing surfaces under their layers' ``curves`` and ``mean_stress`` corrections, times
    ``factor`` (NaN where neither has a curve); ``clamp``: the pairs in a clamp zone."""
    mean_stress = mean_stress or [None] * len(curves)
    static = pairs.static
    per_cycle = crossing_cycles(
        cycles, pairs["force"], pairs["friction"], pairs["slip"], pairs["sliding"], pairs["work"]
    )
    wires = [lay.wire for lay in cable.layers]
    inner, outer = static["interface"], static["interface"] + 1
    E_a, nu_a = (np.array([getattr(w, k) for w in wires])[inner] for k in ("E", "nu"))
    E_b, nu_b = (np.array([getattr(w, k) for w in wires])[outer] for k in ("E", "nu"))
    line = static["line"].astype(bool)
    beta = np.radians(static["crossing_angle"])
    # Hertz at every cycle's peak force: (C, P)
    a, b, p0 = contact_ellipse(
        static["radius_a"],
        static["radius_b"],
        beta,
        E_a,
        nu_a,
        E_b,
        nu_b,
        force=per_cycle.peak_force,
    )
    length = static["tributary"]
    q = np.divide(
        per_cycle.peak_force, length, out=np.zeros_like(per_cycle.peak_force), where=length > 0
    )
    half, p0_line = line_contact(static["radius_a"], static["radius_b"], E_a, nu_a, E_b, nu_b, q)
    a = np.where(line, half, a)  # line: the half-width across the line, and the length along it
    b = np.where(line, 0.5 * length, b)
    p0 = np.where(line, p0_line, p0)
    area = np.where(line, 2 * half * length, np.pi * a * b)
    (cells_a, psi_a), (cells_b, psi_b) = _pair_cells_and_angles(pairs, sections)
    sigma_a = surface_stress_at(sections, cells_a, psi_a)  # (S, P)
    sigma_b = surface_stress_at(sections, cells_b, psi_b)
    sigma = np.maximum(sigma_a, sigma_b)
    sigma_peak = np.array(
        [
            sigma[cycle_steps(i, j, len(sigma))].max(axis=0)
            for i, j in zip(cycles.start, cycles.end, strict=True)
        ]
    )
    f1, f2 = ruiz_parameters(
        per_cycle.friction_amplitude, area, per_cycle.slip_amplitude, sigma_peak
    )
    worst = np.argmax(f2 if np.any(f2 > 0) else per_cycle.slip_amplitude, axis=0)  # (P,)

    def pick(x: Array) -> Array:
        return np.take_along_axis(x, worst[None, :], axis=0)[0]

    sides = np.full((2, len(line)), np.nan)  # inner wire's side, outer wire's side
    for side, (sigma_side, layers) in enumerate(((sigma_a, inner), (sigma_b, outer))):
        for layer, curve in enumerate(curves):
            mine = layers == layer
            if curve is not None and mine.any():
                sides[side, mine] = repeating_damage(
                    sigma_side[:, mine], curve, mean_stress[layer], factor
                )
    damage = np.fmax(sides[0], sides[1])  # the worse side; NaN where neither is assessed
    has = np.array([c is not None for c in curves])
    assessed = np.select(
        [has[inner] & has[outer], has[inner], has[outer]],
        ["both", "inner", "outer"],
        "not assessed",
    )
    return CrossingResults(
        interface=np.asarray(static["interface"]),
        wire_a=np.asarray(static["wire_a"]),
        wire_b=np.asarray(static["wire_b"]),
        z=np.asarray(static["z"]),
        angle=np.asarray(static["angle"]),
        line=line,
        clamp=clamp,
        stuck=stuck_throughout(pairs["sliding"], stuck_slip),
        slip_amplitude=pick(per_cycle.slip_amplitude),
        displacement_amplitude=pick(per_cycle.displacement_amplitude),
        friction_amplitude=pick(per_cycle.friction_amplitude),
        peak_force=pick(per_cycle.peak_force),
        mean_force=pick(per_cycle.mean_force),
        semi_axis_a=pick(a),
        semi_axis_b=pick(b),
        peak_pressure=pick(p0),
        surface_stress=pick(sigma_peak),
        ruiz_f1=pick(f1),
        ruiz_f2=pick(f2),
        energy=per_cycle.energy.sum(axis=0),
        damage=damage,
        assessed=assessed,
    )
