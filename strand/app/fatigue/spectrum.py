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
``spectrum_crossings.csv`` (per pair) and ``spectrum.txt`` go into the sweep's folder.
"""

from __future__ import annotations

import csv
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import numpy.typing as npt

from ...fatigue.spectrum import spectrum_damage
from ...fatigue.tn import TENSION_CYCLE_SHARE
from ...fatigue.zones import ZONES, zone_names
from ..settings import Case
from .text import no_free_span

__all__ = ["SpectrumError", "SpectrumReport", "spectrum_report", "write_spectrum"]

Array = npt.NDArray[np.float64]


class SpectrumError(ValueError):
    """A sweep whose members cannot give the spectrum's damage (one line, naming the member)."""


@dataclass
class SpectrumReport:
    """Miner's sum of a spectrum: ``amplitudes`` and ``counts`` (A,), the members' ``names``;
    per element and per pair the total damage D and the shares (A, ...) of the amplitudes; per
    wire and zone a row (``wires``: columns by name); the T–N sums (``tension``)."""

    parameter: str
    unit: str
    amplitudes: Array
    counts: Array
    names: list[str]
    elements: dict[str, Array]
    crossings: dict[str, Array]
    wires: dict[str, Array]
    tension: dict
    end_zone: float
    length: float = 0.0  # m, the span
    text: str = ""


def _members(case: Case, results: list, parameter: str):
    """The members' fatigue reports in the order of the sweep, and their counts (``SpectrumError``
    where one is missing, failed or stopped)."""
    counts = dict(case.fatigue.spectrum)
    sweep = list(case.load.sweep)
    reports = []
    for i, amplitude in enumerate(sweep):
        name = f"{parameter}_{amplitude:g}"
        r = results[i] if i < len(results) else None
        why = (
            "was not run"
            if r is None
            else "was interrupted"
            if r.interrupted
            else f"failed ({r.failure})"
            if r.failure
            else "has no fatigue report"
            if r.fatigue is None
            else ""
        )
        if why:
            raise SpectrumError(f"no spectrum: the member {name} {why}, so its damage is unknown")
        reports.append(r.fatigue)
    return reports, np.array(sweep), np.array([counts[a] for a in sweep])


def _wire_rows(e: dict, curves: Array) -> dict[str, Array]:
    """Per wire and zone (where the zone has elements): its element of largest D (-1 where not
    assessed), its z, D and the shares there; ``e`` the elements' total ``damage`` and
    ``shares``, ``curves`` the wires' S–N curve keys."""
    total, shares = e["damage"], e["shares"]
    rows: dict[str, list] = {k: [] for k in ("wire", "layer", "zone", "curve", "element", "z")}
    rows |= {"damage": [], "shares": []}
    for w in np.unique(e["wire"]):
        for zone, clamp in zip(ZONES, (False, True), strict=True):
            mine = np.flatnonzero((e["wire"] == w) & (e["clamp"] == clamp))
            if len(mine) == 0:
                continue
            d = total[mine]
            k = None if np.all(np.isnan(d)) else int(mine[np.nanargmax(d)])
            layer = int(e["layer"][mine[0]])
            rows["wire"].append(int(w))
            rows["layer"].append(layer)
            rows["zone"].append(zone)
            rows["curve"].append(curves[w])
            rows["element"].append(-1 if k is None else k)
            rows["z"].append(np.nan if k is None else e["z"][k])
            rows["damage"].append(np.nan if k is None else total[k])
            rows["shares"].append(np.full(len(shares), np.nan) if k is None else shares[:, k])
    out = {k: np.array(v) for k, v in rows.items()}
    out["shares"] = np.array(rows["shares"]).reshape(len(rows["wire"]), len(shares))
    return out


def _tension(reports: list, counts: Array) -> dict:
    """The T–N sums: DNV-OS-E301's (with shares) and, where every member has it, API RP 2SK's;
    per member its largest tension range and mean (N), and whether it has a tension cycle."""
    checks = [r.tension_check for r in reports]
    dnv, dnv_shares = spectrum_damage(counts, [c["dnv"] for c in checks])
    api = None
    if all(c["api"] is not None for c in checks):
        api = float(spectrum_damage(counts, [c["api"] for c in checks])[0])
    return {
        "dnv": float(dnv),
        "dnv_shares": dnv_shares,
        "api": api,
        "range": np.array([c["range"] for c in checks]),
        "mean": np.array([c["mean"] for c in checks]),
        "cycle": np.array([c["cycle"] for c in checks]),
    }


