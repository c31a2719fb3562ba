"""What ``mesh-check``'s three forms share (meshes, plates, G-code): the design from the
options, the printer whose band --tolerance checks, and the text report of a checked pair."""

from __future__ import annotations

import shlex


def design_spec(design: dict):
    """The design the meshes were drawn for, from the design options (mm, deg at the edge)."""
    from wheelstep_cli.config.problem_search import gathered
    from wheelstep_cli.config.resolve import gear_pair_spec

    from wheelstep_cli.errors import DesignError

    law_csv = design["law_csv"]
    try:
        spec = gear_pair_spec(design["profile"], a=design["a"], b=design["b"], c=design["c"],
                              r_min=design["r_min"],
                              turns=design["turns"], center_distance=design["center_distance"],
                              install_distance=design["distance"], law_csv=str(law_csv) if law_csv else None,
                              blend=design["blend"])
    except DesignError as err:
        if design["distance"] is None:
            raise
        # mesh-check's --distance is the spec's installed distance: named as the user typed it,
        # in each problem the run found
        raise gathered([DesignError("distance", e.value, e.limit) if e.param == "install_distance" else e
                        for e in (err, *getattr(err, "also", ()))]) from None
    if design["center_distance"] is not None and spec.install_distance is not None:
        # the law does not depend on it: it only says where to mount the pair when no
        # installed distance is given
        raise DesignError("center_distance", design["center_distance"],
                          "gives the distance checked at when none is installed; "
                          + ("--distance" if design["distance"] is not None else
                             "the profile's install_distance") + " sets it here")
    return spec


def same_file(first: str, second: str) -> bool:
    """Whether two paths name one file, or two files of identical content (a copy); False
    when either cannot be read (a missing or unreadable file is refused where it is read)."""
    from pathlib import Path

    try:
        a, b = Path(first), Path(second)
        if not (a.is_file() and b.is_file()):
            return False
        return a.resolve() == b.resolve() or (
            a.stat().st_size == b.stat().st_size and a.read_bytes() == b.read_bytes())
    except OSError:
        return False


def require_two_meshes(pinion: str, wheel: str) -> None:
    """Refuse (naming the wheel) two mesh arguments that name one mesh: the same file (or
    object of a 3MF), or two files of identical content. A part checked against itself gives
    no meshing figure, its sections overlapping everywhere."""
    from wheelstep_cli.errors import DesignError
    from wheelstep_cli.formats.mesh_read import split_mesh_spec

    (p_file, p_obj), (w_file, w_obj) = split_mesh_spec(pinion), split_mesh_spec(wheel)
    if p_obj == w_obj and same_file(str(p_file), str(w_file)):
        raise DesignError("wheel", wheel, f"is the same mesh as the pinion ({pinion}): give the "
                                          "pinion and the wheel of one pair")


def band_printer_of(tolerance: bool, printer):
    """The printer whose band --tolerance checks (None: no band check); --printer alone is
    refused (it only says whose band)."""
    from wheelstep_cli.errors import DesignError
    from wheelstep_cli.parts.tolerance_cli import band_printer

    if not tolerance:
        if printer is not None:
            raise DesignError("printer", printer, "names the band --tolerance checks: add --tolerance")
        return None
    from wheelstep_cli.config.profiles import load_printer_profile

    return band_printer(load_printer_profile(printer) if printer else None)


def no_design_options(design: dict) -> None:
    """Refuse design options where the design comes from the plates' metadata."""
    from wheelstep_cli.errors import DesignError

    for name, value in design.items():
        if value is not None:
            raise DesignError(name, value, "comes from the plate's metadata; to give it, name the "
                                           "two meshes (PINION WHEEL) instead of plates")


def pair_lines(summary: dict, distance: float) -> list[str]:
    """The text report of one checked pair (mm, deg at the edge)."""
    from wheelstep_cli.parts.mesh_check import meshing_lines

    pair = f"pair {summary['pair']}: " if "pair" in summary else ""
    over = ""
    if "cycle" in summary:        # a print read back from G-code
        from wheelstep_cli.parts.gcode_check import cycle_words

        over = f" ({cycle_words(summary['cycle'])})"
    return [f"meshing check: {pair}{summary['pinion']} + {summary['wheel']} at {distance:g} mm, "
            f"{summary['samples']} poses over {summary['period_deg']:g} deg of pinion{over}",
            *meshing_lines(summary), *_band_lines(summary)]


def _band_lines(summary: dict) -> list[str]:
    if "tolerance" not in summary:
        return []
    from wheelstep_cli.parts.tolerance_cli import tolerance_lines

    return tolerance_lines(summary["tolerance"])


def warn_band_jams(show, band: dict | None, printer: str | None = None, rerun: bool = False) -> None:
    """A warning line on stderr (``show``: cli.output.Output) when a checked band (SPEC §11)
    jams in some case: the report says JAMS among its lines, and a person at the printer
    should not miss it. ``printer``: the --printer as given (None: the default printer), so
    that the command the line suggests fits to the same band; ``rerun``: said by the
    ``gears`` command that drew the pair (the same command fits it), else by a check of
    files (``gears`` fits it from the design the pair was made with)."""
    if not band or not band.get("jams"):
        return
    jammed = [case["case"] for case in band["cases"] if case["jams"]]
    option = f" --printer {shlex.quote(str(printer))}" if printer else ""
    fit = ("the same command with --fit auto draws the teeth to clear the band" if rerun else
           f"`wheelstep gears{option} --fit auto` with the pair's design options draws the teeth "
           "to clear the band")
    # the fit's inset thins the teeth: its own refusal may ask for fewer, which is no news then
    fit += " (if the inset leaves the teeth too thin, its refusal names the tooth count that prints)"
    show.warning(f"WARNING: over the band of {band['printer']} the pair jams in {len(jammed)} of "
                 f"{len(band['cases'])} cases ({'; '.join(jammed)}): printed there it may not turn; {fit}")
