"""Strand geometry, contact pairs and mesh against closed forms; bad cable input."""

import numpy as np
import pytest
from mpi4py import MPI

from strand.app.case import CaseError, load_case
from strand.cable.description import CableError, cable_from_dict, cardinal, load_cable
from strand.cable.geometry import LINE, POINT, build_geometry
from strand.cable.mesh import beam_space, cable_mesh, node_to_block


@pytest.fixture(scope="module")
def cardinal_1m():
    return build_geometry(cardinal(), 1.0, 4e-3)


def test_crossing_pair_counts_match_closed_form(cardinal_1m):
    """Crossings per interface: n_i n_j L (1/p_i + 1/p_j), within ±1 %."""
    g = cardinal_1m
    layers = g.cable.layers
    for i in range(1, len(layers) - 1):
        a, b = layers[i], layers[i + 1]
        closed = a.wires * b.wires * g.length * (1 / a.pitch + 1 / b.pitch)
        count = np.sum((g.pairs.interface == i) & (g.pairs.kind == POINT))
        assert count == pytest.approx(closed, rel=0.01), (i, count, closed)


def test_elements_per_wire_match_seed_paper(cardinal_1m):
    """Seed paper Table 2 (Cardinal, 1 m, 4 mm): 364 / 364 / 357 / 377 / 330, within ±5 %."""
    g = cardinal_1m
    for i, expected in enumerate([364, 364, 357, 377, 330]):
        per_wire = np.sum(g.cell_layer == i) / g.cable.layers[i].wires
        assert per_wire == pytest.approx(expected, rel=0.05), (i, per_wire)


def test_initial_gaps_are_zero(cardinal_1m):
    assert np.abs(cardinal_1m.gaps()).max() < 1e-15


def test_normals_are_radial_and_orthogonal_to_both_wires(cardinal_1m):
    g = cardinal_1m
    p = g.pairs
    x_a, x_b = g.points[p.a], g.points[p.b]
    assert np.allclose(x_a[:, 2], x_b[:, 2], atol=1e-12)  # radially aligned: same z
    d = x_b - x_a
    d /= np.linalg.norm(d, axis=1)[:, None]
    assert np.allclose(d, p.normal, atol=1e-12)
    # orthogonal to the analytic helix tangents of both wires at the contact point
    for end in ("a", "b"):
        node = getattr(p, end)
        wire = g.point_wire[node]
        lay = np.array([g.cable.layers[i].angular_rate for i in g.wire_layer])[wire]
        r = np.linalg.norm(g.points[node, :2], axis=1)
        phi = np.arctan2(g.points[node, 1], g.points[node, 0])
        t = np.column_stack([-r * lay * np.sin(phi), r * lay * np.cos(phi), np.ones(len(node))])
        assert np.abs(np.einsum("ij,ij->i", t, p.normal)).max() < 1e-12


def test_line_pairs_cover_layer_one(cardinal_1m):
    """Every layer-1 node has one core partner; tributary lengths add up to the wire lengths."""
    g = cardinal_1m
    line = g.pairs.kind == LINE
    assert np.sum(line) == np.sum(g.wire_layer[g.point_wire] == 1)
    wire_length = g.length / np.cos(g.cable.layers[1].alpha)
    assert g.pairs.tributary[line].sum() == pytest.approx(6 * wire_length, rel=1e-12)
    assert np.all(g.pairs.tributary[~line] == 0)


def test_elements_respect_h_max():
    for h in (4e-3, 2.5e-3):
        g = build_geometry(cardinal(), 0.3, h)
        assert g.cell_lengths().max() <= h * (1 + 1e-9)
        assert g.cell_lengths().min() > 0


def test_pair_indices_survive_dolfinx_reordering(cardinal_1m):
    """Pair blocks in the dolfinx mesh sit at the geometry's pair coordinates."""
    cm = cable_mesh(cardinal_1m, MPI.COMM_WORLD)
    V = beam_space(cm.mesh)
    blocks = cm.pair_blocks(V)
    x_block = np.empty_like(cm.mesh.geometry.x)
    x_block[node_to_block(V)] = cm.mesh.geometry.x
    p = cardinal_1m.pairs
    assert np.array_equal(x_block[blocks[:, 0]], cardinal_1m.points[p.a])
    assert np.array_equal(x_block[blocks[:, 1]], cardinal_1m.points[p.b])
    # cell tags follow dolfinx's cell order
    original = cm.mesh.topology.original_cell_index
    assert np.array_equal(cm.wire_tags.values, cardinal_1m.cell_wire[original])
    assert (
        np.bincount(cm.layer_tags.values).tolist() == np.bincount(cardinal_1m.cell_layer).tolist()
    )


