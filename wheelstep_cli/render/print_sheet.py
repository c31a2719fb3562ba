"""``print-sheet.md``: what the person at the printer needs, in one page of Markdown.

Only formatting: the figures (volumes, masses) are computed by the batch and passed in.
"""

from __future__ import annotations

from collections import Counter

from wheelstep_cli.errors import counted


def print_sheet_bytes(plan, plates, built, results, failed, masses) -> bytes:
    """The print sheet: parts and quantities, volumes and masses, plates, slicer settings, failures.

    ``masses`` maps (entry index, part name) to (solid, estimated printed) mass in g.
    """
    lines = [f"# Print sheet: {plan.file.name}", ""]
    if plan.description:
        lines += [plan.description, ""]
    total_parts = sum(len(p.items) for p in plates)
    lines += [f"{len(built)} of {counted(len(plan.entries), 'entry', 'entries')} built, "
              f"{counted(total_parts, 'part', 'parts')} on {counted(len(plates), 'plate', 'plates')}.", ""]
    if failed:
        lines += ["## Not built", "", "| entry | where | reason |", "| --- | --- | --- |"]
        for entry, where, reason in failed:
            lines.append(f"| {entry.name} | {plan.file.name}:{where.rsplit(':', 1)[1]} | {reason} |")
        lines.append("")
    lines += _parts(plates, built, results, masses)
    lines += _meshing(built, results)
    lines += _plates(plates)
    lines += _printers(plan)
    return "\n".join(lines).encode("utf-8")


def _parts(plates, built, results, masses) -> list[str]:
    lines = ["## Parts", "",
             "| entry | part | design | printer | qty | volume each (cm3) | solid mass each (g) "
             "| est. printed mass each (g) "
             "| size X x Y x Z (mm) | checks |",
             "| --- | --- | --- | --- | ---: | ---: | ---: | ---: | --- | --- |"]
    totals: Counter = Counter()
    for entry in built:
        for part in results[entry.index].parts:
            size = part.bounds[1] - part.bounds[0]
            solid, mass = masses[entry.index, part.name]
            totals[entry.printer.name, "solid"] += solid * entry.quantity
            totals[entry.printer.name, "mass"] += mass * entry.quantity
            ok = "printable" if all(part.checks.values()) else "FAILED"
            lines.append(f"| {entry.name} | {part.name} | {entry.design_label} | {entry.printer.name} | "
                         f"{entry.quantity} | {part.volume / 1000:.2f} | {solid:.1f} | {mass:.1f} | "
                         f"{size[0]:.1f} x {size[1]:.1f} x {size[2]:.1f} | {ok} |")
    lines.append("")
    printers = list(dict.fromkeys(p.printer.name for p in plates))
    for name in printers:
        printer = next(p.printer for p in plates if p.printer.name == name)
        lines.append(f"Total for {name} ({printer.material}, {printer.density:g} g/cm3): "
                     f"{totals[name, 'mass']:.0f} g estimated printed, {totals[name, 'solid']:.0f} g if solid.")
    return lines + ["", "Masses: solid = volume x density; estimated = perimeters and top/bottom layers "
                    "solid, the rest at the profile's infill.", ""]


def _meshing(built, results) -> list[str]:
    """The meshing check of every built gear pair (on its meshes as written), one row each."""
    rows = [(entry, results[entry.index].mating) for entry in built
            if getattr(results[entry.index], "mating", None) is not None]
    if not rows:
        return []
    lines = ["## Gear meshing (checked on the printed meshes)", "",
             "| entry | at (mm) | interference | backlash (mm) | F'i / f'i drive (um) | "
             "F'i / f'i coast (um) | speed ripple drive / coast (%; hub, a law CSV's output) | over the printer's band |",
             "| --- | ---: | --- | --- | ---: | ---: | ---: | --- |"]
    for entry, m in rows:
        verdict = (f"YES at {m['interfering_poses']} of {m['samples']} poses (allowed)"
                   if m["interference"] else f"none ({m['samples']} poses)")
        lines.append(f"| {entry.name} | {m['distance_mm']:g} | {verdict} | {_fmt(m['backlash_min_mm'], '.3f')}"
                     f" .. {_fmt(m['backlash_max_mm'], '.3f')} | {_flank(m['drive'])} | {_flank(m['coast'])} | "
                     f"{_fmt(m['drive']['hub_speed_ripple_pct'], '.2f')} / "
                     f"{_fmt(m['coast']['hub_speed_ripple_pct'], '.2f')} | "
                     f"{_band(getattr(results[entry.index], 'band', None))} |")
    return lines + [""]


