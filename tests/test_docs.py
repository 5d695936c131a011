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
        [
            sys.executable,
            "-m",
            "sphinx",
            "-E",
            "-W",
            "--keep-going",
            "-q",
            "-b",
            "html",
            str(DOCS),
            str(out),
        ],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert run.returncode == 0, run.stderr[-3000:]
    return out


@pytest.mark.slow  # the Sphinx build they share takes ~20 s
def test_docs_build_without_warnings_and_document_the_api(built):
    api = "".join(p.read_text() for p in (built / "api").glob("*.html"))
    for name in (
        "NonlinearProblem",
        "ContactGroup",
        "HertzPointLaw",
        "StickSlipLaw",
        "run_case",
        "prepare_results_folder",
        "ReissnerBeam",
        "load_case",
    ):
        assert f'id="{name}"' in api or f".{name}" in api, name
    theory = (built / "theory.html").read_text()
    assert "Stick–slip bending law" in theory and "How far small sliding holds" in theory


@pytest.mark.slow  # the Sphinx build they share takes ~20 s
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


@pytest.mark.slow  # the Sphinx build they share takes ~20 s
def test_attribute_docs_keep_their_first_clause(built):
    """Napoleon reads "X: Y" at the start of an attribute's docstring as a type X: strand's
    ``#:`` comments are prose, and their first clause stays in the sentence (it rendered as
    "Type: stall test" under ``NewtonOptions.stall_after``, in 31 places)."""
    solver = re.sub(r"<[^>]+>", "", (built / "api" / "solver.html").read_text())
    assert "stall test: from iteration stall_after on" in solver
    types = [
        re.sub(r"<[^>]+>", "", t).strip()
        for page in (built / "api").glob("*.html")
        for t in re.findall(
            r'Type<span class="colon">:</span></dt>\s*<dd[^>]*>(.*?)</dd>', page.read_text(), re.S
        )
    ]
    assert types  # annotations still give types
    assert [t for t in types if re.search(r"\b(the|a|an|of|in|at|to)\b", t)] == []


def test_every_module_has_an_api_page():
    """Each module of strand and forms is on an API page, itself or as a member of its package."""
    documented = {
        m
        for page in (DOCS / "api").glob("*.md")
        for m in re.findall(r"automodule:: ([\w.]+)", page.read_text())
    }
    missing = []
    for path in [*ROOT.glob("strand/**/*.py"), *ROOT.glob("forms/*.py")]:
        module = ".".join(path.relative_to(ROOT).with_suffix("").parts).removesuffix(".__init__")
        if module in ("strand", "strand.app.__main__", "strand.cable.data"):
            continue
        parent = module.rpartition(".")[0]
        if module not in documented and (parent == "strand" or parent not in documented):
            missing.append(module)
    assert missing == []


@pytest.mark.slow  # the Sphinx build they share takes ~20 s
def test_the_settings_reference_lists_every_setting_with_its_default(built):
    from strand.app.kinds import registered
    from strand.app.settings import KIND_SECTIONS, SECTIONS

    page = (built / "_generated" / "settings.html").read_text()
    for section, cls in SECTIONS.items():
        assert f"[{section}]" in page, section
        classes = [cls] + [
            getattr(k, KIND_SECTIONS[section]) for k in registered() if section in KIND_SECTIONS
        ]
        for c in classes:
            for f in fields(c):
                if f.name != "by_kind":
                    assert (
                        f'<code class="docutils literal notranslate"><span class="pre">{f.name}</span>'
                        in page
                    ), (section, f.name)
    assert '<span class="pre">&quot;hertz&quot;</span>' in page  # a default, as TOML


def test_the_outputs_reference_names_every_file_a_run_writes():
    from strand.app.run_files import outputs

    text = (DOCS / "outputs.md").read_text()
    assert [name for name in outputs() if f"`{name}`" not in text] == []


@pytest.mark.slow  # the Sphinx build they share takes ~20 s
def test_every_demo_is_a_tutorial_with_its_maths(built):
    pages = built / "_generated" / "tutorials"
    for demo in sorted((ROOT / "demos").glob("demo_*.py")):
        page = (pages / f"{demo.stem}.html").read_text()
        assert f"demos/{demo.name}" in page, demo.stem
    assert 'class="math' in (pages / "demo_section_law.html").read_text()


