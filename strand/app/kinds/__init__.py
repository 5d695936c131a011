"""Set-up kinds: everything the application knows about one kind of strand test, registered in
one place.

A kind (``SetupKind``) is one module: its own ``[load]`` and ``[steps]`` settings (frozen
dataclasses; the case file lists them flat beside the common ones), its checks of a case, the
test set-up it builds (a ``strand.setups`` class, the library's mechanics), its load programme,
the measure a sweep reports, its analytical reference, its summary lines and figures. The
registry maps ``[load] kind`` names to kinds: ``register`` adds one (the built-in ones at the end
of this module), ``lookup`` finds one by name (a ``CaseError`` naming the known kinds otherwise)
and ``kind_of`` gives a case's, as the case's settings run it (``SetupKind.for_case``: a variant
with another load parameter, such as the saddle test under displacement control). The built-in
kinds: ``saddle`` (the seed paper's midspan saddle test, under force or displacement control,
``strand.app.kinds.saddle``), ``bending`` (uniform bending by end rotations,
``strand.app.kinds.bending``) and ``tension_cycle`` (the end force cycled about the mean tension,
``strand.app.kinds.tension_cycle``); tests/test_setup_kinds.py registers one of its own.
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from collections.abc import Callable
from dataclasses import dataclass, fields, replace
from pathlib import Path
from typing import Any

from ...model.programme import LoadProgramme, Stage, cycle_stages
from ..case import Case, CaseError
from ..settings import LoadSettings, StepSettings

__all__ = [
    "SetupKind",
    "NoSettings",
    "register",
    "unregister",
    "lookup",
    "kind_of",
    "registered",
    "tension_then_cycle",
]


@dataclass(frozen=True)
class NoSettings:
    """The own settings of a kind that has none."""


class SetupKind(ABC):
    """One kind of test, as a run takes it: settings, checks, set-up, programme and results.

    Attributes:
        name: ``[load] kind`` in a case file.
        parameter: the load parameter of its set-up that the cycle ramps after tensioning; by
            default its amplitude is the ``[load]`` setting of that name and its first and
            largest increments the ``[steps]`` settings ``<parameter>`` and ``<parameter>_max``.
        unit: the parameter's SI unit in texts ("N").
        progress_unit: the parameter's (label, scale) on the progress lines (("kN", 1e3)).
        measure: the field of its set-up's ``state()`` a sweep reports at the peak and back at
            zero load.
        load_settings, step_settings: frozen dataclasses of its own ``[load]`` and ``[steps]``
            settings, with their defaults (names distinct from every other setting there).
        signed: its ``[load]`` settings that may be zero or negative.
        clamp: the set-up clamps the strand at z = 0 (the fatigue report's Poffenberger–Swart
            check at the clamp).
    """

    name: str = ""
    parameter: str = ""
    unit: str = ""
    progress_unit: tuple[str, float] = ("", 1.0)
    measure: str = ""
    load_settings: type = NoSettings
    step_settings: type = NoSettings
    signed: frozenset[str] = frozenset()
    clamp: bool = False

    def load(self, case: Case) -> Any:
        """This kind's own ``[load]`` settings in ``case`` (a ``load_settings``)."""
        return case.load.by_kind[self.name]

    def steps(self, case: Case) -> Any:
        """This kind's own ``[steps]`` settings in ``case`` (a ``step_settings``)."""
        return case.steps.by_kind[self.name]

    def step_sizes(self, steps) -> tuple[float, float]:
        """First and largest increment of the cycle's legs, from its own ``[steps]``."""
        return getattr(steps, self.parameter), getattr(steps, f"{self.parameter}_max")

    def check_settings(self, load, steps) -> None:
        """Check its own settings (``CaseError``), in a case of any kind: the first increment
        may not exceed the largest."""
        first, largest = self.step_sizes(steps)
        if first > largest:
            raise CaseError(f"[steps] {self.parameter} = {first} exceeds {self.parameter}_max")

    def check_case(self, case: Case) -> None:
        """Check a case of this kind against its mesh and common settings (``CaseError``)."""
        return None

    def for_case(self, case: Case) -> SetupKind:
        """The kind as it runs ``case``: itself, or a variant its settings choose, with another
        load parameter (the saddle test under displacement control)."""
        return self

    @abstractmethod
    def setup(self, case: Case) -> Callable:
        """The test set-up factory: takes the ``StrandModel``, returns a ``TestSetup``."""

    def amplitude(self, case: Case) -> float:
        """The amplitude the cycle targets multiply (the parameter's unit)."""
        return getattr(self.load(case), self.parameter)

    def with_amplitude(self, case: Case, amplitude: float) -> Case:
        """``case`` with another amplitude (a member of a sweep)."""
        return replace(case, load=case.load.with_values(**{self.parameter: amplitude}))

    def programme(self, case: Case) -> LoadProgramme:
        """The load programme: the tension, then the cycle of ``parameter``."""
        first, largest = self.step_sizes(self.steps(case))
        return tension_then_cycle(case, self.parameter, self.amplitude(case), first, largest)

    def reference(self, case: Case, result) -> Any:
        """What the analytical reference predicts for the run's ``result`` (a ``RunResult``),
        kept as ``result.reference`` for the summary and figures; None without one."""
        return None

    def summary_lines(self, case: Case, result) -> list[str]:
        """Its lines of the run's summary (after the tension's)."""
        return []

    def figures(self, case: Case, result, note: str = "") -> list[Path]:
        """Its figures (PNG) in ``result.folder``; ``note``: a line in red (an incomplete run)."""
        return []


