"""The checks of a whole case, across its sections: the load steps and the loads, the mesh against
the span, the set-up kind's own checks, the fatigue curves and layers, and a ``[fatigue] spectrum``
run as the ``[load] sweep``; and the warning a run gives for a tension far from the strand's
breaking strength (``tension_warning``).

``strand.app.case`` reads each setting and checks it alone against its declaration (type, sign,
choices); ``checked_case`` then
checks the settings against one another and against the cable, before any computing. It sits
above the set-up kinds (``strand.app.kinds``), whose checks it runs, and below
``strand.app.case``, which calls it when it reads a case.
"""

from __future__ import annotations

from dataclasses import replace
from typing import TYPE_CHECKING

from ..cable.description import Cable, CableError
from ..model.layer_states import first_layer_lift
from . import kinds
from .errors import CaseError
from .settings import Case, FatigueSettings

if TYPE_CHECKING:
    from .kinds import SetupKind

__all__ = ["checked_case", "h_max_range", "tension_warning", "TENSION_SHARES"]

#: elements no shorter than the thinnest wire's diameter over this: a beam (a wire's centre line
#: and section) holds nothing shorter than its diameter, and finer elements only add unknowns
#: (the default 4 mm is 1.2 diameters of Cardinal's wires, a convergence check's half 0.6)
_FINEST = 10
#: elements no longer than the shortest lay length over this: the two-node elements draw each
#: turn of a helix as a polygon of at least this many sides, whose chords stray from the helix
#: by at most r (1 − cos(π/8)) = 7.6 % of its radius
_TURN = 8


#: a ``[load] tension`` outside these shares of the strand's breaking strength is warned of:
#: under 1 %, likely a tension in kN read as N; over 100 %, the strand would break
TENSION_SHARES = (0.01, 1.0)


def h_max_range(cable: Cable) -> tuple[float, float]:
    """The ``[mesh] h_max`` (m) a run of ``cable`` accepts (``_FINEST``, ``_TURN``)."""
    thinnest = min(layer.wire.diameter for layer in cable.layers)
    shortest = min(layer.pitch for layer in cable.layers)
    return thinnest / _FINEST, shortest / _TURN


def checked_case(case: Case) -> tuple[Case, SetupKind]:
    """``case`` with the amplitudes of a ``[fatigue] spectrum`` as its ``[load] sweep``, every
    setting checked against the others and the cable (``CaseError`` naming ``case.source``),
    and its set-up kind (``kinds.kind_of``), resolved once here for the checks and the reader."""
    try:
        case = _spectrum_sweep(case)
        kind = _check_steps_and_load(case)
        _check_fatigue(case.fatigue, case.cable)
        _check_contact(case)
    except CaseError as e:
        raise CaseError(f"{case.source}: {e}") from None
    return case, kind


def _check_steps_and_load(case: Case) -> SetupKind:
    """The checks of the load steps, the mesh and the loads; the case's set-up kind."""
    steps, load, mesh = case.steps, case.load, case.mesh
    for kind in kinds.registered():  # every kind's own settings, whichever the case's
        kind.check_settings(load.by_kind[kind.name], steps.by_kind[kind.name])
    if mesh.h_max >= mesh.length:
        raise CaseError(
            f"[mesh] h_max = {mesh.h_max} m must be shorter than the span [mesh] length = "
            f"{mesh.length} m"
        )
    low, high = h_max_range(case.cable)
    if not low <= mesh.h_max <= high:
        raise CaseError(
            f"[mesh] h_max = {mesh.h_max:g} m is out of range [{low:.3g}, {high:.3g}] m for this "
            f"cable: from the thinnest wire's diameter / {_FINEST} (a beam resolves nothing "
            f"shorter) to the shortest lay length / {_TURN} (a helix needs {_TURN} elements a turn)"
        )
    if steps.relax > 0 and steps.stabilise <= 0:
        raise CaseError(
            f"[steps] relax = {steps.relax:g} N/m needs [steps] stabilise > 0: the relaxation "
            "is the hold after the springs' (set stabilise, 1e4 by default, or relax = 0)"
        )
    kind = kinds.kind_of(case)
    kind.check_case(case)
    if load.sweep and not any(load.cycle):
        raise CaseError(
            f"[load] sweep = {list(load.sweep)} needs a cycle with a target other than 0 "
            f"(cycle = {list(load.cycle)} stays at zero load)"
        )
    return kind


def _check_contact(case: Case) -> None:
    try:
        first_layer_lift(case.cable, case.contact.first_layer)
    except CableError as e:
        raise CaseError(f"[contact] {e}") from None


def _check_fatigue(fatigue: FatigueSettings, cable: Cable) -> None:
    if fatigue.uses_user_curve():
        _check_user_curve(fatigue)
    try:
        fatigue.curve()
    except ValueError as e:
        raise CaseError(f"[fatigue] {e}") from None
    bad = [
        i for i in fatigue.sn_layers if not float(i).is_integer() or not 0 <= i < len(cable.layers)
    ]
    if bad:
        raise CaseError(
            f"[fatigue] sn_layers = {list(fatigue.sn_layers)}: layers are numbered 0 (core) to "
            f"{len(cable.layers) - 1}"
        )
    if fatigue.design_fatigue_factor < 1:
        raise CaseError(
            f"[fatigue] design_fatigue_factor = {fatigue.design_fatigue_factor:g}: expected 1 or "
            "more (it multiplies every damage; 1: none)"
        )
    _check_mean_stress(fatigue, cable)


