"""The files of a run's folder, each named with what it holds: the folder's ``README.txt``.

Every column, unit and meaning is in the outputs reference, docs/outputs.md; this file is the
short list a folder carries with it.
"""

from __future__ import annotations

from pathlib import Path

__all__ = ["OUTPUTS", "OUTPUTS_REFERENCE", "folder_readme", "write_folder_readme"]

#: where every file, column and unit is described
OUTPUTS_REFERENCE = "docs/outputs.md"

#: what each file a run may write holds (the set-up kind, the settings and the outcome decide
#: which are there)
OUTPUTS = {
    "case.toml": "the whole case of the run, every setting and the cable written out, with the "
    "strand version: `strand run case.toml --out <new folder>` runs it again",
    "README.txt": "this list",
    "summary.txt": "the outcome, effort, the tensioned state against the fibre model, the "
    "set-up's own results and any warning",
    "steps.csv": "one row per converged load step: stage, programme time, loads, the set-up's "
    "measures, Newton iterations, residual (N), wall time (s)",
    "axial_forces.csv": "the axial force (N) of every element at every step, with its wire, "
    "layer, height z (m) and angle",
    "moment_curvature.csv": "the set-up's section measures (bending moment, curvature, axial "
    "sum) at every step of the cycle",
    "slip.csv": "per interface, the share of contact pairs slipping in the measuring zone, at "
    "every step",
    "fields.xdmf": "field time series for ParaView (with fields.h5): displacement, rotation, "
    "section forces, wire and layer ids; time t = k to k + 1 is stage k of steps.csv",
    "fields.h5": "the data of fields.xdmf",
    "fields_loads.csv": "the set-up's loads at every frame of the field series (t = 0 the "
    "unloaded strand, then each step of steps.csv)",
    "fields.bp": "the same fields as VTX (ADIOS2), a folder: ParaView",
    "contact_pairs.h5": "every contact pair's history: gap, normal force, traction, slip",
    "contact_points.xdmf": "the contact pairs' history as points, for ParaView",
    "wire_sections.h5": "every element's section forces (axial force, bending moments, torque) "
    "and spin, at the tensioned state and every cycle step",
    "checkpoint.h5": "the last converged state: `strand run <case> --restart checkpoint.h5`",
    "tensioned.h5": "the state after tension, before the cycle (a restart point)",
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


def folder_readme(folder: str | Path) -> str:
    """The ``README.txt`` of a run's ``folder``: each file and folder at its top, with what it
    holds."""
    folder = Path(folder)
    names = sorted({*(p.name for p in folder.iterdir() if not p.name.startswith(".")),
                    "README.txt"})  # fmt: skip
    width = max(len(n) for n in names)
    lines = [
        "The files of this strand run. Every column, unit and meaning: the outputs reference,",
        f"{OUTPUTS_REFERENCE} in strand's documentation.",
        "",
    ]
    for name in names:
        what = OUTPUTS.get(name, "a sub-folder: a run of its own" if (folder / name).is_dir()
                           else "")  # fmt: skip
        lines.append(f"{name:<{width}}  {what}".rstrip())
    return "\n".join(lines) + "\n"


def write_folder_readme(folder: str | Path) -> Path:
    """Write ``folder``'s ``README.txt`` (``folder_readme``); returns its path."""
    path = Path(folder) / "README.txt"
    path.write_text(folder_readme(folder))
    return path
