"""Sweeps: the cycle of a case at several amplitudes (``[load] sweep``), each from the same
tensioned state, and the table that compares them (``sweep.csv``, ``sweep.txt``): effort, the
set-up kind's measure (``SetupKind.measure``) at the peak and back at zero load, and, with the
fatigue outputs, what answers the fatigue question per amplitude (``fatigue_columns``): the
largest surface stress range per layer in the free span and the clamp zone, the worst crossing's
(and line contact's) Ruiz F₂ and slip amplitude per zone, the largest Miner damage per zone and
Poffenberger–Swart's ratio (NaN where skipped). Every column name carries its unit; ``sweep.txt``
gives a line per column and a column per amplitude. A case with a ``[fatigue] spectrum`` runs its
amplitudes as the sweep and gets Miner's sum over them (``strand.app.fatigue.spectrum``)."""

from __future__ import annotations

import sys
import time
from dataclasses import dataclass, fields
from pathlib import Path

import numpy as np

from forms import ReissnerBeam

from ..beam.parallel import is_root, on_root, root_stream
from ..model.checkpoint import restore
from ..model.model import BeamFactory
from ..model.programme import LoadProgramme, Position
from .build import (
    build_problem,
    results_folder,
    settings_text,
    setup_and_programme,
)
from .case import check_loads_given
from .errors import CaseError
from .folder import FolderError, check_results_folder, check_writable, writable_folder
from .kinds import SetupKind, kind_of
from .run_result import RunResult, Start
from .runner import run_programme_with_outputs
from .settings import Case

__all__ = ["run_sweep", "SweepTable", "sweep_table", "fatigue_columns", "unit_of"]


def run_sweep(
    case: Case,
    folder: str | Path | None = None,
    stream=None,
    overwrite: bool = False,
    *,
    beam: BeamFactory = ReissnerBeam,
) -> list[RunResult]:
    """Run the cycle of ``case`` at every amplitude of ``[load] sweep`` from one tensioned state:
    the tension once, into ``folder``/tension, then each amplitude restored from that state
    into ``folder``/<parameter>_<amplitude>, each with all its outputs (its first row is the
    tensioned state); ``sweep.csv`` and ``sweep.txt`` in ``folder`` compare them. ``beam``: the
    wires' beam law, ``beam(w, section)`` (``StrandModel``)."""
    stream = root_stream(stream or sys.stdout)
    t0 = time.perf_counter()
    folder = Path(folder or case.output.folder)
    kind = kind_of(case)
    parameter = kind.parameter
    names = {a: f"{parameter}_{a:g}" for a in case.load.sweep}
    keys = ["tension", *names.values()]
    check_loads_given(case)  # refused before anything is built, as the folders are
    on_root(lambda: _check_sweep_folder(folder, overwrite))
    for key in keys:
        on_root(lambda key=key: check_results_folder(folder / key, overwrite))
    problem, programme = build_problem(case, stream, kind=kind, beam=beam)
    results = []
    try:
        if problem.solver.history:  # its members restore the tensioned state, not the law's
            raise CaseError(
                f"{case.source}: the beam law {type(problem.model.beam).__name__} has a state "
                "of its own, which a sweep's members cannot restore: run each amplitude alone "
                "(no [load] sweep)"
            )
        top = on_root(lambda: _sweep_folder(folder, overwrite, case))  # once the strand is built
        folders = {key: results_folder(case, top / key, overwrite) for key in keys}
        tension = LoadProgramme(programme.stages[:1], parameter)
        print(
            f"--- sweep: tension, then {parameter} amplitudes {list(case.load.sweep)} ---",
            file=stream,
            flush=True,
        )
        tensioned = run_programme_with_outputs(
            case, problem, tension, folders["tension"], stream, keep=lambda s: True, kind=kind
        )
        if tensioned.failure:
            return [tensioned]
        state, last = tensioned.kept, tensioned.steps[-1]
        assert state is not None  # kept at every step, and the tension's steps converged
        for amplitude, name in names.items():
            member = kind.with_amplitude(case, amplitude)
            _, member_programme = setup_and_programme(member, kind)
            print(f"--- sweep: {parameter} amplitude {amplitude:g} ---", file=stream, flush=True)
            restore(problem, state)
            start = Start(Position(1, None), last)
            results.append(
                run_programme_with_outputs(
                    member, problem, member_programme, folders[name], stream, start, kind=kind
                )
            )
            if results[-1].interrupted:
                break
    finally:
        problem.solver.destroy()
    setup = problem.setup
    measure_unit = unit_of(setup.state_type, kind.measure)
    table = sweep_table(case, kind, setup.units[parameter], results, measure_unit=measure_unit)
    if is_root():
        (top / "sweep.csv").write_text(table.csv)
        (top / "sweep.txt").write_text(
            table.text + f"sweep wall time {time.perf_counter() - t0:.0f} s\n"
        )
    print(table.text, file=stream, flush=True)
    if case.fatigue.spectrum and is_root():
        from .fatigue.spectrum import write_spectrum

        text = write_spectrum(top, case, results, parameter, problem.setup.units[parameter])
        print(text, file=stream, end="", flush=True)
        if case.output.plots and (top / "spectrum.png").is_file():
            print(f"figure: {top / 'spectrum.png'}", file=stream, flush=True)
    return [tensioned, *results]


def _check_sweep_folder(folder: Path, overwrite: bool) -> list[Path]:
    """Refuse (``FolderError``) a folder the sweep may not use, writing nothing; the files an
    earlier sweep left at its top otherwise."""
    check_writable(folder)
    if not folder.is_dir():
        return []
    marker = folder / "sweep.txt"  # written first
    others = [p for p in folder.iterdir() if not p.name.startswith(".") and p.is_file()]
    if others and not marker.exists():
        raise FolderError(
            f"{folder}: holds files that are not a strand sweep's; give another folder"
        )
    if marker.exists() and not overwrite:
        raise FolderError(
            f"{folder}: holds an earlier sweep; give another folder (--out) or replace it "
            "(--overwrite)"
        )
    return others


