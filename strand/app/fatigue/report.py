"""The fatigue report of a run: fretting at every contact pair, surface stresses of every wire,
cycle counting, Miner damage and Poffenberger–Swart's reference, from the run's histories.

``fatigue_report`` reads ``contact_pairs.h5`` and ``wire_sections.h5`` (written as the run went,
``strand.app.recorders``), counts the cycles of one steady repetition of the run's cycle (each
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

Units: SI in the computation; the CSV columns name theirs (µm, MPa where that reads better).
"""

from __future__ import annotations

import csv
from pathlib import Path

import numpy as np
import numpy.typing as npt

from ...analytical import poffenberger_swart
from ...cable.description import Cable
from ...contact.hertz import contact_ellipse, line_contact
from ...fatigue.cycles import Cycles, cycle_steps, repeating_cycles
from ...fatigue.fretting import crossing_cycles, ruiz_parameters, stuck_throughout
from ...fatigue.poffenberger import span_check
from ...fatigue.sn import SN_CURVES, SNCurve, miner_damage
from ...fatigue.stress import shear_stress, surface_stress
from ...fatigue.zones import in_clamp_zone, zone_names
from ..history import History, read_history
from ..settings import FatigueSettings
from .findings import FatigueReport
from .tension_check import tension_check
from .text import summary_text

#: ``FatigueReport`` (``strand.app.fatigue.findings``) is importable from here too
__all__ = ["fatigue_report", "ReportError"]

Array = npt.NDArray[np.float64]


class ReportError(ValueError):
    """A results folder without what the report needs (one line, naming the file)."""


def _surface_angles(n: int) -> Array:
    return 2 * np.pi * np.arange(n) / n


def _stress_at(sections: History, cells, angle) -> Array:
    """σ (S, P) of elements ``cells`` (P,) at their surface angles ``angle`` (P,), rad."""
    N, m1, m2 = (sections[k][:, cells] for k in ("axial", "m1", "m2"))
    return surface_stress(N, m1, m2, sections.static["diameter"][cells], angle)


def _pair_cells_and_angles(pairs: History, sections: History):
    """The element of each pair's node on wire a and on wire b (the first whose midpoint lies
    above the pair's z, or the wire's last), and the surface angle ψ (rad) facing the other wire:
    the strand's pairs touch along its radius, so ψ = 0 (outward) on the inner wire a and ψ = π
    (towards the core) on the outer wire b."""
    s, p = sections.static, pairs.static
    out = []
    for wire, psi in ((p["wire_a"], 0.0), (p["wire_b"], np.pi)):
        cells = np.empty(len(wire), dtype=np.int64)
        for w in np.unique(wire):
            mine = np.flatnonzero(s["wire"] == w)
            sel = np.flatnonzero(wire == w)
            k = np.clip(np.searchsorted(s["z"][mine], p["z"][sel]), 0, len(mine) - 1)
            cells[sel] = mine[k]
        out.append((cells, np.full(len(wire), psi)))
    return out


def _write_csv(path: Path, columns: dict[str, npt.ArrayLike], formats: dict[str, str]) -> None:
    names = list(columns)
    arrays = [np.asarray(columns[n]) for n in names]
    kinds = [
        "s" if a.dtype.kind in "US" else formats.get(n, "g")
        for n, a in zip(names, arrays, strict=True)
    ]
    with open(path, "w", newline="") as f:
        writer = csv.writer(f)
        writer.writerow(names)
        for row in zip(*arrays, strict=True):
            writer.writerow([format(v, k) for k, v in zip(kinds, row, strict=True)])


def _load_cycles(history: History) -> Cycles:
    load = history.values.get("load")
    cycles = repeating_cycles(load) if load is not None else None
    if cycles is None or len(cycles) == 0:
        raise ReportError("the history holds no load cycle yet: nothing to count")
    return cycles


def _curve_key(curve: SNCurve | None) -> str:
    """The ``SN_CURVES`` key of ``curve`` ("custom" for a case file's, "not assessed" for None)."""
    if curve is None:
        return "not assessed"
    return next((k for k, c in SN_CURVES.items() if c == curve), "custom")


def _damage(series: Array, curve: SNCurve | None) -> float:
    """Miner damage of one repetition of a repeating stress history, NaN where no curve
    applies."""
    if curve is None:
        return np.nan
    c = repeating_cycles(series)
    return miner_damage(c.range, c.count, curve)


