"""Result files: the XDMF and VTX time series hold every field at every written step, and
meshio and ADIOS2 read them back."""

import xml.etree.ElementTree as ET

import numpy as np
import pytest
from dolfinx import fem

from beam_cases import cantilever
from strand.beam.fields import FieldWriter, cell_function


def write_series(tmp_path):
    """A cantilever under two tip loads, written at t = 0.5 and 1 (XDMF and VTX)."""
    case = cantilever(6)
    wire = cell_function(case.mesh, np.arange(6, dtype=float), "wire")
    path = tmp_path / "out" / "beam.xdmf"
    tips = []
    with FieldWriter(path, case.beam, cell_data=[wire]) as writer:
        for t in (0.5, 1.0):
            case.force.value = [0.0, t * 10.0, 0.0]
            assert case.solver.solve().converged
            writer.write(t)
            tips.append(case.tip_u.copy())
    return case, path, np.array(tips)


def test_xdmf_series_has_all_fields_per_step(tmp_path):
    _, path, _ = write_series(tmp_path)
    root = ET.parse(path).getroot()
    steps = root.findall(".//Grid[@CollectionType='Temporal']/Grid")
    assert [s.find("Time").get("Value") for s in steps] == ["0.5", "1"]
    for s in steps:
        names = {a.get("Name") for a in s.iter("Attribute")}
        assert names == {"displacement", "rotation", "force", "moment", "axial_force", "wire"}
    assert path.with_suffix(".h5").stat().st_size > 0


def test_meshio_and_adios2_read_the_series_back(tmp_path):
    """meshio reads the XDMF file (one line mesh, every field at every time) and ADIOS2 the VTX
    file; both give the tip displacement the solver computed, at the times written."""
    import meshio

    pytest.importorskip("h5py")  # meshio reads the HDF5 data with it
    adios2 = pytest.importorskip("adios2")
    case, path, tips = write_series(tmp_path)
    x = case.mesh.geometry.x
    tip = int(np.argmax(x[:, 0]))  # geometry node at the free end
    with meshio.xdmf.TimeSeriesReader(path) as reader:
        points, cells = reader.read_points_cells()
        assert cells[0].type == "line" and len(cells[0].data) == 6
        for k in range(reader.num_steps):
            t, point_data, cell_data = reader.read_data(k)
            assert t == (0.5, 1.0)[k]
            np.testing.assert_allclose(point_data["displacement"][tip], tips[k], rtol=1e-12)
            assert set(cell_data) == {"force", "moment", "axial_force", "wire"}
    with adios2.FileReader(str(path.with_suffix(".bp"))) as bp:
        np.testing.assert_array_equal(bp.read("step", step_selection=[0, 2]).ravel(), [0.5, 1.0])
        u = bp.read("displacement", step_selection=[1, 1]).reshape(-1, 3)
        np.testing.assert_allclose(u[tip], tips[1], rtol=1e-12)


def test_cell_function_follows_input_cell_order():
    case = cantilever(5)
    f = cell_function(case.mesh, np.arange(5, dtype=float), "id")
    # cell midpoints in input order are at x = (i + 0.5) L/5: evaluate f there via the DG0 dofs
    mid = fem.Function(fem.functionspace(case.mesh, ("DG", 0, (3,))))
    mid.interpolate(lambda x: x)
    xs = mid.x.array.reshape(-1, 3)[:, 0]
    np.testing.assert_allclose(f.x.array, np.floor(xs / 0.2))


def test_frames_are_named_and_their_loads_written_beside_the_series(tmp_path):
    """``write(t, name, loads)``: the XDMF frames carry the names given, and ``<stem>_loads.csv``
    one row per frame with its name, time (as written) and the loads named at construction."""
    import csv

    case = cantilever(4)
    path = tmp_path / "beam.xdmf"
    with FieldWriter(path, case.beam, vtx=False, loads=["P_N"]) as writer:
        writer.write(0.0, "step 0", {"P_N": 0.0})
        for k, t in enumerate((1 / 3, 1.0), start=1):
            case.force.value = [0.0, 30.0 * t, 0.0]
            assert case.solver.solve().converged
            writer.write(t, f"step {k}", {"P_N": 30.0 * t})
    grids = ET.parse(path).getroot().findall(".//Grid[@CollectionType='Temporal']/Grid")
    assert [g.get("Name") for g in grids] == ["step 0", "step 1", "step 2"]
    assert [float(g.find("Time").get("Value")) for g in grids] == [0.0, 1 / 3, 1.0]
    with open(writer.loads_path, newline="") as f:
        rows = list(csv.DictReader(f))
    assert writer.loads_path.name == "beam_loads.csv"
    assert [r["name"] for r in rows] == ["step 0", "step 1", "step 2"]
    assert [float(r["time"]) for r in rows] == [0.0, 1 / 3, 1.0]
    assert [float(r["P_N"]) for r in rows] == [0.0, 10.0, 30.0]
