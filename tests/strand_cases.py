"""Strand cases and helpers shared by several test files: a 1+6 case file, strand geometries,
the finite-difference tangent of a contact group, the ``mpirun`` beside the Python, and a results
folder holding an earlier run."""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest

from strand.app.folder import RUN_MARKER
from strand.cable.description import cable_from_dict, cardinal
from strand.cable.geometry import StrandGeometry, build_geometry

#: a quick 1+6 case file (0.1 m of strand, no plots)
SEVEN_WIRE = """
[cable]
name = "1+6"
[cable.core]
diameter = 3.34e-3
E = 210e9
nu = 0.3
friction = 0.3
[[cable.layer]]
wires = 6
diameter = 3.34e-3
E = 180e9
nu = 0.3
lay_angle = 6.06
lay = "S"
friction = 0.5

[contact]
same_layer = "off"  # crossings only: the runs compared across ranks and restarts
[mesh]
length = 0.1
[load]
tension = 10e3
lateral = 300.0
cycle = [1.0, 0.0]
[steps]
tension = 5e3
lateral = 100.0
lateral_max = 150.0
[output]
plots = false
"""

MPIRUN = Path(sys.executable).parent / "mpirun"
needs_mpirun = pytest.mark.skipif(not MPIRUN.exists(), reason="no mpirun beside the Python")


def seven_wire(lay_angle=6.06, length=0.2, h_max=4e-3) -> StrandGeometry:
    """A 1+6 strand of 3.34 mm wires (core E = 210 GPa, layer 180 GPa); lengths in m, angle in °."""
    cable = cable_from_dict(
        {
            "name": "1+6",
            "core": {"diameter": 3.34e-3, "E": 210e9, "nu": 0.3, "friction": 0.3},
            "layer": [
                {
                    "wires": 6,
                    "diameter": 3.34e-3,
                    "E": 180e9,
                    "nu": 0.3,
                    "lay_angle": lay_angle,
                    "lay": "S",
                    "friction": 0.5,
                }
            ],
        }
    )
    return build_geometry(cable, length, h_max)


def nineteen_wire(length=0.1, h_max=4e-3) -> StrandGeometry:
    """Core, layer 1 and layer 2 of Cardinal: line pairs and crossings."""
    cable = cardinal()
    return build_geometry(type(cable)("1+6+12", cable.layers[:3]), length, h_max)


def fd_tangent(group, w: np.ndarray, step: float = 1e-9) -> np.ndarray:
    """Central finite differences of a pair group's residual (P, m) w.r.t. all its stencil dofs
    (m: the group's ``dofs`` layout, or all 6k)."""
    P, k = group.stencils.shape
    K = np.zeros((P, len(getattr(group, "dofs", range(6 * k))), 6 * k))
    for j in range(6 * k):
        node, comp = divmod(j, 6)
        wp, wm = w.copy(), w.copy()
        wp[group.stencils[:, node], comp] += step
        wm[group.stencils[:, node], comp] -= step
        K[:, :, j] = (group.evaluate(wp, False)[0] - group.evaluate(wm, False)[0]) / (2 * step)
    return K


def check_state_and_tangent(group, w: np.ndarray, state: str) -> tuple[np.ndarray, float]:
    """Evaluate a pair group at ``w`` and check that every pair is in ``state`` ("open",
    "stick" or "slip"); returns its tangent's central differences (``fd_tangent``) and the
    tangent's scale, for the caller to compare with its own layout."""
    _, K = group.evaluate(w, True)
    s = group.state
    if state == "open":
        assert np.all(s.force == 0) and np.all(s.traction == 0)
    else:
        assert np.all(s.force > 0)
        assert np.all(s.slipping == (state == "slip"))
    K_fd = fd_tangent(group, w)
    group.evaluate(w, True)
    return K_fd, max(np.abs(K).max(), 1.0)


#: some of the files a saddle run with fields and plots writes at the top of its folder
RUN_FILES = ("fields.xdmf", "fields.h5", "load_deflection.png", "steps.csv", "summary.txt")


def contents(folder: Path) -> dict[str, int]:
    """Every path under ``folder`` with its modification time (ns)."""
    return {str(p.relative_to(folder)): p.stat().st_mtime_ns for p in folder.rglob("*")}


def earlier_run(folder: Path) -> Path:
    """A folder holding a run: its marker, files, a VTX field folder, a sub-folder that is another
    run's own (e.g. a comparison's), and a hidden file."""
    (folder / "fields.bp").mkdir(parents=True)
    (folder / "fields.bp" / "data.0").write_text("steps")
    for name in (RUN_MARKER, *RUN_FILES):
        (folder / name).write_text(name)
    (folder / "small").mkdir()
    (folder / "small" / RUN_MARKER).write_text("another run")
    (folder / ".keep").write_text("")
    return folder


def one_line_error(capsys) -> str:
    """The one line a refused command wrote to stderr (no traceback)."""
    err = capsys.readouterr().err
    assert "Traceback" not in err
    lines = err.strip().splitlines()
    assert len(lines) == 1, err
    return lines[0]
