"""The results folder of a run: checked before any computing, written only once the run can
start, never shared by two runs.

A run owns the files at the top of its folder (``case.toml``, the whole case written first, marks
them as a run's; ``settings.txt`` marks an older strand's run). A second
run into a folder that holds a run is refused unless asked to ``overwrite``, which first removes
the earlier run's files (and its ``*.bp`` field folders), so that no figure or field of one run
can sit beside another run's tables. Sub-folders (another run's own folder, e.g. a comparison's)
are left alone. A folder holding other files is never written into.

``check_results_folder`` gives the verdict without touching anything (a run asks it first, then
builds its strand); ``prepare_results_folder`` then creates or empties the folder, so that a
case that fails while it is built leaves the folder as it was.
"""

from __future__ import annotations

import os
import shutil
from pathlib import Path

__all__ = [
    "FolderError",
    "RUN_MARKER",
    "check_results_folder",
    "check_writable",
    "prepare_results_folder",
    "writable_folder",
]

#: the file every run writes first into its folder
RUN_MARKER = "case.toml"
#: the file older strand versions wrote first instead
_OLD_MARKERS = ("settings.txt",)


class FolderError(ValueError):
    """A results folder that cannot be used; the message names it and says what to do."""


def writable_folder(folder: str | Path) -> Path:
    """Create ``folder`` if needed and check that files can be written in it; raise
    ``FolderError`` naming the problem otherwise."""
    folder = Path(folder)
    if folder.exists() and not folder.is_dir():
        raise FolderError(f"{folder}: is a file, not a folder; give a results folder")
    try:
        folder.mkdir(parents=True, exist_ok=True)
    except OSError as e:
        raise FolderError(f"{folder}: cannot create the results folder ({e.strerror})") from None
    probe = folder / ".strand-write-test"
    try:
        probe.write_text("")
        probe.unlink()
    except OSError as e:
        raise FolderError(f"{folder}: the results folder is not writable ({e.strerror})") from None
    return folder


def _owned(folder: Path) -> list[Path]:
    """The files (and ``*.bp`` field folders) at the top of ``folder`` that a run owns."""
    return [
        p
        for p in folder.iterdir()
        if not p.name.startswith(".") and (p.is_file() or p.suffix == ".bp")
    ]


def check_writable(folder: str | Path) -> Path:
    """Raise ``FolderError`` (naming the problem) where ``writable_folder`` would: ``folder`` is
    a file, or it (or, not there yet, the folder it would be created in) is not writable; write
    and create nothing."""
    folder = Path(folder)
    if folder.exists() and not folder.is_dir():
        raise FolderError(f"{folder}: is a file, not a folder; give a results folder")
    if not folder.exists():
        parent = next(p for p in folder.absolute().parents if p.exists())
        if not parent.is_dir():
            raise FolderError(f"{folder}: cannot create the results folder ({parent} is a file)")
        if not os.access(parent, os.W_OK | os.X_OK):
            raise FolderError(
                f"{folder}: cannot create the results folder ({parent} is not writable)"
            )
        return folder
    if not os.access(folder, os.W_OK | os.X_OK):
        raise FolderError(f"{folder}: the results folder is not writable (Permission denied)")
    return folder


def check_results_folder(folder: str | Path, overwrite: bool = False) -> Path:
    """Raise ``FolderError`` (naming the problem) where ``prepare_results_folder`` would; write,
    create and remove nothing."""
    folder = check_writable(folder)
    if folder.is_dir() and _owned(folder):
        if not any((folder / m).is_file() for m in (RUN_MARKER, *_OLD_MARKERS)):
            raise FolderError(
                f"{folder}: holds files that are not a strand run's; give a new or empty folder"
            )
        if not overwrite:
            raise FolderError(
                f"{folder}: holds the results of an earlier run; give another folder (--out) "
                "or replace them (--overwrite)"
            )
    return folder


def prepare_results_folder(folder: str | Path, overwrite: bool = False) -> Path:
    """Create ``folder`` (or empty it of an earlier run's files when ``overwrite``) and check
    that it is writable; raise ``FolderError`` naming the problem otherwise."""
    check_results_folder(folder, overwrite)
    folder = writable_folder(folder)
    try:
        for p in _owned(folder):
            shutil.rmtree(p) if p.is_dir() else p.unlink()
    except OSError as e:
        raise FolderError(
            f"{folder}: cannot remove the earlier run's {Path(e.filename).name} ({e.strerror})"
        ) from None
    return folder