def spectrum_report(case: Case, results: list, parameter: str, unit: str) -> SpectrumReport:
    """Miner's sum of ``case``'s spectrum over its sweep members' fatigue reports (``results``:
    the members' ``RunResult``, in the order of ``[load] sweep``), with its text."""
    reports, amplitudes, counts = _members(case, results, parameter)
    first = reports[0]
    e_total, e_shares = spectrum_damage(counts, [r.elements["damage"] for r in reports])
    c_total, c_shares = spectrum_damage(counts, [r.crossings["damage"] for r in reports])
    elements = {k: first.elements[k] for k in ("wire", "layer", "z", "clamp")}
    elements |= {"damage": e_total, "shares": e_shares}
    crossings = {
        k: first.crossings[k] for k in ("interface", "wire_a", "wire_b", "z", "clamp", "line")
    }
    crossings |= {"damage": c_total, "shares": c_shares}
    wires = _wire_rows(elements, first.wires["curve"])
    names = [f"{parameter}_{a:g}" for a in amplitudes]
    report = SpectrumReport(
        parameter,
        unit,
        amplitudes,
        counts,
        names,
        elements,
        crossings,
        wires,
        _tension(reports, counts),
        first.end_zone,
        first.length,
    )
    report.text = spectrum_text(report)
    return report


def _shares(r: SpectrumReport, shares: Array) -> str:
    if np.all(np.isnan(shares)):
        return "no damage"
    return ", ".join(
        f"{a:g} {r.unit} {100 * s:.0f} %" for a, s in zip(r.amplitudes, shares, strict=True)
    )


def _periods(d: float) -> str:
    return "not assessed" if np.isnan(d) else "inf" if d == 0 else f"{1 / d:.3g}"


def _zone_lines(r: SpectrumReport, zone: str) -> list[str]:
    """Per layer its worst wire, and the five worst contact pairs, of one zone."""
    w, c = r.wires, r.crossings
    lines = [" per layer, its worst wire:"]
    for layer in np.unique(w["layer"]):
        mine = np.flatnonzero((w["layer"] == layer) & (w["zone"] == zone))
        if len(mine) == 0:
            continue
        if np.all(np.isnan(w["damage"][mine])):
            lines.append(f"  layer {layer}: not assessed (no S–N curve for its wires)")
            continue
        k = mine[np.nanargmax(w["damage"][mine])]
        lines.append(
            f"  layer {layer}: wire {w['wire'][k]}, D = {w['damage'][k]:.3g} "
            f"({_periods(w['damage'][k])} periods) at z = {w['z'][k]:.4f} m; "
            f"{_shares(r, w['shares'][k])}"
        )
    clamp = zone == ZONES[1]
    d = np.where(c["clamp"] == clamp, c["damage"], np.nan)
    worst = [k for k in np.argsort(-np.nan_to_num(d, nan=-1.0))[:5] if not np.isnan(d[k])]
    if worst:
        lines.append(" five worst contact pairs (their wires' facing surfaces):")
    elif np.any(c["clamp"] == clamp):
        lines.append(" contact pairs: not assessed (no S–N curve for their wires)")
    for k in worst:
        lines.append(
            f"  pair {k} ({c['interface'][k]}|{c['interface'][k] + 1}"
            f"{', line' if c['line'][k] else ''}) z = {c['z'][k]:.4f} m: D = "
            f"{c['damage'][k]:.3g}; {_shares(r, c['shares'][:, k])}"
        )
    return lines


def _tension_lines(r: SpectrumReport) -> list[str]:
    t, w = r.tension, r.wires
    ranges = ", ".join(
        f"{a:g} {r.unit}: {1e-3 * dt:.4g} kN"
        for a, dt in zip(r.amplitudes, t["range"], strict=True)
    )
    lines = [
        f"strand-level T–N on the strand's tension at midspan (mean {1e-3 * t['mean'][0]:.4g} "
        f"kN; largest range per amplitude {ranges}):"
    ]
    if not t["cycle"].any():
        lines.append(
            f"  no tension cycle at any amplitude (ranges under "
            f"{100 * TENSION_CYCLE_SHARE:g} % of the mean): T–N sees next to no damage"
        )
    lines.append(f"  DNV-OS-E301 spiral rope: D = {t['dnv']:.3g}; {_shares(r, t['dnv_shares'])}")
    lines.append(
        "  API RP 2SK spiral strand: not checked ([fatigue] breaking_strength not given)"
        if t["api"] is None
        else f"  API RP 2SK spiral strand: D = {t['api']:.3g}"
    )
    if np.all(np.isnan(w["damage"])):
        lines.append("  wire-level model, same spectrum: no wire assessed")
    else:
        k = int(np.nanargmax(w["damage"]))
        lines.append(
            f"  wire-level model, same spectrum: largest D = {w['damage'][k]:.3g} (wire "
            f"{w['wire'][k]}, {w['zone'][k]})"
        )
    return lines


