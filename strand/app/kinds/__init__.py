"""Set-up kinds: everything the application knows about one kind of strand test, registered in
one place.

A kind (``SetupKind``, ``strand.app.kinds.base``) is one module: its own ``[load]`` and
``[steps]`` settings (frozen dataclasses; the case file lists them flat beside the common ones),
its checks of a case, the test set-up it builds (a ``strand.setups`` class, the library's
mechanics), its load programme, the measure a sweep reports, its analytical reference, its
summary lines and figures. The registry (``strand.app.kind_registry``) maps ``[load] kind``
names to kinds: ``register`` adds one (the built-in ones at the end of this module), ``lookup``
finds one by name (a ``CaseError`` naming the known kinds otherwise) and ``kind_of`` gives a
case's, as the case's settings run it (``SetupKind.for_case``: a variant with another load
parameter, such as the saddle test under displacement control). The built-in kinds: ``saddle``
(the seed paper's midspan saddle test, under force or displacement control,
``strand.app.kinds.saddle``), ``bending`` (uniform bending by end rotations,
``strand.app.kinds.bending``), ``tension_cycle`` (the end force cycled about the mean tension,
``strand.app.kinds.tension_cycle``) and ``fairlead`` (a curvature held while the tension cycles,
or cycled under the tension, ``strand.app.kinds.fairlead``); tests/test_setup_kinds.py registers
one of its own.
"""

from __future__ import annotations

from ..kind_registry import lookup, registered, unregister
from .base import NoSettings, SetupKind, kind_of, register, tension_stage, tension_then_cycle
from .bending import UniformBending
from .fairlead import Fairlead
from .saddle import Saddle
from .tension_cycle import TensionCycle

__all__ = [
    "SetupKind",
    "NoSettings",
    "register",
    "unregister",
    "lookup",
    "kind_of",
    "registered",
    "tension_then_cycle",
    "tension_stage",
]

# the built-in kinds
register(Saddle())
register(UniformBending())
register(TensionCycle())
register(Fairlead())
