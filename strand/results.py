"""Reading a run's field series back in Python: ``fields.xdmf`` (+ ``fields.h5``) per step, as
meshio meshes or PyVista grids.

PyVista's own ``pyvista.read("fields.xdmf")`` goes through VTK's XDMF reader, which crashes the
interpreter with the VTK 9.7 of the pyvista wheels; this reader takes the arrays with meshio and
h5py instead, and hands PyVista grids built from them (``pyvista.from_meshio``). ParaView opens
the XDMF file itself.

>>> from strand.results import read_fields                                 # doctest: +SKIP
>>> steps = read_fields("results/quick_1x6", pyvista=True)                 # doctest: +SKIP
>>> steps[-1].mesh.warp_by_vector("displacement").plot()                   # doctest: +SKIP

Every step carries its programme time (``steps.csv``'s ``time``: stage k runs from t = k to
k + 1) and, where the folder has ``steps.csv``, the number of its row there. Arrays and units as
in docs/outputs.md: points ``displacement`` (m) and ``rotation`` (rad); cells ``force`` (N),
``moment`` (N m), ``axial_force`` (N), ``wire``, ``layer``.
"""

from __future__ import annotations

import csv
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

__all__ = ["FieldStep", "read_fields"]


@dataclass(frozen=True)
class FieldStep:
    """One written step of a field series: its row ``step`` in ``steps.csv`` (None where the
    folder has none), its programme ``time`` and the mesh with its point and cell arrays (a
    ``meshio.Mesh``, or a ``pyvista.UnstructuredGrid``)."""

    step: int | None
    time: float
    mesh: Any


def _series(path: Path) -> Path:
    """The XDMF file of a run's folder, or ``path`` itself when it names one."""
    path = Path(path)
    xdmf = path / "fields.xdmf" if path.is_dir() else path
    if not xdmf.exists():
        raise FileNotFoundError(
            f"no field series {xdmf}: the run writes one with [output] fields = true"
        )
    return xdmf


def _step_numbers(folder: Path) -> dict[float, int]:
    """``steps.csv``'s step number at each programme time (empty without the file)."""
    table = folder / "steps.csv"
    if not table.exists():
        return {}
    with open(table, newline="") as f:
        return {float(row["time"]): int(row["step"]) for row in csv.DictReader(f)}


def read_fields(path: str | Path, pyvista: bool = False) -> list[FieldStep]:
    """Every step of the field series of the run folder ``path`` (or of the XDMF file it names),
    in the order written: a ``meshio.Mesh`` per step, or with ``pyvista`` a
    ``pyvista.UnstructuredGrid`` whose field data also hold ``time`` (and ``step``).
    Needs meshio and h5py (and pyvista for ``pyvista=True``)."""
    import meshio

    xdmf = _series(path)
    numbers = _step_numbers(xdmf.parent)
    steps = []
    with meshio.xdmf.TimeSeriesReader(str(xdmf)) as reader:
        points, cells = reader.read_points_cells()
        for k in range(reader.num_steps):
            t, point_data, cell_data = reader.read_data(k)
            mesh = meshio.Mesh(points, cells, point_data=point_data, cell_data=cell_data)
            # steps.csv keeps 12 significant digits of the time, the XDMF file all of them
            step = next((n for time, n in numbers.items() if np.isclose(time, t, 1e-10)), None)
            steps.append(FieldStep(step, float(t), _to_pyvista(mesh, t, step) if pyvista else mesh))
    return steps


def _to_pyvista(mesh, time: float, step: int | None):
    """The meshio ``mesh`` as a PyVista grid, its time (and step) in the field data."""
    import pyvista

    grid = pyvista.from_meshio(mesh)
    grid.field_data["time"] = [time]
    if step is not None:
        grid.field_data["step"] = [step]
    return grid
