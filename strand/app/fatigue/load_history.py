"""A load history from a global analysis, reduced to a ``[fatigue] spectrum`` (``strand spectrum``).

A mooring or conductor analysis (MoorDyn, OrcaFlex, a conductor vibration code) writes its
results as columns in time: tension, lateral load, curvature. ``read_columns`` reads named
columns of such a file: a header line of names, then one row per time; commas, semicolons, tabs
or blanks between the values; lines starting with ``#`` skipped, and a units line in
parentheses right under the header (MoorDyn's ``(s) (N)``) too. ``history_spectrum`` counts the
cycles of one column by rainflow and bins them (``strand.fatigue.spectrum.reduce_history``);
``spectrum_block`` writes them as the lines to paste at the end of a case file (a
``[fatigue.spectrum]`` table: no second ``[fatigue]``), with the cycles and mean
of each class, the history's duration, and, given a tension column, its mean (for ``[load]
tension``) and one line where it varies by more than that mean. Bad input raises
``HistoryError`` with one line naming the file, the line and the column. Units: those of the
file's columns (the kind's parameter: lateral N, curvature 1/m, tension_swing N); a column's
unit is its entry in the units line, else its name's suffix (``time_s``, ``tension_N``). The time
column is in s unless its unit says otherwise (``SECONDS``). ``--period`` (``parse_period``)
scales the counts from the record's duration to the period. A force column in kN or MN is read
into N, the case's unit, with a line saying so (an SI multiple converts exactly); one in a unit
outside SI (te, kgf, lbf, kip) is refused.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import numpy.typing as npt

from ...cable.input_file import read_text
from ...fatigue.spectrum import Spectrum, reduce_history

__all__ = [
    "HistoryError",
    "HistorySpectrum",
    "read_columns",
    "history_spectrum",
    "spectrum_block",
    "parse_period",
    "SECONDS",
]

Array = npt.NDArray[np.float64]

#: a tension whose range (largest − smallest) exceeds this share of its mean is flagged: one
#: ``[load] tension`` does not stand for it
TENSION_SPREAD = 1.0

#: seconds per unit of a time column or of a period (``--period``): a year is 365.25 days
SECONDS = {"s": 1.0, "min": 60.0, "h": 3600.0, "d": 86400.0, "y": 365.25 * 86400.0}
#: newtons per unit of a force column: read into N, the unit of every force in a case
NEWTONS = {"N": 1.0, "kN": 1e3, "KN": 1e3, "kn": 1e3, "MN": 1e6}
#: force units refused (outside SI; "t" and "ton" mean several things)
NON_SI_FORCES = ("te", "tf", "kgf", "lbf", "kip", "kips")
#: the units a column name's suffix may give (``tension_kN``)
_SUFFIXES = {*SECONDS, *NEWTONS, *NON_SI_FORCES}


class HistoryError(ValueError):
    """A history file that cannot be reduced (one line naming the file and what is wrong)."""


def _text(path: Path) -> str:
    return read_text(path, "history file (CSV)", HistoryError)


def _split(line: str, sep: str | None) -> list[str]:
    return [c.strip() for c in (line.split(sep) if sep else line.split())]


def _units(columns: list[str], line: list[str] | None) -> dict[str, str]:
    """Each column's unit: its entry in the units line ``line`` (brackets stripped), else its
    name's suffix after the last ``_`` where that is a unit this module knows (a time's or a
    force's); "" where neither gives one."""
    if line is not None:
        return {c: (line[i] if i < len(line) else "").strip("()[]") for i, c in enumerate(columns)}
    suffixes = {c: c.rsplit("_", 1)[-1] if "_" in c else "" for c in columns}
    return {c: u if u in _SUFFIXES else "" for c, u in suffixes.items()}


def _read(path: Path, names: list[str]) -> tuple[dict[str, Array], dict[str, str]]:
    """The columns ``names`` of the history file ``path`` as float arrays, and their units
    (``_units``) (``HistoryError``)."""
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
    body, units = rows[1:], None
    if body and all(re.fullmatch(r"\(.*\)|\[.*\]", c) for c in _split(body[0][1], sep) if c):
        units = _split(body[0][1], sep)  # a units line, e.g. MoorDyn's "(s) (N)"
        body = body[1:]
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
    every = _units(columns, units)
    return out, {n: every[n] for n in names}


