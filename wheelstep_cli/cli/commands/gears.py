"""The ``gears`` command: a non-circular gear pair, checked and written."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated, Optional

from wheelstep_cli.cli.options import (A, AllowInterference, B, Blend, C, CenterDistance, DryRun,
                                       FitChoice, Force, Format,
                                       Json, LawCsv, MeshFormat, Out, Printer, Profile, Quiet, RMin, Tolerance,
                                       Turns, Verbose, Z, opt, output_file)
from wheelstep_cli.cli.commands.meshcheck_shared import warn_band_jams
from wheelstep_cli.cli.output import Output
from wheelstep_cli.config.resolve import gear_pair_spec
from wheelstep_cli.config.specs import BoreShape, Corner, Teeth
from wheelstep_cli.parts.gear_exports import GearExtras, checked_extras


Module = Annotated[Optional[float], opt("--module", "-m", help="Module (tooth height unit), mm. Generated "
                                        "teeth take theirs from --z and the centre distance; a module given "
                                        "sets the centre distance that fits it (SPEC §9).",
                                        shown="2 for paper teeth; from --z and the distance for generated")]
Backlash = Annotated[Optional[float], opt("--backlash", help="Normal backlash j_n, mm.",
                                          shown="0.25 x module for paper teeth; for generated teeth the "
                                                "most, up to that, whose play costs each flank at most "
                                                "half the 1 % hub speed ripple bound")]
Plot = output_file("--plot", "Write a picture of the pair in assembly phase with its dimensions (PNG "
                            "or SVG, by the extension).", ".png", ".svg")
Gif = output_file("--gif", "Write the pair turning through a shoe handover, with contact point, TE and "
                           "hub speed (GIF).", ".gif")
Dxf = Annotated[bool, opt("--dxf", help="Also write pinion.dxf and wheel.dxf (mm outlines) in --out.")]
Svg = Annotated[bool, opt("--svg", help="Also write pinion.svg and wheel.svg (mm outlines) in --out.")]
Slice = Annotated[bool, opt("--slice", help="Slice the 3MF plate(s) with PrusaSlicer (prusa-slicer on "
                                            "PATH), write the G-code beside them and check the pair "
                                            "as it prints (mesh-check --gcode); in gears.json under "
                                            "'slice'. Exit 1 if the printed pair does not mesh.")]
Step = Annotated[bool, opt("--step", help="Also write pinion.step and wheel.step (solids) in --out; "
                                          "needs pip install wheelstep[cad].")]


InstallDistance = Annotated[Optional[float], opt(
    "--install-distance", help="Centre distance the pair is mounted and checked at, mm. Generated "
                               "teeth belong where they roll (--center-distance): mounted off it they "
                               "no longer follow the law, and a pair that then fails its check is "
                               "refused with that remedy; paper teeth mounted farther than "
                               "--center-distance get that much more backlash.",
    shown="where generated teeth roll; 144")]
Thickness = Annotated[Optional[float], opt("--thickness", help="Face width, mm.", shown="10")]
Bore = Annotated[Optional[float], opt("--bore", help="Shaft diameter, mm (a hex bore: across flats); "
                                                     "0 for none.", shown="8")]
BoreShapeOpt = Annotated[Optional[BoreShape], opt(
    "--bore-shape", help="Shaft hole: round, d-flat, keyway (DIN 6885) or hex, its key or flat "
                         "at --key-angle from the timing mark.", shown="round")]
FlatDepth = Annotated[Optional[float], opt("--flat-depth", help="D-flat depth from the bore, mm.",
                                           shown="0.1 x bore")]
KeyWidth = Annotated[Optional[float], opt("--key-width", help="Keyway width, mm.", shown="DIN 6885 b")]
KeyDepth = Annotated[Optional[float], opt("--key-depth", help="Keyway depth beyond the bore (hub t2), mm.",
                                          shown="DIN 6885 t2")]
KeyAngle = Annotated[Optional[float], opt("--key-angle", help="Angle of the key, flat or hex flat from "
                                                              "the timing mark, deg (CCW from the top).",
                                          shown="0")]
MarkDepth = Annotated[Optional[float], opt("--mark-depth", help="Timing mark engraving depth, mm; 0 "
                                                                "for none.", shown="0.5")]
Lighten = Annotated[bool, opt("--lighten", help="Cut spoked pockets into the wheel (and the pinion "
                                                  "where it has room), keeping a 2.5 module rim.")]
Chamfer = Annotated[Optional[float], opt(
    "--chamfer", help="45 deg chamfer of the top and bottom edges (teeth, bore, pockets; with a "
                      "hub not the bore's top edge), mm; 0 for none. With --printer it replaces "
                      "the elephant-foot inset, so it must be 0 or at least that inset plus its "
                      "height.", shown="the --printer's chamfer, else 0")]
HubD = Annotated[Optional[float], opt("--hub-d", help="Hub (boss) diameter on the top face, mm.")]
HubLength = Annotated[Optional[float], opt("--hub-length", help="Hub height above the top face, mm.",
                                           shown="8 with --hub-d")]
SetScrew = Annotated[Optional[str], opt("--set-screw", help="Radial set screw through the hub along the "
                                                          "key, with a captive nut slot: M2..M6.",
                                        callback=None)]
TeethOpt = Annotated[Optional[Teeth], opt(
    "--teeth", help="generated: conjugate teeth (SPEC §9); paper: the source's sector "
                    "involutes (SPEC §5).", shown="generated")]
PressureAngle = Annotated[Optional[float], opt(
    "--pressure-angle", help="Rack pressure angle, deg (generated).", shown="20")]
Addendum = Annotated[Optional[float], opt("--addendum", help="Addendum, x module (generated).", shown="1.0")]
Dedendum = Annotated[Optional[float], opt("--dedendum", help="Dedendum, x module (generated).",
                                          shown="1.25")]
Fillet = Annotated[Optional[float], opt("--fillet", help="Rack tip fillet radius, x module (generated).",
                                        shown="0.25")]
Clearance = Annotated[Optional[float], opt(
    "--clearance", help="Tip clearance of the wheel's spaces below the pinion's tips, "
                        "x module (generated).", shown="0.25")]
CornerOpt = Annotated[Optional[Corner], opt(
    "--corner", help="Centre a pinion space or tooth on each pitch-curve corner "
                     "(generated).", shown="space")]
Tilt = Annotated[Optional[float], opt(
    "--tilt", help="Tilt of the rack teeth towards the radius, as a fraction of the "
                   "pitch-curve slope (generated).", shown="0.6")]


def gears(
    a: A = None, b: B = None, c: C = None, r_min: RMin = None, z: Z = None, turns: Turns = None,
    center_distance: CenterDistance = None, install_distance: InstallDistance = None,
    module: Module = None, backlash: Backlash = None, thickness: Thickness = None,
    bore: Bore = None, bore_shape: BoreShapeOpt = None, flat_depth: FlatDepth = None,
    key_width: KeyWidth = None, key_depth: KeyDepth = None, key_angle: KeyAngle = None,
    mark_depth: MarkDepth = None, lighten: Lighten = False, chamfer: Chamfer = None,
    hub_d: HubD = None, hub_length: HubLength = None, set_screw: SetScrew = None,
    fmt: Format = MeshFormat.both, out: Out = Path("wheelstep-out"), profile: Profile = None,
    printer: Printer = None, teeth: TeethOpt = None, pressure_angle: PressureAngle = None,
    addendum: Addendum = None, dedendum: Dedendum = None, fillet: Fillet = None,
    clearance: Clearance = None, blend: Blend = None, corner: CornerOpt = None, tilt: Tilt = None,
    law_csv: LawCsv = None, allow_interference: AllowInterference = False,
    plot: Plot = None, gif: Gif = None, dxf: Dxf = False, svg: Svg = False, step: Step = False,
    force: Force = False, tolerance: Tolerance = False, fit: FitChoice = None, slice_: Slice = False,
    json: Json = False, dry_run: DryRun = False, quiet: Quiet = False, verbose: Verbose = False,
) -> None:
    """Write the gear pair as printable STL/3MF meshes, gears.json and the exports asked for.

    The written meshes are checked first (SPEC §10); overlapping teeth are refused, nothing
    written (generated teeth: exit 2 with what to set; paper teeth: exit 1), unless
    --allow-interference. Generated teeth roll at --center-distance
    (or the distance a --module fits, SPEC §9) and are checked at --install-distance. Each
    gear carries an engraved timing mark; gears.json states the assembly phase the marks
    and keyed bores build in."""
    show = Output(json, quiet, verbose)
    spec = gear_pair_spec(profile, a=a, b=b, c=c, r_min=r_min, z=z, turns=turns, center_distance=center_distance,
                          install_distance=install_distance, module=module, backlash=backlash,
                          thickness=thickness, bore=bore, bore_shape=_value(bore_shape),
                          flat_depth=flat_depth, key_width=key_width, key_depth=key_depth,
                          key_angle=key_angle, mark_depth=mark_depth,
                          lighten=lighten or None, chamfer=chamfer, hub_d=hub_d,
                          hub_length=hub_length, set_screw=set_screw, teeth=_value(teeth),
                          pressure_angle=pressure_angle, addendum=addendum, dedendum=dedendum,
                          fillet=fillet, clearance=clearance, blend=blend, corner=_value(corner),
                          tilt=tilt, law_csv=str(law_csv) if law_csv else None)
    show.parameters(vars(spec), profile)
    chosen = _printer(printer)
    _require_slicer(slice_, fmt.value, chosen)
    # --fit, else the fit the printer's band names (batch fits to it too)
    fit_name = fit.value if fit else getattr(getattr(chosen, "band", None), "fit", None)
    source = "--fit" if fit else f"the band of printer {chosen.name}" if fit_name else None
    _make_gears(spec, chosen, show, out, fmt.value, allow_interference, dry_run, force,
                checked_extras(plot, gif, dxf, svg, step),
                (tolerance or fit_name is not None, fit_name, source), slice_, printer,
                _provenance(profile, spec, chamfer))


def _provenance(profile: str | None, spec, chamfer: float | None) -> dict:
    """The pair's fields saying where its design came from: the design profile read (its
    file and SHA-256) and what gave the edge chamfer (the option, else the profile)."""
    from wheelstep_cli.config.profiles import profile_record

    record = profile_record(profile) if profile else None
    chamfer_from = "--chamfer" if chamfer is not None else (
        f"design profile {record['given']}, gears.chamfer" if record and spec.chamfer is not None else None)
    return {"design_profile": record, "chamfer_from": chamfer_from}


def _value(choice):
    """An enum option's value (None when not given)."""
    return choice.value if choice is not None else None


