"""``CaseError``: a case that cannot be used. It sits below everything that raises it (the case
file's reading, ``strand.app.case``; the checks across settings, ``strand.app.checks``; the set-up
kinds, ``strand.app.kinds``, and their registry, ``strand.app.kind_registry``) and imports
nothing."""

from __future__ import annotations

__all__ = ["CaseError"]


class CaseError(ValueError):
    """A case file that cannot be used; the message names the file and the setting."""
