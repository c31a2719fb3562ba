"""Registry of the part kinds a batch can build, and what a printer profile changes in each.

A kind is a part pipeline (``parts/<kind>.py``: a spec model from config -> build ->
report) plus the few facts the batch needs: which design-profile section holds its
options, which spec fields are bores (enlarged by the printer's hole compensation),
how extra tooth clearance is added, and the domain checks that can run before building.
Pipelines are imported lazily, so a kind whose module is missing is reported as
"not available" instead of breaking the others.
"""

from __future__ import annotations

import importlib
from dataclasses import dataclass, replace
from typing import Any, Callable

from wheelstep_cli.config.batch_file import KindName
from wheelstep_cli.config.resolve import updated
from wheelstep_cli.errors import DesignError


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
    checks: tuple[Callable[[Any], object], ...] = ()  # cheap domain checks, before building
    with_parts: Callable[[Any, list, dict], Any] = lambda built, parts, checks: built  # swap parts in
    mating_check: Callable[[Any], dict] | None = None  # check of the parts together, as written

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
        return tuple(self.spec_type().model_fields)

    def problems(self, spec) -> list[DesignError]:
        """Every problem the domain checks find in ``spec`` (each check runs on its own)."""
        found = []
        for check in self.checks:
            try:
                check(spec)
            except DesignError as err:
                found.append(err)
        return found

    def build_part(self, spec):
        return getattr(self.pipeline(), self.build)(spec)

    def report_of(self, built) -> dict:
        return getattr(self.pipeline(), self.report)(built)


def printed_spec(kind: PartKind, spec, hole_compensation: float, tooth_clearance: float):
    """The spec as it must be drawn for a printer: bores enlarged, tooth clearance added."""
    changes = {name: getattr(spec, name) + hole_compensation
               for name in kind.hole_fields if (getattr(spec, name) or 0) > 0}
    changes.update(kind.clearance(spec, tooth_clearance))
    return updated(spec, **changes)


@dataclass(frozen=True)
class Printing:
    """A part drawn for a printer: the printer and the spec as designed (before compensation)."""

    printer: Any                # wheelstep_cli.config.printers.Printer
    design: Any                 # the kind's spec model, as given


def for_printer(kind: PartKind, built, printer, design=None):
    """``built`` as it is printed on ``printer``: each part's bed-side edges compensated for
    the elephant foot, the part lifted onto z = 0 and checked again (DesignError if it fails).
    ``design`` (the spec before :func:`printed_spec`) is kept with the printer for reports."""
    from wheelstep_cli.geometry.mesh_checks import Part, require_printable
    from wheelstep_cli.geometry.solids import inset_bottom

    parts = []
    # a chamfered part's bed-side edges are already drawn in (and it is no prism there for
    # the foot's step inset to follow): the chamfer replaces the elephant-foot inset
    chamfered = (getattr(getattr(built, "spec", None), "chamfer", 0) or 0) > 0
    for part in kind.parts(built):
        if not chamfered:
            part = inset_bottom(part, printer.elephant_foot_height, printer.elephant_foot_inset)
        lift = [0.0, 0.0, -float(part.bounds[0, 2])]
        parts.append(Part(part.name, part.vertices + lift, part.faces, part.expected_volume))
    checks = {part.name: require_printable(part) for part in parts}
    compensated = kind.with_parts(built, parts, checks)
    return replace(compensated, printing=Printing(printer, design))


def build_for_printer(kind_name: str, spec, printer=None):
    """Build ``spec``'s part as batch builds it for ``printer`` (compensated by
    :func:`printed_spec` and :func:`for_printer`); without a printer exactly as designed."""
    kind = KINDS[kind_name]
    if printer is None:
        return kind.build_part(spec)
    printed = printed_spec(kind, spec, printer.hole_compensation, printer.tooth_clearance)
    for problem in kind.problems(printed):
        raise problem
    return for_printer(kind, kind.build_part(printed), printer, spec)


def printing_record(printing: Printing | None, printed) -> dict:
    """What a part report says of its printer: nothing without one; else the design's and the
    printed parameters (mm), the printer profile and the geometry it changed."""
    if printing is None:
        return {}
    printer = printing.printer
    return {"parameters": printing.design.model_dump() if printing.design is not None else None,
            "printed_parameters": printed.model_dump(),
            "printer_profile": printer.name,
            "printer_file": {"file": printer.file_name, "sha256": printer.sha256},
            "printer_geometry": printer.geometry()}


def _gear_pair_meshing(pair) -> dict:
    """The meshing check ``wheelstep gears`` runs, on the pair's meshes as written."""
    from wheelstep_cli.parts.mesh_check import check_gear_pair, meshing_record

    return meshing_record(check_gear_pair(pair))


def _gear_pair_clearance(spec, extra: float) -> dict:
    from wheelstep_cli.parts.gear_laws import design_backlash

    if not extra:
        return {}
    if spec.backlash is None and spec.teeth == "generated":
        # the default is the most backlash the ripple bound allows: the printer's tooth
        # clearance is taken out of it (at least all of the clearance), not added on top
        return {"backlash": max(design_backlash(spec), extra)}
    return {"backlash": spec.backlash_mm + extra}


def _sectors(spec) -> None:
    from wheelstep_cli.gears.sectors import sectors_per_quarter

    sectors_per_quarter(spec.z, spec.turns)


KINDS: dict[str, PartKind] = {
    KindName.gear_pair.value: PartKind(
        name=KindName.gear_pair.value, module="wheelstep_cli.parts.gear_pair", spec_class="GearPairSpec",
        build="build_gear_pair", report="gear_pair_report", section="gears",
        parts=lambda pair: [pair.pinion, pair.wheel], hole_fields=("bore", "key_width"),
        clearance=_gear_pair_clearance, mating_check=_gear_pair_meshing,
        with_parts=lambda pair, parts, checks: replace(pair, pinion=parts[0], wheel=parts[1], checks=checks),
        checks=(lambda spec: spec.law(), lambda spec: spec.tooth_form(), _sectors)),
    KindName.shoe.value: PartKind(
        name=KindName.shoe.value, module="wheelstep_cli.parts.shoe", spec_class="ShoeSpec",
        build="build_shoe", report="shoe_report", section="shoe", parts=lambda shoe: list(shoe.parts),
        hole_fields=("strut_diameter",), checks=(lambda spec: spec.design(),),
        with_parts=lambda shoe, parts, checks: replace(shoe, parts=parts, checks=checks)),
}
