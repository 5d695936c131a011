"""The documentation builds without a warning and holds what it promises (the API of every module,
a settings reference generated from the settings classes, every output file, the demos as
tutorials, real maths in the theory); the README is a front door whose links resolve; and the
repository cites its own theory pages, not notes a user of the repository does not have."""

from __future__ import annotations

import re
import subprocess
import sys
from dataclasses import fields
from pathlib import Path

import pytest

ROOT = Path(__file__).parents[1]
DOCS = ROOT / "docs"


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    """The HTML build of the docs (one per test session of this module)."""
    pytest.importorskip("sphinx")
    pytest.importorskip("myst_parser")
    pytest.importorskip("jupytext")
    pytest.importorskip("sphinx-mathjax-offline")
    out = tmp_path_factory.mktemp("html")
    run = subprocess.run(
        [sys.executable, "-m", "sphinx", "-E", "-W", "--keep-going", "-q", "-b", "html",
         str(DOCS), str(out)],
        capture_output=True, text=True, timeout=300,
    )  # fmt: skip
    assert run.returncode == 0, run.stderr[-3000:]
    return out


def test_docs_build_without_warnings_and_document_the_api(built):
    api = "".join(p.read_text() for p in (built / "api").glob("*.html"))
    for name in ("NonlinearProblem", "ContactGroup", "HertzPointLaw", "StickSlipLaw", "run_case",
                 "prepare_results_folder", "ReissnerBeam", "load_case"):  # fmt: skip
        assert f'id="{name}"' in api or f".{name}" in api, name
    theory = (built / "theory.html").read_text()
    assert "Stick–slip bending law" in theory and "How far small sliding holds" in theory


def test_the_docs_need_no_network_for_their_scripts_and_maths(built):
    """No page loads a script from elsewhere (MathJax from a CDN left the maths as raw TeX
    offline); the MathJax the pages load is in the build, with its fonts."""
    remote, mathjax = [], set()
    for page in built.rglob("*.html"):
        for src in re.findall(r'<script\b[^>]*\bsrc="([^"]*)"', page.read_text()):
            if re.match(r"(https?:)?//", src):
                remote.append(f"{page.relative_to(built)}: {src}")
            elif "mathjax" in src.lower():
                mathjax.add((page.parent / src.split("?")[0]).resolve())
    assert remote == []
    assert len(mathjax) == 1, mathjax  # one MathJax, every page's relative path to it
    script = mathjax.pop()
    assert script.is_file() and script.stat().st_size > 500_000, script  # all of tex-chtml.js
    assert list((script.parent / "output" / "chtml" / "fonts" / "woff-v2").glob("*.woff"))
    theory = (built / "theory.html").read_text()
    assert "mathjax" in theory.lower() and theory.count('class="math') >= 20


def test_attribute_docs_keep_their_first_clause(built):
    """Napoleon reads "X: Y" at the start of an attribute's docstring as a type X: strand's
    ``#:`` comments are prose, and their first clause stays in the sentence (it rendered as
    "Type: stall test" under ``NewtonOptions.stall_after``, in 31 places)."""
    solver = re.sub(r"<[^>]+>", "", (built / "api" / "solver.html").read_text())
    assert "stall test: from iteration stall_after on" in solver
    types = [
        re.sub(r"<[^>]+>", "", t).strip()
        for page in (built / "api").glob("*.html")
        for t in re.findall(r'Type<span class="colon">:</span></dt>\s*<dd[^>]*>(.*?)</dd>',
                            page.read_text(), re.S)
    ]  # fmt: skip
    assert types  # annotations still give types
    assert [t for t in types if re.search(r"\b(the|a|an|of|in|at|to)\b", t)] == []


def test_every_module_has_an_api_page():
    """Each module of strand and forms is on an API page, itself or as a member of its package."""
    documented = {
        m for page in (DOCS / "api").glob("*.md")
        for m in re.findall(r"automodule:: ([\w.]+)", page.read_text())
    }  # fmt: skip
    missing = []
    for path in [*ROOT.glob("strand/**/*.py"), *ROOT.glob("forms/*.py")]:
        module = ".".join(path.relative_to(ROOT).with_suffix("").parts).removesuffix(".__init__")
        if module in ("strand", "strand.__main__", "strand.cable.data"):
            continue
        parent = module.rpartition(".")[0]
        if module not in documented and (parent == "strand" or parent not in documented):
            missing.append(module)
    assert missing == []


def test_the_settings_reference_lists_every_setting_with_its_default(built):
    from strand.app.kinds import registered
    from strand.app.settings import KIND_SECTIONS, SECTIONS

    page = (built / "_generated" / "settings.html").read_text()
    for section, cls in SECTIONS.items():
        assert f"[{section}]" in page, section
        classes = [cls] + [getattr(k, KIND_SECTIONS[section]) for k in registered()
                           if section in KIND_SECTIONS]  # fmt: skip
        for c in classes:
            for f in fields(c):
                if f.name != "by_kind":
                    assert f"<code class=\"docutils literal notranslate\"><span class=\"pre\">{f.name}</span>" in page, (section, f.name)  # fmt: skip
    assert '<span class="pre">&quot;hertz&quot;</span>' in page  # a default, as TOML


def test_the_outputs_reference_names_every_file_a_run_writes():
    from strand.app.run_files import OUTPUTS

    text = (DOCS / "outputs.md").read_text()
    assert [name for name in OUTPUTS if f"`{name}`" not in text] == []


def test_every_demo_is_a_tutorial_with_its_maths(built):
    pages = built / "_generated" / "tutorials"
    for demo in sorted((ROOT / "demos").glob("demo_*.py")):
        page = (pages / f"{demo.stem}.html").read_text()
        assert f"demos/{demo.name}" in page, demo.stem
    assert 'class="math' in (pages / "demo_section_law.html").read_text()


def test_the_theory_writes_its_formulas_as_maths():
    text = (DOCS / "theory.md").read_text()
    prose = re.sub(r"\$\$.*?\$\$", "", text, flags=re.S)
    prose = re.sub(r"\$[^$\n]+\$", "", prose)
    prose = re.sub(r"`[^`\n]+`", "", prose)
    plain = re.findall(r"\S*[_^]\{\S*", prose)
    assert plain == [], "formulas outside $…$: " + " ".join(plain[:10])
    assert text.count("$$") >= 20


def test_the_readme_is_a_front_door_whose_links_resolve():
    readme = (ROOT / "README.md").read_text()
    assert 120 <= len(readme.splitlines()) <= 180
    assert "make run" in readme and "make test" in readme
    assert "make test" in (ROOT / ".ci" / "run").read_text()  # CI runs the README's command
    targets = re.findall(r"\]\(((?!https?:|#)[^)#]+)(?:#[^)]*)?\)", readme)
    assert targets and [t for t in targets if not (ROOT / t).exists()] == []
    assert "## Stick bending" in readme


def test_the_repository_cites_its_own_theory_pages():
    cited = [
        str(p.relative_to(ROOT))
        for pattern in (
            "strand/**/*.py",
            "forms/*.py",
            "tests/*.py",
            "demos/*.py",
            "*.md",
            "strand/cable/data/*.toml",
        )  # fmt: skip
        for p in ROOT.glob(pattern)
        if p.name != "test_docs.py"
        and any(s in p.read_text() for s in ("physics.md", "physics notes"))
    ]
    assert cited == []
