"""Figures of a run (matplotlib): the wires' axial forces, the set-up kind's own figures and the
deformed strand (``strand.app.deformed_picture``), and how every figure of a run is saved
(``save_figure``, with the note of a run that stopped early). The fatigue report's figures:
``strand.app.fatigue.figures``."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from .deformed_picture import deformed_picture

__all__ = ["results_figures", "save_figure", "incomplete_note"]


def results_figures(case, result, problem, kind) -> list[Path]:
    """The run's figures (PNG) in ``result.folder``: axial force along z per layer and sector at
    the largest load (the seed paper's Fig. 3), its change from the tensioned state (Fig. 4), the
    set-up ``kind``'s own (``SetupKind.figures``; the saddle test's load–deflection loop, Fig. 5),
    and the deformed strand coloured by axial force; titles give the largest load as the kind
    names it (``SetupKind.load_text``). Figures whose data the run did not reach are skipped."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from ..model.cell_results import sector_of

    folder = Path(result.folder)
    paths = []
    n_layers = len(case.cable.layers)
    L = case.mesh.length
    cmap = plt.get_cmap("twilight", 8)

    note = incomplete_note(result)

    def save_fig(fig, name, tight=True):
        paths.append(save_figure(fig, folder / name, note, tight))

    peak, base = result.peak, result.tensioned
    at_peak = kind.load_text(result.peak_step.load if result.peak_step is not None else 0.0)
    if peak is not None:
        fig, axes = plt.subplots(n_layers, 1, figsize=(9, 2.2 * n_layers), sharex=True)
        for i, ax in enumerate(np.atleast_1d(axes)):
            m = peak.layer == i
            sec = sector_of(peak.phi[m])
            sc = ax.scatter(
                1e3 * peak.z[m], peak.axial[m], c=sec, cmap=cmap, vmin=-0.5, vmax=7.5, s=3
            )
            ax.set_ylabel(f"{'core' if i == 0 else f'layer {i}'}\nN (N)")
        ax.set_xlabel("z (mm)")
        cb = fig.colorbar(sc, ax=axes, ticks=range(8))
        cb.ax.set_yticklabels([f"{-180 + 45 * k}…{-135 + 45 * k}°" for k in range(8)])
        cb.set_label("sector of φ (90° = stretched fibre)")
        fig.suptitle(f"wire axial forces at {at_peak}, T = {case.load.tension / 1e3:g} kN")
        save_fig(fig, "axial_force_sectors.png", tight=False)

    if peak is not None and base is not None:
        fig, axes = plt.subplots(
            1,
            n_layers - 1,
            sharey=True,
            layout="constrained",
            figsize=(max(3.2 * (n_layers - 1), 6.0) + 1.0, 3.8),
        )
        near = np.abs(peak.z - L / 2) <= 0.1 * L
        for i, ax in enumerate(np.atleast_1d(axes), start=1):
            m = near & (peak.layer == i)
            sc = ax.scatter(
                peak.phi[m],
                peak.axial[m] - base.axial[m],
                s=3,
                c=1e3 * peak.z[m],
                cmap="viridis",
                vmin=1e3 * 0.4 * L,
                vmax=1e3 * 0.6 * L,
            )
            ax.axhline(0, color="k", lw=0.5)
            ax.set_xticks([-180, -90, 0, 90, 180])
            ax.set_title(f"layer {i}")
            ax.set_xlabel("φ (deg), 90° = stretched fibre")
        np.atleast_1d(axes)[0].set_ylabel("ΔN (N)")
        fig.colorbar(sc, ax=axes, label="z (mm)", pad=0.01)
        fig.suptitle(
            f"change of wire axial force from the tensioned state to {at_peak}\n"
            f"(elements within ±{0.1 * L * 1e3:g} mm of midspan)"
        )
        save_fig(fig, "axial_force_change.png", tight=False)

    paths += kind.figures(case, result, note)

    if peak is not None and result.peak_w is not None:
        paths.append(
            deformed_picture(
                case, result, problem, folder / "deformed_axial_force.png", at_peak, note
            )
        )
    return paths


def save_figure(fig, path: Path, note: str = "", tight: bool = True) -> Path:
    """Lay out ``fig`` (``tight``: tight layout; else its own engine, e.g. constrained for a
    colour bar shared by several axes), with ``note`` in red along the bottom; save and close."""
    import matplotlib.pyplot as plt

    if tight:
        fig.tight_layout(rect=(0, 0.04 if note else 0, 1, 1))
    elif note and fig.get_layout_engine() is not None:  # constrained: leave the bottom free
        fig.get_layout_engine().set(rect=(0, 0.05, 1, 0.95))
    if note:
        fig.text(0.5, 0.005, note, color="tab:red", ha="center", va="bottom", fontsize=9)
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def incomplete_note(result) -> str:
    """The line a figure of a run that stopped early carries ("" for a complete run)."""
    if not result.failure:
        return ""
    how = "was interrupted" if result.interrupted else "stopped early (a load step failed)"
    return f"INCOMPLETE: the run {how} after step {len(result.steps)}; see summary.txt"
