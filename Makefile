# The two commands a new user needs; both set the environment up first (idempotent).
#   make run [CASE=my_case.toml] [NP=n]   the main job (default: the built-in Cardinal case) on
#                                  NP MPI ranks (default: every core); replaces that case's
#                                  earlier results; ARGS="--out folder" passes more options
#   make check                     lint (ruff, mypy), then every test, the slow integration runs
#                                  too; what CI runs
# and for contributors:
#   make test                      lint, then every test but the slow ones (a fresh clone: ≤ 5 min
#                                  on 2 cores), the 25 slowest named
PY := .venv/bin/python
CASE ?= cardinal
NP ?= $(shell nproc 2>/dev/null || echo 1)

.PHONY: setup run test check lint
setup:
	@bash scripts/bootstrap.sh

run: setup
	.venv/bin/mpirun -n $(NP) $(PY) -m strand.app run $(CASE) --overwrite $(ARGS)

test: lint
	$(PY) -m pytest -n auto --dist worksteal -m "not slow" --durations=25

check: lint
	$(PY) -m pytest -n auto --dist worksteal --durations=25

lint: setup
	.venv/bin/ruff check .
	.venv/bin/ruff format --check .
# mypy: a type error not in mypy-baseline.txt fails, and so does one of it that is gone (after
# fixing some, `.venv/bin/mypy | .venv/bin/mypy-baseline sync` shrinks the baseline)
	.venv/bin/mypy | .venv/bin/mypy-baseline filter --no-colors
