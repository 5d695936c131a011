"""UFL physics of strand, importable on its own: finite rotations and Reissner beams.

>>> from forms import CircularSection, ReissnerBeam
"""

from .reissner import (
    REDUCED_QUADRATURE,
    CircularSection,
    ReissnerBeam,
    has_elastic_stresses,
    moment_virtual_work,
    tangent_frame,
    unit_tangent,
)
from .rotations import axial, curvature_matrix, rotation_matrix, skew

__all__ = [
    "REDUCED_QUADRATURE",
    "CircularSection",
    "ReissnerBeam",
    "axial",
    "curvature_matrix",
    "has_elastic_stresses",
    "moment_virtual_work",
    "rotation_matrix",
    "skew",
    "tangent_frame",
    "unit_tangent",
]
