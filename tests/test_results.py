"""A run's field series read back: ``strand.app.results.read_fields`` (meshio, PyVista) and, where
Debian's ParaView is installed, ``pvpython``; the unloaded strand at t = 0, then every step at
its ``steps.csv`` time, with the values and loads the run wrote there."""

from __future__ import annotations

import csv
import shutil
import subprocess
import xml.etree.ElementTree as ET

import numpy as np
import pytest

from strand.app.cli import main
from strand.app.results import read_fields
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
    """The unloaded strand at t = 0 (step 0: zero displacement and rotation, loads 0), then one
    mesh per row of steps.csv, numbered and timed as there (the same times, to the last digit)
    with its loads; at each, the core end's axial displacement is the run's end displacement
    (to the last digit written) and the wire's cell ids are the geometry's (0 the core, 1-6 the
    layer)."""
    out, steps = run
    fields = read_fields(out)
    assert [f.step for f in fields] == [0] + [int(s["step"]) for s in steps]
    assert [f.time for f in fields] == [0.0] + [float(s["time"]) for s in steps]
    first = fields[0]
    assert set(first.mesh.point_data) | set(first.mesh.cell_data) == ARRAYS
    assert np.all(first.mesh.point_data["displacement"] == 0.0)
    assert np.all(first.mesh.point_data["rotation"] == 0.0)
    for name in ("force", "moment", "axial_force"):
        assert np.all(first.mesh.cell_data[name][0] == 0.0)
    assert first.loads == {"tension_N": 0.0, "lateral_N": 0.0}
    for f, s in zip(fields[1:], steps, strict=True):
        mesh = f.mesh
        assert set(mesh.point_data) | set(mesh.cell_data) == ARRAYS
        u = mesh.point_data["displacement"][end_point(mesh.points)]
        assert u[2] == pytest.approx(float(s["end_displacement_m"]), rel=1e-12, abs=1e-18)
        assert f.loads == {name: pytest.approx(float(s[name]), rel=1e-12) for name in f.loads}
        assert set(f.loads) == {"tension_N", "lateral_N"}
    wire = fields[0].mesh.cell_data["wire"][0].ravel()
    assert sorted(np.unique(wire)) == list(range(7))
    assert read_fields(out / "fields.xdmf")[-1].time == fields[-1].time


def test_field_frames_are_named_and_timed_as_steps_csv(run):
    """In fields.xdmf itself (what ParaView reads): frame ``step 0`` at t = 0, then frame
    ``step n`` at the time of row n of steps.csv; fields_loads.csv lists the same frames."""
    out, steps = run
    grids = (
        ET.parse(out / "fields.xdmf").getroot().findall(".//Grid[@CollectionType='Temporal']/Grid")
    )
    names = [g.get("Name") for g in grids]
    times = [float(g.find("Time").get("Value")) for g in grids]
    assert names == ["step 0"] + [f"step {s['step']}" for s in steps]
    assert times == [0.0] + [float(s["time"]) for s in steps]
    with open(out / "fields_loads.csv", newline="") as f:
        frames = list(csv.DictReader(f))
    assert [r["name"] for r in frames] == names
    assert [float(r["time"]) for r in frames] == times


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
    np.testing.assert_array_equal(
        grid.cell_data["axial_force"].ravel(), last.cell_data["axial_force"][0].ravel()
    )
    assert grid.field_data["time"][0] == grids[-1].time
    assert grid.field_data["step"][0] == int(steps[-1]["step"])
    for name in ("tension_N", "lateral_N"):
        assert grid.field_data[name][0] == pytest.approx(float(steps[-1][name]), rel=1e-12)
    assert grids[0].mesh.field_data["step"][0] == 0 and grids[0].time == 0.0
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
    done = subprocess.run(
        ["pvpython", str(script), str(out / "fields.xdmf")],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert done.returncode == 0, done.stderr[-2000:]
    count, names = done.stdout.strip().splitlines()[-2:]
    n, last = count.split()
    assert int(n) == len(steps) + 1 and float(last) == pytest.approx(float(steps[-1]["time"]))
    assert ARRAYS <= set(names.split())
