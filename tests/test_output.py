"""Result files: the XDMF time series holds every field at every written step."""

import xml.etree.ElementTree as ET

import numpy as np
from dolfinx import fem

from beam_cases import cantilever
from strand.output import FieldWriter, cell_function


def test_xdmf_series_has_all_fields_per_step(tmp_path):
    case = cantilever(6)
    wire = cell_function(case.mesh, np.arange(6, dtype=float), "wire")
    path = tmp_path / "out" / "beam.xdmf"
    with FieldWriter(path, case.beam, cell_data=[wire]) as writer:
        for t in (0.5, 1.0):
            case.force.value = [0.0, t * 10.0, 0.0]
            assert case.solver.solve().converged
            writer.write(t)
    grids = ET.parse(path).getroot().findall(".//Grid[@GridType='Collection']/Grid")
    names = {g.get("Name") for g in grids}
    assert {"displacement", "rotation", "force", "moment", "axial_force", "wire"} <= names
    steps = {a.get("Value") for a in ET.parse(path).getroot().iter("Time")}
    assert steps == {"0.5", "1"}
    assert path.with_suffix(".h5").stat().st_size > 0


def test_cell_function_follows_input_cell_order():
    case = cantilever(5)
    f = cell_function(case.mesh, np.arange(5, dtype=float), "id")
    # cell midpoints in input order are at x = (i + 0.5) L/5: evaluate f there via the DG0 dofs
    mid = fem.Function(fem.functionspace(case.mesh, ("DG", 0, (3,))))
    mid.interpolate(lambda x: x)
    xs = mid.x.array.reshape(-1, 3)[:, 0]
    np.testing.assert_allclose(f.x.array, np.floor(xs / 0.2))
