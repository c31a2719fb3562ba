"""``gears --slice``: PrusaSlicer slices the pair's 3MF plates, and the G-code is read back
and checked (SPEC §11). The plates carry their printer's PrusaSlicer settings, so the
G-code is what that printer would get. Lengths in mm.
"""

from __future__ import annotations

import shutil
import subprocess
import tempfile
from pathlib import Path

from wheelstep_cli.errors import DesignError

SLICER = "prusa-slicer"
#: Longest a plate may take to slice (s): the default pair's wheel plate takes about 45 s
#: of CPU; ten times that on a loaded machine.
TIMEOUT = 900


def require_slicer() -> str:
    """The prusa-slicer path; DesignError naming --slice when it is not installed."""
    found = shutil.which(SLICER)
    if found is None:
        raise DesignError("slice_", "on", f"needs PrusaSlicer, and {SLICER} is not on PATH: install "
                                         "it, or slice the 3MF plates yourself and run mesh-check --gcode")
    return found


def slice_plates(plates: dict[Path, bytes], folder: Path) -> dict[Path, Path]:
    """Write each plate into ``folder`` and slice them all (at once: PrusaSlicer runs one
    thread per plate most of the time); plate path -> its G-code in ``folder``."""
    binary = require_slicer()
    runs = {}
    for plate, data in plates.items():
        local = folder / plate.name
        local.write_bytes(data)
        gcode = local.with_suffix(".gcode")
        runs[plate] = (gcode, subprocess.Popen([binary, "--export-gcode", "--dont-arrange", str(local),
                                                "--output", str(gcode)],
                                               stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True))
    out = {}
    for plate, (gcode, run) in runs.items():
        try:
            _, err = run.communicate(timeout=TIMEOUT)
        except subprocess.TimeoutExpired:
            run.kill()
            raise DesignError("slice_", plate.name, f"PrusaSlicer took more than {TIMEOUT} s") from None
        if run.returncode != 0 or not gcode.is_file():
            last = (err or "").strip().splitlines()[-1:] or ["no message"]
            raise DesignError("slice_", plate.name, f"PrusaSlicer failed (exit {run.returncode}): {last[0]}")
        out[plate] = gcode
    return out


def slice_and_check(files: dict[Path, bytes], band: dict | None = None,
                    progress=None) -> tuple[dict[Path, bytes], dict, bool]:
    """Slice the 3MF plates among ``files`` and check the pair as their G-code prints it:
    (G-code path beside each plate -> bytes, the report record, whether it meshes);
    with ``band`` (the pair's band record, ``--tolerance``) also whether the printed least
    backlash lies in the range it predicts. ``progress(done, total)`` hears of each stage."""
    from wheelstep_cli.parts.gcode_check import run_gcode_check
    from wheelstep_cli.parts.plate_pairs import find_plate_pairs

    plates = {path: data for path, data in files.items() if path.suffix == ".3mf"}
    if not plates:
        raise DesignError("slice_", "on", "slices the 3MF plates: give --format 3mf or both")
    with tempfile.TemporaryDirectory(prefix="wheelstep-slice-") as scratch:
        sliced = slice_plates(plates, Path(scratch))
        if progress is not None:
            progress(1, 2)
        pair = find_plate_pairs([str(Path(scratch) / p.name) for p in plates])[0]
        report, summary, _ = run_gcode_check(list(sliced.values()), pair, None, None)
        names = {str(g): plate.with_suffix(".gcode").name for plate, g in sliced.items()}
        written = {plate.with_suffix(".gcode"): gcode.read_bytes() for plate, gcode in sliced.items()}
        header = next(iter(written.values()))[:200].decode(errors="replace").splitlines()[0]
    for gear in ("pinion", "wheel"):
        source = summary["gcode"][gear]["gcode"]
        summary["gcode"][gear]["gcode"] = names[source]
        summary[gear] = f"{names[source]}:{gear}"
    record = {"slicer": header.lstrip("; "), "gcode_files": sorted(names.values()), **summary}
    if band is not None:
        from wheelstep_cli.parts.gcode_check import least_backlash_range, within_band

        record["tolerance"] = {"printer": band["printer"],
                               "least_backlash_range_mm": least_backlash_range(band)}
        record["gcode"]["inside_band"] = within_band(record, record["tolerance"])
    return written, record, bool(summary["meshes"])


def slice_lines(record: dict) -> list[str]:
    """The read-back as text lines (the gears report)."""
    from wheelstep_cli.parts.gcode_check import gcode_lines
    from wheelstep_cli.parts.mesh_check import flank_line

    verdict = "meshes" if record["meshes"] else "DOES NOT MESH (interference or lost contact)"
    return [f"sliced ({record['slicer']}): {', '.join(record['gcode_files'])}; as printed the pair {verdict}, "
            f"backlash {_mm(record['backlash_min_mm'])}..{_mm(record['backlash_max_mm'])} mm",
            *(f"  {line}" for line in gcode_lines(record)),
            *(f"  printed {flank_line(side, record[side])}" for side in ("drive", "coast"))]


def _mm(value) -> str:
    return "n/a" if value is None else f"{value:.3f}"
