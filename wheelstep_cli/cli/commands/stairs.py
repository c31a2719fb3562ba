"""``wheelstep stairs``: size a circular-sole mover for a stair, or check a design (SPEC §6)."""

from __future__ import annotations

from pathlib import Path
from typing import Optional

import typer

from wheelstep_cli.errors import DesignError, require

Opt = typer.Option


def _number_list(text: str, param: str) -> list[float]:
    """``"a,b,c"`` or ``"start:stop:step"`` (inclusive) to floats."""
    import numpy as np

    try:
        if ":" in text:
            start, stop, step = (float(v) for v in text.split(":"))
            require(step > 0, param, text, "step must be > 0")
            n = int(np.floor((stop - start) / step + 1e-9)) + 1
            require(1 <= n <= 10000, param, text, "must give 1 to 10000 values")
            return [start + i * step for i in range(n)]
        return [float(v) for v in text.split(",") if v.strip()]
    except ValueError:
        raise DesignError(param, text, "must be numbers 'a,b,c' or 'start:stop:step'") from None


def _rows(kin):
    import numpy as np

    from wheelstep_cli.mechanism.stairs import KINEMATICS_COLUMNS

    out = []
    for row in kin:
        item = dict(zip(KINEMATICS_COLUMNS, (float(v) for v in row)))
        item["phi"] = float(np.degrees(row[0]))
        out.append(item)
    return out


def _print_table(title: str, rows) -> None:
    typer.echo(title)
    typer.echo(f"{'phi':>8} {'X01':>9} {'dX01':>9} {'d2X01':>9} {'Y01':>9} {'dY01':>9} {'d2Y01':>9}")
    for r in rows:
        typer.echo(f"{r['phi']:8.2f} {r['X01']:9.2f} {r['dX01']:9.2f} {r['d2X01']:9.2f} "
                   f"{r['Y01']:9.2f} {r['dY01']:9.2f} {r['d2Y01']:9.2f}")


def _sweep(run, rise, angles, radii, json):
    import numpy as np

    from wheelstep_cli.formats.jsonio import json_text
    from wheelstep_cli.mechanism.stairs import sizing_sweep

    rows = sizing_sweep(run, rise, np.radians(angles), radii)
    if json:
        typer.echo(json_text({"run_mm": run, "rise_mm": rise, "sweep": [
            {"landing_angle_deg": round(float(np.degrees(r["landing"])), 9), "sole_radius_mm": r["sole_radius"],
             "status": r["status"], "b_mm": r["b"], "y1_mm": r["y1"], "a_mm": r["a"]} for r in rows]}), nl=False)
        return
    typer.echo(f"sizing sweep for run l = {run:g} mm, rise h = {rise:g} mm (a = 2b); cells: b / Y1 (mm)")
    width = 22
    typer.echo(f"{'alpha (deg)':>11} " + " ".join(f"{'Y2 = ' + format(r, 'g'):>{width}}" for r in radii))
    for i, al in enumerate(angles):
        cells = []
        for r in rows[i * len(radii):(i + 1) * len(radii)]:
            if r["status"] == "ok":
                cells.append(f"{r['b']:.1f} / {r['y1']:.1f}")
            elif r["status"] == "singular":
                cells.append("singular")
            else:
                cells.append(f"n/a ({r['status']})")
        typer.echo(f"{al:11.1f} " + " ".join(f"{c:>{width}}" for c in cells))
    typer.echo("n/a: that size would be negative (no physical meaning); "
               "singular: alpha = 15 + k*60 deg, the equations have no unique solution")


