"""Figures readable alone: the deformed picture's magnification, and on the quick case as a user
first runs it (``quick_run``), titles inside their figures, a scale on the deformed view, the S–N
curve that stress_range.png promises, and both analytical laws of load_deflection.png in sight."""

import csv
from pathlib import Path

import numpy as np
import pytest
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.colors import to_rgba

from strand.app.deformed_picture import magnification
from strand.fatigue import SN_CURVES

ROOT = Path(__file__).parents[1]


@pytest.mark.parametrize("largest", [1e-7, 3.3e-6, 4e-5, 1.2e-4, 9e-4, 2.4e-3])
def test_magnification_shows_the_largest_displacement_as_a_fifth_to_a_half_of_the_size(largest):
    """A round factor (1, 2 or 5 × 10^k) that brings the largest displacement to between a fifth
    and a half of the strand's diameter, never below 1 (a displacement already that large is
    shown at true scale)."""
    size = 10e-3
    f = magnification(largest, size)
    mantissa = f / 10 ** np.floor(np.log10(f))
    assert f >= 1 and any(np.isclose(mantissa, m) for m in (1, 2, 5))
    if f > 1:
        assert size / 5 <= f * largest <= size / 2 * (1 + 1e-12)
    else:
        assert largest > size / 5
    assert magnification(0.0, size) == 1.0


def test_every_title_lies_inside_its_figure(quick_run):
    """Every title, suptitle, axis label and legend of the run's matplotlib figures is drawn
    inside the figure: none is clipped at an edge."""
    figures = quick_run["figures"]
    assert {"load_deflection.png", "stress_range.png", "fretting_map.png"} <= set(figures)
    for name, fig in figures.items():
        canvas = FigureCanvasAgg(fig)  # saved and closed: drawn again as it was saved
        canvas.draw()
        renderer = canvas.get_renderer()
        texts = [fig._suptitle] + [
            t for ax in fig.axes for t in (ax.title, ax.xaxis.label, ax.yaxis.label)
        ]
        texts += [ax.get_legend() for ax in fig.axes]
        for t in texts:
            if t is None or (hasattr(t, "get_text") and not t.get_text()):
                continue
            box = t.get_window_extent(renderer)
            assert fig.bbox.x0 <= box.x0 and box.x1 <= fig.bbox.x1, (name, t)
            assert fig.bbox.y0 <= box.y0 and box.y1 <= fig.bbox.y1, (name, t)


def test_the_deformed_view_has_a_title_that_fits_and_a_scale(quick_run):
    """deformed_axial_force.png: its title, with the magnification, lies within the picture;
    a ruler along the strand gives z (mm, true scale) and one beside it the deflection (mm) as
    magnified, a round length."""
    p = quick_run["pictures"]["deformed_axial_force.png"]
    (x0, x1, y0, y1), (width, height) = p["title"], p["window"]
    assert 0 < x0 < x1 < width and 0 < y0 < y1 <= height, p
    factor = float(p["text"].split("magnified ")[1].split("×")[0])
    assert factor > 1 and "P = 0.30 kN" in p["text"]
    rulers = dict(p["rulers"])
    D = quick_run["case"].cable.outer_diameter  # 10.02 mm: the view shows ±6 D of midspan
    shown = rulers["z (mm, true scale)"]
    assert shown == pytest.approx((1e3 * (0.15 - 6 * D), 1e3 * (0.15 + 6 * D)))
    across = rulers["deflection (mm)"][::-1]  # from the axis down
    mantissa = across[1] / 10 ** np.floor(np.log10(across[1]))
    assert across[0] == 0 and any(np.isclose(mantissa, m) for m in (1, 2, 5))
    assert D / 10 < 1e-3 * across[1] * factor <= D / 2  # drawn as up to half the strand


