"""A load history from a global analysis, reduced to a ``[fatigue] spectrum`` (``strand spectrum``).

A mooring or conductor analysis (MoorDyn, OrcaFlex, a conductor vibration code) writes its
results as columns in time: tension, lateral load, curvature. ``read_columns`` reads named
columns of such a file: a header line of names, then one row per time; commas, semicolons, tabs
or blanks between the values; lines starting with ``#`` skipped, and a units line in
parentheses right under the header (MoorDyn's ``(s) (N)``) too. ``history_spectrum`` counts the
cycles of one column by rainflow and bins them (``strand.fatigue.spectrum.reduce_history``);
``spectrum_block`` writes them as the lines to paste into a case file, with the cycles and mean
of each class, the history's duration, and, given a tension column, its mean (for ``[load]
tension``) and one line where it varies by more than that mean. Bad input raises
``HistoryError`` with one line naming the file, the line and the column. Units: those of the
file's columns (the kind's parameter: lateral N, curvature 1/m, tension_swing N).
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import numpy.typing as npt

from ...cable.input_file import read_text
from ...fatigue.spectrum import Spectrum, reduce_history

__all__ = ["HistoryError", "HistorySpectrum", "read_columns", "history_spectrum", "spectrum_block"]

Array = npt.NDArray[np.float64]

#: a tension whose range (largest − smallest) exceeds this share of its mean is flagged: one
#: ``[load] tension`` does not stand for it
TENSION_SPREAD = 1.0


class HistoryError(ValueError):
    """A history file that cannot be reduced (one line naming the file and what is wrong)."""


def _text(path: Path) -> str:
    return read_text(path, "history file (CSV)", HistoryError)


def _split(line: str, sep: str | None) -> list[str]:
    return [c.strip() for c in (line.split(sep) if sep else line.split())]


def read_columns(path: str | Path, names: list[str]) -> dict[str, Array]:
    """The columns ``names`` of the history file ``path``, as float arrays (``HistoryError``)."""
    path = Path(path)
    rows = [
        (n, line)
        for n, line in enumerate(_text(path).splitlines(), start=1)
        if line.strip() and not line.lstrip().startswith("#")
    ]
    if not rows:
        raise HistoryError(f"{path}: empty; expected a header line naming the columns")
    number, header = rows[0]
    sep = next((s for s in (",", ";", "\t") if s in header), None)
    columns = _split(header, sep)
    missing = [n for n in names if n not in columns]
    if missing:
        raise HistoryError(f"{path}: no column {missing[0]!r}; its columns: {columns}")
    body = rows[1:]
    if body and all(re.fullmatch(r"\(.*\)|\[.*\]", c) for c in _split(body[0][1], sep) if c):
        body = body[1:]  # a units line, e.g. MoorDyn's "(s) (N)"
    index = {n: columns.index(n) for n in names}
    out = {n: np.empty(len(body)) for n in names}
    for row, (number, line) in enumerate(body):
        cells = _split(line, sep)
        for name, i in index.items():
            cell = cells[i] if i < len(cells) else ""
            try:
                value = float(cell)
            except ValueError:
                value = np.nan
            if not np.isfinite(value):
                raise HistoryError(
                    f"{path}, line {number}: column {name!r} holds {cell!r}, not a finite number"
                )
            out[name][row] = value
    return out


@dataclass(frozen=True)
class HistorySpectrum:
    """A column's spectrum (``spectrum``: counts × ``scale``), the history's ``duration`` (the
    time column's unit; None without one) and, given a tension column, its ``tension`` values."""

    column: str
    spectrum: Spectrum
    scale: float = 1.0
    duration: float | None = None
    tension_column: str = ""
    tension: Array | None = None


def history_spectrum(
    path: str | Path,
    column: str,
    bins: int = 3,
    time_column: str = "",
    tension_column: str = "",
    scale: float = 1.0,
) -> HistorySpectrum:
    """The spectrum of ``column`` of the history file ``path`` in ``bins`` classes, its counts
    times ``scale`` (the times the history recurs in the spectrum's period), with the duration
    of ``time_column`` (which must increase) and the values of ``tension_column``."""
    if not (isinstance(scale, int | float) and np.isfinite(scale) and scale > 0):
        raise HistoryError(f"scale {scale!r}: expected a positive number of repetitions")
    names = list(dict.fromkeys(n for n in (column, time_column, tension_column) if n))
    data = read_columns(path, names)
    try:
        spectrum = reduce_history(data[column], bins)
    except ValueError as e:
        raise HistoryError(f"{path}: column {column!r}: {e}") from None
    duration = None
    if time_column:
        t = data[time_column]
        if np.any(np.diff(t) <= 0):
            k = int(np.argmax(np.diff(t) <= 0)) + 1
            raise HistoryError(
                f"{path}: time column {time_column!r} does not increase at row "
                f"{k + 1} ({t[k - 1]:g} then {t[k]:g})"
            )
        duration = float(t[-1] - t[0])
    tension = data[tension_column] if tension_column else None
    return HistorySpectrum(column, spectrum, float(scale), duration, tension_column, tension)


def _tension_lines(h: HistorySpectrum) -> list[str]:
    t = h.tension
    mean = float(np.mean(t))
    lines = [
        f"# mean of {h.tension_column!r} over the rows: {mean:.6g} (set [load] tension = "
        f"{mean:.6g} in N), from {t.min():.6g} to {t.max():.6g}"
    ]
    if np.ptp(t) > TENSION_SPREAD * abs(mean):
        lines.append(
            f"# WARNING: {h.tension_column!r} varies by {np.ptp(t):.4g}, more than its "
            "mean: one [load] tension does not stand for it; split the history"
        )
    return lines


def spectrum_block(h: HistorySpectrum, source: str = "") -> str:
    """The spectrum as lines for a case file: comments saying how it was counted, per class its
    range of amplitudes, cycles and mean, then ``[fatigue]`` and ``spectrum = [...]``."""
    s = h.spectrum
    per = "" if h.duration is None else f" in {h.duration:g} (time column's unit)"
    scaled = "" if h.scale == 1 else f", counts × {h.scale:g} (the history's repetitions)"
    lines = [
        f"# rainflow (ASTM E1049) of column {h.column!r}{f' of {source}' if source else ''}: "
        f"{s.turning_points} turning points, {s.cycles:g} cycles{per}{scaled}",
        f"# amplitudes (range/2) in classes of width {s.width:.6g} from 0, each run at its upper "
        "edge (conservative); empty classes left out",
        "#   amplitudes         cycles   mean of its cycles",
    ]
    for a, n, m in zip(s.amplitude, s.count, s.mean, strict=True):
        lines.append(f"#   {a - s.width:>8.6g} – {a:<8.6g} {h.scale * n:>8.6g}   {m:.6g}")
    if h.tension is not None:
        lines += _tension_lines(h)
    lines += ["[fatigue]", "spectrum = ["]
    lines += [
        f"    [{_at_least(a)}, {h.scale * n:.10g}],"
        for a, n in zip(s.amplitude, s.count, strict=True)
    ]
    return "\n".join(lines + ["]"]) + "\n"


def _at_least(a: float) -> str:
    """``a`` > 0 in six significant digits, rounded up: no class runs below its upper edge."""
    text = f"{a:.6g}"
    if float(text) < a:
        text = f"{a + 0.5 * 10 ** (np.floor(np.log10(a)) - 5):.6g}"
    return text