def stairs(
    run: float = Opt(300.0, "--run", help="Stair run (tread going) l, mm."),
    rise: float = Opt(150.0, "--rise", help="Stair rise h, mm."),
    sole_radius: float = Opt(70.0, "--sole-radius", help="Circular sole radius Y2, mm."),
    landing_angle: float = Opt(-90.0, "--landing-angle", help="Hub angle alpha at which a shoe lands on the next step, deg."),
    step: float = Opt(5.0, "--step", help="Hub-angle step of the kinematics tables, deg."),
    a: Optional[float] = Opt(None, "--a", help="Check a given design: hub to crank axes a, mm."),
    b: Optional[float] = Opt(None, "--b", help="Check a given design: crank b, mm."),
    y1: Optional[float] = Opt(None, "--y1", help="Check a given design: strut radius vector Y1, mm."),
    y2: Optional[float] = Opt(None, "--y2", help="Check a given design: sole radius Y2, mm."),
    tol: float = Opt(1.0, "--tol", help="Check: allowed miss of run and rise per cycle, mm."),
    sweep: bool = Opt(False, "--sweep", help="Print the sizing over landing angles and sole radii instead."),
    sweep_angles: str = Opt("-180:0:15", "--sweep-angles", help="Sweep landing angles, deg: 'start:stop:step' or a list."),
    sweep_radii: str = Opt("40,70,100,150,192", "--sweep-radii", help="Sweep sole radii, mm: a list or 'start:stop:step'."),
    plot: Optional[Path] = Opt(None, "--plot", help="Write the climb/descent kinematics plot (PNG)."),
    json: bool = Opt(False, "--json", help="Print JSON instead of tables."),
) -> int:
    """Size crank b, strut Y1 and a = 2b for a stair, with climb and descent kinematics (SPEC §6).

    With --a --b --y1 --y2, check that design against the stair instead (exit 1 if it
    cannot climb). With --sweep, tabulate the sizing over landing angles and sole radii.
    """
    import numpy as np

    from wheelstep_cli.formats.jsonio import json_text
    from wheelstep_cli.mechanism import stairs as st

    require(run > 0, "run", run, "must be > 0 mm")
    require(rise > 0, "rise", rise, "must be > 0 mm")
    require(0.01 <= step <= 45, "step", step, "must be in [0.01, 45] deg")
    if sweep:
        angles = _number_list(sweep_angles, "sweep-angles")
        radii = _number_list(sweep_radii, "sweep-radii")
        require(len(radii) > 0 and min(radii) > 0, "sweep-radii", sweep_radii, "must be > 0 mm")
        _sweep(run, rise, angles, radii, json)
        return 0

    given = {"a": a, "b": b, "y1": y1, "y2": y2}
    checking = any(v is not None for v in given.values())
    if checking:
        for name, value in given.items():
            require(value is not None, name, "missing", "a design check needs all of --a --b --y1 --y2")
            require(value > 0, name, value, "must be > 0 mm")
        require(tol > 0, "tol", tol, "must be > 0 mm")
        design = st.StairDesign(a=a, b=b, y1=y1, y2=y2)
    else:
        design = st.size_for_stair(run, rise, sole_radius, np.radians(landing_angle))

    alpha = float(np.radians(landing_angle))
    beta = st.descent_landing(alpha)
    climb = st.hub_kinematics(design, st.cycle_angles(alpha, np.radians(step)), alpha)
    descent = st.hub_kinematics(design, st.cycle_angles(beta, np.radians(step)), beta)
    adv, ris = st.cycle_motion(design, alpha)
    report = {"b_mm": design.b, "y1_mm": design.y1, "a_mm": design.a, "y2_mm": design.y2,
              "run_mm": run, "rise_mm": rise, "landing_angle_deg": landing_angle,
              "descent_landing_angle_deg": float(np.degrees(beta)),
              "advance_per_cycle_mm": float(adv), "rise_per_cycle_mm": float(ris),
              "units": {"phi": "deg", "X01": "mm", "Y01": "mm", "dX01": "mm/rad", "dY01": "mm/rad",
                        "d2X01": "mm/rad^2", "d2Y01": "mm/rad^2"},
              "climb": _rows(climb), "descent": _rows(descent)}
    check = None
    if checking:
        check = st.check_climb(design, run, rise, tol)
        report["check"] = {
            "climbs": check.climbs, "tolerance_mm": tol,
            "landing_for_rise_deg": [float(np.degrees(v)) for v in check.landing_for_rise],
            "advance_at_rise_mm": list(check.advance_at_rise),
            "landing_for_run_deg": [float(np.degrees(v)) for v in check.landing_for_run],
            "rise_at_run_mm": list(check.rise_at_run),
            "best_landing_deg": float(np.degrees(check.best_landing)),
            "best_advance_mm": check.best_advance, "best_rise_mm": check.best_rise,
        }

    files = {}
    if plot is not None:
        from wheelstep_cli.render.mechanism_plots import stairs_png

        what = "check of" if checking else "sized"
        title = (f"{what} a = {design.a:.1f}, b = {design.b:.1f}, Y1 = {design.y1:.1f}, Y2 = {design.y2:.1f} mm; "
                 f"stair {run:g} x {rise:g} mm, landing {landing_angle:g} deg")
        files[plot] = stairs_png(climb, descent, st.hub_path(design, alpha, adv, ris, 3),
                                 st.hub_path(design, beta, *st.cycle_motion(design, beta), 3), title,
                                 (float(adv), float(ris)))
    if files:
        from wheelstep_cli.formats.atomic import write_files_atomic

        write_files_atomic(files)

    if json:
        typer.echo(json_text(report), nl=False)
    else:
        if checking:
            typer.echo(f"design a = {design.a:g}, b = {design.b:g}, Y1 = {design.y1:g}, Y2 = {design.y2:g} mm "
                       f"against stair run {run:g} x rise {rise:g} mm")
        else:
            typer.echo(f"stair run l = {run:g} mm, rise h = {rise:g} mm, sole radius Y2 = {sole_radius:g} mm, "
                       f"landing alpha = {landing_angle:g} deg")
            typer.echo(f"crank b = {design.b:.2f} mm   strut Y1 = {design.y1:.2f} mm   a = 2b = {design.a:.2f} mm")
        typer.echo(f"per cycle (landing {landing_angle:g} -> {landing_angle + 90:g} deg): "
                   f"advance {adv:.2f} mm, rise {ris:.2f} mm")
        _print_table(f"climb (landing alpha = {landing_angle:g} deg); X01, Y01 mm; d.. per rad of phi (deg)", report["climb"])
        _print_table(f"descent (landing beta = -90 - alpha = {np.degrees(beta):g} deg)", report["descent"])
        if check is not None:
            _print_check(check, run, rise)
        for path in files:
            typer.echo(f"wrote {path}")
    if check is not None and not check.climbs:
        return 1
    return 0


