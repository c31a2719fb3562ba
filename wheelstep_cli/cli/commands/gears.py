"""Commands for the non-circular gear pair: ``pitch``, ``teeth``, ``gears``."""

from __future__ import annotations

from enum import Enum
from pathlib import Path
from typing import Optional

import typer

from wheelstep_cli.config.resolve import gear_pair_spec

Opt = typer.Option


class Teeth(str, Enum):
    generated = "generated"
    paper = "paper"


class Corner(str, Enum):
    space = "space"
    tooth = "tooth"


class Format(str, Enum):
    stl = "stl"
    threemf = "3mf"
    both = "both"


# Shared option declarations (defaults None so a profile can fill what is not given).
A = Opt(None, "--a", help="Hub axis to crank axes, mm [60].")
B = Opt(None, "--b", help="Crank length, mm [100].")
C = Opt(None, "--c", help="Shoe strut length, mm [360].")
Z = Opt(None, "--z", help="Pinion tooth count; the wheel gets z*n/2 [48].")
TURNS = Opt(None, "--turns", "-n", help="Pinion turns per carrier turn, 2 or 4 [2].")
CENTER = Opt(None, "--center-distance", help="Design centre distance L_p, mm [143.5].")
INSTALL = Opt(None, "--install-distance", help="Installed centre distance, mm [144].")
MODULE = Opt(None, "--module", "-m", help="Module (tooth height unit), mm [2].")
BACKLASH = Opt(None, "--backlash", help="Normal backlash j_n, mm [0.25 x module].")
PROFILE = Opt(None, "--profile", help="Design preset: a name in profiles/ or a YAML path.")
JSON = Opt(False, "--json", help="Print JSON instead of a table.")


def pitch(
    a: Optional[float] = A, b: Optional[float] = B, c: Optional[float] = C,
    z: Optional[int] = Z, turns: Optional[int] = TURNS,
    center_distance: Optional[float] = CENTER, profile: Optional[str] = PROFILE,
    json: bool = JSON,
) -> None:
    """Print the equal-arc sector partition of one carrier quarter (SPEC §4)."""
    from wheelstep_cli.gears.sectors import sector_partition, sectors_per_quarter
    from wheelstep_cli.formats.jsonio import json_text
    from wheelstep_cli.parts.gear_pair import partition_rows

    spec = gear_pair_spec(profile, a=a, b=b, c=c, z=z, turns=turns, center_distance=center_distance)
    law = spec.law()
    part = sector_partition(law, sectors_per_quarter(spec.z, spec.turns), spec.center_distance)
    rows = partition_rows(part)
    if json:
        typer.echo(json_text({"u": law.u, "arc_mm": part.arc, "sectors": rows}), nl=False)
        return
    typer.echo(f"u = {law.u:.5f}   common arc l = {part.arc:.4f} mm   "
               f"{part.count} sectors per carrier quarter")
    typer.echo(f"{'i':>3} {'phi_i':>8} {'dphi_i':>7} {'r_Hi':>8} {'theta_i':>8} {'dtheta_i':>8} {'r_i':>7}")
    for row in rows:
        typer.echo(f"{row['i']:>3} {row['phi_deg']:8.2f} {row['dphi_deg']:7.2f} {row['r_wheel_mm']:8.2f} "
                   f"{row['theta_deg']:8.2f} {row['dtheta_deg']:8.2f} {row['r_pinion_mm']:7.2f}")
    typer.echo("(degrees and mm)")


