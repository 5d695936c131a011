"""The settings of a case: its sections (mesh, load, load steps, outputs, fatigue) and the
``Case`` that holds them with the cable and its contact settings (``strand.app.case`` reads them
from a case file).

Every setting is declared once, on its field (``strand.beam.setting.setting``): default, SI unit,
sign, choices and meaning, from which the reader, ``strand run --help``, the settings reference,
the case template and the JSON Schema are made (``strand.app.settings_schema``). ``[load]`` and
``[steps]`` hold the settings every set-up kind shares and, in ``by_kind``, each registered
kind's own (``strand.app.kinds``), all read flat as the case file writes them
(``case.load.zone``). The kinds join in when a case is read: this module imports nothing of them,
and a ``Case`` made in code holds the common settings alone.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field, fields, replace
from types import MappingProxyType
from typing import Any

from ..beam.setting import setting
from ..cable.description import Cable
from ..model.contact_settings import ContactSettings
from .fatigue.settings import FatigueSettings
from .setting_readers import _amplitudes, _cycle, _direction, _iterations, _tension

__all__ = [
    "Case",
    "MeshSettings",
    "LoadSettings",
    "StepSettings",
    "OutputSettings",
    "FatigueSettings",
    "WithKinds",
    "KIND_SECTIONS",
]


@dataclass(frozen=True)
class MeshSettings:
    """The strand's mesh."""

    length: float = setting(1.0, "Free length between the end sections.", unit="m")
    h_max: float = setting(
        4e-3,
        "Largest element (arc length), from the thinnest wire's diameter / 10 to the shortest "
        "lay length / 8.",
        unit="m",
    )


#: the sections whose keys include the set-up kinds' own, and each kind's attribute for them
KIND_SECTIONS = {"load": "load_settings", "steps": "step_settings"}


class WithKinds:
    """A section holding the settings every set-up kind shares (its fields) and, in ``by_kind``,
    each registered kind's own (``SetupKind.load_settings``, ``step_settings``); all of them read
    flat, as the case file writes them (``load.zone``). ``by_kind`` is filled when a case is read
    (``strand.app.case``): a section made in code holds the common settings alone."""

    by_kind: Mapping[str, Any]

    def __getattr__(self, name: str) -> Any:
        for own in self.__dict__.get("by_kind", {}).values():
            if name in own.__dataclass_fields__:
                return getattr(own, name)
        raise AttributeError(f"{type(self).__name__} has no setting {name!r}")

    def items(self) -> list[tuple[str, Any]]:
        """Every setting as (key, value): the common ones, then each kind's own."""
        common = [(f.name, getattr(self, f.name)) for f in fields(self) if f.name != "by_kind"]
        own = [(f.name, getattr(s, f.name)) for s in self.by_kind.values() for f in fields(s)]
        return common + own

    def with_values(self, **values):
        """A copy with ``values`` (common or kinds' settings) changed."""
        by_kind = {}
        for name, own in self.by_kind.items():
            mine = {k: values.pop(k) for k in list(values) if k in own.__dataclass_fields__}
            by_kind[name] = replace(own, **mine)
        return replace(self, **values, by_kind=by_kind)


_NO_KINDS: Mapping[str, Any] = MappingProxyType({})