def test_stress_range_draws_the_sn_curve_with_the_wires_on_it(quick_run):
    """stress_range.png: beside the ranges along z, every layer's S–N curve (EN 1992-1-1's
    prestressing steel, Δσ = 2σ_a against N) and each wire's largest range in the free span and
    the clamp zone (wires.csv), the core's and the outer layer's, placed on it at its life."""
    fig = quick_run["figures"]["stress_range.png"]
    sn = next(ax for ax in fig.axes if ax.get_xscale() == "log" and ax.get_yscale() == "log")
    curve = SN_CURVES["en1992-prestressing-steel"]
    line = next(ln for ln in sn.lines if ln.get_label().startswith("prestressing steel"))
    n, delta = line.get_data()
    assert n.min() <= 1e4 and n.max() >= 1e9
    np.testing.assert_allclose(curve.life(1e6 * np.asarray(delta) / 2), n, rtol=1e-9)
    with open(quick_run["folder"] / "wires.csv") as f:
        rows = list(csv.DictReader(f))
    for layer in ("0", "1"):
        wires = [w for w in rows if w["layer"] == layer]
        for zone, key in (
            ("free span", "range_free_span_MPa"),
            ("clamp zone", "range_clamp_zone_MPa"),
        ):
            points = next(ln for ln in sn.lines if ln.get_gid() == f"{layer} {zone}")
            x, y = points.get_data()
            expected = sorted(float(w[key]) for w in wires)
            np.testing.assert_allclose(sorted(y), expected, rtol=1e-5)
            np.testing.assert_allclose(x, curve.life(1e6 * np.asarray(y) / 2), rtol=1e-9)


def test_stress_range_shows_every_layer_and_stars_the_largest(quick_run):
    """stress_range.png along z: a line per layer (the core and layer 1) whose peak is that
    layer's largest range in wire_stresses.csv, and a star on the largest of all, annotated
    with its value, wire, layer and z, as the suptitle says too."""
    fig = quick_run["figures"]["stress_range.png"]
    along = next(ax for ax in fig.axes if ax.get_xlabel() == "z (mm)")
    with open(quick_run["folder"] / "wire_stresses.csv") as f:
        rows = [
            {k: float(v) if k != "zone" else v for k, v in r.items()} for r in csv.DictReader(f)
        ]
    for layer in (0, 1):
        line = next(ln for ln in along.lines if ln.get_gid() == f"envelope {layer}")
        top = max(r["range_MPa"] for r in rows if r["layer"] == layer)
        assert max(line.get_ydata()) == pytest.approx(top, rel=1e-5), layer
    worst = max(rows, key=lambda r: r["range_MPa"])
    (star,) = [ln for ln in along.lines if ln.get_gid() == "largest"]
    assert star.get_xdata()[0] == pytest.approx(1e3 * worst["z_m"], abs=0.01)
    assert star.get_ydata()[0] == pytest.approx(worst["range_MPa"], rel=1e-5)
    (note,) = [t for t in along.texts if t.get_gid() == "largest"]
    place = f"wire {worst['wire']:.0f} (layer {worst['layer']:.0f})"
    assert f"largest: {worst['range_MPa']:.1f} MPa" in note.get_text()
    assert place in note.get_text() and f"z = {1e3 * worst['z_m']:.1f} mm" in note.get_text()
    assert f"largest {worst['range_MPa']:.1f} MPa, {place}" in fig._suptitle.get_text()


def test_load_deflection_keeps_both_laws_in_sight(quick_run):
    """load_deflection.png: the two friction rules of the stick–slip law, which nearly coincide,
    in different colours, one a wide band under the model, the other a thin dashed line over it."""
    ax = quick_run["figures"]["load_deflection.png"].axes[0]
    model = next(ln for ln in ax.lines if ln.get_label() == "model")
    band, line = (
        next(ln for ln in ax.lines if f"({rule}, Masing)" in ln.get_label())
        for rule in ("cumulative", "own tension")
    )
    assert to_rgba(band.get_color())[:3] != to_rgba(line.get_color())[:3]
    assert to_rgba(model.get_color())[:3] not in (
        to_rgba(band.get_color())[:3],
        to_rgba(line.get_color())[:3],
    )
    assert band.get_linewidth() >= 3 * line.get_linewidth()
    assert band.get_zorder() < model.get_zorder() < line.get_zorder()
    assert line.get_linestyle() not in ("-", "solid")