def crossing_results(
    pairs: History, sections: History, cable: Cable, curves: list, cycles: Cycles, stuck_slip: float
) -> dict[str, Array]:
    """Per pair: the worst counted cycle's fretting results, Hertz contact, Ruiz's parameters,
    whether it stayed stuck throughout (``stuck_slip``, m) and the Miner damage of the wires'
    facing surfaces under their layers' ``curves`` (NaN where neither has one)."""
    st = pairs.static
    cc = crossing_cycles(
        cycles, pairs["force"], pairs["friction"], pairs["slip"], pairs["sliding"], pairs["work"]
    )
    wires = [lay.wire for lay in cable.layers]
    inner, outer = st["interface"], st["interface"] + 1
    E_a, nu_a = (np.array([getattr(w, k) for w in wires])[inner] for k in ("E", "nu"))
    E_b, nu_b = (np.array([getattr(w, k) for w in wires])[outer] for k in ("E", "nu"))
    line = st["line"].astype(bool)
    beta = np.radians(st["crossing_angle"])
    # Hertz at every cycle's peak force: (C, P)
    a, b, p0 = contact_ellipse(
        st["radius_a"], st["radius_b"], beta, E_a, nu_a, E_b, nu_b, force=cc.peak_force
    )
    length = st["tributary"]
    q = np.divide(cc.peak_force, length, out=np.zeros_like(cc.peak_force), where=length > 0)
    half, p0_line = line_contact(st["radius_a"], st["radius_b"], E_a, nu_a, E_b, nu_b, q)
    a = np.where(line, half, a)  # line: the half-width across the line, and the length along it
    b = np.where(line, 0.5 * length, b)
    p0 = np.where(line, p0_line, p0)
    area = np.where(line, 2 * half * length, np.pi * a * b)
    (cells_a, psi_a), (cells_b, psi_b) = _pair_cells_and_angles(pairs, sections)
    sigma_a = _stress_at(sections, cells_a, psi_a)  # (S, P)
    sigma_b = _stress_at(sections, cells_b, psi_b)
    sigma = np.maximum(sigma_a, sigma_b)
    sigma_peak = np.array(
        [
            sigma[cycle_steps(i, j, len(sigma))].max(axis=0)
            for i, j in zip(cycles.start, cycles.end, strict=True)
        ]
    )
    f1, f2 = ruiz_parameters(cc.friction_amplitude, area, cc.slip_amplitude, sigma_peak)
    worst = np.argmax(f2 if np.any(f2 > 0) else cc.slip_amplitude, axis=0)  # (P,)
    pick = lambda x: np.take_along_axis(x, worst[None, :], axis=0)[0]  # noqa: E731
    damage = np.full(len(line), np.nan)
    for k in range(len(line)):
        sides = [_damage(s[:, k], curves[i]) for s, i in ((sigma_a, inner[k]), (sigma_b, outer[k]))]
        if not np.all(np.isnan(sides)):
            damage[k] = np.nanmax(sides)
    has = np.array([c is not None for c in curves])
    assessed = np.select(
        [has[inner] & has[outer], has[inner], has[outer]],
        ["both", "inner", "outer"],
        "not assessed",
    )
    return {
        "slip_amplitude": pick(cc.slip_amplitude),
        "displacement_amplitude": pick(cc.displacement_amplitude),
        "friction_amplitude": pick(cc.friction_amplitude),
        "peak_force": pick(cc.peak_force),
        "mean_force": pick(cc.mean_force),
        "semi_axis_a": pick(a),
        "semi_axis_b": pick(b),
        "peak_pressure": pick(p0),
        "surface_stress": pick(sigma_peak),
        "ruiz_f1": pick(f1),
        "ruiz_f2": pick(f2),
        "energy": cc.energy.sum(axis=0),
        "damage": damage,
        "assessed": assessed,
        "stuck": stuck_throughout(pairs["sliding"], stuck_slip),
    }


