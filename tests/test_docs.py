"""The documentation builds from the docstrings without a warning, and the repository cites its
own theory pages, not notes a user of the repository does not have."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).parents[1]


def test_docs_build_without_warnings_and_document_the_api(tmp_path):
    pytest.importorskip("sphinx")
    pytest.importorskip("myst_parser")
    run = subprocess.run(
        [sys.executable, "-m", "sphinx", "-E", "-W", "--keep-going", "-q", "-b", "html",
         str(ROOT / "docs"), str(tmp_path)],
        capture_output=True, text=True, timeout=300,
    )  # fmt: skip
    assert run.returncode == 0, run.stderr[-3000:]
    api = (tmp_path / "api.html").read_text()
    for name in ("NonlinearProblem", "ContactGroup", "HertzPointLaw", "StickSlipLaw", "run_case",
                 "prepare_results_folder", "ReissnerBeam", "load_case"):  # fmt: skip
        assert f'id="{name}"' in api or f".{name}" in api, name
    theory = (tmp_path / "theory.html").read_text()
    assert "Stick–slip bending law" in theory and "How far small sliding holds" in theory


def test_the_repository_cites_its_own_theory_pages():
    cited = [
        str(p.relative_to(ROOT))
        for pattern in (
            "strand/**/*.py",
            "forms/*.py",
            "tests/*.py",
            "demos/*.py",
            "*.md",
            "strand/data/*.toml",
        )  # fmt: skip
        for p in ROOT.glob(pattern)
        if p.name != "test_docs.py"
        and any(s in p.read_text() for s in ("physics.md", "physics notes"))
    ]
    assert cited == []
