"""Cycle counting of load and stress histories, with the ``rainflow`` package (ASTM E1049-85).

Counted histories are series over the converged steps. ``rainflow_cycles`` counts a history once
through: every cycle with its range, mean, count (1 or ½: the residue of a history that does not
close is counted in half cycles, ASTM's rule) and the indices of its two turning points.

``repeating_cycles`` counts one period of a history repeated without end: the series closed on
itself (its last value followed by its first), rotated to start and end at its largest value and
counted with the three-point rule (Downing & Socie 1982; ASTM E1049-85 §5.4.4), so that every
cycle closes and counts 1. A sine of N whole periods counts N cycles of its peak-to-peak range,
where a once-through count gives N − ½ of them and two halves of the amplitude. Its cycles are the
ones each further repetition of the history adds to a once-through count. A cycle's turning points
``start`` → ``end`` may straddle the closure (``start`` > ``end``): its half runs to the end of
the history and on from its start (``cycle_steps``).

Counted on a load history, the turning points bound the step windows of per-cycle results
(``fretting.crossing_cycles``).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt
import rainflow

__all__ = ["Cycles", "rainflow_cycles", "repeating_cycles", "repeating_ranges", "cycle_steps"]


@dataclass(frozen=True)
class Cycles:
    """Counted cycles: ``range`` and ``mean`` (units of the series), ``count`` (1 or ½), and the
    indices ``start``, ``end`` of their turning points in the series (``start`` > ``end``: a
    cycle of a repeating history whose half runs over the end of the series to its start)."""

    range: npt.NDArray[np.float64]
    mean: npt.NDArray[np.float64]
    count: npt.NDArray[np.float64]
    start: npt.NDArray[np.intp]
    end: npt.NDArray[np.intp]

    def __len__(self) -> int:
        return len(self.range)


def _cycles(rows: list) -> Cycles:
    if not rows:
        empty = np.zeros(0)
        return Cycles(empty, empty, empty, empty.astype(np.intp), empty.astype(np.intp))
    r, m, c, i, j = (np.array(v) for v in zip(*rows, strict=True))
    return Cycles(
        r.astype(float), m.astype(float), c.astype(float), i.astype(np.intp), j.astype(np.intp)
    )


def rainflow_cycles(series) -> Cycles:
    """The rainflow cycles of ``series`` (1D), counted once through (ASTM's half cycles)."""
    return _cycles(list(rainflow.extract_cycles(np.asarray(series, float))))


def repeating_cycles(series) -> Cycles:
    """The rainflow cycles of one period of ``series`` (1D) repeated without end: closed on
    itself, every cycle full (count 1); none where the series is constant."""
    s = np.asarray(series, float)
    n = len(s)
    if n < 2 or not np.ptp(s) > 0:
        return _cycles([])
    top = int(np.argmax(s))
    order = np.r_[top:n, 0 : top + 1]  # from the largest value round to it again
    stack: list[tuple[int, float]] = []
    rows = []
    for k, value in rainflow.reversals(s[order]):
        stack.append((k, value))
        while len(stack) >= 3:
            (k0, v0), (k1, v1), (_, v2) = stack[-3:]
            if abs(v2 - v1) < abs(v1 - v0):
                break
            rows.append((abs(v1 - v0), 0.5 * (v0 + v1), 1.0, order[k0], order[k1]))
            del stack[-3:-1]
    return _cycles(rows)


def _compact(values: npt.NDArray[np.float64], keep: npt.NDArray[np.bool_]):
    """The kept entries of each column of ``values`` (n, M) moved to its top, in order, NaN
    below; and how many each column keeps."""
    order = np.argsort(~keep, axis=0, kind="stable")
    out = np.take_along_axis(np.where(keep, values, np.nan), order, axis=0)
    return out, keep.sum(axis=0)


def repeating_ranges(series, means: bool = False):
    """The ranges of ``repeating_cycles`` for each column of ``series`` (n steps, M histories)
    at once: (M, C), padded with zeros (cycles of no range) to the largest count C; with
    ``means``, also the cycles' means (M, C), (v₀ + v₁)/2 of their turning points, 0 in the
    padding. The same count (rotation to the largest value, ``rainflow.reversals``, three-point
    rule) written over all columns: a loop over the reversals, none over the histories."""
    s = np.asarray(series, float)
    if s.ndim != 2:
        raise ValueError(f"series: (n steps, M histories) expected, got shape {s.shape}")
    n, m = s.shape
    if n < 2 or m == 0:
        return (np.zeros((m, 0)), np.zeros((m, 0))) if means else np.zeros((m, 0))
    # one period from the largest value round to it again
    order = (np.argmax(s, axis=0) + np.arange(n + 1)[:, None]) % n
    r = np.take_along_axis(s, order, axis=0)
    # without repeated values, then the reversals: the ends and every change of direction
    v, count = _compact(r, np.r_[np.ones((1, m), bool), r[1:] != r[:-1]])
    d = np.diff(v, axis=0)
    turns = np.zeros_like(v, dtype=bool)
    turns[1:-1] = d[:-1] * d[1:] < 0
    rows = np.arange(len(v))[:, None]
    turns |= (rows == 0) | (rows == count - 1)
    v, count = _compact(v, turns & (rows < count))
    # the three-point rule on every column's stack at once
    stack = np.zeros((m, len(v)))
    depth = np.zeros(m, dtype=np.intp)
    ranges = np.zeros((m, max(len(v) // 2, 1)))
    centres = np.zeros_like(ranges)
    found = np.zeros(m, dtype=np.intp)
    cols = np.arange(m)
    for k in range(len(v)):
        push = cols[k < count]
        stack[push, depth[push]] = v[k, push]
        depth[push] += 1
        while True:
            c = cols[depth >= 3]
            v0, v1, v2 = (stack[c, depth[c] - i] for i in (3, 2, 1))
            closes = np.abs(v2 - v1) >= np.abs(v1 - v0)
            if not closes.any():
                break
            c, v0, v1, v2 = c[closes], v0[closes], v1[closes], v2[closes]
            ranges[c, found[c]] = np.abs(v1 - v0)
            centres[c, found[c]] = 0.5 * (v0 + v1)
            found[c] += 1
            stack[c, depth[c] - 3] = v2
            depth[c] -= 2
    if means:
        return ranges[:, : found.max()], centres[:, : found.max()]
    return ranges[:, : found.max()]


def cycle_steps(start: int, end: int, n: int) -> npt.NDArray[np.intp]:
    """The steps of a counted cycle's half ``start`` → ``end`` in a history of ``n`` steps:
    ``start``…``end``, or over the end of a repeating history, ``start``…n−1 then 0…``end``."""
    if start <= end:
        return np.arange(start, end + 1)
    return np.r_[start:n, 0 : end + 1]
