"""A wheel built from the tree, installed into a fresh virtual environment, has every preset."""

from __future__ import annotations

import json
import subprocess
import sys
import venv
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
PRESETS = sorted(p.stem for p in (ROOT / "profiles").glob("*.yaml"))


def _run(args, cwd, timeout=600):
    result = subprocess.run([str(a) for a in args], cwd=cwd, capture_output=True, text=True, timeout=timeout)
    assert result.returncode == 0, result.stdout[-3000:] + result.stderr[-3000:]
    return result


def test_installed_wheel_ships_the_presets_and_runs_them(tmp_path):
    wheels = tmp_path / "wheels"
    _run([sys.executable, "-m", "pip", "wheel", "--no-deps", "-q", "-w", wheels, ROOT],
         tmp_path)
    (wheel,) = wheels.glob("wheelstep-*.whl")
    env = tmp_path / "venv"
    # the dependencies come from this interpreter's site-packages; wheelstep itself only from the wheel
    venv.EnvBuilder(system_site_packages=True, with_pip=False).create(env)
    py = env / "bin" / "python"
    _run([sys.executable, "-m", "pip", "--python", py, "install", "--no-deps", "-q", "--force-reinstall", wheel],
         tmp_path)
    work = tmp_path / "user"
    work.mkdir()
    where = _run([py, "-c", "import wheelstep_cli, importlib.resources as r; print(wheelstep_cli.__file__); "
                  "print(sorted(p.name for p in r.files('wheelstep_cli.profiles').iterdir()))"], work).stdout
    assert str(env) in where.splitlines()[0], where
    for name in PRESETS:
        assert f"{name}.yaml" in where, (name, where)
    wheelstep = env / "bin" / "wheelstep"
    _run([wheelstep, "gears", "--profile", "desk-demo", "--out", "gears"], work)
    report = json.loads((work / "gears" / "gears.json").read_text())
    import yaml

    preset = yaml.safe_load((ROOT / "profiles" / "desk-demo.yaml").read_text())
    assert report["parameters"]["z"] == preset["gears"]["z"]   # the installed preset was read
    _run([wheelstep, "batch", ROOT / "examples" / "shop-floor.yaml", "--out", "shop"], work)
    assert (work / "shop" / "manifest.json").is_file() and list((work / "shop").glob("plate-*.3mf"))
