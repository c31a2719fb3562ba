"""End-to-end timing of `wheelstep gears --z 48`: process start to files written, and per stage.

Run on demand:  python benchmarks/gears_e2e.py [--runs 7] [--no-stages] [-- extra gears options]

End to end: the median (and spread) over ``--runs`` runs of this checkout's CLI
(``python -m wheelstep_cli`` from the repository root, not whatever `wheelstep` is on the
PATH), after one warm-up run of the OS file cache. The modules' bytecode is written (to a
temporary ``PYTHONPYCACHEPREFIX``) by the warm-up and read by the runs, as `pip install`
leaves it for a user: a ``PYTHONDONTWRITEBYTECODE`` set in the caller's environment (this
sandbox sets it) would otherwise compile every module from source on every run. Each run is measured twice: wall-clock
time, and CPU time (user + sys of the child process, from ``resource.getrusage``). The
machine is shared by other agents, so wall time swings with their load; the CPU time is
the steadier figure of the work done (with threads it may exceed the wall time).

Stages: one in-process run of the same pipeline, each stage timed (wall and this
process's CPU time): imports, generation of the teeth, extrusion, mesh checks, meshing
check of the written meshes (sections + SPEC §10), encoding the files. Target (issue 13):
end to end at most 1.5 s median on the 2-core machine.
"""

from __future__ import annotations

import argparse
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from dataclasses import replace
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def command() -> list[str]:
    return [sys.executable, "-m", "wheelstep_cli"]


def _children_cpu() -> float:
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def end_to_end(runs: int, extra: list[str]) -> tuple[list[float], list[float]]:
    """(wall s, CPU s) of each of ``runs`` CLI runs after a warm-up."""
    walls, cpus = [], []
    with tempfile.TemporaryDirectory() as out, tempfile.TemporaryDirectory() as pycache:
        env = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}
        env["PYTHONPYCACHEPREFIX"] = pycache
        # an option is given once: extra options replace the defaults' (e.g. `-- --z 32`)
        default = [] if "--z" in extra else ["--z", "48"]
        argv = command() + ["gears", *default, "--out", out, "--force", *extra]
        for i in range(runs + 1):
            cpu0, start = _children_cpu(), time.perf_counter()
            subprocess.run(argv, check=True, capture_output=True, cwd=ROOT, env=env)
            if i:
                walls.append(time.perf_counter() - start)
                cpus.append(_children_cpu() - cpu0)
    return walls, cpus


class _Laps:
    """Wall and CPU time of consecutive stages of this process (s)."""

    def __init__(self) -> None:
        self.rows: list[tuple[str, float, float]] = []
        self._wall, self._cpu = time.perf_counter(), time.process_time()

    def lap(self, name: str) -> None:
        wall, cpu = time.perf_counter(), time.process_time()
        self.rows.append((name, wall - self._wall, cpu - self._cpu))
        self._wall, self._cpu = wall, cpu


def stages() -> list[tuple[str, float, float]]:
    """(stage, wall s, CPU s) of one in-process run of the `gears --z 48` pipeline."""
    sys.path.insert(0, str(ROOT))
    laps = _Laps()
    import wheelstep_cli.cli  # noqa: F401  (what the CLI imports before it parses options)
    from wheelstep_cli.config.specs import GearPairSpec
    from wheelstep_cli.geometry.mesh_checks import require_printable
    from wheelstep_cli.geometry.solids import extrude_plate
    from wheelstep_cli.gears.generation import GenerationSettings, generate_pair, simplify_outline
    from wheelstep_cli.parts import gear_pair as gp
    from wheelstep_cli.parts.mesh_check import check_gear_pair, meshing_record
    laps.lap("imports")
    spec = GearPairSpec(z=48)
    _, law = gp.generation_law(spec)
    settings = replace(GenerationSettings(), tilt=spec.tilt)
    gen = generate_pair(law, spec.z, spec.cutter(), corner=spec.corner, settings=settings,
                        center_distance=gp.rolling_distance(spec, law))
    laps.lap("generate teeth (gears/generation)")
    wheel_outline = simplify_outline(gen.wheel_outline, gen.settings.wheel_tolerance)
    pinion = extrude_plate("pinion", gen.pinion_outline, spec.thickness, spec.bore)
    wheel = extrude_plate("wheel", wheel_outline, spec.thickness, spec.bore)
    laps.lap("thin wheel outline + extrude both")
    checks = {part.name: require_printable(part) for part in (pinion, wheel)}
    laps.lap("mesh checks (watertight, winding, volume)")
    pair = gp.GearPair(spec, spec.law(), None, gen.pinion_outline, wheel_outline, pinion, wheel,
                       checks, gen)
    record = meshing_record(check_gear_pair(pair))
    laps.lap("meshing check (sections + SPEC 10)")
    gp.gear_pair_files(pair, Path("unused"), "both", record)
    laps.lap("encode STL + 3MF + JSON")
    return laps.rows


def _spread(values: list[float]) -> str:
    return (f"median {statistics.median(values):.3f} s (min {min(values):.3f}, "
            f"max {max(values):.3f})")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=7)
    parser.add_argument("--no-stages", action="store_true", help="only the end-to-end runs")
    parser.add_argument("extra", nargs="*", help="more options for `wheelstep gears`")
    args = parser.parse_args()
    before = os.getloadavg()
    walls, cpus = end_to_end(args.runs, args.extra)
    label = " ".join(["wheelstep gears --z 48", *args.extra])
    print(f"{label}, {args.runs} runs: wall {_spread(walls)}; CPU (user+sys) {_spread(cpus)}; "
          "load average %.1f before, %.1f after (1 min)" % (before[0], os.getloadavg()[0]))
    if not args.no_stages:
        rows = stages()
        for name, wall, cpu in rows:
            print(f"  {name:44s} wall {wall:6.3f} s  CPU {cpu:6.3f} s")
        print(f"  {'total in process':44s} wall {sum(r[1] for r in rows):6.3f} s  "
              f"CPU {sum(r[2] for r in rows):6.3f} s")


if __name__ == "__main__":
    main()
