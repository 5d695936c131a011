"""Result files written as a run goes: time series of the beam fields, as XDMF (ParaView, meshio)
and VTX (ADIOS2: ParaView, PyVista), with the loads of every frame in a CSV file beside them."""

from __future__ import annotations

import csv
import xml.etree.ElementTree as ET
from collections.abc import Mapping, Sequence
from pathlib import Path

import dolfinx
import numpy as np
import numpy.typing as npt
from dolfinx import fem

from forms import ReissnerBeam

from .parallel import root_open

__all__ = ["FieldWriter", "cell_function", "meshio_layout", "section_force_values"]


def cell_function(mesh: dolfinx.mesh.Mesh, values_by_input_cell: npt.ArrayLike, name: str):
    """DG0 function from values given per input cell (row of the ``cells`` array of the mesh)."""
    D0 = fem.functionspace(mesh, ("DG", 0))
    f = fem.Function(D0, name=name)
    n_local = mesh.topology.index_map(1).size_local + mesh.topology.index_map(1).num_ghosts
    original = np.asarray(mesh.topology.original_cell_index)[:n_local]
    dofs = D0.dofmap.list[:n_local, 0]
    f.x.array[dofs] = np.asarray(values_by_input_cell, dtype=np.float64)[original]
    return f


class FieldWriter:
    """Time series of displacement u (m), rotation vector θ (rad) and section forces, as XDMF
    (``path``, with its HDF5 file) and, with ``vtx``, as VTX (``path`` with suffix ``.bp``).

    Section forces are cell-wise, in the section frame: ``force`` = (N, V2, V3) in N and
    ``moment`` = (torque, M2, M3) in N m; ``axial_force`` = N alone. Constant cell data (wire and
    layer ids, ...) given as DG0 functions in ``cell_data`` are written with every step so that
    ParaView can threshold on them at any time. The XDMF file is kept in the layout meshio reads
    too (``meshio_layout``), each frame named as given to ``write``.

    Neither dolfinx writer stores a number per frame beside the functions, so the ``loads``
    named here (e.g. ``tension_N``) go to ``loads_path``, a CSV file beside the series
    (``<stem>_loads.csv``): one row per frame, its name, its time and the loads there.
    """

    def __init__(
        self,
        path: str | Path,
        beam: ReissnerBeam,
        cell_data: Sequence[fem.Function] = (),
        vtx: bool = True,
        loads: Sequence[str] = (),
    ):
        self.path = Path(path)
        self.path.parent.mkdir(parents=True, exist_ok=True)
        w = beam.w
        mesh = w.function_space.mesh
        U = fem.functionspace(mesh, ("Lagrange", 1, (3,)))
        D3 = fem.functionspace(mesh, ("DG", 0, (3,)))
        D1 = fem.functionspace(mesh, ("DG", 0))
        self.u = fem.Function(U, name="displacement")
        self.theta = fem.Function(U, name="rotation")
        self.force = fem.Function(D3, name="force")
        self.moment = fem.Function(D3, name="moment")
        self.axial = fem.Function(D1, name="axial_force")
        pts_u = U.element.interpolation_points
        pts_d = D3.element.interpolation_points
        self._exprs = [
            (self.u, fem.Expression(beam.u, pts_u)),
            (self.theta, fem.Expression(beam.theta, pts_u)),
            (self.force, fem.Expression(beam.N, pts_d)),
            (self.moment, fem.Expression(beam.M, pts_d)),
            (self.axial, fem.Expression(beam.N[0], D1.element.interpolation_points)),
        ]
        self.cell_data = list(cell_data)
        self.functions = [f for f, _ in self._exprs] + self.cell_data
        self._file = dolfinx.io.XDMFFile(mesh.comm, str(self.path), "w")
        self._file.write_mesh(mesh)
        self._vtx = None
        if vtx:
            self._vtx = dolfinx.io.VTXWriter(
                mesh.comm,
                self.path.with_suffix(".bp"),
                self.functions,
                engine="BP4",
                mesh_policy=dolfinx.io.VTXMeshPolicy.reuse,
            )
        self._comm = mesh.comm
        self.names: list[str] = []  # of the frames written
        self.load_names = list(loads)
        self.loads_path = self.path.with_name(f"{self.path.stem}_loads.csv")
        self._loads = None
        if self.load_names:
            self._loads = root_open(self.loads_path, "w", mesh.comm, newline="")  # noqa: SIM115
            csv.writer(self._loads).writerow(["frame", "name", "time", *self.load_names])
            self._loads.flush()

    def write(
        self, t: float, name: str | None = None, loads: Mapping[str, float] | None = None
    ) -> None:
        """Evaluate and append every field at time ``t`` as the frame ``name`` (default
        ``step <k>``, k counted from 0), with the value of each load named at construction
        (``loads``); flushed to disk at once."""
        for f, e in self._exprs:
            f.interpolate(e)
        for f in self.functions:
            self._file.write_function(f, t)
        self.names.append(f"step {len(self.names)}" if name is None else name)
        self._file.flush()
        self._relayout()
        if self._vtx is not None:
            self._vtx.write(t)
        if self._loads is not None:
            row = [len(self.names) - 1, self.names[-1], repr(float(t))]
            given = loads or {}
            csv.writer(self._loads).writerow(row + [repr(float(given[n])) for n in self.load_names])
            self._loads.flush()

    def close(self) -> None:
        self._file.close()
        self._relayout()
        if self._vtx is not None:
            self._vtx.close()
            self._vtx = None
        if self._loads is not None:
            self._loads.close()
            self._loads = None

    def _relayout(self) -> None:
        self._comm.Barrier()
        if self._comm.rank == 0:
            meshio_layout(self.path, self.names)
        self._comm.Barrier()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()


