"""``wheelstep stairs``: size a circular-sole mover for a stair, or check a design (SPEC §6)."""

from __future__ import annotations

from typing import Annotated, Optional

from wheelstep_cli.cli.options import (DryRun, Force, Json, Quiet, Verbose, number_list, opt, plot_option,
                                       require_a_file, require_printed)
from wheelstep_cli.cli.output import Output
from wheelstep_cli.errors import DesignError, require

Plot = plot_option("the climb/descent kinematics plot")


def stairs(
    run: Annotated[float, opt("--run", help="Stair run (tread going) l, mm.")] = 300.0,
    rise: Annotated[float, opt("--rise", help="Stair rise h, mm.")] = 150.0,
    sole_radius: Annotated[Optional[float], opt("--sole-radius", help="Circular sole radius Y2, mm.",
                                                shown="70")] = None,
    landing_angle: Annotated[Optional[float], opt("--landing-angle", help="Hub angle alpha at which "
                                                                          "a shoe lands on the next "
                                                                          "step, deg.",
                                                  shown="-90")] = None,
    step: Annotated[Optional[float], opt("--step", help="Hub-angle step of the kinematics tables, "
                                                        "deg.", shown="5")] = None,
    a: Annotated[Optional[float], opt("--a", help="Check a given design: hub to crank axes "
                                                  "a, mm.")] = None,
    b: Annotated[Optional[float], opt("--b", help="Check a given design: crank b, mm.")] = None,
    y1: Annotated[Optional[float], opt("--y1", help="Check a given design: strut radius "
                                                    "vector Y1, mm.")] = None,
    y2: Annotated[Optional[float], opt("--y2", help="Check a given design: sole radius Y2, mm.")] = None,
    tol: Annotated[Optional[float], opt("--tol", help="Check: allowed miss of run and rise per "
                                                      "cycle, mm.", shown="1")] = None,
    sweep: Annotated[bool, opt("--sweep", help="Print the sizing over landing angles and sole "
                                               "radii instead.")] = False,
    sweep_angles: Annotated[Optional[str], opt("--sweep-angles", help="Sweep landing angles, deg: "
                                                                      "'start:stop:step' or a list.",
                                               shown="-180:0:15")] = None,
    sweep_radii: Annotated[Optional[str], opt("--sweep-radii", help="Sweep sole radii, mm: a list or "
                                                                    "'start:stop:step'.",
                                              shown="40,70,100,150,192")] = None,
    plot: Plot = None,
    force: Force = False,
    json: Json = False, dry_run: DryRun = False, quiet: Quiet = False, verbose: Verbose = False,
) -> int:
    """Size crank b, strut Y1 and a = 2b for a stair, with climb and descent kinematics (SPEC §6).

    With --a --b --y1 --y2, check that design against the stair instead (exit 1 if it
    cannot climb). With --sweep, tabulate the sizing over landing angles and sole radii.
    """
    from wheelstep_cli.mechanism import stairs_report as sr
    from wheelstep_cli.parts.mechanism_files import stairs_files

    show = Output(json, quiet, verbose)
    require_printed("step", step, quiet and not json, "tables")
    _only_with(sweep, sweep_angles=sweep_angles, sweep_radii=sweep_radii)
    if sweep:   # a sweep prints a table and writes no file
        _only_with(False, a=a, b=b, y1=y1, y2=y2, sole_radius=sole_radius, landing_angle=landing_angle,
                   step=step, tol=tol, plot=plot, dry_run=dry_run or None, force=force or None)
    require_a_file(dry_run, force, plot=plot)
    sr.check_stair(run, rise, step := 5.0 if step is None else step)
    if sweep:
        _sweep(show, run, rise, number_list(sweep_angles or "-180:0:15", "sweep_angles"),
               sweep_radii or "40,70,100,150,192")
        return 0
    request = _request(run, rise, sole_radius, landing_angle, step, (a, b, y1, y2), tol)
    study = sr.stair_study(request)
    show.parameters(vars(study.design))
    files = stairs_files(study, plot)
    named = show.write_named("stairs", files, dry_run, force, plot=plot)
    report = sr.stair_report(study)
    show.report(report, lambda: _study_lines(study, report))
    show.files(named, dry_run)
    return 1 if study.check is not None and not study.check.climbs else 0