def _printer(name: str | None):
    """The ``--printer`` profile (None: none given)."""
    from wheelstep_cli.config.profiles import load_printer_profile

    return load_printer_profile(name) if name else None


def _require_slicer(slice_: bool, fmt: str, printer) -> None:
    """--slice is refused up front (one line) when PrusaSlicer is not installed, no 3MF
    plate is written or the printer is a resin one (sliced to layers images, not G-code)."""
    if slice_:
        from wheelstep_cli.errors import DesignError
        from wheelstep_cli.parts.slicing import require_slicer

        if fmt == "stl":
            raise DesignError("slice_", "on", "slices the 3MF plates: give --format 3mf or both")
        if printer is not None and printer.technology == "resin":
            raise DesignError("slice_", "on", f"reads back FDM G-code; {printer.name} is a resin printer")
        require_slicer()


def _make_gears(spec, printer, show: Output, out: Path, fmt: str, allow_interference: bool,
                dry_run: bool, force: bool, extras: GearExtras = GearExtras(),
                band: tuple = (False, None), slice_: bool = False, printer_given: str | None = None,
                provenance: dict | None = None) -> None:
    """Build, check, write (unless refused or a dry run) and report the pair of ``spec``;
    ``band`` = (check over the printer's band, the fit or None[, where the fit comes from]);
    ``slice_``: slice the plates and check the G-code; ``printer_given``: --printer as given;
    ``provenance``: where the design came from, as the pair's report states it (:func:`_provenance`)."""
    from dataclasses import replace

    import typer

    from wheelstep_cli.cli.commands.gears_checks import (checked_pair, collisions_first, printable_or_remedied,
                                                         require_height_first, warn_no_printed_play,
                                                         warn_of_the_figures)
    from wheelstep_cli.cli.progress import with_progress
    from wheelstep_cli.parts.bound_figures import bounds_verdict
    from wheelstep_cli.parts.gear_exports import export_files, picture_files
    from wheelstep_cli.parts.gear_pair import gear_pair_files, gear_pair_report
    from wheelstep_cli.parts.mesh_check import speed_words

    collisions_first(show, out, fmt, extras, force)
    bed = require_height_first(spec, printer, fmt, band[1] is not None)
    pair, record, tolerance, check = checked_pair(spec, printer, show, allow_interference, band, bed)
    printable_or_remedied(pair, spec, printer, show, band, bed)
    pair = replace(pair, **(provenance or {}))
    if tolerance is not None:
        record["tolerance"] = tolerance
    record["bounds"] = bounds_verdict(record, (tolerance or {}).get("fit"))
    files = {**gear_pair_files(pair, out, fmt, record),
             **with_progress(extras.step and not show.quiet, "STEP solids", export_files, pair,
                             extras, out)}
    pictures = with_progress(bool(extras.gif) and not show.quiet, "GIF frames", picture_files, pair,
                             extras, check)
    sliced = _slice(show, pair, record, files, out) if slice_ else None
    # the pictures go where the user named them: a file there this command did not write is
    # refused (unless --force) before anything is written, as for the meshes. Their own
    # record: the output folder's would remove them as stale on a run that draws none
    named = {"plot": extras.plot, "gif": extras.gif}
    show.write_named("gears-pictures", pictures, True, force, **named)
    written = show.write_owned(out, "gears", files, dry_run, force)
    written += show.write_named("gears-pictures", pictures, dry_run, force, **named)
    report = {**gear_pair_report(pair, record), **({"slice": sliced} if sliced else {}),
              **show.written_record(written, dry_run)}
    show.report(report, lambda: _gears_lines(pair, record) + _slice_lines(sliced))
    warn_of_the_figures(show, record, speed_words(pair.spec.law_csv is not None))
    warn_no_printed_play(show, pair, record)
    warn_band_jams(show, record.get("tolerance"), printer_given, rerun=True)
    show.files(written, dry_run, joined=True)
    if sliced is not None and not sliced["meshes"]:
        raise typer.Exit(1)


