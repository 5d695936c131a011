"""The free span and the clamp zones of a strand between two end sections (numpy).

Every wire ends in both end sections, which hold the wires' ends together: no relative slip and
plane sections there, so the wire forces and contact slips near an end are the clamp's, not the
free span's. A zone of length e at each end (``[fatigue] end_zone``; by default one lay length
of the outer layer: the length over which each outer wire goes once round the strand, so that
every side of it has been at every angle from the bending plane between the clamp's locked
section and the free span) is reported apart. Units: m.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

__all__ = ["ZONES", "in_clamp_zone", "zone_names"]

#: the zones, in the order the report gives them
ZONES = ("free span", "clamp zone")


def in_clamp_zone(z, length: float, end_zone: float) -> npt.NDArray[np.bool_]:
    """True where the initial axial position ``z`` (m) lies within ``end_zone`` of either end
    of a strand from z = 0 to ``length``."""
    z = np.asarray(z, float)
    return (z < end_zone) | (z > length - end_zone)


def zone_names(clamp: npt.ArrayLike) -> npt.NDArray[np.str_]:
    """Per entry of the mask ``clamp``: "clamp" or "free", for the CSV files."""
    return np.where(np.asarray(clamp, bool), "clamp", "free")
