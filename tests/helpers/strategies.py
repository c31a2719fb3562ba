"""Hypothesis strategies shared by the test modules (one copy of each design space)."""

from __future__ import annotations

from hypothesis import strategies as st

from wheelstep_cli.gears.pitch import CrankLaw


@st.composite
def crank_laws(draw):
    """Valid crank laws over the whole reachable space: R_min > 0, n = 2 or 4 (mm)."""
    a = draw(st.floats(10, 200))
    c = draw(st.floats(50, 600))
    b = draw(st.floats(0, 0.95 * (a + c) / 4))
    L = draw(st.floats(40, 400))
    n = draw(st.sampled_from([2, 4]))
    return CrankLaw(a, b, c, L, n)