def read_columns(path: str | Path, names: list[str]) -> dict[str, Array]:
    """The columns ``names`` of the history file ``path``, as float arrays (``HistoryError``)."""
    return _read(Path(path), names)[0]


def parse_period(text: str) -> float:
    """The period ``text`` in s: a number of seconds, or a number and a unit of ``SECONDS``
    ("3h", "30d", "1y" = 365.25 d) (``HistoryError``)."""
    m = re.fullmatch(r"\s*([0-9.eE+-]+?)\s*([a-z]*)\s*", text)
    try:
        value = float(m.group(1)) * SECONDS[m.group(2) or "s"] if m else np.nan
    except (ValueError, KeyError):
        value = np.nan
    if not (np.isfinite(value) and value > 0):
        raise HistoryError(
            f"--period {text}: expected a positive number of seconds, or a number with "
            f"{', '.join(SECONDS)} (1y = 365.25 d), e.g. 3h, 30d, 1y"
        )
    return value


def _seconds(path: Path, column: str, unit: str) -> float:
    """Seconds per unit of the time ``column`` in ``unit`` (none given: s; ``HistoryError`` for
    a unit that is not a time's)."""
    if unit and unit not in SECONDS:
        raise HistoryError(
            f"{path}: time column {column!r} is in {unit!r}: expected a time in "
            f"{', '.join(SECONDS)}"
        )
    return SECONDS.get(unit, 1.0)


@dataclass(frozen=True, kw_only=True)
class HistorySpectrum:
    """A column's spectrum (``spectrum``: counts × ``scale``), the history's ``duration`` (s;
    None without a time column) with the time column's unit as given (``time_unit``, "": none,
    taken in s), the ``period`` (s) the counts were scaled to (None: by ``scale`` alone),
    given a tension column, its ``tension`` values (N), and ``notes``: a line per column read
    into N from kN or MN."""

    column: str
    spectrum: Spectrum
    scale: float = 1.0
    duration: float | None = None
    tension_column: str = ""
    tension: Array | None = None
    period: float | None = None
    time_unit: str = ""
    notes: tuple[str, ...] = ()


def _check_scale(scale: float | None, period: float | None, time_column: str) -> None:
    """Refuse (``HistoryError``) a bad ``scale`` or ``period`` (s), both together, or a
    period without the time column that gives the record's duration."""
    if scale is not None and not (
        isinstance(scale, int | float) and np.isfinite(scale) and scale > 0
    ):
        raise HistoryError(f"scale {scale!r}: expected a positive number of repetitions")
    if period is None:
        return
    if not (isinstance(period, int | float) and np.isfinite(period) and period > 0):
        raise HistoryError(f"period {period!r}: expected a positive time in s")
    if scale is not None:
        raise HistoryError(
            "--period and --scale: give one (--period scales the counts by the period over "
            "the record's duration)"
        )
    if not time_column:
        raise HistoryError("--period needs --time-column: the record's duration comes from it")


def _duration(path: Path, column: str, t: Array, unit: str) -> float:
    """The duration (s) of the time ``column`` ``t`` in ``unit``, which must increase."""
    factor = _seconds(path, column, unit)
    if np.any(np.diff(t) <= 0):
        k = int(np.argmax(np.diff(t) <= 0)) + 1
        raise HistoryError(
            f"{path}: time column {column!r} does not increase at row "
            f"{k + 1} ({t[k - 1]:g} then {t[k]:g})"
        )
    return factor * float(t[-1] - t[0])


def _in_newtons(path: Path, column: str, values: Array, unit: str) -> tuple[Array, str]:
    """The force ``column``'s ``values`` in N, and a line saying so where they were in kN or MN
    (``HistoryError`` for a unit outside SI)."""
    if unit.lower() in NON_SI_FORCES:
        raise HistoryError(
            f"{path}: column {column!r} is in {unit}, outside SI: give it in N (or kN), the "
            "unit of the case's forces"
        )
    factor = NEWTONS.get(unit, 1.0)
    if factor == 1:
        return values, ""
    return factor * values, f"# column {column!r} is in {unit}: read × {factor:g}, in N"


