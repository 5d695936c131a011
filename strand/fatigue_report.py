"""The fatigue report of a run: fretting at every contact pair, surface stresses of every wire,
cycle counting, Miner damage and Poffenberger–Swart's reference, from the run's histories.

``fatigue_report`` reads ``contact_pairs.h5`` and ``wire_sections.h5`` (written as the run went,
``strand.recorders``), counts the load cycles of the history (rainflow on the cycle load, the
tensioned state first) and writes:

* ``crossings.csv`` — per contact pair: interface, wires, z, angle, worst cycle's slip amplitude,
  friction force amplitude, peak and mean normal force, Hertz contact (semi-axes, peak pressure),
  largest tensile surface stress, Ruiz's F₁ and F₂, dissipated energy over the history, Miner
  damage of the two wires' surfaces facing each other;
* ``wire_stresses.csv`` — per element: the surface point of largest stress range (its angle ψ from
  the strand's outward radius), that range, its mean, the torsional shear range;
* ``wires.csv`` — per wire: largest stress range and where, Miner damage of the history and the
  number of repetitions of the history to failure (wires under the S–N curve);
* ``fatigue.txt`` — the ten worst crossings and hot spots, the first wires to fail, and
  Poffenberger–Swart against the model at the clamp.

Units: SI in the computation; the CSV columns name theirs (µm, MPa where that reads better).
"""

from __future__ import annotations

import csv
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import numpy.typing as npt

from .analytical import poffenberger_swart
from .cable import Cable
from .case import FatigueSettings
from .contact.hertz import contact_ellipse, line_contact
from .fatigue.cycles import Cycles, rainflow_cycles
from .fatigue.fretting import crossing_cycles, ruiz_parameters
from .fatigue.sn import SNCurve, miner_damage
from .fatigue.stress import shear_stress, surface_stress
from .history import History, read_history

__all__ = ["FatigueReport", "fatigue_report", "ReportError"]

Array = npt.NDArray[np.float64]


class ReportError(ValueError):
    """A results folder without what the report needs (one line, naming the file)."""


@dataclass
class FatigueReport:
    """What the report found (arrays per pair, per element, per wire) and its summary text."""

    cycles: Cycles
    crossings: dict[str, Array]
    elements: dict[str, Array]
    wires: dict[str, Array]
    poffenberger_swart: dict | None
    text: str


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
    with open(path, "w", newline="") as f:
        writer = csv.writer(f)
        writer.writerow(names)
        for row in zip(*arrays, strict=True):
            writer.writerow(
                [format(v, formats.get(n, "g")) for n, v in zip(names, row, strict=True)]
            )


def _load_cycles(history: History) -> Cycles:
    load = history.values.get("load")
    cycles = rainflow_cycles(load) if load is not None else None
    if cycles is None or len(cycles) == 0:
        raise ReportError("the history holds no load cycle yet: nothing to count")
    return cycles


