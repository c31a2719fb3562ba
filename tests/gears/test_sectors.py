"""Equal-arc sector partition (SPEC §4): reference table and properties."""

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from wheelstep_cli.errors import DesignError
from wheelstep_cli.gears.pitch_curves import wheel_radius
from wheelstep_cli.gears.sectors import sector_partition, sectors_per_quarter

from tests.helpers.strategies import center_distances, crank_laws

REF_ROWS = {  # i: phi_i, dphi_i, r_Hi, theta_i, dtheta_i, r_i (deg, mm) from SPEC §4
    1: (-45.00, 4.33, 82.20, -90.00, 5.81, 61.30),
    2: (-40.67, 4.12, 86.37, -84.19, 6.23, 57.13),
    12: (-3.50, 3.50, 101.59, -8.49, 8.49, 41.91),
}


def test_reference_rows_at_printed_precision(cli):
    import json

    result = cli("pitch", "--json")
    assert result.exit_code == 0, result.stderr
    data = json.loads(result.stdout)
    # the report says what it was computed for: the source design, at the distance its sectors roll at
    assert data["parameters"] == {"a": 60.0, "b": 100.0, "c": 360.0, "z": 48, "turns": 2, "center_distance": 143.5}
    assert round(data["arc_mm"], 4) == 6.2123
    assert round(data["u"], 5) == 1.25248
    assert len(data["sectors"]) == 24
    rows = {row["i"]: row for row in data["sectors"]}
    keys = ("phi_deg", "dphi_deg", "r_wheel_mm", "theta_deg", "dtheta_deg", "r_pinion_mm")
    for i, ref in REF_ROWS.items():
        assert tuple(round(rows[i][k], 2) for k in keys) == ref
    # rows 13..24 mirror rows 12..1
    for i in range(1, 13):
        assert rows[25 - i]["dphi_deg"] == pytest.approx(rows[i]["dphi_deg"])
        assert rows[25 - i]["r_pinion_mm"] == pytest.approx(rows[i]["r_pinion_mm"])


def test_table_output_lists_every_sector(cli):
    result = cli("pitch", "--z", "40")
    assert result.exit_code == 0
    assert len([l for l in result.stdout.splitlines() if l.strip()[:2].strip().isdigit()]) == 20


def test_the_paper_tables_speak_of_the_paper_method_not_of_generated_teeth(cli):
    """pitch and teeth take the paper's sectors: their help says so, and the common arc is
    said to be the circular sectors' (shorter than the exact curves `gears` spaces teeth on)."""
    for command in ("pitch", "teeth"):
        text = " ".join(cli(command, "--help").stdout.split())
        assert "generated" not in text and "L_p the paper's sectors roll at" in text, text
    assert "l is the arc of the paper's circular sectors" in cli("pitch").stdout


@settings(max_examples=40, deadline=None)
@given(crank_laws(), center_distances(), st.integers(4, 40))
def test_partition_properties(law, L, count):
    part = sector_partition(law, count, L)
    assert part.dphi.sum() == pytest.approx(np.pi / 2, abs=1e-9)
    assert part.dtheta.sum() == pytest.approx(law.turns * np.pi / 2, abs=1e-9)
    np.testing.assert_allclose(part.r_pinion + part.r_wheel, L)
    # equal arcs on both gears
    np.testing.assert_allclose(part.r_wheel * part.dphi, part.arc, rtol=1e-9)
    np.testing.assert_allclose(part.r_pinion * part.dtheta, part.arc, rtol=1e-9)
    # step 1: equal arcs on the exact curve at the sector middles
    mid = wheel_radius(law, part.phi + part.dphi / 2, L) * part.dphi
    np.testing.assert_allclose(mid, part.carrier_arc, rtol=1e-9)
    # mirror symmetry
    np.testing.assert_allclose(part.dphi, part.dphi[::-1], rtol=1e-7)
    np.testing.assert_allclose(part.dtheta, part.dtheta[::-1], rtol=1e-7)
    assert np.all(part.r_pinion > 0) and np.all(part.r_wheel > 0)


def test_tooth_count_must_split_into_sectors():
    assert sectors_per_quarter(48, 2) == 24
    assert sectors_per_quarter(24, 4) == 24
    with pytest.raises(DesignError):
        sectors_per_quarter(47, 2)
    with pytest.raises(DesignError):
        sectors_per_quarter(2, 2)
