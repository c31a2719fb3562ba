"""Printer/material profiles (``profiles/*.yaml`` with a ``printer`` section).

They hold what changes the printed geometry (bed size and height, hole compensation, extra
tooth clearance, elephant-foot inset, the gears' edge chamfer, material density), the skirt
and brim, and the slicer
settings (PrusaSlicer option names), which every plate carries as PrusaSlicer's
configuration and the print sheet lists.
"""

from __future__ import annotations

import hashlib
from dataclasses import dataclass
from pathlib import Path
from typing import Annotated, Any, Optional

from pydantic import AfterValidator, BaseModel, Field, ValidationInfo, field_validator
from pydantic_core import PydanticCustomError

from wheelstep_cli.config.fields import STRICT, Choice, Real, Whole, length, quantity
from wheelstep_cli.config.located_yaml import LocatedYaml, YamlSyntaxError, read_located_yaml
from wheelstep_cli.config.schema import InvalidInput, Issue, dotted, validate_file, yaml_issues
from wheelstep_cli.errors import DesignError


class Technology(Choice):
    fdm = "fdm"
    resin = "resin"


def _single(value: Any) -> Any:
    if isinstance(value, (dict, list)):
        raise PydanticCustomError("single_value", "must be a single value (number or text)")
    return value


BedSize = Annotated[Real, Field(gt=0, le=2000)]
SlicerValue = Annotated[Any, AfterValidator(_single)]


class PrinterSection(BaseModel):
    """The printer: technology, usable bed (X, Y) and the geometry compensations, mm."""

    model_config = STRICT

    technology: Technology
    bed: tuple[BedSize, BedSize] = Field(json_schema_extra={
        "limit": "must be [X, Y] in mm, each > 0 and <= 2000"})
    max_height: Real = length(..., gt=0, le=2000)
    margin: Real = length(5.0, ge=0, le=50)
    skirts: Whole = Field(1, strict=True, ge=0, le=20)
    skirt_distance: Real = length(6.0, ge=0, le=50)
    brim_width: Real = length(0.0, ge=0, le=50)
    hole_compensation: Real = length(0.0, ge=-1, le=1)
    tooth_clearance: Real = length(0.0, ge=0, le=1)
    elephant_foot_height: Real = length(0.0, ge=0, le=2)
    elephant_foot_inset: Real = length(0.0, ge=0, le=1)
    # after the foot: its rule reads the foot's values
    chamfer: Real = length(0.0, ge=0, le=5)

    @field_validator("chamfer")
    @classmethod
    def _chamfer_covers_the_foot(cls, value: float, info: ValidationInfo) -> float:
        least = least_chamfer(info.data.get("elephant_foot_inset", 0.0),
                              info.data.get("elephant_foot_height", 0.0))
        if 0 < value < least:
            raise PydanticCustomError("chamfer_foot", chamfer_limit(least))
        return value


def least_chamfer(inset: float, height: float) -> float:
    """The least 45 deg chamfer (mm) that stands for an elephant-foot inset of ``inset`` mm
    over the lowest ``height`` mm: at height z the chamfer draws the bed-side edges in by
    (chamfer - z), so over the foot's height it draws them in by at least ``inset`` only from
    inset + height on. 0 when the printer has no foot."""
    return float(inset) + float(height) if inset > 0 and height > 0 else 0.0


def chamfer_limit(least: float, printer: str = "") -> str:
    """The limit a chamfer too small to replace the elephant-foot inset is refused with."""
    on = f" on printer {printer}" if printer else ""
    return (f"must be 0 or >= {least:g} mm{on} (the elephant-foot inset plus its height: a "
            "chamfer replaces the inset, so a smaller one would leave the first layers bulging)")


class Fit(Choice):
    """How much play a printed pair is given over its band (see :data:`FIT_MARGINS`)."""

    auto = "auto"
    tight = "tight"
    normal = "normal"
    loose = "loose"


class BandSection(BaseModel):
    """The printer's dimensional band (SPEC §11), mm: outlines come out offset along their
    normals by -outline..+outline, holes come out up to ``hole_shrink`` smaller in diameter,
    and the frame holds a centre distance to +-``center_distance``. Each is given: one left
    out is not taken as 0 (a printer is never taken as perfect)."""

    model_config = STRICT

    outline: Real = length(..., gt=0, le=1)
    hole_shrink: Real = length(..., ge=0, le=1)
    center_distance: Real = length(..., ge=0, le=1)
    # the fit batch draws gear pairs with (parts.fit); none: the printer's tooth_clearance
    fit: Optional[Fit] = None


