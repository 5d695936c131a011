"""Where each layer's pressure goes (``strand.model.layer_pressure``): on the core, round the
ring, against the fibre model."""

from __future__ import annotations

import io
from functools import partial
from pathlib import Path

import numpy as np
import pytest

from strand.app.case import load_case
from strand.app.run import run_case
from strand.app.summary import contact_force_line
from strand.cable.geometry import build_geometry
from strand.model.cell_results import cell_results
from strand.model.contact_settings import ContactSettings
from strand.model.layer_pressure import in_middle_half, layer_pressure, layer_wire_forces
from strand.model.pair_results import PairResults
from strand.model.problem import StrandProblem
from strand.setups.saddle import SaddleTest
from strand.solver import LoadStepper, NewtonOptions
from strand_cases import SEVEN_WIRE, nineteen_wire, seven_wire


def _seven_wire():
    """A 1+6 of equal 3.34 mm wires at 6.06°: its helices would overlap, so packed neighbours
    touch all round (a closed ring)."""
    return seven_wire().cable


def _tensioned(
    same_layer: str,
    model: str = "small",
    stencil: str = "segment",
    geometry=None,
    tension: float = 10e3,
    first_layer: str = "on_core",
    first_step: float | None = None,
):
    """Layer pressure of ``geometry`` (default: a 0.15 m 1+6) pulled to ``tension`` (N)."""
    geometry = geometry or build_geometry(_seven_wire(), 0.15, 4e-3, facing=stencil == "facing")
    settings = ContactSettings(
        same_layer=same_layer, model=model, same_layer_stencil=stencil, first_layer=first_layer
    )
    problem = StrandProblem(
        geometry, settings, NewtonOptions(atol=1e-4, max_it=15), setup=SaddleTest
    )
    first, least = (tension / 2, tension / 10) if first_step is None else (first_step, 10.0)
    LoadStepper(problem.solver, first, least).ramp(
        partial(problem.setup.set, "tension"), 0.0, tension
    )
    model = problem.model
    cells = cell_results(model)
    forces = layer_wire_forces(cells.layer, cells.z, cells.axial, geometry.length)
    return layer_pressure(
        geometry,
        model.pair_results(),
        forces,
        model.positions(),
        same_layer=model.same_layer_pairs,
        same_layer_state=model.same_layer_history(),
    )


def test_without_neighbours_the_core_takes_the_fibre_pressure():
    """A tensioned 1+6 without same-layer contact: the core's line pairs take the layer's
    whole fibre pressure n T sin²α / (r cos α) (measured 0.4 % apart)."""
    (layer,) = _tensioned("off")
    print(layer)
    assert layer.ring == 0 and layer.hoop == 0
    assert layer.crossings_below == pytest.approx(layer.fibre, rel=0.03)
    assert layer.wire_force == pytest.approx(10e3 / 7, rel=0.2)


@pytest.mark.parametrize(
    "model, stencil",
    [("small", "segment"), ("small", "node"), ("small", "facing"), ("large", "segment")],
)
def test_a_jammed_ring_takes_the_rest(model, stencil):
    """Packed equal wires jam into a closed ring: it carries a third of the fibre pressure, the
    core the rest, q_fibre = q_below + q_ring within 3 % (measured 2.0 %: the fibre model leaves
    out the wires' shear forces, and small-sliding same-layer pairs on their neighbours' chords
    carry 2 % less force at h = 4 mm, ``same_layer``'s docstring); the ring's normal part
    follows the polygon relation 2 n sin(π/n) H (measured 0.9 %, the chords' lean along z). The
    same with the node and facing stencils and in large sliding, whose groups give their
    normals b → a (facing: 1.9 %, the ring 40 % of the fibre pressure, segment 38 %: its mesh
    loads the core at one node per wire, docs/theory.md §3.4)."""
    (layer,) = _tensioned("packed", model, stencil)
    print(layer)
    assert layer.gap_closed and layer.gap_min < 0 and layer.gap_force > 0
    assert min(layer.bounding) > 0
    assert 0.2 < layer.ring / layer.fibre < 0.5
    assert layer.crossings_below + layer.ring == pytest.approx(layer.fibre, rel=0.03)
    normal = layer.ring - layer.ring_friction
    assert normal == pytest.approx(2 * 6 * np.sin(np.pi / 6) * layer.hoop, rel=0.02)


