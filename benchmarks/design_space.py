"""Design-space sweep (issue 13): build, check and judge a grid of gear-pair designs in process.

Run on demand:  python benchmarks/design_space.py [--quick] [--only NAME...] [--jsonl FILE]
Each design is a set of GearPairSpec fields (mm, deg). For each: build the pair as
`wheelstep gears` does, run the meshing check of the written meshes (SPEC §10), judge it
against the bounds (no interference; F'i <= 15 um, f'i <= 10 um, band-limited ripple
<= 1 % on both flanks), and print one table row: outcome or refusal reason, F'i, f'i,
ripple (drive/coast; the table shows them as measured, the bound is on the ripple beyond
the law's own), backlash band, time. A design `gears` would refuse for the bounds is
followed by a row with its remedy applied literally (it must come out within bounds). ``--jsonl`` appends each row as JSON (partial
runs keep what finished); the Markdown table goes to stdout for benchmarks/results.md.
"""

from __future__ import annotations

import argparse
import json
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

SOURCE = {}                                                # the source design (GearPairSpec defaults)
DESK = {"a": 30, "b": 50, "c": 180, "z": 24, "center_distance": 71.75, "install_distance": 72.125,
        "backlash": 0.375, "thickness": 6, "bore": 5}       # profiles/desk-demo.yaml


def law_csv_file(folder: Path) -> str:
    """A smooth one-period law (driven = driving - 0.3 sin driving, deg) as a CSV file."""
    phi = np.linspace(0.0, 360.0, 361)
    psi = np.degrees(np.radians(phi) - 0.3 * np.sin(np.radians(phi)))
    path = folder / "law.csv"
    path.write_text("driving_deg,driven_deg\n" + "\n".join(f"{a:.9f},{b:.9f}" for a, b in zip(phi, psi)))
    return str(path)


def grid(folder: Path, quick: bool = False) -> list[tuple[str, dict]]:
    """(name, GearPairSpec fields) of every design of the sweep (>= 60; quick: the Done-when set)."""
    designs = [(f"source z={z}", {"z": z}) for z in range(24, 121, 8)]
    designs += [(f"source n=4 z={z}", {"turns": 4, "z": z}) for z in (24, 32, 48)]
    if quick:
        return designs
    designs += [(f"alpha={pa} z=48", {"pressure_angle": pa}) for pa in (14.5, 17.5, 22.5, 25, 30)]
    designs += [(f"alpha={pa} z=24", {"pressure_angle": pa, "z": 24}) for pa in (14.5, 25, 30)]
    designs += [(f"alpha=25 z={z}", {"pressure_angle": 25, "z": z}) for z in (32, 40, 64, 80, 96, 112)]
    designs += [(f"backlash={j} z=48", {"backlash": j}) for j in (0.2, 0.3, 0.8, 1.0)]
    designs += [("ha=0.8 hf=1.0", {"addendum": 0.8, "dedendum": 1.0}),
                ("ha=1.0 hf=1.4", {"dedendum": 1.4}), ("ha=0.9 hf=1.15 z=32", {"addendum": 0.9,
                                                                                "dedendum": 1.15, "z": 32}),
                ("clearance=0.35", {"clearance": 0.35, "dedendum": 1.35})]
    designs += [(f"install={d}", {"install_distance": d}) for d in (144.5, 145.0)]
    designs += [(f"blend={bl}", {"blend": bl}) for bl in (5, 10)]
    designs += [("corner=tooth", {"corner": "tooth"})]
    designs += [(f"desk-demo z={z}", {**DESK, "z": z}) for z in (24, 32, 40)]
    designs += [("a=50", {"a": 50}), ("a=70 c=350", {"a": 70, "c": 350}), ("b=90", {"b": 90}),
                ("b=90 z=32", {"b": 90, "z": 32}), ("c=400", {"c": 400}),
                ("x1.5 scale", {"a": 90, "b": 150, "c": 540, "center_distance": 215.25,
                                "install_distance": 216.0, "z": 64})]
    designs += [(f"n=4 alpha=25 z={z}", {"turns": 4, "z": z, "pressure_angle": 25}) for z in (24, 48)]
    designs += [(f"n=4 z={z}", {"turns": 4, "z": z}) for z in (64, 96)]
    csv = law_csv_file(folder)
    designs += [(f"law-csv z={z}", {"law_csv": csv, "z": z, "module": 1.5, "bore": 4})
                for z in (28, 40)]
    designs += [(f"module={m}", {"module": m}) for m in (2.5, 3.0)]
    return designs


