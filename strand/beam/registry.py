"""A registry: named entries in the order registered, with one vocabulary and one rule for every
registry of strand (the set-up kinds, the contact compliances, a run's outputs). ``register``
refuses a name that is taken (``ValueError``: ``unregister`` it first), ``unregister`` takes one
out, ``names`` and ``entries`` list them in order, and ``lookup`` finds one by name or raises a
``KeyError`` that lists the names there are."""

from __future__ import annotations

__all__ = ["Registry"]


class Registry[T]:
    """Entries of type ``T`` by name, in the order registered; ``what`` names an entry in
    messages ("set-up kind", "compliance", "output")."""

    def __init__(self, what: str) -> None:
        self.what = what
        self._entries: dict[str, T] = {}

    def register(self, name: str, entry: T) -> T:
        """Keep ``entry`` under ``name``; ``ValueError`` if the name is taken."""
        if name in self._entries:
            article = "an" if self.what[:1] in tuple("aeiou") else "a"
            raise ValueError(f"{article} {self.what} named {name!r} is registered already")
        self._entries[name] = entry
        return entry

    def unregister(self, name: str) -> None:
        """Take the entry ``name`` out; ``KeyError`` if there is none."""
        del self._entries[name]

    def names(self) -> tuple[str, ...]:
        """The names, in the order registered."""
        return tuple(self._entries)

    def entries(self) -> tuple[T, ...]:
        """The entries, in the order registered."""
        return tuple(self._entries.values())

    def lookup(self, name: str) -> T:
        """The entry ``name``; a ``KeyError`` naming the registered ones if there is none."""
        try:
            return self._entries[name]
        except KeyError:
            known = ", ".join(self._entries) or "none"
            raise KeyError(f"no {self.what} named {name!r}; registered: {known}") from None

    def __contains__(self, name: object) -> bool:
        return name in self._entries
