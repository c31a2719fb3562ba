"""One point of a sweep: its design resolved (its key), then built and checked as the
``gears`` or ``shoe`` command does, reduced to one row of figures. Never raises: a refusal
(DesignError) and a crash are rows with their reason."""

from __future__ import annotations

import functools
import hashlib
import json
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from wheelstep_cli.config.names import as_keys, remedy_in_yaml, yaml_message
from wheelstep_cli.errors import DesignError

#: Figures of a row (float, None when not computed), in column order.
FIGURES = ("drive_F_i_um", "drive_f_i_um", "drive_ripple_pct", "coast_F_i_um", "coast_f_i_um",
           "coast_ripple_pct", "backlash_min_mm", "backlash_max_mm", "max_penetration_mm",
           "volume_mm3", "mass_g")
KINDS_OF = {"gears": "gear-pair", "shoe": "shoe"}
#: The tolerance band's cases (parts.tolerance.band_cases, in its order) as column prefixes.
BAND_CASES = {"tight": "band_tight", "pinion grown, wheel shrunk": "band_pinion_grown",
              "pinion shrunk, wheel grown": "band_wheel_grown", "loose": "band_loose"}
#: Columns of the band check (``tolerance: true``): whether any case jams, the band's least
#: and largest backlash (mm), and per case whether it jams, its backlash and drive f'i (um).
BAND_FIGURES = ("band_jams", "band_least_backlash_mm", "band_largest_backlash_mm") + tuple(
    f"{prefix}_{name}" for prefix in BAND_CASES.values()
    for name in ("jams", "backlash_min_mm", "backlash_max_mm", "drive_f_i_um"))


@dataclass(frozen=True)
class Point:
    """A resolved design point: what a worker needs, and its key in the results."""

    index: int
    command: str
    printer_name: str | None
    printer: Any            # config.printers.Printer or None
    values: dict            # the values the sweep gave (for the row's parameter columns)
    spec: Any               # the resolved spec, or None when resolving refused it
    refusal: str | None     # why resolving refused it
    allow_interference: bool
    key: str
    tolerance: bool = False   # also the meshing check over the printer's tolerance band


def versions() -> str:
    """The versions that decide a row's figures: wheelstep (its version and the digest of its
    own files, so a changed checkout under the same version number does not reuse rows) and
    its numeric libraries."""
    from importlib.metadata import version

    from wheelstep_cli import __version__

    libs = {name: version(name) for name in ("numpy", "scipy", "manifold3d", "shapely")}
    return json.dumps({"wheelstep": __version__, "wheelstep_files": package_digest(), **libs},
                      sort_keys=True)


@functools.lru_cache(maxsize=1)
def package_digest() -> str:
    """SHA-256 (first 16 hex digits) of wheelstep's code: every ``.py`` file of the package,
    by relative path and content (the presets reach a row's key through the resolved design
    and the printer's own digest)."""
    root = Path(__file__).resolve().parents[1]
    digest = hashlib.sha256()
    for path in sorted(p for p in root.rglob("*.py") if "__pycache__" not in p.parts):
        digest.update(path.relative_to(root).as_posix().encode() + b"\0" + path.read_bytes() + b"\0")
    return digest.hexdigest()[:16]


def point_key(command: str, design: dict, printer, tool: str) -> str:
    """SHA-256 of the resolved design (all its parameters), the printer preset and the tool's
    versions: the same key means the same row."""
    printer_id = None if printer is None else [printer.name, printer.sha256]
    text = json.dumps([command, design, printer_id, tool], sort_keys=True, default=str)
    return hashlib.sha256(text.encode()).hexdigest()


def resolve_point(index: int, command: str, profile, printer_name: str | None, printer,
                  values: dict, allow_interference: bool, tool: str, tolerance: bool = False) -> Point:
    """The point's spec: its values over the design profile over the defaults, checked (a
    problem becomes the point's refusal); ``tolerance``: with the band check."""
    from wheelstep_cli.config.resolve import spec_problems, spec_values
    from wheelstep_cli.config.sweep_file import COMMANDS

    spec_type, section = COMMANDS[command]
    spec, refusal = None, None
    try:
        spec, problems = spec_problems(spec_type, spec_values(spec_type, section, profile, values,
                                                              on_command_line=False))
        if problems:
            spec, refusal = None, "; ".join(yaml_message(p) for p in problems)
    except DesignError as err:
        refusal = yaml_message(err)
    design = spec.model_dump(mode="json") if spec is not None else {"given": values}
    keyed = {**design, "tolerance_band": True} if tolerance else design
    if printer is None:
        # a row without a printer is still checked on the default printer's bed (_on_a_bed)
        keyed = {**keyed, "bed_of": [(default := _default_printer()).name, default.sha256]}
    return Point(index, command, printer_name, printer, values, spec, refusal, allow_interference,
                 point_key(command, keyed, printer, tool), tolerance)


@functools.lru_cache(maxsize=1)
def _default_printer():
    """The default printer profile (config.printers.Printer), read once per process: a sweep
    resolves up to 10 000 points, and each row without a printer is built on its bed."""
    from wheelstep_cli.config.profiles import load_printer

    return load_printer()


