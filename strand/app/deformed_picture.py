"""The deformed strand as a picture (pyvista, off-screen): the outer layer near midspan at the
largest load, coloured by wire axial force, displacements magnified, with rulers for its scale
(``deformed_picture``, ``deformed_axial_force.png``); the pictures themselves (wires as tubes) are
the library's (``strand.cable.pictures``). Units: m, mm on the rulers.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..cable.pictures import offscreen_plotter, save

__all__ = ["deformed_picture", "magnification", "fit_text", "text_extent"]


def magnification(largest: float, size: float) -> float:
    """The factor (1, 2 or 5 × 10^k, at least 1) that shows a displacement of ``largest`` (m) as
    between a fifth and a half of ``size`` (m)."""
    if largest <= 0 or 2 * largest >= size:
        return 1.0
    target = size / (2 * largest)
    decade = 10.0 ** np.floor(np.log10(target))
    return float(max(f * decade for f in (1, 2, 5) if f * decade <= target))


def deformed_picture(case, result, problem, path, at_peak: str, note: str = "") -> Path:
    """The outer layer over the middle of the span (30 %, at least 12 strand diameters), deformed
    at the largest load and coloured by wire axial force, seen across the load. Displacements are
    magnified (``magnification``: the largest across the strand's axis shown as up to half the
    strand's diameter), the factor in the title (two lines, shrunk to fit the picture:
    ``fit_text``); two rulers give the scale: z along the strand (mm, true scale) under it, and
    beyond its right end the deflection (mm, as magnified) down from the undeformed axis.
    ``at_peak``: the largest load as the title gives it (``SetupKind.load_text``)."""
    import pyvista

    g = problem.geometry
    peak, L = result.peak, case.mesh.length
    D = case.cable.outer_diameter
    half = min(L / 2, max(0.15 * L, 6 * D))
    outer = len(case.cable.layers) - 1
    shown = np.flatnonzero((peak.layer == outer) & (np.abs(peak.z - L / 2) <= half))
    u = result.peak_w[:, :3]  # the geometry's point order, whole on every rank
    factor = magnification(float(np.abs(u[g.cells[shown], :2]).max(initial=0.0)), D)
    x = g.points + factor * u
    lines = np.column_stack([np.full(len(shown), 2), g.cells[shown]]).ravel()
    grid = pyvista.PolyData(x, lines=lines)
    grid.cell_data["N (N)"] = peak.axial[shown]
    radius = case.cable.layers[-1].wire.diameter / 2
    grid = grid.cell_data_to_point_data().tube(radius=radius, n_sides=16)
    width, height = 1800, 650
    plotter = offscreen_plotter(window_size=(width, height))
    plotter.add_mesh(
        grid,
        scalars="N (N)",
        cmap="coolwarm",
        scalar_bar_args={
            "title": "wire axial force N (N)",
            "vertical": False,
            "height": 0.06,
            "width": 0.4,
            "position_x": 0.3,
            "position_y": 0.04,
            "title_font_size": 16,
            "label_font_size": 14,
            "fmt": "%.0f",
            "n_labels": 5,
            "color": "black",
        },
    )
    P = result.peak_step.load
    shown_as = f"displacements magnified {factor:g}×" if factor > 1 else "displacements true scale"
    title = plotter.add_text(
        f"{case.cable.name}: wire axial force in the outer layer within ±{half * 1e3:.0f} mm of "
        f"midspan\nat {at_peak} (downwards), T = {case.load.tension / 1e3:g} kN; "
        f"{shown_as}",
        position=(0.5, 0.97),
        viewport=True,
        font_size=12,
        color="black",
        name="title",
    )
    title.GetTextProperty().SetJustificationToCentered()
    title.GetTextProperty().SetVerticalJustificationToTop()
    if note:
        plotter.add_text(note, position="lower_left", font_size=9, color="red")
    d = np.asarray(case.load.direction, float) * np.sign(P or 1.0)
    axis = np.array([0.0, 0.0, 1.0])
    start, end = (L / 2 - half) * axis, (L / 2 + half) * axis
    below = d * 1.25 * D  # the picture's down is d: under the deflected strand
    along = plotter.add_ruler(
        start + below,
        end + below,
        title="z (mm, true scale)",
        number_labels=5,
        label_format="%.0f",
        font_size_factor=0.45,
        label_color="black",
        tick_color="black",
    )
    along.SetRange(1e3 * start[2], 1e3 * end[2])
    step = _round_length(D / (2 * factor))  # a displacement shown as up to D/2
    beside = end + 0.15 * half * axis
    plotter.add_ruler(
        beside + d * step * factor,
        beside,
        flip_range=True,
        scale=1e3 / factor,
        title="deflection (mm)",
        number_labels=2,
        label_format="%.3g",
        font_size_factor=0.45,
        label_color="black",
        tick_color="black",
    )
    # seen across the load, the load downwards and z to the right, in parallel projection: the
    # shown length over 80 % of the width, a little left of the middle, the axis above it (set
    # after the rulers, which reset the camera)
    plotter.view_vector(-np.cross(axis, d), viewup=-d)
    plotter.enable_parallel_projection()
    plotter.reset_camera()
    camera, middle = plotter.camera, (L / 2 + 0.1 * half) * axis + 0.5 * D * d
    camera.position = middle + (np.asarray(camera.position) - np.asarray(camera.focal_point))
    camera.focal_point = middle
    camera.parallel_scale = 2 * half / 0.8 / (width / height) / 2
    fit_text(plotter, title)
    return save(plotter, path)


def _round_length(length: float) -> float:
    """The largest 1, 2 or 5 × 10^k not above ``length`` (> 0)."""
    decade = 10.0 ** np.floor(np.log10(length))
    return float(max(f * decade for f in (1, 2, 5) if f * decade <= length * (1 + 1e-12)))


def text_extent(plotter, actor) -> tuple[float, float, float, float]:
    """The extent of the text ``actor`` in the rendered picture (pixels: x0, x1, y0, y1)."""
    plotter.render()
    box = [0.0] * 4
    actor.GetBoundingBox(plotter.renderer, box)  # about the actor's own position
    x, y = actor.GetPositionCoordinate().GetComputedDisplayValue(plotter.renderer)
    return x + box[0], x + box[1], y + box[2], y + box[3]


def fit_text(plotter, actor, margin: float = 0.02, smallest: int = 8) -> tuple[float, ...]:
    """Shrink the font of the text ``actor`` until it lies within the picture, ``margin`` of its
    width from either edge (down to ``smallest`` points); its extent (``text_extent``)."""
    width, height = plotter.window_size
    prop = actor.GetTextProperty()
    while True:
        x0, x1, y0, y1 = box = text_extent(plotter, actor)
        if (
            x0 >= margin * width
            and x1 <= (1 - margin) * width
            and y0 >= 0
            and y1 <= height
            or prop.GetFontSize() <= smallest
        ):
            return box
        prop.SetFontSize(prop.GetFontSize() - 1)