def _print_check(check, run, rise) -> None:
    import numpy as np

    if check.climbs:
        typer.echo(f"CLIMBS: landing at {np.degrees(check.best_landing):.2f} deg one cycle advances "
                   f"{check.best_advance:.2f} mm and rises {check.best_rise:.2f} mm (within {check.tolerance:g} mm)")
        return
    typer.echo(f"CANNOT CLIMB a {run:g} x {rise:g} mm stair: no landing angle makes one cycle both "
               f"advance {run:g} mm and rise {rise:g} mm.")
    _echo_section("rises", rise, "advances", check.landing_for_rise, check.advance_at_rise)
    _echo_section("advances", run, "rises", check.landing_for_run, check.rise_at_run)
    typer.echo(f"  closest: landing {np.degrees(check.best_landing):.1f} deg advances {check.best_advance:.1f} mm "
               f"and rises {check.best_rise:.1f} mm")


def register(app: typer.Typer) -> None:
    app.command("stairs")(stairs)


def _echo_section(given: str, amount: float, other: str, landings, values) -> None:
    """One line of the climb check: where a cycle ``given`` ``amount`` mm, how far it ``other``."""
    import numpy as np

    if len(landings):
        typer.echo(f"  where a cycle {given} {amount:g} mm it {other} " + ", ".join(
            f"{v:.1f} mm (landing {np.degrees(al):.1f} deg)" for al, v in zip(landings, values)))
    else:
        noun = {"rises": "a rise", "advances": "an advance"}[given]
        typer.echo(f"  no landing angle gives {noun} of {amount:g} mm per cycle")