def _sweep_folder(folder: Path, overwrite: bool, case: Case) -> Path:
    """The sweep's own folder: it holds the members' folders and the sweep table."""
    for p in _check_sweep_folder(folder, overwrite):
        p.unlink()
    path = writable_folder(folder)
    (path / "sweep.txt").write_text(settings_text(case))
    return path


@dataclass(frozen=True)
class SweepTable:
    """The sweep's table as text (``sweep.txt``) and as CSV (``sweep.csv``)."""

    text: str
    csv: str


def unit_of(record_type, name: str) -> str:
    """The unit of the field ``name`` of a set-up's record type, as column names write it
    (``strand.beam.records.quantity``: "m", "1_per_m"; "" for none)."""
    return next(f.metadata.get("unit", "") for f in fields(record_type) if f.name == name)


def sweep_table(
    case: Case, kind: SetupKind, unit: str, results: list[RunResult], *, measure_unit: str
) -> SweepTable:
    """One row per amplitude (of the ``kind``'s parameter, in ``unit`` as in column names): its
    effort, what the set-up measured at the peak and back at zero load (the kind's ``measure``,
    in ``measure_unit``) and, where the members have a fatigue report, its ``fatigue_columns``.
    Every column name carries its unit; the text gives a line per column, a column per
    amplitude."""
    head = [f"amplitude_{unit}", "steps", "iterations", "cuts", "seconds"]
    measure = f"{kind.measure}_{measure_unit}" if measure_unit else kind.measure
    head += [f"peak_{measure}", f"unloaded_{measure}", "outcome"]
    fatigue = [fatigue_columns(r.fatigue, len(case.cable.layers)) for r in results]
    names = next((list(f) for f in fatigue if f), [])
    head += names
    rows = []
    for r, f in zip(results, fatigue, strict=True):
        cycle = r.cycle_steps
        amp = max((abs(s.load) for s in cycle), default=0.0)
        peak = r.peak_step
        zero = r.unloaded_steps
        rows.append(
            [
                f"{amp:g}",
                str(len(cycle)),
                str(sum(s.iterations for s in cycle)),
                str(sum(s.cuts for s in cycle)),
                f"{r.seconds:.1f}",
                f"{getattr(peak.state, kind.measure):.12g}" if peak else "nan",
                f"{getattr(zero[0].state, kind.measure):.12g}" if zero else "nan",
                "interrupted" if r.interrupted else "failed" if r.failure else "done",
                *(f"{f.get(name, np.nan):.6g}" for name in names),
            ]
        )
    title = (
        f"sweep of {kind.parameter} from one tensioned state ({case.load.tension / 1e3:g} kN), "
        "a column per amplitude:"
    )
    csv_text = "\n".join(",".join(r) for r in [head, *rows]) + "\n"
    return SweepTable("\n".join([title, *_transposed(head, rows)]) + "\n", csv_text)


def _transposed(head: list[str], rows: list[list[str]]) -> list[str]:
    """The table with a line per column (its name, then its value for each row, right-aligned),
    so that it grows down with its columns, not across."""
    name_width = max(map(len, head))
    widths = [max(map(len, row)) for row in rows]
    return [
        f"  {name:<{name_width}}"
        + "".join(f"  {row[i]:>{w}}" for row, w in zip(rows, widths, strict=True))
        for i, name in enumerate(head)
    ]


def fatigue_columns(report, n_layers: int) -> dict[str, float]:
    """What a member's fatigue report (``fatigue.findings.FatigueReport``; None: {}) says about
    the fatigue question, by column name with its unit: per layer (0: the core) and zone (free
    span, clamp zone) the largest surface stress range (MPa); per zone the worst crossing by
    Ruiz's F₂ (MPa J/m²) and its slip amplitude (µm), and the same for the line contacts (their
    F₂ with the tributary length's contact area, ``worst_line_…``), the largest Miner
    damage per cycle of a wire (one steady repetition; NaN: none assessed); Poffenberger–Swart's ratio of the model's
    amplitude to its own (NaN where skipped or without a clamp). NaN where a zone has none."""
    if report is None:
        return {}
    elements, crossings = report.elements, report.crossings
    out: dict[str, float] = {}
    for zone, clamp in (("free", False), ("clamp", True)):
        for i in range(n_layers):
            mine = (elements.clamp == clamp) & (elements.layer == i)
            out[f"stress_range_{zone}_layer_{i}_MPa"] = (
                1e-6 * float(elements.range[mine].max()) if mine.any() else np.nan
            )
    for zone, clamp in (("free", False), ("clamp", True)):
        for kind, line in (("", False), ("line_", True)):
            mine = np.flatnonzero((crossings.clamp == clamp) & (crossings.line == line))
            k = mine[np.argmax(crossings.ruiz_f2[mine])] if len(mine) else None
            f2, slip = (
                (np.nan, np.nan)
                if k is None
                else (crossings.ruiz_f2[k], crossings.slip_amplitude[k])
            )
            out[f"worst_{kind}f2_{zone}_MPa_J_per_m2"] = 1e-6 * f2
            out[f"worst_{kind}slip_amplitude_{zone}_um"] = 1e6 * slip
        damage = report.wires.zone(clamp).damage
        out[f"largest_damage_{zone}"] = (
            np.nan if np.all(np.isnan(damage)) else float(np.nanmax(damage))
        )
    check = report.poffenberger_swart
    out["ps_ratio"] = check.ratio if check is not None and check.holds else np.nan
    return out
