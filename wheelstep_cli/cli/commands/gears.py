"""Commands for the non-circular gear pair: ``pitch``, ``teeth``, ``gears``."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated, Optional

from wheelstep_cli.cli.options import (A, B, Blend, C, CenterDistance, DryRun, Force, Format, Json, LawCsv,
                                       MeshFormat, Out, Printer, Profile, Quiet, Turns, Verbose, Z, opt)
from wheelstep_cli.cli.output import Output
from wheelstep_cli.config.resolve import gear_pair_spec
from wheelstep_cli.config.specs import Corner, Teeth


Module = Annotated[Optional[float], opt("--module", "-m", help="Module (tooth height unit), mm.",
                                        shown="2")]
Backlash = Annotated[Optional[float], opt("--backlash", help="Normal backlash j_n, mm.",
                                          shown="0.25 x module")]


def pitch(a: A = None, b: B = None, c: C = None, z: Z = None, turns: Turns = None,
          center_distance: CenterDistance = None, profile: Profile = None,
          json: Json = False, quiet: Quiet = False, verbose: Verbose = False) -> None:
    """Print the equal-arc sector partition of one carrier quarter (SPEC §4)."""
    from wheelstep_cli.parts.gear_tables import pitch_report

    out = Output(json, quiet, verbose)
    spec = gear_pair_spec(profile, a=a, b=b, c=c, z=z, turns=turns, center_distance=center_distance)
    out.parameters(vars(spec))
    report = pitch_report(spec)
    out.report(report, lambda: _pitch_lines(report))


def _pitch_lines(report: dict) -> list[str]:
    """The sector table: one row per sector, degrees and mm."""
    lines = [f"u = {report['u']:.5f}   common arc l = {report['arc_mm']:.4f} mm   "
             f"{len(report['sectors'])} sectors per carrier quarter",
             f"{'i':>3} {'phi_i':>8} {'dphi_i':>7} {'r_Hi':>8} {'theta_i':>8} {'dtheta_i':>8} {'r_i':>7}"]
    for row in report["sectors"]:
        lines.append(f"{row['i']:>3} {row['phi_deg']:8.2f} {row['dphi_deg']:7.2f} "
                     f"{row['r_wheel_mm']:8.2f} {row['theta_deg']:8.2f} {row['dtheta_deg']:8.2f} "
                     f"{row['r_pinion_mm']:7.2f}")
    return lines + ["(degrees and mm)"]


def teeth(a: A = None, b: B = None, c: C = None, z: Z = None, turns: Turns = None,
          center_distance: CenterDistance = None, module: Module = None,
          backlash: Backlash = None, profile: Profile = None,
          json: Json = False, quiet: Quiet = False, verbose: Verbose = False) -> None:
    """Print the sector-involute tooth points of both gears (SPEC §5)."""
    from wheelstep_cli.parts.gear_tables import teeth_report

    out = Output(json, quiet, verbose)
    spec = gear_pair_spec(profile, a=a, b=b, c=c, z=z, turns=turns, center_distance=center_distance,
                          module=module, backlash=backlash)
    out.parameters(vars(spec))
    report = teeth_report(spec)
    out.report(report, lambda: _teeth_lines(report))


def _teeth_lines(report: dict) -> list[str]:
    """Per gear: one row per sector of ``left/right@radius`` for each tooth point."""
    from wheelstep_cli.parts.gear_tables import FLANK_ANGLES

    lines = []
    for gear, angle in FLANK_ANGLES.items():
        lines.append(f"{gear}: flank 1 {angle}_ij / flank 2 {angle}_sij (deg) at r_ij (mm), j = 1..5")
        for sector in report[gear]:
            cells = "  ".join(f"{p[f'{angle}_deg']:8.2f}/{p[f'{angle}_s_deg']:8.2f}@{p['r_mm']:.2f}"
                              for p in sector["points"])
            lines.append(f"{sector['i']:>3}  {cells}")
    return lines


def gears(
    a: A = None, b: B = None, c: C = None, z: Z = None, turns: Turns = None,
    center_distance: CenterDistance = None,
    install_distance: Annotated[Optional[float], opt("--install-distance",
                                                     help="Installed centre distance, mm.",
                                                     shown="144")] = None,
    module: Module = None, backlash: Backlash = None,
    thickness: Annotated[Optional[float], opt("--thickness", help="Face width, mm.",
                                              shown="10")] = None,
    bore: Annotated[Optional[float], opt("--bore", help="Shaft bore diameter, mm; 0 for none.",
                                         shown="8")] = None,
    fmt: Format = MeshFormat.both, out: Out = Path("wheelstep-out"), profile: Profile = None,
    printer: Printer = None,
    teeth: Annotated[Optional[Teeth], opt(
        "--teeth", help="generated: conjugate teeth (SPEC §9); paper: the source's sector "
                        "involutes (SPEC §5).", shown="generated")] = None,
    pressure_angle: Annotated[Optional[float], opt(
        "--pressure-angle", help="Rack pressure angle, deg (generated).", shown="20")] = None,
    addendum: Annotated[Optional[float], opt(
        "--addendum", help="Addendum, x module (generated).", shown="1.0")] = None,
    dedendum: Annotated[Optional[float], opt(
        "--dedendum", help="Dedendum, x module (generated).", shown="1.25")] = None,
    fillet: Annotated[Optional[float], opt(
        "--fillet", help="Rack tip fillet radius, x module (generated).", shown="0.25")] = None,
    clearance: Annotated[Optional[float], opt(
        "--clearance", help="Tip clearance of the wheel's spaces below the pinion's tips, "
                            "x module (generated).", shown="0.25")] = None,
    blend: Blend = None,
    corner: Annotated[Optional[Corner], opt(
        "--corner", help="Centre a pinion space or tooth on each pitch-curve corner "
                         "(generated).", shown="space")] = None,
    tilt: Annotated[Optional[float], opt(
        "--tilt", help="Tilt of the rack teeth towards the radius, as a fraction of the "
                       "pitch-curve slope (generated).", shown="0.6")] = None,
    law_csv: LawCsv = None,
    allow_interference: Annotated[bool, opt(
        "--allow-interference", help="Write the pair even if the meshing check finds "
                                     "overlapping teeth (the paper method's pair does, at the "
                                     "shoe handovers).")] = False,
    force: Force = False,
    json: Json = False, dry_run: DryRun = False, quiet: Quiet = False, verbose: Verbose = False,
) -> None:
    """Write the non-circular gear pair as printable STL/3MF meshes and gears.json.

    The written meshes are checked first (SPEC §10); overlapping teeth are refused (exit 1,
    nothing written) unless --allow-interference. Generated teeth roll at the installed
    distance, their module following from the perimeter and --z; or at the distance a
    --module fits (SPEC §9)."""
    show = Output(json, quiet, verbose)
    spec = gear_pair_spec(profile, a=a, b=b, c=c, z=z, turns=turns, center_distance=center_distance,
                          install_distance=install_distance, module=module, backlash=backlash,
                          thickness=thickness, bore=bore, teeth=teeth.value if teeth else None,
                          pressure_angle=pressure_angle, addendum=addendum, dedendum=dedendum,
                          fillet=fillet, clearance=clearance, blend=blend,
                          corner=corner.value if corner else None,
                          tilt=tilt, law_csv=str(law_csv) if law_csv else None)
    show.parameters(vars(spec))
    _make_gears(spec, _printer(printer), show, out, fmt.value, allow_interference, dry_run, force)


def _printer(name: str | None):
    """The ``--printer`` profile (None: none given)."""
    from wheelstep_cli.config.profiles import load_printer_profile

    return load_printer_profile(name) if name else None


def _make_gears(spec, printer, show: Output, out: Path, fmt: str, allow_interference: bool,
                dry_run: bool, force: bool) -> None:
    """Build, check, write (unless refused or a dry run) and report the pair of ``spec``."""
    import typer

    from wheelstep_cli.cli.progress import with_progress
    from wheelstep_cli.parts.gear_pair import gear_pair_files, gear_pair_report
    from wheelstep_cli.parts.kinds import build_for_printer
    from wheelstep_cli.parts.mesh_bounds import require_within_bounds
    from wheelstep_cli.parts.mesh_check import check_gear_pair, meshing_record

    pair = build_for_printer("gear-pair", spec, printer)
    record = meshing_record(with_progress(not show.quiet, "meshing check", check_gear_pair, pair))
    if record["interference"] and not allow_interference:
        show.error(f"wheelstep: refused: the teeth interfere at {record['interfering_poses']} of "
                   f"{record['samples']} poses at {record['distance_mm']:g} mm (max overlap "
                   f"{record['max_overlap_area_mm2']:.3f} mm2); nothing written "
                   "(--allow-interference writes them anyway)")
        raise typer.Exit(1)
    require_within_bounds(pair, record)
    files = gear_pair_files(pair, out, fmt, record)
    written = show.write_owned(out, "gears", files, dry_run, force)
    report = {**gear_pair_report(pair, record), "written": [] if dry_run else [str(p) for p in written]}
    show.report(report, lambda: _gears_lines(pair, record))
    _warn_interference(show, record)
    show.files(written, dry_run, joined=True)


def _gears_lines(pair, record: dict) -> list[str]:
    """Both parts, the generated teeth and the meshing check's figures of both flanks."""
    from wheelstep_cli.parts.mesh_check import flank_line

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
                     + f", backlash j_n = {gen.cutter.backlash:g} mm")
    lines.append(f"meshing at {pair.mounted_distance:g} mm: backlash "
                 f"{_num(record, 'backlash_min_mm', '.3f')}..{_num(record, 'backlash_max_mm', '.3f')}"
                 f" mm, interference depth {record['max_penetration_mm']:.3f} mm, the law's own "
                 f"hub speed ripple {record['law_hub_speed_ripple_pct']:.2f} %")
    lines.extend(f"  {flank_line(side, record[side])}" for side in ("drive", "coast"))
    return lines


def _num(record: dict, key: str, fmt: str) -> str:
    return "n/a" if record[key] is None else format(record[key], fmt)


def _warn_interference(show: Output, record: dict) -> None:
    """A warning line on stderr when the (allowed) teeth interfere."""
    if record["interference"]:
        show.warning(f"WARNING: the teeth interfere at {record['interfering_poses']} of "
                     f"{record['samples']} poses (max overlap {record['max_overlap_area_mm2']:.3f} "
                     f"mm2); pointwise hub speed ripple where they do not (diagnostic): "
                     f"{_num(record, 'diagnostic_pointwise_ripple_clear_pct', '.2f')} %")


def register(app) -> None:
    app.command("pitch")(pitch)
    app.command("teeth")(teeth)
    app.command("gears")(gears)
