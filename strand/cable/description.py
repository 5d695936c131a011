"""Cable descriptions: a core wire and layers of helical wires, as a cable engineer gives them.

SI units: diameters in m, moduli and stresses in Pa, lay angles in degrees (measured from the strand
axis); a modulus under 1 GPa (``MIN_MODULUS``: one given in GPa, E = 210) is refused. A wire may
give its ``yield_stress`` (optional): a run then warns when a wire's axial stress exceeds it; its
``tensile_strength`` σ_u (optional): the fatigue report's mean-stress correction needs it
(``strand.fatigue.meanstress``); and its beam's ``shear_coefficient`` κ and
``torsional_stiffness`` GJ (N m²), optional too, which otherwise come from ν and the round
section (``forms.CircularSection``).
A description comes from a TOML file (see ``strand/cable/data/cardinal.toml``) or a dict; every
field is checked and errors name the field (``CableError``).
"""

from __future__ import annotations

import math
import tomllib
from collections.abc import Set as AbstractSet
from dataclasses import dataclass
from importlib import resources
from pathlib import Path

from .input_file import read_text

__all__ = [
    "CableError",
    "Wire",
    "Layer",
    "Cable",
    "load_cable",
    "built_in_cables",
    "built_in_cable",
    "cardinal",
    "judge120",
    "CORE_KEYS",
    "LAYER_KEYS",
    "WIRE_OPTIONS",
]


class CableError(ValueError):
    """A cable description that cannot be built; the message names the offending field."""


@dataclass(frozen=True)
class Wire:
    """Material and size of the wires of one layer."""

    diameter: float  # m
    E: float  # Pa
    nu: float  # -
    yield_stress: float | None = None  # Pa; a run warns when a wire's axial stress exceeds it
    shear_coefficient: float | None = None  # κ of κGA, in (0, 10); default 6(1+ν)/(7+6ν)
    torsional_stiffness: float | None = None  # N m², a wire's GJ, > 0; default G πd⁴/32
    tensile_strength: float | None = None  # Pa, σ_u; the fatigue mean-stress correction needs it

    @property
    def area(self) -> float:
        return math.pi * self.diameter**2 / 4


@dataclass(frozen=True)
class Layer:
    """A layer of ``wires`` identical helical wires (the core is layer 0: one straight wire)."""

    wires: int
    wire: Wire
    lay_angle: float  # degrees from the strand axis; 0 for the core
    lay: str  # "S" (left hand) or "Z" (right hand); "-" for the core
    friction: float  # Coulomb coefficient with the next layer out
    radius: float = 0.0  # m, helix radius of the wire centres (set by Cable)

    @property
    def hand(self) -> int:
        """+1 right hand (Z), −1 left hand (S), 0 straight."""
        return {"Z": 1, "S": -1}.get(self.lay, 0)

    @property
    def alpha(self) -> float:
        """Lay angle in rad."""
        return math.radians(self.lay_angle)

    @property
    def angular_rate(self) -> float:
        """dφ/dz of the wire centres (rad/m), signed by the hand."""
        return 0.0 if self.radius == 0 else self.hand * math.tan(self.alpha) / self.radius

    @property
    def pitch(self) -> float:
        """Lay length (m); inf for the core."""
        return math.inf if self.angular_rate == 0 else 2 * math.pi / abs(self.angular_rate)

    @property
    def fill(self) -> float:
        """Circumferential fill n d / (2π r cosα): the wires of a layer overlap when ≥ 1."""
        if self.radius == 0:
            return 0.0
        return self.wires * self.wire.diameter / (2 * math.pi * self.radius * math.cos(self.alpha))


@dataclass(frozen=True)
class Cable:
    name: str
    layers: tuple[Layer, ...]  # layers[0] is the core

    @property
    def outer_diameter(self) -> float:
        top = self.layers[-1]
        return 2 * top.radius + top.wire.diameter

    @property
    def largest_wire_diameter(self) -> float:
        """The thickest wire's diameter (m)."""
        return max(lay.wire.diameter for lay in self.layers)

    @property
    def n_wires(self) -> int:
        return sum(lay.wires for lay in self.layers)


