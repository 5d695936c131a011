"""Same-layer pairs on facing stations (``[contact] same_layer_stencil = "facing"``): the facing
offset δ, a mesh whose pairs face each other exactly, without a cascade of nodes, the pairs
built from it, and the option refused where it cannot work (docs/theory.md §3.4)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from strand.app.case import load_case
from strand.app.cli import main
from strand.cable.description import CableError, cardinal
from strand.cable.facing import FACING_TOL, facing_offset
from strand.cable.geometry import POINT, build_geometry
from strand.model.contact_settings import ContactSettings
from strand.model.layer_states import helix_clearance
from strand.model.model import strand_stencils
from strand.model.same_layer import same_layer_pairs
from strand_cases import SEVEN_WIRE, one_line_error, seven_wire

LENGTH, H_MAX = 0.3, 4e-3


@pytest.fixture(scope="module")
def facing():
    """0.3 m of Cardinal with facing stations: 8,677 nodes, four helical layers."""
    return build_geometry(cardinal(), LENGTH, H_MAX, facing=True)


def _pair_layers(g):
    return g.wire_layer[g.point_wire[g.facing.a]]


def test_the_facing_offset_is_where_two_neighbouring_helices_come_closest():
    """x_{j+1}(z + δ) − x_j(z) has the length of the helices' clearance D (an independent
    golden-section search) and is perpendicular to both helices' tangents; a dense scan of the
    offset finds no closer point; δ has the sign of −ω (Cardinal: +305, −681, +686, −762 µm)."""
    g = build_geometry(cardinal(), 0.05, H_MAX)
    deltas = []
    for i, layer in enumerate(g.cable.layers[1:], start=1):
        delta = facing_offset(layer)
        deltas.append(delta)
        w0, w1 = np.flatnonzero(g.wire_layer == i)[:2]
        z = 0.0123
        d = g.centres(w1, z + delta) - g.centres(w0, z)
        assert np.linalg.norm(d) == pytest.approx(helix_clearance(layer), abs=1e-15)
        for w, zz in ((w0, z), (w1, z + delta)):
            t = g.centres(w, zz + 1e-6) - g.centres(w, zz - 1e-6)
            assert abs(d @ t) / np.linalg.norm(t) < 1e-12  # m: the offset of the facing point
        scan = z + delta + np.linspace(-1e-3, 1e-3, 200_001)
        distance = np.linalg.norm(g.centres(w1, scan) - g.centres(w0, z), axis=1)
        assert distance.min() >= np.linalg.norm(d) - 1e-15
        assert np.sign(delta) == -np.sign(layer.angular_rate)
    np.testing.assert_allclose(
        np.array(deltas) * 1e6, [305.34, -681.48, 685.61, -761.73], atol=0.01
    )


def test_every_facing_pair_faces_exactly(facing):
    """Every pair's node c (on wire j + 1) is the point of its helix nearest node a (on wire j):
    the segment ac is perpendicular to both tangents (the facing point is within 1e-9 m of c
    along either wire) and its length is the helices' clearance D to 1e-12 m; a is on wire j,
    c on the next wire of the layer in order of phase (wire 0 after the last)."""
    g = facing
    f = g.facing
    assert len(f) > 0
    d = g.points[f.c] - g.points[f.a]
    tangents = g.tangents()
    for end in (f.a, f.c):
        assert np.abs(np.einsum("pi,pi->p", d, tangents[end])).max() < 1e-9
    layer = _pair_layers(g)
    clearance = np.array([0.0] + [helix_clearance(lay) for lay in g.cable.layers[1:]])[layer]
    assert np.abs(np.linalg.norm(d, axis=1) - clearance).max() < 1e-12
    wa, wc = g.point_wire[f.a], g.point_wire[f.c]
    first = np.searchsorted(g.wire_layer, layer)
    n = np.array([lay.wires for lay in g.cable.layers])[layer]
    assert np.array_equal(wc - first, (wa - first + 1) % n)
    for i, lay in enumerate(g.cable.layers[1:], start=1):  # every gap of every layer is paired
        assert set(wa[layer == i] - first[layer == i]) == set(range(lay.wires))


def test_stations_cascade_no_further_than_the_wrap(facing):
    """Each wire of a layer carries its stations (one per Δ = h_max cos α less 2 (10 + 1) µm),
    its crossings and its ends, and wire 0 the receivers of the last wire's stations too: no
    more (a cascade would put L/|δ|, 400 to 1,000 nodes, on each wire here); every cell is at
    most h_max of arc; each wire's tributaries sum to its length."""
    g = facing
    f = g.facing
    layer = _pair_layers(g)
    crossing = g.pairs.kind == POINT
    crossing_nodes = np.concatenate([g.pairs.a[crossing], g.pairs.b[crossing]])
    for i, lay in enumerate(g.cable.layers[1:], start=1):
        cos_a = math.cos(lay.alpha)
        spacing = H_MAX * cos_a - 2 * (FACING_TOL + 1e-6)
        stations = math.floor(LENGTH / spacing) + 1
        for j, w in enumerate(np.flatnonzero(g.wire_layer == i)):
            nodes = np.arange(g.wire_offsets[w], g.wire_offsets[w + 1])
            crossings = len(np.intersect1d(nodes, crossing_nodes))
            receivers = stations if j == 0 else 0
            assert len(nodes) <= 2 + crossings + stations + receivers
            starts = np.count_nonzero(g.point_wire[f.a] == w)
            assert starts >= stations - 8  # lost: near an end or a crossing, or facing past L
            arc = np.diff(g.points[nodes, 2]) / cos_a
            assert arc.max() <= H_MAX * (1 + 1e-12)
            mine = g.point_wire[f.a] == w
            assert f.tributary[mine].sum() == pytest.approx(LENGTH / cos_a, rel=1e-12)
        assert np.count_nonzero(layer == i) > 0
    assert g.cell_lengths().max() <= H_MAX


