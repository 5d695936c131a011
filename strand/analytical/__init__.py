"""Analytical references for any cable, physics only (numpy):

* ``stick_slip``: stick–slip bending of a tensioned strand (EI_min, the layer slip law, Masing
  cycles, loop areas);
* ``rolling``: the stick slope when wires may roll on stuck point ties, and what a Hertz patch
  offers against rolling and drilling;
* ``beam``: the strand as one tensioned beam (midspan load, Poffenberger–Swart);
* ``bent_wires``: the wire stresses of a bent strand under tension in full stick and in full
  slip (the ``fairlead`` kind's closed-form check);
* ``costello``: Costello's axial–torsional stiffness of a straight strand, and its torque
  under tension with the ends held against rotation;
* ``fibre``: the fibre model of a strand under tension, and the bounds of its bending
  stiffness.
"""

from .beam import POFFENBERGER_SWART_DISTANCE, TensionedBeam, clamped_deflection, poffenberger_swart
from .bent_wires import BENT_STATES, BentWireStresses, bent_wire_stresses, triangle
from .costello import costello_stiffness, held_end_torque
from .fibre import bending_stiffness_bounds, fibre_model
from .rolling import ContactPatch, StickEstimate, contact_patch, stick_bending_estimate
from .stick_slip import EI_MIN_VARIANTS, StickSlipLaw, ei_min, loop_area, masing

__all__ = [
    "EI_MIN_VARIANTS",
    "ei_min",
    "StickSlipLaw",
    "masing",
    "loop_area",
    "TensionedBeam",
    "clamped_deflection",
    "POFFENBERGER_SWART_DISTANCE",
    "poffenberger_swart",
    "BENT_STATES",
    "BentWireStresses",
    "bent_wire_stresses",
    "triangle",
    "costello_stiffness",
    "held_end_torque",
    "fibre_model",
    "bending_stiffness_bounds",
    "StickEstimate",
    "stick_bending_estimate",
    "ContactPatch",
    "contact_patch",
]
