"""The band check on a real generated pair (SPEC §11): zero backlash jams at the FDM band's
tight corner; the loose corner of the default pair has more play than the pair as written."""

from __future__ import annotations

from dataclasses import replace

import pytest

from wheelstep_cli.config.profiles import load_printer_profile
from wheelstep_cli.config.resolve import gear_pair_spec
from wheelstep_cli.gears.meshing import MeshingSettings
from wheelstep_cli.parts.kinds import build_for_printer
from wheelstep_cli.parts.tolerance import NOMINAL, band_cases, band_record, check_case, sectioned_pair

FEW = replace(MeshingSettings(), samples=384)


@pytest.fixture(scope="module")
def zero_backlash():
    pair = build_for_printer("gear-pair", gear_pair_spec(None, backlash=0.0), None)
    sections = sectioned_pair(pair)
    return sections, check_case(sections, NOMINAL, FEW)


def test_zero_clearance_jams_at_the_fdm_tight_corner(zero_backlash):
    sections, nominal = zero_backlash
    band = load_printer_profile("fdm-0.4-pla").band
    tight = band_cases(band)[0]
    record = band_record(sections, band, "fdm-0.4-pla", nominal, FEW, cases=(tight,))
    assert record["cases"][0]["case"] == "tight"
    assert record["jams"] and record["cases"][0]["jams"]
    # where rigid teeth cannot go there is no backlash or TE to give: none, and the band's
    # least backlash is none (0), not a penetration estimate
    case = record["cases"][0]
    assert case["interfering_poses"] > 0 and case["max_penetration_mm"] > 0
    assert case["backlash_min_mm"] is None and case["backlash_max_mm"] is None
    assert record["least_backlash_mm"] == 0.0