def teeth(
    a: Optional[float] = A, b: Optional[float] = B, c: Optional[float] = C,
    z: Optional[int] = Z, turns: Optional[int] = TURNS,
    center_distance: Optional[float] = CENTER, module: Optional[float] = MODULE,
    backlash: Optional[float] = BACKLASH, profile: Optional[str] = PROFILE,
    json: bool = JSON,
) -> None:
    """Print the sector-involute tooth points of both gears (SPEC §5)."""
    import numpy as np

    from wheelstep_cli.gears.paper_teeth import check_tooth_form, pinion_flanks, wheel_flanks
    from wheelstep_cli.gears.sectors import sector_partition, sectors_per_quarter
    from wheelstep_cli.formats.jsonio import json_text

    spec = gear_pair_spec(profile, a=a, b=b, c=c, z=z, turns=turns, center_distance=center_distance,
                 module=module, backlash=backlash)
    law = spec.law()
    part = sector_partition(law, sectors_per_quarter(spec.z, spec.turns), spec.center_distance)
    form = spec.tooth_form()
    check_tooth_form(part, form)
    tables = {"pinion": (pinion_flanks(part, form), "theta"), "wheel": (wheel_flanks(part, form), "phi")}
    result = {}
    for gear, (flanks, angle) in tables.items():
        result[gear] = [
            {"i": i + 1, "points": [
                {"j": j + 1, f"{angle}_deg": np.degrees(flanks.left[i, j]),
                 f"{angle}_s_deg": np.degrees(flanks.right[i, j]), "r_mm": flanks.radius[i, j]}
                for j in range(flanks.left.shape[1])]}
            for i in range(flanks.left.shape[0])
        ]
    if json:
        typer.echo(json_text(result), nl=False)
        return
    for gear, (flanks, angle) in tables.items():
        typer.echo(f"{gear}: flank 1 {angle}_ij / flank 2 {angle}_sij (deg) at r_ij (mm), j = 1..5")
        for sector in result[gear]:
            cells = "  ".join(f"{p[f'{angle}_deg']:8.2f}/{p[f'{angle}_s_deg']:8.2f}@{p['r_mm']:.2f}"
                              for p in sector["points"])
            typer.echo(f"{sector['i']:>3}  {cells}")


