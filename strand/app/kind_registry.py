"""The registry of set-up kinds: the kinds by their ``[load] kind`` name, in the order registered.

It imports nothing but ``CaseError`` and the library's ``Registry``, so that what sits below the
kinds can read it: the settings take every registered kind's own settings from ``registered``;
the package ``strand.app.kinds`` registers the built-in kinds when it is imported. ``register``
(``strand.app.kinds.base``) checks a kind against the settings before it adds it here
(``add``)."""

from __future__ import annotations

from typing import Any

from ..beam.registry import Registry
from .errors import CaseError

__all__ = ["add", "unregister", "registered", "lookup"]

_KINDS: Registry[Any] = Registry("set-up kind")  # name → SetupKind


def add(kind: Any) -> Any:
    """Keep ``kind`` (a ``SetupKind``, checked by ``register``) under its name."""
    return _KINDS.register(kind.name, kind)


def unregister(name: str) -> None:
    """Take the kind ``name`` out of the registry."""
    _KINDS.unregister(name)


def registered() -> tuple[Any, ...]:
    """The registered kinds, in the order they were registered."""
    return _KINDS.entries()


def lookup(name: str) -> Any:
    """The kind ``name``; a ``CaseError`` naming the known kinds if there is none."""
    if name not in _KINDS:
        *others, last = _KINDS.names()
        choices = f"{', '.join(others)} or {last}" if others else last
        raise CaseError(f"[load] kind = {name!r} is unknown; choose {choices}")
    return _KINDS.lookup(name)