def _slice(show: Output, pair, record: dict, files: dict, out: Path) -> dict:
    """Slice the plates among ``files``, add the G-code to them and the read-back to gears.json."""
    from wheelstep_cli.cli.progress import with_progress
    from wheelstep_cli.formats.jsonio import json_bytes
    from wheelstep_cli.parts.gear_pair import gear_pair_report
    from wheelstep_cli.parts.slicing import slice_and_check

    gcode, sliced, meshes = with_progress(not show.quiet, "slicing and G-code read-back",
                                          slice_and_check, files, record.get("tolerance"))
    files.update(gcode)
    files[out / "gears.json"] = json_bytes({**gear_pair_report(pair, record), "slice": sliced})
    if not meshes:
        show.warning("WARNING: as PrusaSlicer's G-code prints it, the pair does not mesh "
                     "(see 'slice' in gears.json)")
    return sliced


def _slice_lines(sliced: dict | None) -> list[str]:
    if sliced is None:
        return []
    from wheelstep_cli.parts.slicing import slice_lines

    return slice_lines(sliced)


def _clearance_text(pair) -> str:
    """How a printer's tooth clearance makes up the backlash the teeth were cut with, or a
    fit's inset adds to it (mm)."""
    from wheelstep_cli.parts.tolerance import printed_play

    inset = float(getattr(pair, "inset", 0.0))
    if inset != 0.0:
        # a fit: the printer's clearance is replaced by the outlines' inset
        from wheelstep_cli.parts.fit import inset_words

        drawn = inset_words(inset)
        return f", then both outlines drawn {drawn} along their normals (the fit: j_n {4.0 * inset:+.3f} mm)"
    designed = printed_play(pair)
    if designed is None:
        return ""
    printing = pair.printing
    clearance = float(printing.printer.tooth_clearance)
    if printing.design is not None and printing.design.backlash is None:
        # the default is the most play the ripple bound allows: the clearance is held in it
        return (f" (the design's default, which holds the {clearance:g} mm tooth clearance of printer "
                f"'{printing.printer.name}': {designed:.4g} mm of play once printed)")
    return (f" ({designed:.4g} designed + {clearance:g} tooth clearance of printer "
            f"'{printing.printer.name}')")