def _picture_of(tmp_path, length: float, deflection: float, monkeypatch) -> dict:
    """The deformed picture of the 120-wire mooring strand (61.2 mm) over ``length`` (m), its
    axis deflected along x by ``deflection`` (m) at midspan in a sine: the plotter's window, the
    projected extents (pixels) of the strand's tubes, of the rulers' ends and of the title, and
    the scalar bar's top."""
    from types import SimpleNamespace

    import strand.app.deformed_picture as picture
    from strand.app.case import load_case
    from strand.cable.geometry import build_geometry

    case = load_case(ROOT / "cases" / "mooring_judge120.toml", [f"mesh.length={length}"])
    g = build_geometry(case.cable, length, 1e-2)
    z = g.points[:, 2]
    w = np.zeros((len(z), 6))
    w[:, 0] = deflection * np.sin(np.pi * z / length)
    cell_z = z[g.cells].mean(axis=1)
    result = SimpleNamespace(
        peak=SimpleNamespace(layer=g.cell_layer, z=cell_z, axial=1e4 + 1e3 * cell_z / length),
        peak_w=w,
        peak_step=SimpleNamespace(load=180.3e3),
    )
    seen, save = {}, picture.save

    def keep(plotter, path):
        strand = plotter.actors["strand"]
        rulers = [p for p in _props(plotter) if p.IsA("vtkAxisActor2D")]
        ends = []
        for r in rulers:
            for c in (r.GetPositionCoordinate(), r.GetPosition2Coordinate()):
                ends.append(c.GetComputedDoubleDisplayValue(plotter.renderer))
        bar = next(p for p in _props(plotter) if p.IsA("vtkScalarBarActor"))
        seen.update(
            window=tuple(plotter.window_size),
            strand=picture.projected_extent(plotter, picture._corners(strand.GetBounds())),
            rulers=np.array(ends),
            title=picture.text_extent(plotter, plotter.actors["title"]),
            bar_top=bar.GetPosition2Coordinate().GetComputedDisplayValue(plotter.renderer)[1],
        )
        return save(plotter, path)

    monkeypatch.setattr(picture, "save", keep)
    picture.deformed_picture(case, result, SimpleNamespace(geometry=g), tmp_path / "d.png", "x")
    return seen


def _props(plotter) -> list:
    props = plotter.renderer.GetViewProps()
    return [props.GetItemAsObject(i) for i in range(props.GetNumberOfItems())]


@pytest.mark.parametrize(("length", "deflection"), [(0.05, 2e-4), (0.15, 1e-4), (0.6, 1e-3)])
def test_the_deformed_picture_frames_a_short_thick_strand(
    tmp_path, monkeypatch, length, deflection
):
    """The mooring strand, 61.2 mm thick, over 0.8, 2.5 and 10 diameters: its tubes, as the
    camera projects them (its bounding box's corners, in pixels), lie within the picture with a
    margin of 3 % of its width and height, under the title and above the colour bar; the
    rulers' ends lie within the picture too. The strand fills the region the picture keeps for
    it in one direction (at least 60 % of its width or height)."""
    seen = _picture_of(tmp_path, length, deflection, monkeypatch)
    width, height = seen["window"]
    x0, x1, y0, y1 = seen["strand"]
    assert 0.03 * width <= x0 < x1 <= 0.97 * width, (seen, width)
    assert 0.03 * height <= y0 < y1 <= 0.97 * height, (seen, height)
    assert y1 < seen["title"][2] and y0 > seen["bar_top"], seen
    rulers = seen["rulers"]
    assert np.all((rulers[:, 0] > 0) & (rulers[:, 0] < width)), rulers
    assert np.all((rulers[:, 1] > 0) & (rulers[:, 1] < height)), rulers
    assert (x1 - x0) >= 0.6 * 0.8 * width or (y1 - y0) >= 0.6 * 0.57 * height, seen
