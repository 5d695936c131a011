"""Contact between neighbouring wires of one layer (``strand.model.same_layer``): where they face
each other, their gaps, and pairs that open and close on a tensioned 1+6."""

import csv
import io
from dataclasses import replace
from functools import cache, partial
from pathlib import Path

import numpy as np
import pytest

from strand.analytical import held_end_torque
from strand.app.case import load_case
from strand.app.run import build_problem, run_case
from strand.cable.description import CableError, cable_from_dict, cardinal
from strand.cable.geometry import build_geometry
from strand.model.contact_settings import ContactSettings
from strand.model.layer_states import helix_clearance
from strand.model.problem import StrandProblem
from strand.model.programme import run_programme
from strand.model.same_layer import same_layer_pairs
from strand.setups.saddle import SaddleTest
from strand.solver import LoadStepper, NewtonOptions


def _brute_clearance(layer, samples=400_001) -> float:
    """The same distance by dense sampling of the phase lag (independent of the search)."""
    r, n = layer.radius, layer.wires
    omega = np.tan(layer.alpha) / r
    s = np.linspace(-2 * np.pi / n, 0.0, samples)
    return float(np.sqrt(np.min(2 * r * r * (1 - np.cos(s + 2 * np.pi / n)) + (s / omega) ** 2)))


def test_cardinal_gaps_from_its_helices():
    """The module docstring's gaps: layer 1's six steel wires would overlap by 14.1 µm (they
    touch), layers 2-4 stand 62.0, 78.2, 65.6 µm apart; the search agrees with dense sampling,
    and straight wires (lay angle → 0) come to the chord 2r sin(π/n)."""
    layers = cardinal().layers[1:]
    gaps = [helix_clearance(lay) - lay.wire.diameter for lay in layers]
    np.testing.assert_allclose(np.array(gaps) * 1e6, [-14.1, 62.0, 78.2, 65.6], atol=0.05)
    for lay in layers:
        assert helix_clearance(lay) == pytest.approx(_brute_clearance(lay), rel=1e-9)
    flat = replace(layers[1], lay_angle=1e-4)
    assert helix_clearance(flat) == pytest.approx(2 * flat.radius * np.sin(np.pi / 12), rel=1e-8)


def test_pairs_cover_every_wire_once_with_their_gaps():
    """Every wire of a helical layer faces the next: tributary lengths sum to the wire lengths
    (less a node at each end), the facing points lie on their segments, normals lie across the
    wires; "packed" closes every gap but one per layer, which holds the layer's spare
    circumference (none for layer 1, whose wires touch)."""
    g = build_geometry(cardinal(), 0.1, 4e-3)
    nominal, packed = same_layer_pairs(g, "nominal"), same_layer_pairs(g, "packed")
    assert np.all((nominal.weight >= 0) & (nominal.weight <= 1))
    for i, lay in enumerate(g.cable.layers[1:], start=1):
        sel = nominal.layer == i
        wire_length = g.length / np.cos(lay.alpha)
        assert nominal.tributary[sel].sum() == pytest.approx(lay.wires * wire_length, rel=0.05)
        chord = g.points[nominal.b1[sel]] - g.points[nominal.b0[sel]]
        cosine = np.einsum("pi,pi->p", chord, nominal.normal[sel]) / np.linalg.norm(chord, axis=1)
        assert np.abs(cosine).max() < 0.05
        spare = lay.wires * (helix_clearance(lay) - lay.wire.diameter)
        assert np.allclose(nominal.gap[sel], max(spare / lay.wires, 0.0))
        closed = np.isclose(packed.gap[sel], 0.0)
        if spare > 0:
            assert np.allclose(packed.gap[sel][~closed], spare)
            assert 0 < np.sum(~closed) < 2 * g.length / 4e-3  # one wire's pairs
        else:
            assert np.all(closed)


def test_packed_layers_are_the_default():
    """Same-layer contact is on by default, packed, in small and large sliding."""
    assert ContactSettings().same_layer == "packed"
    assert ContactSettings(model="large").same_layer == "packed"
    assert ContactSettings(same_layer="nominal").same_layer == "nominal"


def test_settings_are_checked():
    with pytest.raises(CableError, match="same_layer = 'tight' is unknown"):
        ContactSettings(same_layer="tight")


def _seven_wire(outer_diameter: float):
    """A 1+6 of a 3.34 mm core and six wires of ``outer_diameter``, 6.06°."""
    return cable_from_dict(
        {
            "name": "1+6",
            "core": {"diameter": 3.34e-3, "E": 210e9, "nu": 0.3, "friction": 0.3},
            "layer": [
                {
                    "wires": 6,
                    "diameter": outer_diameter,
                    "E": 180e9,
                    "nu": 0.3,
                    "lay_angle": 6.06,
                    "lay": "S",
                    "friction": 0.5,
                }
            ],
        }
    )


