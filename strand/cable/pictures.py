"""Pictures of beams and strands, off-screen (pyvista, no display needed): the centre lines of a
1D mesh as tubes, and a strand's wires coloured by layer with a cross-section of its contact
points."""

from __future__ import annotations

import os
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
import numpy.typing as npt

if TYPE_CHECKING:
    import pyvista

    from .geometry import StrandGeometry

__all__ = ["offscreen_plotter", "tubes", "save", "strand_picture"]


def offscreen_plotter(**kwargs: Any):  # -> pyvista.Plotter, whose stubs mypy misreads
    """A pyvista Plotter that renders without a display (EGL here, no X server needed)."""
    os.environ.setdefault("VTK_DEFAULT_OPENGL_WINDOW", "vtkEGLRenderWindow")
    import pyvista

    pyvista.OFF_SCREEN = True
    return pyvista.Plotter(off_screen=True, **kwargs)


def tubes(
    V_or_mesh,  # a FunctionSpace or a Mesh (vtk_mesh takes both; its stubs only the mesh)
    displacement: npt.ArrayLike | None = None,
    scalars: npt.NDArray[Any] | None = None,
    name: str = "value",
    radius: float = 1e-3,
    n_sides: int = 16,
    cells: npt.ArrayLike | None = None,
) -> pyvista.PolyData | None:
    """Tubes of ``radius`` (m) around the (displaced) centrelines of a 1D mesh. Collective: on
    several ranks each rank gives its own part and rank 0 gets the tubes of the whole mesh, the
    other ranks None (draw on rank 0).

    ``displacement`` is an (n_nodes, 3) array in the order of ``dolfinx.plot.vtk_mesh`` of the
    mesh (its geometry nodes; a space's dofs when given a space) and ``scalars`` a per-cell (this
    rank's cells, its ghosts may follow, as in a DG0 function's array) or per-node array to colour
    by; ``cells`` (local cell indices) keeps only those cells.
    """
    import dolfinx.plot
    import pyvista

    mesh = getattr(V_or_mesh, "mesh", V_or_mesh)
    comm = mesh.comm
    index_map = mesh.topology.index_map(mesh.topology.dim)
    owned = index_map.size_local  # vtk_mesh draws this rank's own cells
    topology, cell_types, x = dolfinx.plot.vtk_mesh(V_or_mesh)
    grid = pyvista.UnstructuredGrid(topology, cell_types, x.copy())
    per_cell = scalars is not None and len(scalars) in (owned, owned + index_map.num_ghosts)
    if displacement is not None:
        grid.points = grid.points + np.asarray(displacement).reshape(-1, 3)
    if scalars is not None:
        grid[name] = np.asarray(scalars)[:owned] if per_cell else np.asarray(scalars)
    if cells is not None:
        cells = np.asarray(cells)
        grid = grid.extract_cells(cells[cells < owned])
    if comm.size > 1:
        parts = comm.gather(grid, root=0)
        if comm.rank != 0:
            return None
        grid = pyvista.merge([p for p in parts if p.n_cells], merge_points=True)
    if per_cell:
        grid = grid.cell_data_to_point_data()
    return grid.extract_surface(algorithm=None).tube(radius=radius, n_sides=n_sides)


def save(plotter, path: str | Path) -> Path:
    """Write the plotter's picture to ``path`` (PNG) and close it."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    plotter.screenshot(str(path))
    plotter.close()
    return path


LAYER_COLOURS = ["#4d4d4d", "#8c6d31", "#3182bd", "#31a354", "#e6550d", "#756bb1", "#d6616b"]


def strand_picture(
    geometry: StrandGeometry, path: str | Path, step: float = 0.03, section_z: float | None = None
) -> Path:
    """A PNG with the strand as tubes coloured by layer (cut away like a staircase: layer i is
    drawn over (n_layers − i) × ``step`` m) and a cross-section at ``section_z`` with the wires and
    the contact points within ±3 mm of it."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import pyvista

    g = geometry
    n_layers = len(g.cable.layers)
    plotter = offscreen_plotter(window_size=(1400, 800))
    for i, lay in enumerate(g.cable.layers):
        zmax = min(g.length, (n_layers - i) * step)
        for w in np.flatnonzero(g.wire_layer == i):
            pts = g.points[g.wire_offsets[w] : g.wire_offsets[w + 1]]
            pts = pts[pts[:, 2] <= zmax + 1e-12]
            if len(pts) < 2:
                continue
            line = pyvista.lines_from_points(pts)
            plotter.add_mesh(
                line.tube(radius=lay.wire.diameter / 2, n_sides=16), color=LAYER_COLOURS[i % 7]
            )
    plotter.view_vector(
        (1.0, -0.4, 0.35), viewup=(-1.0, 0.0, 0.0)
    )  # strand axis across the picture
    plotter.reset_camera()
    plotter.camera.zoom(1.4)
    image = plotter.screenshot(return_img=True)
    plotter.close()

    fig, (ax3d, ax) = plt.subplots(1, 2, figsize=(14, 6.5), gridspec_kw={"width_ratios": [1.6, 1]})
    ax3d.imshow(image)
    ax3d.set_axis_off()
    ax3d.set_title(f"{g.cable.name}: {len(g.cells)} elements, {len(g.pairs)} contact pairs")
    z0 = g.length / 2 if section_z is None else section_z
    centres = g.centres(np.arange(len(g.wire_layer)), z0)[:, :2] * 1e3
    for centre, lay_id in zip(centres, g.wire_layer, strict=True):
        lay = g.cable.layers[lay_id]
        ax.add_patch(
            plt.Circle(
                centre,
                lay.wire.diameter / 2e-3,
                fc=LAYER_COLOURS[lay_id % 7],
                alpha=0.35,
                ec="k",
                lw=0.5,
            )
        )
    p = g.pairs
    contact = g.points[p.a] + p.radius_a[:, None] * p.normal
    near = np.abs(contact[:, 2] - z0) < 3e-3
    for i in range(n_layers - 1):
        m = near & (p.interface == i)
        ax.scatter(
            *(contact[m, :2].T * 1e3),
            s=14,
            label=f"{i}|{i + 1} ({'line' if i == 0 else 'crossing'})",
        )
    ax.set_aspect("equal")
    ax.set_xlabel("x (mm)")
    ax.set_ylabel("y (mm)")
    ax.set_title(f"section z = {z0 * 1e3:g} mm, contact points within ±3 mm")
    ax.legend(loc="upper right", fontsize=8)
    lim = g.cable.outer_diameter / 2e-3 * 1.15
    ax.set_xlim(-lim, lim)
    ax.set_ylim(-lim, lim)
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)
    return path
