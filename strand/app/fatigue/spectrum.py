"""The fatigue spectrum of a sweep (``[fatigue] spectrum``): Miner's sum over its members.

A spectrum case runs its amplitudes as a sweep (``strand.app.sweep``). Each member's fatigue report
(``strand.app.fatigue.report``) holds the damage dᵢ of one steady repetition of the case's cycle at
amplitude i (its history, the tensioned state then the cycle, closed on itself and counted as
repeating: ``strand.fatigue.cycles.repeating_cycles``): per element (at its worst surface point),
per contact pair (the two wires' facing surfaces) and, on the strand's tension, by the T–N curves
of the mooring standards, so nᵢ steady cycles at amplitude i damage nᵢ dᵢ. The spectrum weights
them with the counts nᵢ (``strand.fatigue.spectrum.spectrum_damage``); no physics is computed
again:

* per element D = Σᵢ nᵢ dᵢ, and per wire and zone (free span, clamp zone) the largest, at its
  element (the sum per element first, then the largest: the damage of one place);
* per contact pair D = Σᵢ nᵢ dᵢ;
* the strand-level T–N damage Σᵢ nᵢ D_T,i (DNV-OS-E301; API RP 2SK with a breaking strength);

each with every amplitude's share nᵢ dᵢ / D. D is the damage in the period the counts are given
for (a year, the design life); 1/D such periods to failure. Where a layer has no S–N curve, D and
the shares are NaN ("not assessed"). ``spectrum.csv`` (per wire and zone),
``spectrum_crossings.csv`` (per pair) and ``spectrum.txt`` (``strand.app.fatigue.spectrum_text``)
go into the sweep's folder; what they hold: ``strand.app.fatigue.spectrum_findings``.
"""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import numpy as np
import numpy.typing as npt

from ...fatigue.spectrum import spectrum_damage
from ...fatigue.zones import ZONES, zone_names
from ..settings import Case
from .csv_table import assessment_columns, write_csv
from .findings import FatigueReport
from .spectrum_findings import (
    SpectrumCrossings,
    SpectrumElements,
    SpectrumReport,
    SpectrumTension,
    SpectrumWires,
)
from .spectrum_text import spectrum_text

__all__ = ["SpectrumError", "spectrum_report", "write_spectrum"]

Array = npt.NDArray[np.float64]
Names = npt.NDArray[np.character]  # strings (np.str_)


class SpectrumError(ValueError):
    """A sweep whose members cannot give the spectrum's damage (one line, naming the member)."""


def _members(case: Case, results: list, parameter: str) -> tuple[list[FatigueReport], Array, Array]:
    """The members' fatigue reports in the order of the sweep, and their counts (``SpectrumError``
    where one is missing, failed or stopped)."""
    counts = dict(case.fatigue.spectrum)
    sweep = list(case.load.sweep)
    reports = []
    for i, amplitude in enumerate(sweep):
        name = f"{parameter}_{amplitude:g}"
        result = results[i] if i < len(results) else None
        why = (
            "was not run"
            if result is None
            else "was interrupted"
            if result.interrupted
            else f"failed ({result.failure})"
            if result.failure
            else "has no fatigue report"
            if result.fatigue is None
            else ""
        )
        if why:
            raise SpectrumError(f"no spectrum: the member {name} {why}, so its damage is unknown")
        reports.append(result.fatigue)
    return reports, np.array(sweep), np.array([counts[a] for a in sweep])


def _wire_rows(elements: SpectrumElements, curves: Names) -> SpectrumWires:
    """Per wire and zone (where the zone has elements): its element of largest D (-1 where not
    assessed), its z, D and the shares there; ``curves`` the wires' S–N curve keys."""
    total, shares = elements.damage, elements.shares
    rows: dict[str, list] = {k: [] for k in ("wire", "layer", "zone", "curve", "element", "z")}
    rows |= {"damage": [], "shares": []}
    for w in np.unique(elements.wire):
        for zone, clamp in zip(ZONES, (False, True), strict=True):
            mine = np.flatnonzero((elements.wire == w) & (elements.clamp == clamp))
            if len(mine) == 0:
                continue
            d = total[mine]
            k = None if np.all(np.isnan(d)) else int(mine[np.nanargmax(d)])
            rows["wire"].append(int(w))
            rows["layer"].append(int(elements.layer[mine[0]]))
            rows["zone"].append(zone)
            rows["curve"].append(curves[w])
            rows["element"].append(-1 if k is None else k)
            rows["z"].append(np.nan if k is None else elements.z[k])
            rows["damage"].append(np.nan if k is None else total[k])
            rows["shares"].append(np.full(len(shares), np.nan) if k is None else shares[:, k])
    columns = {k: np.array(v) for k, v in rows.items() if k != "shares"}
    return SpectrumWires(
        **columns, shares=np.array(rows["shares"]).reshape(len(rows["wire"]), len(shares))
    )