def element_results(sections: History, n_points: int, curves: list) -> dict[str, Array]:
    """Per element: the surface point of largest stress range over the history, its range,
    mean and peak, the torsional shear range, and the Miner damage per cycle at the worst point
    of the element (every point's stress history repeating, under its layer's curve in
    ``curves``; NaN where the layer has none)."""
    st = sections.static
    psi = _surface_angles(n_points)
    N, m1, m2 = (sections[k][..., None] for k in ("axial", "m1", "m2"))
    sigma = surface_stress(N, m1, m2, st["diameter"][:, None], psi)  # (S, E, n_points)
    hi, lo = sigma.max(axis=0), sigma.min(axis=0)  # (E, n_points)
    ranges = hi - lo
    worst = np.argmax(ranges, axis=1)
    rows = np.arange(len(worst))
    tau = shear_stress(sections["torque"], st["diameter"])
    damage = np.full(len(worst), np.nan)
    for e in rows:
        curve = curves[st["layer"][e]]
        if curve is not None:
            damage[e] = max(_damage(sigma[:, e, k], curve) for k in range(n_points))
    return {
        "angle": np.degrees(psi[worst]),
        "range": ranges[rows, worst],
        "mean": 0.5 * (hi + lo)[rows, worst],
        "peak": hi[rows, worst],
        "shear_range": np.ptp(tau, axis=0),
        "damage": damage,
    }


def _worst_of(elements: dict[str, Array], z: Array, mine: Array) -> tuple:
    """Largest range, its z and angle, and the largest damage (NaN: not assessed, or no
    element) over the elements ``mine``."""
    if len(mine) == 0:
        return np.nan, np.nan, np.nan, np.nan
    k = mine[np.argmax(elements["range"][mine])]
    d = elements["damage"][mine]
    return (
        elements["range"][k],
        z[k],
        elements["angle"][k],
        (np.nan if np.all(np.isnan(d)) else np.nanmax(d)),
    )


def _repetitions(damage: Array) -> Array:
    """Repetitions of the cycle to failure 1/D: inf where D = 0, NaN where not assessed."""
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(damage > 0, 1 / damage, np.where(np.isnan(damage), np.nan, np.inf))


def wire_results(sections: History, elements: dict[str, Array], clamp: Array, curves: list):
    """Per wire: its layer and curve key; over the whole wire and in the free span and the
    clamp zone (``clamp``: the elements' mask) apart: the largest stress range, its element's z
    and angle, the Miner damage per cycle and the repetitions to failure."""
    st = sections.static
    n_wires = int(st["wire"].max()) + 1
    out: dict[str, Array] = {"layer": np.zeros(n_wires, int)}
    masks = {"": np.ones_like(clamp), "_free": ~clamp, "_clamp": clamp}
    for suffix in masks:
        for k in ("range", "z", "angle", "damage"):
            out[k + suffix] = np.full(n_wires, np.nan)
    for w in range(n_wires):
        on = st["wire"] == w
        out["layer"][w] = st["layer"][np.flatnonzero(on)[0]]
        for suffix, mask in masks.items():
            values = _worst_of(elements, st["z"], np.flatnonzero(on & mask))
            for k, v in zip(("range", "z", "angle", "damage"), values, strict=True):
                out[k + suffix][w] = v
    for suffix in masks:
        out["repetitions" + suffix] = _repetitions(out["damage" + suffix])
    out["curve"] = np.array([_curve_key(curves[i]) for i in out["layer"]])
    return out


def poffenberger_swart_check(
    sections: History,
    elements: dict[str, Array],
    cable: Cable,
    tension: float,
    direction,
    distance: float,
) -> dict:
    """Poffenberger–Swart at the clamp z = 0, where its long-span assumption holds
    (``strand.fatigue.poffenberger.span_check``; else ``holds`` False and the ``reason``): Y_b
    the peak-to-peak displacement of the strand axis along ``direction`` at ``distance`` from
    it over the history, K Y_b the outer wires' idealised amplitude, against half the model's
    largest outer-wire stress range over the clamp's first ``distance``/4 (the clamp mouth)."""
    st = sections.static
    span = float(st["core_z"].max() - st["core_z"].min())
    check = span_check(cable, tension, span, distance)
    if not check.holds:
        return {"holds": False, "reason": check.reason, "distance": distance, "span": span}
    d = np.asarray(direction, float) / np.linalg.norm(direction)
    u = sections["core_u"] @ d  # (S, n_core)
    y = np.array([np.interp(distance, st["core_z"], row) for row in u])
    y_b = float(np.ptp(y))
    K = poffenberger_swart(cable, tension, distance)
    outer = len(cable.layers) - 1
    mouth = (st["layer"] == outer) & (st["z"] < distance / 4)
    model = 0.5 * float(elements["range"][mouth].max())
    ref = K * y_b
    return {
        "holds": True,
        "K": K,
        "Y_b": y_b,
        "sigma_a": ref,
        "model": model,
        "ratio": model / ref if ref > 0 else np.nan,
        "distance": distance,
        "span": span,
        "span_error": check.error,
    }


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
    length = float(sections.static["core_z"].max())
    end_zone = settings.end_zone_length(cable)
    crossings = crossing_results(pairs, sections, cable, curves, cycles, settings.stuck_slip)
    crossings["clamp"] = in_clamp_zone(pairs.static["z"], length, end_zone)
    crossings["line"] = pairs.static["line"].astype(bool)
    crossings |= {k: np.asarray(pairs.static[k]) for k in ("interface", "wire_a", "wire_b", "z")}
    elements = element_results(sections, settings.surface_points, curves)
    elements["clamp"] = in_clamp_zone(sections.static["z"], length, end_zone)
    elements |= {k: np.asarray(sections.static[k]) for k in ("layer", "wire", "z")}
    wires = wire_results(sections, elements, elements["clamp"], curves)
    tn = tension_check(sections, cable, settings.breaking_strength, wires)
    ps = (
        poffenberger_swart_check(
            sections, elements, cable, tension, direction, settings.clamp_distance
        )
        if clamp
        else None
    )
    report = FatigueReport(cycles, crossings, elements, wires, ps, "", end_zone, length, tn, curves)
    report.text = summary_text(pairs, sections, cable, curves, settings, report)
    if write:
        write_report(folder, pairs, sections, report)
    return report