#: Least backlash (mm, on the wheel pitch curve) each fit keeps at the band's tight corner:
#: auto keeps the least that is still positive with a safety of 10 um (the check's own
#: error is a few um); tight 0.05 mm (about half an FDM line's wobble); normal 0.1 mm
#: (smooth running with a dry PLA pair); loose 0.2 mm (dirt, wear, a frame that flexes).
FIT_MARGINS = {Fit.auto: 0.01, Fit.tight: 0.05, Fit.normal: 0.1, Fit.loose: 0.2}


class MaterialSection(BaseModel):
    model_config = STRICT

    name: str = Field("", strict=True)
    density: Real = quantity(unit="g/cm3", gt=0, le=25)


class PrinterProfile(BaseModel):
    """A printer profile file."""

    model_config = STRICT

    description: Optional[str] = Field(None, strict=True)
    printer: PrinterSection
    material: MaterialSection
    slicer: dict[str, SlicerValue] = {}
    band: Optional[BandSection] = None


@dataclass(frozen=True)
class Band:
    """A printer's dimensional band (SPEC §11), mm: outline offset +-``outline`` along the
    normals, holes up to ``hole_shrink`` smaller, centre distance +-``center_distance``."""

    outline: float
    hole_shrink: float
    center_distance: float
    fit: Optional[str] = None     # auto, tight, normal, loose: what batch fits gear pairs to


@dataclass(frozen=True)
class Printer:
    """A checked printer + material preset. Lengths in mm, density in g/cm3."""

    name: str
    description: str
    technology: str
    bed: tuple[float, float]
    max_height: float
    margin: float
    skirts: int
    skirt_distance: float
    brim_width: float
    hole_compensation: float
    tooth_clearance: float
    elephant_foot_height: float
    elephant_foot_inset: float
    material: str
    density: float
    slicer: dict[str, Any]
    file_name: str
    sha256: str
    band: Optional[Band] = None
    #: the name or path as the user gave it, for messages (``name`` is what outputs record)
    given: str = ""
    chamfer: float = 0.0       # 45 deg edge chamfer of the gears' tooth faces (--chamfer default)

    def geometry(self) -> dict[str, float]:
        """The settings that change the printed geometry (for reports and 3MF metadata)."""
        return {"hole_compensation": self.hole_compensation, "tooth_clearance": self.tooth_clearance,
                "elephant_foot_height": self.elephant_foot_height,
                "elephant_foot_inset": self.elephant_foot_inset, "chamfer": self.chamfer}

    def chamfer_for(self, given: float | None, param: str = "chamfer") -> float:
        """The chamfer (mm) a part gets on this printer: ``given`` (the design's, None: not
        given) else the printer's; DesignError naming ``param`` for one that is too small to
        replace the elephant-foot inset (see :func:`least_chamfer`)."""
        value = self.chamfer if given is None else given
        least = least_chamfer(self.elephant_foot_inset, self.elephant_foot_height)
        if 0 < value < least:
            raise DesignError(param, value, chamfer_limit(least, self.name))
        return value

    @property
    def nozzle(self) -> float:
        """The nozzle diameter (mm) of the first extruder (PrusaSlicer's ``nozzle_diameter``
        lists one per extruder, comma-separated), 0.4 when the profile gives none."""
        return float(str(self.slicer.get("nozzle_diameter", 0.4)).split(",")[0])

    @property
    def edge_margin(self) -> float:
        """Least distance (mm) from a part to a bed edge: the margin, or more when the brim
        and the skirt (its distance plus its loops, each a first-layer line of twice the
        nozzle, PrusaSlicer's default width) need it, plus one line to spare."""
        line = 2.0 * self.nozzle
        skirt = self.skirt_distance + self.skirts * line if self.skirts else 0.0
        return max(self.margin, self.brim_width + skirt + line)

    def slicer_config(self) -> dict[str, Any]:
        """PrusaSlicer's configuration of a plate: the bed (shape and height), skirt, brim, no
        compensation of its own, then the profile's slicer settings (PrusaSlicer option names)."""
        x, y = self.bed
        config: dict[str, Any] = {"bed_shape": f"0x0,{x:g}x0,{x:g}x{y:g},0x{y:g}",
                                  "max_print_height": f"{self.max_height:g}"}
        if self.technology == "resin":
            config["printer_technology"] = "SLA"
        else:
            config.update(skirts=self.skirts, skirt_distance=f"{self.skirt_distance:g}",
                          brim_width=f"{self.brim_width:g}", xy_size_compensation="0")
        # the meshes are drawn compensated (foot, holes, teeth): a slicer preset's own
        # compensation (PrusaSlicer's are often 0.2 mm) would do it twice
        config["elefant_foot_compensation"] = "0"
        config.update(self.slicer)
        return config


