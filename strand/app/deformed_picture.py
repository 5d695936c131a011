"""The deformed strand as a picture (pyvista, off-screen): the outer layer near midspan at the
largest load, coloured by wire axial force, displacements magnified, with rulers for its scale
(``deformed_picture``, ``deformed_axial_force.png``); the pictures themselves (wires as tubes) are
the library's (``strand.cable.pictures``). Units: m, mm on the rulers.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..cable.pictures import offscreen_plotter, save

__all__ = [
    "deformed_picture",
    "magnification",
    "fit_text",
    "text_extent",
    "STRAND_REGION",
    "parallel_frame",
    "projected_extent",
]

#: where the strand and its rulers go in the picture (fractions of its width and height: x from,
#: x to, y from, y to): below the title, above the colour bar, room on the right for the
#: deflection ruler's labels and below for the z ruler's
STRAND_REGION = (0.05, 0.85, 0.27, 0.84)


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
    at the largest load and coloured by wire axial force, seen across the load (``_tubes``).
    Displacements across the axis are magnified (``magnification``: the largest shown as up to
    half the strand's diameter), along it at true scale, the factor in the title (two lines,
    shrunk to fit the picture: ``fit_text``); two rulers give the scale: z along the strand (mm,
    true scale) under the tubes, and
    beyond its right end the deflection (mm, as magnified) down from the undeformed axis. The
    camera frames the tubes and the rulers within ``STRAND_REGION`` (``parallel_frame``), in a
    picture 650 pixels high and as wide as they need (1100–1800): a strand a few diameters long
    is in view as a long one is. ``at_peak``: the largest load as the title gives it
    (``SetupKind.load_text``)."""
    L, D = case.mesh.length, case.cable.outer_diameter
    half = min(L / 2, max(0.15 * L, 6 * D))
    grid, factor = _tubes(case, result, problem.geometry, half)
    d = np.asarray(case.load.direction, float) * np.sign(result.peak_step.load or 1.0)
    axis = np.array([0.0, 0.0, 1.0])
    start, end = (L / 2 - half) * axis, (L / 2 + half) * axis
    below = d * (np.max(grid.points @ d) + 0.2 * D)  # the picture's down is d: under the tubes
    beside = (grid.bounds[5] + max(0.15 * half, 0.3 * D)) * axis
    content = np.vstack([_corners(grid.bounds), start + below, end + below, beside])
    height = 650
    width = _width(content, axis, -d, height)
    plotter = offscreen_plotter(window_size=(width, height))
    plotter.add_mesh(
        grid,
        name="strand",
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
    shown_as = (
        f"displacements across the axis magnified {factor:g}×"
        if factor > 1
        else "displacements true scale"
    )
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
    deflection = plotter.add_ruler(
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
    deflection.SetTitlePosition(-0.15)  # under the ruler, clear of its two labels
    # seen across the load, the load downwards and z to the right, in parallel projection: the
    # strand and its rulers fill STRAND_REGION (set after the rulers, which reset the camera)
    focal, scale = parallel_frame(content, axis, -d, width / height)
    camera = plotter.camera
    camera.parallel_projection = True
    camera.focal_point = focal
    camera.position = focal - np.cross(axis, d) * 10 * (np.ptp(content, axis=0).max() + D)
    camera.up = -d
    camera.parallel_scale = scale
    plotter.renderer.ResetCameraClippingRange()
    fit_text(plotter, title)
    return save(plotter, path)


def _tubes(case, result, geometry, half: float):
    """The outer layer's wires within ±``half`` (m) of midspan as tubes, displaced at the
    largest load, coloured by axial force ("N (N)"); the displacements across the axis
    magnified (``magnification``), along it at true scale as the z ruler reads them. The tubes
    and the factor."""
    import pyvista

    peak, L = result.peak, case.mesh.length
    outer = len(case.cable.layers) - 1
    shown = np.flatnonzero((peak.layer == outer) & (np.abs(peak.z - L / 2) <= half))
    u = result.peak_w[:, :3]  # the geometry's point order, whole on every rank
    across = float(np.abs(u[geometry.cells[shown], :2]).max(initial=0.0))
    factor = magnification(across, case.cable.outer_diameter)
    x = geometry.points + u * np.array([factor, factor, 1.0])
    lines = np.column_stack([np.full(len(shown), 2), geometry.cells[shown]]).ravel()
    grid = pyvista.PolyData(x, lines=lines)
    grid.cell_data["N (N)"] = peak.axial[shown]
    radius = case.cable.layers[-1].wire.diameter / 2
    return grid.cell_data_to_point_data().tube(radius=radius, n_sides=16), factor


def _corners(bounds) -> np.ndarray:
    """The eight corners (8, 3) of the box ``bounds`` (x0, x1, y0, y1, z0, z1)."""
    x, y, z = np.asarray(bounds, float).reshape(3, 2)
    return np.array([[a, b, c] for a in x for b in y for c in z])


def _width(content: np.ndarray, right, up, height: int) -> int:
    """The picture's width (pixels, 1100–1800) for ``content`` (points, m) seen with ``right``
    and ``up`` in STRAND_REGION of a picture ``height`` high: a short, thick strand gets a
    narrower picture than a long, thin one."""
    x0, x1, y0, y1 = STRAND_REGION
    wide = np.ptp(content @ right) / (x1 - x0)
    high = np.ptp(content @ up) / (y1 - y0)
    return int(np.clip(height * wide / max(high, 1e-300), 1100, 1800))


def parallel_frame(content, right, up, aspect: float, region=STRAND_REGION):
    """The focal point and parallel scale (half the picture's height, m) that put the points
    ``content`` (m) seen with ``right`` and ``up`` (unit vectors) within ``region`` (fractions
    of the picture: x from, x to, y from, y to) of a picture of width/height ``aspect``, filling
    it in one direction and centred in it in the other."""
    right, up = np.asarray(right, float), np.asarray(up, float)
    content = np.asarray(content, float)
    x, y = content @ right, content @ up
    x0, x1, y0, y1 = region
    scale = max(np.ptp(x) / (2 * aspect * (x1 - x0)), np.ptp(y) / (2 * (y1 - y0)))
    width, height = 2 * scale * aspect, 2 * scale
    along = (x.min() + x.max()) / 2 - ((x0 + x1) / 2 - 0.5) * width
    across = (y.min() + y.max()) / 2 - ((y0 + y1) / 2 - 0.5) * height
    return along * right + across * up, float(scale)


def projected_extent(plotter, points) -> tuple[float, float, float, float]:
    """Where the points (m) lie in the rendered picture: pixels x0, x1, y0, y1 (y up)."""
    import vtk

    plotter.render()
    coordinate = vtk.vtkCoordinate()
    coordinate.SetCoordinateSystemToWorld()
    xy = []
    for p in np.asarray(points, float):
        coordinate.SetValue(*p)
        xy.append(coordinate.GetComputedDoubleDisplayValue(plotter.renderer))
    xy = np.array(xy)
    return xy[:, 0].min(), xy[:, 0].max(), xy[:, 1].min(), xy[:, 1].max()


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