def write_report(folder: Path, pairs: History, sections: History, r: FatigueReport) -> None:
    """The CSV files and ``fatigue.txt`` of ``r`` in ``folder``."""
    st, c = pairs.static, r.crossings
    _write_csv(
        folder / "crossings.csv",
        {
            "pair": np.arange(len(st["z"])),
            "interface": st["interface"],
            "wire_a": st["wire_a"],
            "wire_b": st["wire_b"],
            "line": st["line"],
            "z_m": st["z"],
            "zone": zone_names(c["clamp"]),
            "angle_deg": st["angle"],
            "crossing_angle_deg": st["crossing_angle"],
            "stuck_throughout": c["stuck"].astype(int),
            "slip_amplitude_um": 1e6 * c["slip_amplitude"],
            "displacement_amplitude_um": 1e6 * c["displacement_amplitude"],
            "friction_amplitude_N": c["friction_amplitude"],
            "peak_force_N": c["peak_force"],
            "mean_force_N": c["mean_force"],
            "hertz_a_um": 1e6 * c["semi_axis_a"],
            "hertz_b_um": 1e6 * c["semi_axis_b"],
            "peak_pressure_MPa": 1e-6 * c["peak_pressure"],
            "surface_stress_MPa": 1e-6 * c["surface_stress"],
            "ruiz_F1_J_m2": c["ruiz_f1"],
            "ruiz_F2_MPa_J_m2": 1e-6 * c["ruiz_f2"],
            "energy_J": c["energy"],
            "damage": c["damage"],
            "damage_assessed": c["assessed"],
        },
        {"z_m": ".5f", "angle_deg": ".2f", "crossing_angle_deg": ".2f"},
    )
    s, e = sections.static, r.elements
    _write_csv(
        folder / "wire_stresses.csv",
        {
            "element": np.arange(len(s["z"])),
            "wire": s["wire"],
            "layer": s["layer"],
            "z_m": s["z"],
            "zone": zone_names(e["clamp"]),
            "phi_deg": s["phi"],
            "psi_deg": e["angle"],
            "range_MPa": 1e-6 * e["range"],
            "mean_MPa": 1e-6 * e["mean"],
            "peak_MPa": 1e-6 * e["peak"],
            "shear_range_MPa": 1e-6 * e["shear_range"],
            "damage": e["damage"],
        },
        {"z_m": ".5f", "phi_deg": ".2f", "psi_deg": ".1f"},
    )
    w = r.wires
    columns = {"wire": np.arange(len(w["range"])), "layer": w["layer"], "sn_curve": w["curve"]}
    for suffix, zone in (("", ""), ("_free", "_free_span"), ("_clamp", "_clamp_zone")):
        columns |= {
            f"range{zone}_MPa": 1e-6 * w["range" + suffix],
            f"z{zone}_m": w["z" + suffix],
            f"psi{zone}_deg": w["angle" + suffix],
            f"damage{zone}": w["damage" + suffix],
            f"repetitions_to_failure{zone}": w["repetitions" + suffix],
        }
    formats = {
        k: ".5f" if k.startswith("z") else ".1f" for k in columns if k.startswith(("z", "psi"))
    }
    _write_csv(folder / "wires.csv", columns, formats)
    (folder / "fatigue.txt").write_text(r.text)
