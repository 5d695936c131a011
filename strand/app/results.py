"""Reading a run's field series back in Python: ``fields.xdmf`` (+ ``fields.h5``) per step, as
meshio meshes or PyVista grids.

PyVista's own ``pyvista.read("fields.xdmf")`` goes through VTK's XDMF reader, which crashes the
interpreter with the VTK 9.7 of the pyvista wheels; this reader takes the arrays with meshio and
h5py instead, and hands PyVista grids built from them (``pyvista.from_meshio``). ParaView opens
the XDMF file itself.

>>> from strand.app.results import read_fields                                 # doctest: +SKIP
>>> steps = read_fields("results/quick_1x6", pyvista=True)                 # doctest: +SKIP
>>> steps[-1].mesh.warp_by_vector("displacement").plot()                   # doctest: +SKIP

Every step carries its programme time (``steps.csv``'s ``time``: stage k runs from t = k to
k + 1), the number of its row in ``steps.csv`` (0 for the unloaded strand at t = 0 that opens
the series of a run from the start) and the set-up's loads there (``fields_loads.csv``). Arrays
and units as in docs/outputs.md: points ``displacement`` (m) and ``rotation`` (rad); cells
``force`` (N), ``moment`` (N m), ``axial_force`` (N), ``wire``, ``layer``.
"""

from __future__ import annotations

import csv
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

__all__ = ["FieldStep", "read_fields"]


@dataclass(frozen=True)
class FieldStep:
    """One written step of a field series: its row ``step`` in ``steps.csv`` (0: the unloaded
    strand at t = 0; None where the folder says neither), its programme ``time``, the mesh with
    its point and cell arrays (a ``meshio.Mesh``, or a ``pyvista.UnstructuredGrid``) and the
    set-up's ``loads`` there, named with their unit as in ``steps.csv`` (``tension_N``; empty
    where the folder has no ``fields_loads.csv``)."""

    step: int | None
    time: float
    mesh: Any
    loads: dict[str, float] = field(default_factory=dict)


def _series(path: Path) -> Path:
    """The XDMF file of a run's folder, or ``path`` itself when it names one."""
    path = Path(path)
    xdmf = path / "fields.xdmf" if path.is_dir() else path
    if not xdmf.exists():
        raise FileNotFoundError(
            f"no field series {xdmf}: the run writes one with [output] fields = true"
        )
    return xdmf


def _rows(table: Path) -> list[dict[str, str]]:
    """The rows of a CSV file (none without the file)."""
    if not table.exists():
        return []
    with open(table, newline="") as f:
        return list(csv.DictReader(f))


def _frames(xdmf: Path) -> list[tuple[int | None, dict[str, float]]]:
    """Per frame of the series, from ``<stem>_loads.csv``: its step number (its name ``step
    <n>``) and its loads; empty without the file."""
    frames = []
    for row in _rows(xdmf.with_name(f"{xdmf.stem}_loads.csv")):
        name = row.pop("name")
        number = int(name.split()[-1]) if name.startswith("step ") else None
        loads = {k: float(v) for k, v in row.items() if k not in ("frame", "time")}
        frames.append((number, loads))
    return frames


def _step_number(numbers: dict[float, int], t: float) -> int | None:
    """``steps.csv``'s step at programme time ``t`` (None if none)."""
    # steps.csv keeps 12 significant digits of the time
    return next((n for time, n in numbers.items() if np.isclose(time, t, 1e-10)), None)


def read_fields(path: str | Path, pyvista: bool = False) -> list[FieldStep]:
    """Every step of the field series of the run folder ``path`` (or of the XDMF file it names),
    in the order written: a ``meshio.Mesh`` per step, or with ``pyvista`` a
    ``pyvista.UnstructuredGrid`` whose field data also hold ``time``, ``step`` and the loads.
    Needs meshio and h5py (and pyvista for ``pyvista=True``)."""
    import meshio

    xdmf = _series(path)
    numbers = {float(r["time"]): int(r["step"]) for r in _rows(xdmf.parent / "steps.csv")}
    frames = _frames(xdmf)
    steps = []
    with meshio.xdmf.TimeSeriesReader(str(xdmf)) as reader:
        points, cells = reader.read_points_cells()
        for k in range(reader.num_steps):
            t, point_data, cell_data = reader.read_data(k)
            mesh = meshio.Mesh(points, cells, point_data=point_data, cell_data=cell_data)
            step, loads = frames[k] if k < len(frames) else (_step_number(numbers, t), {})
            if pyvista:
                mesh = _to_pyvista(mesh, t, step, loads)
            steps.append(FieldStep(step, float(t), mesh, loads))
    return steps


def _to_pyvista(mesh, time: float, step: int | None, loads: dict[str, float]):
    """The meshio ``mesh`` as a PyVista grid, its time (step and loads) in the field data."""
    import pyvista

    grid = pyvista.from_meshio(mesh)
    grid.field_data["time"] = [time]
    if step is not None:
        grid.field_data["step"] = [step]
    for name, value in loads.items():
        grid.field_data[name] = [value]
    return grid
