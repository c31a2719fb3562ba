"""Commands for the support shoe: ``shoe`` (sizing + printable part) and ``kinematics``."""

from __future__ import annotations

from pathlib import Path
from typing import Optional

import typer

from wheelstep_cli.cli.commands.gears import Format
from wheelstep_cli.config.resolve import shoe_spec

Opt = typer.Option


A = Opt(None, "--a", help="Hub axis to crank axes, mm [60].")
B = Opt(None, "--b", help="Crank length, mm [100].")
C = Opt(None, "--c", help="Shoe strut length, mm [R_min - a + 4b = 360].")
RMIN = Opt(None, "--rmin", "--r-min",
           help="Smallest sole curvature radius R_min = a - 4b + c, mm; sizes c [20].")
PROFILE = Opt(None, "--profile", help="Design preset: a name in profiles/ or a YAML path.")
JSON = Opt(False, "--json", help="Print JSON instead of a table.")


def shoe(
    a: Optional[float] = A, b: Optional[float] = B, c: Optional[float] = C,
    r_min: Optional[float] = RMIN,
    width: Optional[float] = Opt(None, "--width", help="Shoe width across the track, mm [40]."),
    strut_diameter: Optional[float] = Opt(
        None, "--strut-diameter", help="Strut (socket) diameter, mm [12]."),
    socket_depth: Optional[float] = Opt(
        None, "--socket-depth", help="Socket depth from the top face, mm [25]."),
    rim: Optional[float] = Opt(
        None, "--rim", help="Body height above the sole's ends (top face above them), mm [15]."),
    fmt: Format = Opt(Format.both, "--format", help="Mesh files to write."),
    out: Path = Opt(Path("wheelstep-out"), "--out", "-o", help="Output folder."),
    dry_run: bool = Opt(False, "--dry-run", help="Compute and check, write nothing."),
    profile: Optional[str] = PROFILE,
    json: bool = JSON,
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
    from wheelstep_cli.formats.atomic import write_files_atomic
    from wheelstep_cli.formats.jsonio import json_text
    from wheelstep_cli.parts.shoe import build_shoe, shoe_files, shoe_report

    spec = shoe_spec(profile, a=a, b=b, c=c, r_min=r_min, width=width, strut_diameter=strut_diameter,
                 socket_depth=socket_depth, rim=rim)
    built = build_shoe(spec)
    files = shoe_files(built, out, fmt.value)
    written = [] if dry_run else write_files_atomic(files)
    report = shoe_report(built)
    if json:
        report["written"] = [str(p) for p in written]
        typer.echo(json_text(report), nl=False)
        return
    d = built.design
    typer.echo(f"mechanism   a = {d.a:.1f}   b = {d.b:.1f}   c = {d.c:.1f} mm   "
               f"R_min = {d.r_min:.1f} mm")
    typer.echo(f"hub height  Y01 = a - b + c = {d.hub_height:.1f} mm (constant)")
    typer.echo(f"per cycle   X_I = {d.x_walk:.1f} (walking)   X_II = {d.x_roll:.1f} (rolling)   "
               f"X01 = {d.x_cycle:.1f} mm   rolling share {100 * d.roll_share:.2f} %")
    typer.echo(f"sole (shoe frame: origin at the strut pivot, Y along the strut)\n"
               f"{'phi deg':>8} {'X':>8} {'Y':>8} {'rho':>8} {'alpha deg':>9} {'R':>7}  (mm)")
    for row in sole_table(d):
        typer.echo("{:8.1f} {:8.2f} {:8.2f} {:8.2f} {:9.2f} {:7.2f}".format(*row))
    part = report["part"]
    check = built.checks["shoe"]
    size = built.part.bounds[1] - built.part.bounds[0]
    typer.echo(f"shoe: {check.triangles} triangles, {check.volume / 1000:.2f} cm3, "
               f"{size[0]:.1f} x {size[1]:.1f} x {size[2]:.1f} mm, socket floor "
               f"{part['socket_floor_mm']:.1f} mm, printable")
    if written:
        typer.echo("wrote " + ", ".join(str(p) for p in written))


def sole_table(design, count: int = 7):
    """Rows (phi deg, X, Y, rho, alpha deg, R) at ``count`` hub angles over the contact, mm."""
    import numpy as np

    from wheelstep_cli.mechanism.sole import contact_angles, sole_curvature_radius, sole_polar, sole_profile

    phi = contact_angles(count)
    xy = sole_profile(design, phi)
    rho, alpha = sole_polar(design, phi)
    return np.column_stack([np.degrees(phi), xy, rho, np.degrees(alpha),
                            sole_curvature_radius(design, phi)])


def kinematics(
    a: Optional[float] = A, b: Optional[float] = B, c: Optional[float] = C,
    r_min: Optional[float] = RMIN,
    turns: Optional[int] = Opt(None, "--turns", "-n",
                               help="Pinion turns per carrier turn, 2 or 4 [profile's gears.turns, else 2]."),
    motor_rpm: float = Opt(60.0, "--motor-rpm", show_default=False,
                           help="Constant pinion (motor side) speed, rpm [60]."),
    points: int = Opt(361, "--points", show_default=False, help="Samples over one shoe cycle [361]."),
    rows: int = Opt(9, "--rows", show_default=False, help="Table rows printed [9]."),
    plot: Optional[Path] = Opt(None, "--plot", help="Write both speed curves and the sole to this PNG."),
    profile: Optional[str] = PROFILE,
    json: bool = JSON,
) -> None:
    """Hub speed over one shoe cycle with a constant-speed motor, without and with the
    non-circular gears (why the gears exist)."""
    import numpy as np

    from wheelstep_cli.errors import require
    from wheelstep_cli.formats.jsonio import json_text
    from wheelstep_cli.gears.kinematics import hub_kinematics

    require(np.isfinite(motor_rpm) and motor_rpm > 0, "motor-rpm", motor_rpm, "must be > 0")
    require(points >= 3, "points", points, "must be >= 3")
    require(rows >= 2, "rows", rows, "must be >= 2")
    design = shoe_spec(profile, a=a, b=b, c=c, r_min=r_min).design()
    if turns is None:
        turns = _profile_turns(profile) if profile else 2
    kin = hub_kinematics(design, motor_rpm * 2.0 * np.pi / 60.0, turns, points)
    result = {
        "a_mm": design.a, "b_mm": design.b, "c_mm": design.c, "r_min_mm": design.r_min,
        "turns": turns, "motor_rpm": motor_rpm, "cycle_time_s": kin.cycle_time,
        "x_cycle_mm": design.x_cycle,
        "mean_speed_m_s": design.x_cycle / kin.cycle_time / 1000.0,
        "without_gears": {"min_m_s": kin.speed_plain.min() / 1000.0,
                          "max_m_s": kin.speed_plain.max() / 1000.0,
                          "ripple_pct": 100.0 * kin.ripple_plain},
        "with_gears": {"min_m_s": kin.speed_geared.min() / 1000.0,
                       "max_m_s": kin.speed_geared.max() / 1000.0,
                       "ripple_pct": 100.0 * kin.ripple_geared},
        "curve": {"phi_deg": np.degrees(kin.phi), "without_m_s": kin.speed_plain / 1000.0,
                  "with_m_s": kin.speed_geared / 1000.0, "ratio_u": kin.ratio},
    }
    if plot is not None:
        from wheelstep_cli.formats.atomic import write_bytes_atomic

        write_bytes_atomic(plot, kinematics_png(design, kin))
    if json:
        typer.echo(json_text(result), nl=False)
        return
    typer.echo(f"a = {design.a:g}  b = {design.b:g}  c = {design.c:g} mm, motor {motor_rpm:g} rpm, "
               f"{turns} pinion turns per carrier turn: one shoe cycle {kin.cycle_time:.3f} s, "
               f"{design.x_cycle:.1f} mm, mean hub speed {result['mean_speed_m_s']:.3f} m/s")
    typer.echo(f"{'phi deg':>8} {'U':>8} {'without m/s':>12} {'with m/s':>10}")
    pick = np.unique(np.linspace(0, points - 1, rows).round().astype(int))
    for i in pick:
        typer.echo(f"{np.degrees(kin.phi[i]):8.1f} {kin.ratio[i]:8.4f} "
                   f"{kin.speed_plain[i] / 1000:12.3f} {kin.speed_geared[i] / 1000:10.3f}")
    typer.echo(f"ripple (peak-to-peak / mean): without gears {100 * kin.ripple_plain:.1f} %, "
               f"with non-circular gears {100 * kin.ripple_geared:.1f} %")
    if plot is not None:
        typer.echo(f"wrote {plot}")


def _profile_turns(profile: str) -> int:
    """Pinion turns per carrier turn from a profile's ``gears:`` section (2 if not set)."""
    from wheelstep_cli.config.profiles import load_profile

    _, data = load_profile(profile)
    gears = data.get("gears") or {}
    turns = gears.get("turns", 2) if isinstance(gears, dict) else 2
    if not isinstance(turns, int):
        from wheelstep_cli.errors import DesignError

        raise DesignError("turns", turns, f"in profile {profile} must be 2 or 4")
    return turns


def kinematics_png(design, kin) -> bytes:
    """PNG: hub speed without/with the gears over one shoe cycle, and the sole (shoe frame)."""
    import io

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np

    from wheelstep_cli.mechanism.sole import contact_angles, sole_profile

    fig, (ax_v, ax_s) = plt.subplots(1, 2, figsize=(11, 4.5), gridspec_kw={"width_ratios": [3, 2]})
    deg = np.degrees(kin.phi)
    ax_v.plot(deg, kin.speed_plain / 1000, label=f"without non-circular gears (ripple {100 * kin.ripple_plain:.1f} %)")
    ax_v.plot(deg, kin.speed_geared / 1000, label=f"with non-circular gears (ripple {100 * kin.ripple_geared:.1f} %)")
    ax_v.set_xlabel("hub angle phi, deg (one shoe in contact)")
    ax_v.set_ylabel("hub speed, m/s")
    ax_v.set_xlim(deg[0], deg[-1])
    ax_v.set_ylim(0, None)
    ax_v.grid(True, alpha=0.3)
    ax_v.legend(loc="lower center")
    ax_v.set_title(f"constant motor speed {kin.motor_speed * 60 / (2 * np.pi):g} rpm")
    sole = sole_profile(design, contact_angles(201))
    ax_s.plot(sole[:, 0], sole[:, 1], lw=2, label="sole")
    ax_s.plot([0, 0], [0, design.c], "k--", lw=1, label="strut")
    ax_s.plot([0], [0], "ko", label="strut pivot")
    ax_s.set_aspect("equal")
    ax_s.invert_yaxis()  # Y of the shoe frame points to the ground
    ax_s.set_xlabel("X, mm")
    ax_s.set_ylabel("Y, mm (shoe frame, along the strut)")
    ax_s.set_title(f"shoe sole, R_min = {design.r_min:g} mm")
    ax_s.grid(True, alpha=0.3)
    ax_s.legend(loc="center right", fontsize="small")
    fig.tight_layout()
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=110, metadata={"Software": None})
    plt.close(fig)
    return buf.getvalue()


def register(app: typer.Typer) -> None:
    app.command("shoe")(shoe)
    app.command("kinematics")(kinematics)
