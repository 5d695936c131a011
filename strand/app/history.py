"""Per-step histories in one HDF5 file each, written as the run goes, and read back as arrays.

A history file holds ``/static/<name>`` arrays (one value per item: pair, element) and, for every
recorded step k, ``/steps/<k>/<name>`` arrays of the same items, with the step's number and
programme time in ``/steps/<k>``'s attributes. Each step is flushed when written, so an
interrupted run keeps every step so far. ``read_history`` stacks the steps: ``history["force"]``
is (n_steps, n_items, …). A point series (``write_points_xdmf``) indexes the same file for
ParaView: one point per item, at the positions ``/steps/<k>/position``, with every array as a
point field. Serial: one process writes (rank 0 of a distributed run).
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import h5py
import numpy as np
import numpy.typing as npt

from ..beam.parallel import is_root

__all__ = ["HistoryWriter", "History", "read_history", "write_points_xdmf"]


class HistoryWriter:
    """Creates ``path`` with the ``static`` arrays; ``write`` appends one step's arrays (stored
    as float32 unless integer or boolean: histories are for reading, not restarting). Only rank
    0 of a distributed run touches the file (``file`` is None elsewhere); the arrays it is given
    are whole on every rank."""

    def __init__(self, path: str | Path, static: dict[str, npt.ArrayLike], **attributes):
        self.path = Path(path)
        self.steps: list[tuple[int, float, dict[str, tuple]]] = []
        self.file = None
        if not is_root():
            return
        self.file = h5py.File(self.path, "w")
        for key, value in attributes.items():
            self.file.attrs[key] = value
        group = self.file.create_group("static")
        for name, value in static.items():
            group.create_dataset(name, data=np.asarray(value))
        self.file.create_group("steps")
        self.file.flush()

    def write(
        self, number: int, time: float, arrays: dict[str, npt.ArrayLike], **values: float
    ) -> None:
        """Append step ``number`` at programme ``time`` with its ``arrays`` and scalar
        ``values`` (e.g. the load)."""
        if self.file is None:
            return
        key = f"{len(self.steps):06d}"
        group = self.file["steps"].create_group(key)
        group.attrs["step"], group.attrs["time"] = number, time
        for name, value in values.items():
            group.attrs[name] = value
        shapes = {}
        for name, value in arrays.items():
            value = np.asarray(value)
            if value.dtype.kind == "f":
                value = value.astype(np.float32)
            elif value.dtype.kind == "b":
                value = value.astype(np.int8)
            group.create_dataset(name, data=value, compression="gzip", compression_opts=1)
            shapes[name] = (value.shape, value.dtype)
        self.steps.append((number, time, shapes))
        self.file.flush()

    def close(self) -> None:
        if self.file is not None:
            self.file.close()


@dataclass
class History:
    """A history file read back: ``static`` arrays, step ``numbers`` and programme ``times``,
    the steps' scalar ``values`` by name, and the stacked step arrays by name (``history[name]``,
    (n_steps, …))."""

    static: dict[str, np.ndarray]
    numbers: np.ndarray
    times: np.ndarray
    values: dict[str, np.ndarray]
    arrays: dict[str, np.ndarray]
    attributes: dict

    def __getitem__(self, name: str) -> np.ndarray:
        return self.arrays[name]

    def __len__(self) -> int:
        return len(self.numbers)


def read_history(path: str | Path) -> History:
    """Read a file written by ``HistoryWriter`` (float arrays come back as float64)."""
    with h5py.File(path, "r") as f:
        static = {k: v[()] for k, v in f["static"].items()}
        keys = sorted(f["steps"].keys())
        numbers = np.array([f["steps"][k].attrs["step"] for k in keys], dtype=int)
        times = np.array([f["steps"][k].attrs["time"] for k in keys], dtype=float)
        names = list(f["steps"][keys[0]].keys()) if keys else []
        scalars = (
            [a for a in f["steps"][keys[0]].attrs if a not in ("step", "time")] if keys else []
        )
        values = {a: np.array([f["steps"][k].attrs[a] for k in keys]) for a in scalars}
        arrays = {}
        for name in names:
            stack = np.stack([f["steps"][k][name][()] for k in keys])
            arrays[name] = stack.astype(float) if stack.dtype.kind == "f" else stack
        attributes = dict(f.attrs)
    return History(static, numbers, times, values, arrays, attributes)


_KINDS = {"f": "Float", "i": "Int", "u": "UInt"}


def _item(file: str, path: str, shape, dtype) -> str:
    dtype = np.dtype(dtype)
    kind = _KINDS.get(dtype.kind, "Int")
    precision = dtype.itemsize
    dims = " ".join(str(s) for s in shape)
    return (
        f'<DataItem Dimensions="{dims}" NumberType="{kind}" Precision="{precision}" '
        f'Format="HDF">{file}:{path}</DataItem>'
    )


def write_points_xdmf(path: str | Path, writer: HistoryWriter) -> None:
    """(Re)write the XDMF index of ``writer``'s file as a time series of points (ParaView,
    meshio): one point per item at ``/steps/<k>/position``, every other array a point field."""
    path = Path(path)
    h5 = writer.path.name
    static = {k: (v.shape, v.dtype) for k, v in writer.file["static"].items()}
    n = static["vertex"][0][0]
    grids = []
    for k, (_, time, shapes) in enumerate(writer.steps):
        step = f"/steps/{k:06d}"
        fields = []
        for name, (shape, dtype) in [*static.items(), *shapes.items()]:
            if name in ("vertex", "position"):
                continue
            where = f"/static/{name}" if name in static and name not in shapes else f"{step}/{name}"
            kind = "Vector" if len(shape) == 2 and shape[1] == 3 else "Scalar"
            if len(shape) > 2 or (len(shape) == 2 and shape[1] != 3):
                continue
            fields.append(
                f'<Attribute Name="{name}" AttributeType="{kind}" Center="Node">'
                f"{_item(h5, where, shape, dtype)}</Attribute>"
            )
        grids.append(
            f'<Grid Name="points" GridType="Uniform"><Time Value="{time:.12g}"/>'
            f'<Topology TopologyType="Polyvertex" NumberOfElements="{n}" NodesPerElement="1">'
            f"{_item(h5, '/static/vertex', (n, 1), static['vertex'][1])}</Topology>"
            f'<Geometry GeometryType="XYZ">{_item(h5, f"{step}/position", (n, 3), np.float32)}'
            f"</Geometry>{''.join(fields)}</Grid>"
        )
    text = (
        '<?xml version="1.0"?>\n<Xdmf Version="3.0"><Domain>'
        '<Grid Name="series" GridType="Collection" CollectionType="Temporal">\n'
        + "\n".join(grids)
        + "\n</Grid></Domain></Xdmf>\n"
    )
    tmp = path.with_suffix(".xdmf.tmp")
    tmp.write_text(text)
    tmp.replace(path)