def tension_then_cycle(
    case: Case, parameter: str, amplitude: float, first: float, largest: float
) -> LoadProgramme:
    """Tension to ``load.tension``, then the legs ``load.cycle`` × ``amplitude`` of ``parameter``,
    each starting with increment ``first``, growing up to ``largest``."""
    steps = case.steps
    legs = cycle_stages(parameter, amplitude, case.load.cycle, first, largest, steps.cuts,
                        steps.growth, steps.predictor)  # fmt: skip
    return LoadProgramme((tension_stage(case), *legs), parameter)


def tension_stage(case: Case) -> Stage:
    """The ramp of the end force to ``load.tension``, from ``steps.tension``; its first step
    closes the contact pairs, so the secant predictor starts from the second."""
    steps = case.steps
    return Stage("tension", "tension", case.load.tension, steps.tension,
                 steps.tension / 2**steps.cuts, growth=steps.growth,
                 extrapolate=steps.predictor, settles=True)  # fmt: skip


_KINDS: dict[str, SetupKind] = {}


def register(kind: SetupKind) -> SetupKind:
    """Add ``kind`` to the registry (a ``ValueError`` if its name, or the name of one of its own
    settings, is taken: by another kind, or by a setting every kind shares)."""
    if kind.name in _KINDS:
        raise ValueError(f"a set-up kind named {kind.name!r} is registered already")
    for section, common in (("load_settings", LoadSettings), ("step_settings", StepSettings)):
        mine = {f.name for f in fields(getattr(kind, section))}
        owners = {f.name: "every kind" for f in fields(common) if f.name != "by_kind"}
        for other in _KINDS.values():
            owners.update(dict.fromkeys((f.name for f in fields(getattr(other, section))),
                                        other.name))  # fmt: skip
        taken = sorted(mine & set(owners))
        if taken:
            raise ValueError(f"{kind.name}: settings {taken} belong to {owners[taken[0]]}")
    _KINDS[kind.name] = kind
    return kind


def unregister(name: str) -> None:
    """Take the kind ``name`` out of the registry."""
    del _KINDS[name]


def registered() -> tuple[SetupKind, ...]:
    """The registered kinds, in the order they were registered."""
    return tuple(_KINDS.values())


def lookup(name: str) -> SetupKind:
    """The kind ``name``; a ``CaseError`` naming the known kinds if there is none."""
    try:
        return _KINDS[name]
    except KeyError:
        *others, last = _KINDS
        choices = f"{', '.join(others)} or {last}" if others else last
        raise CaseError(f"[load] kind = {name!r} is unknown; choose {choices}") from None


def kind_of(case: Case) -> SetupKind:
    """The kind of ``case`` (its ``[load] kind``), as its settings run it (``for_case``)."""
    return lookup(case.load.kind).for_case(case)


# the built-in kinds (their modules import ``SetupKind`` from here)
from .bending import UniformBending  # noqa: E402
from .saddle import Saddle  # noqa: E402
from .tension_cycle import TensionCycle  # noqa: E402

register(Saddle())
register(UniformBending())
register(TensionCycle())
