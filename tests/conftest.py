from __future__ import annotations

import os
from pathlib import Path

import pytest

import strand  # noqa: F401  (the dolfinx wheel's libraries load before petsc4py/dolfinx)

ROOT = Path(__file__).resolve().parents[1]

# The suite's workers and the MPI runs they start share the cores. Waiting MPICH ranks spin; with
# this they sleep a microsecond now and then (measured on 2 cores: 3 ranks 12.5 → 9.2 s, 2 ranks
# beside a busy core 10.8 → 9.6 s, 2 ranks alone unchanged).
os.environ.setdefault("MPIR_CVAR_CH4_PROGRESS_THROTTLE", "1")


def pytest_collection_modifyitems(items: list[pytest.Item]) -> None:
    """The slow runs first, then the tests of the session's quick run, each group in its own
    order. ``--dist worksteal`` (``make test``, ``make check``) hands each worker a contiguous share and lets an
    idle worker take the end of another's: the long runs then start early, one worker makes the
    quick run for all its tests, and the short tests even the workers out at the end."""
    items.sort(
        key=lambda item: (
            item.get_closest_marker("slow") is None,
            "quick_run" not in getattr(item, "fixturenames", ()),
        )
    )


@pytest.fixture(scope="session")
def quick_run(tmp_path_factory):
    """``cases/quick_1x6.toml`` as a user first runs it (fields off: ~15 s), once per session: its
    folder, and what its figures showed as they were saved (``figures``: name → the matplotlib
    figure; ``pictures``: name → the pyvista plotter's title extent, window size and rulers),
    for the tests of the figures and of the fatigue report."""
    import strand.app.deformed_picture as picture
    import strand.app.plots as plots
    from strand.app.case import load_case
    from strand.app.run import run_case

    figures, pictures = {}, {}
    save_figure, save = plots.save_figure, picture.save

    def keep_figure(fig, path, *args, **kwargs):
        figures[Path(path).name] = fig
        return save_figure(fig, path, *args, **kwargs)

    def keep_picture(plotter, path):
        title = plotter.actors["title"]
        box = picture.text_extent(plotter, title)
        props = plotter.renderer.GetViewProps()
        props = [props.GetItemAsObject(i) for i in range(props.GetNumberOfItems())]
        rulers = [p for p in props if p.IsA("vtkAxisActor2D")]
        pictures[Path(path).name] = {
            "title": tuple(box),
            "text": title.GetInput(),
            "window": tuple(plotter.window_size),
            "rulers": [(r.GetTitle(), r.GetRange()) for r in rulers],
        }
        return save(plotter, path)

    folder = tmp_path_factory.mktemp("quick") / "out"
    case = load_case(ROOT / "cases" / "quick_1x6.toml", ["output.fields=false"])
    with pytest.MonkeyPatch.context() as m:
        m.setattr(plots, "save_figure", keep_figure)
        m.setattr(picture, "save", keep_picture)
        result = run_case(case, folder)
    assert not result.failure
    return {"folder": folder, "figures": figures, "pictures": pictures, "case": case}
