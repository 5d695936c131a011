"""The files of a run's folder, each named with what it holds: the folder's ``README.txt``.

Every column, unit and meaning is in the outputs reference, docs/outputs.md; this file is the
short list a folder carries with it.
"""

from __future__ import annotations

from pathlib import Path

from .outputs import registered_outputs

__all__ = ["OUTPUTS_REFERENCE", "outputs", "folder_readme", "write_folder_readme"]

#: where every file, column and unit is described
OUTPUTS_REFERENCE = "docs/outputs.md"


def outputs() -> dict[str, str]:
    """What each file a run may write holds: the files of every registered output
    (``strand.app.outputs``)."""
    return {name: what for output in registered_outputs() for name, what in output.files.items()}


def folder_readme(folder: str | Path) -> str:
    """The ``README.txt`` of a run's ``folder``: each file and folder at its top, with what it
    holds."""
    folder = Path(folder)
    names = sorted(
        {*(p.name for p in folder.iterdir() if not p.name.startswith(".")), "README.txt"}
    )
    width = max(len(n) for n in names)
    lines = [
        "The files of this strand run. Every column, unit and meaning: the outputs reference,",
        f"{OUTPUTS_REFERENCE} in strand's documentation.",
        "",
    ]
    described = outputs()
    for name in names:
        what = described.get(
            name, "a sub-folder: a run of its own" if (folder / name).is_dir() else ""
        )
        lines.append(f"{name:<{width}}  {what}".rstrip())
    return "\n".join(lines) + "\n"


def write_folder_readme(folder: str | Path) -> Path:
    """Write ``folder``'s ``README.txt`` (``folder_readme``); returns its path."""
    path = Path(folder) / "README.txt"
    path.write_text(folder_readme(folder))
    return path
