from __future__ import annotations

from pathlib import Path

import pytest

import strand  # noqa: F401  (the dolfinx wheel's libraries load before petsc4py/dolfinx)

ROOT = Path(__file__).resolve().parents[1]


@pytest.fixture(scope="session")
def quick_run(tmp_path_factory):
    """``cases/quick_1x6.toml`` as a user first runs it (fields off: ~15 s), once per session: its
    folder and its figures as they were saved (``figures``: name → the matplotlib figure), for
    the tests of the figures and of the fatigue report."""
    import strand.app.plots as plots
    from strand.app.case import load_case
    from strand.app.run import run_case

    figures = {}
    save_figure = plots.save_figure

    def keep_figure(fig, path, *args, **kwargs):
        figures[Path(path).name] = fig
        return save_figure(fig, path, *args, **kwargs)

    folder = tmp_path_factory.mktemp("quick") / "out"
    case = load_case(ROOT / "cases" / "quick_1x6.toml", ["output.fields=false"])
    with pytest.MonkeyPatch.context() as m:
        m.setattr(plots, "save_figure", keep_figure)
        result = run_case(case, folder)
    assert not result.failure
    return {"folder": folder, "figures": figures, "case": case}
