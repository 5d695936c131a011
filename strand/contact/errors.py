"""The error of the contact package: input its builders cannot use, named in one line."""

from __future__ import annotations

__all__ = ["ContactError"]


class ContactError(ValueError):
    """Contact input that cannot be built: an unknown choice, a node on no beam, a bad reach."""