def test_mesh_is_one_component_per_wire(cardinal_1m):
    g = cardinal_1m
    assert len(g.cells) == len(g.points) - len(g.wire_layer)
    assert np.all(g.point_wire[g.cells[:, 0]] == g.point_wire[g.cells[:, 1]])
    assert np.all(np.diff(g.points[g.cells, 2], axis=1) > 0)  # every cell points towards +z


def small_cable(**layer1):
    layer = {
        "wires": 6,
        "diameter": 3e-3,
        "E": 2e11,
        "nu": 0.3,
        "lay_angle": 8.0,
        "lay": "Z",
        "friction": 0.5,
    }
    layer.update(layer1)
    return {"core": {"diameter": 3e-3, "E": 2e11, "nu": 0.3, "friction": 0.3}, "layer": [layer]}


@pytest.mark.parametrize(
    "change, message",
    [
        ({"diameter": -1e-3}, r"layer\[1\]\.diameter = -0\.001 m is out of range \(0, 1\) m$"),
        ({"E": -2e11}, r"layer\[1\]\.E = -2e\+11 Pa is out of range \(0, inf\) Pa$"),
        # a modulus in GPa or MPa read as Pa: refused, with the value it was likely meant as
        ({"E": 210}, r"layer\[1\]\.E = 210 Pa: did you mean 210e9\? A wire's modulus is given in"),
        ({"E": 180e3}, r"layer\[1\]\.E = 180000 Pa: did you mean 180000e6\? A wire's modulus"),
        (
            {"E": 0.5},
            r"layer\[1\]\.E = 0\.5 Pa: A wire's modulus is given in Pa, and none is under",
        ),
        ({"E": 9.99e8}, r"layer\[1\]\.E = 9\.99e\+08 Pa: A wire's modulus .* under 1 GPa$"),
        ({"yield_stress": 0.0}, r"layer\[1\]\.yield_stress = 0 Pa is out of range \(0, inf\) Pa$"),
        (
            {"shear_coefficient": 12.0},
            r"layer\[1\]\.shear_coefficient = 12 is out of range \(0, 10\)$",
        ),
        (
            {"torsional_stiffness": -1.0},
            r"layer\[1\]\.torsional_stiffness = -1 N m² is out of range \(0, inf\) N m²$",
        ),
        ({"wires": 7}, r"layer\[1\]: its 7 wires .* overlap .*fill 1\.\d+"),
        ({"lay_angle": 60.0}, r"layer\[1\]\.lay_angle = 60° is out of range \(0°, 45°\)$"),
        ({"lay": "X"}, r"layer\[1\]\.lay = 'X': expected 'S' \(left\) or 'Z' \(right\)"),
        ({"colour": "red"}, r"layer\[1\]: unknown field\(s\) \['colour'\]"),
        ({"wires": 2.5}, r"layer\[1\]\.wires = 2\.5: expected a positive whole number"),
        ({"nu": 0.7}, r"layer\[1\]\.nu = 0\.7 is out of range \(-1, 0\.5\)$"),
        ({"friction": -0.1}, r"layer\[1\]\.friction = -0\.1 is out of range \[0, 10\)$"),
    ],
)
def test_bad_cable_input_is_named(change, message):
    with pytest.raises(CableError, match=message) as e:
        cable_from_dict(small_cable(**change))
    assert "\n" not in str(e.value)


def test_a_modulus_of_1_gpa_is_accepted():
    assert cable_from_dict(small_cable(E=1e9)).layers[1].wire.E == 1e9


def test_elements_closer_than_the_merge_tolerance_are_refused():
    """Nodes closer than ``merge_tol`` along the axis merge, which would leave a contact point
    without its node: such an ``h_max`` is refused in one line, the bound given; the shortest
    accepted still builds."""
    cable = cable_from_dict(small_cable())
    bound = 1e-6 / np.cos(np.radians(8.0))
    with pytest.raises(CableError, match=r"h_max = 1e-06 m: .* \(h_max > 1\.01e-06 m here\)"):
        build_geometry(cable, 2e-3, 1e-6)
    assert len(build_geometry(cable, 2e-3, 1.01 * bound).cells) > 1000


