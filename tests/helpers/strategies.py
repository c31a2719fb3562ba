"""Hypothesis strategies shared by the test modules (one copy of each design space)."""

from __future__ import annotations

from hypothesis import strategies as st

from wheelstep_cli.gears.laws import CrankLaw
from wheelstep_cli.mechanism.crank import CrankMechanism


@st.composite
def mechanisms(draw):
    """Valid crank mechanisms over the whole reachable space: R_min = a - 4b + c > 0 (mm)."""
    a = draw(st.floats(10, 200))
    c = draw(st.floats(50, 600))
    b = draw(st.floats(0, 0.95 * (a + c) / 4))
    return CrankMechanism(a, b, c)


@st.composite
def crank_laws(draw):
    """Crank laws of valid mechanisms, n = 2 or 4 pinion turns per carrier turn."""
    return CrankLaw(draw(mechanisms()), draw(st.sampled_from([2, 4])))


def center_distances():
    """Centre distances a user may choose, mm."""
    return st.floats(40, 400)


def r_min_designs(min_b: float = 0.0, min_r_min: float = 1.0):
    """Valid designs given as (a, b, R_min) in mm: a > 0, b >= min_b, R_min >= min_r_min and a
    strut c = R_min - a + 4b > 0 (a is a fraction 0.02..0.98 of R_min + 4b)."""
    return st.tuples(st.floats(min_b, 250.0), st.floats(min_r_min, 300.0), st.floats(0.02, 0.98)).map(
        lambda t: (t[2] * (t[1] + 4 * t[0]), t[0], t[1]))


@st.composite
def generated_gear_options(draw):
    """`wheelstep gears` options of generated pairs on the source mechanism: tooth counts from
    the smallest refused to well within bounds, pressure angle, backlash (None: the default)."""
    options = ["--z", str(draw(st.sampled_from([24, 32, 40, 48, 56, 64])))]
    options += ["--pressure-angle", f"{draw(st.floats(18.0, 25.0)):.1f}"]
    backlash = draw(st.one_of(st.none(), st.floats(0.1, 0.5)))
    if backlash is not None:
        options += ["--backlash", f"{backlash:.2f}"]
    return options
