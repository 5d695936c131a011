"""The fatigue report's summary, ``fatigue.txt`` (``strand.app.fatigue.report`` computes what it
says): the load cycles of one steady repetition of the run's cycle (damages are per such cycle), the
pairs stuck throughout, the S–N curve of every layer (one line for those not assessed), per zone
(free span, clamp zone) the five worst crossings, hot spots and first wires to fail, the
strand-level T–N check beside the wire-level damage, and Poffenberger–Swart or why it is
skipped."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from ...cable.description import Cable
from ...fatigue.tn import TENSION_CYCLE_SHARE
from ...fatigue.zones import ZONES, free_span

if TYPE_CHECKING:
    from ..settings import FatigueSettings
    from .findings import FatigueReport

__all__ = ["summary_text", "no_free_span"]


def no_free_span(length: float, end_zone: float) -> str:
    """The report's one line for a span that two clamp zones leave no free span: what span, or
    what end zone, would leave one."""
    return (
        f"{ZONES[0]}: none: the span {length:.4g} m is not longer than two end zones (2 × "
        f"{end_zone:.4g} m, [fatigue] end_zone); a span longer than {2 * end_zone:.4g} m, or an "
        f"end_zone shorter than {length / 2:.4g} m, leaves one"
    )


def _crossing_line(st, c, k) -> str:
    return (
        f"  {k:5d} {st['interface'][k]}|{st['interface'][k] + 1}"
        f"{'  line' if st['line'][k] else '      '}  {st['z'][k]:.4f}  {st['angle'][k]:8.1f}"
        f"  {1e6 * c['slip_amplitude'][k]:12.3f}  {c['peak_force'][k]:10.1f}"
        f"  {c['friction_amplitude'][k]:9.2f}  {1e-6 * c['peak_pressure'][k]:8.0f}"
        f"  {1e-6 * c['surface_stress'][k]:9.1f}  {1e-6 * c['ruiz_f2'][k]:12.4g}"
    )


_CROSSING_HEAD = (
    "  pair  interface  z (m)    angle (°)  slip amp (µm)  P peak (N)  Q amp (N)  "
    "p0 (MPa)  σ_T (MPa)  F2 (MPa J/m²)"
)


def _curve_lines(cable: Cable, curves: list) -> list[str]:
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


def _zone_text(zone: str, pairs, sections, r: FatigueReport, mask_p, mask_e, mask_w) -> list:
    """The five worst crossings, hot spots and first wires to fail of one zone."""
    st, c, e, w, s = pairs.static, r.crossings, r.elements, r.wires, sections.static
    suffix = "_free" if zone == ZONES[0] else "_clamp"
    lines = []
    line = st["line"].astype(bool)
    order = np.argsort(-c["ruiz_f2"])
    point = [k for k in order if mask_p[k] and not line[k]][:5]
    lines_ = [k for k in order if mask_p[k] and line[k]][:3]
    for title, chosen in (
        ("five worst crossings by Ruiz's F2 = σ_T τ δ (Ruiz, Boddington & Chen 1984):", point),
        ("worst line contacts (per tributary length) by the same F2:", lines_),
    ):
        if chosen:
            lines += [f" {title}", _CROSSING_HEAD] + [_crossing_line(st, c, k) for k in chosen]
    lines.append(" five hot spots (largest surface stress range over the history):")
    lines.append("  element  wire  layer  z (m)    ψ (°)  range (MPa)  mean (MPa)")
    for k in [k for k in np.argsort(-e["range"]) if mask_e[k]][:5]:
        lines.append(
            f"  {k:7d} {s['wire'][k]:5d} {s['layer'][k]:6d}  {s['z'][k]:.4f} {e['angle'][k]:6.1f}"
            f"  {1e-6 * e['range'][k]:11.2f}  {1e-6 * e['mean'][k]:10.1f}"
        )
    damage = w["damage" + suffix]
    order = [k for k in np.argsort(-np.nan_to_num(damage, nan=-1.0)) if damage[k] > 0][:5]
    lines.append(" first wires to fail (Miner damage per cycle, a steady repetition):")
    for k in order:
        lines.append(
            f"  wire {k:2d} (layer {int(w['layer'][k])}): damage {damage[k]:.3g} per cycle, "
            f"{w['repetitions' + suffix][k]:.3g} repetitions; largest range "
            f"{1e-6 * w['range' + suffix][k]:.2f} MPa at z = {w['z' + suffix][k]:.4f} m, "
            f"ψ = {w['angle' + suffix][k]:.0f}°"
        )
    if not order:
        assessed = ~np.isnan(damage[mask_w])
        lines.append(
            "  none: no cycle damages the assessed wires" if assessed.any() else "  none assessed"
        )
    return lines


def _tension_lines(tn: dict) -> list[str]:
    """The strand-level T–N check beside the wire-level model, on the same history."""
    wire = (
        "no wire assessed"
        if tn["wire"] is None
        else f"largest damage {tn['wire_damage']:.3g} per cycle (wire {tn['wire']})"
    )
    if not tn["cycle"]:
        return [
            f"tension-only practice (T–N): no tension cycle: the strand's tension at midspan "
            f"stays at {1e-3 * tn['mean']:.4g} kN within {tn['range']:.3g} N (under "
            f"{100 * TENSION_CYCLE_SHARE:g} %), so a T–N check sees no damage; the wire-level "
            f"model: {wire}"
        ]
    api = (
        "API RP 2SK spiral strand (N R^5.05 = 10^(3.25 − 3.43 L_m), R = ΔT/MBS): damage "
        f"{tn['api']:.3g} per cycle"
        if tn["api"] is not None
        else "API RP 2SK: not checked ([fatigue] breaking_strength not given)"
    )
    return [
        f"tension-only practice (T–N) on the strand's tension at midspan (mean "
        f"{1e-3 * tn['mean']:.4g} kN, largest range {1e-3 * tn['range']:.4g} kN, rainflow of the "
        "history repeating):",
        f"  DNV-OS-E301 spiral rope (n = 1.7e17 s^-4.8, s = ΔT over the metallic area "
        f"{1e6 * tn['area']:.1f} mm²): damage {tn['dnv']:.3g} per cycle",
        f"  {api}",
        f"  wire-level model on the same history: {wire}",
    ]


def summary_text(
    pairs, sections, cable: Cable, curves: list, settings: FatigueSettings, r: FatigueReport
) -> str:
    """The report's summary: cycles, stuck pairs, per zone the worst crossings, hot spots and
    first wires to fail; the T–N check; P–S."""
    st, c, cycles = pairs.static, r.crossings, r.cycles
    lines = [
        f"load cycles of one steady repetition of the cycle (rainflow on the cycle load closed "
        f"on itself, ASTM E1049): {len(cycles)} counted, ranges "
        + ", ".join(f"{x:.4g}×{n:g}" for x, n in zip(cycles.range, cycles.count, strict=True)),
        f"stuck throughout (Coulomb slide below {1e9 * settings.stuck_slip:g} nm): "
        + ", ".join(
            f"{int(np.sum(c['stuck'] & (st['interface'] == i)))} of "
            f"{int(np.sum(st['interface'] == i))} pairs at {i}|{i + 1}"
            for i in np.unique(st["interface"])
        ),
        "Miner damage with the S–N curves:",
        *_curve_lines(cable, curves),
    ]
    e_clamp, w_layers = r.elements["clamp"], r.wires["layer"]
    span = free_span(r.length, r.end_zone)
    for zone, on in zip(ZONES, (False, True), strict=True):
        mask_e = e_clamp == on
        if not on and (span is None or not mask_e.any()):
            lines.append(no_free_span(r.length, r.end_zone))
            continue
        if not mask_e.any():
            lines.append(f"{zone}: none: no element lies within {r.end_zone:.4g} m of an end")
            continue
        where = (
            f"z in [{span[0]:.4g}, {span[1]:.4g}] m"
            if not on
            else (f"within {r.end_zone:.4g} m of an end")
        )
        lines.append(f"{zone} ({where}):")
        lines += _zone_text(
            zone, pairs, sections, r, c["clamp"] == on, mask_e, np.ones(len(w_layers), bool)
        )
    lines += _tension_lines(r.tension_check)
    ps = r.poffenberger_swart
    if ps is not None and ps["holds"]:
        lines.append(
            f"Poffenberger–Swart at the clamp (x = {1e3 * ps['distance']:.0f} mm): "
            f"Y_b = {1e3 * ps['Y_b']:.3f} mm peak to peak, K = {1e-9 * ps['K']:.2f} MPa/mm "
            f"→ σ_a = {1e-6 * ps['sigma_a']:.2f} MPa; model (half the outer wires' largest range "
            f"at the clamp mouth) {1e-6 * ps['model']:.2f} MPa; ratio {ps['ratio']:.3f}"
        )
    elif ps is not None:
        lines.append(f"Poffenberger–Swart skipped: {ps['reason']}")
    return "\n".join(lines) + "\n"