def crossing_results(pairs: History, sections: History, cable: Cable, curve: SNCurve,
                     layers: list[int], cycles: Cycles) -> dict[str, Array]:  # fmt: skip
    """Per pair: the worst counted cycle's fretting results, Hertz contact, Ruiz's parameters
    and the Miner damage of the wires' facing surfaces (see the module docstring)."""
    st = pairs.static
    cc = crossing_cycles(cycles, pairs["force"], pairs["friction"], pairs["slip"],
                         pairs["sliding"], pairs["work"])  # fmt: skip
    wires = [lay.wire for lay in cable.layers]
    inner, outer = st["interface"], st["interface"] + 1
    E_a, nu_a = (np.array([getattr(w, k) for w in wires])[inner] for k in ("E", "nu"))
    E_b, nu_b = (np.array([getattr(w, k) for w in wires])[outer] for k in ("E", "nu"))
    line = st["line"].astype(bool)
    beta = np.radians(st["crossing_angle"])
    # Hertz at every cycle's peak force: (C, P)
    a, b, p0 = contact_ellipse(st["radius_a"], st["radius_b"], beta, E_a, nu_a, E_b, nu_b,
                               cc.peak_force)  # fmt: skip
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
    sigma_peak = np.array([sigma[i : j + 1].max(axis=0) for i, j in zip(cycles.start, cycles.end,
                                                                         strict=True)])  # fmt: skip
    f1, f2 = ruiz_parameters(cc.friction_amplitude, area, cc.slip_amplitude, sigma_peak)
    worst = np.argmax(f2 if np.any(f2 > 0) else cc.slip_amplitude, axis=0)  # (P,)
    pick = lambda x: np.take_along_axis(x, worst[None, :], axis=0)[0]  # noqa: E731
    layer_ok = np.isin(inner, layers), np.isin(outer, layers)
    damage = np.zeros(len(line))
    for s_series, ok in ((sigma_a, layer_ok[0]), (sigma_b, layer_ok[1])):
        for k in np.flatnonzero(ok):
            c = rainflow_cycles(s_series[:, k])
            damage[k] = max(damage[k], miner_damage(c.range, c.count, curve))
    return {
        "slip_amplitude": pick(cc.slip_amplitude),
        "displacement_amplitude": pick(cc.displacement_amplitude),
        "friction_amplitude": pick(cc.friction_amplitude),
        "peak_force": pick(cc.peak_force),
        "mean_force": pick(cc.mean_force),
        "semi_axis_a": pick(a), "semi_axis_b": pick(b), "peak_pressure": pick(p0),
        "surface_stress": pick(sigma_peak), "ruiz_f1": pick(f1), "ruiz_f2": pick(f2),
        "energy": cc.energy.sum(axis=0), "damage": damage,
    }  # fmt: skip


def element_results(sections: History, n_points: int, curve: SNCurve,
                    layers: list[int]) -> dict[str, Array]:  # fmt: skip
    """Per element: the surface point of largest stress range over the history, its range,
    mean and peak, the torsional shear range, and the Miner damage at the worst point of the
    element (rainflow on every point's stress history, elements of ``layers`` only)."""
    st = sections.static
    psi = _surface_angles(n_points)
    N, m1, m2 = (sections[k][..., None] for k in ("axial", "m1", "m2"))
    sigma = surface_stress(N, m1, m2, st["diameter"][:, None], psi)  # (S, E, n_points)
    hi, lo = sigma.max(axis=0), sigma.min(axis=0)  # (E, n_points)
    ranges = hi - lo
    worst = np.argmax(ranges, axis=1)
    rows = np.arange(len(worst))
    tau = shear_stress(sections["torque"], st["diameter"])
    damage = np.zeros(len(worst))
    for e in np.flatnonzero(np.isin(st["layer"], layers)):
        for k in range(n_points):
            c = rainflow_cycles(sigma[:, e, k])
            damage[e] = max(damage[e], miner_damage(c.range, c.count, curve))
    return {
        "angle": np.degrees(psi[worst]), "range": ranges[rows, worst],
        "mean": 0.5 * (hi + lo)[rows, worst], "peak": hi[rows, worst],
        "shear_range": np.ptp(tau, axis=0), "damage": damage,
    }  # fmt: skip


def wire_results(sections: History, elements: dict[str, Array], layers: list[int]):
    """Per wire: largest stress range, its element's z and angle, the Miner damage of the
    history and repetitions to failure (inf where the S–N curve does not apply or D = 0)."""
    st = sections.static
    n_wires = int(st["wire"].max()) + 1
    out = {k: np.zeros(n_wires) for k in ("layer", "range", "z", "angle", "damage", "repetitions")}
    for w in range(n_wires):
        mine = np.flatnonzero(st["wire"] == w)
        k = mine[np.argmax(elements["range"][mine])]
        out["layer"][w] = st["layer"][k]
        out["range"][w], out["z"][w], out["angle"][w] = (
            elements["range"][k],
            st["z"][k],
            elements["angle"][k],
        )
        out["damage"][w] = elements["damage"][mine].max()
    with np.errstate(divide="ignore"):
        out["repetitions"] = np.where(out["damage"] > 0, 1 / out["damage"], np.inf)
    return out


