"""Golden figures guard refactors: every preset and a few designs give the stored outputs."""

from __future__ import annotations

import pytest

from tests.helpers import golden


@pytest.mark.parametrize("name", sorted(golden.CASES))
def test_outputs_match_golden(name):
    stored = golden.load(name)
    assert stored["args"] == golden.CASES[name], "case changed: regenerate its golden record"
    diff = golden.differences(stored, golden.run_case(name))
    assert not diff, "\n".join(diff[:40])