def _slicer_issues(doc: LocatedYaml, known: list[Issue] = ()) -> list[Issue]:
    """What PrusaSlicer would not take of the file's ``slicer:`` section, each at its line: its
    single values, for the file's technology (fdm when it names none it can be), but those at
    a line ``known`` already has an issue at."""
    from wheelstep_cli.config.slicer_options import slicer_problems

    data = doc.data if isinstance(doc.data, dict) else {}
    settings, printer = data.get("slicer"), data.get("printer")
    technology = printer.get("technology") if isinstance(printer, dict) else None
    if not isinstance(settings, dict):
        return []
    taken = {issue.where for issue in known}
    single = {k: v for k, v in settings.items() if isinstance(k, str) and not isinstance(v, (dict, list))}
    found = [Issue(doc.where(("slicer", key)), dotted(("slicer", key)), why)
             for key, why in slicer_problems(single, "resin" if technology == "resin" else "fdm")]
    return [issue for issue in found if issue.where not in taken]


def _band(section: BandSection) -> Band:
    values = section.model_dump()
    fit = values.pop("fit")
    return Band(**values, fit=None if fit is None else Fit(fit).value)


def is_printer_profile(data: Any) -> bool:
    return isinstance(data, dict) and "printer" in data


def printer_from_profile(name: str, path: Path, label: str, doc: LocatedYaml | None = None,
                         given: str = "") -> Printer:
    """Read and check a printer profile; every problem is reported with ``label:line``.

    ``doc`` is the profile already parsed (as :func:`read_located_yaml` gives it), if it was;
    ``given``: the name or path as the user wrote it (messages; default ``name``).
    """
    if doc is None:
        try:
            doc = read_located_yaml(path, label)
        except YamlSyntaxError as err:
            raise InvalidInput(yaml_issues(err)) from None
    try:
        profile = validate_file(PrinterProfile, doc)
    except InvalidInput as err:
        # the slicer section's problems with the rest, so one run names every one
        raise InvalidInput([*err.issues, *_slicer_issues(doc, err.issues)]) from None
    if issues := _slicer_issues(doc):
        raise InvalidInput(issues)
    section, material = profile.printer, profile.material
    raw = Path(path).read_bytes()
    printer = Printer(name=name, description=profile.description or name, technology=section.technology,
                   bed=tuple(section.bed), max_height=section.max_height, margin=section.margin,
                   skirts=section.skirts, skirt_distance=section.skirt_distance,
                   brim_width=section.brim_width,
                   hole_compensation=section.hole_compensation, tooth_clearance=section.tooth_clearance,
                   elephant_foot_height=section.elephant_foot_height,
                   elephant_foot_inset=section.elephant_foot_inset, material=material.name,
                   density=material.density, slicer=dict(profile.slicer), chamfer=section.chamfer,
                   file_name=Path(path).name, sha256=hashlib.sha256(raw).hexdigest(),
                   band=None if profile.band is None else _band(profile.band), given=given or name)
    edge = printer.edge_margin
    if min(printer.bed) <= 2.0 * edge:
        # nothing could be placed: every part would be refused with a bed of no size
        raise InvalidInput([Issue(doc.where(("printer", "bed")), "printer.bed",
                                  f"= [{printer.bed[0]:g}, {printer.bed[1]:g}]: must be > {2.0 * edge:g} mm each "
                                  f"(twice the {edge:g} mm a part keeps from each edge: the margin, or the brim "
                                  "and skirt)")])
    return printer


#: The printer a command uses when none is named.
DEFAULT_PRINTER = "fdm-0.4-pla"