def test_the_default_mesh_has_no_facing_stations():
    """Without ``facing`` the geometry is today's (no stations, the seed paper's node counts:
    ``tests/test_geometry.py``), and the facing stencil refuses it."""
    plain = build_geometry(cardinal(), 0.1, H_MAX)
    assert plain.facing is None
    with pytest.raises(ValueError, match="needs a geometry with facing stations"):
        same_layer_pairs(plain, "packed", "facing")
    again = build_geometry(cardinal(), 0.1, H_MAX, facing=False)
    assert np.array_equal(again.points, plain.points)


def test_facing_pairs_are_two_node_pairs_with_the_layers_gaps(facing):
    """The pairs [c, a]: no offset, the facing point on node c (weight 0 on c's next segment),
    normals a → c across both wires; "nominal" gives every pair of a layer its nominal gap,
    "packed" closes all but the wrap pairs (wire n − 1 → 0), which hold the spare circumference
    (none in layer 1, whose wires would overlap)."""
    g = facing
    nominal, packed = (same_layer_pairs(g, gaps, "facing") for gaps in ("nominal", "packed"))
    assert nominal.stencil == "facing" and nominal.stencils.shape == (len(g.facing), 2)
    assert np.array_equal(nominal.stencils, np.column_stack([g.facing.c, g.facing.a]))
    assert np.all(nominal.offset == 0) and np.all(nominal.weight == 0)
    assert np.array_equal(nominal.b1, nominal.b0 + 1)
    assert np.array_equal(g.point_wire[nominal.b1], g.point_wire[nominal.b0])
    tangents = g.tangents()
    cosine = np.einsum("pi,pi->p", nominal.normal, tangents[nominal.a])
    assert np.abs(cosine).max() < 1e-9
    for i, lay in enumerate(g.cable.layers[1:], start=1):
        sel = nominal.layer == i
        spare = lay.wires * (helix_clearance(lay) - lay.wire.diameter)
        np.testing.assert_allclose(nominal.gap[sel], max(spare / lay.wires, 0.0), atol=1e-18)
        wire = g.point_wire[packed.a[sel]] - np.flatnonzero(g.wire_layer == i)[0]
        wrap = wire == lay.wires - 1
        assert np.all(packed.gap[sel][~wrap] == 0)
        np.testing.assert_allclose(packed.gap[sel][wrap], max(spare, 0.0), atol=1e-18)


def test_the_facing_stencil_is_refused_with_large_sliding(tmp_path, capsys):
    """Large sliding re-finds the facing points at every iteration, so its pairs cannot stay on
    stations: the settings refuse the pair of choices, and a run says so in one line."""
    with pytest.raises(CableError, match='"facing" is for small sliding'):
        ContactSettings(model="large", same_layer_stencil="facing")
    with pytest.raises(CableError, match="choose segment, node or facing"):
        ContactSettings(same_layer_stencil="nearest")
    assert ContactSettings(same_layer_stencil="facing").facing_stations
    assert not ContactSettings(same_layer_stencil="facing", same_layer="off").facing_stations
    assert ContactSettings().same_layer_stencil == "segment"  # the default stays
    case = tmp_path / "seven.toml"
    case.write_text(SEVEN_WIRE)
    args = ["run", str(case), "--out", str(tmp_path / "out")]
    settings = ["--set", 'contact.model="large"', "--set", 'contact.same_layer_stencil="facing"']
    assert main([*args, *settings]) == 2
    assert '"facing" is for small sliding' in one_line_error(capsys)
    assert not (tmp_path / "out").exists()


def test_a_case_with_the_facing_stencil_meshes_with_stations(tmp_path, capsys):
    """``strand mesh`` of a case with the facing stencil builds the stations, keeps the pairs'
    two-node stencils whole, and prints each layer's pairs and δ; the problem a run builds has
    the same mesh and pairs."""
    from strand.app.build import build_problem

    case = load_case(
        None, ["mesh.length=0.05", 'contact.same_layer_stencil="facing"', "load.cycle=[0.0]"]
    )
    assert case.contact.facing_stations
    sets = ["--set", "mesh.length=0.05", "--set", 'contact.same_layer_stencil="facing"']
    assert main(["mesh", "--no-picture", "--out", str(tmp_path / "mesh"), *sets]) == 0
    out = capsys.readouterr().out
    assert "layer  facing pairs  offset δ (µm)" in out and "+305.34" in out
    problem, _ = build_problem(case, stream=None)
    g = problem.geometry
    assert g.facing is not None and problem.model.same_layer_pairs.stencil == "facing"
    assert len(problem.model.same_layer_pairs) == len(g.facing)
    stencils = strand_stencils(g, case.contact)
    assert any(s.shape[1] == 2 and np.array_equal(s[:, 0], g.facing.c) for s in stencils)
    problem.solver.destroy()


def test_a_layer_of_straight_wires_faces_at_the_same_z():
    """Straight wires (lay angle → 0) face each other side by side: δ → 0, and the wrap's
    receivers fall on wire 0's stations (no extra node)."""
    g = seven_wire(lay_angle=1e-9, length=0.05)
    layer = g.cable.layers[1]
    assert abs(facing_offset(layer)) < 1e-12
    flat = build_geometry(g.cable, 0.05, H_MAX, facing=True)
    nodes = np.diff(flat.wire_offsets)
    assert np.all(nodes[1:] == nodes[1])  # wire 0 gets no receivers of its own
    assert np.abs(flat.points[flat.facing.c, 2] - flat.points[flat.facing.a, 2]).max() < 1e-12
