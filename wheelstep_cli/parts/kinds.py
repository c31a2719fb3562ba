"""Registry of the part kinds a batch can build, and what a printer profile changes in each.

A kind is a part pipeline (``parts/<kind>.py``: a spec model from config -> build ->
report) plus the few facts the batch needs: which design-profile section holds its
options, which spec fields are bores (enlarged by the printer's hole compensation),
how extra tooth clearance is added, which field takes the printer's edge chamfer, and the
domain checks that can run before building.
Pipelines are imported lazily, so a kind whose module is missing is reported as
"not available" instead of breaking the others.
"""

from __future__ import annotations

import importlib
import re
from dataclasses import dataclass, replace
from typing import Any, Callable

from wheelstep_cli.config.batch_file import KindName
from wheelstep_cli.config.resolve import updated
from wheelstep_cli.errors import DesignError, format_value, rounded_down, rounded_up
from wheelstep_cli.parts.printer_rules import marks_above_the_foot, no_chamfer_fits, printers_chamfer


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
    chamfer_field: str | None = None               # edge chamfer (mm), the printer's when None

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


def printed_spec(kind: PartKind, spec, printer):
    """The spec as it must be drawn on ``printer`` (config.printers.Printer): bores enlarged by
    its hole compensation, its tooth clearance added, and the edge chamfer the design leaves
    open (None) set to the printer's (DesignError for a chamfer too small to replace the
    elephant-foot inset, see config.printers.least_chamfer)."""
    changes = {name: getattr(spec, name) + printer.hole_compensation
               for name in kind.hole_fields if (getattr(spec, name) or 0) > 0}
    changes.update(kind.clearance(spec, printer.tooth_clearance))
    if kind.chamfer_field is not None:
        try:
            changes[kind.chamfer_field] = printer.chamfer_for(getattr(spec, kind.chamfer_field),
                                                              kind.chamfer_field)
        except DesignError as err:
            raise no_chamfer_fits(err, spec, printer) from None
    try:
        printed = updated(spec, **changes)
    except DesignError as err:
        raise printers_chamfer(err, kind.chamfer_field, spec, printer) from None
    marks_above_the_foot(printed, printer)
    return printed


@dataclass(frozen=True)
class Printing:
    """A part drawn for a printer: the printer and the spec as designed (before compensation)."""

    printer: Any                # wheelstep_cli.config.printers.Printer
    design: Any                 # the kind's spec model, as given


def for_printer(kind: PartKind, built, printer, design=None):
    """``built`` as it is printed on ``printer``: each part's bed-side edges compensated for
    the elephant foot (unless the part is chamfered, see below), the part lifted onto z = 0
    and checked again (DesignError if it fails). ``design`` (the spec before
    :func:`printed_spec`) is kept with the printer for reports."""
    from wheelstep_cli.geometry.mesh_checks import Part, require_printable
    from wheelstep_cli.geometry.solids import inset_bottom

    parts = []
    # a chamfered part's bed-side edges are already drawn in, by at least the foot's inset
    # over the foot's height (printed_spec refuses a smaller chamfer), and it is no prism
    # there for the foot's step inset to follow: the chamfer replaces the elephant-foot inset
    chamfered = chamfer_of(built) > 0
    for part in kind.parts(built):
        if not chamfered:
            part = inset_bottom(part, printer.elephant_foot_height, printer.elephant_foot_inset)
        lift = [0.0, 0.0, -float(part.bounds[0, 2])]
        parts.append(Part(part.name, part.vertices + lift, part.faces, part.expected_volume))
    checks = {part.name: require_printable(part) for part in parts}
    compensated = kind.with_parts(built, parts, checks)
    return replace(compensated, printing=Printing(printer, design))


def chamfer_of(built) -> float:
    """The edge chamfer (mm) a built part was drawn with (0 for a kind without one)."""
    return float(getattr(getattr(built, "spec", None), "chamfer_mm", 0.0) or 0.0)


