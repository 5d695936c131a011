"""Pictures: off-screen pyvista renderings of wires as tubes (matplotlib figures come later)."""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np

__all__ = ["offscreen_plotter", "tubes"]


def offscreen_plotter(**kwargs):
    """A pyvista Plotter that renders without a display (EGL here, no X server needed)."""
    os.environ.setdefault("VTK_DEFAULT_OPENGL_WINDOW", "vtkEGLRenderWindow")
    import pyvista

    pyvista.OFF_SCREEN = True
    return pyvista.Plotter(off_screen=True, **kwargs)


def tubes(V_or_mesh, displacement=None, scalars=None, name="value", radius=1e-3, n_sides=16):
    """Tubes of ``radius`` (m) around the (displaced) centrelines of a 1D mesh.

    ``displacement`` is an (n_nodes, 3) array in the order of ``dolfinx.plot.vtk_mesh`` of the
    mesh (its geometry nodes) and ``scalars`` a per-cell or per-node array to colour by.
    """
    import dolfinx.plot
    import pyvista

    topology, cell_types, x = dolfinx.plot.vtk_mesh(V_or_mesh)
    grid = pyvista.UnstructuredGrid(topology, cell_types, x.copy())
    if displacement is not None:
        grid.points = grid.points + np.asarray(displacement).reshape(-1, 3)
    if scalars is not None:
        grid[name] = np.asarray(scalars)
        if len(scalars) == grid.n_cells:
            grid = grid.cell_data_to_point_data()
    return grid.extract_surface(algorithm=None).tube(radius=radius, n_sides=n_sides)


def save(plotter, path: str | Path) -> Path:
    """Write the plotter's picture to ``path`` (PNG) and close it."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    plotter.screenshot(str(path))
    plotter.close()
    return path