def test_missing_fields_are_named():
    data = small_cable()
    del data["layer"][0]["E"]
    with pytest.raises(CableError, match=r"layer\[1\]: missing field 'E'"):
        cable_from_dict(data)
    with pytest.raises(CableError, match=r"missing table \[core\]"):
        cable_from_dict({"layer": data["layer"]})


def test_same_hand_helical_layers_are_refused():
    """Layer 2 at twice layer 1's radius, same hand, tan α doubled: same pitch, so the wires
    would touch along lines, which the crossing search cannot pair."""
    data = small_cable()
    same_pitch = float(np.degrees(np.arctan(2 * np.tan(np.radians(8.0)))))
    data["layer"].append(dict(data["layer"][0], wires=12, lay_angle=same_pitch))
    with pytest.raises(CableError, match="same lay and pitch"):
        build_geometry(cable_from_dict(data), 0.2)


def test_cable_and_case_files(tmp_path):
    cable_file = tmp_path / "my.toml"
    cable_file.write_text(
        'name = "1+6"\n[core]\ndiameter = 3e-3\nE = 2e11\nnu = 0.3\nfriction = 0.3\n'
        '[[layer]]\nwires = 6\ndiameter = 3e-3\nE = 2e11\nnu = 0.3\nlay_angle = 8.0\nlay = "Z"\n'
        "friction = 0.0\n"
    )
    assert load_cable(cable_file).n_wires == 7
    case = tmp_path / "case.toml"
    case.write_text('cable = "my.toml"\n[mesh]\nlength = 0.2\n')
    c = load_case(case)
    assert c.cable.name == "1+6" and c.mesh.length == 0.2 and c.mesh.h_max == 4e-3
    case.write_text('cable = "cardinal"\n[mesh]\nlenght = 0.2\n')
    with pytest.raises(CaseError, match=r"unknown setting\(s\) in \[mesh\]: \['lenght'\]"):
        load_case(case)
    case.write_text('cable = "cardinal"\ntension = 4e4\n')
    with pytest.raises(CaseError, match=r"case.toml: unknown setting\(s\) \['tension'\]"):
        load_case(case)


def test_strand_mesh_command(tmp_path, capsys):
    from strand.app.cli import main

    case = tmp_path / "case.toml"
    case.write_text('cable = "cardinal"\n[mesh]\nlength = 0.1\n')
    assert main(["mesh", str(case), "--out", str(tmp_path / "out")]) == 0
    out = capsys.readouterr().out
    assert "3|4     crossing" in out and "elements/wire" in out
    assert (tmp_path / "out" / "mesh.png").stat().st_size > 10_000
    assert (tmp_path / "out" / "centrelines.vtu").exists()
    case.write_text('cable = "cardinal"\n[mesh]\nh_max = -1\n')
    assert main(["mesh", str(case)]) == 2
    assert "[mesh] h_max = -1 m: expected a positive number" in capsys.readouterr().err


def test_gmsh_model_comes_in_like_strands_own_mesh():
    """A 1D gmsh model with a physical group per wire gives the same mesh, tags and pair nodes."""
    gmsh = pytest.importorskip("gmsh")  # the optional `gmsh` extra

    from strand.cable.mesh import geometry_to_gmsh, input_to_block, mesh_from_gmsh

    g = build_geometry(cardinal(), 0.05, 4e-3)
    gmsh.initialize(["-v", "0"])
    try:
        mesh, wire_tags = mesh_from_gmsh(geometry_to_gmsh(g), MPI.COMM_WORLD)
    finally:
        gmsh.finalize()
    assert np.bincount(wire_tags.values).tolist() == np.bincount(g.cell_wire).tolist()
    V = beam_space(mesh)
    x_block = np.empty_like(mesh.geometry.x)
    x_block[node_to_block(V)] = mesh.geometry.x
    i2b = input_to_block(V)
    assert np.allclose(x_block[i2b[g.pairs.a]], g.points[g.pairs.a], atol=1e-15)
    assert np.allclose(x_block[i2b[g.pairs.b]], g.points[g.pairs.b], atol=1e-15)