def _tensioned(
    cable, gaps: str, model: str = "small", tension: float = 10e3, stencil: str = "segment"
):
    """A 0.15 m piece of ``cable`` with same-layer pairs ``gaps`` of ``stencil`` in the sliding
    ``model``, pulled to ``tension`` (N): the mid-piece pairs' gaps and forces, their initial
    gaps, the layer's radial change (m) and the strand's strain."""
    geometry = build_geometry(cable, 0.15, 4e-3, facing=stencil == "facing")
    problem = StrandProblem(
        geometry,
        ContactSettings(same_layer=gaps, model=model, same_layer_stencil=stencil),
        NewtonOptions(atol=1e-4, max_it=15),
        setup=SaddleTest,
    )
    setup = problem.setup
    LoadStepper(problem.solver, tension / 2, tension / 10).ramp(
        partial(setup.set, "tension"), 0.0, tension
    )
    pairs = same_layer_pairs(geometry, gaps, stencil)
    state = problem.model.same_layer_history()  # in the pairs' order
    x = geometry.points + problem.model.node_values()[:, :3]
    middle = np.abs(geometry.points[pairs.a, 2] - 0.075) < 0.025
    dr = np.mean(np.linalg.norm(x[pairs.a[middle], :2], axis=1)) - cable.layers[1].radius
    strain = setup.state().end_displacement / geometry.length
    return state["gap"][middle], state["force"][middle], pairs.gap[middle], dr, strain


@pytest.mark.parametrize("model", ["small", "large"])
def test_open_neighbours_approach_as_the_tensioned_layer_tightens(model):
    """Tension presses layer 1 onto the core (its radius shrinks by Δr) and stretches the strand
    by ε (the helix's angular rate falls to ω/(1 + ε)). With a nominal gap (6.3 µm) larger than
    the change, the pairs stay open and their gaps change by the clearance of that deformed helix,
    D(r + Δr, ω/(1 + ε)) − D(r, ω) (the two effects: −0.17 and +0.03 µm here; either alone is
    18 % or more off), in small and in large sliding."""
    cable = _seven_wire(3.30e-3)
    layer = cable.layers[1]
    gap, force, gap0, dr, strain = _tensioned(cable, "nominal", model)
    assert dr < 0 and strain > 0 and np.all(force == 0)
    r = layer.radius + dr
    omega = np.tan(layer.alpha) / layer.radius / (1 + strain)
    deformed = replace(layer, radius=r, lay_angle=np.degrees(np.arctan(omega * r)))
    change = helix_clearance(deformed) - helix_clearance(layer)
    np.testing.assert_allclose(gap - gap0, change, rtol=0.05)  # measured 3.5 % (small)


@pytest.mark.parametrize("model", ["small", "large"])
def test_touching_neighbours_jam_as_the_tensioned_layer_tightens(model):
    """Equal wires (3.34 mm on a 3.34 mm core) whose helices would overlap: every neighbour
    touches ("packed" and "nominal" alike), so the layer is a closed ring; tension draws it onto
    the core and the ring jams: every pair is pressed, and both gap settings give the same; in
    small and in large sliding."""
    cable = _seven_wire(3.34e-3)
    results = {gaps: _tensioned(cable, gaps, model) for gaps in ("packed", "nominal")}
    gap, force, gap0, dr, _ = results["packed"]
    assert np.all(gap0 == 0) and dr < 0
    assert np.all(force > 0) and np.all(gap < 0)
    np.testing.assert_allclose(results["nominal"][1], force, rtol=1e-9)


def test_facing_pairs_approach_and_jam_as_the_tensioned_layer_tightens():
    """The two tests above on facing stations (``same_layer_stencil = "facing"``). Open
    neighbours: the pairs' mean gap change is the deformed helices' clearance change within
    5 % (measured 1.5 %; segment 3.5 %), but it is not the same on every wire: the mesh is not
    screw-symmetric (the stations of wire j are shifted by jδ, wire 0 carries the last wire's
    receivers too), and the free wires settle round the core unevenly; the gaps next to wire 0
    close 20–26 % more than the clearance change, those opposite 25–30 % less (segment's mesh:
    3.5 % less on every wire). Touching neighbours jam: every pair pressed, "packed" and
    "nominal" alike."""
    cable = _seven_wire(3.30e-3)
    layer = cable.layers[1]
    gap, force, gap0, dr, strain = _tensioned(cable, "nominal", stencil="facing")
    assert dr < 0 and strain > 0 and np.all(force == 0)
    r = layer.radius + dr
    omega = np.tan(layer.alpha) / layer.radius / (1 + strain)
    deformed = replace(layer, radius=r, lay_angle=np.degrees(np.arctan(omega * r)))
    change = helix_clearance(deformed) - helix_clearance(layer)
    assert np.mean(gap - gap0) == pytest.approx(change, rel=0.05)
    assert np.all(np.abs(gap - gap0 - change) < 0.5 * abs(change))
    jammed = _seven_wire(3.34e-3)
    results = {gaps: _tensioned(jammed, gaps, stencil="facing") for gaps in ("packed", "nominal")}
    gap, force, gap0, dr, _ = results["packed"]
    assert np.all(gap0 == 0) and dr < 0
    assert np.all(force > 0) and np.all(gap < 0)
    np.testing.assert_allclose(results["nominal"][1], force, rtol=1e-9)


