"""Record the results the docs show, so that building them runs nothing.

* ``python scripts/record_figures.py [demo_name ...]`` runs each demo (default: all of
  ``demos/``) serially, one code cell after the other in a fresh interpreter, and keeps in
  ``docs/_static/tutorials/<demo>/`` what each cell prints (``outputs.json``) and the figures the
  demo draws (the PNG files its code names). The tutorial pages show them under their cells
  (``docs/_ext/strand_docs.py``).
* ``python scripts/record_figures.py --outputs`` runs ``cases/quick_1x6.toml`` and keeps its
  figures in ``docs/_static/outputs/`` for the outputs reference.

Figures are stored as 256-colour PNGs (a few tens of kB each). Run it again after changing a
demo: ``tests/test_docs.py`` fails while a recorded cell is no longer in its demo.
"""

from __future__ import annotations

import argparse
import re
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).parents[1]
DEMOS = ROOT / "demos"
STATIC = ROOT / "docs" / "_static"

#: runs a demo's code cells in order in one namespace, keeping what each prints
CELLS = r"""
import contextlib, io, json, sys
import jupytext

demo, out = sys.argv[1], sys.argv[2]
scope = {"__name__": "__main__", "__file__": demo}
cells = []
for cell in jupytext.read(demo).cells:
    if cell.cell_type == "code":
        printed = io.StringIO()
        with contextlib.redirect_stdout(printed):
            exec(compile(cell.source, demo, "exec"), scope)
        cells.append({"code": cell.source, "output": printed.getvalue()})
with open(out, "w") as f:
    json.dump(cells, f, indent=1, ensure_ascii=False)
    f.write("\n")
"""


def figure_names(demo: Path) -> list[str]:
    """The PNG files a demo draws: those its code (not its prose) names."""
    import jupytext

    code = "\n".join(c.source for c in jupytext.read(demo).cells if c.cell_type == "code")
    return sorted(set(re.findall(r"([\w.-]+\.png)\b", code)))


def small_png(source: Path, target: Path) -> None:
    """``source`` as a 256-colour PNG at ``target`` (plots and renders keep their look)."""
    from PIL import Image

    with Image.open(source) as image:
        image.convert("RGB").quantize(256, dither=Image.Dither.NONE).save(target, optimize=True)


def record_demo(demo: Path) -> None:
    target = STATIC / "tutorials" / demo.stem
    with tempfile.TemporaryDirectory() as tmp:
        outputs = Path(tmp) / "outputs.json"
        subprocess.run([sys.executable, "-c", CELLS, str(demo), str(outputs)], cwd=tmp, check=True)
        shutil.rmtree(target, ignore_errors=True)
        target.mkdir(parents=True)
        shutil.copy(outputs, target / "outputs.json")
        for name in figure_names(demo):
            drawn = sorted(Path(tmp).glob(f"results/**/{name}"))
            if len(drawn) != 1:
                raise SystemExit(f"{demo.name}: {name} drawn {len(drawn)} times, not once")
            small_png(drawn[0], target / name)
    print(f"{demo.stem}: {', '.join(figure_names(demo))} and outputs.json in {target}")


def record_outputs() -> None:
    target = STATIC / "outputs"
    with tempfile.TemporaryDirectory() as tmp:
        run = [sys.executable, "-m", "strand.app", "run", str(ROOT / "cases" / "quick_1x6.toml")]
        subprocess.run([*run, "--out", f"{tmp}/run"], cwd=tmp, check=True)
        shutil.rmtree(target, ignore_errors=True)
        target.mkdir(parents=True)
        for png in sorted(Path(tmp, "run").glob("*.png")):
            small_png(png, target / png.name)
            print(target / png.name)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("demos", nargs="*", help="demo names (default: every demo)")
    parser.add_argument("--outputs", action="store_true", help="the quick case's run figures")
    args = parser.parse_args()
    if args.outputs:
        record_outputs()
    if args.demos or not args.outputs:
        names = args.demos or [p.stem for p in sorted(DEMOS.glob("demo_*.py"))]
        for name in names:
            record_demo(DEMOS / f"{name.removesuffix('.py')}.py")


if __name__ == "__main__":
    main()