#: optional fields of a wire (core or layer), None when not given
WIRE_OPTIONS = ("yield_stress", "tensile_strength", "shear_coefficient", "torsional_stiffness")
#: the fields of the core's table and of a layer's
CORE_KEYS = frozenset({"diameter", "E", "nu", "friction", *WIRE_OPTIONS})
LAYER_KEYS = frozenset(
    {"wires", "diameter", "E", "nu", "lay_angle", "lay", "friction", *WIRE_OPTIONS}
)


#: the unit of each number of a core's or a layer's table, as error messages give it
UNITS = {
    "diameter": "m",
    "E": "Pa",
    "nu": "",
    "yield_stress": "Pa",
    "shear_coefficient": "",
    "torsional_stiffness": "N m²",
    "tensile_strength": "Pa",
    "lay_angle": "°",
    "friction": "",
}


def _number(d: dict, key: str, where: str, low: float, high: float = math.inf, closed_low=False):
    if key not in d:
        raise CableError(f"{where}: missing field '{key}'")
    v = d[key]
    if isinstance(v, bool) or not isinstance(v, (int, float)):
        raise CableError(f"{where}.{key}: expected a number, got {v!r}")
    ok = (v >= low if closed_low else v > low) and v < high
    if not ok:
        unit = UNITS[key]
        if unit == "°":
            value, bounds = f"{v:g}°", f"{'[' if closed_low else '('}{low:g}°, {high:g}°)"
        else:
            unit = f" {unit}" if unit else ""
            value, bounds = f"{v:g}{unit}", f"{'[' if closed_low else '('}{low:g}, {high:g}){unit}"
        raise CableError(f"{where}.{key} = {value} is out of range {bounds}")
    return float(v)


#: the smallest modulus a wire may have (Pa): no metal's is under 1 GPa, and a modulus given in
#: GPa or MPa, read as Pa, is (E = 210 for 210 GPa)
MIN_MODULUS = 1e9


def _modulus(d: dict, where: str) -> float:
    """The wire's E (Pa), refused under ``MIN_MODULUS`` with the value it was likely meant as."""
    E = _number(d, "E", where, 0.0)
    if E >= MIN_MODULUS:
        return E
    meant = next((f"{E:g}{e}" for e, k in (("e9", 1e9), ("e6", 1e6)) if 1e9 <= E * k < 1e12), "")
    hint = f"did you mean {meant}? " if meant else ""
    raise CableError(
        f"{where}.E = {E:g} Pa: {hint}A wire's modulus is given in Pa, and none is under 1 GPa"
    )


#: the open range of each optional field of a wire
WIRE_OPTION_RANGES = {
    "yield_stress": (0.0, math.inf),
    "tensile_strength": (0.0, math.inf),
    "shear_coefficient": (0.0, 10.0),
    "torsional_stiffness": (0.0, math.inf),
}


def _wire(d: dict, where: str) -> Wire:
    options = {
        key: _number(d, key, where, *WIRE_OPTION_RANGES[key]) if key in d else None
        for key in WIRE_OPTIONS
    }
    return Wire(
        diameter=_number(d, "diameter", where, 0.0, 1.0),
        E=_modulus(d, where),
        nu=_number(d, "nu", where, -1.0, 0.5),
        **options,
    )


def _check_keys(d: object, allowed: AbstractSet[str], where: str) -> None:
    if not isinstance(d, dict):
        raise CableError(f"{where}: expected a table, got {type(d).__name__}")
    unknown = sorted(set(d) - allowed)
    if unknown:
        raise CableError(f"{where}: unknown field(s) {unknown}; allowed: {sorted(allowed)}")


