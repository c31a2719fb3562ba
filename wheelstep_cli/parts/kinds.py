"""Registry of the part kinds a batch can build, and what a printer profile changes in each.

A kind is a part pipeline (``parts/<kind>.py``: Spec dataclass with defaults -> build ->
report) plus the few facts the batch needs: which design-profile section holds its
options, which spec fields are bores (enlarged by the printer's hole compensation),
how extra tooth clearance is added, and cheap checks that can run before building.
Pipelines are imported lazily, so a kind whose module is missing is reported as
"not available" instead of breaking the others.
"""

from __future__ import annotations

import dataclasses
import importlib
import typing
from dataclasses import dataclass
from typing import Any, Callable

from wheelstep_cli.errors import DesignError, require


@dataclass(frozen=True)
class PartKind:
    """How the batch drives one part pipeline; functions are named by module attribute."""

    name: str
    module: str
    spec_class: str
    build: str
    report: str
    section: str                                   # design-profile section with its options
    parts: Callable[[Any], list]                   # built object -> its Parts, in order
    hole_fields: tuple[str, ...] = ()              # bore diameters (mm), enlarged when > 0
    clearance: Callable[[Any, float], dict] = lambda spec, extra: {}  # spec field updates
    precheck: Callable[[Any], None] = lambda spec: None               # cheap, before building

    def pipeline(self):
        """The kind's module; DesignError 'not available' if it is not installed."""
        try:
            return importlib.import_module(self.module)
        except ModuleNotFoundError as err:
            if err.name and self.module.startswith(err.name):
                raise DesignError("kind", self.name,
                                  f"not available in this build ({self.module} is missing)") from None
            raise

    def spec_type(self) -> type:
        return getattr(self.pipeline(), self.spec_class)

    def spec_keys(self) -> tuple[str, ...]:
        return tuple(f.name for f in dataclasses.fields(self.spec_type()))

    def field_types(self) -> dict[str, Any]:
        """Field name -> resolved type annotation of the spec dataclass."""
        spec = self.spec_type()
        hints = typing.get_type_hints(spec)
        return {f.name: hints.get(f.name, Any) for f in dataclasses.fields(spec)}

    def build_part(self, spec):
        return getattr(self.pipeline(), self.build)(spec)

    def report_of(self, built) -> dict:
        return getattr(self.pipeline(), self.report)(built)


def printed_spec(kind: PartKind, spec, hole_compensation: float, tooth_clearance: float):
    """The spec as it must be drawn for a printer: bores enlarged, tooth clearance added."""
    updates = {name: getattr(spec, name) + hole_compensation
               for name in kind.hole_fields if (getattr(spec, name) or 0) > 0}
    updates.update(kind.clearance(spec, tooth_clearance))
    return dataclasses.replace(spec, **updates)


def _gear_pair_clearance(spec, extra: float) -> dict:
    return {"backlash": spec.backlash_mm + extra} if extra else {}


def _gear_pair_precheck(spec) -> None:
    """The instant checks of build_gear_pair (mechanism, tooth count, tooth form, sizes)."""
    from wheelstep_cli.gears.sectors import sectors_per_quarter

    spec.law()
    spec.tooth_form()
    sectors_per_quarter(spec.z, spec.turns)
    require(spec.thickness > 0, "thickness", spec.thickness, "must be > 0 mm")
    require(spec.bore >= 0, "bore", spec.bore, "must be >= 0 mm")
    require(spec.install_distance >= spec.center_distance, "install_distance", spec.install_distance,
            f"must be >= center_distance {spec.center_distance:g} mm")


def _shoe_parts(shoe) -> list:
    return list(shoe.parts)


def _shoe_precheck(spec) -> None:
    """The instant checks of build_shoe: mechanism sizing and positive part sizes."""
    spec.design()
    for name in ("width", "strut_diameter", "socket_depth", "rim"):
        value = getattr(spec, name)
        require(value > 0, name, value, "must be > 0 mm")


KINDS: dict[str, PartKind] = {
    "gear-pair": PartKind(
        name="gear-pair", module="wheelstep_cli.parts.gear_pair", spec_class="GearPairSpec",
        build="build_gear_pair", report="gear_pair_report", section="gears",
        parts=lambda pair: [pair.pinion, pair.wheel], hole_fields=("bore",),
        clearance=_gear_pair_clearance, precheck=_gear_pair_precheck),
    "shoe": PartKind(
        name="shoe", module="wheelstep_cli.parts.shoe", spec_class="ShoeSpec",
        build="build_shoe", report="shoe_report", section="shoe", parts=_shoe_parts,
        hole_fields=("strut_diameter",), precheck=_shoe_precheck),
}
