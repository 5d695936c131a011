"""The fatigue report of a run: fretting at every contact pair, surface stresses of every wire,
cycle counting, Miner damage and Poffenberger–Swart's reference, from the run's histories.

``fatigue_report`` reads ``contact_pairs.h5`` and ``wire_sections.h5`` (written as the run went,
``strand.app.fatigue.recorders``), counts the cycles of one steady repetition of the run's cycle (each
history, the tensioned state then the cycle's steps, closed on itself and counted by rainflow:
``strand.fatigue.cycles.repeating_cycles``; the load's cycles bound the pairs' per-cycle windows)
and writes (damages and energies per cycle, ranges over the history):

* ``crossings.csv`` — per contact pair: interface, wires, z, its zone (free span or clamp zone,
  ``strand.fatigue.zones``), angle, whether it stayed stuck throughout (Coulomb slide below
  ``[fatigue] stuck_slip``), worst cycle's slip amplitude, friction force amplitude, peak and
  mean normal force, Hertz contact (semi-axes, peak pressure), largest tensile surface stress,
  Ruiz's F₁ and F₂, dissipated energy per cycle, Miner damage of the two wires' surfaces
  facing each other (NaN, "not assessed", where neither wire's material has an S–N curve);
* ``wire_stresses.csv`` — per element: its zone, the surface point of largest stress range (its
  angle ψ from the strand's outward radius), that range, its mean, the torsional shear range;
* ``wires.csv`` — per wire: its layer's S–N curve (or "not assessed"), largest stress range and
  where, Miner damage per cycle and the number of repetitions of the cycle to failure,
  over the whole wire and in the free span and the clamp zone apart (NaN where not assessed);
* ``fatigue.txt`` — per zone the five worst crossings, hot spots and first wires to fail; the
  strand-level T–N check of the mooring standards (``strand.fatigue.tn``) on the strand's tension
  history beside the wire-level damage; Poffenberger–Swart against the model at the clamp where
  its long-span assumption holds (``strand.fatigue.poffenberger``), else why not.

Per pair: ``strand.app.fatigue.crossings``; per element and wire:
``strand.app.fatigue.wire_stresses``; what the report holds: ``strand.app.fatigue.findings``.
Units: SI in the computation; the CSV columns name theirs (µm, MPa where that reads better).
"""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import numpy as np

from ...analytical import poffenberger_swart
from ...cable.description import Cable
from ...fatigue.cycles import Cycles, repeating_cycles
from ...fatigue.poffenberger import span_check
from ...fatigue.zones import in_clamp_zone, zone_names
from ..history import History, read_history
from ..settings import FatigueSettings
from .crossings import crossing_results
from .csv_table import assessment_columns, write_csv
from .findings import ElementResults, FatigueReport, PoffenbergerSwartCheck
from .tension_check import tension_check
from .text import summary_text
from .wire_stresses import element_results, wire_results

#: ``FatigueReport`` (``strand.app.fatigue.findings``) is importable from here too
__all__ = ["fatigue_report", "ReportError"]


class ReportError(ValueError):
    """A results folder without what the report needs (one line, naming the file)."""


def _load_cycles(history: History) -> Cycles:
    load = history.values.get("load")
    cycles = repeating_cycles(load) if load is not None else None
    if cycles is None or len(cycles) == 0:
        raise ReportError("the history holds no load cycle yet: nothing to count")
    return cycles


def poffenberger_swart_check(
    sections: History,
    elements: ElementResults,
    cable: Cable,
    tension: float,
    direction,
    distance: float,
) -> PoffenbergerSwartCheck:
    """Poffenberger–Swart at the clamp z = 0, where its long-span assumption holds
    (``strand.fatigue.poffenberger.span_check``; else ``holds`` False and the ``reason``): Y_b
    the peak-to-peak displacement of the strand axis along ``direction`` at ``distance`` (m)
    from it over the history, K Y_b the outer wires' idealised amplitude, against half the
    model's largest outer-wire stress range over the clamp's first ``distance``/4 (the clamp
    mouth); ``tension`` in N."""
    static = sections.static
    span = float(static["core_z"].max() - static["core_z"].min())
    check = span_check(cable, tension, span, distance)
    if not check.holds:
        return PoffenbergerSwartCheck(
            holds=False, reason=check.reason, distance=distance, span=span
        )
    d = np.asarray(direction, float) / np.linalg.norm(direction)
    u = sections["core_u"] @ d  # (S, n_core)
    y = np.array([np.interp(distance, static["core_z"], row) for row in u])
    y_b = float(np.ptp(y))
    K = poffenberger_swart(cable, tension, distance)
    outer = len(cable.layers) - 1
    mouth = (static["layer"] == outer) & (static["z"] < distance / 4)
    model = 0.5 * float(elements.range[mouth].max())
    sigma_a = K * y_b
    return PoffenbergerSwartCheck(
        holds=True,
        K=K,
        y_b=y_b,
        sigma_a=sigma_a,
        model=model,
        ratio=model / sigma_a if sigma_a > 0 else np.nan,
        distance=distance,
        span=span,
        span_error=check.error,
    )


