"""A real slicer takes every plate of the shop-floor example with the README's literal command
(the plates carry the bed and the settings); the slicer tests fail instead of skipping in CI."""

from __future__ import annotations

import json
import zipfile
from pathlib import Path

import pytest

from tests.helpers.meshcheck import read_3mf_strict
from tests.helpers.slicer import extrusion_extent, info_verdicts, require_slicer, slicer

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="module")
def shop_floor(tmp_path_factory):
    from wheelstep_cli.cli import run

    out = tmp_path_factory.mktemp("shop") / "out"
    assert run(["batch", str(ROOT / "examples" / "shop-floor.yaml"), "--out", str(out), "--jobs", "2",
                "-q"]) == 0
    return out


def _plates(out: Path) -> list[Path]:
    return sorted(out.glob("plate-*.3mf"), key=lambda p: int(p.stem.split("-")[1]))


def _bed(plate: Path) -> tuple[float, float]:
    with zipfile.ZipFile(plate) as zf:
        config = zf.read("Metadata/Slic3r_PE.config").decode()
    shape = next(line for line in config.splitlines() if line.startswith("; bed_shape = "))
    corners = [tuple(map(float, c.split("x"))) for c in shape.split(" = ")[1].split(",")]
    return max(c[0] for c in corners), max(c[1] for c in corners)


def test_every_plate_slices_with_the_readme_command_inside_the_bed(shop_floor):
    require_slicer()
    plates = _plates(shop_floor)
    assert len(plates) >= 4
    for plate in plates:
        # the README's literal command: the plate's own layout (build-item transforms), which
        # PrusaSlicer 2.5's command line would otherwise re-arrange
        result = slicer("--export-gcode", "--dont-arrange", plate.name, cwd=shop_floor)
        assert result.returncode == 0, plate.name + result.stdout[-1500:] + result.stderr[-1500:]
        (gcode,) = shop_floor.glob("*.gcode")        # named by the plate's output_filename_format
        x0, y0, x1, y1 = extrusion_extent(gcode.read_text())
        gcode.unlink()
        bx, by = _bed(plate)
        assert 0.0 <= x0 and 0.0 <= y0 and x1 <= bx and y1 <= by, (plate.name, (x0, y0, x1, y1))


def test_every_object_is_one_manifold_part_and_lib3mf_reads_strictly(shop_floor):
    plates = _plates(shop_floor)
    result = slicer("--info", *map(str, plates))
    assert result.returncode == 0, result.stderr
    manifold, parts = info_verdicts(result.stdout)
    objects = sum(len(read_3mf_strict(p)["objects"]) for p in plates)
    assert manifold == ["yes"] * objects and parts == [1] * objects, result.stdout[-2000:]
    for plate in plates:
        assert read_3mf_strict(plate)["warnings"] == [], plate.name


def test_ini_beside_the_plates_holds_the_plates_settings(shop_floor):
    manifest = json.loads((shop_floor / "manifest.json").read_text())
    for plate in manifest["plates"]:
        ini = (shop_floor / f"{plate['printer_profile']}.ini").read_text().splitlines()[1:]
        with zipfile.ZipFile(shop_floor / plate["file"]) as zf:
            config = zf.read("Metadata/Slic3r_PE.config").decode().splitlines()[1:]
        assert ini == [line[2:] for line in config]
        keys = {line.split(" = ")[0] for line in ini}
        assert {"bed_shape", "nozzle_diameter", "layer_height", "first_layer_height", "skirts",
                "skirt_distance", "brim_width", "max_print_height", "perimeters"} <= keys


def test_mesh_check_on_the_plates_reproduces_the_design_figures(shop_floor, cli):
    from wheelstep_cli.parts.gear_pair import build_gear_pair
    from wheelstep_cli.parts.mesh_check import check_gear_pair
    from wheelstep_cli.parts.plate_pairs import find_plate_pairs

    plates = [str(p) for p in _plates(shop_floor)]
    demo = next(p for p in plates if any(f.pair == "demo-gears/1" for f in _pairs(p)))
    result = cli("mesh-check", demo, "--json", "--samples", "768")
    assert result.exit_code == 0, result.stderr
    pairs = json.loads(result.stdout)["pairs"]
    assert sorted(p["pair"] for p in pairs) == ["demo-gears/1", "demo-gears/2"]
    expected = check_gear_pair(build_gear_pair(find_plate_pairs([demo], "demo-gears/1")[0].spec)).to_dict()
    for measured in pairs:
        assert measured["interference"] == expected["interference"]
        for key in ("backlash_min_mm", "backlash_max_mm"):
            assert measured[key] == pytest.approx(expected[key], rel=0.01), key
    # the full-scale pair does not fit one bed together: its two plates are checked as a pair
    halves = [p for p in plates if any(f == "bntu-gears/1" for f in _pair_ids(p))]
    assert len(halves) == 2
    both = cli("mesh-check", *halves, "--json", "--samples", "768")
    assert both.exit_code == 0, both.stderr
    assert json.loads(both.stdout)["pairs"][0]["pair"] == "bntu-gears/1"
    single = cli("mesh-check", halves[0])
    assert single.exit_code == 2 and "no pinion and wheel share" in single.stderr


def _pairs(plate: str):
    from wheelstep_cli.parts.plate_pairs import find_plate_pairs
    from wheelstep_cli.errors import DesignError

    try:
        return find_plate_pairs([plate])
    except DesignError:
        return []


def _pair_ids(plate: str) -> set[str]:
    from wheelstep_cli.formats.mesh_read import read_3mf_objects

    return {o.metadata.get("pair") for o in read_3mf_objects(Path(plate), "pinion")}


def test_resin_plate_slices_for_sla_with_its_own_settings(tmp_path):
    from tests.helpers.files import SMALL_BATCH
    from wheelstep_cli.cli import run

    require_slicer()
    (tmp_path / "b.yaml").write_text(SMALL_BATCH)
    out = tmp_path / "out"
    assert run(["batch", str(tmp_path / "b.yaml"), "--out", str(out), "-q"]) == 0
    manifest = json.loads((out / "manifest.json").read_text())
    plate = next(p for p in manifest["plates"] if p["printer_profile"] == "resin-0.05-standard")
    result = slicer("--export-sla", plate["file"], cwd=out)
    assert result.returncode == 0, result.stdout[-1500:] + result.stderr[-1500:]
    assert list(out.glob("*.sl1"))
