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

__all__ = ["Cycles", "rainflow_cycles", "repeating_cycles", "cycle_steps"]


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


def cycle_steps(start: int, end: int, n: int) -> npt.NDArray[np.intp]:
    """The steps of a counted cycle's half ``start`` → ``end`` in a history of ``n`` steps:
    ``start``…``end``, or over the end of a repeating history, ``start``…n−1 then 0…``end``."""
    if start <= end:
        return np.arange(start, end + 1)
    return np.r_[start:n, 0 : end + 1]
