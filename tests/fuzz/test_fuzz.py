"""A short stability fuzz in CI (the long one: ``python -m tests.fuzz --n 5000``)."""

from __future__ import annotations

import hashlib
import subprocess
import time

import pytest

from tests.fuzz.cases import Invocation, invocations
from tests.fuzz.runner import _findings, check, names_a_given_parameter

SEED, COUNT, BUDGET_S = 20261201, 70, 150.0


def test_seeded_invocations_find_nothing():
    start, failures, ran = time.perf_counter(), [], 0
    for inv in invocations(SEED, COUNT, slow_share=0.05):
        if time.perf_counter() - start > BUDGET_S:
            break
        ran += 1
        failures += [f"{' '.join(inv.args)[:160]}: {f}" for f in check(inv)]
    assert ran >= 20, f"only {ran} invocations fitted the time budget"
    assert not failures, "\n".join(failures[:30])


def test_good_behaviour_passes_the_checker():
    assert check(Invocation(["pitch", "--json"])) == []
    assert check(Invocation(["pitch", "--z", "nan"])) == []
    assert check(Invocation(["mesh-check", "x.stl", "x.stl"], {"x.stl": b"solid x\nendsolid\n"})) == []


def test_the_checker_catches_tracebacks_noise_bad_json_and_touched_files(tmp_path):
    (tmp_path / "notes.txt").write_bytes(b"mine")
    before = {"notes.txt": "not its digest any more"}
    run = subprocess.CompletedProcess([], 2, stdout="{nan}", stderr="Traceback (most recent call last):\n"
                                      "  File x\nValueError: boom\n")
    found = _findings(Invocation(["pitch", "--json"]), run, tmp_path, before)
    assert any(f.startswith("traceback") for f in found)
    assert any(f.startswith("refusal is not") for f in found)
    assert any(f.startswith("touched a file") for f in found)
    ok = subprocess.CompletedProcess([], 0, stdout='{"a": NaN}', stderr="")
    assert any("not valid JSON" in f for f in _findings(Invocation(["pitch", "--json"]), ok, tmp_path,
                                                        {"notes.txt": _digest(b"mine")}))


@pytest.mark.parametrize("line, args, named", [
    ("wheelstep: error: --z = 1e+08: must be <= 400", ["gears", "--z", "1e8"], True),
    ("wheelstep: error: --z = 1e+08: must be <= 400", ["gears", "--z=1e8"], True),
    ("wheelstep: error (wheelstep gears): Invalid value for '--z': not a number", ["gears", "--z", "x"], True),
    ("wheelstep: error (wheelstep gears): No such option: --nope", ["gears", "--nope"], True),
    ("wheelstep: error: p.yaml:1: gears.z = '48': must be a whole number", ["gears", "--profile", "p.yaml"], True),
    ("wheelstep: error: pinion = x.stl: no such file", ["mesh-check", "x.stl", "y.stl"], True),
    # a derived quantity, a spec field, a flag the user did not type, an argument's name
    # with a value that was an option's
    ("wheelstep: error: crank-angle = 0: loop cannot close", ["linkage", "--l3", "5e-324"], False),
    ("wheelstep: error: install_distance = -1: must be >= 0", ["mesh-check", "a", "b", "--distance", "-1"], False),
    ("wheelstep: error: --r3 = 1: too short for --y0", ["trajectory", "--y0", "nan"], False),
    ("wheelstep: error: addendum = 5: too big", ["gears", "--backlash", "5"], False),
    # the flag typed but another value (a printer's compensation shown as the user's), the
    # other argument's name, a command name taken for a file, a negative number for a flag
    ("wheelstep: error: --backlash = 1.65: too big", ["gears", "--backlash", "1.5"], False),
    ("wheelstep: error: --backlash = 1.5 (1.65 as printed): too big", ["gears", "--backlash", "1.5"], True),
    ("wheelstep: error: wheel = x.stl: no such file", ["mesh-check", "x.stl", "y.stl"], False),
    ("wheelstep: error: gears: cannot run", ["gears", "--z", "48"], False),
    ("wheelstep: error: cannot run with -inf", ["stairs", "--run", "-inf"], False),
    ("wheelstep: error: --run = -inf: must be finite", ["stairs", "--run", "-inf"], True),
    ("wheelstep: error: --landing-angle = 0: gives strut Y1 < 0", ["stairs", "--landing-angle", "5e-324"], True),
    ("wheelstep: error: --landing-angle = 0.001: gives", ["stairs", "--landing-angle", "5e-324"], False),
])
def test_the_checker_knows_a_refusal_that_names_what_the_user_gave(tmp_path, line, args, named):
    assert names_a_given_parameter(line, args) is named
    run = subprocess.CompletedProcess([], 2, stdout="", stderr=line + "\n")
    found = _findings(Invocation(args), run, tmp_path, {})
    assert any(f.startswith("refusal names no parameter") for f in found) is not named


def _digest(data: bytes) -> str:
    return hashlib.sha256(data).hexdigest()
