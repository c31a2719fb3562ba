"""Each defect the first stability fuzz found (issue 16), replayed: one line on stderr naming
the parameter the user gave, exit 2, no traceback and nothing written. Which of them fail on
the code before the fixes is in benchmarks/results.md (#16 defect replays on the old code)."""

from __future__ import annotations

import pytest

from tests.fuzz.cases import BATCH_TEXTS, MESH_TEXTS
from tests.helpers.clicheck import error_line

PNG = MESH_TEXTS["png.stl"]
HUGE = MESH_TEXTS["huge.stl"]
BATCH = {"merge": BATCH_TEXTS[1], "recursive": BATCH_TEXTS[0], "kind-list": BATCH_TEXTS[2],
         "huge-z": BATCH_TEXTS[3], "long-name": BATCH_TEXTS[6], "bomb": BATCH_TEXTS[7]}
#: A 318-byte alias bomb of 9 x 9 ... x 9 (9 levels) = 387 million values: the old code took
#: more than 3 GB and a minute (the one in BATCH_TEXTS has 300 000 and passed old validation).
BOMB = "a: &a [1,1,1,1,1,1,1,1,1]\n" + "".join(
    f"{n}: &{n} [{','.join([f'*{p}'] * 9)}]\n" for p, n in zip("abcdefgh", "bcdefghi")) + "parts: [*i]\n"