def chamfer_record(design, printed, printer, given_by: str | None = None) -> dict:
    """What a report says of the edge chamfer: its size (mm), where it came from and what
    became of the printer's elephant-foot inset. ``design``/``printed``: the spec as given and
    as drawn (the same without a printer); ``given_by``: what gave a design's chamfer, as the
    command knows it (None: a batch entry's, its overrides or its design)."""
    mm = float(printed.chamfer_mm)
    if design.chamfer is not None:
        source = given_by or "the batch entry (its overrides, else its design)"
    elif printer is not None:
        source = f"printer profile {printer.name}"
    else:
        source = "none given (no --chamfer, no --printer)"
    if printer is None:
        foot = "none (no printer)"
    elif mm > 0:
        foot = ("replaced by the chamfer (it draws the bed-side edges in by at least the "
                f"{printer.elephant_foot_inset:g} mm inset over the {printer.elephant_foot_height:g} "
                "mm foot)")
    elif printer.elephant_foot_inset > 0 and printer.elephant_foot_height > 0:
        foot = (f"applied: the lowest {printer.elephant_foot_height:g} mm drawn "
                f"{printer.elephant_foot_inset:g} mm smaller")
    else:
        foot = "none (the printer has no elephant foot)"
    return {"mm": mm, "from": source, "elephant_foot_inset": foot}


def build_for_printer(kind_name: str, spec, printer=None):
    """Build ``spec``'s part as batch builds it for ``printer`` (compensated by
    :func:`printed_spec` and :func:`for_printer`); without a printer exactly as designed."""
    kind = KINDS[kind_name]
    if printer is None:
        return kind.build_part(spec)
    printed = printed_spec(kind, spec, printer)
    try:
        for problem in kind.problems(printed):
            raise problem
        return for_printer(kind, kind.build_part(printed), printer, spec)
    except DesignError as err:
        raise as_designed(err, spec, printed) from None


def as_designed(err: DesignError, spec, printed, printed_beside: bool = True) -> DesignError:
    """``err`` (raised on the printer-compensated ``printed`` spec) showing each value the
    printer changed as the user gave it in ``spec``, the printed one beside it (unless not
    ``printed_beside``: a file's line shows the value as written), and a limit of it in mm
    both ways (the user's value is the one to change)."""
    def changed(name: str) -> tuple | None:
        field = name.replace("-", "_")
        if field not in type(spec).model_fields:
            return None
        given, drawn = getattr(spec, field), getattr(printed, field)
        return None if given is None or given == drawn else (given, drawn)

    def shown(name: str, value):
        both = changed(name)
        if both is None:
            return value
        return f"{format_value(both[0])} ({format_value(both[1])} as printed)" if printed_beside else both[0]

    def shift_of(name: str) -> float | None:
        both = changed(name)
        if both is None or not all(isinstance(v, (int, float)) for v in both):
            return None
        return float(both[1]) - float(both[0])

    def limit_of(name: str, limit: str) -> str:
        shift = shift_of(name)
        return flags_as_given(limit if shift is None else given_limit(limit, shift), shift_of)

    restated = DesignError(
        err.param, shown(err.param, err.value), limit_of(err.param, err.limit),
        {name: (shown(name, value), limit_of(name, limit)) for name, (value, limit) in err.alternatives.items()})
    # the values as given, by name, whichever statement is made (a script reads the number)
    restated.given_values = {name: both[0] for name in type(spec).model_fields if (both := changed(name))}
    return err._with_extras(restated)


def flags_as_given(text: str, shift_of) -> str:
    """``text`` with each bound it names another input by ("--bore <= 27.89 mm", the mark's
    room) said for the value as given, when ``shift_of(name)`` (mm the printer drew it larger;
    None: unchanged) says the printer changed it, the printed bound beside it."""
    def said(found) -> str:
        shift = shift_of(found.group(1).replace("-", "_"))
        if shift is None:
            return found.group(0)
        return f"--{found.group(1)} {_bound_as_given(found.group(2), found.group(3), shift)}"

    return _FLAG_BOUND.sub(said, text)


_BOUND = re.compile(r"must be (<=|<|>=|>) (-?\d+(?:\.\d+)?) mm")
#: Another input's bound a limit names by its flag: "--bore <= 27.89 mm".
_FLAG_BOUND = re.compile(r"--([a-z][a-z-]*) (<=|<|>=|>) (-?\d+(?:\.\d+)?) mm(?! \()")


def given_limit(limit: str, shift: float) -> str:
    """``limit`` (a DesignError's, on a value the printer drew ``shift`` mm larger) with its
    first bound in mm said for the value as given, the printed bound beside it: "must be <
    36.09 mm" -> "must be < 35.89 mm (< 36.09 mm as printed)", rounded the safe way."""
    found = _BOUND.search(limit)
    if found is None:
        return limit
    return limit[:found.start()] + f"must be {_bound_as_given(found.group(1), found.group(2), shift)}" \
        + limit[found.end():]


