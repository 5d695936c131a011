"""The fatigue figures' content, read back from their artists (no pixels): ``stress_range.png``
shows every layer and stars the largest range wherever it lies (here in the core, not the outer
layer); ``spectrum.png`` gives each class's damage and places the classes on the wire S–N and the
T–N curves."""

from __future__ import annotations

from dataclasses import replace
from types import SimpleNamespace

import numpy as np
import pytest

import strand.app.plots as plots
from strand.app.case import case_from_dict
from strand.app.fatigue.findings import ElementResults
from strand.app.fatigue.spectrum import spectrum_report, write_spectrum
from strand.app.fatigue.spectrum_figure import spectrum_figure, spectrum_figure_data
from strand.app.fatigue.stress_range import largest_range, layer_envelope, stress_range_figure
from strand.app.fatigue.wire_stresses import wire_results
from strand.fatigue import SN_CURVES
from strand.fatigue.tn import api_spiral_strand_life, dnv_spiral_rope_life

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


def test_stress_range_names_the_mean_stress_correction_its_curve_leaves_out(tmp_path, drawn):
    report = replace_ns(report_of(three_layers(), [STEEL] * 3), mean_stress="swt")
    stress_range_figure(tmp_path / "stress_range.png", report)
    title = drawn["stress_range.png"]._suptitle.get_text()
    assert "the damage takes the swt mean-stress correction, the curve the ranges" in title


def replace_ns(namespace: SimpleNamespace, **changes) -> SimpleNamespace:
    return SimpleNamespace(**{**vars(namespace), **changes})


# --- spectrum.png ---------------------------------------------------------------------------

CLASSES = [[100.0, 2e6], [200.0, 3e5], [300.0, 1e4]]  # lateral amplitude (N), cycles a year
AREA, MBS, MEAN = 1e-4, 2e5, 5e4  # m², N, N


def _member(amplitude: float) -> SimpleNamespace:
    """A spectrum member's fatigue report as the spectrum and its figure read it: one steel
    wire of two elements, in the free span (a range of 1.5 MPa per N of amplitude) and at the
    clamp (2 MPa per N), each damaged by one cycle of its range; one pair; a tension range of
    100 N per N of amplitude about 50 kN, with its DNV-OS-E301 and API RP 2SK damage."""
    ranges = np.array([1.5e6, 2e6]) * amplitude
    damage = 1 / STEEL.life(ranges / 2)
    dt = 100 * amplitude
    return SimpleNamespace(
        elements=SimpleNamespace(
            wire=np.array([0, 0]),
            layer=np.array([0, 0]),
            z=np.array([0.5, 0.02]),
            clamp=np.array([False, True]),
            range=ranges,
            damage=damage,
        ),
        crossings=SimpleNamespace(
            interface=np.array([0]),
            wire_a=np.array([0]),
            wire_b=np.array([1]),
            z=np.array([0.5]),
            clamp=np.array([False]),
            line=np.array([True]),
            damage=np.array([damage[0]]),
        ),
        wires=SimpleNamespace(curve=np.array(["en1992-prestressing-steel"])),
        curves=[STEEL],
        end_zone=0.1,
        length=1.0,
        tension_check=SimpleNamespace(
            dnv=float(1 / dnv_spiral_rope_life(dt, AREA)),
            api=float(1 / api_spiral_strand_life(dt, MBS, MEAN)),
            range=dt,
            mean=MEAN,
            cycle=True,
            area=AREA,
        ),
    )


def _spectrum_case(plots: bool = True):
    return case_from_dict(
        {
            "fatigue": {"spectrum": CLASSES, "breaking_strength": MBS},
            "output": {"plots": plots},
        }
    )


def _results() -> list[SimpleNamespace]:
    return [SimpleNamespace(fatigue=_member(a), failure="", interrupted=False) for a, _ in CLASSES]


def test_the_spectrum_figure_data_holds_each_class_at_the_worst_places():
    """The clamp element (largest D) first, then the free span's; per class its range in the
    member and nᵢ/Nᵢ by hand; the T–N classes nᵢ D_T,i; their sums the report's D."""
    results = _results()
    report = spectrum_report(_spectrum_case(), results, "lateral", "N")
    data = spectrum_figure_data(report, [r.fatigue for r in results], MBS)
    amplitudes, counts = np.array(CLASSES).T
    np.testing.assert_array_equal(data.amplitudes, amplitudes)
    np.testing.assert_array_equal(data.counts, counts)
    assert [(p.element, p.clamp) for p in data.places] == [(1, True), (0, False)]
    for place, per_newton in zip(data.places, (2e6, 1.5e6), strict=True):
        np.testing.assert_allclose(place.range, per_newton * amplitudes, rtol=1e-12)
        np.testing.assert_allclose(place.damage, counts / STEEL.life(place.range / 2), rtol=1e-9)
    assert data.places[0].damage.sum() == pytest.approx(np.nanmax(report.wires.damage))
    np.testing.assert_allclose(
        data.dnv, counts / dnv_spiral_rope_life(100 * amplitudes, AREA), rtol=1e-12
    )
    assert data.dnv.sum() == pytest.approx(report.tension.dnv, rel=1e-12)
    assert data.api.sum() == pytest.approx(report.tension.api, rel=1e-12)


