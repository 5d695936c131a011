"""Fatigue of stranded wires: fretting at the contacts, surface stresses, cycle counting, damage.

Physics only (numpy): ``stress`` (surface stresses of round wires from their section forces),
``fretting`` (per-cycle slip, forces, energy and Ruiz's parameters of contact pairs), ``cycles``
(rainflow counting), ``sn`` (S–N curves, CIGRE's Safe Border Line, Miner's rule). The run's
per-step histories come from ``strand.history``; ``strand.fatigue_report`` puts them together.
"""

from .cycles import Cycles, rainflow_cycles
from .fretting import CrossingCycles, crossing_cycles, ruiz_parameters
from .sn import SN_CURVES, SNCurve, miner_damage
from .stress import section_components, section_frames, shear_stress, surface_stress

__all__ = [
    "Cycles",
    "rainflow_cycles",
    "CrossingCycles",
    "crossing_cycles",
    "ruiz_parameters",
    "SN_CURVES",
    "SNCurve",
    "miner_damage",
    "section_components",
    "section_frames",
    "shear_stress",
    "surface_stress",
]