def cable_from_dict(data: dict) -> Cable:
    """Build and check a ``Cable`` from the TOML structure (name, [core], [[layer]])."""
    _check_keys(data, {"name", "core", "layer"}, "cable")
    if "core" not in data:
        raise CableError("cable: missing table [core]")
    layers_in = data.get("layer", [])
    if not isinstance(layers_in, list) or not layers_in:
        raise CableError("cable: at least one [[layer]] of helical wires is needed")
    core = data["core"]
    _check_keys(core, CORE_KEYS, "core")
    layers = [
        Layer(1, _wire(core, "core"), 0.0, "-", _number(core, "friction", "core", 0.0, 10, True))
    ]
    radius = 0.0
    previous = layers[0].wire.diameter
    for i, lay in enumerate(layers_in, start=1):
        where = f"layer[{i}]"
        _check_keys(lay, LAYER_KEYS, where)
        wire = _wire(lay, where)
        if "wires" not in lay:
            raise CableError(f"{where}: missing field 'wires'")
        n = lay["wires"]
        if isinstance(n, bool) or not isinstance(n, int) or n < 1:
            raise CableError(f"{where}.wires = {n!r}: expected a positive whole number")
        angle = _number(lay, "lay_angle", where, 0.0, 45.0)
        if lay.get("lay") not in ("S", "Z"):
            raise CableError(
                f"{where}.lay = {lay.get('lay')!r}: expected 'S' (left) or 'Z' (right)"
            )
        radius += (previous + wire.diameter) / 2
        previous = wire.diameter
        layer = Layer(
            n, wire, angle, lay["lay"], _number(lay, "friction", where, 0.0, 10, True), radius
        )
        if layer.fill >= 1.0:
            raise CableError(
                f"{where}: its {n} wires of {wire.diameter * 1e3:g} mm at lay angle {angle:g}° "
                f"overlap on radius {radius * 1e3:.3f} mm (circumferential fill {layer.fill:.3f} "
                "≥ 1): use fewer or thinner wires"
            )
        layers.append(layer)
    name = data.get("name", "cable")
    if not isinstance(name, str):
        raise CableError("cable.name: expected a string")
    return Cable(name, tuple(layers))


def load_cable(path: str | Path) -> Cable:
    """Read a cable description from a TOML file."""
    path = Path(path)
    text = read_text(path, "cable file (TOML)", CableError)
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as e:
        raise CableError(f"{path}: not valid TOML ({e})") from None
    try:
        return cable_from_dict(data)
    except CableError as e:
        raise CableError(f"{path}: {e}") from None


def built_in_cables() -> tuple[str, ...]:
    """The names of strand's built-in cables, sorted: one per file ``<name>.toml`` of
    ``strand/cable/data``, so that a new file there is a new built-in cable."""
    files = resources.files("strand.cable.data").iterdir()
    return tuple(sorted(f.name.removesuffix(".toml") for f in files if f.name.endswith(".toml")))


def built_in_cable(name: str) -> Cable:
    """The built-in cable ``name`` (any case; ``built_in_cables``); ``CableError`` naming the
    built-in ones for another name."""
    names = built_in_cables()
    if name.lower() not in names:
        raise CableError(f"no built-in cable {name!r}; the built-in cables: {', '.join(names)}")
    return _built_in(f"{name.lower()}.toml")


def _built_in(file: str) -> Cable:
    return cable_from_dict(
        tomllib.loads(resources.files("strand.cable.data").joinpath(file).read_text())
    )


def cardinal() -> Cable:
    """Cardinal ACSR 54/7 (1 + 6 steel, 12/18/24 aluminium), the seed paper's conductor."""
    return _built_in("cardinal.toml")


def judge120() -> Cable:
    """A 120-wire all-steel spiral strand of 61 mm (1 + 7 + 17 + 14 + 21 + 27 + 33), Judge et al.
    (2012); its sources and assumptions are in ``strand/cable/data/judge120.toml``."""
    return _built_in("judge120.toml")
