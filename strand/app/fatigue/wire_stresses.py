"""The wires' surface stresses over a run's history (``wire_sections.h5``), and their damage: per
element the surface point of largest stress range (``element_results``), per wire the largest
over the whole wire and per zone (``wire_results``). Each point's stress history repeats (one
steady repetition of the run's cycle, counted by rainflow closed on itself) and is damaged under
its layer's S–N curve (Miner): each counted cycle's range as it is, or its layer's mean-stress
correction's equivalent range (``strand.fatigue.meanstress``; ``[fatigue] mean_stress``), and the
sum times the design fatigue factor (``[fatigue] design_fatigue_factor``). Units: Pa, m; angles in
degrees in the results.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from ...fatigue.cycles import repeating_ranges
from ...fatigue.meanstress import MeanStress
from ...fatigue.sn import SN_CURVES, USER_SOURCE, SNCurve, miner_damage
from ...fatigue.stress import shear_stress, surface_stress
from ..history import History
from .findings import ElementResults, WireResults, WireZone

__all__ = ["element_results", "wire_results", "surface_stress_at", "repeating_damage"]

Array = npt.NDArray[np.float64]


def _surface_angles(n: int) -> Array:
    return 2 * np.pi * np.arange(n) / n


def surface_stress_at(sections: History, cells, angle) -> Array:
    """σ (S, P), Pa, of the elements ``cells`` (P,) at their surface angles ``angle`` (P,), rad."""
    N, m1, m2 = (sections[k][:, cells] for k in ("axial", "m1", "m2"))
    return surface_stress(N, m1, m2, sections.static["diameter"][cells], angle)


def _curve_key(curve: SNCurve | None) -> str:
    """The ``SN_CURVES`` key of ``curve`` ("user" for the user's own, "custom" for the case
    file's ``sn_A``…, "not assessed" for None)."""
    if curve is None:
        return "not assessed"
    if curve.source == USER_SOURCE:
        return "user"
    return next((k for k, c in SN_CURVES.items() if c == curve), "custom")


def repeating_damage(
    series: Array,
    curve: SNCurve | None,
    mean_stress: MeanStress | None = None,
    factor: float = 1.0,
) -> Array:
    """Miner damage of one repetition of each column of ``series`` (n steps, M histories) of
    repeating stress (Pa), times ``factor`` (the design fatigue factor): (M,), NaN where no
    curve applies. With ``mean_stress``, each cycle counts at its equivalent range."""
    series = np.asarray(series, float)
    if curve is None:
        return np.full(series.shape[1], np.nan)
    if mean_stress is None:
        ranges = repeating_ranges(series)  # (M, C), padded with no range
    else:
        ranges = mean_stress.ranges(*repeating_ranges(series, means=True))
    return factor * miner_damage(ranges, 1.0, curve)


def element_results(
    sections: History,
    n_points: int,
    curves: list,
    clamp: npt.NDArray[np.bool_],
    mean_stress: list | None = None,
    factor: float = 1.0,
) -> ElementResults:
    """Per element: the surface point (of ``n_points`` around the wire) of largest stress range
    over the history, its range, mean and peak, the torsional shear range, and the Miner damage
    per cycle at the worst point of the element (every point's stress history repeating, under
    its layer's curve in ``curves`` and correction in ``mean_stress``, times ``factor``; NaN
    where the layer has no curve); ``clamp``: the elements in a clamp zone."""
    mean_stress = mean_stress or [None] * len(curves)
    static = sections.static
    psi = _surface_angles(n_points)
    N, m1, m2 = (sections[k][..., None] for k in ("axial", "m1", "m2"))
    sigma = surface_stress(N, m1, m2, static["diameter"][:, None], psi)  # (S, E, n_points)
    hi, lo = sigma.max(axis=0), sigma.min(axis=0)  # (E, n_points)
    ranges = hi - lo
    worst = np.argmax(ranges, axis=1)
    rows = np.arange(len(worst))
    tau = shear_stress(sections["torque"], static["diameter"])
    damage = np.full(len(worst), np.nan)
    for layer, curve in enumerate(curves):
        mine = np.flatnonzero(static["layer"] == layer)
        if curve is not None and len(mine):
            points = sigma[:, mine, :].reshape(len(sigma), -1)  # (S, elements × points)
            damage[mine] = (
                repeating_damage(points, curve, mean_stress[layer], factor)
                .reshape(len(mine), -1)
                .max(axis=1)
            )
    return ElementResults(
        wire=np.asarray(static["wire"]),
        layer=np.asarray(static["layer"]),
        z=np.asarray(static["z"]),
        clamp=clamp,
        angle=np.degrees(psi[worst]),
        range=ranges[rows, worst],
        mean=0.5 * (hi + lo)[rows, worst],
        peak=hi[rows, worst],
        shear_range=np.ptp(tau, axis=0),
        damage=damage,
    )


def _worst_of(elements: ElementResults, mine: Array) -> tuple[float, float, float, float]:
    """Largest range, its z and angle, and the largest damage (NaN: not assessed, or no
    element) over the elements ``mine``."""
    if len(mine) == 0:
        return np.nan, np.nan, np.nan, np.nan
    k = mine[np.argmax(elements.range[mine])]
    damage = elements.damage[mine]
    return (
        elements.range[k],
        elements.z[k],
        elements.angle[k],
        (np.nan if np.all(np.isnan(damage)) else np.nanmax(damage)),
    )


def _repetitions(damage: Array) -> Array:
    """Repetitions of the cycle to failure 1/D: inf where D = 0, NaN where not assessed."""
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(damage > 0, 1 / damage, np.where(np.isnan(damage), np.nan, np.inf))


def _wire_zone(elements: ElementResults, wires: Array, mask: npt.NDArray[np.bool_]) -> WireZone:
    """Per wire of ``wires``: the worst of its elements in ``mask`` (``_worst_of``)."""
    worst = np.full((len(wires), 4), np.nan)
    for w in wires:
        worst[w] = _worst_of(elements, np.flatnonzero((elements.wire == w) & mask))
    range_, z, angle, damage = (np.array(column) for column in worst.T)
    return WireZone(range=range_, z=z, angle=angle, damage=damage, repetitions=_repetitions(damage))


def wire_results(elements: ElementResults, curves: list) -> WireResults:
    """Per wire: its layer and curve key (``curves``: per layer its S–N curve); over the whole
    wire and in the free span and the clamp zone apart: the largest stress range, its element's
    z and angle, the Miner damage per cycle and the repetitions to failure."""
    wires = np.arange(int(elements.wire.max()) + 1)
    layer = np.array(
        [elements.layer[np.flatnonzero(elements.wire == w)[0]] for w in wires], dtype=int
    )
    return WireResults(
        layer=layer,
        curve=np.array([_curve_key(curves[i]) for i in layer]),
        whole=_wire_zone(elements, wires, np.ones_like(elements.clamp)),
        free_span=_wire_zone(elements, wires, ~elements.clamp),
        clamp_zone=_wire_zone(elements, wires, elements.clamp),
    )