def history_spectrum(
    path: str | Path,
    column: str,
    bins: int = 3,
    time_column: str = "",
    tension_column: str = "",
    scale: float | None = None,
    period: float | None = None,
) -> HistorySpectrum:
    """The spectrum of ``column`` of the history file ``path`` in ``bins`` classes, its counts
    times ``scale`` (the times the history recurs in the spectrum's period; None: 1) or,
    instead, scaled from the record's duration to ``period`` (s), with the duration of
    ``time_column`` (which must increase) and the values of ``tension_column``."""
    _check_scale(scale, period, time_column)
    path = Path(path)
    names = list(dict.fromkeys(n for n in (column, time_column, tension_column) if n))
    data, units = _read(path, names)
    notes = []
    for name in names:
        if name != time_column:
            data[name], note = _in_newtons(path, name, data[name], units[name])
            notes += [note] if note else []
    duration = None
    if time_column:
        duration = _duration(path, time_column, data[time_column], units[time_column])
    try:
        spectrum = reduce_history(data[column], bins)
    except ValueError as e:
        raise HistoryError(f"{path}: column {column!r}: {e}") from None
    if period is not None:
        scale = period / duration
    elif scale is None:
        scale = 1.0
    return HistorySpectrum(
        column=column,
        spectrum=spectrum,
        scale=float(scale),
        duration=duration,
        tension_column=tension_column,
        tension=data[tension_column] if tension_column else None,
        period=period,
        time_unit=units[time_column] if time_column else "",
        notes=tuple(notes),
    )


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
    range of amplitudes, cycles and mean, then the sub-table ``[fatigue.spectrum]`` with
    ``classes = [...]``, which a case takes beside its own ``[fatigue]`` table."""
    s = h.spectrum
    lines = [
        f"# rainflow (ASTM E1049) of column {h.column!r}{f' of {source}' if source else ''}: "
        f"{s.turning_points} turning points, {s.cycles:g} cycles{_per(h)}",
        *h.notes,
        *_scaled(h),
        f"# amplitudes (range/2) in classes of width {s.width:.6g} from 0, each run at its upper "
        "edge (conservative); empty classes left out",
        "#   amplitudes         cycles   mean of its cycles",
    ]
    for a, n, m in zip(s.amplitude, s.count, s.mean, strict=True):
        lines.append(f"#   {a - s.width:>8.6g} – {a:<8.6g} {h.scale * n:>8.6g}   {m:.6g}")
    if h.tension is not None:
        lines += _tension_lines(h)
    lines += [
        "# a table of its own: paste it at the end of a case file, [fatigue] or not",
        "[fatigue.spectrum]",
        "classes = [  # [amplitude, cycles]",
    ]
    lines += [
        f"    [{_at_least(a)}, {h.scale * n:.10g}],"
        for a, n in zip(s.amplitude, s.count, strict=True)
    ]
    return "\n".join(lines + ["]"]) + "\n"


def _per(h: HistorySpectrum) -> str:
    """The record's duration, as the block's first line ends."""
    if h.duration is None:
        return ""
    taken = "" if h.time_unit else " (the time column has no unit: taken in s)"
    return f" in {h.duration:g} s{taken}"


def _scaled(h: HistorySpectrum) -> list[str]:
    """The line saying how the counts were scaled (none: as counted)."""
    if h.period is not None:
        return [
            f"# counts × {h.scale:.6g}: the record's {h.duration:g} s scaled to the period "
            f"{h.period:g} s ({h.period / SECONDS['d']:g} d)"
        ]
    if h.scale != 1:
        return [f"# counts × {h.scale:g} (the history's repetitions)"]
    return []


def _at_least(a: float) -> str:
    """``a`` > 0 in six significant digits, rounded up: no class runs below its upper edge."""
    text = f"{a:.6g}"
    if float(text) < a:
        text = f"{a + 0.5 * 10 ** (np.floor(np.log10(a)) - 5):.6g}"
    return text