def _check_user_curve(fatigue: FatigueSettings) -> None:
    """The user's own S–N curve complete and plausible (one line each)."""
    f = fatigue
    which = "sn_curve" if f.sn_curve == "user" else "steel_sn_curve"
    if not f.user_sn_m1 > 0:
        raise CaseError(
            f'[fatigue] {which} = "user" needs user_sn_m1, the slope m1 of N = a1 Δσ^-m1 up to '
            "the knee"
        )
    if bool(f.user_sn_log_a) == bool(f.user_sn_range):
        raise CaseError(
            f'[fatigue] {which} = "user" needs one intercept: user_sn_log_a (log10 a1, Δσ in '
            "MPa) or user_sn_range (Pa) at user_sn_cycles, "
            + ("not both" if f.user_sn_log_a else "none is given")
        )
    if f.user_sn_range and f.user_sn_range < 1e6:
        raise CaseError(
            f"[fatigue] user_sn_range = {f.user_sn_range:g} Pa is below 1 MPa: did you mean "
            f"{f.user_sn_range:g}e6 (Pa)?"
        )
    if f.user_sn_given != f.user_sn_use and not f.user_sn_sd > 0:
        raise CaseError(
            f'[fatigue] user_sn_use = "{f.user_sn_use}" from a {f.user_sn_given} curve needs '
            "user_sn_sd, the standard deviation of log10 N (the characteristic curve lies 2 of "
            "them below the mean)"
        )
    curve = f.user_curve()
    at_knee = 2 * curve.A * curve.knee**curve.b  # MPa
    if not 1 <= at_knee <= 1e4:
        raise CaseError(
            f"[fatigue] the user curve gives a range of {at_knee:.3g} MPa at its knee "
            f"({f.user_sn_knee:.3g} cycles), outside 1 to 10000 MPa: log10 a1 is for Δσ in MPa"
        )


def _check_mean_stress(fatigue: FatigueSettings, cable: Cable) -> None:
    """A known law, and the tensile strength of every assessed layer's wires, above the user
    curve's mean where that curve is corrected."""
    law = fatigue.mean_stress
    if law == "none":
        return
    missing = fatigue.unknown_strength(cable)
    if missing:
        raise CaseError(
            f"[fatigue] mean_stress = {law!r} needs the wires' tensile strength: the cable "
            f"{cable.name!r} gives none for layer(s) {missing} (tensile_strength, Pa, in the "
            "cable's tables)"
        )
    user = fatigue.user_curve() if fatigue.uses_user_curve() else None
    for i, (lay, curve) in enumerate(zip(cable.layers, fatigue.curves(cable), strict=True)):
        if curve is not None and curve == user:
            if not fatigue.user_sn_mean < lay.wire.tensile_strength:
                raise CaseError(
                    f"[fatigue] user_sn_mean = {fatigue.user_sn_mean:g} Pa is not below the "
                    f"tensile strength of layer {i}'s wires ({lay.wire.tensile_strength:g} Pa)"
                )


def _spectrum_sweep(case: Case) -> Case:
    """``case`` with the amplitudes of ``[fatigue] spectrum`` as its ``[load] sweep``: a
    spectrum runs as a sweep; refused where the sweep lists other amplitudes, or without the
    fatigue outputs, which give each amplitude's damage."""
    spectrum, sweep = case.fatigue.spectrum, case.load.sweep
    if not spectrum:
        return case
    amplitudes = tuple(a for a, _ in spectrum)
    if not case.fatigue.outputs:
        raise CaseError(
            "[fatigue] spectrum needs [fatigue] outputs = true (each amplitude's "
            "damage comes from its fatigue report)"
        )
    if not any(case.load.cycle):
        raise CaseError(
            f"[fatigue] spectrum needs a cycle with a target other than 0 (cycle = "
            f"{list(case.load.cycle)} stays at zero load)"
        )
    if sweep and sorted(sweep) != sorted(amplitudes):
        raise CaseError(
            f"[fatigue] spectrum amplitudes {list(amplitudes)} differ from [load] sweep = "
            f"{list(sweep)}; give the spectrum alone: it runs its amplitudes as the sweep"
        )
    return case if sweep else replace(case, load=case.load.with_values(sweep=amplitudes))


def _strength(case: Case) -> tuple[float, str] | None:
    """The breaking strength (N) the tension is held against, and what it is: ``[fatigue]
    breaking_strength`` where given, else the wires' aggregate tensile force Σ A σ_u where every
    layer gives its ``tensile_strength``, else their yield force Σ A σ_y where every layer gives
    its ``yield_stress`` (below the strand's break); None without any."""
    given = case.fatigue.breaking_strength
    if given > 0:
        return given, "breaking strength ([fatigue] breaking_strength)"
    layers = case.cable.layers
    for key, what in (
        ("tensile_strength", "wires' aggregate tensile force Σ A σ_u"),
        ("yield_stress", "wires' aggregate yield force Σ A σ_y"),
    ):
        if all(getattr(lay.wire, key) is not None for lay in layers):
            force = sum(lay.wires * lay.wire.area * getattr(lay.wire, key) for lay in layers)
            return force, f"{what} (no [fatigue] breaking_strength given)"
    return None


def tension_warning(case: Case) -> str:
    """One line where ``[load] tension`` lies outside ``TENSION_SHARES`` of the strand's
    breaking strength (``_strength``), naming both; "" otherwise, or without a strength."""
    strength = _strength(case)
    if strength is None:
        return ""
    force, what = strength
    tension = case.load.tension
    share = tension / force
    low, high = TENSION_SHARES
    if low <= share <= high:
        return ""
    why = "is it in kN? Forces are in N" if share < low else "the strand would break"
    return (
        f"[load] tension = {tension:g} N is {100 * share:.3g} % of the strand's {what}, "
        f"{force:.4g} N: {why}"
    )
