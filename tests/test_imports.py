"""How strand is imported, in a fresh interpreter each: a user's own ``forms.py`` that shadows
strand's beam forms is named in one line with the fix; and with the PyPI wheel of dolfinx,
``import dolfinx`` may come before ``import strand`` once ``make setup`` has put
``scripts/mpi_first`` into the environment (its ``.pth`` file, read here by ``site.addsitedir``)."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

from strand_cases import MPIRUN, needs_mpirun

ROOT = Path(__file__).resolve().parents[1]
MPI_FIRST = ROOT / "scripts" / "mpi_first"


def python(code: str, cwd: Path, ranks: int = 1) -> subprocess.CompletedProcess:
    """``code`` run as a script ``main.py`` in ``cwd`` (so ``cwd`` is first on ``sys.path``)."""
    (cwd / "main.py").write_text(code)
    command = [sys.executable, "main.py"]
    if ranks > 1:
        command = [str(MPIRUN), "-n", str(ranks), *command]
    env = {**os.environ, "PYTHONDONTWRITEBYTECODE": "1"}  # no __pycache__ in scripts/
    return subprocess.run(command, cwd=cwd, env=env, capture_output=True, text=True, timeout=300)


@pytest.mark.parametrize("shadow", ["forms.py", "forms/__init__.py"])
@pytest.mark.parametrize(
    "statement",
    [
        "import strand",
        "from strand.model.model import StrandModel",
        "from strand.app.run import run_case",
    ],
)
def test_a_users_forms_is_named_in_one_line(tmp_path, shadow, statement):
    """A user's ``forms.py`` (or ``forms`` package) beside their script: importing strand, or
    any module of it that imports the beam forms, stops on one line that names the file and
    says to rename it, instead of "cannot import name 'CircularSection' from 'forms'"."""
    path = tmp_path / shadow
    path.parent.mkdir(exist_ok=True)
    path.write_text("import ufl\n\nresidual = None\n")
    done = python(statement + "\n", tmp_path)
    assert done.returncode != 0
    last = done.stderr.strip().splitlines()[-1]
    named = tmp_path / shadow.removesuffix("/__init__.py")
    assert last.startswith(f"ImportError: {named} shadows strand's beam forms"), done.stderr
    assert f"rename it, e.g. to my_{named.name}" in last


def test_strands_own_forms_pass(tmp_path):
    """Without a shadow (a folder ``forms`` without ``__init__.py`` is none) strand imports."""
    (tmp_path / "forms").mkdir()
    done = python("import strand.model.model\nprint('imported')\n", tmp_path)
    assert done.returncode == 0 and done.stdout == "imported\n", done.stderr


DOLFINX_FIRST = f"""
import site
import sys

site.addsitedir({str(MPI_FIRST)!r})
import dolfinx
from dolfinx import mesh
from mpi4py import MPI

import strand

domain = mesh.create_unit_interval(MPI.COMM_WORLD, 8)
cells = MPI.COMM_WORLD.allreduce(domain.topology.index_map(1).size_local)
if MPI.COMM_WORLD.rank == 0:
    print(dolfinx.__version__, "dolfinx_solver" in sys.modules, cells, MPI.COMM_WORLD.size)
"""


def _needs_the_wheel():
    import importlib.util

    if importlib.util.find_spec("dolfinx_solver") is None:
        pytest.skip("dolfinx is not the PyPI wheel (dolfinx-solver-real): no MPI order to keep")


def test_import_dolfinx_before_strand(tmp_path):
    """``import dolfinx`` first works with ``strand_mpi_first.pth``: the wheel's
    ``dolfinx_solver`` (MPI) is imported before it. Without the file (when the environment
    does not hold it already), the same import stops on the wheel's ``libmpi.so.12``."""
    _needs_the_wheel()
    done = python(DOLFINX_FIRST, tmp_path)
    assert done.returncode == 0, done.stderr[-2000:]
    assert done.stdout.split()[1:] == ["True", "8", "1"], done.stdout
    bare = python("import sys\nimport dolfinx\n", tmp_path)
    if "strand_mpi_first" not in sys.modules:  # this environment has no .pth of its own
        assert bare.returncode != 0 and "libmpi.so.12" in bare.stderr, bare.stderr[-2000:]


@needs_mpirun
def test_import_dolfinx_before_strand_on_2_ranks(tmp_path):
    """The same on two processes: one MPI world of 2, the mesh's 8 cells once."""
    _needs_the_wheel()
    done = python(DOLFINX_FIRST, tmp_path, ranks=2)
    assert done.returncode == 0, done.stderr[-2000:]
    assert done.stdout.split()[1:] == ["True", "8", "2"], done.stdout