def _request(run: float, rise: float, sole_radius, landing_angle, step, design: tuple, tol):
    """The stair study's request (mm, deg) from the options (None: not given), refusing
    the one that would do nothing: ``tol`` without a ``design`` (a, b, y1, y2) to check,
    ``sole_radius`` with one (it sizes a design instead)."""
    from wheelstep_cli.mechanism import stairs_report as sr

    given = any(v is not None for v in design)
    if tol is not None and not given:
        raise DesignError("tol", tol, "is the design check's allowed miss: give the design to "
                                      "check (--a --b --y1 --y2)")
    if sole_radius is not None and given:
        raise DesignError("sole_radius", sole_radius, "sizes a design for the stair; the design "
                                                      "checked has its own sole radius (--y2)")
    tol = 1.0 if tol is None else tol
    return sr.StairRequest(run, rise, 70.0 if sole_radius is None else sole_radius,
                           -90.0 if landing_angle is None else landing_angle,
                           step, sr.given_design(*design, tol), tol)


def _only_with(used: bool, **given) -> None:
    """Refuse the options ``given`` unless they are ``used`` in this mode (sweep options
    without --sweep; the design check and the plot with it)."""
    if used:
        return
    for name, value in given.items():
        if value is not None:
            mode = "need --sweep" if name.startswith("sweep") else "do nothing with --sweep"
            raise DesignError(name, value, f"is not used: such options {mode}")


#: Most cells (landing angles x sole radii) of a sizing sweep.
MAX_SWEEP_CELLS = 100_000


def _sweep(show: Output, run: float, rise: float, angles: list[float], radii_text: str) -> None:
    """Size over every landing angle (deg) and sole radius (mm) and print the grid."""
    import numpy as np

    from wheelstep_cli.mechanism.stairs import sizing_sweep
    from wheelstep_cli.mechanism.stairs_report import sweep_report

    radii = number_list(radii_text, "sweep-radii")
    require(min(radii) > 0, "sweep-radii", radii_text, "must be > 0 mm")
    # every cell is a sizing and a row of the printed table: a grid beyond this is no table
    # to read and takes memory by the gigabyte
    require(len(angles) * len(radii) <= MAX_SWEEP_CELLS, "sweep-radii", radii_text,
            f"gives {len(radii)} radii, {len(angles) * len(radii)} cells with the {len(angles)} landing angles; "
            f"at most {MAX_SWEEP_CELLS} cells (fewer radii or angles)")
    rows = sizing_sweep(run, rise, np.radians(angles), radii)
    show.report(sweep_report(run, rise, rows), lambda: _sweep_lines(run, rise, angles, radii, rows))


def _sweep_cell(row: dict) -> str:
    if row["status"] == "ok":
        return f"{row['b']:.1f} / {row['y1']:.1f}"
    return "singular" if row["status"] == "singular" else f"n/a ({row['status']})"


def _sweep_lines(run, rise, angles, radii, rows) -> list[str]:
    """The grid: one line per landing angle, one ``b / Y1`` cell per sole radius."""
    width = 22
    lines = [f"sizing sweep for run l = {run:g} mm, rise h = {rise:g} mm (a = 2b); cells: b / Y1 (mm)",
             f"{'alpha (deg)':>11} " + " ".join(f"{'Y2 = ' + format(r, 'g'):>{width}}" for r in radii)]
    for i, al in enumerate(angles):
        cells = [_sweep_cell(r) for r in rows[i * len(radii):(i + 1) * len(radii)]]
        lines.append(f"{al:11.1f} " + " ".join(f"{c:>{width}}" for c in cells))
    return lines + ["n/a: that size would be negative (no physical meaning); "
                    "singular: alpha = 15 + k*60 deg, the equations have no unique solution"]


