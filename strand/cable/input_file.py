"""Reading a user's input file (case, cable, load history) with one-line errors."""

from __future__ import annotations

from pathlib import Path

__all__ = ["read_text"]


def read_text(path: Path, kind: str, error: type[Exception], missing: str = "file") -> str:
    """The text of ``path``; a file that is missing, a folder, not text or unreadable raises
    ``error`` with one line naming it: "<path>: no such <missing>", "<path>: is a folder; give a
    <kind>", and so on (``kind`` e.g. "case file (TOML)")."""
    try:
        return path.read_text()
    except FileNotFoundError:
        raise error(f"{path}: no such {missing}") from None
    except IsADirectoryError:
        raise error(f"{path}: is a folder; give a {kind}") from None
    except UnicodeDecodeError:
        raise error(f"{path}: not a text file; give a {kind}") from None
    except OSError as e:
        raise error(f"{path}: cannot be read ({e.strerror})") from None
