"""The type check of ``make lint``: mypy's errors through mypy-baseline, with this project's
settings (``[tool.mypy-baseline]`` in pyproject.toml). A new error fails, an error of the baseline
that is gone fails too (the baseline may only shrink, by ``mypy-baseline sync``), and the errors
of the baseline alone pass; line numbers do not count, so that an edit above an old error leaves
it in the baseline. Each case runs mypy on a small module of its own (about 2 s)."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
BIN = Path(sys.executable).parent
MYPY, BASELINE = BIN / "mypy", BIN / "mypy-baseline"

pytestmark = pytest.mark.skipif(
    not (MYPY.exists() and BASELINE.exists()), reason="mypy or mypy-baseline not installed"
)

OLD = 'old: int = "one"\n'  # the error the baseline holds
NEW = "new: str = 2\n"


def _mypy(folder: Path) -> str:
    """mypy's report on ``folder``'s module.py, with this project's settings."""
    return subprocess.run(
        [str(MYPY), "--no-incremental", "--config-file", str(ROOT / "pyproject.toml"), "module.py"],
        cwd=folder,
        capture_output=True,
        text=True,
    ).stdout


def _check(tmp_path: Path, source: str, baseline: str) -> subprocess.CompletedProcess[str]:
    """``make lint``'s pipe, mypy into mypy-baseline filter, on ``source`` against
    ``baseline``."""
    (tmp_path / "module.py").write_text(source)
    (tmp_path / "baseline.txt").write_text(baseline)
    return subprocess.run(
        [str(BASELINE), "filter", "--config", str(ROOT / "pyproject.toml")]
        + ["--baseline-path", "baseline.txt", "--no-colors"],
        cwd=tmp_path,
        input=_mypy(tmp_path),
        capture_output=True,
        text=True,
    )


@pytest.fixture(scope="module")
def baseline(tmp_path_factory: pytest.TempPathFactory) -> str:
    """The baseline of a module with the one old error, as ``mypy-baseline sync`` writes it."""
    folder = tmp_path_factory.mktemp("sync")
    (folder / "module.py").write_text(OLD)
    subprocess.run(
        [str(BASELINE), "sync", "--config", str(ROOT / "pyproject.toml")]
        + ["--baseline-path", "baseline.txt"],
        cwd=folder,
        input=_mypy(folder),
        check=True,
        capture_output=True,
        text=True,
    )
    text = (folder / "baseline.txt").read_text()
    assert text.count("\n") == 1 and "module.py:0: error:" in text, text
    return text


def test_the_baseline_alone_passes(tmp_path: Path, baseline: str) -> None:
    # moved down a line: the baseline holds no line numbers
    assert _check(tmp_path, "\n" + OLD, baseline).returncode == 0


def test_a_new_error_fails(tmp_path: Path, baseline: str) -> None:
    out = _check(tmp_path, OLD + NEW, baseline)
    assert out.returncode != 0
    assert "new: 1" in out.stdout and 'expression has type "int"' in out.stdout


def test_a_fixed_error_must_leave_the_baseline(tmp_path: Path, baseline: str) -> None:
    out = _check(tmp_path, "old: int = 1\n", baseline)
    assert out.returncode != 0 and "fixed: 1" in out.stdout