def _band(band: dict | None) -> str:
    """The band check's verdict for the person at the printer: a pair that jams is said so."""
    if band is None or not band["checked"]:
        return "not checked (the printer profile has no band)" if band is not None else "not checked"
    if band["jams"]:
        return (f"**JAMS** on {band['printer']}: see the report's tolerance section "
                "(`fit: auto` in the printer profile's band section insets the teeth until the band clears)")
    least = band.get("least_backlash_mm")
    return f"clears on {band['printer']}" + (f" (least backlash {least:.3f} mm)" if least is not None else "")


def _flank(flank: dict) -> str:
    """F'i / f'i of one flank side, um."""
    return f"{_fmt(flank['F_i_total_um'], '.1f')} / {_fmt(flank['f_i_tooth_um'], '.1f')}"


def _fmt(value, spec: str) -> str:
    return "n/a" if value is None else format(value, spec)


def _plates(plates) -> list[str]:
    lines = ["## Plates", ""]
    for plate in plates:
        printer = plate.printer
        lines += [f"### {plate.stem}.3mf: {printer.name} ({printer.material}, bed "
                  f"{printer.bed[0]:g} x {printer.bed[1]:g} mm)", "",
                  f"![{plate.stem}]({plate.stem}.png)", ""]
        counts = Counter(f"{i.entry} {i.part.name}" for i in plate.items)
        for label, count in counts.items():
            lines.append(f"- {count} x {label}")
        lines.append("")
    return lines


def _teeth_compensation(printer) -> str:
    """How the printer's gear teeth are compensated: its tooth clearance, or its band's fit."""
    fit = getattr(printer.band, "fit", None) if printer.band is not None else None
    if fit is None:
        return (f"gear teeth with the tooth clearance {printer.tooth_clearance:g} mm in their backlash "
                "(held in a default backlash, added to one the design sets)")
    return (f"gear tooth outlines inset along their normals for the band's fit '{fit}' "
            "(each pair's report gives the inset; no tooth clearance)")


def _bed_side(plan, printer) -> str:
    """How the bed-side edges of ``printer``'s parts are compensated for the elephant foot:
    inset, or on a chamfered part (a gear pair) by its 45 deg face chamfer instead."""
    chamfers = sorted({float(getattr(e.printed, "chamfer_mm", 0.0) or 0.0) for e in plan.entries
                       if e.printer.name == printer.name})
    inset = (f"bed-side edges inset {printer.elephant_foot_inset:g} mm over the lowest "
             f"{printer.elephant_foot_height:g} mm (elephant foot)")
    chamfered = [c for c in chamfers if c > 0.0]
    if not chamfered or printer.elephant_foot_inset <= 0.0:
        return inset
    said = (f"gear faces chamfered {' / '.join(f'{c:g}' for c in chamfered)} mm at 45 deg, which "
            "takes the place of the elephant-foot inset")
    return said if 0.0 not in chamfers else f"{said}; other parts' {inset}"


def _printers(plan) -> list[str]:
    lines = ["## Printer profiles and recommended slicer settings", ""]
    seen = []
    for entry in plan.entries:
        if entry.printer.name in seen:
            continue
        seen.append(entry.printer.name)
        printer = entry.printer
        lines += [f"### {printer.name}", "", printer.description, "",
                  f"Geometry already compensated in the meshes: bores +{printer.hole_compensation:g} mm, "
                  f"{_teeth_compensation(printer)}, {_bed_side(plan, printer)}. Do not compensate "
                  "again in the slicer.", "",
                  "| setting | value |", "| --- | --- |"]
        lines += [f"| {key} | {value} |" for key, value in printer.slicer.items()]
        lines.append("")
    return lines