def _bound_as_given(op: str, bound: str, shift: float) -> str:
    """A bound ``op`` ``bound`` mm on a value the printer drew ``shift`` mm larger, said for
    the value as given (rounded the safe way) with the printed bound beside it."""
    as_given = (rounded_down if op.startswith("<") else rounded_up)(float(bound) - shift)
    return f"{op} {as_given} mm ({op} {bound} mm as printed)"


def made_from(built) -> dict:
    """What a part report says of the design profile the part was made from
    (``design_profile``, config.profiles.profile_record), when it was made from one."""
    return {"design_profile": built.design_profile} if built.design_profile is not None else {}


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


def _shoe_fits(spec) -> None:
    """The shoe's mechanism sized and its strut socket fitted in the body, before any solid."""
    from wheelstep_cli.parts.shoe_socket import socket_fits

    socket_fits(spec)


def _cutter(spec) -> None:
    """The rack cutter of generated teeth (its cross-field rule: a dedendum above the addendum)."""
    if getattr(spec.teeth, "value", spec.teeth) == "generated":
        spec.cutter()


def _gear_pair_clearance(spec, extra: float) -> dict:
    from wheelstep_cli.parts.gear_laws import design_backlash

    if not extra:
        return {}
    if spec.backlash is None and spec.teeth == "generated":
        # the default is the most backlash the ripple bound allows: the printer's tooth
        # clearance is taken out of it (at least all of the clearance), not added on top
        return {"backlash": max(design_backlash(spec), extra)}
    return {"backlash": spec.backlash_mm + extra}


def _hub_round_hole(spec) -> None:
    from wheelstep_cli.parts.gear_faces import require_hub_round_hole

    require_hub_round_hole(spec)


def _law_periods(spec) -> None:
    from wheelstep_cli.parts.gear_laws import require_law_periods

    require_law_periods(spec)


def _sectors(spec) -> None:
    from wheelstep_cli.gears.sectors import sectors_per_quarter

    try:
        spec.law()
    except DesignError as err:
        if err.param == "turns":
            return      # no turns to count sectors by: the law's own check names it
    sectors_per_quarter(spec.z, spec.turns)


KINDS: dict[str, PartKind] = {
    KindName.gear_pair.value: PartKind(
        name=KindName.gear_pair.value, module="wheelstep_cli.parts.gear_pair", spec_class="GearPairSpec",
        build="build_gear_pair", report="gear_pair_report", section="gears",
        parts=lambda pair: [pair.pinion, pair.wheel], hole_fields=("bore", "key_width"),
        clearance=_gear_pair_clearance, mating_check=_gear_pair_meshing, chamfer_field="chamfer",
        with_parts=lambda pair, parts, checks: replace(pair, pinion=parts[0], wheel=parts[1], checks=checks),
        checks=(lambda spec: spec.law(), lambda spec: spec.tooth_form(), _cutter, _sectors, _law_periods,
                _hub_round_hole)),
    KindName.shoe.value: PartKind(
        name=KindName.shoe.value, module="wheelstep_cli.parts.shoe", spec_class="ShoeSpec",
        build="build_shoe", report="shoe_report", section="shoe", parts=lambda shoe: list(shoe.parts),
        hole_fields=("strut_diameter",), checks=(_shoe_fits,),
        with_parts=lambda shoe, parts, checks: replace(shoe, parts=parts, checks=checks)),
}


def height_inputs(kind_name: str, spec):
    """What a part of ``spec`` stands on the bed as (plate_layout.HeightInputs: a gear pair's
    plate and hub, a shoe's width, lying on its side), each lowered only as far as ``spec``,
    changed so, is still a valid spec of its kind (its model's rules and the kind's problems)."""
    from wheelstep_cli.parts.plate_layout import HeightInputs

    if kind_name == "gear-pair":
        hub = spec.hub_mm[1]
        values = {"thickness": float(spec.thickness), **({"hub_length": hub} if hub > 0 else {})}
    else:
        values = {"width": float(spec.width)}

    def accepts(options: dict) -> bool:
        try:
            return not KINDS[kind_name].problems(updated(spec, **options))
        except DesignError:
            return False

    return HeightInputs(values, accepts)
