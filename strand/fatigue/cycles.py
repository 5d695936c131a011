"""Cycle counting of load and stress histories, with the ``rainflow`` package (ASTM E1049-85).

Counted histories are series over the converged steps. ``rainflow_cycles`` returns every counted
cycle with its range, mean, count (1 or ½: the residue of a history that does not close is counted
in half cycles, ASTM's rule) and the indices of its two turning points. Counted on a load history,
the turning points bound the step windows of per-cycle results (``fretting.crossing_cycles``).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt
import rainflow

__all__ = ["Cycles", "rainflow_cycles"]


@dataclass(frozen=True)
class Cycles:
    """Counted cycles: ``range`` and ``mean`` (units of the series), ``count`` (1 or ½), and the
    indices ``start``, ``end`` of their turning points in the series."""

    range: npt.NDArray[np.float64]
    mean: npt.NDArray[np.float64]
    count: npt.NDArray[np.float64]
    start: npt.NDArray[np.intp]
    end: npt.NDArray[np.intp]

    def __len__(self) -> int:
        return len(self.range)


def rainflow_cycles(series) -> Cycles:
    """The rainflow cycles of ``series`` (1D)."""
    rows = list(rainflow.extract_cycles(np.asarray(series, float)))
    if not rows:
        empty = np.zeros(0)
        return Cycles(empty, empty, empty, empty.astype(np.intp), empty.astype(np.intp))
    r, m, c, i, j = (np.array(v) for v in zip(*rows, strict=True))
    return Cycles(r.astype(float), m.astype(float), c.astype(float), i.astype(np.intp),
                  j.astype(np.intp))  # fmt: skip
