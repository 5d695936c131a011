"""Settings declared once: a field of a frozen settings dataclass carries its unit, meaning, sign
rule and choices in its metadata (``setting``), and everything else is read from there: one
generic reader of a value (``read_value``), the check of a settings object built in code
(``check_declared``), and, in the application, the case file's reader, ``strand run --help``,
the settings reference, the case template, ``case.toml`` and the JSON Schema of a case file
(``strand.app.settings_schema``).

A number is positive unless its ``sign`` says otherwise: "any" (zero and negative allowed: a
signed setting, or one its set-up kind checks itself), "zero_is_off" (≥ 0, 0: off or not given)
or "count" (a whole number ≥ 0). A number whose default is an ``int`` takes whole numbers only.
Units: SI, as each setting names them.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable, Mapping
from dataclasses import MISSING, Field, dataclass, field, fields
from typing import Any

__all__ = [
    "Declared",
    "SettingError",
    "setting",
    "declared",
    "choices_text",
    "read_value",
    "check_declared",
]

#: the sign rules of a number (``Declared.sign``)
SIGNS = ("positive", "any", "zero_is_off", "count")


class SettingError(ValueError):
    """A value refused by its declaration, in one line naming the setting."""


@dataclass(frozen=True)
class Declared:
    """What a setting is, beside its type and default (``setting``).

    Attributes:
        doc: its meaning, as the settings reference gives it; its first sentence (to the first
            full stop outside brackets) is the summary of ``strand run --help`` and the case
            template.
        unit: its SI unit ("" for a ratio, a count or a setting that is not a number).
        sign: a number's sign rule (``SIGNS``).
        choices: the strings it may take, or a function giving them (registered names, or
            names of a module better imported only when a case is read).
        read: a reader of its value ``read(where, value)`` for a value that is more than a
            boolean, a number, a string or a list of numbers (``where``: the setting and value,
            for the error), checking what the type does not.
        schema: the JSON Schema of its value where the type's is not enough (with ``read``).
    """

    doc: str
    unit: str = ""
    sign: str = "positive"
    choices: tuple[str, ...] | Callable[[], Iterable[str]] | None = None
    read: Callable[[str, Any], Any] | None = None
    schema: Mapping[str, Any] | None = None

    def __post_init__(self):
        if self.sign not in SIGNS:
            raise ValueError(f"sign {self.sign!r}: choose one of {SIGNS}")

    def allowed(self) -> tuple[str, ...]:
        """The strings the setting may take (``choices``, called if a function); () for any."""
        if self.choices is None:
            return ()
        return tuple(self.choices() if callable(self.choices) else self.choices)

    @property
    def summary(self) -> str:
        """The meaning's first sentence (``doc``)."""
        return first_sentence(self.doc)


def setting(
    default: Any,
    doc: str,
    *,
    unit: str = "",
    sign: str = "positive",
    choices: tuple[str, ...] | Callable[[], Iterable[str]] | None = None,
    read: Callable[[str, Any], Any] | None = None,
    schema: Mapping[str, Any] | None = None,
) -> Any:
    """A dataclass field of a settings class: ``default`` (immutable), with its meaning
    ``doc``, ``unit``, ``sign`` rule, ``choices``, a ``read``\\ er and ``schema`` of its own
    (``Declared``)."""
    meta = Declared(doc, unit, sign, choices, read, schema)
    return field(default=default, metadata={"setting": meta})


def declared(f: Field) -> Declared | None:
    """The declaration of the dataclass field ``f``; None for a field that is no setting."""
    return f.metadata.get("setting")


def default_of(f: Field) -> Any:
    """The default of the dataclass field ``f`` (``MISSING`` if none)."""
    if f.default is not MISSING:
        return f.default
    if f.default_factory is not MISSING:
        return f.default_factory()
    return MISSING


def first_sentence(text: str, stops: str = ".") -> str:
    """``text`` up to its first full stop (or other of ``stops``) followed by a space, outside
    brackets."""
    depth = 0
    for i, c in enumerate(text):
        depth += (c in "([") - (c in ")]")
        if c in stops and depth == 0 and text[i + 1 : i + 2] == " ":
            return text[: i + 1].rstrip(";")
    return text


def choices_text(choices: Iterable[str]) -> str:
    """``a, b or c``."""
    *others, last = choices
    return f"{', '.join(others)} or {last}" if others else last


def _number(where: str, value: Any, default: int | float, sign: str) -> int | float:
    if isinstance(value, bool) or not isinstance(value, int | float) or not math.isfinite(value):
        raise SettingError(f"{where}: expected a number")
    if sign == "count":
        if not (isinstance(value, int) and value >= 0):
            raise SettingError(f"{where}: expected a whole number ≥ 0")
        return value
    if isinstance(default, int) and not float(value).is_integer():
        raise SettingError(f"{where}: expected a whole number")
    if sign == "zero_is_off" and value < 0:
        raise SettingError(f"{where}: expected a positive number, or 0 for off")
    if sign == "positive" and not value > 0:
        raise SettingError(f"{where}: expected a positive number")
    return type(default)(value)


def numbers(where: str, value: Any) -> tuple[float, ...]:
    """A list of numbers as a tuple of floats (``SettingError`` otherwise)."""
    if not isinstance(value, list) or not all(
        isinstance(v, int | float) and not isinstance(v, bool) for v in value
    ):
        raise SettingError(f"{where}: expected a list of numbers")
    return tuple(float(v) for v in value)


def _string(where: str, value: Any, meta: Declared) -> str:
    if not isinstance(value, str):
        raise SettingError(f"{where}: expected a string")
    allowed = meta.allowed()
    if allowed and value not in allowed:
        raise SettingError(f"{where} is unknown; choose {choices_text(allowed)}")
    return value


def read_value(where: str, value: Any, default: Any, meta: Declared) -> Any:
    """``value`` of a setting declared ``meta`` with ``default``, checked (``SettingError``
    starting with ``where``, the setting and value as a case file gives them) and of the
    default's type."""
    if meta.read is not None:
        return meta.read(where, value)
    if isinstance(default, bool):
        if not isinstance(value, bool):
            raise SettingError(f"{where}: expected true or false")
        return value
    if isinstance(default, int | float):
        return _number(where, value, default, meta.sign)
    if isinstance(default, tuple):
        return numbers(where, value)
    if isinstance(default, str):
        return _string(where, value, meta)
    raise TypeError(f"{where}: no reader for a default {default!r}; declare one (read=)")


def where_text(prefix: str, key: str, value: Any, unit: str) -> str:
    """How an error names a setting and its value: ``<prefix><key> = <value> <unit>``."""
    shown = f"{prefix}{key} = {value!r}"
    return f"{shown} {unit}" if unit and isinstance(value, int | float) else shown


def check_declared(settings: Any, prefix: str = "") -> None:
    """Check every declared field of the dataclass instance ``settings`` that differs from its
    default (the defaults are valid: the tests check them) by ``read_value``, for settings made
    in code rather than read from a case file; ``prefix`` starts each setting's name in the
    error ("contact ")."""
    for f in fields(settings):
        meta, default = declared(f), default_of(f)
        value = getattr(settings, f.name)
        if meta is None or (type(value) is type(default) and value == default):
            continue
        read_value(where_text(prefix, f.name, value, meta.unit), value, default, meta)
