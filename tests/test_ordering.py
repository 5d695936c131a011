"""The MUMPS ordering chosen by trial (``strand.solver.ordering``)."""

import numpy as np
import pytest
from mpi4py import MPI
from petsc4py import PETSc

from strand.solver.ordering import ORDERINGS, cheapest_ordering, factorisation_flops


def _matrix(n: int, pattern, values) -> PETSc.Mat:
    """A serial AIJ matrix of order ``n`` with ``values`` at the (i, j) of ``pattern``."""
    A = PETSc.Mat().createAIJ([n, n], nnz=n, comm=MPI.COMM_SELF)
    for (i, j), v in zip(pattern, values, strict=True):
        A.setValue(i, j, v)
    A.assemble()
    return A


def test_a_dense_matrix_costs_two_thirds_n_cubed():
    """(Not with PORD, which exits on a dense graph: "no valid number of stages".)"""
    n = 60
    pattern = [(i, j) for i in range(n) for j in range(n)]
    A = _matrix(n, pattern, np.ones(len(pattern)))
    assert factorisation_flops(A, ORDERINGS["amf"]) == pytest.approx(2 * n**3 / 3, rel=0.05)
    A.destroy()


def test_the_count_is_the_patterns_alone():
    """Two matrices on one pattern, one of which would need pivoting, cost the same."""
    rng = np.random.default_rng(1)
    n = 200
    pattern = sorted(
        {(i, i) for i in range(n)} | {tuple(rng.integers(0, n, 2)) for _ in range(600)}
    )
    A = _matrix(n, pattern, rng.normal(size=len(pattern)))
    B = _matrix(n, pattern, np.where([i == j for i, j in pattern], 10.0, 1e-3))
    for name in ("pord", "amf"):
        assert factorisation_flops(A, ORDERINGS[name]) == factorisation_flops(B, ORDERINGS[name])
    name, flops = cheapest_ordering(A, ("pord", "amf", "amd"))
    assert set(flops) == {"pord", "amf", "amd"} and flops[name] == min(flops.values())
    A.destroy()
    B.destroy()


def test_unknown_orderings_are_refused():
    A = _matrix(2, [(0, 0), (1, 1)], [1.0, 1.0])
    with pytest.raises(ValueError, match="MUMPS orderings \\['nested'\\]"):
        cheapest_ordering(A, ("pord", "nested"))
    A.destroy()
