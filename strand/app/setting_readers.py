"""Readers and JSON Schema fragments of the case settings whose values need more than their
declaration (``strand.beam.setting.setting(read=..., schema=...)``): the tension, the cycle, the
direction, the sweep's amplitudes and the fatigue spectrum; and the choices read when a case is."""

from __future__ import annotations

from typing import Any

from ..beam.setting import Declared, SettingError, numbers, read_value


def _iterations() -> tuple[str, ...]:
    """``[steps] iteration``'s choices (``NewtonOptions.iteration``), read when a case is."""
    from ..solver.convergence import ITERATIONS

    return ITERATIONS


def _tension(where: str, value: Any) -> float:
    number = read_value(where, value, 0.0, Declared("", sign="any"))
    if not number > 0:
        raise SettingError(
            f"{where}: expected a positive tension; a compressed strand is outside the model "
            "(its wires buckle and its contact pairs open)"
        )
    return number


def _cycle(where: str, value: Any) -> tuple[float, ...]:
    targets = numbers(where, value)
    if not targets:
        raise SettingError(f"{where}: expected at least one lateral target")
    return targets


def _direction(where: str, value: Any) -> tuple[float, ...]:
    d = numbers(where, value)
    if len(d) != 3 or d[2] != 0 or d[:2] == (0, 0):
        raise SettingError(f"{where}: expected [x, y, 0], a direction across the strand axis")
    return d


def _amplitudes(where: str, value: Any) -> tuple[float, ...]:
    sweep = numbers(where, value)
    if not all(v > 0 for v in sweep):
        raise SettingError(f"{where}: expected positive amplitudes (the cycle gives the signs)")
    if len(set(sweep)) != len(sweep):
        raise SettingError(f"{where}: an amplitude is listed twice")
    return sweep


def _spectrum(where: str, value: Any) -> tuple[tuple[float, float], ...]:
    """``[fatigue] spectrum``: the list ``[[amplitude, cycles], ...]``, or the table
    ``[fatigue.spectrum]`` with that list as ``classes`` (``strand spectrum``'s block)."""
    from ..fatigue.spectrum import spectrum_classes

    if isinstance(value, dict):
        if set(value) != {"classes"}:
            raise SettingError(
                f"[fatigue.spectrum]: expected the one key classes = [[amplitude, cycles], ...]; "
                f"got {sorted(value)}"
            )
        value = value["classes"]
    try:
        return spectrum_classes(value)
    except ValueError as e:
        raise SettingError(f"[fatigue] spectrum: {e}") from None


_PAIRS = {
    "type": "array",
    "items": {"type": "array", "items": {"type": "number"}, "minItems": 2, "maxItems": 2},
}
_SPECTRUM = {
    "anyOf": [
        _PAIRS,
        {
            "type": "object",
            "properties": {"classes": _PAIRS},
            "required": ["classes"],
            "additionalProperties": False,
        },
    ]
}
