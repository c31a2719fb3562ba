"""STEP export of a generated pair: fit, write and read-back time, size, edges (issue 12).

Run on demand (needs the cad extra):  python benchmarks/step_export.py [--z 48] [--tolerance 0.005]

For each gear of the pair built as `wheelstep gears` builds it: the outline's point count,
the B-spline edges and poles of the fit (geometry.spline_fit), the CPU time of the fit, of
building and writing the STEP, the file size, and the time build123d's ``import_step``
(OpenCASCADE's reader, with its shape healing, as a CAD user's program reads it) takes to
read it back. Figures go to benchmarks/results.md.
"""

from __future__ import annotations

import argparse
import tempfile
import time
from pathlib import Path


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--z", type=int, default=48)
    parser.add_argument("--tolerance", type=float, default=0.005)
    args = parser.parse_args()

    from build123d import import_step

    from wheelstep_cli.config.resolve import gear_pair_spec
    from wheelstep_cli.formats.step import face_step_bytes
    from wheelstep_cli.geometry.spline_fit import FitSettings, fit_ring
    from wheelstep_cli.parts.gear_faces import gear_faces
    from wheelstep_cli.parts.gear_pair import build_gear_pair

    pair = build_gear_pair(gear_pair_spec(None, z=args.z))
    fit = FitSettings(tolerance=args.tolerance)
    print("| gear | outline points | edges | poles | fit CPU s | fit + write CPU s | MB | import_step s |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- |")
    for name, face in gear_faces(pair).items():
        start = time.process_time()
        edges = fit_ring(face.outline, fit)
        fitted = time.process_time() - start
        start = time.process_time()
        data = face_step_bytes(face, float(pair.spec.thickness), fit)
        written = time.process_time() - start
        with tempfile.TemporaryDirectory() as tmp:
            path = Path(tmp) / f"{name}.step"
            path.write_bytes(data)
            start = time.perf_counter()
            solid = import_step(path)
            read = time.perf_counter() - start
        assert solid.is_valid
        print(f"| {name} | {len(face.outline)} | {len(edges)} | {sum(len(e.poles) for e in edges)} | "
              f"{fitted:.2f} | {written:.2f} | {len(data) / 1e6:.2f} | {read:.2f} |")


if __name__ == "__main__":
    main()