def evaluate(fields: dict) -> dict:
    """Build and check one design; the row: outcome, reason, figures (um, %, mm), seconds."""
    from wheelstep_cli.errors import DesignError
    from wheelstep_cli.parts.gear_pair import GearPairSpec, build_gear_pair
    from wheelstep_cli.parts.mesh_bounds import bound_violations, remedy_check, require_within_bounds
    from wheelstep_cli.parts.mesh_check import check_gear_pair, meshing_record

    start = time.perf_counter()
    try:
        pair = build_gear_pair(GearPairSpec(**fields))
    except DesignError as err:
        return {"outcome": "refused", "reason": str(err), "seconds": time.perf_counter() - start}
    record = meshing_record(check_gear_pair(pair))
    broken = bound_violations(record)
    remedy, refused = None, False
    if broken and not record["interference"]:
        try:
            # as `gears` refuses it: a remedy is offered once a build with it is within the bounds
            require_within_bounds(pair, record, verify=remedy_check(None))
        except DesignError as err:
            remedy, refused = remedy_fields(str(err)), True
    outcome = "within bounds"
    if broken:
        # "out of bounds": outside them yet not refused, which `gears` would write (a gap in the gate)
        outcome = "refused: interference" if record["interference"] else (
            "refused: bounds" if remedy else "refused: bounds, no remedy found" if refused else "out of bounds")
    row = {"outcome": outcome,
           "reason": "; ".join(broken), "remedy": remedy,
           "seconds": time.perf_counter() - start, "interfering_poses": record["interfering_poses"],
           "backlash_mm": [record["backlash_min_mm"], record["backlash_max_mm"]]}
    for side in ("drive", "coast"):
        row[side] = {k: record[side][k] for k in ("F_i_total_um", "f_i_tooth_um", "hub_speed_ripple_pct")}
    return row


def remedy_fields(message: str) -> dict:
    """The options a refusal's remedy names (``use --z 56 --backlash 0.2``) as spec fields."""
    if "; nothing written; use --" not in message:          # no remedy found
        return {}
    # the options up to what the line says of them in brackets (what was tried first)
    words = message.split("; nothing written; use ", 1)[1].split(" (", 1)[0].split()
    return {flag[2:].replace("-", "_"): _value(v) for flag, v in zip(words[::2], words[1::2])}


def _value(word: str):
    """A remedy's value as the spec takes it: a whole number, a number, or a choice's text."""
    for kind in (int, float):
        try:
            return kind(word)
        except ValueError:
            pass
    return word


def _f(value, spec=".1f") -> str:
    return "-" if value is None else format(value, spec)


def table_row(name: str, row: dict) -> str:
    """One Markdown row: design | outcome | F'i d/c | f'i d/c | ripple d/c | backlash | s | reason."""
    if row["outcome"] == "refused":
        return f"| {name} | refused | - | - | - | - | {row['seconds']:.1f} | {row['reason']} |"
    d, c = row["drive"], row["coast"]
    lo, hi = row["backlash_mm"]
    return (f"| {name} | {row['outcome']} | {_f(d['F_i_total_um'])}/{_f(c['F_i_total_um'])} | "
            f"{_f(d['f_i_tooth_um'])}/{_f(c['f_i_tooth_um'])} | "
            f"{_f(d['hub_speed_ripple_pct'], '.2f')}/{_f(c['hub_speed_ripple_pct'], '.2f')} | "
            f"{_f(lo, '.3f')}..{_f(hi, '.3f')} | {row['seconds']:.1f} | {row['reason']} |")


HEADER = ("| design | outcome | F'i um drive/coast | f'i um drive/coast | ripple % drive/coast | "
          "backlash mm | s | reason |\n|---|---|---|---|---|---|---|---|")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="only the source design's z grid")
    parser.add_argument("--only", nargs="*", help="only designs whose name contains one of these")
    parser.add_argument("--jsonl", type=Path, help="append each row as JSON to this file")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as folder:
        designs = grid(Path(folder), args.quick)
        if args.only:
            designs = [(n, f) for n, f in designs if any(o in n for o in args.only)]
        print(f"{len(designs)} designs", file=sys.stderr)
        print(HEADER)
        rows = []
        for name, fields in designs:
            row = evaluate(fields)
            rows.append(row)
            print(table_row(name, row), flush=True)
            if row.get("remedy"):
                # the remedy applied literally: it must pass
                applied = evaluate({**fields, **row["remedy"]})
                row["remedy_outcome"] = applied["outcome"]
                print(table_row(f"{name} + remedy {row['remedy']}", applied), flush=True)
            if args.jsonl:
                with args.jsonl.open("a") as out:
                    out.write(json.dumps({"design": name, "fields": fields, **row}) + "\n")
    # "out of bounds" would be written (a gap in the gate); the rest is refused before writing
    written = [r for r in rows if r["outcome"] in ("within bounds", "out of bounds")]
    good = sum(r["outcome"] == "within bounds" for r in written)
    remedied = [r for r in rows if r.get("remedy")]
    fixed = sum(r.get("remedy_outcome") == "within bounds" for r in remedied)
    bare = sum(r["outcome"] == "refused: bounds, no remedy found" for r in rows)
    total = sum(r["seconds"] for r in rows)
    print(f"\n{len(rows)} designs: {len(written)} would be written ({good} within bounds), "
          f"{len(remedied)} refused for the bounds with a remedy ({fixed} of them pass with it), "
          f"{bare} with no remedy found, {len(rows) - len(written) - len(remedied) - bare} refused "
          f"otherwise; {total:.0f} s in all "
          f"({total / max(1, len(rows)):.1f} s per design, remedies not counted)")


if __name__ == "__main__":
    main()
