"""Small vs large sliding on one case: the same mesh, laws, loads and solver, two contact models.

``compare_case`` runs a case twice, with ``contact.model = "small"`` (pairs fixed at t = 0) and
``"large"`` (pairs re-projected at every iteration, the baseline), each into its own folder with
every output of ``strand run``; then it compares them at the largest lateral load: the cost of
each (steps, Newton iterations, wall time, time in the contact terms), the midspan deflections,
and per layer and 45° sector the largest difference of the wire axial forces relative to that
layer's force range. Writes ``comparison.txt`` and ``sliding_comparison.png`` (axial forces of
both models along z per layer, and their difference coloured by sector). Forces in N.
"""

from __future__ import annotations

import sys
from dataclasses import replace
from pathlib import Path

import numpy as np

from ..model.cell_results import CellResults, sector_of
from .kinds import kind_of
from .settings import Case

__all__ = ["compare_case", "force_differences", "difference_table", "overlay_figure"]

SECTORS = 8


def force_differences(a: CellResults, b: CellResults, n_layers: int) -> list[dict]:
    """Per layer: the range of a's axial forces (N), and max abs(N_b − N_a) relative to it, over the
    layer and per 45° sector of φ (NaN for the core, which has no sector)."""
    rows = []
    for layer in range(n_layers):
        m = a.layer == layer
        span = float(np.ptp(a.axial[m]))
        diff = np.abs(b.axial[m] - a.axial[m]) / span
        sector = sector_of(a.phi[m], SECTORS)
        per = np.array([diff[sector == s].max(initial=0.0) for s in range(SECTORS)])
        rows.append(
            {
                "layer": layer,
                "range": span,
                "max": float(diff.max()),
                "sectors": per if layer else np.full(SECTORS, np.nan),
            }
        )
    return rows


def difference_table(a: CellResults, b: CellResults, n_layers: int) -> str:
    """``force_differences`` as text."""
    width = 360 // SECTORS
    head = " ".join(f"{-180 + width * s:>5d}" for s in range(SECTORS))
    lines = [
        "layer   range N  max |ΔN|/range   per sector from φ (deg): max |ΔN|/range",
        f"{'':>34}{head}",
    ]
    for row in force_differences(a, b, n_layers):
        per = " ".join(f"{v:5.3f}" for v in row["sectors"]) if row["layer"] else "    -"
        name = "core" if row["layer"] == 0 else str(row["layer"])
        lines.append(f"{name:>5} {row['range']:9.1f} {row['max']:15.3f}   {per}")
    return "\n".join(lines)


def overlay_figure(a: CellResults, b: CellResults, n_layers: int, title: str, path: Path) -> Path:
    """Axial forces of a (small sliding) and b (large sliding) along z per layer; right: b − a
    coloured by sector."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(
        n_layers,
        2,
        figsize=(13, 2.2 * n_layers + 0.6),
        sharex=True,
        squeeze=False,
        gridspec_kw={"width_ratios": [3, 2]},
    )
    colours = plt.get_cmap("tab10")
    width = 360 // SECTORS
    for layer in range(n_layers):
        m = a.layer == layer
        ax, dx = axes[layer]
        ax.scatter(1e3 * a.z[m], a.axial[m], s=2, label="small sliding")
        ax.scatter(1e3 * b.z[m], b.axial[m], s=2, marker="x", label="large sliding")
        ax.set_ylabel(f"{'core' if layer == 0 else f'layer {layer}'}\nN (N)")
        sector = sector_of(a.phi[m], SECTORS) if layer else np.zeros(m.sum(), dtype=int)
        for s in np.unique(sector):
            k = sector == s
            label = f"{-180 + width * s}…{-180 + width * (s + 1)}°" if layer else "core"
            dx.scatter(
                1e3 * a.z[m][k], (b.axial - a.axial)[m][k], s=2, color=colours(s), label=label
            )
        dx.set_ylabel("ΔN, large − small (N)")
    axes[0, 0].legend(markerscale=4)
    if n_layers > 1:
        axes[1, 1].legend(markerscale=4, fontsize=7, ncol=2, title="φ sector", title_fontsize=7)
    for ax in axes[-1]:
        ax.set_xlabel("z (mm)")
    fig.suptitle(title)
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def compare_case(
    case: Case, folder: str | Path | None = None, stream=None, overwrite: bool = False
) -> str:
    """Run ``case`` with both contact models into ``folder``/small and ``folder``/large (default
    folder: the case's output folder + ``/sliding_comparison``); return the comparison text,
    also written to ``comparison.txt`` there. Both folders are checked before either run
    (``folder.check_results_folder``; ``overwrite`` replaces an earlier comparison). Both
    run without same-layer contact, which large sliding does not have."""
    from ..beam.parallel import is_root, on_root, root_stream
    from .folder import check_results_folder
    from .run import run_case

    stream = root_stream(stream or sys.stdout)
    folder = Path(folder or Path(case.output.folder) / "sliding_comparison")
    for model in ("small", "large"):
        on_root(lambda model=model: check_results_folder(folder / model, overwrite))
    kind = kind_of(case)  # resolved once, carried into both runs
    results = {}
    for model in ("small", "large"):
        print(f"--- contact model: {model} sliding ---", file=stream, flush=True)
        variant = replace(case, contact=replace(case.contact, model=model, same_layer="off"))
        results[model] = run_case(variant, folder / model, stream, overwrite, kind=kind)
        if results[model].interrupted:
            raise KeyboardInterrupt
    small, large = results["small"], results["large"]
    n_layers = len(case.cable.layers)
    targets = [c * kind.amplitude(case) for c in case.load.cycle]
    lines = [
        f"{case.cable.name}, L = {case.mesh.length:g} m, tension {case.load.tension / 1e3:g} kN, "
        f"{kind.parameter} cycle {targets} {kind.unit}; same-layer contact off in both",
        "model  steps  cuts  Newton its  time s  s/it  contact s  δ at peak mm  δ back at P = 0 mm",
    ]
    for model, r in results.items():
        peak = r.peak_step
        zero = ", ".join(f"{1e3 * s.state.deflection:+.3f}" for s in r.unloaded_steps)
        its = r.iterations
        lines.append(
            f"{model:6s} {len(r.steps):5d} {sum(s.cuts for s in r.steps):5d} {its:11d} "
            f"{r.seconds:7.1f} {r.seconds / max(its, 1):5.2f} {r.timings.get('terms', 0.0):10.1f} "
            f"{1e3 * peak.state.deflection if peak else float('nan'):13.3f}  {zero or '-'}"
        )
        if r.failure:
            lines.append(f"       FAILED: {r.failure}")
    if small.peak is not None and large.peak is not None:
        lines += [
            "wire axial forces at the largest lateral load (large − small):",
            difference_table(small.peak, large.peak, n_layers),
            f"speed ratio (large / small wall time): {large.seconds / small.seconds:.2f}",
        ]
        if case.output.plots and is_root():
            path = overlay_figure(
                small.peak,
                large.peak,
                n_layers,
                f"{case.cable.name}, L = {case.mesh.length:g} m: wire axial forces at the "
                "largest lateral load",
                folder / "sliding_comparison.png",
            )
            lines.append(f"figure: {path}")
    text = "\n".join(lines) + "\n"
    if is_root():
        folder.mkdir(parents=True, exist_ok=True)
        (folder / "comparison.txt").write_text(text)
    print(text, file=stream, flush=True)
    return text
