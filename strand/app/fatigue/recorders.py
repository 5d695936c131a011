"""The fatigue histories' recorders: per contact pair and per wire section, at the tensioned state
and every step of the cycle, what the fatigue report (``strand.app.fatigue.report``) reads
(``strand.app.history`` files). Units: SI, as the history files name them."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..step_records import RunStep, StepContext

__all__ = ["PairHistory", "WireSectionHistory"]


class _CycleHistory:
    """A history file whose first step is the tensioned state (the last step before the cycle),
    then every step of the cycle: the reference that slips and energies are counted from."""

    def __init__(self, parameter: str):
        self.parameter = parameter  # the cycle's load parameter, written with every step
        #: (RunStep, arrays, load) of the latest tension step
        self._tensioned: tuple[RunStep, dict, float] | None = None
        self.started = False

    def _arrays(self, ctx: StepContext) -> dict:
        raise NotImplementedError

    def record(self, ctx: StepContext) -> None:
        load = ctx.problem.setup.get(self.parameter)
        if not ctx.cycle:
            self._tensioned = (ctx.step, self._arrays(ctx), load)
        else:
            if not self.started:
                self.started = True
                if self._tensioned is not None:
                    self._write(*self._tensioned)
            self._write(ctx.step, self._arrays(ctx), load)

    def _write(self, step: RunStep, arrays: dict, load: float) -> None:
        self.writer.write(step.number, step.time, arrays, load=load)


class PairHistory(_CycleHistory):
    """``contact_pairs.h5`` (``strand.app.history``) and ``contact_points.xdmf`` (its ParaView
    series): per contact pair, at the tensioned state and every cycle step, the contact point,
    normal force (N), friction force vector (N, on the inner wire a; the outer one b takes its
    opposite), gap (m), state (0 open, 1 stick, 2 slip), and since the start of the cycle: the
    relative displacement of the surface points ``slip`` and its Coulomb part ``sliding`` (vectors,
    m) and the energy friction dissipated ``work`` (J). Static: the pair's wires, interface, kind
    (1: line), initial z (m) and angle φ about the axis (deg, from the x axis), crossing angle
    (deg), tributary length and radii (m)."""

    def __init__(self, folder: Path, model, parameter: str):
        super().__init__(parameter)
        from ...cable.geometry import LINE
        from ...contact.pairs import crossing_angle
        from ...model.strand_contact import wire_neighbours
        from ..history import HistoryWriter

        g, p = model.geometry, model.geometry.pairs
        self.model, self.a, self.b = model, p.a, p.b
        self.r_a, self.r_b = p.radius_a, p.radius_b
        x0 = 0.5 * (g.points[p.a] + g.points[p.b])
        tangents = np.stack(
            [
                g.points[nxt] - g.points[prev]
                for prev, nxt in (wire_neighbours(g, p.a), wire_neighbours(g, p.b))
            ],
            axis=1,
        )
        tangents /= np.linalg.norm(tangents, axis=2)[..., None]
        static = {
            "vertex": np.arange(len(p.a), dtype=np.int32)[:, None],
            "wire_a": g.point_wire[p.a],
            "wire_b": g.point_wire[p.b],
            "interface": p.interface,
            "line": (p.kind == LINE).astype(np.int8),
            "z": x0[:, 2],
            "angle": np.degrees(np.arctan2(x0[:, 1], x0[:, 0])),
            "crossing_angle": np.degrees(crossing_angle(tangents)),
            "tributary": p.tributary,
            "radius_a": p.radius_a,
            "radius_b": p.radius_b,
        }
        self.folder = Path(folder)
        self.writer = HistoryWriter(self.folder / "contact_pairs.h5", static, kind="contact pairs")
        self._origin = None

    def _arrays(self, ctx: StepContext) -> dict:
        r = ctx.pairs
        x = self.model.positions()
        point = x[self.a] + (self.r_a + 0.5 * r.gap)[:, None] * r.normal
        state = np.where(r.force > 0, np.where(r.slipping, 2, 1), 0).astype(np.int8)
        return {
            "position": point,
            "force": r.force,
            "friction": r.friction,
            "gap": r.gap,
            "state": state,
            "slip": r.slip,
            "sliding": r.sliding,
            "work": r.work,
        }

    def _write(self, step: RunStep, arrays: dict, load: float) -> None:
        from ..history import write_points_xdmf

        if self._origin is None:  # the start of the cycle: slips and work count from here
            self._origin = {k: arrays[k].copy() for k in ("slip", "sliding", "work")}
        arrays = dict(arrays, **{k: arrays[k] - v for k, v in self._origin.items()})
        super()._write(step, arrays, load)
        if self.writer.file is not None:  # the rank that writes (rank 0)
            write_points_xdmf(self.folder / "contact_points.xdmf", self.writer)

    def close(self) -> None:
        self.writer.close()


class WireSectionHistory(_CycleHistory):
    """``wire_sections.h5`` (``strand.app.history``): per element, at the tensioned state and every
    cycle step, the axial force N (N), the bending moments M₁, M₂ (N m) about e₁ (the strand's
    outward radius; the load direction for the core) and e₂ = t × e₁, and the torque T = m·t
    (N m, about the current tangent t): what surface stresses follow from
    (``strand.fatigue.stress``); the spin θ·t (rad, the section's rotation about t: its nodes'
    mean rotation vector projected on t, ``cell_results.section_spin``), the displacement of the
    core's nodes ``core_u`` (m), and ``midspan_force`` (3,): the force resultant Σ n (N; the
    wires' spatial section forces, axial and shear) of the cross-section z = L/2
    (``cell_results.section_resultants``), whose z component is the strand's tension there. Static: wire, layer, initial z (m), angle φ (deg, as
    ``axial_forces.csv``), wire diameter (m), and the core nodes' initial z ``core_z``."""

    def __init__(self, folder: Path, model, cells_now, direction, parameter: str):
        super().__init__(parameter)
        from ..history import HistoryWriter

        g = model.geometry
        diameters = np.array([lay.wire.diameter for lay in g.cable.layers])
        self.direction = np.asarray(direction, float)
        self.model, self.core = model, model.core_points()
        static = {
            "wire": g.cell_wire,
            "layer": g.cell_layer,
            "z": cells_now.z,
            "phi": cells_now.phi,
            "diameter": diameters[g.cell_layer],
            "core_z": g.points[self.core, 2],
        }
        self.writer = HistoryWriter(Path(folder) / "wire_sections.h5", static, kind="wire sections")

    def _arrays(self, ctx: StepContext) -> dict:
        from ...fatigue.stress import section_components, section_frames
        from ...model.cell_results import section_resultants

        c = ctx.cells
        e1, e2 = section_frames(c.tangent, c.radial, fallback=self.direction)
        m = section_components(c.moment, c.tangent, e1, e2)
        u = self.model.positions()[self.core] - self.model.geometry.points[self.core]
        midspan = section_resultants(self.model, c, self.model.geometry.length / 2)[1]
        return {
            "axial": c.axial,
            "m1": m[:, 0],
            "m2": m[:, 1],
            "torque": c.torque,
            "spin": c.spin,
            "core_u": u,
            "midspan_force": midspan,
        }

    def close(self) -> None:
        self.writer.close()
