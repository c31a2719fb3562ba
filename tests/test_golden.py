"""Golden figures guard refactors: every preset and a few designs give the stored outputs."""

from __future__ import annotations

import warnings

import pytest

from tests.helpers import golden


@pytest.mark.parametrize("name", sorted(golden.CASES))
def test_outputs_match_golden(name):
    stored = golden.load(name)
    assert stored["args"] == golden.CASES[name], "case changed: regenerate its golden record"
    new = golden.run_case(name)
    if stored.get("cpu") != new["cpu"]:
        warnings.warn(f"golden {name}: recorded on CPU kind {stored.get('cpu')}, run on {new['cpu']}: the "
                      "files' bytes are not compared, the figures to the cross-CPU tolerances")
    diff = golden.differences(stored, new)
    assert not diff, "\n".join(diff[:40])


def test_a_record_from_another_cpu_kind_is_compared_by_its_figures_to_the_cross_cpu_tolerances():
    """Across CPU kinds a mesh's bytes differ (its triangles by 0.09 %, its volume by 2e-8):
    such a run passes on its figures; on the same kind every byte counts; and a figure moved
    further than the tessellation moves it fails on any kind."""
    import copy

    stored = golden.load("gears-default")
    moved = copy.deepcopy(stored)
    moved["cpu"] = "another kind"
    wheel = "out/gears.json:.parts.wheel."
    moved["figures"][wheel + "volume_mm3"] *= 1 + 2e-8
    moved["figures"][wheel + "triangles"] += round(0.001 * moved["figures"][wheel + "triangles"])
    moved["files"]["out/wheel.stl"] = {"sha256": "0" * 64, "bytes": 1}
    assert golden.differences(stored, moved) == []
    assert len(golden.differences(stored, {**moved, "cpu": stored["cpu"]})) == 3
    moved["figures"][wheel + "volume_mm3"] *= 1 + 1e-4
    assert any("volume_mm3" in line for line in golden.differences(stored, moved))
    del moved["files"]["out/wheel.stl"]
    assert any("out/wheel.stl" in line for line in golden.differences(stored, moved))
