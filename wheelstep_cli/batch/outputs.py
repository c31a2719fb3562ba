"""What a batch writes besides the plates: each entry's report, the manifest (inputs and
every output with SHA-256, checks, tool versions) and the print sheet's figures."""

from __future__ import annotations

import hashlib
import json
from pathlib import Path

from wheelstep_cli.batch.build import BuiltPart, EntryResult
from wheelstep_cli.batch.plan import Entry
from wheelstep_cli.config.printers import Printer

MANIFEST = "manifest.json"


def previous_record(out: Path) -> tuple[dict[str, str], bool]:
    """(relative name -> SHA-256 of the outputs listed by an earlier batch's manifest in ``out``,
    whether that manifest.json is one: written by wheelstep batch, or absent)."""
    from wheelstep_cli.formats.owned import read_record

    path = out / MANIFEST
    if not path.exists():
        return {}, True
    try:
        ours = json.loads(path.read_text(encoding="utf-8")).get("tool") == "wheelstep batch"
    except (OSError, ValueError, AttributeError, UnicodeDecodeError):
        ours = False
    return (read_record(path, "outputs"), True) if ours else ({}, False)


def part_summary(part: BuiltPart, printer: Printer) -> dict:
    """Volume, bounding box, mass estimates and checks of one built part."""
    from wheelstep_cli.batch.mass import estimated_mass, solid_mass

    lo, hi = part.bounds
    return {"volume_mm3": part.volume, "bounding_box_mm": [lo, hi], "size_mm": hi - lo,
            "triangles": part.triangles, "solid_mass_g": solid_mass(part, printer),
            "estimated_mass_g": estimated_mass(part, printer), "checks": part.checks}


#: Inputs a part resolves from others (a gear pair's distances, a shoe's strut and sole
#: radius, one from the other), as its design report states them.
RESOLVED = ("center_distance", "install_distance", "c", "r_min")


def _resolved(values: dict, report: dict | None, key: str) -> dict:
    """``values`` with the inputs the part resolved (:data:`RESOLVED`: a gear pair's centre
    distances, mm, a shoe's c and r_min, mm) as its design report's ``key`` states them, as
    ``wheelstep gears`` and ``wheelstep shoe`` report them."""
    resolved = ((report or {}).get(key) or {})
    return {**values, **{name: resolved[name] for name in RESOLVED if name in resolved and name in values}}


def _is_fitted(result: EntryResult) -> bool:
    """Whether the entry's gear pair was drawn for its printer band's fit (batch.build)."""
    return bool(result.band and "fit" in result.band)


def fit_brief(band: dict) -> dict:
    """The fit a band record names and its inset (mm), or nothing when it names none."""
    return {"fit": band["fit"]["fit"], "inset_mm": band["fit"]["inset_mm"]} if "fit" in band else {}


def printed_values(entry: Entry, result: EntryResult) -> dict:
    """The printed parameters: a fitted pair's as drawn (without the printer's tooth clearance)."""
    return result.report["printed_parameters"] if _is_fitted(result) else entry.printed.model_dump()


def printer_geometry(entry: Entry, result: EntryResult) -> dict:
    """The printer settings that changed the entry's geometry; a fitted pair's teeth get the
    fit's inset instead of the tooth clearance."""
    geometry = entry.printer.geometry()
    if _is_fitted(result):
        geometry.update(tooth_clearance=0.0, outline_inset=result.band["fit"]["inset_mm"])
    return geometry


def entry_report_bytes(entry: Entry, result: EntryResult) -> bytes:
    from wheelstep_cli.formats.jsonio import json_bytes

    return json_bytes({
        "entry": entry.name, "kind": entry.kind, "design_profile": entry.design_label,
        "printer_profile": entry.printer.name, "quantity": entry.quantity,
        "parameters": _resolved(entry.spec.model_dump(), result.report, "parameters"),
        "printed_parameters": _resolved(printed_values(entry, result), result.report, "printed_parameters"),
        "printer_geometry": printer_geometry(entry, result),
        "printed_parts": {p.name: part_summary(p, entry.printer) for p in result.parts},
        # the meshing record with what the report says of the bounds (as in the design report)
        **({"meshing": result.report.get("meshing", result.mating)} if result.mating is not None else {}),
        **({"tolerance": result.band} if result.band is not None else {}),
        "design_report": result.report,
    })


def tool_versions() -> dict[str, str]:
    """Versions of the tool, Python and the libraries that shape the output."""
    import platform
    from importlib import metadata

    from wheelstep_cli import __version__

    versions = {"wheelstep": __version__, "python": platform.python_version()}
    for dist in ("numpy", "scipy", "shapely", "manifold3d", "matplotlib", "PyYAML", "pydantic", "typer",
                 "rich"):
        try:
            versions[dist] = metadata.version(dist)
        except metadata.PackageNotFoundError:
            versions[dist] = "not installed"
    return versions