def _images(page: Path) -> list[Path]:
    """The images an HTML page of the build shows, as files of the build."""
    sources = re.findall(r'<img [^>]*src="([^"]+)"', page.read_text())
    return [
        (page.parent / src).resolve() for src in sources if not src.startswith(("http", "data:"))
    ]


@pytest.mark.slow  # the Sphinx build they share takes ~20 s
def test_every_image_a_page_shows_is_in_the_build(built):
    shown = {page: _images(page) for page in built.rglob("*.html")}
    missing = [
        (str(p.relative_to(built)), str(i))
        for p, images in shown.items()
        for i in images
        if not (i.is_file() and i.stat().st_size > 0)
    ]
    assert missing == []
    committed = {p.name for p in DOCS.glob("_static/**/*.png")}
    assert committed <= {i.name for images in shown.values() for i in images}


@pytest.mark.slow  # the Sphinx build they share takes ~20 s
def test_every_tutorial_shows_its_figures_and_what_it_printed(built):
    """Each tutorial page shows the figures its demo draws and what its cells printed, as
    recorded (``scripts/record_figures.py``): the crossed beams' friction loop against the closed
    form among them."""
    pages = built / "_generated" / "tutorials"
    for demo in sorted((ROOT / "demos").glob("demo_*.py")):
        page = pages / f"{demo.stem}.html"
        figures = {p.name for p in (DOCS / "_static" / "tutorials" / demo.stem).glob("*.png")}
        assert figures and figures <= {i.name for i in _images(page)}, demo.stem
        assert page.read_text().count('class="demo-output') >= 1, demo.stem
    crossed = (pages / "demo_crossed_beams.html").read_text()
    assert "friction_loop.png" in crossed and "largest |Q − Q_exact| / μP = " in crossed


def test_the_recorded_results_are_those_of_the_demos_as_they_are():
    """Every recorded cell is a code cell of its demo as it is now, and every recorded figure is
    named by one (else: ``python scripts/record_figures.py <demo>``)."""
    pytest.importorskip("sphinx")
    pytest.importorskip("jupytext")
    sys.path.insert(0, str(DOCS / "_ext"))
    from strand_docs import demo_page

    for demo in sorted((ROOT / "demos").glob("demo_*.py")):
        assert (DOCS / "_static" / "tutorials" / demo.stem / "outputs.json").is_file(), demo.stem
        assert demo_page(demo)[1] == [], demo.stem


@pytest.mark.slow  # the Sphinx build they share takes ~20 s
def test_the_outputs_reference_shows_every_figure_a_run_draws(built):
    """Each figure a run draws, the quick case's, beside its description."""
    from strand.app.run_files import outputs

    figures = {name for name in outputs() if name.endswith(".png")}
    page = built / "outputs.html"
    assert figures <= {i.name for i in _images(page)}
    for name in figures:  # under it, a caption that names it and says what it shows
        caption = rf'src="_images/{name}" />\s*<figcaption>\s*<p><span class="caption-text"><code'
        assert re.search(
            caption + rf'[^>]*><span class="pre">{name}</span></code> \(', page.read_text()
        ), name


@pytest.mark.slow  # the Sphinx build they share takes ~20 s
def test_the_gallery_shows_every_figure_with_a_link_to_its_page(built):
    """The gallery shows every figure the docs hold, each linked to its tutorial or to its
    description in the outputs reference."""
    recorded = {p.name for p in (DOCS / "_static").glob("*/**/*.png")}
    gallery = built / "gallery.html"
    assert recorded <= {i.name for i in _images(gallery)}
    links = re.findall(r'href="([^"]+)"', gallery.read_text())
    for demo in sorted((ROOT / "demos").glob("demo_*.py")):
        assert f"_generated/tutorials/{demo.stem}.html" in links, demo.stem
    for name in sorted(p.stem for p in (DOCS / "_static" / "outputs").glob("*.png")):
        assert f"outputs.html#{name.replace('_', '-')}-png" in links, name


def test_the_figures_are_small():
    large = [str(p) for p in DOCS.glob("_static/**/*.png") if p.stat().st_size > 120_000]
    assert large == []