def _tension(reports: list[FatigueReport], counts: Array) -> SpectrumTension:
    """The T–N sums: DNV-OS-E301's (with shares) and, where every member has it, API RP 2SK's;
    per member its largest tension range and mean (N), and whether it has a tension cycle."""
    checks = [r.tension_check for r in reports]
    dnv, dnv_shares = spectrum_damage(counts, [c.dnv for c in checks])
    api = None
    if all(c.api is not None for c in checks):
        api = float(spectrum_damage(counts, [c.api for c in checks])[0])
    return SpectrumTension(
        dnv=float(dnv),
        dnv_shares=dnv_shares,
        api=api,
        range=np.array([c.range for c in checks]),
        mean=np.array([c.mean for c in checks]),
        cycle=np.array([c.cycle for c in checks]),
    )


def spectrum_report(case: Case, results: list, parameter: str, unit: str) -> SpectrumReport:
    """Miner's sum of ``case``'s spectrum over its sweep members' fatigue reports (``results``:
    the members' ``RunResult``, in the order of ``[load] sweep``), with its text."""
    reports, amplitudes, counts = _members(case, results, parameter)
    first = reports[0]
    e_total, e_shares = spectrum_damage(counts, [r.elements.damage for r in reports])
    c_total, c_shares = spectrum_damage(counts, [r.crossings.damage for r in reports])
    elements = SpectrumElements(
        wire=first.elements.wire,
        layer=first.elements.layer,
        z=first.elements.z,
        clamp=first.elements.clamp,
        damage=e_total,
        shares=e_shares,
    )
    crossings = SpectrumCrossings(
        interface=first.crossings.interface,
        wire_a=first.crossings.wire_a,
        wire_b=first.crossings.wire_b,
        z=first.crossings.z,
        clamp=first.crossings.clamp,
        line=first.crossings.line,
        damage=c_total,
        shares=c_shares,
    )
    report = SpectrumReport(
        parameter=parameter,
        unit=unit,
        amplitudes=amplitudes,
        counts=counts,
        names=[f"{parameter}_{a:g}" for a in amplitudes],
        elements=elements,
        crossings=crossings,
        wires=_wire_rows(elements, first.wires.curve),
        tension=_tension(reports, counts),
        end_zone=first.end_zone,
        length=first.length,
        mean_stress=case.fatigue.mean_stress,
        design_factor=case.fatigue.design_fatigue_factor,
    )
    return replace(report, text=spectrum_text(report))


def _share_columns(report: SpectrumReport, shares: Array) -> dict[str, Array]:
    return {f"share_{name}": shares[i] for i, name in enumerate(report.names)}


def write_spectrum(folder: Path, case: Case, results: list, parameter: str, unit: str) -> str:
    """Write ``spectrum.csv``, ``spectrum_crossings.csv``, ``spectrum.txt`` and (``[output]
    plots``) ``spectrum.png`` (``strand.app.fatigue.spectrum_figure``) into the sweep's
    ``folder``; return the text (only ``spectrum.txt``, with the reason, where a member cannot
    give its damage)."""
    folder = Path(folder)
    try:
        report = spectrum_report(case, results, parameter, unit)
    except SpectrumError as e:
        (folder / "spectrum.txt").write_text(f"{e}\n")
        return f"{e}\n"
    wires, crossings = report.wires, report.crossings
    with np.errstate(divide="ignore"):
        write_csv(
            folder / "spectrum.csv",
            {
                "wire": wires.wire,
                "layer": wires.layer,
                "zone": zone_names(wires.zone == ZONES[1]),
                "sn_curve": wires.curve,
                **assessment_columns(report.mean_stress, report.design_factor, len(wires.wire)),
                "element": wires.element,
                "z_m": wires.z,
                "damage": wires.damage,
                "periods_to_failure": 1 / wires.damage,
                **_share_columns(report, wires.shares.T),
            },
        )
        write_csv(
            folder / "spectrum_crossings.csv",
            {
                "pair": np.arange(len(crossings.z)),
                "interface": crossings.interface,
                "wire_a": crossings.wire_a,
                "wire_b": crossings.wire_b,
                "line": crossings.line.astype(int),
                "zone": zone_names(crossings.clamp),
                "z_m": crossings.z,
                "damage": crossings.damage,
                "periods_to_failure": 1 / crossings.damage,
                **_share_columns(report, crossings.shares),
            },
        )
    (folder / "spectrum.txt").write_text(report.text)
    if case.output.plots:
        from .spectrum_figure import spectrum_figure, spectrum_figure_data

        members = [r.fatigue for r in results]
        data = spectrum_figure_data(report, members, case.fatigue.breaking_strength)
        spectrum_figure(folder / "spectrum.png", data)
    return report.text
