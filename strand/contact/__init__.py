"""Beam-to-beam contact: laws, kinematics, pair groups and their builders from mesh nodes.

The public API puts any beams of a dolfinx mesh in contact, at small sliding
(``strand.contact.pairs``) or large sliding (``strand.contact.windows``):

>>> from strand.contact import candidate_pairs, contact_terms, PenaltyLaw, ElasticSlip
"""

from .candidates import candidate_pairs, candidate_stencils
from .element import resolve_normal
from .errors import ContactError
from .friction_laws import ElasticSlip, FrictionLaw, Mindlin
from .hertz import hertz_mindlin
from .microslip import MindlinDeresiewicz
from .nodes import BeamNodes, beam_nodes, dof_values, locate_nodes
from .normal_laws import HertzLineLaw, HertzPointLaw, LinePenaltyLaw, NormalLaw, PenaltyLaw
from .pairs import NodePairs, contact_terms, hertz_laws, node_pairs
from .sliding import SlidingGroup, SlidingWindowError
from .windows import NodeChains, sliding_terms

__all__ = [
    "BeamNodes",
    "ContactError",
    "ElasticSlip",
    "FrictionLaw",
    "HertzLineLaw",
    "HertzPointLaw",
    "LinePenaltyLaw",
    "Mindlin",
    "MindlinDeresiewicz",
    "NodeChains",
    "NodePairs",
    "NormalLaw",
    "PenaltyLaw",
    "SlidingGroup",
    "SlidingWindowError",
    "beam_nodes",
    "candidate_pairs",
    "candidate_stencils",
    "contact_terms",
    "dof_values",
    "hertz_laws",
    "hertz_mindlin",
    "locate_nodes",
    "node_pairs",
    "resolve_normal",
    "sliding_terms",
]
