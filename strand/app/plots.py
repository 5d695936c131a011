"""Figures of a run (matplotlib, and the deformed strand with pyvista): the wires' axial forces,
the set-up kind's own figures and the deformed strand; the fatigue report's figures:
``strand.app.fatigue.figures``. The pictures themselves (off-screen pyvista, wires as tubes) are
the library's (``strand.cable.pictures``)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..cable.pictures import offscreen_plotter, save

__all__ = ["results_figures", "save_figure"]


def results_figures(case, result, problem, kind) -> list[Path]:
    """The run's figures (PNG) in ``result.folder``: axial force along z per layer and sector at
    the largest load (the seed paper's Fig. 3), its change from the tensioned state (Fig. 4), the
    set-up ``kind``'s own (``SetupKind.figures``; the saddle test's load–deflection loop, Fig. 5),
    and the deformed strand coloured by axial force; titles give the largest load as the kind
    names it (``SetupKind.load_text``). Figures whose data the run did not reach are skipped."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from ..model.post import sector_of

    folder = Path(result.folder)
    paths = []
    n_layers = len(case.cable.layers)
    L = case.mesh.length
    cmap = plt.get_cmap("twilight", 8)

    note = incomplete_note(result)

    def save_fig(fig, name, tight=True):
        paths.append(save_figure(fig, folder / name, note, tight))

    peak, base = result.peak, result.tensioned
    at_peak = kind.load_text(result.peak_step.load if result.peak_step is not None else 0.0)
    if peak is not None:
        fig, axes = plt.subplots(n_layers, 1, figsize=(9, 2.2 * n_layers), sharex=True)
        for i, ax in enumerate(np.atleast_1d(axes)):
            m = peak.layer == i
            sec = sector_of(peak.phi[m])
            sc = ax.scatter(
                1e3 * peak.z[m], peak.axial[m], c=sec, cmap=cmap, vmin=-0.5, vmax=7.5, s=3
            )
            ax.set_ylabel(f"{'core' if i == 0 else f'layer {i}'}\nN (N)")
        ax.set_xlabel("z (mm)")
        cb = fig.colorbar(sc, ax=axes, ticks=range(8))
        cb.ax.set_yticklabels([f"{-180 + 45 * k}…{-135 + 45 * k}°" for k in range(8)])
        cb.set_label("sector of φ (90° = stretched fibre)")
        fig.suptitle(f"wire axial forces at {at_peak}, T = {case.load.tension / 1e3:g} kN")
        save_fig(fig, "axial_force_sectors.png", tight=False)

    if peak is not None and base is not None:
        fig, axes = plt.subplots(
            1,
            n_layers - 1,
            sharey=True,
            layout="constrained",
            figsize=(max(3.2 * (n_layers - 1), 6.0) + 1.0, 3.8),
        )
        near = np.abs(peak.z - L / 2) <= 0.1 * L
        for i, ax in enumerate(np.atleast_1d(axes), start=1):
            m = near & (peak.layer == i)
            sc = ax.scatter(
                peak.phi[m],
                peak.axial[m] - base.axial[m],
                s=3,
                c=1e3 * peak.z[m],
                cmap="viridis",
                vmin=1e3 * 0.4 * L,
                vmax=1e3 * 0.6 * L,
            )
            ax.axhline(0, color="k", lw=0.5)
            ax.set_xticks([-180, -90, 0, 90, 180])
            ax.set_title(f"layer {i}")
            ax.set_xlabel("φ (deg), 90° = stretched fibre")
        np.atleast_1d(axes)[0].set_ylabel("ΔN (N)")
        fig.colorbar(sc, ax=axes, label="z (mm)", pad=0.01)
        fig.suptitle(
            f"change of wire axial force from the tensioned state to {at_peak}\n"
            f"(elements within ±{0.1 * L * 1e3:g} mm of midspan)"
        )
        save_fig(fig, "axial_force_change.png", tight=False)

    paths += kind.figures(case, result, note)

    if peak is not None and result.peak_w is not None:
        paths.append(
            deformed_picture(
                case, result, problem, folder / "deformed_axial_force.png", at_peak, note
            )
        )
    return paths


def save_figure(fig, path: Path, note: str = "", tight: bool = True) -> Path:
    """Lay out ``fig`` (``tight``: tight layout; else its own engine, e.g. constrained for a
    colour bar shared by several axes), with ``note`` in red along the bottom; save and close."""
    import matplotlib.pyplot as plt

    if tight:
        fig.tight_layout(rect=(0, 0.04 if note else 0, 1, 1))
    elif note and fig.get_layout_engine() is not None:  # constrained: leave the bottom free
        fig.get_layout_engine().set(rect=(0, 0.05, 1, 0.95))
    if note:
        fig.text(0.5, 0.005, note, color="tab:red", ha="center", va="bottom", fontsize=9)
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def incomplete_note(result) -> str:
    """The line a figure of a run that stopped early carries ("" for a complete run)."""
    if not result.failure:
        return ""
    how = "was interrupted" if result.interrupted else "stopped early (a load step failed)"
    return f"INCOMPLETE: the run {how} after step {len(result.steps)}; see summary.txt"


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
