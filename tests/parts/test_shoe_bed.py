"""The remedy of a shoe too large for the bed: the shoe of the same mechanism drawn smaller."""

from __future__ import annotations

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from wheelstep_cli.config.specs import ShoeSpec
from wheelstep_cli.parts.smaller import scaled_mechanism


@settings(max_examples=80, derandomize=True, deadline=None)
@given(scale=st.floats(0.2, 0.99), a=st.floats(30.0, 120.0), b_over_a=st.floats(1.2, 2.5),
       r_min=st.floats(5.0, 80.0), strut=st.sampled_from(["c", "r_min", "both", "neither"]))
def test_scaled_mechanism_rounds_each_length_down_and_keeps_the_strut_as_given(scale, a, b_over_a, r_min, strut):
    """a, b and the strut as given come out at most ``scale`` times their size, less by at
    most the 0.1 mm they are rounded down to; c and r_min given together still agree."""
    b = a * b_over_a
    c = r_min - a + 4 * b
    given_values = {"c": {"c": c}, "r_min": {"r_min": r_min}, "both": {"c": c, "r_min": r_min},
                    "neither": {}}[strut]
    spec = ShoeSpec(a=a, b=b, **given_values)
    options, factor = scaled_mechanism(spec, scale)
    expected = {"a", "b"} | ({"c"} if "c" in given_values else {"r_min"}) | set(given_values)
    assert set(options) == expected
    lengths = {"a": a, "b": b, "c": c, "r_min": spec.design().r_min}
    for name in ("a", "b", "c") if "c" in given_values else ("a", "b", "r_min"):
        assert lengths[name] * scale - 0.1 - 1e-9 <= options[name] <= lengths[name] * scale + 1e-9
        assert options[name] * 10 == pytest.approx(round(options[name] * 10), abs=1e-6)
    assert factor == pytest.approx(options["a"] / a)
    smaller = ShoeSpec(**{**spec.model_dump(), **options})
    smaller.design()        # c and r_min, both given, agree (a contradiction is refused)
