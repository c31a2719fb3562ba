"""The remedy of a gear pair too large for the bed: the same pair drawn smaller."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from wheelstep_cli.config.profiles import load_printer
from wheelstep_cli.parts.smaller import scaled_options
from wheelstep_cli.parts.gear_pair import GearPairSpec, build_gear_pair
from wheelstep_cli.parts.plate_layout import bed_scale


@settings(max_examples=60, derandomize=True, deadline=None)
@given(scale=st.floats(0.2, 1.0), way=st.sampled_from(["module", "center", "install", "none"]),
       opening=st.floats(0.0, 1.0), backlash=st.one_of(st.none(), st.floats(0.0, 0.5)))
def test_scaled_options_scale_every_length_given_by_one_factor_within_the_scale(scale, way, opening, backlash):
    """The sizing input is rounded down (0.001 mm of module, 0.1 mm of distance), so the
    factor is at most the scale and less by at most that step; the other lengths given follow
    by that factor (to 0.001 mm), so the opening and the play keep their share."""
    given_values = {"module": {"module": 2.5, "install_distance": 190.0 + opening},
                    "center": {"center_distance": 143.0, "install_distance": 143.0 + opening},
                    "install": {"install_distance": 144.0 + opening}, "none": {}}[way]
    design = GearPairSpec(**given_values, backlash=backlash)
    options, factor = scaled_options(design, scale)
    sizing = {"module": "module", "center": "center_distance"}.get(way, "install_distance")
    size = float(getattr(design, sizing) or 144.0)
    step = 0.001 if sizing == "module" else 0.1
    assert scale - step / size - 1e-12 <= factor <= scale + 1e-12
    assert options[sizing] == pytest.approx(size * factor, abs=1e-9)
    for name, value in given_values.items() | {("backlash", backlash)}:
        if name != sizing and value is not None:
            assert options[name] == pytest.approx(value * factor, abs=6e-4)
    assert set(options) == {sizing} | {name for name, value in given_values.items() if value is not None} | (
        {"backlash"} if backlash is not None else set())


def test_a_generated_pair_drawn_smaller_shrinks_by_the_factor():
    """What the remedy rests on: with the tooth count kept, a generated pair at a smaller
    distance has a footprint smaller by the distance's factor (the module follows the pitch),
    so the scale the bed allows brings the wheel onto it."""
    printer = load_printer("resin-0.05-standard")
    design = GearPairSpec(z=32)
    wheel = np.ptp(build_gear_pair(design).wheel.bounds[:, :2], axis=0)
    scale = bed_scale(wheel, printer)
    assert scale < 1.0          # the 32-tooth pair's wheel is too large for the resin bed
    options, factor = scaled_options(design, scale)
    smaller = np.ptp(build_gear_pair(design.model_copy(update=options)).wheel.bounds[:, :2], axis=0)
    assert smaller == pytest.approx(wheel * factor, rel=2e-3)
    assert bed_scale(smaller, printer) == 1.0


def test_a_smaller_pair_remedy_says_what_it_changes_besides_the_size():
    """The count (or play) a try at the smaller size needed is said after the size: the pair
    with other teeth is not the same pair drawn smaller."""
    from wheelstep_cli.parts.bed_remedy import _changed_besides

    scaled = {"install_distance": 62.0, "backlash": 0.2}     # a backlash given scales with the pair
    changed = lambda found: _changed_besides(found, scaled, "install_distance")  # noqa: E731
    assert changed({"install_distance": 61.9, "backlash": 0.2}) == ""
    assert changed({"install_distance": 62.0, "z": 40, "backlash": 0.2}) == " with 40 teeth"
    assert changed({"install_distance": 62.0, "z": 40, "backlash": 0.1}) == " with 40 teeth and a backlash of 0.1 mm"


def test_the_part_a_bed_refusal_names_is_the_one_its_scale_is_set_by():
    """The pinion fits the bed one way round, the wheel is far too large: the refusal names the
    wheel (whose size the remedy's percentage is reckoned from), not the first part off the bed."""
    from types import SimpleNamespace

    from wheelstep_cli.errors import DesignError
    from wheelstep_cli.parts.kinds import height_inputs
    from wheelstep_cli.parts.plate_layout import require_on_bed

    printer = load_printer("fdm-0.4-pla")
    part = lambda name, x, y: SimpleNamespace(name=name, bounds=np.array([[0, 0, 0], [x, y, 10.0]]))  # noqa: E731
    parts = [part("pinion", 120.0, 300.0), part("wheel", 400.0, 400.0)]
    with pytest.raises(DesignError) as err:
        require_on_bed(parts, printer, "thickness", 10.0, lowers=height_inputs("gear-pair", GearPairSpec()))
    assert "part 'wheel' (400.0 x 400.0 mm) does not fit" in err.value.limit
    assert err.value.bed_scale == pytest.approx(246.0 / 400.0)
