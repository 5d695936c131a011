"""strand's registries share one vocabulary and one rule (``strand.beam.registry.Registry``): the
set-up kinds, the contact compliances and a run's outputs each refuse a name that is taken, keep
the order registered, and say which names there are when one is missing."""

from __future__ import annotations

import pytest

from strand.app import kind_registry, kinds  # noqa: F401  (kinds: registers the built-in ones)
from strand.app.outputs import register_output, registered_outputs
from strand.beam.registry import Registry
from strand.model.compliances import compliance_named, compliances, register_compliance


def test_a_registry_keeps_the_order_and_refuses_a_taken_name():
    r: Registry[int] = Registry("number")
    r.register("one", 1)
    r.register("two", 2)
    assert r.names() == ("one", "two") and r.entries() == (1, 2) and "one" in r
    with pytest.raises(ValueError, match="a number named 'one' is registered already"):
        r.register("one", 3)
    assert r.lookup("one") == 1
    with pytest.raises(KeyError, match="no number named 'three'; registered: one, two"):
        r.lookup("three")
    r.unregister("one")
    assert r.names() == ("two",)


def test_every_registry_refuses_a_taken_name():
    hertz = compliance_named("hertz")
    with pytest.raises(ValueError, match="a compliance named 'hertz' is registered already"):
        register_compliance("hertz", hertz.build)
    steps = registered_outputs()[0]
    with pytest.raises(ValueError, match=f"an output named '{steps.name}' is registered"):
        register_output(steps.name, steps.make, files=steps.files)
    kind = kind_registry.registered()[0]
    with pytest.raises(ValueError, match="a set-up kind named .* is registered already"):
        kind_registry.add(kind)
    # nothing was replaced
    assert compliance_named("hertz") is hertz and registered_outputs()[0] is steps
    assert kind_registry.registered()[0] is kind and "hertz" in compliances()