def test_the_spectrum_figure_shows_each_class_damage_and_its_place_on_the_curves(tmp_path, drawn):
    """write_spectrum with plots: spectrum.png, its bars a series per place and T–N curve, a
    bar per class of height nᵢ dᵢ, the classes' amplitudes and counts under them; beside, the
    wire's S–N curve, DNV-OS-E301's and API RP 2SK's on ΔT/A, each class at its count and on
    its curve at its life. Without plots, no figure."""
    write_spectrum(tmp_path, _spectrum_case(), _results(), "lateral", "N")
    assert (tmp_path / "spectrum.png").is_file()
    bars, curves = drawn["spectrum.png"].axes[:2]
    amplitudes, counts = np.array(CLASSES).T
    heights = {}
    for bar in bars.patches:
        heights.setdefault(bar.get_gid(), []).append(bar.get_height())
    assert sorted(heights) == ["bars 0", "bars 1", "bars 2", "bars 3"]
    clamp = counts / STEEL.life(1e6 * amplitudes)
    np.testing.assert_allclose(heights["bars 0"], clamp, rtol=1e-9)
    np.testing.assert_allclose(
        heights["bars 3"], counts / api_spiral_strand_life(100 * amplitudes, MBS, MEAN)
    )
    labels = [t.get_text() for t in bars.get_xticklabels()]
    assert labels == ["100 N\nn = 2e+06", "200 N\nn = 3e+05", "300 N\nn = 1e+04"]
    lines = {ln.get_gid(): ln.get_data() for ln in curves.lines if ln.get_gid()}
    n, s = lines["curve dnv"]
    np.testing.assert_allclose(dnv_spiral_rope_life(1e6 * s * AREA, AREA), n, rtol=1e-9)
    n, s = lines["curve api"]
    np.testing.assert_allclose(api_spiral_strand_life(1e6 * s * AREA, MBS, MEAN), n, rtol=1e-9)
    n, s = lines["life wire 0"]
    np.testing.assert_allclose(s, 2 * amplitudes, rtol=1e-12)
    np.testing.assert_allclose(n, STEEL.life(1e6 * amplitudes), rtol=1e-12)
    np.testing.assert_allclose(lines["count wire 1"][0], counts)
    np.testing.assert_allclose(lines["count dnv"][1], 100 * amplitudes / AREA / 1e6)
    other = tmp_path / "no_plots"
    other.mkdir()
    write_spectrum(other, _spectrum_case(plots=False), _results(), "lateral", "N")
    assert not (other / "spectrum.png").exists() and (other / "spectrum.txt").is_file()


def test_the_spectrum_figure_says_what_its_bars_include_that_its_curves_do_not(tmp_path, drawn):
    """With a mean-stress correction and a design fatigue factor, the title names both: the bars
    include them, the curves and the points on them do not."""
    results = _results()
    report = spectrum_report(_spectrum_case(), results, "lateral", "N")
    data = spectrum_figure_data(report, [r.fatigue for r in results], MBS)
    spectrum_figure(
        tmp_path / "spectrum.png", replace(data, mean_stress="goodman", design_factor=3)
    )
    title = drawn["spectrum.png"]._suptitle.get_text()
    assert "the goodman mean-stress correction" in title
    assert "the design fatigue factor 3" in title
    spectrum_figure(tmp_path / "spectrum.png", data)
    assert "\n" not in drawn["spectrum.png"]._suptitle.get_text()


def test_without_a_tension_cycle_the_spectrum_figure_leaves_t_n_out(tmp_path, drawn):
    """No member's tension cycles (a saddle spectrum): the bars and the curves are the wire's
    alone, and the title says why."""
    results = _results()
    for r in results:
        r.fatigue.tension_check.cycle = False
    write_spectrum(tmp_path, _spectrum_case(), results, "lateral", "N")
    fig = drawn["spectrum.png"]
    bars, curves = fig.axes[:2]
    assert {bar.get_gid() for bar in bars.patches} == {"bars 0", "bars 1"}
    gids = {ln.get_gid() for ln in curves.lines} - {None}
    assert gids == {"curve wire", "count wire 0", "life wire 0", "count wire 1", "life wire 1"}
    assert "no tension cycle in any class" in fig._suptitle.get_text()
