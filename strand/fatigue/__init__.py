"""Fatigue of stranded wires: fretting at the contacts, surface stresses, cycle counting, damage.

Physics only (numpy): ``stress`` (surface stresses of round wires from their section forces),
``fretting`` (per-cycle slip, forces, energy and Ruiz's parameters of contact pairs), ``cycles``
(rainflow counting), ``sn`` (wire S–N curves: CIGRE's Safe Border Lines for aluminium, EN 1992-1-1's
for steel wire, a user's own; Miner's rule), ``meanstress`` (Goodman, Gerber and SWT mean-stress
corrections), ``tn`` (the strand-level T–N curves of DNV-OS-E301 and API RP 2SK),
``zones`` (free span and clamp zones), ``poffenberger`` (where Poffenberger–Swart holds),
``spectrum`` (load spectra: a history reduced by rainflow, their Miner sum). The run's
per-step histories come from ``strand.app.history``; ``strand.app.fatigue.report`` puts them
together.
"""

from .cycles import Cycles, rainflow_cycles, repeating_cycles, repeating_ranges
from .fretting import CrossingCycles, crossing_cycles, ruiz_parameters, stuck_throughout
from .meanstress import MEAN_STRESS_LAWS, MeanStress, equivalent_amplitude
from .poffenberger import SpanCheck, span_check, span_error
from .sn import SN_CURVES, SNCurve, miner_damage, user_curve, wire_material
from .spectrum import Spectrum, reduce_history, spectrum_classes, spectrum_damage
from .stress import section_components, section_frames, shear_stress, surface_stress
from .tn import api_spiral_strand_life, dnv_spiral_rope_life, tension_damage
from .zones import ZONES, free_span, in_clamp_zone, lock_reach

__all__ = [
    "Cycles",
    "rainflow_cycles",
    "repeating_cycles",
    "repeating_ranges",
    "CrossingCycles",
    "crossing_cycles",
    "ruiz_parameters",
    "stuck_throughout",
    "SpanCheck",
    "span_check",
    "span_error",
    "SN_CURVES",
    "SNCurve",
    "miner_damage",
    "user_curve",
    "wire_material",
    "MEAN_STRESS_LAWS",
    "MeanStress",
    "equivalent_amplitude",
    "Spectrum",
    "reduce_history",
    "spectrum_classes",
    "spectrum_damage",
    "api_spiral_strand_life",
    "dnv_spiral_rope_life",
    "tension_damage",
    "ZONES",
    "in_clamp_zone",
    "free_span",
    "lock_reach",
    "section_components",
    "section_frames",
    "shear_stress",
    "surface_stress",
]