@dataclass(frozen=True)
class LoadSettings(WithKinds):
    """The loads: the tension, then the set-up kind's cycle."""

    kind: str = setting(
        "saddle",
        "The set-up kind: saddle, bending, tension_cycle, fairlead or another registered one. "
        "``strand.app.kinds``: saddle: a midspan saddle load (the seed "
        "paper's test); bending: uniform bending by end rotations (the section's M–κ); "
        "tension_cycle: the end force cycled by tension_swing (N), with a saddle load "
        "fixed_lateral (N) held at midspan; fairlead: bent to bend_curvature (1/m), bend_radius "
        "(m) or bend_angle (deg) over bend_length (m), held while the tension cycles by "
        'tension_swing (N), or (cycled = "curvature") the curvature cycles about it by '
        "curvature_swing (1/m).",
    )
    tension: float = setting(40e3, "End force, held during bending.", unit="N", read=_tension)
    cycle: tuple[float, ...] = setting(
        (1.0, 0.0, -1.0, 0.0),
        "Targets after tensioning, in units of the kind's amplitude (lateral, curvature, "
        "tension_swing); [0.0]: the tension alone.",
        read=_cycle,
        schema={"type": "array", "items": {"type": "number"}, "minItems": 1},
    )
    direction: tuple[float, ...] = setting(
        (1.0, 0.0, 0.0),
        "Direction of a positive lateral load / stretched fibre: [x, y, 0], across the strand "
        "axis.",
        read=_direction,
        schema={"type": "array", "items": {"type": "number"}, "minItems": 3, "maxItems": 3},
    )
    sweep: tuple[float, ...] = setting(
        (),
        "Amplitudes of the kind's parameter (lateral, curvature, …) to run, each from the same "
        "tensioned state, into <folder>/<parameter>_<amplitude>/, with sweep.csv beside them; "
        "[] runs the amplitude alone.",
        read=_amplitudes,
        schema={
            "type": "array",
            "items": {"type": "number", "exclusiveMinimum": 0},
            "uniqueItems": True,
        },
    )
    by_kind: Mapping[str, Any] = field(default=_NO_KINDS, hash=False)


#: PETSc's line searches for Newton (``[steps] line_search``)
LINE_SEARCHES = ("cp", "basic", "bt", "l2")
#: ``[steps] control``: growth after easy solves, or the predictor-miss controller (``ErrorControl``)
STEP_CONTROLS = ("growth", "error")