CASES = [  # (args, files, text the line must hold)
    (["gears", "--law-csv", "law.csv"], {"law.csv": b"\xff\xfe\x00phi"}, "--law-csv"),
    (["gears", "--law-csv", "missing.csv"], {}, "--law-csv"),
    (["gears", "--profile", "p.yaml"], {"p.yaml": b"\xff\xfe not utf-8"}, "--profile = p.yaml"),
    (["gears", "--profile", "p.yaml"], {"p.yaml": b"gears: {z: '48'}\n"}, "gears.z"),
    (["gears", "--profile", "p.yaml"], {"p.yaml": b"mechanism: {c: text}\n"}, "mechanism.c"),
    (["gears", "--profile", "p.yaml"], {"p.yaml": b"gears: {thickness: {a: 1}}\n"}, "gears.thickness"),
    (["stairs", "--sweep", "--sweep-angles", "0:inf:1"], {}, "--sweep-angles"),
    (["linkage", "--beta", "nan"], {}, "--beta"),
    (["linkage", "--beta", "inf"], {}, "--beta"),
    (["linkage", "--l3", "1e300"], {}, "--l3"),
    (["linkage", "--rpm", "inf"], {}, "--rpm"),
    (["trajectory", "--r3", "1e308"], {}, "--r3"),
    (["trajectory", "--y0", "nan"], {}, "--y0"),
    (["shoe", "--rmin", "1e20"], {}, "--rmin"),
    (["shoe", "--rmin", "1e-300"], {}, "--rmin"),
    (["kinematics", "--motor-rpm", "5e-324"], {}, "--motor-rpm"),
    (["kinematics", "--points", "1000000000"], {}, "--points"),
    (["gears", "--z", "100000000"], {}, "--z"),
    (["stairs", "--sweep", "--landing-angle", "nan", "--json"], {}, "--landing-angle"),
    (["pitch", "--center-distance=1e308"], {}, "--center-distance"),
    (["gears", "--backlash", "5"], {}, "--backlash"),
    (["mesh-check", "h.stl", "p.stl", "--distance", "inf"], {"h.stl": HUGE, "p.stl": PNG}, "--distance"),
    # found by sampling the refusals of a seed-3 campaign (the fuzz runner does not check names)
    (["mesh-check", "h.stl", "p.stl", "--distance", "-1"], {"h.stl": HUGE, "p.stl": PNG}, "--distance = -1"),
    # found by the runner's check that a refusal names a parameter the user gave
    (["linkage", "--l3", "5e-324"], {}, "--l3 = 5e-324"),
    (["stairs", "--run", "0.5"], {}, "--run = 0.5: with it, landing-angle = -90 (the default) fails: gives crank b"),
    (["trajectory", "--r2", "1e-300"], {}, "--r2 = 1e-300"),
    (["kinematics", "--b", "5e-324"], {}, "--b = 5e-324"),
    (["teeth", "--b", "0.5", "--c", "3", "--z", "144"], {}, "--z = 144"),
    (["teeth", "--backlash", "144"], {}, "--backlash = 144: with it, module = 2 fails: the paper teeth's default module (none given): too large"),
    (["gears", "--tilt", "-0.0"], {}, "--tilt = -0"),   # its remedy: tests/cli/test_design_bounds.py
    # found by a scan of every numeric option with every fuzz value, one at a time
    (["pitch", "--center-distance", "5e-324"], {}, "--center-distance = 5e-324"),
    (["mesh-check", "--distance", "0"], {}, "Missing argument 'PINION'"),
    (["shoe", "--width", "3"], {}, "--width = 3: must be >= 16"),
    (["shoe", "--strut-diameter", "1e-300"], {}, "--strut-diameter = 1e-300"),
    (["shoe", "--rmin", "144"], {}, "--rmin = 144"),
    (["gears", "--module", "1e-300"], {}, "--module = 1e-300"),
    (["gears", "--module", "144"], {}, "--module = 144: must be <= 14.64 mm"),     # 9.8 m apart: 9 GB
    (["gears", "--module", "0.1", "--z", "6"], {}, "--module = 0.1: must be >= 0.12 mm"),  # 0.85 mm apart
    # reviewer's findings: the file option given that path whatever the order, the value as typed
    (["gears", "--out", ".", "--profile", "p.yaml"], {"p.yaml": b"\xff\xfe not utf-8"}, "--profile = p.yaml"),
    (["gears", "--teeth", "paper", "--backlash", "3", "--printer", "fdm-0.4-pla"], {},
     "--backlash = 3 (3.15 as printed): "),
    (["gears", "--install-distance", "10000"], {}, "--install-distance = 10000"),
    (["gears", "--thickness", "1e-300"], {}, "--thickness = 1e-300: must be >= 0.5 mm"),
    # teeth finer than the least module (their pinion's root too near the axis for any hole:
    # "must be < -1.36 mm" before), refused for the distance that makes them so
    (["gears", "--install-distance", "3"], {}, "--install-distance = 3: gives teeth of module 0.044 mm, under "
     "the least 0.1 mm"),
    (["gears", "--install-distance", "20"], {}, "--install-distance = 20: with it, bore = 8 (the default) fails: must be <"),
    (["mesh-check", "h.stl", "p.stl", "--samples", "2147483648"], {"h.stl": HUGE, "p.stl": PNG},
     "--samples"),
    (["mesh-check", "h.stl", "h2.stl"], {"h.stl": HUGE, "h2.stl": HUGE.replace(b"1e30", b"2e30")},
     "h.stl"),
    (["mesh-check", "p.stl", "h.stl"], {"p.stl": PNG, "h.stl": HUGE}, "p.stl"),
    (["gears", "--out", "x" * 300], {}, "--out = " + "x" * 300 + ": cannot be written"),
    (["gears", "--out=o/" + "x" * 300 + "/p"], {}, "--out = o/"),
] + [(["batch", "b.yaml", "--out", "o"], {"b.yaml": text.encode()}, "b.yaml")
     for text in [*BATCH.values(), BOMB]]


@pytest.mark.parametrize("args, files, named", CASES, ids=[" ".join(c[0])[:60] for c in CASES])
def test_defect_is_one_line_naming_the_parameter(cli, tmp_path, monkeypatch, args, files, named):
    monkeypatch.chdir(tmp_path)
    for name, data in files.items():
        (tmp_path / name).write_bytes(data)
    line = error_line(cli(*args))
    assert named in line and "Traceback" not in line and "No module" not in line, line
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted(files)
