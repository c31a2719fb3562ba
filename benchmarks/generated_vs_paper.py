"""Generated vs paper teeth on the source design, measured by the same meshing check (SPEC §10).

Run from the repository root:  python benchmarks/generated_vs_paper.py [--quick]

For each pair: hub speed ripple, transmission error, backlash, interference, and the
time to generate (outlines + meshes) and to check. The first rows are the two
methods as `wheelstep gears` writes them; the rest are the alternatives tried while
choosing the generated method's corner treatment (all at the installed 144 mm).
Results are recorded in benchmarks/results.md.
"""

from __future__ import annotations

import argparse
import sys
import time
from dataclasses import replace
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from wheelstep_cli.gears.generation import (GenerationSettings, RackCutter, generate_pair,  # noqa: E402
                                            simplify_outline)
from wheelstep_cli.gears.laws import CrankLaw, blended_law  # noqa: E402
from wheelstep_cli.gears.meshing import MeshingSettings, check_meshing  # noqa: E402
from wheelstep_cli.mechanism.crank import CrankMechanism  # noqa: E402
from wheelstep_cli.parts.gear_pair import GearPairSpec, build_gear_pair  # noqa: E402

INSTALL = 144.0


def measure(name, pinion, wheel, law, distance, seconds, samples):
    t0 = time.perf_counter()
    rep = check_meshing(pinion, wheel, law, distance,
                        MeshingSettings(samples=samples))
    check_s = time.perf_counter() - t0
    d = rep.to_dict()
    return {
        "pair": name, "ripple_pct": d["drive"]["hub_speed_ripple_pct"],
        "te_pp_arcmin": d["drive"]["te_max_arcmin"] - d["drive"]["te_min_arcmin"],
        "te_arcmin": (d["drive"]["te_min_arcmin"], d["drive"]["te_max_arcmin"]),
        "backlash_mm": (d["backlash_min_mm"], d["backlash_max_mm"]),
        "interference": d["interference"], "contact_lost": d["contact_lost"],
        "generate_s": seconds, "check_s": check_s,
    }


def built(spec, samples):
    t0 = time.perf_counter()
    pair = build_gear_pair(spec)
    seconds = time.perf_counter() - t0
    law = CrankLaw(CrankMechanism(spec.a, spec.b, spec.c), spec.turns)
    return pair.pinion_outline, pair.wheel_outline, law, seconds


def variant(label, samples, blend=0.0, cutter=None, corner="space", **changes):
    """One alternative: ``changes`` are GenerationSettings fields (lead, pivot, tilt, ...)."""
    law = CrankLaw(CrankMechanism(60, 100, 360), 2)
    gen_law = blended_law(law, np.radians(blend))
    settings = replace(GenerationSettings(), **changes)
    t0 = time.perf_counter()
    pair = generate_pair(gen_law, 48, cutter or RackCutter(backlash=0.5), corner=corner,
                         settings=settings, strict=False, center_distance=INSTALL)
    seconds = time.perf_counter() - t0
    p, w = simplify_outline(pair.pinion_outline), simplify_outline(pair.wheel_outline)
    return measure(label, p, w, law, INSTALL, seconds, samples)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--quick", action="store_true", help="only the two shipped pairs")
    ap.add_argument("--samples", type=int, default=1536)
    args = ap.parse_args()
    rows = []
    p, w, law, s = built(GearPairSpec(teeth="paper"), args.samples)
    rows.append(measure("paper (SPEC §5), L 143.5 installed 144", p, w, law, INSTALL, s, args.samples))
    p, w, law, s = built(GearPairSpec(), args.samples)
    rows.append(measure("generated (default)", p, w, law, INSTALL, s, args.samples))
    if not args.quick:
        alpha = np.radians
        alternatives = [
            ("rack pinion, wheel carved, normal backlash, no tilt", dict(tilt=0.0, backlash_mode="normal")),
            ("  same, pinion tooth centred on the corner", dict(tilt=0.0, backlash_mode="normal", corner="tooth")),
            ("  same, pressure angle 15", dict(tilt=0.0, backlash_mode="normal",
                                               cutter=RackCutter(alpha(15), backlash=0.5))),
            ("  same, pressure angle 25", dict(tilt=0.0, backlash_mode="normal",
                                               cutter=RackCutter(alpha(25), backlash=0.5))),
            ("normal backlash, tilt 0.6", dict(tilt=0.6, backlash_mode="normal")),
            ("angular backlash split, no tilt", dict(tilt=0.0, lead=0.0)),
            ("angular backlash split, tilt 0.6", dict(tilt=0.6, lead=0.0)),
            ("angular backlash all on the coast side (TE 0), tilt 0.6", dict(tilt=0.6, lead=1.0)),
            ("angular backlash split, tilt 0.3", dict(tilt=0.3)),
            ("angular backlash split, tilt 1.0", dict(tilt=1.0)),
            ("angular backlash split, tilt 0.6, tooth on corner", dict(tilt=0.6, corner="tooth")),
            ("default + blend 1 deg (rack undercut check off)", dict(blend=1.0)),
            ("default + blend 4 deg", dict(blend=4.0)),
            ("default, rack pivots the whole corner turn", dict(pivot=1.0)),
            ("default, rack pivots 0.3 of the turn from each side", dict(pivot=0.3)),
            ("default, 160 rays per tooth (pinion and wheel)", dict(rays_per_tooth=160,
                                                                   wheel_rays_per_tooth=160)),
            ("default, 960 rays per tooth", dict(rays_per_tooth=960, wheel_rays_per_tooth=960)),
            ("default, 192 wheel-carving poses per tooth", dict(carve_poses_per_tooth=192)),
            ("default, play split evenly (lead 0)", dict(lead=0.0)),
        ]
        for label, kw in alternatives:
            blend = kw.pop("blend", 0.0)
            rows.append(variant(label, args.samples, blend=blend, **kw))
    print(f"{'pair':58s} {'ripple%':>8s} {'TE p-p':>7s} {'TE min..max (arcmin)':>21s} "
          f"{'backlash mm':>13s} {'interf':>6s} {'gen s':>6s} {'check s':>7s}")
    for r in rows:
        te, bl = r["te_arcmin"], r["backlash_mm"]
        print(f"{r['pair']:58s} {r['ripple_pct']:8.2f} {r['te_pp_arcmin']:7.2f} "
              f"{te[0]:9.2f}..{te[1]:<9.2f} {bl[0]:6.3f}..{bl[1]:<6.3f} {str(r['interference']):>6s} "
              f"{r['generate_s']:6.2f} {r['check_s']:7.2f}")


if __name__ == "__main__":
    main()