@dataclass(frozen=True, kw_only=True)
class StepSettings(WithKinds):
    """The load steps and the Newton solves."""

    tension: float = setting(
        1e3,
        "First tension increment (grows ×growth after easy steps); the first step closes "
        "every contact pair without friction, so its size sets the wire forces' load-step "
        "error (benchmarks/window.py).",
        unit="N",
    )
    growth: float = setting(
        1.5, "The next increment over this one after a step of at most 6 iterations."
    )
    cuts: int = setting(6, "Halvings allowed before a step is declared failed.")
    max_iterations: int = setting(12, "Newton iterations per attempt.")
    stall: bool = setting(
        True,
        "Cut an attempt whose residual has not halved in two iterations (from the 4th on): it "
        "would not converge (false: run to the limit; NewtonOptions.stall_after).",
    )
    line_search: str = setting(
        "cp",
        "Newton's line search: PETSc's cp (critical point: one secant step along each Newton "
        "direction), or basic (full steps), bt, l2 (NewtonOptions.linesearch, docs/theory.md "
        "§6).",
        choices=LINE_SEARCHES,
    )
    tolerance: float = setting(
        1e-2, "Absolute residual tolerance (2.5e-7 of Cardinal's 40 kN).", unit="N"
    )
    balance: float = setting(
        1e-4,
        "Also converged when every node is in balance to this fraction of the mean wire "
        "tension T/n; 0: off. No node out of balance by more than that (66 mN for Cardinal at "
        "40 kN), nor by that force × the largest wire diameter in moment "
        "(NewtonOptions.force_tol).",
        sign="zero_is_off",
    )
    control: str = setting(
        "growth",
        "growth: ×growth after easy solves; error: from the predictor's miss (ErrorControl).",
        choices=STEP_CONTROLS,
    )
    error_tolerance: float = setting(
        1e-6, "Error control: the predictor's miss aimed at by each step.", unit="m"
    )
    retry: bool = setting(
        True,
        "Try a failed increment again from the other starting guess (the predictor or the "
        "last converged state), then halve it; each halved increment likewise.",
    )
    predictor: bool = setting(
        True,
        "Start each Newton solve of a ramp (tension, legs) from the secant predictor of its "
        "last step; false: from the last converged state.",
    )
    iteration: str = setting(
        "newton",
        "newton: an LU per iteration; reuse_lu: GMRES on each Jacobian with an earlier one's "
        "LU; lbfgs: L-BFGS on a solve's first LU; either falls back to Newton when it fails "
        "(NewtonOptions.iteration, docs/theory.md §6).",
        choices=_iterations,
    )
    stabilise: float = setting(
        1e4,
        "Springs (per pair) on every contact pair's slip for a step whose cuts are exhausted; "
        "0: off. The step is tried again with them (near-mechanisms: wires rolling round the "
        "layer below), and they are released when it converges; their energy over the strain "
        "energy is reported (Stabiliser).",
        unit="N/m",
        sign="zero_is_off",
    )
    held_onset: float = setting(
        1e-6,
        "A second hold, where the springs' own cuts are exhausted too: the same-layer "
        "pairs' normal law rises from first touch over this approach by a cubic, exact beyond "
        "it (CubicOnset), so that neighbours of a packed layer at nanometre gaps stop opening "
        "and closing every iteration; the force it leaves out is counted with the springs' "
        "energy. 0: no second hold (none either with stabilise = 0).",
        unit="m",
        sign="zero_is_off",
    )
    relax: float = setting(
        0.0,
        "A third hold, where the second's cuts are exhausted too: the step solved by "
        "pseudo-transient continuation, every free node held by a spring of this first "
        "stiffness (× the largest wire diameter² on the rotations) to where the last solve "
        "left it, stiffer after a failed solve, softer as the strand comes to rest, until the "
        "step converges without it: an equilibrium of the strand itself, for a tangent that "
        "is not positive (past a buckling; Stabiliser.relaxed_solve). 0 (the default): none; "
        "1e5 to try it; it needs stabilise > 0. Off by default: on a buckling core (1 m of "
        "Cardinal, ring vaulted, before the bending set-up held it centred) it did not come "
        "to rest in 100 pseudo-time steps (design notes 2026-11-29, last).",
        unit="N/m",
        sign="zero_is_off",
    )
    by_kind: Mapping[str, Any] = field(default=_NO_KINDS, hash=False)


@dataclass(frozen=True)
class OutputSettings:
    """What a run writes, and where."""

    folder: str = setting(
        "results/cardinal",
        "The results folder; for a case file: results/<file name without .toml>.",
    )
    fields: bool = setting(True, "Field time series: XDMF (+ HDF5) for ParaView and meshio.")
    vtx: bool = setting(
        True, "With fields: also VTX (ADIOS2 .bp; as large again, ~250 MB for Cardinal)."
    )
    plots: bool = setting(True, "PNG figures at the end.")
    checkpoint: bool = setting(
        True,
        "checkpoint.h5: the last converged state (strand run --restart), and tensioned.h5: the "
        "state before the cycle (3.4 MB each for Cardinal).",
    )


@dataclass(frozen=True)
class Case:
    cable: Cable
    mesh: MeshSettings = field(default_factory=MeshSettings)
    contact: ContactSettings = field(default_factory=ContactSettings)
    load: LoadSettings = field(default_factory=LoadSettings)
    steps: StepSettings = field(default_factory=StepSettings)
    output: OutputSettings = field(default_factory=OutputSettings)
    fatigue: FatigueSettings = field(default_factory=FatigueSettings)
    source: str = "built-in default"
    #: the ``[load]`` settings a run needs that the case leaves at their defaults (Cardinal's)
    #: although its cable is not a built-in one (``check_loads_given``)
    unset_loads: tuple[str, ...] = ()


#: the sections of a case file after ``cable``, and their settings classes
SECTIONS = {
    "mesh": MeshSettings,
    "contact": ContactSettings,
    "load": LoadSettings,
    "steps": StepSettings,
    "output": OutputSettings,
    "fatigue": FatigueSettings,
}
