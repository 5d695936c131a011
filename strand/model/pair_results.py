"""The contact pairs of a strand at one state, as one typed record (``PairResults``): what
``StrandModel.pair_results`` gathers from the contact groups, in the geometry's pair order, the
same on every rank. Units: m, N, J."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

__all__ = ["PairResults"]

Array = npt.NDArray[np.float64]


@dataclass(frozen=True)
class PairResults:
    """Per geometry pair (P pairs; vectors (P, 3), spatial):

    Attributes:
        gap: gap between the wire surfaces, m (negative in contact).
        force: normal contact force, N.
        traction: magnitude of the friction force, N.
        slipping: whether the pair slips (its friction at the Coulomb cap).
        friction: friction force on the inner wire a, N (b takes its opposite).
        normal: unit normal from a to b.
        slip: relative displacement of the surface points since t = 0, m
            (``FrictionHistory``).
        sliding: the Coulomb (irreversible) part of ``slip``, m.
        work: energy friction dissipated since t = 0, J.
    """

    gap: Array
    force: Array
    traction: Array
    slipping: npt.NDArray[np.bool_]
    friction: Array
    normal: Array
    slip: Array
    sliding: Array
    work: Array
