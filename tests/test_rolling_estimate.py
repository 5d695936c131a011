"""The smeared stick-bending estimate with wires free to roll (``strand.analytical.rolling``) and
the Hertz patch's rotational stiffness, against identities and closed forms."""

import numpy as np
import pytest

from strand.analytical import contact_patch, stick_bending_estimate
from strand.analytical.fibre import bending_stiffness_bounds
from strand.cable.description import Cable, Wire, cardinal


def _reduced(layers: int) -> Cable:
    """Cardinal's core and its first ``layers`` helical layers."""
    c = cardinal()
    return Cable(f"{c.name} 1..{layers}", c.layers[: layers + 1])


@pytest.mark.parametrize("layers", [1, 2, 3, 4])
def test_held_spin_gives_plane_sections(layers):
    """Holding every spin (centre-line ties) forces plane sections: EI_max exactly, and every
    layer carries its plane-section axial force."""
    cable = _reduced(layers)
    held = stick_bending_estimate(cable, spin=False)
    assert held.ei == pytest.approx(bending_stiffness_bounds(cable)[1], rel=1e-12)
    np.testing.assert_allclose(held.axial_share, 1.0, atol=1e-12)
    # holding spin and sideways motion in every layer is the same
    assert stick_bending_estimate(cable, held=tuple(range(1, layers + 1))).ei == pytest.approx(
        held.ei, rel=1e-12
    )


def test_one_layer_cannot_roll():
    """A 1+6 cannot roll on its core: a layer-1 wire rolling on the core's fixed surface would
    need a sideways shift that its tie forbids, so the free spin changes nothing."""
    cable = _reduced(1)
    assert stick_bending_estimate(cable).ei == pytest.approx(
        bending_stiffness_bounds(cable)[1], rel=1e-9
    )


@pytest.mark.parametrize("layers", [2, 3, 4])
def test_rolling_softens_and_torsion_restores(layers):
    """With two layers or more the free spin lowers the slope below EI_max; stiffer torsion
    raises it monotonically towards EI_max, and rotational restraint per crossing likewise."""
    cable = _reduced(layers)
    ei_min, ei_max = bending_stiffness_bounds(cable)
    slopes = [stick_bending_estimate(cable, torsion_scale=f).ei for f in (1, 10, 100, 1e6)]
    assert ei_min < slopes[0] < 0.7 * ei_max
    assert np.all(np.diff(slopes) > 0)
    assert slopes[-1] == pytest.approx(ei_max, rel=1e-3)
    rolls = [stick_bending_estimate(cable, k_roll=k).ei for k in (0, 10, 1000, 1e7)]
    assert np.all(np.diff(rolls) > 0) and rolls[-1] == pytest.approx(ei_max, rel=1e-3)


def test_fields_are_the_minimiser():
    """The returned slope is the minimum: Cardinal with free spin lies below every variant that
    holds more (a layer's spin and shift, or all spins)."""
    c = cardinal()
    free = stick_bending_estimate(c)
    for held in [(1,), (2,), (3,), (4,)]:
        assert stick_bending_estimate(c, held=held).ei >= free.ei - 1e-9
    assert free.spin.shape == free.torque.shape == free.axial_share.shape == (4,)
    # layer 1 sits on the core: its axial share stays at the plane-section value
    assert free.axial_share[0] == pytest.approx(1.0, abs=1e-9)


def test_patch_of_crossed_equal_wires_at_right_angles():
    """Equal cylinders crossed at 90° touch like a sphere of their radius on a flat: Hertz's
    c = (3PR/(4E*))^(1/3); identical materials drill with (8/3) G c³."""
    w = Wire(diameter=3.32e-3, E=65e9, nu=0.33)
    P, R = 100.0, w.diameter / 2
    patch = contact_patch(P, w, w, np.pi / 2, friction=0.5)
    E_star = w.E / (2 * (1 - w.nu**2))
    c = (3 * P * R / (4 * E_star)) ** (1 / 3)
    assert patch.radius == pytest.approx(c, rel=1e-12)
    G = w.E / (2 * (1 + w.nu))
    assert patch.k_drill == pytest.approx(8 / 3 * G * c**3, rel=1e-12)
    assert patch.drill_slip_torque == pytest.approx(3 * np.pi * 0.5 * P * c / 16, rel=1e-12)
    # a smaller crossing angle makes the patch longer, so larger at the same force
    assert contact_patch(P, w, w, np.radians(20), 0.5).radius > patch.radius
