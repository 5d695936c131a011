"""The contact settings of a strand: the case file's ``[contact]`` section (SI units).

They choose the contact normal (``strand.contact.element.resolve_normal``), the laws of the pairs
(``strand.model.strand_contact.pair_laws``) and small or large sliding
(``strand.model.strand_contact``).
"""

from __future__ import annotations

from dataclasses import KW_ONLY, dataclass, fields

from ..beam.setting import SettingError, check_declared, setting
from ..cable.description import CableError
from ..contact.element import SLIP, resolve_normal
from ..contact.kinematics import NORMALS
from .compliances import PENALTY_SETTINGS, compliance_named, compliances
from .layer_states import FIRST_LAYER, SAME_LAYER, SAME_LAYER_STENCILS

__all__ = ["ContactSettings"]


@dataclass(frozen=True)
class ContactSettings:
    """Contact model settings (SI units), each declared with its meaning (``setting``)."""

    normal: str = setting(
        "auto",
        "The contact normal: auto (director with friction, frozen without), neighbour, "
        "director or frozen. "
        '"director" (the seed paper\'s: rotated nodal tangents), "neighbour" (translation-only, '
        'from neighbour chords), "frozen" (initial radial normal), or "auto": "director" with '
        'friction, "frozen" without. With friction the two geometry-following normals converge '
        'alike and give the same gaps (Cardinal, 4.3 kN: max error 3.7 vs 3.4 µm); "director" '
        "keeps 2-node stencils, so its LU is 1.6× cheaper. A frictionless strand has near-zero-"
        "energy modes (wires rolling around the layer below) that only the frozen normal's "
        "spurious stiffness holds; its gaps are then only approximate in bending (by how much: "
        'docs/benchmarks.md, "Contact normals"). See ``strand.contact.kinematics``.',
        choices=("auto", *NORMALS),
    )
    compliance: str = setting(
        "hertz",
        "The contact laws of the pairs: hertz (from the wires), penalty (the seed paper's), "
        "hertz_microslip, or another registered one. "
        '"hertz" (contact mechanics from the wires\' radii and moduli and the current normal '
        "force: Hertz crossed cylinders at the crossing angle and Hertz line contact core | "
        "layer 1 for the normal, Mindlin's initial stiffness for the stick; "
        '``strand.contact.hertz``) or "penalty" (the seed paper\'s: a penalty K_N, and friction '
        'reaching μP after an elastic slip g_lim), or "hertz_microslip" ("hertz" with '
        "Mindlin–Deresiewicz's microslip from Mindlin's stick to gross slip, without a kink: "
        "``strand.contact.microslip``), or another registered one "
        "(``strand.model.compliances.register_compliance``). k_point, k_line and g_lim apply "
        'to "penalty" (and any compliance registered as using them) only. The default has no '
        "free parameter: every stiffness follows from the wires.",
        choices=compliances,
    )
    k_point: float = setting(
        5e7, "Penalty stiffness of a crossing (5e4 N/mm); penalty only.", unit="N/m"
    )
    k_line: float = setting(
        5e9,
        "Penalty of the core | layer-1 line contact per metre of layer-1 wire; penalty only: "
        "each line pair gets k_line × its tributary length.",
        unit="N/m²",
    )
    g_lim: float = setting(
        5e-6,
        "Elastic slip at which friction reaches μP (K_T = μP/g_lim); penalty only.",
        unit="m",
    )
    friction: bool = setting(
        True, "Use the Coulomb coefficients of the cable (false: frictionless)."
    )
    model: str = setting(
        "small",
        '"small" sliding (pairs fixed at t = 0, ``strand.contact.element``) or "large" sliding '
        "(pairs re-projected at every iteration, ``strand.contact.sliding``: the baseline).",
        choices=("small", "large"),
    )
    reach: float = setting(
        1e-3,
        "Large sliding only: sliding distance reserved either side of each initial pair (its "
        "window holds every segment of the two wires within reach).",
        unit="m",
    )
    same_layer: str = setting(
        "auto",
        "Contact between neighbouring wires of one layer: auto (packed), packed, nominal, "
        "random or off. "
        "``strand.model.same_layer``: "
        '"off", or how stranding spreads a layer\'s spare circumference over its gaps: '
        '"nominal" (evenly: each gap the one its helices give), "packed" (bunched: neighbours '
        "touching, the spare circumference in one gap, as stranding leaves a layer whose "
        'nominal gaps are of the order of its wires\' diameter tolerance), "random" (split at '
        'random from ``gap_seed``), or "auto": "packed". A layer whose helices would overlap '
        "touches all round whatever the choice. In large sliding each facing point is re-found "
        "on the neighbour's centreline within the sliding reach.",
        choices=("auto", *SAME_LAYER),
    )
    same_layer_stencil: str = setting(
        "segment",
        "The nodes a same-layer pair ties: segment, node (a cheaper LU) or facing "
        "(experimental). "
        "In small sliding (``strand.model.same_layer``): "
        '"segment" (node a to the facing point of the neighbour\'s segment [b₀, b₁]) or "node" '
        "(node a to the neighbour's nearest node c, the gap across c's director tangent and "
        "the slip at the facing point, carried by c: two nodes a pair, as the crossings, so "
        "each LU of 1 m of Cardinal takes 2.9e10 operations instead of 5.3e10 and the main "
        "job's window 0.7 of the time; its results differ from the default's by one to twenty "
        'times the mesh error, ``benchmarks/stencils.py``), or "facing" (small sliding only: '
        "facing stations, every wire of a layer meshed so that each station a of wire j has a "
        "node c of wire j + 1 exactly where it faces it, at z + δ of the layer, the closest "
        "points of the two helices: two nodes a pair, no offset, the gap across c's director "
        "tangent; wire 0 carries the receivers of the last wire's stations too; 1 m of "
        "Cardinal has 28.7k nodes instead of 21.6k and an LU 0.69 of the default's time; "
        'docs/theory.md §3.4). "facing" is experimental: 1 m of Cardinal with packed layers '
        "does not tension past 1 kN with it, and on the 1+6 it moves the core's contact force "
        "by 3.3 % (design notes, 2026-11-29). Large sliding re-finds facing points on the "
        'centreline; "facing" is refused there.',
        choices=SAME_LAYER_STENCILS,
    )
    slip: str = setting(
        "surface",
        "Friction's slip: of the surface points, or (the seed paper's) of the centre lines. "
        "Between layers (``strand.contact.element``, in large "
        'sliding ``strand.contact.sliding_slip``): "surface" (the relative motion of the two '
        "surface points in contact: a wire rolls on its neighbour without slip) or "
        "\"centreline\" (the seed paper's: the motion of the centre lines' closest points, "
        'blind to a wire\'s spin: rolling is slip). Same-layer pairs take "surface".',
        choices=SLIP,
    )
    _: KW_ONLY
    gap_seed: int = setting(
        0, 'The seed of "random" gaps (the same seed, the same gaps).', sign="count"
    )
    first_layer: str = setting(
        "on_core",
        "A first layer whose helices overlap (a closed ring): on_core (on the core too) or "
        "ring (a vault off the core). "
        "It sits there when its helices would overlap (a closed ring, as "
        'Cardinal\'s steel layer): "on_core" (on the core too, as on a king wire that just '
        'fits) or "ring" (a vault standing off the core, whose line pairs start open by '
        "``layer_states.ring_lift``).",
        choices=FIRST_LAYER,
    )

    @property
    def facing_stations(self) -> bool:
        """Whether the strand's wires carry facing stations (``cable.geometry.build_geometry``'s
        ``facing``): with same-layer contact on the "facing" stencil."""
        return self.same_layer_stencil == "facing" and self.same_layer != "off"

    def __post_init__(self):
        try:
            check_declared(self, "contact ")
        except SettingError as e:  # strand.app.case reports CableError as a [contact] error
            raise CableError(str(e)) from None
        object.__setattr__(self, "normal", resolve_normal(self.normal, self.friction))
        if self.same_layer == "auto":
            object.__setattr__(self, "same_layer", "packed")
        if self.same_layer_stencil == "facing" and self.model == "large":
            raise CableError(
                'contact same_layer_stencil = "facing" is for small sliding: large sliding '
                "re-finds each facing point on the neighbour's centreline at every iteration, "
                'so its pairs cannot stay on fixed stations; use "segment" with model = "large"'
            )
        uses = compliance_named(self.compliance).uses
        defaults = {f.name: f.default for f in fields(self)}
        given = [n for n in PENALTY_SETTINGS if n not in uses and getattr(self, n) != defaults[n]]
        if given:
            users = [f'"{c}"' for c in compliances() if set(given) <= set(compliance_named(c).uses)]
            raise CableError(
                f"contact {', '.join(given)} apply to compliance = {' or '.join(users)} only "
                f"(the {self.compliance} compliance does not read them); set one or the other"
            )
