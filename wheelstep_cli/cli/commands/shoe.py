"""Commands for the support shoe: ``shoe`` (sizing + printable part) and ``kinematics``."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated, Optional

from wheelstep_cli.cli.options import (A, B, C, DryRun, Force, Format, Json, MeshFormat, Out, Printer, Profile,
                                       Quiet, RMin, Turns, Verbose, opt, plot_option, require_a_file)
from wheelstep_cli.cli.output import Output
from wheelstep_cli.config.resolve import shoe_spec

Plot = plot_option("both speed curves and the sole")


def shoe(
    a: A = None, b: B = None, c: C = None, r_min: RMin = None,
    width: Annotated[Optional[float], opt("--width", help="Shoe width across the track, mm.",
                                          shown="40")] = None,
    strut_diameter: Annotated[Optional[float], opt("--strut-diameter",
                                                   help="Strut (socket) diameter, mm.",
                                                   shown="12")] = None,
    socket_depth: Annotated[Optional[float], opt("--socket-depth",
                                                 help="Socket depth from the top face, mm.",
                                                 shown="25")] = None,
    rim: Annotated[Optional[float], opt("--rim", help="Body height above the sole's ends (top "
                                                      "face above them), mm.", shown="15")] = None,
    fmt: Format = MeshFormat.both, out: Out = Path("wheelstep-out"), profile: Profile = None,
    printer: Printer = None, force: Force = False,
    json: Json = False, dry_run: DryRun = False, quiet: Quiet = False, verbose: Verbose = False,
) -> None:
    """Size the crank mechanism and write the printable support shoe (SPEC §2).

    The sole keeps the hub at a constant height. The part is printed lying on its side:
    the sole curve is in the XY plane, the width along Z, the strut socket a hole along +Y.
    Writes shoe.stl / shoe.3mf, shoe.json, shoe-profile.csv and shoe-profile.dxf (the sole
    in the shoe frame: origin at the strut pivot, Y along the strut).

    Part defaults suit a full-scale plastic prototype (FDM): 40 mm wide, 12 mm strut in a
    25 mm deep socket (a polygon whose flats touch the nominal circle, so the strut fits;
    ream or drill for a press fit), a flat top 15 mm above the sole's ends; at least 2 mm
    of plastic is kept around and under the socket.
    """
    from dataclasses import replace

    from wheelstep_cli.config.profiles import load_printer_profile, profile_record
    from wheelstep_cli.parts.kinds import build_for_printer
    from wheelstep_cli.parts.shoe import shoe_files, shoe_report
    from wheelstep_cli.parts.shoe_bed import shoe_on_its_bed

    show = Output(json, quiet, verbose)
    spec = shoe_spec(profile, a=a, b=b, c=c, r_min=r_min, width=width,
                     strut_diameter=strut_diameter, socket_depth=socket_depth, rim=rim)
    design = spec.design()
    show.parameters({**vars(spec), "c": design.c, "r_min": design.r_min}, profile)
    chosen = load_printer_profile(printer) if printer else None
    built = build_for_printer("shoe", spec, chosen)
    # too large for its plate's bed: the shoe drawn smaller as the remedy
    built = shoe_on_its_bed(built, chosen, fmt.value != "stl", lambda s: build_for_printer("shoe", s, chosen))
    if profile:
        built = replace(built, design_profile=profile_record(profile))
    files = shoe_files(built, out, fmt.value)
    written = show.write_owned(out, "shoe", files, dry_run, force)
    report = shoe_report(built)
    show.report({**report, **show.written_record(written, dry_run)},
                lambda: _shoe_lines(built, report))
    show.files(written, dry_run, joined=True)


def _shoe_lines(built, report: dict) -> list[str]:
    """The mechanism, the hub motion per cycle, the sole table and the part."""
    from wheelstep_cli.mechanism.sole import sole_table

    d = built.design
    lines = [f"mechanism   a = {d.a:.1f}   b = {d.b:.1f}   c = {d.c:.1f} mm   R_min = {d.r_min:.1f} mm",
             f"hub height  Y01 = a - b + c = {d.hub_height:.1f} mm (constant)",
             f"per cycle   X_I = {d.x_walk:.1f} (walking)   X_II = {d.x_roll:.1f} (rolling)   "
             f"X01 = {d.x_cycle:.1f} mm   rolling share {100 * d.roll_share:.2f} %",
             f"sole (shoe frame: origin at the strut pivot, Y along the strut)\n"
             f"{'phi deg':>8} {'X':>8} {'Y':>8} {'rho':>8} {'alpha deg':>9} {'R':>7}  (mm)"]
    lines += ["{:8.1f} {:8.2f} {:8.2f} {:8.2f} {:9.2f} {:7.2f}".format(*row) for row in sole_table(d)]
    check = built.checks["shoe"]
    size = built.part.bounds[1] - built.part.bounds[0]
    lines.append(f"shoe: {check.triangles} triangles, {check.volume / 1000:.2f} cm3, "
                 f"{size[0]:.1f} x {size[1]:.1f} x {size[2]:.1f} mm, "
                 f"{report['part']['socket_floor_mm']:.1f} mm of plastic under the socket, printable")
    return lines


def kinematics(
    a: A = None, b: B = None, c: C = None, r_min: RMin = None, turns: Turns = None,
    motor_rpm: Annotated[float, opt("--motor-rpm",
                                    help="Constant pinion (motor side) speed, rpm.")] = 60.0,
    points: Annotated[int, opt("--points", help="Samples over one shoe cycle.")] = 361,
    rows: Annotated[Optional[int], opt("--rows", help="Table rows printed.",
                                       shown="9, or every sample when --points gives fewer")] = None,
    plot: Plot = None, profile: Profile = None, force: Force = False,
    json: Json = False, dry_run: DryRun = False, quiet: Quiet = False, verbose: Verbose = False,
) -> None:
    """Hub speed over one shoe cycle with a constant-speed motor, without and with the
    non-circular gears (why the gears exist)."""
    from wheelstep_cli.gears.kinematics import check_inputs, hub_speed_study, kinematics_report
    from wheelstep_cli.parts.gear_laws import kinematics_law
    from wheelstep_cli.parts.mechanism_files import kinematics_files

    show = Output(json, quiet, verbose)
    require_a_file(dry_run, force, plot=plot)
    if rows is not None and (json or quiet):
        from wheelstep_cli.errors import DesignError

        raise DesignError("rows", rows, "shapes the printed table, which --json and -q do not "
                                        "print (--json gives every sample)")
    rows = min(9, points) if rows is None else rows     # the default table: 9 rows, or every sample
    check_inputs(motor_rpm, points, rows)
    design = shoe_spec(profile, a=a, b=b, c=c, r_min=r_min).design()
    gears = _profile_gears(profile)
    used = gears.get("turns", 2) if turns is None else turns     # the command line's over the profile's
    law, what = kinematics_law(design, used, gears, turns is not None)
    kin = hub_speed_study(design, used, motor_rpm, points, law)
    show.parameters({"a": design.a, "b": design.b, "c": design.c, "r_min": design.r_min,
                     "turns": kin.turns, "gears_law": what}, profile)
    files = kinematics_files(design, kin, plot, what)
    named = show.write_named("kinematics", files, dry_run, force, plot=plot)
    report = kinematics_report(design, kin, motor_rpm, what)
    show.report(report, lambda: _kinematics_lines(report, rows))
    show.files(named, dry_run)


def _seconds(time: float) -> str:
    """A time in seconds to the millisecond, or to 3 digits when shorter than 10 ms (a fast
    motor's cycle printed as 0.000 s)."""
    return f"{time:.3f}" if time >= 0.01 else f"{time:.3g}"


def _kinematics_lines(report: dict, rows: int) -> list[str]:
    """The cycle, a table of ``rows`` samples and both ripples."""
    from wheelstep_cli.gears.kinematics import table_rows

    curve = report["curve"]
    lines = [f"a = {report['a_mm']:g}  b = {report['b_mm']:g}  c = {report['c_mm']:g} mm, motor "
             f"{report['motor_rpm']:g} rpm, {report['turns']:g} pinion turn{'' if report['turns'] == 1 else 's'} per carrier turn: one "
             f"shoe cycle {_seconds(report['cycle_time_s'])} s, {report['x_cycle_mm']:.1f} mm, mean hub "
             f"speed {report['mean_speed_m_s']:.3f} m/s",
             f"{'phi deg':>8} {'U':>8} {'without m/s':>12} {'with m/s':>10}"]
    for i in table_rows(len(curve["phi_deg"]), rows):
        lines.append(f"{curve['phi_deg'][i]:8.1f} {curve['ratio_u'][i]:8.4f} "
                     f"{curve['without_m_s'][i]:12.3f} {curve['with_m_s'][i]:10.3f}")
    lines.append("U = omega / omega_H = r_H / r: pinion speed per carrier speed at phi (SPEC §3); "
                 "hub speed without gears (the motor on the carrier) and with them")
    lines.append(f"ripple (peak-to-peak / mean): without gears "
                 f"{report['without_gears']['ripple_pct']:.1f} %, with non-circular gears "
                 f"{report['with_gears']['ripple_pct']:.1f} % (gears on {report['with_gears']['law']})")
    return lines


def _profile_gears(profile: str | None) -> dict:
    """The values a design profile's ``gears:`` section gives (none without a profile); the
    profile is checked whole by its model, and a gears section as ``gears --profile`` checks
    it (the hub speed of gears that cannot be made is no answer)."""
    from wheelstep_cli.config.profiles import load_design_profile
    from wheelstep_cli.config.resolve import gear_pair_spec

    values = load_design_profile(profile).values("gears") if profile else {}
    if values:
        gear_pair_spec(profile)
    return values


def register(app) -> None:
    app.command("shoe")(shoe)
    app.command("kinematics")(kinematics)
