"""The CSV files of the fatigue report and of a spectrum (``crossings.csv``, ``wire_stresses.csv``,
``wires.csv``, ``spectrum.csv``, ``spectrum_crossings.csv``): one writer, a column per array;
and the columns naming a mean-stress correction and a design fatigue factor."""

from __future__ import annotations

import csv
from pathlib import Path

import numpy as np
import numpy.typing as npt

__all__ = ["write_csv", "assessment_columns"]


def assessment_columns(mean_stress: str, factor: float, rows: int) -> dict[str, np.ndarray]:
    """``rows`` rows of the columns ``mean_stress`` (the law) and ``design_fatigue_factor``,
    each where there is one: without them the tables are as they were."""
    columns: dict[str, np.ndarray] = {}
    if mean_stress != "none":
        columns["mean_stress"] = np.full(rows, mean_stress)
    if factor != 1:
        columns["design_fatigue_factor"] = np.full(rows, float(factor))
    return columns


def write_csv(
    path: Path, columns: dict[str, npt.ArrayLike], formats: dict[str, str] | None = None
) -> None:
    """Write ``columns`` (name → one value per row) as a CSV file under a header of their names:
    strings as they are, numbers in the format spec ``formats`` gives their column (default
    ``g``: 6 significant digits, ``nan`` and ``inf`` as such)."""
    formats = formats or {}
    names = list(columns)
    arrays = [np.asarray(columns[name]) for name in names]
    specs = [formats.get(name, "g") for name in names]
    with open(path, "w", newline="") as f:
        writer = csv.writer(f)
        writer.writerow(names)
        for row in zip(*arrays, strict=True):
            writer.writerow(
                [v if isinstance(v, str) else format(v, s) for s, v in zip(specs, row, strict=True)]
            )
