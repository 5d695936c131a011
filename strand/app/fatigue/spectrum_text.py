"""A spectrum's summary, ``spectrum.txt`` (``strand.app.fatigue.spectrum`` computes what it says,
``strand.app.fatigue.spectrum_findings`` holds it): the amplitudes and their counts, the S–N
curves, per zone each layer's worst wire and the five worst contact pairs, and the strand-level
T–N sums beside the wire-level model's, each damage D with every amplitude's share of it."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
import numpy.typing as npt

from ...fatigue.tn import TENSION_CYCLE_SHARE
from ...fatigue.zones import ZONES
from .text import assessment_lines, no_free_span

if TYPE_CHECKING:
    from .spectrum_findings import SpectrumReport

__all__ = ["spectrum_text"]

Array = npt.NDArray[np.float64]


def _shares(report: SpectrumReport, shares: Array) -> str:
    if np.all(np.isnan(shares)):
        return "no damage"
    return ", ".join(
        f"{a:g} {report.unit} {100 * share:.0f} %"
        for a, share in zip(report.amplitudes, shares, strict=True)
    )


def _periods(damage: float) -> str:
    return "not assessed" if np.isnan(damage) else "inf" if damage == 0 else f"{1 / damage:.3g}"


def _zone_lines(report: SpectrumReport, zone: str) -> list[str]:
    """Per layer its worst wire, and the five worst contact pairs, of one zone."""
    wires, crossings = report.wires, report.crossings
    lines = [" per layer, its worst wire:"]
    for layer in np.unique(wires.layer):
        mine = np.flatnonzero((wires.layer == layer) & (wires.zone == zone))
        if len(mine) == 0:
            continue
        if np.all(np.isnan(wires.damage[mine])):
            lines.append(f"  layer {layer}: not assessed (no S–N curve for its wires)")
            continue
        k = mine[np.nanargmax(wires.damage[mine])]
        lines.append(
            f"  layer {layer}: wire {wires.wire[k]}, D = {wires.damage[k]:.3g} "
            f"({_periods(wires.damage[k])} periods) at z = {wires.z[k]:.4f} m; "
            f"{_shares(report, wires.shares[k])}"
        )
    clamp = zone == ZONES[1]
    damage = np.where(crossings.clamp == clamp, crossings.damage, np.nan)
    worst = [k for k in np.argsort(-np.nan_to_num(damage, nan=-1.0))[:5] if not np.isnan(damage[k])]
    if worst:
        lines.append(" five worst contact pairs (their wires' facing surfaces):")
    elif np.any(crossings.clamp == clamp):
        lines.append(" contact pairs: not assessed (no S–N curve for their wires)")
    for k in worst:
        interface = crossings.interface[k]
        lines.append(
            f"  pair {k} ({interface}|{interface + 1}"
            f"{', line' if crossings.line[k] else ''}) z = {crossings.z[k]:.4f} m: D = "
            f"{crossings.damage[k]:.3g}; {_shares(report, crossings.shares[:, k])}"
        )
    return lines


def _tension_lines(report: SpectrumReport) -> list[str]:
    tension, wires = report.tension, report.wires
    ranges = ", ".join(
        f"{a:g} {report.unit}: {1e-3 * dt:.4g} kN"
        for a, dt in zip(report.amplitudes, tension.range, strict=True)
    )
    lines = [
        f"strand-level T–N on the strand's tension at midspan (mean "
        f"{1e-3 * tension.mean[0]:.4g} kN; largest range per amplitude {ranges}):"
    ]
    if not tension.cycle.any():
        lines.append(
            f"  no tension cycle at any amplitude (ranges under "
            f"{100 * TENSION_CYCLE_SHARE:g} % of the mean): T–N sees next to no damage"
        )
    lines.append(
        f"  DNV-OS-E301 spiral rope: D = {tension.dnv:.3g}; {_shares(report, tension.dnv_shares)}"
    )
    lines.append(
        "  API RP 2SK spiral strand: not checked ([fatigue] breaking_strength not given)"
        if tension.api is None
        else f"  API RP 2SK spiral strand: D = {tension.api:.3g}"
    )
    if np.all(np.isnan(wires.damage)):
        lines.append("  wire-level model, same spectrum: no wire assessed")
    else:
        k = int(np.nanargmax(wires.damage))
        lines.append(
            f"  wire-level model, same spectrum: largest D = {wires.damage[k]:.3g} (wire "
            f"{wires.wire[k]}, {wires.zone[k]})"
        )
    return lines


def spectrum_text(report: SpectrumReport) -> str:
    """``spectrum.txt``: the spectrum, per zone each layer's worst wire and the worst pairs,
    the T–N sums beside the wire-level model's."""
    lines = [
        f"fatigue spectrum of {report.parameter}: Miner's D = Σ n_i d_i, n_i the cycles in the "
        "spectrum's period, d_i the damage per cycle of the member at amplitude i (its fatigue "
        "report: one steady repetition of the cycle, its history closed on itself); D is per that "
        "period, 1/D periods to failure",
        f"  amplitude ({report.unit})  cycles n_i  member",
        *(
            f"  {a:>13g}  {n:>10.4g}  {name}"
            for a, n, name in zip(report.amplitudes, report.counts, report.names, strict=True)
        ),
    ]
    wires = report.wires
    curves = sorted({(int(la), str(cu)) for la, cu in zip(wires.layer, wires.curve, strict=True)})
    lines.append("S–N curves: " + ", ".join(f"layer {la} {cu}" for la, cu in curves))
    lines += assessment_lines(report.mean_stress, report.design_factor)
    for zone in ZONES:
        where = "" if zone == ZONES[0] else f" (within {report.end_zone:.3g} m of an end)"
        if not np.any(wires.zone == zone):
            lines.append(
                no_free_span(report.length, report.end_zone)
                if zone == ZONES[0]
                else f"{zone}{where}: none: no element lies within it"
            )
            continue
        lines += [f"{zone}{where}:", *_zone_lines(report, zone)]
    return "\n".join(lines + _tension_lines(report)) + "\n"