def poffenberger_swart_check(sections: History, elements: dict[str, Array], cable: Cable,
                             tension: float, direction, distance: float) -> dict:  # fmt: skip
    """Poffenberger–Swart at the clamp z = 0: Y_b the peak-to-peak displacement of the strand
    axis along ``direction`` at ``distance`` from it over the history, K Y_b the outer wires'
    idealised amplitude, against half the model's largest outer-wire stress range over the
    clamp's first ``distance``/4 (the clamp mouth)."""
    st = sections.static
    d = np.asarray(direction, float) / np.linalg.norm(direction)
    u = sections["core_u"] @ d  # (S, n_core)
    y = np.array([np.interp(distance, st["core_z"], row) for row in u])
    y_b = float(np.ptp(y))
    K = poffenberger_swart(cable, tension, distance)
    outer = len(cable.layers) - 1
    mouth = (st["layer"] == outer) & (st["z"] < distance / 4)
    model = 0.5 * float(elements["range"][mouth].max())
    ref = K * y_b
    return {"K": K, "Y_b": y_b, "sigma_a": ref, "model": model,
            "ratio": model / ref if ref > 0 else np.nan, "distance": distance}  # fmt: skip


def fatigue_report(
    folder: str | Path, cable: Cable, tension: float, settings: FatigueSettings | None = None,
    direction=(1.0, 0.0, 0.0), clamp: bool = True, write: bool = True,
) -> FatigueReport:  # fmt: skip
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
    curve, layers = settings.curve(), settings.layers(cable)
    crossings = crossing_results(pairs, sections, cable, curve, layers, cycles)
    elements = element_results(sections, settings.surface_points, curve, layers)
    wires = wire_results(sections, elements, layers)
    ps = (
        poffenberger_swart_check(sections, elements, cable, tension, direction,
                                 settings.clamp_distance)
        if clamp else None
    )  # fmt: skip
    text = summary_text(pairs, sections, cycles, crossings, elements, wires, ps, curve, layers)
    report = FatigueReport(cycles, crossings, elements, wires, ps, text)
    if write:
        write_report(folder, pairs, sections, report)
    return report


def write_report(folder: Path, pairs: History, sections: History, r: FatigueReport) -> None:
    """The CSV files and ``fatigue.txt`` of ``r`` in ``folder``."""
    st, c = pairs.static, r.crossings
    _write_csv(folder / "crossings.csv", {
        "pair": np.arange(len(st["z"])), "interface": st["interface"], "wire_a": st["wire_a"],
        "wire_b": st["wire_b"], "line": st["line"], "z_m": st["z"], "angle_deg": st["angle"],
        "crossing_angle_deg": st["crossing_angle"],
        "slip_amplitude_um": 1e6 * c["slip_amplitude"],
        "displacement_amplitude_um": 1e6 * c["displacement_amplitude"],
        "friction_amplitude_N": c["friction_amplitude"], "peak_force_N": c["peak_force"],
        "mean_force_N": c["mean_force"], "hertz_a_um": 1e6 * c["semi_axis_a"],
        "hertz_b_um": 1e6 * c["semi_axis_b"], "peak_pressure_MPa": 1e-6 * c["peak_pressure"],
        "surface_stress_MPa": 1e-6 * c["surface_stress"], "ruiz_F1_J_m2": c["ruiz_f1"],
        "ruiz_F2_MPa_J_m2": 1e-6 * c["ruiz_f2"], "energy_J": c["energy"], "damage": c["damage"],
    }, {"z_m": ".5f", "angle_deg": ".2f", "crossing_angle_deg": ".2f"})  # fmt: skip
    s, e = sections.static, r.elements
    _write_csv(folder / "wire_stresses.csv", {
        "element": np.arange(len(s["z"])), "wire": s["wire"], "layer": s["layer"], "z_m": s["z"],
        "phi_deg": s["phi"], "psi_deg": e["angle"], "range_MPa": 1e-6 * e["range"],
        "mean_MPa": 1e-6 * e["mean"], "peak_MPa": 1e-6 * e["peak"],
        "shear_range_MPa": 1e-6 * e["shear_range"], "damage": e["damage"],
    }, {"z_m": ".5f", "phi_deg": ".2f", "psi_deg": ".1f"})  # fmt: skip
    w = r.wires
    _write_csv(folder / "wires.csv", {
        "wire": np.arange(len(w["range"])), "layer": w["layer"].astype(int),
        "range_MPa": 1e-6 * w["range"], "z_m": w["z"], "psi_deg": w["angle"],
        "damage": w["damage"], "repetitions_to_failure": w["repetitions"],
    }, {"z_m": ".5f", "psi_deg": ".1f"})  # fmt: skip
    (folder / "fatigue.txt").write_text(r.text)