def _gears_lines(pair, record: dict) -> list[str]:
    """Both parts, the generated teeth and the meshing check's figures of both flanks."""
    from wheelstep_cli.parts.bound_figures import bounds_line
    from wheelstep_cli.parts.mesh_check import figure_text, flank_line, mounting_line, speed_words

    lines = []
    for part in (pair.pinion, pair.wheel):
        check = pair.checks[part.name]
        size = part.bounds[1] - part.bounds[0]
        lines.append(f"{part.name}: {check.triangles} triangles, {check.volume / 1000:.2f} cm3, "
                     f"{size[0]:.1f} x {size[1]:.1f} x {size[2]:.1f} mm, printable")
    if pair.generated is not None:
        gen = pair.generated
        lines.append(f"generated teeth: z = {gen.pinion_teeth}/{gen.wheel_teeth}, pitch "
                     f"{gen.pitch:.4f} mm, module {gen.module:.4f} mm, rolling at "
                     f"{gen.center_distance:g} mm"
                     + (f" (the centre distance module {pair.spec.module:g} mm fits)"
                        if pair.spec.module is not None else "")
                     + _opening_text(pair)
                     + f", backlash j_n = {gen.cutter.backlash:.4g} mm" + _clearance_text(pair))
    speed = speed_words(pair.spec.law_csv is not None)
    lines.append(f"meshing at {pair.mounted_distance:g} mm: backlash "
                 f"{figure_text(record['backlash_min_mm'], '.3f')}.."
                 f"{figure_text(record['backlash_max_mm'], '.3f')}"
                 f" mm on the wheel pitch curve, interference depth {record['max_penetration_mm']:.3f} mm, the law's own "
                 f"{speed} ripple {record['law_hub_speed_ripple_pct']:.2f} %")
    own = record.get("law_hub_speed_ripple_pct", 0.0)
    # a fit's inset outlines carry the print compensation: their figures are not the design's
    drawn = " (as drawn, with the fit's inset)" if float(getattr(pair, "inset", 0.0)) != 0.0 else ""
    lines.extend(f"  {flank_line(side, record[side], own, speed, drawn)}" for side in ("drive", "coast"))
    if "mounting" in record:
        lines.append(f"  {mounting_line(record['mounting'])}")
    if "bounds" in record:
        lines.append(f"  {bounds_line(record['bounds'])}")
    if "tolerance" in record:
        from wheelstep_cli.parts.tolerance_cli import tolerance_lines

        lines.extend(tolerance_lines(record["tolerance"]))
    return lines + _chamfer_lines(pair) + _lighten_lines(pair)


