"""Load spectra: cycle counts per amplitude, from a load history by rainflow, and their Miner sum
(physics only, numpy).

A spectrum is a list of classes (amplitude, count): ``count`` cycles of ``amplitude`` (zero to
peak, the unit of the load) in a period the user chooses (a year, the design life).

``reduce_history`` counts the cycles of a load history with ``cycles.rainflow_cycles`` (ASTM
E1049-85: the residue in half cycles), takes each cycle's amplitude range/2 and sorts it into
``bins`` classes of equal width from 0 to the largest amplitude. Each class is represented by its
upper edge, so no cycle is run at less than its own amplitude (conservative); a cycle on an edge
belongs to the class below it. Empty classes are dropped. Each class keeps the count-weighted mean
of its cycles' means: a spectrum run cycles about the set-up's mean load, so cycles whose mean
lies far from it are not what the run simulates.

``spectrum_damage`` is Miner's sum over the classes, D = Σᵢ nᵢ dᵢ, dᵢ the damage of one member
run at amplitude i (per repetition of its cycle), with each class's share nᵢ dᵢ / D; where dᵢ is
NaN (no S–N curve: not assessed), D is NaN too, never 0 or inf.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt
import rainflow

from .cycles import rainflow_cycles

__all__ = ["Spectrum", "reduce_history", "spectrum_damage", "spectrum_classes"]

Array = npt.NDArray[np.float64]


@dataclass(frozen=True)
class Spectrum:
    """Classes of cycles: ``amplitude`` (each class's upper edge, the load's unit), ``count``
    (cycles, halves from rainflow's residue included), ``mean`` (the count-weighted mean of the
    class's cycles' means); ``width`` of the classes, ``turning_points`` and ``cycles`` (all
    counted) of the history."""

    amplitude: Array
    count: Array
    mean: Array
    width: float
    turning_points: int
    cycles: float


def turning_points(series) -> int:
    """The number of turning points of ``series``: its ends and its reversals, a run of equal
    values counted once."""
    series = np.asarray(series, float)
    if len(series) < 2:
        return len(series)
    values = [v for _, v in rainflow.reversals(series)]
    return sum(1 for i, v in enumerate(values) if i == 0 or v != values[i - 1])


def reduce_history(series, bins: int = 3) -> Spectrum:
    """The spectrum of the load history ``series`` (1D) in ``bins`` equal classes of amplitude
    (``ValueError``, one line, for fewer than two turning points or a bad ``bins``)."""
    if isinstance(bins, bool) or not isinstance(bins, int | np.integer) or bins < 1:
        raise ValueError(f"bins = {bins!r}: expected a positive whole number of classes")
    series = np.asarray(series, float)
    points = turning_points(series)
    if points < 2:
        raise ValueError(
            f"{points} turning point(s) in {len(series)} value(s): no cycle to count (needs 2)"
        )
    c = rainflow_cycles(series)
    amplitude = c.range / 2
    width = float(amplitude.max()) / bins
    edges = width * np.arange(1, bins + 1)
    edges[-1] = amplitude.max()  # the largest cycle in the top class, whatever the round-off
    k = np.searchsorted(edges, amplitude, side="left")
    count = np.bincount(k, weights=c.count, minlength=bins)
    weighted = np.bincount(k, weights=c.count * c.mean, minlength=bins)
    full = count > 0
    return Spectrum(
        edges[full], count[full], weighted[full] / count[full], width, points, float(c.count.sum())
    )


def spectrum_classes(value) -> tuple[tuple[float, float], ...]:
    """``value`` (a list of [amplitude, count] pairs) checked as a spectrum (``ValueError``, one
    line): amplitudes positive and distinct, counts positive."""
    pairs = []
    for entry in value if isinstance(value, list | tuple) else [value]:
        if (
            not isinstance(entry, list | tuple)
            or len(entry) != 2
            or not all(isinstance(v, int | float) and not isinstance(v, bool) for v in entry)
            or not all(np.isfinite(entry))
        ):
            raise ValueError(
                f"expected [[amplitude, cycles], ...], pairs of numbers; got {entry!r}"
            )
        amplitude, count = float(entry[0]), float(entry[1])
        if not amplitude > 0:
            raise ValueError(
                f"amplitude {entry[0]!r}: expected a positive amplitude (the cycle gives the signs)"
            )
        if not count > 0:
            raise ValueError(
                f"{entry[1]!r} cycles at amplitude {entry[0]!r}: expected a positive count"
            )
        pairs.append((amplitude, count))
    amplitudes = [a for a, _ in pairs]
    twice = sorted({a for a in amplitudes if amplitudes.count(a) > 1})
    if twice:
        raise ValueError(f"amplitude {twice[0]:g} is listed twice")
    return tuple(pairs)


def spectrum_damage(counts, damages) -> tuple[Array, Array]:
    """Miner's sum D = Σᵢ nᵢ dᵢ of ``damages`` (A, ...) per class, weighted by ``counts`` (A,),
    and each class's share nᵢ dᵢ / D (A, ...): NaN where D is NaN (not assessed) or 0."""
    n = np.asarray(counts, float)
    d = np.asarray(damages, float)
    parts = n.reshape((-1,) + (1,) * (d.ndim - 1)) * d
    total = parts.sum(axis=0)
    with np.errstate(divide="ignore", invalid="ignore"):
        shares = np.where(total > 0, parts / total, np.nan)
    return total, shares
