# The two commands a new user needs; both set the environment up first (idempotent).
#   make run [CASE=my_case.toml]   the main job (default: the built-in Cardinal case; replaces
#                                  that case's earlier results)
#   make test                      lint (ruff), then the whole test suite
PY := .venv/bin/python
CASE ?= cardinal

.PHONY: setup run test lint
setup:
	@bash scripts/bootstrap.sh

run: setup
	$(PY) -m strand run $(CASE) --overwrite

test: lint
	$(PY) -m pytest -n auto --dist worksteal

lint: setup
	.venv/bin/ruff check .
	.venv/bin/ruff format --check .