#: The meshing figures the manifest keeps of each gear pair (the entry's report has them all).
MESHING_KEYS = ("interference", "interfering_poses", "samples", "distance_mm", "backlash_min_mm",
                "backlash_max_mm", "drive", "coast")


def _meshing(result: EntryResult) -> dict:
    """The entry's meshing check in brief (gear pairs, built or refused), else nothing."""
    if result.mating is None:
        return {}
    brief = {"meshing": {key: result.mating[key] for key in MESHING_KEYS}}
    if result.band is not None:
        band = result.band
        brief["tolerance"] = {"printer": band["printer"], "checked": band["checked"], "jams": band["jams"],
                              **fit_brief(band),
                              **({"note": band["note"]} if "note" in band else {
                                  "least_backlash_mm": band["least_backlash_mm"],
                                  "largest_backlash_mm": band["largest_backlash_mm"],
                                  "cases": {c["case"]: {"jams": c["jams"], "backlash_min_mm": c["backlash_min_mm"],
                                                        "backlash_max_mm": c["backlash_max_mm"]}
                                            for c in band["cases"]}})}
    return brief


def _band_checks(built, results) -> dict:
    """When the band is checked (``batch``'s default): whether every gear pair meshes over its printer's band,
    and the printers that state none (told to add one, not taken as perfect)."""
    bands = [results[e.index].band for e in built if results[e.index].band is not None]
    if not bands:
        return {}
    jams = any(b["jams"] for b in bands if b["checked"])
    unchecked = sorted({b["printer"] for b in bands if not b["checked"]})
    # a pair whose printer states no band was not checked over one: not known to mesh (null)
    return {"gear_pairs_mesh_over_printer_bands": False if jams else (None if unchecked else True),
            "printers_without_band": unchecked}


def _law_csvs(plan) -> dict:
    """The law CSVs the entries name (as given; no folder), each with the SHA-256 of its bytes."""
    from wheelstep_cli.parts.gear_laws import law_csv_metadata

    found = {}
    for entry in plan.entries:
        path = getattr(entry.printed, "law_csv", None)
        if path is not None:
            try:
                digest = law_csv_metadata(entry.printed)["law_csv_sha256"]
            except OSError:         # its entry failed on it, and says so
                digest = None
            found[Path(path).name] = {"file": Path(path).name, "sha256": digest}
    return dict(sorted(found.items()))


def manifest_bytes(plan, out, files, plates, built, results, failed) -> bytes:
    from wheelstep_cli.formats.jsonio import json_bytes

    printers = {}
    for entry in plan.entries:
        printers[entry.printer.name] = {"file": entry.printer.file_name, "sha256": entry.printer.sha256}
    checks_ok = all(all(p.checks.values()) for e in built for p in results[e.index].parts)
    meshes = [results[e.index].mating for e in built if results[e.index].mating is not None]
    return json_bytes({
        "tool": "wheelstep batch",
        "versions": tool_versions(),
        "inputs": {
            "batch": {"file": plan.file.name, "sha256": plan.sha256},
            "design_profiles": {n: {"file": f, "sha256": s} for n, (f, s) in sorted(plan.designs.items())},
            "printer_profiles": dict(sorted(printers.items())),
            "law_csvs": _law_csvs(plan),
        },
        "entries": [
            {"name": e.name, "kind": e.kind, "design_profile": e.design_label, "printer_profile": e.printer.name,
             "quantity": e.quantity, "overrides": e.overrides, "line": int(e.where.rsplit(":", 1)[1]),
             "status": "built" if e in built else "failed",
             **({"parts": {p.name: {"volume_mm3": p.volume, "triangles": p.triangles, "checks": p.checks}
                           for p in results[e.index].parts}} if e in built else {}),
             **_meshing(results[e.index])}
            for e in plan.entries],
        # each with the remedies its reason offers, as the entry's keys (none: []), as --json says them
        "failed": [{"name": e.name, "where": f"{plan.file.name}:{where.rsplit(':', 1)[1]}", "reason": reason,
                    "remedies": results[e.index].remedies if e.index in results else []}
                   for e, where, reason in failed],
        "plates": [{"file": f"{p.stem}.3mf", "picture": f"{p.stem}.png", "printer_profile": p.printer.name,
                    "parts": [i.label for i in p.items]} for p in plates],
        "checks": {"meshes_printable": checks_ok,
                   "gear_pairs_without_interference": not any(m["interference"] for m in meshes),
                   "every_part_on_a_bed": not any(
            "does not fit" in reason for _, _, reason in failed),
            "validated_before_build": True, **_band_checks(built, results)},
        "outputs": {p.relative_to(out).as_posix(): hashlib.sha256(data).hexdigest()
                    for p, data in sorted(files.items(), key=lambda kv: kv[0].as_posix())},
    })
