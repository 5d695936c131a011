"""Beam-to-beam contact: laws, kinematics, pair groups and their builders from mesh nodes.

The public API puts any beams of a dolfinx mesh in contact, at small sliding
(``strand.contact.pairs``) or large sliding (``strand.contact.windows``):

>>> from strand.contact import candidate_pairs, contact_terms, PenaltyLaw, ElasticSlip
"""

from .element import resolve_normal
from .errors import ContactError
from .laws import (
    ElasticSlip,
    FrictionLaw,
    HertzLineLaw,
    HertzPointLaw,
    LinePenaltyLaw,
    Mindlin,
    NormalLaw,
    PenaltyLaw,
    hertz_mindlin,
)
from .nodes import BeamNodes, beam_nodes, dof_values, locate_nodes
from .pairs import (
    NodePairs,
    candidate_pairs,
    candidate_stencils,
    contact_terms,
    hertz_laws,
    node_pairs,
)
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