_XI = "https://www.w3.org/2001/XInclude"


def meshio_layout(path: str | Path, names: Sequence[str] = ()) -> None:
    """Rewrite dolfinx's XDMF index (one temporal collection per function, topology type
    ``PolyLine``) in place as one temporal collection whose steps hold every function, with the
    type spelled ``Polyline``: the layout meshio's ``TimeSeriesReader`` reads (it takes only the
    last collection and does not know ``PolyLine``) and ParaView reads as before. Step k is
    named ``names[k]`` (``step <k>`` beyond them). The HDF5 data are not touched. A file already
    in that layout is left as it is."""
    ET.register_namespace("xi", _XI)
    tree = ET.parse(path)
    domain = tree.getroot().find("Domain")
    if domain is None:
        raise ValueError(f"{path}: not an XDMF file (no Domain element)")
    grids = list(domain)
    for topology in domain.iter("Topology"):
        if topology.get("TopologyType") == "PolyLine":
            topology.set("TopologyType", "Polyline")
    collections = [
        g
        for g in grids
        if g.get("GridType") == "Collection" and g.get("CollectionType") == "Temporal"
    ]
    if len(collections) > 1:
        steps = [list(c) for c in collections]
        n = min(len(s) for s in steps)
        merged = ET.Element("Grid", Name="fields", GridType="Collection", CollectionType="Temporal")
        for k in range(n):
            first = steps[0][k]
            name = names[k] if k < len(names) else f"step {k}"
            grid = ET.SubElement(merged, "Grid", Name=name, GridType="Uniform")
            for child in first:
                if child.tag != "Attribute":  # the mesh's xi:include and the time
                    grid.append(child)
            for s in steps:
                grid.extend(a for a in s[k] if a.tag == "Attribute")
        for c in collections:
            domain.remove(c)
        domain.append(merged)
    ET.indent(tree)
    tree.write(path, xml_declaration=True, encoding="utf-8")


def section_force_values(beam: ReissnerBeam) -> np.ndarray:
    """Cell-wise (N, V2, V3, Mt, M2, M3) as a (cells, 6) array in the local cell order."""
    mesh = beam.w.function_space.mesh
    D6 = fem.functionspace(mesh, ("DG", 0, (6,)))
    f = fem.Function(D6)
    f.interpolate(fem.Expression(beam.section_forces(), D6.element.interpolation_points))
    n = mesh.topology.index_map(1).size_local
    return f.x.array.reshape(-1, 6)[D6.dofmap.list[:n, 0]]
