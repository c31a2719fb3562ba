"""wheelstep's generator vs the open-source ncgears (PyPI) on a smooth law both can take.

ncgears cannot take the crank law (its pitch curves have corners), so both generate
Bäsel's kind of smooth 1:1 law psi(phi) = phi - 0.3 sin(phi) with 28 teeth of
module 1.5 at 20 deg, and both pairs are measured by the same meshing check
(wheelstep_cli.gears.meshing) at the centre distance each reports. Times are wall
clock on this machine. ncgears is optional: the script says so and skips it when it
is not installed (pip install ncgears; its code is not part of this repository).

Run from the repository root:  python benchmarks/ncgears_compare.py
"""

from __future__ import annotations

import sys
import tempfile
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from wheelstep_cli.gears.generation import RackCutter, generate_pair, simplify_outline  # noqa: E402
from wheelstep_cli.gears.laws import law_from_samples  # noqa: E402
from wheelstep_cli.gears.meshing import MeshingSettings, check_meshing  # noqa: E402
from wheelstep_cli.gears.pitch_curves import center_distance_for_module  # noqa: E402
from wheelstep_cli.geometry.planar import signed_area  # noqa: E402

AMPLITUDE, TEETH, MODULE = 0.3, 28, 1.5
CLEARANCE = 0.05            # ncgears: inward offset of each face, x module
BACKLASH = 4 * CLEARANCE * MODULE   # ncgears thins every flank of both gears: same total play


def law():
    phi = np.linspace(0.0, 360.0, 721)
    psi = np.degrees(np.radians(phi) - AMPLITUDE * np.sin(np.radians(phi)))
    return law_from_samples(phi, psi)


def report(name, pinion, wheel, the_law, distance, seconds):
    t0 = time.perf_counter()
    rep = check_meshing(pinion, wheel, the_law, distance,
                        MeshingSettings(samples=1024))
    d = rep.to_dict()
    print(f"{name:28s} centre {distance:8.4f} mm  generate {seconds:6.2f} s  check "
          f"{time.perf_counter() - t0:5.2f} s  interference {str(d['interference']):5s}  "
          f"TE {d['drive']['te_min_arcmin']:7.2f}..{d['drive']['te_max_arcmin']:<7.2f}'  "
          f"F'i {d['drive']['F_i_total_um']:.1f} um  f'i {d['drive']['f_i_tooth_um']:.1f} um  "
          f"largest TE step {d['drive']['te_max_step_um']:.1f} um  "
          f"backlash {d['backlash_min_mm']:.3f}..{d['backlash_max_mm']:.3f} mm")
    return rep


def orient(pinion, wheel, sx, turn):
    """Mirror both outlines by ``sx`` in y, turn the wheel by ``turn`` rad, make both CCW."""
    p = pinion * [1.0, sx]
    c, s = np.cos(turn), np.sin(turn)
    w2 = (wheel * [1.0, sx]) @ np.array([[c, s], [-s, c]])
    return (p[::-1] if signed_area(p) < 0 else p), (w2[::-1] if signed_area(w2) < 0 else w2)


def best_orientation(pinion, wheel, the_law, distance):
    """ncgears' frames are not ours: try the mirror images and keep the one that meshes.
    Returns the oriented outlines and (sx, turn)."""
    best = None
    for sx in (1.0, -1.0):
        for turn in (0.0, np.pi):
            p, w2 = orient(pinion, wheel, sx, turn)
            rep = check_meshing(p, w2, the_law, distance,
                                MeshingSettings(samples=64))
            score = np.nanmax(np.abs(rep.transmission_error)) + 10 * rep.interference.sum()
            if best is None or score < best[0]:
                best = (score, p, w2, (sx, turn))
    return best[1], best[2], best[3]


def main() -> None:
    the_law = law()
    distance = center_distance_for_module(the_law, TEETH, MODULE)
    t0 = time.perf_counter()
    pair = generate_pair(the_law, TEETH, RackCutter(np.radians(20.0), 1.0, 1.25, 0.25, BACKLASH),
                         center_distance=distance)
    seconds = time.perf_counter() - t0
    # thinned as `gears` writes them: the pinion as generated, the wheel at its tolerance
    report("wheelstep generated", pair.pinion_outline,
           simplify_outline(pair.wheel_outline, pair.settings.wheel_tolerance), the_law, distance, seconds)
    try:
        import ncgears
    except ImportError:
        print("ncgears: not installed (pip install ncgears) - skipped")
        return
    with tempfile.TemporaryDirectory() as tmp:
        t0 = time.perf_counter()
        try:
            theirs = ncgears.generate(f"phi - {AMPLITUDE}*sin(phi)", teeth=TEETH, module=MODULE,
                                      pressure_angle_deg=20.0, clearance=CLEARANCE,
                                      output_directory=tmp, name="ncgears")
        except Exception as exc:        # report exactly why it could not run
            print(f"ncgears: failed: {type(exc).__name__}: {exc}")
            return
        seconds = time.perf_counter() - t0
    nc_law = law()
    # same 1 um simplification as wheelstep's written outlines (the check is O(vertices^2))
    drive = simplify_outline(np.asarray(theirs.drive_outline, dtype=float))
    driven = simplify_outline(np.asarray(theirs.driven_outline, dtype=float))
    print(f"ncgears outlines: {len(theirs.drive_outline)} / {len(theirs.driven_outline)} points, "
          f"{len(drive)} / {len(driven)} after 1 um simplification")
    p, w, frame = best_orientation(drive, driven, nc_law, theirs.center_distance)
    name = f"ncgears {getattr(ncgears, '__version__', '')}".strip()
    report(name, p, w, nc_law, theirs.center_distance, seconds)
    # the unsimplified outlines (these once exhausted memory in the check)
    import tracemalloc

    raw = orient(np.asarray(theirs.drive_outline, dtype=float),
                 np.asarray(theirs.driven_outline, dtype=float), *frame)
    tracemalloc.start()
    report(f"{name} unsimplified", *raw, nc_law, theirs.center_distance, seconds)
    print(f"  ({len(raw[0])} / {len(raw[1])} points; peak traced memory of the check "
          f"{tracemalloc.get_traced_memory()[1] / 1e6:.0f} MB)")
    tracemalloc.stop()
    print(f"ncgears' own verification: {theirs.summary()}")


if __name__ == "__main__":
    main()
