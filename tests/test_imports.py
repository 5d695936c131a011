"""How strand is imported, in a fresh interpreter each: a user's own ``forms.py`` that shadows
strand's beam forms is named in one line with the fix."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

from strand_cases import MPIRUN


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