def _crossing_line(st, c, k) -> str:
    return (
        f"  {k:5d} {st['interface'][k]}|{st['interface'][k] + 1}"
        f"{'  line' if st['line'][k] else '      '}  {st['z'][k]:.4f}  {st['angle'][k]:8.1f}"
        f"  {1e6 * c['slip_amplitude'][k]:12.3f}  {c['peak_force'][k]:10.1f}"
        f"  {c['friction_amplitude'][k]:9.2f}  {1e-6 * c['peak_pressure'][k]:8.0f}"
        f"  {1e-6 * c['surface_stress'][k]:9.1f}  {1e-6 * c['ruiz_f2'][k]:12.4g}"
    )


def summary_text(pairs, sections, cycles, c, e, w, ps, curve, layers) -> str:
    """The report's summary: cycles, ten worst crossings, hot spots, first wires to fail, P–S."""
    st = pairs.static
    lines = [
        f"load cycles (rainflow on the cycle load, ASTM E1049): {len(cycles)} counted, ranges "
        + ", ".join(f"{r:.4g}×{n:g}" for r, n in zip(cycles.range, cycles.count, strict=True)),
    ]
    line = st["line"].astype(bool)
    point_order = [k for k in np.argsort(-c["ruiz_f2"]) if not line[k]][:10]
    line_order = [k for k in np.argsort(-c["ruiz_f2"]) if line[k]][:3]
    for title, order in (
        ("ten worst crossings by Ruiz's F2 = σ_T τ δ (Ruiz, Boddington & Chen 1984):", point_order),
        ("worst line contacts (per tributary length) by the same F2:", line_order),
    ):
        if not order:
            continue
        lines += [title, "  pair  interface  z (m)    angle (°)  slip amp (µm)  P peak (N)  "
                         "Q amp (N)  p0 (MPa)  σ_T (MPa)  F2 (MPa J/m²)"]  # fmt: skip
        lines += [_crossing_line(st, c, k) for k in order]
    s = sections.static
    lines.append("ten hot spots (largest surface stress range over the history):")
    lines.append("  element  wire  layer  z (m)    ψ (°)  range (MPa)  mean (MPa)")
    for k in np.argsort(-e["range"])[:10]:
        lines.append(
            f"  {k:7d} {s['wire'][k]:5d} {s['layer'][k]:6d}  {s['z'][k]:.4f} {e['angle'][k]:6.1f}"
            f"  {1e-6 * e['range'][k]:11.2f}  {1e-6 * e['mean'][k]:10.1f}"
        )
    lines.append(
        f"Miner damage with {curve.name} ({curve.source}) on layers {layers}; first wires to fail:"
    )
    order = [k for k in np.argsort(-w["damage"]) if w["damage"][k] > 0][:5]
    for k in order:
        lines.append(
            f"  wire {k:2d} (layer {int(w['layer'][k])}): damage {w['damage'][k]:.3g} per history, "
            f"{w['repetitions'][k]:.3g} repetitions; largest range {1e-6 * w['range'][k]:.2f} MPa "
            f"at z = {w['z'][k]:.4f} m, ψ = {w['angle'][k]:.0f}°"
        )
    if not order:
        lines.append("  none: no cycle damages the wires under the curve")
    if ps is not None:
        lines.append(
            f"Poffenberger–Swart at the clamp (x = {1e3 * ps['distance']:.0f} mm): "
            f"Y_b = {1e3 * ps['Y_b']:.3f} mm peak to peak, K = {1e-9 * ps['K']:.2f} MPa/mm "
            f"→ σ_a = {1e-6 * ps['sigma_a']:.2f} MPa; model (half the outer wires' largest range "
            f"at the clamp mouth) {1e-6 * ps['model']:.2f} MPa; ratio {ps['ratio']:.3f}"
        )
    return "\n".join(lines) + "\n"