def test_the_mooring_page_shows_its_recorded_figures_with_their_stamp():
    """Each figure ``scripts/record_figures.py --mooring`` recorded is on docs/mooring.md, its
    caption stamped with the recording's date and commit (``stamp.txt``), and the page gives
    the command that drew them."""
    folder = DOCS / "_static" / "mooring"
    stamp = dict(line.split(": ", 1) for line in (folder / "stamp.txt").read_text().splitlines())
    assert "+changes" not in stamp["commit"], stamp
    page = (DOCS / "mooring.md").read_text()
    figures = re.findall(r"```\{figure\} _static/mooring/(\S+)\n(.*?)```", page, re.S)
    shown = {name: caption for name, caption in figures}
    assert set(shown) == {p.name for p in folder.glob("*.png")} and len(shown) == 4
    for name, caption in shown.items():
        assert f"`{name}`" in caption, name
        assert f"({stamp['date']}, commit {stamp['commit']})" in caption, name
    commands = [
        " ".join(c.replace("\\\n", " ").split()) for c in re.findall(r"```\n(.*?)```", page, re.S)
    ]
    assert stamp["command"] in commands


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
    commands = readme.split("## Two commands", 1)[1].split("```bash\n", 1)[1].split("```", 1)[0]
    run, test = (line.split("#")[0].strip() for line in commands.splitlines())
    assert run == "make run" and test == "make check"
    assert f"\n{test}\n" in (ROOT / ".ci" / "run").read_text()  # CI runs the README's command
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
        )
        for p in ROOT.glob(pattern)
        if p.name != "test_docs.py"
        and any(s in p.read_text() for s in ("physics.md", "physics notes"))
    ]
    assert cited == []


@pytest.mark.slow  # the Sphinx build they share takes ~20 s
def test_the_forms_page_documents_what_a_law_overrides(built):
    """Every method a beam law of one's own overrides is on the forms page (autodoc drops a
    method without a docstring), with the page's "what to override" list."""
    page = (built / "api" / "forms.html").read_text()
    assert "What to override" in page
    for name in (
        "ReissnerBeam.strain_energy_density",
        "ReissnerBeam.residual",
        "ReissnerBeam.N",
        "ReissnerBeam.M",
        "CircularSection.force_stiffness",
        "CircularSection.moment_stiffness",
    ):
        assert f'id="forms.reissner.{name}"' in page, name


def _css_rules(css: str) -> list[tuple[set[str], dict[str, str]]]:
    """The rules of a style sheet without nesting: (selectors, declarations)."""
    css = re.sub(r"/\*.*?\*/", "", css, flags=re.S)
    rules = []
    for selectors, body in re.findall(r"([^{}]+)\{([^{}]*)\}", css):
        declarations = dict(
            (k.strip(), v.strip())
            for k, _, v in (d.partition(":") for d in body.split(";") if ":" in d)
        )
        rules.append(({" ".join(s.split()) for s in selectors.split(",")}, declarations))
    return rules


@pytest.mark.slow  # the Sphinx build they share takes ~20 s
def test_code_cells_and_printed_lines_wrap(built):
    """Every code cell and printed output of a tutorial is a ``pre`` in a ``div.highlight``, on a
    page that loads ``strand.css``, whose rule for them wraps long lines (at 1200 px in Chromium,
    lines over ~75 characters were cut behind a scrollbar); no rule there makes a block scroll
    sideways or hides a long output below a scrollbar, and the page may grow past alabaster's
    fixed 1100 px."""
    rules = _css_rules((built / "_static" / "strand.css").read_text())
    wrap = [d for s, d in rules if "div.highlight pre" in s]
    assert any(d.get("white-space") == "pre-wrap" for d in wrap), wrap
    assert any(d.get("overflow-wrap") == "anywhere" for d in wrap), wrap  # unbroken strings too
    scrolls = ("overflow", "overflow-x", "overflow-y", "max-height")
    assert [d for _, d in rules if any(k in d for k in scrolls)] == []
    assert [d for _, d in rules if d.get("white-space") in ("pre", "nowrap")] == []
    document = [d for s, d in rules if "div.document" in s]
    assert any(d.get("width") == "auto" for d in document), document
    pages = sorted((built / "_generated" / "tutorials").glob("*.html"))
    assert len(pages) == len(list((ROOT / "demos").glob("demo_*.py")))
    for page in pages:
        text = page.read_text()
        assert "_static/strand.css" in text, page.name
        blocks = re.findall(r"(<div class=\"highlight\"><pre>)|<pre\b", text)
        assert blocks and all(blocks), page.name  # every pre opens a div.highlight's


