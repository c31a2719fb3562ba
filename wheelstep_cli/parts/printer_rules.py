"""What a printer's profile asks of a part's faces (parts.kinds.printed_spec): its own edge
chamfer against the part's thickness, and the elephant-foot inset's prism at the bottom
against the timing marks. Each refusal names what the user gave, with a limit that passes.
Lengths in mm.
"""

from __future__ import annotations

from wheelstep_cli.errors import DesignError, rounded_down, rounded_up


def marks_above_the_foot(printed, printer) -> None:
    """Refuse (DesignError naming mark_depth, also stated for the thickness) timing marks
    engraved into the lowest two foot heights of an unchamfered gear: the elephant-foot inset
    needs a prism there (geometry.solids.inset_bottom said only "pinion = elephant foot")."""
    from wheelstep_cli.config.printers import least_chamfer

    depth, thickness = getattr(printed, "mark_depth", 0.0), getattr(printed, "thickness", None)
    height, inset = printer.elephant_foot_height, printer.elephant_foot_inset
    if not depth or thickness is None or printed.chamfer_mm > 0 or height <= 0 or inset <= 0:
        return
    if thickness - depth < 2.0 * height - 1e-9:
        least = least_chamfer(inset, height)
        # a chamfer replaces the inset where one fits the thickness (both faces' leave an edge)
        chamfer = (f" (or --chamfer from {least:g} to below {0.5 * thickness:g} mm, which replaces the inset)"
                   if 2.0 * least < thickness else "")
        why = (f"the marks reach into the lowest {2.0 * height:g} mm, which printer {printer.name}'s "
               f"elephant-foot inset draws in{chamfer}")
        raise DesignError("mark_depth", depth, f"must be <= {rounded_down(thickness - 2.0 * height + 1e-9)} mm: "
                          f"deeper, {why}",
                          {"thickness": (thickness, f"must be >= {rounded_up(depth + 2.0 * height - 1e-9)} mm: "
                                                    f"thinner, {why}")})


def no_chamfer_fits(err: DesignError, spec, printer) -> DesignError:
    """``err`` (a chamfer below the least that replaces the printer's elephant-foot inset)
    restated when that least does not fit the gear (a chamfer is below half the thickness):
    only 0 does, and the line said a range no value of which passes."""
    from wheelstep_cli.config.printers import least_chamfer

    thickness = getattr(spec, "thickness", None)
    least = least_chamfer(printer.elephant_foot_inset, printer.elephant_foot_height)
    if thickness is None or 2.0 * least < thickness:
        return err
    return DesignError(err.param, err.value, f"must be 0 on printer {printer.name} for a {thickness:g} mm gear: "
                       f"a chamfer that replaces its elephant-foot inset is at least {least:g} mm, and one "
                       f"must be below half the thickness")


def printers_chamfer(err: DesignError, field: str | None, spec, printer) -> DesignError:
    """``err`` of the printed spec; the thickness rule the printer's own edge chamfer breaks
    (the design gives none) said of the thickness, the printer named, with the chamfers that
    would do (not of a chamfer never given)."""
    from wheelstep_cli.config.printers import least_chamfer

    thickness = getattr(spec, "thickness", None)
    if field is None or err.param != field or getattr(spec, field) is not None or thickness is None:
        return err
    flag, half = "--" + field.replace("_", "-"), 0.5 * float(thickness)
    least = least_chamfer(printer.elephant_foot_inset, printer.elephant_foot_height)
    # a chamfer the printer takes (none, or at least its foot's) that leaves the faces an edge
    would_do = f"{flag} 0 for none" if least >= half else f"{flag} from {least:g} to below {half:g} mm, or 0 for none"
    err = DesignError("thickness", thickness,
                      f"must be > twice the edge chamfer of printer {printer.name}, "
                      f"{2.0 * printer.chamfer:g} mm; or {would_do}",
                      {field: (None, f"must be given ({would_do.split(' ', 1)[1]}): printer "
                                     f"{printer.name}'s {printer.chamfer:g} mm is not below half the "
                                     f"thickness {half:g} mm")})
    err.remedy, err.remedies = {field: 0.0}, [{field: 0.0}]
    return err
