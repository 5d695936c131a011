#!/usr/bin/env bash
# Make .venv with a Python >= 3.12 and install strand with its extras (idempotent).
#
# Looks for an interpreter in this order: $STRAND_PYTHON, python3.13/python3.12 on PATH,
# pyenv's installed versions. Re-installs only when pyproject.toml changed.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
venv="$root/.venv"
stamp="$venv/.strand-installed"

ok_python() {  # usable: >= 3.12, venv module, C headers (FFCx JIT compiles forms)
  "$1" - <<'PY' >/dev/null 2>&1
import os, sys, sysconfig, venv  # noqa: F401
assert sys.version_info >= (3, 12)
assert os.path.exists(os.path.join(sysconfig.get_paths()["include"], "Python.h"))
PY
}

find_python() {
  local c
  for c in ${STRAND_PYTHON:-} python3.13 python3.12 python3; do
    c="$(command -v "$c" 2>/dev/null || true)"
    [ -n "$c" ] && ok_python "$c" && { echo "$c"; return 0; }
  done
  local pyenv_root="${PYENV_ROOT:-$HOME/.pyenv}"
  for c in $(ls -d "$pyenv_root"/versions/3.1[2-9]* 2>/dev/null | sort -rV); do
    ok_python "$c/bin/python3" && { echo "$c/bin/python3"; return 0; }
  done
  return 1
}

# what the environment is made from: a change of either re-installs
hash_of() {
  cat "$root/pyproject.toml" "$root"/scripts/mpi_first/strand_mpi_first.{py,pth} | sha256sum | cut -d' ' -f1
}

if [ -x "$venv/bin/python" ] && [ -f "$stamp" ] && [ "$(cat "$stamp")" = "$(hash_of)" ]; then
  exit 0
fi

if [ ! -x "$venv/bin/python" ] || ! ok_python "$venv/bin/python"; then
  if ! py="$(find_python)"; then
    cat >&2 <<'MSG'
strand setup: no Python >= 3.12 with development headers was found.
  dolfinx 0.11 (PyPI wheel dolfinx-solver-real) needs Python >= 3.12, and its form compiler needs Python.h.
  Install one, then re-run:
    - pyenv:   pyenv install 3.12      (found automatically under ~/.pyenv/versions)
    - Debian:  apt-get install python3.12 python3.12-venv python3.12-dev
    - or point STRAND_PYTHON at an interpreter: STRAND_PYTHON=/path/to/python3.12 make test
MSG
    exit 1
  fi
  echo "strand setup: creating .venv with $py ($("$py" --version))"
  rm -rf "$venv"
  "$py" -m venv "$venv"
fi

echo "strand setup: installing strand-cables[fenics,dev] into .venv"
# the distribution was called `strand` before (a name PyPI gives to an unrelated package)
"$venv/bin/python" -m pip uninstall --quiet --yes strand >/dev/null 2>&1 || true
pip_quiet() { "$venv/bin/python" -m pip install --quiet "$@" 2>&1 | grep -v "is ignored: it is neither" || true; }
pip_quiet --upgrade pip
# byte-compiled here, once: without it (pip --no-compile) every fresh interpreter the tests start
# compiled what it imports again where PYTHONDONTWRITEBYTECODE is set (a fresh clone's make test:
# setup 17 s shorter, pytest 33 s longer; 2026-11-29)
pip_quiet -e "$root[fenics,dev]"
# `import dolfinx` before `import strand`: the wheel's MPI library loaded first (the module's
# docstring says how)
site="$("$venv/bin/python" -c 'import sysconfig; print(sysconfig.get_paths()["purelib"])')"
cp "$root"/scripts/mpi_first/strand_mpi_first.py "$root"/scripts/mpi_first/strand_mpi_first.pth "$site/"
"$venv/bin/python" -c "import dolfinx, strand" || { echo "strand setup: install failed" >&2; exit 1; }
hash_of > "$stamp"
echo "strand setup: done"
