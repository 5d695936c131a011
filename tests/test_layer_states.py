"""The states a layer's geometry allows (``strand.model.layer_states``): its spare circumference
spread evenly, bunched or at random over its gaps, and a first layer whose helices overlap as a
ring on the core or vaulted over it."""

from dataclasses import replace

import numpy as np
import pytest
from test_layer_pressure import _seven_wire, _tensioned

from strand.app.case import case_from_dict
from strand.app.case_toml import cable_table
from strand.app.errors import CaseError
from strand.cable.description import CableError, cardinal
from strand.cable.geometry import build_geometry
from strand.model.contact_settings import ContactSettings
from strand.model.layer_states import first_layer_lift, helix_clearance, ring_lift, spread_gaps
from strand.model.same_layer import same_layer_pairs
from strand_cases import nineteen_wire


@pytest.mark.parametrize("how", ["nominal", "packed", "random"])
def test_every_spread_shares_out_the_whole_spare_circumference(how):
    """n gaps, none negative, that add up to the spare circumference; none without spare."""
    gaps = spread_gaps(0.74e-3, 12, how, np.random.default_rng(3))
    assert len(gaps) == 12 and np.all(gaps >= 0)
    assert gaps.sum() == pytest.approx(0.74e-3, rel=1e-12)
    assert np.all(spread_gaps(-84e-6, 6, how, np.random.default_rng(3)) == 0)
    if how == "nominal":
        assert np.all(gaps == pytest.approx(0.74e-3 / 12, rel=1e-12))
    if how == "packed":
        assert np.all(gaps[:-1] == 0)


def test_random_gaps_are_uniform_over_the_splits():
    """Dirichlet(1, …, 1) shares: each gap's mean is spare / n, its variance
    (n − 1) / (n² (n + 1)) spare² (within 4 % over 20,000 draws)."""
    n, rng = 12, np.random.default_rng(0)
    shares = np.array([spread_gaps(1.0, n, "random", rng) for _ in range(20_000)])
    assert shares.mean(axis=0) == pytest.approx(np.full(n, 1 / n), rel=0.04)
    assert shares.var(axis=0) == pytest.approx(np.full(n, (n - 1) / (n**2 * (n + 1))), rel=0.04)


def _layer_gaps(pairs, geometry, layer):
    """The initial gap of each wire of ``layer`` to its next neighbour, m."""
    wire_of = np.searchsorted(geometry.wire_offsets, pairs.a, side="right") - 1
    wires = np.flatnonzero(geometry.wire_layer == layer)
    gaps = [np.unique(pairs.gap[(pairs.layer == layer) & (wire_of == w)]) for w in wires]
    assert all(len(g) == 1 for g in gaps)  # one gap along each wire
    return np.concatenate(gaps)


def test_random_gaps_come_again_from_their_seed():
    """The same seed gives the same gaps, another seed others; layer 2's gaps add up to its
    spare circumference, 12 (D − d)."""
    geometry = nineteen_wire(0.05)
    one, again, other = (same_layer_pairs(geometry, "random", seed=s) for s in (7, 7, 8))
    assert np.array_equal(one.gap, again.gap)
    assert not np.allclose(one.gap, other.gap)
    layer = geometry.cable.layers[2]
    spare = 12 * (helix_clearance(layer) - layer.wire.diameter)
    assert _layer_gaps(one, geometry, 2).sum() == pytest.approx(spare, rel=1e-12)
    assert np.all(_layer_gaps(one, geometry, 1) == 0)  # layer 1's helices overlap: a ring
    nominal = same_layer_pairs(geometry, "nominal")
    assert np.all(_layer_gaps(nominal, geometry, 2) == pytest.approx(spare / 12, rel=1e-12))


def test_a_lifted_ring_just_touches_at_its_lay_length():
    """Straight wires of one diameter round an equal core touch: no lift. Laid at Cardinal's
    6.06°, the ring's helices overlap by 14.1 µm; widened by its lift at the same lay length,
    they just touch (to 1e-9 m). The lift grows with the lay angle."""
    layer = cardinal().layers[1]
    assert ring_lift(replace(layer, lay_angle=0.0)) == pytest.approx(0.0, abs=1e-12)
    lift = ring_lift(layer)
    r = layer.radius + lift
    angle = np.degrees(np.arctan(np.tan(layer.alpha) * r / layer.radius))
    lifted = replace(layer, radius=r, lay_angle=float(angle))
    assert helix_clearance(lifted) == pytest.approx(layer.wire.diameter, abs=1e-9)
    assert lifted.pitch == pytest.approx(layer.pitch, rel=1e-12)
    assert 10e-6 < lift < 20e-6
    assert ring_lift(replace(layer, lay_angle=8.0)) > lift


def test_a_king_wire_opens_the_first_layer_and_leaves_no_ring():
    """A king wire (a core 3.40 mm thick under Cardinal's 3.34 mm steel wires: the cable's
    ``core.diameter``) opens layer 1's gaps, so its wires cannot vault: ``first_layer = "ring"``
    is refused in one line when the case is read, before any computing."""
    king = cable_table(cardinal()) | {"name": "king"}
    king["core"] |= {"diameter": 3.40e-3}
    cable = case_from_dict({"cable": king}).cable
    layer = cable.layers[1]
    assert helix_clearance(layer) - layer.wire.diameter > 0
    with pytest.raises(CaseError, match=r'first_layer = "ring".*do not touch one another'):
        case_from_dict({"cable": king, "contact": {"first_layer": "ring"}})
    assert first_layer_lift(cable, "on_core") == 0.0
    with pytest.raises(CableError, match="first_layer = 'vault' is unknown"):
        ContactSettings(first_layer="vault")
    with pytest.raises(CableError, match="gap_seed"):
        ContactSettings(gap_seed=-1)
    with pytest.raises(CaseError, match=r"\[contact\] gap_seed = 1.5: expected a whole number"):
        case_from_dict({"contact": {"gap_seed": 1.5}})


def test_a_vaulted_ring_takes_the_whole_fibre_pressure():
    """A 1+6 of equal wires vaulted over its core (``first_layer = "ring"``): its core's line
    pairs start open by the lift and, at 10 kN, stay open (by 14.0–14.2 µm: the ring's contacts
    close by a fraction of a µm); the ring carries the layer's fibre pressure n T sin²α /
    (r cos α) within 6 % (measured 4.5 % short, besides the 1+6 on its core's 2 %: the ring's
    friction, 4.3 % of its load here against 1.7 % on the core, and the wires' shear forces), the
    polygon relation ring ≈ 2 n sin(π/n) H holds within 2 % (measured 0.9 %), and the core
    takes nothing. A ring of circles under pressure is a mechanism but for its wires' bending:
    the first tension step, frictionless, is 200 N (a 5 kN one stalls)."""
    geometry = build_geometry(_seven_wire(), 0.15, 4e-3)
    lift = first_layer_lift(geometry.cable, "ring")
    assert lift == pytest.approx(ring_lift(geometry.cable.layers[1]))
    (layer,) = _tensioned("packed", geometry=geometry, first_layer="ring", first_step=200.0)
    print(layer)
    assert layer.crossings_below == 0.0
    assert layer.ring == pytest.approx(layer.fibre, rel=0.06)
    normal = layer.ring - layer.ring_friction
    assert normal == pytest.approx(2 * 6 * np.sin(np.pi / 6) * layer.hoop, rel=0.02)
