"""The fatigue report's summary, ``fatigue.txt`` (``strand.app.fatigue.report`` computes what it
says): the load cycles of one steady repetition of the run's cycle (damages are per such cycle), the
pairs stuck throughout, the S–N curve of every layer (one line for those not assessed), per zone
(free span, clamp zone) the five worst crossings, hot spots and first wires to fail, the
strand-level T–N check beside the wire-level damage, and Poffenberger–Swart or why it is
skipped."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from ...fatigue.meanstress import LAW_NAMES
from ...fatigue.sn import SNCurve
from ...fatigue.tn import TENSION_CYCLE_SHARE
from ...fatigue.zones import ZONES, free_span

if TYPE_CHECKING:
    from ..settings import FatigueSettings
    from .findings import (
        CrossingResults,
        ElementResults,
        FatigueReport,
        PoffenbergerSwartCheck,
        TensionCheck,
        WireZone,
    )

__all__ = ["summary_text", "no_free_span", "assessment_lines"]


def no_free_span(length: float, end_zone: float) -> str:
    """The report's one line for a span that two clamp zones leave no free span: what span, or
    what end zone, would leave one."""
    return (
        f"{ZONES[0]}: none: the span {length:.4g} m is not longer than two end zones (2 × "
        f"{end_zone:.4g} m, [fatigue] end_zone); a span longer than {2 * end_zone:.4g} m, or an "
        f"end_zone shorter than {length / 2:.4g} m, leaves one"
    )


def assessment_lines(mean_stress: str, factor: float) -> list[str]:
    """The report's lines for a mean-stress correction and a design fatigue factor (none for
    "none" and 1: the damage is then the plain Miner sum of the ranges)."""
    lines = []
    if mean_stress != "none":
        lines.append(
            f"  mean stress: {LAW_NAMES[mean_stress]} ([fatigue] mean_stress), the wires' tensile "
            "strength from the cable: each cycle damages at its equivalent range at the curve's "
            "own mean (0 for the built-in curves, which come from tensioned tests: their mean "
            "then counts twice, conservative); the ranges printed are the cycles' own"
        )
    if factor != 1:
        lines.append(
            f"  design fatigue factor {factor:g} ([fatigue] design_fatigue_factor): every damage, "
            f"wire-level and T–N, is the Miner sum × {factor:g}; repetitions and periods to "
            f"failure are divided by {factor:g}"
        )
    return lines


def _crossing_line(crossings: CrossingResults, k: int) -> str:
    interface = crossings.interface[k]
    return (
        f"  {k:5d} {interface}|{interface + 1}"
        f"{'  line' if crossings.line[k] else '      '}  {crossings.z[k]:.4f}"
        f"  {crossings.angle[k]:8.1f}"
        f"  {1e6 * crossings.slip_amplitude[k]:12.3f}  {crossings.peak_force[k]:10.1f}"
        f"  {crossings.friction_amplitude[k]:9.2f}  {1e-6 * crossings.peak_pressure[k]:8.0f}"
        f"  {1e-6 * crossings.surface_stress[k]:9.1f}  {1e-6 * crossings.ruiz_f2[k]:12.4g}"
    )


_CROSSING_HEAD = (
    "  pair  interface  z (m)    angle (°)  slip amp (µm)  P peak (N)  Q amp (N)  "
    "p0 (MPa)  σ_T (MPa)  F2 (MPa J/m²)"
)


def _curve_lines(curves: list[SNCurve | None]) -> list[str]:
    """Which S–N curve each layer's wires are assessed with, and one line for those without."""
    lines, done = [], set()
    for curve in curves:
        if curve is None or curve.name in done:
            continue
        done.add(curve.name)
        on = [i for i, c in enumerate(curves) if c is not None and c.name == curve.name]
        lines.append(f"  layers {on}: {curve.name} ({curve.source})")
    missing = [i for i, c in enumerate(curves) if c is None]
    if missing:
        lines.append(
            f"  layers {missing}: not assessed (no S–N curve for their wires' material;"
            " damage NaN in the CSV files)"
        )
    return lines


def _hot_spot_lines(elements: ElementResults, clamp: bool) -> list[str]:
    """The five elements of the zone of largest surface stress range."""
    lines = [
        " five hot spots (largest surface stress range over the history):",
        "  element  wire  layer  z (m)    ψ (°)  range (MPa)  mean (MPa)",
    ]
    for k in [k for k in np.argsort(-elements.range) if elements.clamp[k] == clamp][:5]:
        lines.append(
            f"  {k:7d} {elements.wire[k]:5d} {elements.layer[k]:6d}  {elements.z[k]:.4f} "
            f"{elements.angle[k]:6.1f}  {1e-6 * elements.range[k]:11.2f}  "
            f"{1e-6 * elements.mean[k]:10.1f}"
        )
    return lines


def _first_wires_lines(layer: np.ndarray, zone: WireZone) -> list[str]:
    """The five wires of largest damage in the zone (``layer``: the wires' layers)."""
    damage = zone.damage
    order = [k for k in np.argsort(-np.nan_to_num(damage, nan=-1.0)) if damage[k] > 0][:5]
    lines = [" first wires to fail (Miner damage per cycle, a steady repetition):"]
    for k in order:
        lines.append(
            f"  wire {k:2d} (layer {int(layer[k])}): damage {damage[k]:.3g} per cycle, "
            f"{zone.repetitions[k]:.3g} repetitions; largest range "
            f"{1e-6 * zone.range[k]:.2f} MPa at z = {zone.z[k]:.4f} m, "
            f"ψ = {zone.angle[k]:.0f}°"
        )
    if not order:
        assessed = ~np.isnan(damage)
        lines.append(
            "  none: no cycle damages the assessed wires" if assessed.any() else "  none assessed"
        )
    return lines


