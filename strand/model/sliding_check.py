"""How far the small-sliding assumption holds at a state: the drift of the crossings' gaps as
the wires slide round the strand (docs/theory.md §3.2). Units: m.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from ..cable.geometry import LINE

__all__ = ["SlidingCheck", "sliding_check"]

Array = npt.NDArray[np.float64]


@dataclass(frozen=True)
class SlidingCheck:
    """How far the small-sliding assumption holds at a state, per interface i|i+1 (crossings):
    the largest drift (m) of a pair's gap caused by sliding, how many of its closed pairs there
    are and how many of them drift by more than ``LIMIT`` × the interface's mean contact approach
    (m, over its closed pairs), and the z (m) of the largest drift."""

    drift: Array
    beyond: npt.NDArray[np.intp]
    closed: npt.NDArray[np.intp]
    approach: Array
    z: Array

    #: the drift, as a share of the mean approach, beyond which a pair's force is unreliable
    LIMIT = 0.25

    @property
    def share(self) -> Array:
        """The share of each interface's closed pairs beyond the limit (0 where none is closed)."""
        return self.beyond / np.maximum(self.closed, 1)

    def exceeded(self) -> npt.NDArray[np.intp]:
        """Interfaces with at least one pair beyond the limit."""
        return np.flatnonzero(self.beyond > 0)

    def message(self) -> str:
        i = int(self.exceeded()[0])
        return (
            f"beyond small sliding at interface {i}|{i + 1}: the wires slid round the strand so "
            f"far that the gaps of {self.beyond[i]:,} of its {self.closed[i]:,} closed pairs "
            f"({100 * self.share[i]:.3g} %, fixed at t = 0) "
            f"drift by more than {100 * self.LIMIT:.0f} % of the mean contact approach "
            f"({1e6 * self.approach[i]:.2f} µm), by up to {1e6 * self.drift[i]:.2f} µm at "
            f"z = {self.z[i]:.3f} m: their forces are unreliable (docs/theory.md §3.2; "
            '[contact] model = "large" re-projects the pairs)'
        )


def sliding_check(geometry, positions: Array, gap: Array) -> SlidingCheck:
    """The small-sliding check of ``geometry``'s crossings from the node ``positions`` (N, 3)
    and the pairs' current gaps (P,) (m, negative in contact).

    Pairs are fixed at t = 0. The outer node of a crossing stays on its layer's cylinder of
    radius R; when it moves round the strand by s relative to the inner node (across the pair's
    initial normal), the pair's gap drifts by s²/(2R) although the surfaces did not move apart
    (docs/theory.md §3.2; a test checks it against the element's own gap). Axial sliding leaves
    the gap as it is; so does any sliding of a line pair on the straight core (not checked)."""
    p = geometry.pairs
    radius = np.array([lay.radius for lay in geometry.cable.layers])[p.interface + 1]
    around = np.cross([0.0, 0.0, 1.0], p.normal)
    around /= np.linalg.norm(around, axis=1)[:, None]
    moved = positions - geometry.points
    s = np.einsum("ij,ij->i", moved[p.b] - moved[p.a], around)
    drift = s**2 / (2 * radius)
    n = len(geometry.cable.layers) - 1
    largest, at, approach = np.zeros(n), np.zeros(n), np.full(n, np.inf)
    beyond, count = np.zeros(n, dtype=np.intp), np.zeros(n, dtype=np.intp)
    for i in range(n):
        closed = np.flatnonzero((p.interface == i) & (p.kind != LINE) & (gap < 0))
        if not len(closed):
            continue
        worst = closed[np.argmax(drift[closed])]
        largest[i], at[i] = drift[worst], geometry.points[p.a[worst], 2]
        approach[i] = -gap[closed].mean()
        count[i] = len(closed)
        beyond[i] = np.count_nonzero(drift[closed] > SlidingCheck.LIMIT * approach[i])
    return SlidingCheck(drift=largest, beyond=beyond, closed=count, approach=approach, z=at)