@pytest.mark.slow
def test_a_frictionless_cardinal_with_packed_layers_tensions_to_40_kn(tmp_path):
    """Without friction a wire's sideways motion is held by contact alone. With same-layer
    contact (packed, the default) and the geometry-following normal (``director``, the default
    with friction) 0.15 m of Cardinal takes the full 40 kN, and its ends hold Costello's torque
    within 10 % (measured −4.4 %; −4.9 % at 0.3 m). The frozen normal is the default without
    friction (``ContactSettings``)."""
    case = load_case(
        None,
        [
            "mesh.length=0.15",
            "contact.friction=false",
            'contact.normal="director"',
            "load.cycle=[0.0]",
            "output.fields=false",
            "output.plots=false",
            "fatigue.outputs=false",
        ],
    )
    assert case.contact.normal == "director" and case.contact.same_layer == "packed"
    result = run_case(case, tmp_path / "out", stream=io.StringIO())
    assert not result.failure
    with open(tmp_path / "out" / "steps.csv") as f:
        last = list(csv.DictReader(f))[-1]
    assert float(last["tension_N"]) == pytest.approx(40e3)
    torque = held_end_torque(case.cable, 40e3)
    assert float(last["end_torque_L_Nm"]) == pytest.approx(torque, rel=0.10)


@cache
def _saddle_peak(stencil: str, h: float) -> tuple[float, float, float]:
    """The quick 1+6 (0.3 m) at 10 kN and a 300 N saddle load, same-layer pairs of ``stencil``
    with elements of at most ``h``: midspan deflection, end displacement (m) and the core's
    contact force (N)."""
    quick = Path(__file__).resolve().parents[1] / "cases" / "quick_1x6.toml"
    case = load_case(
        quick, [f'contact.same_layer_stencil="{stencil}"', f"mesh.h_max={h}", "load.cycle=[1.0]"]
    )
    problem, programme = build_problem(case)
    run_programme(problem, programme)
    s = problem.setup.state()
    core = problem.model.pair_results().force.sum()
    problem.solver.destroy()
    return s.deflection, s.end_displacement, core


def test_node_and_segment_stencils_converge_together():
    """Node to nearest node ("node") and node to facing segment ("segment", the default) are two
    discretisations of one line contact. On the quick 1+6 at the saddle's peak the node stencil
    moves the deflection and the end displacement by less than the mesh error (segment at h
    against h/2; measured 0.09 against 0.67 µm, 0.004 against 0.009 µm), and at h/2 the two
    stencils are closer than at h in deflection and in the core's contact force (measured
    28.8 → 11.0 N of 5.3 kN)."""
    h = 4e-3
    segment, node = _saddle_peak("segment", h), _saddle_peak("node", h)
    fine_segment, fine_node = _saddle_peak("segment", h / 2), _saddle_peak("node", h / 2)
    for k in (0, 1):
        mesh_error = abs(segment[k] - fine_segment[k])
        assert abs(node[k] - segment[k]) < mesh_error
    for k in (0, 2):
        assert abs(fine_node[k] - fine_segment[k]) < abs(node[k] - segment[k])


def test_facing_and_segment_stencils_converge_together():
    """Facing stations ("facing") against node to segment on the quick 1+6 at the saddle's
    peak: at h/2 the two are closer than at h in deflection, end displacement and the core's
    contact force (measured 2.6 → 0.14 µm, 0.026 → 0.011 µm, 174 → 78 N of 5.3 kN). At h the
    facing mesh moves them by more than the mesh error (segment at h against h/2: 0.67 µm,
    0.009 µm, 5.5 N): its shifted lattices load the core at a node per wire, not six balanced
    ones per node, and the core's contact force falls 3.3 % (docs/theory.md §3.4)."""
    h = 4e-3
    segment, facing = _saddle_peak("segment", h), _saddle_peak("facing", h)
    fine_segment, fine_facing = _saddle_peak("segment", h / 2), _saddle_peak("facing", h / 2)
    for k in (0, 1, 2):
        assert abs(fine_facing[k] - fine_segment[k]) < abs(facing[k] - segment[k])
    assert facing[2] < segment[2]  # the core's share, lower on the facing mesh
