"""The free span and the clamp zones of a strand between two end sections (numpy).

Every wire ends in both end sections, which hold the wires' ends together: no relative slip and
plane sections there, so the wire forces and contact slips near an end are the clamp's, not the
free span's. A zone of length e at each end (``[fatigue] end_zone``) is reported apart.

Its default is the end sections' reach, ``lock_reach``: half the longest lay length of the
helical layers. In a bent strand away from its ends a helical wire sticks where it passes the
bending plane's extreme fibres and slips between them (Papailiou 1997): the places where its
slip is zero recur every half lay length along the strand. An end section locks the wire's end
wherever it lies in that pattern; from the wire's first extreme-fibre crossing on, at most half a
lay length from the end, its slip and axial force follow the free span's pattern again. The
curvature a clamped end concentrates within a few √(EI/T) (Poffenberger–Swart's decay length) is
the clamp's bending, which a real clamp has too, not the lock's: the zone does not set it apart.
Units: m.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

__all__ = ["ZONES", "in_clamp_zone", "zone_names", "lock_reach", "free_span"]

#: the zones, in the order the report gives them
ZONES = ("free span", "clamp zone")


def lock_reach(cable) -> float:
    """How far from an end section its lock on the wires reaches (m): half the longest lay
    length of the helical layers of ``cable`` (a ``strand.cable.description.Cable``)."""
    return max(layer.pitch for layer in cable.layers[1:]) / 2


def free_span(length: float, end_zone: float) -> tuple[float, float] | None:
    """The free span (z from, z to; m) of a strand from z = 0 to ``length`` with clamp zones of
    ``end_zone`` at both ends; None where the two zones leave none."""
    return (end_zone, length - end_zone) if 2 * end_zone < length else None


def in_clamp_zone(z, length: float, end_zone: float) -> npt.NDArray[np.bool_]:
    """True where the initial axial position ``z`` (m) lies within ``end_zone`` of either end
    of a strand from z = 0 to ``length``."""
    z = np.asarray(z, float)
    return (z < end_zone) | (z > length - end_zone)


def zone_names(clamp: npt.ArrayLike) -> npt.NDArray[np.str_]:
    """Per entry of the mask ``clamp``: "clamp" or "free", for the CSV files."""
    return np.where(np.asarray(clamp, bool), "clamp", "free")
