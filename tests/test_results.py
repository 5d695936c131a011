"""A run's field series read back: ``strand.results.read_fields`` (meshio, PyVista) and, where
Debian's ParaView is installed, ``pvpython``; every step at its ``steps.csv`` time, with the
values the run wrote there."""

from __future__ import annotations

import csv
import shutil
import subprocess

import numpy as np
import pytest

from strand.cli import main
from strand.results import read_fields
from strand_cases import SEVEN_WIRE

ARRAYS = {"displacement", "rotation", "force", "moment", "axial_force", "wire", "layer"}


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    """The quick 1+6 saddle case (0.1 m), fields written, no VTX and no figures."""
    folder = tmp_path_factory.mktemp("fields")
    case = folder / "seven.toml"
    case.write_text(SEVEN_WIRE.replace("plots = false", "plots = false\nvtx = false"))
    out = folder / "out"
    assert main(["run", str(case), "--out", str(out)]) == 0
    with open(out / "steps.csv", newline="") as f:
        steps = list(csv.DictReader(f))
    return out, steps


def end_point(points: np.ndarray) -> int:
    """The core's node at the far end z = L: the saddle test's pilot, whose u_z is steps.csv's
    end displacement."""
    return int(np.argmin(np.hypot(points[:, 0], points[:, 1]) - points[:, 2]))


def test_read_fields_gives_every_step_with_the_values_of_steps_csv(run):
    """One mesh per row of steps.csv, numbered and timed as there; at each, the core end's axial
    displacement is the run's end displacement (to the last digit written) and the wire's cell
    ids are the geometry's (0 the core, 1-6 the layer)."""
    out, steps = run
    fields = read_fields(out)
    assert [f.step for f in fields] == [int(s["step"]) for s in steps]
    np.testing.assert_allclose([f.time for f in fields], [float(s["time"]) for s in steps],
                               rtol=1e-11)  # fmt: skip
    for f, s in zip(fields, steps, strict=True):
        mesh = f.mesh
        assert set(mesh.point_data) | set(mesh.cell_data) == ARRAYS
        u = mesh.point_data["displacement"][end_point(mesh.points)]
        assert u[2] == pytest.approx(float(s["end_displacement_m"]), rel=1e-12, abs=1e-18)
    wire = fields[0].mesh.cell_data["wire"][0].ravel()
    assert sorted(np.unique(wire)) == list(range(7))
    assert read_fields(out / "fields.xdmf")[-1].time == fields[-1].time


def test_read_fields_as_pyvista_grids(run):
    """The same steps as PyVista grids (what ``pyvista.read("fields.xdmf")`` would give, were
    VTK's XDMF reader not to crash): the same arrays and values, time and step in the field
    data, and the deformed strand by warping."""
    pytest.importorskip("pyvista")
    out, steps = run
    meshes, grids = read_fields(out), read_fields(out, pyvista=True)
    last, grid = meshes[-1].mesh, grids[-1].mesh
    assert grid.n_points == len(last.points) and grid.n_cells == len(last.cells[0].data)
    assert ARRAYS <= set(grid.array_names)
    np.testing.assert_array_equal(grid.point_data["displacement"], last.point_data["displacement"])
    np.testing.assert_array_equal(grid.cell_data["axial_force"].ravel(),
                                  last.cell_data["axial_force"][0].ravel())  # fmt: skip
    assert grid.field_data["time"][0] == grids[-1].time
    assert grid.field_data["step"][0] == int(steps[-1]["step"])
    warped = grid.warp_by_vector("displacement")
    np.testing.assert_allclose(warped.points, last.points + last.point_data["displacement"])


PVPYTHON_CHECK = """
import sys
from paraview.simple import OpenDataFile, UpdatePipeline
reader = OpenDataFile(sys.argv[1])
times = list(reader.TimestepValues)
UpdatePipeline(times[-1], reader)
print(len(times), times[-1])
print(" ".join(sorted(reader.PointData.keys() + reader.CellData.keys())))
"""


@pytest.mark.skipif(shutil.which("pvpython") is None, reason="ParaView's pvpython not installed")
def test_paraview_opens_the_series_with_every_step_and_array(run, tmp_path):
    out, steps = run
    script = tmp_path / "check.py"
    script.write_text(PVPYTHON_CHECK)
    done = subprocess.run(["pvpython", str(script), str(out / "fields.xdmf")],
                          capture_output=True, text=True, timeout=300)  # fmt: skip
    assert done.returncode == 0, done.stderr[-2000:]
    count, names = done.stdout.strip().splitlines()[-2:]
    n, last = count.split()
    assert int(n) == len(steps) and float(last) == pytest.approx(float(steps[-1]["time"]))
    assert ARRAYS <= set(names.split())