def spectrum_text(r: SpectrumReport) -> str:
    """``spectrum.txt``: the spectrum, per zone each layer's worst wire and the worst pairs,
    the T–N sums beside the wire-level model's."""
    lines = [
        f"fatigue spectrum of {r.parameter}: Miner's D = Σ n_i d_i, n_i the cycles in the "
        "spectrum's period, d_i the damage per cycle of the member at amplitude i (its fatigue "
        "report: one steady repetition of the cycle, its history closed on itself); D is per that "
        "period, 1/D periods to failure",
        f"  amplitude ({r.unit})  cycles n_i  member",
        *(
            f"  {a:>13g}  {n:>10.4g}  {m}"
            for a, n, m in zip(r.amplitudes, r.counts, r.names, strict=True)
        ),
    ]
    curves = sorted(
        {(int(la), str(cu)) for la, cu in zip(r.wires["layer"], r.wires["curve"], strict=True)}
    )
    lines.append("S–N curves: " + ", ".join(f"layer {la} {cu}" for la, cu in curves))
    for zone in ZONES:
        where = "" if zone == ZONES[0] else f" (within {r.end_zone:.3g} m of an end)"
        if not np.any(r.wires["zone"] == zone):
            lines.append(
                no_free_span(r.length, r.end_zone)
                if zone == ZONES[0]
                else f"{zone}{where}: none: no element lies within it"
            )
            continue
        lines += [f"{zone}{where}:", *_zone_lines(r, zone)]
    return "\n".join(lines + _tension_lines(r)) + "\n"


def _write_csv(path: Path, columns: dict[str, npt.ArrayLike]) -> None:
    arrays = [np.asarray(v) for v in columns.values()]
    with open(path, "w", newline="") as f:
        writer = csv.writer(f)
        writer.writerow(list(columns))
        for row in zip(*arrays, strict=True):
            writer.writerow([v if isinstance(v, str) else format(v, ".6g") for v in row])


def _share_columns(r: SpectrumReport, shares: Array) -> dict[str, Array]:
    return {f"share_{name}": shares[i] for i, name in enumerate(r.names)}


def write_spectrum(folder: Path, case: Case, results: list, parameter: str, unit: str) -> str:
    """Write ``spectrum.csv``, ``spectrum_crossings.csv`` and ``spectrum.txt`` into the sweep's
    ``folder``; return the text (only ``spectrum.txt``, with the reason, where a member cannot
    give its damage)."""
    folder = Path(folder)
    try:
        r = spectrum_report(case, results, parameter, unit)
    except SpectrumError as e:
        (folder / "spectrum.txt").write_text(f"{e}\n")
        return f"{e}\n"
    w, c = r.wires, r.crossings
    with np.errstate(divide="ignore"):
        _write_csv(
            folder / "spectrum.csv",
            {
                "wire": w["wire"],
                "layer": w["layer"],
                "zone": zone_names(w["zone"] == ZONES[1]),
                "sn_curve": w["curve"],
                "element": w["element"],
                "z_m": w["z"],
                "damage": w["damage"],
                "periods_to_failure": 1 / w["damage"],
                **_share_columns(r, w["shares"].T),
            },
        )
        _write_csv(
            folder / "spectrum_crossings.csv",
            {
                "pair": np.arange(len(c["z"])),
                "interface": c["interface"],
                "wire_a": c["wire_a"],
                "wire_b": c["wire_b"],
                "line": c["line"].astype(int),
                "zone": zone_names(c["clamp"]),
                "z_m": c["z"],
                "damage": c["damage"],
                "periods_to_failure": 1 / c["damage"],
                **_share_columns(r, c["shares"]),
            },
        )
    (folder / "spectrum.txt").write_text(r.text)
    return r.text