def _chamfer_lines(pair) -> list[str]:
    """The edge chamfer (mm) and where it came from, when there is one or a printer."""
    from wheelstep_cli.parts.gear_pair import chamfer_report

    chamfer = chamfer_report(pair)
    if not chamfer["mm"] and pair.printing is None:
        return []
    return [f"chamfer {chamfer['mm']:g} mm ({chamfer['from']}); elephant-foot inset "
            f"{chamfer['elephant_foot_inset']}"]


def _opening_text(pair) -> str:
    """The installed distance and the normal backlash (mm) its opening adds, when the pair
    is not mounted where it rolls."""
    import math

    if not pair.opening:
        return ""
    added = 2.0 * pair.opening * math.sin(pair.generated.cutter.pressure_angle)
    return (f", mounted at {pair.mounted_distance:g} mm (opening {pair.opening:+.3f} mm: about "
            f"{added:+.3f} mm of normal backlash)")


def _lighten_lines(pair) -> list[str]:
    """What --lighten saved per gear (cm3, g)."""
    if not pair.spec.lighten:
        return []
    from wheelstep_cli.parts.gear_pair import gear_pair_report

    saved = gear_pair_report(pair)["lighten"]
    return [f"lighten: {name} {saved[name]['pockets']} pockets, {saved[name]['volume_saved_cm3']:.1f} "
            f"cm3 / {saved[name]['mass_saved_g']:.1f} g saved ({saved['density_from']})"
            for name in ("pinion", "wheel")]


def register(app) -> None:
    app.command("gears")(gears)
