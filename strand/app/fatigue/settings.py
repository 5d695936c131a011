"""The ``[fatigue]`` section of a case: which fatigue outputs a run writes and the curves, mean
stress law and design factor they are assessed against (``strand.app.fatigue.report``). Every
setting is declared once, on its field (``strand.beam.setting.setting``)."""

from __future__ import annotations

from dataclasses import dataclass

from ...beam.setting import setting
from ...cable.description import Cable
from ..setting_readers import _SPECTRUM, _spectrum

__all__ = ["FatigueSettings", "USER_CURVE_LEVELS"]


def _sn_curves() -> tuple[str, ...]:
    from ...fatigue.sn import SN_CURVES

    return (*SN_CURVES, "custom", "user")


def _steel_sn_curves() -> tuple[str, ...]:
    from ...fatigue.sn import SN_CURVES

    return (*SN_CURVES, "user", "none")


def _mean_stress_laws() -> tuple[str, ...]:
    from ...fatigue.meanstress import MEAN_STRESS_LAWS

    return MEAN_STRESS_LAWS


#: ``[fatigue] user_sn_given``, ``user_sn_use``: the user curve as given and as assessed
USER_CURVE_LEVELS = ("characteristic", "mean")


@dataclass(frozen=True, kw_only=True)
class FatigueSettings:
    """The fatigue outputs and the curves they are assessed against."""

    outputs: bool = setting(
        True, "Contact pair and wire section histories, and the fatigue report."
    )
    sn_curve: str = setting(
        "cigre-sbl-multilayer",
        'A built-in curve (``strand.fatigue.SN_CURVES``), or "custom" with σ_a = sn_A N^sn_b '
        '(MPa) up to sn_knee cycles, sn_A2 N^sn_b2 beyond, or "user" (user_sn_*).',
        choices=_sn_curves,
    )
    sn_A: float = setting(450.0, "Custom: σ_a = A N^b up to the knee.", unit="MPa")
    sn_b: float = setting(-0.2, "Custom: the exponent b up to the knee.", sign="any")
    sn_knee: float = setting(2e7, "Custom: the knee.", unit="cycles")
    sn_A2: float = setting(263.0, "Custom: σ_a = A2 N^b2 beyond the knee.", unit="MPa")
    sn_b2: float = setting(-0.17, "Custom: the exponent b2 beyond the knee.", sign="any")
    sn_layers: tuple[float, ...] = setting(
        (),
        "Layers (0 = core) the curve applies to; [] = those with E < 100 GPa.",
        schema={"type": "array", "items": {"type": "integer", "minimum": 0}},
    )
    steel_sn_curve: str = setting(
        "en1992-prestressing-steel",
        'The other steel wires\' (E ≥ 100 GPa) curve, or "en1992-steel-duct" (fretting), '
        '"user", or "none": not assessed.',
        choices=_steel_sn_curves,
    )
    user_sn_m1: float = setting(
        0.0,
        'A user\'s own curve (sn_curve or steel_sn_curve = "user"), N = a1 Δσ^-m1 (Δσ the range '
        "in MPa): its slope to the knee (required).",
        sign="zero_is_off",
    )
    user_sn_m2: float = setting(
        0.0,
        "The user curve's slope beyond the knee, continuous there; 0: m1 throughout.",
        sign="zero_is_off",
    )
    user_sn_log_a: float = setting(
        0.0,
        "The user curve's intercept log10 a1 (Δσ in MPa); 0: user_sn_range instead.",
        sign="zero_is_off",
    )
    user_sn_range: float = setting(
        0.0,
        "Or the user curve's intercept as the range Δσ0 at user_sn_cycles (instead of "
        "user_sn_log_a).",
        unit="Pa",
        sign="zero_is_off",
    )
    user_sn_cycles: float = setting(2e6, "Cycles at which user_sn_range is given.", unit="cycles")
    user_sn_knee: float = setting(
        1e7, "Cycles where the user curve's slope turns from m1 to m2.", unit="cycles"
    )
    user_sn_given: str = setting(
        "characteristic",
        "The user curve as given: characteristic or mean.",
        choices=USER_CURVE_LEVELS,
    )
    user_sn_use: str = setting(
        "characteristic",
        "The user curve assessed with: characteristic or mean.",
        choices=USER_CURVE_LEVELS,
    )
    user_sn_sd: float = setting(
        0.0,
        "Standard deviation of log10 N: the characteristic curve lies two of them below the "
        "mean (needed where use and given differ).",
        sign="zero_is_off",
    )
    user_sn_mean: float = setting(
        0.0,
        "The mean stress of the user curve's tests (0: fully reversed).",
        unit="Pa",
        sign="zero_is_off",
    )
    mean_stress: str = setting(
        "none",
        "Wire-level mean-stress correction: none, goodman, gerber or swt (with the wires' "
        "tensile_strength); none: the built-in curves come from tensioned tests "
        "(docs/fatigue.md).",
        choices=_mean_stress_laws,
    )
    design_fatigue_factor: float = setting(
        1.0,
        "DFF: every damage, wire-level and T–N, is the Miner sum × DFF (lives ÷ DFF); 1: none; "
        "the standards' values: docs/fatigue.md.",
    )
    surface_points: int = setting(
        16, "Points around each wire's circumference (ranges within 2 %)."
    )
    clamp_distance: float = setting(
        0.089, "Poffenberger–Swart's distance from the clamp (3.5 in).", unit="m"
    )
    end_zone: float = setting(
        0.0,
        "Clamp zone at each end, reported apart from the free span; 0: half the longest lay "
        "length (how far the ends' lock reaches).",
        unit="m",
        sign="zero_is_off",
    )
    stuck_slip: float = setting(
        1e-9,
        "A pair whose Coulomb slide stays below this stayed stuck throughout.",
        unit="m",
    )
    breaking_strength: float = setting(
        0.0,
        "The strand's minimum breaking strength (MBS) for API RP 2SK's T–N; 0: not given.",
        unit="N",
        sign="zero_is_off",
    )
    spectrum: tuple[tuple[float, float], ...] = setting(
        (),
        "The load spectrum [[amplitude, cycles], ...], run as the sweep: Miner's sum per wire "
        "and pair. It gives the cycles in a period (a year, the design life) at each "
        "amplitude of lateral (N), curvature (1/m) or tension_swing (N); writes spectrum.csv, "
        "spectrum.txt; or "
        "a table [fatigue.spectrum] with classes = [[...], ...], as strand spectrum prints it "
        "(beside [fatigue], no second one).",
        read=_spectrum,
        schema=_SPECTRUM,
    )

    def user_curve(self):
        """The user's own S–N curve (``user_sn_*``; ``strand.fatigue.sn.user_curve``): the one
        ``user_sn_use`` names, moved from the one given by ``CHARACTERISTIC_SDS`` standard
        deviations ``user_sn_sd`` of log10 N where the two differ."""
        from ...fatigue.sn import CHARACTERISTIC_SDS, user_curve

        sign = {"mean": 1, "characteristic": 0}
        shift = (sign[self.user_sn_use] - sign[self.user_sn_given]) * CHARACTERISTIC_SDS
        point = (self.user_sn_range, self.user_sn_cycles) if self.user_sn_range else None
        intercept = (
            f"Δσ = {1e-6 * self.user_sn_range:g} MPa at {self.user_sn_cycles:.3g} cycles"
            if point
            else f"log10 a1 = {self.user_sn_log_a:g} (Δσ in MPa)"
        )
        beyond = f", m2 = {self.user_sn_m2:g} beyond" if self.user_sn_m2 else ""
        moved = (
            f", moved from the {self.user_sn_given} one given by {abs(shift):g} × "
            f"{self.user_sn_sd:g} in log10 N"
            if shift
            else ""
        )
        name = (
            f"user curve ({self.user_sn_use}): N = a1 Δσ^-{self.user_sn_m1:g}, {intercept}, "
            f"knee {self.user_sn_knee:.3g} cycles{beyond}{moved}"
        )
        return user_curve(
            self.user_sn_m1,
            self.user_sn_knee,
            log_a=self.user_sn_log_a,
            point=point,
            m2=self.user_sn_m2,
            shift=shift * self.user_sn_sd,
            name=name,
        )

    def curve(self):
        """The S–N curve these settings name (``strand.fatigue.SNCurve``)."""
        from ...fatigue.sn import SN_CURVES, SNCurve

        if self.sn_curve == "user":
            return self.user_curve()
        if self.sn_curve == "custom":
            return SNCurve(
                "custom (case file)",
                self.sn_A,
                self.sn_b,
                self.sn_knee,
                self.sn_A2,
                self.sn_b2,
                "the case file",
            )
        return SN_CURVES[self.sn_curve]

    def layers(self, cable: Cable) -> list[int]:
        """The layers (0 = core) whose wires the S–N curve applies to."""
        if self.sn_layers:
            return [int(i) for i in self.sn_layers]
        return [i for i, lay in enumerate(cable.layers) if lay.wire.E < 100e9]

    def curves(self, cable: Cable) -> list:
        """Per layer (0 = core), its wires' S–N curve, or None (not assessed): ``sn_curve`` on
        ``layers``, ``steel_sn_curve`` on the other steel layers (E ≥ 100 GPa)."""
        from ...fatigue.sn import SN_CURVES, wire_material

        mine = self.layers(cable)
        steel = (
            self.user_curve()
            if self.steel_sn_curve == "user"
            else SN_CURVES.get(self.steel_sn_curve)
        )
        return [
            self.curve() if i in mine else steel if wire_material(lay.wire.E) == "steel" else None
            for i, lay in enumerate(cable.layers)
        ]

    def uses_user_curve(self) -> bool:
        """Whether ``sn_curve`` or ``steel_sn_curve`` names the user's own curve."""
        return "user" in (self.sn_curve, self.steel_sn_curve)

    def unknown_strength(self, cable: Cable) -> list[int]:
        """The assessed layers (with a curve) whose wires give no tensile strength."""
        return [
            i
            for i, (lay, curve) in enumerate(zip(cable.layers, self.curves(cable), strict=True))
            if curve is not None and lay.wire.tensile_strength is None
        ]

    def mean_stress_corrections(self, cable: Cable) -> list:
        """Per layer (0 = core), its wires' mean-stress correction
        (``strand.fatigue.meanstress.MeanStress``), or None: no ``mean_stress``, or no curve.
        The user's curve is taken at its tests' mean ``user_sn_mean``, the others at zero."""
        from ...fatigue.meanstress import MeanStress

        curves = self.curves(cable)
        if self.mean_stress == "none":
            return [None] * len(curves)
        user = self.user_curve() if self.uses_user_curve() else None
        return [
            None
            if curve is None
            else MeanStress(
                self.mean_stress,
                lay.wire.tensile_strength,
                self.user_sn_mean if curve == user else 0.0,
            )
            for lay, curve in zip(cable.layers, curves, strict=True)
        ]

    def end_zone_length(self, cable: Cable) -> float:
        """The clamp zone's length at each end (m): ``end_zone``, or how far the end sections'
        lock on the wires reaches, half the longest lay length (``strand.fatigue.zones``)."""
        from ...fatigue.zones import lock_reach

        return self.end_zone if self.end_zone > 0 else lock_reach(cable)