def _chromium() -> str | None:
    import shutil

    return next(
        (
            shutil.which(b)
            for b in ("chromium", "chromium-browser", "google-chrome")
            if shutil.which(b)
        ),
        None,
    )


#: appended to a page before Chromium renders it: after the page (and MathJax) has loaded, it
#: writes what it measured into the page, which ``--dump-dom`` then prints
_MEASURE = """<script>
window.addEventListener('load', () => setTimeout(() => {
  const clipped = [];
  for (const el of document.querySelectorAll('pre, div.highlight, table, div.math')) {
    const style = getComputedStyle(el);
    if ((el.scrollWidth > el.clientWidth + 1 && style.overflowX !== 'visible') ||
        (el.scrollHeight > el.clientHeight + 1 && style.overflowY !== 'visible'))
      clipped.push([el.tagName, el.scrollWidth, el.clientWidth, el.scrollHeight, el.clientHeight,
                    el.textContent.slice(0, 60)]);
  }
  const root = document.documentElement;
  const body = document.querySelector('div.body'), style = getComputedStyle(body);
  const text = body.clientWidth - parseFloat(style.paddingLeft) - parseFloat(style.paddingRight);
  const images = [...document.querySelectorAll('div.body img')].map(
    i => [i.getAttribute('src'), i.clientWidth, i.naturalWidth]);
  const p = document.createElement('pre');
  p.id = 'strand-measure';
  p.textContent = JSON.stringify({clipped, images, page: [root.scrollWidth, root.clientWidth],
                                  body: text, mathjax: !!document.querySelector('mjx-container')});
  document.body.appendChild(p);
}, 500));
</script>"""


def _measure_in_chromium(browser: str, page: Path, width: int = 1200) -> dict:
    """What Chromium, headless with a window ``width`` px wide, lays out on ``page``: the blocks
    whose content is wider or taller than their box, which scrolls (``clipped``), the page's scroll and client widths,
    the text's width and each image's shown and natural width."""
    import html
    import json

    probe = page.with_name(f"{page.stem}.measure.html")
    probe.write_text(page.read_text().replace("</body>", _MEASURE + "</body>"))
    try:
        done = subprocess.run(
            [
                browser,
                "--headless",
                "--no-sandbox",
                "--disable-gpu",
                f"--window-size={width},900",
                "--virtual-time-budget=10000",
                "--dump-dom",
                probe.as_uri(),
            ],
            capture_output=True,
            text=True,
            timeout=180,
        )
    finally:
        probe.unlink()
    found = re.search(r'<pre id="strand-measure">(.*?)</pre>', done.stdout, re.S)
    assert found, done.stderr[-2000:]
    return json.loads(html.unescape(found.group(1)))


@pytest.mark.slow
def test_nothing_is_clipped_at_1200_px_in_chromium(built):
    """In a real browser (Chromium, headless, a window 1200 px wide: Debian's ``chromium``,
    ``.ci/run``), no code cell, printed output, table or formula of a tutorial is wider or taller
    than its box, and no page scrolls sideways; the gallery shows each figure at its own width, or at the
    text's full width if wider (two-panel figures were shrunk to 384 of their 1200 px).
    Measured before the fix: 5 to 11 blocks per tutorial cut sideways, and the long outputs
    cut at 26 lines."""
    browser = _chromium()
    if browser is None:
        pytest.skip("no Chromium (Debian: apt-get install chromium)")
    pages = sorted((built / "_generated" / "tutorials").glob("*.html"))
    faults = []
    for page in [*pages, built / "gallery.html"]:
        measured = _measure_in_chromium(browser, page)
        faults += [(page.name, *c) for c in measured["clipped"]]
        scroll, client = measured["page"]
        if scroll > client:
            faults.append((page.name, "page", scroll, client))
        if page.name == "demo_section_law.html":
            assert measured["mathjax"], "MathJax rendered the formulas before measuring"
    assert faults == []
    gallery = _measure_in_chromium(browser, built / "gallery.html")
    assert gallery["body"] >= 850  # the text's width at 1200 px (800 px with alabaster's cap)
    small = [i for i in gallery["images"] if i[1] < min(i[2], gallery["body"]) - 1]
    assert small == [] and len(gallery["images"]) >= 10, gallery["images"]
