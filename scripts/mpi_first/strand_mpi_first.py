"""``import dolfinx`` first, with the PyPI wheel of dolfinx: its MPI library loaded before it.

The wheel (``dolfinx-solver-real``) links dolfinx and petsc4py against ``libmpi.so.12``, which
the ``mpich`` wheel installs in ``<venv>/lib``, a folder the dynamic loader does not search: only
``import dolfinx_solver`` (which ``import strand`` does) loads it, through ``mpi4py.MPI``. A
script that starts with ``import dolfinx``, as FEniCS scripts do, stops on
``ImportError: libmpi.so.12``.

``strand_mpi_first.pth``, which ``make setup`` puts beside this module into the virtual
environment's site-packages, calls ``install()`` when Python starts: a finder, first on
``sys.meta_path``, that finds nothing itself but imports ``dolfinx_solver`` the first time
``dolfinx``, ``petsc4py`` or ``slepc4py`` is imported, then steps aside. It costs Python's start
one small import and nothing else; no MPI is loaded until dolfinx is. Without the wheel
(conda, apt) it does nothing. The same kind of finder as setuptools' ``distutils-precedence.pth``.
"""

from __future__ import annotations

import sys

#: the module that loads the wheel's MPI library, and the modules that need it loaded first
FIRST = "dolfinx_solver"
AFTER = frozenset({"dolfinx", "petsc4py", "slepc4py"})


class MPIFirst:
    """A meta path finder that imports ``FIRST`` before the first of ``AFTER``; finds nothing."""

    done = False

    @classmethod
    def find_spec(cls, name: str, path=None, target=None) -> None:
        if cls.done or name.partition(".")[0] not in AFTER:
            return None
        cls.done = True  # first: FIRST's own import of petsc4py passes through here
        if FIRST not in sys.modules:
            import importlib.util

            if importlib.util.find_spec(FIRST) is not None:
                importlib.import_module(FIRST)
        return None


def install() -> None:
    """Put ``MPIFirst`` first on ``sys.meta_path`` (once)."""
    if MPIFirst not in sys.meta_path:
        sys.meta_path.insert(0, MPIFirst)
