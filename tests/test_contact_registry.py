"""The contact compliance registry (``strand.model.compliances``): a compliance registered from
outside the library is a ``[contact] compliance`` a case can choose, its laws are the ones the
strand's pairs use, and an unknown name is refused with the registered ones."""

from __future__ import annotations

import numpy as np
import pytest

from strand.app.case import CaseError, case_from_dict
from strand.cable.description import CableError
from strand.cable.geometry import LINE
from strand.contact.friction_laws import ElasticSlip
from strand.contact.normal_laws import PenaltyLaw
from strand.model.compliances import compliances, register_compliance, unregister_compliance
from strand.model.contact_settings import ContactSettings
from strand.model.problem import StrandProblem
from strand.setups.saddle import SaddleTest
from strand.solver import NewtonOptions
from strand_cases import seven_wire


@pytest.fixture
def mine():
    """A foreign compliance "mine": the seed paper's penalty with the stiffness doubled; the
    kinds of pairs it was asked for in ``calls``."""
    calls = []

    def build(wires, settings):
        calls.append((wires.line, len(wires)))
        k = 2 * (settings.k_line * wires.tributary if wires.line else settings.k_point)
        friction = None if wires.mu is None else ElasticSlip(wires.mu, settings.g_lim)
        return PenaltyLaw(np.broadcast_to(k, (len(wires),)).copy()), friction

    register_compliance("mine", build, uses=("k_point", "k_line", "g_lim"))
    yield calls
    unregister_compliance("mine")
    assert "mine" not in compliances()


def test_a_registered_compliance_gives_the_strands_pair_laws(mine):
    geometry = seven_wire(length=0.1)
    settings = ContactSettings(compliance="mine", k_line=2e9)  # a setting it says it uses
    problem = StrandProblem(geometry, settings, NewtonOptions(atol=1e-4), setup=SaddleTest)
    assert (True, int(np.sum(geometry.pairs.kind == LINE))) in mine  # built through the registry
    problem.setup.set_tension(5e3)
    assert problem.solver.solve().converged
    res = problem.pair_results()
    pairs = geometry.pairs
    closed = res.gap < 0
    assert closed.any()
    print(f"{closed.sum()} closed pairs, max force {res.force.max():.3g} N, calls {mine}")
    # the core | layer-1 line pairs: p = 2 k_line × tributary × ⟨−g⟩, the doubled penalty
    expected = 2 * 2e9 * pairs.tributary * np.maximum(-res.gap, 0.0)
    assert np.allclose(res.force, expected, rtol=1e-9, atol=1e-9 * res.force.max())


def test_a_case_selects_a_registered_compliance_and_refuses_an_unknown_one(mine):
    assert case_from_dict({"contact": {"compliance": "mine"}}).contact.compliance == "mine"
    with pytest.raises(
        CaseError,
        match="compliance = 'stiff' is unknown; choose penalty, hertz, hertz_microslip or mine",
    ) as e:
        case_from_dict({"contact": {"compliance": "stiff"}})
    assert "\n" not in str(e.value)
    with pytest.raises(CableError, match='k_point apply to compliance = "penalty" or "mine" only'):
        ContactSettings(compliance="hertz", k_point=1e8)
