"""Beam-to-beam contact on fixed node pairs (small sliding): laws, kinematics, assembly.

The public API puts any beams of a dolfinx mesh in contact (``strand.contact.pairs``):

>>> from strand.contact import candidate_pairs, contact_terms, PenaltyLaw, ElasticSlip
"""

from .laws import (
    ElasticSlip,
    FrictionLaw,
    HertzLineLaw,
    HertzPointLaw,
    Mindlin,
    NormalLaw,
    PenaltyLaw,
    hertz_mindlin,
)
from .pairs import (
    BeamNodes,
    NodePairs,
    beam_nodes,
    candidate_pairs,
    contact_terms,
    hertz_laws,
    locate_nodes,
    node_pairs,
)

__all__ = [
    "BeamNodes",
    "ElasticSlip",
    "FrictionLaw",
    "HertzLineLaw",
    "HertzPointLaw",
    "Mindlin",
    "NodePairs",
    "NormalLaw",
    "PenaltyLaw",
    "beam_nodes",
    "candidate_pairs",
    "contact_terms",
    "hertz_laws",
    "hertz_mindlin",
    "locate_nodes",
    "node_pairs",
]