def _zone_text(report: FatigueReport, clamp: bool) -> list[str]:
    """The five worst crossings, hot spots and first wires to fail of one zone (``clamp``: the
    clamp zone, else the free span)."""
    crossings = report.crossings
    lines = []
    order = np.argsort(-crossings.ruiz_f2)
    here = crossings.clamp == clamp
    point = [k for k in order if here[k] and not crossings.line[k]][:5]
    line = [k for k in order if here[k] and crossings.line[k]][:3]
    for title, chosen in (
        ("five worst crossings by Ruiz's F2 = σ_T τ δ (Ruiz, Boddington & Chen 1984):", point),
        ("worst line contacts (per tributary length) by the same F2:", line),
    ):
        if chosen:
            lines += [f" {title}", _CROSSING_HEAD] + [_crossing_line(crossings, k) for k in chosen]
    lines += _hot_spot_lines(report.elements, clamp)
    return lines + _first_wires_lines(report.wires.layer, report.wires.zone(clamp))


def _tension_lines(check: TensionCheck) -> list[str]:
    """The strand-level T–N check beside the wire-level model, on the same history."""
    wire = "no wire assessed"
    if check.wire is not None:
        where = "clamp zone" if check.wire_in_clamp else "free span"
        if check.wire_in_clamp and check.free_wire is None:
            where += ": no free span"
        wire = f"largest damage {check.wire_damage:.3g} per cycle (wire {check.wire}, {where})"
        if check.wire_in_clamp and check.free_wire is not None:
            wire += f"; in the free span {check.free_damage:.3g} per cycle (wire {check.free_wire})"
    if not check.cycle:
        return [
            f"tension-only practice (T–N): no tension cycle: the strand's tension at midspan "
            f"stays at {1e-3 * check.mean:.4g} kN within {check.range:.3g} N (under "
            f"{100 * TENSION_CYCLE_SHARE:g} %), so a T–N check sees no damage; the wire-level "
            f"model: {wire}"
        ]
    api = (
        "API RP 2SK spiral strand (N R^5.05 = 10^(3.25 − 3.43 L_m), R = ΔT/MBS): damage "
        f"{check.api:.3g} per cycle"
        if check.api is not None
        else "API RP 2SK: not checked ([fatigue] breaking_strength not given)"
    )
    return [
        f"tension-only practice (T–N) on the strand's tension at midspan (mean "
        f"{1e-3 * check.mean:.4g} kN, largest range {1e-3 * check.range:.4g} kN, rainflow of "
        "the history repeating):",
        f"  DNV-OS-E301 spiral rope (n = 1.7e17 s^-4.8, s = ΔT over the metallic area "
        f"{1e6 * check.area:.1f} mm²): damage {check.dnv:.3g} per cycle",
        f"  {api}",
        f"  wire-level model on the same history: {wire}",
    ]


def _poffenberger_swart_lines(check: PoffenbergerSwartCheck | None) -> list[str]:
    """Poffenberger–Swart against the model at the clamp, or why it is skipped."""
    if check is None:
        return []
    if not check.holds:
        return [f"Poffenberger–Swart skipped: {check.reason}"]
    return [
        f"Poffenberger–Swart at the clamp (x = {1e3 * check.distance:.0f} mm): "
        f"Y_b = {1e3 * check.y_b:.3f} mm peak to peak, K = {1e-9 * check.K:.2f} MPa/mm "
        f"→ σ_a = {1e-6 * check.sigma_a:.2f} MPa; model (half the outer wires' largest range "
        f"at the clamp mouth) {1e-6 * check.model:.2f} MPa; ratio {check.ratio:.3f}"
    ]


def summary_text(report: FatigueReport, settings: FatigueSettings) -> str:
    """The report's summary: cycles, stuck pairs, per zone the worst crossings, hot spots and
    first wires to fail; the T–N check; P–S."""
    crossings, cycles = report.crossings, report.cycles
    lines = [
        f"load cycles of one steady repetition of the cycle (rainflow on the cycle load closed "
        f"on itself, ASTM E1049): {len(cycles)} counted, ranges "
        + ", ".join(f"{x:.4g}×{n:g}" for x, n in zip(cycles.range, cycles.count, strict=True)),
        f"stuck throughout (Coulomb slide below {1e9 * settings.stuck_slip:g} nm): "
        + ", ".join(
            f"{int(np.sum(crossings.stuck & (crossings.interface == i)))} of "
            f"{int(np.sum(crossings.interface == i))} pairs at {i}|{i + 1}"
            for i in np.unique(crossings.interface)
        ),
        "Miner damage with the S–N curves:",
        *_curve_lines(report.curves),
        *assessment_lines(report.mean_stress, report.design_factor),
    ]
    in_clamp = report.elements.clamp
    span = free_span(report.length, report.end_zone)
    for zone, clamp in zip(ZONES, (False, True), strict=True):
        here = in_clamp == clamp
        if not clamp and (span is None or not here.any()):
            lines.append(no_free_span(report.length, report.end_zone))
            continue
        if not here.any():
            lines.append(f"{zone}: none: no element lies within {report.end_zone:.4g} m of an end")
            continue
        where = (
            f"z in [{span[0]:.4g}, {span[1]:.4g}] m"
            if not clamp
            else (f"within {report.end_zone:.4g} m of an end")
        )
        lines.append(f"{zone} ({where}):")
        lines += _zone_text(report, clamp)
    lines += _tension_lines(report.tension_check)
    lines += _poffenberger_swart_lines(report.poffenberger_swart)
    return "\n".join(lines) + "\n"
