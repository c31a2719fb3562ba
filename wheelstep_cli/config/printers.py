"""Printer/material profiles (``profiles/*.yaml`` with a ``printer`` section).

They hold what changes the printed geometry (bed size, hole compensation, extra tooth
clearance, elephant-foot inset, material density) and the recommended slicer settings,
which are only passed on to the print sheet.
"""

from __future__ import annotations

import hashlib
import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from wheelstep_cli.config.located_yaml import LocatedYaml, read_located_yaml
from wheelstep_cli.config.schema import InvalidInput, Issue, check_mapping, dotted, show

TECHNOLOGIES = ("fdm", "resin")
#: printer key -> (smallest, largest) allowed value in mm
PRINTER_LIMITS = {
    "margin": (0.0, 50.0),
    "hole_compensation": (-1.0, 1.0),
    "tooth_clearance": (0.0, 1.0),
    "elephant_foot_height": (0.0, 2.0),
    "elephant_foot_inset": (0.0, 1.0),
}
PRINTER_KEYS = ("technology", "bed", *PRINTER_LIMITS)
MATERIAL_KEYS = ("name", "density")


@dataclass(frozen=True)
class Printer:
    """A printer + material preset. Lengths in mm, density in g/cm3."""

    name: str
    description: str
    technology: str
    bed: tuple[float, float]
    margin: float = 5.0
    hole_compensation: float = 0.0
    tooth_clearance: float = 0.0
    elephant_foot_height: float = 0.0
    elephant_foot_inset: float = 0.0
    material: str = ""
    density: float = 1.0
    slicer: dict[str, Any] = field(default_factory=dict)
    file_name: str = ""
    sha256: str = ""

    def geometry(self) -> dict[str, float]:
        """The settings that change the printed geometry (for reports and 3MF metadata)."""
        return {"hole_compensation": self.hole_compensation, "tooth_clearance": self.tooth_clearance,
                "elephant_foot_height": self.elephant_foot_height,
                "elephant_foot_inset": self.elephant_foot_inset}


def is_printer_profile(data: Any) -> bool:
    return isinstance(data, dict) and "printer" in data


def printer_from_profile(name: str, path: Path, label: str, doc: LocatedYaml | None = None) -> Printer:
    """Read and check a printer profile; every problem is reported with ``label:line``.

    ``doc`` is the profile already parsed (as :func:`read_located_yaml` gives it), if it was.
    """
    from wheelstep_cli.config.located_yaml import YamlSyntaxError

    if doc is None:
        try:
            doc = read_located_yaml(path, label)
        except YamlSyntaxError as err:
            raise InvalidInput([Issue(err.where, "", err.limit)]) from None
    issues: list[Issue] = []
    printer = _parse_printer(name, doc, issues)
    if issues:
        raise InvalidInput(issues)
    raw = Path(path).read_bytes()
    return Printer(**printer, file_name=Path(path).name, sha256=hashlib.sha256(raw).hexdigest())


def _number(doc: LocatedYaml, path: tuple, value: Any, lo: float, hi: float,
            issues: list[Issue], lo_open: bool = False) -> float | None:
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        issues.append(Issue(doc.where(path), dotted(path), f"= {show(value)}: must be a number (mm)"))
        return None
    if (value <= lo if lo_open else value < lo) or value > hi:
        low = f"> {lo:g}" if lo_open else f">= {lo:g}"
        issues.append(Issue(doc.where(path), dotted(path), f"= {show(value)}: must be {low} and <= {hi:g}"))
        return None
    return float(value)


def _parse_printer(name: str, doc: LocatedYaml, issues: list[Issue]) -> dict:
    top = check_mapping(doc, (), doc.data, ("description", "printer", "material", "slicer"), issues,
                        required=("printer", "material"))
    section = check_mapping(doc, ("printer",), top.get("printer"), PRINTER_KEYS, issues,
                            required=("technology", "bed"))
    out: dict[str, Any] = {"name": name, "description": str(top.get("description", name))}
    tech = section.get("technology")
    if "technology" in section and tech not in TECHNOLOGIES:
        issues.append(Issue(doc.where(("printer", "technology")), "printer.technology",
                            f"= {show(tech)}: must be one of: {', '.join(TECHNOLOGIES)}"))
    out["technology"] = tech
    bed = section.get("bed")
    if "bed" in section:
        if not (isinstance(bed, list) and len(bed) == 2):
            issues.append(Issue(doc.where(("printer", "bed")), "printer.bed",
                                f"= {show(bed)}: must be [X, Y] in mm"))
        else:
            sizes = [_number(doc, ("printer", "bed", i), v, 0.0, 2000.0, issues, lo_open=True)
                     for i, v in enumerate(bed)]
            out["bed"] = tuple(sizes)
    for key, (lo, hi) in PRINTER_LIMITS.items():
        if key in section:
            out[key] = _number(doc, ("printer", key), section[key], lo, hi, issues)
    material = check_mapping(doc, ("material",), top.get("material"), MATERIAL_KEYS, issues,
                             required=("density",))
    if "density" in material:
        out["density"] = _number(doc, ("material", "density"), material["density"], 0.0, 25.0,
                                 issues, lo_open=True)
    out["material"] = str(material.get("name", ""))
    slicer = check_mapping(doc, ("slicer",), top.get("slicer"), list(top.get("slicer") or {}), issues)
    for key, value in slicer.items():
        if isinstance(value, (dict, list)):
            issues.append(Issue(doc.where(("slicer", key)), f"slicer.{key}",
                                "must be a single value (number or text)"))
    out["slicer"] = dict(slicer) if isinstance(slicer, dict) else {}
    return out