@pytest.mark.parametrize("same_layer, tolerance", [("off", 0.015), ("packed", 0.045)])
def test_each_layer_of_a_1_6_12_is_in_radial_equilibrium(same_layer, tolerance):
    """0.1 m of Cardinal's 1+6+12 at 20 kN: layer 1 carries its own pressure and layer 2's,
    q_fibre,1 + q_below,2 = q_below,1 + q_ring,1, and layer 2 its own. Without same-layer
    contact within 1.5 % (measured 0.6 and 0.9 %); packed within 4.5 % (measured 2.3–3.4 %
    over two load paths: besides the 1+6's 2 %, the crossings' own friction and the shear
    forces of wires bent between crossings). Packed, layer 1's ring jams, its gap closed; layer 2's gap, 12 ×
    62 µm of spare circumference, stays open; its arch of touching wires, held by friction,
    carries some (6 % here, 17 % with other load steps: the split depends on the path)."""
    inner, outer = _tensioned(same_layer, geometry=nineteen_wire(0.1, 4e-3), tension=20e3)
    print(inner, outer, sep="\n")
    assert inner.fibre + outer.crossings_below == pytest.approx(
        inner.crossings_below + inner.ring, rel=tolerance
    )
    assert outer.fibre == pytest.approx(outer.crossings_below + outer.ring, rel=tolerance)
    if same_layer == "packed":
        assert inner.gap_closed and not outer.gap_closed
        assert outer.gap_min == pytest.approx(12 * 62.0e-6, rel=0.1)
        assert 0 < outer.ring / outer.fibre < 0.3


def test_a_bending_run_reports_and_draws_where_the_pressure_goes(tmp_path):
    """A quick 1+6 bending run (packed layers, 0.1 m) writes the table at tension and at the
    largest curvature in its summary, and ``layer_pressure.png``."""
    path = tmp_path / "seven.toml"
    path.write_text(SEVEN_WIRE.replace('same_layer = "off"', 'same_layer = "packed"'))
    bending = [
        'load.kind="bending"',
        "load.curvature=0.05",
        "load.zone=0.04",
        "steps.curvature=0.025",
        "steps.curvature_max=0.05",
        "load.cycle=[1.0]",
    ]
    case = load_case(
        path, [*bending, "output.fields=false", "fatigue.outputs=false", "output.plots=true"]
    )
    result = run_case(case, tmp_path / "out", stream=io.StringIO())
    summary = (tmp_path / "out" / "summary.txt").read_text()
    print(summary[summary.index("where each layer") :])
    assert "where each layer's pressure goes" in summary
    assert "at the largest load κ = 0.05 1/m:" in summary
    assert (tmp_path / "out" / "layer_pressure.png").stat().st_size > 10_000
    for state in (result.tensioned_layers, result.peak_layers):
        (layer,) = state
        assert layer.gap_closed
        assert layer.crossings_below + layer.ring == pytest.approx(layer.fibre, rel=0.05)


def test_the_summary_and_layer_pressure_take_the_same_middle_half():
    """The middle half is [L/4, 3L/4), half-open to round-off, wherever a sum or mean is taken
    over it. The quick 1+6 has line pairs at z = L/4 and 3L/4 (3L/4 lands above 0.225 in
    floating point); loaded alone, those at L/4 give the summary's mean contact force, which
    left them out before the two were one function."""
    case = load_case(Path(__file__).resolve().parents[1] / "cases" / "quick_1x6.toml")
    L = case.mesh.length
    assert in_middle_half([L / 4, L / 2, 3 * L / 4 - 1e-9], L).all()
    assert not in_middle_half([L / 4 - 1e-9, 3 * L / 4, 0.225], L).any()
    g = build_geometry(case.cable, L, case.mesh.h_max)
    z = g.points[g.pairs.a, 2]
    start = np.isclose(z, L / 4, rtol=0, atol=1e-12)
    end = np.isclose(z, 3 * L / 4, rtol=0, atol=1e-12)
    assert start.sum() == end.sum() == 6
    P = len(z)
    zeros, vectors = np.zeros(P), np.zeros((P, 3))
    pairs = PairResults(
        gap=zeros,
        force=np.where(start, 100.0, 0.0),
        traction=zeros,
        slipping=np.zeros(P, bool),
        friction=vectors,
        normal=vectors,
        slip=vectors,
        sliding=vectors,
        work=zeros,
    )
    inside = in_middle_half(z, L)
    assert inside[start].all() and not inside[end].any()  # those at 3L/4 are the next span's
    expected = 100.0 * start.sum() / g.pairs.tributary[inside].sum()
    assert contact_force_line(g, pairs).endswith(f"0|1 {expected:.0f} N/m")