def gears(
    a: Optional[float] = A, b: Optional[float] = B, c: Optional[float] = C,
    z: Optional[int] = Z, turns: Optional[int] = TURNS,
    center_distance: Optional[float] = CENTER, install_distance: Optional[float] = INSTALL,
    module: Optional[float] = MODULE, backlash: Optional[float] = BACKLASH,
    thickness: Optional[float] = Opt(None, "--thickness", help="Face width, mm [10]."),
    bore: Optional[float] = Opt(None, "--bore", help="Shaft bore diameter, mm; 0 for none [8]."),
    fmt: Format = Opt(Format.both, "--format", help="Mesh files to write."),
    out: Path = Opt(Path("wheelstep-out"), "--out", "-o", help="Output folder."),
    profile: Optional[str] = PROFILE,
    teeth: Optional[Teeth] = Opt(None, "--teeth",
                                 help="generated: conjugate teeth (SPEC §9, default); "
                                      "paper: the source's sector involutes (SPEC §5)."),
    pressure_angle: Optional[float] = Opt(None, "--pressure-angle",
                                          help="Rack pressure angle, deg (generated) [20]."),
    addendum: Optional[float] = Opt(None, "--addendum", help="Addendum, x module (generated) [1.0]."),
    dedendum: Optional[float] = Opt(None, "--dedendum", help="Dedendum, x module (generated) [1.25]."),
    fillet: Optional[float] = Opt(None, "--fillet", help="Rack tip fillet radius, x module (generated) [0.25]."),
    blend: Optional[float] = Opt(None, "--blend",
                                 help="Half-width (carrier deg) of the ratio blend at each handover (generated) [0]."),
    corner: Optional[Corner] = Opt(None, "--corner",
                                   help="Centre a pinion space or tooth on each pitch-curve corner (generated) [space]."),
    tilt: Optional[float] = Opt(None, "--tilt",
                                help="Tilt of the rack teeth towards the radius, as a fraction of the "
                                     "pitch-curve slope (generated) [0.6]."),
    law_csv: Optional[Path] = Opt(None, "--law-csv",
                                  help="CSV of driving angle, driven angle (deg) over one period: "
                                       "generate this law instead of the crank law (generated)."),
    allow_interference: bool = Opt(
        False, "--allow-interference",
        help="Write the pair even if the meshing check finds overlapping teeth "
             "(the paper method's pair does, at the shoe handovers)."),
) -> None:
    """Write the non-circular gear pair as printable STL/3MF meshes and gears.json.

    The written meshes are checked first (SPEC §10); a pair whose teeth overlap is
    refused (exit 1, nothing written) unless --allow-interference. Generated teeth
    (default) roll at the installed distance; the module follows from the pitch-curve
    perimeter and --z (--module applies to --teeth paper only)."""
    from wheelstep_cli.cli.commands.meshcheck import _run_with_progress
    from wheelstep_cli.formats.atomic import write_files_atomic
    from wheelstep_cli.parts.gear_pair import build_gear_pair, gear_pair_files
    from wheelstep_cli.parts.mesh_check import check_gear_pair, meshing_record

    spec = gear_pair_spec(profile, a=a, b=b, c=c, z=z, turns=turns, center_distance=center_distance,
                 install_distance=install_distance, module=module, backlash=backlash,
                 thickness=thickness, bore=bore, teeth=teeth.value if teeth else None,
                 pressure_angle=pressure_angle, addendum=addendum, dedendum=dedendum,
                 fillet=fillet, blend=blend, corner=corner.value if corner else None, tilt=tilt,
                 law_csv=str(law_csv) if law_csv else None)
    pair = build_gear_pair(spec)
    meshing = _run_with_progress(check_gear_pair, pair)
    record = meshing_record(meshing)
    if meshing.interferes and not allow_interference:
        typer.echo(f"wheelstep: refused: the teeth interfere at {record['interfering_poses']} of "
                   f"{record['samples']} poses at {spec.install_distance:g} mm (max overlap "
                   f"{record['max_overlap_area_mm2']:.3f} mm2); nothing written "
                   "(--allow-interference writes them anyway)", err=True)
        raise typer.Exit(1)
    written = write_files_atomic(gear_pair_files(pair, out, fmt.value, record))
    for part in (pair.pinion, pair.wheel):
        check = pair.checks[part.name]
        size = part.bounds[1] - part.bounds[0]
        typer.echo(f"{part.name}: {check.triangles} triangles, {check.volume / 1000:.2f} cm3, "
                   f"{size[0]:.1f} x {size[1]:.1f} x {size[2]:.1f} mm, printable")
    if pair.generated is not None:
        gen = pair.generated
        typer.echo(f"generated teeth: z = {gen.pinion_teeth}/{gen.wheel_teeth}, pitch {gen.pitch:.4f} mm, "
                   f"module {gen.module:.4f} mm, rolling at {gen.curves.center_distance:g} mm, "
                   f"backlash j_n = {gen.cutter.backlash:g} mm")
    _echo_meshing(record, spec.install_distance)
    typer.echo("wrote " + ", ".join(str(p) for p in written))


def _echo_meshing(record: dict, distance: float) -> None:
    """One line on the meshing check; a warning line when the teeth interfere."""
    def num(key, fmt):
        return "n/a" if record[key] is None else format(record[key], fmt)

    typer.echo(f"meshing at {distance:g} mm: hub speed ripple {num('hub_speed_ripple_pct', '.2f')} %, "
               f"backlash {num('backlash_min_mm', '.3f')}..{num('backlash_max_mm', '.3f')} mm, "
               f"TE {num('te_peak_to_peak_arcmin', '.2f')}' p-p")
    if record["interference"]:
        typer.echo(f"WARNING: the teeth interfere at {record['interfering_poses']} of "
                   f"{record['samples']} poses (max overlap {record['max_overlap_area_mm2']:.3f} "
                   f"mm2); hub speed ripple where they do not: "
                   f"{num('hub_speed_ripple_clear_pct', '.2f')} %", err=True)


def register(app: typer.Typer) -> None:
    app.command("pitch")(pitch)
    app.command("teeth")(teeth)
    app.command("gears")(gears)