def _study_lines(study, report: dict) -> list[str]:
    """The design (sized or given), the motion per cycle, both tables and the check."""
    d, req = study.design, study.request
    alpha = req.landing_angle_deg
    if req.checking:
        lines = [f"design a = {d.a:g}, b = {d.b:g}, Y1 = {d.y1:g}, Y2 = {d.y2:g} mm "
                 f"against stair run {req.run:g} x rise {req.rise:g} mm"]
    else:
        lines = [f"stair run l = {req.run:g} mm, rise h = {req.rise:g} mm, sole radius Y2 = "
                 f"{req.sole_radius:g} mm, landing alpha = {alpha:g} deg",
                 f"crank b = {d.b:.2f} mm   strut Y1 = {d.y1:.2f} mm   a = 2b = {d.a:.2f} mm"]
    lines.append(f"per cycle (landing {alpha:g} -> {_worked_out(alpha + 90)} deg): "
                 f"advance {study.advance:.2f} mm, rise {study.rise:.2f} mm")
    lines += _table(f"climb (landing alpha = {alpha:g} deg); X01, Y01 mm; d.. per rad of phi (deg)",
                    report["climb"])
    lines += _table(f"descent (landing beta = -90 - alpha = {_worked_out(report['descent_landing_angle_deg'])} deg)",
                    report["descent"])
    if study.check is not None:
        lines += _check_lines(study.check, req.run, req.rise)
    return lines


def _worked_out(angle: float) -> str:
    """An angle worked out from the one given (deg), to the nanodegree: -90 + 90 is 0, not the
    -1e-13 a given -90.0000000000001 leaves."""
    return f"{round(angle, 9) + 0.0:g}"


def _table(title: str, rows) -> list[str]:
    lines = [title, f"{'phi':>8} {'X01':>9} {'dX01':>9} {'d2X01':>9} {'Y01':>9} {'dY01':>9} {'d2Y01':>9}"]
    for r in rows:
        # rounded first: a value within 0.005 of zero prints as 0.00, not -0.00
        cells = {key: round(value, 2) + 0.0 for key, value in r.items()}
        lines.append(f"{cells['phi']:8.2f} {cells['X01']:9.2f} {cells['dX01']:9.2f} {cells['d2X01']:9.2f} "
                     f"{cells['Y01']:9.2f} {cells['dY01']:9.2f} {cells['d2Y01']:9.2f}")
    return lines


def _check_lines(check, run, rise) -> list[str]:
    import numpy as np

    if check.climbs:
        return [f"CLIMBS: landing at {np.degrees(check.best_landing):.2f} deg one cycle advances "
                f"{check.best_advance:.2f} mm and rises {check.best_rise:.2f} mm (within "
                f"{check.tolerance:g} mm)"]
    # lengths shown finer than the tolerance, so a miss by less than 0.1 mm reads as a miss
    places = max(1, int(np.ceil(-np.log10(check.tolerance))) + 1) if check.tolerance > 0 else 3
    return [f"CANNOT CLIMB a {run:g} x {rise:g} mm stair: no landing angle makes one cycle both "
            f"advance {run:g} mm and rise {rise:g} mm (within {check.tolerance:g} mm).",
            _section("rises", rise, "advances", check.landing_for_rise, check.advance_at_rise, places),
            _section("advances", run, "rises", check.landing_for_run, check.rise_at_run, places),
            f"  closest: landing {_deg(check.best_landing)} deg advances "
            f"{check.best_advance:.{places}f} mm and rises {check.best_rise:.{places}f} mm"]


def _deg(angle: float) -> str:
    """An angle (rad) in degrees to 0.1, without a negative zero."""
    import numpy as np

    shown = f"{float(np.degrees(angle)):.1f}"
    return "0.0" if shown == "-0.0" else shown


def _section(given: str, amount: float, other: str, landings, values, places: int = 1) -> str:
    """One line of the climb check: where a cycle ``given`` ``amount`` mm, how far it ``other``
    (mm to ``places`` decimals)."""
    if len(landings):
        return f"  where a cycle {given} {amount:g} mm it {other} " + ", ".join(
            f"{v:.{places}f} mm (landing {_deg(al)} deg)" for al, v in zip(landings, values))
    noun = {"rises": "a rise", "advances": "an advance"}[given]
    return f"  no landing angle gives {noun} of {amount:g} mm per cycle"


def register(app) -> None:
    app.command("stairs")(stairs)
