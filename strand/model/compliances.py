"""The contact compliances a case can choose (``[contact] compliance``), by name.

A compliance turns the wires of a set of pairs (``Wires``: radii, moduli, Coulomb coefficients,
tributary lengths, crossing angles) and the contact settings into the pairs' normal and friction
laws (``strand.contact.normal_laws``, ``strand.contact.friction_laws``). ``ContactSettings``
accepts the registered names; the strand's crossings, line pairs and same-layer pairs take their
laws from here (``strand_contact.pair_laws``, ``same_layer.same_layer_laws``). Adding one::

    register_compliance("mine", build, uses=("k_point", "k_line"))

where ``build(wires, settings)`` returns ``(NormalLaw, FrictionLaw | None)`` and ``uses`` names
the ``[contact]`` settings it reads of ``k_point``, ``k_line`` and ``g_lim`` (the others are
refused with it). Units: m, Pa, N.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np
import numpy.typing as npt

from ..beam.registry import Registry
from ..contact.friction_laws import ElasticSlip, FrictionLaw
from ..contact.hertz import hertz_mindlin
from ..contact.normal_laws import NormalLaw, PenaltyLaw

__all__ = [
    "Wires",
    "Compliance",
    "PENALTY_SETTINGS",
    "register_compliance",
    "unregister_compliance",
    "compliances",
    "compliance_named",
]

Array = npt.NDArray[np.float64]

#: the [contact] settings that only a compliance naming them in ``uses`` reads
PENALTY_SETTINGS = ("k_point", "k_line", "g_lim")


@dataclass(frozen=True, kw_only=True)
class Wires:
    """What a compliance sees of P pairs of one kind: ``line`` (line pairs, else crossings),
    the radii (m), Young's moduli (Pa) and Poisson ratios of the wires a and b, the Coulomb
    coefficients ``mu`` (None: frictionless), the tributary lengths (m) and the crossing angles
    (rad; line pairs: 0). Each (P,)."""

    line: bool
    radius_a: Array
    radius_b: Array
    E_a: Array
    nu_a: Array
    E_b: Array
    nu_b: Array
    mu: Array | None
    tributary: Array
    angle: Array

    def __len__(self) -> int:
        return len(self.radius_a)


#: build(wires, settings) → (normal law, friction law or None)
Build = Callable[[Wires, Any], tuple[NormalLaw, FrictionLaw | None]]


@dataclass(frozen=True)
class Compliance:
    """A registered compliance: its name, ``build`` and the penalty settings it ``uses``."""

    name: str
    build: Build
    uses: tuple[str, ...] = ()


_COMPLIANCES: Registry[Compliance] = Registry("compliance")


def register_compliance(name: str, build: Build, *, uses: tuple[str, ...] = ()) -> Compliance:
    """Make ``name`` a ``[contact] compliance``: ``build(wires, settings)`` gives the laws of
    the pairs ``wires`` (``Wires``); ``uses``: which of ``PENALTY_SETTINGS`` it reads."""
    unknown = set(uses) - set(PENALTY_SETTINGS)
    if unknown:
        raise ValueError(
            f"compliance {name!r} uses {sorted(unknown)}: not among {', '.join(PENALTY_SETTINGS)}"
        )
    return _COMPLIANCES.register(name, Compliance(name, build, tuple(uses)))


def unregister_compliance(name: str) -> None:
    """Take the compliance ``name`` out of the registry."""
    _COMPLIANCES.unregister(name)


def compliances() -> tuple[str, ...]:
    """The registered compliances' names, in the order they were registered."""
    return _COMPLIANCES.names()


def compliance_named(name: str) -> Compliance:
    """The compliance ``name``; a ``KeyError`` if none is registered under it."""
    return _COMPLIANCES.lookup(name)


def _penalty(wires: Wires, settings) -> tuple[NormalLaw, FrictionLaw | None]:
    """The seed paper's: a penalty K_N (``k_point`` a crossing, ``k_line`` × the tributary
    length a line pair) and friction reaching μP after an elastic slip ``g_lim``."""
    if wires.line:
        law = PenaltyLaw(settings.k_line * wires.tributary)
    else:
        law = PenaltyLaw(np.full(len(wires), settings.k_point))
    return law, None if wires.mu is None else ElasticSlip(wires.mu, settings.g_lim)


def _hertz(wires: Wires, settings, microslip: bool = False) -> tuple[NormalLaw, FrictionLaw | None]:
    """Hertz crossed cylinders at the crossing angle, or Hertz line contact over the tributary
    length, and Mindlin's initial stick stiffness (``contact.hertz.hertz_mindlin``); with
    ``microslip``, Mindlin–Deresiewicz's curve from it to gross slip."""
    w = wires
    return hertz_mindlin(
        w.line,
        w.radius_a,
        w.radius_b,
        w.angle,
        w.tributary,
        E_a=w.E_a,
        nu_a=w.nu_a,
        E_b=w.E_b,
        nu_b=w.nu_b,
        mu=w.mu,
        microslip=microslip,
    )


def _hertz_microslip(wires: Wires, settings) -> tuple[NormalLaw, FrictionLaw | None]:
    """The "hertz" compliance with Mindlin–Deresiewicz's microslip (``contact.microslip``)."""
    return _hertz(wires, settings, microslip=True)


register_compliance("penalty", _penalty, uses=PENALTY_SETTINGS)
register_compliance("hertz", _hertz)
register_compliance("hertz_microslip", _hertz_microslip)