def fatigue_report(
    folder: str | Path,
    cable: Cable,
    tension: float,
    settings: FatigueSettings | None = None,
    direction=(1.0, 0.0, 0.0),
    clamp: bool = True,
    write: bool = True,
) -> FatigueReport:
    """Read the run's histories in ``folder``, compute the fatigue results and (``write``) put
    the CSV files and ``fatigue.txt`` there. ``clamp``: the set-up clamps the strand at z = 0
    (Poffenberger–Swart applies there)."""
    folder = Path(folder)
    settings = settings or FatigueSettings()
    for name in ("contact_pairs.h5", "wire_sections.h5"):
        if not (folder / name).is_file():
            raise ReportError(f"{folder / name}: not found; run with [fatigue] outputs = true")
    pairs = read_history(folder / "contact_pairs.h5")
    sections = read_history(folder / "wire_sections.h5")
    cycles = _load_cycles(sections)
    curves = settings.curves(cable)
    mean_stress = settings.mean_stress_corrections(cable)
    factor = settings.design_fatigue_factor
    length = float(sections.static["core_z"].max())
    end_zone = settings.end_zone_length(cable)
    crossings = crossing_results(
        pairs,
        sections,
        cable,
        curves,
        cycles,
        stuck_slip=settings.stuck_slip,
        clamp=in_clamp_zone(pairs.static["z"], length, end_zone),
        mean_stress=mean_stress,
        factor=factor,
    )
    elements = element_results(
        sections,
        settings.surface_points,
        curves,
        in_clamp_zone(sections.static["z"], length, end_zone),
        mean_stress,
        factor,
    )
    wires = wire_results(elements, curves)
    poffenberger = (
        poffenberger_swart_check(
            sections, elements, cable, tension, direction, settings.clamp_distance
        )
        if clamp
        else None
    )
    report = FatigueReport(
        cycles=cycles,
        crossings=crossings,
        elements=elements,
        wires=wires,
        tension_check=tension_check(sections, cable, settings.breaking_strength, wires, factor),
        poffenberger_swart=poffenberger,
        curves=curves,
        end_zone=end_zone,
        length=length,
        mean_stress=settings.mean_stress,
        design_factor=factor,
    )
    report = replace(report, text=summary_text(report, settings))
    if write:
        write_report(folder, pairs, sections, report)
    return report


def write_report(folder: Path, pairs: History, sections: History, report: FatigueReport) -> None:
    """The CSV files and ``fatigue.txt`` of ``report`` in ``folder``."""
    pair, crossings = pairs.static, report.crossings
    write_csv(
        folder / "crossings.csv",
        {
            "pair": np.arange(len(pair["z"])),
            "interface": pair["interface"],
            "wire_a": pair["wire_a"],
            "wire_b": pair["wire_b"],
            "line": pair["line"],
            "z_m": pair["z"],
            "zone": zone_names(crossings.clamp),
            "angle_deg": pair["angle"],
            "crossing_angle_deg": pair["crossing_angle"],
            "stuck_throughout": crossings.stuck.astype(int),
            "slip_amplitude_um": 1e6 * crossings.slip_amplitude,
            "displacement_amplitude_um": 1e6 * crossings.displacement_amplitude,
            "friction_amplitude_N": crossings.friction_amplitude,
            "peak_force_N": crossings.peak_force,
            "mean_force_N": crossings.mean_force,
            "hertz_a_um": 1e6 * crossings.semi_axis_a,
            "hertz_b_um": 1e6 * crossings.semi_axis_b,
            "peak_pressure_MPa": 1e-6 * crossings.peak_pressure,
            "surface_stress_MPa": 1e-6 * crossings.surface_stress,
            "ruiz_F1_J_m2": crossings.ruiz_f1,
            "ruiz_F2_MPa_J_m2": 1e-6 * crossings.ruiz_f2,
            "energy_J": crossings.energy,
            "damage": crossings.damage,
            "damage_assessed": crossings.assessed,
        },
        {"z_m": ".5f", "angle_deg": ".2f", "crossing_angle_deg": ".2f"},
    )
    element, elements = sections.static, report.elements
    write_csv(
        folder / "wire_stresses.csv",
        {
            "element": np.arange(len(element["z"])),
            "wire": element["wire"],
            "layer": element["layer"],
            "z_m": element["z"],
            "zone": zone_names(elements.clamp),
            "phi_deg": element["phi"],
            "psi_deg": elements.angle,
            "range_MPa": 1e-6 * elements.range,
            "mean_MPa": 1e-6 * elements.mean,
            "peak_MPa": 1e-6 * elements.peak,
            "shear_range_MPa": 1e-6 * elements.shear_range,
            "damage": elements.damage,
        },
        {"z_m": ".5f", "phi_deg": ".2f", "psi_deg": ".1f"},
    )
    wires = report.wires
    columns = {"wire": np.arange(len(wires.layer)), "layer": wires.layer, "sn_curve": wires.curve}
    columns |= assessment_columns(report.mean_stress, report.design_factor, len(wires.layer))
    for zone, results in (
        ("", wires.whole),
        ("_free_span", wires.free_span),
        ("_clamp_zone", wires.clamp_zone),
    ):
        columns |= {
            f"range{zone}_MPa": 1e-6 * results.range,
            f"z{zone}_m": results.z,
            f"psi{zone}_deg": results.angle,
            f"damage{zone}": results.damage,
            f"repetitions_to_failure{zone}": results.repetitions,
        }
    formats = {
        k: ".5f" if k.startswith("z") else ".1f" for k in columns if k.startswith(("z", "psi"))
    }
    write_csv(folder / "wires.csv", columns, formats)
    (folder / "fatigue.txt").write_text(report.text)
