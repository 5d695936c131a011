"""The contact settings of a strand: the case file's ``[contact]`` section (SI units).

They choose the contact normal (``strand.contact.element.resolve_normal``), the laws of the pairs
(``strand.model.strand_contact.pair_laws``) and small or large sliding
(``strand.model.strand_contact``).
"""

from __future__ import annotations

from dataclasses import KW_ONLY, dataclass, fields
from typing import ClassVar

from ..cable.description import CableError
from ..contact.element import check_slip, resolve_normal
from ..contact.errors import ContactError
from .compliances import PENALTY_SETTINGS, compliance_named, compliances
from .layer_states import FIRST_LAYER, SAME_LAYER, SAME_LAYER_STENCILS

__all__ = ["ContactSettings"]


@dataclass(frozen=True)
class ContactSettings:
    """Contact model settings (SI units).

    Attributes:
        normal: "director" (the seed paper's: rotated nodal tangents), "neighbour"
            (translation-only, from neighbour chords), "frozen" (initial radial normal), or
            "auto" (default): "director" with friction, "frozen" without. With friction the two
            geometry-following normals converge alike and give the same gaps (Cardinal, 4.3 kN:
            max error 3.7 vs 3.4 µm); "director" keeps 2-node stencils, so its LU is 1.6× cheaper.
            A frictionless strand has near-zero-energy modes (wires rolling around the layer
            below) that only the frozen normal's spurious stiffness holds; its gaps are then only
            approximate in bending (by how much: docs/benchmarks.md, "Contact normals"). See
            ``strand.contact.kinematics``.
        compliance: "hertz" (default: contact mechanics from the wires' radii and moduli and the
            current normal force: Hertz crossed cylinders at the crossing angle and Hertz line
            contact core | layer 1 for the normal, Mindlin's initial stiffness for the stick;
            ``strand.contact.hertz``) or "penalty" (the seed paper's: a penalty K_N, and friction
            reaching μP after an elastic slip g_lim), or "hertz_microslip" ("hertz" with
            Mindlin–Deresiewicz's microslip from Mindlin's stick to gross slip, without a kink:
            ``strand.contact.microslip``), or another registered one
            (``strand.model.compliances.register_compliance``). k_point, k_line and g_lim apply
            to "penalty" (and any compliance registered as using them) only. The default has no
            free parameter: every stiffness follows from the wires.
        k_point: penalty stiffness of a crossing, N/m (5e4 N/mm).
        k_line: penalty of the core | layer-1 line contact per metre of layer-1 wire, N/m²; each
            line pair gets k_line × its tributary length.
        g_lim: slip at which friction reaches μP (elastic slip, K_T = μP/g_lim), m.
        friction: use the Coulomb coefficients of the cable (False: frictionless).
        model: "small" sliding (pairs fixed at t = 0, ``strand.contact.element``) or "large"
            sliding (pairs re-projected at every iteration, ``strand.contact.sliding``: the
            baseline).
        reach: large sliding only: sliding distance reserved either side of each initial pair,
            m (its window holds every segment of the two wires within reach).
        same_layer: contact between neighbouring wires of one layer (``strand.model.same_layer``):
            "off", or how stranding spreads a layer's spare circumference over its gaps:
            "nominal" (evenly: each gap the one its helices give), "packed" (bunched:
            neighbours touching, the spare circumference in one gap, as stranding leaves a
            layer whose nominal gaps are of the order of its wires' diameter tolerance),
            "random" (split at random from ``gap_seed``), or "auto" (default): "packed". A
            layer whose helices would overlap touches all round whatever the choice. In large
            sliding each facing point is re-found on the neighbour's centreline within the
            sliding reach.
        gap_seed: the seed of "random" gaps (the same seed, the same gaps).
        first_layer: where the first helical layer sits when its helices would overlap (a
            closed ring, as Cardinal's steel layer): "on_core" (default: on the core too, as on
            a king wire that just fits) or "ring" (a vault standing off the core, whose line
            pairs start open by ``layer_states.ring_lift``).
        same_layer_stencil: the nodes a same-layer pair ties in small sliding
            (``strand.model.same_layer``): "segment" (default: node a to the facing point of the
            neighbour's segment [b₀, b₁]) or "node" (node a to the neighbour's nearest node c,
            the gap across c's director tangent and the slip at the facing point, carried by
            c: two nodes a pair, as the crossings, so each LU of 1 m of Cardinal takes 2.9e10
            operations instead of 5.3e10 and the main job's window 0.7 of the time; its results
            differ from the default's by one to twenty times the mesh error,
            ``benchmarks/stencils.py``), or "facing" (small sliding only: facing stations,
            every wire of a layer meshed so that each station a of wire j has a node c of wire
            j + 1 exactly where it faces it, at z + δ of the layer, the closest points of the two
            helices: two nodes a pair, no offset, the gap across c's director tangent; wire 0
            carries the receivers of the last wire's stations too; 1 m of Cardinal has 28.7k
            nodes instead of 21.6k and an LU 0.69 of the default's time; docs/theory.md §3.4).
            "facing" is experimental: 1 m of Cardinal with packed layers does not tension
            past 1 kN with it, and on the 1+6 it moves the core's contact force by 3.3 %
            (design notes, 2026-11-29). Large sliding re-finds facing points on the
            centreline; "facing" is refused there.
        slip: the friction's slip measure between layers (``strand.contact.element``, in large
            sliding ``strand.contact.sliding_slip``): "surface" (the relative motion of the two
            surface points in contact: a wire rolls on its neighbour without slip) or
            "centreline" (the seed paper's: the motion of the centre lines' closest points,
            blind to a wire's spin: rolling is slip). Same-layer pairs take "surface".
    """

    normal: str = "auto"
    compliance: str = "hertz"
    k_point: float = 5e7
    k_line: float = 5e9
    g_lim: float = 5e-6
    friction: bool = True
    model: str = "small"
    reach: float = 1e-3
    same_layer: str = "auto"
    same_layer_stencil: str = "segment"
    slip: str = "surface"
    _: KW_ONLY
    gap_seed: int = 0
    first_layer: str = "on_core"

    #: the SI unit of every number (error messages give it)
    UNITS: ClassVar[dict[str, str]] = {
        "k_point": "N/m",
        "k_line": "N/m²",
        "g_lim": "m",
        "reach": "m",
        "gap_seed": "",
    }

    @property
    def facing_stations(self) -> bool:
        """Whether the strand's wires carry facing stations (``cable.geometry.build_geometry``'s
        ``facing``): with same-layer contact on the "facing" stencil."""
        return self.same_layer_stencil == "facing" and self.same_layer != "off"

    def __post_init__(self):
        try:
            object.__setattr__(self, "normal", resolve_normal(self.normal, self.friction))
            check_slip(self.slip)
        except ContactError as e:  # strand.app.case reports CableError as a [contact] error
            raise CableError(str(e)) from None
        if self.compliance not in compliances():
            *others, last = compliances()
            choices = f"{', '.join(others)} or {last}" if others else last
            raise CableError(f"contact compliance {self.compliance!r} is unknown; choose {choices}")
        if self.model not in ("small", "large"):
            raise CableError(f"contact model {self.model!r} is unknown; choose small or large")
        if self.same_layer == "auto":
            object.__setattr__(self, "same_layer", "packed")
        if self.same_layer not in SAME_LAYER:
            raise CableError(
                f"contact same_layer {self.same_layer!r} is unknown; choose auto, "
                f"{', '.join(SAME_LAYER)}"
            )
        if self.same_layer_stencil not in SAME_LAYER_STENCILS:
            *others, last = SAME_LAYER_STENCILS
            raise CableError(
                f"contact same_layer_stencil {self.same_layer_stencil!r} is unknown; choose "
                f"{', '.join(others)} or {last}"
            )
        if self.same_layer_stencil == "facing" and self.model == "large":
            raise CableError(
                'contact same_layer_stencil = "facing" is for small sliding: large sliding '
                "re-finds each facing point on the neighbour's centreline at every iteration, "
                'so its pairs cannot stay on fixed stations; use "segment" with model = "large"'
            )
        if self.first_layer not in FIRST_LAYER:
            raise CableError(
                f"contact first_layer {self.first_layer!r} is unknown; choose "
                f"{' or '.join(FIRST_LAYER)}"
            )
        if not (isinstance(self.gap_seed, int) and not isinstance(self.gap_seed, bool)) or (
            self.gap_seed < 0
        ):
            raise CableError(f"contact gap_seed = {self.gap_seed!r}: must be a whole number ≥ 0")
        for name in ("k_point", "k_line", "g_lim", "reach"):
            value = getattr(self, name)
            if not (isinstance(value, int | float) and value > 0):
                raise CableError(
                    f"contact {name} = {value!r} {self.UNITS[name]}: must be a positive number"
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
