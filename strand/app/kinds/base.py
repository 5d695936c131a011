"""What a set-up kind is (``SetupKind``: its settings, checks, set-up, programme, reference,
summary lines and figures), the load programme most kinds share (``tension_then_cycle``), and
``register`` and ``kind_of``, the registry's doors that know the settings and the case
(``strand.app.kind_registry`` holds the kinds)."""

from __future__ import annotations

from abc import ABC, abstractmethod
from collections.abc import Callable
from dataclasses import dataclass, fields, replace
from pathlib import Path
from typing import Any

from ...beam.setting import declared
from ...model.programme import LoadProgramme, Stage, cycle_stages
from ..errors import CaseError
from ..kind_registry import add, lookup, registered
from ..settings import Case, LoadSettings, StepSettings

__all__ = [
    "SetupKind",
    "NoSettings",
    "register",
    "kind_of",
    "tension_then_cycle",
    "tension_stage",
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
        progress_unit: the parameter's (label, scale) on the progress lines (("kN", 1e3)), and
            in figure titles (``load_text``).
        symbol: the parameter's symbol in figure titles ("P"; "": its name).
        measure: the field of its set-up's ``state()`` a sweep reports at the peak and back at
            zero load.
        load_settings, step_settings: frozen dataclasses of its own ``[load]`` and ``[steps]``
            settings, each field declared with ``strand.beam.setting.setting`` (default, unit,
            sign, choices, meaning; names distinct from every other setting there): the case
            reader, ``strand run --help``, the settings reference, the template and the JSON
            Schema take them from there when a case is read.
        clamp: the set-up clamps the strand at z = 0 (the fatigue report's Poffenberger–Swart
            check at the clamp).
        example: settings (``--set`` form, "section.key=value") that a case of the kind needs
            beyond the defaults, for a kind whose own settings have no default that runs (its
            docs tables are built from the default case with them).
    """

    name: str = ""
    parameter: str = ""
    unit: str = ""
    progress_unit: tuple[str, float] = ("", 1.0)
    symbol: str = ""
    measure: str = ""
    load_settings: type = NoSettings
    step_settings: type = NoSettings
    clamp: bool = False
    example: tuple[str, ...] = ()

    def load_text(self, value: float) -> str:
        """A value of the cycled parameter as figure titles give it ("P = 4.30 kN")."""
        label, scale = self.progress_unit
        return f"{self.symbol or self.parameter} = {value / scale:.2f} {label}"

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
            raise CaseError(
                f"[steps] {self.parameter} = {first} {self.unit} exceeds "
                f"{self.parameter}_max = {largest} {self.unit}"
            )

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
    legs = cycle_stages(
        parameter,
        amplitude,
        case.load.cycle,
        first,
        largest,
        cuts=steps.cuts,
        growth=steps.growth,
        predictor=steps.predictor,
    )
    return LoadProgramme((tension_stage(case), *legs), parameter)


def tension_stage(case: Case) -> Stage:
    """The ramp of the end force to ``load.tension``, from ``steps.tension``; its first step
    closes the contact pairs, so the secant predictor starts from the second."""
    steps = case.steps
    return Stage(
        "tension",
        "tension",
        case.load.tension,
        steps.tension,
        steps.tension / 2**steps.cuts,
        growth=steps.growth,
        extrapolate=steps.predictor,
        settles=True,
    )


def register(kind: SetupKind) -> SetupKind:
    """Add ``kind`` to the registry (a ``ValueError`` if its name, or the name of one of its own
    settings, is taken: by another kind, or by a setting every kind shares; or if one of its
    own settings is not declared with ``setting``)."""
    if kind.name in {other.name for other in registered()}:
        raise ValueError(f"a set-up kind named {kind.name!r} is registered already")
    for section, common in (("load_settings", LoadSettings), ("step_settings", StepSettings)):
        undeclared = [f.name for f in fields(getattr(kind, section)) if declared(f) is None]
        if undeclared:
            raise ValueError(
                f"{kind.name}: settings {undeclared} are not declared: give each its default, "
                "unit and meaning with strand.beam.setting.setting"
            )
        mine = {f.name for f in fields(getattr(kind, section))}
        owners = {f.name: "every kind" for f in fields(common) if f.name != "by_kind"}
        for other in registered():
            owners.update(
                dict.fromkeys((f.name for f in fields(getattr(other, section))), other.name)
            )
        taken = sorted(mine & set(owners))
        if taken:
            raise ValueError(f"{kind.name}: settings {taken} belong to {owners[taken[0]]}")
    return add(kind)


def kind_of(case: Case) -> SetupKind:
    """The kind of ``case`` (its ``[load] kind``), as its settings run it (``for_case``)."""
    return lookup(case.load.kind).for_case(case)