def evaluate(point: Point) -> dict:
    """The row of one point (worker entry point): outcome ``ok``, ``refused`` or ``failed``."""
    start = time.perf_counter()
    row: dict[str, Any] = dict.fromkeys(FIGURES)
    row.update(key=point.key, index=point.index, outcome="ok", reason=None, interference=None)
    try:
        if point.refusal is not None:
            raise DesignError("design", "", point.refusal)
        row.update(_figures(point))
        if row["interference"] and not point.allow_interference:
            row.update(outcome="refused", reason="the teeth interfere (allow_interference: true "
                                                 "keeps such designs)")
    except DesignError as err:
        # a rule several inputs share is said of the one the sweep gave (as a command names the flag given)
        err = err.for_given(point.values)
        reason = err.limit if err.param == "design" else remedy_in_yaml(err, as_keys, entry=False)
        row.update(outcome="refused", reason=reason)
    except Exception as err:  # a crash of one design must not stop the sweep
        row.update(outcome="failed", reason=f"internal error: {type(err).__name__}: {err}")
    row["seconds"] = time.perf_counter() - start
    return row


def build_point(point: Point):
    """(built part, meshing record or None) exactly as the command builds and checks it; with
    ``point.tolerance`` as ``gears --tolerance`` does (the band record under ``tolerance``)."""
    from wheelstep_cli.parts.kinds import build_for_printer

    if point.command != "gears":
        from wheelstep_cli.parts.shoe import require_shoe_on_bed

        return _on_a_bed(lambda bed: require_shoe_on_bed(
            build_for_printer(KINDS_OF[point.command], point.spec, point.printer), bed), point.printer), None
    from wheelstep_cli.parts.mesh_check import check_gear_pair, meshing_record
    from wheelstep_cli.parts.tolerance_cli import band_pair

    from wheelstep_cli.parts.bed_remedy import scaled_to_bed
    from wheelstep_cli.parts.bound_figures import bounds_verdict

    built, band, nominal = _on_a_bed(lambda bed: scaled_to_bed(
        lambda: band_pair(point.spec, point.printer, point.tolerance, bed), point.spec, None, unbuilt=True),
        point.printer)
    record = meshing_record(nominal if nominal is not None else check_gear_pair(built))
    if band is not None:
        record["tolerance"] = band
    # whether it is within the bounds, as `gears` reports it (a best design's gears.json too)
    record["bounds"] = bounds_verdict(record, (band or {}).get("fit"))
    return built, record


def _on_a_bed(build, printer):
    """``build(bed)`` with the point's ``printer``, else the default printer (a best design's
    plates go on it), whose refusals of a part too large say so."""
    from wheelstep_cli.parts.plate_layout import default_printer_said

    try:
        return build(printer or _default_printer())
    except DesignError as err:
        if printer is not None or getattr(err, "beyond_printer", None) is None:
            raise
        raise default_printer_said(err, note="the default printer: the sweep names no printers") from None


def _figures(point: Point) -> dict:
    """The figures of a built point: per-flank transmission error, backlash, volume, mass."""
    built, record = build_point(point)
    volume = sum(check.volume for check in built.checks.values())
    out = {"volume_mm3": float(volume),
           "mass_g": None if point.printer is None else float(volume / 1000.0 * point.printer.density)}
    if record is None:
        return out
    for side in ("drive", "coast"):
        flank = record[side]
        out[f"{side}_F_i_um"] = flank["F_i_total_um"]
        out[f"{side}_f_i_um"] = flank["f_i_tooth_um"]
        out[f"{side}_ripple_pct"] = flank["hub_speed_ripple_pct"]
    out.update(backlash_min_mm=record["backlash_min_mm"], backlash_max_mm=record["backlash_max_mm"],
               max_penetration_mm=record["max_penetration_mm"], interference=bool(record["interference"]))
    if "tolerance" in record:
        out.update(_band_figures(record["tolerance"]))
    return {**out, **_bounds_refusal(built, record, point.printer)}


def _band_figures(band: dict) -> dict:
    """The BAND_FIGURES of a band record (parts.tolerance.band_record)."""
    out = {"band_jams": bool(band["jams"]), "band_least_backlash_mm": band["least_backlash_mm"],
           "band_largest_backlash_mm": band["largest_backlash_mm"]}
    for case in band["cases"]:
        prefix = BAND_CASES[case["case"]]
        out.update({f"{prefix}_jams": bool(case["jams"]),
                    f"{prefix}_backlash_min_mm": case["backlash_min_mm"],
                    f"{prefix}_backlash_max_mm": case["backlash_max_mm"],
                    f"{prefix}_drive_f_i_um": case["drive"]["f_i_tooth_um"]})
    return out


def _bounds_refusal(pair, record: dict, printer) -> dict:
    """The refusal `gears` gives a pair meshing outside the SPEC §10 bounds, or with teeth too
    thin for the point's ``printer`` (None: none), its figures kept in the row; or nothing."""
    from wheelstep_cli.parts.mesh_bounds import require_within_bounds
    from wheelstep_cli.parts.printed_teeth import require_printable_teeth

    try:
        require_within_bounds(pair, record)
        require_printable_teeth(pair, printer)
    except DesignError as err:
        # the remedy as the sweep file's keys (its grid and fixed values)
        return {"outcome": "refused", "reason": remedy_in_yaml(err, as_keys, entry=False)}
    return {}
