"""The files of a run's folder, each named with what it holds: the folder's ``README.txt``.

Every column, unit and meaning is in the outputs reference, docs/outputs.md; this file is the
short list a folder carries with it.
"""

from __future__ import annotations

from pathlib import Path

from .outputs import registered_outputs

__all__ = ["OUTPUTS", "OUTPUTS_REFERENCE", "outputs", "folder_readme", "write_folder_readme"]

#: where every file, column and unit is described
OUTPUTS_REFERENCE = "docs/outputs.md"

#: what each file a run writes outside its recorders holds (the set-up kind, the settings and the
#: outcome decide which are there); the recorders' files: ``outputs``
OUTPUTS = {
    "case.toml": "the whole case of the run, every setting and the cable written out, with the "
    "strand version: `strand run case.toml --out <new folder>` runs it again",
    "README.txt": "this list",
    "summary.txt": "the outcome, effort, the tensioned state against the fibre model, the "
    "set-up's own results and any warning",
    "fatigue.txt": "the fatigue report: stress ranges, S-N damage, fretting",
    "crossings.csv": "fatigue: per contact pair, the worst cycle's slip amplitude and forces",
    "wire_stresses.csv": "fatigue: per element, the surface stresses at its point of largest "
    "stress range (range, mean, peak) and their damage",
    "wires.csv": "fatigue: per wire, the largest stress range and its damage",
    "load_deflection.png": "figure: load against deflection over the cycle",
    "moment_curvature.png": "figure: bending moment against curvature",
    "axial_force_sectors.png": "figure: wire axial forces per layer and sector",
    "axial_force_change.png": "figure: change of wire axial forces over the cycle",
    "deformed_axial_force.png": "figure: the deformed strand coloured by axial force "
    "(displacements magnified, factor in the title)",
    "fretting_map.png": "figure: the contact pairs that slid, per interface",
    "stress_range.png": "figure: stress ranges against the S-N curve",
    "layer_pressure.png": "figure: per layer, its pressure on the crossings below, its "
    "same-layer ring's share and the fibre model, tensioned and at the peak",
}


def outputs() -> dict[str, str]:
    """What each file a run may write holds: ``OUTPUTS`` and the files of every registered
    output (``strand.app.outputs``)."""
    files = dict(OUTPUTS)
    for output in registered_outputs():
        files.update(output.files)
    return files


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
