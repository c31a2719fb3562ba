"""The paper method's tables of the gear pair (SPEC §4, §5): ``pitch`` and ``teeth``."""

from __future__ import annotations

from typing import Annotated, Optional

from wheelstep_cli.cli.options import A, B, C, Json, Profile, Quiet, RMin, Turns, Verbose, Z, opt
from wheelstep_cli.cli.output import Output
from wheelstep_cli.config.resolve import paper_table_spec

# the paper method's tables (pitch, teeth): their own rules, not the generator's
PaperDistance = Annotated[Optional[float], opt(
    "--center-distance", help="Centre distance L_p the paper's sectors roll at, mm (SPEC §4).",
    shown="the installed distance less the paper's 0.5 opening: 143.5 for the source design")]
PaperModule = Annotated[Optional[float], opt("--module", "-m", help="Module of the paper's sector-involute "
                                                                    "teeth, mm (SPEC §5).", shown="2")]
PaperBacklash = Annotated[Optional[float], opt("--backlash", help="Normal backlash j_n of the paper's "
                                                                  "teeth, mm.", shown="0.25 x module")]


def pitch(a: A = None, b: B = None, c: C = None, r_min: RMin = None, z: Z = None, turns: Turns = None,
          center_distance: PaperDistance = None, profile: Profile = None,
          json: Json = False, quiet: Quiet = False, verbose: Verbose = False) -> None:
    """Print the equal-arc sector partition of one carrier quarter (SPEC §4)."""
    from wheelstep_cli.parts.gear_tables import pitch_report

    out = Output(json, quiet, verbose)
    # the sector partition of SPEC §4 is the paper method's, at the distance its sectors roll at
    spec, left_out = paper_table_spec(profile, a=a, b=b, c=c, r_min=r_min, z=z, turns=turns,
                                      center_distance=center_distance)
    parameters = {"a": spec.a, "b": spec.b, "c": spec.c, "z": spec.z, "turns": spec.turns,
                  "center_distance": spec.center_distance}
    out.parameters(parameters)
    _note_left_out(out, left_out)
    # the report says what it was computed for, as the part commands' reports do
    report = {"tool": "wheelstep pitch", "parameters": parameters, **pitch_report(spec)}
    out.report(report, lambda: _pitch_lines(report))


def _note_left_out(out: Output, note: str | None) -> None:
    """Say what of the profile the paper tables leave out (its blend), on stderr."""
    if note is not None:
        out.warning(f"note: {note}")


def _pitch_lines(report: dict) -> list[str]:
    """The sector table: one row per sector, degrees and mm."""
    lines = [f"u = {report['u']:.5f}   common arc l = {report['arc_mm']:.4f} mm   "
             f"{len(report['sectors'])} sectors per carrier quarter",
             f"{'i':>3} {'phi_i':>8} {'dphi_i':>7} {'r_Hi':>8} {'theta_i':>8} {'dtheta_i':>8} {'r_i':>7}"]
    for row in report["sectors"]:
        lines.append(f"{row['i']:>3} {row['phi_deg']:8.2f} {row['dphi_deg']:7.2f} "
                     f"{row['r_wheel_mm']:8.2f} {row['theta_deg']:8.2f} {row['dtheta_deg']:8.2f} "
                     f"{row['r_pinion_mm']:7.2f}")
    # the paper's circular sectors are shorter than the exact pitch curve between the same
    # angles: gears' generated teeth are spaced along the exact curve (a larger pitch)
    return lines + ["(degrees and mm; l is the arc of the paper's circular sectors, SPEC §4: "
                    "`gears` spaces generated teeth along the exact pitch curves, so its pitch is larger)"]


def teeth(a: A = None, b: B = None, c: C = None, r_min: RMin = None, z: Z = None, turns: Turns = None,
          center_distance: PaperDistance = None, module: PaperModule = None,
          backlash: PaperBacklash = None, profile: Profile = None,
          json: Json = False, quiet: Quiet = False, verbose: Verbose = False) -> None:
    """Print the sector-involute tooth points of both gears (SPEC §5)."""
    from wheelstep_cli.parts.gear_tables import teeth_report

    out = Output(json, quiet, verbose)
    # the sector-involute teeth of SPEC §5 are the paper's: their rules, not the generator's
    spec, left_out = paper_table_spec(profile, a=a, b=b, c=c, r_min=r_min, z=z, turns=turns,
                                      center_distance=center_distance, module=module, backlash=backlash)
    parameters = {"a": spec.a, "b": spec.b, "c": spec.c, "z": spec.z, "turns": spec.turns,
                  "center_distance": spec.center_distance, "module": spec.paper_module,
                  "backlash": spec.backlash_mm}
    out.parameters(parameters)
    _note_left_out(out, left_out)
    report = {"tool": "wheelstep teeth", "parameters": parameters, **teeth_report(spec)}
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


def register(app) -> None:
    app.command("pitch")(pitch)
    app.command("teeth")(teeth)
