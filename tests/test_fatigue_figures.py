"""The fatigue figures' content, read back from their artists (no pixels): ``stress_range.png``
shows every layer and stars the largest range wherever it lies (here in the core, not the outer
layer); ``spectrum.png`` gives each class's damage and places the classes on the wire S–N and the
T–N curves."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest

import strand.app.plots as plots
from strand.app.fatigue.findings import ElementResults
from strand.app.fatigue.stress_range import largest_range, layer_envelope, stress_range_figure
from strand.app.fatigue.wire_stresses import wire_results
from strand.fatigue import SN_CURVES

STEEL = SN_CURVES["en1992-prestressing-steel"]


@pytest.fixture
def drawn(monkeypatch):
    """The figures saved while the test runs, by file name (drawn, then closed)."""
    figures = {}
    save = plots.save_figure

    def keep(fig, path, *args, **kwargs):
        figures[path.name] = fig
        return save(fig, path, *args, **kwargs)

    monkeypatch.setattr(plots, "save_figure", keep)
    return figures


def three_layers() -> ElementResults:
    """A core, 6 wires in layer 1 and 12 in layer 2, 30 elements each over 0.3 m, clamp zones
    of 50 mm: ranges of 150–250 MPa, the core's largest 420 MPa at z = 295 mm (its last
    element), layer 2's 310 MPa in the free span (wire 11 at z = 145 mm)."""
    z = (np.arange(30) + 0.5) * 0.01
    wires, layers = np.arange(19), np.array([0] + [1] * 6 + [2] * 12)
    rng = np.random.default_rng(5)
    ranges = 150e6 + 100e6 * rng.random((19, 30))
    ranges[0, -1] = 420e6
    ranges[11, 14] = 310e6
    E = 19 * 30
    return ElementResults(
        wire=np.repeat(wires, 30),
        layer=np.repeat(layers, 30),
        z=np.tile(z, 19),
        clamp=np.tile((z < 0.05) | (z > 0.25), 19),
        angle=np.zeros(E),
        range=ranges.ravel(),
        mean=np.full(E, 500e6),
        peak=np.full(E, 600e6),
        shear_range=np.zeros(E),
        damage=np.zeros(E),
    )


def report_of(elements: ElementResults, curves: list) -> SimpleNamespace:
    """What ``stress_range_figure`` reads of a fatigue report."""
    return SimpleNamespace(
        elements=elements,
        wires=wire_results(elements, curves),
        curves=curves,
        end_zone=0.05,
        length=0.3,
        poffenberger_swart=None,
        mean_stress="none",
    )


def test_the_largest_range_is_found_in_any_layer():
    largest = largest_range(three_layers())
    assert (largest.range, largest.wire, largest.layer, largest.clamp) == (420e6, 0, 0, True)
    assert largest.z == pytest.approx(0.295)
    assert largest.where() == "wire 0 (core), z = 295.0 mm, clamp zone"


def test_a_layers_envelope_holds_its_largest_range_at_each_z():
    """Layer 2's envelope: a point per element length of its wires (30), z increasing, each the
    largest of its 12 wires there; wire 11's 310 MPa at z = 145 mm among them."""
    elements = three_layers()
    z, ranges, wires = layer_envelope(elements, 2)
    assert len(z) == 30 and np.all(np.diff(z) > 0)
    table = elements.range.reshape(19, 30)[7:]
    np.testing.assert_array_equal(ranges, table.max(axis=0))
    np.testing.assert_array_equal(wires, 7 + table.argmax(axis=0))
    assert (ranges[14], wires[14], z[14]) == (310e6, 11, pytest.approx(0.145))


def test_stress_range_draws_every_layer_and_stars_the_largest_in_the_core(tmp_path, drawn):
    """Along z a line per layer (core, 1, 2) peaking at its largest range; the star on the
    core's 420 MPa at z = 295 mm, in both panels, its place in the annotation and the title. On
    the S–N side the core's and layer 1's wires on the steel curve, layer 2 named as not
    assessed (no curve)."""
    stress_range_figure(
        tmp_path / "stress_range.png", report_of(three_layers(), [STEEL] * 2 + [None])
    )
    fig = drawn["stress_range.png"]
    along, sn = fig.axes[:2]
    peaks = {ln.get_gid(): max(ln.get_ydata()) for ln in along.lines if ln.get_gid()}
    assert peaks == {"envelope 0": 420, "envelope 1": pytest.approx(250, abs=5),
                     "envelope 2": 310, "largest": 420}  # fmt: skip
    (star,) = [ln for ln in along.lines if ln.get_gid() == "largest"]
    assert (star.get_xdata()[0], star.get_ydata()[0]) == (pytest.approx(295), 420)
    (note,) = [t for t in along.texts if t.get_gid() == "largest"]
    assert note.get_text() == "largest: 420.0 MPa\nwire 0 (core)\nz = 295.0 mm, clamp zone"
    assert "largest 420.0 MPa, wire 0 (core), z = 295.0 mm" in fig._suptitle.get_text()
    gids = {ln.get_gid() for ln in sn.lines}
    assert {"0 clamp zone", "1 free span", "1 clamp zone", "largest"} <= gids
    assert not any(g and g.startswith("2 ") for g in gids)
    (on_curve,) = [ln for ln in sn.lines if ln.get_gid() == "largest"]
    assert on_curve.get_xdata()[0] == pytest.approx(STEEL.life(210e6))
    assert "not assessed: layer 2" in sn.get_title()
